"""The ``deltasph`` command: the command line of ``sph-cli`` (run, check, preview,
schema), word for word, and ``deltasph plot <run folder>``."""

from __future__ import annotations

import sys
from typing import Optional, Sequence

from . import _core


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Runs the command ``argv`` (default: the process's arguments); returns its exit code."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args[:1] == ["plot"]:
        from .plot import main as plot_main

        return plot_main(args[1:])
    return _core.cli(args)


def run() -> None:
    """Entry point of the ``deltasph`` console script."""
    sys.exit(main())

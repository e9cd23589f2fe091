"""The ``deltasph`` command: the command line of ``sph-cli`` (run, check, preview,
schema), word for word, and ``deltasph plot <run folder>``."""

import sys

from . import _core


def main(argv=None):
    """Runs the command ``argv`` (default: the process's arguments); returns its exit code."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args[:1] == ["plot"]:
        from .plot import main as plot_main

        return plot_main(args[1:])
    return _core.cli(args)


def run():
    """Entry point of the ``deltasph`` console script."""
    sys.exit(main())

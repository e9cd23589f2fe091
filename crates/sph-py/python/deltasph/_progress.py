"""Progress reporting for ``Simulation.run``: a callable, a tqdm bar, or nothing."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Union

#: What ``Simulation.run`` calls with the simulated time and the step count.
Report = Callable[[float, int], Any]


def reporter(progress: Union[None, bool, Report], start: float,
             until: float) -> Optional[Report]:
    """Turns the ``progress`` argument of ``run`` into a callable ``(time, n_steps)`` or None."""
    if progress is None or progress is False:
        return None
    if progress is True:
        return _Bar(start, until)
    if callable(progress):
        return progress
    raise TypeError(
        f"progress = {progress!r}: expected True, False, None or a callable(time, n_steps)"
    )


def close(report: Optional[Report]) -> None:
    """Finishes a reporter made by :func:`reporter` (only the built-in bar needs it)."""
    if isinstance(report, _Bar):
        report.close()


class _Bar:
    """A tqdm bar over simulated time when tqdm is installed, else a one-line counter."""

    def __init__(self, start: float, until: float) -> None:
        self.start = start
        self.span = max(until - start, 0.0)
        try:
            from tqdm.auto import tqdm  # type: ignore[import-untyped, unused-ignore]
        except ImportError:
            self.bar: Any = None
        else:
            self.bar = tqdm(total=self.span, unit="s", unit_scale=True, desc="deltasph")
        self.done = 0.0

    def __call__(self, time: float, n_steps: int) -> None:
        done = min(max(time - self.start, 0.0), self.span)
        if self.bar is not None:
            self.bar.update(done - self.done)
            self.bar.set_postfix(steps=n_steps, refresh=False)
        else:
            share = 100.0 * done / self.span if self.span > 0 else 100.0
            print(f"\rdeltasph: t = {time:.5f} s, {n_steps} steps, {share:5.1f}%",
                  end="", file=sys.stderr, flush=True)
        self.done = done

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        else:
            print(file=sys.stderr)

"""Reading a run folder back: its snapshots as numpy arrays, its time series, its case.

A run folder is what ``sph-cli run`` (or ``Simulation.run(out=...)``) writes::

    import deltasph as ds
    run = ds.load("dam_break_out")
    run.times                  # snapshot times [s]
    snap = run.snapshot(-1)    # the last snapshot; run.at(0.5) the one nearest 0.5 s
    snap["pressure"], snap["position"]      # (N,) and (N, D), rows in id order
    run.series["time"], run.series["probe0_pressure"]
"""

from __future__ import annotations

import math
import os
import pathlib
import sys
import xml.etree.ElementTree as ElementTree
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core

if sys.version_info >= (3, 11):
    import tomllib as _toml
else:  # Python 3.9 and 3.10
    import tomli as _toml

#: A file or folder name.
PathLike = Union[str, "os.PathLike[str]"]


class Snapshot(Dict[str, npt.NDArray[Any]]):
    """The fields of one snapshot by name (``position``, ``velocity`` (N, D),
    ``density``, ``pressure``, ``kind``, ``id`` (N,), and the optional ``free_surface``,
    ``normal``, ``lambda``, ``shifting_velocity``), rows sorted by particle id; with
    ``time`` [s], ``step`` and ``path``."""

    def __init__(self, path: PathLike, spacing: Optional[float] = None) -> None:
        time, step, fields = _core.read_snapshot(str(path))
        order = np.argsort(fields["id"], kind="stable")
        super().__init__((name, values[order]) for name, values in fields.items())
        self.time, self.step, self.path = time, step, pathlib.Path(path)
        #: The run's particle spacing Δx [m], when known (snapshots from a run folder).
        self.spacing = spacing

    def __repr__(self) -> str:
        return (f"Snapshot('{self.path.name}', t = {self.time:.6g} s, step {self.step}, "
                f"{len(self['id'])} particles, fields {sorted(self)})")


class RunFolder:
    """A run folder: ``times`` (to 10 significant digits; a snapshot's own ``time`` is
    exact) and ``files`` of its snapshots (from its XDMF index),
    ``snapshot(i)``, ``at(time)``, ``series`` (the time series as a dict of arrays),
    ``dataframe()`` (the same as a pandas DataFrame), ``case`` (its ``case.toml`` as a
    dict) and ``restart`` (the newest restart file, or None)."""

    def __init__(self, path: PathLike) -> None:
        self.path = pathlib.Path(path)
        index = self.path / "particles.xmf"
        if not index.is_file():
            raise FileNotFoundError(
                f"{self.path}: not a run folder (expected particles.xmf, the index that "
                f"sph-cli run and Simulation.run(out=...) write)")
        self.files, self.times = _index(index)
        self._series: Optional[Dict[str, npt.NDArray[np.float64]]] = None
        self._spacing: Optional[float] = None

    def __len__(self) -> int:
        return len(self.files)

    def __repr__(self) -> str:
        span = f"t = {self.times[0]:.6g}–{self.times[-1]:.6g} s" if len(self) else "empty"
        return f"RunFolder('{self.path}', {len(self)} snapshots, {span})"

    def snapshot(self, index: int) -> Snapshot:
        """The snapshot at position ``index`` of the index (negative from the end)."""
        if self._spacing is None and (self.path / "case.toml").is_file():
            self._spacing = self.case.get("particles", {}).get("spacing")
        return Snapshot(self.path / self.files[index], self._spacing)

    __getitem__ = snapshot

    def at(self, time: float) -> Snapshot:
        """The snapshot nearest to ``time`` [s]."""
        if not len(self):
            raise IndexError(f"{self.path}: the run folder holds no snapshot")
        if not math.isfinite(time):
            raise ValueError(f"time = {time}: expected a finite time in seconds")
        return self.snapshot(int(np.argmin(np.abs(self.times - time))))

    @property
    def series(self) -> Dict[str, npt.NDArray[np.float64]]:
        """``timeseries.csv`` as ``{column: array}``; NaN where a probe had no fluid."""
        if self._series is None:
            path = self.path / "timeseries.csv"
            with open(path, encoding="utf-8") as f:
                names = f.readline().strip().split(",")
            data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
            self._series = {name: data[:, k] for k, name in enumerate(names)}
        return self._series

    def dataframe(self) -> Any:
        """The time series as a pandas DataFrame (needs pandas)."""
        import pandas  # type: ignore[import-untyped, import-not-found, unused-ignore]

        return pandas.DataFrame(self.series)

    @property
    def case(self) -> Dict[str, Any]:
        """The case of the run (``case.toml``) as a dict."""
        with open(self.path / "case.toml", "rb") as f:
            return _toml.load(f)

    @property
    def restart(self) -> Optional[pathlib.Path]:
        """The newest restart file (for ``Simulation.from_restart``), or None."""
        path = self.path / "restart.h5"
        return path if path.is_file() else None


def _index(path: pathlib.Path) -> Tuple[List[str], npt.NDArray[np.float64]]:
    """Snapshot files and times listed by an XDMF index that deltasph wrote."""
    root = ElementTree.parse(path).getroot()
    files: List[str] = []
    times: List[float] = []
    for grid in root.iter("Grid"):
        time = grid.find("Time")
        if grid.get("GridType") == "Uniform" and time is not None:
            files.append(grid.get("Name", ""))
            times.append(float(time.get("Value", "nan")))
    return files, np.array(times)


def load(path: PathLike) -> RunFolder:
    """The run folder ``path`` (see :class:`RunFolder`)."""
    return RunFolder(path)

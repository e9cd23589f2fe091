"""Reading a run folder back: its snapshots as numpy arrays, its time series, its case.

A run folder is what ``sph-cli run`` (or ``Simulation.run(out=...)``) writes::

    import deltasph as ds
    run = ds.load("dam_break_out")
    run.times                  # snapshot times [s]
    snap = run.snapshot(-1)    # the last snapshot; run.at(0.5) the one nearest 0.5 s
    snap["pressure"], snap["position"]      # (N,) and (N, D), rows in id order
    run.series["time"], run.series["probe0_pressure"]
"""

import math
import pathlib
import xml.etree.ElementTree as ElementTree

import numpy as np

from . import _core

try:  # Python 3.11+
    import tomllib as _toml
except ModuleNotFoundError:  # Python 3.9 and 3.10
    import tomli as _toml


class Snapshot(dict):
    """The fields of one snapshot by name (``position``, ``velocity`` (N, D),
    ``density``, ``pressure``, ``kind``, ``id`` (N,), and the optional ``free_surface``,
    ``normal``, ``lambda``, ``shifting_velocity``), rows sorted by particle id; with
    ``time`` [s], ``step`` and ``path``."""

    def __init__(self, path, spacing=None):
        time, step, fields = _core.read_snapshot(str(path))
        order = np.argsort(fields["id"], kind="stable")
        super().__init__((name, values[order]) for name, values in fields.items())
        self.time, self.step, self.path = time, step, pathlib.Path(path)
        #: The run's particle spacing Δx [m], when known (snapshots from a run folder).
        self.spacing = spacing

    def __repr__(self):
        return (f"Snapshot('{self.path.name}', t = {self.time:.6g} s, step {self.step}, "
                f"{len(self['id'])} particles, fields {sorted(self)})")


class RunFolder:
    """A run folder: ``times`` (to 10 significant digits; a snapshot's own ``time`` is
    exact) and ``files`` of its snapshots (from its XDMF index),
    ``snapshot(i)``, ``at(time)``, ``series`` (the time series as a dict of arrays),
    ``dataframe()`` (the same as a pandas DataFrame), ``case`` (its ``case.toml`` as a
    dict) and ``restart`` (the newest restart file, or None)."""

    def __init__(self, path):
        self.path = pathlib.Path(path)
        index = self.path / "particles.xmf"
        if not index.is_file():
            raise FileNotFoundError(
                f"{self.path}: not a run folder (expected particles.xmf, the index that "
                f"sph-cli run and Simulation.run(out=...) write)")
        self.files, self.times = _index(index)
        self._series = None
        self._spacing = None

    def __len__(self):
        return len(self.files)

    def __repr__(self):
        span = f"t = {self.times[0]:.6g}–{self.times[-1]:.6g} s" if len(self) else "empty"
        return f"RunFolder('{self.path}', {len(self)} snapshots, {span})"

    def snapshot(self, index):
        """The snapshot at position ``index`` of the index (negative from the end)."""
        if self._spacing is None and (self.path / "case.toml").is_file():
            self._spacing = self.case.get("particles", {}).get("spacing")
        return Snapshot(self.path / self.files[index], self._spacing)

    __getitem__ = snapshot

    def at(self, time):
        """The snapshot nearest to ``time`` [s]."""
        if not len(self):
            raise IndexError(f"{self.path}: the run folder holds no snapshot")
        if not math.isfinite(time):
            raise ValueError(f"time = {time}: expected a finite time in seconds")
        return self.snapshot(int(np.argmin(np.abs(self.times - time))))

    @property
    def series(self):
        """``timeseries.csv`` as ``{column: array}``; NaN where a probe had no fluid."""
        if self._series is None:
            path = self.path / "timeseries.csv"
            with open(path, encoding="utf-8") as f:
                names = f.readline().strip().split(",")
            data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
            self._series = {name: data[:, k] for k, name in enumerate(names)}
        return self._series

    def dataframe(self):
        """The time series as a pandas DataFrame (needs pandas)."""
        import pandas

        return pandas.DataFrame(self.series)

    @property
    def case(self):
        """The case of the run (``case.toml``) as a dict."""
        with open(self.path / "case.toml", "rb") as f:
            return _toml.load(f)

    @property
    def restart(self):
        """The newest restart file (for ``Simulation.from_restart``), or None."""
        path = self.path / "restart.h5"
        return path if path.is_file() else None


def _index(path):
    """Snapshot files and times listed by an XDMF index that deltasph wrote."""
    root = ElementTree.parse(path).getroot()
    files, times = [], []
    for grid in root.iter("Grid"):
        time = grid.find("Time")
        if grid.get("GridType") == "Uniform" and time is not None:
            files.append(grid.get("Name"))
            times.append(float(time.get("Value")))
    return files, np.array(times)


def load(path):
    """The run folder ``path`` (see :class:`RunFolder`)."""
    return RunFolder(path)

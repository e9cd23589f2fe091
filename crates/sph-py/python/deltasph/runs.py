"""Reading a run folder back: its snapshots as numpy arrays, its time series, its case.

A run folder is what ``sph-cli run`` (or ``Simulation.run(out=...)``) writes::

    import deltasph as ds
    run = ds.load("dam_break_out")
    run.times                  # snapshot times [s]
    snap = run.snapshot(-1)    # the last snapshot; run.at(0.5) the one nearest 0.5 s
    snap["pressure"], snap["position"]      # (N,) and (N, D), rows in id order
    run.series["time"], run.series["probe0_pressure"]

and measured again at any points (the in-run probes' and gauges' rules)::

    m = ds.measure("dam_break_out", line=([3.2, 0.0], [3.2, 0.4], 9), elevation=[1.0, 3.0])
    m.times, m.pressure        # (S,) and (S, 9): a row per snapshot
"""

from __future__ import annotations

import math
import os
import pathlib
import sys
import xml.etree.ElementTree as ElementTree
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core

if sys.version_info >= (3, 11):
    import tomllib as _toml
else:  # Python 3.9 and 3.10
    import tomli as _toml

#: A file or folder name.
PathLike = Union[str, "os.PathLike[str]"]
#: Numbers as a nested sequence or an array.
ArrayLike = Union[Sequence[Any], npt.NDArray[Any]]


class Snapshot(Dict[str, npt.NDArray[Any]]):
    """The fields of one snapshot by name (``position``, ``velocity`` (N, D),
    ``density``, ``pressure``, ``mass``, ``kind``, ``id`` (N,), and the optional ``free_surface``,
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

    def to_pyvista(self) -> Any:
        """The particles as a ``pyvista.PolyData``: one vertex cell per particle (2D at
        z = 0), every other field as point data, ``time`` in its field data. Needs pyvista
        (``pip install deltasph[pyvista]``)::

            cloud = ds.load("dam_out")[-1].to_pyvista()
            cloud.plot(scalars="pressure")   # or cloud.threshold(..., scalars="kind")
        """
        import pyvista  # type: ignore[import-untyped, import-not-found, unused-ignore]

        x = self["position"]
        points = np.zeros((len(x), 3))
        points[:, : x.shape[1]] = x
        cloud = pyvista.PolyData(points)
        for name, values in self.items():
            if name != "position":
                cloud.point_data[name] = values
        cloud.field_data["time"] = [self.time]
        return cloud


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

    def measure(self, points: Optional[ArrayLike] = None, **options: Any) -> "Measurement":
        """:func:`measure` on this run folder."""
        return measure(self.path, points, **options)

    def surface(self, **options: Any) -> pathlib.Path:
        """:func:`surface` on this run folder."""
        return surface(self.path, **options)

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


class Measurement:
    """What :func:`measure` read from each snapshot of a run: ``times`` [s] and
    ``steps`` (S,), the ``points`` (P, D), elevation ``lines`` (G, D - 1) and
    ``sections`` (K, D, D: their corners) asked for, and an array per field:
    ``pressure`` and ``density`` (S, P), ``velocity`` (S, P, D), ``elevation`` (S, G),
    above ``diagnostics.still_level``, ``volume_flow`` and ``mass_flow`` (S, K). A point
    with no fluid within the kernel support (dry, or inside a wall) reads NaN; a dry
    line reads its bottom, as an in-run gauge does."""

    def __init__(self, times: npt.NDArray[np.float64], steps: npt.NDArray[np.uint64],
                 points: npt.NDArray[np.float64], lines: npt.NDArray[np.float64],
                 sections: npt.NDArray[np.float64],
                 series: Dict[str, npt.NDArray[np.float64]]) -> None:
        self.times, self.steps, self.points, self.lines = times, steps, points, lines
        self.sections, self.series = sections, series

    def __getattr__(self, name: str) -> npt.NDArray[np.float64]:
        series = self.__dict__.get("series", {})
        if name in series:
            return series[name]  # type: ignore[no-any-return]
        raise AttributeError(
            f"no {name!r} measured (measured: {', '.join(sorted(series)) or 'nothing'})")

    def __repr__(self) -> str:
        return (f"Measurement({len(self.times)} snapshots, {len(self.points)} points, "
                f"{len(self.lines)} lines, fields {sorted(self.series)})")


def measure(run: PathLike, points: Optional[ArrayLike] = None, *,
            line: Optional[Tuple[ArrayLike, ArrayLike, int]] = None,
            grid: Optional[Tuple[ArrayLike, ArrayLike, ArrayLike]] = None,
            elevation: Optional[ArrayLike] = None,
            sections: Optional[ArrayLike] = None,
            fields: Sequence[str] = ("pressure",),
            out: Optional[PathLike] = None, overwrite: bool = False) -> Measurement:
    """Reads ``fields`` (``"pressure"``, ``"velocity"``, ``"density"``) at points, the
    free-surface elevation on vertical lines and the flow through sections, from every
    snapshot of the run folder ``run``, as ``sph-cli measure`` does (see
    :class:`Measurement`).

    The points are ``points`` (P, D), then the ``n`` points of ``line = (a, b, n)`` from
    ``a`` to ``b`` (ends included), then the nodes of ``grid = (lo, hi, counts)`` (the
    first axis varying fastest). ``elevation`` lists the lines: x in 2D (a number each),
    (x, y) in 3D. ``sections`` lists the sections by their corners: a segment (2D, two
    corners; flow to the right of first-to-second counts positive) or a parallelogram
    (3D, three corners; normal (c1 - c0) × (c2 - c0)). ``out`` also writes the CSV there (an earlier one replaced only with
    ``overwrite``, and only if the measure tool wrote it)."""
    blocks: List[npt.NDArray[np.float64]] = []
    if points is not None:
        blocks.append(np.atleast_2d(np.asarray(points, dtype=float)))
    if line is not None:
        a, b, n = line
        if not (isinstance(n, (int, np.integer)) and n >= 2):
            raise ValueError(f"line = {line}: expected (a, b, n) with n >= 2 points")
        s = np.linspace(0.0, 1.0, int(n))[:, None]
        a_, b_ = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        blocks.append(a_ + s * (b_ - a_))
    if grid is not None:
        lo, hi, counts = (np.asarray(v) for v in grid)
        if not (counts.dtype.kind in "iu" and np.all(counts >= 1)):
            raise ValueError(f"grid = {grid}: expected (lo, hi, counts), counts >= 1")
        axes = [np.linspace(l, h, int(c)) for l, h, c in zip(lo, hi, counts)]
        nodes = np.meshgrid(*axes, indexing="ij")
        blocks.append(np.stack([n.ravel(order="F") for n in nodes], axis=1))
    dimension = max((b.shape[1] for b in blocks), default=0)
    lines = np.asarray([] if elevation is None else elevation, dtype=float)
    if lines.ndim <= 1:
        lines = lines.reshape(-1, 1)
    corners = np.asarray([] if sections is None else sections, dtype=float)
    all_points = np.concatenate(blocks) if blocks else np.zeros((0, dimension))
    if not (len(all_points) or len(lines) or len(corners)):
        raise ValueError("measure: no points; give points, line, grid, elevation or sections")
    wanted = list(fields) if len(all_points) else []
    times, steps, series = _core.measure(
        str(run), all_points.tolist(), wanted, lines.tolist(), corners.tolist(),
        None if out is None else (str(out), overwrite))
    return Measurement(times, steps, all_points, lines, corners, series)


def surface(run: PathLike, *, spacing: Optional[float] = None, level: float = 0.5,
            out: Optional[PathLike] = None, overwrite: bool = False) -> pathlib.Path:
    """Writes the fluid's free surface at every snapshot of the run folder ``run`` as a
    mesh, as ``sph-cli surface`` does, and returns the ParaView collection that lists
    them (``RUN/surface/surface.pvd`` unless ``out`` names another folder).

    The surface is the ``level`` (½: where the fluid's volume ends) of the fluid's kernel
    sum sampled on a grid of ``spacing`` (default: the particle spacing); 2D meshes are
    polylines, 3D meshes triangles, each point carrying ``wall_fraction`` (the walls'
    kernel sum: ½ where the mesh runs along a wetted wall, 0 on the free surface).
    Earlier meshes there are replaced only with ``overwrite``; a folder holding files the
    tool did not write is refused. ``pyvista.read(path)`` reads the collection (a
    ``MultiBlock`` per time) or one ``surface_NNNNNN.vtp``."""
    collection, _ = _core.surface(str(run), spacing, level,
                                  None if out is None else str(out), overwrite)
    return pathlib.Path(collection)

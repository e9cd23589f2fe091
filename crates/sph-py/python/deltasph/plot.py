"""Plots of runs (needs matplotlib): a snapshot coloured by a field, and the time series.

::

    import deltasph as ds
    from deltasph import plot
    run = ds.load("dam_break_out")
    fig = plot.snapshot(run.at(0.5), "pressure")      # or a live ds.Simulation
    figs = plot.series(run)                           # {"energy": Figure, "probes": ...}

``deltasph plot <run folder>`` writes the same as PNGs.
"""

from __future__ import annotations

import argparse
import pathlib
import re
import sys
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from .runs import PathLike, RunFolder

#: Arrays of floats.
Floats = npt.NDArray[np.float64]

#: Units of the snapshot fields, for colour bars.
UNITS = {
    "pressure": "Pa",
    "density": "kg/m³",
    "velocity": "m/s",
    "shifting_velocity": "m/s",
    "lambda": "–",
    "free_surface": "–",
    "position": "m",
}

#: Time-series panels: a title, a pattern of the columns it draws, and the axis label.
PANELS = [
    ("energy", r"^(kinetic|potential|internal|total|work_of_dissipation_and_walls)$",
     "energy [J]"),
    ("power", r"^(viscous|diffusive|wall)_power$", "power [W]"),
    ("probes", r"_pressure$|_point$|_filtered$", "pressure [Pa] (gaps: no fluid in reach)"),
    ("density", r"^max_density_variation$", "max |ρ/ρ0 − 1|"),
    ("surge front", r"^surge_front$", "front [m]"),
    ("loads", r"_(pressure|viscous)_f[xyz]$|_moment_[xyz]$|_c[xyz]$",
     "force [N], moment [N m], coefficient"),
    ("gauges", r"_elevation$", "elevation [m]"),
    ("sections", r"_volume_flow$", "volume flow [m³/s; m²/s in 2D]"),
]


#: Samples after a probe first finds fluid that the probe panel's axis range leaves out:
#: its first wet readings ring with the impact's acoustic wave while one or two
#: particles are in reach (−34 kPa against a 6 kPa head on the dam break's wall, settling
#: within about 8 samples), and would flatten the rest of the signal to a line.
RINGING = 8


def _mark_wetting(ax: Any, t: Floats, data: Mapping[str, Floats], lines: Dict[str, Any]) -> None:
    """Dotted lines where each probe finds fluid after a dry spell; the axis range left
    to the settled samples, the clipped ringing's extent written on the panel."""
    settled, clipped = [], []
    for c, line in lines.items():
        v = np.asarray(data[c], dtype=float)
        wet = np.isfinite(v)
        calm = wet.copy()
        for start in np.flatnonzero(wet[1:] & ~wet[:-1]) + 1:
            calm[start:start + RINGING] = False
            ax.axvline(t[start], color=line.get_color(), ls=":", lw=0.9)
        settled.append(v[calm])
        ringing = v[wet & ~calm]
        if ringing.size:
            clipped.append(f"{c} {ringing.min() / 1e3:.1f} to {ringing.max() / 1e3:.1f} kPa")
    values = np.concatenate(settled)
    if not clipped or not values.size:
        return
    lo, hi = values.min(), values.max()
    pad = 0.05 * (hi - lo) if hi > lo else 1.0
    ax.set_ylim(lo - pad, hi + pad)
    ax.set_xlim(t[0], t[-1])
    ax.text(0.01, 0.98, f"dotted: a probe gets wet; its first {RINGING} samples ring "
            "acoustically, off the axis:\n" + "\n".join(clipped),
            transform=ax.transAxes, va="top", fontsize=7)


def _wave_targets(case: Mapping[str, Any]) -> Optional[Tuple[float, float]]:
    """The crest and trough of the regular waves a case's wave maker makes (Stokes's
    second order: ±H/2 + A2), or None."""
    from ._core import regular_wave

    bodies = case.get("wall", []) + case.get("shape", []) + case.get("tank", [])
    for body in bodies:
        waves = body.get("prescribed", {}).get("waves")
        if not waves or "height" not in waves:
            continue
        gravity = float(np.linalg.norm(case.get("fluid", {}).get("gravity", [0.0, -9.81])))
        period = waves.get("period")
        if period is None:
            k = 2 * np.pi / waves["wavelength"]
            period = 2 * np.pi / np.sqrt(gravity * k * np.tanh(k * waves["depth"]))
        theory = regular_wave(waves["height"], period, waves["depth"], gravity)
        half, a2 = 0.5 * waves["height"], theory["bound_second_harmonic"]
        return float(half + a2), float(-half + a2)
    return None


def _pyplot() -> Any:
    try:
        import matplotlib

        if "matplotlib.pyplot" not in sys.modules:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError(
            "deltasph.plot needs matplotlib: pip install \"deltasph[plot]\" (or matplotlib)"
        ) from e
    return plt


def _state(source: Any) -> Tuple[Floats, Any, Mapping[str, Any], float, Optional[float]]:
    """Positions, kind, fields, time and spacing of a Snapshot or a Simulation."""
    if hasattr(source, "positions"):  # a live Simulation
        fields = {"pressure": source.pressure, "density": source.density,
                  "velocity": source.velocities}
        keep = source.kind != 255  # rows of removed particles
        fields = {k: v[keep] for k, v in fields.items()}
        return (source.positions[keep], source.kind[keep], fields, source.time,
                source.spacing)
    return (source["position"], source["kind"], source, source.time,
            getattr(source, "spacing", None))


def _values(fields: Mapping[str, Any], field: str) -> Floats:
    if field not in fields:
        raise KeyError(f"field = {field!r}: expected one of {sorted(fields)}")
    values: Floats = np.asarray(fields[field], dtype=float)
    return np.linalg.norm(values, axis=1) if values.ndim == 2 else values


def _marker_size(ax: Any, spacing: float, fig: Any) -> float:
    """Marker area (points²) of a disc Δx across, in the axes' data scale once the
    figure is laid out."""
    fig.canvas.draw()
    x0, x1 = ax.transData.transform([(0.0, 0.0), (spacing, 0.0)])[:, 0]
    points = abs(x1 - x0) * 72.0 / fig.dpi
    return float(max(points, 0.5)) ** 2


def snapshot(source: Any, field: str = "pressure", ax: Any = None,
             spacing: Optional[float] = None, cmap: str = "viridis", scale: float = 1.0,
             label: Optional[str] = None, vmin: Optional[float] = None,
             vmax: Optional[float] = None) -> Any:
    """Draws the fluid of ``source`` (a :class:`deltasph.runs.Snapshot` or a
    ``Simulation``) coloured by ``field`` (vectors by their magnitude) times ``scale``,
    walls grey, each particle a disc Δx across, with a colour bar in the field's unit
    (or ``label``) from ``vmin`` to ``vmax``. 3D runs are drawn projected onto the x
    and last axes. Returns the figure."""
    plt = _pyplot()
    x, kind, fields, time, own_spacing = _state(source)
    spacing = spacing or own_spacing
    if spacing is None:
        raise ValueError("spacing: expected the particle spacing Δx [m] (a Snapshot from "
                         "ds.load carries it; a lone snapshot file does not)")
    values = _values(fields, field) * scale
    axes = (0, x.shape[1] - 1)
    if ax is None:
        span = np.ptp(x[:, axes], axis=0) + spacing
        width = 8.0
        fig, ax = plt.subplots(figsize=(width, max(2.5, width * span[1] / span[0] * 0.9)),
                               constrained_layout=True)
    fig = ax.figure
    lo, hi = x[:, axes].min(axis=0) - spacing, x[:, axes].max(axis=0) + spacing
    ax.set_aspect("equal")
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    wall, fluid = kind == 1, kind == 0
    walls = ax.scatter(x[wall, axes[0]], x[wall, axes[1]], c="0.6", marker="s",
                       linewidths=0)
    dots = ax.scatter(x[fluid, axes[0]], x[fluid, axes[1]], c=values[fluid],
                      cmap=cmap, vmin=vmin, vmax=vmax, linewidths=0)
    ax.set_xlabel(f"{'xyz'[axes[0]]} [m]")
    ax.set_ylabel(f"{'xyz'[axes[1]]} [m]")
    ax.set_title(f"{field}, t = {time:.4g} s")
    unit = UNITS.get(field, "")
    name = f"|{field}|" if np.ndim(fields[field]) == 2 else field
    label = label or (f"{name} [{unit}]" if unit else name)
    fig.colorbar(dots, ax=ax, label=label, shrink=0.9)
    size = _marker_size(ax, spacing, fig)  # after the colour bar has taken its room
    walls.set_sizes([1.1 * size])  # squares overlapping slightly: no antialiasing seams
    dots.set_sizes([size])
    return fig


def series(run: RunFolder) -> Dict[str, Any]:
    """Figures of the time series of a run folder (``ds.load(...)``), one per panel
    that has columns: energy, power, probes, density, surge front, loads, gauges (with
    the target crest and trough of a regular wave maker). Returns ``{panel: Figure}``."""
    plt = _pyplot()
    data = run.series
    t = data["time"]
    figures = {}
    for title, pattern, ylabel in PANELS:
        columns = [c for c in data if c not in ("time", "step", "dt") and re.search(pattern, c)]
        if not columns:
            continue
        fig, ax = plt.subplots(figsize=(8, 4), constrained_layout=True)
        lines = {c: ax.plot(t, data[c], lw=1.0, label=c)[0] for c in columns}
        if title == "probes":
            _mark_wetting(ax, t, data, lines)
        targets = _wave_targets(run.case) if title == "gauges" else None
        for level, name in zip(targets or (), ("crest", "trough")):
            ax.axhline(level, color="k", ls="--", lw=0.8,
                       label=f"target {name} (Stokes II)")
        ax.set_xlabel("t [s]")
        ax.set_ylabel(ylabel)
        ax.set_title(f"{run.path.name}: {title}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, ncol=2 if len(columns) > 4 else 1)
        figures[title] = fig
    return figures


def write(run: RunFolder, out: Optional[PathLike] = None, fields: Sequence[str] = ("pressure",),
          count: int = 4) -> List[pathlib.Path]:
    """Writes PNGs of ``count`` snapshots (spread over the run, the last included) of
    each of ``fields``, and of the time series, into ``out`` (default:
    ``<run folder>/plots``, created). Returns the paths written."""
    plt = _pyplot()
    out = pathlib.Path(out) if out is not None else run.path / "plots"
    out.mkdir(parents=True, exist_ok=True)
    written = []
    picks = sorted(set(np.linspace(0, len(run) - 1, min(count, len(run))).round().astype(int)))
    for k in picks:
        snap = run.snapshot(int(k))
        for field in fields:
            fig = snapshot(snap, field)
            path = out / f"{snap.path.stem}_{field}.png"
            fig.savefig(path, dpi=120)
            plt.close(fig)
            written.append(path)
    for title, fig in series(run).items():
        path = out / f"series_{title.replace(' ', '_')}.png"
        fig.savefig(path, dpi=120)
        plt.close(fig)
        written.append(path)
    return written


def main(argv: Optional[Sequence[str]] = None) -> int:
    """``deltasph plot <run folder> [--field F ...] [--count N] [--out DIR]``."""
    from .runs import load

    parser = argparse.ArgumentParser(
        prog="deltasph plot",
        description="Write PNGs of a run folder's snapshots and time series.")
    parser.add_argument("folder", help="a run folder (sph-cli run or Simulation.run(out=...))")
    parser.add_argument("--field", action="append", help="snapshot field (default pressure; "
                        "repeat for more): pressure, density, velocity, ...")
    parser.add_argument("--count", type=int, default=4, help="snapshots drawn (default 4)")
    parser.add_argument("--out", help="where the PNGs go (default <folder>/plots)")
    args = parser.parse_args(argv)
    try:
        run = load(args.folder)
        paths = write(run, args.out, tuple(args.field or ["pressure"]), max(args.count, 1))
    except (OSError, KeyError, ValueError, ImportError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    for path in paths:
        print(f"wrote {path}")
    return 0

"""Type stubs of the native part of deltasph (all quantities SI)."""

from collections.abc import Callable, Mapping
from os import PathLike
from pathlib import Path
from typing import Any, Optional, Union, final

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = ["Simulation", "read_snapshot", "measure", "surface", "cli", "case_schema", "regular_wave", "__version__"]

_Progress = Union[bool, None, Callable[[float, int], object]]

@final
class Simulation:
    """A weakly-compressible δ-SPH simulation, 2D or 3D.

    Arrays are copies in particle-id order: row ``i`` is always the particle
    created ``i``-th, across steps and neighbour-list rebuilds.
    """

    def __new__(cls, config: Mapping[str, Any]) -> Simulation:
        """Builds a simulation from a dict mirroring the TOML case file, key for key.

        Raises ConfigError (ValueError) for a bad value, ConfigKeyError (KeyError)
        for an unknown or missing key, TypeError if ``config`` is not a dict.
        """
    @staticmethod
    def from_toml(path: Union[str, PathLike[str]]) -> Simulation:
        """Builds a simulation from a TOML case file (FileNotFoundError if absent)."""
    def to_toml(self) -> str:
        """The case as TOML text, every default filled in."""
    def run(
        self,
        until: Optional[float] = None,
        progress: _Progress = None,
        *,
        out: Union[str, PathLike[str], None] = None,
        output_interval: Optional[float] = None,
        force: bool = False,
        checkpoint_every: Optional[float] = None,
    ) -> None:
        """Advances to time ``until`` [s] (default ``time.end``), landing on it exactly.

        The interpreter is released; Ctrl-C raises KeyboardInterrupt between steps.
        ``progress``: True for a bar, or ``callable(time, n_steps)``.
        Raises InstabilityError on blow-up, keeping the state at that moment; a
        ``until`` before the current time raises ValueError.

        With ``out``: writes the command line's run folder there (snapshots every
        ``output_interval`` s, XDMF index, time series, case copy, restart files every
        ``checkpoint_every`` s of wall time and at the end); ``force`` replaces an
        earlier run's files. Later calls with the same ``out`` continue the folder.
        """
    @staticmethod
    def from_restart(
        path: Union[str, PathLike[str]], until: Optional[float] = None
    ) -> Simulation:
        """Continues a run from its restart file, bit for bit; ``run(out=<its folder>)``
        goes on writing that folder."""
    def step(self, n: Optional[int] = None) -> None:
        """Advances exactly ``n`` steps (default 1)."""
    @property
    def failed(self) -> Optional[str]:
        """The stability guard's message if it stopped this simulation (its state
        arrays then hold the blown-up state, kept for inspection), else None."""
    @property
    def removed_mass(self) -> float:
        """Mass [kg] of the fluid removed so far because it left the domain (per metre
        of depth in 2D)."""
    @property
    def time(self) -> float:
        """Simulated time [s]."""
    @property
    def dt(self) -> float:
        """The last time step [s] (0 before the first step)."""
    @property
    def n_steps(self) -> int:
        """Steps taken so far."""
    @property
    def dimension(self) -> int:
        """2 or 3."""
    @property
    def name(self) -> str: ...
    @property
    def n_particles(self) -> int:
        """Fluid and wall particles in the run."""
    @property
    def n_removed(self) -> int:
        """Fluid particles removed after leaving the domain (NaN rows, kind 255)."""
    @property
    def n_created(self) -> int:
        """Fluid particles created so far at inlets (each with a new id, a new row)."""
    @property
    def n_fluid(self) -> int: ...
    @property
    def sound_speed(self) -> float:
        """Numerical sound speed c0 [m/s]."""
    @property
    def reference_density(self) -> float:
        """ρ0 [kg/m³]."""
    @property
    def smoothing_length(self) -> float:
        """h [m]."""
    @property
    def spacing(self) -> float:
        """Initial particle spacing Δx [m]."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """Positions [m], shape (N, D)."""
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """Velocities [m/s], shape (N, D); wall rows: zero, or a sliding lid's velocity."""
    @property
    def density(self) -> npt.NDArray[np.float64]:
        """Density [kg/m³], shape (N,)."""
    @property
    def pressure(self) -> npt.NDArray[np.float64]:
        """Pressure [Pa], shape (N,): EOS for fluid, extrapolated for walls."""
    @property
    def mass(self) -> npt.NDArray[np.float64]:
        """Mass [kg] (per unit depth in 2D), shape (N,)."""
    @property
    def kind(self) -> npt.NDArray[np.uint8]:
        """0 fluid, 1 wall, shape (N,)."""
    def wall_crossings(self) -> int:
        """Fluid particles inside a wall now (zero in a sound run)."""
    def energies(self) -> dict[str, Optional[float]]:
        """``kinetic``, ``potential``, ``internal``, ``total`` (the fluid's), ``bodies``
        (the free bodies'), ``dissipated``, ``moving_work`` and ``forcing_work`` (the
        body force's and the absorbers') [J]: ``total + bodies + dissipated`` stays
        constant.

        ``dissipated``, ``moving_work`` and ``forcing_work`` are None unless
        ``diagnostics.energy_budget = true``.
        """
    def probe_pressure(self, points: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Shepard-interpolated pressure [Pa] at points (M, D) or one point (D,); NaN at
        a point with no fluid within the kernel support."""
    def probe_velocity(self, points: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Shepard-interpolated fluid velocity [m/s] at points (M, D) or one point (D,),
        (M, D); NaN rows where no fluid is within the kernel support."""
    def loads(self) -> dict[str, dict[str, npt.NDArray[np.float64]]]:
        """The fluid's load on each body (every tank and wall, by name, in case order):
        ``{name: {"pressure": (D,), "viscous": (D,), "moment": (3,)}}`` in N (per unit
        width in 2D) and N m about ``diagnostics.moment_point``."""
    def body_motions(self) -> dict[str, dict[str, npt.NDArray[np.float64]]]:
        """The moving bodies now, by name: ``position`` (D,), ``rotation`` (1,) or (3,),
        ``velocity`` (D,), ``angular_velocity`` (1,) or (3,); empty when all are fixed."""
    def prescribed_motion(
        self, times: npt.ArrayLike
    ) -> dict[str, dict[str, npt.NDArray[np.float64]]]:
        """Each prescribed body's (wave makers included) ``position`` (M, D),
        ``rotation`` (M, 1|3), ``velocity`` (M, D) and ``angular_velocity`` (M, 1|3) at
        ``times`` (an absorbing wave maker's correction: its current one, extrapolated)."""
    def wave_elevation(self, positions: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The free surface's elevation [m] above ``diagnostics.still_level`` on vertical
        lines at x values (2D) or (x, y) rows (3D), as gauges read it; (M,)."""
    def free_surface(self) -> dict[str, npt.NDArray[Any]]:
        """Free-surface detection: ``on_surface`` (N,), ``normal`` (N, D), ``lambda`` (N,)."""
    def set_velocities(self, velocities: npt.NDArray[np.float64]) -> None:
        """Sets the fluid velocities from a float64 array (N, D) in id order; wall rows
        must hold the walls' own velocities, as ``velocities`` returns them."""
    def set_density(self, density: npt.NDArray[np.float64]) -> None:
        """Sets densities from a positive float64 array (N,) in id order."""
    def write_snapshot(
        self, path: Union[str, PathLike[str]], overwrite: bool = False
    ) -> Path:
        """Writes HDF5 at ``path`` and an XDMF index beside it; returns the index path.

        Existing files are refused unless ``overwrite``; even then only files written
        by deltasph are replaced."""

def read_snapshot(path: Union[str, PathLike[str]]) -> tuple[float, int, dict[str, npt.NDArray[Any]]]:
    """``(time, step, fields)`` of a snapshot file, rows in the file's order."""

def measure(
    run: Union[str, PathLike[str]],
    points: list[list[float]],
    fields: list[str],
    elevations: list[list[float]],
    sections: list[list[list[float]]],
    out: Optional[tuple[Union[str, PathLike[str]], bool]] = None,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.uint64], dict[str, npt.NDArray[np.float64]]]:
    """``(times, steps, series)`` measured at ``points``, on the vertical lines
    ``elevations`` and through the ``sections`` (their corners) in every snapshot of the
    run folder ``run``; NaN where dry."""

def surface(
    run: Union[str, PathLike[str]],
    spacing: Optional[float] = None,
    level: float = 0.5,
    out: Optional[Union[str, PathLike[str]]] = None,
    overwrite: bool = False,
) -> tuple[str, list[str]]:
    """Writes the free surface of every snapshot of the run folder ``run`` as meshes
    (``sph-cli surface``): ``(collection, files)``."""

def cli(args: list[str]) -> int:
    """Runs the ``deltasph`` command line with ``args``; returns its exit code."""

def case_schema() -> str:
    """The JSON Schema of the case file (what ``sph-cli schema`` prints)."""

def regular_wave(
    height: float, period: float, depth: float, gravity: float = 9.81, hinge_height: float = 0.0
) -> dict[str, float]:
    """``wavenumber``, ``wavelength``, ``kd``, ``bound_second_harmonic`` (Stokes's A2),
    ``piston_stroke`` and ``flap_stroke`` (Biesel), ``madsen_second_order`` of regular
    waves (docs/theory.md §14)."""

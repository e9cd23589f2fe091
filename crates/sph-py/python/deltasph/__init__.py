"""deltasph: a weakly-compressible δ-SPH solver for free-surface flows.

Set up a case from a TOML file or a dict with the same keys, step it, and read
the particle state as numpy arrays::

    import deltasph as ds
    sim = ds.Simulation.from_toml("examples/dam_break_2d.toml")
    sim.run(until=0.3)
    x, p = sim.positions, sim.pressure

All quantities are SI. Arrays are copies in particle-id order (row i is always the
particle created i-th), so they can be compared across steps and edited freely.

``sim.run(out="folder")`` writes the command line's run folder, ``ds.load("folder")``
reads one back, ``ds.measure("folder", ...)`` reads fields at points from its snapshots,
``ds.surface("folder")`` writes its free-surface meshes, ``deltasph.plot`` draws it,
``ds.case_schema()`` is the case file's JSON Schema for editors.
"""

from ._core import Simulation, __version__, case_schema, regular_wave
from .errors import ConfigError, ConfigKeyError, InstabilityError
from .runs import Measurement, RunFolder, Snapshot, load, measure, surface

#: Values of ``Simulation.kind``.
FLUID = 0
WALL = 1

__all__ = [
    "Simulation",
    "FLUID",
    "WALL",
    "ConfigError",
    "ConfigKeyError",
    "InstabilityError",
    "Measurement",
    "RunFolder",
    "case_schema",
    "regular_wave",
    "Snapshot",
    "load",
    "measure",
    "surface",
    "__version__",
]

"""Shared helpers for the deltasph Python tests: example cases as dicts, with overrides."""

import copy
import pathlib
try:  # Python 3.11+
    import tomllib
except ModuleNotFoundError:  # 3.9 and 3.10: pip install tomli
    import tomli as tomllib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def example(name, **overrides):
    """The example case `name` as a dict; `overrides` maps "table.key" to a value."""
    with open(EXAMPLES / f"{name}.toml", "rb") as f:
        config = tomllib.load(f)
    config = copy.deepcopy(config)
    for dotted, value in overrides.items():
        *tables, key = dotted.split("__")
        target = config
        for t in tables:
            target = target.setdefault(t, {})
        target[key] = value
    return config


@pytest.fixture
def coarse_dam_break():
    """The 2D dam break at H/Δx = 20 (2000 fluid particles): seconds per hundred steps."""
    return example("dam_break_2d", particles__spacing=0.03)


@pytest.fixture
def ctrl_c():
    """Ctrl-C raising KeyboardInterrupt, as in an interactive Python, also where the
    tests were started with SIGINT ignored (a background job of a shell without job
    control); restored afterwards."""
    import signal

    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)

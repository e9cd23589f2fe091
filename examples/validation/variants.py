"""A study's runs: its case file with changes given on the command line
(`--set section.key=value`), run into a folder or read back from an earlier run."""
import argparse
import pathlib
import time
import tomllib

import deltasph as ds


def load_case(path, changes=()):
    """The case file at `path` with `changes` ("section.key=value", the value in TOML;
    a number in the path indexes an array of tables) applied."""
    with open(path, "rb") as f:
        cfg = tomllib.load(f)
    for change in changes:
        key_path, value = change.split("=", 1)
        *tables, key = key_path.strip().split(".")
        node = cfg
        for t in tables:
            node = node[int(t)] if isinstance(node, list) else node.setdefault(t, {})
        node[key] = tomllib.loads(f"v = {value.strip()}")["v"]
    return cfg


def run(cfg, folder, reuse):
    """Runs the case `cfg` into `folder` (with `reuse`, reads the series an earlier run
    left there, its wall time from the folder's file times); returns the series as a
    dict of columns, the wall time and the number of particles."""
    if not reuse:
        sim = ds.Simulation(cfg)
        start = time.perf_counter()
        sim.run(out=folder, force=True)
        wall = time.perf_counter() - start
    else:
        wall = (folder / "timeseries.csv").stat().st_mtime - (folder / "case.toml").stat().st_mtime
    done = ds.load(folder)
    return done.series, wall, len(done.snapshot(0)["id"])


def study_arguments(description, name, quick_help):
    """A study's command line: --quick (`quick_help`), --scratch (default ./`name`_runs),
    --set (changes to the case: the study prints its analysis and writes no record) and
    --reuse; parsed."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--quick", action="store_true", help=quick_help)
    parser.add_argument("--scratch", type=pathlib.Path, default=pathlib.Path(f"{name}_runs"),
                        help=f"where the runs' folders go (default ./{name}_runs)")
    parser.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                        help="change the case (repeatable; e.g. scheme.alpha=0): prints the "
                             "analysis and writes no record")
    parser.add_argument("--reuse", action="store_true",
                        help="analyse the runs already in --scratch instead of running them")
    return parser.parse_args()

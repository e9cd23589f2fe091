"""Cost of driving the solver from Python.

1. The 2D dam break at about 40k fluid particles: the same N steps run by
   `sph-cli run` and by `sim.step(1)` in a Python loop (and by `sim.run()`), each
   timed on the stepping loop alone, best of `--repeat` runs.
2. State arrays of a 1M-particle case: time to return positions, velocities,
   density, pressure and kind (copies in id order), median of 5 calls.

    python3 scripts/python_overhead.py [--steps 60] [--repeat 2]
"""

import argparse
import pathlib
import re
import statistics
import subprocess
import tempfile
import time

import deltasph as ds

ROOT = pathlib.Path(__file__).resolve().parents[1]


def case_text(steps):
    text = (ROOT / "examples" / "dam_break_2d.toml").read_text()
    text = text.replace("spacing = 0.012", "spacing = 0.004255")  # H/Δx = 141
    text = re.sub(r"^\[time\]$", f"[time]\nmax_steps = {steps}", text, flags=re.M)
    text = text.replace("output_interval = 0.05", "output_interval = 0.0")
    return text.replace("interval = 0.002", "interval = 10.0")


def cli_seconds(binary, case, scratch):
    out = scratch / f"cli-{time.monotonic_ns()}"
    done = subprocess.run([binary, "run", case, "--out", out, "-q"], check=True,
                          capture_output=True, text=True)
    return float(re.search(r"wall time\s+([0-9.]+) s", done.stdout).group(1))


def python_loop_seconds(case, steps):
    sim = ds.Simulation.from_toml(case)
    start = time.perf_counter()
    for _ in range(steps):
        sim.step(1)
    return time.perf_counter() - start, sim.n_fluid


def python_run_seconds(case):
    sim = ds.Simulation.from_toml(case)
    start = time.perf_counter()
    sim.run()
    return time.perf_counter() - start


def array_times():
    config = {
        "name": "million",
        "dimension": 2,
        "particles": {"spacing": 0.001},
        "fluid": {"density": 1000.0, "sound_speed": 10.0},
        "fluid_block": [{"lo": [0.0, 0.0], "hi": [1.0, 1.0], "hydrostatic": False}],
        "time": {"end": 1.0},
    }
    sim = ds.Simulation(config)
    rows = []
    for name in ("positions", "velocities", "density", "pressure", "kind"):
        times = []
        for _ in range(5):
            start = time.perf_counter()
            getattr(sim, name)
            times.append(time.perf_counter() - start)
        rows.append((name, statistics.median(times)))
    return sim.n_particles, rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=60)
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "sph-cli"], cwd=ROOT,
                   check=True)
    binary = ROOT / "target" / "release" / "sph-cli"
    with tempfile.TemporaryDirectory() as scratch:
        scratch = pathlib.Path(scratch)
        case = scratch / "case.toml"
        case.write_text(case_text(args.steps))
        cli, loop, run = [], [], []
        for _ in range(args.repeat):
            cli.append(cli_seconds(binary, case, scratch))
            seconds, n_fluid = python_loop_seconds(case, args.steps)
            loop.append(seconds)
            run.append(python_run_seconds(case))
    base = min(cli)
    print(f"dam break, {n_fluid} fluid particles, {args.steps} RK4 steps (best of {args.repeat})")
    print("| driver | wall time [s] | particle-steps/s | vs CLI |")
    print("|---|---|---|---|")
    for label, seconds in [("sph-cli run", base), ("Python sim.step(1) loop", min(loop)),
                           ("Python sim.run()", min(run))]:
        rate = n_fluid * args.steps / seconds
        print(f"| {label} | {seconds:.3f} | {rate:.3e} | {100 * (seconds / base - 1):+.1f}% |")
    n, rows = array_times()
    print(f"\nstate arrays of {n} particles (median of 5 calls)")
    print("| array | ms |")
    print("|---|---|")
    for name, seconds in rows:
        print(f"| {name} | {1e3 * seconds:.1f} |")


if __name__ == "__main__":
    main()

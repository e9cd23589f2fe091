#!/usr/bin/env python3
"""Throughput of sph-cli: every speed figure of the README comes from this script.

Parts (run one with its name, or all by default):
  evals     particle-evaluations/s of the 2D dam break (δ-SPH, RK4, output off) at about
            5k, 20k and 40k fluid particles with 1 and 2 threads, and at 20k with
            h/Δx = 2; with --baseline BIN the same runs of another build, alternated.
  variants  the cost of a step of each scheme at 20k particles, 2 threads, relative to
            δ-SPH: plain WCSPH, δ-SPH with the energy budget, δ+-SPH, δ+-SPH with tensile
            control; at h/Δx = 1.33 and 2 (the default).
  interleaved
            the same step costs as `variants`, measured in one process (the deltasph
            Python module): the schemes' simulations advance in turns, 10 steps each, so
            that the machine's slow spells fall on all of them alike.
  open      particle-steps/s of the cylinder in a stream (examples/validation/
            cylinder.toml, D/Δx = 20, δ+-SPH, 2 threads) fed by its inlet and outlet,
            against the same particles in a domain periodic both ways driven by a body
            force (no open boundaries), interleaved as above.
  les       particle-evaluations/s of the Taylor-Green vortex (examples/
            les_taylor_green.toml at L/Δx = 100, 10k particles, 2 threads, output off)
            with δ-SPH, δ+-SPH and δ-LES-SPH, the same physical viscosity and c0, runs
            alternated.
  solution  wall time of examples/dam_break_2d.toml as it stands (output on), and of
            the same case with the symplectic scheme at CFL 0.25 (its default); with --baseline BIN
            the baseline's time too, alternated.
  scaling   particle-steps/s, bytes per particle (peak resident memory over all
            particles) and peak memory from 10³ to 10⁶ fluid particles, 2D and 3D
            dam breaks, 2 threads.

Each figure is the median of --repeat runs (default 3; scaling runs once).
Usage: python3 scripts/throughput.py [part ...] [--repeat N] [--baseline BIN]
Build first: cargo build --release.
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CLI = ROOT / "target" / "release" / "sph-cli"
EXAMPLE = ROOT / "examples" / "dam_break_2d.toml"
BASE_2D = EXAMPLE.read_text()
BASE_3D = (ROOT / "examples" / "dam_break_3d.toml").read_text()
H, G = 0.6, 9.81


def set_key(text, key, value, table):
    """Sets `key = value` in the case text, adding it under `[table]` when absent."""
    if re.search(rf"^{key} = .*$", text, flags=re.M):
        return re.sub(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.M)
    return text.replace(f"[{table}]", f"[{table}]\n{key} = {value}", 1)


def quiet(text):
    """The case without output: no snapshots, probes or energy budget."""
    text = set_key(text, "output_interval", "0.0", "time")
    text = re.sub(r"^probes = .*$", "", text, flags=re.M)
    return set_key(text, "energy", "false", "diagnostics")


def case_2d(n_fluid, max_steps=None, **scheme):
    """The 2D dam break (2H × H column) at about `n_fluid` fluid particles, output off."""
    dx = math.sqrt(2 * H * H / n_fluid)
    text = quiet(set_key(BASE_2D, "spacing", f"{dx:.6g}", "particles"))
    if max_steps is not None:
        text = set_key(text, "max_steps", str(max_steps), "time")
    for key, value in scheme.items():
        table = "particles" if key == "h_over_dx" else "scheme"
        text = set_key(text, key, value, table)
        if key == "h_over_dx":
            # wall layers covering the support 2h
            text = set_key(text, "layers", str(math.ceil(2 * float(value) - 1e-9)), "tank")
    return text


def case_3d(n_fluid, max_steps):
    """The 3D dam break (0.6 × 0.3 × 0.3 m column) at about `n_fluid` fluid particles."""
    dx = (0.6 * 0.3 * 0.3 / n_fluid) ** (1 / 3)
    text = quiet(set_key(BASE_3D, "spacing", f"{dx:.6g}", "particles"))
    return set_key(text, "max_steps", str(max_steps), "time")


def run(text, threads=2, cli=CLI):
    """Runs a case; the summary's figures and the peak resident memory [bytes]."""
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "case.toml"
        case.write_text(text)
        env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
        with open(Path(tmp) / "stdout", "w") as out:
            proc = subprocess.Popen([str(cli), "run", str(case), "--out", str(Path(tmp) / "out"),
                                     "--quiet"], env=env, stdout=out, stderr=subprocess.STDOUT)
            _, status, usage = os.wait4(proc.pid, 0)
        text_out = (Path(tmp) / "stdout").read_text()
        if status != 0:
            raise SystemExit(f"{cli} failed:\n{text_out}")
    grab = lambda pattern: float(re.search(pattern, text_out).group(1))
    return {
        "fluid": int(grab(r"particles\s+(\d+) fluid")),
        "walls": int(grab(r"fluid, (\d+) wall")),
        "steps": int(grab(r"in (\d+) steps")),
        "wall": grab(r"wall time\s+([\d.]+)"),
        "psteps": grab(r"throughput\s+([\d.e+]+) particle-steps"),
        "pevals": grab(r"([\d.e+]+) particle-evaluations"),
        "peak": usage.ru_maxrss * 1024,
    }


def median_runs(texts, repeat, threads=2):
    """Runs every (label, text, cli) `repeat` times, alternating; the median wall times
    and the last run of each."""
    walls = {label: [] for label, _, _ in texts}
    last = {}
    for _ in range(repeat):
        for label, text, cli in texts:
            r = run(text, threads, cli)
            walls[label].append(r["wall"])
            last[label] = r
    return {label: (statistics.median(w), last[label]) for label, w in walls.items()}


def evals(args):
    print("particle-evaluations/s, 2D dam break, δ-SPH, RK4, Wendland C2, output off")
    clis = [("now", CLI)] + ([("baseline", Path(args.baseline))] if args.baseline else [])
    print(f"{'fluid':>7} {'h/dx':>5} {'threads':>7} " + " ".join(f"{c:>12}" for c, _ in clis)
          + ("  ratio" if args.baseline else ""))
    for n, h_dx, threads in ((5_000, 1.33, 1), (5_000, 1.33, 2), (20_000, 1.33, 1),
                             (20_000, 1.33, 2), (40_000, 1.33, 2), (20_000, 2.0, 2)):
        text = case_2d(n, max_steps=args.steps, h_over_dx=h_dx)
        res = median_runs([(c, text, cli) for c, cli in clis], args.repeat, threads)
        rate = {c: r["steps"] * 4 * r["fluid"] / wall for c, (wall, r) in res.items()}
        line = f"{res['now'][1]['fluid']:>7} {h_dx:>5} {threads:>7} " + " ".join(
            f"{rate[c]:>12.3e}" for c, _ in clis)
        if args.baseline:
            line += f"  {rate['now'] / rate['baseline']:.2f}"
        print(line)


def variants(args):
    for h_dx in (1.33, 2.0):
        print(f"cost of a step relative to δ-SPH (RK4), about 20k fluid particles, 2 threads, "
              f"h/Δx = {h_dx}")
        variants_at(args, h_dx)


def variants_at(args, h_dx):
    cases = variant_cases(h_dx, args.steps)
    res = median_runs([(label, text, CLI) for label, text in cases], args.repeat)
    ref = res["δ-SPH"][0] / res["δ-SPH"][1]["steps"]
    for label, (wall, r) in res.items():
        per_step = wall / r["steps"]
        print(f"  {label:<26} {1e3 * per_step:7.2f} ms/step  ×{per_step / ref:.2f}")


def variant_cases(h_dx, steps):
    """The variants of `variants`, as (label, case text)."""
    n = 20_000

    def case(**scheme):
        return case_2d(n, steps, h_over_dx=h_dx, **scheme)

    return [
        ("δ-SPH", case()),
        ("plain WCSPH", case(diffusion='"none"')),
        ("δ-SPH + energy budget", set_key(case(), "energy_budget", "true", "diagnostics")),
        ("δ+-SPH", case(shifting='"delta_plus"')),
        ("δ+-SPH + tensile control", case(shifting='"delta_plus"', tensile_control="true")),
    ]


def interleaved(args):
    import time
    import deltasph as ds

    os.environ.setdefault("RAYON_NUM_THREADS", "2")
    block = 10
    for h_dx in (1.33, 2.0):
        print(f"cost of a step relative to δ-SPH (RK4), about 20k fluid particles, "
              f"{os.environ['RAYON_NUM_THREADS']} threads, h/Δx = {h_dx}, interleaved")
        sims = []
        for label, text in variant_cases(h_dx, None):
            with tempfile.TemporaryDirectory() as tmp:
                case = Path(tmp) / "case.toml"
                case.write_text(text)
                sims.append((label, ds.Simulation.from_toml(case)))
        spent = {label: 0.0 for label, _ in sims}
        for _ in range(args.steps // block):
            for label, sim in sims:
                start = time.perf_counter()
                sim.step(block)
                spent[label] += time.perf_counter() - start
        ref = spent["δ-SPH"]
        for label, _ in sims:
            per_step = spent[label] / (args.steps // block * block)
            print(f"  {label:<26} {1e3 * per_step:7.2f} ms/step  ×{spent[label] / ref:.2f}")


def open_boundaries(args):
    import time
    import tomllib
    import deltasph as ds

    os.environ.setdefault("RAYON_NUM_THREADS", "2")
    with open(ROOT / "examples" / "validation" / "cylinder.toml", "rb") as f:
        streamed = tomllib.load(f)
    streamed["time"]["output_interval"] = 0.0
    periodic = {**streamed, "domain": {**streamed["domain"], "periodic": [True, True]},
                "fluid": {**streamed["fluid"], "gravity": [0.01, 0.0]}}
    del periodic["open_boundary"]
    sims = [(label, ds.Simulation(cfg)) for label, cfg in
            (("inlet and outlet", streamed), ("periodic, body force", periodic))]
    block, spent, done = 10, {label: 0.0 for label, _ in sims}, {label: 0.0 for label, _ in sims}
    for _ in range(args.steps // block):
        for label, sim in sims:
            start = time.perf_counter()
            sim.step(block)
            spent[label] += time.perf_counter() - start
            done[label] += block * sim.n_particles
    print(f"cylinder at D/Δx = 20, δ+-SPH, {os.environ['RAYON_NUM_THREADS']} threads, "
          f"{args.steps} steps each, interleaved")
    for label, sim in sims:
        print(f"  {label:<22} {sim.n_particles} particles  "
              f"{done[label] / spent[label]:.4g} particle-steps/s")


def les(args):
    text = quiet((ROOT / "examples" / "les_taylor_green.toml").read_text())
    text = set_key(text, "spacing", "0.01", "particles")
    text = set_key(text, "max_steps", str(args.steps), "time")
    plain = re_scheme(text, 'diffusion = "delta_sph"')
    cases = [
        ("δ-SPH", plain),
        ("δ+-SPH", set_key(plain, "shifting", '"delta_plus"', "scheme")),
        ("δ-LES-SPH", text),
    ]
    res = median_runs([(label, t, CLI) for label, t in cases], args.repeat)
    print("particle-evaluations/s, Taylor-Green L/Δx = 100 (10k particles), RK4, 2 threads")
    ref = res["δ-SPH"][1]["pevals"]
    for label, (wall, r) in res.items():
        print(f"  {label:<10} {r['pevals']:10.3e}  cost of a step ×{ref / r['pevals']:.2f}")


def re_scheme(text, line):
    """The LES case turned into a δ-SPH case: no closure, `line` in its place."""
    text = re.sub(r"^turbulence = .*$", line, text, flags=re.M)
    return re.sub(r"^les_velocity = .*$", "", text, flags=re.M)


def solution(args):
    print(f"wall time of {EXAMPLE.relative_to(ROOT)} to t·sqrt(g/H) = 7 (output on), 2 threads")
    base = set_key(BASE_2D, "end", "1.73", "time")
    symplectic = set_key(set_key(base, "integrator", '"symplectic"', "scheme"),
                         "cfl", "0.25", "scheme")
    texts = [("now, RK4", base, CLI), ("now, symplectic CFL 0.25", symplectic, CLI)]
    if args.baseline:
        texts.append(("baseline, RK4", base, Path(args.baseline)))
    res = median_runs(texts, args.repeat)
    for label, (wall, r) in res.items():
        print(f"  {label:<26} {wall:7.2f} s, {r['steps']} steps")
    rk4 = res["now, RK4"][0]
    print(f"  symplectic / RK4: {res['now, symplectic CFL 0.25'][0] / rk4:.2f}")
    if args.baseline:
        print(f"  now / baseline: {rk4 / res['baseline, RK4'][0]:.3f}")


def scaling(args):
    print("particle-steps/s (fluid particles × steps / stepping wall time), 2 threads")
    print(f"{'dim':>3} {'fluid':>9} {'walls':>9} {'steps':>6} {'p-steps/s':>10} "
          f"{'bytes/particle':>15} {'peak MiB':>9}")
    for dim, case in ((2, case_2d), (3, case_3d)):
        for n, steps in ((1e3, 400), (1e4, 100), (1e5, 20), (1e6, 4)):
            r = run(case(int(n), max_steps=steps))
            total = r["fluid"] + r["walls"]
            print(f"{dim:>3} {r['fluid']:>9} {r['walls']:>9} {r['steps']:>6} "
                  f"{r['psteps']:>10.3e} {r['peak'] / total:>15.0f} {r['peak'] / 2**20:>9.0f}")


def main():
    parts = {"evals": evals, "variants": variants, "interleaved": interleaved,
             "open": open_boundaries, "les": les, "solution": solution, "scaling": scaling}
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("parts", nargs="*", help=" ".join(parts))
    ap.add_argument("--steps", type=int, default=200, help="steps of the fixed-step runs")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--baseline", help="another sph-cli build to compare with")
    args = ap.parse_args()
    unknown = [name for name in args.parts if name not in parts]
    if unknown:
        ap.error(f"unknown part {unknown[0]!r}: expected one of {', '.join(parts)}")
    for name in args.parts or parts:
        parts[name](args)
        print()


if __name__ == "__main__":
    main()

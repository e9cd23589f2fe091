#!/usr/bin/env python3
"""End-to-end throughput of sph-cli on the 2D dam break (delta-SPH, Wendland C2, h/dx = 1.33).

Part 1: three resolutions (about 5k, 20k and 40k fluid particles), a fixed number of
steps, with 1 and 2 threads: particles, neighbours per particle, steps, force
evaluations, particle-steps/s and particle-evaluations/s.
Part 2: wall time to reach t*sqrt(g/H) = 2 at about 20k particles with RK4 (CFL 1.5)
and with the symplectic scheme (CFL 0.15, its largest stable value for the dam break).

Usage: python3 scripts/throughput.py [--steps N]   (build first: cargo build --release)
"""
import argparse
import math
import os
import re
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CLI = ROOT / "target" / "release" / "sph-cli"
BASE = (ROOT / "examples" / "dam_break_2d.toml").read_text()
H, G = 0.6, 9.81


def case_text(n_fluid, end=None, max_steps=None, integrator=None, cfl=None):
    dx = math.sqrt(2 * H * H / n_fluid)
    text = re.sub(r"^spacing = .*$", f"spacing = {dx:.6f}", BASE, flags=re.M)
    text = re.sub(r"^output_interval = .*$", "output_interval = 0.0", text, flags=re.M)
    text = re.sub(r"^probes = .*$", "", text, flags=re.M)
    text = re.sub(r"^energy = true$", "energy = false", text, flags=re.M)
    if end is not None:
        text = re.sub(r"^end = .*$", f"end = {end}", text, flags=re.M)
    if max_steps is not None:
        text = text.replace("[time]", f"[time]\nmax_steps = {max_steps}")
    if integrator is not None:
        text = re.sub(r'^integrator = .*$', f'integrator = "{integrator}"', text, flags=re.M)
    if cfl is not None:
        text = re.sub(r"^cfl = .*$", f"cfl = {cfl}", text, flags=re.M)
    return text


def run(text, threads):
    with tempfile.TemporaryDirectory() as tmp:
        case = Path(tmp) / "case.toml"
        case.write_text(text)
        env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
        out = subprocess.run([str(CLI), "run", str(case), "--out", str(Path(tmp) / "out"), "--quiet"],
                             env=env, capture_output=True, text=True, check=True).stdout
    grab = lambda pattern: float(re.search(pattern, out).group(1))
    return {
        "fluid": int(grab(r"particles\s+(\d+) fluid")),
        "neighbours": grab(r"neighbours\s+([\d.]+)"),
        "steps": int(grab(r"in (\d+) steps")),
        "wall": grab(r"wall time\s+([\d.]+)"),
        "psteps": grab(r"throughput\s+([\d.e+]+) particle-steps"),
        "pevals": grab(r"([\d.e+]+) particle-evaluations"),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=200)
    args = ap.parse_args()
    print(f"{'fluid':>7} {'neigh':>6} {'threads':>7} {'steps':>6} {'evals':>6} {'wall s':>7} "
          f"{'p-steps/s':>10} {'p-evals/s':>10}")
    for n in (5_000, 20_000, 40_000):
        for threads in (1, 2):
            r = run(case_text(n, max_steps=args.steps), threads)
            print(f"{r['fluid']:>7} {r['neighbours']:>6.1f} {threads:>7} {r['steps']:>6} {4 * r['steps']:>6} "
                  f"{r['wall']:>7.2f} {r['psteps']:>10.3e} {r['pevals']:>10.3e}")
    t_end = 2.0 / math.sqrt(G / H)
    print(f"\nwall time to t*sqrt(g/H) = 2 (t = {t_end:.4f} s), about 20k particles, 2 threads:")
    for integrator, cfl in (("rk4", 1.5), ("symplectic", 0.15)):
        r = run(case_text(20_000, end=t_end, integrator=integrator, cfl=cfl), 2)
        print(f"  {integrator:<10} CFL {cfl}: {r['steps']} steps, {r['wall']:.2f} s, "
              f"{r['pevals']:.3e} particle-evaluations/s")


if __name__ == "__main__":
    main()

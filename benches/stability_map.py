"""Stability map: where each scheme variant holds and where it breaks.

Sweeps, for the 2D dam break (H/Δx = 12, to t·sqrt(g/H) = 7) and the hydrostatic tank
(H/Δx = 10, to t·sqrt(g/H) = 20):

- map "alpha": density diffusion (none, Molteni-Colagrossi, Ferrari, δ-SPH with δ = 0.1)
  × artificial viscosity α (0 to 0.1) × Courant number × integrator
  (RK4 with frozen diffusion, symplectic);
- map "delta": δ (0 to 0.2) of Molteni-Colagrossi, Ferrari and δ-SPH × Courant number ×
  integrator, without viscosity (α = 0): the smallest δ that keeps the flow noise-free.

The Courant grids differ by integrator (RK4 0.5 to 3, symplectic 0.15 to 0.5): each
spans its scheme's edge. Each run records whether it completed or blew up (and when, in
t·sqrt(g/H)), the largest |ρ/ρ0 − 1| met, the pressure noise, the energy change and
the wall time:

- blew up: the stability guard stopped the run with its default limits (|ρ/ρ0 − 1| >
  0.2 for longer than an impact's transient, 10 h/c0; a density outside (0, 2ρ0), a
  speed above c0, or NaN), as a user running the case would see it;
- pressure noise: the RMS over the fluid of p_i minus the local linear least-squares
  fit of p around i (kernel weights within 2h), divided by ρ0 g H, averaged over snapshots every
  Δt* = 0.5 from t* = 3 (dam break: after the impact) or t* = 5 (hydrostatic). It sees
  the particle-to-particle oscillation that density diffusion removes and not the
  smooth field;
- energy change: E_k + E_p + E_c at the end minus at the start, divided by the potential
  energy the dam-break column releases (ρ0 g H³(1 − 2/5.366)) or, for the hydrostatic
  tank, by ρ0 g H² L/2.

Writes docs/stability/{results.csv, README.md, <case>_<map>_<variant>.png}. Runs in
parallel processes, one solver thread each.

    python3 benches/stability_map.py              # the full grids (about 4 minutes on 2 cores)
    python3 benches/stability_map.py --quick      # coarser grids (about 1 minute)
"""

import argparse
import csv
import math
import multiprocessing
import os
import pathlib
import time
import tomllib

ROOT = pathlib.Path(__file__).resolve().parent.parent
RHO0, G = 1000.0, 9.81
DIFFUSIONS = {"none": "no diffusion", "molteni_colagrossi": "Molteni-Colagrossi",
              "ferrari": "Ferrari", "delta_sph": "δ-SPH"}
DELTA_VARIANTS = ("molteni_colagrossi", "ferrari", "delta_sph")
#: one colour scale for every heat map, so that they compare
NOISE_RANGE = (1e-3, 1.0)
INTEGRATORS = {"rk4": "RK4 (frozen diffusion)", "symplectic": "symplectic"}
FULL = {"cfl": {"rk4": [0.5, 1.0, 1.5, 2.0, 2.5, 3.0],
                "symplectic": [0.15, 0.25, 0.5]},
        "alpha": [0.0, 0.02, 0.1],
        "delta": [0.0, 0.025, 0.05, 0.1, 0.2]}
QUICK = {"cfl": {"rk4": [1.5, 2.5], "symplectic": [0.15, 0.5]},
         "alpha": [0.0, 0.02], "delta": [0.0, 0.1]}


class Case:
    """One of the two cases: its configuration and its measures."""

    def __init__(self, name, toml, spacing, depth, until, noise_from, energy_scale):
        self.name, self.toml, self.spacing, self.depth = name, toml, spacing, depth
        self.until, self.noise_from, self.energy_scale = until, noise_from, energy_scale

    def config(self, diffusion, delta, alpha, integrator, cfl):
        with open(ROOT / "examples" / self.toml, "rb") as f:
            c = tomllib.load(f)
        c["particles"]["spacing"] = self.spacing
        s = c["scheme"]
        s.update(diffusion=diffusion, delta=delta, integrator=integrator, cfl=cfl)
        if alpha == 0.0:
            s["viscosity"] = "none"
            s.pop("alpha", None)
        else:
            s.update(viscosity="artificial", alpha=alpha)
        c["time"] = {"end": self.until * math.sqrt(self.depth / G)}
        c["diagnostics"] = {"probes": c["diagnostics"].get("probes", [])}
        return c


def pressure_noise(sim, h):
    """RMS over the fluid of p_i minus the local linear fit of p around i (weighted
    least squares with Wendland C2 weights within 2h, i included): the particle-to-
    particle pressure noise. A linear fit reproduces a linear field exactly even where
    the neighbourhood is one-sided (free surface, walls), so the smooth field, the
    hydrostatic gradient included, does not count."""
    import numpy as np
    import deltasph as ds
    fluid = sim.kind == ds.FLUID
    x, p = sim.positions[fluid], sim.pressure[fluid]
    d = x[None, :, :] - x[:, None, :]                          # x_j - x_i
    q = np.sqrt((d ** 2).sum(axis=2)) / h
    w = np.where(q < 2.0, (1.0 - 0.5 * q) ** 4 * (2.0 * q + 1.0), 0.0)
    basis = np.concatenate([np.ones(q.shape + (1,)), d / h], axis=2)   # [1, (x_j-x_i)/h]
    moments = np.einsum("ij,ija,ijb->iab", w, basis, basis)
    rhs = np.einsum("ij,ija,j->ia", w, basis, p)
    coef = np.linalg.solve(moments + 1e-12 * np.eye(basis.shape[2]), rhs[..., None])[..., 0]
    return float(np.sqrt(np.mean((p - coef[:, 0]) ** 2)))


CASES = {
    "dam_break": Case("dam_break", "dam_break_2d.toml", 0.05, 0.6, 7.0, 3.0,
                      RHO0 * G * 0.6**3 * (1.0 - 2.0 / 5.366)),
    "hydrostatic": Case("hydrostatic", "hydrostatic_2d.toml", 0.1, 1.0, 20.0, 5.0,
                        RHO0 * G * 1.0**2 * 2.0 / 2.0),
}


def one_run(job):
    """Runs one point of a map; returns its row."""
    import numpy as np
    import deltasph as ds
    case = CASES[job["case"]]
    cfg = case.config(job["diffusion"], job["delta"], job["alpha"], job["integrator"],
                      job["cfl"])
    t_ref = math.sqrt(case.depth / G)
    sim = ds.Simulation(cfg)
    fluid = sim.kind == ds.FLUID
    e0 = sim.energies()["total"]
    noise, max_drho, blew_up = [], 0.0, None
    h = 1.33 * case.spacing
    start = time.perf_counter()
    t_star = 0.0
    try:
        while t_star < case.until - 1e-9:
            t_star = min(t_star + 0.5, case.until)
            sim.run(until=t_star * t_ref)
            max_drho = max(max_drho, float(np.abs(sim.density[fluid] / RHO0 - 1).max()))
            if t_star >= case.noise_from:
                noise.append(pressure_noise(sim, h) / (RHO0 * G * case.depth))
    except ds.InstabilityError as e:
        blew_up = e.time / t_ref
        max_drho = max(max_drho, float(np.abs(sim.density[fluid] / RHO0 - 1).max()))
    wall = time.perf_counter() - start
    row = dict(job, completed=blew_up is None, blew_up_at=blew_up, max_drho=max_drho,
               wall_s=round(wall, 3), steps=sim.n_steps, noise=math.nan, energy_change=math.nan)
    if blew_up is None:
        row["noise"] = sum(noise) / len(noise)
        row["energy_change"] = (sim.energies()["total"] - e0) / case.energy_scale
    return row


def jobs(grid):
    """The runs of both maps, each once (the maps share δ = 0.1, α = 0)."""
    keys = set()
    for case in CASES:
        for integrator in INTEGRATORS:
            for cfl in grid["cfl"][integrator]:
                for diffusion in DIFFUSIONS:
                    for alpha in grid["alpha"]:
                        keys.add((case, integrator, cfl, diffusion, 0.1, alpha))
                for diffusion in DELTA_VARIANTS:
                    for delta in grid["delta"]:
                        keys.add((case, integrator, cfl, diffusion, delta, 0.0))
    out = [dict(case=c, integrator=i, cfl=cfl, diffusion=d, delta=delta, alpha=a)
           for (c, i, cfl, d, delta, a) in keys]
    # the costliest first, so that the pool ends together
    return sorted(out, key=lambda j: j["cfl"] * (2 if j["integrator"] == "rk4" else 1))


def in_map(r, kind):
    """Whether row r belongs to the map "alpha" (δ = 0.1) or "delta" (α = 0)."""
    if kind == "alpha":
        return r["delta"] == 0.1
    return r["alpha"] == 0.0 and r["diffusion"] in DELTA_VARIANTS


def worker_init():
    os.environ["RAYON_NUM_THREADS"] = "1"


def heat_map(rows, case, kind, diffusion, out):
    """One PNG: y = α or δ, x = CFL, one panel per integrator; colour = noise of the
    completed runs, crosses with the blow-up time for the others."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    key = "alpha" if kind == "alpha" else "delta"
    sel = [r for r in rows if r["case"] == case and in_map(r, kind)
           and r["diffusion"] == diffusion]
    ys = sorted({r[key] for r in sel})
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), constrained_layout=True)
    for ax, integrator in zip(axes, INTEGRATORS):
        xs = sorted({r["cfl"] for r in sel if r["integrator"] == integrator})
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in sel:
            if r["integrator"] != integrator:
                continue
            i, j = ys.index(r[key]), xs.index(r["cfl"])
            if r["completed"]:
                grid[i, j] = r["noise"]
                ax.text(j, i, f"{r['noise']:.3f}", ha="center", va="center", fontsize=7)
            else:
                ax.text(j, i, f"✗ {r['blew_up_at']:.2f}", ha="center", va="center",
                        fontsize=7, color="firebrick")
        im = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis",
                       norm=matplotlib.colors.LogNorm(vmin=NOISE_RANGE[0], vmax=NOISE_RANGE[1]))
        ax.set_xticks(range(len(xs)), [f"{x:g}" for x in xs])
        ax.set_yticks(range(len(ys)), [f"{y:g}" for y in ys])
        ax.set_xlabel("Courant number")
        ax.set_ylabel("α" if key == "alpha" else "δ")
        ax.set_title(INTEGRATORS[integrator], fontsize=10)
    fig.colorbar(im, ax=axes, label="pressure noise / ρ0 g H")
    fig.suptitle(f"{case}: {DIFFUSIONS[diffusion]}"
                 + (" (δ = 0.1)" if kind == "alpha" and diffusion != "none" else "")
                 + (", α = 0" if kind == "delta" else "")
                 + " — ✗ t*: blew up at t·sqrt(g/H) = t*")
    name = f"{case}_{kind}_{diffusion}.png"
    fig.savefig(out / name, dpi=110)
    plt.close(fig)
    return name


def largest_stable_cfl(rows, case, integrator, diffusion="delta_sph", alpha=0.02, delta=0.1):
    ok = [r["cfl"] for r in rows if r["case"] == case and in_map(r, "alpha")
          and r["integrator"] == integrator and r["diffusion"] == diffusion
          and r["alpha"] == alpha and r["delta"] == delta and r["completed"]]
    cfls = sorted({r["cfl"] for r in rows if r["integrator"] == integrator})
    # the largest CFL below which every run completed
    stable = None
    for c in cfls:
        if c in ok:
            stable = c
        else:
            break
    return stable


def summary(rows):
    lines = []
    for case in CASES:
        for integrator in INTEGRATORS:
            for diffusion in DIFFUSIONS:
                for alpha in sorted({r["alpha"] for r in rows if in_map(r, "alpha")}):
                    c = largest_stable_cfl(rows, case, integrator, diffusion, alpha)
                    lines.append((case, integrator, diffusion, alpha, c))
    return lines


DEFAULT_CFL = {"rk4": 1.5, "symplectic": 0.25}


def headline(rows):
    """The README's findings: largest stable Courant numbers, and the smallest δ that
    keeps each case as quiet as δ = 0.2 (noise within 25%) at the default Courant
    number, without viscosity."""
    lines = []
    for case in CASES:
        for integrator in INTEGRATORS:
            for alpha in (0.02, 0.0):
                c = largest_stable_cfl(rows, case, integrator, "delta_sph", alpha)
                lines.append(f"- {case}, {INTEGRATORS[integrator]}, δ-SPH (δ = 0.1), α = {alpha:g}: "
                             f"stable up to CFL {c if c is not None else '(none of the grid)'}")
    for case in CASES:
        for integrator in INTEGRATORS:
            for diffusion in DELTA_VARIANTS:
                sel = {r["delta"]: r for r in rows
                       if r["case"] == case and r["integrator"] == integrator
                       and r["diffusion"] == diffusion and r["alpha"] == 0.0
                       and r["cfl"] == DEFAULT_CFL[integrator]}
                ref = sel.get(max(sel, default=None))
                if ref is None or not ref["completed"]:
                    continue
                quiet = [d for d, r in sorted(sel.items())
                         if r["completed"] and r["noise"] <= 1.25 * ref["noise"]]
                lines.append(f"- {case}, {INTEGRATORS[integrator]} at CFL "
                             f"{DEFAULT_CFL[integrator]}, α = 0, {DIFFUSIONS[diffusion]}: "
                             f"smallest δ as quiet as δ = {max(sel):g} "
                             f"(noise {ref['noise']:.4f} ρ0gH): {quiet[0]:g}"
                             f"; δ = 0: " + ("completes, noise "
                                              f"{sel[0.0]['noise']:.4f}" if sel.get(0.0, {}).get("completed")
                                              else "blows up" if 0.0 in sel else "not run"))
    return lines


def write_report(rows, out, grid):
    names = [heat_map(rows, case, kind, d, out) for case in CASES
             for kind in ("alpha", "delta")
             for d in (DIFFUSIONS if kind == "alpha" else DELTA_VARIANTS)]
    with open(out / "results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    text = ["# Stability map", "",
            "Generated by `python3 benches/stability_map.py"
            + (" --quick" if grid is QUICK else "") + f"`: {len(rows)} runs, "
            f"{sum(r['wall_s'] for r in rows) / 60:.0f} minutes of one-thread solver time. "
            "Cases, measures and "
            "grids are described in the script's docstring; every run is a row of "
            "[results.csv](results.csv).", "",
            "## Findings", ""] + headline(rows) + ["",
            "## Largest Courant number with every smaller one stable", "",
            "| case | integrator | diffusion | " + " | ".join(
                f"α = {a:g}" for a in grid["alpha"]) + " |",
            "|---|---|---|" + "---|" * len(grid["alpha"])]
    table = {}
    for case, integrator, diffusion, alpha, c in summary(rows):
        table.setdefault((case, integrator, diffusion), {})[alpha] = c
    for (case, integrator, diffusion), by_alpha in table.items():
        cells = [("—" if by_alpha.get(a) is None else f"{by_alpha[a]:g}")
                 for a in grid["alpha"]]
        text.append(f"| {case} | {integrator} | {DIFFUSIONS[diffusion]} | "
                    + " | ".join(cells) + " |")
    text += ["", "(— : the smallest Courant number of the grid already failed.)", "",
             "## Heat maps", "",
             "Colour and number: pressure noise / ρ0 g H of a completed run; ✗ t*: the run "
             "blew up at t·sqrt(g/H) = t*.", ""]
    text += [f"![{n}]({n})" for n in names]
    (out / "README.md").write_text("\n".join(text) + "\n")


def read_rows(path):
    """Rows of results.csv with their types back."""
    def value(k, v):
        if k in ("case", "integrator", "diffusion"):
            return v
        if k == "completed":
            return v == "True"
        return float(v) if v not in ("", "None") else None
    with open(path) as f:
        return [{k: value(k, v) for k, v in r.items()} for r in csv.DictReader(f)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarser grids")
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "docs" / "stability")
    parser.add_argument("--workers", type=int, default=os.cpu_count())
    parser.add_argument("--report-only", action="store_true",
                        help="rewrite the report from an existing results.csv")
    args = parser.parse_args()
    grid = QUICK if args.quick else FULL
    if args.report_only:
        rows = read_rows(args.out / "results.csv")
        write_report(rows, args.out, grid)
        return
    todo = jobs(grid)
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    rows = []
    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(args.workers, initializer=worker_init) as pool:
        for k, row in enumerate(pool.imap_unordered(one_run, todo), 1):
            rows.append(row)
            state = "ok" if row["completed"] else f"blew up at t* = {row['blew_up_at']:.2f}"
            print(f"[{k}/{len(todo)}] {row['case']} {row['integrator']} CFL {row['cfl']} "
                  f"{row['diffusion']} δ {row['delta']} α {row['alpha']}: {state} "
                  f"({row['wall_s']:.1f} s)", flush=True)
    order = ("case", "integrator", "diffusion", "delta", "alpha", "cfl")
    rows.sort(key=lambda r: tuple(str(r[k]) if isinstance(r[k], str) else r[k] for k in order))
    write_report(rows, args.out, grid)
    print(f"report in {args.out / 'README.md'} ({(time.perf_counter() - start) / 60:.1f} minutes)")


if __name__ == "__main__":
    main()

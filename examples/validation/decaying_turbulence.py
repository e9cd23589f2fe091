#!/usr/bin/env python3
"""2D decaying turbulence at Re = 10⁴: δ-SPH without closure ("DNS-SPH") and δ-LES-SPH
against a pseudo-spectral reference (Di Mascio et al. 2017's claim that the LES closure
brings the large scales closer to the resolved flow and removes the high-k energy
pile-up of an under-resolved SPH run).

The flow: `turbulence_field.py` (the unforced 8 × 8 Taylor-Green cell array of the unit
square plus a 5% random perturbation), case file `decaying_turbulence.toml` (c0 = 10U,
h = 2Δx, RK4, TIC on). The reference: `turbulence_reference.py` (fluidsim ns2d on a
1024² grid, cached in examples/validation/data/).

Schemes (`--scheme`): `les` δ-LES-SPH at its defaults; `dns` δ-SPH (density diffusion
δ = 0.1, physical viscosity, no shifting); `dns_plus` δ+-SPH (the same with shifting).

Every `--every` time units the run records the particles' kinetic energy ½Σm|u|²/Σm
and the shell-summed spectrum E(k) of the gridded velocity; at t = 1, 2, 3 the
vorticity. The gridding: the particle velocity interpolated (Shepard-normalised
Wendland C2, h = 2Δx) onto the L/Δx × L/Δx grid of the cell centres, then FFT. That
kernel filters the smallest resolved scales, so gridded spectra and enstrophy are
compared with the reference's through the same filter (F² E(k), F the kernel's
transfer function), the kinetic energy of the particles with the reference's
unfiltered one. Enstrophy: Σ (2πk)² E(k) over the resolved shells k <= L/(4Δx) (the
kernel's support is 4Δx). Spectral errors: rms of log₁₀(E/E_ref) over k <= L/(8Δx)
("large scales") and the mean of E/E_ref over L/(8Δx) < k <= L/(4Δx) ("high k").
At t = 1, 2, 3 the correlation of the gridded vorticity with the filtered reference's.
`--set table.key=value` (repeatable) changes a case key: such runs enter the table (the
sensitivities of docs/validation/decaying_turbulence.md), not the figures.

    RAYON_NUM_THREADS=1 python3 examples/validation/decaying_turbulence.py --scheme les
    RAYON_NUM_THREADS=1 python3 examples/validation/decaying_turbulence.py --scheme dns
    python3 examples/validation/decaying_turbulence.py --summary
    python3 examples/validation/decaying_turbulence.py --quick   # L/Δx = 100, all three schemes

Writes docs/validation/decaying_turbulence_<scheme>_n<L/Δx>.npz per run (ignored by git)
and, with --summary, decaying_turbulence.csv, decaying_turbulence_table.md and the PNGs
decaying_turbulence_{energy,spectra,vorticity}.png.
"""
import argparse
import json
import pathlib
import sys
import time
import tomllib

import numpy as np
from scipy.spatial import cKDTree
from scipy.special import j0

import deltasph as ds

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import turbulence_field as tf  # noqa: E402
from records import write_csv, write_table  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
REFERENCE = HERE / "data" / "turbulence_reference_re10000_n1024.npz"
SNAPSHOTS = (1.0, 2.0, 3.0)
SCHEMES = {"les": "δ-LES-SPH", "dns": "δ-SPH (DNS-SPH)", "dns_plus": "δ+-SPH (DNS-SPH)"}
COLOURS = {"les": "tab:red", "dns": "tab:blue", "dns_plus": "tab:orange"}


def config(scheme, n, end, overrides=()):
    """The case of `scheme` at L/Δx = n, with `overrides` ("table.key=<TOML value>")."""
    case = tomllib.loads((HERE / "decaying_turbulence.toml").read_text())
    case["particles"]["spacing"] = 1.0 / n
    case["time"]["end"] = end
    if scheme != "les":
        for key in ("turbulence", "les_velocity"):
            del case["scheme"][key]
        case["scheme"]["diffusion"] = "delta_sph"
    if scheme == "dns_plus":
        case["scheme"]["shifting"] = "delta_plus"
    for override in overrides:
        dotted, value = override.split("=", 1)
        table, key = dotted.strip().split(".")
        case.setdefault(table, {})[key] = tomllib.loads(f"v = {value}")["v"]
    return case


def wendland_c2(q):
    """Wendland C2 in 2D with support 2h, up to its normalisation (Shepard cancels it)."""
    r = np.clip(1.0 - 0.5 * q, 0.0, None)
    return r**4 * (1.0 + 2.0 * q)


def gridded_velocity(sim, n):
    """The particle velocity of a running simulation on the n × n grid of cell centres
    (see `gridded`)."""
    return gridded(sim.positions, sim.mass / sim.density, sim.velocities, n)


def gridded(positions, volumes, velocities, n):
    """Particle velocities on the n × n grid of cell centres (indexing [iy, ix]):
    Shepard-normalised kernel interpolation with h = 2Δx over the periodic square."""
    x = np.mod(positions[:, :2], 1.0)
    g = (np.arange(n) + 0.5) / n
    gx, gy = np.meshgrid(g, g)
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    h = 2.0 / n
    pairs = cKDTree(grid, boxsize=1.0).sparse_distance_matrix(
        cKDTree(x, boxsize=1.0), 2.0 * h, output_type="coo_matrix")
    w = wendland_c2(pairs.data / h) * volumes[pairs.col]
    norm = np.bincount(pairs.row, weights=w, minlength=n * n)
    return [(np.bincount(pairs.row, weights=w * velocities[pairs.col, d], minlength=n * n)
             / norm).reshape(n, n) for d in range(2)]


def kinetic_energy(sim):
    m, u = sim.mass, sim.velocities
    return 0.5 * np.sum(m * np.sum(u * u, axis=1)) / np.sum(m)


def perturb(sim):
    x = sim.positions
    sim.set_velocities(np.column_stack(tf.velocity(x[:, 0], x[:, 1])))


def run(scheme, n, end, every, overrides=()):
    sim = ds.Simulation(config(scheme, n, end, overrides))
    variant = ", ".join(overrides)
    perturb(sim)
    times, energy, spectra, vorticity, field_times = [], [], [], [], []
    start, steps, status = time.perf_counter(), 0, "stable"
    samples = np.arange(0.0, end + 0.5 * every, every)
    try:
        for t in samples:
            while sim.time < t * (1 - 1e-12):
                sim.step()
                steps += 1
            u, v = gridded_velocity(sim, n)
            times.append(sim.time)
            energy.append(kinetic_energy(sim))
            spectra.append(tf.spectrum(u, v)[1])
            if any(abs(t - s) < 1e-9 for s in SNAPSHOTS):
                field_times.append(sim.time)
                vorticity.append(tf.vorticity_on_grid(u, v).astype(np.float32))
            print(f"{scheme} n={n} t={sim.time:.2f} E={energy[-1]:.5f} "
                  f"Z={tf.shell_enstrophy(spectra[-1], n // 4):.2f} "
                  f"wall {time.perf_counter() - start:.0f} s", flush=True)
    except ds.InstabilityError as err:
        status = f"unstable at t = {sim.time:.3f}: {str(err).splitlines()[0]}"
        print(status)
    wall = time.perf_counter() - start
    np.savez_compressed(
        OUT / f"decaying_turbulence_{scheme}_n{n}{tag(overrides)}.npz", scheme=scheme, n=n,
        variant=variant, time=np.array(times), energy=np.array(energy),
        spectra=np.array(spectra), field_times=np.array(field_times),
        vorticity=np.array(vorticity), wall_s=wall, steps=steps,
        particles=sim.n_particles, status=status)
    print(f"{scheme} n={n}: {steps} steps, {wall:.0f} s, "
          f"{sim.n_particles * steps / wall:.3g} particle-steps/s, {status}")


def sample_at(times, s):
    """The index of the sample recorded at the nominal time s (a run stops at the first
    step at or past it), or None."""
    if len(times) == 0:
        return None
    i = int(np.argmin(np.abs(times - s)))
    return i if abs(times[i] - s) < 0.01 else None


def tag(overrides):
    """The file-name suffix of a run with `overrides`: '' without, else `_` and the
    overridden keys and values."""
    text = "_".join(o.split(".", 1)[1].replace("=", "") for o in overrides)
    return "_" + "".join(c if c.isalnum() or c in "_.-" else "" for c in text) if text else ""


def load(path):
    with np.load(path) as data:
        return {k: data[k] for k in data.files}


def gridding_transfer(k, n):
    """F(k) of the gridding: the continuum transfer function of the normalised Wendland
    C2 kernel with h = 2Δx = 2/n at wavenumber 2πk, F = ∫W J0(2πk r) r dr / ∫W r dr.
    The reference seen through the same filter has the spectrum F² E(k)."""
    h = 2.0 / n
    r = np.linspace(0.0, 2.0 * h, 2001)
    w = wendland_c2(r / h) * r
    kernel = np.trapezoid(w, r)
    return np.array([np.trapezoid(w * j0(2.0 * np.pi * kk * r), r) / kernel
                     for kk in np.atleast_1d(k)])


def filtered_reference(ref, n):
    """The reference's spectra through the gridding filter of an L/Δx = n run, truncated
    to the run's shells k = 1 .. n/2, and its enstrophy over the resolved band
    |n| <= n/4."""
    k = np.arange(1, n // 2 + 1)
    spectra = ref["spectra"][:, : n // 2] * gridding_transfer(k, n) ** 2
    return spectra, tf.shell_enstrophy(spectra, n // 4)


def spectral_slope(e):
    """The least-squares slope of log E against log k over kL ∈ [60, 150] (docs/theory.md §13 V3's
    band; shells k = 10 .. 23), from a spectrum E(k), k = 1, 2, ..."""
    k = np.arange(1, len(e) + 1)
    band = (2.0 * np.pi * k >= 60.0) & (2.0 * np.pi * k <= 150.0)
    return float(np.polyfit(np.log(k[band]), np.log(e[band]), 1)[0])


def filtered_reference_vorticity(ref, j, n):
    """The reference's vorticity at its j-th field time on a run's grid of cell centres
    (n × n, x = (i + ½)/n), through the gridding filter: the stored 256² point values
    (x = i/256) to Fourier coefficients, the shells |k| < n/2 kept and damped by F(k),
    then evaluated at the cell centres."""
    w = ref["vorticity"][j].astype(float)
    m = w.shape[0]
    coefficients = np.fft.fft2(w) / m**2
    kx, ky = tf.wavenumbers(m)
    kept = (np.abs(kx) < n // 2) & (np.abs(ky) < n // 2)
    k = np.hypot(kx, ky)
    on_run = np.zeros((n, n), dtype=complex)
    shift = np.exp(1j * np.pi * (kx + ky) / n)
    transfer = np.interp(k, np.arange(n), gridding_transfer(np.arange(n), n))
    on_run[ky[kept].astype(int) % n, kx[kept].astype(int) % n] = (
        coefficients * transfer * shift)[kept]
    return np.real(np.fft.ifft2(on_run)) * n**2


def vorticity_correlation(run_record, ref, s):
    """⟨ω ω_ref⟩ / sqrt(⟨ω²⟩⟨ω_ref²⟩) at time s, the reference filtered as the run."""
    j = sample_at(run_record["field_times"], s)
    if j is None:
        return None
    w = run_record["vorticity"][j].astype(float)
    exact = filtered_reference_vorticity(
        ref, int(np.argmin(np.abs(ref["field_times"] - s))), w.shape[0])
    return float(np.sum(w * exact) / np.sqrt(np.sum(w * w) * np.sum(exact * exact)))


def figures(run_record, ref):
    """The comparison figures of one run against the reference: particle kinetic energy
    against the reference's, gridded enstrophy and spectra against the filtered
    reference's."""
    n, t = int(run_record["n"]), run_record["time"]
    spectra_ref, enstrophy_ref = filtered_reference(ref, n)
    e_ref = np.interp(t, ref["time"], ref["energy"])
    z_ref = np.interp(t, ref["time"], enstrophy_ref)
    enstrophy = tf.shell_enstrophy(run_record["spectra"], n // 4)
    row = {"scheme": SCHEMES[str(run_record["scheme"])],
           "variant": str(run_record.get("variant", "")), "n": n,
           "status": str(run_record["status"]), "wall_s": float(run_record["wall_s"]),
           "steps": int(run_record["steps"]),
           "particle_steps_per_s": float(run_record["particles"] * run_record["steps"]
                                         / run_record["wall_s"])}
    for s in SNAPSHOTS:
        i = sample_at(t, s)
        if i is not None:
            row[f"E_err_{s:g}"] = float(run_record["energy"][i] / e_ref[i] - 1.0)
            row[f"Z_err_{s:g}"] = float(enstrophy[i] / z_ref[i] - 1.0)
        correlation = vorticity_correlation(run_record, ref, s)
        if correlation is not None:
            row[f"vorticity_correlation_{s:g}"] = correlation
    row["E_rms_err"] = float(np.sqrt(np.mean((run_record["energy"] / e_ref - 1.0) ** 2)))
    band = n // 4
    k = np.arange(1, band + 1)
    for s in run_record["field_times"]:
        j, r = (int(np.argmin(np.abs(times - s))) for times in (t, ref["time"]))
        sph, exact = run_record["spectra"][j][:band], spectra_ref[r][:band]
        large = k <= band // 2
        row[f"spectrum_large_{s:.0f}"] = float(np.sqrt(np.mean(
            np.log10(sph[large] / exact[large]) ** 2)))
        row[f"spectrum_high_{s:.0f}"] = float(np.mean(sph[~large] / exact[~large]))
        row[f"slope_{s:.0f}"] = spectral_slope(run_record["spectra"][j])
        row[f"slope_reference_filtered_{s:.0f}"] = spectral_slope(spectra_ref[r])
    return row


def summary():
    ref = load(REFERENCE)
    runs = [load(p) for p in sorted(OUT.glob("decaying_turbulence_*_n*.npz"))]
    rows = [figures(r, ref) for r in runs]
    columns = list(dict.fromkeys(c for r in rows for c in r))
    write_csv(OUT / "decaying_turbulence.csv", columns, rows)
    table(rows)
    plots([r for r in runs if not str(r.get("variant", ""))], ref)
    (OUT / "decaying_turbulence.json").write_text(json.dumps(rows, indent=1))


def pct(x):
    return f"{100 * x:+.1f}%" if x is not None else "–"


def table(rows):
    header = ["scheme", "overrides", "L/Δx", "E err t=1/2/3", "Z err t=1/2/3 (resolved band)",
              "ω correlation t=1/2/3", "log₁₀ spectrum rms, large scales t=2/3",
              "high-k E/E_ref t=2/3",
              "wall", "status"]
    body = []
    for r in rows:
        body.append([
            r["scheme"], r["variant"] or "defaults", str(r["n"]),
            " / ".join(pct(r.get(f"E_err_{s:g}")) for s in SNAPSHOTS),
            " / ".join(pct(r.get(f"Z_err_{s:g}")) for s in SNAPSHOTS),
            " / ".join(f"{r[k]:.2f}" if k in r else "–"
                       for k in (f"vorticity_correlation_{s:g}" for s in SNAPSHOTS)),
            " / ".join(f"{r[k]:.3f}" if k in r else "–"
                       for k in ("spectrum_large_2", "spectrum_large_3")),
            " / ".join(f"{r[k]:.2f}" if k in r else "–"
                       for k in ("spectrum_high_2", "spectrum_high_3")),
            f"{r['wall_s']:.0f} s", r["status"].split(":")[0]])
    write_table(OUT / "decaying_turbulence_table.md", header, body)


def line_style(runs, n):
    """Solid for the finest resolution of the runs, dashed, dotted for the coarser."""
    resolutions = sorted({int(r["n"]) for r in runs}, reverse=True)
    return ("-", "--", ":")[min(resolutions.index(n), 2)]


def run_line(run_record, runs):
    """Label, colour and line style of a run's curves."""
    scheme, n = str(run_record["scheme"]), int(run_record["n"])
    return {"label": f"{SCHEMES[scheme]}, L/Δx = {n}", "color": COLOURS[scheme],
            "ls": line_style(runs, n), "lw": 1.0}


def plots(runs, ref):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    axes[0].plot(ref["time"], ref["energy"], "k", lw=1.5, label="spectral 1024²")
    for n in sorted({int(r["n"]) for r in runs}):
        axes[1].plot(ref["time"], filtered_reference(ref, n)[1], "k", lw=1.2,
                     ls=line_style(runs, n), label=f"spectral, filtered as L/Δx = {n}")
    for r in runs:
        axes[0].plot(r["time"], r["energy"], **run_line(r, runs))
        axes[1].plot(r["time"], tf.shell_enstrophy(r["spectra"], int(r["n"]) // 4),
                     **run_line(r, runs))
    axes[0].set_ylabel("kinetic energy E / U²")
    axes[1].set_ylabel("enstrophy ½⟨ω²⟩ over |n| ≤ L/(4Δx)")
    for ax in axes:
        ax.set_xlabel("t U/L")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "decaying_turbulence_energy.png", dpi=120)
    plt.close(fig)
    spectra_plot(plt, runs, ref)
    vorticity_plot(plt, runs, ref)


def spectra_plot(plt, runs, ref):
    times = [t for t in SNAPSHOTS if t > 1.0]
    fig, axes = plt.subplots(1, len(times), figsize=(5.5 * len(times), 4.2))
    for ax, s in zip(axes, times):
        r = int(np.argmin(np.abs(ref["time"] - s)))
        k = np.arange(1, len(ref["spectra"][r]) + 1)
        ax.loglog(k, ref["spectra"][r], "k", lw=1.5, label="spectral 1024²")
        for n in sorted({int(rr["n"]) for rr in runs}):
            e = filtered_reference(ref, n)[0][r]
            ax.loglog(np.arange(1, len(e) + 1), e, color="grey", lw=1.0,
                      ls=line_style(runs, n), label=f"spectral, filtered as L/Δx = {n}")
        for run_record in runs:
            j = sample_at(run_record["time"], s)
            if j is not None:
                e = run_record["spectra"][j]
                ax.loglog(np.arange(1, len(e) + 1), e, **run_line(run_record, runs))
        ax.loglog(k[10:200], 30.0 * k[10:200] ** -3.0, "k", ls=(0, (1, 3)), lw=0.6,
                  label="k⁻³")
        ax.set_ylim(1e-10, 1)
        ax.set_xlabel("k L / 2π")
        ax.set_ylabel("E(k)")
        ax.set_title(f"t U/L = {s:g}")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "decaying_turbulence_spectra.png", dpi=120)
    plt.close(fig)


def vorticity_plot(plt, runs, ref):
    """Vorticity at t = 1, 2, 3: the reference (at 256², the grid it is stored on), then
    each scheme at its finest resolution, gridded as for the spectra."""
    finest = {}
    for r in runs:
        if int(r["n"]) > int(finest.get(str(r["scheme"]), {"n": 0})["n"]):
            finest[str(r["scheme"])] = r
    shown = [finest[s] for s in SCHEMES if s in finest]
    fig, axes = plt.subplots(len(SNAPSHOTS), 1 + len(shown),
                             figsize=(3.4 * (1 + len(shown)), 3.4 * len(SNAPSHOTS)),
                             squeeze=False)
    for row, s in zip(axes, SNAPSHOTS):
        reference = ref["vorticity"][int(np.argmin(np.abs(ref["field_times"] - s)))]
        panels = [("spectral 1024²", reference)]
        for r in shown:
            j = sample_at(r["field_times"], s)
            w = r["vorticity"][j] if j is not None else np.full((2, 2), np.nan)
            panels.append((f"{SCHEMES[str(r['scheme'])]}, L/Δx = {int(r['n'])}", w))
        scale = 0.7 * np.max(np.abs(reference))
        for ax, (title, w) in zip(row, panels):
            ax.imshow(w, origin="lower", extent=(0, 1, 0, 1), cmap="RdBu_r", vmin=-scale,
                      vmax=scale)
            ax.set_title(f"{title}, t U/L = {s:g}", fontsize=8)
            ax.set_xticks([])
            ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(OUT / "decaying_turbulence_vorticity.png", dpi=75)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scheme", choices=sorted(SCHEMES), nargs="+",
                        default=["les", "dns_plus", "dns"])
    parser.add_argument("--n", type=int, default=200, help="L/Δx")
    parser.add_argument("--end", type=float, default=3.0)
    parser.add_argument("--every", type=float, default=0.05)
    parser.add_argument("--quick", action="store_true", help="L/Δx = 100, then --summary")
    parser.add_argument("--set", action="append", default=[], metavar="TABLE.KEY=VALUE",
                        help="override a case key (TOML value); such runs enter the "
                             "table, not the figures")
    parser.add_argument("--summary", action="store_true")
    args = parser.parse_args()
    if not args.summary:
        for scheme in args.scheme:
            run(scheme, 100 if args.quick else args.n, args.end, args.every, args.set)
    if args.summary or args.quick:
        summary()


if __name__ == "__main__":
    main()

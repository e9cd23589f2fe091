"""Pseudo-spectral reference of the 2D decaying turbulence (`turbulence_field.py`).

Runs fluidsim's `ns2d` solver (fluidsim 26.10.0, fluidfft 0.4.5 with pyfftw; 2/3
dealiasing, RK4, CFL 1) on an n × n grid of the periodic unit square from the initial
vorticity of `turbulence_field.vorticity`, with ν = 1/Re (U = L = ρ = 1), and stores

- E(t), the enstrophy Z(t) = ½⟨ω²⟩ and the spectrum E(k, t) every `--every` time units;
- the vorticity field (down-sampled to 256²) at the `--snapshots`;

in `examples/validation/data/turbulence_reference_re<Re>_n<n>.npz`, the cached reference of
`decaying_turbulence.py`. Run it at two grids to show the reference is resolved.

    pip install fluidsim==26.10.0 fluidfft==0.4.5 pyfftw==0.15.1
    python3 examples/validation/turbulence_reference.py --re 10000 --n 1024
"""

import argparse
import os
import pathlib
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import turbulence_field as tf  # noqa: E402

DATA = pathlib.Path(__file__).resolve().parent / "data"
FIELD_GRID = 256


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--re", type=float, default=1e4)
    parser.add_argument("--n", type=int, default=1024)
    parser.add_argument("--end", type=float, default=3.0)
    parser.add_argument("--every", type=float, default=0.02)
    parser.add_argument("--snapshots", type=float, nargs="+", default=[1.0, 2.0, 3.0])
    return parser.parse_args()


def simulation(re, n, end):
    from fluidsim.solvers.ns2d.solver import Simul

    params = Simul.create_default_params()
    params.short_name_type_run = "decaying"
    params.oper.nx = params.oper.ny = n
    params.oper.Lx = params.oper.Ly = 1.0
    params.oper.type_fft = "fft2d.with_pyfftw"
    params.nu_2 = 1.0 / re
    params.time_stepping.type_time_scheme = "RK4"
    params.time_stepping.t_end = end
    params.time_stepping.deltat_max = 0.01
    params.init_fields.type = "in_script"
    params.output.periods_print.print_stdout = 0
    params.output.HAS_TO_SAVE = False
    sim = Simul(params)
    x, y = np.meshgrid(sim.oper.x_seq, sim.oper.y_seq)
    sim.state.init_from_rotfft(sim.oper.fft2(tf.vorticity(x, y)))
    return sim


def velocity(sim):
    return sim.state.get_var("ux"), sim.state.get_var("uy")


def sample(sim):
    u, v = velocity(sim)
    return 0.5 * np.mean(u * u + v * v), tf.enstrophy(u, v), tf.spectrum(u, v)[1]


def coarse_vorticity(sim):
    w = sim.state.get_var("rot")
    step = w.shape[0] // FIELD_GRID
    return w[::step, ::step].astype(np.float32)


def main():
    args = arguments()
    os.environ.setdefault("FLUIDSIM_PATH", tempfile.mkdtemp(prefix="fluidsim-"))
    sim = simulation(args.re, args.n, args.end)
    sim.time_stepping.prepare_main_loop()
    times, rows, fields, field_times = [], [], [], []
    snapshots = sorted(args.snapshots)
    start = time.perf_counter()
    next_sample = 0.0
    while True:
        t = sim.time_stepping.t
        if t >= next_sample - 1e-12:
            times.append(t)
            rows.append(sample(sim))
            next_sample += args.every
            print(f"t = {t:.3f}  E = {rows[-1][0]:.5f}  Z = {rows[-1][1]:.2f}  "
                  f"wall {time.perf_counter() - start:.0f} s", flush=True)
        if snapshots and t >= snapshots[0] - 1e-12:
            field_times.append(t)
            fields.append(coarse_vorticity(sim))
            snapshots.pop(0)
        if t >= args.end - 1e-12:
            break
        sim.time_stepping.one_time_step()
    DATA.mkdir(exist_ok=True)
    path = DATA / f"turbulence_reference_re{args.re:g}_n{args.n}.npz"
    np.savez_compressed(
        path, re=args.re, n=args.n, time=np.array(times),
        energy=np.array([r[0] for r in rows]), enstrophy=np.array([r[1] for r in rows]),
        spectra=np.array([r[2] for r in rows], dtype=np.float32), field_times=np.array(field_times),
        vorticity=np.array(fields), wall_s=time.perf_counter() - start,
        steps=sim.time_stepping.it)
    print(f"wrote {path} ({sim.time_stepping.it} steps, "
          f"{time.perf_counter() - start:.0f} s)")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Runs the same cases with two sph-cli builds and compares every output bit for bit.

For refactors that must not change results: the 2D dam break, δ+-SPH with tensile
control, a dam break on a wall with loads, sensors and the energy budget, the 2D dam
break and the δ+-SPH case on 2 MPI processes, and the 3D dam break. Both binaries need
the `mpi` feature. Every HDF5 dataset of every snapshot and restart file and every
time-series CSV must be identical.

    python3 scripts/same_bits.py OLD_SPH_CLI NEW_SPH_CLI [--work DIR]
"""
import argparse, filecmp, glob, os, subprocess, sys, tempfile
import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cases(work):
    """(name, case file, end time, processes) of each run, writing the variants."""
    ex = os.path.join(ROOT, "examples")
    plus = open(os.path.join(ex, "dam_break_2d.toml")).read()
    plus = plus.replace('walls = "free_slip"',
                        'walls = "free_slip"\nshifting = "delta_plus"\ntensile_control = true')
    wall = open(os.path.join(ex, "validation", "dam_break_wall.toml")).read()
    wall = (wall.replace("spacing = 0.0075", "spacing = 0.015")
            .replace("hi = [3.2421, 1.8]", "hi = [3.2796, 1.8]")
            .replace("output_interval = 0.0", "output_interval = 0.1")
            .replace("[diagnostics]", "[diagnostics]\nenergy_budget = true\nfree_surface = true"))
    files = {}
    for name, text in [("plus", plus), ("wall", wall)]:
        files[name] = os.path.join(work, name + ".toml")
        open(files[name], "w").write(text)
    d2, d3 = os.path.join(ex, "dam_break_2d.toml"), os.path.join(ex, "dam_break_3d.toml")
    return [("d2", d2, 0.7, 1), ("plus", files["plus"], 0.6, 1), ("wall", files["wall"], 0.6, 1),
            ("mpi", d2, 0.4, 2), ("mpiplus", files["plus"], 0.3, 2), ("d3", d3, 0.15, 1)]


def run(binary, out, work, serial):
    for name, case, end, ranks in cases(work):
        if serial and ranks > 1:
            continue
        cmd = [binary, "run", "-q", case, "--until", str(end), "--out", os.path.join(out, name)]
        if ranks > 1:
            cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + cmd
        subprocess.run(cmd, check=True, cwd=ROOT, stdout=subprocess.DEVNULL)


def differences(a, b):
    bad = 0
    for case in sorted(os.listdir(a)):
        files = sorted(glob.glob(os.path.join(a, case, "*.h5")))
        for f in files:
            g = os.path.join(b, case, os.path.basename(f))
            with h5py.File(f) as x, h5py.File(g) as y:
                names = []
                x.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
                for n in names:
                    u, v = np.asarray(x[n][()]), np.asarray(y[n][()]) if n in y else None
                    same = v is not None and u.shape == v.shape and (
                        np.array_equal(u, v, equal_nan=u.dtype.kind == "f"))
                    if not same:
                        print(f"{case}/{os.path.basename(f)}: {n} differs")
                        bad += 1
        for f in glob.glob(os.path.join(a, case, "*.csv")):
            if not filecmp.cmp(f, os.path.join(b, case, os.path.basename(f)), shallow=False):
                print(f"{case}/{os.path.basename(f)} differs")
                bad += 1
        print(f"{case}: {len(files)} HDF5 files compared")
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--work", default=None)
    ap.add_argument("--serial", action="store_true",
                    help="skip the MPI cases (for builds without the mpi feature)")
    args = ap.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="same_bits_")
    os.makedirs(work, exist_ok=True)
    for label, binary in [("old", args.old), ("new", args.new)]:
        run(os.path.abspath(binary), os.path.join(work, label), work, args.serial)
    bad = differences(os.path.join(work, "old"), os.path.join(work, "new"))
    print(f"{bad} differences ({work})")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()

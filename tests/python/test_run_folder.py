"""Run folders from Python: ``Simulation.run(out=...)`` writes the command line's run
folder file for file, ``Simulation.from_restart`` continues one bit for bit, ``ds.load``
reads folders back, and the ``deltasph`` command is the command line's."""

import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import threading

import h5py
import numpy as np
import pytest

import deltasph as ds
from conftest import EXAMPLES, example
from test_simulation import cli_binary

#: A dry probe (the top of the right wall) beside the two wetted ones of the example.
DRY = [3.2196, 1.7]


def case_file(tmp_path, end=0.1, name="case", **overrides):
    """The 2D dam break at H/Δx = 20 to `end`, snapshots every 0.025 s, as a TOML file
    (`overrides` as for `example`)."""
    config = example("dam_break_2d", particles__spacing=0.03, time__end=end,
                     time__output_interval=0.025, **overrides)
    config["diagnostics"]["probes"] = [[0.6, 0.015], DRY]
    path = tmp_path / f"{name}.toml"
    path.write_text(ds.Simulation(config).to_toml())
    return path


def cli(*args):
    return subprocess.run([cli_binary(), *map(str, args), "--quiet"], check=True,
                          capture_output=True, text=True)


def assert_same_folders(a, b):
    """Every snapshot array, the index and the time series are equal."""
    snaps = sorted(p.name for p in a.glob("particles_*.h5"))
    assert snaps and snaps == sorted(p.name for p in b.glob("particles_*.h5"))
    for name in snaps:
        with h5py.File(a / name) as x, h5py.File(b / name) as y:
            assert sorted(x) == sorted(y), name
            for field in x:
                np.testing.assert_array_equal(x[field][:], y[field][:], err_msg=field)
            assert x.attrs["time"] == y.attrs["time"] and x.attrs["step"] == y.attrs["step"]
    for name in ("particles.xmf", "timeseries.csv"):
        assert (a / name).read_text() == (b / name).read_text(), name
    for name in ("restart.h5", "case.toml"):
        assert (b / name).is_file(), name


def test_python_writes_the_cli_run_folder(tmp_path):
    case = case_file(tmp_path)
    cli("run", case, "--out", tmp_path / "cli")
    sim = ds.Simulation.from_toml(case)
    sim.run(out=tmp_path / "py")
    assert_same_folders(tmp_path / "cli", tmp_path / "py")
    assert len(list((tmp_path / "py").glob("particles_*.h5"))) == 5  # t = 0, 0.025, ..., 0.1


def test_from_restart_continues_the_folder_bit_for_bit(tmp_path):
    case = case_file(tmp_path, end=0.05)
    cli("run", case, "--out", tmp_path / "cli")
    shutil.copytree(tmp_path / "cli", tmp_path / "py")
    cli("run", "--restart", tmp_path / "cli" / "restart.h5", "--until", 0.1)
    sim = ds.Simulation.from_restart(tmp_path / "py" / "restart.h5")
    assert sim.time == pytest.approx(0.05, abs=1e-12)
    sim.run(until=0.1, out=tmp_path / "py")
    assert_same_folders(tmp_path / "cli", tmp_path / "py")


def folder_bytes(folder, pattern):
    return sum(f.stat().st_size for f in folder.glob(pattern))


def test_snapshots_and_restarts_are_compressed_unless_the_case_says_0(tmp_path):
    """Deflate level 2 by default, none with ``output.compression = 0``: the same data
    read back by h5py and ``ds.load``, in 59% of the snapshot bytes and 66% of the
    restart file's here (measured; 2D dam break at H/Δx = 20 to t = 0.1)."""
    case = case_file(tmp_path)
    plain = case_file(tmp_path, name="plain", output__compression=0)
    cli("run", case, "--out", tmp_path / "packed")
    cli("run", plain, "--out", tmp_path / "plain")
    packed, unpacked = tmp_path / "packed", tmp_path / "plain"
    for folder, filters in ((packed, ("gzip", 2, True)), (unpacked, (None, None, False))):
        for f in [*folder.glob("particles_*.h5"), folder / "restart.h5"]:
            with h5py.File(f) as h5:
                for name, d in h5.items():
                    assert (d.compression, d.compression_opts, d.shuffle) == filters, (f, name)
    for a, b in zip(ds.load(packed), ds.load(unpacked)):
        for field in ("position", "velocity", "density", "pressure", "kind", "id"):
            np.testing.assert_array_equal(a[field], b[field], err_msg=field)
    ratio = folder_bytes(packed, "particles_*.h5") / folder_bytes(unpacked, "particles_*.h5")
    assert ratio < 0.7, ratio
    ratio = folder_bytes(packed, "restart.h5") / folder_bytes(unpacked, "restart.h5")
    assert ratio < 0.8, ratio


def test_run_folders_keep_what_users_own(tmp_path):
    case = case_file(tmp_path, end=0.03)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("keep")
    with pytest.raises(OSError, match="mine"):
        ds.Simulation.from_toml(case).run(out=mine)
    assert (mine / "notes.txt").read_text() == "keep" and len(list(mine.iterdir())) == 1
    out = tmp_path / "out"
    first = ds.Simulation.from_toml(case)
    first.run(until=0.01, out=out)
    first.run(until=0.03, out=out)  # the same simulation goes on in its folder
    assert ds.load(out).times[-1] == pytest.approx(0.03, abs=1e-12)
    with pytest.raises(OSError, match="holds an earlier run"):
        ds.Simulation.from_toml(case).run(out=out)
    (out / "notes.txt").write_text("keep")
    ds.Simulation.from_toml(case).run(until=0.01, out=out, force=True)
    assert (out / "notes.txt").read_text() == "keep"
    assert ds.load(out).times[-1] == pytest.approx(0.01, abs=1e-12)
    with pytest.raises(ValueError, match="only with out="):
        ds.Simulation.from_toml(case).run(until=0.01, output_interval=0.005)


def test_ctrl_c_in_a_folder_run_leaves_a_restart_that_continues_it(tmp_path, ctrl_c):
    """Ctrl-C: a last snapshot and a restart file, then KeyboardInterrupt naming it; the
    restart continues to the same end state as an uninterrupted run."""
    case = case_file(tmp_path, end=100.0)
    sim = ds.Simulation.from_toml(case)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt, match="from_restart"):
        sim.run(until=100.0, out=tmp_path / "run")
    run = ds.load(tmp_path / "run")
    assert 0.0 < sim.time < 100.0 and run[-1].time == sim.time
    end = sim.time + 0.02
    again = ds.Simulation.from_restart(run.restart)
    assert again.time == sim.time
    again.run(until=end, out=tmp_path / "run")
    whole = ds.Simulation.from_toml(case)
    whole.step(sim.n_steps)
    whole.run(until=end)
    np.testing.assert_array_equal(again.positions, whole.positions)
    assert ds.load(tmp_path / "run")[-1].time == end


def test_load_reads_snapshots_series_and_case(tmp_path):
    case = case_file(tmp_path)
    sim = ds.Simulation.from_toml(case)
    sim.run(out=tmp_path / "run", output_interval=0.05)
    run = ds.load(tmp_path / "run")
    # snapshots come at the first step at or past each output time, the last at the end
    # (the index holds times to 10 significant digits, the snapshots exactly)
    assert run.times[0] == 0.0 and run.times[2] == pytest.approx(0.1, abs=1e-12)
    assert 0.05 <= run.times[1] < 0.05 + 2e-3 and len(run) == 3
    last = run[-1]
    assert last.time == sim.time and last.step == sim.n_steps
    for name, mine in (("position", sim.positions), ("velocity", sim.velocities),
                       ("pressure", sim.pressure), ("kind", sim.kind)):
        np.testing.assert_array_equal(last[name], mine, err_msg=name)
    assert last["position"].shape == (sim.n_particles, 2)
    assert run.at(0.04).path.name == "particles_000001.h5" and run.at(0.09).time == sim.time
    assert run.case["particles"]["spacing"] == 0.03 and last.spacing == 0.03
    assert run.restart == tmp_path / "run" / "restart.h5"
    series = run.series
    assert series["time"][-1] == pytest.approx(0.1)
    # a probe with no fluid in reach reads NaN, one at the bottom of the column does not
    assert np.isnan(series["probe1_pressure"]).all()
    assert np.isfinite(series["probe0_pressure"]).all() and series["probe0_pressure"][0] > 0
    with pytest.raises(FileNotFoundError, match="not a run folder"):
        ds.load(tmp_path)


def deltasph(*args, env=None):
    """The ``deltasph`` command, as its console script runs it (``env``: variables added
    to the environment)."""
    return subprocess.run([sys.executable, "-c", "import sys, deltasph._cli as c; "
                           "sys.exit(c.main())", *map(str, args)],
                          capture_output=True, text=True, env={**os.environ, **(env or {})})


def test_the_deltasph_command_refuses_to_run_under_an_mpi_launcher(tmp_path):
    # the wheel's command is built without MPI: started by mpirun it would run the whole
    # case once per process into one folder, so it refuses (the CI's sph-cli is built
    # with MPI, so this is where the refusal is tested)
    out = tmp_path / "run"
    done = deltasph("run", EXAMPLES / "dam_break_2d.toml", "--out", out,
                    env={"OMPI_COMM_WORLD_SIZE": "2"})
    assert done.returncode == 2
    assert done.stderr.startswith("error: started by an MPI launcher"), done.stderr
    assert not out.exists()


def test_the_deltasph_command_is_the_cli(tmp_path):
    case = EXAMPLES / "dam_break_2d.toml"
    ours = deltasph("check", case)
    theirs = subprocess.run([cli_binary(), "check", case], capture_output=True, text=True)
    assert ours.returncode == theirs.returncode == 0
    # the same report, but for the machine's free memory, which changes between the calls
    free_memory = re.compile(r"the memory available: [^\n]*")
    assert free_memory.sub("", ours.stdout) == free_memory.sub("", theirs.stdout)
    assert "the memory available: " in ours.stdout
    bad = deltasph("run", tmp_path / "missing.toml")
    assert bad.returncode == 2 and bad.stderr.startswith("error: ")
    usage = deltasph("--help")
    assert usage.returncode == 0 and "Usage: deltasph" in usage.stdout
    assert "deltasph plot" in usage.stdout


def test_deltasph_plot_writes_pngs(tmp_path):
    case = case_file(tmp_path, end=0.05)
    ds.Simulation.from_toml(case).run(out=tmp_path / "run")
    done = deltasph("plot", tmp_path / "run", "--count", "2", "--field", "pressure",
                    "--field", "velocity")
    assert done.returncode == 0, done.stderr
    pngs = sorted(p.name for p in (tmp_path / "run" / "plots").glob("*.png"))
    assert "particles_000000_pressure.png" in pngs and "particles_000002_velocity.png" in pngs
    assert {"series_energy.png", "series_probes.png", "series_surge_front.png"} <= set(pngs)
    for p in (tmp_path / "run" / "plots").glob("*.png"):
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    missing = deltasph("plot", tmp_path / "nothing")
    assert missing.returncode == 2 and "not a run folder" in missing.stderr


def test_the_probe_panel_keeps_a_probes_first_wet_samples_off_its_axis():
    """A probe dry until t = 0.5 s whose first wet samples ring (−30 kPa) before a
    settled ±1 kPa signal: the panel's range is the settled signal's, a dotted line
    marks the wetting, and the clipped extent is written on the panel."""
    from types import SimpleNamespace

    from deltasph import plot

    t = np.linspace(0.0, 1.0, 501)
    wet = np.where(t >= 0.5, 1e3 * np.sin(40 * t), np.nan)
    first = np.flatnonzero(np.isfinite(wet))[0]
    wet[first:first + 3] = [-3e4, 2e4, -1.5e4]
    run = SimpleNamespace(series={"time": t, "probe0_pressure": wet},
                          path=pathlib.Path("synthetic"), case={})
    fig = plot.series(run)["probes"]
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    assert -1.2e3 < lo < -0.9e3 and 0.9e3 < hi < 1.2e3, (lo, hi)
    assert ax.get_xlim() == (0.0, 1.0)
    assert any(line.get_xdata()[0] == t[first] for line in ax.lines[1:])
    assert "probe0_pressure -30.0 to 20.0 kPa" in ax.texts[0].get_text()

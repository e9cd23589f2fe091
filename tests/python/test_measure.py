"""``ds.measure`` and ``deltasph measure``: fields at points and wave elevations read
from a finished run's snapshots with the in-run rules: equal to what the running
simulation read at the same state, the same numbers from Python and the command line."""

import subprocess

import numpy as np
import pytest

import deltasph as ds
from conftest import example
from test_simulation import cli_binary

#: In the column, at its collapsing corner, and ahead of the water (dry).
POINTS = [[0.3, 0.12], [1.19, 0.3], [3.2196, 0.16]]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The 2D dam break at H/Δx = 20 to t = 0.1 s, snapshots every 0.025 s, with the
    simulation's own readings at its end (the last snapshot's state)."""
    folder = tmp_path_factory.mktemp("measure") / "out"
    config = example("dam_break_2d", particles__spacing=0.03, time__end=0.1,
                     time__output_interval=0.025)
    config["diagnostics"]["probes"] = POINTS
    config["diagnostics"]["sections"] = [{"name": "foot", "corners": [[1.25, -0.1], [1.25, 0.7]]}]
    sim = ds.Simulation(config)
    sim.run(out=folder)
    final = {"pressure": sim.probe_pressure(POINTS), "velocity": sim.probe_velocity(POINTS),
             "elevation": sim.wave_elevation([[0.5], [1.5]])}
    return folder, final


def test_measure_reads_what_the_run_read(run):
    folder, final = run
    m = ds.measure(folder, POINTS, fields=["pressure", "velocity", "density"],
                   elevation=[0.5, 1.5], sections=[[[1.25, -0.1], [1.25, 0.7]]])
    assert m.pressure.shape == (5, 3) and m.velocity.shape == (5, 3, 2)
    assert m.elevation.shape == (5, 2) and m.density.shape == (5, 3)
    np.testing.assert_allclose(m.times, ds.load(folder).times, rtol=1e-9)
    # every snapshot has its time-series row (the series interval divides the snapshots')
    series = ds.load(folder).series
    rows = [int(np.flatnonzero(series["step"] == step)[0]) for step in m.steps]
    for k in range(3):
        np.testing.assert_allclose(m.pressure[:, k], series[f"probe{k}_pressure"][rows],
                                   rtol=1e-9, atol=1e-9)
    assert np.isnan(m.pressure[:, 2]).all() and np.isnan(m.velocity[:, 2]).all()
    assert not np.isnan(m.pressure[:, :2]).any()
    np.testing.assert_allclose(m.volume_flow[:, 0], series["foot_volume_flow"][rows],
                               rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(m.mass_flow[:, 0], series["foot_mass_flow"][rows],
                               rtol=1e-9, atol=1e-9)
    assert m.volume_flow[-1, 0] > 0.01, "the collapsing column flows out past x = 1.25"
    # the last snapshot is the simulation's end state, read at full precision
    np.testing.assert_allclose(m.pressure[-1], final["pressure"], rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(m.velocity[-1], final["velocity"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(m.elevation[-1], final["elevation"], rtol=1e-12)


def test_python_and_the_command_line_measure_the_same(run, tmp_path):
    folder, _ = run
    line = ([0.2, 0.05], [1.0, 0.05], 5)
    grid = ([0.1, 0.1], [0.5, 0.3], [3, 2])
    m = ds.measure(folder, line=line, grid=grid, fields=["velocity"], elevation=[0.7],
                   out=tmp_path / "py.csv")
    assert m.points.shape == (11, 2)
    np.testing.assert_allclose(m.points[5:8, 0], [0.1, 0.3, 0.5])
    np.testing.assert_allclose(m.points[8], [0.1, 0.3])
    subprocess.run([cli_binary(), "measure", str(folder), "--line", "0.2,0.05", "1.0,0.05",
                    "5", "--grid", "0.1,0.1", "0.5,0.3", "3,2", "--fields", "velocity",
                    "--elevation", "0.7", "--out", str(tmp_path / "cli.csv")], check=True)
    assert (tmp_path / "py.csv").read_text() == (tmp_path / "cli.csv").read_text()
    table = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True)
    np.testing.assert_array_equal(table["point10_v"], m.velocity[:, 10, 1])
    np.testing.assert_array_equal(table["line0_elevation"], m.elevation[:, 0])
    with pytest.raises(OSError, match="--force"):
        ds.measure(folder, line=line, out=tmp_path / "py.csv")
    ds.measure(folder, line=line, out=tmp_path / "py.csv", overwrite=True)


def test_bad_requests_are_refused_in_one_line(run, tmp_path):
    folder, _ = run
    with pytest.raises(ds.ConfigError, match="fields = heat: expected pressure"):
        ds.measure(folder, POINTS, fields=["heat"])
    with pytest.raises(ds.ConfigError, match=r"points\[0\] = \[0.1, 0.2, 0.3\]"):
        ds.measure(folder, [[0.1, 0.2, 0.3]])
    with pytest.raises(OSError, match="not a run folder"):
        ds.measure(tmp_path, POINTS)
    with pytest.raises(ValueError, match="no points"):
        ds.measure(folder)
    assert "pressure" in repr(ds.load(folder).measure(POINTS))

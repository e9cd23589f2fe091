"""Driving the solver from Python: construction, stepping, state arrays, energies,
probes, snapshots, and agreement with the command line to the last bit."""

import os
import pathlib
import re
import signal
import subprocess
import threading
import time

import h5py
import numpy as np
import pytest

import deltasph as ds
from conftest import EXAMPLES, ROOT, example

STATE = ("positions", "velocities", "density", "pressure")


def assert_same_state(a, b):
    for name in STATE:
        x, y = getattr(a, name), getattr(b, name)
        assert np.array_equal(x, y), f"{name} differs"


def test_toml_and_dict_give_identical_runs():
    from_file = ds.Simulation.from_toml(EXAMPLES / "dam_break_2d.toml")
    from_dict = ds.Simulation(example("dam_break_2d"))
    from_file.step(15)
    from_dict.step(15)
    assert from_file.n_steps == from_dict.n_steps == 15
    assert from_file.time == from_dict.time
    assert_same_state(from_file, from_dict)


def cli_binary():
    """The sph-cli these tests run: $SPH_CLI when set (scripts/test.sh passes the one its
    Rust tests built, with the mpi feature, so that CI compiles it once), else a release
    build of this tree."""
    given = os.environ.get("SPH_CLI")
    if given:
        return pathlib.Path(given)
    subprocess.run(
        ["cargo", "build", "--release", "-q", "-p", "sph-cli"], cwd=ROOT, check=True
    )
    return ROOT / "target" / "release" / "sph-cli"


def test_python_run_equals_cli_bit_for_bit(tmp_path):
    """Same case, same 40 steps: every array of the CLI's last snapshot equals Python's."""
    text = (EXAMPLES / "dam_break_2d.toml").read_text()
    text = re.sub(r"^\[time\]$", "[time]\nmax_steps = 40", text, flags=re.M)
    case = tmp_path / "case.toml"
    case.write_text(text)
    out = tmp_path / "cli"
    subprocess.run(
        [cli_binary(), "run", case, "--out", out, "--quiet"], check=True, capture_output=True
    )
    last = sorted(out.glob("particles_*.h5"))[-1]
    sim = ds.Simulation.from_toml(case)
    sim.step(40)
    with h5py.File(last) as f:
        assert f.attrs["step"] == 40
        assert f.attrs["time"] == sim.time
        order = np.argsort(f["id"][:])
        d = sim.dimension
        np.testing.assert_array_equal(f["position"][:][order, :d], sim.positions)
        np.testing.assert_array_equal(f["velocity"][:][order, :d], sim.velocities)
        np.testing.assert_array_equal(f["density"][:][order], sim.density)
        np.testing.assert_array_equal(f["pressure"][:][order], sim.pressure)
        np.testing.assert_array_equal(f["kind"][:][order], sim.kind)


def test_state_arrays_shapes_and_units(coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    n, d = sim.n_particles, sim.dimension
    assert sim.positions.shape == (n, d) and sim.positions.dtype == np.float64
    assert sim.velocities.shape == (n, d)
    assert sim.density.shape == sim.pressure.shape == sim.mass.shape == (n,)
    assert sim.kind.dtype == np.uint8
    assert (sim.kind == 0).sum() == sim.n_fluid == 40 * 20
    # The floor under the column carries the hydrostatic pressure at its own depth,
    # extrapolated from the fluid (Adami et al. 2012), p_w = ρ0 g (H - y_w), in the
    # two layers within the kernel support (2h = 0.08 m) of the fluid.
    x, p = sim.positions, sim.pressure
    floor = (sim.kind == 1) & (x[:, 1] < 0) & (x[:, 1] > -0.06) & (x[:, 0] > 0.1) & (x[:, 0] < 1.0)
    assert floor.sum() > 50
    exact = 1000.0 * 9.81 * (0.6 - x[floor, 1])
    assert np.max(np.abs(p[floor] / exact - 1)) < 0.01
    assert sim.time == 0.0 and sim.n_steps == 0 and sim.dt == 0.0


def test_arrays_are_copies(coarse_dam_break):
    sim, twin = ds.Simulation(coarse_dam_break), ds.Simulation(coarse_dam_break)
    for name in STATE:
        a = getattr(sim, name)
        a[...] = 1e9
        assert not np.array_equal(getattr(sim, name), a)
    sim.step(5)
    twin.step(5)
    assert_same_state(sim, twin)


def test_rows_follow_particle_ids_across_list_rebuilds(coarse_dam_break):
    """The solver reorders particles by cell; rows must still track the same particle."""
    sim = ds.Simulation(coarse_dam_break)
    x0 = sim.positions
    sim.run(until=0.1)
    moved = np.linalg.norm(sim.positions - x0, axis=1)
    walls = sim.kind == 1
    assert np.all(moved[walls] == 0.0)
    # No particle travels farther than free fall allows in 0.1 s (plus the spacing).
    assert moved.max() < 0.5 * 9.81 * 0.1**2 * 2 + sim.spacing


def test_run_lands_on_until_and_honours_max_steps(coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    sim.run(until=0.0123)
    assert sim.time == pytest.approx(0.0123, rel=1e-12)
    coarse_dam_break["time"]["max_steps"] = 7
    capped = ds.Simulation(coarse_dam_break)
    capped.run()
    assert capped.n_steps == 7


def test_step_is_exact(coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    sim.step()
    sim.step(9)
    assert sim.n_steps == 10
    assert sim.dt > 0.0


def test_energies_and_budget(coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    e = sim.energies()
    assert set(e) == {
        "kinetic", "potential", "internal", "total", "bodies", "dissipated", "moving_work",
        "forcing_work",
    }
    assert e["dissipated"] is None and e["moving_work"] is None and e["bodies"] == 0.0
    # E_p of the column about y = 0: ρ0 g Σ V y = ρ0 g (2H·H) H/2, to lattice accuracy.
    assert e["potential"] == pytest.approx(1000 * 9.81 * 1.2 * 0.6 * 0.3, rel=0.02)
    coarse_dam_break["diagnostics"]["energy_budget"] = True
    sim = ds.Simulation(coarse_dam_break)
    e0 = sim.energies()
    assert e0["dissipated"] == 0.0
    sim.run(until=0.3)
    e = sim.energies()
    assert e["kinetic"] > 0.0 and e["dissipated"] > 0.0
    # each energy against its formula (docs/theory.md §10) from the state arrays, in the
    # fluid: ½Σm|u|², -Σm g·x and Σm c0² [ln(ρ/ρ0) + ρ0/ρ - 1] (the linear EOS)
    fluid = sim.kind == ds.FLUID
    m, u, x, rho = sim.mass[fluid], sim.velocities[fluid], sim.positions[fluid], sim.density[fluid]
    rho0, c0 = sim.reference_density, sim.sound_speed
    assert e["kinetic"] == pytest.approx(0.5 * np.sum(m * np.sum(u * u, axis=1)), rel=1e-10)
    assert e["potential"] == pytest.approx(np.sum(m * 9.81 * x[:, 1]), rel=1e-10)
    internal = np.sum(m * c0**2 * (np.log(rho / rho0) + rho0 / rho - 1.0))
    assert e["internal"] == pytest.approx(internal, rel=1e-6)
    # docs/theory.md §10: E_k + E_p + E_c + dissipated is conserved. The Rust suite closes
    # the 3D budget within 2% of the dissipated energy; the same bound holds here.
    residual = e["total"] + e["dissipated"] - e0["total"]
    assert abs(residual) < 0.02 * e["dissipated"], (residual, e["dissipated"])


def test_probe_pressure_matches_hydrostatics():
    sim = ds.Simulation(example("hydrostatic_2d"))
    depth = np.array([0.25, 0.5, 0.75])
    points = np.column_stack([np.full(3, 1.0), 1.0 - depth])
    p = sim.probe_pressure(points)
    assert p.shape == (3,)
    # Shepard interpolation of a linear field is exact up to the lattice's first moment.
    np.testing.assert_allclose(p, 1000 * 9.81 * depth, rtol=0.01)
    assert sim.probe_pressure([1.0, 0.5]).shape == (1,)
    # a dry point inside the domain reads NaN; one outside it is refused
    assert np.isnan(sim.probe_pressure([[1.0, 1.8]])[0])
    with pytest.raises(ValueError, match="expected a point inside the domain"):
        sim.probe_pressure([[10.0, 10.0]])
    # so is one deeper than the kernel support (2h = 0.1 m) inside the floor, 6 layers
    # of 0.025 m thick: fluid can never reach it
    case = example("hydrostatic_2d")
    case["tank"][0]["layers"] = 6
    sim = ds.Simulation(case)
    assert np.isnan(sim.probe_pressure([[1.0, -0.09]])[0])
    with pytest.raises(ValueError, match=r"points\[1\] .* kernel support inside tank\[0\]"):
        sim.probe_pressure([[1.0, 0.5], [1.0, -0.12]])


def test_set_velocities_and_density(coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    fluid = sim.kind == 0
    u = np.zeros((sim.n_particles, 2))
    u[fluid, 0] = 0.3
    sim.set_velocities(u)
    np.testing.assert_array_equal(sim.velocities, u)
    kinetic = 0.5 * np.sum(sim.mass[fluid] * 0.3**2)
    assert sim.energies()["kinetic"] == pytest.approx(kinetic, rel=1e-12)
    rho = sim.density
    rho[fluid] = 1001.0
    sim.set_density(rho)
    assert np.all(sim.density[fluid] == 1001.0)
    assert np.all(sim.pressure[fluid] == pytest.approx(sim.sound_speed**2 * 1.0))
    sim.step(3)
    assert sim.velocities[fluid, 0].mean() > 0.2


def test_three_dimensional_case():
    config = example("dam_break_3d", particles__spacing=0.05)
    sim = ds.Simulation(config)
    assert sim.dimension == 3
    assert sim.positions.shape == (sim.n_particles, 3)
    sim.step(2)
    assert sim.n_steps == 2


def test_write_snapshot(tmp_path, coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    sim.step(3)
    path = tmp_path / "state.h5"
    index = sim.write_snapshot(path)
    assert pathlib.Path(index) == tmp_path / "state.xmf"
    assert "state.h5:/position" in pathlib.Path(index).read_text()
    with h5py.File(path) as f:
        order = np.argsort(f["id"][:])
        np.testing.assert_array_equal(f["position"][:][order, :2], sim.positions)
        assert f["position"].shape == (sim.n_particles, 3)
        assert f.attrs["step"] == 3 and f.attrs["dimension"] == 2
    before = path.read_bytes()
    with pytest.raises(OSError, match="file exists"):
        sim.write_snapshot(path)
    assert path.read_bytes() == before
    sim.step()
    sim.write_snapshot(path, overwrite=True)
    with h5py.File(path) as f:
        assert f.attrs["step"] == 4
        assert f.attrs["creator"].startswith("deltasph")
    assert not list(tmp_path.glob("*.partial"))


def test_write_snapshot_never_overwrites_another_programs_files(tmp_path, coarse_dam_break):
    """overwrite=True replaces deltasph's own snapshots only: an HDF5 file or an .xmf
    index of someone else's is kept, byte for byte."""
    sim = ds.Simulation(coarse_dam_break)
    theirs = tmp_path / "results.h5"
    with h5py.File(theirs, "w") as f:
        f["measured"] = np.arange(5.0)
    before = theirs.read_bytes()
    with pytest.raises(OSError, match="not written by deltasph"):
        sim.write_snapshot(theirs, overwrite=True)
    assert theirs.read_bytes() == before
    index = tmp_path / "view.xmf"
    index.write_text("<Xdmf>my own index</Xdmf>")
    with pytest.raises(OSError, match="not written by deltasph"):
        sim.write_snapshot(tmp_path / "view.h5", overwrite=True)
    assert index.read_text() == "<Xdmf>my own index</Xdmf>"
    assert not (tmp_path / "view.h5").exists()


def test_instability_raises_with_time_step_particle(coarse_dam_break, tmp_path):
    coarse_dam_break["fluid"]["sound_speed"] = 2.0  # far below sqrt(2 g H) = 3.4 m/s
    sim = ds.Simulation(coarse_dam_break)
    with pytest.raises(ds.InstabilityError) as info:
        sim.run(until=1.0)
    err = info.value
    assert 0.0 < err.time < 1.0 and err.step == sim.n_steps and err.time == sim.time
    assert 0 <= err.particle < sim.n_particles
    assert str(err).startswith("unstable at t = ")
    # The simulation says it failed, refuses to go on, and keeps the state at which it
    # stopped for inspection.
    assert sim.failed == str(err) and "failed" in repr(sim)
    with pytest.raises(ValueError, match="the stability guard stopped this simulation"):
        sim.step()
    sim.write_snapshot(tmp_path / "blown.h5")
    assert (tmp_path / "blown.h5").exists()


def test_a_healthy_simulation_has_not_failed(coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    sim.step(2)
    assert sim.failed is None and "failed" not in repr(sim)


def test_fluid_leaving_the_default_domain_warns_once_with_its_mass():
    # a free block thrown along +x, no walls and no [domain]: it leaves the default box
    # (its own box widened by half, at least 10 spacings) within 0.1 s at 5 m/s
    config = {
        "dimension": 2,
        "particles": {"spacing": 0.02},
        "fluid": {"density": 1000.0, "sound_speed": 50.0},
        "fluid_block": [{"lo": [0.0, 0.0], "hi": [0.2, 0.2], "velocity": [5.0, 0.0]}],
        "time": {"end": 0.15},
    }
    sim = ds.Simulation(config)
    with pytest.warns(UserWarning, match="left the default domain") as caught:
        sim.run()
    assert len([w for w in caught if "default domain" in str(w.message)]) == 1
    assert sim.n_removed == 100
    assert sim.removed_mass == pytest.approx(100 * 1000.0 * 0.02**2, rel=1e-12)


def test_progress_callback(coarse_dam_break):
    seen = []
    sim = ds.Simulation(coarse_dam_break)
    sim.run(until=0.05, progress=lambda t, n: seen.append((t, n)))
    assert seen and seen[-1] == (sim.time, sim.n_steps)
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))


def test_progress_bar_without_tqdm_prints_to_stderr(coarse_dam_break, capsys):
    sim = ds.Simulation(coarse_dam_break)
    sim.run(until=0.01, progress=True)
    assert "deltasph" in capsys.readouterr().err


def test_interpreter_released_while_running():
    """A pure-Python loop in another thread keeps running while the solver works."""
    sim = ds.Simulation(example("dam_break_2d"))
    counter, done = [0], threading.Event()

    def count():
        while not done.is_set():
            counter[0] += 1

    worker = threading.Thread(target=count)
    worker.start()
    start = time.perf_counter()
    sim.run(until=0.03)
    elapsed = time.perf_counter() - start
    done.set()
    worker.join()
    # The same loop alone, for its rate on this machine.
    done.clear()
    alone = [0]

    def count_alone():
        while not done.is_set():
            alone[0] += 1

    worker = threading.Thread(target=count_alone)
    worker.start()
    time.sleep(0.2)
    done.set()
    worker.join()
    # Released, the loop keeps most of its own rate beside the solver's threads
    # (measured: 84% on 2 cores); held, it would run only between the run's slices.
    assert elapsed > 0.05 and counter[0] / elapsed > 0.1 * alone[0] / 0.2, (
        counter[0] / elapsed, alone[0] / 0.2)


def test_ctrl_c_stops_between_steps(ctrl_c):
    sim = ds.Simulation(example("dam_break_2d"))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        sim.run(until=100.0)
    assert time.perf_counter() - start < 5.0
    assert 0.0 < sim.time < 100.0
    steps = sim.n_steps
    sim.step()
    assert sim.n_steps == steps + 1 and np.all(np.isfinite(sim.positions))


def test_repr_and_help():
    sim = ds.Simulation(example("hydrostatic_2d"))
    assert repr(sim).startswith("Simulation('hydrostatic_2d', 2D")
    assert "TOML" in ds.Simulation.from_toml.__doc__
    assert "(N, D)" in ds.Simulation.positions.__doc__
    assert "hydrostatic_2d" in sim.to_toml()


def test_free_surface_detection(tmp_path):
    """The top layer of the hydrostatic tank is the free surface; walls and bulk are not."""
    config = example("hydrostatic_2d", particles__spacing=0.05)
    config["diagnostics"]["free_surface"] = True
    sim = ds.Simulation(config)
    fs = sim.free_surface()
    fluid = sim.kind == ds.FLUID
    y = sim.positions[:, 1]
    top = fluid & (y > 1.0 - sim.spacing)
    assert np.all(fs["on_surface"][top])
    assert not np.any(fs["on_surface"][fluid & (y < 1.0 - 2 * sim.spacing)])
    assert not np.any(fs["on_surface"][~fluid])
    x = sim.positions[:, 0]
    flat = top & (x > 3 * sim.spacing) & (x < 2.0 - 3 * sim.spacing)  # away from the walls
    np.testing.assert_allclose(fs["normal"][flat], np.tile([0.0, 1.0], (flat.sum(), 1)),
                               atol=1e-9)
    sim.write_snapshot(tmp_path / "s.h5")
    with h5py.File(tmp_path / "s.h5") as f:
        order = np.argsort(f["id"][:])
        np.testing.assert_array_equal(f["free_surface"][:][order], fs["on_surface"])
    assert "free_surface" in (tmp_path / "s.xmf").read_text()


def test_wall_crossings_through_the_impact(coarse_dam_break):
    """The dam break at H/Δx = 20 through the impact on the right wall (t* ≈ 2.5) and
    the run-up: no fluid particle inside a wall at any step."""
    sim = ds.Simulation(coarse_dam_break)
    worst = 0
    while sim.time < 0.8:
        sim.step(10)
        worst = max(worst, sim.wall_crossings())
    assert isinstance(worst, int) and worst == 0


def test_loads_name_each_body_and_carry_the_weight():
    """The hydrostatic tank (H = 1 m, 2 m wide, H/Δx = 20) at t·sqrt(g/H) = 10: its
    vertical load is the water's weight ρ0 g H L per unit width (measured 1.004, the
    water 0.25% denser than ρ0), its side thrusts cancel."""
    sim = ds.Simulation(example("hydrostatic_2d", particles__spacing=0.05))
    sim.run(until=3.19, progress=False)
    loads = sim.loads()
    assert list(loads) == ["tank0"]
    tank = loads["tank0"]
    assert tank["pressure"].shape == (2,) and tank["moment"].shape == (3,)
    assert not tank["viscous"].any()  # free-slip walls
    weight = 1000 * 9.81 * 1.0 * 2.0
    assert -tank["pressure"][1] == pytest.approx(weight, rel=0.01)
    assert abs(tank["pressure"][0]) < 1e-3 * weight


def test_shapes_from_python():
    """A polygon of fluid in a tank, from a dict: the lattice points of the triangle
    (a right isosceles one, legs of 20 spacings: 210 points on or inside it), and the
    polygon wall's load named after it."""
    config = {
        "dimension": 2,
        "particles": {"spacing": 0.05},
        "fluid": {"density": 1000.0, "gravity": [0.0, -9.81]},
        "shape": [
            {"role": "fluid", "polygon": [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]},
            {"role": "wall", "name": "floor",
             "polygon": [[-0.2, -0.2], [1.2, -0.2], [1.2, 0.0], [-0.2, 0.0]]},
        ],
        "time": {"end": 0.01},
    }
    sim = ds.Simulation(config)
    assert sim.n_fluid == 210
    assert list(sim.loads()) == ["floor"]
    config["shape"][0]["polygon"] = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]
    with pytest.raises(ValueError, match=r"^shape\[0\]\.polygon = edges 0 and 2 cross"):
        ds.Simulation(config)


def test_prescribed_motion_moves_the_walls_and_reports_the_body():
    case = example("validation/stokes_plate", particles__spacing=0.01)
    case["time"]["end"] = 0.3
    sim = ds.Simulation(case)
    x0 = sim.positions
    sim.run(until=0.3)
    u_amp, omega = 0.1, 2 * np.pi
    plate = sim.body_motions()["plate"]
    # the pivot (the origin) moves by (U/ω) sin ωt along x, at U cos ωt
    np.testing.assert_allclose(plate["position"], [u_amp / omega * np.sin(omega * 0.3), 0.0], atol=1e-15)
    np.testing.assert_allclose(plate["velocity"], [u_amp * np.cos(omega * 0.3), 0.0], atol=1e-15)
    assert plate["rotation"].shape == (1,) and plate["rotation"][0] == 0.0
    assert list(sim.body_motions()) == ["plate"]
    # its wall particles moved rigidly with it (along the periodic x, wrapped), the lid not
    wall = sim.kind == ds.WALL
    moved = sim.positions[wall] - x0[wall]
    shift = u_amp / omega * np.sin(omega * 0.3)
    on_plate = x0[wall][:, 1] < 0
    np.testing.assert_allclose(np.mod(moved[on_plate, 0] - shift + 0.1, 0.2) - 0.1, 0.0, atol=1e-12)
    assert np.all(moved[~on_plate] == 0.0)
    np.testing.assert_allclose(sim.velocities[wall][on_plate, 0], u_amp * np.cos(omega * 0.3), rtol=1e-12)


def test_a_motion_table_from_numpy_drives_the_plate():
    # the plate's motion as rows [t, x, y] sampled every 0.02 s from (U/ω) sin ωt: the
    # spline through them moves the plate as the expression does, to the spline's error
    # (O(Δt⁴) ≈ 1e-8 m in position, O(Δt²) ≈ 1e-4 U in velocity)
    u_amp, omega = 0.1, 2 * np.pi
    t = np.arange(0.0, 0.42, 0.02)
    case = example("validation/stokes_plate", particles__spacing=0.01, time__end=0.3)
    prescribed = case["wall"][0]["prescribed"]
    del prescribed["displacement"]
    prescribed["table"] = np.c_[t, u_amp / omega * np.sin(omega * t), 0 * t]
    sim = ds.Simulation(case)
    sim.run(until=0.3)
    plate = sim.body_motions()["plate"]
    np.testing.assert_allclose(plate["position"][0], u_amp / omega * np.sin(omega * 0.3), atol=1e-7)
    np.testing.assert_allclose(plate["velocity"][0], u_amp * np.cos(omega * 0.3), atol=2e-5)
    # rows that go back in time are refused in one line naming the key
    prescribed["table"] = np.c_[t[::-1], t, t]
    with pytest.raises(ValueError, match=r"^wall\[0\]\.prescribed\.table = 21 rows: expected times that increase"):
        ds.Simulation(case)


def test_a_free_body_falls_onto_the_water_and_reports_its_state():
    # the floating box released 2 cm above its draft: it falls and is caught by the water
    case = example(
        "floating_box_2d", particles__spacing=0.02, diagnostics__energy_budget=True
    )
    case["shape"][0]["box"] = {"lo": [0.4, 0.27], "hi": [0.6, 0.37]}
    sim = ds.Simulation(case)
    e0 = sim.energies()
    start = sim.body_motions()["box"]
    np.testing.assert_allclose(start["position"], [0.5, 0.32], atol=1e-9)
    assert np.all(start["velocity"] == 0.0)
    sim.run(until=0.1)
    box = sim.body_motions()["box"]
    # 3 cm of its 5 cm draft under water: the net weight, 2/5 of its weight, pulls it
    # down at less than (2/5) g (the water's added mass slows it), to t = 0.1 s
    assert -0.5 * 0.4 * 9.81 * 0.1**2 < box["position"][1] - 0.32 < -0.002
    assert -0.4 * 9.81 * 0.1 < box["velocity"][1] < -0.02
    assert abs(box["position"][0] - 0.5) < 1e-9 and abs(box["rotation"][0]) < 1e-9
    # the box gave the water energy through the wall terms alone: fluid + box + what was
    # dissipated stays at its start within 1% of what the box lost (m g Δy = 10 kg ×
    # 9.81 m/s² × 0.02 m less its kinetic energy; the Rust suite closes to 0.5% of kz0²/2)
    e = sim.energies()
    lost = e0["bodies"] - e["bodies"]
    assert lost > 0.5
    closure = e["total"] + e["bodies"] + e["dissipated"] - (e0["total"] + e0["bodies"])
    assert abs(closure) < 0.01 * lost, (closure, lost)
    # its walls did on the water the work the box lost
    assert abs(e["moving_work"] - lost) < 0.01 * lost, (e["moving_work"], lost)


def test_a_wave_maker_moves_as_theory_says_and_gauges_read_the_surface(tmp_path):
    case = example("wave_flume_2d", particles__spacing=0.05, time__end=0.2,
                   time__output_interval=0.1, diagnostics__interval=0.05)
    case["wall"][0]["lo"] = [-0.25, 0.0]  # the kernel support thick at this spacing
    sim = ds.Simulation(case)
    theory = ds.regular_wave(0.04, 1.625, 0.5)
    assert abs(theory["kd"] - 1.0) < 1e-3
    # after the two-period ramp the piston moves by S/2 sin ωt + X2 sin 2ωt (Madsen)
    omega = 2 * np.pi / 1.625
    t = np.array([0.0, 3.5, 4.0, 7.7])
    paddle = sim.prescribed_motion(t)["paddle"]
    expected = 0.5 * theory["piston_stroke"] * np.sin(omega * t) \
        + theory["madsen_second_order"] * np.sin(2 * omega * t)
    expected[0] = 0.0
    np.testing.assert_allclose(paddle["position"][:, 0], expected, atol=1e-15)
    assert paddle["position"].shape == (4, 2) and np.all(paddle["position"][:, 1] == 0.0)
    assert abs(theory["piston_stroke"] / 0.04 - 1 / 0.9818) < 1e-3  # Biesel at kd = 1
    # still water at its level, to a hundredth of the spacing
    eta = sim.wave_elevation([3.0, 9.0])
    assert np.all(np.abs(eta) < 5e-4), eta
    with pytest.raises(ValueError, match=r"^positions\[0\] = \[1.0, 2.0\]: expected 1 coordinate"):
        sim.wave_elevation([[1.0, 2.0]])
    # velocity probes: still water at rest, a point above the water dry (NaN)
    u = sim.probe_velocity([[3.0, 0.25], [3.0, 0.75]])
    assert u.shape == (2, 2) and np.all(u[0] == 0.0) and np.all(np.isnan(u[1])), u
    sim.run(out=tmp_path / "flume")
    run = ds.load(tmp_path / "flume")
    assert {"g1_elevation", "r3_elevation"} <= set(run.series)
    assert np.all(np.abs(run.series["g1_elevation"]) < 5e-4)
    from deltasph import plot
    figures = plot.series(run)
    lines = figures["gauges"].axes[0].get_lines()
    crest = [ln for ln in lines if ln.get_label().startswith("target crest")][0]
    np.testing.assert_allclose(crest.get_ydata()[0], 0.02 + theory["bound_second_harmonic"])

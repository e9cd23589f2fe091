"""Bad input raises the right exception with the command line's one-line message,
and never crashes the interpreter."""

import numpy as np
import pytest

import deltasph as ds
from conftest import example


def test_unknown_key_is_a_key_error_naming_the_key():
    config = example("hydrostatic_2d")
    config["fluid"]["viscosity"] = 1e-3
    with pytest.raises(ds.ConfigKeyError) as info:
        ds.Simulation(config)
    assert isinstance(info.value, KeyError) and isinstance(info.value, ValueError)
    assert str(info.value).startswith("fluid.viscosity = 0.001: unknown field `viscosity`")


def test_a_section_of_the_wrong_type_is_named():
    config = example("hydrostatic_2d")
    config["particles"] = [1, 2]
    with pytest.raises(ds.ConfigError, match=r"^particles = \[1, 2\]: expected a table"):
        ds.Simulation(config)
    config = example("hydrostatic_2d")
    config["tank"] = {"lo": [0.0, 0.0], "hi": [1.0, 1.0]}
    with pytest.raises(ds.ConfigError, match=r"^tank = .*: expected an array of tables"):
        ds.Simulation(config)


def test_missing_key_names_it():
    config = example("hydrostatic_2d")
    del config["particles"]["spacing"]
    with pytest.raises(KeyError, match=r"^particles.spacing = \(missing\): missing field"):
        ds.Simulation(config)


def test_negative_spacing_is_a_value_error():
    with pytest.raises(ValueError) as info:
        ds.Simulation(example("hydrostatic_2d", particles__spacing=-0.01))
    assert type(info.value) is ds.ConfigError
    assert str(info.value) == "particles.spacing = -0.01: expected a positive number"


def test_same_message_as_toml(tmp_path):
    text = (tmp_path / "c.toml")
    src = (example.__globals__["EXAMPLES"] / "hydrostatic_2d.toml").read_text()
    text.write_text(src.replace("spacing = 0.025", "spacing = -0.01"))
    with pytest.raises(ds.ConfigError) as from_file:
        ds.Simulation.from_toml(text)
    with pytest.raises(ds.ConfigError) as from_dict:
        ds.Simulation(example("hydrostatic_2d", particles__spacing=-0.01))
    assert str(from_file.value) == str(from_dict.value)


@pytest.mark.parametrize(
    "key, value, fragment",
    [
        ("particles__spacing", "fine", "particles.spacing = \"fine\": invalid type"),
        ("scheme__diffusion", "magic", "scheme.diffusion = \"magic\": unknown variant"),
        ("fluid__gravity", [0.0, -9.81, 0.0], "fluid.gravity"),
        ("particles__h_over_dx", float("nan"), "particles.h_over_dx = NaN"),
        ("time__end", 1j, "time.end = 1j: expected a number"),
        ("output__compression", 10,
         "output.compression = 10: expected a deflate level from 0 (none) to 9"),
        ("output__compression", -1, "output.compression = -1"),
    ],
)
def test_bad_values(key, value, fragment):
    with pytest.raises(ds.ConfigError, match=None) as info:
        ds.Simulation(example("hydrostatic_2d", **{key: value}))
    assert fragment in str(info.value)
    assert "\n" not in str(info.value)


def test_numpy_values_are_accepted():
    config = example("hydrostatic_2d")
    config["fluid"]["gravity"] = np.array([0.0, -9.81])
    config["particles"]["spacing"] = np.float64(0.025)
    config["tank"][0]["layers"] = np.int64(4)
    assert ds.Simulation(config).n_fluid == 80 * 40


def test_config_must_be_a_dict():
    with pytest.raises(TypeError, match="expected a dict"):
        ds.Simulation("examples/hydrostatic_2d.toml")
    with pytest.raises(ds.ConfigError, match="expected string keys"):
        ds.Simulation({1: 2})


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such case file"):
        ds.Simulation.from_toml(tmp_path / "absent.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("dimension = \n")
    with pytest.raises(ds.ConfigError, match=r"bad.toml: TOML syntax at line 1, column"):
        ds.Simulation.from_toml(bad)


@pytest.fixture(scope="module")
def sim():
    return ds.Simulation(example("hydrostatic_2d", particles__spacing=0.05))


def test_set_velocities_checks(sim):
    n = sim.n_particles
    with pytest.raises(ValueError, match=rf"shape \(3, 2\), expected \({n}, 2\)"):
        sim.set_velocities(np.zeros((3, 2)))
    with pytest.raises(ValueError, match=rf"expected \({n}, 2\)"):
        sim.set_velocities(np.zeros((n, 3)))
    with pytest.raises(TypeError, match="dtype float32, expected float64"):
        sim.set_velocities(np.zeros((n, 2), dtype=np.float32))
    with pytest.raises(TypeError, match="got list, expected a numpy.ndarray"):
        sim.set_velocities([[0.0, 0.0]] * n)
    u = np.zeros((n, 2))
    u[5, 1] = np.nan
    with pytest.raises(ValueError, match="row 5 holds a non-finite value"):
        sim.set_velocities(u)
    wall = int(np.flatnonzero(sim.kind == 1)[0])
    u = np.zeros((n, 2))
    u[wall] = 1.0
    with pytest.raises(ValueError, match=f"row {wall} = \\[1.0, 1.0\\] is a wall particle"):
        sim.set_velocities(u)
    # Nothing was changed by the refused calls.
    assert np.all(sim.velocities == 0.0)


def test_a_sliding_lid_keeps_its_velocity_through_a_round_trip():
    """The cavity's lid rows come back at the lid speed, are accepted back unchanged,
    and cannot be stopped (or sped up) from Python."""
    sim = ds.Simulation(example("validation/cavity", particles__spacing=0.05))
    u = sim.velocities
    lid = (sim.kind == ds.WALL) & (u[:, 0] != 0.0)
    assert lid.sum() > 0 and np.allclose(u[lid], [1.0, 0.0])
    fluid = sim.kind == ds.FLUID
    u[fluid, 0] = 0.25
    sim.set_velocities(u)
    assert np.array_equal(sim.velocities, u)
    row = int(np.flatnonzero(lid)[0])
    u[row] = 0.0
    with pytest.raises(ValueError, match=rf"row {row} = \[0.0, 0.0\] is a wall particle, "
                                         r"expected its velocity \[1.0, 0.0\]"):
        sim.set_velocities(u)
    sim.step()
    assert np.allclose(sim.velocities[lid], [1.0, 0.0])


def test_set_density_checks(sim):
    rho = sim.density
    rho[0] = -1.0
    with pytest.raises(ValueError, match="row 0 = -1, expected a positive density"):
        sim.set_density(rho)
    with pytest.raises(TypeError, match="dtype int64"):
        sim.set_density(np.ones(sim.n_particles, dtype=np.int64))


def test_probe_and_run_checks(sim):
    with pytest.raises(ValueError, match=r"expected \(M, 2\)"):
        sim.probe_pressure([[1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match="not an array of numbers"):
        sim.probe_pressure([["a", "b"]])
    with pytest.raises(ValueError, match="until = NaN: expected a finite time"):
        sim.run(until=float("nan"))
    with pytest.raises(TypeError, match="progress = 3"):
        sim.run(until=0.0, progress=3)
    with pytest.raises(ValueError, match=r"n = -1: expected a number of steps, 0 or more"):
        sim.step(-1)
    with pytest.raises(ValueError, match=r"points\[1\] = \[50\.0, 0\.1\]: expected a point inside "
                                         r"the domain"):
        sim.probe_pressure([[0.5, 0.1], [50.0, 0.1]])


def test_run_cannot_go_back_in_time():
    sim = ds.Simulation(example("hydrostatic_2d", particles__spacing=0.05))
    sim.step(3)
    with pytest.raises(ValueError, match=r"until = 0 s: expected a time no earlier than "
                                         r"the simulation's, t = 0\.0\d+ s"):
        sim.run(until=0.0)
    assert sim.n_steps == 3


def test_step_count_that_would_overflow_is_refused(sim):
    sim.step(2)
    with pytest.raises(ValueError, match=r"n = 18446744073709551615: expected a step count below"):
        sim.step(2**64 - 1)
    assert sim.n_steps == 2

"""The validation runner's bookkeeping (examples/validation/run_all.py): the cost
prediction behind the per-run cap, and the rows and signals that --resume reads back."""

import math
import sys
from types import SimpleNamespace

import numpy as np

from conftest import EXAMPLES

sys.path.insert(0, str(EXAMPLES / "validation"))
import run_all  # noqa: E402


def test_predicted_wall_time_grows_with_particles_times_steps():
    previous = {"wall_s": 2.0, "resolution": 20.0}
    # 2D: particles ∝ n², steps ∝ n, so doubling n costs 8×; 3D costs 16×.
    assert math.isclose(run_all.predicted_wall(SimpleNamespace(dim=2), previous, 40), 16.0)
    assert math.isclose(run_all.predicted_wall(SimpleNamespace(dim=3), previous, 40), 32.0)


def test_resume_reads_back_rows_and_signals_as_written(tmp_path):
    rows = [{
        "case": "dam_break", "diffusion": "δ-SPH", "integrator": "RK4", "resolution": 15,
        "spacing": 0.04, "particles": 450, "steps": 1400, "wall_s": 1.5,
        "particle_steps_per_s": 420000, "stable": True, "error": 0.18, "details": "a=1",
    }, {
        "case": "hydrostatic", "diffusion": "SPH", "integrator": "SE2", "resolution": 12.5,
        "spacing": 0.08, "particles": 200, "steps": 90, "wall_s": 0.2,
        "particle_steps_per_s": 90000, "stable": False, "error": math.nan, "details": "",
    }]
    signal = (np.array([0.01, 0.02]), np.array([0.0, 0.25]))
    run_all.write_csv(tmp_path, rows)
    run_all.save_signals(tmp_path, {("dam_break", "δ-SPH", "RK4", 15.0): signal})
    done, signals = run_all.earlier_results(tmp_path)
    assert set(done) == {("dam_break", "δ-SPH", "RK4", 15.0),
                         ("hydrostatic", "SPH", "SE2", 12.5)}
    first = done[("dam_break", "δ-SPH", "RK4", 15.0)]
    assert first == {**rows[0], "resolution": 15.0}
    second = done[("hydrostatic", "SPH", "SE2", 12.5)]
    assert second["stable"] is False and math.isnan(second["error"])
    t, p = signals[("dam_break", "δ-SPH", "RK4", 15.0)]
    assert np.array_equal(t, signal[0]) and np.array_equal(p, signal[1])

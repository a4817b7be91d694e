"""strata.explore.run: a short closed-loop exploration of the shipped room; the explored share
grows, the flown path is continuous, starts at the start, keeps the robot's radius from the
surfaces the map holds, and its length is the library's path length."""
import numpy as np
import pytest

import strata

ROBOT_RADIUS_M = 0.3  # explore::RobotConfig's default
VOXEL_M = 0.1
STEP_M = 0.05  # one motion step (0.05 s) at the robot's 1 m/s at most


@pytest.fixture(scope="module", params=["history", "nbvp"])
def run(request):
    return strata.explore.run("room", planner=request.param, time_limit_s=20.0,
                              voxel_size_m=VOXEL_M, eval_period_s=2.0)


def test_the_explored_share_grows_over_time(run):
    curve = run.curve
    assert curve.shape[1] == 4 and curve.shape[0] >= 5
    assert (np.diff(curve[:, 0]) > 0).all(), "simulated time increases"
    assert (np.diff(curve[:, 1]) >= -1e-9).all(), "the explored share never shrinks"
    assert curve[-1, 1] == pytest.approx(run.explored_fraction)
    assert run.explored_fraction > curve[0, 1] + 0.2, "the flight saw more than its start"
    assert run.stop_reason in ("time limit", "target", "no gain")
    assert run.planning_steps > 0 and run.reachable_voxels > 0


def test_the_flown_path_is_continuous_and_keeps_clear_of_the_map(run):
    flown = run.flown
    assert flown.ndim == 2 and flown.shape[1] == 3 and flown.shape[0] == run.flown_time_s.shape[0]
    assert np.allclose(flown[0], run.start, atol=1e-6)
    steps = np.linalg.norm(np.diff(flown, axis=0), axis=1)
    assert steps.max() <= STEP_M + 1e-3
    assert steps.sum() == pytest.approx(run.path_length_m, rel=1e-4)
    assert run.curve[-1, 2] == pytest.approx(run.path_length_m, rel=1e-4)
    assert run.path_length_m > 1.0, "it flew"
    assert run.collisions == 0 and run.min_clearance_m >= ROBOT_RADIUS_M
    surface = run.mesh.vertices.astype(np.float64)
    assert surface.shape[0] > 1000
    for p in flown[::10]:
        # The mapped surface is within a voxel of the true one the clearance is measured to.
        assert np.linalg.norm(surface - p, axis=1).min() > ROBOT_RADIUS_M - VOXEL_M


def test_bad_input_is_refused_by_name():
    with pytest.raises(strata.InputError, match="'history' or 'nbvp'"):
        strata.explore.run("room", planner="frontier")
    with pytest.raises(strata.InputError, match="nowhere"):
        strata.explore.run("nowhere")
    with pytest.raises(strata.InputError, match="start"):
        strata.explore.run("room", start=(0.0, 0.0))

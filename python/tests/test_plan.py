"""strata.plan on a Mapper's ESDF: a wall with a door, fused from synthetic depth, crossed through
the door by every planner of the library; endpoints in the wall or a planner that does not exist
refused by name."""
import numpy as np
import pytest

import strata

WALL_Z, BACK_Z = 2.0, 4.0      # the wall and the wall seen through the door (camera at the origin)
DOOR_X = (0.3, 0.9)            # the door's sides on the wall, over the whole image's height
RADIUS_M = 0.1
START, GOAL = (-0.6, 0.0, 1.0), (1.2, 0.0, 3.3)  # in front of the wall / behind it, off the door


@pytest.fixture(scope="module")
def mapper():
    width, height, f = 64, 48, 30.0
    intrinsics = strata.CameraIntrinsics(width, height, f, f, width / 2 - 0.5, height / 2 - 0.5)
    v, u = np.mgrid[0:height, 0:width]
    x_on_wall = WALL_Z * (u - intrinsics.cx) / f
    door = (x_on_wall > DOOR_X[0]) & (x_on_wall < DOOR_X[1])
    depth = np.where(door, BACK_Z, WALL_Z).astype(np.float32)
    config = strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05, allocate_free_space=True),
                                 esdf=True)
    m = strata.Mapper(config)
    for _ in range(3):
        m.integrate(depth, intrinsics, np.eye(4))
    m.update_esdf()
    return m


@pytest.mark.parametrize("planner", ["grid", "topo", "rrt"])
def test_every_planner_goes_through_the_door(mapper, planner):
    straight = np.array([START, GOAL])
    assert not mapper.is_path_free(straight, RADIUS_M), "the wall blocks the straight line"
    result = strata.plan.plan(mapper, START, GOAL, planner=planner, radius_m=RADIUS_M,
                              time_budget_s=2.0)
    assert result.success, result.message
    path = result.path
    assert path.dtype == np.float64 and path.ndim == 2 and path.shape[1] == 3
    assert np.allclose(path[0], START, atol=1e-6) and np.allclose(path[-1], GOAL, atol=1e-6)
    assert mapper.is_path_free(path, RADIUS_M)
    assert result.length_m > np.linalg.norm(np.subtract(GOAL, START))
    assert np.isclose(result.length_m, np.linalg.norm(np.diff(path, axis=0), axis=1).sum(),
                      rtol=1e-5)
    assert result.min_clearance_m >= RADIUS_M - 0.05  # sampled every half voxel
    # Where the path crosses the wall's plane, it is inside the door with the robot's room.
    i = int(np.argmax(path[:, 2] >= WALL_Z))
    a, b = path[i - 1], path[i]
    x = a[0] + (b[0] - a[0]) * (WALL_Z - a[2]) / (b[2] - a[2])
    assert DOOR_X[0] + RADIUS_M - 0.05 <= x <= DOOR_X[1] - RADIUS_M + 0.05, path


def test_bad_endpoints_and_planners_are_refused_by_name(mapper):
    with pytest.raises(strata.InputError, match="start.*collision"):
        strata.plan.plan(mapper, (0.0, 0.0, WALL_Z), GOAL, radius_m=RADIUS_M)
    with pytest.raises(strata.InputError, match="goal.*outside the map"):
        strata.plan.plan(mapper, START, (0.0, 0.0, 40.0), radius_m=RADIUS_M)
    with pytest.raises(strata.InputError, match="unknown planner"):
        strata.plan.plan(mapper, START, GOAL, planner="dijkstra", radius_m=RADIUS_M)
    with pytest.raises(strata.InputError, match="3 numbers"):
        strata.plan.plan(mapper, (0.0, 0.0), GOAL)
    with pytest.raises(strata.InputError, match="'occupied' or 'free'"):
        strata.plan.plan(mapper, START, GOAL, unknown="maybe")


def test_planning_needs_an_esdf():
    with pytest.raises(strata.InputError, match="ESDF"):
        strata.plan.plan(strata.Mapper(), START, GOAL)

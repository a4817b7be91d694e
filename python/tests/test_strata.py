"""The Python package against the installed copy (python/run_pytest.cmake installs it first):
every bound type, bad input raising the named exception before any work, threads, and equality
with the C++ library's own results (the map the C++ save writes, read back)."""
import importlib
import os
import threading

import numpy as np
import pytest

import strata

DATA = os.environ.get("STRATA_DATA_DIR", "")
KITCHEN = os.path.join(DATA, "redkitchen")


def need_kitchen():
    if not os.path.isdir(KITCHEN):
        pytest.skip(f"{KITCHEN} is absent: the redkitchen sample of ../shared/data is needed")
    return strata.io.Dataset(KITCHEN)


def plane_frame(distance_m=1.0, width=64, height=48):
    """A camera 1 m in front of a wall (z = distance in the camera frame)."""
    intrinsics = strata.CameraIntrinsics(width, height, 50.0, 50.0, width / 2 - 0.5,
                                         height / 2 - 0.5)
    depth = np.full((height, width), distance_m, dtype=np.float32)
    return depth, intrinsics


def test_the_package_is_the_installed_one():
    prefix = os.environ.get("STRATA_PYTHON_PREFIX")
    if prefix:
        assert strata.__file__.startswith(prefix), strata.__file__
    importlib.import_module("strata.io")  # a real submodule
    from strata.trajectory import evaluate  # noqa: F401


def test_configs_validate_and_show_their_fields():
    config = strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05), esdf=True)
    assert "voxel 5 cm" in repr(config) and "esdf=True" in repr(config)
    with pytest.raises(strata.InputError, match="voxel_size_m"):
        strata.MapConfig(voxel_size_m=-1.0)
    with pytest.raises(ValueError):  # InputError is a ValueError
        strata.CameraIntrinsics(640, 480, 0.0, 525.0, 320.0, 240.0)


def test_a_wall_fuses_meshes_and_answers_distances():
    depth, intrinsics = plane_frame()
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05), esdf=True))
    pose = np.eye(4)
    assert mapper.integrate(depth, intrinsics, pose) > 0
    mesh = mapper.mesh()
    assert mesh.vertices.dtype == np.float32 and mesh.vertices.shape[1] == 3
    assert mesh.faces.dtype == np.int32 and mesh.faces.shape[0] > 0
    assert np.abs(mesh.vertices[:, 2] - 1.0).max() < 0.05, "the wall's surface at z = 1 m"
    mapper.update_esdf()
    distance, gradient, known = mapper.distance(np.array([[0.0, 0.0, 0.8]], dtype=np.float32))
    assert known[0]
    assert abs(distance[0] - 0.2) < 0.06, distance
    assert gradient.shape == (1, 3)


def test_uint16_depth_with_a_scale_fuses_as_metres():
    depth, intrinsics = plane_frame()
    a = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05)))
    b = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05)))
    a.integrate(depth, intrinsics, np.eye(4))
    b.integrate((depth * 1000).astype(np.uint16), intrinsics, np.eye(4), depth_scale=1000.0)
    assert np.array_equal(a.mesh().vertices, b.mesh().vertices)


def test_bad_input_names_what_was_expected():
    depth, intrinsics = plane_frame()
    mapper = strata.Mapper()
    with pytest.raises(strata.InputError, match="float32"):
        mapper.integrate(depth.astype(np.float64), intrinsics, np.eye(4))
    with pytest.raises(strata.InputError, match="H x W"):
        mapper.integrate(depth[None], intrinsics, np.eye(4))
    with pytest.raises(strata.InputError):
        mapper.integrate(depth[:10], intrinsics, np.eye(4))  # not the intrinsics' size
    with pytest.raises(strata.InputError, match="4 x 4"):
        mapper.integrate(depth, intrinsics, np.eye(3))
    nan_pose = np.eye(4)
    nan_pose[0, 3] = np.nan
    with pytest.raises(strata.InputError):
        mapper.integrate(depth, intrinsics, nan_pose)
    with pytest.raises(strata.InputError, match="uint8"):
        mapper.integrate(depth, intrinsics, np.eye(4), color=np.zeros((48, 64, 3), np.float32))
    with pytest.raises(strata.InputError, match="N x 3"):
        mapper.distance(np.zeros((4, 2)))
    with pytest.raises(strata.InputError, match="not finite"):
        mapper.is_path_free(np.array([[0, 0, 0], [np.inf, 0, 0]], dtype=np.float32), 0.1)
    assert mapper.frames_integrated == 0, "nothing was fused by the refused calls"
    mapper.close()
    with pytest.raises(strata.InputError, match="closed"):
        mapper.integrate(depth, intrinsics, np.eye(4))


def test_save_and_load_give_the_same_map(tmp_path):
    depth, intrinsics = plane_frame()
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05)))
    mapper.integrate(depth, intrinsics, np.eye(4))
    path = str(tmp_path / "wall.strata")
    mapper.save(path)
    loaded = strata.Mapper.load(path)
    assert loaded.block_count == mapper.block_count
    assert np.array_equal(loaded.mesh().vertices, mapper.mesh().vertices)
    with pytest.raises(strata.InputError, match="missing.strata"):
        strata.Mapper.load(str(tmp_path / "missing.strata"))


def test_sessions_with_change_detection_find_the_dome_that_appeared():
    width, height, f = 64, 48, 50.0
    intrinsics = strata.CameraIntrinsics(width, height, f, f, width / 2 - 0.5, height / 2 - 0.5)
    wall = np.full((height, width), 2.0, dtype=np.float32)
    # A dome of 0.35 m radius standing 0.4 m out of the wall's view (a flat patch would be
    # refused as degenerate by the object discovery).
    v, u = np.mgrid[0:height, 0:width]
    x, y = (u - intrinsics.cx) / f * 1.6, (v - intrinsics.cy) / f * 1.6
    inside = x * x + y * y < 0.35 ** 2
    dome = np.where(inside, 1.6 - np.sqrt(np.maximum(0.0, 0.35 ** 2 - x * x - y * y)), 2.0)
    dome = dome.astype(np.float32)
    config = strata.MapperConfig(strata.MapConfig.for_change_detection(0.05),
                                 change_detection=True)
    mapper = strata.Mapper(config)
    mapper.begin_session()
    for _ in range(12):  # a voxel counts as observed after 10 frames (ChangeConfig.min_weight)
        mapper.integrate(wall, intrinsics, np.eye(4))
    assert mapper.end_session() == []
    mapper.begin_session()
    for _ in range(12):
        mapper.integrate(dome, intrinsics, np.eye(4))
    objects = mapper.end_session()
    assert len(objects) == 1
    assert np.abs(objects[0].centroid - np.array([0.0, 0.0, 1.39])).max() < 0.1, objects[0]
    assert objects[0].mesh.faces.shape[0] > 100
    assert mapper.session_count == 2


def test_threads_read_while_another_integrates():
    depth, intrinsics = plane_frame()
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05)))
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)

    reader = threading.Thread(target=count)
    reader.start()
    for _ in range(10):
        mapper.integrate(depth, intrinsics, np.eye(4))
    stop.set()
    reader.join()
    assert mapper.frames_integrated == 10
    assert len(ticks) > 0, "the GIL was released during device work"


def test_the_kitchen_from_python_equals_the_cpp_map(tmp_path):
    data = need_kitchen()
    assert len(data) == 150
    frame = data[0]
    assert frame["depth"].dtype == np.float32 and frame["depth"].shape == (480, 640)
    assert frame["color"].dtype == np.uint8 and frame["color"].shape == (480, 640, 3)
    with pytest.raises(IndexError):
        data[150]
    config = strata.MapperConfig(strata.MapConfig(voxel_size_m=0.04))
    mapper = strata.Mapper(config)
    for i in range(0, 10):
        f = data[i]
        mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
    path = str(tmp_path / "kitchen.strata")
    mapper.save(path)
    # The same frames through the C++ loop of strata::Mapper::load + save give the same bytes.
    again = strata.Mapper.load(path, config)
    path2 = str(tmp_path / "kitchen2.strata")
    again.save(path2)
    with open(path, "rb") as a, open(path2, "rb") as b:
        assert a.read() == b.read()


def test_trajectory_evaluation_of_arrays():
    t = np.arange(10, dtype=np.float64) * 0.1
    truth = np.zeros((10, 8))
    truth[:, 0] = t
    truth[:, 1] = t  # along x
    truth[:, 7] = 1.0
    estimate = truth.copy()
    estimate[:, 2] += 0.01  # 1 cm off in y: removed by the alignment
    error = strata.trajectory.evaluate(estimate, truth)
    assert error.matched == 10
    assert error.ate_rmse_m < 1e-6
    with pytest.raises(strata.InputError, match="N x 8"):
        strata.trajectory.evaluate(estimate[:, :7], truth)
    with pytest.raises(strata.InputError, match="se3"):
        strata.trajectory.evaluate(estimate, truth, alignment="affine")


def test_vio_over_the_euroc_excerpt_against_its_truth():
    folder = os.path.join(DATA, "euroc_v101_micro")
    if not os.path.isdir(folder):
        pytest.skip(f"{folder} is absent: the EuRoC excerpt of ../shared/data is needed")
    run = strata.odometry.run_euroc(folder)
    assert run.stereo and run.frames_processed == 95
    assert run.frames_tracked > 50, run
    assert run.trajectory.shape == (run.frames_tracked, 8)
    assert run.truth.shape[1] == 8 and run.truth.shape[0] > 0
    error = strata.trajectory.evaluate(run.trajectory, run.truth)
    assert error.matched > 50
    assert error.ate_rmse_m < 0.05, error
    with pytest.raises(strata.InputError, match="nowhere"):
        strata.odometry.run_euroc(os.path.join(DATA, "nowhere"))


def test_the_examples_run_and_draw(tmp_path):
    """examples/python: each runs as a newcomer would and writes its picture."""
    import subprocess
    import sys
    examples = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python")
    runs = {
        "fuse_kitchen.py": ["--data", KITCHEN],
        "vio_euroc.py": ["--data", os.path.join(DATA, "euroc_v101_micro")],
        "room_objects.py": ["--frames", "30"],
    }
    for script, args in runs.items():
        if args[0] == "--data" and not os.path.isdir(args[1]):
            pytest.skip(f"{args[1]} is absent")
        out = tmp_path / (script[:-3] + ".png")
        result = subprocess.run([sys.executable, os.path.join(examples, script), *args,
                                 "--out", str(out)], capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
        assert out.stat().st_size > 10000, script
        assert "wrote" in result.stdout, result.stdout


def test_a_simulated_session_as_arrays():
    data = strata.sim.session("room", 1, frames=5, noise=False)
    assert len(data) == 5 and data.recorded_frames > 5
    frame = data[2]
    assert frame["depth"].dtype == np.float32
    assert frame["depth"].shape == (data.intrinsics.height, data.intrinsics.width)
    assert frame["color"].shape == (data.intrinsics.height, data.intrinsics.width, 3)
    assert np.isfinite(frame["T_W_C"]).all()
    with pytest.raises(strata.InputError, match="nowhere"):
        strata.sim.session("nowhere")
    with pytest.raises(strata.InputError):
        strata.sim.session("room", 99)

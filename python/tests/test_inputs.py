"""How arrays reach the library: arrays in its dtype and C order are read in place (no temporary,
strata.input_copies() unchanged), others are converted first and fuse the same; the C++ call's own
time (Mapper.last_call_s) is part of the Python call's; Ctrl-C stops a long C++ loop."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import strata


def wall_frame(width=64, height=48):
    intrinsics = strata.CameraIntrinsics(width, height, 50.0, 50.0, width / 2 - 0.5,
                                         height / 2 - 0.5)
    v, u = np.mgrid[0:height, 0:width]
    depth = (1.0 + 0.002 * u + 0.001 * v).astype(np.float32)  # a slanted wall: rows differ
    color = np.stack([u % 256, v % 256, (u + v) % 256], axis=-1).astype(np.uint8)
    return depth, color, intrinsics


def mapper():
    return strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.05), esdf=True))


def test_arrays_in_the_library_layout_are_read_in_place():
    depth, color, intrinsics = wall_frame()
    m = mapper()
    before = strata.input_copies()
    m.integrate(depth, intrinsics, np.eye(4), color)
    m.integrate((depth * 1000).astype(np.uint16), intrinsics, np.eye(4), depth_scale=1000.0)
    m.update_esdf()
    m.distance(np.zeros((5, 3), np.float32))
    assert strata.input_copies() == before, "a C-contiguous float32/uint16/uint8 array was copied"


def test_other_layouts_are_converted_once_and_fuse_the_same():
    depth, color, intrinsics = wall_frame()
    a, b = mapper(), mapper()
    a.integrate(depth, intrinsics, np.eye(4), color)
    before = strata.input_copies()
    b.integrate(np.asfortranarray(depth), intrinsics, np.eye(4), np.asfortranarray(color))
    assert strata.input_copies() == before + 2, "Fortran-order depth and colour are converted"
    assert np.array_equal(a.mesh().vertices, b.mesh().vertices)
    assert np.array_equal(a.mesh().colors, b.mesh().colors)
    a.update_esdf()
    points = np.array([[0.0, 0.0, 0.8], [0.1, 0.0, 0.7]])
    before = strata.input_copies()
    from_float64 = a.distance(points)  # float64: converted to the library's float32
    assert strata.input_copies() == before + 1
    assert np.array_equal(from_float64[0], a.distance(points.astype(np.float32))[0])


def test_a_frame_of_another_size_after_one_is_refused_and_the_next_fuses():
    depth, _, intrinsics = wall_frame()
    m = mapper()
    m.integrate(depth, intrinsics, np.eye(4))
    with pytest.raises(strata.InputError):
        m.integrate(depth[:20], intrinsics, np.eye(4))  # the frame buffer is reused, not trusted
    m.integrate(depth, intrinsics, np.eye(4))
    assert m.frames_integrated == 2


def test_the_cpp_call_time_is_part_of_the_python_call():
    depth, _, intrinsics = wall_frame()
    m = mapper()
    assert m.last_call_s == 0.0
    start = time.perf_counter()
    m.integrate(depth, intrinsics, np.eye(4))
    python_s = time.perf_counter() - start
    assert 0.0 < m.last_call_s <= python_s
    m.update_esdf()
    points = np.zeros((1000, 3), np.float32)
    m.distance(points)
    start = time.perf_counter()
    m.distance(points)
    python_s = time.perf_counter() - start
    assert 0.0 < m.last_call_s <= python_s


def test_ctrl_c_stops_vio_between_frames():
    folder = os.path.join(os.environ.get("STRATA_DATA_DIR", ""), "euroc_v101_micro")
    if not os.path.isdir(folder):
        pytest.skip(f"{folder} is absent: the EuRoC excerpt of ../shared/data is needed")

    class Interrupted(Exception):
        pass

    def handler(signum, frame):
        raise Interrupted()

    frames = 60
    start = time.monotonic()
    whole = strata.odometry.run_euroc(folder, frames=frames)
    whole_s = time.monotonic() - start
    assert whole.frames_processed == frames
    old = signal.signal(signal.SIGINT, handler)
    timer = threading.Timer(0.1 * whole_s, lambda: os.kill(os.getpid(), signal.SIGINT))
    try:
        timer.start()
        start = time.monotonic()
        with pytest.raises(Interrupted):
            strata.odometry.run_euroc(folder, frames=frames)
        stopped_s = time.monotonic() - start
    finally:
        timer.join()
        signal.signal(signal.SIGINT, old)
    assert stopped_s < 0.6 * whole_s, (stopped_s, whole_s)

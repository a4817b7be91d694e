"""strata.odometry.Vio fed live: the EuRoC excerpt's images (read with Pillow) and IMU samples
pushed one at a time in time order, as strata-vio receives them; the poses equal those of the
library's own replay (run_euroc) over the same data and follow the truth."""
import csv
import os

import numpy as np
import pytest

import strata

DATA = os.environ.get("STRATA_DATA_DIR", "")
EUROC = os.path.join(DATA, "euroc_v101_micro")


def need_euroc():
    if not os.path.isdir(EUROC):
        pytest.skip(f"{EUROC} is absent: the EuRoC excerpt of ../shared/data is needed")
    return os.path.join(EUROC, "mav0")


def camera_list(mav0, cam):
    with open(os.path.join(mav0, cam, "data.csv")) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return {int(r[0]): os.path.join(mav0, cam, "data", r[1].strip()) for r in rows}


def grey(path):
    from PIL import Image
    return np.asarray(Image.open(path).convert("L"), dtype=np.uint8)


@pytest.fixture(scope="module")
def live():
    mav0 = need_euroc()
    left, right = camera_list(mav0, "cam0"), camera_list(mav0, "cam1")
    stamps = sorted(set(left) & set(right))
    imu_t = np.loadtxt(os.path.join(mav0, "imu0", "data.csv"), delimiter=",", usecols=0,
                       dtype=np.int64, comments="#")
    imu = np.loadtxt(os.path.join(mav0, "imu0", "data.csv"), delimiter=",", usecols=range(1, 7),
                     comments="#")
    vio = strata.odometry.Vio(EUROC)
    assert vio.stereo and vio.status == "initializing"
    frames, i = [], 0
    for t in stamps:  # the replay's order: the samples up to the frame's time, then the frame
        while i < len(imu_t) and imu_t[i] <= t:
            frames += vio.push_imu(int(imu_t[i]), imu[i, :3], imu[i, 3:])
            i += 1
        frames += vio.push_frame(t, grey(left[t]), grey(right[t]))
    for j in range(i, len(imu_t)):
        frames += vio.push_imu(int(imu_t[j]), imu[j, :3], imu[j, 3:])
    vio.flush()
    return vio, frames, (grey(left[stamps[0]]), stamps)


def tum(frames):
    rows = []
    for f in frames:
        T = f.T_W_C
        R = T[:3, :3]
        w = np.sqrt(max(1e-12, 1 + np.trace(R))) / 2
        q = [(R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w),
             (R[1, 0] - R[0, 1]) / (4 * w), w]
        rows.append([f.timestamp_ns * 1e-9, *T[:3, 3], *q])
    return np.array(rows)


def test_live_poses_equal_the_replay_and_follow_the_truth(live):
    vio, frames, _ = live
    tracked = [f for f in frames if f.status == "tracking"]
    stats = vio.stats
    assert stats["frames_processed"] == len(frames) == 95
    assert stats["frames_tracking"] == len(tracked) > 50
    replay = strata.odometry.run_euroc(EUROC)
    assert replay.frames_tracked == len(tracked)
    live_positions = np.array([f.T_W_C[:3, 3] for f in tracked])
    times = np.array([f.timestamp_ns * 1e-9 for f in tracked])
    assert np.allclose(times, replay.trajectory[:, 0])
    # The same pipeline on the same samples in the same order: the same poses (OpenCV's and the
    # solver's threads may reorder floating-point sums: within a millimetre).
    assert np.abs(live_positions - replay.trajectory[:, 1:4]).max() < 1e-3
    error = strata.trajectory.evaluate(tum(tracked), replay.truth)
    assert error.matched > 50 and error.ate_rmse_m < 0.05, error
    for f in tracked:
        assert np.allclose(f.T_W_C[:3, :3] @ f.T_W_C[:3, :3].T, np.eye(3), atol=1e-6)
        assert f.features > 0


def test_bad_samples_and_images_are_refused_or_counted(live):
    _, _, (image, stamps) = live
    vio = strata.odometry.Vio(EUROC)
    with pytest.raises(strata.InputError, match="left"):
        vio.push_frame(stamps[0], image[:10], image)  # not the calibrated size
    with pytest.raises(strata.InputError, match="right"):
        vio.push_frame(stamps[0], image, image.astype(np.float32))
    with pytest.raises(strata.InputError, match="gyro"):
        vio.push_imu(stamps[0], [0.0, 0.0], [0.0, 0.0, 9.81])
    assert vio.stats["frames_in"] == 0, "nothing of the state changed"
    vio.push_imu(stamps[0], [0.0, 0.0, 0.0], [0.0, 0.0, 9.81])
    vio.push_imu(stamps[0] - 1, [0.0, 0.0, 0.0], [0.0, 0.0, 9.81])  # out of order
    vio.push_imu(stamps[0] + 1, [np.nan, 0.0, 0.0], [0.0, 0.0, 9.81])
    stats = vio.stats
    assert stats["imu_samples"] == 1 and stats["imu_out_of_order_skipped"] == 1
    assert stats["imu_nonfinite_skipped"] == 1
    with pytest.raises(strata.InputError):
        strata.odometry.Vio(os.path.join(DATA, "nowhere"))

"""strata.localize: the redkitchen excerpt split in two, a map store of frames 0-74 (their reference
poses as the odometry, so the map frame is the dataset's) and frames 75-100 localised against it,
one by one (Localizer), fused with an odometry in a frame of its own (PoseFusion) and as a
session (localize_session); errors are against the dataset's reference poses, which hold over
frames 75-89 (docs/localize.md)."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import strata

DATA = os.environ.get("STRATA_DATA_DIR", "")
KITCHEN = os.path.join(DATA, "redkitchen")


def translation_error(T, truth):
    return float(np.linalg.norm(T[:3, 3] - truth[:3, 3]))


def angle_deg(R):
    return float(np.degrees(np.arccos(np.clip((np.trace(R) - 1) / 2, -1.0, 1.0))))


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory):
    """(root, map store path, PriorMap, the dataset)."""
    if not os.path.isdir(KITCHEN):
        pytest.skip(f"{KITCHEN} is absent: the redkitchen sample of ../shared/data is needed")
    root = tmp_path_factory.mktemp("localize")
    written = strata.sim.drifted_session(KITCHEN, str(root / "kitchen_map"), 0, 74, drift=False,
                                         offset=False)
    assert written["frames"] == 75
    path = str(root / "map.sqlite")
    store = strata.store.Store(path)
    assert store.import_session(str(root / "kitchen_map"), keyframe_every=3).keyframes == 25
    store.close()
    prior_map = strata.localize.PriorMap(path)
    return root, path, prior_map, strata.io.Dataset(KITCHEN)


def test_the_prior_map_holds_the_stores_keyframes_in_the_datasets_frame(kitchen):
    _, _, prior_map, data = kitchen
    assert prior_map.keyframes == 25
    assert prior_map.sessions == ["kitchen_map"] and prior_map.skipped_sessions == []
    poses = prior_map.keyframe_poses
    assert poses.shape == (25, 4, 4) and poses.dtype == np.float64
    # Nothing aligned: the only session anchors the map frame, so keyframe k is frame 3k's truth.
    for k in (0, 12, 24):
        assert np.allclose(poses[k], data[3 * k]["T_W_C"], atol=1e-6)
    assert "25 keyframes" in repr(prior_map)


def test_frames_of_the_second_half_localise_within_5_cm(kitchen):
    _, _, prior_map, data = kitchen
    localizer = strata.localize.Localizer(prior_map)
    for i in range(75, 91, 3):
        f = data[i]
        r = localizer.localize(f["color"], f["depth"], data.intrinsics)
        assert r.localized, (i, r.reason)
        assert r.reason == "" and r.source in ("appearance", "surface", "prior")
        assert r.T_W_C.shape == (4, 4) and r.covariance.shape == (6, 6)
        assert np.allclose(r.covariance, r.covariance.T) and np.all(np.diag(r.covariance) > 0)
        assert translation_error(r.T_W_C, f["T_W_C"]) < 0.05, i
        assert angle_deg(r.T_W_C[:3, :3].T @ f["T_W_C"][:3, :3]) < 2.0, i
        assert 0 <= r.keyframe < prior_map.keyframes
        assert r.candidates >= r.accepted >= 1 and r.inliers > 0 and 0 < r.overlap <= 1
        assert r.time_ms >= r.features_ms + r.verify_ms > 0
    # With a prior (the truth), a later frame too; the truth itself is off by a few cm there.
    f = data[100]
    r = localizer.localize(f["color"], f["depth"], data.intrinsics, prior=f["T_W_C"])
    assert r.localized, r.reason
    assert translation_error(r.T_W_C, f["T_W_C"]) < 0.15


def test_pose_fusion_takes_odometry_in_a_frame_of_its_own_into_the_map_frame(kitchen):
    _, _, prior_map, data = kitchen
    localizer = strata.localize.Localizer(prior_map)
    # The odometry frame O: the map frame turned 0.3 rad about z and shifted.
    T_O_W = np.eye(4)
    c, s = np.cos(0.3), np.sin(0.3)
    T_O_W[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    T_O_W[:3, 3] = [2.0, -1.0, 0.5]
    fusion = strata.localize.PoseFusion()
    assert not fusion.initialised and fusion.prior() is None
    fused = None
    for i in range(75, 91, 3):
        f = data[i]
        predicted = fusion.predict(f["timestamp_s"], T_O_W @ f["T_W_C"])
        if i == 75:
            assert predicted.status == "uninitialised"
        prior = fusion.prior()
        fused = fusion.correct(localizer.localize(f["color"], f["depth"], data.intrinsics, prior))
        assert translation_error(fused.T_W_C, f["T_W_C"]) < 0.05 or fused.status == "uninitialised"
    assert fusion.initialised and fused.status == "corrected", fused
    assert fusion.accepted >= 2 and fusion.rejected == 0
    assert np.allclose(fusion.T_W_O[:3, 3], np.linalg.inv(T_O_W)[:3, 3], atol=0.05)
    assert fused.translation_sigma_m > 0 and fused.covariance.shape == (6, 6)
    assert translation_error(fusion.prior(), data[90]["T_W_C"]) < 0.05
    with pytest.raises(strata.InputError):
        fusion.predict(data[80]["timestamp_s"], T_O_W @ data[80]["T_W_C"])  # time went back
    assert fusion.initialised, "a refused odometry pose changes nothing"
    fusion.reset()
    assert not fusion.initialised and fusion.prior() is None


def test_a_session_localises_frame_by_frame_with_and_without_odometry(kitchen):
    root, path, prior_map, _ = kitchen
    live = root / "kitchen_live"
    strata.sim.drifted_session(KITCHEN, str(live), 75, 100, seed=3)
    truth = np.loadtxt(live / "groundtruth.txt", comments="#")
    fused = strata.localize.localize_session(str(live), prior_map, every=3)
    n = len(truth)
    assert fused.with_odometry and fused.T_W_C.shape == (n, 4, 4) and len(fused.status) == n
    assert fused.timestamps_s.shape == (n,) and np.allclose(fused.timestamps_s, truth[:, 0])
    assert fused.attempts == len(range(0, n, 3)) and fused.localizations >= 0.6 * fused.attempts
    assert fused.placed.mean() >= 0.8 and fused.rejected == 0
    assert set(fused.status) <= {"uninitialised", "tracking", "corrected"}
    errors = np.linalg.norm(fused.T_W_C[:, :3, 3] - truth[:, 1:4], axis=1)
    early = fused.placed & (truth[:, 0] <= truth[15, 0])  # frames 75-90
    assert early.any() and errors[early].max() < 0.05
    assert np.isnan(fused.T_W_C[~fused.placed]).all()
    # Without odometry, from the path: only the localised frames are placed.
    alone = strata.localize.localize_session(str(live), path, every=5, odometry=False)
    assert not alone.with_odometry
    assert np.array_equal(alone.placed, alone.localized) and alone.localizations >= 3
    assert np.nanmax(np.linalg.norm(alone.T_W_C[:, :3, 3] - truth[:, 1:4], axis=1)) < 0.15


def test_ctrl_c_stops_a_session_between_frames(kitchen):
    root, _, prior_map, _ = kitchen
    live = root / "kitchen_live_all"
    strata.sim.drifted_session(KITCHEN, str(live), 75, 149, seed=4)
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            strata.localize.localize_session(str(live), prior_map)  # 75 frames: over 5 s
    finally:
        timer.cancel()
    assert time.monotonic() - start < 4.0, "stopped at the next frame, not at the end"


def test_bad_input_is_refused_by_name(kitchen, tmp_path):
    root, _, prior_map, data = kitchen
    missing = str(tmp_path / "missing.sqlite")
    with pytest.raises(strata.InputError, match="missing.sqlite"):
        strata.localize.PriorMap(missing)
    with pytest.raises(strata.InputError, match="missing.sqlite"):
        strata.localize.localize_session(str(root / "kitchen_map"), missing)
    with pytest.raises(strata.InputError, match="nowhere"):
        strata.localize.localize_session(str(tmp_path / "nowhere"), prior_map)
    localizer = strata.localize.Localizer(prior_map)
    f = data[80]
    with pytest.raises(strata.InputError):
        localizer.localize(f["color"], f["depth"][:240], data.intrinsics)  # wrong size
    with pytest.raises(strata.InputError):
        localizer.localize(f["color"], f["depth"].astype(np.float64), data.intrinsics)
    with pytest.raises(strata.InputError):
        localizer.localize(f["color"], f["depth"], data.intrinsics, prior=np.eye(3))
    with pytest.raises(strata.InputError):
        strata.localize.PoseFusion().predict(0.0, np.full((4, 4), np.nan))

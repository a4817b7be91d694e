"""strata.store and strata.align: the redkitchen excerpt split in two sessions, the second written
in a frame of its own with drifted odometry (strata.sim.drifted_session, which returns the true
offset), imported into a store and aligned; the recovered offset and trajectories are held to
that truth, and the store to what the alignment returned."""
import os
import shutil

import numpy as np
import pytest

import strata

DATA = os.environ.get("STRATA_DATA_DIR", "")
KITCHEN = os.path.join(DATA, "redkitchen")


def angle_deg(R):
    return np.degrees(np.arccos(np.clip((np.trace(R) - 1) / 2, -1.0, 1.0)))


@pytest.fixture(scope="module")
def split(tmp_path_factory):
    """Frames 0-74 as the anchor (odometry = the reference poses), 75-149 offset and drifting."""
    if not os.path.isdir(KITCHEN):
        pytest.skip(f"{KITCHEN} is absent: the redkitchen sample of ../shared/data is needed")
    root = tmp_path_factory.mktemp("align")
    anchor = strata.sim.drifted_session(KITCHEN, str(root / "kitchen_a"), 0, 74, drift=False,
                                        offset=False)
    drifted = strata.sim.drifted_session(KITCHEN, str(root / "kitchen_b"), 75, 149, seed=3)
    assert anchor["frames"] == 75 and drifted["frames"] == 75
    assert np.allclose(anchor["T_W_S"], np.eye(4))
    store = strata.store.Store(str(root / "map.sqlite"))
    for name in ("kitchen_a", "kitchen_b"):
        imported = store.import_session(str(root / name), keyframe_every=3)
        assert not imported.skipped and imported.frames == 75 and imported.keyframes == 25
    alignment = strata.align.align_store(store)
    return root, drifted["T_W_S"], store, alignment


def test_the_second_halfs_offset_is_recovered(split):
    root, T_W_S_true, store, alignment = split
    assert [s.aligned for s in alignment.sessions] == [True, True]
    assert np.allclose(alignment.sessions[0].T_W_S, np.eye(4), atol=1e-9), "the anchor"
    # The offset's error at the second half's first camera (as test_align_store.cpp measures it).
    T_S_C0 = store.keyframes(alignment.sessions[1].id)["T_S_C"][0]
    error = np.linalg.inv(T_W_S_true @ T_S_C0) @ alignment.sessions[1].T_W_S @ T_S_C0
    assert np.linalg.norm(error[:3, 3]) < 0.02
    assert angle_deg(error[:3, :3]) < 1.0
    assert alignment.loops_accepted > 0 and alignment.loops_verified >= alignment.loops_accepted
    assert alignment.candidates >= alignment.loops_verified
    assert set(alignment.times) == {"features_s", "retrieval_s", "verification_s", "graph_s"}


def test_the_aligned_trajectories_and_score_follow_the_truth(split):
    root, _, _, alignment = split
    score = alignment.score
    assert score is not None, "both folders have groundtruth.txt"
    assert score.aligned_sessions == 2
    assert score.ate_after_rmse_m < 0.05 < score.ate_before_rmse_m
    assert score.loop_precision == 1.0 and score.accepted_false == 0
    drifted = alignment.sessions[1]
    assert drifted.trajectory.shape == (75, 8) and drifted.odometry.shape == (75, 8)
    assert drifted.keyframe_T_W_C.shape == (25, 4, 4)
    truth = np.loadtxt(root / "kitchen_b" / "groundtruth.txt", comments="#")
    after = strata.trajectory.evaluate(drifted.trajectory, truth)
    assert after.matched == 75 and after.ate_rmse_m < 0.05, after
    # In the world frame without any fit: the alignment itself placed the session.
    assert np.abs(drifted.trajectory[:, 1:4] - truth[:, 1:4]).max() < 0.1


def test_the_store_holds_the_result_and_refuses_a_session_whose_folder_is_gone(split):
    root, _, store, alignment = split
    sessions = store.sessions()
    assert [s.name for s in sessions] == ["kitchen_a", "kitchen_b"]
    assert all(s.aligned for s in sessions)
    assert np.allclose(sessions[1].T_W_S, alignment.sessions[1].T_W_S)
    assert store.loop_count() == alignment.loops_verified
    keyframes = store.keyframes(sessions[1].id)
    assert len(keyframes["id"]) == 25 and not np.isnan(keyframes["T_W_C"]).any()
    assert np.allclose(keyframes["T_W_C"], alignment.sessions[1].keyframe_T_W_C)
    assert store.import_session(str(root / "kitchen_a")).skipped, "already in the store"
    reader = strata.store.Store(store.path, read_only=True)
    assert [s.aligned for s in reader.sessions()] == [True, True]
    reader.close()
    shutil.move(str(root / "kitchen_b"), str(root / "moved"))
    try:
        with pytest.raises(strata.InputError, match="kitchen_b"):
            strata.align.align_store(store)
    finally:
        shutil.move(str(root / "moved"), str(root / "kitchen_b"))
    assert all(s.aligned for s in store.sessions()), "the store is as it was"
    assert store.loop_count() == alignment.loops_verified


def test_bad_store_input_is_refused_by_name(tmp_path):
    with pytest.raises(strata.InputError, match="missing.sqlite"):
        strata.store.Store(str(tmp_path / "missing.sqlite"), create=False)
    store = strata.store.Store(str(tmp_path / "map.sqlite"))
    with pytest.raises(strata.InputError):
        store.import_session(str(tmp_path / "nowhere"))
    with pytest.raises(strata.InputError):
        strata.align.align_store(store)  # no session
    store.close()
    with pytest.raises(strata.InputError, match="closed"):
        store.sessions()

"""strata.objects.build on two simulated sessions of the shipped room: every model placed at each of
its instances lies on the segment the library discovered in that session, the outcomes and the
instances agree, and an object seen in both sessions is one model."""
import numpy as np
import pytest

import strata

FRAMES = 30


@pytest.fixture(scope="module")
def database():
    sessions = [strata.sim.session("room", s, frames=FRAMES) for s in (0, 1)]
    recorded = sessions[0].recorded_frames / len(sessions[0])
    return strata.objects.build(sessions, voxel_size_m=0.05, recorded_per_fused=recorded)


def placed(mesh, T):
    return mesh.vertices.astype(np.float64) @ T[:3, :3].T + T[:3, 3]


def nearest(a, b):
    """For each row of a, the distance to the nearest row of b."""
    return np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(-1)).min(1)


def test_every_instance_lies_on_the_segment_it_was_matched_to(database):
    models = database.models
    assert len(models) > 0 and len(database.discovered) == 2
    segments = {(o.session, o.id): o for session in database.discovered for o in session}
    for model in models:
        assert model.mesh.faces.shape[0] > 0 and model.surface_area_m2 > 0
        assert (np.diff(model.extent_m) <= 0).all(), "extents sorted descending"
        for instance in model.instances:
            T = instance["T_W_M"]
            assert T.shape == (4, 4) and np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3),
                                                     atol=1e-6)
            segment = segments[(instance["session"], instance["segment_id"])]
            world = placed(model.mesh, T)
            # The merged model may be more complete than one session's view of it: the view's
            # surface lies on the model.
            gap = nearest(segment.mesh.vertices.astype(np.float64), world)
            assert np.median(gap) < 0.05, (model, instance, np.median(gap))


def test_outcomes_instances_and_session_meshes_agree(database):
    placed_segments = {(i["session"], i["segment_id"], m.id)
                       for m in database.models for i in m.instances}
    matched = {(o["session"], o["segment_id"], o["model_id"])
               for o in database.outcomes if o["model_id"] != 0}
    assert matched == placed_segments
    assert len(database.outcomes) == sum(len(s) for s in database.discovered)
    assert {o["model_id"] for o in database.outcomes if o["new_model"]} <= {
        m.id for m in database.models} | {j for o in database.outcomes for j in o["joined_models"]}
    for session in (0, 1):
        expected = sum(m.mesh.vertices.shape[0] for m in database.models
                       for i in m.instances if i["session"] == session)
        assert database.session_objects(session).vertices.shape[0] == expected
    assert database.static_mesh.faces.shape[0] > 1000


def test_an_object_seen_in_both_sessions_is_one_model(database):
    both = [m for m in database.models if {i["session"] for i in m.instances} == {0, 1}]
    assert both, "an object was re-identified in the second session"
    for model in both:
        first, second = model.instances[0], model.instances[1]
        assert second["match_score"] >= 0.5  # DatabaseConfig.min_match_score
        # The model frame moved with the object: its origin's motion is the segments' motion
        # (centroids of partial views: within 0.2 m).
        segments = {(o.session, o.id): o for s in database.discovered for o in s}
        a = segments[(first["session"], first["segment_id"])].centroid
        b = segments[(second["session"], second["segment_id"])].centroid
        moved = second["T_W_M"][:3, 3] - first["T_W_M"][:3, 3]
        assert np.linalg.norm(moved - (b - a)) < 0.2, (model, moved, b - a)


def test_bad_sessions_are_refused_by_name():
    one = strata.sim.session("room", 0, frames=2)
    with pytest.raises(strata.InputError, match="at least two sessions"):
        strata.objects.build([one])
    with pytest.raises(strata.InputError, match="strata.io.Dataset"):
        strata.objects.build([one, 3])
    with pytest.raises(strata.InputError, match="nowhere"):
        strata.objects.build([one, "/nowhere/session"])

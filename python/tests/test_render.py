"""Mapper.render and Mapper.score_keyframe: the map rendered back against the geometry and
colour it was fused from (a wall at a known distance, the redkitchen frames' own depth and
colour), and keyframe scores telling a frame the map explains from one it does not."""
import os

import numpy as np
import pytest

import strata

DATA = os.environ.get("STRATA_DATA_DIR", "")
KITCHEN = os.path.join(DATA, "redkitchen")
VOXEL_M = 0.05
WALL_RGB = (200, 50, 20)


def wall(distance_m=1.0, width=64, height=48):
    intrinsics = strata.CameraIntrinsics(width, height, 50.0, 50.0, width / 2 - 0.5,
                                         height / 2 - 0.5)
    depth = np.full((height, width), distance_m, dtype=np.float32)
    color = np.empty((height, width, 3), np.uint8)
    color[:] = WALL_RGB
    return depth, color, intrinsics


def wall_mapper(scoring=False):
    depth, color, intrinsics = wall()
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=VOXEL_M),
                                               keyframe_scoring=scoring))
    for _ in range(3):
        mapper.integrate(depth, intrinsics, np.eye(4), color)
    return mapper, intrinsics


@pytest.mark.parametrize("back_m", [0.0, 0.3])
def test_a_wall_renders_at_its_distance_in_its_colour(back_m):
    mapper, intrinsics = wall_mapper()
    T_W_C = np.eye(4)
    T_W_C[2, 3] = -back_m  # the camera moved back along its axis
    image = mapper.render(T_W_C, intrinsics)
    h, w = intrinsics.height, intrinsics.width
    assert image.depth.shape == (h, w) and image.depth.dtype == np.float32
    assert image.color.shape == (h, w, 3) and image.color.dtype == np.uint8
    assert image.normals.shape == (h, w, 3) and image.hit.shape == (h, w)
    assert image.hit[h // 2, w // 2], "the centre ray hits the wall"
    assert (image.depth[~image.hit] == 0).all()
    hits = image.depth[image.hit]
    assert np.abs(hits - (1.0 + back_m)).max() < VOXEL_M / 2, "the wall's distance"
    assert np.abs(image.color[image.hit].astype(int) - WALL_RGB).max() <= 2
    normals = image.normals[image.hit]
    length = np.linalg.norm(normals, axis=1)
    known = length > 0  # 0 where the gradient is unknown (the wall's rim)
    assert known.mean() > 0.5 and np.allclose(length[known], 1.0, atol=1e-3)
    assert (normals[known, 2] < -0.9).all(), "the wall faces the camera (normal along -z)"
    assert image.device_ms > 0


def test_the_kitchen_renders_back_its_frames_depth_and_colour():
    if not os.path.isdir(KITCHEN):
        pytest.skip(f"{KITCHEN} is absent: the redkitchen sample of ../shared/data is needed")
    data = strata.io.Dataset(KITCHEN)
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.04)))
    for i in range(20):
        f = data[i]
        mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
    frame = data[10]
    image = mapper.render(frame["T_W_C"], data.intrinsics)
    both = image.hit & (frame["depth"] > 0)
    assert both.mean() > 0.5, "most of the frame is in the map"
    error = np.abs(image.depth - frame["depth"])[both]
    assert np.median(error) < 0.02, "the rendered depth is the measured one within 2 cm"
    assert (error > 0.10).mean() < 0.05
    colour_error = np.abs(image.color.astype(int) - frame["color"])[both].mean()
    assert colour_error < 25, colour_error  # the voxel colour is a blend of 20 frames


def test_score_keyframe_tells_a_known_view_from_a_changed_one():
    mapper, intrinsics = wall_mapper(scoring=True)
    depth, color, _ = wall()
    seen = mapper.score_keyframe(depth, intrinsics, np.eye(4), color)
    moved = mapper.score_keyframe(depth + 0.5, intrinsics, np.eye(4), color)  # the wall moved
    assert seen.samples > 0 and 0 < seen.coverage <= 1
    assert seen.surface_change < 0.3 and seen.depth_change_m < 0.01
    assert moved.surface_change > 0.9 and moved.depth_change_m > 0.3
    assert moved.keyframe and moved.reason
    assert mapper.frames_integrated == 3, "scoring fuses nothing"
    with pytest.raises(strata.InputError, match="keyframe_scoring"):
        wall_mapper(scoring=False)[0].score_keyframe(depth, intrinsics, np.eye(4))
    with pytest.raises(strata.InputError, match="4 x 4"):
        mapper.score_keyframe(depth, intrinsics, np.eye(3))


def test_render_refuses_a_bad_pose_and_a_closed_mapper():
    mapper, intrinsics = wall_mapper()
    with pytest.raises(strata.InputError, match="4 x 4"):
        mapper.render(np.eye(3), intrinsics)
    bad = np.eye(4)
    bad[0, 0] = np.nan
    with pytest.raises(strata.InputError):
        mapper.render(bad, intrinsics)
    mapper.close()
    with pytest.raises(strata.InputError, match="closed"):
        mapper.render(np.eye(4), intrinsics)

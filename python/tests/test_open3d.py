"""Open3D interop (strata.io.to_open3d and the conversions from Open3D), where Debian's
python3-open3d is installed; skipped, saying so, where it is not."""
import numpy as np
import pytest

import strata

o3d = pytest.importorskip("open3d", reason="Open3D is not installed (Debian: python3-open3d)")


def plane_frame(distance_m=1.0, width=64, height=48):
    depth = np.full((height, width), distance_m, dtype=np.float32)
    intrinsics = strata.CameraIntrinsics(width, height, 50.0, 50.0, (width - 1) / 2, (height - 1) / 2)
    return depth, intrinsics


def test_a_fused_mesh_becomes_an_open3d_mesh_with_the_same_geometry():
    depth, intrinsics = plane_frame()
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.02)))
    color = np.full(depth.shape + (3,), 200, dtype=np.uint8)
    mapper.integrate(depth, intrinsics, np.eye(4), color)
    mesh = mapper.mesh()
    assert len(mesh.faces) > 100
    o3d_mesh = strata.io.to_open3d(mesh)
    assert np.allclose(np.asarray(o3d_mesh.vertices), mesh.vertices)
    assert np.array_equal(np.asarray(o3d_mesh.triangles), mesh.faces)
    assert np.allclose(np.asarray(o3d_mesh.vertex_colors), mesh.colors / 255.0)
    # Open3D agrees on the area of the fused plane's patch.
    assert o3d_mesh.get_surface_area() == pytest.approx(
        0.5 * np.linalg.norm(np.cross(mesh.vertices[mesh.faces[:, 1]] - mesh.vertices[mesh.faces[:, 0]],
                                      mesh.vertices[mesh.faces[:, 2]] - mesh.vertices[mesh.faces[:, 0]]), axis=1).sum(),
        rel=1e-4)


def test_open3d_points_and_images_go_into_the_mapper():
    depth, intrinsics = plane_frame()
    image = o3d.geometry.Image(depth)
    back = strata.io.image_from_open3d(image)
    assert back.dtype == np.float32 and back.shape == depth.shape
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.02), esdf=True))
    mapper.integrate(back, intrinsics, np.eye(4))
    mapper.update_esdf()
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(np.array([[0.0, 0.0, 0.9], [0.0, 0.0, 0.8]])))
    points = strata.io.points_from_open3d(cloud)
    assert points.dtype == np.float32 and points.shape == (2, 3)
    distance, _, known = mapper.distance(points)
    assert known.all()
    assert distance == pytest.approx([0.1, 0.2], abs=0.03)

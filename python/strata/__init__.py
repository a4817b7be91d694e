"""Strata from Python: the C++ library's types and calls with numpy arrays in and out.

    import numpy as np, strata
    mapper = strata.Mapper(strata.MapperConfig(strata.MapConfig(voxel_size_m=0.02), esdf=True))
    data = strata.io.Dataset("../shared/data/redkitchen")
    for i in range(len(data)):
        f = data[i]
        mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
    mesh = mapper.mesh()            # mesh.vertices N x 3 float32, mesh.faces M x 3 int32
    mapper.update_esdf()
    distance, gradient, known = mapper.distance(np.array([[0.0, 0.0, 1.0]]))

Errors raise strata.InputError (a ValueError) or strata.DeviceError (a strata.Error, a
RuntimeError) with the C++ message. See docs/python.md.
"""
import sys as _sys

from ._strata import (  # noqa: F401 (re-exported)
    align,
    CameraIntrinsics,
    DeviceError,
    DiscoveredObject,
    Error,
    InputError,
    KeyframeDecision,
    localize,
    MapConfig,
    Mapper,
    MapperConfig,
    Mesh,
    Rendering,
    input_copies,
    explore,
    io,
    objects,
    odometry,
    plan,
    sim,
    store,
    trajectory,
    validation_errors,
)

# `import strata.io` and `from strata.trajectory import evaluate` work like real submodules.
_sys.modules[__name__ + ".io"] = io
_sys.modules[__name__ + ".trajectory"] = trajectory
_sys.modules[__name__ + ".odometry"] = odometry
_sys.modules[__name__ + ".sim"] = sim
_sys.modules[__name__ + ".plan"] = plan
_sys.modules[__name__ + ".store"] = store
_sys.modules[__name__ + ".align"] = align
_sys.modules[__name__ + ".localize"] = localize
_sys.modules[__name__ + ".objects"] = objects
_sys.modules[__name__ + ".explore"] = explore



def _to_open3d(mesh):
    """A strata.Mesh as an open3d.geometry.TriangleMesh (vertex colours and normals when it has
    them). Needs Open3D (Debian: python3-open3d); ImportError saying so otherwise."""
    o3d = _open3d("strata.io.to_open3d")
    import numpy as np

    out = o3d.geometry.TriangleMesh(
        o3d.utility.Vector3dVector(np.asarray(mesh.vertices, dtype=np.float64)),
        o3d.utility.Vector3iVector(np.asarray(mesh.faces, dtype=np.int32)))
    if len(mesh.colors) == len(mesh.vertices) and len(mesh.colors) > 0:
        out.vertex_colors = o3d.utility.Vector3dVector(np.asarray(mesh.colors, dtype=np.float64) / 255.0)
    if len(mesh.normals) == len(mesh.vertices) and len(mesh.normals) > 0:
        out.vertex_normals = o3d.utility.Vector3dVector(np.asarray(mesh.normals, dtype=np.float64))
    return out


def _points_from_open3d(cloud):
    """An open3d.geometry.PointCloud's points as an N x 3 float32 array (for Mapper.distance)."""
    _open3d("strata.io.points_from_open3d")
    import numpy as np

    return np.ascontiguousarray(np.asarray(cloud.points), dtype=np.float32)


def _image_from_open3d(image):
    """An open3d.geometry.Image as a numpy array Mapper.integrate takes as it is: a float32 depth
    image in metres, a uint16 depth image (with integrate's depth_scale) or an H x W x 3 uint8
    colour image; the array shares the image's memory where its layout allows."""
    _open3d("strata.io.image_from_open3d")
    import numpy as np

    return np.asarray(image)


def _open3d(who):
    try:
        import open3d
    except ImportError as e:
        raise ImportError(f"{who} needs Open3D (Debian: apt-get install python3-open3d)") from e
    return open3d


io.to_open3d = _to_open3d
io.points_from_open3d = _points_from_open3d
io.image_from_open3d = _image_from_open3d

__all__ = [
    "CameraIntrinsics", "DeviceError", "DiscoveredObject", "Error", "InputError",
    "KeyframeDecision", "MapConfig", "Mapper", "MapperConfig", "Mesh", "Rendering", "align",
    "explore", "input_copies", "io", "localize", "objects", "odometry", "plan", "sim", "store",
    "trajectory", "validation_errors",
]

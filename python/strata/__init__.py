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
_sys.modules[__name__ + ".objects"] = objects
_sys.modules[__name__ + ".explore"] = explore

__all__ = [
    "CameraIntrinsics", "DeviceError", "DiscoveredObject", "Error", "InputError",
    "KeyframeDecision", "MapConfig", "Mapper", "MapperConfig", "Mesh", "Rendering", "align",
    "explore", "input_copies", "io", "objects", "odometry", "plan", "sim", "store", "trajectory",
    "validation_errors",
]

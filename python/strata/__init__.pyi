# Type stubs of the package `strata` (the compiled module strata._strata re-exported by
# __init__.py). tests/test_stubs.py holds them to the module: every public name of the module and
# of its classes is here, and nothing here is missing from the module.
from typing import List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import align as align
from . import explore as explore
from . import io as io
from . import localize as localize
from . import objects as objects
from . import odometry as odometry
from . import plan as plan
from . import sim as sim
from . import store as store
from . import trajectory as trajectory

class Error(RuntimeError): ...
class InputError(ValueError): ...
class DeviceError(Error): ...

class CameraIntrinsics:
    width: int  # px
    height: int  # px
    fx: float  # px
    fy: float  # px
    cx: float  # px
    cy: float  # px
    def __init__(self, width: int, height: int, fx: float, fy: float, cx: float,
                 cy: float) -> None: ...
    def validate(self) -> None: ...

class MapConfig:
    voxel_size_m: float
    truncation_voxels: float
    max_depth_m: float
    min_depth_m: float
    max_weight: float
    allocate_free_space: bool
    def __init__(self, voxel_size_m: float = ..., truncation_voxels: float = ...,
                 max_depth_m: float = ..., min_depth_m: float = ..., max_weight: float = ...,
                 allocate_free_space: bool = ...) -> None: ...
    def validate(self) -> None: ...
    @staticmethod
    def for_change_detection(voxel_size_m: float) -> MapConfig: ...

class MapperConfig:
    map: MapConfig
    esdf: bool
    change_detection: bool
    keyframe_scoring: bool
    def __init__(self, map: MapConfig = ..., esdf: bool = False, change_detection: bool = False,
                 keyframe_scoring: bool = False, recorded_per_fused: float = 1.0) -> None: ...

class Mesh:
    @property
    def vertices(self) -> npt.NDArray[np.float32]: ...  # N x 3
    @property
    def faces(self) -> npt.NDArray[np.int32]: ...  # M x 3
    @property
    def colors(self) -> npt.NDArray[np.uint8]: ...  # N x 3 or 0 x 3
    @property
    def normals(self) -> npt.NDArray[np.float32]: ...  # N x 3 or 0 x 3

class DiscoveredObject:
    @property
    def id(self) -> int: ...
    @property
    def session(self) -> int: ...
    @property
    def centroid(self) -> npt.NDArray[np.float32]: ...  # 3
    @property
    def bbox_min(self) -> npt.NDArray[np.float32]: ...  # 3
    @property
    def bbox_max(self) -> npt.NDArray[np.float32]: ...  # 3
    @property
    def mesh(self) -> Mesh: ...

class Rendering:
    @property
    def depth(self) -> npt.NDArray[np.float32]: ...  # H x W, 0 where missed
    @property
    def color(self) -> npt.NDArray[np.uint8]: ...  # H x W x 3
    @property
    def normals(self) -> npt.NDArray[np.float32]: ...  # H x W x 3, world frame
    @property
    def hit(self) -> npt.NDArray[np.bool_]: ...  # H x W
    @property
    def device_ms(self) -> float: ...

class KeyframeDecision:
    @property
    def keyframe(self) -> bool: ...
    @property
    def reason(self) -> str: ...
    @property
    def device_ms(self) -> float: ...
    @property
    def samples(self) -> int: ...
    @property
    def hits(self) -> int: ...
    @property
    def coverage(self) -> float: ...
    @property
    def color_change(self) -> float: ...
    @property
    def depth_change_m(self) -> float: ...
    @property
    def surface_change(self) -> float: ...
    @property
    def ncc(self) -> float: ...
    @property
    def histogram(self) -> float: ...

class Mapper:
    def __init__(self, config: MapperConfig = ..., device: Union[None, int, str] = None) -> None: ...
    @staticmethod
    def load(path: str, config: MapperConfig = ...,
             device: Union[None, int, str] = None) -> Mapper: ...
    def integrate(self, depth: npt.NDArray[Union[np.float32, np.uint16]],
                  intrinsics: CameraIntrinsics, T_W_C: npt.ArrayLike,
                  color: Optional[npt.NDArray[np.uint8]] = None,
                  depth_scale: float = 1000.0) -> int: ...
    def track_and_integrate(
        self, depth: npt.NDArray[Union[np.float32, np.uint16]], intrinsics: CameraIntrinsics,
        color: Optional[npt.NDArray[np.uint8]] = None,
        depth_scale: float = 1000.0) -> Tuple[npt.NDArray[np.float64], bool, str]: ...
    def update_esdf(self) -> int: ...
    def distance(
        self, points: npt.ArrayLike
    ) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.float32], npt.NDArray[np.bool_]]: ...
    def is_path_free(self, polyline: npt.ArrayLike, radius_m: float) -> bool: ...
    def mesh(self) -> Mesh: ...
    def render(self, T_W_C: npt.ArrayLike, intrinsics: CameraIntrinsics) -> Rendering: ...
    def score_keyframe(self, depth: npt.NDArray[Union[np.float32, np.uint16]],
                       intrinsics: CameraIntrinsics, T_W_C: npt.ArrayLike,
                       color: Optional[npt.NDArray[np.uint8]] = None,
                       depth_scale: float = 1000.0) -> KeyframeDecision: ...
    def begin_session(self) -> int: ...
    def end_session(self) -> List[DiscoveredObject]: ...
    def save(self, path: str) -> None: ...
    def close(self) -> None: ...
    @property
    def block_count(self) -> int: ...
    @property
    def frames_integrated(self) -> int: ...
    @property
    def session_count(self) -> int: ...
    @property
    def session_open(self) -> bool: ...
    @property
    def config(self) -> MapperConfig: ...
    @property
    def last_call_s(self) -> float: ...

def input_copies() -> int: ...
def validation_errors() -> int: ...

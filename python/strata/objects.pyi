# Type stubs of strata.objects (see __init__.pyi).
from typing import Any, Dict, List, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import DiscoveredObject, Mesh
from .io import Dataset

class ObjectModel:
    @property
    def id(self) -> int: ...
    @property
    def merged_observations(self) -> int: ...
    @property
    def mesh(self) -> Mesh: ...  # model frame
    # session, segment_id, T_W_M 4 x 4, match_score, merged, pose_constrained
    @property
    def instances(self) -> List[Dict[str, Any]]: ...
    @property
    def extent_m(self) -> npt.NDArray[np.float32]: ...  # 3, descending
    @property
    def surface_area_m2(self) -> float: ...

class ObjectDatabase:
    @property
    def models(self) -> List[ObjectModel]: ...
    # session, segment_id, model_id, new_model, skipped, score, candidates, refused, joined_models
    @property
    def outcomes(self) -> List[Dict[str, Any]]: ...
    @property
    def discovered(self) -> List[List[DiscoveredObject]]: ...
    @property
    def static_mesh(self) -> Mesh: ...
    def session_objects(self, session: int) -> Mesh: ...
    @property
    def build_s(self) -> float: ...

def build(sessions: Sequence[Union[str, Dataset]], voxel_size_m: float = 0.05,
          recorded_per_fused: float = 1.0, min_weight: float = 10.0,
          device: Union[None, int, str] = None) -> ObjectDatabase: ...

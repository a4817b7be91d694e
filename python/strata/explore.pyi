# Type stubs of strata.explore (see __init__.pyi).
from typing import Optional, Union

import numpy as np
import numpy.typing as npt

from . import Mesh

class ExplorationRun:
    @property
    def planner(self) -> str: ...
    @property
    def curve(self) -> npt.NDArray[np.float64]: ...  # N x 4
    @property
    def flown(self) -> npt.NDArray[np.float64]: ...  # M x 3
    @property
    def flown_time_s(self) -> npt.NDArray[np.float64]: ...  # M
    @property
    def start(self) -> npt.NDArray[np.float64]: ...  # 3
    @property
    def explored_fraction(self) -> float: ...
    @property
    def path_length_m(self) -> float: ...
    @property
    def sim_time_s(self) -> float: ...
    @property
    def wall_s(self) -> float: ...
    @property
    def start_clearing_fraction(self) -> float: ...
    @property
    def min_clearance_m(self) -> float: ...
    @property
    def collisions(self) -> int: ...
    @property
    def reachable_voxels(self) -> int: ...
    @property
    def planning_steps(self) -> int: ...
    @property
    def stop_reason(self) -> str: ...
    @property
    def mesh(self) -> Mesh: ...

def run(world: str = "room", planner: str = "history", time_limit_s: float = 60.0,
        voxel_size_m: Optional[float] = None, start: npt.ArrayLike = None, start_yaw_deg: float = 0.0,
        width: int = 160, height: int = 120, eval_period_s: float = 5.0, seed: int = 1,
        device: Union[None, int, str] = None) -> ExplorationRun: ...

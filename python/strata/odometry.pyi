# Type stubs of strata.odometry (see __init__.pyi).
from typing import List, Tuple

import numpy as np
import numpy.typing as npt

class VioRun:
    @property
    def stereo(self) -> bool: ...
    @property
    def trajectory(self) -> npt.NDArray[np.float64]: ...  # N x 8
    @property
    def truth(self) -> npt.NDArray[np.float64]: ...  # M x 8
    @property
    def frames_processed(self) -> int: ...
    @property
    def frames_tracked(self) -> int: ...
    @property
    def failures(self) -> List[Tuple[float, str]]: ...
    @property
    def imu_out_of_range(self) -> int: ...
    @property
    def wall_s(self) -> float: ...

def run_euroc(folder: str, mono: bool = False, frames: int = 0, window: int = 10) -> VioRun: ...

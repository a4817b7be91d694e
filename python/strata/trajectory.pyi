# Type stubs of strata.trajectory (see __init__.pyi).
import numpy as np
import numpy.typing as npt

class TrajectoryError:
    @property
    def matched(self) -> int: ...
    @property
    def ate_rmse_m(self) -> float: ...
    @property
    def ate_max_m(self) -> float: ...
    @property
    def path_length_m(self) -> float: ...
    @property
    def rpe_trans_percent(self) -> float: ...
    @property
    def rpe_rot_deg_per_m(self) -> float: ...
    @property
    def scale(self) -> float: ...
    @property
    def aligned_positions(self) -> npt.NDArray[np.float64]: ...  # N x 3
    @property
    def truth_positions(self) -> npt.NDArray[np.float64]: ...  # N x 3

# N x 8 arrays in TUM order (t, x, y, z, qx, qy, qz, qw); alignment "se3" or "sim3".
def evaluate(estimate: npt.ArrayLike, truth: npt.ArrayLike,
             alignment: str = "se3") -> TrajectoryError: ...

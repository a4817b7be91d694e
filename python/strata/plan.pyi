# Type stubs of strata.plan (see __init__.pyi).
import numpy as np
import numpy.typing as npt

from . import Mapper

class PlanResult:
    @property
    def success(self) -> bool: ...
    @property
    def message(self) -> str: ...
    @property
    def path(self) -> npt.NDArray[np.float64]: ...  # N x 3
    @property
    def length_m(self) -> float: ...
    @property
    def min_clearance_m(self) -> float: ...
    @property
    def planning_ms(self) -> float: ...
    @property
    def build_ms(self) -> float: ...
    @property
    def collision_checks(self) -> int: ...

# planner: "grid", "topo" or "rrt"; unknown: "occupied" or "free".
def plan(mapper: Mapper, start: npt.ArrayLike, goal: npt.ArrayLike, planner: str = "grid",
         radius_m: float = 0.3, unknown: str = "occupied", time_budget_s: float = 1.0,
         seed: int = 1) -> PlanResult: ...

# Type stubs of strata.sim (see __init__.pyi).
from typing import Dict, Optional, Union

import numpy as np
import numpy.typing as npt

from .io import Dataset

def session(world: str = "room", session: int = 0, frames: int = 30, rate_hz: float = 30.0,
            noise: bool = True) -> Dataset: ...
# T_W_S 4 x 4 (the true session-to-world), frames, frames_dropped
def drifted_session(source: str, out: str, first_frame: int = 0,
                    last_frame: Optional[int] = None, seed: int = 1, drift: bool = True,
                    offset: bool = True) -> Dict[str, Union[int, npt.NDArray[np.float64]]]: ...

# Type stubs of strata.sim (see __init__.pyi).
from .io import Dataset

def session(world: str = "room", session: int = 0, frames: int = 30, rate_hz: float = 30.0,
            noise: bool = True) -> Dataset: ...

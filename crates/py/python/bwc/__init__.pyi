import os
from typing import Any, Mapping, Optional, Sequence, Union
import numpy as np
import numpy.typing as npt

class BwcError(ValueError): ...
class BwcWarning(UserWarning): ...

def cor(
    model: str,
    params: Mapping[str, float],
    v0: Union[None, float, Sequence[float], npt.NDArray[np.float64]] = None,
    *,
    input: Optional[Mapping[str, Any]] = None,
    solver: Optional[Mapping[str, Any]] = None,
    sweep: Optional[Mapping[str, Any]] = None,
    threads: Optional[int] = None,
) -> dict: ...
def simulate(scene: Union[str, os.PathLike, Mapping[str, Any]], *, threads: Optional[int] = None) -> dict: ...
def identify(
    config: Union[str, os.PathLike, Mapping[str, Any]],
    *,
    seed: Optional[int] = None,
    threads: Optional[int] = None,
) -> dict: ...
def coverage(
    config: Union[str, os.PathLike, Mapping[str, Any]],
    *,
    replicates: int = 40,
    first_seed: int = 1,
    noise: Optional[float] = None,
    fit: Optional[str] = None,
    threads: Optional[int] = None,
) -> dict: ...

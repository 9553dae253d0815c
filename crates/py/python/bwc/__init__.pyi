import os
from typing import Any, Mapping, Optional, Sequence, Union
import numpy as np
import numpy.typing as npt

__version__: str

class BwcError(ValueError): ...
class BwcWarning(UserWarning): ...

class Result(dict):
    def __getattr__(self, name: str) -> Any: ...

class Params(Result): ...
class Cor(Result): ...
class Run(Result): ...
class Simulation(Result): ...
class Fit(Result): ...
class Identification(Result): ...
class Coverage(Result): ...

def cor(
    model: str,
    params: Mapping[str, Optional[float]],
    v0: Union[None, float, Sequence[float], npt.NDArray[np.float64]] = None,
    *,
    input: Optional[Mapping[str, Any]] = None,
    solver: Optional[Mapping[str, Any]] = None,
    sweep: Optional[Mapping[str, Any]] = None,
    threads: Optional[int] = None,
) -> Cor: ...
def simulate(scene: Union[str, os.PathLike, Mapping[str, Any]], *, threads: Optional[int] = None) -> Simulation: ...
def identify(
    config: Union[str, os.PathLike, Mapping[str, Any]],
    *,
    seed: Optional[int] = None,
    threads: Optional[int] = None,
) -> Identification: ...
def coverage(
    config: Union[str, os.PathLike, Mapping[str, Any]],
    *,
    replicates: int = 40,
    first_seed: int = 1,
    noise: Optional[float] = None,
    fit: Optional[str] = None,
    threads: Optional[int] = None,
) -> Coverage: ...

"""Type stubs of the native module (re-exported by ``brdf_kernels``)."""

import os
from typing import Any, Literal, Sequence, TypedDict, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

_Array = npt.NDArray[np.floating[Any]]
_ArrayLike = Union[npt.ArrayLike, float]
_Convention = Literal["reciprocal", "printed"]
_Distribution = Literal["beckmann", "ggx"]
_ParamValue = Union[float, Sequence[float], str]

class LutError(ValueError):
    """An invalid BLUT file or byte string, or a table that cannot be built from its spec."""

@overload
def g_modified(theta_i: float, theta_r: float, sigma: float, *, convention: _Convention = ..., nodes: int = ..., terms: Literal[False] = ...) -> float: ...
@overload
def g_modified(theta_i: _ArrayLike, theta_r: _ArrayLike, sigma: float, *, convention: _Convention = ..., nodes: int = ..., terms: Literal[False] = ...) -> Any: ...
@overload
def g_modified(theta_i: _ArrayLike, theta_r: _ArrayLike, sigma: float, *, convention: _Convention = ..., nodes: int = ..., terms: Literal[True]) -> tuple[Any, Any, Any]: ...
def g_modified_dots(n_i: _ArrayLike, n_o: _ArrayLike, i_o: _ArrayLike, sigma: float, *, convention: _Convention = ..., nodes: int = ..., terms: bool = ...) -> Any: ...
def g_blinn(theta_i: _ArrayLike, theta_r: _ArrayLike) -> Any: ...
def g_blinn_dots(n_i: _ArrayLike, n_o: _ArrayLike, i_o: _ArrayLike) -> Any: ...
def g_smith_separable(cos_i: _ArrayLike, cos_o: _ArrayLike, width: float, *, distribution: _Distribution = ...) -> Any: ...
def g_smith_correlated(cos_i: _ArrayLike, cos_o: _ArrayLike, width: float, *, distribution: _Distribution = ...) -> Any: ...
def eval(model: str, wi: npt.ArrayLike, wo: npt.ArrayLike, **params: _ParamValue) -> _Array: ...
def sample(model: str, wo: npt.ArrayLike, u: npt.ArrayLike, **params: _ParamValue) -> tuple[_Array, _Array, _Array]: ...
def albedo(model: str, wo: npt.ArrayLike, **params: _ParamValue) -> _Array: ...

class ParamInfo(TypedDict, total=False):
    name: str
    kind: Literal["scalar", "rgb", "choice"]
    unit: str
    range: str
    ui_range: tuple[float, float]
    default: Union[float, list[float], str]
    help: str
    channels: list[str]
    options: list[str]

class ModelInfo(TypedDict):
    name: str
    aliases: list[str]
    about: str
    lit_colour: bool
    has_delta: bool
    anisotropic: bool
    params: list[ParamInfo]

def models() -> list[ModelInfo]: ...

class Table:
    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Table: ...
    @staticmethod
    def from_bytes(data: bytes) -> Table: ...
    def save(self, path: Union[str, os.PathLike[str]]) -> None: ...
    def to_bytes(self) -> bytes: ...
    @property
    def header(self) -> dict[str, Any]: ...
    def lookup(self, *coords: _ArrayLike) -> _Array: ...

def build_table(spec: dict[str, Any]) -> Table: ...

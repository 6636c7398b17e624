"""Type stubs of morpho.dask (see the docstrings in dask.py)."""

from os import PathLike
from typing import Any, Dict, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

_F64 = npt.NDArray[np.float64]
_U32 = npt.NDArray[np.uint32]
_Path = Union[str, "PathLike[str]"]
_Method = Literal["decider", "tetra", "lorensen"]
_Normals = Literal["zucker", "central", "mesh", "none"]

@overload
def isosurface(
    darr: Any,
    level: Optional[float] = None,
    spacing: Union[float, Sequence[float]] = (1.0, 1.0, 1.0),
    origin: Union[float, Sequence[float]] = (0.0, 0.0, 0.0),
    method: _Method = "decider",
    normals: _Normals = "zucker",
    flip: bool = False,
    return_report: Literal[False] = False,
    value_range: Optional[Tuple[float, float]] = None,
    out: None = None,
) -> Tuple[_F64, _U32, Optional[_F64]]: ...
@overload
def isosurface(
    darr: Any,
    level: Optional[float] = None,
    spacing: Union[float, Sequence[float]] = (1.0, 1.0, 1.0),
    origin: Union[float, Sequence[float]] = (0.0, 0.0, 0.0),
    method: _Method = "decider",
    normals: _Normals = "zucker",
    flip: bool = False,
    *,
    return_report: Literal[True],
    value_range: Optional[Tuple[float, float]] = None,
    out: None = None,
) -> Tuple[_F64, _U32, Optional[_F64], Dict[str, Any]]: ...
@overload
def isosurface(
    darr: Any,
    level: Optional[float] = None,
    spacing: Union[float, Sequence[float]] = (1.0, 1.0, 1.0),
    origin: Union[float, Sequence[float]] = (0.0, 0.0, 0.0),
    method: _Method = "decider",
    normals: _Normals = "zucker",
    flip: bool = False,
    return_report: bool = False,
    value_range: Optional[Tuple[float, float]] = None,
    *,
    out: _Path,
) -> Dict[str, Any]: ...
def read_chunked(
    index: _Path, return_report: bool = False
) -> Union[Tuple[_F64, _U32, Optional[_F64]], Tuple[_F64, _U32, Optional[_F64], Dict[str, Any]]]: ...
def from_raw(
    path: _Path,
    shape: Sequence[int],
    dtype: npt.DTypeLike,
    chunks: Any = "auto",
    offset: int = 0,
) -> Any: ...

"""Type stubs of the morpho package (see the docstrings in __init__.py)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

_Coords = npt.ArrayLike
_F64 = npt.NDArray[np.float64]
_U32 = npt.NDArray[np.uint32]
_Path = Union[str, "PathLike[str]"]

GraphKind = Literal[
    "closest-pairs", "cp", "nng", "emst", "strip", "sig", "rng", "gabriel", "gg", "hull",
    "delaunay", "dt", "alpha", "beta-circle", "beta-lune", "gamma", "gamma-range",
]

def triangulate(points: _Coords) -> _U32: ...
def graph(
    points: _Coords,
    kind: GraphKind,
    *,
    a: float = ...,
    b: float = ...,
    c0: float = ...,
    c1: float = ...,
    range: Tuple[float, float, float, float] = ...,
) -> _U32: ...
def boundary(
    points: _Coords,
    method: Literal["gamma", "min-area-change", "voronoi-skeleton"] = "gamma",
    c: Union[Literal["auto"], float] = "auto",
    seeds: int = 200,
) -> _U32: ...
@overload
def isosurface(
    volume: npt.ArrayLike,
    level: Optional[float] = None,
    spacing: Union[float, Sequence[float]] = (1.0, 1.0, 1.0),
    origin: Union[float, Sequence[float]] = (0.0, 0.0, 0.0),
    method: Literal["decider", "tetra", "lorensen"] = "decider",
    normals: Literal["zucker", "central", "mesh", "none"] = "zucker",
    flip: bool = False,
    return_report: Literal[False] = False,
) -> Tuple[_F64, _U32, Optional[_F64]]: ...
@overload
def isosurface(
    volume: npt.ArrayLike,
    level: Optional[float] = None,
    spacing: Union[float, Sequence[float]] = (1.0, 1.0, 1.0),
    origin: Union[float, Sequence[float]] = (0.0, 0.0, 0.0),
    method: Literal["decider", "tetra", "lorensen"] = "decider",
    normals: Literal["zucker", "central", "mesh", "none"] = "zucker",
    flip: bool = False,
    *,
    return_report: Literal[True],
) -> Tuple[_F64, _U32, Optional[_F64], Dict[str, Any]]: ...
def contour(
    samples_xy: _Coords,
    values: npt.ArrayLike,
    threshold: float,
    rating: Literal["mean", "min", "max", "median", "area-mean"] = "mean",
    below: bool = False,
    holes: bool = False,
    min_area: float = 0.0,
) -> Union[List[_U32], _U32]: ...
def info(vertices: Any, faces: Optional[npt.ArrayLike] = None) -> Dict[str, Any]: ...
def curvature(
    vertices: Any,
    faces: Optional[npt.ArrayLike] = None,
    normals: Union[Literal["jet", "area", "uniform", "inverse"], npt.ArrayLike] = "jet",
    ring: Optional[int] = None,
    fit: Optional[Literal["jet", "paraboloid", "quadric"]] = None,
) -> Dict[str, Any]: ...
@overload
def reduce(
    vertices: Any,
    faces: Optional[npt.ArrayLike] = None,
    keep: Optional[float] = None,
    triangles: Optional[int] = None,
    rms: Optional[float] = None,
    max_error: Optional[float] = None,
    point: Literal["bivariate", "implicit"] = "bivariate",
    freeze_boundary: bool = False,
    normals: Union[Literal["area", "uniform", "inverse"], npt.ArrayLike] = "area",
    height_field: bool = False,
    new_triangles: Literal["generations", "last-step"] = "generations",
    order: Literal["levels", "hamann"] = "levels",
    return_report: Literal[False] = False,
) -> Tuple[_F64, _U32]: ...
@overload
def reduce(
    vertices: Any,
    faces: Optional[npt.ArrayLike] = None,
    keep: Optional[float] = None,
    triangles: Optional[int] = None,
    rms: Optional[float] = None,
    max_error: Optional[float] = None,
    point: Literal["bivariate", "implicit"] = "bivariate",
    freeze_boundary: bool = False,
    normals: Union[Literal["area", "uniform", "inverse"], npt.ArrayLike] = "area",
    height_field: bool = False,
    new_triangles: Literal["generations", "last-step"] = "generations",
    order: Literal["levels", "hamann"] = "levels",
    *,
    return_report: Literal[True],
) -> Tuple[_F64, _U32, Dict[str, Any]]: ...
@overload
def smooth(
    vertices: Any,
    faces: Optional[npt.ArrayLike] = None,
    normals: Union[Literal["area", "uniform", "inverse"], npt.ArrayLike] = "area",
    folds: Literal["guard", "keep"] = "guard",
    density: Optional[int] = None,
    return_report: Literal[False] = False,
) -> Tuple[_F64, _U32, _F64]: ...
@overload
def smooth(
    vertices: Any,
    faces: Optional[npt.ArrayLike] = None,
    normals: Union[Literal["area", "uniform", "inverse"], npt.ArrayLike] = "area",
    folds: Literal["guard", "keep"] = "guard",
    density: Optional[int] = None,
    *,
    return_report: Literal[True],
) -> Tuple[_F64, _U32, _F64, Dict[str, Any]]: ...
def read(path: _Path) -> Dict[str, Any]: ...
def write(
    path: _Path, data: Optional[Mapping[str, Any]] = None, ascii: bool = False, **arrays: Any
) -> None: ...

class FlintTree:
    """The flintstone tree of a polygon (closed=True) or polyline."""

    def __init__(self, points: npt.NDArray[np.float64], closed: bool = True) -> None: ...
    def __len__(self) -> int: ...
    @property
    def node_count(self) -> int: ...
    @property
    def depth(self) -> int: ...
    @property
    def closed(self) -> bool: ...
    def approx(
        self,
        level: Optional[int] = None,
        error: Optional[float] = None,
        count: Optional[int] = None,
        method: Literal["flintstone", "dp", "strip", "blg", "arc"] = "flintstone",
    ) -> Dict[str, Any]: ...
    def contains(self, queries: npt.NDArray[np.float64]) -> npt.NDArray[np.int8]: ...

def flint(points: _Coords, closed: bool = True) -> FlintTree: ...
from . import dask as dask

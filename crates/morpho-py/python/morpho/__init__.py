"""morpho — computational morphology from Python (the Rust library ``morpho`` through PyO3).

Shapes from scattered points, samples and volumes: Delaunay triangulations, geometric graphs
(γ-graph, α-shapes, β-skeletons, …), boundaries through all points (γ-constriction), contour
surfaces of volumes (marching cubes with the asymptotic decider, consistent), region contours of
rated samples, flintstone trees, curvature of meshes, triangle reduction, smooth G¹ surfaces,
and every morpho file format.
Contour surfaces of chunked volumes larger than memory, on Dask: ``morpho.dask.isosurface``.

Arrays
------
* Coordinates are ``(n, 2)`` or ``(n, 3)`` arrays. A C-contiguous ``float64`` array is passed to
  Rust **without a copy**; any other real dtype (ints, float32) or layout (Fortran order,
  slices with strides) is **copied** once into a C-contiguous ``float64`` array. Non-numeric
  dtypes (complex, object, str, bool), a wrong number of dimensions or columns, and NaN/inf
  coordinates raise ``ValueError``.
* Index results (triangles, edges, rings) are ``uint32`` arrays that own the library's buffers
  (no copy); coordinates are ``float64``.
* Volumes: ``volume[i, j, k]`` is the sample at index ``(i, j, k)`` and a vertex is
  ``origin + (i, j, k) * spacing`` in that column order, as in ``skimage.measure.marching_cubes``.
  Any integer or float dtype, any layout; the samples are converted to ``float32`` (the
  library's sample type) in one pass.

The GIL is released while Rust computes (``threading`` gives real parallelism); errors are
``ValueError`` for bad input, ``OSError`` for files, ``RuntimeError`` otherwise, with the
library's message; an internal panic is a ``RuntimeError``, never an abort.
"""

from __future__ import annotations

import numpy as _np

from . import _morpho
from ._morpho import FlintTree, __version__

__all__ = [
    "triangulate",
    "graph",
    "boundary",
    "isosurface",
    "contour",
    "info",
    "curvature",
    "reduce",
    "smooth",
    "read",
    "write",
    "FlintTree",
    "flint",
    "__version__",
]


def _coords(a, what="points", dims=(2, 3)):
    """``a`` as a C-contiguous float64 ``(n, d)`` array (no copy when it already is one)."""
    if not isinstance(a, _np.ndarray):
        try:
            a = _np.asarray(a)
        except (ValueError, TypeError) as e:  # ragged lists
            raise ValueError(f"{what}: not an array of coordinates ({e})") from None
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{what}: expected real numbers, got an array of dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] not in dims:
        want = " or ".join(f"(n, {d})" for d in dims)
        raise ValueError(f"{what}: expected an array of shape {want}, got {a.shape}")
    return _np.ascontiguousarray(a, dtype=_np.float64)


def _values(a, n, what="values"):
    a = _np.asarray(a)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{what}: expected real numbers, got an array of dtype {a.dtype}")
    if a.ndim != 1 or a.shape[0] != n:
        raise ValueError(f"{what}: expected an array of shape ({n},), got {a.shape}")
    return _np.ascontiguousarray(a, dtype=_np.float64)


def _faces(f, what="faces"):
    f = _np.asarray(f)
    if f.dtype.kind not in "iu":
        raise ValueError(f"{what}: expected integer indices, got an array of dtype {f.dtype}")
    if f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"{what}: expected an array of shape (m, 3), got {f.shape}")
    return _np.ascontiguousarray(f, dtype=_np.int64)


def _mesh(vertices, faces):
    """(vertices, faces) from arrays or from a mesh object with ``.vertices``/``.faces``."""
    if faces is None:
        if hasattr(vertices, "vertices") and hasattr(vertices, "faces"):
            vertices, faces = vertices.vertices, vertices.faces
        else:
            raise ValueError("a mesh is (vertices, faces) or an object with .vertices and .faces")
    return _coords(vertices, "vertices", (3,)), _faces(faces)


def triangulate(points):
    """Delaunay triangulation of 2D or 3D points.

    ``points``: ``(n, 2)`` or ``(n, 3)``. Returns ``(m, 3)`` triangles (2D, counter-clockwise)
    or ``(m, 4)`` tetrahedra (3D) as ``uint32`` indices into ``points``; a duplicate point is
    represented by its first occurrence. Exact predicates with symbolic perturbation: the result
    does not depend on the input order. Collinear (coplanar) input gives no simplices.
    """
    return _morpho.triangulate(_coords(points))


def graph(points, kind, **params):
    """A geometric graph of the points (Veltkamp 1992, ch. 2–3): ``(k, 2)`` uint32 edges.

    ``kind``: ``closest-pairs``, ``nng``, ``emst``, ``strip``, ``sig``, ``rng``, ``gabriel``,
    ``hull``, ``delaunay``, ``alpha`` (``a=``), ``beta-circle``/``beta-lune`` (``b=``),
    ``gamma`` (``c0=``, ``c1=``), ``gamma-range`` (``range=(c0, c1, c2, c3)``).
    """
    unknown = set(params) - {"a", "b", "c0", "c1", "range"}
    if unknown:
        raise ValueError(f"graph: unknown parameter(s) {sorted(unknown)}")
    r = params.get("range")
    if r is not None:
        r = tuple(float(x) for x in r)
        if len(r) != 4:
            raise ValueError("graph: range must be four numbers (c0, c1, c2, c3)")
    return _morpho.graph(
        _coords(points), str(kind), params.get("a"), params.get("b"),
        params.get("c0"), params.get("c1"), r,
    )


def boundary(points, method="gamma", c="auto", seeds=200):
    """The boundary through all scattered points (Veltkamp 1992, ch. 4–5).

    2D: a simple polygon, ``(n,)`` uint32 indices in boundary order. 3D: a closed genus-0 mesh,
    ``(m, 3)`` uint32 triangles (vertices are the input points). ``method``: ``gamma``
    (γ-constriction), ``min-area-change``, ``voronoi-skeleton`` (``seeds`` tried); ``c``:
    ``"auto"`` or a number in [−1, 0]. When not every point could be put on the boundary the
    best valid result is returned with a ``RuntimeWarning``.
    """
    return _morpho.boundary(_coords(points), str(method), c, int(seeds))


def isosurface(volume, level=None, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0),
               method="decider", normals="zucker", flip=False, return_report=False):
    """The contour surface ``volume == level`` (Hamann 1991, §3.2–3.4).

    A drop-in for ``skimage.measure.marching_cubes(volume, level, spacing=…)``: ``volume[i, j, k]``,
    vertices ``origin + (i, j, k) * spacing``, ``level=None`` is the middle of the data range.
    Returns ``(vertices (n, 3) float64, faces (m, 3) uint32, normals (n, 3) float64 or None)``
    (and a dict of figures — parts, boundary edges, holes — with ``return_report=True``).
    ``method``: ``decider`` (marching cubes with the asymptotic decider: consistent, no holes),
    ``tetra`` (six tetrahedra per cell), ``lorensen`` (the original table; may leave holes).
    ``normals``: ``zucker`` (Zucker–Hummel gradient), ``central``, ``mesh``, ``none``.
    Triangles are counter-clockwise seen from the side below the level (outside of the region
    above it) and normals point there; ``flip=True`` reverses both. NaN samples: their cells are
    skipped. A level outside the data range gives an empty mesh.
    """
    if not isinstance(volume, _np.ndarray):
        volume = _np.asarray(volume)
    if volume.ndim != 3:
        raise ValueError(f"volume: expected a 3D array, got shape {volume.shape}")
    if volume.dtype == _np.bool_:
        volume = volume.view(_np.uint8)
    if level is None:
        if volume.dtype.kind not in "iuf":
            raise ValueError(f"volume: expected integers or floats, got dtype {volume.dtype}")
        level = (float(_np.nanmin(volume)) + float(_np.nanmax(volume))) / 2.0
    sp = tuple(float(s) for s in _np.broadcast_to(_np.asarray(spacing, dtype=float), (3,)))
    org = tuple(float(s) for s in _np.broadcast_to(_np.asarray(origin, dtype=float), (3,)))
    return _morpho.isosurface(volume, float(level), sp, org, str(method), str(normals),
                              bool(flip), bool(return_report))


def contour(samples_xy, values, threshold, rating="mean", below=False, holes=False,
            min_area=0.0):
    """Regions where the rated samples are above (``below=True``: below) ``threshold``.

    The samples are triangulated (Delaunay), each triangle rated from its corner values
    (``rating``: ``mean``, ``min``, ``max``, ``median``, ``area-mean``), and the external
    contour of the black triangles traced (Dorgerloh et al.). 2D samples: a list of rings, each a
    ``(k,)`` uint32 array of sample indices (outer rings counter-clockwise; with ``holes=True``
    the holes too, clockwise); ``min_area`` drops small regions. 3D samples: ``(m, 3)``
    triangles of the external surfaces. NaN values: those samples are skipped.
    """
    pts = _coords(samples_xy, "samples")
    return _morpho.contour(pts, _values(values, pts.shape[0]), float(threshold), str(rating),
                           bool(below), bool(holes), float(min_area))


def info(vertices, faces=None):
    """Topology and figures of a triangle mesh, the keys of ``morpho info``'s report.

    ``info(vertices, faces)`` or ``info(mesh)`` for an object with ``.vertices``/``.faces``
    (e.g. a ``trimesh.Trimesh``). Keys: vertices, used_vertices, triangles, edges, parts,
    boundary_loops, boundary_edges, euler_characteristic, genus (None unless an orientable
    manifold), manifold, orientable, consistently_oriented, closed, non_manifold_edges,
    non_manifold_vertices, bbox, area, signed_volume.
    """
    v, f = _mesh(vertices, faces)
    return _morpho.info(v, f)


def curvature(vertices, faces=None, normals="jet", ring=None, fit=None):
    """Per-vertex curvature by a local surface fit (Hamann 1991, §4.2); the CLI's options.

    ``normals``: ``jet`` (default: area-weighted normals, and with the default fit the jet's
    own curvature, as ``morpho curvature``), ``area``/``uniform``/``inverse`` (estimated, V §9.4
    weightings; ``area`` with the default fit and ring is the thesis's method) or an ``(n, 3)``
    array. ``fit``: ``jet`` (default with ``normals="jet"``: the quartic jet over the 2-ring,
    its curvature at the vertex), ``paraboloid`` (the thesis's osculating paraboloid; the
    default otherwise; after jet-corrected normals with ``normals="jet"``) or ``quadric`` (with
    linear terms). ``ring``: neighbourhood size (default 1 for the paraboloid, 2 otherwise).
    Returns a dict of arrays ``k1, k2, H, K, A``, ``dir1, dir2, normals``,
    ``status`` (0 ok; otherwise the curvatures are NaN), ``undetermined`` (count) and, with
    jet normals, ``jet_fallbacks``. ``curvature(mesh)`` takes a mesh object too.
    """
    v, f = _mesh(vertices, faces)
    if not isinstance(normals, str):
        normals = _coords(normals, "normals", (3,))
    return _morpho.curvature(v, f, normals, None if ring is None else int(ring), fit)


def reduce(vertices, faces=None, keep=None, triangles=None, rms=None, max_error=None,
           point="bivariate", freeze_boundary=False, normals="area", height_field=False,
           new_triangles="generations", order="levels", return_report=False):
    """Triangle reduction (Hamann 1991 ch. 5, Alg. 5.1), as ``morpho reduce``.

    Give exactly one stop: ``keep`` (percent of the triangles), ``triangles`` (a count),
    ``rms`` or ``max_error`` (tolerances at the input's vertices). ``point``: ``bivariate``
    (H (5.29)) or ``implicit`` (H (5.33)); ``freeze_boundary``: never remove a triangle with a
    corner on the boundary; ``normals``: ``area``/``uniform``/``inverse`` or an ``(n, 3)``
    array (the curvature fit's normals); ``height_field``: the mesh is z = f(x, y) (errors are
    vertical); ``order``: ``levels`` (Hamann's weight order within doubling error levels, the
    command's default) or ``hamann`` (Alg. 5.1's order alone). Returns ``(vertices, faces)`` — the command's output bit for bit — and with
    ``return_report=True`` a dict (``source``: the input vertex each output vertex inherits,
    ``removals``, ``stop``, ``rms``, ``max_error``). ``reduce(mesh, keep=…)`` takes a mesh
    object too.
    """
    v, f = _mesh(vertices, faces)
    if not isinstance(normals, str):
        normals = _coords(normals, "normals", (3,))
    if triangles is not None:
        triangles = int(triangles)
        if triangles < 0:
            raise ValueError(f"reduce: triangles must be a count, got {triangles}")
    num = lambda x: None if x is None else float(x)
    return _morpho.reduce(v, f, num(keep), triangles, num(rms), num(max_error), str(point),
                          bool(freeze_boundary), normals, bool(height_field),
                          str(new_triangles), str(order), bool(return_report))


def smooth(vertices, faces=None, normals="area", folds="guard", density=None,
           return_report=False):
    """The cubic three-split G¹ surface through a closed mesh (Veltkamp 1992, §9.6),
    tessellated, as ``morpho smooth --scheme split3``.

    The mesh must be a closed, consistently oriented 2-manifold. ``normals``: the vertex
    normals the surface interpolates, ``area``/``uniform``/``inverse`` or an ``(n, 3)`` array;
    ``folds="guard"`` repairs normals that do not see all their triangles and keeps a cubic
    boundary where a quadratic one would fold (``"keep"``: the text's construction as is);
    ``density``: steps per micro-patch edge (``None``: 8, fewer on big meshes). Returns
    ``(vertices, faces, normals)`` of the tessellation (surface normals), and with
    ``return_report=True`` a dict (patches, singular and unresolved edges, max normal jump, …).
    """
    v, f = _mesh(vertices, faces)
    if not isinstance(normals, str):
        normals = _coords(normals, "normals", (3,))
    if density is not None:
        density = int(density)
        if density < 1:
            raise ValueError(f"smooth: density must be at least 1, got {density}")
    return _morpho.smooth(v, f, normals, str(folds), density, bool(return_report))


def read(path):
    """Reads any file morpho reads (format by extension) into a dict of arrays.

    ``kind`` is ``points`` (``points``, ``columns``), ``mesh`` (``vertices``, ``faces``,
    ``normals`` when present, ``vertex_properties``, ``face_properties``), ``volume``
    (``volume`` float32 indexed ``[x, y, z]`` — Fortran order, the file's buffer without a copy —
    ``spacing``, ``origin``; so ``isosurface(d["volume"], level, spacing=d["spacing"],
    origin=d["origin"])`` equals ``morpho isosurface``) or ``shapes`` (``polygons``,
    ``polylines``).
    """
    import os

    return _morpho.read(os.fspath(path))


def write(path, data=None, ascii=False, **arrays):
    """Writes points, a mesh, a volume or polygons (format by extension), atomically.

    ``write(path, read(other))`` converts; or by keywords: ``write("m.ply", vertices=v,
    faces=f, normals=n)``, ``write("p.csv", points=p, columns={"value": z})``,
    ``write("v.nrrd", volume=vol, spacing=(…), origin=(…))`` (``vol[x, y, z]``, any layout),
    ``write("p.geojson", polygons=[[ring, …], …])``. Meshes may carry extra columns,
    ``vertex_properties={name: (n,) array}`` and ``face_properties={name: (m,) array}`` (PLY:
    written with their dtype when PLY has it — (u)int8/16/32, float32 — else as float64).
    """
    import os

    d = dict(data or {})
    d.update(arrays)
    d.pop("kind", None)
    out = {}
    for k, v in d.items():
        if k in ("points", "vertices", "normals") and v is not None:
            v = _coords(v, k, (2, 3) if k == "points" else (3,))
        elif k == "faces":
            v = _faces(v)
        elif k == "columns":
            v = {str(c): _values(x, len(x), c) for c, x in v.items()}
        elif k in ("polygons",):
            v = [[_coords(r, "ring", (2,)) for r in poly] for poly in v]
        elif k in ("polylines",):
            v = [_coords(r, "polyline", (2,)) for r in v]
        elif k in ("vertex_properties", "face_properties") and v is not None:
            v = {str(name): _prop(x, f"{k[:-11]} property {name}") for name, x in v.items()}
        elif k == "volume":
            v = _np.asarray(v)
            if v.ndim != 3:
                raise ValueError(f"volume: expected a 3D array, got shape {v.shape}")
        out[k] = v
    return _morpho.write(os.fspath(path), out, bool(ascii))


def _prop(a, what):
    """A property column: 1D, its own dtype when PLY has it, else float64."""
    a = _np.asarray(a)
    if a.ndim != 1 or a.dtype.kind not in "iuf":
        raise ValueError(f"{what}: expected a 1D array of numbers, got {a.dtype} {a.shape}")
    if a.dtype not in (_np.uint8, _np.int8, _np.uint16, _np.int16, _np.uint32, _np.int32,
                       _np.float32, _np.float64):
        a = a.astype(_np.float64)
    return _np.ascontiguousarray(a)


def __getattr__(name):
    # ``morpho.dask`` (chunked contour surfaces) is imported on first use: it needs dask.
    if name == "dask":
        import importlib

        return importlib.import_module(".dask", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def flint(points, closed=True):
    """The flintstone tree of a polygon (``closed=True``) or polyline, ``(n, 2)`` vertices
    (Veltkamp 1992, ch. 6–7, Alg. 7.1): a :class:`FlintTree` with ``approx(level=|error=|count=,
    method=)`` and ``contains(queries)``."""
    return FlintTree(_coords(points, "points", (2,)), bool(closed))

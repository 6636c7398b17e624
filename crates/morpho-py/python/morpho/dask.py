"""Contour surfaces of chunked volumes on Dask (issue 24 part 3).

``morpho.dask.isosurface(darr, level, …)`` contours a 3D Dask array chunk by chunk — each chunk,
with the one-sample halo its cells and their gradients need, is contoured by the Rust library in
a worker (threads, processes or a ``dask.distributed`` cluster: whatever scheduler is active) —
and stitches the chunks into one mesh **identical** to ``morpho.isosurface(np.asarray(darr),
level, …)``: the same vertices (bit for bit, in the same order), the same triangles, the same
normals. With ``out="mesh.json"`` nothing is gathered: every worker writes its chunk's part
(``mesh.part-I-J-K.ply``) and the client writes the JSON index; :func:`read_chunked` stitches
the parts into the same single mesh.

How: vertices are named by a global id from the grid entity they lie on (an edge or diagonal of
the whole array's grid), and everything computed for a cell depends only on its own samples (the
asymptotic decider's choice on a face only on that face's four samples), the perturbation ε of
samples equal to the level (from the *whole* array's range, computed in a first pass) and the
gradient stencils of its corners (the halo). Stitching is a concatenation, a sort by id, a merge
of equal ids (checked to agree bit for bit) and a renumbering of the triangles.

Conventions are those of :func:`morpho.isosurface` for a C-ordered array: ``darr[i, j, k]``,
vertices ``origin + (i, j, k) * spacing``. (A Fortran-ordered numpy array given to
``morpho.isosurface`` is read with x = axis 0; its surface is the same but may be triangulated
differently inside cells, so the reference is ``np.ascontiguousarray(volume)``.) Chunk samples
of any integer or float dtype (bool as uint8) are converted to float32 in the worker; NaN samples
are handled as by ``morpho.isosurface`` (their cells are skipped).

Memory: a worker holds one chunk plus its halo and that chunk's part of the surface; the
single-mesh mode gathers every part on the client (about twice the final mesh while stitching).
Two passes over the data: one for the finite sample range (skipped when ``value_range`` is
given), one for the contour.
"""

from __future__ import annotations

import json
import math
import os

import numpy as _np

from . import _morpho

__all__ = ["isosurface", "read_chunked", "from_raw"]

_METHODS = ("decider", "tetra", "lorensen")
_NORMALS = ("zucker", "central", "mesh", "none")


def _as_dask(darr):
    import dask.array as da

    if not isinstance(darr, da.Array):
        if not hasattr(darr, "shape") or not hasattr(darr, "dtype"):
            darr = _np.asarray(darr)
        darr = da.from_array(darr)
    if darr.ndim != 3:
        raise ValueError(f"volume: expected a 3D array, got shape {darr.shape}")
    if darr.dtype == _np.bool_:
        darr = darr.astype(_np.uint8)
    if darr.dtype.kind not in "iuf":
        raise ValueError(
            f"volume: expected a 3D array of integers or floats, got dtype {darr.dtype}"
        )
    if any(math.isnan(c) for cs in darr.chunks for c in cs):
        raise ValueError("volume: the chunk sizes are unknown (call compute_chunk_sizes())")
    return darr


def _three(v, what):
    try:
        t = _np.broadcast_to(_np.asarray(v, dtype=float), (3,))
    except (ValueError, TypeError):
        raise ValueError(f"{what}: expected a number or three numbers, got {v!r}") from None
    return tuple(float(s) for s in t)


def _plan(shape, chunks):
    """For each chunk (index (a, b, c)): the samples it needs (lo, hi per axis) and the cells it
    owns (half-open per axis); chunks without cells are left out."""
    per_axis = []
    for n, cs in zip(shape, chunks):
        axis = []
        s = 0
        for t, c in enumerate(cs):
            e = s + c
            c0, c1 = s, min(e, n - 1)
            if c0 < c1:
                axis.append((t, (max(c0 - 1, 0), min(c1 + 2, n)), (c0, c1)))
            s = e
        per_axis.append(axis)
    plan = []
    for a in per_axis[0]:
        for b in per_axis[1]:
            for c in per_axis[2]:
                idx = (a[0], b[0], c[0])
                lo = (a[1][0], b[1][0], c[1][0])
                hi = (a[1][1], b[1][1], c[1][1])
                cells = (a[2], b[2], c[2])
                plan.append((idx, lo, hi, cells))
    return plan


def _assemble(pieces, counts):
    """The block from its pieces (flat, C order of a ``counts`` grid of neighbour slabs)."""
    if len(pieces) == 1:
        return _np.asarray(pieces[0])
    n0, n1, n2 = counts
    it = iter(pieces)
    nested = [[[_np.asarray(next(it)) for _ in range(n2)] for _ in range(n1)] for _ in range(n0)]
    return _np.block(nested)


def _contour(pieces, counts, shape, lo, cells, rng, args):
    return _morpho._isosurface_block(_assemble(pieces, counts), shape, lo, cells, rng, *args)


def _tasks(darr, plan, func, token, **kw):
    """One task per planned block, ``func(pieces, counts, lo=…, cells=…, **kw)``, reading the
    block's samples from the chunks it overlaps: the chunk itself whole, its neighbours through
    small slicing tasks (only the halo slabs travel between workers). A hand-made graph: one
    layer for all blocks, whatever their number."""
    import functools
    import operator

    from dask.delayed import Delayed
    from dask.highlevelgraph import HighLevelGraph

    starts = [_np.cumsum((0,) + tuple(c)) for c in darr.chunks]
    name = f"morpho-{func.__name__.strip('_')}-{token}"
    halo = f"morpho-halo-{token}"
    layer = {}
    keys = []
    for idx, lo, hi, cells in plan:
        axes = []
        for a in range(3):
            st = starts[a]
            t0 = int(_np.searchsorted(st, lo[a], side="right")) - 1
            t1 = int(_np.searchsorted(st, hi[a], side="left"))
            axes.append([(t, slice(max(lo[a], st[t]) - st[t], min(hi[a], st[t + 1]) - st[t]),
                          st[t + 1] - st[t]) for t in range(t0, t1)])
        pieces = []
        for t0, s0, n0 in axes[0]:
            for t1, s1, n1 in axes[1]:
                for t2, s2, n2 in axes[2]:
                    src = (darr.name, t0, t1, t2)
                    sl = (s0, s1, s2)
                    if all(s.start == 0 and s.stop == n for s, n in zip(sl, (n0, n1, n2))):
                        pieces.append(src)
                    else:
                        k = (halo, *idx, t0, t1, t2)
                        layer[k] = (operator.getitem, src, sl)
                        pieces.append(k)
        counts = tuple(len(ax) for ax in axes)
        key = (name, *idx)
        layer[key] = (functools.partial(func, counts=counts, lo=lo, cells=cells, **kw), pieces)
        keys.append(key)
    graph = HighLevelGraph.from_collections(name, layer, dependencies=[darr])
    return [Delayed(k, graph, layer=name) for k in keys]


def _ranges(darr, token):
    """The finite range of each chunk (tasks)."""
    from dask.delayed import Delayed
    from dask.highlevelgraph import HighLevelGraph

    name = f"morpho-range-{token}"
    import itertools

    layer = {(name, *t): (_morpho._block_range, (darr.name, *t))
             for t in itertools.product(*(range(len(c)) for c in darr.chunks))}
    graph = HighLevelGraph.from_collections(name, layer, dependencies=[darr])
    return [Delayed(k, graph, layer=name) for k in layer]


def _split64(a):
    a = _np.asarray(a, dtype=_np.uint64)
    return (a >> _np.uint64(32)).astype(_np.uint32), (a & _np.uint64(0xFFFFFFFF)).astype(_np.uint32)


def _join64(hi, lo):
    hi = _np.asarray(hi).astype(_np.uint64)
    lo = _np.asarray(lo).astype(_np.uint64)
    return (hi << _np.uint64(32)) | lo


def _contour_part(pieces, counts, shape, lo, cells, rng, args, stem):
    """Contours a chunk and writes its part (a PLY with the global vertex ids and the cells of
    the faces as properties); returns the part's entry of the index."""
    from . import write

    b = _contour(pieces, counts, shape, lo, cells, rng, args)
    path = "{}.part-{}.ply".format(stem, "-".join(str(c[0]) for c in cells))
    ids, v, f, fc = b[0], b[1], b[3], b[4]
    entry = {
        "file": None,
        "cells": [list(c) for c in cells],
        "vertices": int(len(v)),
        "faces": int(len(f)),
        "nan_cells": [int(c) for c in b[5]],
        "fan_points": int(b[6]),
        "centroid_fallbacks": int(b[7]),
        "zero_normals": bool(b[8]),
    }
    if len(v) or len(f):
        ih, il = _split64(ids)
        ch, cl = _split64(fc)
        write(path, vertices=v, faces=f, normals=b[2],
              vertex_properties={"id_hi": ih, "id_lo": il},
              face_properties={"cell_hi": ch, "cell_lo": cl})
        entry["file"] = os.path.basename(path)
    return entry


def isosurface(darr, level=None, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0),
               method="decider", normals="zucker", flip=False, return_report=False,
               value_range=None, out=None):
    """The contour surface ``darr == level`` of a 3D Dask array, chunk by chunk.

    Arguments as :func:`morpho.isosurface` (``level=None``: the middle of the data range).
    ``darr``: a ``dask.array.Array`` (from Zarr, a memory map, …; a numpy array is wrapped
    with ``dask.array.from_array``). The tasks run on the active Dask scheduler (a
    ``dask.distributed.Client`` when one is the default). ``value_range``: the smallest and
    largest finite sample (as float32) when known, which saves the first pass.

    Returns ``(vertices, faces, normals)`` (and the report dict with ``return_report=True``),
    identical to ``morpho.isosurface(np.asarray(darr), level, …)``. With ``out="dir/mesh.json"``
    the surface is written as a chunked mesh instead — one PLY part per chunk
    (``dir/mesh.part-I-J-K.ply``, I, J, K the chunk's first cell; written by the workers, so
    ``dir`` must be visible to them; vertex properties ``id_hi``/``id_lo`` are the global
    vertex id, face properties ``cell_hi``/``cell_lo`` the cell) and the JSON index — and the
    index (a dict) is returned; :func:`read_chunked` stitches it.
    """
    import dask

    darr = _as_dask(darr)
    if method not in _METHODS:
        raise ValueError(f"unknown isosurface method '{method}': use decider, tetra or lorensen")
    if normals not in _NORMALS:
        raise ValueError(f"unknown normals '{normals}': use zucker, central, mesh or none")
    sp, org = _three(spacing, "spacing"), _three(origin, "origin")
    shape = tuple(int(n) for n in darr.shape)
    # the library's checks of level, spacing, origin and shape, before any data is read
    lvl = 0.0 if level is None else float(level)
    _morpho._stitch_blocks(shape, [], None, lvl, sp, org, method, normals, bool(flip))
    degenerate = min(shape) < 2
    from dask.base import tokenize

    token = tokenize(darr, level, sp, org, method, normals, bool(flip), value_range, out)
    todo = []
    if value_range is None and not degenerate:
        todo.append(_ranges(darr, token))
    if level is None:
        import dask.array as da

        todo += [da.nanmin(darr), da.nanmax(darr)]
    got = list(dask.compute(*todo)) if todo else []
    if degenerate:
        value_range = None
    elif value_range is None:
        rs = [r for r in got.pop(0) if r is not None]
        value_range = (min(r[0] for r in rs), max(r[1] for r in rs)) if rs else None
    else:
        value_range = (float(_np.float32(value_range[0])), float(_np.float32(value_range[1])))
    if level is None:
        level = (float(got[0]) + float(got[1])) / 2.0
    args = (float(level), sp, org, method, normals, bool(flip))
    plan = [] if degenerate else _plan(shape, darr.chunks)
    kw = dict(shape=shape, rng=value_range, args=args)
    if out is None:
        blocks = list(dask.compute(*_tasks(darr, plan, _contour, token, **kw)))
        return _morpho._stitch_blocks(shape, blocks, value_range, *args, bool(return_report))
    out = os.fspath(out)
    stem = os.path.splitext(out)[0]
    parts = list(dask.compute(*_tasks(darr, plan, _contour_part, token, stem=stem, **kw)))
    index = {
        "format": "morpho-chunked-mesh",
        "version": 1,
        "shape": list(shape),
        "chunks": [list(c) for c in darr.chunks],
        "level": float(level),
        "value_range": None if value_range is None else list(value_range),
        "spacing": list(sp),
        "origin": list(org),
        "method": method,
        "normals": normals,
        "flip": bool(flip),
        "vertices_total": sum(p["vertices"] for p in parts),
        "faces": sum(p["faces"] for p in parts),
        "parts": parts,
    }
    tmp = out + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(index, fh, indent=1)
    os.replace(tmp, out)
    return index


def _raw_block(block, path, dtype, shape, offset, block_info=None):
    loc = block_info[None]["array-location"]
    mm = _np.memmap(path, dtype=dtype, mode="r", shape=shape, offset=offset)
    return _np.array(mm[tuple(slice(a, b) for a, b in loc)])


def from_raw(path, shape, dtype, chunks="auto", offset=0):
    """A headerless raw file (C order: the last axis varies fastest — a volume stored x fastest
    is ``shape=(nz, ny, nx)``) as a Dask array whose chunks are read by memory-mapping the file
    **in the worker**: nothing but the path travels, so it suits ``dask.distributed``
    (``da.from_array(np.memmap(…))`` would ship the whole map to the workers). ``offset``: bytes
    to skip (e.g. an attached NRRD header with raw encoding); ``dtype`` e.g. ``"<u2"``."""
    import dask.array as da

    path = os.path.abspath(os.fspath(path))
    dtype = _np.dtype(dtype)
    shape = tuple(int(n) for n in shape)
    need = offset + dtype.itemsize * int(_np.prod(shape))
    size = os.path.getsize(path)
    if size < need:
        raise ValueError(f"{path}: {size} bytes, a {shape} {dtype} volume needs {need}")
    tmpl = da.empty(shape, dtype=dtype, chunks=chunks)
    # the file's dtype goes positionally: map_blocks' own ``dtype`` is the result's
    return tmpl.map_blocks(_raw_block, path, dtype, shape, int(offset), dtype=dtype,
                           meta=_np.empty((0,) * len(shape), dtype))


def read_chunked(index, return_report=False):
    """The single mesh of a chunked mesh written by ``isosurface(…, out=index)``:
    ``(vertices, faces, normals)`` as ``isosurface`` returns them (stitched by global vertex
    id; identical to the single-machine result). Needs the whole mesh in memory."""
    from . import read

    index = os.fspath(index)
    with open(index) as fh:
        try:
            ix = json.load(fh)
        except ValueError:
            ix = None
    if not isinstance(ix, dict) or ix.get("format") != "morpho-chunked-mesh":
        raise ValueError(f"{index}: not the index of a morpho chunked mesh")
    folder = os.path.dirname(index)
    blocks = []
    for p in ix["parts"]:
        nan = _np.asarray(p["nan_cells"], dtype=_np.uint64)
        fan, cen, zero = int(p["fan_points"]), int(p["centroid_fallbacks"]), bool(p["zero_normals"])
        if p["file"] is None:
            e3 = _np.zeros((0, 3))
            n = None if ix["normals"] in ("mesh", "none") else e3
            blocks.append((_np.zeros(0, _np.uint64), e3, n, _np.zeros((0, 3), _np.uint32),
                           _np.zeros(0, _np.uint64), nan, fan, cen, zero))
            continue
        m = read(os.path.join(folder, p["file"]))
        vp, fp = m["vertex_properties"], m["face_properties"]
        blocks.append((
            _join64(vp["id_hi"], vp["id_lo"]),
            _np.ascontiguousarray(m["vertices"]),
            m.get("normals"),
            _np.ascontiguousarray(m["faces"], dtype=_np.uint32),
            _join64(fp["cell_hi"], fp["cell_lo"]),
            nan, fan, cen, zero,
        ))
    vr = ix["value_range"]
    return _morpho._stitch_blocks(
        tuple(ix["shape"]), blocks, None if vr is None else tuple(vr), float(ix["level"]),
        tuple(ix["spacing"]), tuple(ix["origin"]), ix["method"], ix["normals"],
        bool(ix["flip"]), bool(return_report))

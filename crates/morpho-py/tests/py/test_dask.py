"""morpho.dask.isosurface (issue 24 part 3): chunked contour surfaces equal the single-machine
surface of ``morpho.isosurface`` — positions and normals bit for bit, the same triangles (also
after a canonical sort), the same parts and χ — for several chunkings (uneven last chunks,
1-cell-thick chunks), methods and normals; closed across the seams; from Zarr, from a memory map,
on a two-process ``dask.distributed`` cluster; as a chunked mesh (PLY parts + JSON index).
Negative controls show that a missing chunk, a missing halo or a wrong id break the checks."""

import contextlib
import json
import signal

import numpy as np
import pytest

import dask
import dask.array as da

import morpho
import morpho.dask as mdask
from morpho import _morpho


def pm_volume(shape, seed):
    """Random ±1 samples: every face ambiguous with probability 1/8, so the asymptotic decider
    decides many faces that chunk seams cut."""
    rng = np.random.default_rng(seed)
    return np.where(rng.random(shape) < 0.5, 1.0, -1.0).astype(np.float32)


def gyroid(shape, seed=0):
    x, y, z = np.meshgrid(*[np.linspace(0, 2 * np.pi, s) for s in shape], indexing="ij")
    return np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x)


def sphere(shape):
    x, y, z = np.meshgrid(*[np.linspace(-1, 1, s) for s in shape], indexing="ij")
    return x * x + 1.2 * y * y + 0.9 * z * z


def bits(a):
    return None if a is None else np.ascontiguousarray(a).view(np.uint64)


def assert_identical(got, ref):
    """Same arrays bit for bit, and the same surface after a canonical sort."""
    (v, f, n), (v0, f0, n0) = got[:3], ref[:3]
    assert v.shape == v0.shape and f.shape == f0.shape
    assert (n is None) == (n0 is None)
    assert np.array_equal(bits(v), bits(v0))
    assert np.array_equal(f, f0)
    if n0 is not None:
        assert np.array_equal(bits(n), bits(n0))
    assert canonical(v, f) == canonical(v0, f0)


def canonical(v, f):
    """Vertices sorted by their bits, triangles renumbered to that order, each rotated to start
    at its smallest index (orientation kept), sorted."""
    b = bits(v)
    order = np.lexsort(b.T[::-1])
    rank = np.empty(len(v), np.int64)
    rank[order] = np.arange(len(v))
    t = rank[np.asarray(f, dtype=np.int64)]
    r = np.argmin(t, axis=1)
    t = np.stack([t[np.arange(len(t)), (r + i) % 3] for i in range(3)], axis=1)
    t = t[np.lexsort(t.T[::-1])]
    return b[order].tobytes(), t.tobytes()


def seam_holes(v, f, shape, spacing=(1, 1, 1), origin=(0, 0, 0)):
    """Edges used by one triangle that do not lie on one of the volume's outer faces."""
    f = np.asarray(f, dtype=np.int64)
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    u, c = np.unique(e, axis=0, return_counts=True)
    once = u[c == 1]
    lo = np.asarray(origin, float)
    hi = lo + (np.asarray(shape) - 1) * np.asarray(spacing, float)
    p, q = v[once[:, 0]], v[once[:, 1]]
    on_face = ((p == lo) & (q == lo)).any(1) | ((p == hi) & (q == hi)).any(1)
    return int((~on_face).sum())


def topo(v, f):
    i = morpho.info(v, f)
    return i["parts"], i["euler_characteristic"], i["boundary_edges"]


CHUNKINGS = [(4, 4, 4), (5, 3, 7), (13, 11, 12), (1, 11, 12), (13, 11, 1), (2, 3, 1)]


@pytest.mark.parametrize("chunks", CHUNKINGS)
@pytest.mark.parametrize("method", ["decider", "tetra", "lorensen"])
def test_random_pm1_equals_single_machine(chunks, method):
    vol = pm_volume((13, 11, 12), seed=24)
    kw = dict(spacing=(0.5, 1.0, 2.0), origin=(1.0, -2.0, 3.0), method=method)
    ref = morpho.isosurface(vol, 0.0, return_report=True, **kw)
    got = mdask.isosurface(da.from_array(vol, chunks=chunks), 0.0, return_report=True, **kw)
    assert len(ref[1]) > 1000
    assert_identical(got, ref)
    assert got[3] == ref[3]
    assert topo(*got[:2]) == topo(*ref[:2])
    if method != "lorensen":  # the decider and tetra are closed across every face
        assert seam_holes(got[0], got[1], vol.shape, kw["spacing"], kw["origin"]) == 0


def test_one_cell_chunks_every_axis():
    vol = pm_volume((6, 5, 7), seed=3)
    ref = morpho.isosurface(vol, 0.0)
    got = mdask.isosurface(da.from_array(vol, chunks=1), 0.0)
    assert_identical(got, ref)
    assert seam_holes(got[0], got[1], vol.shape) == 0


@pytest.mark.parametrize("normals", ["zucker", "central", "mesh", "none"])
def test_normals_and_flip(normals):
    vol = gyroid((21, 18, 23)).astype(np.float32)
    for flip in (False, True):
        ref = morpho.isosurface(vol, 0.1, normals=normals, flip=flip)
        got = mdask.isosurface(da.from_array(vol, chunks=(6, 7, 5)), 0.1, normals=normals,
                               flip=flip)
        assert_identical(got, ref)


@pytest.mark.parametrize("chunks", [(8, 10, 7), (16, 16, 16), (31, 29, 2)])
def test_gyroid_and_sphere_fields(chunks):
    g = gyroid((31, 29, 33))  # float64: converted to float32 in the workers as in isosurface
    ref = morpho.isosurface(g, 0.0, return_report=True)
    got = mdask.isosurface(da.from_array(g, chunks=chunks), 0.0, return_report=True)
    assert_identical(got, ref)
    assert got[3]["parts"] == ref[3]["parts"] and topo(*got[:2]) == topo(*ref[:2])
    s = sphere((31, 29, 33))
    ref = morpho.isosurface(s, 0.6, spacing=(0.1, 0.2, 0.3))
    got = mdask.isosurface(da.from_array(s, chunks=chunks), 0.6, spacing=(0.1, 0.2, 0.3))
    assert_identical(got, ref)
    i = morpho.info(*got[:2])
    assert i["closed"] and i["parts"] == 1 and i["euler_characteristic"] == 2
    assert seam_holes(got[0], got[1], s.shape, (0.1, 0.2, 0.3)) == 0


def test_level_none_integers_plateaus_and_nan():
    rng = np.random.default_rng(5)
    ints = rng.integers(0, 3, (12, 9, 10)).astype(np.int16)  # samples equal to the level (ε)
    for level in (1.0, None):
        ref = morpho.isosurface(ints, level)
        got = mdask.isosurface(da.from_array(ints, chunks=(5, 4, 3)), level)
        assert_identical(got, ref)
    noisy = rng.uniform(-1, 1, (12, 9, 10)).astype(np.float32)
    noisy.flat[::37] = np.nan  # NaN cells are skipped, as by isosurface
    noisy.flat[5] = np.inf
    ref = morpho.isosurface(noisy, 0.0, return_report=True)
    got = mdask.isosurface(da.from_array(noisy, chunks=(4, 4, 4)), 0.0, return_report=True)
    assert ref[3]["skipped_cells"] > 0
    assert_identical(got, ref)
    assert got[3] == ref[3]
    b = da.from_array(pm_volume((7, 8, 9), 1) > 0, chunks=3)  # bool as uint8
    assert_identical(mdask.isosurface(b, 0.5), morpho.isosurface(np.asarray(b), 0.5))
    # a level outside the range: empty, no error
    v, f, n = mdask.isosurface(da.from_array(noisy, chunks=4), 5.0)
    assert len(v) == len(f) == 0


def test_zarr_store(tmp_path):
    import zarr
    vol = (sphere((25, 22, 27)) * 1000).astype(np.uint16)
    z = zarr.open_array(str(tmp_path / "v.zarr"), mode="w", shape=vol.shape, chunks=(8, 8, 8),
                        dtype="u2")
    z[:] = vol
    d = da.from_zarr(str(tmp_path / "v.zarr"))
    assert d.chunks[0] == (8, 8, 8, 1)  # uneven last chunk of one sample (no cells of its own)
    ref = morpho.isosurface(vol, 700, spacing=(1, 2, 3))
    assert_identical(mdask.isosurface(d, 700, spacing=(1, 2, 3)), ref)


def test_memory_mapped_raw_file(tmp_path):
    vol = gyroid((20, 24, 19)).astype("<f4")
    vol.tofile(tmp_path / "v.raw")
    mm = np.memmap(tmp_path / "v.raw", dtype="<f4", mode="r", shape=vol.shape)
    d = da.from_array(mm, chunks=(7, 9, 6))
    ref = morpho.isosurface(vol, 0.2)
    assert_identical(mdask.isosurface(d, 0.2), ref)
    # mapped in the tasks (what a cluster needs), after a 100-byte header
    with open(tmp_path / "h.raw", "wb") as fh:
        fh.write(b"\0" * 100 + vol.tobytes())
    d = mdask.from_raw(tmp_path / "h.raw", vol.shape, "<f4", chunks=(6, 10, 8), offset=100)
    assert_identical(mdask.isosurface(d, 0.2), ref)
    with pytest.raises(ValueError, match="needs"):
        mdask.from_raw(tmp_path / "v.raw", (20, 24, 20), "<f4")


def test_chunked_mesh_output(tmp_path):
    vol = pm_volume((11, 12, 10), seed=9)
    ref = morpho.isosurface(vol, 0.0, normals="central", return_report=True)
    ix = mdask.isosurface(da.from_array(vol, chunks=(4, 5, 6)), 0.0, normals="central",
                          out=tmp_path / "mesh.json")
    assert json.loads((tmp_path / "mesh.json").read_text()) == ix
    assert sum(p["faces"] for p in ix["parts"]) == len(ref[1])
    assert len(ix["parts"]) == 3 * 3 * 2 and all(p["file"] for p in ix["parts"])
    part = morpho.read(tmp_path / ix["parts"][0]["file"])  # every part is a mesh of its own
    assert set(part["vertex_properties"]) == {"id_hi", "id_lo"}
    assert set(part["face_properties"]) == {"cell_hi", "cell_lo"}
    got = mdask.read_chunked(tmp_path / "mesh.json", return_report=True)
    assert_identical(got, ref)
    assert got[3] == ref[3]


@contextlib.contextmanager
def time_limit(seconds):
    """Fails (instead of hanging) when the block takes longer than `seconds`."""
    def expire(*_):
        raise TimeoutError(f"took more than {seconds} s")

    old = signal.signal(signal.SIGALRM, expire)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def test_distributed_local_cluster(tmp_path):
    import distributed
    vol = pm_volume((17, 15, 16), seed=11)
    ref = morpho.isosurface(vol, 0.0, return_report=True)
    vol.tofile(tmp_path / "v.raw")  # each worker maps the file itself
    d = mdask.from_raw(tmp_path / "v.raw", vol.shape, vol.dtype, chunks=(6, 8, 5))
    with time_limit(120), \
            distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                     dashboard_address=None, silence_logs=50) as cluster, \
            distributed.Client(cluster, timeout=60) as client:
        got = mdask.isosurface(d, 0.0, return_report=True)
        ix = mdask.isosurface(d, 0.0, out=tmp_path / "m.json")
        workers = {ts for ts in client.run(lambda: 1)}
    assert len(workers) == 2
    assert_identical(got, ref)
    assert got[3] == ref[3]
    assert_identical(mdask.read_chunked(tmp_path / "m.json"), ref)
    assert ix["faces"] == len(ref[1])


def test_bad_input_raises_value_error():
    good = da.from_array(pm_volume((5, 5, 5), 0), chunks=3)
    with pytest.raises(ValueError, match="3D"):
        mdask.isosurface(da.zeros((5, 5), chunks=2), 0.0)
    with pytest.raises(ValueError, match="3D"):
        mdask.isosurface(da.zeros((5, 5, 5, 2), chunks=2), 0.0)
    with pytest.raises(ValueError, match="dtype"):
        mdask.isosurface(da.zeros((5, 5, 5), dtype=np.complex64, chunks=2), 0.0)
    with pytest.raises(ValueError, match="dtype"):
        mdask.isosurface(da.from_array(np.full((3, 3, 3), "a", dtype=object), chunks=2), 0.0)
    with pytest.raises(ValueError, match="level"):
        mdask.isosurface(good, float("nan"))
    with pytest.raises(ValueError, match="spacing"):
        mdask.isosurface(good, 0.0, spacing=(1, 0, 1))
    with pytest.raises(ValueError, match="spacing"):
        mdask.isosurface(good, 0.0, spacing=(1, 2))
    with pytest.raises(ValueError, match="method"):
        mdask.isosurface(good, 0.0, method="nope")
    with pytest.raises(ValueError, match="normals"):
        mdask.isosurface(good, 0.0, normals="nope")
    unknown = good[good[:, 0, 0] > 0]  # chunk sizes not known
    with pytest.raises(ValueError, match="chunk sizes"):
        mdask.isosurface(unknown, 0.0)
    with pytest.raises(ValueError, match="not the index"):
        mdask.read_chunked(__file__)


def _blocks(vol, chunks, level=0.0):
    d = da.from_array(vol, chunks=chunks)
    shape = vol.shape
    rng = (float(np.nanmin(vol)), float(np.nanmax(vol)))
    args = (level, (1.0, 1.0, 1.0), (0.0, 0.0, 0.0), "decider", "zucker", False)
    plan = mdask._plan(shape, d.chunks)
    tasks = mdask._tasks(d, plan, mdask._contour, "test", shape=shape, rng=rng, args=args)
    return list(dask.compute(*tasks)), shape, rng, args


def test_the_checks_can_fail():
    """Negative controls: a missing chunk leaves seam holes; a block without its halo is
    refused; a wrong id remap is caught by the stitch or changes the surface; the seams are
    where the asymptotic decider decides faces (both sides decide alike)."""
    vol = pm_volume((9, 10, 11), seed=2)
    ref = morpho.isosurface(vol, 0.0)
    blocks, shape, rng, args = _blocks(vol, (4, 4, 4))
    ok = _morpho._stitch_blocks(shape, blocks, rng, *args)
    assert_identical(ok, ref)
    # a missing chunk: open seams
    v, f, _ = _morpho._stitch_blocks(shape, blocks[1:], rng, *args)
    assert seam_holes(v, f, shape) > 0
    # a missing overlap: the library refuses a block without its one-sample halo
    with pytest.raises(ValueError, match="halo"):
        _morpho._isosurface_block(vol[4:9, 0:5, 0:5], shape, (4, 0, 0), ((4, 8), (0, 4), (0, 4)),
                                  rng, *args)
    # a wrong id remap: two shared points under one id disagree (refused), or a renamed point
    # is not merged (the surface differs)
    b = list(blocks[0])
    shared = np.isin(b[0], np.concatenate([x[0] for x in blocks[1:]]))
    assert shared.any() and not shared.all()
    s, t = np.argmax(shared), np.argmin(shared)
    ids = b[0].copy()
    ids[[s, t]] = ids[[t, s]]
    b[0] = ids
    with pytest.raises(ValueError, match="disagree"):
        _morpho._stitch_blocks(shape, [tuple(b)] + blocks[1:], rng, *args)
    b = list(blocks[0])
    ids = b[0].copy()
    ids[np.argmax(shared)] += np.uint64(16 * vol.size * 8)  # off the grid entities' ids
    b[0] = ids
    v, f, _ = _morpho._stitch_blocks(shape, [tuple(b)] + blocks[1:], rng, *args)
    assert len(v) != len(ref[0]) or seam_holes(v, f, shape) > 0
    # the seams cut ambiguous faces, decided alike on both sides
    amb = 0
    for i in (4, 8):
        a, bb, c, e = vol[i, :-1, :-1], vol[i, 1:, :-1], vol[i, 1:, 1:], vol[i, :-1, 1:]
        amb += int(((a == c) & (bb == e) & (a != bb)).sum())
    assert amb > 0


def test_stubs_and_docstrings():
    import ast
    import pathlib

    stub = pathlib.Path(mdask.__file__).with_suffix(".pyi")
    names = {n.name for n in ast.walk(ast.parse(stub.read_text()))
             if isinstance(n, ast.FunctionDef)}
    for name in mdask.__all__:
        assert name in names and getattr(mdask, name).__doc__.strip(), name
    assert morpho.dask is mdask  # reachable as an attribute after `import morpho`


def test_ct_head_memmap_equals_cli(tmp_path, cli, data):
    """The staged CT head, decompressed to a raw file, memory-mapped (C order [z, y, x]) and
    chunked unevenly: the stitched surface is `morpho isosurface` on the NRRD header bit for
    bit (columns back in x, y, z order and the winding flipped, as for any C-ordered array)."""
    import gzip
    import shutil

    name = "cthead_8bit_256x256x99"
    raw = tmp_path / "ct.raw"
    with gzip.open(data / "volumes" / f"{name}.raw.gz") as src, open(raw, "wb") as dst:
        shutil.copyfileobj(src, dst)
    mm = np.memmap(raw, dtype=np.uint8, mode="r", shape=(99, 256, 256))
    darr = da.from_array(mm, chunks=(40, 100, 128))  # uneven last chunks on two axes
    rep = cli("isosurface", data / "volumes" / f"{name}.nhdr", "--level", "120",
              "-o", tmp_path / "ct.ply")
    m = morpho.read(tmp_path / "ct.ply")
    v, f, n, r = mdask.isosurface(darr, 120.0, spacing=(2.0, 1.0, 1.0), return_report=True)
    assert np.array_equal(bits(v[:, ::-1]), bits(m["vertices"]))
    assert np.array_equal(f[:, [0, 2, 1]], m["faces"])
    assert r["parts"] == rep["parts"] and r["boundary_edges"] == rep["boundary_edges"]
    assert_identical((v, f, n), morpho.isosurface(np.asarray(mm), 120.0, spacing=(2, 1, 1)))


def test_fortran_source_and_given_range():
    vol = np.asfortranarray(gyroid((14, 17, 15)).astype(np.float32))
    ref = morpho.isosurface(np.ascontiguousarray(vol), 0.3)
    d = da.from_array(vol, chunks=(5, 6, 7))  # F-ordered chunks: read in their logical order
    assert_identical(mdask.isosurface(d, 0.3), ref)
    rng = (float(vol.min()), float(vol.max()))
    assert_identical(mdask.isosurface(d, 0.3, value_range=rng), ref)  # no first pass

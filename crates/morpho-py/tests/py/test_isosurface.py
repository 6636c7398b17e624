"""isosurface against the `morpho` command and against skimage.measure.marching_cubes."""

import numpy as np
import pytest

import morpho


def ellipsoid(shape=(40, 50, 60)):
    x, y, z = np.meshgrid(*[np.linspace(-1, 1, s) for s in shape], indexing="ij")
    return (x - 0.1) ** 2 / 0.5 + y * y / 0.7 + z * z / 0.8


def vset(v, decimals=9):
    return set(map(tuple, np.round(v, decimals).tolist()))


def area(v, f):
    return 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1).sum()


def same_surface(a, b, decimals=9, edge_vertices_only=False):
    """Same vertices and area; the triangulation inside a cell may differ between layouts (the
    cell table is not symmetric under reversing the axes; the six tetrahedra of `tetra` cut
    cells along axis-dependent diagonals, so there only the vertices on grid edges agree)."""
    assert len(a[0]) == len(b[0]) and len(a[1]) == len(b[1])
    if edge_vertices_only:
        on_edge = lambda v: v[(np.abs(v - np.round(v)) < 1e-12).sum(1) >= 2]
        assert vset(on_edge(a[0]), decimals) == vset(on_edge(b[0]), decimals)
    else:
        assert vset(a[0], decimals) == vset(b[0], decimals)
    assert abs(area(a[0], a[1]) - area(b[0], b[1])) <= 1e-3 * area(b[0], b[1])


def canon(v, f, decimals=9):
    """Triangles as sets of rounded vertex coordinates (independent of vertex numbering)."""
    r = np.round(v, decimals)
    return {tuple(sorted(map(tuple, r[t].tolist()))) for t in f}


@pytest.mark.parametrize("method", ["decider", "tetra", "lorensen"])
def test_matches_cli_bit_for_bit(tmp_path, cli, method):
    vol = np.asfortranarray(ellipsoid().astype(np.float32))  # vol[x, y, z], the file's order
    morpho.write(tmp_path / "v.nrrd", volume=vol, spacing=(1.0, 2.0, 3.0), origin=(5, 6, 7))
    rep = cli("isosurface", tmp_path / "v.nrrd", "--level", "0.5", "--method", method,
              "-o", tmp_path / "s.ply")
    m = morpho.read(tmp_path / "s.ply")
    d = morpho.read(tmp_path / "v.nrrd")
    assert d["volume"].flags.f_contiguous and np.array_equal(d["volume"], vol)
    v, f, n, r = morpho.isosurface(d["volume"], 0.5, spacing=d["spacing"], origin=d["origin"],
                                   method=method, return_report=True)
    assert np.array_equal(v, m["vertices"])  # same positions, bit for bit
    assert np.array_equal(f, m["faces"])
    assert np.allclose(n, m["normals"], atol=1e-6)  # PLY stores normals as float32
    assert r["parts"] == rep["parts"] and r["boundary_edges"] == rep["boundary_edges"]
    # the same samples in C order: the same surface, in axis order
    vc = np.ascontiguousarray(vol)
    v2, f2, n2 = morpho.isosurface(vc, 0.5, spacing=(1, 2, 3), origin=(5, 6, 7), method=method)
    same_surface((v2, f2), (v, f), edge_vertices_only=method == "tetra")
    assert morpho.info(v2, f2)["boundary_edges"] == r["boundary_edges"]
    fn = np.cross(v2[f2[:, 1]] - v2[f2[:, 0]], v2[f2[:, 2]] - v2[f2[:, 0]])
    assert ((fn * n2[f2[:, 0]]).sum(1) > 0).mean() > 0.99  # winding follows the normals


def test_ct_head_matches_cli(tmp_path, cli, data):
    src = data / "volumes" / "cthead_8bit_256x256x99.nhdr"
    rep = cli("isosurface", src, "--level", "80", "-o", tmp_path / "skull.ply")
    m = morpho.read(tmp_path / "skull.ply")
    d = morpho.read(src)
    assert d["volume"].shape == (256, 256, 99)
    v, f, n = morpho.isosurface(d["volume"], 80, spacing=d["spacing"], origin=d["origin"])
    assert np.array_equal(v, m["vertices"]) and np.array_equal(f, m["faces"])
    assert len(f) == rep["triangles"]


def test_like_skimage():
    measure = pytest.importorskip("skimage.measure")
    vol = ellipsoid()
    for sp in [(1, 1, 1), (1.0, 2.0, 3.0)]:
        v, f, n = morpho.isosurface(vol, 0.5, spacing=sp)
        sv, sf, sn, _ = measure.marching_cubes(vol, 0.5, spacing=sp)
        assert 0.5 < len(v) / len(sv) < 2  # same order of magnitude
        a, sa = measure.mesh_surface_area(v, f), measure.mesh_surface_area(sv, sf)
        assert abs(a - sa) / sa < 0.01
        assert np.allclose(v.min(0), sv.min(0), atol=1e-4 * max(sp))  # same axis order
        assert np.allclose(v.max(0), sv.max(0), atol=1e-4 * max(sp))
        info = morpho.info(v, f)
        assert info["closed"] and info["manifold"] and info["parts"] == 1
        # normals point the way skimage's do (towards lower values)
        i = [np.argmin(((sv - p) ** 2).sum(1)) for p in v[:: max(1, len(v) // 200)]]
        dots = (n[:: max(1, len(v) // 200)] * sn[i]).sum(1)
        assert (dots > 0).mean() > 0.95
    # level=None: the middle of the data range, as skimage
    v, f, n = morpho.isosurface(vol)
    sv, sf, _, _ = measure.marching_cubes(vol)
    assert abs(measure.mesh_surface_area(v, f) / measure.mesh_surface_area(sv, sf) - 1) < 0.01


def test_trimesh_round_trip(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    v, f, n = morpho.isosurface(ellipsoid(), 0.5)
    t = trimesh.Trimesh(v, f, process=False)
    assert t.is_watertight and t.is_winding_consistent
    info = morpho.info(t)
    assert info["closed"] and abs(info["signed_volume"] - t.volume) < 1e-6 * abs(t.volume)
    assert abs(info["area"] - t.area) < 1e-9 * t.area
    morpho.write(tmp_path / "s.ply", vertices=v, faces=f, normals=n)
    t2 = trimesh.load(tmp_path / "s.ply", process=False)
    assert np.allclose(t2.vertices, v) and np.array_equal(t2.faces, f)
    t.export(tmp_path / "t.off")
    back = morpho.read(tmp_path / "t.off")
    assert np.allclose(back["vertices"], v) and np.array_equal(back["faces"], f)


def test_dtypes_and_layouts_agree():
    base = (ellipsoid() * 100).astype(np.int16)
    ref = morpho.isosurface(base.astype(np.float32), 50.0)
    for arr in [base, base.astype(np.float64), base.astype(np.int32), np.asfortranarray(base),
                np.ascontiguousarray(base[::-1])[::-1], base.astype(np.uint16)]:
        v, f, n = morpho.isosurface(arr, 50.0)
        if arr.flags.f_contiguous and not arr.flags.c_contiguous:
            same_surface((v, f), ref, 6)
        else:
            assert canon(v, f, 6) == canon(ref[0], ref[1], 6)
    big = np.zeros((20, 22, 24), dtype=np.uint8)
    big[5:15, 6:16, 7:17] = 200
    strided = np.zeros((40, 22, 48), dtype=np.uint8)
    strided[::2, :, ::2] = big
    v1, f1, _ = morpho.isosurface(big, 100)
    v2, f2, _ = morpho.isosurface(strided[::2, :, ::2], 100)  # non-contiguous view
    assert canon(v1, f1) == canon(v2, f2)


def test_empty_and_normals_none():
    vol = ellipsoid()
    v, f, n = morpho.isosurface(vol, 100.0)
    assert v.shape == (0, 3) and f.shape == (0, 3)
    v, f, n = morpho.isosurface(vol, 0.5, normals="none")
    assert n is None and len(f) > 0

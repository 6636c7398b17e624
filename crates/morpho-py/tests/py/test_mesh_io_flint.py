"""info, curvature, read/write, FlintTree against the `morpho` command."""

import csv
import json

import numpy as np
import pytest

import morpho
from conftest import write_csv


def test_info_matches_cli(tmp_path, cli, data):
    for name in ["bunny_npm.obj", "fandisk.obj", "horse.obj.gz"]:
        src = data / "meshes" / name
        rep = cli("info", src)
        d = morpho.read(src)
        got = morpho.info(d["vertices"], d["faces"])
        for k in ["vertices", "used_vertices", "triangles", "edges", "parts", "boundary_loops",
                  "euler_characteristic", "genus", "manifold", "orientable",
                  "consistently_oriented", "non_manifold_edges", "non_manifold_vertices"]:
            assert got[k] == rep[k], (name, k)
        assert got["area"] == pytest.approx(rep["area"], rel=1e-12)
        assert got["signed_volume"] == pytest.approx(rep["signed_volume"], rel=1e-12)


def test_info_open_mesh():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]])
    f = np.array([[0, 1, 2], [1, 3, 2]])
    i = morpho.info(v, f)
    assert i["boundary_loops"] == 1 and not i["closed"] and i["euler_characteristic"] == 1
    assert i["genus"] == 0 and i["area"] == pytest.approx(1.0)


@pytest.mark.parametrize("opts", [[], ["--normals", "area"], ["--fit", "quadric"]])
def test_curvature_matches_cli(tmp_path, cli, data, opts):
    src = data / "meshes" / "spot.obj"
    cli("curvature", src, *opts, "-o", tmp_path / "k.csv")
    with open(tmp_path / "k.csv") as fh:
        rows = list(csv.DictReader(fh))
    d = morpho.read(src)
    kw = dict(zip([o.lstrip("-") for o in opts[::2]], opts[1::2]))
    c = morpho.curvature(d["vertices"], d["faces"], **kw)
    for key in ["k1", "k2", "H", "K", "A"]:
        ref = np.array([float(r[key]) if r[key] != "" else np.nan for r in rows])
        assert np.allclose(c[key], ref, rtol=1e-9, atol=1e-12, equal_nan=True), key
    assert c["undetermined"] == int(np.isnan(c["H"]).sum())
    assert ("jet_fallbacks" in c) == (kw.get("normals", "jet") == "jet")
    if not opts:  # the default differs from the thesis's method on a real mesh
        area = morpho.curvature(d["vertices"], d["faces"], normals="area")
        assert not np.allclose(c["H"], area["H"], equal_nan=True)


def test_curvature_sphere_and_ring():
    v, f, n = morpho.isosurface(
        np.fromfunction(lambda i, j, k: (i - 20) ** 2 + (j - 20) ** 2 + (k - 20) ** 2,
                        (41, 41, 41)), 15.0 ** 2, normals="none")
    for ring in (2, 3):  # the 1-ring of marching-cubes triangles is too small for the fit
        c = morpho.curvature(v, f, ring=ring)
        h = np.nanmedian(c["H"])
        assert abs(h * 15 - 1) < 0.15  # H = 1/R (the mesh faces the inside: values below the level)
    with pytest.raises(ValueError, match="ring"):
        morpho.curvature(v, f, ring=0)
    with pytest.raises(ValueError, match="normals"):
        morpho.curvature(v, f, normals=np.ones((3, 3)))
    with pytest.raises(ValueError, match="fit"):
        morpho.curvature(v, f, fit="cubic")


def test_io_round_trips(tmp_path):
    p = np.random.default_rng(1).random((50, 3))
    morpho.write(tmp_path / "p.csv", points=p, columns={"value": p[:, 0] * 2})
    d = morpho.read(tmp_path / "p.csv")
    assert d["kind"] == "points" and np.allclose(d["points"], p)
    assert np.allclose(d["columns"]["value"], p[:, 0] * 2)
    v, f, n = morpho.isosurface(np.random.default_rng(2).random((8, 9, 10)), 0.5)
    for ext in ["ply", "obj", "off", "stl"]:
        morpho.write(tmp_path / f"m.{ext}", vertices=v, faces=f)
        m = morpho.read(tmp_path / f"m.{ext}")
        assert m["kind"] == "mesh" and len(m["faces"]) == len(f)
        if ext != "stl":  # STL has no shared vertices
            assert np.allclose(m["vertices"], v, atol=1e-5) and np.array_equal(m["faces"], f)
    vol = np.random.default_rng(3).random((5, 6, 7)).astype(np.float32)
    for name in ["v.nrrd", "v.mhd"]:
        morpho.write(tmp_path / name, volume=vol, spacing=(1, 2, 3), origin=(0.5, 0, 0))
        d = morpho.read(tmp_path / name)
        assert d["volume"].shape == (5, 6, 7) and np.array_equal(d["volume"], vol)
        assert d["spacing"] == (1, 2, 3) and d["origin"] == (0.5, 0, 0)
    # write(path, read(other)) converts
    morpho.write(tmp_path / "copy.nrrd", morpho.read(tmp_path / "v.nrrd"))
    assert np.array_equal(morpho.read(tmp_path / "copy.nrrd")["volume"], vol)
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1.0]])
    morpho.write(tmp_path / "s.geojson", polygons=[[sq]])
    s = morpho.read(tmp_path / "s.geojson")
    assert s["kind"] == "shapes" and np.allclose(s["polygons"][0][0][:4], sq)


def test_read_matches_cli_convert(tmp_path, cli, data):
    src = data / "volumes" / "dipy_aniso_vox_58x58x24_i16.nhdr"
    cli("convert", src, "-o", tmp_path / "a.nrrd")
    d = morpho.read(src)
    morpho.write(tmp_path / "b.nrrd", d)
    a, b = morpho.read(tmp_path / "a.nrrd"), morpho.read(tmp_path / "b.nrrd")
    assert np.array_equal(a["volume"], b["volume"]) and a["spacing"] == b["spacing"]


def polygon(n=300, seed=0):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + 0.3 * np.sin(5 * t) + 0.05 * np.random.default_rng(seed).random(n)
    return np.c_[r * np.cos(t), r * np.sin(t)]


def test_flint_matches_cli(tmp_path, cli):
    p = polygon()
    write_csv(tmp_path / "poly.csv", p)
    tree = morpho.flint(p)
    rep = cli("flint", "build", tmp_path / "poly.csv", "-o", tmp_path / "t.json")
    assert tree.node_count == rep["nodes"] and tree.depth == rep["depth"] and len(tree) == 300
    for method in ["flintstone", "dp", "arc"]:
        rep = cli("flint", "approx", tmp_path / "poly.csv", "--count", "20", "--method", method,
                  "-o", tmp_path / f"{method}.csv")
        a = tree.approx(count=20, method=method)
        with open(tmp_path / f"{method}.csv") as fh:
            rows = list(csv.DictReader(fh))
        assert len(a["vertices"]) == len(rows)
        assert np.allclose(p[a["vertices"]], [[float(r["x"]), float(r["y"])] for r in rows])
        for e in ["e1", "e2", "e3", "e4", "e5"]:
            assert a[e] == pytest.approx(rep[e], rel=1e-12, abs=1e-15), (method, e)
    q = np.random.default_rng(5).uniform(-1.5, 1.5, (2000, 2))
    q[0] = p[3]  # on the boundary
    write_csv(tmp_path / "q.csv", q)
    cli("flint", "contains", tmp_path / "poly.csv", tmp_path / "q.csv", "-o", tmp_path / "in.csv")
    with open(tmp_path / "in.csv") as fh:
        ref = [int(r["inside"]) for r in csv.DictReader(fh)]
    got = tree.contains(q)
    assert got.dtype == np.int8 and got.tolist() == ref and got[0] == 2


def test_flint_errors():
    with pytest.raises(ValueError, match="not simple"):
        morpho.flint(np.array([[0, 0], [1, 1], [1, 0], [0, 1.0]]))
    with pytest.raises(ValueError, match="at least 3"):
        morpho.flint(np.array([[0, 0], [1, 1.0]]))
    t = morpho.flint(polygon(), closed=False)
    with pytest.raises(ValueError, match="closed"):
        t.contains(np.zeros((1, 2)))
    with pytest.raises(ValueError, match="exactly one"):
        t.approx(level=1, count=3)


def test_write_mesh_properties_round_trip(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    vp = {"id": np.array([4000000000, 1, 2, 3], dtype=np.uint32),
          "w": np.array([0.5, -1, 2, 3], dtype=np.float32), "big": np.arange(4, dtype=np.int64)}
    fp = {"label": np.array([-3, 0, 7, 9], dtype=np.int16)}
    for ascii in (False, True):
        morpho.write(tmp_path / "p.ply", vertices=v, faces=f, vertex_properties=vp,
                     face_properties=fp, ascii=ascii)
        m = morpho.read(tmp_path / "p.ply")
        assert m["vertex_properties"]["id"].tolist() == vp["id"].tolist()
        assert m["vertex_properties"]["w"].tolist() == vp["w"].tolist()
        assert m["vertex_properties"]["big"].tolist() == [0, 1, 2, 3]
        assert m["face_properties"]["label"].tolist() == fp["label"].tolist()
    with pytest.raises(ValueError, match="3 values for 4 vertices"):
        morpho.write(tmp_path / "q.ply", vertices=v, faces=f,
                     vertex_properties={"x2": np.zeros(3, np.float32)})
    with pytest.raises(ValueError, match="1D"):
        morpho.write(tmp_path / "q.ply", vertices=v, faces=f,
                     face_properties={"c": np.zeros((4, 2))})

"""triangulate, graph, boundary, contour against the `morpho` command on the same input."""

import json

import numpy as np
import pytest

import morpho
from conftest import simplex_set, tri_set, write_csv


def rng_points(n, d, seed=7):
    p = np.random.default_rng(seed).random((n, d))
    p[n // 2] = p[0]  # a duplicate: represented by its first occurrence
    return p


@pytest.mark.parametrize("d", [2, 3])
def test_triangulate_matches_cli(tmp_path, cli, d):
    p = rng_points(500, d)
    cli("triangulate", write_csv(tmp_path / "p.csv", p), "-o", tmp_path / "t.json")
    j = json.loads((tmp_path / "t.json").read_text())
    t = morpho.triangulate(p)
    assert t.dtype == np.uint32 and t.shape[1] == d + 1
    key = "triangles" if d == 2 else "tetrahedra"
    if d == 2:
        assert tri_set(t) == tri_set(j[key])
    else:
        assert simplex_set(t) == simplex_set(j[key])
    assert len(t) == len(j[key])


def test_triangulate_orientation_and_euler():
    p = rng_points(300, 2)
    t = morpho.triangulate(p)
    a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert (cross > 0).all()  # counter-clockwise
    assert 150 not in set(t.ravel().tolist())  # the duplicate of point 0


def test_triangulate_staged_points(tmp_path, cli, data):
    src = data / "geostat" / "meuse.csv"
    d = morpho.read(src)
    cli("triangulate", src, "-o", tmp_path / "t.json")
    j = json.loads((tmp_path / "t.json").read_text())
    assert tri_set(morpho.triangulate(d["points"])) == tri_set(j["triangles"])


@pytest.mark.parametrize("kind,params,flags", [
    ("gabriel", {}, []),
    ("rng", {}, []),
    ("emst", {}, []),
    ("nng", {}, []),
    ("alpha", {"a": 3.0}, ["--a", "3"]),
    ("beta-lune", {"b": 0.5}, ["--b", "0.5"]),
    ("gamma", {"c0": -0.2, "c1": 0.4}, ["--c0", "-0.2", "--c1", "0.4"]),
    ("gamma-range", {"range": (-1, 1, -0.3, 1)}, ["--range", "-1,1,-0.3,1"]),
])
def test_graph_matches_cli(tmp_path, cli, kind, params, flags):
    p = rng_points(300, 2, seed=3)
    cli("graph", write_csv(tmp_path / "p.csv", p), "--kind", kind, *flags, "-o", tmp_path / "g.json")
    j = json.loads((tmp_path / "g.json").read_text())
    e = morpho.graph(p, kind, **params)
    assert e.dtype == np.uint32 and e.shape[1] == 2
    assert simplex_set(e) == simplex_set(j["edges"])


def test_graph_3d_matches_cli(tmp_path, cli):
    p = rng_points(200, 3, seed=5)
    cli("graph", write_csv(tmp_path / "p.csv", p), "--kind", "gabriel", "-o", tmp_path / "g.json")
    j = json.loads((tmp_path / "g.json").read_text())
    assert simplex_set(morpho.graph(p, "gabriel")) == simplex_set(j["edges"])


def test_boundary_2d_matches_cli(tmp_path, cli, data):
    src = data / "curves2d" / "svg_groundtruth" / "simple_samples_sparse.csv"
    p = morpho.read(src)["points"]
    write_csv(tmp_path / "p.csv", p)
    cli("boundary", tmp_path / "p.csv", "-o", tmp_path / "b.json")
    j = json.loads((tmp_path / "b.json").read_text())
    poly = morpho.boundary(p)
    assert poly.dtype == np.uint32
    assert poly.tolist() == j["polygon"]
    assert sorted(poly.tolist()) == list(range(len(p)))  # every point on it


def test_boundary_2d_circle_and_methods(tmp_path, cli):
    t = np.sort(np.random.default_rng(2).random(80)) * 2 * np.pi
    p = np.c_[np.cos(t), 0.6 * np.sin(t)]
    write_csv(tmp_path / "c.csv", p)
    for m in ["gamma", "min-area-change"]:
        cli("boundary", tmp_path / "c.csv", "--method", m, "-o", tmp_path / f"{m}.json")
        j = json.loads((tmp_path / f"{m}.json").read_text())
        assert morpho.boundary(p, method=m).tolist() == j["polygon"]


def test_boundary_3d_matches_cli(tmp_path, cli):
    g = np.random.default_rng(4).normal(size=(150, 3))
    p = g / np.linalg.norm(g, axis=1)[:, None] * [1.0, 0.8, 0.6]
    cli("boundary", write_csv(tmp_path / "s.csv", p), "-o", tmp_path / "b.json")
    j = json.loads((tmp_path / "b.json").read_text())
    t = morpho.boundary(p)
    assert t.shape[1] == 3
    assert tri_set(t) == tri_set(j["triangles"])
    inf = morpho.info(p, t)
    assert inf["closed"] and inf["genus"] == 0 and inf["used_vertices"] == len(p)


def test_contour_matches_cli(tmp_path, cli, data):
    src = data / "geostat" / "meuse.csv"
    d = morpho.read(src)
    cli("contour", src, "--value", "zinc", "--threshold", "500", "-o", tmp_path / "z.json")
    j = json.loads((tmp_path / "z.json").read_text())
    rings = morpho.contour(d["points"], d["columns"]["zinc"], 500)
    assert [r.tolist() for r in rings] == j["cycles"]
    assert len(rings) > 0 and all(r.dtype == np.uint32 for r in rings)
    for rating in ["min", "max", "median", "area-mean"]:
        cli("contour", src, "--value", "zinc", "--threshold", "500", "--rating", rating,
            "--holes", "-o", tmp_path / f"{rating}.json")
        j = json.loads((tmp_path / f"{rating}.json").read_text())
        got = morpho.contour(d["points"], d["columns"]["zinc"], 500, rating=rating, holes=True)
        assert [r.tolist() for r in got] == j["cycles"]


def test_contour_synthetic_and_3d(tmp_path, cli):
    r = np.random.default_rng(9)
    p = r.random((400, 2))
    v = np.exp(-20 * ((p - 0.5) ** 2).sum(1))
    rings = morpho.contour(p, v, 0.5)
    write_csv(tmp_path / "s.csv", p, {"value": v})
    cli("contour", tmp_path / "s.csv", "--threshold", "0.5", "-o", tmp_path / "s.json")
    assert [x.tolist() for x in rings] == json.loads((tmp_path / "s.json").read_text())["cycles"]
    assert len(rings) == 1  # one blob
    p3 = r.random((300, 3))
    v3 = np.exp(-10 * ((p3 - 0.5) ** 2).sum(1))
    t = morpho.contour(p3, v3, 0.5)
    write_csv(tmp_path / "s3.csv", p3, {"value": v3})
    cli("contour", tmp_path / "s3.csv", "--threshold", "0.5", "-o", tmp_path / "s3.ply")
    m = morpho.read(tmp_path / "s3.ply")
    # the CLI's mesh has the surface's own vertices; compare as coordinate triangles
    ours = {tuple(sorted(map(tuple, p3[tt].round(12).tolist()))) for tt in t}
    theirs = {tuple(sorted(map(tuple, m["vertices"][tt].round(12).tolist()))) for tt in m["faces"]}
    assert ours == theirs and len(t) > 0

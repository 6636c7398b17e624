"""reduce (Hamann ch. 5) and smooth (Veltkamp §9.6 three-split) against `morpho reduce` and
`morpho smooth` on the same input: the same vertices bit for bit and the same faces."""

import numpy as np
import pytest

import morpho


def bumpy_ellipsoid(n=26):
    x, y, z = np.meshgrid(*[np.linspace(-1.2, 1.2, n)] * 3, indexing="ij")
    f = x * x / 0.9 + y * y / 0.6 + z * z + 0.1 * np.sin(4 * x) * np.cos(3 * y)
    v, t, _ = morpho.isosurface(f, 0.8)
    return v, t


def open_cap(n=24):
    """A sphere cut by the volume's faces: an open mesh with boundary loops."""
    x, y, z = np.meshgrid(*[np.linspace(0, 1, n)] * 3, indexing="ij")
    v, t, _ = morpho.isosurface(x * x + y * y + z * z, 0.7)
    return v, t


def icosphere(subdivisions=1):
    p = (1 + 5 ** 0.5) / 2
    v = np.array([[-1, p, 0], [1, p, 0], [-1, -p, 0], [1, -p, 0], [0, -1, p], [0, 1, p],
                  [0, -1, -p], [0, 1, -p], [p, 0, -1], [p, 0, 1], [-p, 0, -1], [-p, 0, 1]],
                 dtype=float)
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = list(v)
    for _ in range(subdivisions):
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                v.append((v[a] + v[b]) / 2)
                mid[k] = len(v) - 1
            return mid[k]

        f = [g for a, b, c in f
             for g in ([a, m(a, b), m(c, a)], [b, m(b, c), m(a, b)], [c, m(c, a), m(b, c)],
                       [m(a, b), m(b, c), m(c, a)])]
    v = np.array(v)
    v /= np.linalg.norm(v, axis=1)[:, None]
    v *= (1 + 0.2 * v[:, [0]] * v[:, [1]])  # not a sphere: no mirror-symmetric edges everywhere
    return v, np.array(f)


def cli_mesh(tmp_path, cli, cmd, v, f, *args):
    src, out = tmp_path / "in.ply", tmp_path / f"{cmd}-out.ply"
    morpho.write(src, vertices=v, faces=f)
    rep = cli(cmd, src, "-o", out, *args)
    return morpho.read(out), rep


def same_bits(a, b):
    return a.shape == b.shape and np.array_equal(np.ascontiguousarray(a).view(np.uint64),
                                                 np.ascontiguousarray(b).view(np.uint64))


@pytest.mark.parametrize("cli_args,kw", [
    (["--keep", "30"], dict(keep=30)),
    (["--triangles", "700"], dict(triangles=700)),
    (["--rms", "0.004", "--point", "implicit"], dict(rms=0.004, point="implicit")),
    (["--max-error", "0.1", "--normals", "uniform"], dict(max_error=0.1, normals="uniform")),
    (["--keep", "30", "--order", "hamann"], dict(keep=30, order="hamann")),
])
def test_reduce_matches_cli(tmp_path, cli, cli_args, kw):
    v, f = bumpy_ellipsoid()
    m, rep = cli_mesh(tmp_path, cli, "reduce", v, f, *cli_args)
    rv, rf, r = morpho.reduce(v, f, return_report=True, **kw)
    assert same_bits(rv, m["vertices"]) and np.array_equal(rf, m["faces"])
    assert len(rf) < len(f) and r["triangles_in"] == len(f)
    assert len(r["source"]) == len(rv) and r["source"].max() < len(v)
    i = morpho.info(rv, rf)
    assert i["closed"] and i["genus"] == 0 and i["consistently_oriented"]
    assert rep["triangles_out"] == len(rf)


def test_reduce_open_mesh_freeze_boundary(tmp_path, cli):
    v, f = open_cap()
    for frozen in (False, True):
        args = ["--keep", "40"] + (["--freeze-boundary"] if frozen else [])
        m, _ = cli_mesh(tmp_path, cli, "reduce", v, f, *args)
        rv, rf = morpho.reduce(v, f, keep=40, freeze_boundary=frozen)
        assert same_bits(rv, m["vertices"]) and np.array_equal(rf, m["faces"])
        assert morpho.info(rv, rf)["boundary_loops"] == morpho.info(v, f)["boundary_loops"]


def test_reduce_staged_bunny(tmp_path, cli, data):
    m0 = morpho.read(data / "meshes" / "bunny_npm.obj")
    out = tmp_path / "b.ply"
    cli("reduce", data / "meshes" / "bunny_npm.obj", "-o", out, "--keep", "25")
    m = morpho.read(out)
    rv, rf = morpho.reduce(m0["vertices"], m0["faces"], keep=25)
    assert same_bits(rv, m["vertices"]) and np.array_equal(rf, m["faces"])
    a, b = morpho.info(m0["vertices"], m0["faces"]), morpho.info(rv, rf)
    assert a["euler_characteristic"] == b["euler_characteristic"]


@pytest.mark.parametrize("folds", ["guard", "keep"])
def test_smooth_matches_cli(tmp_path, cli, folds):
    v, f = icosphere(1)
    m, rep = cli_mesh(tmp_path, cli, "smooth", v, f, "--scheme", "split3", "--density", "3",
                      "--folds", folds)
    sv, sf, sn, r = morpho.smooth(v, f, folds=folds, density=3, return_report=True)
    assert same_bits(sv, m["vertices"]) and np.array_equal(sf, m["faces"])
    assert same_bits(sn, m["normals"])
    assert r["patches"] == rep["patches"] == 3 * len(f)
    assert r["singular_edges"] == rep["singular_edges"]
    assert r["max_normal_jump_rad"] == rep["max_normal_jump_rad"] < 1e-6
    i = morpho.info(sv, sf)
    assert i["closed"] and i["genus"] == 0
    # the default density (8 here) as the command's
    m, _ = cli_mesh(tmp_path, cli, "smooth", v, f, "--folds", folds)
    sv, sf, _ = morpho.smooth(v, f, folds=folds)
    assert same_bits(sv, m["vertices"]) and np.array_equal(sf, m["faces"])


def test_smooth_staged_spot(tmp_path, cli, data):
    src = data / "meshes" / "spot.obj"
    m0 = morpho.read(src)
    out = tmp_path / "s.ply"
    cli("smooth", src, "-o", out, "--density", "2")
    m = morpho.read(out)
    sv, sf, sn = morpho.smooth(m0["vertices"], m0["faces"], density=2)
    assert same_bits(sv, m["vertices"]) and np.array_equal(sf, m["faces"])


def test_reduce_and_smooth_bad_input():
    v, f = bumpy_ellipsoid(14)
    with pytest.raises(ValueError, match="exactly one"):
        morpho.reduce(v, f)
    with pytest.raises(ValueError, match="exactly one"):
        morpho.reduce(v, f, keep=50, rms=0.1)
    with pytest.raises(ValueError):
        morpho.reduce(v, f, keep=0)
    with pytest.raises(ValueError):
        morpho.reduce(v, f, triangles=len(f) + 1)
    with pytest.raises(ValueError, match="point"):
        morpho.reduce(v, f, keep=50, point="nope")
    w = v.copy()
    w[3, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        morpho.reduce(w, f, keep=50)
    with pytest.raises(ValueError, match="one normal per vertex"):
        morpho.reduce(v, f, keep=50, normals=np.ones((3, 3)))
    ov, of = open_cap(10)
    with pytest.raises(ValueError):
        morpho.smooth(ov, of)  # not closed
    iv, iff = icosphere(0)
    with pytest.raises(ValueError, match="folds"):
        morpho.smooth(iv, iff, folds="nope")
    with pytest.raises(ValueError, match="density"):
        morpho.smooth(iv, iff, density=0)
    with pytest.raises(ValueError, match="faces"):
        morpho.smooth(iv, iff[:, :2])

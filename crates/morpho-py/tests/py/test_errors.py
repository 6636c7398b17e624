"""Bad input raises ValueError (or OSError for files) with the library's message; layouts that
are not C-contiguous float64 are copied (documented), never misread."""

import threading

import numpy as np
import pytest

import morpho
from morpho import _morpho

P = np.random.default_rng(0).random((100, 2))


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("fn", [morpho.triangulate, lambda p: morpho.graph(p, "gabriel"),
                                morpho.boundary, morpho.flint])
def test_non_finite_points(fn, bad):
    p = P.copy()
    p[17, 1] = bad
    with pytest.raises(ValueError, match="point 17 has a non-finite coordinate"):
        fn(p)


@pytest.mark.parametrize("arr", [
    P.astype(complex), P.astype(str), np.array([[object()] * 2] * 5), P.astype(bool),
])
def test_wrong_dtype(arr):
    with pytest.raises(ValueError, match="real numbers"):
        morpho.triangulate(arr)


@pytest.mark.parametrize("arr", [P[:, 0], np.random.random((10, 4)), np.random.random((2, 3, 2)),
                                 [[1, 2], [3]]])
def test_wrong_shape(arr):
    with pytest.raises(ValueError):
        morpho.triangulate(arr)


def test_native_layer_refuses_what_it_cannot_borrow():
    # the native functions borrow without copying: they refuse, the package converts
    with pytest.raises(ValueError, match="C-contiguous"):
        _morpho.triangulate(np.asfortranarray(P))
    with pytest.raises(TypeError):
        _morpho.triangulate(P.astype(np.float32))


def test_non_contiguous_and_other_dtypes_are_copied():
    ref = morpho.triangulate(P)
    wide = np.zeros((100, 5))
    wide[:, [0, 3]] = P
    assert np.array_equal(morpho.triangulate(wide[:, [0, 3]]), ref)
    assert np.array_equal(morpho.triangulate(np.asfortranarray(P)), ref)
    strided = np.zeros((200, 2))
    strided[::2] = P
    assert np.array_equal(morpho.triangulate(strided[::2]), ref)
    assert np.array_equal(morpho.triangulate(P.tolist()), ref)
    ints = (P * 1000).astype(np.int32)
    assert np.array_equal(morpho.triangulate(ints), morpho.triangulate(ints.astype(float)))


def test_graph_errors():
    with pytest.raises(ValueError, match="unknown graph kind"):
        morpho.graph(P, "nope")
    with pytest.raises(ValueError, match="needs the parameter a"):
        morpho.graph(P, "alpha")
    with pytest.raises(ValueError, match="unknown parameter"):
        morpho.graph(P, "alpha", alpha=1)
    with pytest.raises(ValueError):
        morpho.graph(P, "beta-lune", b=7)  # b outside [-1, 1]


def test_boundary_errors():
    with pytest.raises(ValueError, match="c must be"):
        morpho.boundary(P, c=0.5)
    with pytest.raises(ValueError, match="unknown boundary method"):
        morpho.boundary(P, method="x")


def test_isosurface_errors():
    v = np.random.random((5, 6, 7))
    with pytest.raises(ValueError, match="3D array"):
        morpho.isosurface(v[0], 0.5)
    with pytest.raises(ValueError, match="expected a 3D array of integers or floats"):
        morpho.isosurface(v.astype(complex), 0.5)
    with pytest.raises(ValueError, match="unknown isosurface method"):
        morpho.isosurface(v, 0.5, method="x")
    with pytest.raises(ValueError, match="unknown normals"):
        morpho.isosurface(v, 0.5, normals="x")
    with pytest.raises(ValueError, match="spacing"):
        morpho.isosurface(v, 0.5, spacing=(1, 0, 1))
    with pytest.raises(ValueError, match="finite"):
        morpho.isosurface(v, np.nan)
    # NaN samples: their cells are skipped, the rest is contoured
    w = v.copy()
    w[2, 3, 3] = np.nan
    _, f, _, r = morpho.isosurface(w, 0.5, return_report=True)
    assert r["skipped_cells"] > 0 and len(f) > 0


def test_mesh_errors():
    v = np.random.random((4, 3))
    with pytest.raises(ValueError, match="refers to vertex 9"):
        morpho.info(v, np.array([[0, 1, 9]]))
    with pytest.raises(ValueError, match="integer indices"):
        morpho.info(v, np.array([[0, 1, 2.5]]))
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        morpho.info(v[:, :2], np.array([[0, 1, 2]]))
    with pytest.raises(ValueError):
        morpho.info(v)  # no faces, no mesh object


def test_contour_errors():
    with pytest.raises(ValueError, match="values"):
        morpho.contour(P, np.ones(99), 0.5)
    with pytest.raises(ValueError):
        morpho.contour(P, np.ones(100), 0.5, rating="nope")
    with pytest.raises(ValueError, match="finite"):
        morpho.contour(P, np.ones(100), np.inf)


def test_file_errors(tmp_path):
    with pytest.raises(OSError):
        morpho.read(tmp_path / "missing.ply")
    (tmp_path / "bad.ply").write_text("ply\nformat nonsense\n")
    with pytest.raises(ValueError, match="bad.ply"):
        morpho.read(tmp_path / "bad.ply")
    with pytest.raises(ValueError, match="extension"):
        morpho.write(tmp_path / "x.unknown", points=P)
    with pytest.raises(ValueError, match="data needs"):
        morpho.write(tmp_path / "x.csv")
    with pytest.raises(OSError):
        morpho.write(tmp_path / "no" / "such" / "dir.csv", points=P)


def test_gil_released_threads_agree():
    pts = np.random.default_rng(1).random((20000, 2))
    ref = morpho.triangulate(pts)
    out = [None] * 4

    def work(i):
        out[i] = morpho.triangulate(pts)

    ts = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert all(np.array_equal(o, ref) for o in out)


def test_panic_is_an_exception_not_an_abort():
    with pytest.raises(RuntimeError, match="internal error \\(panic\\): deliberate test panic"):
        _morpho._panic_for_tests()
    assert len(morpho.triangulate(P)) > 0  # the interpreter goes on

//! `FlintTree`: the 2D flintstone tree of a polygon or polyline (Veltkamp 1992 ch. 6–7,
//! Alg. 7.1, `morpho::flint::FlintTree2`), its approximations (by level, error or vertex count;
//! or a baseline: Douglas–Peucker, strip, BLG, arc) and exact point-in-polygon queries.

use crate::convert::{as_points2, bad, compute, coords, py_err};
use morpho::flint::{baseline, Approximation, Baseline, Containment, FlintTree2, Target};
use numpy::{PyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The flintstone tree of a polygon (`closed=True`) or polyline.
#[pyclass(name = "FlintTree", module = "morpho", frozen)]
pub struct FlintTree {
    tree: FlintTree2,
    points: Vec<morpho::geom::Point2>,
}

/// The approximation target from exactly one of level, error, count.
fn target(level: Option<u32>, error: Option<f64>, count: Option<usize>) -> PyResult<Target> {
    match (level, error, count) {
        (Some(l), None, None) => Ok(Target::Level(l)),
        (None, Some(e), None) => Ok(Target::Error(e)),
        (None, None, Some(n)) => Ok(Target::Count(n)),
        _ => Err(bad("approx needs exactly one of level=, error=, count=")),
    }
}

/// An approximation as a dict: `vertices` (input indices), `closed`, `e1`…`e5`, `simple`.
fn approximation<'py>(py: Python<'py>, a: Approximation) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let v: Vec<u64> = a.vertices.iter().map(|&i| i as u64).collect();
    d.set_item("vertices", PyArray1::from_vec(py, v))?;
    d.set_item("closed", a.closed)?;
    d.set_item("e1", a.errors.e1)?;
    d.set_item("e2", a.errors.e2)?;
    d.set_item("e3", a.errors.e3)?;
    d.set_item("e4", a.errors.e4)?;
    d.set_item("e5", a.errors.e5)?;
    d.set_item("simple", a.simple)?;
    Ok(d)
}

#[pymethods]
impl FlintTree {
    /// Builds the tree of `(n, 2)` vertices (a polygon when `closed`, else a polyline).
    #[new]
    #[pyo3(signature = (points, closed=true))]
    fn new(py: Python<'_>, points: PyReadonlyArray2<'_, f64>, closed: bool) -> PyResult<Self> {
        let (s, _) = coords(&points, "points", &[2])?;
        let p = as_points2(s).to_vec();
        let tree = compute(py, || FlintTree2::new(&p, closed))?.map_err(py_err)?;
        Ok(FlintTree { tree, points: p })
    }

    /// Number of vertices.
    fn __len__(&self) -> usize {
        self.tree.len()
    }

    /// Number of tree nodes below the root.
    #[getter]
    fn node_count(&self) -> usize {
        self.tree.node_count()
    }

    /// Depth of the tree.
    #[getter]
    fn depth(&self) -> u32 {
        self.tree.depth()
    }

    /// True for a polygon.
    #[getter]
    fn closed(&self) -> bool {
        self.tree.is_closed()
    }

    /// An approximation by tree level, error bound or vertex count; `method` "flintstone" (the
    /// tree) or a baseline "dp", "strip", "blg", "arc".
    #[pyo3(signature = (level=None, error=None, count=None, method="flintstone"))]
    fn approx<'py>(
        &self,
        py: Python<'py>,
        level: Option<u32>,
        error: Option<f64>,
        count: Option<usize>,
        method: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let t = target(level, error, count)?;
        let b = match method {
            "flintstone" => None,
            "dp" => Some(Baseline::DouglasPeucker),
            "strip" => Some(Baseline::Strip),
            "blg" => Some(Baseline::Blg),
            "arc" => Some(Baseline::Arc),
            m => {
                return Err(bad(format!(
                    "unknown approximation method '{m}': use flintstone, dp, strip, blg or arc"
                )))
            }
        };
        let a = compute(py, || match b {
            None => self.tree.approximate(t),
            Some(b) => baseline(&self.points, self.tree.is_closed(), b, t),
        })?
        .map_err(py_err)?;
        approximation(py, a)
    }

    /// Exact point-in-polygon of `(q, 2)` queries: int8 array, 0 outside, 1 inside,
    /// 2 on the boundary. Polygons only.
    fn contains<'py>(
        &self,
        py: Python<'py>,
        queries: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let (s, _) = coords(&queries, "queries", &[2])?;
        let q = as_points2(s);
        let r = compute(py, || self.tree.contains_batch(q))?.map_err(py_err)?;
        let v: Vec<i8> = r
            .iter()
            .map(|c| match c {
                Containment::Outside => 0,
                Containment::Inside => 1,
                Containment::Boundary => 2,
            })
            .collect();
        Ok(PyArray1::from_vec(py, v))
    }
}

//! `reduce` (Hamann 1991 ch. 5, Alg. 5.1: triangle removal, `morpho::reduce::reduce`, as
//! `morpho reduce`) and `smooth` (the cubic three-split G¹ surface of Veltkamp 1992 §9.6
//! through a closed mesh, tessellated: `morpho::smooth::{three_split_with, tessellate}`, as
//! `morpho smooth --scheme split3`). Both take the options and defaults of their command, so
//! that the same input gives the command's output bit for bit.

use crate::convert::{bad, compute, frows, point_rows, py_err, rows, vector_rows};
use crate::mesh::{normal_source, trimesh};
use morpho::curvature::NormalSource;
use morpho::mesh::vertex_normals;
use morpho::reduce::{
    reduce as reduce_mesh, Domain, NewPoint, NewTriangles, Order, ReduceOptions, Stop, StopReason,
};
use morpho::smooth::{continuity, tessellate, three_split_with, visible_normals, SplitOptions};
use numpy::{PyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// Reduces a triangle mesh by triangle removal; exactly one of `keep` (percent of the
/// triangles), `triangles` (a count), `rms`, `max_error` (tolerances at the input's vertices).
/// Returns `(vertices, faces)` and with `return_report` a dict (`source`: the input vertex each
/// output vertex inherits, `removals`, `stop`, `rms`, `max_error`).
#[pyfunction]
#[pyo3(signature = (vertices, faces, keep=None, triangles=None, rms=None, max_error=None, point="bivariate", freeze_boundary=false, normals=None, height_field=false, new_triangles="generations", order="levels", return_report=false))]
#[allow(clippy::too_many_arguments)]
pub fn reduce<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: &Bound<'py, PyAny>,
    keep: Option<f64>,
    triangles: Option<usize>,
    rms: Option<f64>,
    max_error: Option<f64>,
    point: &str,
    freeze_boundary: bool,
    normals: Option<&Bound<'py, PyAny>>,
    height_field: bool,
    new_triangles: &str,
    order: &str,
    return_report: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let stop = match (keep, triangles, rms, max_error) {
        (Some(p), None, None, None) => Stop::Keep(p),
        (None, Some(n), None, None) => Stop::Triangles(n),
        (None, None, Some(e), None) => Stop::Rms(e),
        (None, None, None, Some(e)) => Stop::MaxError(e),
        _ => {
            return Err(bad(
                "reduce: give exactly one of keep=, triangles=, rms=, max_error=",
            ))
        }
    };
    let point = match point {
        "bivariate" => NewPoint::Bivariate,
        "implicit" => NewPoint::Implicit,
        p => {
            return Err(bad(format!(
                "reduce: unknown point '{p}': use bivariate or implicit"
            )))
        }
    };
    let new_triangles = match new_triangles {
        "generations" => NewTriangles::Generations,
        "last-step" => NewTriangles::LastStep,
        n => {
            return Err(bad(format!(
                "reduce: unknown new_triangles '{n}': use generations or last-step"
            )))
        }
    };
    let order = match order {
        "levels" => Order::ErrorLevels,
        "hamann" => Order::Hamann,
        o => {
            return Err(bad(format!(
                "reduce: unknown order '{o}': use levels or hamann"
            )))
        }
    };
    let mesh = trimesh(&vertices, faces)?;
    let normals = normal_source(normals)?;
    if let NormalSource::Given(n) = &normals {
        if n.len() != mesh.positions.len() {
            return Err(bad("normals: one normal per vertex is needed"));
        }
    }
    let opts = ReduceOptions {
        stop,
        point,
        freeze_boundary,
        domain: if height_field {
            Domain::HeightField
        } else {
            Domain::Surface
        },
        normals,
        check_intersections: !height_field,
        new_triangles,
        order,
    };
    let r = compute(py, || reduce_mesh(&mesh, &opts))?.map_err(py_err)?;
    let v = frows(py, point_rows(r.mesh.positions)).into_any();
    let f = rows(py, r.mesh.triangles).into_any();
    if !return_report {
        return PyTuple::new(py, [v, f]);
    }
    let d = PyDict::new(py);
    d.set_item("source", PyArray1::from_vec(py, r.source))?;
    d.set_item("triangles_in", r.triangles_in)?;
    d.set_item("removals", r.removals)?;
    d.set_item(
        "stop",
        match r.stop {
            StopReason::Target => "target",
            StopReason::Tolerance => "tolerance",
            StopReason::NoRemovable => "no_removable_left",
        },
    )?;
    d.set_item("rms", r.rms)?;
    d.set_item("max_error", r.max_error)?;
    PyTuple::new(py, [v, f, d.into_any()])
}

/// The three-split G¹ surface through a closed, consistently oriented mesh, tessellated with
/// `density` steps per micro-patch edge (`None`: the command's default, 8 or fewer on big
/// meshes). `folds="guard"` (default) repairs vertex normals that do not see all their
/// triangles and guards singular edges; `"keep"` builds the text's construction as is.
/// Returns `(vertices, faces, normals)` and with `return_report` a dict of figures.
#[pyfunction]
#[pyo3(signature = (vertices, faces, normals=None, folds="guard", density=None, return_report=false))]
pub fn smooth<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: &Bound<'py, PyAny>,
    normals: Option<&Bound<'py, PyAny>>,
    folds: &str,
    density: Option<usize>,
    return_report: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let guard = match folds {
        "guard" => true,
        "keep" => false,
        f => {
            return Err(bad(format!(
                "smooth: unknown folds '{f}': use guard or keep"
            )))
        }
    };
    let mesh = trimesh(&vertices, faces)?;
    let n = match normal_source(normals)? {
        NormalSource::Estimated(w) => vertex_normals(&mesh, w),
        NormalSource::Given(n) => n,
        NormalSource::File => unreachable!("normal_source never gives File"),
    };
    if n.len() != mesh.positions.len() {
        return Err(bad("normals: one normal per vertex is needed"));
    }
    let (s, adjusted) = compute(py, || {
        let (n, adjusted) = if guard {
            let a = visible_normals(&mesh, &n, 0.05);
            let k = a.adjusted.len();
            (a.normals, k)
        } else {
            (n, 0)
        };
        let s = three_split_with(&mesh, &n, &SplitOptions { fold_guard: guard });
        (s, adjusted)
    })?;
    let s = s.map_err(py_err)?;
    let per = |d: usize| s.patches.len().saturating_mul(d * d);
    let density = match density {
        Some(d) if per(d) > 32_000_000 => {
            return Err(bad(format!(
            "smooth: density {d} would give {} triangles over {} patches; choose a smaller density",
            per(d),
            s.patches.len()
        )))
        }
        Some(d) => d,
        None => (1..=8).rev().find(|&d| per(d) <= 4_000_000).unwrap_or(1),
    };
    let (t, c) = compute(py, || {
        let c = return_report.then(|| continuity(&s, 20));
        (tessellate(&s, density), c)
    })?;
    let t = t.map_err(py_err)?;
    let v = frows(py, point_rows(t.positions)).into_any();
    let f = rows(py, t.triangles).into_any();
    let nr = match t.normals {
        Some(n) => frows(py, vector_rows(n)).into_any(),
        None => py.None().into_bound(py),
    };
    let Some(c) = c else {
        return PyTuple::new(py, [v, f, nr]);
    };
    let d = PyDict::new(py);
    d.set_item("patches", s.patches.len())?;
    d.set_item("density", density)?;
    d.set_item("adjusted_normals", adjusted)?;
    d.set_item("singular_edges", s.singular_edges.len())?;
    d.set_item("unresolved_edges", s.unresolved_edges.len())?;
    d.set_item("sign_warnings", s.sign_warnings.len())?;
    d.set_item("fold_guarded_edges", s.fold_guarded.len())?;
    d.set_item("max_displacement", s.max_displacement)?;
    d.set_item("max_normal_jump_rad", c.max_normal_jump_rad)?;
    d.set_item("non_g1_edges", c.non_g1_edges.len())?;
    d.set_item("folds", c.folds)?;
    PyTuple::new(py, [v, f, nr, d.into_any()])
}

//! Point-set functions: `triangulate`, `graph`, `boundary`, `contour` (the library's
//! `delaunay`, `graphs`, `boundary` and `contour` families; see their modules for the methods).

use crate::convert::{as_points2, as_points3, bad, compute, coords, indices, py_err, rows};
use morpho::boundary::{boundary_2d, boundary_3d, CParam, Method2, Method3, Options2, Options3};
use morpho::contour::{contour_samples, Rating, SampleContour, SampleOptions};
use morpho::graphs::{graph_2d, graph_3d, Kind};
use morpho::mesh::{Column, PointSet};
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyRuntimeWarning;
use pyo3::prelude::*;
use pyo3::types::PyList;

/// Delaunay triangulation of `(n, 2)` or `(n, 3)` points: `(m, 3)` triangles or `(m, 4)`
/// tetrahedra as input indices (a duplicate point is represented by its first occurrence).
#[pyfunction]
pub fn triangulate<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let (s, d) = coords(&points, "points", &[2, 3])?;
    if d == 2 {
        let p = as_points2(s);
        let d = compute(py, || morpho::delaunay::triangulate_2d(p))?.map_err(py_err)?;
        let t = compute(py, || d.to_input_indices())?;
        Ok(rows(py, t).into_any())
    } else {
        let p = as_points3(s);
        let d = compute(py, || morpho::delaunay::triangulate_3d(p))?.map_err(py_err)?;
        let t = compute(py, || d.to_input_indices())?;
        Ok(rows(py, t).into_any())
    }
}

/// The graph kind from its name and parameters (the CLI's words).
fn kind(
    name: &str,
    a: Option<f64>,
    b: Option<f64>,
    c0: Option<f64>,
    c1: Option<f64>,
    range: Option<[f64; 4]>,
) -> PyResult<Kind> {
    let need = |v: Option<f64>, p: &str| {
        v.ok_or_else(|| bad(format!("graph kind '{name}' needs the parameter {p}")))
    };
    let k = match name {
        "closest-pairs" | "cp" => Kind::ClosestPairs,
        "nng" => Kind::Nng,
        "emst" => Kind::Emst,
        "strip" => Kind::Strip,
        "sig" => Kind::Sig,
        "rng" => Kind::Rng,
        "gabriel" | "gg" => Kind::Gabriel,
        "hull" => Kind::Hull,
        "delaunay" | "dt" => Kind::Delaunay,
        "alpha" => Kind::Alpha(need(a, "a")?),
        "beta-circle" => Kind::BetaCircle(need(b, "b")?),
        "beta-lune" => Kind::BetaLune(need(b, "b")?),
        "gamma" => Kind::Gamma(need(c0, "c0")?, need(c1, "c1")?),
        "gamma-range" => Kind::GammaRange(
            range.ok_or_else(|| bad("graph kind 'gamma-range' needs range=(c0, c1, c2, c3)"))?,
        ),
        other => return Err(bad(format!("unknown graph kind '{other}'"))),
    };
    k.validate().map_err(|e| bad(e.to_string()))?;
    Ok(k)
}

/// A geometric graph of the points: `(k, 2)` edges as input indices.
#[pyfunction]
#[pyo3(signature = (points, kind_name, a=None, b=None, c0=None, c1=None, range=None))]
#[allow(clippy::too_many_arguments)]
pub fn graph<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    kind_name: &str,
    a: Option<f64>,
    b: Option<f64>,
    c0: Option<f64>,
    c1: Option<f64>,
    range: Option<[f64; 4]>,
) -> PyResult<Bound<'py, PyAny>> {
    let k = kind(kind_name, a, b, c0, c1, range)?;
    let (s, d) = coords(&points, "points", &[2, 3])?;
    let g = if d == 2 {
        let p = as_points2(s);
        compute(py, || graph_2d(p, k))?
    } else {
        let p = as_points3(s);
        compute(py, || graph_3d(p, k))?
    }
    .map_err(py_err)?;
    Ok(rows(py, g.edges).into_any())
}

/// The `c` parameter: `"auto"` or a number in [−1, 0].
fn c_param(c: &Bound<'_, PyAny>) -> PyResult<CParam> {
    if let Ok(s) = c.extract::<String>() {
        if s == "auto" {
            return Ok(CParam::Auto);
        }
    } else if let Ok(v) = c.extract::<f64>() {
        if (-1.0..=0.0).contains(&v) {
            return Ok(CParam::Fixed(v));
        }
    }
    Err(bad("boundary: c must be \"auto\" or a number in [-1, 0]"))
}

/// The boundary through all points: 2D a polygon (`(n,)` input indices in boundary order), 3D a
/// closed mesh (`(m, 3)` triangles). A warning when some points could not be put on it.
#[pyfunction]
#[pyo3(signature = (points, method="gamma", c=None, seeds=200))]
pub fn boundary<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    method: &str,
    c: Option<Bound<'py, PyAny>>,
    seeds: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let c = match &c {
        Some(c) => c_param(c)?,
        None => CParam::Auto,
    };
    if !matches!(method, "gamma" | "min-area-change" | "voronoi-skeleton") {
        return Err(bad(format!(
            "unknown boundary method '{method}': use gamma, min-area-change or voronoi-skeleton"
        )));
    }
    let (s, d) = coords(&points, "points", &[2, 3])?;
    let (out, left_out) = if d == 2 {
        let method = match method {
            "gamma" => Method2::Gamma { c, keep: vec![] },
            "min-area-change" => Method2::MinAreaChange { c, keep: vec![] },
            _ => Method2::VoronoiSkeleton {
                max_seeds: seeds.max(1),
            },
        };
        let p = as_points2(s);
        let b = compute(py, || boundary_2d(p, &Options2 { method }))?.map_err(py_err)?;
        (indices(py, b.polygon).into_any(), b.left_out.len())
    } else {
        let method = match method {
            "gamma" => Method3::Gamma {
                c,
                until: morpho::boundary::Until::All,
                keep: vec![],
            },
            "min-area-change" => Method3::MinAreaChange {
                c,
                until: morpho::boundary::Until::All,
                keep: vec![],
            },
            _ => Method3::VoronoiSkeleton {
                max_seeds: seeds.max(1),
            },
        };
        let p = as_points3(s);
        let b = compute(py, || boundary_3d(p, &Options3 { method }))?.map_err(py_err)?;
        (rows(py, b.triangles).into_any(), b.left_out.len())
    };
    if left_out > 0 {
        let msg = format!(
            "boundary: {left_out} point(s) are not on the boundary; the best valid result is returned"
        );
        PyErr::warn(
            py,
            &py.get_type::<PyRuntimeWarning>(),
            &std::ffi::CString::new(msg)?,
            1,
        )?;
    }
    Ok(out)
}

/// Regions where the rating of the samples is above (below) the threshold. 2D: a list of rings
/// (each a `(k,)` array of sample indices; outer rings counter-clockwise, holes clockwise);
/// 3D: the external surfaces as `(m, 3)` triangles of sample indices.
#[pyfunction]
#[pyo3(signature = (samples, values, threshold, rating="mean", below=false, holes=false, min_area=0.0))]
#[allow(clippy::too_many_arguments)]
pub fn contour<'py>(
    py: Python<'py>,
    samples: PyReadonlyArray2<'py, f64>,
    values: PyReadonlyArray1<'py, f64>,
    threshold: f64,
    rating: &str,
    below: bool,
    holes: bool,
    min_area: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let (s, d) = coords(&samples, "samples", &[2, 3])?;
    let n = s.len() / d;
    if values.len() != n {
        return Err(bad(format!(
            "values: {} values for {n} samples",
            values.len()
        )));
    }
    if !threshold.is_finite() || !min_area.is_finite() {
        return Err(bad("threshold and min_area must be finite numbers"));
    }
    if d == 3 && (holes || min_area > 0.0) {
        return Err(bad(
            "holes and min_area apply to 2D samples; 3D gives the external surfaces",
        ));
    }
    let rating: Rating = rating.parse().map_err(py_err)?;
    let ps = PointSet {
        dim: d,
        coords: s.to_vec(),
        columns: vec![Column {
            name: "value".into(),
            values: values.as_array().to_vec(),
        }],
    };
    let opts = SampleOptions {
        value: Some("value".into()),
        threshold,
        rating,
        below,
        holes,
        min_area,
    };
    let r = compute(py, || contour_samples(&ps, &opts))?.map_err(py_err)?;
    match r {
        SampleContour::Plane(p) => {
            let list = PyList::empty(py);
            for c in p.cycles_as_samples() {
                list.append(indices(py, c))?;
            }
            Ok(list.into_any())
        }
        SampleContour::Space(sp) => {
            let t: Vec<[u32; 3]> = sp
                .surface
                .triangles
                .iter()
                .map(|t| t.map(|v| sp.sample_of_vertex[v as usize]))
                .collect();
            Ok(rows(py, t).into_any())
        }
    }
}

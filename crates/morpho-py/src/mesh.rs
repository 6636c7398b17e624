//! Mesh functions: `info` (topology, `morpho::mesh::analyze_topology`, the figures of
//! `morpho info`) and `curvature` (the osculating-paraboloid fit of Hamann 1991 §4.2,
//! `morpho::curvature::surface_curvature`).

use crate::convert::{as_points3, bad, compute, coords, frows, index_rows, py_err};
use morpho::curvature::{
    surface_curvature, NormalSource, SurfaceFit, SurfaceOptions, VertexStatus,
};
use morpho::geom::Vector3;
use morpho::mesh::{analyze_topology, NormalWeighting, TriMesh};
use numpy::{PyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A validated triangle mesh from `(n, 3)` vertices and `(m, 3)` faces (copied: the library's
/// mesh owns its arrays).
pub fn trimesh(
    vertices: &PyReadonlyArray2<'_, f64>,
    faces: &Bound<'_, PyAny>,
) -> PyResult<TriMesh> {
    let (s, _) = coords(vertices, "vertices", &[3])?;
    let p = as_points3(s);
    let t = index_rows::<3>(faces, "faces", p.len())?;
    let m = TriMesh::new(p.to_vec(), t);
    m.validate().map_err(py_err)?;
    Ok(m)
}

/// Topology and figures of a triangle mesh, as a dict with the keys of `morpho info`'s report.
#[pyfunction]
pub fn info<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let m = trimesh(&vertices, faces)?;
    let (t, b, area, vol) = compute(py, || {
        let t = analyze_topology(&m);
        (t, m.bbox(), m.area(), m.signed_volume())
    })?;
    let d = PyDict::new(py);
    d.set_item("kind", "mesh")?;
    d.set_item("vertices", m.num_vertices())?;
    d.set_item("used_vertices", t.num_used_vertices)?;
    d.set_item("triangles", m.num_triangles())?;
    d.set_item("edges", t.num_edges)?;
    d.set_item("parts", t.parts.len())?;
    d.set_item("boundary_loops", t.boundary_loops.len())?;
    d.set_item("boundary_edges", t.num_boundary_edges)?;
    d.set_item("euler_characteristic", t.euler_characteristic)?;
    d.set_item("genus", t.genus())?;
    d.set_item("manifold", t.manifold)?;
    d.set_item("orientable", t.orientable)?;
    d.set_item("consistently_oriented", t.consistently_oriented)?;
    d.set_item("closed", t.is_closed())?;
    d.set_item("non_manifold_edges", t.non_manifold_edges.len())?;
    d.set_item("non_manifold_vertices", t.non_manifold_vertices.len())?;
    d.set_item("bbox", (b.min.to_vec(), b.max.to_vec()))?;
    d.set_item("area", area)?;
    d.set_item("signed_volume", vol)?;
    Ok(d)
}

/// Vertex normals from Python: `None` (area weighting), a weighting name (`area`, `uniform`,
/// `inverse`) or an `(n, 3)` float64 array (the caller's normals).
pub fn normal_source(normals: Option<&Bound<'_, PyAny>>) -> PyResult<NormalSource> {
    Ok(match normals {
        None => NormalSource::Estimated(NormalWeighting::Area),
        Some(n) => {
            if let Ok(s) = n.extract::<String>() {
                NormalSource::Estimated(match s.as_str() {
                    "area" => NormalWeighting::Area,
                    "uniform" => NormalWeighting::Uniform,
                    "inverse" => NormalWeighting::InverseArea,
                    o => {
                        return Err(bad(format!(
                            "normals: unknown weighting '{o}': use area, uniform, inverse or an (n, 3) array"
                        )))
                    }
                })
            } else {
                let a: PyReadonlyArray2<'_, f64> = n.extract().map_err(|_| {
                    bad("normals: expected a weighting name or an (n, 3) float64 array")
                })?;
                let (s, _) = coords(&a, "normals", &[3])?;
                NormalSource::Given(
                    as_points3(s)
                        .iter()
                        .map(|p| Vector3::new(p.x, p.y, p.z))
                        .collect(),
                )
            }
        }
    })
}

/// Per-vertex curvature of a triangle mesh: a dict of `(n,)` arrays `k1, k2, H, K, A`, `(n, 3)`
/// arrays `dir1, dir2, normals`, `status` (0 ok, 1 isolated, 2 no normal, 3 too few points,
/// 4 ill-conditioned; the curvatures of such vertices are NaN), `undetermined` and, with jet
/// normals, `jet_fallbacks`.
///
/// The options are the CLI's (`morpho curvature`): `normals="jet"` (default: area-weighted
/// normals; with the default fit, the jet's own curvature), a weighting name or an `(n, 3)`
/// array; `fit="jet"` (the default with `normals="jet"`: the quartic/cubic jet over the
/// 2-ring, its curvature at the vertex), `"paraboloid"` (the thesis's, H §4.2; the default
/// otherwise; after jet-corrected normals with `normals="jet"`) or `"quadric"`; `ring`
/// defaults to 1 for the paraboloid and 2 otherwise. The thesis's method is `normals="area"`.
#[pyfunction]
#[pyo3(signature = (vertices, faces, normals=None, ring=None, fit=None))]
pub fn curvature<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: &Bound<'py, PyAny>,
    normals: Option<&Bound<'py, PyAny>>,
    ring: Option<usize>,
    fit: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let m = trimesh(&vertices, faces)?;
    let jet_normals = match normals {
        None => true,
        Some(n) => n.extract::<String>().is_ok_and(|s| s == "jet"),
    };
    let source = if jet_normals {
        NormalSource::Estimated(NormalWeighting::Area)
    } else {
        normal_source(normals)?
    };
    let fit = match (fit, jet_normals) {
        (Some("jet"), _) | (None, true) => SurfaceFit::Jet,
        (Some("paraboloid"), _) | (None, false) => SurfaceFit::Paraboloid,
        (Some("quadric"), _) => SurfaceFit::Quadric,
        (Some(o), _) => {
            return Err(bad(format!(
                "fit: unknown surface '{o}': use jet, paraboloid or quadric"
            )))
        }
    };
    // as the CLI: the jet fit needs no jet-corrected normal (it is the same fit)
    let jet_normals = jet_normals && fit != SurfaceFit::Jet;
    let jet_report = jet_normals || fit == SurfaceFit::Jet;
    let ring = ring.unwrap_or(match fit {
        SurfaceFit::Paraboloid => 1,
        _ => 2,
    });
    let opts = SurfaceOptions {
        normals: source,
        ring,
        fit,
        jet_normals,
    };
    let c = compute(py, || surface_curvature(&m, &opts))?.map_err(py_err)?;
    let v3 = |v: &[Vector3]| v.iter().map(|n| [n.x, n.y, n.z]).collect::<Vec<_>>();
    let d = PyDict::new(py);
    d.set_item("dir1", frows(py, v3(&c.dir1)))?;
    d.set_item("dir2", frows(py, v3(&c.dir2)))?;
    d.set_item("normals", frows(py, v3(&c.normals)))?;
    let status: Vec<u8> = c
        .status
        .iter()
        .map(|s| match s {
            VertexStatus::Ok => 0,
            VertexStatus::Isolated => 1,
            VertexStatus::NoNormal => 2,
            VertexStatus::TooFewPoints => 3,
            VertexStatus::IllConditioned => 4,
        })
        .collect();
    d.set_item("status", PyArray1::from_vec(py, status))?;
    d.set_item("undetermined", c.undetermined)?;
    if jet_report {
        d.set_item("jet_fallbacks", c.jet_fallbacks)?;
    }
    d.set_item("k1", PyArray1::from_vec(py, c.k1))?;
    d.set_item("k2", PyArray1::from_vec(py, c.k2))?;
    d.set_item("H", PyArray1::from_vec(py, c.h))?;
    d.set_item("K", PyArray1::from_vec(py, c.k))?;
    d.set_item("A", PyArray1::from_vec(py, c.a))?;
    Ok(d)
}

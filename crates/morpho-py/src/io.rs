//! `read(path)` and `write(path, data)`: every format of `morpho::io` (by extension), as
//! dicts of numpy arrays. `write(p2, read(p1))` converts like `morpho convert`.
//!
//! - points: `{"kind": "points", "points": (n, d), "columns": {name: (n,)}}`
//! - meshes: `{"kind": "mesh", "vertices": (n, 3), "faces": (m, 3) uint32, "normals": (n, 3) or
//!   absent, "vertex_properties": {…}, "face_properties": {…}}`
//! - volumes: `{"kind": "volume", "volume": (nx, ny, nz) float32 in Fortran order (the file's
//!   samples, no copy: `volume[x, y, z]`), "spacing", "origin"}` (or `"coords"`, per-axis
//!   sample coordinates, for rectilinear grids)
//! - polygons: `{"kind": "shapes", "polygons": [[ring (k, 2), …], …], "polylines": [(k, 2), …]}`

use crate::convert::{as_points3, bad, compute, coords, frows, py_err, rows};
use crate::mesh::trimesh;
use morpho::geom::{Point2, Vector3};
use morpho::io::{self, Data, Encoding};
use morpho::mesh::{Column, PointSet, Polygon, Polyline, Property, ScalarKind, Shapes2};
use morpho::volume::Axes;
use numpy::ndarray::{Array2, Array3, ShapeBuilder};
use numpy::{PyArray1, PyArray2, PyArray3, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;

/// `(k, 2)` array of 2D points.
fn pts2<'py>(py: Python<'py>, p: &[Point2]) -> Bound<'py, PyArray2<f64>> {
    frows(py, p.iter().map(|q| [q.x, q.y]).collect())
}

/// Reads any file morpho reads, as a dict (see the module documentation).
#[pyfunction]
pub fn read(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let data = compute(py, || io::read_any(&path))?.map_err(py_err)?;
    let d = PyDict::new(py);
    match data {
        Data::Points(ps) => {
            d.set_item("kind", "points")?;
            let n = ps.len();
            let a = Array2::from_shape_vec((n, ps.dim), ps.coords).expect("n × dim");
            d.set_item("points", PyArray2::from_owned_array(py, a))?;
            let cols = PyDict::new(py);
            for c in ps.columns {
                cols.set_item(c.name, PyArray1::from_vec(py, c.values))?;
            }
            d.set_item("columns", cols)?;
        }
        Data::Mesh(m) => {
            d.set_item("kind", "mesh")?;
            d.set_item(
                "vertices",
                frows(py, crate::convert::point_rows(m.positions)),
            )?;
            d.set_item("faces", rows(py, m.triangles))?;
            if let Some(n) = m.normals {
                d.set_item("normals", frows(py, crate::convert::vector_rows(n)))?;
            }
            let props = |ps: Vec<morpho::mesh::Property>| -> PyResult<Bound<'_, PyDict>> {
                let p = PyDict::new(py);
                for q in ps {
                    p.set_item(q.name, PyArray1::from_vec(py, q.values))?;
                }
                Ok(p)
            };
            d.set_item("vertex_properties", props(m.vertex_props)?)?;
            d.set_item("face_properties", props(m.face_props)?)?;
        }
        Data::Volume(v) => {
            d.set_item("kind", "volume")?;
            let [nx, ny, nz] = v.dims;
            let a = Array3::from_shape_vec((nx, ny, nz).f(), v.data).expect("dims");
            d.set_item("volume", PyArray3::from_owned_array(py, a))?;
            match v.axes {
                Axes::Uniform { origin, spacing } => {
                    d.set_item("spacing", (spacing[0], spacing[1], spacing[2]))?;
                    d.set_item("origin", (origin[0], origin[1], origin[2]))?;
                }
                Axes::Coords(c) => {
                    let l = PyList::empty(py);
                    for axis in c {
                        l.append(PyArray1::from_vec(py, axis))?;
                    }
                    d.set_item("coords", l)?;
                }
            }
            if let Some(dir) = v.orientation.directions {
                d.set_item("directions", dir.map(|r| r.to_vec()).to_vec())?;
            }
        }
        Data::Shapes(s) => {
            d.set_item("kind", "shapes")?;
            let polys = PyList::empty(py);
            for p in &s.polygons {
                let rings = PyList::empty(py);
                for r in &p.rings {
                    rings.append(pts2(py, r))?;
                }
                polys.append(rings)?;
            }
            d.set_item("polygons", polys)?;
            let lines = PyList::empty(py);
            for l in &s.polylines {
                lines.append(pts2(py, &l.points))?;
            }
            d.set_item("polylines", lines)?;
        }
    }
    Ok(d)
}

/// A `(k, 2)` float64 array as points.
fn ring(a: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Point2>> {
    let arr: PyReadonlyArray2<'_, f64> = a
        .extract()
        .map_err(|_| bad(format!("{what}: expected a float64 array of shape (k, 2)")))?;
    let (s, _) = coords(&arr, what, &[2])?;
    Ok(crate::convert::as_points2(s).to_vec())
}

/// Extra per-vertex or per-face columns (`{name: (n,) array}`), each written with the kind of
/// its dtype (8/16/32-bit integers, float32; anything else as float64 by the caller).
fn properties(d: Option<Bound<'_, PyAny>>, n: usize, what: &str) -> PyResult<Vec<Property>> {
    let Some(d) = d.filter(|d| !d.is_none()) else {
        return Ok(Vec::new());
    };
    let d = d
        .downcast::<PyDict>()
        .map_err(|_| bad(format!("{what}_properties: expected a dict of arrays")))?;
    let mut out = Vec::new();
    for (k, v) in d.iter() {
        let name: String = k.extract()?;
        macro_rules! kind {
            ($($t:ty => $kind:ident),*) => {{
                $(if let Ok(a) = v.extract::<PyReadonlyArray1<'_, $t>>() {
                    Some((ScalarKind::$kind, a.as_array().iter().map(|&x| x as f64).collect::<Vec<f64>>()))
                } else)* { None }
            }};
        }
        let (kind, values) = kind!(u8 => U8, i8 => I8, u16 => U16, i16 => I16, u32 => U32,
            i32 => I32, f32 => F32, f64 => F64)
        .ok_or_else(|| {
            bad(format!(
                "{what} property {name}: expected a 1D array of (u)int8/16/32, float32 or float64"
            ))
        })?;
        if values.len() != n {
            let plural = if what == "vertex" {
                "vertices"
            } else {
                "faces"
            };
            return Err(bad(format!(
                "{what} property {name}: {} values for {n} {plural}",
                values.len()
            )));
        }
        out.push(Property { name, kind, values });
    }
    Ok(out)
}

/// Writes a dict like those `read` returns (the kind from its keys: `faces` → mesh, `volume` →
/// volume, `polygons`/`polylines` → shapes, `points` → points), atomically; the format by the
/// extension. `ascii=True` writes ASCII PLY/VTK.
#[pyfunction]
#[pyo3(signature = (path, data, ascii=false))]
pub fn write(py: Python<'_>, path: PathBuf, data: &Bound<'_, PyDict>, ascii: bool) -> PyResult<()> {
    let enc = if ascii {
        Encoding::Ascii
    } else {
        Encoding::BinaryLittleEndian
    };
    let get = |k: &str| data.get_item(k);
    if let Some(faces) = get("faces")? {
        let v: PyReadonlyArray2<'_, f64> = get("vertices")?
            .ok_or_else(|| bad("write: a mesh needs 'vertices' beside 'faces'"))?
            .extract()
            .map_err(|_| bad("vertices: expected a float64 array of shape (n, 3)"))?;
        let mut m = trimesh(&v, &faces)?;
        if let Some(n) = get("normals")? {
            if !n.is_none() {
                let a: PyReadonlyArray2<'_, f64> = n
                    .extract()
                    .map_err(|_| bad("normals: expected a float64 array of shape (n, 3)"))?;
                let (s, _) = coords(&a, "normals", &[3])?;
                if s.len() / 3 != m.positions.len() {
                    return Err(bad("normals: one normal per vertex is needed"));
                }
                m.normals = Some(
                    as_points3(s)
                        .iter()
                        .map(|p| Vector3::new(p.x, p.y, p.z))
                        .collect(),
                );
            }
        }
        m.vertex_props = properties(get("vertex_properties")?, m.positions.len(), "vertex")?;
        m.face_props = properties(get("face_properties")?, m.triangles.len(), "face")?;
        return compute(py, || io::write_mesh(&path, &m, enc))?.map_err(py_err);
    }
    if let Some(vol) = get("volume")? {
        let three = |k: &str, dflt: f64| -> PyResult<[f64; 3]> {
            match get(k)? {
                Some(v) if !v.is_none() => {
                    let t: (f64, f64, f64) = v
                        .extract()
                        .map_err(|_| bad(format!("{k}: expected three numbers")))?;
                    Ok([t.0, t.1, t.2])
                }
                _ => Ok([dflt; 3]),
            }
        };
        let (v, _) = crate::volume::to_volume(
            py,
            &vol,
            three("spacing", 1.0)?,
            three("origin", 0.0)?,
            true,
        )?;
        return compute(py, || io::write_volume(&path, &v))?.map_err(py_err);
    }
    if get("polygons")?.is_some() || get("polylines")?.is_some() {
        let mut s = Shapes2::default();
        if let Some(p) = get("polygons")? {
            for (i, poly) in p.try_iter()?.enumerate() {
                let mut rings = Vec::new();
                for r in poly?.try_iter()? {
                    rings.push(ring(&r?, &format!("polygon {i}"))?);
                }
                s.polygons.push(Polygon { rings });
            }
        }
        if let Some(l) = get("polylines")? {
            for (i, line) in l.try_iter()?.enumerate() {
                let points = ring(&line?, &format!("polyline {i}"))?;
                s.polylines.push(Polyline {
                    points,
                    closed: false,
                });
            }
        }
        return compute(py, || io::write_shapes2(&path, &s))?.map_err(py_err);
    }
    if let Some(p) = get("points")? {
        let a: PyReadonlyArray2<'_, f64> = p
            .extract()
            .map_err(|_| bad("points: expected a float64 array of shape (n, 2) or (n, 3)"))?;
        let (s, dim) = coords(&a, "points", &[2, 3])?;
        let n = s.len() / dim;
        let mut ps = PointSet {
            dim,
            coords: s.to_vec(),
            columns: vec![],
        };
        if let Some(cols) = get("columns")? {
            let cols = cols
                .downcast::<PyDict>()
                .map_err(|_| bad("columns: expected a dict"))?;
            for (k, v) in cols.iter() {
                let name: String = k.extract()?;
                let vals: PyReadonlyArray1<'_, f64> = v
                    .extract()
                    .map_err(|_| bad(format!("column {name}: expected a float64 array")))?;
                if vals.as_array().len() != n {
                    return Err(bad(format!("column {name}: one value per point is needed")));
                }
                ps.columns.push(Column {
                    name,
                    values: vals.as_array().to_vec(),
                });
            }
        }
        return compute(py, || io::write_points(&path, &ps))?.map_err(py_err);
    }
    Err(bad(
        "write: data needs 'points', 'vertices' and 'faces', 'volume', or 'polygons'",
    ))
}

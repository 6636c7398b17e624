//! JSON: point arrays (reading) and the JSON form of morpho's results (writing).
//!
//! # Reading
//! [`read_points`]: a JSON array of `[x, y]` or `[x, y, z]` numbers (the delaunator fixtures'
//! format), or an object with a `"points"` array of that form. Every point has the dimension of
//! the first; a non-number coordinate is an error naming the point.
//!
//! # Writing
//! One compact JSON document per file, followed by a newline. Object keys are in alphabetical
//! order (serde_json's map); numbers use the shortest round-trip form. Indices refer to the
//! input order of the points unless said otherwise. The documents:
//!
//! | writer | document |
//! |---|---|
//! | [`write_triangulation_2d`] | `{"points", "triangles", "hull"[, "constrained"]}` |
//! | [`write_triangulation_3d`] | `{"points", "tetrahedra", "hull"}` |
//! | [`write_graph`] | `{"kind", "dim", "points", "edges"?, "triangles"?, "gamma"?}` |
//! | [`write_boundary_2d`] | `{"polygon": [indices]}` |
//! | [`write_interior_2d`] | `{"triangles", "area"}` |
//! | [`write_boundary_3d`] | `{"triangles"}` |
//! | [`write_interior_3d`] | `{"tetrahedra", "volume"[, "note"]}` |
//! | [`write_contour_cycles`] | `{"cycles": [[sample indices]], "regions": [{"outer", "holes", "area"}]}` |
//!
//! Write failures are [`Error::Io`] (through the one mapping of `io`);
//! complexity is linear in the size of the result.

use crate::boundary::{Boundary2, Boundary3};
use crate::contour::PlaneContour;
use crate::geom::{Point2, Point3};
use crate::graphs::{Graph, Kind};
use crate::mesh::PointSet;
use crate::{Error, Result};
use serde_json::{json, Value};
use std::io::Write;

/// Reads points from a JSON array of coordinate arrays (see the module documentation).
///
/// ```
/// let p = morpho::io::json::read_points(b"[[0, 0], [1, 0.5]]").unwrap();
/// assert_eq!((p.dim, p.coords), (2, vec![0.0, 0.0, 1.0, 0.5]));
/// ```
pub fn read_points(bytes: &[u8]) -> Result<PointSet> {
    let v: serde_json::Value = serde_json::from_slice(bytes)
        .map_err(|e| Error::at_line(e.line() as u64, format!("bad JSON: {e}")))?;
    let arr = match &v {
        serde_json::Value::Array(a) => a,
        serde_json::Value::Object(o) => match o.get("points") {
            Some(serde_json::Value::Array(a)) => a,
            _ => {
                return Err(Error::format(
                    "expected an array of points or an object with \"points\"",
                ))
            }
        },
        _ => return Err(Error::format("expected an array of points")),
    };
    let mut dim = 0;
    let mut coords = Vec::with_capacity(arr.len() * 3);
    for (i, p) in arr.iter().enumerate() {
        let p = p
            .as_array()
            .ok_or_else(|| Error::format(format!("point {i} is not an array")))?;
        if dim == 0 {
            dim = p.len();
            if dim != 2 && dim != 3 {
                return Err(Error::format(format!(
                    "point {i} has {dim} coordinates; expected 2 or 3"
                )));
            }
        } else if p.len() != dim {
            return Err(Error::format(format!(
                "point {i} has {} coordinates, the first had {dim}",
                p.len()
            )));
        }
        for c in p {
            let c = c
                .as_f64()
                .ok_or_else(|| Error::format(format!("point {i} has a non-number coordinate")))?;
            coords.push(c);
        }
    }
    Ok(PointSet {
        dim: dim.max(2),
        coords,
        columns: vec![],
    })
}

/// Writes `v` compactly followed by a newline.
pub fn write_value(w: &mut dyn Write, v: &Value) -> Result<()> {
    serde_json::to_writer(&mut *w, v).map_err(json_err)?;
    writeln!(w).map_err(super::werr)
}

/// Writes `v` indented (two spaces) followed by a newline.
pub fn write_value_pretty(w: &mut dyn Write, v: &Value) -> Result<()> {
    serde_json::to_writer_pretty(&mut *w, v).map_err(json_err)?;
    writeln!(w).map_err(super::werr)
}

/// serde_json fails while writing a [`Value`] only when the writer fails.
fn json_err(e: serde_json::Error) -> Error {
    super::werr(e.into())
}

/// A 2D triangulation in input indices: the points as given (duplicates included), the
/// triangles and the hull cycle (counter-clockwise) as input indices, and for a constrained
/// triangulation its constrained edges.
#[derive(Debug, Clone, Copy)]
pub struct Triangulation2<'a> {
    /// The input points.
    pub points: &'a [Point2],
    /// Triangles as input indices.
    pub triangles: &'a [[u32; 3]],
    /// The hull cycle as input indices.
    pub hull: &'a [u32],
    /// The constrained edges as input indices (constrained triangulations only).
    pub constrained: Option<&'a [[u32; 2]]>,
}

/// A 3D Delaunay tetrahedralization in input indices: the points as given, the tetrahedra and
/// the outward-oriented hull triangles as input indices.
#[derive(Debug, Clone, Copy)]
pub struct Triangulation3<'a> {
    /// The input points.
    pub points: &'a [Point3],
    /// Tetrahedra as input indices.
    pub tets: &'a [[u32; 4]],
    /// Hull triangles as input indices, oriented outward.
    pub hull: &'a [[u32; 3]],
}

/// Writes `{"points", "triangles", "hull"}` (and `"constrained"` when given).
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::io::json::{write_triangulation_2d, Triangulation2};
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// let t = Triangulation2 { points: &p, triangles: &[[0, 1, 2]], hull: &[0, 1, 2], constrained: None };
/// let mut out = Vec::new();
/// write_triangulation_2d(&mut out, &t).unwrap();
/// assert_eq!(
///     String::from_utf8(out).unwrap(),
///     "{\"hull\":[0,1,2],\"points\":[[0.0,0.0],[1.0,0.0],[0.0,1.0]],\"triangles\":[[0,1,2]]}\n"
/// );
/// ```
pub fn write_triangulation_2d(w: &mut dyn Write, t: &Triangulation2) -> Result<()> {
    let mut v = json!({
        "points": t.points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        "triangles": t.triangles,
        "hull": t.hull,
    });
    if let Some(c) = t.constrained {
        v["constrained"] = json!(c);
    }
    write_value(w, &v)
}

/// Writes `{"points", "tetrahedra", "hull"}`.
pub fn write_triangulation_3d(w: &mut dyn Write, t: &Triangulation3) -> Result<()> {
    let v = json!({
        "points": t.points.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>(),
        "tetrahedra": t.tets,
        "hull": t.hull,
    });
    write_value(w, &v)
}

/// Writes a geometric graph of `points`: `{"kind", "dim", "points"}` with `"edges"` (unless the
/// graph is made of triangles only), `"triangles"` (when it has some, or when a 3D graph has no
/// edges) and, for the γ kinds, `"gamma"` (the γ-values aligned with the simplices).
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::graphs::{graph_2d, Kind};
/// use morpho::mesh::PointSet;
/// let p = [Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(1.0, 3.0)];
/// let g = graph_2d(&p, Kind::Emst).unwrap();
/// let mut out = Vec::new();
/// morpho::io::json::write_graph(&mut out, Kind::Emst, &PointSet::from_points2(&p), &g).unwrap();
/// let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
/// assert_eq!(v["edges"].as_array().unwrap().len(), 2);
/// ```
pub fn write_graph(w: &mut dyn Write, kind: Kind, points: &PointSet, g: &Graph) -> Result<()> {
    let mut v = json!({
        "kind": kind.name(),
        "dim": points.dim,
        "points": (0..points.len()).map(|i| points.point(i).to_vec()).collect::<Vec<_>>(),
    });
    if g.triangles.is_empty() || !g.edges.is_empty() {
        v["edges"] = json!(g.edges);
    }
    if !g.triangles.is_empty() || (g.dim == 3 && g.edges.is_empty()) {
        v["triangles"] = json!(g.triangles);
    }
    if matches!(kind, Kind::Gamma(..) | Kind::GammaRange(_)) {
        v["gamma"] = json!(g.gamma);
    }
    write_value(w, &v)
}

/// Writes `{"polygon": [input indices in boundary order]}`.
pub fn write_boundary_2d(w: &mut dyn Write, b: &Boundary2) -> Result<()> {
    write_value(w, &json!({ "polygon": b.polygon }))
}

/// Writes the interior triangulation of a 2D boundary: `{"triangles", "area"}`.
pub fn write_interior_2d(w: &mut dyn Write, b: &Boundary2) -> Result<()> {
    write_value(w, &json!({ "triangles": b.interior, "area": b.area }))
}

/// Writes the triangles of a 3D boundary: `{"triangles"}` (input indices, oriented outward).
pub fn write_boundary_3d(w: &mut dyn Write, b: &Boundary3) -> Result<()> {
    write_value(w, &json!({ "triangles": b.triangles }))
}

/// Why [`Boundary3::interior`] is empty although there is a surface: the general engine ran
/// (its surface need not bound Delaunay tetrahedra), so the volume comes from the surface.
pub(crate) const NO_INTERIOR_NOTE: &str = "no interior tetrahedralization after the augmented (c < 0) constriction; volume from the closed surface";

/// `NO_INTERIOR_NOTE` when it applies to `b` (no interior tetrahedra, some triangles).
pub fn interior_3d_note(b: &Boundary3) -> Option<&'static str> {
    (b.interior.is_empty() && !b.triangles.is_empty()).then_some(NO_INTERIOR_NOTE)
}

/// Writes the interior of a 3D boundary: `{"tetrahedra", "volume"}`, with `"note"`
/// ([`interior_3d_note`]) instead of an unexplained empty list when there are no tetrahedra.
pub fn write_interior_3d(w: &mut dyn Write, b: &Boundary3) -> Result<()> {
    let mut v = json!({ "tetrahedra": b.interior, "volume": b.volume });
    if let Some(note) = interior_3d_note(b) {
        v["note"] = json!(note);
    }
    write_value(w, &v)
}

/// Writes the cycles of a plane contour as input sample indices, with its regions:
/// `{"cycles": [[…]…], "regions": [{"outer": k, "holes": […], "area": a}…]}`.
pub fn write_contour_cycles(w: &mut dyn Write, r: &PlaneContour) -> Result<()> {
    let regions: Vec<Value> = r
        .contour
        .regions
        .iter()
        .map(|g| json!({"outer": g.outer, "holes": g.holes, "area": g.area}))
        .collect();
    let v = json!({"cycles": r.cycles_as_samples(), "regions": regions});
    write_value(w, &v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that fails after `left` bytes.
    struct Full {
        left: usize,
    }
    impl Write for Full {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            if self.left == 0 {
                return Err(std::io::Error::new(std::io::ErrorKind::StorageFull, "full"));
            }
            let n = b.len().min(self.left);
            self.left -= n;
            Ok(n)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn write_failures_are_io_errors() {
        let v = json!({"a": [1, 2, 3]});
        for left in [0, 3, 12] {
            let e = write_value(&mut Full { left }, &v).unwrap_err();
            assert!(matches!(e, Error::Io { .. }), "{left}: {e:?}");
            let e = write_value_pretty(&mut Full { left }, &v).unwrap_err();
            assert!(matches!(e, Error::Io { .. }), "{left}: {e:?}");
        }
    }

    #[test]
    fn points_errors() {
        assert!(read_points(b"[[0,0],[1,2,3]]").is_err());
        assert!(read_points(b"[[0]]").is_err());
        assert!(read_points(b"{\"points\": 3}").is_err());
        let p = read_points(b"{\"points\": [[0,0,1]]}").unwrap();
        assert_eq!(p.dim, 3);
    }
}

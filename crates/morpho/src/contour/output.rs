//! Output of a plane contour: GeoJSON (a FeatureCollection of Polygons with closed rings, outer
//! rings counter-clockwise and holes clockwise as RFC 7946 asks, properties `threshold`, `value`,
//! `area`, `external`), a JSON list of cycles in input sample indices, and an SVG picture of the
//! coloured triangulation with the contour drawn over it.

use super::pipeline::PlaneContour;
use crate::geom::{bbox2, Point2};
use crate::{Error, Result};
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::io::Write;

fn werr(e: impl std::fmt::Display) -> Error {
    Error::invalid(format!("cannot write: {e}"))
}

fn ring_coords(ring: &[u32], points: &[Point2]) -> Value {
    let mut v: Vec<Value> = ring
        .iter()
        .map(|&i| json!([points[i as usize].x, points[i as usize].y]))
        .collect();
    if let Some(first) = v.first().cloned() {
        v.push(first);
    }
    Value::Array(v)
}

/// The GeoJSON FeatureCollection of the contour's regions.
pub fn geojson_value(r: &PlaneContour, threshold: f64, below: bool) -> Value {
    let c = &r.contour;
    let features: Vec<Value> = c
        .regions
        .iter()
        .map(|reg| {
            let rings: Vec<Value> = std::iter::once(reg.outer)
                .chain(reg.holes.iter().copied())
                .map(|k| ring_coords(&c.cycles[k as usize], &r.points))
                .collect();
            json!({
                "type": "Feature",
                "geometry": {"type": "Polygon", "coordinates": rings},
                "properties": {
                    "threshold": threshold,
                    "value": r.selected.column,
                    "below": below,
                    "area": reg.area,
                    "external": reg.external,
                }
            })
        })
        .collect();
    json!({"type": "FeatureCollection", "features": features})
}

/// Writes the GeoJSON FeatureCollection.
pub fn write_geojson(
    w: &mut dyn Write,
    r: &PlaneContour,
    threshold: f64,
    below: bool,
) -> Result<()> {
    serde_json::to_writer(&mut *w, &geojson_value(r, threshold, below)).map_err(werr)?;
    writeln!(w).map_err(werr)
}

/// Writes `{"cycles": [[sample indices…]…], "regions": [{"outer": k, "holes": […]}…]}`.
pub fn write_cycles_json(w: &mut dyn Write, r: &PlaneContour) -> Result<()> {
    let regions: Vec<Value> = r
        .contour
        .regions
        .iter()
        .map(|g| json!({"outer": g.outer, "holes": g.holes, "area": g.area}))
        .collect();
    let v = json!({"cycles": r.cycles_as_samples(), "regions": regions});
    serde_json::to_writer(&mut *w, &v).map_err(werr)?;
    writeln!(w).map_err(werr)
}

/// Most triangles drawn in the SVG; larger triangulations are drawn as the contour only.
pub const SVG_MAX_TRIANGLES: usize = 200_000;

/// An SVG picture: the triangles (black ones dark, white ones light), the contour cycles in red
/// (holes dashed), the samples as dots (up to 20 000 of them).
pub fn svg_string(r: &PlaneContour) -> String {
    let bb = bbox2(&r.points);
    let size = 800.0;
    let margin = 10.0;
    let ext = bb.extent();
    let span = ext[0].max(ext[1]);
    let s = if span > 0.0 { size / span } else { 1.0 };
    let (w, h) = (ext[0] * s + 2.0 * margin, ext[1] * s + 2.0 * margin);
    let tx = |p: &Point2| {
        (
            (p.x - bb.min[0]) * s + margin,
            (bb.max[1] - p.y) * s + margin,
        )
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.2} {h:.2}">"#
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    if r.triangles.len() <= SVG_MAX_TRIANGLES {
        for (k, color) in [(false, "#e8eef5"), (true, "#f2b872")] {
            let _ = write!(
                out,
                r##"<path fill="{color}" stroke="#9aa5b1" stroke-width="0.3" d=""##
            );
            for (t, &b) in r.triangles.iter().zip(&r.black) {
                if b != k {
                    continue;
                }
                let [p, q, u] = t.map(|v| tx(&r.points[v as usize]));
                let _ = write!(
                    out,
                    "M{:.2} {:.2}L{:.2} {:.2}L{:.2} {:.2}Z",
                    p.0, p.1, q.0, q.1, u.0, u.1
                );
            }
            let _ = writeln!(out, r#""/>"#);
        }
    }
    let c = &r.contour;
    for reg in &c.regions {
        for (i, k) in std::iter::once(reg.outer)
            .chain(reg.holes.iter().copied())
            .enumerate()
        {
            let dash = if i > 0 {
                r#" stroke-dasharray="4 2""#
            } else {
                ""
            };
            let _ = write!(
                out,
                r##"<path fill="none" stroke="#c81e1e" stroke-width="1.6"{dash} d=""##
            );
            for (j, &v) in c.cycles[k as usize].iter().enumerate() {
                let p = tx(&r.points[v as usize]);
                let _ = write!(
                    out,
                    "{}{:.2} {:.2}",
                    if j == 0 { 'M' } else { 'L' },
                    p.0,
                    p.1
                );
            }
            let _ = writeln!(out, r#"Z"/>"#);
        }
    }
    if r.points.len() <= 20_000 {
        let _ = write!(out, r##"<path fill="#333" stroke="none" d=""##);
        for p in &r.points {
            let (x, y) = tx(p);
            let _ = write!(out, "M{:.2} {:.2}h1.2v1.2h-1.2Z", x - 0.6, y - 0.6);
        }
        let _ = writeln!(out, r#""/>"#);
    }
    let _ = writeln!(out, "</svg>");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::pipeline::{finish_plane, SampleOptions, SelectedSamples, Triangulation2};

    fn square() -> PlaneContour {
        let pts = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ];
        let sel = SelectedSamples {
            column: "zinc".into(),
            input: vec![0, 1, 2, 3],
            values: vec![1.0, 1.0, 1.0, 1.0],
            skipped: 0,
        };
        let tri = Triangulation2 {
            points: &pts,
            vertex_of_input: &[0, 1, 2, 3],
            input_of_vertex: &[0, 1, 2, 3],
            triangles: &[[0, 1, 2], [0, 2, 3]],
            neighbors: None,
        };
        finish_plane(sel, tri, &SampleOptions::default()).unwrap()
    }

    #[test]
    fn geojson_rings_closed_and_ccw() {
        let r = square();
        let v = geojson_value(&r, 0.0, false);
        let ring = &v["features"][0]["geometry"]["coordinates"][0];
        let ring = ring.as_array().unwrap();
        assert_eq!(ring.len(), 5);
        assert_eq!(ring[0], ring[4]);
        let pts: Vec<(f64, f64)> = ring
            .iter()
            .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect();
        let area: f64 = pts
            .windows(2)
            .map(|w| w[0].0 * w[1].1 - w[1].0 * w[0].1)
            .sum();
        assert!(area > 0.0);
        assert_eq!(v["features"][0]["properties"]["threshold"], 0.0);
        let mut buf = Vec::new();
        write_cycles_json(&mut buf, &r).unwrap();
        let j: Value = serde_json::from_slice(&buf).unwrap();
        assert_eq!(j["cycles"][0].as_array().unwrap().len(), 4);
        let svg = svg_string(&r);
        assert!(svg.starts_with("<svg") && svg.contains("#c81e1e"));
    }
}

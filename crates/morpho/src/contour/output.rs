//! SVG picture of a plane contour: the coloured triangulation with the contour drawn over it.
//! (GeoJSON and the JSON list of cycles are written by [`crate::io::write_contour_2d`].)

use super::pipeline::PlaneContour;
use crate::geom::{bbox2, Point2};
use std::fmt::Write as _;

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

//! SVG pictures of morpho's 2D results: Delaunay triangulations with their Voronoi diagrams,
//! constrained triangulations, geometric graphs, boundary polygons and their constriction,
//! contours of rated samples, and views of (2D or 3D) point sets.
//!
//! Most pictures are built with the [`Svg`] builder of [`super::svg`]. Two keep the layout they
//! were born with, written directly: [`boundary_svg`] (`morpho boundary -o *.svg`: an 800-pixel
//! square frame, coordinates with two decimals) and [`contour_svg`] (`morpho contour -o *.svg`:
//! 800 pixels along the longer side plus a 10-pixel margin). Every function returns the SVG
//! document as a `String`; [`crate::io::write_text`] saves it. Time and memory are linear in
//! the size of the result drawn.

use super::colormap::{finite_range, Colormap};
use super::raster::{camera_basis, RenderOptions, UpAxis};
use super::svg::{point_radius, Stroke, Svg};
use crate::boundary::Boundary2;
use crate::contour::PlaneContour;
use crate::delaunay::{cdt::Cdt2, d2::Delaunay2, voronoi};
use crate::geom::{bbox2, Aabb2, Point2, Vector3};
use crate::graphs::Graph;
use crate::mesh::PointSet;
use std::fmt::Write as _;

/// A Delaunay triangulation (edges thin blue, points dark), optionally with its Voronoi
/// diagram (red, dashed; rays and lines cut at the diagonal of the points' box, so they leave
/// the picture), 900 pixels wide.
///
/// ```
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0), Point2::new(1.0, 1.2)];
/// let d = morpho::delaunay::triangulate_2d(&p).unwrap();
/// let svg = morpho::render::delaunay_svg(&d, true);
/// assert_eq!(svg.matches("<circle").count(), 4);
/// assert!(svg.contains("stroke-dasharray")); // the Voronoi diagram
/// ```
pub fn delaunay_svg(d: &Delaunay2, with_voronoi: bool) -> String {
    let b = bbox2(&d.points);
    let mut svg = Svg::new(b, 900.0);
    let edges: Vec<_> = d
        .edges()
        .iter()
        .map(|e| (d.points[e[0] as usize], d.points[e[1] as usize]))
        .collect();
    svg.segments(&edges, &Stroke::solid([58, 110, 165], 0.8));
    if with_voronoi && !d.collinear {
        let reach = b.diagonal().max(f64::MIN_POSITIVE);
        svg.segments(
            &voronoi::voronoi(d).segments(reach),
            &Stroke::dashed([209, 73, 91], 0.8),
        );
    }
    svg.points(&d.points, point_radius(d.points.len()), [30, 30, 30]);
    svg.finish()
}

/// A constrained Delaunay triangulation: edges thin blue, constrained edges bold black,
/// 900 pixels wide.
pub fn cdt_svg(c: &Cdt2) -> String {
    let pts = c.points();
    let b = bbox2(pts);
    let mut svg = Svg::new(b, 900.0);
    let (mut thin, mut bold) = (Vec::new(), Vec::new());
    for (e, k) in c.edges() {
        let seg = (pts[e[0] as usize], pts[e[1] as usize]);
        if k {
            bold.push(seg);
        } else {
            thin.push(seg);
        }
    }
    svg.segments(&thin, &Stroke::solid([58, 110, 165], 0.8));
    svg.segments(&bold, &Stroke::solid([20, 20, 20], 2.6));
    svg.points(pts, point_radius(pts.len()), [30, 30, 30]);
    svg.finish()
}

/// A 2D geometric graph on `points`: edges in blue over the points, with an optional title,
/// 420 pixels wide.
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::graphs::{graph_2d, Kind};
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.5, 2.0)];
/// let g = graph_2d(&p, Kind::Emst).unwrap();
/// let svg = morpho::render::graph_svg(&p, &g, Some("EMST"));
/// assert!(svg.contains(">EMST</text>"));
/// ```
pub fn graph_svg(points: &[Point2], g: &Graph, title: Option<&str>) -> String {
    let mut svg = Svg::fit(points, 420.0);
    if let Some(t) = title {
        svg.title(t);
    }
    let segs: Vec<_> = g
        .edges
        .iter()
        .map(|e| (points[e[0] as usize], points[e[1] as usize]))
        .collect();
    svg.segments(&segs, &Stroke::solid([40, 90, 160], 1.2));
    svg.points(points, point_radius(points.len()).max(2.0), [20, 20, 20]);
    svg.finish()
}

/// A closed polygon through some of `points` (`cycle`: indices into them) in red over all the
/// points, with a title, `width` pixels wide.
pub fn cycle_svg(points: &[Point2], cycle: &[u32], title: &str, width: f64) -> String {
    let mut svg = Svg::fit(points, width);
    svg.title(title);
    let poly: Vec<Point2> = cycle.iter().map(|&i| points[i as usize]).collect();
    svg.polyline(&poly, true, &Stroke::solid([200, 60, 40], 1.6));
    svg.points(points, point_radius(points.len()), [30, 30, 30]);
    svg.finish()
}

/// A text label at point `index` of a figure, shifted `dx` pixels to the right.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLabel<'a> {
    /// The point labelled.
    pub index: usize,
    /// The text.
    pub text: &'a str,
    /// Horizontal shift in pixels (negative: to the left).
    pub dx: f64,
}

/// One state of a constriction: the graph's edges thin, the deleted ones dashed grey, the
/// polygon fat red (if any), the points dark with `highlight` (if any) larger in red, and the
/// `labels`; 330 pixels wide.
pub fn constriction_svg(
    points: &[Point2],
    graph: &[[u32; 2]],
    deleted: &[[u32; 2]],
    polygon: &[u32],
    title: &str,
    highlight: Option<usize>,
    labels: &[PointLabel],
) -> String {
    let key = |e: &[u32; 2]| [e[0].min(e[1]), e[0].max(e[1])];
    let dead: std::collections::HashSet<[u32; 2]> = deleted.iter().map(key).collect();
    let seg = |e: &[u32; 2]| (points[e[0] as usize], points[e[1] as usize]);
    let mut svg = Svg::fit(points, 330.0);
    svg.title(title);
    let (gone, kept): (Vec<_>, Vec<_>) = graph.iter().partition(|e| dead.contains(&key(e)));
    svg.segments(
        &kept.into_iter().map(seg).collect::<Vec<_>>(),
        &Stroke::solid([120, 150, 190], 0.8),
    );
    svg.segments(
        &gone.into_iter().map(seg).collect::<Vec<_>>(),
        &Stroke::dashed([150, 150, 150], 0.8),
    );
    if !polygon.is_empty() {
        let poly: Vec<_> = polygon.iter().map(|&i| points[i as usize]).collect();
        svg.polyline(&poly, true, &Stroke::solid([200, 60, 40], 2.4));
    }
    svg.points(points, 2.6, [20, 20, 20]);
    if let Some(h) = highlight {
        svg.point(points[h], 3.6, [200, 30, 30]);
    }
    for l in labels {
        svg.label(points[l.index], l.dx, 3.0, l.text, 10.0, [60, 60, 60]);
    }
    svg.finish()
}

/// A 2D boundary through `points` (`morpho boundary -o *.svg`): the Delaunay edges the
/// construction started from faint grey, the deleted edges dashed red, the polygon bold black,
/// the points blue and the points left out larger in orange.
///
/// ```
/// use morpho::boundary::{boundary_2d, Options2};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(1.0, 0.4), Point2::new(1.0, 2.0)];
/// let b = boundary_2d(&p, &Options2::default()).unwrap();
/// let svg = morpho::render::boundary_svg(&p, &b);
/// assert_eq!(svg.matches("<polygon").count(), 1);
/// assert_eq!(svg.matches("<circle").count(), 4 + b.left_out.len());
/// ```
pub fn boundary_svg(points: &[Point2], b: &Boundary2) -> String {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        lo = [lo[0].min(p.x), lo[1].min(p.y)];
        hi = [hi[0].max(p.x), hi[1].max(p.y)];
    }
    let size = 800.0;
    let ext = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    let s = (size - 40.0) / ext;
    let tx = |p: &Point2| (20.0 + (p.x - lo[0]) * s, size - 20.0 - (p.y - lo[1]) * s);
    let width = 40.0 + (hi[0] - lo[0]) * s;
    let height = 40.0 + (hi[1] - lo[1]) * s;
    let off = size - height;
    let mut w = String::new();
    // Writing into a String cannot fail.
    let _ = writeln!(
        w,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 {off:.1} {width:.1} {height:.1}">"#
    );
    let _ = writeln!(
        w,
        r#"<rect x="0" y="{off:.1}" width="{width:.1}" height="{height:.1}" fill="white"/>"#
    );
    let line = |w: &mut String, e: &[u32; 2]| {
        let (a, c) = (tx(&points[e[0] as usize]), tx(&points[e[1] as usize]));
        let _ = writeln!(
            w,
            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" />"#,
            a.0, a.1, c.0, c.1
        );
    };
    let _ = writeln!(w, r##"<g stroke="#bbb" stroke-width="0.5">"##);
    for e in &b.graph_edges {
        line(&mut w, e);
    }
    let _ = writeln!(w, "</g>");
    let _ = writeln!(
        w,
        r##"<g stroke="#d33" stroke-width="0.8" stroke-dasharray="3 2">"##
    );
    for e in &b.deleted {
        line(&mut w, e);
    }
    let _ = writeln!(w, "</g>");
    let poly: Vec<String> = b
        .polygon
        .iter()
        .map(|&i| {
            let (x, y) = tx(&points[i as usize]);
            format!("{x:.2},{y:.2}")
        })
        .collect();
    let _ = writeln!(
        w,
        r##"<polygon points="{}" fill="none" stroke="#000" stroke-width="2"/>"##,
        poly.join(" ")
    );
    let _ = writeln!(w, r##"<g fill="#16c">"##);
    for p in points {
        let (x, y) = tx(p);
        let _ = writeln!(w, r#"<circle cx="{x:.2}" cy="{y:.2}" r="2"/>"#);
    }
    let _ = writeln!(w, "</g>");
    let _ = writeln!(w, r##"<g fill="#e80">"##);
    for &i in &b.left_out {
        let (x, y) = tx(&points[i as usize]);
        let _ = writeln!(w, r#"<circle cx="{x:.2}" cy="{y:.2}" r="4"/>"#);
    }
    let _ = writeln!(w, "</g>\n</svg>");
    w
}

/// Most triangles [`contour_svg`] draws; larger triangulations are drawn as the contour only.
pub const CONTOUR_SVG_MAX_TRIANGLES: usize = 200_000;

/// A plane contour (`morpho contour -o *.svg`): the triangles (black ones orange, white ones
/// light), the contour cycles in red (holes dashed), the samples as dots (up to 20 000 of
/// them).
pub fn contour_svg(r: &PlaneContour) -> String {
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
    if r.triangles.len() <= CONTOUR_SVG_MAX_TRIANGLES {
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

/// How [`point_set_svg`] draws a point set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointsView<'a> {
    /// A value per point shown through `colormap` (black dots without).
    pub values: Option<&'a [f64]>,
    /// The colour map of `values`.
    pub colormap: Colormap,
    /// Values mapped to the ends of the map (default: the finite values' range).
    pub range: Option<(f64, f64)>,
    /// 3D points: rotation of the viewpoint about the up axis, degrees (as
    /// [`RenderOptions::azimuth_deg`]).
    pub azimuth_deg: f64,
    /// 3D points: height of the viewpoint above the horizontal plane, degrees.
    pub elevation_deg: f64,
    /// 3D points: the axis pointing up.
    pub up: UpAxis,
    /// Figure width in pixels.
    pub width: f64,
}

/// Dots for a point set: 2D points as they are; 3D points in the orthographic projection of
/// the viewpoint, far points first and faded towards white (depth cue). Returns the SVG and the
/// number of points skipped for non-finite coordinates.
///
/// ```
/// use morpho::mesh::PointSet;
/// use morpho::render::Colormap;
/// use morpho::render::{point_set_svg, PointsView};
/// use morpho::render::UpAxis;
/// let p = PointSet { dim: 3, coords: vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0], columns: vec![] };
/// let view = PointsView {
///     values: None, colormap: Colormap::Viridis, range: None,
///     azimuth_deg: 35.0, elevation_deg: 25.0, up: UpAxis::Y, width: 400.0,
/// };
/// let (svg, skipped) = point_set_svg(&p, &view);
/// assert_eq!((svg.matches("<circle").count(), skipped), (2, 0));
/// ```
pub fn point_set_svg(p: &PointSet, view: &PointsView) -> (String, usize) {
    let n = p.len();
    // 2D positions (3D: orthographic projection) and a depth per point.
    let (pos, depth): (Vec<Point2>, Vec<f64>) = if p.dim == 3 {
        let o = RenderOptions {
            azimuth_deg: view.azimuth_deg,
            elevation_deg: view.elevation_deg,
            up: view.up,
            ..Default::default()
        };
        let (r, u, e) = camera_basis(&o);
        (0..n)
            .map(|i| {
                let q = p.point(i);
                let v = Vector3::new(q[0], q[1], q[2]);
                (Point2::new(v.dot(&r), v.dot(&u)), v.dot(&e))
            })
            .unzip()
    } else {
        (0..n)
            .map(|i| (Point2::new(p.point(i)[0], p.point(i)[1]), 0.0))
            .unzip()
    };
    let mut b = Aabb2::empty();
    for q in &pos {
        if q.x.is_finite() && q.y.is_finite() {
            b.add(q.coords.as_slice());
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    if p.dim == 3 {
        // Far points first, near points on top.
        order.sort_by(|&a, &b| depth[a].total_cmp(&depth[b]));
    }
    let (dlo, dhi) = finite_range(depth.iter().copied()).unwrap_or((0.0, 1.0));
    let (vlo, vhi) = match view.values {
        Some(v) => view
            .range
            .or(finite_range(v.iter().copied()))
            .unwrap_or((0.0, 1.0)),
        None => (0.0, 1.0),
    };
    let mut s = Svg::new(b, view.width);
    let r = point_radius(n);
    for i in order {
        let mut c = match view.values {
            Some(v) => view.colormap.color_of(v[i], vlo, vhi),
            None => [0, 0, 0],
        };
        if p.dim == 3 && dhi > dlo {
            // Fade far points towards white (depth cue).
            let f = 0.55 * (dhi - depth[i]) / (dhi - dlo);
            for ch in &mut c {
                *ch = (*ch as f64 + f * (255.0 - *ch as f64)).round() as u8;
            }
        }
        s.point(pos[i], r, c);
    }
    let skipped = s.skipped();
    (s.finish(), skipped)
}

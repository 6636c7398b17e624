//! SVG pictures of 2D points, segments, polylines, polygons (with holes) and (coloured)
//! triangulations — the picture format of every 2D stage.
//!
//! [`Svg::new`] fixes a data box and a pixel width; data coordinates (y up) are mapped to SVG
//! pixels (y down) by one uniform scale (aspect kept) plus a margin. Every element is appended to
//! one `String`, so a figure with `n` elements costs O(n) time and memory; numbers are written
//! with at most two decimals and no trailing zeros. Elements with non-finite coordinates are
//! skipped (counted in [`Svg::skipped`]). Text is XML-escaped.
//!
//! Element kinds: points → `<circle>`, single segments → `<line>`, batches of segments,
//! polylines, polygons and triangles → `<path>`, labels and title → `<text>`.
//!
//! ```
//! use morpho::geom::{bbox2, Point2};
//! use morpho::render::{Stroke, Svg};
//!
//! let pts = [Point2::new(0.0, 0.0), Point2::new(2.0, 1.0)];
//! let mut svg = Svg::new(bbox2(&pts), 400.0);
//! svg.title("two points");
//! svg.points(&pts, 3.0, [0, 0, 0]);
//! svg.segment(pts[0], pts[1], &Stroke::dashed([200, 0, 0], 1.0));
//! let text = svg.finish();
//! assert_eq!(text.matches("<circle").count(), 2);
//! ```

use crate::geom::{Aabb2, Point2};
use crate::mesh::{Polygon, Shapes2};
use std::fmt::Write as _;

/// An sRGB colour.
pub type Rgb = [u8; 3];

/// How a line is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// Line colour.
    pub color: Rgb,
    /// Width in pixels.
    pub width: f64,
    /// Dashed instead of solid.
    pub dashed: bool,
    /// 0 (invisible) … 1 (opaque).
    pub opacity: f64,
}

impl Stroke {
    /// A solid opaque line.
    pub fn solid(color: Rgb, width: f64) -> Self {
        Stroke {
            color,
            width,
            dashed: false,
            opacity: 1.0,
        }
    }
    /// A dashed opaque line.
    pub fn dashed(color: Rgb, width: f64) -> Self {
        Stroke {
            dashed: true,
            ..Stroke::solid(color, width)
        }
    }
}

impl Default for Stroke {
    fn default() -> Self {
        Stroke::solid([0, 0, 0], 1.0)
    }
}

/// How an area is filled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fill {
    /// Fill colour.
    pub color: Rgb,
    /// 0 (invisible) … 1 (opaque).
    pub opacity: f64,
}

impl Fill {
    /// An opaque fill.
    pub fn solid(color: Rgb) -> Self {
        Fill {
            color,
            opacity: 1.0,
        }
    }
}

/// Builder of one SVG figure. See the module documentation.
#[derive(Debug, Clone)]
pub struct Svg {
    body: String,
    min: [f64; 2],
    max: [f64; 2],
    scale: f64,
    offset: [f64; 2],
    width: f64,
    height: f64,
    title: Option<String>,
    background: Option<Rgb>,
    skipped: usize,
}

const TITLE_H: f64 = 24.0;

impl Svg {
    /// A figure showing the data box `bbox` in `width_px` pixels (at least 16) with a margin of
    /// 4 % of the width. An empty box shows `[0,1]²`; a box of zero extent is widened to a unit
    /// square around its centre. The figure is at most `width_px` high (the longer side of the
    /// box spans the drawing area).
    pub fn new(bbox: Aabb2, width_px: f64) -> Self {
        let width = if width_px.is_finite() {
            width_px.clamp(16.0, 1.0e6)
        } else {
            800.0
        };
        let margin = (0.04 * width).max(2.0);
        let (mut min, mut max) =
            if bbox.is_empty() || !bbox.min.iter().chain(&bbox.max).all(|v| v.is_finite()) {
                ([0.0, 0.0], [1.0, 1.0])
            } else {
                (bbox.min, bbox.max)
            };
        // Half extents and halved coordinates never overflow, even for boxes near ±f64::MAX.
        let inner = width - 2.0 * margin;
        let mut half = [0.5 * max[0] - 0.5 * min[0], 0.5 * max[1] - 0.5 * min[1]];
        let mut scale = 0.5 * inner / half[0].max(half[1]);
        if !(scale.is_finite() && scale > 0.0) {
            // Zero (or subnormal) extent: a square around the centre.
            let c = [0.5 * min[0] + 0.5 * max[0], 0.5 * min[1] + 0.5 * max[1]];
            let m = c[0].abs().max(c[1].abs());
            let h = if m > 1e-300 { 0.5 * m } else { 0.5 };
            min = [c[0] - h, c[1] - h];
            max = [c[0] + h, c[1] + h];
            half = [h, h];
            scale = 0.5 * inner / h;
        }
        // Centre the shorter side horizontally; the height shrinks to the content.
        let used_w = 2.0 * (half[0] * scale);
        let height = (2.0 * (half[1] * scale) + 2.0 * margin).max(2.0 * margin + 1.0);
        let offset = [margin + 0.5 * (inner - used_w), margin];
        Svg {
            body: String::new(),
            min,
            max,
            scale,
            offset,
            width,
            height,
            title: None,
            background: Some([255, 255, 255]),
            skipped: 0,
        }
    }

    /// A figure fitted to the finite points of a set.
    pub fn fit(points: &[Point2], width_px: f64) -> Self {
        Svg::new(finite_bbox(points), width_px)
    }

    /// Width and height of the figure in pixels (without the title band).
    pub fn size(&self) -> (f64, f64) {
        (self.width, self.height)
    }

    /// Pixels per data unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Number of elements skipped for non-finite coordinates.
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// Background colour (`None`: transparent). White by default.
    pub fn set_background(&mut self, c: Option<Rgb>) {
        self.background = c;
    }

    /// Maps a data point to SVG pixel coordinates (y flipped).
    pub fn to_px(&self, p: Point2) -> [f64; 2] {
        [
            self.offset[0] + (0.5 * p.x - 0.5 * self.min[0]) * (2.0 * self.scale),
            self.offset[1] + (0.5 * self.max[1] - 0.5 * p.y) * (2.0 * self.scale),
        ]
    }

    fn ok(&mut self, ps: &[Point2]) -> bool {
        if ps.iter().all(|p| p.x.is_finite() && p.y.is_finite()) {
            true
        } else {
            self.skipped += 1;
            false
        }
    }

    /// A title above the drawing.
    pub fn title(&mut self, text: &str) {
        self.title = Some(text.to_string());
    }

    /// A filled disc of radius `r_px` pixels.
    pub fn point(&mut self, p: Point2, r_px: f64, color: Rgb) {
        if !self.ok(&[p]) {
            return;
        }
        let q = self.to_px(p);
        self.body.push_str("<circle cx=\"");
        num(&mut self.body, q[0]);
        self.body.push_str("\" cy=\"");
        num(&mut self.body, q[1]);
        self.body.push_str("\" r=\"");
        num(&mut self.body, r_px);
        self.body.push_str("\" fill=\"");
        hex(&mut self.body, color);
        self.body.push_str("\"/>\n");
    }

    /// Many discs of one radius and colour.
    pub fn points(&mut self, ps: &[Point2], r_px: f64, color: Rgb) {
        for &p in ps {
            self.point(p, r_px, color);
        }
    }

    /// One segment as a `<line>`.
    pub fn segment(&mut self, a: Point2, b: Point2, stroke: &Stroke) {
        if !self.ok(&[a, b]) {
            return;
        }
        let (p, q) = (self.to_px(a), self.to_px(b));
        self.body.push_str("<line x1=\"");
        num(&mut self.body, p[0]);
        self.body.push_str("\" y1=\"");
        num(&mut self.body, p[1]);
        self.body.push_str("\" x2=\"");
        num(&mut self.body, q[0]);
        self.body.push_str("\" y2=\"");
        num(&mut self.body, q[1]);
        self.body.push('"');
        stroke_attrs(&mut self.body, stroke);
        self.body.push_str("/>\n");
    }

    /// Many segments (graph edges) in one `<path>` of `M…L…` pairs; segments with non-finite
    /// ends are skipped. Nothing is written for an empty list.
    pub fn segments(&mut self, segs: &[(Point2, Point2)], stroke: &Stroke) {
        let start = self.body.len();
        self.body.push_str("<path d=\"");
        let mut any = false;
        for &(a, b) in segs {
            if !self.ok(&[a, b]) {
                continue;
            }
            any = true;
            let (p, q) = (self.to_px(a), self.to_px(b));
            self.body.push('M');
            pair(&mut self.body, p);
            self.body.push('L');
            pair(&mut self.body, q);
        }
        if !any {
            self.body.truncate(start);
            return;
        }
        self.body.push_str("\" fill=\"none\"");
        stroke_attrs(&mut self.body, stroke);
        self.body.push_str("/>\n");
    }

    /// An open or closed polyline (`<path>`, no fill). Fewer than two points draw nothing.
    pub fn polyline(&mut self, pts: &[Point2], closed: bool, stroke: &Stroke) {
        if pts.len() < 2 || !self.ok(pts) {
            return;
        }
        self.body.push_str("<path d=\"");
        self.ring(pts, closed);
        self.body.push_str("\" fill=\"none\"");
        stroke_attrs(&mut self.body, stroke);
        self.body.push_str("/>\n");
    }

    /// A chain of cubic Bézier segments `[p0, p1, p2, p3]` as one `<path>` of `C` commands (a
    /// true curve, not a sampled one); each segment starts where the one before ends (a segment
    /// whose `p0` differs starts a new subpath). `closed` appends `Z`.
    pub fn cubics(&mut self, segs: &[[Point2; 4]], closed: bool, stroke: &Stroke) {
        if segs.is_empty() || !segs.iter().all(|s| self.ok(s)) {
            return;
        }
        self.body.push_str("<path d=\"");
        for (k, s) in segs.iter().enumerate() {
            if k == 0 || segs[k - 1][3] != s[0] {
                self.body.push('M');
                let q = self.to_px(s[0]);
                pair(&mut self.body, q);
            }
            self.body.push('C');
            for (i, &p) in s[1..].iter().enumerate() {
                if i > 0 {
                    self.body.push(' ');
                }
                let q = self.to_px(p);
                pair(&mut self.body, q);
            }
        }
        if closed {
            self.body.push('Z');
        }
        self.body.push_str("\" fill=\"none\"");
        stroke_attrs(&mut self.body, stroke);
        self.body.push_str("/>\n");
    }

    /// A polygon with holes: ring 0 outer, the others holes, filled with `fill-rule="evenodd"`
    /// so that holes stay empty whatever their orientation. One `<path>`.
    pub fn polygon(&mut self, poly: &Polygon, fill: Option<Fill>, stroke: Option<&Stroke>) {
        let rings: Vec<&Vec<Point2>> = poly.rings.iter().filter(|r| r.len() >= 2).collect();
        if rings.is_empty() {
            return;
        }
        if rings
            .iter()
            .any(|r| !r.iter().all(|p| p.x.is_finite() && p.y.is_finite()))
        {
            self.skipped += 1;
            return;
        }
        self.body.push_str("<path d=\"");
        for r in rings {
            self.ring(r, true);
        }
        self.body.push('"');
        fill_attrs(&mut self.body, fill);
        self.body.push_str(" fill-rule=\"evenodd\"");
        if let Some(s) = stroke {
            stroke_attrs(&mut self.body, s);
        }
        self.body.push_str("/>\n");
    }

    /// One triangle with its own fill (coloured triangulations) and optional outline.
    pub fn triangle(&mut self, t: [Point2; 3], fill: Option<Fill>, stroke: Option<&Stroke>) {
        if !self.ok(&t) {
            return;
        }
        self.body.push_str("<path d=\"");
        self.ring(&t, true);
        self.body.push('"');
        fill_attrs(&mut self.body, fill);
        if let Some(s) = stroke {
            stroke_attrs(&mut self.body, s);
            self.body.push_str(" stroke-linejoin=\"round\"");
        }
        self.body.push_str("/>\n");
    }

    /// A text label whose lower-left corner is at `p`, shifted by (`dx`, `dy`) pixels
    /// (positive `dy` moves up), `size_px` high.
    pub fn label(&mut self, p: Point2, dx: f64, dy: f64, text: &str, size_px: f64, color: Rgb) {
        if !self.ok(&[p]) {
            return;
        }
        let q = self.to_px(p);
        self.body.push_str("<text x=\"");
        num(&mut self.body, q[0] + dx);
        self.body.push_str("\" y=\"");
        num(&mut self.body, q[1] - dy);
        self.body.push_str("\" font-size=\"");
        num(&mut self.body, size_px);
        self.body.push_str("\" font-family=\"sans-serif\" fill=\"");
        hex(&mut self.body, color);
        self.body.push_str("\">");
        escape(&mut self.body, text);
        self.body.push_str("</text>\n");
    }

    fn ring(&mut self, pts: &[Point2], closed: bool) {
        for (i, &p) in pts.iter().enumerate() {
            self.body.push(if i == 0 { 'M' } else { 'L' });
            let q = self.to_px(p);
            pair(&mut self.body, q);
        }
        if closed {
            self.body.push('Z');
        }
    }

    /// The SVG document.
    pub fn finish(self) -> String {
        let top = if self.title.is_some() { TITLE_H } else { 0.0 };
        let h = self.height + top;
        let mut s = String::with_capacity(self.body.len() + 512);
        s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        s.push_str("<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"");
        num(&mut s, self.width);
        s.push_str("\" height=\"");
        num(&mut s, h);
        s.push_str("\" viewBox=\"0 0 ");
        num(&mut s, self.width);
        s.push(' ');
        num(&mut s, h);
        s.push_str("\">\n");
        if let Some(bg) = self.background {
            s.push_str("<rect width=\"100%\" height=\"100%\" fill=\"");
            hex(&mut s, bg);
            s.push_str("\"/>\n");
        }
        if let Some(t) = &self.title {
            s.push_str("<text x=\"");
            num(&mut s, 0.5 * self.width);
            s.push_str("\" y=\"");
            num(&mut s, TITLE_H - 6.0);
            s.push_str("\" text-anchor=\"middle\" font-size=\"16\" font-family=\"sans-serif\">");
            escape(&mut s, t);
            s.push_str("</text>\n");
        }
        if top > 0.0 {
            s.push_str("<g transform=\"translate(0 ");
            num(&mut s, top);
            s.push_str(")\">\n");
        } else {
            s.push_str("<g>\n");
        }
        s.push_str(&self.body);
        s.push_str("</g>\n</svg>\n");
        s
    }
}

/// Writes `v` with at most two decimals and no trailing zeros (`12`, `3.5`, `-0.25`).
/// Non-finite values are written as `0`.
fn num(s: &mut String, v: f64) {
    if !v.is_finite() {
        s.push('0');
        return;
    }
    let r = (v * 100.0).round();
    if r.abs() >= 9.0e15 {
        let _ = write!(s, "{}", v.round());
        return;
    }
    let mut r = r as i64;
    if r < 0 {
        s.push('-');
        r = -r;
    }
    let (int, frac) = (r / 100, r % 100);
    let _ = write!(s, "{int}");
    if frac != 0 {
        if frac % 10 == 0 {
            let _ = write!(s, ".{}", frac / 10);
        } else {
            let _ = write!(s, ".{frac:02}");
        }
    }
    // "-0" for tiny negatives is valid SVG; keep it simple.
}

fn pair(s: &mut String, p: [f64; 2]) {
    num(s, p[0]);
    s.push(' ');
    num(s, p[1]);
}

fn hex(s: &mut String, c: Rgb) {
    let _ = write!(s, "#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

fn stroke_attrs(s: &mut String, st: &Stroke) {
    s.push_str(" stroke=\"");
    hex(s, st.color);
    s.push_str("\" stroke-width=\"");
    num(s, st.width.max(0.0));
    s.push('"');
    if st.dashed {
        let d = (3.0 * st.width).max(2.0);
        s.push_str(" stroke-dasharray=\"");
        num(s, d);
        s.push(' ');
        num(s, d);
        s.push('"');
    }
    if st.opacity < 1.0 {
        s.push_str(" stroke-opacity=\"");
        num(s, st.opacity.max(0.0));
        s.push('"');
    }
}

fn fill_attrs(s: &mut String, f: Option<Fill>) {
    match f {
        None => s.push_str(" fill=\"none\""),
        Some(f) => {
            s.push_str(" fill=\"");
            hex(s, f.color);
            s.push('"');
            if f.opacity < 1.0 {
                s.push_str(" fill-opacity=\"");
                num(s, f.opacity.max(0.0));
                s.push('"');
            }
        }
    }
}

/// Appends `text` with `& < > " '` escaped; control characters other than tab/newline are dropped
/// (they are not allowed in XML 1.0).
fn escape(s: &mut String, text: &str) {
    for ch in text.chars() {
        match ch {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\t' && c != '\n' => {}
            c => s.push(c),
        }
    }
}

/// Bounding box of the points with finite coordinates.
pub fn finite_bbox(points: &[Point2]) -> Aabb2 {
    let mut b = Aabb2::empty();
    for p in points {
        if p.x.is_finite() && p.y.is_finite() {
            b.add(p.coords.as_slice());
        }
    }
    b
}

/// Default figure width in pixels of the helpers below.
pub const DEFAULT_WIDTH: f64 = 800.0;

/// Point radius in pixels that stays legible for many points: 3 px for up to 1000 points,
/// shrinking with `1/sqrt(n)` down to 0.5 px.
pub fn point_radius(n: usize) -> f64 {
    if n <= 1000 {
        3.0
    } else {
        (3.0 * (1000.0 / n as f64).sqrt()).max(0.5)
    }
}

/// Black dots for a point set.
pub fn points_svg(points: &[Point2]) -> String {
    let mut svg = Svg::fit(points, DEFAULT_WIDTH);
    svg.points(points, point_radius(points.len()), [0, 0, 0]);
    svg.finish()
}

/// Light-blue filled polygons with dark outlines, and polylines in dark red.
pub fn polygon_svg(shapes: &Shapes2) -> String {
    let mut b = Aabb2::empty();
    for p in shapes
        .polygons
        .iter()
        .flat_map(|p| p.rings.iter().flatten())
    {
        if p.x.is_finite() && p.y.is_finite() {
            b.add(p.coords.as_slice());
        }
    }
    for p in shapes.polylines.iter().flat_map(|l| l.points.iter()) {
        if p.x.is_finite() && p.y.is_finite() {
            b.add(p.coords.as_slice());
        }
    }
    let mut svg = Svg::new(b, DEFAULT_WIDTH);
    let outline = Stroke::solid([30, 50, 90], 1.2);
    let fill = Fill {
        color: [150, 190, 230],
        opacity: 0.6,
    };
    for p in &shapes.polygons {
        svg.polygon(p, Some(fill), Some(&outline));
    }
    let line = Stroke::solid([160, 30, 30], 1.5);
    for l in &shapes.polylines {
        svg.polyline(&l.points, l.closed, &line);
    }
    svg.finish()
}

/// Triangles (index triples into `points`) outlined in grey over light fill, with the points on
/// top. Triangles with an index out of range are skipped.
pub fn triangulation_svg(points: &[Point2], triangles: &[[u32; 3]]) -> String {
    let mut svg = Svg::fit(points, DEFAULT_WIDTH);
    let edge = Stroke::solid([90, 90, 90], 0.6);
    let fill = Fill {
        color: [220, 232, 245],
        opacity: 1.0,
    };
    for t in triangles {
        if let (Some(a), Some(b), Some(c)) = (
            points.get(t[0] as usize),
            points.get(t[1] as usize),
            points.get(t[2] as usize),
        ) {
            svg.triangle([*a, *b, *c], Some(fill), Some(&edge));
        }
    }
    svg.points(points, 0.6 * point_radius(points.len()), [0, 0, 0]);
    svg.finish()
}

/// Triangles filled with per-triangle colours (e.g. the coloured triangulations of Dorgerloh
/// et al.), thin white edges. `colors.len()` must equal `triangles.len()`; missing colours are
/// drawn grey.
pub fn colored_triangulation_svg(
    points: &[Point2],
    triangles: &[[u32; 3]],
    colors: &[Rgb],
) -> String {
    let mut svg = Svg::fit(points, DEFAULT_WIDTH);
    let edge = Stroke::solid([255, 255, 255], 0.4);
    for (i, t) in triangles.iter().enumerate() {
        if let (Some(a), Some(b), Some(c)) = (
            points.get(t[0] as usize),
            points.get(t[1] as usize),
            points.get(t[2] as usize),
        ) {
            let col = colors.get(i).copied().unwrap_or(super::colormap::MISSING);
            svg.triangle([*a, *b, *c], Some(Fill::solid(col)), Some(&edge));
        }
    }
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numstr(v: f64) -> String {
        let mut s = String::new();
        num(&mut s, v);
        s
    }

    #[test]
    fn numbers_are_compact() {
        assert_eq!(numstr(12.0), "12");
        assert_eq!(numstr(3.5), "3.5");
        assert_eq!(numstr(-0.25), "-0.25");
        assert_eq!(numstr(0.004), "0");
        assert_eq!(numstr(1.005e3), "1005");
        assert_eq!(numstr(7.06), "7.06");
        assert_eq!(numstr(f64::NAN), "0");
        assert_eq!(numstr(1e20), "100000000000000000000");
    }

    #[test]
    fn mapping_flips_y_and_keeps_aspect() {
        let mut b = Aabb2::empty();
        b.add(&[0.0, 0.0]);
        b.add(&[2.0, 1.0]);
        let svg = Svg::new(b, 100.0);
        let (w, h) = svg.size();
        assert_eq!(w, 100.0);
        let m = 4.0;
        assert!((h - (2.0 * m + 46.0)).abs() < 1e-9, "{h}");
        let p0 = svg.to_px(Point2::new(0.0, 0.0));
        let p1 = svg.to_px(Point2::new(2.0, 1.0));
        assert!((p0[0] - m).abs() < 1e-9 && (p0[1] - (h - m)).abs() < 1e-9);
        assert!((p1[0] - (w - m)).abs() < 1e-9 && (p1[1] - m).abs() < 1e-9);
        // Equal scale on both axes.
        assert!(((p1[0] - p0[0]) / 2.0 - (p0[1] - p1[1])).abs() < 1e-9);
    }

    #[test]
    fn degenerate_boxes() {
        let svg = Svg::new(Aabb2::empty(), 100.0);
        assert!(svg.scale().is_finite() && svg.scale() > 0.0);
        let mut b = Aabb2::empty();
        b.add(&[5.0, 5.0]);
        let svg = Svg::new(b, 100.0);
        let p = svg.to_px(Point2::new(5.0, 5.0));
        assert!((p[0] - 50.0).abs() < 1e-9, "{p:?}");
        let svg = Svg::new(b, f64::NAN);
        assert_eq!(svg.size().0, 800.0);
        // Extreme boxes: near ±f64::MAX and subnormal.
        for (lo, hi) in [(-1.7e308, 1.7e308), (0.0, 1e-320), (1e300, 1e300)] {
            let mut b = Aabb2::empty();
            b.add(&[lo, lo]);
            b.add(&[hi, hi]);
            let svg = Svg::new(b, 100.0);
            let (w, h) = svg.size();
            assert!(
                svg.scale() > 0.0 && svg.scale().is_finite() && h <= w,
                "{lo} {hi}"
            );
            for v in [lo, hi] {
                let p = svg.to_px(Point2::new(v, v));
                assert!(
                    p.iter().all(|c| (0.0..=100.0).contains(c)),
                    "{lo} {hi} {p:?}"
                );
            }
        }
    }

    #[test]
    fn escaping() {
        let mut s = String::new();
        escape(&mut s, "a<b & \"c\" 'd'>\u{1}");
        assert_eq!(s, "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
    }

    #[test]
    fn skipped_nonfinite() {
        let mut svg = Svg::new(Aabb2::empty(), 100.0);
        svg.point(Point2::new(f64::NAN, 0.0), 1.0, [0, 0, 0]);
        svg.segments(
            &[(Point2::new(0.0, 0.0), Point2::new(f64::INFINITY, 0.0))],
            &Stroke::default(),
        );
        assert_eq!(svg.skipped(), 2);
        let s = svg.finish();
        assert!(!s.contains("<circle") && !s.contains("<path"));
    }
}

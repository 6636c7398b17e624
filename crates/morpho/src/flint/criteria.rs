//! The error criteria e1–e5 of an approximation of a polyline or polygon by a subsequence of
//! its vertices (Veltkamp 1992, §6.2 and Def. 7.4; reading notes A.1).
//!
//! For each approximating edge `v_p v_s` and the original vertices `v_p … v_s`:
//! - e1: largest distance to the closed segment; e2: largest distance to its line;
//! - e3 (strip, Def. 6.1): `(w_1 + w_2)/2` with `w_1`, `w_2` the largest distances on either
//!   side of the line (0 for an empty side);
//! - e4 (rectangle): half the shorter side of the minimum-area enclosing rectangle (any
//!   orientation; rotating over the edges of the convex hull);
//! - e5 (flintstone): `max{w_1, w_2}` of the flintstone's widths ([`super::Flintstone`]).
//!
//! An approximation's value is the maximum over its edges; an edge between neighbours has all
//! five 0. Invariants (tested): `e3 ≤ e2 ≤ e1`, `e2 ≤ e5`, `e3 ≤ e5`.
//! Cost O(k log k) for an edge over k vertices (the hull), O(N log N) per approximation.
//! Side decisions (which side of the line, hull turns) are exact (`orient2d`); the distances are
//! `f64`.

use super::disc::{at, Flintstone};
use crate::geom::predicates::raw::orient2d;
use crate::geom::vec::{dist, dot, sub};

/// The five error criteria of one edge or, as maxima, of an approximation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Criteria {
    /// Largest distance to the approximating segment.
    pub e1: f64,
    /// Largest distance to the approximating segment's line.
    pub e2: f64,
    /// Strip error `(w_1 + w_2)/2`.
    pub e3: f64,
    /// Half the shorter side of the minimum-area enclosing rectangle.
    pub e4: f64,
    /// Flintstone error `max{w_1, w_2}`.
    pub e5: f64,
}

impl Criteria {
    /// The component-wise maximum.
    pub fn max(self, o: Criteria) -> Criteria {
        Criteria {
            e1: self.e1.max(o.e1),
            e2: self.e2.max(o.e2),
            e3: self.e3.max(o.e3),
            e4: self.e4.max(o.e4),
            e5: self.e5.max(o.e5),
        }
    }
    /// The values as an array `[e1, e2, e3, e4, e5]`.
    pub fn as_array(&self) -> [f64; 5] {
        [self.e1, self.e2, self.e3, self.e4, self.e5]
    }
}

/// Distance from `x` to the closed segment `a b`.
pub(crate) fn dist_to_segment(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> f64 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    if l2 == 0.0 {
        return dist(a, x);
    }
    let s = (dot(sub(x, a), ab) / l2).clamp(0.0, 1.0);
    dist([a[0] + s * ab[0], a[1] + s * ab[1]], x)
}

/// Unsigned distance from `x` to the line through `a b` (`a ≠ b`).
fn dist_to_line(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> f64 {
    let ab = sub(b, a);
    let ax = sub(x, a);
    (ab[0] * ax[1] - ab[1] * ax[0]).abs() / dist(a, b)
}

/// Convex hull (counter-clockwise, no collinear points) by Andrew's monotone chain with exact
/// turns.
fn convex_hull(mut p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut h: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &x in iter {
            while h.len() >= start + 2 && orient2d(h[h.len() - 2], h[h.len() - 1], x) <= 0.0 {
                h.pop();
            }
            h.push(x);
        }
        h.pop();
    }
    h
}

/// Half the shorter side of the minimum-area rectangle enclosing `pts` (0 for < 3 hull points).
fn rectangle_half_width(pts: Vec<[f64; 2]>) -> f64 {
    let h = convex_hull(pts);
    if h.len() < 3 {
        return 0.0;
    }
    let mut best = (f64::INFINITY, 0.0);
    for i in 0..h.len() {
        let (a, b) = (h[i], h[(i + 1) % h.len()]);
        let l = dist(a, b);
        let u = [(b[0] - a[0]) / l, (b[1] - a[1]) / l];
        let (mut lo, mut hi, mut wid) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
        for &x in &h {
            let d = sub(x, a);
            let s = dot(d, u);
            lo = lo.min(s);
            hi = hi.max(s);
            wid = wid.max((u[0] * d[1] - u[1] * d[0]).abs());
        }
        let area = (hi - lo) * wid;
        if area < best.0 {
            best = (area, (hi - lo).min(wid));
        }
    }
    best.1 / 2.0
}

/// e1–e5 of the edge between positions `lo < hi` (wrapping modulo `points.len()`).
pub fn edge_criteria(points: &[[f64; 2]], lo: usize, hi: usize) -> Criteria {
    if hi <= lo + 1 {
        return Criteria::default();
    }
    let (a, b) = (at(points, lo), at(points, hi));
    let mut c = Criteria::default();
    let (mut w1, mut w2) = (0.0f64, 0.0f64);
    for p in lo + 1..hi {
        let x = at(points, p);
        c.e1 = c.e1.max(dist_to_segment(a, b, x));
        if a == b {
            continue;
        }
        let d = dist_to_line(a, b, x);
        c.e2 = c.e2.max(d);
        let o = orient2d(a, b, x);
        if o > 0.0 {
            w1 = w1.max(d);
        } else if o < 0.0 {
            w2 = w2.max(d);
        }
    }
    c.e3 = (w1 + w2) / 2.0;
    c.e4 = rectangle_half_width((lo..=hi).map(|p| at(points, p)).collect());
    c.e5 = if a == b {
        f64::INFINITY
    } else {
        Flintstone::of(points, lo, hi).error()
    };
    c
}

/// e1–e5 (maxima over the edges) of the approximation through the increasing positions
/// `positions` of `points`; `closed` adds the edge from the last back to the first (+N).
pub fn approximation_criteria(points: &[[f64; 2]], positions: &[usize], closed: bool) -> Criteria {
    let mut c = Criteria::default();
    for w in positions.windows(2) {
        c = c.max(edge_criteria(points, w[0], w[1]));
    }
    if closed && !positions.is_empty() {
        let (first, last) = (positions[0], positions[positions.len() - 1]);
        c = c.max(edge_criteria(points, last, first + points.len()));
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_of_square_and_strip_of_zigzag() {
        let sq = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 1.0]];
        assert_eq!(rectangle_half_width(sq), 1.0);
        let z = [[0.0, 0.0], [1.0, 1.0], [2.0, -3.0], [3.0, 0.0]];
        let c = edge_criteria(&z, 0, 3);
        assert_eq!((c.e1, c.e2, c.e3), (3.0, 3.0, 2.0));
        assert!(c.e5 >= c.e2 && c.e4 > 0.0, "{c:?}");
    }
}

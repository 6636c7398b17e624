//! The 2D G¹ cubic Bézier curve through every vertex of a polygon or polyline (Veltkamp 1992,
//! §9.2; paper §5.1; NOTES B.2).
//!
//! 1. A unit tangent `T_i` per vertex from `a = v_{i−1} − v_i`, `b = v_{i+1} − v_i` with one
//!    of three weightings: by length `b − a` (the thesis default), uniform `b/|b| − a/|a|`, by
//!    inverse length `b/|b|² − a/|a|²`. Ends of an open polyline take their edge direction.
//! 2. The segment from `v_{i−1}` to `v_i` is the cubic `p0 = v_{i−1}`,
//!    `p1 = p0 + ((p3−p0)·T_{i−1}) T_{i−1}/3`, `p2 = p3 + ((p0−p3)·T_i) T_i/3`, `p3 = v_i`
//!    (a third of the projection of the other end onto the tangent line).
//! 3. G¹ at `v_i` holds iff `(a·T_i)(b·T_i) < 0` (the projections of both neighbours fall on
//!    opposite sides). Under weightings 1 and 3 this fails exactly when
//!    `a·b ≥ min(|a|², |b|²)`; weighting 2 fails only where the polygon doubles back (NOTES
//!    B.2, derived there). The text gives no repair: as the notes propose, a failing vertex is
//!    switched to weighting 2 and **reported** ([`CurveFailure`]), with its kind
//!    (tangent-line continuity only, or a zero handle that makes the curve non-regular).
//!
//! Repeated consecutive vertices are refused ([`SmoothError::RepeatedVertex`]); a polygon
//! that doubles back exactly has no G¹ repair ([`SmoothError::DoublesBack`]). O(N).

use super::SmoothError;
use crate::geom::{vec, Point2};

/// The tangent weighting of §9.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CurveWeighting {
    /// `T ∝ v_{i+1} − v_{i−1}` (the thesis default).
    #[default]
    Length,
    /// `T ∝` the sum of the unit edge vectors.
    Uniform,
    /// `T ∝` the sum of the edge vectors divided by their squared lengths.
    InverseLength,
}

/// Why G¹ failed at a vertex under the requested weighting.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailureKind {
    /// Both handles point the same way: only the tangent *line* is continuous (a cusp).
    TangentLineOnly,
    /// A handle has length zero (`a·T = 0` or `b·T = 0`): the curve is not regular there.
    ZeroHandle,
}

/// A vertex where the requested weighting does not give G¹, and what was done.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CurveFailure {
    /// Index of the polygon vertex.
    pub vertex: usize,
    /// How it failed.
    pub kind: FailureKind,
}

/// The G¹ curve: one cubic per polygon edge.
#[derive(Debug, Clone, PartialEq)]
pub struct G1Curve {
    /// Whether the curve closes (segment N−1 runs from the last vertex back to the first).
    pub closed: bool,
    /// Control points `[p0, p1, p2, p3]` of each segment, in polygon order.
    pub segments: Vec<[[f64; 2]; 4]>,
    /// The unit tangent used at each vertex (after repair).
    pub tangents: Vec<[f64; 2]>,
    /// Every vertex where the requested weighting failed G¹; each was repaired with the
    /// uniform weighting.
    pub failures: Vec<CurveFailure>,
}

fn unit(v: [f64; 2]) -> Option<[f64; 2]> {
    let l = vec::norm(v);
    (l > 0.0 && l.is_finite()).then(|| vec::scale(v, 1.0 / l))
}

/// The raw (unnormalised) tangent of weighting `w` from `a = v_{i−1} − v_i`, `b = v_{i+1} − v_i`.
pub fn tangent(a: [f64; 2], b: [f64; 2], w: CurveWeighting) -> [f64; 2] {
    match w {
        CurveWeighting::Length => vec::sub(b, a),
        CurveWeighting::Uniform => vec::sub(
            vec::scale(b, 1.0 / vec::norm(b)),
            vec::scale(a, 1.0 / vec::norm(a)),
        ),
        CurveWeighting::InverseLength => vec::sub(
            vec::scale(b, 1.0 / vec::norm2(b)),
            vec::scale(a, 1.0 / vec::norm2(a)),
        ),
    }
}

/// The G¹ test at a vertex `v`: `None` when `(a·T)(b·T) < 0`, else the failure kind. A
/// handle `|a·T|/3` shorter than `1e-6 |v|` counts as zero: stored in absolute coordinates
/// its direction would carry a rounding error above 1e-9 (see `Joint::rounding`), and one
/// below `ε|v|` vanishes altogether (seen on Benelux 1:10m with weighting 3). `rel` is 3e-6
/// for the requested weighting and 0 for the uniform repair (which has no better choice).
fn g1_test(
    v: [f64; 2],
    a: [f64; 2],
    b: [f64; 2],
    t: Option<[f64; 2]>,
    rel: f64,
) -> Option<FailureKind> {
    let Some(t) = t else {
        return Some(FailureKind::ZeroHandle);
    };
    let (pa, pb) = (vec::dot(a, t), vec::dot(b, t));
    let tiny = rel * vec::norm(v);
    if pa.abs() <= tiny || pb.abs() <= tiny {
        Some(FailureKind::ZeroHandle)
    } else if (pa < 0.0) == (pb < 0.0) {
        Some(FailureKind::TangentLineOnly)
    } else {
        None
    }
}

fn check_input(points: &[Point2], closed: bool) -> Result<Vec<[f64; 2]>, SmoothError> {
    let need = if closed { 3 } else { 2 };
    if points.len() < need {
        return Err(SmoothError::TooFew {
            got: points.len(),
            need,
        });
    }
    let v: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
    if let Some(index) = v
        .iter()
        .position(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        return Err(SmoothError::NonFinite { index });
    }
    for i in 1..v.len() {
        if v[i] == v[i - 1] {
            return Err(SmoothError::RepeatedVertex { index: i });
        }
    }
    if closed && v[0] == v[v.len() - 1] {
        return Err(SmoothError::RepeatedVertex { index: 0 });
    }
    Ok(v)
}

/// The closed (or open) G¹ cubic curve through every vertex (see the module doc).
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::smooth::{g1_curve, CurveWeighting};
/// let sq = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let c = g1_curve(&sq, true, CurveWeighting::Length).unwrap();
/// assert_eq!(c.segments.len(), 4);
/// assert!(c.failures.is_empty());
/// assert_eq!(c.segments[0][3], [1.0, 0.0]); // interpolates the vertices
/// ```
pub fn g1_curve(
    points: &[Point2],
    closed: bool,
    weighting: CurveWeighting,
) -> Result<G1Curve, SmoothError> {
    let v = check_input(points, closed)?;
    let n = v.len();
    let mut tangents = Vec::with_capacity(n);
    let mut failures = Vec::new();
    for i in 0..n {
        let interior = closed || (i > 0 && i + 1 < n);
        if !interior {
            let d = if i == 0 {
                vec::sub(v[1], v[0])
            } else {
                vec::sub(v[n - 1], v[n - 2])
            };
            tangents.push(unit(d).expect("distinct consecutive vertices"));
            continue;
        }
        let a = vec::sub(v[(i + n - 1) % n], v[i]);
        let b = vec::sub(v[(i + 1) % n], v[i]);
        let t = unit(tangent(a, b, weighting));
        match g1_test(v[i], a, b, t, 3e-6) {
            None => tangents.push(t.unwrap()),
            Some(kind) => {
                failures.push(CurveFailure { vertex: i, kind });
                let t2 = unit(tangent(a, b, CurveWeighting::Uniform));
                if g1_test(v[i], a, b, t2, 0.0).is_some() {
                    return Err(SmoothError::DoublesBack { index: i });
                }
                tangents.push(t2.unwrap());
            }
        }
    }
    let count = if closed { n } else { n - 1 };
    let segments = (0..count)
        .map(|s| {
            let (i, j) = (s, (s + 1) % n);
            let (p0, p3) = (v[i], v[j]);
            let (ti, tj) = (tangents[i], tangents[j]);
            let p1 = vec::add_scaled(p0, vec::dot(vec::sub(p3, p0), ti) / 3.0, ti);
            let p2 = vec::add_scaled(p3, vec::dot(vec::sub(p0, p3), tj) / 3.0, tj);
            [p0, p1, p2, p3]
        })
        .collect();
    Ok(G1Curve {
        closed,
        segments,
        tangents,
        failures,
    })
}

/// The joints of a curve (segment k's end against segment k+1's start; closed curves include
/// the last joint back to segment 0), measured on the Bézier end tangents.
pub fn curve_joints(c: &G1Curve) -> Vec<super::Joint> {
    let segs: Vec<super::BezierCurve<2>> = c
        .segments
        .iter()
        .map(|s| super::BezierCurve {
            control: s.to_vec(),
        })
        .collect();
    let n = segs.len();
    let count = if c.closed { n } else { n.saturating_sub(1) };
    (0..count)
        .map(|k| super::bezier::joint(&segs[k], &segs[(k + 1) % n]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_never_fails_and_length_fails_on_a_sharp_turn() {
        // sharp turn at vertex 1: long leg a, short leg b, a·b > |b|²
        let p = [(0.0, 0.0), (10.0, 0.0), (9.0, 0.5), (5.0, 5.0)].map(|(x, y)| Point2::new(x, y));
        let c = g1_curve(&p, true, CurveWeighting::Length).unwrap();
        assert!(c.failures.iter().any(|f| f.vertex == 1));
        for j in curve_joints(&c) {
            assert!(j.is_g1(1e-12), "{j:?}");
        }
        let u = g1_curve(&p, true, CurveWeighting::Uniform).unwrap();
        assert!(u.failures.is_empty());
    }

    #[test]
    fn doubling_back_is_refused() {
        let p = [(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        let e = g1_curve(&p, true, CurveWeighting::Length).unwrap_err();
        assert_eq!(e, SmoothError::DoublesBack { index: 1 });
    }
}

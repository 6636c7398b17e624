//! Smallest enclosing disc and ball (Welzl 1991, "Smallest enclosing disks (balls and
//! ellipsoids)", in the randomized incremental form; expected linear time).
//!
//! # Algorithm
//! The points are shuffled with a seeded ChaCha RNG (so results are deterministic), then
//! `solve(i, F)` — the smallest ball containing the first `i` points with the points `F` on its
//! boundary — is computed by the nested incremental loops of Welzl's method: start from the
//! smallest ball through `F`, and whenever a point `p_j` (j < i) lies outside the current ball,
//! replace it by `solve(j, F ∪ {p_j})`. With |F| = d + 1 the ball is fixed. Expected O(n) time
//! for fixed dimension (2 or 3), O(n) memory, recursion depth ≤ d + 1.
//!
//! # Exact decisions, inexact constructions
//! The current ball is represented by its *support* (the 1–4 input points that define it), never
//! by its floating-point centre, and "is p outside?" is decided exactly from the support points:
//! - 1 point: coordinate equality;
//! - 2 points (diametral ball, 2D and 3D): sign of (a − p)·(b − p) (Thales), exact;
//! - 3 points in 2D: [`incircle_sign`](super::predicates::incircle_sign) with the orientation from
//!   `orient2d`;
//! - 3 points in 3D (the ball whose equator is the circle through a, b, c): sign of the degree-6
//!   polynomial |n|²|w|² − |u|² w·(v×n) − |v|² w·(n×u) (u = b−a, v = c−a, w = p−a, n = u×v),
//!   which is |n|²(|p−o|² − r²); exact;
//! - 4 points in 3D: [`insphere`](super::predicates::raw::insphere) with the orientation from
//!   `orient3d`.
//!
//! The two polynomial tests are evaluated in floating point with a forward error bound (a
//! static filter with a 50× safety margin over the worst-case bound); when the value is within the bound,
//! the sign is recomputed exactly with Shewchuk-style floating-point expansions (error-free
//! `two_sum`/`two_prod`). So every decision is exact (barring overflow/underflow of the
//! coordinates' products), points exactly on the boundary count as inside, duplicates are
//! harmless, and collinear/cocircular/cospherical sets give a valid support. Centre and radius
//! are then constructed in `f64`: the radius is the largest distance from the centre to a
//! support point.
//!
//! # Output
//! `support` lists the indices (into the input) of the points that define the ball: 1 when all
//! points coincide, otherwise 2–3 (disc) or 2–4 (ball). All of them lie on the boundary; in
//! cocircular/cospherical configurations the set need not be a minimal one (e.g. three corners of
//! a rectangle where two diagonal corners would do).
//!
//! # Errors
//! Empty input and non-finite coordinates.

use super::expansion::{cross as xcross, dot as xdot, Expansion};
use super::predicates::raw;
use super::vec::{cross, dist, dist2, dot, sub};
use super::{Point2, Point3};
use crate::{Error, Result};
use rand::seq::SliceRandom;
use rand::SeedableRng;

/// The smallest disc containing a set of plane points.
#[derive(Debug, Clone, PartialEq)]
pub struct EnclosingDisc {
    /// Centre of the disc.
    pub center: Point2,
    /// Radius (0 for a single point).
    pub radius: f64,
    /// Indices of the input points defining the disc (all on its boundary).
    pub support: Vec<usize>,
}

/// The smallest ball containing a set of points in space.
#[derive(Debug, Clone, PartialEq)]
pub struct EnclosingBall {
    /// Centre of the ball.
    pub center: Point3,
    /// Radius (0 for a single point).
    pub radius: f64,
    /// Indices of the input points defining the ball (all on its boundary).
    pub support: Vec<usize>,
}

/// Smallest enclosing disc of `points` (Welzl). Err for empty input or non-finite coordinates.
///
/// ```
/// use morpho::geom::{smallest_enclosing_disc, Point2};
/// let d = smallest_enclosing_disc(&[Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(1.0, 0.5)]).unwrap();
/// assert_eq!((d.center, d.radius), (Point2::new(1.0, 0.0), 1.0));
/// assert_eq!(d.support, vec![0, 1]);
/// ```
pub fn smallest_enclosing_disc(points: &[Point2]) -> Result<EnclosingDisc> {
    let pts: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
    let support = solve_all(&pts, outside2)?;
    let s: Vec<[f64; 2]> = support.iter().map(|&i| pts[i]).collect();
    let c = center2(&s);
    let radius = s.iter().map(|p| dist(*p, c)).fold(0.0, f64::max);
    Ok(EnclosingDisc {
        center: Point2::new(c[0], c[1]),
        radius,
        support,
    })
}

/// Smallest enclosing ball of `points` (Welzl). Err for empty input or non-finite coordinates.
///
/// ```
/// use morpho::geom::{smallest_enclosing_ball, Point3};
/// let pts = [Point3::new(1.0, 0.0, 0.0), Point3::new(-1.0, 0.0, 0.0), Point3::new(0.0, 0.5, 0.5)];
/// let b = smallest_enclosing_ball(&pts).unwrap();
/// assert_eq!((b.center, b.radius), (Point3::origin(), 1.0));
/// ```
pub fn smallest_enclosing_ball(points: &[Point3]) -> Result<EnclosingBall> {
    let pts: Vec<[f64; 3]> = points.iter().map(|p| [p.x, p.y, p.z]).collect();
    let support = solve_all(&pts, outside3)?;
    let s: Vec<[f64; 3]> = support.iter().map(|&i| pts[i]).collect();
    let c = center3(&s);
    let radius = s.iter().map(|p| dist(*p, c)).fold(0.0, f64::max);
    Ok(EnclosingBall {
        center: Point3::new(c[0], c[1], c[2]),
        radius,
        support,
    })
}

/// Validates, shuffles, runs Welzl and maps the support back to input indices.
fn solve_all<const D: usize>(
    pts: &[[f64; D]],
    outside: fn(&[[f64; D]], &[f64; D]) -> bool,
) -> Result<Vec<usize>> {
    if pts.is_empty() {
        return Err(Error::invalid(
            "smallest enclosing ball of an empty point set",
        ));
    }
    if let Some(i) = pts.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        return Err(Error::invalid(format!(
            "point {i} has a non-finite coordinate"
        )));
    }
    let mut order: Vec<usize> = (0..pts.len()).collect();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x5eed_ba11);
    order.shuffle(&mut rng);
    let shuffled: Vec<[f64; D]> = order.iter().map(|&i| pts[i]).collect();
    let mut fixed = Vec::with_capacity(D + 1);
    let sup = solve(&shuffled, shuffled.len(), &mut fixed, outside);
    let mut sup: Vec<usize> = sup.into_iter().map(|i| order[i]).collect();
    sup.sort_unstable();
    Ok(sup)
}

/// Support of the smallest ball containing `pts[..upto]` with `pts[fixed]` on its boundary.
fn solve<const D: usize>(
    pts: &[[f64; D]],
    upto: usize,
    fixed: &mut Vec<usize>,
    outside: fn(&[[f64; D]], &[f64; D]) -> bool,
) -> Vec<usize> {
    let mut sup = fixed.clone();
    if fixed.len() == D + 1 {
        return sup;
    }
    let mut spts: Vec<[f64; D]> = sup.iter().map(|&i| pts[i]).collect();
    for i in 0..upto {
        if outside(&spts, &pts[i]) {
            fixed.push(i);
            sup = solve(pts, i, fixed, outside);
            fixed.pop();
            spts.clear();
            spts.extend(sup.iter().map(|&k| pts[k]));
        }
    }
    sup
}

// ---------------------------------------------------------------------------------------------
// Exact decisions.

/// Relative factor of the static filters: the worst-case forward error of the evaluated
/// expressions is below 16·ε·(magnitude bound) (≤ 12 rounding steps on any path); 50× margin.
const FILTER: f64 = 800.0 * f64::EPSILON;

fn outside2(s: &[[f64; 2]], p: &[f64; 2]) -> bool {
    match s {
        [] => true,
        [a] => a != p,
        [a, b] => diametral_outside(a, b, p),
        [a, b, c] => {
            let o = raw::orient2d(*a, *b, *c);
            if o != 0.0 {
                // the exact sign (its integer stage settles the near-cocircular tests of
                // densely sampled circles far faster than robust's expansions)
                (super::predicates::incircle_sign(*a, *b, *c, *p) as f64) * o.signum() < 0.0
            } else {
                // Collinear support cannot arise with exact decisions; stay well-defined anyway.
                let (x, y) = farthest_pair(s);
                diametral_outside(&s[x], &s[y], p)
            }
        }
        _ => true,
    }
}

fn outside3(s: &[[f64; 3]], p: &[f64; 3]) -> bool {
    match s {
        [] => true,
        [a] => a != p,
        [a, b] => diametral_outside(a, b, p),
        [a, b, c] => circle_ball_outside(a, b, c, p),
        [a, b, c, d] => {
            let o = raw::orient3d(*a, *b, *c, *d);
            if o != 0.0 {
                raw::insphere(*a, *b, *c, *d, *p) * o.signum() < 0.0
            } else {
                // Coplanar support cannot arise with exact decisions; stay well-defined anyway.
                circle_ball_outside(a, b, c, p)
            }
        }
        _ => true,
    }
}

fn farthest_pair<const D: usize>(s: &[[f64; D]]) -> (usize, usize) {
    let mut best = (0, 0, -1.0);
    for i in 0..s.len() {
        for j in i + 1..s.len() {
            let d = dist2(s[i], s[j]);
            if d > best.2 {
                best = (i, j, d);
            }
        }
    }
    (best.0, best.1)
}

/// p strictly outside the ball with diameter ab ⇔ (a − p)·(b − p) > 0.
fn diametral_outside<const D: usize>(a: &[f64; D], b: &[f64; D], p: &[f64; D]) -> bool {
    let mut val = 0.0;
    let mut mag = 0.0;
    for k in 0..D {
        let (x, y) = (a[k] - p[k], b[k] - p[k]);
        val += x * y;
        mag += (x * y).abs();
    }
    if val.abs() > FILTER * mag {
        return val > 0.0;
    }
    let mut sum = Expansion::zero();
    for k in 0..D {
        sum = sum.add(&Expansion::diff(a[k], p[k]).mul(&Expansion::diff(b[k], p[k])));
    }
    sum.sign() > 0
}

/// p strictly outside the smallest ball through a, b, c (centre in their plane).
fn circle_ball_outside(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], p: &[f64; 3]) -> bool {
    let (u, v, w) = (sub(*b, *a), sub(*c, *a), sub(*p, *a));
    let acr = |x: [f64; 3], y: [f64; 3]| {
        [
            x[1] * y[2] + x[2] * y[1],
            x[2] * y[0] + x[0] * y[2],
            x[0] * y[1] + x[1] * y[0],
        ]
    };
    let abs = |x: [f64; 3]| x.map(f64::abs);
    let n = cross(u, v);
    let val =
        dot(n, n) * dot(w, w) - dot(u, u) * dot(w, cross(v, n)) - dot(v, v) * dot(w, cross(n, u));
    let na = acr(abs(u), abs(v));
    let mag = dot(na, na) * dot(w, w)
        + dot(u, u) * dot(abs(w), acr(abs(v), na))
        + dot(v, v) * dot(abs(w), acr(na, abs(u)));
    let nn = dot(n, n);
    if nn > FILTER * dot(na, na) {
        // Non-collinear support (the usual case): the filter decides unless val is tiny.
        if val.abs() > FILTER * mag {
            return val > 0.0;
        }
    }
    // Exact evaluation.
    let e = |x: &[f64; 3], y: &[f64; 3]| [0, 1, 2].map(|k| Expansion::diff(x[k], y[k]));
    let (u, v, w) = (e(b, a), e(c, a), e(p, a));
    let n = xcross(&u, &v);
    let nn = xdot(&n, &n);
    if nn.sign() == 0 {
        // Collinear support cannot arise with exact decisions; stay well-defined anyway.
        let s = [*a, *b, *c];
        let (x, y) = farthest_pair(&s);
        return diametral_outside(&s[x], &s[y], p);
    }
    let val = nn
        .mul(&xdot(&w, &w))
        .sub(&xdot(&u, &u).mul(&xdot(&w, &xcross(&v, &n))))
        .sub(&xdot(&v, &v).mul(&xdot(&w, &xcross(&n, &u))));
    val.sign() > 0
}

// ---------------------------------------------------------------------------------------------
// Constructions (inexact).

fn center2(s: &[[f64; 2]]) -> [f64; 2] {
    match s {
        [a] => *a,
        [a, b] => [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
        [a, b, c] => {
            let (ux, uy, vx, vy) = (b[0] - a[0], b[1] - a[1], c[0] - a[0], c[1] - a[1]);
            let d = 2.0 * (ux * vy - uy * vx);
            if d == 0.0 {
                let (x, y) = farthest_pair(s);
                return center2(&[s[x], s[y]]);
            }
            let (uu, vv) = (ux * ux + uy * uy, vx * vx + vy * vy);
            [
                a[0] + (vy * uu - uy * vv) / d,
                a[1] + (ux * vv - vx * uu) / d,
            ]
        }
        _ => [f64::NAN; 2],
    }
}

fn center3(s: &[[f64; 3]]) -> [f64; 3] {
    let sub =
        |x: &[f64; 3], y: &[f64; 3]| nalgebra::Vector3::new(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
    match s {
        [a] => *a,
        [a, b] => [0, 1, 2].map(|k| 0.5 * (a[k] + b[k])),
        [a, b, c] => {
            let (u, v) = (sub(b, a), sub(c, a));
            let n = u.cross(&v);
            let nn = n.norm_squared();
            if nn == 0.0 {
                let (x, y) = farthest_pair(s);
                return center3(&[s[x], s[y]]);
            }
            let m = (u.norm_squared() * v.cross(&n) + v.norm_squared() * n.cross(&u)) / (2.0 * nn);
            [0, 1, 2].map(|k| a[k] + m[k])
        }
        [a, b, c, d] => {
            let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
            let det = 2.0 * u.dot(&v.cross(&w));
            if det == 0.0 {
                return center3(&[*a, *b, *c]);
            }
            let m = (u.norm_squared() * v.cross(&w)
                + v.norm_squared() * w.cross(&u)
                + w.norm_squared() * u.cross(&v))
                / det;
            [0, 1, 2].map(|k| a[k] + m[k])
        }
        _ => [f64::NAN; 3],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use rand::Rng;

    /// Brute force from the definition: the smallest of all candidate discs (diametral discs of
    /// pairs, circumdiscs of triples) that contains every point (relative tolerance 1e-12).
    fn brute2(p: &[Point2]) -> f64 {
        let pts: Vec<[f64; 2]> = p.iter().map(|p| [p.x, p.y]).collect();
        let scale = 1.0 + pts.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
        let mut best = f64::INFINITY;
        let mut consider = |s: &[[f64; 2]]| {
            let c = center2(s);
            let r = s
                .iter()
                .map(|q| ((q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2)).sqrt())
                .fold(0.0, f64::max);
            if pts.iter().all(|q| {
                ((q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2)).sqrt() <= r + 1e-12 * scale
            }) {
                best = best.min(r);
            }
        };
        if pts.len() == 1 {
            return 0.0;
        }
        for i in 0..pts.len() {
            for j in i + 1..pts.len() {
                consider(&[pts[i], pts[j]]);
                for k in j + 1..pts.len() {
                    if raw::orient2d(pts[i], pts[j], pts[k]) != 0.0 {
                        consider(&[pts[i], pts[j], pts[k]]);
                    }
                }
            }
        }
        best
    }

    fn brute3(p: &[Point3]) -> f64 {
        let pts: Vec<[f64; 3]> = p.iter().map(|p| [p.x, p.y, p.z]).collect();
        let scale = 1.0 + pts.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
        let dist = |a: &[f64; 3], b: &[f64; 3]| {
            ((0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>()).sqrt()
        };
        let mut best = f64::INFINITY;
        let mut consider = |s: &[[f64; 3]]| {
            let c = center3(s);
            let r = s.iter().map(|q| dist(q, &c)).fold(0.0, f64::max);
            if pts.iter().all(|q| dist(q, &c) <= r + 1e-12 * scale) {
                best = best.min(r);
            }
        };
        if pts.len() == 1 {
            return 0.0;
        }
        let n = pts.len();
        for i in 0..n {
            for j in i + 1..n {
                consider(&[pts[i], pts[j]]);
                for k in j + 1..n {
                    let u = nalgebra::Vector3::from(pts[j]) - nalgebra::Vector3::from(pts[i]);
                    let v = nalgebra::Vector3::from(pts[k]) - nalgebra::Vector3::from(pts[i]);
                    if u.cross(&v).norm() > 1e-12 * scale * scale {
                        consider(&[pts[i], pts[j], pts[k]]);
                    }
                    for l in k + 1..n {
                        if raw::orient3d(pts[i], pts[j], pts[k], pts[l]) != 0.0 {
                            consider(&[pts[i], pts[j], pts[k], pts[l]]);
                        }
                    }
                }
            }
        }
        best
    }

    fn check2(p: &[Point2]) -> EnclosingDisc {
        let d = smallest_enclosing_disc(p).unwrap();
        let scale = 1.0
            + p.iter()
                .fold(0.0f64, |m, q| m.max(q.x.abs()).max(q.y.abs()));
        for q in p {
            assert!(
                (q - d.center).norm() <= d.radius + 1e-12 * scale,
                "point outside"
            );
        }
        for &i in &d.support {
            assert!(
                ((p[i] - d.center).norm() - d.radius).abs() <= 1e-12 * scale,
                "support not on boundary"
            );
        }
        assert!(!d.support.is_empty() && d.support.len() <= 3);
        let b = brute2(p);
        assert!(
            (d.radius - b).abs() <= 1e-9 * b.max(1e-300),
            "radius {} vs brute {}",
            d.radius,
            b
        );
        d
    }

    fn check3(p: &[Point3]) -> EnclosingBall {
        let d = smallest_enclosing_ball(p).unwrap();
        let scale = 1.0
            + p.iter().fold(0.0f64, |m, q| {
                m.max(q.x.abs()).max(q.y.abs()).max(q.z.abs())
            });
        for q in p {
            assert!(
                (q - d.center).norm() <= d.radius + 1e-12 * scale,
                "point outside"
            );
        }
        for &i in &d.support {
            assert!(
                ((p[i] - d.center).norm() - d.radius).abs() <= 1e-12 * scale,
                "support not on boundary"
            );
        }
        assert!(!d.support.is_empty() && d.support.len() <= 4);
        let b = brute3(p);
        assert!(
            (d.radius - b).abs() <= 1e-9 * b.max(1e-300),
            "radius {} vs brute {}",
            d.radius,
            b
        );
        d
    }

    #[test]
    fn errors() {
        assert!(smallest_enclosing_disc(&[]).is_err());
        assert!(smallest_enclosing_ball(&[]).is_err());
        assert!(smallest_enclosing_disc(&[Point2::new(f64::NAN, 0.0)]).is_err());
        assert!(smallest_enclosing_ball(&[Point3::new(0.0, f64::INFINITY, 0.0)]).is_err());
    }

    #[test]
    fn single_and_equal_points() {
        let d = check2(&[Point2::new(3.0, 4.0)]);
        assert_eq!((d.radius, d.support.clone()), (0.0, vec![0]));
        let d = check2(&[Point2::new(3.0, 4.0); 7]);
        assert_eq!((d.radius, d.support.len()), (0.0, 1));
        let b = check3(&[Point3::new(1.0, 2.0, 3.0); 5]);
        assert_eq!((b.radius, b.support.len()), (0.0, 1));
        // Two distinct points, many duplicates.
        let mut p = vec![Point3::new(0.0, 0.0, 0.0); 5];
        p.extend(vec![Point3::new(2.0, 0.0, 0.0); 5]);
        let b = check3(&p);
        assert_eq!(
            (b.center, b.radius, b.support.len()),
            (Point3::new(1.0, 0.0, 0.0), 1.0, 2)
        );
    }

    #[test]
    fn collinear_points() {
        let p: Vec<Point2> = (0..20)
            .map(|i| Point2::new(i as f64 * 0.3, 1.0 + i as f64 * 0.7))
            .collect();
        let d = check2(&p);
        assert_eq!(d.support, vec![0, 19]);
        let p: Vec<Point3> = (0..20)
            .map(|i| Point3::new(i as f64 * 0.3, -(i as f64), 2.0 * i as f64))
            .collect();
        let b = check3(&p);
        assert_eq!(b.support, vec![0, 19]);
    }

    #[test]
    fn cocircular_and_cospherical() {
        // 12 points of a circle with exact integer coordinates (Pythagorean: radius 5).
        let c: Vec<(f64, f64)> = vec![
            (5., 0.),
            (4., 3.),
            (3., 4.),
            (0., 5.),
            (-3., 4.),
            (-4., 3.),
            (-5., 0.),
            (-4., -3.),
            (-3., -4.),
            (0., -5.),
            (3., -4.),
            (4., -3.),
        ];
        let p: Vec<Point2> = c
            .iter()
            .map(|&(x, y)| Point2::new(x + 10.0, y - 7.0))
            .collect();
        let d = check2(&p);
        assert_eq!((d.center, d.radius), (Point2::new(10.0, -7.0), 5.0));
        // Points on a sphere of radius 3 with integer coordinates (1,2,2 permutations/signs).
        let mut s = Vec::new();
        for &(x, y, z) in &[
            (1., 2., 2.),
            (2., 1., 2.),
            (2., 2., 1.),
            (3., 0., 0.),
            (0., 3., 0.),
            (0., 0., 3.),
        ] {
            for sx in [-1.0, 1.0] {
                for sy in [-1.0, 1.0] {
                    for sz in [-1.0, 1.0] {
                        s.push(Point3::new(sx * x, sy * y, sz * z));
                    }
                }
            }
        }
        let b = check3(&s);
        assert!((b.radius - 3.0).abs() < 1e-12 && b.center.coords.norm() < 1e-12);
        // A great circle only (coplanar, cocircular): support of 2 or 3.
        let g: Vec<Point3> = c.iter().map(|&(x, y)| Point3::new(x, y, 1.0)).collect();
        let b = check3(&g);
        assert!((b.radius - 5.0).abs() < 1e-12 && b.support.len() <= 3);
        // Square: four cocircular points.
        let sq = [
            Point2::new(0., 0.),
            Point2::new(1., 0.),
            Point2::new(1., 1.),
            Point2::new(0., 1.),
        ];
        let d = check2(&sq);
        assert!((d.radius - 0.5f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn triangle_cases() {
        // Acute triangle: three support points; obtuse: two.
        let d = check2(&[
            Point2::new(0., 0.),
            Point2::new(4., 0.),
            Point2::new(2., 3.),
        ]);
        assert_eq!(d.support.len(), 3);
        let d = check2(&[
            Point2::new(0., 0.),
            Point2::new(4., 0.),
            Point2::new(2., 1.),
        ]);
        assert_eq!(d.support, vec![0, 1]);
        // Regular tetrahedron: four support points, centre at the centroid.
        let t = [
            Point3::new(1., 1., 1.),
            Point3::new(1., -1., -1.),
            Point3::new(-1., 1., -1.),
            Point3::new(-1., -1., 1.),
        ];
        let b = check3(&t);
        assert_eq!(b.support.len(), 4);
        assert!((b.radius - 3f64.sqrt()).abs() < 1e-14);
        // Equilateral triangle in space: three support points.
        let e = [
            Point3::new(1., 0., 0.),
            Point3::new(0., 1., 0.),
            Point3::new(0., 0., 1.),
        ];
        let b = check3(&e);
        assert_eq!(b.support.len(), 3);
        assert!((b.center - Point3::new(1. / 3., 1. / 3., 1. / 3.)).norm() < 1e-15);
    }

    #[test]
    fn nearly_degenerate_decisions_are_exact() {
        // p on the diametral circle of (0,0),(1,0) up to one ulp: exact Thales test.
        let a = [0.0, 0.0];
        let b = [1.0, 0.0];
        let y = (0.25f64).sqrt(); // point (0.5, 0.5) is exactly on the circle
        assert!(!diametral_outside(&a, &b, &[0.5, y]));
        assert!(diametral_outside(
            &a,
            &b,
            &[0.5, f64::from_bits(y.to_bits() + 1)]
        ));
        assert!(!diametral_outside(
            &a,
            &b,
            &[0.5, f64::from_bits(y.to_bits() - 1)]
        ));
        // Circle-ball test on exactly cocircular points in a tilted plane: on ⇒ inside.
        let (a, b, c) = ([5., 0., 1.], [0., 5., 1.], [-5., 0., 1.]);
        assert!(!circle_ball_outside(&a, &b, &c, &[3., 4., 1.]));
        assert!(!circle_ball_outside(&a, &b, &c, &[0., 0., 6.])); // north pole of the ball
        assert!(circle_ball_outside(
            &a,
            &b,
            &c,
            &[0., 0., 6.000000000000001]
        ));
        assert!(!circle_ball_outside(
            &a,
            &b,
            &c,
            &[0., 0., 5.999999999999999]
        ));
        // Large offsets: the float filter cannot decide, the expansions do.
        let o = 1e8;
        let (a, b, c) = ([o + 5., o, 1.], [o, o + 5., 1.], [o - 5., o, 1.]);
        assert!(!circle_ball_outside(&a, &b, &c, &[o + 3., o + 4., 1.]));
        assert!(!circle_ball_outside(&a, &b, &c, &[o, o, 6.]));
        assert!(circle_ball_outside(&a, &b, &c, &[o, o - 5.0000001, 1.]));
    }

    #[test]
    fn expansion_arithmetic() {
        let x = Expansion::diff(1e16, 1.0);
        assert_eq!(x.0.len(), 2); // 1e16 − 1 is not a double
        assert_eq!(x.sub(&Expansion::diff(1e16, 0.0)).grow(1.0).sign(), 0);
        let t53 = 2f64.powi(53);
        let y = Expansion::diff(t53, -1.0); // 2^53 + 1, not a double
        let sq = y.mul(&y); // 2^106 + 2^54 + 1
        let back = sq.sub(&Expansion::diff(2f64.powi(106), -2f64.powi(54)));
        assert_eq!(back.sign(), 1);
        assert_eq!(back.grow(-1.0).sign(), 0);
        assert_eq!(
            sq.grow(-1.0)
                .sub(&Expansion::diff(2f64.powi(106), -2f64.powi(54)))
                .sign(),
            0
        );
        assert_eq!(Expansion::diff(0.1, 0.1).sign(), 0);
        assert_eq!(Expansion::diff(0.1, 0.3).sign(), -1);
    }

    #[test]
    fn larger_random_sets() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let p: Vec<Point3> = (0..20000)
            .map(|_| {
                Point3::new(
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                )
            })
            .collect();
        let b = smallest_enclosing_ball(&p).unwrap();
        assert!(p
            .iter()
            .all(|q| (q - b.center).norm() <= b.radius * (1.0 + 1e-12)));
        assert!(b.radius < 3f64.sqrt() && b.radius > 1.5);
        let q: Vec<Point2> = (0..20000)
            .map(|_| Point2::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)))
            .collect();
        let d = smallest_enclosing_disc(&q).unwrap();
        assert!(q
            .iter()
            .all(|x| (x - d.center).norm() <= d.radius * (1.0 + 1e-12)));
    }

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![(-4i32..=4).prop_map(|i| i as f64), -10.0..10.0f64,]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn disc_matches_brute_force(p in prop::collection::vec((coord(), coord()), 1..12)) {
            let p: Vec<Point2> = p.into_iter().map(|(x, y)| Point2::new(x, y)).collect();
            check2(&p);
        }

        #[test]
        fn ball_matches_brute_force(p in prop::collection::vec((coord(), coord(), coord()), 1..10)) {
            let p: Vec<Point3> = p.into_iter().map(|(x, y, z)| Point3::new(x, y, z)).collect();
            check3(&p);
        }

        #[test]
        fn coplanar_ball_matches_disc(p in prop::collection::vec((coord(), coord()), 1..12), z in coord()) {
            let p2: Vec<Point2> = p.iter().map(|&(x, y)| Point2::new(x, y)).collect();
            let p3: Vec<Point3> = p.iter().map(|&(x, y)| Point3::new(x, y, z)).collect();
            let d = check2(&p2);
            let b = check3(&p3);
            prop_assert!((d.radius - b.radius).abs() <= 1e-9 * d.radius.max(1e-300));
        }

        /// Exact decisions are invariant under an exact translation: the same support comes
        /// out (coordinates are multiples of 1/16, the shift 2^30 keeps them exact).
        #[test]
        fn exact_translation_keeps_support(
            p in prop::collection::vec((-64i32..64, -64i32..64, -64i32..64), 1..25),
            t in (-4i32..4, -4i32..4, -4i32..4),
        ) {
            let sh = 2f64.powi(30);
            let p3: Vec<Point3> = p.iter().map(|&(x, y, z)| Point3::new(x as f64 / 16.0, y as f64 / 16.0, z as f64 / 16.0)).collect();
            let q3: Vec<Point3> = p3.iter().map(|q| Point3::new(q.x + t.0 as f64 * sh, q.y + t.1 as f64 * sh, q.z + t.2 as f64 * sh)).collect();
            let (a, b) = (smallest_enclosing_ball(&p3).unwrap(), smallest_enclosing_ball(&q3).unwrap());
            prop_assert_eq!(&a.support, &b.support);
            prop_assert!((a.radius - b.radius).abs() <= 1e-6 * a.radius.max(1e-3));
            let p2: Vec<Point2> = p3.iter().map(|q| Point2::new(q.x, q.y)).collect();
            let q2: Vec<Point2> = q3.iter().map(|q| Point2::new(q.x, q.y)).collect();
            let (a, b) = (smallest_enclosing_disc(&p2).unwrap(), smallest_enclosing_disc(&q2).unwrap());
            prop_assert_eq!(&a.support, &b.support);
        }

        #[test]
        fn order_does_not_matter(p in prop::collection::vec((coord(), coord(), coord()), 1..30), seed in any::<u64>()) {
            let p: Vec<Point3> = p.into_iter().map(|(x, y, z)| Point3::new(x, y, z)).collect();
            let mut q = p.clone();
            q.shuffle(&mut rand_chacha::ChaCha8Rng::seed_from_u64(seed));
            let (a, b) = (smallest_enclosing_ball(&p).unwrap(), smallest_enclosing_ball(&q).unwrap());
            prop_assert!((a.radius - b.radius).abs() <= 1e-9 * a.radius.max(1e-300));
        }
    }
}

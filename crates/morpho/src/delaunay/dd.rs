//! d-dimensional Delaunay triangulation (Dorgerloh et al. §2, algorithm *SimpleDelaunay*:
//! Bowyer–Watson insertion in d dimensions; Veltkamp 1992 §2.2.9, Definition 2.11).
//!
//! # Algorithm
//! Bowyer–Watson as in Dorgerloh et al. §2 steps 3(a)–(e): for each new point the region
//! `R(p)` of simplices whose circumscribing ball contains `p` is removed and `p` is joined to the
//! facets `F(p)` of its boundary. Differences from the paper, all for exactness and generality:
//! - *circumball(p, s)* is the exact sign of the (d+2)×(d+2) lifted determinant instead of a
//!   comparison of distances to a constructed centre (the paper's ConstructCircumball is only
//!   used for output, see [`DelaunayD::circumcenter`]);
//! - the paper's first simplex `(p_1 … p_{d+1})` assumes the points are affinely independent and
//!   that later points fall inside; here the first simplex is the first d+1 affinely independent
//!   points and the hull is closed by *ghost* simplices with an infinite vertex (a ghost is in
//!   conflict with `p` when `p` lies strictly beyond its hull facet, or on the facet's hyperplane
//!   and in conflict with the finite neighbour), so points outside the current hull are handled;
//! - `R(p)` is found by a visibility walk and a breadth-first search from the located simplex
//!   instead of a scan of all simplices.
//!
//! # Predicates
//! `orient` = det of rows `[q_i, 1]` ((d+1)×(d+1); equal to Shewchuk's `orient2d`/`orient3d`
//! for d = 2, 3) and `insphere` = det of rows `[q_i, |q_i|², 1]` ((d+2)×(d+2); > 0 when the last
//! point is inside the sphere of a positive simplex). A floating-point filter evaluates the
//! determinant by cofactor expansion over column subsets together with the permanent of the
//! absolute values, which bounds the rounding error; when the sign is not certain, the
//! determinant is recomputed exactly with big integers (every `f64` is an integer times a power
//! of two, so after a common power-of-two scaling all entries are integers) by Bareiss'
//! fraction-free elimination (both in [`crate::geom::exact`]).
//!
//! # Degeneracies
//! Duplicates are merged; vertices are numbered in lexicographic order (the canonical index).
//! Cospherical ties are broken by the same symbolic perturbation as [`super::d3`]: vertex `v` is
//! lifted by `ε^(N−v)`, and the sign of the perturbed in-sphere determinant is the sign of the
//! first non-zero cofactor (an exact `orient`) in decreasing canonical index. The result is
//! therefore independent of the insertion order and identical to [`super::d3`] for d = 3.
//! Input in a lower-dimensional affine subspace gives no simplices and a note.
//!
//! # Complexity
//! Randomized incremental: about `O(n^⌈d/2⌉)` expected for points in general position, plus the
//! exact-fallback cost; meant for up to a few thousand points (exactness first, speed second).

use super::DelaunayError;
use crate::geom::exact::{affinely_independent, insphere_sign, orient_sign};
use crate::util::{Rng, NONE};

type Result<T, E = DelaunayError> = std::result::Result<T, E>;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use std::collections::HashMap;

const INF: u32 = u32::MAX;
const FREE: u32 = u32::MAX - 1;
/// Largest supported dimension (that of the exact determinants).
pub const MAX_DIM: usize = crate::geom::exact::MAX_DIM;

/// A d-dimensional Delaunay triangulation.
#[derive(Debug, Clone)]
pub struct DelaunayD {
    /// Dimension d.
    pub dim: usize,
    /// Distinct points, flat (`dim` coordinates each), sorted lexicographically.
    pub points: Vec<f64>,
    /// For every input point, its vertex.
    pub vertex_of_input: Vec<u32>,
    /// For every vertex, its first input point.
    pub input_of_vertex: Vec<u32>,
    /// Simplices (d+1 vertices each), positively oriented (`orient > 0`).
    pub simplices: Vec<Vec<u32>>,
    /// `neighbors[s][i]`: the simplex across the facet opposite corner `i`, or [`NONE`].
    pub neighbors: Vec<Vec<u32>>,
    /// Convex hull facets (d vertices each), ordered so that `orient(facet…, x) > 0` for points
    /// `x` outside the hull.
    pub hull: Vec<Vec<u32>>,
    /// Number of merged duplicate input points.
    pub duplicates: usize,
    /// Why there are no simplices, if so.
    pub degenerate: Option<String>,
}

/// Symbolically perturbed in-sphere (see the module doc): `q` has d+2 points with distinct
/// canonical `ids`, the first d+1 positively oriented. True for "inside".
pub fn perturbed_insphere(q: &[&[f64]], ids: &[u32]) -> bool {
    let s = insphere_sign(q);
    if s != 0 {
        return s > 0;
    }
    let n = q.len();
    let mut idx: Vec<usize> = (0..n).collect();
    idx.sort_unstable_by(|a, b| ids[*b].cmp(&ids[*a]));
    for k in idx {
        let s = if k == n - 1 {
            -orient_sign(&q[..n - 1])
        } else {
            let mut w: Vec<&[f64]> = q[..n - 1].to_vec();
            w[k] = q[n - 1];
            orient_sign(&w)
        };
        if s != 0 {
            return s > 0;
        }
    }
    false
}

struct Bnd {
    v: Vec<u32>,
    i: usize,
    out: u32,
}

struct Builder<'a> {
    d: usize,
    pts: &'a [f64],
    sv: Vec<u32>,
    sn: Vec<u32>,
    stamp: Vec<u32>,
    free: Vec<u32>,
    last: u32,
    rng: Rng,
    overflow: bool,
}

impl<'a> Builder<'a> {
    fn p(&self, v: u32) -> &'a [f64] {
        let d = self.d;
        &self.pts[v as usize * d..v as usize * d + d]
    }
    fn verts(&self, s: u32) -> &[u32] {
        let d1 = self.d + 1;
        &self.sv[s as usize * d1..s as usize * d1 + d1]
    }
    fn nb(&self, s: u32, i: usize) -> u32 {
        self.sn[s as usize * (self.d + 1) + i]
    }
    fn set_nb(&mut self, s: u32, i: usize, code: u32) {
        let d1 = self.d + 1;
        self.sn[s as usize * d1 + i] = code;
    }
    fn rand(&mut self) -> u64 {
        self.rng.next_u64()
    }
    fn alloc(&mut self) -> u32 {
        let d1 = self.d + 1;
        if let Some(s) = self.free.pop() {
            self.stamp[s as usize] = 0;
            s
        } else {
            if self.stamp.len() >= 1 << 28 {
                // neighbour codes `simplex << 3 | face` would overflow (checked by the caller)
                self.overflow = true;
                return 0;
            }
            self.sv.extend(std::iter::repeat(FREE).take(d1));
            self.sn.extend(std::iter::repeat(0).take(d1));
            self.stamp.push(0);
            (self.stamp.len() - 1) as u32
        }
    }
    fn finite_conflict(&self, s: u32, p: u32) -> bool {
        let v = self.verts(s);
        let mut q: Vec<&[f64]> = v.iter().map(|&x| self.p(x)).collect();
        q.push(self.p(p));
        let mut ids = v.to_vec();
        ids.push(p);
        perturbed_insphere(&q, &ids)
    }
    fn in_conflict(&self, s: u32, p: u32) -> bool {
        let d = self.d;
        let v = self.verts(s);
        if v[d] == INF {
            let mut q: Vec<&[f64]> = v[..d].iter().map(|&x| self.p(x)).collect();
            q.push(self.p(p));
            let o = orient_sign(&q);
            if o != 0 {
                return o > 0;
            }
            return self.finite_conflict(self.nb(s, d) >> 3, p);
        }
        self.finite_conflict(s, p)
    }
    fn locate(&mut self, p: u32) -> u32 {
        let d = self.d;
        let d1 = d + 1;
        let mut s = self.last;
        if self.verts(s)[d] == INF {
            s = self.nb(s, d) >> 3;
        }
        let mut prev = NONE;
        let mut steps = 0usize;
        'walk: loop {
            let v = self.verts(s).to_vec();
            if v[d] == INF {
                return s;
            }
            steps += 1;
            if steps > 4 * self.stamp.len() + 100 {
                break;
            }
            let r = self.rand() as usize;
            for k in 0..d1 {
                let i = (r + k) % d1;
                let n = self.nb(s, i) >> 3;
                if n == prev {
                    continue;
                }
                let mut q: Vec<&[f64]> = v.iter().map(|&x| self.p(x)).collect();
                q[i] = self.p(p);
                if orient_sign(&q) < 0 {
                    prev = s;
                    s = n;
                    continue 'walk;
                }
            }
            return s;
        }
        (0..self.stamp.len() as u32)
            .find(|&s| self.verts(s)[0] != FREE && self.in_conflict(s, p))
            .unwrap_or(self.last)
    }
    fn insert(&mut self, p: u32, k: u32) {
        let d1 = self.d + 1;
        let t0 = self.locate(p);
        let cs = 2 * k + 2;
        let ns = cs + 1;
        let mut stack = vec![t0];
        let mut conflict = vec![t0];
        let mut bnd: Vec<Bnd> = Vec::new();
        self.stamp[t0 as usize] = cs;
        while let Some(t) = stack.pop() {
            for i in 0..d1 {
                let code = self.nb(t, i);
                let u = code >> 3;
                let su = self.stamp[u as usize];
                if su == cs {
                    continue;
                }
                if su != ns {
                    if self.in_conflict(u, p) {
                        self.stamp[u as usize] = cs;
                        stack.push(u);
                        conflict.push(u);
                        continue;
                    }
                    self.stamp[u as usize] = ns;
                }
                let mut v = self.verts(t).to_vec();
                v[i] = p;
                bnd.push(Bnd { v, i, out: code });
            }
        }
        for &t in &conflict {
            self.sv[t as usize * d1] = FREE;
            self.free.push(t);
        }
        let mut ridges: HashMap<Vec<u32>, u32> = HashMap::new();
        let mut last = NONE;
        for b in bnd {
            let n = self.alloc();
            self.sv[n as usize * d1..n as usize * d1 + d1].copy_from_slice(&b.v);
            self.set_nb(n, b.i, b.out);
            self.set_nb(b.out >> 3, (b.out & 7) as usize, (n << 3) | b.i as u32);
            if b.v[d1 - 1] != INF || last == NONE {
                last = n;
            }
            for j in 0..d1 {
                if j == b.i {
                    continue;
                }
                let mut key: Vec<u32> = (0..d1)
                    .filter(|&s| s != j && s != b.i)
                    .map(|s| b.v[s])
                    .collect();
                key.sort_unstable();
                if let Some(m) = ridges.remove(&key) {
                    self.set_nb(n, j, m);
                    self.set_nb(m >> 3, (m & 7) as usize, (n << 3) | j as u32);
                } else {
                    ridges.insert(key, (n << 3) | j as u32);
                }
            }
        }
        self.last = last;
    }
}

/// Computes the Delaunay triangulation of the points `coords` (flat, `dim` coordinates each;
/// facade name [`triangulate_nd`](crate::delaunay::triangulate_nd)).
///
/// Bowyer–Watson insertion (Dorgerloh et al. §2, *SimpleDelaunay*) with exact predicates (a
/// floating-point filter, then big-integer determinants) and symbolic perturbation; identical
/// to [`triangulate_3d`](crate::delaunay::triangulate_3d) for d = 3. Randomized incremental,
/// about O(n^⌈d/2⌉) expected for points in general position: meant for up to a few thousand
/// points.
///
/// Errors: `dim` outside 2 ..= [`MAX_DIM`] ([`DelaunayError::UnsupportedDimension`]),
/// `coords.len()` not a multiple of `dim` ([`DelaunayError::DimensionMismatch`]), no points,
/// non-finite coordinates. Affinely degenerate input (all points in a hyperplane) gives `Ok`
/// with no simplices and [`DelaunayD::degenerate`] set.
///
/// ```rust
/// use morpho::delaunay::triangulate_nd;
/// // the unit 4-cube's 16 corners: its volume is 1, and every simplex is positive
/// let c: Vec<f64> = (0..16u32).flat_map(|i| (0..4).map(move |k| (i >> k & 1) as f64)).collect();
/// let d = triangulate_nd(&c, 4).unwrap();
/// assert!((d.hull_volume() - 1.0).abs() < 1e-12);
/// assert!((0..d.simplices.len()).all(|s| d.volume(s) > 0.0));
/// let total: f64 = (0..d.simplices.len()).map(|s| d.volume(s)).sum();
/// assert!((total - 1.0).abs() < 1e-12);
/// assert!(triangulate_nd(&[0.0, 1.0, 2.0], 2).is_err()); // 3 numbers are not 2D points
/// ```
pub fn triangulate_d(coords: &[f64], dim: usize) -> Result<DelaunayD> {
    if !(2..=MAX_DIM).contains(&dim) {
        return Err(DelaunayError::UnsupportedDimension { dim, max: MAX_DIM });
    }
    if coords.len() % dim != 0 {
        return Err(DelaunayError::DimensionMismatch {
            coords: coords.len(),
            dim,
        });
    }
    let n_in = coords.len() / dim;
    if n_in == 0 {
        return Err(DelaunayError::NoPoints { dim });
    }
    if n_in >= (u32::MAX as usize) / 16 {
        return Err(DelaunayError::TooManyPoints { found: n_in, dim });
    }
    for (i, x) in coords.iter().enumerate() {
        if !x.is_finite() {
            return Err(DelaunayError::NonFinite {
                index: i / dim,
                coords: vec![],
            });
        }
    }
    // sort + dedup
    let norm: Vec<f64> = coords.iter().map(|x| x + 0.0).collect();
    let row = |i: u32| &norm[i as usize * dim..i as usize * dim + dim];
    let mut idx: Vec<u32> = (0..n_in as u32).collect();
    idx.sort_by(|&a, &b| {
        row(a)
            .partial_cmp(row(b))
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    let mut points: Vec<f64> = Vec::new();
    let mut vertex_of_input = vec![0u32; n_in];
    let mut input_of_vertex: Vec<u32> = Vec::new();
    for &i in &idx {
        let r = row(i);
        let nv = input_of_vertex.len();
        if nv == 0 || &points[(nv - 1) * dim..nv * dim] != r {
            points.extend_from_slice(r);
            input_of_vertex.push(i);
        }
        vertex_of_input[i as usize] = (input_of_vertex.len() - 1) as u32;
    }
    let nv = input_of_vertex.len();
    let mut out = DelaunayD {
        dim,
        points,
        vertex_of_input,
        input_of_vertex,
        simplices: Vec::new(),
        neighbors: Vec::new(),
        hull: Vec::new(),
        duplicates: n_in - nv,
        degenerate: None,
    };
    let mut order: Vec<u32> = (0..nv as u32).collect();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x0dd_5eed);
    order.shuffle(&mut rng);
    let pts = &out.points;
    let p = |v: u32| &pts[v as usize * dim..v as usize * dim + dim];
    // first simplex: greedy affinely independent points
    let mut first: Vec<u32> = Vec::new();
    for &v in &order {
        let mut q: Vec<&[f64]> = first.iter().map(|&x| p(x)).collect();
        q.push(p(v));
        if affinely_independent(&q) {
            first.push(v);
            if first.len() == dim + 1 {
                break;
            }
        }
    }
    if first.len() < dim + 1 {
        out.degenerate = Some(format!(
            "all points lie in a {}-dimensional affine subspace",
            first.len() - 1
        ));
        return Ok(out);
    }
    {
        let q: Vec<&[f64]> = first.iter().map(|&x| p(x)).collect();
        if orient_sign(&q) < 0 {
            first.swap(0, 1);
        }
    }
    let d1 = dim + 1;
    let mut bld = Builder {
        d: dim,
        pts,
        sv: first.clone(),
        sn: vec![0; d1],
        stamp: vec![0],
        free: Vec::new(),
        last: 0,
        rng: Rng::new(0x2545_F491_4F6C_DD1D),
        overflow: false,
    };
    for i in 0..d1 {
        let mut f: Vec<u32> = (0..d1).filter(|&k| k != i).map(|k| first[k]).collect();
        if (dim - i) % 2 == 0 {
            f.swap(0, 1);
        }
        f.push(INF);
        bld.sv.extend(f);
        bld.sn.extend(std::iter::repeat(0).take(d1));
        bld.stamp.push(0);
    }
    // brute-force linking of the first d+2 simplices
    let ns = d1 + 1;
    for s in 0..ns {
        for i in 0..d1 {
            let mut f: Vec<u32> = (0..d1)
                .filter(|&k| k != i)
                .map(|k| bld.sv[s * d1 + k])
                .collect();
            f.sort_unstable();
            for t in 0..ns {
                if t == s {
                    continue;
                }
                for j in 0..d1 {
                    let mut g: Vec<u32> = (0..d1)
                        .filter(|&k| k != j)
                        .map(|k| bld.sv[t * d1 + k])
                        .collect();
                    g.sort_unstable();
                    if f == g {
                        bld.sn[s * d1 + i] = ((t as u32) << 3) | j as u32;
                    }
                }
            }
        }
    }
    let mut k = 0;
    for &v in &order {
        if first.contains(&v) {
            continue;
        }
        bld.insert(v, k);
        k += 1;
        if bld.overflow {
            return Err(DelaunayError::TooManySimplices {
                dim,
                limit: 1 << 28,
            });
        }
    }
    let nslots = bld.stamp.len();
    let mut map = vec![NONE; nslots];
    let mut m = 0;
    for s in 0..nslots {
        let v = bld.verts(s as u32);
        if v[0] != FREE && v[dim] != INF {
            map[s] = m;
            m += 1;
        }
    }
    let mut simplices = Vec::new();
    let mut neighbors = Vec::new();
    let mut hull = Vec::new();
    for s in 0..nslots {
        let v = bld.verts(s as u32);
        if v[0] == FREE {
            continue;
        }
        if v[dim] == INF {
            hull.push(v[..dim].to_vec());
            continue;
        }
        simplices.push(v.to_vec());
        neighbors.push(
            (0..d1)
                .map(|i| map[(bld.nb(s as u32, i) >> 3) as usize])
                .collect(),
        );
    }
    out.simplices = simplices;
    out.neighbors = neighbors;
    out.hull = hull;
    Ok(out)
}

impl DelaunayD {
    /// Coordinates of vertex `v`.
    pub fn point(&self, v: u32) -> &[f64] {
        &self.points[v as usize * self.dim..(v as usize + 1) * self.dim]
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.input_of_vertex.len()
    }

    /// Signed volume of simplex `s` (`orient / d!`, in `f64`).
    pub fn volume(&self, s: usize) -> f64 {
        let q: Vec<&[f64]> = self.simplices[s].iter().map(|&v| self.point(v)).collect();
        simplex_volume(&q)
    }

    /// Volume of the convex hull from its facets (divergence theorem, `f64`).
    pub fn hull_volume(&self) -> f64 {
        let Some(f0) = self.hull.first() else {
            return 0.0;
        };
        let o = self.point(f0[0]).to_vec();
        -self
            .hull
            .iter()
            .map(|f| {
                let mut q: Vec<&[f64]> = f.iter().map(|&v| self.point(v)).collect();
                q.push(&o);
                simplex_volume(&q)
            })
            .sum::<f64>()
    }

    /// Circumcentre of simplex `s` (solves the d×d linear system `2(q_i − q_0)·c = |q_i|² − |q_0|²`
    /// in `f64` with partial pivoting; a construction, not a decision).
    pub fn circumcenter(&self, s: usize) -> Vec<f64> {
        let d = self.dim;
        let q: Vec<&[f64]> = self.simplices[s].iter().map(|&v| self.point(v)).collect();
        let mut a = vec![0.0; d * (d + 1)];
        for i in 0..d {
            let mut rhs = 0.0;
            for k in 0..d {
                let e = q[i + 1][k] - q[0][k];
                a[i * (d + 1) + k] = 2.0 * e;
                rhs += e * e;
            }
            a[i * (d + 1) + d] = rhs;
        }
        // Gaussian elimination with partial pivoting; solution is c − q_0.
        for c in 0..d {
            let piv = (c..d)
                .max_by(|&x, &y| {
                    a[x * (d + 1) + c]
                        .abs()
                        .total_cmp(&a[y * (d + 1) + c].abs())
                })
                .unwrap_or(c);
            for k in 0..=d {
                a.swap(c * (d + 1) + k, piv * (d + 1) + k);
            }
            for r in 0..d {
                if r != c {
                    let f = a[r * (d + 1) + c] / a[c * (d + 1) + c];
                    for k in c..=d {
                        a[r * (d + 1) + k] -= f * a[c * (d + 1) + k];
                    }
                }
            }
        }
        (0..d)
            .map(|k| q[0][k] + a[k * (d + 1) + d] / a[k * (d + 1) + k])
            .collect()
    }
}

/// `orient(q…)/d!` in `f64` (Gaussian elimination); for volumes only, not for decisions.
pub fn simplex_volume(q: &[&[f64]]) -> f64 {
    let d = q.len() - 1;
    let mut a: Vec<f64> = (1..=d)
        .flat_map(|i| (0..d).map(move |k| (i, k)))
        .map(|(i, k)| q[i][k] - q[0][k])
        .collect();
    // det of rows (q_i − q_0) equals orient(q_0 … q_d) up to the sign (−1)^d
    let mut det = 1.0;
    for c in 0..d {
        let Some(piv) = (c..d).max_by(|&x, &y| a[x * d + c].abs().total_cmp(&a[y * d + c].abs()))
        else {
            return 0.0;
        };
        if a[piv * d + c] == 0.0 {
            return 0.0;
        }
        if piv != c {
            for k in 0..d {
                a.swap(c * d + k, piv * d + k);
            }
            det = -det;
        }
        det *= a[c * d + c];
        for r in c + 1..d {
            let f = a[r * d + c] / a[c * d + c];
            for k in c..d {
                a[r * d + k] -= f * a[c * d + k];
            }
        }
    }
    let mut fact = 1.0;
    for i in 2..=d {
        fact *= i as f64;
    }
    let sign = if d % 2 == 0 { 1.0 } else { -1.0 };
    sign * det / fact
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_2d() {
        let d = triangulate_d(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.5, 0.5], 2).unwrap();
        assert_eq!(d.simplices.len(), 4);
        assert_eq!(d.hull.len(), 4);
        let v: f64 = (0..4).map(|s| d.volume(s)).sum();
        assert!((v - 1.0).abs() < 1e-12);
        assert!((d.hull_volume() - 1.0).abs() < 1e-12);
    }
}

//! Hamann's side-vertex surface (Hamann 1991, ch. 6: Def. 6.1, Thm 6.1, Def. 6.2, Thm 6.2,
//! §6.3; NOTES E.1, E.3): a tangent-plane-continuous surface through the vertices and vertex
//! normals of a closed, consistently oriented 2-manifold triangle mesh, built from the
//! degree-elevated and generalized conics of `conic.rs`.
//!
//! Per triangle `(v1, v2, v3)` with unit normals `n1, n2, n3`, at barycentric `u`:
//! 1. the **boundary curve** `c_i` on edge `e_i` (opposite `v_i`) is the conic from `v_{i+1}`
//!    to `v_{i+2}`, with the boundary normal `n^S_i(t)` along it ([`ConicEdge`]); it is built
//!    once per mesh edge, from its lower to its higher vertex index, so both triangles of an
//!    edge evaluate the very same curve and normal field;
//! 2. the **building block** `s_i(u)` is the **radial** conic from `v_i` (normal `n_i`) to
//!    `c_i(t)` (normal `n^S_i(t)`), `t = u_{i+2}/(1−u_i)`, evaluated at `t̄ = 1 − u_i` (§6.3);
//!    it interpolates all three boundary curves and the normals along `e_i` (Def. 6.2 (iv), (v));
//! 3. the **patch** is `s(u) = Σ wᵢ(u) sᵢ(u)` (6.1) with the squared side-vertex weights
//!    [`side_vertex_weights`] (NOTES E.1: the printed (6.2) lacks the squares and violates
//!    Thm 6.1 (iii)).
//!
//! **G¹.** On `e_i` every block equals `c_i`, `w_i = 1`, and the other weights vanish, so the
//! tangent plane of `s` there is that of `s_i`: spanned by `ċ_i` and the radial curve's end
//! tangent, both perpendicular to `n^S_i` (the proof of Thm 6.2 uses only Thm 6.1 (i), (ii)
//! and Def. 6.2). Neighbours share `c_i` and `n^S_i`, so the scheme is G¹ exactly (up to
//! rounding) along every edge, away from the vertices, where the weights are 0/0 but every
//! block passes through the vertex. The independent check is
//! [`super::side_vertex_continuity`].
//!
//! **Where the text's scheme degenerates, and the handle floor.** A conic's handle at one end
//! is `∝ sin` of the tangent angle at the *other* end ((6.9)). (a) When a radial conic's end
//! tangent at the boundary lies along its chord (β → 0) the handle at `v_i` collapses, and
//! where β changes side (convex ↔ generalized conic, Def. 6.3) the unsigned angle makes the
//! block only C⁰ along a curve *inside* the triangle, where the patch can fold. (b) Where a
//! radial conic's handle at the boundary nearly collapses (α → 0, `|b3 − b2| ≈ 1e-4 |b3 − b0|`
//! on spot) the tangent plane is continuous at the edge but turns within 1e-4 of it. With the
//! text's conics (`handle_floor: 0`) spot's edges measure normal jumps up to 1.2e-5 rad and
//! fandisk's up to π (handles of 1e-10 in its flat parts). **Deviation:** the default
//! [`SideVertexOptions::handle_floor`] 0.1 keeps every handle's shape ratio ≥ 0.1 and softens
//! an angle below a quarter of the other one, both C¹ (`conic.rs`), leaving circular arcs and
//! sphere data exactly as in the text. Measured with exact derivatives (below): normal jumps
//! ≤ 3.5e-12 rad on fandisk, spot, bunny_npm and rocker-arm (no edge above 1e-9; the
//! finite-difference check of before reported 1.6e-8 … 3.6e-7, its own rounding), no edge
//! fold. The horse has 16 edges where the two patches' tangent planes agree but their normals
//! are opposite (jump π, a fold along the edge): reported in `non_g1_edges`. What remains of
//! (a) is not smooth yet: a few tessellation vertices (spot, density 8: 96 of 187 394;
//! fandisk 16) have a surface normal pointing away from their triangles, almost all where a
//! radial conic's angle is near 0 (reported by [`super::reversed_normals`]; dark specks in a
//! picture). On
//! sphere-like data (every conic convex, angles away from 0) none of this occurs: jumps
//! ≤ 1e-9 rad.
//!
//! **Normals.** [`SideVertexSurface::normal`] returns the input normal at a vertex, the
//! boundary normal `n^S` on an edge (Thm 6.2) and inside the triangle the unit cross product
//! of the two **exact first derivatives** ([`SideVertexSurface::derivatives`]): the whole
//! construction (weights, boundary conic and its normal field at `t(u)`, the radial conic
//! built from them, evaluated at `1 − u_i`) is evaluated once over dual numbers with two
//! partials (`dual.rs`, forward mode), whose value parts mirror [`SideVertexSurface::eval`]
//! operation for operation (equal to an ulp). Where the construction branches on a value (the unsigned
//! angle where a tangent crosses its chord, degenerate-data fallbacks) the derivative is that
//! of the branch taken. The five-point difference normal
//! ([`SideVertexSurface::difference_normal`]) is kept as an independent cross-check.
//!
//! **Not spherical** (Rem. 6.3): on sphere data every block lies on the sphere, their convex
//! combination does not. The regular tetrahedron with sphere normals and automatic weights
//! deviates from the unit sphere by at most 0.0342 (at the face centroids; the thesis says
//! "about 0.01", NOTES E.4, not reproduced: see the test `hamann_sphere_test`).
//!
//! Cost: O(edges) to build, O(1) per evaluation (three boundary and three radial conics),
//! one dual evaluation (about 3 plain ones) per interior normal.

use super::conic::{check_tension, Conic, ConicEdge};
use super::dual::{v3, Dual, D3};
use super::{side_vertex_weights, SmoothError};
use crate::geom::{vec, Vector3};
use crate::mesh::TriMesh;
use std::collections::HashMap;

type P3 = [f64; 3];

/// Options of [`side_vertex`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideVertexOptions {
    /// Scales every conic's automatic weight (Thm 6.3): `ω = tension · sin(γ/2)`. 1 is the
    /// thesis's recommendation; smaller values pull the patches towards the flat triangles.
    pub tension: f64,
    /// The handle floor κ of every conic (`conic.rs`, "collapsing handles"; 0 = the text's
    /// conics, at most 0.5). The default 0.1 leaves every conic with shape ratio ≥ 0.2 (all
    /// circular arcs, every sphere-data block) as in the text.
    pub handle_floor: f64,
}

impl Default for SideVertexOptions {
    fn default() -> Self {
        SideVertexOptions {
            tension: 1.0,
            handle_floor: 0.1,
        }
    }
}

/// The side-vertex surface of a mesh: one patch per triangle.
///
/// ```
/// use morpho::mesh::{generate, vertex_normals, NormalWeighting};
/// use morpho::smooth::{side_vertex, SideVertexOptions};
/// let m = generate::icosphere(0);
/// let n = vertex_normals(&m, NormalWeighting::Area);
/// let s = side_vertex(&m, &n, &SideVertexOptions::default()).unwrap();
/// let p = s.eval(0, [1.0 / 3.0; 3]);
/// let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
/// assert!(r > 0.98 && r < 1.0); // close to the sphere, not on it (Rem. 6.3)
/// assert_eq!(s.eval(0, [1.0, 0.0, 0.0]), s.positions[m.triangles[0][0] as usize]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SideVertexSurface {
    /// The mesh's vertices.
    pub positions: Vec<P3>,
    /// Unit vertex normals.
    pub normals: Vec<P3>,
    /// The mesh's triangles (patch k is triangle k).
    pub triangles: Vec<[u32; 3]>,
    /// The tension of every conic.
    pub tension: f64,
    /// The handle floor of every conic.
    pub handle_floor: f64,
    /// One boundary curve per mesh edge, from its lower to its higher vertex index.
    pub edges: Vec<([u32; 2], ConicEdge)>,
    /// Per triangle and side i (opposite corner i): the index into `edges`.
    pub sides: Vec<[u32; 3]>,
}

/// The side-vertex surface through `mesh` and `normals` (one per vertex, any positive length).
///
/// Errors: fewer than 4 vertices, a non-finite coordinate, a missing vertex, a zero-area
/// triangle, an open, non-manifold or inconsistently oriented mesh, a zero or non-finite
/// normal, a tension outside (0, 1e6] — each a [`SmoothError`] naming the input.
pub fn side_vertex(
    mesh: &TriMesh,
    normals: &[Vector3],
    opts: &SideVertexOptions,
) -> Result<SideVertexSurface, SmoothError> {
    check_tension(opts.tension)?;
    super::conic::check_floor(opts.handle_floor)?;
    let (_, unit) = super::split3::check_closed(mesh, normals)?;
    let positions: Vec<P3> = mesh.positions.iter().map(|&p| p.into()).collect();
    let mut index: HashMap<[u32; 2], u32> = HashMap::with_capacity(mesh.triangles.len() * 3 / 2);
    let mut edges = Vec::with_capacity(mesh.triangles.len() * 3 / 2);
    let mut sides = Vec::with_capacity(mesh.triangles.len());
    for t in &mesh.triangles {
        let mut side = [0u32; 3];
        for (i, s) in side.iter_mut().enumerate() {
            let (a, b) = (t[(i + 1) % 3], t[(i + 2) % 3]);
            let key = [a.min(b), a.max(b)];
            *s = *index.entry(key).or_insert_with(|| {
                let [p, q] = key.map(|v| v as usize);
                let c = Conic::build(
                    positions[p],
                    unit[p],
                    positions[q],
                    unit[q],
                    opts.tension,
                    opts.handle_floor,
                );
                edges.push((key, ConicEdge::from_conic(c, unit[p], unit[q])));
                (edges.len() - 1) as u32
            });
        }
        sides.push(side);
    }
    Ok(SideVertexSurface {
        positions,
        normals: unit,
        triangles: mesh.triangles.clone(),
        tension: opts.tension,
        handle_floor: opts.handle_floor,
        edges,
        sides,
    })
}

/// `u` clamped to the triangle: negative coordinates to 0, then divided by the sum.
fn clamp(u: [f64; 3]) -> [f64; 3] {
    let v = u.map(|x| if x > 0.0 { x } else { 0.0 });
    let s = v[0] + v[1] + v[2];
    if s > 0.0 && s.is_finite() {
        v.map(|x| x / s)
    } else {
        [1.0 / 3.0; 3]
    }
}

impl SideVertexSurface {
    /// The boundary curve on side `i` of `tri` (opposite corner i) and whether it runs
    /// against the side's direction `v_{i+1} → v_{i+2}`.
    pub fn side(&self, tri: usize, i: usize) -> (&ConicEdge, bool) {
        let (key, e) = &self.edges[self.sides[tri][i] as usize];
        (e, key[0] != self.triangles[tri][(i + 1) % 3])
    }

    /// The point and boundary normal of side `i` of `tri` at `t` (0 at `v_{i+1}`).
    pub fn boundary(&self, tri: usize, i: usize, t: f64) -> (P3, P3) {
        let (e, rev) = self.side(tri, i);
        let t = if rev { 1.0 - t } else { t };
        (e.conic.eval(t), e.normal(t))
    }

    /// Building block `s_i(u)` of patch `tri` (Def. 6.2): the radial conic from corner i to
    /// side i, at barycentric `u` (clamped to the triangle).
    pub fn block(&self, tri: usize, i: usize, u: [f64; 3]) -> P3 {
        let u = clamp(u);
        let vi = self.triangles[tri][i] as usize;
        let rest = 1.0 - u[i];
        if rest <= 0.0 {
            return self.positions[vi];
        }
        let t = (u[(i + 2) % 3] / rest).clamp(0.0, 1.0);
        let (p, np) = self.boundary(tri, i, t);
        if u[i] == 0.0 {
            return p;
        }
        let (tension, floor) = (self.tension, self.handle_floor);
        Conic::build(self.positions[vi], self.normals[vi], p, np, tension, floor).eval(rest)
    }

    /// The radial conic of block `i` of `tri` through the point `u` (its parameter there is
    /// `1 − u_i`).
    pub fn radial(&self, tri: usize, i: usize, u: [f64; 3]) -> Conic {
        let u = clamp(u);
        let vi = self.triangles[tri][i] as usize;
        let rest = 1.0 - u[i];
        let t = if rest > 0.0 {
            (u[(i + 2) % 3] / rest).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let (p, np) = self.boundary(tri, i, t);
        let (tension, floor) = (self.tension, self.handle_floor);
        Conic::build(self.positions[vi], self.normals[vi], p, np, tension, floor)
    }

    /// The patch `s(u) = Σ wᵢ(u) sᵢ(u)` of triangle `tri` at barycentric `u` (clamped to the
    /// triangle); exactly the vertex at a corner and the boundary curve on a side.
    pub fn eval(&self, tri: usize, u: [f64; 3]) -> P3 {
        let u = clamp(u);
        let w = side_vertex_weights(u);
        let mut p = [0.0; 3];
        for (i, &wi) in w.iter().enumerate() {
            if wi == 1.0 {
                return self.block(tri, i, u);
            }
            if wi != 0.0 {
                p = vec::add_scaled(p, wi, self.block(tri, i, u));
            }
        }
        p
    }

    /// The unit surface normal of patch `tri` at `u` (module doc, "normals"): the input normal
    /// at a corner, the boundary normal `n^S` on a side, and inside the triangle
    /// [`Self::derivative_normal`].
    pub fn normal(&self, tri: usize, u: [f64; 3]) -> P3 {
        let u = clamp(u);
        if let Some(k) = (0..3).find(|&k| u[k] == 1.0) {
            return self.normals[self.triangles[tri][k] as usize];
        }
        if let Some(i) = (0..3).find(|&i| u[i] == 0.0) {
            return self.boundary(tri, i, u[(i + 2) % 3]).1;
        }
        self.derivative_normal(tri, u)
    }

    /// The normal of the patch alone: the unit cross product `∂s/∂a × ∂s/∂b` of its exact
    /// one-sided first derivatives ([`Self::derivatives`]), also on a side of the triangle
    /// (where it is the limit from inside, not the prescribed `n^S`); the zero vector at a
    /// corner or where the derivatives are parallel.
    pub fn derivative_normal(&self, tri: usize, u: [f64; 3]) -> P3 {
        let (_, [da, db]) = self.derivatives(tri, u);
        let n = vec::cross(da, db);
        let l = vec::norm(n);
        if l > 0.0 && l.is_finite() {
            vec::scale(n, 1.0 / l)
        } else {
            [0.0; 3]
        }
    }

    /// The point `s(u)` and its exact first derivatives along the barycentric directions
    /// `a = e₂ − e₁` and `b = e₃ − e₁` (so `∂s/∂a × ∂s/∂b` points like the triangle's normal),
    /// by forward-mode differentiation of the whole construction: weights, radial conics
    /// (whose end point and end normal move with `t = u_{i+2}/(1−u_i)`), boundary curves and
    /// their normal fields. `u` is clamped to the triangle; on a side the derivatives are the
    /// one-sided ones from inside (the blocks whose weight vanishes there to first order are
    /// skipped). At a corner (weights 0/0) the derivatives are zero. The point equals
    /// [`Self::eval`] to an ulp (the value parts mirror it operation for operation).
    pub fn derivatives(&self, tri: usize, u: [f64; 3]) -> (P3, [P3; 2]) {
        let u = clamp(u);
        if u.contains(&1.0) {
            return (self.eval(tri, u), [[0.0; 3]; 2]);
        }
        let ud = [
            Dual {
                v: u[0],
                d: [-1.0, -1.0],
            },
            Dual {
                v: u[1],
                d: [1.0, 0.0],
            },
            Dual {
                v: u[2],
                d: [0.0, 1.0],
            },
        ];
        let q = [ud[1] * ud[2], ud[2] * ud[0], ud[0] * ud[1]].map(|x| x * x);
        let s = q[0] + q[1] + q[2];
        let mut p = v3::c([0.0; 3]);
        for (i, qi) in q.iter().enumerate() {
            let wi = *qi / s;
            if wi.v == 0.0 && wi.d == [0.0; 2] {
                continue;
            }
            p = v3::add_scaled(p, wi, self.block_dual(tri, i, ud));
        }
        (v3::val(p), [v3::part(p, 0), v3::part(p, 1)])
    }

    /// [`Self::block`] over dual numbers, for `u` in the triangle but not at corner i.
    fn block_dual(&self, tri: usize, i: usize, u: [Dual; 3]) -> D3 {
        let vi = self.triangles[tri][i] as usize;
        let rest = Dual::c(1.0) - u[i];
        let mut t = u[(i + 2) % 3] / rest;
        if t.v < 0.0 {
            t = Dual::c(0.0);
        } else if t.v > 1.0 {
            t = Dual::c(1.0);
        }
        let (e, rev) = self.side(tri, i);
        let t = if rev { Dual::c(1.0) - t } else { t };
        let (p, np) = e.eval_dual(t);
        let vp = v3::c(self.positions[vi]);
        let vn = v3::c(self.normals[vi]);
        Conic::build_dual(vp, vn, p, np, self.tension, self.handle_floor).eval(rest)
    }

    /// The normal of the patch alone, from one-sided finite differences inside the triangle:
    /// [`Self::difference_normal`] with `h = 1e-3` times the distance from the nearest corner
    /// (at least 1e-5). Kept as an independent cross-check of [`Self::derivative_normal`].
    pub fn sampled_normal(&self, tri: usize, u: [f64; 3]) -> P3 {
        let u = clamp(u);
        let k = (0..3).max_by(|&a, &b| u[a].total_cmp(&u[b])).unwrap_or(0);
        self.difference_normal(tri, u, 1e-3 * (1.0 - u[k]).clamp(1e-2, 1.0))
    }

    /// The unit normal `D_a × D_b` at `u` from the five-point one-sided difference formula
    /// (O(h⁴)) with step `h` along `e_{k+1} − e_k` and `e_{k+2} − e_k`, k the largest
    /// coordinate (the steps stay in the triangle for `h ≤ 1/12`, and the cyclic order keeps
    /// the orientation); the zero vector where the derivatives are parallel.
    pub fn difference_normal(&self, tri: usize, u: [f64; 3], h: f64) -> P3 {
        let u = clamp(u);
        let k = (0..3).max_by(|&a, &b| u[a].total_cmp(&u[b])).unwrap_or(0);
        let h = h.clamp(0.0, 1.0 / 12.0);
        let f0 = self.eval(tri, u);
        let deriv = |i: usize| -> P3 {
            let at = |s: f64| {
                let mut v = u;
                v[i] += s * h;
                v[k] -= s * h;
                self.eval(tri, v)
            };
            let c = [-25.0, 48.0, -36.0, 16.0, -3.0];
            let mut d = vec::scale(f0, c[0]);
            for (s, &ci) in c.iter().enumerate().skip(1) {
                d = vec::add_scaled(d, ci, at(s as f64));
            }
            vec::scale(d, 1.0 / (12.0 * h))
        };
        let n = vec::cross(deriv((k + 1) % 3), deriv((k + 2) % 3));
        let l = vec::norm(n);
        if l > 0.0 && l.is_finite() {
            vec::scale(n, 1.0 / l)
        } else {
            [0.0; 3]
        }
    }

    /// The surface tessellated with `density` (1..=4096) steps per triangle edge, with the
    /// surface normals ([`Self::normal`]); corners and sides are evaluated exactly, so shared
    /// points weld.
    pub fn tessellate(&self, density: usize) -> Result<TriMesh, SmoothError> {
        super::tessellate::tessellate_patches(self.triangles.len(), density, None, |t, b| {
            (self.eval(t, b), self.normal(t, b))
        })
    }

    /// The largest distance between `s(u)` and the flat triangle's point `Σ uᵢ vᵢ` on the
    /// grid with `samples` (≥ 1) steps per edge: an upper bound of the distance from the
    /// surface to the input mesh. O(triangles · samples²).
    pub fn max_deviation(&self, samples: usize) -> f64 {
        let n = samples.max(1);
        let mut worst: f64 = 0.0;
        for (t, tri) in self.triangles.iter().enumerate() {
            let v = tri.map(|i| self.positions[i as usize]);
            for i in 0..=n {
                for j in 0..=n - i {
                    let u = [
                        (n - i - j) as f64 / n as f64,
                        j as f64 / n as f64,
                        i as f64 / n as f64,
                    ];
                    let flat = vec::add(
                        vec::add(vec::scale(v[0], u[0]), vec::scale(v[1], u[1])),
                        vec::scale(v[2], u[2]),
                    );
                    worst = worst.max(vec::dist(self.eval(t, u), flat));
                }
            }
        }
        worst
    }

    /// Mesh edges whose boundary curve is a generalized conic with an inflection (Def. 6.3).
    pub fn inflected_edges(&self) -> Vec<[u32; 2]> {
        self.edges
            .iter()
            .filter(|(_, e)| !e.conic.convex)
            .map(|(k, _)| *k)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::mesh::{generate, vertex_normals, NormalWeighting};

    fn surface(m: &TriMesh, n: &[Vector3]) -> SideVertexSurface {
        side_vertex(m, n, &SideVertexOptions::default()).unwrap()
    }

    /// A seeded xorshift64*.
    struct Rng(u64);
    impl Rng {
        fn uni(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The fourth-order central difference of `s` at `u` along `dir` (a barycentric direction).
    fn central(s: &SideVertexSurface, t: usize, u: P3, dir: P3, h: f64) -> P3 {
        let at = |k: f64| s.eval(t, std::array::from_fn(|i| u[i] + k * h * dir[i]));
        let c = [(-2.0, 1.0), (-1.0, -8.0), (1.0, 8.0), (2.0, -1.0)];
        let mut d = [0.0; 3];
        for (k, w) in c {
            d = vec::add_scaled(d, w, at(k));
        }
        vec::scale(d, 1.0 / (12.0 * h))
    }

    /// Exact derivatives against differences at random interior points of a mesh with
    /// perturbed normals (convex and inflected conics, soft angles and floors all active), and
    /// the point part against `eval` bit for bit. A dropped chain-rule term (e.g. the
    /// dependence of the radial conic's end on `t`) fails by O(1).
    #[test]
    fn derivatives_agree_with_differences() {
        let m = generate::icosphere(1);
        let mut r = Rng(0x9e37_79b9_7f4a_7c15);
        let n: Vec<Vector3> = vertex_normals(&m, NormalWeighting::Area)
            .iter()
            .map(|v| v + Vector3::new(r.uni() - 0.5, r.uni() - 0.5, r.uni() - 0.5) * 0.8)
            .collect();
        let s = surface(&m, &n);
        assert!(!s.inflected_edges().is_empty());
        let (mut worst, mut count, mut off) = (0.0f64, 0, 0);
        for t in 0..m.triangles.len() {
            for _ in 0..8 {
                let (a, b) = (0.1 + 0.8 * r.uni(), r.uni());
                let u = [1.0 - a, a * (1.0 - b), a * b].map(|x| 0.05 + 0.85 * x);
                let (p, [da, db]) = s.derivatives(t, u);
                let q = s.eval(t, u);
                assert!(
                    vec::dist(p, q) <= 1e-15 * vec::norm(q).max(1.0),
                    "{p:?} {q:?}"
                );
                let fa = central(&s, t, u, [-1.0, 1.0, 0.0], 1e-3);
                let fb = central(&s, t, u, [-1.0, 0.0, 1.0], 1e-3);
                let scale = vec::norm(da).max(vec::norm(db));
                let err = vec::dist(da, fa).max(vec::dist(db, fb)) / scale;
                worst = worst.max(err);
                count += 1;
                off += usize::from(err > 1e-6);
            }
        }
        println!("{count} points: worst relative difference {worst:e}, {off} above 1e-6");
        // the differences straddle the few kinks of the construction (module doc, (a)) and
        // lose accuracy where a handle is short; everywhere else they agree to 1e-6
        assert!(
            off * 50 <= count && worst < 1e-3,
            "{off} of {count}, worst {worst}"
        );
    }

    /// Closed forms: on a triangle whose three vertex normals are its facet normal every conic
    /// is a uniform segment and the patch is the flat triangle, `∂s/∂a = v₂ − v₁`,
    /// `∂s/∂b = v₃ − v₁`; on sphere data every building block lies on the unit sphere, so its
    /// derivatives are tangent to it, and the boundary normal is the point, so its derivatives
    /// equal the point's.
    #[test]
    fn derivatives_have_the_closed_forms() {
        let m = generate::tetrahedron();
        let tri = m.triangles[0].map(|i| m.positions[i as usize].coords);
        let f = (tri[1] - tri[0]).cross(&(tri[2] - tri[0])).normalize();
        let mut n = vertex_normals(&m, NormalWeighting::Area);
        for i in m.triangles[0] {
            n[i as usize] = f;
        }
        let s = surface(&m, &n);
        let (ea, eb) = ((tri[1] - tri[0]).into(), (tri[2] - tri[0]).into());
        for u in [
            [0.2, 0.3, 0.5],
            [0.6, 0.3, 0.1],
            [0.0, 0.4, 0.6],
            [0.05, 0.9, 0.05],
        ] {
            let (_, [da, db]) = s.derivatives(0, u);
            assert!(
                vec::dist(da, ea) < 1e-13 && vec::dist(db, eb) < 1e-13,
                "{u:?}"
            );
        }
        // sphere data
        let mut m = generate::tetrahedron();
        for p in &mut m.positions {
            *p = Point3::from(p.coords / 3f64.sqrt());
        }
        let n: Vec<Vector3> = m.positions.iter().map(|p| p.coords).collect();
        let s = surface(&m, &n);
        let mut r = Rng(7);
        for t in 0..4 {
            for _ in 0..20 {
                let u0 = [r.uni(), r.uni(), r.uni()];
                let sum: f64 = u0.iter().sum();
                let u = [
                    Dual {
                        v: u0[0] / sum,
                        d: [-1.0, -1.0],
                    },
                    Dual {
                        v: u0[1] / sum,
                        d: [1.0, 0.0],
                    },
                    Dual {
                        v: u0[2] / sum,
                        d: [0.0, 1.0],
                    },
                ];
                for i in 0..3 {
                    let b = s.block_dual(t, i, u);
                    let p = v3::val(b);
                    assert!((vec::norm(p) - 1.0).abs() < 1e-12);
                    for k in 0..2 {
                        let d = v3::part(b, k);
                        assert!(vec::dot(p, d).abs() < 1e-12 * vec::norm(d).max(1.0));
                        assert!(vec::norm(d) > 0.1);
                    }
                }
                let e = &s.edges[t % s.edges.len()].1;
                let tt = Dual {
                    v: u[1].v,
                    d: [1.0, 0.0],
                };
                let (p, np) = e.eval_dual(tt);
                for k in 0..3 {
                    assert!((p[k].v - np[k].v).abs() < 1e-14);
                    assert!((p[k].d[0] - np[k].d[0]).abs() < 1e-12, "{p:?} {np:?}");
                }
            }
        }
    }
}

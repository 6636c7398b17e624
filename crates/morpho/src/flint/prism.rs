//! The prism tree (Ponce & Faugeras 87; Veltkamp 1992, §6.3, Def. 6.2, Fig. 6.4; reading
//! notes A.9) on the 3D iterative extreme-point fit hierarchy (`baselines3.rs`).
//!
//! **Prism of a node** with approximation triangle T = `(c0, c1, c2)` (counter-clockwise seen
//! from outside) and open polyhedron P: five half-spaces `lo ≤ n·x ≤ hi` (top and bottom
//! parallel to T, `n` T's unit normal) and `m_k·x ≤ d_k` for the side from `c_k` to `c_{k+1}`,
//! `m_k` the outward normal of the plane through that side parallel to the bisector plane of T
//! and its neighbouring approximation triangle T' across the side: `m_k ∥ e × (n + n')`, `e` the
//! side's direction and `n'` the unit normal of T' (the plane holding the side and the mean
//! normal bisects the dihedral angle; for coplanar T and T' it is the plane through the side
//! perpendicular to T). The offsets `lo, hi, d_k` are the extremes over P's vertices and its
//! three paths' vertices: the smallest truncated pyramid of these orientations containing P
//! (Def. 6.2; as the text says, the sides need not pass through T's edges) and the paths (which
//! the walk needs: where two paths run along the same edges and cancel mod 2, a path vertex
//! need not be a vertex of P; found by the brute-force comparison).
//!
//! *The neighbour across a side* is the node on the other side of the same path (same side id,
//! opposite direction) at the level nearest to the node's own (ties: the lower id); a side
//! with none (disc-patch arcs, the two root halves share all sides and find each other) or a
//! neighbour whose triangle is degenerate, or a mean normal that vanishes (T' folded back onto
//! T), takes `n' = n`. A node whose own triangle is degenerate (collinear corners) gets no
//! prism: it is never excluded (documented; counted by [`PrismTree3::unfiltered`]).
//!
//! **Exactness.** The five normals are stored `f64` vectors and define the half-spaces exactly;
//! only the dot products are rounded. Each stored offset is an upper bound (lower for `lo`) of
//! the exact extreme over P's vertices: `fl(a·v) ± SLACK·Σ|a_i v_i| ± tiny`, with SLACK = 8u
//! above the `γ₃ ≈ 3u` error of a 3-term dot product plus the rounding of the bound itself;
//! a query is excluded only when the same bound on `a·x` is beyond the offset. So a point
//! excluded is certainly outside the prism, which holds every vertex of P, hence P's convex
//! hull — the condition of the walk's replacement by triangle and path fills (`query3.rs`,
//! Lemma 6.1): the point-in-mesh answer is exact at the leaves and never depends on the
//! filter. With coordinates beyond 1e±150 (the flintstone tree's `prune` off) no prism is
//! stored. The tests check every vertex of every node's P against the prism in exact
//! arithmetic.
//!
//! **Refinement key** (approximations by `--error`/`--count`): the prism's half height
//! `(hi − lo)/2`, the 3D analogue of the strip error e3 (a slab about T's plane), so that the
//! prism tree, like the strip tree, chooses by e1 (the IEPF vertex) and stops by its own
//! bounding volume. Level approximations equal the IEPF's.
//! Point-in-prism costs five dot products (V: "5 faces"). Prism–prism filtering of mesh–mesh
//! intersection is not built.

use super::query::Containment;
use super::tree3::FlintTree3;
use super::{Approximation3, FlintError, Target};
use crate::geom::vec::{cross, dot, norm, sub};
use crate::geom::Point3;
use crate::mesh::TriMesh;
use crate::util::{IdMap, NONE};
use rayon::prelude::*;

/// Relative slack of a bounded dot product: 8u (u = 2⁻⁵³).
const SLACK: f64 = 4.0 * f64::EPSILON;

/// One prism: five half-spaces `a·x ≤ b` (the bottom stored as `−n·x ≤ −lo`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prism {
    /// Outward normals: top `n`, bottom `−n`, sides `m_0, m_1, m_2`.
    pub normals: [[f64; 3]; 5],
    /// Offsets: each an upper bound of the exact largest `normal·v` over P's vertices.
    pub offsets: [f64; 5],
}

/// `fl(a·x)` and a bound of its rounding error.
#[inline]
fn dot_err(a: [f64; 3], x: [f64; 3]) -> (f64, f64) {
    let s = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
    let e = SLACK * ((a[0] * x[0]).abs() + (a[1] * x[1]).abs() + (a[2] * x[2]).abs())
        + f64::MIN_POSITIVE;
    (s, e)
}

impl Prism {
    /// The prism with these normals holding the points `verts`; `None` if a value is not
    /// finite.
    fn of(normals: [[f64; 3]; 5], pos: &[[f64; 3]], verts: &[u32]) -> Option<Prism> {
        let mut offsets = [f64::NEG_INFINITY; 5];
        for &v in verts {
            let x = pos[v as usize];
            for k in 0..5 {
                let (s, e) = dot_err(normals[k], x);
                offsets[k] = offsets[k].max(s + e);
            }
        }
        (offsets.iter().all(|o| o.is_finite()) && normals.iter().flatten().all(|c| c.is_finite()))
            .then_some(Prism { normals, offsets })
    }

    /// True when `x` is certainly outside the prism (conservative).
    #[inline]
    pub fn excludes(&self, x: [f64; 3]) -> bool {
        (0..5).any(|k| {
            let (s, e) = dot_err(self.normals[k], x);
            s - e > self.offsets[k]
        })
    }

    /// Half the distance between top and bottom (the normals are unit up to rounding).
    pub fn half_height(&self) -> f64 {
        0.5 * (self.offsets[0] + self.offsets[1]) / norm(self.normals[0]).max(f64::MIN_POSITIVE)
    }
}

/// The prism tree: the IEPF hierarchy ([`FlintTree3::iepf`]) with a prism per inner node.
#[derive(Debug, Clone, PartialEq)]
pub struct PrismTree3 {
    /// The IEPF hierarchy.
    pub tree: FlintTree3,
    /// Per node id its prism (`None` for leaves and degenerate triangles).
    pub prisms: Vec<Option<Prism>>,
    /// The prisms in the order of the query walk's node copy.
    q: Vec<Option<Prism>>,
}

/// The vertices of node `id`'s open polyhedron and of its three paths (with repeats): the
/// paths' fills, which the walk puts in the node's place, are spanned by path vertices, and
/// where two paths cancel along shared edges a path vertex need not be a vertex of P.
fn node_vertices(tree: &FlintTree3, id: u32) -> Vec<u32> {
    let mut v: Vec<u32> = tree
        .node_triangles(id)
        .iter()
        .flat_map(|&t| tree.triangles()[t as usize])
        .collect();
    for p in tree.node_paths(id) {
        v.extend(p);
    }
    v
}

/// Unit normal of triangle `corners`; `None` when degenerate.
fn unit_normal(pos: &[[f64; 3]], corners: [u32; 3]) -> Option<[f64; 3]> {
    let [a, b, c] = corners.map(|v| pos[v as usize]);
    let n = cross(sub(b, a), sub(c, a));
    let l = norm(n);
    (l > 0.0 && l.is_finite()).then(|| n.map(|x| x / l))
}

impl PrismTree3 {
    /// The prism tree of a closed mesh (preconditions and errors of [`FlintTree3::new`]).
    ///
    /// ```
    /// use morpho::flint::{Containment, PrismTree3};
    /// use morpho::geom::Point3;
    /// use morpho::mesh::generate;
    /// let t = PrismTree3::new(&generate::icosphere(3)).unwrap();
    /// assert_eq!(t.contains(Point3::new(0.1, 0.2, 0.3)).unwrap(), Containment::Inside);
    /// assert_eq!(t.contains(Point3::new(1.5, 0.0, 0.0)).unwrap(), Containment::Outside);
    /// ```
    pub fn new(mesh: &TriMesh) -> Result<PrismTree3, FlintError> {
        Self::of(FlintTree3::iepf(mesh)?)
    }

    /// The prisms of an IEPF tree ([`FlintError::BadTarget`] for a flintstone tree).
    pub fn of(tree: FlintTree3) -> Result<PrismTree3, FlintError> {
        if !tree.is_iepf() {
            return Err(FlintError::BadTarget(
                "a prism tree needs the IEPF hierarchy".into(),
            ));
        }
        let pos = tree.positions();
        // side id → (node, reversed, level) of the inner nodes bounded by it
        let mut refs: IdMap<u32, Vec<(u32, bool, u32)>> = IdMap::default();
        for (id, nd) in tree.nodes.iter().enumerate() {
            if nd.is_leaf() {
                continue;
            }
            for &(s, rev) in &nd.sides {
                if s != NONE {
                    refs.entry(s).or_default().push((id as u32, rev, nd.level));
                }
            }
        }
        let prisms: Vec<Option<Prism>> = (0..tree.nodes.len())
            .into_par_iter()
            .map(|id| {
                let nd = &tree.nodes[id];
                if nd.is_leaf() || !tree.prune {
                    return None;
                }
                let n = unit_normal(pos, nd.corners)?;
                let p = nd.corners.map(|v| pos[v as usize]);
                let mut normals = [n, n.map(|x| -x), [0.0; 3], [0.0; 3], [0.0; 3]];
                for k in 0..3 {
                    let (s, rev) = nd.sides[k];
                    let nb = refs.get(&s).and_then(|r| {
                        r.iter()
                            .filter(|&&(o, orev, _)| orev != rev && o != id as u32)
                            .min_by_key(|&&(o, _, l)| (l.abs_diff(nd.level), o))
                            .and_then(|&(o, _, _)| unit_normal(pos, tree.nodes[o as usize].corners))
                    });
                    let mut mean = nb.map_or(n, |n2| std::array::from_fn(|i| n[i] + n2[i]));
                    if norm(mean) < 1e-9 {
                        mean = n;
                    }
                    let e = sub(p[(k + 1) % 3], p[k]);
                    let mut m = cross(e, mean);
                    let l = norm(m);
                    if !(l > 0.0 && l.is_finite()) {
                        return None;
                    }
                    m = m.map(|x| x / l);
                    if dot(m, sub(p[(k + 2) % 3], p[k])) > 0.0 {
                        m = m.map(|x| -x);
                    }
                    normals[2 + k] = m;
                }
                Prism::of(normals, pos, &node_vertices(&tree, id as u32))
            })
            .collect();
        let q = tree.q.order.iter().map(|&id| prisms[id as usize]).collect();
        Ok(PrismTree3 { tree, prisms, q })
    }

    /// Inner nodes without a prism (degenerate triangles; all when the filters are off).
    pub fn unfiltered(&self) -> usize {
        self.tree
            .nodes
            .iter()
            .zip(&self.prisms)
            .filter(|(n, p)| !n.is_leaf() && p.is_none())
            .count()
    }

    /// Where `x` is relative to the closed mesh: the walk of [`FlintTree3::contains`] with the
    /// prisms as filters (exact).
    pub fn contains(&self, x: Point3) -> Result<Containment, FlintError> {
        Ok(self.locate_counted(x)?.0)
    }

    /// [`Self::contains`] and the number of nodes the walk examined.
    pub fn locate_counted(&self, x: Point3) -> Result<(Containment, usize), FlintError> {
        if !(x.x.is_finite() && x.y.is_finite() && x.z.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        Ok(self.locate([x.x, x.y, x.z]))
    }

    /// [`Self::contains`] for many points, in parallel (rayon).
    pub fn contains_batch(&self, xs: &[Point3]) -> Result<Vec<Containment>, FlintError> {
        super::query3::contains_batch_by(xs, |x| self.locate(x).0)
    }

    fn locate(&self, x: [f64; 3]) -> (Containment, usize) {
        self.tree
            .locate_with(x, |i| self.q[i].is_some_and(|p| p.excludes(x)))
    }

    /// The refinement key of node `id`: its prism's half height (∞ without a prism).
    pub fn key(&self, id: u32) -> f64 {
        self.prisms[id as usize].map_or(f64::INFINITY, |p| p.half_height())
    }

    /// The approximation for `target`: the IEPF's triangles, refined while the prism's half
    /// height exceeds ε (or the largest first, to a count); e1, e2, e5 as for the other trees.
    pub fn approximate(&self, target: Target) -> Result<Approximation3, FlintError> {
        self.tree.approximate_by(target, &|id| self.key(id))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flint::contains_brute3;
    use crate::mesh::generate;
    use num_bigint::BigInt;
    use rand::{Rng, SeedableRng};

    /// `x` as `(mantissa, exponent)` with `x = m · 2^e` exactly.
    fn exact(x: f64) -> (BigInt, i32) {
        if x == 0.0 {
            return (BigInt::from(0), 0);
        }
        let bits = x.to_bits();
        let sign = if bits >> 63 == 1 { -1 } else { 1 };
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp - 1075)
        };
        (BigInt::from(m) * sign, e)
    }

    /// Exact sign of `a·x − b`.
    fn exact_sign(a: [f64; 3], x: [f64; 3], b: f64) -> std::cmp::Ordering {
        let mut terms: Vec<(BigInt, i32)> = (0..3)
            .map(|i| {
                let ((ma, ea), (mx, ex)) = (exact(a[i]), exact(x[i]));
                (ma * mx, ea + ex)
            })
            .collect();
        let (mb, eb) = exact(b);
        terms.push((-mb, eb));
        let lo = terms.iter().map(|t| t.1).min().unwrap();
        let sum: BigInt = terms
            .into_iter()
            .map(|(m, e)| m << ((e - lo) as usize))
            .sum();
        sum.cmp(&BigInt::from(0))
    }

    fn prism_checks(t: &PrismTree3) -> usize {
        let pos = t.tree.positions();
        let mut checked = 0;
        for (id, nd) in t.tree.nodes.iter().enumerate() {
            let Some(p) = t.prisms[id] else { continue };
            assert!(!nd.is_leaf());
            {
                for v in node_vertices(&t.tree, id as u32) {
                    let x = pos[v as usize];
                    for k in 0..5 {
                        // exactly inside every half-space
                        assert_ne!(
                            exact_sign(p.normals[k], x, p.offsets[k]),
                            std::cmp::Ordering::Greater,
                            "node {id} vertex {v} face {k}"
                        );
                    }
                    assert!(!p.excludes(x));
                    checked += 1;
                }
            }
            // the side planes are parallel to a bisector: perpendicular to T's side
            let c = nd.corners.map(|v| pos[v as usize]);
            for k in 0..3 {
                let e = sub(c[(k + 1) % 3], c[k]);
                assert!(dot(p.normals[2 + k], e).abs() <= 1e-9 * norm(e));
                // outward: the opposite corner is not beyond the side plane
                assert!(dot(p.normals[2 + k], sub(c[(k + 2) % 3], c[k])) <= 0.0);
            }
        }
        checked
    }

    fn random_queries(t: &FlintTree3, n: usize, seed: u64) -> Vec<[f64; 3]> {
        let pos = t.positions();
        let (lo, hi) = crate::geom::vec::bounds(pos);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut xs: Vec<[f64; 3]> = (0..n)
            .map(|_| std::array::from_fn(|k| rng.gen_range(lo[k] - 0.1..=hi[k] + 0.1)))
            .collect();
        // every vertex, and the midpoints of some edges (on the boundary)
        xs.extend_from_slice(pos);
        for tr in t.triangles().iter().step_by(7) {
            let (a, b) = (pos[tr[0] as usize], pos[tr[1] as usize]);
            xs.push(std::array::from_fn(|k| 0.5 * (a[k] + b[k])));
        }
        xs
    }

    #[test]
    fn prisms_hold_their_polyhedra_and_queries_equal_brute_force() {
        for m in [
            generate::icosphere(3),
            generate::torus(2.0, 0.7, 24, 12),
            generate::cube(),
        ] {
            let t = PrismTree3::new(&m).unwrap();
            assert!(prism_checks(&t) > 0);
            let mut excluded = 0;
            for x in random_queries(&t.tree, 3000, 7) {
                let (got, visits) = t.locate(x);
                let want = contains_brute3(t.tree.positions(), t.tree.triangles(), x);
                assert_eq!(got, want, "{x:?}");
                excluded += usize::from(visits < t.tree.nodes.len());
            }
            assert!(excluded > 0, "the prisms never pruned");
        }
    }

    #[test]
    fn prism_walk_prunes_on_a_sphere() {
        let t = PrismTree3::new(&generate::icosphere(4)).unwrap();
        assert_eq!(t.unfiltered(), 0);
        let (c, visits) = t.locate([0.0, 0.0, 0.0]);
        assert_eq!(c, Containment::Inside);
        assert!(visits < t.tree.nodes.len() / 4, "{visits} visits");
        // the half height is the slab about T's plane: e2 ≤ 2·key
        let a = t.approximate(Target::Count(100)).unwrap();
        assert!(a.triangles.len() >= 100);
    }
}

//! Point in polyhedron on a 3D flintstone tree (Veltkamp 1992, §7.4, Lemma 6.1; reading notes
//! A.8), and its brute-force oracle.
//!
//! The answer is the crossing parity of a ray from X towards +x, with X moved symbolically by
//! (0, ε, ε²) ([`ray_crosses_triangle`]): exact, and defined for every ray (through edges and
//! vertices too). Outside the root ball ⇒ outside. Otherwise the walk opens every node whose
//! flintstone may hold X; a node whose flintstone certainly does not (its convex `f64`
//! superset, `ball.rs`) is *replaced*: instead of its open polyhedron P the ray is tested
//! against its triangle and the *fills* of its three paths. Leaves are the input triangles,
//! where "on the boundary" is decided exactly ([`segment_meets_triangle`] of the point).
//!
//! **Why the replacement is exact (and where it deviates from V).** Lemma 6.1 swaps a part B
//! for an approximation A "joined to the rest without cracks". In 3D a neighbour that is opened
//! while this node is replaced leaves a crack: its children follow the path with finer
//! triangles than this node's straight side. So each replaced node stands in with its triangle
//! *plus* the fill of each side — a surface spanning the side and its path: the triangles
//! `(u, m, v)` of the side's splits down to single edges, and a fan from `u` over a path never
//! split. Then `∂fill = path + side`, and with `∂P = path₁ + path₂ + path₃` (the check of
//! `region.rs`) P − triangle − fills is a closed surface (mod 2) inside the convex superset of
//! the flintstone; X outside it ⇒ the closed surface does not change the parity. Sides shared
//! by two replaced nodes contribute twice and cancel. Each fill is tested hierarchically
//! (each side keeps a ball around its path; a ray that misses it skips the whole fill).
//!
//! [`contains_brute3`] is the oracle: every triangle, on-triangle test and a ray along +z (a
//! different axis from the walk's, so the two do not share their degenerate cases).
//! Cost: O(nodes whose flintstone holds X + their children + fills the ray meets).

use super::ball::Filter;
use super::query::Containment;
use super::tree3::FlintTree3;
use super::FlintError;
use crate::geom::intersect::{ray_crosses_triangle, segment_meets_triangle};
use crate::geom::vec::dist2;
use crate::geom::Point3;
use crate::util::NONE;
use rayon::prelude::*;
use smallvec::SmallVec;

/// The ray axis of the hierarchical walk (+x).
const AXIS: usize = 0;

/// Point in a closed mesh by brute force: on a triangle (exact) ⇒ boundary, else the parity of
/// a ray along +z with the symbolic perturbation of [`ray_crosses_triangle`].
pub fn contains_brute3(positions: &[[f64; 3]], triangles: &[[u32; 3]], x: [f64; 3]) -> Containment {
    let mut inside = false;
    for t in triangles {
        let [a, b, c] = t.map(|v| positions[v as usize]);
        if segment_meets_triangle(x, x, a, b, c) {
            return Containment::Boundary;
        }
        inside ^= ray_crosses_triangle(x, 2, a, b, c);
    }
    if inside {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

/// The answers of `locate` for many points, in input order and in parallel (rayon), after
/// refusing any non-finite coordinate (shared by the flintstone and prism walks' batches).
pub(super) fn contains_batch_by(
    xs: &[Point3],
    locate: impl Fn([f64; 3]) -> Containment + Sync,
) -> Result<Vec<Containment>, FlintError> {
    if xs
        .iter()
        .any(|x| !(x.x.is_finite() && x.y.is_finite() && x.z.is_finite()))
    {
        return Err(FlintError::NonFiniteQuery);
    }
    Ok(xs.par_iter().map(|x| locate([x.x, x.y, x.z])).collect())
}

/// Does the ray from `x` (towards +`AXIS`, perturbed) certainly miss the ball `(c, r2)`?
#[inline]
fn ray_misses(x: [f64; 3], (c, r2): ([f64; 3], f64)) -> bool {
    let (v, w) = ((AXIS + 1) % 3, (AXIS + 2) % 3);
    let dv = c[v] - x[v];
    let dw = c[w] - x[w];
    if dv * dv + dw * dw > r2 {
        return true;
    }
    c[AXIS] < x[AXIS] && dist2(c, x) > r2
}

impl FlintTree3 {
    /// Where `x` is relative to the closed mesh (hierarchical, exact).
    ///
    /// ```
    /// use morpho::flint::{Containment, FlintTree3};
    /// use morpho::geom::Point3;
    /// use morpho::mesh::generate;
    /// let t = FlintTree3::from_mesh(&generate::cube()).unwrap();
    /// assert_eq!(t.contains(Point3::new(0.5, 0.5, 0.5)).unwrap(), Containment::Inside);
    /// assert_eq!(t.contains(Point3::new(1.0, 0.5, 0.5)).unwrap(), Containment::Boundary);
    /// assert_eq!(t.contains(Point3::new(1.5, 0.5, 0.5)).unwrap(), Containment::Outside);
    /// ```
    pub fn contains(&self, x: Point3) -> Result<Containment, FlintError> {
        if !(x.x.is_finite() && x.y.is_finite() && x.z.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        Ok(self.locate([x.x, x.y, x.z]).0)
    }

    /// [`Self::contains`] for many points, in parallel (rayon).
    pub fn contains_batch(&self, xs: &[Point3]) -> Result<Vec<Containment>, FlintError> {
        contains_batch_by(xs, |x| self.locate(x).0)
    }

    /// [`Self::contains`] and the number of nodes the walk examined (0 outside the root ball).
    pub fn locate_counted(&self, x: Point3) -> Result<(Containment, usize), FlintError> {
        if !(x.x.is_finite() && x.y.is_finite() && x.z.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        Ok(self.locate([x.x, x.y, x.z]))
    }

    /// The brute-force answer on this tree's mesh ([`contains_brute3`]).
    pub fn contains_brute(&self, x: [f64; 3]) -> Containment {
        contains_brute3(&self.pos, &self.tris, x)
    }

    /// The hierarchical walk (finite `x`).
    pub(crate) fn locate(&self, x: [f64; 3]) -> (Containment, usize) {
        let p = |v: u32| self.pos[v as usize];
        let q = &self.q;
        self.locate_with(x, |i| {
            let nd = &q.nodes[i];
            nd.filter.excludes(x, || nd.corners.map(p))
        })
    }

    /// The walk with the node filter `excludes(i)` for the node at position `i` of the
    /// breadth-first copy ([`QueryIndex::order`]); it must be true only when `x` is certainly
    /// outside a convex set holding every vertex of the node's open polyhedron (then the
    /// replacement by triangle and fills is exact, see the module doc).
    #[inline]
    pub(crate) fn locate_with(
        &self,
        x: [f64; 3],
        excludes: impl Fn(usize) -> bool,
    ) -> (Containment, usize) {
        if dist2(x, self.root.center) > self.root.reach2 {
            return (Containment::Outside, 0);
        }
        let q = &self.q;
        let p = |v: u32| self.pos[v as usize];
        let mut inside = false;
        let mut visits = 0;
        let mut stack: SmallVec<[u32; 128]> = SmallVec::new();
        stack.extend((0..q.top).rev());
        while let Some(id) = stack.pop() {
            visits += 1;
            let nd = &q.nodes[id as usize];
            if nd.leaf {
                let [a, b, c] = nd.corners.map(p);
                // on the triangle only inside its box (exact comparisons)
                let in_box = (0..3)
                    .all(|k| a[k].min(b[k]).min(c[k]) <= x[k] && x[k] <= a[k].max(b[k]).max(c[k]));
                if in_box && segment_meets_triangle(x, x, a, b, c) {
                    return (Containment::Boundary, visits);
                }
                inside ^= ray_crosses_triangle(x, AXIS, a, b, c);
                continue;
            }
            if excludes(id as usize) {
                let cs = nd.corners.map(p);
                inside ^= ray_crosses_triangle(x, AXIS, cs[0], cs[1], cs[2]);
                for &s in &nd.sides {
                    inside ^= self.fill_parity(s, x);
                }
                continue;
            }
            stack.extend((nd.first_child..nd.first_child + nd.n_children).rev());
        }
        let c = if inside {
            Containment::Inside
        } else {
            Containment::Outside
        };
        (c, visits)
    }

    /// Crossing parity of the ray with the fill of side `s` (see the module doc).
    fn fill_parity(&self, s: u32, x: [f64; 3]) -> bool {
        let q = &self.q;
        let mut par = false;
        let mut stack: SmallVec<[u32; 32]> = SmallVec::new();
        stack.push(s);
        let p = |v: u32| self.pos[v as usize];
        while let Some(s) = stack.pop() {
            let sd = &q.sides[s as usize];
            if sd.len < 3 || ray_misses(x, sd.ball) {
                continue;
            }
            let path = &q.paths[sd.start as usize..(sd.start + sd.len) as usize];
            let (u, v) = (path[0], path[path.len() - 1]);
            if sd.m != NONE {
                par ^= ray_crosses_triangle(x, AXIS, p(u), p(sd.m), p(v));
                stack.push(sd.a);
                stack.push(sd.b);
            } else {
                for w in path[1..].windows(2) {
                    par ^= ray_crosses_triangle(x, AXIS, p(u), p(w[0]), p(w[1]));
                }
            }
        }
        par
    }
}

/// A node as the walk reads it: filter, corners, sides, children (contiguous).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct QNode {
    filter: Filter,
    leaf: bool,
    corners: [u32; 3],
    sides: [u32; 3],
    first_child: u32,
    n_children: u32,
}

/// A side as the fills read it: ball, path range in `paths`, split (`m = NONE` if none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct QSide {
    ball: ([f64; 3], f64),
    start: u32,
    len: u32,
    m: u32,
    a: u32,
    b: u32,
}

/// The compact, breadth-first copy of a tree for the point queries: the children of a node
/// are consecutive (the root's are `0..top`), so the filters the walk reads lie together.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct QueryIndex {
    nodes: Vec<QNode>,
    /// The node id at each position of `nodes`.
    pub(crate) order: Vec<u32>,
    top: u32,
    sides: Vec<QSide>,
    paths: Vec<u32>,
}

impl QueryIndex {
    pub(crate) fn of(t: &FlintTree3) -> QueryIndex {
        let mut order: Vec<u32> = t.root.children.clone();
        let mut i = 0;
        while i < order.len() {
            let id = order[i] as usize;
            order.extend(t.nodes[id].children.iter().copied());
            i += 1;
        }
        let mut new_of = vec![NONE; t.nodes.len()];
        for (k, &id) in order.iter().enumerate() {
            new_of[id as usize] = k as u32;
        }
        let nodes = order
            .iter()
            .map(|&id| {
                let nd = &t.nodes[id as usize];
                QNode {
                    // a leaf is never excluded (it has no stone)
                    filter: nd.stone.as_ref().map_or(Filter::none(), |s| s.filter),
                    leaf: nd.is_leaf(),
                    corners: nd.corners,
                    sides: nd.sides.map(|s| s.0),
                    first_child: nd.children.first().map_or(0, |&c| new_of[c as usize]),
                    n_children: nd.children.len() as u32,
                }
            })
            .collect();
        let mut paths = Vec::new();
        let sides = t
            .sides
            .iter()
            .map(|sd| {
                let start = paths.len() as u32;
                paths.extend_from_slice(&sd.path);
                let (m, a, b) = sd.split.unwrap_or((NONE, NONE, NONE));
                QSide {
                    ball: sd.ball,
                    start,
                    len: sd.path.len() as u32,
                    m,
                    a,
                    b,
                }
            })
            .collect();
        QueryIndex {
            nodes,
            order,
            top: t.root.children.len() as u32,
            sides,
            paths,
        }
    }
}

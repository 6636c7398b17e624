//! The 3D flintstone tree of a closed triangle mesh (Veltkamp 1992, §7.3.2, Alg. 7.2; reading
//! notes A.7).
//!
//! **Construction, as the text describes it.** The root holds a ball around every vertex and
//! the level-0 triangle `v_i v_j v_k`; the three shortest edge paths (Dijkstra, Euclidean edge
//! lengths) between them divide the closed mesh into two open polyhedra, the root's two
//! children, whose triangles are `v_i v_j v_k` in both orientations. Then, level by level
//! (Alg. 7.2's two loops): first every approximation triangle whose open polyhedron has more
//! than one triangle decides the sides it wants split — an angle below the threshold (default
//! 20°) is not split: one small angle splits the two sides next to it, two small angles the
//! side between them — and a side marked by either of its two triangles is split by both
//! (forced splits, no cracks); then every triangle splits: at its marked sides (2, 3 or 4
//! children, Fig. 7.10), at a vertex on the side's path giving the smallest difference of the
//! new sides' lengths (Euclidean `| |u m| − |m v| |`: the text leaves open which lengths), or,
//! with no marked side, 3-split at the flintstone's split vertex (cap vertex, else larger signed
//! radius, Def. 7.5). New paths are shortest paths inside the open polyhedron, which is divided
//! along them (`region.rs`); void children (no triangle: coinciding paths) are discarded, so a
//! node has 1–4 children. An open polyhedron of one triangle is a leaf; no vertex is ever
//! created, and every input triangle is exactly one leaf. Each node stores its flintstone
//! ([`Flintstone3`], `ball.rs`) over the vertices of its open polyhedron and of its three paths.
//!
//! **Deviations (documented, each forced by a gap in the text):**
//! - *Root ball.* V asks for the smallest ball touching ≥ 3 vertices; the root keeps the
//!   smallest enclosing ball (Welzl, [`crate::geom::smallest_enclosing_ball`]), which is all the
//!   queries need. Its corners are three support points when it has ≥ 3 (the pair farthest apart
//!   and the one spanning the largest triangle with them); with two, the third corner is the
//!   vertex farthest from the centre that is not collinear with them — the vertex the notes'
//!   O(N²) search would mostly pick, in O(N).
//! - *Split vertex of a 3-split* is chosen by V's rule among the vertices *not on* the three
//!   paths (a vertex on a path is split at by a side split instead); with none, every side
//!   whose path has an inner vertex is split (progress, V's last refinement steps).
//! - *Retries.* When the division for V's choice fails the check of `region.rs` (a part
//!   would keep every triangle, a component has no owner, or a part's boundary is not its
//!   paths), the alternatives are tried in order: 3-split at the other ball's vertex, side
//!   splits at every side with an inner path vertex, at each such side alone. A node that
//!   splits otherwise than a neighbour forced leaves a crack in the level approximation (the
//!   queries stay exact, see `query3.rs`).
//! - *Fallback (genus > 0, several parts, coinciding paths).* V's text is for genus-0
//!   polyhedra. Wherever a division does not give parts whose boundary equals their three paths
//!   mod 2 (`region.rs`), or would not shrink every part, the node's open polyhedron is cut into
//!   disc patches instead (`patch3.rs`) whose corners are three vertices of each patch's
//!   boundary loop and whose paths are the loop's arcs (not shortest paths); patches of one
//!   triangle are leaves. The root of a torus is divided this way; [`FlintTree3::fallbacks`]
//!   counts the nodes. If even the patches failed the check, the node's triangles become its
//!   leaves (never observed; kept so that the tree is always valid). Measured: the horse
//!   (96 966 triangles, genus 0) has 6 130 fallback nodes among ≈ 65 000 inner nodes, 4 929 of
//!   them with ≤ 3 triangles (the last refinements); the torus's root is divided this way.
//! - *Union and unbounded stones* (a vertex in the corners' plane outside their circumcircle,
//!   or corners that coalesce or are collinear) are represented, never pruned by (see
//!   `ball.rs`); their error is their hull's (∪) or ∞ (unbounded).
//!
//! Preconditions (typed [`FlintError`]s): at least one triangle, indices in range, finite
//! coordinates, no triangle with a repeated vertex or collinear corners (exact), a closed
//! 2-manifold (every edge in exactly two triangles, every vertex fan one disc) that is
//! consistently oriented. Self-intersection is not checked (the point queries count crossing
//! parity, which stays well defined). Coordinates whose squares over- or underflow (beyond
//! about 1e±150) turn the query filters off (answers stay exact, queries become brute force).
//! Cost: O(N (log N)²) best, O(N² log N) worst (Thm 7.3); storage Θ(N_t) nodes (Thm 7.4) plus
//! the paths.

use super::ball::{reach2, Flintstone3};
use super::patch3::{boundary_loop, corners_and_arcs, disc_patches};
use super::region::Surface;
use super::FlintError;
use crate::geom::intersect::degenerate_triangle;
use crate::geom::vec::{dist, dist2, sub};
use crate::geom::{smallest_enclosing_ball, Point3};
use crate::mesh::{analyze_topology, TriMesh};
use crate::util::NONE;

/// One path of the approximation (a side of one or two approximation triangles), split at most
/// once into two sub-sides.
#[derive(Debug, Clone, PartialEq)]
pub struct Side3 {
    /// The edge path, from its first to its last vertex (input indices).
    pub path: Vec<u32>,
    /// `(vertex, first half, second half)` once the side is split.
    pub split: Option<(u32, u32, u32)>,
    pub(crate) mark: bool,
    /// A ball `(centre, inflated r²)` holding every path vertex (the fill filter).
    pub(crate) ball: ([f64; 3], f64),
}

/// One node of the tree below the root.
#[derive(Debug, Clone, PartialEq)]
pub struct FlintNode3 {
    /// The approximation triangle (input indices; counter-clockwise seen from outside the open
    /// polyhedron's side; for a leaf the input triangle).
    pub corners: [u32; 3],
    /// Side `k` runs from `corners[k]` to `corners[k+1]`: `(side id, stored reversed)`;
    /// `(NONE, false)` for leaves.
    pub sides: [(u32, bool); 3],
    /// The flintstone (`None` for leaves).
    pub stone: Option<Flintstone3>,
    /// Child node ids.
    pub children: Vec<u32>,
    /// Tree level (the root's children: 1).
    pub level: u32,
    /// The input triangle of a leaf, else [`NONE`].
    pub triangle: u32,
    /// Children made by the disc-patch fallback.
    pub patched: bool,
    /// Range of this node's triangles in [`FlintTree3::leaf_order`].
    pub range: [u32; 2],
}

impl FlintNode3 {
    /// True for a leaf (one input triangle).
    pub fn is_leaf(&self) -> bool {
        self.triangle != NONE
    }
    /// The flintstone error `max{w1, w2}` (0 for a leaf).
    pub fn error(&self) -> f64 {
        self.stone.as_ref().map_or(0.0, |s| s.error())
    }
}

/// The root: the enclosing ball, the level-0 triangle and the root's children.
#[derive(Debug, Clone, PartialEq)]
pub struct FlintRoot3 {
    /// Centre of the smallest enclosing ball.
    pub center: [f64; 3],
    /// Its radius.
    pub radius: f64,
    /// Inflated squared radius about `center` holding every vertex (the query's first test).
    pub(crate) reach2: f64,
    /// The level-0 triangle `v_i v_j v_k`.
    pub corners: [u32; 3],
    /// Child node ids (two halves, or disc patches after the fallback).
    pub children: Vec<u32>,
    /// True when the root was divided into disc patches.
    pub patched: bool,
}

/// A 3D flintstone tree (Alg. 7.2) with its mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct FlintTree3 {
    pub(crate) pos: Vec<[f64; 3]>,
    pub(crate) tris: Vec<[u32; 3]>,
    /// The root.
    pub root: FlintRoot3,
    /// All nodes below the root.
    pub nodes: Vec<FlintNode3>,
    /// All paths (sides).
    pub sides: Vec<Side3>,
    /// Input triangles in depth-first leaf order: node `n` covers `leaf_order[n.range]`.
    pub leaf_order: Vec<u32>,
    pub(crate) prune: bool,
    /// Per node the refinement key of the 3D IEPF hierarchy (e1 of the node: the largest
    /// distance of its vertices to its triangle; 0 for leaves); empty for the flintstone tree,
    /// whose key is the flintstone error (`baselines3.rs`).
    pub(crate) keys: Vec<f64>,
    /// The compact copy the point queries walk (`query3.rs`).
    pub(crate) q: super::query3::QueryIndex,
}

/// The default smallest angle that is still split (degrees).
pub const DEFAULT_MIN_ANGLE: f64 = 20.0;

/// A node under construction: its id and its open polyhedron.
struct Item {
    node: u32,
    region: Vec<u32>,
    /// 3D IEPF: the node came from a 3-split, so its side 0 is an *old* side, to be 2-split
    /// next (`baselines3.rs`).
    old: bool,
}

/// Which hierarchy the builder makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Method3 {
    /// Alg. 7.2 (this module).
    Flintstone,
    /// The 3D iterative extreme-point fit (`baselines3.rs`).
    Iepf,
}

struct Builder<'a> {
    s: Surface<'a>,
    nodes: Vec<FlintNode3>,
    sides: Vec<Side3>,
    prune: bool,
    min_angle: f64,
    method: Method3,
    keys: Vec<f64>,
}

/// Flat positions and the neighbour table of a checked mesh.
type Checked = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// Checks the mesh; returns flat positions and the neighbour table.
fn check(positions: &[Point3], triangles: &[[u32; 3]]) -> Result<Checked, FlintError> {
    if triangles.is_empty() {
        return Err(FlintError::EmptyMesh);
    }
    let n = positions.len();
    for (t, tr) in triangles.iter().enumerate() {
        if let Some(&v) = tr.iter().find(|&&v| v as usize >= n) {
            return Err(FlintError::VertexOutOfRange {
                triangle: t,
                vertex: v,
                vertices: n,
            });
        }
    }
    let pos: Vec<[f64; 3]> = positions.iter().map(|p| [p.x, p.y, p.z]).collect();
    for tr in triangles {
        for &v in tr {
            if pos[v as usize].iter().any(|c| !c.is_finite()) {
                return Err(FlintError::NonFinite { index: v as usize });
            }
        }
    }
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        if a == b
            || b == c
            || a == c
            || degenerate_triangle(pos[a as usize], pos[b as usize], pos[c as usize])
        {
            return Err(FlintError::DegenerateTriangle { triangle: t });
        }
    }
    let topo = analyze_topology(&TriMesh::new(positions.to_vec(), triangles.to_vec()));
    if let Some(&[a, b]) = topo.non_manifold_edges.first() {
        return Err(FlintError::NonManifoldEdge { a, b });
    }
    if let Some(&v) = topo.non_manifold_vertices.first() {
        return Err(FlintError::NonManifoldVertex { vertex: v });
    }
    if topo.num_boundary_edges > 0 {
        return Err(FlintError::OpenMesh {
            boundary_edges: topo.num_boundary_edges,
        });
    }
    if !topo.consistently_oriented {
        return Err(FlintError::InconsistentOrientation);
    }
    Ok((pos, topo.neighbors))
}

/// Angle at `a` of triangle `a b c` (radians; NaN when degenerate).
fn angle(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (u, v) = (sub(b, a), sub(c, a));
    let d = crate::geom::vec::dot(u, v) / (dist(a, b) * dist(a, c));
    d.clamp(-1.0, 1.0).acos()
}

impl FlintTree3 {
    /// Builds the tree of a closed, consistently oriented 2-manifold triangle mesh with the
    /// default angle threshold ([`DEFAULT_MIN_ANGLE`]).
    ///
    /// ```
    /// use morpho::flint::FlintTree3;
    /// use morpho::mesh::generate;
    /// let m = generate::icosphere(2);
    /// let t = FlintTree3::from_mesh(&m).unwrap();
    /// assert_eq!(t.leaf_count(), m.triangles.len());
    /// ```
    pub fn new(positions: &[Point3], triangles: &[[u32; 3]]) -> Result<FlintTree3, FlintError> {
        Self::with_min_angle(positions, triangles, DEFAULT_MIN_ANGLE)
    }

    /// [`Self::new`] on a [`TriMesh`].
    pub fn from_mesh(mesh: &TriMesh) -> Result<FlintTree3, FlintError> {
        Self::new(&mesh.positions, &mesh.triangles)
    }

    /// [`Self::new`] with the smallest angle (degrees, in [0, 60)) that a 3-split may make.
    pub fn with_min_angle(
        positions: &[Point3],
        triangles: &[[u32; 3]],
        min_angle_deg: f64,
    ) -> Result<FlintTree3, FlintError> {
        Self::build(positions, triangles, min_angle_deg, Method3::Flintstone)
    }

    /// The tree of `method` (the IEPF ignores `min_angle_deg`).
    pub(crate) fn build(
        positions: &[Point3],
        triangles: &[[u32; 3]],
        min_angle_deg: f64,
        method: Method3,
    ) -> Result<FlintTree3, FlintError> {
        if !(0.0..60.0).contains(&min_angle_deg) {
            return Err(FlintError::BadTarget(format!(
                "smallest angle {min_angle_deg}° (must be in [0, 60))"
            )));
        }
        let (pos, nbr) = check(positions, triangles)?;
        let mut used = vec![false; pos.len()];
        for tr in triangles {
            for &v in tr {
                used[v as usize] = true;
            }
        }
        let used: Vec<u32> = (0..pos.len() as u32)
            .filter(|&v| used[v as usize])
            .collect();
        let big = used
            .iter()
            .flat_map(|&v| pos[v as usize])
            .fold(0.0f64, |m, c| m.max(c.abs()));
        let (lo, hi) =
            crate::geom::vec::bounds(&used.iter().map(|&v| pos[v as usize]).collect::<Vec<_>>());
        let diag = dist(lo, hi);
        let prune = big < 1e150 && diag > 1e-150;
        let pts: Vec<Point3> = used.iter().map(|&v| positions[v as usize]).collect();
        let ball = smallest_enclosing_ball(&pts).map_err(|_| FlintError::EmptyMesh)?;
        let center = [ball.center.x, ball.center.y, ball.center.z];
        let support: Vec<u32> = ball.support.iter().map(|&i| used[i]).collect();
        let corners = root_corners(&pos, &used, &support, center);
        let reach = if prune {
            reach2(&pos, &used, center)
        } else {
            f64::INFINITY
        };
        let tris = triangles.to_vec();
        let (nodes, sides, children, patched, keys) = {
            let mut b = Builder {
                s: Surface::new(&pos, &tris, &nbr),
                nodes: Vec::new(),
                sides: Vec::new(),
                prune,
                min_angle: min_angle_deg.to_radians(),
                method,
                keys: Vec::new(),
            };
            let (children, patched) = b.run(corners);
            (b.nodes, b.sides, children, patched, b.keys)
        };
        let mut t = FlintTree3 {
            pos,
            tris,
            root: FlintRoot3 {
                center,
                radius: ball.radius,
                reach2: reach,
                corners: corners.unwrap_or([NONE; 3]),
                children,
                patched,
            },
            nodes,
            sides,
            leaf_order: Vec::new(),
            prune,
            keys,
            q: Default::default(),
        };
        t.number_leaves();
        t.q = super::query3::QueryIndex::of(&t);
        Ok(t)
    }

    /// Depth-first leaf order and each node's range in it.
    fn number_leaves(&mut self) {
        let mut order = Vec::with_capacity(self.tris.len());
        // (node, entered)
        let mut stack: Vec<(u32, bool)> = self
            .root
            .children
            .iter()
            .rev()
            .map(|&c| (c, false))
            .collect();
        while let Some((id, entered)) = stack.pop() {
            let nd = &mut self.nodes[id as usize];
            if entered {
                nd.range[1] = order.len() as u32;
                continue;
            }
            nd.range[0] = order.len() as u32;
            if nd.is_leaf() {
                order.push(nd.triangle);
                nd.range[1] = order.len() as u32;
                continue;
            }
            stack.push((id, true));
            for &c in self.nodes[id as usize].children.iter().rev() {
                stack.push((c, false));
            }
        }
        self.leaf_order = order;
    }

    /// The input vertex positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.pos
    }
    /// The input triangles.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.tris
    }
    /// Nodes including the root.
    pub fn node_count(&self) -> usize {
        self.nodes.len() + 1
    }
    /// Number of leaves (= input triangles).
    pub fn leaf_count(&self) -> usize {
        self.nodes.iter().filter(|n| n.is_leaf()).count()
    }
    /// The largest node level (root: 0).
    pub fn depth(&self) -> u32 {
        self.nodes.iter().map(|n| n.level).max().unwrap_or(0)
    }
    /// Nodes whose children come from the disc-patch fallback (root included).
    pub fn fallbacks(&self) -> usize {
        self.nodes.iter().filter(|n| n.patched).count() + usize::from(self.root.patched)
    }
    /// The input triangles of node `id`'s open polyhedron.
    pub fn node_triangles(&self, id: u32) -> &[u32] {
        let r = self.nodes[id as usize].range;
        &self.leaf_order[r[0] as usize..r[1] as usize]
    }
    /// The three boundary paths of node `id`, directed corner to corner (empty for leaves).
    pub fn node_paths(&self, id: u32) -> Vec<Vec<u32>> {
        let nd = &self.nodes[id as usize];
        if nd.is_leaf() {
            return Vec::new();
        }
        nd.sides
            .iter()
            .map(|&(s, rev)| directed(&self.sides[s as usize].path, rev))
            .collect()
    }
    /// Count of inner nodes by stone kind `[cap, intersection, flat, union, unbounded]`.
    pub fn kind_counts(&self) -> [usize; 5] {
        use super::disc::StoneKind::*;
        let mut c = [0; 5];
        for st in self.nodes.iter().filter_map(|n| n.stone.as_ref()) {
            c[match st.kind {
                Cap => 0,
                Intersection => 1,
                Segment => 2,
                Union => 3,
                Unbounded => 4,
            }] += 1;
        }
        c
    }
}

/// A path in the given direction.
fn directed(path: &[u32], rev: bool) -> Vec<u32> {
    let mut p = path.to_vec();
    if rev {
        p.reverse();
    }
    p
}

/// The level-0 triangle (see the module doc); `None` if all vertices are collinear.
fn root_corners(pos: &[[f64; 3]], used: &[u32], support: &[u32], c: [f64; 3]) -> Option<[u32; 3]> {
    let p = |v: u32| pos[v as usize];
    let mut best: Option<(f64, u32, u32)> = None;
    for (k, &a) in support.iter().enumerate() {
        for &b in &support[k + 1..] {
            let d = dist2(p(a), p(b));
            if p(a) != p(b) && best.map_or(true, |(bd, _, _)| d > bd) {
                best = Some((d, a, b));
            }
        }
    }
    let (_, i, j) = best?;
    let area = |k: u32| crate::geom::vec::triangle_area2(p(i), p(j), p(k));
    let third = support
        .iter()
        .copied()
        .filter(|&k| !degenerate_triangle(p(i), p(j), p(k)))
        .max_by(|&a, &b| area(a).total_cmp(&area(b)));
    let k = third.or_else(|| {
        used.iter()
            .copied()
            .filter(|&k| !degenerate_triangle(p(i), p(j), p(k)))
            .max_by(|&a, &b| dist2(p(a), c).total_cmp(&dist2(p(b), c)).then(b.cmp(&a)))
    })?;
    Some([i, j, k])
}

/// A way to split a node: 3-split at a vertex, or side splits at the listed sides.
enum Split {
    Vertex(u32),
    Sides(Vec<usize>),
}

/// A child to be made: corners and directed sides.
type Spec = ([u32; 3], [(u32, bool); 3]);

impl Builder<'_> {
    /// Builds everything below the root; returns the root's children and whether they are
    /// disc patches.
    fn run(&mut self, corners: Option<[u32; 3]>) -> (Vec<u32>, bool) {
        let all: Vec<u32> = (0..self.s.tris.len() as u32).collect();
        let mut frontier = Vec::new();
        let mut root_children = Vec::new();
        let halves = corners.and_then(|c| self.root_halves(c, &all));
        let patched = halves.is_none();
        match halves {
            Some((specs, regions)) => {
                for (spec, region) in specs.into_iter().zip(regions) {
                    if let Some(id) = self.make(spec, region, 1, &mut frontier, false) {
                        root_children.push(id);
                    }
                }
            }
            None => {
                root_children = self.patches(&all, 1, &mut frontier);
            }
        }
        while !frontier.is_empty() {
            if self.method == Method3::Flintstone {
                for it in &frontier {
                    self.decide(it);
                }
            }
            let mut next = Vec::new();
            for it in frontier {
                self.split(it, &mut next);
            }
            frontier = next;
        }
        (root_children, patched)
    }

    /// The two halves of the closed mesh cut along the root triangle's paths, if valid.
    fn root_halves(&mut self, c: [u32; 3], all: &[u32]) -> Option<(Vec<Spec>, Vec<Vec<u32>>)> {
        let [i, j, k] = c;
        let pij = self.s.shortest_paths(all, i, &[j])?.pop()?;
        let pjk = self.s.shortest_paths(all, j, &[k])?.pop()?;
        let pki = self.s.shortest_paths(all, k, &[i])?.pop()?;
        let ra = [pij.as_slice(), pjk.as_slice(), pki.as_slice()];
        let (ri, rj, rk) = (
            directed(&pki, true),
            directed(&pjk, true),
            directed(&pij, true),
        );
        let rb = [ri.as_slice(), rj.as_slice(), rk.as_slice()];
        let regions = self.s.divide(all, &ra, &[ra, rb])?;
        let (sij, sjk, ski) = (self.side(pij), self.side(pjk), self.side(pki));
        let specs = vec![
            ([i, j, k], [(sij, false), (sjk, false), (ski, false)]),
            ([i, k, j], [(ski, true), (sjk, true), (sij, true)]),
        ];
        Some((specs, regions))
    }

    /// A new side with its path.
    fn side(&mut self, path: Vec<u32>) -> u32 {
        let ball = if self.prune {
            let pts: Vec<[f64; 3]> = path.iter().map(|&v| self.s.pos[v as usize]).collect();
            let (lo, hi) = crate::geom::vec::bounds(&pts);
            let c = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
            (c, reach2(self.s.pos, &path, c))
        } else {
            ([0.0; 3], f64::INFINITY)
        };
        self.sides.push(Side3 {
            path,
            split: None,
            mark: false,
            ball,
        });
        (self.sides.len() - 1) as u32
    }

    fn path(&self, (s, rev): (u32, bool)) -> Vec<u32> {
        directed(&self.sides[s as usize].path, rev)
    }

    /// Makes the node of `region` (a leaf for one triangle); `None` for a void region.
    fn make(
        &mut self,
        spec: Spec,
        region: Vec<u32>,
        level: u32,
        frontier: &mut Vec<Item>,
        old: bool,
    ) -> Option<u32> {
        if region.is_empty() {
            return None;
        }
        let id = self.nodes.len() as u32;
        if self.method == Method3::Iepf {
            self.keys.push(0.0);
        }
        if region.len() == 1 {
            let t = region[0];
            self.nodes.push(FlintNode3 {
                corners: self.s.tris[t as usize],
                sides: [(NONE, false); 3],
                stone: None,
                children: Vec::new(),
                level,
                triangle: t,
                patched: false,
                range: [0, 0],
            });
            return Some(id);
        }
        let (corners, sides) = spec;
        let paths: Vec<Vec<u32>> = sides.iter().map(|&s| self.path(s)).collect();
        let pr: Vec<&[u32]> = paths.iter().map(|p| p.as_slice()).collect();
        let verts = self.s.vertices(&region, &pr);
        let stone = Flintstone3::of(self.s.pos, corners, &verts, self.prune);
        if self.method == Method3::Iepf {
            // over the open polyhedron's own vertices, as the approximation's e1 (a path
            // may hold more where two paths run along the same edges and cancel)
            let own = self.s.vertices(&region, &[]);
            let far = super::baselines3::farthest(self.s.pos, corners, &own);
            self.keys[id as usize] = far.map_or(0.0, |f| f.1);
        }
        self.nodes.push(FlintNode3 {
            corners,
            sides,
            stone: Some(stone),
            children: Vec::new(),
            level,
            triangle: NONE,
            patched: false,
            range: [0, 0],
        });
        frontier.push(Item {
            node: id,
            region,
            old,
        });
        Some(id)
    }

    fn splittable(&self, s: u32) -> bool {
        self.sides[s as usize].path.len() >= 3
    }

    /// Alg. 7.2's first loop: mark the sides this node wants split (small angles).
    fn decide(&mut self, it: &Item) {
        let nd = &self.nodes[it.node as usize];
        let p = nd.corners.map(|v| self.s.pos[v as usize]);
        let small: Vec<bool> = (0..3)
            .map(|i| angle(p[i], p[(i + 1) % 3], p[(i + 2) % 3]) < self.min_angle)
            .collect();
        let n_small = small.iter().filter(|&&s| s).count();
        // side k joins corners k and k+1
        let want: Vec<usize> = match n_small {
            1 => {
                let i = small.iter().position(|&s| s).unwrap_or(0);
                vec![i, (i + 2) % 3]
            }
            2 => {
                let i = small.iter().position(|&s| !s).unwrap_or(0);
                // the side between the two small corners i+1 and i+2
                vec![(i + 1) % 3]
            }
            3 => vec![0, 1, 2],
            _ => vec![],
        };
        let sides = nd.sides;
        for k in want {
            let s = sides[k].0;
            if self.splittable(s) {
                self.sides[s as usize].mark = true;
            }
        }
    }

    /// Splits side `s` (once): the inner path vertex with the most equal new side lengths.
    fn ensure_split(&mut self, s: u32) -> (u32, u32, u32) {
        if let Some(x) = self.sides[s as usize].split {
            return x;
        }
        let path = self.sides[s as usize].path.clone();
        let (u, v) = (
            self.s.pos[path[0] as usize],
            self.s.pos[path[path.len() - 1] as usize],
        );
        let k = if self.method == Method3::Iepf {
            super::baselines3::path_split(self.s.pos, &path)
        } else {
            (1..path.len() - 1)
                .min_by(|&a, &b| {
                    let f = |i: usize| {
                        let x = self.s.pos[path[i] as usize];
                        (dist(u, x) - dist(x, v)).abs()
                    };
                    f(a).total_cmp(&f(b)).then(a.cmp(&b))
                })
                .unwrap_or(1)
        };
        let a = self.side(path[..=k].to_vec());
        let b = self.side(path[k..].to_vec());
        let x = (path[k], a, b);
        self.sides[s as usize].split = Some(x);
        x
    }

    /// The directed halves `(corner k → m, m → corner k+1)` of a node's side.
    fn halves(&mut self, side: (u32, bool)) -> (u32, (u32, bool), (u32, bool)) {
        let (m, a, b) = self.ensure_split(side.0);
        if side.1 {
            (m, (b, true), (a, true))
        } else {
            (m, (a, false), (b, false))
        }
    }

    /// Alg. 7.2's second loop for one node.
    fn split(&mut self, it: Item, next: &mut Vec<Item>) {
        let nd = &self.nodes[it.node as usize];
        let (corners, sides, level) = (nd.corners, nd.sides, nd.level);
        let paths: Vec<Vec<u32>> = sides.iter().map(|&s| self.path(s)).collect();
        let pr: Vec<&[u32]> = paths.iter().map(|p| p.as_slice()).collect();
        let marked = |b: &Self, k: usize| {
            let sd = &b.sides[sides[k].0 as usize];
            (sd.mark || sd.split.is_some()) && sd.path.len() >= 3
        };
        let marked: Vec<usize> = if self.method == Method3::Iepf {
            Vec::new() // the IEPF follows no neighbour's split (baselines3.rs)
        } else {
            (0..3).filter(|&k| marked(self, k)).collect()
        };
        let splittable: Vec<usize> = (0..3).filter(|&k| self.splittable(sides[k].0)).collect();
        let interior = self.s.interior(&it.region, &pr);
        // candidate splits, in order: V's choice, then the alternatives when a division fails
        // (a part would keep every triangle, or its boundary is not its paths)
        let mut tries: Vec<Split> = Vec::new();
        let mut qs: Vec<u32> = Vec::new();
        if self.method == Method3::Iepf {
            // V §6.3: 2-split at the old side, else 3-split at the vertex farthest from the
            // triangle; then the same alternatives as below
            if it.old && splittable.contains(&0) {
                tries.push(Split::Sides(vec![0]));
            }
            if let Some((q, _)) = super::baselines3::farthest(self.s.pos, corners, &interior) {
                tries.push(Split::Vertex(q));
            }
        } else if !interior.is_empty() {
            let st = Flintstone3::of(self.s.pos, corners, &interior, false);
            qs.extend(st.split());
            for d in [st.below, st.above].into_iter().flatten() {
                if !qs.contains(&d.vertex) {
                    qs.push(d.vertex);
                }
            }
            if qs.is_empty() {
                qs.push(interior[0]);
            }
        }
        if !marked.is_empty() && self.method == Method3::Flintstone {
            tries.push(Split::Sides(marked.clone()));
        }
        tries.extend(qs.iter().map(|&q| Split::Vertex(q)));
        if splittable != marked && !splittable.is_empty() {
            tries.push(Split::Sides(splittable.clone()));
        }
        for &k in &splittable {
            if marked != [k] {
                tries.push(Split::Sides(vec![k]));
            }
        }
        let mut planned = None;
        let mut by_vertex = false;
        for t in tries {
            by_vertex = matches!(t, Split::Vertex(_));
            planned = match t {
                Split::Vertex(q) => self.three_split(&it.region, corners, sides, q),
                Split::Sides(m) => match m.len() {
                    1 => self.side_split1(&it.region, corners, sides, m[0]),
                    2 => {
                        // the split sides meet at corner r (the unsplit one is r + 1)
                        let unsplit = (0..3).find(|k| !m.contains(k)).unwrap_or(1);
                        self.side_split2(&it.region, corners, sides, (unsplit + 2) % 3)
                    }
                    _ => self.side_split3(&it.region, corners, sides),
                },
            };
            if planned.is_some() {
                break;
            }
        }
        let children = match planned {
            Some((specs, regions)) => {
                let mut ch = Vec::new();
                for (spec, region) in specs.into_iter().zip(regions) {
                    if let Some(id) = self.make(spec, region, level + 1, next, by_vertex) {
                        ch.push(id);
                    }
                }
                ch
            }
            None => {
                self.nodes[it.node as usize].patched = true;
                self.patches(&it.region, level + 1, next)
            }
        };
        self.nodes[it.node as usize].children = children;
    }

    /// Divides `region` for the given children specs along the new sides' paths.
    fn plan(
        &mut self,
        region: &[u32],
        specs: Vec<Spec>,
        new_sides: &[u32],
    ) -> Option<(Vec<Spec>, Vec<Vec<u32>>)> {
        let cuts: Vec<Vec<u32>> = new_sides
            .iter()
            .map(|&s| self.sides[s as usize].path.clone())
            .collect();
        let cr: Vec<&[u32]> = cuts.iter().map(|p| p.as_slice()).collect();
        let bounds: Vec<[Vec<u32>; 3]> = specs
            .iter()
            .map(|(_, s)| [self.path(s[0]), self.path(s[1]), self.path(s[2])])
            .collect();
        let br: Vec<[&[u32]; 3]> = bounds
            .iter()
            .map(|b| [b[0].as_slice(), b[1].as_slice(), b[2].as_slice()])
            .collect();
        let regions = self.s.divide(region, &cr, &br)?;
        Some((specs, regions))
    }

    /// New sides from `src` to each target, by shortest paths inside `region`.
    fn new_sides(&mut self, region: &[u32], src: u32, targets: &[u32]) -> Option<Vec<u32>> {
        let ps = self.s.shortest_paths(region, src, targets)?;
        Some(ps.into_iter().map(|p| self.side(p)).collect())
    }

    fn three_split(
        &mut self,
        region: &[u32],
        c: [u32; 3],
        s: [(u32, bool); 3],
        q: u32,
    ) -> Option<(Vec<Spec>, Vec<Vec<u32>>)> {
        let n = self.new_sides(region, q, &c)?; // q → c_k
        let specs = vec![
            ([c[0], c[1], q], [s[0], (n[1], true), (n[0], false)]),
            ([c[1], c[2], q], [s[1], (n[2], true), (n[1], false)]),
            ([c[2], c[0], q], [s[2], (n[0], true), (n[2], false)]),
        ];
        self.plan(region, specs, &n)
    }

    /// One side (`k`) split at m: children `(c_k, m, c_{k+2})`, `(m, c_{k+1}, c_{k+2})`.
    fn side_split1(
        &mut self,
        region: &[u32],
        c: [u32; 3],
        s: [(u32, bool); 3],
        k: usize,
    ) -> Option<(Vec<Spec>, Vec<Vec<u32>>)> {
        let (c0, c1, c2) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
        let (s1, s2) = (s[(k + 1) % 3], s[(k + 2) % 3]);
        let (m, h0, h1) = self.halves(s[k]);
        let d = self.new_sides(region, m, &[c2])?[0]; // m → c2
        let specs = vec![
            ([c0, m, c2], [h0, (d, false), s2]),
            ([m, c1, c2], [h1, s1, (d, true)]),
        ];
        self.plan(region, specs, &[d])
    }

    /// Sides `r` and `r+2` (meeting at corner r) split: a corner triangle and the quadrilateral
    /// cut along its shorter diagonal.
    fn side_split2(
        &mut self,
        region: &[u32],
        c: [u32; 3],
        s: [(u32, bool); 3],
        r: usize,
    ) -> Option<(Vec<Spec>, Vec<Vec<u32>>)> {
        let (c0, c1, c2) = (c[r], c[(r + 1) % 3], c[(r + 2) % 3]);
        let s1 = s[(r + 1) % 3];
        let (m0, a0, b0) = self.halves(s[r]); // c0 → m0 → c1
        let (m2, a2, b2) = self.halves(s[(r + 2) % 3]); // c2 → m2 → c0
        let p = |v: u32| self.s.pos[v as usize];
        let diag_m0 = dist2(p(m0), p(c2)) <= dist2(p(m2), p(c1));
        if diag_m0 {
            let n = self.new_sides(region, m0, &[m2, c2])?; // m0 → m2, m0 → c2
            let (e, d) = (n[0], n[1]);
            let specs = vec![
                ([c0, m0, m2], [a0, (e, false), b2]),
                ([m0, c1, c2], [b0, s1, (d, true)]),
                ([m0, c2, m2], [(d, false), a2, (e, true)]),
            ];
            self.plan(region, specs, &[e, d])
        } else {
            let n = self.new_sides(region, m2, &[m0, c1])?; // m2 → m0, m2 → c1
            let (e, d) = (n[0], n[1]);
            let specs = vec![
                ([c0, m0, m2], [a0, (e, true), b2]),
                ([m0, c1, m2], [b0, (d, true), (e, false)]),
                ([m2, c1, c2], [(d, false), s1, a2]),
            ];
            self.plan(region, specs, &[e, d])
        }
    }

    /// All three sides split: four children (Fig. 7.10 right).
    fn side_split3(
        &mut self,
        region: &[u32],
        c: [u32; 3],
        s: [(u32, bool); 3],
    ) -> Option<(Vec<Spec>, Vec<Vec<u32>>)> {
        let (m0, a0, b0) = self.halves(s[0]); // c0 → m0 → c1
        let (m1, a1, b1) = self.halves(s[1]); // c1 → m1 → c2
        let (m2, a2, b2) = self.halves(s[2]); // c2 → m2 → c0
        let n0 = self.new_sides(region, m0, &[m1])?[0]; // m0 → m1
        let n1 = self.new_sides(region, m1, &[m2])?[0]; // m1 → m2
        let n2 = self.new_sides(region, m2, &[m0])?[0]; // m2 → m0
        let specs = vec![
            ([c[0], m0, m2], [a0, (n2, true), b2]),
            ([m0, c[1], m1], [b0, a1, (n0, true)]),
            ([m2, m1, c[2]], [(n1, true), b1, a2]),
            ([m0, m1, m2], [(n0, false), (n1, false), (n2, false)]),
        ];
        self.plan(region, specs, &[n0, n1, n2])
    }

    /// The fallback: disc patches of `region` as children (see the module doc).
    fn patches(&mut self, region: &[u32], level: u32, frontier: &mut Vec<Item>) -> Vec<u32> {
        let cap = region.len().div_ceil(2).max(1);
        let ps = disc_patches(self.s.tris, self.s.nbr, region, cap);
        let mut specs = Vec::new();
        let mut cuts = Vec::new();
        let mut ok = true;
        for p in &ps {
            if p.len() == 1 {
                let t = self.s.tris[p[0] as usize];
                // a leaf: its "paths" are its edges
                let arcs = [vec![t[0], t[1]], vec![t[1], t[2]], vec![t[2], t[0]]];
                let sd = arcs.map(|a| self.side(a));
                cuts.extend(sd);
                specs.push((t, sd.map(|x| (x, false))));
                continue;
            }
            match boundary_loop(self.s.tris, self.s.nbr, p) {
                Some(lp) => {
                    let (cs, arcs) = corners_and_arcs(&lp);
                    let sd = arcs.map(|a| self.side(a));
                    cuts.extend(sd);
                    specs.push((cs, sd.map(|x| (x, false))));
                }
                None => ok = false,
            }
        }
        let planned = if ok {
            self.plan(region, specs, &cuts)
        } else {
            None
        };
        let mut children = Vec::new();
        match planned {
            Some((specs, regions)) => {
                for (spec, r) in specs.into_iter().zip(regions) {
                    if let Some(id) = self.make(spec, r, level, frontier, false) {
                        children.push(id);
                    }
                }
            }
            None => {
                for &t in region {
                    let tr = self.s.tris[t as usize];
                    if let Some(id) =
                        self.make((tr, [(NONE, false); 3]), vec![t], level, frontier, false)
                    {
                        children.push(id);
                    }
                }
            }
        }
        children
    }
}

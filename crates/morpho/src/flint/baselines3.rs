//! The 3D iterative extreme-point fit (IEPF) of Faugeras et al. 84 (Veltkamp 1992, §6.3,
//! Fig. 6.3; reading notes A.9), built by the same machinery as the 3D flintstone tree
//! (`tree3.rs`: open polyhedra divided along shortest edge paths, `region.rs`; the disc-patch
//! fallback, `patch3.rs`) and read through the same approximation code (`approx3.rs`).
//!
//! **Construction.**
//! - *Initial triangle*: the level-0 triangle of the flintstone tree (three support vertices of
//!   the smallest enclosing ball, `tree3.rs`), so that the hierarchies start alike and compare
//!   at equal triangle counts. The closed edge path through its three vertices is the three
//!   shortest paths between them; it divides the mesh into the root's two children (the
//!   triangle in both orientations).
//! - *3-split* (odd iterations): a node is split at the vertex of its open polyhedron farthest
//!   from its (closed) triangle — the vertex that determines e1 — joined to the three corners
//!   by shortest paths inside the open polyhedron. As in the flintstone tree the vertex is
//!   chosen among the vertices *not on* the node's three paths (a path vertex is reached by a
//!   2-split instead); ties go to the first vertex found.
//! - *2-split* (the iteration after): each child of a 3-split has one *old* side (its parent's
//!   side) and is split there, at the inner vertex of the side's path farthest from the side's
//!   chord (ties: the first along the path); the vertex is stored with the side, so the
//!   triangle across the old side, split in the same iteration, splits at the same vertex
//!   and the pair of Fig. 6.3 stays without a crack. Each half is joined to the opposite
//!   corner by a shortest path. The children then 3-split again: levels alternate 3 and 2
//!   children where the text's steps apply.
//!
//! **Where the text is silent** (each forced, and documented):
//! - an old side whose path is one edge (no vertex to split at): the node 3-splits at once;
//! - no vertex off the paths: the node is side-split at every side whose path has an inner
//!   vertex (progress), as the flintstone tree does;
//! - a division that fails the check of `region.rs` (a part keeping every triangle, paths that
//!   coincide, genus > 0): the alternatives of `tree3.rs` in order (side splits), then the
//!   disc-patch fallback; void children (no triangle) are dropped. So not every level
//!   alternates, and a node split otherwise than its neighbour leaves a crack in that level's
//!   approximation (reported by the approximation, never hidden; the point queries stay exact);
//! - degenerate (collinear-corner) approximation triangles are kept in the hierarchy; their e1
//!   is the distance to the nearest corner segment (`closest_on_triangle` degrades to it) and
//!   approximations drop triangles whose corners coincide (`approx3.rs`).
//!
//! An open polyhedron of one triangle is a leaf; no vertex is created, and every input
//! triangle is exactly one leaf (tested). Each node also keeps its flintstone (so e5 of an
//! IEPF approximation is measured on the same footing) and its refinement key, e1 of the node
//! (largest distance of its vertices to its triangle): `--error ε` refines while e1 > ε (the
//! 3D Douglas–Peucker), `--count N` refines the largest e1 first. Cost: as the flintstone
//! tree's, O(N (log N)²) best, O(N² log N) worst (V §6.3).

use super::tree3::{FlintTree3, Method3};
use super::FlintError;
use crate::geom::vec::{closest_on_triangle, dist, dot, sub};
use crate::geom::Point3;
use crate::mesh::TriMesh;

/// The vertex of `verts` farthest from the closed triangle `corners` and its distance (ties:
/// the first); `None` for no vertex.
pub(crate) fn farthest(pos: &[[f64; 3]], corners: [u32; 3], verts: &[u32]) -> Option<(u32, f64)> {
    let [a, b, c] = corners.map(|v| pos[v as usize]);
    let mut best: Option<(u32, f64)> = None;
    for &v in verts {
        let x = pos[v as usize];
        let d = dist(x, closest_on_triangle(x, a, b, c));
        if best.map_or(true, |(_, bd)| d > bd) {
            best = Some((v, d));
        }
    }
    best
}

/// Distance from `x` to the closed segment `a b` (3D).
fn dist_to_segment3(a: [f64; 3], b: [f64; 3], x: [f64; 3]) -> f64 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    if l2 == 0.0 {
        return dist(a, x);
    }
    let s = (dot(sub(x, a), ab) / l2).clamp(0.0, 1.0);
    dist([a[0] + s * ab[0], a[1] + s * ab[1], a[2] + s * ab[2]], x)
}

/// The index (in `1..len−1`) of the inner vertex of `path` farthest from its chord (ties: the
/// first); `path` has at least 3 vertices.
pub(crate) fn path_split(pos: &[[f64; 3]], path: &[u32]) -> usize {
    let (u, v) = (pos[path[0] as usize], pos[path[path.len() - 1] as usize]);
    let mut best = (1, -1.0);
    for (k, &w) in path.iter().enumerate().take(path.len() - 1).skip(1) {
        let d = dist_to_segment3(u, v, pos[w as usize]);
        if d > best.1 {
            best = (k, d);
        }
    }
    best.0
}

impl FlintTree3 {
    /// The 3D iterative extreme-point fit hierarchy of a closed mesh (see the module doc of
    /// `baselines3.rs`), as a [`FlintTree3`]: same node layout, leaves, approximations and
    /// point queries (flintstone filters over the IEPF's open polyhedra); the approximations
    /// refine by e1. Same preconditions and errors as [`FlintTree3::new`].
    ///
    /// ```
    /// use morpho::flint::{FlintTree3, Target};
    /// use morpho::mesh::generate;
    /// let t = FlintTree3::iepf(&generate::icosphere(2)).unwrap();
    /// assert_eq!(t.leaf_count(), 320);
    /// assert!(t.is_iepf());
    /// let a = t.approximate(Target::Count(40)).unwrap();
    /// assert!(a.triangles.len() >= 40 && a.e2 <= a.e1);
    /// ```
    pub fn iepf(mesh: &TriMesh) -> Result<FlintTree3, FlintError> {
        Self::iepf_of(&mesh.positions, &mesh.triangles)
    }

    /// [`Self::iepf`] on positions and triangles.
    pub fn iepf_of(positions: &[Point3], triangles: &[[u32; 3]]) -> Result<FlintTree3, FlintError> {
        Self::build(
            positions,
            triangles,
            super::tree3::DEFAULT_MIN_ANGLE,
            Method3::Iepf,
        )
    }

    /// True for a tree built by [`Self::iepf`].
    pub fn is_iepf(&self) -> bool {
        !self.keys.is_empty()
    }

    /// The refinement key of node `id`: e1 of the node for the IEPF, the flintstone error
    /// otherwise (0 for leaves).
    pub fn key(&self, id: u32) -> f64 {
        match self.keys.get(id as usize) {
            Some(&k) => k,
            None => self.nodes[id as usize].error(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flint::Target;
    use crate::mesh::generate;

    fn tree_checks(t: &FlintTree3) {
        // every input triangle is exactly one leaf
        let mut seen = vec![0u32; t.triangles().len()];
        for n in &t.nodes {
            if n.is_leaf() {
                seen[n.triangle as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1), "leaves ≠ input triangles");
        // the key is e1: no vertex of a node's open polyhedron is farther from its triangle
        for (id, n) in t.nodes.iter().enumerate() {
            if n.is_leaf() {
                assert_eq!(t.key(id as u32), 0.0);
                continue;
            }
            let verts: Vec<u32> = t
                .node_triangles(id as u32)
                .iter()
                .flat_map(|&tr| t.triangles()[tr as usize])
                .collect();
            let (_, far) = farthest(t.positions(), n.corners, &verts).unwrap();
            assert_eq!(far, t.key(id as u32), "node {id}");
        }
    }

    #[test]
    fn iepf_leaves_and_keys_on_sphere_torus_cube() {
        for m in [
            generate::icosphere(3),
            generate::torus(2.0, 0.7, 24, 12),
            generate::cube(),
        ] {
            let t = FlintTree3::iepf(&m).unwrap();
            tree_checks(&t);
        }
    }

    #[test]
    fn iepf_alternates_three_and_two_splits_on_a_sphere() {
        let t = FlintTree3::iepf(&generate::icosphere(4)).unwrap();
        // the root's two halves 3-split, their children 2-split (at their old side)
        for &h in &t.root.children {
            let n = &t.nodes[h as usize];
            assert_eq!(n.children.len(), 3, "level 1 is a 3-split");
            for &c in &n.children {
                let cn = &t.nodes[c as usize];
                if !cn.is_leaf() && !cn.patched {
                    assert_eq!(cn.children.len(), 2, "level 2 is a 2-split");
                    // the split vertex lies on the old side's path (side 0)
                    let p = t.node_paths(c);
                    let m = t.nodes[cn.children[0] as usize].corners[1];
                    assert!(p[0][1..p[0].len() - 1].contains(&m));
                }
            }
        }
        let counts: Vec<usize> = (0..4)
            .map(|l| t.approximate(Target::Level(l)).unwrap().triangles.len())
            .collect();
        assert_eq!(&counts[..3], &[2, 6, 12], "{counts:?}");
    }

    #[test]
    fn iepf_approximations_bookkeeping() {
        let t = FlintTree3::iepf(&generate::icosphere(4)).unwrap();
        let mut last = usize::MAX;
        for eps in [0.0, 0.01, 0.05, 0.2, 1.0] {
            let a = t.approximate(Target::Error(eps)).unwrap();
            // every unrefined inner node has e1 within ε, and e2 ≤ e1
            assert!(
                a.e1 <= eps || (eps == 0.0 && a.e1 == 0.0),
                "{eps}: {}",
                a.e1
            );
            assert!(a.e2 <= a.e1 * (1.0 + 1e-12), "{} > {}", a.e2, a.e1);
            assert!(a.triangles.len() <= last, "counts monotone in ε");
            last = a.triangles.len();
        }
        let full = t.approximate(Target::Error(0.0)).unwrap();
        assert_eq!(full.triangles.len(), 5120);
    }
}

//! The box tree of the pair-level lens filter of [`super::beyond3`] (issue 17 item 8): a
//! kd-tree over the point indices whose walk gives `PairFilter` its order of third points
//! (neighbouring x in a row, so the blocker that rejected one is tried first on the next) and
//! skips the subtrees whose largest index is ≤ b.
//!
//! # The box verdict, measured twice and removed
//! A region test was built on it (branch `beyond6`): for a pair (a, b) and a blocker p, the
//! filter's two polynomials A(x), E(x) bounded over a node's box in ball arithmetic, so that
//! one blocker certified over a box would skip its subtree. With the pair's blockers (Delaunay
//! neighbours of a and b, the points nearest the segment's quarter points) it covered ≤ 1.5 %
//! of the nodes on the fandisk subsets and made the runs 10–40 % slower. Branch `beyond7`
//! tried it again with better-placed blockers: the four most recent points that blocked a
//! triple of the same pair (in the filter or in an exact decision — the walk's spatial order
//! makes them the likeliest to cover the next box) and, per node, the point nearest the
//! circumcentre of (a, b, box centre). On 400 fandisk points at c = −0.5 the recent blockers
//! covered 1.58·10⁵ of 4.5·10⁶ nodes (3.5 %), the per-node probes none at all (nodes of ≥ 16
//! or ≥ 64 points), and the run was 23–50 % slower (3.04 s → 3.73–4.59 s CPU). A blocker
//! covers a wedge of azimuths about the axis ab of half-angle below arctan(1/φ) (30° at
//! c = −0.5) and only the x beyond a radial bound in it; a node's box, bounded coordinate-wise,
//! spans that wedge unless it is small against its distance from the axis. The verdict code
//! (`BoxBlocker`, `BoxIv`, `PairIv` and their soundness tests) was removed; the git history
//! of this file (commit before `beyond7`) has it.

/// Most points in a leaf of [`BoxTree`].
const LEAF: usize = 8;

/// A node of [`BoxTree`]: its bounding box (exact point coordinates), the largest point index
/// below it and either two children or a range of `BoxTree::perm`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Node {
    /// the bounding box (read by the tests; the walk uses the order and `max_index`)
    #[cfg_attr(not(test), allow(dead_code))]
    pub lo: [f64; 3],
    #[cfg_attr(not(test), allow(dead_code))]
    pub hi: [f64; 3],
    pub max_index: u32,
    /// children (`kids[0] < kids[1]`), or 0 for a leaf
    pub kids: [u32; 2],
    pub start: u32,
    pub end: u32,
}

/// A kd-tree over point indices (median split on the longest side, leaves of ≤ [`LEAF`]
/// points): bounding boxes of the exact coordinates, so every point of a subtree lies in its
/// node's closed box. Node 0 is the root.
pub(crate) struct BoxTree {
    pub nodes: Vec<Node>,
    pub perm: Vec<u32>,
}

impl BoxTree {
    /// The tree over all points `p` (finite coordinates).
    pub fn new(p: &[[f64; 3]]) -> Self {
        let mut t = BoxTree {
            nodes: Vec::with_capacity(2 * p.len() / LEAF + 2),
            perm: (0..p.len() as u32).collect(),
        };
        if !p.is_empty() {
            t.build(p, 0, p.len());
        }
        t
    }

    fn build(&mut self, p: &[[f64; 3]], start: usize, end: usize) -> u32 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut max_index = 0;
        for &i in &self.perm[start..end] {
            let q = p[i as usize];
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
            max_index = max_index.max(i);
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            lo,
            hi,
            max_index,
            kids: [0, 0],
            start: start as u32,
            end: end as u32,
        });
        if end - start > LEAF {
            let ax = (0..3)
                .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
                .unwrap_or(0);
            let mid = (start + end) / 2;
            self.perm[start..end].select_nth_unstable_by(mid - start, |&x, &y| {
                p[x as usize][ax].total_cmp(&p[y as usize][ax])
            });
            let l = self.build(p, start, mid);
            let r = self.build(p, mid, end);
            self.nodes[id as usize].kids = [l, r];
        }
        id
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The tree: every point in exactly one leaf, inside the boxes of its node and all its
    /// ancestors, each node's largest index right.
    #[test]
    fn box_tree_holds_every_point_once() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for n in [0, 1, 7, 8, 9, 100, 1000] {
            let p: Vec<[f64; 3]> = (0..n)
                .map(|_| [0; 3].map(|_| (r.gen::<f64>() * 10.0).floor()))
                .collect();
            let t = BoxTree::new(&p);
            let mut seen = vec![0; n];
            fn walk(t: &BoxTree, p: &[[f64; 3]], id: u32, seen: &mut [u32]) -> u32 {
                let nd = t.nodes[id as usize];
                let mut mx = 0;
                for &i in &t.perm[nd.start as usize..nd.end as usize] {
                    let q = p[i as usize];
                    assert!((0..3).all(|k| nd.lo[k] <= q[k] && q[k] <= nd.hi[k]));
                    mx = mx.max(i);
                }
                assert_eq!(mx, nd.max_index);
                if nd.kids[0] == 0 {
                    assert!(nd.end - nd.start <= LEAF as u32);
                    for &i in &t.perm[nd.start as usize..nd.end as usize] {
                        seen[i as usize] += 1;
                    }
                } else {
                    walk(t, p, nd.kids[0], seen);
                    walk(t, p, nd.kids[1], seen);
                }
                mx
            }
            if n > 0 {
                walk(&t, &p, 0, &mut seen);
            }
            assert!(seen.iter().all(|&s| s == 1), "n = {n}");
        }
    }
}

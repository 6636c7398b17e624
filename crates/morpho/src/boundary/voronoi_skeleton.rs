//! Shortest Voronoi skeleton boundary (O'Rourke, Booth & Washington 1987, as summarised in
//! Veltkamp 1992, §4.3.4 and compared in §5.6).
//!
//! The triangles inside a simple polygon whose vertices are all the points form a tree in the
//! dual Voronoi diagram (the *Voronoi skeleton*); a natural boundary is taken to be one whose
//! skeleton is short. As V describes, the only known algorithm is trial and error: grow a tree
//! from each Voronoi vertex (Delaunay triangle) as seed and keep the shortest tree that reaches
//! every point. The growth here is Prim-like: always add the neighbouring triangle across the
//! shortest Voronoi edge (distance between the two circumcentres) whose apex vertex is not yet
//! in the region, which keeps the region a triangulated simple polygon. A growth is abandoned
//! as soon as its length exceeds the best complete tree found (this never changes the result).
//!
//! Complexity: O(N log N) per seed, O(S·N log N) for S seeds; V quotes O(N³) for all seeds.
//! `max_seeds` caps S (seeds then evenly spaced over the triangles); with S = all triangles
//! this is the full trial-and-error method.

use crate::delaunay::d2::Delaunay2;
use crate::util::NONE;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A heap entry (length, a, b) that pops the smallest length first, ties by `a`, then `b`
/// (also used by [`super::voronoi_skeleton3`]).
#[derive(Clone, Copy)]
pub(super) struct E(pub(super) f64, pub(super) u32, pub(super) u32);
impl PartialEq for E {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for E {}
impl PartialOrd for E {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for E {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0)
            .then(o.1.cmp(&self.1))
            .then(o.2.cmp(&self.2))
    }
}

/// The result of [`shortest_skeleton`].
#[derive(Debug, Clone)]
#[allow(dead_code)] // `vertices`, `seeds`: diagnostics, read by no caller yet
pub struct Skeleton {
    /// Triangles of the region (the interior triangulation).
    pub alive: Vec<bool>,
    /// Total length of the skeleton tree.
    pub length: f64,
    /// Number of region vertices (all vertices when complete).
    pub vertices: usize,
    /// Seeds tried.
    pub seeds: usize,
    /// Number of triangles added (iterations).
    pub iterations: usize,
}

/// Grows the Voronoi skeleton from up to `max_seeds` seeds and returns the shortest complete
/// one (or, when no growth reaches every vertex, the one reaching most vertices, then
/// shortest). Requires at least one triangle.
pub fn shortest_skeleton(d: &Delaunay2, max_seeds: usize) -> Skeleton {
    let nt = d.triangles.len();
    let nv = d.points.len();
    let cc: Vec<_> = (0..nt as u32).map(|t| d.circumcenter(t)).collect();
    let seeds: Vec<u32> = if nt <= max_seeds.max(1) {
        (0..nt as u32).collect()
    } else {
        let s = max_seeds.max(1);
        (0..s).map(|k| ((k * nt) / s) as u32).collect()
    };
    let mut stamp_t = vec![u32::MAX; nt];
    let mut stamp_v = vec![u32::MAX; nv];
    let mut best: Option<(usize, f64, u32)> = None; // (vertices, length, seed)
    let mut heap = BinaryHeap::new();
    let grow = |seed: u32,
                epoch: u32,
                bound: f64,
                stamp_t: &mut [u32],
                stamp_v: &mut [u32],
                heap: &mut BinaryHeap<E>|
     -> (usize, f64, usize) {
        heap.clear();
        stamp_t[seed as usize] = epoch;
        let mut count = 0;
        for &v in &d.triangles[seed as usize] {
            if stamp_v[v as usize] != epoch {
                stamp_v[v as usize] = epoch;
                count += 1;
            }
        }
        let mut len = 0.0;
        let mut iters = 0;
        let push = |heap: &mut BinaryHeap<E>, t: u32| {
            for &n in &d.neighbors[t as usize] {
                if n != NONE {
                    heap.push(E((cc[t as usize] - cc[n as usize]).norm(), t, n));
                }
            }
        };
        push(heap, seed);
        while count < nv {
            let Some(E(l, from, t)) = heap.pop() else {
                break;
            };
            if stamp_t[t as usize] == epoch {
                continue;
            }
            let Some(g) = (0..3).find(|&g| d.neighbors[t as usize][g] == from) else {
                continue;
            };
            let apex = d.triangles[t as usize][g];
            if stamp_v[apex as usize] == epoch {
                continue;
            }
            stamp_t[t as usize] = epoch;
            stamp_v[apex as usize] = epoch;
            count += 1;
            len += l;
            iters += 1;
            if len > bound {
                break;
            }
            push(heap, t);
        }
        (count, len, iters)
    };
    for (ep, &s) in seeds.iter().enumerate() {
        let bound = match best {
            Some((c, l, _)) if c == nv => l,
            _ => f64::INFINITY,
        };
        let (count, len, _) = grow(s, ep as u32, bound, &mut stamp_t, &mut stamp_v, &mut heap);
        let better = match best {
            None => true,
            Some((c, l, _)) => count > c || (count == c && len < l),
        };
        if better && (count == nv || len <= bound) {
            best = Some((count, len, s));
        }
    }
    let (_, _, seed) = best.unwrap_or((0, 0.0, 0));
    // regrow the winner with fresh stamps to read off its region
    let mut st = vec![u32::MAX; nt];
    let mut sv = vec![u32::MAX; nv];
    let (count, length, iterations) = grow(seed, 0, f64::INFINITY, &mut st, &mut sv, &mut heap);
    Skeleton {
        alive: st.iter().map(|&x| x == 0).collect(),
        length,
        vertices: count,
        seeds: seeds.len(),
        iterations,
    }
}

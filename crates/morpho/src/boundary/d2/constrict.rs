//! 2D constriction of the γ-graph (Veltkamp 1992, §5.2 Algorithm 5.1, §5.4 Hamiltonicity
//! fallback, §5.5 heap, §5.7 constrained constriction; V §4.3.3 for the minimal-area-change key).
//!
//! # Two engines
//! - [`constrict_dt`] — constriction of γ(\[-1,1\],\[0,1\]) in general position, i.e. of the
//!   Delaunay triangulation. The pruned graph is a set of live triangles; a boundary edge vᵢvⱼ
//!   of live triangle vᵢvⱼvₖ (its neighbour across vᵢvⱼ dead or absent) is *removable* iff vₖ is
//!   not yet a boundary vertex. Removing it kills the triangle, puts vₖ on the boundary and
//!   makes vᵢvₖ, vₖvⱼ boundary edges. A binary heap holds (key, triangle, edge); an entry is
//!   checked again when popped (lazy revalidation: a vertex never leaves the boundary, so an
//!   entry that became unremovable stays so and is skipped). The loop stops when every vertex is
//!   on the boundary or the heap is empty ("locked"). O(N log N) after the triangulation.
//!   Cocircular groups are handled by the triangulation's symbolic perturbation: the engine
//!   constricts that one Delaunay triangulation (a subgraph of γ(\[-1,1\],\[0,1\]); the general
//!   engine adds the other chords of the group when needed).
//! - [`General`] — constriction of an arbitrary (pruned) graph whose edges may cross, as
//!   needed for γ(\[-1,1\],\[c,1\]) with c < 0 (§5.4) and for constraints (§5.7). The boundary is an
//!   explicit vertex cycle (`next`/`prev`), triangles are implicit (edges vᵢvₖ and vⱼvₖ present,
//!   vₖ left of the counter-clockwise boundary edge vᵢ→vⱼ). Boundary edge vᵢvⱼ is removable
//!   w.r.t. vₖ iff vₖ is not on the boundary, vᵢvₖ and vⱼvₖ are live, the closed triangle
//!   contains no other vertex (otherwise the vertex would be cut off), and — constrained —
//!   neither vᵢvⱼ nor an edge crossing the triangle is a keep edge. Removal deletes vᵢvⱼ and
//!   *every edge crossing the triangle* (V §5.4); since every live edge lies in the closed
//!   region, those are exactly the live edges properly crossing vᵢvₖ or vⱼvₖ (found through a
//!   segment grid). The heap stores per boundary edge only its smallest key (§5.5); a popped
//!   entry that is no longer valid is recomputed and pushed again. When the heap runs empty, all
//!   boundary edges are re-examined once more, so "locked" really means nothing is removable.
//!
//! # Adaptive augmentation (§5.4)
//! [`General::augment`] adds the edges of γ(\[-1,1\],\[c,1\]) (from
//! [`crate::graphs::fast::beyond_dt_2d`] and the cocircular chords) that lie inside the current
//! region — both ends in it, inward at boundary ends (exact cone test), crossing no boundary
//! edge — and constriction continues from the locked state. `c = auto` tries c = −0.1, −0.2, …,
//! −1 in turn.
//!
//! # Constraints (§5.7)
//! Keep edges are added to the graph and never deleted: a boundary keep edge is never
//! removable, and a triangle crossed by a keep edge is not removed. V's rewiring for a keep edge
//! vⱼvₗ crossing vᵢvⱼvₖ is implemented: vᵢvₖ is deleted from the graph and vᵢvₗ inserted (when it
//! lies in the region and crosses no keep edge), so that vᵢvⱼvₗ becomes a boundary triangle.
//!
//! Every sidedness, crossing and containment decision uses the exact `orient2d`.

use crate::boundary::indicator::Key;
use crate::boundary::indicator::MinKey;
use crate::delaunay::d2::Delaunay2;
use crate::geom::grid::BoxGrid;
use crate::geom::intersect::segments_cross_properly;
use crate::geom::predicates::raw::orient2d;
use crate::util::NONE;
use std::collections::{BinaryHeap, HashMap, HashSet};

/// Heap entries: smallest key first, ties by the smallest item.
type Entry = MinKey<[u32; 3]>;

/// The state of a Delaunay constriction.
#[derive(Debug, Clone)]
pub struct DtState {
    /// Live triangles (the interior triangulation).
    pub alive: Vec<bool>,
    /// Vertices on the boundary.
    pub on_boundary: Vec<bool>,
    /// Number of boundary vertices.
    pub boundary_vertices: usize,
    /// Number of deletions.
    pub iterations: usize,
    /// Deleted boundary edges (vertex indices) in deletion order.
    pub deleted: Vec<[u32; 2]>,
    /// Removed triangles in removal order (replaying a prefix gives the intermediate
    /// boundaries, e.g. for pictures of the constriction steps).
    pub removed: Vec<u32>,
}

/// Constricts the Delaunay triangulation (see the module documentation). Requires a
/// triangulation with at least one triangle.
pub fn constrict_dt(d: &Delaunay2, p: &[[f64; 2]], key: Key) -> DtState {
    let nt = d.triangles.len();
    let nv = d.points.len();
    let mut st = DtState {
        alive: vec![true; nt],
        on_boundary: vec![false; nv],
        boundary_vertices: 0,
        iterations: 0,
        deleted: Vec::new(),
        removed: Vec::new(),
    };
    for &v in &d.hull {
        if !st.on_boundary[v as usize] {
            st.on_boundary[v as usize] = true;
            st.boundary_vertices += 1;
        }
    }
    let mut heap = BinaryHeap::new();
    let push = |heap: &mut BinaryHeap<Entry>, on_b: &[bool], t: usize, e: usize| {
        let tri = d.triangles[t];
        let k = tri[e];
        if on_b[k as usize] {
            return;
        }
        let (i, j) = (tri[(e + 1) % 3], tri[(e + 2) % 3]);
        heap.push(Entry {
            key: key.value(p[i as usize], p[j as usize], p[k as usize]),
            item: [t as u32, e as u32, 0],
        });
    };
    for t in 0..nt {
        for e in 0..3 {
            if d.neighbors[t][e] == NONE {
                push(&mut heap, &st.on_boundary, t, e);
            }
        }
    }
    while st.boundary_vertices < nv {
        let Some(en) = heap.pop() else { break };
        let (t, e) = (en.item[0] as usize, en.item[1] as usize);
        if !st.alive[t] {
            continue;
        }
        let tri = d.triangles[t];
        let k = tri[e] as usize;
        if st.on_boundary[k] {
            continue; // stale: vₖ joined the boundary meanwhile
        }
        // (the edge is a boundary edge: it was one when pushed and t is still alive)
        st.alive[t] = false;
        st.on_boundary[k] = true;
        st.boundary_vertices += 1;
        st.iterations += 1;
        st.deleted.push([tri[(e + 1) % 3], tri[(e + 2) % 3]]);
        st.removed.push(t as u32);
        for f in 1..3 {
            let ef = (e + f) % 3;
            let n = d.neighbors[t][ef];
            if n == NONE || !st.alive[n as usize] {
                continue;
            }
            let n = n as usize;
            if let Some(g) = (0..3).find(|&g| d.neighbors[n][g] == t as u32) {
                push(&mut heap, &st.on_boundary, n, g);
            }
        }
    }
    st
}

/// The counter-clockwise boundary cycle (vertex indices) of a set of live triangles forming a
/// triangulated disc; starts at the smallest boundary vertex.
pub fn region_cycle(d: &Delaunay2, alive: &[bool]) -> Vec<u32> {
    let mut next = vec![NONE; d.points.len()];
    let mut count = 0usize;
    for (t, tri) in d.triangles.iter().enumerate() {
        if !alive[t] {
            continue;
        }
        for e in 0..3 {
            let n = d.neighbors[t][e];
            if n == NONE || !alive[n as usize] {
                next[tri[(e + 1) % 3] as usize] = tri[(e + 2) % 3];
                count += 1;
            }
        }
    }
    let Some(start) = next.iter().position(|&w| w != NONE) else {
        return Vec::new();
    };
    let start = start as u32;
    let mut cyc = vec![start];
    let mut v = start;
    loop {
        let w = next[v as usize];
        if w == NONE || w == start || cyc.len() > count {
            break;
        }
        cyc.push(w);
        v = w;
    }
    cyc
}

pub(super) fn ekey(a: u32, b: u32) -> u64 {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    ((a as u64) << 32) | b as u64
}

/// Constriction of a general (pruned) graph; see the module documentation.
pub struct General<'a> {
    pub(super) p: &'a [[f64; 2]],
    pub(super) key: Key,
    pub(super) edges: Vec<[u32; 2]>,
    pub(super) live: Vec<bool>,
    pub(super) id: HashMap<u64, u32>,
    pub(super) adj: Vec<Vec<u32>>,
    pub(super) keep: HashSet<u64>,
    /// Boundary successor (counter-clockwise) of each vertex, `NONE` when not on the boundary.
    pub next: Vec<u32>,
    pub(super) prev: Vec<u32>,
    /// Number of boundary vertices.
    pub boundary_vertices: usize,
    /// Number of deletions.
    pub iterations: usize,
    /// Deleted edges (vertex indices).
    pub deleted: Vec<[u32; 2]>,
    pub(super) egrid: BoxGrid<2>,
    pub(super) vgrid: BoxGrid<2>,
    pub(super) heap: BinaryHeap<Entry>,
}

impl<'a> General<'a> {
    /// A graph on points `p` with boundary cycle `cycle` (counter-clockwise, simple) and the
    /// given edges (all inside the closed region bounded by the cycle; the cycle's edges must
    /// be among them). `keep` edges are never deleted.
    pub fn new(
        p: &'a [[f64; 2]],
        key: Key,
        cycle: &[u32],
        edges: impl IntoIterator<Item = [u32; 2]>,
        keep: &[[u32; 2]],
    ) -> Self {
        let n = p.len();
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for q in p {
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let area = ((hi[0] - lo[0]) * (hi[1] - lo[1])).max(0.0);
        let cell = 1.5 * (area / n.max(1) as f64).sqrt();
        let mut g = General {
            p,
            key,
            edges: Vec::new(),
            live: Vec::new(),
            id: HashMap::new(),
            adj: vec![Vec::new(); n],
            keep: keep.iter().map(|e| ekey(e[0], e[1])).collect(),
            next: vec![NONE; n],
            prev: vec![NONE; n],
            boundary_vertices: 0,
            iterations: 0,
            deleted: Vec::new(),
            egrid: BoxGrid::fitted(lo, hi, cell, 2 * n + 16, true),
            vgrid: BoxGrid::fitted(lo, hi, cell, 2 * n + 16, false),
            heap: BinaryHeap::new(),
        };
        for (v, q) in p.iter().enumerate() {
            g.vgrid.insert(v as u32, *q, *q);
        }
        for e in edges {
            g.add_edge(e[0], e[1]);
        }
        for e in keep {
            g.add_edge(e[0], e[1]);
        }
        let m = cycle.len();
        for k in 0..m {
            let (a, b) = (cycle[k], cycle[(k + 1) % m]);
            g.add_edge(a, b);
            g.next[a as usize] = b;
            g.prev[b as usize] = a;
        }
        g.boundary_vertices = m;
        g.push_all();
        g
    }

    pub(super) fn add_edge(&mut self, a: u32, b: u32) {
        if a == b {
            return;
        }
        let k = ekey(a, b);
        if let Some(&i) = self.id.get(&k) {
            if !self.live[i as usize] {
                self.live[i as usize] = true;
                self.adj[a as usize].push(b);
                self.adj[b as usize].push(a);
            }
            return;
        }
        let i = self.edges.len() as u32;
        self.edges.push([a, b]);
        self.live.push(true);
        self.id.insert(k, i);
        self.adj[a as usize].push(b);
        self.adj[b as usize].push(a);
        let (pa, pb) = (self.p[a as usize], self.p[b as usize]);
        self.egrid.insert(
            i,
            [pa[0].min(pb[0]), pa[1].min(pb[1])],
            [pa[0].max(pb[0]), pa[1].max(pb[1])],
        );
    }

    pub(super) fn kill(&mut self, i: u32) {
        let i = i as usize;
        if !self.live[i] {
            return;
        }
        self.live[i] = false;
        let [a, b] = self.edges[i];
        self.adj[a as usize].retain(|&x| x != b);
        self.adj[b as usize].retain(|&x| x != a);
        self.deleted.push([a, b]);
    }

    /// True when edge ab is live.
    pub fn has(&self, a: u32, b: u32) -> bool {
        self.id
            .get(&ekey(a, b))
            .is_some_and(|&i| self.live[i as usize])
    }

    fn tri_box(&self, i: u32, j: u32, k: u32) -> ([f64; 2], [f64; 2]) {
        let (a, b, c) = (self.p[i as usize], self.p[j as usize], self.p[k as usize]);
        (
            [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1])],
            [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1])],
        )
    }

    /// Live edges properly crossing vᵢvₖ or vⱼvₖ (= crossing the open triangle).
    fn crossing(&self, i: u32, j: u32, k: u32) -> Vec<u32> {
        let (lo, hi) = self.tri_box(i, j, k);
        let (pi, pj, pk) = (self.p[i as usize], self.p[j as usize], self.p[k as usize]);
        let mut out = Vec::new();
        self.egrid.for_each(lo, hi, |e| {
            if !self.live[e as usize] {
                return;
            }
            let [a, b] = self.edges[e as usize];
            let (pa, pb) = (self.p[a as usize], self.p[b as usize]);
            if segments_cross_properly(pa, pb, pi, pk) || segments_cross_properly(pa, pb, pj, pk) {
                out.push(e);
            }
        });
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The closed triangle vᵢvⱼvₖ (counter-clockwise) contains no vertex but its corners.
    fn empty(&self, i: u32, j: u32, k: u32) -> bool {
        let (lo, hi) = self.tri_box(i, j, k);
        let (pi, pj, pk) = (self.p[i as usize], self.p[j as usize], self.p[k as usize]);
        let mut ok = true;
        self.vgrid.for_each(lo, hi, |v| {
            if !ok || v == i || v == j || v == k {
                return;
            }
            let q = self.p[v as usize];
            if orient2d(pi, pj, q) >= 0.0
                && orient2d(pj, pk, q) >= 0.0
                && orient2d(pk, pi, q) >= 0.0
            {
                ok = false;
            }
        });
        ok
    }

    /// Why boundary edge i→j cannot be removed w.r.t. k, or `None` when it can.
    fn check(&self, i: u32, j: u32, k: u32) -> Option<Blocked> {
        if self.next[k as usize] != NONE
            || !self.has(i, k)
            || !self.has(j, k)
            || self.keep.contains(&ekey(i, j))
            || orient2d(self.p[i as usize], self.p[j as usize], self.p[k as usize]) <= 0.0
            || !self.empty(i, j, k)
        {
            return Some(Blocked::Other);
        }
        if !self.keep.is_empty() {
            for e in self.crossing(i, j, k) {
                let [a, b] = self.edges[e as usize];
                if self.keep.contains(&ekey(a, b)) {
                    return Some(Blocked::Keep(a, b));
                }
            }
        }
        None
    }

    /// Smallest-key removal of boundary edge i→j, applying V's rewiring (§5.7) for keep edges
    /// that block a candidate.
    fn best(&mut self, i: u32, j: u32) -> Option<(f64, u32)> {
        if self.keep.contains(&ekey(i, j)) {
            return None;
        }
        let mut rounds = 0;
        loop {
            let mut cand: Vec<(f64, u32)> = self.adj[i as usize]
                .iter()
                .copied()
                .filter(|&k| {
                    self.next[k as usize] == NONE
                        && self.has(j, k)
                        && orient2d(self.p[i as usize], self.p[j as usize], self.p[k as usize])
                            > 0.0
                })
                .map(|k| {
                    (
                        self.key
                            .value(self.p[i as usize], self.p[j as usize], self.p[k as usize]),
                        k,
                    )
                })
                .collect();
            cand.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut rewired = false;
            for (key, k) in cand {
                match self.check(i, j, k) {
                    None => return Some((key, k)),
                    Some(Blocked::Keep(a, b)) if rounds < 8 => {
                        // keep edge from i or j through the triangle: V §5.7 rewiring
                        if self.rewire(i, j, k, [a, b]) {
                            rewired = true;
                            break;
                        }
                    }
                    Some(_) => {}
                }
            }
            if !rewired {
                return None;
            }
            rounds += 1;
        }
    }

    pub(super) fn push(&mut self, i: u32, j: u32) -> bool {
        if let Some((key, k)) = self.best(i, j) {
            self.heap.push(Entry {
                key,
                item: [i, j, k],
            });
            true
        } else {
            false
        }
    }

    pub(super) fn push_all(&mut self) -> bool {
        let mut any = false;
        for v in 0..self.next.len() as u32 {
            let w = self.next[v as usize];
            if w != NONE {
                any |= self.push(v, w);
            }
        }
        any
    }

    /// Runs the constriction until every vertex is on the boundary or nothing is removable.
    pub fn run(&mut self) {
        let n = self.p.len();
        loop {
            while self.boundary_vertices < n {
                let Some(en) = self.heap.pop() else { break };
                let [i, j, k] = en.item;
                if self.next[i as usize] != j {
                    continue; // no longer a boundary edge
                }
                if self.check(i, j, k).is_some() {
                    self.push(i, j);
                    continue;
                }
                self.remove(i, j, k);
            }
            if self.boundary_vertices >= n || !self.push_all() {
                break;
            }
        }
    }

    fn remove(&mut self, i: u32, j: u32, k: u32) {
        let cross = self.crossing(i, j, k);
        if let Some(&e) = self.id.get(&ekey(i, j)) {
            self.kill(e);
        }
        for e in cross {
            self.kill(e);
        }
        self.next[i as usize] = k;
        self.prev[k as usize] = i;
        self.next[k as usize] = j;
        self.prev[j as usize] = k;
        self.boundary_vertices += 1;
        self.iterations += 1;
        self.push(i, k);
        self.push(k, j);
    }

    /// The boundary cycle (counter-clockwise) starting at the smallest boundary vertex.
    pub fn cycle(&self) -> Vec<u32> {
        let Some(start) = (0..self.next.len()).find(|&v| self.next[v] != NONE) else {
            return Vec::new();
        };
        let mut cyc = vec![start as u32];
        let mut v = self.next[start];
        while v as usize != start && cyc.len() <= self.next.len() {
            cyc.push(v);
            v = self.next[v as usize];
        }
        cyc
    }

    /// Is vertex v on the boundary?
    pub fn on_boundary(&self, v: u32) -> bool {
        self.next[v as usize] != NONE
    }
}

pub(super) enum Blocked {
    Keep(u32, u32),
    Other,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every edge is found by a query of its own box, whatever the direction of its
    /// coordinates (the grid takes boxes, not endpoints: an edge going down or left once
    /// registered in no cell).
    #[test]
    fn every_edge_is_in_the_grid_cells_of_its_box() {
        let p = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.4]];
        let edges = [[1, 3], [4, 0], [4, 1], [3, 4]];
        let g = General::new(&p, Key::Gamma, &[0, 1, 2, 3], edges, &[]);
        assert_eq!(g.edges.len(), 8);
        for (i, &[a, b]) in g.edges.iter().enumerate() {
            let (pa, pb) = (p[a as usize], p[b as usize]);
            let mut found = false;
            g.egrid.for_each(
                [pa[0].min(pb[0]), pa[1].min(pb[1])],
                [pa[0].max(pb[0]), pa[1].max(pb[1])],
                |e| found |= e == i as u32,
            );
            assert!(found, "edge {i} = {a}-{b} not in the grid");
        }
    }
}

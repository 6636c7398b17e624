//! Open polyhedra as sets of triangles of a closed mesh: shortest edge paths inside one
//! (Dijkstra with Euclidean edge lengths, V §7.3.2, Thm 7.3's Θ(n log n) per path), and the
//! division of one along new paths into the parts of the new approximation triangles
//! (Alg. 7.2, "divide P accordingly"; reading notes A.7).
//!
//! **Division.** The triangles of P are grouped into the components that remain connected
//! across edges that are neither on a new path nor on P's boundary. Each component goes to the
//! child whose directed boundary (its three paths, corner to corner, in the direction of the
//! child's counter-clockwise corners) holds a directed edge of one of the component's
//! triangles: on an outward-oriented surface a part lies left of its boundary. A child that
//! gets no triangle is *void* (V's table after Fig. 7.12) and is dropped.
//!
//! **The check that makes the tree safe.** Every non-void child must satisfy
//! `∂(its triangles) = its three paths (mod 2)`: then the triangle of its corners plus the
//! fills of its paths (see `query3.rs`) differ from its triangles by a closed surface, which is
//! what Lemma 6.1 needs. Where paths coincide, wind around a handle (genus > 0) or do not
//! separate P, the check fails and the caller falls back (`patch3.rs`); every child must also
//! have fewer triangles than P, so the construction always ends.
//! Cost: O(n log n) per path search and O(n) per division for P of n triangles.

use crate::util::{IdMap, IdSet, NONE};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// The closed mesh the regions live in, with its neighbour table and scratch stamps.
pub(crate) struct Surface<'a> {
    pub pos: &'a [[f64; 3]],
    pub tris: &'a [[u32; 3]],
    /// `nbr[t][i]`: the triangle across edge (v_i, v_{i+1}) of t.
    pub nbr: &'a [[u32; 3]],
    vstamp: Vec<u32>,
    vloc: Vec<u32>,
    tstamp: Vec<u32>,
    towner: Vec<u32>,
    stamp: u32,
    /// Triangles around each vertex (CSR over the whole mesh): `fan[fan_start[v]..fan_start[v+1]]`.
    fan_start: Vec<u32>,
    fan: Vec<u32>,
    /// Per triangle-edge slot `3t + i`: the smaller slot of the edge's two slots (its own when
    /// the neighbour is missing) — one id per undirected edge of a 2-manifold.
    canon: Vec<u32>,
    /// Dijkstra scratch by input vertex, valid where `dstamp == stamp` (no per-call clearing).
    dist: Vec<f64>,
    pred: Vec<u32>,
    dstamp: Vec<u32>,
    /// Dijkstra's settled vertices and targets (`== stamp`).
    done: Vec<u32>,
    want: Vec<u32>,
    heap: BinaryHeap<Key>,
    /// Division scratch per slot: the cut mark, the directed owner (`eown`, valid where
    /// `eown_stamp == stamp`) and the mod-2 boundary parity (`odd == pstamp`).
    ecut: Vec<u32>,
    eown: Vec<u32>,
    eown_stamp: Vec<u32>,
    odd: Vec<u32>,
    pstamp: u32,
}

/// Undirected key of an edge.
#[inline]
pub(crate) fn ukey(a: u32, b: u32) -> u64 {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    (u64::from(a) << 32) | u64::from(b)
}

/// Directed key of an edge.
#[inline]
fn dkey(a: u32, b: u32) -> u64 {
    (u64::from(a) << 32) | u64::from(b)
}

#[derive(PartialEq)]
struct Key(f64, u32);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Key {
    fn cmp(&self, o: &Self) -> Ordering {
        // min-heap on distance, then vertex
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

impl<'a> Surface<'a> {
    pub fn new(pos: &'a [[f64; 3]], tris: &'a [[u32; 3]], nbr: &'a [[u32; 3]]) -> Self {
        let nv = pos.len();
        let mut fan_start = vec![0u32; nv + 1];
        for tr in tris {
            for &v in tr {
                fan_start[v as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            fan_start[i + 1] += fan_start[i];
        }
        let mut fill = fan_start.clone();
        let mut fan = vec![0u32; fan_start[nv] as usize];
        for (t, tr) in tris.iter().enumerate() {
            for &v in tr {
                fan[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
        let mut canon: Vec<u32> = (0..3 * tris.len() as u32).collect();
        for (t, tr) in tris.iter().enumerate() {
            for i in 0..3 {
                let n = nbr[t][i];
                if n == NONE {
                    continue;
                }
                let (a, b) = (tr[i], tr[(i + 1) % 3]);
                let tn = tris[n as usize];
                if let Some(j) = (0..3).find(|&j| {
                    let (c, d) = (tn[j], tn[(j + 1) % 3]);
                    (c == b && d == a) || (c == a && d == b)
                }) {
                    let (me, other) = (3 * t as u32 + i as u32, 3 * n + j as u32);
                    canon[me as usize] = me.min(other);
                }
            }
        }
        let ns = 3 * tris.len();
        Surface {
            pos,
            tris,
            nbr,
            vstamp: vec![0; nv],
            vloc: vec![0; nv],
            tstamp: vec![0; tris.len()],
            towner: vec![0; tris.len()],
            stamp: 0,
            fan_start,
            fan,
            canon,
            dist: vec![0.0; nv],
            pred: vec![NONE; nv],
            dstamp: vec![0; nv],
            done: vec![0; nv],
            want: vec![0; nv],
            heap: BinaryHeap::new(),
            ecut: vec![0; ns],
            eown: vec![0; ns],
            eown_stamp: vec![0; ns],
            odd: vec![0; ns],
            pstamp: 0,
        }
    }

    fn next_stamp(&mut self) -> u32 {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            for a in [
                &mut self.vstamp,
                &mut self.tstamp,
                &mut self.dstamp,
                &mut self.done,
                &mut self.want,
                &mut self.ecut,
                &mut self.eown_stamp,
            ] {
                a.iter_mut().for_each(|s| *s = 0);
            }
            self.stamp = 1;
        }
        self.stamp
    }

    fn next_pstamp(&mut self) -> u32 {
        self.pstamp = self.pstamp.wrapping_add(1);
        if self.pstamp == 0 {
            self.odd.iter_mut().for_each(|s| *s = 0);
            self.pstamp = 1;
        }
        self.pstamp
    }

    /// The slot `3t + i` of a triangle whose edge `i` runs from `a` to `b` (directed), if any.
    fn directed_slot(&self, a: u32, b: u32) -> Option<u32> {
        let (lo, hi) = (self.fan_start[a as usize], self.fan_start[a as usize + 1]);
        for &t in &self.fan[lo as usize..hi as usize] {
            let tr = self.tris[t as usize];
            for i in 0..3 {
                if tr[i] == a && tr[(i + 1) % 3] == b {
                    return Some(3 * t + i as u32);
                }
            }
        }
        None
    }

    /// The canonical slot of the undirected edge `{a, b}` (see `canon`), if it is a mesh edge.
    fn edge_id(&self, a: u32, b: u32) -> Option<u32> {
        self.directed_slot(a, b)
            .or_else(|| self.directed_slot(b, a))
            .map(|s| self.canon[s as usize])
    }

    /// The distinct vertices of `region`'s triangles and of `extra` (first-seen order).
    pub fn vertices(&mut self, region: &[u32], extra: &[&[u32]]) -> Vec<u32> {
        let s = self.next_stamp();
        let mut out = Vec::new();
        let tris = self.tris;
        let all = region
            .iter()
            .flat_map(|&t| tris[t as usize])
            .chain(extra.iter().flat_map(|p| p.iter().copied()));
        for v in all {
            if self.vstamp[v as usize] != s {
                self.vstamp[v as usize] = s;
                out.push(v);
            }
        }
        out
    }

    /// Vertices of `region` on none of `paths`.
    pub fn interior(&mut self, region: &[u32], paths: &[&[u32]]) -> Vec<u32> {
        let s = self.next_stamp();
        for p in paths {
            for &v in p.iter() {
                self.vstamp[v as usize] = s;
            }
        }
        let mut out = Vec::new();
        for &t in region {
            for v in self.tris[t as usize] {
                if self.vstamp[v as usize] != s {
                    self.vstamp[v as usize] = s;
                    out.push(v);
                }
            }
        }
        out
    }

    /// Shortest edge paths inside `region` from `src` to each of `targets` (vertex lists from
    /// `src` to the target); `None` if one is unreachable.
    ///
    /// Dijkstra over the edges of `region`'s triangles, found through the mesh's vertex fans
    /// (a triangle counts iff it is in `region`), with scratch arrays kept between calls and
    /// validated by a stamp: the cost is one pass over `region` (its vertices' first-seen order,
    /// the heap's tie-break) plus the explored part, not a fresh adjacency per call. Same result
    /// as [`Self::shortest_paths_reference`] (the per-call CSR version it replaces): each vertex
    /// sees the same neighbour multiset, relaxation is order-free (strict `<`), and the heap
    /// pops by (distance, first-seen index), a total order.
    pub fn shortest_paths(
        &mut self,
        region: &[u32],
        src: u32,
        targets: &[u32],
    ) -> Option<Vec<Vec<u32>>> {
        let s = self.next_stamp();
        let tris = self.tris;
        let mut verts = Vec::new();
        for &t in region {
            self.tstamp[t as usize] = s;
            for v in tris[t as usize] {
                if self.vstamp[v as usize] != s {
                    self.vstamp[v as usize] = s;
                    self.vloc[v as usize] = verts.len() as u32;
                    verts.push(v);
                }
            }
        }
        if self.vstamp[src as usize] != s || targets.iter().any(|&t| self.vstamp[t as usize] != s) {
            return None;
        }
        let mut left = targets.len();
        for &t in targets {
            if self.want[t as usize] != s {
                self.want[t as usize] = s;
            } else {
                left -= 1;
            }
        }
        let mut heap = std::mem::take(&mut self.heap);
        heap.clear();
        self.dist[src as usize] = 0.0;
        self.pred[src as usize] = NONE;
        self.dstamp[src as usize] = s;
        heap.push(Key(0.0, self.vloc[src as usize]));
        while let Some(Key(d, lu)) = heap.pop() {
            let u = verts[lu as usize];
            if self.done[u as usize] == s {
                continue;
            }
            self.done[u as usize] = s;
            if self.want[u as usize] == s {
                left -= 1;
                if left == 0 {
                    break;
                }
            }
            let pu = self.pos[u as usize];
            let (lo, hi) = (self.fan_start[u as usize], self.fan_start[u as usize + 1]);
            for &t in &self.fan[lo as usize..hi as usize] {
                if self.tstamp[t as usize] != s {
                    continue;
                }
                for w in tris[t as usize] {
                    if w == u || self.done[w as usize] == s {
                        continue;
                    }
                    let nd = d + crate::geom::vec::dist(pu, self.pos[w as usize]);
                    let wi = w as usize;
                    let cur = if self.dstamp[wi] == s {
                        self.dist[wi]
                    } else {
                        f64::INFINITY
                    };
                    if nd < cur {
                        self.dstamp[wi] = s;
                        self.dist[wi] = nd;
                        self.pred[wi] = u;
                        heap.push(Key(nd, self.vloc[wi]));
                    }
                }
            }
        }
        self.heap = heap;
        targets
            .iter()
            .map(|&t| {
                if self.done[t as usize] != s {
                    return None;
                }
                let mut p = vec![t];
                let mut u = t;
                while u != src {
                    u = self.pred[u as usize];
                    p.push(u);
                }
                p.reverse();
                Some(p)
            })
            .collect()
    }

    #[cfg(test)]
    /// The per-call CSR version of [`Self::shortest_paths`], kept as its test oracle.
    pub fn shortest_paths_reference(
        &mut self,
        region: &[u32],
        src: u32,
        targets: &[u32],
    ) -> Option<Vec<Vec<u32>>> {
        let verts = self.vertices(region, &[]);
        for (i, &v) in verts.iter().enumerate() {
            self.vloc[v as usize] = i as u32;
        }
        let s = self.stamp;
        let n = verts.len();
        let loc = |v: u32, me: &Self| -> Option<usize> {
            (me.vstamp[v as usize] == s).then(|| me.vloc[v as usize] as usize)
        };
        // CSR adjacency from the triangles' edges (both directions; repeats are harmless)
        let mut deg = vec![0u32; n + 1];
        for &t in region {
            let tr = self.tris[t as usize];
            for k in 0..3 {
                deg[self.vloc[tr[k] as usize] as usize] += 2;
            }
        }
        let mut start = vec![0u32; n + 1];
        for i in 0..n {
            start[i + 1] = start[i] + deg[i];
        }
        let mut fill = start.clone();
        let mut adj = vec![0u32; start[n] as usize];
        for &t in region {
            let tr = self.tris[t as usize];
            for k in 0..3 {
                let (a, b) = (tr[k], tr[(k + 1) % 3]);
                let (la, lb) = (self.vloc[a as usize], self.vloc[b as usize]);
                adj[fill[la as usize] as usize] = lb;
                fill[la as usize] += 1;
                adj[fill[lb as usize] as usize] = la;
                fill[lb as usize] += 1;
            }
        }
        let ls = loc(src, self)?;
        let lt: Vec<usize> = targets
            .iter()
            .map(|&t| loc(t, self))
            .collect::<Option<_>>()?;
        let mut dist = vec![f64::INFINITY; n];
        let mut pred = vec![NONE; n];
        let mut done = vec![false; n];
        let mut left = lt.len();
        let mut want = vec![false; n];
        for &t in &lt {
            if !want[t] {
                want[t] = true;
            } else {
                left -= 1;
            }
        }
        dist[ls] = 0.0;
        let mut heap = BinaryHeap::new();
        heap.push(Key(0.0, ls as u32));
        while let Some(Key(d, u)) = heap.pop() {
            let u = u as usize;
            if done[u] {
                continue;
            }
            done[u] = true;
            if want[u] {
                left -= 1;
                if left == 0 {
                    break;
                }
            }
            let pu = self.pos[verts[u] as usize];
            for &w in &adj[start[u] as usize..start[u + 1] as usize] {
                let w = w as usize;
                if done[w] {
                    continue;
                }
                let nd = d + crate::geom::vec::dist(pu, self.pos[verts[w] as usize]);
                if nd < dist[w] {
                    dist[w] = nd;
                    pred[w] = u as u32;
                    heap.push(Key(nd, w as u32));
                }
            }
        }
        lt.iter()
            .map(|&t| {
                if !done[t] {
                    return None;
                }
                let mut p = vec![verts[t]];
                let mut u = t;
                while u != ls {
                    u = pred[u] as usize;
                    p.push(verts[u]);
                }
                p.reverse();
                Some(p)
            })
            .collect()
    }

    /// Divides `region` along `cuts` among `children` (each: its three directed boundary
    /// paths). Returns each child's triangles (empty = void), or `None` when a component has no
    /// owner, a non-void child's boundary differs from its paths mod 2, or a child would keep
    /// all of `region`.
    ///
    /// Edges are named by their triangle slots (`canon`, and the slot of a directed edge on an
    /// oriented 2-manifold) instead of hashed vertex pairs: the same components, owners and
    /// parities as [`Self::divide_hashed`], which it falls back to when a path edge is not a
    /// mesh edge (never from the builder: its paths are edge paths).
    pub fn divide(
        &mut self,
        region: &[u32],
        cuts: &[&[u32]],
        children: &[[&[u32]; 3]],
    ) -> Option<Vec<Vec<u32>>> {
        let mut child_edges: Vec<Vec<u32>> = Vec::with_capacity(children.len());
        for paths in children {
            let mut ids = Vec::new();
            for p in paths {
                for w in p.windows(2) {
                    match self.edge_id(w[0], w[1]) {
                        Some(e) => ids.push(e),
                        None => return self.divide_hashed(region, cuts, children),
                    }
                }
            }
            child_edges.push(ids);
        }
        let mut cut_ids = Vec::new();
        for p in cuts {
            for w in p.windows(2) {
                match self.edge_id(w[0], w[1]) {
                    Some(e) => cut_ids.push(e),
                    None => return self.divide_hashed(region, cuts, children),
                }
            }
        }
        let s = self.next_stamp();
        for &t in region {
            self.tstamp[t as usize] = s;
        }
        for &e in &cut_ids {
            self.ecut[e as usize] = s;
        }
        for (k, paths) in children.iter().enumerate() {
            for p in paths {
                for w in p.windows(2) {
                    if let Some(e) = self.directed_slot(w[0], w[1]) {
                        let e = e as usize;
                        if self.eown_stamp[e] != s {
                            self.eown_stamp[e] = s;
                            self.eown[e] = k as u32;
                        } else if self.eown[e] != k as u32 {
                            self.eown[e] = NONE;
                        }
                    }
                }
            }
        }
        let mut parts: Vec<Vec<u32>> = vec![Vec::new(); children.len()];
        for &t in region {
            self.towner[t as usize] = NONE - 1;
        }
        let mut comp: Vec<u32> = Vec::new();
        for &seed in region {
            if self.towner[seed as usize] != NONE - 1 {
                continue;
            }
            comp.clear();
            comp.push(seed);
            self.towner[seed as usize] = NONE - 2;
            let mut i = 0;
            let mut owner = NONE;
            while i < comp.len() {
                let t = comp[i] as usize;
                i += 1;
                for k in 0..3 {
                    let slot = 3 * t + k;
                    if owner == NONE && self.eown_stamp[slot] == s && self.eown[slot] != NONE {
                        owner = self.eown[slot];
                    }
                    let n = self.nbr[t][k];
                    if n == NONE
                        || self.tstamp[n as usize] != s
                        || self.towner[n as usize] != NONE - 1
                        || self.ecut[self.canon[slot] as usize] == s
                    {
                        continue;
                    }
                    self.towner[n as usize] = NONE - 2;
                    comp.push(n);
                }
            }
            if owner == NONE {
                return None;
            }
            for &t in &comp {
                self.towner[t as usize] = owner;
            }
            parts[owner as usize].extend_from_slice(&comp);
        }
        for (k, part) in parts.iter().enumerate() {
            if part.is_empty() {
                continue;
            }
            if part.len() >= region.len() {
                return None;
            }
            let ps = self.next_pstamp();
            let mut odd = 0usize;
            let mut toggle = |odd_slots: &mut [u32], e: u32| {
                let o = &mut odd_slots[e as usize];
                if *o == ps {
                    *o = 0;
                    odd -= 1;
                } else {
                    *o = ps;
                    odd += 1;
                }
            };
            for &e in &child_edges[k] {
                toggle(&mut self.odd, e);
            }
            for &t in part {
                for i in 0..3 {
                    let n = self.nbr[t as usize][i];
                    if n == NONE
                        || self.tstamp[n as usize] != s
                        || self.towner[n as usize] != k as u32
                    {
                        toggle(&mut self.odd, self.canon[3 * t as usize + i]);
                    }
                }
            }
            if odd != 0 {
                return None;
            }
        }
        Some(parts)
    }

    /// [`Self::divide`] with edges as hashed vertex pairs (any paths, also non-mesh edges).
    pub fn divide_hashed(
        &mut self,
        region: &[u32],
        cuts: &[&[u32]],
        children: &[[&[u32]; 3]],
    ) -> Option<Vec<Vec<u32>>> {
        let s = self.next_stamp();
        for &t in region {
            self.tstamp[t as usize] = s;
        }
        let mut cut: IdSet<u64> = IdSet::default();
        for p in cuts {
            for w in p.windows(2) {
                cut.insert(ukey(w[0], w[1]));
            }
        }
        let mut owner_of: IdMap<u64, u32> = IdMap::default();
        for (k, paths) in children.iter().enumerate() {
            for p in paths {
                for w in p.windows(2) {
                    let e = owner_of.entry(dkey(w[0], w[1])).or_insert(k as u32);
                    if *e != k as u32 {
                        *e = NONE;
                    }
                }
            }
        }
        let mut parts: Vec<Vec<u32>> = vec![Vec::new(); children.len()];
        // components; towner = NONE while unvisited
        for &t in region {
            self.towner[t as usize] = NONE - 1;
        }
        let mut comp: Vec<u32> = Vec::new();
        for &seed in region {
            if self.towner[seed as usize] != NONE - 1 {
                continue;
            }
            comp.clear();
            comp.push(seed);
            self.towner[seed as usize] = NONE - 2;
            let mut i = 0;
            let mut owner = NONE;
            while i < comp.len() {
                let t = comp[i] as usize;
                i += 1;
                let tr = self.tris[t];
                for k in 0..3 {
                    let (a, b) = (tr[k], tr[(k + 1) % 3]);
                    if owner == NONE {
                        if let Some(&o) = owner_of.get(&dkey(a, b)) {
                            if o != NONE {
                                owner = o;
                            }
                        }
                    }
                    let n = self.nbr[t][k];
                    if n == NONE
                        || self.tstamp[n as usize] != s
                        || self.towner[n as usize] != NONE - 1
                        || cut.contains(&ukey(a, b))
                    {
                        continue;
                    }
                    self.towner[n as usize] = NONE - 2;
                    comp.push(n);
                }
            }
            if owner == NONE {
                return None;
            }
            for &t in &comp {
                self.towner[t as usize] = owner;
            }
            parts[owner as usize].extend_from_slice(&comp);
        }
        for (k, part) in parts.iter().enumerate() {
            if part.is_empty() {
                continue;
            }
            if part.len() >= region.len() {
                return None;
            }
            let mut odd: IdSet<u64> = IdSet::default();
            let mut toggle = |e: u64| {
                if !odd.remove(&e) {
                    odd.insert(e);
                }
            };
            for p in &children[k] {
                for w in p.windows(2) {
                    toggle(ukey(w[0], w[1]));
                }
            }
            for &t in part {
                let tr = self.tris[t as usize];
                for i in 0..3 {
                    let n = self.nbr[t as usize][i];
                    if n == NONE
                        || self.tstamp[n as usize] != s
                        || self.towner[n as usize] != k as u32
                    {
                        toggle(ukey(tr[i], tr[(i + 1) % 3]));
                    }
                }
            }
            if !odd.is_empty() {
                return None;
            }
        }
        Some(parts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{analyze_topology, generate, TriMesh};
    use crate::util::Rng;

    /// Closed test meshes: regular ones (many exactly equal edge lengths, so the heap's
    /// tie-break decides paths) and a jittered one.
    fn meshes() -> Vec<TriMesh> {
        let mut r = Rng::new(5);
        let mut jit = generate::icosphere(3);
        for p in &mut jit.positions {
            p.x += 0.01 * r.unit();
            p.y += 0.01 * r.unit();
        }
        vec![
            generate::icosphere(3),
            generate::torus(2.0, 0.5, 24, 12),
            generate::uv_sphere(crate::geom::Point3::new(0.0, 0.0, 0.0), 1.0, 12, 16),
            jit,
        ]
    }

    /// A connected region of about `size` triangles grown from `seed` by breadth-first search.
    fn grow(tris: usize, nbr: &[[u32; 3]], seed: u32, size: usize) -> Vec<u32> {
        let mut seen = vec![false; tris];
        let mut out = vec![seed];
        seen[seed as usize] = true;
        let mut i = 0;
        while i < out.len() && out.len() < size {
            for n in nbr[out[i] as usize] {
                if n != NONE && !seen[n as usize] && out.len() < size {
                    seen[n as usize] = true;
                    out.push(n);
                }
            }
            i += 1;
        }
        out
    }

    /// Lockstep with the per-call CSR Dijkstra: the same paths (or `None`), including on
    /// regular meshes where exact distance ties occur, with the scratch reused across calls
    /// and sometimes a source or target outside the region.
    #[test]
    fn shortest_paths_equal_the_per_call_csr_version() {
        let mut r = Rng::new(18);
        let mut found = 0;
        for m in meshes() {
            let topo = analyze_topology(&m);
            let pos: Vec<[f64; 3]> = m.positions.iter().map(|p| [p.x, p.y, p.z]).collect();
            let nt = m.triangles.len();
            let mut s = Surface::new(&pos, &m.triangles, &topo.neighbors);
            for round in 0..150 {
                let size = if round % 10 == 0 {
                    nt
                } else {
                    2 + r.below(nt as u64) as usize
                };
                let region = grow(nt, &topo.neighbors, r.below(nt as u64) as u32, size);
                let vs: Vec<u32> = region
                    .iter()
                    .flat_map(|&t| m.triangles[t as usize])
                    .collect();
                let mut pick = || {
                    if r.below(20) == 0 {
                        r.below(pos.len() as u64) as u32
                    } else {
                        vs[r.below(vs.len() as u64) as usize]
                    }
                };
                let src = pick();
                let targets: Vec<u32> = (0..1 + round % 3).map(|_| pick()).collect();
                let a = s.shortest_paths(&region, src, &targets);
                let b = s.shortest_paths_reference(&region, src, &targets);
                assert_eq!(a, b, "round {round}: region {} src {src}", region.len());
                found += usize::from(a.is_some());
            }
        }
        assert!(found > 300, "too few reachable cases: {found}");
    }

    /// Cuts and children's boundaries of one division.
    type Case<'a> = (Vec<&'a [u32]>, Vec<[&'a [u32]; 3]>);

    /// Lockstep with the hashed division: the same parts (or `None`) for the root halves of
    /// random corner triples (valid divisions), random paths as children (mostly invalid), and
    /// a non-mesh edge (the hashed fallback).
    #[test]
    fn divide_equals_the_hashed_version() {
        let mut r = Rng::new(7);
        let (mut some, mut none) = (0, 0);
        for m in meshes() {
            let topo = analyze_topology(&m);
            let pos: Vec<[f64; 3]> = m.positions.iter().map(|p| [p.x, p.y, p.z]).collect();
            let nt = m.triangles.len();
            let mut s = Surface::new(&pos, &m.triangles, &topo.neighbors);
            for round in 0..120 {
                let size = if round % 3 == 0 {
                    nt
                } else {
                    2 + r.below(nt as u64) as usize
                };
                let region = grow(nt, &topo.neighbors, r.below(nt as u64) as u32, size);
                let vs: Vec<u32> = s.vertices(&region, &[]);
                let c: Vec<u32> = (0..3)
                    .map(|_| vs[r.below(vs.len() as u64) as usize])
                    .collect();
                let p = |s: &mut Surface, a: u32, b: u32| {
                    s.shortest_paths(&region, a, &[b])
                        .and_then(|mut v| v.pop())
                        .unwrap_or_default()
                };
                let (pij, pjk, pki) = (
                    p(&mut s, c[0], c[1]),
                    p(&mut s, c[1], c[2]),
                    p(&mut s, c[2], c[0]),
                );
                let rev = |v: &Vec<u32>| v.iter().rev().copied().collect::<Vec<u32>>();
                let (ri, rj, rk) = (rev(&pki), rev(&pjk), rev(&pij));
                let ra = [pij.as_slice(), pjk.as_slice(), pki.as_slice()];
                let rb = [ri.as_slice(), rj.as_slice(), rk.as_slice()];
                let mut bogus = pij.clone();
                if round % 7 == 0 && pij.len() >= 2 {
                    // a chord that is not a mesh edge
                    bogus.push(c[2]);
                    bogus.push(pij[0]);
                }
                let cases: Vec<Case> = vec![
                    (ra.to_vec(), vec![ra, rb]),
                    (ra.to_vec(), vec![rb, ra]),
                    (vec![pij.as_slice()], vec![ra]),
                    (
                        vec![pij.as_slice(), pjk.as_slice()],
                        vec![ra, [rk.as_slice(), pjk.as_slice(), ri.as_slice()]],
                    ),
                    (
                        vec![bogus.as_slice()],
                        vec![[bogus.as_slice(), pjk.as_slice(), pki.as_slice()], rb],
                    ),
                ];
                for (cuts, children) in cases {
                    let a = s.divide(&region, &cuts, &children);
                    let b = s.divide_hashed(&region, &cuts, &children);
                    assert_eq!(a, b, "round {round}");
                    if a.is_some() {
                        some += 1;
                    } else {
                        none += 1;
                    }
                }
            }
        }
        assert!(
            some > 50 && none > 50,
            "cases: {some} valid, {none} invalid"
        );
    }
}

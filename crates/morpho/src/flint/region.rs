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
        Surface {
            pos,
            tris,
            nbr,
            vstamp: vec![0; pos.len()],
            vloc: vec![0; pos.len()],
            tstamp: vec![0; tris.len()],
            towner: vec![0; tris.len()],
            stamp: 0,
        }
    }

    fn next_stamp(&mut self) -> u32 {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.vstamp.iter_mut().for_each(|s| *s = 0);
            self.tstamp.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        self.stamp
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
    pub fn shortest_paths(
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
    pub fn divide(
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

//! The coloured dual graph and the graph steps of the contour algorithm (Dorgerloh et al.,
//! §3.1–§3.4, Figures 1–3), shared by triangles (K = 3) and tetrahedra (K = 4, §3.7): the
//! algorithm is the same, only the number of neighbours differs.
//!
//! * [`simplex_neighbors`] — the adjacency of the simplices across shared facets, computed in
//!   O(n + |V|) by radix-sorting the facets (no hashing); it also checks that no facet is shared
//!   by more than two simplices and that twins have opposite orientations.
//! * `Dual::construct_dual` (§3.1): one graph vertex per simplex, one edge per shared facet.
//! * `Dual::extend` (§3.2, Fig. 1): the vertex `v_ext` for the exterior, joined to every
//!   vertex of degree < K (the simplices with a facet on the hull). [`Dual::run`] does both in
//!   one pass over the colours and the neighbour array.
//! * [`Dual::hollow_out`] (§3.3, Fig. 2): from `v_ext`, deletes every white vertex that can be
//!   reached through white vertices, re-joining its neighbours to `v_ext`, and *marks* the black
//!   vertices so reached. O(n): each vertex enters the work list at most once and has at most K
//!   neighbours (Lemma 3).
//! * [`Dual::remove_v_ext`] (§3.4, Fig. 3) and [`Dual::marked_components`] (§3.4): the connected
//!   components of what remains — black simplices plus the white ones they enclose — by
//!   depth-first search, reported as the marked simplices of each component.
//!
//! `v_ext` is not stored as a vertex with an adjacency list (its degree is unbounded); the edge
//! `{u, v_ext}` is a flag on u, and deleting a vertex (with its edges) is a flag as well, so that
//! every step keeps O(1) work per incidence.

use super::ContourError;
use crate::util::NONE;
use crate::Result;

/// Witness that a triangulation needs no checking: its simplices have distinct in-range
/// vertices, are counter-clockwise (triangles) or positively oriented (tetrahedra) with non-zero
/// area (volume), and its neighbour array matches them. It is made only by
/// [`Valid::delaunay2`] and [`Valid::delaunay3`] from a triangulation that `delaunay::d2/d3` has
/// just returned and that nothing has touched since — the one use is `contour_samples`, which
/// triangulates the samples itself — so the contour functions skip the O(n) re-validation
/// (indices, orientations, neighbour symmetry) that they run on triangulations given by a caller
/// or read from a file. The private field keeps it from being made anywhere else.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Valid(());

impl Valid {
    /// The triangulation was returned by [`crate::delaunay::triangulate_2d`] this instant: its
    /// triangles are counter-clockwise (exact `orient2d` > 0) and `neighbors` is its adjacency
    /// across the edge opposite each corner.
    pub(crate) fn delaunay2(_fresh: &crate::delaunay::Delaunay2) -> Self {
        Valid(())
    }
    /// The tetrahedralization was returned by [`crate::delaunay::triangulate_3d`] this instant:
    /// its tetrahedra are positively oriented (exact `orient3d` > 0) and `neighbors` is its
    /// adjacency across the face opposite each corner.
    pub(crate) fn delaunay3(_fresh: &crate::delaunay::Delaunay3) -> Self {
        Valid(())
    }
}

/// Asks the processor to bring `x` into the cache: the graph searches push a vertex some pops
/// before they read its neighbour row, a random place in an array far larger than the cache.
/// A hint only; it changes no result.
#[inline(always)]
fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    #[allow(unused_unsafe)]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: prefetching is a hint, valid for any address; `x` is a live reference.
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(x as *const T as *const i8);
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

/// Checks that every index of `simplices` is below `n`.
pub fn check_indices<const K: usize>(simplices: &[[u32; K]], n: usize) -> Result<(), ContourError> {
    if simplices.len() >= NONE as usize {
        return Err(ContourError::TooManySimplices {
            count: simplices.len(),
        });
    }
    for (s, simplex) in simplices.iter().enumerate() {
        for &v in simplex {
            if v as usize >= n {
                return Err(ContourError::VertexOutOfRange {
                    simplex: s,
                    vertex: v,
                    vertices: n,
                });
            }
        }
        for i in 0..K {
            for j in i + 1..K {
                if simplex[i] == simplex[j] {
                    return Err(ContourError::RepeatedVertex {
                        simplex: s,
                        vertex: simplex[i],
                    });
                }
            }
        }
    }
    Ok(())
}

/// The facet opposite corner `i` of a positively oriented simplex, oriented outwards
/// (counter-clockwise edge of a triangle; for a tetrahedron a face that is counter-clockwise
/// seen from outside).
#[inline]
pub fn facet<const K: usize>(s: &[u32; K], i: usize) -> [u32; 3] {
    if K == 3 {
        [s[(i + 1) % 3], s[(i + 2) % 3], NONE]
    } else {
        const T: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];
        [s[T[i][0]], s[T[i][1]], s[T[i][2]]]
    }
}

/// The vertices of a facet sorted, and the parity of the sorting permutation.
#[inline]
fn sorted_facet<const K: usize>(s: &[u32; K], i: usize) -> ([u32; 3], bool) {
    let mut f = facet(s, i);
    let m = K - 1;
    let mut odd = false;
    for a in 0..m {
        for b in 0..m - 1 - a {
            if f[b] > f[b + 1] {
                f.swap(b, b + 1);
                odd = !odd;
            }
        }
    }
    (f, odd)
}

/// Neighbours of positively oriented simplices across their facets: `nb[s][i]` is the simplex
/// sharing the facet opposite corner `i` of `s`, or [`NONE`] on the hull. O(n + nverts) time by
/// radix sort of the facets. Errors when a facet is shared by more than two simplices or by two
/// simplices on the same side (inconsistent orientation or overlap).
///
/// ```
/// use morpho::contour::simplex_neighbors;
/// use morpho::util::NONE;
/// // two counter-clockwise triangles sharing the edge 1–2 (opposite corner 0 of the first)
/// let nb = simplex_neighbors(&[[0, 1, 2], [1, 3, 2]], 4).unwrap();
/// assert_eq!(nb, vec![[1, NONE, NONE], [NONE, 0, NONE]]);
/// ```
pub fn simplex_neighbors<const K: usize>(
    simplices: &[[u32; K]],
    nverts: usize,
) -> Result<Vec<[u32; K]>, ContourError> {
    check_indices(simplices, nverts)?;
    let nf = simplices.len() * K;
    let key = |f: u32, d: usize| -> u32 {
        let (s, i) = (f as usize / K, f as usize % K);
        sorted_facet(&simplices[s], i).0[d]
    };
    // LSD radix sort by the sorted facet's coordinates, last digit first.
    let mut order: Vec<u32> = (0..nf as u32).collect();
    let mut tmp = vec![0u32; nf];
    let mut count = vec![0u32; nverts + 1];
    for d in (0..K - 1).rev() {
        count.iter_mut().for_each(|c| *c = 0);
        for &f in &order {
            count[key(f, d) as usize + 1] += 1;
        }
        for v in 0..nverts {
            count[v + 1] += count[v];
        }
        for &f in &order {
            let k = key(f, d) as usize;
            tmp[count[k] as usize] = f;
            count[k] += 1;
        }
        std::mem::swap(&mut order, &mut tmp);
    }
    drop(tmp);
    let mut nb = vec![[NONE; K]; simplices.len()];
    let mut i = 0;
    while i < nf {
        let f0 = order[i] as usize;
        let (k0, p0) = sorted_facet(&simplices[f0 / K], f0 % K);
        let mut j = i + 1;
        while j < nf
            && sorted_facet(&simplices[order[j] as usize / K], order[j] as usize % K).0 == k0
        {
            j += 1;
        }
        match j - i {
            1 => {}
            2 => {
                let f1 = order[i + 1] as usize;
                let p1 = sorted_facet(&simplices[f1 / K], f1 % K).1;
                if p0 == p1 {
                    return Err(ContourError::SameSide {
                        first: f0 / K,
                        second: f1 / K,
                    });
                }
                nb[f0 / K][f0 % K] = (f1 / K) as u32;
                nb[f1 / K][f1 % K] = (f0 / K) as u32;
            }
            n => {
                return Err(ContourError::NonManifoldFacet {
                    simplex: f0 / K,
                    count: n,
                })
            }
        }
        i = j;
    }
    Ok(nb)
}

/// Checks a given neighbour array against the simplices: right length, symmetric, and each pair
/// really shares the facet. O(n).
pub fn check_neighbors<const K: usize>(
    simplices: &[[u32; K]],
    nb: &[[u32; K]],
) -> Result<(), ContourError> {
    if nb.len() != simplices.len() {
        return Err(ContourError::NeighbourCount {
            neighbours: nb.len(),
            simplices: simplices.len(),
        });
    }
    for (s, row) in nb.iter().enumerate() {
        for (i, &t) in row.iter().enumerate() {
            if t == NONE {
                continue;
            }
            let ok = (t as usize) < simplices.len()
                && (0..K).any(|j| {
                    nb[t as usize][j] as usize == s
                        && sorted_facet(&simplices[t as usize], j).0
                            == sorted_facet(&simplices[s], i).0
                });
            if !ok {
                return Err(ContourError::BadNeighbour {
                    simplex: s,
                    facet: i,
                });
            }
        }
    }
    Ok(())
}

const EXT: u8 = 1;
const REMOVED: u8 = 2;
const MARKED: u8 = 4;
const BLACK: u8 = 8;
/// Reached by the component search (§3.4).
const DONE: u8 = 16;

/// The marked vertices of the components of §3.4 ([`Dual::marked_components`]): those of
/// component `c` are `marked[start[c]..start[c + 1]]`, in search order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MarkedComponents {
    /// Marked vertices, grouped by component.
    pub marked: Vec<u32>,
    /// `start[c]`: where the group of component `c` begins; `start[ncomp] = marked.len()`.
    pub start: Vec<u32>,
}

impl MarkedComponents {
    /// Number of components.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }
    /// The marked vertices of component `c`.
    pub fn group(&self, c: usize) -> &[u32] {
        &self.marked[self.start[c] as usize..self.start[c + 1] as usize]
    }
}

/// The coloured dual graph G of a triangulation (tetrahedrization), with the state of the graph
/// steps of the contour algorithm.
///
/// G_init is the neighbour array itself (borrowed). Deleting a vertex of G deletes its edges, so
/// G is stored as G_init plus a flag per vertex: an edge of G_init is in G while both its ends are
/// present. The edge `{u, v_ext}` is a flag on u. Flags are packed in one byte per vertex.
#[derive(Debug, Clone)]
pub struct Dual<'a, const K: usize> {
    /// G_init: the dual as built by `construct_dual` (kept for `contour_of_component`).
    pub init: &'a [[u32; K]],
    /// Flags of each vertex, its colour (`BLACK`) among them.
    state: Vec<u8>,
    /// The vertices joined to `v_ext`: `extend` fills it with the hull simplices, `hollow_out`
    /// starts its set S from it and leaves in it the marked vertices (the only ones still
    /// joined), on which `remove_v_ext` clears the flag.
    joined: Vec<u32>,
}

impl<'a, const K: usize> Dual<'a, K> {
    /// §3.1: one vertex per simplex with its colour, one edge per shared facet. The callers
    /// have checked that there is one colour per simplex. ([`Self::run`] does this and
    /// `extend` in one pass; the separate steps are the tests' reference.)
    #[cfg(test)]
    pub fn construct_dual(neighbors: &'a [[u32; K]], black: &[bool]) -> Self {
        debug_assert_eq!(neighbors.len(), black.len());
        Dual {
            init: neighbors,
            state: black.iter().map(|&b| if b { BLACK } else { 0 }).collect(),
            joined: Vec::new(),
        }
    }

    /// The edge `{u, v_ext}` is in G.
    #[inline]
    #[cfg(test)]
    pub fn ext(&self, u: usize) -> bool {
        self.state[u] & EXT != 0
    }
    /// `u` was deleted from V by `hollow_out` (a white simplex reachable from the exterior).
    #[inline]
    pub fn removed(&self, u: usize) -> bool {
        self.state[u] & REMOVED != 0
    }
    /// `u` was marked by `hollow_out` (a black simplex touching the exterior white region).
    #[inline]
    pub fn marked(&self, u: usize) -> bool {
        self.state[u] & MARKED != 0
    }

    /// Number of neighbours of `u` in G, not counting `v_ext`.
    #[cfg(test)]
    pub fn degree(&self, u: usize) -> usize {
        self.init[u]
            .iter()
            .filter(|&&v| v != NONE && !self.removed(v as usize))
            .count()
    }

    /// §3.2, Fig. 1: adds `v_ext` and joins it to every vertex of degree < K.
    #[cfg(test)]
    pub fn extend(&mut self) {
        for (u, (nb, st)) in self.init.iter().zip(self.state.iter_mut()).enumerate() {
            if nb.contains(&NONE) {
                *st |= EXT;
                self.joined.push(u as u32);
            }
        }
    }

    /// §3.3, Fig. 2: hollows out the white region connected to the exterior and marks the black
    /// simplices that touch it. Each vertex enters S at most once (when it is joined to
    /// `v_ext`).
    pub fn hollow_out(&mut self) {
        // S as a stack: the deleted and marked sets do not depend on the order in which S is
        // worked off (a white vertex is deleted iff it is reachable from `v_ext` through white
        // vertices; a black one is marked iff it is joined to `v_ext` at some point), and the
        // last-in-first-out order stays near the simplices just visited in memory.
        let mut s = std::mem::take(&mut self.joined);
        let mut marked = Vec::new();
        while let Some(u) = s.pop() {
            let u = u as usize;
            if self.state[u] & BLACK == 0 {
                for &v in &self.init[u] {
                    // for each v ∈ N(u) − {v_ext} (edges to deleted vertices are gone)
                    if v == NONE {
                        continue;
                    }
                    let v = v as usize;
                    // if v_ext ∉ N(v): E := E ∪ {v, v_ext}, S := S ∪ {v}
                    if self.state[v] & (REMOVED | EXT) == 0 {
                        self.state[v] |= EXT;
                        if self.state[v] & BLACK == 0 {
                            // a white v reads its neighbours when popped
                            prefetch(&self.init[v]);
                        }
                        s.push(v as u32);
                    }
                }
                // E := E − {u, v_ext}, V := V − {u} (with all edges {v, u})
                self.state[u] = (self.state[u] & !EXT) | REMOVED;
            } else {
                self.state[u] |= MARKED;
                marked.push(u as u32);
            }
        }
        // The edges {u, v_ext} left are those of the marked vertices.
        self.joined = marked;
    }

    /// §3.4, Fig. 3: removes `v_ext` and its edges.
    pub fn remove_v_ext(&mut self) {
        for &u in &self.joined {
            self.state[u as usize] &= !EXT;
        }
        self.joined = Vec::new();
    }

    /// §3.4: the connected components of the remaining graph (black simplices and the white ones
    /// they enclose), by depth-first search from each vertex not yet reached, in index order (so
    /// component `c` is the one whose smallest vertex is the `c`-th smallest of the starts).
    /// Returns the *marked* vertices of each component — the only ones the contour steps
    /// (§3.5, the faces of §3.7) read — grouped by component in that order, each group in
    /// search order (not sorted). May assume `remove_v_ext` has run; sets the `DONE` flag of
    /// every vertex it reaches, so it runs once. O(n): each vertex is pushed once and has at
    /// most K neighbours.
    ///
    /// The "reached" flag lives in the state byte the search reads anyway, and no per-simplex
    /// component array is written: the old form (a `NONE`-filled `u32` per simplex plus a
    /// `bool` per simplex, [`Self::black_components_reference`] in the tests) is what the
    /// tests compare this with, group for group.
    pub fn marked_components(&mut self) -> MarkedComponents {
        let n = self.init.len();
        let mut marked = Vec::new();
        let mut start = vec![0u32];
        let mut stack = Vec::new();
        for s in 0..n {
            if self.state[s] & (REMOVED | DONE) != 0 {
                continue;
            }
            self.state[s] |= DONE;
            stack.push(s as u32);
            while let Some(u) = stack.pop() {
                let u = u as usize;
                if self.state[u] & MARKED != 0 {
                    marked.push(u as u32);
                }
                for &v in &self.init[u] {
                    if v != NONE && self.state[v as usize] & (REMOVED | DONE) == 0 {
                        self.state[v as usize] |= DONE;
                        prefetch(&self.init[v as usize]);
                        stack.push(v);
                    }
                }
            }
            start.push(marked.len() as u32);
        }
        MarkedComponents { marked, start }
    }

    /// The former §3.4 search, kept as the tests' reference for [`Self::marked_components`]:
    /// the component of each vertex ([`NONE`] for removed vertices) and their number.
    #[cfg(test)]
    pub fn black_components_reference(&self) -> (Vec<u32>, usize) {
        let n = self.init.len();
        let mut comp = vec![NONE; n];
        let mut done: Vec<bool> = self.state.iter().map(|&e| e & REMOVED != 0).collect();
        let mut count = 0u32;
        let mut stack = Vec::new();
        for start in 0..n {
            if done[start] {
                continue;
            }
            done[start] = true;
            comp[start] = count;
            stack.push(start as u32);
            while let Some(u) = stack.pop() {
                for &v in &self.init[u as usize] {
                    if v != NONE && !done[v as usize] {
                        done[v as usize] = true;
                        comp[v as usize] = count;
                        stack.push(v);
                    }
                }
            }
            count += 1;
        }
        (comp, count as usize)
    }

    /// Runs §3.1–§3.4 (`construct_dual`, `extend`, `hollow_out`, `remove_v_ext`).
    pub fn run(neighbors: &'a [[u32; K]], black: &[bool]) -> Self {
        // `construct_dual` and `extend` in one pass over the colours and G_init.
        debug_assert_eq!(neighbors.len(), black.len());
        let mut joined = Vec::new();
        let state = neighbors
            .iter()
            .zip(black)
            .enumerate()
            .map(|(u, (nb, &b))| {
                let c = if b { BLACK } else { 0 };
                if nb.contains(&NONE) {
                    joined.push(u as u32);
                    c | EXT
                } else {
                    c
                }
            })
            .collect();
        let mut g = Dual {
            init: neighbors,
            state,
            joined,
        };
        g.hollow_out();
        g.remove_v_ext();
        g
    }

    /// True when the facet opposite corner `k` of the marked simplex `u` belongs to the external
    /// contour: its other side is the exterior face or a white simplex deleted by `hollow_out`.
    #[inline]
    pub fn is_contour_facet(&self, u: usize, k: usize) -> bool {
        let v = self.init[u][k];
        v == NONE || self.removed(v as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbors_of_two_triangles() {
        // Square split along 0-2: triangles (0,1,2) and (0,2,3).
        let t = [[0, 1, 2], [0, 2, 3]];
        let nb = simplex_neighbors(&t, 4).unwrap();
        // Edge opposite corner 1 of t0 is (2,0); opposite corner 2 of t1 is... (0,2).
        assert_eq!(nb[0], [NONE, 1, NONE]);
        assert_eq!(nb[1], [NONE, NONE, 0]);
        check_neighbors(&t, &nb).unwrap();
        // Same orientation on both sides: an overlap.
        assert!(simplex_neighbors(&[[0, 1, 2], [0, 1, 3]], 4).is_err());
        // Three triangles on one edge.
        assert!(simplex_neighbors(&[[0, 1, 2], [1, 0, 3], [1, 0, 4]], 5).is_err());
        assert!(check_neighbors(&t, &[[NONE, 1, NONE], [NONE, NONE, NONE]]).is_err());
    }

    #[test]
    fn hollow_out_keeps_enclosed_white() {
        // A path of triangles 0-1-2-3-4 where 0 and 4 touch the hull; 2 is white and enclosed
        // only if it has no hull facet and all its neighbours are black.
        let nb: Vec<[u32; 3]> = vec![
            [1, NONE, NONE],
            [0, 2, 5],
            [1, 3, 6],
            [2, 4, 7],
            [3, NONE, NONE],
            [1, 6, NONE],
            [2, 5, 7],
            [3, 6, NONE],
        ];
        let black = [false, true, false, true, false, true, true, true];
        let g = Dual::run(&nb, &black);
        assert!(g.removed(0) && g.removed(4) && !g.removed(2));
        assert!(g.marked(1) && g.marked(3) && g.marked(5) && g.marked(7));
        assert!(!g.marked(6));
        assert_eq!(g.degree(1), 2);
        assert!(!g.ext(1));
        let (comp, n) = g.black_components_reference();
        assert_eq!(n, 1);
        assert_eq!(comp[0], NONE);
        assert_eq!(comp[2], comp[6]);
        let mut g = g;
        let m = g.marked_components();
        assert_eq!(m.len(), 1);
        let mut group = m.group(0).to_vec();
        group.sort();
        assert_eq!(group, [1, 3, 5, 7]);
    }

    /// The fused `run` (construct_dual and extend in one pass) leaves the state of the separate
    /// steps, and `marked_components` groups the marked vertices exactly as the reference search
    /// numbers the components; on random neighbour arrays of random triangulations, random
    /// colourings from all-white to all-black.
    #[test]
    fn fused_steps_and_components_match_the_reference() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for round in 0..200 {
            // A random triangulated grid of (w+1) × (h+1) points: two triangles per cell, the
            // diagonal chosen at random; neighbours from `simplex_neighbors`.
            let (w, h) = (1 + next() as usize % 9, 1 + next() as usize % 9);
            let id = |x: usize, y: usize| (y * (w + 1) + x) as u32;
            let mut tri = Vec::new();
            for y in 0..h {
                for x in 0..w {
                    let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
                    if next() % 2 == 0 {
                        tri.push([a, b, c]);
                        tri.push([a, c, d]);
                    } else {
                        tri.push([a, b, d]);
                        tri.push([b, c, d]);
                    }
                }
            }
            let nb = simplex_neighbors(&tri, (w + 1) * (h + 1)).unwrap();
            let p = (round % 11) as u64;
            let black: Vec<bool> = (0..tri.len()).map(|_| next() % 10 < p).collect();
            let mut r = Dual::construct_dual(&nb, &black);
            r.extend();
            let mut fused = Dual::run(&nb, &black);
            r.hollow_out();
            r.remove_v_ext();
            assert_eq!(r.state, fused.state);
            let (comp, ncomp) = r.black_components_reference();
            let m = fused.marked_components();
            assert_eq!(m.len(), ncomp);
            let mut got = vec![NONE; tri.len()];
            for c in 0..m.len() {
                for &u in m.group(c) {
                    assert_eq!(got[u as usize], NONE, "vertex twice");
                    got[u as usize] = c as u32;
                }
            }
            for u in 0..tri.len() {
                let want = if r.marked(u) { comp[u] } else { NONE };
                assert_eq!(got[u], want, "round {round}, vertex {u}");
            }
        }
    }
}

//! Geometric graphs from the Delaunay triangulation (Veltkamp 1992, Thms 3.2–3.3: every
//! γ(\[c₀,c₁\],\[c₂,c₃\]) with \[c₂,c₃\] ⊆ \[0,1\] is a subgraph of γ(\[-1,1\],\[0,1\]), which is the Delaunay
//! triangulation plus, for cocircular/cospherical groups, every chord of the group (V §3.3:
//! "γ(\[-1,1\],\[0,1\]) forms all possible overlapping simplices")).
//!
//! Size (over 800 lines): the 2D and 3D candidate sets share the cocircular/cospherical group
//! machinery (union–find, the group fast paths and their test switches) and its unit tests;
//! splitting the 3D half into its own file is the next step.
//!
//! # Candidates
//! [`Candidates2`]/[`Candidates3`] hold every simplex of γ(\[-1,1\],\[0,1\]) with its
//! [`CenterInterval`]: for a Delaunay edge (triangle) the interval ends are the offsets of the
//! circumcircles of its two adjacent triangles (tetrahedra) — the largest empty balls on each
//! side —, ±∞ on the hull. Cocircular (cospherical) groups are found by exact in-circle
//! (in-sphere) tests between neighbours; a chord of a group has the group's circle on both
//! sides. Building them is O(N) after the triangulation (plus O(g²)/O(g³) per group of g
//! points), so every Delaunay-subgraph kind costs O(N log N) in total.
//!
//! # Beyond the Delaunay triangulation (c < 0)
//! An edge outside γ(\[-1,1\],\[0,1\]) belongs to γ(\[-1,1\],\[c,1\]) iff the lens of two balls with
//! offsets ±F(c) is empty. The lens contains the disc of radius w = λ·|uv| around the edge's
//! midpoint (λ = (k − √(k² − 1))/2, k = 1/(1 − |c|)), and an empty disc centred at a point m of
//! Delaunay triangle T has radius at most B_T (the circumradius of an acute T, the longest edge
//! over √2 otherwise). A grid with a max pyramid of these bounds lists, for each vertex u, only
//! the midpoint cells m with 2λ·|m − u| ≤ B(m); the partners v = 2m − u come from a grid query.
//! Each candidate is tested with the midpoint disc and then its exact interval is computed from
//! the points within F + ρ of the midpoint (all that can bind). The work is proportional to the
//! number of candidate pairs the bound admits — local for evenly spread points, larger where the
//! hull is long and thin — instead of the O(N³) of V Thm 3.1. 3D beyond-Delaunay graphs use the
//! brute force (limited to small inputs).

use super::gamma::{offset_ratio, CenterInterval, EdgeFrame, TriFrame};
use super::lune::LuneGrid;
use crate::delaunay::d2::Delaunay2;
use crate::delaunay::d3::Delaunay3;
use crate::geom::distance::dot_sign;
use crate::geom::grid::PointGrid as Grid;
use crate::geom::predicates::{incircle_sign, raw};
use crate::util::{sorted3, NONE};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::sync::Mutex;

/// Every edge of γ(\[-1,1\],\[0,1\]) of a 2D point set with its interval of empty-ball offsets.
/// Edges are `[a, b]` with a < b in vertex indices of the triangulation; the interval's normal
/// is the left normal of a→b.
#[derive(Debug, Clone, Default)]
pub struct Candidates2 {
    pub edges: Vec<[u32; 2]>,
    pub intervals: Vec<CenterInterval>,
    /// True for edges of the Delaunay triangulation, false for extra chords of cocircular groups.
    pub in_dt: Vec<bool>,
}

/// The sorted vertex sets of the union-find groups of simplices with more than one member.
fn union_groups<const K: usize>(parent: &mut [u32], simplices: &[[u32; K]]) -> Vec<Vec<u32>> {
    let mut size = vec![0u32; simplices.len()];
    let mut root = vec![0u32; simplices.len()];
    for t in 0..simplices.len() {
        root[t] = find(parent, t as u32);
        size[root[t] as usize] += 1;
    }
    let mut groups: HashMap<u32, Vec<u32>> = HashMap::new();
    for (t, simplex) in simplices.iter().enumerate() {
        if size[root[t] as usize] > 1 {
            groups
                .entry(root[t])
                .or_default()
                .extend_from_slice(simplex);
        }
    }
    let mut out: Vec<Vec<u32>> = groups
        .into_values()
        .map(|mut v| {
            v.sort_unstable();
            v.dedup();
            v
        })
        .collect();
    out.sort();
    out
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

/// The vertex coordinates of a triangulation as arrays.
pub fn coords2(d: &Delaunay2) -> Vec<[f64; 2]> {
    d.points.iter().map(|p| [p.x, p.y]).collect()
}

/// A Delaunay edge a < b (vertex indices) with the apexes of the triangles on its two sides:
/// `left` lies left of a→b, `right` right of it ([`NONE`] on the hull side); `t_left`,
/// `t_right` are those triangles.
#[derive(Debug, Clone, Copy)]
pub struct DtEdge {
    pub a: u32,
    pub b: u32,
    pub left: u32,
    pub right: u32,
    pub t_left: u32,
    pub t_right: u32,
}

/// Every edge of a (non-collinear) 2D Delaunay triangulation once, as a parallel iterator in
/// triangle order (an edge is reported by the smaller of its two triangles).
pub fn dt_edges(d: &Delaunay2) -> impl ParallelIterator<Item = DtEdge> + '_ {
    d.triangles
        .par_iter()
        .enumerate()
        .flat_map_iter(move |(t, _)| (0..3).filter_map(move |i| dt_edge_at(d, t, i)))
}

/// The edge of triangle `t` opposite its corner `i`, when `t` reports it (it is the smaller of
/// the edge's triangles).
#[inline]
fn dt_edge_at(d: &Delaunay2, t: usize, i: usize) -> Option<DtEdge> {
    let nb = d.neighbors[t][i];
    if nb != NONE && (nb as usize) < t {
        return None; // reported from the other side
    }
    let tri = d.triangles[t];
    let (u, v) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
    let apex = if nb == NONE {
        NONE
    } else {
        let n = d.triangles[nb as usize];
        n.into_iter().find(|&x| x != u && x != v).unwrap_or(NONE)
    };
    let (t, nbt) = (t as u32, nb);
    // the triangle is counter-clockwise: its own corner is left of u→v
    Some(if u < v {
        DtEdge {
            a: u,
            b: v,
            left: tri[i],
            right: apex,
            t_left: t,
            t_right: nbt,
        }
    } else {
        DtEdge {
            a: v,
            b: u,
            left: apex,
            right: tri[i],
            t_left: nbt,
            t_right: t,
        }
    })
}

/// Triangles per parallel block of [`decide_sorted_2d`].
const TRI_BLOCK: usize = 1 << 16;
/// Triangles whose edges are listed before they are decided in [`decide_sorted_2d`].
const SLICE: usize = 512;
/// Consecutive smaller input indices per bucket of [`decide_sorted_2d`].
const SPAN: usize = 8192;

/// Decides every edge of a non-collinear 2D Delaunay triangulation once with `decide` (in
/// parallel, in triangle order) and returns the kept edges as input indices `[i, j]`, i < j,
/// sorted, with their values — without a separate sort of the whole edge list: each block of
/// triangles drops its kept edges into buckets of [`SPAN`] consecutive smaller indices, and each
/// bucket is then counting-sorted on its own straight into its place in the output (its counters
/// stay in the cache; the runs of one smaller index are ordered by the larger). Every Delaunay
/// edge is reported once and the input indices of distinct vertices differ, so there are no
/// repeats. O(N + E) after the triangulation, plus the decisions.
pub fn decide_sorted_2d<T: Copy + Default + Send + Sync>(
    d: &Delaunay2,
    decide: impl Fn(&DtEdge) -> Option<T> + Sync,
) -> (Vec<[u32; 2]>, Vec<T>) {
    let inp = &d.input_of_vertex;
    let nbuckets = d.vertex_of_input.len().div_ceil(SPAN).max(1);
    type Spread<T> = Vec<Vec<(u32, u32, T)>>;
    let spread: Vec<Spread<T>> = d
        .triangles
        .par_chunks(TRI_BLOCK)
        .enumerate()
        .map(|(k, tris)| {
            let mut out: Spread<T> = vec![Vec::new(); nbuckets];
            // the edges of a slice of triangles first (independent loads of the neighbouring
            // triangles, which lie anywhere in memory, overlap), then their decisions
            let mut es = Vec::with_capacity(3 * SLICE);
            let end = k * TRI_BLOCK + tris.len();
            for s0 in (k * TRI_BLOCK..end).step_by(SLICE) {
                es.clear();
                for t in s0..(s0 + SLICE).min(end) {
                    es.extend((0..3).filter_map(|i| dt_edge_at(d, t, i)));
                }
                for e in &es {
                    if let Some(x) = decide(e) {
                        let (a, b) = (inp[e.a as usize], inp[e.b as usize]);
                        let (a, b) = (a.min(b), a.max(b));
                        out[a as usize / SPAN].push((a, b, x));
                    }
                }
            }
            out
        })
        .collect();
    let sizes: Vec<usize> = (0..nbuckets)
        .map(|q| spread.iter().map(|s| s[q].len()).sum())
        .collect();
    let total: usize = sizes.iter().sum();
    let mut edges = vec![[0u32; 2]; total];
    let mut vals = vec![T::default(); total];
    let mut parts = Vec::with_capacity(nbuckets);
    let (mut re, mut rv) = (&mut edges[..], &mut vals[..]);
    for &size in &sizes {
        let (he, te) = re.split_at_mut(size);
        let (hv, tv) = rv.split_at_mut(size);
        parts.push((he, hv));
        re = te;
        rv = tv;
    }
    parts.into_par_iter().enumerate().for_each(|(q, (oe, ov))| {
        let base = q * SPAN;
        let mut start = vec![0u32; SPAN + 1];
        for s in &spread {
            for x in &s[q] {
                start[x.0 as usize - base + 1] += 1;
            }
        }
        for a in 0..SPAN {
            start[a + 1] += start[a];
        }
        let mut fill = start.clone();
        for s in &spread {
            for &(a, b, x) in &s[q] {
                let f = &mut fill[a as usize - base];
                oe[*f as usize] = [a, b];
                ov[*f as usize] = x;
                *f += 1;
            }
        }
        let mut long = Vec::new();
        for a in 0..SPAN {
            let (s0, s1) = (start[a] as usize, start[a + 1] as usize);
            if s1 - s0 > 24 {
                long.clear();
                long.extend((s0..s1).map(|i| (oe[i], ov[i])));
                long.sort_unstable_by_key(|x| x.0);
                for (i, &(e, x)) in (s0..s1).zip(&long) {
                    oe[i] = e;
                    ov[i] = x;
                }
                continue;
            }
            for i in s0 + 1..s1 {
                let mut j = i;
                while j > s0 && oe[j - 1][1] > oe[j][1] {
                    oe.swap(j - 1, j);
                    ov.swap(j - 1, j);
                    j -= 1;
                }
            }
        }
    });
    (edges, vals)
}

/// Adds `extra` edges (vertex indices, none of them a Delaunay edge) to sorted input-index edges
/// with their values, keeping the order (for the chords of cocircular groups; rare).
pub fn merge_extra<T: Copy>(
    d: &Delaunay2,
    edges: &mut Vec<[u32; 2]>,
    vals: &mut Vec<T>,
    extra: Vec<([u32; 2], T)>,
) {
    if extra.is_empty() {
        return;
    }
    let map = |v: u32| d.input_of_vertex[v as usize];
    let mut all: Vec<([u32; 2], T)> = edges.iter().copied().zip(vals.iter().copied()).collect();
    all.extend(extra.into_iter().map(|(e, x)| {
        let (a, b) = (map(e[0]), map(e[1]));
        ([a.min(b), a.max(b)], x)
    }));
    all.sort_unstable_by_key(|x| x.0);
    all.dedup_by_key(|x| x.0);
    edges.clear();
    vals.clear();
    for (e, x) in all {
        edges.push(e);
        vals.push(x);
    }
}

/// The exact incircle sign of a Delaunay edge's two apexes (0: the four points are cocircular;
/// −1 on the hull, where there is no second apex).
fn apex_rel(p: &[[f64; 2]], e: &DtEdge) -> f64 {
    if e.left == NONE || e.right == NONE {
        return -1.0;
    }
    let g = |v: u32| p[v as usize];
    incircle_sign(g(e.a), g(e.b), g(e.left), g(e.right)) as f64
}

/// The empty-ball interval of a Delaunay edge, and whether its two triangles are cocircular.
pub fn dt_interval(p: &[[f64; 2]], e: &DtEdge) -> (CenterInterval, bool) {
    let g = |v: u32| (v != NONE).then(|| p[v as usize]);
    let rel = apex_rel(p, e);
    let f = EdgeFrame::new(p[e.a as usize], p[e.b as usize]);
    (f.two_apexes(g(e.left), g(e.right), rel), rel == 0.0)
}

/// The triangle groups formed by cocircular neighbour pairs `ties`: each group's sorted vertex
/// set and the set of the group triangles' edges (the Delaunay edges among its vertices).
fn cocircular_groups(d: &Delaunay2, ties: &mut [[u32; 2]]) -> (Vec<Vec<u32>>, HashSet<[u32; 2]>) {
    if ties.is_empty() {
        return (vec![], HashSet::new());
    }
    ties.sort_unstable();
    let mut parent: Vec<u32> = (0..d.triangles.len() as u32).collect();
    let mut edges = HashSet::new();
    for &[t, nb] in ties.iter() {
        let (r1, r2) = (find(&mut parent, t), find(&mut parent, nb));
        parent[r1 as usize] = r2;
        for x in [t, nb] {
            let tri = d.triangles[x as usize];
            for i in 0..3 {
                let (u, v) = (tri[i], tri[(i + 1) % 3]);
                edges.insert([u.min(v), u.max(v)]);
            }
        }
    }
    (union_groups(&mut parent, &d.triangles), edges)
}

/// Notes that the two triangles of `e` are cocircular (from parallel workers).
fn record_tie(ties: &Mutex<Vec<[u32; 2]>>, e: &DtEdge) {
    ties.lock()
        .unwrap_or_else(|x| x.into_inner())
        .push([e.t_left, e.t_right]);
}

/// Calls `f(a, b, group)` for every chord a < b of a cocircular group that is not a Delaunay
/// edge (V §3.3), groups in a deterministic order.
fn for_each_group_chord(
    d: &Delaunay2,
    ties: Mutex<Vec<[u32; 2]>>,
    mut f: impl FnMut(u32, u32, &[u32]),
) {
    let mut ties = ties.into_inner().unwrap_or_else(|x| x.into_inner());
    let (groups, existing) = cocircular_groups(d, &mut ties);
    for vs in groups {
        for i in 0..vs.len() {
            for j in i + 1..vs.len() {
                let (a, b) = (vs[i], vs[j]);
                if !existing.contains(&[a, b]) {
                    f(a, b, &vs);
                }
            }
        }
    }
}

/// Calls `f(a, b, interval)` for every chord a < b of a cocircular group that is not a Delaunay
/// edge (as [`for_each_group_chord`]), with the chord's interval ([`chord_interval`], from the
/// group's [`CircleOrder`] in O(1) per chord after O(g log g) per group).
fn for_each_group_chord_interval(
    d: &Delaunay2,
    p: &[[f64; 2]],
    ties: Mutex<Vec<[u32; 2]>>,
    mut f: impl FnMut(u32, u32, &CenterInterval),
) {
    let mut ties = ties.into_inner().unwrap_or_else(|x| x.into_inner());
    let (groups, existing) = cocircular_groups(d, &mut ties);
    for vs in groups {
        let order = group_fast_paths()
            .then(|| CircleOrder::new(p, &vs))
            .flatten();
        for i in 0..vs.len() {
            for j in i + 1..vs.len() {
                let (a, b) = (vs[i], vs[j]);
                if existing.contains(&[a, b]) {
                    continue;
                }
                let iv = match &order {
                    Some(o) => o.chord_interval(p, &vs, i, j),
                    None => chord_interval(p, a, b, &vs),
                };
                f(a, b, &iv);
            }
        }
    }
}

#[cfg(test)]
thread_local! {
    /// Points examined for the intervals of cocircular chords on this thread (tests only).
    pub(super) static CHORD_WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    /// Tests only: compute every group chord and triple point by point (the reference).
    static POINT_BY_POINT: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether the group fast paths ([`CircleOrder`], [`SphereGroup`]) are used (always, but in
/// the tests that compare them with the point-by-point reference).
fn group_fast_paths() -> bool {
    #[cfg(test)]
    {
        !POINT_BY_POINT.with(|c| c.get())
    }
    #[cfg(not(test))]
    {
        true
    }
}

#[cfg(test)]
fn count_chord_work(k: usize) {
    CHORD_WORK.with(|c| c.set(c.get() + k as u64));
}
#[cfg(not(test))]
#[inline(always)]
fn count_chord_work(_: usize) {}

/// The points of a cocircular group in their order around the circle, with a range-minimum
/// table over it, so that the interval of a chord (V §3.3) costs O(1) instead of O(g).
///
/// [`chord_interval`] adds the group's points in `vs` order; all of them lie on the chord's
/// circle, so on each side the first one added binds and the others tie (exact in-circle 0,
/// never "better"), and the result depends only on those two points
/// ([`EdgeFrame::cocircular_ends`]). The points on one side of a chord are an arc of the
/// circle: the first in `vs` order is the arc's smallest index, a range minimum.
struct CircleOrder {
    /// the position around the circle of each group point (index into `vs`)
    pos: Vec<u32>,
    /// `table[k][s]`: the smallest `vs` index among the positions s .. s + 2ᵏ of the circular
    /// sequence written twice
    table: Vec<Vec<u32>>,
}

impl CircleOrder {
    /// `None` when the group's points are not all on one circle (then the chords are computed
    /// point by point): checked exactly, O(g) in-circle tests.
    fn new(p: &[[f64; 2]], vs: &[u32]) -> Option<Self> {
        let g = vs.len();
        if g < 3 {
            return None;
        }
        let at = |i: usize| p[vs[i] as usize];
        let (o, u, w) = (at(0), at(1), at(2));
        if raw::orient2d(o, u, w) == 0.0 {
            return None;
        }
        count_chord_work(g);
        if (3..g).any(|i| incircle_sign(o, u, w, at(i)) != 0) {
            return None;
        }
        // seen from o on the circle the other points span less than a half-turn, in their order
        // around the circle (inscribed angles): sorted by exact orientation around o
        let mut rest: Vec<u32> = (1..g as u32).collect();
        let mut work = 0usize;
        let mut tie = false;
        rest.sort_by(|&x, &y| {
            work += 1;
            let s = raw::orient2d(o, at(x as usize), at(y as usize));
            if s > 0.0 {
                std::cmp::Ordering::Less
            } else if s < 0.0 {
                std::cmp::Ordering::Greater
            } else {
                tie |= x != y;
                std::cmp::Ordering::Equal
            }
        });
        count_chord_work(work);
        if tie {
            return None; // (three collinear points: not a circle)
        }
        let mut cyc = vec![0u32];
        cyc.extend(rest);
        let mut pos = vec![0u32; g];
        for (k, &i) in cyc.iter().enumerate() {
            pos[i as usize] = k as u32;
        }
        let mut level: Vec<u32> = cyc.iter().chain(&cyc).copied().collect();
        let mut table = Vec::new();
        let mut w = 1;
        while w <= 2 * g {
            let next: Vec<u32> = (0..level.len().saturating_sub(w))
                .map(|s| level[s].min(level[s + w]))
                .collect();
            table.push(level);
            level = next;
            w *= 2;
        }
        Some(CircleOrder { pos, table })
    }

    /// The smallest `vs` index at the positions `lo .. hi` (hi > lo) of the doubled sequence.
    fn min(&self, lo: usize, hi: usize) -> u32 {
        let k = (usize::BITS - 1 - (hi - lo).leading_zeros()) as usize;
        self.table[k][lo].min(self.table[k][hi - (1 << k)])
    }

    /// The interval of the chord `vs[i] vs[j]` (i < j): equal to [`chord_interval`].
    fn chord_interval(&self, p: &[[f64; 2]], vs: &[u32], i: usize, j: usize) -> CenterInterval {
        count_chord_work(2);
        let g = vs.len();
        let (pa, pb) = (p[vs[i] as usize], p[vs[j] as usize]);
        let (x, y) = (self.pos[i] as usize, self.pos[j] as usize);
        let (lo, hi) = (x.min(y), x.max(y));
        // the two arcs between the ends: positions lo+1 .. hi and hi+1 .. lo+g
        let first = |s: usize, e: usize| (s < e).then(|| p[vs[self.min(s, e) as usize] as usize]);
        let (one, two) = (first(lo + 1, hi), first(hi + 1, lo + g));
        let rep = one.or(two);
        let one_left = rep.is_some_and(|q| raw::orient2d(pa, pb, q) > 0.0) == one.is_some();
        let (left, right) = if one_left { (one, two) } else { (two, one) };
        EdgeFrame::new(pa, pb).cocircular_ends(left, right)
    }
}

/// Decides every edge of γ(\[-1,1\],\[0,1\]) in parallel: `keep(edge, interval, in_dt)` for each
/// Delaunay edge (in triangle order) and then for each extra chord of a cocircular group
/// (V §3.3); returns the kept results in that order. O(N + Σ g²) after the triangulation, with
/// one exact in-circle test per edge.
pub fn filter_candidates_2d<T: Send>(
    d: &Delaunay2,
    keep: impl Fn([u32; 2], &CenterInterval, bool) -> Option<T> + Sync + Send,
) -> Vec<T> {
    let p = coords2(d);
    if d.collinear {
        // consecutive points on the line: nothing off the line, nothing between them
        return d
            .hull
            .windows(2)
            .filter_map(|w| {
                let (a, b) = (w[0].min(w[1]), w[0].max(w[1]));
                let iv = EdgeFrame::new(p[a as usize], p[b as usize]).start();
                keep([a, b], &iv, true)
            })
            .collect();
    }
    let ties = Mutex::new(Vec::new());
    let mut out: Vec<T> = dt_edges(d)
        .filter_map(|e| {
            let (iv, tie) = dt_interval(&p, &e);
            if tie {
                record_tie(&ties, &e);
            }
            keep([e.a, e.b], &iv, true)
        })
        .collect();
    for_each_group_chord_interval(d, &p, ties, |a, b, iv| {
        out.extend(keep([a, b], iv, false));
    });
    out
}

/// The interval of the chord a b of a cocircular group `vs` (V §3.3): all group points lie on
/// one circle, so the exact tie-breaking of [`EdgeFrame::add`] makes both ends its offset.
fn chord_interval(p: &[[f64; 2]], a: u32, b: u32, vs: &[u32]) -> CenterInterval {
    count_chord_work(vs.len());
    let f = EdgeFrame::new(p[a as usize], p[b as usize]);
    let mut iv = f.start();
    for &x in vs {
        if x != a && x != b {
            f.add(&mut iv, p[x as usize]);
        }
    }
    iv
}

/// [`filter_candidates_2d`] for a non-collinear triangulation with the kept edges as sorted
/// input indices `[i, j]`, i < j, and their values, decided vertex star by vertex star
/// ([`decide_sorted_2d`]; no sort of the whole edge list).
pub fn filter_candidates_sorted_2d<T: Send + Sync + Copy + Default>(
    d: &Delaunay2,
    p: &[[f64; 2]],
    keep: impl Fn([u32; 2], &CenterInterval) -> Option<T> + Sync + Send,
) -> (Vec<[u32; 2]>, Vec<T>) {
    let ties = Mutex::new(Vec::new());
    let (mut edges, mut vals) = decide_sorted_2d(d, |e| {
        let (iv, tie) = dt_interval(p, e);
        if tie {
            record_tie(&ties, e);
        }
        keep([e.a, e.b], &iv)
    });
    let mut extra = Vec::new();
    for_each_group_chord_interval(d, p, ties, |a, b, iv| {
        if let Some(x) = keep([a, b], iv) {
            extra.push(([a, b], x));
        }
    });
    merge_extra(d, &mut edges, &mut vals, extra);
    (edges, vals)
}

/// The Gabriel graph (V Def. 2.9; `lune` = None) or the lune-based β-skeleton (V Def. 2.16;
/// `lune` = Some((b, grid)), b ∈ (0, 1), `grid` over the points) of a non-collinear
/// triangulation as sorted input indices ([`decide_sorted_2d`]): a Delaunay edge must pass the
/// Gabriel test of [`gabriel_2d`] and then have an empty lune ([`LuneGrid::lune_empty`], its
/// apexes first); a chord of a cocircular group must pass the Gabriel test against its group and
/// then have an empty lune (the lune β-skeleton ⊆ Gabriel graph, V Fig. 3.2). O(N·k) with k the
/// points in a lune's box.
pub fn gabriel_lune_sorted_2d(
    d: &Delaunay2,
    p: &[[f64; 2]],
    lune: Option<(f64, &LuneGrid<'_>)>,
) -> Vec<[u32; 2]> {
    let outside = |a: u32, b: u32, x: u32| {
        x == NONE || dot_sign(&p[a as usize], &p[b as usize], &p[x as usize]) >= 0
    };
    let at = |x: u32| (x != NONE).then(|| p[x as usize]);
    let empty = |x: u32, y: u32, apexes: [u32; 2]| match lune {
        Some((b, g)) => g.lune_empty(p[x as usize], p[y as usize], apexes.map(at), b),
        None => true,
    };
    let ties = Mutex::new(Vec::new());
    let (mut edges, mut vals) = decide_sorted_2d(d, |e| {
        if apex_rel(p, e) == 0.0 {
            record_tie(&ties, e);
        }
        let keep = outside(e.a, e.b, e.left)
            && outside(e.a, e.b, e.right)
            && empty(e.a, e.b, [e.left, e.right]);
        keep.then_some(())
    });
    let mut extra = Vec::new();
    for_each_group_chord(d, ties, |x, y, vs| {
        if vs.iter().all(|&z| z == x || z == y || outside(x, y, z)) && empty(x, y, [NONE; 2]) {
            extra.push(([x, y], ()));
        }
    });
    merge_extra(d, &mut edges, &mut vals, extra);
    edges
}

/// The edges of a non-collinear 2D Delaunay triangulation as sorted input indices `[i, j]`,
/// i < j ([`decide_sorted_2d`]).
pub fn dt_edges_sorted_2d(d: &Delaunay2) -> Vec<[u32; 2]> {
    decide_sorted_2d(d, |_| Some(())).0
}

/// Builds the candidates from a 2D Delaunay triangulation ([`filter_candidates_2d`] keeping
/// everything). O(N + Σ g²).
pub fn candidates_2d(d: &Delaunay2) -> Candidates2 {
    let all = filter_candidates_2d(d, |e, iv, in_dt| Some((e, *iv, in_dt)));
    let mut out = Candidates2::default();
    out.edges.reserve(all.len());
    out.intervals.reserve(all.len());
    out.in_dt.reserve(all.len());
    for (e, iv, in_dt) in all {
        out.edges.push(e);
        out.intervals.push(iv);
        out.in_dt.push(in_dt);
    }
    out
}

/// The Gabriel graph (V Def. 2.9) from the triangulation without intervals: a Delaunay edge
/// (a, b) is a Gabriel edge iff neither adjacent apex x lies strictly inside the disc with
/// diameter ab, i.e. (a − x)·(b − x) ≥ 0 (the largest empty balls on its two sides are the two
/// circumcircles); a chord of a cocircular group is one iff no other group point has
/// (a − x)·(b − x) < 0 (it is then a diameter of the group's circle). Exact signs; O(N).
pub fn gabriel_2d(d: &Delaunay2) -> Vec<[u32; 2]> {
    let p = coords2(d);
    if d.collinear {
        return d
            .hull
            .windows(2)
            .map(|w| [w[0].min(w[1]), w[0].max(w[1])])
            .collect();
    }
    let outside = |a: u32, b: u32, x: u32| {
        x == NONE || dot_sign(&p[a as usize], &p[b as usize], &p[x as usize]) >= 0
    };
    let ties = Mutex::new(Vec::new());
    let mut out: Vec<[u32; 2]> = dt_edges(d)
        .filter_map(|e| {
            if apex_rel(&p, &e) == 0.0 {
                record_tie(&ties, &e);
            }
            (outside(e.a, e.b, e.left) && outside(e.a, e.b, e.right)).then_some([e.a, e.b])
        })
        .collect();
    for_each_group_chord(d, ties, |a, b, vs| {
        if vs.iter().all(|&x| x == a || x == b || outside(a, b, x)) {
            out.push([a, b]);
        }
    });
    out
}

/// An upper bound of the empty-disc radius at every point of the hull, on a grid with a max
/// pyramid: for a point m in triangle T the nearest vertex of T is at most B_T away, with
/// B_T = circumradius for acute T and (longest edge)/√2 otherwise (T then lies in the disc on
/// its longest edge). Each cell stores the largest B_T of the triangles whose box meets it.
struct MidpointBound {
    origin: [f64; 2],
    h: f64,
    /// side of the finest level (power of two)
    side: usize,
    /// `levels[0]` is the finest: side × side; `levels[k]` has side >> k.
    levels: Vec<Vec<f64>>,
}

impl MidpointBound {
    fn new(d: &Delaunay2, p: &[[f64; 2]]) -> Self {
        let b = crate::geom::bbox2(&d.points);
        let n = p.len().max(1);
        let ext = b.extent();
        let size = ext[0].max(ext[1]).max(f64::MIN_POSITIVE);
        let mut side = 1usize;
        while side * side < n && side < 4096 {
            side *= 2;
        }
        let h = size / side as f64 * (1.0 + 1e-12);
        let mut fine = vec![0.0f64; side * side];
        let origin = b.min;
        let ci = |x: f64, o: f64| (((x - o) / h).floor().max(0.0) as usize).min(side - 1);
        for t in &d.triangles {
            let (a, bb, c) = (p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]);
            let l2 = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2);
            let (ea, eb, ec) = (l2(bb, c), l2(a, c), l2(a, bb));
            let longest = ea.max(eb).max(ec);
            let acute = 2.0 * longest < ea + eb + ec; // largest angle < 90°
            let bt = if acute {
                let area2 = raw::orient2d(a, bb, c).abs();
                (ea * eb * ec).sqrt() / (2.0 * area2)
            } else {
                (longest / 2.0).sqrt()
            };
            let bt = if bt.is_finite() { bt } else { longest.sqrt() };
            let (x0, x1) = (
                ci(a[0].min(bb[0]).min(c[0]), origin[0]),
                ci(a[0].max(bb[0]).max(c[0]), origin[0]),
            );
            let (y0, y1) = (
                ci(a[1].min(bb[1]).min(c[1]), origin[1]),
                ci(a[1].max(bb[1]).max(c[1]), origin[1]),
            );
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let v = &mut fine[y * side + x];
                    *v = v.max(bt);
                }
            }
        }
        let mut levels = vec![fine];
        let mut s = side;
        while s > 1 {
            let prev = levels.last().map(Vec::as_slice).unwrap_or(&[]);
            let ns = s / 2;
            let mut next = vec![0.0f64; ns * ns];
            for y in 0..ns {
                for x in 0..ns {
                    let m = prev[(2 * y) * s + 2 * x]
                        .max(prev[(2 * y) * s + 2 * x + 1])
                        .max(prev[(2 * y + 1) * s + 2 * x])
                        .max(prev[(2 * y + 1) * s + 2 * x + 1]);
                    next[y * ns + x] = m;
                }
            }
            levels.push(next);
            s = ns;
        }
        MidpointBound {
            origin,
            h,
            side,
            levels,
        }
    }

    /// The finest cell containing m (clamped to the grid).
    fn cell_of(&self, m: [f64; 2]) -> usize {
        let ci = |x: f64, o: f64| (((x - o) / self.h).floor().max(0.0) as usize).min(self.side - 1);
        ci(m[1], self.origin[1]) * self.side + ci(m[0], self.origin[0])
    }

    /// Calls `f(lo, hi, cell)` for every finest cell whose bound B satisfies
    /// `slope · dist(u, cell) ≤ B`, by descending the pyramid.
    fn for_each_cell(&self, u: [f64; 2], slope: f64, mut f: impl FnMut([f64; 2], [f64; 2], usize)) {
        let top = self.levels.len() - 1;
        let mut stack = vec![(top, 0usize, 0usize)];
        while let Some((lvl, x, y)) = stack.pop() {
            let cells = 1usize << lvl;
            let w = self.h * cells as f64;
            let lo = [self.origin[0] + x as f64 * w, self.origin[1] + y as f64 * w];
            let hi = [lo[0] + w, lo[1] + w];
            let dx = (lo[0] - u[0]).max(0.0).max(u[0] - hi[0]);
            let dy = (lo[1] - u[1]).max(0.0).max(u[1] - hi[1]);
            let dist = (dx * dx + dy * dy).sqrt();
            let ls = self.side >> lvl;
            let bnd = self.levels[lvl][y * ls + x];
            if slope * dist > bnd * (1.0 + 1e-9) {
                continue;
            }
            if lvl == 0 {
                f(lo, hi, y * self.side + x);
            } else {
                for (cx, cy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    stack.push((lvl - 1, 2 * x + cx, 2 * y + cy));
                }
            }
        }
    }
}

/// The edges outside γ(\[-1,1\],\[0,1\]) whose largest intersection parameter c₁′ is ≥ `c` (c < 0),
/// with their intervals. See the module documentation for the algorithm.
pub fn beyond_dt_2d(
    d: &Delaunay2,
    cand: &Candidates2,
    c: f64,
) -> (Vec<[u32; 2]>, Vec<CenterInterval>) {
    beyond_dt_2d_impl(d, cand, c, None)
}

/// [`beyond_dt_2d`] restricted to the edges with at least one end in `at` (triangulation
/// vertex ids; duplicates and out-of-range ids are ignored), in increasing order of their sorted
/// vertex pair. The same edges and intervals as filtering the full result, at the cost of the
/// partner searches of the listed vertices only: the boundary constriction's adaptive
/// augmentation (V §5.4) only ever uses edges at vertices not yet on the boundary.
pub fn beyond_dt_2d_at(
    d: &Delaunay2,
    cand: &Candidates2,
    c: f64,
    at: &[u32],
) -> (Vec<[u32; 2]>, Vec<CenterInterval>) {
    let mut mark = vec![false; d.points.len()];
    for &v in at {
        if let Some(m) = mark.get_mut(v as usize) {
            *m = true;
        }
    }
    beyond_dt_2d_impl(d, cand, c, Some(&mark))
}

/// The search of [`beyond_dt_2d`]: from every vertex a (or every marked one), the partners b
/// with b > a (or any b, b > a when b is marked too, so that each edge is found once).
fn beyond_dt_2d_impl(
    d: &Delaunay2,
    cand: &Candidates2,
    c: f64,
    mark: Option<&[bool]>,
) -> (Vec<[u32; 2]>, Vec<CenterInterval>) {
    let p = coords2(d);
    let n = p.len();
    let mut edges = Vec::new();
    let mut ivs = Vec::new();
    if n < 3 || c >= 0.0 {
        return (edges, ivs);
    }
    let sources: Vec<usize> = match mark {
        None => (0..n).collect(),
        Some(m) => (0..n).filter(|&v| m[v]).collect(),
    };
    // partner b of source a is searched from a: always when b > a, and when b < a only if b is
    // not itself a source
    let takes = |a: usize, b: usize| b > a || (b != a && mark.is_some_and(|m| !m[b]));
    let key_of = |a: usize, b: usize| [a.min(b) as u32, a.max(b) as u32];
    let existing: HashSet<[u32; 2]> = cand.edges.iter().copied().collect();
    let grid = Grid::new(&p, 2.0);
    let cabs = c.abs().min(1.0);
    let mut found: Vec<([u32; 2], CenterInterval)> = Vec::new();
    if cabs >= 1.0 {
        // every pair not blocked by a point on its segment
        for &a in &sources {
            for b in 0..n {
                if !takes(a, b) {
                    continue;
                }
                let key = key_of(a, b);
                if existing.contains(&key) {
                    continue;
                }
                let f = EdgeFrame::new(p[key[0] as usize], p[key[1] as usize]);
                let mut iv = f.start();
                for x in 0..n {
                    if x != a && x != b {
                        f.add(&mut iv, p[x]);
                    }
                }
                if iv.gamma_values().is_some() {
                    found.push((key, iv));
                }
            }
        }
    } else {
        let k = 1.0 / (1.0 - cabs);
        let f_over_r = offset_ratio(cabs);
        // midpoint disc radius / edge length, ½ (k − √(k² − 1)) without cancellation (|c| near
        // 1) and shrunk by far more than its rounding (|c| near 0 puts it within an ulp of ½):
        // a smaller disc only rejects what the exact one rejects
        let lam = 0.5 / (k + f_over_r) * (1.0 - 1e-9);
        let bound = MidpointBound::new(d, &p);
        // one vertex's partners at a time, vertices in parallel (results in vertex order)
        let per_vertex: Vec<Vec<([u32; 2], CenterInterval)>> = sources
            .par_iter()
            .map(|&a| {
                let mut found = Vec::new();
                let mut near: Vec<u32> = Vec::new();
                let pa = p[a];
                // candidate partners: v = 2m − u for midpoints m in cells whose bound allows
                // λ·|uv| = 2λ·|m − u| ≤ B(m)
                bound.for_each_cell(pa, 2.0 * lam, |lo, hi, cell| {
                    let vlo = [2.0 * lo[0] - pa[0], 2.0 * lo[1] - pa[1]];
                    let vhi = [2.0 * hi[0] - pa[0], 2.0 * hi[1] - pa[1]];
                    grid.for_each_in_box(vlo, vhi, |b| {
                        if takes(a, b as usize) {
                            let pb = p[b as usize];
                            let m = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
                            if bound.cell_of(m) == cell {
                                near.push(b);
                            }
                        }
                        true
                    });
                });
                near.sort_unstable();
                near.dedup();
                for &b in &near {
                    let key = key_of(a, b as usize);
                    if existing.contains(&key) {
                        continue;
                    }
                    // the frame in sorted order, so that the interval is that of the full search
                    let (pu, pv) = (p[key[0] as usize], p[key[1] as usize]);
                    let len = ((pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2)).sqrt();
                    let m = [0.5 * (pu[0] + pv[0]), 0.5 * (pu[1] + pv[1])];
                    let w = lam * len;
                    // midpoint disc must be empty
                    let empty = grid.for_each_within(m, w, |x| x == key[0] || x == key[1]);
                    if !empty {
                        continue;
                    }
                    let r = 0.5 * len;
                    let reach = r * (k + f_over_r) * (1.0 + 1e-9);
                    let f = EdgeFrame::new(pu, pv);
                    let mut iv = f.start();
                    // The ends only move inwards as points are added, so once one passes ±F
                    // for certain (the ends' accuracy allowed for: `CenterInterval::past`)
                    // c₁′ < c is certain and the search ends.
                    // Growing shells around m find the binding points early.
                    let f_off = iv.r_over_n * f_over_r * (1.0 + 1e-9);
                    let mut inner2 = -1.0;
                    for sh in (0..4).rev() {
                        let rad = reach / (1u32 << sh) as f64;
                        let more = grid.for_each_within(m, rad, |x| {
                            let q = p[x as usize];
                            let d2 = (q[0] - m[0]).powi(2) + (q[1] - m[1]).powi(2);
                            if d2 < inner2 || x == key[0] || x == key[1] {
                                return true;
                            }
                            f.add(&mut iv, q);
                            !iv.past(f_off)
                        });
                        if !more {
                            break;
                        }
                        inner2 = rad * rad;
                    }
                    // Only a gap can be trusted: a non-Delaunay edge always has one, and when
                    // its true c₁′ ≥ c every binding point is within reach, so the local
                    // interval is exact. A local interval without a gap means a binding point
                    // beyond reach, i.e. c₁′ < c.
                    if iv.lo <= iv.hi {
                        continue;
                    }
                    // c₁′ ≥ c decided exactly (not by the rounded γ-value)
                    if f.c1_at_least(&iv, c) {
                        found.push((key, iv));
                    }
                }
                found
            })
            .collect();
        found = per_vertex.into_iter().flatten().collect();
    }
    if mark.is_some() {
        found.sort_unstable_by_key(|e| e.0);
    }
    for (e, iv) in found {
        edges.push(e);
        ivs.push(iv);
    }
    (edges, ivs)
}

/// Every triangle of 3D γ(\[-1,1\],\[0,1\]) with its interval (normal of the sorted corners
/// (b − a) × (c − a)).
#[derive(Debug, Clone, Default)]
pub struct Candidates3 {
    pub triangles: Vec<[u32; 3]>,
    pub intervals: Vec<CenterInterval>,
    pub in_dt: Vec<bool>,
}

/// The vertex coordinates of a tetrahedralization as arrays.
pub fn coords3(d: &Delaunay3) -> Vec<[f64; 3]> {
    d.points.iter().map(|p| [p.x, p.y, p.z]).collect()
}

/// Which triples of the cospherical and flat groups [`candidates_3d_with`] adds to the
/// Delaunay faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroupTriples {
    /// None: the Delaunay faces only (the kinds that need no more than the faces and the pairs
    /// of the groups skip the Θ(g³) triples).
    Faces,
    /// Every triple with an empty ball through it: the triples of the cospherical groups and of
    /// the cocircular (flat) cells — all of γ(\[-1,1\],\[0,1\]) but the triangles below.
    Balls,
    /// [`GroupTriples::Balls`] and the triangles of coplanar hull facets with more than three
    /// points whose closed triangle is empty but whose circumcircle holds a point of the facet:
    /// only the outer half-space is an empty neighbourhood of them (γ-values (−1, 1)), so only
    /// the γ kinds with a parameter −1 (and the boundary's γ(\[-1,1\],\[0,1\])) contain them.
    /// Listed from the empty triangles of each facet ([`super::facets`]), O(1) each after
    /// O(g² log g) per facet of g points; they can be Θ(g³) (points in convex position).
    All,
}

/// Builds the 3D candidates. Cospherical groups (adjacent tetrahedra with a common empty
/// sphere, found by exact in-sphere) contribute every non-degenerate triple of their vertices;
/// such a triple's interval is computed against the group's vertices and the vertices of all
/// tetrahedra around its corners (every point that can touch an empty ball through it).
///
/// A group of g points has up to g³/6 triples, all in γ(\[-1,1\],\[0,1\]) when the points lie on
/// one sphere: that output costs O(1) per triple on the sphere, not O(g) ([`SphereGroup`]).
pub fn candidates_3d(d: &Delaunay3) -> Candidates3 {
    candidates_3d_with(d, GroupTriples::All).0
}

/// The Delaunay faces with their intervals and the group triples `which`, and the sorted
/// vertex sets of the groups whose pairs may be chords of γ(\[-1,1\],\[0,1\]) (V §3.3): the
/// cospherical groups and the cocircular cells.
///
/// Groups: (a) cospherical tetrahedra; (b) coplanar, cocircular faces sharing an edge — one
/// circle, which bounds the same family of balls for every triple of it; (c) coplanar hull
/// faces sharing an edge — a hull facet, whose every empty triangle is a hull triangle
/// (Def. 2.10) with an empty outer half-space. A triangle of a facet whose circumcircle holds
/// no point of the facet is a Delaunay face or a triple of a cell (b) (the facet's Delaunay
/// faces triangulate its planar Delaunay subdivision, whose cells are the cells (b)); the
/// others have no empty finite ball (their interval is `finite_blocked`) and are listed from
/// the facet's empty triangles ([`super::facets`]) in O(1) each, only for
/// [`GroupTriples::All`]. Testing every triple of a facet against every candidate point, as
/// before, cost O(g⁴): hours for the 1597 points of the fandisk model's top facet
/// (issue 17, item 8).
pub fn candidates_3d_with(d: &Delaunay3, which: GroupTriples) -> (Candidates3, Vec<Vec<u32>>) {
    let p = coords3(d);
    let mut out = Candidates3::default();
    let nt = d.tets.len();
    let mut parent: Vec<u32> = (0..nt as u32).collect();
    for f in d.triangles() {
        let t = sorted3(f.v);
        let Some(fr) = TriFrame::new(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]) else {
            continue;
        };
        let mut iv = fr.start();
        let mut apexes = [NONE; 2];
        for (k, &tet) in f.tets.iter().enumerate() {
            if tet == NONE {
                continue;
            }
            let tv = d.tets[tet as usize];
            if let Some(&x) = tv.iter().find(|&&x| !t.contains(&x)) {
                fr.add(&mut iv, p[x as usize]);
                apexes[k] = x;
            }
        }
        if f.tets[1] != NONE && apexes[1] != NONE {
            let tv = d.tets[f.tets[0] as usize].map(|x| p[x as usize]);
            if raw::insphere(tv[0], tv[1], tv[2], tv[3], p[apexes[1] as usize]) == 0.0 {
                let (r1, r2) = (find(&mut parent, f.tets[0]), find(&mut parent, f.tets[1]));
                parent[r1 as usize] = r2;
            }
        }
        out.triangles.push(t);
        out.intervals.push(iv);
        out.in_dt.push(true);
    }
    // groups of vertices whose triples all belong to γ([-1,1],[0,1]): (a) cospherical
    // tetrahedra (common empty sphere), (b) cocircular cells
    let mut spheres = union_groups(&mut parent, &d.tets);
    let (mut groups, facets) = flat_groups(d, &p, &out.triangles);
    for g in spheres.iter_mut() {
        g.sort_unstable();
        g.dedup();
    }
    spheres.sort();
    spheres.dedup();
    // the cells first: a circle of a cospherical group with more than three points is a cell
    // (its Delaunay faces are coplanar and cocircular), whose triples [`CircleGroup`] decides
    // in O(1) each, while [`SphereGroup`] would take them point by point (the whole group lies
    // on one side of them)
    groups.extend(spheres);
    if which == GroupTriples::Faces || (groups.is_empty() && facets.is_empty()) {
        return (out, groups);
    }
    let mut existing: HashSet<[u32; 3]> = out.triangles.iter().copied().collect();
    for vs in &groups {
        // every point that can touch an empty ball through a triple of the group: the group and
        // the vertices of all tetrahedra around its vertices
        let mut cands: Vec<u32> = vs.clone();
        for &v in vs {
            for tet in d.tets_around_vertex(v) {
                cands.extend_from_slice(&d.tets[tet as usize]);
            }
        }
        cands.sort_unstable();
        cands.dedup();
        let sphere = group_fast_paths()
            .then(|| SphereGroup::new(&p, vs, &cands))
            .flatten();
        let circle = (group_fast_paths() && sphere.is_none())
            .then(|| CircleGroup::new(&p, vs, &cands))
            .flatten();
        for i in 0..vs.len() {
            for j in i + 1..vs.len() {
                for k in j + 1..vs.len() {
                    let t = [vs[i], vs[j], vs[k]];
                    if existing.contains(&t) {
                        continue;
                    }
                    let Some(fr) =
                        TriFrame::new(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize])
                    else {
                        continue;
                    };
                    let fast = match (&sphere, &circle) {
                        (Some(g), _) => g.interval(&p, &fr, t),
                        (None, Some(g)) => Some(g.interval(&fr)),
                        (None, None) => None,
                    };
                    let iv = match fast {
                        Some(iv) => iv,
                        None => {
                            count_triple_work(cands.len());
                            #[cfg(test)]
                            SLOW_TRIPLES.with(|c| c.set(c.get() + 1));
                            let mut iv = fr.start();
                            for &x in &cands {
                                if !t.contains(&x) {
                                    fr.add(&mut iv, p[x as usize]);
                                }
                            }
                            iv
                        }
                    };
                    if iv.gamma_values().is_none() {
                        continue;
                    }
                    if iv.lo <= iv.hi {
                        existing.insert(t);
                        out.triangles.push(t);
                        out.intervals.push(iv);
                        out.in_dt.push(false);
                    }
                }
            }
        }
    }
    if which == GroupTriples::All {
        for (vs, inner) in &facets {
            facet_triangles(&p, vs, *inner, &mut existing, &mut out);
        }
    }
    (out, groups)
}

/// A cell of [`candidates_3d_with`] (b): points on one circle, with no candidate point strictly
/// inside that circle in its plane (checked exactly once per group: O(|cands|) tests).
///
/// Every sphere through a triple of the group is a sphere through the circle, so the relation
/// "x is better than y" of [`TriFrame::add`] between points off the plane (x inside the sphere
/// through the circle and y) is the same for every triple, and so is the binding point on each
/// side of the plane (the first of the best in candidate order); a point in the plane binds
/// nothing (none is inside the circle, so none is in a closed triangle of it either). The two
/// binding points are found once by adding every candidate for one triple; then a triple costs
/// O(1) instead of O(|cands|) ([`TriFrame::ends`]), bit for bit the same interval. The triples
/// of g cocircular points (a flat cell of a 3D set: all of them in γ(\[-1,1\],\[0,1\]), Θ(g³))
/// cost O(g⁴) point by point: 324 integer points of a circle with one point above and one
/// below it took minutes (issue 17, item 8).
struct CircleGroup {
    /// The binding points on the normal's side of the first triple and on the other side.
    sides: [Option<[f64; 3]>; 2],
}

impl CircleGroup {
    fn new(p: &[[f64; 3]], vs: &[u32], cands: &[u32]) -> Option<Self> {
        let at = |v: u32| p[v as usize];
        let (&a, &b) = (vs.first()?, vs.get(1)?);
        let c = *vs
            .iter()
            .find(|&&c| TriFrame::new(at(a), at(b), at(c)).is_some())?;
        let fr = TriFrame::new(at(a), at(b), at(c))?;
        let n = crate::geom::vec::cross(
            crate::geom::vec::sub(at(b), at(a)),
            crate::geom::vec::sub(at(c), at(a)),
        );
        count_triple_work(cands.len());
        let mut iv = fr.start();
        let mut g = 0;
        for &x in cands {
            let member = g < vs.len() && vs[g] == x;
            if member {
                g += 1;
            }
            let q = at(x);
            if fr.side(q) != 0.0 {
                if member {
                    return None;
                }
                fr.add(&mut iv, q);
                continue;
            }
            // in the plane: the group on the circle (a, b, c exactly not collinear: the circle
            // side of a is 0, not the collinear 0 — checked by a member off the circle below),
            // every other point not inside it
            let side = super::gamma::circumcircle_side_3d(at(a), at(b), at(c), q, n);
            if (member && side != 0.0) || (!member && side > 0.0) {
                return None;
            }
        }
        let lifted = {
            let mut d = at(a);
            let k = (0..3)
                .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
                .unwrap_or(0);
            d[k] += 1.0 + d[k].abs();
            d
        };
        // corners exactly not collinear (else every side above was 0)
        if raw::orient3d(at(a), at(b), at(c), lifted) == 0.0 {
            return None;
        }
        (g == vs.len() && !iv.finite_blocked && !iv.all_blocked).then_some(CircleGroup {
            sides: [iv.hi_at, iv.lo_at],
        })
    }

    /// The interval of a triple of the group (frame `fr`).
    fn interval(&self, fr: &TriFrame) -> CenterInterval {
        count_triple_work(1);
        let [x, y] = self.sides;
        // the first triple's normal side is this one's, or the other
        let flip = match (x, y) {
            (Some(q), _) => fr.side(q) < 0.0,
            (None, Some(q)) => fr.side(q) > 0.0,
            (None, None) => false,
        };
        if flip {
            fr.ends(y, x)
        } else {
            fr.ends(x, y)
        }
    }
}

/// The triangles of the hull facet `vs` (sorted) that are not candidates yet: its empty
/// triangles whose circumcircle holds a point of the facet (see [`candidates_3d_with`]), each
/// with the interval the point-by-point computation gives but for the value of its finite end
/// (no finite ball is empty, only the presence of a binding point matters; `inner` is a point
/// off the facet's plane, all of which lie on one side). Appended in sorted order.
fn facet_triangles(
    p: &[[f64; 3]],
    vs: &[u32],
    inner: u32,
    existing: &mut HashSet<[u32; 3]>,
    out: &mut Candidates3,
) {
    if !group_fast_paths() {
        facet_triangles_reference(p, vs, existing, out);
        return;
    }
    let fp: Vec<[f64; 3]> = vs.iter().map(|&v| p[v as usize]).collect();
    let mut found: Vec<[u32; 3]> = Vec::new();
    super::facets::empty_triangles_3d(&fp, |a, b, c| {
        let mut t = [vs[a as usize], vs[b as usize], vs[c as usize]];
        t.sort_unstable();
        if !existing.contains(&t) {
            found.push(t);
        }
    });
    found.sort_unstable();
    for t in found {
        let Some(fr) = TriFrame::new(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]) else {
            continue;
        };
        count_triple_work(1);
        let mut iv = fr.start();
        fr.add(&mut iv, p[inner as usize]);
        iv.finite_blocked = true;
        existing.insert(t);
        out.triangles.push(t);
        out.intervals.push(iv);
        out.in_dt.push(false);
    }
}

#[cfg(test)]
thread_local! {
    /// Points examined for the intervals of group triples on this thread (tests only).
    pub(super) static TRIPLE_WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    static SLOW_TRIPLES: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

#[cfg(test)]
fn count_triple_work(k: usize) {
    TRIPLE_WORK.with(|c| c.set(c.get() + k as u64));
}
#[cfg(not(test))]
#[inline(always)]
fn count_triple_work(_: usize) {}

/// A group of [`candidates_3d`] whose points lie on one sphere S that no other candidate point
/// lies in or on (checked exactly once per group: O(g + |cands|) in-sphere tests).
///
/// For a triple of it, every other group point above (below) its plane lies on S, i.e. on the
/// sphere through the triple and the first of them: they all tie (exact in-sphere 0, never
/// "better" in [`TriFrame::add`]); a candidate off the group is strictly outside S, so it never
/// beats a group point on its side; and no candidate in the plane is inside the triangle's
/// circle (it would be inside S). So when the group has points on both sides, the point-by-point
/// interval is fixed by the first group point on each side in candidate order
/// ([`TriFrame::cospherical_ends`]) — found by scanning the group in order, usually after a few
/// points. Triples with the whole group on one side (faces of the group's hull) are computed
/// point by point.
struct SphereGroup<'a> {
    vs: &'a [u32],
}

impl<'a> SphereGroup<'a> {
    fn new(p: &[[f64; 3]], vs: &'a [u32], cands: &[u32]) -> Option<Self> {
        let at = |v: u32| p[v as usize];
        // four group points off one plane define S
        let (&a, &b) = (vs.first()?, vs.get(1)?);
        let c = *vs
            .iter()
            .find(|&&c| TriFrame::new(at(a), at(b), at(c)).is_some())?;
        let e = *vs
            .iter()
            .find(|&&e| raw::orient3d(at(a), at(b), at(c), at(e)) != 0.0)?;
        let o = raw::orient3d(at(a), at(b), at(c), at(e));
        count_triple_work(cands.len());
        let mut g = 0;
        for &x in cands {
            let ins = raw::insphere(at(a), at(b), at(c), at(e), at(x)) * o;
            let member = g < vs.len() && vs[g] == x;
            if member {
                g += 1;
            }
            // group points on S, every other candidate strictly outside
            if (member && ins != 0.0) || (!member && ins >= 0.0) {
                return None;
            }
        }
        (g == vs.len()).then_some(SphereGroup { vs })
    }

    /// The interval of the triple `t` of the group (frame `fr`), or `None` when the group has
    /// no point strictly on one side of its plane.
    fn interval(&self, p: &[[f64; 3]], fr: &TriFrame, t: [u32; 3]) -> Option<CenterInterval> {
        let (mut above, mut below) = (None, None);
        let mut seen = 0;
        for &x in self.vs {
            if t.contains(&x) {
                continue;
            }
            seen += 1;
            let q = p[x as usize];
            let side = fr.tau(q).0;
            if side > 0.0 && above.is_none() {
                above = Some(q);
            } else if side < 0.0 && below.is_none() {
                below = Some(q);
            }
            if above.is_some() && below.is_some() {
                count_triple_work(seen);
                return Some(fr.cospherical_ends(above, below));
            }
        }
        count_triple_work(seen);
        None
    }
}

/// [`facet_triangles`] by the definition, for the tests: every triple of the facet that is
/// not a candidate yet, with its interval against every point. O(g³·N).
fn facet_triangles_reference(
    p: &[[f64; 3]],
    vs: &[u32],
    existing: &mut HashSet<[u32; 3]>,
    out: &mut Candidates3,
) {
    for i in 0..vs.len() {
        for j in i + 1..vs.len() {
            for k in j + 1..vs.len() {
                let t = [vs[i], vs[j], vs[k]];
                if existing.contains(&t) {
                    continue;
                }
                let Some(iv) = super::gamma::center_interval_3d(
                    p,
                    t[0] as usize,
                    t[1] as usize,
                    t[2] as usize,
                ) else {
                    continue;
                };
                count_triple_work(p.len());
                if iv.gamma_values().is_some() && iv.lo <= iv.hi {
                    existing.insert(t);
                    out.triangles.push(t);
                    out.intervals.push(iv);
                    out.in_dt.push(false);
                }
            }
        }
    }
}

/// A hull facet's sorted vertices and a vertex off its plane.
type Facet = (Vec<u32>, u32);

/// The flat groups of [`candidates_3d_with`] from the Delaunay faces: the cells, vertex sets of
/// coplanar faces sharing an edge that are cocircular (exact in-sphere test against a point
/// off the plane), and the hull facets with more than three points, vertex sets of coplanar
/// hull faces sharing an edge, each with a vertex off its plane (the apex of one of its faces).
fn flat_groups(d: &Delaunay3, p: &[[f64; 3]], faces: &[[u32; 3]]) -> (Vec<Vec<u32>>, Vec<Facet>) {
    let hull: HashSet<[u32; 3]> = d.hull.iter().map(|t| sorted3(*t)).collect();
    let mut by_edge: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    for (i, t) in faces.iter().enumerate() {
        for (a, b) in [(t[0], t[1]), (t[0], t[2]), (t[1], t[2])] {
            by_edge.entry([a, b]).or_default().push(i);
        }
    }
    let mut cell = (vec![false; faces.len()], (0..faces.len() as u32).collect());
    let mut facet = (vec![false; faces.len()], (0..faces.len() as u32).collect());
    let join = |(joined, parent): &mut (Vec<bool>, Vec<u32>), x: usize, y: usize| {
        let (r1, r2) = (find(parent, x as u32), find(parent, y as u32));
        parent[r1 as usize] = r2;
        joined[x] = true;
        joined[y] = true;
    };
    for (edge, fs) in &by_edge {
        for x in 0..fs.len() {
            for y in x + 1..fs.len() {
                let (f, g) = (faces[fs[x]], faces[fs[y]]);
                let apex = g
                    .iter()
                    .copied()
                    .find(|v| !edge.contains(v))
                    .unwrap_or(g[0]);
                let q = f.map(|v| p[v as usize]);
                let pa = p[apex as usize];
                if raw::orient3d(q[0], q[1], q[2], pa) != 0.0 {
                    continue;
                }
                if hull.contains(&f) && hull.contains(&g) {
                    join(&mut facet, fs[x], fs[y]);
                }
                let n = crate::geom::vec::cross(
                    crate::geom::vec::sub(q[1], q[0]),
                    crate::geom::vec::sub(q[2], q[0]),
                );
                let e = [q[0][0] + n[0], q[0][1] + n[1], q[0][2] + n[2]];
                if raw::orient3d(q[0], q[1], q[2], e) != 0.0
                    && raw::insphere(q[0], q[1], q[2], e, pa) == 0.0
                {
                    join(&mut cell, fs[x], fs[y]);
                }
            }
        }
    }
    let collect = |(joined, parent): &mut (Vec<bool>, Vec<u32>)| {
        let mut groups: HashMap<u32, (Vec<u32>, usize)> = HashMap::new();
        for i in 0..faces.len() {
            if joined[i] {
                let r = find(parent, i as u32);
                let g = groups.entry(r).or_insert((Vec::new(), i));
                g.0.extend_from_slice(&faces[i]);
            }
        }
        let mut v: Vec<(Vec<u32>, usize)> = groups.into_values().collect();
        for g in v.iter_mut() {
            g.0.sort_unstable();
            g.0.dedup();
        }
        v.sort();
        v
    };
    let cells = collect(&mut cell).into_iter().map(|g| g.0).collect();
    let facets = collect(&mut facet)
        .into_iter()
        .filter(|g| g.0.len() > 3)
        .filter_map(|(vs, face)| {
            // the apex of the face's tetrahedron (a hull face has one)
            let t = faces[face];
            d.tets_around_vertex(t[0])
                .into_iter()
                .flat_map(|tet| d.tets[tet as usize])
                .find(|&x| {
                    let q = t.map(|v| p[v as usize]);
                    raw::orient3d(q[0], q[1], q[2], p[x as usize]) != 0.0
                })
                .map(|x| (vs, x))
        })
        .collect();
    (cells, facets)
}

#[cfg(test)]
mod tests {
    //! The group fast paths against the point-by-point reference (bit for bit), and the work
    //! they do on large cocircular / cospherical groups.
    use super::*;
    use crate::delaunay::{d2, d3};
    use crate::geom::{Point2, Point3};

    fn reference<T>(f: impl FnOnce() -> T) -> T {
        POINT_BY_POINT.with(|c| c.set(true));
        let out = f();
        POINT_BY_POINT.with(|c| c.set(false));
        out
    }

    /// Every integer point on the circle x² + y² = r².
    fn circle(r: i64) -> Vec<[f64; 2]> {
        let mut v = Vec::new();
        for x in -r..=r {
            let y2 = r * r - x * x;
            let y = (y2 as f64).sqrt().round() as i64;
            if y * y == y2 {
                v.push([x as f64, y as f64]);
                if y != 0 {
                    v.push([x as f64, -y as f64]);
                }
            }
        }
        v
    }

    /// Every integer point on the sphere x² + y² + z² = r2.
    fn sphere(r2: i64) -> Vec<[f64; 3]> {
        let r = (r2 as f64).sqrt() as i64 + 1;
        let mut v = Vec::new();
        for x in -r..=r {
            for y in -r..=r {
                for z in -r..=r {
                    if x * x + y * y + z * z == r2 {
                        v.push([x as f64, y as f64, z as f64]);
                    }
                }
            }
        }
        v
    }

    fn sets_2d() -> Vec<(&'static str, Vec<[f64; 2]>)> {
        let mut with_outside = circle(25);
        with_outside.extend([[40.0, 0.0], [0.0, -31.0], [30.5, 30.0], [-26.0, 2.0]]);
        let mut rings = circle(5);
        rings.extend(circle(25));
        rings.extend(circle(65).into_iter().map(|q| [q[0] + 0.5, q[1]]));
        vec![
            ("circle 5", circle(5)),
            ("circle 1105", circle(1105)),
            ("circle 25 and outside", with_outside),
            ("three rings", rings),
            (
                "grid 7×6",
                (0..42).map(|i| [(i % 7) as f64, (i / 7) as f64]).collect(),
            ),
        ]
    }

    fn cands2(p: &[[f64; 2]]) -> (Candidates2, u64) {
        let pts: Vec<Point2> = p.iter().map(|q| Point2::new(q[0], q[1])).collect();
        let d = d2::triangulate(&pts).unwrap();
        CHORD_WORK.with(|c| c.set(0));
        let cand = candidates_2d(&d);
        (cand, CHORD_WORK.with(|c| c.get()))
    }

    #[test]
    fn cocircular_chords_equal_the_point_by_point_intervals() {
        for (name, p) in sets_2d() {
            let (fast, _) = cands2(&p);
            let (slow, _) = reference(|| cands2(&p));
            assert!(fast.in_dt.iter().any(|x| !x), "{name}: no chords");
            assert_eq!(fast.edges, slow.edges, "{name}");
            assert_eq!(fast.in_dt, slow.in_dt, "{name}");
            // bit for bit, binding points included
            assert_eq!(fast.intervals, slow.intervals, "{name}");
        }
    }

    /// The issue-17 case: the chords of g exactly cocircular points (all of γ(\[-1,1\],\[0,1\]),
    /// Θ(g²) of them) cost O(1) each, not O(g) (the point-by-point intervals took 242 s for
    /// g ≈ 1000 in `graph --kind gamma-range`).
    #[test]
    fn cocircular_chords_cost_constant_work_each() {
        let p = circle(5 * 13 * 17 * 29);
        let g = p.len() as u64;
        assert_eq!(g, 324);
        let (fast, work) = cands2(&p);
        let chords = fast.in_dt.iter().filter(|x| !**x).count() as u64;
        assert_eq!(chords, g * (g - 1) / 2 - (2 * g - 3));
        let bound = 2 * chords + g * (2 + 64 - (g.leading_zeros() as u64));
        // (the point-by-point reference examines g = 324 points per chord)
        assert!(
            work <= bound,
            "{work} points examined for {chords} chords (bound {bound})"
        );
    }

    fn sets_3d() -> Vec<(&'static str, Vec<[f64; 3]>)> {
        // points outside the sphere (candidates off the group), or one inside (then the groups
        // are other sets: the reference path)
        let mut with_more = sphere(25);
        with_more.extend([
            [9.0, 0.5, 0.0],
            [-2.0, 7.0, 3.0],
            [0.0, 0.0, -5.5],
            [4.0, 4.0, 4.0],
        ]);
        let mut with_inside = sphere(25);
        with_inside.extend([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
        let mut shells = sphere(9);
        shells.extend(sphere(50).into_iter().map(|q| [q[0] + 0.5, q[1], q[2]]));
        vec![
            (
                "circle 65, apexes",
                circle_3d(65, &[[0.0, 0.0, 130.0], [0.0, 0.0, -130.0]]),
            ),
            (
                "circle 25, more points",
                circle_3d(
                    25,
                    &[
                        [0.0, 0.0, 50.0],
                        [0.0, 0.0, -50.0],
                        [3.0, 1.0, 80.0],
                        [-20.0, 4.0, 62.5],
                        [1.0, -2.0, -76.0],
                        [40.0, 0.0, -1.0],
                        [30.0, 30.0, 0.0],
                    ],
                ),
            ),
            ("sphere 25", sphere(25)),
            ("sphere 26", sphere(26)),
            ("sphere 25 and outside", with_more),
            ("sphere 25 and inside", with_inside),
            ("two shells", shells),
            (
                "grid 4×3×3",
                (0..36)
                    .map(|i| [(i % 4) as f64, ((i / 4) % 3) as f64, (i / 12) as f64])
                    .collect(),
            ),
        ]
    }

    /// The integer points of the circle x² + y² = r² in the plane z = 0 and the points `more`
    /// (two at (0, 0, ±2r) make the disc a wall of Delaunay faces: one cocircular cell).
    fn circle_3d(r: i64, more: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut p: Vec<[f64; 3]> = circle(r).into_iter().map(|q| [q[0], q[1], 0.0]).collect();
        p.extend_from_slice(more);
        p
    }

    /// A cocircular cell of g points (all Θ(g³) triples in γ(\[-1,1\],\[0,1\])) costs O(1) per
    /// triple, not O(g): 108 points of a circle with a point above and below, each making a
    /// cospherical cone with it, whose circle triples the cone took point by point (the whole
    /// cone lies on one side of them).
    #[test]
    fn cocircular_triples_in_space_cost_constant_work_each() {
        let p = circle_3d(1105, &[[0.0, 0.0, 2210.0], [0.0, 0.0, -2210.0]]);
        let g = p.len() as u64 - 2;
        assert_eq!(g, 108);
        let pts: Vec<Point3> = p.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let d = d3::triangulate(&pts).unwrap();
        TRIPLE_WORK.with(|c| c.set(0));
        SLOW_TRIPLES.with(|c| c.set(0));
        let cand = candidates_3d(&d);
        let work = TRIPLE_WORK.with(|c| c.get());
        let triples = cand.in_dt.iter().filter(|x| !**x).count() as u64;
        let flat = cand
            .triangles
            .iter()
            .zip(&cand.in_dt)
            .filter(|(t, dt)| !**dt && t.iter().all(|&v| d.points[v as usize].z == 0.0))
            .count() as u64;
        assert_eq!(flat, g * (g - 1) * (g - 2) / 6 - (g - 2));
        let slow = SLOW_TRIPLES.with(|c| c.get());
        assert!(slow < 4 * g, "{slow} triples point by point");
        assert!(
            work <= 40 * triples,
            "{work} points examined for {triples} triples"
        );
    }

    fn cands3(p: &[[f64; 3]]) -> (Candidates3, u64) {
        let pts: Vec<Point3> = p.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let d = d3::triangulate(&pts).unwrap();
        TRIPLE_WORK.with(|c| c.set(0));
        let cand = candidates_3d(&d);
        (cand, TRIPLE_WORK.with(|c| c.get()))
    }

    #[test]
    fn cospherical_triples_equal_the_point_by_point_intervals() {
        for (name, p) in sets_3d() {
            let (fast, _) = cands3(&p);
            let (slow, _) = reference(|| cands3(&p));
            assert!(fast.in_dt.iter().any(|x| !x), "{name}: no group triples");
            assert_eq!(fast.triangles, slow.triangles, "{name}");
            assert_eq!(fast.in_dt, slow.in_dt, "{name}");
            assert_alike(&fast.intervals, &slow.intervals, name);
        }
    }

    /// Intervals equal bit for bit, but for the finite end of a `finite_blocked` one (a hull
    /// facet triangle that only the outer half-space leaves empty), where only the presence of
    /// a binding point matters ([`facet_triangles`]).
    fn assert_alike(fast: &[CenterInterval], slow: &[CenterInterval], name: &str) {
        assert_eq!(fast.len(), slow.len(), "{name}");
        for (a, b) in fast.iter().zip(slow) {
            if a.finite_blocked || b.finite_blocked {
                let key = |x: &CenterInterval| {
                    (
                        x.finite_blocked,
                        x.all_blocked,
                        x.lo_at.is_some(),
                        x.hi_at.is_some(),
                        x.gamma_values(),
                    )
                };
                assert_eq!(key(a), key(b), "{name}");
            } else {
                assert_eq!(a, b, "{name}");
            }
        }
    }

    /// A g×g lattice on the top facet z = 0 of a box, with lattice points below it (and a few
    /// points off the lattice, so that the tetrahedralization is not all cospherical): a hull
    /// facet of g² points whose unit squares are cocircular cells.
    fn facet_box(g: usize) -> Vec<[f64; 3]> {
        let mut p: Vec<[f64; 3]> = (0..g * g)
            .map(|i| [(i % g) as f64, (i / g) as f64, 0.0])
            .collect();
        let s = (g - 1) as f64;
        for z in 1..3 {
            for i in 0..4 {
                p.push([
                    (i % 2) as f64 * s,
                    (i / 2) as f64 * s,
                    -(z as f64) * s / 2.0,
                ]);
            }
        }
        p.extend([
            [0.3, 0.7, -0.4],
            [s * 0.6, s * 0.45, -s * 0.3],
            [1.7, s - 0.9, -0.8],
        ]);
        p
    }

    fn cands3_with(p: &[[f64; 3]], which: GroupTriples) -> (Candidates3, u64) {
        let pts: Vec<Point3> = p.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let d = d3::triangulate(&pts).unwrap();
        TRIPLE_WORK.with(|c| c.set(0));
        let cand = candidates_3d_with(&d, which).0;
        (cand, TRIPLE_WORK.with(|c| c.get()))
    }

    /// The triangles of hull facets, listed from their empty triangles, against every triple
    /// of the facet decided on every point; and without them for [`GroupTriples::Balls`].
    #[test]
    fn facet_triangles_equal_the_definition() {
        let mut slanted = facet_box(5);
        // the same on a plane through no axis (an integer map keeps it exactly flat)
        for q in slanted.iter_mut() {
            *q = [q[0] + q[2], q[1] - 2.0 * q[2], q[2] + q[0] - q[1]];
        }
        for (name, p) in [
            ("facet 4×4", facet_box(4)),
            ("facet 6×6", facet_box(6)),
            ("slanted facet 5×5", slanted),
        ] {
            let (fast, _) = cands3_with(&p, GroupTriples::All);
            let (slow, _) = reference(|| cands3_with(&p, GroupTriples::All));
            assert_eq!(fast.triangles, slow.triangles, "{name}");
            assert_eq!(fast.in_dt, slow.in_dt, "{name}");
            assert_alike(&fast.intervals, &slow.intervals, name);
            let blocked = fast.intervals.iter().filter(|iv| iv.finite_blocked).count();
            assert!(blocked > 0, "{name}");
            // Balls: the same but the half-space-only triangles
            let (balls, _) = cands3_with(&p, GroupTriples::Balls);
            assert_eq!(
                balls.triangles.len(),
                fast.triangles.len() - blocked,
                "{name}"
            );
            let kept: Vec<_> = fast
                .triangles
                .iter()
                .zip(&fast.intervals)
                .filter(|x| !x.1.finite_blocked)
                .map(|x| *x.0)
                .collect();
            assert_eq!(balls.triangles, kept, "{name}");
        }
    }

    /// The fandisk case (issue 17, item 8): a hull facet of g² coplanar points cost O(g⁴)
    /// (every triple against every candidate point; hours for the model's 1597-point facet in
    /// `graph --kind gamma --c0 0 --c1 0.5`). Now its triangles cost O(1) each and nothing at
    /// all when only the triples with an empty ball are asked for.
    #[test]
    fn facet_triangles_cost_constant_work_each() {
        let p = facet_box(10);
        let g2 = 100u64;
        let (all, work) = cands3(&p);
        let extra = all.in_dt.iter().filter(|x| !**x).count() as u64;
        // (the cells' triples are point by point on their few neighbours)
        assert!(
            work <= 2 * extra + 200 * g2,
            "{work} points examined for {extra} group triples"
        );
        let (_, work) = cands3_with(&p, GroupTriples::Balls);
        assert!(work <= 200 * g2, "{work} points examined");
    }

    /// The issue-17 case: the triples of g exactly cospherical points (all of
    /// γ(\[-1,1\],\[0,1\]), Θ(g³) of them) cost O(1) each on average, not O(g) (144 points took
    /// 48 s in `graph`, any kind).
    #[test]
    fn cospherical_triples_cost_constant_work_each() {
        let p = sphere(89);
        let g = p.len() as u64;
        assert_eq!(g, 144);
        let (fast, work) = cands3(&p);
        let triples = fast.in_dt.iter().filter(|x| !**x).count() as u64;
        assert!(triples > g * (g - 1) * (g - 2) / 6 - 4 * g * g);
        // (the group's hull faces, whose triples have the group on one side, are point by
        // point: 1884 triples here)
        assert!(SLOW_TRIPLES.with(|c| c.get()) < 4 * g * g);
        // the point-by-point reference examines 144 points per triple
        assert!(
            work <= 40 * triples,
            "{work} points examined for {triples} triples"
        );
    }

    #[test]
    fn faces_only_candidates_skip_the_group_triples() {
        let p = sphere(26);
        let pts: Vec<Point3> = p.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let d = d3::triangulate(&pts).unwrap();
        let all = candidates_3d(&d);
        TRIPLE_WORK.with(|c| c.set(0));
        let (faces, groups) = candidates_3d_with(&d, GroupTriples::Faces);
        assert_eq!(TRIPLE_WORK.with(|c| c.get()), 0);
        assert!(faces.in_dt.iter().all(|x| *x));
        let dt: Vec<_> = all
            .triangles
            .iter()
            .zip(&all.in_dt)
            .filter(|x| *x.1)
            .collect();
        assert_eq!(dt.len(), faces.triangles.len());
        // the sphere, and the flat groups of its circles
        assert!(groups.iter().any(|g| g.len() == p.len()));
    }
}

//! The graph family as one entry point: [`graph_2d`] and [`graph_3d`] build any [`Kind`] from
//! the Delaunay triangulation (Veltkamp 1992 §2.2 and ch. 3; construction per [`super::fast`]).
//!
//! Complexities after the O(N log N) triangulation: CP, NNG, hull, Delaunay, GG, α (a ≤ 0), β_c/γ
//! with parameters ≥ 0: O(N); EMST (Borůvka on the Delaunay edges): O(N log N) worst case, about
//! 2.5 passes over the edges on evenly spread points; RNG, lune-based β (b > 0): O(N·k) with k
//! the points in the box of a lune — queried only for the halves of the lune that the empty
//! circumdiscs of the edge's two Delaunay triangles do not cover ([`super::lune`]); SIG: O(N·k)
//! with k the points in the edge's neighbourhood (grid queries); ∞-SG: O(N) filter plus
//! O(N) per surviving edge; α (a > 0): O(h³) over the h hull vertices; γ beyond the Delaunay
//! triangulation: see [`super::fast::beyond_dt_2d`] and [`super::beyond3::beyond_dt_3d`]. 3D γ
//! with a parameter −1 (nearly every triple) uses the brute force of V Thm 3.1 and is limited to
//! [`BRUTE_LIMIT_3D`] points; 3D α with a > 0 works on the hull vertices only (a ball of radius
//! 1/a containing every point through a triangle touches only hull vertices), O(h⁴) in the worst
//! case, limited to [`ALPHA_HULL_LIMIT_3D`] hull vertices; degenerate (coplanar) 3D input uses the
//! brute force limited to [`BRUTE_LIMIT_3D`] points.
//!
//! In 2D the kinds made of Delaunay edges (Delaunay, GG, RNG, lune-based β, α with a < 0, γ within
//! the triangulation) decide each edge once in parallel and drop it straight into its bucket of
//! smaller input index ([`super::fast::decide_sorted_2d`]): the output comes out sorted without
//! a global sort of the edge list (nor a gather of the γ-values).

use super::beyond3;
use super::brute::{self, in_slab};
use super::fast;
use super::gamma::{in_gamma, in_gamma_range, CenterInterval};
use super::lune::LuneGrid;
use super::GraphError;
use crate::delaunay::{d2, d3};
use crate::geom::distance::{cmp_dist2, dot_sign, in_lune_ball, sum_of_roots_exceeds};
use crate::geom::grid::PointGrid as Grid;
use crate::geom::vec::dist2;
use crate::geom::{Point2, Point3};
use rayon::prelude::*;
use std::cmp::Ordering;

type Result<T, E = GraphError> = std::result::Result<T, E>;

/// Largest input for the brute-force 3D constructions (degenerate input, γ with a parameter −1).
pub const BRUTE_LIMIT_3D: usize = 150;

/// Largest number of hull vertices for 3D α-shapes with a > 0 (O(h³) triples, each checked
/// against the hull vertices with early exit: O(h⁴) only when most triples pass, e.g. points on
/// a sphere of radius 1/a).
pub const ALPHA_HULL_LIMIT_3D: usize = 300;

/// Which graph to build.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// Closest pairs (Def. 2.3).
    ClosestPairs,
    /// Nearest neighbours graph with all ties (Def. 2.4).
    Nng,
    /// Euclidean minimum spanning tree (Def. 2.5).
    Emst,
    /// Infinite strip graph (Def. 2.6).
    Strip,
    /// Sphere of influence graph (Def. 2.7).
    Sig,
    /// Relative neighbourhood graph (Def. 2.8).
    Rng,
    /// Gabriel graph (Def. 2.9).
    Gabriel,
    /// Convex hull (Def. 2.10): edges in 2D, triangles in 3D.
    Hull,
    /// The Delaunay triangulation: its edges in 2D, its triangles in 3D.
    Delaunay,
    /// α(a)-shape (Defs. 2.12–2.14).
    Alpha(f64),
    /// Circle-based β-skeleton (Def. 2.15), b ∈ [−1, 1]; 2D only (= γ(b, b)).
    BetaCircle(f64),
    /// Lune-based β-skeleton (Def. 2.16), b ∈ [−1, 1] in 2D, b ∈ [0, 1] in 3D.
    BetaLune(f64),
    /// γ(c₀, c₁) with |c₀| ≤ |c₁| (Defs. 3.1–3.2).
    Gamma(f64, f64),
    /// γ(\[c₀,c₁\],\[c₂,c₃\]) (Def. 3.3).
    GammaRange([f64; 4]),
}

impl Kind {
    /// The CLI name of the kind.
    ///
    /// ```rust
    /// use morpho::graphs::Kind;
    /// assert_eq!(Kind::BetaLune(0.5).name(), "beta-lune");
    /// assert_eq!(Kind::GammaRange([-1.0, 1.0, 0.0, 1.0]).name(), "gamma-range");
    /// ```
    pub fn name(&self) -> &'static str {
        match self {
            Kind::ClosestPairs => "closest-pairs",
            Kind::Nng => "nng",
            Kind::Emst => "emst",
            Kind::Strip => "strip",
            Kind::Sig => "sig",
            Kind::Rng => "rng",
            Kind::Gabriel => "gabriel",
            Kind::Hull => "hull",
            Kind::Delaunay => "delaunay",
            Kind::Alpha(_) => "alpha",
            Kind::BetaCircle(_) => "beta-circle",
            Kind::BetaLune(_) => "beta-lune",
            Kind::Gamma(..) => "gamma",
            Kind::GammaRange(_) => "gamma-range",
        }
    }
    /// Checks the parameter ranges: β and γ parameters in [−1, 1], |c₀| ≤ |c₁| for γ(c₀, c₁),
    /// ordered ranges for γ(\[c₀,c₁\],\[c₂,c₃\]), a finite α. [`graph_2d`] and [`graph_3d`] call
    /// it first; the CLI calls it before reading the points.
    ///
    /// ```rust
    /// use morpho::graphs::{GraphError, Kind};
    /// assert!(Kind::Gamma(0.2, 0.5).validate().is_ok());
    /// assert_eq!(
    ///     Kind::Gamma(0.5, 0.2).validate(),
    ///     Err(GraphError::GammaOrder { c0: 0.5, c1: 0.2 })
    /// );
    /// assert!(Kind::Alpha(f64::NAN).validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        let unit = |v: f64, what: &'static str| -> Result<()> {
            if !(-1.0..=1.0).contains(&v) {
                Err(GraphError::ParameterOutOfRange {
                    name: what,
                    value: v,
                })
            } else {
                Ok(())
            }
        };
        match *self {
            Kind::Alpha(a) if !a.is_finite() => Err(GraphError::AlphaNotFinite { value: a }),
            Kind::BetaCircle(b) | Kind::BetaLune(b) => unit(b, "b"),
            Kind::Gamma(c0, c1) => {
                unit(c0, "c0")?;
                unit(c1, "c1")?;
                if c0.abs() > c1.abs() {
                    return Err(GraphError::GammaOrder { c0, c1 });
                }
                Ok(())
            }
            Kind::GammaRange(r) => {
                for (v, name) in r.iter().zip(["c0", "c1", "c2", "c3"]) {
                    unit(*v, name)?;
                }
                if r[0] > r[1] || r[2] > r[3] {
                    return Err(GraphError::GammaRangeOrder { range: r });
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }
}

/// A geometric graph on a point set; indices refer to the input points (a duplicated point is
/// represented by its first occurrence).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Graph {
    /// Dimension of the points (2 or 3).
    pub dim: usize,
    /// Edges `[i, j]`, i < j, sorted (2D graphs, and 3D graphs made of edges).
    pub edges: Vec<[u32; 2]>,
    /// Triangles `[i, j, k]`, sorted (3D hull, Delaunay, α-shape and γ-graphs).
    pub triangles: Vec<[u32; 3]>,
    /// For the γ kinds: the γ-values (c₀′, c₁′) of each simplex, aligned with `edges` (2D) or
    /// `triangles` (3D).
    pub gamma: Vec<[f64; 2]>,
}

/// Maps edges (vertex indices) to input indices and sorts them by (smaller, larger) input
/// index with a counting sort on the smaller one, dropping repeats; returns the sorted edges
/// and, for each, its position in `e`. O(N + E) (plus tiny per-vertex sorts).
fn sort_edges(
    input_of_vertex: &[u32],
    n_input: usize,
    e: &[[u32; 2]],
) -> (Vec<[u32; 2]>, Vec<u32>) {
    let mapped: Vec<[u32; 2]> = e
        .par_iter()
        .map(|k| {
            let (a, b) = (
                input_of_vertex[k[0] as usize],
                input_of_vertex[k[1] as usize],
            );
            [a.min(b), a.max(b)]
        })
        .collect();
    let mut start = vec![0u32; n_input + 1];
    for m in &mapped {
        start[m[0] as usize + 1] += 1;
    }
    for i in 0..n_input {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut slot = vec![(0u32, 0u32); mapped.len()];
    for (i, m) in mapped.iter().enumerate() {
        let f = &mut fill[m[0] as usize];
        slot[*f as usize] = (m[1], i as u32);
        *f += 1;
    }
    let mut edges = Vec::with_capacity(mapped.len());
    let mut from = Vec::with_capacity(mapped.len());
    for a in 0..n_input {
        let bucket = &mut slot[start[a] as usize..start[a + 1] as usize];
        bucket.sort_unstable();
        let mut last = None;
        for &(b, i) in bucket.iter() {
            if last != Some(b) {
                edges.push([a as u32, b]);
                from.push(i);
                last = Some(b);
            }
        }
    }
    (edges, from)
}

/// The 2D graph from edges in vertex indices (with their γ-values for the γ kinds: `gamma`
/// empty or aligned with `e`).
fn finish2(d: &d2::Delaunay2, e: Vec<[u32; 2]>, gamma: Vec<[f64; 2]>) -> Graph {
    let (edges, from) = sort_edges(&d.input_of_vertex, d.vertex_of_input.len(), &e);
    let gamma = if gamma.len() == e.len() && !e.is_empty() {
        from.iter().map(|&i| gamma[i as usize]).collect()
    } else {
        vec![]
    };
    Graph {
        dim: 2,
        edges,
        triangles: vec![],
        gamma,
    }
}

/// A nearest neighbour of every vertex over the given (Delaunay) edges, by exact distance
/// comparisons (ties: the first found). `u32::MAX` for a vertex without edges.
fn nearest_over<const D: usize>(p: &[[f64; D]], edges: &[[u32; 2]]) -> Vec<u32> {
    let mut nn = vec![u32::MAX; p.len()];
    for e in edges {
        for (v, w) in [(e[0], e[1]), (e[1], e[0])] {
            let cur = nn[v as usize];
            let (pv, pw) = (&p[v as usize], &p[w as usize]);
            if cur == u32::MAX || cmp_dist2(pv, pw, pv, &p[cur as usize]) == Ordering::Less {
                nn[v as usize] = w;
            }
        }
    }
    nn
}

/// Relative band within which two float squared lengths may be in the wrong order: each carries
/// a relative error below (D + 2)ε (rounded differences, squares and sums), so floats further
/// apart than this are ordered correctly; closer ones are compared exactly.
const NEAR_TIE: f64 = 32.0 * f64::EPSILON;

/// An exact nearest neighbour of every vertex of a non-collinear 2D triangulation (among its
/// Delaunay neighbours, which contain one) with its float squared distance. The triangles are
/// split into one block per thread; each block offers its edges to both ends in triangle order
/// (spatially coherent), then the blocks' answers are merged per vertex. Float comparisons
/// decide unless two candidates are within [`NEAR_TIE`]; then [`cmp_dist2`] does (ties: the
/// first offered).
fn nearest_tri(d: &d2::Delaunay2, p: &[[f64; 2]]) -> (Vec<u32>, Vec<f64>) {
    let n = p.len();
    let offer = |near: &mut (f64, u32), v: u32, w: u32, x: f64| {
        let pv = &p[v as usize];
        let take = near.1 == u32::MAX
            || x < near.0 * (1.0 - 2.0 * NEAR_TIE)
            || (x <= near.0 * (1.0 + 2.0 * NEAR_TIE)
                && cmp_dist2(pv, &p[w as usize], pv, &p[near.1 as usize]) == Ordering::Less);
        if take {
            *near = (x, w);
        }
    };
    let size = d
        .triangles
        .len()
        .div_ceil(rayon::current_num_threads().max(1))
        .max(1);
    let parts: Vec<Vec<(f64, u32)>> = d
        .triangles
        .par_chunks(size)
        .enumerate()
        .map(|(k, tris)| {
            let mut near = vec![(f64::INFINITY, u32::MAX); n];
            for (i, tri) in tris.iter().enumerate() {
                let t = k * size + i;
                let nb = &d.neighbors[t];
                for j in 0..3 {
                    if nb[j] == crate::util::NONE || nb[j] as usize > t {
                        let (a, b) = (tri[(j + 1) % 3], tri[(j + 2) % 3]);
                        let x = dist2(p[a as usize], p[b as usize]);
                        offer(&mut near[a as usize], a, b, x);
                        offer(&mut near[b as usize], b, a, x);
                    }
                }
            }
            near
        })
        .collect();
    (0..n)
        .into_par_iter()
        .map(|v| {
            let mut near = parts[0][v];
            for part in &parts[1..] {
                let (x, w) = part[v];
                if w != u32::MAX {
                    offer(&mut near, v as u32, w, x);
                }
            }
            (near.1, near.0)
        })
        .unzip()
}

/// An edge during Borůvka's algorithm: float squared length, the current components of its
/// ends, and its two vertices.
#[derive(Clone, Copy)]
struct BEdge {
    w: f64,
    a: u32,
    b: u32,
    e: [u32; 2],
}

impl BEdge {
    fn new<const D: usize>(p: &[[f64; D]], a: u32, b: u32) -> Self {
        BEdge {
            w: dist2(p[a as usize], p[b as usize]),
            a,
            b,
            e: [a, b],
        }
    }
}

/// The least edge of a component so far: its float squared length, the component at its other
/// end and its position in the edge list (16 bytes, so that an update touches one cache line).
#[derive(Clone, Copy)]
struct Least {
    w: f64,
    t: u32,
    j: u32,
}

/// The Delaunay edges of a non-collinear 2D triangulation for [`emst_boruvka`], in triangle
/// order (spatially coherent: the triangles are created along the insertion order), written in
/// parallel over blocks of triangles straight into their final places (an edge is reported by
/// the smaller of its two triangles).
fn tri_edges(d: &d2::Delaunay2, p: &[[f64; 2]]) -> Vec<BEdge> {
    const BLOCK: usize = 1 << 14;
    let reports = |t: usize, j: usize| {
        let nb = d.neighbors[t][j];
        nb == crate::util::NONE || nb as usize > t
    };
    let counts: Vec<usize> = (0..d.triangles.len().div_ceil(BLOCK))
        .into_par_iter()
        .map(|k| {
            (k * BLOCK..((k + 1) * BLOCK).min(d.triangles.len()))
                .map(|t| (0..3).filter(|&j| reports(t, j)).count())
                .sum()
        })
        .collect();
    let blank = BEdge {
        w: 0.0,
        a: 0,
        b: 0,
        e: [0; 2],
    };
    let mut es = vec![blank; counts.iter().sum()];
    let mut rest: &mut [BEdge] = &mut es;
    let mut parts = Vec::with_capacity(counts.len());
    for &c in &counts {
        let (head, tail) = rest.split_at_mut(c);
        parts.push(head);
        rest = tail;
    }
    parts.into_par_iter().enumerate().for_each(|(k, out)| {
        let mut slot = out.iter_mut();
        for t in k * BLOCK..((k + 1) * BLOCK).min(d.triangles.len()) {
            let tri = d.triangles[t];
            for j in 0..3 {
                if reports(t, j) {
                    if let Some(x) = slot.next() {
                        *x = BEdge::new(p, tri[(j + 1) % 3], tri[(j + 2) % 3]);
                    }
                }
            }
        }
    });
    es
}

/// Euclidean minimum spanning tree over the edges `es` (a superset of one EMST: the Gabriel or
/// Delaunay edges, in vertex indices) in the exact order of (length, smaller input index, larger
/// input index): a strict total order, so the tree is the unique minimum for it whatever the
/// algorithm (the one Kruskal's algorithm finds when the ties are sorted by input indices).
///
/// Borůvka's algorithm with contraction: every round each component picks its least outgoing
/// edge (all of them are tree edges; under a strict total order they form a forest whose only
/// cycles are the 2-cycles of an edge chosen from both sides), the components are merged along
/// them, renumbered densely in the order of their smallest member (spatially coherent, as the
/// vertices are in Hilbert order) and the edges inside a component are dropped. The first round
/// links every vertex to its nearest neighbour. Comparisons use the float squared lengths and
/// fall back to [`cmp_dist2`] (then the input indices) only within [`NEAR_TIE`] of a tie. Every
/// round at least halves the components; the edge list shrinks with them (it keeps parallel
/// edges between two components: O(E log N) in the worst case; on uniform points about 2.5E
/// edge visits in all, by sequential passes).
fn emst_boruvka<const D: usize>(
    p: &[[f64; D]],
    input: &[u32],
    mut es: Vec<BEdge>,
) -> Vec<[u32; 2]> {
    const NO: u32 = u32::MAX;
    let n = p.len();
    let mut out = Vec::with_capacity(n.saturating_sub(1));
    if n < 2 {
        return out;
    }
    let key = |e: &[u32; 2]| {
        let (a, b) = (input[e[0] as usize], input[e[1] as usize]);
        ((a.min(b) as u64) << 32) | a.max(b) as u64
    };
    // (w, e) strictly before (v, f) in the total order, for distinct edges e, f
    let before = |w: f64, e: &[u32; 2], v: f64, f: &[u32; 2]| -> bool {
        if (w - v).abs() > NEAR_TIE * (w + v) {
            return w < v;
        }
        let [a, b, c, d] = [e[0], e[1], f[0], f[1]].map(|x| &p[x as usize]);
        cmp_dist2(a, b, c, d).then(key(e).cmp(&key(f))) == Ordering::Less
    };
    let mut ncomp = n;
    let none = Least {
        w: 0.0,
        t: NO,
        j: NO,
    };
    let mut least = vec![none; n];
    let mut parent = vec![0u32; n];
    let mut first = true;
    while ncomp > 1 && !es.is_empty() {
        least[..ncomp].fill(none);
        for (j, x) in es.iter().enumerate() {
            if x.a == x.b {
                continue; // (a loop in the input; dropped below)
            }
            for (c, t) in [(x.a as usize, x.b), (x.b as usize, x.a)] {
                let l = &mut least[c];
                let take = l.t == NO
                    || x.w < l.w * (1.0 - 2.0 * NEAR_TIE)
                    || (x.w <= l.w * (1.0 + 2.0 * NEAR_TIE)
                        && before(x.w, &x.e, l.w, &es[l.j as usize].e));
                if take {
                    *l = Least {
                        w: x.w,
                        t,
                        j: j as u32,
                    };
                }
            }
        }
        // link every component to the other end of its least edge; of an edge chosen from both
        // ends, the smaller component becomes the root
        for c in 0..ncomp {
            let t = least[c].t;
            if t == NO || (least[t as usize].t == c as u32 && (c as u32) < t) {
                parent[c] = c as u32;
            } else {
                parent[c] = t;
                // (in the first round the components are the vertices themselves)
                out.push(if first {
                    [c as u32, t]
                } else {
                    es[least[c].j as usize].e
                });
            }
        }
        // roots (with path compression), dense labels in root order (in the roots' `least.t`),
        // then every component's label (in `parent`)
        let mut next = 0u32;
        for c in 0..ncomp {
            let mut r = c as u32;
            while parent[r as usize] != r {
                r = parent[r as usize];
            }
            let mut x = c as u32;
            while parent[x as usize] != r {
                let up = parent[x as usize];
                parent[x as usize] = r;
                x = up;
            }
            if r as usize == c {
                least[c].t = next;
                next += 1;
            }
        }
        for c in 0..ncomp {
            parent[c] = least[parent[c] as usize].t;
        }
        ncomp = next as usize;
        first = false;
        let label = &parent;
        es.retain_mut(|e| {
            e.a = label[e.a as usize];
            e.b = label[e.b as usize];
            e.a != e.b
        });
    }
    out
}

/// The sphere-of-influence graph (V Def. 2.7) given a nearest neighbour `nn[v]` of every vertex
/// and its float squared distance `r2[v]`: the pairs with |ab| < r_a + r_b.
///
/// A pair is found from the end with the larger float radius (ties: the larger vertex), which sees the
/// other within r_a + r_b ≤ 2·r_a: a grid query of half-width 2·r_a around it. The points,
/// radii and vertices are laid out in the grid's cell order, so a query reads a few contiguous
/// runs; the queries run in parallel in that order. Each pair is decided by floats with a wide
/// margin, and exactly ([`sum_of_roots_exceeds`]) within it. O(N·k) with k the points in a
/// query box (a handful for evenly spread points).
fn sig_edges<const D: usize>(p: &[[f64; D]], nn: &[u32], r2: &[f64]) -> Vec<[u32; 2]> {
    let n = p.len();
    if n < 2 {
        return vec![];
    }
    let grid = Grid::new(p, 1.0);
    // per slot (cell order): point, radius, vertex
    let slots: Vec<([f64; D], f64, u32)> = grid
        .items()
        .par_iter()
        .map(|&v| (p[v as usize], r2[v as usize].sqrt(), v))
        .collect();
    // the relative error of the float test below is a few ε; 1e-9 is a wide margin (and values
    // near the bottom of the float range always go to the exact test)
    const MARGIN: f64 = 1e-9;
    const TINY: f64 = 1e-250;
    slots
        .par_iter()
        .fold(Vec::new, |mut out, &(pa, ra, a)| {
            let reach = 2.0 * ra * (1.0 + MARGIN);
            let (mut lo, mut hi) = (pa, pa);
            for k in 0..D {
                lo[k] -= reach;
                hi[k] += reach;
            }
            grid.for_each_run(lo, hi, |run| {
                for &(pb, rb, b) in &slots[run] {
                    let d2 = dist2(pa, pb);
                    let s = ra + rb;
                    let s2 = s * s;
                    // (most candidates are rejected here) found from the end with the larger
                    // (radius, vertex): sqrt is monotone, so r_b ≤ r_a up to rounding
                    if d2 > s2 * (1.0 + MARGIN) || rb > ra || (rb == ra && b >= a) {
                        continue;
                    }
                    let inside = if d2 < s2 * (1.0 - MARGIN) && s2 > TINY {
                        true
                    } else {
                        let (na, nb) = (&p[nn[a as usize] as usize], &p[nn[b as usize] as usize]);
                        sum_of_roots_exceeds(&pa, &pb, na, nb)
                    };
                    if inside {
                        out.push([a, b]);
                    }
                }
                true
            });
            out
        })
        .reduce(Vec::new, |mut x, y| {
            x.extend(y);
            x
        })
}

/// The classic graphs that depend only on distances, in D dimensions, from the Delaunay edges
/// and the Gabriel edges (EMST ⊆ RNG ⊆ lune-β ⊆ GG and ∞-SG ⊆ GG, V Fig. 3.2). Every decision
/// is exact ([`crate::geom::distance`]); `input` maps vertices to input indices (tie order).
fn classic<const D: usize>(
    p: &[[f64; D]],
    input: &[u32],
    dt_edges: &[[u32; 2]],
    gabriel: &[[u32; 2]],
    kind: Kind,
) -> Result<Vec<[u32; 2]>> {
    let n = p.len();
    if n < 2 {
        return Ok(vec![]);
    }
    Ok(match kind {
        Kind::Nng | Kind::ClosestPairs => {
            let nn = nearest_over(p, dt_edges);
            let is_nn = |v: u32, w: u32| {
                let (pv, pw) = (&p[v as usize], &p[w as usize]);
                cmp_dist2(pv, pw, pv, &p[nn[v as usize] as usize]) == Ordering::Equal
            };
            let mut e: Vec<[u32; 2]> = dt_edges
                .par_iter()
                .copied()
                .filter(|e| is_nn(e[0], e[1]) || is_nn(e[1], e[0]))
                .collect();
            if kind == Kind::ClosestPairs {
                let len = |e: &[u32; 2]| (&p[e[0] as usize], &p[e[1] as usize]);
                let mut min: Option<[u32; 2]> = None;
                for x in &e {
                    let (a, b) = len(x);
                    if min.map_or(true, |m| {
                        let (c, d) = len(&m);
                        cmp_dist2(a, b, c, d) == Ordering::Less
                    }) {
                        min = Some(*x);
                    }
                }
                if let Some(m) = min {
                    let (c, d) = len(&m);
                    e.retain(|x| {
                        let (a, b) = len(x);
                        cmp_dist2(a, b, c, d) == Ordering::Equal
                    });
                }
            }
            e
        }
        Kind::Emst => emst_boruvka(
            p,
            input,
            dt_edges
                .par_iter()
                .map(|e| BEdge::new(p, e[0], e[1]))
                .collect(),
        ),
        Kind::Rng | Kind::BetaLune(_) => {
            let b = match kind {
                Kind::BetaLune(b) => b,
                _ => 0.5,
            };
            if b >= 1.0 {
                return Ok(strip(p, gabriel));
            }
            let grid = Grid::new(p, 2.0);
            gabriel
                .par_iter()
                .copied()
                .filter(|e| lune_empty_grid(p, &grid, *e, b))
                .collect()
        }
        Kind::Sig => {
            let nn = nearest_over(p, dt_edges);
            let r2: Vec<f64> = (0..n).map(|a| dist2(p[a], p[nn[a] as usize])).collect();
            sig_edges(p, &nn, &r2)
        }
        Kind::Strip => strip(p, gabriel),
        _ => return Err(GraphError::NotDistanceGraph { kind: kind.name() }),
    })
}

/// True when the open lune of the pair e (V Def. 2.16, b ∈ [0, 1)) contains no point, by a
/// grid query around its midpoint with exact [`in_lune_ball`] tests.
fn lune_empty_grid<const D: usize>(
    p: &[[f64; D]],
    grid: &Grid<'_, D>,
    e: [u32; 2],
    b: f64,
) -> bool {
    let (u, v) = (&p[e[0] as usize], &p[e[1] as usize]);
    let len = dist2(*u, *v).sqrt();
    let rad = len / (2.0 * (1.0 - b));
    let mut m = [0.0; D];
    for t in 0..D {
        m[t] = 0.5 * (u[t] + v[t]);
    }
    // the lune lies within max(len/2, √(R² − (R − len/2)²)) of the midpoint
    let reach =
        (0.5 * len).max((rad * rad - (rad - 0.5 * len).powi(2)).max(0.0).sqrt()) * (1.0 + 1e-9);
    grid.for_each_within(m, reach, |x| {
        if x == e[0] || x == e[1] {
            return true;
        }
        let q = &p[x as usize];
        !(in_lune_ball(q, u, v, b) && in_lune_ball(q, v, u, b))
    })
}

/// ∞-SG ⊆ GG (the open slab contains the Gabriel ball): test each Gabriel edge's slab, with
/// early exit at the first point inside (exact signs).
fn strip<const D: usize>(p: &[[f64; D]], gabriel: &[[u32; 2]]) -> Vec<[u32; 2]> {
    gabriel
        .par_iter()
        .copied()
        .filter(|e| {
            let (u, v) = (&p[e[0] as usize], &p[e[1] as usize]);
            !p.iter().any(|x| in_slab(u, v, x))
        })
        .collect()
}

/// Largest coordinate magnitudes (as powers of two) used as they are: the graph predicates
/// (degree ≤ 5 in coordinate differences, on floats and expansions) neither over- nor underflow
/// for sets whose largest magnitude M lies in [2⁻¹⁰⁰, 2¹⁰⁰].
const SAFE_EXPONENT: i32 = 100;

/// For a set whose largest coordinate magnitude `m` lies outside the safe range
/// [2⁻¹⁰⁰, 2¹⁰⁰]: the power of two that brings it near 1 (exact: the graphs, which are
/// invariant under scaling, do not change; `None` inside the range, where nothing is scaled).
/// An error when the scaling would flush a non-zero coordinate below the normal range (the
/// set spans more magnitudes than the exact predicates can hold).
fn extreme_scale(coords: impl Iterator<Item = f64> + Clone) -> Result<Option<f64>> {
    let m = coords.clone().fold(0.0f64, |a, x| a.max(x.abs()));
    let safe = 2f64.powi(-SAFE_EXPONENT)..=2f64.powi(SAFE_EXPONENT);
    if m == 0.0 || !m.is_finite() || safe.contains(&m) {
        return Ok(None);
    }
    let s = crate::geom::exact::power_of_two_scale(m);
    if s == 1.0 {
        return Ok(None);
    }
    if coords
        .into_iter()
        .any(|x| x != 0.0 && (x * s).abs() < f64::MIN_POSITIVE)
    {
        return Err(GraphError::ScaleRange { largest: m });
    }
    Ok(Some(s))
}

/// The kind for points multiplied by `s`: the α-shape's a is an inverse length (a/s, exact for
/// a power of two); every other parameter is scale-free.
fn scaled_kind(kind: Kind, s: f64) -> Result<Kind> {
    match kind {
        Kind::Alpha(a) if !(a / s).is_finite() => Err(GraphError::AlphaOutOfScale { value: a }),
        Kind::Alpha(a) => Ok(Kind::Alpha(a / s)),
        k => Ok(k),
    }
}

/// Builds the graph of kind `kind` on 2D points (duplicates merged; indices are input indices,
/// a duplicate represented by its first occurrence). Parameters are validated
/// ([`Kind::validate`]). Complexity per kind: see [`crate::graphs`] (O(N log N) for the
/// triangulation, then mostly linear).
///
/// Errors: a parameter out of range, points the triangulation refuses
/// ([`GraphError::Delaunay`]), coordinates spanning more magnitudes than the exact predicates
/// handle.
///
/// ```rust
/// use morpho::graphs::{graph_2d, Kind};
/// use morpho::geom::Point2;
/// // six points on a line and one above: the Gabriel graph keeps the five line edges
/// let mut p: Vec<Point2> = (0..6).map(|i| Point2::new(i as f64, 0.0)).collect();
/// p.push(Point2::new(2.5, 10.0));
/// let g = graph_2d(&p, Kind::Gabriel).unwrap();
/// assert!((0..5u32).all(|i| g.edges.contains(&[i, i + 1])));
/// // γ(0, 0) (the smallest discs) is the Gabriel graph, with the γ-values of every edge
/// let gg = graph_2d(&p, Kind::Gabriel).unwrap();
/// let g0 = graph_2d(&p, Kind::Gamma(0.0, 0.0)).unwrap();
/// assert_eq!(g0.edges, gg.edges);
/// assert_eq!(g0.gamma.len(), g0.edges.len());
/// // EMST: a tree
/// assert_eq!(graph_2d(&p, Kind::Emst).unwrap().edges.len(), p.len() - 1);
/// ```
///
/// Sets at extreme scales (largest coordinate outside [2⁻¹⁰⁰, 2¹⁰⁰]) are first multiplied by
/// the power of two that brings them near 1: exact, so the graph is the
/// same, and no predicate or float filter over- or underflows (at 1e300 every squared
/// distance is ∞, which sent every pair to the exact fallback — and that overflowed too).
pub fn graph_2d(points: &[Point2], kind: Kind) -> Result<Graph> {
    kind.validate()?;
    if let Some(s) = extreme_scale(points.iter().flat_map(|q| [q.x, q.y]))? {
        let scaled: Vec<Point2> = points.iter().map(|q| q * s).collect();
        return graph_2d(&scaled, scaled_kind(kind, s)?);
    }
    // β_c(b) = γ(b, b) (V §3.2), and the lune-based skeleton with b < 0 is the circle-based one
    if let Kind::BetaCircle(b) | Kind::BetaLune(b) = kind {
        if matches!(kind, Kind::BetaCircle(_)) || b < 0.0 {
            let mut g = graph_2d(points, Kind::Gamma(b, b))?;
            g.gamma.clear();
            return Ok(g);
        }
    }
    // the lune-based kinds (b ∈ (0, 1); RNG: b = ½) query a grid over the points, built from the
    // input points on another thread while the (mostly sequential) triangulation runs here
    let lune_b = match kind {
        Kind::Rng => Some(0.5),
        Kind::BetaLune(b) if b > 0.0 && b < 1.0 => Some(b),
        _ => None,
    };
    let ip: Vec<[f64; 2]> = match lune_b {
        Some(_) => points.iter().map(|q| [q.x, q.y]).collect(),
        None => vec![],
    };
    let (d, lune_grid) = std::thread::scope(|s| {
        let grid = lune_b.map(|_| s.spawn(|| LuneGrid::new(&ip)));
        let d = d2::triangulate(points);
        // (a grid thread that failed is replaced by one built here)
        let grid = grid.map(|h| h.join().unwrap_or_else(|_| LuneGrid::new(&ip)));
        (d, grid)
    });
    let d = d?;
    let p = fast::coords2(&d);
    let dt_edges = || -> Vec<[u32; 2]> {
        if d.collinear {
            d.hull
                .windows(2)
                .map(|w| [w[0].min(w[1]), w[0].max(w[1])])
                .collect()
        } else {
            fast::dt_edges(&d).map(|e| [e.a, e.b]).collect()
        }
    };
    // the edges of a non-collinear triangulation as sorted input indices (no sort needed)
    let sorted = |edges: Vec<[u32; 2]>, gamma: Vec<[f64; 2]>| Graph {
        dim: 2,
        edges,
        triangles: vec![],
        gamma,
    };
    // γ kinds: decide every candidate edge in parallel, keeping its γ-values (computed once and
    // handed to `decide`)
    type Decide<'a> = dyn Fn(&CenterInterval, (f64, f64)) -> bool + Sync + 'a;
    let gamma_kind = |decide: &Decide<'_>, beyond: Option<f64>| {
        let keep = |e: [u32; 2], iv: &CenterInterval| {
            let v = iv.gamma_values()?;
            decide(iv, v).then_some((e, [v.0, v.1]))
        };
        let kept: Vec<([u32; 2], [f64; 2])> = match beyond {
            // the Delaunay-subgraph part streams, vertex star by vertex star in input order
            None if !d.collinear => {
                let (e, g) =
                    fast::filter_candidates_sorted_2d(&d, &p, |e, iv| keep(e, iv).map(|x| x.1));
                return sorted(e, g);
            }
            // beyond the triangulation the candidates are needed anyway (as the edges that
            // exist), so they are built once and filtered
            None => fast::filter_candidates_2d(&d, |e, iv, _| keep(e, iv)),
            Some(c) => {
                let cand = fast::candidates_2d(&d);
                let (be, bi) = fast::beyond_dt_2d(&d, &cand, c);
                let dt = cand.edges.iter().zip(&cand.intervals);
                dt.chain(be.iter().zip(&bi))
                    .filter_map(|(e, iv)| keep(*e, iv))
                    .collect()
            }
        };
        let (e, g): (Vec<[u32; 2]>, Vec<[f64; 2]>) = kept.into_iter().unzip();
        finish2(&d, e, g)
    };
    Ok(match kind {
        Kind::Delaunay if !d.collinear => sorted(fast::dt_edges_sorted_2d(&d), vec![]),
        Kind::Delaunay => finish2(&d, dt_edges(), vec![]),
        Kind::Hull => {
            let h = &d.hull;
            let mut e = Vec::new();
            if d.collinear {
                e.extend(h.windows(2).map(|w| [w[0], w[1]]));
            } else if h.len() >= 2 {
                for i in 0..h.len() {
                    e.push([h[i], h[(i + 1) % h.len()]]);
                }
            }
            finish2(&d, e, vec![])
        }
        Kind::Gabriel if !d.collinear => sorted(fast::gabriel_lune_sorted_2d(&d, &p, None), vec![]),
        Kind::Gabriel => finish2(&d, fast::gabriel_2d(&d), vec![]),
        // RNG and lune-based β with b ∈ (0, 1) (b = 0 is the Gabriel graph, b = 1 the strip)
        Kind::Rng | Kind::BetaLune(_) if !d.collinear && lune_grid.is_some() => {
            let lune = lune_grid.as_ref().map(|g| (lune_b.unwrap_or(0.5), g));
            sorted(fast::gabriel_lune_sorted_2d(&d, &p, lune), vec![])
        }
        Kind::BetaLune(b) if !d.collinear && b == 0.0 => {
            sorted(fast::gabriel_lune_sorted_2d(&d, &p, None), vec![])
        }
        // the vertex fans give the Delaunay neighbours in parallel and in vertex order
        Kind::Emst if !d.collinear => finish2(
            &d,
            emst_boruvka(&p, &d.input_of_vertex, tri_edges(&d, &p)),
            vec![],
        ),
        Kind::Sig if !d.collinear => {
            let (nn, r2) = nearest_tri(&d, &p);
            finish2(&d, sig_edges(&p, &nn, &r2), vec![])
        }
        Kind::Alpha(a) if a < 0.0 => {
            let rad = 1.0 / a.abs();
            let keep = |e: [u32; 2], iv: &CenterInterval| {
                let len = dist2(p[e[0] as usize], p[e[1] as usize]).sqrt();
                let h2 = rad * rad - 0.25 * len * len;
                if h2 < 0.0 {
                    return None;
                }
                let s = h2.sqrt() / len;
                (iv.ball_empty(s) || iv.ball_empty(-s)).then_some(e)
            };
            if d.collinear {
                finish2(
                    &d,
                    fast::filter_candidates_2d(&d, |e, iv, _| keep(e, iv)),
                    vec![],
                )
            } else {
                sorted(
                    fast::filter_candidates_sorted_2d(&d, &p, |e, iv| keep(e, iv).map(|_| ())).0,
                    vec![],
                )
            }
        }
        Kind::Alpha(a) => {
            // a = 0: hull; a > 0: discs containing everything, through two hull vertices
            let hv: Vec<u32> = d.hull.clone();
            let hp: Vec<[f64; 2]> = hv.iter().map(|&v| p[v as usize]).collect();
            let e = if a == 0.0 {
                brute::hull_2d(&hp)
            } else {
                brute::alpha_2d(&hp, a)
            };
            let e = e
                .into_iter()
                .map(|[i, j]| [hv[i as usize], hv[j as usize]])
                .collect();
            finish2(&d, e, vec![])
        }
        Kind::BetaCircle(_) => unreachable!("dispatched to Gamma(b, b) above"),
        Kind::BetaLune(b) if b < 0.0 => unreachable!("dispatched to Gamma({b}, {b}) above"),
        // decided on the interval itself (not through the rounded γ-values), so that a
        // parameter equal to a γ-value is decided exactly
        Kind::Gamma(c0, c1) => gamma_kind(
            &|iv, _| iv.neighborhood_empty(c0, c1, 1.0) || iv.neighborhood_empty(c0, c1, -1.0),
            (c1 < 0.0).then_some(c1),
        ),
        Kind::GammaRange(r) => {
            gamma_kind(&|_, v| in_gamma_range(v, r), (r[2] < 0.0).then_some(r[2]))
        }
        _ => {
            let needs_gabriel = matches!(kind, Kind::Rng | Kind::BetaLune(_) | Kind::Strip);
            let g = if needs_gabriel {
                fast::gabriel_2d(&d)
            } else {
                vec![]
            };
            let dt = if needs_gabriel { vec![] } else { dt_edges() };
            finish2(&d, classic(&p, &d.input_of_vertex, &dt, &g, kind)?, vec![])
        }
    })
}

/// A triangle with its γ-values when the graph kind has them.
type Simplex3 = ([u32; 3], Option<[f64; 2]>);
/// Decides a candidate triangle: `None` to drop it, `Some(γ-values)` to keep it.
type TriPredicate<'a> = dyn Fn(&CenterInterval, &[u32; 3]) -> Option<Option<[f64; 2]>> + 'a;

fn finish3(
    d: &d3::Delaunay3,
    edges: Vec<[u32; 2]>,
    mut tris: Vec<([u32; 3], Option<[f64; 2]>)>,
) -> Graph {
    let map = |v: u32| d.input_of_vertex[v as usize];
    let mut e: Vec<[u32; 2]> = edges
        .into_iter()
        .map(|[a, b]| {
            let (a, b) = (map(a), map(b));
            [a.min(b), a.max(b)]
        })
        .collect();
    e.sort_unstable();
    e.dedup();
    for (t, _) in tris.iter_mut() {
        *t = t.map(map);
        t.sort_unstable();
    }
    tris.sort_by_key(|x| x.0);
    tris.dedup_by(|x, y| x.0 == y.0);
    let gamma = if !tris.is_empty() && tris.iter().all(|x| x.1.is_some()) {
        tris.iter().map(|x| x.1.unwrap_or_default()).collect()
    } else {
        vec![]
    };
    Graph {
        dim: 3,
        edges: e,
        triangles: tris.into_iter().map(|x| x.0).collect(),
        gamma,
    }
}

/// Builds a graph on 3D points (duplicates merged). Kinds made of triangles (hull, Delaunay,
/// α, γ) fill `triangles`; the others `edges`. Circle-based β and lune-based β with b < 0 are
/// not defined in 3D (V §2.2.11).
///
/// Sets at extreme scales are first scaled exactly, as in [`graph_2d`]. Complexity: see
/// [`crate::graphs`]; degenerate input and γ with a parameter −1 are limited to
/// [`BRUTE_LIMIT_3D`] points, α with a > 0 to [`ALPHA_HULL_LIMIT_3D`] hull vertices.
///
/// ```rust
/// use morpho::graphs::{graph_3d, GraphError, Kind};
/// use morpho::geom::Point3;
/// // a tetrahedron with a point inside: the hull has 4 triangles, the Delaunay
/// // tetrahedralization's 4 tetrahedra have 10 distinct triangles
/// let p = [[0., 0., 0.], [4., 0., 0.], [0., 4., 0.], [0., 0., 4.], [1., 1., 1.]]
///     .map(|[x, y, z]| Point3::new(x, y, z));
/// assert_eq!(graph_3d(&p, Kind::Hull).unwrap().triangles.len(), 4);
/// assert_eq!(graph_3d(&p, Kind::Delaunay).unwrap().triangles.len(), 10);
/// assert_eq!(graph_3d(&p, Kind::Emst).unwrap().edges.len(), 4);
/// let e = graph_3d(&p, Kind::BetaCircle(0.5)).unwrap_err();
/// assert!(matches!(e, GraphError::Only2d { kind: "beta-circle", .. }));
/// ```
pub fn graph_3d(points: &[Point3], kind: Kind) -> Result<Graph> {
    kind.validate()?;
    if let Some(s) = extreme_scale(points.iter().flat_map(|q| [q.x, q.y, q.z]))? {
        let scaled: Vec<Point3> = points.iter().map(|q| q * s).collect();
        return graph_3d(&scaled, scaled_kind(kind, s)?);
    }
    let d = d3::triangulate(points)?;
    let p = fast::coords3(&d);
    if let Some(why) = &d.degenerate {
        if p.len() > BRUTE_LIMIT_3D {
            return Err(GraphError::DegenerateTooLarge {
                why: why.clone(),
                points: p.len(),
                limit: BRUTE_LIMIT_3D,
            });
        }
        return brute_3d(&d, &p, kind);
    }
    // the triples of cospherical (and flat) groups — up to g³/6 of them — only for the kinds
    // made of such triangles; the others need the Delaunay faces and the groups' pairs
    let triples = matches!(kind, Kind::Gamma(..) | Kind::GammaRange(_))
        || matches!(kind, Kind::Alpha(a) if a < 0.0);
    let (cand, groups) = fast::candidates_3d_groups(&d, triples);
    let mut dt_edges: Vec<[u32; 2]> = Vec::with_capacity(d.tets.len() * 2);
    for t in &d.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                dt_edges.push([t[i].min(t[j]), t[i].max(t[j])]);
            }
        }
    }
    dt_edges.sort_unstable();
    dt_edges.dedup();
    let tri_filter = |f: &TriPredicate<'_>| -> Vec<Simplex3> {
        cand.triangles
            .iter()
            .zip(&cand.intervals)
            .filter_map(|(t, iv)| f(iv, t).map(|g| (*t, g)))
            .collect()
    };
    let gabriel = || -> Vec<[u32; 2]> {
        // candidate pairs: Delaunay edges and pairs within cospherical (and flat) groups, each
        // decided exactly below (a superset of the Gabriel edges: every Gabriel edge is an edge
        // of the Delaunay subdivision)
        let mut pairs = dt_edges.clone();
        for vs in &groups {
            for i in 0..vs.len() {
                pairs.extend(vs[i + 1..].iter().map(|&w| [vs[i], w]));
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let grid = Grid::new(&p, 2.0);
        pairs
            .into_iter()
            .filter(|e| {
                let (u, v) = (p[e[0] as usize], p[e[1] as usize]);
                let m = [
                    0.5 * (u[0] + v[0]),
                    0.5 * (u[1] + v[1]),
                    0.5 * (u[2] + v[2]),
                ];
                grid.for_each_within(m, 0.5 * dist2(u, v).sqrt() * (1.0 + 1e-9), |x| {
                    x == e[0] || x == e[1] || dot_sign(&u, &v, &p[x as usize]) >= 0
                })
            })
            .collect()
    };
    Ok(match kind {
        Kind::Delaunay => finish3(
            &d,
            dt_edges,
            cand.triangles
                .iter()
                .zip(&cand.in_dt)
                .filter(|x| *x.1)
                .map(|x| (*x.0, None))
                .collect(),
        ),
        Kind::Hull => finish3(
            &d,
            vec![],
            hull_3d(&d, &p).into_iter().map(|t| (t, None)).collect(),
        ),
        Kind::Gamma(c0, c1) if c1 >= 0.0 => finish3(
            &d,
            vec![],
            tri_filter(&|iv, _| {
                let v = iv.gamma_values()?;
                (iv.neighborhood_empty(c0, c1, 1.0) || iv.neighborhood_empty(c0, c1, -1.0))
                    .then_some(Some([v.0, v.1]))
            }),
        ),
        Kind::GammaRange(r) if r[2] >= 0.0 => finish3(
            &d,
            vec![],
            tri_filter(&|iv, _| {
                let v = iv.gamma_values()?;
                in_gamma_range(v, r).then_some(Some([v.0, v.1]))
            }),
        ),
        Kind::Gamma(..) | Kind::GammaRange(_) => {
            // c₁ < 0 (c₂ < 0): the candidates plus the triangles beyond the tetrahedralization
            let (c, keep): (f64, &TriPredicate<'_>) = match kind {
                Kind::Gamma(c0, c1) => (c1, &move |iv: &CenterInterval, _: &[u32; 3]| {
                    let v = iv.gamma_values()?;
                    (iv.neighborhood_empty(c0, c1, 1.0) || iv.neighborhood_empty(c0, c1, -1.0))
                        .then_some(Some([v.0, v.1]))
                }),
                Kind::GammaRange(r) => (r[2], &move |iv: &CenterInterval, _: &[u32; 3]| {
                    let v = iv.gamma_values()?;
                    in_gamma_range(v, r).then_some(Some([v.0, v.1]))
                }),
                _ => unreachable!("matched above"),
            };
            if c <= -1.0 && p.len() > BRUTE_LIMIT_3D {
                return Err(GraphError::GammaMinusOneTooLarge {
                    points: p.len(),
                    limit: BRUTE_LIMIT_3D,
                });
            }
            let mut t = tri_filter(keep);
            let (bt, bi) = beyond3::beyond_dt_3d(&d, &cand, c);
            t.extend(
                bt.iter()
                    .zip(&bi)
                    .filter_map(|(t, iv)| keep(iv, t).map(|g| (*t, g))),
            );
            finish3(&d, vec![], t)
        }
        Kind::Alpha(a) if a < 0.0 => {
            let rad = 1.0 / a.abs();
            finish3(
                &d,
                vec![],
                tri_filter(&|iv, t| {
                    let (m, r2, n) = super::gamma::triangle_circle(
                        p[t[0] as usize],
                        p[t[1] as usize],
                        p[t[2] as usize],
                    )?;
                    let _ = m;
                    let h2 = rad * rad - r2;
                    if h2 < 0.0 {
                        return None;
                    }
                    let s = h2.sqrt() / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    (iv.ball_empty(s) || iv.ball_empty(-s)).then_some(None)
                }),
            )
        }
        Kind::Alpha(0.0) => finish3(
            &d,
            vec![],
            hull_3d(&d, &p).into_iter().map(|t| (t, None)).collect(),
        ),
        Kind::Alpha(a) => {
            let mut hv: Vec<u32> = d.hull.iter().flatten().copied().collect();
            hv.sort_unstable();
            hv.dedup();
            if hv.len() > ALPHA_HULL_LIMIT_3D {
                return Err(GraphError::AlphaHullTooLarge {
                    hull_vertices: hv.len(),
                    limit: ALPHA_HULL_LIMIT_3D,
                });
            }
            let hp: Vec<[f64; 3]> = hv.iter().map(|&v| p[v as usize]).collect();
            let t = brute::alpha_3d(&hp, a);
            finish3(
                &d,
                vec![],
                t.into_iter()
                    .map(|t| (t.map(|i| hv[i as usize]), None))
                    .collect(),
            )
        }
        Kind::BetaCircle(b) | Kind::BetaLune(b)
            if matches!(kind, Kind::BetaCircle(_)) || b < 0.0 =>
        {
            return Err(GraphError::Only2d {
                kind: kind.name(),
                b,
                degenerate: false,
            })
        }
        Kind::Gabriel => finish3(&d, gabriel(), vec![]),
        _ => {
            let g = gabriel();
            finish3(
                &d,
                classic(&p, &d.input_of_vertex, &dt_edges, &g, kind)?,
                vec![],
            )
        }
    })
}

/// The 3D hull triangles of Def. 2.10: the hull facets of the tetrahedralization, and for
/// coplanar facets with more than three points every empty non-degenerate triangle of them.
fn hull_3d(d: &d3::Delaunay3, p: &[[f64; 3]]) -> Vec<[u32; 3]> {
    use crate::geom::predicates::raw;
    let h = &d.hull;
    // group hull triangles that share an edge and are coplanar
    let mut parent: Vec<usize> = (0..h.len()).collect();
    fn root(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut by_edge: std::collections::HashMap<[u32; 2], usize> = std::collections::HashMap::new();
    for (i, t) in h.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = [a.min(b), a.max(b)];
            if let Some(&j) = by_edge.get(&key) {
                let other = h[j];
                let apex = other
                    .iter()
                    .copied()
                    .find(|&x| x != a && x != b)
                    .unwrap_or(a);
                let q = t.map(|x| p[x as usize]);
                if raw::orient3d(q[0], q[1], q[2], p[apex as usize]) == 0.0 {
                    let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ri] = rj;
                }
            } else {
                by_edge.insert(key, i);
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<u32>> = std::collections::BTreeMap::new();
    let mut out: Vec<[u32; 3]> = Vec::new();
    let mut gsize: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for i in 0..h.len() {
        *gsize.entry(root(&mut parent, i)).or_default() += 1;
    }
    for (i, t) in h.iter().enumerate() {
        let r = root(&mut parent, i);
        if gsize[&r] == 1 {
            let mut s = *t;
            s.sort_unstable();
            out.push(s);
        } else {
            groups.entry(r).or_default().extend_from_slice(t);
        }
    }
    for (_, mut vs) in groups {
        vs.sort_unstable();
        vs.dedup();
        let gp: Vec<[f64; 3]> = vs.iter().map(|&v| p[v as usize]).collect();
        for i in 0..vs.len() {
            for j in i + 1..vs.len() {
                for k in j + 1..vs.len() {
                    let n = crate::geom::vec::cross(
                        crate::geom::vec::sub(gp[j], gp[i]),
                        crate::geom::vec::sub(gp[k], gp[i]),
                    );
                    if n == [0.0, 0.0, 0.0] {
                        continue;
                    }
                    let empty = (0..vs.len()).all(|x| {
                        x == i
                            || x == j
                            || x == k
                            || !super::gamma::in_closed_triangle_3d(gp[i], gp[j], gp[k], gp[x], n)
                    });
                    if empty {
                        out.push([vs[i], vs[j], vs[k]]);
                    }
                }
            }
        }
    }
    out
}

/// Brute-force 3D construction (V Thm 3.1) for small or degenerate inputs.
fn brute_3d(d: &d3::Delaunay3, p: &[[f64; 3]], kind: Kind) -> Result<Graph> {
    let tris = |t: Vec<([u32; 3], Option<[f64; 2]>)>| finish3(d, vec![], t);
    let edges = |e: Vec<[u32; 2]>| finish3(d, e, vec![]);
    Ok(match kind {
        Kind::Gamma(c0, c1) => tris(
            brute::gamma_values_3d(p)
                .into_iter()
                .filter(|(_, v)| in_gamma(*v, c0, c1))
                .map(|(t, v)| (t, Some([v.0, v.1])))
                .collect(),
        ),
        Kind::GammaRange(r) => tris(
            brute::gamma_values_3d(p)
                .into_iter()
                .filter(|(_, v)| in_gamma_range(*v, r))
                .map(|(t, v)| (t, Some([v.0, v.1])))
                .collect(),
        ),
        Kind::Hull => tris(brute::hull_3d(p).into_iter().map(|t| (t, None)).collect()),
        Kind::Delaunay => tris(
            brute::gamma_values_3d(p)
                .into_iter()
                .filter(|(_, v)| in_gamma_range(*v, [-1.0, 1.0, 0.0, 1.0]))
                .map(|(t, _)| (t, None))
                .collect(),
        ),
        Kind::Alpha(a) => tris(
            brute::alpha_3d(p, a)
                .into_iter()
                .map(|t| (t, None))
                .collect(),
        ),
        Kind::ClosestPairs => edges(brute::closest_pairs(p)),
        Kind::Nng => edges(brute::nng(p)),
        Kind::Emst => edges(brute::emst(p)),
        Kind::Strip => edges(brute::strip(p)),
        Kind::Sig => edges(brute::sig(p)),
        Kind::Rng => edges(brute::rng(p)),
        Kind::Gabriel => edges(brute::gabriel(p)),
        Kind::BetaLune(b) if b >= 0.0 => edges(brute::beta_lune(p, b)),
        Kind::BetaCircle(b) | Kind::BetaLune(b) => {
            return Err(GraphError::Only2d {
                kind: kind.name(),
                b,
                degenerate: true,
            })
        }
    })
}

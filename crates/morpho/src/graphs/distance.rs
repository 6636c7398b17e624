//! The distance graphs of Veltkamp ch. 2 in 2D and 3D from the Delaunay edges (split from
//! [`super::build`]): closest pairs and the NNG over the Delaunay edges, the EMST by Borůvka's
//! algorithm, the SIG by grid queries, the RNG and the lune-based β-skeleton by exact lune
//! tests, the ∞-strip graph by slab tests over the Gabriel edges. Complexities: see
//! [`crate::graphs`].

use super::brute::in_slab;
use super::build::{nearest_over, Kind, NEAR_TIE};
use super::GraphError;
use crate::delaunay::d2;
use crate::geom::distance::{cmp_dist2, in_lune_ball, sum_of_roots_exceeds};
use crate::geom::grid::PointGrid as Grid;
use crate::geom::vec::dist2;
use rayon::prelude::*;
use std::cmp::Ordering;

type Result<T, E = GraphError> = std::result::Result<T, E>;

/// An edge during Borůvka's algorithm: float squared length, the current components of its
/// ends, and its two vertices.
#[derive(Clone, Copy)]
pub(super) struct BEdge {
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
pub(super) fn tri_edges(d: &d2::Delaunay2, p: &[[f64; 2]]) -> Vec<BEdge> {
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
pub(super) fn emst_boruvka<const D: usize>(
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
pub(super) fn sig_edges<const D: usize>(p: &[[f64; D]], nn: &[u32], r2: &[f64]) -> Vec<[u32; 2]> {
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
pub(super) fn classic<const D: usize>(
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

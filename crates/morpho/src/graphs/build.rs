//! The graph family as one entry point: [`graph_2d`] (here) and [`super::build3::graph_3d`]
//! build any [`Kind`] from the Delaunay triangulation (Veltkamp 1992 §2.2 and ch. 3;
//! construction per [`super::fast`]; the distance graphs shared by both dimensions in
//! [`super::distance`]).
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

use super::brute;
use super::distance::{classic, emst_boruvka, sig_edges, tri_edges};
use super::fast;
use super::gamma::{CenterInterval, EdgeFrame};
use super::lune::LuneGrid;
use super::GraphError;
use crate::delaunay::d2;
use crate::geom::distance::cmp_dist2;
use crate::geom::vec::dist2;
use crate::geom::Point2;
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
    /// ordered ranges for γ(\[c₀,c₁\],\[c₂,c₃\]), a finite α. [`graph_2d`] and [`graph_3d`](super::graph_3d) call
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
pub(super) fn sort_edges(
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
pub(super) fn nearest_over<const D: usize>(p: &[[f64; D]], edges: &[[u32; 2]]) -> Vec<u32> {
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
pub(super) const NEAR_TIE: f64 = 32.0 * f64::EPSILON;

/// An exact nearest neighbour of every vertex of a non-collinear 2D triangulation (among its
/// Delaunay neighbours, which contain one) with its float squared distance. The triangles are
/// split into one block per thread; each block offers its edges to both ends in triangle order
/// (spatially coherent), then the blocks' answers are merged per vertex. Float comparisons
/// decide unless two candidates are within [`NEAR_TIE`]; then [`cmp_dist2`] does (ties: the
/// first offered).
pub(super) fn nearest_tri(d: &d2::Delaunay2, p: &[[f64; 2]]) -> (Vec<u32>, Vec<f64>) {
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

/// Largest coordinate magnitudes (as powers of two) used as they are: the graph predicates
/// (degree ≤ 5 in coordinate differences, on floats and expansions) neither over- nor underflow
/// for sets whose largest magnitude M lies in [2⁻¹⁰⁰, 2¹⁰⁰].
const SAFE_EXPONENT: i32 = 100;

/// For a set whose largest coordinate magnitude `m` lies outside the safe range
/// [2⁻¹⁰⁰, 2¹⁰⁰]: the power of two that brings it near 1 (exact: the graphs, which are
/// invariant under scaling, do not change; `None` inside the range, where nothing is scaled).
/// An error when the scaling would flush a non-zero coordinate below the normal range (the
/// set spans more magnitudes than the exact predicates can hold).
pub(super) fn extreme_scale(coords: impl Iterator<Item = f64> + Clone) -> Result<Option<f64>> {
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
pub(super) fn scaled_kind(kind: Kind, s: f64) -> Result<Kind> {
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
    // γ kinds: decide every candidate edge in parallel, exactly on its interval (through the
    // edge's frame), keeping its γ-values
    type Decide<'a> = dyn Fn(&EdgeFrame, &CenterInterval) -> bool + Sync + 'a;
    let gamma_kind = |decide: &Decide<'_>, beyond: Option<f64>| {
        let keep = |e: [u32; 2], iv: &CenterInterval| {
            let v = iv.gamma_values()?;
            let f = EdgeFrame::new(p[e[0] as usize], p[e[1] as usize]);
            decide(&f, iv).then_some((e, [v.0, v.1]))
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
        // decided exactly on the interval (not through the rounded γ-values), so that a
        // parameter equal to or an ulp from a γ-value is decided right (Lemmas 3.1, 3.2; Def. 3.3)
        Kind::Gamma(c0, c1) => {
            gamma_kind(&|f, iv| f.in_gamma(iv, c0, c1), (c1 < 0.0).then_some(c1))
        }
        Kind::GammaRange(r) => gamma_kind(
            &|f, iv| f.in_gamma_range(iv, r),
            (r[2] < 0.0).then_some(r[2]),
        ),
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

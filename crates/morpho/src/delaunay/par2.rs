//! The 2D Delaunay triangulation on two threads: split at the lexicographic median, triangulate
//! both halves in parallel, keep the triangles that cannot see the other half, and
//! re-triangulate the seam exactly (issue 23 item 3; Veltkamp 1992 §2.2.9 Def. 2.11; divide and
//! conquer with a merge by re-triangulation rather than Guibas–Stolfi's zipper).
//!
//! # What it computes
//! The same triangles as the sequential engine of [`super::d2`] — as a set: the perturbed
//! Delaunay triangulation DT(P) of the distinct points is unique (every in-circle tie is broken by
//! the symbolic perturbation of [`super::d2::incircle_sos`], which depends on the lexicographic
//! order of the two points compared and on nothing else, so a triangle that is perturbed-empty
//! in a subset computation is decided exactly as in the whole), and both paths compute it.
//!
//! # Algorithm
//! `P` (the distinct, scaled vertices, in the engine's Hilbert order) is split by lexicographic
//! rank (x, then y) into the first half `L` and the rest `R`; every point of `L` has
//! `x ≤ x_L = max_L x` and every point of `R` has `x ≥ x_R = min_R x` (with `x_L ≤ x_R`).
//! 1. DT(L ∪ G_R) and DT(R ∪ G_L) are built in parallel (`rayon::join`) by the sequential
//!    engine on the two subsets (their Hilbert order is the global one restricted, so the
//!    insertion stays local). The *guards* G_R ⊆ R (G_L ⊆ L) are every 32nd vertex in Hilbert
//!    order: without them the empty circles of a half are bounded by that half's points only,
//!    and on points along a curve nearly every circle opening towards the other half crossed
//!    the split line (|S| ≈ n/2 on the flower curve of the bench).
//! 2. A triangle of DT(L ∪ G_R) is **final** when its three vertices are in L and its closed
//!    circumdisk lies strictly left of the line `x = x_R` (of DT(R ∪ G_L): in R, strictly right
//!    of `x = x_L`). Decided exactly by
//!    [`disk_beyond`]: with `b' = b − a`, `c' = c − a`, `X' = X − a_x`,
//!    `D = b'×c' > 0`, `u = |b'|²c'_y − |c'|²b'_y`, `w = |c'|²b'_x − |b'|²c'_x` (the circumcentre
//!    is `a + (u, w)/(2D)`, the radius `√(u² + w²)/(2D)`), "centre_x + radius < X" is
//!    `g = 2D·X' − u > 0` and `g² − u² − w² > 0` (for "right of", `g = u − 2D·X'`): a floating-
//!    point evaluation with a proven running error bound ([`crate::geom::bounded`]) and, when
//!    that bound does not decide both signs, the exact evaluation in expansions
//!    ([`crate::geom::expansion`]). A tangent circle is not final.
//! 3. `S` = the L-vertices of the non-final triangles and of the hull of DT(L ∪ G_R), and the
//!    R-vertices of the same of DT(R ∪ G_L); DT(S) is built (sequentially; `S` is a seam a few
//!    triangles wide).
//! 4. The seam triangles are those of DT(S) reached by a flood fill that starts across every
//!    *F-boundary edge* (an edge of a final triangle whose neighbour in its half is not final or
//!    the outside) and never crosses an F-boundary edge or the hull.
//! 5. The output is F_L ∪ F_R ∪ seam with neighbour links (the F-boundary edges are looked up in
//!    a hash map of DT(S)'s directed edges) and the ghost triangles of the hull, handed to the
//!    engine's `finish` like the sequential result. A count check (2n − h − 2 triangles for h
//!    hull vertices) or a failed look-up — impossible by the proof below — falls back to the
//!    sequential engine, as do inputs with a collinear half or a collinear `S`.
//!
//! # Why it is correct
//! Let F = F_L ∪ F_R. (i) F ⊆ DT(P): a final t ∈ DT(L ∪ G_R) is perturbed-empty of L, and
//! every `q ∈ R` has `q_x ≥ x_R` so lies strictly outside t's closed disk: the exact in-circle
//! is non-zero and negative, the perturbation is not consulted. (ii) Every T ∈ DT(P) \ F has
//! its vertices in S: if T ⊆ L then T is perturbed-empty of P ⊇ L ∪ G_R, so T ∈ DT(L ∪ G_R),
//! not final, and its vertices (all in L) are in S (the same for R). Otherwise every L-vertex v
//! of T has an edge v r of T with r ∈ R. If v were neither a hull vertex of L ∪ G_R nor a vertex
//! of a non-final triangle, its whole star in DT(L ∪ G_R) would be final, hence in DT(P), and
//! would cover a neighbourhood of v (v is interior to the hull); the star of v in DT(P) would
//! then be that star, all of whose triangles lie in L — but T is in it (the same for the
//! R-vertices of T). (iii) So T is perturbed-empty of P ⊇ S with vertices in S: T ∈ DT(S).
//! (iv) DT(P) \ F tiles hull(P) minus the union of F; its boundary consists of hull edges and
//! F-boundary edges (an F_L triangle and an F_R triangle share no vertex, so an edge of
//! F_L whose neighbour in its half is not final has a non-F triangle or the outside across it in
//! DT(P)). Crossing a DT(S) edge of a seam triangle that is neither a hull edge nor an
//! F-boundary edge leads to the DT(P) triangle beyond it, which is not in F, so in DT(S) by
//! (iii): the flood stays in DT(P) \ F. Every edge-connected part of DT(P) \ F touches an
//! F-boundary edge unless F is empty (then S = P and the answer is DT(S)), so the flood reaches
//! all of it. No step uses a property of F beyond (i), so declaring a final triangle non-final
//! (a conservative filter) only makes S larger.
//!
//! # Order and determinism
//! The triangles come as F_L in DT(L ∪ G_R)'s order, F_R in DT(R ∪ G_L)'s order, then the seam in flood
//! order: a function of the point set, the same for every thread count (the halves are built
//! by the deterministic sequential engine), but not the sequential engine's order (that is the
//! creation order of its flips, which no other schedule reproduces; a canonical sort of 2 M
//! triangles would cost about a fifth of the whole run). `hull`, `points`, `vertex_of_input`
//! and `input_of_vertex` are identical to the sequential result.
//!
//! # Cost
//! Two halves of n/2 + n/64 points in parallel, plus O(n) sequential work (the median selection, the
//! final test of each triangle, the assembly) and DT(S) with |S| = O(√n) for uniform points.
//! Memory: the two halves' arrays and the output exist together (about twice the sequential
//! engine's peak triangle arrays).

use super::d2::{first_noncollinear, lex_cmp, run_insertion, Arrays, Kernel, INF};
use super::DelaunayError;
use crate::geom::bounded::Bounded;
use crate::geom::expansion::Expansion;
use crate::util::IdMap;
use crate::util::NONE;

/// Fewest distinct points for which [`super::d2::triangulate`] takes the split path on more
/// than one thread (below it the sequential engine is faster than the split's fixed costs).
pub const MIN_SPLIT: usize = 50_000;

/// Every `GUARD`-th vertex (in the engine's Hilbert order, so a sample of uniform density
/// over the data) is added to the other half's triangulation as a guard (module doc, step 1).
const GUARD: u32 = 32;

/// One half: its triangulation (local vertex ids, ghosts included) and which triangles are final.
struct Half {
    /// Global vertex id of every local vertex.
    ids: Vec<u32>,
    tv: Vec<[u32; 3]>,
    th: Vec<[u32; 3]>,
    /// For every triangle, its index among the final triangles, or [`NONE`].
    fin: Vec<u32>,
    n_final: u32,
    /// Global ids of the vertices of non-final triangles and of the hull (unsorted, repeats).
    seam: Vec<u32>,
}

/// Builds DT(ids) — the half's own vertices (`in_r[v] != left`) and its guards — and classifies
/// its triangles; `None` when it is collinear.
fn half<K: Kernel>(
    k: &K,
    ids: Vec<u32>,
    in_r: &[bool],
    line: f64,
    left: bool,
) -> Result<Option<Half>, DelaunayError> {
    let own = |v: u32| in_r[v as usize] != left;
    let sub = k.subset(&ids);
    let Some(k0) = first_noncollinear(&sub, ids.len()) else {
        return Ok(None);
    };
    let (tv, th) = run_insertion(sub, ids.len(), k0, None)?;
    let mut fin = vec![NONE; tv.len()];
    let mut n_final = 0u32;
    let mut seam = Vec::new();
    for (t, v) in tv.iter().enumerate() {
        if v.contains(&INF) {
            seam.extend(
                v.iter()
                    .filter(|&&w| w != INF)
                    .map(|&w| ids[w as usize])
                    .filter(|&w| own(w)),
            );
            continue;
        }
        let g = v.map(|w| ids[w as usize]);
        if g.iter().all(|&w| own(w)) && disk_beyond(k.xy(g[0]), k.xy(g[1]), k.xy(g[2]), line, left)
        {
            fin[t] = n_final;
            n_final += 1;
        } else {
            seam.extend(g.iter().filter(|&&w| own(w)));
        }
    }
    Ok(Some(Half {
        ids,
        tv,
        th,
        fin,
        n_final,
        seam,
    }))
}

/// Does the closed circumdisk of the counter-clockwise triangle `a, b, c` lie strictly left
/// (`left`) or strictly right of the vertical line `x = line`? Exact (module doc, step 2).
pub(super) fn disk_beyond(a: [f64; 2], b: [f64; 2], c: [f64; 2], line: f64, left: bool) -> bool {
    let (bx, by) = (Bounded::diff(b[0], a[0]), Bounded::diff(b[1], a[1]));
    let (cx, cy) = (Bounded::diff(c[0], a[0]), Bounded::diff(c[1], a[1]));
    let xl = Bounded::diff(line, a[0]);
    let d = bx.times(cy).minus(by.times(cx));
    let b2 = bx.times(bx).plus(by.times(by));
    let c2 = cx.times(cx).plus(cy.times(cy));
    let u = b2.times(cy).minus(c2.times(by));
    let w = c2.times(bx).minus(b2.times(cx));
    let dx = d.times(xl).scale2(2.0);
    let g = if left { dx.minus(u) } else { u.minus(dx) };
    let h = g.times(g).minus(u.times(u).plus(w.times(w)));
    match (g.sign(), h.sign()) {
        (Some(-1), _) | (_, Some(-1)) => false,
        (Some(1), Some(1)) => true,
        _ => disk_beyond_exact(a, b, c, line, left),
    }
}

/// [`disk_beyond`] in exact expansion arithmetic (the polynomials of the module doc, step 2).
#[cold]
fn disk_beyond_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2], line: f64, left: bool) -> bool {
    let (bx, by) = (Expansion::diff(b[0], a[0]), Expansion::diff(b[1], a[1]));
    let (cx, cy) = (Expansion::diff(c[0], a[0]), Expansion::diff(c[1], a[1]));
    let xl = Expansion::diff(line, a[0]);
    let d = bx.mul(&cy).sub(&by.mul(&cx));
    let b2 = bx.mul(&bx).add(&by.mul(&by));
    let c2 = cx.mul(&cx).add(&cy.mul(&cy));
    let u = b2.mul(&cy).sub(&c2.mul(&by));
    let w = c2.mul(&bx).sub(&b2.mul(&cx));
    let dx = d.mul(&xl).scale(2.0);
    let g = if left { dx.sub(&u) } else { u.sub(&dx) };
    if g.sign() <= 0 {
        return false;
    }
    g.mul(&g).sub(&u.mul(&u).add(&w.mul(&w))).sign() > 0
}

/// Writes the final triangles of `h` (global vertex ids, output twins; [`NONE`] across an
/// F-boundary edge) into `tv`, `th`, whose first triangle has output id `off`.
fn copy_final(h: &Half, off: u32, tv: &mut [[u32; 3]], th: &mut [[u32; 3]]) {
    let mut k = 0;
    for (t, v) in h.tv.iter().enumerate() {
        if h.fin[t] == NONE {
            continue;
        }
        tv[k] = v.map(|w| h.ids[w as usize]);
        th[k] = h.th[t].map(|e| match h.fin[(e / 3) as usize] {
            NONE => NONE,
            id => 3 * (off + id) + e % 3,
        });
        k += 1;
    }
}

/// Above this predicted share of seam vertices the split declines (the sequential engine is
/// then faster than two halves plus the seam). Measured on samples of 10⁶ points (every 32nd):
/// uniform 0.018, the flower curve of the bench 0.49.
const MAX_SEAM_SHARE: f64 = 0.125;

/// The share of the vertices of the guard sample (every [`GUARD`]-th vertex) that lie on a
/// triangle of the sample's Delaunay triangulation whose circumdisk meets the strip
/// `x_l ≤ x ≤ x_r`: an estimate of |S|/n. Points along a curve make every triangle's circle as
/// large as the curve's local feature size (three consecutive samples span nearly the
/// osculating circle), so a straight split line meets a large share of them.
fn seam_share<K: Kernel>(k: &K, n: usize, x_l: f64, x_r: f64) -> Result<f64, DelaunayError> {
    let ids: Vec<u32> = (0..n as u32).step_by(GUARD as usize).collect();
    let sub = k.subset(&ids);
    let Some(k0) = first_noncollinear(&sub, ids.len()) else {
        return Ok(0.0);
    };
    let (tv, _) = run_insertion(sub, ids.len(), k0, None)?;
    let mut hit = vec![false; ids.len()];
    for v in &tv {
        if v.contains(&INF) {
            continue;
        }
        let g = v.map(|w| k.xy(ids[w as usize]));
        if !disk_beyond(g[0], g[1], g[2], x_r, true) && !disk_beyond(g[0], g[1], g[2], x_l, false) {
            for w in v {
                hit[*w as usize] = true;
            }
        }
    }
    Ok(hit.iter().filter(|&&h| h).count() as f64 / ids.len() as f64)
}

#[inline]
fn key(a: u32, b: u32) -> u64 {
    ((a as u64) << 32) | b as u64
}

/// The Delaunay triangulation of the `n` vertices of `k` by the split (module doc), as the
/// engine's corner and twin arrays with ghosts (global vertex ids); `Ok(None)` where the split
/// does not apply (fewer than 8 points, a collinear half or seam) — the caller then runs the
/// sequential engine.
///
/// With `predict`, the split is also declined when a sample predicts a wide seam
/// ([`seam_share`] above [`MAX_SEAM_SHARE`]).
pub(super) fn insert_split<K: Kernel>(
    k: &K,
    n: usize,
    predict: bool,
) -> Result<Option<Arrays>, DelaunayError> {
    if n < 8 {
        return Ok(None);
    }
    // 1. the lexicographic median
    let m = n / 2;
    let mut ids: Vec<u32> = (0..n as u32).collect();
    ids.select_nth_unstable_by(m, |&a, &b| lex_cmp(k.xy(a), k.xy(b)));
    let x_r = k.xy(ids[m])[0];
    let x_l = ids[..m]
        .iter()
        .map(|&v| k.xy(v)[0])
        .fold(f64::NEG_INFINITY, f64::max);
    if predict && seam_share(k, n, x_l, x_r)? > MAX_SEAM_SHARE {
        return Ok(None);
    }
    let mut in_r = vec![false; n];
    for &v in &ids[m..] {
        in_r[v as usize] = true;
    }
    drop(ids);
    let guard = |v: u32| v % GUARD == 0;
    let l_ids: Vec<u32> = (0..n as u32)
        .filter(|&v| !in_r[v as usize] || guard(v))
        .collect();
    let r_ids: Vec<u32> = (0..n as u32)
        .filter(|&v| in_r[v as usize] || guard(v))
        .collect();
    // 2. both halves in parallel
    let (hl, hr) = rayon::join(
        || half(k, l_ids, &in_r, x_r, true),
        || half(k, r_ids, &in_r, x_l, false),
    );
    drop(in_r);
    let (Some(hl), Some(hr)) = (hl?, hr?) else {
        return Ok(None);
    };
    // 3. the seam's vertices and their triangulation
    let mut in_s = vec![false; n];
    for &v in hl.seam.iter().chain(&hr.seam) {
        in_s[v as usize] = true;
    }
    let s_ids: Vec<u32> = (0..n as u32).filter(|&v| in_s[v as usize]).collect();
    drop(in_s);
    let ks = k.subset(&s_ids);
    let Some(k0) = first_noncollinear(&ks, s_ids.len()) else {
        return Ok(None);
    };
    let (mut stv, sth) = run_insertion(ks, s_ids.len(), k0, None)?;
    for v in stv.iter_mut().flatten() {
        if *v != INF {
            *v = s_ids[*v as usize];
        }
    }
    drop(s_ids);
    // the directed edges of DT(S) (ghosts' hull edges included) → half-edge
    let mut s_edge: IdMap<u64, u32> = IdMap::default();
    s_edge.reserve(3 * stv.len());
    for (t, v) in stv.iter().enumerate() {
        for j in 0..3 {
            let (x, y) = (v[(j + 1) % 3], v[(j + 2) % 3]);
            if x != INF && y != INF {
                s_edge.insert(key(x, y), 3 * t as u32 + j as u32);
            }
        }
    }
    // F-boundary edges: directed as in their final triangle → its output half-edge
    let off_r = hl.n_final;
    let n_f = hl.n_final + hr.n_final;
    let mut f_bnd: IdMap<u64, u32> = IdMap::default();
    let mut seeds: Vec<u64> = Vec::new();
    for (h, off) in [(&hl, 0), (&hr, off_r)] {
        for (t, v) in h.tv.iter().enumerate() {
            let id = h.fin[t];
            if id == NONE {
                continue;
            }
            for i in 0..3 {
                if h.fin[(h.th[t][i] / 3) as usize] == NONE {
                    let (a, b) = (
                        h.ids[v[(i + 1) % 3] as usize],
                        h.ids[v[(i + 2) % 3] as usize],
                    );
                    f_bnd.insert(key(a, b), 3 * (off + id) + i as u32);
                    seeds.push(key(b, a));
                }
            }
        }
    }
    // 4. flood fill of the seam from across the F-boundary edges
    let ghost = |t: u32| stv[t as usize].contains(&INF);
    let mut seam_id = vec![NONE; stv.len()];
    let mut order: Vec<u32> = Vec::new();
    let start_fill = |t: u32, seam_id: &mut Vec<u32>, order: &mut Vec<u32>| {
        if seam_id[t as usize] == NONE {
            seam_id[t as usize] = n_f + order.len() as u32;
            order.push(t);
        }
    };
    for &e in &seeds {
        let Some(&he) = s_edge.get(&e) else {
            return Ok(None); // impossible (module doc, (iii)); the sequential engine decides
        };
        if !ghost(he / 3) {
            start_fill(he / 3, &mut seam_id, &mut order);
        }
    }
    if f_bnd.is_empty() {
        // F is empty: S = P and DT(S) is the answer
        return Ok(Some((stv, sth)));
    }
    let mut q = 0;
    while q < order.len() {
        let t = order[q] as usize;
        q += 1;
        for j in 0..3 {
            let (x, y) = (stv[t][(j + 1) % 3], stv[t][(j + 2) % 3]);
            if f_bnd.contains_key(&key(y, x)) {
                continue;
            }
            let u = sth[t][j] / 3;
            if !ghost(u) {
                start_fill(u, &mut seam_id, &mut order);
            }
        }
    }
    // 5. assembly: F_L, F_R, seam, then the ghosts of the hull
    let n_real = n_f as usize + order.len();
    let mut tv: Vec<[u32; 3]> = Vec::with_capacity(n_real + n_real / 8 + 16);
    let mut th: Vec<[u32; 3]> = Vec::with_capacity(tv.capacity());
    tv.resize(n_f as usize, [0; 3]);
    th.resize(n_f as usize, [0; 3]);
    {
        // the final triangles of both halves, written in parallel into their own ranges
        let (tvl, tvr) = tv.split_at_mut(off_r as usize);
        let (thl, thr) = th.split_at_mut(off_r as usize);
        rayon::join(
            || copy_final(&hl, 0, tvl, thl),
            || copy_final(&hr, off_r, tvr, thr),
        );
    }
    drop((hl, hr));
    for &t in &order {
        let t = t as usize;
        let v = stv[t];
        let me = tv.len() as u32;
        let mut tw = [NONE; 3];
        for j in 0..3 {
            let (x, y) = (v[(j + 1) % 3], v[(j + 2) % 3]);
            if let Some(&fh) = f_bnd.get(&key(y, x)) {
                tw[j] = fh;
                th[(fh / 3) as usize][(fh % 3) as usize] = 3 * me + j as u32;
                continue;
            }
            let e = sth[t][j];
            if !ghost(e / 3) {
                let id = seam_id[(e / 3) as usize];
                if id == NONE {
                    return Ok(None); // impossible (module doc, (iv))
                }
                tw[j] = 3 * id + e % 3;
            }
        }
        tv.push(v);
        th.push(tw);
    }
    drop((stv, sth, seam_id, order));
    // ghosts (y, x, INF) across every real edge (x, y) without a neighbour
    let mut ghost_of: IdMap<u32, u32> = IdMap::default();
    for t in 0..n_real {
        for i in 0..3 {
            if th[t][i] == NONE {
                let (x, y) = (tv[t][(i + 1) % 3], tv[t][(i + 2) % 3]);
                let g = tv.len() as u32;
                tv.push([y, x, INF]);
                th.push([NONE, NONE, 3 * t as u32 + i as u32]);
                th[t][i] = 3 * g + 2;
                if ghost_of.insert(y, g).is_some() {
                    return Ok(None); // a hull vertex twice: impossible
                }
            }
        }
    }
    let hull = tv.len() - n_real;
    for g in n_real..tv.len() {
        // ghost (y, x, INF): its edge (x, INF) is the edge (INF, x) of the ghost starting at x
        let x = tv[g][1];
        let Some(&g2) = ghost_of.get(&x) else {
            return Ok(None);
        };
        th[g][0] = 3 * g2 + 1;
        th[g2 as usize][1] = 3 * g as u32;
    }
    if n_real + hull + 2 != 2 * n {
        return Ok(None); // Euler: 2n − h − 2 triangles
    }
    Ok(Some((tv, th)))
}

#[cfg(test)]
mod tests {
    use super::super::d2::{triangulate_split, Delaunay2, FloatKernel, Split};
    use super::super::test_sets::*;
    use super::*;
    use crate::geom::Point2;
    use crate::util::Rng;

    fn canon(d: &Delaunay2) -> Vec<[u32; 3]> {
        canonical(&d.triangles)
    }

    /// The split result's invariants: neighbour symmetry (with matching edges), each vertex's
    /// triangle contains it, every edge locally Delaunay (perturbed), Euler.
    fn check(d: &Delaunay2) {
        let nt = d.triangles.len();
        let mut hull_edges = 0;
        for t in 0..nt {
            let v = d.triangles[t];
            assert!(d.orient(v[0], v[1], v[2]) > 0.0, "triangle {t} not ccw");
            for i in 0..3 {
                let u = d.neighbors[t][i];
                let (x, y) = (v[(i + 1) % 3], v[(i + 2) % 3]);
                if u == NONE {
                    hull_edges += 1;
                    continue;
                }
                let w = d.triangles[u as usize];
                let j = (0..3)
                    .find(|&j| w[(j + 1) % 3] == y && w[(j + 2) % 3] == x)
                    .expect("neighbour shares the edge");
                assert_eq!(d.neighbors[u as usize][j], t as u32);
                assert!(
                    d.incircle_sos(v[0], v[1], v[2], w[j]) < 0,
                    "edge not Delaunay"
                );
            }
        }
        let n = d.points.len();
        assert_eq!(hull_edges, d.hull.len());
        assert_eq!(nt + d.hull.len() + 2, 2 * n);
        for (v, &t) in d.vertex_tri.iter().enumerate() {
            assert!(d.triangles[t as usize].contains(&(v as u32)));
        }
    }

    /// The split path on its own and against the sequential engine; asserts that the split
    /// applied (no fallback to the sequential engine) when there are `min_split` points or more.
    fn same_min(p: &[Point2], min_split: usize) -> Delaunay2 {
        let s = triangulate_split(p, Split::Never).unwrap();
        let d = triangulate_split(p, Split::Always).unwrap();
        let k = FloatKernel(d.points.iter().map(|q| [q.x, q.y]).collect());
        let split = insert_split(&k, d.points.len(), false).unwrap();
        if d.points.len() >= min_split {
            assert!(
                split.is_some(),
                "the split fell back (n = {})",
                d.points.len()
            );
        }
        assert_eq!(
            canon(&s),
            canon(&d),
            "triangle sets differ (n = {})",
            p.len()
        );
        assert_eq!(s.hull, d.hull);
        assert_eq!(s.vertex_of_input, d.vertex_of_input);
        if !d.collinear {
            check(&d);
        }
        d
    }

    fn same(p: &[Point2]) -> Delaunay2 {
        same_min(p, 8)
    }

    #[test]
    fn split_equals_sequential_uniform_and_clustered() {
        for (n, seed) in [(300, 1), (5000, 2), (40_000, 3)] {
            same(&uniform(n, seed));
        }
        // clusters of very different density
        same(&clusters());
    }

    #[test]
    fn split_equals_sequential_curves_and_circle() {
        for p in curves(20_000) {
            same(&p);
        }
        // the integer circle (many exactly cocircular: S = P), the float circle with its centre
        let [circ, c2] = circles();
        assert!(circ.len() > 8);
        same(&circ);
        same(&c2);
    }

    #[test]
    fn split_equals_sequential_lattices_with_duplicates() {
        // full grid: every cell cocircular, columns of equal x across the split
        let g: Vec<Point2> = (0..100 * 100)
            .map(|i| Point2::new((i % 100) as f64, (i / 100) as f64))
            .collect();
        same(&g);
        // random lattice subsets with duplicates, odd sizes, at several scales
        let cases = [
            (3000, 40, 1.0),
            (777, 12, 0.25),
            (5000, 300, 1e-3),
            (20, 3, 1.0),
        ];
        for p in lattice_subsets(&cases) {
            same(&p);
        }
        // a triangular lattice (sheared): non-integer after scaling, many cocircular hexagons
        same(&triangular_lattice());
    }

    #[test]
    fn split_tiny_and_degenerate_inputs() {
        let mut r = Rng::new(5);
        for n in 1..40 {
            for _ in 0..20 {
                let m = 1 + r.below(6);
                let p: Vec<Point2> = (0..n)
                    .map(|_| Point2::new(r.below(m) as f64, r.below(m) as f64))
                    .collect();
                same_min(&p, usize::MAX);
                same_min(&uniform(n, r.below(1 << 40)), usize::MAX);
            }
        }
        // collinear halves: one line of points, then two parallel lines
        let line: Vec<Point2> = (0..50)
            .map(|i| Point2::new(i as f64, 2.0 * i as f64))
            .collect();
        same_min(&line, usize::MAX);
        let two: Vec<Point2> = (0..50)
            .map(|i| Point2::new((i % 25) as f64, (i / 25) as f64))
            .collect();
        same_min(&two, usize::MAX);
        // a vertical line on the left, a cloud on the right
        let mut mixed: Vec<Point2> = (0..100).map(|i| Point2::new(0.0, i as f64)).collect();
        mixed.extend(
            uniform(100, 9)
                .iter()
                .map(|p| Point2::new(1.0 + p.x, 100.0 * p.y)),
        );
        same_min(&mixed, usize::MAX);
    }

    /// The predictor accepts uniform points and declines points along a curve (where the seam
    /// would hold about half of the points); the result is the same either way.
    #[test]
    fn seam_prediction_declines_curves() {
        let n = 100_000;
        let flower: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let t = i as f64 * std::f64::consts::TAU / n as f64;
                let r = 1.0 + 0.3 * (5.0 * t).sin();
                [r * t.cos(), r * t.sin()]
            })
            .collect();
        let cloud: Vec<[f64; 2]> = uniform(n, 4).iter().map(|p| [p.x, p.y]).collect();
        for (pts, declines) in [(flower, true), (cloud, false)] {
            let k = FloatKernel(pts);
            let got = insert_split(&k, n, true).unwrap();
            assert_eq!(got.is_none(), declines);
            assert!(insert_split(&k, n, false).unwrap().is_some());
        }
    }

    #[test]
    fn split_is_the_same_for_every_thread_count() {
        same_for_every_thread_count(Split::Always);
    }

    /// The exact side test against an integer oracle of the same polynomials on small integer
    /// coordinates (many exact tangencies).
    #[test]
    fn disk_beyond_matches_integer_oracle() {
        let mut r = Rng::new(3);
        let mut tangent = 0;
        for _ in 0..20_000 {
            let q: Vec<[i64; 2]> = (0..3)
                .map(|_| [r.below(9) as i64 - 4, r.below(9) as i64 - 4])
                .collect();
            let (a, mut b, mut c) = (q[0], q[1], q[2]);
            let orient = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            if orient == 0 {
                continue;
            }
            if orient < 0 {
                std::mem::swap(&mut b, &mut c);
            }
            let x = r.below(13) as i64 - 6;
            // centre (cx, cy) = a + (u, w)/(2D); compare 2D·(x − a_x) with u and the radius
            let (bx, by, cx, cy) = (b[0] - a[0], b[1] - a[1], c[0] - a[0], c[1] - a[1]);
            let d = (bx * cy - by * cx) as i128;
            let (b2, c2) = ((bx * bx + by * by) as i128, (cx * cx + cy * cy) as i128);
            let u = b2 * cy as i128 - c2 * by as i128;
            let w = c2 * bx as i128 - b2 * cx as i128;
            let xl = (x - a[0]) as i128;
            for left in [true, false] {
                let g = if left { 2 * d * xl - u } else { u - 2 * d * xl };
                let h = g * g - u * u - w * w;
                tangent += (h == 0) as i32;
                let want = g > 0 && h > 0;
                let f = |p: [i64; 2]| [p[0] as f64, p[1] as f64];
                assert_eq!(
                    disk_beyond(f(a), f(b), f(c), x as f64, left),
                    want,
                    "{a:?} {b:?} {c:?} x = {x} left = {left}"
                );
                // moved and scaled by a power of two (exact; the signs do not change), so the
                // float filter sees tiny differences of large coordinates
                let e = 2f64.powi(-40);
                let s = |p: [i64; 2]| [1.0 + p[0] as f64 * e, 3.0 + p[1] as f64 * e];
                assert_eq!(
                    disk_beyond(s(a), s(b), s(c), 1.0 + x as f64 * e, left),
                    want
                );
            }
        }
        assert!(
            tangent > 100,
            "the oracle meets exact tangencies ({tangent})"
        );
    }
}

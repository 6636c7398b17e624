//! The cubic three-split G¹ surface (Veltkamp 1992, §9.6, Thm 9.1; NOTES B.5) through the
//! vertices and vertex normals of a closed, consistently oriented 2-manifold triangle mesh.
//!
//! Per macro triangle `(V0,V1,V2)`: (1) corners `p300,p030,p003`; (2) edge points a third of
//! the way to the other end's projection onto the tangent plane; (3) Farin's
//! `p111 = Σedge/4 − Σcorner/6`; (4) subdivision at the centroid `Z` into three cubic micro
//! patches `(V_i, V_{i+1}, Z)`; (5) per macro edge, the linear-E,F,G conditions (9.3a), (9.3d)
//! with `e0 = e1 = 1` give `f0,g0,f1,g1` (least squares in the tangent plane) and the pair
//! (9.4) gives the two interior points `L1, R1`; (6) the C¹ Clough–Tocher interior:
//! `Y_i = (W_i + X_a + X_b)/3`, `Z = (Y_0+Y_1+Y_2)/3` (the text's `Y_1..Y_3` is an index garble).
//! O(triangles).
//!
//! **Deviation: Step 5 without (9.4) where possible (not in the text).** (9.4)'s determinant
//! `f0 g1 − g0 f1` vanishes when the two triangles of an edge are mirror images (octahedron,
//! icosahedron with sphere normals, symmetric grids), where (9.3) is also inconsistent
//! (NOTES B.5), and it is *small on most edges of a good real mesh*, whose neighbouring
//! triangles are nearly symmetric: on the horse 75 % of the edges have it below 1e-3 of its
//! scale and 331 below 1e-7, on spot 104 exactly 0. The residual of (9.3) does not vanish with
//! it, so (9.4) throws `L1, R1` out by residual/determinant: 1.4e14 edge lengths on spot's edge
//! 104–1842, 3.8e12 on the horse (the "wild oscillation" of V Fig. 9.5). No threshold or choice
//! of the free ratio `e1/e0` cures that (see `transversal.rs`). So, per macro edge:
//! 1. if a **degree-elevated quadratic boundary** exists near the Step-2 one (its middle
//!    point `Q` in both tangent planes, nearest the Step-2 boundary in least squares; each edge
//!    point moves by at most `QUAD_MOVE` of its distance from the vertex), the edge gets it and
//!    Step 5 is the **explicit transversal construction** of `transversal.rs`: `L1, R1` in
//!    closed form, G¹ by construction (proof sketch there: (8.10) with quadratic `E`, linear
//!    `F, G`), no division by the determinant;
//! 2. else (an inflected edge: offset, nearly parallel tangent planes; or a fold at an end),
//!    (9.4) on the cubic boundary if it moves `L1, R1` by at most `MAX_MOVE` edge lengths,
//!    solved backward-stably (offsets from `M1`, one refinement step: `solve_94`), because G¹
//!    needs the residual of (9.3b, c) to vanish, and Cramer's rule on absolute coordinates
//!    left `ε|M1||f|/Δ` — on fandisk's nearly flat edges (`Δ ≈ 1e-9`) 555 edges creased by
//!    1e-9…1e-3 rad that were not reported;
//! 3. else the minimum-norm correction of `singular.rs` with a pseudo-inverse cut-off at
//!    `SINGULAR` (kept only if it also moves at most `MAX_MOVE`, else the Step-4 points stay):
//!    the edge is listed in [`SplitSurface::unresolved_edges`] when (9.3) keeps a residual.
//!
//! So every `L1, R1` lies within `MAX_MOVE` edge lengths of its Step-4 value (no spikes), and
//! every edge not listed as unresolved satisfies (8.10) exactly (up to rounding). Edges where
//! (9.4) is ill-conditioned (`|f0 g1 − g0 f1| ≤ SINGULAR (|f0|+|g0|)(|f1|+|g1|)` on the final
//! data) are **reported** in [`SplitSurface::singular_edges`] whichever way they were built;
//! edges whose `f`, `g` differ in sign (a fold, NOTES B.1: the text's "opposite signs" is a
//! garble) in [`SplitSurface::sign_warnings`]. Continuity is verified independently by
//! [`super::continuity`].
//!
//! **Every non-G¹ edge reported (issue 19, item 4).** The arguments above give G¹ in exact
//! arithmetic; in floating point an edge can still crease where the data are ill-conditioned
//! (fandisk: `Δ` near 1e-13, a transversal edge next to a nearly degenerate corner, a fold
//! where `f, g` are positive at one end although the normal sees its triangles). So after
//! Step 6 every macro edge is checked a posteriori on the final control points
//! (`check::macro_edges_not_g1`): first a certificate — the Bernstein coefficients of the
//! degree-8 polynomials `N_P × N_Q` and `N_P · N_Q` of the two patches' unnormalised normals
//! bound `tan θ ≤ 1e-10` on the whole edge, with well-conditioned normals —, and where it
//! does not certify, the 20 samples of [`super::continuity`] with its own code. The edges
//! above 1e-9 rad are listed in [`SplitSurface::non_g1_edges`]: the same set as the
//! independent check's non-G¹ macro edges.
//!
//! **Folds (derived here; the text only says "the normal at a vertex should be altered").**
//! The sign rule `f, g < 0` at an edge end holds exactly when the edge point lies strictly
//! inside the cone of its two `W` neighbours in the tangent plane, which holds when the edge
//! points around the vertex form a fan (every corner turns counter-clockwise about the vertex
//! normal, see `fan_ok`). Step 2's projected edge points do, wherever the vertex normal sees
//! its triangles ([`super::visible_normals`] repairs the vertices where it does not). On real
//! meshes almost every fold came from the singular-edge boundaries instead: a quadratic edge
//! point rotates within the tangent plane and can turn a neighbouring corner over (spot: all
//! 28 sign warnings touch a singular edge). A quadratic boundary is therefore accepted only if
//! the fans at both ends stay valid ([`SplitOptions::fold_guard`], off by default: see
//! there for its cost); otherwise the edge keeps its cubic boundary, is listed in
//! [`SplitSurface::fold_guarded`] and goes through the bounded (9.4) of Step 5; where that
//! does not apply either it is in `unresolved_edges`: a reported crease instead of a fold.

use super::triangle::{tri_index, BezierTriangle};
use super::SmoothError;
use crate::geom::vec;
use crate::mesh::TriMesh;
use crate::util::IdMap;
use rayon::prelude::*;

type P3 = [f64; 3];

/// Relative threshold of `is_singular`: below it (9.4) moves `L1, R1` by more than about
/// `1/SINGULAR` times its residual (module doc).
const SINGULAR: f64 = 1e-2;
/// Largest move of an edge point from Step 2 to the quadratic boundary, relative to its
/// distance from the vertex, for the quadratic boundary to be used.
const QUAD_MOVE: f64 = 1.0;
/// Largest move of `L1` or `R1` by (9.4), in edge lengths, accepted as a solution.
const MAX_MOVE: f64 = 3.0;
/// Largest relative residual of (9.3b, c) accepted on a singular edge.
const RESOLVED: f64 = 1e-10;
/// The half-edge map and the unit normals of a checked mesh.
type Checked = (IdMap<(u32, u32), usize>, Vec<P3>);

/// One cubic micro patch of the split surface.
#[derive(Debug, Clone, PartialEq)]
pub struct MicroPatch {
    /// The macro triangle (index into the input's triangles) it belongs to.
    pub macro_tri: u32,
    /// Control points in [`tri_index`] order (b300 first = the first corner).
    pub control: [P3; 10],
}

impl MicroPatch {
    /// The patch as a [`BezierTriangle`].
    pub fn triangle(&self) -> BezierTriangle {
        BezierTriangle::new(3, self.control.to_vec())
    }
}

/// A split surface: micro patches and what its construction found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SplitSurface {
    /// Micro patches; for the three-split, patch `3t+i` has corners `(V_i, V_{i+1}, Z)` of
    /// macro triangle t.
    pub patches: Vec<MicroPatch>,
    /// Macro edges `[a, b]` (a < b) where (9.4) is ill-conditioned on the final data or would
    /// move `L1, R1` by more than `MAX_MOVE` edge lengths (reported; built as the module doc
    /// says, without (9.4) where the quadratic boundary is usable). Contains every unresolved
    /// edge.
    pub singular_edges: Vec<[u32; 2]>,
    /// Edges where neither the transversal construction nor a bounded (9.4) applied and the
    /// minimum-norm correction left a residual of (9.3): not G¹ (module doc).
    pub unresolved_edges: Vec<[u32; 2]>,
    /// Macro edges whose `f0,g0` or `f1,g1` differ in sign (a fold is likely).
    pub sign_warnings: Vec<[u32; 2]>,
    /// Edges that keep the cubic boundary because the quadratic one would have turned a
    /// neighbouring corner over (module doc, "folds").
    pub fold_guarded: Vec<[u32; 2]>,
    /// Macro edges `[a, b]` (a < b) that the construction's a-posteriori check measured
    /// **not** G¹ (normal angle above 1e-9 rad at the 20 sample points of
    /// [`super::continuity`], whatever the reason: a residual, rounding on an ill-conditioned
    /// edge, a fold), sorted. The same edges as `continuity(s, 20)`'s non-G¹ macro edges
    /// (module doc, "Every non-G¹ edge reported"); for the six-split the same check on both
    /// halves of each macro edge, and for the two-split the three-split's list less the
    /// rebuilt edges.
    pub non_g1_edges: Vec<[u32; 2]>,
    /// Input triangles with a non-G¹ edge inside them (an edge from a split point to a
    /// corner, `edgesplit.rs`), sorted; empty without edge splits.
    pub non_g1_inner: Vec<u32>,
    /// Input macro edges `[a, b]` (a < b) split by the local edge split (`edgesplit.rs`:
    /// their first-pass three-split was not G¹), sorted.
    pub split_edges: Vec<[u32; 2]>,
    /// Max over edges of `|L1 − L1_step4| / |edge|` (and the same for `R1`), with Step 4 on the
    /// final boundaries; at most `MAX_MOVE` = 3 by construction (module doc).
    pub max_displacement: f64,
    /// Barycentric coordinates, in its macro triangle, of each micro patch's three corners,
    /// where the layout is not fixed by the scheme (the two-split, [`super::two_split`]);
    /// empty for the three- and six-split (their fixed layouts, see [`super::max_deviation`]).
    pub domain: Vec<[[f64; 3]; 3]>,
}

/// Checks that `mesh` is a closed, consistently oriented 2-manifold without zero-area
/// triangles and that `normals` are finite unit-able vectors; returns the half-edge map
/// `(a, b) → 3t + i` (edge i of triangle t runs from its vertex i to vertex i+1) and the unit
/// normals.
pub(crate) fn check_closed(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
) -> Result<Checked, SmoothError> {
    let nv = mesh.positions.len();
    if nv < 4 || mesh.triangles.len() < 4 {
        return Err(SmoothError::TooFew { got: nv, need: 4 });
    }
    if let Some(index) = mesh
        .positions
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(SmoothError::NonFinite { index });
    }
    let mut half = IdMap::with_capacity_and_hasher(mesh.triangles.len() * 3, Default::default());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= nv) {
            return Err(SmoothError::BadIndex { triangle: t });
        }
        if zero_area(mesh, tri) {
            return Err(SmoothError::ZeroArea { triangle: t });
        }
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if half.insert((a, b), 3 * t + i).is_some() {
                return Err(SmoothError::NonManifold { a, b });
            }
        }
    }
    for &(a, b) in half.keys() {
        if !half.contains_key(&(b, a)) {
            return Err(SmoothError::NotClosed { a, b });
        }
    }
    if normals.len() != nv {
        return Err(SmoothError::BadNormal {
            vertex: normals.len().min(nv),
        });
    }
    let mut unit = Vec::with_capacity(nv);
    for (v, n) in normals.iter().enumerate() {
        unit.push(unit_normal(n).ok_or(SmoothError::BadNormal { vertex: v })?);
    }
    Ok((half, unit))
}

/// Whether triangle `tri` (indices `< mesh.positions.len()`) repeats a corner or has a zero
/// cross product of its edge vectors ([`SmoothError::ZeroArea`]).
fn zero_area(mesh: &TriMesh, tri: &[u32; 3]) -> bool {
    let p = |k: usize| -> P3 { mesh.positions[tri[k] as usize].into() };
    let c = vec::cross(vec::sub(p(1), p(0)), vec::sub(p(2), p(0)));
    tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || vec::norm2(c) == 0.0
}

/// `n` scaled to unit length, or `None` when its length is zero or not finite
/// ([`SmoothError::BadNormal`]).
fn unit_normal(n: &crate::geom::Vector3) -> Option<P3> {
    let l = n.norm();
    (l > 0.0 && l.is_finite()).then(|| [n.x / l, n.y / l, n.z / l])
}

/// [`check_closed`]'s checks and the opposite half-edge of every half-edge (`twin[3t + i]`
/// runs `b → a` where `3t + i` runs `a → b`), found in per-vertex lists of outgoing half-edges
/// sorted by their ends (a counting sort by start vertex) instead of a hash map, in parallel
/// where it can be. A mesh that fails any check goes through [`check_closed`] itself, so the
/// error is its own. O(triangles · log degree).
fn closed_twins(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
) -> Result<(Vec<u32>, Vec<P3>), SmoothError> {
    let slow = || -> Result<(Vec<u32>, Vec<P3>), SmoothError> {
        let (half, unit) = check_closed(mesh, normals)?;
        let twin = mesh
            .triangles
            .iter()
            .flat_map(|t| [0, 1, 2].map(|i| half[&(t[(i + 1) % 3], t[i])] as u32))
            .collect();
        Ok((twin, unit))
    };
    let (nv, nt) = (mesh.positions.len(), mesh.triangles.len());
    if nv < 4 || nt < 4 || 3 * nt >= crate::util::NONE as usize || normals.len() != nv {
        return slow();
    }
    let finite = mesh
        .positions
        .par_iter()
        .all(|p| p.iter().all(|c| c.is_finite()));
    let proper = mesh
        .triangles
        .par_iter()
        .all(|tri| tri.iter().all(|&v| (v as usize) < nv) && !zero_area(mesh, tri));
    let unit: Vec<Option<P3>> = normals.par_iter().map(unit_normal).collect();
    if !(finite && proper && unit.iter().all(Option::is_some)) {
        return slow();
    }
    let unit: Vec<P3> = unit.into_iter().flatten().collect();
    // outgoing half-edges (end, half-edge) of each vertex, sorted by end
    let start = corner_starts(mesh, nv);
    let mut fill = start.clone();
    let mut out = vec![(0u32, 0u32); 3 * nt];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for i in 0..3 {
            let k = &mut fill[tri[i] as usize];
            out[*k as usize] = (tri[(i + 1) % 3], (3 * t + i) as u32);
            *k += 1;
        }
    }
    let mut manifold = true;
    for v in 0..nv {
        let seg = &mut out[start[v] as usize..start[v + 1] as usize];
        seg.sort_unstable();
        // the same half-edge a → b twice
        manifold &= seg.windows(2).all(|w| w[0].0 != w[1].0);
    }
    if !manifold {
        return slow();
    }
    let mut twin = vec![crate::util::NONE; 3 * nt];
    twin.par_chunks_mut(3)
        .zip(mesh.triangles.par_iter())
        .for_each(|(w, t)| {
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3] as usize);
                let seg = &out[start[b] as usize..start[b + 1] as usize];
                if let Ok(k) = seg.binary_search_by_key(&a, |x| x.0) {
                    w[i] = seg[k].1;
                }
            }
        });
    if twin.par_iter().any(|&e| e == crate::util::NONE) {
        // a half-edge without its opposite: not closed
        return slow();
    }
    Ok((twin, unit))
}

/// Step 2: the edge point from `a` towards `b`.
fn edge_point(a: P3, na: P3, b: P3) -> P3 {
    let d = vec::sub(b, a);
    let proj = vec::add_scaled(d, -vec::dot(d, na), na);
    vec::add_scaled(a, 1.0 / 3.0, proj)
}

/// Steps 1–4 for one macro triangle from its corners and edge points:
/// `e[i] = [E(V_i → V_{i+1}), E(V_i → V_{i+2})]`.
fn micro_patches(v: [P3; 3], ep: [[P3; 2]; 3]) -> [[P3; 10]; 3] {
    let e = |i: usize, j: usize| if j == (i + 1) % 3 { ep[i][0] } else { ep[i][1] };
    let mut c = [[0.0; 3]; 10];
    c[tri_index(3, 3, 0)] = v[0];
    c[tri_index(3, 0, 3)] = v[1];
    c[tri_index(3, 0, 0)] = v[2];
    c[tri_index(3, 2, 1)] = e(0, 1);
    c[tri_index(3, 2, 0)] = e(0, 2);
    c[tri_index(3, 1, 2)] = e(1, 0);
    c[tri_index(3, 0, 2)] = e(1, 2);
    c[tri_index(3, 1, 0)] = e(2, 0);
    c[tri_index(3, 0, 1)] = e(2, 1);
    let edges = [e(0, 1), e(0, 2), e(1, 0), e(1, 2), e(2, 0), e(2, 1)];
    let se = edges.iter().fold([0.0; 3], |s, p| vec::add(s, *p));
    let sv = vec::add(vec::add(v[0], v[1]), v[2]);
    c[tri_index(3, 1, 1)] = vec::sub(vec::scale(se, 0.25), vec::scale(sv, 1.0 / 6.0));
    let mac = BezierTriangle::new(3, c.to_vec());
    let bary = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let z = [1.0 / 3.0; 3];
    let mut out = [[[0.0; 3]; 10]; 3];
    for i in 0..3 {
        let s = mac.subdivide(bary[i], bary[(i + 1) % 3], z);
        out[i].copy_from_slice(&s.control);
    }
    out
}

/// `min |d + f a + g b|²` over (f, g): the 2×2 normal equations.
fn solve_fg(d: P3, a: P3, b: P3) -> (f64, f64) {
    let (aa, ab, bb) = (vec::dot(a, a), vec::dot(a, b), vec::dot(b, b));
    let (ad, bd) = (vec::dot(a, d), vec::dot(b, d));
    let det = aa * bb - ab * ab;
    ((-ad * bb + bd * ab) / det, (-bd * aa + ad * ab) / det)
}

/// The data of one macro edge in the notation of V 9.3 (Fig. 9.2).
struct EdgeData {
    m: [P3; 4],
    l: [P3; 3],
    r: [P3; 3],
}

/// The edge `a → b` (a < b; `p`, `q` the patches of its half-edges `a → b`, `b → a`) in the notation of V 9.3 and its `(f0, g0, f1, g1)` from (9.3a),
/// (9.3d) with `e0 = e1 = 1`.
fn edge_data(patches: &[MicroPatch], p: usize, q: usize) -> (EdgeData, [f64; 4]) {
    let (pp, qq) = (&patches[p].control, &patches[q].control);
    let e = EdgeData {
        m: [pp[0], pp[1], pp[3], pp[6]],
        l: [pp[2], pp[4], pp[7]],
        r: [qq[7], qq[4], qq[2]],
    };
    let (m, l, r) = (e.m, e.l, e.r);
    let (f0, g0) = solve_fg(
        vec::sub(m[1], m[0]),
        vec::sub(l[0], m[0]),
        vec::sub(r[0], m[0]),
    );
    let (f1, g1) = solve_fg(
        vec::sub(m[3], m[2]),
        vec::sub(l[2], m[2]),
        vec::sub(r[2], m[2]),
    );
    (e, [f0, g0, f1, g1])
}

/// `|f0 g1 − g0 f1| ≤ SINGULAR (|f0|+|g0|)(|f1|+|g1|)`: (9.4) is ill-conditioned.
fn is_singular([f0, g0, f1, g1]: [f64; 4]) -> bool {
    let delta = f0 * g1 - g0 * f1;
    delta.abs() <= SINGULAR * (f0.abs() + g0.abs()) * (f1.abs() + g1.abs()) || delta.is_nan()
}

/// Whether `lr` is finite and within `bound` of `old`.
fn moves_at_most(lr: (P3, P3), old: (P3, P3), bound: f64) -> bool {
    vec::dist(lr.0, old.0) <= bound && vec::dist(lr.1, old.1) <= bound
}

/// The pair (9.4) solved for `(L1, R1)` with `e0 = e1 = 1`.
///
/// Solved for the offsets `u = L1 − M1`, `v = R1 − M1` (per coordinate the 2×2 system
/// `2f0 u + 2g0 v = −A0 − 2(M2−M1)`, `2f1 u + 2g1 v = −A1 − 2(M2−M1)`, with `A0, A1` as in
/// `singular::solve_singular` at `ρ = 1`), by Cramer's rule followed by one step of iterative
/// refinement on the residual. Why: G¹ needs the *residual* of (9.3b, c) to vanish, not an
/// accurate `L1`: the normal jump is about residual/|D|. Cramer's rule on absolute
/// coordinates (the earlier code) left a residual of about `ε·|M1|·|f|/Δ`, `Δ = f0g1 − g0f1`:
/// on fandisk's nearly flat edges `Δ ≈ 1e-9` and the edges were creased by 1e-6…1e-3 rad
/// while (9.4) moved `L1, R1` by less than `MAX_MOVE`. On offsets the rounding is relative
/// to the edge length, and one refinement step (residual recomputed from the equations, the
/// correction solved the same way) brings the residual down to rounding of `|B||x| + |rhs|`
/// as long as `κ(B)·ε < 1`: the solve is then backward stable.
fn solve_94(e: &EdgeData, [f0, g0, f1, g1]: [f64; 4]) -> (P3, P3) {
    let (m, l, r) = (e.m, e.l, e.r);
    let d = |x: P3, y: P3| vec::sub(x, y);
    let m21 = d(m[2], m[1]);
    let (a0, a1) = super::singular::a_terms(&m, &l, &r, [f0, g0, f1, g1]);
    let big = 4.0 * (f0 * g1 - g0 * f1);
    let cramer = |b0: f64, b1: f64| {
        (
            (2.0 * g1 * b0 - 2.0 * g0 * b1) / big,
            (2.0 * f0 * b1 - 2.0 * f1 * b0) / big,
        )
    };
    let (mut u, mut v) = ([0.0; 3], [0.0; 3]);
    for k in 0..3 {
        let b0 = -a0[k] - 2.0 * m21[k];
        let b1 = -a1[k] - 2.0 * m21[k];
        let (x, y) = cramer(b0, b1);
        // one refinement step on the residual of the same equations
        let r0 = b0 - (2.0 * f0 * x + 2.0 * g0 * y);
        let r1 = b1 - (2.0 * f1 * x + 2.0 * g1 * y);
        let (dx, dy) = cramer(r0, r1);
        u[k] = x + dx;
        v[k] = y + dy;
    }
    (vec::add(m[1], u), vec::add(m[1], v))
}

/// Whether the edge points around vertex `a` still form a fan: for every corner `(a, b, c)`
/// (counter-clockwise), `h_ab, h_ac` turn counter-clockwise about `a`'s normal, by the exact
/// `orient3d(a, h_ab, h_ac, a + n_a) < 0`. Then every projected corner angle is in (0, π) and
/// each edge point lies strictly inside the cone of its two neighbouring `W` points, which is
/// the orientation rule `f, g < 0` of NOTES B.1 at `a` (module doc, "folds").
fn fan_ok(pos: &[P3], nrm: &[P3], corners: &Corners, handles: &[P3], a: u32) -> bool {
    let pa = pos[a as usize];
    let up = vec::add(pa, nrm[a as usize]);
    corners.of(a).iter().all(|&(ab, ac)| {
        crate::geom::predicates::raw::orient3d(pa, handles[ab as usize], handles[ac as usize], up)
            < 0.0
    })
}

/// CSR offsets of the triangle corners at each vertex: vertex `v`'s corners are
/// `start[v]..start[v + 1]` (every index of `mesh.triangles` must be `< nv`).
fn corner_starts(mesh: &TriMesh, nv: usize) -> Vec<u32> {
    let mut start = vec![0u32; nv + 1];
    for tri in &mesh.triangles {
        for &v in tri {
            start[v as usize + 1] += 1;
        }
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    start
}

/// The corners `(a, b, c)` of each vertex `a` as the half-edges `(a → b, a → c)` (CSR).
struct Corners {
    start: Vec<u32>,
    list: Vec<(u32, u32)>,
}

impl Corners {
    /// The corners of every vertex, in triangle order (`twin[e]`: the half-edge opposite `e`).
    fn new(mesh: &TriMesh, nv: usize, twin: &[u32]) -> Corners {
        let start = corner_starts(mesh, nv);
        let mut fill = start.clone();
        let mut list = vec![(0, 0); 3 * mesh.triangles.len()];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                let k = &mut fill[tri[i] as usize];
                list[*k as usize] = ((3 * t + i) as u32, twin[3 * t + (i + 2) % 3]);
                *k += 1;
            }
        }
        Corners { start, list }
    }

    fn of(&self, a: u32) -> &[(u32, u32)] {
        &self.list[self.start[a as usize] as usize..self.start[a as usize + 1] as usize]
    }
}

/// The cubic three-split G¹ surface (module doc).
///
/// ```
/// use morpho::mesh::{generate, vertex_normals, NormalWeighting};
/// use morpho::smooth::{continuity, three_split};
/// let m = generate::icosphere(0);
/// let n = vertex_normals(&m, NormalWeighting::Area);
/// let s = three_split(&m, &n).unwrap();
/// assert_eq!(s.patches.len(), 3 * m.triangles.len());
/// // every icosahedron edge is mirror-symmetric: reported
/// assert_eq!(s.singular_edges.len(), 30);
/// let _ = continuity(&s, 20);
/// ```
pub fn three_split(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
) -> Result<SplitSurface, SmoothError> {
    three_split_with(mesh, normals, &SplitOptions::default())
}

/// Options of [`three_split_with`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SplitOptions {
    /// Accept an edge's quadratic boundary only where it keeps the fans at both ends (module
    /// doc, "folds"). Off by default: it removes most folds on real meshes (spot with visible
    /// normals: 2 803 fold samples → 0), but a guarded edge keeps its cubic boundary and is G¹
    /// only where (9.4) stays bounded.
    pub fold_guard: bool,
}

/// [`three_split`] with options: the three-split of the module doc, then the local edge
/// split of `edgesplit.rs` where its a-posteriori check finds non-G¹ macro edges (a macro
/// triangle next to a split edge then has more than three patches, see
/// [`SplitSurface::domain`]).
pub fn three_split_with(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
    opts: &SplitOptions,
) -> Result<SplitSurface, SmoothError> {
    super::edgesplit::three_split_split(mesh, normals, opts)
}

/// One three-split pass (module doc) without the edge split: patch `3t+i` is micro patch i
/// of macro triangle t.
pub(crate) fn three_split_once(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
    opts: &SplitOptions,
) -> Result<SplitSurface, SmoothError> {
    three_split_pass(mesh, normals, opts, None).map(|(s, _)| s)
}

/// Step 5's result on one macro edge.
#[derive(Debug, Clone, Copy)]
struct Solved {
    p: usize,
    q: usize,
    lr: (P3, P3),
    sign_warning: bool,
    singular: bool,
    unresolved: bool,
    displacement: f64,
}

/// What a pass keeps for a later pass on a refined mesh (`edgesplit.rs`): per macro edge of
/// its mesh (sorted, `a < b`) the quadratic boundary, the fold guard's decision, Step 5's
/// result and the a-posteriori verdict, and per patch Step 4's 111 point (`L1` or `R1`). A
/// patch's Step-4 control points are the surface's final ones but for the 111 point (Step 5)
/// and the 102, 012, 003 points (Step 6), and those three are rewritten by Step 6 before
/// anything reads them: so the final patches with the kept 111 points stand for Step 4's.
pub(crate) struct PassCache {
    triangles: Vec<[u32; 3]>,
    edges: Vec<(u32, u32)>,
    quad: Vec<Option<(P3, P3)>>,
    guarded: Vec<bool>,
    solved: Vec<Solved>,
    bad: Vec<bool>,
    step4_111: Vec<P3>,
}

/// An earlier pass on a coarser mesh for [`three_split_pass`] to reuse: its cache, its surface,
/// and per triangle of the refined mesh the earlier mesh's triangle with the same vertices in
/// the same order (`util::NONE` for a new triangle). The refined mesh keeps every earlier
/// vertex with its index, position and normal and only appends vertices.
pub(crate) struct Reuse<'a> {
    pub(crate) cache: &'a PassCache,
    pub(crate) surf: &'a SplitSurface,
    pub(crate) from: &'a [u32],
}

/// [`three_split_once`], reusing an earlier pass where the inputs of a step are the same
/// (the second pass of `edgesplit.rs` made local; bit for bit the full pass, since every step
/// is a pure function of the inputs it is skipped on):
/// - an edge of the earlier mesh keeps its quadratic boundary (a function of its two ends);
/// - the fold guard's decision on such an edge is the earlier one while neither end is
///   *perturbed*: a perturbed vertex is one of a new triangle (its corners changed) or the end
///   of an edge whose decision changed; elsewhere the handles around both ends are, at the
///   moment of the decision, those of the earlier pass (the edge order among earlier edges is
///   kept), so the fans and the decision are the same;
/// - a triangle of the earlier mesh whose three edges kept their decision keeps its Step-4
///   patches; an edge between two such triangles keeps its Step-5 result; an edge between two
///   triangles whose final patches are the earlier ones (in the same patch order) keeps its
///   a-posteriori verdict.
///
/// Returns the surface and the cache for a next pass.
pub(crate) fn three_split_pass(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
    opts: &SplitOptions,
    reuse: Option<&Reuse>,
) -> Result<(SplitSurface, PassCache), SmoothError> {
    // half-edge e = 3t + i runs from vertex i of triangle t to vertex i + 1; twin[e] the
    // opposite half-edge (the mesh is closed)
    let (twin, nrm) = closed_twins(mesh, normals)?;
    let nt = mesh.triangles.len();
    let reuse = reuse.filter(|r| r.from.len() == nt);
    // the earlier triangle of each triangle, checked (NONE: new)
    let from: Vec<u32> = match reuse {
        Some(r) => (0..nt)
            .map(|t| {
                let f = r.from[t];
                let same = r.cache.triangles.get(f as usize) == Some(&mesh.triangles[t])
                    && r.surf.patches.len() == 3 * r.cache.triangles.len();
                if same {
                    f
                } else {
                    crate::util::NONE
                }
            })
            .collect(),
        None => vec![crate::util::NONE; nt],
    };
    let pos: Vec<P3> = mesh.positions.iter().map(|p| (*p).into()).collect();
    // the edge point of each half-edge (Step 2; later the quadratic boundary's; filled in
    // place, three entries per triangle: an indexed write, where a flat-mapped collect
    // concatenates per-thread pieces, a second copy)
    let mut handles = vec![[0.0; 3]; 3 * nt];
    handles
        .par_chunks_mut(3)
        .zip(mesh.triangles.par_iter())
        .for_each(|(h, t)| {
            for i in 0..3 {
                let (a, b) = (t[i] as usize, t[(i + 1) % 3] as usize);
                h[i] = edge_point(pos[a], nrm[a], pos[b]);
            }
        });
    let tri_patches = |handles: &[P3], t: usize| {
        let v = mesh.triangles[t].map(|i| pos[i as usize]);
        let ep = [0, 1, 2].map(|i| {
            [
                handles[3 * t + i],
                handles[twin[3 * t + (i + 2) % 3] as usize],
            ]
        });
        micro_patches(v, ep)
    };
    let corners = Corners::new(mesh, pos.len(), &twin);
    // the edges a < b and their two patches: p on the side a → b, q on b → a
    let mut edge_pq: Vec<((u32, u32), (usize, usize))> = mesh
        .triangles
        .iter()
        .enumerate()
        .flat_map(|(t, tri)| (0..3).map(move |i| (t, tri, i)))
        .filter(|&(_, tri, i)| tri[i] < tri[(i + 1) % 3])
        .map(|(t, tri, i)| {
            let e = 3 * t + i;
            ((tri[i], tri[(i + 1) % 3]), (e, twin[e] as usize))
        })
        .collect();
    edge_pq.par_sort_unstable_by_key(|&(e, _)| e);
    // each edge (sorted ends) with its two half-edges
    let edges: Vec<(u32, u32)> = edge_pq.iter().map(|x| x.0).collect();
    let pq: Vec<(usize, usize)> = edge_pq.into_iter().map(|x| x.1).collect();
    // the earlier pass's index of each edge (None: a new edge)
    let prev_edge: Vec<Option<usize>> = match reuse {
        Some(r) => edges
            .par_iter()
            .map(|e| r.cache.edges.binary_search(e).ok())
            .collect(),
        None => vec![None; edges.len()],
    };
    let mut out = SplitSurface::default();
    // The boundary of each edge: the degree-elevated quadratic wherever its point Q (in both
    // tangent planes) is usable, so that Step 5 is the explicit transversal construction
    // (transversal.rs); else the cubic of Step 2 and (9.4).
    let quad: Vec<Option<(P3, P3)>> = edges
        .par_iter()
        .zip(&pq)
        .zip(&prev_edge)
        .map(|((&(a, b), &(p, q)), pe)| {
            if let (Some(r), Some(i)) = (reuse, *pe) {
                return r.cache.quad[i];
            }
            let (pa, pb) = (pos[a as usize], pos[b as usize]);
            let h = (handles[p], handles[q]);
            // the Q whose boundary is nearest the Step-2 one: least squares of |M − H|
            let c = vec::scale(
                vec::add(
                    vec::add_scaled(vec::scale(h.0, 3.0), -1.0, pa),
                    vec::add_scaled(vec::scale(h.1, 3.0), -1.0, pb),
                ),
                0.25,
            );
            let (m1, m2, _) =
                super::singular::quadratic_handles(pa, nrm[a as usize], pb, nrm[b as usize], c)?;
            let near = |m: P3, h: P3, v: P3| vec::dist(m, h) <= QUAD_MOVE * vec::dist(h, v);
            (near(m1, h.0, pa) && near(m2, h.1, pb)).then_some((m1, m2))
        })
        .collect();
    // vertices whose fans may differ from the earlier pass's (see the doc above)
    let mut perturbed = vec![false; pos.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if reuse.is_some() && from[t] == crate::util::NONE {
            for &v in tri {
                perturbed[v as usize] = true;
            }
        }
    }
    let mut quadratic = vec![false; edges.len()];
    let mut guarded = vec![false; edges.len()];
    // earlier edges whose decision changed
    let mut differs = vec![false; edges.len()];
    for (k, (&(a, b), qd)) in edges.iter().zip(&quad).enumerate() {
        let Some((m1, m2)) = *qd else { continue };
        let (p, q) = pq[k];
        let old = (handles[p], handles[q]);
        handles[p] = m1;
        handles[q] = m2;
        if opts.fold_guard {
            let earlier = match (reuse, prev_edge[k]) {
                (Some(r), Some(i)) => Some(r.cache.guarded[i]),
                _ => None,
            };
            let known = earlier.filter(|_| !perturbed[a as usize] && !perturbed[b as usize]);
            let guard = known.unwrap_or_else(|| {
                !(fan_ok(&pos, &nrm, &corners, &handles, a)
                    && fan_ok(&pos, &nrm, &corners, &handles, b))
            });
            if earlier.is_some_and(|g| g != guard) {
                differs[k] = true;
                perturbed[a as usize] = true;
                perturbed[b as usize] = true;
            }
            if guard {
                // the new boundary would turn a neighbour's projected angle over (a fold)
                handles[p] = old.0;
                handles[q] = old.1;
                out.fold_guarded.push([a, b]);
                guarded[k] = true;
                continue;
            }
        }
        quadratic[k] = true;
    }
    // triangles with the earlier corners and handles: their Step-4 patches are the earlier ones
    let mut same4: Vec<bool> = from.iter().map(|&f| f != crate::util::NONE).collect();
    for (k, &(p, q)) in pq.iter().enumerate() {
        if prev_edge[k].is_none() || differs[k] {
            same4[p / 3] = false;
            same4[q / 3] = false;
        }
    }
    // Steps 1–4 with the final boundaries, per macro triangle in parallel (the patch order is
    // the triangle order)
    // (in the output's array: allocated and first touched in parallel, then filled per macro
    // triangle; a reused triangle's Step-4 patches are the earlier surface's with the earlier
    // Step-4 111 points, see `PassCache`)
    let mut patches: Vec<MicroPatch> = (0..3 * nt)
        .into_par_iter()
        .map(|k| MicroPatch {
            macro_tri: (k / 3) as u32,
            control: [[0.0; 3]; 10],
        })
        .collect();
    patches
        .par_chunks_mut(3)
        .enumerate()
        .for_each(|(t, out)| match reuse {
            Some(r) if same4[t] => {
                let f = 3 * from[t] as usize;
                for (i, o) in out.iter_mut().enumerate() {
                    o.control = r.surf.patches[f + i].control;
                    o.control[4] = r.cache.step4_111[f + i];
                }
            }
            _ => {
                for (o, c) in out.iter_mut().zip(tri_patches(&handles, t)) {
                    o.control = c;
                }
            }
        });
    // Step 4's 111 points (Step 5 overwrites them in `patches`)
    let step4_111: Vec<P3> = patches.par_iter().map(|p| p.control[4]).collect();
    // Step 5: each edge reads only its own two patches' boundary rows and writes only their
    // 111 points, so the edges are solved in parallel and applied in edge order.
    let solved: Vec<(Solved, bool)> = edges
        .par_iter()
        .zip(&pq)
        .enumerate()
        .map(|(k, (&(a, b), &(p, q)))| {
            if let (Some(r), Some(i)) = (reuse, prev_edge[k]) {
                if same4[p / 3] && same4[q / 3] {
                    return (
                        Solved {
                            p,
                            q,
                            ..r.cache.solved[i]
                        },
                        true,
                    );
                }
            }
            let (e, fg) = edge_data(&patches, p, q);
            let sign_warning = fg[0] * fg[1] <= 0.0 || fg[2] * fg[3] <= 0.0;
            let len = vec::dist(e.m[0], e.m[3]);
            let old = (step4_111[p], step4_111[q]);
            let bound = MAX_MOVE * len;
            let lr94 = solve_94(&e, fg);
            let bounded94 = moves_at_most(lr94, old, bound);
            // ill-conditioned, or (9.4) would throw L1, R1 beyond the bound
            let singular = is_singular(fg) || !bounded94;
            let explicit = if quadratic[k] {
                super::transversal::transversal_edge(
                    &e.m,
                    &e.l,
                    &e.r,
                    nrm[a as usize],
                    nrm[b as usize],
                )
            } else {
                None
            };
            let explicit = explicit
                .map(|t| (t.l1, t.r1))
                .filter(|&lr| moves_at_most(lr, old, bound));
            let (lr, unresolved) = match explicit {
                Some(lr) => (lr, false),
                None if bounded94 => (lr94, false),
                None => {
                    let (lr, res) =
                        super::singular::solve_singular(&e.m, &e.l, &e.r, fg, old, SINGULAR);
                    if moves_at_most(lr, old, bound) {
                        (lr, res > RESOLVED || res.is_nan())
                    } else {
                        // no bounded solution: keep Step 4 (a reported crease, not a spike)
                        (old, true)
                    }
                }
            };
            let solved = Solved {
                p,
                q,
                lr,
                sign_warning,
                singular,
                unresolved,
                displacement: vec::dist(lr.0, step4_111[p]).max(vec::dist(lr.1, step4_111[q]))
                    / len,
            };
            (solved, false)
        })
        .collect();
    // triangles whose final patches are the earlier ones: Step 4 and all three edges kept
    let mut same_final = same4.clone();
    for (&(a, b), (r, kept)) in edges.iter().zip(&solved) {
        if r.sign_warning {
            out.sign_warnings.push([a, b]);
        }
        if r.singular {
            out.singular_edges.push([a, b]);
        }
        if r.unresolved {
            out.unresolved_edges.push([a, b]);
        }
        out.max_displacement = out.max_displacement.max(r.displacement);
        patches[r.p].control[4] = r.lr.0;
        patches[r.q].control[4] = r.lr.1;
        if !kept {
            same_final[r.p / 3] = false;
            same_final[r.q / 3] = false;
        }
    }
    // Step 6: the C¹ interior of each macro triangle (in parallel: a triangle's three patches)
    patches.par_chunks_mut(3).for_each(|tp| {
        let mut y = [[0.0; 3]; 3];
        for i in 0..3 {
            let (mi, mp) = (i, (i + 2) % 3);
            let w = tp[mi].control[2];
            y[i] = vec::scale(
                vec::add(vec::add(w, tp[mi].control[4]), tp[mp].control[4]),
                1.0 / 3.0,
            );
            tp[mi].control[5] = y[i];
            tp[mp].control[8] = y[i];
        }
        let z = vec::scale(vec::add(vec::add(y[0], y[1]), y[2]), 1.0 / 3.0);
        for p in tp.iter_mut() {
            p.control[9] = z;
        }
    });
    // The a-posteriori check (module doc): every macro edge certified or sampled as
    // `continuity` samples it; an edge between two triangles with the earlier final patches,
    // taken in the same order, keeps the earlier verdict.
    let earlier_bad = |k: usize| -> Option<bool> {
        let (r, i) = (reuse?, prev_edge[k]?);
        let (p, q) = pq[k];
        if !(same_final[p / 3] && same_final[q / 3]) {
            return None;
        }
        let f = |x: usize| 3 * from[x / 3] as usize + x % 3;
        ((p < q) == (f(p) < f(q))).then_some(r.cache.bad[i])
    };
    let kept_bad: Vec<Option<bool>> = (0..edges.len()).map(earlier_bad).collect();
    let todo: Vec<usize> = (0..edges.len())
        .filter(|&k| kept_bad[k].is_none())
        .collect();
    let pairs: Vec<(usize, usize)> = todo
        .iter()
        .map(|&k| {
            let (p, q) = pq[k];
            (p.min(q), p.max(q))
        })
        .collect();
    let checked = super::check::macro_edges_not_g1(|k| &patches[k].control, &pairs, 20);
    let mut bad: Vec<bool> = kept_bad.iter().map(|b| b.unwrap_or(false)).collect();
    for (&k, &b) in todo.iter().zip(&checked) {
        bad[k] = b;
    }
    out.non_g1_edges = edges
        .iter()
        .zip(&bad)
        .filter(|(_, &b)| b)
        .map(|(&(a, b), _)| [a, b])
        .collect();
    out.patches = patches;
    let cache = PassCache {
        triangles: mesh.triangles.clone(),
        edges,
        quad,
        guarded,
        solved: solved.into_iter().map(|(s, _)| s).collect(),
        bad,
        step4_111,
    };
    Ok((out, cache))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `closed_twins` against its definition, `check_closed`: on valid meshes (icospheres,
    /// a torus, a genus-3 surface, spot) every twin is the hash map's opposite half-edge and
    /// the unit normals are the same bits; on broken ones (a flipped triangle, a removed
    /// triangle, a repeated triangle, an index out of range, a repeated corner, a NaN
    /// position, a zero normal, too few normals) the error is `check_closed`'s.
    #[test]
    fn closed_twins_agree_with_check_closed() {
        use crate::geom::{Point3, Vector3};
        let normals =
            |m: &TriMesh| crate::mesh::vertex_normals(m, crate::mesh::NormalWeighting::Area);
        let mut meshes = vec![
            crate::mesh::generate::icosphere(0),
            crate::mesh::generate::icosphere(3),
            crate::mesh::generate::torus(2.0, 0.5, 24, 12),
            crate::mesh::generate::multi_torus(3),
        ];
        let spot = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/data/meshes/spot.obj"
        );
        if std::path::Path::new(spot).exists() {
            meshes.push(crate::io::read_mesh(std::path::Path::new(spot)).unwrap());
        }
        let bits = |u: &[P3]| -> Vec<u64> { u.iter().flatten().map(|x| x.to_bits()).collect() };
        for (k, m) in meshes.iter().enumerate() {
            let n = normals(m);
            let (half, unit) = check_closed(m, &n).unwrap();
            let (twin, unit2) = closed_twins(m, &n).unwrap();
            assert_eq!(bits(&unit), bits(&unit2), "mesh {k}");
            for (t, tri) in m.triangles.iter().enumerate() {
                for i in 0..3 {
                    let want = half[&(tri[(i + 1) % 3], tri[i])] as u32;
                    assert_eq!(twin[3 * t + i], want, "mesh {k}, half-edge {}", 3 * t + i);
                }
            }
        }
        let base = crate::mesh::generate::icosphere(2);
        let n = normals(&base);
        let mut broken: Vec<(TriMesh, Vec<Vector3>)> = Vec::new();
        let mut m = base.clone();
        m.triangles[7].swap(0, 1);
        broken.push((m, n.clone()));
        let mut m = base.clone();
        m.triangles.remove(11);
        broken.push((m, n.clone()));
        let mut m = base.clone();
        let t = m.triangles[3];
        m.triangles.push(t);
        broken.push((m, n.clone()));
        let mut m = base.clone();
        m.triangles[5][2] = m.positions.len() as u32;
        broken.push((m, n.clone()));
        let mut m = base.clone();
        m.triangles[9][1] = m.triangles[9][0];
        broken.push((m, n.clone()));
        let mut m = base.clone();
        m.positions[4] = Point3::new(f64::NAN, 0.0, 0.0);
        broken.push((m, n.clone()));
        let mut n0 = n.clone();
        n0[6] = Vector3::new(0.0, 0.0, 0.0);
        broken.push((base.clone(), n0));
        broken.push((base.clone(), n[..n.len() - 1].to_vec()));
        for (k, (m, n)) in broken.iter().enumerate() {
            let want = check_closed(m, n).map(|_| ()).unwrap_err();
            let got = closed_twins(m, n).map(|_| ()).unwrap_err();
            assert_eq!(got, want, "broken mesh {k}");
        }
    }

    /// The residual of (9.3b, c) at `(l1, r1)`, per unit edge length, computed on offsets
    /// from `M1` (independently of `solve_94`'s arrangement: straight from the equations).
    fn residual_93(e: &EdgeData, [f0, g0, f1, g1]: [f64; 4], (l1, r1): (P3, P3)) -> f64 {
        let (m, l, r) = (e.m, e.l, e.r);
        let d = vec::sub;
        let (u, v) = (d(l1, m[1]), d(r1, m[1]));
        let mut worst: f64 = 0.0;
        for k in 0..3 {
            // 9.3b: (M1−M0)·1 ... written as the coefficient of B²₁ of the degree-3 product
            let eq_b = d(m[1], m[0])[k]
                + 2.0 * d(m[2], m[1])[k]
                + f1 * d(l[0], m[0])[k]
                + g1 * d(r[0], m[0])[k]
                + 2.0 * f0 * u[k]
                + 2.0 * g0 * v[k];
            let eq_c = d(m[3], m[2])[k]
                + 2.0 * d(m[2], m[1])[k]
                + f0 * d(l[2], m[2])[k]
                + g0 * d(r[2], m[2])[k]
                + 2.0 * f1 * u[k]
                + 2.0 * g1 * v[k];
            worst = worst.max(eq_b.abs()).max(eq_c.abs());
        }
        worst / vec::dist(m[0], m[3])
    }

    #[test]
    fn solve_94_is_backward_stable_on_a_nearly_mirror_symmetric_edge_far_from_the_origin() {
        // an edge of unit length at distance 100 from the origin whose sides are mirror
        // images up to `eps`: Δ = f0 g1 − g0 f1 ≈ eps (fandisk's nearly flat edges)
        let o = [100.0, -60.0, 40.0];
        let at = |p: P3| vec::add(o, p);
        for eps in [1e-7, 1e-9, 1e-11] {
            let e = EdgeData {
                m: [
                    at([0.0, 0.0, 0.0]),
                    at([0.33, 0.0, 0.01]),
                    at([0.67, 0.0, 0.012]),
                    at([1.0, 0.0, 0.0]),
                ],
                l: [
                    at([0.2, 0.3, 0.004]),
                    at([0.5, 0.3, 0.01]),
                    at([0.8, 0.3, 0.004]),
                ],
                r: [
                    at([0.2, -0.3 - eps, 0.004]),
                    at([0.5, -0.3, 0.01]),
                    at([0.8, -0.3 + 0.5 * eps, 0.004]),
                ],
            };
            let (f0, g0) = solve_fg(
                vec::sub(e.m[1], e.m[0]),
                vec::sub(e.l[0], e.m[0]),
                vec::sub(e.r[0], e.m[0]),
            );
            let (f1, g1) = solve_fg(
                vec::sub(e.m[3], e.m[2]),
                vec::sub(e.l[2], e.m[2]),
                vec::sub(e.r[2], e.m[2]),
            );
            let fg = [f0, g0, f1, g1];
            let lr = solve_94(&e, fg);
            let res = residual_93(&e, fg, lr);
            // the rounding of storing L1, R1: a few ulps of their distance from the origin
            let size = vec::norm(lr.0).max(vec::norm(lr.1));
            eprintln!(
                "eps {eps}: residual {res:e}, size {size:e}, Δ {:e}",
                f0 * g1 - g0 * f1
            );
            assert!(
                res < 1e-15 * size,
                "eps {eps}: residual {res:e}, size {size:e}"
            );
        }
    }
}

//! The cubic two-split G¹ surface (Veltkamp 1992, §9.7 "Towards an adaptive splitting scheme";
//! NOTES B.6): chosen pairs of adjacent macro triangles are each split at the midpoint of their
//! common edge (4 micro patches per pair), every other macro triangle is three-split (§9.6,
//! [`super::three_split_with`]). Experimental, as the notes recommend: the text leaves the
//! construction incomplete, and the parts below that replace it are derived here.
//!
//! **Which pairs (the text's purpose: avoid thin micro triangles).** A macro edge `AB` with
//! triangles `P = (A,B,C)`, `Q = (B,A,D)` is a candidate when the worst two-split micro
//! triangle (`(A,M,C)`, `(M,B,C)`, `(B,M,D)`, `(M,A,D)`, `M` the edge midpoint) is better
//! than the worst three-split micro triangle of `P` and `Q` (quality `2√3·|cross|/Σ|edge|²`,
//! 1 for equilateral), its four outer edges admit the normal field below, and the unfolded
//! quadrilateral `ACBD` is convex at `A` and `B`. Candidates are taken greedily, thinnest
//! three-split micro triangle first (ties by edge), when neither triangle is paired or next
//! to a pair (the text's precondition: the four other neighbours of a pair are three-split).
//! A heuristic choice, not a geometric decision: any set of pairs is a valid surface.
//!
//! **Why not (9.6a–b) (found here).** With constant `e_i, f_i, g_i` fixed at the far ends
//! (C0 of (9.5)), (9.6b) is, for `d_i = Y_i − Z`, the homogeneous 4×4 system
//! `(−e_i−f_i−g_i) d_i + f_i d_{i−1} + g_i d_{i+1} = 0` per coordinate: regular for generic
//! data, so every solution — the least-squares one included — has `Y_i = Z`, a singular point
//! of all four patches at `Z` (the tangent plane there is undefined). It has a plane of
//! solutions only when the far-end ratios happen to be those of a planar star (the symmetric
//! case `f = g = −e/2`). So the pair is built differently:
//!
//! 1. **Inside the pair: C¹ over one planar domain.** `P ∪ Q` is unfolded about `AB` into the
//!    plane; the four micro patches are made C¹ over that domain (C¹ ⇒ tangent-plane
//!    continuous wherever the patches are regular). With `D = αA + βM + γC` and
//!    `D = α'B + β'M + γ'C` in the domain (`γ = γ'`: both are the ratio of the heights of `D`
//!    and `C` above `AB`), the C¹ conditions across `A–M` are, row by row from `A`:
//!    `h_AD = αA + βW_A + γh_AC` (this sets the diagonal's handle `W_A` in `A`'s tangent plane),
//!    `X_4 = αW_A + βY_A + γX_1`, `Y_D = αY_A + βZ + γY_C`; across `B–M` the same with
//!    `α', β'`; across `M–C` and `M–D` (inside one macro triangle, `M` the midpoint):
//!    `W_C = (h_CA + h_CB)/2` (Step 4 gives it), `X_1 + X_2 = 2Y_C`, `X_3 + X_4 = 2Y_D`,
//!    `Y_A + Y_B = 2Z`. Seven vector equations of rank six in the nine points
//!    `X_1..X_4, Y_A..Y_D, Z`: three points of freedom per coordinate.
//! 2. **Outer edges: a prescribed normal field (replacing (9.7) and the Farin ratio the text
//!    does not give).** Each outer edge has the three-split's degree-elevated quadratic
//!    boundary (required for a candidate), so `T(s) = K − M` is linear and Peters' linearly
//!    varying normal `n(s) = (1−s) n0 + s ρ n1` with `ρ = −(n0·T1)/(n1·T0)` (positive exactly
//!    when the edge is not inflected; `ρ = 1` on a straight edge in one plane) satisfies
//!    `n·T ≡ 0`. A side is tangent to `n(s)^⊥` iff its cross-boundary derivative `D = L − M`
//!    (V (8.8)) has `n·D ≡ 0`: a cubic whose end coefficients vanish (the rows lie in the
//!    vertex tangent planes) and whose middle ones give two linear conditions on the side's
//!    111 point, `2 n0·D1 + ρ n1·D0 = 0`, `2ρ n1·D1 + n0·D2 = 0`. On the pair's side these 8
//!    conditions join the C¹ system (a 29×27 linear system, solved nearest the Step-4
//!    subdivision values by the pseudo-inverse: the notes' squared least-squares completion);
//!    on the three-split neighbour's side they set its 111 point (nearest its three-split
//!    value), whose interior is then rebuilt by Clough–Tocher (Step 6). Both sides are then
//!    orthogonal to the same `n(s)`: G¹ where they lie on opposite sides of the boundary.
//!
//! **Checked, not assumed.** A pair is kept only if its system leaves no residual (relative
//! `RESOLVED`), no control point moves more than `MAX_MOVE` of the pair's longest edge, and a
//! local check of its 8 micro edges (both sides' unit normals at `CHECK_SAMPLES` points) finds
//! no jump above 1e-9 rad and no fold; otherwise both triangles stay three-split (counted in
//! [`TwoSplit::rejected`]). The surface's edges are then those of the three-split (reported
//! there) and of accepted pairs; the independent check [`super::continuity`] measures all.
//! Vertices and normals are interpolated: corners and vertex rows stay in the tangent planes.
//! Linear precision: on a plane with one normal the Step-4 values satisfy every condition
//! and nothing moves. O(triangles), pairs in parallel.
//!
//! **What it achieves (measured, bench/README.md).** Perturbed icospheres: 11–20 pairs each,
//! every macro and micro edge G¹ to 2e-13 rad wherever the three-split is. Real scans (area
//! normals, visibility repair, fold guard): spot 817 pairs, bunny_npm 236, fandisk 1 253,
//! rocker-arm 767, horse 4 629; the non-G¹ edges are exactly the three-split's (spot 18,
//! bunny_npm 11, fandisk 1 098, rocker-arm 24: all reported by the three-split part), none in
//! or around a pair. But many candidates are rejected (spot 333, rocker-arm 1 993, horse
//! 6 385), so far fewer thin three-split micro triangles are avoided than candidates exist;
//! the rejections spread over the three causes ([`Rejections`]; spot 138 system, 92 move,
//! 103 check). The
//! construction costs about twice the three-split's (it builds the three-split first, then a
//! 29×27 SVD and a local check per candidate).

use super::split3::{check_closed, three_split_once, MicroPatch, SplitOptions, SplitSurface};
use super::triangle::{tri_index, BezierTriangle};
use super::SmoothError;
use crate::geom::vec;
use crate::mesh::TriMesh;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

type P3 = [f64; 3];

/// Smallest (and inverse largest) end-normal scale `ρ` of an outer edge's field.
const RHO_MIN: f64 = 0.1;
/// Relative size below which `n0·T1` and `n1·T0` count as zero (straight edge in one plane).
const FLAT: f64 = 1e-12;
/// Largest relative third difference of a degree-elevated quadratic boundary.
const QUADRATIC: f64 = 1e-12;
/// Smallest domain coefficient `β`, `β'` of the midpoint (convexity at `A`, `B`).
const CONVEX: f64 = 0.05;
/// Smallest `n0·n1` of an outer edge's end normals (the field must not vanish).
const NORMAL_DOT: f64 = -0.5;
/// Largest move of a control point, in longest edges of the pair.
const MAX_MOVE: f64 = 1.0;
/// Largest residual of the pair's system, relative to its longest edge.
const RESOLVED: f64 = 1e-10;
/// Relative singular-value cut-off of the pseudo-inverse.
const CUT: f64 = 1e-12;
/// Samples per micro edge of a pair's local check.
const CHECK_SAMPLES: usize = 12;
/// Largest normal jump accepted by the local check (rad).
const G1_TOL: f64 = 1e-9;

/// A two-split surface: the patches and what the pairing did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TwoSplit {
    /// The micro patches: 2 per paired macro triangle, 3 per three-split one, in triangle
    /// order; [`SplitSurface::domain`] gives each patch's corners in its macro triangle. The
    /// edge lists are the three-split's, less the edges the pairs rebuilt.
    pub surface: SplitSurface,
    /// Accepted pairs `[P, Q]` of macro triangles (P < Q).
    pub pairs: Vec<[u32; 2]>,
    /// Candidate pairs chosen but left three-split because their system kept a residual,
    /// moved a point too far or the local check found a jump or fold (module doc).
    pub rejected: Vec<[u32; 2]>,
    /// How many of [`TwoSplit::rejected`] failed at which step.
    pub rejected_by: Rejections,
}

/// Why candidate pairs were rejected (counts).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Rejections {
    /// The domain is not convex at `A` or `B`, a vertex fan would turn, an outer edge has no
    /// field, or the linear system (pair or neighbour side) keeps a residual.
    pub system: usize,
    /// A control point would move more than `MAX_MOVE` longest edges.
    pub moved: usize,
    /// The local check found a normal jump above 1e-9 rad or a fold.
    pub check: usize,
}

/// Why one pair was rejected.
#[derive(Debug, Clone, Copy)]
enum Reject {
    System,
    Move,
    Check,
}

/// The field scale `ρ` of an outer edge with boundary `m` (start normal `n0`, end `n1`), or
/// `None` when the boundary is not a degree-elevated quadratic or the edge is inflected.
fn field_rho(m: &[P3; 4], n0: P3, n1: P3) -> Option<f64> {
    let len = vec::dist(m[0], m[3]);
    let third = vec::add(vec::sub(m[3], m[0]), vec::scale(vec::sub(m[1], m[2]), 3.0));
    if len.is_nan()
        || len <= 0.0
        || vec::norm(third) > QUADRATIC * len
        || vec::dot(n0, n1) < NORMAL_DOT
    {
        return None;
    }
    let (t0, t1) = (vec::sub(m[1], m[0]), vec::sub(m[3], m[2]));
    let (num, den) = (-vec::dot(n0, t1), vec::dot(n1, t0));
    let scale = vec::norm(t0) + vec::norm(t1);
    if num.abs() <= FLAT * scale && den.abs() <= FLAT * scale {
        return Some(1.0);
    }
    let rho = num / den;
    (rho.is_finite() && (RHO_MIN..=1.0 / RHO_MIN).contains(&rho)).then_some(rho)
}

/// The two field conditions on a side's 111 point `x`: rows `(normal, value)` with
/// `normal·x = value` (module doc, step 2): `m` the boundary, `l0`, `l2` the side's row ends.
fn field_rows(m: &[P3; 4], l0: P3, l2: P3, n0: P3, n1: P3, rho: f64) -> [(P3, f64); 2] {
    let d0 = vec::sub(l0, m[0]);
    let d2 = vec::sub(l2, m[2]);
    [
        (n0, vec::dot(n0, m[1]) - 0.5 * rho * vec::dot(n1, d0)),
        (n1, vec::dot(n1, m[1]) - vec::dot(n0, d2) / (2.0 * rho)),
    ]
}

/// Quality `2√3·|(b−a)×(c−a)| / (|ab|²+|bc|²+|ca|²)` of a flat triangle (1: equilateral).
fn quality(a: P3, b: P3, c: P3) -> f64 {
    let s = vec::dist2(a, b) + vec::dist2(b, c) + vec::dist2(c, a);
    let q = 2.0 * 3f64.sqrt() * vec::norm(vec::cross(vec::sub(b, a), vec::sub(c, a))) / s;
    if q.is_finite() {
        q
    } else {
        0.0
    }
}

/// The macro patch of triangle `t` (Steps 1–3) rebuilt from its three-split micro patches:
/// patch `3t+k` carries the handles of edge `V_k → V_{k+1}` at indices 1 and 3.
fn macro_patch(tp: &[[P3; 10]]) -> BezierTriangle {
    let h = |k: usize| (tp[k][1], tp[k][3]); // (h(V_k→V_k+1), h(V_k+1→V_k))
    let v = [tp[0][0], tp[1][0], tp[2][0]];
    let mut c = [[0.0; 3]; 10];
    c[tri_index(3, 3, 0)] = v[0];
    c[tri_index(3, 0, 3)] = v[1];
    c[tri_index(3, 0, 0)] = v[2];
    c[tri_index(3, 2, 1)] = h(0).0;
    c[tri_index(3, 1, 2)] = h(0).1;
    c[tri_index(3, 0, 2)] = h(1).0;
    c[tri_index(3, 0, 1)] = h(1).1;
    c[tri_index(3, 1, 0)] = h(2).0;
    c[tri_index(3, 2, 0)] = h(2).1;
    let se = [h(0).0, h(0).1, h(1).0, h(1).1, h(2).0, h(2).1]
        .iter()
        .fold([0.0; 3], |s, p| vec::add(s, *p));
    let sv = vec::add(vec::add(v[0], v[1]), v[2]);
    c[tri_index(3, 1, 1)] = vec::sub(vec::scale(se, 0.25), vec::scale(sv, 1.0 / 6.0));
    BezierTriangle::new(3, c.to_vec())
}

/// The unit-vector basis `e_k` of barycentric coordinates.
fn unit(k: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[k % 3] = 1.0;
    e
}

/// One chosen pair: triangle `p` with the common edge `i` (`A = p[i]`, `B = p[i+1]`), `q`
/// with edge `j` (`B = q[j]`, `A = q[j+1]`).
#[derive(Clone, Copy)]
struct Pair {
    p: usize,
    i: usize,
    q: usize,
    j: usize,
}

/// What a pair's construction produced: its four micro patches `(A,M,C)`, `(M,B,C)`,
/// `(B,M,D)`, `(M,A,D)` and the neighbours' new 111 points `(patch index, point)`.
struct Built {
    patches: [[P3; 10]; 4],
    nbr: [(usize, P3); 4],
    displacement: f64,
}

/// The shared data of a run.
struct Ctx<'a> {
    tris: &'a [[u32; 3]],
    nrm: &'a [P3],
    half: &'a crate::util::IdMap<(u32, u32), usize>,
    base: &'a [[P3; 10]],
}

impl Ctx<'_> {
    /// The outer edge `a → b` of the pair (a half-edge of the pair's triangle): its boundary,
    /// end normals and field scale; `None` if it admits no field.
    fn outer(&self, a: u32, b: u32) -> Option<([P3; 4], P3, P3, f64)> {
        let pp = &self.base[self.half[&(a, b)]];
        let m = [pp[0], pp[1], pp[3], pp[6]];
        let (n0, n1) = (self.nrm[a as usize], self.nrm[b as usize]);
        field_rho(&m, n0, n1).map(|rho| (m, n0, n1, rho))
    }

    /// The corners `A, B, C, D` of a pair.
    fn corners(&self, pr: &Pair) -> [u32; 4] {
        let (tp, tq) = (self.tris[pr.p], self.tris[pr.q]);
        [
            tp[pr.i],
            tp[(pr.i + 1) % 3],
            tp[(pr.i + 2) % 3],
            tq[(pr.j + 2) % 3],
        ]
    }

    /// Steps 4–5 of a pair (module doc), or why it is rejected.
    fn build(&self, pr: &Pair) -> Result<Built, Reject> {
        let [a, b, c, d] = self.corners(pr);
        let mp = macro_patch(&self.base[3 * pr.p..3 * pr.p + 3]);
        let mq = macro_patch(&self.base[3 * pr.q..3 * pr.q + 3]);
        let (ea, eb, ec) = (unit(pr.i), unit(pr.i + 1), unit(pr.i + 2));
        let mid = vec::midpoint(ea, eb);
        let (fb, fa, fd) = (unit(pr.j), unit(pr.j + 1), unit(pr.j + 2));
        let midq = vec::midpoint(fb, fa);
        let old = [
            mp.subdivide(ea, mid, ec),
            mp.subdivide(mid, eb, ec),
            mq.subdivide(fb, midq, fd),
            mq.subdivide(midq, fa, fd),
        ]
        .map(|t| {
            let mut c = [[0.0; 3]; 10];
            c.copy_from_slice(&t.control);
            c
        });
        let [p1, p2, q1, q2] = old;
        let (pa, pb, pc, pd) = (p1[0], p2[6], p1[9], q1[9]);
        let lmax = [(pa, pb), (pb, pc), (pc, pa), (pa, pd), (pd, pb)]
            .iter()
            .fold(0.0f64, |s, &(x, y)| s.max(vec::dist(x, y)));
        // the unfolded domain: A = 0, B = (len, 0), C above, D below
        let ab = vec::sub(pb, pa);
        let len = vec::norm(ab);
        let flat = |x: P3| {
            let r = vec::sub(x, pa);
            (vec::dot(r, ab) / len, vec::norm(vec::cross(r, ab)) / len)
        };
        let ((xc, yc), (xd, yd)) = (flat(pc), flat(pd));
        let yd = -yd;
        let g = yd / yc;
        let beta = (xd - g * xc) / (0.5 * len);
        let alpha = 1.0 - beta - g;
        let beta2 = -((xd - len) - g * (xc - len)) / (0.5 * len);
        let alpha2 = 1.0 - beta2 - g;
        if !(beta >= CONVEX && beta2 >= CONVEX && g.is_finite()) {
            return Err(Reject::System);
        }
        // handles and the diagonal's vertex rows from the C¹ conditions at A and B
        let (h_ac, h_ca, h_ad, h_da) = (p1[2], p1[5], q2[7], q2[8]);
        let (h_bc, h_cb, h_bd, h_db) = (p2[7], p2[8], q1[2], q1[5]);
        let w_a = vec::scale(
            vec::add_scaled(vec::add_scaled(h_ad, -alpha, pa), -g, h_ac),
            1.0 / beta,
        );
        let w_b = vec::scale(
            vec::add_scaled(vec::add_scaled(h_bd, -alpha2, pb), -g, h_bc),
            1.0 / beta2,
        );
        let (w_c, w_d) = (p1[8], q1[8]);
        // the new diagonal handles must keep the vertex fans at A and B (exact orientation of
        // each corner's two handles about the vertex normal; W_A is a positive combination of
        // h_AC and h_AD, so this fails only where their projected angle is reflex)
        let turns = |v: P3, n: P3, h1: P3, h2: P3| {
            crate::geom::predicates::raw::orient3d(v, h1, h2, vec::add(v, n)) < 0.0
        };
        let (na, nb) = (self.nrm[a as usize], self.nrm[b as usize]);
        if !(turns(pa, na, w_a, h_ac)
            && turns(pa, na, h_ad, w_a)
            && turns(pb, nb, h_bc, w_b)
            && turns(pb, nb, w_b, h_bd))
        {
            return Err(Reject::System);
        }
        let mut displacement = (vec::dist(w_a, p1[1]).max(vec::dist(w_b, p2[3]))) / lmax;
        // unknowns: X1 X2 X3 X4 YA YB YC YD Z, old values from Step 4
        let x_old = [
            p1[4],
            p2[4],
            q1[4],
            q2[4],
            p1[3],
            p2[1],
            p1[7],
            q1[7],
            vec::midpoint(p1[6], q1[6]),
        ];
        let (x1, x2, x3, x4, ya, yb, yc_, yd_, z) = (0, 1, 2, 3, 4, 5, 6, 7, 8);
        // C¹ rows: (coefficients over unknowns, known right-hand side)
        let c1: Vec<(Vec<(usize, f64)>, P3)> = vec![
            (
                vec![(x4, 1.0), (ya, -beta), (x1, -g)],
                vec::scale(w_a, alpha),
            ),
            (
                vec![(yd_, 1.0), (ya, -alpha), (z, -beta), (yc_, -g)],
                [0.0; 3],
            ),
            (
                vec![(x3, 1.0), (yb, -beta2), (x2, -g)],
                vec::scale(w_b, alpha2),
            ),
            (
                vec![(yd_, 1.0), (yb, -alpha2), (z, -beta2), (yc_, -g)],
                [0.0; 3],
            ),
            (vec![(x1, 1.0), (x2, 1.0), (yc_, -2.0)], [0.0; 3]),
            (vec![(ya, 1.0), (yb, 1.0), (z, -2.0)], [0.0; 3]),
            (vec![(x3, 1.0), (x4, 1.0), (yd_, -2.0)], [0.0; 3]),
        ];
        // outer edges (pair orientation), the side's row ends, its unknown, the neighbour
        let outer = [
            (c, a, w_c, w_a, x1),
            (b, c, w_b, w_c, x2),
            (d, b, w_d, w_b, x3),
            (a, d, w_a, w_d, x4),
        ];
        let mut fields = Vec::with_capacity(4);
        for &(u, v, l0, l2, x) in &outer {
            let (m, n0, n1, rho) = self.outer(u, v).ok_or(Reject::System)?;
            fields.push((m, n0, n1, rho, field_rows(&m, l0, l2, n0, n1, rho), x));
        }
        let rows = 3 * c1.len() + 8;
        let mut am = DMatrix::<f64>::zeros(rows, 27);
        let mut bv = DVector::<f64>::zeros(rows);
        for (e, (coef, rhs)) in c1.iter().enumerate() {
            for k in 0..3 {
                for &(u, w) in coef {
                    am[(3 * e + k, 3 * u + k)] += w;
                }
                bv[3 * e + k] = rhs[k];
            }
        }
        let mut r = 3 * c1.len();
        for f in &fields {
            for (nn, val) in f.4 {
                for k in 0..3 {
                    am[(r, 3 * f.5 + k)] = nn[k];
                }
                bv[r] = val;
                r += 1;
            }
        }
        let xo = DVector::from_iterator(27, x_old.iter().flat_map(|p| p.iter().copied()));
        let svd = am.clone().svd(true, true);
        let cut = CUT * svd.singular_values.max();
        let corr = svd
            .solve(&(&bv - &am * &xo), cut)
            .map_err(|_| Reject::System)?;
        let xs = &xo + corr;
        let res = (&am * &xs - &bv).amax();
        if res.is_nan() || res > RESOLVED * lmax {
            return Err(Reject::System);
        }
        let pt = |u: usize| [xs[3 * u], xs[3 * u + 1], xs[3 * u + 2]];
        for (u, o) in x_old.iter().enumerate() {
            displacement = displacement.max(vec::dist(pt(u), *o) / lmax);
        }
        let (zz, ya_, yb_, yc, yd) = (pt(z), pt(ya), pt(yb), pt(yc_), pt(yd_));
        let patches = [
            [pa, w_a, h_ac, ya_, pt(x1), h_ca, zz, yc, w_c, pc],
            [zz, yb_, yc, w_b, pt(x2), w_c, pb, h_bc, h_cb, pc],
            [pb, w_b, h_bd, yb_, pt(x3), h_db, zz, yd, w_d, pd],
            [zz, ya_, yd, w_a, pt(x4), w_d, pa, h_ad, h_da, pd],
        ];
        // the neighbours' 111 points on the same fields (pair orientation u → v: the
        // neighbour's patch runs v → u, its row is [7] at u, [4], [2] at v)
        let mut nbr = [(0usize, [0.0; 3]); 4];
        for (k, (&(u, v, ..), f)) in outer.iter().zip(&fields).enumerate() {
            let idx = self.half[&(v, u)];
            let np = &self.base[idx];
            let (m, n0, n1, rho) = (f.0, f.1, f.2, f.3);
            let rows = field_rows(&m, np[7], np[2], n0, n1, rho);
            let x = min_norm(rows, np[4]).ok_or(Reject::System)?;
            displacement = displacement.max(vec::dist(x, np[4]) / lmax);
            nbr[k] = (idx, x);
        }
        if displacement.is_nan() || displacement > MAX_MOVE {
            return Err(Reject::Move);
        }
        let built = Built {
            patches,
            nbr,
            displacement,
        };
        if self.locally_g1(&built) {
            Ok(built)
        } else {
            Err(Reject::Check)
        }
    }

    /// The local check of a pair: every micro edge inside it and its four outer edges (with
    /// the neighbours' new 111 points) are G¹ at `CHECK_SAMPLES` points, without folds.
    fn locally_g1(&self, b: &Built) -> bool {
        let t: Vec<BezierTriangle> = b
            .patches
            .iter()
            .map(|c| BezierTriangle::new(3, c.to_vec()))
            .collect();
        let nb: Vec<BezierTriangle> = b
            .nbr
            .iter()
            .map(|&(idx, x)| {
                let mut c = self.base[idx];
                c[4] = x;
                BezierTriangle::new(3, c.to_vec())
            })
            .collect();
        // (patch, corner i → i+1) against (patch, corner j → j+1) run the other way
        let inner = [
            (&t[0], 1, &t[1], 2), // M–C
            (&t[2], 1, &t[3], 2), // M–D
            (&t[0], 0, &t[3], 0), // A–M
            (&t[1], 0, &t[2], 0), // M–B
            (&t[0], 2, &nb[0], 0),
            (&t[1], 1, &nb[1], 0),
            (&t[2], 2, &nb[2], 0),
            (&t[3], 1, &nb[3], 0),
        ];
        inner.iter().all(|&(p, i, q, j)| {
            (1..=CHECK_SAMPLES).all(|k| {
                let s = k as f64 / (CHECK_SAMPLES + 1) as f64;
                let bp = vec::lerp(unit(i), unit(i + 1), s);
                let bq = vec::lerp(unit(j), unit(j + 1), 1.0 - s);
                let (n1, n2) = (p.normal(bp), q.normal(bq));
                let dot = vec::dot(n1, n2);
                dot > 0.0 && vec::norm(vec::cross(n1, n2)).atan2(dot) <= G1_TOL
            })
        })
    }
}

/// The point nearest `old` meeting both rows `normal·x = value` (pseudo-inverse), or `None`
/// if they are inconsistent.
fn min_norm(rows: [(P3, f64); 2], old: P3) -> Option<P3> {
    let n = nalgebra::Matrix2x3::from_fn(|i, k| rows[i].0[k]);
    let o = nalgebra::Vector3::from(old);
    let b = nalgebra::Vector2::new(rows[0].1, rows[1].1);
    let svd = n.svd(true, true);
    let cut = CUT * svd.singular_values.max();
    let x = o + svd.solve(&(b - n * o), cut).ok()?;
    let res = (n * x - b).amax();
    let scale = old.iter().fold(1.0f64, |s, c| s.max(c.abs()));
    (res <= RESOLVED * scale).then_some([x[0], x[1], x[2]])
}

/// The three-split's Step 6 (C¹ Clough–Tocher interior) on one macro triangle's patches.
fn clough_tocher(tp: &mut [[P3; 10]]) {
    let mut y = [[0.0; 3]; 3];
    for i in 0..3 {
        let mp = (i + 2) % 3;
        y[i] = vec::scale(vec::add(vec::add(tp[i][2], tp[i][4]), tp[mp][4]), 1.0 / 3.0);
        tp[i][5] = y[i];
        tp[mp][8] = y[i];
    }
    let z = vec::scale(vec::add(vec::add(y[0], y[1]), y[2]), 1.0 / 3.0);
    for p in tp.iter_mut() {
        p[9] = z;
    }
}

/// The cubic two-split G¹ surface (module doc) with the three-split's options for the
/// triangles left three-split.
///
/// ```
/// use morpho::mesh::{generate, vertex_normals, NormalWeighting};
/// use morpho::smooth::{continuity, two_split, SplitOptions};
/// let m = generate::icosphere(1);
/// let n = vertex_normals(&m, NormalWeighting::Area);
/// let s = two_split(&m, &n, &SplitOptions::default()).unwrap();
/// assert!(!s.pairs.is_empty());
/// let c = continuity(&s.surface, 20);
/// assert_eq!(c.folds, 0);
/// ```
pub fn two_split(
    mesh: &TriMesh,
    normals: &[crate::geom::Vector3],
    opts: &SplitOptions,
) -> Result<TwoSplit, SmoothError> {
    let base = three_split_once(mesh, normals, opts)?;
    let (half, nrm) = check_closed(mesh, normals)?;
    let pos: Vec<P3> = mesh.positions.iter().map(|p| (*p).into()).collect();
    let mut patches: Vec<[P3; 10]> = base.patches.iter().map(|p| p.control).collect();
    let tris = &mesh.triangles;
    let ctx = Ctx {
        tris,
        nrm: &nrm,
        half: &half,
        base: &patches,
    };
    let unresolved: std::collections::HashSet<[u32; 2]> =
        base.unresolved_edges.iter().copied().collect();
    let key = |a: u32, b: u32| [a.min(b), a.max(b)];
    // candidates: (worst three-split quality, edge, pair)
    let mut edges: Vec<(u32, u32)> = half.keys().copied().filter(|&(a, b)| a < b).collect();
    edges.sort_unstable();
    let q3 = |t: usize| {
        let v = tris[t].map(|i| pos[i as usize]);
        let z = vec::scale(vec::add(vec::add(v[0], v[1]), v[2]), 1.0 / 3.0);
        (0..3).fold(1.0f64, |s, i| s.min(quality(v[i], v[(i + 1) % 3], z)))
    };
    let mut cands: Vec<(f64, usize, Pair)> = edges
        .par_iter()
        .enumerate()
        .filter_map(|(e, &(a, b))| {
            let (hp, hq) = (half[&(a, b)], half[&(b, a)]);
            let pr = Pair {
                p: hp / 3,
                i: hp % 3,
                q: hq / 3,
                j: hq % 3,
            };
            let [ca, cb, cc, cd] = ctx.corners(&pr);
            let outer = [(cc, ca), (cb, cc), (cd, cb), (ca, cd)];
            // the four outer neighbours are other triangles, their edges admit a field
            let ok = outer.iter().all(|&(u, v)| {
                let t = half[&(v, u)] / 3;
                t != pr.p
                    && t != pr.q
                    && !unresolved.contains(&key(u, v))
                    && ctx.outer(u, v).is_some()
            });
            if !ok || pr.p == pr.q {
                return None;
            }
            let [pa, pb, pc, pd] = [ca, cb, cc, cd].map(|v| pos[v as usize]);
            let m = vec::midpoint(pa, pb);
            let two = quality(pa, m, pc)
                .min(quality(m, pb, pc))
                .min(quality(pb, m, pd))
                .min(quality(m, pa, pd));
            let three = q3(pr.p).min(q3(pr.q));
            (two > three).then_some((three, e, pr))
        })
        .collect();
    cands.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    // greedy: 0 free, 1 paired, 2 next to a pair
    let mut state = vec![0u8; tris.len()];
    let mut chosen = Vec::new();
    let nbrs = |t: usize| -> [usize; 3] {
        let v = tris[t];
        [0, 1, 2].map(|i| half[&(v[(i + 1) % 3], v[i])] / 3)
    };
    for &(_, _, pr) in &cands {
        if state[pr.p] != 0 || state[pr.q] != 0 {
            continue;
        }
        state[pr.p] = 1;
        state[pr.q] = 1;
        for t in nbrs(pr.p).into_iter().chain(nbrs(pr.q)) {
            if state[t] == 0 {
                state[t] = 2;
            }
        }
        chosen.push(pr);
    }
    let built: Vec<Result<Built, Reject>> = chosen.par_iter().map(|pr| ctx.build(pr)).collect();
    let mut out = TwoSplit::default();
    let mut pair_of: Vec<Option<(usize, usize)>> = vec![None; tris.len()]; // (built index, side)
    let mut rebuilt_edges = std::collections::HashSet::new();
    let mut displacement = base.max_displacement;
    for (k, (pr, b)) in chosen.iter().zip(&built).enumerate() {
        let pq = [pr.p.min(pr.q) as u32, pr.p.max(pr.q) as u32];
        let b = match b {
            Ok(b) => b,
            Err(why) => {
                out.rejected.push(pq);
                match why {
                    Reject::System => out.rejected_by.system += 1,
                    Reject::Move => out.rejected_by.moved += 1,
                    Reject::Check => out.rejected_by.check += 1,
                }
                continue;
            }
        };
        out.pairs.push(pq);
        pair_of[pr.p] = Some((k, 0));
        pair_of[pr.q] = Some((k, 1));
        let [a, bb, c, d] = ctx.corners(pr);
        for (u, v) in [(a, bb), (c, a), (bb, c), (d, bb), (a, d)] {
            rebuilt_edges.insert(key(u, v));
        }
        displacement = displacement.max(b.displacement);
    }
    for b in built.iter().flatten() {
        for &(idx, x) in &b.nbr {
            patches[idx][4] = x;
        }
    }
    // Step 6 again on the three-split triangles next to a pair
    patches.par_chunks_mut(3).enumerate().for_each(|(t, tp)| {
        if pair_of[t].is_none() {
            clough_tocher(tp);
        }
    });
    let z3 = [1.0 / 3.0; 3];
    let mut s = SplitSurface::default();
    for t in 0..tris.len() {
        match pair_of[t] {
            None => {
                for k in 0..3 {
                    s.patches.push(MicroPatch {
                        macro_tri: t as u32,
                        control: patches[3 * t + k],
                    });
                    s.domain.push([unit(k), unit(k + 1), z3]);
                }
            }
            Some((k, side)) => {
                // only accepted pairs are recorded in pair_of
                let (Ok(b), pr) = (&built[k], &chosen[k]) else {
                    continue;
                };
                let (i, first) = if side == 0 { (pr.i, 0) } else { (pr.j, 2) };
                let m = vec::midpoint(unit(i), unit(i + 1));
                s.patches.push(MicroPatch {
                    macro_tri: t as u32,
                    control: b.patches[first],
                });
                s.domain.push([unit(i), m, unit(i + 2)]);
                s.patches.push(MicroPatch {
                    macro_tri: t as u32,
                    control: b.patches[first + 1],
                });
                s.domain.push([m, unit(i + 1), unit(i + 2)]);
            }
        }
    }
    let keep = |v: &Vec<[u32; 2]>| -> Vec<[u32; 2]> {
        v.iter()
            .copied()
            .filter(|e| !rebuilt_edges.contains(e))
            .collect()
    };
    s.singular_edges = keep(&base.singular_edges);
    s.unresolved_edges = keep(&base.unresolved_edges);
    s.non_g1_edges = keep(&base.non_g1_edges);
    s.sign_warnings = keep(&base.sign_warnings);
    s.fold_guarded = keep(&base.fold_guarded);
    s.max_displacement = displacement;
    out.surface = s;
    Ok(out)
}

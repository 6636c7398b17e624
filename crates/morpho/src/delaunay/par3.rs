//! Parallel 3D Delaunay tetrahedralization by splitting the sorted points in two and merging
//! with an exact certificate (issue 23 item 3; Veltkamp 1992 §2.2.8–2.2.9, Dorgerloh et al. §2:
//! the Delaunay triangulation and its empty-sphere characterisation; the engine of each part is
//! the Bowyer–Watson engine of `d3.rs`).
//!
//! # Algorithm
//! `P` = the distinct points sorted lexicographically (the canonical order of `d3.rs`, whose rank
//! is the symbolic perturbation's index). `L` = the first half, `R` = the second half.
//! 1. `DT(L)` and `DT(R)` are built in parallel (`rayon::join`). Their vertices keep their
//!    relative canonical order, so the perturbation decides every tie as in `DT(P)`.
//! 2. A tetrahedron of `DT(L)` is **final** when its closed circumsphere lies strictly on the side
//!    `x < x_min(R)` (of `DT(R)`: strictly `x > x_max(L)`). With `o` the circumcentre relative to
//!    a vertex `a`, `e = ±(a_x − X)`, this is `o_y² + o_z² < e² ± 2 e o_x`, multiplied by the
//!    squared determinant a homogeneous polynomial of degree 8 in the coordinates
//!    ([`clear_of_split`]): evaluated in floating point with an a priori error bound
//!    ([`clear_of_split_static`], proof there), then with a proven running error bound
//!    (`geom::bounded`), and exactly in big integers (`geom::exact`) when neither decides. Any
//!    doubt means "not final".
//! 3. `S` = the vertices of the non-final tetrahedra of `DT(L)` and `DT(R)` plus every vertex of
//!    their hull triangles. `DT(S)` is built (sequentially).
//! 4. The **seam** = the tetrahedra of `DT(S)` reached by a flood fill that starts, for every
//!    face of a final tetrahedron whose neighbour in its half is not final (or is the hull), at
//!    the `DT(S)` tetrahedron on the other side of that face, and never crosses such a face.
//! 5. The result is `F_L ∪ F_R ∪ seam` with neighbour links; the hull is `DT(S)`'s hull.
//!
//! # Why it is `DT(P)`
//! `DT(X)` means the unique triangulation of the perturbed lifted points (`d3.rs`): a
//! tetrahedron is in it iff every other point of `X` is strictly outside its perturbed
//! circumsphere. Hence (a) a tetrahedron of `DT(P)` whose vertices lie in `X ⊆ P` is in `DT(X)`,
//! and so is every face of `DT(P)` with vertices in `X`, hull triangles included (a hull triangle
//! of `P` is one of `X`: same supporting plane, and points in that plane are decided by the same
//! perturbed in-circle rule).
//! * **F ⊆ DT(P).** A final tetrahedron of `DT(L)` has no point of `L` in its perturbed sphere,
//!   and every point of `R` strictly outside its closed sphere (no tie, no perturbation needed).
//! * **Every other tetrahedron `T` of `DT(P)` has its vertices in `S`.** If all vertices of `T`
//!   are in `L`, `T ∈ DT(L)` by (a) and is not final, so its vertices are in `S`. Otherwise let
//!   `v ∈ L` be a vertex of `T` not in `S`: `v` is interior to `hull(L)` (not a hull vertex) and
//!   every tetrahedron of its star in `DT(L)` is final, hence in `DT(P)`; that star covers a
//!   neighbourhood of `v`, so it is `v`'s whole star in `DT(P)`, and `T` (which has a vertex in
//!   `R`) cannot be in it. Same for `R`. By (a), `T ∈ DT(S)`.
//! * **The flood fill finds exactly `DT(P) \ F`.** `DT(P) \ F ⊆ DT(S)` tiles
//!   `Z = hull(P) \ int ∪F`, and no other tetrahedron of `DT(S)` meets `int Z` (a
//!   triangulation). A face of a final tetrahedron whose neighbour in its half is not final is
//!   either a hull triangle of `P` or shared with a tetrahedron of `DT(P) \ F` (a final
//!   tetrahedron of the other half cannot share it: its vertices are all on that side); that
//!   tetrahedron is the one of `DT(S)` on the far side of the face (found combinatorially: it
//!   holds the face with the opposite orientation). Walking across faces of `DT(S)` other than
//!   these and the hull stays in `Z`, and reaches all of it: a face-connected part of
//!   `DT(P) \ F` with no face on `F` would be a 3-chain with boundary on `∂hull(P)`, i.e. all of
//!   `hull(P)`, which means `F = ∅` (then every `DT(S)` tetrahedron is reached from no seed —
//!   handled by taking all of `DT(S)` when there is no final tetrahedron).
//! * The hull vertices are what makes the second point hold at the boundary of a half: without
//!   them, a vertex on `∂hull(L)` whose `DT(L)` tetrahedra are all final but which is joined to
//!   `R` outside `hull(L)` would be missing from `S` (the test `hull_vertices_matter` builds
//!   such a case).
//!
//! Any inconsistency the merge can see (a face of `F` not in `DT(S)`, a seam tetrahedron whose
//! neighbour is neither seam nor a recorded face of `F`, a degenerate half) makes it give up and
//! run the sequential engine on `P`, counted in [`SplitStats::fallback`]; the tests require it
//! never to happen on their inputs.
//!
//! # Order of the output
//! `F_L` in `DT(L)`'s order, then `F_R` in `DT(R)`'s, then the seam in `DT(S)`'s: every part
//! comes from the deterministic sequential engine on a set fixed by the split, so the output is
//! the same vector for every thread count (tested). It is the same *set* as [`d3::triangulate`]
//! but not the same order; [`triangulate_auto`] (the facade's `triangulate_3d`) takes this path
//! only with more than one rayon thread and at least [`PAR_MIN`] points.
//!
//! # Complexity and limits
//! Work `O(n log n)` expected for points spread in space plus `DT(S)`, whose size is the layer of
//! points near the split plane and near the two halves' hulls (a few percent of `n` for uniform
//! points, see `bench/README.md`). On points on a sphere every tetrahedron's sphere is the
//! whole sphere: nothing is final, `S = P`, and the split only adds work — [`triangulate_auto`]
//! notices this on a sample first (see [`predicted_seam_share`]) and stays sequential.

use super::d3::{self, build_sorted, dedup_sorted, Core, Delaunay3, FACE_OF};
use super::DelaunayError;
use crate::geom::bounded::Bounded;
use crate::geom::exact::{big_cross, big_dot, big_sign, to_big_rows};
use crate::geom::Point3;
use crate::util::{IdMap, NONE};
use num_bigint::BigInt;

type Result<T, E = DelaunayError> = std::result::Result<T, E>;

/// Fewest distinct points for which [`triangulate_auto`] splits (below, the merge costs more
/// than the second core saves).
pub const PAR_MIN: usize = 60_000;

/// Counters of one split run (for tests and benches).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SplitStats {
    /// Distinct points.
    pub points: usize,
    /// Final tetrahedra of the left and of the right half.
    pub final_tets: [usize; 2],
    /// Points of the seam set `S`.
    pub seam_points: usize,
    /// Tetrahedra of the seam (taken from `DT(S)`).
    pub seam_tets: usize,
    /// Finality tests decided by the exact big-integer stage.
    pub exact_tests: usize,
    /// The merge gave up (or did not apply) and the sequential engine ran on all points.
    pub fallback: bool,
}

/// The facade's 3D Delaunay entry ([`triangulate_3d`](crate::delaunay::triangulate_3d)): the
/// split-and-merge path when rayon has more than one thread, there are at least [`PAR_MIN`]
/// points and a sample predicts a small seam; otherwise [`d3::triangulate`]. Same tetrahedron
/// set either way (the unique perturbed Delaunay tetrahedralization).
pub fn triangulate_auto(points: &[Point3]) -> Result<Delaunay3> {
    if rayon::current_num_threads() > 1
        && points.len() >= PAR_MIN
        && predicted_seam_share(points) < 0.5
    {
        triangulate_split(points)
    } else {
        d3::triangulate(points)
    }
}

/// The split-and-merge tetrahedralization (module doc) at any size: the same tetrahedron set
/// as [`d3::triangulate`].
pub fn triangulate_split(points: &[Point3]) -> Result<Delaunay3> {
    triangulate_split_stats(points).map(|r| r.0)
}

/// [`triangulate_split`] with its counters.
pub fn triangulate_split_stats(points: &[Point3]) -> Result<(Delaunay3, SplitStats)> {
    let coords: Vec<[f64; 3]> = points.iter().map(|p| [p.x, p.y, p.z]).collect();
    let (pts, vertex_of_input, input_of_vertex) = dedup_sorted(&coords)?;
    drop(coords);
    let duplicates = points.len() - pts.len();
    let mut st = SplitStats {
        points: pts.len(),
        ..Default::default()
    };
    let core = match merge(&pts, &mut st)? {
        Some(c) => c,
        None => {
            st.fallback = true;
            build_sorted(&pts)?
        }
    };
    let d = Delaunay3::from_core(&pts, vertex_of_input, input_of_vertex, duplicates, core);
    Ok((d, st))
}

/// The share of the points of a fixed sample of about 4096 input points that the seam set `S`
/// of the sample's own split would hold (1.0 when the sample is degenerate). Points on a sphere
/// give 1.0; uniform points about 0.3 at this sample size (the seam layer shrinks relative to
/// `n` as `n` grows).
pub fn predicted_seam_share(points: &[Point3]) -> f64 {
    const M: usize = 4096;
    let step = (points.len() / M).max(1);
    let sample: Vec<[f64; 3]> = points
        .iter()
        .step_by(step)
        .map(|p| [p.x, p.y, p.z])
        .collect();
    let Ok((pts, _, _)) = dedup_sorted(&sample) else {
        return 1.0;
    };
    let mut st = SplitStats::default();
    match merge(&pts, &mut st) {
        Ok(Some(_)) if !pts.is_empty() => st.seam_points as f64 / pts.len() as f64,
        _ => 1.0,
    }
}

/// One half's triangulation and which of its tetrahedra are final.
struct Half {
    core: Core,
    fin: Vec<bool>,
    exact: usize,
}

fn half(pts: &[[f64; 3]], x: f64, right: bool) -> Result<Half> {
    let core = build_sorted(pts)?;
    let mut exact = 0;
    let fin = core
        .tets
        .iter()
        .map(|t| {
            let q = [
                pts[t[0] as usize],
                pts[t[1] as usize],
                pts[t[2] as usize],
                pts[t[3] as usize],
            ];
            clear_of_split(&q, x, right, &mut exact)
        })
        .collect();
    Ok(Half { core, fin, exact })
}

/// Whether the closed circumsphere of the (positive) tetrahedron `q` lies strictly in
/// `x > split` (`right`) or strictly in `x < split` (not `right`). Exact: the sign of
/// `G = 4e²D² ± 4eN_xD − N_y² − N_z²` (`D = b·(c×d)`, `N = |b|² c×d + |c|² d×b + |d|² b×c`,
/// `b, c, d` the edge vectors from `a = q₀`, so that the circumcentre is `a + N/(2D)`;
/// `e = ±(a_x − split)`), which is positive iff `|o| < e ± o_x` for `o = N/(2D)`. Floating point
/// with a proven bound first; `exact` counts the big-integer evaluations.
fn clear_of_split(q: &[[f64; 3]; 4], split: f64, right: bool, exact: &mut usize) -> bool {
    let a = q[0];
    // e's sign is exact: a rounded difference is zero iff the operands are equal and keeps
    // their order. The sphere passes through a, so e ≤ 0 means "not clear".
    let e = if right {
        Bounded::diff(a[0], split)
    } else {
        Bounded::diff(split, a[0])
    };
    if e.v <= 0.0 {
        return false;
    }
    if let Some(r) = clear_of_split_static(q, e.v, right) {
        return r;
    }
    // written out (no array closures): this runs once per tetrahedron of both halves
    #[inline(always)]
    fn rel(p: &[f64; 3], a: &[f64; 3]) -> [Bounded; 3] {
        [
            Bounded::diff(p[0], a[0]),
            Bounded::diff(p[1], a[1]),
            Bounded::diff(p[2], a[2]),
        ]
    }
    let (b, c, d) = (rel(&q[1], &a), rel(&q[2], &a), rel(&q[3], &a));
    let cd = Bounded::cross3(c, d);
    let db = Bounded::cross3(d, b);
    let bc = Bounded::cross3(b, c);
    let (bb, cc, dd) = (
        Bounded::dot3(b, b),
        Bounded::dot3(c, c),
        Bounded::dot3(d, d),
    );
    let nk = |k: usize| bb.times(cd[k]).plus(cc.times(db[k])).plus(dd.times(bc[k]));
    let n = [nk(0), nk(1), nk(2)];
    let det = Bounded::dot3(b, cd);
    let ed = e.times(det);
    let g1 = ed.times(ed).scale2(4.0);
    let g2 = ed.times(n[0]).scale2(4.0);
    let g = if right { g1.plus(g2) } else { g1.minus(g2) }
        .minus(n[1].times(n[1]))
        .minus(n[2].times(n[2]));
    if let Some(s) = g.sign() {
        return s > 0;
    }
    *exact += 1;
    clear_of_split_exact(q, split, right) > 0
}

/// [`clear_of_split`]'s decision by a plain floating-point evaluation of `G` with an a priori
/// bound (the semi-static filter, ~4× cheaper than the running bound), or `None`.
///
/// Proof of the bound. Let u = 2⁻⁵³. The ten leaves (the edge vectors `b, c, d` and `e > 0`,
/// each one rounded difference) are required to be 0 or of magnitude in [2⁻⁶⁰, 2⁶⁰]. Then every
/// nonzero intermediate value lies in [2⁻⁸⁰⁰, 2⁵⁰⁰] (a nonzero sum of floats ≥ 2ᵏ is ≥ 2ᵏ⁻⁵²;
/// following the tree: cross terms ≥ 2⁻¹⁷², N ≥ 2⁻³⁴⁴, D ≥ 2⁻²⁸⁴, G's terms ≥ 2⁻⁷⁹²), so no
/// operation underflows or overflows and each rounds with relative error ≤ u. Expanding the
/// evaluation tree (depth ≤ 10 roundings after the leaves) into monomials of degree 8 in the
/// computed leaves, the computed G differs from G of the computed leaves by ≤ γ₁₀·Gₐ, and the
/// leaves' own rounding (each ≤ u relative, 8 factors per monomial) adds ≤ γ₈·Gₐ·(1−u)⁻⁸,
/// where Gₐ is the same tree on the absolute values with every operation an addition. Gₐ
/// computed in floating point is ≥ Gₐ·(1−u)¹². In total |G̃ − G| < 20u·G̃ₐ; the test uses
/// 32u·G̃ₐ (a power-of-two multiple, exact).
#[inline]
fn clear_of_split_static(q: &[[f64; 3]; 4], e: f64, right: bool) -> Option<bool> {
    const LO: f64 = 8.673_617_379_884_035e-19; // 2⁻⁶⁰
    const HI: f64 = 1.152_921_504_606_847e18; // 2⁶⁰
    let a = q[0];
    let b = [q[1][0] - a[0], q[1][1] - a[1], q[1][2] - a[2]];
    let c = [q[2][0] - a[0], q[2][1] - a[1], q[2][2] - a[2]];
    let d = [q[3][0] - a[0], q[3][1] - a[1], q[3][2] - a[2]];
    let mut ok = e > LO && e < HI;
    for v in [b, c, d] {
        for x in v {
            let y = x.abs();
            ok &= y == 0.0 || (y > LO && y < HI);
        }
    }
    if !ok {
        return None;
    }
    #[inline(always)]
    fn cross(x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
        [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ]
    }
    #[inline(always)]
    fn cross_abs(x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
        [
            x[1] * y[2] + x[2] * y[1],
            x[2] * y[0] + x[0] * y[2],
            x[0] * y[1] + x[1] * y[0],
        ]
    }
    #[inline(always)]
    fn dot(x: [f64; 3], y: [f64; 3]) -> f64 {
        x[0] * y[0] + x[1] * y[1] + x[2] * y[2]
    }
    let abs = |v: [f64; 3]| [v[0].abs(), v[1].abs(), v[2].abs()];
    let (ba, ca, da) = (abs(b), abs(c), abs(d));
    let (cd, db, bc) = (cross(c, d), cross(d, b), cross(b, c));
    let (cda, dba, bca) = (cross_abs(ca, da), cross_abs(da, ba), cross_abs(ba, ca));
    let (bb, cc, dd) = (dot(b, b), dot(c, c), dot(d, d));
    let n = [
        bb * cd[0] + cc * db[0] + dd * bc[0],
        bb * cd[1] + cc * db[1] + dd * bc[1],
        bb * cd[2] + cc * db[2] + dd * bc[2],
    ];
    let na = [
        bb * cda[0] + cc * dba[0] + dd * bca[0],
        bb * cda[1] + cc * dba[1] + dd * bca[1],
        bb * cda[2] + cc * dba[2] + dd * bca[2],
    ];
    let ed = e * dot(b, cd);
    let eda = e * dot(ba, cda);
    let g1 = 4.0 * ed * ed;
    let g2 = 4.0 * ed * n[0];
    let g = if right { g1 + g2 } else { g1 - g2 } - n[1] * n[1] - n[2] * n[2];
    let ga = 4.0 * eda * eda + 4.0 * eda * na[0] + na[1] * na[1] + na[2] * na[2];
    let err = ga * (16.0 * f64::EPSILON);
    if g > err {
        Some(true)
    } else if g < -err {
        Some(false)
    } else {
        None
    }
}

/// The sign of [`clear_of_split`]'s `G` in big integers (after a common power-of-two scaling,
/// which keeps the sign of a homogeneous polynomial).
fn clear_of_split_exact(q: &[[f64; 3]; 4], split: f64, right: bool) -> i32 {
    let rows = to_big_rows(&[&q[0], &q[1], &q[2], &q[3], &[split]]);
    let p = |i: usize| -> [BigInt; 3] { [0, 1, 2].map(|k| rows[i][k].clone()) };
    let a = p(0);
    let rel = |i: usize| -> [BigInt; 3] {
        let v = p(i);
        [0, 1, 2].map(|k| &v[k] - &a[k])
    };
    let (b, c, d) = (rel(1), rel(2), rel(3));
    let e = if right {
        &a[0] - &rows[4][0]
    } else {
        &rows[4][0] - &a[0]
    };
    let cd = big_cross(&c, &d);
    let db = big_cross(&d, &b);
    let bc = big_cross(&b, &c);
    let (bb, cc, dd) = (big_dot(&b, &b), big_dot(&c, &c), big_dot(&d, &d));
    let n: [BigInt; 3] = [0, 1, 2].map(|k| &bb * &cd[k] + &cc * &db[k] + &dd * &bc[k]);
    let det = big_dot(&b, &cd);
    let ed = &e * &det;
    let g2 = &ed * &n[0];
    let g = if right {
        &ed * &ed + &g2
    } else {
        &ed * &ed - &g2
    };
    // G/4 = e²D² ± eN_xD − (N_y² + N_z²)/4: compare 4·(e²D² ± eN_xD) with N_y² + N_z²
    let g: BigInt = g * 4 - &n[1] * &n[1] - &n[2] * &n[2];
    big_sign(&g)
}

/// Orientation of triangle `u` relative to `v` (same vertex set): true when `u` is a rotation
/// of `v` (same orientation), false when it is a rotation of `v` reversed.
#[inline]
fn same_orientation(u: [u32; 3], v: [u32; 3]) -> bool {
    let k = v.iter().position(|&x| x == u[0]).unwrap_or(0);
    v[(k + 1) % 3] == u[1]
}

#[inline]
fn face(t: &[u32; 4], i: usize) -> [u32; 3] {
    let f = FACE_OF[i];
    [t[f[0]], t[f[1]], t[f[2]]]
}

#[inline]
fn key(f: [u32; 3]) -> [u32; 3] {
    crate::util::sorted3(f)
}

/// A face of a final tetrahedron whose neighbour in its half is not final or the hull.
struct Barrier {
    /// Output tetrahedron and slot.
    tet: u32,
    slot: u8,
    /// The face (global vertices), oriented outward of `tet`.
    tri: [u32; 3],
    /// The `DT(S)` tetrahedron across it and its slot, or [`NONE`].
    seam: u32,
    seam_slot: u8,
    /// Found in `DT(S)` as a hull triangle.
    hull: bool,
}

/// Steps 1–5 of the module doc on the sorted distinct points; `None` when the merge does not
/// apply or sees an inconsistency (the caller runs the sequential engine).
fn merge(pts: &[[f64; 3]], st: &mut SplitStats) -> Result<Option<Core>> {
    let n = pts.len();
    if n < 8 {
        return Ok(None); // a half needs four points
    }
    let h = n / 2;
    let (x_max_l, x_min_r) = (pts[h - 1][0], pts[h][0]);
    let (l, r) = rayon::join(
        || half(&pts[..h], x_min_r, false),
        || half(&pts[h..], x_max_l, true),
    );
    let (l, r) = (l?, r?);
    if l.core.degenerate.is_some() || r.core.degenerate.is_some() {
        return Ok(None);
    }
    st.exact_tests = l.exact + r.exact;
    let parts = [(&l, 0u32), (&r, h as u32)];

    // S: vertices of non-final tetrahedra and of hull triangles of both halves.
    let mut in_s = vec![false; n];
    for &(hf, off) in &parts {
        for (t, v) in hf.core.tets.iter().enumerate() {
            if !hf.fin[t] {
                for &x in v {
                    in_s[(x + off) as usize] = true;
                }
            }
        }
        for f in &hf.core.hull {
            for &x in f {
                in_s[(x + off) as usize] = true;
            }
        }
    }
    let s_ids: Vec<u32> = (0..n as u32).filter(|&v| in_s[v as usize]).collect();
    drop(in_s);
    st.seam_points = s_ids.len();
    let spts: Vec<[f64; 3]> = s_ids.iter().map(|&v| pts[v as usize]).collect();
    let sc = build_sorted(&spts)?;
    drop(spts);
    if sc.degenerate.is_some() {
        return Ok(None);
    }
    let sglob = |t: &[u32; 4]| t.map(|x| s_ids[x as usize]);

    // Output ids of the final tetrahedra: F_L then F_R, each in its half's order.
    let mut out_id: [Vec<u32>; 2] = [Vec::new(), Vec::new()];
    let mut m = 0u32;
    for (k, &(hf, _)) in parts.iter().enumerate() {
        out_id[k] = hf
            .fin
            .iter()
            .map(|&f| {
                if f {
                    m += 1;
                    m - 1
                } else {
                    NONE
                }
            })
            .collect();
        st.final_tets[k] = hf.fin.iter().filter(|&&f| f).count();
    }
    let n_final = m as usize;

    // Final tetrahedra with their links inside the halves; barrier faces collected.
    let mut tets: Vec<[u32; 4]> = Vec::with_capacity(n_final + sc.tets.len());
    let mut nbrs: Vec<[u32; 4]> = Vec::with_capacity(n_final + sc.tets.len());
    let mut barriers: Vec<Barrier> = Vec::new();
    let mut by_key: IdMap<[u32; 3], u32> = IdMap::default();
    for (k, &(hf, off)) in parts.iter().enumerate() {
        for (t, v) in hf.core.tets.iter().enumerate() {
            if !hf.fin[t] {
                continue;
            }
            let g = v.map(|x| x + off);
            let me = tets.len() as u32;
            let mut nb = [NONE; 4];
            for i in 0..4 {
                let u = hf.core.neighbors[t][i];
                if u != NONE && hf.fin[u as usize] {
                    nb[i] = out_id[k][u as usize];
                } else {
                    let tri = face(&g, i);
                    by_key.insert(key(tri), barriers.len() as u32);
                    barriers.push(Barrier {
                        tet: me,
                        slot: i as u8,
                        tri,
                        seam: NONE,
                        seam_slot: 0,
                        hull: false,
                    });
                }
            }
            tets.push(g);
            nbrs.push(nb);
        }
    }

    // Find each barrier face in DT(S): the tetrahedron across it, or the hull.
    let mut bar = vec![[NONE; 4]; sc.tets.len()];
    if !barriers.is_empty() {
        for (u, v) in sc.tets.iter().enumerate() {
            let g = sglob(v);
            for j in 0..4 {
                let tri = face(&g, j);
                let Some(&b) = by_key.get(&key(tri)) else {
                    continue;
                };
                let br = &mut barriers[b as usize];
                if same_orientation(tri, br.tri) {
                    if sc.neighbors[u][j] == NONE {
                        br.hull = true;
                    }
                } else {
                    br.seam = u as u32;
                    br.seam_slot = j as u8;
                    bar[u][j] = br.tet;
                }
            }
        }
    }
    drop(by_key);

    // Flood fill of the seam from the far sides of the barrier faces.
    let mut seam = vec![false; sc.tets.len()];
    let mut stack: Vec<u32> = Vec::new();
    if n_final == 0 {
        seam.iter_mut().for_each(|s| *s = true);
    }
    for br in &barriers {
        if br.seam != NONE {
            if !seam[br.seam as usize] {
                seam[br.seam as usize] = true;
                stack.push(br.seam);
            }
        } else if !br.hull {
            return Ok(None); // a face of F that DT(S) does not have: inconsistent
        }
    }
    while let Some(u) = stack.pop() {
        for j in 0..4 {
            if bar[u as usize][j] != NONE {
                continue;
            }
            let w = sc.neighbors[u as usize][j];
            if w != NONE && !seam[w as usize] {
                seam[w as usize] = true;
                stack.push(w);
            }
        }
    }
    let mut seam_id = vec![NONE; sc.tets.len()];
    let mut next = n_final as u32;
    for (u, s) in seam.iter().enumerate() {
        if *s {
            seam_id[u] = next;
            next += 1;
        }
    }
    st.seam_tets = next as usize - n_final;

    // Links of the final tetrahedra across the barriers.
    for br in &barriers {
        if br.seam != NONE {
            nbrs[br.tet as usize][br.slot as usize] = seam_id[br.seam as usize];
        }
    }
    // Seam tetrahedra with their links.
    for (u, v) in sc.tets.iter().enumerate() {
        if !seam[u] {
            continue;
        }
        let mut nb = [NONE; 4];
        for j in 0..4 {
            nb[j] = if bar[u][j] != NONE {
                bar[u][j]
            } else {
                let w = sc.neighbors[u][j];
                if w == NONE {
                    NONE
                } else if seam[w as usize] {
                    seam_id[w as usize]
                } else {
                    return Ok(None); // the fill met a face it should have stopped at
                }
            };
        }
        tets.push(sglob(v));
        nbrs.push(nb);
    }
    let hull = sc
        .hull
        .iter()
        .map(|f| f.map(|x| s_ids[x as usize]))
        .collect();
    Ok(Some(Core {
        tets,
        neighbors: nbrs,
        hull,
        degenerate: None,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn canon(d: &Delaunay3) -> Vec<[u32; 4]> {
        let mut v: Vec<[u32; 4]> = d
            .tets
            .iter()
            .map(|t| {
                let mut s = *t;
                s.sort_unstable();
                s
            })
            .collect();
        v.sort_unstable();
        v
    }

    fn hull_set(d: &Delaunay3) -> Vec<[u32; 3]> {
        let mut v: Vec<[u32; 3]> = d.hull.iter().map(|f| crate::util::sorted3(*f)).collect();
        v.sort_unstable();
        v
    }

    /// The split result equals the sequential one as a set, passes the local certificate and
    /// the topology check, and the merge did not fall back.
    fn same(pts: &[Point3]) -> SplitStats {
        let seq = d3::triangulate(pts).unwrap();
        let (par, st) = triangulate_split_stats(pts).unwrap();
        assert_eq!(canon(&par), canon(&seq), "tetrahedron sets differ ({st:?})");
        assert_eq!(hull_set(&par), hull_set(&seq), "hulls differ");
        assert_eq!(par.degenerate, seq.degenerate);
        assert_eq!(par.vertex_of_input, seq.vertex_of_input);
        par.check_topology().unwrap();
        par.check_delaunay_local().unwrap();
        for (v, &t) in par.vertex_tet.iter().enumerate() {
            if t != NONE {
                assert!(par.tets[t as usize].contains(&(v as u32)));
            }
        }
        st
    }

    fn rng(seed: u64) -> rand_chacha::ChaCha8Rng {
        rand_chacha::ChaCha8Rng::seed_from_u64(seed)
    }

    fn uniform(n: usize, seed: u64) -> Vec<Point3> {
        let mut r = rng(seed);
        (0..n)
            .map(|_| Point3::new(r.gen(), r.gen(), r.gen()))
            .collect()
    }

    #[test]
    fn uniform_equals_sequential() {
        for (n, seed) in [(3000, 1), (20_000, 2)] {
            let st = same(&uniform(n, seed));
            assert!(!st.fallback);
            assert!(st.final_tets[0] > 0 && st.final_tets[1] > 0, "{st:?}");
            assert!(st.seam_points < st.points, "{st:?}");
        }
    }

    #[test]
    fn clustered_equals_sequential() {
        let mut r = rng(7);
        let mut p = Vec::new();
        for c in 0..12 {
            let ctr = [r.gen::<f64>() * 10.0, r.gen::<f64>(), r.gen::<f64>() * 3.0];
            let s = 10f64.powi(-(c % 4) - 1);
            for _ in 0..600 {
                p.push(Point3::new(
                    ctr[0] + s * r.gen::<f64>(),
                    ctr[1] + s * r.gen::<f64>(),
                    ctr[2] + s * r.gen::<f64>(),
                ));
            }
        }
        assert!(!same(&p).fallback);
    }

    #[test]
    fn sphere_equals_sequential() {
        let mut r = rng(3);
        let p: Vec<Point3> = (0..3000)
            .map(|_| {
                let v = [0; 3].map(|_| r.gen::<f64>() - 0.5);
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                Point3::new(v[0] / l, v[1] / l, v[2] / l)
            })
            .collect();
        let st = same(&p);
        assert!(!st.fallback);
        assert!(predicted_seam_share(&p) > 0.9);
        assert!(predicted_seam_share(&uniform(100_000, 5)) < 0.5);
    }

    /// Integer lattices: cospherical ties everywhere, equal x across the split, duplicates.
    #[test]
    fn lattices_equal_sequential() {
        for g in [4usize, 5, 7, 9] {
            let mut p: Vec<Point3> = (0..g * g * g)
                .map(|i| Point3::new((i % g) as f64, ((i / g) % g) as f64, (i / g / g) as f64))
                .collect();
            // duplicates of points on both sides of the split, and a shuffle
            let extra: Vec<Point3> = p.iter().step_by(3).copied().collect();
            p.extend(extra);
            let mut r = rng(g as u64);
            use rand::seq::SliceRandom;
            p.shuffle(&mut r);
            assert!(!same(&p).fallback, "grid {g}");
        }
        // a thin lattice slab with a perturbed-lattice part
        let mut r = rng(11);
        let p: Vec<Point3> = (0..4000)
            .map(|_| {
                Point3::new(
                    r.gen_range(0..40) as f64,
                    r.gen_range(0..10) as f64 * 0.5,
                    r.gen_range(0..6) as f64 * 0.25,
                )
            })
            .collect();
        assert!(!same(&p).fallback);
    }

    #[test]
    fn tiny_and_degenerate_inputs() {
        for n in [1usize, 2, 3, 4, 5, 6, 9, 16, 17, 33, 64] {
            for seed in 0..8 {
                same(&uniform(n, 100 + seed));
            }
        }
        // coplanar halves: L in the plane z = 0, R above it (the merge falls back)
        let mut p: Vec<Point3> = (0..50)
            .map(|i| Point3::new((i % 7) as f64 * 0.1, (i / 7) as f64, 0.0))
            .collect();
        p.extend((0..50).map(|i| Point3::new(1.0 + (i % 7) as f64, (i / 7) as f64, i as f64)));
        same(&p);
        // all coplanar, all collinear
        let flat: Vec<Point3> = (0..100)
            .map(|i| Point3::new(i as f64, (i * i % 17) as f64, 0.0))
            .collect();
        let d = triangulate_split(&flat).unwrap();
        assert!(d.tets.is_empty() && d.degenerate.is_some());
        assert!(triangulate_split(&[]).is_err());
        assert!(triangulate_split(&[Point3::new(f64::NAN, 0.0, 0.0)]).is_err());
    }

    /// Extreme scales go through the exact stage of the finality test.
    #[test]
    fn extreme_scales() {
        for s in [1e-300, 1e300, 1e-160] {
            let p: Vec<Point3> = uniform(800, 9).iter().map(|q| q * s).collect();
            assert!(!same(&p).fallback);
        }
    }

    /// `L` a dense cube, `R` a wide slab to its right: the vertices on `L`'s faces y = 0 and
    /// y = 1 have only final tetrahedra in `DT(L)` yet are joined to `R` around `hull(L)`, so
    /// the merge is wrong without the hull vertices in `S`.
    #[test]
    fn hull_vertices_matter() {
        let mut r = rng(21);
        let mut p: Vec<Point3> = (0..3000)
            .map(|_| Point3::new(r.gen(), r.gen(), r.gen()))
            .collect();
        p.extend((0..3000).map(|_| {
            Point3::new(
                1.5 + r.gen::<f64>(),
                -20.0 + 41.0 * r.gen::<f64>(),
                -20.0 + 41.0 * r.gen::<f64>(),
            )
        }));
        let st = same(&p);
        assert!(!st.fallback);
    }

    /// Points of `L` exactly on the leftmost point of the circumspheres of the tetrahedra of
    /// `R` (and the mirror case): six points on a sphere of large integer radius (Pythagorean
    /// quadruples), so that the float evaluation of the finality polynomial, which is exactly 0,
    /// comes out with either sign; finality needs the error bound and the exact stage.
    #[test]
    fn touching_spheres_need_the_exact_stage() {
        let mut r = rng(33);
        let mut exact = 0;
        for trial in 0..160 {
            let c = [0; 3].map(|_| r.gen_range(-(1 << 20)..(1 << 20)) as f64);
            let mut pt = [0i64; 4];
            let mut sphere: Vec<[f64; 3]> = Vec::new();
            let mut rad = 0.0;
            while sphere.len() < 6 {
                let [m, n, p, q] = [0; 4].map(|_| r.gen_range(1i64..3000));
                if sphere.is_empty() {
                    pt = [m, n, p, q];
                }
                // one radius for all: rotate the parameters of the first quadruple
                let [m, n, p, q] = match sphere.len() % 3 {
                    0 => pt,
                    1 => [pt[1], pt[0], pt[3], pt[2]],
                    _ => [pt[2], pt[3], pt[0], pt[1]],
                };
                let quad = [
                    m * m + n * n - p * p - q * q,
                    2 * (m * q + n * p),
                    2 * (n * q - m * p),
                ];
                rad = (m * m + n * n + p * p + q * q) as f64;
                let k = sphere.len();
                let perm = [[0, 1, 2], [1, 2, 0], [2, 0, 1]][k % 3];
                let sy = if k / 3 == 0 { 1.0 } else { -1.0 };
                let v = perm.map(|i| quad[i] as f64);
                if v[0] == 0.0 {
                    break;
                }
                sphere.push([v[0].abs(), sy * v[1], -sy * v[2]]);
            }
            if sphere.len() < 6 {
                continue;
            }
            let sgn = if trial % 2 == 0 { 1.0 } else { -1.0 };
            let mut p: Vec<Point3> = sphere
                .iter()
                .map(|o| Point3::new(c[0] + sgn * o[0], c[1] + o[1], c[2] + o[2]))
                .collect();
            p.push(Point3::new(c[0] - sgn * rad, c[1], c[2]));
            // five more points far on the other side, so that each half has 6 points in 3D
            for k in 0..5 {
                let f = [
                    (k % 2) as f64,
                    ((k / 2) % 2) as f64,
                    (k / 4) as f64 + 0.5 * (k % 3) as f64,
                ];
                p.push(Point3::new(
                    c[0] - sgn * rad * (3.0 + f[0]),
                    c[1] + rad * f[1],
                    c[2] + rad * f[2],
                ));
            }
            let st = same(&p);
            assert!(!st.fallback);
            exact += st.exact_tests;
        }
        assert!(exact > 0, "no finality test reached the exact stage");
    }

    /// The output is the same vector for one and for two threads.
    #[test]
    fn same_output_for_every_thread_count() {
        let p = uniform(30_000, 4);
        let run = |k: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .unwrap()
                .install(|| triangulate_split(&p).unwrap())
        };
        let (a, b) = (run(1), run(2));
        assert_eq!(a.tets, b.tets);
        assert_eq!(a.neighbors, b.neighbors);
        assert_eq!(a.hull, b.hull);
    }

    #[test]
    fn static_filter_agrees_with_exact() {
        let mut r = rng(6);
        let (mut decided, mut undecided) = (0, 0);
        for i in 0..20_000 {
            // nearly flat tetrahedra (huge spheres) at various offsets and scales
            let s = 2f64.powi(r.gen_range(-20..20));
            let off = r.gen_range(-1e6..1e6) * s;
            let flat = if i % 2 == 0 { 1e-9 } else { 1.0 };
            let mut q: [[f64; 3]; 4] = [0; 4].map(|_| {
                [
                    off + r.gen::<f64>() * s,
                    r.gen::<f64>() * s,
                    r.gen::<f64>() * s * flat,
                ]
            });
            if crate::geom::exact::orient3d_exact(q[0], q[1], q[2], q[3]) < 0.0 {
                q.swap(0, 1);
            }
            if crate::geom::exact::orient3d_exact(q[0], q[1], q[2], q[3]) == 0.0 {
                continue;
            }
            let right = i % 3 == 0;
            let split = if right {
                off - r.gen::<f64>() * s * 3.0
            } else {
                off + s + r.gen::<f64>() * s * 3.0
            };
            let e = if right {
                q[0][0] - split
            } else {
                split - q[0][0]
            };
            if e <= 0.0 {
                continue;
            }
            match clear_of_split_static(&q, e, right) {
                Some(f) => {
                    decided += 1;
                    assert_eq!(
                        f,
                        clear_of_split_exact(&q, split, right) > 0,
                        "{q:?} {split} {right}"
                    );
                }
                None => undecided += 1,
            }
        }
        assert!(decided > 1000, "{decided} decided, {undecided} not");
    }

    #[test]
    fn exact_stage_agrees_with_filter() {
        let mut r = rng(5);
        let mut n = 0;
        for _ in 0..2000 {
            let q: [[f64; 3]; 4] = [0; 4].map(|_| [r.gen(), r.gen(), r.gen()]);
            let o = crate::geom::exact::orient3d_exact(q[0], q[1], q[2], q[3]);
            if o <= 0.0 {
                continue;
            }
            for (split, right) in [(-0.5, true), (1.5, false), (0.2, true), (0.8, false)] {
                let mut ex = 0;
                let f = clear_of_split(&q, split, right, &mut ex);
                assert_eq!(f, clear_of_split_exact(&q, split, right) > 0);
                n += 1;
            }
        }
        assert!(n > 1000);
    }
}

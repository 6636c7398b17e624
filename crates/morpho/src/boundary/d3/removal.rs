//! Removal of a tetrahedron by the general 3D engine [`General3`] (Veltkamp 1992, §5.3
//! conditions, §5.4 deletion of crossing triangles, §5.5 heap): the removability test, the
//! conservative exact open-tetrahedron test, the heap and its sweeps.
//!
//! A tetrahedron Q = abcl with boundary face abc (l strictly on its inner side, all four faces
//! live, Q not flat) is removable iff
//! - it has **one** boundary face and l is not a boundary vertex, or **two** boundary faces and
//!   the edge joining the two vertices opposite them is not a boundary edge (never three or
//!   four) — exactly V's conditions, which keep the surface a closed 2-manifold of genus 0;
//! - the closed Q contains no other vertex (exact `orient3d`);
//! - its new boundary faces meet no other boundary triangle except in common vertices/edges
//!   (exact tests of [`crate::geom::intersect`]; a safety net — the invariant already implies it);
//! - no keep triangle is a boundary face of Q or crosses its interior (V §5.7).
//!
//! Its key is the sum of the γ-indicators of its boundary faces w.r.t. the opposite vertices
//! ([`super::constrict::gamma_indicator_3d`], Def. 5.2). Removing Q deletes its boundary faces
//! and **every live triangle meeting the open Q** (V §5.4). That test is conservative and exact:
//! a triangle is kept only when a separating plane is proven — for a triangle sharing a vertex
//! a with Q, the planes through a spanned by two other corners (complete for two cones with a
//! common apex; only `orient3d`); otherwise the face planes of Q, the triangle's plane, and the
//! edge–edge planes of the separating-axis theorem evaluated in floating point with an error
//! filter (a doubtful sign counts as "meets"). Deleting too much only removes choices; it never
//! breaks the invariant.

use super::constrict::gamma_indicator_3d;
use super::general::*;
use crate::geom::intersect::triangles_meet_beyond_shared;
use crate::geom::predicates::raw::orient3d;
use crate::geom::vec::{cross, sub};
use crate::graphs::fast::GroupTriples;
use crate::util::{sorted3, IdMap};

/// The group triples the constriction from the hull takes beyond the whole-γ size
/// ([`super::Engine3::gamma_from_hull`], local path, no keep triangles): those of
/// [`GroupTriples::Balls`], without the triangles [`GroupTriples::All`] adds — the empty
/// triangles of a coplanar hull facet of more than three points that are neither Delaunay
/// faces nor triples of a cocircular cell (`graphs::fast::candidates_3d_with` (c)), Θ(g³) for
/// a facet of g points: most of the fandisk's 5.6·10⁶ triangles, its 2.28 GB peak and about
/// 40 % of the CPU time of `boundary --c=-0.5` (issue 17 item 8; `bench/README.md`, cross7).
///
/// Such a triangle t lies in the plane H of a hull facet, and every point is on H's closed
/// inner side. Leaving t out changes no removal, so neither the surface nor any count:
/// 1. Every point of H is a boundary vertex from the start (the hull faces triangulate the
///    facet through all its points: Delaunay faces are empty) and stays one: a removal never
///    takes a vertex off the boundary (a one-face removal of abc + l keeps a, b, c on its new
///    faces, a two-face removal has all four corners on them).
/// 2. No removal has a non-boundary face in H. A one-face removal's new faces all contain l,
///    which is not a boundary vertex, so not in H (1). For a two-face removal with a new face
///    F ⊂ H: the tetrahedron Q lies in the region R bounded by the surface (it is on the inner
///    side of its two boundary faces, its new faces meet no other boundary face and the closed
///    Q holds no other point — what [`General3::check`] tests), so F ⊂ R ∩ H, which lies on the
///    surface (R ⊂ the hull); the boundary faces covering F lie in H, so by induction they are
///    hull faces: F itself (a third boundary face of Q: refused) or faces overlapping F in its
///    plane, which `hits_boundary` finds (refused).
/// 3. So t is never a face of a removed tetrahedron and never becomes a boundary face (t is
///    no hull face; a new face is never in H by 2.); it is never deleted (it meets no open
///    tetrahedron: H separates them, [`super::support`]); and [`General3::local_gamma`] never
///    proposes it (its candidates contain a vertex off the boundary, not in H by 1.).
///    A tetrahedron with t as a face is refused with t (2.) and without it (`has`); a face of
///    the sweep list listed only through t has no removable tetrahedron (the live faces of
///    one that is removable lie on its edges and list it anyway), so the same faces are pushed.
/// 4. What does change: the ids of the triangles added later (no decision depends on an id's
///    value: crossings are deleted as a set, candidates sorted by key and apex, the sweep list
///    by face) and the grids' cell (the median edge of the given triangles; every grid query
///    is followed by exact tests, the cell changes work only).
///
/// Checked at every removal in lockstep with the engine given every triangle
/// (`hull_facet_triangles_change_no_removal`), and `cmp` on the CLI outputs.
pub(super) const FROM_HULL_TRIPLES: GroupTriples = GroupTriples::Balls;

/// Sign of det[x − y, e, f] (e, f edge vectors as differences of doubles), or `None` when the
/// floating-point value is not certified.
pub(super) fn sat_sign(x: P, y: P, e: (P, P), f: (P, P)) -> Option<i32> {
    let (u, v, w) = (sub(x, y), sub(e.1, e.0), sub(f.1, f.0));
    let t = [
        u[0] * (v[1] * w[2] - v[2] * w[1]),
        u[1] * (v[2] * w[0] - v[0] * w[2]),
        u[2] * (v[0] * w[1] - v[1] * w[0]),
    ];
    let val = t[0] + t[1] + t[2];
    let mag = (0..3)
        .map(|k| {
            let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
            u[k].abs() * ((v[k1] * w[k2]).abs() + (v[k2] * w[k1]).abs())
        })
        .sum::<f64>();
    let bound = 16.0 * f64::EPSILON * mag;
    if !val.is_finite() || !mag.is_finite() {
        None
    } else if val > bound {
        Some(1)
    } else if val < -bound {
        Some(-1)
    } else if mag == 0.0 {
        Some(0)
    } else {
        None
    }
}

/// Conservative exact test: may closed triangle `t` meet the open tetrahedron `q`? `false` only
/// when a separating plane is proven (see the module documentation). One query of
/// [`OpenTet`]; a search testing many triangles against one tetrahedron prepares it once
/// (the engine's only caller, [`General3::crossing`], does).
#[cfg_attr(not(test), allow(dead_code))]
pub fn may_meet_open_tet(t: [P; 3], tv: [u32; 3], q: [P; 4], qv: [u32; 4]) -> bool {
    OpenTet::new(q, qv).may_meet(t, tv)
}

/// What [`Plane::side`] multiplies the permanent by: the floating-point value of
/// (b − a) × (c − a) · (x − a) has eight rounded operations on the path of each of its terms
/// (three differences, the product, the minor's difference, the product by a component of
/// x − a, two sums), so its error is at most ((1 + ε)⁸ − 1) ≈ 8ε times the exact permanent
/// Σ |wₖ| (|uᵢvⱼ| + |uⱼvᵢ|), which the computed one (seven rounded operations per term) is at
/// least (1 − ε)⁷ of — the analysis of Shewchuk's first `orient3d` stage for this evaluation
/// order; twice that leaves room for the absolute error of an underflow, which the floor
/// below keeps under 1e-100 of the bound.
const PLANE_ERR: f64 = 16.0 * f64::EPSILON;

/// Below this permanent [`Plane::side`] leaves the sign to `orient3d` (underflow).
const PLANE_FLOOR: f64 = 1e-200;

/// The sign of an `orient3d` value: 1, −1, 0, or 2 when it is not a number (a NaN compares
/// false with 0 in the product form of [`may_meet_open_tet_reference`]: 2 satisfies no side).
fn sign_code(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else if v == 0.0 {
        0
    } else {
        2
    }
}

/// `s` on the closed non-negative side.
fn nonneg(s: i8) -> bool {
    s == 0 || s == 1
}

/// `s` on the closed non-positive side.
fn nonpos(s: i8) -> bool {
    s == 0 || s == -1
}

/// `x` and `y` on opposite closed sides (the sign of x·y ≤ 0, without the product's underflow).
fn opposite(x: i8, y: i8) -> bool {
    (nonpos(x) && nonneg(y)) || (nonneg(x) && nonpos(y))
}

/// The plane through `a`, `b`, `c` for many exact `orient3d(a, b, c, x)` signs: the normal
/// (b − a) × (c − a) and the row of its permanent are computed once, a point then costs a dot
/// product and an error bound ([`PLANE_ERR`]); a sign the bound does not certify (exact zeros:
/// coplanar corners on the fandisk's flat faces, and near-zeros) is `orient3d`'s. Either way
/// the exact sign.
#[derive(Clone, Copy)]
struct Plane {
    a: P,
    b: P,
    c: P,
    n: P,
    m: P,
}

impl Plane {
    fn new(a: P, b: P, c: P) -> Self {
        let (u, v) = (sub(b, a), sub(c, a));
        Plane {
            a,
            b,
            c,
            n: [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ],
            m: [
                (u[1] * v[2]).abs() + (u[2] * v[1]).abs(),
                (u[2] * v[0]).abs() + (u[0] * v[2]).abs(),
                (u[0] * v[1]).abs() + (u[1] * v[0]).abs(),
            ],
        }
    }

    /// [`sign_code`] of `orient3d(a, b, c, x)`, which is −(b − a) × (c − a) · (x − a). A corner of
    /// the plane given again is on it (two equal rows: 0 exactly, without `orient3d`'s adaptive
    /// stages, which an exact zero always reaches).
    fn side(&self, x: P) -> i8 {
        if x == self.a || x == self.b || x == self.c {
            return 0;
        }
        let w = sub(x, self.a);
        let det = self.n[0] * w[0] + self.n[1] * w[1] + self.n[2] * w[2];
        let perm = self.m[0] * w[0].abs() + self.m[1] * w[1].abs() + self.m[2] * w[2].abs();
        if perm > PLANE_FLOOR && perm.is_finite() && det.abs() > PLANE_ERR * perm {
            return if det > 0.0 { -1 } else { 1 };
        }
        sign_code(orient3d(self.a, self.b, self.c, x))
    }
}

/// Q's faces as corner positions (the fourth is the opposite corner).
const TET_FACES: [[usize; 4]; 4] = [[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]];

/// The open tetrahedron q of a removal prepared for [`OpenTet::may_meet`]: its orientation,
/// its face planes ([`Plane`]) with the side of the opposite corner, computed once instead of
/// for every triangle tested, and the side of each face plane a triangle corner was found on,
/// by vertex id (triangles of one search share most corners; a vertex id names one point).
/// The same answers as [`may_meet_open_tet_reference`] (the same exact signs, compared
/// directly instead of through products, which could underflow to 0).
pub(super) struct OpenTet {
    q: [P; 4],
    qv: [u32; 4],
    flat: bool,
    faces: [Plane; 4],
    opp: [i8; 4],
    /// vertex → its side of each face plane (3: not computed yet)
    memo: IdMap<u32, [i8; 4]>,
}

impl OpenTet {
    pub(super) fn new(q: [P; 4], qv: [u32; 4]) -> Self {
        let faces = TET_FACES.map(|f| Plane::new(q[f[0]], q[f[1]], q[f[2]]));
        let opp = std::array::from_fn(|k| {
            let f = TET_FACES[k];
            sign_code(orient3d(q[f[0]], q[f[1]], q[f[2]], q[f[3]]))
        });
        OpenTet {
            q,
            qv,
            flat: orient3d(q[0], q[1], q[2], q[3]) == 0.0,
            faces,
            opp,
            memo: IdMap::default(),
        }
    }

    /// The side of face plane `f` vertex `v` at `x` is on.
    fn face_side(&mut self, f: usize, v: u32, x: P) -> i8 {
        let e = self.memo.entry(v).or_insert([3; 4]);
        if e[f] == 3 {
            e[f] = self.faces[f].side(x);
        }
        e[f]
    }

    /// [`may_meet_open_tet`] of the closed triangle `t` (vertex ids `tv`).
    pub(super) fn may_meet(&mut self, t: [P; 3], tv: [u32; 3]) -> bool {
        let (q, qv) = (self.q, self.qv);
        // shared vertex: cones with a common apex, planes through it spanned by two corners
        if let Some((it, iq)) = (0..3)
            .flat_map(|i| (0..4).map(move |j| (i, j)))
            .find(|&(i, j)| tv[i] == qv[j])
        {
            let a = t[it];
            let ts: [P; 2] = [t[(it + 1) % 3], t[(it + 2) % 3]];
            let ts = if it == 1 { [ts[1], ts[0]] } else { ts };
            // Q's corners other than a: those not on t first (`qs`), then those shared with
            // t, which lie on t and so on both sides: they only have to be on Q's side too
            let mut qall = [[0.0; 3]; 3];
            let mut nqs = 0;
            for j in (0..4).filter(|&j| j != iq && !tv.contains(&qv[j])) {
                qall[nqs] = q[j];
                nqs += 1;
            }
            let mut m = nqs;
            for j in (0..4).filter(|&j| j != iq && tv.contains(&qv[j])) {
                qall[m] = q[j];
                m += 1;
            }
            debug_assert_eq!(m, 3);
            let mut all = [[0.0; 3]; 5];
            all[..2].copy_from_slice(&ts);
            all[2..2 + nqs].copy_from_slice(&qall[..nqs]);
            let n_all = 2 + nqs;
            for i in 0..n_all {
                for j in i + 1..n_all {
                    let pl = Plane::new(a, all[i], all[j]);
                    let st = ts.map(|x| pl.side(x));
                    let sq = qall.map(|x| pl.side(x));
                    if st.iter().chain(&sq).all(|&s| s == 0) {
                        continue; // degenerate plane
                    }
                    if (st.iter().all(|&s| nonpos(s)) && sq.iter().all(|&s| nonneg(s)))
                        || (st.iter().all(|&s| nonneg(s)) && sq.iter().all(|&s| nonpos(s)))
                    {
                        return false;
                    }
                }
            }
            return true;
        }
        if self.flat {
            return false; // flat: no interior
        }
        // (each test below only proves a separation: the answer does not depend on their
        // order; the triangle's plane comes first, and it separates most of the long
        // triangles whose boxes meet the tetrahedron's)
        // the triangle's plane
        let tp = Plane::new(t[0], t[1], t[2]);
        let sq = q.map(|x| tp.side(x));
        if sq.iter().all(|&s| nonneg(s)) || sq.iter().all(|&s| nonpos(s)) {
            return false;
        }
        // face planes of q
        for f in 0..4 {
            let s = self.opp[f];
            if (0..3).all(|k| {
                let x = self.face_side(f, tv[k], t[k]);
                opposite(x, s)
            }) {
                return false;
            }
        }
        // edge–edge planes
        let qe = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
        for i in 0..3 {
            let e = (t[i], t[(i + 1) % 3]);
            for &(j, k) in &qe {
                let f = (q[j], q[k]);
                // signs of (x − e.0)·(e × f) for every corner x
                let mut st = [0i32; 3];
                let mut sqs = [0i32; 4];
                let mut ok = true;
                // the corners of e are exactly on the plane; only the third one is evaluated
                match sat_sign(t[(i + 2) % 3], e.0, e, f) {
                    Some(s) => st[2] = s,
                    None => ok = false,
                }
                for (m, &x) in q.iter().enumerate() {
                    match sat_sign(x, e.0, e, f) {
                        Some(s) => sqs[m] = s,
                        None => ok = false,
                    }
                }
                if !ok || (st.iter().all(|&s| s == 0) && sqs.iter().all(|&s| s == 0)) {
                    continue;
                }
                // t lies in a closed half-space through e; q's vertices of edge f share one
                // value, the separating plane through e works when q is on the other closed side
                if (st.iter().all(|&s| s <= 0) && sqs.iter().all(|&s| s >= 0))
                    || (st.iter().all(|&s| s >= 0) && sqs.iter().all(|&s| s <= 0))
                {
                    return false;
                }
            }
        }
        true
    }
}

/// [`may_meet_open_tet`] as it was before [`OpenTet`] (the reference of the tests): every
/// `orient3d` evaluated in full, signs compared through products.
#[cfg(test)]
pub(super) fn may_meet_open_tet_reference(
    t: [P; 3],
    tv: [u32; 3],
    q: [P; 4],
    qv: [u32; 4],
) -> bool {
    // shared vertex: cones with a common apex, planes through it spanned by two corners
    if let Some((it, iq)) = (0..3)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .find(|&(i, j)| tv[i] == qv[j])
    {
        let a = t[it];
        // (fixed arrays instead of a list per plane: the same points and planes in the same
        // order as before, without an allocation per candidate)
        let ts: [P; 2] = [t[(it + 1) % 3], t[(it + 2) % 3]];
        let ts = if it == 1 { [ts[1], ts[0]] } else { ts };
        // Q's corners other than a: those not on t first (`qs`), then those shared with t,
        // which lie on t and so on both sides: they only have to be on Q's side too
        let mut qall = [[0.0; 3]; 3];
        let mut nqs = 0;
        for j in (0..4).filter(|&j| j != iq && !tv.contains(&qv[j])) {
            qall[nqs] = q[j];
            nqs += 1;
        }
        let mut m = nqs;
        for j in (0..4).filter(|&j| j != iq && tv.contains(&qv[j])) {
            qall[m] = q[j];
            m += 1;
        }
        debug_assert_eq!(m, 3);
        let mut all = [[0.0; 3]; 5];
        all[..2].copy_from_slice(&ts);
        all[2..2 + nqs].copy_from_slice(&qall[..nqs]);
        let n_all = 2 + nqs;
        for i in 0..n_all {
            for j in i + 1..n_all {
                let (u, v) = (all[i], all[j]);
                let st = ts.map(|x| orient3d(a, u, v, x));
                let sq = qall.map(|x| orient3d(a, u, v, x));
                if st.iter().chain(&sq).all(|&s| s == 0.0) {
                    continue; // degenerate plane
                }
                if (st.iter().all(|&s| s <= 0.0) && sq.iter().all(|&s| s >= 0.0))
                    || (st.iter().all(|&s| s >= 0.0) && sq.iter().all(|&s| s <= 0.0))
                {
                    return false;
                }
            }
        }
        return true;
    }
    let o = orient3d(q[0], q[1], q[2], q[3]);
    if o == 0.0 {
        return false; // flat: no interior
    }
    // (each test below only proves a separation: the answer does not depend on their order;
    // the triangle's plane comes first, 4 `orient3d` against 16 for the face planes, and it
    // separates most of the long triangles whose boxes meet the tetrahedron's)
    // the triangle's plane
    let sq = q.map(|x| orient3d(t[0], t[1], t[2], x));
    if sq.iter().all(|&s| s >= 0.0) || sq.iter().all(|&s| s <= 0.0) {
        return false;
    }
    // face planes of q
    let faces = [[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]];
    for f in faces {
        let s = orient3d(q[f[0]], q[f[1]], q[f[2]], q[f[3]]);
        if t.iter()
            .all(|&x| orient3d(q[f[0]], q[f[1]], q[f[2]], x) * s <= 0.0)
        {
            return false;
        }
    }
    // edge–edge planes
    let qe = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    for i in 0..3 {
        let e = (t[i], t[(i + 1) % 3]);
        for &(j, k) in &qe {
            let f = (q[j], q[k]);
            // signs of (x − e.0)·(e × f) for every corner x
            let mut st = [0i32; 3];
            let mut sqs = [0i32; 4];
            let mut ok = true;
            // the corners of e are exactly on the plane; only the third one is evaluated
            match sat_sign(t[(i + 2) % 3], e.0, e, f) {
                Some(s) => st[2] = s,
                None => ok = false,
            }
            for (m, &x) in q.iter().enumerate() {
                match sat_sign(x, e.0, e, f) {
                    Some(s) => sqs[m] = s,
                    None => ok = false,
                }
            }
            if !ok || (st.iter().all(|&s| s == 0) && sqs.iter().all(|&s| s == 0)) {
                continue;
            }
            // t lies in a closed half-space through e; q's vertices of edge f share one value,
            // the separating plane through e works when q is on the other closed side
            if (st.iter().all(|&s| s <= 0) && sqs.iter().all(|&s| s >= 0))
                || (st.iter().all(|&s| s >= 0) && sqs.iter().all(|&s| s <= 0))
            {
                return false;
            }
        }
    }
    true
}

impl General3<'_> {
    /// Combinatorial removability of tetrahedron (face, l) and its key; cheap checks only.
    /// Returns (key, boundary faces of Q, new faces).
    pub(super) fn combinatorial(&self, f: [u32; 3], l: u32) -> Option<Removal> {
        let [a, b, c] = f;
        if l == a || l == b || l == c || !self.is_bface(f) {
            return None;
        }
        if !self.has(a, b, l) || !self.has(b, c, l) || !self.has(a, c, l) {
            return None;
        }
        self.combinatorial_rest(f, l)
    }

    /// [`Self::combinatorial`] for a boundary face `f` = abc and an apex `l` from `eadj`'s
    /// list of edge ab, where `bc_listed` (`ac_listed`) says that `l` was found in the list
    /// of edge bc (ac) given by [`General3::live_thirds`]: the lookups those lists already
    /// answered are skipped (the same answer, without `combinatorial`'s hash lookups of `id`
    /// and `bnext`).
    ///
    /// Why: `f` was checked to be a boundary face by the caller; and a third vertex is in the
    /// list of an edge xy (not both ends cold) exactly while xyl is live ([`General3::kill`]
    /// removes it from all three lists, [`General3::add_tri_grid`] adds it when it becomes
    /// live, [`General3::heat`] lists the untouched initial faces), so `l` from the list of ab
    /// makes abl live, and from the lists of bc and ac, bcl and acl. Test
    /// `thirds_filter_constricts_identically` (the lists against the triangles after every
    /// step, and the removals with this path and with [`Self::combinatorial`]).
    pub(super) fn combinatorial_listed(
        &self,
        f: [u32; 3],
        l: u32,
        bc_listed: bool,
        ac_listed: bool,
    ) -> Option<Removal> {
        let [a, b, c] = f;
        if l == a || l == b || l == c {
            return None;
        }
        if (!bc_listed && !self.has(b, c, l)) || (!ac_listed && !self.has(a, c, l)) {
            return None;
        }
        self.combinatorial_rest(f, l)
    }

    /// The part of [`Self::combinatorial`] after the boundary face `f` = abc and the live
    /// triangles abl, bcl, acl were checked.
    fn combinatorial_rest(&self, f: [u32; 3], l: u32) -> Option<Removal> {
        let [a, b, c] = f;
        let (pa, pb, pc, pl) = (self.pt(a), self.pt(b), self.pt(c), self.pt(l));
        if orient3d(pa, pb, pc, pl) <= 0.0 {
            return None;
        }
        let faces = tet_faces(a, b, c, l);
        let mut bf = Faces::new();
        let mut nf = Faces::new();
        let mut opp = smallvec::SmallVec::<[u32; 4]>::new();
        for (face, o) in faces {
            if self.is_bface(face) {
                bf.push(face);
                opp.push(o);
            } else {
                if self.is_bface([face[1], face[0], face[2]]) {
                    return None; // the reversed face is on the boundary: Q lies outside
                }
                nf.push([face[0], face[2], face[1]]);
            }
        }
        match bf.len() {
            1 => {
                if self.on_boundary(l) {
                    return None;
                }
            }
            2 => {
                if self.bedge(opp[0], opp[1]) {
                    return None;
                }
            }
            _ => return None,
        }
        if !self.keep.is_empty() && bf.iter().any(|&x| self.keep.contains(&sorted3(x))) {
            return None;
        }
        let r = circumradius(pa, pb, pc, pl);
        let mut key = 0.0;
        for (face, &o) in bf.iter().zip(&opp) {
            key += gamma_indicator_3d(
                self.pt(face[0]),
                self.pt(face[1]),
                self.pt(face[2]),
                self.pt(o),
                r,
            );
        }
        Some((key, bf, nf))
    }

    /// The closed tetrahedron contains no vertex but its corners.
    pub(super) fn empty(&mut self, qv: [u32; 4]) -> bool {
        let mut buf = std::mem::take(&mut self.buf);
        let ok = self.empty_with(qv, &mut buf);
        self.buf = buf;
        ok
    }

    /// [`Self::empty`] with a scratch buffer of the caller's.
    pub(super) fn empty_with(&self, qv: [u32; 4], buf: &mut Vec<u32>) -> bool {
        let q = qv.map(|v| self.pt(v));
        let (lo, hi) = bbox(&q);
        self.vgrid.query(lo, hi, buf);
        let o = orient3d(q[0], q[1], q[2], q[3]);
        let faces = [[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]];
        let signs: Vec<f64> = faces
            .iter()
            .map(|f| orient3d(q[f[0]], q[f[1]], q[f[2]], q[f[3]]))
            .collect();
        let mut ok = o != 0.0;
        for &v in buf.iter() {
            if !ok {
                break;
            }
            if qv.contains(&v) {
                continue;
            }
            let x = self.pt(v);
            if faces
                .iter()
                .zip(&signs)
                .all(|(f, &s)| orient3d(q[f[0]], q[f[1]], q[f[2]], x) * s >= 0.0)
            {
                ok = false;
            }
        }
        ok
    }

    /// Triangle `t` (vertex ids) meets a boundary triangle other than those in `skip` beyond
    /// their common vertices/edges. Stops at the first such triangle.
    pub(super) fn hits_boundary(&self, t: [u32; 3], skip: &[[u32; 3]]) -> bool {
        let pt = t.map(|v| self.pt(v));
        let bb = bbox(&pt);
        let mut skip_s = [[u32::MAX; 3]; 4];
        for (k, &x) in skip.iter().take(4).enumerate() {
            skip_s[k] = sorted3(x);
        }
        let st = sorted3(t);
        // floating-point plane of t: a box farther from it than a generous bound of the
        // rounding error (relative 1e-8) holds no point of t's plane, so no triangle in it can
        // meet t (a triangle sharing a vertex with t touches the plane and is never culled)
        let nrm = cross(sub(pt[1], pt[0]), sub(pt[2], pt[0]));
        let n1: f64 = nrm.iter().map(|x| x.abs()).sum();
        let scale = |x: P| x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let st_scale = scale(bb.0).max(scale(bb.1));
        let plane_ok = n1.is_finite() && n1 > 0.0;
        // (`bfaces` hands over only live boundary faces whose boxes may meet `bb`, in no
        // particular order: the answer is an `any` of a function of the id)
        self.bfaces
            .any(bb.0, bb.1, |i| {
                // (the tests of the box and of the plane first, the flags below: each test is
                // a function of the id, so their order changes no answer, only which arrays a
                // rejected id is read from)
                let ub = self.tbox[i as usize];
                if !boxes_meet(bb, ub) {
                    return false;
                }
                if plane_ok {
                    let c: P = std::array::from_fn(|k| 0.5 * (ub.0[k] + ub.1[k]));
                    let h: P = std::array::from_fn(|k| 0.5 * (ub.1[k] - ub.0[k]));
                    let dist = (0..3).map(|k| nrm[k] * (c[k] - pt[0][k])).sum::<f64>();
                    let rad = (0..3).map(|k| nrm[k].abs() * h[k]).sum::<f64>();
                    let margin = 1e-8 * n1 * (st_scale + scale(ub.0).max(scale(ub.1)));
                    if dist.abs() > rad + margin {
                        return false;
                    }
                }
                // live boundary triangle (either orientation of the sorted triple)
                if !self.live[i as usize] || !self.bflag[i as usize] {
                    return false;
                }
                let u = self.tris[i as usize];
                if u == st || skip_s.contains(&u) || skip.iter().skip(4).any(|&x| sorted3(x) == u) {
                    return false;
                }
                let pu = u.map(|v| self.pt(v));
                triangles_meet_beyond_shared(t, pt, u, pu)
            })
            .0
    }

    /// Live triangles meeting the open tetrahedron (conservative), other than its faces: those
    /// of the crossing index whose box meets the tetrahedron's and which
    /// [`may_meet_open_tet`], in id order. (The index leaves out the triangles in supporting
    /// planes, for which that test is always false: [`super::support`].)
    ///
    /// The cheap tests (live, not a face of the tetrahedron, exact boxes meet) run while the
    /// index hands the ids over ([`super::crosstree::BoxIndex::query_where`]: live ids whose
    /// boxes, rounded outward, meet the query's, each once), so that only the survivors are
    /// sorted. The same set as filtering the sorted answer of a query: every test is a function
    /// of the id alone, and the index hands over every live id whose exact box meets.
    pub(super) fn crossing(&mut self, qv: [u32; 4]) -> Vec<u32> {
        let q = qv.map(|v| self.pt(v));
        let bb = bbox(&q);
        let mut buf = std::mem::take(&mut self.buf);
        let (live, tris, tbox) = (&self.live, &self.tris, &self.tbox);
        self.crossing_examined += self.tgrid.query_where(
            bb.0,
            bb.1,
            |i| {
                let i = i as usize;
                live[i] && !tris[i].iter().all(|v| qv.contains(v)) && boxes_meet(bb, tbox[i])
            },
            &mut buf,
        );
        buf.sort_unstable();
        let mut out = Vec::new();
        let mut open = OpenTet::new(q, qv);
        for &i in &buf {
            let u = self.tris[i as usize];
            let pu = u.map(|v| self.pt(v));
            if open.may_meet(pu, u) {
                out.push(i);
            }
        }
        self.buf = buf;
        out
    }

    /// The crossing search as it was before the filter during the walk (the reference of the
    /// lockstep test): the sorted answer of [`super::crosstree::BoxIndex::query`], then each
    /// test in turn.
    #[cfg(test)]
    pub(super) fn crossing_by_query(&self, qv: [u32; 4]) -> Vec<u32> {
        let q = qv.map(|v| self.pt(v));
        let bb = bbox(&q);
        let mut buf = Vec::new();
        self.tgrid.query(bb.0, bb.1, &mut buf);
        let mut out = Vec::new();
        for &i in &buf {
            if !self.live[i as usize] {
                continue;
            }
            let u = self.tris[i as usize];
            if u.iter().all(|v| qv.contains(v)) {
                continue;
            }
            let pu = u.map(|v| self.pt(v));
            if !boxes_meet(bb, bbox(&pu)) {
                continue;
            }
            if may_meet_open_tet(pu, u, q, qv) {
                out.push(i);
            }
        }
        out
    }

    /// Full removability check of tetrahedron (boundary face f, apex l).
    pub(super) fn check(&mut self, f: [u32; 3], l: u32) -> Option<Removal> {
        let (key, bf, nf) = self.combinatorial(f, l)?;
        let qv = [f[0], f[1], f[2], l];
        if !self.empty(qv) {
            return None;
        }
        for &t in &nf {
            if self.hits_boundary(t, &bf) {
                return None;
            }
        }
        if !self.keep.is_empty() {
            let cr = self.crossing(qv);
            if let Some(&i) = cr
                .iter()
                .find(|&&i| self.keep.contains(&self.tris[i as usize]))
            {
                self.blocked_by = Some(self.tris[i as usize]);
                return None;
            }
        }
        Some((key, bf, nf))
    }

    /// The smallest-key removable tetrahedron on boundary face f.
    pub(super) fn best(&mut self, f: [u32; 3]) -> Option<(f64, u32)> {
        if self.keep.is_empty() {
            let mut buf = std::mem::take(&mut self.buf);
            let b = self.best_plain(f, &mut buf);
            self.buf = buf;
            return b;
        }
        if !self.is_bface(f) || self.keep.contains(&sorted3(f)) {
            return None;
        }
        if !self.keep.is_empty() {
            // keep triangles x y m on an edge of f: make f + m a tetrahedron (V §5.7 rewiring)
            for k in 0..3 {
                let (x, y) = (f[k], f[(k + 1) % 3]);
                let ms: Vec<u32> = self.eadj.get(&ek(x, y)).map_or(Vec::new(), |v| v.to_vec());
                for m in ms {
                    if m != f[(k + 2) % 3] && self.keep.contains(&sorted3([x, y, m])) {
                        self.rewire(f, [x, y, m]);
                    }
                }
            }
        }
        for _round in 0..4 {
            let cands: Vec<u32> = self
                .eadj
                .get(&ek(f[0], f[1]))
                .map_or(Vec::new(), |v| v.to_vec());
            let mut keyed: Vec<(f64, u32)> = cands
                .into_iter()
                .filter(|&l| l != f[2])
                .filter_map(|l| self.combinatorial(f, l).map(|(k, _, _)| (k, l)))
                .collect();
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut rewired = false;
            for (k, l) in keyed {
                self.blocked_by = None;
                if self.check(f, l).is_some() {
                    return Some((k, l));
                }
                if let Some(kt) = self.blocked_by.take() {
                    rewired |= self.rewire(f, kt);
                    if rewired {
                        break;
                    }
                }
            }
            if !rewired {
                return None;
            }
        }
        None
    }

    /// [`Self::best`] without keep triangles, where nothing is rewired: read-only (the
    /// removability checks of [`Self::check`] without the keep crossings), so that
    /// [`Self::push_all`] can evaluate faces in parallel.
    pub(super) fn best_plain(&self, f: [u32; 3], buf: &mut Vec<u32>) -> Option<(f64, u32)> {
        debug_assert!(self.keep.is_empty());
        if !self.is_bface(f) {
            return None;
        }
        let apexes = self.eadj.get(&ek(f[0], f[1]))?;
        if apexes.iter().all(|&l| l == f[2]) {
            return None;
        }
        // A tetrahedron abcl needs the live triangles bcl and acl: apexes missing from the
        // lists of edges bc and ac are dropped here, two lookups per face instead of
        // `combinatorial`'s per apex (the same apexes pass: [`General3::live_thirds`])
        let (bc, ac) = if self.filter_thirds {
            (self.live_thirds(f[1], f[2]), self.live_thirds(f[0], f[2]))
        } else {
            (None, None)
        };
        let listed = |s: Option<&[u32]>, l: u32| match s {
            Some(s) => s.contains(&l),
            None => true,
        };
        // (with the filter, the lookups the lists answered are skipped:
        // [`Self::combinatorial_listed`]; without it, the reference)
        let mut keyed: Vec<(f64, u32, Removal)> = apexes
            .iter()
            .filter(|&&l| l != f[2] && listed(bc, l) && listed(ac, l))
            .filter_map(|&l| {
                if self.filter_thirds {
                    self.combinatorial_listed(f, l, bc.is_some(), ac.is_some())
                } else {
                    self.combinatorial(f, l)
                }
                .map(|r| (r.0, l, r))
            })
            .collect();
        keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        keyed.into_iter().find_map(|(k, l, (_, bf, nf))| {
            let removable = self.empty_with([f[0], f[1], f[2], l], buf)
                && !nf.iter().any(|&t| self.hits_boundary(t, &bf));
            removable.then_some((k, l))
        })
    }

    pub(super) fn push(&mut self, f: [u32; 3]) -> bool {
        if let Some((key, l)) = self.best(f) {
            self.heap.push(Entry { key, item: (f, l) });
            true
        } else {
            false
        }
    }

    /// Pushes every boundary face that can have a removable tetrahedron: one sharing an edge
    /// with a live triangle that is not a boundary face (a tetrahedron with at most two
    /// boundary faces has two other live faces, each on an edge of every boundary face of it;
    /// the other boundary faces never have one).
    pub(super) fn push_all(&mut self) -> bool {
        use rayon::prelude::*;
        let faces = self.sweep_faces();
        // Without keep triangles evaluating a face changes nothing (no rewiring): the faces
        // are tested and evaluated in parallel against the same state, then handled in order.
        if self.keep.is_empty() && !self.sequential_sweeps {
            enum Verdict {
                Skipped,
                Push(f64, u32),
                Locked(P, P),
            }
            let this = &*self;
            let verdicts: Vec<Verdict> = faces
                .par_iter()
                .map_init(Vec::new, |buf, &f| {
                    if this.unchanged_lock(f) {
                        Verdict::Skipped
                    } else if let Some((key, l)) = this.best_plain(f, buf) {
                        Verdict::Push(key, l)
                    } else {
                        let (lo, hi) = this.lock_box(f);
                        Verdict::Locked(lo, hi)
                    }
                })
                .collect();
            let mut any = false;
            for (f, v) in faces.into_iter().zip(verdicts) {
                match v {
                    Verdict::Skipped => {
                        self.skipped += 1;
                        if self.verify_skips {
                            assert!(self.best(f).is_none(), "skipped a removable face {f:?}");
                        }
                    }
                    Verdict::Push(key, l) => {
                        self.heap.push(Entry { key, item: (f, l) });
                        any = true;
                        self.locked_at.remove(&f);
                    }
                    Verdict::Locked(lo, hi) => {
                        self.locked_at.insert(f, (self.epoch, lo, hi));
                    }
                }
            }
            return any;
        }
        let mut any = false;
        for f in faces {
            // A face found locked is skipped while nothing meeting the box of f and its
            // apexes has changed: its removability depends only on the live triangles on its
            // edges and the tetrahedra they span (boundary flags of their faces and edges,
            // points inside, live triangles crossing them, boundary faces meeting their new
            // faces) — all inside that box — and every mutation stamps the cells of its box.
            if self.skip_locked(f) {
                continue;
            }
            let e = self.epoch;
            if self.push(f) {
                any = true;
                self.locked_at.remove(&f);
            } else {
                // (a mutation during this face's own evaluation, e.g. a rewiring, is after e)
                let (lo, hi) = self.lock_box(f);
                self.locked_at.insert(f, (e, lo, hi));
            }
        }
        any
    }

    /// The boundary faces [`Self::push_all`] examines: for every directed edge x→y of a live
    /// triangle that is not a boundary face, the boundary face (x, y, `bnext`(x→y)) when there
    /// is one, rotated to start at its smallest vertex; sorted, each once.
    ///
    /// Kept up to date instead of rebuilt from every live triangle (6 look-ups each in the
    /// directed-edge map) at every sweep: whether the directed edge x→y names a face of the
    /// list, and which, depends only on `bnext`(x→y) and on the live and boundary flags of the
    /// triangles on the edge {x, y}, and every change of those (`add_tri_grid`, `kill`,
    /// `set_boundary`) records the changed triangle's edges in `dirty_edges`. So only the
    /// directed edges of the dirty edges are decided again (`sweep_src`: edge → face named,
    /// with a count of the edges naming each face). The same list as
    /// [`Self::sweep_faces_rebuilt`] in every state, consistent or not (checked in the tests,
    /// and at every sweep with `verify_sweep_list`).
    pub(super) fn sweep_faces(&mut self) -> Vec<[u32; 3]> {
        let mut dirty = std::mem::take(&mut self.dirty_edges);
        let src = match self.sweep_src.take() {
            // (rebuilt in one pass when more triangles changed than there are — three edges
            // recorded per change —, and in the tests' reference runs; the tests' checked runs
            // always update)
            Some(mut src)
                if !self.rebuild_sweeps
                    && (dirty.len() < 3 * self.tris.len() || self.verify_sweep_list) =>
            {
                self.incremental_sweeps += 1;
                dirty.sort_unstable();
                dirty.dedup();
                let (named, count) = &mut src;
                for &e in &dirty {
                    let (a, b) = ((e >> 32) as u32, e as u32);
                    let inner = self.on_inner_triangle(a, b);
                    for (x, y) in [(a, b), (b, a)] {
                        let now = match self.bnext.get(&dk(x, y)) {
                            Some(&z) if inner => Some(sorted_rot([x, y, z])),
                            _ => None,
                        };
                        let before = named.get(&dk(x, y)).copied();
                        if before == now {
                            continue;
                        }
                        if let Some(f) = before {
                            named.remove(&dk(x, y));
                            let c = count.get_mut(&f).expect("a named face is counted");
                            *c -= 1;
                            if *c == 0 {
                                count.remove(&f);
                            }
                        }
                        if let Some(f) = now {
                            named.insert(dk(x, y), f);
                            *count.entry(f).or_insert(0) += 1;
                        }
                    }
                }
                src
            }
            _ => self.sweep_src_rebuilt(),
        };
        let mut faces: Vec<[u32; 3]> = src.1.keys().copied().collect();
        faces.sort_unstable();
        self.sweep_src = Some(src);
        if self.verify_sweep_list {
            assert_eq!(faces, self.sweep_faces_rebuilt(), "incremental sweep list");
        }
        faces
    }

    /// Every directed edge (x, y) of a live non-boundary triangle that names a boundary face
    /// (x, y, z) through `bnext`, with that face (rotated to its smallest corner first),
    /// sorted and without repeats: what both rebuilds below read.
    fn named_edges(&self) -> Vec<(u64, [u32; 3])> {
        use rayon::prelude::*;
        let this = self;
        let mut edges: Vec<(u64, [u32; 3])> = (0..this.tris.len())
            .into_par_iter()
            .filter(|&i| this.live[i] && !this.bflag[i])
            .flat_map_iter(|i| {
                let t = this.tris[i];
                (0..6).filter_map(move |j| {
                    let (a, b) = (t[j / 2], t[(j / 2 + 1) % 3]);
                    let (x, y) = if j % 2 == 0 { (a, b) } else { (b, a) };
                    this.bnext
                        .get(&dk(x, y))
                        .map(|&z| (dk(x, y), sorted_rot([x, y, z])))
                })
            })
            .collect();
        edges.par_sort_unstable();
        edges.dedup();
        edges
    }

    /// The table `sweep_src` of [`Self::sweep_faces`] built from every live non-boundary
    /// triangle.
    pub(super) fn sweep_src_rebuilt(&self) -> SweepSrc {
        let edges = self.named_edges();
        let mut named: IdMap<u64, [u32; 3]> = IdMap::default();
        let mut count: IdMap<[u32; 3], u32> = IdMap::default();
        named.reserve(edges.len());
        count.reserve(edges.len() / 2);
        for (e, f) in edges {
            named.insert(e, f);
            *count.entry(f).or_insert(0) += 1;
        }
        (named, count)
    }

    /// The list of [`Self::sweep_faces`] rebuilt from every live non-boundary triangle.
    pub(super) fn sweep_faces_rebuilt(&self) -> Vec<[u32; 3]> {
        use rayon::prelude::*;
        let mut faces: Vec<[u32; 3]> = self.named_edges().into_iter().map(|(_, f)| f).collect();
        faces.par_sort_unstable();
        faces.dedup();
        faces
    }

    /// The edge {a, b} is an edge of a live triangle that is not a boundary face.
    pub(super) fn on_inner_triangle(&self, a: u32, b: u32) -> bool {
        self.eadj.get(&ek(a, b)).is_some_and(|thirds| {
            thirds.iter().any(|&m| {
                self.id
                    .get(&sorted3([a, b, m]))
                    .is_some_and(|&i| self.live[i as usize] && !self.bflag[i as usize])
            })
        })
    }

    /// Whether face f was found locked before and nothing meeting the box of f and its
    /// apexes has changed since (then [`Self::push_all`] skips it).
    pub(super) fn unchanged_lock(&self, f: [u32; 3]) -> bool {
        self.skip_unchanged
            && self
                .locked_at
                .get(&f)
                .is_some_and(|&(e, lo, hi)| !self.changed_since(e, lo, hi))
    }

    /// [`Self::unchanged_lock`], counted, and in the tests verified.
    pub(super) fn skip_locked(&mut self, f: [u32; 3]) -> bool {
        if !self.unchanged_lock(f) {
            return false;
        }
        self.skipped += 1;
        if self.verify_skips {
            assert!(self.best(f).is_none(), "skipped a removable face {f:?}");
        }
        true
    }

    /// The box of face f and the apexes on its edges: everything its removability depends on.
    pub(super) fn lock_box(&self, f: [u32; 3]) -> (P, P) {
        // (the box of the corners grown by every apex: the same box as `bbox` of them all,
        // without collecting them)
        let mut b = bbox(&f.map(|v| self.pt(v)));
        for k in 0..3 {
            for &l in self
                .eadj
                .get(&ek(f[k], f[(k + 1) % 3]))
                .into_iter()
                .flatten()
            {
                let q = self.pt(l);
                for i in 0..3 {
                    b.0[i] = b.0[i].min(q[i]);
                    b.1[i] = b.1[i].max(q[i]);
                }
            }
        }
        b
    }

    pub(super) fn remove(&mut self, f: [u32; 3], l: u32, bf: &[[u32; 3]], nf: &[[u32; 3]]) {
        let qv = [f[0], f[1], f[2], l];
        let cross = self.crossing(qv);
        for i in cross {
            if self.bflag[i as usize] {
                continue; // (cannot meet the open Q; never delete the surface)
            }
            self.kill(i);
        }
        for &b in bf {
            self.set_boundary(b, false);
            if let Some(&i) = self.id.get(&sorted3(b)) {
                self.kill(i);
            }
        }
        for &n in nf {
            self.set_boundary(n, true);
        }
        self.iterations += 1;
        for &n in nf {
            self.push(n);
        }
        // the faces next to the new ones may have gained options (two-face removals); others
        // are recomputed lazily when popped, and by the final sweep of `run`
        for &n in nf {
            for k in 0..3 {
                let (a, b) = (n[k], n[(k + 1) % 3]);
                if let Some(&c) = self.bnext.get(&dk(b, a)) {
                    self.push([b, a, c]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Brute force: does closed triangle t meet the open tetrahedron q? Dense sampling of t in
    /// barycentric coordinates with an exact in-open-tetrahedron test (a sampled point is a
    /// rounded float, so this is an oracle for the "meets" direction only, in general position).
    fn sampled_meet(t: [P; 3], q: [P; 4]) -> bool {
        let faces = [[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]];
        let m = 40;
        // interior samples only: a rounded point of an edge shared with q could fall inside
        for i in 1..m {
            for j in 1..m - i {
                let (u, v) = (i as f64 / m as f64, j as f64 / m as f64);
                let w = 1.0 - u - v;
                let x: P = std::array::from_fn(|k| u * t[0][k] + v * t[1][k] + w * t[2][k]);
                if faces.iter().all(|f| {
                    orient3d(q[f[0]], q[f[1]], q[f[2]], x)
                        * orient3d(q[f[0]], q[f[1]], q[f[2]], q[f[3]])
                        > 0.0
                }) {
                    return true;
                }
            }
        }
        false
    }

    /// The sweep's face list kept up to date from the changed edges equals the list rebuilt
    /// from every live triangle at every sweep (checked inside each sweep), and the engine
    /// constricts exactly as with the rebuilt list (same surface, removals, additions) —
    /// through the whole schedule of c steps and the insertion of the last vertices: on
    /// clustered cube points where the Delaunay constriction locks, from the hull of a bumpy
    /// sphere with interior points and of an integer lattice (many ties), and with keep
    /// triangles (faces evaluated one after the other, with rewiring during the sweep).
    #[test]
    fn incremental_sweep_list_equals_the_rebuilt_one() {
        use crate::boundary::d3::augment::augment_until_done_3d;
        use crate::boundary::d3::constrict::{constrict_3d, Until};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let mut sets: Vec<(Vec<crate::geom::Point3>, bool, usize)> = Vec::new();
        // (the clustered cube points of `sweeps_that_skip_unchanged_faces_constrict_identically`)
        for seed in [1647u64, 1755, 1, 2, 3, 4] {
            let cube = super::super::test_sets::clustered_cube(seed);
            sets.push((cube, false, 0));
        }
        let bumpy = super::super::test_sets::bumpy_sphere(&mut rng, 800);
        sets.push((bumpy.clone(), true, 0));
        let lattice = super::super::test_sets::lattice(6, 5, 4);
        sets.push((lattice, true, 0));
        sets.push((bumpy[..400].to_vec(), true, 6));
        let (mut removals, mut incremental) = (0, 0);
        for (k, (pts, from_hull, n_keep)) in sets.iter().enumerate() {
            let d = crate::delaunay::d3::triangulate(pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let all = crate::graphs::fast::candidates_3d(&d).triangles;
            let (start, live) = if *from_hull {
                (d.hull.clone(), all.clone())
            } else {
                let st = constrict_3d(&d, Until::All);
                let live = super::super::test_sets::live_faces(&d, &st.alive);
                (st.triangles, live)
            };
            // keep triangles: interior Delaunay triangles spread over the set
            let keep: Vec<[u32; 3]> = all
                .iter()
                .step_by(all.len() / (n_keep + 1) + 1)
                .take(*n_keep)
                .copied()
                .collect();
            let go = |rebuild: bool| {
                let mut g = General3::blank(&pos, &start, &live, &keep);
                g.build(&start, &live, &keep);
                g.track = true;
                g.rebuild_sweeps = rebuild;
                g.verify_sweep_list = !rebuild;
                g.push_all();
                // first a constriction with a sweep after every 10 removals (many sweeps with
                // few changes each), then the schedule as `boundary_3d` runs it
                while !g.done() {
                    let mut removed = 0;
                    while removed < 10 && !g.done() {
                        let Some(en) = g.heap.pop() else { break };
                        if !g.is_bface(en.item.0) {
                            continue;
                        }
                        match g.check(en.item.0, en.item.1) {
                            Some((_, bf, nf)) => {
                                g.remove(en.item.0, en.item.1, &bf, &nf);
                                removed += 1;
                            }
                            None => {
                                g.push(en.item.0);
                            }
                        }
                    }
                    if !g.push_all() && g.heap.is_empty() {
                        break;
                    }
                }
                let c = augment_until_done_3d(&mut g, 0.0);
                (
                    g.boundary(),
                    (g.iterations, g.added, g.boundary_vertices, c),
                    g.incremental_sweeps,
                )
            };
            let (b1, s1, i1) = go(true);
            let (b2, s2, i2) = go(false);
            assert_eq!(i1, 0);
            assert_eq!(s1, s2, "set {k}");
            assert_eq!(b1, b2, "set {k}");
            removals += s1.0;
            incremental += i2;
        }
        assert!(
            removals > 2000 && incremental > 300,
            "{removals} {incremental}"
        );
    }

    /// The incremental sweep list equals the rebuilt one after any sequence of the engine's
    /// mutation primitives — killing and reviving live triangles, adding new ones, taking
    /// faces off the boundary and putting triangles on it (in either orientation), in
    /// arbitrary order, not only as removals combine them — checked after every few steps.
    #[test]
    fn sweep_list_follows_every_mutation_primitive() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let (d, pos, all) = super::super::test_sets::cube_candidates(&mut rng, 400);
        let mut g = General3::new(&pos, &d.hull, &all, &[]);
        let n = pos.len() as u32;
        let (mut checks, mut listed) = (0, 0);
        for step in 0..3000 {
            let i = rng.gen_range(0..g.tris.len());
            let t = g.tris[i];
            match rng.gen_range(0..6) {
                0 | 1 => g.kill(i as u32),
                2 => {
                    g.add_tri(t);
                }
                3 => {
                    let x = [0; 3].map(|_: u32| rng.gen_range(0..n));
                    g.add_tri(x);
                }
                4 => {
                    let f = if g.is_bface(t) { t } else { [t[0], t[2], t[1]] };
                    g.set_boundary(f, false);
                }
                _ => {
                    let f = if rng.gen_bool(0.5) {
                        t
                    } else {
                        [t[0], t[2], t[1]]
                    };
                    g.set_boundary(f, true);
                }
            }
            if step % 7 == 0 {
                let inc = g.sweep_faces();
                assert_eq!(inc, g.sweep_faces_rebuilt(), "step {step}");
                checks += 1;
                listed += inc.len();
            }
        }
        assert!(g.incremental_sweeps >= checks && checks > 400, "{checks}");
        assert!(listed > 20 * checks, "{listed}");
    }

    /// The crossing search that leaves the triangles of supporting planes out of its grid
    /// (issue 17 item 8) returns exactly the crossings of the old search (every triangle of
    /// the old grid tested) at every removal, and the constriction is the same — run in lockstep
    /// from the hull with the candidates of coplanar hull facets (Θ(g³) long triangles) and the
    /// local γ-triangles at c = −0.5, on fandisk-like lattice prisms and a cube with points on
    /// its faces. And the work: the triangles the grid hands over per removal stay a small
    /// fraction of all (the old search examined T/4–T/2 of them per removal on the fandisk).
    #[test]
    fn crossing_without_supporting_planes_is_the_old_crossing_and_local() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let mut cube = super::super::test_sets::cube(&mut rng, 260);
        for p in cube.iter_mut().step_by(2) {
            let k = rng.gen_range(0..3);
            p[k] = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        }
        let sets = [
            super::super::test_sets::l_prism(4),
            super::super::test_sets::l_prism(5),
            cube,
        ];
        let (mut removals, mut calls, mut examined) = (0usize, 0usize, (0usize, 0usize));
        let (mut never, mut crossed) = (0usize, 0usize);
        for (k, pts) in sets.iter().enumerate() {
            let d = crate::delaunay::d3::triangulate(pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let all = crate::graphs::fast::candidates_3d(&d).triangles;
            let make = |cull: bool| {
                let mut g = General3::blank_with(&pos, &d.hull, &all, &[], cull);
                g.build(&d.hull, &all, &[]);
                g.track = true;
                g.push_all();
                let extra = g.local_gamma(-0.5, 16);
                g.augment(&extra);
                g
            };
            let (mut old, mut new) = (make(false), make(true));
            assert!(new.support.len() >= 6, "set {k}");
            assert_eq!(old.heap.len(), new.heap.len());
            let t_all = old.tris.len();
            // `run`, in lockstep, comparing every crossing set
            loop {
                while !old.done() {
                    let (Some(a), Some(b)) = (old.heap.pop(), new.heap.pop()) else {
                        assert!(new.heap.is_empty(), "set {k}");
                        break;
                    };
                    assert_eq!(a.item, b.item, "set {k}");
                    if !old.is_bface(a.item.0) {
                        continue;
                    }
                    let (ra, rb) = (old.check(a.item.0, a.item.1), new.check(b.item.0, b.item.1));
                    assert_eq!(ra.is_some(), rb.is_some(), "set {k}");
                    match (ra, rb) {
                        (Some((_, bf, nf)), Some(_)) => {
                            let f = a.item.0;
                            let qv = [f[0], f[1], f[2], a.item.1];
                            let (ca, cb) = (old.crossing(qv), new.crossing(qv));
                            assert_eq!(ca, cb, "set {k}: crossings of {qv:?}");
                            // the filter during the grid walk: the old sorted query, filtered
                            assert_eq!(ca, old.crossing_by_query(qv), "set {k}: {qv:?}");
                            assert_eq!(cb, new.crossing_by_query(qv), "set {k}: {qv:?}");
                            crossed += ca.len();
                            calls += 1;
                            // the work: the new grid hands over exactly the old candidates
                            // but those in supporting planes, never one of those
                            let bb = bbox(&qv.map(|v| pos[v as usize]));
                            let (mut ia, mut ib) = (Vec::new(), Vec::new());
                            old.tgrid.query(bb.0, bb.1, &mut ia);
                            new.tgrid.query(bb.0, bb.1, &mut ib);
                            let held = |i: &u32| new.support.holds(&pos, new.tris[*i as usize]);
                            assert!(!ib.iter().any(held), "set {k}: {qv:?}");
                            let n_held = ia.iter().filter(|i| held(i)).count();
                            ia.retain(|i| !held(i));
                            assert_eq!(ia, ib, "set {k}: {qv:?}");
                            never += n_held;
                            old.remove(f, a.item.1, &bf, &nf);
                            new.remove(f, a.item.1, &bf, &nf);
                        }
                        _ => {
                            assert_eq!(old.push(a.item.0), new.push(b.item.0));
                        }
                    }
                }
                let (pa, pb) = (old.push_all(), new.push_all());
                assert_eq!(pa, pb, "set {k}");
                if old.done() || !pa {
                    break;
                }
            }
            assert_eq!(old.boundary(), new.boundary(), "set {k}");
            assert_eq!(old.iterations, new.iterations, "set {k}");
            let r = old.iterations.max(1);
            let (per_old, per_new) = (
                old.crossing_examined as f64 / r as f64,
                new.crossing_examined as f64 / r as f64,
            );
            eprintln!(
                "set {k}: {} points, {t_all} triangles, {} removals, examined per removal \
                 old {per_old:.0}, new {per_new:.0}",
                pos.len(),
                old.iterations
            );
            // (two crossing searches per removal here: the compared one and `remove`'s; the
            // old search examined about all T triangles in each on the lattice prisms)
            assert!(per_new <= per_old, "set {k}: {per_new} > {per_old}");
            removals += old.iterations;
            examined.0 += old.crossing_examined;
            examined.1 += new.crossing_examined;
        }
        assert!(removals > 100 && calls == removals, "{removals} {calls}");
        eprintln!("crossings {crossed}");
        assert!(crossed > 100, "{crossed}");
        // the old search spent a good part of its work on triangles that never cross
        eprintln!("examined {examined:?}, never crossing {never}");
        assert!(
            examined.0 > examined.1 && 5 * never > examined.0 / 2,
            "{examined:?} {never}"
        );
    }

    /// [`Plane::side`] is the sign of `orient3d` (filter or fallback): on random points at
    /// scales 1e-120 … 1e120, on lattice points (exact zeros), on points one ulp off a plane
    /// and on the plane's own corners. And the filter decides most random cases itself.
    #[test]
    fn plane_side_is_the_sign_of_orient3d() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(41);
        let (mut n, mut zeros, mut near) = (0usize, 0usize, 0usize);
        for it in 0..40_000 {
            let scale = 10f64.powi([0, 0, 0, 3, -7, 120, -120][it % 7]);
            let lattice = it % 5 == 1;
            let mut pt = || -> P {
                std::array::from_fn(|_| {
                    if lattice {
                        rng.gen_range(-3i32..=3) as f64 * scale
                    } else {
                        rng.gen_range(-1.0..1.0) * scale
                    }
                })
            };
            let (a, b, c) = (pt(), pt(), pt());
            let mut x = pt();
            if it % 5 == 2 {
                // on the plane up to rounding, then nudged by an ulp or two
                let (s, t) = (rng.gen_range(-2.0..2.0), rng.gen_range(-2.0..2.0));
                x = std::array::from_fn(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]));
                let k = rng.gen_range(0..3);
                for _ in 0..rng.gen_range(0..3) {
                    x[k] = if rng.gen_bool(0.5) {
                        x[k].next_up()
                    } else {
                        x[k].next_down()
                    };
                }
                near += 1;
            } else if it % 5 == 3 {
                x = [a, b, c][it % 3];
            }
            let want = sign_code(orient3d(a, b, c, x));
            assert_eq!(Plane::new(a, b, c).side(x), want, "{a:?} {b:?} {c:?} {x:?}");
            zeros += usize::from(want == 0);
            n += 1;
        }
        assert!(
            n == 40_000 && zeros > 8_000 && near > 7_000,
            "{zeros} {near}"
        );
    }

    /// [`OpenTet::may_meet`] (one prepared tetrahedron for many triangles, face sides kept by
    /// vertex id) answers as the former [`may_meet_open_tet_reference`], on random and lattice
    /// configurations (coplanar corners: exact zeros) sharing 0, 1 or 2 vertices with Q.
    #[test]
    fn open_tet_answers_as_the_reference() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
        let (mut meet, mut apart) = (0usize, 0usize);
        for it in 0..400 {
            let lattice = it % 2 == 0;
            let pts: Vec<P> = (0..40)
                .map(|_| {
                    std::array::from_fn(|_| {
                        if lattice {
                            rng.gen_range(0i32..4) as f64
                        } else {
                            rng.gen_range(-1.0..1.0)
                        }
                    })
                })
                .collect();
            let qv = [0u32, 1, 2, 3];
            let q = qv.map(|v| pts[v as usize]);
            let mut open = OpenTet::new(q, qv);
            for _ in 0..200 {
                let mut tv = [0u32; 3];
                for k in 0..3 {
                    tv[k] = rng.gen_range(0..40);
                }
                if tv[0] == tv[1] || tv[1] == tv[2] || tv[0] == tv[2] {
                    continue;
                }
                let t = tv.map(|v| pts[v as usize]);
                let want = may_meet_open_tet_reference(t, tv, q, qv);
                assert_eq!(open.may_meet(t, tv), want, "{t:?} {q:?}");
                assert_eq!(may_meet_open_tet(t, tv, q, qv), want);
                if want {
                    meet += 1;
                } else {
                    apart += 1;
                }
            }
        }
        assert!(meet > 5_000 && apart > 5_000, "{meet} {apart}");
    }

    /// Every `stride`-th vertex of the fandisk model of the shared data (`None` when the file
    /// is not there): large coplanar hull facets on a CAD surface.
    fn fandisk_subset(stride: usize) -> Option<Vec<crate::geom::Point3>> {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/data/meshes/fandisk.obj"
        );
        let text = std::fs::read_to_string(path).ok()?;
        let pts: Vec<crate::geom::Point3> = text
            .lines()
            .filter(|l| l.starts_with("v "))
            .step_by(stride)
            .filter_map(|l| {
                let v: Vec<f64> = l[2..]
                    .split_whitespace()
                    .filter_map(|x| x.parse().ok())
                    .collect();
                (v.len() == 3).then(|| crate::geom::Point3::new(v[0], v[1], v[2]))
            })
            .collect();
        (pts.len() > 100).then_some(pts)
    }

    /// [`FROM_HULL_TRIPLES`]: the constriction from the hull (local γ-triangles at c = −0.5, as
    /// `Engine3::gamma_from_hull` beyond the whole-γ size) given every candidate
    /// ([`GroupTriples::All`]) and given those without the hull facets' empty triangles makes
    /// the same removals — run in lockstep, comparing every heap entry, every removability
    /// verdict, every crossing set (as vertex triples: the ids differ) and every sweep — on
    /// fandisk-like lattice prisms, a cube with points on its faces and a fandisk subset. And
    /// the argument's steps on the engine with every triangle: no face of a removed
    /// tetrahedron is a facet triangle, and every facet triangle is still live at the end.
    #[test]
    fn hull_facet_triangles_change_no_removal() {
        use crate::graphs::fast::candidates_3d_with;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let mut cube = super::super::test_sets::cube(&mut rng, 300);
        for p in cube.iter_mut().step_by(2) {
            let k = rng.gen_range(0..3);
            p[k] = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        }
        let mut sets = vec![
            ("prism 4", super::super::test_sets::l_prism(4)),
            ("prism 5", super::super::test_sets::l_prism(5)),
            ("cube faces", cube),
        ];
        if let Some(f) = fandisk_subset(9) {
            sets.push(("fandisk / 9", f));
        }
        let (mut removals, mut facet_total, mut sweeps) = (0usize, 0usize, 0usize);
        for (name, pts) in &sets {
            let d = crate::delaunay::d3::triangulate(pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let all = candidates_3d_with(&d, GroupTriples::All).0.triangles;
            let few = candidates_3d_with(&d, FROM_HULL_TRIPLES).0.triangles;
            let kept: std::collections::HashSet<[u32; 3]> = few.iter().copied().collect();
            let facet: std::collections::HashSet<[u32; 3]> =
                all.iter().copied().filter(|t| !kept.contains(t)).collect();
            assert!(
                facet.len() > few.len() / 4,
                "{name}: {} facet triangles",
                facet.len()
            );
            facet_total += facet.len();
            let make = |tris: &[[u32; 3]]| {
                let mut g = General3::new(&pos, &d.hull, tris, &[]);
                let extra = g.local_gamma(-0.5, 16);
                (g, extra)
            };
            let (mut old, xa) = make(&all);
            let (mut new, xb) = make(&few);
            assert_eq!(xa, xb, "{name}: local γ-triangles");
            assert_eq!(old.augment(&xa), new.augment(&xb), "{name}");
            assert_eq!(old.heap.len(), new.heap.len(), "{name}");
            let tri_set = |g: &General3, ids: &[u32]| -> Vec<[u32; 3]> {
                let mut v: Vec<[u32; 3]> = ids.iter().map(|&i| g.tris[i as usize]).collect();
                v.sort_unstable();
                v
            };
            loop {
                while !old.done() {
                    let (a, b) = (old.heap.pop(), new.heap.pop());
                    let (Some(a), Some(b)) = (a, b) else {
                        assert!(a.is_none() && b.is_none(), "{name}: heaps");
                        break;
                    };
                    assert_eq!(a.item, b.item, "{name}");
                    assert_eq!(a.key.to_bits(), b.key.to_bits(), "{name}");
                    if !old.is_bface(a.item.0) {
                        assert!(!new.is_bface(b.item.0), "{name}");
                        continue;
                    }
                    let (ra, rb) = (old.check(a.item.0, a.item.1), new.check(b.item.0, b.item.1));
                    assert_eq!(ra.is_some(), rb.is_some(), "{name}: {:?}", a.item);
                    match (ra, rb) {
                        (Some((_, bf, nf)), Some((_, bf2, nf2))) => {
                            assert_eq!((&bf, &nf), (&bf2, &nf2), "{name}");
                            let f = a.item.0;
                            let qv = [f[0], f[1], f[2], a.item.1];
                            for face in bf.iter().chain(&nf) {
                                assert!(!facet.contains(&sorted3(*face)), "{name}: {qv:?}");
                            }
                            let (ca, cb) = (old.crossing(qv), new.crossing(qv));
                            assert_eq!(tri_set(&old, &ca), tri_set(&new, &cb), "{name}: {qv:?}");
                            old.remove(f, a.item.1, &bf, &nf);
                            new.remove(f, a.item.1, &bf, &nf);
                        }
                        _ => assert_eq!(old.push(a.item.0), new.push(b.item.0), "{name}"),
                    }
                }
                let (pa, pb) = (old.push_all(), new.push_all());
                assert_eq!(pa, pb, "{name}: sweep");
                sweeps += 1;
                if old.done() || !pa {
                    break;
                }
            }
            assert_eq!(old.boundary(), new.boundary(), "{name}");
            assert_eq!(old.iterations, new.iterations, "{name}");
            assert_eq!(old.added, new.added, "{name}");
            assert_eq!(old.boundary_vertices, new.boundary_vertices, "{name}");
            for t in &facet {
                assert!(
                    old.has(t[0], t[1], t[2]),
                    "{name}: facet triangle {t:?} deleted"
                );
            }
            eprintln!(
                "{name}: {} points, {} / {} triangles, {} removals, done {}",
                pos.len(),
                few.len(),
                all.len(),
                old.iterations,
                old.done()
            );
            removals += old.iterations;
        }
        assert!(
            removals > 300 && facet_total > 5000 && sweeps >= 4,
            "{removals} {facet_total}"
        );
    }

    /// Diagnostics (ignored): the crossing search's work on a point file
    /// (`MORPHO_DIAG_XYZ`, x y z per line) constricted from the hull at c = −0.5.
    #[test]
    #[ignore]
    fn diag_crossing_work() {
        let Ok(path) = std::env::var("MORPHO_DIAG_XYZ") else {
            return;
        };
        let text = std::fs::read_to_string(path).unwrap();
        let pts: Vec<crate::geom::Point3> = text
            .lines()
            .filter_map(|l| {
                let v: Vec<f64> = l
                    .split_whitespace()
                    .filter_map(|x| x.parse().ok())
                    .collect();
                (v.len() >= 3).then(|| crate::geom::Point3::new(v[0], v[1], v[2]))
            })
            .collect();
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let all = crate::graphs::fast::candidates_3d(&d).triangles;
        let mut g = General3::new(&pos, &d.hull, &all, &[]);
        let held = all
            .iter()
            .filter(|t| g.support.holds(&pos, sorted3(**t)))
            .count();
        let mut lens: Vec<f64> = all
            .iter()
            .filter(|t| !g.support.holds(&pos, sorted3(**t)))
            .map(|t| {
                (0..3)
                    .map(|k| {
                        crate::geom::vec::dist(pos[t[k] as usize], pos[t[(k + 1) % 3] as usize])
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        lens.sort_by(f64::total_cmp);
        let q = |f: f64| {
            lens.get((f * lens.len() as f64) as usize)
                .copied()
                .unwrap_or(0.0)
        };
        eprintln!(
            "points {} triangles {} planes {} held {held}; rest longest edge q10 {:.3} q50 {:.3} q90 {:.3} q99 {:.3}; cells t {:.3} b {:.3}",
            pos.len(),
            all.len(),
            g.support.len(),
            q(0.1),
            q(0.5),
            q(0.9),
            q(0.99),
            g.bgrid.cell(),
            g.bgrid.cell()
        );
        let extra = g.local_gamma(-0.5, 16);
        let added = g.augment(&extra);
        eprintln!("local gamma {} added {added}", extra.len());
        let (mut last_i, mut last_e) = (0, 0);
        loop {
            while !g.done() {
                let Some(en) = g.heap.pop() else { break };
                if !g.is_bface(en.item.0) {
                    continue;
                }
                match g.check(en.item.0, en.item.1) {
                    Some((_, bf, nf)) => {
                        let f = en.item.0;
                        g.remove(f, en.item.1, &bf, &nf);
                        if g.iterations % 500 == 0 {
                            eprintln!(
                                "removals {} examined per removal {:.0}",
                                g.iterations,
                                (g.crossing_examined - last_e) as f64
                                    / (g.iterations - last_i) as f64
                            );
                            (last_i, last_e) = (g.iterations, g.crossing_examined);
                        }
                    }
                    None => {
                        g.push(en.item.0);
                    }
                }
            }
            if g.done() || !g.push_all() {
                break;
            }
        }
        eprintln!(
            "removals {} examined {} done {}",
            g.iterations,
            g.crossing_examined,
            g.done()
        );
    }

    #[test]
    fn open_tet_test_never_misses_a_sampled_hit() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut hits, mut sep) = (0, 0);
        for it in 0..3000 {
            let mut pts: Vec<P> = (0..7)
                .map(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)))
                .collect();
            // share 0, 1 or 2 vertices
            let share = it % 3;
            let qv = [0u32, 1, 2, 3];
            let tv: [u32; 3] = match share {
                0 => [4, 5, 6],
                1 => [0, 5, 6],
                _ => [0, 1, 6],
            };
            if it % 7 == 0 {
                pts[6] = [
                    0.5 * (pts[2][0] + pts[3][0]),
                    0.5 * (pts[2][1] + pts[3][1]),
                    0.5 * (pts[2][2] + pts[3][2]),
                ];
            }
            let q = qv.map(|v| pts[v as usize]);
            let t = tv.map(|v| pts[v as usize]);
            if orient3d(q[0], q[1], q[2], q[3]) == 0.0 {
                continue;
            }
            let got = may_meet_open_tet(t, tv, q, qv);
            if sampled_meet(t, q) {
                assert!(got, "missed {t:?} {q:?}");
                hits += 1;
            } else if !got {
                sep += 1;
            }
        }
        assert!(hits > 300 && sep > 300, "{hits} {sep}");
    }

    #[test]
    fn disjoint_and_touching_cases_are_separated() {
        let q = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let qv = [0, 1, 2, 3];
        // a triangle on the face z = 0 (outside), sharing edge 0 1
        assert!(!may_meet_open_tet(
            [q[0], q[1], [0.5, -1.0, 0.0]],
            [0, 1, 9],
            q,
            qv
        ));
        // the same edge, pointing inside
        assert!(may_meet_open_tet(
            [q[0], q[1], [0.3, 0.3, 0.3]],
            [0, 1, 9],
            q,
            qv
        ));
        // far away, no shared vertex
        assert!(!may_meet_open_tet(
            [[2.0, 2.0, 2.0], [3.0, 2.0, 2.0], [2.0, 3.0, 2.0]],
            [7, 8, 9],
            q,
            qv
        ));
        // piercing through the middle
        assert!(may_meet_open_tet(
            [[0.2, 0.2, -1.0], [0.2, 0.2, 2.0], [-3.0, -3.0, 0.2]],
            [7, 8, 9],
            q,
            qv
        ));
    }

    /// hits_boundary (grid, plane culling, early exit) against all boundary faces tested
    /// exactly one by one.

    #[test]
    fn hits_boundary_matches_all_faces() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let pts: Vec<crate::geom::Point3> = (0..200)
            .map(|i| {
                let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                if i % 3 == 0 {
                    crate::geom::Point3::new(v[0], v[1], (v[2] * 8.0).round() / 8.0)
                } else {
                    crate::geom::Point3::new(v[0], v[1], v[2])
                }
            })
            .collect();
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        // the hull of the first 40 points: a closed surface the random triangles cross
        let d2 = crate::delaunay::d3::triangulate(&pts[..40]).unwrap();
        let inner: Vec<[u32; 3]> = d2
            .hull
            .iter()
            .map(|f| f.map(|v| d.vertex_of_input[d2.input_of_vertex[v as usize] as usize]))
            .collect();
        let g = General3::new(&pos, &inner, &[], &[]);
        let faces = g.boundary();
        assert_eq!(faces.len(), inner.len());
        let n = pos.len() as u32;
        let (mut hits, mut clear) = (0, 0);
        for _ in 0..1500 {
            let t = [
                rng.gen_range(0..n),
                rng.gen_range(0..n),
                rng.gen_range(0..n),
            ];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue;
            }
            let st = sorted3(t);
            let expect = faces.iter().any(|&u| {
                sorted3(u) != st
                    && !crate::mesh::validity::self_intersections_brute(&pos, &[t, u]).is_empty()
            });
            assert_eq!(g.hits_boundary(t, &[]), expect, "{t:?}");
            if expect {
                hits += 1;
            } else {
                clear += 1;
            }
        }
        assert!(hits > 100 && clear > 100, "{hits} {clear}");
    }
}

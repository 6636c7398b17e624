//! 3D constriction of a general pruned γ-graph (Veltkamp 1992, §5.4 last paragraphs: 3D
//! γ([-1,1],[c,1]) with c < 0 by adaptive augmentation; §5.3 removability; §5.5 heap; §5.7
//! constraints), the fallback of [`super::constrict3`] when the Delaunay constriction locks.
//!
//! # State
//! A set of live triangles (the pruned graph; tetrahedra are implicit: four live triangles on
//! four vertices) and a closed boundary surface made of live triangles, oriented outward
//! (`bface`, with a directed-edge map). Invariant: every live triangle lies in the closed region
//! bounded by the surface, and every vertex lies in it (no vertex is ever cut off).
//!
//! # Removal (V §5.3 conditions, §5.4 deletion of crossing triangles)
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
//! ([`super::constrict3::gamma_indicator_3d`], Def. 5.2). Removing Q deletes its boundary faces
//! and **every live triangle meeting the open Q** (V §5.4). That test is conservative and exact:
//! a triangle is kept only when a separating plane is proven — for a triangle sharing a vertex
//! a with Q, the planes through a spanned by two other corners (complete for two cones with a
//! common apex; only `orient3d`); otherwise the face planes of Q, the triangle's plane, and the
//! edge–edge planes of the separating-axis theorem evaluated in floating point with an error
//! filter (a doubtful sign counts as "meets"). Deleting too much only removes choices; it never
//! breaks the invariant.
//!
//! # Heap (V §5.5)
//! One entry per boundary face with its best (smallest-key) removable tetrahedron; a popped
//! entry is re-checked and, when stale, recomputed. When the heap runs empty all boundary faces
//! are examined again, so "locked" means nothing is removable; a face found locked by an earlier
//! sweep is examined again only when a mutation (every one stamps the grid cells of its box)
//! met the box of the face and its apexes since — its removability depends on nothing outside.
//! Triangles added by [`General3::augment`] are not stamped: a live triangle enters only the
//! removability of the boundary faces on its edges, which `augment` evaluates and locks again
//! itself.
//!
//! # Adaptive augmentation (V §5.4)
//! [`General3::augment`] adds triangles (of γ([-1,1],[c,1]), c < 0) that are certified to lie in
//! the region: they meet no boundary triangle except in common vertices/edges (exact), and have
//! a vertex not on the boundary, or a boundary edge from which they go inward (m strictly inside
//! the interior dihedral wedge of the two boundary faces there; exact `orient3d`). Such a
//! triangle is connected, starts inside and never crosses the surface, so it lies in the closed
//! region.
//!
//! # Constraints (V §5.7)
//! Keep triangles are live from the start (added to the graph like V's F) and never deleted: a
//! keep boundary face is never removable, and a tetrahedron whose interior a keep triangle
//! meets is not removed. V's 3D rewiring: when keep triangle x y m blocks a tetrahedron on
//! boundary face x y z, the triangles z x m and z y m are inserted (where they can be certified
//! inside, as for augmentation), so that x y z m becomes a boundary tetrahedron whose removal
//! brings x y m to the boundary. The constriction may still lock with a keep triangle off the
//! boundary (V: "a constrained constriction may get locked"); the caller reports it.
//!
//! # Complexity
//! Removal: O(k log n) with k the live triangles and vertices near Q (uniform hash grids over
//! bounding boxes, cell twice the median edge length; boundary faces and the other live
//! triangles in separate grids; triangles spanning more than 512 cells are kept in a list
//! tested always). Boundary tests stop at the first hit and skip boxes that a conservative
//! floating-point bound puts off the triangle's plane. The sweep of `run` visits only the
//! boundary faces next to a live non-boundary triangle (the only ones that can carry a
//! removable tetrahedron), so a caller may pass only the live triangles near the locked
//! vertices (as [`super::boundary_3d_with`] does) and pay for the boundary only once, in
//! [`General3::new`]. Worst case O(T²) for T triangles.
//!
//! Preconditions: the initial surface is a closed genus-0 2-manifold enclosing every vertex and
//! every given triangle (as produced by [`super::constrict3`] or the convex hull).

use super::constrict3::gamma_indicator_3d;
use super::indicator::MinKey;
use crate::geom::grid::BoxGrid;
use crate::geom::intersect::{degenerate_triangle, triangles_meet_beyond_shared};
use crate::geom::predicates::raw::orient3d;
use crate::geom::vec::{cross, dist, dot, norm, sub};
use crate::util::{sorted3, IdMap, IdSet};
use std::collections::BinaryHeap;

/// How far below c a rejected triangle's γ-scan goes on ([`General3::gamma_decide`]): the
/// cached upper bound of c₁′ then also rejects it for c − 0.1, … (the steps of the caller's
/// schedule), instead of rescanning it at every step.
const UB_LOOKAHEAD: f64 = 0.25;

/// Heap entries: smallest key first, ties by the smallest item.
type Entry = MinKey<([u32; 3], u32)>;

type P = [f64; 3];

/// The rotation of an oriented face that starts at its smallest vertex.
fn sorted_rot(f: [u32; 3]) -> [u32; 3] {
    if f[0] < f[1] && f[0] < f[2] {
        f
    } else if f[1] < f[2] {
        [f[1], f[2], f[0]]
    } else {
        [f[2], f[0], f[1]]
    }
}

fn ek(a: u32, b: u32) -> u64 {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    ((a as u64) << 32) | b as u64
}

fn dk(a: u32, b: u32) -> u64 {
    ((a as u64) << 32) | b as u64
}

/// The four outward faces of tetrahedron (a, b, c, d) when (a, b, c) is outward (d on the inner
/// side), each with its opposite vertex.
fn tet_faces(a: u32, b: u32, c: u32, d: u32) -> [([u32; 3], u32); 4] {
    [
        ([a, b, c], d),
        ([b, a, d], c),
        ([c, b, d], a),
        ([a, c, d], b),
    ]
}

fn circumradius(a: P, b: P, c: P, d: P) -> f64 {
    let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
    let det = dot(u, cross(v, w));
    if det == 0.0 {
        return f64::INFINITY;
    }
    let (vw, wu, uv) = (cross(v, w), cross(w, u), cross(u, v));
    let (uu, vv, ww) = (dot(u, u), dot(v, v), dot(w, w));
    let x: P = std::array::from_fn(|k| (uu * vw[k] + vv * wu[k] + ww * uv[k]) / (2.0 * det));
    norm(x)
}

/// The kernel's box grid in 3D (boxes of triangles, points as zero-size boxes).
type Grid = BoxGrid<3>;

fn bbox(ps: &[P]) -> (P, P) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for q in ps {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    (lo, hi)
}

fn boxes_meet(a: (P, P), b: (P, P)) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

/// Sign of det[x − y, e, f] (e, f edge vectors as differences of doubles), or `None` when the
/// floating-point value is not certified.
fn sat_sign(x: P, y: P, e: (P, P), f: (P, P)) -> Option<i32> {
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
/// when a separating plane is proven (see the module documentation).
pub fn may_meet_open_tet(t: [P; 3], tv: [u32; 3], q: [P; 4], qv: [u32; 4]) -> bool {
    // shared vertex: cones with a common apex, planes through it spanned by two corners
    if let Some((it, iq)) = (0..3)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .find(|&(i, j)| tv[i] == qv[j])
    {
        let a = t[it];
        let ts: Vec<P> = (0..3).filter(|&i| i != it).map(|i| t[i]).collect();
        let qs: Vec<P> = (0..4)
            .filter(|&j| j != iq && !tv.contains(&qv[j]))
            .map(|j| q[j])
            .collect();
        // Q's corners shared with t other than a lie on t: they are on both sides; keep them
        let qsh: Vec<P> = (0..4)
            .filter(|&j| j != iq && tv.contains(&qv[j]))
            .map(|j| q[j])
            .collect();
        let all: Vec<P> = ts.iter().chain(&qs).copied().collect();
        for i in 0..all.len() {
            for j in i + 1..all.len() {
                let (u, v) = (all[i], all[j]);
                let st: Vec<f64> = ts.iter().map(|&x| orient3d(a, u, v, x)).collect();
                let sq: Vec<f64> = qs
                    .iter()
                    .chain(&qsh)
                    .map(|&x| orient3d(a, u, v, x))
                    .collect();
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
    // face planes of q
    let o = orient3d(q[0], q[1], q[2], q[3]);
    if o == 0.0 {
        return false; // flat: no interior
    }
    let faces = [[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]];
    for f in faces {
        let s = orient3d(q[f[0]], q[f[1]], q[f[2]], q[f[3]]);
        if t.iter()
            .all(|&x| orient3d(q[f[0]], q[f[1]], q[f[2]], x) * s <= 0.0)
        {
            return false;
        }
    }
    // the triangle's plane
    let sq: Vec<f64> = q.iter().map(|&x| orient3d(t[0], t[1], t[2], x)).collect();
    if sq.iter().all(|&s| s >= 0.0) || sq.iter().all(|&s| s <= 0.0) {
        return false;
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

/// The third vertices of the live triangles on an edge (most edges have a handful: stored
/// inline, without an allocation each).
type Thirds = smallvec::SmallVec<[u32; 4]>;

/// A removal: key, boundary faces of the tetrahedron, its new boundary faces.
type Removal = (f64, Vec<[u32; 3]>, Vec<[u32; 3]>);

/// The general 3D constriction (see the module documentation). Vertex indices are indices into
/// the point array given to [`General3::new`].
pub struct General3<'a> {
    p: &'a [P],
    tris: Vec<[u32; 3]>,
    live: Vec<bool>,
    /// The triangle is a boundary face (in either orientation).
    bflag: Vec<bool>,
    /// Bounding box of every triangle.
    tbox: Vec<(P, P)>,
    id: IdMap<[u32; 3], u32>,
    eadj: IdMap<u64, Thirds>,
    /// directed boundary edge a→b → third vertex of the outward boundary face containing it
    bnext: IdMap<u64, u32>,
    vcount: Vec<u32>,
    keep: IdSet<[u32; 3]>,
    /// Live triangles that were not boundary faces when added (for [`Self::crossing`]).
    tgrid: Grid,
    /// Triangles that have been boundary faces (for [`Self::hits_boundary`]; `bflag` tells
    /// which still are).
    bgrid: Grid,
    in_bgrid: Vec<bool>,
    vgrid: Grid,
    /// The bounding box of the points.
    pbox: (P, P),
    /// The points again in cells 8× wider, for walks over wide boxes
    /// ([`General3::point_grid_for`]).
    vcoarse: Grid,
    heap: BinaryHeap<Entry>,
    buf: Vec<u32>,
    blocked_by: Option<[u32; 3]>,
    /// Triangles found in a γ-graph by [`General3::local_gamma`] (not tested again).
    in_gamma: IdSet<[u32; 3]>,
    /// Upper bounds of c₁′ of triangles rejected by [`General3::local_gamma`] (from a subset
    /// of the points: more points only lower it), so that a smaller c skips them when the
    /// bound is already below it.
    gamma_ub: IdMap<[u32; 3], f64>,
    /// The nearest vertices of a vertex and the box half-width that certified them
    /// ([`General3::local_gamma`]).
    near_cache: IdMap<u32, (Vec<u32>, f64)>,
    /// Change tracking for [`General3::push_all`] (on after construction): every mutation of a
    /// live triangle or of the boundary stamps the cells of its box (cells of `bgrid`) with a
    /// new epoch (except the additions of [`General3::augment`], which re-evaluates the faces
    /// they concern); `changed_all` is the epoch of a change too wide to stamp.
    track: bool,
    epoch: u64,
    changed: IdMap<(i64, i64, i64), u64>,
    changed_all: u64,
    /// Boundary faces found without a removable tetrahedron by a sweep, with the epoch and the
    /// box of everything their removability depends on (see [`General3::push_all`]).
    locked_at: IdMap<[u32; 3], (u64, P, P)>,
    /// Sweeps skip unchanged locked faces (switchable for the equivalence test).
    skip_unchanged: bool,
    /// Faces skipped so (for the tests).
    skipped: usize,
    /// Tests: evaluate the faces of a sweep or of an augmentation one after the other even
    /// without keep triangles.
    sequential_sweeps: bool,
    /// Tests: evaluate every skipped face anyway and panic if it has a removable tetrahedron.
    verify_skips: bool,
    /// Number of boundary vertices.
    pub boundary_vertices: usize,
    /// Number of removed tetrahedra.
    pub iterations: usize,
    /// Number of triangles added by [`General3::augment`].
    pub added: usize,
}

impl<'a> General3<'a> {
    /// A graph on points `p` with the closed outward-oriented boundary surface `boundary` and
    /// the live triangles `tris` (all inside the closed region; the boundary triangles are
    /// added to them). `keep` triangles are never deleted.
    pub fn new(p: &'a [P], boundary: &[[u32; 3]], tris: &[[u32; 3]], keep: &[[u32; 3]]) -> Self {
        let mut g = Self::blank(p, boundary, tris, keep);
        g.build(boundary, tris, keep);
        g.track = true;
        g.push_all();
        g
    }

    /// The engine's tables before anything is added (cell size from the given triangles).
    fn blank(p: &'a [P], boundary: &[[u32; 3]], tris: &[[u32; 3]], keep: &[[u32; 3]]) -> Self {
        let (lo, hi) = bbox(p);
        let n = p.len().max(1);
        // cell: twice the median edge length of the triangles (points of a scanned surface
        // fill the bounding box far from evenly, so its volume per point is a poor scale)
        let mut lens: Vec<f64> = boundary
            .iter()
            .chain(tris)
            .step_by((boundary.len() + tris.len()) / 20_000 + 1)
            .flat_map(|t| {
                (0..3).map(move |k| {
                    let (a, b) = (p[t[k] as usize], p[t[(k + 1) % 3] as usize]);
                    dist(a, b)
                })
            })
            .filter(|x| x.is_finite())
            .collect();
        let mut cell = if lens.is_empty() {
            0.0
        } else {
            let mid = lens.len() / 2;
            2.0 * *lens.select_nth_unstable_by(mid, f64::total_cmp).1
        };
        if cell <= 0.0 || !cell.is_finite() {
            let vol = (0..3).map(|k| (hi[k] - lo[k]).max(0.0)).product::<f64>();
            cell = 2.0 * (vol / n as f64).cbrt();
        }
        if cell <= 0.0 || !cell.is_finite() {
            cell = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max).max(1.0) / (n as f64).sqrt();
        }
        General3 {
            p,
            tris: Vec::new(),
            live: Vec::new(),
            bflag: Vec::new(),
            tbox: Vec::new(),
            id: IdMap::default(),
            eadj: IdMap::default(),
            bnext: IdMap::default(),
            vcount: vec![0; p.len()],
            keep: keep.iter().map(|&f| sorted3(f)).collect(),
            tgrid: Grid::new(lo, cell, true),
            bgrid: Grid::new(lo, cell, true),
            in_bgrid: Vec::new(),
            vgrid: Grid::new(lo, cell, false),
            pbox: (lo, hi),
            vcoarse: Grid::new(lo, cell * Grid::COARSEN, false),
            heap: BinaryHeap::new(),
            buf: Vec::new(),
            blocked_by: None,
            in_gamma: IdSet::default(),
            gamma_ub: IdMap::default(),
            near_cache: IdMap::default(),
            track: false,
            epoch: 0,
            changed: IdMap::default(),
            changed_all: 0,
            locked_at: IdMap::default(),
            skip_unchanged: true,
            skipped: 0,
            sequential_sweeps: false,
            verify_skips: false,
            boundary_vertices: 0,
            iterations: 0,
            added: 0,
        }
    }

    /// The initial state of [`General3::new`], in bulk: the same as adding every boundary
    /// face (boundary grid only), then every live triangle, then marking the boundary faces —
    /// ids, edge lists and grid cells in that order — but with every list allocated once and
    /// the independent tables built in parallel.
    fn build(&mut self, boundary: &[[u32; 3]], tris: &[[u32; 3]], keep: &[[u32; 3]]) {
        use rayon::prelude::*;
        let nt = boundary.len() + tris.len() + keep.len();
        self.id.reserve(nt);
        self.tris.reserve(nt);
        // ids: boundary faces first (not in the grid of live triangles), no repeats
        let mut n_boundary_ids = 0;
        for (k, &t) in boundary.iter().chain(tris).chain(keep).enumerate() {
            if k == boundary.len() {
                n_boundary_ids = self.tris.len();
            }
            let s = sorted3(t);
            if s[0] == s[1] || s[1] == s[2] {
                continue;
            }
            if let std::collections::hash_map::Entry::Vacant(e) = self.id.entry(s) {
                e.insert(self.tris.len() as u32);
                self.tris.push(s);
            }
        }
        if tris.is_empty() && keep.is_empty() {
            n_boundary_ids = self.tris.len();
        }
        let n = self.tris.len();
        self.live = vec![true; n];
        self.bflag = vec![false; n];
        self.in_bgrid = vec![false; n];
        let p = self.p;
        self.tbox = self
            .tris
            .par_iter()
            .map(|s| bbox(&s.map(|v| p[v as usize])))
            .collect();
        // boundary faces in the boundary grid, in the order of the list
        let mut bids = Vec::with_capacity(boundary.len());
        for f in boundary {
            if let Some(&i) = self.id.get(&sorted3(*f)) {
                self.bflag[i as usize] = true;
                if !self.in_bgrid[i as usize] {
                    self.in_bgrid[i as usize] = true;
                    bids.push(i);
                }
            }
        }
        let (tl, tbox) = (&self.tris, &self.tbox);
        let (eadj, bnext, vcount, bv, vgrid, vcoarse, tgrid, bgrid) = (
            &mut self.eadj,
            &mut self.bnext,
            &mut self.vcount,
            &mut self.boundary_vertices,
            &mut self.vgrid,
            &mut self.vcoarse,
            &mut self.tgrid,
            &mut self.bgrid,
        );
        rayon::join(
            || {
                // edge → third vertices, in id order
                let mut e: Vec<(u64, u32, u32)> = tl
                    .par_iter()
                    .enumerate()
                    .flat_map_iter(|(i, s)| {
                        (0..3).map(move |k| {
                            let (a, b, c) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
                            (ek(a, b), i as u32, c)
                        })
                    })
                    .collect();
                e.par_sort_unstable();
                eadj.reserve(e.len() / 2);
                for run in e.chunk_by(|a, b| a.0 == b.0) {
                    eadj.insert(run[0].0, run.iter().map(|x| x.2).collect());
                }
            },
            || {
                rayon::join(
                    || {
                        rayon::join(
                            || {
                                tgrid.insert_many(
                                    (n_boundary_ids..n).map(|i| (i as u32, tbox[i].0, tbox[i].1)),
                                );
                            },
                            || {
                                bgrid.insert_many(bids.iter().map(|&i| {
                                    let (lo, hi) = tbox[i as usize];
                                    (i, lo, hi)
                                }));
                            },
                        )
                    },
                    || {
                        vgrid.reserve(p.len());
                        for (v, &q) in p.iter().enumerate() {
                            vgrid.insert(v as u32, q, q);
                            vcoarse.insert(v as u32, q, q);
                        }
                        bnext.reserve(3 * boundary.len());
                        for f in boundary {
                            for k in 0..3 {
                                let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
                                bnext.insert(dk(a, b), c);
                                let v = a as usize;
                                if vcount[v] == 0 {
                                    *bv += 1;
                                }
                                vcount[v] += 1;
                            }
                        }
                    },
                );
            },
        );
    }

    /// Records a mutation inside the box (see `track`).
    fn touched(&mut self, lo: P, hi: P) {
        if !self.track {
            return;
        }
        self.epoch += 1;
        let (a, b) = self.bgrid.range(lo, hi);
        let span = Grid::span(a, b);
        if span > Grid::MAX_SPAN {
            self.changed_all = self.epoch;
            return;
        }
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    self.changed.insert((x, y, z), self.epoch);
                }
            }
        }
    }

    /// Has anything meeting the box changed after `epoch`?
    fn changed_since(&self, epoch: u64, lo: P, hi: P) -> bool {
        if self.changed_all > epoch {
            return true;
        }
        let (a, b) = self.bgrid.range(lo, hi);
        let span = Grid::span(a, b);
        span > Grid::MAX_SPAN
            || (a[0]..=b[0]).any(|x| {
                (a[1]..=b[1]).any(|y| {
                    (a[2]..=b[2]).any(|z| self.changed.get(&(x, y, z)).is_some_and(|&e| e > epoch))
                })
            })
    }

    /// The point grid to walk for a box: `vgrid`, or `vcoarse` (cells 8× wider) when the box
    /// spans many fine cells (a wide box over a scanned surface has mostly empty cells).
    /// Either holds every point at its own level (points are never wide boxes).
    fn point_grid_for(&self, lo: P, hi: P) -> &Grid {
        let (a, b) = self.vgrid.range(lo, hi);
        let span = Grid::span(a, b);
        if span <= 4096 {
            &self.vgrid
        } else {
            &self.vcoarse
        }
    }

    fn pt(&self, v: u32) -> P {
        self.p[v as usize]
    }

    fn add_tri(&mut self, t: [u32; 3]) -> bool {
        self.add_tri_grid(t, true)
    }

    fn add_tri_grid(&mut self, t: [u32; 3], grid: bool) -> bool {
        let s = sorted3(t);
        if s[0] == s[1] || s[1] == s[2] {
            return false;
        }
        if let Some(&i) = self.id.get(&s) {
            if self.live[i as usize] {
                return false;
            }
            self.live[i as usize] = true;
        } else {
            let i = self.tris.len() as u32;
            self.tris.push(s);
            self.live.push(true);
            self.bflag.push(false);
            self.in_bgrid.push(false);
            self.id.insert(s, i);
            let (lo, hi) = bbox(&s.map(|v| self.pt(v)));
            self.tbox.push((lo, hi));
            if grid {
                self.tgrid.insert(i, lo, hi);
            }
        }
        for k in 0..3 {
            let (a, b, c) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
            self.eadj.entry(ek(a, b)).or_default().push(c);
        }
        if self.track {
            let (lo, hi) = self.tbox[self.id[&s] as usize];
            self.touched(lo, hi);
        }
        true
    }

    fn kill(&mut self, i: u32) {
        if !self.live[i as usize] {
            return;
        }
        self.live[i as usize] = false;
        let (lo, hi) = self.tbox[i as usize];
        self.touched(lo, hi);
        let s = self.tris[i as usize];
        for k in 0..3 {
            let (a, b, c) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
            if let Some(v) = self.eadj.get_mut(&ek(a, b)) {
                v.retain(|x| *x != c);
            }
        }
    }

    /// True when triangle abc is live.
    pub fn has(&self, a: u32, b: u32, c: u32) -> bool {
        self.id
            .get(&sorted3([a, b, c]))
            .is_some_and(|&i| self.live[i as usize])
    }

    fn set_boundary(&mut self, f: [u32; 3], on: bool) {
        if self.track {
            let (lo, hi) = bbox(&f.map(|v| self.pt(v)));
            self.touched(lo, hi);
        }
        if let Some(&i) = self.id.get(&sorted3(f)) {
            self.bflag[i as usize] = on;
            if on && !self.in_bgrid[i as usize] {
                self.in_bgrid[i as usize] = true;
                let (lo, hi) = self.tbox[i as usize];
                self.bgrid.insert(i, lo, hi);
            }
        }
        for k in 0..3 {
            let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            if on {
                self.bnext.insert(dk(a, b), c);
            } else {
                self.bnext.remove(&dk(a, b));
            }
            let v = a as usize;
            if on {
                if self.vcount[v] == 0 {
                    self.boundary_vertices += 1;
                }
                self.vcount[v] += 1;
            } else {
                self.vcount[v] = self.vcount[v].saturating_sub(1);
                if self.vcount[v] == 0 {
                    self.boundary_vertices -= 1;
                }
            }
        }
    }

    /// Is the oriented face a boundary face (with this orientation)?
    fn is_bface(&self, f: [u32; 3]) -> bool {
        self.bnext.get(&dk(f[0], f[1])) == Some(&f[2])
    }

    fn on_boundary(&self, v: u32) -> bool {
        self.vcount[v as usize] > 0
    }

    fn bedge(&self, a: u32, b: u32) -> bool {
        self.bnext.contains_key(&dk(a, b)) || self.bnext.contains_key(&dk(b, a))
    }

    /// The boundary surface (outward faces).
    pub fn boundary(&self) -> Vec<[u32; 3]> {
        let mut out: Vec<[u32; 3]> = self
            .bnext
            .iter()
            .filter_map(|(&k, &c)| {
                let (a, b) = ((k >> 32) as u32, k as u32);
                (a < b && a < c).then_some([a, b, c])
            })
            .collect();
        out.sort_unstable();
        out
    }

    /// Combinatorial removability of tetrahedron (face, l) and its key; cheap checks only.
    /// Returns (key, boundary faces of Q, new faces).
    fn combinatorial(&self, f: [u32; 3], l: u32) -> Option<Removal> {
        let [a, b, c] = f;
        if l == a || l == b || l == c || !self.is_bface(f) {
            return None;
        }
        if !self.has(a, b, l) || !self.has(b, c, l) || !self.has(a, c, l) {
            return None;
        }
        let (pa, pb, pc, pl) = (self.pt(a), self.pt(b), self.pt(c), self.pt(l));
        if orient3d(pa, pb, pc, pl) <= 0.0 {
            return None;
        }
        let faces = tet_faces(a, b, c, l);
        let mut bf = Vec::new();
        let mut nf = Vec::new();
        let mut opp = Vec::new();
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
    fn empty(&mut self, qv: [u32; 4]) -> bool {
        let mut buf = std::mem::take(&mut self.buf);
        let ok = self.empty_with(qv, &mut buf);
        self.buf = buf;
        ok
    }

    /// [`Self::empty`] with a scratch buffer of the caller's.
    fn empty_with(&self, qv: [u32; 4], buf: &mut Vec<u32>) -> bool {
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
    fn hits_boundary(&self, t: [u32; 3], skip: &[[u32; 3]]) -> bool {
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
        self.bgrid.any_in_box(bb.0, bb.1, |i| {
            // live boundary triangle (either orientation of the sorted triple)
            if !self.live[i as usize] || !self.bflag[i as usize] {
                return false;
            }
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
            let u = self.tris[i as usize];
            if u == st || skip_s.contains(&u) || skip.iter().skip(4).any(|&x| sorted3(x) == u) {
                return false;
            }
            let pu = u.map(|v| self.pt(v));
            triangles_meet_beyond_shared(t, pt, u, pu)
        })
    }

    /// Live triangles meeting the open tetrahedron (conservative), other than its faces.
    fn crossing(&mut self, qv: [u32; 4]) -> Vec<u32> {
        let q = qv.map(|v| self.pt(v));
        let bb = bbox(&q);
        let mut buf = std::mem::take(&mut self.buf);
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
        self.buf = buf;
        out
    }

    /// Full removability check of tetrahedron (boundary face f, apex l).
    fn check(&mut self, f: [u32; 3], l: u32) -> Option<Removal> {
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
    fn best(&mut self, f: [u32; 3]) -> Option<(f64, u32)> {
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
    fn best_plain(&self, f: [u32; 3], buf: &mut Vec<u32>) -> Option<(f64, u32)> {
        debug_assert!(self.keep.is_empty());
        if !self.is_bface(f) {
            return None;
        }
        let mut keyed: Vec<(f64, u32, Removal)> = self
            .eadj
            .get(&ek(f[0], f[1]))
            .into_iter()
            .flatten()
            .filter(|&&l| l != f[2])
            .filter_map(|&l| self.combinatorial(f, l).map(|r| (r.0, l, r)))
            .collect();
        keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        keyed.into_iter().find_map(|(k, l, (_, bf, nf))| {
            let removable = self.empty_with([f[0], f[1], f[2], l], buf)
                && !nf.iter().any(|&t| self.hits_boundary(t, &bf));
            removable.then_some((k, l))
        })
    }

    /// V §5.7 (3D, Fig. 5.12 right): keep triangle `kt` = x y m crosses a tetrahedron on
    /// boundary face f = x y z: insert z x m and z y m (where they lie inside, see
    /// [`General3::augment`]) so that f + m becomes a tetrahedron whose removal brings `kt` to
    /// the boundary. Returns whether a triangle was inserted.
    fn rewire(&mut self, f: [u32; 3], kt: [u32; 3]) -> bool {
        let common: Vec<u32> = f.iter().copied().filter(|v| kt.contains(v)).collect();
        if common.len() != 2 {
            return false;
        }
        let (Some(&z), Some(&m)) = (
            f.iter().find(|v| !common.contains(v)),
            kt.iter().find(|v| !common.contains(v)),
        ) else {
            return false;
        };
        let mut any = false;
        for &x in &common {
            any |= self.try_insert([z, x, m]);
        }
        any
    }

    /// Does the triangle a b m leave the boundary edge ab into the region? (exact: m strictly
    /// inside the interior dihedral wedge of the two boundary faces at ab)
    fn inward_at_edge(&self, a: u32, b: u32, m: u32) -> bool {
        let (Some(&y), Some(&w)) = (self.bnext.get(&dk(a, b)), self.bnext.get(&dk(b, a))) else {
            return false;
        };
        let (pa, pb, py, pw, pm) = (self.pt(a), self.pt(b), self.pt(y), self.pt(w), self.pt(m));
        let convex = orient3d(pa, pb, py, pw);
        let o1 = orient3d(pa, pb, py, pm) > 0.0;
        let o2 = orient3d(pb, pa, pw, pm) > 0.0;
        if convex > 0.0 {
            o1 && o2
        } else if convex < 0.0 {
            o1 || o2
        } else {
            o1 && o2
        }
    }

    /// Inserts triangle t when it is new, non-degenerate, certified to start inside the region
    /// (a vertex off the boundary, or a boundary edge it leaves inward) and meets no boundary
    /// triangle beyond common vertices/edges.
    fn try_insert(&mut self, t: [u32; 3]) -> bool {
        !self.has(t[0], t[1], t[2]) && self.insertable_at_boundary(t) && self.add_tri(t)
    }

    /// The conditions of [`Self::try_insert`] that depend on the boundary only (not on the
    /// live triangles, which adding changes): distinct corners, started inside, not
    /// degenerate, meeting no boundary triangle.
    fn insertable_at_boundary(&self, t: [u32; 3]) -> bool {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return false;
        }
        if t.iter().all(|&v| self.on_boundary(v))
            && !(0..3).any(|k| {
                let (a, b, m) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                self.bedge(a, b) && self.inward_at_edge(a, b, m)
            })
        {
            return false;
        }
        let pt = t.map(|v| self.pt(v));
        !(degenerate_triangle(pt[0], pt[1], pt[2]) || self.hits_boundary(t, &[]))
    }

    fn push(&mut self, f: [u32; 3]) -> bool {
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
    fn push_all(&mut self) -> bool {
        use rayon::prelude::*;
        let this = &*self;
        let mut faces: Vec<[u32; 3]> = (0..this.tris.len())
            .into_par_iter()
            .filter(|&i| this.live[i] && !this.bflag[i])
            .flat_map_iter(|i| {
                let t = this.tris[i];
                (0..6).filter_map(move |j| {
                    let (a, b) = (t[j / 2], t[(j / 2 + 1) % 3]);
                    let (x, y) = if j % 2 == 0 { (a, b) } else { (b, a) };
                    this.bnext.get(&dk(x, y)).map(|&z| sorted_rot([x, y, z]))
                })
            })
            .collect();
        faces.par_sort_unstable();
        faces.dedup();
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

    /// Whether face f was found locked before and nothing meeting the box of f and its
    /// apexes has changed since (then [`Self::push_all`] skips it).
    fn unchanged_lock(&self, f: [u32; 3]) -> bool {
        self.skip_unchanged
            && self
                .locked_at
                .get(&f)
                .is_some_and(|&(e, lo, hi)| !self.changed_since(e, lo, hi))
    }

    /// [`Self::unchanged_lock`], counted, and in the tests verified.
    fn skip_locked(&mut self, f: [u32; 3]) -> bool {
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
    fn lock_box(&self, f: [u32; 3]) -> (P, P) {
        let mut q: Vec<P> = f.iter().map(|&v| self.pt(v)).collect();
        for k in 0..3 {
            if let Some(ls) = self.eadj.get(&ek(f[k], f[(k + 1) % 3])) {
                q.extend(ls.iter().map(|&l| self.pt(l)));
            }
        }
        bbox(&q)
    }

    fn remove(&mut self, f: [u32; 3], l: u32, bf: &[[u32; 3]], nf: &[[u32; 3]]) {
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

    /// Keep triangles not (yet) on the boundary.
    pub fn keep_missing(&self) -> usize {
        self.keep
            .iter()
            .filter(|k| !self.is_bface(**k) && !self.is_bface([k[0], k[2], k[1]]))
            .count()
    }

    /// Every vertex and every keep triangle is on the boundary.
    pub fn done(&self) -> bool {
        self.boundary_vertices >= self.p.len() && (self.keep.is_empty() || self.keep_missing() == 0)
    }

    /// Runs the constriction until every vertex and keep triangle is on the boundary or nothing
    /// is removable.
    pub fn run(&mut self) {
        loop {
            while !self.done() {
                let Some(en) = self.heap.pop() else { break };
                if !self.is_bface(en.item.0) {
                    continue;
                }
                match self.check(en.item.0, en.item.1) {
                    Some((_, bf, nf)) => self.remove(en.item.0, en.item.1, &bf, &nf),
                    None => {
                        self.push(en.item.0);
                    }
                }
            }
            if self.done() || !self.push_all() {
                break;
            }
        }
    }

    /// The triangles of γ([-1,1],[c,1]) (Def. 3.1 by the exact centre intervals of
    /// [`crate::graphs::gamma::TriFrame`]) on the vertices not on the boundary and pairs of
    /// their `k` nearest vertices or edges of the `k` boundary faces nearest to them — the part
    /// of the γ-graph needed to free a locked vertex (V §5.4 "adaptive augmentation": only where
    /// needed). Each triangle is decided against every point that can change the decision
    /// (the diametral ball, then the balls that certify an empty neighbourhood; for c = −1 the
    /// points in the closed triangle); see [`Self::gamma_decide`]. Triangles found at an
    /// earlier (larger) c are not returned again, and triangles rejected earlier with an upper
    /// bound of c₁′ below c are not tested again. The nearest vertices of a vertex are computed
    /// once (positions do not change); the candidates are decided in parallel (rayon).
    /// O(L·k²·m) for L locked vertices and m points in the balls scanned.
    pub fn local_gamma(&mut self, c: f64, k: usize) -> Vec<[u32; 3]> {
        use rayon::prelude::*;
        let locked: Vec<u32> = (0..self.p.len() as u32)
            .filter(|&v| !self.on_boundary(v))
            .collect();
        // the nearest vertices of the vertices met for the first time (in parallel)
        let missing: Vec<u32> = locked
            .iter()
            .copied()
            .filter(|l| !self.near_cache.contains_key(l))
            .collect();
        let this = &*self;
        let found: Vec<(Vec<u32>, f64)> = missing.par_iter().map(|&l| this.nearest(l, k)).collect();
        self.near_cache.extend(missing.into_iter().zip(found));
        // candidates of every locked vertex (read-only, in parallel; in the order of `locked`)
        let this = &*self;
        let mut cand: Vec<([u32; 3], u32)> = locked
            .par_iter()
            .map_init(Vec::new, |tb, &l| this.gamma_candidates(l, k, c, tb))
            .flatten_iter()
            .collect();
        // each triangle once (with the first locked vertex that proposed it)
        cand.sort_unstable();
        cand.dedup_by_key(|e| e.0);
        let this = &*self;
        let verdicts: Vec<Option<f64>> = cand
            .par_iter()
            .map(|&(t, l)| this.gamma_decide(t, c, &this.near_cache[&l].0))
            .collect();
        let mut out = Vec::new();
        for (&(t, _), v) in cand.iter().zip(verdicts) {
            match v {
                None => {
                    self.in_gamma.insert(t);
                    out.push(t);
                }
                Some(ub) => {
                    self.gamma_ub.insert(t, ub);
                }
            }
        }
        out
    }

    /// The candidate triangles of [`Self::local_gamma`] for the locked vertex `l` (its nearest
    /// vertices cached): `l` with pairs of its `k` nearest vertices and with the edges of the
    /// `k` boundary faces nearest to it, minus live triangles, triangles already found and
    /// triangles whose cached bound of c₁′ is below `c`. `tb` is scratch space.
    fn gamma_candidates(
        &self,
        l: u32,
        k: usize,
        c: f64,
        tb: &mut Vec<u32>,
    ) -> Vec<([u32; 3], u32)> {
        let (near, rad) = &self.near_cache[&l];
        let mut cand = Vec::new();
        let pl = self.pt(l);
        // pairs of near vertices, and the edges of the k boundary faces nearest to l (by
        // centroid; the faces a removal w.r.t. l starts from)
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (i, &x) in near.iter().enumerate() {
            for &y in &near[i + 1..] {
                pairs.push((x, y));
            }
        }
        // the k faces nearest by centroid among those meeting the box of half-width 2·rad:
        // a face missing from the box of half-width rad has its centroid farther than rad,
        // so when that smaller box already holds k faces with centroids within rad, they
        // are the same k (and the same order)
        let mut faces: Vec<(f64, [u32; 3])> = Vec::new();
        for reach_l in [*rad, 2.0 * rad] {
            self.bgrid.query(
                std::array::from_fn(|i| pl[i] - reach_l),
                std::array::from_fn(|i| pl[i] + reach_l),
                tb,
            );
            faces = tb
                .iter()
                .filter(|&&i| self.live[i as usize] && self.bflag[i as usize])
                .map(|&i| self.tris[i as usize])
                .map(|u| {
                    let q = u.map(|v| self.pt(v));
                    let d2 = (0..3)
                        .map(|i| ((q[0][i] + q[1][i] + q[2][i]) / 3.0 - pl[i]).powi(2))
                        .sum::<f64>();
                    (d2, u)
                })
                .collect();
            faces.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            if faces.iter().filter(|f| f.0 <= rad * rad).count() >= k {
                break;
            }
        }
        for (_, u) in faces.into_iter().take(k) {
            for e in 0..3 {
                pairs.push((u[e], u[(e + 1) % 3]));
            }
        }
        for (x, y) in pairs {
            let t = sorted3([l, x, y]);
            if x == l || y == l || self.has(t[0], t[1], t[2]) || self.in_gamma.contains(&t) {
                continue;
            }
            if self.gamma_ub.get(&t).is_some_and(|&ub| ub < c) {
                continue;
            }
            cand.push((t, l));
        }
        cand
    }

    /// The `k` nearest vertices of `l` (by growing boxes of the vertex grid; ties by index) and
    /// the box half-width that certified them.
    fn nearest(&self, l: u32, k: usize) -> (Vec<u32>, f64) {
        let pl = self.pt(l);
        let n = self.p.len();
        let mut buf = Vec::new();
        let mut rad = self.vgrid.cell();
        loop {
            self.vgrid.query(
                std::array::from_fn(|i| pl[i] - rad),
                std::array::from_fn(|i| pl[i] + rad),
                &mut buf,
            );
            if buf.len() > k || buf.len() >= n {
                let mut v: Vec<(f64, u32)> = buf
                    .iter()
                    .filter(|&&x| x != l)
                    .map(|&x| {
                        let q = self.pt(x);
                        let d2 = (0..3).map(|i| (q[i] - pl[i]).powi(2)).sum::<f64>();
                        (d2, x)
                    })
                    .collect();
                v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                // only points within rad are certainly among the nearest (unless the box holds
                // every point)
                if buf.len() < n {
                    v.retain(|e| e.0 <= rad * rad);
                }
                if v.len() >= k || buf.len() >= n {
                    return (v.into_iter().take(k).map(|e| e.1).collect(), rad);
                }
            }
            rad *= 2.0;
        }
    }

    /// Decides whether triangle `t` is in γ([-1,1],[c,1]): `None` when it is, `Some(ub)` with an
    /// upper bound ub < c of its c₁′ when it is not. Points only narrow the centre interval
    /// (c₁′ never grows), so a decision needs only the points that could still change it:
    /// 1. the points `first` (near the triangle; blocking points are often among them);
    /// 2. the points of the diametral ball B(m, r). If then no ball is empty (c₁′ < 0, the gap
    ///    regime of `gamma_values`), c₁′ is final: a point outside B(m, r) has τ of the sign
    ///    of its side (q > 0) and never moves the gap's farther end;
    /// 3. otherwise the points of the witness ball B(s) of
    ///    [`CenterInterval::witness_offset`], again and again while s moves: once every point
    ///    of B(s) has been added and s stays, an empty neighbourhood of γ([-1,1],[c,1]) lies in
    ///    a ball no further point enters. No fixed radius in terms of c suffices: while some
    ///    ball is empty (c₁′ ≥ 0) a far point inside the largest empty balls can still open a
    ///    gap whose far end passes c.
    ///
    /// A rejection scans on until ub < c − [`UB_LOOKAHEAD`] (or the ball's points run out) so
    /// that the cached bound also settles the next smaller c. Each ball's points are added
    /// nearest to its centre first.
    fn gamma_decide(&self, t: [u32; 3], c: f64, first: &[u32]) -> Option<f64> {
        use crate::graphs::gamma::{triangle_circle, CenterInterval, TriFrame};
        let [pa, pb, pc] = t.map(|v| self.pt(v));
        let (Some(f), Some((m, r2, n))) = (TriFrame::new(pa, pb, pc), triangle_circle(pa, pb, pc))
        else {
            // degenerate (collinear corners): never a γ-triangle
            return Some(f64::NEG_INFINITY);
        };
        let mut iv = f.start();
        let mut buf = Vec::new();
        let pts = self.p;
        if c <= -1.0 {
            // c = −1: every triangle is in γ([-1,1],[-1,1]) unless a point lies in the closed
            // triangle (then no neighbourhood is empty); such points lie in its bounding box
            let (lo, hi) = bbox(&[pa, pb, pc]);
            self.vgrid.query(lo, hi, &mut buf);
            for &z in &buf {
                if !t.contains(&z) {
                    f.add(&mut iv, pts[z as usize]);
                }
            }
            return if iv.all_blocked {
                Some(f64::NEG_INFINITY)
            } else {
                None
            };
        }
        let ub_of = |iv: &CenterInterval| iv.gamma_values().map_or(f64::NEG_INFINITY, |g| g.1);
        let stop = c - UB_LOOKAHEAD;
        // adds the points; true when rejected (ub below stop on the way, or below c at the end)
        let scan = |iv: &mut CenterInterval, ids: &mut dyn Iterator<Item = u32>| -> bool {
            for (j, z) in ids.enumerate() {
                if !t.contains(&z) {
                    f.add(iv, pts[z as usize]);
                }
                if j % 32 == 31 && ub_of(iv) < stop {
                    return true;
                }
            }
            ub_of(iv) < c
        };
        if scan(&mut iv, &mut first.iter().copied()) {
            return Some(ub_of(&iv));
        }
        let nlen = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let (plo, phi) = self.pbox;
        // every point of the ball B(s) (touching the triangle, offset s), by cells of the point
        // grid (the coarse one for wide boxes) whose centres lie deepest in the ball first —
        // by the power q − 2·s·h (< 0 inside; divided by |s| when |s| > 1: the same order
        // without overflow). When the ball's box holds every point, or is not finite: all
        // points in that order.
        let mut cells: Vec<(f64, &[u32])> = Vec::new();
        let mut scan_ball = |iv: &mut CenterInterval, s: f64| -> bool {
            let depth = |x: P| {
                let d: P = std::array::from_fn(|i| x[i] - m[i]);
                let q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - r2;
                let h = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
                if s.abs() > 1.0 {
                    q / s.abs() - 2.0 * s.signum() * h
                } else {
                    q - 2.0 * s * h
                }
            };
            let centre: P = std::array::from_fn(|i| m[i] + s * n[i]);
            let radius = nlen * (iv.r_over_n * iv.r_over_n + s * s).sqrt() * (1.0 + 1e-9);
            let finite = radius.is_finite() && centre.iter().all(|x| x.is_finite());
            let all = !finite
                || (0..3).all(|i| centre[i] - radius <= plo[i] && centre[i] + radius >= phi[i]);
            let (lo, hi): (P, P) = if all {
                (plo, phi)
            } else {
                (
                    std::array::from_fn(|i| centre[i] - radius),
                    std::array::from_fn(|i| centre[i] + radius),
                )
            };
            let g = self.point_grid_for(lo, hi);
            if !g.is_single_level() {
                // (points are never wide boxes; kept for safety) every point, in index order
                return scan(iv, &mut (0..pts.len() as u32));
            }
            cells.clear();
            let (origin, cell) = (g.origin(), g.cell());
            g.for_cells(lo, hi, |k, ids| {
                let mid = std::array::from_fn(|i| origin[i] + (k[i] as f64 + 0.5) * cell);
                cells.push((depth(mid), ids));
            });
            cells.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
            let r2s = radius * radius;
            let inside = |z: &u32| {
                all || {
                    let x = pts[*z as usize];
                    (0..3).map(|i| (x[i] - centre[i]).powi(2)).sum::<f64>() <= r2s
                }
            };
            scan(
                iv,
                &mut cells
                    .iter()
                    .flat_map(|e| e.1.iter().copied())
                    .filter(inside),
            )
        };
        if scan_ball(&mut iv, 0.0) {
            return Some(ub_of(&iv));
        }
        let mut scanned = 0.0; // B(0) = B(m, r)
                               // s moves only when a point of B(s) changed the interval, i.e. became a binding point
                               // strictly better than the last one on its side (exact): at most 2n + 2 moves. The cap
                               // makes that explicit; beyond it (never reached) every point decides.
        let mut moves = 0usize;
        loop {
            if ub_of(&iv) < 0.0 {
                return None; // the gap regime with B(m, r) added: c₁′ ≥ c is final
            }
            moves += 1;
            if moves > 2 * pts.len() + 4 {
                let all = scan(&mut iv, &mut (0..pts.len() as u32));
                return all.then(|| ub_of(&iv));
            }
            let Some(s) = iv.witness_offset(c) else {
                // only half-spaces can be empty (`finite_blocked`): every point decides
                return if scan(&mut iv, &mut (0..pts.len() as u32)) {
                    Some(ub_of(&iv))
                } else {
                    None
                };
            };
            if s == scanned {
                return None;
            }
            if scan_ball(&mut iv, s) {
                return Some(ub_of(&iv));
            }
            scanned = s;
        }
    }

    /// Adds the given triangles where they are certified inside (as for the rewiring; see
    /// the module documentation) and pushes the boundary faces on their edges; returns how
    /// many were added.
    ///
    /// The same as [`Self::try_insert`] one after the other, in order: adding a triangle
    /// changes the live triangles but not the boundary, so the boundary conditions
    /// ([`Self::insertable_at_boundary`]) are decided for all triangles first, in parallel —
    /// unless a triangle comes back that was a boundary face (its flag would count again):
    /// from then on one by one. The boundary faces on the new triangles' edges are then
    /// evaluated (in parallel without keep triangles) and pushed or locked again.
    pub fn augment(&mut self, tris: &[[u32; 3]]) -> usize {
        use rayon::prelude::*;
        let this = &*self;
        let at_boundary: Vec<bool> = tris
            .par_iter()
            .map(|&t| this.insertable_at_boundary(t))
            .collect();
        let mut one_by_one = false;
        let mut added = 0;
        let mut faces = Vec::new();
        // No change stamps for the added triangles: a live triangle enters the removability
        // of exactly the boundary faces on its edges (as a candidate tetrahedron's face, all
        // of which contain an edge of the face), and those are evaluated and locked again
        // below — other locked faces stay valid.
        let track = std::mem::replace(&mut self.track, false);
        for (&t, ok) in tris.iter().zip(at_boundary) {
            let inserted = if one_by_one {
                self.try_insert(t)
            } else if ok && !self.has(t[0], t[1], t[2]) {
                one_by_one = self
                    .id
                    .get(&sorted3(t))
                    .is_some_and(|&i| self.bflag[i as usize]);
                self.add_tri(t)
            } else {
                false
            };
            if inserted {
                added += 1;
                // the boundary faces on its edges may have gained a tetrahedron
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    for (x, y) in [(a, b), (b, a)] {
                        if let Some(&z) = self.bnext.get(&dk(x, y)) {
                            faces.push([x, y, z]);
                        }
                    }
                }
            }
        }
        self.track = track;
        self.added += added;
        if self.keep.is_empty() && !self.sequential_sweeps {
            // without keep triangles an evaluation changes nothing: all in parallel, then the
            // verdicts in order (as one after the other)
            let this = &*self;
            let verdicts: Vec<Result<(f64, u32), (P, P)>> = faces
                .par_iter()
                .map_init(Vec::new, |buf, &f| {
                    this.best_plain(f, buf).ok_or_else(|| this.lock_box(f))
                })
                .collect();
            let e = self.epoch;
            for (f, v) in faces.into_iter().zip(verdicts) {
                match v {
                    Ok((key, l)) => {
                        self.heap.push(Entry { key, item: (f, l) });
                        self.locked_at.remove(&f);
                    }
                    Err((lo, hi)) => {
                        if track {
                            self.locked_at.insert(f, (e, lo, hi));
                        }
                    }
                }
            }
            return added;
        }
        for f in faces {
            let e = self.epoch;
            if self.push(f) {
                self.locked_at.remove(&f);
            } else if track {
                let (lo, hi) = self.lock_box(f);
                self.locked_at.insert(f, (e, lo, hi));
            }
        }
        added
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

    /// The bulk construction (`build`) gives exactly the tables of adding the triangles one
    /// by one as the engine does later (`add_tri_grid`, `set_boundary`): same ids, edge lists
    /// in the same order, same grid cells (coarse levels included) — on a dense sphere with a
    /// few far points (big triangles on coarse levels), with repeated and degenerate triangles
    /// among the live ones.
    #[test]
    fn bulk_construction_equals_one_by_one() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        let mut pts: Vec<crate::geom::Point3> = (0..12000)
            .map(|_| {
                let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
                let s = 1.0 + rng.gen_range(0.0..0.01);
                crate::geom::Point3::new(v[0] / r * s, v[1] / r * s, v[2] / r * s)
            })
            .collect();
        for k in 0..4 {
            let f = 40.0 * (k as f64 + 1.0);
            pts.push(crate::geom::Point3::new(f, -f / 2.0, f / 3.0));
        }
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let st =
            crate::boundary::constrict3::constrict_3d(&d, crate::boundary::constrict3::Until::All);
        let mut live = crate::graphs::fast::candidates_3d(&d).triangles;
        live.extend_from_slice(&st.triangles[..50]);
        live.push([3, 3, 7]);
        live.push(live[10]);
        let keep = vec![live[20]];
        let mut bulk = General3::blank(&pos, &st.triangles, &live, &keep);
        bulk.build(&st.triangles, &live, &keep);
        let mut one = General3::blank(&pos, &st.triangles, &live, &keep);
        for (v, &q) in pos.iter().enumerate() {
            one.vgrid.insert(v as u32, q, q);
        }
        for &t in &st.triangles {
            one.add_tri_grid(t, false);
        }
        for &t in live.iter().chain(&keep) {
            one.add_tri(t);
        }
        for &f in &st.triangles {
            one.set_boundary(f, true);
        }
        assert!(
            !bulk.tgrid.is_single_level(),
            "no big triangles in the test"
        );
        assert_eq!(bulk.tris, one.tris);
        assert_eq!(bulk.live, one.live);
        assert_eq!(bulk.bflag, one.bflag);
        assert_eq!(bulk.in_bgrid, one.in_bgrid);
        assert_eq!(bulk.tbox, one.tbox);
        assert_eq!(bulk.id, one.id);
        assert_eq!(bulk.eadj, one.eadj);
        assert_eq!(bulk.bnext, one.bnext);
        assert_eq!(bulk.vcount, one.vcount);
        assert_eq!(bulk.boundary_vertices, one.boundary_vertices);
        assert_eq!(bulk.tgrid, one.tgrid);
        assert_eq!(bulk.bgrid, one.bgrid);
        assert_eq!(bulk.vgrid, one.vgrid);
        // the cells of the point grid chosen for a box (the coarse one for wide boxes) hold
        // every point inside the box, each once
        let mut wide = 0;
        for k in 0..200 {
            let c: P = pos[k * 7 % pos.len()];
            let h = if k % 2 == 0 {
                0.005 * k as f64
            } else {
                0.6 + 0.004 * k as f64
            };
            let (lo, hi) = (c.map(|x| x - h), c.map(|x| x + h));
            let inside = |z: &u32| (0..3).all(|i| (lo[i]..=hi[i]).contains(&pos[*z as usize][i]));
            let g = bulk.point_grid_for(lo, hi);
            wide += usize::from(std::ptr::eq(g, &bulk.vcoarse));
            assert!(g.is_single_level());
            let mut a = Vec::new();
            g.for_cells(lo, hi, |_, ids| {
                a.extend(ids.iter().copied().filter(inside))
            });
            let b: Vec<u32> = (0..pos.len() as u32).filter(inside).collect();
            a.sort_unstable();
            assert_eq!(a, b, "box {lo:?} {hi:?}");
        }
        assert!(wide > 50, "{wide}");
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

    /// local_gamma with k ≥ n tries every triangle at a vertex off the boundary: its results
    /// over decreasing c must be exactly the triangles of γ([-1,1],[c,1]) there (Def. 3.1 by
    /// the full center interval over all points), without the live ones.
    #[test]
    fn local_gamma_matches_the_full_definition() {
        use crate::graphs::gamma::center_interval_3d;
        for seed in 0..4u64 {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let n = 24;
            let pts: Vec<crate::geom::Point3> = (0..n)
                .map(|i| {
                    if seed == 3 && i % 4 == 0 {
                        // far points: they decide for balls far beyond the diametral ones
                        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                        let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                        crate::geom::Point3::new(4.0 * v[0] / r, 4.0 * v[1] / r, 4.0 * v[2] / r)
                    } else if i % 2 == 0 || seed == 2 {
                        // on a sphere (rounded), and inside
                        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                        let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                        let s = if i % 4 == 0 { 1.0 } else { 0.6 };
                        crate::geom::Point3::new(v[0] / r * s, v[1] / r * s, v[2] / r * s)
                    } else {
                        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-0.5..0.5));
                        crate::geom::Point3::new(v[0], v[1], v[2])
                    }
                })
                .collect();
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let nv = pos.len();
            let mut g = General3::new(&pos, &d.hull, &[], &[]);
            let locked: Vec<u32> = (0..nv as u32).filter(|&v| !g.on_boundary(v)).collect();
            assert!(locked.len() >= 5, "{}", locked.len());
            let mut found: std::collections::BTreeSet<[u32; 3]> = Default::default();
            for c in [-0.1, -0.3, -0.5, -0.7, -0.9, -1.0] {
                for t in g.local_gamma(c, nv) {
                    assert!(found.insert(t), "returned twice: {t:?}");
                }
                let mut expect: std::collections::BTreeSet<[u32; 3]> = Default::default();
                for a in 0..nv as u32 {
                    for b in a + 1..nv as u32 {
                        for e in b + 1..nv as u32 {
                            let t = [a, b, e];
                            if !t.iter().any(|v| locked.contains(v)) || g.has(a, b, e) {
                                continue;
                            }
                            let Some(iv) =
                                center_interval_3d(&pos, a as usize, b as usize, e as usize)
                            else {
                                continue;
                            };
                            if iv.gamma_values().is_some_and(|v| v.1 >= c) {
                                expect.insert(t);
                            }
                        }
                    }
                }
                let missing: Vec<_> = expect.difference(&found).collect();
                let extra: Vec<_> = found.difference(&expect).collect();
                for t in missing.iter().chain(&extra) {
                    let iv = center_interval_3d(&pos, t[0] as usize, t[1] as usize, t[2] as usize);
                    eprintln!("{t:?}: {:?}", iv.and_then(|iv| iv.gamma_values()));
                }
                assert!(
                    missing.is_empty() && extra.is_empty(),
                    "seed {seed}, c {c}: missing {missing:?}, extra {extra:?}"
                );
            }
        }
    }

    /// n points on a bumpy ellipsoid (radius 1 ± 0.15 waves, ±0.01 noise, z stretched by 1.3).
    fn bumpy_sphere(n: usize, seed: u64) -> Vec<crate::geom::Point3> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                let s = 1.0
                    + 0.15 * (5.0 * v[0] / n).sin() * (4.0 * v[1] / n).cos()
                    + rng.gen_range(-0.01..0.01);
                crate::geom::Point3::new(v[0] / n * s, v[1] / n * s, 1.3 * v[2] / n * s)
            })
            .collect()
    }

    /// gamma_decide on a dense bumpy sphere (3000 points, grid cells far smaller than the
    /// set): for triangles among the 16 nearest vertices of many vertices, at several c, it
    /// accepts exactly the triangles whose c₁′ over *all* points (the full center interval)
    /// is ≥ c, and a rejection's bound is ≥ that c₁′. Includes triangles whose largest empty
    /// balls reach far beyond the balls of parameter c (a far point inside them opens the gap
    /// that rejects them), which a scan bounded by those balls gets wrong.
    #[test]
    fn gamma_decide_matches_the_full_center_interval() {
        use crate::graphs::gamma::center_interval_3d;
        let pts = bumpy_sphere(3000, 9);
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let g = General3::new(&pos, &d.hull, &[], &[]);
        let (mut accepted, mut rejected, mut far_gap) = (0, 0, 0);
        for l in (0..pos.len() as u32).step_by(97) {
            let near = g.nearest(l, 16).0;
            for (i, &x) in near.iter().enumerate() {
                for &y in &near[i + 1..] {
                    let t = sorted3([l, x, y]);
                    let Some(full) =
                        center_interval_3d(&pos, t[0] as usize, t[1] as usize, t[2] as usize)
                    else {
                        continue;
                    };
                    let c1 = full.gamma_values().map_or(f64::NEG_INFINITY, |v| v.1);
                    for c in [-0.1, -0.3, -0.6, -0.9] {
                        match g.gamma_decide(t, c, &near) {
                            None => {
                                assert!(c1 >= c, "{t:?} c {c}: accepted, c1' = {c1}");
                                accepted += 1;
                            }
                            Some(ub) => {
                                assert!(c1 < c && ub >= c1, "{t:?} c {c}: {ub} vs c1' {c1}");
                                rejected += 1;
                                // a gap on one side beyond the balls of parameter c
                                far_gap +=
                                    usize::from(full.lo > full.hi && full.lo * full.hi > 0.0);
                            }
                        }
                    }
                }
            }
        }
        assert!(
            accepted > 500 && rejected > 500 && far_gap > 100,
            "{accepted} {rejected} {far_gap}"
        );
    }

    /// augment (boundary conditions decided in parallel first) adds exactly the triangles that
    /// try_insert one after the other adds, in the same order: same ids, live flags and edge
    /// lists — with repeated triangles, boundary faces and degenerate ones among them.
    #[test]
    fn augment_equals_inserting_one_by_one() {
        let pts = bumpy_sphere(1500, 4);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let mut a = General3::new(&pos, &d.hull, &[], &[]);
        let mut b = General3::new(&pos, &d.hull, &[], &[]);
        let mut extra = a.local_gamma(-0.6, 16);
        extra.extend(b.local_gamma(-0.6, 16).into_iter().take(40));
        extra.extend(d.hull.iter().take(30).map(|&f| sorted3(f)));
        extra.push([5, 5, 9]);
        // triples of hull vertices: outside the region unless along an inward hull edge
        let hv: Vec<u32> = d.hull.iter().flatten().copied().collect();
        for _ in 0..200 {
            let t = [0; 3].map(|_: u32| hv[rng.gen_range(0..hv.len())]);
            extra.push(t);
        }
        let added = a.augment(&extra);
        let mut one = 0;
        for &t in &extra {
            one += usize::from(b.try_insert(t));
        }
        assert_eq!(added, one);
        let fails = extra
            .iter()
            .filter(|&&t| !b.insertable_at_boundary(t))
            .count();
        assert!(
            added > 100 && fails > 100,
            "{added} of {}, {fails}",
            extra.len()
        );
        assert_eq!(a.tris, b.tris);
        assert_eq!(a.live, b.live);
        assert_eq!(a.eadj, b.eadj);
    }

    /// hits_boundary (grid, plane culling, early exit) against all boundary faces tested
    /// exactly one by one.
    /// Skipping the locked faces whose surroundings did not change gives exactly the
    /// constriction of the full sweep (same surface, same number of removals), through
    /// several sweeps, augmentations and c steps; every skipped face, evaluated anyway, has no
    /// removable tetrahedron; and it does skip. The sweeps' parallel evaluation (no keep
    /// triangles) equals the evaluation one face after the other.
    #[test]
    fn sweeps_that_skip_unchanged_faces_constrict_identically() {
        let mut skipped = 0;
        // clustered cube points on which the Delaunay constriction locks (seeds of the
        // integration test `locked_delaunay_constriction_falls_back_and_stays_valid`), plus
        // more clustered sets
        for seed in [1647u64, 1755, 1, 2, 3, 4] {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let n = rng.gen_range(40..600);
            let pts: Vec<crate::geom::Point3> = (0..n)
                .map(|_| {
                    let x: f64 = rng.gen_range(-1.0..1.0);
                    let y: f64 = rng.gen_range(-1.0..1.0);
                    let z: f64 = rng.gen_range(-1.0..1.0);
                    crate::geom::Point3::new(x.powi(3), y.powi(3), z.powi(3))
                })
                .collect();
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let st =
                super::super::constrict3::constrict_3d(&d, super::super::constrict3::Until::All);
            let mut live: Vec<[u32; 3]> = Vec::new();
            for (t, tet) in d.tets.iter().enumerate() {
                if st.alive[t] {
                    for (a, b, c) in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)] {
                        live.push(sorted3([tet[a], tet[b], tet[c]]));
                    }
                }
            }
            live.sort_unstable();
            live.dedup();
            // reference: no skipping, faces one after the other; against it: skipping (each
            // skipped face verified), faces evaluated in parallel — from the first sweep on
            let go = |fast: bool| {
                let mut g = General3::blank(&pos, &st.triangles, &live, &[]);
                g.build(&st.triangles, &live, &[]);
                g.track = true;
                g.skip_unchanged = fast;
                g.verify_skips = fast;
                g.sequential_sweeps = !fast;
                g.push_all();
                g.run();
                let mut trace = vec![(g.iterations, g.boundary_vertices)];
                for step in 1..=10 {
                    if g.done() {
                        break;
                    }
                    let x = g.local_gamma(-(step as f64) / 10.0, 16);
                    g.augment(&x);
                    g.run();
                    trace.push((g.iterations, g.boundary_vertices));
                }
                (g.boundary(), trace, g.skipped)
            };
            let (b1, t1, _) = go(false);
            let (b2, t2, sk) = go(true);
            assert_eq!(t1, t2, "seed {seed}");
            assert_eq!(b1, b2, "seed {seed}");
            skipped += sk;
        }
        assert!(skipped > 500, "{skipped}");
    }

    /// Every mutation primitive (kill, add, boundary flag) stamps its box: a box meeting the
    /// mutated triangle sees the change, a far box does not, and nothing is stamped during
    /// construction.
    #[test]
    fn mutations_stamp_the_cells_they_touch() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let pts: Vec<crate::geom::Point3> = (0..300)
            .map(|_| {
                let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                crate::geom::Point3::new(v[0], v[1], v[2])
            })
            .collect();
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let all = crate::graphs::fast::candidates_3d(&d).triangles;
        let mut g = General3::new(&pos, &d.hull, &all, &[]);
        assert!(g.changed.is_empty() && g.changed_all == 0);
        let shift = 50.0 * g.bgrid.cell() + 10.0;
        let far = |b: (P, P)| -> (P, P) { (b.0.map(|x| x + shift), b.1.map(|x| x + shift)) };
        for round in 0..60 {
            let e = g.epoch;
            let i = rng.gen_range(0..g.tris.len());
            let t = g.tris[i];
            let b = g.tbox[i];
            match round % 3 {
                0 if g.live[i] => g.kill(i as u32),
                1 if !g.live[i] => assert!(g.add_tri(t)),
                _ => g.set_boundary(t, !g.bflag[i]),
            }
            assert!(g.epoch > e, "round {round}: a mutation without a stamp");
            assert!(g.changed_since(e, b.0, b.1), "round {round}");
            let (flo, fhi) = far(b);
            assert!(!g.changed_since(e, flo, fhi), "round {round}");
            assert!(!g.changed_since(g.epoch, b.0, b.1));
        }
        assert!(g.epoch >= 30, "{}", g.epoch);
    }

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
                    && !super::super::validity3::self_intersections_brute(&pos, &[t, u]).is_empty()
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

//! The general 3D constriction engine [`General3`] (Veltkamp 1992, §5.4 last paragraphs: 3D
//! γ(\[-1,1\],\[c,1\]) with c < 0 by adaptive augmentation; §5.3 removability; §5.5 heap; §5.7
//! constraints): the fallback of the Delaunay constriction ([`super::constrict`]) when it locks.
//! This file holds the engine's state, its bulk construction and its mutation primitives;
//! removals are in [`super::removal`], augmentation in [`super::augment`], constraints in
//! [`super::keep`]. (About 770 lines: the tables, their construction and the tests that the
//! bulk construction and the change stamps equal the one-by-one mutations belong together.)
//!
//! # State
//! A set of live triangles (the pruned graph; tetrahedra are implicit: four live triangles on
//! four vertices) and a closed boundary surface made of live triangles, oriented outward
//! (`bface`, with a directed-edge map). Invariant: every live triangle lies in the closed region
//! bounded by the surface, and every vertex lies in it (no vertex is ever cut off).
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
//! # Complexity
//! Removal: O(k log n) with k the live triangles and vertices near Q (uniform grids over
//! bounding boxes, cell twice the median edge length; boundary faces and the other live
//! triangles in separate grids, [`super::trigrid::TriGrid`]: the triangles of
//! [`General3::new`] in one flat array built by a counting sort, later ones in a hash grid;
//! triangles spanning more than 512 cells on coarser levels or in a list tested always). The
//! crossing search and the boundary-hit test use box hierarchies instead
//! ([`super::crosstree::BoxIndex`]: per size class, dead ids skipped), whose cost follows the
//! boxes that meet the query rather than the cells (the grid's cell follows the long
//! triangles: on the fandisk it is half the object). Boundary tests stop at the first hit and skip boxes that a conservative
//! floating-point bound puts off the triangle's plane. The sweep of `run` visits only the
//! boundary faces next to a live non-boundary triangle (the only ones that can carry a
//! removable tetrahedron), so a caller may pass only the live triangles near the locked
//! vertices (as [`super::boundary_3d`] does) and pay for the boundary only once, in
//! [`General3::new`] — and there only for its boxes: the hash maps receive the initial
//! boundary faces at the vertices of the given triangles, the others when a mutation first
//! touches a corner of theirs ([`General3::build_lazy`]). That list of faces is kept up to
//! date from the edges the mutations changed (`General3::sweep_faces`), not rebuilt from every
//! live triangle at each sweep.
//! The grid of [`General3::crossing`] leaves out the triangles lying in a supporting plane
//! of the points ([`super::support`]; they never meet the open tetrahedron of a removal): the
//! Θ(g³) empty triangles of each coplanar hull facet of g points, which on CAD models such as
//! the fandisk are most of all triangles and, being long, met the box of every tetrahedron
//! (issue 17 item 8: each removal examined T/4–T/2 of all triangles).
//! Worst case O(T²) for T triangles.
//!
//! Preconditions: the initial surface is a closed genus-0 2-manifold enclosing every vertex and
//! every given triangle (as produced by [`super::constrict`] or the convex hull).

use super::crosstree::BoxIndex;
use super::support::Support;
use super::trigrid::TriGrid;
use crate::boundary::indicator::MinKey;
use crate::geom::grid::BoxGrid;
use crate::geom::vec::{cross, dist, dot, norm, sub};
use crate::util::{sorted3, IdMap, IdSet};
use std::collections::BinaryHeap;

/// How far below c a rejected triangle's γ-scan goes on ([`General3::gamma_decide`]): the
/// cached upper bound of c₁′ then also rejects it for c − 0.1, … (the steps of the caller's
/// schedule), instead of rescanning it at every step.
pub(super) const UB_LOOKAHEAD: f64 = 0.25;

/// What [`General3::gamma_decide`] adds to a floating-point c₁′ to make it a proven upper bound:
/// the offsets it comes from are certified to a relative 1e-10 of |τ| + r/|n|
/// (`graphs::gamma::TAU_TOL`), which moves |c| by less than 1e-10, and the conversion rounds a
/// few ε.
pub(super) const UB_MARGIN: f64 = 1e-8;

/// The lowest bound of c₁′ worth scanning for: the schedule's smallest c above −1 (c = −1 is
/// decided by the closed triangle alone and never consults a cached bound, and c₁′ ≥ −1
/// always). Without it the look-ahead of the rounds c ≤ −0.8 (c − 0.25 < −1) could never stop
/// a rejected scan early. The decisions do not depend on it, only how much is rescanned.
pub(super) const UB_FLOOR: f64 = -0.9;

/// Heap entries: smallest key first, ties by the smallest item.
pub(super) type Entry = MinKey<([u32; 3], u32)>;

pub(super) type P = [f64; 3];

/// The rotation of an oriented face that starts at its smallest vertex.
pub(super) fn sorted_rot(f: [u32; 3]) -> [u32; 3] {
    if f[0] < f[1] && f[0] < f[2] {
        f
    } else if f[1] < f[2] {
        [f[1], f[2], f[0]]
    } else {
        [f[2], f[0], f[1]]
    }
}

pub(super) fn ek(a: u32, b: u32) -> u64 {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    ((a as u64) << 32) | b as u64
}

pub(super) fn dk(a: u32, b: u32) -> u64 {
    ((a as u64) << 32) | b as u64
}

/// The four outward faces of tetrahedron (a, b, c, d) when (a, b, c) is outward (d on the inner
/// side), each with its opposite vertex.
pub(super) fn tet_faces(a: u32, b: u32, c: u32, d: u32) -> [([u32; 3], u32); 4] {
    [
        ([a, b, c], d),
        ([b, a, d], c),
        ([c, b, d], a),
        ([a, c, d], b),
    ]
}

pub(super) fn circumradius(a: P, b: P, c: P, d: P) -> f64 {
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

/// log₂ of the edge, in cells of `bgrid`, of the blocks whose latest change stamp
/// [`General3::changed_since`] consults before the cells (blocks of 4³ cells).
const CHANGE_BLOCK_SHIFT: u32 = 2;

/// The block (of 4³ cells, [`CHANGE_BLOCK_SHIFT`]) holding cell coordinate `c`, per axis
/// (floor division: an arithmetic shift, also below zero).
fn block_of(c: i64) -> i64 {
    c >> CHANGE_BLOCK_SHIFT
}

/// The kernel's box grid in 3D (boxes of triangles, points as zero-size boxes).
pub(super) type Grid = BoxGrid<3>;

pub(super) fn bbox(ps: &[P]) -> (P, P) {
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

pub(super) fn boxes_meet(a: (P, P), b: (P, P)) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

/// The third vertices of the live triangles on an edge (most edges have a handful: stored
/// inline, without an allocation each).
pub(super) type Thirds = smallvec::SmallVec<[u32; 4]>;

/// Up to four faces of a tetrahedron (inline, no allocation).
pub(super) type Faces = smallvec::SmallVec<[[u32; 3]; 4]>;

/// The table behind the sweep's face list (see `General3::sweep_src`): directed edge → face
/// it names, and face → how many directed edges name it.
pub(super) type SweepSrc = (IdMap<u64, [u32; 3]>, IdMap<[u32; 3], u32>);

/// A removal: key, boundary faces of the tetrahedron, its new boundary faces.
pub(super) type Removal = (f64, Faces, Faces);

/// The boundary faces whose coplanar groups propose the supporting planes of [`General3::new`]
/// ([`Support::new`]): those with all three corners among the corners of the live and keep
/// triangles given to it (`tris`, `keep`); the whole `boundary` (borrowed, same order) when
/// that is every face, as on the paths that start from the hull or from the whole object.
///
/// Why any subset changes no result (only how many triangles [`General3::crossing`]
/// examines): a plane enters [`Support`] only after it was checked against **every** point,
/// so every plane proposed by a subset is a supporting plane of the whole set, and a triangle
/// in it never meets the open tetrahedron of a removal (the argument of [`super::support`]);
/// a triangle that a plane of the whole boundary would have left out of the crossing grid and
/// a subset's does not is in the grid and is found not to cross, as before. What the subset
/// saves: after a locked Delaunay constriction of 437 645 dragon points the local engine
/// starts from 875 k boundary faces and 230 k live triangles near 1 092 locked vertices, and
/// the planes' directed-edge map and coplanarity tests over the whole boundary were the
/// largest single part of the engine's construction (≈ 29 % of it, measured). A triangle
/// added later with a corner outside the marked set is in no group of the subset, so it goes
/// into the crossing grid and is tested (as any triangle off a supporting plane). O(B + T).
pub(super) fn support_faces<'b>(
    n: usize,
    boundary: &'b [[u32; 3]],
    tris: &[[u32; 3]],
    keep: &[[u32; 3]],
) -> std::borrow::Cow<'b, [[u32; 3]]> {
    let mut mark = vec![false; n];
    for t in tris.iter().chain(keep) {
        for &v in t {
            if let Some(m) = mark.get_mut(v as usize) {
                *m = true;
            }
        }
    }
    let inside = |f: &[u32; 3]| f.iter().all(|&v| mark.get(v as usize) == Some(&true));
    if boundary.iter().all(inside) {
        std::borrow::Cow::Borrowed(boundary)
    } else {
        std::borrow::Cow::Owned(boundary.iter().copied().filter(inside).collect())
    }
}

/// The initial boundary faces of [`General3::build_lazy`] that are not (yet) in the engine's
/// hash maps, read-only: per vertex whether it is still cold (no mutation has touched a
/// triangle at it), and every initial face by vertex. Empty (no vertex cold) after
/// [`General3::build`].
#[derive(Default)]
pub(super) struct Cold {
    /// Per vertex: still cold.
    pub(super) cold: Vec<bool>,
    /// The initial boundary faces as given (oriented outward); face i has id i.
    faces: Vec<[u32; 3]>,
    /// Vertex v's initial faces are `at[start[v]..start[v + 1]]`, ids increasing.
    start: Vec<u32>,
    at: Vec<u32>,
}

impl Cold {
    /// The table of the initial boundary `faces` on `n` vertices, every vertex cold; `None`
    /// when a face is degenerate or out of range, or a face (sorted triple) or a directed edge
    /// appears twice. O(F·d) for F faces and d faces per vertex.
    fn new(n: usize, faces: &[[u32; 3]]) -> Option<Self> {
        if faces.len() >= u32::MAX as usize {
            return None;
        }
        let mut start = vec![0u32; n + 1];
        for f in faces {
            if f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || f.iter().any(|&v| v as usize >= n) {
                return None;
            }
            for &v in f {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut next = start.clone();
        let mut at = vec![0u32; 3 * faces.len()];
        // beside each entry of `at` (face g at vertex v): the corners after v in g, and
        // whether v is g's first corner (for the check below, read in `at`'s order)
        let mut after = vec![[0u32; 2]; 3 * faces.len()];
        let mut first = vec![false; 3 * faces.len()];
        for (i, f) in faces.iter().enumerate() {
            for k in 0..3 {
                let v = f[k] as usize;
                let e = next[v] as usize;
                at[e] = i as u32;
                after[e] = [f[(k + 1) % 3], f[(k + 2) % 3]];
                first[e] = k == 0;
                next[v] += 1;
            }
        }
        // each directed edge and each sorted triple once (looked up at the first corner): for
        // face f = v w u at its first corner v, another face g at v with the directed edge
        // v→w (g's corner after v is w) or with the same corners (then g = v u w, the other
        // one is already the directed edge) — the entries of v side by side, not the faces
        // (the check that read `faces[g]` for every g at v missed the cache once per entry)
        for v in 0..n {
            let (lo, hi) = (start[v] as usize, start[v + 1] as usize);
            for e in lo..hi {
                if !first[e] {
                    continue;
                }
                let [w, u] = after[e];
                let twice = (lo..hi).any(|x| {
                    x != e && (after[x][0] == w || (after[x][0] == u && after[x][1] == w))
                });
                if twice {
                    return None;
                }
            }
        }
        let c = Cold {
            cold: vec![true; n],
            faces: faces.to_vec(),
            start,
            at,
        };
        Some(c)
    }

    /// The ids of the initial faces at v (none for a vertex out of range).
    fn at(&self, v: u32) -> &[u32] {
        let v = v as usize;
        if v + 1 >= self.start.len() {
            return &[];
        }
        &self.at[self.start[v] as usize..self.start[v + 1] as usize]
    }

    /// Every vertex of `vs` is cold (false when the table is empty).
    pub(super) fn all_cold(&self, vs: &[u32]) -> bool {
        vs.iter()
            .all(|&v| self.cold.get(v as usize).copied().unwrap_or(false))
    }

    /// The third vertex of the initial face with the directed edge a→b.
    fn directed(&self, a: u32, b: u32) -> Option<u32> {
        self.at(a).iter().find_map(|&i| {
            let f = self.faces[i as usize];
            (0..3)
                .find(|&k| f[k] == a && f[(k + 1) % 3] == b)
                .map(|k| f[(k + 2) % 3])
        })
    }

    /// The id of the initial face with the sorted corners s.
    fn find(&self, s: [u32; 3]) -> Option<u32> {
        self.at(s[0])
            .iter()
            .copied()
            .find(|&i| sorted3(self.faces[i as usize]) == s)
    }
}

/// The general 3D constriction (see the module documentation). Vertex indices are indices into
/// the point array given to [`General3::new`].
pub struct General3<'a> {
    pub(super) p: &'a [P],
    pub(super) tris: Vec<[u32; 3]>,
    pub(super) live: Vec<bool>,
    /// The triangle is a boundary face (in either orientation).
    pub(super) bflag: Vec<bool>,
    /// Bounding box of every triangle.
    pub(super) tbox: Vec<(P, P)>,
    pub(super) id: IdMap<[u32; 3], u32>,
    pub(super) eadj: IdMap<u64, Thirds>,
    /// directed boundary edge a→b → third vertex of the outward boundary face containing it
    pub(super) bnext: IdMap<u64, u32>,
    pub(super) vcount: Vec<u32>,
    pub(super) keep: IdSet<[u32; 3]>,
    /// Live triangles that were not boundary faces when added (for [`Self::crossing`]), but
    /// for those in a supporting plane of the points (`support`), which never cross.
    pub(super) tgrid: BoxIndex,
    /// The supporting planes proposed by the initial boundary faces among the corners of the
    /// initial live triangles ([`support_faces`], [`super::support`]).
    pub(super) support: Support,
    /// Triangles the grid of [`Self::crossing`] handed over (work counter for the tests).
    pub(super) crossing_examined: usize,
    /// Triangles that have been boundary faces (for [`Self::hits_boundary`]; `bflag` tells
    /// which still are).
    pub(super) bgrid: TriGrid,
    pub(super) in_bgrid: Vec<bool>,
    /// The ids of `bgrid` again, alive exactly while a live boundary face (`live` and
    /// `bflag`), for [`Self::hits_boundary`] ([`super::crosstree`]: its cost follows the
    /// boxes that meet the query, not the dead faces and the coarse cells).
    pub(super) bfaces: BoxIndex,
    pub(super) vgrid: Grid,
    /// The bounding box of the points.
    pub(super) pbox: (P, P),
    /// The points again in cells 8× wider, for walks over wide boxes
    /// ([`General3::point_grid_for`]).
    pub(super) vcoarse: Grid,
    pub(super) heap: BinaryHeap<Entry>,
    pub(super) buf: Vec<u32>,
    pub(super) blocked_by: Option<[u32; 3]>,
    /// Triangles found in a γ-graph by [`General3::local_gamma`] (not tested again).
    pub(super) in_gamma: IdSet<[u32; 3]>,
    /// Upper bounds of c₁′ of triangles rejected by [`General3::local_gamma`] (from a subset
    /// of the points: more points only lower it), so that a smaller c skips them when the
    /// bound is already below it.
    pub(super) gamma_ub: IdMap<[u32; 3], f64>,
    /// The nearest vertices of a vertex and the box half-width that certified them
    /// ([`General3::local_gamma`]).
    pub(super) near_cache: IdMap<u32, (Vec<u32>, f64)>,
    /// Change tracking for [`General3::push_all`] (on after construction): every mutation of a
    /// live triangle or of the boundary stamps the cells of its box (cells of `bgrid`) with a
    /// new epoch (except the additions of [`General3::augment`], which re-evaluates the faces
    /// they concern); `changed_all` is the epoch of a change too wide to stamp.
    pub(super) track: bool,
    pub(super) epoch: u64,
    pub(super) changed: IdMap<(i64, i64, i64), u64>,
    /// The latest epoch stamped in each block of 4³ cells ([`CHANGE_BLOCK_SHIFT`]) of `changed` (the
    /// maximum over its cells: epochs only grow), so that [`General3::changed_since`] can
    /// answer "no" from the few blocks of a box instead of every cell.
    pub(super) changed_blocks: IdMap<(i64, i64, i64), u64>,
    pub(super) changed_all: u64,
    /// Boundary faces found without a removable tetrahedron by a sweep, with the epoch and the
    /// box of everything their removability depends on (see [`General3::push_all`]).
    pub(super) locked_at: IdMap<[u32; 3], (u64, P, P)>,
    /// Sweeps skip unchanged locked faces (switchable for the equivalence test).
    pub(super) skip_unchanged: bool,
    /// Faces skipped so (for the tests).
    pub(super) skipped: usize,
    /// Tests: evaluate the faces of a sweep or of an augmentation one after the other even
    /// without keep triangles.
    pub(super) sequential_sweeps: bool,
    /// Tests: evaluate every skipped face anyway and panic if it has a removable tetrahedron.
    pub(super) verify_skips: bool,
    /// [`General3::best_plain`] drops the apexes l of a face abc for which bcl or acl is not
    /// live by the lists of `eadj` ([`General3::live_thirds`]) before
    /// [`General3::combinatorial`]'s lookups (switchable: off is the reference of the
    /// equivalence test).
    pub(super) filter_thirds: bool,
    /// The sweep's face list ([`General3::sweep_faces`]) kept up to date from `dirty_edges`
    /// instead of rebuilt from every live triangle: every directed boundary edge x→y (key
    /// `dk`) on a live non-boundary triangle with the face it names (x, y, `bnext`(x→y)), and
    /// how many such edges name each face; `None` before the first sweep.
    pub(super) sweep_src: Option<SweepSrc>,
    /// The (undirected) edges of every triangle whose live or boundary state changed since the
    /// last sweep — the only edges on which a boundary face can have entered or left the list.
    pub(super) dirty_edges: Vec<u64>,
    /// Tests: rebuild the sweep's face list from every live triangle each time (the reference
    /// the incremental list is compared with).
    pub(super) rebuild_sweeps: bool,
    /// Tests: compare the incremental face list with a full rebuild at every sweep (panics on
    /// a difference).
    pub(super) verify_sweep_list: bool,
    /// Sweeps whose face list was updated incrementally (for the tests).
    pub(super) incremental_sweeps: usize,
    /// Ids below this are faces of the Delaunay tetrahedralization of the points: the
    /// triangles given to [`General3::new`] when its caller vouches for them
    /// ([`General3::trust_initial_as_delaunay`]; 0 otherwise). The final check trusts such
    /// boundary faces instead of looking every tetrahedron's faces up
    /// ([`General3::boundary_with_delaunay_flags`]).
    pub(super) delaunay_ids: u32,
    /// The initial boundary faces kept out of the hash maps while no corner of theirs is
    /// touched ([`General3::build_lazy`]; empty after [`General3::build`]).
    pub(super) cold: Cold,
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
        g.build_lazy(boundary, tris, keep);
        g.track = true;
        g.push_all();
        g
    }

    /// The engine's tables before anything is added (cell size from the given triangles).
    pub(super) fn blank(
        p: &'a [P],
        boundary: &[[u32; 3]],
        tris: &[[u32; 3]],
        keep: &[[u32; 3]],
    ) -> Self {
        Self::blank_with(p, boundary, tris, keep, true)
    }

    /// [`Self::blank`], with or without leaving the triangles of supporting planes out of the
    /// crossing grid (`cull`).
    pub(super) fn blank_with(
        p: &'a [P],
        boundary: &[[u32; 3]],
        tris: &[[u32; 3]],
        keep: &[[u32; 3]],
        cull: bool,
    ) -> Self {
        let support = if cull {
            Support::new(p, &support_faces(p.len(), boundary, tris, keep))
        } else {
            Support::default()
        };
        Self::blank_with_support(p, boundary, tris, keep, support)
    }

    /// [`Self::blank`] with the given supporting planes (tests: those of the whole boundary,
    /// the construction before [`support_faces`]).
    pub(super) fn blank_with_support(
        p: &'a [P],
        boundary: &[[u32; 3]],
        tris: &[[u32; 3]],
        keep: &[[u32; 3]],
        support: Support,
    ) -> Self {
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
            tgrid: BoxIndex::new(lo),
            support,
            crossing_examined: 0,
            bgrid: TriGrid::new(lo, cell),
            bfaces: BoxIndex::new(lo),
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
            changed_blocks: IdMap::default(),
            changed_all: 0,
            locked_at: IdMap::default(),
            skip_unchanged: true,
            skipped: 0,
            sequential_sweeps: false,
            verify_skips: false,
            filter_thirds: true,
            sweep_src: None,
            dirty_edges: Vec::new(),
            rebuild_sweeps: false,
            verify_sweep_list: false,
            incremental_sweeps: 0,
            delaunay_ids: 0,
            cold: Cold::default(),
            boundary_vertices: 0,
            iterations: 0,
            added: 0,
        }
    }

    /// The initial state of [`General3::new`], in bulk: the same as adding every boundary
    /// face (boundary grid only), then every live triangle, then marking the boundary faces —
    /// ids, edge lists and grid cells in that order — but with every list allocated once and
    /// the independent tables built in parallel.
    pub(super) fn build(&mut self, boundary: &[[u32; 3]], tris: &[[u32; 3]], keep: &[[u32; 3]]) {
        self.build_with(boundary, tris, keep, false);
    }

    /// [`General3::build`], but the hash maps (`id`, `bnext`, `eadj`) receive only what
    /// concerns the vertices of the live and keep triangles (`tris`, `keep`): the initial
    /// boundary faces with none of them among their corners stay in a read-only table
    /// ([`Cold`]) until a mutation touches one of their corners. Every other table (ids,
    /// flags, boxes, grids, vertex counts) is the same as after [`General3::build`].
    ///
    /// What the caller may assume: every query of the engine answers as after
    /// [`General3::build`] (test `lazy_engine_equals_the_eager_one`), because
    /// - a vertex stays *cold* until a mutation (`add_tri_grid`, `kill`, `set_boundary`)
    ///   touches a triangle at it; before its tables change, the mutation *heats* the
    ///   triangle's corners ([`General3::heat`]), which puts every initial boundary face at
    ///   them into `id` and `bnext`, and the third vertices of those faces into `eadj` for
    ///   every edge that had no warm end — in id order, the order of the bulk construction
    ///   (such an edge carries initial boundary faces only: the live and keep triangles given
    ///   here and every triangle added later have warm corners);
    /// - so the maps hold exactly the state of every triangle and directed edge with a warm
    ///   corner, and a triangle (directed edge) whose corners are all cold is untouched: an
    ///   initial boundary face, live, when [`Cold`] lists it, absent otherwise. The
    ///   accessors `has`, `is_bface`, `bedge`, [`General3::bnext_of`], [`General3::id_of`]
    ///   and `boundary` consult [`Cold`] for those; the other readers of the maps
    ///   (`removal.rs`: the sweep, `best_plain`, `lock_box`, `remove`) only read edges of
    ///   faces that share an edge with a live non-boundary triangle or of triangles just
    ///   mutated, whose corners are warm.
    ///
    /// Why it pays: after a locked Delaunay constriction the local engine starts from the
    /// whole surface (875 k faces on the 437 645-point dragon) but works only near the
    /// ≈ 1 100 locked vertices; the maps' entries of the far faces (2.6 M directed edges,
    /// 1.3 M edges, 875 k triangle ids) were a third of the engine's construction.
    /// Falls back to [`General3::build`] when the boundary has a degenerate face, a face
    /// twice or a directed edge twice (not a 2-manifold: the precondition of the engine).
    pub(super) fn build_lazy(
        &mut self,
        boundary: &[[u32; 3]],
        tris: &[[u32; 3]],
        keep: &[[u32; 3]],
    ) {
        let Some(mut cold) = Cold::new(self.p.len(), boundary) else {
            return self.build(boundary, tris, keep);
        };
        for t in tris.iter().chain(keep) {
            for &v in t {
                if let Some(c) = cold.cold.get_mut(v as usize) {
                    *c = false;
                }
            }
        }
        self.cold = cold;
        self.build_with(boundary, tris, keep, true);
    }

    /// [`General3::build`] (`lazy` false) or the construction of [`General3::build_lazy`]
    /// (`lazy`: `self.cold` set, the boundary faces distinct and non-degenerate).
    fn build_with(
        &mut self,
        boundary: &[[u32; 3]],
        tris: &[[u32; 3]],
        keep: &[[u32; 3]],
        lazy: bool,
    ) {
        use rayon::prelude::*;
        // (lazy: only the boundary faces with a warm corner go into the maps)
        let warm_faces = if lazy {
            boundary.iter().filter(|f| !self.cold.all_cold(*f)).count()
        } else {
            boundary.len()
        };
        let nt = boundary.len() + tris.len() + keep.len();
        self.id.reserve(warm_faces + tris.len() + keep.len());
        self.tris.reserve(nt);
        // ids: boundary faces first (not in the grid of live triangles), no repeats
        let mut n_boundary_ids = 0;
        // the id of each boundary face in list order (none for a degenerate one), recorded
        // here instead of looked up again below
        let mut bface_ids: Vec<u32> = Vec::with_capacity(boundary.len());
        for (k, &t) in boundary.iter().chain(tris).chain(keep).enumerate() {
            if k == boundary.len() {
                n_boundary_ids = self.tris.len();
            }
            let s = sorted3(t);
            if s[0] == s[1] || s[1] == s[2] {
                continue;
            }
            if lazy && k < boundary.len() {
                // (distinct faces: the id is the position; in the map only with a warm corner)
                let i = self.tris.len() as u32;
                self.tris.push(s);
                if !self.cold.all_cold(&s) {
                    self.id.insert(s, i);
                }
                bface_ids.push(i);
                continue;
            }
            let i = match self.id.entry(s) {
                std::collections::hash_map::Entry::Vacant(e) => {
                    let i = self.tris.len() as u32;
                    e.insert(i);
                    self.tris.push(s);
                    i
                }
                std::collections::hash_map::Entry::Occupied(e) => *e.get(),
            };
            if k < boundary.len() {
                bface_ids.push(i);
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
        for i in bface_ids {
            self.bflag[i as usize] = true;
            if !self.in_bgrid[i as usize] {
                self.in_bgrid[i as usize] = true;
                bids.push(i);
            }
        }
        // (triangles in a supporting plane stay out of the crossing grid: they never cross)
        let in_tgrid: Vec<bool> = (n_boundary_ids..n)
            .into_par_iter()
            .map(|i| !self.support.holds(p, self.tris[i]))
            .collect();
        let (tl, tbox, cold) = (&self.tris, &self.tbox, &self.cold);
        let (eadj, bnext, vcount, bv, vgrid, vcoarse, tgrid, bgrid, bfaces) = (
            &mut self.eadj,
            &mut self.bnext,
            &mut self.vcount,
            &mut self.boundary_vertices,
            &mut self.vgrid,
            &mut self.vcoarse,
            &mut self.tgrid,
            &mut self.bgrid,
            &mut self.bfaces,
        );
        rayon::join(
            || {
                // edge → third vertices, in id order
                // (lazy: the edges of the initial boundary faces without a warm end stay out)
                let mut e: Vec<(u64, u32, u32)> = tl
                    .par_iter()
                    .enumerate()
                    .flat_map_iter(|(i, s)| {
                        (0..3).filter_map(move |k| {
                            let (a, b, c) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
                            let out = lazy && i < n_boundary_ids && cold.all_cold(&[a, b]);
                            (!out).then_some((ek(a, b), i as u32, c))
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
                                    (n_boundary_ids..n)
                                        .filter(|&i| in_tgrid[i - n_boundary_ids])
                                        .map(|i| (i as u32, tbox[i].0, tbox[i].1)),
                                );
                            },
                            || {
                                bgrid.insert_many(bids.iter().map(|&i| {
                                    let (lo, hi) = tbox[i as usize];
                                    (i, lo, hi)
                                }));
                                // (all live boundary faces)
                                bfaces.insert_many(bids.iter().map(|&i| {
                                    let (lo, hi) = tbox[i as usize];
                                    (i, lo, hi)
                                }));
                            },
                        )
                    },
                    || {
                        // (in bulk: each cell's list allocated once; the same grids as
                        // inserting the points one by one, ids increasing)
                        let pts = || p.iter().enumerate().map(|(v, &q)| (v as u32, q, q));
                        vgrid.insert_many(pts());
                        vcoarse.insert_many(pts());
                        bnext.reserve(3 * warm_faces);
                        for f in boundary {
                            let warm = !lazy || !cold.all_cold(f);
                            for k in 0..3 {
                                let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
                                if warm {
                                    bnext.insert(dk(a, b), c);
                                }
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
    pub(super) fn touched(&mut self, lo: P, hi: P) {
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
        let (ba, bb) = (a.map(block_of), b.map(block_of));
        for x in ba[0]..=bb[0] {
            for y in ba[1]..=bb[1] {
                for z in ba[2]..=bb[2] {
                    self.changed_blocks.insert((x, y, z), self.epoch);
                }
            }
        }
    }

    /// Has anything meeting the box changed after `epoch`? (Whether a cell of the box was
    /// stamped after `epoch`; first asked of the blocks of 4³ cells ([`CHANGE_BLOCK_SHIFT`]) that meet
    /// the box: a block's epoch is the latest of its cells', so when no block of the box is
    /// newer than `epoch`, no cell is — the same answer as the cells alone, test
    /// `block_stamps_answer_as_the_cells`.)
    pub(super) fn changed_since(&self, epoch: u64, lo: P, hi: P) -> bool {
        if self.changed_all > epoch {
            return true;
        }
        let (a, b) = self.bgrid.range(lo, hi);
        let span = Grid::span(a, b);
        if span > Grid::MAX_SPAN {
            return true;
        }
        let (ba, bb) = (a.map(block_of), b.map(block_of));
        let newer = |m: &IdMap<(i64, i64, i64), u64>, c| m.get(&c).is_some_and(|&e| e > epoch);
        let any_block = (ba[0]..=bb[0]).any(|x| {
            (ba[1]..=bb[1]).any(|y| (ba[2]..=bb[2]).any(|z| newer(&self.changed_blocks, (x, y, z))))
        });
        any_block && self.changed_since_cells(epoch, a, b)
    }

    /// Whether a cell of the range `a..=b` was stamped after `epoch` (the cell scan of
    /// [`General3::changed_since`]).
    pub(super) fn changed_since_cells(&self, epoch: u64, a: [i64; 3], b: [i64; 3]) -> bool {
        (a[0]..=b[0]).any(|x| {
            (a[1]..=b[1]).any(|y| {
                (a[2]..=b[2]).any(|z| self.changed.get(&(x, y, z)).is_some_and(|&e| e > epoch))
            })
        })
    }

    /// The point grid to walk for a box: `vgrid`, or `vcoarse` (cells 8× wider) when the box
    /// spans many fine cells (a wide box over a scanned surface has mostly empty cells).
    /// Either holds every point at its own level (points are never wide boxes).
    pub(super) fn point_grid_for(&self, lo: P, hi: P) -> &Grid {
        let (a, b) = self.vgrid.range(lo, hi);
        let span = Grid::span(a, b);
        if span <= 4096 {
            &self.vgrid
        } else {
            &self.vcoarse
        }
    }

    pub(super) fn pt(&self, v: u32) -> P {
        self.p[v as usize]
    }

    pub(super) fn add_tri(&mut self, t: [u32; 3]) -> bool {
        self.add_tri_grid(t, true)
    }

    pub(super) fn add_tri_grid(&mut self, t: [u32; 3], grid: bool) -> bool {
        let s = sorted3(t);
        if s[0] == s[1] || s[1] == s[2] {
            return false;
        }
        self.heat(s);
        if let Some(&i) = self.id.get(&s) {
            if self.live[i as usize] {
                return false;
            }
            self.live[i as usize] = true;
            self.tgrid.set_alive(i, true);
            self.bfaces.set_alive(i, self.bflag[i as usize]);
        } else {
            let i = self.tris.len() as u32;
            self.tris.push(s);
            self.live.push(true);
            self.bflag.push(false);
            self.in_bgrid.push(false);
            self.id.insert(s, i);
            let (lo, hi) = bbox(&s.map(|v| self.pt(v)));
            self.tbox.push((lo, hi));
            if grid && !self.support.holds(self.p, s) {
                self.tgrid.insert(i, lo, hi);
            }
        }
        for k in 0..3 {
            let (a, b, c) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
            self.eadj.entry(ek(a, b)).or_default().push(c);
            self.dirty_edges.push(ek(a, b));
        }
        if self.track {
            let (lo, hi) = self.tbox[self.id[&s] as usize];
            self.touched(lo, hi);
        }
        true
    }

    pub(super) fn kill(&mut self, i: u32) {
        if !self.live[i as usize] {
            return;
        }
        self.heat(self.tris[i as usize]);
        self.live[i as usize] = false;
        self.tgrid.set_alive(i, false);
        self.bfaces.set_alive(i, false);
        let (lo, hi) = self.tbox[i as usize];
        self.touched(lo, hi);
        let s = self.tris[i as usize];
        for k in 0..3 {
            let (a, b, c) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
            if let Some(v) = self.eadj.get_mut(&ek(a, b)) {
                v.retain(|x| *x != c);
            }
            self.dirty_edges.push(ek(a, b));
        }
    }

    /// True when triangle abc is live.
    pub fn has(&self, a: u32, b: u32, c: u32) -> bool {
        self.id_of(sorted3([a, b, c]))
            .is_some_and(|i| self.live[i as usize])
    }

    /// The id of the triangle with the sorted corners `s`, if it has one: the map `id`, or for
    /// corners that are all cold the initial boundary face ([`General3::build_lazy`]).
    pub(super) fn id_of(&self, s: [u32; 3]) -> Option<u32> {
        match self.id.get(&s) {
            Some(&i) => Some(i),
            None if self.cold.all_cold(&s) => self.cold.find(s),
            None => None,
        }
    }

    /// The third vertex of the outward boundary face with the directed edge a→b, if there is
    /// one: the map `bnext`, or for two cold ends the initial boundary face
    /// ([`General3::build_lazy`]: a face with a warm corner is in the map).
    pub(super) fn bnext_of(&self, a: u32, b: u32) -> Option<u32> {
        match self.bnext.get(&dk(a, b)) {
            Some(&c) => Some(c),
            None if self.cold.all_cold(&[a, b]) => self.cold.directed(a, b),
            None => None,
        }
    }

    /// Warms the corners of `t` before a mutation of a triangle at them: each initial boundary
    /// face at a cold corner v enters `id` and `bnext` unless another corner of it is warm
    /// (then it is there already), and each edge v–w of them with w cold enters `eadj` with
    /// the third vertices of its two initial faces, in id order (see
    /// [`General3::build_lazy`]). Changes no answer of the engine.
    pub(super) fn heat(&mut self, t: [u32; 3]) {
        for v in t {
            if !self.cold.all_cold(&[v]) {
                continue;
            }
            self.cold.cold[v as usize] = false;
            let (lo, hi) = (
                self.cold.start[v as usize] as usize,
                self.cold.start[v as usize + 1] as usize,
            );
            for j in lo..hi {
                let i = self.cold.at[j];
                let f = self.cold.faces[i as usize];
                let k = (0..3).find(|&k| f[k] == v).unwrap_or(0);
                let (w, u) = (f[(k + 1) % 3], f[(k + 2) % 3]);
                let (cw, cu) = (self.cold.all_cold(&[w]), self.cold.all_cold(&[u]));
                if cw && cu {
                    self.id.insert(sorted3(f), i);
                    for k in 0..3 {
                        self.bnext.insert(dk(f[k], f[(k + 1) % 3]), f[(k + 2) % 3]);
                    }
                }
                if cw {
                    self.eadj.entry(ek(v, w)).or_default().push(u);
                }
                if cu {
                    self.eadj.entry(ek(u, v)).or_default().push(w);
                }
            }
        }
    }

    pub(super) fn set_boundary(&mut self, f: [u32; 3], on: bool) {
        self.heat(f);
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
                self.bfaces.insert(i, lo, hi);
            }
            self.bfaces
                .set_alive(i, on && self.live[i as usize] && self.in_bgrid[i as usize]);
        }
        for k in 0..3 {
            let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            self.dirty_edges.push(ek(a, b));
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

    /// The third vertices of every live triangle on edge xy, from `eadj` without a lookup of
    /// each triangle; `None` when x and y are both cold (the initial boundary faces on such an
    /// edge are left out of `eadj`, [`General3::build_lazy`]: unknown).
    ///
    /// Why the list holds every live triangle xyl (so that `l` missing from it proves
    /// `!self.has(x, y, l)`): a triangle enters `eadj` on each of its edges when it is
    /// constructed ([`General3::build_with`]) or added or revived ([`General3::add_tri_grid`]),
    /// and leaves only when killed ([`General3::kill`]); the one exception is an initial
    /// boundary face on an edge with both ends cold at construction, and [`General3::heat`]
    /// enters it on that edge when the first of the two ends warms (the other is cold then).
    /// Test `thirds_filter_constricts_identically`.
    pub(super) fn live_thirds(&self, x: u32, y: u32) -> Option<&[u32]> {
        if self.cold.all_cold(&[x, y]) {
            return None;
        }
        Some(self.eadj.get(&ek(x, y)).map_or(&[][..], |v| v.as_slice()))
    }

    /// Is the oriented face a boundary face (with this orientation)?
    pub(super) fn is_bface(&self, f: [u32; 3]) -> bool {
        self.bnext_of(f[0], f[1]) == Some(f[2])
    }

    pub(super) fn on_boundary(&self, v: u32) -> bool {
        self.vcount[v as usize] > 0
    }

    pub(super) fn bedge(&self, a: u32, b: u32) -> bool {
        self.bnext_of(a, b).is_some() || self.bnext_of(b, a).is_some()
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
        // (the initial faces whose corners are all cold, untouched: [`General3::build_lazy`])
        out.extend(
            self.cold
                .faces
                .iter()
                .filter(|f| self.cold.all_cold(*f))
                .map(|&f| sorted_rot(f)),
        );
        out.sort_unstable();
        out
    }

    /// The caller's word that every triangle given to [`General3::new`] (boundary, live and
    /// keep triangles) is a face of the Delaunay tetrahedralization of the points (as in
    /// [`super::Engine3::augment_after_lock`]: faces of Delaunay tetrahedra). Call right after
    /// `new`, before anything is added.
    pub(super) fn trust_initial_as_delaunay(&mut self) {
        debug_assert_eq!(self.added, 0);
        self.delaunay_ids = self.tris.len() as u32;
    }

    /// [`General3::boundary`] and, when the caller vouched for the initial triangles
    /// ([`General3::trust_initial_as_delaunay`]), for each boundary triangle whether it is one
    /// of them (then a Delaunay face; a triangle added later counts as not, even when it
    /// happens to be one: the final check then tests it, which can only cost time). As
    /// [`crate::mesh::validity::faces_of_tetrahedra`], a triangle listed twice (both
    /// orientations) is trusted once, its first copy, so that the pair is still tested.
    ///
    /// The ids come with the faces instead of being looked up again: a face of `bnext` has a
    /// warm corner ([`General3::build_lazy`]: the map receives only such faces, and
    /// `set_boundary` warms the corners first), so its id is [`General3::id_of`]'s map lookup;
    /// an initial face whose corners are all cold is untouched and its id is its position in
    /// [`Cold`] (what `id_of` would find there). Same answer as looking every triangle up
    /// (test `delaunay_flags_equal_the_lookups`); it saves a missed hash lookup and a scan of
    /// the cold table per untouched face (875 k of them after the dragon's constriction).
    pub(super) fn boundary_with_delaunay_flags(&self) -> (Vec<[u32; 3]>, Option<Vec<bool>>) {
        if self.delaunay_ids == 0 {
            return (self.boundary(), None);
        }
        let mut with_ids: Vec<([u32; 3], Option<u32>)> = self
            .bnext
            .iter()
            .filter_map(|(&k, &c)| {
                let (a, b) = ((k >> 32) as u32, k as u32);
                (a < b && a < c).then(|| ([a, b, c], self.id_of(sorted3([a, b, c]))))
            })
            .collect();
        with_ids.extend(
            self.cold
                .faces
                .iter()
                .enumerate()
                .filter(|(_, f)| self.cold.all_cold(*f))
                .map(|(i, &f)| (sorted_rot(f), Some(i as u32))),
        );
        // (faces distinct up to the pairs of one triple listed twice, whose ids are equal:
        // the order of the faces is that of `boundary`)
        with_ids.sort_unstable();
        let mut seen = vec![false; self.delaunay_ids as usize];
        let flags = with_ids
            .iter()
            .map(|&(_, id)| match id {
                Some(i) if i < self.delaunay_ids && !seen[i as usize] => {
                    seen[i as usize] = true;
                    true
                }
                _ => false,
            })
            .collect();
        (with_ids.into_iter().map(|(t, _)| t).collect(), Some(flags))
    }

    /// [`General3::boundary_with_delaunay_flags`] as before: every boundary triangle looked up
    /// with [`General3::id_of`] (the reference of its test).
    #[cfg(test)]
    pub(super) fn boundary_with_delaunay_flags_looked_up(
        &self,
    ) -> (Vec<[u32; 3]>, Option<Vec<bool>>) {
        let tris = self.boundary();
        if self.delaunay_ids == 0 {
            return (tris, None);
        }
        let mut seen = vec![false; self.delaunay_ids as usize];
        let flags = tris
            .iter()
            .map(|&t| match self.id_of(sorted3(t)) {
                Some(i) if i < self.delaunay_ids && !seen[i as usize] => {
                    seen[i as usize] = true;
                    true
                }
                _ => false,
            })
            .collect();
        (tris, Some(flags))
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

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
        let st = crate::boundary::d3::constrict::constrict_3d(
            &d,
            crate::boundary::d3::constrict::Until::All,
        );
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
            one.vcoarse.insert(v as u32, q, q);
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
            bulk.tgrid.classes() > 1,
            "boxes of one size only in the test"
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
        assert_eq!(bulk.tgrid.ids(), one.tgrid.ids());
        assert_eq!(bulk.bgrid.contents(), one.bgrid.contents());
        assert_eq!(bulk.bfaces.ids(), one.bfaces.ids());
        assert_eq!(bulk.vgrid, one.vgrid);
        assert_eq!(bulk.vcoarse, one.vcoarse);
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
            let pts = super::super::test_sets::clustered_cube(seed);
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let st = crate::boundary::d3::constrict::constrict_3d(
                &d,
                crate::boundary::d3::constrict::Until::All,
            );
            let live = super::super::test_sets::live_faces(&d, &st.alive);
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

    /// `changed_since` with its block stamps answers as the former scan of every cell of the
    /// box (written out here), on random boxes from a cell to beyond `MAX_SPAN` cells and
    /// every epoch, after each of a sequence of random mutations of an engine on cube points.
    #[test]
    fn block_stamps_answer_as_the_cells() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
        let (d, pos, all) = super::super::test_sets::cube_candidates(&mut rng, 400);
        let mut g = General3::new(&pos, &d.hull, &all, &[]);
        let cell = g.bgrid.cell();
        let former = |g: &General3<'_>, epoch: u64, lo: P, hi: P| {
            if g.changed_all > epoch {
                return true;
            }
            let (a, b) = g.bgrid.range(lo, hi);
            Grid::span(a, b) > Grid::MAX_SPAN
                || (a[0]..=b[0]).any(|x| {
                    (a[1]..=b[1]).any(|y| {
                        (a[2]..=b[2]).any(|z| g.changed.get(&(x, y, z)).is_some_and(|&e| e > epoch))
                    })
                })
        };
        let mut seen = [0usize; 2];
        for round in 0..120 {
            let i = rng.gen_range(0..g.tris.len());
            let t = g.tris[i];
            match round % 3 {
                0 if g.live[i] => g.kill(i as u32),
                1 if !g.live[i] => {
                    g.add_tri(t);
                }
                _ => g.set_boundary(t, !g.bflag[i]),
            }
            for _ in 0..200 {
                let c: P = std::array::from_fn(|_| rng.gen_range(-0.1..1.1));
                let w = cell * [0.1, 1.0, 3.0, 9.0][rng.gen_range(0..4)];
                let h: P = std::array::from_fn(|_| rng.gen_range(0.0..w));
                let (lo, hi) = (c, std::array::from_fn(|k| c[k] + h[k]));
                let e = rng.gen_range(0..=g.epoch);
                let want = former(&g, e, lo, hi);
                assert_eq!(g.changed_since(e, lo, hi), want, "round {round} epoch {e}");
                seen[want as usize] += 1;
            }
        }
        assert!(seen[0] > 1000 && seen[1] > 1000, "{seen:?}");
    }

    /// The Delaunay-face flags with the ids carried along equal those of looking every
    /// boundary triangle up (`boundary_with_delaunay_flags_looked_up`, the former code), on
    /// lazy engines after locked Delaunay constrictions (live triangles: the tetrahedra at the
    /// vertices off the boundary, so that most boundary faces stay cold), after construction,
    /// the first run and every augmentation round.
    #[test]
    fn delaunay_flags_equal_the_lookups() {
        let mut cold_faces = 0;
        for seed in [1647u64, 1755, 1, 2, 3, 4] {
            let Some((d, pos, st)) = super::super::test_sets::locked_clustered_cube(seed) else {
                continue;
            };
            let mut on = vec![false; pos.len()];
            for t in &st.triangles {
                for &v in t {
                    on[v as usize] = true;
                }
            }
            let region: Vec<bool> = (0..d.tets.len())
                .map(|t| st.alive[t] && d.tets[t].iter().any(|&v| !on[v as usize]))
                .collect();
            let live = super::super::test_sets::live_faces(&d, &region);
            let mut g = General3::new(&pos, &st.triangles, &live, &[]);
            g.trust_initial_as_delaunay();
            let check = |g: &General3<'_>, what: &str| {
                let (a, b) = (
                    g.boundary_with_delaunay_flags(),
                    g.boundary_with_delaunay_flags_looked_up(),
                );
                assert_eq!(a, b, "seed {seed} {what}");
                assert!(a.1.is_some_and(|f| f.iter().any(|&x| x)));
                g.cold.faces.iter().filter(|f| g.cold.all_cold(*f)).count()
            };
            cold_faces += check(&g, "start");
            g.run();
            check(&g, "run");
            for step in 1..=10 {
                if g.done() {
                    break;
                }
                let x = g.local_gamma(-(step as f64) / 10.0, 16);
                g.augment(&x);
                g.run();
                cold_faces += check(&g, &format!("step {step}"));
            }
        }
        assert!(cold_faces > 500, "{cold_faces} cold faces");
    }

    /// Every mutation primitive (kill, add, boundary flag) stamps its box: a box meeting the
    /// mutated triangle sees the change, a far box does not, and nothing is stamped during
    /// construction.
    #[test]
    fn mutations_stamp_the_cells_they_touch() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let (d, pos, all) = super::super::test_sets::cube_candidates(&mut rng, 300);
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

    /// The refusal of [`Cold::new`] as the check it replaces: for each face f, another face
    /// at f's first corner with the directed edge f₀→f₁ or the same sorted corners, found by
    /// reading the faces. On random face lists over few vertices (faces repeated, reversed,
    /// rotated, sharing directed edges: both answers occur often) and on a real closed
    /// surface (accepted) with one face reversed or repeated (refused).
    #[test]
    fn cold_table_refuses_as_the_face_scan() {
        fn reference(n: usize, faces: &[[u32; 3]]) -> bool {
            if faces.iter().any(|f| {
                f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || f.iter().any(|&v| v as usize >= n)
            }) {
                return false;
            }
            faces.iter().enumerate().all(|(i, f)| {
                let s = sorted3(*f);
                !faces.iter().enumerate().any(|(j, g)| {
                    j != i
                        && g.contains(&f[0])
                        && (sorted3(*g) == s
                            || (0..3).any(|k| g[k] == f[0] && g[(k + 1) % 3] == f[1]))
                })
            })
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let (mut yes, mut no) = (0, 0);
        for round in 0..3000 {
            let n = rng.gen_range(3..9usize);
            let m = rng.gen_range(1..7usize);
            let mut faces: Vec<[u32; 3]> = Vec::new();
            while faces.len() < m {
                let f: [u32; 3] = std::array::from_fn(|_| rng.gen_range(0..n as u32));
                // mostly non-degenerate faces, a few out of range or degenerate
                if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) && rng.gen_range(0..10) > 0 {
                    continue;
                }
                faces.push(f);
            }
            let nn = if round % 50 == 0 { n - 1 } else { n };
            let want = reference(nn, &faces);
            assert_eq!(Cold::new(nn, &faces).is_some(), want, "{nn} {faces:?}");
            if want {
                yes += 1;
            } else {
                no += 1;
            }
        }
        assert!(yes > 300 && no > 300, "{yes} {no}");
        // a closed surface: the hull of random points
        let pts: Vec<crate::geom::Point3> = (0..300)
            .map(|_| {
                let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                crate::geom::Point3::new(v[0], v[1], v[2])
            })
            .collect();
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let hull = d.hull.clone();
        let n = d.points.len();
        assert!(hull.len() > 20);
        assert!(Cold::new(n, &hull).is_some());
        assert!(reference(n, &hull));
        let mut rev = hull.clone();
        rev.push([hull[7][0], hull[7][2], hull[7][1]]);
        assert!(Cold::new(n, &rev).is_none() && !reference(n, &rev));
        let mut rot = hull.clone();
        rot.push([hull[3][1], hull[3][2], hull[3][0]]);
        assert!(Cold::new(n, &rot).is_none() && !reference(n, &rot));
    }

    /// Every live triangle xyl is in `eadj`'s list of its edge xy unless x and y are both cold
    /// ([`General3::live_thirds`]: what makes the apex filter of `best_plain` exact), and every
    /// third vertex l in the list of an edge xy names a live triangle xyl (what lets
    /// [`General3::combinatorial_listed`] skip the lookups the lists answered).
    fn assert_thirds_listed(g: &General3<'_>, at: &str) {
        for (&e, list) in g.eadj.iter() {
            let (x, y) = ((e >> 32) as u32, e as u32);
            for &l in list {
                assert!(
                    g.has(x, y, l),
                    "{at}: {l} listed on {x}-{y}, {x} {y} {l} not live"
                );
            }
        }
        for (i, s) in g.tris.iter().enumerate() {
            if !g.live[i] {
                continue;
            }
            for k in 0..3 {
                let (x, y, l) = (s[k], s[(k + 1) % 3], s[(k + 2) % 3]);
                if let Some(list) = g.live_thirds(x, y) {
                    assert!(list.contains(&l), "{at}: live {s:?} not listed on {x}-{y}");
                }
            }
        }
    }

    /// The apex filter of `best_plain` ([`General3::live_thirds`]) changes no removal: after a
    /// locked Delaunay constriction, engines on the live triangles near the locked vertices
    /// (lazy construction: most boundary faces cold, as on the dragon) and on all of them,
    /// with the filter and without it (the reference), go through the augmentation schedule
    /// with the same removals and end with the same boundary; the lists hold every live
    /// triangle after each step.
    #[test]
    fn thirds_filter_constricts_identically() {
        let (mut locked, mut cold_runs) = (0, 0);
        for seed in (1..=40u64).chain([1647, 1755]) {
            let Some((d, pos, st)) = super::super::test_sets::locked_clustered_cube(seed) else {
                continue;
            };
            locked += 1;
            let on: IdSet<u32> = st.triangles.iter().flatten().copied().collect();
            // the live tetrahedra at a locked vertex and their live neighbours
            let mut near = vec![false; d.tets.len()];
            for (t, tet) in d.tets.iter().enumerate() {
                if st.alive[t] && tet.iter().any(|v| !on.contains(v)) {
                    near[t] = true;
                    for &n in &d.neighbors[t] {
                        if n != crate::util::NONE && st.alive[n as usize] {
                            near[n as usize] = true;
                        }
                    }
                }
            }
            let all = super::super::test_sets::live_faces(&d, &st.alive);
            let local = super::super::test_sets::live_faces(&d, &near);
            for (name, live, lazy) in [("local", &local, true), ("all", &all, false)] {
                let go = |filter: bool| {
                    let mut g = General3::blank(&pos, &st.triangles, live, &[]);
                    g.filter_thirds = filter;
                    if lazy {
                        g.build_lazy(&st.triangles, live, &[]);
                    } else {
                        g.build(&st.triangles, live, &[]);
                    }
                    let cold = g.cold.cold.iter().filter(|&&c| c).count();
                    g.trust_initial_as_delaunay();
                    g.track = true;
                    g.push_all();
                    g.run();
                    assert_thirds_listed(&g, name);
                    let mut trace = vec![(g.iterations, g.boundary_vertices, g.added)];
                    for step in 1..=10 {
                        if g.done() {
                            break;
                        }
                        let x = g.local_gamma(-(step as f64) / 10.0, 16);
                        g.augment(&x);
                        g.run();
                        assert_thirds_listed(&g, name);
                        trace.push((g.iterations, g.boundary_vertices, g.added));
                    }
                    (g.boundary(), trace, cold)
                };
                let (b0, t0, _) = go(false);
                let (b1, t1, cold) = go(true);
                assert_eq!(t0, t1, "seed {seed} {name}");
                assert_eq!(b0, b1, "seed {seed} {name}");
                if lazy && cold > 0 {
                    cold_runs += 1;
                }
            }
        }
        assert!(
            locked >= 3 && cold_runs >= 3,
            "{locked} locked, {cold_runs} with cold vertices"
        );
    }
}

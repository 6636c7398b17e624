//! 3D constriction of γ(\[-1,1\],\[0,1\]) = the Delaunay tetrahedralization (Veltkamp 1992, §5.3,
//! Def. 5.2, Eq. 5.2, the selection rule with the sum of γ-indicators; Algorithm 5.1 and the
//! heap of §5.5).
//!
//! # What it computes
//! Starting from the convex hull, boundary tetrahedra are deleted from the Delaunay
//! tetrahedralization until every vertex lies on the boundary ([`Until::All`]) or nothing is
//! removable any more ([`Until::Locked`]). A live tetrahedron with
//! - **one** boundary triangle vᵢvⱼvₖ is removable iff the opposite vertex vₗ is not on the
//!   boundary; its key is the γ-indicator of vᵢvⱼvₖ w.r.t. vₗ;
//! - **two** boundary triangles vᵢvⱼvₖ, vⱼvₖvₗ is removable iff the edge vᵢvₗ is not on the
//!   boundary; its key is the sum of the two γ-indicators;
//! - three or four boundary triangles is never removable.
//!
//! The key is the γ-indicator ([`Key::Gamma`], below) or Boissonnat's minimal area change
//! ([`Key::MinAreaChange`], V §4.3.3, Eq. 4.1, [`min_area_change_3d`]): (Σ area of the
//! tetrahedron's interior faces − Σ area of its boundary faces) / (Σ area of all four faces).
//! Smallest key first in both cases; the removability rules are the same for both keys (V
//! §4.3.3 removes exactly the one- and two-boundary-triangle tetrahedra with these
//! conditions).
//!
//! These are exactly V's conditions; they keep the boundary a closed 2-manifold of genus 0
//! (removing a one-triangle tetrahedron pushes a new vertex into a face; removing a
//! two-triangle tetrahedron flips the shared edge vⱼvₖ to vᵢvₗ, which is allowed only when vᵢvₗ is
//! not yet a boundary edge — this also excludes vertices of boundary degree 3).
//!
//! # γ-indicator (Def. 5.2)
//! |c₀| = 1 − r/R with r the circumradius of the boundary triangle and R that of the
//! tetrahedron (floating point: it only orders the heap). The sign (Eq. 5.2: + when the sphere
//! centre lies on vₗ's side of the triangle's plane) is decided **exactly**: with the triangle's
//! circumcentre m, the centre is m + s·n and vₗ on the sphere gives s·h = q/2 with h the height
//! of vₗ and q = |vₗ − m|² − r²; so the centre is on vₗ's side iff q > 0, i.e. iff vₗ lies outside
//! the triangle's diametral sphere. q·|n|² is a polynomial in the coordinate differences,
//! evaluated in floating point with a conservative filter and otherwise exactly with big
//! integers ([`center_side`]).
//!
//! # Complexity
//! Heap with lazy revalidation: an entry stores the boundary-face mask its key was computed
//! for and is skipped when the mask changed or the tetrahedron became unremovable; when a
//! two-triangle removal takes edge vⱼvₖ off the boundary, the tetrahedra around vⱼvₖ are pushed
//! again (they may have become removable). A push of a (tetrahedron, mask) pair that already
//! has an entry in the heap is skipped (the key is a function of the pair, so the entry would be
//! the same; see [`constrict_3d_with`]). Each live tetrahedron's boundary-face mask is kept up
//! to date (one byte read per heap entry, push and rotation step; in one word with the
//! tetrahedron's pending entries, so that a push reads one line, and the live flags are
//! derived from it at the end instead of written at every removal), its corners and neighbours
//! are packed side by side (one cache line per step of a rotation around an edge, the hot
//! loop; 32 bytes per tetrahedron while the constriction runs), and the heap is 4-ary over
//! packed integer entries; the removals are the same, in the same order, as with a binary heap
//! and masks recomputed from the neighbours (test `constriction_equals_the_reference`). A
//! popped two-face entry is not rotated around its edge again when no tetrahedron at an end
//! of that edge was removed since its push (a per-vertex removal stamp in the entry): the
//! rotation found the edge interior then and nothing around it changed.
//! O(T log T) for T tetrahedra (V §5.5: O(N² log N) in the worst case, O(N log N) expected).
//!
//! Preconditions: a non-degenerate tetrahedralization (at least one tetrahedron).

pub use crate::boundary::indicator::Key;
use crate::delaunay::d3::{Delaunay3, FACE_OF};
use crate::geom::exact::diametral_side_exact;
use crate::geom::vec::{cross, dot, sub, triangle_area2};
use crate::geom::Point3;
use crate::util::{sorted3, IdSet, NONE};

/// When to stop the 3D constriction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Until {
    /// Stop as soon as every vertex is on the boundary (V's default).
    All,
    /// Continue while removable tetrahedra remain (V §5.3: artificial objects may need more
    /// removals); the boundary stays a closed genus-0 2-manifold throughout.
    Locked,
}

/// The result of [`constrict_3d`].
#[derive(Debug, Clone)]
pub struct Constriction3 {
    /// Live tetrahedra (the interior tetrahedralization).
    pub alive: Vec<bool>,
    /// Boundary triangles (vertex indices), oriented outward.
    pub triangles: Vec<[u32; 3]>,
    /// Vertices on the boundary.
    pub boundary_vertices: usize,
    /// Number of deleted tetrahedra.
    pub iterations: usize,
}

/// Sign of q·|n|² (see the module documentation): +1 when `l` lies outside the diametral
/// sphere of triangle `ijk` (the tetrahedron's circumcentre is on l's side of the plane), −1
/// inside, 0 on it. Exact.
pub fn center_side(i: [f64; 3], j: [f64; 3], k: [f64; 3], l: [f64; 3]) -> i32 {
    // float evaluation with a generous filter
    let (b, c, d) = (sub(j, i), sub(k, i), sub(l, i));
    let n = cross(b, c);
    let (bb, cc, dd, nn) = (dot(b, b), dot(c, c), dot(d, d), dot(n, n));
    let w = [
        cc * cross(n, b)[0] + bb * cross(c, n)[0],
        cc * cross(n, b)[1] + bb * cross(c, n)[1],
        cc * cross(n, b)[2] + bb * cross(c, n)[2],
    ];
    let val = dd * nn - dot(d, w);
    let mag = dd * nn + dd.sqrt() * (cc * nn.sqrt() * bb.sqrt() + bb * cc.sqrt() * nn.sqrt()) * 2.0;
    if val.is_finite() && mag.is_finite() && val.abs() > 1e-9 * mag {
        return if val > 0.0 { 1 } else { -1 };
    }
    // exact: the same polynomial over big integers
    diametral_side_exact(i, j, k, l)
}

/// Circumradius of a 3D triangle (floating point).
fn tri_circumradius(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (x, y, z) = (sub(a, b), sub(b, c), sub(c, a));
    let area2 = triangle_area2(a, b, c);
    if area2 > 0.0 {
        (dot(x, x) * dot(y, y) * dot(z, z)).sqrt() / (2.0 * area2)
    } else {
        f64::INFINITY
    }
}

/// The γ-indicator of triangle (i, j, k) w.r.t. l, given the circumradius `big_r` of the
/// tetrahedron (Def. 5.2 with the exact sign of Eq. 5.2).
pub fn gamma_indicator_3d(i: [f64; 3], j: [f64; 3], k: [f64; 3], l: [f64; 3], big_r: f64) -> f64 {
    let s = center_side(i, j, k, l);
    if s == 0 {
        return 0.0;
    }
    let r = tri_circumradius(i, j, k);
    let mag = if big_r.is_finite() && big_r > 0.0 {
        (1.0 - r / big_r).clamp(0.0, 1.0)
    } else {
        1.0
    };
    if s > 0 {
        mag
    } else {
        -mag
    }
}

/// Boissonnat's minimal area change (V §4.3.3, Eq. 4.1) of removing the tetrahedron with
/// corners `p` whose boundary faces are the bits of `boundary` (bit f = the face opposite
/// corner f): (Σ area of the interior faces − Σ area of the boundary faces) / (Σ area of all
/// four faces). 0 for a tetrahedron without area.
pub fn min_area_change_3d(p: [[f64; 3]; 4], boundary: u8) -> f64 {
    let (mut inner, mut outer) = (0.0, 0.0);
    for (f, o) in FACE_OF.iter().enumerate() {
        let a = triangle_area2(p[o[0]], p[o[1]], p[o[2]]);
        if boundary >> f & 1 == 1 {
            outer += a;
        } else {
            inner += a;
        }
    }
    let all = inner + outer;
    if all > 0.0 {
        (inner - outer) / all
    } else {
        0.0
    }
}

/// The key of removing the tetrahedron with corners `p` (in [`Delaunay3`] face order: face f
/// is opposite corner f, [`FACE_OF`]) whose boundary faces are the bits of `boundary`:
/// [`Key::Gamma`] sums the γ-indicators of the boundary faces w.r.t. their opposite corners
/// (`big_r` = the tetrahedron's circumradius); [`Key::MinAreaChange`] is
/// [`min_area_change_3d`] (`big_r` unused). Smaller keys are removed first.
pub fn removal_key(key: Key, p: [[f64; 3]; 4], boundary: u8, big_r: f64) -> f64 {
    match key {
        Key::Gamma => FACE_OF
            .iter()
            .enumerate()
            .filter(|(f, _)| boundary >> f & 1 == 1)
            .map(|(f, o)| gamma_indicator_3d(p[o[0]], p[o[1]], p[o[2]], p[f], big_r))
            .sum(),
        Key::MinAreaChange => min_area_change_3d(p, boundary),
    }
}

/// The largest [`State::stamp`] (28 bits, below the mask in a heap entry, [`QuadHeap`]); a
/// saturated stamp proves nothing ([`State::edge_unchanged`]).
const STAMP_SAT: u32 = (1 << 28) - 1;

/// Bit of [`State::mask`] marking a removed tetrahedron (the face bits are 0–3).
const DEAD: u8 = 0x80;

/// The bit of [`State::meta`] recording that an entry (t, m) is in the heap: bit 16 + m (the
/// mask m of a pushed entry is 1–15).
fn pending_bit(m: u8) -> u32 {
    1 << (16 + m as u32)
}

/// A tetrahedron's corners and its neighbours (across the face opposite each corner) side by
/// side in half a cache line: a step of the rotation around an edge, the hot loop of the
/// constriction, reads one line instead of one in `Delaunay3::tets` and one in
/// `Delaunay3::neighbors`.
#[derive(Clone, Copy)]
#[repr(C, align(32))]
struct Cell {
    v: [u32; 4],
    n: [u32; 4],
}

/// The cells of `d`'s tetrahedra.
fn cells_of(d: &Delaunay3) -> Vec<Cell> {
    d.tets
        .iter()
        .zip(&d.neighbors)
        .map(|(&v, &n)| Cell { v, n })
        .collect()
}

/// The circumradius of the tetrahedron with corners `p`: [`Delaunay3::circumsphere`]'s
/// expression on the same values (bit-identical; test `circumradius_is_the_delaunay_one`), from
/// corners the caller has already read.
fn circumradius(p: [Point3; 4]) -> f64 {
    let a = p[0];
    let b = p[1] - a;
    let c = p[2] - a;
    let d = p[3] - a;
    let den = 2.0 * b.dot(&c.cross(&d));
    let num = c.cross(&d) * b.norm_squared()
        + d.cross(&b) * c.norm_squared()
        + b.cross(&c) * d.norm_squared();
    (num / den).norm()
}

struct State<'a> {
    d: &'a Delaunay3,
    /// `d`'s tetrahedra and neighbours, packed ([`Cell`]).
    cells: Vec<Cell>,
    /// Per tetrahedron, in one word (one cache line for the two reads of a push):
    /// - the low byte, its mask ([`State::mask`]): for a live tetrahedron its boundary faces
    ///   (bit f: the neighbour across face f is absent or removed), [`DEAD`] for a removed
    ///   one; kept up to date by [`State::kill`], so that a heap entry, a push and a step of
    ///   the rotation around an edge read one byte instead of the four neighbours and their
    ///   live flags (the live set is the tetrahedra not [`DEAD`]);
    /// - the high 16 bits, the masks m with an entry (t, m) in the heap ([`pending_bit`];
    ///   see [`constrict_3d_with`]).
    meta: Vec<u32>,
    vcount: Vec<u32>,
    /// Per vertex, how many removed tetrahedra had it as a corner (saturating at
    /// [`STAMP_SAT`]): a two-face entry records the stamp of an end of the edge its
    /// removability depends on, and when that stamp is unchanged at the pop no tetrahedron
    /// around the edge was removed meanwhile, so the rotation around it is not redone
    /// ([`State::edge_unchanged`]).
    stamp: Vec<u32>,
    nbv: usize,
    keep: IdSet<[u32; 3]>,
    key: Key,
}

impl<'a> State<'a> {
    /// The state with the live tetrahedra `alive` (no vertex counted on the boundary yet).
    fn new(d: &'a Delaunay3, alive: impl Fn(usize) -> bool, keep: &[[u32; 3]], key: Key) -> Self {
        let meta = (0..d.tets.len())
            .map(|t| {
                if !alive(t) {
                    return DEAD as u32;
                }
                let mut m = 0u32;
                for (f, &n) in d.neighbors[t].iter().enumerate() {
                    if n == NONE || !alive(n as usize) {
                        m |= 1 << f;
                    }
                }
                m
            })
            .collect();
        State {
            d,
            cells: cells_of(d),
            meta,
            vcount: vec![0; d.points.len()],
            stamp: vec![0; d.points.len()],
            nbv: 0,
            keep: keep.iter().map(|&f| sorted3(f)).collect(),
            key,
        }
    }

    /// The boundary faces of live tetrahedron t ([`DEAD`] when removed).
    fn mask(&self, t: usize) -> u8 {
        self.meta[t] as u8
    }

    /// Tetrahedron t is live (not removed).
    fn alive(&self, t: usize) -> bool {
        self.mask(t) != DEAD
    }

    /// The live tetrahedra (those not [`DEAD`]).
    fn alive_flags(&self) -> Vec<bool> {
        (0..self.meta.len()).map(|t| self.alive(t)).collect()
    }

    /// Removes live tetrahedron t: its live neighbours gain the shared face as a boundary face.
    fn kill(&mut self, t: usize) {
        // (the pending bits stay: a push of a removed tetrahedron stops at its mask)
        self.meta[t] = self.meta[t] & !0xff | DEAD as u32;
        for n in self.cells[t].n {
            if n != NONE && self.mask(n as usize) != DEAD {
                let nn = &self.cells[n as usize].n;
                // (two tetrahedra share at most one face)
                let g = nn.iter().position(|&x| x == t as u32).unwrap_or(4);
                if g < 4 {
                    self.meta[n as usize] |= 1 << g;
                }
            }
        }
    }

    fn face(&self, t: usize, f: usize) -> [u32; 3] {
        let v = self.cells[t].v;
        let o = FACE_OF[f];
        [v[o[0]], v[o[1]], v[o[2]]]
    }

    /// The key of removing tetrahedron t with boundary mask m, or `None` when not removable.
    fn key(&self, t: usize, m: u8) -> Option<f64> {
        if !self.removable(t, m) {
            return None;
        }
        let q = self.cells[t].v.map(|x| self.d.points[x as usize]);
        // the circumradius is computed only for the γ-indicator
        let r = match self.key {
            Key::Gamma => circumradius(q),
            Key::MinAreaChange => 0.0,
        };
        Some(removal_key(self.key, q.map(|x| x.into()), m, r))
    }

    /// Tetrahedron t with boundary faces m (bit f: the face opposite corner f) may be removed
    /// (V §5.3): one boundary face whose opposite vertex is not on the boundary, or two whose
    /// opposite edge (joining the corners opposite them) is not on the boundary; never a keep
    /// triangle (V §5.7), never three or four faces.
    fn removable(&self, t: usize, m: u8) -> bool {
        let v = self.cells[t].v;
        let mut faces = [0usize; 4];
        let mut nf = 0;
        for f in 0..4 {
            if m >> f & 1 == 1 {
                faces[nf] = f;
                nf += 1;
            }
        }
        let faces = &faces[..nf];
        if !self.keep.is_empty()
            && faces
                .iter()
                .any(|&f| self.keep.contains(&sorted3(self.face(t, f))))
        {
            return false;
        }
        match *faces {
            [f] => self.vcount[v[f] as usize] == 0,
            [f, g] => !self.edge_on_boundary(t as u32, v[f], v[g]),
            _ => false,
        }
    }

    /// The end of the edge that decides whether tetrahedron t with the two boundary faces of
    /// `m` is removable (the corner opposite the lower face; the edge joins the corners
    /// opposite the two faces, [`State::removable`]).
    fn edge_end(&self, t: usize, m: u8) -> u32 {
        self.cells[t].v[m.trailing_zeros() as usize & 3]
    }

    /// The stamp an entry (t, m) records when pushed: its edge end's for two boundary faces,
    /// 0 (never used) otherwise.
    fn entry_stamp(&self, t: usize, m: u8) -> u32 {
        if m.count_ones() == 2 {
            self.stamp[self.edge_end(t, m) as usize]
        } else {
            0
        }
    }

    /// Entry (t, m) with stamp `s`, found removable when pushed and with t's mask still m, is
    /// still removable: m has two faces and the stamp of its edge end is still `s` (not
    /// saturated). Why: the verdict then depended only on the edge joining the corners
    /// opposite the two faces being off the boundary (keep triangles never change), and
    /// whether an edge is on the boundary changes only when a live tetrahedron around it is
    /// removed — whose corners include both ends, so the end's stamp would have grown.
    fn edge_unchanged(&self, t: usize, m: u8, s: u32) -> bool {
        m.count_ones() == 2 && s < STAMP_SAT && self.stamp[self.edge_end(t, m) as usize] == s
    }

    fn add_face(&mut self, f: [u32; 3], delta: i32) {
        for &v in &f {
            self.add_vertex(v, delta);
        }
    }

    /// Changes the number of boundary faces at vertex v by `delta` (counting the vertices on
    /// the boundary).
    fn add_vertex(&mut self, v: u32, delta: i32) {
        let v = v as usize;
        let before = self.vcount[v];
        self.vcount[v] = (before as i64 + delta as i64).max(0) as u32;
        if before == 0 && self.vcount[v] > 0 {
            self.nbv += 1;
        } else if before > 0 && self.vcount[v] == 0 {
            self.nbv -= 1;
        }
    }

    /// Edge ab of the live tetrahedron t lies on the boundary: some face containing ab
    /// separates a live tetrahedron from a removed one or from the outside. Rotating around
    /// ab from t through live tetrahedra either meets a boundary face (a bit of the mask of
    /// the live tetrahedron it leaves) or comes back to t (every tetrahedron around ab is
    /// live: interior edge).
    fn edge_on_boundary(&self, t: u32, a: u32, b: u32) -> bool {
        let cells = &self.cells;
        let [f0, f1] = faces_with_edge(cells, t, a, b);
        let m = self.mask(t as usize);
        if (m >> f0 | m >> f1) & 1 == 1 {
            return true;
        }
        let (mut prev, mut cur) = (t, cells[t as usize].n[f0]);
        for _ in 0..cells.len() {
            // cur is live: the face it was entered through is interior
            let [g0, g1] = faces_with_edge(cells, cur, a, b);
            let nb = &cells[cur as usize].n;
            let g = if nb[g0] != prev { g0 } else { g1 };
            let next = nb[g];
            if next == t {
                return false;
            }
            if self.mask(cur as usize) >> g & 1 == 1 {
                return true;
            }
            (prev, cur) = (cur, next);
        }
        true
    }
}

/// The two faces of tetrahedron t that contain its edge ab: those opposite its two other
/// corners (face f is opposite corner f).
fn faces_with_edge(cells: &[Cell], t: u32, a: u32, b: u32) -> [usize; 2] {
    let v = cells[t as usize].v;
    let mut o = [0; 2];
    let mut k = 0;
    for (i, &x) in v.iter().enumerate() {
        if x != a && x != b && k < 2 {
            o[k] = i;
            k += 1;
        }
    }
    o
}

/// The tetrahedra around edge ab of tetrahedron t (t included) into `out` (cleared first), by
/// rotation through the neighbours (no vertex star needed).
fn around_edge_from(cells: &[Cell], t: u32, a: u32, b: u32, out: &mut Vec<u32>) {
    let others = |t: u32| faces_with_edge(cells, t, a, b);
    out.clear();
    out.push(t);
    for start in others(t) {
        let mut prev = t;
        let mut cur = cells[t as usize].n[start];
        while cur != NONE && cur != t && out.len() <= cells.len() {
            if out.contains(&cur) {
                break;
            }
            out.push(cur);
            let o = others(cur);
            let n0 = cells[cur as usize].n[o[0]];
            let next = if n0 != prev {
                n0
            } else {
                cells[cur as usize].n[o[1]]
            };
            prev = cur;
            cur = next;
        }
        if cur == t {
            break; // closed ring: the other direction gives the same tetrahedra
        }
    }
}

/// A 4-ary min-heap of the constriction's entries packed into `u128`s: the key's
/// [`f64::total_cmp`] order in the high 64 bits, then the tetrahedron, then the mask, then
/// the entry's edge stamp ([`State::stamp`], below the mask: it orders only entries with the
/// same key, tetrahedron and mask, which the heap never holds twice) — so the integer order is
/// the order of `MinKey<(u32, u8)>` (smallest key first, ties by the smallest (tetrahedron,
/// mask)), and the pop sequence is that of a `BinaryHeap` of those holding the same entries. Four children per node: half the levels of a binary heap, each level's
/// children in one or two cache lines (the heap holds the whole constriction front).
#[derive(Default)]
struct QuadHeap {
    a: Vec<u128>,
}

impl QuadHeap {
    /// The packed entry of key `key`, item (t, m) (m < 16) and stamp `s` (< [`STAMP_SAT`] + 1).
    fn pack(key: f64, t: u32, m: u8, s: u32) -> u128 {
        let b = key.to_bits() as i64;
        // the total_cmp transform, then the sign bit flipped: signed order → unsigned order
        let k = (b ^ ((((b >> 63) as u64) >> 1) as i64)) as u64 ^ (1 << 63);
        (k as u128) << 64 | (t as u128) << 32 | ((m & 15) as u128) << 28 | (s & STAMP_SAT) as u128
    }

    fn push(&mut self, key: f64, t: u32, m: u8, s: u32) {
        let e = Self::pack(key, t, m, s);
        let mut i = self.a.len();
        self.a.push(e);
        while i > 0 {
            let p = (i - 1) / 4;
            if self.a[p] <= e {
                break;
            }
            self.a[i] = self.a[p];
            i = p;
        }
        self.a[i] = e;
    }

    /// The smallest entry's item (t, m) and stamp.
    fn pop(&mut self) -> Option<(u32, u8, u32)> {
        let top = *self.a.first()?;
        let last = self.a.pop()?;
        let n = self.a.len();
        if n > 0 {
            let mut i = 0;
            loop {
                let c = 4 * i + 1;
                if c >= n {
                    break;
                }
                let end = (c + 4).min(n);
                let mut best = c;
                for j in c + 1..end {
                    if self.a[j] < self.a[best] {
                        best = j;
                    }
                }
                if self.a[best] >= last {
                    break;
                }
                self.a[i] = self.a[best];
                i = best;
            }
            self.a[i] = last;
        }
        Some((
            (top >> 32) as u32,
            (top >> 28) as u8 & 15,
            top as u32 & STAMP_SAT,
        ))
    }
}

/// Constricts the Delaunay tetrahedralization (see the module documentation).
pub fn constrict_3d(d: &Delaunay3, until: Until) -> Constriction3 {
    constrict_3d_keep(d, until, &[])
}

/// [`constrict_3d`] with keep triangles (vertex indices; V §5.7): a boundary triangle in
/// `keep` is never deleted. Only triangles of the Delaunay tetrahedralization can be kept (the
/// crossing case of V Fig. 5.12 right needs γ-graphs beyond Delaunay, not implemented); others
/// are ignored by the constriction and reported missing by the caller.
pub fn constrict_3d_keep(d: &Delaunay3, until: Until, keep: &[[u32; 3]]) -> Constriction3 {
    constrict_3d_with(d, until, keep, Key::Gamma)
}

/// [`constrict_3d_keep`] with the selection key `key` ([`Key::Gamma`]: V §5.3;
/// [`Key::MinAreaChange`]: Boissonnat, V §4.3.3, Eq. 4.1).
pub fn constrict_3d_with(
    d: &Delaunay3,
    until: Until,
    keep: &[[u32; 3]],
    key: Key,
) -> Constriction3 {
    let nt = d.tets.len();
    let nv = d.points.len();
    let mut st = State::new(d, |_| true, keep, key);
    for t in 0..nt {
        for f in 0..4 {
            if d.neighbors[t][f] == NONE {
                let fc = st.face(t, f);
                st.add_face(fc, 1);
            }
        }
    }
    let mut heap = QuadHeap::default();
    // bit `pending_bit(m)` of meta[t]: an entry (t, m) is in the heap. A push of a pending pair is skipped:
    // the key is a function of the tetrahedron and its mask, so the skipped entry would equal
    // the pending one and pop right after it, with nothing changed in between — the first
    // either removes the tetrahedron (the copy then finds it dead) or is discarded (the copy is
    // judged on the same state and discarded too). It saves the key (the circumsphere and the
    // exact sides of the boundary faces) and the heap traffic of the tetrahedra pushed again
    // around a flipped edge or by an unchanged neighbour.
    //
    // Clearing the bit when (t, m) is popped is not needed for the result (so no test can catch
    // its omission; dragon13 found none did): while t lives, (a) its mask only gains bits (a
    // boundary face stays one while t lives), so a stale mask never recurs, and (b) a verdict
    // "not removable" with mask m is final: with one boundary face the opposite vertex is on the
    // boundary and stays there while t (which holds it) lives; with two, the edge opposite
    // their shared edge is on the boundary and stays there while t (around it) lives; keep
    // faces never change. So a popped (t, m) is never pushed again with a different outcome.
    // The bit is cleared anyway, to keep the bits' meaning ("in the heap") exact.
    let push = |st: &mut State, heap: &mut QuadHeap, t: usize| {
        let m = st.mask(t);
        if m == 0 || m == DEAD || st.meta[t] & pending_bit(m) != 0 {
            return;
        }
        if let Some(key) = st.key(t, m) {
            st.meta[t] |= pending_bit(m);
            heap.push(key, t as u32, m, st.entry_stamp(t, m));
        }
    };
    for t in 0..nt {
        push(&mut st, &mut heap, t);
    }
    let mut iterations = 0;
    let mut ring = Vec::new();
    while until == Until::Locked || st.nbv < nv {
        let Some((t, mask, stamp)) = heap.pop() else {
            break;
        };
        let t = t as usize;
        st.meta[t] &= !pending_bit(mask);
        // (a removed tetrahedron's mask is DEAD, never a pushed mask; every entry was
        // removable when pushed)
        if st.mask(t) != mask || !(st.edge_unchanged(t, mask, stamp) || st.removable(t, mask)) {
            continue;
        }
        let m = mask;
        // corner i lies on the three faces other than face i: its count gains those that become
        // boundary faces and loses those that stop being ones (never below zero: the faces it
        // loses were counted)
        let Cell { v, n: nb } = st.cells[t];
        for (i, &x) in v.iter().enumerate() {
            let lost = (m & !(1 << i)).count_ones() as i32;
            st.add_vertex(x, 3 - 2 * lost);
            let s = &mut st.stamp[x as usize];
            *s = (*s + 1).min(STAMP_SAT);
        }
        st.kill(t);
        iterations += 1;
        for f in 0..4 {
            if m >> f & 1 == 0 {
                let n = nb[f];
                if n != NONE {
                    push(&mut st, &mut heap, n as usize);
                }
            }
        }
        if m.count_ones() == 2 {
            // the shared edge left the boundary: tetrahedra around it may now be removable
            let mut shared = [0u32; 2];
            let mut k = 0;
            for (f, &x) in v.iter().enumerate() {
                if m >> f & 1 == 0 {
                    shared[k] = x;
                    k += 1;
                }
            }
            around_edge_from(&st.cells, t as u32, shared[0], shared[1], &mut ring);
            for &n in &ring {
                push(&mut st, &mut heap, n as usize);
            }
        }
    }
    let mut triangles = Vec::new();
    for t in 0..nt {
        let m = st.mask(t);
        if m == DEAD {
            continue;
        }
        for f in 0..4 {
            if m >> f & 1 == 1 {
                triangles.push(st.face(t, f));
            }
        }
    }
    Constriction3 {
        alive: st.alive_flags(),
        triangles,
        boundary_vertices: st.nbv,
        iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::predicates::raw::orient3d;
    use rand::{Rng, SeedableRng};

    fn circumcentre(p: [[f64; 3]; 4]) -> [f64; 3] {
        // solve 2(pk − p0)·x = |pk|² − |p0|², k = 1..3 (Cramer)
        let r = |k: usize| sub(p[k], p[0]);
        let (a, b, c) = (r(1), r(2), r(3));
        let rhs = [dot(a, a) / 2.0, dot(b, b) / 2.0, dot(c, c) / 2.0];
        let det = dot(a, cross(b, c));
        let x = [
            (rhs[0] * cross(b, c)[0] + rhs[1] * cross(c, a)[0] + rhs[2] * cross(a, b)[0]) / det,
            (rhs[0] * cross(b, c)[1] + rhs[1] * cross(c, a)[1] + rhs[2] * cross(a, b)[1]) / det,
            (rhs[0] * cross(b, c)[2] + rhs[1] * cross(c, a)[2] + rhs[2] * cross(a, b)[2]) / det,
        ];
        [x[0] + p[0][0], x[1] + p[0][1], x[2] + p[0][2]]
    }

    /// `edge_on_boundary` (a rotation around the edge) against the definition: some face
    /// containing ab of some live tetrahedron lies on the hull or next to a removed one. On
    /// random and integer-grid point sets with random removal sets (in order of index, so the
    /// live set is arbitrary, not only what constriction leaves).
    #[test]
    fn edge_on_boundary_matches_the_definition() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let mut seen = [0usize; 2];
        for case in 0..12 {
            let pts: Vec<crate::geom::Point3> = (0..80)
                .map(|_| {
                    if case % 2 == 0 {
                        crate::geom::Point3::new(rng.gen(), rng.gen(), rng.gen())
                    } else {
                        let g = |r: &mut rand_chacha::ChaCha8Rng| r.gen_range(0..4) as f64;
                        crate::geom::Point3::new(g(&mut rng), g(&mut rng), g(&mut rng))
                    }
                })
                .collect();
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let nt = d.tets.len();
            let kill = [0.0, 0.2, 0.5][case % 3];
            let alive: Vec<bool> = (0..nt).map(|_| !rng.gen_bool(kill)).collect();
            let st = State::new(&d, |t| alive[t], &[], Key::Gamma);
            let brute = |a: u32, b: u32| {
                (0..nt).filter(|&t| st.alive(t)).any(|t| {
                    (0..4).any(|f| {
                        let fc = st.face(t, f);
                        let n = d.neighbors[t][f];
                        fc.contains(&a) && fc.contains(&b) && (n == NONE || !st.alive(n as usize))
                    })
                })
            };
            for t in 0..nt {
                if !st.alive(t) {
                    continue;
                }
                let v = d.tets[t];
                for i in 0..4 {
                    for j in i + 1..4 {
                        let want = brute(v[i], v[j]);
                        assert_eq!(st.edge_on_boundary(t as u32, v[i], v[j]), want);
                        seen[want as usize] += 1;
                    }
                }
            }
        }
        assert!(seen[0] > 100 && seen[1] > 100, "{seen:?}");
    }

    #[test]
    fn center_side_matches_constructed_centre() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let mut checked = 0;
        for _ in 0..3000 {
            let p: [[f64; 3]; 4] = std::array::from_fn(|_| {
                [
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                ]
            });
            let vol = orient3d(p[0], p[1], p[2], p[3]);
            if vol.abs() < 1e-3 {
                continue;
            }
            let c = circumcentre(p);
            let oc = orient3d(p[0], p[1], p[2], c);
            if oc.abs() < 1e-6 {
                continue;
            }
            let expect = if (oc > 0.0) == (vol > 0.0) { 1 } else { -1 };
            assert_eq!(center_side(p[0], p[1], p[2], p[3]), expect);
            checked += 1;
        }
        assert!(checked > 1000);
        // centre exactly in the plane: l on the diametral sphere (right angle at l in 3D)
        assert_eq!(
            center_side(
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [0.0, 2.0, 0.0],
                [1.0, 2.0, 1.0]
            ),
            0
        );
        assert_eq!(
            center_side(
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [0.0, 2.0, 0.0],
                [1.0, 2.0, 1.01]
            ),
            1
        );
    }

    /// The constriction as first written, the reference of the optimized one: masks
    /// recomputed from the neighbours' `alive` flags, the rotation around an edge through the
    /// `alive` flags, a `BinaryHeap` of `MinKey` entries, every push made (no skipping of pending
    /// pairs), the corners' coordinates from a copy of the points.
    fn reference(d: &Delaunay3, until: Until, keep: &[[u32; 3]], key: Key) -> Constriction3 {
        use crate::boundary::indicator::MinKey;
        let nt = d.tets.len();
        let nv = d.points.len();
        let p: Vec<[f64; 3]> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let cells = cells_of(d);
        let keep: IdSet<[u32; 3]> = keep.iter().map(|&f| sorted3(f)).collect();
        let mut alive = vec![true; nt];
        let mut vcount = vec![0i64; nv];
        let face = |t: usize, f: usize| FACE_OF[f].map(|i| d.tets[t][i]);
        let mask = |alive: &[bool], t: usize| {
            (0..4)
                .filter(|&f| {
                    let n = d.neighbors[t][f];
                    n == NONE || !alive[n as usize]
                })
                .fold(0u8, |m, f| m | 1 << f)
        };
        let edge_on_boundary = |alive: &[bool], t: u32, a: u32, b: u32| {
            // every live tetrahedron around ab, by rotation, and their faces at ab
            let mut ring = Vec::new();
            around_edge_from(&cells, t, a, b, &mut ring);
            ring.iter().any(|&u| {
                alive[u as usize]
                    && (0..4).any(|f| {
                        let n = d.neighbors[u as usize][f];
                        face(u as usize, f).contains(&a)
                            && face(u as usize, f).contains(&b)
                            && (n == NONE || !alive[n as usize])
                    })
            })
        };
        let removable = |alive: &[bool], vcount: &[i64], t: usize, m: u8| {
            let faces: Vec<usize> = (0..4).filter(|&f| m >> f & 1 == 1).collect();
            if faces.iter().any(|&f| keep.contains(&sorted3(face(t, f)))) {
                return false;
            }
            let v = d.tets[t];
            match faces[..] {
                [f] => vcount[v[f] as usize] == 0,
                [f, g] => !edge_on_boundary(alive, t as u32, v[f], v[g]),
                _ => false,
            }
        };
        let key_of = |t: usize, m: u8| {
            let r = match key {
                Key::Gamma => d.circumsphere(t as u32).1,
                Key::MinAreaChange => 0.0,
            };
            removal_key(key, d.tets[t].map(|x| p[x as usize]), m, r)
        };
        let mut heap = std::collections::BinaryHeap::new();
        let push = |alive: &[bool],
                    vcount: &[i64],
                    heap: &mut std::collections::BinaryHeap<MinKey<(u32, u8)>>,
                    t: usize| {
            let m = mask(alive, t);
            if alive[t] && m != 0 && removable(alive, vcount, t, m) {
                heap.push(MinKey {
                    key: key_of(t, m),
                    item: (t as u32, m),
                });
            }
        };
        let on = |vcount: &[i64]| vcount.iter().filter(|&&c| c > 0).count();
        for t in 0..nt {
            for f in 0..4 {
                if d.neighbors[t][f] == NONE {
                    for v in face(t, f) {
                        vcount[v as usize] += 1;
                    }
                }
            }
        }
        for t in 0..nt {
            push(&alive, &vcount, &mut heap, t);
        }
        let mut iterations = 0;
        while until == Until::Locked || on(&vcount) < nv {
            let Some(en) = heap.pop() else { break };
            let (t, m) = (en.item.0 as usize, en.item.1);
            if !alive[t] || mask(&alive, t) != m || !removable(&alive, &vcount, t, m) {
                continue;
            }
            for f in 0..4 {
                for v in face(t, f) {
                    vcount[v as usize] += if m >> f & 1 == 1 { -1 } else { 1 };
                }
            }
            alive[t] = false;
            iterations += 1;
            let mut again: Vec<u32> = d.neighbors[t]
                .iter()
                .copied()
                .filter(|&n| n != NONE)
                .collect();
            if m.count_ones() == 2 {
                let sh: Vec<u32> = (0..4)
                    .filter(|&f| m >> f & 1 == 0)
                    .map(|f| d.tets[t][f])
                    .collect();
                let mut ring = Vec::new();
                around_edge_from(&cells, t as u32, sh[0], sh[1], &mut ring);
                again.extend(ring);
            }
            for n in again {
                push(&alive, &vcount, &mut heap, n as usize);
            }
        }
        let triangles = (0..nt)
            .filter(|&t| alive[t])
            .flat_map(|t| {
                let m = mask(&alive, t);
                (0..4)
                    .filter(move |&f| m >> f & 1 == 1)
                    .map(move |f| face(t, f))
            })
            .collect();
        Constriction3 {
            boundary_vertices: on(&vcount),
            alive,
            triangles,
            iterations,
        }
    }

    /// The constriction (boundary masks kept up to date, the 4-ary heap of packed entries,
    /// pending pushes skipped) gives exactly the reference's: same live tetrahedra, boundary
    /// triangles (in order), removal count and vertices on the boundary — for both keys and
    /// both stop rules, on a bumpy sphere with interior points (it locks), clustered cube points,
    /// an integer lattice (many equal keys: ties decided by the item) and with keep triangles.
    #[test]
    fn constriction_equals_the_reference() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let sphere = super::super::test_sets::bumpy_sphere(&mut rng, 3000);
        let lattice = super::super::test_sets::lattice(7, 6, 5);
        let clustered: Vec<crate::geom::Point3> = super::super::test_sets::cube(&mut rng, 1500)
            .iter()
            .map(|q| crate::geom::Point3::new(q.x.powi(3), q.y.powi(3), q.z.powi(3)))
            .collect();
        let (mut differs_from_locked, mut locked_short, mut with_keep) = (false, false, 0);
        for pts in [&sphere, &lattice, &clustered] {
            let d = crate::delaunay::d3::triangulate(pts).unwrap();
            // keep triangles: some interior faces (each a face of tetrahedron t)
            let keep: Vec<[u32; 3]> = (0..d.tets.len())
                .step_by(d.tets.len() / 7)
                .map(|t| FACE_OF[1].map(|i| d.tets[t][i]))
                .collect();
            for key in [Key::Gamma, Key::MinAreaChange] {
                let mut iters = Vec::new();
                for until in [Until::All, Until::Locked] {
                    for k in [&[][..], &keep[..]] {
                        let a = constrict_3d_with(&d, until, k, key);
                        let b = reference(&d, until, k, key);
                        assert_eq!(a.alive, b.alive, "{key:?} {until:?}");
                        assert_eq!(a.triangles, b.triangles, "{key:?} {until:?}");
                        assert_eq!(
                            (a.iterations, a.boundary_vertices),
                            (b.iterations, b.boundary_vertices)
                        );
                        assert!(a.iterations >= 50, "{}", a.iterations);
                        if k.is_empty() {
                            iters.push(a.iterations);
                            locked_short |= a.boundary_vertices < d.points.len();
                        } else {
                            with_keep += 1;
                        }
                    }
                }
                differs_from_locked |= iters[0] != iters[1];
            }
        }
        assert!(differs_from_locked && locked_short && with_keep == 12);
    }

    /// The circumradius from the corners is bit for bit `Delaunay3::circumsphere`'s radius
    /// (the constriction keys, and so the order of the removals, depend on it), on every
    /// tetrahedron of random, lattice and clustered sets, flat slivers of a lattice included.
    #[test]
    fn circumradius_is_the_delaunay_one() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        let sets = [
            super::super::test_sets::cube(&mut rng, 2000),
            super::super::test_sets::lattice(6, 5, 4),
            super::super::test_sets::bumpy_sphere(&mut rng, 2000),
        ];
        let mut n = 0;
        for pts in &sets {
            let d = crate::delaunay::d3::triangulate(pts).unwrap();
            for (t, v) in d.tets.iter().enumerate() {
                let r = circumradius(v.map(|x| d.points[x as usize]));
                assert_eq!(r.to_bits(), d.circumsphere(t as u32).1.to_bits(), "{t}");
                n += 1;
            }
        }
        assert!(n > 20_000, "{n}");
    }

    /// The 4-ary heap pops what a `BinaryHeap` of `MinKey<(u32, u8)>` pops, under random
    /// interleaved pushes and pops with many equal keys (ties by the item), ±0, infinities,
    /// NaN and subnormal keys.
    #[test]
    fn quad_heap_pops_in_binary_heap_order() {
        use crate::boundary::indicator::MinKey;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            5e-324,
            -5e-324,
            1.0,
            -1.0,
        ];
        for round in 0..40 {
            let mut q = QuadHeap::default();
            let mut b = std::collections::BinaryHeap::new();
            for _ in 0..3000 {
                if rng.gen_bool(if round % 2 == 0 { 0.6 } else { 0.45 }) {
                    let key = match rng.gen_range(0..3) {
                        0 => special[rng.gen_range(0..special.len())],
                        1 => rng.gen_range(-4..4) as f64 / 4.0,
                        _ => rng.gen_range(-2.0..2.0),
                    };
                    let item = (
                        rng.gen_range(0..50u32) * 97_000_001 % u32::MAX,
                        rng.gen_range(0..16u8),
                    );
                    // (the stamp, below the item, changes no order of items)
                    let stamp = rng.gen_range(0..=STAMP_SAT);
                    q.push(key, item.0, item.1, stamp);
                    b.push(MinKey { key, item });
                } else {
                    let p = q.pop().map(|(t, m, _)| (t, m));
                    assert_eq!(p, b.pop().map(|e| e.item));
                }
            }
            while let Some(e) = b.pop() {
                assert_eq!(q.pop().map(|(t, m, _)| (t, m)), Some(e.item));
            }
            assert_eq!(q.pop(), None);
        }
    }
}

//! Triangle platelets and coronas, the ordered boundary vertex set and the half-plane test
//! (Hamann 1991, §5.1, Defs 5.1–5.9, Thms 5.1–5.3, (5.9)–(5.18), Rem. 5.2; notes D.1).
//!
//! - The platelet `TP_i` is every triangle sharing a vertex with `T_i`, the corona
//!   `CP_i = TP_i \ {T_i}` (Defs 5.1, 5.2). [`classify_corona`] decides continuous (5.3),
//!   cyclic (5.4) and closed (5.5) on any triangle list (neighbours = triangles sharing an edge).
//! - The ordered boundary vertex set `B_i^ord` (Thm 5.2, counter-clockwise by Def. 5.8) is
//!   built from the half-edge structure: every corona triangle with exactly one vertex `a_k` of
//!   `T_i` contributes its edge opposite `a_k` (its *link edge*); these edges, chained, are the
//!   platelet boundary polygon (5.8), oriented like `T_i` because the mesh is. Closed corona: a
//!   cycle; open corona: a path.
//! - **Added guarantee (not in the text).** Rem. 5.2 (continuous, acyclic, half-plane test) is
//!   necessary but not sufficient for a manifold result on a general mesh (a vertex adjacent to
//!   two corners of `T_i` without being the apex of their common neighbour would become a
//!   double edge). [`ring_of`] therefore also requires the link edges to form **one simple
//!   path or cycle** (every boundary vertex once), at least 3 of them when closed, and, when
//!   the corona is open, the mesh-boundary edges at `T_i`'s corners to form one chain from the
//!   path's end back to its start through corners only. Under these conditions collapsing
//!   `T_i` to a point keeps the surface a manifold with the same χ and boundary loops (Thm 5.4).
//! - [`half_plane_test`]: (5.18), the centroid strictly left of every projected boundary
//!   segment, decided by exact `orient2d` on the projected coordinates.
//! - The origin of the new point by corona type (H p.107, Fig. 5.4 lost; notes D.3.2).
//!
//! Cost: O(Σ valence of the corners) per triangle.

use super::state::{next, State};
use crate::geom::predicates::raw::orient2d;
use crate::geom::vec::{cross, dot, norm, scale, sub};
use crate::geom::Point3;
use crate::util::NONE;

/// The corona properties of H Defs 5.3–5.5.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CoronaClass {
    /// Def. 5.3: every two corona triangles are joined by a chain of neighbouring corona
    /// triangles.
    pub continuous: bool,
    /// Def. 5.4: three corona triangles are pairwise neighbours.
    pub cyclic: bool,
    /// Def. 5.5: every corona triangle has exactly two corona neighbours.
    pub closed: bool,
}

impl CoronaClass {
    /// The corona part of Rem. 5.2: continuous and acyclic.
    pub fn admits_removal(&self) -> bool {
        self.continuous && !self.cyclic
    }
}

/// Classifies a corona given as triangle ids with a neighbour function (ids of the triangles
/// across each edge, [`NONE`] for none) and a membership test.
pub(crate) fn classify(
    corona: &[u32],
    member: impl Fn(u32) -> bool,
    nbrs: impl Fn(u32) -> [u32; 3],
) -> CoronaClass {
    let m = corona.len();
    let in_c = |t: u32| t != NONE && member(t);
    let mut closed = m > 0;
    let mut cyclic = false;
    for &t in corona {
        let n = nbrs(t);
        let cn: Vec<u32> = n.iter().copied().filter(|&u| in_c(u)).collect();
        if cn.len() != 2 {
            closed = false;
        }
        for i in 0..cn.len() {
            for j in i + 1..cn.len() {
                if nbrs(cn[i]).contains(&cn[j]) {
                    cyclic = true;
                }
            }
        }
    }
    // continuity: a walk over corona neighbours from the first triangle reaches all
    let mut seen = vec![false; m];
    let mut stack = Vec::new();
    if m > 0 {
        seen[0] = true;
        stack.push(corona[0]);
    }
    while let Some(t) = stack.pop() {
        for u in nbrs(t) {
            if let Some(k) = corona.iter().position(|&c| c == u) {
                if !seen[k] {
                    seen[k] = true;
                    stack.push(u);
                }
            }
        }
    }
    CoronaClass {
        continuous: seen.iter().all(|&s| s),
        cyclic,
        closed,
    }
}

/// Classifies the corona of triangle `t` of the triangle list `tris` (H Defs 5.1–5.5):
/// neighbours are triangles sharing an edge (two vertices), in any orientation.
///
/// ```
/// use morpho::reduce::classify_corona;
/// // a fan of 6 triangles around vertex 0 and one more ring: the corona of 0-1-2
/// let mesh = morpho::mesh::generate::disk(3, 8);
/// let c = classify_corona(&mesh.triangles, 20);
/// assert!(c.continuous);
/// ```
pub fn classify_corona(tris: &[[u32; 3]], t: usize) -> CoronaClass {
    let tv = tris[t];
    let corona: Vec<u32> = (0..tris.len())
        .filter(|&u| u != t && tris[u].iter().any(|v| tv.contains(v)))
        .map(|u| u as u32)
        .collect();
    let shares_edge = |a: [u32; 3], b: [u32; 3]| a.iter().filter(|v| b.contains(v)).count() == 2;
    let nbrs = |u: u32| {
        let mut out = [NONE; 3];
        let mut k = 0;
        for (w, tw) in tris.iter().enumerate() {
            if w as u32 != u && k < 3 && shares_edge(tris[u as usize], *tw) {
                out[k] = w as u32;
                k += 1;
            }
        }
        out
    };
    classify(&corona, |u| u as usize != t && corona.contains(&u), nbrs)
}

/// The plane frame of a triangle (H (5.9)–(5.15)): unit normal `n = d1×d2/|d1×d2|`, origin
/// `c`, `b1 = d1/|d1|`, `b2 = n × b1`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub c: [f64; 3],
    pub n: [f64; 3],
    pub b1: [f64; 3],
    pub b2: [f64; 3],
}

impl Frame {
    /// The frame of triangle `a` with origin `c` (`None` for a degenerate triangle).
    pub fn of(a: [[f64; 3]; 3], c: [f64; 3]) -> Option<Frame> {
        let (d1, d2) = (sub(a[1], a[0]), sub(a[2], a[0]));
        let nn = cross(d1, d2);
        let (ln, l1) = (norm(nn), norm(d1));
        if !(ln > 0.0 && l1 > 0.0 && ln.is_finite()) {
            return None;
        }
        let n = scale(nn, 1.0 / ln);
        let b1 = scale(d1, 1.0 / l1);
        Some(Frame {
            c,
            n,
            b1,
            b2: cross(n, b1),
        })
    }
    /// Local coordinates (u, v) of the projection of `x` (5.12)–(5.15).
    #[inline]
    pub fn uv(&self, x: [f64; 3]) -> [f64; 2] {
        let d = sub(x, self.c);
        [dot(d, self.b1), dot(d, self.b2)]
    }
    /// Signed distance of `x` from the plane (5.12).
    #[inline]
    pub fn height(&self, x: [f64; 3]) -> f64 {
        dot(sub(x, self.c), self.n)
    }
}

/// (5.18) on projected coordinates: `origin` strictly left of every segment `ring[j] →
/// ring[j+1]` (and `ring[last] → ring[0]` when `closed`), by exact `orient2d`.
pub(crate) fn half_plane_2d(ring: &[[f64; 2]], origin: [f64; 2], closed: bool) -> bool {
    let m = ring.len();
    if m < 2 {
        return false;
    }
    let segs = if closed { m } else { m - 1 };
    (0..segs).all(|j| orient2d(ring[j], ring[(j + 1) % m], origin) > 0.0)
}

/// The half-plane test of H §5.1, steps (i)–(vi): project the ordered boundary vertex set
/// `ring` (counter-clockwise, Def. 5.8) onto the plane of `tri` and decide (5.18), whether the
/// centroid lies strictly on the positive side of every line `L_j` (exact `orient2d` after
/// projection). `closed`: the polygon closes (closed corona, N = n_i); else N = n_i − 1.
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::reduce::half_plane_test;
/// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
/// let square = [[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]]
///     .map(|[x, y]| Point3::new(x, y, 0.3));
/// assert!(half_plane_test(t, &square, true));
/// let mut rev = square;
/// rev.reverse(); // clockwise: fails
/// assert!(!half_plane_test(t, &rev, true));
/// ```
pub fn half_plane_test(tri: [Point3; 3], ring: &[Point3], closed: bool) -> bool {
    let a: [[f64; 3]; 3] = tri.map(|p| p.coords.into());
    let c = centroid(a);
    let Some(f) = Frame::of(a, c) else {
        return false;
    };
    let r: Vec<[f64; 2]> = ring.iter().map(|p| f.uv(p.coords.into())).collect();
    half_plane_2d(&r, [0.0, 0.0], closed)
}

pub(crate) fn centroid(a: [[f64; 3]; 3]) -> [f64; 3] {
    std::array::from_fn(|k| (a[0][k] + a[1][k] + a[2][k]) / 3.0)
}

/// Where the new point's frame is centred (H p.107).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Origin {
    /// Closed corona: the centroid of `T_i`.
    Centroid,
    /// A corner of `T_i` (open corona with one corner on the boundary; the corner shared only
    /// with the first/last corona triangle; an ear's free corner).
    Vertex(u32),
    /// The midpoint of `T_i`'s boundary edge.
    Midpoint(u32, u32),
}

/// The removal of one triangle, before geometry: what goes, the ordered boundary vertex set
/// and the origin.
#[derive(Debug, Default)]
pub(crate) struct Ring {
    /// Ring vertices in order (a cycle without repetition, or a path from its start to its end).
    pub verts: Vec<u32>,
    /// For ring edge `j` (`verts[j] → verts[j+1]`): the half-edge outside the platelet
    /// across it ([`NONE`] on the mesh boundary).
    pub outer: Vec<u32>,
    pub closed: bool,
    /// Every triangle that disappears: `T_i` first, then the rest of the corona part replaced.
    pub removed: Vec<u32>,
    /// The mesh-boundary corners of `T_i` (open corona), in boundary order.
    pub chain: Vec<u32>,
    /// Corners of `T_i` on the mesh boundary.
    pub any_boundary: bool,
}

/// Scratch buffers of [`ring_of`] (reused across calls: no allocation in the hot loop).
#[derive(Default)]
pub(crate) struct Scratch {
    fan: Vec<u32>,
    link: Vec<(u32, u32, u32)>,
    bnd: Vec<(u32, u32)>,
    pub corona: Vec<u32>,
    pub mark: Vec<u32>,
    pub stamp: u32,
}

/// The ring, removed set and corona class of triangle `t`, or `None` when removing it would
/// break the manifold (see the module documentation) — the topological part of Rem. 5.2.
pub(crate) fn ring_of(s: &State, t: u32, sc: &mut Scratch, ring: &mut Ring) -> Option<CoronaClass> {
    let a = s.tri[t as usize];
    ring.verts.clear();
    ring.outer.clear();
    ring.removed.clear();
    ring.chain.clear();
    ring.removed.push(t);
    sc.link.clear();
    sc.bnd.clear();
    sc.corona.clear();
    ring.any_boundary = false;
    let is_t = |v: u32| a.contains(&v);
    for &ak in &a {
        ring.any_boundary |= s.fan(ak, &mut sc.fan);
        for &h in &sc.fan {
            let u = h / 3;
            if u == t {
                continue;
            }
            let tv = s.tri[u as usize];
            let k = tv.iter().filter(|&&v| is_t(v)).count();
            match k {
                1 => {
                    let hn = next(h);
                    sc.link.push((s.from(hn), s.to(hn), s.opp[hn as usize]));
                    ring.removed.push(u);
                    sc.corona.push(u);
                }
                2 => {
                    if !sc.corona.contains(&u) {
                        ring.removed.push(u);
                        sc.corona.push(u);
                    }
                }
                _ => return None, // the same three corners twice
            }
        }
    }
    for &u in &ring.removed {
        for i in 0..3 {
            let h = 3 * u + i;
            if s.opp[h as usize] == NONE {
                let (x, y) = (s.from(h), s.to(h));
                if is_t(x) || is_t(y) {
                    sc.bnd.push((x, y));
                }
            }
        }
    }
    let m = sc.link.len();
    if m == 0 {
        return None;
    }
    // every vertex at most once as a start and once as an end of a link edge
    for i in 0..m {
        for j in i + 1..m {
            if sc.link[i].0 == sc.link[j].0 || sc.link[i].1 == sc.link[j].1 {
                return None;
            }
        }
    }
    let start = (0..m)
        .find(|&i| !sc.link.iter().any(|l| l.1 == sc.link[i].0))
        .unwrap_or(0);
    let closed = !ring.any_boundary;
    let mut i = start;
    for _ in 0..m {
        let (w, u, o) = sc.link[i];
        ring.verts.push(w);
        ring.outer.push(o);
        match sc.link.iter().position(|l| l.0 == u) {
            Some(j) => i = j,
            None => {
                ring.verts.push(u);
                break;
            }
        }
    }
    if ring.outer.len() != m {
        return None; // more than one path or cycle
    }
    let is_cycle = ring.verts.len() == m;
    if closed != is_cycle || (closed && m < 3) {
        return None;
    }
    // ring vertices distinct (also across start and end of a path)
    for i in 0..ring.verts.len() {
        if ring.verts[i + 1..].contains(&ring.verts[i]) {
            return None;
        }
    }
    if !closed && !boundary_chain(sc, ring, &is_t) {
        return None;
    }
    ring.closed = closed;
    // the thesis's corona predicates (Defs 5.3–5.5) with stamps for membership
    sc.stamp = sc.stamp.wrapping_add(1);
    if sc.stamp == 0 {
        sc.mark.iter_mut().for_each(|m| *m = 0);
        sc.stamp = 1;
    }
    if sc.mark.len() < s.tri.len() {
        sc.mark.resize(s.tri.len(), 0);
    }
    for &u in &sc.corona {
        sc.mark[u as usize] = sc.stamp;
    }
    let (mark, stamp) = (&sc.mark, sc.stamp);
    let class = classify(
        &sc.corona,
        |u| mark[u as usize] == stamp,
        |u| {
            std::array::from_fn(|i| {
                let o = s.opp[3 * u as usize + i];
                if o == NONE {
                    NONE
                } else {
                    o / 3
                }
            })
        },
    );
    Some(class)
}

/// Open corona: the boundary edges at the corners must run from the ring's end back to its
/// start through corners only, each corner at most once; fills `ring.chain`.
fn boundary_chain(sc: &Scratch, ring: &mut Ring, is_t: &impl Fn(u32) -> bool) -> bool {
    let (s0, e) = (ring.verts[0], *ring.verts.last().unwrap());
    let mut cur = e;
    for step in 0..sc.bnd.len() {
        let Some(&(_, y)) = sc.bnd.iter().find(|b| b.0 == cur) else {
            return false;
        };
        if y == s0 {
            return step + 1 == sc.bnd.len() && !ring.chain.is_empty();
        }
        if !is_t(y) || ring.chain.contains(&y) {
            return false;
        }
        ring.chain.push(y);
        cur = y;
    }
    false
}

/// The origin of the new point's frame by corona type (H p.107; notes D.3.2): `valence`
/// gives the number of triangles at a corner.
pub(crate) fn origin_of(ring: &Ring, mut valence: impl FnMut(u32) -> usize) -> Origin {
    if ring.closed {
        return Origin::Centroid;
    }
    match ring.chain.as_slice() {
        [v] => Origin::Vertex(*v),
        [a, b] => match (valence(*a) == 2, valence(*b) == 2) {
            (true, false) => Origin::Vertex(*a),
            (false, true) => Origin::Vertex(*b),
            _ => Origin::Midpoint(*a, *b),
        },
        [_, m, _] => Origin::Vertex(*m),
        _ => Origin::Centroid,
    }
}

//! 3D Delaunay tetrahedralization (Veltkamp 1992 §2.2.8–2.2.9: Delaunay triangulation and convex
//! hull; Dorgerloh et al. §2: Bowyer–Watson insertion, here with exact predicates instead of
//! constructed circumcentres).
//!
//! Size (over 800 lines): one algorithm — the Bowyer–Watson engine with its flat arrays, work
//! buffers and symbolic perturbation, and the queries and invariant checks on its result.
//!
//! # Algorithm
//! Incremental Bowyer–Watson insertion:
//! 1. Input points are checked (NaN/inf → error), sorted lexicographically and duplicates merged;
//!    the *canonical index* of a vertex is its rank in that order (so vertex ids do not depend on
//!    the input order).
//! 2. Insertion order: biased randomized insertion order (BRIO, rounds of doubling size from a
//!    fixed-seed shuffle) with every round sorted along a 3D Hilbert curve.
//! 3. The triangulation is stored in flat arrays (`[u32; 4]` vertices and `[u32; 4]` neighbour
//!    codes `tet << 2 | face` per tetrahedron). The convex hull is closed by *ghost* tetrahedra
//!    `[a, b, c, ∞]` (∞ always in slot 3), so points outside the hull need no special case.
//! 4. Location: remembering stochastic visibility walk from the last created tetrahedron, with the
//!    exact `orient3d`.
//! 5. Cavity: breadth-first search of the tetrahedra in conflict (exact `insphere`; for a ghost,
//!    "strictly beyond the hull face", or, when coplanar with it, the conflict of its finite
//!    neighbour), then the star-shaped re-triangulation joining the new point to every boundary
//!    facet. New tetrahedra are linked to each other through a small generation-stamped hash
//!    table on their shared cavity-boundary edges. Freed tetrahedra are reused through a free
//!    list; all work buffers are reused, so an insertion allocates nothing in the steady state.
//!    The cavity search prefetches the four neighbours of each popped tetrahedron. (A
//!    transparent-huge-page hint on the arrays was tried and measured slower: the kernel's
//!    zeroing of 2 MiB pages cost more than the TLB misses it saved, see `bench/README.md`.)
//!
//! # Degeneracies
//! Duplicates are merged. Cospherical ties (`insphere == 0` exactly) are broken by symbolic
//! perturbation of the lifting map (Devillers & Teillaud, "Perturbations for Delaunay and weighted
//! Delaunay 3D triangulations", 2011): vertex `v` is lifted to `|v|² + ε^(N−v)`, so the vertex with
//! the largest canonical index has the dominant perturbation. The sign of the perturbed
//! determinant is the sign of the first non-zero cofactor, i.e. of an exact `orient3d` of four of
//! the five points, taken in decreasing canonical index. Because the lifted points of a sphere are
//! in convex position, the perturbation hides no vertex, and the result is the unique Delaunay
//! triangulation of the perturbed set: deterministic and independent of the insertion order.
//! Coplanar points on the hull are handled through the coplanar ghost rule above, which equals
//! the perturbed in-circle test inside the plane of the hull face.
//! All-collinear or all-coplanar input is not an error: the result has no tetrahedra and
//! [`Delaunay3::degenerate`] says why.
//!
//! # Predicates
//! Shewchuk's adaptive `orient3d`/`insphere` (via `geom::predicates`) when every coordinate is 0
//! or within 2^±120 (no overflow/underflow possible), the in-sphere test first through a
//! semi-static bound on the same floating-point determinant ([`insphere_semi_static`]: no
//! permanent to evaluate; undecided tests go on to the full cascade); an exact i128 in-sphere
//! when all coordinates are integers of magnitude ≤ 2^20 (lattices hit exact ties constantly);
//! otherwise (e.g. 1e-300 or 1e300) the big-integer determinants; all three in
//! [`crate::geom::exact`].
//!
//! # Complexity
//! Expected `O(n log n)` for points spread in space (`O(n²)` worst case, e.g. points on the
//! moment curve, where the output itself is quadratic). Memory: about 7.7 tetrahedra (with
//! ghosts) per point during the construction, 36 bytes each; measured peak ≈ 370 bytes per
//! point for 1M uniform points (see `examples/bench_delaunay3d.rs`).

use super::DelaunayError;
use crate::geom::exact::{
    insphere_exact, insphere_small_int, orient2d_exact, orient3d_exact, safe_range,
};
use crate::geom::predicates::insphere_sign;
use crate::geom::predicates::raw::orient3d;
use crate::geom::Point3;
use crate::util::hilbert::hilbert3;
use crate::util::{Rng, NONE};

type Result<T, E = DelaunayError> = std::result::Result<T, E>;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use std::collections::HashSet;

/// The infinite vertex (internal).
const INF: u32 = u32::MAX;
/// Marks a freed tetrahedron slot (internal, in vertex slot 0).
const FREE: u32 = u32::MAX - 1;
/// Most tetrahedra (including ghosts) during the construction: neighbour codes are `tet << 2 | face`.
const MAX_TETS: usize = 1 << 30;

/// Vertex positions of the face opposite corner `i`, ordered so that
/// `orient3d(face…, v_i) > 0` for a positive tetrahedron, i.e. oriented outward.
pub const FACE_OF: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];

/// A 3D Delaunay tetrahedralization.
#[derive(Debug, Clone)]
pub struct Delaunay3 {
    /// The distinct input points, sorted lexicographically by (x, y, z).
    pub points: Vec<Point3>,
    /// For every input point, its vertex in [`Self::points`].
    pub vertex_of_input: Vec<u32>,
    /// For every vertex, the first input point at that position.
    pub input_of_vertex: Vec<u32>,
    /// Tetrahedra, positively oriented: `geom::orient3d(a, b, c, d) > 0` (Shewchuk's convention,
    /// i.e. `d` lies on the side of plane `abc` from which `a, b, c` appear clockwise).
    pub tets: Vec<[u32; 4]>,
    /// `neighbors[t][i]`: the tetrahedron across the face opposite corner `i` of `t`, or [`NONE`]
    /// on the hull.
    pub neighbors: Vec<[u32; 4]>,
    /// Convex hull triangles, oriented outward (right-hand normal points out of the hull).
    pub hull: Vec<[u32; 3]>,
    /// Number of input points merged into an earlier identical point.
    pub duplicates: usize,
    /// Why there are no tetrahedra ("all points coplanar", "all points collinear", …), if so.
    pub degenerate: Option<String>,
    /// One incident tetrahedron per vertex ([`NONE`] when there are no tetrahedra).
    pub vertex_tet: Vec<u32>,
}

/// A triangle of the tetrahedralization with its (one or two) tetrahedra.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Face3 {
    /// The vertices, oriented outward of `tets[0]`.
    pub v: [u32; 3],
    /// The tetrahedron on the inner side of `v`, and the one on the other side ([`NONE`] on the hull).
    pub tets: [u32; 2],
}

#[inline]
fn arr(p: &Point3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// Sign of the symbolically perturbed `insphere(q0, q1, q2, q3, q4)` when the exact value is 0;
/// `ids` are the canonical indices of the five points (all distinct), `q` their coordinates.
/// Requires `orient3d(q0..q3) != 0`. Returns true for "inside".
pub(crate) fn perturbed_insphere(q: &[[f64; 3]; 5], ids: &[u32; 5]) -> bool {
    let mut idx = [0usize, 1, 2, 3, 4];
    idx.sort_unstable_by(|a, b| ids[*b].cmp(&ids[*a]));
    for &k in &idx {
        let s = if k == 4 {
            -orient3d_exact(q[0], q[1], q[2], q[3])
        } else {
            let mut w = [q[0], q[1], q[2], q[3]];
            w[k] = q[4];
            orient3d_exact(w[0], w[1], w[2], w[3])
        };
        if s != 0.0 {
            return s > 0.0;
        }
    }
    false
}

/// Shewchuk's stage-A error constant for `insphere` ((16 + 224u)u, u = 2^-53), times the 24
/// products of the permanent, with a relative slack of 2^-40 for the roundings of the bound
/// itself (see [`insphere_semi_static`]).
const SEMI_STATIC_ISP: f64 = 24.0 * (16.0 + 224.0 * U53) * U53 * (1.0 + 1.0 / (1u64 << 40) as f64);
/// The unit roundoff of `f64`.
const U53: f64 = f64::EPSILON / 2.0;

/// Sign of `insphere(a, b, c, d, e)` (positive: `e` inside the sphere through the positively
/// oriented `a, b, c, d`) when a *semi-static* bound certifies it, else 0 (undecided: the caller
/// runs the full cascade [`insphere_sign`]). The determinant is Shewchuk's stage-A expression on
/// the rounded differences `X = fl(p − e)`; only its error bound is cheaper.
///
/// May assume: every coordinate is 0 or within 2^±120 (`geom::exact::safe_range`, the
/// Builder's `safe`), so every non-zero difference lies in [2^-172, 2^121] and no product below
/// under- or overflows.
///
/// Argument (CGAL's filtered kernels use a bound of the same shape; this one is derived here):
/// Shewchuk's stage A certifies the sign when `|det| > errA · P`, where `P` is his permanent
/// evaluated in floating point and errA = (16 + 224u)u. `P` is a sum of 24 non-negative terms
/// `|X_px · X_qy| · |X_rz| · lift_s`, each at most `Mx · My · Mz · Λ` with `Mx = max |X_kx|`
/// (likewise y, z) and `Λ = max lift ≤ Mx² + My² + Mz²`; evaluated in floating point (depth
/// ≤ 10, non-negative operands, no underflow) it is at most (1 + u)^10 · 24 · B, with
/// `B = Mx · My · Mz · (Mx² + My² + Mz²)`. `B` computed in floating point (5 roundings) is at
/// least (1 − u)^5 · B. So `|det| > fl(24 · errA · (1 + 2^-40) · fl(B))` implies
/// `|det| > errA · P`: the sign is the one stage A would certify, i.e. the exact sign. When some
/// `M` is 0 the determinant evaluates to exactly 0 and nothing is certified.
#[inline(always)]
fn insphere_semi_static(
    pa: [f64; 3],
    pb: [f64; 3],
    pc: [f64; 3],
    pd: [f64; 3],
    pe: [f64; 3],
) -> i32 {
    let [aex, aey, aez] = [pa[0] - pe[0], pa[1] - pe[1], pa[2] - pe[2]];
    let [bex, bey, bez] = [pb[0] - pe[0], pb[1] - pe[1], pb[2] - pe[2]];
    let [cex, cey, cez] = [pc[0] - pe[0], pc[1] - pe[1], pc[2] - pe[2]];
    let [dex, dey, dez] = [pd[0] - pe[0], pd[1] - pe[1], pd[2] - pe[2]];
    let ab = aex * bey - bex * aey;
    let bc = bex * cey - cex * bey;
    let cd = cex * dey - dex * cey;
    let da = dex * aey - aex * dey;
    let ac = aex * cey - cex * aey;
    let bd = bex * dey - dex * bey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    let mx = aex.abs().max(bex.abs()).max(cex.abs().max(dex.abs()));
    let my = aey.abs().max(bey.abs()).max(cey.abs().max(dey.abs()));
    let mz = aez.abs().max(bez.abs()).max(cez.abs().max(dez.abs()));
    let bound = SEMI_STATIC_ISP * ((mx * my * mz) * (mx * mx + my * my + mz * mz));
    (det > bound) as i32 - (-det > bound) as i32
}

/// A record of a cavity boundary facet: the new tetrahedron's vertices (old tet with the new
/// point in slot `i`) and the outside neighbour code.
#[derive(Clone, Copy)]
struct Bnd {
    v: [u32; 4],
    i: u8,
    out: u32,
}

struct Builder<'a> {
    /// Points in insertion order (internal vertex ids).
    pts: &'a [[f64; 3]],
    /// Canonical (lexicographic) index of each internal vertex: the perturbation rank.
    rank: &'a [u32],
    /// All coordinates are in the safe range of Shewchuk's predicates.
    safe: bool,
    /// Set when the tetrahedron count reached [`MAX_TETS`].
    overflow: bool,
    /// All coordinates are integers of magnitude ≤ 2^20 (lattices): exact integer in-sphere.
    small_int: bool,
    tv: Vec<[u32; 4]>,
    tn: Vec<[u32; 4]>,
    stamp: Vec<u32>,
    free: Vec<u32>,
    last: u32,
    rng: Rng,
    stack: Vec<u32>,
    conflict: Vec<u32>,
    bnd: Vec<Bnd>,
    table: Vec<(u64, u32, u32)>,
    gen: u32,
}

impl<'a> Builder<'a> {
    #[inline]
    fn p(&self, v: u32) -> [f64; 3] {
        self.pts[v as usize]
    }

    #[inline]
    fn rand(&mut self) -> u64 {
        self.rng.next_u64()
    }

    fn alloc(&mut self) -> u32 {
        if let Some(t) = self.free.pop() {
            self.stamp[t as usize] = 0;
            t
        } else {
            if self.tv.len() >= MAX_TETS {
                // neighbour codes `tet << 2 | face` would overflow: abandon (checked by caller)
                self.overflow = true;
                return 0;
            }
            self.tv.push([FREE; 4]);
            self.tn.push([0; 4]);
            self.stamp.push(0);
            (self.tv.len() - 1) as u32
        }
    }

    #[inline]
    fn o3(&self, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
        if self.safe {
            orient3d(a, b, c, d)
        } else {
            orient3d_exact(a, b, c, d)
        }
    }

    /// Conflict of the finite tetrahedron `t` with point `p` (exact, perturbed).
    #[inline(always)]
    fn finite_conflict(&self, t: u32, p: u32) -> bool {
        let v = self.tv[t as usize];
        let q = [
            self.p(v[0]),
            self.p(v[1]),
            self.p(v[2]),
            self.p(v[3]),
            self.p(p),
        ];
        let s = if self.small_int {
            insphere_small_int(&q)
        } else if self.safe {
            let f = insphere_semi_static(q[0], q[1], q[2], q[3], q[4]);
            if f != 0 {
                return f > 0;
            }
            insphere_sign(q[0], q[1], q[2], q[3], q[4]) as f64
        } else {
            insphere_exact(q[0], q[1], q[2], q[3], q[4])
        };
        if s != 0.0 {
            return s > 0.0;
        }
        let r = |x: u32| self.rank[x as usize];
        perturbed_insphere(&q, &[r(v[0]), r(v[1]), r(v[2]), r(v[3]), r(p)])
    }

    #[inline(always)]
    fn in_conflict(&self, t: u32, p: u32) -> bool {
        let v = self.tv[t as usize];
        if v[3] == INF {
            let o = self.o3(self.p(v[0]), self.p(v[1]), self.p(v[2]), self.p(p));
            if o != 0.0 {
                return o > 0.0;
            }
            return self.finite_conflict(self.tn[t as usize][3] >> 2, p);
        }
        self.finite_conflict(t, p)
    }

    /// Visibility walk to a tetrahedron in conflict with `p` (a finite one containing it, or a
    /// ghost whose hull face sees it strictly).
    fn locate(&mut self, p: u32) -> u32 {
        let mut t = self.last;
        if self.tv[t as usize][3] == INF {
            t = self.tn[t as usize][3] >> 2;
        }
        let pp = self.p(p);
        let mut prev = NONE;
        let mut steps = 0usize;
        'walk: loop {
            let v = self.tv[t as usize];
            if v[3] == INF {
                return t;
            }
            steps += 1;
            if steps > 4 * self.tv.len() + 100 {
                break;
            }
            let q = [self.p(v[0]), self.p(v[1]), self.p(v[2]), self.p(v[3])];
            let r = self.rand() as usize;
            for k in 0..4 {
                let i = (r + k) & 3;
                let n = self.tn[t as usize][i] >> 2;
                if n == prev {
                    continue;
                }
                let mut w = q;
                w[i] = pp;
                if self.o3(w[0], w[1], w[2], w[3]) < 0.0 {
                    prev = t;
                    t = n;
                    continue 'walk;
                }
            }
            return t;
        }
        // Fallback (never expected): scan for a tetrahedron in conflict.
        (0..self.tv.len() as u32)
            .find(|&t| self.tv[t as usize][0] != FREE && self.in_conflict(t, p))
            .unwrap_or(self.last)
    }

    fn insert(&mut self, p: u32, k: u32) {
        let t0 = self.locate(p);
        let cs = 2 * k + 2;
        let ns = cs + 1;
        self.stack.clear();
        self.conflict.clear();
        self.bnd.clear();
        self.stamp[t0 as usize] = cs;
        self.stack.push(t0);
        self.conflict.push(t0);
        while let Some(t) = self.stack.pop() {
            let codes = self.tn[t as usize];
            // the four neighbours' stamps and corners are read next, in an order that depends
            // on the tests: ask for all of them at once (a hint only)
            for c in codes {
                prefetch(&self.stamp, c >> 2);
                prefetch(&self.tv, c >> 2);
            }
            for (i, &code) in codes.iter().enumerate() {
                let u = code >> 2;
                let su = self.stamp[u as usize];
                if su == cs {
                    continue;
                }
                if su != ns {
                    if self.in_conflict(u, p) {
                        self.stamp[u as usize] = cs;
                        self.stack.push(u);
                        self.conflict.push(u);
                        continue;
                    }
                    self.stamp[u as usize] = ns;
                }
                let mut v = self.tv[t as usize];
                v[i] = p;
                self.bnd.push(Bnd {
                    v,
                    i: i as u8,
                    out: code,
                });
            }
        }
        for j in 0..self.conflict.len() {
            let t = self.conflict[j];
            self.tv[t as usize][0] = FREE;
            self.free.push(t);
        }
        // Hash table on cavity-boundary edges.
        let need = (4 * self.bnd.len()).next_power_of_two().max(64);
        if self.table.len() < need {
            self.table = vec![(0, 0, 0); need];
            self.gen = 0;
        }
        self.gen = self.gen.wrapping_add(1);
        if self.gen == 0 {
            self.table.iter_mut().for_each(|e| e.2 = 0);
            self.gen = 1;
        }
        let mask = self.table.len() - 1;
        let bits = self.table.len().trailing_zeros();
        let mut last = NONE;
        for b in 0..self.bnd.len() {
            let Bnd { v, i, out } = self.bnd[b];
            let i = i as usize;
            let n = self.alloc();
            self.tv[n as usize] = v;
            self.tn[n as usize][i] = out;
            self.tn[(out >> 2) as usize][(out & 3) as usize] = (n << 2) | i as u32;
            if v[3] != INF || last == NONE {
                last = n;
            }
            for j in 0..4 {
                if j == i {
                    continue;
                }
                // the two slots other than i and j
                let (sa, sc) = EDGE_AFTER[i][j];
                let (a, c) = (v[sa as usize], v[sc as usize]);
                let key = if a < c {
                    ((a as u64) << 32) | c as u64
                } else {
                    ((c as u64) << 32) | a as u64
                };
                let mut h = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits)) as usize;
                loop {
                    let e = self.table[h];
                    if e.2 != self.gen {
                        self.table[h] = (key, (n << 2) | j as u32, self.gen);
                        break;
                    }
                    if e.0 == key {
                        let m = e.1;
                        self.tn[n as usize][j] = m;
                        self.tn[(m >> 2) as usize][(m & 3) as usize] = (n << 2) | j as u32;
                        // tombstone: key can never match again
                        self.table[h].0 = u64::MAX;
                        break;
                    }
                    h = (h + 1) & mask;
                }
            }
        }
        self.last = last;
    }
}

/// `EDGE_AFTER[i][j]` (`j ≠ i`): the slots `(x, y)` that follow slot `i` in the outward cyclic
/// order [`FACE_OF`]`[j]` of the face opposite corner `j` (the face is `(i, x, y)` up to rotation).
const EDGE_AFTER: [[(u8, u8); 4]; 4] = {
    let mut t = [[(0u8, 0u8); 4]; 4];
    let mut i = 0;
    while i < 4 {
        let mut j = 0;
        while j < 4 {
            if j != i {
                let f = FACE_OF[j];
                let mut k = 0;
                while f[k] != i {
                    k += 1;
                }
                t[i][j] = (f[(k + 1) % 3] as u8, f[(k + 2) % 3] as u8);
            }
            j += 1;
        }
        i += 1;
    }
    t
};

/// Asks the processor to load `v[i]` into the cache (a hint only; `i` need not be in range).
#[inline(always)]
fn prefetch<T>(v: &[T], i: u32) {
    #[cfg(target_arch = "x86_64")]
    #[allow(unused_unsafe)]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // no bounds check: the address is only a hint and is never dereferenced
        let x = v.as_ptr().wrapping_add(i as usize);
        // SAFETY: prefetching is a hint, valid for any address (it never faults).
        unsafe { _mm_prefetch::<_MM_HINT_T0>(x as *const i8) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (v, i);
}

/// BRIO insertion order of `pts` (fixed seed), each round Hilbert-sorted.
pub(crate) fn brio_order(pts: &[[f64; 3]]) -> Vec<u32> {
    let n = pts.len();
    let mut order: Vec<u32> = (0..n as u32).collect();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x5eed_de1a);
    order.shuffle(&mut rng);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    const BITS: u32 = 16;
    let scale: Vec<f64> = (0..3)
        .map(|k| {
            let e = hi[k] - lo[k];
            if e > 0.0 && e.is_finite() {
                ((1u32 << BITS) - 1) as f64 / e
            } else {
                0.0
            }
        })
        .collect();
    let key = |i: u32| -> u64 {
        let p = pts[i as usize];
        let mut c = [0u32; 3];
        for k in 0..3 {
            let v = ((p[k] - lo[k]) * scale[k]).clamp(0.0, ((1u32 << BITS) - 1) as f64);
            c[k] = if v.is_finite() { v as u32 } else { 0 };
        }
        hilbert3(c, BITS)
    };
    let mut keyed: Vec<(u64, u32)> = order.iter().map(|&i| (key(i), i)).collect();
    // rounds [0, n/2^r), …, [n/4, n/2), [n/2, n)
    let mut end = n;
    while end > 0 {
        let start = if end <= 256 { 0 } else { end / 2 };
        keyed[start..end].sort_unstable();
        end = start;
    }
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// Distinct sorted points, vertex of each input point, first input point of each vertex.
pub(crate) type Dedup<const D: usize> = (Vec<[f64; D]>, Vec<u32>, Vec<u32>);

/// Checks the input and merges duplicates: returns the sorted distinct points, the vertex of each
/// input point and the first input point of each vertex.
pub(crate) fn dedup_sorted<const D: usize>(coords: &[[f64; D]]) -> Result<Dedup<D>> {
    if coords.is_empty() {
        return Err(DelaunayError::NoPoints { dim: D });
    }
    if coords.len() >= u32::MAX as usize / 8 {
        return Err(DelaunayError::TooManyPoints {
            found: coords.len(),
            dim: D,
        });
    }
    let mut pts: Vec<[f64; D]> = Vec::with_capacity(coords.len());
    for (i, c) in coords.iter().enumerate() {
        if c.iter().any(|x| !x.is_finite()) {
            return Err(DelaunayError::NonFinite {
                index: i,
                coords: vec![],
            });
        }
        // normalise -0.0 to 0.0 so that equal points compare equal
        let mut q = *c;
        for x in q.iter_mut() {
            *x += 0.0;
        }
        pts.push(q);
    }
    let idx = lex_order(&pts);
    let mut uniq: Vec<[f64; D]> = Vec::new();
    let mut vertex_of_input = vec![0u32; pts.len()];
    let mut input_of_vertex = Vec::new();
    for &i in &idx {
        let p = pts[i as usize];
        if uniq.last() != Some(&p) {
            uniq.push(p);
            input_of_vertex.push(i);
        }
        vertex_of_input[i as usize] = (uniq.len() - 1) as u32;
    }
    Ok((uniq, vertex_of_input, input_of_vertex))
}

/// An unsigned key with the order of the finite, non-NaN `x` (−0.0 must have been normalised
/// to 0.0): the sign bit flipped for non-negative values, all bits flipped for negative ones.
#[inline]
fn order_key(x: f64) -> u64 {
    let b = x.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | 1 << 63
    }
}

/// The indices of `pts` in lexicographic order of the coordinates, ties by index (a total order:
/// the permutation is unique). Sorts (key, index) records, so no comparison reaches back into
/// `pts`. May assume: finite coordinates, no −0.0.
fn lex_order<const D: usize>(pts: &[[f64; D]]) -> Vec<u32> {
    let mut rec: Vec<([u64; D], u32)> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| (p.map(order_key), i as u32))
        .collect();
    if rec.len() >= 1 << 15 {
        use rayon::slice::ParallelSliceMut;
        rec.par_sort_unstable();
    } else {
        rec.sort_unstable();
    }
    rec.into_iter().map(|(_, i)| i).collect()
}

/// The order of [`lex_order`] by an index sort with comparisons on the points (main's method
/// until December 2026; kept as the oracle of the lockstep test).
#[cfg(test)]
fn old_order<const D: usize>(pts: &[[f64; D]]) -> Vec<u32> {
    let mut idx: Vec<u32> = (0..pts.len() as u32).collect();
    let cmp = |&a: &u32, &b: &u32| {
        let (pa, pb) = (&pts[a as usize], &pts[b as usize]);
        for k in 0..D {
            match pa[k].partial_cmp(&pb[k]) {
                Some(std::cmp::Ordering::Equal) | None => continue,
                Some(o) => return o,
            }
        }
        a.cmp(&b)
    };
    // a total order (ties by index): the parallel sort gives the same permutation
    if idx.len() >= 1 << 15 {
        use rayon::slice::ParallelSliceMut;
        idx.par_sort_unstable_by(cmp);
    } else {
        idx.sort_unstable_by(cmp);
    }
    idx
}

/// Computes the Delaunay tetrahedralization of `points` on one thread (the facade's
/// [`triangulate_3d`](crate::delaunay::triangulate_3d) calls it, or the parallel split of
/// `par3.rs` for large inputs when there are several threads: same tetrahedron set).
///
/// Positively oriented tetrahedra whose circumspheres contain no vertex, with neighbours and the
/// outward hull triangles. Duplicates are merged; co-spherical ties are broken by symbolic
/// perturbation, so the result depends on the point set only. Bowyer–Watson insertion in a
/// biased randomized Hilbert order with exact predicates at any scale: expected O(n log n)
/// for points spread in space, O(n²) worst case (points on the moment curve, where the output
/// is quadratic); about 370 bytes per point at the peak.
///
/// Errors: empty input ([`DelaunayError::NoPoints`]), a NaN or infinite coordinate
/// ([`DelaunayError::NonFinite`]), more than 2³⁰ tetrahedra. Collinear or coplanar input (or
/// fewer than four distinct points) gives `Ok` with no tetrahedra and
/// [`Delaunay3::degenerate`] set.
///
/// ```rust
/// use morpho::delaunay::triangulate_3d;
/// use morpho::geom::Point3;
/// // a tetrahedron with a point inside: four tetrahedra, the hull keeps the four faces
/// let p = [[0., 0., 0.], [4., 0., 0.], [0., 4., 0.], [0., 0., 4.], [1., 1., 1.]]
///     .map(|[x, y, z]| Point3::new(x, y, z));
/// let d = triangulate_3d(&p).unwrap();
/// assert_eq!(d.tets.len(), 4);
/// assert_eq!(d.hull.len(), 4);
/// assert!(d.check_delaunay_local().is_ok() && d.check_topology().is_ok());
/// // coplanar input is not an error
/// let flat = triangulate_3d(&p[..3]).unwrap();
/// assert!(flat.tets.is_empty() && flat.degenerate.is_some());
/// ```
pub fn triangulate(points: &[Point3]) -> Result<Delaunay3> {
    let coords: Vec<[f64; 3]> = points.iter().map(arr).collect();
    let (pts, vertex_of_input, input_of_vertex) = dedup_sorted(&coords)?;
    drop(coords);
    let duplicates = points.len() - pts.len();
    let core = build_sorted(&pts)?;
    Ok(Delaunay3::from_core(
        &pts,
        vertex_of_input,
        input_of_vertex,
        duplicates,
        core,
    ))
}

/// The engine's result on distinct, lexicographically sorted points (vertex = index): positive
/// tetrahedra in the engine's order, their neighbours ([`NONE`] on the hull), the outward hull
/// triangles, or why there are no tetrahedra. Used by [`triangulate`] and by the parallel
/// merge in `par3`, which runs it on halves and on the seam set.
pub(crate) struct Core {
    pub tets: Vec<[u32; 4]>,
    pub neighbors: Vec<[u32; 4]>,
    pub hull: Vec<[u32; 3]>,
    pub degenerate: Option<String>,
}

impl Core {
    fn degenerate(why: &str) -> Core {
        Core {
            tets: Vec::new(),
            neighbors: Vec::new(),
            hull: Vec::new(),
            degenerate: Some(why.into()),
        }
    }
}

impl Delaunay3 {
    /// The result type from the engine's [`Core`] on the sorted distinct points `pts`.
    pub(crate) fn from_core(
        pts: &[[f64; 3]],
        vertex_of_input: Vec<u32>,
        input_of_vertex: Vec<u32>,
        duplicates: usize,
        core: Core,
    ) -> Delaunay3 {
        let mut vertex_tet = vec![NONE; pts.len()];
        for (t, v) in core.tets.iter().enumerate() {
            for &x in v {
                vertex_tet[x as usize] = t as u32;
            }
        }
        Delaunay3 {
            points: pts.iter().map(|p| Point3::new(p[0], p[1], p[2])).collect(),
            vertex_of_input,
            input_of_vertex,
            tets: core.tets,
            neighbors: core.neighbors,
            hull: core.hull,
            duplicates,
            degenerate: core.degenerate,
            vertex_tet,
        }
    }
}

/// Bowyer–Watson on distinct, lexicographically sorted points: the canonical index of a vertex
/// is its index in `pts` (only the relative order of the indices matters to the perturbation,
/// so a subsequence of a sorted set is triangulated as a subset of the whole).
pub(crate) fn build_sorted(pts: &[[f64; 3]]) -> Result<Core> {
    if pts.is_empty() {
        return Ok(Core::degenerate("no points"));
    }
    let order = brio_order(pts);
    // initial simplex
    let a = order[0];
    if pts.len() == 1 {
        return Ok(Core::degenerate("a single distinct point"));
    }
    let b = order[1];
    let (pa, pb) = (pts[a as usize], pts[b as usize]);
    let collinear = |c: &[f64; 3]| {
        orient2d_exact([pa[0], pa[1]], [pb[0], pb[1]], [c[0], c[1]]) == 0.0
            && orient2d_exact([pa[1], pa[2]], [pb[1], pb[2]], [c[1], c[2]]) == 0.0
            && orient2d_exact([pa[0], pa[2]], [pb[0], pb[2]], [c[0], c[2]]) == 0.0
    };
    let Some(ci) = order.iter().position(|&c| !collinear(&pts[c as usize])) else {
        return Ok(Core::degenerate("all points collinear"));
    };
    let c = order[ci];
    let pc = pts[c as usize];
    let Some(di) = order
        .iter()
        .position(|&d| orient3d_exact(pa, pb, pc, pts[d as usize]) != 0.0)
    else {
        return Ok(Core::degenerate("all points coplanar"));
    };
    let d = order[di];
    let mut first = if orient3d_exact(pa, pb, pc, pts[d as usize]) > 0.0 {
        [a, b, c, d]
    } else {
        [b, a, c, d]
    };
    if orient3d_exact(
        pts[first[0] as usize],
        pts[first[1] as usize],
        pts[first[2] as usize],
        pts[first[3] as usize],
    ) < 0.0
    {
        first.swap(0, 1);
    }
    let n = pts.len();
    // internal numbering = insertion order (memory locality); `canon` maps back
    let mut canon: Vec<u32> = Vec::with_capacity(n);
    canon.extend_from_slice(&first);
    canon.extend(
        order
            .iter()
            .copied()
            .filter(|&p| p != a && p != b && p != c && p != d),
    );
    drop(order);
    let ipts: Vec<[f64; 3]> = canon.iter().map(|&v| pts[v as usize]).collect();
    let cap = 7 * n + 16;
    let mut bld = Builder {
        pts: &ipts,
        rank: &canon,
        safe: safe_range(&ipts),
        overflow: false,
        small_int: ipts
            .iter()
            .flatten()
            .all(|x| x.fract() == 0.0 && x.abs() <= (1u32 << 20) as f64),
        tv: Vec::with_capacity(cap),
        tn: Vec::with_capacity(cap),
        stamp: Vec::with_capacity(cap),
        free: Vec::new(),
        last: 0,
        rng: Rng::new(0x2545_F491_4F6C_DD1D),
        stack: Vec::new(),
        conflict: Vec::new(),
        bnd: Vec::new(),
        table: Vec::new(),
        gen: 0,
    };
    let first = [0, 1, 2, 3];
    bld.tv.push(first);
    for f in FACE_OF {
        bld.tv.push([first[f[1]], first[f[0]], first[f[2]], INF]);
    }
    bld.tn.resize(5, [0; 4]);
    bld.stamp.resize(5, 0);
    link_brute(&bld.tv, &mut bld.tn);
    for p in 4..n as u32 {
        bld.insert(p, p - 4);
        if bld.overflow {
            return Err(DelaunayError::TooManySimplices {
                dim: 3,
                limit: MAX_TETS,
            });
        }
    }
    // compact in place
    let Builder { mut tv, mut tn, .. } = bld;
    let mut map = vec![NONE; tv.len()];
    let mut m = 0u32;
    for (t, v) in tv.iter().enumerate() {
        if v[0] != FREE && v[3] != INF {
            map[t] = m;
            m += 1;
        }
    }
    let mut hull = Vec::new();
    let mut w = 0usize;
    for t in 0..tv.len() {
        let v = tv[t];
        if v[0] == FREE {
            continue;
        }
        if v[3] == INF {
            hull.push([v[0], v[2], v[1]].map(|x| canon[x as usize]));
            continue;
        }
        let v = v.map(|x| canon[x as usize]);
        let mut nb = [NONE; 4];
        for i in 0..4 {
            nb[i] = map[(tn[t][i] >> 2) as usize];
        }
        tv[w] = v;
        tn[w] = nb;
        w += 1;
    }
    tv.truncate(w);
    tn.truncate(w);
    tv.shrink_to_fit();
    tn.shrink_to_fit();
    drop(map);
    Ok(Core {
        tets: tv,
        neighbors: tn,
        hull,
        degenerate: None,
    })
}

/// Links the faces of a handful of tetrahedra by brute force (initial simplex).
fn link_brute(tv: &[[u32; 4]], tn: &mut [[u32; 4]]) {
    let face = |t: usize, i: usize| {
        let mut f: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| tv[t][k]).collect();
        f.sort_unstable();
        f
    };
    for t in 0..tv.len() {
        for i in 0..4 {
            let f = face(t, i);
            for u in 0..tv.len() {
                if u == t {
                    continue;
                }
                for j in 0..4 {
                    if face(u, j) == f {
                        tn[t][i] = ((u as u32) << 2) | j as u32;
                    }
                }
            }
        }
    }
}

impl Delaunay3 {
    /// Number of vertices (distinct points).
    pub fn num_vertices(&self) -> usize {
        self.points.len()
    }

    fn pa(&self, v: u32) -> [f64; 3] {
        arr(&self.points[v as usize])
    }

    /// A tetrahedron containing `p` (in its closure), or `None` when `p` is outside the convex
    /// hull, not finite, or there are no tetrahedra. Visibility walk with exact `orient3d` (it terminates on
    /// Delaunay triangulations).
    pub fn locate(&self, p: &Point3) -> Option<u32> {
        self.locate_from(p, 0)
    }

    /// [`Self::locate`] starting the walk at tetrahedron `hint`.
    pub fn locate_from(&self, p: &Point3, hint: u32) -> Option<u32> {
        if self.tets.is_empty() || !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
            return None;
        }
        let pp = arr(p);
        let mut t = if (hint as usize) < self.tets.len() {
            hint
        } else {
            0
        };
        let mut steps = 0usize;
        'walk: loop {
            steps += 1;
            if steps > 4 * self.tets.len() + 100 {
                break;
            }
            let v = self.tets[t as usize];
            let q = [self.pa(v[0]), self.pa(v[1]), self.pa(v[2]), self.pa(v[3])];
            for i in 0..4 {
                let mut w = q;
                w[i] = pp;
                if orient3d_exact(w[0], w[1], w[2], w[3]) < 0.0 {
                    let n = self.neighbors[t as usize][i];
                    if n == NONE {
                        return None;
                    }
                    t = n;
                    continue 'walk;
                }
            }
            return Some(t);
        }
        (0..self.tets.len() as u32).find(|&t| {
            let v = self.tets[t as usize];
            let q = [self.pa(v[0]), self.pa(v[1]), self.pa(v[2]), self.pa(v[3])];
            (0..4).all(|i| {
                let mut w = q;
                w[i] = pp;
                orient3d_exact(w[0], w[1], w[2], w[3]) >= 0.0
            })
        })
    }

    /// All tetrahedra incident to vertex `v` (empty for an invalid `v`).
    pub fn tets_around_vertex(&self, v: u32) -> Vec<u32> {
        let Some(&t0) = self.vertex_tet.get(v as usize) else {
            return Vec::new();
        };
        if t0 == NONE {
            return Vec::new();
        }
        let mut seen = HashSet::new();
        let mut out = vec![t0];
        seen.insert(t0);
        let mut k = 0;
        while k < out.len() {
            let t = out[k] as usize;
            k += 1;
            for i in 0..4 {
                if self.tets[t][i] == v {
                    continue;
                }
                let n = self.neighbors[t][i];
                if n != NONE && seen.insert(n) {
                    out.push(n);
                }
            }
        }
        out
    }

    /// The tetrahedra around edge `ab`, in rotational order (empty when `ab` is not an edge).
    pub fn tets_around_edge(&self, a: u32, b: u32) -> Vec<u32> {
        let Some(t0) = self
            .tets_around_vertex(a)
            .into_iter()
            .find(|&t| self.tets[t as usize].contains(&b))
        else {
            return Vec::new();
        };
        let others = |t: u32| -> [usize; 2] {
            let v = self.tets[t as usize];
            let mut o = [0; 2];
            let mut k = 0;
            for i in 0..4 {
                if v[i] != a && v[i] != b {
                    o[k] = i;
                    k += 1;
                }
            }
            o
        };
        let rotate = |start_slot: usize| -> (Vec<u32>, bool) {
            let mut out = Vec::new();
            let mut prev = t0;
            let mut cur = self.neighbors[t0 as usize][start_slot];
            while cur != NONE && cur != t0 {
                out.push(cur);
                let o = others(cur);
                let n0 = self.neighbors[cur as usize][o[0]];
                let next = if n0 != prev {
                    n0
                } else {
                    self.neighbors[cur as usize][o[1]]
                };
                prev = cur;
                cur = next;
            }
            (out, cur == t0)
        };
        let o = others(t0);
        let (fwd, closed) = rotate(o[0]);
        let mut res = vec![t0];
        if closed {
            res.extend(fwd);
        } else {
            let (bwd, _) = rotate(o[1]);
            let mut r: Vec<u32> = bwd.into_iter().rev().collect();
            r.push(t0);
            r.extend(fwd);
            res = r;
        }
        res
    }

    /// Every triangle once, with its tetrahedra (the second is [`NONE`] on the hull).
    pub fn triangles(&self) -> Vec<Face3> {
        let mut out = Vec::with_capacity(self.tets.len() * 2 + self.hull.len());
        for (t, v) in self.tets.iter().enumerate() {
            for i in 0..4 {
                let n = self.neighbors[t][i];
                if n == NONE || (t as u32) < n {
                    let f = FACE_OF[i];
                    // corner i lies on the side opposite the right-hand normal: outward
                    out.push(Face3 {
                        v: [v[f[0]], v[f[1]], v[f[2]]],
                        tets: [t as u32, n],
                    });
                }
            }
        }
        out
    }

    /// Circumcentre of tetrahedron `t` (a Voronoi vertex), computed in `f64`.
    pub fn circumcenter(&self, t: u32) -> Point3 {
        self.circumsphere(t).0
    }

    /// Circumsphere (centre, radius) of tetrahedron `t`, computed in `f64`.
    pub fn circumsphere(&self, t: u32) -> (Point3, f64) {
        let v = self.tets[t as usize];
        let a = self.points[v[0] as usize];
        let b = self.points[v[1] as usize] - a;
        let c = self.points[v[2] as usize] - a;
        let d = self.points[v[3] as usize] - a;
        let den = 2.0 * b.dot(&c.cross(&d));
        let num = c.cross(&d) * b.norm_squared()
            + d.cross(&b) * c.norm_squared()
            + b.cross(&c) * d.norm_squared();
        let off = num / den;
        (a + off, off.norm())
    }

    /// The tetrahedra with input indices (a merged duplicate is represented by its first
    /// occurrence).
    pub fn to_input_indices(&self) -> Vec<[u32; 4]> {
        self.tets
            .iter()
            .map(|t| t.map(|v| self.input_of_vertex[v as usize]))
            .collect()
    }

    /// Local certificate of the (perturbed) Delaunay property in `O(T)`: for every interior face,
    /// the apex of each neighbour is outside the circumsphere of the other tetrahedron (exact
    /// `insphere`, ties decided by the symbolic perturbation), and along every hull edge the two
    /// hull triangles are locally convex. Together with [`Self::check_topology`] this implies the
    /// global empty-sphere property (Delaunay's lemma).
    pub fn check_delaunay_local(&self) -> std::result::Result<(), String> {
        for (t, v) in self.tets.iter().enumerate() {
            for i in 0..4 {
                let n = self.neighbors[t][i];
                if n == NONE || n < t as u32 {
                    continue;
                }
                let nv = self.tets[n as usize];
                let Some(&apex) = nv.iter().find(|x| !v.contains(x)) else {
                    return Err(format!("tets {t} and {n} have the same vertices"));
                };
                let q = [
                    self.pa(v[0]),
                    self.pa(v[1]),
                    self.pa(v[2]),
                    self.pa(v[3]),
                    self.pa(apex),
                ];
                let s = insphere_exact(q[0], q[1], q[2], q[3], q[4]);
                if s > 0.0 || (s == 0.0 && perturbed_insphere(&q, &[v[0], v[1], v[2], v[3], apex]))
                {
                    return Err(format!("face between {t} and {n} is not locally Delaunay"));
                }
            }
        }
        let mut edge: std::collections::HashMap<(u32, u32), usize> = Default::default();
        for (h, f) in self.hull.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                if let Some(&g) = edge.get(&(b, a)) {
                    let other = self.hull[g];
                    let Some(&apex) = other.iter().find(|x| !f.contains(x)) else {
                        return Err(format!("hull triangles {h} and {g} coincide"));
                    };
                    let o =
                        orient3d_exact(self.pa(f[0]), self.pa(f[1]), self.pa(f[2]), self.pa(apex));
                    if o < 0.0 {
                        return Err(format!("hull not convex at edge {a}-{b}"));
                    }
                } else {
                    edge.insert((a, b), h);
                }
            }
        }
        Ok(())
    }

    /// Checks the combinatorial invariants (positive orientation, neighbour symmetry); for tests.
    pub fn check_topology(&self) -> std::result::Result<(), String> {
        for (t, v) in self.tets.iter().enumerate() {
            let q = v.map(|x| self.pa(x));
            if orient3d_exact(q[0], q[1], q[2], q[3]) <= 0.0 {
                return Err(format!("tet {t} not positive"));
            }
            for i in 0..4 {
                let n = self.neighbors[t][i];
                if n == NONE {
                    continue;
                }
                let nv = self.tets[n as usize];
                let Some(j) = (0..4).find(|&j| self.neighbors[n as usize][j] == t as u32) else {
                    return Err(format!("neighbour {n} of {t} not symmetric"));
                };
                let mut f1: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| v[k]).collect();
                let mut f2: Vec<u32> = (0..4).filter(|&k| k != j).map(|k| nv[k]).collect();
                f1.sort_unstable();
                f2.sort_unstable();
                if f1 != f2 {
                    return Err(format!("tets {t} and {n} do not share the face"));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_grid(n: usize) -> Vec<Point3> {
        let mut v = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    v.push(Point3::new(i as f64, j as f64, k as f64));
                }
            }
        }
        v
    }

    #[test]
    fn single_tet() {
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
        ];
        let d = triangulate(&p).unwrap();
        assert_eq!(d.tets.len(), 1);
        assert_eq!(d.hull.len(), 4);
        d.check_topology().unwrap();
    }

    #[test]
    fn cube_grid_counts() {
        let d = triangulate(&cube_grid(3)).unwrap();
        d.check_topology().unwrap();
        let vol: f64 = d
            .tets
            .iter()
            .map(|t| {
                let q = t.map(|x| arr(&d.points[x as usize]));
                orient3d_exact(q[0], q[1], q[2], q[3]) / 6.0
            })
            .sum();
        assert!((vol - 8.0).abs() < 1e-12, "{vol}");
        assert_eq!(d.hull.len(), 6 * 8);
    }

    /// The semi-static in-sphere filter against the exact sign: random tuples over many
    /// scales, and near-cospherical ones (integer points of a sphere, scaled and shifted so
    /// that rounding breaks the tie, the fifth point moved by a few ulps), where a bound too
    /// small certifies wrong signs. Both decided and undecided cases must occur.
    #[test]
    fn semi_static_insphere_agrees_with_exact() {
        let mut rng = Rng::new(7);
        let mut unit = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let sign = |x: f64| (x > 0.0) as i32 - (x < 0.0) as i32;
        let (mut decided, mut undecided, mut near_decided) = (0, 0, 0);
        // random tuples, scales 2^-60 .. 2^60, offsets up to 2^8 times the scale
        for k in 0..20_000 {
            let scale = 2f64.powi((k % 121) - 60);
            let off = [unit(), unit(), unit()].map(|x| (x - 0.5) * 256.0 * scale);
            let mut q = [[0.0; 3]; 5];
            for p in q.iter_mut() {
                *p = [0, 1, 2].map(|c| off[c] + unit() * scale);
            }
            let f = insphere_semi_static(q[0], q[1], q[2], q[3], q[4]);
            let e = sign(insphere_exact(q[0], q[1], q[2], q[3], q[4]));
            if f != 0 {
                assert_eq!(f, e, "{q:?}");
                decided += 1;
            }
        }
        // integer points on x² + y² + z² = 50 (cospherical), scaled and shifted
        let mut sph = Vec::new();
        for x in -7i32..=7 {
            for y in -7i32..=7 {
                for z in -7i32..=7 {
                    if x * x + y * y + z * z == 50 {
                        sph.push([x as f64, y as f64, z as f64]);
                    }
                }
            }
        }
        assert!(sph.len() >= 20);
        let mut pick = Rng::new(11);
        for k in 0..40_000 {
            let scale = unit() * 2f64.powi((k % 41) - 20);
            let shift = [unit(), unit(), unit()].map(|x| x * 10.0);
            let mut q = [[0.0; 3]; 5];
            for p in q.iter_mut() {
                let s = sph[(pick.next_u64() % sph.len() as u64) as usize];
                *p = [0, 1, 2].map(|c| s[c] * scale + shift[c]);
            }
            // move the fifth point by up to 3 ulps in one coordinate
            let c = (k % 3) as usize;
            for _ in 0..(k / 3) % 4 {
                q[4][c] = if k % 2 == 0 {
                    q[4][c].next_up()
                } else {
                    q[4][c].next_down()
                };
            }
            let f = insphere_semi_static(q[0], q[1], q[2], q[3], q[4]);
            let e = sign(insphere_exact(q[0], q[1], q[2], q[3], q[4]));
            if f != 0 {
                assert_eq!(f, e, "near-cospherical {q:?}");
                near_decided += 1;
            } else {
                undecided += 1;
            }
        }
        assert!(decided > 19_000, "random tuples decided: {decided}");
        assert!(
            undecided > 1000 && near_decided > 1000,
            "{undecided} {near_decided}"
        );
    }

    /// The keyed sort of `dedup_sorted` gives main's permutation (index sort comparing the
    /// points, ties by index): negative, zero, tiny, huge and repeated coordinates, on the
    /// sequential (small) and the parallel (≥ 2^15) paths.
    #[test]
    fn lex_order_matches_index_sort() {
        let vals = [
            -f64::MAX,
            -3.5,
            -1.0,
            -1e-300,
            -f64::MIN_POSITIVE,
            -5e-324,
            0.0,
            5e-324,
            1e-300,
            0.75,
            1.0,
            2.0,
            f64::MAX,
        ];
        let mut rng = Rng::new(3);
        for n in [1usize, 2, 17, 1000, 40_000] {
            let pts: Vec<[f64; 3]> = (0..n)
                .map(|_| {
                    [0, 1, 2].map(|_| {
                        let r = rng.next_u64();
                        if r % 4 == 0 {
                            (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5
                        } else {
                            vals[(r >> 8) as usize % vals.len()]
                        }
                    })
                })
                .collect();
            assert_eq!(lex_order(&pts), old_order(&pts), "n = {n}");
        }
    }

    /// `EDGE_AFTER[i][j]` lists the two slots following `i` in the outward face opposite `j`.
    #[test]
    fn edge_after_table() {
        for i in 0..4 {
            for j in 0..4 {
                if i == j {
                    continue;
                }
                let (x, y) = EDGE_AFTER[i][j];
                let f = FACE_OF[j];
                let k = f.iter().position(|&s| s == i).unwrap();
                assert_eq!((x as usize, y as usize), (f[(k + 1) % 3], f[(k + 2) % 3]));
                assert!(x as usize != i && y as usize != i && x != y);
            }
        }
    }

    #[test]
    fn degenerate_inputs() {
        let line: Vec<Point3> = (0..5).map(|i| Point3::new(i as f64, 0.0, 0.0)).collect();
        let d = triangulate(&line).unwrap();
        assert!(d.tets.is_empty());
        assert_eq!(d.degenerate.as_deref(), Some("all points collinear"));
        let plane: Vec<Point3> = (0..9)
            .map(|i| Point3::new((i % 3) as f64, (i / 3) as f64, 0.0))
            .collect();
        let d = triangulate(&plane).unwrap();
        assert_eq!(d.degenerate.as_deref(), Some("all points coplanar"));
        assert!(triangulate(&[]).is_err());
        assert!(triangulate(&[Point3::new(f64::NAN, 0.0, 0.0)]).is_err());
    }
}

//! Slab-wise extraction of contour points and triangles (Hamann 1991, §3.2) for one range of
//! cell layers `z0..z1`.
//!
//! Contour points live on grid *entities*: cell edges (all methods), face diagonals and body
//! diagonals (tetra method). Entities of a z-plane (x-edges, y-edges, xy-diagonals) form that
//! plane's block; entities spanning a layer (z-edges, yz/xz-diagonals, body diagonals) form the
//! layer's block. A slab emits, in this order, plane z0, layer z0, plane z0+1, layer z0+1, …,
//! plane z1 (a plane block row by row: the row's x-edges, then its y-edges and xy-diagonals; a
//! layer block by (y, x, slot)); cell-interior points (decider fans) go to a separate
//! list in cell order. The order depends only on the data, never on how layers are split into
//! slabs, so concatenating slabs (dropping each slab's last plane, which the next slab starts
//! with) gives the same vertex numbering as one serial pass. Work space: three index arrays of
//! O(nx·ny) per slab.

use super::tables::{self, polygon_table, tet_table, FACE_CORNERS, NO_FACE, TETS};
use super::{IsoMethod, NormalMethod};
use crate::geom::{Point3, Vector3};
use crate::volume::gradient::{gradient_at, CentralTable, GradientOperator};
use crate::volume::Volume;

use crate::util::NONE;
/// Chunk-local triangle corners with this bit refer to the interior point list.
pub(super) const INTERIOR: u32 = 1 << 31;
/// Key of vertices not on a grid entity (cell-interior points).
pub(super) const KEY_INTERIOR: u64 = u64::MAX;

/// Entity types packed into keys: 0 x-edge, 1 y-edge, 2 z-edge, 3 xy-diag, 4 yz-diag,
/// 5 xz-diag, 6 body diagonal.
pub(super) fn key(kind: u64, x: usize, y: usize, z: usize) -> u64 {
    (kind << 60) | ((x as u64) << 40) | ((y as u64) << 20) | z as u64
}

/// Integer extent [lo, hi] of the entity `key` along `axis` (`None` for interior points).
pub(super) fn extent(key: u64, axis: usize) -> Option<(usize, usize)> {
    if key == KEY_INTERIOR {
        return None;
    }
    let kind = key >> 60;
    let c = [
        (key >> 40 & 0xFFFFF) as usize,
        (key >> 20 & 0xFFFFF) as usize,
        (key & 0xFFFFF) as usize,
    ];
    let spans: [bool; 3] = match kind {
        0 => [true, false, false],
        1 => [false, true, false],
        2 => [false, false, true],
        3 => [true, true, false],
        4 => [false, true, true],
        5 => [true, false, true],
        _ => [true, true, true],
    };
    Some((c[axis], c[axis] + spans[axis] as usize))
}

/// Root of vertex `x` in the union–find parents `p` (path halving).
#[inline]
pub(super) fn vp_find(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let g = p[p[x as usize] as usize];
        p[x as usize] = g;
        x = g;
    }
    x
}

/// Joins the vertices of one polygon (all grid-edge vertices, slab-local indices) in the
/// union–find parents `p`; the smaller root wins, so a parent never comes after its child.
#[inline]
fn unite_polygon(p: &mut [u32], v: &[u32]) {
    let mut r = vp_find(p, v[0]);
    for &w in &v[1..] {
        let s = vp_find(p, w);
        if s != r {
            let (lo, hi) = (r.min(s), r.max(s));
            p[hi as usize] = lo;
            r = lo;
        }
    }
}

/// The polygon sides (face segments) that cell `p` of sign configuration `cfg` has on the
/// outer faces of a volume of `dims` samples. On a face the contour crosses 0, 2 or 4 of its
/// edges, and each segment joins two crossings, so a face holds (sign changes around it) / 2
/// segments, whichever way an ambiguous face is resolved (marching-cubes methods).
#[inline]
fn outer_sides(p: [usize; 3], cfg: u8, dims: [usize; 3]) -> usize {
    let mut n = 0;
    for (f, fc) in FACE_CORNERS.iter().enumerate() {
        let axis = f / 2;
        let outer = if f % 2 == 0 {
            p[axis] == 0
        } else {
            p[axis] + 2 == dims[axis]
        };
        if outer {
            let b = |k: usize| cfg >> fc[k] & 1;
            let changes = (b(0) ^ b(1)) + (b(1) ^ b(2)) + (b(2) ^ b(3)) + (b(3) ^ b(0));
            n += changes as usize / 2;
        }
    }
    n
}

/// True when the entity between samples with sign codes `a`, `b` carries a contour point.
#[inline]
fn cut(a: u8, b: u8) -> bool {
    (a ^ b) == 1
}

/// Corner bits of a 4-bit column code (bit 0: y0 z0, 1: y1 z0, 2: y0 z1, 3: y1 z1) at x = 0.
const SPREAD: [u8; 16] = {
    let mut t = [0u8; 16];
    let mut a = 0;
    while a < 16 {
        t[a] = ((a & 1) | (a >> 1 & 1) << 2 | (a >> 2 & 1) << 4 | (a >> 3 & 1) << 6) as u8;
        a += 1;
    }
    t
};

/// Vertex index arrays of the planes below and above a layer and of the layer itself.
pub(super) struct Index<'a> {
    plo: &'a [u32],
    phi: &'a [u32],
    lay: &'a [u32],
    ps: usize,
    ls: usize,
    /// Per cell entity (0..19): array (0 plane below, 1 plane above, 2 layer) and offset from
    /// the cell's base slot.
    delta: &'a [(u8, usize); 19],
}

/// The [`Index::delta`] table for row length `nx` and strides `ps`, `ls`.
fn delta_table(nx: usize, ps: usize, ls: usize) -> [(u8, usize); 19] {
    std::array::from_fn(|e| {
        let p = |dx: usize, dy: usize, slot: usize| ps * (dx + nx * dy) + slot;
        let l = |dx: usize, dy: usize, slot: usize| ls * (dx + nx * dy) + slot;
        match e {
            0..=11 => {
                let (axis, j) = (e / 4, e % 4);
                let (lo, hi) = (j & 1, j >> 1);
                match axis {
                    0 => (hi as u8, p(0, lo, 0)),
                    1 => (hi as u8, p(lo, 0, 1)),
                    _ => (2, l(lo, hi, 0)),
                }
            }
            12 => (2, l(0, 0, 1)),
            13 => (2, l(1, 0, 1)),
            14 => (2, l(0, 0, 2)),
            15 => (2, l(0, 1, 2)),
            16 => (0, p(0, 0, 2)),
            17 => (1, p(0, 0, 2)),
            _ => (2, l(0, 0, 3)),
        }
    })
}

/// Calls `f(k)` for every k with `cut(a[k], b[k])`, in increasing k, testing eight sign codes
/// at a time (`a` and `b` have the same length).
#[inline]
fn for_each_cut(a: &[u8], b: &[u8], mut f: impl FnMut(usize)) {
    let n = a.len().min(b.len());
    let mut k = 0;
    while k + 8 <= n {
        let wa = u64::from_le_bytes(a[k..k + 8].try_into().unwrap_or([0; 8]));
        let wb = u64::from_le_bytes(b[k..k + 8].try_into().unwrap_or([0; 8]));
        let mut d = wa ^ wb;
        while d != 0 {
            let j = (d.trailing_zeros() / 8) as usize;
            if (d >> (8 * j)) & 0xFF == 1 {
                f(k + j);
            }
            d &= !(0xFFu64 << (8 * j));
        }
        k += 8;
    }
    for j in k..n {
        if cut(a[j], b[j]) {
            f(j);
        }
    }
}

/// Sign codes of the two planes of a layer and their row summaries.
pub(super) struct Signs<'a> {
    s0: &'a [u8],
    s1: &'a [u8],
    r0: &'a [u8],
    r1: &'a [u8],
}

pub(super) struct Ctx<'a> {
    pub vol: &'a Volume,
    pub axes: &'a [Vec<f64>; 3],
    pub alpha: f64,
    pub eps: f64,
    pub method: IsoMethod,
    pub normals: NormalMethod,
    /// false: triangles and normals point out of {f > α} (along −∇f); true: along +∇f.
    pub flip: bool,
    /// Record grid keys of vertices (needed for the topology analysis only).
    pub keys: bool,
    /// Decider topology during the extraction (`super::parts`): a union–find parent per
    /// grid-edge vertex, every polygon's vertices united, and the polygon sides on the
    /// volume's outer faces counted. Only meaningful with [`IsoMethod::Decider`] (the
    /// tests record `keys` alongside, for the edge-table oracle).
    pub parts: bool,
    /// Offset and span tables for central-difference normals (`Some` iff `normals` is
    /// `Central`), built for `gvol`.
    pub central: Option<&'a CentralTable>,
    /// The samples gradients are taken from: `vol` itself, or (for a block of a larger grid,
    /// see `block`) `vol` with a one-sample halo, so that a grid point's stencil is the one it
    /// has in the whole grid. Grid point `p` of `vol` is `p + goff` of `gvol`.
    pub gvol: &'a Volume,
    /// Plane coordinates of `gvol`.
    pub gaxes: &'a [Vec<f64>; 3],
    /// Offset of `vol` in `gvol`.
    pub goff: [usize; 3],
    /// Record the cell of every triangle, of every interior point and of every skipped cell
    /// (needed to stitch blocks only).
    pub cells: bool,
}

#[derive(Default)]
pub(super) struct ChunkOut {
    pub pos: Vec<Point3>,
    pub nrm: Vec<Vector3>,
    pub keys: Vec<u64>,
    pub ipos: Vec<Point3>,
    pub inrm: Vec<Vector3>,
    pub tris: Vec<[u32; 3]>,
    /// With [`Ctx::parts`]: the union–find parent of each grid-edge vertex (slab-local index,
    /// a parent never above its child), and the polygon sides lying on the volume's outer
    /// faces.
    pub vp: Vec<u32>,
    pub outer: usize,
    /// With [`Ctx::cells`]: the cell of each triangle, of each interior point, and the cells
    /// skipped for a NaN corner.
    pub tcell: Vec<[usize; 3]>,
    pub icell: Vec<[usize; 3]>,
    pub nan_cells: Vec<[usize; 3]>,
    pub last_plane_start: usize,
    pub fans: usize,
    pub centroids: usize,
    pub skipped_cells: usize,
    /// More than 2³¹ − 1 vertices in this slab (indices no longer fit).
    pub overflow: bool,
    /// Some grid-gradient normal is the zero vector (undefined).
    pub zero_normals: bool,
    /// Work space: gradients of two grid planes (freed when the slab is done). From
    /// `gbase` (a 64-byte boundary) eight words per (x, y): for the planes z mod 2 = 0 and 1
    /// the gradient's three f64 bits and the stamp, so a lookup reads one cache line and a
    /// layer's z-edges find both ends' entries in it. Zeroed memory (stamp 0: empty) that is
    /// only paged in where the surface passes.
    gcache: Vec<u64>,
    gbase: usize,
}

impl Ctx<'_> {
    /// f − α with values equal to α raised by ε (H Rem. 3.8); NaN stays NaN.
    #[inline]
    fn g(&self, v: f32) -> f64 {
        let d = v as f64 - self.alpha;
        if d == 0.0 {
            self.eps
        } else {
            d
        }
    }
    fn op(&self) -> Option<GradientOperator> {
        match self.normals {
            NormalMethod::ZuckerHummel => Some(GradientOperator::ZuckerHummel),
            NormalMethod::Central => Some(GradientOperator::Central),
            _ => None,
        }
    }
    /// Gradient at grid point `p`. Zucker–Hummel gradients (54 samples) are cached per plane:
    /// planes z and z + 1 of the current layer use slots z mod 2, and a stamp z + 1 marks valid
    /// entries, so nothing is ever cleared.
    #[inline]
    fn grad(&self, p: [usize; 3], out: &mut ChunkOut) -> Vector3 {
        let Some(op) = self.op() else {
            return Vector3::zeros();
        };
        if let Some(tab) = self.central {
            // six samples: recomputing is as cheap as the cache lookup
            let q = self.gpoint(p);
            let g = tab.at(&self.gvol.data, self.gindex(q), q);
            return Vector3::new(g[0], g[1], g[2]);
        }
        let (slot, i, stamp) = (p[2] % 2, p[0] + self.vol.dims[0] * p[1], p[2] as u32 + 1);
        let b = out.gbase + 8 * i + 4 * slot;
        let e = &mut out.gcache[b..b + 4];
        let g = if e[3] == stamp as u64 {
            [e[0], e[1], e[2]].map(f64::from_bits)
        } else {
            let g = gradient_at(self.gvol, self.gaxes, self.gpoint(p), op);
            e.copy_from_slice(&[g[0].to_bits(), g[1].to_bits(), g[2].to_bits(), stamp as u64]);
            g
        };
        Vector3::new(g[0], g[1], g[2])
    }
    /// Asks the processor to load the gradient cache line of grid position `i` = x + nx·y
    /// (both planes' entries). Zucker–Hummel only (the cache is empty otherwise); a hint, no
    /// effect on any result.
    #[inline(always)]
    fn prefetch_grad(&self, out: &ChunkOut, i: usize) {
        #[cfg(target_arch = "x86_64")]
        #[allow(unused_unsafe)]
        if let Some(e) = out.gcache.get(out.gbase + 8 * i) {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            // SAFETY: prefetching is a hint, valid for any address; this is a live reference.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(e as *const u64 as *const i8) };
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = (out, i);
    }
    /// Grid point `p` of `vol` as a grid point of `gvol`.
    #[inline]
    fn gpoint(&self, p: [usize; 3]) -> [usize; 3] {
        [
            p[0] + self.goff[0],
            p[1] + self.goff[1],
            p[2] + self.goff[2],
        ]
    }
    /// Linear index of grid point `q` of `gvol`.
    #[inline]
    fn gindex(&self, q: [usize; 3]) -> usize {
        let [nx, ny, _] = self.gvol.dims;
        q[0] + nx * (q[1] + ny * q[2])
    }
    /// Oriented unit normal from a gradient (zero when undefined).
    #[inline]
    fn orient(&self, g: Vector3) -> Vector3 {
        let l2 = g.x * g.x + g.y * g.y + g.z * g.z;
        if l2 > 0.0 && l2.is_finite() {
            let s = if self.flip { 1.0 } else { -1.0 } / l2.sqrt();
            Vector3::new(g.x * s, g.y * s, g.z * s)
        } else {
            Vector3::zeros()
        }
    }
    /// [`Ctx::orient`] applied in place to the edge-point gradients `out.nrm[from..]` (a
    /// separate loop: its iterations are independent, so the square roots and divisions of
    /// neighbouring points overlap instead of stalling the point generation); records whether
    /// a normal came out zero.
    fn orient_from(&self, from: usize, out: &mut ChunkOut) {
        if self.op().is_none() {
            return;
        }
        let mut zero = false;
        for n in out.nrm.get_mut(from..).unwrap_or_default() {
            *n = self.orient(*n);
            zero |= n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
        }
        out.zero_normals |= zero;
    }
    fn point(&self, p: [usize; 3]) -> Point3 {
        Point3::new(self.axes[0][p[0]], self.axes[1][p[1]], self.axes[2][p[2]])
    }

    /// Sign codes of plane z: bit 0 set for f ≥ α (f > α after Rem. 3.8), 2 for NaN; and per
    /// row y: 0 all negative, 1 all positive, 2 mixed, 3 with a NaN.
    fn signs(&self, z: usize, s: &mut [u8], rows: &mut [u8]) {
        let [nx, ny, _] = self.vol.dims;
        let data = &self.vol.data[nx * ny * z..nx * ny * (z + 1)];
        for y in 0..ny {
            let (src, dst) = (&data[nx * y..nx * (y + 1)], &mut s[nx * y..nx * (y + 1)]);
            let mut or = 0u8;
            let mut and = 1u8;
            for (d, &v) in dst.iter_mut().zip(src) {
                let c = if v.is_nan() {
                    2
                } else {
                    (v as f64 >= self.alpha) as u8
                };
                *d = c;
                or |= c;
                and &= c;
            }
            rows[y] = if or & 2 != 0 {
                3
            } else if or != and {
                2
            } else {
                and
            };
        }
    }

    /// Reads one sample per cache line of plane `z` (if it exists).
    fn touch(&self, z: usize) {
        let n = self.vol.dims[0] * self.vol.dims[1];
        if let Some(plane) = self.vol.data.get(n * z..n * (z + 1)) {
            let mut acc = 0.0f32;
            for k in (0..plane.len()).step_by(16) {
                acc += plane[k];
            }
            std::hint::black_box(acc);
        }
    }

    /// Adds the contour point on the entity from grid point `a` to `b` (known to be cut).
    fn vertex(&self, a: [usize; 3], b: [usize; 3], k: u64, out: &mut ChunkOut) -> u32 {
        let [nx, ny, _] = self.vol.dims;
        let (ia, ib) = (
            a[0] + nx * (a[1] + ny * a[2]),
            b[0] + nx * (b[1] + ny * b[2]),
        );
        let ga = self.g(self.vol.data[ia]);
        let gb = self.g(self.vol.data[ib]);
        let mut t = ga / (ga - gb);
        if t.is_nan() {
            // an infinite sample: the contour point sits at the finite end
            t = match (ga.is_infinite(), gb.is_infinite()) {
                (true, true) => 0.5,
                (true, false) => 1.0,
                _ => 0.0,
            };
        }
        let (pa, pb) = (self.point(a), self.point(b));
        out.pos.push(pa + (pb - pa) * t);
        if let Some(tab) = self.central {
            let (qa, qb) = (self.gpoint(a), self.gpoint(b));
            let [na, nb] = tab.at2(&self.gvol.data, self.gindex(qa), qa, self.gindex(qb), qb);
            let u = 1.0 - t;
            // normalised later in a batch (`orient_from`)
            out.nrm.push(Vector3::new(
                na[0] * u + nb[0] * t,
                na[1] * u + nb[1] * t,
                na[2] * u + nb[2] * t,
            ));
        } else if self.op().is_some() {
            let (na, nb) = (self.grad(a, out), self.grad(b, out));
            out.nrm.push(na * (1.0 - t) + nb * t);
        }
        if self.keys {
            out.keys.push(k);
        }
        if self.parts {
            out.vp.push(out.pos.len() as u32 - 1);
        }
        out.overflow |= out.pos.len() >= INTERIOR as usize;
        (out.pos.len() - 1) as u32
    }

    fn build_plane(&self, z: usize, s: &[u8], rows: &[u8], arr: &mut [u32], out: &mut ChunkOut) {
        let [nx, ny, _] = self.vol.dims;
        let tet = self.method == IsoMethod::Tetra;
        let ps = self.strides().0;
        for y in 0..ny {
            let xe = rows[y] >= 2;
            let ye = y + 1 < ny && (rows[y] >= 2 || rows[y] != rows[y + 1]);
            if !xe && !ye {
                continue;
            }
            let row = nx * y;
            if !out.gcache.is_empty() {
                // the row's cache lines first, so that their misses overlap (the same cuts as
                // below, in the same order; nothing is computed here)
                if xe {
                    for_each_cut(&s[row..row + nx - 1], &s[row + 1..row + nx], |x| {
                        self.prefetch_grad(out, row + x);
                        self.prefetch_grad(out, row + x + 1);
                    });
                }
                if ye {
                    for_each_cut(&s[row..row + nx], &s[row + nx..row + 2 * nx], |x| {
                        self.prefetch_grad(out, row + x);
                        self.prefetch_grad(out, row + nx + x);
                    });
                }
            }
            if xe {
                for_each_cut(&s[row..row + nx - 1], &s[row + 1..row + nx], |x| {
                    arr[ps * (row + x)] =
                        self.vertex([x, y, z], [x + 1, y, z], key(0, x, y, z), out);
                });
            }
            if ye && !tet {
                for_each_cut(&s[row..row + nx], &s[row + nx..row + 2 * nx], |x| {
                    arr[ps * (row + x) + 1] =
                        self.vertex([x, y, z], [x, y + 1, z], key(1, x, y, z), out);
                });
            } else if ye {
                for x in 0..nx {
                    let i = row + x;
                    if cut(s[i], s[i + nx]) {
                        arr[ps * i + 1] =
                            self.vertex([x, y, z], [x, y + 1, z], key(1, x, y, z), out);
                    }
                    if tet && x + 1 < nx && cut(s[i + 1], s[i + nx]) {
                        arr[ps * i + 2] =
                            self.vertex([x + 1, y, z], [x, y + 1, z], key(3, x, y, z), out);
                    }
                }
            }
        }
    }

    fn build_layer(&self, z: usize, sg: &Signs, arr: &mut [u32], out: &mut ChunkOut) {
        let [nx, ny, _] = self.vol.dims;
        let tet = self.method == IsoMethod::Tetra;
        let ls = self.strides().1;
        let (s0, s1) = (sg.s0, sg.s1);
        for y in 0..ny {
            let same = |r: &[u8]| r.iter().all(|&q| q < 2 && q == r[0]);
            let ze = !same(&[sg.r0[y], sg.r1[y]]);
            let de = tet && y + 1 < ny && !same(&[sg.r0[y], sg.r1[y], sg.r0[y + 1], sg.r1[y + 1]]);
            if !ze && !de {
                continue;
            }
            if !tet {
                let row = nx * y;
                if !out.gcache.is_empty() {
                    // both ends' entries share one cache line (see `ChunkOut::gcache`)
                    for_each_cut(&s0[row..row + nx], &s1[row..row + nx], |x| {
                        self.prefetch_grad(out, row + x);
                    });
                }
                for_each_cut(&s0[row..row + nx], &s1[row..row + nx], |x| {
                    arr[ls * (row + x)] =
                        self.vertex([x, y, z], [x, y, z + 1], key(2, x, y, z), out);
                });
                continue;
            }
            for x in 0..nx {
                let i = x + nx * y;
                let o = ls * i;
                if cut(s0[i], s1[i]) {
                    arr[o] = self.vertex([x, y, z], [x, y, z + 1], key(2, x, y, z), out);
                }
                if !tet {
                    continue;
                }
                if y + 1 < ny && cut(s0[i + nx], s1[i]) {
                    arr[o + 1] = self.vertex([x, y + 1, z], [x, y, z + 1], key(4, x, y, z), out);
                }
                if x + 1 < nx && cut(s0[i + 1], s1[i]) {
                    arr[o + 2] = self.vertex([x + 1, y, z], [x, y, z + 1], key(5, x, y, z), out);
                }
                if x + 1 < nx && y + 1 < ny && cut(s0[i + 1], s1[i + nx]) {
                    arr[o + 3] =
                        self.vertex([x + 1, y, z], [x, y + 1, z + 1], key(6, x, y, z), out);
                }
            }
        }
    }

    /// Slots per grid position in the plane and layer index arrays.
    fn strides(&self) -> (usize, usize) {
        if self.method == IsoMethod::Tetra {
            (3, 4)
        } else {
            (2, 1)
        }
    }

    /// Extracts layers `z0..z1` (cells with lower z index in that range).
    ///
    /// The index arrays are never cleared: a cell only looks up entities its sign
    /// configuration says are cut, and those were written for the current plane/layer.
    pub fn chunk(&self, z0: usize, z1: usize) -> ChunkOut {
        let [nx, ny, _] = self.vol.dims;
        let mut out = ChunkOut::default();
        if self.normals == NormalMethod::ZuckerHummel {
            out.gcache = vec![0u64; 8 * nx * ny + 8];
            // no huge-page hint: the cache is touched sparsely, and a parallel run makes one
            // per slab, so zeroing whole 2 MiB pages measured slower than the faults it saves
            let off = out.gcache.as_ptr().align_offset(64);
            out.gbase = if off < 8 { off } else { 0 };
        }
        let (ps, ls) = self.strides();
        let mut plo = vec![NONE; ps * nx * ny];
        let mut phi = vec![NONE; ps * nx * ny];
        let mut lay = vec![NONE; ls * nx * ny];
        let (mut slo, mut shi) = (vec![0u8; nx * ny], vec![0u8; nx * ny]);
        let (mut rlo, mut rhi) = (vec![0u8; ny], vec![0u8; ny]);
        let mut col = vec![0u8; nx];
        let delta = delta_table(nx, ps, ls);
        self.signs(z0, &mut slo, &mut rlo);
        self.build_plane(z0, &slo, &rlo, &mut plo, &mut out);
        self.orient_from(0, &mut out);
        // after an eighth of the layers, reserve the output for the projected total: saves
        // most of the copies of repeated doubling
        let project_at = z0 + ((z1 - z0) / 8).max(1);
        for z in z0..z1 {
            if z == project_at {
                Self::reserve_projected(&mut out, z - z0, z1 - z0);
            }
            if self.op().is_some() {
                // gradients of plane z + 1 read plane z + 2: bring it into the cache in one
                // sequential sweep instead of scattered misses
                self.touch(z + 2);
            }
            self.signs(z + 1, &mut shi, &mut rhi);
            let sg = Signs {
                s0: &slo,
                s1: &shi,
                r0: &rlo,
                r1: &rhi,
            };
            let from = out.pos.len();
            self.build_layer(z, &sg, &mut lay, &mut out);
            out.last_plane_start = out.pos.len();
            self.build_plane(z + 1, &shi, &rhi, &mut phi, &mut out);
            self.orient_from(from, &mut out);
            let ix = Index {
                plo: &plo,
                phi: &phi,
                lay: &lay,
                ps,
                ls,
                delta: &delta,
            };
            self.cells(z, &sg, &ix, &mut col, &mut out);
            std::mem::swap(&mut plo, &mut phi);
            std::mem::swap(&mut slo, &mut shi);
            std::mem::swap(&mut rlo, &mut rhi);
        }
        out.gcache = Default::default();
        // a projection far above the real size: give the excess back
        if out.pos.capacity() > 2 * out.pos.len() + 1024 {
            out.pos.shrink_to_fit();
            out.nrm.shrink_to_fit();
            out.keys.shrink_to_fit();
            out.vp.shrink_to_fit();
        }
        if out.tris.capacity() > 2 * out.tris.len() + 1024 {
            out.tris.shrink_to_fit();
        }
        out
    }

    /// Reserves the output buffers for `total` layers at the rate of the `done` ones so far,
    /// plus an eighth. (No huge-page hint here: these buffers are reallocated later, and
    /// moving huge pages to an address of another alignment splits them, which measured
    /// slower than the page faults it saves.)
    fn reserve_projected(out: &mut ChunkOut, done: usize, total: usize) {
        let more = |len: usize| {
            let p = (len as u64).saturating_mul(total as u64) / done.max(1) as u64;
            (p + p / 8).saturating_sub(len as u64).min(INTERIOR as u64) as usize
        };
        let (np, nt) = (more(out.pos.len()), more(out.tris.len()));
        out.pos.reserve(np);
        if !out.nrm.is_empty() {
            out.nrm.reserve(np);
        }
        if !out.keys.is_empty() {
            out.keys.reserve(np);
        }
        if !out.vp.is_empty() {
            out.vp.reserve(np);
        }
        out.tris.reserve(nt);
    }

    /// Finds the cells of layer z that the contour crosses.
    fn cells(&self, z: usize, sg: &Signs, ix: &Index, col: &mut [u8], out: &mut ChunkOut) {
        let [nx, ny, _] = self.vol.dims;
        let (s0, s1) = (sg.s0, sg.s1);
        let sy = nx;
        for y in 0..ny - 1 {
            let r = [sg.r0[y], sg.r0[y + 1], sg.r1[y], sg.r1[y + 1]];
            if r[0] < 2 && r.iter().all(|&q| q == r[0]) {
                continue; // a row of cells with all corners on one side
            }
            if r.contains(&3) {
                // a NaN nearby: check each cell
                for x in 0..nx - 1 {
                    let i = x + sy * y;
                    let c = [
                        s0[i],
                        s0[i + 1],
                        s0[i + sy],
                        s0[i + sy + 1],
                        s1[i],
                        s1[i + 1],
                        s1[i + sy],
                        s1[i + sy + 1],
                    ];
                    let mut cfg = 0u8;
                    let mut any = 0u8;
                    for (k, &ck) in c.iter().enumerate() {
                        cfg |= (ck & 1) << k;
                        any |= ck;
                    }
                    if any & 2 != 0 {
                        out.skipped_cells += 1;
                        if self.cells {
                            out.nan_cells.push([x, y, z]);
                        }
                    } else if cfg != 0 && cfg != 255 {
                        self.cell([x, y, z], cfg, ix, out);
                    }
                }
                continue;
            }
            // 4-bit column codes (y, z) per x; a cell's configuration joins two columns
            for (x, cx) in col.iter_mut().enumerate() {
                let i = x + sy * y;
                *cx = s0[i] | s0[i + sy] << 1 | s1[i] << 2 | s1[i + sy] << 3;
            }
            let mut x = 0;
            while x + 1 < nx {
                // eight cells at once when their nine columns are all inside or all outside
                if x + 9 <= nx {
                    let w = u64::from_le_bytes(col[x..x + 8].try_into().unwrap_or([1; 8]));
                    let w1 = u64::from_le_bytes(col[x + 1..x + 9].try_into().unwrap_or([1; 8]));
                    if w == w1 && (w == 0 || w == 0x0F0F_0F0F_0F0F_0F0F) {
                        x += 8;
                        continue;
                    }
                }
                let (a, b) = (col[x], col[x + 1]);
                x += 1;
                if a == b && (a == 0 || a == 15) {
                    continue;
                }
                let x = x - 1;
                let cfg = SPREAD[a as usize] | SPREAD[b as usize] << 1;
                self.cell([x, y, z], cfg, ix, out);
            }
        }
    }

    /// Triangulates one cell crossed by the contour (`cfg` not 0 or 255, no NaN corner).
    #[inline]
    fn cell(&self, p: [usize; 3], cfg: u8, ix: &Index, out: &mut ChunkOut) {
        self.cell_triangles(p, cfg, ix, out);
        if self.parts {
            out.outer += outer_sides(p, cfg, self.vol.dims);
        }
        if self.cells {
            out.tcell.resize(out.tris.len(), p);
        }
    }

    fn cell_triangles(&self, p: [usize; 3], cfg: u8, ix: &Index, out: &mut ChunkOut) {
        let [x, y, z] = p;
        let [nx, ny, _] = self.vol.dims;
        let (plo, phi, lay) = (ix.plo, ix.phi, ix.lay);
        let data = &self.vol.data;
        let sy = nx;
        let sz = nx * ny;
        let pos = x + nx * y;
        let (bp, bl) = (ix.ps * pos, ix.ls * pos);
        let ent = |e: u8| -> u32 {
            let (arr, d) = ix.delta[e as usize];
            match arr {
                0 => plo[bp + d],
                1 => phi[bp + d],
                _ => lay[bl + d],
            }
        };
        let flip = self.flip;
        let push = |out: &mut ChunkOut, a: u32, b: u32, c: u32| {
            out.tris.push(if flip { [a, c, b] } else { [a, b, c] });
        };
        if self.method == IsoMethod::Tetra {
            let tets = tet_table();
            for (t, tet) in TETS.iter().enumerate() {
                let mut c4 = 0usize;
                for (i, &c) in tet.iter().enumerate() {
                    c4 |= ((cfg >> c & 1) as usize) << i;
                }
                for tri in &tets.tris[t * 16 + c4] {
                    push(out, ent(tri[0]), ent(tri[1]), ent(tri[2]));
                }
            }
            return;
        }
        let table = polygon_table();
        let amb = table.ambiguous[cfg as usize];
        let b = x + sy * y + sz * z;
        let idx = [
            b,
            b + 1,
            b + sy,
            b + sy + 1,
            b + sz,
            b + sz + 1,
            b + sz + sy,
            b + sz + sy + 1,
        ];
        let mut g = [0.0f64; 8];
        let mut have_g = false;
        let mut load = |g: &mut [f64; 8]| {
            if !have_g {
                for k in 0..8 {
                    g[k] = self.g(data[idx[k]]);
                }
                have_g = true;
            }
        };
        let connect = if amb == 0 {
            0
        } else if self.method == IsoMethod::Lorensen {
            tables::lorensen_connect(cfg)
        } else {
            load(&mut g);
            let mut m = 0u8;
            for (f, fc) in FACE_CORNERS.iter().enumerate() {
                if amb >> f & 1 == 0 {
                    continue;
                }
                // asymptotic decider (Thm. 3.3): the bilinear saddle value is above α iff the
                // product of the positive diagonal exceeds that of the negative one; a tie (two
                // straight lines) cuts off the positive corners (H's choice).
                let (p, q) = if cfg >> fc[0] & 1 == 1 {
                    (
                        g[fc[0] as usize] * g[fc[2] as usize],
                        g[fc[1] as usize] * g[fc[3] as usize],
                    )
                } else {
                    (
                        g[fc[1] as usize] * g[fc[3] as usize],
                        g[fc[0] as usize] * g[fc[2] as usize],
                    )
                };
                if p > q {
                    m |= 1 << f;
                }
            }
            m
        };
        for poly in table.get(cfg, connect) {
            let n = poly.len as usize;
            let mut v = [0u32; 12];
            for i in 0..n {
                v[i] = ent(poly.edges[i]);
            }
            if self.parts {
                unite_polygon(&mut out.vp, &v[..n]);
            }
            if poly.fan_face == NO_FACE || self.method == IsoMethod::Lorensen {
                for i in 1..n - 1 {
                    push(out, v[0], v[i], v[i + 1]);
                }
            } else {
                load(&mut g);
                let c = self.interior_point(&g, poly.fan_face, &v[..n], p, out);
                for i in 0..n {
                    push(out, v[i], v[(i + 1) % n], c);
                }
            }
        }
    }

    /// The interior contour point y_n of Thm. 3.6 (Eqs. 3.10–3.11) for a polygon with two
    /// segments on face `f`, or the centroid of the polygon (Rem. 3.9) when the denominator
    /// vanishes or the point falls outside the cell (Rem. 3.10). Returns its interior id.
    fn interior_point(
        &self,
        g: &[f64; 8],
        f: u8,
        poly: &[u32],
        cell: [usize; 3],
        out: &mut ChunkOut,
    ) -> u32 {
        let a = (f / 2) as usize;
        let side = (f % 2) as usize;
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        let (b, c) = (b.min(c), b.max(c));
        let corner = |ia: usize, ib: usize, ic: usize| (ia << a) | (ib << b) | (ic << c);
        let h = |i: usize, j: usize| g[corner(side, i, j)];
        let d10 = h(1, 0) - h(0, 0);
        let d01 = h(0, 1) - h(0, 0);
        let d11 = h(1, 1) - h(1, 0) - h(0, 1) + h(0, 0);
        let ub = -d01 / d11;
        let uc = -d10 / d11;
        let bil = |s: usize| {
            let q = |i: usize, j: usize| g[corner(s, i, j)];
            q(0, 0) * (1.0 - ub) * (1.0 - uc)
                + q(1, 0) * ub * (1.0 - uc)
                + q(0, 1) * (1.0 - ub) * uc
                + q(1, 1) * ub * uc
        };
        let (f0, f1) = (bil(0), bil(1));
        let den = f1 - f0;
        let t0 = -f0 / den;
        let mut local = [0.0; 3];
        local[a] = t0;
        local[b] = ub;
        local[c] = uc;
        let mut p = Point3::new(
            self.lerp_axis(0, cell[0], local[0]),
            self.lerp_axis(1, cell[1], local[1]),
            self.lerp_axis(2, cell[2], local[2]),
        );
        out.fans += 1;
        // the point must lie strictly inside the cell: a point on a face would put fan edges on
        // that face (Condition 3.1) and a point outside may fold the surface (Rem. 3.10)
        let strictly_inside = (0..3).all(|k| {
            let (lo, hi) = (self.axes[k][cell[k]], self.axes[k][cell[k] + 1]);
            p[k] > lo && p[k] < hi
        });
        if !(den != 0.0 && t0.is_finite() && strictly_inside) {
            out.centroids += 1;
            let mut s = Vector3::zeros();
            for &v in poly {
                s += out.pos[v as usize].coords;
            }
            p = Point3::from(s / poly.len() as f64);
            for k in 0..3 {
                let (lo, hi) = (self.axes[k][cell[k]], self.axes[k][cell[k] + 1]);
                local[k] = ((p[k] - lo) / (hi - lo)).clamp(0.0, 1.0);
            }
        }
        out.ipos.push(p);
        if self.cells {
            out.icell.push(cell);
        }
        if self.op().is_some() {
            // Eq. 3.19: trilinear interpolation of the eight corner gradients
            let mut gsum = Vector3::zeros();
            for cc in 0..8usize {
                let bit = |k: usize| cc >> k & 1;
                let w: f64 = (0..3)
                    .map(|k| {
                        if bit(k) == 1 {
                            local[k]
                        } else {
                            1.0 - local[k]
                        }
                    })
                    .product();
                gsum += self.grad([cell[0] + bit(0), cell[1] + bit(1), cell[2] + bit(2)], out) * w;
            }
            let n = self.orient(gsum);
            out.zero_normals |= n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
            out.inrm.push(n);
        }
        out.overflow |= out.ipos.len() >= INTERIOR as usize;
        INTERIOR | (out.ipos.len() - 1) as u32
    }

    fn lerp_axis(&self, k: usize, i: usize, t: f64) -> f64 {
        let (lo, hi) = (self.axes[k][i], self.axes[k][i + 1]);
        lo + (hi - lo) * t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn for_each_cut_matches_the_definition() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        for n in [0usize, 1, 7, 8, 9, 16, 17, 40] {
            for density in [0.0, 0.1, 0.5] {
                let code = |rng: &mut rand_chacha::ChaCha8Rng| -> u8 {
                    if rng.gen_bool(density) {
                        rng.gen_range(0..3)
                    } else {
                        0
                    }
                };
                let a: Vec<u8> = (0..n).map(|_| code(&mut rng)).collect();
                let b: Vec<u8> = (0..n).map(|_| code(&mut rng)).collect();
                let mut got = Vec::new();
                for_each_cut(&a, &b, |k| got.push(k));
                let want: Vec<usize> = (0..n).filter(|&k| cut(a[k], b[k])).collect();
                assert_eq!(got, want);
            }
        }
    }

    #[test]
    fn spread_places_column_bits_on_corners() {
        for a in 0..16usize {
            let s = SPREAD[a];
            for (bit, corner) in [(0, 0), (1, 2), (2, 4), (3, 6)] {
                assert_eq!(s >> corner & 1, (a >> bit & 1) as u8);
            }
            assert_eq!(s & 0b1010_1010, 0);
        }
    }
}

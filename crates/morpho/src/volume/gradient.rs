//! Gradients of volumes and normals of contour triangulations (Hamann 1991, §3.4).
//!
//! * [`GradientOperator::ZuckerHummel`]: the 3·3·3 operator of Thm. 3.8 (Eq. 3.17): the x
//!   component is Σ r·c·f over the 18 neighbours with r = ±1, weights c = √n / n with
//!   n = |r| + |s| + |t|. H states it for equal spacing; here each component is divided by
//!   W · (x₊ − x₋) (W = 1 + 4/√2 + 4/√3, x₊ and x₋ the coordinates of the planes used) so that the
//!   result estimates ∂f/∂x on anisotropic and rectilinear grids and equals it for linear f.
//! * [`GradientOperator::Central`]: central differences (f₊ − f₋)/(x₊ − x₋).
//!
//! At the volume border the neighbour index is clamped (one-sided differences). Cost: O(1) per
//! grid point (18 resp. 2 samples per component); nothing is stored for the whole volume
//! (`CentralTable` keeps O(nx + ny + nz) per-axis offsets and plane distances so that many
//! central differences are evaluated without branches, bit-identical to [`gradient_at`]).
//! Contour points interpolate these grid gradients: linearly along a cell edge (Eq. 3.18) and
//! trilinearly inside a cell (Eq. 3.19) — see `volume::isosurface`.
//!
//! [`mesh_normals`] estimates vertex normals from the triangulation alone (Rem. 3.15): a local
//! frame (d₁, d₂, n) at each vertex, a least-squares quadric d = f(x̄, ȳ) through the vertex's
//! one-ring projected to the (d₁, d₂) plane, and the graph normal at the vertex; the frame is
//! re-aligned with that normal and the fit repeated once (H's "optimally oriented" system). The
//! ± ambiguity H mentions is resolved by the triangles' orientation. O(Σ degree) time.

use crate::geom::Vector3;
use crate::mesh::TriMesh;
use crate::volume::Volume;

/// How gradients at grid points are estimated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GradientOperator {
    /// Zucker–Hummel 3·3·3 operator (H Thm. 3.8).
    ZuckerHummel,
    /// Central differences.
    Central,
}

/// Per-axis plane coordinates of a volume (`axes[k][i]`).
pub fn axis_coords(vol: &Volume) -> [Vec<f64>; 3] {
    std::array::from_fn(|k| (0..vol.dims[k]).map(|i| vol.coord(k, i)).collect())
}

/// Gradient estimate at grid point `p` (`p[k] < vol.dims[k]`, every dim ≥ 2). `axes` comes from
/// [`axis_coords`]. NaN samples in the stencil give a NaN component.
///
/// ```
/// use morpho::volume::{axis_coords, gradient_at, GradientOperator, Volume};
/// let v = Volume::from_fn([5; 3], [0.0; 3], [4.0; 3], |x, y, z| 2.0 * x + 3.0 * y - z);
/// let axes = axis_coords(&v);
/// for op in [GradientOperator::Central, GradientOperator::ZuckerHummel] {
///     let g = gradient_at(&v, &axes, [2, 2, 2], op);
///     assert!((g[0] - 2.0).abs() < 1e-4 && (g[1] - 3.0).abs() < 1e-4 && (g[2] + 1.0).abs() < 1e-4);
/// }
/// ```
pub fn gradient_at(
    vol: &Volume,
    axes: &[Vec<f64>; 3],
    p: [usize; 3],
    op: GradientOperator,
) -> [f64; 3] {
    let d = vol.dims;
    if (0..3).all(|k| p[k] >= 1 && p[k] + 1 < d[k]) {
        return gradient_interior(vol, axes, p, op);
    }
    let lo = |k: usize| p[k].saturating_sub(1);
    let hi = |k: usize| (p[k] + 1).min(d[k] - 1);
    let at = |x: usize, y: usize, z: usize| vol.data[x + d[0] * (y + d[1] * z)] as f64;
    let mut g = [0.0; 3];
    match op {
        GradientOperator::Central => {
            for (k, gk) in g.iter_mut().enumerate() {
                let (mut a, mut b) = (p, p);
                a[k] = lo(k);
                b[k] = hi(k);
                let span = axes[k][b[k]] - axes[k][a[k]];
                *gk = (at(b[0], b[1], b[2]) - at(a[0], a[1], a[2])) / span;
            }
        }
        GradientOperator::ZuckerHummel => {
            const W: f64 =
                1.0 + 4.0 * std::f64::consts::FRAC_1_SQRT_2 + 4.0 / 1.732_050_807_568_877_2;
            const C: [f64; 3] = [
                1.0,
                std::f64::consts::FRAC_1_SQRT_2,
                0.577_350_269_189_625_8,
            ];
            for (k, gk) in g.iter_mut().enumerate() {
                let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
                let mut s = 0.0;
                for o1 in [-1i64, 0, 1] {
                    let i1 = match o1 {
                        -1 => lo(k1),
                        0 => p[k1],
                        _ => hi(k1),
                    };
                    for o2 in [-1i64, 0, 1] {
                        let i2 = match o2 {
                            -1 => lo(k2),
                            0 => p[k2],
                            _ => hi(k2),
                        };
                        let c = C[(o1 != 0) as usize + (o2 != 0) as usize];
                        let mut a = [0usize; 3];
                        let mut b = [0usize; 3];
                        a[k] = lo(k);
                        b[k] = hi(k);
                        a[k1] = i1;
                        b[k1] = i1;
                        a[k2] = i2;
                        b[k2] = i2;
                        s += c * (at(b[0], b[1], b[2]) - at(a[0], a[1], a[2]));
                    }
                }
                let span = axes[k][hi(k)] - axes[k][lo(k)];
                *gk = s / (W * span);
            }
        }
    }
    g
}

/// Central differences with per-axis tables of the clamped neighbour offsets and plane
/// distances, for evaluating many grid points of one volume: the same arithmetic (and so the
/// same bits) as [`gradient_at`] with [`GradientOperator::Central`], without its branches.
pub(crate) struct CentralTable {
    /// `lo[k][i]`, `hi[k][i]`: linear-index offsets to the lower and upper neighbour along k.
    lo: [Vec<usize>; 3],
    hi: [Vec<usize>; 3],
    /// `span[k][i]`: coordinate distance between those neighbours.
    span: [Vec<f64>; 3],
}

impl CentralTable {
    /// Tables for `vol` (every dim ≥ 2) with plane coordinates `axes` from [`axis_coords`].
    pub(crate) fn new(vol: &Volume, axes: &[Vec<f64>; 3]) -> Self {
        let d = vol.dims;
        let st = [1usize, d[0], d[0] * d[1]];
        let lo = std::array::from_fn(|k| {
            (0..d[k])
                .map(|i| st[k] * (i - i.saturating_sub(1)))
                .collect()
        });
        let hi = std::array::from_fn(|k| {
            (0..d[k])
                .map(|i| st[k] * ((i + 1).min(d[k] - 1) - i))
                .collect()
        });
        let span = std::array::from_fn(|k| {
            (0..d[k])
                .map(|i| axes[k][(i + 1).min(d[k] - 1)] - axes[k][i.saturating_sub(1)])
                .collect()
        });
        CentralTable { lo, hi, span }
    }

    /// Gradient at grid point `p` with linear index `j` of `data` (the volume's samples).
    #[inline(always)]
    pub(crate) fn at(&self, data: &[f32], j: usize, p: [usize; 3]) -> [f64; 3] {
        [
            self.component(data, j, p, 0),
            self.component(data, j, p, 1),
            self.component(data, j, p, 2),
        ]
    }

    /// [`CentralTable::at`] at two grid points (`ja`, `a`) and (`jb`, `b`), with the six
    /// divisions written as one loop so that they can be done two at a time.
    #[inline(always)]
    pub(crate) fn at2(
        &self,
        data: &[f32],
        ja: usize,
        a: [usize; 3],
        jb: usize,
        b: [usize; 3],
    ) -> [[f64; 3]; 2] {
        let mut num = [0.0f64; 6];
        let mut den = [1.0f64; 6];
        for k in 0..3 {
            for (s, (j, p)) in [(ja, a), (jb, b)].into_iter().enumerate() {
                let (l, h) = (self.lo[k][p[k]], self.hi[k][p[k]]);
                num[2 * k + s] = data[j + h] as f64 - data[j - l] as f64;
                den[2 * k + s] = self.span[k][p[k]];
            }
        }
        let mut q = [0.0f64; 6];
        for i in 0..6 {
            q[i] = num[i] / den[i];
        }
        [[q[0], q[2], q[4]], [q[1], q[3], q[5]]]
    }

    #[inline(always)]
    fn component(&self, data: &[f32], j: usize, p: [usize; 3], k: usize) -> f64 {
        let (l, h, s) = (self.lo[k][p[k]], self.hi[k][p[k]], self.span[k][p[k]]);
        (data[j + h] as f64 - data[j - l] as f64) / s
    }
}

/// [`gradient_at`] for a point with all neighbours inside the volume (same arithmetic as the
/// general path, without clamping).
#[inline(always)]
fn gradient_interior(
    vol: &Volume,
    axes: &[Vec<f64>; 3],
    p: [usize; 3],
    op: GradientOperator,
) -> [f64; 3] {
    let d = vol.dims;
    let st = [1usize, d[0], d[0] * d[1]];
    let i = p[0] + st[1] * p[1] + st[2] * p[2];
    let data = &vol.data;
    let span = |k: usize| axes[k][p[k] + 1] - axes[k][p[k] - 1];
    match op {
        GradientOperator::Central => {
            let c = |k: usize| (data[i + st[k]] as f64 - data[i - st[k]] as f64) / span(k);
            [c(0), c(1), c(2)]
        }
        GradientOperator::ZuckerHummel => {
            const W: f64 =
                1.0 + 4.0 * std::f64::consts::FRAC_1_SQRT_2 + 4.0 / 1.732_050_807_568_877_2;
            zh_interior(data, i, st, [W * span(0), W * span(1), W * span(2)])
        }
    }
}

/// Weights of the Zucker–Hummel terms by the number of nonzero transverse offsets (H Thm. 3.8).
const ZH_C: [f64; 3] = [
    1.0,
    std::f64::consts::FRAC_1_SQRT_2,
    0.577_350_269_189_625_8,
];

/// Transverse offsets of the nine Zucker–Hummel terms of one component, in summation order.
const ZH_ORDER: [(isize, isize); 9] = [
    (0, 0),
    (0, -1),
    (0, 1),
    (-1, 0),
    (-1, -1),
    (-1, 1),
    (1, 0),
    (1, -1),
    (1, 1),
];

/// The interior Zucker–Hummel gradient at linear index `i` (strides `st`; all 26 neighbours
/// inside the data), component k divided by `wspan[k]` = W · (x₊ − x₋).
///
/// The three components share their samples: the 26 neighbours are read and widened to f64
/// once (54 reads before), then each component is summed in the order of [`ZH_ORDER`] — for
/// component k, offset (o₁, o₂) along axes k + 1, k + 2 (mod 3), `s += c · (f₊ − f₋)` from
/// s = 0.0 — which is the order of the one-component-at-a-time formula, so the result is the
/// same bits (the unit test `zh_interior_matches_the_27_point_formula_bitwise` checks this on
/// random volumes against that formula).
#[inline(always)]
fn zh_interior(data: &[f32], i: usize, st: [usize; 3], wspan: [f64; 3]) -> [f64; 3] {
    // v[(dx + 1) + 3 (dy + 1) + 9 (dz + 1)] = f(p + (dx, dy, dz)); the centre is never used
    let mut v = [0.0f64; 27];
    let base = i - st[0] - st[1] - st[2];
    for dz in 0..3 {
        for dy in 0..3 {
            let row = &data[base + dy * st[1] + dz * st[2]..][..3];
            for dx in 0..3 {
                v[dx + 3 * dy + 9 * dz] = row[dx] as f64;
            }
        }
    }
    [
        zh_sum::<0>(&v, wspan[0]),
        zh_sum::<1>(&v, wspan[1]),
        zh_sum::<2>(&v, wspan[2]),
    ]
}

/// Component `K` of [`zh_interior`] from its widened samples `v` (a const parameter, so that
/// every index below is a constant once the loop is unrolled).
#[inline(always)]
fn zh_sum<const K: usize>(v: &[f64; 27], wspan: f64) -> f64 {
    let at = |d: [isize; 3]| v[(d[0] + 1 + 3 * (d[1] + 1) + 9 * (d[2] + 1)) as usize];
    let mut s = 0.0;
    for (o1, o2) in ZH_ORDER {
        let mut d = [0isize; 3];
        d[(K + 1) % 3] = o1;
        d[(K + 2) % 3] = o2;
        d[K] = 1;
        let h = at(d);
        d[K] = -1;
        let l = at(d);
        s += ZH_C[(o1 != 0) as usize + (o2 != 0) as usize] * (h - l);
    }
    s / wspan
}

/// Vertex normals from the triangulation alone (H Rem. 3.15), oriented like the triangles.
/// Vertices without triangles get the zero vector.
pub fn mesh_normals(mesh: &TriMesh) -> Vec<Vector3> {
    mesh_normals_where(mesh, |_| true)
}

/// [`mesh_normals`] for the vertices `v` with `want(v)`; the others get the zero vector.
pub fn mesh_normals_where(mesh: &TriMesh, want: impl Fn(usize) -> bool) -> Vec<Vector3> {
    let n = mesh.positions.len();
    // area-weighted face normals: initial frame and orientation reference
    let mut acc = vec![Vector3::zeros(); n];
    let mut deg = vec![0u32; n + 1];
    for &[a, b, c] in &mesh.triangles {
        let (pa, pb, pc) = (
            mesh.positions[a as usize],
            mesh.positions[b as usize],
            mesh.positions[c as usize],
        );
        let fnrm = (pb - pa).cross(&(pc - pa));
        for v in [a, b, c] {
            acc[v as usize] += fnrm;
            deg[v as usize] += 2;
        }
    }
    // CSR of one-ring neighbours (with repetitions, harmless for least squares weighting)
    let mut start = vec![0usize; n + 1];
    for v in 0..n {
        start[v + 1] = start[v] + deg[v] as usize;
    }
    let mut fill = start.clone();
    let mut nb = vec![0u32; start[n]];
    for &[a, b, c] in &mesh.triangles {
        for (v, w1, w2) in [(a, b, c), (b, c, a), (c, a, b)] {
            let f = &mut fill[v as usize];
            nb[*f] = w1;
            nb[*f + 1] = w2;
            *f += 2;
        }
    }
    (0..n)
        .map(|v| {
            if !want(v) {
                return Vector3::zeros();
            }
            let reference = acc[v];
            let Some(mut nrm) = reference.try_normalize(0.0) else {
                return Vector3::zeros();
            };
            let ring = &nb[start[v]..start[v + 1]];
            for _ in 0..2 {
                match fit_normal(mesh, v, ring, &nrm) {
                    Some(m) => nrm = if m.dot(&reference) < 0.0 { -m } else { m },
                    None => break,
                }
            }
            nrm
        })
        .collect()
}

/// One least-squares quadric (or plane, with fewer than 6 neighbours) fit in the frame with
/// normal `n`; returns the graph normal at the vertex in world coordinates.
fn fit_normal(mesh: &TriMesh, v: usize, ring: &[u32], n: &Vector3) -> Option<Vector3> {
    let o = mesh.positions[v];
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let d1 = n.cross(&helper).normalize();
    let d2 = n.cross(&d1);
    let mut pts: Vec<(f64, f64, f64)> = Vec::with_capacity(ring.len() + 1);
    pts.push((0.0, 0.0, 0.0));
    let mut scale: f64 = 0.0;
    for &w in ring {
        let q = mesh.positions[w as usize] - o;
        let p = (q.dot(&d1), q.dot(&d2), q.dot(n));
        scale = scale.max(p.0.abs()).max(p.1.abs());
        pts.push(p);
    }
    if scale <= 0.0 || !scale.is_finite() {
        return None;
    }
    let distinct = {
        let mut u: Vec<(i64, i64)> = pts
            .iter()
            .map(|p| ((p.0 / scale * 1e9) as i64, (p.1 / scale * 1e9) as i64))
            .collect();
        u.sort_unstable();
        u.dedup();
        u.len()
    };
    let ncoef = if distinct >= 6 { 6 } else { 3 };
    if distinct < 3 {
        return None;
    }
    let mut ata = nalgebra::SMatrix::<f64, 6, 6>::zeros();
    let mut atb = nalgebra::SVector::<f64, 6>::zeros();
    for &(x, y, d) in &pts {
        let (x, y, d) = (x / scale, y / scale, d / scale);
        let row = [1.0, x, y, x * x, x * y, y * y];
        for i in 0..ncoef {
            atb[i] += row[i] * d;
            for j in 0..ncoef {
                ata[(i, j)] += row[i] * row[j];
            }
        }
    }
    let c: [f64; 3] = if ncoef == 6 {
        let c = ata.lu().solve(&atb)?;
        [c[0], c[1], c[2]]
    } else {
        let a3: nalgebra::Matrix3<f64> = ata.fixed_view::<3, 3>(0, 0).into_owned();
        let b3: nalgebra::Vector3<f64> = atb.fixed_view::<3, 1>(0, 0).into_owned();
        let c = a3.lu().solve(&b3)?;
        [c[0], c[1], c[2]]
    };
    // graph z = c0 + c1 x + c2 y + ...; normal at origin ∝ (-c1, -c2, 1) (scale cancels)
    let m = d1 * (-c[1]) + d2 * (-c[2]) + n;
    let m = m.try_normalize(0.0)?;
    if m.iter().all(|x| x.is_finite()) {
        Some(m)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::volume::Axes;

    /// Component k of the interior Zucker–Hummel gradient at linear index `i` (strides `st`),
    /// divided by `wspan` = W · (x₊ − x₋), by the direct formula: 18 samples read for this
    /// component alone (the code before the samples were shared), the oracle of
    /// [`zh_interior`].
    fn zh_component(data: &[f32], i: usize, st: [usize; 3], k: usize, wspan: f64) -> f64 {
        const C: [f64; 3] = [
            1.0,
            std::f64::consts::FRAC_1_SQRT_2,
            0.577_350_269_189_625_8,
        ];
        let (a, b) = (st[(k + 1) % 3], st[(k + 2) % 3]);
        let (hi, lo) = (i + st[k], i - st[k]);
        let mut s = 0.0;
        for (o1, w1) in [(0isize, 0usize), (-1, 1), (1, 1)] {
            for (o2, w2) in [(0isize, 0usize), (-1, 1), (1, 1)] {
                let off = o1 * a as isize + o2 * b as isize;
                let h = data[hi.wrapping_add_signed(off)] as f64;
                let l = data[lo.wrapping_add_signed(off)] as f64;
                s += C[w1 + w2] * (h - l);
            }
        }
        s / wspan
    }

    /// [`gradient_at`]'s interior Zucker–Hummel path (shared samples, [`zh_interior`]) against
    /// the direct 18-samples-per-component formula, bit for bit, at every interior point of
    /// random volumes: uniform and rectilinear axes, samples of mixed magnitudes with ±0,
    /// repeated values, NaN and ±∞ (whose differences are not exact or not finite; NaN results
    /// compare equal whatever their sign and payload), and small dims (stencils reaching the first and last planes).
    #[test]
    fn zh_interior_matches_the_27_point_formula_bitwise() {
        use crate::util::Rng;
        const W: f64 = 1.0 + 4.0 * std::f64::consts::FRAC_1_SQRT_2 + 4.0 / 1.732_050_807_568_877_2;
        let mut rng = Rng::new(0x5eed_1507);
        for case in 0..24 {
            let d = [
                3 + rng.below(6) as usize,
                3 + rng.below(6) as usize,
                3 + rng.below(6) as usize,
            ];
            let mut v = Volume::from_fn(d, [0.0; 3], [1.0, 2.0, 0.5], |_, _, _| 0.0);
            if case % 2 == 1 {
                v.axes = Axes::Coords(std::array::from_fn(|k| {
                    let mut c = 0.0;
                    (0..d[k])
                        .map(|_| {
                            c += 0.01 + rng.unit() * 3.0;
                            c
                        })
                        .collect()
                }));
            }
            for x in v.data.iter_mut() {
                *x = match rng.below(16) {
                    0 => 0.0,
                    1 => -0.0,
                    2 => 1.0,
                    3 if case >= 16 => f32::NAN,
                    4 if case >= 16 => f32::INFINITY,
                    5 if case >= 16 => f32::NEG_INFINITY,
                    6 => (rng.unit() * 1e30) as f32,
                    7 => (rng.unit() * 1e-30) as f32,
                    _ => (rng.unit() * 200.0 - 100.0) as f32,
                };
            }
            let ax = axis_coords(&v);
            let st = [1, d[0], d[0] * d[1]];
            for z in 1..d[2] - 1 {
                for y in 1..d[1] - 1 {
                    for x in 1..d[0] - 1 {
                        let p = [x, y, z];
                        let i = v.index(x, y, z);
                        let got = gradient_at(&v, &ax, p, GradientOperator::ZuckerHummel);
                        for k in 0..3 {
                            let wspan = W * (ax[k][p[k] + 1] - ax[k][p[k] - 1]);
                            let want = zh_component(&v.data, i, st, k, wspan);
                            // a NaN's sign and payload are not specified by the compiler
                            // (LLVM may swap an addition's operands); any NaN gives a zero
                            // normal downstream (`Ctx::orient`)
                            let bits = |g: f64| if g.is_nan() { 0 } else { g.to_bits() };
                            assert_eq!(
                                bits(got[k]),
                                bits(want),
                                "case {case} {p:?} component {k}: {} vs {want}",
                                got[k]
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn linear_field_gives_exact_gradient() {
        for op in [GradientOperator::Central, GradientOperator::ZuckerHummel] {
            let mut v = Volume::from_fn([5, 4, 6], [0.0, -1.0, 2.0], [2.0, 5.0, 3.0], |x, y, z| {
                3.0 * x - 2.0 * y + 0.5 * z
            });
            // also a rectilinear, non-uniform grid
            let coords = [
                vec![0.0, 0.1, 0.5, 0.6, 2.0],
                vec![-1.0, 0.0, 3.0, 5.0],
                vec![2.0, 2.1, 2.2, 2.5, 2.9, 3.0],
            ];
            for pass in 0..2 {
                if pass == 1 {
                    v.axes = Axes::Coords(coords.clone());
                    for z in 0..6 {
                        for y in 0..4 {
                            for x in 0..5 {
                                let i = v.index(x, y, z);
                                v.data[i] = (3.0 * coords[0][x] - 2.0 * coords[1][y]
                                    + 0.5 * coords[2][z])
                                    as f32;
                            }
                        }
                    }
                }
                let ax = axis_coords(&v);
                for p in [[0, 0, 0], [2, 1, 3], [4, 3, 5], [1, 2, 0]] {
                    let g = gradient_at(&v, &ax, p, op);
                    assert!((g[0] - 3.0).abs() < 1e-5, "{op:?} {p:?} {g:?}");
                    assert!((g[1] + 2.0).abs() < 1e-5, "{op:?} {p:?} {g:?}");
                    assert!((g[2] - 0.5).abs() < 1e-5, "{op:?} {p:?} {g:?}");
                }
            }
        }
    }

    #[test]
    fn central_table_matches_gradient_at_bitwise() {
        let mut v = Volume::from_fn([5, 2, 4], [0.0; 3], [1.0, 2.0, 3.0], |x, y, z| {
            (3.0 * x).sin() + y * z * z
        });
        v.axes = Axes::Coords([
            vec![0.0, 0.1, 0.5, 0.6, 2.0],
            vec![-1.0, 0.3],
            vec![2.0, 2.1, 2.25, 2.9],
        ]);
        v.data[7] = f32::NAN;
        let ax = axis_coords(&v);
        let tab = CentralTable::new(&v, &ax);
        for z in 0..4 {
            for y in 0..2 {
                for x in 0..5 {
                    let want = gradient_at(&v, &ax, [x, y, z], GradientOperator::Central);
                    let got = tab.at(&v.data, v.index(x, y, z), [x, y, z]);
                    for k in 0..3 {
                        assert_eq!(want[k].to_bits(), got[k].to_bits(), "{x} {y} {z} {k}");
                    }
                }
            }
        }
    }

    #[test]
    fn zucker_weights_follow_thm_3_8() {
        // a single unit impulse at (2,1,1) seen from (1,1,1): x component weight 1, from (1,0,1):
        // weight 1/sqrt 2, from (1,0,0): 1/sqrt 3 (before the span normalisation).
        let mut v = Volume::from_fn([4, 3, 3], [0.0; 3], [3.0, 2.0, 2.0], |_, _, _| 0.0);
        let i = v.index(2, 1, 1);
        v.data[i] = 1.0;
        let ax = axis_coords(&v);
        let w = 1.0 + 4.0 / 2f64.sqrt() + 4.0 / 3f64.sqrt();
        let g = gradient_at(&v, &ax, [1, 1, 1], GradientOperator::ZuckerHummel);
        assert!((g[0] * w * 2.0 - 1.0).abs() < 1e-12);
        let g = gradient_at(&v, &ax, [1, 0, 1], GradientOperator::ZuckerHummel);
        assert!((g[0] * w * 2.0 - 1.0 / 2f64.sqrt()).abs() < 1e-12);
        let g = gradient_at(&v, &ax, [1, 0, 0], GradientOperator::ZuckerHummel);
        assert!((g[0] * w * 2.0 - 1.0 / 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn mesh_normals_of_a_planar_fan_and_a_paraboloid() {
        use crate::geom::Point3;
        // vertex 0 at the apex of z = x^2 + y^2 with a ring of 8: normal (0,0,1)
        let mut pos = vec![Point3::new(0.0, 0.0, 0.0)];
        for k in 0..8 {
            let a = k as f64 * std::f64::consts::PI / 4.0;
            let (x, y) = (0.3 * a.cos() + 0.01, 0.3 * a.sin());
            pos.push(Point3::new(x, y, x * x + y * y));
        }
        let tris: Vec<[u32; 3]> = (0..8).map(|k| [0, 1 + k, 1 + (k + 1) % 8]).collect();
        let m = TriMesh::new(pos, tris);
        let n = mesh_normals(&m);
        // the quadric fit recovers the true normal at the apex (0,0,1) closely
        assert!(n[0].z > 0.999, "{:?}", n[0]);
        // flipping the triangles flips the normal
        let mut m2 = m.clone();
        for t in &mut m2.triangles {
            t.swap(1, 2);
        }
        assert!(mesh_normals(&m2)[0].z < -0.999);
    }
}

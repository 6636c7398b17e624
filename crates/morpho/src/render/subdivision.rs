//! Domain-subdivision view of a volume (Hamann 1991, §2.2): the domain box C is split into
//! `q_x × q_y × q_z` sub-boxes `V_{r,s,t}` separated by gaps, so that one can "look inside"; the
//! faces of every sub-box are coloured by the function values on them.
//!
//! Sub-box geometry exactly as in §2.2: with gap ratio `α` (space between two consecutive
//! sub-boxes relative to a sub-box edge),
//! `Δx = (x_max − x_min) / (q_x + α_x (q_x − 1))`, `x_r = x_min + r (1 + α_x) Δx`,
//! `r = 0 … q_x − 1` (likewise for y and z). Function values at points of the faces come from
//! the trilinear interpolant of the eight surrounding grid values. Each face is evaluated on a
//! `(k+1) × (k+1)` grid of points (Hamann's refinement for large sub-boxes; `k = 1` gives only
//! the four corners) and split into triangles; the renderer interpolates the values over each
//! triangle (Gouraud-style colouring, [`super::raster`]).
//!
//! Output: a [`TriMesh`] with outward faces and the vertex property `value`; render it with
//! [`super::raster::render_mesh`] and `Scalars` from that property. Size: `6 q_x q_y q_z (k+1)²`
//! vertices, `12 q_x q_y q_z k²` triangles; time linear in that.
//!
//! The transparency view of §2.2 is [`grid_planes_mesh`]: the three sets of grid rectangles
//! parallel to the xy-, xz- and yz-planes coloured by the samples at their corners; render it
//! with `RenderOptions::transparency = Some(t)` (back-to-front alpha blending).

use super::RenderError;
use crate::geom::Point3;
use crate::mesh::{Property, ScalarKind, TriMesh};
use crate::volume::Volume;
use crate::Result;

/// Largest number of triangles [`domain_subdivision_mesh`] builds.
pub const MAX_TRIANGLES: usize = 20_000_000;

/// Cell index and weight along axis `k` for coordinate `x` (clamped to the grid).
fn locate(vol: &Volume, k: usize, x: f64) -> (usize, usize, f64) {
    let n = vol.dims[k];
    if n == 1 {
        return (0, 0, 0.0);
    }
    let (c0, cn) = (vol.coord(k, 0), vol.coord(k, n - 1));
    if x <= c0 {
        return (0, 0, 0.0);
    }
    if x >= cn {
        return (n - 1, n - 1, 0.0);
    }
    // First plane strictly greater than x (binary search over the coordinates).
    let (mut lo, mut hi) = (0usize, n - 1);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if vol.coord(k, mid) <= x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (a, b) = (vol.coord(k, lo), vol.coord(k, hi));
    (lo, hi, ((x - a) / (b - a)).clamp(0.0, 1.0))
}

/// The trilinear interpolant of the grid values at `p` (clamped to the domain).
pub fn trilinear(vol: &Volume, p: [f64; 3]) -> f64 {
    let (x0, x1, tx) = locate(vol, 0, p[0]);
    let (y0, y1, ty) = locate(vol, 1, p[1]);
    let (z0, z1, tz) = locate(vol, 2, p[2]);
    let f = |x, y, z| vol.at(x, y, z) as f64;
    let lerp = |a: f64, b: f64, t: f64| if t == 0.0 { a } else { a + t * (b - a) };
    let c00 = lerp(f(x0, y0, z0), f(x1, y0, z0), tx);
    let c10 = lerp(f(x0, y1, z0), f(x1, y1, z0), tx);
    let c01 = lerp(f(x0, y0, z1), f(x1, y0, z1), tx);
    let c11 = lerp(f(x0, y1, z1), f(x1, y1, z1), tx);
    lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz)
}

/// Hamann's sub-boxes: `q` boxes per axis (each ≥ 1), gap ratios `alpha` (each ≥ 0), every
/// face evaluated on a `(k+1)²` grid (`k ≥ 1`). See the module documentation.
pub fn domain_subdivision_mesh(
    vol: &Volume,
    q: [usize; 3],
    alpha: [f64; 3],
    k: usize,
) -> Result<TriMesh, RenderError> {
    vol.validate()?;
    if vol.dims.contains(&0) {
        return Err(RenderError::EmptyVolume { dims: vol.dims });
    }
    if q.contains(&0) || k == 0 {
        return Err(RenderError::SubBoxes { boxes: q, k });
    }
    if alpha.iter().any(|a| !a.is_finite() || *a < 0.0) {
        return Err(RenderError::GapRatios { ratios: alpha });
    }
    let boxes = q[0]
        .checked_mul(q[1])
        .and_then(|v| v.checked_mul(q[2]))
        .and_then(|v| v.checked_mul(12 * k * k))
        .filter(|&t| t <= MAX_TRIANGLES)
        .ok_or(RenderError::TooManyBoxTriangles { max: MAX_TRIANGLES })?;
    let lo: [f64; 3] = std::array::from_fn(|a| vol.coord(a, 0));
    let hi: [f64; 3] = std::array::from_fn(|a| vol.coord(a, vol.dims[a] - 1));
    let mut m = subdivision_mesh_with(lo, hi, q, alpha, k, boxes, |p| {
        (Point3::new(p[0], p[1], p[2]), trilinear(vol, p))
    });
    m.vertex_props[0].name = "value".into();
    Ok(m)
}

/// The lower corners and edge lengths of Hamann's sub-boxes along one axis (§2.2):
/// `Δ = (hi − lo) / (q + α (q − 1))`, `x_r = lo + r (1 + α) Δ`, `r = 0 … q − 1`. The last box's
/// far face `x_{q−1} + Δ` is `hi` up to rounding.
///
/// ```
/// let (starts, d) = morpho::render::subbox_starts(0.0, 39.0, 5, 1.0);
/// assert_eq!(starts.len(), 5);
/// assert!((starts[4] + d - 39.0).abs() < 1e-12);
/// ```
pub fn subbox_starts(lo: f64, hi: f64, q: usize, alpha: f64) -> (Vec<f64>, f64) {
    let d = (hi - lo) / (q as f64 + alpha * (q as f64 - 1.0));
    (
        (0..q).map(|r| lo + r as f64 * (1.0 + alpha) * d).collect(),
        d,
    )
}

/// The sub-box mesh over the parameter box `[lo, hi]` (uvw-space for curvilinear volumes,
/// Hamann §2.2): `eval(uvw)` gives the mapped position and the value. `cap` reserves triangles.
pub(super) fn subdivision_mesh_with(
    lo: [f64; 3],
    hi: [f64; 3],
    q: [usize; 3],
    alpha: [f64; 3],
    k: usize,
    cap: usize,
    eval: impl Fn([f64; 3]) -> (Point3, f64),
) -> TriMesh {
    let axes: [(Vec<f64>, f64); 3] =
        std::array::from_fn(|a| subbox_starts(lo[a], hi[a], q[a], alpha[a]));
    let delta: [f64; 3] = std::array::from_fn(|a| axes[a].1);
    let mut positions = Vec::with_capacity(cap / 2 + 8);
    let mut values = Vec::with_capacity(cap / 2 + 8);
    let mut triangles = Vec::with_capacity(cap);
    // The six faces of the unit cube: fixed axis, its side, and the two in-face axes ordered so
    // that (u × v) points outwards.
    const FACES: [(usize, f64, usize, usize); 6] = [
        (0, 0.0, 2, 1),
        (0, 1.0, 1, 2),
        (1, 0.0, 0, 2),
        (1, 1.0, 2, 0),
        (2, 0.0, 1, 0),
        (2, 1.0, 0, 1),
    ];
    for t in 0..q[2] {
        for s in 0..q[1] {
            for r in 0..q[0] {
                let idx = [r, s, t];
                let corner: [f64; 3] = std::array::from_fn(|a| axes[a].0[idx[a]]);
                for &(fa, side, ua, va) in &FACES {
                    let base = positions.len() as u32;
                    for j in 0..=k {
                        for i in 0..=k {
                            let mut p = [0.0; 3];
                            p[fa] = if side > 0.0 {
                                corner[fa] + delta[fa]
                            } else {
                                corner[fa]
                            };
                            p[ua] = corner[ua] + i as f64 / k as f64 * delta[ua];
                            p[va] = corner[va] + j as f64 / k as f64 * delta[va];
                            let (x, f) = eval(p);
                            positions.push(x);
                            values.push(f);
                        }
                    }
                    let id = |i: usize, j: usize| base + (j * (k + 1) + i) as u32;
                    for j in 0..k {
                        for i in 0..k {
                            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                        }
                    }
                }
            }
        }
    }
    let mut m = TriMesh::new(positions, triangles);
    m.vertex_props.push(Property {
        name: "value".into(),
        kind: ScalarKind::F64,
        values,
    });
    m
}

/// Hamann's three sets of rectangles (§2.2, transparency): every grid cell of the planes
/// `z = z_k`, `y = y_j`, `x = x_i`, taking every `stride[a]`-th plane along axis `a` (the last
/// plane always included), each rectangle split into two triangles, vertex property `value` =
/// the samples. Planes with fewer than 2 × 2 samples are left out.
pub fn grid_planes_mesh(vol: &Volume, stride: [usize; 3]) -> Result<TriMesh, RenderError> {
    vol.validate()?;
    if vol.dims.contains(&0) {
        return Err(RenderError::EmptyVolume { dims: vol.dims });
    }
    let stride = stride.map(|s| s.max(1));
    let planes = |a: usize| -> Vec<usize> {
        let n = vol.dims[a];
        let mut v: Vec<usize> = (0..n).step_by(stride[a]).collect();
        if v.last() != Some(&(n - 1)) {
            v.push(n - 1);
        }
        v
    };
    let mut total = 0usize;
    for a in 0..3 {
        let (u, w) = ((a + 1) % 3, (a + 2) % 3);
        let cells = vol.dims[u].saturating_sub(1) * vol.dims[w].saturating_sub(1);
        total = total.saturating_add(planes(a).len().saturating_mul(2 * cells));
    }
    if total > MAX_TRIANGLES {
        return Err(RenderError::TooManyPlaneTriangles { triangles: total });
    }
    let mut positions = Vec::new();
    let mut values = Vec::new();
    let mut triangles = Vec::with_capacity(total);
    // A grid point on planes of several families is one vertex (a third of the vertices for
    // stride 1), through a table over the grid when it is not much larger than the mesh;
    // otherwise each plane has its own vertices. The triangles are the same either way.
    let shared = vol.len() <= total.saturating_mul(4);
    let mut vertex_of = vec![u32::MAX; if shared { vol.len() } else { 0 }];
    for a in 0..3 {
        // In-plane axes (u, w) cyclic after a, so that u × w points along +a.
        let (u, w) = ((a + 1) % 3, (a + 2) % 3);
        let (nu, nw) = (vol.dims[u], vol.dims[w]);
        if nu < 2 || nw < 2 {
            continue;
        }
        for c in planes(a) {
            let mut ids = Vec::with_capacity(nu * nw);
            for j in 0..nw {
                for i in 0..nu {
                    let mut g = [0usize; 3];
                    g[a] = c;
                    g[u] = i;
                    g[w] = j;
                    let gi = vol.index(g[0], g[1], g[2]);
                    if shared && vertex_of[gi] != u32::MAX {
                        ids.push(vertex_of[gi]);
                        continue;
                    }
                    let id = positions.len() as u32;
                    positions.push(Point3::new(
                        vol.coord(0, g[0]),
                        vol.coord(1, g[1]),
                        vol.coord(2, g[2]),
                    ));
                    values.push(vol.data[gi] as f64);
                    if shared {
                        vertex_of[gi] = id;
                    }
                    ids.push(id);
                }
            }
            let id = |i: usize, j: usize| ids[j * nu + i];
            for j in 0..nw - 1 {
                for i in 0..nu - 1 {
                    triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                    triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
        }
    }
    let mut m = TriMesh::new(positions, triangles);
    m.vertex_props.push(Property {
        name: "value".into(),
        kind: ScalarKind::F64,
        values,
    });
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trilinear_reproduces_linear_functions() {
        let v = Volume::from_fn([4, 5, 3], [0.0, -1.0, 2.0], [3.0, 1.0, 4.0], |x, y, z| {
            2.0 * x - y + 0.5 * z
        });
        for p in [[0.3, -0.2, 2.7], [3.0, 1.0, 4.0], [1.5, 0.0, 3.0]] {
            let want = 2.0 * p[0] - p[1] + 0.5 * p[2];
            assert!((trilinear(&v, p) - want).abs() < 1e-5, "{p:?}");
        }
        // Clamped outside the domain.
        assert!((trilinear(&v, [-5.0, -1.0, 2.0]) - 2.0).abs() < 1e-5);
    }

    #[test]
    fn hamann_subbox_geometry_and_orientation() {
        let v = Volume::from_fn([5, 5, 5], [0.0; 3], [4.0; 3], |x, y, z| x + y + z);
        let (q, a, k) = ([3, 2, 1], [1.0, 0.5, 0.0], 2);
        let m = domain_subdivision_mesh(&v, q, a, k).unwrap();
        m.validate().unwrap();
        let nbox = 6;
        assert_eq!(m.triangles.len(), nbox * 12 * k * k);
        assert_eq!(m.positions.len(), nbox * 6 * (k + 1) * (k + 1));
        // Δx = 4 / (3 + 1·2) = 0.8; boxes at 0, 1.6, 3.2; the last ends at the domain end.
        let b = m.bbox();
        assert!((b.max[0] - 4.0).abs() < 1e-12 && b.min[0].abs() < 1e-12);
        let xs: std::collections::BTreeSet<i64> = m
            .positions
            .iter()
            .map(|p| (p.x * 1000.0).round() as i64)
            .collect();
        assert!(
            xs.contains(&1600) && xs.contains(&2400) && !xs.contains(&1200) && !xs.contains(&2800)
        );
        // Each box is closed and outward: total signed volume = sum of box volumes.
        let dy = 4.0 / (2.0 + 0.5);
        let one = 0.8 * dy * 4.0;
        assert!(
            (m.signed_volume() - 6.0 * one).abs() < 1e-9,
            "{}",
            m.signed_volume()
        );
        // Values are the linear function at the vertices.
        let val = &m.vertex_prop("value").unwrap().values;
        for (p, f) in m.positions.iter().zip(val) {
            assert!((p.x + p.y + p.z - f).abs() < 1e-5);
        }
        assert!(domain_subdivision_mesh(&v, [0, 1, 1], a, 1).is_err());
        assert!(domain_subdivision_mesh(&v, [1, 1, 1], [-1.0, 0.0, 0.0], 1).is_err());
        assert!(domain_subdivision_mesh(&v, [100_000, 100_000, 100_000], a, 1).is_err());
    }

    #[test]
    fn grid_planes_counts() {
        let v = Volume::from_fn([4, 3, 5], [0.0; 3], [3.0, 2.0, 4.0], |x, y, z| {
            x + 10.0 * y + 100.0 * z
        });
        let m = grid_planes_mesh(&v, [1, 1, 1]).unwrap();
        m.validate().unwrap();
        // x-planes: 4 × (2·4 cells); y-planes: 3 × (4·3); z-planes: 5 × (3·2); two triangles each.
        assert_eq!(m.triangles.len(), 2 * (4 * 8 + 3 * 12 + 5 * 6));
        let val = &m.vertex_prop("value").unwrap().values;
        for (p, f) in m.positions.iter().zip(val) {
            assert!((p.x + 10.0 * p.y + 100.0 * p.z - f).abs() < 1e-3);
        }
        // Grid points shared by the three families are one vertex each: every grid point of
        // this 4×3×5 grid lies on a plane, so there are 60 vertices.
        assert_eq!(m.positions.len(), 60);
        // Stride 2 along z: planes 0, 2, 4.
        let m2 = grid_planes_mesh(&v, [100, 100, 2]).unwrap();
        assert_eq!(m2.triangles.len(), 2 * (2 * 8 + 2 * 12 + 3 * 6));
    }
}

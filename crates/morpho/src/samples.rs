//! Sample data generators for tests and the demo: a chalice-like outline (the 2D boundary
//! problem of Veltkamp 1992, ch. 5), the 3D Shepp–Logan head phantom (a standard test volume for
//! contour surfaces), points on surfaces, and a synthetic "borehole" field of rated samples.
//!
//! All generators are deterministic for a given seed (ChaCha8).

use crate::geom::{Point2, Point3};
use crate::mesh::{Column, PointSet};
use crate::volume::Volume;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Control polygon of a chalice silhouette (right half, from the foot's rim up to the cup's rim),
/// mirrored to a closed outline. Units: the chalice is about 2 wide and 3 high.
const CHALICE_HALF: [[f64; 2]; 15] = [
    [0.0, 0.0],
    [0.75, 0.0],
    [0.8, 0.1],
    [0.3, 0.22],
    [0.12, 0.45],
    [0.1, 1.1],
    [0.18, 1.35],
    [0.7, 1.7],
    [0.95, 2.3],
    [1.0, 2.85],
    [0.97, 3.0],
    [0.9, 2.85],
    [0.84, 2.4],
    [0.6, 2.05],
    [0.0, 1.9],
];

/// Points sampled from a closed chalice-like outline, in boundary order, with roughly uniform
/// arc-length spacing. `jitter` displaces each point randomly by up to that fraction of the
/// spacing (0 = exactly on the curve). The result has `n` points (n ≥ 8).
///
/// ```
/// let p = morpho::samples::chalice_outline(200, 0.0, 1);
/// assert_eq!(p.len(), 200);
/// ```
pub fn chalice_outline(n: usize, jitter: f64, seed: u64) -> Vec<Point2> {
    // closed control polygon: right half up to the cup rim, inner cup bottom, left half mirrored
    let mut ctrl: Vec<Point2> = Vec::new();
    for p in CHALICE_HALF.iter().take(CHALICE_HALF.len() - 1) {
        ctrl.push(Point2::new(p[0], p[1]));
    }
    ctrl.push(Point2::new(0.0, CHALICE_HALF[CHALICE_HALF.len() - 1][1]));
    for p in CHALICE_HALF
        .iter()
        .take(CHALICE_HALF.len() - 1)
        .skip(1)
        .rev()
    {
        ctrl.push(Point2::new(-p[0], p[1]));
    }
    sample_closed_catmull_rom(&ctrl, n.max(8), jitter, seed)
}

/// Samples `n` points with equal arc-length spacing from the closed centripetal-free (uniform)
/// Catmull–Rom spline through `ctrl`.
pub fn sample_closed_catmull_rom(ctrl: &[Point2], n: usize, jitter: f64, seed: u64) -> Vec<Point2> {
    let m = ctrl.len();
    let eval = |s: f64| -> Point2 {
        let i = (s.floor() as isize).rem_euclid(m as isize) as usize;
        let t = s - s.floor();
        let p0 = ctrl[(i + m - 1) % m].coords;
        let p1 = ctrl[i].coords;
        let p2 = ctrl[(i + 1) % m].coords;
        let p3 = ctrl[(i + 2) % m].coords;
        let t2 = t * t;
        let t3 = t2 * t;
        let v = 0.5
            * ((2.0 * p1)
                + (-p0 + p2) * t
                + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
                + (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t3);
        Point2::from(v)
    };
    // dense polyline for arc length
    let dense_n = 400 * m;
    let dense: Vec<Point2> = (0..=dense_n)
        .map(|k| eval(k as f64 * m as f64 / dense_n as f64))
        .collect();
    let mut cum = vec![0.0; dense.len()];
    for k in 1..dense.len() {
        cum[k] = cum[k - 1] + (dense[k] - dense[k - 1]).norm();
    }
    let total = cum[dense.len() - 1];
    let h = total / n as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    let mut k = 0;
    for j in 0..n {
        let target = j as f64 * h;
        while k + 1 < dense.len() && cum[k + 1] < target {
            k += 1;
        }
        let seg = (cum[k + 1] - cum[k]).max(f64::MIN_POSITIVE);
        let t = ((target - cum[k]) / seg).clamp(0.0, 1.0);
        let mut p = dense[k] + (dense[k + 1] - dense[k]) * t;
        if jitter > 0.0 {
            let a: f64 = rng.gen::<f64>() * std::f64::consts::TAU;
            let r: f64 = rng.gen::<f64>() * jitter * h;
            p += nalgebra::Vector2::new(a.cos(), a.sin()) * r;
        }
        out.push(p);
    }
    out
}

/// One ellipsoid of the 3D Shepp–Logan phantom: intensity `a`, semi-axes, centre, rotation
/// about z in degrees.
struct Ellipsoid {
    a: f64,
    axes: [f64; 3],
    center: [f64; 3],
    rot_z_deg: f64,
}

/// The ten ellipsoids of the 3D Shepp–Logan phantom with the "modified" (Toft) contrast, on the
/// cube [-1, 1]³. The two ellipsoids with Euler angles (φ, θ=0, ψ) are rotated about z by φ + ψ.
const SHEPP_LOGAN: [(f64, [f64; 3], [f64; 3], f64); 10] = [
    (1.0, [0.69, 0.92, 0.81], [0.0, 0.0, 0.0], 0.0),
    (-0.8, [0.6624, 0.874, 0.78], [0.0, -0.0184, 0.0], 0.0),
    (-0.2, [0.11, 0.31, 0.22], [0.22, 0.0, 0.0], -8.0),
    (-0.2, [0.16, 0.41, 0.28], [-0.22, 0.0, 0.0], 28.0),
    (0.1, [0.21, 0.25, 0.41], [0.0, 0.35, -0.15], 0.0),
    (0.1, [0.046, 0.046, 0.05], [0.0, 0.1, 0.25], 0.0),
    (0.1, [0.046, 0.046, 0.05], [0.0, -0.1, 0.25], 0.0),
    (0.1, [0.046, 0.023, 0.05], [-0.08, -0.605, 0.0], 0.0),
    (0.1, [0.023, 0.023, 0.02], [0.0, -0.606, 0.0], 0.0),
    (0.1, [0.023, 0.046, 0.02], [0.06, -0.605, 0.0], 0.0),
];

/// Value of the 3D Shepp–Logan phantom at (x, y, z) ∈ [-1, 1]³: the sum of the intensities of
/// the ellipsoids containing the point (skull 1.0, brain 0.2, ventricles 0.0, tumours 0.3 …).
pub fn shepp_logan(x: f64, y: f64, z: f64) -> f64 {
    let mut v = 0.0;
    for &(a, axes, center, rot) in &SHEPP_LOGAN {
        let e = Ellipsoid {
            a,
            axes,
            center,
            rot_z_deg: rot,
        };
        let (s, c) = e.rot_z_deg.to_radians().sin_cos();
        let (dx, dy, dz) = (x - e.center[0], y - e.center[1], z - e.center[2]);
        let (u, w) = (c * dx + s * dy, -s * dx + c * dy);
        let q = (u / e.axes[0]).powi(2) + (w / e.axes[1]).powi(2) + (dz / e.axes[2]).powi(2);
        if q <= 1.0 {
            v += e.a;
        }
    }
    v
}

/// The Shepp–Logan phantom sampled on an `n³` grid over [-1, 1]³, each sample the mean of 2³
/// point samples spread over its voxel (the partial-volume effect of a real scanner, which
/// gives contour surfaces without staircase terraces).
pub fn shepp_logan_volume(n: usize) -> Volume {
    let h = if n > 1 { 2.0 / (n - 1) as f64 } else { 1.0 };
    let q = 0.25 * h;
    Volume::from_fn([n, n, n], [-1.0; 3], [1.0; 3], |x, y, z| {
        let mut s = 0.0;
        for dx in [-q, q] {
            for dy in [-q, q] {
                for dz in [-q, q] {
                    s += shepp_logan(x + dx, y + dy, z + dz);
                }
            }
        }
        s / 8.0
    })
}

/// `n` points spread uniformly over the unit sphere (Fibonacci lattice), scaled by `r`.
///
/// ```
/// let pts = morpho::samples::sphere_points(100, 2.0);
/// assert_eq!(pts.len(), 100);
/// assert!(pts.iter().all(|p| (p.coords.norm() - 2.0).abs() < 1e-12));
/// ```
pub fn sphere_points(n: usize, r: f64) -> Vec<Point3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let rho = (1.0 - z * z).max(0.0).sqrt();
            let t = golden * i as f64;
            Point3::new(r * rho * t.cos(), r * rho * t.sin(), r * z)
        })
        .collect()
}

/// A synthetic borehole field: `n` sample sites uniformly in [0, 1000]², each with a `value`
/// column from three Gaussian "deposits" plus noise (values roughly 0..100).
///
/// ```
/// let f = morpho::samples::borehole_field(50, 7);
/// assert_eq!((f.len(), f.dim), (50, 2));
/// assert!(f.column("value").is_some());
/// assert_eq!(f, morpho::samples::borehole_field(50, 7)); // the seed fixes the field
/// ```
pub fn borehole_field(n: usize, seed: u64) -> PointSet {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let deposits = [
        (300.0, 650.0, 140.0, 80.0),
        (700.0, 300.0, 110.0, 70.0),
        (720.0, 760.0, 60.0, 55.0),
    ];
    let mut coords = Vec::with_capacity(2 * n);
    let mut values = Vec::with_capacity(n);
    for _ in 0..n {
        let x: f64 = rng.gen::<f64>() * 1000.0;
        let y: f64 = rng.gen::<f64>() * 1000.0;
        let mut v = 5.0 * rng.gen::<f64>();
        for &(cx, cy, s, a) in &deposits {
            let d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            v += a * (-d2 / (2.0 * s * s)).exp();
        }
        coords.extend_from_slice(&[x, y]);
        values.push(v);
    }
    PointSet {
        dim: 2,
        coords,
        columns: vec![Column {
            name: "value".into(),
            values,
        }],
    }
}

/// A non-degenerate Delaunay triangulation without a Hamilton cycle (V §5.4, Fig. 5.7, after
/// Dillencourt 1987): 20 points whose Delaunay triangulation is two-connected (not
/// three-connected) and non-Hamiltonian, so the γ-constriction of the Delaunay graph cannot reach
/// every point and the §5.4 fallback (`γ([-1,1],[c,1])`, c < 0) is needed.
///
/// Construction (our own, from first principles; Dillencourt's coordinates are not reproduced).
/// Delaunay triangulations are 1-tough (Dillencourt, "Toughness and Delaunay triangulations",
/// 1990), so no tough set certifies non-Hamiltonicity; *forced edges* do. Indices 0–6 are
/// consecutive hull vertices (clockwise) s0, h1, s1, h2, s2, h3, s3; 7 and 8 are v and w inside:
/// - h1, h2, h3 are "ears": hull vertices of degree 2 (h1 ~ s0, s1; h2 ~ s1, s2; h3 ~ s2, s3).
///   A Hamilton cycle must use both edges of a degree-2 vertex, so s1's two cycle edges are
///   s1h1 and s1h2, and s2's are s2h2 and s2h3;
/// - v has degree 3 with neighbours s1, s2 and w. Its edges to s1 and s2 are therefore unusable
///   and v has one usable edge: no Hamilton cycle exists.
///
/// Realising this as a Delaunay triangulation needs care: an ear's apex angle plus the angle
/// opposite its base must stay below π, and the ears' base angles together must fit in the hull
/// turning at the s vertices. The coordinates were found by a randomised search over this
/// template (ears placed from the turning angles at s0..s3; w low in the quadrilateral
/// s0 s1 s2 s3 so that v's two obtuse triangles have empty circumcircles), then eleven extra
/// interior points were added one at a time while the structure held, and the coordinates were
/// rounded to 10⁻³. Verified with the exact predicates in `tests/dillencourt.rs`: the structure
/// above, no four cocircular points across any Delaunay edge (the triangulation is unique),
/// two-connectedness, and no Hamilton cycle by exhaustive search. The γ-constriction of the
/// Delaunay graph leaves v out; the adaptive fallback succeeds with c = −0.1.
pub fn dillencourt_points() -> Vec<Point2> {
    [
        [-1.619, 0.0],   // s0
        [-4.99, 0.774],  // h1
        [-0.984, 4.611], // s1
        [0.045, 5.338],  // h2
        [1.212, 4.49],   // s2
        [5.774, 0.188],  // h3
        [2.376, -0.244], // s3
        [0.126, 2.946],  // v
        [0.137, 2.436],  // w
        [1.755, -0.311],
        [0.47, 0.375],
        [-0.034, 1.46],
        [-0.472, 0.566],
        [0.646, 0.978],
        [-0.336, -0.01],
        [1.065, 0.372],
        [-0.95, 0.179],
        [0.572, -0.436],
        [1.119, -0.293],
        [0.029, 0.815],
    ]
    .iter()
    .map(|&[x, y]| Point2::new(x, y))
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chalice_is_closed_and_evenly_spaced() {
        let p = chalice_outline(300, 0.0, 1);
        assert_eq!(p.len(), 300);
        let d: Vec<f64> = (0..p.len())
            .map(|i| (p[(i + 1) % p.len()] - p[i]).norm())
            .collect();
        let max = d.iter().cloned().fold(0.0, f64::max);
        // chords are at most the arc spacing and not much shorter, even at the foot's corners
        assert!(d.iter().all(|&x| x > 0.3 * max), "{d:?}");
        // the outline is a simple polygon (exact segment intersection test)
        let n = p.len();
        let o = |a: usize, b: usize, c: usize| {
            crate::graphs::gamma::sign(crate::geom::orient2d(&p[a % n], &p[b % n], &p[c % n]))
        };
        for i in 0..n {
            for j in i + 2..n {
                if (j + 1) % n == i {
                    continue;
                }
                let cross = o(i, i + 1, j) * o(i, i + 1, j + 1) < 0.0
                    && o(j, j + 1, i) * o(j, j + 1, i + 1) < 0.0;
                assert!(!cross, "edges {i} and {j} cross");
            }
        }
        // symmetric about x = 0: as many points left as right (within 2)
        let left = p.iter().filter(|q| q.x < 0.0).count() as i64;
        assert!((left - (300 - left)).abs() <= 4);
    }

    #[test]
    fn shepp_logan_values() {
        assert_eq!(shepp_logan(0.0, 0.0, 0.0), 1.0 - 0.8);
        assert_eq!(shepp_logan(0.0, 0.0, 0.8), 1.0); // skull shell only
        assert_eq!(shepp_logan(0.95, 0.95, 0.95), 0.0); // outside
        assert!((shepp_logan(0.22, 0.0, 0.0) - 0.0).abs() < 1e-12); // ventricle
        let v = shepp_logan_volume(16);
        assert_eq!(v.len(), 16 * 16 * 16);
    }

    #[test]
    fn sphere_points_are_on_sphere() {
        for p in sphere_points(100, 2.0) {
            assert!((p.coords.norm() - 2.0).abs() < 1e-12);
        }
    }

    #[test]
    fn borehole_field_is_deterministic() {
        let a = borehole_field(50, 7);
        let b = borehole_field(50, 7);
        assert_eq!(a, b);
        assert_eq!(a.len(), 50);
        assert!(a.column("value").unwrap().values.iter().all(|v| *v >= 0.0));
    }
}

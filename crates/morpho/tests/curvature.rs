//! Curvature (H ch. 4): exactness oracles, convergence, orientation, Tables 4.1 and 4.2.
#![allow(clippy::needless_range_loop)]

use morpho::curvature::tables::{table_4_1, table_4_2};
use morpho::curvature::{
    surface_curvature, trivariate_curvature, CurvatureError, Gradients, NormalSource,
    SurfaceOptions, VertexStatus,
};
use morpho::geom::{Point3, Vector3};
use morpho::mesh::{generate, NormalWeighting, TriMesh};
use rand::{Rng as _, SeedableRng};

type Rng = rand_chacha::ChaCha8Rng;

trait Below {
    fn below(&mut self, n: u64) -> u64;
}
impl Below for Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.gen_range(0..n)
    }
}
use nalgebra::{Matrix3, Rotation3};

fn unif(r: &mut Rng) -> f64 {
    r.gen::<f64>()
}

fn eig2(a: f64, b: f64, c: f64) -> [f64; 2] {
    let m = (a + c) / 2.0;
    let r = (((a - c) / 2.0).powi(2) + b * b).sqrt();
    [m - r, m + r]
}

/// A quadratic form sampled on a random non-degenerate 1-ring around the origin, rotated and
/// translated rigidly, with its exact normal: the fit is exact.
#[test]
fn quadratic_forms_are_exact_on_any_one_ring() {
    let mut rng = Rng::seed_from_u64(20);
    for case in 0..300 {
        let (al, be, ga) = (
            4.0 * unif(&mut rng) - 2.0,
            4.0 * unif(&mut rng) - 2.0,
            4.0 * unif(&mut rng) - 2.0,
        );
        let m = 3 + rng.below(8) as usize;
        let scale = 10f64.powi(rng.below(7) as i32 - 3);
        let mut ang: Vec<f64> = (0..m)
            .map(|i| (i as f64 + 0.8 * unif(&mut rng)) * std::f64::consts::TAU / m as f64)
            .collect();
        ang.sort_by(f64::total_cmp);
        let rot = Rotation3::from_euler_angles(
            6.0 * unif(&mut rng),
            6.0 * unif(&mut rng),
            6.0 * unif(&mut rng),
        );
        // a rigid shift only where the heights stay far above the rounding of the positions
        // (|shift|·ε / (κ r²) ≪ 1e-10)
        let shift = if scale >= 1.0 {
            Vector3::new(unif(&mut rng), unif(&mut rng), unif(&mut rng)) * 5.0
        } else {
            Vector3::zeros()
        };
        let place = |x: f64, y: f64| {
            let z = 0.5 * (al * x * x + 2.0 * be * x * y + ga * y * y);
            Point3::from(rot * Vector3::new(x, y, z) + shift)
        };
        let mut pos = vec![place(0.0, 0.0)];
        for &t in &ang {
            let r = scale * (0.3 + unif(&mut rng));
            pos.push(place(r * t.cos(), r * t.sin()));
        }
        let tris: Vec<[u32; 3]> = (0..m)
            .map(|i| [0, 1 + i as u32, 1 + ((i + 1) % m) as u32])
            .collect();
        let mesh = TriMesh::new(pos, tris);
        let mut normals = vec![Vector3::z(); m + 1];
        normals[0] = rot * Vector3::z();
        let opts = SurfaceOptions {
            normals: NormalSource::Given(normals),
            ring: 1,
            ..Default::default()
        };
        let c = surface_curvature(&mesh, &opts).unwrap();
        assert_eq!(c.status[0], VertexStatus::Ok, "case {case}");
        let e = eig2(al, be, ga);
        assert!(
            (c.k1[0] - e[0]).abs() < 1e-10 && (c.k2[0] - e[1]).abs() < 1e-10,
            "case {case}: {:?} vs {e:?}",
            [c.k1[0], c.k2[0]]
        );
        // the direction of κ₁ is an eigenvector of the form, in the rotated frame
        let d = rot.inverse() * c.dir1[0];
        let a = Matrix3::new(al, be, 0.0, be, ga, 0.0, 0.0, 0.0, 0.0);
        if (e[1] - e[0]).abs() > 1e-3 {
            assert!((a * d - d * e[0]).norm() < 1e-8, "case {case}");
        }
        assert!((c.h[0] - (e[0] + e[1]) / 2.0).abs() < 1e-10);
        assert!((c.k[0] - e[0] * e[1]).abs() < 1e-10);
        assert!((c.a[0] - e[0].abs() - e[1].abs()).abs() < 1e-10);
    }
}

/// The same in R⁴: `f = ½xᵀAx` at the centre of a 3³ non-uniform grid with its exact gradient.
#[test]
fn trivariate_quadratic_forms_are_exact() {
    let mut rng = Rng::seed_from_u64(4);
    for case in 0..200 {
        let mut a = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in i..3 {
                a[i][j] = 4.0 * unif(&mut rng) - 2.0;
                a[j][i] = a[i][j];
            }
        }
        let coords: [Vec<f64>; 3] =
            std::array::from_fn(|_| vec![-0.2 - unif(&mut rng), 0.0, 0.2 + unif(&mut rng)]);
        let mut vals = Vec::new();
        let mut grads = Vec::new();
        for z in 0..3 {
            for y in 0..3 {
                for x in 0..3 {
                    let p = [coords[0][x], coords[1][y], coords[2][z]];
                    let ap: [f64; 3] =
                        std::array::from_fn(|i| (0..3).map(|j| a[i][j] * p[j]).sum());
                    vals.push(0.5 * (0..3).map(|i| p[i] * ap[i]).sum::<f64>());
                    grads.push(ap);
                }
            }
        }
        let c = trivariate_curvature([3; 3], &coords, &vals, &Gradients::Given(grads)).unwrap();
        let m = Matrix3::from_fn(|i, j| a[i][j]);
        let mut e: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
        e.sort_by(f64::total_cmp);
        let i = 13;
        assert!(c.determined[i]);
        let got = [c.k1[i], c.k2[i], c.k3[i]];
        for q in 0..3 {
            assert!(
                (got[q] - e[q]).abs() < 1e-10,
                "case {case}: {got:?} vs {e:?}"
            );
        }
    }
}

fn sphere_errors(subdiv: u32, r: f64) -> (f64, f64) {
    let mut m = generate::icosphere(subdiv);
    let normals: Vec<Vector3> = m.positions.iter().map(|p| p.coords.normalize()).collect();
    for p in &mut m.positions {
        *p = Point3::from(p.coords.normalize() * r);
    }
    let h =
        (m.positions[m.triangles[0][0] as usize] - m.positions[m.triangles[0][1] as usize]).norm();
    let c = surface_curvature(
        &m,
        &SurfaceOptions {
            normals: NormalSource::Given(normals),
            ring: 1,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(c.undetermined, 0);
    let err =
        c.k1.iter()
            .chain(&c.k2)
            .map(|k| (k + 1.0 / r).abs())
            .fold(0.0, f64::max);
    (h, err)
}

#[test]
fn spheres_converge_quadratically() {
    let r = 2.0;
    let e: Vec<(f64, f64)> = (2..=6).map(|s| sphere_errors(s, r)).collect();
    for w in e.windows(2) {
        let slope = (w[0].1 / w[1].1).ln() / (w[0].0 / w[1].0).ln();
        println!(
            "h {:.4} → {:.4}: max |κ+1/R| {:.3e} → {:.3e}, slope {slope:.2}",
            w[0].0, w[1].0, w[0].1, w[1].1
        );
        assert!((1.7..2.5).contains(&slope), "slope {slope}");
    }
    assert!(e[4].1 < 1e-3);
}

#[test]
fn planes_give_zero() {
    let t = table_4_1(11);
    assert_eq!(t[0].undetermined, 2);
    assert!(t[0].rms.iter().all(|x| *x < 1e-12), "{:?}", t[0].rms);
    // a tilted, translated plane with estimated normals, every weighting, two rings
    let mut m = generate::disk(6, 17);
    let rot = Rotation3::from_euler_angles(0.3, -1.1, 2.0);
    for p in &mut m.positions {
        *p = Point3::from(rot * p.coords * 1e-3 + Vector3::new(1.0, 2.0, -3.0));
    }
    for w in [
        NormalWeighting::Area,
        NormalWeighting::Uniform,
        NormalWeighting::InverseArea,
    ] {
        for ring in [1, 2] {
            let c = surface_curvature(
                &m,
                &SurfaceOptions {
                    normals: NormalSource::Estimated(w),
                    ring,
                    ..Default::default()
                },
            )
            .unwrap();
            for v in 0..m.positions.len() {
                if c.status[v] == VertexStatus::Ok {
                    assert!(c.a[v] < 1e-6, "{w:?} ring {ring} vertex {v}: {}", c.a[v]);
                }
            }
        }
    }
}

#[test]
fn h_flips_with_the_orientation() {
    let m = generate::torus(2.0, 1.0, 48, 24);
    let opts = SurfaceOptions::default();
    let c = surface_curvature(&m, &opts).unwrap();
    let mut f = m.clone();
    f.triangles.iter_mut().for_each(|t| t.swap(1, 2));
    let d = surface_curvature(&f, &opts).unwrap();
    assert_eq!(c.undetermined, 0);
    let mut negative = 0;
    for v in 0..m.positions.len() {
        assert!((c.h[v] + d.h[v]).abs() < 1e-9 * (1.0 + c.h[v].abs()));
        assert!((c.k[v] - d.k[v]).abs() < 1e-9);
        assert!((c.k1[v] + d.k2[v]).abs() < 1e-9);
        negative += usize::from(c.h[v] < 0.0);
    }
    // outward normals: the torus bends away from them almost everywhere (H < 0)
    assert!(negative > m.positions.len() * 3 / 4);
}

#[test]
fn larger_rings_and_thread_count_independence() {
    let m = generate::icosphere(3);
    let c1 = surface_curvature(&m, &SurfaceOptions::default()).unwrap();
    let opts3 = SurfaceOptions {
        ring: 3,
        ..Default::default()
    };
    let c3 = surface_curvature(&m, &opts3).unwrap();
    assert_eq!(c3.undetermined, 0);
    // a 3-ring spans ~0.8 of the unit sphere here: a coarse paraboloid, still close
    assert!(c3.h.iter().all(|h| (h + 1.0).abs() < 0.05));
    assert_ne!(c1.h, c3.h);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let s = one.install(|| surface_curvature(&m, &opts3).unwrap());
    assert_eq!(s, c3);
}

#[test]
fn bad_input_is_refused_or_flagged() {
    let mut m = generate::icosphere(1);
    m.positions.push(Point3::new(9.0, 9.0, 9.0)); // isolated
    let iso = m.positions.len() - 1;
    let c = surface_curvature(&m, &SurfaceOptions::default()).unwrap();
    assert_eq!(c.status[iso], VertexStatus::Isolated);
    assert!(c.h[iso].is_nan() && c.k1[iso].is_nan());
    assert_eq!(c.undetermined, 1);
    // zero-area triangle: three collinear vertices besides the sphere
    let mut z = generate::icosphere(1);
    let b = z.positions.len() as u32;
    z.positions.extend([
        Point3::new(5.0, 0.0, 0.0),
        Point3::new(6.0, 0.0, 0.0),
        Point3::new(7.0, 0.0, 0.0),
    ]);
    z.triangles.push([b, b + 1, b + 2]);
    let c = surface_curvature(&z, &SurfaceOptions::default()).unwrap();
    assert_eq!(c.undetermined, 3);
    assert!(c.status[b as usize..]
        .iter()
        .all(|s| *s == VertexStatus::NoNormal));
    // NaN coordinate
    let mut n = generate::icosphere(1);
    n.positions[3].x = f64::NAN;
    assert!(matches!(
        surface_curvature(&n, &SurfaceOptions::default()),
        Err(CurvatureError::Mesh(_))
    ));
    let zero = SurfaceOptions {
        ring: 0,
        ..Default::default()
    };
    assert_eq!(surface_curvature(&m, &zero), Err(CurvatureError::ZeroRing));
    let given = SurfaceOptions {
        normals: NormalSource::Given(vec![Vector3::z(); 3]),
        ring: 1,
        ..Default::default()
    };
    assert!(matches!(
        surface_curvature(&m, &given),
        Err(CurvatureError::NormalCount { given: 3, .. })
    ));
    // a volume with one sample along an axis
    let coords = [vec![0.0, 1.0], vec![0.0], vec![0.0, 1.0]];
    assert!(matches!(
        trivariate_curvature([2, 1, 2], &coords, &[0.0; 4], &Gradients::Differences),
        Err(CurvatureError::FlatAxis { axis: 1, .. })
    ));
    let coords = [vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0, 1.0]];
    let mut vals = [0.0; 8];
    vals[5] = f64::NAN;
    assert_eq!(
        trivariate_curvature([2, 2, 2], &coords, &vals, &Gradients::Differences),
        Err(CurvatureError::NonFiniteSample { index: 5 })
    );
}

/// The notes' float64 reimplementation (C.4), κ₁/κ₂/H/K over all but the 2 corners.
const REF_41: [[f64; 4]; 9] = [
    [0.0; 4],
    [0.000182, 0.000000, 0.000091, 0.000000],
    [0.000113, 0.000029, 0.000054, 0.000054],
    [0.001587, 0.000974, 0.000611, 0.000792],
    [0.001065, 0.001065, 0.000768, 0.000801],
    [0.002388, 0.002388, 0.000762, 0.003874],
    [0.002581, 0.002926, 0.000763, 0.001784],
    [0.001210, 0.002824, 0.001229, 0.001371],
    [0.000915, 0.000831, 0.000625, 0.001222],
];

#[test]
fn table_4_1_reproduced() {
    let t = table_4_1(51);
    for r in &t {
        println!(
            "{} {:?} thesis {:?} interior {:?}",
            r.row, r.rms, r.thesis, r.rms_interior
        );
        assert_eq!(r.undetermined, 2, "row {}", r.row);
        for q in 0..4 {
            let bound = if r.row == 7 && q == 0 { 1.2 } else { 1.0 };
            assert!(
                r.rms[q] <= bound * r.thesis[q] + 1e-12,
                "row {} col {q}",
                r.row
            );
            let rf = REF_41[r.row - 1][q];
            assert!(
                (r.rms[q] - rf).abs() <= 0.02 * rf + 1e-6,
                "row {} col {q}: {} vs notes {rf}",
                r.row,
                r.rms[q]
            );
            // the notes suggest interior ≤ 0.1 × table for rows 4–8, but their own reference
            // (row 4 κ₂: .000208 vs .1 × .001342) breaks that: interior ≤ 0.2 × table here
            if (4..=8).contains(&r.row) {
                assert!(
                    r.rms_interior[q] <= 0.2 * r.thesis[q],
                    "row {} col {q}",
                    r.row
                );
            }
        }
    }
    assert!(t[0].rms.iter().all(|x| *x < 1e-12));
}

/// The notes' reference (C.5): H, K over all but the 102 rank-deficient points.
const REF_42: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [0.001462, 0.001659],
    [0.001718, 0.001918],
    [0.001755, 0.001078],
    [0.003229, 0.002588],
    [0.002023, 0.004997],
];

#[test]
fn table_4_2_reproduced() {
    let t = table_4_2(26);
    for r in &t {
        println!(
            "{} {:?} thesis {:?} interior {:?} undetermined {}",
            r.row, r.rms, r.thesis, r.rms_interior, r.undetermined
        );
        assert_eq!(r.undetermined, 102, "row {}", r.row);
        for q in 0..2 {
            assert!(
                r.rms_interior[q] <= r.thesis[q] + 1e-12,
                "row {} col {q}",
                r.row
            );
            let rf = REF_42[r.row - 1][q];
            assert!(
                (r.rms[q] - rf).abs() <= 0.02 * rf + 1e-6,
                "row {} col {q}: {} vs notes {rf}",
                r.row,
                r.rms[q]
            );
        }
    }
    assert!(t[0].rms.iter().all(|x| *x < 1e-12));
}

/// A jittered (2k+1)² grid around the origin of the graph of `f` (value, ∂x, ∂y), vertex 0 at
/// the origin (issue 20: the extensions for estimated normals).
fn graph_patch(k: i32, h: f64, seed: u64, f: impl Fn(f64, f64) -> f64) -> TriMesh {
    let mut rng = Rng::seed_from_u64(seed);
    let n = 2 * k + 1;
    let mut idx = vec![0u32; (n * n) as usize];
    let mut pos = vec![Point3::new(0.0, 0.0, f(0.0, 0.0))];
    for j in -k..=k {
        for i in -k..=k {
            let id = ((j + k) * n + (i + k)) as usize;
            if i == 0 && j == 0 {
                idx[id] = 0;
                continue;
            }
            let (x, y) = (
                h * (i as f64 + 0.3 * (unif(&mut rng) - 0.5)),
                h * (j as f64 + 0.3 * (unif(&mut rng) - 0.5)),
            );
            idx[id] = pos.len() as u32;
            pos.push(Point3::new(x, y, f(x, y)));
        }
    }
    let at = |i: i32, j: i32| idx[(j * n + i) as usize];
    let mut tris = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            // alternate diagonals: not centrally symmetric
            if (i + j) % 2 == 0 {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            } else {
                tris.push([at(i, j), at(i + 1, j), at(i, j + 1)]);
                tris.push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    TriMesh::new(pos, tris)
}

/// `SurfaceFit::Quadric` with a wrong (vertical) normal on a tilted quadratic graph gives the
/// graph's exact curvatures at the vertex (H (4.15)), for any tilt and scale.
#[test]
fn quadric_fit_is_exact_with_a_tilted_normal() {
    use morpho::curvature::tables::graph_curvatures;
    use morpho::curvature::SurfaceFit;
    let mut rng = Rng::seed_from_u64(21);
    for case in 0..100 {
        let r: Vec<f64> = (0..5).map(|_| 4.0 * unif(&mut rng) - 2.0).collect();
        let (a, b, al, be, ga) = (r[0], r[1], r[2], r[3], r[4]);
        let h = 10f64.powi(rng.below(4) as i32 - 3);
        let m = graph_patch(1, h, case, |x, y| {
            a * x + b * y + 0.5 * (al * x * x + 2.0 * be * x * y + ga * y * y)
        });
        let opts = SurfaceOptions {
            normals: NormalSource::Given(vec![Vector3::z(); m.positions.len()]),
            ring: 1,
            fit: SurfaceFit::Quadric,
            ..Default::default()
        };
        let c = surface_curvature(&m, &opts).unwrap();
        let ex = graph_curvatures([0.0, a, b, al, be, ga]);
        let tol = 1e-8 * (1.0 + ex[0].abs().max(ex[1].abs()));
        assert_eq!(c.status[0], VertexStatus::Ok, "case {case}");
        assert!(
            (c.k1[0] - ex[0]).abs() < tol && (c.k2[0] - ex[1]).abs() < tol,
            "case {case}: {:?} vs {ex:?}",
            [c.k1[0], c.k2[0]]
        );
        // the fitted normal is the graph's
        let n = Vector3::new(-a, -b, 1.0).normalize();
        assert!((c.normals[0] - n).norm() < 1e-8, "case {case}");
    }
}

/// Jet normals (the cubic over the 2-ring) are the exact normals of any cubic graph sampled
/// irregularly, starting from the (wrong) vertical normal: the cubic is exact in that frame.
#[test]
fn jet_normals_are_exact_on_cubics() {
    let mut rng = Rng::seed_from_u64(22);
    for case in 0..50 {
        let c: Vec<f64> = (0..9).map(|_| 2.0 * unif(&mut rng) - 1.0).collect();
        let m = graph_patch(2, 0.1, 100 + case, |x, y| {
            c[0] * x
                + c[1] * y
                + c[2] * x * x
                + c[3] * x * y
                + c[4] * y * y
                + c[5] * x * x * x
                + c[6] * x * x * y
                + c[7] * x * y * y
                + c[8] * y * y * y
        });
        let opts = SurfaceOptions {
            normals: NormalSource::Given(vec![Vector3::z(); m.positions.len()]),
            jet_normals: true,
            ..Default::default()
        };
        let r = surface_curvature(&m, &opts).unwrap();
        let n = Vector3::new(-c[0], -c[1], 1.0).normalize();
        assert!(
            (r.normals[0] - n).norm() < 1e-9,
            "case {case}: {:?} vs {n:?}",
            r.normals[0]
        );
    }
}

/// The default for estimated normals: spheres converge quadratically (max error against the
/// edge length: slope ≥ 1.4 between any two levels, ≥ 1.8 from level 2 to 6), planes give 0, H flips with the orientation, the thread count does not
/// matter.
#[test]
fn estimated_normals_default_converges_flips_and_is_deterministic() {
    let opts = SurfaceOptions::estimated_normals();
    let mut e = Vec::new();
    for s in 2..=6 {
        let m = generate::icosphere(s);
        let h = (m.positions[m.triangles[0][0] as usize] - m.positions[m.triangles[0][1] as usize])
            .norm();
        let c = surface_curvature(&m, &opts).unwrap();
        assert_eq!(c.undetermined, 0);
        assert_eq!(c.jet_fallbacks, 0);
        let err =
            c.k1.iter()
                .chain(&c.k2)
                .map(|k| (k + 1.0).abs())
                .fold(0.0, f64::max);
        e.push((h, err));
    }
    let slope = |a: (f64, f64), b: (f64, f64)| (a.1 / b.1).ln() / (a.0 / b.0).ln();
    let s: Vec<f64> = e.windows(2).map(|w| slope(w[0], w[1])).collect();
    let all = slope(e[0], e[4]);
    println!("max |κ+1| {e:?}, slopes {s:?}, level 2 → 6: {all:.2}");
    assert!(s.iter().all(|&x| x > 1.4) && all > 1.8, "{s:?} {all}");
    // a tilted plane: zero
    let mut p = graph_patch(4, 0.2, 5, |x, y| 0.3 * x - 0.7 * y + 2.0);
    for q in &mut p.positions {
        *q = Point3::from(Rotation3::from_euler_angles(0.4, 0.2, -1.0) * q.coords);
    }
    let c = surface_curvature(&p, &opts).unwrap();
    for v in 0..p.positions.len() {
        if c.status[v] == VertexStatus::Ok {
            assert!(c.a[v] < 1e-9, "vertex {v}: {}", c.a[v]);
        }
    }
    // orientation
    let t = generate::torus(2.0, 1.0, 48, 24);
    let a = surface_curvature(&t, &opts).unwrap();
    let mut f = t.clone();
    f.triangles.iter_mut().for_each(|t| t.swap(1, 2));
    let b = surface_curvature(&f, &opts).unwrap();
    for v in 0..t.positions.len() {
        assert!((a.h[v] + b.h[v]).abs() < 1e-9 * (1.0 + a.h[v].abs()));
        assert!((a.k[v] - b.k[v]).abs() < 1e-9);
    }
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    assert_eq!(one.install(|| surface_curvature(&t, &opts).unwrap()), a);
}

/// Non-manifold vertices (two fans sharing their apex), isolated vertices and zero-area
/// triangles: no panic, the documented status per vertex, NaN exactly where undetermined.
#[test]
fn non_manifold_isolated_and_degenerate_inputs_are_documented() {
    let mut pos = vec![Point3::origin()];
    let mut tris = Vec::new();
    for (fan, tilt) in [(0, 1.0), (1, -1.0)] {
        let base = pos.len() as u32;
        for i in 0..8 {
            let t = i as f64 * std::f64::consts::TAU / 8.0;
            // the second fan lies in a tilted plane below the first
            pos.push(Point3::new(
                t.cos(),
                t.sin(),
                0.1 * tilt + 0.05 * fan as f64,
            ));
        }
        for i in 0..8u32 {
            tris.push([0, base + i, base + (i + 1) % 8]);
        }
    }
    pos.push(Point3::new(5.0, 5.0, 5.0)); // isolated
    let b = pos.len() as u32;
    pos.extend([
        Point3::new(7.0, 0.0, 0.0),
        Point3::new(8.0, 0.0, 0.0),
        Point3::new(9.0, 0.0, 0.0),
    ]);
    tris.push([b, b + 1, b + 2]); // zero area
    let m = TriMesh::new(pos, tris);
    for opts in [
        SurfaceOptions::default(),
        SurfaceOptions::estimated_normals(),
    ] {
        let c = surface_curvature(&m, &opts).unwrap();
        assert_eq!(c.status[b as usize - 1], VertexStatus::Isolated);
        for v in b as usize..b as usize + 3 {
            assert_eq!(c.status[v], VertexStatus::NoNormal);
        }
        for v in 0..m.positions.len() {
            assert_eq!(
                c.h[v].is_nan(),
                c.status[v] != VertexStatus::Ok,
                "vertex {v}: {:?} {}",
                c.status[v],
                c.h[v]
            );
        }
        assert_eq!(
            c.undetermined,
            c.status.iter().filter(|s| **s != VertexStatus::Ok).count()
        );
    }
}

/// Boundary vertices with estimated normals (the default) get the quadric with linear terms
/// over the 2-ring: every boundary vertex of a quadratic graph (h = 0.1) is determined and
/// within 0.06 of the exact κ, and on the monkey saddle of Table 4.1's grid the boundary RMS of
/// H is below 0.02 (the one-sided jet and paraboloid gave 1.1 there; libigl 0.026).
#[test]
fn boundary_vertices_get_the_quadric_with_estimated_normals() {
    use morpho::curvature::tables::{graph_curvatures, grid_mesh};
    let opts = SurfaceOptions::estimated_normals();
    let m = 21;
    let on_boundary = |v: usize| {
        let (i, j) = (v % m, v / m);
        i == 0 || j == 0 || i == m - 1 || j == m - 1
    };
    let quad = |x: f64, y: f64| {
        [
            0.3 * x * x - 0.5 * x * y + 0.2 * y * y + 0.4 * x - 0.1 * y,
            0.6 * x - 0.5 * y + 0.4,
            -0.5 * x + 0.4 * y - 0.1,
            0.6,
            -0.5,
            0.4,
        ]
    };
    let mut mesh = grid_mesh(m, quad);
    mesh.normals = None;
    let c = surface_curvature(&mesh, &opts).unwrap();
    let mut worst: f64 = 0.0;
    for v in (0..m * m).filter(|&v| on_boundary(v)) {
        let p = mesh.positions[v];
        let ex = graph_curvatures(quad(p.x, p.y));
        assert_eq!(c.status[v], VertexStatus::Ok, "vertex {v}");
        worst = worst.max((c.k1[v] - ex[0]).abs().max((c.k2[v] - ex[1]).abs()));
    }
    println!("quadratic graph, boundary: max |Δκ| {worst:.3e}");
    assert!(worst < 0.06, "{worst}");
    // the monkey saddle on the thesis's 51×51 grid
    let m = 51;
    let monkey = |x: f64, y: f64| {
        [
            0.2 * (x * x * x - 3.0 * x * y * y),
            0.6 * (x * x - y * y),
            -1.2 * x * y,
            1.2 * x,
            -1.2 * y,
            -1.2 * x,
        ]
    };
    let mut mesh = grid_mesh(m, monkey);
    mesh.normals = None;
    let c = surface_curvature(&mesh, &opts).unwrap();
    let (mut s, mut n) = (0.0, 0);
    for v in 0..m * m {
        let (i, j) = (v % m, v / m);
        if !(i == 0 || j == 0 || i == m - 1 || j == m - 1) {
            continue;
        }
        let p = mesh.positions[v];
        let ex = graph_curvatures(monkey(p.x, p.y));
        assert_eq!(c.status[v], VertexStatus::Ok, "vertex {v}");
        s += (c.h[v] - ex[2]).powi(2);
        n += 1;
    }
    let rms = (s / n as f64).sqrt();
    println!("monkey saddle boundary RMS of H: {rms:.3e}");
    assert!(rms < 0.02, "{rms}");
}

/// The curvature of the jet ([`SurfaceFit::Jet`]), the default for estimated normals, is
/// exact on any quartic graph `z = a x + b y + ½(αx² + 2βxy + γy²) + cubic + quartic` sampled
/// on an irregular 2-ring, in a frame whose normal is tilted against the surface's (the
/// gradient terms matter), rigidly rotated, at any scale: κ₁, κ₂ equal the graph's at the
/// vertex (computed here from E, F, G, L, M, N) to 1e-9, the principal direction of κ₁ has
/// normal curvature κ₁, the normal is the graph's; the opposite frame normal flips H and keeps
/// K, and so does flipping the mesh's orientation with estimated normals.
#[test]
fn jet_curvature_is_exact_on_cubic_graphs_with_a_tilted_frame() {
    use morpho::curvature::SurfaceFit;
    let mut rng = Rng::seed_from_u64(23);
    for case in 0..200 {
        let r: Vec<f64> = (0..14).map(|_| 4.0 * unif(&mut rng) - 2.0).collect();
        let (a, b, al, be, ga) = (r[0], r[1], r[2], r[3], r[4]);
        let cub = [r[5], r[6], r[7], r[8]].map(|x| 0.5 * x);
        // quartic terms in half of the cases (the jet has degree 4 where it is determined)
        let quart = [r[9], r[10], r[11], r[12], r[13]].map(|x| 0.25 * x * (case % 2) as f64);
        let h = 10f64.powi(rng.below(4) as i32 - 3);
        let f = |x: f64, y: f64| {
            let (x2, y2) = (x * x, y * y);
            a * x
                + b * y
                + 0.5 * (al * x2 + 2.0 * be * x * y + ga * y2)
                + cub[0] * x2 * x
                + cub[1] * x2 * y
                + cub[2] * x * y2
                + cub[3] * y2 * y
                + quart[0] * x2 * x2
                + quart[1] * x2 * x * y
                + quart[2] * x2 * y2
                + quart[3] * x * y2 * y
                + quart[4] * y2 * y2
        };
        let m = graph_patch(2, h, 300 + case, f);
        // the analytic curvature at the origin: shape operator I⁻¹ II of the graph
        let (e, ff, g) = (1.0 + a * a, a * b, 1.0 + b * b);
        let l = (1.0 + a * a + b * b).sqrt();
        let (ll, mm, nn) = (al / l, be / l, ga / l);
        let det = e * g - ff * ff;
        let hx = (e * nn - 2.0 * ff * mm + g * ll) / (2.0 * det);
        let kx = (ll * nn - mm * mm) / det;
        let d = (hx * hx - kx).max(0.0).sqrt();
        let ex = [hx - d, hx + d];
        let tol = 1e-9 * (1.0 + ex[0].abs().max(ex[1].abs()));
        let rot = Rotation3::from_euler_angles(
            6.0 * unif(&mut rng),
            6.0 * unif(&mut rng),
            6.0 * unif(&mut rng),
        );
        let mut mr = m.clone();
        for p in &mut mr.positions {
            *p = Point3::from(rot * p.coords);
        }
        // the frame's normal is the (rotated) z axis: tilted against the graph's normal
        let given = SurfaceOptions {
            normals: NormalSource::Given(vec![rot * Vector3::z(); m.positions.len()]),
            ring: 2,
            fit: SurfaceFit::Jet,
            ..Default::default()
        };
        let c = surface_curvature(&mr, &given).unwrap();
        assert_eq!(c.status[0], VertexStatus::Ok, "case {case}");
        assert!(
            (c.k1[0] - ex[0]).abs() < tol && (c.k2[0] - ex[1]).abs() < tol,
            "case {case} h {h}: {:?} vs {ex:?}",
            [c.k1[0], c.k2[0]]
        );
        let n = rot * Vector3::new(-a, -b, 1.0).normalize();
        assert!((c.normals[0] - n).norm() < 1e-9, "case {case}");
        // κ₁'s direction in the graph's parameters: its normal curvature II/I is κ₁
        let t = rot.inverse() * c.dir1[0];
        assert!(
            t.dot(&Vector3::new(-a, -b, 1.0)).abs() < 1e-9,
            "case {case}"
        );
        let (dx, dy) = (t.x, t.y);
        let kn = (ll * dx * dx + 2.0 * mm * dx * dy + nn * dy * dy)
            / (e * dx * dx + 2.0 * ff * dx * dy + g * dy * dy);
        assert!((kn - ex[0]).abs() < tol, "case {case}: {kn} vs {}", ex[0]);
        assert!((c.dir2[0].dot(&c.dir1[0])).abs() < 1e-9);
        // the opposite frame normal: the same graph seen from below, H flips, K stays
        let down = SurfaceOptions {
            normals: NormalSource::Given(vec![-(rot * Vector3::z()); m.positions.len()]),
            ..given.clone()
        };
        let c1 = surface_curvature(&mr, &down).unwrap();
        assert!((c1.h[0] + c.h[0]).abs() < tol && (c1.k[0] - c.k[0]).abs() < tol);
        // estimated normals (the default): flipping the orientation flips H and keeps K
        let mut fl = mr.clone();
        fl.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        let c = surface_curvature(&fl, &SurfaceOptions::estimated_normals()).unwrap();
        let c0 = surface_curvature(&mr, &SurfaceOptions::estimated_normals()).unwrap();
        assert!((c.h[0] + c0.h[0]).abs() < tol && (c.k[0] - c0.k[0]).abs() < tol);
    }
}

/// With estimated (area) normals, the default ([`SurfaceOptions::estimated_normals`]: the jet's
/// curvature) converges faster than O(h²) (slope > 2 from h = 0.04 to 0.01; O(h³)
/// asymptotically) at a vertex of an irregularly sampled quartic graph (the
/// area normal's frame is tilted by O(h) against the surface's, so the graph over it is no
/// longer a polynomial: the jet's Hessian carries its fifth-order part); the previous default
/// (jet normals, then the thesis's 1-ring paraboloid) converges only like O(h) there (the
/// asymmetric 1-ring turns the cubic terms into curvature).
#[test]
fn default_converges_beyond_h2_on_irregular_graphs() {
    let mut rng = Rng::seed_from_u64(24);
    for case in 0..20 {
        let r: Vec<f64> = (0..14).map(|_| 2.0 * unif(&mut rng) - 1.0).collect();
        let f = |x: f64, y: f64| {
            let (x2, y2) = (x * x, y * y);
            r[0] * x
                + r[1] * y
                + 0.5 * (r[2] * x2 + 2.0 * r[3] * x * y + r[4] * y2)
                + r[5] * x2 * x
                + r[6] * x2 * y
                + r[7] * x * y2
                + r[8] * y2 * y
                + r[9] * x2 * x2
                + r[10] * x2 * x * y
                + r[11] * x2 * y2
                + r[12] * x * y2 * y
                + r[13] * y2 * y2
        };
        let ex = graph_curvatures_xy(r[0], r[1], r[2], r[3], r[4]);
        let err = |opts: &SurfaceOptions, h: f64| {
            // the same jitter pattern at every scale
            let m = graph_patch(2, h, 500 + case, f);
            let c = surface_curvature(&m, opts).unwrap();
            assert_eq!(c.status[0], VertexStatus::Ok);
            (c.k1[0] - ex[0]).abs().max((c.k2[0] - ex[1]).abs())
        };
        let slope = |opts: &SurfaceOptions| {
            let (e0, e1) = (err(opts, 0.04), err(opts, 0.01));
            ((e0 / e1).ln() / 4f64.ln(), e0, e1)
        };
        let (s, e0, e1) = slope(&SurfaceOptions::estimated_normals());
        assert!(s > 2.0, "case {case}: slope {s} ({e0:.2e} → {e1:.2e})");
        assert!(e1 < 1e-4, "case {case}: {e1:.2e}");
        let (s, e0, e1) = slope(&SurfaceOptions::jet_normals_paraboloid());
        assert!(
            s < 1.5,
            "case {case}: previous default, slope {s} ({e0:.2e} → {e1:.2e})"
        );
    }
}

/// κ₁ ≤ κ₂ of a graph at a point from its derivatives (H (4.15), written out).
fn graph_curvatures_xy(fx: f64, fy: f64, fxx: f64, fxy: f64, fyy: f64) -> [f64; 2] {
    let w2 = 1.0 + fx * fx + fy * fy;
    let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
    let h = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy)
        / (2.0 * w2 * w2.sqrt());
    let r = (h * h - k).max(0.0).sqrt();
    [h - r, h + r]
}

/// A sphere band tessellated irregularly (a jittered latitude–longitude grid, random
/// diagonals) gives H = −1/R, K = 1/R² with an interior error that decays at least like O(h²)
/// with the jet fit (slopes > 1.6 between levels; the quartic jet gives about 3).
#[test]
fn jet_curvature_on_jittered_spheres_converges() {
    let opts = SurfaceOptions::estimated_normals();
    let mut e = Vec::new();
    for (k, n) in [(0, 24usize), (1, 48), (2, 96)] {
        let mut rng = Rng::seed_from_u64(40 + k);
        let r0 = 2.5;
        let (nu, nv) = (2 * n, n);
        let mut pos = Vec::new();
        // rows away from the poles only (an open band: |latitude| ≤ 60°), jittered
        for j in 0..=nv {
            for i in 0..nu {
                let jit = |r: &mut Rng| 0.3 * (unif(r) - 0.5);
                let th = std::f64::consts::FRAC_PI_3
                    * (2.0
                        * (j as f64
                            + if j == 0 || j == nv {
                                0.0
                            } else {
                                jit(&mut rng)
                            })
                        / nv as f64
                        - 1.0);
                let ph = std::f64::consts::TAU * (i as f64 + jit(&mut rng)) / nu as f64;
                pos.push(Point3::new(
                    r0 * th.cos() * ph.cos(),
                    r0 * th.cos() * ph.sin(),
                    r0 * th.sin(),
                ));
            }
        }
        let id = |i: usize, j: usize| (j * nu + i % nu) as u32;
        let mut tris = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                if rng.below(2) == 0 {
                    tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                    tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                } else {
                    tris.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                    tris.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
        }
        let m = TriMesh::new(pos, tris);
        let c = surface_curvature(&m, &opts).unwrap();
        assert_eq!(c.undetermined, 0);
        // interior: more than 3 rows from the band's edges
        let (mut s, mut cnt) = (0.0, 0);
        for j in 4..=nv - 4 {
            for i in 0..nu {
                let v = id(i, j) as usize;
                // outward normals: H = −1/R
                s += (c.h[v] + 1.0 / r0).powi(2) + (c.k[v] - 1.0 / (r0 * r0)).powi(2);
                cnt += 1;
            }
        }
        e.push((s / cnt as f64).sqrt());
    }
    let slopes: Vec<f64> = e.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("jittered sphere band, interior RMS of (H, K) errors {e:?}, slopes {slopes:?}");
    assert!(slopes.iter().all(|&s| s > 1.6), "{slopes:?}");
}

/// The torus (R 2, r 1) on its 40×120 parameter grid (`bench/curvature_peers.py`'s first
/// mesh: cells up to 3:1, every vertex's 2-ring a hexagonal stencil of 18 points) with
/// estimated normals: the default's median relative error of H and K stays below
/// `vtkCurvatures`' on the same mesh (4.36e-4 and 1.38e-3, measured by the script), and its
/// RMS below 2e-4. The jet's distance weights (`fit::jet_weight`) make this hold: the
/// unweighted quartic jet over the 2-ring has medians 1.62e-3 / 1.52e-3 and RMS 5.3e-4 /
/// 6.9e-4 here (its Hessian carries the far points' fifth- and sixth-order remainder).
#[test]
fn torus_grid_median_error_is_below_vtks() {
    let (big_r, r) = (2.0, 1.0);
    let m = generate::torus(big_r, r, 120, 40);
    let c = surface_curvature(&m, &SurfaceOptions::estimated_normals()).unwrap();
    assert_eq!(c.undetermined, 0);
    let n = m.positions.len();
    let (mut hx, mut kx) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for p in &m.positions {
        // the tube angle v: cos v = (ρ − R)/r with ρ the distance from the axis
        let cv = ((p.x * p.x + p.y * p.y).sqrt() - big_r) / r;
        let w = big_r + r * cv;
        // outward normals: H < 0 on the outer half (H = −1/R convention of the module doc)
        hx.push(-(big_r + 2.0 * r * cv) / (2.0 * r * w));
        kx.push(cv / (r * w));
    }
    let stats = |app: &[f64], ex: &[f64]| {
        let scale = 0.1 * (ex.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt();
        let mut rel: Vec<f64> = app
            .iter()
            .zip(ex)
            .map(|(a, e)| (a - e).abs() / e.abs().max(scale))
            .collect();
        rel.sort_by(f64::total_cmp);
        let rms = (app
            .iter()
            .zip(ex)
            .map(|(a, e)| (a - e) * (a - e))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        (rel[n / 2], rms)
    };
    let (med_h, rms_h) = stats(&c.h, &hx);
    let (med_k, rms_k) = stats(&c.k, &kx);
    assert!(
        med_h < 4.0e-4 && rms_h < 2e-4,
        "H: median {med_h:.3e}, RMS {rms_h:.3e}"
    );
    assert!(
        med_k < 1.0e-3 && rms_k < 2e-4,
        "K: median {med_k:.3e}, RMS {rms_k:.3e}"
    );
}

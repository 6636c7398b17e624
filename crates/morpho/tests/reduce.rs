//! Triangle reduction (Hamann 1991, ch. 5; notes D.5): invariants after every removal,
//! exactness on the plane, the removability predicates, curvature at the new point, the
//! tolerance stop, degenerate and bad input.

mod common;
use morpho::curvature::NormalSource;
use morpho::geom::intersect::degenerate_triangle;
use morpho::geom::predicates::raw::orient2d;
use morpho::geom::Point3;
use morpho::mesh::validity::self_intersections;
use morpho::mesh::{analyze_topology, generate, TriMesh};
use morpho::reduce::*;

fn opts(stop: Stop) -> ReduceOptions {
    ReduceOptions {
        stop,
        ..Default::default()
    }
}

fn p3(m: &TriMesh) -> Vec<[f64; 3]> {
    m.positions.iter().map(|p| p.coords.into()).collect()
}

/// Parts, loops, χ, manifold, oriented, no self-intersection, no degenerate triangle.
fn assert_valid(input: &TriMesh, out: &TriMesh, what: &str) {
    let (a, b) = (analyze_topology(input), analyze_topology(out));
    assert_eq!(a.euler_characteristic, b.euler_characteristic, "{what}: χ");
    assert_eq!(a.parts.len(), b.parts.len(), "{what}: parts");
    assert_eq!(
        a.boundary_loops.len(),
        b.boundary_loops.len(),
        "{what}: loops"
    );
    assert!(
        b.manifold && b.consistently_oriented,
        "{what}: manifold/oriented"
    );
    let pos = p3(out);
    for t in &out.triangles {
        let c = t.map(|v| pos[v as usize]);
        assert!(!degenerate_triangle(c[0], c[1], c[2]), "{what}: degenerate");
    }
}

fn no_self_intersection(m: &TriMesh, what: &str) {
    assert!(
        self_intersections(&p3(m), &m.triangles, 1).is_empty(),
        "{what}: self-intersection"
    );
}

#[test]
fn plane_stays_exactly_planar_and_covers_the_domain() {
    for keep in [50.0, 20.0, 10.0] {
        let (rms, n) = table51::rms(0, keep).unwrap();
        assert!(
            n <= (keep / 100.0 * 5000.0) as usize,
            "{keep}: {n} triangles"
        );
        assert!(rms <= 1e-12, "{keep}: rms {rms}");
    }
    let (_, f, g) = table51::functions()[0];
    let (mesh, nor) = table51::grid_mesh(f, g);
    let r = reduce(
        &mesh,
        &ReduceOptions {
            stop: Stop::Keep(10.0),
            domain: Domain::HeightField,
            normals: NormalSource::Given(nor),
            ..Default::default()
        },
    )
    .unwrap();
    let pos = p3(&r.mesh);
    let mut area = 0.0;
    for t in &r.mesh.triangles {
        let c = t.map(|v| [pos[v as usize][0], pos[v as usize][1]]);
        let a = orient2d(c[0], c[1], c[2]);
        assert!(a > 0.0, "flipped over xy");
        area += a / 2.0;
    }
    assert!((area - 4.0).abs() < 1e-12, "area {area}");
    for p in &pos {
        assert!((p[2] - 0.2 * (p[0] + p[1])).abs() < 1e-12);
    }
    assert_valid(&mesh, &r.mesh, "plane");
}

/// χ after every single removal: the run to n − 4k triangles is the run to n − 4(k−1) plus
/// one removal (deterministic order; a closed mesh loses exactly 4 per removal).
fn chi_after_each_removal(mesh: &TriMesh, steps: usize, what: &str) {
    let n = mesh.triangles.len();
    let chi = analyze_topology(mesh).euler_characteristic;
    for k in 1..=steps {
        let r = reduce(mesh, &opts(Stop::Triangles(n - 4 * k))).unwrap();
        if r.stop == StopReason::NoRemovable {
            break;
        }
        assert_eq!(r.mesh.triangles.len(), n - 4 * k, "{what}: step {k}");
        let t = analyze_topology(&r.mesh);
        assert_eq!(t.euler_characteristic, chi, "{what}: step {k}");
        assert!(t.manifold && t.consistently_oriented, "{what}: step {k}");
    }
}

#[test]
fn euler_characteristic_after_every_removal_torus_and_double_torus() {
    let torus = generate::torus(2.0, 0.6, 24, 12);
    chi_after_each_removal(&torus, 60, "torus");
    let dt = generate::multi_torus(2);
    chi_after_each_removal(&dt, 20, "double torus");
    for (m, what) in [(torus, "torus"), (dt, "double torus")] {
        let r = reduce(&m, &opts(Stop::Keep(10.0))).unwrap();
        assert_valid(&m, &r.mesh, what);
        no_self_intersection(&r.mesh, what);
    }
}

fn scan(name: &str) -> Option<TriMesh> {
    let p = common::data(&format!("meshes/{name}"))?;
    Some(morpho::io::read_mesh(&p).unwrap())
}

#[test]
fn closed_scans_keep_topology_and_stay_embedded() {
    for name in ["bunny_npm.obj", "spot.obj", "fandisk.obj"] {
        let Some(m) = scan(name) else {
            return;
        };
        if analyze_topology(&m).manifold {
            chi_after_each_removal(&m, 15, name);
        }
        for keep in [50.0, 10.0] {
            match reduce(&m, &opts(Stop::Keep(keep))) {
                Ok(r) => {
                    assert_valid(&m, &r.mesh, name);
                    no_self_intersection(&r.mesh, name);
                }
                Err(e) => panic!("{name}: {e}"),
            }
        }
    }
}

#[test]
fn open_meshes_keep_boundary_loops_and_frozen_boundaries() {
    let disk = generate::disk(8, 24);
    let r = reduce(&disk, &opts(Stop::Keep(20.0))).unwrap();
    assert_valid(&disk, &r.mesh, "disk");
    let ann = generate::annulus(0.5, 1.0, 6, 32);
    let r = reduce(&ann, &opts(Stop::Keep(30.0))).unwrap();
    assert_valid(&ann, &r.mesh, "annulus");
    // frozen: every boundary vertex of the input survives unmoved
    let mut o = opts(Stop::Keep(20.0));
    o.freeze_boundary = true;
    let r = reduce(&disk, &o).unwrap();
    assert_valid(&disk, &r.mesh, "frozen disk");
    let tin = analyze_topology(&disk);
    let tout = analyze_topology(&r.mesh);
    assert_eq!(tin.boundary_loops[0].len(), tout.boundary_loops[0].len());
    for &v in &tout.boundary_loops[0] {
        let src = r.source[v as usize] as usize;
        assert_eq!(r.mesh.positions[v as usize], disk.positions[src]);
    }
}

/// A closed fan: centre 0, ring 1..=n, counter-clockwise.
fn wheel(n: u32) -> Vec<[u32; 3]> {
    (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect()
}

#[test]
fn removability_predicates_on_hand_made_coronas() {
    // a strip of 5 triangles: T = the middle one splits its corona in two (discontinuous)
    let strip = vec![[0, 1, 2], [1, 3, 2], [2, 3, 4], [3, 5, 4], [4, 5, 6]];
    let c = classify_corona(&strip, 2);
    assert!(!c.continuous && !c.cyclic && !c.closed);
    // T at the end of the strip: continuous, acyclic, open
    let c = classify_corona(&strip, 0);
    assert!(c.continuous && !c.cyclic && !c.closed);
    // discontinuous: two triangles touching T at one vertex each, not each other
    let disc = vec![[0, 1, 2], [0, 3, 4], [1, 5, 6]];
    let c = classify_corona(&disc, 0);
    assert!(!c.continuous);
    // cyclic: the three triangles around a valence-3 vertex 3 inside T's platelet
    let cyc = vec![[0, 1, 2], [1, 3, 2], [1, 4, 3], [3, 4, 2]];
    let c = classify_corona(&cyc, 0);
    assert!(c.cyclic && !c.admits_removal());
    // closed: an interior triangle of a fine disc
    let disk = generate::disk(4, 12);
    let interior = (0..disk.triangles.len())
        .find(|&t| disk.triangles[t].iter().all(|&v| v < 13))
        .unwrap();
    let c = classify_corona(&disk.triangles, interior);
    assert!(c.continuous && c.closed);
    let _ = wheel(6);
    // half-plane test: star-shaped vs not
    let t = [
        Point3::new(-0.1, -0.1, 0.0),
        Point3::new(0.2, -0.1, 0.0),
        Point3::new(-0.1, 0.2, 0.0),
    ];
    let star: Vec<Point3> = (0..8)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 8.0;
            let r = if i % 2 == 0 { 1.0 } else { 0.5 };
            Point3::new(r * a.cos(), r * a.sin(), 0.1)
        })
        .collect();
    assert!(half_plane_test(t, &star, true));
    // a C shape: the centroid is outside the kernel
    let c_shape: Vec<Point3> = [
        [1.0, -1.0],
        [1.0, -0.5],
        [-0.5, -0.5],
        [-0.5, 0.5],
        [1.0, 0.5],
        [1.0, 1.0],
        [-1.0, 1.0],
        [-1.0, -1.0],
    ]
    .iter()
    .map(|&[x, y]| Point3::new(x + 0.5, y, 0.0))
    .collect();
    assert!(!half_plane_test(t, &c_shape, true));
    // open polygon: no closing segment
    assert!(half_plane_test(t, &star[..5], false));
}

#[test]
fn curvature_at_the_new_point_matches_an_off_origin_quadric() {
    // graph z = f(u, v) quadratic with non-zero slope at 0: exact H, K from C.1
    let c = [0.3, -0.4, 0.7, 0.5, -0.2, 0.0];
    let (fu, fv, fuu, fuv, fvv) = (c[2], c[4], 2.0 * c[0], c[1], 2.0 * c[3]);
    let l = (1.0f64 + fu * fu + fv * fv).sqrt();
    let k_ex = (fuu * fvv - fuv * fuv) / l.powi(4);
    let h_ex =
        ((1.0 + fv * fv) * fuu - 2.0 * fu * fv * fuv + (1.0 + fu * fu) * fvv) / (2.0 * l.powi(3));
    let (k1, k2) = graph_quadratic_curvature(c);
    assert!(
        ((k1 + k2) / 2.0 - h_ex).abs() < 1e-12,
        "H {} vs {h_ex}",
        (k1 + k2) / 2.0
    );
    assert!((k1 * k2 - k_ex).abs() < 1e-12, "K {} vs {k_ex}", k1 * k2);
    // ellipsoid x²/4 + y² + z²/9 = 1 at an off-axis point, against its graph form
    let q: Quadric = [0.25, 0.0, 0.0, 1.0, 0.0, 1.0 / 9.0, 0.0, 0.0, 0.0, -1.0];
    let (x, y) = (0.8, 0.3);
    let z = 3.0 * (1.0f64 - x * x / 4.0 - y * y).sqrt();
    // z = 3 sqrt(1 − x²/4 − y²): derivatives
    let s = 1.0 - x * x / 4.0 - y * y;
    let (gx, gy) = (-x / 4.0, -y);
    let fx = 3.0 * gx / s.sqrt();
    let fy = 3.0 * gy / s.sqrt();
    let fxx = 3.0 * (-0.25 / s.sqrt() - gx * gx / s.powf(1.5));
    let fyy = 3.0 * (-1.0 / s.sqrt() - gy * gy / s.powf(1.5));
    let fxy = 3.0 * (-gx * gy / s.powf(1.5));
    let l = (1.0 + fx * fx + fy * fy).sqrt();
    let k_ex = (fxx * fyy - fxy * fxy) / l.powi(4);
    let h_ex =
        ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy) / (2.0 * l.powi(3));
    let (k1, k2) = quadric_curvature(&q, [x, y, z]).unwrap();
    assert!((k1 * k2 - k_ex).abs() < 1e-12, "K {} vs {k_ex}", k1 * k2);
    assert!(
        ((k1 + k2).abs() / 2.0 - h_ex.abs()).abs() < 1e-12,
        "H {} vs {h_ex}",
        (k1 + k2) / 2.0
    );
    // (5.33): the line through (0,0,0) along z meets the ellipsoid at z = ±3
    let t = line_intersection(&q, [0.0, 0.0, 0.5], [0.0, 0.0, 1.0]).unwrap();
    assert!((t - 2.5).abs() < 1e-12);
}

#[test]
fn tolerance_mode_stays_within_and_one_more_removal_exceeds() {
    let (_, f, g) = table51::functions()[3];
    let (mesh, nor) = table51::grid_mesh(f, g);
    let eps = 0.001;
    let base = ReduceOptions {
        stop: Stop::Rms(eps),
        domain: Domain::HeightField,
        normals: NormalSource::Given(nor),
        check_intersections: false,
        ..Default::default()
    };
    let r = reduce(&mesh, &base).unwrap();
    assert_eq!(r.stop, StopReason::Tolerance);
    assert!(r.rms.unwrap() <= eps);
    // the same run one removal further
    let n = r.mesh.triangles.len();
    let mut prev = None;
    for target in (0..n).rev() {
        let o = ReduceOptions {
            stop: Stop::Triangles(target),
            ..base.clone()
        };
        let s = reduce(&mesh, &o).unwrap();
        if s.removals == r.removals + 1 {
            prev = s.rms;
            break;
        }
    }
    assert!(prev.unwrap() > eps, "{prev:?}");
    // max error on a surface
    let torus = generate::torus(2.0, 0.6, 24, 12);
    let r = reduce(&torus, &opts(Stop::MaxError(0.1))).unwrap();
    assert!(r.max_error.unwrap() <= 0.1);
    assert!(r.mesh.triangles.len() < torus.triangles.len());
}

#[test]
fn implicit_new_point_keeps_the_guarantees() {
    let m = generate::icosphere(3);
    let mut o = opts(Stop::Keep(25.0));
    o.point = NewPoint::Implicit;
    let r = reduce(&m, &o).unwrap();
    assert_valid(&m, &r.mesh, "implicit");
    for p in &r.mesh.positions {
        assert!((p.coords.norm() - 1.0).abs() < 0.05);
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let m = generate::icosphere(1);
    let n = m.triangles.len();
    for p in [0.0, -1.0, 100.5, f64::NAN] {
        assert!(matches!(
            reduce(&m, &opts(Stop::Keep(p))),
            Err(ReduceError::BadPercentage { .. })
        ));
    }
    assert!(matches!(
        reduce(&m, &opts(Stop::Triangles(n + 1))),
        Err(ReduceError::CountAboveInput { .. })
    ));
    assert!(matches!(
        reduce(&m, &opts(Stop::Rms(f64::NAN))),
        Err(ReduceError::BadTolerance { .. })
    ));
    let mut nan = m.clone();
    nan.positions[0].x = f64::NAN;
    assert!(matches!(
        reduce(&nan, &opts(Stop::Keep(50.0))),
        Err(ReduceError::Mesh(_))
    ));
    // three triangles on one edge
    let p = vec![
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(0.0, -1.0, 0.0),
        Point3::new(0.0, 0.0, 1.0),
    ];
    let fin = TriMesh::new(p.clone(), vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    assert!(matches!(
        reduce(&fin, &opts(Stop::Keep(50.0))),
        Err(ReduceError::NonManifoldEdge { .. })
    ));
    let flip = TriMesh::new(p.clone(), vec![[0, 1, 2], [0, 1, 3]]);
    assert!(matches!(
        reduce(&flip, &opts(Stop::Keep(50.0))),
        Err(ReduceError::InconsistentOrientation { .. })
    ));
    let deg = TriMesh::new(p.clone(), vec![[0, 1, 1]]);
    assert!(matches!(
        reduce(&deg, &opts(Stop::Keep(50.0))),
        Err(ReduceError::DegenerateTriangle { .. })
    ));
    // two fans touching at vertex 0
    let bow = TriMesh::new(
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(-1.0, 0.0, 0.0),
            Point3::new(0.0, -1.0, 0.0),
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    assert!(matches!(
        reduce(&bow, &opts(Stop::Keep(50.0))),
        Err(ReduceError::NonManifoldVertex { .. })
    ));
    assert!(matches!(
        reduce(&TriMesh::default(), &opts(Stop::Keep(50.0))),
        Err(ReduceError::Empty)
    ));
    // a tetrahedron: nothing is removable, no panic
    let r = reduce(&generate::tetrahedron(), &opts(Stop::Keep(10.0))).unwrap();
    assert_eq!(r.stop, StopReason::NoRemovable);
    assert_eq!(r.mesh.triangles.len(), 4);
}

/// Table 5.1 (H p. 122, notes D.4) reproduced: every cell within 1.25× of the thesis's value
/// (plane ≤ 1e-12), measured from scratch by (5.41) at the 2601 knots (independent of the
/// incremental tracker, which must agree), the square [-1, 1]² covered (area 4, no knot
/// outside, no projected fold) and the triangle count at most the target. Fails at 2×; the
/// narrow reading of Rem. 5.9 ([`NewTriangles::LastStep`]) gives 18–157× and fails too.
#[test]
fn table_5_1_within_1_25_of_the_thesis() {
    let mut worst: f64 = 0.0;
    for (k, (name, f, _)) in table51::functions().iter().enumerate() {
        for (c, keep) in [50.0, 20.0, 10.0].into_iter().enumerate() {
            let r = table51::reduce_function(k, keep).unwrap();
            assert!(r.mesh.triangles.len() <= (keep / 100.0 * 5000.0) as usize);
            let (rms, _, miss) = table51::knot_rms(&r.mesh, *f);
            assert_eq!(miss, 0, "{name} {keep}: knots outside the reduced domain");
            let tracked = r.rms.unwrap();
            assert!(
                (tracked - rms).abs() <= 1e-9 * rms + 1e-15,
                "{name} {keep}: tracked {tracked} vs measured {rms}"
            );
            let pos = p3(&r.mesh);
            let mut area = 0.0;
            for t in &r.mesh.triangles {
                let q = t.map(|v| [pos[v as usize][0], pos[v as usize][1]]);
                let a = orient2d(q[0], q[1], q[2]);
                assert!(a > 0.0, "{name} {keep}: projected fold");
                area += a / 2.0;
            }
            assert!((area - 4.0).abs() < 1e-12, "{name} {keep}: area {area}");
            let th = table51::THESIS[k][c];
            if th == 0.0 {
                assert!(rms <= 1e-12, "{name} {keep}: {rms}");
            } else {
                let ratio = rms / th;
                worst = worst.max(ratio);
                assert!(
                    ratio <= 1.25,
                    "{name} {keep}: {rms} = {ratio:.2}× the thesis's {th}"
                );
            }
        }
    }
    eprintln!("Table 5.1: worst ratio to the thesis {worst:.3}");
    // the narrow reading of Rem. 5.9 is what made the table 15–150× off
    let (_, f, g) = table51::functions()[3];
    let (mesh, nor) = table51::grid_mesh(f, g);
    let o = ReduceOptions {
        stop: Stop::Keep(50.0),
        domain: Domain::HeightField,
        normals: NormalSource::Given(nor),
        check_intersections: false,
        new_triangles: NewTriangles::LastStep,
        ..Default::default()
    };
    let r = reduce(&mesh, &o).unwrap();
    assert!(table51::knot_rms(&r.mesh, f).0 > 10.0 * table51::THESIS[3][0]);
}

/// The surface of the box [0, n]³ as a closed mesh with n × n squares per face (two
/// triangles each), outward oriented.
fn grid_box(n: u32) -> TriMesh {
    use std::collections::HashMap;
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    let mut id = |p: [u32; 3], pos: &mut Vec<Point3>| {
        *ids.entry(p).or_insert_with(|| {
            pos.push(Point3::new(p[0] as f64, p[1] as f64, p[2] as f64));
            (pos.len() - 1) as u32
        })
    };
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        for s in [0, n] {
            for i in 0..n {
                for j in 0..n {
                    let mut q = |di: u32, dj: u32| {
                        let mut p = [0; 3];
                        p[a] = s;
                        p[u] = i + di;
                        p[v] = j + dj;
                        id(p, &mut pos)
                    };
                    let (p00, p10, p11, p01) = (q(0, 0), q(1, 0), q(1, 1), q(0, 1));
                    if s == n {
                        tris.push([p00, p10, p11]);
                        tris.push([p00, p11, p01]);
                    } else {
                        tris.push([p00, p11, p10]);
                        tris.push([p00, p01, p11]);
                    }
                }
            }
        }
    }
    TriMesh::new(pos, tris)
}

#[test]
fn error_levels_keep_a_box_exact_where_the_weight_order_rounds_it() {
    let b = grid_box(8);
    assert_eq!(analyze_topology(&b).euler_characteristic, 2);
    let run = |order: Order| {
        let o = ReduceOptions {
            stop: Stop::Keep(30.0),
            order,
            ..Default::default()
        };
        let r = reduce(&b, &o).unwrap();
        assert_valid(&b, &r.mesh, "box");
        no_self_intersection(&r.mesh, "box");
        mesh_distance(&b, &r.mesh)
    };
    let levels = run(Order::ErrorLevels);
    let hamann = run(Order::Hamann);
    // flat removals first, creases and corners kept: every input vertex stays on the output
    assert!(levels.hausdorff < 1e-9, "levels: {levels:?}");
    // the thesis's order alone takes flat triangles beside the creases and rounds them
    assert!(hamann.hausdorff > 1e-3, "hamann: {hamann:?}");
}

#[test]
fn error_levels_beat_the_weight_order_on_curved_scans_and_keep_the_guarantees() {
    for name in ["bunny_npm.obj", "spot.obj"] {
        let Some(m) = scan(name) else {
            return;
        };
        let mut rms = Vec::new();
        for order in [Order::ErrorLevels, Order::Hamann] {
            let o = ReduceOptions {
                stop: Stop::Keep(20.0),
                order,
                ..Default::default()
            };
            let r = reduce(&m, &o).unwrap();
            assert_valid(&m, &r.mesh, name);
            no_self_intersection(&r.mesh, name);
            assert!(r.mesh.triangles.len() <= m.triangles.len() / 5, "{name}");
            rms.push(mesh_distance(&m, &r.mesh).rms);
        }
        assert!(
            rms[0] < 0.8 * rms[1],
            "{name}: levels {} vs hamann {}",
            rms[0],
            rms[1]
        );
    }
}

#[test]
fn error_levels_with_a_tolerance_stop_within_it() {
    let m = generate::torus(2.0, 0.7, 48, 24);
    let tol = 0.05;
    let o = ReduceOptions {
        stop: Stop::MaxError(tol),
        order: Order::ErrorLevels,
        ..Default::default()
    };
    let r = reduce(&m, &o).unwrap();
    assert_eq!(r.stop, StopReason::Tolerance);
    assert!(r.max_error.unwrap() <= tol);
    assert!(mesh_distance(&m, &r.mesh).max_input_to_output <= tol * (1.0 + 1e-9));
    assert!(
        r.mesh.triangles.len() < m.triangles.len() / 2,
        "{}",
        r.mesh.triangles.len()
    );
    assert_valid(&m, &r.mesh, "torus");
}

#[test]
fn table_5_1_error_levels_beat_the_thesis() {
    // the cylinder, the hyperboloid and the cubic at 80 % removed (thesis: 0.000999,
    // 0.000794, 0.001029; the weight order alone gives 1.10×, 1.03×, 0.92× of those)
    for k in [1usize, 4, 6] {
        let (name, f, _) = table51::functions()[k];
        let r = table51::reduce_function_ordered(
            k,
            20.0,
            NewTriangles::Generations,
            Order::ErrorLevels,
        )
        .unwrap();
        let (rms, _, miss) = table51::knot_rms(&r.mesh, f);
        assert_eq!(miss, 0, "{name}: knots outside the reduced domain");
        let ratio = rms / table51::THESIS[k][1];
        assert!(ratio < 0.85, "{name}: {rms} = {ratio:.2}× the thesis");
    }
}

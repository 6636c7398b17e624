//! Tests of `morpho::smooth` (issue 19): the 2D G¹ curve on real curves and polygons and the
//! weighting failure set on random polygons (NOTES B.2); the three-split on generated and real
//! closed meshes: interpolation, independent continuity, the singular case (NOTES B.5, B.9).

mod common;
use morpho::geom::{Point2, Point3, Vector3};
use morpho::mesh::{generate, vertex_normals, NormalWeighting, TriMesh};
use morpho::smooth::*;
use std::path::Path;

/// A seeded xorshift64* (the library's `util::Rng` is crate-private).
struct Rng(u64);
impl Rng {
    fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

fn uni(r: &mut Rng) -> f64 {
    (r.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// A uniform random point of the reference triangle, as barycentric coordinates `[u, v, w]`
/// (a point of the unit square folded across its diagonal).
fn barycentric(r: &mut Rng) -> [f64; 3] {
    let (u, v) = (uni(r), uni(r));
    let (u, v) = if u + v > 1.0 {
        (1.0 - u, 1.0 - v)
    } else {
        (u, v)
    };
    [u, v, 1.0 - u - v]
}

/// Rings of a CSV: `component,closed,order,x,y` (curves2d) or two columns (polygons).
fn rings(path: &Path) -> Vec<(Vec<Point2>, bool)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let mut out: Vec<(Vec<Point2>, bool)> = Vec::new();
    let mut comp = usize::MAX;
    for l in lines {
        let f: Vec<f64> = l.split(',').map(|s| s.trim().parse().unwrap()).collect();
        if header.starts_with("component") {
            if f[0] as usize != comp {
                comp = f[0] as usize;
                out.push((Vec::new(), f[1] == 1.0));
            }
            out.last_mut().unwrap().0.push(Point2::new(f[3], f[4]));
        } else {
            if out.is_empty() {
                out.push((Vec::new(), true));
            }
            out[0].0.push(Point2::new(f[0], f[1]));
        }
    }
    // the documented repair: consecutive duplicates (and a repeated closing vertex) dropped
    for (r, closed) in &mut out {
        r.dedup();
        if *closed && r.len() > 1 && r[0] == r[r.len() - 1] {
            r.pop();
        }
    }
    out
}

fn check_curve(c: &G1Curve, pts: &[Point2]) {
    for (k, s) in c.segments.iter().enumerate() {
        assert_eq!(s[0], [pts[k].x, pts[k].y]);
    }
    for (k, j) in curve_joints(c).iter().enumerate() {
        // the bound, relative to the rounding of the stored points (Joint::rounding)
        assert!(j.is_g1(1e-12), "joint {k}: {j:?}");
    }
}

#[test]
fn g1_at_every_joint_of_every_real_curve_and_polygon() {
    let Some(data) = common::data_dir() else {
        return;
    };
    let mut files = Vec::new();
    for dir in ["curves2d/svg_groundtruth", "polygons"] {
        for e in std::fs::read_dir(data.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "csv") {
                files.push(p);
            }
        }
    }
    files.sort();
    assert!(files.len() >= 10);
    let mut joints = 0;
    let mut refused = 0;
    for f in &files {
        for (r, closed) in rings(f) {
            if r.len() < 3 {
                continue;
            }
            for w in [
                CurveWeighting::Length,
                CurveWeighting::Uniform,
                CurveWeighting::InverseLength,
            ] {
                let c = match g1_curve(&r, closed, w) {
                    Ok(c) => c,
                    // the documented refusal: only where the polygon really doubles back
                    Err(SmoothError::DoublesBack { index }) => {
                        let n = r.len();
                        let a = r[(index + n - 1) % n] - r[index];
                        let b = r[(index + 1) % n] - r[index];
                        let cross = a.x * b.y - a.y * b.x;
                        assert!(
                            cross.abs() <= 1e-12 * a.norm() * b.norm() && a.dot(&b) > 0.0,
                            "{}: vertex {index}",
                            f.display()
                        );
                        refused += 1;
                        continue;
                    }
                    Err(e) => panic!("{}: {e}", f.display()),
                };
                if w == CurveWeighting::Uniform {
                    // never a cusp; only handles too short for their coordinates (curve.rs)
                    assert!(c.failures.iter().all(|f| f.kind == FailureKind::ZeroHandle));
                }
                check_curve(&c, &r);
                joints += c.segments.len();
            }
        }
    }
    eprintln!("{joints} joints G1, {refused} curves refused (doubling back)");
    assert!(joints > 10_000, "{joints}");
    assert!(refused <= 6, "{refused}");
}

#[test]
fn failure_set_of_weightings_1_and_3_is_the_derived_one() {
    let mut rng = Rng::new(19);
    let mut seen = 0;
    for _ in 0..300 {
        let n = 3 + rng.below(20) as usize;
        let pts: Vec<Point2> = (0..n)
            .map(|_| Point2::new(uni(&mut rng) * 10.0, uni(&mut rng) * 10.0))
            .collect();
        let mut expect = Vec::new();
        let mut near_tie = false;
        for i in 0..n {
            let v = |k: usize| pts[k % n];
            let a = v(i + n - 1) - v(i);
            let b = v(i + 1) - v(i);
            let x = a.dot(&b);
            let m = a.norm_squared().min(b.norm_squared());
            near_tie |= (x - m).abs() <= 1e-4 * m;
            if x >= m {
                expect.push(i);
            }
        }
        if near_tie {
            continue;
        }
        for w in [CurveWeighting::Length, CurveWeighting::InverseLength] {
            let Ok(c) = g1_curve(&pts, true, w) else {
                continue;
            };
            let got: Vec<usize> = c.failures.iter().map(|f| f.vertex).collect();
            assert_eq!(got, expect, "{w:?} {pts:?}");
            seen += got.len();
            check_curve(&c, &pts);
        }
    }
    assert!(seen > 50, "{seen}");
}

#[test]
fn bad_polygons_are_refused() {
    let p = |v: &[(f64, f64)]| {
        v.iter()
            .map(|&(x, y)| Point2::new(x, y))
            .collect::<Vec<_>>()
    };
    let w = CurveWeighting::Length;
    assert!(matches!(
        g1_curve(
            &p(&[(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 1.0)]),
            true,
            w
        ),
        Err(SmoothError::RepeatedVertex { index: 2 })
    ));
    assert!(matches!(
        g1_curve(&p(&[(0.0, 0.0), (f64::NAN, 0.0), (0.0, 1.0)]), true, w),
        Err(SmoothError::NonFinite { index: 1 })
    ));
    assert!(matches!(
        g1_curve(&p(&[(0.0, 0.0), (1.0, 0.0)]), true, w),
        Err(SmoothError::TooFew { .. })
    ));
    // an open polyline of two points is one straight cubic
    let c = g1_curve(&p(&[(0.0, 0.0), (3.0, 0.0)]), false, w).unwrap();
    assert_eq!(
        c.segments,
        vec![[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]]
    );
}

/// Interpolation of positions and normals, continuity, no folds; returns the figures.
fn check_surface(m: &TriMesh, n: &[Vector3], expect_singular: bool) -> Continuity {
    let s = three_split(m, n).unwrap();
    if expect_singular {
        assert!(!s.singular_edges.is_empty());
    }
    assert!(s.unresolved_edges.is_empty(), "{:?}", s.unresolved_edges);
    for (k, p) in s.patches.iter().enumerate() {
        let t = m.triangles[k / 3];
        let (a, b) = (t[k % 3] as usize, t[(k + 1) % 3] as usize);
        let tri = p.triangle();
        for (v, bary) in [(a, [1.0, 0.0, 0.0]), (b, [0.0, 1.0, 0.0])] {
            let x: [f64; 3] = m.positions[v].into();
            let e = tri.eval(bary);
            let d = ((e[0] - x[0]).powi(2) + (e[1] - x[1]).powi(2) + (e[2] - x[2]).powi(2)).sqrt();
            assert!(d <= 1e-12 * (1.0 + m.bbox().diagonal()), "vertex {v}: {d}");
            let nn = tri.normal(bary);
            let ang = (Vector3::from(nn).cross(&n[v]).norm()).atan2(Vector3::from(nn).dot(&n[v]));
            assert!(ang <= 1e-12 * 100.0, "normal at vertex {v}: {ang}");
        }
    }
    let c = continuity(&s, 20);
    assert_eq!(c.open_edges, 0);
    assert_eq!(c.folds, 0);
    assert!(
        c.max_position_gap <= 1e-12 * (1.0 + m.bbox().diagonal()),
        "{c:?}"
    );
    assert!(
        c.max_normal_jump_rad <= 1e-9,
        "{:?}",
        (
            c.max_macro_jump_rad,
            c.max_micro_jump_rad,
            c.non_g1_edges.len()
        )
    );
    c
}

fn perturbed_icosahedron(seed: u64) -> TriMesh {
    let mut m = generate::icosphere(0);
    let mut rng = Rng::new(seed);
    for p in &mut m.positions {
        *p = Point3::from(p.coords * (0.7 + 0.6 * uni(&mut rng)));
    }
    m
}

#[test]
fn three_split_generic_mesh_is_g1_with_every_weighting() {
    for seed in 1..6 {
        let m = perturbed_icosahedron(seed);
        for w in [
            NormalWeighting::Area,
            NormalWeighting::Uniform,
            NormalWeighting::InverseArea,
        ] {
            let n = vertex_normals(&m, w);
            check_surface(&m, &n, false);
        }
    }
}

/// The regular octahedron with vertices ±e_k, outward (every edge mirror-symmetric).
fn octahedron() -> TriMesh {
    TriMesh::new(
        vec![
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(-1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, -1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
            Point3::new(0.0, 0.0, -1.0),
        ],
        vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    )
}

#[test]
fn three_split_reports_singular_edges_and_the_fallback_is_g1() {
    // octahedron and icosahedron with exact (sphere) normals: every edge mirror-symmetric
    let oct = octahedron();
    for m in [oct, generate::icosphere(0)] {
        let n: Vec<Vector3> = m.positions.iter().map(|p| p.coords.normalize()).collect();
        let s = three_split(&m, &n).unwrap();
        assert_eq!(s.singular_edges.len(), m.triangles.len() * 3 / 2);
        let c = check_surface(&m, &n, true);
        eprintln!(
            "{} tris: macro {:.1e} micro {:.1e} rad, max displacement {:.3}",
            m.triangles.len(),
            c.max_macro_jump_rad,
            c.max_micro_jump_rad,
            s.max_displacement
        );
    }
}

#[test]
fn three_split_on_real_closed_meshes() {
    let Some(data) = common::data_dir() else {
        return;
    };
    for name in ["spot.obj", "rocker-arm.obj", "fandisk.obj"] {
        let p = data.join("meshes").join(name);
        let m = morpho::io::read_mesh(&p).unwrap();
        let top = morpho::mesh::analyze_topology(&m);
        if !top.is_closed() {
            continue;
        }
        let n = vertex_normals(&m, NormalWeighting::Area);
        let s = three_split(&m, &n).unwrap();
        let c = continuity(&s, 20);
        eprintln!(
            "{name}: {} tris, singular {} unresolved {} signw {}, macro {:.2e} micro {:.2e} rad, folds {}, max displacement {:.3}",
            m.triangles.len(), s.singular_edges.len(), s.unresolved_edges.len(), s.sign_warnings.len(), c.max_macro_jump_rad, c.max_micro_jump_rad, c.folds, s.max_displacement
        );
        assert!(c.max_normal_jump_rad <= 1e-9 || !c.non_g1_edges.is_empty());
    }
}

#[test]
fn bad_meshes_are_refused() {
    let m = generate::tetrahedron();
    let n = vertex_normals(&m, NormalWeighting::Area);
    let mut open = m.clone();
    open.triangles.pop();
    assert!(matches!(
        three_split(&open, &n),
        Err(SmoothError::TooFew { .. } | SmoothError::NotClosed { .. })
    ));
    let mut flipped = m.clone();
    flipped.triangles[0].swap(0, 1);
    assert!(matches!(
        three_split(&flipped, &n),
        Err(SmoothError::NonManifold { .. } | SmoothError::NotClosed { .. })
    ));
    let mut nan = m.clone();
    nan.positions[0].x = f64::NAN;
    assert!(matches!(
        three_split(&nan, &n),
        Err(SmoothError::NonFinite { index: 0 })
    ));
    let mut zero = m.clone();
    zero.positions[1] = zero.positions[0];
    assert!(matches!(
        three_split(&zero, &n),
        Err(SmoothError::ZeroArea { .. })
    ));
    let mut badn = n.clone();
    badn[2] = Vector3::zeros();
    assert!(matches!(
        three_split(&m, &badn),
        Err(SmoothError::BadNormal { vertex: 2 })
    ));
}

#[test]
fn tessellation_interpolates_and_carries_surface_normals() {
    let m = perturbed_icosahedron(3);
    let n = vertex_normals(&m, NormalWeighting::Area);
    let s = three_split(&m, &n).unwrap();
    let t = tessellate(&s, 6).unwrap();
    let top = morpho::mesh::analyze_topology(&t);
    assert!(top.is_closed());
    assert_eq!(t.triangles.len(), s.patches.len() * 36);
    for (v, p) in m.positions.iter().enumerate() {
        let k = t
            .positions
            .iter()
            .position(|q| (q - p).norm() < 1e-12)
            .expect("vertex kept");
        assert!((t.normals.as_ref().unwrap()[k] - n[v]).norm() < 1e-9);
    }
    assert!(tessellate(&s, 0).is_err());
}

/// A closed flat box over an n×n grid: top z = 0 (interior vertices jittered in x, y by
/// `jitter`), bottom z = −1, side walls. Returns the mesh and the top interior vertex flags.
fn flat_box(n: usize, jitter: f64, seed: u64) -> (TriMesh, Vec<bool>) {
    let mut rng = Rng::new(seed);
    let mut pos = Vec::new();
    let mut inner = Vec::new();
    let id =
        |layer: usize, i: usize, j: usize| (layer * (n + 1) * (n + 1) + i * (n + 1) + j) as u32;
    for layer in 0..2 {
        for i in 0..=n {
            for j in 0..=n {
                let interior = i > 0 && j > 0 && i < n && j < n;
                let (mut x, mut y) = (i as f64, j as f64);
                if interior && layer == 0 {
                    x += jitter * (uni(&mut rng) - 0.5);
                    y += jitter * (uni(&mut rng) - 0.5);
                }
                pos.push(Point3::new(x, y, -(layer as f64)));
                inner.push(layer == 0 && interior);
            }
        }
    }
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (
                id(0, i, j),
                id(0, i + 1, j),
                id(0, i + 1, j + 1),
                id(0, i, j + 1),
            );
            tris.push([a, b, c]);
            tris.push([a, c, d]);
            let (a, b, c, d) = (
                id(1, i, j),
                id(1, i + 1, j),
                id(1, i + 1, j + 1),
                id(1, i, j + 1),
            );
            tris.push([a, c, b]);
            tris.push([a, d, c]);
        }
    }
    // the boundary ring, counter-clockwise seen from above
    let mut ring = Vec::new();
    ring.extend((0..n).map(|i| (i, 0)));
    ring.extend((0..n).map(|j| (n, j)));
    ring.extend((0..n).map(|i| (n - i, n)));
    ring.extend((0..n).map(|j| (0, n - j)));
    for k in 0..ring.len() {
        let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
        let (t0, t1) = (id(0, p.0, p.1), id(0, q.0, q.1));
        let (b0, b1) = (id(1, p.0, p.1), id(1, q.0, q.1));
        tris.push([t0, b0, b1]);
        tris.push([t0, b1, t1]);
    }
    (TriMesh::new(pos, tris), inner)
}

#[test]
fn linear_precision_a_flat_region_gives_the_plane() {
    for (jitter, seed) in [(0.0, 1), (0.4, 2), (0.4, 3)] {
        let (m, inner) = flat_box(6, jitter, seed);
        assert!(morpho::mesh::analyze_topology(&m).is_closed());
        let n = vertex_normals(&m, NormalWeighting::Area);
        let s = three_split(&m, &n).unwrap();
        if jitter == 0.0 {
            // the regular grid's diagonals are mirror-symmetric: reported
            assert!(!s.singular_edges.is_empty());
        }
        // the box's sharp rims may be unresolved; nothing in the flat region is
        for &[a, b] in &s.unresolved_edges {
            assert!(!inner[a as usize] || !inner[b as usize], "{a}-{b}");
        }
        let mut checked = 0;
        let mut rng = Rng::new(seed);
        // vertices of macro triangles the edge split bisected (more than 3 patches): next to
        // them the parametrisation follows the bisected domain (edgesplit.rs), so only the
        // plane itself is checked there
        let mut per = vec![0usize; m.triangles.len()];
        for p in &s.patches {
            per[p.macro_tri as usize] += 1;
        }
        let mut near_split = vec![false; m.positions.len()];
        for (t, &k) in m.triangles.iter().zip(&per) {
            if k > 3 {
                t.iter().for_each(|&v| near_split[v as usize] = true);
            }
        }
        for (k, p) in s.patches.iter().enumerate() {
            let t = m.triangles[p.macro_tri as usize];
            if !t.iter().all(|&v| inner[v as usize]) {
                continue;
            }
            if t.iter().any(|&v| near_split[v as usize]) {
                checked += 1;
                let tri = p.triangle();
                for _ in 0..20 {
                    let e = tri.eval(barycentric(&mut rng));
                    assert!(e[2].abs() <= 1e-12, "patch {k}: off the plane by {}", e[2]);
                }
                continue;
            }
            checked += 1;
            let c: Vec<Point3> = t.iter().map(|&v| m.positions[v as usize]).collect();
            // the patch's corners in its macro triangle (the domain where the edge split
            // bisected the triangle, else the fixed layout)
            let at = |d: [f64; 3]| {
                Point3::from(c[0].coords * d[0] + c[1].coords * d[1] + c[2].coords * d[2])
            };
            let (a, b, z) = match s.domain.get(k) {
                Some(d) => (at(d[0]), at(d[1]), at(d[2])),
                None => (
                    c[k % 3],
                    c[(k + 1) % 3],
                    Point3::from((c[0].coords + c[1].coords + c[2].coords) / 3.0),
                ),
            };
            let tri = p.triangle();
            for _ in 0..20 {
                let [u, v, w] = barycentric(&mut rng);
                let e = tri.eval([u, v, w]);
                // the affine map of the micro triangle: the plane, linearly parametrised
                let x = a.coords * u + b.coords * v + z.coords * w;
                let d = (Vector3::from(e) - x).norm();
                assert!(d <= 1e-12, "jitter {jitter}, patch {k}: {d} z {}", e[2]);
            }
        }
        assert!(checked >= 3 * 16, "{checked}");
    }
}

/// min over the incident faces of `n·n_f` at vertex `v` (computed here, not by the library).
fn min_face_dot(m: &TriMesh, n: &Vector3, v: u32) -> f64 {
    m.triangles
        .iter()
        .filter(|t| t.contains(&v))
        .map(|t| {
            let p = |k: usize| m.positions[t[k] as usize];
            (p(1) - p(0)).cross(&(p(2) - p(0))).normalize().dot(n)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn fold_remedies_on_real_meshes() {
    let Some(data) = common::data_dir() else {
        return;
    };
    // figures before the remedies (fan guard on singular edges, visible normals):
    // spot 277 fold samples, rocker-arm 436, fandisk 46298
    // rocker-arm: 1 fold edge before the transversal Step 5 (split3 module doc), 4 since (a
    // regression in folds, traded for bounded control points; open)
    for (name, max_fold_edges) in [("spot.obj", 0), ("rocker-arm.obj", 4), ("fandisk.obj", 116)] {
        let p = data.join("meshes").join(name);
        let m = morpho::io::read_mesh(&p).unwrap();
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let a = visible_normals(&m, &n0, 0.05);
        for (v, n) in a.normals.iter().enumerate() {
            let d = min_face_dot(&m, n, v as u32);
            if a.adjusted.contains(&(v as u32)) {
                // an adjusted normal sees every incident triangle, and better than before
                assert!(
                    d > 0.0 && d > min_face_dot(&m, &n0[v], v as u32),
                    "{name} {v}"
                );
                assert!((n.norm() - 1.0).abs() < 1e-12);
            } else {
                assert_eq!(*n, n0[v]);
            }
        }
        assert!(a.infeasible.is_empty());
        let guard = SplitOptions { fold_guard: true };
        let s = three_split_with(&m, &a.normals, &guard).unwrap();
        let c = continuity(&s, 20);
        eprintln!(
            "{name}: adjusted {}; singular {} unresolved {} guarded {} signw {}; non-g1 {} fold edges {} folds {} macro {:.2e}",
            a.adjusted.len(), s.singular_edges.len(), s.unresolved_edges.len(), s.fold_guarded.len(), s.sign_warnings.len(), c.non_g1_edges.len(), c.fold_edges, c.folds, c.max_macro_jump_rad
        );
        assert!(c.fold_edges <= max_fold_edges, "{name}: {}", c.fold_edges);
        // a guarded edge keeps its cubic boundary and is solved by (9.4) when that stays
        // bounded: it may be G¹ or (reported) unresolved
        assert!(s.fold_guarded.len() <= s.patches.len() / 2);
        assert!(c.max_micro_jump_rad <= 1e-9 || name == "fandisk.obj");
    }
}

/// The largest distance from the three-split surface to the flat mesh at the same parameter
/// (as `max_deviation`), divided by the longest edge of the macro triangle: sampled here, on
/// a grid of `n` steps per micro edge.
fn local_deviation(s: &SplitSurface, m: &TriMesh, n: usize) -> f64 {
    let mut worst: f64 = 0.0;
    for (k, patch) in s.patches.iter().enumerate() {
        let t = m.triangles[patch.macro_tri as usize];
        let v: Vec<Vector3> = t.iter().map(|&i| m.positions[i as usize].coords).collect();
        let len = (v[0] - v[1])
            .norm()
            .max((v[1] - v[2]).norm())
            .max((v[2] - v[0]).norm());
        // the patch's corners in its macro triangle: the three-split's fixed layout, or the
        // domain the edge split records
        let at = |d: [f64; 3]| v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
        let (a, b, z) = match s.domain.get(k) {
            Some(d) => (at(d[0]), at(d[1]), at(d[2])),
            None => (v[k % 3], v[(k + 1) % 3], (v[0] + v[1] + v[2]) / 3.0),
        };
        let tri = patch.triangle();
        for i in 0..=n {
            for j in 0..=n - i {
                let w = [(n - i - j) as f64, j as f64, i as f64].map(|x| x / n as f64);
                let flat = a * w[0] + b * w[1] + z * w[2];
                worst = worst.max((Vector3::from(tri.eval(w)) - flat).norm() / len);
            }
        }
    }
    worst
}

/// The normal jump along the macro edge `a b` of `s` (built on `m`), from both patches' own
/// control points (Bézier derivatives), at `samples` interior points.
fn edge_jump(s: &SplitSurface, m: &TriMesh, a: u32, b: u32, samples: usize) -> f64 {
    let find = |x: u32, y: u32| {
        let t = m
            .triangles
            .iter()
            .position(|t| (0..3).any(|i| t[i] == x && t[(i + 1) % 3] == y))
            .unwrap();
        // the patch of macro triangle t whose corners 0, 1 are x, y (any layout)
        let (px, py): ([f64; 3], [f64; 3]) = (
            m.positions[x as usize].into(),
            m.positions[y as usize].into(),
        );
        s.patches
            .iter()
            .map(|p| p.triangle())
            .zip(&s.patches)
            .find(|(tr, p)| {
                let c = tr.corners();
                p.macro_tri as usize == t && c[0] == px && c[1] == py
            })
            .unwrap()
            .0
    };
    let (p, q) = (find(a, b), find(b, a));
    let mut worst: f64 = 0.0;
    for k in 1..=samples {
        let t = k as f64 / (samples + 1) as f64;
        let n1 = Vector3::from(p.normal([1.0 - t, t, 0.0]));
        let n2 = Vector3::from(q.normal([t, 1.0 - t, 0.0]));
        worst = worst.max(n1.cross(&n2).norm().atan2(n1.dot(&n2)));
    }
    worst
}

#[test]
fn three_split_nearly_singular_edge_of_spot_stays_g1_and_bounded() {
    let Some(data) = common::data_dir() else {
        return;
    };
    // spot's edge 104–1842: the two triangles are (near) mirror images, |f0 g1 − g0 f1| is at
    // rounding level, and plain (9.4) throws L1, R1 out by 1.4e14 edge lengths there. The old
    // code caught this edge with its singular threshold, so this test also passes on it; it
    // pins the transversal construction on a real mesh. The deviation test below is the one
    // that fails on the old code (spot: 10.3 longest edges).
    let m = morpho::io::read_mesh(&data.join("meshes/spot.obj")).unwrap();
    let n0 = vertex_normals(&m, NormalWeighting::Area);
    let n = visible_normals(&m, &n0, 0.05).normals;
    let s = three_split_with(&m, &n, &SplitOptions { fold_guard: true }).unwrap();
    let (a, b) = (104u32, 1842u32);
    let jump = edge_jump(&s, &m, a, b, 40);
    let len = (m.positions[a as usize] - m.positions[b as usize]).norm();
    let t = m
        .triangles
        .iter()
        .position(|t| (0..3).any(|i| t[i] == a && t[(i + 1) % 3] == b))
        .unwrap();
    let far = s
        .patches
        .iter()
        .filter(|p| p.macro_tri as usize == t)
        .flat_map(|p| p.control.iter())
        .map(|c| (Vector3::from(*c) - m.positions[a as usize].coords).norm())
        .fold(0.0, f64::max);
    let longest = (0..3)
        .map(|i| {
            (m.positions[m.triangles[t][i] as usize]
                - m.positions[m.triangles[t][(i + 1) % 3] as usize])
                .norm()
        })
        .fold(len, f64::max);
    eprintln!(
        "spot edge {a}-{b}: jump {jump:.2e} rad, farthest control point {:.2} longest edges",
        far / longest
    );
    assert!(jump <= 1e-9, "{jump}");
    assert!(far <= 2.0 * longest, "{}", far / longest);
}

#[test]
fn three_split_stays_near_real_meshes() {
    let Some(data) = common::data_dir() else {
        return;
    };
    for (name, max_local) in [("spot.obj", 1.5), ("horse.obj.gz", 1.5)] {
        let m = morpho::io::read_mesh(&data.join("meshes").join(name)).unwrap();
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let n = visible_normals(&m, &n0, 0.05).normals;
        let s = three_split_with(&m, &n, &SplitOptions { fold_guard: true }).unwrap();
        let dev = local_deviation(&s, &m, 3);
        eprintln!(
            "{name}: max deviation {dev:.3} of the macro triangle's longest edge, max displacement {:.3}, unresolved {}",
            s.max_displacement,
            s.unresolved_edges.len()
        );
        assert!(dev <= max_local, "{name}: {dev}");
        assert!(s.max_displacement <= 3.0 + 1e-12, "{name}");
    }
}

/// Six-split (V §9.8 rebuilt, `morpho::smooth::six_split`): interpolation of every vertex and
/// its normal, continuity over every macro and micro edge (independent check), no folds.
fn check_six(m: &TriMesh, n: &[Vector3]) -> (SplitSurface, Continuity) {
    let s = six_split(m, n).unwrap();
    assert_eq!(s.patches.len(), 6 * m.triangles.len());
    let tol = 1e-12 * (1.0 + m.bbox().diagonal());
    let mut worst: f64 = 0.0;
    for (k, p) in s.patches.iter().enumerate() {
        let t = m.triangles[k / 6];
        let (i, h) = ((k % 6) / 2, k % 2);
        // patch 6t+2i = (V_i, M_i, O), 6t+2i+1 = (M_i, V_{i+1}, O)
        let (v, bary) = if h == 0 {
            (t[i] as usize, [1.0, 0.0, 0.0])
        } else {
            (t[(i + 1) % 3] as usize, [0.0, 1.0, 0.0])
        };
        let tri = p.triangle();
        let x: [f64; 3] = m.positions[v].into();
        let e = tri.eval(bary);
        let d = ((e[0] - x[0]).powi(2) + (e[1] - x[1]).powi(2) + (e[2] - x[2]).powi(2)).sqrt();
        assert!(d <= tol, "vertex {v}: {d}");
        let nn = Vector3::from(tri.normal(bary));
        let ang = nn.cross(&n[v]).norm().atan2(nn.dot(&n[v]));
        worst = worst.max(ang);
        assert!(ang <= 1e-10, "normal at vertex {v}: {ang} {:?}", p.control);
    }
    eprintln!("max vertex normal angle {worst:.1e} rad");
    let c = continuity(&s, 20);
    assert_eq!(c.open_edges, 0);
    assert!(c.max_position_gap <= tol, "{c:?}");
    (s, c)
}

#[test]
fn six_split_generic_meshes_are_g1_with_every_weighting() {
    for seed in 1..6 {
        let m = perturbed_icosahedron(seed);
        for w in [
            NormalWeighting::Area,
            NormalWeighting::Uniform,
            NormalWeighting::InverseArea,
        ] {
            let n = vertex_normals(&m, w);
            let (s, c) = check_six(&m, &n);
            assert!(s.unresolved_edges.is_empty(), "{:?}", s.unresolved_edges);
            assert_eq!(c.folds, 0);
            assert!(
                c.max_normal_jump_rad <= 1e-9,
                "seed {seed}: macro {:.1e} micro {:.1e}",
                c.max_macro_jump_rad,
                c.max_micro_jump_rad
            );
        }
    }
}

#[test]
fn six_split_is_g1_where_the_three_split_is_singular() {
    // octahedron and icosahedron with exact (sphere) normals: every edge mirror-symmetric,
    // (9.4) singular for the three-split; the six-split's sides are solved independently
    let oct = octahedron();
    for m in [oct, generate::icosphere(0), generate::icosphere(2)] {
        let n: Vec<Vector3> = m.positions.iter().map(|p| p.coords.normalize()).collect();
        let (s, c) = check_six(&m, &n);
        assert!(s.singular_edges.is_empty() && s.unresolved_edges.is_empty());
        assert_eq!(c.folds, 0);
        assert!(
            c.max_normal_jump_rad <= 1e-9,
            "{} tris: macro {:.1e} micro {:.1e}",
            m.triangles.len(),
            c.max_macro_jump_rad,
            c.max_micro_jump_rad
        );
        // close to the sphere: the boundary and the surface stay near radius 1
        for p in &s.patches {
            let tri = p.triangle();
            for b in [[0.2, 0.3, 0.5], [0.5, 0.5, 0.0], [0.1, 0.8, 0.1]] {
                let r = Vector3::from(tri.eval(b)).norm();
                assert!((r - 1.0).abs() < 0.1, "{r}");
            }
        }
    }
}

#[test]
fn six_split_linear_precision_a_flat_region_gives_the_plane() {
    for (jitter, seed) in [(0.0, 1), (0.4, 2), (0.4, 3)] {
        let (m, inner) = flat_box(6, jitter, seed);
        let n = vertex_normals(&m, NormalWeighting::Area);
        let (s, _) = check_six(&m, &n);
        for &[a, b] in &s.unresolved_edges {
            assert!(!inner[a as usize] || !inner[b as usize], "{a}-{b}");
        }
        let mut checked = 0;
        let mut rng = Rng::new(seed);
        for (k, p) in s.patches.iter().enumerate() {
            let t = m.triangles[k / 6];
            if !t.iter().all(|&v| inner[v as usize]) {
                continue;
            }
            checked += 1;
            let c: Vec<Point3> = t.iter().map(|&v| m.positions[v as usize]).collect();
            let z = (c[0].coords + c[1].coords + c[2].coords) / 3.0;
            let (i, h) = ((k % 6) / 2, k % 2);
            let mid = (c[i].coords + c[(i + 1) % 3].coords) / 2.0;
            let (a, b) = if h == 0 {
                (c[i].coords, mid)
            } else {
                (mid, c[(i + 1) % 3].coords)
            };
            let tri = p.triangle();
            for _ in 0..20 {
                let [u, v, w] = barycentric(&mut rng);
                // the affine map of the micro triangle: the plane, linearly parametrised
                let x = a * u + b * v + z * w;
                let d = (Vector3::from(tri.eval([u, v, w])) - x).norm();
                assert!(d <= 1e-12, "jitter {jitter}, patch {k}: {d}");
            }
        }
        assert!(checked >= 6 * 16, "{checked}");
    }
}

/// The icosphere(1) with every radius scaled by `1 ± amp` (seeded).
fn perturbed_icosphere(seed: u64, amp: f64) -> TriMesh {
    let mut m = generate::icosphere(1);
    let mut rng = Rng::new(seed);
    for p in &mut m.positions {
        *p = Point3::from(p.coords * (1.0 - amp + 2.0 * amp * uni(&mut rng)));
    }
    m
}

/// From the failure found on spot reduced to 20 % (module doc of `smooth::split6`): on an
/// inflected edge the field through the natural boundary was solved with `ρ = 1` fixed, its
/// middle normal swung far from the end normals and the sides' exact cross derivatives turned
/// outward (reported creases). These perturbed icospheres have 2–6 such edges each; before the
/// fix they were not G¹ there (4–12 non-G¹ micro edges per mesh, measured with the same
/// meshes through `morpho smooth --folds keep`); now every edge is G¹ and none is unresolved.
#[test]
fn six_split_inflected_edges_are_g1() {
    for seed in [2, 7, 9, 11] {
        let m = perturbed_icosphere(seed, 0.1);
        let n = vertex_normals(&m, NormalWeighting::Area);
        let (s, c) = check_six(&m, &n);
        assert!(
            !s.singular_edges.is_empty(),
            "seed {seed}: no inflected edge"
        );
        assert!(
            s.unresolved_edges.is_empty(),
            "seed {seed}: {:?}",
            s.unresolved_edges
        );
        assert_eq!(c.folds, 0, "seed {seed}");
        assert!(
            c.max_normal_jump_rad <= 1e-9,
            "seed {seed}: macro {:.1e} micro {:.1e}",
            c.max_macro_jump_rad,
            c.max_micro_jump_rad
        );
    }
}

/// The macro edge `[a, b]` (a < b) between micro patches `p` and `q` of different macro
/// triangles, from the patches' corner positions.
fn macro_edge(m: &TriMesh, s: &SplitSurface, p: usize, q: usize) -> [u32; 2] {
    let (tp, tq) = (
        m.triangles[s.patches[p].macro_tri as usize],
        m.triangles[s.patches[q].macro_tri as usize],
    );
    let shared: Vec<u32> = tp.iter().copied().filter(|v| tq.contains(v)).collect();
    assert_eq!(shared.len(), 2, "patches {p} {q}");
    [shared[0].min(shared[1]), shared[0].max(shared[1])]
}

#[test]
fn six_split_on_real_closed_meshes_reports_every_non_g1_edge() {
    let Some(data) = common::data_dir() else {
        return;
    };
    for name in ["spot.obj", "rocker-arm.obj", "fandisk.obj"] {
        let p = data.join("meshes").join(name);
        let m = morpho::io::read_mesh(&p).unwrap();
        if !morpho::mesh::analyze_topology(&m).is_closed() {
            continue;
        }
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let n = visible_normals(&m, &n0, 0.05).normals;
        let (s, c) = check_six(&m, &n);
        eprintln!(
            "{name}: {} tris, fallback {} unresolved {} signw {}, macro {:.2e} micro {:.2e} rad, non-G1 {}, folds {} on {} edges, max displacement {:.3}",
            m.triangles.len(), s.singular_edges.len(), s.unresolved_edges.len(), s.sign_warnings.len(),
            c.max_macro_jump_rad, c.max_micro_jump_rad, c.non_g1_edges.len(), c.folds, c.fold_edges, s.max_displacement
        );
        // inside every macro triangle the micro patches are C¹ (Powell–Sabin interior)
        // (fandisk: 1.25e-9 at a point where a micro patch is nearly singular, |normal| ≈ 5e-5
        // of its size, since the inflected-edge fix of split6b; 2.9e-10 before)
        let micro = if name == "fandisk.obj" { 2e-9 } else { 1e-9 };
        assert!(c.max_micro_jump_rad <= micro, "{}", c.max_micro_jump_rad);
        // every macro edge that is not G¹ is reported: unresolved, or built with the fallback
        // field (inflected), or a side turned over
        let reported: std::collections::HashSet<[u32; 2]> = s
            .unresolved_edges
            .iter()
            .chain(&s.singular_edges)
            .chain(&s.sign_warnings)
            .copied()
            .collect();
        let mut silent = Vec::new();
        for &(p, q) in &c.non_g1_edges {
            if s.patches[p].macro_tri == s.patches[q].macro_tri {
                continue; // a micro edge: bounded above
            }
            let e = macro_edge(&m, &s, p, q);
            if !reported.contains(&e) {
                silent.push(e);
            }
        }
        silent.dedup();
        assert!(
            silent.is_empty(),
            "{name}: not G1, not reported: {silent:?}"
        );
    }
}

/// Two-split (V §9.7, experimental; `morpho::smooth::two_split`): the layout (each pair's two
/// triangles share an edge, 4 patches instead of 6, no triangle next to a pair is paired),
/// interpolation of every vertex and its normal at every patch corner that is a mesh vertex,
/// and the independent continuity check; every edge that is not G¹ must be one the
/// three-split part reports (the pairs are G¹ by construction and a local check).
fn check_two(m: &TriMesh, n: &[Vector3]) -> (TwoSplit, Continuity) {
    let t = two_split(m, n, &SplitOptions::default()).unwrap();
    let s = &t.surface;
    assert_eq!(s.patches.len(), 3 * m.triangles.len() - 2 * t.pairs.len());
    assert_eq!(s.domain.len(), s.patches.len());
    let mut paired = vec![false; m.triangles.len()];
    let shares_edge = |a: [u32; 3], b: [u32; 3]| a.iter().filter(|v| b.contains(v)).count() == 2;
    for &[p, q] in &t.pairs {
        assert!(shares_edge(
            m.triangles[p as usize],
            m.triangles[q as usize]
        ));
        assert!(!paired[p as usize] && !paired[q as usize]);
        paired[p as usize] = true;
        paired[q as usize] = true;
    }
    for &[p, q] in &t.pairs {
        for (u, &tu) in m.triangles.iter().enumerate() {
            for w in [p, q] {
                if u as u32 != p && u as u32 != q && shares_edge(tu, m.triangles[w as usize]) {
                    assert!(!paired[u], "triangle {u} next to pair {p}-{q} is paired");
                }
            }
        }
    }
    let tol = 1e-12 * (1.0 + m.bbox().diagonal());
    let (mut corners, mut checked) = (0, 0);
    for (p, d) in s.patches.iter().zip(&s.domain) {
        let tri = m.triangles[p.macro_tri as usize];
        let bt = p.triangle();
        for (c, w) in d.iter().enumerate() {
            let Some(k) = (0..3).find(|&k| w[k] == 1.0) else {
                continue;
            };
            corners += 1;
            let v = tri[k] as usize;
            let mut bary = [0.0; 3];
            bary[c] = 1.0;
            let x: [f64; 3] = m.positions[v].into();
            let e = bt.eval(bary);
            let dd = (Vector3::from(e) - Vector3::from(x)).norm();
            assert!(dd <= tol, "vertex {v}: {dd}");
            // a three-split patch's corner can be degenerate (its two handles collinear or one
            // of zero length, as at the flat box's rim and corners): no tangent plane to compare
            let (i1, i2) = [(1, 2), (3, 7), (8, 5)][c];
            let h = |i: usize| Vector3::from(p.control[i]) - Vector3::from(e);
            let (h1, h2) = (h(i1), h(i2));
            if !paired[p.macro_tri as usize]
                && h1.cross(&h2).norm() <= 1e-9 * h1.norm().max(h2.norm()).powi(2)
            {
                continue;
            }
            checked += 1;
            let nn = Vector3::from(bt.normal(bary));
            let ang = nn.cross(&n[v]).norm().atan2(nn.dot(&n[v]));
            // the tangent plane is interpolated; a three-split patch may be turned over at a
            // vertex whose normal does not see its triangles (its fold), a pair's never is
            assert!(
                ang.min(std::f64::consts::PI - ang) <= 1e-10,
                "normal at vertex {v}: {ang}, paired {} control {:?}",
                paired[p.macro_tri as usize],
                p.control
            );
            assert!(
                ang <= 1e-10 || !paired[p.macro_tri as usize],
                "pair turned over at vertex {v}"
            );
        }
    }
    // every micro patch has two mesh-vertex corners
    assert_eq!(corners, 2 * s.patches.len());
    assert!(
        checked * 5 >= corners * 4,
        "{checked} of {corners} corners checked"
    );
    let c = continuity(s, 20);
    assert_eq!(c.open_edges, 0);
    assert!(c.max_position_gap <= tol, "{c:?}");
    // every non-G¹ edge is a macro edge the three-split part reports
    let reported: std::collections::HashSet<[u32; 2]> = s
        .unresolved_edges
        .iter()
        .chain(&s.singular_edges)
        .chain(&s.fold_guarded)
        .chain(&s.sign_warnings)
        .copied()
        .collect();
    // the three-split alone (same normals): its non-G¹ macro edges
    let s3 = three_split(m, n).unwrap();
    let c3 = continuity(&s3, 20);
    let non_g1_3: std::collections::HashSet<[u32; 2]> = c3
        .non_g1_edges
        .iter()
        .filter(|&&(p, q)| s3.patches[p].macro_tri != s3.patches[q].macro_tri)
        .map(|&(p, q)| macro_edge(m, &s3, p, q))
        // the edges the three-split's first pass left non-G¹ and its edge split then split
        // (edgesplit.rs): the two-split builds on that first pass
        .chain(s3.split_edges.iter().copied())
        .collect();
    assert!(
        c.folds <= c3.folds,
        "folds {} > three-split's {}",
        c.folds,
        c3.folds
    );
    for &(p, q) in &c.non_g1_edges {
        let (tp, tq) = (s.patches[p].macro_tri, s.patches[q].macro_tri);
        assert_ne!(
            tp, tq,
            "micro edge {p}-{q} inside macro triangle {tp} is not G1"
        );
        assert!(
            !(paired[tp as usize] && paired[tq as usize]),
            "edge {p}-{q} inside a pair is not G1"
        );
        let e = macro_edge(m, s, p, q);
        assert!(
            reported.contains(&e) || non_g1_3.contains(&e),
            "non-G1 edge {e:?} (triangles {tp} {tq}, paired {} {}) neither reported nor non-G1 in the three-split",
            paired[tp as usize],
            paired[tq as usize]
        );
    }
    (t, c)
}

#[test]
fn two_split_perturbed_icospheres_are_g1() {
    for seed in [1, 2, 7, 9, 11] {
        for amp in [0.05, 0.1] {
            let m = perturbed_icosphere(seed, amp);
            let n = vertex_normals(&m, NormalWeighting::Area);
            let (t, c) = check_two(&m, &n);
            eprintln!(
                "seed {seed} amp {amp}: {} pairs, {} rejected, jump {:.1e} (macro {:.1e} micro {:.1e}), non-G1 {}, folds {}, unresolved {}",
                t.pairs.len(), t.rejected.len(), c.max_normal_jump_rad, c.max_macro_jump_rad,
                c.max_micro_jump_rad, c.non_g1_edges.len(), c.folds, t.surface.unresolved_edges.len()
            );
            assert!(t.pairs.len() >= 5, "seed {seed}: {} pairs", t.pairs.len());
            if c.folds == 0 && t.surface.unresolved_edges.is_empty() {
                assert!(c.max_normal_jump_rad <= 1e-9, "seed {seed} amp {amp}");
            }
        }
    }
    // the unperturbed icosphere: the pairs avoid thin triangles nowhere better than elsewhere,
    // but every triangle qualifies (the two-split's worst micro triangle, quality 0.75, beats
    // the three-split's 0.6)
    let m = generate::icosphere(1);
    let n = vertex_normals(&m, NormalWeighting::Area);
    let (t, c) = check_two(&m, &n);
    assert!(t.pairs.len() >= 10, "{}", t.pairs.len());
    assert!(c.max_normal_jump_rad <= 1e-9, "{c:?}");
}

#[test]
fn two_split_linear_precision_a_flat_region_gives_the_plane() {
    for (jitter, seed) in [(0.0, 1), (0.4, 2), (0.4, 3)] {
        let (m, inner) = flat_box(6, jitter, seed);
        let n = vertex_normals(&m, NormalWeighting::Area);
        let (t, _) = check_two(&m, &n);
        let s = &t.surface;
        let mut rng = Rng::new(seed);
        let (mut checked, mut in_pairs) = (0, 0);
        let paired: std::collections::HashSet<u32> = t.pairs.iter().flatten().copied().collect();
        for (p, d) in s.patches.iter().zip(&s.domain) {
            let tri = m.triangles[p.macro_tri as usize];
            if !tri.iter().all(|&v| inner[v as usize]) {
                continue;
            }
            checked += 1;
            in_pairs += usize::from(paired.contains(&p.macro_tri));
            let c: Vec<Vector3> = tri
                .iter()
                .map(|&v| m.positions[v as usize].coords)
                .collect();
            let at = |w: [f64; 3]| c[0] * w[0] + c[1] * w[1] + c[2] * w[2];
            let bt = p.triangle();
            for _ in 0..20 {
                let [u, v, w] = barycentric(&mut rng);
                // the affine map of the micro triangle's domain corners
                let x = at(d[0]) * u + at(d[1]) * v + at(d[2]) * w;
                let e = Vector3::from(bt.eval([u, v, w]));
                assert!(
                    (e - x).norm() <= 1e-12,
                    "jitter {jitter}: {}",
                    (e - x).norm()
                );
            }
        }
        eprintln!(
            "jitter {jitter}: {} pairs, {checked} flat patches, {in_pairs} in pairs",
            t.pairs.len()
        );
        assert!(in_pairs >= 8, "{in_pairs}");
    }
}

#[test]
fn two_split_on_a_real_closed_mesh_reports_every_non_g1_edge() {
    let Some(data) = common::data_dir() else {
        return;
    };
    for name in ["spot.obj", "bunny_npm.obj"] {
        let p = data.join("meshes").join(name);
        let Ok(m) = morpho::io::read_mesh(&p) else {
            continue;
        };
        if !morpho::mesh::analyze_topology(&m).is_closed() {
            continue;
        }
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let n = visible_normals(&m, &n0, 0.05).normals;
        let (t, c) = check_two(&m, &n);
        eprintln!(
            "{name}: {} tris, {} pairs, {} rejected, jump {:.1e} (micro {:.1e}), non-G1 {} of {}, folds {} ({} edges), unresolved {}",
            m.triangles.len(), t.pairs.len(), t.rejected.len(), c.max_normal_jump_rad,
            c.max_micro_jump_rad, c.non_g1_edges.len(), c.edges, c.folds, c.fold_edges,
            t.surface.unresolved_edges.len()
        );
        assert!(
            t.pairs.len() >= m.triangles.len() / 50,
            "{name}: {}",
            t.pairs.len()
        );
    }
}

#[test]
fn two_split_refuses_bad_meshes() {
    let mut open = generate::icosphere(1);
    open.triangles.pop();
    let n = vertex_normals(&open, NormalWeighting::Area);
    assert!(matches!(
        two_split(&open, &n, &SplitOptions::default()),
        Err(SmoothError::NotClosed { .. })
    ));
    let mut nan = generate::icosphere(1);
    let n = vertex_normals(&nan, NormalWeighting::Area);
    nan.positions[3].x = f64::NAN;
    assert!(matches!(
        two_split(&nan, &n, &SplitOptions::default()),
        Err(SmoothError::NonFinite { .. })
    ));
    let m = generate::icosphere(1);
    let mut n = vertex_normals(&m, NormalWeighting::Area);
    n[5] = Vector3::new(f64::NAN, 0.0, 0.0);
    assert!(two_split(&m, &n, &SplitOptions::default()).is_err());
}

#[test]
fn three_split_non_g1_edges_by_cause_on_fandisk() {
    let Some(data) = common::data_dir() else {
        return;
    };
    let m = morpho::io::read_mesh(&data.join("meshes").join("fandisk.obj")).unwrap();
    let n0 = vertex_normals(&m, NormalWeighting::Area);
    let a = visible_normals(&m, &n0, 0.05);
    let s = three_split_with(&m, &a.normals, &SplitOptions { fold_guard: true }).unwrap();
    let c = continuity(&s, 20);
    let k = morpho::smooth::non_g1_causes(&s, &m, &a.normals, &c);
    eprintln!("fandisk: non-G1 {} {k:?}", c.non_g1_edges.len());
    // every non-G¹ edge is in exactly one class
    assert_eq!(
        k.micro + k.fold_invisible + k.fold + k.inflected + k.other,
        c.non_g1_edges.len()
    );
    // micro: only edges inside a macro triangle the edge split bisected (edgesplit.rs), each
    // listed by its triangle
    for &(p, q) in &c.non_g1_edges {
        let (tp, tq) = (s.patches[p].macro_tri, s.patches[q].macro_tri);
        assert!(tp != tq || s.non_g1_inner.contains(&tp), "{p} {q}");
    }
    // the repaired normals see their triangles: no unavoidable fold
    assert_eq!(k.fold_invisible, 0);
    // before the backward-stable (9.4) (split3 module doc, Step 5 case 2): 1 099 non-G¹ edges,
    // 19 fold edges, 677 of them not listed as unresolved; after: 544, 7, 144; after the
    // edge split (edgesplit.rs, two rounds): 135 (26 inside split triangles), 6
    assert!(c.non_g1_edges.len() <= 135, "{}", c.non_g1_edges.len());
    assert!(c.fold_edges <= 7, "{}", c.fold_edges);
    assert!(k.unlisted <= 144, "{}", k.unlisted);
}

/// Issue 19, item 4 ("report every edge that is not G¹"): the three-split's own list of
/// non-G¹ macro edges (its a-posteriori check, `SplitSurface::non_g1_edges`) is exactly the
/// set of macro edges the independent check finds above 1e-9 rad, on the real meshes where
/// edges were claimed G¹ and measured not (fandisk 144, rocker-arm 5 before the check), and
/// nothing is unlisted.
#[test]
fn three_split_lists_exactly_the_non_g1_macro_edges_on_real_meshes() {
    let Some(data) = common::data_dir() else {
        return;
    };
    for name in ["fandisk.obj", "spot.obj", "rocker-arm.obj"] {
        let m = morpho::io::read_mesh(&data.join("meshes").join(name)).unwrap();
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let a = visible_normals(&m, &n0, 0.05);
        let s = three_split_with(&m, &a.normals, &SplitOptions { fold_guard: true }).unwrap();
        let (measured, k) = measured_non_g1_macro_edges(name, &m, &s, &a.normals);
        // non-G¹ edges inside a macro triangle occur only where the edge split bisected it,
        // and are listed by triangle (fandisk; edgesplit.rs)
        assert!(k.micro == 0 || !s.non_g1_inner.is_empty(), "{name}");
        assert_eq!(measured, s.non_g1_edges, "{name}");
        assert_eq!(k.unlisted, 0, "{name}");
        // spot keeps 3 after the edge split (edgesplit.rs), fandisk and rocker-arm more
        assert!(
            !measured.is_empty(),
            "{name}: nothing to list, the test is vacuous"
        );
    }
}

/// The macro edges (sorted, each once: the six-split has two shared edges per macro edge) of
/// `s`'s non-G¹ shared edges as `continuity` measures them at 20 samples, and their causes
/// (`normals`: those `s` was built with); prints the counts under `name`.
fn measured_non_g1_macro_edges(
    name: &str,
    m: &TriMesh,
    s: &SplitSurface,
    normals: &[Vector3],
) -> (Vec<[u32; 2]>, morpho::smooth::NonG1Causes) {
    let c = continuity(s, 20);
    let mut measured: Vec<[u32; 2]> = c
        .non_g1_edges
        .iter()
        .filter(|&&(p, q)| s.patches[p].macro_tri != s.patches[q].macro_tri)
        .map(|&(p, q)| macro_edge(m, s, p, q))
        .collect();
    measured.sort_unstable();
    measured.dedup();
    let k = morpho::smooth::non_g1_causes(s, m, normals, &c);
    eprintln!(
        "{name}: non-G1 {} listed {} {k:?}",
        c.non_g1_edges.len(),
        s.non_g1_edges.len()
    );
    (measured, k)
}

/// The six-split runs the same a-posteriori check on both halves of every macro edge: its
/// `non_g1_edges` are exactly the macro edges `continuity` measures not G¹ (either half), so
/// nothing is unlisted (before the check, fandisk had 1 and rocker-arm 3 non-G¹ macro edges
/// that were not among the `unresolved_edges`, and `non_g1_edges` was empty).
#[test]
fn six_split_lists_exactly_the_non_g1_macro_edges_on_real_meshes() {
    let Some(data) = common::data_dir() else {
        return;
    };
    for name in ["fandisk.obj", "spot.obj", "rocker-arm.obj"] {
        let m = morpho::io::read_mesh(&data.join("meshes").join(name)).unwrap();
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let a = visible_normals(&m, &n0, 0.05);
        let s = six_split(&m, &a.normals).unwrap();
        let (measured, k) = measured_non_g1_macro_edges(name, &m, &s, &a.normals);
        assert_eq!(measured, s.non_g1_edges, "{name}");
        assert_eq!(k.unlisted, 0, "{name}");
        assert!(
            !measured.is_empty(),
            "{name}: nothing to list, the test is vacuous"
        );
    }
}

//! Tests of Hamann's side-vertex surface (H ch. 6; NOTES E.5; issue 19 item 5): interpolation
//! of vertices and normals, circle precision of the conics, Thm 6.1 (i)–(iii) for the squared
//! weights, Hamann's sphere test (tetrahedron in the unit sphere), tangent-plane continuity
//! measured independently of the construction, and bad input.

mod common;
use morpho::geom::{Point3, Vector3};
use morpho::mesh::{generate, vertex_normals, NormalWeighting, TriMesh};
use morpho::smooth::*;

type P3 = [f64; 3];

fn v(p: P3) -> Vector3 {
    Vector3::from(p)
}

fn angle(a: P3, b: P3) -> f64 {
    v(a).cross(&v(b)).norm().atan2(v(a).dot(&v(b)))
}

/// A seeded xorshift64*.
struct Rng(u64);
impl Rng {
    fn uni(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn unit(&mut self) -> Vector3 {
        loop {
            let p = Vector3::new(self.uni(), self.uni(), self.uni()) * 2.0 - Vector3::repeat(1.0);
            if p.norm() > 0.1 && p.norm() < 1.0 {
                return p.normalize();
            }
        }
    }
}

/// The regular tetrahedron inscribed in the unit sphere with the sphere's normals.
fn unit_tet() -> (TriMesh, Vec<Vector3>) {
    let mut m = generate::tetrahedron();
    for p in &mut m.positions {
        *p = Point3::from(p.coords / 3f64.sqrt());
    }
    let n = m.positions.iter().map(|p| p.coords).collect();
    (m, n)
}

fn spot() -> Option<(TriMesh, Vec<Vector3>)> {
    let m = morpho::io::read_mesh(&common::data("meshes/spot.obj")?).unwrap();
    let n = vertex_normals(&m, NormalWeighting::Area);
    Some((m, n))
}

/// Barycentric grid points with `n` steps per edge.
fn grid(n: usize) -> Vec<P3> {
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
            out.push([1.0 - a - b, b, a]);
        }
    }
    out
}

#[test]
fn interpolates_every_vertex_and_its_normal() {
    let ico = generate::icosphere(1);
    let ico_n = vertex_normals(&ico, NormalWeighting::Area);
    for (m, n) in [Some((ico, ico_n)), spot(), Some(unit_tet())]
        .into_iter()
        .flatten()
    {
        let s = side_vertex(&m, &n, &SideVertexOptions::default()).unwrap();
        for (t, tri) in m.triangles.iter().enumerate() {
            for k in 0..3 {
                let mut u = [0.0; 3];
                u[k] = 1.0;
                let vk = tri[k] as usize;
                let p: P3 = m.positions[vk].into();
                assert!((v(s.eval(t, u)) - v(p)).norm() <= 1e-12);
                let nk = n[vk].normalize();
                assert!((v(s.normal(t, u)) - nk).norm() <= 1e-12);
                // the boundary curves leave the vertex in its tangent plane, so the surface's
                // tangent plane there is the prescribed one
                for side in [(k + 1) % 3, (k + 2) % 3] {
                    let (e, rev) = s.side(t, side);
                    let local = if k == (side + 1) % 3 { 0.0 } else { 1.0 };
                    let end = if rev { 1.0 - local } else { local };
                    let at = if end == 0.0 { 1e-12 } else { 1.0 - 1e-12 };
                    let tan = e.conic.unit_tangent(end);
                    assert!(
                        v(tan).dot(&nk).abs() <= 1e-12,
                        "tangent·n at vertex {vk}: {} {e:?}",
                        v(tan).dot(&nk)
                    );
                    assert!((v(e.normal(end)) - nk).norm() <= 1e-12);
                    // and the boundary normal field is continuous into the vertex
                    assert!((v(e.normal(at)) - nk).norm() <= 1e-6);
                }
            }
            // the boundary curves of neighbouring patches are the same curve (C⁰)
            for i in 0..3 {
                for k in 1..10 {
                    let tt = k as f64 / 10.0;
                    let mut u = [0.0; 3];
                    u[(i + 1) % 3] = 1.0 - tt;
                    u[(i + 2) % 3] = tt;
                    let (p, _) = s.boundary(t, i, tt);
                    assert!((v(s.eval(t, u)) - v(p)).norm() <= 1e-12);
                }
            }
        }
    }
}

#[test]
fn conics_have_circle_precision() {
    let mut r = Rng(0x5eed_c1c1e);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let c = Vector3::new(r.uni(), r.uni(), r.uni()) * 10.0 - Vector3::repeat(5.0);
        let rad = 0.01 + 5.0 * r.uni();
        let a = r.unit();
        let b = a.cross(&r.unit()).normalize();
        let th0 = 6.3 * r.uni();
        let th1 = th0 + 0.05 + 2.9 * r.uni(); // arcs up to ~169°
        let dir = |t: f64| a * t.cos() + b * t.sin();
        let (p0, p1) = (c + dir(th0) * rad, c + dir(th1) * rad);
        let conic =
            Conic::new(p0.into(), dir(th0).into(), p1.into(), dir(th1).into(), 1.0).unwrap();
        assert!(conic.convex);
        assert!((conic.angles[0] - conic.angles[1]).abs() < 1e-12); // isosceles
        let normal = a.cross(&b);
        for k in 0..=50 {
            let p = v(conic.eval(k as f64 / 50.0));
            let off_sphere = ((p - c).norm() - rad).abs();
            let off_plane = (p - c).dot(&normal).abs();
            worst = worst.max(off_sphere.max(off_plane) / rad);
        }
    }
    assert!(
        worst <= 1e-12,
        "conic off its circle by {worst:e} (relative)"
    );
    // the literal weights ω1 = ω2 = ω would leave the circle: the elevated (1+2ω)/3 are used
    let q = Conic::new(
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        1.0,
    )
    .unwrap();
    let w = 0.5f64.sqrt(); // sin(γ/2), γ = π/2
    assert!((q.omega - w).abs() < 1e-15);
    assert!((q.weights[1] - (1.0 + 2.0 * w) / 3.0).abs() < 1e-15);
}

#[test]
fn generalized_conic_has_one_inflection() {
    let s = 0.5f64.sqrt();
    let c = Conic::new([0.0; 3], [-s, s, 0.0], [1.0, 0.0, 0.0], [-s, s, 0.0], 1.0).unwrap();
    assert!(!c.convex);
    // the signed curvature (z of ċ × c̈) changes sign exactly once
    let pts: Vec<Vector3> = (0..=200).map(|k| v(c.eval(k as f64 / 200.0))).collect();
    let mut signs = Vec::new();
    for w in pts.windows(3) {
        let k = (w[1] - w[0]).cross(&(w[2] - w[1])).z;
        if k.abs() > 1e-14 {
            signs.push(k > 0.0);
        }
    }
    let changes = signs.windows(2).filter(|w| w[0] != w[1]).count();
    assert_eq!(changes, 1);
    // a convex configuration keeps one curvature sign (Rem. 6.4)
    let c = Conic::new([0.0; 3], [-s, s, 0.0], [1.0, 0.0, 0.0], [s, s, 0.0], 1.0).unwrap();
    assert!(c.convex);
    let pts: Vec<Vector3> = (0..=200).map(|k| v(c.eval(k as f64 / 200.0))).collect();
    assert!(pts
        .windows(3)
        .all(|w| (w[1] - w[0]).cross(&(w[2] - w[1])).z < 0.0));
}

#[test]
fn weight_functions_satisfy_theorem_6_1() {
    let mut r = Rng(0x6_1);
    for _ in 0..1000 {
        let (a, b) = (r.uni(), r.uni());
        let u = if a + b <= 1.0 {
            [a, b, 1.0 - a - b]
        } else {
            [1.0 - a, 1.0 - b, a + b - 1.0]
        };
        // (i) partition of unity, non-negative
        let w = side_vertex_weights(u);
        assert!((w.iter().sum::<f64>() - 1.0).abs() <= 1e-14);
        assert!(w.iter().all(|&x| x >= 0.0));
        for e in 0..3 {
            // a point on edge e (u_e = 0)
            let mut p = u;
            let x = p[e];
            p[e] = 0.0;
            p[(e + 1) % 3] += x;
            if p[(e + 1) % 3] < 0.05 || p[(e + 2) % 3] < 0.05 {
                continue;
            }
            // (ii) w_i(e_k) = δ_ik
            let w = side_vertex_weights(p);
            for (i, wi) in w.iter().enumerate() {
                assert_eq!(*wi, if i == e { 1.0 } else { 0.0 });
            }
            // (iii) zero derivative of w_e across e_e, in any direction (central differences;
            // the unsquared (6.2) gives −1/(u_j u_k) here)
            for d in [
                [1.0, -0.5, -0.5],
                [1.0, -1.0, 0.0],
                [1.0, 0.0, -1.0],
                [0.0, 1.0, -1.0],
            ] {
                let mut dd = [0.0; 3];
                for k in 0..3 {
                    dd[k] = d[(k + 3 - e) % 3];
                }
                let h = 1e-6;
                let at = |s: f64| side_vertex_weights([0, 1, 2].map(|k| p[k] + s * dd[k]));
                let der = (at(h)[e] - at(-h)[e]) / (2.0 * h);
                assert!(der.abs() <= 1e-6, "D w_{e} = {der} at {p:?} along {dd:?}");
            }
        }
    }
    // at the vertices (0/0) the vertex's own weight
    assert_eq!(side_vertex_weights([0.0, 1.0, 0.0]), [0.0, 1.0, 0.0]);
}

#[test]
fn hamann_sphere_test() {
    let (m, n) = unit_tet();
    let s = side_vertex(&m, &n, &SideVertexOptions::default()).unwrap();
    // every building block (and so every boundary and radial conic) lies on the sphere
    let mut block_off: f64 = 0.0;
    for t in 0..4 {
        for u in grid(24) {
            for i in 0..3 {
                block_off = block_off.max((v(s.block(t, i, u)).norm() - 1.0).abs());
            }
        }
    }
    assert!(
        block_off <= 1e-12,
        "a building block leaves the sphere by {block_off:e}"
    );
    // the blend does not (Rem. 6.3): the maximum over a dense tessellation is at the face
    // centroids (density 48 contains them), 0.03422, as in NOTES E.4; the thesis's "about
    // 0.01" is not reproduced (a grid of 4 or 5 steps per edge, which misses the centroid,
    // shows 0.0167 / 0.0158)
    let dev = |s: &SideVertexSurface, d: usize| {
        let t = s.tessellate(d).unwrap();
        t.positions
            .iter()
            .map(|p| (p.coords.norm() - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let d48 = dev(&s, 48);
    let text = SideVertexOptions {
        handle_floor: 0.0,
        ..Default::default()
    };
    let faithful = side_vertex(&m, &n, &text).unwrap();
    assert_eq!(dev(&faithful, 48), d48); // the floor leaves sphere data alone
    println!("sphere test: max | |s| - 1 | = {d48:.6} (density 48)");
    assert!((0.03420..=0.03424).contains(&d48), "{d48}");
    let centroid = (v(s.eval(0, [1.0 / 3.0; 3])).norm() - 1.0).abs();
    assert!((centroid - d48).abs() < 1e-12);
    assert!((dev(&s, 4) - 0.016666).abs() < 1e-5);
    assert!((dev(&s, 5) - 0.015797).abs() < 1e-5);
    // lower weights (Fig. 6.7): flatter, further from the sphere
    let low = side_vertex(
        &m,
        &n,
        &SideVertexOptions {
            tension: 0.5,
            ..Default::default()
        },
    )
    .unwrap();
    let d_low = dev(&low, 48);
    println!("tension 0.5: {d_low:.6}");
    assert!(d_low > 0.2 && d_low < 0.577, "{d_low}");
}

#[test]
fn tangent_planes_are_continuous() {
    // sphere data: every conic a great-circle arc
    let (m, n) = unit_tet();
    let s = side_vertex(&m, &n, &SideVertexOptions::default()).unwrap();
    let c = side_vertex_continuity(&s, 20, 1e-9);
    println!("tetrahedron: max normal jump {:e}", c.max_normal_jump_rad);
    assert_eq!((c.edges, c.open_edges, c.folds), (6, 0, 0));
    assert!(c.max_normal_jump_rad <= 1e-9 && c.non_g1_edges.is_empty());
    assert!(c.max_position_gap <= 1e-14);
    // estimated normals on an icosphere, and with a tension
    let m = generate::icosphere(2);
    let n = vertex_normals(&m, NormalWeighting::Area);
    for tension in [1.0, 0.3] {
        let s = side_vertex(
            &m,
            &n,
            &SideVertexOptions {
                tension,
                ..Default::default()
            },
        )
        .unwrap();
        let c = side_vertex_continuity(&s, 20, 1e-9);
        println!(
            "icosphere(2), tension {tension}: max normal jump {:e}",
            c.max_normal_jump_rad
        );
        assert_eq!((c.edges, c.folds), (480, 0));
        assert!(c.max_normal_jump_rad <= 1e-9, "{}", c.max_normal_jump_rad);
    }
    // a real mesh with inflected (non-convex) edges, the text's conics (handle floor 0): no
    // fold; where a radial conic's end handle nearly collapses (one tangent along its chord,
    // l32/l ≈ 1e-4) the normal turns within 1e-4 of the edge, which finite differences
    // resolved only to 1e-5 rad; the exact derivatives measure 3.7e-11
    let Some((m, n)) = spot() else {
        return;
    };
    let text = SideVertexOptions {
        handle_floor: 0.0,
        ..Default::default()
    };
    let s = side_vertex(&m, &n, &text).unwrap();
    assert!(s.inflected_edges().len() > 100);
    let c = side_vertex_continuity(&s, 10, 1e-9);
    println!(
        "spot, text: max normal jump {:e}, {} of {} edges above 1e-9, position gap {:e}",
        c.max_normal_jump_rad,
        c.non_g1_edges.len(),
        c.edges,
        c.max_position_gap
    );
    assert_eq!((c.folds, c.open_edges), (0, 0));
    assert!(c.max_normal_jump_rad <= 1e-9, "{}", c.max_normal_jump_rad);
    assert!(c.max_position_gap <= 1e-14);
    // with the default handle floor 0.1 no handle collapses; exact derivatives measure the
    // issue's number: measured 6.5e-13 (finite differences reported 1.6e-8, their rounding)
    let s = side_vertex(&m, &n, &SideVertexOptions::default()).unwrap();
    let c = side_vertex_continuity(&s, 10, 1e-9);
    println!(
        "spot, floor 0.1: max normal jump {:e}, {} of {} edges above 1e-9",
        c.max_normal_jump_rad,
        c.non_g1_edges.len(),
        c.edges
    );
    assert_eq!(c.folds, 0);
    assert!(c.max_normal_jump_rad <= 1e-9, "{}", c.max_normal_jump_rad);
    assert!(c.non_g1_edges.is_empty());
    // inside the patches the boundary normal is the limit of the patch normal
    let mut worst: f64 = 0.0;
    for t in (0..m.triangles.len()).step_by(7) {
        for i in 0..3 {
            let mut u = [0.0; 3];
            u[(i + 1) % 3] = 0.5;
            u[(i + 2) % 3] = 0.5;
            let mut inner = u;
            inner[i] = 1e-4;
            inner[(i + 1) % 3] -= 1e-4;
            worst = worst.max(angle(s.normal(t, u), s.sampled_normal(t, inner)));
        }
    }
    assert!(worst < 0.05, "{worst}");
}

#[test]
fn tessellation_is_closed_with_surface_normals() {
    let m = generate::icosphere(1);
    let n = vertex_normals(&m, NormalWeighting::Area);
    let s = side_vertex(&m, &n, &SideVertexOptions::default()).unwrap();
    let t = s.tessellate(6).unwrap();
    let topo = morpho::mesh::analyze_topology(&t);
    assert!(topo.is_closed() && topo.consistently_oriented);
    assert_eq!(topo.euler_characteristic, 2);
    assert_eq!(t.triangles.len(), m.triangles.len() * 36);
    let nn = t.normals.as_ref().unwrap();
    for (p, q) in t.positions.iter().zip(nn) {
        assert!((q.norm() - 1.0).abs() < 1e-12);
        assert!(q.dot(&p.coords.normalize()) > 0.99);
    }
    assert!(t.signed_volume() > 0.0);
    // deviation from the flat mesh is bounded and positive
    let d = s.max_deviation(6);
    assert!(d > 0.0 && d < 0.1, "{d}");
    assert!(matches!(
        s.tessellate(0),
        Err(SmoothError::Parameter { .. })
    ));
}

#[test]
fn bad_input_is_a_typed_error() {
    let o = SideVertexOptions::default();
    // open mesh
    let disk = generate::disk(3, 8);
    let n = vertex_normals(&disk, NormalWeighting::Area);
    assert!(matches!(
        side_vertex(&disk, &n, &o),
        Err(SmoothError::NotClosed { .. })
    ));
    // non-manifold: a tetrahedron with one face twice
    let (mut m, n) = unit_tet();
    let f = m.triangles[0];
    m.triangles.push(f);
    assert!(matches!(
        side_vertex(&m, &n, &o),
        Err(SmoothError::NonManifold { .. })
    ));
    // inconsistent orientation
    let (mut m, n) = unit_tet();
    m.triangles[0].swap(0, 1);
    assert!(side_vertex(&m, &n, &o).is_err());
    // zero-length and NaN normal, wrong count
    let (m, mut n) = unit_tet();
    n[2] = Vector3::zeros();
    assert!(matches!(
        side_vertex(&m, &n, &o),
        Err(SmoothError::BadNormal { vertex: 2 })
    ));
    n[2] = Vector3::new(f64::NAN, 0.0, 1.0);
    assert!(matches!(
        side_vertex(&m, &n, &o),
        Err(SmoothError::BadNormal { vertex: 2 })
    ));
    assert!(side_vertex(&m, &n[..3], &o).is_err());
    // NaN position
    let (mut m, n) = unit_tet();
    m.positions[1].x = f64::NAN;
    assert!(matches!(
        side_vertex(&m, &n, &o),
        Err(SmoothError::NonFinite { index: 1 })
    ));
    // zero-area triangle, missing vertex
    let (mut m, n) = unit_tet();
    m.positions[1] = m.positions[0];
    assert!(side_vertex(&m, &n, &o).is_err());
    let (mut m, n) = unit_tet();
    m.triangles[0][0] = 9;
    assert!(matches!(
        side_vertex(&m, &n, &o),
        Err(SmoothError::BadIndex { .. })
    ));
    // tension
    let (m, n) = unit_tet();
    for tension in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            side_vertex(
                &m,
                &n,
                &SideVertexOptions {
                    tension,
                    ..Default::default()
                }
            ),
            Err(SmoothError::Parameter { .. })
        ));
    }
    // the conic itself
    assert!(matches!(
        Conic::new(
            [f64::NAN; 3],
            [0.0, 0.0, 1.0],
            [1.0; 3],
            [0.0, 0.0, 1.0],
            1.0
        ),
        Err(SmoothError::NonFinite { index: 0 })
    ));
    assert!(matches!(
        Conic::new([0.0; 3], [0.0; 3], [1.0; 3], [0.0, 0.0, 1.0], 1.0),
        Err(SmoothError::BadNormal { vertex: 0 })
    ));
    // degenerate but finite data never panics: antiparallel normals, normals along the edge
    let (m, _) = unit_tet();
    let mut r = Rng(7);
    let n: Vec<Vector3> = (0..4).map(|_| r.unit()).collect();
    let s = side_vertex(&m, &n, &o).unwrap();
    for u in grid(6) {
        assert!(s.eval(0, u).iter().all(|x| x.is_finite()));
    }
}

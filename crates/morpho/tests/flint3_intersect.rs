//! Mesh–mesh intersection by descending two 3D flintstone trees (V §7.4, notes A.8): the set
//! of intersecting triangle pairs equals the brute-force exact test on overlapping perturbed
//! icospheres, a mesh against a translated copy and against itself, cubes touching at a face,
//! an edge or a vertex, disjoint meshes, coplanar overlaps and real scans; detection agrees;
//! the segments lie on both triangles.
mod common;
use common::XorShift as Rng;
use morpho::flint::{intersect3, intersect3_brute, intersects3, triangle_meet, FlintTree3};
use morpho::geom::Point3;
use morpho::mesh::{generate, TriMesh};

fn shifted(m: &TriMesh, d: [f64; 3]) -> TriMesh {
    let mut m = m.clone();
    for p in &mut m.positions {
        *p = Point3::new(p.x + d[0], p.y + d[1], p.z + d[2]);
    }
    m
}

/// Each vertex moved radially by a random factor in [1 − a, 1 + a].
fn perturbed(m: &TriMesh, a: f64, seed: u64) -> TriMesh {
    let mut r = Rng(seed);
    let mut m = m.clone();
    for p in &mut m.positions {
        let f = 1.0 + a * (2.0 * r.unit() - 1.0);
        *p = Point3::new(p.x * f, p.y * f, p.z * f);
    }
    m
}

fn flat(m: &TriMesh) -> Vec<[f64; 3]> {
    m.positions.iter().map(|p| [p.x, p.y, p.z]).collect()
}

/// Checks the descent against brute force; returns the pairs.
fn check(name: &str, a: &TriMesh, b: &TriMesh) -> Vec<[u32; 2]> {
    let ta = FlintTree3::from_mesh(a).unwrap();
    let tb = FlintTree3::from_mesh(b).unwrap();
    let (pairs, st) = intersect3(&ta, &tb);
    let want = intersect3_brute(&flat(a), &a.triangles, &flat(b), &b.triangles);
    assert_eq!(pairs, want, "{name}: pairs differ from brute force");
    let (hit, _) = intersects3(&ta, &tb);
    assert_eq!(hit, !want.is_empty(), "{name}: detection");
    assert!(
        st.leaf_tests <= st.passed && st.passed <= st.visited,
        "{name}: {st:?}"
    );
    assert_eq!(st.brute_pairs, a.triangles.len() * b.triangles.len());
    // the geometry: every reported point lies (up to rounding) on both triangles
    for &[i, j] in &pairs {
        let ca = a.triangles[i as usize].map(|v| flat(a)[v as usize]);
        let cb = b.triangles[j as usize].map(|v| flat(b)[v as usize]);
        let m = triangle_meet(ca, cb).expect("a reported pair meets");
        assert!(!m.points.is_empty(), "{name}: pair {i},{j} without points");
        for p in &m.points {
            for c in [ca, cb] {
                let d = dist_to_triangle(*p, c);
                assert!(d < 1e-9, "{name}: pair {i},{j}: point {p:?} is {d} off");
            }
        }
    }
    pairs
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// How far `p` is off the closed triangle, relative to its size: the larger of the distance to
/// its plane and the most negative barycentric coordinate (both 0 on the triangle).
fn dist_to_triangle(p: [f64; 3], t: [[f64; 3]; 3]) -> f64 {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let nn = dot(n, n);
    let off_plane = dot(sub(p, t[0]), n).abs() / nn.sqrt();
    let size = dot(sub(t[1], t[0]), sub(t[1], t[0])).sqrt();
    let bary = (0..3)
        .map(|k| dot(cross(sub(t[(k + 1) % 3], p), sub(t[(k + 2) % 3], p)), n) / nn)
        .fold(f64::INFINITY, f64::min);
    (off_plane / size).max(-bary)
}

#[test]
fn perturbed_icospheres_overlapping() {
    let ico = generate::icosphere(3);
    let a = perturbed(&ico, 0.02, 7);
    for (k, d) in [[0.8, 0.3, -0.1], [1.3, 1.0, 0.4], [0.05, 0.0, 0.02]]
        .iter()
        .enumerate()
    {
        let b = shifted(&perturbed(&ico, 0.03, 11 + k as u64), *d);
        let p = check(&format!("icospheres {d:?}"), &a, &b);
        assert!(p.len() > 20, "{d:?}: {}", p.len());
    }
}

#[test]
fn mesh_against_a_translated_copy_and_itself() {
    let m = perturbed(&generate::torus(2.0, 0.6, 28, 14), 0.01, 3);
    let p = check("torus shifted", &m, &shifted(&m, [0.37, 0.11, 0.05]));
    assert!(p.len() > 50);
    // itself: every triangle meets itself and each triangle it shares a vertex with
    let p = check("torus itself", &m, &m);
    let n = m.triangles.len();
    assert!(p.len() >= n * 13, "{} pairs for {n} triangles", p.len());
    for i in 0..n as u32 {
        assert!(p.binary_search(&[i, i]).is_ok(), "triangle {i} with itself");
    }
}

#[test]
fn touching_cubes_share_a_face_an_edge_or_a_vertex() {
    let c = generate::cube();
    let lo = c
        .positions
        .iter()
        .map(|p| p.x)
        .fold(f64::INFINITY, f64::min);
    let hi = c
        .positions
        .iter()
        .map(|p| p.x)
        .fold(f64::NEG_INFINITY, f64::max);
    let s = hi - lo;
    for (name, d, on) in [
        ("face", [s, 0.0, 0.0], 1usize),
        ("edge", [s, s, 0.0], 2),
        ("vertex", [s, s, s], 3),
    ] {
        let b = shifted(&c, d);
        let p = check(name, &c, &b);
        assert!(!p.is_empty(), "{name}: touching cubes meet");
        // every common point lies on the contact: `on` coordinates equal `hi`
        for &[i, j] in &p {
            let ca = c.triangles[i as usize].map(|v| flat(&c)[v as usize]);
            let cb = b.triangles[j as usize].map(|v| flat(&b)[v as usize]);
            for q in triangle_meet(ca, cb).unwrap().points {
                assert!(q[..on].iter().all(|&x| x == hi), "{name}: {q:?}");
            }
        }
        // apart by a hair: nothing
        let gap = shifted(&c, d.map(|x| if x > 0.0 { x * (1.0 + 1e-12) } else { 0.0 }));
        assert!(check(&format!("{name} apart"), &c, &gap).is_empty());
    }
}

#[test]
fn disjoint_meshes_stop_at_the_roots() {
    let a = generate::icosphere(2);
    let b = shifted(&a, [2.5, 0.0, 0.0]);
    assert!(check("disjoint", &a, &b).is_empty());
    let (ta, tb) = (
        FlintTree3::from_mesh(&a).unwrap(),
        FlintTree3::from_mesh(&b).unwrap(),
    );
    let (_, st) = intersect3(&ta, &tb);
    assert_eq!((st.visited, st.passed), (1, 0), "{st:?}");
    // nested without contact: a small sphere inside a large one
    let small = shifted(&perturbed(&a, 0.0, 1), [0.0; 3]);
    let mut big = a.clone();
    for p in &mut big.positions {
        *p = Point3::new(p.x * 3.0, p.y * 3.0, p.z * 3.0);
    }
    assert!(check("nested", &small, &big).is_empty());
}

#[test]
fn coplanar_overlaps() {
    let c = generate::cube();
    let b = shifted(&c, [0.5, 0.25, 0.0]);
    let p = check("coplanar cubes", &c, &b);
    let mut coplanar = 0;
    for &[i, j] in &p {
        let ca = c.triangles[i as usize].map(|v| flat(&c)[v as usize]);
        let cb = b.triangles[j as usize].map(|v| flat(&b)[v as usize]);
        let m = triangle_meet(ca, cb).unwrap();
        if m.coplanar {
            coplanar += 1;
            let z = m.points[0][2];
            assert!(m.points.iter().all(|q| q[2] == z), "{m:?}");
        }
    }
    assert!(coplanar >= 4, "{coplanar} coplanar pairs");
}

#[test]
fn real_mesh_against_a_shifted_copy() {
    let Some(path) = common::data("meshes/bunny_npm.obj") else {
        return;
    };
    let m = morpho::io::read_mesh(&path).unwrap();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in flat(&m) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d = [
        0.23 * (hi[0] - lo[0]),
        0.11 * (hi[1] - lo[1]),
        0.05 * (hi[2] - lo[2]),
    ];
    let p = check("bunny shifted", &m, &shifted(&m, d));
    assert!(p.len() > 100, "{}", p.len());
    // against itself: exactly the brute-force contacts too
    check("bunny itself", &m, &m);
}

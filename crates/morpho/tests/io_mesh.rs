//! Mesh file formats (PLY, OBJ, OFF, STL): round trips, the real meshes in
//! `shared/data/meshes`, hostile and broken input, and a mutation fuzz test.

mod common;
use morpho::geom::{Point3, Vector3};
use morpho::io::{self, obj, off, ply, stl, Encoding};
use morpho::mesh::{Column, PointSet, Property, ScalarKind, TriMesh};
use proptest::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

const ENCODINGS: [Encoding; 3] = [
    Encoding::Ascii,
    Encoding::BinaryLittleEndian,
    Encoding::BinaryBigEndian,
];

/// The real meshes (`shared/data/meshes`).
fn data_dir() -> Option<PathBuf> {
    common::data("meshes")
}

fn ply_bytes(m: &TriMesh, enc: Encoding) -> Vec<u8> {
    let mut b = Vec::new();
    ply::write_mesh(&mut b, m, enc).unwrap();
    b
}
fn obj_bytes(m: &TriMesh) -> Vec<u8> {
    let mut b = Vec::new();
    obj::write(&mut b, m).unwrap();
    b
}
fn off_bytes(m: &TriMesh) -> Vec<u8> {
    let mut b = Vec::new();
    off::write(&mut b, m).unwrap();
    b
}
fn stl_bytes(m: &TriMesh, enc: Encoding) -> Vec<u8> {
    let mut b = Vec::new();
    stl::write(&mut b, m, enc).unwrap();
    b
}

/// A closed torus (genus 1) of `n × m` quads, each split in two triangles.
fn torus(n: u32, m: u32) -> TriMesh {
    let mut pos = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / n as f64,
                std::f64::consts::TAU * j as f64 / m as f64,
            );
            let r = 2.0 + 0.7 * v.cos();
            pos.push(Point3::new(r * u.cos(), r * u.sin(), 0.7 * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..m {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

/// Vertices used by triangles, undirected edges, connected parts (by shared vertices).
fn topo_counts(m: &TriMesh) -> (usize, usize, usize) {
    let n = m.positions.len();
    let mut used = vec![false; n];
    let mut edges: Vec<(u32, u32)> = Vec::with_capacity(3 * m.triangles.len());
    for t in &m.triangles {
        for k in 0..3 {
            used[t[k] as usize] = true;
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for &(a, b) in &edges {
        let (ra, rb) = (find(&mut parent, a as usize), find(&mut parent, b as usize));
        parent[ra] = rb;
    }
    let mut roots = vec![false; n];
    let mut parts = 0;
    for (v, &u) in used.iter().enumerate() {
        if u {
            let r = find(&mut parent, v);
            if !std::mem::replace(&mut roots[r], true) {
                parts += 1;
            }
        }
    }
    (used.iter().filter(|&&u| u).count(), edges.len(), parts)
}

/// Checks that `stl` is `orig` with positions rounded to f32 and corners merged: the used
/// original vertices correspond one to one to the STL vertices (numbered in order of first
/// appearance) and the triangles are the same up to that renaming — so the topology (edges,
/// parts, genus) is exactly preserved.
fn assert_stl_matches(orig: &TriMesh, stl: &TriMesh) {
    assert_eq!(stl.triangles.len(), orig.triangles.len());
    let mut id = vec![u32::MAX; orig.positions.len()];
    let mut next = 0u32;
    for (t, (a, b)) in orig.triangles.iter().zip(&stl.triangles).enumerate() {
        for k in 0..3 {
            let v = a[k] as usize;
            if id[v] == u32::MAX {
                id[v] = next;
                next += 1;
            }
            assert_eq!(id[v], b[k], "triangle {t} corner {k}");
        }
    }
    assert_eq!(stl.positions.len(), next as usize, "STL vertex count");
    for (v, &i) in id.iter().enumerate() {
        if i != u32::MAX {
            let (p, q) = (orig.positions[v], stl.positions[i as usize]);
            let r = |c: f64| c as f32 as f64;
            assert_eq!(Point3::new(r(p.x), r(p.y), r(p.z)), q, "vertex {v}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Round trips on generated meshes

fn with_props(mut m: TriMesh) -> TriMesh {
    let n = m.positions.len();
    let f = m.triangles.len();
    m.normals = Some(
        m.positions
            .iter()
            .map(|p| p.coords.normalize())
            .collect::<Vec<Vector3>>(),
    );
    let kinds = [
        (ScalarKind::I8, -128.0, 127.0),
        (ScalarKind::U8, 0.0, 255.0),
        (ScalarKind::I16, -32768.0, 32767.0),
        (ScalarKind::U16, 0.0, 65535.0),
        (ScalarKind::I32, -2147483648.0, 2147483647.0),
        (ScalarKind::U32, 0.0, 4294967295.0),
    ];
    for (k, (kind, lo, hi)) in kinds.into_iter().enumerate() {
        let vals = |len: usize| {
            (0..len)
                .map(|i| match i % 3 {
                    0 => lo,
                    1 => hi,
                    _ => ((i * 7919 + k) as f64 % (hi - lo + 1.0)) + lo,
                })
                .collect::<Vec<f64>>()
        };
        m.vertex_props.push(Property {
            name: format!("v_{kind:?}"),
            kind,
            values: vals(n),
        });
        m.face_props.push(Property {
            name: format!("f_{kind:?}"),
            kind,
            values: vals(f),
        });
    }
    m.vertex_props.push(Property {
        name: "quality".into(),
        kind: ScalarKind::F32,
        values: (0..n)
            .map(|i| (i as f32 * 0.1f32 - 3.3e-20) as f64)
            .collect(),
    });
    m.vertex_props.push(Property {
        name: "curvature".into(),
        kind: ScalarKind::F64,
        values: (0..n).map(|i| (i as f64).sin() * 1e-200).collect(),
    });
    m.face_props.push(Property {
        name: "area".into(),
        kind: ScalarKind::F64,
        values: (0..f).map(|i| 1.0 / (i as f64 + 3.0)).collect(),
    });
    m
}

#[test]
fn ply_round_trip_with_normals_and_properties_is_exact() {
    let m = with_props(torus(12, 7));
    for enc in ENCODINGS {
        let back = ply::read_mesh(&ply_bytes(&m, enc)).unwrap();
        assert_eq!(back, m, "{enc:?}");
    }
}

#[test]
fn ply_points_round_trip() {
    let pts = PointSet {
        dim: 3,
        coords: vec![0.1, 0.2, 0.3, -1e300, 5e-324, 7.0],
        columns: vec![Column {
            name: "value".into(),
            values: vec![1.5, -2.25],
        }],
    };
    let p2 = PointSet {
        dim: 2,
        coords: vec![0.1, 0.2, -3.0, 4.0, 5.0, 6.0],
        columns: vec![],
    };
    for enc in ENCODINGS {
        for p in [&pts, &p2] {
            let mut b = Vec::new();
            ply::write_points(&mut b, p, enc).unwrap();
            assert_eq!(&ply::read_points(&b).unwrap(), p, "{enc:?}");
        }
    }
    // Points from a mesh file: normals are not columns, other vertex properties are.
    let m = with_props(torus(4, 3));
    let p = ply::read_points(&ply_bytes(&m, Encoding::Ascii)).unwrap();
    assert_eq!(p.len(), m.positions.len());
    assert_eq!(p.columns.len(), m.vertex_props.len());
    assert!(p.column("nx").is_none());
    assert_eq!(p.column("v_U16").unwrap().values, m.vertex_props[3].values);
}

#[test]
fn files_through_the_dispatch_functions() {
    let dir = tempfile::tempdir().unwrap();
    let m = torus(9, 5);
    for name in ["t.ply", "t.obj", "t.off", "t.stl"] {
        let p = dir.path().join(name);
        io::write_mesh(&p, &m, Encoding::default()).unwrap();
        let back = io::read_mesh(&p).unwrap();
        if name.ends_with("stl") {
            assert_stl_matches(&m, &back);
        } else {
            assert_eq!(back, m, "{name}");
        }
    }
    let p = dir.path().join("pts.ply");
    let pts = PointSet::from_points3(&m.positions);
    io::write_points(&p, &pts).unwrap();
    assert_eq!(io::read_points(&p).unwrap(), pts);
    // A planar point set stays 2D, also through `read_any`.
    let p2 = dir.path().join("pts2.ply");
    let flat = PointSet {
        dim: 2,
        coords: vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.5],
        columns: vec![],
    };
    io::write_points(&p2, &flat).unwrap();
    match io::read_any(&p2).unwrap() {
        io::Data::Points(q) => assert_eq!(q, flat),
        other => panic!("expected points, got {other:?}"),
    }
    match io::read_any(&dir.path().join("t.ply")).unwrap() {
        io::Data::Mesh(q) => assert_eq!(q, m),
        other => panic!("expected a mesh, got {other:?}"),
    }
}

fn finite_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>().prop_filter("finite", |x| x.is_finite()),
        -1e3..1e3f64,
        Just(0.0),
        Just(-0.0),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn obj_off_ply_round_trips_are_exact(
        coords in prop::collection::vec(finite_f64(), 9..60),
        seed in any::<u64>(),
    ) {
        let n = coords.len() / 3;
        let positions: Vec<Point3> =
            (0..n).map(|i| Point3::new(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2])).collect();
        let mut s = seed;
        let mut next = || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 33) as u32 % n as u32 };
        let triangles: Vec<[u32; 3]> = (0..n).map(|_| [next(), next(), next()]).collect();
        let m = TriMesh::new(positions, triangles);
        prop_assert_eq!(&obj::read(&obj_bytes(&m)).unwrap(), &m);
        prop_assert_eq!(&off::read(&off_bytes(&m)).unwrap(), &m);
        for enc in ENCODINGS {
            prop_assert_eq!(&ply::read_mesh(&ply_bytes(&m, enc)).unwrap(), &m);
        }
        // ASCII STL keeps f64 values; distinct positions stay distinct vertices.
        let back = stl::read(&stl_bytes(&m, Encoding::Ascii)).unwrap();
        prop_assert_eq!(back.triangles.len(), m.triangles.len());
        for (a, b) in m.triangles.iter().zip(&back.triangles) {
            for k in 0..3 {
                prop_assert_eq!(m.positions[a[k] as usize], back.positions[b[k] as usize]);
            }
        }
    }

    #[test]
    fn stl_binary_round_trip_keeps_topology(n in 3u32..12, m in 3u32..9, scale in 1e-3..1e3f64) {
        let mut t = torus(n, m);
        for p in &mut t.positions {
            *p = Point3::new((p.x * scale) as f32 as f64, (p.y * scale) as f32 as f64, (p.z * scale) as f32 as f64);
        }
        let back = stl::read(&stl_bytes(&t, Encoding::BinaryLittleEndian)).unwrap();
        assert_stl_matches(&t, &back);
        // Torus: V - E + F = 0, one part.
        let (v, e, parts) = topo_counts(&back);
        prop_assert_eq!(v as i64 - e as i64 + back.triangles.len() as i64, 0);
        prop_assert_eq!(parts, 1);
    }
}

// ---------------------------------------------------------------------------------------------
// Real data

/// File, vertices, triangles, vertices used by triangles (from the data README).
const MESHES: [(&str, usize, usize, usize); 7] = [
    ("bunny_npm.obj", 1839, 3674, 1839),
    ("dragon_vrip_res4.obj", 5205, 11102, 5203),
    ("fandisk.obj", 6475, 12946, 6475),
    ("spot.obj", 2930, 5856, 2930),
    ("rocker-arm.obj", 10044, 20088, 10044),
    ("stanford-bunny.obj.gz", 35947, 69451, 34834),
    ("horse.obj.gz", 48485, 96966, 48485),
];

fn check_real_mesh(name: &str, nv: usize, nt: usize, used: usize) {
    let Some(dir) = data_dir() else { return };
    let t0 = Instant::now();
    let mut lap = Instant::now();
    let mut times = Vec::new();
    let mut tick = |what: &str| {
        times.push(format!("{what} {:.0?}", lap.elapsed()));
        lap = Instant::now();
    };
    let m = io::read_mesh(&dir.join(name)).unwrap();
    tick("read");
    assert_eq!(m.positions.len(), nv, "{name} vertices");
    assert_eq!(m.triangles.len(), nt, "{name} triangles");
    let mut is_used = vec![false; m.positions.len()];
    for &v in m.triangles.iter().flatten() {
        is_used[v as usize] = true;
    }
    assert_eq!(
        is_used.iter().filter(|&&u| u).count(),
        used,
        "{name} used vertices"
    );
    tick("topo");
    for enc in ENCODINGS {
        let b = ply_bytes(&m, enc);
        tick("write ply");
        assert_eq!(ply::read_mesh(&b).unwrap(), m, "{name} PLY {enc:?}");
        tick("read ply");
    }
    let b = obj_bytes(&m);
    tick("write obj");
    assert_eq!(obj::read(&b).unwrap(), m, "{name} OBJ");
    tick("read obj");
    let b = off_bytes(&m);
    tick("write off");
    assert_eq!(off::read(&b).unwrap(), m, "{name} OFF");
    tick("read off");
    // ASCII STL is exercised on the smaller meshes only (it is slow to write in debug builds).
    let stl_encodings: &[Encoding] = if nt < 50_000 {
        &[Encoding::BinaryLittleEndian, Encoding::Ascii]
    } else {
        &[Encoding::BinaryLittleEndian]
    };
    for &enc in stl_encodings {
        let b = stl_bytes(&m, enc);
        tick("write stl");
        let s = stl::read(&b).unwrap();
        tick("read stl");
        assert_eq!(s.triangles.len(), nt, "{name} STL {enc:?} triangles");
        assert_eq!(s.positions.len(), used, "{name} STL {enc:?} vertices");
        if enc == Encoding::BinaryLittleEndian {
            assert_stl_matches(&m, &s);
            tick("stl check");
        }
    }
    eprintln!("{name}: {:?} total; {}", t0.elapsed(), times.join(", "));
}

#[test]
fn real_small_meshes() {
    for (name, nv, nt, used) in &MESHES[..5] {
        check_real_mesh(name, *nv, *nt, *used);
    }
}

#[test]
fn real_stanford_bunny() {
    let (name, nv, nt, used) = MESHES[5];
    check_real_mesh(name, nv, nt, used);
}

#[test]
fn real_horse() {
    let (name, nv, nt, used) = MESHES[6];
    check_real_mesh(name, nv, nt, used);
}

// ---------------------------------------------------------------------------------------------
// Bad input

fn err(r: Result<TriMesh, morpho::Error>) -> String {
    match r {
        Ok(m) => panic!(
            "expected an error, got a mesh with {} vertices",
            m.positions.len()
        ),
        Err(e) => e.to_string(),
    }
}

fn assert_has(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "'{msg}' should mention '{p}'");
    }
}

fn triangle() -> TriMesh {
    TriMesh::new(
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        ],
        vec![[0, 1, 2]],
    )
}

#[test]
fn empty_files_are_errors() {
    assert!(ply::read_mesh(b"").is_err());
    assert!(ply::read_points(b"").is_err());
    assert!(obj::read(b"").is_err());
    assert!(off::read(b"").is_err());
    assert!(stl::read(b"").is_err());
    assert!(obj::read(b"\n\n# only comments\n").is_err());
    assert!(off::read(b"# nothing\n").is_err());
}

#[test]
fn truncated_binary_files_name_the_byte() {
    // With properties (general record decoder) and without (fixed-size / index-list fast paths).
    for (enc, m) in [Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian]
        .into_iter()
        .flat_map(|e| [(e, with_props(triangle())), (e, triangle())])
    {
        let b = ply_bytes(&m, enc);
        let header = b.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        let e = err(ply::read_mesh(&b[..b.len() - 3]));
        assert_has(&e, &["byte", "truncated"]);
        for cut in header..b.len() {
            let e = err(ply::read_mesh(&b[..cut]));
            assert!(e.contains("byte"), "{e}");
        }
        for cut in 0..header {
            assert!(ply::read_mesh(&b[..cut]).is_err());
        }
    }
    let b = ply_bytes(&triangle(), Encoding::Ascii);
    let e = err(ply::read_mesh(&b[..b.len() - 8]));
    assert_has(&e, &["line", "face 0"]);
    let s = stl_bytes(&triangle(), Encoding::BinaryLittleEndian);
    let e = err(stl::read(&s[..s.len() - 1]));
    assert_has(&e, &["byte 84", "truncated"]);
    let e = err(stl::read(&s[..90]));
    assert_has(&e, &["byte 84"]);
}

#[test]
fn absurd_counts_fail_fast_without_allocating() {
    let t = Instant::now();
    for fmt in ["binary_little_endian", "binary_big_endian", "ascii"] {
        for (el, props) in [
            (
                "vertex",
                "property float x\nproperty float y\nproperty float z\n",
            ),
            ("face", "property list uchar int vertex_indices\n"),
            ("edge", "property int a\n"),
        ] {
            let mut b =
                format!(
                "ply\nformat {fmt} 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
                 property float z\n",
                if el == "vertex" { 1_000_000_000_000u64 } else { 0 }
            );
            if el != "vertex" {
                b.push_str(&format!("element {el} 1000000000000\n{props}"));
            }
            b.push_str("end_header\n0 0 0 0 0 0 0 0 0 0 0 0\n");
            let e = err(ply::read_mesh(b.as_bytes()));
            assert_has(&e, &["1000000000000", "left"]);
            assert!(ply::read_points(b.as_bytes()).is_err() || el != "vertex");
        }
    }
    let e = err(off::read(b"OFF\n1000000000000 1000000000000 0\n0 0 0\n"));
    assert_has(&e, &["line 2", "1000000000000"]);
    let e = err(off::read(
        b"OFF\n3 18446744073709551615 0\n0 0 0\n1 0 0\n0 1 0\n",
    ));
    assert_has(&e, &["line 2"]);
    let mut s = vec![0u8; 84];
    s[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = err(stl::read(&s));
    assert_has(&e, &["truncated", "4294967295"]);
    assert!(t.elapsed().as_secs_f64() < 2.0, "took {:?}", t.elapsed());
}

#[test]
fn face_index_out_of_range_names_the_face() {
    let mut m = triangle();
    m.triangles.push([0, 1, 2]);
    for enc in ENCODINGS {
        let mut b = ply_bytes(&m, enc);
        // Patch the last index of face 1 to 3.
        let n = b.len();
        match enc {
            Encoding::Ascii => {
                b[n - 2] = b'3';
            }
            Encoding::BinaryLittleEndian => b[n - 4..].copy_from_slice(&3i32.to_le_bytes()),
            Encoding::BinaryBigEndian => b[n - 4..].copy_from_slice(&3i32.to_be_bytes()),
        }
        let e = err(ply::read_mesh(&b));
        assert_has(&e, &["face 1", "vertex 3"]);
    }
    let e = err(obj::read(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n"));
    assert_has(&e, &["line 5", "face 1", "vertex 4"]);
    let e = err(obj::read(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"));
    assert_has(&e, &["line 4"]);
    let e = err(off::read(
        b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n",
    ));
    assert_has(&e, &["line 7", "face 1", "vertex 3"]);
}

#[test]
fn non_finite_coordinates_name_the_vertex() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut m = triangle();
        m.positions.push(Point3::new(0.0, 0.0, 1.0));
        // Build files by hand since the writers refuse non-finite meshes.
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 {bad} 0\nf 1 2 3\n");
        assert_has(&err(obj::read(text.as_bytes())), &["line 3", "vertex 2"]);
        let text = format!("OFF\n3 1 0\n0 0 0\n1 0 0\n0 {bad} 0\n3 0 1 2\n");
        assert_has(&err(off::read(text.as_bytes())), &["line 5", "vertex 2"]);
        let text = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nend_header\n0 0 0\n1 0 0\n0 {bad} 0\n"
        );
        assert_has(
            &err(ply::read_mesh(text.as_bytes())),
            &["line 10", "vertex 2"],
        );
        assert!(ply::read_points(text.as_bytes()).is_err());
        let mut b = ply_bytes(&m, Encoding::BinaryLittleEndian);
        let start = b.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        let at = start + 2 * 24 + 8;
        b[at..at + 8].copy_from_slice(&bad.to_le_bytes());
        assert_has(
            &err(ply::read_mesh(&b)),
            &[&format!("byte {}", start + 48), "vertex 2"],
        );
        let mut s = stl_bytes(&triangle(), Encoding::BinaryLittleEndian);
        s[84 + 12 + 12 + 4..84 + 12 + 12 + 8].copy_from_slice(&(bad as f32).to_le_bytes());
        assert_has(&err(stl::read(&s)), &["triangle 0", "corner 1"]);
    }
}

#[test]
fn non_utf8_text_is_an_error() {
    assert_has(
        &err(obj::read(b"v 0 0 0\nv 1 0 0\nv 0 1 \xc3\x28\nf 1 2 3\n")),
        &["line 3", "UTF-8"],
    );
    assert_has(
        &err(off::read(b"OFF\n3 1 0\n0 0 0\n1 \xff 0\n0 1 0\n3 0 1 2\n")),
        &["line 4", "UTF-8"],
    );
    let mut p = ply_bytes(&triangle(), Encoding::Ascii);
    let n = p.len();
    p[n - 3] = 0xfe;
    assert_has(&err(ply::read_mesh(&p)), &["UTF-8"]);
    assert_has(
        &err(ply::read_mesh(
            b"ply\nformat ascii 1.0\nelement vert\xe9x 3\nend_header\n",
        )),
        &["line 3", "UTF-8"],
    );
    let s =
        "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 \u{0}\n";
    assert!(stl::read(s.as_bytes()).is_err());
    let mut s = stl_bytes(&triangle(), Encoding::Ascii);
    let k = s.len() - 20;
    s[k] = 0xff;
    assert!(stl::read(&s).is_err());
}

#[test]
fn faces_with_fewer_than_three_corners_are_errors() {
    assert_has(
        &err(obj::read(b"v 0 0 0\nv 1 0 0\nf 1 2\n")),
        &["line 3", "2 corners"],
    );
    assert_has(
        &err(obj::read(b"v 0 0 0\nv 1 0 0\nf\n")),
        &["line 3", "0 corners"],
    );
    assert_has(
        &err(off::read(b"OFF\n2 1 0\n0 0 0\n1 0 0\n2 0 1\n")),
        &["line 5", "2 corners"],
    );
    let p = b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
              property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
              0 0 0\n1 0 0\n2 0 1\n";
    assert_has(&err(ply::read_mesh(p)), &["line 12", "face 0", "2 corners"]);
    let s = "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n";
    assert!(stl::read(s.as_bytes()).is_err());
}

#[test]
fn malformed_headers_are_errors() {
    let bad: [&[u8]; 9] = [
        b"ply\n",
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n",
        b"ply\nformat ascii 2.0\nend_header\n",
        b"ply\nformat fancy 1.0\nend_header\n",
        b"ply\nproperty float x\nend_header\n",
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
        b"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
        b"ply\nformat ascii 1.0\nelement vertex 0\nelement vertex 0\nend_header\n",
        b"PLY\nformat ascii 1.0\nend_header\n",
    ];
    for b in bad {
        assert!(ply::read_mesh(b).is_err(), "{}", String::from_utf8_lossy(b));
    }
    assert!(stl::write(&mut Vec::new(), &triangle(), Encoding::BinaryBigEndian).is_err());
    // Writers refuse what the format cannot hold.
    let mut m = triangle();
    m.vertex_props.push(Property {
        name: "red".into(),
        kind: ScalarKind::U8,
        values: vec![0.0, 256.0, 1.0],
    });
    assert!(ply::write_mesh(&mut Vec::new(), &m, Encoding::Ascii).is_err());
    m.vertex_props[0].values[1] = 2.0;
    m.vertex_props[0].name = "has space".into();
    assert!(ply::write_mesh(&mut Vec::new(), &m, Encoding::Ascii).is_err());
}

// ---------------------------------------------------------------------------------------------
// Fuzz: mutated valid files never panic

fn seeds() -> Vec<(u8, Vec<u8>)> {
    let mut m = with_props(torus(4, 3));
    m.triangles.truncate(10);
    for p in &mut m.face_props {
        p.values.truncate(10);
    }
    let plain = torus(3, 3);
    let quads =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -1/2/1 -2 -3\n";
    let noff = "NCOFF\n4 2 0\n0 0 0 0 0 1 1 0 0\n1 0 0 0 0 1 1 0 0\n1 1 0 0 0 1 1 0 0\n0 1 0 0 0 1 1 0 0\n4 0 1 2 3 1 1 1\n3 0 1 2\n";
    vec![
        (0, ply_bytes(&m, Encoding::Ascii)),
        (0, ply_bytes(&m, Encoding::BinaryLittleEndian)),
        (0, ply_bytes(&m, Encoding::BinaryBigEndian)),
        (1, obj_bytes(&plain)),
        (1, quads.as_bytes().to_vec()),
        (2, off_bytes(&plain)),
        (2, noff.as_bytes().to_vec()),
        (3, stl_bytes(&plain, Encoding::BinaryLittleEndian)),
        (3, stl_bytes(&plain, Encoding::Ascii)),
    ]
}

fn read_any(fmt: u8, b: &[u8]) {
    let _ = match fmt {
        0 => {
            let _ = ply::read_points(b);
            ply::read_mesh(b)
        }
        1 => obj::read(b),
        2 => off::read(b),
        _ => stl::read(b),
    }
    .and_then(|m| m.validate().map(|_| m).map_err(morpho::Error::from));
}

#[derive(Debug, Clone)]
enum Mutation {
    Set(usize, u8),
    Digit(usize, u8),
    Insert(usize, u8),
    Delete(usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Set(i, b)),
        (any::<usize>(), b'0'..=b'9').prop_map(|(i, b)| Mutation::Digit(i, b)),
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Insert(i, b)),
        any::<usize>().prop_map(Mutation::Delete),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

/// 256 cases, or `IO_MESH_FUZZ_CASES` for a longer run.
fn fuzz_cases() -> u32 {
    std::env::var("IO_MESH_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(fuzz_cases()))]

    #[test]
    fn mutated_files_never_panic(which in 0usize..9, muts in prop::collection::vec(mutation(), 1..6)) {
        let (fmt, mut b) = seeds().swap_remove(which);
        for m in muts {
            let n = b.len().max(1);
            match m {
                Mutation::Set(i, v) => { if let Some(x) = b.get_mut(i % n) { *x = v } }
                Mutation::Digit(i, v) => { if let Some(x) = b.get_mut(i % n) { *x = v } }
                Mutation::Insert(i, v) => b.insert((i % n).min(b.len()), v),
                Mutation::Delete(i) => { if !b.is_empty() { b.remove(i % n); } }
                Mutation::Truncate(i) => b.truncate(i % n),
            }
        }
        let t = Instant::now();
        read_any(fmt, &b);
        prop_assert!(t.elapsed().as_secs_f64() < 1.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Parse speed (run with `cargo test --release --test io_mesh -- --ignored --nocapture`)

#[test]
#[ignore]
fn parse_speed() {
    let m = match data_dir() {
        Some(d) => io::read_mesh(&d.join("horse.obj.gz")).unwrap(),
        None => torus(300, 200),
    };
    // CPU time of this thread (Linux), so that a busy machine does not distort the figures;
    // wall-clock time elsewhere.
    fn cpu_seconds() -> Option<f64> {
        let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
        Some(s.split_whitespace().next()?.parse::<f64>().ok()? * 1e-9)
    }
    let rate = |name: &str, bytes: &[u8], f: &dyn Fn(&[u8])| {
        f(bytes);
        let (c0, t0) = (cpu_seconds(), Instant::now());
        let mut reps = 0;
        let s = loop {
            f(bytes);
            reps += 1;
            let s = match (c0, cpu_seconds()) {
                (Some(a), Some(b)) => b - a,
                _ => t0.elapsed().as_secs_f64(),
            };
            if s >= 0.3 {
                break s / reps as f64;
            }
        };
        eprintln!(
            "{name:>32}: {:>9} bytes, {:>7.2} ms, {:>7.1} MB/s",
            bytes.len(),
            s * 1e3,
            bytes.len() as f64 / s / 1e6
        );
    };
    let obj = obj_bytes(&m);
    rate("OBJ", &obj, &|b| {
        obj::read(b).unwrap();
    });
    let off = off_bytes(&m);
    rate("OFF", &off, &|b| {
        off::read(b).unwrap();
    });
    for enc in ENCODINGS {
        let b = ply_bytes(&m, enc);
        rate(&format!("PLY {enc:?}"), &b, &|b| {
            ply::read_mesh(b).unwrap();
        });
        let vertex_bytes = b.len() - 13 * m.triangles.len();
        rate(&format!("PLY vertices {enc:?}"), &b[..vertex_bytes], &|b| {
            ply::read_points(b).unwrap();
        });
    }
    for enc in [Encoding::BinaryLittleEndian, Encoding::Ascii] {
        let b = stl_bytes(&m, enc);
        rate(&format!("STL {enc:?}"), &b, &|b| {
            stl::read(b).unwrap();
        });
    }
}

//! The 3D flintstone tree (V §7.3, Alg. 7.2): structure, the containment invariant, the
//! boundary-equals-paths invariant that makes the queries exact, hierarchical point-in-mesh
//! against brute force (including points on vertices, edges and faces and rays through
//! vertices), approximations, and refusals of bad input.
mod common;
use common::{real_mesh as real, XorShift as Rng};
use morpho::flint::{contains_brute3, FlintError, FlintTree3, Target};
use morpho::geom::Point3;
use morpho::mesh::{generate, TriMesh};
use std::collections::HashMap;

fn meshes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("cube", generate::cube()),
        ("icosphere3", generate::icosphere(3)),
        (
            "uv_sphere",
            generate::uv_sphere(Point3::new(0.1, -0.2, 0.3), 1.5, 16, 24),
        ),
        ("torus", generate::torus(2.0, 0.6, 32, 14)),
        ("multi_torus3", generate::multi_torus(3)),
    ]
}

fn check_structure(name: &str, m: &TriMesh, t: &FlintTree3) {
    // every input triangle is exactly one leaf
    let mut seen = vec![0u32; m.triangles.len()];
    for nd in &t.nodes {
        if nd.is_leaf() {
            seen[nd.triangle as usize] += 1;
            assert_eq!(nd.corners, m.triangles[nd.triangle as usize], "{name}");
            assert!(nd.children.is_empty());
        } else {
            assert!(
                !nd.children.is_empty(),
                "{name}: inner node without children"
            );
            assert!(
                nd.children.len() <= 4 || nd.patched,
                "{name}: {} children",
                nd.children.len()
            );
        }
    }
    assert!(
        seen.iter().all(|&c| c == 1),
        "{name}: leaves {:?}",
        seen.iter().filter(|&&c| c != 1).count()
    );
    assert_eq!(t.leaf_count(), m.triangles.len());
    let pos = t.positions();
    for (id, nd) in t.nodes.iter().enumerate() {
        let Some(stone) = &nd.stone else { continue };
        let id = id as u32;
        let tris = t.node_triangles(id);
        assert!(
            tris.len() >= 2,
            "{name}: inner node of {} triangles",
            tris.len()
        );
        // children partition the node's triangles
        let sum: usize = nd.children.iter().map(|&c| t.node_triangles(c).len()).sum();
        assert_eq!(sum, tris.len(), "{name}");
        let paths = t.node_paths(id);
        // paths run corner to corner
        for (k, p) in paths.iter().enumerate() {
            assert_eq!(p[0], nd.corners[k], "{name}");
            assert_eq!(*p.last().unwrap(), nd.corners[(k + 1) % 3], "{name}");
        }
        // the containment invariant (exact), for the open polyhedron's and the paths' vertices
        let mut verts: Vec<u32> = tris
            .iter()
            .flat_map(|&tr| m.triangles[tr as usize])
            .collect();
        verts.extend(paths.iter().flatten());
        for &v in &verts {
            assert!(
                stone.contains(pos, pos[v as usize]),
                "{name}: node {id} ({:?}) misses vertex {v}",
                stone.kind
            );
        }
        // ∂(triangles) = the three paths (mod 2), checked independently of the builder
        let mut odd: HashMap<(u32, u32), u32> = HashMap::new();
        let key = |a: u32, b: u32| (a.min(b), a.max(b));
        for &tr in tris {
            let [a, b, c] = m.triangles[tr as usize];
            for (x, y) in [(a, b), (b, c), (c, a)] {
                *odd.entry(key(x, y)).or_default() += 1;
            }
        }
        for p in &paths {
            for w in p.windows(2) {
                *odd.entry(key(w[0], w[1])).or_default() += 1;
            }
        }
        // interior edges count 2, boundary edges once + once on a path
        let bad = odd.values().filter(|&&c| c % 2 == 1).count();
        assert_eq!(
            bad, 0,
            "{name}: node {id}: boundary differs from its paths on {bad} edges"
        );
    }
}

#[test]
fn generated_meshes_structure_and_invariants() {
    for (name, m) in meshes() {
        let t = FlintTree3::from_mesh(&m).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_structure(name, &m, &t);
        eprintln!(
            "{name}: {} triangles, {} nodes, depth {}, fallbacks {} (root {}), kinds {:?}",
            m.triangles.len(),
            t.node_count(),
            t.depth(),
            t.fallbacks(),
            t.root.patched,
            t.kind_counts()
        );
    }
}

/// Queries: random in the box (enlarged), every vertex, edge midpoints, face centroids, and
/// points whose ray (+x) or oracle ray (+z) passes exactly through a vertex.
fn queries(m: &TriMesh, n_random: usize, rng: &mut Rng) -> Vec<[f64; 3]> {
    let b = m.bbox();
    let e = b.extent();
    let mut q = Vec::new();
    for _ in 0..n_random {
        q.push(std::array::from_fn(|k| {
            b.min[k] - 0.1 * e[k] + 1.2 * e[k] * rng.unit()
        }));
    }
    let p = |v: u32| {
        let x = m.positions[v as usize];
        [x.x, x.y, x.z]
    };
    let nv = m.positions.len();
    let nt = m.triangles.len();
    for _ in 0..n_random / 10 {
        let v = p(rng.below(nv) as u32);
        q.push(v);
        let [a, bb, c] = m.triangles[rng.below(nt)].map(p);
        q.push(std::array::from_fn(|k| 0.5 * (a[k] + bb[k])));
        q.push(std::array::from_fn(|k| (a[k] + bb[k] + c[k]) / 3.0));
        let s = b.min[0] - 0.1 * e[0] + 1.2 * e[0] * rng.unit();
        q.push([s, v[1], v[2]]); // +x ray through a vertex
        let s = b.min[2] - 0.1 * e[2] + 1.2 * e[2] * rng.unit();
        q.push([v[0], v[1], s]); // +z ray through a vertex
        q.push([s, a[1], 0.5 * (a[2] + bb[2])]);
    }
    q
}

fn compare(name: &str, m: &TriMesh, t: &FlintTree3, q: &[[f64; 3]]) -> [usize; 3] {
    let pos: Vec<[f64; 3]> = m.positions.iter().map(|p| [p.x, p.y, p.z]).collect();
    let pts: Vec<Point3> = q.iter().map(|x| Point3::new(x[0], x[1], x[2])).collect();
    let got = t.contains_batch(&pts).unwrap();
    let mut counts = [0usize; 3];
    for (i, x) in q.iter().enumerate() {
        let want = contains_brute3(&pos, &m.triangles, *x);
        assert_eq!(got[i], want, "{name}: query {i} {x:?}");
        counts[want as usize] += 1;
    }
    counts
}

#[test]
fn queries_equal_brute_force_on_generated_meshes() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    let mut total = 0;
    for (name, m) in meshes() {
        let t = FlintTree3::from_mesh(&m).unwrap();
        let q = queries(&m, 20_000, &mut rng);
        let c = compare(name, &m, &t, &q);
        total += q.len();
        eprintln!("{name}: {} queries: outside/inside/boundary {c:?}", q.len());
        assert!(c[1] > 0 && c[0] > 0 && c[2] > 0, "{name}: {c:?}");
    }
    assert!(total >= 100_000);
}

#[test]
fn real_meshes_structure_and_queries() {
    let mut rng = Rng(12345);
    for (name, n) in [
        ("bunny_npm.obj", 5000),
        ("spot.obj", 5000),
        ("rocker-arm.obj", 1500),
        ("horse.obj.gz", 600),
    ] {
        let Some(m) = real(name) else {
            eprintln!("skipping {name}: not found");
            continue;
        };
        let t0 = std::time::Instant::now();
        let t = FlintTree3::from_mesh(&m).unwrap_or_else(|e| panic!("{name}: {e}"));
        let build = t0.elapsed();
        check_structure(name, &m, &t);
        let q = queries(&m, n, &mut rng);
        let c = compare(name, &m, &t, &q);
        // the walk descends only where flintstones do not decide: far fewer pieces than
        // the brute force's triangles
        let visits: usize = q
            .iter()
            .map(|x| t.locate_counted(Point3::new(x[0], x[1], x[2])).unwrap().1)
            .sum();
        let mean = visits as f64 / q.len() as f64;
        assert!(
            mean < 0.05 * m.triangles.len() as f64,
            "{name}: {mean} nodes per query"
        );
        eprintln!(
            "{name}: {} triangles, build {build:?}, {} nodes, depth {}, fallbacks {}, kinds {:?}; {} queries {c:?}, mean visits {mean:.1}",
            m.triangles.len(),
            t.node_count(),
            t.depth(),
            t.fallbacks(),
            t.kind_counts(),
            q.len()
        );
    }
}

#[test]
fn approximations() {
    let m = generate::icosphere(3);
    let t = FlintTree3::from_mesh(&m).unwrap();
    let l0 = t.approximate(Target::Level(0)).unwrap();
    assert_eq!(l0.triangles.len(), 2);
    assert_eq!(l0.triangles[0], t.root.corners);
    // the complete tree reproduces the input
    let full = t.approximate(Target::Error(0.0)).unwrap();
    let mut a: Vec<[u32; 3]> = full.triangles.clone();
    let mut b = m.triangles.clone();
    a.sort_unstable();
    b.sort_unstable();
    assert_eq!(a, b);
    assert_eq!(full.e5, 0.0);
    // level counts grow, adaptive counts shrink with ε and meet their bound; cracks (edges
    // of odd multiplicity) are counted: none at level 0, few where a side was split on one
    // side only
    let mut last = 0;
    for l in 0..14 {
        let ap = t.approximate(Target::Level(l)).unwrap();
        assert!(ap.triangles.len() + ap.dropped >= last);
        last = ap.triangles.len() + ap.dropped;
        let mut mult: HashMap<(u32, u32), u32> = HashMap::new();
        for &[a, b, c] in &ap.triangles {
            for (x, y) in [(a, b), (b, c), (c, a)] {
                *mult.entry((x.min(y), x.max(y))).or_default() += 1;
            }
        }
        let odd = mult.values().filter(|&&k| k % 2 == 1).count();
        eprintln!(
            "level {l}: {} triangles ({} dropped), {odd} crack edges of {}, e5 {:.4}",
            ap.triangles.len(),
            ap.dropped,
            mult.len(),
            ap.e5
        );
        if l == 0 {
            assert_eq!(odd, 0);
        }
    }
    let mut last = usize::MAX;
    for eps in [0.0, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0] {
        let ap = t.approximate(Target::Error(eps)).unwrap();
        let n = ap.triangles.len() + ap.dropped;
        assert!(n <= last, "ε {eps}: {n} > {last}");
        last = n;
        assert!(ap.e5 <= eps, "ε {eps}: e5 {}", ap.e5);
        assert!(ap.e2 <= ap.e1 + 1e-12);
        // every unrefined inner node is within ε
        for &id in &ap.nodes {
            assert!(t.nodes[id as usize].error() <= eps);
        }
    }
    let c = t.approximate(Target::Count(100)).unwrap();
    assert!(c.triangles.len() + c.dropped >= 100);
    let (mesh, map) = c.to_mesh(&t);
    assert_eq!(mesh.triangles.len(), c.triangles.len());
    assert!(map.windows(2).all(|w| w[0] < w[1]), "input order");
    assert!(t.approximate(Target::Error(f64::NAN)).is_err());
    assert!(t.approximate(Target::Count(0)).is_err());
}

#[test]
fn bad_input_is_a_typed_error() {
    let cube = generate::cube();
    let e = |pos: &[Point3], tris: &[[u32; 3]]| FlintTree3::new(pos, tris).unwrap_err();
    assert!(matches!(e(&cube.positions, &[]), FlintError::EmptyMesh));
    // open: one triangle missing
    let open = &cube.triangles[1..];
    assert!(matches!(
        e(&cube.positions, open),
        FlintError::OpenMesh { .. }
    ));
    // index out of range
    let mut bad = cube.triangles.clone();
    bad[0][1] = 99;
    assert!(matches!(
        e(&cube.positions, &bad),
        FlintError::VertexOutOfRange { .. }
    ));
    // NaN
    let mut nan = cube.positions.clone();
    nan[0].x = f64::NAN;
    assert!(matches!(
        e(&nan, &cube.triangles),
        FlintError::NonFinite { .. }
    ));
    // degenerate: repeated vertex, collinear corners
    let mut rep = cube.triangles.clone();
    rep[0][1] = rep[0][0];
    assert!(matches!(
        e(&cube.positions, &rep),
        FlintError::DegenerateTriangle { triangle: 0 }
    ));
    let line = [
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(2.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
    ];
    assert!(matches!(
        e(&line, &[[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]]),
        FlintError::DegenerateTriangle { triangle: 0 }
    ));
    // inconsistently oriented: one triangle flipped
    let mut flip = cube.triangles.clone();
    flip[0].swap(1, 2);
    assert!(matches!(
        e(&cube.positions, &flip),
        FlintError::InconsistentOrientation
    ));
    // non-manifold: two tetrahedra sharing an edge (four triangles on it)
    let tet = generate::tetrahedron();
    let mut pos = tet.positions.clone();
    let mut tris = tet.triangles.clone();
    let [a, b] = [tris[0][0], tris[0][1]];
    let off = pos.len() as u32;
    for p in &tet.positions {
        pos.push(Point3::new(p.x + 5.0, p.y, p.z));
    }
    for tr in &tet.triangles {
        tris.push(tr.map(|v| {
            if v == a {
                a
            } else if v == b {
                b
            } else {
                v + off
            }
        }));
    }
    let err = e(&pos, &tris);
    assert!(
        matches!(
            err,
            FlintError::NonManifoldEdge { .. } | FlintError::NonManifoldVertex { .. }
        ),
        "{err}"
    );
    // a query with NaN
    let t = FlintTree3::from_mesh(&cube).unwrap();
    assert!(matches!(
        t.contains(Point3::new(f64::NAN, 0.0, 0.0)),
        Err(FlintError::NonFiniteQuery)
    ));
    assert!(FlintTree3::with_min_angle(&cube.positions, &cube.triangles, 75.0).is_err());
}

#[test]
fn two_parts_and_scaled_coordinates() {
    // two disjoint spheres: the root falls back to disc patches, queries stay exact
    let a = generate::icosphere(2);
    let mut pos = a.positions.clone();
    let mut tris = a.triangles.clone();
    let off = pos.len() as u32;
    pos.extend(a.positions.iter().map(|p| Point3::new(p.x + 3.0, p.y, p.z)));
    tris.extend(a.triangles.iter().map(|t| t.map(|v| v + off)));
    let m = TriMesh::new(pos, tris);
    let t = FlintTree3::from_mesh(&m).unwrap();
    check_structure("two spheres", &m, &t);
    let mut rng = Rng(7);
    let q = queries(&m, 5000, &mut rng);
    let c = compare("two spheres", &m, &t, &q);
    assert!(c[1] > 0);
    // scaled coordinates: exact within the predicates' range (filters off beyond 1e±150);
    // beyond it (1e±200) a typed error or an answer, never a panic
    let torus = generate::torus(2.0, 0.6, 16, 8);
    for s in [1e-30, 1e30, 1e-200, 1e200] {
        let m2 = TriMesh::new(
            torus
                .positions
                .iter()
                .map(|p| Point3::from(p.coords * s))
                .collect(),
            torus.triangles.clone(),
        );
        let q = queries(&m2, 2000, &mut rng);
        match FlintTree3::from_mesh(&m2) {
            Ok(t2) if (1e-100..1e100).contains(&s) => {
                check_structure("scaled torus", &m2, &t2);
                compare("scaled torus", &m2, &t2, &q);
            }
            Ok(t2) => {
                let pts: Vec<Point3> = q.iter().map(|x| Point3::new(x[0], x[1], x[2])).collect();
                assert_eq!(t2.contains_batch(&pts).unwrap().len(), q.len());
            }
            Err(e) => assert!(!(1e-100..=1e100).contains(&s), "{s}: {e}"),
        }
    }
}

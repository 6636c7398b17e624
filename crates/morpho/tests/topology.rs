//! Topology of triangle meshes (Hamann 1991 §3.3, Def. 5.14): generated meshes with known answers,
//! brute-force oracles straight from the definitions, property tests, and the real meshes of
//! /work/shared/data (section 2 of its README gives their counts).

mod common;
use morpho::geom::Point3;
use morpho::mesh::{analyze_topology, orient_consistently, Topology};
use morpho::mesh::{generate, TriMesh};
use morpho::util::NONE;
use proptest::prelude::*;
use std::collections::{BTreeMap, BTreeSet};

fn merge(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let off = a.positions.len() as u32;
    let mut m = a.clone();
    m.positions.extend_from_slice(&b.positions);
    m.triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + off)));
    m
}

fn translate(m: &TriMesh, d: [f64; 3]) -> TriMesh {
    let mut m = m.clone();
    for p in m.positions.iter_mut() {
        *p += nalgebra::Vector3::new(d[0], d[1], d[2]);
    }
    m
}

/// Invariants that hold for every mesh.
fn check_invariants(m: &TriMesh, t: &Topology) {
    let nt = m.triangles.len();
    assert_eq!(t.neighbors.len(), nt);
    assert_eq!(t.part_of_triangle.len(), nt);
    // Every boundary edge lies in exactly one loop or open chain.
    let mut seen = BTreeMap::new();
    for l in &t.boundary_loops {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            *seen.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    for c in &t.open_boundary_chains {
        assert_ne!(c.first(), c.last());
        for w in c.windows(2) {
            *seen.entry((w[0].min(w[1]), w[0].max(w[1]))).or_insert(0) += 1;
        }
    }
    let oracle = brute_edges(m);
    let boundary: BTreeSet<_> = oracle
        .iter()
        .filter(|(_, v)| v.len() == 1)
        .map(|(k, _)| *k)
        .collect();
    assert_eq!(seen.len(), boundary.len());
    assert!(seen.values().all(|&c| c == 1), "edge in two loops");
    assert!(seen.keys().all(|k| boundary.contains(k)));
    assert_eq!(t.num_boundary_edges, boundary.len());
    assert_eq!(t.boundary_loop_lengths.len(), t.boundary_loops.len());
    // Part sums.
    assert_eq!(
        t.parts.iter().map(|p| p.triangles).sum::<usize>(),
        nt - t.degenerate_triangles.len()
    );
    assert_eq!(t.parts.iter().map(|p| p.edges).sum::<usize>(), t.num_edges);
    assert_eq!(
        t.parts.iter().map(|p| p.boundary_loops).sum::<usize>(),
        t.boundary_loops.len()
    );
}

/// Undirected edge → triangles containing it (non-degenerate triangles only), by brute force.
fn brute_edges(m: &TriMesh) -> BTreeMap<(u32, u32), Vec<usize>> {
    let mut e: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    for (t, tri) in m.triangles.iter().enumerate() {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            continue;
        }
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            e.entry((a.min(b), a.max(b))).or_default().push(t);
        }
    }
    e
}

/// Alg. 3.1 literally: O(n²) comparison of every pair of triangles.
fn brute_neighbors(m: &TriMesh) -> Vec<[u32; 3]> {
    let tris = &m.triangles;
    let deg = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    (0..tris.len())
        .map(|i| {
            let mut out = [NONE; 3];
            if deg(&tris[i]) {
                return out;
            }
            for k in 0..3 {
                let (a, b) = (tris[i][k], tris[i][(k + 1) % 3]);
                let others: Vec<usize> = (0..tris.len())
                    .filter(|&j| j != i && !deg(&tris[j]))
                    .filter(|&j| tris[j].contains(&a) && tris[j].contains(&b))
                    .collect();
                if others.len() == 1 {
                    out[k] = others[0] as u32;
                }
            }
            out
        })
        .collect()
}

/// Connected parts by brute force: repeatedly merge labels of triangles sharing an edge.
fn brute_parts(m: &TriMesh) -> usize {
    let e = brute_edges(m);
    let mut label: Vec<usize> = (0..m.triangles.len()).collect();
    loop {
        let mut changed = false;
        for ts in e.values() {
            let min = ts.iter().map(|&t| label[t]).min().unwrap();
            for &t in ts {
                if label[t] != min {
                    label[t] = min;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let used: BTreeSet<usize> = e.values().flatten().map(|&t| label[t]).collect();
    used.len()
}

/// Non-manifold vertices from the definition: the triangles at v, joined when they share an
/// edge (v, w) that has exactly two triangles, form more than one group; or v is on an edge with
/// more than two triangles.
fn brute_non_manifold_vertices(m: &TriMesh) -> Vec<u32> {
    let e = brute_edges(m);
    let nv = m.positions.len() as u32;
    let mut out = Vec::new();
    for v in 0..nv {
        let at: Vec<usize> = e
            .iter()
            .filter(|(k, _)| k.0 == v || k.1 == v)
            .flat_map(|(_, ts)| ts.iter().copied())
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        if at.is_empty() {
            continue;
        }
        if e.iter()
            .any(|(k, ts)| (k.0 == v || k.1 == v) && ts.len() > 2)
        {
            out.push(v);
            continue;
        }
        let mut group: Vec<usize> = (0..at.len()).collect();
        loop {
            let mut changed = false;
            for (k, ts) in &e {
                if (k.0 == v || k.1 == v) && ts.len() == 2 {
                    let i = at.iter().position(|&t| t == ts[0]).unwrap();
                    let j = at.iter().position(|&t| t == ts[1]).unwrap();
                    let g = group[i].min(group[j]);
                    if group[i] != g || group[j] != g {
                        group[i] = g;
                        group[j] = g;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        if group.iter().collect::<BTreeSet<_>>().len() > 1 {
            out.push(v);
        }
    }
    out
}

/// (consistently oriented, orientable) from the definition, by trying every flip assignment.
fn brute_orientation(m: &TriMesh) -> (bool, bool) {
    let e = brute_edges(m);
    let manifold: Vec<((u32, u32), [usize; 2])> = e
        .iter()
        .filter(|(_, ts)| ts.len() == 2)
        .map(|(k, ts)| (*k, [ts[0], ts[1]]))
        .collect();
    // Direction of edge (lo, hi) in triangle t: true when t runs lo → hi.
    let forward = |t: usize, k: (u32, u32)| {
        let tri = m.triangles[t];
        (0..3).any(|i| tri[i] == k.0 && tri[(i + 1) % 3] == k.1)
    };
    let ok = |flip: u64| {
        manifold.iter().all(|&(k, [a, b])| {
            let fa = forward(a, k) ^ (flip >> a & 1 == 1);
            let fb = forward(b, k) ^ (flip >> b & 1 == 1);
            fa != fb
        })
    };
    let n = m.triangles.len();
    (ok(0), (0..1u64 << n).any(ok))
}

fn brute_chi(m: &TriMesh) -> i64 {
    let e = brute_edges(m);
    let tris: BTreeSet<usize> = e.values().flatten().copied().collect();
    let verts: BTreeSet<u32> = tris.iter().flat_map(|&t| m.triangles[t]).collect();
    verts.len() as i64 - e.len() as i64 + tris.len() as i64
}

fn random_mesh(nv: u32, tris: Vec<[u32; 3]>) -> TriMesh {
    let pos = (0..nv)
        .map(|i| {
            let f = i as f64;
            Point3::new(f.sin(), (1.7 * f).cos(), 0.3 * f)
        })
        .collect();
    TriMesh::new(pos, tris)
}

// ---------------------------------------------------------------------------------------------
// Known surfaces.

#[test]
fn closed_surfaces_of_known_genus() {
    let cases: Vec<(&str, TriMesh, i64)> = vec![
        (
            "uv sphere",
            generate::uv_sphere(Point3::origin(), 1.0, 8, 12),
            0,
        ),
        ("icosphere", generate::icosphere(2), 0),
        ("torus", generate::torus(3.0, 1.0, 16, 8), 1),
        ("double torus", generate::multi_torus(2), 2),
        ("triple torus", generate::multi_torus(3), 3),
        ("genus 6", generate::multi_torus(6), 6),
    ];
    for (name, m, g) in cases {
        let t = analyze_topology(&m);
        check_invariants(&m, &t);
        assert_eq!(t.euler_characteristic, 2 - 2 * g, "{name}");
        assert_eq!(t.genus(), Some(g), "{name}");
        assert_eq!(t.parts.len(), 1, "{name}");
        assert!(t.boundary_loops.is_empty() && t.is_closed(), "{name}");
        assert!(
            t.manifold && t.orientable && t.consistently_oriented,
            "{name}"
        );
        assert!(t.neighbors.iter().flatten().all(|&n| n != NONE), "{name}");
        assert_eq!(t.neighbors, brute_neighbors(&m), "{name}");
        assert!(m.signed_volume() > 0.0, "{name}");
    }
}

#[test]
fn disk_and_annulus() {
    let m = generate::disk(4, 10);
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert_eq!((t.euler_characteristic, t.boundary_loops.len()), (1, 1));
    assert_eq!(t.genus(), Some(0));
    // The loop runs counter-clockwise (with the triangles), 10 edges of the unit circle.
    let l = &t.boundary_loops[0];
    assert_eq!(l.len(), 10);
    let expected = 10.0 * 2.0 * (std::f64::consts::PI / 10.0).sin();
    assert!((t.boundary_loop_lengths[0] - expected).abs() < 1e-12);
    let area: f64 = (0..l.len())
        .map(|i| {
            let (a, b) = (
                m.positions[l[i] as usize],
                m.positions[l[(i + 1) % l.len()] as usize],
            );
            a.x * b.y - a.y * b.x
        })
        .sum();
    assert!(area > 0.0);

    let m = generate::annulus(1.0, 2.0, 3, 12);
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert_eq!(t.euler_characteristic, 0);
    assert_eq!(t.boundary_loops.len(), 2);
    assert_eq!(t.parts[0].boundary_loops, 2);
    assert_eq!(t.genus(), Some(0));
    let mut len = t.boundary_loop_lengths.clone();
    len.sort_by(f64::total_cmp);
    let s = 2.0 * 12.0 * (std::f64::consts::PI / 12.0).sin();
    assert!((len[0] - s).abs() < 1e-12 && (len[1] - 2.0 * s).abs() < 1e-12);
}

#[test]
fn two_disjoint_spheres() {
    let m = merge(
        &generate::icosphere(1),
        &translate(
            &generate::uv_sphere(Point3::origin(), 1.0, 5, 7),
            [5.0, 0.0, 0.0],
        ),
    );
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert_eq!(t.parts.len(), 2);
    assert_eq!(t.euler_characteristic, 4);
    assert_eq!(t.genus(), Some(0));
    assert!(t.parts.iter().all(|p| p.euler_characteristic == 2));
    assert_eq!(t.part_of_triangle[0], 0);
    assert_eq!(*t.part_of_triangle.last().unwrap(), 1);
    // A torus and a double torus: genus adds up.
    let m = merge(&generate::torus(2.0, 0.5, 8, 6), &generate::multi_torus(2));
    let t = analyze_topology(&m);
    assert_eq!((t.parts.len(), t.genus()), (2, Some(3)));
}

#[test]
fn mobius_strip_is_not_orientable() {
    let mut m = generate::mobius(20, 2);
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert!(!t.orientable && !t.consistently_oriented);
    assert!(t.manifold);
    assert_eq!(t.euler_characteristic, 0);
    assert_eq!(t.boundary_loops.len(), 1);
    assert_eq!(t.genus(), None);
    let before = m.clone();
    assert!(orient_consistently(&mut m).is_err());
    assert_eq!(m, before);
}

#[test]
fn two_tetrahedra_sharing_an_edge() {
    let a = generate::tetrahedron();
    let b = translate(&a, [3.0, 0.0, 0.0]);
    // Glue b's vertices 0 and 1 onto a's: the edge (0, 1) then has four triangles.
    let mut m = merge(&a, &b);
    for t in m.triangles.iter_mut().skip(4) {
        for v in t.iter_mut() {
            if *v == 4 || *v == 5 {
                *v -= 4;
            }
        }
    }
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert_eq!(t.non_manifold_edges, vec![[0, 1]]);
    assert_eq!(t.non_manifold_vertices, vec![0, 1]);
    assert_eq!(t.parts.len(), 1);
    assert!(!t.manifold && t.genus().is_none());
    assert!(t.is_closed());
    // V 6 − E 11 + F 8.
    assert_eq!(t.euler_characteristic, 3);
    assert_eq!(t.num_used_vertices, 6);
}

#[test]
fn two_cones_sharing_a_tip() {
    let mut c1 = generate::disk(2, 8);
    for p in c1.positions.iter_mut().skip(1) {
        p.z = 1.0;
    }
    let mut c2 = c1.clone();
    for p in c2.positions.iter_mut() {
        p.z = -p.z;
    }
    // Share the tip (vertex 0 of both).
    let mut m = merge(&c1, &c2);
    let off = c1.positions.len() as u32;
    for t in m.triangles.iter_mut().skip(c1.triangles.len()) {
        for v in t.iter_mut() {
            if *v == off {
                *v = 0;
            }
        }
    }
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert_eq!(t.parts.len(), 2);
    assert_eq!(t.non_manifold_vertices, vec![0]);
    assert!(t.non_manifold_edges.is_empty());
    assert!(!t.manifold);
    // Each cone on its own is a disc.
    assert!(t.parts.iter().all(|p| p.manifold && p.genus == Some(0)));
    assert_eq!(t.boundary_loops.len(), 2);
    assert_eq!(t.euler_characteristic, 33 - 80 + 48);
    assert_eq!(t.num_used_vertices, 33);

    // Two fans of the *same* part at one vertex: a pinched annulus (touching at one vertex).
    let mut a = generate::annulus(1.0, 2.0, 1, 8);
    for t in a.triangles.iter_mut() {
        for v in t.iter_mut() {
            if *v == 12 {
                *v = 0; // outer vertex 12 (outer ring is 8..16) glued onto inner vertex 0
            }
        }
    }
    let t = analyze_topology(&a);
    check_invariants(&a, &t);
    assert_eq!(t.parts.len(), 1);
    assert_eq!(t.non_manifold_vertices, vec![0]);
    assert!(!t.parts[0].manifold && t.genus().is_none());
    // The inner and the outer boundary touch at vertex 0 but stay two loops (boundary edges are
    // paired within each fan), each through vertex 0 once.
    assert_eq!(t.boundary_loops.len(), 2);
    let mut sizes: Vec<usize> = t.boundary_loops.iter().map(|l| l.len()).collect();
    sizes.sort_unstable();
    assert_eq!(sizes, vec![8, 8]);
    assert!(t
        .boundary_loops
        .iter()
        .all(|l| l.iter().filter(|&&v| v == 0).count() == 1));
}

#[test]
fn sphere_with_one_flipped_triangle() {
    let mut m = generate::icosphere(2);
    let vol = m.signed_volume();
    m.triangles[37].swap(0, 1);
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert!(!t.consistently_oriented && t.orientable && t.manifold);
    assert_eq!(t.genus(), Some(0));
    assert_eq!(t.num_directed_edge_conflicts, 3);
    assert_eq!(orient_consistently(&mut m).unwrap(), 1);
    assert!(analyze_topology(&m).consistently_oriented);
    assert!((m.signed_volume() - vol).abs() < 1e-12);
    assert!(same_up_to_rotation(&m, &generate::icosphere(2)));
    // Already consistent: nothing to do.
    assert_eq!(orient_consistently(&mut m).unwrap(), 0);
    // An open surface flipped in its majority: the fewer-flips class is kept.
    let mut d = generate::disk(3, 8);
    d.triangles[0].swap(1, 2);
    assert_eq!(orient_consistently(&mut d).unwrap(), 1);
    assert!(same_up_to_rotation(&d, &generate::disk(3, 8)));
}

/// Same triangles, each compared up to a rotation of its vertex order (same orientation).
fn same_up_to_rotation(a: &TriMesh, b: &TriMesh) -> bool {
    let canon = |t: &[u32; 3]| {
        let mut t = *t;
        let k = (0..3).min_by_key(|&i| t[i]).unwrap();
        t.rotate_left(k);
        t
    };
    a.triangles.len() == b.triangles.len()
        && a.triangles
            .iter()
            .zip(&b.triangles)
            .all(|(x, y)| canon(x) == canon(y))
}

#[test]
fn empty_mesh() {
    let m = TriMesh::default();
    let t = analyze_topology(&m);
    assert_eq!(
        t,
        Topology {
            manifold: true,
            orientable: true,
            consistently_oriented: true,
            ..Default::default()
        }
    );
    assert_eq!(t.genus(), Some(0));
    // Vertices but no triangles: none used.
    let m = TriMesh::new(vec![Point3::origin(); 3], vec![]);
    assert_eq!(analyze_topology(&m).num_used_vertices, 0);
}

// ---------------------------------------------------------------------------------------------
// Oracles and properties on random meshes.

fn arb_mesh() -> impl Strategy<Value = TriMesh> {
    (3u32..12).prop_flat_map(|nv| {
        prop::collection::vec(prop::array::uniform3(0..nv), 0..30)
            .prop_map(move |tris| random_mesh(nv, tris))
    })
}

fn generated(i: usize) -> TriMesh {
    match i % 7 {
        0 => generate::icosphere(1),
        1 => generate::torus(2.0, 0.7, 7, 5),
        2 => generate::multi_torus(2),
        3 => generate::disk(3, 7),
        4 => generate::annulus(1.0, 2.0, 2, 6),
        5 => generate::mobius(9, 2),
        _ => merge(&generate::cube(), &generate::tetrahedron()),
    }
}

fn summary(
    t: &Topology,
) -> (
    i64,
    usize,
    Option<i64>,
    usize,
    usize,
    usize,
    bool,
    bool,
    usize,
) {
    (
        t.euler_characteristic,
        t.parts.len(),
        t.genus(),
        t.boundary_loops.len(),
        t.non_manifold_edges.len(),
        t.non_manifold_vertices.len(),
        t.manifold,
        t.orientable,
        t.num_edges,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn neighbours_parts_chi_match_brute_force(m in arb_mesh()) {
        let t = analyze_topology(&m);
        prop_assert_eq!(&t.neighbors, &brute_neighbors(&m));
        prop_assert_eq!(t.parts.len(), brute_parts(&m));
        prop_assert_eq!(t.euler_characteristic, brute_chi(&m));
        prop_assert_eq!(t.num_edges, brute_edges(&m).len());
        let nm: Vec<[u32; 2]> = brute_edges(&m)
            .iter()
            .filter(|(_, v)| v.len() > 2)
            .map(|(k, _)| [k.0, k.1])
            .collect();
        prop_assert_eq!(&t.non_manifold_edges, &nm);
        prop_assert_eq!(&t.non_manifold_vertices, &brute_non_manifold_vertices(&m));
        if m.triangles.len() <= 12 {
            prop_assert_eq!((t.consistently_oriented, t.orientable), brute_orientation(&m));
        }
        // Orienting: succeeds exactly for orientable meshes and then gives a consistent mesh
        // with the same topology; on failure the mesh is unchanged.
        let mut o = m.clone();
        match orient_consistently(&mut o) {
            Ok(_) => {
                prop_assert!(t.orientable);
                let to = analyze_topology(&o);
                prop_assert!(to.consistently_oriented);
                prop_assert_eq!(summary(&to), summary(&t));
            }
            Err(_) => {
                prop_assert!(!t.orientable);
                prop_assert_eq!(&o, &m);
            }
        }
        check_invariants(&m, &t);
        // Neighbour relation is symmetric.
        for (a, ns) in t.neighbors.iter().enumerate() {
            for &b in ns {
                if b != NONE {
                    prop_assert!(t.neighbors[b as usize].contains(&(a as u32)));
                }
            }
        }
    }

    #[test]
    fn relabelling_does_not_change_topology(
        which in 0usize..7,
        random in arb_mesh(),
        use_random in any::<bool>(),
        seed in any::<u64>(),
    ) {
        use rand::seq::SliceRandom;
        use rand::{Rng, SeedableRng};
        let m = if use_random { random } else { generated(which) };
        let base = analyze_topology(&m);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        // Shuffle the triangle order.
        let mut s = m.clone();
        s.triangles.shuffle(&mut rng);
        prop_assert_eq!(summary(&analyze_topology(&s)), summary(&base));
        // Rotate each triangle's vertex order (keeps orientation).
        let mut r = m.clone();
        for t in r.triangles.iter_mut() {
            t.rotate_left(rng.gen_range(0..3));
        }
        let tr = analyze_topology(&r);
        prop_assert_eq!(summary(&tr), summary(&base));
        prop_assert_eq!(tr.consistently_oriented, base.consistently_oriented);
        // Renumber the vertices.
        let mut perm: Vec<u32> = (0..m.positions.len() as u32).collect();
        perm.shuffle(&mut rng);
        let mut p = m.clone();
        for (i, &j) in perm.iter().enumerate() {
            p.positions[j as usize] = m.positions[i];
        }
        for t in p.triangles.iter_mut() {
            *t = t.map(|v| perm[v as usize]);
        }
        // Next to non-manifold edges, boundary edges are paired by edge index, a choice that
        // renumbering may change: there only the number of boundary edges must agree.
        let tp = analyze_topology(&p);
        let (mut a, mut b) = (summary(&tp), summary(&base));
        if !base.non_manifold_edges.is_empty() {
            a.3 = 0;
            b.3 = 0;
        }
        prop_assert_eq!(a, b);
        prop_assert_eq!(tp.num_boundary_edges, base.num_boundary_edges);
    }

    #[test]
    fn orient_consistently_repairs_random_flips(which in 0usize..5, seed in any::<u64>()) {
        use rand::{Rng, SeedableRng};
        let good = match which {
            0 => generate::icosphere(1),
            1 => generate::torus(2.0, 0.7, 7, 5),
            2 => generate::multi_torus(2),
            3 => generate::uv_sphere(Point3::new(1.0, 1.0, 1.0), 2.0, 5, 6),
            _ => merge(&generate::cube(), &translate(&generate::icosphere(0), [4.0, 0.0, 0.0])),
        };
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut m = good.clone();
        let mut flipped = 0;
        for t in m.triangles.iter_mut() {
            if rng.gen_bool(0.3) {
                t.swap(0, 2);
                flipped += 1;
            }
        }
        // Closed surfaces: the outward class is restored, so exactly the flipped ones change.
        prop_assert_eq!(orient_consistently(&mut m).unwrap(), flipped);
        let t = analyze_topology(&m);
        prop_assert!(t.consistently_oriented);
        prop_assert!(m.signed_volume() > 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Real meshes.

/// A tiny OBJ reader for the test data: `v x y z` and triangular `f a b c` lines (1-based,
/// `a/b/c` forms allowed); everything else is ignored.
fn read_obj(name: &str) -> Option<TriMesh> {
    use std::io::Read;
    let path = common::data(&format!("meshes/{name}"))?;
    let bytes = std::fs::read(&path).expect("read a real mesh");
    let text = if name.ends_with(".gz") {
        let mut s = String::new();
        flate2::read::GzDecoder::new(&bytes[..])
            .read_to_string(&mut s)
            .expect("gunzip");
        s
    } else {
        String::from_utf8(bytes).expect("utf-8")
    };
    let mut m = TriMesh::default();
    for line in text.lines() {
        let mut it = line.split_ascii_whitespace();
        match it.next() {
            Some("v") => {
                let mut c = [0.0; 3];
                for x in c.iter_mut() {
                    *x = it.next().unwrap().parse().unwrap();
                }
                m.positions.push(Point3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let mut f = [0u32; 3];
                for x in f.iter_mut() {
                    let s = it.next().unwrap();
                    *x = s.split('/').next().unwrap().parse::<u32>().unwrap() - 1;
                }
                assert!(it.next().is_none(), "{name}: non-triangle face");
                m.triangles.push(f);
            }
            _ => {}
        }
    }
    m.validate().unwrap();
    Some(m)
}

#[test]
fn real_bunny_npm_closed_genus_0() {
    let Some(mut m) = read_obj("bunny_npm.obj") else {
        return;
    };
    assert_eq!((m.num_vertices(), m.num_triangles()), (1839, 3674));
    let t = analyze_topology(&m);
    check_invariants(&m, &t);
    assert!(t.is_closed() && t.manifold && t.consistently_oriented);
    assert_eq!(
        (t.parts.len(), t.euler_characteristic, t.genus()),
        (1, 2, Some(0))
    );
    assert!(m.signed_volume() > 0.0);
    assert_eq!(orient_consistently(&mut m).unwrap(), 0);
}

#[test]
fn real_rocker_arm_genus_1() {
    let Some(m) = read_obj("rocker-arm.obj") else {
        return;
    };
    assert_eq!((m.num_vertices(), m.num_triangles()), (10044, 20088));
    let t = analyze_topology(&m);
    assert!(t.is_closed() && t.manifold && t.consistently_oriented);
    assert_eq!((t.euler_characteristic, t.genus()), (0, Some(1)));
}

#[test]
fn real_fandisk_and_spot_genus_0() {
    for (name, nv, nt) in [("fandisk.obj", 6475, 12946), ("spot.obj", 2930, 5856)] {
        let Some(m) = read_obj(name) else { return };
        assert_eq!((m.num_vertices(), m.num_triangles()), (nv, nt), "{name}");
        let t = analyze_topology(&m);
        assert!(
            t.is_closed() && t.manifold && t.consistently_oriented,
            "{name}"
        );
        assert_eq!((t.parts.len(), t.genus()), (1, Some(0)), "{name}");
        assert!(m.signed_volume() > 0.0, "{name}");
    }
}

#[test]
fn real_stanford_bunny_open() {
    let Some(m) = read_obj("stanford-bunny.obj.gz") else {
        return;
    };
    assert_eq!((m.num_vertices(), m.num_triangles()), (35947, 69451));
    let t = analyze_topology(&m);
    check_invariants_fast(&t);
    assert_eq!(t.num_used_vertices, 34834);
    assert_eq!(t.num_boundary_edges, 223);
    assert_eq!(t.parts.len(), 1);
    assert_eq!(t.euler_characteristic, -3);
    assert!(t.consistently_oriented);
    let loop_edges: usize = t.boundary_loops.iter().map(|l| l.len()).sum();
    assert_eq!(loop_edges, 223);
    // χ = 2 − 2g − b with b = 5 holes in the base: genus 0.
    assert_eq!((t.boundary_loops.len(), t.genus()), (5, Some(0)));
    assert!(t.manifold);
    eprintln!(
        "stanford bunny: {} boundary loops (sizes {:?}), genus {:?}, manifold {}, {} non-manifold vertices",
        t.boundary_loops.len(),
        t.boundary_loops.iter().map(|l| l.len()).collect::<Vec<_>>(),
        t.genus(),
        t.manifold,
        t.non_manifold_vertices.len()
    );
}

/// The checks of [`check_invariants`] that need no brute force.
fn check_invariants_fast(t: &Topology) {
    let loop_edges: usize = t.boundary_loops.iter().map(|l| l.len()).sum::<usize>()
        + t.open_boundary_chains
            .iter()
            .map(|c| c.len() - 1)
            .sum::<usize>();
    assert_eq!(loop_edges, t.num_boundary_edges);
    assert_eq!(t.parts.iter().map(|p| p.edges).sum::<usize>(), t.num_edges);
}

#[test]
fn real_dragon_non_manifold() {
    let Some(m) = read_obj("dragon_vrip_res4.obj") else {
        return;
    };
    assert_eq!((m.num_vertices(), m.num_triangles()), (5205, 11102));
    let t = analyze_topology(&m);
    check_invariants_fast(&t);
    assert_eq!(t.num_used_vertices, 5203);
    assert_eq!(t.non_manifold_edges.len(), 803);
    assert_eq!(t.num_boundary_edges, 0);
    // README: 1606 directed edges used twice. They all sit on the non-manifold edges (each
    // has four triangles, two in each direction); the manifold edges are consistent.
    assert_eq!(t.num_directed_edge_conflicts, 1606);
    assert!(!t.manifold);
    assert!(t.consistently_oriented && t.orientable);
    assert_eq!(t.genus(), None);
}

#[test]
fn real_horse_closed_genus_0_inward() {
    let t0 = std::time::Instant::now();
    let Some(mut m) = read_obj("horse.obj.gz") else {
        return;
    };
    assert_eq!((m.num_vertices(), m.num_triangles()), (48485, 96966));
    let t1 = std::time::Instant::now();
    let t = analyze_topology(&m);
    eprintln!("horse: read {:?}, analyze {:?}", t1 - t0, t1.elapsed());
    check_invariants_fast(&t);
    assert!(t.is_closed() && t.manifold && t.consistently_oriented);
    assert_eq!(
        (t.parts.len(), t.euler_characteristic, t.genus()),
        (1, 2, Some(0))
    );
    // Faces inward as staged (README: signed volume −2.63e-4); orienting flips every triangle.
    assert!((m.signed_volume() + 2.63e-4).abs() < 0.01e-4);
    assert_eq!(orient_consistently(&mut m).unwrap(), 96966);
    assert!(m.signed_volume() > 0.0);
}

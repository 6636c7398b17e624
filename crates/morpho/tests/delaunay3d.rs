//! 3D and d-dimensional Delaunay: brute-force oracles on random and degenerate inputs.

use morpho::delaunay::{triangulate_3d, Delaunay3};
use morpho::delaunay::{triangulate_nd, DelaunayD};
use morpho::geom::Point3;
use morpho::internals::delaunay as dd;
use morpho::internals::{insphere_exact, insphere_sign, orient3d_exact, orient_sign};
use morpho::util::NONE;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use std::collections::{BTreeSet, HashMap, HashSet};

fn arr(p: &Point3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

fn rng(seed: u64) -> rand_chacha::ChaCha8Rng {
    rand_chacha::ChaCha8Rng::seed_from_u64(seed)
}

fn random_points(n: usize, seed: u64) -> Vec<Point3> {
    let mut r = rng(seed);
    (0..n)
        .map(|_| Point3::new(r.gen(), r.gen(), r.gen()))
        .collect()
}

fn grid(n: usize, scale: f64, offset: f64) -> Vec<Point3> {
    let mut v = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                v.push(Point3::new(
                    offset + i as f64 * scale,
                    offset + j as f64 * scale,
                    offset + k as f64 * scale,
                ));
            }
        }
    }
    v
}

/// Integer points on the spheres x² + y² + z² = r² (exactly cospherical).
fn sphere_lattice(r2: i64) -> Vec<Point3> {
    let r = (r2 as f64).sqrt() as i64 + 1;
    let mut v = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            for z in -r..=r {
                if x * x + y * y + z * z == r2 {
                    v.push(Point3::new(x as f64, y as f64, z as f64));
                }
            }
        }
    }
    v
}

fn sorted<const N: usize>(mut a: [u32; N]) -> [u32; N] {
    a.sort_unstable();
    a
}

/// The full brute-force oracle. Returns the canonical set of tetrahedra (as coordinates, so that
/// it can be compared across inputs in different orders).
fn check(d: &Delaunay3, input: &[Point3]) -> BTreeSet<[[u64; 3]; 4]> {
    // every input point maps to a vertex at the same position
    assert_eq!(d.vertex_of_input.len(), input.len());
    for (i, p) in input.iter().enumerate() {
        let v = d.vertex_of_input[i] as usize;
        assert_eq!(arr(&d.points[v]), arr(p).map(|x| x + 0.0), "input {i}");
    }
    let distinct: HashSet<[u64; 3]> = input
        .iter()
        .map(|p| arr(p).map(|x| (x + 0.0).to_bits()))
        .collect();
    assert_eq!(distinct.len(), d.points.len());
    assert_eq!(d.duplicates, input.len() - distinct.len());
    for (v, &i) in d.input_of_vertex.iter().enumerate() {
        assert_eq!(d.vertex_of_input[i as usize] as usize, v);
    }
    if d.tets.is_empty() {
        assert!(d.degenerate.is_some());
        return BTreeSet::new();
    }
    assert!(d.degenerate.is_none());
    d.check_topology().unwrap();
    d.check_delaunay_local().unwrap();
    let p = |v: u32| arr(&d.points[v as usize]);
    // every tet positive, empty (perturbed) circumsphere
    for t in &d.tets {
        assert!(orient3d_exact(p(t[0]), p(t[1]), p(t[2]), p(t[3])) > 0.0);
        for v in 0..d.points.len() as u32 {
            if t.contains(&v) {
                continue;
            }
            let s = insphere_exact(p(t[0]), p(t[1]), p(t[2]), p(t[3]), p(v));
            assert!(s <= 0.0, "vertex {v} inside the sphere of {t:?}");
            if s == 0.0 {
                // ties: the d-dimensional code's perturbation must say "outside"
                let q = [p(t[0]), p(t[1]), p(t[2]), p(t[3]), p(v)];
                let r: Vec<&[f64]> = q.iter().map(|x| &x[..]).collect();
                assert!(
                    !dd::perturbed_insphere(&r, &[t[0], t[1], t[2], t[3], v]),
                    "perturbed tie {t:?} {v}"
                );
            }
        }
    }
    // faces: ≤ 2 tets each, hull faces exactly once and equal to the hull list
    let mut faces: HashMap<[u32; 3], usize> = HashMap::new();
    let mut edges: HashSet<[u32; 2]> = HashSet::new();
    let mut used: HashSet<u32> = HashSet::new();
    for t in &d.tets {
        for i in 0..4 {
            let f: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| t[k]).collect();
            *faces.entry(sorted([f[0], f[1], f[2]])).or_default() += 1;
            used.insert(t[i]);
            for j in i + 1..4 {
                edges.insert(sorted([t[i], t[j]]));
            }
        }
    }
    assert!(faces.values().all(|&c| c <= 2));
    let once: BTreeSet<[u32; 3]> = faces
        .iter()
        .filter(|(_, &c)| c == 1)
        .map(|(f, _)| *f)
        .collect();
    let hull: BTreeSet<[u32; 3]> = d.hull.iter().map(|h| sorted(*h)).collect();
    assert_eq!(hull.len(), d.hull.len());
    assert_eq!(once, hull);
    assert_eq!(d.triangles().len(), faces.len());
    // every vertex is used
    assert_eq!(used.len(), d.points.len());
    // hull is convex and outward oriented
    for h in &d.hull {
        for v in 0..d.points.len() as u32 {
            assert!(orient3d_exact(p(h[0]), p(h[1]), p(h[2]), p(v)) >= 0.0);
        }
    }
    // Euler characteristic of a ball
    let (nv, ne, nf, nt) = (
        d.points.len() as i64,
        edges.len() as i64,
        faces.len() as i64,
        d.tets.len() as i64,
    );
    assert_eq!(nv - ne + nf - nt, 1, "Euler");
    // volumes (in f64; the point sets here have coordinates of moderate size)
    let vol: f64 = d
        .tets
        .iter()
        .map(|t| {
            let a = d.points[t[0] as usize];
            let b = d.points[t[1] as usize] - a;
            let c = d.points[t[2] as usize] - a;
            let e = d.points[t[3] as usize] - a;
            -b.cross(&c).dot(&e) / 6.0
        })
        .sum();
    let hv: f64 = d
        .hull
        .iter()
        .map(|h| {
            let a = d.points[h[0] as usize].coords;
            let b = d.points[h[1] as usize].coords;
            let c = d.points[h[2] as usize].coords;
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum();
    assert!(vol > 0.0);
    assert!(
        (vol - hv).abs() <= 1e-9 * vol.abs().max(hv.abs()),
        "volume {vol} vs hull {hv}"
    );
    canonical(d)
}

fn canonical(d: &Delaunay3) -> BTreeSet<[[u64; 3]; 4]> {
    d.tets
        .iter()
        .map(|t| {
            let mut c = t.map(|v| arr(&d.points[v as usize]).map(f64::to_bits));
            c.sort_unstable();
            c
        })
        .collect()
}

fn shuffled(p: &[Point3], seed: u64) -> Vec<Point3> {
    use rand::seq::SliceRandom;
    let mut v = p.to_vec();
    v.shuffle(&mut rng(seed));
    v
}

/// Oracle + determinism under two shuffles + agreement with the d-dimensional code.
fn full(points: &[Point3], with_dd: bool) -> Delaunay3 {
    let d = triangulate_3d(points).unwrap();
    let c = check(&d, points);
    for s in [1, 2] {
        let q = shuffled(points, s);
        let e = triangulate_3d(&q).unwrap();
        assert_eq!(canonical(&e), c, "shuffle {s} changed the triangulation");
        check(&e, &q);
    }
    if with_dd {
        let flat: Vec<f64> = points.iter().flat_map(arr).collect();
        let g = triangulate_nd(&flat, 3).unwrap();
        let gs: BTreeSet<[u32; 4]> = g
            .simplices
            .iter()
            .map(|s| sorted([s[0], s[1], s[2], s[3]]))
            .collect();
        let ds: BTreeSet<[u32; 4]> = d.tets.iter().map(|t| sorted(*t)).collect();
        assert_eq!(gs, ds, "3D and dD triangulations differ");
        assert_eq!(g.hull.len(), d.hull.len());
    }
    d
}

#[test]
fn random_sets() {
    for seed in 0..6 {
        full(&random_points(60, seed), true);
    }
}

#[test]
fn larger_lattice_local_certificate() {
    // 9³ lattice in shuffled order; plus a lattice with a random jitter on one axis
    let p = shuffled(&grid(9, 1.0, 0.0), 5);
    let d = triangulate_3d(&p).unwrap();
    d.check_topology().unwrap();
    d.check_delaunay_local().unwrap();
    assert_eq!(d.hull.len(), 6 * 8 * 8 * 2);
    // exact integer volumes: 6·vol = Σ orient3d
    let six_vol: i64 = d
        .tets
        .iter()
        .map(|t| {
            let q = t.map(|v| arr(&d.points[v as usize]).map(|x| x as i64));
            let e = |i: usize, k: usize| q[i][k] - q[3][k];
            e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1))
                - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
                + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0))
        })
        .sum();
    assert_eq!(six_vol, 6 * 512);
    let e = triangulate_3d(&shuffled(&p, 6)).unwrap();
    assert_eq!(canonical(&e), canonical(&d));
}

#[test]
fn integer_grid_4() {
    let d = full(&grid(4, 1.0, 0.0), true);
    assert_eq!(d.hull.len(), 6 * 9 * 2);
}

#[test]
fn cospherical_lattice() {
    // two concentric exact lattice spheres and the centre
    let mut p = sphere_lattice(25);
    let n25 = p.len();
    p.extend(sphere_lattice(50));
    p.push(Point3::new(0.0, 0.0, 0.0));
    assert!(n25 > 20);
    full(&p, true);
    full(&sphere_lattice(27), true);
}

#[test]
fn coplanar_subsets_and_duplicates() {
    let mut r = rng(7);
    let mut p: Vec<Point3> = Vec::new();
    // a 5×5 grid in the plane z = 0 (a hull face full of cocircular points)
    for i in 0..5 {
        for j in 0..5 {
            p.push(Point3::new(i as f64, j as f64, 0.0));
        }
    }
    for _ in 0..20 {
        p.push(Point3::new(
            r.gen_range(0..5) as f64,
            r.gen_range(0..5) as f64,
            r.gen_range(1..4) as f64,
        ));
    }
    // duplicates
    let dup: Vec<Point3> = p.iter().step_by(3).cloned().collect();
    p.extend(dup);
    let d = full(&p, true);
    assert!(d.duplicates > 0);
    // points coplanar with hull faces, outside the current hull during insertion
    let mut q = grid(3, 1.0, 0.0);
    q.extend([
        Point3::new(-1.0, 0.5, 0.0),
        Point3::new(3.0, 1.0, 2.0),
        Point3::new(1.0, -2.0, 2.0),
        Point3::new(0.5, 0.5, 2.0),
    ]);
    full(&q, true);
}

#[test]
fn degenerate_no_tets() {
    let line: Vec<Point3> = (0..10)
        .map(|i| Point3::new(i as f64, 2.0 * i as f64, -(i as f64)))
        .collect();
    let d = triangulate_3d(&line).unwrap();
    check(&d, &line);
    assert_eq!(d.degenerate.as_deref(), Some("all points collinear"));
    let mut r = rng(3);
    let plane: Vec<Point3> = (0..30)
        .map(|_| {
            let (u, v): (f64, f64) = (r.gen(), r.gen());
            Point3::new(u, v, 2.0 * u)
        })
        .collect();
    let d = triangulate_3d(&plane).unwrap();
    check(&d, &plane);
    assert_eq!(d.degenerate.as_deref(), Some("all points coplanar"));
    let one = vec![Point3::new(1.0, 1.0, 1.0); 3];
    let d = triangulate_3d(&one).unwrap();
    assert_eq!(d.duplicates, 2);
    assert!(d.tets.is_empty());
    assert!(triangulate_3d(&[]).is_err());
    assert!(triangulate_3d(&[Point3::new(0.0, f64::INFINITY, 0.0)]).is_err());
}

#[test]
fn extreme_scales() {
    // tiny, huge and huge-offset coordinates: the predicates switch to big integers
    for (s, o) in [(1e-300, 0.0), (1e300, 0.0), (1.0, 1e300), (1e-310, 0.0)] {
        let p = grid(3, s, o);
        let d = triangulate_3d(&p).unwrap();
        if o == 1e300 {
            // 1e300 + k == 1e300: everything is one point
            assert_eq!(d.points.len(), 1);
            continue;
        }
        d.check_topology().unwrap();
        assert_eq!(d.points.len(), 27);
        assert_eq!(d.hull.len(), 48);
        // same combinatorics as the unit grid
        let u = triangulate_3d(&grid(3, 1.0, 0.0)).unwrap();
        let a: BTreeSet<[u32; 4]> = d.tets.iter().map(|t| sorted(*t)).collect();
        let b: BTreeSet<[u32; 4]> = u.tets.iter().map(|t| sorted(*t)).collect();
        assert_eq!(a, b, "scale {s}");
    }
    // huge offset with distinct representable coordinates: 1e300 + k·1e300·2^-40
    let p = grid(3, 1e300 / (1u64 << 40) as f64, 1e300);
    let d = triangulate_3d(&p).unwrap();
    assert_eq!(d.points.len(), 27);
    d.check_topology().unwrap();
    d.check_delaunay_local().unwrap();
    let flat: Vec<f64> = p.iter().flat_map(arr).collect();
    let g = triangulate_nd(&flat, 3).unwrap();
    let a: BTreeSet<[u32; 4]> = d.tets.iter().map(|t| sorted(*t)).collect();
    let b: BTreeSet<[u32; 4]> = g
        .simplices
        .iter()
        .map(|s| sorted([s[0], s[1], s[2], s[3]]))
        .collect();
    assert_eq!(a, b);
    for (s, o) in [(1e-300, 0.0), (1e300, 0.0)] {
        let d = triangulate_3d(
            &random_points(40, 4)
                .iter()
                .map(|q| Point3::from(q.coords * s + nalgebra::Vector3::repeat(o)))
                .collect::<Vec<_>>(),
        )
        .unwrap();
        d.check_topology().unwrap();
        d.check_delaunay_local().unwrap();
    }
    // a grid with an offset of 2^60 (representable steps)
    let o = (1u64 << 60) as f64;
    let p = grid(3, 256.0, o);
    let d = triangulate_3d(&p).unwrap();
    assert_eq!(
        d.tets.len(),
        triangulate_3d(&grid(3, 1.0, 0.0)).unwrap().tets.len()
    );
    d.check_topology().unwrap();
}

#[test]
fn api_queries() {
    let p = random_points(80, 11);
    let d = triangulate_3d(&p).unwrap();
    // locate: every tet's centroid is located in a tet containing it; outside → None
    for (t, v) in d.tets.iter().enumerate().step_by(7) {
        let c = v
            .iter()
            .map(|&x| d.points[x as usize].coords)
            .fold(nalgebra::Vector3::zeros(), |a, b| a + b)
            / 4.0;
        let c = Point3::from(c);
        let found = d.locate(&c).unwrap();
        assert_eq!(found as usize, t);
    }
    assert_eq!(d.locate(&Point3::new(5.0, 5.0, 5.0)), None);
    // tets around a vertex = brute-force filter
    for v in 0..d.points.len() as u32 {
        let mut a = d.tets_around_vertex(v);
        a.sort_unstable();
        let b: Vec<u32> = (0..d.tets.len() as u32)
            .filter(|&t| d.tets[t as usize].contains(&v))
            .collect();
        assert_eq!(a, b);
    }
    // tets around an edge: brute force, and consecutive ones are neighbours
    for t in d.tets.iter().take(20) {
        let (a, b) = (t[0], t[2]);
        let ring = d.tets_around_edge(a, b);
        let mut s = ring.clone();
        s.sort_unstable();
        let brute: Vec<u32> = (0..d.tets.len() as u32)
            .filter(|&u| d.tets[u as usize].contains(&a) && d.tets[u as usize].contains(&b))
            .collect();
        assert_eq!(s, brute);
        for w in ring.windows(2) {
            assert!(d.neighbors[w[0] as usize].contains(&w[1]));
        }
    }
    // triangles: each face once, with consistent tets; hull faces have NONE
    let tris = d.triangles();
    let hull = tris.iter().filter(|f| f.tets[1] == NONE).count();
    assert_eq!(hull, d.hull.len());
    for f in &tris {
        let t = d.tets[f.tets[0] as usize];
        let apex = *t.iter().find(|v| !f.v.contains(v)).unwrap();
        let q = |v: u32| arr(&d.points[v as usize]);
        // outward of tets[0]: the apex is on the inner side
        assert!(orient3d_exact(q(f.v[0]), q(f.v[1]), q(f.v[2]), q(apex)) > 0.0);
    }
    // circumsphere: all four vertices at the radius
    for t in 0..d.tets.len() as u32 {
        let (c, r) = d.circumsphere(t);
        for &v in &d.tets[t as usize] {
            let dist = (d.points[v as usize] - c).norm();
            assert!((dist - r).abs() <= 1e-6 * r.max(1.0));
        }
    }
    let inp = d.to_input_indices();
    for (t, ti) in d.tets.iter().zip(&inp) {
        for k in 0..4 {
            assert_eq!(arr(&p[ti[k] as usize]), arr(&d.points[t[k] as usize]));
        }
    }
}

/// Brute-force oracle for the d-dimensional code.
fn check_d(g: &DelaunayD) {
    let d = g.dim;
    let nv = g.num_vertices() as u32;
    for s in &g.simplices {
        let q: Vec<&[f64]> = s.iter().map(|&v| g.point(v)).collect();
        assert_eq!(orient_sign(&q), 1);
        for v in 0..nv {
            if s.contains(&v) {
                continue;
            }
            let mut r = q.clone();
            r.push(g.point(v));
            let mut ids = s.clone();
            ids.push(v);
            assert!(insphere_sign(&r) <= 0);
            assert!(!dd::perturbed_insphere(&r, &ids));
        }
    }
    // neighbour symmetry and facet counts
    let mut facets: HashMap<Vec<u32>, usize> = HashMap::new();
    for (i, s) in g.simplices.iter().enumerate() {
        for k in 0..=d {
            let mut f: Vec<u32> = (0..=d).filter(|&j| j != k).map(|j| s[j]).collect();
            f.sort_unstable();
            *facets.entry(f).or_default() += 1;
            let n = g.neighbors[i][k];
            if n != NONE {
                assert!(g.neighbors[n as usize].contains(&(i as u32)));
            }
        }
    }
    assert!(facets.values().all(|&c| c <= 2));
    let once: BTreeSet<Vec<u32>> = facets
        .into_iter()
        .filter(|(_, c)| *c == 1)
        .map(|(f, _)| f)
        .collect();
    let hull: BTreeSet<Vec<u32>> = g
        .hull
        .iter()
        .map(|h| {
            let mut h = h.clone();
            h.sort_unstable();
            h
        })
        .collect();
    assert_eq!(once, hull);
    let vol: f64 = (0..g.simplices.len()).map(|s| g.volume(s)).sum();
    let hv = g.hull_volume();
    assert!(vol > 0.0);
    assert!((vol - hv).abs() <= 1e-9 * vol, "dim {d}: {vol} vs {hv}");
}

#[test]
fn dd_random_and_grids() {
    for dim in 2..=5 {
        let n = [0, 0, 50, 30, 20, 14][dim];
        let mut r = rng(dim as u64);
        let c: Vec<f64> = (0..n * dim).map(|_| r.gen()).collect();
        let g = triangulate_nd(&c, dim).unwrap();
        check_d(&g);
        // shuffled input, same simplices (vertex ids are canonical)
        let mut idx: Vec<usize> = (0..n).collect();
        use rand::seq::SliceRandom;
        idx.shuffle(&mut r);
        let c2: Vec<f64> = idx
            .iter()
            .flat_map(|&i| c[i * dim..i * dim + dim].to_vec())
            .collect();
        let g2 = triangulate_nd(&c2, dim).unwrap();
        let a: BTreeSet<Vec<u32>> = g
            .simplices
            .iter()
            .map(|s| {
                let mut s = s.clone();
                s.sort_unstable();
                s
            })
            .collect();
        let b: BTreeSet<Vec<u32>> = g2
            .simplices
            .iter()
            .map(|s| {
                let mut s = s.clone();
                s.sort_unstable();
                s
            })
            .collect();
        assert_eq!(a, b);
    }
    // integer grids (all cospherical ties) in 2, 3 and 4 dimensions
    for (dim, k) in [(2usize, 5usize), (3, 3), (4, 3)] {
        let n = k.pow(dim as u32);
        let c: Vec<f64> = (0..n)
            .flat_map(|mut i| {
                (0..dim)
                    .map(|_| {
                        let x = (i % k) as f64;
                        i /= k;
                        x
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let g = triangulate_nd(&c, dim).unwrap();
        check_d(&g);
        let vol: f64 = (0..g.simplices.len()).map(|s| g.volume(s)).sum();
        assert!((vol - ((k - 1) as f64).powi(dim as i32)).abs() < 1e-9);
    }
    // degenerate: 3D points on a plane
    let c: Vec<f64> = (0..10)
        .flat_map(|i| [i as f64, (i * i) as f64, 0.0])
        .collect();
    let g = triangulate_nd(&c, 3).unwrap();
    assert!(g.simplices.is_empty() && g.degenerate.is_some());
    assert!(triangulate_nd(&[1.0, f64::NAN], 2).is_err());
    assert!(triangulate_nd(&[1.0, 2.0], 1).is_err());
    assert!(triangulate_nd(&[1.0, 2.0, 3.0], 2).is_err());
    assert!(triangulate_nd(&[], 2).is_err());
}

#[test]
fn dd_agrees_with_2d_lattice_and_6d() {
    // d = 6, a small random set
    let mut r = rng(66);
    let c: Vec<f64> = (0..10 * 6).map(|_| r.gen()).collect();
    let g = triangulate_nd(&c, 6).unwrap();
    check_d(&g);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn prop_small_integer_sets(pts in proptest::collection::vec((0i32..4, 0i32..4, 0i32..4), 1..30)) {
        let p: Vec<Point3> = pts.iter().map(|&(x, y, z)| Point3::new(x as f64, y as f64, z as f64)).collect();
        let d = triangulate_3d(&p).unwrap();
        let c = check(&d, &p);
        let e = triangulate_3d(&shuffled(&p, 9)).unwrap();
        prop_assert_eq!(canonical(&e), c);
        if !d.tets.is_empty() {
            let flat: Vec<f64> = p.iter().flat_map(arr).collect();
            let g = triangulate_nd(&flat, 3).unwrap();
            let gs: BTreeSet<[u32; 4]> = g.simplices.iter().map(|s| sorted([s[0], s[1], s[2], s[3]])).collect();
            let ds: BTreeSet<[u32; 4]> = d.tets.iter().map(|t| sorted(*t)).collect();
            prop_assert_eq!(gs, ds);
        }
    }

    #[test]
    fn prop_dd_small_integer_sets_4d(pts in proptest::collection::vec(proptest::collection::vec(0i32..3, 4), 1..24)) {
        let c: Vec<f64> = pts.iter().flatten().map(|&x| x as f64).collect();
        let g = triangulate_nd(&c, 4).unwrap();
        // every input maps to its vertex
        for (i, &v) in g.vertex_of_input.iter().enumerate() {
            prop_assert_eq!(g.point(v), &c[i * 4..i * 4 + 4]);
        }
        if g.simplices.is_empty() {
            prop_assert!(g.degenerate.is_some());
        } else {
            check_d(&g);
        }
    }

    #[test]
    fn prop_random_float_sets(seed in 0u64..1000, n in 5usize..50) {
        let p = random_points(n, seed);
        let d = triangulate_3d(&p).unwrap();
        check(&d, &p);
    }
}

/// Same tetrahedra as scipy's Qhull on random points (skipped when python3/scipy is absent).
#[test]
fn matches_qhull_when_available() {
    let p = random_points(300, 42);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pts.txt");
    let text: String = p
        .iter()
        .map(|q| format!("{:e} {:e} {:e}\n", q.x, q.y, q.z))
        .collect();
    std::fs::write(&path, text).unwrap();
    let script = "import sys, numpy as np\nfrom scipy.spatial import Delaunay\n\
                  d = Delaunay(np.loadtxt(sys.argv[1]))\n\
                  [print(*sorted(s)) for s in d.simplices.tolist()]";
    let out = std::process::Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(&path)
        .output();
    let Ok(out) = out else {
        eprintln!("python3 not available: skipping the Qhull comparison");
        return;
    };
    if !out.status.success() {
        eprintln!("scipy not available: skipping the Qhull comparison");
        return;
    }
    let qhull: BTreeSet<[u32; 4]> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| {
            let v: Vec<u32> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect();
    let d = triangulate_3d(&p).unwrap();
    let ours: BTreeSet<[u32; 4]> = d.to_input_indices().into_iter().map(sorted).collect();
    assert_eq!(ours, qhull);
}

//! 3D boundary by the shortest Voronoi skeleton (O'Rourke et al. as in Veltkamp §4.3.4, §5.6)
//! through the public entry point `boundary_3d(.., method: VoronoiSkeleton)`: validity
//! (closed genus-0 2-manifold, exact self-intersection check), coverage, the interior
//! tetrahedra, errors on degenerate input, and a property test over random and degenerate
//! sets. The growth itself is tested against its definition and an exhaustive enumeration in
//! `boundary::voronoi_skeleton3`.

use morpho::boundary::{boundary_3d, Boundary3, Options3};
use morpho::geom::Point3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn opts(max_seeds: usize) -> Options3 {
    Options3::voronoi_skeleton(max_seeds)
}

fn ellipsoid(seed: u64, n: usize, ax: [f64; 3]) -> Vec<Point3> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let z: f64 = r.gen_range(-1.0..1.0);
            let t: f64 = r.gen_range(0.0..std::f64::consts::TAU);
            let s = (1.0 - z * z).sqrt();
            Point3::new(ax[0] * s * t.cos(), ax[1] * s * t.sin(), ax[2] * z)
        })
        .collect()
}

fn cube(seed: u64, n: usize) -> Vec<Point3> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| Point3::new(r.gen(), r.gen(), r.gen()))
        .collect()
}

/// Closed, genus 0, no self-intersection, outward, 2V − 4 triangles, the interior
/// tetrahedra's boundary is the boundary and their volume the enclosed volume, `left_out` is
/// exactly the input points not on it, and the skeleton length is reported.
fn assert_valid(pts: &[Point3], b: &Boundary3) {
    assert!(b.closed_manifold, "not a closed manifold");
    assert_eq!(b.genus, Some(0));
    assert!(b.intersections.is_empty(), "{:?}", b.intersections);
    let mesh = morpho::mesh::TriMesh::new(pts.to_vec(), b.triangles.clone());
    let topo = morpho::mesh::analyze_topology(&mesh);
    assert!(topo.consistently_oriented);
    assert!(b.volume > 0.0);
    assert_eq!(b.triangles.len(), 2 * topo.num_used_vertices - 4);
    assert_eq!(b.interior.len(), topo.num_used_vertices - 3);
    assert_eq!(b.iterations + 1, b.interior.len());
    assert!(b.skeleton_length.is_some_and(|l| l >= 0.0));
    // the faces of the interior tetrahedra used once are exactly the boundary triangles
    let mut count = std::collections::HashMap::new();
    let mut vol = 0.0;
    for t in &b.interior {
        let p = t.map(|v| pts[v as usize]);
        vol += (p[1] - p[0])
            .dot(&(p[2] - p[0]).cross(&(p[3] - p[0])))
            .abs()
            / 6.0;
        for f in [
            [t[0], t[1], t[2]],
            [t[0], t[1], t[3]],
            [t[0], t[2], t[3]],
            [t[1], t[2], t[3]],
        ] {
            let mut s = f;
            s.sort_unstable();
            *count.entry(s).or_insert(0) += 1;
        }
    }
    let mut once: Vec<[u32; 3]> = count
        .into_iter()
        .filter(|&(_, c)| c == 1)
        .map(|(f, _)| f)
        .collect();
    once.sort_unstable();
    let mut tris: Vec<[u32; 3]> = b
        .triangles
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect();
    tris.sort_unstable();
    assert_eq!(once, tris);
    assert!((vol - b.volume).abs() <= 1e-9 * vol.max(1e-300));
    let d = morpho::delaunay::triangulate_3d(pts).unwrap();
    let mut on = vec![false; pts.len()];
    for t in &b.triangles {
        for &v in t {
            on[v as usize] = true;
        }
    }
    let expect: Vec<u32> = (0..pts.len() as u32)
        .filter(|&i| !on[d.input_of_vertex[d.vertex_of_input[i as usize] as usize] as usize])
        .collect();
    assert_eq!(expect, b.left_out);
    assert_eq!(b.all_on_boundary, b.left_out.is_empty());
}

#[test]
fn random_sphere_and_ellipsoid_sets_give_valid_boundaries() {
    let mut complete = 0;
    let mut total = 0;
    for seed in 0..6u64 {
        for pts in [
            cube(seed, 30 + 10 * seed as usize),
            ellipsoid(seed, 40, [1.0, 1.0, 1.0]),
            ellipsoid(seed + 50, 60, [3.0, 1.5, 0.6]),
        ] {
            let b = boundary_3d(&pts, &opts(200)).unwrap();
            assert_valid(&pts, &b);
            total += 1;
            complete += b.all_on_boundary as usize;
        }
    }
    eprintln!("{complete} of {total} complete");
    assert!(complete * 2 >= total, "only {complete} of {total} complete");
}

#[test]
fn more_seeds_never_give_a_worse_tree() {
    for seed in 0..4u64 {
        let pts = ellipsoid(seed + 7, 35, [2.0, 1.0, 1.0]);
        let few = boundary_3d(&pts, &opts(3)).unwrap();
        let all = boundary_3d(&pts, &opts(usize::MAX)).unwrap();
        assert_valid(&pts, &few);
        assert_valid(&pts, &all);
        assert!(all.left_out.len() <= few.left_out.len());
        if all.left_out.len() == few.left_out.len() {
            assert!(all.skeleton_length.unwrap() <= few.skeleton_length.unwrap());
        }
    }
}

#[test]
fn degenerate_input_is_a_clear_error_or_valid() {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let bad: Vec<Vec<Point3>> = vec![
        vec![],
        vec![p(0., 0., 0.)],
        vec![p(0., 0., 0.), p(1., 0., 0.), p(0., 1., 0.)],
        // coplanar
        (0..10)
            .map(|i| p(i as f64, (i * i % 7) as f64, 0.0))
            .collect(),
        // collinear
        (0..6)
            .map(|i| p(i as f64, 2.0 * i as f64, 3.0 * i as f64))
            .collect(),
        // four copies of one point and a second point
        vec![p(1., 1., 1.); 4]
            .into_iter()
            .chain([p(0., 0., 0.)])
            .collect(),
    ];
    for pts in &bad {
        let e = boundary_3d(pts, &opts(10)).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("no closed surface") || m.contains("no points"),
            "{e}"
        );
    }
    let nan = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(0., 1., 0.),
        p(0., 0., f64::NAN),
    ];
    assert!(boundary_3d(&nan, &opts(10)).is_err());
    // duplicates of a tetrahedron's corners: valid, copies count as on the boundary
    let mut pts = vec![p(0., 0., 0.), p(1., 0., 0.), p(0., 1., 0.), p(0., 0., 1.)];
    pts.extend(pts.clone());
    pts.push(p(0.2, 0.2, 0.2));
    let b = boundary_3d(&pts, &opts(10)).unwrap();
    assert_valid(&pts, &b);
    assert!(b.all_on_boundary);
    // (keep triangles: Method3::VoronoiSkeleton has no such parameter; the CLI refuses
    // `--keep` with this method, tested in morpho-cli)
}

mod prop {
    use super::*;
    use proptest::prelude::*;

    fn pts3() -> impl Strategy<Value = Vec<Point3>> {
        prop_oneof![
            proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 0..30),
            // a small lattice: duplicates, coplanar and cospherical subsets, flat sets
            proptest::collection::vec((0i32..3, 0i32..3, 0i32..2), 0..30).prop_map(|v| v
                .into_iter()
                .map(|(a, b, c)| (a as f64, b as f64, c as f64))
                .collect()),
        ]
        .prop_map(|v| {
            v.into_iter()
                .map(|(x, y, z)| Point3::new(x, y, z))
                .collect()
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn valid_or_the_documented_error(pts in pts3(), seeds in 1usize..20) {
            let r = boundary_3d(&pts, &opts(seeds));
            let Ok(d) = morpho::delaunay::triangulate_3d(&pts) else {
                prop_assert!(pts.is_empty());
                prop_assert!(r.unwrap_err().to_string().contains("no points"));
                return Ok(());
            };
            match r {
                Ok(b) => {
                    prop_assert!(!d.tets.is_empty());
                    assert_valid(&pts, &b);
                }
                Err(e) => {
                    prop_assert!(d.tets.is_empty());
                    prop_assert!(e.to_string().contains("no closed surface"));
                }
            }
        }
    }
}

//! Hamann's volume views (H §2.2–2.3, issue 22 part 1): the geometry each view promises,
//! checked against closed forms and brute force, and bad input refused or noted.
use morpho::render::{
    height_surface_mesh, render_view, subbox_starts, transparency_rectangle_count,
    transparency_view_mesh, trilinear, Axis, Formula, HeightStyle, Source, View, ViewOptions,
};
use morpho::volume::Volume;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn small_opts() -> ViewOptions {
    let mut o = ViewOptions::default();
    o.render.width = 96;
    o.render.height = 72;
    o
}

/// Boxes plus gaps tile [lo, hi] exactly: q boxes of edge Δ, q−1 gaps of αΔ, the last far
/// face at hi to 1e-12 (relative), consecutive starts (1+α)Δ apart.
#[test]
fn sub_boxes_and_gaps_tile_the_domain() {
    for &(lo, hi) in &[(0.0, 39.0), (-1.0, 1.0), (1e3, 1e3 + 0.25)] {
        for q in 1..=9 {
            for &alpha in &[0.0, 0.25, 1.0, 3.5] {
                let (s, d) = subbox_starts(lo, hi, q, alpha);
                assert_eq!(s.len(), q);
                assert_eq!(s[0], lo);
                let total = q as f64 * d + (q as f64 - 1.0) * alpha * d;
                let tol = 1e-12 * (hi - lo).abs().max(lo.abs());
                assert!((total - (hi - lo)).abs() <= tol);
                assert!((s[q - 1] + d - hi).abs() <= tol, "q {q} α {alpha}");
                for r in 1..q {
                    assert!((s[r] - s[r - 1] - (1.0 + alpha) * d).abs() <= tol);
                }
            }
        }
    }
}

/// The trilinear interpolant reproduces every trilinear function (exactly representable
/// samples: integer coefficients on an integer grid).
#[test]
fn trilinear_interpolation_is_exact_for_trilinear_functions() {
    let f = |x: f64, y: f64, z: f64| {
        1.0 + 2.0 * x - y + 3.0 * z + x * y - 2.0 * x * z + y * z + x * y * z
    };
    let v = Volume::from_fn([5, 4, 6], [0.0; 3], [4.0, 3.0, 5.0], f);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..500 {
        let mut u = || rng.gen::<f64>();
        let p = [u() * 4.0, u() * 3.0, u() * 5.0];
        let want = f(p[0], p[1], p[2]);
        let got = trilinear(&v, p);
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{p:?}: {got} vs {want}"
        );
    }
}

/// The transparency view draws the closed-form number of rectangles (two triangles each);
/// the closed form equals a brute-force count of the grid's faces.
#[test]
fn transparency_rectangles_match_the_closed_form() {
    for n in [[1, 1, 1], [2, 3, 4], [5, 1, 2], [7, 7, 7]] {
        let brute: usize = (0..3)
            .map(|a| {
                (0..3)
                    .map(|b| if a == b { n[b] + 1 } else { n[b] })
                    .product::<usize>()
            })
            .sum();
        assert_eq!(transparency_rectangle_count(n), brute);
        let v = Volume::from_fn(
            n.map(|c| c + 1),
            [0.0; 3],
            n.map(|c| c as f64),
            |x, y, z| x + y * z,
        );
        let (m, cells) = transparency_view_mesh(&Source::Volume(&v), None).unwrap();
        assert_eq!(cells, n);
        assert_eq!(m.triangles.len(), 2 * brute, "{n:?}");
    }
}

/// Height surfaces use Hamann's I₁/I₂ triangulation: 2kl triangles, heights in [0, 1].
#[test]
fn height_surfaces_have_two_k_l_triangles() {
    let v = Volume::from_fn([9, 9, 9], [0.0; 3], [1.0; 3], |x, y, z| x * x + y - z);
    for (k, l) in [(1, 1), (3, 5), (16, 16)] {
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            let m = height_surface_mesh(&Source::Volume(&v), axis, 0.5, k, l, None).unwrap();
            assert_eq!(m.triangles.len(), 2 * k * l);
            assert!(m.positions.iter().all(|p| (0.0..=1.0).contains(&p.z)));
        }
    }
    let f = Source::Formula {
        formula: Formula::HamannExp,
        grid: 8,
    };
    let m = height_surface_mesh(&f, Axis::Z, 19.5, 12, 7, None).unwrap();
    assert_eq!(m.triangles.len(), 2 * 12 * 7);
}

/// Every view renders the seed's formula example; the subdivision draws q_x q_y q_z boxes.
#[test]
fn every_view_renders_and_counts_its_primitives() {
    let src = Source::Formula {
        formula: Formula::HamannExp,
        grid: 8,
    };
    let views = [
        View::Subdivision {
            q: [3, 4, 2],
            alpha: [1.0, 0.5, 0.0],
            k: 1,
            links: true,
        },
        View::Transparency { n: None, t: 0.5 },
        View::Slices,
        View::Heights {
            k: 6,
            style: HeightStyle::Surface,
        },
        View::Heights {
            k: 6,
            style: HeightStyle::Network,
        },
    ];
    for v in &views {
        let pic = render_view(&src, v, &small_opts()).unwrap();
        assert!(pic.image.width > 0 && pic.triangles > 0 || matches!(v, View::Slices));
        if let View::Subdivision { q, .. } = v {
            assert_eq!(pic.primitives, q.iter().product::<usize>());
        }
    }
}

/// Bad volumes: one sample along an axis and all-NaN are typed errors for the 3D views; a
/// constant volume gives a picture with a note — never a panic.
#[test]
fn degenerate_volumes_are_refused_or_noted() {
    let flat = Volume::from_fn([4, 1, 4], [0.0; 3], [1.0, 0.0, 1.0], |x, _, z| x + z);
    let mut nan = Volume::from_fn([3, 3, 3], [0.0; 3], [1.0; 3], |_, _, _| 0.0);
    nan.data.iter_mut().for_each(|x| *x = f32::NAN);
    let sub = View::Subdivision {
        q: [2; 3],
        alpha: [1.0; 3],
        k: 1,
        links: false,
    };
    for v in [&flat, &nan] {
        for view in [&sub, &View::Transparency { n: None, t: 0.5 }] {
            assert!(render_view(&Source::Volume(v), view, &small_opts()).is_err());
        }
    }
    let c = Volume::from_fn([3, 3, 3], [0.0; 3], [1.0; 3], |_, _, _| 2.0);
    let pic = render_view(&Source::Volume(&c), &sub, &small_opts()).unwrap();
    assert!(!pic.notes.is_empty(), "a constant volume should be noted");
}

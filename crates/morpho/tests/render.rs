//! Pictures: rasterizer (z-buffer, silhouettes, shading, determinism), SVG structure, volume
//! slices. Meshes are built inline so these tests do not depend on the generators or readers.

mod common;
use morpho::geom::{Aabb2, Point2, Point3};
use morpho::mesh::{Polygon, Polyline, Property, ScalarKind, Shapes2, TriMesh};
use morpho::render::Colormap;
use morpho::render::Image;
use morpho::render::{self, Fill, Stroke, Svg};
use morpho::render::{
    middle, orthogonal_slices, slice_height_mesh, slice_image, Axis, SliceOptions, Upsample,
};
use morpho::render::{
    reflection_coordinate, render_mesh, render_mesh_stats, Projection, ReflectionLines,
    RenderOptions, Scalars, Shading, UpAxis,
};
use morpho::volume::Volume;
use std::f64::consts::PI;

/// UV sphere of radius `r` around `c`, outward counter-clockwise triangles.
fn uv_sphere(c: [f64; 3], r: f64, nu: usize, nv: usize) -> TriMesh {
    let mut pos = vec![Point3::new(c[0], c[1], c[2] + r)];
    for j in 1..nv {
        let th = PI * j as f64 / nv as f64;
        for i in 0..nu {
            let ph = 2.0 * PI * i as f64 / nu as f64;
            pos.push(Point3::new(
                c[0] + r * th.sin() * ph.cos(),
                c[1] + r * th.sin() * ph.sin(),
                c[2] + r * th.cos(),
            ));
        }
    }
    pos.push(Point3::new(c[0], c[1], c[2] - r));
    let south = (pos.len() - 1) as u32;
    let ring = |j: usize, i: usize| (1 + (j - 1) * nu + (i % nu)) as u32;
    let mut tris = Vec::new();
    for i in 0..nu {
        tris.push([0, ring(1, i), ring(1, i + 1)]);
        tris.push([south, ring(nv - 1, i + 1), ring(nv - 1, i)]);
    }
    for j in 1..nv - 1 {
        for i in 0..nu {
            let (a, b, c2, d) = (
                ring(j, i),
                ring(j, i + 1),
                ring(j + 1, i),
                ring(j + 1, i + 1),
            );
            tris.push([a, c2, d]);
            tris.push([a, d, b]);
        }
    }
    TriMesh::new(pos, tris)
}

/// Torus around the z axis.
fn torus(big: f64, small: f64, nu: usize, nv: usize) -> TriMesh {
    let mut pos = Vec::new();
    for i in 0..nu {
        let u = 2.0 * PI * i as f64 / nu as f64;
        for j in 0..nv {
            let v = 2.0 * PI * j as f64 / nv as f64;
            let rr = big + small * v.cos();
            pos.push(Point3::new(rr * u.cos(), rr * u.sin(), small * v.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut tris = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

fn icosahedron() -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let v = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let f = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    TriMesh::new(v.iter().map(|p| Point3::new(p[0], p[1], p[2])).collect(), f)
}

/// Default options on a transparent background, so that coverage is alpha > 0.
fn clear() -> RenderOptions {
    RenderOptions {
        background: [255, 255, 255, 0],
        ..Default::default()
    }
}

fn covered(img: &Image) -> usize {
    img.rgba.chunks(4).filter(|p| p[3] > 0).count()
}

fn ortho_front(w: u32, h: u32) -> RenderOptions {
    RenderOptions {
        width: w,
        height: h,
        azimuth_deg: 0.0,
        elevation_deg: 0.0,
        projection: Projection::Orthographic,
        shading: Shading::Flat,
        supersample: 1,
        margin: 0.0,
        ..clear()
    }
}

#[test]
fn icosahedron_is_closed_and_outward() {
    let m = icosahedron();
    assert!(m.signed_volume() > 0.0);
    assert!(uv_sphere([0.0; 3], 1.0, 16, 8).signed_volume() > 0.0);
    assert!(torus(2.0, 0.5, 16, 8).signed_volume() > 0.0);
}

#[test]
fn zbuffer_small_triangle_in_front_covers_big_one() {
    // Big red square at z = 0, small blue triangle at z = 0.5 (nearer to a camera on +z),
    // drawn in both orders.
    let big = [
        Point3::new(-1.0, -1.0, 0.0),
        Point3::new(1.0, -1.0, 0.0),
        Point3::new(1.0, 1.0, 0.0),
        Point3::new(-1.0, 1.0, 0.0),
    ];
    let small = [
        Point3::new(-0.2, -0.2, 0.5),
        Point3::new(0.2, -0.2, 0.5),
        Point3::new(0.0, 0.2, 0.5),
    ];
    for small_first in [false, true] {
        let mut pos = big.to_vec();
        pos.extend_from_slice(&small);
        let mut tris = vec![[0, 1, 2], [0, 2, 3]];
        let st = [4, 5, 6];
        if small_first {
            tris.insert(0, st);
        } else {
            tris.push(st);
        }
        let mut m = TriMesh::new(pos, tris);
        let tri_of_small = if small_first { 0 } else { 2 };
        let mut fv = vec![0.0; 3];
        fv[tri_of_small] = 1.0;
        m.face_props.push(Property {
            name: "part".into(),
            kind: ScalarKind::F64,
            values: fv.clone(),
        });
        let o = RenderOptions {
            scalars: Some(Scalars {
                values: fv,
                per_face: true,
                colormap: Colormap::Coolwarm,
                range: Some((0.0, 1.0)),
            }),
            ..ortho_front(100, 100)
        };
        let img = render_mesh(&m, &o);
        // Centre pixel: the small triangle (red end of coolwarm, value 1), lit head-on.
        let c = img.get(50, 50);
        assert!(c[0] > c[2], "centre {c:?}");
        // Corner: big square (blue end).
        let k = img.get(5, 5);
        assert!(k[2] > k[0], "corner {k:?}");
        // Just outside the small triangle's base: blue.
        let o2 = img.get(50, 65);
        assert!(o2[2] > o2[0], "below {o2:?}");
    }
}

#[test]
fn transparency_blends_back_to_front() {
    // Front square (value 1 → white) listed first, back square (value 0 → black) second; red
    // background; t = 0.5. Back to front: red → (0.5 black + 0.5 red) → (0.5 white + 0.5 that),
    // the closed form (1 − t) c_front + t (1 − t) c_back + t² bg = 0.5·255 + 0.25·0 + 0.25·255
    // = 191.25 in red and 127.5 in green and blue, rounded once: (191, 128, 128). (Rounding
    // after every layer, as the renderer did before, gave 192: the back layer's 127.5 rounded
    // up to 128, then 0.5·255 + 0.5·128 = 191.5 → 192.)
    let sq = |z: f64| {
        vec![
            Point3::new(-1.0, -1.0, z),
            Point3::new(1.0, -1.0, z),
            Point3::new(1.0, 1.0, z),
            Point3::new(-1.0, 1.0, z),
        ]
    };
    let mut pos = sq(0.5);
    pos.extend(sq(0.0));
    let m = TriMesh::new(pos, vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]);
    let o = RenderOptions {
        transparency: Some(0.5),
        background: [255, 0, 0, 255],
        scalars: Some(Scalars {
            values: vec![1.0, 1.0, 0.0, 0.0],
            per_face: true,
            colormap: Colormap::Greys,
            range: Some((0.0, 1.0)),
        }),
        ..ortho_front(20, 20)
    };
    let img = render_mesh(&m, &o);
    assert_eq!(img.get(10, 10), [191, 128, 128, 255]);
    // t = 0: opaque painter's order, the front square wins.
    let img = render_mesh(
        &m,
        &RenderOptions {
            transparency: Some(0.0),
            ..o.clone()
        },
    );
    assert_eq!(img.get(10, 10), [255, 255, 255, 255]);
    // t = 1: invisible.
    let img = render_mesh(
        &m,
        &RenderOptions {
            transparency: Some(1.0),
            ..o
        },
    );
    assert_eq!(img.get(10, 10), [255, 0, 0, 255]);
}

/// `n` parallel squares, layer 0 in front, each with its own per-face grey level `values[i]`
/// (Greys map over 0..255). In the 17×16 front view no sample centre lies on the squares'
/// diagonals; in the 16×16 view of `shared_diagonal_samples_are_blended_once` sixteen do.
fn stack(values: &[f64]) -> (TriMesh, Vec<f64>) {
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    let mut fv = Vec::new();
    for (i, &v) in values.iter().enumerate() {
        let z = -(i as f64);
        let b = pos.len() as u32;
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            pos.push(Point3::new(x, y, z));
        }
        tris.push([b, b + 1, b + 2]);
        tris.push([b, b + 2, b + 3]);
        fv.extend([v, v]);
    }
    (TriMesh::new(pos, tris), fv)
}

/// The [`stack`] of `values` alpha-blended with transparency `t` in a `w`×`h` front view on a
/// transparent black background, with the closed form of a pixel the squares cover: grey level
/// `Σ (1 − t) tⁱ grey(v_i)` and alpha `255 (1 − tⁿ)`.
fn blend_stack(
    values: &[f64],
    t: f64,
    w: u32,
    h: u32,
) -> (morpho::render::Image, morpho::render::RenderStats, f64, f64) {
    let (m, fv) = stack(values);
    let o = RenderOptions {
        transparency: Some(t),
        background: [0, 0, 0, 0],
        scalars: Some(Scalars {
            values: fv,
            per_face: true,
            colormap: Colormap::Greys,
            range: Some((0.0, 255.0)),
        }),
        ..ortho_front(w, h)
    };
    let (img, st) = render_mesh_stats(&m, &o);
    // Greys: 0 → black, 1 → white (an 8-bit map, so the level is the value rounded).
    let grey = |v: f64| Colormap::Greys.color(v / 255.0)[0] as f64;
    let (mut want, mut tr) = (0.0, 1.0);
    for &v in values {
        want += tr * (1.0 - t) * grey(v);
        tr *= t;
    }
    (img, st, want, 255.0 * (1.0 - tr))
}

/// Alpha blending of many layers equals the closed form `Σ (1 − t) tⁱ c_i + tⁿ bg` (all
/// layers, exact arithmetic) to one level, for every t, although the renderer stops taking
/// layers once they cannot matter. The faint layers (4 levels of 255 at t = 0.99: each adds
/// 0.04) are the case that rounding after every layer got wrong: it never left the
/// background (0) while the closed form reaches 40 (1 − 0.99³⁰⁰) = 38.0.
#[test]
fn transparency_matches_the_closed_form_over_many_layers() {
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut cases: Vec<(f64, Vec<f64>)> = Vec::new();
    for &t in &[0.0, 0.3, 0.5, 0.8, 0.95] {
        for n in [1, 2, 5, 9, 10, 40] {
            cases.push((t, (0..n).map(|_| (next() * 255.0).round()).collect()));
        }
    }
    cases.push((0.99, vec![40.0; 300]));
    for (t, values) in cases {
        let (img, st, want, alpha) = blend_stack(&values, t, 17, 16);
        for (i, p) in img.rgba.chunks(4).enumerate() {
            if !(1..16).contains(&(i % 17)) {
                continue; // the squares' left and right edges
            }
            assert!(
                (p[0] as f64 - want).abs() <= 1.0 && (p[3] as f64 - alpha).abs() <= 1.0,
                "t {t}, {} layers: {p:?}, closed form {want:.2} / alpha {alpha:.2}",
                values.len()
            );
        }
        // Early termination: no sample takes a layer once t^i ≤ 1/512.
        let needed = (0..=values.len())
            .find(|&i| t.powi(i as i32) <= 1.0 / 512.0)
            .unwrap_or(values.len())
            .min(values.len());
        assert!(
            st.composited <= (needed * 17 * 16) as u64,
            "t {t}: {} samples composited, {} layers needed",
            st.composited,
            needed
        );
    }
}

/// Alpha blending gives the same bytes with 1, 2 and 3 threads (bands are independent; the
/// back-to-front sort is a total order).
#[test]
fn transparency_is_deterministic_across_thread_counts() {
    let v = Volume::from_fn([13, 11, 9], [0.0; 3], [39.0, 30.0, 20.0], |x, y, z| {
        (0.2 * x).sin() + (0.15 * y).cos() * z * 0.1
    });
    let gm = morpho::render::grid_planes_mesh(&v, [1, 1, 1]).unwrap();
    let gv = gm.vertex_prop("value").unwrap().values.clone();
    for t in [0.5, 0.9] {
        let o = RenderOptions {
            width: 200,
            height: 150,
            up: UpAxis::Z,
            transparency: Some(t),
            scalars: Some(Scalars {
                values: gv.clone(),
                per_face: false,
                colormap: Colormap::Viridis,
                range: None,
            }),
            ..Default::default()
        };
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| render_mesh_stats(&gm, &o))
        };
        let (a, sa) = run(1);
        for threads in [2, 3] {
            let (b, sb) = run(threads);
            assert!(a == b, "t {t}: 1 and {threads} threads differ");
            assert_eq!(sa.composited, sb.composited);
        }
        assert!(sa.composited > 0);
    }
}

#[test]
fn zbuffer_behind_is_hidden_in_perspective() {
    // The small triangle behind the big square must not show (perspective camera).
    let pos = vec![
        Point3::new(-1.0, -1.0, 0.0),
        Point3::new(1.0, -1.0, 0.0),
        Point3::new(1.0, 1.0, 0.0),
        Point3::new(-1.0, 1.0, 0.0),
        Point3::new(-0.2, -0.2, -0.5),
        Point3::new(0.2, -0.2, -0.5),
        Point3::new(0.0, 0.2, -0.5),
    ];
    let m = TriMesh::new(pos, vec![[4, 5, 6], [0, 1, 2], [0, 2, 3]]);
    let o = RenderOptions {
        projection: Projection::Perspective { fov_deg: 40.0 },
        color: [0, 200, 0],
        back_color: None,
        scalars: None,
        ..ortho_front(60, 60)
    };
    let img = render_mesh(&m, &o);
    // Every covered pixel has the same flat colour (the square faces the camera uniformly in
    // flat shading); the hidden triangle would not change that, but its back would be dimmer.
    let centre = img.get(30, 30);
    let corner = img.get(20, 40);
    assert_eq!(centre, corner);
}

#[test]
fn sphere_silhouette_area_is_pi_r_squared() {
    let m = uv_sphere([3.0, -2.0, 7.0], 2.5, 96, 48);
    for ss in [1, 3] {
        let o = RenderOptions {
            margin: 0.1,
            supersample: ss,
            ..ortho_front(201, 201)
        };
        let img = render_mesh(&m, &o);
        // Sphere fits the box, so its silhouette radius is 0.8 * 201 / 2 pixels.
        let r = 0.8 * 201.0 / 2.0;
        // Coverage with anti-aliasing: alpha sums partial pixels.
        let area = img.rgba.chunks(4).map(|p| p[3] as f64 / 255.0).sum::<f64>();
        let expect = PI * r * r;
        let rel = (area - expect).abs() / expect;
        assert!(rel < 0.02, "area {area} vs {expect} ({rel})");
    }
    // Perspective: still a disc (round), area between the inscribed polygon and the disc.
    let o = RenderOptions {
        projection: Projection::Perspective { fov_deg: 30.0 },
        elevation_deg: 30.0,
        margin: 0.1,
        ..ortho_front(201, 201)
    };
    let img = render_mesh(&m, &o);
    let area = covered(&img) as f64;
    let r = 0.8 * 201.0 / 2.0;
    assert!((area - PI * r * r).abs() / (PI * r * r) < 0.03, "{area}");
}

#[test]
fn flat_and_smooth_differ_and_smooth_is_smoother() {
    let m = uv_sphere([0.0; 3], 1.0, 12, 6);
    let flat = render_mesh(&m, &ortho_front(120, 120));
    let smooth = render_mesh(
        &m,
        &RenderOptions {
            shading: Shading::Smooth,
            ..ortho_front(120, 120)
        },
    );
    assert_ne!(flat, smooth);
    // Same silhouette.
    assert_eq!(covered(&flat), covered(&smooth));
    // Total variation along the middle row: flat shading jumps at facet edges; smooth varies
    // gradually, so the largest jump between neighbours is smaller.
    let max_jump = |img: &Image| {
        (20..99)
            .map(|x| (img.get(x, 60)[1] as i32 - img.get(x + 1, 60)[1] as i32).abs())
            .max()
            .unwrap()
    };
    assert!(
        max_jump(&smooth) < max_jump(&flat),
        "{} {}",
        max_jump(&smooth),
        max_jump(&flat)
    );
}

#[test]
fn mesh_normals_are_used_when_present() {
    let mut m = uv_sphere([0.0; 3], 1.0, 24, 12);
    let o = RenderOptions {
        shading: Shading::Smooth,
        ..ortho_front(80, 80)
    };
    let a = render_mesh(&m, &o);
    // Exact sphere normals: close to the area-weighted ones.
    m.normals = Some(m.positions.iter().map(|p| p.coords.normalize()).collect());
    let b = render_mesh(&m, &o);
    let diff: u64 = a
        .rgba
        .iter()
        .zip(&b.rgba)
        .map(|(x, y)| (*x as i64 - *y as i64).unsigned_abs())
        .sum();
    assert!(diff > 0);
    assert!((diff as f64) / (a.rgba.len() as f64) < 3.0, "{diff}");
    // Inverted normals shade differently (dark where the headlight hits).
    m.normals = Some(m.positions.iter().map(|p| -p.coords.normalize()).collect());
    let c = render_mesh(&m, &o);
    assert_ne!(b, c);
}

#[test]
fn reflection_lines_on_a_sphere_follow_the_reflected_ray() {
    // Normal facing the eye: the ray comes straight back, angle 0; tilted by α about x: 2α.
    assert_eq!(
        reflection_coordinate([0.0, 0.0, -1.0], [0.0, 0.0, 1.0]),
        0.0
    );
    let a = 0.3f64;
    let t = reflection_coordinate([0.0, 0.0, -1.0], [0.0, a.sin(), a.cos()]);
    assert!((t - 2.0 * a).abs() < 1e-15, "{t}");
    // Exact sphere normals, orthographic front view: the stripes along the vertical centre
    // line are where |θ·lines/π − round| < width/2 with θ = 2 asin(y).
    let mut m = uv_sphere([0.0; 3], 1.0, 96, 48);
    m.normals = Some(m.positions.iter().map(|p| p.coords.normalize()).collect());
    let rl = ReflectionLines::default();
    let o = RenderOptions {
        shading: Shading::Smooth,
        reflection_lines: Some(rl),
        ..ortho_front(201, 201)
    };
    let img = render_mesh(&m, &o);
    let (mut agree, mut total, mut dark) = (0, 0, 0);
    for py in 10..191u32 {
        let y = 1.0 - (py as f64 + 0.5) / 100.5;
        let th = 2.0 * y.asin();
        let u = th * rl.lines as f64 / PI;
        let predicted = (u - u.round()).abs() < 0.5 * rl.width;
        // skip samples next to a stripe border
        if ((u - u.round()).abs() - 0.5 * rl.width).abs() < 0.05 {
            continue;
        }
        let px = img.get(100, py);
        let is_dark = px[0] == rl.color[0] && px[1] == rl.color[1] && px[2] == rl.color[2];
        total += 1;
        dark += usize::from(is_dark);
        agree += usize::from(is_dark == predicted);
    }
    assert!(dark > 20 && dark < total - 20, "{dark} of {total}");
    assert!(agree as f64 >= 0.97 * total as f64, "{agree} of {total}");
    // Without reflection lines no sample has the stripe colour.
    let plain = render_mesh(
        &m,
        &RenderOptions {
            reflection_lines: None,
            ..o
        },
    );
    assert!(!plain.rgba.chunks(4).any(|p| p[..3] == rl.color));
}

#[test]
fn deterministic_output() {
    let m = torus(2.0, 0.7, 40, 20);
    let o = RenderOptions {
        width: 160,
        height: 120,
        wireframe: true,
        ..clear()
    };
    let a = render_mesh(&m, &o);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let b = pool.install(|| render_mesh(&m, &o));
    assert_eq!(a, b);
    let mut pa = Vec::new();
    let mut pb = Vec::new();
    a.write_png(&mut pa).unwrap();
    b.write_png(&mut pb).unwrap();
    assert_eq!(pa, pb);
}

#[test]
fn empty_mesh_is_background() {
    let o = RenderOptions {
        width: 30,
        height: 20,
        background: [10, 20, 30, 255],
        ..clear()
    };
    let img = render_mesh(&TriMesh::default(), &o);
    assert_eq!((img.width, img.height), (30, 20));
    assert!(img.rgba.chunks(4).all(|p| p == [10, 20, 30, 255]));
    // Points only, no triangles: also background.
    let m = TriMesh::new(vec![Point3::origin()], vec![]);
    assert_eq!(render_mesh(&m, &o), img);
    // Zero-size request is clamped, not a panic.
    let img = render_mesh(
        &icosahedron(),
        &RenderOptions {
            width: 0,
            height: 0,
            ..clear()
        },
    );
    assert_eq!((img.width, img.height), (1, 1));
}

#[test]
fn huge_tiny_and_nan_coordinates() {
    let base = render_mesh(
        &icosahedron(),
        &RenderOptions {
            width: 64,
            height: 64,
            ..clear()
        },
    );
    for s in [1e-300, 1e-9, 1e9, 1e300] {
        let mut m = icosahedron();
        for p in &mut m.positions {
            *p = Point3::from(p.coords * s);
        }
        let img = render_mesh(
            &m,
            &RenderOptions {
                width: 64,
                height: 64,
                ..clear()
            },
        );
        assert!(covered(&img) > 1000, "scale {s}");
        let diff = img
            .rgba
            .iter()
            .zip(&base.rgba)
            .filter(|(a, b)| (**a as i32 - **b as i32).abs() > 2)
            .count();
        assert!(diff < 40, "scale {s}: {diff} bytes differ");
    }
    // Far from the origin.
    let mut m = icosahedron();
    for p in &mut m.positions {
        p.x += 1e12;
    }
    assert!(
        covered(&render_mesh(
            &m,
            &RenderOptions {
                width: 64,
                height: 64,
                ..clear()
            }
        )) > 1000
    );
    // A NaN vertex: its triangles are skipped, the rest drawn.
    let mut m = icosahedron();
    m.positions[0].x = f64::NAN;
    let (img, st) = render_mesh_stats(
        &m,
        &RenderOptions {
            width: 64,
            height: 64,
            ..clear()
        },
    );
    assert_eq!(st.invalid, 5);
    assert!(covered(&img) > 1000);
    // Degenerate: all triangles collapsed to a point or a line.
    let m = TriMesh::new(vec![Point3::new(1.0, 1.0, 1.0); 3], vec![[0, 1, 2]]);
    let (img, st) = render_mesh_stats(
        &m,
        &RenderOptions {
            width: 16,
            height: 16,
            ..clear()
        },
    );
    assert_eq!(st.degenerate, 1);
    assert_eq!(covered(&img), 0);
    let m = TriMesh::new(
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
        ],
        vec![[0, 1, 2]],
    );
    let img = render_mesh(
        &m,
        &RenderOptions {
            width: 16,
            height: 16,
            ..clear()
        },
    );
    assert_eq!(covered(&img), 0);
}

#[test]
fn vertex_scalars_colour_by_height() {
    let m = uv_sphere([0.0; 3], 1.0, 32, 16);
    let z: Vec<f64> = m.positions.iter().map(|p| p.z).collect();
    let o = RenderOptions {
        up: UpAxis::Z,
        scalars: Some(Scalars {
            values: z,
            per_face: false,
            colormap: Colormap::Viridis,
            range: None,
        }),
        ..ortho_front(100, 100)
    };
    let img = render_mesh(&m, &o);
    // z up: top of the image is high z (yellow: red+green high), bottom low (purple).
    let top = img.get(50, 8);
    let bot = img.get(50, 92);
    assert!(top[1] > 120 && top[0] > top[2], "top {top:?}");
    assert!(bot[2] > bot[1], "bottom {bot:?}");
    // Wrong length: ignored (plain colour), no panic.
    let o2 = RenderOptions {
        scalars: Some(Scalars {
            values: vec![1.0; 3],
            per_face: false,
            colormap: Colormap::Viridis,
            range: None,
        }),
        ..o.clone()
    };
    let plain = render_mesh(
        &m,
        &RenderOptions {
            scalars: None,
            ..o.clone()
        },
    );
    assert_eq!(render_mesh(&m, &o2), plain);
}

#[test]
fn wireframe_draws_edges() {
    let m = icosahedron();
    let o = ortho_front(120, 120);
    let a = render_mesh(&m, &o);
    let b = render_mesh(
        &m,
        &RenderOptions {
            wireframe: true,
            wire_color: [255, 0, 0],
            ..o
        },
    );
    assert_eq!(covered(&a), covered(&b));
    let red = b
        .rgba
        .chunks(4)
        .filter(|p| p[0] == 255 && p[1] == 0)
        .count();
    assert!(red > 300 && red < covered(&b) / 2, "{red}");
}

// ---------------------------------------------------------------- SVG

/// Checks that tags balance and counts elements by name.
fn xml_check(s: &str) -> std::collections::HashMap<String, usize> {
    let mut counts = std::collections::HashMap::new();
    let mut stack: Vec<String> = Vec::new();
    let mut rest = s;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        let j = rest.find('>').expect("unclosed <");
        let tag = &rest[..j];
        rest = &rest[j + 1..];
        if tag.starts_with('?') {
            continue;
        }
        assert!(!tag.contains('<'), "bad tag {tag}");
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name), "unbalanced");
            continue;
        }
        let name: String = tag.chars().take_while(|c| c.is_alphanumeric()).collect();
        // Attributes: quotes balanced.
        assert_eq!(tag.matches('"').count() % 2, 0, "{tag}");
        *counts.entry(name.clone()).or_insert(0) += 1;
        if !tag.ends_with('/') {
            stack.push(name);
        }
    }
    assert!(stack.is_empty(), "unclosed: {stack:?}");
    counts
}

#[test]
fn svg_counts_and_balance() {
    let pts: Vec<Point2> = (0..50)
        .map(|i| Point2::new((i as f64).cos() * i as f64, (i as f64 * 0.7).sin()))
        .collect();
    let c = xml_check(&render::points_svg(&pts));
    assert_eq!(c["circle"], 50);
    assert_eq!(c["svg"], 1);

    let tris: Vec<[u32; 3]> = (0..48)
        .map(|i| [i, i + 1, i + 2])
        .chain([[0, 1, 999]])
        .collect();
    let c = xml_check(&render::triangulation_svg(&pts, &tris));
    assert_eq!(c["path"], 48);
    assert_eq!(c["circle"], 50);

    let shapes = Shapes2 {
        polygons: vec![Polygon {
            rings: vec![
                vec![
                    Point2::new(0.0, 0.0),
                    Point2::new(4.0, 0.0),
                    Point2::new(4.0, 4.0),
                    Point2::new(0.0, 4.0),
                ],
                vec![
                    Point2::new(1.0, 1.0),
                    Point2::new(2.0, 1.0),
                    Point2::new(2.0, 2.0),
                ],
            ],
        }],
        polylines: vec![Polyline {
            points: vec![Point2::new(5.0, 0.0), Point2::new(6.0, 3.0)],
            closed: false,
        }],
    };
    let s = render::polygon_svg(&shapes);
    let c = xml_check(&s);
    assert_eq!(c["path"], 2);
    assert!(s.contains("evenodd"));
    // Two rings: two M commands in the polygon's path.
    let poly_d = s.lines().find(|l| l.contains("evenodd")).unwrap();
    assert_eq!(poly_d.matches('M').count(), 2);
    assert_eq!(poly_d.matches('Z').count(), 2);
}

#[test]
fn svg_builder_elements() {
    let mut b = Aabb2::empty();
    b.add(&[0.0, 0.0]);
    b.add(&[10.0, 5.0]);
    let mut s = Svg::new(b, 400.0);
    s.title("A & B <test>");
    s.point(Point2::new(1.0, 1.0), 2.0, [255, 0, 0]);
    s.segment(
        Point2::new(0.0, 0.0),
        Point2::new(10.0, 5.0),
        &Stroke::dashed([0, 0, 0], 1.0),
    );
    s.segments(
        &[
            (Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)),
            (Point2::new(0.0, 1.0), Point2::new(1.0, 1.0)),
        ],
        &Stroke::solid([0, 0, 255], 0.5),
    );
    s.triangle(
        [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
        ],
        Some(Fill {
            color: [0, 255, 0],
            opacity: 0.5,
        }),
        None,
    );
    s.label(Point2::new(5.0, 2.5), 2.0, 2.0, "x\"<y>", 10.0, [0, 0, 0]);
    let out = s.finish();
    let c = xml_check(&out);
    assert_eq!(c["circle"], 1);
    assert_eq!(c["line"], 1);
    assert_eq!(c["path"], 2);
    assert_eq!(c["text"], 2);
    assert!(out.contains("A &amp; B &lt;test&gt;"));
    assert!(out.contains("stroke-dasharray"));
    assert!(out.contains("fill-opacity=\"0.5\""));
    // The point (1, 1) near the lower left: y flipped.
    let (w, h) = (400.0, 16.0 + 0.5 * (400.0 - 32.0));
    assert!(out.contains(&format!("width=\"{}\"", w as i64)));
    let cy = out
        .split("cy=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap();
    let cy: f64 = cy.parse().unwrap();
    assert!(cy > h / 2.0 && cy < h, "{cy} {h}");
}

#[test]
fn svg_large_input_is_linear() {
    // 250k segments in one path (1M take ~0.3 s in release): quick and of proportional size.
    let n = 250_000;
    let segs: Vec<(Point2, Point2)> = (0..n)
        .map(|i| {
            let x = (i % 1000) as f64;
            let y = (i / 1000) as f64;
            (Point2::new(x, y), Point2::new(x + 0.5, y + 0.5))
        })
        .collect();
    let mut b = Aabb2::empty();
    b.add(&[0.0, 0.0]);
    b.add(&[1000.0, 1000.0]);
    let t = std::time::Instant::now();
    let mut s = Svg::new(b, 1000.0);
    s.segments(&segs, &Stroke::default());
    let out = s.finish();
    let dt = t.elapsed().as_secs_f64();
    assert!(out.len() < 40 * n, "{}", out.len());
    assert!(dt < 20.0, "{dt}");
    assert_eq!(out.matches('M').count(), n);
}

// ---------------------------------------------------------------- slices

fn grey_opts(upsample: Upsample) -> SliceOptions {
    SliceOptions {
        colormap: Colormap::Greys,
        range: Some((0.0, 255.0)),
        size: None,
        upsample,
        labels: true,
    }
}

#[test]
fn slice_pixels_are_samples() {
    // f = x + 10 y + 100 z on a 4 x 5 x 6 unit grid (values up to 3 + 40 + 500).
    let v = Volume::from_fn([4, 5, 6], [0.0; 3], [3.0, 4.0, 5.0], |x, y, z| {
        (x + 10.0 * y + 40.0 * z).min(255.0)
    });
    for up in [Upsample::Nearest, Upsample::Bilinear] {
        let img = slice_image(&v, Axis::Z, 2, &grey_opts(up)).unwrap();
        assert_eq!((img.width, img.height), (4, 5));
        for py in 0..5u32 {
            for px in 0..4u32 {
                // Row 0 is the top = largest y.
                let (x, y) = (px as f64, (4 - py) as f64);
                let want = Colormap::Greys.color((x + 10.0 * y + 80.0) / 255.0);
                let got = img.get(px, py);
                assert_eq!([got[0], got[1], got[2]], want, "({px},{py}) {up:?}");
            }
        }
        // x-slice: (y right, z up), 5 x 6.
        let img = slice_image(&v, Axis::X, 1, &grey_opts(up)).unwrap();
        assert_eq!((img.width, img.height), (5, 6));
        let got = img.get(3, 0); // y = 3, z = 5
        assert_eq!(
            got[0],
            Colormap::Greys.color((1.0 + 30.0 + 200.0) / 255.0)[0]
        );
    }
}

#[test]
fn slice_aspect_size_and_interpolation() {
    // Spacing 1 in x, 2 in y: the z-slice is 4 x (3 * 2) pixels.
    let v = Volume::new(
        [4, 3, 2],
        [0.0; 3],
        [1.0, 2.0, 1.0],
        (0..24).map(|i| i as f32).collect(),
    )
    .unwrap();
    let img = slice_image(&v, Axis::Z, 0, &SliceOptions::default()).unwrap();
    assert_eq!((img.width, img.height), (4, 6));
    let o = SliceOptions {
        size: Some(100),
        ..Default::default()
    };
    let img = slice_image(&v, Axis::Z, 1, &o).unwrap();
    assert_eq!((img.width, img.height), (67, 100));
    // Bilinear upsampling: a linear ramp in x gives non-decreasing greys along a row, with
    // more distinct values than nearest.
    let ramp = Volume::from_fn([3, 2, 1], [0.0; 3], [2.0, 1.0, 0.0], |x, _, _| x);
    let mut o = grey_opts(Upsample::Bilinear);
    o.range = None;
    o.size = Some(60);
    let bil = slice_image(&ramp, Axis::Z, 0, &o).unwrap();
    o.upsample = Upsample::Nearest;
    let near = slice_image(&ramp, Axis::Z, 0, &o).unwrap();
    let row = |img: &Image| {
        (0..img.width)
            .map(|x| img.get(x, 10)[0])
            .collect::<Vec<u8>>()
    };
    let (rb, rn) = (row(&bil), row(&near));
    assert!(rb.windows(2).all(|w| w[1] >= w[0]));
    let distinct = |r: &[u8]| r.iter().collect::<std::collections::BTreeSet<_>>().len();
    assert_eq!(distinct(&rn), 3);
    assert!(distinct(&rb) > 10);
    assert_eq!((rn[0], rn[59]), (0, 255));
}

#[test]
fn slice_errors_nan_and_ranges() {
    let mut v = Volume::from_fn([3, 3, 3], [0.0; 3], [1.0; 3], |x, y, z| x + y + z);
    assert!(slice_image(&v, Axis::Y, 3, &SliceOptions::default()).is_err());
    assert!(orthogonal_slices(&v, [0, 0, 5], &SliceOptions::default()).is_err());
    let i = v.index(1, 1, 1);
    v.data[i] = f32::NAN;
    let img = slice_image(&v, Axis::Z, 1, &grey_opts(Upsample::Bilinear)).unwrap();
    let c = img.get(1, 1);
    assert_eq!([c[0], c[1], c[2]], morpho::render::MISSING);
    // Broken volume: error, not panic.
    let mut bad = v.clone();
    bad.data.pop();
    assert!(slice_image(&bad, Axis::Z, 0, &SliceOptions::default()).is_err());
    // Constant volume: degenerate range, no panic.
    let flat = Volume::from_fn([2, 2, 2], [0.0; 3], [1.0; 3], |_, _, _| 7.0);
    assert!(orthogonal_slices(&flat, middle(&flat), &SliceOptions::default()).is_ok());
}

#[test]
fn orthogonal_slices_layout() {
    let v = Volume::from_fn([40, 30, 20], [0.0; 3], [39.0, 29.0, 19.0], |x, y, z| {
        x + y + z
    });
    let o = SliceOptions {
        labels: false,
        ..Default::default()
    };
    let img = orthogonal_slices(&v, middle(&v), &o).unwrap();
    // Unlabelled: gap + (30 + gap) + (40 + gap) + (40 + gap) wide at 1 px per sample … scaled
    // up by 5 so the longest side reaches 192 px.
    assert_eq!(img.width, 12 + (150 + 12) + (200 + 12) + (200 + 12));
    assert_eq!(img.height, 12 + 150 + 12);
    let lab = orthogonal_slices(&v, middle(&v), &SliceOptions::default()).unwrap();
    assert!(lab.height > img.height);
    // The labels put black pixels at the top left.
    let dark = (0..40)
        .flat_map(|x| (12..26).map(move |y| (x, y)))
        .filter(|&(x, y)| lab.get(x, y)[0] == 0)
        .count();
    assert!(dark > 10);
}

#[test]
fn height_mesh_of_slice() {
    let v = Volume::from_fn([5, 4, 3], [0.0; 3], [4.0, 3.0, 2.0], |x, y, _| x * y);
    let m = slice_height_mesh(&v, Axis::Z, 1, None, 0.5).unwrap();
    assert_eq!(m.positions.len(), 20);
    assert_eq!(m.triangles.len(), 2 * 4 * 3);
    m.validate().unwrap();
    let zmax = m.positions.iter().map(|p| p.z).fold(0.0, f64::max);
    assert!((zmax - 0.5).abs() < 1e-12);
    // Upward-facing (counter-clockwise seen from +z): positive projected area.
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        assert!((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) > 0.0);
    }
    assert_eq!(m.vertex_prop("value").unwrap().values[19], 12.0);
}

// ---------------------------------------------------------------- pictures to look at

/// Reads `v` and `f` lines of an OBJ file (triangles and polygons fanned; `v/vt/vn` indices).
fn tiny_obj(text: &str) -> TriMesh {
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> = it.take(3).filter_map(|t| t.parse().ok()).collect();
                if c.len() == 3 {
                    pos.push(Point3::new(c[0], c[1], c[2]));
                }
            }
            Some("f") => {
                let idx: Vec<u32> = it
                    .filter_map(|t| t.split('/').next()?.parse::<u32>().ok())
                    .map(|i| i - 1)
                    .collect();
                for k in 1..idx.len().saturating_sub(1) {
                    tris.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    TriMesh::new(pos, tris)
}

#[test]
fn bunny_renders() {
    let Some(path) = common::data("meshes/bunny_npm.obj") else {
        return;
    };
    let text = std::fs::read_to_string(&path).unwrap();
    let m = tiny_obj(&text);
    assert_eq!(m.triangles.len(), 3674);
    let img = render_mesh(
        &m,
        &RenderOptions {
            width: 120,
            height: 100,
            ..clear()
        },
    );
    let n = covered(&img);
    assert!(n > 2000 && n < 120 * 100, "{n}");
}

/// Writes the pictures to `$MORPHO_PICTURES` (e.g. /tmp/pics) to look at them. Ignored by default.
#[test]
#[ignore]
fn pictures() {
    let dir =
        std::path::PathBuf::from(std::env::var("MORPHO_PICTURES").unwrap_or("/tmp/pics".into()));
    std::fs::create_dir_all(&dir).unwrap();
    let save = |name: &str, img: &Image| img.save_png(&dir.join(name)).unwrap();
    let o = RenderOptions::default();
    let sphere = uv_sphere([0.0; 3], 1.0, 48, 24);
    save("sphere_smooth.png", &render_mesh(&sphere, &o));
    save(
        "sphere_flat.png",
        &render_mesh(
            &sphere,
            &RenderOptions {
                shading: Shading::Flat,
                ..o.clone()
            },
        ),
    );
    let t = torus(2.0, 0.7, 64, 24);
    save(
        "torus_z.png",
        &render_mesh(
            &t,
            &RenderOptions {
                up: UpAxis::Z,
                ..o.clone()
            },
        ),
    );
    save(
        "torus_wire.png",
        &render_mesh(
            &torus(2.0, 0.7, 24, 12),
            &RenderOptions {
                up: UpAxis::Z,
                wireframe: true,
                shading: Shading::Flat,
                ..o.clone()
            },
        ),
    );
    let z: Vec<f64> = t.positions.iter().map(|p| p.z).collect();
    save(
        "torus_height.png",
        &render_mesh(
            &t,
            &RenderOptions {
                up: UpAxis::Z,
                scalars: Some(Scalars {
                    values: z,
                    per_face: false,
                    colormap: Colormap::Viridis,
                    range: None,
                }),
                ..o.clone()
            },
        ),
    );
    let mut half = icosahedron();
    for tr in half.triangles.iter_mut().take(6) {
        tr.swap(1, 2);
    }
    save(
        "ico_flipped.png",
        &render_mesh(
            &half,
            &RenderOptions {
                shading: Shading::Flat,
                back_color: Some([220, 120, 100]),
                wireframe: true,
                ..o.clone()
            },
        ),
    );
    // SVG: polygon with a hole and a polyline; a triangulated grid; a coloured triangulation.
    let ring = |c: (f64, f64), r: f64, n: usize, cw: bool| -> Vec<Point2> {
        (0..n)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / n as f64 * if cw { -1.0 } else { 1.0 };
                Point2::new(c.0 + r * a.cos(), c.1 + r * a.sin())
            })
            .collect()
    };
    let shapes = Shapes2 {
        polygons: vec![Polygon {
            rings: vec![
                ring((0.0, 0.0), 3.0, 7, false),
                ring((0.5, 0.3), 1.0, 5, true),
            ],
        }],
        polylines: vec![Polyline {
            points: vec![
                Point2::new(4.0, -3.0),
                Point2::new(5.0, 0.0),
                Point2::new(4.5, 3.0),
            ],
            closed: false,
        }],
    };
    std::fs::write(dir.join("polygon.svg"), render::polygon_svg(&shapes)).unwrap();
    let mut gp = Vec::new();
    for j in 0..8 {
        for i in 0..12 {
            gp.push(Point2::new(
                i as f64 + 0.3 * ((i * j) as f64).sin(),
                j as f64 * 0.8,
            ));
        }
    }
    let mut gt = Vec::new();
    for j in 0..7u32 {
        for i in 0..11u32 {
            let a = j * 12 + i;
            gt.push([a, a + 1, a + 13]);
            gt.push([a, a + 13, a + 12]);
        }
    }
    std::fs::write(
        dir.join("triangulation.svg"),
        render::triangulation_svg(&gp, &gt),
    )
    .unwrap();
    let cols: Vec<[u8; 3]> = (0..gt.len())
        .map(|t| Colormap::Viridis.color(((t * 7) % 11) as f64 / 10.0))
        .collect();
    std::fs::write(
        dir.join("colored.svg"),
        render::colored_triangulation_svg(&gp, &gt, &cols),
    )
    .unwrap();

    // Hamann's test function of ch. 2 (three Gaussian bumps) on [0, 39]^3.
    let f = |x: f64, y: f64, z: f64| {
        15.0 * ((-0.005 * ((x - 10.0).powi(2) + (y - 10.0).powi(2) + (z - 10.0).powi(2))).exp()
            + (-0.0025 * ((x - 15.0).powi(2) + (y - 20.0).powi(2) + (z - 20.0).powi(2))).exp()
            + (-0.005 * ((x - 25.0).powi(2) + (y - 25.0).powi(2) + (z - 25.0).powi(2))).exp())
    };
    let vol = Volume::new([40, 40, 20], [0.0; 3], [1.0, 1.0, 2.0], {
        let g = Volume::from_fn([40, 40, 20], [0.0; 3], [39.0, 39.0, 38.0], f);
        g.data
    })
    .unwrap();
    save(
        "slices.png",
        &orthogonal_slices(&vol, [12, 20, 10], &SliceOptions::default()).unwrap(),
    );
    save(
        "slices_coolwarm_nearest.png",
        &orthogonal_slices(
            &vol,
            [12, 20, 10],
            &SliceOptions {
                colormap: Colormap::Coolwarm,
                upsample: Upsample::Nearest,
                size: Some(300),
                ..Default::default()
            },
        )
        .unwrap(),
    );
    save(
        "slice_z.png",
        &slice_image(
            &vol,
            Axis::Z,
            10,
            &SliceOptions {
                size: Some(256),
                ..Default::default()
            },
        )
        .unwrap(),
    );
    let hm = slice_height_mesh(&vol, Axis::Z, 10, None, 0.4).unwrap();
    let val = hm.vertex_prop("value").unwrap().values.clone();
    save(
        "slice_height.png",
        &render_mesh(
            &hm,
            &RenderOptions {
                up: UpAxis::Z,
                scalars: Some(Scalars {
                    values: val,
                    per_face: false,
                    colormap: Colormap::Viridis,
                    range: None,
                }),
                ..o.clone()
            },
        ),
    );
    // Hamann Fig. 2.2: domain subdivision, q = 5, α = 1 (on the same function, x, y, z in [0, 39]).
    let cube = Volume::from_fn([40, 40, 40], [0.0; 3], [39.0; 3], f);
    let dm = morpho::render::domain_subdivision_mesh(&cube, [5, 5, 5], [1.0; 3], 4).unwrap();
    let dv = dm.vertex_prop("value").unwrap().values.clone();
    save(
        "subdivision.png",
        &render_mesh(
            &dm,
            &RenderOptions {
                up: UpAxis::Z,
                shading: Shading::Flat,
                scalars: Some(Scalars {
                    values: dv,
                    per_face: false,
                    colormap: Colormap::Viridis,
                    range: None,
                }),
                ..o.clone()
            },
        ),
    );
    // Hamann Fig. 2.5: the three sets of grid rectangles, alpha blended with t = 0.5.
    let small = Volume::from_fn([9, 9, 9], [0.0; 3], [39.0; 3], f);
    let gm = morpho::render::grid_planes_mesh(&small, [1, 1, 1]).unwrap();
    let gv = gm.vertex_prop("value").unwrap().values.clone();
    save(
        "transparency.png",
        &render_mesh(
            &gm,
            &RenderOptions {
                up: UpAxis::Z,
                transparency: Some(0.75),
                scalars: Some(Scalars {
                    values: gv,
                    per_face: false,
                    colormap: Colormap::Viridis,
                    range: None,
                }),
                ..o.clone()
            },
        ),
    );
    let bunny = common::data("meshes/bunny_npm.obj");
    if let Some(text) = bunny.and_then(|p| std::fs::read_to_string(p).ok()) {
        let b = tiny_obj(&text);
        save("bunny.png", &render_mesh(&b, &o));
        save(
            "bunny_flat_ortho.png",
            &render_mesh(
                &b,
                &RenderOptions {
                    shading: Shading::Flat,
                    projection: Projection::Orthographic,
                    ..o.clone()
                },
            ),
        );
        let y: Vec<f64> = b.positions.iter().map(|p| p.y).collect();
        save(
            "bunny_coolwarm.png",
            &render_mesh(
                &b,
                &RenderOptions {
                    scalars: Some(Scalars {
                        values: y,
                        per_face: false,
                        colormap: Colormap::Coolwarm,
                        range: None,
                    }),
                    ..o.clone()
                },
            ),
        );
    }
}

// ---------------------------------------------------------------- property tests

mod props {
    use super::*;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![
            8 => -10.0..10.0f64,
            1 => Just(0.0),
            1 => Just(f64::NAN),
            1 => prop_oneof![Just(1e300), Just(-1e-300), Just(f64::INFINITY), Just(-1.7e308), Just(f64::MAX)],
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Random triangle soups (with NaN, huge values, bad indices, repeated corners) render
        /// without panicking, deterministically, with the requested size.
        #[test]
        fn soup_never_panics(
            pts in prop::collection::vec((coord(), coord(), coord()), 0..12),
            tris in prop::collection::vec((0u32..14, 0u32..14, 0u32..14), 0..16),
            az in -400.0..400.0f64,
            el in -100.0..100.0f64,
            persp in any::<bool>(),
            smooth in any::<bool>(),
            wire in any::<bool>(),
        ) {
            let m = TriMesh::new(
                pts.iter().map(|&(x, y, z)| Point3::new(x, y, z)).collect(),
                tris.iter().map(|&(a, b, c)| [a, b, c]).collect(),
            );
            let o = RenderOptions {
                width: 24,
                height: 17,
                azimuth_deg: az,
                elevation_deg: el,
                projection: if persp { Projection::Perspective { fov_deg: 40.0 } } else { Projection::Orthographic },
                shading: if smooth { Shading::Smooth } else { Shading::Flat },
                wireframe: wire,
                ..clear()
            };
            let (a, st) = render_mesh_stats(&m, &o);
            prop_assert_eq!((a.width, a.height), (24, 17));
            prop_assert_eq!(st.drawn + st.invalid + st.degenerate, m.triangles.len());
            let b = render_mesh(&m, &o);
            prop_assert_eq!(a, b);
        }

        /// Points with non-finite coordinates are skipped; the rest become one circle each.
        #[test]
        fn svg_points_count(pts in prop::collection::vec((coord(), coord()), 0..40)) {
            let p: Vec<Point2> = pts.iter().map(|&(x, y)| Point2::new(x, y)).collect();
            let finite = p.iter().filter(|q| q.x.is_finite() && q.y.is_finite()).count();
            let s = render::points_svg(&p);
            let c = xml_check(&s);
            prop_assert_eq!(c.get("circle").copied().unwrap_or(0), finite);
            prop_assert!(!s.contains("NaN") && !s.contains("inf"));
            // Every circle lies inside the 800-pixel-wide figure, whatever the magnitudes.
            for part in s.split("cx=\"").skip(1) {
                let cx: f64 = part.split('"').next().unwrap().parse().unwrap();
                prop_assert!((0.0..=800.0).contains(&cx), "{}", cx);
            }
        }

        /// Nearest-sample slice pixels are exactly the mapped samples, for random volumes.
        #[test]
        fn slice_nearest_exact(
            dims in (1usize..6, 1usize..6, 1usize..6),
            seed in any::<u64>(),
            axis in 0usize..3,
        ) {
            let dims = [dims.0, dims.1, dims.2];
            let n = dims[0] * dims[1] * dims[2];
            let data: Vec<f32> = (0..n).map(|i| ((i as u64 * 2654435761 + seed) % 256) as f32).collect();
            let v = Volume::new(dims, [0.0; 3], [1.0; 3], data).unwrap();
            let ax = Axis::from_index(axis).unwrap();
            let (ku, kv) = ax.in_plane();
            let idx = dims[axis] / 2;
            let img = slice_image(&v, ax, idx, &grey_opts(Upsample::Nearest)).unwrap();
            prop_assert_eq!((img.width as usize, img.height as usize), (dims[ku], dims[kv]));
            for py in 0..dims[kv] {
                for px in 0..dims[ku] {
                    let mut g = [0usize; 3];
                    g[axis] = idx;
                    g[ku] = px;
                    g[kv] = dims[kv] - 1 - py;
                    let want = Colormap::Greys.color(v.at(g[0], g[1], g[2]) as f64 / 255.0);
                    let got = img.get(px as u32, py as u32);
                    prop_assert_eq!([got[0], got[1], got[2]], want);
                }
            }
        }
    }
}

/// Every picture of `render::figures` is balanced XML with the elements it promises.
#[test]
fn figures_are_balanced_and_complete() {
    use morpho::boundary::{boundary_2d, Options2};
    use morpho::contour::{contour_samples, SampleContour, SampleOptions};
    use morpho::delaunay::{triangulate_2d, triangulate_constrained_2d};
    use morpho::graphs::{graph_2d, Kind};
    use morpho::mesh::{Column, PointSet};
    use morpho::render::*;
    let pts = morpho::samples::chalice_outline(60, 0.2, 3);
    let n = pts.len();
    let d = triangulate_2d(&pts).unwrap();
    for voronoi in [false, true] {
        let c = xml_check(&delaunay_svg(&d, voronoi));
        assert_eq!(c["circle"], n);
        assert_eq!(c["path"], 1 + voronoi as usize);
    }
    let c = xml_check(&cdt_svg(
        &triangulate_constrained_2d(&pts, &[[0, 30]]).unwrap(),
    ));
    assert_eq!((c["circle"], c["path"]), (n, 2));
    let g = graph_2d(&pts, Kind::Rng).unwrap();
    let c = xml_check(&graph_svg(&pts, &g, Some("RNG <1>")));
    assert_eq!((c["circle"], c["path"], c["text"]), (n, 1, 1));
    let b = boundary_2d(&pts, &Options2::default()).unwrap();
    let s = boundary_svg(&pts, &b);
    let c = xml_check(&s);
    assert_eq!(c["circle"], n + b.left_out.len());
    assert_eq!(c["polygon"], 1);
    assert_eq!(c["line"], b.graph_edges.len() + b.deleted.len());
    let c = xml_check(&cycle_svg(&pts, &b.polygon, "chalice", 300.0));
    assert_eq!((c["circle"], c["path"]), (n, 1));
    let labels = [PointLabel {
        index: 3,
        text: "v",
        dx: -4.0,
    }];
    let c = xml_check(&constriction_svg(
        &pts,
        &b.graph_edges,
        &b.deleted,
        &b.polygon,
        "t",
        Some(3),
        &labels,
    ));
    assert_eq!((c["circle"], c["text"]), (n + 1, 2));
    let mut samples = PointSet::from_points2(&pts);
    samples.columns.push(Column {
        name: "value".into(),
        values: pts.iter().map(|p| p.x).collect(),
    });
    let opts = SampleOptions {
        threshold: 0.0,
        ..Default::default()
    };
    let SampleContour::Plane(r) = contour_samples(&samples, &opts).unwrap() else {
        panic!("2D samples give a plane contour")
    };
    let s = contour_svg(&r);
    let c = xml_check(&s);
    assert_eq!(c["path"], 2 + r.contour.cycles.len() + 1);
    assert!(s.contains("#c81e1e"));
}

/// A sample centre on the diagonal two triangles of a square share is blended once (the fill
/// rule of alpha blending): in the 16×16 front view the diagonal of every square passes through
/// sixteen sample centres, and each pixel equals the closed form of the layers in front of it.
#[test]
fn shared_diagonal_samples_are_blended_once() {
    for (t, values) in [(0.5, vec![200.0]), (0.3, vec![90.0, 250.0, 10.0])] {
        let (img, _, want, alpha) = blend_stack(&values, t, 16, 16);
        let mut on_diagonal = 0;
        for y in 1..15 {
            for x in 1..15 {
                let p = img.get(x, y);
                on_diagonal += usize::from(x + y == 15 || x == y);
                assert!(
                    (p[0] as f64 - want).abs() <= 1.0 && (p[3] as f64 - alpha).abs() <= 1.0,
                    "t {t}, pixel ({x}, {y}): {p:?}, closed form {want:.2} / alpha {alpha:.2}"
                );
            }
        }
        assert!(on_diagonal > 0);
    }
}

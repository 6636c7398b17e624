//! Volume orientation survives read → write in every volume format and places contour surfaces
//! in world space (issue 17 item 11: the MNI volume came out mirrored in x and y in SimpleITK
//! after `convert x.nhdr -o x.mhd`, because `space` and `space directions` were dropped).
mod common;
use morpho::io;
use morpho::mesh::analyze_topology;
use morpho::volume::{isosurface, Axes, IsoOptions, Orientation, Volume};
use std::path::Path;

fn ball(dims: usize) -> Volume {
    let c = (dims - 1) as f64 / 2.0;
    Volume::from_fn([dims; 3], [0.0; 3], [(dims - 1) as f64; 3], |x, y, z| {
        ((x - c).powi(2) + (y - c).powi(2) + (z - c).powi(2)).sqrt()
    })
}

fn origin(v: &Volume) -> [f64; 3] {
    match &v.axes {
        Axes::Uniform { origin, .. } => *origin,
        _ => panic!("not uniform"),
    }
}

/// Signed volume of a closed mesh (positive when its triangles face outward).
fn signed_volume(m: &morpho::mesh::TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize].coords);
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum()
}

fn write_nrrd_text(path: &Path, header_extra: &str) {
    let mut s = format!(
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n{header_extra}\n"
    );
    s.push('\n');
    let mut b = s.into_bytes();
    b.extend_from_slice(&[0, 1, 2, 3, 4, 5, 6, 7]);
    std::fs::write(path, b).unwrap();
}

#[test]
fn nrrd_space_and_directions_round_trip_through_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("oblique.nrrd");
    // axis 0 along y (spacing 2), axis 1 along −x (spacing 3), axis 2 along z (spacing 0.5)
    write_nrrd_text(
        &src,
        "space: left-posterior-superior\nspace directions: (0,2,0) (-3,0,0) (0,0,0.5)\nspace origin: (10,20,30)",
    );
    let v = io::read_volume(&src).unwrap();
    assert_eq!(v.spacing(), [2.0, 3.0, 0.5]);
    assert_eq!(
        v.orientation.directions,
        Some([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    );
    assert_eq!(
        v.orientation.space.as_deref(),
        Some("left-posterior-superior")
    );
    for ext in ["nrrd", "mhd", "mha", "json"] {
        let out = dir.path().join(format!("copy.{ext}"));
        io::write_volume(&out, &v).unwrap();
        let back = io::read_volume(&out).unwrap();
        assert_eq!(
            back.orientation.directions, v.orientation.directions,
            "{ext}"
        );
        assert_eq!(origin(&back), [10.0, 20.0, 30.0], "{ext}");
        assert_eq!(back.spacing(), v.spacing(), "{ext}");
        assert_eq!(back.data, v.data, "{ext}");
        assert_eq!(
            back.orientation.space.as_deref(),
            Some("left-posterior-superior"),
            "{ext}"
        );
    }
}

/// A RAS volume written as MetaImage (LPS by definition) gets x and y negated in its origin
/// and directions, and reads back as the same physical grid.
#[test]
fn ras_becomes_lps_in_metaimage() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("ras.nrrd");
    write_nrrd_text(
        &src,
        "space: right-anterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (-98,-134,-72)",
    );
    let v = io::read_volume(&src).unwrap();
    assert!(v.orientation.is_axis_aligned());
    let mhd = dir.path().join("ras.mhd");
    io::write_volume(&mhd, &v).unwrap();
    let text = std::fs::read_to_string(&mhd).unwrap();
    assert!(
        text.contains("TransformMatrix = -1.0 0.0 0.0 0.0 -1.0 0.0 0.0 0.0 1.0"),
        "{text}"
    );
    assert!(text.contains("Offset = 98.0 134.0 -72.0"), "{text}");
    let back = io::read_volume(&mhd).unwrap();
    assert_eq!(
        back.orientation.space.as_deref(),
        Some("left-posterior-superior")
    );
    // sample (i, j, k) sits at the same physical point: RAS (x, y, z) = LPS (−x, −y, z)
    let (o, d) = (origin(&back), back.orientation.directions.unwrap());
    for (i, j, k) in [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 1.0)] {
        let lps: Vec<f64> = (0..3)
            .map(|b| o[b] + i * d[0][b] + j * d[1][b] + k * d[2][b])
            .collect();
        let ras = [-98.0 + i, -134.0 + j, -72.0 + k];
        assert_eq!(lps, vec![-ras[0], -ras[1], ras[2]]);
    }
    // and back to NRRD: the LPS grid, named so
    let nrrd = dir.path().join("back.nrrd");
    io::write_volume(&nrrd, &back).unwrap();
    let again = io::read_volume(&nrrd).unwrap();
    assert_eq!(again.orientation, back.orientation);
}

#[test]
fn metaimage_transform_matrix_is_read_per_axis() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.mhd");
    std::fs::write(dir.path().join("t.raw"), [0u8; 8]).unwrap();
    std::fs::write(
        &p,
        "ObjectType = Image\nNDims = 3\nTransformMatrix = 0 0 1 1 0 0 0 1 0\nOffset = 1 2 3\n\
         AnatomicalOrientation = RAI\nElementSpacing = 1 1 1\nDimSize = 2 2 2\n\
         ElementType = MET_UCHAR\nElementDataFile = t.raw\n",
    )
    .unwrap();
    let v = io::read_volume(&p).unwrap();
    assert_eq!(
        v.orientation.directions,
        Some([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    );
    assert_eq!(v.orientation.anatomical.as_deref(), Some("RAI"));
    let bad = dir.path().join("bad.mhd");
    std::fs::write(
        &bad,
        "NDims = 3\nTransformMatrix = 1 0 0 1 0 0 0 0 1\nDimSize = 2 2 2\n\
         ElementType = MET_UCHAR\nElementDataFile = t.raw\n",
    )
    .unwrap();
    let e = io::read_volume(&bad).unwrap_err().to_string();
    assert!(e.contains("linearly dependent"), "{e}");
}

/// The contour surface is placed by the directions: a mirrored grid gives the mirrored surface,
/// still closed and still facing outward; a rotated grid the rotated surface.
#[test]
fn contour_surfaces_are_in_world_space() {
    let plain = ball(17);
    let opts = IsoOptions {
        level: 5.0,
        ..Default::default()
    };
    let a = isosurface(&plain, &opts).unwrap().mesh;
    // oriented along −∇f (the default): the distance field's surface faces inward
    assert!(signed_volume(&a) < 0.0);
    for (name, d) in [
        (
            "mirror x",
            [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        ),
        (
            "rotate z",
            [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        ),
        (
            "permute",
            [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        ),
    ] {
        let mut v = plain.clone();
        v.orientation = Orientation {
            directions: Some(d),
            ..Default::default()
        };
        let b = isosurface(&v, &opts).unwrap().mesh;
        assert_eq!(a.triangles.len(), b.triangles.len(), "{name}");
        for (p, q) in a.positions.iter().zip(&b.positions) {
            let want: Vec<f64> = (0..3)
                .map(|k| p.x * d[0][k] + p.y * d[1][k] + p.z * d[2][k])
                .collect();
            assert!(
                (0..3).all(|k| (q[k] - want[k]).abs() < 1e-9),
                "{name}: {q:?} vs {want:?}"
            );
        }
        let t = analyze_topology(&b);
        assert!(
            t.is_closed() && t.manifold && t.consistently_oriented,
            "{name}"
        );
        assert!(
            (signed_volume(&b) - signed_volume(&a)).abs() < 1e-6 * signed_volume(&a).abs(),
            "{name}: the windings changed side"
        );
        // normals follow the surface: outward, like the windings
        let n = b.normals.as_ref().unwrap();
        let c = 8.0;
        let mut agree = 0;
        for (p, nn) in b.positions.iter().zip(n) {
            let centre: Vec<f64> = (0..3).map(|k| c * (d[0][k] + d[1][k] + d[2][k])).collect();
            let r = [p.x - centre[0], p.y - centre[1], p.z - centre[2]];
            agree += ((r[0] * nn.x + r[1] * nn.y + r[2] * nn.z) > 0.0) as usize;
        }
        let outward_a = a
            .positions
            .iter()
            .zip(a.normals.as_ref().unwrap())
            .filter(|(p, nn)| ((p.x - c) * nn.x + (p.y - c) * nn.y + (p.z - c) * nn.z) > 0.0)
            .count();
        assert_eq!(agree, outward_a, "{name}: normals changed side");
    }
}

/// The real MNI template (RAS) converted to MetaImage keeps its physical placement.
#[test]
fn mni_template_keeps_its_placement_in_metaimage() {
    let Some(src) = common::data("volumes/mni_icbm152_t1_2009a_197x233x189.nhdr") else {
        return;
    };
    let v = io::read_volume(&src).unwrap();
    assert_eq!(
        v.orientation.space.as_deref(),
        Some("right-anterior-superior")
    );
    let dir = tempfile::tempdir().unwrap();
    let mhd = dir.path().join("mni.mhd");
    io::write_volume(&mhd, &v).unwrap();
    let back = io::read_volume(&mhd).unwrap();
    assert_eq!(origin(&back), [98.0, 134.0, -72.0]);
    assert_eq!(
        back.orientation.directions,
        Some([[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]])
    );
}

/// A sidecar's `affine_ijk_to_ras_mm` (as the shipped MNI/dipy sidecars carry) gives the
/// space, the axis directions (oblique and mirrored allowed) and, without a spacing key, the
/// spacing; the world position of voxel (i,j,k) is the affine applied to it.
#[test]
fn sidecar_affine_gives_space_directions_and_spacing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("v.raw"), [0u8, 1, 2, 3, 4, 5, 6, 7]).unwrap();
    // axis 0 along -x scaled 2, axis 1 rotated 30° in y–z scaled 3, axis 2 scaled 0.5
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let a = [
        [-2.0, 0.0, 0.0, 10.0],
        [0.0, 3.0 * c, -0.5 * s, -20.0],
        [0.0, 3.0 * s, 0.5 * c, 30.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let doc = serde_json::json!({
        "data_file": "v.raw", "dims_xyz": [2, 2, 2], "dtype": "uint8",
        "affine_ijk_to_ras_mm": a,
    });
    let path = dir.path().join("v.json");
    std::fs::write(&path, doc.to_string()).unwrap();
    let v = io::read_volume(&path).unwrap();
    assert_eq!(
        v.orientation.space.as_deref(),
        Some("right-anterior-superior")
    );
    for (got, want) in v.spacing().iter().zip([2.0, 3.0, 0.5]) {
        assert!((got - want).abs() < 1e-12, "{:?}", v.spacing());
    }
    let o = origin(&v);
    assert_eq!(o, [10.0, -20.0, 30.0]);
    for (i, j, k) in [(1usize, 0usize, 0usize), (0, 1, 0), (0, 0, 1), (1, 1, 1)] {
        let grid = [
            o[0] + i as f64 * 2.0,
            o[1] + j as f64 * 3.0,
            o[2] + k as f64 * 0.5,
        ];
        let w = v.orientation.to_world(o, grid);
        let (fi, fj, fk) = (i as f64, j as f64, k as f64);
        let want = [0, 1, 2].map(|r| a[r][0] * fi + a[r][1] * fj + a[r][2] * fk + a[r][3]);
        for r in 0..3 {
            assert!(
                (w[r] - want[r]).abs() < 1e-12,
                "voxel {i},{j},{k}: {w:?} vs {want:?}"
            );
        }
    }
    // a singular affine is refused with the key named
    let mut bad = doc.clone();
    bad["affine_ijk_to_ras_mm"] =
        serde_json::json!([[1, 0, 0, 0], [2, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]);
    std::fs::write(&path, bad.to_string()).unwrap();
    let e = io::read_volume(&path).unwrap_err().to_string();
    assert!(e.contains("affine_ijk_to_ras_mm"), "{e}");
}

//! Issue 24, the CLI's streaming mode: a contour surface stitched slab by slab with
//! [`IsoStream`] equals the in-memory [`isosurface`] — positions and normals bit for bit, the
//! same triangles in the same order, the same part labels and topology figures — for every slab
//! thickness (1 cell … all), every method and normal mode, on volumes with many ambiguous
//! faces, NaN cells, plateaus at the level, and a mirrored oblique orientation.

use morpho::mesh::{Property, ScalarKind, TriMesh};
use morpho::volume::{
    isosurface, isosurface_block, IsoMethod, IsoOptions, IsoResult, IsoStream, NormalMethod,
    Orientation, StreamPiece, Volume, VolumeError, VolumeGrid,
};
use rand::{Rng, SeedableRng};

/// Streams `vol` in slabs of `k` cells along z (each with its one-sample halo) and assembles
/// what the stream emits into the result `isosurface` gives.
fn streamed(vol: &Volume, k: usize, opts: &IsoOptions) -> Result<IsoResult, VolumeError> {
    let grid = VolumeGrid::of(vol);
    let range = if vol.dims.iter().any(|&d| d < 2) {
        None
    } else {
        vol.value_range()
    };
    let d = vol.dims;
    let mut s = IsoStream::new(grid.clone(), range, opts)?;
    let mut piece = StreamPiece::default();
    let (mut pos, mut nrm, mut ipos, mut inrm, mut tris) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut drain = |p: &mut StreamPiece| {
        pos.append(&mut p.positions);
        nrm.append(&mut p.normals);
        ipos.append(&mut p.interior_positions);
        inrm.append(&mut p.interior_normals);
        tris.append(&mut p.triangles);
    };
    let cells = d[2].saturating_sub(1);
    let mut z0 = 0;
    while z0 < cells {
        let z1 = (z0 + k).min(cells);
        let (s0, s1) = (z0.saturating_sub(1), (z1 + 2).min(d[2]));
        let plane = d[0] * d[1];
        let samples = &vol.data[plane * s0..plane * s1];
        let b = isosurface_block(
            &grid,
            samples,
            [d[0], d[1], s1 - s0],
            [0, 0, s0],
            [[0, d[0] - 1], [0, d[1] - 1], [z0, z1]],
            range,
            opts,
        )?;
        s.push(b, [z0, z1], &mut piece)?;
        drain(&mut piece);
        z0 = z1;
    }
    let sum = s.finish(&mut piece)?;
    drain(&mut piece);
    assert_eq!(pos.len(), sum.edge_vertices);
    assert_eq!(ipos.len(), sum.interior_vertices);
    assert_eq!(tris.len(), sum.triangles);
    pos.append(&mut ipos);
    nrm.append(&mut inrm);
    let tris: Vec<[u32; 3]> = tris.iter().map(|t| t.map(|c| sum.resolve(c))).collect();
    let mut mesh = TriMesh::new(pos, tris);
    if opts.normals != NormalMethod::None && !mesh.positions.is_empty() {
        mesh.normals = Some(nrm);
    }
    if opts.topology && !mesh.triangles.is_empty() {
        mesh.face_props.push(Property {
            name: "part".into(),
            kind: ScalarKind::U32,
            values: (0..sum.triangles)
                .map(|t| sum.part(t).map_or(f64::NAN, |p| p as f64))
                .collect(),
        });
    }
    Ok(IsoResult {
        mesh,
        ..sum.figures
    })
}

fn volumes() -> Vec<(&'static str, Volume, f64)> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2424);
    let d = [9, 8, 12];
    let n = d[0] * d[1] * d[2];
    let pm: Vec<f32> = (0..n)
        .map(|_| if rng.gen_bool(0.5) { 1.0 } else { -1.0 })
        .collect();
    let noise: Vec<f32> = (0..n).map(|_| rng.gen_range(-1.0f32..1.0)).collect();
    let mut nan = noise.clone();
    for i in (0..n).step_by(29) {
        nan[i] = f32::NAN;
    }
    let ints: Vec<f32> = (0..n).map(|_| rng.gen_range(0..3) as f32).collect();
    let v = |data: Vec<f32>| Volume::new(d, [-1.5, 0.25, 3.0], [0.3, 0.7, 1.1], data).unwrap();
    let ball = Volume::from_fn([13, 12, 11], [-1.0; 3], [1.0; 3], |x, y, z| {
        x * x + y * y + z * z + 0.3 * (5.0 * x).sin()
    });
    // flat spots: zero gradients, so the mesh-normal fallback runs across slab seams
    let flat = Volume::from_fn([10, 10, 10], [-1.0; 3], [1.0; 3], |x, y, z| {
        ((x * 2.0).round() + (y * 2.0).round() + (z * 2.0).round()) * 0.5
    });
    let mut mirrored = v(noise.clone());
    let (c, s) = (0.6f64, 0.8f64);
    mirrored.orientation = Orientation {
        space: Some("left-posterior-superior".into()),
        anatomical: None,
        directions: Some([[-c, s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]),
    };
    vec![
        ("ball", ball, 0.5),
        ("random ±1", v(pm), 0.0),
        ("noise", v(noise), 0.1),
        ("nan", v(nan), 0.0),
        ("ints", v(ints), 1.0),
        ("flat", flat, 0.25),
        ("mirrored", mirrored, 0.1),
    ]
}

#[test]
fn streamed_equals_in_memory() {
    for (name, vol, level) in volumes() {
        for method in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
            for normals in [
                NormalMethod::ZuckerHummel,
                NormalMethod::Central,
                NormalMethod::Mesh,
                NormalMethod::None,
            ] {
                let opts = IsoOptions {
                    level,
                    method,
                    normals,
                    ..Default::default()
                };
                let single = isosurface(&vol, &opts).unwrap();
                assert!(!single.mesh.triangles.is_empty(), "{name}");
                for k in [1, 2, 3, 5, 40] {
                    let what = format!("{name} {method:?} {normals:?} slabs of {k}");
                    let st = streamed(&vol, k, &opts).unwrap();
                    assert_eq!(st, single, "{what}");
                }
            }
        }
    }
}

#[test]
fn empty_levels_and_bad_order() {
    let (_, vol, _) = volumes().swap_remove(0);
    let opts = IsoOptions {
        level: 99.0,
        ..Default::default()
    };
    let st = streamed(&vol, 3, &opts).unwrap();
    assert_eq!(st, isosurface(&vol, &opts).unwrap());
    assert!(st.note.unwrap().contains("outside"));
    // a slab that does not follow the previous one is refused
    let opts = IsoOptions {
        level: 0.5,
        ..Default::default()
    };
    let grid = VolumeGrid::of(&vol);
    let mut s = IsoStream::new(grid, vol.value_range(), &opts).unwrap();
    let mut piece = StreamPiece::default();
    let err = s
        .push(Default::default(), [2, 4], &mut piece)
        .unwrap_err()
        .to_string();
    assert!(err.contains("does not follow"), "{err}");
}

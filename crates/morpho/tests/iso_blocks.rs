//! Issue 24 part 3: contour surfaces extracted block by block and stitched equal the
//! single-block surface — positions and normals bit for bit, the same triangles (in the same
//! order, so also the same set after a canonical sort), the same topology figures and χ — for
//! every chunking tried (chunk sizes 1…n cells, uneven last chunks), on volumes with many
//! ambiguous faces (random ±1 samples, a checkerboard, uniform noise) and NaN cells; the
//! stitched surface is closed across the seams.

use morpho::mesh::{analyze_topology, TriMesh};
use morpho::volume::{
    isosurface, isosurface_block, stitch_blocks, IsoBlock, IsoMethod, IsoOptions, IsoResult,
    NormalMethod, Volume, VolumeError, VolumeGrid,
};
use rand::{Rng, SeedableRng};
use std::collections::HashMap;

/// Cuts `vol` into blocks of `cs` cells per axis (the last ones shorter), each with its
/// one-sample halo, extracts them (in a shuffled order) and stitches them.
fn chunked(vol: &Volume, cs: [usize; 3], opts: &IsoOptions) -> Result<IsoResult, VolumeError> {
    let grid = VolumeGrid::of(vol);
    let range = vol.value_range();
    let d = vol.dims;
    let starts = |k: usize| -> Vec<[usize; 2]> {
        let n = d[k].saturating_sub(1);
        (0..n)
            .step_by(cs[k])
            .map(|a| [a, (a + cs[k]).min(n)])
            .collect()
    };
    let mut blocks: Vec<IsoBlock> = Vec::new();
    for cz in starts(2) {
        for cy in starts(1) {
            for cx in starts(0) {
                let cells = [cx, cy, cz];
                let lo: [usize; 3] = std::array::from_fn(|k| cells[k][0].saturating_sub(1));
                let hi: [usize; 3] = std::array::from_fn(|k| (cells[k][1] + 2).min(d[k]));
                let dims: [usize; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
                let mut s = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
                for z in lo[2]..hi[2] {
                    for y in lo[1]..hi[1] {
                        let a = vol.index(lo[0], y, z);
                        s.extend_from_slice(&vol.data[a..a + dims[0]]);
                    }
                }
                blocks.push(isosurface_block(&grid, &s, dims, lo, cells, range, opts)?);
            }
        }
    }
    blocks.reverse();
    stitch_blocks(&grid, blocks, range, opts)
}

fn bits(m: &TriMesh) -> (Vec<[u64; 3]>, Option<Vec<[u64; 3]>>) {
    let p = m
        .positions
        .iter()
        .map(|p| [p.x, p.y, p.z].map(f64::to_bits))
        .collect();
    let n = m.normals.as_ref().map(|n| {
        n.iter()
            .map(|v| [v.x, v.y, v.z].map(f64::to_bits))
            .collect()
    });
    (p, n)
}

/// Triangles as position-bit triples, rotated to start at the smallest, sorted.
fn canonical(m: &TriMesh) -> Vec<[[u64; 3]; 3]> {
    let mut t: Vec<[[u64; 3]; 3]> = m
        .triangles
        .iter()
        .map(|t| {
            let q = t.map(|v| {
                let p = m.positions[v as usize];
                [p.x, p.y, p.z].map(f64::to_bits)
            });
            let r = (0..3).min_by_key(|&i| q[i]).unwrap_or(0);
            [q[r], q[(r + 1) % 3], q[(r + 2) % 3]]
        })
        .collect();
    t.sort_unstable();
    t
}

/// Edges used by one triangle that do not lie on the volume's outer faces.
fn seam_holes(m: &TriMesh, lo: [f64; 3], hi: [f64; 3]) -> usize {
    let mut count: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &m.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count
        .iter()
        .filter(|(_, &c)| c == 1)
        .filter(|((a, b), _)| {
            let (p, q) = (m.positions[*a as usize], m.positions[*b as usize]);
            !(0..3).any(|k| (p[k] == lo[k] && q[k] == lo[k]) || (p[k] == hi[k] && q[k] == hi[k]))
        })
        .count()
}

fn volumes() -> Vec<(&'static str, Volume, f64)> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(24);
    let d = [11, 9, 10];
    let n = d[0] * d[1] * d[2];
    let pm: Vec<f32> = (0..n)
        .map(|_| if rng.gen_bool(0.5) { 1.0 } else { -1.0 })
        .collect();
    let noise: Vec<f32> = (0..n).map(|_| rng.gen_range(-1.0f32..1.0)).collect();
    let mut check = Vec::with_capacity(n);
    for z in 0..d[2] {
        for y in 0..d[1] {
            for x in 0..d[0] {
                check.push(if (x + y + z) % 2 == 0 { 1.0 } else { -1.0 });
            }
        }
    }
    let mut nan = noise.clone();
    for i in (0..n).step_by(37) {
        nan[i] = f32::NAN;
    }
    // integer plateaus: many samples exactly at the level (ε of Rem. 3.8)
    let ints: Vec<f32> = (0..n).map(|_| rng.gen_range(0..3) as f32).collect();
    let v = |data: Vec<f32>| Volume::new(d, [-1.5, 0.25, 3.0], [0.3, 0.7, 1.1], data).unwrap();
    let ball = Volume::from_fn([13, 12, 11], [-1.0; 3], [1.0; 3], |x, y, z| {
        x * x + y * y + z * z + 0.3 * (5.0 * x).sin()
    });
    vec![
        ("ball", ball, 0.5),
        ("random ±1", v(pm), 0.0),
        ("checkerboard", v(check), 0.0),
        ("noise", v(noise), 0.1),
        ("nan", v(nan), 0.0),
        ("ints", v(ints), 1.0),
    ]
}

#[test]
fn chunked_equals_single_block() {
    let sizes: [[usize; 3]; 8] = [
        [1, 1, 1],
        [2, 2, 2],
        [3, 3, 3],
        [4, 5, 3],
        [7, 2, 6],
        [1, 8, 20],
        [20, 20, 1],
        [20, 20, 20],
    ];
    for (name, vol, level) in volumes() {
        let lo = [0, 1, 2].map(|k| vol.coord(k, 0));
        let hi = [0, 1, 2].map(|k| vol.coord(k, vol.dims[k] - 1));
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
                let chi = analyze_topology(&single.mesh).euler_characteristic;
                for cs in sizes {
                    let what = format!("{name} {method:?} {normals:?} chunks {cs:?}");
                    let st = chunked(&vol, cs, &opts).unwrap();
                    assert_eq!(bits(&st.mesh), bits(&single.mesh), "{what}");
                    assert_eq!(canonical(&st.mesh), canonical(&single.mesh), "{what}");
                    assert_eq!(st, single, "{what}");
                    assert_eq!(
                        analyze_topology(&st.mesh).euler_characteristic,
                        chi,
                        "{what}"
                    );
                    if method != IsoMethod::Lorensen && name != "nan" {
                        assert_eq!(st.interior_boundary_edges, 0, "{what}");
                        assert_eq!(seam_holes(&st.mesh, lo, hi), 0, "{what}");
                    }
                }
            }
        }
    }
}

#[test]
fn missing_blocks_leave_seams_and_bad_blocks_are_refused() {
    let (_, vol, level) = volumes().swap_remove(3);
    let opts = IsoOptions {
        level,
        ..Default::default()
    };
    let grid = VolumeGrid::of(&vol);
    let range = vol.value_range();
    let d = vol.dims;
    let block = |z0: usize, z1: usize, halo: usize| {
        let (s0, s1) = (z0.saturating_sub(halo), (z1 + 1 + halo).min(d[2]));
        let plane = d[0] * d[1];
        let s = vol.data[plane * s0..plane * s1].to_vec();
        let cells = [[0, d[0] - 1], [0, d[1] - 1], [z0, z1]];
        isosurface_block(
            &grid,
            &s,
            [d[0], d[1], s1 - s0],
            [0, 0, s0],
            cells,
            range,
            &opts,
        )
    };
    // only the lower half: open along the seam plane (the closedness check can fail)
    let half = stitch_blocks(&grid, vec![block(0, 4, 1).unwrap()], range, &opts).unwrap();
    let lo = [0, 1, 2].map(|k| vol.coord(k, 0));
    let hi = [0, 1, 2].map(|k| vol.coord(k, vol.dims[k] - 1));
    assert!(seam_holes(&half.mesh, lo, hi) > 0);
    assert!(half.interior_boundary_edges > 0);
    // no halo with gradient normals: refused, not silently different
    assert!(matches!(block(2, 5, 0), Err(VolumeError::BadBlock { .. })));
    // the same cells twice
    let twice = vec![block(0, 4, 1).unwrap(), block(3, 6, 1).unwrap()];
    assert!(matches!(
        stitch_blocks(&grid, twice, range, &opts),
        Err(VolumeError::BlocksDisagree { .. })
    ));
    // blocks from different data disagree on their shared points
    let mut other = vol.clone();
    for v in &mut other.data {
        *v *= 0.5;
    }
    let plane = d[0] * d[1];
    let s = other.data[plane * 3..].to_vec();
    let cells = [[0, d[0] - 1], [0, d[1] - 1], [4, d[2] - 1]];
    let b2 = isosurface_block(
        &grid,
        &s,
        [d[0], d[1], d[2] - 3],
        [0, 0, 3],
        cells,
        range,
        &opts,
    )
    .unwrap();
    assert!(matches!(
        stitch_blocks(&grid, vec![block(0, 4, 1).unwrap(), b2], range, &opts),
        Err(VolumeError::BlocksDisagree { .. })
    ));
    // outside the grid
    let s = vec![0.0; 8];
    let bad = isosurface_block(
        &grid,
        &s,
        [2, 2, 2],
        [d[0] - 1, 0, 0],
        [[0, 1]; 3],
        range,
        &opts,
    );
    assert!(matches!(bad, Err(VolumeError::BadBlock { .. })));
}

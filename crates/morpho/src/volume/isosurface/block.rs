//! Contour surfaces of a grid given block by block (issue 24 part 3): each block of cells is
//! extracted on its own — on another thread, process or machine — and the blocks are stitched
//! into the surface [`isosurface`](super::isosurface) gives for the whole grid, identical to
//! the bit (positions, normals, vertex and triangle order, topology figures).
//!
//! Why this works: everything the extraction computes for a cell depends only on that cell's
//! eight samples, the perturbation ε (Rem. 3.8, from the *whole* grid's range, which the caller
//! passes), the plane coordinates, and — for grid-gradient normals — the 3·3·3 stencils of its
//! corners. The asymptotic decider's choice on a face uses the four samples of that face only
//! (products of the two diagonals, Thm. 3.3), so the two cells sharing a face decide it the
//! same way whichever block each is in. A contour point on a grid entity (edge or diagonal) is
//! interpolated from that entity's two samples, so the blocks on either side of a seam compute
//! the same bits for it. So a block gets the samples of its cells plus a one-sample halo where
//! the grid continues (the gradient stencils' reach), its plane coordinates are computed from
//! the global indices exactly as [`Volume::coord`] does, and its vertices are named by a global
//! id derived from their grid entity.
//!
//! Global ids ([`IsoBlock::ids`]): for a point on the entity of kind κ at grid point (x, y, z)
//! of a grid with n_x × n_y × n_z samples,
//! `id = ((((2z + L)·n_y + y)·2 + S)·n_x + x)·4 + σ`, where plane entities (x-edges, y-edges,
//! xy-diagonals) have L = 0 and layer entities (z-edges, yz-, xz- and body diagonals) L = 1, and
//! (S, σ) orders the entities of a row as the extraction emits them (x-edges S = 0; y-edge and
//! xy-diagonal S = 1, σ = 0, 1; the four layer entities σ = 0…3). Cell-interior points (the
//! decider's fan points, Thm. 3.6) are not shared: the r-th one of cell c (linear index
//! x + n_x(y + n_y z)) gets `16·N + 4c + r` for N samples. Sorting by id is therefore the
//! single-machine vertex order, and stitching ([`stitch_blocks`]) is: concatenate, sort by id,
//! merge equal ids (checking that their positions and normals agree bit for bit), renumber the
//! triangles, and order them by their cell ([`IsoBlock::triangle_cells`]) — then the shared
//! tail of [`isosurface`](super::isosurface) (normal fallbacks, topology, notes).
//!
//! Cost: a block costs what the extraction of its cells costs, plus a copy of its samples;
//! stitching is O((V + T) log(V + T)) for the blocks' V vertices and T triangles, with
//! 16 bytes per vertex and per triangle of work space. Limits: axes up to 2²⁰ samples (as
//! [`isosurface`](super::isosurface)) and at most 2⁵⁸ samples in the grid (so ids fit in 64
//! bits).

use super::extract::{key, Ctx, INTERIOR, KEY_INTERIOR};
use super::{finish, perturbation, IsoOptions, IsoResult, NormalMethod};
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;
use crate::volume::gradient::{axis_coords, CentralTable};
use crate::volume::{validate_axes, Axes, DType, Orientation, Volume, VolumeError};

/// The geometry of the whole grid blocks are cut from: dimensions, axes, orientation.
#[derive(Debug, Clone, PartialEq)]
pub struct VolumeGrid {
    /// Samples along x, y, z.
    pub dims: [usize; 3],
    /// Positions of the grid planes (as [`Volume::axes`]).
    pub axes: Axes,
    /// Where the grid sits in world space (as [`Volume::orientation`]).
    pub orientation: Orientation,
}

impl VolumeGrid {
    /// The grid of `vol`.
    pub fn of(vol: &Volume) -> Self {
        VolumeGrid {
            dims: vol.dims,
            axes: vol.axes.clone(),
            orientation: vol.orientation.clone(),
        }
    }

    /// An axis-aligned grid with uniform axes.
    pub fn uniform(dims: [usize; 3], origin: [f64; 3], spacing: [f64; 3]) -> Self {
        VolumeGrid {
            dims,
            axes: Axes::Uniform { origin, spacing },
            orientation: Orientation::default(),
        }
    }

    /// Coordinate of grid plane `i` along axis `k` (the arithmetic of [`Volume::coord`]).
    fn coord(&self, k: usize, i: usize) -> f64 {
        match &self.axes {
            Axes::Uniform { origin, spacing } => origin[k] + i as f64 * spacing[k],
            Axes::Coords(c) => c[k][i],
        }
    }

    /// Checks the axes and the limits; returns the number of samples.
    pub(super) fn validate(&self) -> Result<usize, VolumeError> {
        let n = self.dims[0]
            .checked_mul(self.dims[1])
            .and_then(|v| v.checked_mul(self.dims[2]))
            .ok_or(VolumeError::DimsOverflow { dims: self.dims })?;
        if self.dims.iter().any(|&d| d >= 1 << 20) {
            return Err(VolumeError::AxisTooLong { dims: self.dims });
        }
        if n as u64 >= 1 << 58 {
            return Err(bad(format!(
                "grid {:?} has more than 2^58 samples",
                self.dims
            )));
        }
        validate_axes(&self.axes, self.dims)?;
        Ok(n)
    }
}

/// The contour of one block of cells ([`isosurface_block`]), in global terms.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct IsoBlock {
    /// Global id of each vertex (module doc): equal ids in two blocks are the same point.
    pub ids: Vec<u64>,
    /// Vertex positions (in the grid's axis-aligned frame; the stitch applies the orientation).
    pub positions: Vec<Point3>,
    /// Vertex normals for the grid-gradient methods (Zucker–Hummel, central), else `None`.
    pub normals: Option<Vec<Vector3>>,
    /// Triangles in indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Linear index x + n_x(y + n_y z) of the cell each triangle comes from.
    pub triangle_cells: Vec<u64>,
    /// Linear indices of the cells skipped for a NaN corner.
    pub nan_cells: Vec<u64>,
    /// Polygons fanned around an interior point.
    pub fan_points: usize,
    /// Of those, centroid fallbacks.
    pub centroid_fallbacks: usize,
    /// Some grid-gradient normal came out zero (the stitch fills it from the mesh).
    pub zero_normals: bool,
}

impl IsoBlock {
    /// Ids, normals, triangles and triangle cells match the vertices (what the stitchers
    /// check of a block that may come from another process).
    pub(super) fn consistent(&self) -> bool {
        let nv = self.positions.len();
        self.ids.len() == nv
            && self.normals.as_ref().map_or(true, |n| n.len() == nv)
            && self.triangles.iter().flatten().all(|&v| (v as usize) < nv)
            && self.triangle_cells.len() == self.triangles.len()
    }
}

/// Position of entity kind κ (as packed by `extract::key`) in the emission order: (L, S, σ).
const ORDER: [(u64, u64, u64); 7] = [
    (0, 0, 0), // x-edge
    (0, 1, 0), // y-edge
    (1, 0, 0), // z-edge
    (0, 1, 1), // xy-diagonal
    (1, 0, 1), // yz-diagonal
    (1, 0, 2), // xz-diagonal
    (1, 0, 3), // body diagonal
];

/// Global id of the entity `kind` at global grid point `p` of a grid with dims `d`.
fn entity_id(kind: usize, p: [usize; 3], d: [usize; 3]) -> u64 {
    let (l, s, sigma) = ORDER[kind];
    let [nx, ny, _] = d.map(|v| v as u64);
    let [x, y, z] = p.map(|v| v as u64);
    ((((2 * z + l) * ny + y) * 2 + s) * nx + x) * 4 + sigma
}

/// The grid key (`extract::key`, global coordinates) of a global id; `KEY_INTERIOR` for
/// cell-interior points.
pub(super) fn key_of_id(id: u64, d: [usize; 3]) -> u64 {
    let [nx, ny, nz] = d.map(|v| v as u64);
    if id >= 16 * nx * ny * nz {
        return KEY_INTERIOR;
    }
    let sigma = id % 4;
    let r = id / 4;
    let x = r % nx;
    let r = r / nx;
    let s = r % 2;
    let r = r / 2;
    let y = r % ny;
    let zz = r / ny;
    let (z, l) = (zz / 2, zz % 2);
    let kind = ORDER.iter().position(|&o| o == (l, s, sigma)).unwrap_or(0);
    key(kind as u64, x as usize, y as usize, z as usize)
}

pub(super) fn cell_index(c: [usize; 3], d: [usize; 3]) -> u64 {
    c[0] as u64 + d[0] as u64 * (c[1] as u64 + d[1] as u64 * c[2] as u64)
}

fn bad(reason: String) -> VolumeError {
    VolumeError::BadBlock { reason }
}

/// Contours the cells `cells[k][0]..cells[k][1]` (global cell indices along each axis; cell i
/// spans samples i and i + 1) of the grid `grid`, given the block `samples` of `dims` samples
/// (x fastest) whose sample (0, 0, 0) is the grid's sample `offset`.
///
/// The block must hold the samples of its cells (`offset ≤ c₀` and `c₁ < offset + dims`) and,
/// for grid-gradient normals, a one-sample halo where the grid continues (`offset ≤ c₀ − 1`
/// unless c₀ = 0, `offset + dims ≥ c₁ + 2` unless that passes the grid's end) — the
/// stencils then are those of the whole grid, which is what makes the stitched normals
/// identical. `range` is the smallest and largest finite sample of the *whole* grid (`None`:
/// there is none); it sets ε (Rem. 3.8) and must be the same for every block. `opts.parallel`
/// and `opts.topology` are ignored here (blocks are extracted serially; topology is
/// [`stitch_blocks`]'s).
///
/// Errors: a block outside the grid or missing samples, a sample count that does not match
/// `dims`, a non-finite level, or the limits of the module doc. A level outside `range` gives
/// an empty block.
///
/// ```
/// use morpho::volume::{isosurface, isosurface_block, stitch_blocks, IsoOptions, Volume, VolumeGrid};
/// let v = Volume::from_fn([12, 10, 9], [-1.0; 3], [1.0; 3], |x, y, z| x * x + y * y + z * z);
/// let opts = IsoOptions { level: 0.5, ..Default::default() };
/// let grid = VolumeGrid::of(&v);
/// // two blocks along z: cells 0..4 and 4..8, each with its halo
/// let block = |z0: usize, z1: usize| {
///     let (s0, s1) = (z0.saturating_sub(1), (z1 + 2).min(9));
///     let samples = v.data[120 * s0..120 * s1].to_vec();
///     let cells = [[0, 11], [0, 9], [z0, z1]];
///     isosurface_block(&grid, &samples, [12, 10, s1 - s0], [0, 0, s0], cells, v.value_range(), &opts)
/// };
/// let blocks = vec![block(0, 4).unwrap(), block(4, 8).unwrap()];
/// let stitched = stitch_blocks(&grid, blocks, v.value_range(), &opts).unwrap();
/// assert_eq!(stitched, isosurface(&v, &opts).unwrap());
/// ```
pub fn isosurface_block(
    grid: &VolumeGrid,
    samples: &[f32],
    dims: [usize; 3],
    offset: [usize; 3],
    cells: [[usize; 2]; 3],
    range: Option<(f32, f32)>,
    opts: &IsoOptions,
) -> Result<IsoBlock, VolumeError> {
    grid.validate()?;
    if !opts.level.is_finite() {
        return Err(VolumeError::NonFiniteLevel { level: opts.level });
    }
    let n = dims[0]
        .checked_mul(dims[1])
        .and_then(|v| v.checked_mul(dims[2]))
        .ok_or(VolumeError::DimsOverflow { dims })?;
    if n != samples.len() {
        return Err(VolumeError::SampleCount {
            found: samples.len(),
            dims,
            needed: n,
        });
    }
    let g = grid.dims;
    let grid_normals = matches!(
        opts.normals,
        NormalMethod::ZuckerHummel | NormalMethod::Central
    );
    for k in 0..3 {
        let [c0, c1] = cells[k];
        if offset[k] + dims[k] > g[k] {
            return Err(bad(format!(
                "samples {}..{} along axis {k} pass the grid's {} samples",
                offset[k],
                offset[k] + dims[k],
                g[k]
            )));
        }
        if c0 > c1 || c1 + 1 > g[k].max(1) {
            return Err(bad(format!(
                "cells {c0}..{c1} along axis {k} are not cells of a grid of {} samples",
                g[k]
            )));
        }
        if c0 == c1 {
            continue;
        }
        if offset[k] > c0 || c1 + 1 > offset[k] + dims[k] {
            return Err(bad(format!(
                "cells {c0}..{c1} along axis {k} need samples {c0}..={c1}, the block has {}..{}",
                offset[k],
                offset[k] + dims[k]
            )));
        }
        let (h0, h1) = (c0.saturating_sub(1), (c1 + 2).min(g[k]));
        if grid_normals && (offset[k] > h0 || offset[k] + dims[k] < h1) {
            return Err(bad(format!(
                "gradient normals of cells {c0}..{c1} along axis {k} need samples {h0}..{h1} \
                 (a one-sample halo), the block has {}..{}",
                offset[k],
                offset[k] + dims[k]
            )));
        }
    }
    if cells.iter().any(|c| c[0] == c[1]) {
        return Ok(IsoBlock::default());
    }
    let Ok(eps) = perturbation(g, range, opts.level) else {
        return Ok(IsoBlock::default());
    };
    // the block with its halo (gradients) and the samples of its cells (extraction), both with
    // the plane coordinates of the whole grid
    let coords = |lo: [usize; 3], len: [usize; 3]| -> [Vec<f64>; 3] {
        std::array::from_fn(|k| (lo[k]..lo[k] + len[k]).map(|i| grid.coord(k, i)).collect())
    };
    let gvol = Volume {
        dims,
        axes: Axes::Coords(coords(offset, dims)),
        data: samples.to_vec(),
        source_dtype: DType::F32,
        orientation: Orientation::default(),
    };
    let c0 = cells.map(|c| c[0]);
    let e: [usize; 3] = std::array::from_fn(|k| cells[k][1] - cells[k][0] + 1);
    let goff: [usize; 3] = std::array::from_fn(|k| c0[k] - offset[k]);
    let mut data = Vec::with_capacity(e[0] * e[1] * e[2]);
    for z in 0..e[2] {
        for y in 0..e[1] {
            let at = goff[0] + dims[0] * (goff[1] + y + dims[1] * (goff[2] + z));
            data.extend_from_slice(&samples[at..at + e[0]]);
        }
    }
    let vol = Volume {
        dims: e,
        axes: Axes::Coords(coords(c0, e)),
        data,
        source_dtype: DType::F32,
        orientation: Orientation::default(),
    };
    let (axes, gaxes) = (axis_coords(&vol), axis_coords(&gvol));
    let central = (opts.normals == NormalMethod::Central).then(|| CentralTable::new(&gvol, &gaxes));
    let ctx = Ctx {
        vol: &vol,
        axes: &axes,
        alpha: opts.level,
        eps,
        method: opts.method,
        normals: opts.normals,
        flip: opts.flip,
        keys: true,
        parts: false,
        central: central.as_ref(),
        gvol: &gvol,
        gaxes: &gaxes,
        goff,
        cells: true,
    };
    let out = ctx.chunk(0, e[2] - 1);
    drop(vol);
    drop(gvol);
    let ne = out.pos.len();
    if out.overflow || ne + out.ipos.len() >= INTERIOR as usize {
        return Err(VolumeError::TooManyVertices {
            vertices: ne + out.ipos.len(),
        });
    }
    let global = |p: [usize; 3]| -> [usize; 3] { std::array::from_fn(|k| p[k] + c0[k]) };
    let mut ids = Vec::with_capacity(ne + out.ipos.len());
    for &k in &out.keys {
        let kind = (k >> 60) as usize;
        let p = [
            (k >> 40 & 0xFFFFF) as usize,
            (k >> 20 & 0xFFFFF) as usize,
            (k & 0xFFFFF) as usize,
        ];
        ids.push(entity_id(kind, global(p), g));
    }
    let base = 16 * (g[0] as u64 * g[1] as u64 * g[2] as u64);
    let mut rank = 0u64;
    for (i, &c) in out.icell.iter().enumerate() {
        rank = if i > 0 && out.icell[i - 1] == c {
            rank + 1
        } else {
            0
        };
        if rank >= 4 {
            return Err(bad(format!("more than four interior points in cell {c:?}")));
        }
        ids.push(base + 4 * cell_index(global(c), g) + rank);
    }
    let mut positions = out.pos;
    positions.extend_from_slice(&out.ipos);
    let normals = grid_normals.then(|| {
        let mut nr = out.nrm;
        nr.extend_from_slice(&out.inrm);
        nr
    });
    let mut triangles = out.tris;
    for t in &mut triangles {
        for v in t.iter_mut() {
            if *v & INTERIOR != 0 {
                *v = ne as u32 + (*v & !INTERIOR);
            }
        }
    }
    Ok(IsoBlock {
        ids,
        positions,
        normals,
        triangles,
        triangle_cells: out
            .tcell
            .iter()
            .map(|&c| cell_index(global(c), g))
            .collect(),
        nan_cells: out
            .nan_cells
            .iter()
            .map(|&c| cell_index(global(c), g))
            .collect(),
        fan_points: out.fans,
        centroid_fallbacks: out.centroids,
        zero_normals: out.zero_normals,
    })
}

/// Stitches the blocks of [`isosurface_block`] (any order, each cell in at most one block)
/// into the surface [`isosurface`](super::isosurface) gives for the whole grid: the same
/// [`IsoResult`] when the blocks cover every cell and were made with the same `range` and
/// options. `opts.topology` adds the parts, boundary edges and holes of the whole surface.
///
/// Errors: two blocks owning one cell, or disagreeing on a shared point (position or normal
/// bits) — blocks of different volumes, ranges or options; more than 2³¹ − 1 vertices.
pub fn stitch_blocks(
    grid: &VolumeGrid,
    blocks: Vec<IsoBlock>,
    range: Option<(f32, f32)>,
    opts: &IsoOptions,
) -> Result<IsoResult, VolumeError> {
    grid.validate()?;
    if !opts.level.is_finite() {
        return Err(VolumeError::NonFiniteLevel { level: opts.level });
    }
    if let Err(note) = perturbation(grid.dims, range, opts.level) {
        return Ok(IsoResult {
            note: Some(note),
            ..Default::default()
        });
    }
    let g = grid.dims;
    for (b, blk) in blocks.iter().enumerate() {
        if !blk.consistent() {
            return Err(bad(format!(
                "block {b} is inconsistent (ids, normals, triangles or cells do not match its \
                 vertices)"
            )));
        }
    }
    let grid_normals = matches!(
        opts.normals,
        NormalMethod::ZuckerHummel | NormalMethod::Central
    );
    // vertices: sort by global id, merge equal ids
    let mut ent: Vec<(u64, u32, u32)> = Vec::new();
    for (b, blk) in blocks.iter().enumerate() {
        ent.extend(
            blk.ids
                .iter()
                .enumerate()
                .map(|(l, &id)| (id, b as u32, l as u32)),
        );
    }
    ent.sort_unstable();
    let mut map: Vec<Vec<u32>> = blocks
        .iter()
        .map(|b| vec![u32::MAX; b.positions.len()])
        .collect();
    let mut pos = Vec::new();
    let mut nrm = Vec::new();
    let mut keys = Vec::new();
    let same = |a: &Point3, b: &Point3| (0..3).all(|k| a[k].to_bits() == b[k].to_bits());
    let same_n = |a: &Vector3, b: &Vector3| (0..3).all(|k| a[k].to_bits() == b[k].to_bits());
    let mut i = 0;
    while i < ent.len() {
        let (id, b, l) = ent[i];
        let p = blocks[b as usize].positions[l as usize];
        let nv = pos.len();
        if nv >= INTERIOR as usize {
            return Err(VolumeError::TooManyVertices { vertices: nv });
        }
        let nr = blocks[b as usize].normals.as_ref().map(|n| n[l as usize]);
        let mut j = i;
        while j < ent.len() && ent[j].0 == id {
            let (_, bj, lj) = ent[j];
            let blk = &blocks[bj as usize];
            let nj = blk.normals.as_ref().map(|n| n[lj as usize]);
            let normals_agree = match (nr, nj) {
                (Some(a), Some(b)) => same_n(&a, &b),
                (None, None) => true,
                _ => false,
            };
            if !same(&p, &blk.positions[lj as usize]) || !normals_agree {
                return Err(VolumeError::BlocksDisagree {
                    reason: format!("blocks {b} and {bj} give different points for id {id}"),
                });
            }
            map[bj as usize][lj as usize] = nv as u32;
            j += 1;
        }
        pos.push(p);
        if grid_normals {
            nrm.push(nr.unwrap_or_else(Vector3::zeros));
        }
        if opts.topology {
            keys.push(key_of_id(id, g));
        }
        i = j;
    }
    drop(ent);
    // triangles: in cell order, each cell's in the order its block emitted them
    let mut tord: Vec<(u64, u32, u32)> = Vec::new();
    for (b, blk) in blocks.iter().enumerate() {
        tord.extend(
            blk.triangle_cells
                .iter()
                .enumerate()
                .map(|(t, &c)| (c, b as u32, t as u32)),
        );
    }
    tord.sort_unstable();
    for w in tord.windows(2) {
        if w[0].0 == w[1].0 && w[0].1 != w[1].1 {
            return Err(VolumeError::BlocksDisagree {
                reason: format!("blocks {} and {} both own cell {}", w[0].1, w[1].1, w[0].0),
            });
        }
    }
    let tris: Vec<[u32; 3]> = tord
        .iter()
        .map(|&(_, b, t)| {
            blocks[b as usize].triangles[t as usize].map(|v| map[b as usize][v as usize])
        })
        .collect();
    drop(tord);
    let mut nan: Vec<u64> = blocks
        .iter()
        .flat_map(|b| b.nan_cells.iter().copied())
        .collect();
    nan.sort_unstable();
    let len0 = nan.len();
    nan.dedup();
    if nan.len() != len0 {
        return Err(VolumeError::BlocksDisagree {
            reason: "two blocks own the same NaN cell".into(),
        });
    }
    let mut r = IsoResult {
        mesh: TriMesh::new(pos, tris),
        fan_points: blocks.iter().map(|b| b.fan_points).sum(),
        centroid_fallbacks: blocks.iter().map(|b| b.centroid_fallbacks).sum(),
        skipped_cells: nan.len(),
        ..Default::default()
    };
    if grid_normals {
        r.mesh.normals = Some(nrm);
    }
    let zero_normals = blocks.iter().any(|b| b.zero_normals);
    drop(blocks);
    let nan_cell = |c: [usize; 3]| nan.binary_search(&cell_index(c, g)).is_ok();
    let gr = (grid.dims, &grid.axes, &grid.orientation);
    Ok(finish(
        r,
        super::Topo::Keys(keys),
        zero_normals,
        gr,
        nan_cell,
        opts,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_decode_to_their_keys() {
        let d = [5, 4, 3];
        let mut seen = Vec::new();
        for kind in 0..7 {
            for z in 0..3 {
                for y in 0..4 {
                    for x in 0..5 {
                        let id = entity_id(kind, [x, y, z], d);
                        assert!(id < 16 * 60);
                        assert_eq!(key_of_id(id, d), key(kind as u64, x, y, z));
                        seen.push(id);
                    }
                }
            }
        }
        seen.sort_unstable();
        let n = seen.len();
        seen.dedup();
        assert_eq!(seen.len(), n, "ids are unique");
        assert_eq!(key_of_id(16 * 60 + 7, d), KEY_INTERIOR);
    }
}

//! Contour surfaces f = α of rectilinear volumes (Hamann 1991, §3.1–3.4).
//!
//! Three methods ([`IsoMethod`]):
//! * `Decider` — consistent marching cubes (H §3.2): contour points by linear interpolation on
//!   cell edges; on faces with four contour points (Eq. 3.5) the asymptotic decider of the
//!   bilinear face interpolant (Thm. 3.3, Eq. 3.8) joins the points lying in the same quadrant of
//!   the hyperbola's asymptotes — computed as the sign of the saddle value, i.e. comparing the
//!   products of the two diagonals; in the degenerate case (the contour is the two asymptotes)
//!   the positive corners are cut off, H's preferred "adhoc" rule. Linking the face segments
//!   gives closed polygons of 3–12 points per cell; a polygon with at most one segment per face
//!   is fan-triangulated from its first point (Thm. 3.4 (i)), a polygon with two segments on one
//!   face is triangulated as a fan around an interior contour point of the trilinear interpolant
//!   (Thm. 3.5–3.6, Eqs. 3.10–3.11), or around the polygon's centroid when Eq. 3.11's
//!   denominator vanishes (Rem. 3.9) or the point leaves the cell (the hazard of Rem. 3.10), so
//!   Condition 3.1 holds and the triangulation is continuous (Def. 3.11).
//! * `Tetra` — the six-tetrahedra split T¹…T⁶ of H §3.2 with linear interpolation in each
//!   tetrahedron; contour points also lie on face and body diagonals.
//! * `Lorensen` — Lorensen & Cline's cell-local rule (the baseline with holes, H Fig. 3.2): each
//!   ambiguous face cuts off the corners of the cell's minority sign, polygons are fanned without
//!   interior points.
//!
//! Samples equal to α are raised by ε = 10⁻⁹·(max − min) (Rem. 3.8), so every decision sees
//! f ≠ α. Vertices are shared: one per cut grid entity (edge/diagonal). Triangles are oriented
//! with normals pointing out of the region {f > α} (i.e. along −∇f, "inside = above α", the
//! CT convention); [`IsoOptions::flip`] reverses this (normals along +∇f, H's Def. 3.14 when the
//! inside is {f < α}). Vertex normals ([`NormalMethod`]) follow the same orientation.
//!
//! NaN samples: cells with a NaN corner are skipped; the surface then has boundary edges on the
//! faces of skipped cells, which are counted as boundary edges (like the volume's outer faces),
//! not as interior holes; the count of skipped cells is put in the note. NaN never panics.
//! Infinite samples are ordinary samples on their side of α; a contour point on an edge with
//! an infinite end sits at the finite end.
//!
//! Topology (H §3.3): edges are grouped per vertex (counting sort, O(n)); triangles sharing an
//! edge are neighbours (Def. 3.7) and are merged into parts with union–find (the result of
//! Alg. 3.2, without its O(n²) relabelling); part labels are numbered in order of first triangle
//! and stored as the face property `part`. Boundary edges (one triangle) are classified by the grid
//! face they lie on: on the volume's outer faces (or next to a skipped cell) they are boundary
//! edges of Def. 3.6, otherwise they belong to an interior hole (Def. 3.10).
//!
//! Complexity: O(N + T) for N samples and T triangles; parallel over z-slabs (rayon) with output
//! identical to the serial run (the vertex order is canonical, see `extract`). Memory: the
//! volume, the output, and per running slab O(nx·ny) work space (sign codes, vertex index arrays,
//! a two-plane gradient cache); the slabs' outputs are appended into the first slab's buffers,
//! so a parallel run may hold up to about twice the output briefly. With `topology`, per-vertex
//! grid keys (8 bytes) and a transient edge table (24 bytes per triangle, whose memory then
//! holds the part labels, and 4 per vertex and per triangle for grouping and union–find) are
//! added. The topology tables ask for transparent huge pages
//! (`util::advise_huge_pages`: fewer page faults, same contents).

mod block;
mod extract;
mod stream;
mod tables;

pub use block::{isosurface_block, stitch_blocks, IsoBlock, VolumeGrid};
pub use stream::{IsoStream, StreamPiece, StreamSummary, INTERIOR_REF};

use crate::geom::Vector3;
use crate::mesh::{Property, ScalarKind, TriMesh};
use crate::util::advise_huge_pages;
use crate::volume::gradient::{axis_coords, mesh_normals, mesh_normals_where, CentralTable};
use crate::volume::Volume;
use crate::volume::VolumeError;
use extract::{extent, ChunkOut, Ctx, INTERIOR, KEY_INTERIOR};
use rayon::prelude::*;

/// Contouring method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum IsoMethod {
    /// Marching cubes with the asymptotic decider and interior points (consistent).
    #[default]
    Decider,
    /// Six tetrahedra per cell (consistent).
    Tetra,
    /// Lorensen–Cline cell-local table (may leave holes).
    Lorensen,
}

/// How vertex normals are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalMethod {
    /// Zucker–Hummel 3·3·3 gradients at grid points, interpolated (H Thm. 3.8, Eqs. 3.18–3.19).
    #[default]
    ZuckerHummel,
    /// Central differences at grid points, interpolated.
    Central,
    /// From the triangulation alone (H Rem. 3.15).
    Mesh,
    /// No normals.
    None,
}

/// Options of [`isosurface`].
#[derive(Debug, Clone, PartialEq)]
pub struct IsoOptions {
    /// Contour level α.
    pub level: f64,
    /// Which extraction (marching cubes, marching tetrahedra, …).
    pub method: IsoMethod,
    /// How vertex normals are computed.
    pub normals: NormalMethod,
    /// Orient triangles and normals along +∇f (out of {f < α}) instead of −∇f.
    pub flip: bool,
    /// Run slabs in parallel (output is identical either way).
    pub parallel: bool,
    /// Compute parts, boundary edges and holes (O(T) extra work and memory).
    pub topology: bool,
}

impl Default for IsoOptions {
    fn default() -> Self {
        IsoOptions {
            level: 0.0,
            method: IsoMethod::Decider,
            normals: NormalMethod::ZuckerHummel,
            flip: false,
            parallel: true,
            topology: true,
        }
    }
}

/// Result of [`isosurface`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct IsoResult {
    /// The triangulation; face property `part` when topology was computed.
    pub mesh: TriMesh,
    /// Number of parts (0 when topology was not computed).
    pub parts: usize,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Of those, edges not lying on the volume's outer faces nor next to a skipped cell.
    pub interior_boundary_edges: usize,
    /// Closed boundary loops containing an interior boundary edge (Def. 3.10 interior holes).
    pub interior_holes: usize,
    /// Edges shared by more than two triangles.
    pub non_manifold_edges: usize,
    /// Polygons triangulated around an interior point (Thm. 3.6).
    pub fan_points: usize,
    /// Of those, points taken as the polygon centroid (Rem. 3.9/3.10).
    pub centroid_fallbacks: usize,
    /// Cells skipped because a corner is NaN.
    pub skipped_cells: usize,
    /// Explanation when the result is empty or degraded (level outside the range, NaN cells).
    pub note: Option<String>,
}

/// Extracts the contour surface f = `opts.level` of `vol`.
///
/// Errors: invalid volume (sizes, axes), non-finite level, an axis longer than 2²⁰ samples, or
/// more than 2³¹ − 1 vertices. A level outside the data range, or a volume thinner than two
/// samples along some axis, gives an empty mesh and a note.
///
/// ```
/// use morpho::mesh::analyze_topology;
/// use morpho::volume::{isosurface, IsoOptions, Volume};
/// // f = x² + y² + z² on 16³ samples over [-1, 1]³: the level 0.5 is a sphere
/// let v = Volume::from_fn([16; 3], [-1.0; 3], [1.0; 3], |x, y, z| x * x + y * y + z * z);
/// let r = isosurface(&v, &IsoOptions { level: 0.5, ..Default::default() }).unwrap();
/// assert_eq!((r.parts, r.boundary_edges, r.interior_holes), (1, 0, 0));
/// let t = analyze_topology(&r.mesh);
/// assert!(t.is_closed() && t.manifold && t.consistently_oriented);
/// assert_eq!((t.euler_characteristic, t.genus()), (2, Some(0)));
/// // a level outside the data range gives an empty mesh and a note, not an error
/// let r = isosurface(&v, &IsoOptions { level: 9.0, ..Default::default() }).unwrap();
/// assert!(r.mesh.triangles.is_empty() && r.note.is_some());
/// ```
pub fn isosurface(vol: &Volume, opts: &IsoOptions) -> Result<IsoResult, VolumeError> {
    vol.validate()?;
    if !opts.level.is_finite() {
        return Err(VolumeError::NonFiniteLevel { level: opts.level });
    }
    if vol.dims.iter().any(|&d| d >= 1 << 20) {
        return Err(VolumeError::AxisTooLong { dims: vol.dims });
    }
    let range = if vol.dims.iter().any(|&d| d < 2) {
        None
    } else {
        fast_range(&vol.data).or_else(|| vol.value_range())
    };
    let eps = match perturbation(vol.dims, range, opts.level) {
        Ok(eps) => eps,
        Err(note) => {
            return Ok(IsoResult {
                note: Some(note),
                ..Default::default()
            })
        }
    };
    let axes = axis_coords(vol);
    let central = (opts.normals == NormalMethod::Central).then(|| CentralTable::new(vol, &axes));
    // the decider's topology is found during the extraction (`decider_analysis`); other
    // methods, and any run that skips a NaN cell, take the edge-table pass (`analyze`)
    let parts = opts.topology && opts.method == IsoMethod::Decider;
    let mut ctx = Ctx {
        vol,
        axes: &axes,
        alpha: opts.level,
        eps,
        method: opts.method,
        normals: opts.normals,
        flip: opts.flip,
        keys: opts.topology && !parts,
        parts,
        central: central.as_ref(),
        gvol: vol,
        gaxes: &axes,
        goff: [0; 3],
        cells: false,
    };
    let layers = vol.dims[2] - 1;
    let threads = rayon::current_num_threads().max(1);
    let per = if opts.parallel {
        layers.div_ceil(4 * threads).max(2)
    } else {
        layers
    };
    let ranges: Vec<(usize, usize)> = (0..layers)
        .step_by(per)
        .map(|z0| (z0, (z0 + per).min(layers)))
        .collect();
    let run = |ctx: &Ctx| -> Vec<ChunkOut> {
        if opts.parallel && ranges.len() > 1 {
            ranges.par_iter().map(|&(a, b)| ctx.chunk(a, b)).collect()
        } else {
            ranges.iter().map(|&(a, b)| ctx.chunk(a, b)).collect()
        }
    };
    let mut chunks = run(&ctx);
    if parts && chunks.iter().any(|c| c.skipped_cells > 0) {
        // NaN cells: the surface may end inside the volume, vertex unions no longer give the
        // edge-connected parts, and the boundary edges need grid keys: extract again with keys
        drop(chunks);
        ctx.parts = false;
        ctx.keys = true;
        chunks = run(&ctx);
    }
    let vps: Vec<(Vec<u32>, usize, usize)> = chunks
        .iter_mut()
        .map(|c| (std::mem::take(&mut c.vp), c.last_plane_start, c.outer))
        .collect();
    let zero_normals = chunks.iter().any(|c| c.zero_normals);
    let (r, keys) = assemble(chunks, opts)?;
    let topo = if ctx.parts {
        Topo::Parents(global_parents(vps))
    } else {
        Topo::Keys(keys)
    };
    let nan_cell = |c: [usize; 3]| {
        (0..8).any(|k| {
            vol.at(c[0] + (k & 1), c[1] + (k >> 1 & 1), c[2] + (k >> 2 & 1))
                .is_nan()
        })
    };
    let grid = (vol.dims, &vol.axes, &vol.orientation);
    Ok(finish(r, topo, zero_normals, grid, nan_cell, opts))
}

/// What [`finish`] computes the topology from.
pub(super) enum Topo {
    /// Grid keys of the vertices (empty without topology): the edge-table pass [`analyze`].
    Keys(Vec<u64>),
    /// The decider's vertex parents over the grid-edge vertices and the outer-face polygon
    /// sides ([`global_parents`]): [`decider_analysis`]. Never with skipped cells.
    Parents((Vec<u32>, usize)),
}

/// The union–find parents of all grid-edge vertices (numbered as [`assemble`] numbers them)
/// from the slabs' `(parents, last_plane_start, outer sides)`, and the total of outer sides.
/// A slab's last plane is the next slab's first (same vertices in the same order, see
/// `extract`): its vertices are dropped and their links to their parents replayed as unions.
/// Assumes `assemble` accepted the slabs (fewer than 2³¹ vertices).
fn global_parents(vps: Vec<(Vec<u32>, usize, usize)>) -> (Vec<u32>, usize) {
    let nc = vps.len();
    let outer = vps.iter().map(|v| v.2).sum();
    if nc == 1 {
        let vp = vps.into_iter().next().map(|v| v.0).unwrap_or_default();
        return (vp, outer);
    }
    let ne: usize = vps
        .iter()
        .enumerate()
        .map(|(i, v)| if i + 1 == nc { v.0.len() } else { v.1 })
        .sum();
    let mut vp = Vec::with_capacity(ne);
    let mut links = Vec::new();
    for (i, (p, lps, _)) in vps.into_iter().enumerate() {
        let eo = vp.len() as u32;
        let keep = if i + 1 == nc { p.len() } else { lps };
        vp.extend(p[..keep].iter().map(|&q| q + eo));
        links.extend((keep..p.len()).map(|v| (eo + v as u32, eo + p[v])));
    }
    for (a, b) in links {
        union(&mut vp, a, b);
    }
    (vp, outer)
}

/// Parts and boundary edges of a decider surface without skipped cells (H §3.3), from the
/// vertex parents `vp` of its grid-edge vertices (indices `< vp.len()`, every other index an
/// interior fan point; a parent never after its child) and the polygon sides on the volume's
/// outer faces.
///
/// Why vertex unions give the edge-connected parts: a polygon is one connected run of
/// triangles (fan diagonals, or spokes to its interior point), and two polygons share an
/// edge only along a face segment; the asymptotic decider resolves a face from its four
/// samples alone, so both cells of an interior face have the same segments on it, each used
/// once by each cell: no boundary edge inside the volume, no non-manifold edge, no hole. A
/// grid-edge vertex belongs to one polygon per cell around its edge, and those cells (all
/// valid, all crossed) follow one another around the edge across shared faces whose segment
/// ends at the vertex: polygons sharing a vertex are edge-connected. So a part is a set of
/// vertices, and the boundary edges are the outer-face segments. Parts are numbered by their
/// first triangle, as [`analyze`] numbers them (`tests::decider_topology_matches_the_edge_table`).
fn decider_analysis(tris: &[[u32; 3]], mut vp: Vec<u32>, outer: usize) -> Analysis {
    const LABELLED: u32 = 1 << 31;
    let ne = vp.len() as u32;
    // parents precede children: in increasing order a parent already points at its root
    for v in 0..vp.len() {
        vp[v] = vp[vp[v] as usize];
    }
    let mut labels = Vec::with_capacity(tris.len());
    let mut parts = 0u32;
    for t in tris {
        // every triangle has a grid-edge vertex (at most one corner is a fan point)
        let v = if t[0] < ne {
            t[0]
        } else if t[1] < ne {
            t[1]
        } else {
            t[2]
        };
        // a root's slot holds the root itself, or its part once numbered
        let r = vp[v as usize];
        let l = if r & LABELLED != 0 {
            r & !LABELLED
        } else {
            let q = vp[r as usize];
            if q & LABELLED != 0 {
                q & !LABELLED
            } else {
                vp[r as usize] = LABELLED | parts;
                parts += 1;
                parts - 1
            }
        };
        labels.push(l as f64);
    }
    Analysis {
        labels,
        parts: parts as usize,
        boundary_edges: outer,
        interior_boundary_edges: 0,
        interior_holes: 0,
        non_manifold_edges: 0,
    }
}

/// The perturbation ε of Rem. 3.8 for samples of finite range `range` (`None`: no finite
/// sample) and the level; or, when the surface is empty for want of cells or of a crossing,
/// the note saying so.
fn perturbation(dims: [usize; 3], range: Option<(f32, f32)>, level: f64) -> Result<f64, String> {
    if dims.iter().any(|&d| d < 2) {
        return Err(format!(
            "volume {dims:?} has no cells (needs at least 2 samples per axis)"
        ));
    }
    let Some((lo, hi)) = range else {
        return Err("volume has no finite sample".into());
    };
    let (lo, hi) = (lo as f64, hi as f64);
    if level < lo || level > hi {
        return Err(format!(
            "level {level} is outside the data range [{lo}, {hi}]: empty surface"
        ));
    }
    let range = hi - lo;
    Ok(if range > 0.0 {
        range * 1e-9
    } else {
        1e-9 * level.abs().max(1.0)
    })
}

/// The grid a surface was extracted from: dimensions, axes and orientation.
type GridRef<'a> = (
    [usize; 3],
    &'a crate::volume::Axes,
    &'a crate::volume::Orientation,
);

/// Everything after the extraction proper, shared by [`isosurface`] and the stitching of
/// blocks: unreferenced vertices dropped (after NaN cells), normal fallbacks, the topology
/// analysis, notes and the world transform. `keys` are the grid keys of the vertices (empty
/// without topology), `nan_cell(c)` tells whether cell `c` has a NaN corner (asked only when
/// cells were skipped).
fn finish(
    mut r: IsoResult,
    topo: Topo,
    zero_normals: bool,
    grid: GridRef<'_>,
    nan_cell: impl Fn([usize; 3]) -> bool,
    opts: &IsoOptions,
) -> IsoResult {
    let (dims, axes, orientation) = grid;
    let (mut keys, parents) = match topo {
        Topo::Keys(k) => (k, None),
        Topo::Parents(p) => (Vec::new(), Some(p)),
    };
    if r.skipped_cells > 0 {
        drop_unreferenced(&mut r.mesh, &mut keys);
        r.note = Some(format!(
            "{} cells with a NaN corner were skipped; the surface ends at their faces",
            r.skipped_cells
        ));
    }
    match opts.normals {
        NormalMethod::ZuckerHummel | NormalMethod::Central => {
            let missing = zero_normals
                && r.mesh
                    .normals
                    .as_ref()
                    .is_some_and(|nr| nr.iter().any(|n| n.x == 0.0 && n.y == 0.0 && n.z == 0.0));
            if missing {
                // flat spots (zero gradient) or NaN stencils: normals from the mesh there
                let mut m = Vec::new();
                if let Some(nr) = &r.mesh.normals {
                    m = mesh_normals_where(&r.mesh, |v| {
                        nr[v].x == 0.0 && nr[v].y == 0.0 && nr[v].z == 0.0
                    });
                }
                if let Some(nr) = &mut r.mesh.normals {
                    for (n, mn) in nr.iter_mut().zip(m) {
                        if n.x == 0.0 && n.y == 0.0 && n.z == 0.0 {
                            *n = mn;
                        }
                    }
                }
            }
        }
        NormalMethod::Mesh => r.mesh.normals = Some(mesh_normals(&r.mesh)),
        NormalMethod::None => r.mesh.normals = None,
    }
    if opts.topology {
        let skipped = r.skipped_cells > 0;
        let valid_cell = |c: [i64; 3]| -> bool {
            for k in 0..3 {
                if c[k] < 0 || c[k] + 1 >= dims[k] as i64 {
                    return false;
                }
            }
            !skipped || !nan_cell([c[0] as usize, c[1] as usize, c[2] as usize])
        };
        let a = match parents {
            Some((vp, outer)) => decider_analysis(&r.mesh.triangles, vp, outer),
            None => analyze(&r.mesh, &keys, valid_cell),
        };
        r.parts = a.parts;
        r.boundary_edges = a.boundary_edges;
        r.interior_boundary_edges = a.interior_boundary_edges;
        r.interior_holes = a.interior_holes;
        r.non_manifold_edges = a.non_manifold_edges;
        r.mesh.face_props.push(Property {
            name: "part".into(),
            kind: ScalarKind::U32,
            values: a.labels,
        });
    }
    if r.mesh.triangles.is_empty() && r.note.is_none() {
        r.note = Some(format!("no contour at level {}", opts.level));
    }
    to_world(axes, orientation, &mut r.mesh);
    r
}

/// Places the surface in the volume's world space ([`crate::volume::Orientation`]): positions
/// by the axis directions about the origin, normals by the inverse transpose, and triangle
/// windings reversed when the directions mirror (so that normals and windings keep pointing to
/// the same side). A no-op for axis-aligned volumes.
fn to_world(axes: &crate::volume::Axes, o: &crate::volume::Orientation, mesh: &mut TriMesh) {
    let w = World::of(axes, o);
    if w.o.is_none() {
        return;
    }
    for p in &mut mesh.positions {
        *p = w.point(*p);
    }
    if let Some(ns) = &mut mesh.normals {
        for n in ns.iter_mut() {
            *n = w.normal(*n);
        }
    }
    if w.mirrors() {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
    }
}

/// Where a volume's grid frame sits in world space, point by point ([`to_world`] applies it to
/// a whole mesh, the stream to each emitted piece): `o` is `None` for axis-aligned volumes and
/// per-index axes, where the grid frame is the world frame.
pub(super) struct World<'a> {
    origin: [f64; 3],
    o: Option<&'a crate::volume::Orientation>,
}

impl<'a> World<'a> {
    pub(super) fn of(axes: &crate::volume::Axes, o: &'a crate::volume::Orientation) -> World<'a> {
        match *axes {
            crate::volume::Axes::Uniform { origin, .. } if !o.is_axis_aligned() => {
                World { origin, o: Some(o) }
            }
            _ => World {
                origin: [0.0; 3],
                o: None,
            },
        }
    }
    pub(super) fn point(&self, p: crate::geom::Point3) -> crate::geom::Point3 {
        match self.o {
            Some(o) => {
                let w = o.to_world(self.origin, [p.x, p.y, p.z]);
                crate::geom::Point3::new(w[0], w[1], w[2])
            }
            None => p,
        }
    }
    pub(super) fn normal(&self, n: Vector3) -> Vector3 {
        match self.o {
            Some(o) => {
                let w = o.normal_to_world([n.x, n.y, n.z]);
                Vector3::new(w[0], w[1], w[2])
            }
            None => n,
        }
    }
    /// The directions mirror: triangle windings are reversed.
    pub(super) fn mirrors(&self) -> bool {
        self.o.is_some_and(|o| o.determinant() < 0.0)
    }
}

/// Smallest and largest sample ignoring NaN (`f32::min`/`max` skip a NaN operand), in chunks
/// that vectorise; `None` when a sample is infinite or there is no finite one (then
/// [`Volume::value_range`] decides).
fn fast_range(data: &[f32]) -> Option<(f32, f32)> {
    let (mut lo, mut hi) = ([f32::INFINITY; 8], [f32::NEG_INFINITY; 8]);
    let mut it = data.chunks_exact(8);
    for c in &mut it {
        for k in 0..8 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let (mut l, mut h) = (f32::INFINITY, f32::NEG_INFINITY);
    for &v in it.remainder().iter().chain(&lo) {
        l = l.min(v);
    }
    for &v in it.remainder().iter().chain(&hi) {
        h = h.max(v);
    }
    (l.is_finite() && h.is_finite()).then_some((l, h))
}

/// Concatenates slab outputs in canonical order; returns the result and per-vertex grid keys.
fn assemble(
    chunks: Vec<ChunkOut>,
    opts: &IsoOptions,
) -> Result<(IsoResult, Vec<u64>), VolumeError> {
    let nc = chunks.len();
    let mut edge_off = Vec::with_capacity(nc);
    let mut int_off = Vec::with_capacity(nc);
    let (mut ne, mut ni, mut nt) = (0usize, 0usize, 0usize);
    for (i, c) in chunks.iter().enumerate() {
        edge_off.push(ne);
        int_off.push(ni);
        ne += if i + 1 == nc {
            c.pos.len()
        } else {
            c.last_plane_start
        };
        ni += c.ipos.len();
        nt += c.tris.len();
    }
    if ne + ni >= INTERIOR as usize || chunks.iter().any(|c| c.overflow) {
        return Err(VolumeError::TooManyVertices { vertices: ne + ni });
    }
    let grid_normals = matches!(
        opts.normals,
        NormalMethod::ZuckerHummel | NormalMethod::Central
    );
    let mut r = IsoResult::default();
    // the first slab's buffers become the output (no copy for a serial run)
    let (mut pos, mut nrm, mut keys, mut tris) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut ipos = Vec::with_capacity(ni);
    let mut inrm = Vec::with_capacity(if grid_normals { ni } else { 0 });
    for (i, mut c) in chunks.into_iter().enumerate() {
        let keep = if i + 1 == nc {
            c.pos.len()
        } else {
            c.last_plane_start
        };
        c.pos.truncate(keep);
        c.keys.truncate(keep);
        c.nrm.truncate(keep);
        let (eo, io) = (edge_off[i] as u32, (ne + int_off[i]) as u32);
        let remap = |t: &mut [u32; 3]| {
            for v in t.iter_mut() {
                *v = if *v & INTERIOR != 0 {
                    io + (*v & !INTERIOR)
                } else {
                    eo + *v
                };
            }
        };
        if i == 0 {
            pos = std::mem::take(&mut c.pos);
            pos.reserve_exact(ne + ni - pos.len());
            nrm = std::mem::take(&mut c.nrm);
            if grid_normals {
                // room for the interior points' normals, so that no full copy is needed
                nrm.reserve_exact(ne + ni - nrm.len());
            }
            keys = std::mem::take(&mut c.keys);
            if opts.topology {
                keys.reserve_exact(ne + ni - keys.len());
            }
            tris = std::mem::take(&mut c.tris);
            tris.reserve_exact(nt - tris.len());
            tris.iter_mut().for_each(remap);
        } else {
            pos.append(&mut c.pos);
            nrm.append(&mut c.nrm);
            keys.append(&mut c.keys);
            c.tris.iter_mut().for_each(remap);
            tris.append(&mut c.tris);
        }
        ipos.append(&mut c.ipos);
        inrm.append(&mut c.inrm);
        r.fan_points += c.fans;
        r.centroid_fallbacks += c.centroids;
        r.skipped_cells += c.skipped_cells;
    }
    if opts.topology {
        keys.resize(ne + ni, KEY_INTERIOR);
    }
    pos.append(&mut ipos);
    nrm.append(&mut inrm);
    r.mesh = TriMesh::new(pos, tris);
    if grid_normals {
        r.mesh.normals = Some(nrm);
    }
    Ok((r, keys))
}

/// Removes vertices no triangle uses (only possible next to skipped NaN cells).
fn drop_unreferenced(mesh: &mut TriMesh, keys: &mut Vec<u64>) {
    let n = mesh.positions.len();
    let mut map = vec![u32::MAX; n];
    for t in &mesh.triangles {
        for &v in t {
            map[v as usize] = 0;
        }
    }
    let mut k = 0u32;
    for m in map.iter_mut() {
        if *m == 0 {
            *m = k;
            k += 1;
        }
    }
    if k as usize == n {
        return;
    }
    let keep = |i: usize| map[i] != u32::MAX;
    let mut i = 0;
    mesh.positions.retain(|_| {
        i += 1;
        keep(i - 1)
    });
    i = 0;
    keys.retain(|_| {
        i += 1;
        keep(i - 1)
    });
    if let Some(nr) = &mut mesh.normals {
        i = 0;
        nr.retain(|_| {
            i += 1;
            keep(i - 1)
        });
    }
    for t in &mut mesh.triangles {
        *t = t.map(|v| map[v as usize]);
    }
}

struct Analysis {
    /// Part label of each triangle (as the `part` face property stores it).
    labels: Vec<f64>,
    parts: usize,
    boundary_edges: usize,
    interior_boundary_edges: usize,
    interior_holes: usize,
    non_manifold_edges: usize,
}

fn find(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let g = p[p[x as usize] as usize];
        p[x as usize] = g;
        x = g;
    }
    x
}

fn union(p: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(p, a), find(p, b));
    if ra != rb {
        // smaller root wins: deterministic
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        p[hi as usize] = lo;
    }
}

/// The vertices of a triangle in increasing order: its three edges, each as (smaller end,
/// larger end), are (lo, mid), (lo, hi) and (mid, hi) whatever the winding, also when a
/// vertex repeats.
#[inline]
fn sorted3(t: &[u32; 3]) -> (u32, u32, u32) {
    let (a, b) = (t[0].min(t[1]), t[0].max(t[1]));
    let (lo, c) = (a.min(t[2]), a.max(t[2]));
    (lo, b.min(c), b.max(c))
}

/// Neighbours, parts and holes (H §3.3) of a contour triangulation with grid keys.
///
/// Assumes vertex indices `< keys.len()` and fewer than 2³² triangles (as [`assemble`] makes
/// them). The edge table groups the 3·T triangle edges by their smaller end; a triangle's
/// edges are (lo, mid), (lo, hi), (mid, hi) of its sorted vertices ([`sorted3`]), so it adds
/// two entries to group lo (side by side) and one to group mid: two scattered counter updates
/// and two scattered stores per triangle instead of three. Each group is the same multiset
/// as when the edges are taken one by one in winding order (`tests::analyze_edge_table`, the
/// oracle), and it is sorted by the whole entry, so every later step and result is the same.
fn analyze(mesh: &TriMesh, keys: &[u64], valid_cell: impl Fn([i64; 3]) -> bool) -> Analysis {
    let n = mesh.positions.len();
    let nt = mesh.triangles.len();
    // edges grouped by their smaller vertex (counting sort); an entry is the larger vertex
    // and the triangle, packed as (b << 32) | t so that sorting the u64s sorts by (b, t)
    let mut start = vec![0u32; n + 1];
    advise_huge_pages(&mut start);
    for t in &mesh.triangles {
        let (lo, mid, _) = sorted3(t);
        start[lo as usize + 1] += 2;
        start[mid as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    // start[a] is group a's cursor: after the scatter it is the group's end, i.e. the start
    // of group a + 1, and group a begins where group a − 1 ends
    let mut ent = vec![0u64; 3 * nt];
    advise_huge_pages(&mut ent);
    for (ti, t) in mesh.triangles.iter().enumerate() {
        let (lo, mid, hi) = sorted3(t);
        let ti = ti as u64;
        let s = start[lo as usize] as usize;
        ent[s] = (mid as u64) << 32 | ti;
        ent[s + 1] = (hi as u64) << 32 | ti;
        start[lo as usize] += 2;
        let s = &mut start[mid as usize];
        ent[*s as usize] = (hi as u64) << 32 | ti;
        *s += 1;
    }
    analyze_groups(n, ent, start, keys, valid_cell)
}

/// The rest of [`analyze`] from its filled edge table: `ent` holds the 3·T entries
/// `(b << 32) | t` of the edges grouped by their smaller end a (group a is
/// `ent[start[a − 1]..start[a]]`, group 0 starts at 0), each group in any order; `n` is the
/// vertex count. Sorts each group and walks it: an edge met once is a boundary edge, twice
/// joins its two triangles, more often is non-manifold (all its triangles joined).
fn analyze_groups(
    n: usize,
    mut ent: Vec<u64>,
    start: Vec<u32>,
    keys: &[u64],
    valid_cell: impl Fn([i64; 3]) -> bool,
) -> Analysis {
    let nt = ent.len() / 3;
    let mut tp: Vec<u32> = Vec::with_capacity(nt);
    advise_huge_pages(&mut tp);
    tp.extend(0..nt as u32);
    let mut bnd: Vec<(u32, u32, bool)> = Vec::new();
    let mut nonman = 0;
    let (vertex, tri) = (|e: u64| (e >> 32) as u32, |e: u64| e as u32);
    for a in 0..n {
        let begin = if a == 0 { 0 } else { start[a - 1] as usize };
        let s = &mut ent[begin..start[a] as usize];
        s.sort_unstable();
        let mut i = 0;
        while i < s.len() {
            let mut j = i + 1;
            while j < s.len() && vertex(s[j]) == vertex(s[i]) {
                j += 1;
            }
            match j - i {
                1 => {
                    let b = vertex(s[i]);
                    let interior = !on_domain_boundary(keys[a], keys[b as usize], &valid_cell);
                    bnd.push((a as u32, b, interior));
                }
                2 => union(&mut tp, tri(s[i]), tri(s[i + 1])),
                _ => {
                    nonman += 1;
                    for k in i + 1..j {
                        union(&mut tp, tri(s[i]), tri(s[k]));
                    }
                }
            }
            i = j;
        }
    }
    drop(start);
    // the smaller root wins every union, so a parent precedes its child and a part's root is
    // its first triangle: in increasing order, a triangle's parent already points at its root,
    // and the root is met (and numbered) before the rest of its part. The labels reuse the
    // edge table's memory (its first nt entries; the rest is given back)
    ent.truncate(nt);
    let mut parts = 0u32;
    for t in 0..nt {
        let r = tp[tp[t] as usize] as usize;
        tp[t] = r as u32;
        let label = if r == t {
            parts += 1;
            (parts - 1) as f64
        } else {
            f64::from_bits(ent[r])
        };
        ent[t] = label.to_bits();
    }
    let mut labels: Vec<f64> = ent.into_iter().map(f64::from_bits).collect();
    labels.shrink_to_fit();
    let interior_boundary_edges = bnd.iter().filter(|e| e.2).count();
    let mut interior_holes = 0;
    if interior_boundary_edges > 0 {
        let mut vp: Vec<u32> = (0..n as u32).collect();
        for &(a, b, _) in &bnd {
            union(&mut vp, a, b);
        }
        let mut roots: Vec<u32> = bnd
            .iter()
            .filter(|e| e.2)
            .map(|e| find(&mut vp, e.0))
            .collect();
        roots.sort_unstable();
        roots.dedup();
        interior_holes = roots.len();
    }
    Analysis {
        labels,
        parts: parts as usize,
        boundary_edges: bnd.len(),
        interior_boundary_edges,
        interior_holes,
        non_manifold_edges: nonman,
    }
}

/// True when the mesh edge between vertices with grid keys `ka`, `kb` lies on a cell face that
/// has no valid cell on one side (volume border or skipped cell).
fn on_domain_boundary(ka: u64, kb: u64, valid_cell: &impl Fn([i64; 3]) -> bool) -> bool {
    if ka == KEY_INTERIOR || kb == KEY_INTERIOR {
        return false;
    }
    for axis in 0..3 {
        let (Some(ea), Some(eb)) = (extent(ka, axis), extent(kb, axis)) else {
            return false;
        };
        if ea.0 == ea.1 && eb.0 == eb.1 && ea.0 == eb.0 {
            let mut cell = [0i64; 3];
            for o in 0..3 {
                if o != axis {
                    let (la, lb) = (
                        extent(ka, o).map_or(0, |e| e.0),
                        extent(kb, o).map_or(0, |e| e.0),
                    );
                    cell[o] = la.min(lb) as i64;
                }
            }
            cell[axis] = ea.0 as i64 - 1;
            let below = valid_cell(cell);
            cell[axis] = ea.0 as i64;
            let above = valid_cell(cell);
            return !(below && above);
        }
    }
    false
}

/// The triangles of part `part` (face property `part`), with unused vertices removed.
/// `mesh` must satisfy [`TriMesh::validate`] (vertex indices in range).
pub fn extract_part(mesh: &TriMesh, part: u32) -> TriMesh {
    let Some(labels) = mesh.face_prop("part") else {
        return mesh.clone();
    };
    let mut map = vec![u32::MAX; mesh.positions.len()];
    let mut out = TriMesh::default();
    let mut kept_faces = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if labels.values.get(t) != Some(&(part as f64)) {
            continue;
        }
        kept_faces.push(t);
        let nt = tri.map(|v| {
            if map[v as usize] == u32::MAX {
                map[v as usize] = out.positions.len() as u32;
                out.positions.push(mesh.positions[v as usize]);
            }
            map[v as usize]
        });
        out.triangles.push(nt);
    }
    if let Some(nr) = &mesh.normals {
        let mut o = vec![Vector3::zeros(); out.positions.len()];
        for (v, &m) in map.iter().enumerate() {
            if m != u32::MAX {
                o[m as usize] = nr.get(v).copied().unwrap_or_else(Vector3::zeros);
            }
        }
        out.normals = Some(o);
    }
    for p in &mesh.vertex_props {
        let mut vals = vec![0.0; out.positions.len()];
        for (v, &m) in map.iter().enumerate() {
            if m != u32::MAX {
                vals[m as usize] = p.values.get(v).copied().unwrap_or(f64::NAN);
            }
        }
        out.vertex_props.push(Property {
            name: p.name.clone(),
            kind: p.kind,
            values: vals,
        });
    }
    for p in &mesh.face_props {
        out.face_props.push(Property {
            name: p.name.clone(),
            kind: p.kind,
            values: kept_faces
                .iter()
                .map(|&t| p.values.get(t).copied().unwrap_or(f64::NAN))
                .collect(),
        });
    }
    out
}

/// The part with the most triangles (lowest label on ties), or `None` without parts. Labels
/// that are not integers in `0..triangles` are ignored.
///
/// ```
/// use morpho::volume::{extract_part, isosurface, largest_part, IsoOptions, Volume};
/// // two balls side by side: two parts
/// let ball = |x: f64, y: f64, z: f64, cx: f64| (x - cx).powi(2) + (y - 0.5).powi(2) + (z - 0.5).powi(2);
/// let v = Volume::from_fn([24, 12, 12], [0.0; 3], [2.0, 1.0, 1.0], |x, y, z| {
///     ball(x, y, z, 0.5).min(ball(x, y, z, 1.5))
/// });
/// let r = isosurface(&v, &IsoOptions { level: 0.1, ..Default::default() }).unwrap();
/// assert_eq!(r.parts, 2);
/// let big = extract_part(&r.mesh, largest_part(&r.mesh).unwrap());
/// assert!(big.triangles.len() >= r.mesh.triangles.len() / 2);
/// assert!(big.triangles.len() < r.mesh.triangles.len());
/// ```
pub fn largest_part(mesh: &TriMesh) -> Option<u32> {
    let labels = mesh.face_prop("part")?;
    let mut count: Vec<usize> = Vec::new();
    let nt = mesh.triangles.len();
    for &l in &labels.values {
        // labels of a foreign mesh: only integers in 0..nt count (no allocation from values)
        if !(l >= 0.0 && l < nt as f64 && l.fract() == 0.0) {
            continue;
        }
        let l = l as usize;
        if l >= count.len() {
            count.resize(l + 1, 0);
        }
        count[l] += 1;
    }
    let mut best: Option<(usize, u32)> = None;
    for (l, &c) in count.iter().enumerate() {
        if c > 0 && best.map_or(true, |b| c > b.0) {
            best = Some((c, l as u32));
        }
    }
    best.map(|b| b.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(vals: [f64; 8]) -> Volume {
        let mut data = vec![0f32; 8];
        for (c, v) in vals.iter().enumerate() {
            data[c] = *v as f32;
        }
        Volume::new([2, 2, 2], [0.0; 3], [1.0; 3], data).unwrap()
    }

    /// The topology pass before [`sorted3`]: its edge table filled as before (edges counted and
    /// stored one by one in winding order), kept verbatim as the oracle of [`analyze`]'s fill;
    /// the group walk after it ([`analyze_groups`]) is the one both share, unchanged.
    fn analyze_edge_table(
        mesh: &TriMesh,
        keys: &[u64],
        valid_cell: impl Fn([i64; 3]) -> bool,
    ) -> Analysis {
        let n = mesh.positions.len();
        let nt = mesh.triangles.len();
        // edges grouped by their smaller vertex (counting sort); an entry is the larger vertex
        // and the triangle, packed as (b << 32) | t so that sorting the u64s sorts by (b, t)
        let mut start = vec![0u32; n + 1];
        advise_huge_pages(&mut start);
        for t in &mesh.triangles {
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                start[a.min(b) as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        // start[a] is group a's cursor: after the scatter it is the group's end, i.e. the start
        // of group a + 1, and group a begins where group a − 1 ends
        let mut ent = vec![0u64; 3 * nt];
        advise_huge_pages(&mut ent);
        for (ti, t) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                let s = &mut start[a.min(b) as usize];
                ent[*s as usize] = (a.max(b) as u64) << 32 | ti as u64;
                *s += 1;
            }
        }
        analyze_groups(n, ent, start, keys, valid_cell)
    }

    fn same_analysis(a: &Analysis, b: &Analysis) -> bool {
        let bits = |l: &[f64]| l.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        bits(&a.labels) == bits(&b.labels)
            && (a.parts, a.boundary_edges, a.interior_boundary_edges)
                == (b.parts, b.boundary_edges, b.interior_boundary_edges)
            && (a.interior_holes, a.non_manifold_edges) == (b.interior_holes, b.non_manifold_edges)
    }

    /// The mesh and grid keys `isosurface` hands to the topology pass (slabs of three layers,
    /// before `finish`), with the unreferenced vertices dropped as `finish` does.
    fn extracted(vol: &Volume, opts: &IsoOptions) -> Option<(TriMesh, Vec<u64>)> {
        let range = fast_range(&vol.data).or_else(|| vol.value_range());
        let eps = perturbation(vol.dims, range, opts.level).ok()?;
        let axes = axis_coords(vol);
        let ctx = Ctx {
            vol,
            axes: &axes,
            alpha: opts.level,
            eps,
            method: opts.method,
            normals: NormalMethod::None,
            flip: opts.flip,
            keys: true,
            parts: false,
            central: None,
            gvol: vol,
            gaxes: &axes,
            goff: [0; 3],
            cells: false,
        };
        let layers = vol.dims[2] - 1;
        let per = 3.min(layers);
        let chunks: Vec<ChunkOut> = (0..layers)
            .step_by(per)
            .map(|z0| ctx.chunk(z0, (z0 + per).min(layers)))
            .collect();
        let (mut r, mut keys) = assemble(chunks, opts).ok()?;
        if r.skipped_cells > 0 {
            drop_unreferenced(&mut r.mesh, &mut keys);
        }
        Some((r.mesh, keys))
    }

    /// The decider topology found during the extraction ([`global_parents`] +
    /// [`decider_analysis`], slabs of `per` layers) and the edge-table pass [`analyze`] on
    /// the same assembled mesh (both recorded in one extraction), and the triangle count;
    /// `None` when the volume has no surface or a cell was skipped (then `isosurface` takes
    /// the edge-table pass: `decider_topology_matches_the_edge_table` checks it end to end).
    fn parents_and_edge_table(
        vol: &Volume,
        opts: &IsoOptions,
        per: usize,
    ) -> Option<(Analysis, Analysis, usize)> {
        let range = fast_range(&vol.data).or_else(|| vol.value_range());
        let eps = perturbation(vol.dims, range, opts.level).ok()?;
        let axes = axis_coords(vol);
        let ctx = Ctx {
            vol,
            axes: &axes,
            alpha: opts.level,
            eps,
            method: IsoMethod::Decider,
            normals: NormalMethod::None,
            flip: opts.flip,
            keys: true,
            parts: true,
            central: None,
            gvol: vol,
            gaxes: &axes,
            goff: [0; 3],
            cells: false,
        };
        let layers = vol.dims[2] - 1;
        let per = per.min(layers);
        let mut chunks: Vec<ChunkOut> = (0..layers)
            .step_by(per)
            .map(|z0| ctx.chunk(z0, (z0 + per).min(layers)))
            .collect();
        let vps: Vec<(Vec<u32>, usize, usize)> = chunks
            .iter_mut()
            .map(|c| (std::mem::take(&mut c.vp), c.last_plane_start, c.outer))
            .collect();
        let (r, keys) = assemble(chunks, opts).ok()?;
        if r.skipped_cells > 0 {
            return None;
        }
        let (vp, outer) = global_parents(vps);
        assert_eq!(vp.len() + r.fan_points, r.mesh.positions.len());
        let got = decider_analysis(&r.mesh.triangles, vp, outer);
        let dims = vol.dims;
        let valid_cell = |c: [i64; 3]| (0..3).all(|k| c[k] >= 0 && c[k] + 1 < dims[k] as i64);
        let want = analyze(&r.mesh, &keys, valid_cell);
        Some((got, want, r.mesh.triangles.len()))
    }

    #[test]
    fn decider_topology_matches_the_edge_table() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(10);
        let (mut tris, mut bnd, mut parts, mut fallbacks) = (0usize, 0, 0, 0);
        for round in 0..90 {
            // NaN cells in a third of the rounds; integer samples (ties with the level, Rem. 3.8)
            // in every other one
            let v = random_volume(&mut rng, 10, [0.0, 0.03, 0.0][round % 3], round % 2 == 0);
            let opts = IsoOptions {
                level: 0.0,
                flip: round % 5 == 1,
                ..Default::default()
            };
            for per in [1, 2, 3, usize::MAX] {
                let Some((got, want, nt)) = parents_and_edge_table(&v, &opts, per) else {
                    continue;
                };
                assert!(
                    same_analysis(&got, &want),
                    "round {round} per {per}: {:?} vs {:?}",
                    (got.parts, got.boundary_edges),
                    (want.parts, want.boundary_edges)
                );
                tris += nt;
                bnd += want.boundary_edges;
                parts += want.parts;
            }
            // end to end (two threads' slabs, and the NaN fallback): `isosurface` against the
            // edge-table pass on the mesh `extracted` gives
            let Some((mesh, keys)) = extracted(&v, &opts) else {
                continue;
            };
            let skipped = v.data.iter().any(|x| x.is_nan());
            fallbacks += skipped as usize;
            let valid_cell = |c: [i64; 3]| cell_is_valid(&v, c);
            let want = analyze(&mesh, &keys, valid_cell);
            for parallel in [false, true] {
                let o = IsoOptions {
                    parallel,
                    ..opts.clone()
                };
                let r = isosurface(&v, &o).unwrap();
                let labels = &r.mesh.face_prop("part").unwrap().values;
                let got = Analysis {
                    labels: labels.to_vec(),
                    parts: r.parts,
                    boundary_edges: r.boundary_edges,
                    interior_boundary_edges: r.interior_boundary_edges,
                    interior_holes: r.interior_holes,
                    non_manifold_edges: r.non_manifold_edges,
                };
                assert!(same_analysis(&got, &want), "round {round} end to end");
                assert_eq!(r.mesh.triangles, mesh.triangles);
            }
        }
        // the inputs reach what is compared: borders, several parts, the NaN fallback
        assert!(
            tris > 4000 && bnd > 1000 && parts > 100,
            "{tris} {bnd} {parts}"
        );
        assert!(fallbacks > 10, "{fallbacks}");
    }

    #[test]
    fn decider_topology_matches_the_edge_table_on_every_cell_pair() {
        // two cells sharing a face, along each axis, every sign configuration of their twelve
        // corners (±1, then with a tie): every way a face is crossed from both sides
        for axis in 0..3 {
            let mut dims = [2usize; 3];
            dims[axis] = 3;
            for bits in 0u32..1 << 12 {
                for tie in [false, true] {
                    let data: Vec<f32> = (0..12)
                        .map(|k| match (bits >> k & 1, tie && k == 5) {
                            (_, true) => 0.0,
                            (1, _) => 1.0 + k as f32 / 16.0,
                            _ => -1.0 - (k % 5) as f32 / 8.0,
                        })
                        .collect();
                    let v = Volume::new(dims, [0.0; 3], [1.0; 3], data).unwrap();
                    for per in [1, 2] {
                        let opts = IsoOptions {
                            level: 0.0,
                            ..Default::default()
                        };
                        let Some((got, want, _)) = parents_and_edge_table(&v, &opts, per) else {
                            continue;
                        };
                        assert!(same_analysis(&got, &want), "{axis} {bits} {tie} {per}");
                    }
                }
            }
        }
    }

    #[test]
    fn decider_topology_matches_the_edge_table_on_smooth_volumes() {
        // the gyroid and the bumpy sphere of the benchmarks at 40³, a level through samples
        let n = 40;
        let gyroid =
            |x: f64, y: f64, z: f64| x.sin() * y.cos() + y.sin() * z.cos() + z.sin() * x.cos();
        let bumpy = |x: f64, y: f64, z: f64| {
            (x * x + y * y + z * z).sqrt()
                - 0.7
                - 0.06 * (9.0 * x).sin() * (9.0 * y).sin() * (9.0 * z).sin()
        };
        let s = 6.0 * std::f64::consts::PI;
        let vols = [
            Volume::from_fn([n; 3], [0.0; 3], [s; 3], gyroid),
            Volume::from_fn([n; 3], [-1.0; 3], [1.0; 3], bumpy),
        ];
        for v in &vols {
            for (per, level) in [(usize::MAX, 0.0), (5, 0.0), (7, v.data[777] as f64)] {
                let opts = IsoOptions {
                    level,
                    ..Default::default()
                };
                let (got, want, nt) = parents_and_edge_table(v, &opts, per).unwrap();
                assert!(same_analysis(&got, &want), "{per} {level}");
                assert!(nt > 1000);
            }
        }
    }

    #[test]
    fn sorted3_gives_the_edges_by_smaller_end() {
        for a in 0..4u32 {
            for b in 0..4u32 {
                for c in 0..4u32 {
                    let t = [a, b, c];
                    let (lo, mid, hi) = sorted3(&t);
                    let mut want: Vec<(u32, u32)> = (0..3)
                        .map(|i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3])))
                        .collect();
                    want.sort_unstable();
                    let mut got = vec![(lo, mid), (lo, hi), (mid, hi)];
                    got.sort_unstable();
                    assert_eq!(got, want, "{t:?}");
                }
            }
        }
    }

    /// Whether cell `c` (its lowest corner) lies in `v` and none of its eight samples is NaN:
    /// the cells the extraction does not skip, for the topology passes' `valid_cell`.
    fn cell_is_valid(v: &Volume, c: [i64; 3]) -> bool {
        (0..3).all(|k| c[k] >= 0 && c[k] + 1 < v.dims[k] as i64)
            && !(0..8).any(|k| {
                v.at(
                    c[0] as usize + (k & 1),
                    c[1] as usize + (k >> 1 & 1),
                    c[2] as usize + (k >> 2 & 1),
                )
                .is_nan()
            })
    }

    /// A random volume of 2 to `max − 1` samples per axis, unit spacing: each sample NaN with
    /// probability `nan`, else an integer in −2..=2 (`ints`: ties with the level 0) or a float
    /// in [−1, 1).
    fn random_volume(
        rng: &mut rand_chacha::ChaCha8Rng,
        max: usize,
        nan: f64,
        ints: bool,
    ) -> Volume {
        use rand::Rng;
        let dims = [
            rng.gen_range(2..max),
            rng.gen_range(2..max),
            rng.gen_range(2..max),
        ];
        let data: Vec<f32> = (0..dims.iter().product::<usize>())
            .map(|_| {
                if rng.gen_bool(nan) {
                    f32::NAN
                } else if ints {
                    rng.gen_range(-2..3) as f32
                } else {
                    rng.gen_range(-1.0f32..1.0)
                }
            })
            .collect();
        Volume::new(dims, [0.0; 3], [1.0; 3], data).unwrap()
    }

    #[test]
    fn topology_matches_the_edge_table_on_random_volumes() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let mut compared = [0usize; 3];
        for round in 0..60 {
            // NaN cells in every other round; integer samples (ties with the level, Rem. 3.8) in
            // a third of them
            let v = random_volume(&mut rng, 9, [0.0, 0.03][round % 2], round % 3 == 0);
            for (mi, method) in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen]
                .into_iter()
                .enumerate()
            {
                let opts = IsoOptions {
                    level: 0.0,
                    method,
                    ..Default::default()
                };
                let Some((mesh, keys)) = extracted(&v, &opts) else {
                    continue;
                };
                let valid_cell = |c: [i64; 3]| cell_is_valid(&v, c);
                let got = analyze(&mesh, &keys, valid_cell);
                let want = analyze_edge_table(&mesh, &keys, valid_cell);
                assert!(same_analysis(&got, &want), "round {round} {method:?}");
                compared[mi] += mesh.triangles.len();
            }
        }
        assert!(compared.iter().all(|&t| t > 1000), "{compared:?}");
    }

    #[test]
    fn topology_matches_the_edge_table_on_triangle_soups() {
        // few vertices: repeated vertices in a triangle, edges of 3+ triangles, boundary loops
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(8);
        let (mut nonman, mut holes) = (0, 0);
        for round in 0..300 {
            let n = rng.gen_range(1..12u32);
            let nt = rng.gen_range(0..30);
            let tris: Vec<[u32; 3]> = (0..nt)
                .map(|_| [0; 3].map(|_: u32| rng.gen_range(0..n)))
                .collect();
            let mesh = TriMesh::new(vec![crate::geom::Point3::origin(); n as usize], tris);
            // keys of x-edges on the outer face z = 0 of a 4³ grid, or interior points
            let keys: Vec<u64> = (0..n)
                .map(|_| {
                    if rng.gen_bool(0.5) {
                        KEY_INTERIOR
                    } else {
                        extract::key(0, rng.gen_range(0..3), rng.gen_range(0..4), 0)
                    }
                })
                .collect();
            let valid_cell = |c: [i64; 3]| c.iter().all(|&x| (0..3).contains(&x));
            let got = analyze(&mesh, &keys, valid_cell);
            let want = analyze_edge_table(&mesh, &keys, valid_cell);
            assert!(same_analysis(&got, &want), "round {round}");
            nonman += want.non_manifold_edges;
            holes += want.interior_holes;
        }
        assert!(nonman > 0 && holes > 0, "{nonman} {holes}");
    }

    #[test]
    fn single_corner_is_one_outward_triangle() {
        let v = cube([1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0]);
        for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
            let r = isosurface(
                &v,
                &IsoOptions {
                    level: 0.0,
                    method: m,
                    ..Default::default()
                },
            )
            .unwrap();
            assert!(!r.mesh.triangles.is_empty());
            // normals out of {f > 0}: away from corner 0
            for t in 0..r.mesh.triangles.len() {
                let [a, b, c] = r.mesh.triangle_points(crate::mesh::TriId(t as u32));
                let n = (b - a).cross(&(c - a));
                assert!(n.x + n.y + n.z > 0.0, "{m:?}");
            }
            let nr = r.mesh.normals.as_ref().unwrap();
            for n in nr {
                assert!(n.x + n.y + n.z > 0.0, "{m:?} {n:?}");
            }
            assert_eq!(r.parts, 1);
            assert_eq!(r.interior_holes, 0);
        }
    }

    #[test]
    fn fast_range_matches_value_range() {
        let mut d: Vec<f32> = (0..37).map(|i| (i as f32 * 0.37).sin()).collect();
        d[3] = f32::NAN;
        d[36] = f32::NAN;
        let v = Volume::new([37, 1, 1], [0.0; 3], [1.0; 3], d.clone()).unwrap();
        assert_eq!(fast_range(&d), v.value_range());
        d[5] = f32::INFINITY;
        assert_eq!(fast_range(&d), None);
        assert_eq!(fast_range(&[f32::NAN; 9]), None);
    }

    #[test]
    fn largest_part_ignores_bad_labels() {
        let mut m = TriMesh::new(
            vec![crate::geom::Point3::origin(); 3],
            vec![[0, 1, 2], [0, 2, 1], [1, 2, 0]],
        );
        m.face_props.push(Property {
            name: "part".into(),
            kind: ScalarKind::F64,
            values: vec![1e300, 2.0, f64::NAN],
        });
        assert_eq!(largest_part(&m), Some(2));
        m.face_props[0].values = vec![-1.0, 0.5, 7.0];
        assert_eq!(largest_part(&m), None);
    }

    #[test]
    fn level_outside_range_gives_note() {
        let v = cube([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let r = isosurface(
            &v,
            &IsoOptions {
                level: 9.0,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(r.mesh.triangles.is_empty());
        assert!(r.note.unwrap().contains("outside"));
        assert!(isosurface(
            &v,
            &IsoOptions {
                level: f64::NAN,
                ..Default::default()
            }
        )
        .is_err());
    }

    #[test]
    fn degenerate_face_cuts_off_positive_corners() {
        // face z = 0 with f = +1, -1, -1, +1: the face contour is the two asymptotes (Eq. 3.9
        // collapses); H's adhoc rule cuts off the positive corners -> two separate triangles.
        let v = cube([1.0, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, -1.0]);
        let r = isosurface(&v, &IsoOptions::default()).unwrap();
        assert_eq!(r.mesh.triangles.len(), 2);
        assert_eq!(r.parts, 2);
        // a slightly larger positive diagonal joins them (saddle above α): one hexagon with two
        // segments on face z = 0, fanned around an interior point (Thm. 3.5)
        let v = cube([1.1, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, -1.0]);
        let r = isosurface(&v, &IsoOptions::default()).unwrap();
        assert_eq!(r.parts, 1);
        assert_eq!(r.fan_points, 1);
        assert_eq!(r.mesh.triangles.len(), 6);
        // and a smaller one separates them
        let v = cube([0.9, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, -1.0]);
        assert_eq!(isosurface(&v, &IsoOptions::default()).unwrap().parts, 2);
    }

    #[test]
    fn value_equal_to_level_is_perturbed() {
        // corner 0 exactly at α: treated as above α (Rem. 3.8)
        let v = cube([0.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0]);
        let r = isosurface(
            &v,
            &IsoOptions {
                level: 0.0,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(r.mesh.triangles.len(), 1);
    }
}

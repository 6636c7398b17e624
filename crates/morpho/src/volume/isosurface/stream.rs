//! The contour surface of a volume too large for memory, stitched slab by slab (issue 24: the
//! CLI's streaming mode). Blocks of [`isosurface_block`](super::isosurface_block) that span the
//! whole grid in x and y and follow each other in z are pushed in order; the surface comes out
//! piece by piece, in the vertex and triangle order of [`isosurface`](super::isosurface), with
//! the same positions, normals, part labels and topology figures — only at no time in memory
//! whole.
//!
//! Why one block of delay suffices: a vertex's global id orders it by the layer of its grid
//! entity (module doc of `block.rs`: layer 2z for the entities in the plane z, 2z + 1 for those
//! between the planes z and z + 1), so the vertices of a block with cells z₀..z₁ are those of
//! its bottom plane (shared with the previous block), its inside layers, and its top plane
//! (shared with the next). When a block arrives, the previous block's top plane is merged with
//! its bottom plane (checked bit for bit) and, with the block's inside layers, numbered and
//! emitted: every triangle touching these vertices is known by then (only the two blocks hold
//! cells next to them), so unreferenced ones (beside NaN cells) are dropped and missing normals
//! are fitted from the mesh (`mesh_normals_where` on the two blocks' triangles, in global
//! order, which gives the same bits as on the whole mesh because the fit only sees a vertex's
//! own triangles). Then the previous block's triangles are emitted. Cell-interior points (the
//! decider's fan points) come after all edge vertices in the single-machine order; they are
//! emitted to a separate list and the triangles name the j-th of them `INTERIOR_REF | j`
//! ([`StreamSummary::resolve`] turns that into `edge_vertices + j` once the count is known).
//!
//! Topology (as `analyze` in `mod.rs`): triangles are merged into parts with a union–find
//! over triangle numbers (4 bytes per triangle, the one structure that grows with the output);
//! an edge is complete once the block above the plane it lies in has been emitted, so edges
//! are grouped per emitted block (sort) and only the edges lying in the top plane are carried
//! to the next. Boundary edges are classified with the NaN cells of the last two blocks.
//!
//! Memory: two blocks' extraction output, the carried plane edges, the boundary edges, and the
//! triangle union–find.

use super::block::{cell_index, key_of_id};
use super::{
    on_domain_boundary, perturbation, union, IsoBlock, IsoOptions, IsoResult, NormalMethod, World,
};
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;
use crate::volume::gradient::mesh_normals_where;
use crate::volume::{VolumeError, VolumeGrid};
use std::collections::{HashMap, HashSet};

/// Flag of a triangle corner that names the j-th cell-interior vertex (`INTERIOR_REF | j`).
pub const INTERIOR_REF: u32 = 1 << 31;

/// What [`IsoStream::push`] and [`IsoStream::finish`] emit: append it to the output, then
/// clear it (the stream only appends).
#[derive(Debug, Default, Clone, PartialEq)]
pub struct StreamPiece {
    /// Edge vertices, in final order (world coordinates).
    pub positions: Vec<Point3>,
    /// Their normals (grid-gradient or mesh methods), else empty.
    pub normals: Vec<Vector3>,
    /// Cell-interior vertices, in final order after all edge vertices.
    pub interior_positions: Vec<Point3>,
    /// Their normals.
    pub interior_normals: Vec<Vector3>,
    /// Triangles, in final order; corners `≥ INTERIOR_REF` name interior vertices.
    pub triangles: Vec<[u32; 3]>,
}

impl StreamPiece {
    /// Empties every list.
    pub fn clear(&mut self) {
        self.positions.clear();
        self.normals.clear();
        self.interior_positions.clear();
        self.interior_normals.clear();
        self.triangles.clear();
    }
}

/// The figures of a streamed surface (those of [`super::IsoResult`]) and its part labels.
#[derive(Debug, Clone, Default)]
pub struct StreamSummary {
    /// Edge vertices emitted (interior vertex j is vertex `edge_vertices + j`).
    pub edge_vertices: usize,
    /// Cell-interior vertices emitted.
    pub interior_vertices: usize,
    /// Triangles emitted.
    pub triangles: usize,
    /// The figures of [`super::isosurface`]'s result (parts, boundary edges, holes, fan
    /// points, skipped cells, note), with an empty mesh.
    pub figures: IsoResult,
    /// Root triangle of each triangle's part (empty without topology).
    roots: Vec<u32>,
    /// The roots in increasing order: part label = position.
    root_list: Vec<u32>,
}

impl StreamSummary {
    /// The vertex a triangle corner names, once every vertex is known.
    pub fn resolve(&self, corner: u32) -> u32 {
        if corner & INTERIOR_REF != 0 {
            self.edge_vertices as u32 + (corner & !INTERIOR_REF)
        } else {
            corner
        }
    }

    /// Part label of triangle `t` (parts numbered in order of their first triangle, as the
    /// `part` face property of [`super::isosurface`]); `None` without topology.
    pub fn part(&self, t: usize) -> Option<u32> {
        let r = *self.roots.get(t)?;
        self.root_list.binary_search(&r).ok().map(|p| p as u32)
    }
}

/// A block waiting for the next one: its vertices' final numbers are known except those of
/// its top plane.
struct Held {
    block: IsoBlock,
    /// Final number of each local vertex (`u32::MAX`: not yet; `INTERIOR_REF | j`).
    fin: Vec<u32>,
    /// Local vertices of the top plane, by increasing id.
    top: Vec<u32>,
    /// Local triangles in cell order.
    order: Vec<u32>,
    /// Top plane (z of the grid plane).
    z1: usize,
    nan: HashSet<u64>,
}

/// An edge of an emitted triangle: final endpoints (smaller first), triangle, grid ids.
type EdgeEntry = (u32, u32, u32, u64, u64);

/// The stitcher: push blocks in z order, drain each [`StreamPiece`], then [`finish`](Self::finish).
pub struct IsoStream {
    grid: VolumeGrid,
    opts: IsoOptions,
    /// Ids per layer (8·n_x·n_y) and the first cell-interior id (16·N).
    layer: u64,
    interior_base: u64,
    next_z: usize,
    held: Option<Held>,
    prev_nan: HashSet<u64>,
    next_vertex: u32,
    next_interior: u32,
    next_triangle: u32,
    carry: Vec<EdgeEntry>,
    pending: Vec<EdgeEntry>,
    boundary: Vec<(u32, u32, bool)>,
    tp: Vec<u32>,
    nonman: usize,
    fan_points: usize,
    centroid_fallbacks: usize,
    skipped: usize,
    note: Option<String>,
    empty: bool,
}

impl IsoStream {
    /// A stream for the surface `opts.level` of `grid`, whose finite samples span `range`
    /// (the whole grid's, as for [`isosurface_block`](super::isosurface_block)).
    pub fn new(
        grid: VolumeGrid,
        range: Option<(f32, f32)>,
        opts: &IsoOptions,
    ) -> Result<IsoStream, VolumeError> {
        let n = grid.validate()?;
        if !opts.level.is_finite() {
            return Err(VolumeError::NonFiniteLevel { level: opts.level });
        }
        let [nx, ny, _] = grid.dims.map(|d| d as u64);
        let (note, empty) = match perturbation(grid.dims, range, opts.level) {
            Ok(_) => (None, false),
            Err(note) => (Some(note), true),
        };
        Ok(IsoStream {
            layer: 8 * nx * ny,
            interior_base: 16 * n as u64,
            grid,
            opts: opts.clone(),
            next_z: 0,
            held: None,
            prev_nan: HashSet::new(),
            next_vertex: 0,
            next_interior: 0,
            next_triangle: 0,
            carry: Vec::new(),
            pending: Vec::new(),
            boundary: Vec::new(),
            tp: Vec::new(),
            nonman: 0,
            fan_points: 0,
            centroid_fallbacks: 0,
            skipped: 0,
            note,
            empty,
        })
    }

    /// True when the level is outside the data (or the grid has no cells): every block is
    /// empty and [`finish`](Self::finish) gives the note.
    pub fn is_empty(&self) -> bool {
        self.empty
    }

    /// Takes the block of the cells `z0..z1` (all of x and y) — `z0` must be where the
    /// previous block ended (0 first) — and appends to `out` what is final now.
    pub fn push(
        &mut self,
        block: IsoBlock,
        z: [usize; 2],
        out: &mut StreamPiece,
    ) -> Result<(), VolumeError> {
        let [z0, z1] = z;
        let cells_z = self.grid.dims[2].saturating_sub(1);
        if z0 != self.next_z || z1 <= z0 || z1 > cells_z {
            return Err(bad(format!(
                "block of cells {z0}..{z1} along z does not follow the previous one (next: {})",
                self.next_z
            )));
        }
        self.next_z = z1;
        if self.empty {
            return Ok(());
        }
        if !block.consistent() {
            return Err(bad(
                "block is inconsistent (ids, normals, triangles or cells do not match its \
                 vertices)"
                    .into(),
            ));
        }
        self.fan_points += block.fan_points;
        self.centroid_fallbacks += block.centroid_fallbacks;
        self.skipped += block.nan_cells.len();
        // the block's vertices by id, and their layers
        let nv = block.ids.len();
        let mut byid: Vec<u32> = (0..nv as u32).collect();
        byid.sort_unstable_by_key(|&l| block.ids[l as usize]);
        let mut bottom = Vec::new();
        let mut inside = Vec::new();
        let mut top = Vec::new();
        let mut interior = Vec::new();
        for &l in &byid {
            let id = block.ids[l as usize];
            if id >= self.interior_base {
                interior.push(l);
                continue;
            }
            let m = id / self.layer;
            match m {
                _ if m == 2 * z0 as u64 => bottom.push(l),
                _ if m == 2 * z1 as u64 => top.push(l),
                _ if m > 2 * z0 as u64 && m < 2 * z1 as u64 => inside.push(l),
                _ => {
                    return Err(bad(format!(
                        "vertex id {id} lies outside the block's cells {z0}..{z1}"
                    )))
                }
            }
        }
        let mut order: Vec<u32> = (0..block.triangles.len() as u32).collect();
        order.sort_by_key(|&t| block.triangle_cells[t as usize]);
        let mut cur = Held {
            fin: vec![u32::MAX; nv],
            top,
            order,
            z1,
            nan: block.nan_cells.iter().copied().collect(),
            block,
        };
        let mut held = self.held.take();
        self.emit_vertices(
            held.as_mut(),
            Some(&mut cur),
            &bottom,
            &inside,
            &interior,
            out,
        )?;
        if let Some(h) = held {
            self.emit_triangles(&h, out)?;
            let pn = std::mem::take(&mut self.prev_nan);
            self.group_edges(Some(h.z1), &pn, &h.nan);
            self.prev_nan = h.nan;
        }
        self.held = Some(cur);
        Ok(())
    }

    /// Emits the last block's top plane and triangles; returns the figures.
    pub fn finish(mut self, out: &mut StreamPiece) -> Result<StreamSummary, VolumeError> {
        if let Some(mut h) = self.held.take() {
            self.emit_vertices(Some(&mut h), None, &[], &[], &[], out)?;
            self.emit_triangles(&h, out)?;
            let pn = std::mem::take(&mut self.prev_nan);
            self.group_edges(Some(h.z1), &pn, &h.nan);
            self.group_edges(None, &h.nan, &HashSet::new());
        }
        // parts: roots flattened in increasing order (a parent is always a smaller triangle)
        let mut roots = std::mem::take(&mut self.tp);
        for t in 0..roots.len() {
            let p = roots[t] as usize;
            roots[t] = roots[p];
        }
        let root_list: Vec<u32> = (0..roots.len() as u32)
            .filter(|&t| roots[t as usize] == t)
            .collect();
        let mut interior_holes = 0;
        let interior_boundary_edges = self.boundary.iter().filter(|e| e.2).count();
        if interior_boundary_edges > 0 {
            let mut uf: HashMap<u32, u32> = HashMap::new();
            fn root(uf: &mut HashMap<u32, u32>, mut x: u32) -> u32 {
                while let Some(&p) = uf.get(&x) {
                    if p == x {
                        break;
                    }
                    x = p;
                }
                x
            }
            for &(a, b, _) in &self.boundary {
                uf.entry(a).or_insert(a);
                uf.entry(b).or_insert(b);
                let (ra, rb) = (root(&mut uf, a), root(&mut uf, b));
                if ra != rb {
                    uf.insert(ra.max(rb), ra.min(rb));
                }
            }
            let mut rs: Vec<u32> = self
                .boundary
                .iter()
                .filter(|e| e.2)
                .map(|e| root(&mut uf, e.0))
                .collect();
            rs.sort_unstable();
            rs.dedup();
            interior_holes = rs.len();
        }
        let triangles = self.next_triangle as usize;
        let mut note = self.note.take();
        if self.skipped > 0 {
            note = Some(format!(
                "{} cells with a NaN corner were skipped; the surface ends at their faces",
                self.skipped
            ));
        }
        if triangles == 0 && note.is_none() {
            note = Some(format!("no contour at level {}", self.opts.level));
        }
        let topo = self.opts.topology;
        Ok(StreamSummary {
            edge_vertices: self.next_vertex as usize,
            interior_vertices: self.next_interior as usize,
            triangles,
            figures: IsoResult {
                mesh: TriMesh::default(),
                parts: if topo { root_list.len() } else { 0 },
                boundary_edges: if topo { self.boundary.len() } else { 0 },
                interior_boundary_edges: if topo { interior_boundary_edges } else { 0 },
                interior_holes: if topo { interior_holes } else { 0 },
                non_manifold_edges: if topo { self.nonman } else { 0 },
                fan_points: self.fan_points,
                centroid_fallbacks: self.centroid_fallbacks,
                skipped_cells: self.skipped,
                note,
            },
            roots: if topo { roots } else { Vec::new() },
            root_list: if topo { root_list } else { Vec::new() },
        })
    }

    /// Numbers and emits the vertices that are final now: the previous block's top plane
    /// merged with the current block's `bottom`, the current block's `inside` layers and its
    /// cell-interior points.
    fn emit_vertices(
        &mut self,
        mut prev: Option<&mut Held>,
        mut cur: Option<&mut Held>,
        bottom: &[u32],
        inside: &[u32],
        interior: &[u32],
        out: &mut StreamPiece,
    ) -> Result<(), VolumeError> {
        let empty: Vec<u32> = Vec::new();
        let ptop = prev.as_ref().map_or(&empty, |h| &h.top).clone();
        // the merged plane: (prev local, cur local), by id
        let mut plane: Vec<(Option<u32>, Option<u32>)> = Vec::with_capacity(ptop.len());
        {
            let pid = |l: u32| prev.as_ref().map_or(0, |h| h.block.ids[l as usize]);
            let cid = |l: u32| cur.as_ref().map_or(0, |h| h.block.ids[l as usize]);
            let (mut i, mut j) = (0, 0);
            while i < ptop.len() || j < bottom.len() {
                let a = ptop.get(i).map(|&l| pid(l));
                let b = bottom.get(j).map(|&l| cid(l));
                match (a, b) {
                    (Some(x), Some(y)) if x == y => {
                        plane.push((Some(ptop[i]), Some(bottom[j])));
                        i += 1;
                        j += 1;
                    }
                    (Some(x), Some(y)) if x < y => {
                        plane.push((Some(ptop[i]), None));
                        i += 1;
                    }
                    (Some(_), None) => {
                        plane.push((Some(ptop[i]), None));
                        i += 1;
                    }
                    _ => {
                        plane.push((None, Some(bottom[j])));
                        j += 1;
                    }
                }
            }
        }
        let (pb, cb) = (
            prev.as_deref().map(|h| &h.block),
            cur.as_deref().map(|h| &h.block),
        );
        for &(p, c) in &plane {
            if let (Some(p), Some(c), Some(pb), Some(cb)) = (p, c, pb, cb) {
                let same_p = (0..3).all(|k| {
                    pb.positions[p as usize][k].to_bits() == cb.positions[c as usize][k].to_bits()
                });
                let same_n = match (&pb.normals, &cb.normals) {
                    (Some(a), Some(b)) => {
                        (0..3).all(|k| a[p as usize][k].to_bits() == b[c as usize][k].to_bits())
                    }
                    (None, None) => true,
                    _ => false,
                };
                if !same_p || !same_n {
                    return Err(VolumeError::BlocksDisagree {
                        reason: format!(
                            "consecutive blocks give different points for id {}",
                            pb.ids[p as usize]
                        ),
                    });
                }
            }
        }
        // which vertices the two blocks' triangles use
        let used = |b: Option<&IsoBlock>| -> Vec<bool> {
            let Some(b) = b else { return Vec::new() };
            let mut u = vec![false; b.ids.len()];
            for t in &b.triangles {
                for &v in t {
                    u[v as usize] = true;
                }
            }
            u
        };
        let (up, uc) = (used(pb), used(cb));
        // the final vertices, in order: (block 0 = prev / 1 = cur, local)
        let mut fin: Vec<(u8, u32)> = Vec::new();
        for &(p, c) in &plane {
            let referenced = p.is_some_and(|p| up[p as usize]) || c.is_some_and(|c| uc[c as usize]);
            if referenced {
                fin.push(match (p, c) {
                    (Some(p), _) => (0, p),
                    (None, Some(c)) => (1, c),
                    _ => unreachable!("a plane entry has a vertex"),
                });
            }
        }
        fin.extend(
            inside
                .iter()
                .filter(|&&c| uc[c as usize])
                .map(|&c| (1u8, c)),
        );
        let ints: Vec<u32> = interior
            .iter()
            .copied()
            .filter(|&c| uc[c as usize])
            .collect();
        // normals: grid normals, the mesh's where they are zero or wanted from the mesh
        let want_mesh = |n: Option<Vector3>| -> bool {
            match self.opts.normals {
                NormalMethod::Mesh => true,
                NormalMethod::None => false,
                _ => n.is_some_and(|n| n.x == 0.0 && n.y == 0.0 && n.z == 0.0),
            }
        };
        let normal_of = |which: u8, l: u32| -> Option<Vector3> {
            let b = if which == 0 { pb } else { cb };
            b.and_then(|b| b.normals.as_ref()).map(|n| n[l as usize])
        };
        let mut mesh_n: HashMap<(u8, u32), Vector3> = HashMap::new();
        let needs_fit = fin
            .iter()
            .map(|&(w, l)| (w, l))
            .chain(ints.iter().map(|&c| (1u8, c)))
            .any(|(w, l)| want_mesh(normal_of(w, l)));
        if needs_fit {
            let want: Vec<(u8, u32)> = fin
                .iter()
                .copied()
                .chain(ints.iter().map(|&c| (1u8, c)))
                .filter(|&(w, l)| want_mesh(normal_of(w, l)))
                .collect();
            mesh_n = fit_normals(pb, cb, &plane, &want);
        }
        let world = World::of(&self.grid.axes, &self.grid.orientation);
        for &(w, l) in &fin {
            let b = if w == 0 { pb } else { cb };
            let Some(b) = b else { continue };
            out.positions.push(world.point(b.positions[l as usize]));
            if self.opts.normals != NormalMethod::None {
                let n = mesh_n
                    .get(&(w, l))
                    .copied()
                    .or_else(|| normal_of(w, l))
                    .unwrap_or_else(Vector3::zeros);
                out.normals.push(world.normal(n));
            }
        }
        // final numbers
        if self.next_vertex as usize + fin.len() >= INTERIOR_REF as usize
            || self.next_interior as usize + ints.len() >= INTERIOR_REF as usize
        {
            return Err(VolumeError::TooManyVertices {
                vertices: self.next_vertex as usize + fin.len(),
            });
        }
        for &(w, l) in &fin {
            let v = self.next_vertex;
            self.next_vertex += 1;
            let h = if w == 0 {
                prev.as_deref_mut()
            } else {
                cur.as_deref_mut()
            };
            if let Some(h) = h {
                h.fin[l as usize] = v;
            }
        }
        // merged plane vertices: the current block's copy gets the previous block's number
        if let (Some(p), Some(c)) = (prev.as_deref(), cur.as_deref_mut()) {
            for &(pl, cl) in &plane {
                if let (Some(pl), Some(cl)) = (pl, cl) {
                    c.fin[cl as usize] = p.fin[pl as usize];
                }
            }
        }
        if let Some(c) = cur {
            for &l in &ints {
                c.fin[l as usize] = INTERIOR_REF | self.next_interior;
                self.next_interior += 1;
                out.interior_positions
                    .push(world.point(c.block.positions[l as usize]));
                if self.opts.normals != NormalMethod::None {
                    let n = mesh_n
                        .get(&(1, l))
                        .copied()
                        .or_else(|| c.block.normals.as_ref().map(|n| n[l as usize]))
                        .unwrap_or_else(Vector3::zeros);
                    out.interior_normals.push(world.normal(n));
                }
            }
        }
        Ok(())
    }

    /// Emits the triangles of a block whose vertices all have their final numbers, and
    /// collects their edges for the topology.
    fn emit_triangles(&mut self, h: &Held, out: &mut StreamPiece) -> Result<(), VolumeError> {
        let mirrors = World::of(&self.grid.axes, &self.grid.orientation).mirrors();
        let topo = self.opts.topology;
        for &t in &h.order {
            let local = h.block.triangles[t as usize];
            let tri = local.map(|v| h.fin[v as usize]);
            if tri.contains(&u32::MAX) {
                return Err(bad(format!(
                    "a triangle of the block ending at plane {} has an unnumbered vertex",
                    h.z1
                )));
            }
            let tn = self.next_triangle;
            self.next_triangle = tn.checked_add(1).ok_or(VolumeError::TooManyVertices {
                vertices: tn as usize,
            })?;
            if topo {
                self.tp.push(tn);
                for i in 0..3 {
                    let (a, b) = (tri[i], tri[(i + 1) % 3]);
                    let (ia, ib) = (
                        h.block.ids[local[i] as usize],
                        h.block.ids[local[(i + 1) % 3] as usize],
                    );
                    let e = if a < b {
                        (a, b, tn, ia, ib)
                    } else {
                        (b, a, tn, ib, ia)
                    };
                    self.pending.push(e);
                }
            }
            let mut o = tri;
            if mirrors {
                o.swap(1, 2);
            }
            out.triangles.push(o);
        }
        Ok(())
    }

    /// Groups the pending edges with the carried ones: an edge lying in the plane `keep`
    /// waits for the next block, every other edge is complete (two triangles: neighbours;
    /// one: a boundary edge, classified with the NaN cells of the two blocks around it;
    /// more: non-manifold).
    fn group_edges(&mut self, keep: Option<usize>, nan_a: &HashSet<u64>, nan_b: &HashSet<u64>) {
        if !self.opts.topology {
            return;
        }
        let mut ent = std::mem::take(&mut self.pending);
        ent.append(&mut self.carry);
        ent.sort_unstable();
        let dims = self.grid.dims;
        let in_plane =
            |id: u64, z: usize| id < self.interior_base && id / self.layer == 2 * z as u64;
        let valid_cell = |c: [i64; 3]| -> bool {
            for k in 0..3 {
                if c[k] < 0 || c[k] + 1 >= dims[k] as i64 {
                    return false;
                }
            }
            let ci = cell_index([c[0] as usize, c[1] as usize, c[2] as usize], dims);
            !nan_a.contains(&ci) && !nan_b.contains(&ci)
        };
        let mut carry = Vec::new();
        let mut i = 0;
        while i < ent.len() {
            let mut j = i + 1;
            while j < ent.len() && ent[j].0 == ent[i].0 && ent[j].1 == ent[i].1 {
                j += 1;
            }
            let (a, b, t0, ia, ib) = ent[i];
            if keep.is_some_and(|z| in_plane(ia, z) && in_plane(ib, z)) {
                carry.extend_from_slice(&ent[i..j]);
                i = j;
                continue;
            }
            match j - i {
                1 => {
                    let interior =
                        !on_domain_boundary(key_of_id(ia, dims), key_of_id(ib, dims), &valid_cell);
                    self.boundary.push((a, b, interior));
                }
                2 => union(&mut self.tp, t0, ent[i + 1].2),
                _ => {
                    self.nonman += 1;
                    for k in i + 1..j {
                        union(&mut self.tp, t0, ent[k].2);
                    }
                }
            }
            i = j;
        }
        self.carry = carry;
    }
}

/// Mesh normals (H Rem. 3.15, as `finish` fits them on the whole mesh) of the vertices `want`
/// of the previous block (0) and the current block (1), from the two blocks' triangles in
/// global order: the fit at a vertex sees only the vertex's own triangles, all of which are
/// in these blocks, so the bits are those of the whole mesh.
fn fit_normals(
    pb: Option<&IsoBlock>,
    cb: Option<&IsoBlock>,
    plane: &[(Option<u32>, Option<u32>)],
    want: &[(u8, u32)],
) -> HashMap<(u8, u32), Vector3> {
    let np = pb.map_or(0, |b| b.positions.len());
    let mut cmap: Vec<u32> = (0..cb.map_or(0, |b| b.positions.len()) as u32)
        .map(|l| np as u32 + l)
        .collect();
    for &(p, c) in plane {
        if let (Some(p), Some(c)) = (p, c) {
            cmap[c as usize] = p;
        }
    }
    let mut positions: Vec<Point3> = pb.map_or(Vec::new(), |b| b.positions.clone());
    if let Some(b) = cb {
        positions.extend_from_slice(&b.positions);
    }
    let by_cell = |b: &IsoBlock| -> Vec<usize> {
        let mut o: Vec<usize> = (0..b.triangles.len()).collect();
        o.sort_by_key(|&t| b.triangle_cells[t]);
        o
    };
    let mut tris = Vec::new();
    if let Some(b) = pb {
        tris.extend(by_cell(b).into_iter().map(|t| b.triangles[t]));
    }
    if let Some(b) = cb {
        tris.extend(
            by_cell(b)
                .into_iter()
                .map(|t| b.triangles[t].map(|v| cmap[v as usize])),
        );
    }
    let mesh = TriMesh::new(positions, tris);
    let mut wanted = vec![false; mesh.positions.len()];
    let local = |w: u8, l: u32| {
        if w == 0 {
            l as usize
        } else {
            cmap[l as usize] as usize
        }
    };
    for &(w, l) in want {
        wanted[local(w, l)] = true;
    }
    let n = mesh_normals_where(&mesh, |v| wanted[v]);
    want.iter()
        .map(|&(w, l)| ((w, l), n[local(w, l)]))
        .collect()
}

fn bad(reason: String) -> VolumeError {
    VolumeError::BadBlock { reason }
}

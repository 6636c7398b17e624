//! Topology of triangle meshes (Hamann 1991, §3.3: Alg. 3.1 neighbours, Alg. 3.2 connected parts,
//! Def. 3.10 holes; Def. 5.14 and Rem. 5.4 Euler–Poincaré characteristic and genus).
//!
//! TODO(helper): implement in O(n) (hash-free edge sort); see issue 2 item 5.

use super::TriMesh;

/// Marks "no neighbour" in [`Topology::neighbors`].
pub const NONE: u32 = u32::MAX;

/// Figures of one connected part (triangles connected through shared edges).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PartInfo {
    pub triangles: usize,
    /// Vertices used by the part's triangles.
    pub vertices: usize,
    pub edges: usize,
    pub boundary_loops: usize,
    /// χ = V − E + F of the part.
    pub euler_characteristic: i64,
    /// (2 − χ − b) / 2 for an orientable manifold part; `None` when not a manifold.
    pub genus: Option<i64>,
}

/// The topology of a triangle mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Topology {
    /// `neighbors[t][i]`: the triangle across the edge (v_i, v_{i+1}) of triangle t, or [`NONE`]
    /// (boundary edge, or a non-manifold edge shared by more than two triangles).
    pub neighbors: Vec<[u32; 3]>,
    /// Part index of each triangle (parts numbered in order of their first triangle).
    pub part_of_triangle: Vec<u32>,
    pub parts: Vec<PartInfo>,
    /// Closed vertex cycles formed by boundary edges (edges of exactly one triangle).
    pub boundary_loops: Vec<Vec<u32>>,
    /// Edges shared by more than two triangles.
    pub non_manifold_edges: Vec<[u32; 2]>,
    /// Vertices whose triangle fan is not a single disc or half-disc.
    pub non_manifold_vertices: Vec<u32>,
    /// Number of distinct (undirected) edges.
    pub num_edges: usize,
    /// Number of vertices referenced by at least one triangle.
    pub num_used_vertices: usize,
    /// χ = V − E + F over used vertices.
    pub euler_characteristic: i64,
    /// True when every edge has at most two triangles and every vertex is manifold.
    pub manifold: bool,
    /// True when each manifold edge is traversed in opposite directions by its two triangles.
    pub consistently_oriented: bool,
    /// True when the triangles can be re-oriented consistently (may be true while
    /// `consistently_oriented` is false).
    pub orientable: bool,
}

impl Topology {
    /// Σ genus over parts; `None` if any part is not an orientable manifold.
    pub fn genus(&self) -> Option<i64> {
        self.parts.iter().map(|p| p.genus).sum()
    }
}

/// Computes the topology of `mesh` in O(n log n) or better. `mesh` must satisfy
/// [`TriMesh::validate`].
pub fn analyze(mesh: &TriMesh) -> Topology {
    let _ = mesh;
    Topology::default()
}

/// Flips triangles so every part is consistently oriented (and outward, for closed parts, by the
/// sign of the enclosed volume). Returns the number of flipped triangles, or an error for a
/// non-orientable part.
pub fn orient_consistently(mesh: &mut TriMesh) -> crate::Result<usize> {
    let _ = mesh;
    Err(crate::Error::unsupported(
        "orient_consistently: not implemented yet",
    ))
}

//! Flintstones: hierarchical approximation and localization of polygons and polylines
//! (Veltkamp 1992, ch. 6–7; paper §4; reading notes part A).
//!
//! - [`Flintstone`], [`SideDisc`], [`StoneKind`]: discs with signed radius, half-planes and the
//!   ± operator (Defs. 7.1–7.4), exact membership;
//! - [`Criteria`], [`edge_criteria`], [`approximation_criteria`]: the error criteria e1–e5 (§6.2);
//! - [`FlintTree2`]: the 2D flintstone tree (Alg. 7.1 within a depth budget that keeps the
//!   build O(N log N) on dense smooth curves, see `tree2.rs`; [`FlintTree2::new_alg71`]
//!   without it) of a simple polygon or open polyline;
//!   [`FlintTree2::new_repaired`] first removes zero-area spikes (GIS collinear back-tracks,
//!   [`crate::mesh::validity::remove_spikes`]);
//! - [`Target`], [`Approximation`]: level-ℓ, adaptive-ε and edge-count approximations (§7.2.3);
//! - [`FlintTree2::contains`], [`intersect`], [`intersect_counted`]: hierarchical
//!   point-in-polygon and boundary intersection (§7.4, Lemma 6.1; crossings, touchings and
//!   collinear overlaps, with the pairs visited), with the brute-force oracles
//!   [`contains_brute`] and [`intersect_brute`];
//! - [`Baseline`], [`baseline`]: Douglas–Peucker (iterative end-point fit), strip tree, BLG tree
//!   and arc tree (§6.3) through the same criteria; [`BaselineTree`]: their point-in-polygon
//!   walk (capsule, strip, ellipse regions), with visits counted like
//!   [`FlintTree2::locate_counted`]. The point queries run on a flat copy of the tree with an
//!   exact box pre-filter (`locate.rs`); batches are Hilbert-sorted and parallel.
//! - [`FlintTree3`]: the 3D flintstone tree of a closed triangle mesh (Alg. 7.2, §7.3) with
//!   [`Flintstone3`] balls of signed radius (Defs. 7.5–7.6), its point-in-polyhedron walk
//!   [`FlintTree3::contains`] (Lemma 6.1, exact; crack-safe through path fills, see
//!   `query3.rs`) with the oracle [`contains_brute3`], and its approximations
//!   [`Approximation3`] (level ℓ, adaptive ε, triangle count; §7.3.3).
//!   [`CellCache3`]: a grid of cached answers over the tree for large batches (cells that
//!   meet no triangle's box answered once per connected component by the exact walk; the
//!   others by the walk; `locate3.rs`).
//! - [`intersect3`], [`intersects3`]: mesh–mesh intersection by descending two 3D trees
//!   (§7.4; pairs pruned only where convex supersets of the flintstones are provably
//!   disjoint, exact triangle–triangle tests at the leaves, see `intersect3.rs`), with the
//!   intersection geometry [`triangle_meet`] and the brute-force oracle [`intersect3_brute`].
//!
//! - [`FlintTree3::iepf`]: the 3D iterative extreme-point fit (Faugeras et al. 84, V §6.3)
//!   through the same splitting, approximation and query code (`baselines3.rs`);
//!   [`PrismTree3`]: the prism tree (Ponce–Faugeras 87, Def. 6.2) on it, with its point-in-mesh
//!   walk (prisms as conservative filters, exact at the leaves; `prism.rs`).

mod approx;
mod approx3;
mod ball;
mod baselines;
mod baselines3;
mod bquery;
mod criteria;
mod disc;
mod intersect3;
mod locate;
mod locate3;
mod patch3;
mod prism;
mod query;
mod query3;
mod region;
mod tree2;
mod tree3;

pub use approx::{Approximation, Target};
pub use approx3::Approximation3;
pub use ball::{Flintstone3, SideBall};
pub use baselines::{baseline, Baseline};
pub use bquery::BaselineTree;
pub use criteria::{approximation_criteria, edge_criteria, Criteria};
pub use disc::{Flintstone, SideDisc, StoneKind};
pub use intersect3::{
    intersect3, intersect3_brute, intersects3, triangle_meet, IntersectStats3, TriangleMeet,
};
pub use locate3::{CellCache3, DEFAULT_CELLS};
pub use prism::{Prism, PrismTree3};
pub use query::{
    contains_brute, intersect, intersect_brute, intersect_counted, Containment, Crossing,
    IntersectStats,
};
pub use query3::contains_brute3;
pub use tree2::{FlintNode, FlintRoot, FlintTree2};
pub use tree3::{FlintNode3, FlintRoot3, FlintTree3, Side3, DEFAULT_MIN_ANGLE};

/// A refusal of the flintstone constructions and queries, naming the offending input.
///
/// ```
/// use morpho::flint::{FlintError, FlintTree2};
/// use morpho::geom::Point2;
/// let bow = [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let e = FlintTree2::new(&bow, true).unwrap_err();
/// assert!(matches!(e, FlintError::NotSimple { .. }));
/// assert!(e.to_string().contains("edge 0 (vertices 0–1)"), "{e}");
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FlintError {
    /// Fewer than three vertices.
    #[error("flint: {n} vertices, at least 3 are needed")]
    TooFewVertices {
        /// The number given.
        n: usize,
    },
    /// A vertex with a NaN or infinite coordinate.
    #[error("flint: vertex {index} has a non-finite coordinate")]
    NonFinite {
        /// Input index of the vertex.
        index: usize,
    },
    /// All vertices coincide (no chord exists).
    #[error("flint: all vertices coincide")]
    AllCoincident,
    /// The polygon is not simple: two vertices coincide or two edges meet (exact test).
    #[error("flint: polygon is not simple: {}", not_simple(*first, *second, *repeated, *n))]
    NotSimple {
        /// First vertex / edge (edge k joins vertex k to k+1).
        first: usize,
        /// Second vertex / edge.
        second: usize,
        /// True when two vertices coincide, false when two edges meet.
        repeated: bool,
        /// Number of vertices (for naming the closing edge).
        n: usize,
    },
    /// A polygon still not simple after its zero-area spikes were removed (`--repair`); the
    /// edges are named by the input indices of their end vertices.
    #[error("flint: polygon is not simple after removing {removed} spike vertices: edge {}–{} meets edge {}–{} (input vertices)", .first[0], .first[1], .second[0], .second[1])]
    NotSimpleAfterRepair {
        /// Number of vertices removed.
        removed: usize,
        /// End vertices of the first edge.
        first: [usize; 2],
        /// End vertices of the second edge (equal ends: a repeated vertex).
        second: [usize; 2],
    },
    /// A query that needs a closed polygon on an open polyline.
    #[error("flint: point-in-polygon needs a closed polygon, the input is an open polyline")]
    NotClosed,
    /// A query point with a NaN or infinite coordinate.
    #[error("flint: a query point has a non-finite coordinate")]
    NonFiniteQuery,
    /// A mesh without triangles.
    #[error("flint: the mesh has no triangles")]
    EmptyMesh,
    /// A triangle naming a vertex that does not exist.
    #[error("flint: triangle {triangle} refers to vertex {vertex}, but there are only {vertices} vertices")]
    VertexOutOfRange {
        /// Index of the triangle.
        triangle: usize,
        /// The vertex it names.
        vertex: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// A triangle with a repeated vertex or collinear corners (exact test).
    #[error("flint: triangle {triangle} is degenerate (repeated vertex or collinear corners)")]
    DegenerateTriangle {
        /// Index of the triangle.
        triangle: usize,
    },
    /// An edge shared by more than two triangles.
    #[error("flint: the mesh is not a 2-manifold: edge {a}–{b} has more than two triangles")]
    NonManifoldEdge {
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
    },
    /// A vertex whose triangles do not form one fan.
    #[error("flint: the mesh is not a 2-manifold at vertex {vertex}")]
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
    },
    /// A mesh with boundary edges where a closed one is needed.
    #[error("flint: the mesh is not closed ({boundary_edges} boundary edges); the 3D tree needs a closed mesh")]
    OpenMesh {
        /// Number of boundary edges.
        boundary_edges: usize,
    },
    /// Two triangles traverse a shared edge in the same direction.
    #[error("flint: the mesh is not consistently oriented (orient it first)")]
    InconsistentOrientation,
    /// An approximation target out of range.
    #[error("flint: invalid approximation target: {0}")]
    BadTarget(String),
}

fn not_simple(i: usize, j: usize, repeated: bool, n: usize) -> String {
    if repeated {
        format!("vertices {i} and {j} coincide")
    } else {
        let e = |k: usize| format!("edge {k} (vertices {k}–{})", (k + 1) % n.max(1));
        format!("{} meets {}", e(i), e(j))
    }
}

impl FlintError {
    /// The refusal of a ring rebuilt from `repair.kept` (its vertex `k` is input vertex
    /// `repair.kept[k]`), with a [`FlintError::NotSimple`] renamed by input indices
    /// ([`FlintError::NotSimpleAfterRepair`]); other refusals unchanged.
    pub fn after_repair(self, repair: &crate::mesh::validity::SpikeRepair) -> FlintError {
        let FlintError::NotSimple {
            first,
            second,
            repeated,
            n,
        } = self
        else {
            return self;
        };
        let k = &repair.kept;
        let edge = |e: usize| [k[e], k[(e + 1) % n]];
        let (first, second) = if repeated {
            ([k[first]; 2], [k[second]; 2])
        } else {
            (edge(first), edge(second))
        };
        FlintError::NotSimpleAfterRepair {
            removed: repair.removed.len(),
            first,
            second,
        }
    }

    /// Every refusal is caused by the input (CLI exit code 2).
    pub fn is_input_error(&self) -> bool {
        true
    }
}

//! Principal curvatures of a triangle mesh by the osculating-paraboloid fit over the
//! platelet, Hamann 1991, §4.2 steps (i)–(viii) (notes C.1, C.2).
//!
//! For each vertex `y₀` with unit normal `n` and platelet points `y₁..yₘ` (the 1-ring; the
//! k-ring with [`SurfaceOptions::ring`] = k):
//! 1. tangent plane through `y₀` with normal `n`, orthonormal tangent basis `b₁, b₂ = n × b₁`
//!    (any basis gives the same curvatures, H Thm 4.2; we take `b₁ ∝ n × e_k` with `e_k` the
//!    axis least aligned with `n`, the numerically stable choice, instead of the text's
//!    division by `n^x`),
//! 2. heights `d_j = n·(y_j − y₀)` and tangent coordinates `u_j, v_j` of the projections,
//! 3. least squares `½(c20 u² + 2 c11 uv + c02 v²) = d_j` (H (4.28)–(4.30)). The matrix of
//!    (4.28) is printed without the ½, so its literal solution must be doubled (notes C.2); we
//!    use the rows `(u²/2, uv, v²/2)`, which give `c` directly,
//! 4. κ₁ ≤ κ₂ are the eigenvalues of `[[c20, c11], [c11, c02]]` (H (4.31)); their
//!    eigenvectors, mapped back through `b₁, b₂`, are the principal directions; `H = (κ₁+κ₂)/2`,
//!    `K = κ₁κ₂`, and the absolute curvature `A = |κ₁| + |κ₂|` (H Def. 5.10).
//!
//! **Order and sign.** κ₁ is the algebraically smaller curvature (notes C.4: the column pattern
//! of Table 4.1 matches this order; H (5.39) writes the opposite). Curvatures are measured
//! along `n`: a surface bending towards its normal has positive curvature. With outward
//! normals a sphere of radius R therefore has κ₁ = κ₂ = H = −1/R (the sign of the thesis's
//! graph convention, H (4.15)); reversing the orientation (or the normals) flips κ₁, κ₂, H and
//! the directions' roles, and keeps K.
//!
//! **Estimated normals** (not in the thesis; issue 20). The thesis's tables used exact normals
//! (notes C.4). With area-weighted normals the 1-ring paraboloid is fine on regular grids, but
//! on irregular meshes the normal's error tilts the tangent plane and the fit turns it into
//! curvature: on a randomly tessellated unit sphere (4000 points, convex hull) its interior
//! RMS of H is 1.5 and of K 1.8e3, against libigl's 0.026 / 0.053.
//! [`SurfaceOptions::estimated_normals`] (the CLI's default, [`SurfaceFit::Jet`]) therefore
//! fits a jet — a polynomial graph `d = f(u, v)` through the vertex, with linear terms — over
//! the 2-ring in the frame `(b₁, b₂, n)` of the area-weighted normal, of degree 4 (14
//! coefficients, at least 14 points) where that is determined, else of degree 3 (9
//! coefficients, from the same moments), else the same on the 3-ring, and takes the curvature
//! of the fitted graph at the vertex: with `g = ∇f(0)` (≠ 0: the area normal is not the
//! surface's) and `Hess f(0)`, the first fundamental form is `I + ggᵀ`, the second
//! `Hess / √(1+|g|²)`, and κ₁ ≤ κ₂ are the eigenvalues of the shape operator (H (4.15); the
//! normal becomes the jet's, `(n − g₁b₁ − g₂b₂)/√(1+|g|²)`). The linear terms absorb the area
//! normal's tilt; the cubic terms keep the odd-order part of the surface out of the slopes and
//! the Hessian on irregular rings; the quartic terms keep the fourth-order part out of the
//! Hessian, which on point-symmetric stencils (regular grids: the odd terms decouple there, so
//! a cubic jet is no better than a quadric) is the whole O(h²) error. With degree 3 alone
//! the 2-ring's Hessian error on grids was 2.5–4× the 1-ring paraboloid's (the stencil's
//! radius is twice as large), behind `vtkCurvatures` on every regular grid; with degree 4 the
//! measured slopes are 3.8–4.1 on grids, 3.1–3.4 on the jittered torus and 1.9 (with 16×
//! smaller errors than before) on the random sphere. On the 12 meshes of
//! `bench/curvature_peers.py` (torus regular and jittered, ellipsoid, random sphere, the 8
//! curved surfaces of Table 4.1 on its grid, all with estimated normals) its interior RMS and
//! median relative error of H and K are below libigl's `principal_curvature` in all 48
//! comparisons (≤ 0.01×) and below `vtkCurvatures`' in all 48 (with the distance weights
//! below; without them 46 of 48: the median relative error of H and K on the torus parameter
//! grid was 3.7× and 1.1× VTK's); `bench/README.md` has the tables. It also skips the second fit of the
//! previous default (jet-corrected normal, then the thesis's paraboloid:
//! [`SurfaceOptions::jet_normals_paraboloid`], CLI `--fit paraboloid`), which stays available,
//! as does the quadric with linear terms ([`SurfaceFit::Quadric`], 2-ring). The library's
//! [`Default`] stays the thesis's method (and `morpho reduce`, which weights by its
//! curvature, is unchanged).
//!
//! **Distance weights** (not in the thesis; issue 20). The jet's least squares weighs each ring
//! point by `w = 1/(ε + |y_j − y₀|²/ρ²)⁴` (ρ the ring's RMS radius, ε = 0.1:
//! `fit::jet_weight`); the weights enter only the moments (`Σ w uᵃtᵇ`, `Σ w d uᵃtᵇ`),
//! so any polynomial of degree ≤ 4 is still reproduced exactly (weighted least squares of an
//! exact model has zero residual), and the O(h⁴)/O(h³) orders are kept. What they change is
//! which combination of the points carries the surface's terms beyond degree 4 into the
//! Hessian: unweighted, the 2-ring's far points (radius 2h, fifth- and sixth-order remainder
//! 32–64× the 1-ring's) dominate it. Measured on the 40×120 torus grid (whose error was the
//! one left behind `vtkCurvatures`), with a per-hypothesis experiment: the frame is not the
//! cause (the exact normal's frame, or a second fit in the jet's normal frame, changes the
//! median of H by < 1 %); the ring is (degree 4 over the 3-ring is 2× worse, degree 6 over the
//! 3-ring 2.6× better but 27 unknowns); weighting the 2-ring by distance takes the median
//! relative error of H from 1.62e-3 to 3.14e-4 and of K from 1.52e-3 to 3.18e-4 (VTK
//! 4.36e-4 / 1.38e-3), RMS 5.3e-4 → 1.6e-4; weights `1/(ε+q)^p` (ε = 0.1) gave a median of H
//! of 5.7e-4 with p = 2, 3.7e-4 with p = 3, 3.1e-4 with p = 4, and a heavier 1-ring by graph distance (×100) 3.0e-4 but less on
//! the jittered torus. Every other mesh of `bench/curvature_peers.py` improves or stays far
//! below the peers, and the convergence slopes rise (regular torus 4.3, jittered 3.6). ε
//! bounds a point's weight by ε⁻⁴ = 10⁴ (a point on the vertex: a zero-length edge). The
//! weights cost seven products, three sums and one division per point (one vector operation
//! each for four vertices in the batched pass): on the skull, one thread, +2.4 % of the CLI's
//! instructions and +2 to +3.4 % of its process CPU (+3 to +5 % of the compute alone;
//! `bench/README.md`). The jet normals of
//! [`SurfaceOptions::jet_normals`] stay unweighted (their outputs are unchanged).
//!
//! **Undetermined vertices** (NaN in every output, a [`VertexStatus`] other than `Ok`, and
//! counted in [`SurfaceCurvature::undetermined`]): a vertex in no triangle, a vertex without a
//! normal (zero or non-finite), a platelet of fewer than 3 points, and a platelet whose normal
//! matrix has `cond(UᵀU) > 1e10` (notes C.2). The condition number is invariant under scaling,
//! so the rule is scale-free. On the 51×51 grid of Table 4.1 exactly the two corners in one
//! triangle are undetermined. With [`SurfaceFit::Jet`] a vertex is undetermined only when its
//! jets (pivot ratio > 1e10 in the coordinates divided by the RMS radius: scale-free too) and
//! the fallback paraboloid all are.
//!
//! **Boundaries.** On an open fan (a vertex with more neighbours than triangles: on a boundary)
//! every platelet is one-sided. The thesis's method keeps its steps there (larger errors, as in
//! Table 4.1). With [`SurfaceFit::Jet`] or [`SurfaceOptions::jet_normals`] the cubic's slopes at the edge of its data
//! extrapolate badly, and the paraboloid turns the tilt into curvature (monkey saddle of Table
//! 4.1's grid: RMS of H on the boundary vertices 1.1, on the trig surface 1.3). There the
//! estimated normal is kept and the quadric with linear terms ([`SurfaceFit::Quadric`]) is
//! fitted over the 2-ring (or the larger platelet asked for); if it is undetermined, the
//! paraboloid over the 1-ring. Boundary RMS of H on the eight Table 4.1 surfaces becomes
//! 2e-4–1.3e-2 (monkey 9.6e-3, trig 6.4e-3), below libigl's 1.9e-3–4.0e-2 on every surface;
//! interior vertices are unchanged (`tests/curvature.rs`).
//!
//! **Other inputs.** Zero-area triangles add their vertices to the platelet and nothing to
//! estimated normals. Non-manifold vertices are fitted over all the triangles that contain them, as the
//! platelet definition (H Def. 4.9) says; the result is meaningful only if the normal is. A
//! non-finite coordinate is refused ([`CurvatureError::Mesh`]).
//!
//! Cost: O(V·m) for platelets of m points; vertices are evaluated in parallel (rayon) in chunks
//! written straight into the output arrays; the result does not depend on the number of
//! threads. The adjacency (incident triangles and sorted neighbours) is built once in
//! compressed rows, its rows filled in parallel and packed (no gaps: the ring search's rows
//! are dense); the adjacency, the triangles' cross products and the output arrays ask for
//! transparent huge pages before their first write (`util::advise_huge_pages`: on the skull
//! 29k → 22k page faults of the CLI run, the same contents); estimated normals are summed per vertex in the
//! same pass as the fits (the same sums as [`crate::mesh::vertex_normals`]); each vertex's
//! offsets `y_j − y₀` are gathered once for the jet and the paraboloid; the jets' normal
//! equations are formed from their distinct moments `Σ uᵃtᵇ` and solved by LDLᵀ in generated
//! straight-line code (`fit/jet_solve.rs`, the same operations as [`Normal::solve_ldl`] in the
//! same order, each term rounded once differently: results equal to rounding, not bit for bit;
//! `bench/README.md`); nothing is allocated per vertex. The quartic jets of the interior
//! vertices are computed four at a time, one vertex per lane of a four-wide vector (`F4`):
//! each lane does the scalar code's operations in the same order (the moments by the same
//! generic code, the solve generated from the same elimination: every entry receives the same
//! terms in the same order, its rows finished one by one, `gen_jet_solve.py`), a shorter ring
//! is padded with points that add exactly zero, and a lane whose quartic is refused is
//! recomputed alone by the scalar path, so the results are those of the one-vertex code bit
//! for bit; on processors with AVX2 (detected at run time) the vertex pass runs a second
//! compilation of itself with AVX2 enabled (no FMA: the same bits). Tests
//! `batched_and_avx2_passes_are_bitwise_the_scalar_pass`, `quartic_solve4_lanes_are_quartic_solve`
//! and `quartic_solve4_is_quartic_solve_on_random_and_ill_conditioned_rings`.

use super::error::CurvatureError;
use super::fit::{jet_weight, CubicJet, Normal, QuarticJet, QuarticJet4, F4};
use crate::geom::{vec, Vector3};
use crate::mesh::{vertex_normal_from, weighted_crosses, NormalWeighting, TriMesh};
use crate::util::advise_huge_pages;
use rayon::prelude::*;

/// Where the vertex normals of the fit come from.
#[derive(Debug, Clone, PartialEq)]
pub enum NormalSource {
    /// Estimated from the triangles with one of the weightings of V §9.4.
    Estimated(NormalWeighting),
    /// The mesh's own per-vertex normals ([`TriMesh::normals`], PLY `nx ny nz`).
    File,
    /// Normals given by the caller, one per vertex (need not be unit length).
    Given(Vec<Vector3>),
}

impl Default for NormalSource {
    fn default() -> Self {
        NormalSource::Estimated(NormalWeighting::Area)
    }
}

/// The local surface fitted over the platelet, in the frame of the vertex's tangent plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SurfaceFit {
    /// The thesis's osculating paraboloid `½(c20 u² + 2 c11 uv + c02 v²)` (H (4.28)–(4.31)):
    /// the tangent plane is taken from the normal as given, 3 coefficients, ≥ 3 points.
    #[default]
    Paraboloid,
    /// The quadric with linear terms `a u + b v + ½(c20 u² + 2 c11 uv + c02 v²)` through the
    /// vertex: the fit corrects the tilt of an estimated normal (the curvatures are those of
    /// the fitted graph at the vertex, H (4.15), and the normal becomes the fitted one);
    /// 5 coefficients, ≥ 5 points — use a 2-ring or larger. Not in the thesis: an extension
    /// for estimated normals (see the module doc).
    Quadric,
    /// The jet `a u + b v + ½(c20 u² + 2 c11 uv + c02 v²) + c30 u³ + c21 u²v + c12 uv² +
    /// c03 v³ + c40 u⁴ + … + c04 v⁴` through the vertex over its k-ring
    /// (k = [`SurfaceOptions::ring`], at least 2), in the frame of the given or estimated
    /// normal; the curvatures are those of the fitted graph at the vertex (H (4.15), as for
    /// [`SurfaceFit::Quadric`]) and the normal becomes the fitted one. The least squares
    /// weighs each point by its distance (`1/(0.1 + r²/ρ²)⁴`, ρ the ring's RMS radius: module
    /// doc, "Distance weights"). Degree 4 (14
    /// coefficients) where the ring has ≥ 14 points and the fit is determined (pivot ratio at
    /// most 1e10), else degree 3 (9 coefficients, ≥ 9 points). Where both are undetermined
    /// the (k+1)-ring is tried, then the thesis's paraboloid
    /// over the 1-ring with the normal as given (counted in
    /// [`SurfaceCurvature::jet_fallbacks`]); on a boundary vertex (an open fan) the quadric with
    /// linear terms is fitted instead, as with [`SurfaceOptions::jet_normals`]. Not in the
    /// thesis: the default for estimated normals ([`SurfaceOptions::estimated_normals`]; the
    /// module doc gives the measurements). [`SurfaceOptions::jet_normals`] adds nothing to it.
    Jet,
}

/// Options of [`surface_curvature`].
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceOptions {
    /// The normals of the tangent planes.
    pub normals: NormalSource,
    /// The platelet: the vertices within this many edges (1 = the thesis's 1-ring).
    pub ring: usize,
    /// The fitted surface (default: the thesis's paraboloid).
    pub fit: SurfaceFit,
    /// Replace each normal by that of a cubic fit over the vertex's 2-ring before the fit
    /// (not in the thesis; see the module doc). Where the cubic is undetermined on the 2-ring
    /// (fewer than 9 points, pivot ratio above 1e10) the 3-ring is tried; where it is
    /// undetermined there too, the normal is kept and counted in
    /// [`SurfaceCurvature::jet_fallbacks`]. Vertices on a boundary get the quadric fit
    /// instead of the jet and the paraboloid (module doc, "Boundaries").
    pub jet_normals: bool,
}

impl Default for SurfaceOptions {
    /// The thesis's method (H §4.2): 1-ring paraboloid, area-weighted estimated normals.
    fn default() -> Self {
        SurfaceOptions {
            normals: NormalSource::default(),
            ring: 1,
            fit: SurfaceFit::Paraboloid,
            jet_normals: false,
        }
    }
}

impl SurfaceOptions {
    /// The method for meshes whose normals are estimated (the CLI's default): the jet (degree
    /// 4, else 3) over the 2-ring in the frame of the area-weighted normal, its curvature at
    /// the vertex
    /// ([`SurfaceFit::Jet`]). The module doc gives the measurements that chose it.
    pub fn estimated_normals() -> Self {
        SurfaceOptions {
            normals: NormalSource::Estimated(NormalWeighting::Area),
            ring: 2,
            fit: SurfaceFit::Jet,
            jet_normals: false,
        }
    }

    /// The previous default for estimated normals: area-weighted normals corrected by the
    /// cubic fit over the 2-ring ([`SurfaceOptions::jet_normals`]), then the thesis's 1-ring
    /// paraboloid (CLI `--fit paraboloid`, with the default `--normals jet`).
    pub fn jet_normals_paraboloid() -> Self {
        SurfaceOptions {
            normals: NormalSource::Estimated(NormalWeighting::Area),
            ring: 1,
            fit: SurfaceFit::Paraboloid,
            jet_normals: true,
        }
    }
}

/// Why a vertex has no curvature (or `Ok`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VertexStatus {
    /// The fit is determined.
    Ok,
    /// The vertex is in no triangle.
    Isolated,
    /// The vertex has no usable normal (zero or non-finite).
    NoNormal,
    /// Fewer than 3 platelet points besides the vertex.
    TooFewPoints,
    /// `cond(UᵀU) > 1e10`: the platelet's projection cannot determine the paraboloid.
    IllConditioned,
}

/// Per-vertex curvatures of a mesh (NaN where [`SurfaceCurvature::status`] is not `Ok`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceCurvature {
    /// Smaller principal curvature κ₁.
    pub k1: Vec<f64>,
    /// Larger principal curvature κ₂ (κ₁ ≤ κ₂).
    pub k2: Vec<f64>,
    /// Mean curvature (κ₁+κ₂)/2.
    pub h: Vec<f64>,
    /// Gaussian curvature κ₁κ₂.
    pub k: Vec<f64>,
    /// Absolute curvature |κ₁|+|κ₂| (H Def. 5.10).
    pub a: Vec<f64>,
    /// Unit principal direction of κ₁ (tangent to the surface).
    pub dir1: Vec<Vector3>,
    /// Unit principal direction of κ₂ (`normal × dir1`).
    pub dir2: Vec<Vector3>,
    /// The unit normals the fit used (zero where there was none).
    pub normals: Vec<Vector3>,
    /// Why each vertex is (un)determined.
    pub status: Vec<VertexStatus>,
    /// Number of vertices whose status is not `Ok`.
    pub undetermined: usize,
    /// With [`SurfaceOptions::jet_normals`]: interior vertices whose cubic fit was undetermined
    /// and that kept their given or estimated normal; with [`SurfaceFit::Jet`]: interior
    /// vertices whose jet was undetermined on both rings and that got the thesis's paraboloid
    /// instead (boundary vertices get no jet).
    pub jet_fallbacks: usize,
}

/// Condition-number bound of the 3×3 normal matrix (notes C.2).
pub const SURFACE_MAX_COND: f64 = 1e10;

/// Curvatures of every vertex of `mesh` (H §4.2; the module doc gives the conventions).
///
/// ```
/// use morpho::curvature::{surface_curvature, SurfaceOptions};
/// use morpho::mesh::generate;
/// let sphere = generate::icosphere(4); // unit sphere, outward
/// let c = surface_curvature(&sphere, &SurfaceOptions::default()).unwrap();
/// assert_eq!(c.undetermined, 0);
/// assert!(c.h.iter().all(|h| (h + 1.0).abs() < 0.05)); // H = −1/R with outward normals
/// ```
pub fn surface_curvature(
    mesh: &TriMesh,
    opts: &SurfaceOptions,
) -> Result<SurfaceCurvature, CurvatureError> {
    curvature_pass(mesh, opts, true, false, false)
}

/// [`surface_curvature`] without the vector outputs: `dir1`, `dir2` and `normals` are left
/// empty; every other field is the same, bit for bit (test
/// `scalar_outputs_are_bitwise_the_full_pass`). For callers that use only κ₁, κ₂, H, K, A and
/// the statuses (the CLI writes nothing else): the three vector arrays are 72 % of the
/// outputs' memory (24 of 33 bytes per vertex, 19 MB on the 257k-vertex skull), fresh pages
/// that were written twice (zeroed, then filled). Fresh pages are what made the skull's
/// one-thread time bimodal on the benchmark's virtual machine: the kernel's clearing of a
/// fresh page (`clear_page_erms`) costs up to 5× more in some runs than in others
/// (`bench/README.md`, branch `jet10`).
///
/// ```
/// use morpho::curvature::{surface_curvature, surface_curvature_scalars, SurfaceOptions};
/// use morpho::mesh::generate;
/// let sphere = generate::icosphere(3);
/// let opts = SurfaceOptions::estimated_normals();
/// let (all, some) = (
///     surface_curvature(&sphere, &opts).unwrap(),
///     surface_curvature_scalars(&sphere, &opts).unwrap(),
/// );
/// assert_eq!((all.h, all.status), (some.h, some.status));
/// assert!(some.dir1.is_empty() && some.normals.is_empty());
/// ```
pub fn surface_curvature_scalars(
    mesh: &TriMesh,
    opts: &SurfaceOptions,
) -> Result<SurfaceCurvature, CurvatureError> {
    curvature_pass(mesh, opts, false, false, false)
}

/// [`surface_curvature`], or without `vectors` [`surface_curvature_scalars`]; with `baseline`
/// the vertex pass never takes its AVX2 compilation, with `unbatched` never the four-lane
/// quartic (for the tests that compare them).
fn curvature_pass(
    mesh: &TriMesh,
    opts: &SurfaceOptions,
    vectors: bool,
    baseline: bool,
    unbatched: bool,
) -> Result<SurfaceCurvature, CurvatureError> {
    mesh.validate()?;
    if opts.ring == 0 {
        return Err(CurvatureError::ZeroRing);
    }
    let n = mesh.positions.len();
    // estimated normals are summed vertex by vertex inside the parallel pass (the same sums in
    // the same order as `vertex_normals`, so the same bits): no serial pass over the
    // triangles and no array of normals
    let given: Option<&[Vector3]> = match &opts.normals {
        NormalSource::Estimated(_) => None,
        NormalSource::File => Some(
            mesh.normals
                .as_deref()
                .ok_or(CurvatureError::NoFileNormals)?,
        ),
        NormalSource::Given(g) => Some(g),
    };
    if let Some(g) = given {
        if g.len() != n {
            return Err(CurvatureError::NormalCount {
                given: g.len(),
                vertices: n,
            });
        }
    }
    let adj = Adjacency::new(mesh);
    // estimated normals: each triangle's weighted cross product once, in parallel (the
    // per-vertex sums below are the same bits as `vertex_normals`)
    let crosses = match &opts.normals {
        NormalSource::Estimated(w) => Some(weighted_crosses(mesh, *w)),
        _ => None,
    };
    let pass = Pass {
        mesh,
        adj: &adj,
        opts,
        given,
        crosses,
        baseline,
        unbatched,
    };
    // the outputs are allocated once and filled in place, chunk by chunk, in parallel (the
    // zeroed f64 arrays come from the allocator untouched; the vector arrays are written in
    // parallel): no per-vertex results collected and copied afterwards; each array asks
    // for transparent huge pages before its first write (one page fault per 2 MiB instead
    // of per 4 KiB: `advise_huge_pages`; the same contents)
    let zeros = || -> Vec<f64> {
        let mut v = vec![0.0; n];
        advise_huge_pages(&mut v);
        v
    };
    let zeros3 = || -> Vec<Vector3> {
        if !vectors {
            return Vec::new();
        }
        let mut v = Vec::with_capacity(n);
        advise_huge_pages(&mut v);
        v.par_extend((0..n).into_par_iter().map(|_| Vector3::zeros()));
        v
    };
    let mut status = vec![VertexStatus::Ok; n];
    advise_huge_pages(&mut status);
    let mut out = SurfaceCurvature {
        k1: zeros(),
        k2: zeros(),
        h: zeros(),
        k: zeros(),
        a: zeros(),
        dir1: zeros3(),
        dir2: zeros3(),
        normals: zeros3(),
        status,
        undetermined: 0,
        jet_fallbacks: 0,
    };
    // each chunk's slices of the vector outputs, or `None` for every chunk without them
    let vector_chunks: Vec<Option<VectorsOut<'_>>> = if vectors {
        out.dir1
            .chunks_mut(CHUNK)
            .zip(out.dir2.chunks_mut(CHUNK))
            .zip(out.normals.chunks_mut(CHUNK))
            .map(|((d1, d2), nm)| Some((d1, d2, nm)))
            .collect()
    } else {
        (0..n.div_ceil(CHUNK)).map(|_| None).collect()
    };
    let (undetermined, jet_fallbacks) = out
        .k1
        .par_chunks_mut(CHUNK)
        .zip(out.k2.par_chunks_mut(CHUNK))
        .zip(out.h.par_chunks_mut(CHUNK))
        .zip(out.k.par_chunks_mut(CHUNK))
        .zip(out.a.par_chunks_mut(CHUNK))
        .zip(out.status.par_chunks_mut(CHUNK))
        .zip(vector_chunks)
        .enumerate()
        .map_init(
            Scratch::default,
            |s, (c, ((((((k1, k2), h), k), a), status), vectors))| {
                let out = ChunkOut {
                    k1,
                    k2,
                    h,
                    k,
                    a,
                    status,
                    vectors,
                };
                pass.chunk(c * CHUNK, out, s)
            },
        )
        .reduce(|| (0, 0), |x, y| (x.0 + y.0, x.1 + y.1));
    out.undetermined = undetermined;
    out.jet_fallbacks = jet_fallbacks;
    Ok(out)
}

/// Vertices per parallel work item of [`surface_curvature`] (the item is the unit rayon
/// splits by; 1024 vertices are ~0.1 % of the 500k-vertex skull, small enough to balance two
/// cores, large enough that the per-item overhead is nothing).
const CHUNK: usize = 1024;

/// What every vertex of one [`surface_curvature`] call reads.
struct Pass<'a> {
    mesh: &'a TriMesh,
    adj: &'a Adjacency,
    opts: &'a SurfaceOptions,
    /// The normals from the file or the caller; `None`: estimated from the triangles.
    given: Option<&'a [Vector3]>,
    /// With estimated normals: every triangle's weighted cross product
    /// ([`weighted_crosses`]).
    crosses: Option<Vec<[f64; 3]>>,
    /// Never take the AVX2 compilation of the vertex pass ([`Pass::chunk`]; for tests).
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    baseline: bool,
    /// Never put vertices through the four-lane quartic ([`Pass::batch_run`]; for tests).
    unbatched: bool,
}

/// The per-thread buffers of the vertex pass, reused from vertex to vertex (no allocation per
/// vertex).
#[derive(Default)]
struct Scratch {
    ring: Vec<u32>,
    ring2: Vec<u32>,
    /// The offsets `y_j − y₀` of `ring` / `ring2`: gathered once, read by every fit of the
    /// vertex (the jet's 2-ring and the paraboloid's 1-ring, its prefix).
    dif: Vec<[f64; 3]>,
    dif2: Vec<[f64; 3]>,
    marks: Marks,
    batch: Batch,
}

/// Up to four vertices waiting for the four-lane quartic ([`Pass::batch_push`],
/// [`Pass::batch_run`]).
#[derive(Default)]
struct Batch {
    /// Vertices in the batch (lanes `0..count`).
    count: usize,
    /// Point `p` of lane `l` is `(pts[p][0].0[l], pts[p][1].0[l], pts[p][2].0[l])` =
    /// `(u, t, d)` for `p < len[l]`; the rest of a lane is stale until `batch_run` pads it.
    /// `pts[p][3]` holds the points' weights ([`jet_weight`]), computed by `batch_run`.
    pts: Vec<[F4; 4]>,
    len: [usize; 4],
    frame: [Frame; 4],
    /// The vertex's index in its chunk.
    index: [usize; 4],
}

/// The offsets `y_j − y₀` of the points `ring` into `out`.
fn gather(mesh: &TriMesh, y0: [f64; 3], ring: &[u32], out: &mut Vec<[f64; 3]>) {
    out.clear();
    out.extend(
        ring.iter()
            .map(|&j| vec::sub(mesh.positions[j as usize].into(), y0)),
    );
}

/// One chunk's slices of `dir1`, `dir2` and `normals`.
type VectorsOut<'o> = (&'o mut [Vector3], &'o mut [Vector3], &'o mut [Vector3]);

/// The output slices of one chunk of vertices ([`SurfaceCurvature`]'s fields of the same
/// names); `vectors` is `None` when the pass keeps no vector outputs
/// ([`surface_curvature_scalars`]).
struct ChunkOut<'o> {
    k1: &'o mut [f64],
    k2: &'o mut [f64],
    h: &'o mut [f64],
    k: &'o mut [f64],
    a: &'o mut [f64],
    status: &'o mut [VertexStatus],
    vectors: Option<VectorsOut<'o>>,
}

impl Pass<'_> {
    /// The vertices `first..` of one chunk into its output slices; the numbers of undetermined
    /// vertices and of jet fallbacks. On x86-64 processors with AVX2 (checked at run time) the
    /// same code is compiled a second time for AVX2 and that copy runs: wider vectors for the
    /// moments and the elimination, the same operations in the same order (no FMA: Rust never
    /// contracts a product and a sum), so the same bits (test
    /// `avx2_pass_is_bitwise_the_baseline_pass`).
    fn chunk(&self, first: usize, out: ChunkOut<'_>, s: &mut Scratch) -> (usize, usize) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && !self.baseline {
            // SAFETY: the processor has AVX2 (detected just above), the only requirement of
            // `chunk_avx2`
            return unsafe { self.chunk_avx2(first, out, s) };
        }
        self.chunk_any(first, out, s)
    }

    /// [`Pass::chunk_any`] compiled with AVX2 enabled.
    ///
    /// # Safety
    /// The processor must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn chunk_avx2(
        &self,
        first: usize,
        out: ChunkOut<'_>,
        s: &mut Scratch,
    ) -> (usize, usize) {
        self.chunk_any(first, out, s)
    }

    /// The body of [`Pass::chunk`], inlined (with the whole per-vertex fit) into each of its
    /// two compilations.
    #[inline(always)]
    fn chunk_any(&self, first: usize, out: ChunkOut<'_>, s: &mut Scratch) -> (usize, usize) {
        let ChunkOut {
            k1,
            k2,
            h,
            k,
            a,
            status,
            mut vectors,
        } = out;
        let (mut undetermined, mut fallbacks) = (0, 0);
        let len = k1.len();
        let mut put = |i: usize, r: Vertex, fallback: bool| {
            fallbacks += usize::from(fallback);
            undetermined += usize::from(r.status != VertexStatus::Ok);
            k1[i] = r.k[0];
            k2[i] = r.k[1];
            h[i] = 0.5 * (r.k[0] + r.k[1]);
            k[i] = r.k[0] * r.k[1];
            a[i] = r.k[0].abs() + r.k[1].abs();
            if let Some((dir1, dir2, normals)) = &mut vectors {
                dir1[i] = r.d[0].into();
                dir2[i] = r.d[1].into();
                normals[i] = r.n.into();
            }
            status[i] = r.status;
        };
        // interior vertices of the jet fit with at least 14 points go four at a time through
        // the quartic (`QuarticJet4`, one lane per vertex); every other vertex, and a lane
        // whose quartic is refused, through `vertex` (which then computes it again, as main
        // did: the cubic, the 3-ring, the fallbacks)
        let batching = self.opts.fit == SurfaceFit::Jet && !self.unbatched;
        s.batch.count = 0;
        for i in 0..len {
            let v = first + i;
            if batching && !self.adj.open[v] && self.batch_push(v, i, s) {
                if s.batch.count == 4 {
                    self.batch_run(first, s, &mut put);
                }
                continue;
            }
            let (r, fallback) = self.vertex(v, s);
            put(i, r, fallback);
        }
        if s.batch.count > 0 {
            self.batch_run(first, s, &mut put);
        }
        (undetermined, fallbacks)
    }

    /// The given or estimated normal of `v` (not normalised; zero when there is none).
    #[inline(always)]
    fn normal_of(&self, v: usize) -> [f64; 3] {
        match self.given {
            Some(g) => g[v].into(),
            None => match &self.crosses {
                Some(c) => vertex_normal_from(c, self.adj.triangles(v)).into(),
                None => [0.0; 3],
            },
        }
    }

    /// Puts the interior vertex `v` (index `i` in its chunk) of the jet fit into the next lane
    /// of `s.batch`: its ring of `max(ring, 2)` as in [`Pass::vertex`], its frame
    /// ([`jet_frame`]) and its local coordinates. `false` (nothing added) when the ring has
    /// fewer than 14 points or the frame is undetermined: then `vertex` decides.
    #[inline(always)]
    fn batch_push(&self, v: usize, i: usize, s: &mut Scratch) -> bool {
        let nrm = self.normal_of(v);
        let y0: [f64; 3] = self.mesh.positions[v].into();
        self.adj
            .ring(v, self.opts.ring.max(2), &mut s.ring2, &mut s.marks);
        gather(self.mesh, y0, &s.ring2, &mut s.dif2);
        if s.dif2.len() < 14 {
            return false;
        }
        let Some(frame) = jet_frame(&s.dif2, nrm) else {
            return false;
        };
        let b = &mut s.batch;
        let lane = b.count;
        if b.pts.len() < s.dif2.len() {
            b.pts.resize(s.dif2.len(), [F4::ZERO; 4]);
        }
        for (p, &w) in b.pts.iter_mut().zip(&s.dif2) {
            let (u, t, d) = frame.local(w);
            p[0].0[lane] = u;
            p[1].0[lane] = t;
            p[2].0[lane] = d;
        }
        b.len[lane] = s.dif2.len();
        b.frame[lane] = frame;
        b.index[lane] = i;
        b.count += 1;
        true
    }

    /// The quartic jets of the vertices in `s.batch` (lanes past `count` are empty), their
    /// curvatures into `put`; a refused lane goes through [`Pass::vertex`]. Empties the batch.
    #[inline(always)]
    fn batch_run(&self, first: usize, s: &mut Scratch, put: &mut impl FnMut(usize, Vertex, bool)) {
        let b = &mut s.batch;
        let count = b.count;
        let len: [usize; 4] = std::array::from_fn(|l| if l < count { b.len[l] } else { 0 });
        let longest = len.iter().copied().max().unwrap_or(0);
        // pad the shorter lanes with (0, 0, 0): adds exactly nothing (`QuarticJet4`)
        for (l, &n) in len.iter().enumerate() {
            for p in &mut b.pts[n..longest] {
                for x in p.iter_mut() {
                    x.0[l] = 0.0;
                }
            }
        }
        // the weights first, in a loop of their own: every monomial of a point depends on its
        // weight, and computed inline the division's latency held up the moments' chain
        // (skull, one thread, process CPU medians of one alternating run: main 378 ms, inline
        // 389 ms, this 385 ms); the same operations, so the same bits (a padding point
        // (0, 0, 0) has weight ε⁻⁴ and still adds exactly +0)
        for p in &mut b.pts[..longest] {
            p[3] = jet_weight(p[0], p[1], p[2]);
        }
        let mut q = QuarticJet4::new();
        for p in &b.pts[..longest] {
            q.add(p[0], p[1], p[2], p[3]);
        }
        let sol = q.solve(SURFACE_MAX_COND);
        let (frame, index) = (b.frame, b.index);
        b.count = 0;
        for l in 0..count {
            match sol[l] {
                Some(c) => {
                    let f = &frame[l];
                    let r = graph_vertex(
                        f.n,
                        (f.b1, f.b2),
                        [c[0], c[1]],
                        [c[2] * f.inv, c[3] * f.inv, c[4] * f.inv],
                    );
                    put(index[l], r, false);
                }
                None => {
                    let (r, fallback) = self.vertex(first + index[l], s);
                    put(index[l], r, fallback);
                }
            }
        }
    }

    /// The fit at vertex `v`, and whether its jet normal fell back to the given one.
    fn vertex(&self, v: usize, s: &mut Scratch) -> (Vertex, bool) {
        let (adj, opts, mesh) = (self.adj, self.opts, self.mesh);
        let mut nrm = self.normal_of(v);
        let y0: [f64; 3] = mesh.positions[v].into();
        let deg = adj.of(v).len();
        let mut fallback = false;
        let jet_fit_here = opts.fit == SurfaceFit::Jet && !adj.open[v];
        if jet_fit_here {
            // the curvature of the cubic jet itself (no second fit)
            let k = opts.ring.max(2);
            adj.ring(v, k, &mut s.ring2, &mut s.marks);
            gather(mesh, y0, &s.ring2, &mut s.dif2);
            let jet = jet_fit(&s.dif2, nrm, true, true).or_else(|| {
                adj.ring(v, k + 1, &mut s.ring, &mut s.marks);
                gather(mesh, y0, &s.ring, &mut s.dif);
                jet_fit(&s.dif, nrm, true, true)
            });
            return match jet {
                Some(j) => (graph_vertex(j.n, j.b, j.g, j.hess), false),
                // the breadth-first ring lists the 1-ring first
                None => (fit_vertex(&s.dif2[..deg], nrm), true),
            };
        }
        // on an open fan the jet and the paraboloid are one-sided: the quadric with linear
        // terms over the (at least) 2-ring instead (module doc, "Boundaries")
        let boundary_quadric = (opts.jet_normals || opts.fit == SurfaceFit::Jet) && adj.open[v];
        if opts.jet_normals && !boundary_quadric {
            adj.ring(v, 2, &mut s.ring2, &mut s.marks);
            gather(mesh, y0, &s.ring2, &mut s.dif2);
            // a 2-ring too small or too flat for the cubic (a valence-3 vertex among
            // valence-3 neighbours has 8 points): the 3-ring
            let jet = jet_normal(&s.dif2, nrm).or_else(|| {
                adj.ring(v, 3, &mut s.ring, &mut s.marks);
                gather(mesh, y0, &s.ring, &mut s.dif);
                jet_normal(&s.dif, nrm)
            });
            match jet {
                Some(j) => nrm = j,
                None => fallback = true,
            }
        }
        // the breadth-first ring lists the 1-ring first: reuse the 2-ring's prefix
        let platelet: &[[f64; 3]] = match (opts.jet_normals, opts.ring) {
            (true, 1) if !boundary_quadric => &s.dif2[..deg],
            (true, 2) if !boundary_quadric => &s.dif2,
            _ => {
                let k = if boundary_quadric {
                    opts.ring.max(2)
                } else {
                    opts.ring
                };
                adj.ring(v, k, &mut s.ring, &mut s.marks);
                gather(mesh, y0, &s.ring, &mut s.dif);
                &s.dif
            }
        };
        let r = match opts.fit {
            SurfaceFit::Paraboloid | SurfaceFit::Jet if boundary_quadric => {
                let r = fit_quadric(platelet, nrm);
                if r.status == VertexStatus::Ok {
                    r
                } else {
                    fit_vertex(&platelet[..deg], nrm)
                }
            }
            // (an interior vertex with the jet fit returned above)
            SurfaceFit::Paraboloid | SurfaceFit::Jet => fit_vertex(platelet, nrm),
            SurfaceFit::Quadric => fit_quadric(platelet, nrm),
        };
        (r, fallback)
    }
}

/// The result of one vertex.
struct Vertex {
    k: [f64; 2],
    d: [[f64; 3]; 2],
    n: [f64; 3],
    status: VertexStatus,
}

impl Vertex {
    fn undetermined(n: [f64; 3], status: VertexStatus) -> Self {
        Vertex {
            k: [f64::NAN; 2],
            d: [[f64::NAN; 3]; 2],
            n,
            status,
        }
    }
}

/// Steps (i)–(viii) at a vertex with platelet offsets `ring` (`y_j − y₀`, without `y₀`) and
/// normal `nrm`.
fn fit_vertex(ring: &[[f64; 3]], nrm: [f64; 3]) -> Vertex {
    let n = match unit_normal(ring, nrm, 3) {
        Ok(n) => n,
        Err(r) => return r,
    };
    let (b1, b2) = tangent_basis(n);
    let mut ne = Normal::<3>::new();
    for &w in ring {
        let d = vec::dot(n, w);
        // the projection's offset from y₀ is w − d n, orthogonal to n: its b-coordinates are
        // those of w
        let (u, t) = (vec::dot(w, b1), vec::dot(w, b2));
        ne.add([0.5 * u * u, u * t, 0.5 * t * t], d);
    }
    let Some(c) = ne.solve(SURFACE_MAX_COND) else {
        return Vertex::undetermined(n, VertexStatus::IllConditioned);
    };
    let (k, e) = sym2_eigen(c[0], c[1], c[2]);
    let d1 = vec::add_scaled(vec::scale(b1, e[0]), e[1], b2);
    let d2 = vec::cross(n, d1);
    Vertex {
        k,
        d: [d1, d2],
        n,
        status: VertexStatus::Ok,
    }
}

/// The unit normal, or the status of a vertex without one.
fn unit_normal(ring: &[[f64; 3]], nrm: [f64; 3], need: usize) -> Result<[f64; 3], Vertex> {
    let len = vec::norm(nrm);
    if len.is_nan() || len <= 0.0 || len.is_infinite() {
        let status = if ring.is_empty() {
            VertexStatus::Isolated
        } else {
            VertexStatus::NoNormal
        };
        return Err(Vertex::undetermined([0.0; 3], status));
    }
    let n = vec::scale(nrm, 1.0 / len);
    if ring.is_empty() {
        return Err(Vertex::undetermined(n, VertexStatus::Isolated));
    }
    if ring.len() < need {
        return Err(Vertex::undetermined(n, VertexStatus::TooFewPoints));
    }
    Ok(n)
}

/// The quadric with linear terms ([`SurfaceFit::Quadric`]) at vertex `v`: least squares
/// `a u + b v + ½(c20 u² + 2 c11 uv + c02 v²) = d_j` in the frame of `nrm`, then the
/// curvatures of that graph at the origin (H (4.15)): the eigenvalues of `S Hess S / l` with
/// `l = √(1+a²+b²)` and `S = (I + ggᵀ)^{-1/2}`, `g = (a, b)`. The coordinates are divided by
/// the platelet's RMS radius ρ first, so that the condition number stays scale-free.
fn fit_quadric(ring: &[[f64; 3]], nrm: [f64; 3]) -> Vertex {
    let n = match unit_normal(ring, nrm, 5) {
        Ok(n) => n,
        Err(r) => return r,
    };
    let (b1, b2) = tangent_basis(n);
    let rho2 = ring.iter().map(|&w| vec::norm2(w)).sum::<f64>() / ring.len() as f64;
    let rho = rho2.sqrt();
    if !(rho > 0.0 && rho.is_finite()) {
        return Vertex::undetermined(n, VertexStatus::IllConditioned);
    }
    let inv = 1.0 / rho;
    let mut ne = Normal::<5>::new();
    for &w in ring {
        let w = vec::scale(w, inv);
        let (u, t) = (vec::dot(w, b1), vec::dot(w, b2));
        ne.add([u, t, 0.5 * u * u, u * t, 0.5 * t * t], vec::dot(n, w));
    }
    let Some(c) = ne.solve(SURFACE_MAX_COND) else {
        return Vertex::undetermined(n, VertexStatus::IllConditioned);
    };
    // slopes are scale-free; second derivatives scale by 1/ρ
    graph_vertex(
        n,
        (b1, b2),
        [c[0], c[1]],
        [c[2] * inv, c[3] * inv, c[4] * inv],
    )
}

/// The curvatures, principal directions and normal at the origin of the graph
/// `d = a u + b v + ½(h11 u² + 2 h12 uv + h22 v²) + (higher terms)` over the frame `(b₁, b₂, n)`
/// (H (4.15)): with the gradient `g = (a, b)`, the first fundamental form is `I + ggᵀ`, the
/// second `Hess / l` along the graph's unit normal `(n − a b₁ − b b₂)/l`, `l = √(1+|g|²)`, and
/// the principal curvatures are the eigenvalues of the shape operator `(I + ggᵀ)⁻¹ Hess / l`,
/// i.e. of the symmetric `S Hess S / l` with `S = (I + ggᵀ)^{-1/2} = I + (1/l − 1) ĝĝᵀ`; an
/// eigenvector `e` gives the parameter direction `S e`, mapped onto the tangent
/// `(b₁ + a n, b₂ + b n)`. Curvature is measured along the graph's normal, which has a positive
/// component along `n`: flipping `n` flips the curvatures.
#[inline(always)]
fn graph_vertex(
    n: [f64; 3],
    (b1, b2): ([f64; 3], [f64; 3]),
    g: [f64; 2],
    hess: [f64; 3],
) -> Vertex {
    let [ga, gb] = g;
    let [h11, h12, h22] = hess;
    let g2 = ga * ga + gb * gb;
    let l = (1.0 + g2).sqrt();
    // S = I + (1/l − 1) ĝĝᵀ
    let f = if g2 > 0.0 { (1.0 / l - 1.0) / g2 } else { 0.0 };
    let s = [
        [1.0 + f * ga * ga, f * ga * gb],
        [f * ga * gb, 1.0 + f * gb * gb],
    ];
    let hs = [
        [h11 * s[0][0] + h12 * s[1][0], h11 * s[0][1] + h12 * s[1][1]],
        [h12 * s[0][0] + h22 * s[1][0], h12 * s[0][1] + h22 * s[1][1]],
    ];
    let m = |i: usize, j: usize| (s[i][0] * hs[0][j] + s[i][1] * hs[1][j]) / l;
    let (k, e) = sym2_eigen(m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), m(1, 1));
    // the parameter direction S e, mapped onto the graph's tangent (b₁ + a n, b₂ + b n)
    let w = [
        s[0][0] * e[0] + s[0][1] * e[1],
        s[1][0] * e[0] + s[1][1] * e[1],
    ];
    let t1 = vec::add_scaled(
        vec::add_scaled(vec::scale(b1, w[0]), w[1], b2),
        w[0] * ga + w[1] * gb,
        n,
    );
    let d1 = vec::scale(t1, 1.0 / vec::norm(t1));
    let nf = vec::scale(
        vec::add_scaled(vec::add_scaled(n, -ga, b1), -gb, b2),
        1.0 / l,
    );
    Vertex {
        k,
        d: [d1, vec::cross(nf, d1)],
        n: nf,
        status: VertexStatus::Ok,
    }
}

/// The jet `a u + b v + ½(c20 u² + 2c11 uv + c02 v²) + c30 u³ + c21 u²v + c12 uv² + c03 v³
/// [+ c40 u⁴ + c31 u³v + c22 u²v² + c13 uv³ + c04 v⁴]` fitted over `ring` in the frame
/// `(b₁, b₂, n)` of `nrm` (jet fitting): with `quartic`, of degree 4 where the ring has at least
/// 14 points and its fit is determined, else of degree 3 (from the same moments). Returns the
/// unit `n`, the tangent basis, the gradient and the Hessian at the origin (in the units of the
/// positions). Coordinates are divided by the RMS radius ρ first (scale-free pivot test; slopes
/// are scale-free, second derivatives scale by 1/ρ). With `weighted` (the curvature of
/// [`SurfaceFit::Jet`]) each point has the least-squares weight [`jet_weight`] of its scaled
/// distance (module doc, "Distance weights"); without (the jet normals of
/// [`SurfaceOptions::jet_normals`]) every weight is 1. `None` when `nrm` is not usable, fewer
/// than 9 points, or a pivot ratio above 1e10 in degree 3.
fn jet_fit(ring: &[[f64; 3]], nrm: [f64; 3], quartic: bool, weighted: bool) -> Option<Jet> {
    let f = jet_frame(ring, nrm)?;
    let weight = |u, t, d| if weighted { jet_weight(u, t, d) } else { 1.0 };
    let c: [f64; 5] = if quartic && ring.len() >= 14 {
        // the 42 moments of the quartic's rows (`QuarticJet`); the cubic's are their prefix
        let mut q = QuarticJet::new();
        for &w in ring {
            let (u, t, d) = f.local(w);
            q.add_weighted(u, t, d, weight(u, t, d));
        }
        match q.solve(SURFACE_MAX_COND) {
            Some(c) => std::array::from_fn(|i| c[i]),
            None => {
                let c = q.cubic().solve(SURFACE_MAX_COND)?;
                std::array::from_fn(|i| c[i])
            }
        }
    } else {
        // the 25 moments of the cubic's rows (`CubicJet`): fewer products than the rows
        let mut jet = CubicJet::new();
        for &w in ring {
            let (u, t, d) = f.local(w);
            jet.add_weighted(u, t, d, weight(u, t, d));
        }
        let c = jet.solve(SURFACE_MAX_COND)?;
        std::array::from_fn(|i| c[i])
    };
    Some(Jet {
        n: f.n,
        b: (f.b1, f.b2),
        g: [c[0], c[1]],
        hess: [c[2] * f.inv, c[3] * f.inv, c[4] * f.inv],
    })
}

/// The frame of a jet fit ([`jet_fit`], [`Pass::batch_push`]): the unit normal, the tangent
/// basis and the reciprocal RMS radius of the ring.
#[derive(Debug, Clone, Copy, Default)]
struct Frame {
    n: [f64; 3],
    b1: [f64; 3],
    b2: [f64; 3],
    inv: f64,
}

impl Frame {
    /// The local coordinates `(u, t, d)` of the offset `w`, divided by the RMS radius.
    #[inline(always)]
    fn local(&self, w: [f64; 3]) -> (f64, f64, f64) {
        let w = vec::scale(w, self.inv);
        (
            vec::dot(w, self.b1),
            vec::dot(w, self.b2),
            vec::dot(self.n, w),
        )
    }
}

/// The frame of the jet over `ring` with normal `nrm`; `None` when `nrm` is not usable, the
/// ring has fewer than 9 points or its RMS radius is zero or not finite.
#[inline(always)]
fn jet_frame(ring: &[[f64; 3]], nrm: [f64; 3]) -> Option<Frame> {
    let len = vec::norm(nrm);
    if !(len > 0.0 && len.is_finite()) || ring.len() < 9 {
        return None;
    }
    let n = vec::scale(nrm, 1.0 / len);
    let (b1, b2) = tangent_basis(n);
    let rho2 = ring.iter().map(|&w| vec::norm2(w)).sum::<f64>() / ring.len() as f64;
    if !(rho2 > 0.0 && rho2.is_finite()) {
        return None;
    }
    Some(Frame {
        n,
        b1,
        b2,
        inv: 1.0 / rho2.sqrt(),
    })
}

/// A fitted jet at a vertex ([`jet_fit`]): frame, gradient and Hessian at the origin.
struct Jet {
    n: [f64; 3],
    b: ([f64; 3], [f64; 3]),
    g: [f64; 2],
    hess: [f64; 3],
}

/// The normal of the cubic jet ([`jet_fit`]) over `ring` in the frame of `nrm`: the graph's
/// normal at the vertex, `(n − a b₁ − b b₂)/√(1+a²+b²)`. The cubic terms keep the surface's
/// third-order part out of the slopes (a quadric's slopes carry it, O(h²) with the 2-ring's
/// larger constant).
fn jet_normal(ring: &[[f64; 3]], nrm: [f64; 3]) -> Option<[f64; 3]> {
    let j = jet_fit(ring, nrm, false, false)?;
    let (b1, b2) = j.b;
    let m = vec::add_scaled(vec::add_scaled(j.n, -j.g[0], b1), -j.g[1], b2);
    let l = vec::norm(m);
    (l > 0.0 && l.is_finite()).then(|| vec::scale(m, 1.0 / l))
}

/// Orthonormal `b₁, b₂` with `(b₁, b₂, n)` right-handed, `b₁ ∝ n × e_k` for the axis `e_k`
/// least aligned with `n`.
pub(crate) fn tangent_basis(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let a = n.map(f64::abs);
    let k = if a[0] <= a[1] && a[0] <= a[2] {
        0
    } else if a[1] <= a[2] {
        1
    } else {
        2
    };
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let c = vec::cross(n, e);
    let b1 = vec::scale(c, 1.0 / vec::norm(c));
    (b1, vec::cross(n, b1))
}

/// Eigenvalues `λ₁ ≤ λ₂` of `[[a, b], [b, c]]` and the unit eigenvector of λ₁ (closed form).
fn sym2_eigen(a: f64, b: f64, c: f64) -> ([f64; 2], [f64; 2]) {
    let m = 0.5 * (a + c);
    let r = hypot2(0.5 * (a - c), b);
    let (l1, l2) = (m - r, m + r);
    // (A − λ₁I) has rows (a−λ₁, b) and (b, c−λ₁); an eigenvector is orthogonal to both: take
    // the perpendicular of the longer row
    let (p, q) = ([b, l1 - a], [l1 - c, b]);
    let e = if vec::norm2(p) >= vec::norm2(q) { p } else { q };
    let len = vec::norm(e);
    let e = if len > 0.0 {
        vec::scale(e, 1.0 / len)
    } else {
        [1.0, 0.0]
    };
    ([l1, l2], e)
}

/// `√(x² + y²)`: the plain formula where neither square can overflow nor lose bits to
/// underflow (libm's `hypot` was 4 % of the whole curvature pass), else [`f64::hypot`].
#[inline]
fn hypot2(x: f64, y: f64) -> f64 {
    // exactly flat or umbilic platelets (c20 = c02, c11 = 0: planar parts of contour surfaces)
    // are common; their squares would fall below the range and into `hypot`
    if x == 0.0 {
        return y.abs();
    }
    if y == 0.0 {
        return x.abs();
    }
    let q = x * x + y * y;
    if (1e-290..=f64::MAX).contains(&q) {
        q.sqrt()
    } else {
        x.hypot(y)
    }
}

/// Vertex adjacency: incident triangles and unique neighbours (ascending), in compressed rows.
struct Adjacency {
    /// The triangles of vertex `v` are `tri[tstart[v]..tstart[v + 1]]`, ascending.
    tstart: Vec<usize>,
    tri: Vec<u32>,
    /// The neighbours of `v` are `nb[nstart[v]..nstart[v + 1]]`: exact rows, no gaps (the
    /// ring search reads a row's bounds from one cache line and its rows are dense).
    nstart: Vec<usize>,
    nb: Vec<u32>,
    /// Vertices whose neighbours outnumber their triangles: an open fan (on a boundary).
    open: Vec<bool>,
}

/// Vertices per parallel block of [`Adjacency::new`].
const ADJ_BLOCK: usize = 4096;

impl Adjacency {
    /// Incident triangles by counting (O(T)), then each vertex's sorted neighbours, in
    /// parallel blocks of vertices. A vertex has room for two neighbours per incident triangle
    /// (the other two corners), so every block's room is known before any row is filled and
    /// the blocks are filled in parallel in place; inside its block a row is moved left to
    /// the end of the previous one as soon as it is made (it never overtakes its own room:
    /// each earlier row took at most its room). The blocks' packed rows are then moved left
    /// one after the other (in order: each lands at or before its place, `copy_within`
    /// handles the overlap) and the row starts shifted by their block's start: exact rows in
    /// half the memory of the rooms (6 MB instead of 12 on the 257k-vertex skull).
    fn new(mesh: &TriMesh) -> Self {
        let n = mesh.positions.len();
        let mut tstart = vec![0usize; n + 1];
        advise_huge_pages(&mut tstart);
        for t in &mesh.triangles {
            for &x in t {
                tstart[x as usize] += 1;
            }
        }
        // inclusive sums: tstart[v] = the end of v's row (tstart[n] = the total)
        let mut sum = 0;
        for e in &mut tstart {
            sum += *e;
            *e = sum;
        }
        // each row filled from its end, the triangles taken in descending order: the rows
        // come out ascending and tstart[v] moves back to the start of v's row (no second
        // array of cursors: 2 MB fewer fresh pages on the skull)
        let mut tri = vec![0u32; sum];
        advise_huge_pages(&mut tri);
        for (ti, t) in mesh.triangles.iter().enumerate().rev() {
            for &x in t {
                let e = &mut tstart[x as usize];
                *e -= 1;
                tri[*e] = ti as u32;
            }
        }
        let mut nb = vec![0u32; 2 * tstart[n]];
        advise_huge_pages(&mut nb);
        // nstart[v + 1], until the blocks are joined: the end of v's row relative to its
        // block's first row
        let mut nstart = vec![0usize; n + 1];
        advise_huge_pages(&mut nstart);
        let mut open = vec![false; n];
        let mut rows = Vec::with_capacity(n.div_ceil(ADJ_BLOCK));
        let mut rest: &mut [u32] = &mut nb;
        for lo in (0..n).step_by(ADJ_BLOCK) {
            let hi = (lo + ADJ_BLOCK).min(n);
            let (row, r) = std::mem::take(&mut rest).split_at_mut(2 * (tstart[hi] - tstart[lo]));
            rows.push(row);
            rest = r;
        }
        rows.into_par_iter()
            .zip(nstart[1..].par_chunks_mut(ADJ_BLOCK))
            .zip(open.par_chunks_mut(ADJ_BLOCK))
            .enumerate()
            .for_each(|(b, ((row, end), open))| {
                let base = 2 * tstart[b * ADJ_BLOCK];
                let mut used = 0;
                for (i, (e, o)) in end.iter_mut().zip(open.iter_mut()).enumerate() {
                    let v = b * ADJ_BLOCK + i;
                    let (t0, t1) = (tstart[v], tstart[v + 1]);
                    let room = 2 * t0 - base;
                    let out = &mut row[room..2 * t1 - base];
                    // each occurrence of v in a triangle adds at most its two other corners
                    let mut m = 0;
                    for &ti in &tri[t0..t1] {
                        for &x in &mesh.triangles[ti as usize] {
                            if x as usize != v {
                                out[m] = x;
                                m += 1;
                            }
                        }
                    }
                    let out = &mut out[..m];
                    out.sort_unstable();
                    let mut k = 0;
                    for j in 0..m {
                        if k == 0 || out[j] != out[k - 1] {
                            out[k] = out[j];
                            k += 1;
                        }
                    }
                    // used ≤ room: the earlier rows of the block took at most their rooms
                    row.copy_within(room..room + k, used);
                    used += k;
                    *e = used;
                    *o = k > t1 - t0;
                }
            });
        // join the blocks: block b's packed rows start at `at` (the rows before it)
        let mut at = 0;
        let mut starts = Vec::with_capacity(n.div_ceil(ADJ_BLOCK));
        for lo in (0..n).step_by(ADJ_BLOCK) {
            let hi = (lo + ADJ_BLOCK).min(n);
            let used = nstart[hi];
            nb.copy_within(2 * tstart[lo]..2 * tstart[lo] + used, at);
            starts.push(at);
            at += used;
        }
        nb.truncate(at);
        nstart[1..]
            .par_chunks_mut(ADJ_BLOCK)
            .zip(starts)
            .for_each(|(end, at)| {
                for e in end {
                    *e += at;
                }
            });
        Adjacency {
            tstart,
            tri,
            nstart,
            nb,
            open,
        }
    }
    /// The triangles containing `v`, ascending.
    fn triangles(&self, v: usize) -> &[u32] {
        &self.tri[self.tstart[v]..self.tstart[v + 1]]
    }
    fn of(&self, v: usize) -> &[u32] {
        &self.nb[self.nstart[v]..self.nstart[v + 1]]
    }
    /// The vertices within `k` edges of `v`, without `v`, into `out` (breadth-first: the
    /// 1-ring first, in its sorted order, then each level in discovery order).
    fn ring(&self, v: usize, k: usize, out: &mut Vec<u32>, marks: &mut Marks) {
        out.clear();
        out.extend_from_slice(self.of(v));
        if k == 1 {
            return;
        }
        let g = marks.next(self.open.len());
        let seen = &mut marks.stamp;
        seen[v] = g;
        for &x in out.iter() {
            seen[x as usize] = g;
        }
        let mut level = 0..out.len();
        for _ in 1..k {
            let end = out.len();
            for i in level.clone() {
                let w = out[i] as usize;
                for &x in self.of(w) {
                    if seen[x as usize] != g {
                        seen[x as usize] = g;
                        out.push(x);
                    }
                }
            }
            level = end..out.len();
        }
    }
}

/// Visited marks of the ring search, one per vertex and thread: a vertex is seen in the
/// current search when its stamp equals the search's generation (no clearing between
/// searches; the O(1) test replaced a scan of the ring found so far).
#[derive(Default)]
struct Marks {
    stamp: Vec<u32>,
    generation: u32,
}

impl Marks {
    /// The generation of a new search over `n` vertices.
    fn next(&mut self, n: usize) -> u32 {
        if self.stamp.len() < n {
            // zeroed by the allocator: pages are touched only where the searches go
            self.stamp = vec![0; n];
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.fill(0);
            self.generation = 1;
        }
        self.generation
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::mesh::{generate, vertex_normals};
    use std::collections::BTreeSet;

    /// A mesh with every special case of the adjacency: a triangle repeating a vertex, a
    /// non-manifold edge (three triangles), a boundary, an isolated vertex, and enough
    /// vertices for several parallel blocks.
    fn awkward_mesh() -> TriMesh {
        let mut m = generate::torus(2.0, 0.7, 90, 60);
        let n = m.positions.len() as u32;
        m.positions.push(Point3::new(9.0, 9.0, 9.0)); // isolated
        m.positions.push(Point3::new(5.0, 0.0, 0.0));
        m.triangles.push([0, 0, 1]);
        m.triangles.push([0, 1, n + 1]); // third triangle on edge 0–1
        m.triangles.push([2, 2, 2]);
        m
    }

    #[test]
    fn adjacency_rows_match_a_direct_construction() {
        // and a mesh of three parallel blocks whose rows use their rooms unevenly (open fans
        // from holes everywhere, a repeated vertex and a non-manifold edge in the middle
        // block, an isolated vertex at the end): the packing inside the blocks and their
        // joining must keep every row
        let mut holes = generate::torus(2.0, 0.7, 150, 60);
        let mut k = 0;
        holes.triangles.retain(|_| {
            k += 1;
            k % 7 != 0
        });
        holes.positions.push(Point3::new(9.0, 9.0, 9.0));
        holes.triangles.push([4100, 4100, 8200]);
        holes.triangles.push([4097, 4098, 8999]);
        holes.triangles.push([4097, 4098, 12]);
        holes.triangles.push([4097, 4098, 5000]);
        for m in [awkward_mesh(), holes] {
            adjacency_rows_match(&m);
        }
    }

    fn adjacency_rows_match(m: &TriMesh) {
        let adj = Adjacency::new(m);
        // exact rows: nothing between them
        assert_eq!(adj.nstart[0], 0);
        assert_eq!(adj.nstart[m.positions.len()], adj.nb.len());
        for v in 0..m.positions.len() {
            let tris: Vec<u32> = (0..m.triangles.len() as u32)
                .filter(|&t| m.triangles[t as usize].contains(&(v as u32)))
                .collect();
            let uses: usize = m
                .triangles
                .iter()
                .map(|t| t.iter().filter(|&&x| x as usize == v).count())
                .sum();
            let nb: BTreeSet<u32> = tris
                .iter()
                .flat_map(|&t| m.triangles[t as usize])
                .filter(|&x| x as usize != v)
                .collect();
            assert_eq!(adj.of(v), nb.iter().copied().collect::<Vec<_>>(), "{v}");
            assert_eq!(adj.open[v], nb.len() > uses, "{v}");
            // every triangle once per corner it gives v, ascending
            let mut t2 = adj.triangles(v).to_vec();
            assert!(t2.windows(2).all(|w| w[0] <= w[1]));
            t2.dedup();
            assert_eq!(t2, tris, "{v}");
        }
    }

    /// The rings of the adjacency's rows against a breadth-first search over neighbour sets
    /// built directly from the triangles: the same vertices in the same order (the fits' sums
    /// run in ring order, so the order is part of the result).
    #[test]
    fn rings_match_a_direct_breadth_first_search() {
        let m = awkward_mesh();
        let adj = Adjacency::new(&m);
        let n = m.positions.len();
        let mut nbs = vec![BTreeSet::new(); n];
        for t in &m.triangles {
            for &a in t {
                for &b in t {
                    if a != b {
                        nbs[a as usize].insert(b);
                    }
                }
            }
        }
        let (mut out, mut marks) = (Vec::new(), Marks::default());
        for v in (0..n).step_by(7).chain([0, 1, 2, n - 2, n - 1]) {
            for k in 1..=3 {
                let mut want: Vec<u32> = nbs[v].iter().copied().collect();
                let mut seen: BTreeSet<u32> = want.iter().copied().collect();
                seen.insert(v as u32);
                let mut level = 0..want.len();
                for _ in 1..k {
                    let end = want.len();
                    for i in level.clone() {
                        for &x in &nbs[want[i] as usize] {
                            if seen.insert(x) {
                                want.push(x);
                            }
                        }
                    }
                    level = end..want.len();
                }
                adj.ring(v, k, &mut out, &mut marks);
                assert_eq!(out, want, "{v} {k}");
            }
        }
    }

    #[test]
    fn hypot2_is_hypot() {
        let mut x = 0.3f64;
        for e in [-300, -200, -150, -20, 0, 20, 150, 154, 160, 300] {
            for _ in 0..50 {
                x = (x * 7.1 + 0.13).fract();
                let (a, b) = ((x - 0.5) * 10f64.powi(e), (0.7 - x) * 10f64.powi(e / 2));
                let (h, r) = (hypot2(a, b), a.hypot(b));
                assert!((h - r).abs() <= 2.0 * f64::EPSILON * r, "{a} {b}: {h} {r}");
            }
        }
        assert_eq!(hypot2(0.0, 0.0), 0.0);
        assert_eq!(hypot2(-0.0, -3e-300), 3e-300);
        assert_eq!(hypot2(-2.5, 0.0), 2.5);
        assert!(hypot2(0.0, f64::NAN).is_nan());
        assert_eq!(hypot2(f64::MAX, f64::MAX), f64::INFINITY);
        assert!((hypot2(3e200, 4e200) / 5e200 - 1.0).abs() < 1e-15);
        assert!(hypot2(f64::NAN, 1.0).is_nan());
    }

    /// Meshes whose 2-rings have many lengths: a jittered torus, a UV sphere (valence-3n
    /// poles), a disk (a boundary, a high-valence centre), the awkward mesh, and a torus with a
    /// patch collapsed onto one point (rank-deficient quartics: refused lanes).
    fn lane_meshes() -> Vec<TriMesh> {
        let mut x = 0.3f64;
        let mut next = move || {
            x = (x * 3.7 + 0.19).fract();
            x - 0.5
        };
        let mut jittered = generate::torus(2.0, 0.7, 40, 23);
        for p in &mut jittered.positions {
            p.x += 0.02 * next();
            p.y += 0.02 * next();
            p.z += 0.02 * next();
        }
        let mut collapsed = generate::torus(2.0, 0.7, 30, 20);
        for p in collapsed.positions.iter_mut().skip(200).take(45) {
            *p = Point3::new(2.5, 0.1, 0.3);
        }
        vec![
            jittered,
            generate::uv_sphere(Point3::new(0.0, 0.0, 0.0), 1.5, 17, 29),
            generate::disk(9, 23),
            awkward_mesh(),
            collapsed,
        ]
    }

    /// The bits of every output of a curvature pass (NaN included).
    fn bits(c: &SurfaceCurvature) -> Vec<u64> {
        let mut b: Vec<u64> = [&c.k1, &c.k2, &c.h, &c.k, &c.a]
            .iter()
            .flat_map(|v| v.iter().map(|x| x.to_bits()))
            .collect();
        for v in [&c.dir1, &c.dir2, &c.normals] {
            b.extend(v.iter().flat_map(|p| [p.x, p.y, p.z]).map(f64::to_bits));
        }
        b.extend(c.status.iter().map(|s| *s as u64));
        b.extend([c.undetermined as u64, c.jet_fallbacks as u64]);
        b
    }

    #[test]
    fn batched_and_avx2_passes_are_bitwise_the_scalar_pass() {
        // the four-lane quartic (`Pass::batch_run`) and the AVX2 compilation must give the
        // scalar pass's bits on every vertex: a lane that mixes another vertex's points, a
        // padding that adds something, a refused lane not recomputed, or a different order of
        // operations changes some bits
        let mut refused = 0;
        for (k, m) in lane_meshes().iter().enumerate() {
            for opts in [
                SurfaceOptions::estimated_normals(),
                SurfaceOptions {
                    ring: 3,
                    ..SurfaceOptions::estimated_normals()
                },
            ] {
                let scalar = curvature_pass(m, &opts, true, true, true).unwrap();
                let want = bits(&scalar);
                for (baseline, unbatched) in [(true, false), (false, true), (false, false)] {
                    let c = curvature_pass(m, &opts, true, baseline, unbatched).unwrap();
                    assert!(
                        bits(&c) == want,
                        "mesh {k} ring {} baseline {baseline} unbatched {unbatched}",
                        opts.ring
                    );
                }
                refused += scalar.jet_fallbacks + scalar.undetermined;
            }
        }
        // the collapsed patch and the awkward mesh exercise the refused lanes
        assert!(refused > 0);
    }

    /// `surface_curvature_scalars` is the full pass without its vector outputs: every scalar
    /// output and status the same bits, on every mesh and fit (the vertex results reach the
    /// same slots whether or not the vector slices are there).
    #[test]
    fn scalar_outputs_are_bitwise_the_full_pass() {
        let mut meshes = lane_meshes();
        // more than one parallel chunk, with boundaries
        meshes.push(generate::disk(40, 90));
        for (k, m) in meshes.iter().enumerate() {
            for opts in [
                SurfaceOptions::default(),
                SurfaceOptions::estimated_normals(),
                SurfaceOptions::jet_normals_paraboloid(),
                SurfaceOptions {
                    fit: SurfaceFit::Quadric,
                    ring: 2,
                    ..SurfaceOptions::default()
                },
            ] {
                let full = surface_curvature(m, &opts).unwrap();
                let some = surface_curvature_scalars(m, &opts).unwrap();
                assert!(some.dir1.is_empty() && some.dir2.is_empty() && some.normals.is_empty());
                let want = SurfaceCurvature {
                    dir1: Vec::new(),
                    dir2: Vec::new(),
                    normals: Vec::new(),
                    ..full
                };
                assert!(bits(&some) == bits(&want), "mesh {k} {opts:?}");
            }
        }
    }

    #[test]
    fn per_vertex_normals_are_bitwise_vertex_normals() {
        // the awkward mesh's zero-area triangles, and one whose cross product overflows (no
        // direction either): `vertex_normals` skips both kinds, `weighted_crosses` stores −0
        let mut m = awkward_mesh();
        let n = m.positions.len() as u32;
        m.positions.push(Point3::new(1e200, 0.0, 0.0));
        m.positions.push(Point3::new(0.0, -1e200, 3.0));
        m.triangles.push([5, n, n + 1]);
        m.triangles.push([7, 7, n]);
        let adj = Adjacency::new(&m);
        for w in [
            NormalWeighting::Area,
            NormalWeighting::Uniform,
            NormalWeighting::InverseArea,
        ] {
            let all = vertex_normals(&m, w);
            let crosses = weighted_crosses(&m, w);
            for (v, n) in all.iter().enumerate() {
                let one = vertex_normal_from(&crosses, adj.triangles(v));
                for k in 0..3 {
                    assert_eq!(one[k].to_bits(), n[k].to_bits(), "{v} {w:?}");
                }
            }
        }
    }
}

//! The 3D boundary (Veltkamp 1992, §5.3–§5.7): [`boundary_3d`] constricts the 3D
//! Delaunay tetrahedralization (V §5.3, [`constrict`]) to a closed genus-0 triangle mesh through
//! (ideally) every point; when that constriction locks with points inside, the general engine
//! ([`general`], [`removal`]) continues with γ(\[-1,1\],\[c,1\]) triangles, c = −0.1 … −1, added
//! where needed (V §5.4, [`augment`]) — first on the live tetrahedra within four neighbour steps
//! of the vertices off the boundary, on the whole object when that does not free every vertex
//! (after c = −1 the vertices still off are put on it through a boundary face that sees them,
//! [`insert`]);
//! keep triangles (V §5.7, [`keep`]) that are not Delaunay faces are constricted by the general
//! engine from the hull. The engine state of one run and its final checks are in [`engine`].

mod augment;
pub(crate) mod constrict;
mod crosstree;
mod engine;
pub(crate) mod general;
mod insert;
mod keep;
mod removal;
mod support;
#[cfg(test)]
mod test_sets;
mod trigrid;

use super::BoundaryError;
use super::CParam;
use crate::boundary::indicator::Key;

/// The result type of the boundary constructions.
type Result<T> = std::result::Result<T, BoundaryError>;
pub use constrict::Until;
use engine::Engine3;

/// The 3D boundary method and its parameters (one variant per method; each carries only the
/// parameters it uses).
#[derive(Debug, Clone, PartialEq)]
pub enum Method3 {
    /// γ-indicator constriction of the Delaunay tetrahedralization (V §5.3), with the §5.4
    /// fallback when `c` is [`CParam::Auto`]: when the constriction locks with points off the
    /// boundary, the general engine continues, adding the triangles of γ(\[-1,1\],\[c,1\]) for
    /// c = −0.1, −0.2, …, −1 at the vertices off the boundary, inside the current object
    /// (adaptive augmentation). [`CParam::Fixed`]`(c)` constricts γ(\[-1,1\],\[c,1\]) from the
    /// convex hull (c = 0: the Delaunay constriction alone; c < 0: the whole graph up to 400
    /// points, a pruned one above).
    Gamma {
        /// The γ-graph parameter (see [`CParam`]).
        c: CParam,
        /// When the Delaunay constriction stops.
        until: Until,
        /// Triangles (input indices) that must be on the boundary (V §5.7). When every keep
        /// triangle is a Delaunay face the Delaunay constriction keeps them; otherwise the
        /// general engine constricts the Delaunay triangles plus the keep triangles from the
        /// convex hull, with V's rewiring. Keep triangles not on the result are listed in
        /// [`Boundary3::keep_missing`].
        keep: Vec<[u32; 3]>,
    },
    /// Boissonnat's minimal area change (V §4.3.3, Eq. 4.1) as the selection key of the
    /// Delaunay constriction; the general engine (the [`CParam::Auto`] continuation after a
    /// lock, [`CParam::Fixed`]`(c < 0)`, keep triangles that are not Delaunay faces) always
    /// uses the γ-indicator. Parameters as for [`Method3::Gamma`].
    MinAreaChange {
        /// The γ-graph parameter (see [`CParam`]).
        c: CParam,
        /// When the Delaunay constriction stops.
        until: Until,
        /// Triangles (input indices) that must be on the boundary (V §5.7).
        keep: Vec<[u32; 3]>,
    },
    /// The shortest Voronoi skeleton of Delaunay tetrahedra (V §4.3.4, §5.6).
    VoronoiSkeleton {
        /// Seed tetrahedra tried (all tetrahedra when there are fewer; at least 1 is used).
        max_seeds: usize,
    },
}

impl Method3 {
    /// The name used by the CLI and in reports: `gamma`, `min-area-change` or
    /// `voronoi-skeleton`.
    pub fn name(&self) -> &'static str {
        match self {
            Method3::Gamma { .. } => "gamma",
            Method3::MinAreaChange { .. } => "min-area-change",
            Method3::VoronoiSkeleton { .. } => "voronoi-skeleton",
        }
    }
}

/// Options of [`boundary_3d`]: the method with its parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Options3 {
    /// The method and its parameters.
    pub method: Method3,
}

impl Options3 {
    /// γ-indicator constriction with `c = auto`, the given stop rule and no keep triangles.
    pub fn gamma(until: Until) -> Self {
        Options3 {
            method: Method3::Gamma {
                c: CParam::Auto,
                until,
                keep: Vec::new(),
            },
        }
    }

    /// The shortest Voronoi skeleton from up to `max_seeds` seed tetrahedra.
    ///
    /// ```rust
    /// use morpho::boundary::{boundary_3d, Options3};
    /// use morpho::geom::Point3;
    /// let p = [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 4.0], [1.0, 1.0, 0.9]]
    ///     .map(|[x, y, z]| Point3::new(x, y, z));
    /// let o = Options3::voronoi_skeleton(10);
    /// assert_eq!(o.method.name(), "voronoi-skeleton");
    /// let b = boundary_3d(&p, &o).unwrap();
    /// assert!(b.skeleton_length.is_some() && b.closed_manifold);
    /// ```
    pub fn voronoi_skeleton(max_seeds: usize) -> Self {
        Options3 {
            method: Method3::VoronoiSkeleton { max_seeds },
        }
    }
}

impl Default for Options3 {
    /// [`Options3::gamma`]`(`[`Until::All`]`)`.
    fn default() -> Self {
        Options3::gamma(Until::All)
    }
}

/// A 3D boundary (all indices are input indices).
#[derive(Debug, Clone)]
pub struct Boundary3 {
    /// Boundary triangles, oriented outward.
    pub triangles: Vec<[u32; 3]>,
    /// Every input point is a vertex of the boundary.
    pub all_on_boundary: bool,
    /// Input points not on the boundary.
    pub left_out: Vec<u32>,
    /// Deleted tetrahedra (Delaunay and general engine together; skeleton: tetrahedra added).
    pub iterations: usize,
    /// The c of the last graph γ(\[-1,1\],\[c,1\]) used (0 = Delaunay).
    pub c_used: f64,
    /// Triangles of γ(\[-1,1\],\[c,1\]), c < 0, added by the general engine.
    pub added_triangles: usize,
    /// The boundary is a closed 2-manifold (checked by `mesh::topology::analyze`).
    pub closed_manifold: bool,
    /// Its genus (`None` when not an orientable manifold).
    pub genus: Option<i64>,
    /// Pairs of boundary triangles that intersect although they must not (exact test,
    /// [`crate::mesh::validity::self_intersections_trusting`], every pair except two faces of the
    /// Delaunay tetrahedralization, which meet only in common faces; at most 10 listed).
    /// Empty for a valid boundary.
    pub intersections: Vec<(u32, u32)>,
    /// The interior tetrahedralization (empty when the general engine ran: its implicit
    /// tetrahedra are not kept as a tiling — the engine deletes conservatively, so its
    /// remaining triangles need not bound a set of interior-disjoint tetrahedra; the volume is
    /// then taken from the surface).
    pub interior: Vec<[u32; 4]>,
    /// Keep triangles (input indices) that are not boundary triangles.
    pub keep_missing: Vec<[u32; 3]>,
    /// Enclosed volume.
    pub volume: f64,
    /// Length of the Voronoi skeleton (skeleton method only).
    pub skeleton_length: Option<f64>,
}

/// Constructs a closed boundary mesh through 3D points (see the module documentation and
/// [`Method3`]). Errors when the points are coplanar or fewer than four, when a keep triangle
/// is out of range, degenerate, or intersects another, and for c outside [−1, 0].
///
/// The points are first multiplied by the power of two that brings the largest coordinate
/// magnitude near 1 (exact): the constriction keys and
/// the engines' floating-point filters would otherwise over- or underflow at extreme absolute
/// scales, and the result would depend on the units. The volume and the skeleton length are
/// reported in input units.
///
/// A tetrahedron with a point inside: the closed surface through all five points.
/// ```rust
/// use morpho::boundary::{boundary_3d, Options3, Until};
/// use morpho::geom::Point3;
/// let p = [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 4.0], [1.0, 1.0, 0.9]]
///     .map(|[x, y, z]| Point3::new(x, y, z));
/// let b = boundary_3d(&p, &Options3::gamma(Until::All)).unwrap();
/// assert!(b.all_on_boundary && b.closed_manifold && b.intersections.is_empty());
/// assert_eq!((b.triangles.len(), b.genus), (6, Some(0)));
/// assert!(b.volume > 0.0);
/// ```
///
/// Coplanar points have no closed surface:
/// ```rust
/// use morpho::boundary::{boundary_3d, BoundaryError, Options3};
/// use morpho::geom::Point3;
/// let flat: Vec<Point3> = (0..6).map(|i| Point3::new(i as f64, (i * i) as f64, 0.0)).collect();
/// let e = boundary_3d(&flat, &Options3::default()).unwrap_err();
/// assert!(matches!(e, BoundaryError::NoSurface { .. }));
/// assert!(e.to_string().starts_with("boundary: no closed surface exists"));
/// ```
pub fn boundary_3d(points: &[crate::geom::Point3], opts: &Options3) -> Result<Boundary3> {
    let m = points
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let s = crate::geom::exact::power_of_two_scale(m);
    if s != 1.0 {
        let scaled: Vec<crate::geom::Point3> = points.iter().map(|p| p * s).collect();
        let mut b = boundary_3d_unit(&scaled, opts)?;
        b.volume = b.volume / s / s / s;
        if let Some(l) = &mut b.skeleton_length {
            *l /= s;
        }
        return Ok(b);
    }
    boundary_3d_unit(points, opts)
}

/// [`boundary_3d`] on points whose largest coordinate magnitude is near 1: the steps of
/// [`Engine3`] in order.
fn boundary_3d_unit(points: &[crate::geom::Point3], opts: &Options3) -> Result<Boundary3> {
    let mut e = Engine3::new(points)?;
    let (key, c, until, keep) = match &opts.method {
        Method3::Gamma { c, until, keep } => (Key::Gamma, c, until, keep),
        Method3::MinAreaChange { c, until, keep } => (Key::MinAreaChange, c, until, keep),
        Method3::VoronoiSkeleton { max_seeds } => return Ok(e.finish(e.skeleton(*max_seeds))),
    };
    let fixed_c = super::d2::check_c(*c)?;
    e.set_keep(keep)?;
    let outcome = match fixed_c {
        Some(c) if c < 0.0 => e.gamma_from_hull(c),
        _ if e.non_delaunay_keep() => e.keep_from_hull(fixed_c),
        _ => e.delaunay_constriction(key, *until, fixed_c.is_none()),
    };
    Ok(e.finish(outcome))
}

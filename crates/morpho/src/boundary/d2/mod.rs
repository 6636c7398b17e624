//! The 2D boundary (Veltkamp 1992, §5.2–§5.7): [`boundary_2d`] and its engine state
//! [`Engine2`], one object that owns every step from the points to the polygon:
//! 1. [`Engine2::new`]: the Delaunay triangulation of the (scaled) points, refused when it has
//!    no triangle (fewer than three distinct points, or all collinear);
//! 2. [`Engine2::set_keep`]: the keep edges checked and mapped to vertices (V §5.7, [`keep`]);
//! 3. one constriction: [`Engine2::skeleton`] (V §4.3.4), [`Engine2::delaunay_constriction`]
//!    (V §5.2, Algorithm 5.1, [`constrict::constrict_dt`]; continued by adaptive augmentation
//!    when it locks, V §5.4, [`augment`]) or [`Engine2::general_from_hull`] (γ(\[-1,1\],\[c,1\])
//!    with c < 0 or keep edges, the general engine [`constrict::General`]);
//! 4. [`Engine2::finish`]: the polygon, the points left out, the interior, the area and the
//!    missing keep edges in input indices.

pub mod augment;
pub mod constrict;
pub mod keep;

use super::voronoi_skeleton;
use super::BoundaryError;
use super::{CParam, Key};
use crate::delaunay::d2::{triangulate, Delaunay2};
use crate::geom::Point2;
use crate::graphs::fast::{beyond_dt_2d, candidates_2d, coords2};

/// The result type of the boundary constructions.
type Result<T> = std::result::Result<T, BoundaryError>;
use constrict::{constrict_dt, region_cycle, General};

/// The 2D boundary method and its parameters (one variant per method; each carries only the
/// parameters it uses).
#[derive(Debug, Clone, PartialEq)]
pub enum Method2 {
    /// γ-indicator constriction of γ(\[-1,1\],\[0,1\]) (V §5.2, Algorithm 5.1), with the
    /// Hamiltonicity fallback of §5.4 when `c` is [`CParam::Auto`] and the keep edges of §5.7.
    Gamma {
        /// The γ-graph parameter (see [`CParam`]).
        c: CParam,
        /// Edges (input indices) that must be on the boundary (V §5.7).
        keep: Vec<[u32; 2]>,
    },
    /// Boissonnat's minimal area change constriction of the Delaunay triangulation (V §4.3.3,
    /// Eq. 4.1); [`CParam::Fixed`]`(c < 0)` constricts γ(\[-1,1\],\[c,1\]) with that key, and
    /// [`CParam::Auto`] means c = 0 (the fallback belongs to the γ-indicator).
    MinAreaChange {
        /// The γ-graph parameter (see [`CParam`]).
        c: CParam,
        /// Edges (input indices) that must be on the boundary (V §5.7).
        keep: Vec<[u32; 2]>,
    },
    /// O'Rourke et al.'s shortest Voronoi skeleton (V §4.3.4).
    VoronoiSkeleton {
        /// Seed triangles tried (all triangles when there are fewer; at least 1 is used).
        max_seeds: usize,
    },
}

impl Method2 {
    /// The name used by the CLI and in reports: `gamma`, `min-area-change` or
    /// `voronoi-skeleton`.
    ///
    /// ```rust
    /// use morpho::boundary::Method2;
    /// assert_eq!(Method2::VoronoiSkeleton { max_seeds: 5 }.name(), "voronoi-skeleton");
    /// ```
    pub fn name(&self) -> &'static str {
        match self {
            Method2::Gamma { .. } => "gamma",
            Method2::MinAreaChange { .. } => "min-area-change",
            Method2::VoronoiSkeleton { .. } => "voronoi-skeleton",
        }
    }
}

/// Options of [`boundary_2d`]: the method with its parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Options2 {
    /// The method and its parameters.
    pub method: Method2,
}

impl Options2 {
    /// γ-indicator constriction with `c = auto` and no keep edges (the default).
    ///
    /// ```rust
    /// use morpho::boundary::{Method2, Options2};
    /// assert_eq!(Options2::gamma(), Options2::default());
    /// assert_eq!(Options2::gamma().method.name(), "gamma");
    /// assert!(matches!(Options2::min_area_change().method, Method2::MinAreaChange { .. }));
    /// ```
    pub fn gamma() -> Self {
        Options2 {
            method: Method2::Gamma {
                c: CParam::Auto,
                keep: Vec::new(),
            },
        }
    }

    /// Minimal area change constriction (c = 0, no keep edges).
    pub fn min_area_change() -> Self {
        Options2 {
            method: Method2::MinAreaChange {
                c: CParam::Auto,
                keep: Vec::new(),
            },
        }
    }

    /// The shortest Voronoi skeleton from up to `max_seeds` seed triangles.
    ///
    /// ```rust
    /// use morpho::boundary::{boundary_2d, Options2};
    /// use morpho::geom::Point2;
    /// let ring: Vec<Point2> = (0..12)
    ///     .map(|k| {
    ///         let t = k as f64 / 12.0 * std::f64::consts::TAU;
    ///         Point2::new(t.cos(), t.sin())
    ///     })
    ///     .collect();
    /// let b = boundary_2d(&ring, &Options2::voronoi_skeleton(10)).unwrap();
    /// assert!(b.all_on_boundary && b.skeleton_length.unwrap() > 0.0);
    /// ```
    pub fn voronoi_skeleton(max_seeds: usize) -> Self {
        Options2 {
            method: Method2::VoronoiSkeleton { max_seeds },
        }
    }
}

impl Default for Options2 {
    /// [`Options2::gamma`].
    fn default() -> Self {
        Options2::gamma()
    }
}

/// A 2D boundary and how it was found. All indices are input indices.
#[derive(Debug, Clone)]
pub struct Boundary2 {
    /// The simple polygon, counter-clockwise.
    pub polygon: Vec<u32>,
    /// Every input point is on the polygon.
    pub all_on_boundary: bool,
    /// Input points not on the polygon.
    pub left_out: Vec<u32>,
    /// The c of the last graph γ(\[-1,1\],\[c,1\]) used (0 = Delaunay).
    pub c_used: f64,
    /// Number of deletions (γ, min-area) or triangle additions (skeleton).
    pub iterations: usize,
    /// The Delaunay edges the construction started from.
    pub graph_edges: Vec<[u32; 2]>,
    /// The edges deleted during constriction, in order.
    pub deleted: Vec<[u32; 2]>,
    /// A triangulation of the interior.
    pub interior: Vec<[u32; 3]>,
    /// Area enclosed by the polygon.
    pub area: f64,
    /// Keep edges that did not end on the boundary.
    pub keep_missing: Vec<[u32; 2]>,
    /// Length of the Voronoi skeleton (skeleton method only).
    pub skeleton_length: Option<f64>,
}

/// Constructs a boundary polygon through the points (see the module documentation).
///
/// The points are first multiplied by the power of two that brings the largest coordinate
/// magnitude near 1 (exact), so that the result does not
/// depend on the units: the γ-indicators, the minimal-area-change keys and the skeleton
/// lengths are floating-point values that over- or underflow at extreme absolute scales. The
/// area and the skeleton length are reported in input units.
///
/// Errors ([`BoundaryError`]): a non-finite coordinate, fewer than three distinct points or
/// all collinear, a keep edge out of range, joining two copies of a point, through another
/// point or crossing another keep edge, c outside [−1, 0]. Expected O(N log N) for the
/// Delaunay constriction; the fallback adds the γ-graph edges at the vertices off the
/// boundary.
///
/// A square with its centre: the centre is brought onto the boundary.
/// ```rust
/// use morpho::boundary::{boundary_2d, check_polygon, Options2};
/// use morpho::geom::Point2;
/// let p = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0), (1.0, 1.1)]
///     .map(|(x, y)| Point2::new(x, y));
/// let b = boundary_2d(&p, &Options2::default()).unwrap();
/// assert!(b.all_on_boundary);
/// assert_eq!(b.polygon.len(), 5);
/// assert!(check_polygon(&p, &b.polygon).simple && b.area > 0.0);
/// ```
///
/// Refusals name the offending input:
/// ```rust
/// use morpho::boundary::{boundary_2d, BoundaryError, CParam, Method2, Options2};
/// use morpho::geom::Point2;
/// let line: Vec<Point2> = (0..5).map(|i| Point2::new(i as f64, 0.0)).collect();
/// let e = boundary_2d(&line, &Options2::default()).unwrap_err();
/// assert!(matches!(e, BoundaryError::NoPolygon));
///
/// let p = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let keep = Options2 { method: Method2::Gamma { c: CParam::Auto, keep: vec![[0, 7]] } };
/// let e = boundary_2d(&p, &keep).unwrap_err();
/// assert!(matches!(e, BoundaryError::KeepEdgeOutOfRange { index: 0, edge: [0, 7], points: 3 }));
/// assert_eq!(
///     e.to_string(),
///     "boundary: keep edge (0, 7) refers to a point that does not exist (3 points)"
/// );
/// ```
pub fn boundary_2d(points: &[Point2], opts: &Options2) -> Result<Boundary2> {
    if let Some(index) = points
        .iter()
        .position(|p| !p.x.is_finite() || !p.y.is_finite())
    {
        return Err(BoundaryError::NonFinite { index });
    }
    let m = points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let s = crate::geom::exact::power_of_two_scale(m);
    if s != 1.0 {
        let scaled: Vec<Point2> = points.iter().map(|p| p * s).collect();
        let mut b = boundary_2d_unit(&scaled, opts)?;
        b.area = b.area / s / s;
        if let Some(l) = &mut b.skeleton_length {
            *l /= s;
        }
        return Ok(b);
    }
    boundary_2d_unit(points, opts)
}

/// [`boundary_2d`] on finite points whose largest coordinate magnitude is near 1: the steps of
/// [`Engine2`] in order.
fn boundary_2d_unit(points: &[Point2], opts: &Options2) -> Result<Boundary2> {
    let mut e = Engine2::new(points)?;
    let (key, c, keep) = match &opts.method {
        Method2::Gamma { c, keep } => (Key::Gamma, c, keep),
        Method2::MinAreaChange { c, keep } => (Key::MinAreaChange, c, keep),
        Method2::VoronoiSkeleton { max_seeds } => return Ok(e.skeleton(*max_seeds)),
    };
    e.set_keep(keep)?;
    let fixed_c = check_c(*c)?;
    // the Hamiltonicity fallback (V §5.4) belongs to the γ-indicator
    let fallback = key == Key::Gamma;
    let outcome = if e.keep.is_empty() && fixed_c.map_or(true, |c| c == 0.0) {
        e.delaunay_constriction(key, fallback && fixed_c.is_none())
    } else {
        e.general_from_hull(key, fixed_c, fallback)
    };
    Ok(e.finish(outcome))
}

/// `Some(c)` for [`CParam::Fixed`]`(c)` with c in [−1, 0], `None` for [`CParam::Auto`]; an
/// error for any other c.
pub(super) fn check_c(c: CParam) -> Result<Option<f64>> {
    match c {
        CParam::Auto => Ok(None),
        CParam::Fixed(c) if (-1.0..=0.0).contains(&c) => Ok(Some(c)),
        CParam::Fixed(c) => Err(BoundaryError::COutOfRange { c }),
    }
}

/// What a constriction step produced, before [`Engine2::finish`] (vertex indices).
pub(super) struct Outcome2 {
    /// The boundary cycle, counter-clockwise.
    pub(super) cycle: Vec<u32>,
    /// A triangulation of the interior.
    pub(super) interior: Vec<[u32; 3]>,
    pub(super) c_used: f64,
    pub(super) iterations: usize,
    /// The deleted edges in order.
    pub(super) deleted: Vec<[u32; 2]>,
    pub(super) skeleton_length: Option<f64>,
}

/// The state of one [`boundary_2d`] run (see the module documentation).
pub(super) struct Engine2 {
    pub(super) d: Delaunay2,
    /// The vertices' coordinates.
    pub(super) p: Vec<[f64; 2]>,
    /// The keep edges in vertex indices.
    pub(super) keep: Vec<[u32; 2]>,
}

impl Engine2 {
    /// Step 1: the Delaunay triangulation; an error when it has no triangle.
    pub(super) fn new(points: &[Point2]) -> Result<Self> {
        let d = triangulate(points).map_err(BoundaryError::from)?;
        if d.collinear || d.triangles.is_empty() {
            return Err(BoundaryError::NoPolygon);
        }
        let p = coords2(&d);
        Ok(Engine2 {
            d,
            p,
            keep: Vec::new(),
        })
    }

    /// Step 2: the keep edges (input indices), checked ([`keep::keep_vertices`]).
    pub(super) fn set_keep(&mut self, keep: &[[u32; 2]]) -> Result<()> {
        self.keep = keep::keep_vertices(&self.d, &self.p, keep)?;
        Ok(())
    }

    /// Step 3, the shortest Voronoi skeleton (V §4.3.4), finished.
    pub(super) fn skeleton(&self, max_seeds: usize) -> Boundary2 {
        let sk = voronoi_skeleton::shortest_skeleton(&self.d, max_seeds);
        self.finish(Outcome2 {
            cycle: region_cycle(&self.d, &sk.alive),
            interior: alive_triangles(&self.d, &sk.alive),
            c_used: 0.0,
            iterations: sk.iterations,
            deleted: Vec::new(),
            skeleton_length: Some(sk.length),
        })
    }

    /// Step 3, the Delaunay constriction (V §5.2, Algorithm 5.1) with `key`; when it locks and
    /// `augment`, continued in the general engine by adaptive augmentation
    /// ([`Engine2::augment_after_lock`], V §5.4).
    pub(super) fn delaunay_constriction(&self, key: Key, augment: bool) -> Outcome2 {
        let st = constrict_dt(&self.d, &self.p, key);
        if st.boundary_vertices == self.d.points.len() || !augment {
            return Outcome2 {
                cycle: region_cycle(&self.d, &st.alive),
                interior: alive_triangles(&self.d, &st.alive),
                c_used: 0.0,
                iterations: st.iterations,
                deleted: st.deleted,
                skeleton_length: None,
            };
        }
        self.augment_after_lock(key, st)
    }

    /// Step 3, the general engine from the convex hull: γ(\[-1,1\],\[c,1\]) for `fixed_c` (the
    /// Delaunay graph plus its cocircular chords when `None` or 0) with the keep edges (V §5.7);
    /// when it locks with `fixed_c` `None` and `fallback`, adaptive augmentation (V §5.4).
    pub(super) fn general_from_hull(
        &self,
        key: Key,
        fixed_c: Option<f64>,
        fallback: bool,
    ) -> Outcome2 {
        let d = &self.d;
        let cand = candidates_2d(d);
        let mut edges = cand.edges.clone();
        let c0 = fixed_c.unwrap_or(0.0);
        if c0 < 0.0 {
            edges.extend(beyond_dt_2d(d, &cand, c0).0);
        }
        let mut g = General::new(&self.p, key, &d.hull, edges, &self.keep);
        g.run();
        let c = if fixed_c.is_none() && fallback && g.boundary_vertices < d.points.len() {
            augment::augment_until_done(d, &mut g, 0.0, true)
        } else {
            c0
        };
        let cycle = g.cycle();
        Outcome2 {
            interior: triangulate_polygon(&self.p, &cycle),
            cycle,
            c_used: c,
            iterations: g.iterations,
            deleted: g.deleted.clone(),
            skeleton_length: None,
        }
    }

    /// Step 4: the result in input indices: the polygon, the points left out, the interior,
    /// the area (shoelace formula), the Delaunay edges and the keep edges not on the polygon.
    pub(super) fn finish(&self, o: Outcome2) -> Boundary2 {
        let d = &self.d;
        let cyc = o.cycle;
        let mut on = vec![false; d.points.len()];
        for &v in &cyc {
            on[v as usize] = true;
        }
        let m = cyc.len();
        let mut area2 = 0.0;
        for k in 0..m {
            let (a, b) = (self.p[cyc[k] as usize], self.p[cyc[(k + 1) % m] as usize]);
            area2 += a[0] * b[1] - a[1] * b[0];
        }
        let inp = |v: u32| d.input_of_vertex[v as usize];
        let left_out: Vec<u32> = (0..d.vertex_of_input.len())
            .filter(|&i| !on[d.vertex_of_input[i] as usize])
            .map(|i| i as u32)
            .collect();
        Boundary2 {
            polygon: cyc.iter().map(|&v| inp(v)).collect(),
            all_on_boundary: left_out.is_empty(),
            left_out,
            c_used: o.c_used,
            iterations: o.iterations,
            graph_edges: d.edges().iter().map(|e| [inp(e[0]), inp(e[1])]).collect(),
            deleted: o.deleted.iter().map(|e| [inp(e[0]), inp(e[1])]).collect(),
            interior: o
                .interior
                .iter()
                .map(|t| [inp(t[0]), inp(t[1]), inp(t[2])])
                .collect(),
            area: 0.5 * area2,
            keep_missing: keep::keep_missing(&cyc, &self.keep)
                .iter()
                .map(|e| [inp(e[0]), inp(e[1])])
                .collect(),
            skeleton_length: o.skeleton_length,
        }
    }
}

/// The live triangles of a Delaunay triangulation.
fn alive_triangles(d: &Delaunay2, alive: &[bool]) -> Vec<[u32; 3]> {
    d.triangles
        .iter()
        .zip(alive)
        .filter(|(_, &a)| a)
        .map(|(t, _)| *t)
        .collect()
}

/// The intermediate boundaries of the Delaunay γ-constriction (V Fig. 5.2 style "steps"): for
/// each `k` in `steps`, the counter-clockwise polygon (input indices) after `k` deletions
/// (clamped to the number of deletions made). Points as for [`boundary_2d`].
///
/// Step 0 is the convex hull:
/// ```rust
/// use morpho::boundary::{constriction_steps_2d, Key};
/// use morpho::geom::Point2;
/// let p = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0), (1.0, 1.1)]
///     .map(|(x, y)| Point2::new(x, y));
/// let steps = constriction_steps_2d(&p, Key::Gamma, &[0, 1]).unwrap();
/// assert_eq!(steps[0].len(), 4);
/// assert_eq!(steps[1].len(), 5);
/// ```
pub fn constriction_steps_2d(
    points: &[Point2],
    key: Key,
    steps: &[usize],
) -> Result<Vec<Vec<u32>>> {
    let Engine2 { d, p, .. } = Engine2::new(points)?;
    let st = constrict_dt(&d, &p, key);
    let mut out = Vec::with_capacity(steps.len());
    for &k in steps {
        let mut alive = vec![true; d.triangles.len()];
        for &t in st.removed.iter().take(k) {
            alive[t as usize] = false;
        }
        let cyc = region_cycle(&d, &alive);
        out.push(cyc.iter().map(|&v| d.input_of_vertex[v as usize]).collect());
    }
    Ok(out)
}

/// Triangulation of the interior of a simple polygon `cyc` (indices into `p`, either
/// orientation): the constrained Delaunay triangulation of its vertices restricted to the
/// inside ([`crate::delaunay::cdt::triangulate_polygon_interior`]), `cyc.len() − 2`
/// counter-clockwise triangles, for any size (no vertex limit). Empty when `cyc` is not a
/// simple polygon ([`crate::mesh::validity::check_polygon`] reports that case).
///
/// ```rust
/// use morpho::boundary::triangulate_polygon;
/// let p = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// assert_eq!(triangulate_polygon(&p, &[0, 1, 2, 3]).len(), 2);
/// assert!(triangulate_polygon(&p, &[0, 2, 1, 3]).is_empty()); // a bow tie
/// ```
pub fn triangulate_polygon(p: &[[f64; 2]], cyc: &[u32]) -> Vec<[u32; 3]> {
    let pts: Vec<Point2> = p.iter().map(|q| Point2::new(q[0], q[1])).collect();
    crate::delaunay::cdt::triangulate_polygon_interior(&pts, cyc).unwrap_or_default()
}

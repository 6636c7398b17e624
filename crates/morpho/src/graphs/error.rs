//! Why a graph construction refused its input: [`GraphError`].

use crate::delaunay::DelaunayError;

/// A refusal of the graph family, naming the offending parameter or input.
///
/// `Display` is the one-line message the CLI prints after `error:`; the crate error
/// [`crate::Error::Graph`] adds the file name. A refusal of the underlying triangulation is
/// [`GraphError::Delaunay`].
///
/// ```rust
/// use morpho::graphs::{graph_2d, GraphError, Kind};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)];
/// let e = graph_2d(&p, Kind::BetaLune(2.0)).unwrap_err();
/// assert!(matches!(e, GraphError::ParameterOutOfRange { name: "b", .. }));
/// assert_eq!(e.to_string(), "b must lie in [-1, 1], got 2");
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GraphError {
    /// A β or γ parameter outside [−1, 1].
    #[error("{name} must lie in [-1, 1], got {value}")]
    ParameterOutOfRange {
        /// The parameter's name (`b`, `c0` … `c3`).
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The α parameter is NaN or infinite.
    #[error("alpha parameter must be finite")]
    AlphaNotFinite {
        /// The value given.
        value: f64,
    },
    /// γ(c₀, c₁) with |c₀| > |c₁|.
    #[error("γ(c0, c1) needs |c0| ≤ |c1| (got {c0}, {c1})")]
    GammaOrder {
        /// c₀ as given.
        c0: f64,
        /// c₁ as given.
        c1: f64,
    },
    /// γ([c₀, c₁], [c₂, c₃]) with c₀ > c₁ or c₂ > c₃.
    #[error("γ ranges must be [c0 ≤ c1], [c2 ≤ c3]")]
    GammaRangeOrder {
        /// The four parameters as given.
        range: [f64; 4],
    },
    /// The coordinates span more binary magnitudes than the exact graph predicates handle.
    #[error(
        "coordinates span too many magnitudes (largest {largest:e}) for exact graph predicates"
    )]
    ScaleRange {
        /// The largest coordinate magnitude.
        largest: f64,
    },
    /// α overflows once the points are rescaled to the safe range.
    #[error("alpha parameter {value} is out of range at the scale of these points")]
    AlphaOutOfScale {
        /// The value given.
        value: f64,
    },
    /// 3D degenerate (coplanar or collinear) input is handled by brute force, up to `limit`
    /// points.
    #[error(
        "3D graph of degenerate input ({why}) with more than {limit} points; use the 2D graph"
    )]
    DegenerateTooLarge {
        /// Why the input is degenerate (from [`crate::delaunay::Delaunay3::degenerate`]).
        why: String,
        /// Number of distinct points.
        points: usize,
        /// The limit.
        limit: usize,
    },
    /// A 3D γ-graph with a parameter −1 (nearly every triple) on more than `limit` points.
    #[error(
        "3D γ-graphs with a parameter −1 contain nearly every triple of points (the brute force of V Thm 3.1); limited to {limit} points"
    )]
    GammaMinusOneTooLarge {
        /// Number of distinct points.
        points: usize,
        /// The limit.
        limit: usize,
    },
    /// A 3D γ-graph beyond the tetrahedralization (a parameter c < 0) whose enumeration would
    /// test more candidate triples than the limit ([`crate::graphs::triple_limit`]).
    #[error(
        "3D γ-graphs with a parameter c = {c} < 0 test the triples of every 'open' vertex (near the hull or on a sampled surface: Θ(N³), V Lemma 3.4); these {points} points ({open} open) need at least {triples} candidate triples, above the limit of {limit} (raise it with --max-triples or MORPHO_TRIPLE_LIMIT; about 2·10⁻⁷ s each on one core)"
    )]
    TooManyTriples {
        /// The parameter c.
        c: f64,
        /// Number of distinct points.
        points: usize,
        /// Of them, the open vertices.
        open: usize,
        /// The candidate triples the enumeration would test (C(open, 3) when it is refused
        /// before its partner searches: a lower bound).
        triples: u64,
        /// The limit.
        limit: u64,
    },
    /// A 3D γ-graph beyond the tetrahedralization (a parameter c < 0) whose triple loop added
    /// more points to the triples' intervals than the limit ([`crate::graphs::triple_limit`]):
    /// (nearly) cospherical input, where every candidate is decided by a scan of every point.
    #[error(
        "3D γ-graphs with a parameter c = {c} < 0 decide each candidate triple by the points around it; on these {points} points ({triples} candidate triples, nearly cospherical: every triple sees every point) the search added more than {limit} points to the triples' intervals and was stopped after {added} (Θ(N⁴) on points of a sphere; raise the limit with --max-triples or MORPHO_TRIPLE_LIMIT)"
    )]
    TooMuchWork {
        /// The parameter c.
        c: f64,
        /// Number of distinct points.
        points: usize,
        /// The candidate triples counted before the loop.
        triples: u64,
        /// The points added when the search was stopped.
        added: u64,
        /// The limit.
        limit: u64,
    },
    /// A 3D α-shape with a > 0 on more than `limit` hull vertices.
    #[error("3D α-shapes with a > 0 are limited to {limit} hull vertices (got {hull_vertices})")]
    AlphaHullTooLarge {
        /// Number of hull vertices.
        hull_vertices: usize,
        /// The limit.
        limit: usize,
    },
    /// A kind that is defined in 2D only (circle-based β, lune-based β with b < 0) asked in 3D.
    #[error("{}", only_2d(kind, *degenerate))]
    Only2d {
        /// The kind's CLI name ([`crate::graphs::Kind::name`]).
        kind: &'static str,
        /// Its parameter b.
        b: f64,
        /// True when the input was degenerate (the brute-force path refused it).
        degenerate: bool,
    },
    /// [`crate::graphs::Kind`] is not one of the distance graphs (internal dispatch).
    #[error("{kind} is not a distance graph")]
    NotDistanceGraph {
        /// The kind's CLI name.
        kind: &'static str,
    },
    /// The triangulation refused the points.
    #[error(transparent)]
    Delaunay(#[from] DelaunayError),
}

fn only_2d(kind: &str, degenerate: bool) -> &'static str {
    if degenerate {
        "β-skeletons with b < 0 and circle-based β are defined in 2D only"
    } else if kind == "beta-circle" {
        "the circle-based β-skeleton is defined in 2D only (V §2.2.11)"
    } else {
        "the lune-based β-skeleton with b < 0 is defined in 2D only (V §2.2.11)"
    }
}

impl GraphError {
    /// True for refusals of the input (all but an internal error of the triangulation).
    pub fn is_input_error(&self) -> bool {
        match self {
            GraphError::Delaunay(e) => e.is_input_error(),
            _ => true,
        }
    }
}

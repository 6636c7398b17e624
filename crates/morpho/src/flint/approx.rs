//! Approximations read off a flintstone tree: level ℓ, adaptive to an error bound ε, and to a
//! target edge count (Veltkamp 1992, §7.2.2–7.2.3; reading notes A.4–A.5).
//!
//! - **Level ℓ**: the vertices of tree levels 0..=ℓ (≤ 2^{ℓ+1} edges).
//! - **Adaptive ε**: an approximating edge is refined only if **its own** flintstone error
//!   `max{w_1, w_2}` exceeds ε (V 7.2.3); the result is a subtree of the full tree.
//! - **Count N**: the edge of largest flintstone error is refined first (a heap) until the
//!   approximation has N edges or is complete.
//!
//! Every result reports e1–e5 ([`Criteria`]) and, for polygons, whether it is simple by the
//! exact test of [`crate::mesh::validity::check_polygon`]: V notes that early levels need not
//! be simple, and a non-simple result is returned as it is, flagged, not hidden.
//! Cost: O(output) to select the vertices, plus O(N log N) for the criteria.

use super::criteria::{approximation_criteria, Criteria};
use super::tree2::FlintTree2;
use super::FlintError;
use crate::geom::Point2;
use crate::mesh::validity::check_polygon;
use crate::util::NONE;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// How coarse an approximation should be.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// All vertices of tree levels 0..=ℓ.
    Level(u32),
    /// Refine every edge whose flintstone error exceeds ε (≥ 0, finite).
    Error(f64),
    /// Refine the worst edge first until this many edges (≥ 1).
    Count(usize),
}

/// An approximation by input vertices, in input order.
#[derive(Debug, Clone, PartialEq)]
pub struct Approximation {
    /// Input indices of the kept vertices, increasing along the polygon from the root chord's
    /// first end (so a polygon's list may wrap past index N − 1 to 0).
    pub vertices: Vec<usize>,
    /// Closed (polygon) or open (polyline).
    pub closed: bool,
    /// e1–e5 of the approximation.
    pub errors: Criteria,
    /// For polygons: the exact simplicity of the result (`None` for polylines).
    pub simple: Option<bool>,
}

impl Approximation {
    /// Number of edges.
    pub fn edges(&self) -> usize {
        if self.closed {
            self.vertices.len()
        } else {
            self.vertices.len().saturating_sub(1)
        }
    }
}

/// A node in the refinement heap of the approximations (2D and 3D): by error, ties by the
/// smaller node id.
pub(super) struct ByError(pub(super) f64, pub(super) u32);
impl PartialEq for ByError {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for ByError {}
impl PartialOrd for ByError {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for ByError {
    fn cmp(&self, o: &Self) -> Ordering {
        // larger error first; ties: smaller node id first
        self.0.total_cmp(&o.0).then(o.1.cmp(&self.1))
    }
}

impl FlintTree2 {
    /// The positions (unwrapped, increasing) of the approximation `target`.
    pub(crate) fn select(&self, target: Target) -> Result<Vec<usize>, FlintError> {
        let mut pos = vec![self.root.chord[0], self.root.chord[1]];
        let tops = self.root.children.iter().copied().filter(|&c| c != NONE);
        match target {
            Target::Level(l) => {
                pos.extend(
                    self.nodes
                        .iter()
                        .filter(|nd| nd.level <= l)
                        .map(|nd| nd.vertex),
                );
            }
            Target::Error(eps) => {
                if !(eps.is_finite() && eps >= 0.0) {
                    return Err(FlintError::BadTarget(format!("error bound {eps}")));
                }
                let mut stack: Vec<u32> = tops.collect();
                while let Some(id) = stack.pop() {
                    let nd = &self.nodes[id as usize];
                    if nd.stone.error() > eps {
                        pos.push(nd.vertex);
                        stack.extend(nd.children.iter().copied().filter(|&c| c != NONE));
                    }
                }
            }
            Target::Count(want) => {
                if want == 0 {
                    return Err(FlintError::BadTarget("edge count 0".into()));
                }
                let mut heap: BinaryHeap<ByError> = tops
                    .map(|c| ByError(self.nodes[c as usize].stone.error(), c))
                    .collect();
                let edges = |k: usize| if self.closed { k } else { k - 1 };
                while edges(pos.len()) < want {
                    let Some(ByError(_, id)) = heap.pop() else {
                        break;
                    };
                    let nd = &self.nodes[id as usize];
                    pos.push(nd.vertex);
                    for &c in nd.children.iter().filter(|&&c| c != NONE) {
                        heap.push(ByError(self.nodes[c as usize].stone.error(), c));
                    }
                }
            }
        }
        pos.sort_unstable();
        Ok(pos)
    }

    /// The approximation for `target`, with its e1–e5 and (polygons) exact simplicity.
    ///
    /// ```
    /// use morpho::flint::{FlintTree2, Target};
    /// use morpho::geom::Point2;
    /// let p: Vec<Point2> = (0..64)
    ///     .map(|k| { let a = k as f64 * std::f64::consts::TAU / 64.0; Point2::new(a.cos(), a.sin()) })
    ///     .collect();
    /// let t = FlintTree2::new(&p, true).unwrap();
    /// let a = t.approximate(Target::Level(2)).unwrap();
    /// assert!(a.edges() <= 8 && a.simple == Some(true));
    /// // e2 ≤ e1 and e2 ≤ e5, up to rounding (distances are constructed in f64)
    /// assert!(a.errors.e2 <= a.errors.e1 + 1e-12 && a.errors.e2 <= a.errors.e5 + 1e-12);
    /// ```
    pub fn approximate(&self, target: Target) -> Result<Approximation, FlintError> {
        let pos = self.select(target)?;
        Ok(self.approximation_of(pos))
    }

    /// Wraps increasing positions into an [`Approximation`] (criteria, simplicity).
    pub(crate) fn approximation_of(&self, pos: Vec<usize>) -> Approximation {
        make_approximation(&self.points, pos, self.closed)
    }
}

/// Wraps increasing positions of `points` into an [`Approximation`] (criteria, simplicity).
pub(crate) fn make_approximation(
    points: &[[f64; 2]],
    pos: Vec<usize>,
    closed: bool,
) -> Approximation {
    let errors = approximation_criteria(points, &pos, closed);
    let n = points.len();
    let vertices: Vec<usize> = pos.iter().map(|&p| p % n).collect();
    let simple = closed.then(|| {
        let pts: Vec<Point2> = vertices
            .iter()
            .map(|&v| Point2::new(points[v][0], points[v][1]))
            .collect();
        let cycle: Vec<u32> = (0..pts.len() as u32).collect();
        pts.len() >= 3 && check_polygon(&pts, &cycle).simple
    });
    Approximation {
        vertices,
        closed,
        errors,
        simple,
    }
}

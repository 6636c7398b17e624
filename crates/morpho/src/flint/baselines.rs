//! The baseline hierarchies of Veltkamp 1992, §6.3 (reading notes A.9), built on the same
//! data and read through the same criteria ([`super::Criteria`]) and approximation targets
//! ([`super::Target`]) as the flintstone tree:
//!
//! - **Douglas–Peucker / iterative end-point fit** (Duda–Hart 73, Douglas–Peucker 73): split
//!   at the vertex farthest from the *segment* (the one that determines e1), refine while
//!   e1 > tolerance;
//! - **strip tree** (Ballard 81): the same split vertex, refine while the strip error e3 >
//!   tolerance ("e1 to choose, e3 to stop");
//! - **BLG tree** (van Oosterom–van den Bos 89): the same split vertex; a node keeps the
//!   distance of its vertex to the segment and is refined while it exceeds the tolerance;
//! - **arc tree** (Günther 88, polygon form): split `v_i…v_{i+n}` at `v_{i+⌈n/2⌉}`; each arc
//!   lies in the ellipse with foci at its end points and major axis its length `l`, whose
//!   semi-minor axis `sqrt(l² − c²)/2` (`c` the chord) bounds e1; refine while it exceeds the
//!   tolerance.
//!
//! For a closed polygon the initial end points are those of the flintstone root (the two
//! smallest-bounding-disc support points farthest apart; the notes' choice for comparability).
//! Every baseline builds its full binary hierarchy (N − 1 nodes; IEPF Θ(N log N) best, O(N²)
//! worst, as here) and reads the approximation off it exactly as [`super::FlintTree2`] does:
//! tree levels, refinement while the node's own key exceeds ε, or worst key first to a count.
//! Ties in "farthest" go to the first vertex along the polyline.

use super::approx::{make_approximation, Approximation, Target};
use super::criteria::{dist_to_segment, edge_criteria};
use super::disc::at;
use super::tree2::root_of;
use super::FlintError;
use crate::geom::vec::dist;
use crate::geom::Point2;
use std::collections::BinaryHeap;

/// Which baseline hierarchy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Baseline {
    /// Iterative end-point fit (Douglas–Peucker).
    DouglasPeucker,
    /// Ballard's strip tree.
    Strip,
    /// The BLG tree.
    Blg,
    /// Günther's (polygon) arc tree.
    Arc,
}

struct Hnode {
    lo: usize,
    hi: usize,
    split: usize,
    key: f64,
    level: u32,
}

/// The split vertex and key of the polyline `lo..=hi` (`hi ≥ lo + 2`).
pub(crate) fn split_key(p: &[[f64; 2]], lo: usize, hi: usize, m: Baseline) -> (usize, f64) {
    let (a, b) = (at(p, lo), at(p, hi));
    if m == Baseline::Arc {
        let q = lo + (hi - lo).div_ceil(2);
        let l: f64 = (lo..hi).map(|k| dist(at(p, k), at(p, k + 1))).sum();
        let c = dist(a, b);
        return (q, ((l * l - c * c).max(0.0)).sqrt() / 2.0);
    }
    let (mut q, mut far) = (lo + 1, -1.0);
    for k in lo + 1..hi {
        let d = dist_to_segment(a, b, at(p, k));
        if d > far {
            (q, far) = (k, d);
        }
    }
    let key = if m == Baseline::Strip {
        edge_criteria(p, lo, hi).e3
    } else {
        far
    };
    (q, key)
}

/// The approximation of `points` (a polygon when `closed`) by baseline `method` for `target`.
///
/// ```
/// use morpho::flint::{baseline, Baseline, Target};
/// use morpho::geom::Point2;
/// let p: Vec<Point2> = (0..50).map(|k| Point2::new(k as f64, ((k * k) % 7) as f64 * 0.1)).collect();
/// let a = baseline(&p, false, Baseline::DouglasPeucker, Target::Error(0.25)).unwrap();
/// assert!(a.errors.e1 <= 0.25);
/// ```
pub fn baseline(
    points: &[Point2],
    closed: bool,
    method: Baseline,
    target: Target,
) -> Result<Approximation, FlintError> {
    // the flintstone tree's input checks and root chord (not the tree itself)
    let (flat, _, [i, j]) = root_of(points, closed)?;
    let p = &flat[..];
    let n = p.len();
    let mut spans = vec![(i, j)];
    if closed {
        spans.push((j, i + n));
    }
    // full hierarchy, children implicit by (lo, hi) pairs
    let mut nodes: Vec<Hnode> = Vec::with_capacity(n);
    let mut tops = Vec::new();
    let mut stack: Vec<(usize, usize, u32)> = spans.iter().map(|&(a, b)| (a, b, 1)).collect();
    while let Some((lo, hi, level)) = stack.pop() {
        if hi < lo + 2 {
            continue;
        }
        let (split, key) = split_key(p, lo, hi, method);
        if level == 1 {
            tops.push(nodes.len());
        }
        nodes.push(Hnode {
            lo,
            hi,
            split,
            key,
            level,
        });
        stack.push((lo, split, level + 1));
        stack.push((split, hi, level + 1));
    }
    let by_span: std::collections::HashMap<(usize, usize), usize> = nodes
        .iter()
        .enumerate()
        .map(|(k, h)| ((h.lo, h.hi), k))
        .collect();
    let kids = |h: &Hnode| {
        [(h.lo, h.split), (h.split, h.hi)]
            .into_iter()
            .filter_map(|s| by_span.get(&s).copied())
            .collect::<Vec<usize>>()
    };
    let mut pos = vec![i, j];
    match target {
        Target::Level(l) => pos.extend(nodes.iter().filter(|h| h.level <= l).map(|h| h.split)),
        Target::Error(eps) => {
            if !(eps.is_finite() && eps >= 0.0) {
                return Err(FlintError::BadTarget(format!("error bound {eps}")));
            }
            let mut st = tops.clone();
            while let Some(k) = st.pop() {
                if nodes[k].key > eps {
                    pos.push(nodes[k].split);
                    st.extend(kids(&nodes[k]));
                }
            }
        }
        Target::Count(want) => {
            if want == 0 {
                return Err(FlintError::BadTarget("edge count 0".into()));
            }
            let key = |k: usize| (ordered(nodes[k].key), std::cmp::Reverse(k));
            let mut heap: BinaryHeap<_> = tops.iter().map(|&k| key(k)).collect();
            let edges = |m: usize| if closed { m } else { m - 1 };
            while edges(pos.len()) < want {
                let Some((_, std::cmp::Reverse(k))) = heap.pop() else {
                    break;
                };
                pos.push(nodes[k].split);
                heap.extend(kids(&nodes[k]).into_iter().map(key));
            }
        }
    }
    pos.sort_unstable();
    Ok(make_approximation(p, pos, closed))
}

/// A total order on f64 keys for the heap.
fn ordered(x: f64) -> u64 {
    let b = x.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | (1 << 63)
    }
}

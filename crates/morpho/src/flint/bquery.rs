//! Point-in-polygon through the baseline hierarchies (Veltkamp 1992, §6.3 and §7.4; reading
//! notes A.8–A.9), by the same walk as the flintstone tree, so that the nodes visited per
//! query can be compared on equal terms.
//!
//! Every baseline node covers the polyline `lo..=hi` by a convex region that also contains
//! its chord; at a node whose region does not contain X, the chord stands in for the polyline
//! in the crossing parity (Lemma 6.1), otherwise the node is opened; leaves are the original
//! edges, tested exactly (the same `crosses`/`on_edge` as the flintstone walk). The regions:
//!
//! - **Douglas–Peucker / BLG tree**: the capsule of points within `d` of the chord, `d` the
//!   distance of the split vertex to the segment — the largest over the polyline, i.e. the key
//!   the BLG tree stores (so the two trees answer queries identically);
//! - **strip tree**: Ballard's strip, the rectangle along the chord that covers every vertex;
//! - **arc tree**: Günther's ellipse with foci at the chord ends and major axis the arc length.
//!
//! The regions are constructed in `f64`; "X outside" is decided with a relative slack of
//! 1e-9 on the region's size and coordinates, so rounding can only open a node that need not be
//! opened (slower, never wrong): every final answer is exact. The root is the flintstone
//! tree's (same chord, same smallest bounding disc) for every method.

use super::baselines::{split_key, Baseline};
use super::criteria::dist_to_segment;
use super::disc::at;
use super::query::{crosses, on_edge, Containment};
use super::tree2::FlintTree2;
use super::FlintError;
use crate::geom::vec::{dist, dot, perp, scale, sub};
use crate::geom::Point2;
use crate::util::NONE;

/// A convex region covering a node's polyline and chord.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Region {
    /// Points within `r` of the segment `a b`.
    Capsule { r: f64 },
    /// `s ∈ [s0, s1]`, `h ∈ [h0, h1]` in the frame of the chord (`u` along, `n` across).
    Strip { s: [f64; 2], h: [f64; 2] },
    /// `|X − a| + |X − b| ≤ l`.
    Ellipse { l: f64 },
}

#[derive(Debug, Clone, PartialEq)]
struct Bnode {
    split: usize,
    region: Region,
    children: [u32; 2],
}

/// A baseline hierarchy of a closed polygon, prepared for point queries.
#[derive(Debug, Clone, PartialEq)]
pub struct BaselineTree {
    tree: FlintTree2,
    method: Baseline,
    nodes: Vec<Bnode>,
    tops: [u32; 2],
}

fn region(p: &[[f64; 2]], lo: usize, hi: usize, m: Baseline) -> Region {
    let (a, b) = (at(p, lo), at(p, hi));
    match m {
        Baseline::DouglasPeucker | Baseline::Blg => Region::Capsule {
            r: (lo + 1..hi)
                .map(|k| dist_to_segment(a, b, at(p, k)))
                .fold(0.0, f64::max),
        },
        Baseline::Strip => {
            let l = dist(a, b);
            let u = scale(sub(b, a), 1.0 / l);
            let nrm = perp(u);
            let (mut s, mut h) = ([0.0, l], [0.0f64, 0.0f64]);
            for k in lo + 1..hi {
                let d = sub(at(p, k), a);
                let (x, y) = (dot(d, u), dot(d, nrm));
                s = [s[0].min(x), s[1].max(x)];
                h = [h[0].min(y), h[1].max(y)];
            }
            Region::Strip { s, h }
        }
        Baseline::Arc => Region::Ellipse {
            l: (lo..hi).map(|k| dist(at(p, k), at(p, k + 1))).sum(),
        },
    }
}

/// Is `x` surely outside the region of the polyline with chord `a b`?
fn surely_outside(reg: &Region, a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
    let size = dist(a, b) + a[0].abs() + a[1].abs() + x[0].abs() + x[1].abs();
    match *reg {
        Region::Capsule { r } => dist_to_segment(a, b, x) > r + 1e-9 * (r + size),
        Region::Strip { s, h } => {
            let l = dist(a, b);
            let u = scale(sub(b, a), 1.0 / l);
            let nrm = perp(u);
            let d = sub(x, a);
            let (xs, xh) = (dot(d, u), dot(d, nrm));
            let sl = 1e-9 * (size + (s[1] - s[0]) + (h[1] - h[0]));
            xs < s[0] - sl || xs > s[1] + sl || xh < h[0] - sl || xh > h[1] + sl
        }
        Region::Ellipse { l } => dist(x, a) + dist(x, b) > l + 1e-9 * (l + size),
    }
}

impl BaselineTree {
    /// Builds the full hierarchy of `method` over a simple polygon (the flintstone tree's
    /// input checks and root chord).
    ///
    /// ```
    /// use morpho::flint::{Baseline, BaselineTree, Containment};
    /// use morpho::geom::Point2;
    /// let sq = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)].map(|(x, y)| Point2::new(x, y));
    /// let t = BaselineTree::new(&sq, Baseline::Strip).unwrap();
    /// assert_eq!(t.locate_counted(Point2::new(1.0, 1.0)).unwrap().0, Containment::Inside);
    /// ```
    pub fn new(points: &[Point2], method: Baseline) -> Result<BaselineTree, FlintError> {
        let tree = FlintTree2::new(points, true)?;
        let p = tree.points();
        let n = p.len();
        let [i, j] = tree.root.chord;
        let mut nodes: Vec<Bnode> = Vec::with_capacity(n);
        let mut tops = [NONE; 2];
        // (lo, hi, parent, slot); parent NONE: a top, slot = which
        let mut stack = vec![(i, j, NONE, 0usize), (j, i + n, NONE, 1)];
        while let Some((lo, hi, parent, slot)) = stack.pop() {
            if hi < lo + 2 {
                continue;
            }
            let (split, _) = split_key(p, lo, hi, method);
            let id = nodes.len() as u32;
            nodes.push(Bnode {
                split,
                region: region(p, lo, hi, method),
                children: [NONE; 2],
            });
            if parent == NONE {
                tops[slot] = id;
            } else {
                nodes[parent as usize].children[slot] = id;
            }
            stack.push((lo, split, id, 0));
            stack.push((split, hi, id, 1));
        }
        Ok(BaselineTree {
            tree,
            method,
            nodes,
            tops,
        })
    }

    /// The hierarchy.
    pub fn method(&self) -> Baseline {
        self.method
    }

    /// Where `x` is relative to the polygon, and the number of pieces (nodes and leaf edges)
    /// the walk examined.
    pub fn locate_counted(&self, x: Point2) -> Result<(Containment, usize), FlintError> {
        if !(x.x.is_finite() && x.y.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        let x = [x.x, x.y];
        let r = &self.tree.root;
        let slack = 1e-12 * (r.radius + r.center[0].abs() + r.center[1].abs());
        if dist(x, r.center) > r.radius + slack {
            return Ok((Containment::Outside, 0));
        }
        let p = self.tree.points();
        let n = p.len();
        let [i, j] = r.chord;
        let mut stack = vec![(i, j, self.tops[0]), (j, i + n, self.tops[1])];
        let (mut inside, mut visits) = (false, 0);
        while let Some((lo, hi, id)) = stack.pop() {
            visits += 1;
            let (a, b) = (at(p, lo), at(p, hi));
            if id == NONE {
                if on_edge(a, b, x) {
                    return Ok((Containment::Boundary, visits));
                }
                inside ^= crosses(a, b, x);
                continue;
            }
            let nd = &self.nodes[id as usize];
            if surely_outside(&nd.region, a, b, x) {
                inside ^= crosses(a, b, x);
                continue;
            }
            stack.push((nd.split, hi, nd.children[1]));
            stack.push((lo, nd.split, nd.children[0]));
        }
        let c = if inside {
            Containment::Inside
        } else {
            Containment::Outside
        };
        Ok((c, visits))
    }
}

//! The 2D flintstone tree of a simple polygon or an open polyline (Veltkamp 1992, §7.2.2,
//! Alg. 7.1; paper §4.1; reading notes A.4).
//!
//! The root holds the chord `v_i v_j` of the two smallest-bounding-disc support points farthest
//! apart (existing Welzl, [`crate::geom::smallest_enclosing_disc`]; for a polyline: its two end
//! points) and the disc. Every polyline `v_p … v_s` with `p + 1 < s` gets a node: its flintstone
//! ([`Flintstone`]) and the split vertex of Alg. 7.1 (cap vertex, else larger signed radius; the
//! middle position when all interior vertices lie on the chord). Its children are the nodes
//! of `v_p … v_q` and `v_q … v_s` (none for an edge). So the tree has exactly N − 1 nodes
//! (root + one per other vertex) and an in-order traversal gives the polygon order.
//! The recursion is breadth-agnostic (an explicit stack), so depth never overflows.
//!
//! Levels: the root is level 0, its children level 1, …; the level-ℓ approximation has at most
//! `2^{ℓ+1}` edges. Build: Θ(N log N) best, O(N²) worst (Thm 7.1); storage Θ(N) (Thm 7.2).
//! Input checks: ≥ 3 vertices, finite coordinates, and for a polygon the exact simplicity test
//! of [`crate::mesh::validity::check_polygon`] (near-duplicate points are accepted; points that
//! really coincide or edges that really meet are refused, naming their vertex indices).

use super::disc::Flintstone;
use super::FlintError;
use crate::geom::{smallest_enclosing_disc, Point2};
use crate::mesh::validity::{check_polygon, remove_spikes, SpikeRepair};
use crate::util::NONE;

/// One node of the tree below the root: the polyline between positions `stone.lo` and
/// `stone.hi`, split at `vertex`.
#[derive(Debug, Clone, PartialEq)]
pub struct FlintNode {
    /// Position of the split vertex (its input index is `vertex % n`).
    pub vertex: usize,
    /// The flintstone of the polyline `lo..=hi`.
    pub stone: Flintstone,
    /// Nodes of `lo..=vertex` and `vertex..=hi` ([`NONE`] for an edge).
    pub children: [u32; 2],
    /// Tree level (root children: 1).
    pub level: u32,
}

/// The root: chord, smallest bounding disc, and the nodes of its one or two polylines.
#[derive(Debug, Clone, PartialEq)]
pub struct FlintRoot {
    /// Positions of the chord ends (`i < j`).
    pub chord: [usize; 2],
    /// Centre of the smallest bounding disc.
    pub center: [f64; 2],
    /// Radius of the smallest bounding disc.
    pub radius: f64,
    /// Node of `i..=j` and (polygons) of `j..=i+N`; [`NONE`] where that polyline is one edge or
    /// absent.
    pub children: [u32; 2],
}

/// A 2D flintstone tree (Alg. 7.1) with its input.
#[derive(Debug, Clone, PartialEq)]
pub struct FlintTree2 {
    pub(crate) points: Vec<[f64; 2]>,
    pub(crate) closed: bool,
    /// The root.
    pub root: FlintRoot,
    /// All nodes below the root.
    pub nodes: Vec<FlintNode>,
    /// The query layout (closed polygons; empty for polylines).
    pub(crate) flat: super::locate::Flat,
}

/// Checks finiteness and count; for polygons, exact simplicity.
fn check_input(points: &[Point2], closed: bool) -> Result<Vec<[f64; 2]>, FlintError> {
    if points.len() < 3 {
        return Err(FlintError::TooFewVertices { n: points.len() });
    }
    if let Some(index) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(FlintError::NonFinite { index });
    }
    let flat: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
    if closed {
        let cycle: Vec<u32> = (0..points.len() as u32).collect();
        let c = check_polygon(points, &cycle);
        if !c.simple {
            let (i, j) = c.conflict.unwrap_or((0, 0));
            let repeated = flat[i] == flat[j];
            return Err(FlintError::NotSimple {
                first: i,
                second: j,
                repeated,
                n: points.len(),
            });
        }
    }
    Ok(flat)
}

impl FlintTree2 {
    /// Builds the tree of a simple polygon (`closed`, the last vertex joins the first) or an
    /// open polyline.
    ///
    /// ```
    /// use morpho::flint::FlintTree2;
    /// use morpho::geom::Point2;
    /// let sq = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.1), (2.0, 2.0), (0.0, 2.0)].map(|(x, y)| Point2::new(x, y));
    /// let t = FlintTree2::new(&sq, true).unwrap();
    /// assert_eq!(t.node_count(), 4); // N − 1
    /// assert_eq!(t.in_order(), vec![0, 1, 2, 3, 4]);
    /// ```
    pub fn new(points: &[Point2], closed: bool) -> Result<FlintTree2, FlintError> {
        let flat = check_input(points, closed)?;
        let n = flat.len();
        let disc = smallest_enclosing_disc(points).map_err(|_| FlintError::AllCoincident)?;
        if disc.support.len() < 2 {
            return Err(FlintError::AllCoincident);
        }
        let chord = if closed {
            root_pair(&flat, &disc.support).ok_or(FlintError::AllCoincident)?
        } else {
            if flat[0] == flat[n - 1] {
                return Err(FlintError::NotSimple {
                    first: 0,
                    second: n - 1,
                    repeated: true,
                    n,
                });
            }
            [0, n - 1]
        };
        let mut t = FlintTree2 {
            points: flat,
            closed,
            root: FlintRoot {
                chord,
                center: [disc.center.x, disc.center.y],
                radius: disc.radius,
                children: [NONE, NONE],
            },
            nodes: Vec::with_capacity(n),
            flat: Default::default(),
        };
        t.root.children[0] = t.build(chord[0], chord[1]);
        if closed {
            t.root.children[1] = t.build(chord[1], chord[0] + n);
            t.flat = super::locate::Flat::new(&t);
        }
        Ok(t)
    }

    /// Builds the tree of the closed ring `points` after removing its zero-area spikes and
    /// repeated consecutive vertices ([`remove_spikes`]: exact, area unchanged). The tree's
    /// vertices (and every index it reports) are those of the repaired ring: vertex `k` is input
    /// vertex `repair.kept[k]`. A ring that is still not simple is refused with its edges named
    /// by input indices ([`FlintError::NotSimpleAfterRepair`]).
    ///
    /// ```
    /// use morpho::flint::{Containment, FlintTree2};
    /// use morpho::geom::Point2;
    /// // a square with a spike up from its top edge at (1, 2)
    /// let p = [(0., 0.), (2., 0.), (2., 2.), (1., 2.), (1., 3.), (1., 2.), (0., 2.)]
    ///     .map(|(x, y)| Point2::new(x, y));
    /// assert!(FlintTree2::new(&p, true).is_err());
    /// let (t, r) = FlintTree2::new_repaired(&p).unwrap();
    /// assert_eq!(r.removed, vec![4, 5]);
    /// assert_eq!(t.len(), 5);
    /// assert_eq!(t.contains(Point2::new(1.0, 1.0)).unwrap(), Containment::Inside);
    /// ```
    pub fn new_repaired(points: &[Point2]) -> Result<(FlintTree2, SpikeRepair), FlintError> {
        if let Some(index) = points
            .iter()
            .position(|p| !(p.x.is_finite() && p.y.is_finite()))
        {
            return Err(FlintError::NonFinite { index });
        }
        let repair = remove_spikes(points);
        let kept: Vec<Point2> = repair.kept.iter().map(|&i| points[i]).collect();
        FlintTree2::new(&kept, true)
            .map(|t| (t, repair.clone()))
            .map_err(|e| e.after_repair(&repair))
    }

    /// Builds the subtree of the polyline `lo..=hi`; returns its node id or [`NONE`].
    fn build(&mut self, lo: usize, hi: usize) -> u32 {
        if hi < lo + 2 {
            return NONE;
        }
        // (lo, hi, parent, child slot, level); parent NONE = the subtree's own root
        let mut stack = vec![(lo, hi, NONE, 0usize, 1u32)];
        let mut top = NONE;
        while let Some((lo, hi, parent, slot, level)) = stack.pop() {
            let stone = Flintstone::of(&self.points, lo, hi);
            let vertex = stone.split().unwrap_or((lo + hi) / 2);
            let id = self.nodes.len() as u32;
            self.nodes.push(FlintNode {
                vertex,
                stone,
                children: [NONE, NONE],
                level,
            });
            if parent == NONE {
                top = id;
            } else {
                self.nodes[parent as usize].children[slot] = id;
            }
            if hi >= vertex + 2 {
                stack.push((vertex, hi, id, 1, level + 1));
            }
            if vertex >= lo + 2 {
                stack.push((lo, vertex, id, 0, level + 1));
            }
        }
        top
    }

    /// Number of input vertices.
    pub fn len(&self) -> usize {
        self.points.len()
    }
    /// Never true (a tree has ≥ 3 vertices); for clippy's `len` convention.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
    /// True for a polygon, false for an open polyline.
    pub fn is_closed(&self) -> bool {
        self.closed
    }
    /// The input vertices.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }
    /// Nodes including the root (N − 1, Thm 7.2).
    pub fn node_count(&self) -> usize {
        self.nodes.len() + 1
    }
    /// The largest node level (root: 0).
    pub fn depth(&self) -> u32 {
        self.nodes.iter().map(|n| n.level).max().unwrap_or(0)
    }

    /// Vertex input indices in in-order: the root's first chord end, the first subtree, the
    /// second chord end, the second subtree (= polygon order starting at `v_i`).
    pub fn in_order(&self) -> Vec<usize> {
        let n = self.len();
        let mut out = vec![self.root.chord[0] % n];
        self.in_order_of(self.root.children[0], &mut out);
        out.push(self.root.chord[1] % n);
        if self.closed {
            self.in_order_of(self.root.children[1], &mut out);
        }
        out
    }

    fn in_order_of(&self, id: u32, out: &mut Vec<usize>) {
        // explicit stack: (node, visited-left)
        let mut stack = vec![(id, false)];
        while let Some((id, left_done)) = stack.pop() {
            if id == NONE {
                continue;
            }
            let nd = &self.nodes[id as usize];
            if left_done {
                out.push(nd.vertex % self.len());
                stack.push((nd.children[1], false));
            } else {
                stack.push((id, true));
                stack.push((nd.children[0], false));
            }
        }
    }

    /// Count of nodes by kind `[cap, intersection, segment, union, unbounded]`.
    pub fn kind_counts(&self) -> [usize; 5] {
        use super::disc::StoneKind::*;
        let mut c = [0; 5];
        for nd in &self.nodes {
            c[match nd.stone.kind {
                Cap => 0,
                Intersection => 1,
                Segment => 2,
                Union => 3,
                Unbounded => 4,
            }] += 1;
        }
        c
    }
}

/// The two support points farthest apart, in increasing order.
fn root_pair(p: &[[f64; 2]], support: &[usize]) -> Option<[usize; 2]> {
    let mut best: Option<(f64, usize, usize)> = None;
    for (k, &a) in support.iter().enumerate() {
        for &b in &support[k + 1..] {
            let d = crate::geom::vec::dist2(p[a], p[b]);
            if p[a] != p[b] && best.map_or(true, |(bd, _, _)| d > bd) {
                best = Some((d, a.min(b), a.max(b)));
            }
        }
    }
    best.map(|(_, a, b)| [a, b])
}

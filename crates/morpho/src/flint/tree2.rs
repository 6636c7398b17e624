//! The 2D flintstone tree of a simple polygon or an open polyline (Veltkamp 1992, §7.2.2,
//! Alg. 7.1; paper §4.1; reading notes A.4).
//!
//! The root holds the chord `v_i v_j` of the two smallest-bounding-disc support points farthest
//! apart (existing Welzl, [`crate::geom::smallest_enclosing_disc`]; for a polyline: its two end
//! points) and the disc. Every polyline `v_p … v_s` with `p + 1 < s` gets a node: its flintstone
//! ([`Flintstone`]) and the split vertex of Alg. 7.1 (cap vertex, else larger signed radius; the
//! middle position when all interior vertices lie on the chord), within the depth budget
//! below. Its children are the nodes
//! of `v_p … v_q` and `v_q … v_s` (none for an edge). So the tree has exactly N − 1 nodes
//! (root + one per other vertex) and an in-order traversal gives the polygon order.
//! The recursion is breadth-agnostic (an explicit stack), so depth never overflows.
//!
//! Levels: the root is level 0, its children level 1, …; the level-ℓ approximation has at most
//! `2^{ℓ+1}` edges. Storage Θ(N) (Thm 7.2).
//!
//! **Deviation from Alg. 7.1 (V §7.2.2): a depth budget.** Alg. 7.1's build is Θ(N log N) best,
//! O(N²) worst (Thm 7.1), and ordinary dense data reach the worst case: on a densely sampled
//! smooth or slightly rough curve the widest side disc belongs to a vertex next to a chord end
//! (the key `(x−a)·(x−b) / 2|(b−a)×(x−a)|` is largest where the product of the distances to
//! the ends is smallest), each split cuts off a few vertices, the depth grows like N and the
//! build like Σ subtree sizes (a 10⁶-vertex rough star: 71 s, depth in the thousands; a circle
//! of 10⁷ vertices would run for hours). [`FlintTree2::new`] therefore takes Alg. 7.1's vertex
//! only while both parts stay within a per-level cap: `N` edges for the first `⌈log₂ N⌉`
//! levels, then `max(⌈c/2⌉, ⌊3c/4⌋)` of the level above. Otherwise it splits at the vertex
//! farthest from the chord line among the positions whose two parts both fit the cap (the
//! middle half of the polyline once the cap has shrunk to `3k/4`; Douglas–Peucker's rule on
//! that window). A node within its cap can always be split so (`⌈k/2⌉` fits), so the depth is
//! at most `⌈log₂ N⌉ + log_{4/3} N + 2` (≈ 3.4 log₂ N) and the build O(N log N) on every
//! input. Nothing else changes: the flintstone of a node depends only on its chord ends, so
//! exactly N − 1 nodes, in-order = polygon order, every vertex of a node's polyline in its
//! flintstone and the discs through their defining vertices hold as before; only which vertex
//! splits a node differs, and only where Alg. 7.1's would break the budget (on the project's
//! Benelux 1:50m border never; on the Great Britain coast 1:10m at 38 of 3 695 nodes, depth
//! 57 → 37; on the 10⁶-vertex upsampled coast and rough star at 10 % and 6 % of the nodes).
//! On (nearly) cocircular input, such as an exact circle, the in-circle tests of a visit fall
//! through the floating-point filter; they are settled by the integer stage of
//! [`crate::geom::predicates::incircle_sign`] (and so is the smallest enclosing disc's Welzl),
//! so such input costs about what generic input does (`bench/README.md`, "the exact circle").
//! What it costs in
//! approximation quality (e1–e5 at equal edge counts) is measured in `bench/README.md`
//! ("Flintstone tree build: the depth budget"). [`FlintTree2::new_alg71`] builds the thesis's
//! tree without the budget (its figures, the notes' A.6 numbers).
//! Input checks: ≥ 3 vertices, finite coordinates, and for a polygon the exact simplicity test
//! of [`crate::mesh::validity::check_polygon`] (near-duplicate points are accepted; points that
//! really coincide or edges that really meet are refused, naming their vertex indices).

use super::disc::{at, small_coordinates, Flintstone};
use super::FlintError;
use crate::geom::vec::dist2;
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
/// What [`root_of`] gives: the points as arrays, the smallest enclosing disc, the root chord.
pub(crate) type Root = (Vec<[f64; 2]>, crate::geom::EnclosingDisc, [usize; 2]);

/// The input checks of [`FlintTree2::new`] and its root: the points as arrays, the smallest
/// enclosing disc and the root chord (a closed polygon: the pair of the disc's support points
/// chosen by `root_pair`; a polyline: its ends). Shared with the baselines, which need the same
/// checks and chord but not the tree.
pub(crate) fn root_of(points: &[Point2], closed: bool) -> Result<Root, FlintError> {
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
    Ok((flat, disc, chord))
}

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
        FlintTree2::with_rule(points, closed, true)
    }

    /// [`FlintTree2::new`] with Alg. 7.1's split vertex at every node (no depth budget): the
    /// thesis's tree, for reproducing its figures and the notes' A.6 numbers. Its build is
    /// O(N²) in the worst case (Thm 7.1), and dense smooth curves reach it (see the module
    /// doc): not for untrusted or large input.
    ///
    /// ```
    /// use morpho::flint::FlintTree2;
    /// use morpho::geom::Point2;
    /// let sq = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.1), (2.0, 2.0), (0.0, 2.0)].map(|(x, y)| Point2::new(x, y));
    /// assert_eq!(FlintTree2::new_alg71(&sq, true).unwrap(), FlintTree2::new(&sq, true).unwrap());
    /// ```
    pub fn new_alg71(points: &[Point2], closed: bool) -> Result<FlintTree2, FlintError> {
        FlintTree2::with_rule(points, closed, false)
    }

    fn with_rule(points: &[Point2], closed: bool, budget: bool) -> Result<FlintTree2, FlintError> {
        let (flat, disc, chord) = root_of(points, closed)?;
        let n = flat.len();
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
        t.root.children[0] = t.build(chord[0], chord[1], budget);
        if closed {
            t.root.children[1] = t.build(chord[1], chord[0] + n, budget);
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
    ///
    /// One scan per node ([`Flintstone::scan`]): a node's side-disc reaches (the largest
    /// vertex distance from each side centre, [`super::disc::SideDisc::reach`]) are not a pass
    /// of their own but gathered by its children's scans, which visit exactly the interior
    /// vertices of its two parts, plus the three vertices no child scan visits (the chord ends
    /// and the split vertex; a part without a child node is one edge, with no interior). A
    /// maximum does not depend on the order, so every node equals [`Flintstone::of_windowed`]'s
    /// (lockstep test `fused_build_equals_the_per_node_passes`).
    fn build(&mut self, lo: usize, hi: usize, budget: bool) -> u32 {
        if hi < lo + 2 {
            return NONE;
        }
        // without the budget: N at every level (Alg. 7.1's vertex always taken)
        let caps = if budget {
            level_caps(self.points.len())
        } else {
            Vec::new()
        };
        // the quadratic in-circle filter's precondition, once for the whole tree
        let quad = small_coordinates(&self.points);
        let first = self.nodes.len();
        // squared reaches gathered so far, per node of this subtree (`id − first`)
        let mut reach2: Vec<[f64; 2]> = Vec::with_capacity(self.points.len().min(hi - lo));
        // (lo, hi, parent, child slot, level); parent NONE = the subtree's own root
        let mut stack = vec![(lo, hi, NONE, 0usize, 1u32)];
        let mut top = NONE;
        while let Some((lo, hi, parent, slot, level)) = stack.pop() {
            // the children (level + 1) may have at most `cap` edges each
            // (never below ⌈k/2⌉ by the caps' construction; the max keeps the window non-empty
            // whatever happens)
            let cap = match budget {
                true => caps.get(level as usize + 1).copied().unwrap_or(1),
                false => hi - lo,
            }
            .max((hi - lo).div_ceil(2));
            let window = (hi - lo > cap).then(|| [hi - cap, lo + cap]);
            let outer = match parent {
                NONE => [[0.0; 2]; 2],
                _ => self.nodes[parent as usize].stone.centres(),
            };
            let (stone, far, outer2) = Flintstone::scan(&self.points, lo, hi, window, outer, quad);
            if parent != NONE {
                let r = &mut reach2[parent as usize - first];
                r[0] = r[0].max(outer2[0]);
                r[1] = r[1].max(outer2[1]);
            }
            let vertex = match stone.split() {
                Some(q) if q - lo <= cap && hi - q <= cap => q,
                // Alg. 7.1's vertex (or none: a segment) leaves a part over the budget
                _ => far.unwrap_or((lo + hi) / 2),
            };
            // the vertices no child scan visits: the chord ends and the split vertex
            let c = stone.centres();
            let mut own = [0.0f64; 2];
            for x in [lo, vertex, hi].map(|p| at(&self.points, p)) {
                own[0] = own[0].max(dist2(c[0], x));
                own[1] = own[1].max(dist2(c[1], x));
            }
            reach2.push(own);
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
        for (nd, r) in self.nodes[first..].iter_mut().zip(reach2) {
            nd.stone.finish_reach(r);
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

/// Levels of unconstrained Alg. 7.1 splits: `⌈log₂ N⌉` (a balanced tree's height).
fn budget_slack(n: usize) -> usize {
    n.next_power_of_two().trailing_zeros() as usize
}

/// The depth budget: `caps[ℓ]` is the most edges a node of level `ℓ` may span. `N` down to the
/// slack, then `max(⌈c/2⌉, ⌊3c/4⌋)` per level, so that a node within its cap can always be split
/// with both parts within the next (a part of `⌈k/2⌉ ≤ ⌈c/2⌉` edges fits), and the tree depth
/// is at most `slack + log_{4/3} N + 2`. Ends at the first cap below 2 (no node below).
fn level_caps(n: usize) -> Vec<usize> {
    // the root's two parts may each span up to N edges (levels 0 and 1)
    let mut caps = vec![n; budget_slack(n).max(1) + 1];
    let mut c = n;
    while c >= 2 {
        c = c.div_ceil(2).max(c / 4 * 3 + c % 4 * 3 / 4);
        caps.push(c);
    }
    caps
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Main's build before the fused scans (one `of_windowed` per node, its reach pass
    /// included): the oracle of the lockstep test below.
    fn reference_nodes(points: &[[f64; 2]], lo: usize, hi: usize, budget: bool) -> Vec<FlintNode> {
        let mut nodes: Vec<FlintNode> = Vec::new();
        if hi < lo + 2 {
            return nodes;
        }
        let caps = if budget {
            level_caps(points.len())
        } else {
            Vec::new()
        };
        let mut stack = vec![(lo, hi, NONE, 0usize, 1u32)];
        while let Some((lo, hi, parent, slot, level)) = stack.pop() {
            let cap = match budget {
                true => caps.get(level as usize + 1).copied().unwrap_or(1),
                false => hi - lo,
            }
            .max((hi - lo).div_ceil(2));
            let window = (hi - lo > cap).then(|| [hi - cap, lo + cap]);
            // Shewchuk's filter and the exact sign only: main's decisions before the
            // quadratic filter
            let (stone, far) = Flintstone::of_windowed_with(points, lo, hi, window, false);
            let vertex = match stone.split() {
                Some(q) if q - lo <= cap && hi - q <= cap => q,
                _ => far.unwrap_or((lo + hi) / 2),
            };
            let id = nodes.len() as u32;
            nodes.push(FlintNode {
                vertex,
                stone,
                children: [NONE, NONE],
                level,
            });
            if parent != NONE {
                nodes[parent as usize].children[slot] = id;
            }
            if hi >= vertex + 2 {
                stack.push((vertex, hi, id, 1, level + 1));
            }
            if vertex >= lo + 2 {
                stack.push((lo, vertex, id, 0, level + 1));
            }
        }
        nodes
    }

    /// The fused build (each node's reaches gathered by its children's scans) against one
    /// `of_windowed` per node, node for node (`PartialEq` on every field, the reaches
    /// included, NaN fields as printed), with and without the depth budget, on polygons and polylines: random walks
    /// (rough, unbalanced trees), an upsampled star (dense, the budget's windows), a circle
    /// rounded to `f64` (near-cocircular ties), a coarse grid walk with collinear runs and
    /// repeated points. A reach gathered from a wrong range (a child's scan including its chord
    /// ends or missing a part, the split vertex not added) or not folded in fails it.
    #[test]
    fn fused_build_equals_the_per_node_passes() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
        let mut sets: Vec<(Vec<[f64; 2]>, bool)> = Vec::new();
        for n in [5usize, 40, 700, 3000] {
            let mut p = [0.0f64, 0.0];
            let walk: Vec<[f64; 2]> = (0..n)
                .map(|_| {
                    p = [
                        p[0] + rng.gen_range(-1.0..1.0),
                        p[1] + rng.gen_range(-1.0..1.0),
                    ];
                    p
                })
                .collect();
            sets.push((walk, false));
            let ph: f64 = rng.gen_range(0.0..1.0);
            let star: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let t = (k as f64 + ph) * std::f64::consts::TAU / n as f64;
                    let r = 1.0 + 0.05 * (7.0 * t).cos() + rng.gen_range(-1e-4..1e-4);
                    [r * t.cos(), r * t.sin()]
                })
                .collect();
            sets.push((star, true));
            let circle: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let t = k as f64 * std::f64::consts::TAU / n as f64;
                    [3.0 + 2.0 * t.cos(), -1.0 + 2.0 * t.sin()]
                })
                .collect();
            sets.push((circle, true));
            let grid: Vec<[f64; 2]> = (0..n)
                .map(|_| [rng.gen_range(-4..=4) as f64, rng.gen_range(-4..=4) as f64])
                .collect();
            sets.push((grid, false));
        }
        let mut compared = 0;
        for (pts, closed) in &sets {
            let ps: Vec<Point2> = pts.iter().map(|p| Point2::new(p[0], p[1])).collect();
            for budget in [true, false] {
                let Ok(t) = FlintTree2::with_rule(&ps, *closed, budget) else {
                    continue;
                };
                let n = pts.len();
                let [i, j] = t.root.chord;
                let mut want = reference_nodes(pts, i, j, budget);
                if *closed {
                    let off = want.len() as u32;
                    let mut second = reference_nodes(pts, j, i + n, budget);
                    for nd in &mut second {
                        for c in &mut nd.children {
                            if *c != NONE {
                                *c += off;
                            }
                        }
                    }
                    want.extend(second);
                }
                // compared as printed: a repeated chord end of an open walk gives NaN fields
                // (in both), which `==` would call different
                assert_eq!(
                    format!("{:?}", t.nodes),
                    format!("{want:?}"),
                    "n {n} closed {closed} budget {budget}"
                );
                compared += want.len();
            }
        }
        assert!(compared > 10_000, "{compared}");
    }

    /// The budget's induction: a node within its level's cap can be split with both parts
    /// within the next level's cap, and the caps end after `slack + log_{4/3} N + 2` levels.
    #[test]
    fn level_caps_admit_a_split_and_bound_the_depth() {
        for n in (3..2000).chain([4096, 4097, 1 << 20, 10_000_000, 1 << 40]) {
            let caps = level_caps(n);
            let slack = budget_slack(n);
            assert!(caps[..=slack].iter().all(|&c| c == n));
            for w in caps.windows(2) {
                if w[0] >= 2 {
                    assert!(w[0].div_ceil(2) <= w[1] && w[1] <= w[0], "{n}: {w:?}");
                }
            }
            assert!(*caps.last().unwrap() < 2 && caps[caps.len() - 2] >= 2);
            let bound = slack as f64 + (n as f64).ln() / (4.0f64 / 3.0).ln() + 2.0;
            assert!(
                ((caps.len() - 1) as f64) <= bound,
                "{n}: {} levels",
                caps.len() - 1
            );
        }
    }
}

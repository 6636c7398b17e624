//! The fast point-in-polygon walk over a flat copy of the 2D flintstone tree (Veltkamp 1992,
//! §7.4, Lemma 6.1; issue 18's throughput target).
//!
//! Same answer as the Lemma 6.1 walk of `query.rs` (crossing parity of a ray towards +x over a
//! mixed boundary of chords and edges, on-boundary decided at the leaves), on a layout made for
//! the query:
//! - **flat, DFS order.** The tree's nodes are already numbered in preorder (left child = id + 1);
//!   [`Flat`] keeps, per node, 32 bytes: the bounding box of its polyline in `f32` (rounded
//!   outwards, so every test below stays conservative), the chord ends and split vertex as
//!   input indices, the right child. The flintstone's defining vertices live in a second array
//!   read only when the box test cannot decide.
//! - **exact box pre-filter.** A piece whose box is above, below or left of X (strictly) holds
//!   no crossing of the ray and not X: skipped. A piece whose box does not contain X otherwise
//!   is replaced by its chord (Lemma 6.1 with the box as the convex region). Comparisons of
//!   coordinates are exact, so these are exact decisions, not tolerances.
//! - **flintstone filter** only for X inside the box: outside one of the flintstone's discs
//!   (each holds the whole polyline; compared in `f64` against its reach with a slack far above
//!   the rounding, so "outside" is certain), or strictly on a cap's empty side of the chord
//!   (exact `orient2d`) ⇒ the chord; otherwise the node is opened. A ∪ or unbounded
//!   flintstone is not convex: its hull disc about the chord midpoint serves instead.
//! - **leaves**: the edge's y-extent and x-extent reject most edges with comparisons; otherwise
//!   one exact `orient2d` gives both "on the edge" and the crossing.
//! - **no allocation per query** (the caller's stack is reused); batches run in parallel
//!   (rayon) with the answers in input order. Sorting a batch along a Hilbert curve first
//!   (so that consecutive queries walk the same nodes) is available for measurement
//!   ([`FlintTree2::contains_batch_hilbert`]); on uniform random queries it cost more than it
//!   saved (bench/README.md).
//!
//! Opening a node that could have been skipped never changes the parity, so every filter only
//! has to be conservative (a float filter may say "maybe inside", never "outside" wrongly);
//! the crossings and "on the boundary" are exact (`orient2d`: Shewchuk's adaptive predicate, a
//! float evaluation with an error bound first, exact expansions only when that cannot decide). O(log N) expected per query on
//! well-behaved boundaries, O(N) worst.

use super::disc::{Flintstone, StoneKind};
use super::query::Containment;
use super::tree2::FlintTree2;
use crate::geom::intersect::on_segment;
use crate::geom::predicates::raw::orient2d;
use crate::util::hilbert::{hilbert2, HILBERT2_BITS};
use crate::util::NONE;
use rayon::prelude::*;

/// Stack entries: a node id, or an edge (its first vertex's input index) with this bit set.
const EDGE: u32 = 1 << 31;
/// Set in [`FlatNode::mid`] when the node has a left child node (it is then `id + 1`).
const HAS_LEFT: u32 = 1 << 31;

/// The hot part of one node (32 bytes, two per cache line).
#[derive(Debug, Clone, Copy, PartialEq)]
struct FlatNode {
    /// `[xmin, ymin, xmax, ymax]` of the polyline, rounded outwards to `f32`.
    bb: [f32; 4],
    /// Input index of the first chord end.
    lo: u32,
    /// Input index of the last chord end.
    hi: u32,
    /// Input index of the split vertex, with [`HAS_LEFT`].
    mid: u32,
    /// The right child: a node id, or `EDGE | index` of the edge `mid → hi`.
    right: u32,
}

/// The cold part: the flintstone as a conservative filter.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FlatStone {
    /// Discs `(centre, t)` each holding every vertex of the polyline: X with
    /// `|X − centre|² > t` (in `f64`) is certainly outside. `t` is the square of the disc's
    /// reach (every vertex's `f64` distance folded in) plus a relative and an absolute
    /// slack far above the rounding of these sums; `+∞` for no disc.
    discs: [([f64; 2], f64); 2],
    /// A cap's empty side of the chord line `lo → hi`: `1` left, `-1` right, `0` none. X
    /// strictly on that side (exact `orient2d`) is outside the cap.
    empty: i8,
    /// Every vertex on the chord segment: only the chord's points are in the flintstone.
    segment: bool,
}

/// The query layout of a closed [`FlintTree2`].
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Flat {
    nodes: Vec<FlatNode>,
    stones: Vec<FlatStone>,
    /// The one or two top pieces (stack entries).
    tops: Vec<u32>,
}

/// `v` rounded down to an `f32` (never above `v`).
fn down(v: f64) -> f32 {
    let f = v as f32;
    if f as f64 > v {
        next_toward_neg(f)
    } else {
        f
    }
}

/// `v` rounded up to an `f32` (never below `v`).
fn up(v: f64) -> f32 {
    -down(-v)
}

fn next_toward_neg(f: f32) -> f32 {
    if f.is_nan() || f == f32::NEG_INFINITY {
        f
    } else if f == 0.0 {
        -f32::from_bits(1)
    } else if f > 0.0 {
        f32::from_bits(f.to_bits() - 1)
    } else {
        f32::from_bits(f.to_bits() + 1)
    }
}

type Box2 = [f64; 4];

fn bb_of(a: [f64; 2], b: [f64; 2]) -> Box2 {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[0].max(b[0]),
        a[1].max(b[1]),
    ]
}

fn union(a: Box2, b: Box2) -> Box2 {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

impl Flat {
    /// The flat copy of a closed tree (O(N)).
    pub(crate) fn new(t: &FlintTree2) -> Flat {
        let n = t.len();
        let p = &t.points;
        let ix = |pos: usize| (pos % n) as u32;
        let m = t.nodes.len();
        let mut nodes = Vec::with_capacity(m);
        let mut stones = Vec::with_capacity(m);
        for nd in &t.nodes {
            let (lo, hi, mid) = (nd.stone.lo, nd.stone.hi, nd.vertex);
            let [l, r] = nd.children;
            debug_assert!(l == NONE || l as usize == nodes.len() + 1, "preorder");
            nodes.push(FlatNode {
                bb: [0.0; 4],
                lo: ix(lo),
                hi: ix(hi),
                mid: ix(mid) | if l == NONE { 0 } else { HAS_LEFT },
                right: if r == NONE { EDGE | ix(mid) } else { r },
            });
            stones.push(flat_stone(&nd.stone));
        }
        // boxes bottom-up: children have larger ids
        let mut boxes = vec![[0.0; 4]; m];
        for id in (0..m).rev() {
            let nd = &t.nodes[id];
            let [l, r] = nd.children;
            let piece = |c: u32, a: usize, b: usize| {
                if c == NONE {
                    bb_of(p[a % n], p[b % n])
                } else {
                    boxes[c as usize]
                }
            };
            let b = union(
                piece(l, nd.stone.lo, nd.vertex),
                piece(r, nd.vertex, nd.stone.hi),
            );
            boxes[id] = b;
            nodes[id].bb = [down(b[0]), down(b[1]), up(b[2]), up(b[3])];
        }
        let [i, j] = t.root.chord;
        // a top piece of one edge is that input edge
        let tops = [(t.root.children[0], i), (t.root.children[1], j)]
            .map(|(c, a)| if c == NONE { EDGE | ix(a) } else { c })
            .to_vec();
        Flat {
            nodes,
            stones,
            tops,
        }
    }

    /// Where `x` is relative to the polygon `p` (finite `x`); `stack` is scratch space.
    #[inline]
    pub(crate) fn locate(&self, p: &[[f64; 2]], x: [f64; 2], stack: &mut Vec<u32>) -> Containment {
        let n = p.len() as u32;
        let mut inside = false;
        stack.clear();
        stack.extend_from_slice(&self.tops);
        let (xx, xy) = (x[0], x[1]);
        while let Some(e) = stack.pop() {
            if e & EDGE != 0 {
                let i = e & !EDGE;
                let k = if i + 1 == n { 0 } else { i + 1 };
                let (a, b) = (p[i as usize], p[k as usize]);
                // y-extent and x-extent: no crossing and not on the edge
                if (a[1] > xy && b[1] > xy) || (a[1] < xy && b[1] < xy) || (a[0] < xx && b[0] < xx)
                {
                    continue;
                }
                let o = orient2d(a, b, x);
                if o == 0.0 && on_segment(a, b, x) {
                    return Containment::Boundary;
                }
                inside ^= crossing(a, b, xy, o);
                continue;
            }
            let nd = &self.nodes[e as usize];
            let bb = nd.bb;
            // the box is above, below or left of X: no crossing, X not on the polyline
            if xy < bb[1] as f64 || xy > bb[3] as f64 || xx > bb[2] as f64 {
                continue;
            }
            let (a, b) = (p[nd.lo as usize], p[nd.hi as usize]);
            if xx < bb[0] as f64 || !self.in_stone(e as usize, a, b, x) {
                // X outside a convex region holding the polyline and the chord: the chord's
                // crossing stands in for the polyline's (Lemma 6.1)
                inside ^= crosses(a, b, x);
                continue;
            }
            stack.push(nd.right);
            let mid = nd.mid & !HAS_LEFT;
            stack.push(if nd.mid & HAS_LEFT != 0 {
                e + 1
            } else {
                EDGE | nd.lo
            });
            debug_assert!(nd.mid & HAS_LEFT != 0 || (nd.lo + 1) % n == mid);
        }
        if inside {
            Containment::Inside
        } else {
            Containment::Outside
        }
    }

    /// May `x` lie in the flintstone of node `id` (chord `a b`)? False only when it certainly
    /// does not: outside one of its conservative discs, strictly on a cap's empty side, or off
    /// a segment flintstone (the last two exact).
    #[inline]
    fn in_stone(&self, id: usize, a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
        let s = &self.stones[id];
        for (c, t) in s.discs {
            let (dx, dy) = (x[0] - c[0], x[1] - c[1]);
            if dx * dx + dy * dy > t {
                return false;
            }
        }
        if s.empty != 0 || s.segment {
            let o = orient2d(a, b, x);
            if s.segment {
                return o == 0.0 && on_segment(a, b, x);
            }
            if (o > 0.0 && s.empty > 0) || (o < 0.0 && s.empty < 0) {
                return false;
            }
        }
        true
    }

    /// The answers for many finite points, in input order, located in parallel chunks
    /// (rayon; one scratch stack per chunk). With `hilbert`, the points are visited sorted
    /// along a Hilbert curve and the answers put back in place.
    pub(crate) fn locate_batch(
        &self,
        p: &[[f64; 2]],
        xs: &[[f64; 2]],
        hilbert: bool,
    ) -> Vec<Containment> {
        let init = || Vec::with_capacity(64);
        if !hilbert {
            return xs
                .par_iter()
                .with_min_len(1024)
                .map_init(init, |stack, &x| self.locate(p, x, stack))
                .collect();
        }
        let order = hilbert_order(xs);
        let sorted: Vec<Containment> = order
            .par_iter()
            .with_min_len(1024)
            .map_init(init, |stack, &k| self.locate(p, xs[k as usize], stack))
            .collect();
        let mut out = vec![Containment::Outside; xs.len()];
        for (&k, c) in order.iter().zip(sorted) {
            out[k as usize] = c;
        }
        out
    }
}

/// The filter of one flintstone (see [`FlatStone`]).
fn flat_stone(f: &Flintstone) -> FlatStone {
    let disc = |(c, r): ([f64; 2], f64)| {
        let reach = r + 1e-12 * (r + c[0].abs() + c[1].abs()) + 1e-150;
        (c, reach * reach)
    };
    let none = ([0.0; 2], f64::INFINITY);
    let mut discs = [none; 2];
    // ∩ and cap: the side discs; ∪, segment, unbounded (not convex or no disc): the hull disc
    // about the chord midpoint
    for (k, d) in f.filter_discs().into_iter().take(2).enumerate() {
        discs[k] = disc(d);
    }
    let empty = match (f.kind, f.left, f.right) {
        (StoneKind::Cap, None, Some(_)) => 1,
        (StoneKind::Cap, Some(_), None) => -1,
        _ => 0,
    };
    FlatStone {
        discs,
        empty,
        segment: f.kind == StoneKind::Segment,
    }
}

/// The crossing of the ray from `x` towards +x with edge `a b`, given `o = orient2d(a, b, x)`
/// (half-open rule, exact).
#[inline]
fn crossing(a: [f64; 2], b: [f64; 2], xy: f64, o: f64) -> bool {
    if (a[1] > xy) == (b[1] > xy) {
        return false;
    }
    if b[1] > a[1] {
        o > 0.0
    } else {
        o < 0.0
    }
}

/// [`crossing`] computing the orientation only when the edge straddles the ray's line.
#[inline]
fn crosses(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
    if (a[1] > x[1]) == (b[1] > x[1]) {
        return false;
    }
    crossing(a, b, x[1], orient2d(a, b, x))
}

/// Query indices sorted by the Hilbert key of their cell in a 2^16 × 2^16 grid over their box
/// (ties by index: deterministic).
fn hilbert_order(xs: &[[f64; 2]]) -> Vec<u32> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for x in xs {
        for d in 0..2 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let cells = (1u64 << HILBERT2_BITS) as f64;
    let scale = |d: usize| {
        let w = hi[d] - lo[d];
        if w > 0.0 && w.is_finite() {
            (cells - 1.0) / w
        } else {
            0.0
        }
    };
    let (sx, sy) = (scale(0), scale(1));
    let mut keys: Vec<u64> = xs
        .par_iter()
        .enumerate()
        .map(|(k, x)| {
            let cx = ((x[0] - lo[0]) * sx) as u32;
            let cy = ((x[1] - lo[1]) * sy) as u32;
            (u64::from(hilbert2(cx, cy)) << 32) | k as u64
        })
        .collect();
    keys.par_sort_unstable();
    keys.into_iter().map(|k| k as u32).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outward_rounding_never_crosses_the_value() {
        for v in [
            0.0,
            -0.0,
            1.0,
            0.1,
            -0.1,
            1e-300,
            -1e-300,
            3.4e38,
            1e39,
            -1e39,
            49.795_012_164_550_8,
            -13.215937238392002,
            153.1437314373144,
        ] {
            assert!(down(v) as f64 <= v, "{v}");
            assert!(up(v) as f64 >= v, "{v}");
            assert!((up(v) as f64 - v).abs() <= (v.abs() * 1e-7).max(1e-44) || v.abs() > 3e38);
        }
    }
}

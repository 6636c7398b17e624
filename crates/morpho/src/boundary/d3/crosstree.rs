//! [`BoxIndex`]: boxes of triangles by id, for the searches of the general engine that need
//! the live triangles near a tetrahedron or a face — [`super::general::General3::crossing`]
//! (issue 17 item 8) and [`super::general::General3::hits_boundary`].
//!
//! The uniform grid it replaces there ([`super::trigrid::TriGrid`], one cell size, set by the
//! long triangles: 2.3 units on the fandisk, whose box is 4.8 × 5.2 × 2.7) handed over about
//! 17 times more ids than the boxes that really meet a small tetrahedron's (25.7·10³ per
//! removal on the whole fandisk at c = −0.5, of which 5.3·10³ dead and 17.8·10³ with a box
//! missing the query's; bench/README, branch `cross4`), and kept dead ids for good. Here the
//! boxes go into bounding-volume hierarchies, one per size class of boxes (the longest side,
//! classes a factor 4 apart, so that a long triangle does not widen the nodes over short
//! ones), each balanced by median splits of the box centres along the widest axis, with the
//! number of live ids under every node so that a query skips dead subtrees and never hands a
//! dead id over. A query visits the nodes whose boxes meet the query's: its cost follows the
//! boxes that meet it (plus O(log n) per class and tree). Insertions after the bulk
//! construction use the logarithmic method ([`BoxIndex`]).
//!
//! Exactness: the index is only a filter. Boxes are stored in `f32`, relative to an origin,
//! rounded outward by one monotone function of the `f64` coordinate ([`down`], [`up`]), so a
//! stored box meets the stored query box whenever the exact boxes meet; the callers apply the
//! exact `f64` box test and the exact predicates to what is handed over. The order of the
//! answer is unspecified (callers sort it or take a predicate's `any`).

use crate::util::NONE;

type P = [f64; 3];
/// A box in `f32`: lower corner, then upper corner.
type B = [f32; 6];

/// Items per leaf of a [`BoxTree`].
const LEAF: usize = 8;

/// The largest `f32` not above `x − o` (`x − o` rounded to `f64` first; both roundings are
/// monotone, so `x ≤ y` implies `down(x) ≤ down(y)` and `down(x) ≤ up(y)`).
#[inline]
fn down(x: f64, o: f64) -> f32 {
    let d = x - o;
    let f = d as f32;
    if (f as f64) > d {
        -next_up(-f)
    } else {
        f
    }
}

/// The smallest `f32` not below `x − o` (see [`down`]).
#[inline]
fn up(x: f64, o: f64) -> f32 {
    let d = x - o;
    let f = d as f32;
    if (f as f64) < d {
        next_up(f)
    } else {
        f
    }
}

/// The next `f32` above `f` (`f` not NaN, below +∞; `f32::next_up` needs Rust 1.86).
#[inline]
fn next_up(f: f32) -> f32 {
    if f == 0.0 {
        f32::from_bits(1)
    } else if f > 0.0 {
        f32::from_bits(f.to_bits() + 1)
    } else {
        f32::from_bits(f.to_bits() - 1)
    }
}

#[inline]
fn meets(a: &B, b: &B) -> bool {
    a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5]
}

#[inline]
fn union(a: &B, b: &B) -> B {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
        a[4].max(b[4]),
        a[5].max(b[5]),
    ]
}

const EMPTY: B = [
    f32::INFINITY,
    f32::INFINITY,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NEG_INFINITY,
    f32::NEG_INFINITY,
];

/// A node of a [`Class`]: the union of its items' boxes ([`EMPTY`] in unused slots) and the
/// number of its live items, side by side (a query reads both: one cache line, not two).
#[derive(Debug, Clone, Copy)]
struct Node {
    b: B,
    live: u32,
}

/// One size class: items `start..start + len` of the tree, in an implicit binary tree (node
/// `k` has children `2k + 1`, `2k + 2`; the root covers the class's items and every node splits
/// its range at the middle, down to at most [`LEAF`] items).
#[derive(Debug)]
struct Class {
    start: usize,
    len: usize,
    nodes: Vec<Node>,
}

/// An item of a [`BoxTree`]: stored box, id and liveness together (32 bytes: a leaf's test
/// of an item reads one cache line, not three).
#[derive(Debug, Clone, Copy)]
struct Item {
    b: B,
    id: u32,
    alive: bool,
}

/// The deepest a class's implicit tree can be: its nodes are indexed by `usize` and a node
/// `k` at depth `d` has `k ≥ 2^d − 1`, so `d < usize::BITS` (the traversal's stack holds at
/// most one pending sibling per level, plus the node being expanded).
const MAX_DEPTH: usize = usize::BITS as usize + 1;

/// A static bounding-volume hierarchy per size class of boxes, with the live items under each
/// node (see the module documentation).
#[derive(Debug, Default)]
struct BoxTree {
    classes: Vec<Class>,
    items: Vec<Item>,
}

/// The size class of a box: log₄ of its longest side (zero or not finite: the smallest).
fn class_of(b: &B) -> i32 {
    let ext = (0..3).map(|k| b[k + 3] - b[k]).fold(0.0f32, f32::max);
    if ext > 0.0 && ext.is_finite() {
        (ext.log2().floor() as i32).div_euclid(2)
    } else {
        i32::MIN
    }
}

impl BoxTree {
    /// The hierarchies of `items` (id, stored box, alive), each id once.
    fn new(mut items: Vec<(u32, B, bool)>) -> Self {
        items.sort_by_cached_key(|x| class_of(&x.1));
        let mut t = BoxTree::default();
        let n = items.len();
        let mut s = 0;
        while s < n {
            let cs = class_of(&items[s].1);
            let mut e = s + 1;
            while e < n && class_of(&items[e].1) == cs {
                e += 1;
            }
            let mut c = Class {
                start: s,
                len: e - s,
                nodes: Vec::new(),
            };
            build(&mut items[s..e], 0, &mut c);
            t.classes.push(c);
            s = e;
        }
        t.items = items
            .iter()
            .map(|x| Item {
                b: x.1,
                id: x.0,
                alive: x.2,
            })
            .collect();
        t
    }

    fn len(&self) -> usize {
        self.items.len()
    }

    /// Marks item `p` dead or alive, updating the live counts on its path.
    fn set_alive(&mut self, p: usize, on: bool) {
        if self.items[p].alive == on {
            return;
        }
        self.items[p].alive = on;
        let ci = self.classes.partition_point(|c| c.start <= p) - 1;
        let c = &mut self.classes[ci];
        let (mut k, mut lo, mut hi) = (0usize, c.start, c.start + c.len);
        loop {
            if on {
                c.nodes[k].live += 1;
            } else {
                c.nodes[k].live -= 1;
            }
            if hi - lo <= LEAF {
                break;
            }
            let mid = lo + (hi - lo) / 2;
            if p < mid {
                k = 2 * k + 1;
                hi = mid;
            } else {
                k = 2 * k + 2;
                lo = mid;
            }
        }
    }

    /// Calls `f` on every live id whose stored box meets `q`, each once, until it returns
    /// true; returns whether it did. `met` counts the calls.
    ///
    /// The traversal's stack is an array on the call stack (depth-first, the left child
    /// first: at most one pending right sibling per level, [`MAX_DEPTH`]), not a heap
    /// allocation per query.
    fn any(&self, q: &B, met: &mut usize, f: &mut dyn FnMut(u32) -> bool) -> bool {
        let mut stack = [(0usize, 0usize, 0usize); MAX_DEPTH];
        for c in &self.classes {
            let mut top = 1;
            stack[0] = (0, c.start, c.start + c.len);
            while top > 0 {
                top -= 1;
                let (k, a, b) = stack[top];
                let node = &c.nodes[k];
                if node.live == 0 || !meets(&node.b, q) {
                    continue;
                }
                if b - a <= LEAF {
                    for it in &self.items[a..b] {
                        if it.alive && meets(&it.b, q) {
                            *met += 1;
                            if f(it.id) {
                                return true;
                            }
                        }
                    }
                    continue;
                }
                let mid = a + (b - a) / 2;
                stack[top] = (2 * k + 2, mid, b);
                stack[top + 1] = (2 * k + 1, a, mid);
                top += 2;
            }
        }
        false
    }
}

/// Builds node `k` over `items` (the node's range), recursively (depth O(log n)).
fn build(items: &mut [(u32, B, bool)], k: usize, c: &mut Class) -> B {
    if c.nodes.len() <= k {
        c.nodes.resize(k + 1, Node { b: EMPTY, live: 0 });
    }
    c.nodes[k].live = items.iter().filter(|x| x.2).count() as u32;
    let bound = if items.len() <= LEAF {
        items.iter().fold(EMPTY, |u, x| union(&u, &x.1))
    } else {
        // the widest axis of the centres (sums of the corners: the same order)
        let mut cb = EMPTY;
        for x in items.iter() {
            for a in 0..3 {
                let m = x.1[a] + x.1[a + 3];
                cb[a] = cb[a].min(m);
                cb[a + 3] = cb[a + 3].max(m);
            }
        }
        let axis = (0..3)
            .max_by(|&a, &b| (cb[a + 3] - cb[a]).total_cmp(&(cb[b + 3] - cb[b])))
            .unwrap_or(0);
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |x, y| {
            (x.1[axis] + x.1[axis + 3]).total_cmp(&(y.1[axis] + y.1[axis + 3]))
        });
        let (l, r) = items.split_at_mut(mid);
        let bl = build(l, 2 * k + 1, c);
        let br = build(r, 2 * k + 2, c);
        union(&bl, &br)
    };
    c.nodes[k].b = bound;
    bound
}

/// Where an id is held: [`BoxIndex::buf`] (this tag) or a tree (its index), and the item.
const IN_BUF: u32 = u32::MAX - 1;

/// Items the unsorted buffer holds before it becomes a tree.
const BUF_MAX: usize = 256;

/// A dynamic index of boxes by id (see the module documentation): static [`BoxTree`]s of
/// geometrically decreasing sizes (the logarithmic method: an insertion goes into a small
/// buffer scanned by every query; a full buffer is merged with every tree not larger than
/// twice the merged items into one new tree, so each item is rebuilt O(log n) times) and the
/// liveness of each id (dead ids are never handed over).
#[derive(Debug)]
pub(super) struct BoxIndex {
    origin: P,
    trees: Vec<BoxTree>,
    buf: Vec<(u32, B, bool)>,
    /// Id → (tree or [`IN_BUF`], item), or `(NONE, _)` when not held.
    loc: Vec<(u32, u32)>,
}

impl BoxIndex {
    /// An empty index with boxes stored relative to `lo`.
    pub(super) fn new(lo: P) -> Self {
        BoxIndex {
            origin: lo,
            trees: Vec::new(),
            buf: Vec::new(),
            loc: Vec::new(),
        }
    }

    fn stored(&self, lo: P, hi: P) -> B {
        let o = self.origin;
        [
            down(lo[0], o[0]),
            down(lo[1], o[1]),
            down(lo[2], o[2]),
            up(hi[0], o[0]),
            up(hi[1], o[1]),
            up(hi[2], o[2]),
        ]
    }

    fn set_loc(&mut self, id: u32, at: (u32, u32)) {
        let i = id as usize;
        if self.loc.len() <= i {
            self.loc.resize(i + 1, (NONE, 0));
        }
        self.loc[i] = at;
    }

    /// Many boxes at once (ids not held yet, distinct), alive: one tree when the index is
    /// empty, else one by one.
    pub(super) fn insert_many(&mut self, items: impl Iterator<Item = (u32, P, P)>) {
        if !self.trees.is_empty() || !self.buf.is_empty() {
            for (id, lo, hi) in items {
                self.insert(id, lo, hi);
            }
            return;
        }
        let v: Vec<(u32, B, bool)> = items
            .map(|(id, lo, hi)| (id, self.stored(lo, hi), true))
            .collect();
        if !v.is_empty() {
            self.push_tree(v);
        }
    }

    /// A new id (not held yet), alive.
    pub(super) fn insert(&mut self, id: u32, lo: P, hi: P) {
        let b = self.stored(lo, hi);
        self.set_loc(id, (IN_BUF, self.buf.len() as u32));
        self.buf.push((id, b, true));
        if self.buf.len() >= BUF_MAX {
            let mut v = std::mem::take(&mut self.buf);
            while self.trees.last().is_some_and(|t| t.len() <= 2 * v.len()) {
                let t = self.trees.pop().unwrap_or_default();
                v.extend(t.items.iter().map(|x| (x.id, x.b, x.alive)));
            }
            self.push_tree(v);
        }
    }

    fn push_tree(&mut self, v: Vec<(u32, B, bool)>) {
        let t = BoxTree::new(v);
        let ti = self.trees.len() as u32;
        for (k, x) in t.items.iter().enumerate() {
            self.set_loc(x.id, (ti, k as u32));
        }
        self.trees.push(t);
    }

    /// Marks `id` dead (never handed over) or alive again; ids not held are ignored.
    pub(super) fn set_alive(&mut self, id: u32, on: bool) {
        let Some(&(t, k)) = self.loc.get(id as usize) else {
            return;
        };
        if t == IN_BUF {
            self.buf[k as usize].2 = on;
        } else if t != NONE {
            self.trees[t as usize].set_alive(k as usize, on);
        }
    }

    /// Calls `f` on every live id whose stored box meets the box `[lo, hi]` — a superset of
    /// the live ids whose exact boxes meet it (boxes rounded outward, see [`down`]) — each
    /// once, in no particular order, until it returns true; returns whether it did and how
    /// many ids it handed over.
    pub(super) fn any(&self, lo: P, hi: P, mut f: impl FnMut(u32) -> bool) -> (bool, usize) {
        let q = self.stored(lo, hi);
        let mut met = 0;
        for t in &self.trees {
            if t.any(&q, &mut met, &mut f) {
                return (true, met);
            }
        }
        for x in &self.buf {
            if x.2 && meets(&x.1, &q) {
                met += 1;
                if f(x.0) {
                    return (true, met);
                }
            }
        }
        (false, met)
    }

    /// Every id held, dead or alive, sorted (tests).
    #[cfg(test)]
    pub(super) fn ids(&self) -> Vec<u32> {
        let mut v: Vec<u32> = self.buf.iter().map(|x| x.0).collect();
        for t in &self.trees {
            v.extend(t.items.iter().map(|x| x.id));
        }
        v.sort_unstable();
        v
    }

    /// The most size classes of a tree (tests).
    #[cfg(test)]
    pub(super) fn classes(&self) -> usize {
        self.trees
            .iter()
            .map(|t| t.classes.len())
            .max()
            .unwrap_or(0)
    }

    /// The ids [`BoxIndex::any`] hands over, sorted (tests).
    #[cfg(test)]
    pub(super) fn query(&self, lo: P, hi: P, out: &mut Vec<u32>) {
        out.clear();
        self.any(lo, hi, |i| {
            out.push(i);
            false
        });
        out.sort_unstable();
    }

    /// The ids [`BoxIndex::any`] hands over for which `take` is true go into `out` (cleared
    /// first), in no particular order; returns how many ids were handed over.
    pub(super) fn query_where(
        &self,
        lo: P,
        hi: P,
        mut take: impl FnMut(u32) -> bool,
        out: &mut Vec<u32>,
    ) -> usize {
        out.clear();
        self.any(lo, hi, |i| {
            if take(i) {
                out.push(i);
            }
            false
        })
        .1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn meets64(a: (P, P), b: (P, P)) -> bool {
        (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
    }

    /// The index against brute force: every live id whose exact box meets the query box is
    /// handed over, exactly once; no dead id is; every id handed over has a stored box meeting
    /// the stored query box; `any` stops at the first id its predicate accepts and finds one
    /// exactly when the brute-force set has one. Boxes of every size class, flat and zero-size
    /// boxes, queries touching a box in one coordinate, a far origin; a bulk tree, then
    /// insertions one by one (the buffer and merged trees), kills and revivals.
    #[test]
    fn index_answers_every_live_box_that_meets() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
        for (si, &(origin, scale)) in [([0.0; 3], 1.0), ([-3.0, 1e6, 7.5], 1e-3)]
            .iter()
            .enumerate()
        {
            let n = 12_000;
            let mut boxes: Vec<(P, P)> = Vec::with_capacity(n);
            for i in 0..n {
                let c: P = std::array::from_fn(|k| origin[k] + scale * rng.gen_range(0.0..10.0));
                let ext = scale * 10f64.powf(rng.gen_range(-4.0..1.0));
                let mut h: P = std::array::from_fn(|_| ext * rng.gen_range(0.0..1.0));
                match i % 7 {
                    0 => h[i % 3] = 0.0, // flat
                    1 => h = [0.0; 3],   // a point
                    _ => {}
                }
                boxes.push((
                    std::array::from_fn(|k| c[k] - h[k]),
                    std::array::from_fn(|k| c[k] + h[k]),
                ));
            }
            // ids with gaps; the first half in bulk, the rest one by one between queries
            let id = |i: usize| (3 * i + 1) as u32;
            let bulk = n / 2;
            let mut t = BoxIndex::new(origin);
            t.insert_many((0..bulk).map(|i| (id(i), boxes[i].0, boxes[i].1)));
            assert!(t.classes() >= 3, "set {si}");
            let mut held = bulk;
            let mut alive = vec![false; n];
            alive[..bulk].fill(true);
            let mut seen = vec![0u32; 3 * n + 2];
            let (mut checked, mut stops) = (0usize, 0usize);
            for round in 0..400 {
                for _ in 0..rng.gen_range(0..40) {
                    if held < n {
                        t.insert(id(held), boxes[held].0, boxes[held].1);
                        alive[held] = true;
                        held += 1;
                    }
                }
                // kill or revive a few
                for _ in 0..30 {
                    let i = rng.gen_range(0..held);
                    let on = rng.gen_bool(0.3);
                    alive[i] = on;
                    t.set_alive(id(i), on);
                }
                t.set_alive(2, false); // not held
                t.set_alive(u32::MAX - 5, true); // not held
                let c: P = std::array::from_fn(|k| origin[k] + scale * rng.gen_range(0.0..10.0));
                let h = scale * 10f64.powf(rng.gen_range(-4.0..0.5));
                let mut q: (P, P) = (c.map(|x| x - h), c.map(|x| x + h));
                if round % 5 == 0 {
                    // a query touching one box in one coordinate exactly
                    let b = boxes[rng.gen_range(0..held)];
                    q.0[0] = b.1[0];
                }
                let mut got = Vec::new();
                let (stop, met) = t.any(q.0, q.1, |i| {
                    got.push(i);
                    false
                });
                assert!(!stop);
                assert_eq!(met, got.len());
                for &i in &got {
                    seen[i as usize] += 1;
                    let k = (i as usize - 1) / 3;
                    assert!(k < held && alive[k], "set {si}: dead id {i} handed over");
                }
                let mut want = Vec::new();
                for k in 0..held {
                    let s = seen[id(k) as usize];
                    if alive[k] && meets64(q, boxes[k]) {
                        assert_eq!(s, 1, "set {si} round {round}: id {} missing", id(k));
                        want.push(id(k));
                        checked += 1;
                    } else {
                        assert!(s <= 1, "set {si}: id {} twice", id(k));
                    }
                }
                for &i in &got {
                    seen[i as usize] = 0;
                }
                // nothing beyond the stored query
                let sq = t.stored(q.0, q.1);
                for &i in &got {
                    let b = boxes[(i as usize - 1) / 3];
                    assert!(meets(&t.stored(b.0, b.1), &sq));
                }
                // `any` stops at an accepted id, and finds one when there is one
                if let Some(&w) = want.get(want.len() / 2) {
                    let mut after = 0;
                    let (found, _) = t.any(q.0, q.1, |i| {
                        after += 1;
                        i == w
                    });
                    assert!(found);
                    assert!(after <= got.len());
                    stops += 1;
                }
                let mut taken = Vec::new();
                let met2 = t.query_where(q.0, q.1, |i| i % 2 == 0, &mut taken);
                taken.sort_unstable();
                got.sort_unstable();
                got.retain(|i| i % 2 == 0);
                assert_eq!((met2, &taken), (met, &got));
            }
            assert_eq!(held, n, "set {si}");
            assert!(t.trees.len() >= 2, "set {si}");
            assert_eq!(t.ids(), (0..n).map(id).collect::<Vec<_>>());
            assert!(checked > 1000 && stops > 100, "set {si}: {checked} {stops}");
        }
    }

    /// The outward rounding: `down(x) ≤ fl(x − o) ≤ up(x)` (`fl`: the `f64` difference),
    /// checked on values that are not `f32`s, far from the origin and at `f32`'s overflow.
    #[test]
    fn rounding_is_outward() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        for _ in 0..100_000 {
            let x: f64 = rng.gen_range(-1e7..1e7) * 10f64.powi(rng.gen_range(-30..30));
            let o: f64 = if rng.gen_bool(0.5) {
                0.0
            } else {
                rng.gen_range(-1e3..1e3)
            };
            let d = x - o;
            assert!(
                (down(x, o) as f64) <= d && (up(x, o) as f64) >= d,
                "{x} {o}"
            );
        }
        assert_eq!(up(1e300, 0.0), f32::INFINITY);
        assert_eq!(down(1e300, 0.0), f32::MAX);
        assert_eq!(down(-1e300, 0.0), f32::NEG_INFINITY);
        assert_eq!(up(-1e300, 0.0), -f32::MAX);
        assert_eq!(up(1e-300, 0.0), f32::from_bits(1));
        assert_eq!(down(-1e-300, 0.0), -f32::from_bits(1));
        for x in [1.0f32, -1.0, 3.5e-40, -7.25e30] {
            assert_eq!(next_up(x), x.next_up());
            assert_eq!(-next_up(-x), x.next_down());
        }
    }
}

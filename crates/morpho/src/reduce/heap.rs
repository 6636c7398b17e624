//! The order of Algorithm 5.1 (Hamann 1991, §5.2): a binary min-heap of triangle weights with
//! lazy invalidation. Each entry carries the triangle's version at push time; an entry whose
//! triangle died or was re-weighted since is skipped when popped. Ties (Rem. 5.7: arbitrary)
//! are broken by the smaller triangle slot, so runs are deterministic.
//!
//! O(log n) per push and pop; entries beyond the live ones are bounded by the pushes.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

#[derive(Debug, Clone, Copy)]
struct Entry {
    w: f64,
    t: u32,
    version: u32,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    // reversed: BinaryHeap is a max-heap, we want the smallest weight first
    fn cmp(&self, o: &Self) -> Ordering {
        o.w.total_cmp(&self.w)
            .then(o.t.cmp(&self.t))
            .then(o.version.cmp(&self.version))
    }
}

/// Min-heap of (weight, triangle) with versions.
#[derive(Default)]
pub(crate) struct WeightHeap {
    heap: BinaryHeap<Entry>,
    /// Current version of each triangle slot.
    pub version: Vec<u32>,
}

impl WeightHeap {
    /// Pushes triangle `t` with weight `w`, invalidating its older entries.
    pub fn push(&mut self, t: u32, w: f64) {
        if self.version.len() <= t as usize {
            self.version.resize(t as usize + 1, 0);
        }
        self.version[t as usize] = self.version[t as usize].wrapping_add(1);
        self.heap.push(Entry {
            w,
            t,
            version: self.version[t as usize],
        });
    }
    /// Invalidates every entry of `t`.
    pub fn invalidate(&mut self, t: u32) {
        if let Some(v) = self.version.get_mut(t as usize) {
            *v = v.wrapping_add(1);
        }
    }
    /// The valid entry of smallest weight, removed.
    pub fn pop(&mut self) -> Option<(u32, f64)> {
        while let Some(e) = self.heap.pop() {
            if self.version.get(e.t as usize) == Some(&e.version) {
                return Some((e.t, e.w));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn pops_in_weight_order_and_skips_stale() {
        let mut h = WeightHeap::default();
        h.push(0, 3.0);
        h.push(1, 1.0);
        h.push(2, 2.0);
        h.push(1, 5.0); // re-weighted: the 1.0 entry is stale
        h.invalidate(2);
        let order: Vec<u32> = std::iter::from_fn(|| h.pop().map(|e| e.0)).collect();
        assert_eq!(order, vec![0, 1]);
    }
}

//! Small shared helpers below the geometry kernel: the [`NONE`] sentinel of index tables and
//! [`sorted3`], the canonical key of a triangle. Inside the crate this family also holds the id
//! hasher and its maps, the seeded generators and the Hilbert curve keys (crate-private engine
//! pieces). No module defines its own copy of these.

mod hash;
pub(crate) mod hilbert;
mod rng;

#[cfg(test)]
pub(crate) use hash::IdHasher;
pub(crate) use hash::{IdMap, IdSet, KeyedIdState};
pub(crate) use rng::{Rng, Rng32};

/// The "no index" sentinel of every `u32` index table (no neighbour, no part, no tetrahedron, …).
///
/// ```
/// use morpho::util::NONE;
/// let neighbours = [3u32, NONE, 7];
/// assert_eq!(neighbours.iter().filter(|&&n| n != NONE).count(), 2);
/// ```
pub const NONE: u32 = u32::MAX;

/// The three ids in increasing order: the canonical key of an unoriented triangle.
///
/// ```
/// assert_eq!(morpho::util::sorted3([5, 1, 3]), [1, 3, 5]);
/// ```
#[inline]
pub fn sorted3(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sorted3_sorts_every_permutation() {
        for t in [
            [1, 2, 3],
            [1, 3, 2],
            [2, 1, 3],
            [2, 3, 1],
            [3, 1, 2],
            [3, 2, 1],
        ] {
            assert_eq!(sorted3(t), [1, 2, 3]);
        }
        assert_eq!(sorted3([4, 4, 0]), [0, 4, 4]);
    }
}

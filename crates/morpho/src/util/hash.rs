//! One fast hasher for the hash maps of the library: [`IdHasher`], a folded 64×64→128-bit
//! multiply per 64-bit word (the low and high halves of the product xored), which mixes every
//! input bit into every output bit in one multiplication. That matters for keys whose
//! information sits in the high bits only — the bit patterns of small integer-valued floats
//! (2.0 is `0x4000_0000_0000_0000`) — where a plain multiplicative hash leaves the low bits,
//! and so the table's bucket index, all zero.
//!
//! [`IdMap`]/[`IdSet`] use it unkeyed (state 0, a fixed odd multiplier): for ids the library
//! makes itself (vertex, edge, triangle and cell ids). Keys read from a file that an adversary
//! may write (the STL vertex-welding map) use [`KeyedIdState`], the same hasher with a secret
//! random starting state and multiplier, so that colliding keys cannot be prepared in advance.

use std::collections::hash_map::RandomState;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasher, BuildHasherDefault, Hasher};

/// The fixed multiplier of the unkeyed hasher (2⁶⁴/φ, odd).
const MUL: u64 = 0x9e37_79b9_7f4a_7c15;

/// The folded multiply: the xor of the two halves of the 128-bit product.
#[inline(always)]
fn fold(a: u64, b: u64) -> u64 {
    let m = (a as u128) * (b as u128);
    (m as u64) ^ ((m >> 64) as u64)
}

/// The library's hasher (see the module documentation). `Default` gives the unkeyed hasher of
/// [`IdMap`]/[`IdSet`]; [`KeyedIdState`] gives keyed ones. Not a cryptographic hash.
#[derive(Clone, Copy, Debug)]
pub struct IdHasher {
    h: u64,
    k: u64,
}

impl Default for IdHasher {
    #[inline]
    fn default() -> Self {
        IdHasher { h: 0, k: MUL }
    }
}

impl Hasher for IdHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        // eight bytes at a time ([u32; 3] keys hash their 12 bytes in one call); a partial
        // last word carries its length, so that trailing zero bytes are not lost
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(c);
            self.write_u64(u64::from_le_bytes(w));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut w = [0u8; 8];
            w[..rest.len()].copy_from_slice(rest);
            self.write_u64(u64::from_le_bytes(w) ^ ((rest.len() as u64) << 59));
        }
    }
    #[inline]
    fn write_u32(&mut self, x: u32) {
        self.write_u64(x as u64);
    }
    #[inline]
    fn write_u64(&mut self, x: u64) {
        self.h = fold(self.h ^ x, self.k);
    }
    #[inline]
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.h
    }
}

/// A `HashMap` with the unkeyed [`IdHasher`] (for ids the library makes itself).
pub type IdMap<K, V> = HashMap<K, V, BuildHasherDefault<IdHasher>>;
/// A `HashSet` with the unkeyed [`IdHasher`].
pub type IdSet<K> = HashSet<K, BuildHasherDefault<IdHasher>>;

/// Builds keyed [`IdHasher`]s: a starting state and an odd multiplier drawn from std's
/// [`RandomState`] (different per map and per run), for keys that come from input files.
#[derive(Clone, Debug)]
pub struct KeyedIdState {
    k0: u64,
    k1: u64,
}

impl KeyedIdState {
    /// Fresh random keys.
    pub fn new() -> Self {
        let s = RandomState::new();
        KeyedIdState {
            k0: s.hash_one(0x5354_4c31u64),
            k1: s.hash_one(0x5354_4c32u64) | 1,
        }
    }
}

impl Default for KeyedIdState {
    fn default() -> Self {
        Self::new()
    }
}

impl BuildHasher for KeyedIdState {
    type Hasher = IdHasher;
    #[inline]
    fn build_hasher(&self) -> IdHasher {
        IdHasher {
            h: self.k0,
            k: self.k1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::Hash;

    fn hash_of<T: Hash>(x: &T) -> u64 {
        let mut h = IdHasher::default();
        x.hash(&mut h);
        h.finish()
    }

    /// Keys that differ only in their high bits (integer-valued float coordinates, ids
    /// shifted into the high half of an edge key) still spread over the low bits that pick
    /// the bucket: among 4096 keys, the low 12 bits take most of their 4096 values.
    #[test]
    fn high_bit_keys_spread_over_the_low_bits() {
        let float_keys: Vec<(u64, u64, u64)> = (0..16)
            .flat_map(|x| (0..16).flat_map(move |y| (0..16).map(move |z| (x, y, z))))
            .map(|(x, y, z)| {
                let b = |v: i32| (v as f64).to_bits();
                (b(x), b(y), b(z))
            })
            .collect();
        let edge_keys: Vec<u64> = (0..4096u64).map(|a| a << 32 | (a + 1)).collect();
        let spread = |hs: Vec<u64>| {
            let mut low: Vec<u64> = hs.iter().map(|h| h & 4095).collect();
            low.sort_unstable();
            low.dedup();
            low.len()
        };
        // a uniform hash leaves about 4096·(1 − 1/e) ≈ 2589 distinct values
        assert!(spread(float_keys.iter().map(hash_of).collect()) > 2300);
        assert!(spread(edge_keys.iter().map(hash_of).collect()) > 2300);
        // and the high 7 bits (hashbrown's control byte) vary as well
        let mut top: Vec<u64> = float_keys.iter().map(|k| hash_of(k) >> 57).collect();
        top.sort_unstable();
        top.dedup();
        assert!(top.len() > 100);
    }

    #[test]
    fn keyed_hashers_differ_but_agree_on_equal_keys() {
        let (a, b) = (KeyedIdState::new(), KeyedIdState::new());
        let k = (1.5f64.to_bits(), 0u64, 7u64);
        assert_eq!(a.hash_one(k), a.hash_one(k));
        assert_ne!(a.hash_one(k), b.hash_one(k));
        let mut s: IdSet<[u32; 3]> = IdSet::default();
        assert!(s.insert([1, 2, 3]) && !s.insert([1, 2, 3]) && s.insert([1, 2, 4]));
    }
}

/// The examples of this crate-private module (run as unit tests, since doc-tests only see
/// the public API).
#[cfg(test)]
mod examples {
    #[test]
    fn example_1() {
        use crate::util::IdMap;
        let mut m: IdMap<[u32; 3], u32> = IdMap::default();
        m.insert([1, 2, 3], 7);
        assert_eq!(m.get(&[1, 2, 3]), Some(&7));
    }
    #[test]
    fn example_2() {
        use crate::util::KeyedIdState;
        use std::collections::HashMap;
        let mut m: HashMap<(u64, u64, u64), u32, KeyedIdState> =
            HashMap::with_hasher(KeyedIdState::new());
        m.insert((2.0f64.to_bits(), 0, 1), 0);
        assert!(m.contains_key(&(2.0f64.to_bits(), 0, 1)));
    }
}

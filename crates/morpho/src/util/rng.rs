//! Small deterministic generators (Marsaglia 2003, "Xorshift RNGs", J. Stat. Softw. 8(14)):
//! reproducible pseudo-random choices inside the algorithms (walk directions, insertion order
//! shuffles). Not for statistics and not for anything an adversary may predict.
//!
//! Two widths, because the triangulations' outputs depend on the exact sequences they were
//! written with: [`Rng`] is the 64-bit generator with shifts (13, 7, 17) of the 3D and dD
//! constructions and the 2D insertion-order shuffle; [`Rng32`] the 32-bit one with shifts
//! (13, 17, 5) of the 2D point-location walks.

/// Marsaglia's 64-bit xorshift generator, shifts (13, 7, 17).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rng(u64);

impl Rng {
    /// A generator with state `seed`. The state must not be 0 (xorshift stays at 0 forever), so
    /// 0 is replaced by a fixed odd constant.
    #[inline]
    pub const fn new(seed: u64) -> Self {
        Rng(if seed == 0 {
            0x9e37_79b9_7f4a_7c15
        } else {
            seed
        })
    }

    /// The next 64-bit value (the new state).
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }

    /// The next value as a double uniform in [0, 1): the top 53 bits of [`Rng::next_u64`]
    /// over 2⁵³ (the unit tests' random coordinates).
    #[cfg(test)]
    #[inline]
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next value reduced modulo `n` (`n > 0`; slightly biased for `n` not a power of two,
    /// which does not matter for the choices it makes).
    #[inline]
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

/// Marsaglia's 32-bit xorshift generator, shifts (13, 17, 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rng32(u32);

impl Rng32 {
    /// A generator with state `seed` (0 is replaced by a fixed odd constant).
    #[inline]
    pub const fn new(seed: u32) -> Self {
        Rng32(if seed == 0 { 0x9e37_79b9 } else { seed })
    }

    /// The next 32-bit value (the new state).
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sequences the callers were written with (the first values of the copies this
    /// module replaced, computed by hand-unrolled shifts).
    #[test]
    fn sequences_are_the_classic_xorshifts() {
        let step64 = |mut x: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let step32 = |mut x: u32| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        };
        let (mut r, mut x) = (Rng::new(0x2545_F491_4F6C_DD1D), 0x2545_F491_4F6C_DD1Du64);
        let (mut r32, mut y) = (Rng32::new(0x2545_f491), 0x2545_f491u32);
        for _ in 0..1000 {
            x = step64(x);
            y = step32(y);
            assert_eq!(r.next_u64(), x);
            assert_eq!(r32.next_u32(), y);
        }
        // Marsaglia's published first output of xorshift32 from 2463534242
        assert_eq!(Rng32::new(2_463_534_242).next_u32(), 723_471_715);
        // never stuck at zero
        assert_ne!(Rng::new(0).next_u64(), 0);
        assert_ne!(Rng32::new(0).next_u32(), 0);
    }
}

/// The examples of this crate-private module (run as unit tests, since doc-tests only see
/// the public API).
#[cfg(test)]
mod examples {
    #[test]
    fn example_1() {
        use crate::util::Rng;
        let mut a = Rng::new(42);
        let mut b = Rng::new(42);
        assert_eq!(a.next_u64(), b.next_u64()); // same seed, same sequence
        assert!(a.below(6) < 6);
    }
    #[test]
    fn example_2() {
        use crate::util::Rng32;
        let mut r = Rng32::new(0x9e37_79b9);
        let first = r.next_u32();
        assert_ne!(first, 0x9e37_79b9);
    }
}

//! Hilbert curve keys of grid cells: sorting points by the key of their cell puts points that
//! are close in space close in the order (the insertion orders of the Delaunay
//! constructions, Amenta, Choi & Rote 2003 "Incremental constructions con BRIO").

/// Bits per axis of [`hilbert2`].
pub const HILBERT2_BITS: u32 = 16;

/// Hilbert curve index of the 2D cell (x, y), each coordinate < 2^[`HILBERT2_BITS`] (the
/// classic quadrant-rotation algorithm, written without data-dependent branches).
#[inline]
pub fn hilbert2(mut x: u32, mut y: u32) -> u32 {
    let mask = (1u32 << HILBERT2_BITS) - 1;
    let mut d: u32 = 0;
    let mut s = 1u32 << (HILBERT2_BITS - 1);
    while s > 0 {
        let rx = ((x & s) != 0) as u32;
        let ry = ((y & s) != 0) as u32;
        d += s * s * ((3 * rx) ^ ry);
        // if ry == 0: reflect when rx == 1, then swap x and y
        let flip = 0u32.wrapping_sub(rx & (ry ^ 1)) & mask;
        x ^= flip;
        y ^= flip;
        let swap = (x ^ y) & 0u32.wrapping_sub(ry ^ 1);
        x ^= swap;
        y ^= swap;
        s >>= 1;
    }
    d
}

/// 3D Hilbert index of integer coordinates with `bits` bits each (1 ≤ `bits` ≤ 21; Skilling
/// 2004, "Programming the Hilbert curve", transpose method).
pub fn hilbert3(mut x: [u32; 3], bits: u32) -> u64 {
    let m = 1u32 << (bits - 1);
    let mut q = m;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            if x[i] & q != 0 {
                x[0] ^= p;
            } else {
                let t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
        q >>= 1;
    }
    for i in 1..3 {
        x[i] ^= x[i - 1];
    }
    let mut t = 0;
    q = m;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    for xi in x.iter_mut() {
        *xi ^= t;
    }
    let mut h = 0u64;
    for b in (0..bits).rev() {
        for xi in x {
            h = (h << 1) | ((xi >> b) & 1) as u64;
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert2_is_a_bijection_along_which_cells_are_neighbours() {
        let mut seen = std::collections::HashSet::new();
        for x in 0..64 {
            for y in 0..64 {
                seen.insert(hilbert2(x << 10, y << 10) >> 20);
            }
        }
        assert_eq!(seen.len(), 4096);
        let mut cells: Vec<(u32, i32, i32)> = (0..64 * 64)
            .map(|k| {
                let (x, y) = (k % 64, k / 64);
                (hilbert2(x << 10, y << 10) >> 20, x as i32, y as i32)
            })
            .collect();
        cells.sort();
        for w in cells.windows(2) {
            assert_eq!((w[0].1 - w[1].1).abs() + (w[0].2 - w[1].2).abs(), 1);
        }
    }

    #[test]
    fn hilbert3_is_a_bijection_along_which_cells_are_neighbours() {
        let mut cells: Vec<(u64, [i32; 3])> = Vec::new();
        for x in 0..8 {
            for y in 0..8 {
                for z in 0..8 {
                    cells.push((hilbert3([x, y, z], 3), [x as i32, y as i32, z as i32]));
                }
            }
        }
        cells.sort_unstable();
        assert!(cells.iter().enumerate().all(|(i, c)| c.0 == i as u64));
        for w in cells.windows(2) {
            let d: i32 = (0..3).map(|k| (w[0].1[k] - w[1].1[k]).abs()).sum();
            assert_eq!(d, 1);
        }
    }
}

/// The examples of this crate-private module (run as unit tests, since doc-tests only see
/// the public API).
#[cfg(test)]
mod examples {
    #[test]
    fn example_1() {
        use crate::util::hilbert::hilbert2;
        // the curve starts at the origin cell; the key is a bijection of the grid
        assert_eq!(hilbert2(0, 0), 0);
        assert_ne!(hilbert2(1, 0), hilbert2(0, 1));
    }
    #[test]
    fn example_2() {
        use crate::util::hilbert::hilbert3;
        assert_eq!(hilbert3([0, 0, 0], 4), 0);
        assert!(hilbert3([15, 15, 15], 4) < 1 << 12);
    }
}

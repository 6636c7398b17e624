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

/// Size of a transparent huge page on x86-64 and aarch64 Linux (2 MiB).
const HUGE_PAGE: usize = 2 << 20;

/// The whole huge pages inside the byte range `start..start + bytes`, as (first byte, length),
/// or `None` when the range holds fewer than two (a hint would then save little and could
/// round a small buffer's memory up to 2 MiB). Never reaches outside the range.
pub(crate) fn huge_page_span(start: usize, bytes: usize) -> Option<(usize, usize)> {
    let end = start.checked_add(bytes)?;
    let lo = start.checked_next_multiple_of(HUGE_PAGE)?;
    let hi = end / HUGE_PAGE * HUGE_PAGE;
    (hi >= lo && hi - lo >= 2 * HUGE_PAGE).then_some((lo, hi - lo))
}

/// Asks the kernel to back the not yet touched capacity of a large buffer with transparent
/// huge pages (`madvise(MADV_HUGEPAGE)` on the whole huge pages inside the allocation): one
/// page fault per 2 MiB instead of per 4 KiB when the buffer is first written (issue 23 item 4:
/// page faults were a fifth of `morpho isosurface`'s CPU). Only a hint: the contents never
/// change, the call may fail (kernels without THP, `never` mode) and is then ignored; memory
/// beyond the written part of a huge page is committed, so call it on buffers that will be
/// filled (a few MiB of slack at most). Call it again after a reallocation. No-op off Linux.
pub(crate) fn advise_huge_pages<T>(v: &mut Vec<T>) {
    #[cfg(target_os = "linux")]
    {
        let bytes = v.capacity().saturating_mul(std::mem::size_of::<T>());
        if let Some((lo, len)) = huge_page_span(v.as_mut_ptr() as usize, bytes) {
            // SAFETY: `lo..lo + len` lies inside the Vec's allocation (`huge_page_span`), which
            // we own; MADV_HUGEPAGE only changes how the kernel backs those pages, never their
            // contents, so no Rust-visible memory changes.
            unsafe {
                libc::madvise(lo as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = v;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_page_span_stays_inside_the_range() {
        let h = HUGE_PAGE;
        // brute force over starts and lengths around page boundaries
        for start in [0, 1, 4096, h - 1, h, h + 1, 3 * h - 4096, 7 * h + 12345] {
            for bytes in [
                0,
                1,
                h,
                2 * h - 1,
                2 * h,
                3 * h - 1,
                3 * h,
                4 * h + 1,
                9 * h + 7,
            ] {
                match huge_page_span(start, bytes) {
                    Some((lo, len)) => {
                        assert!(lo >= start && lo + len <= start + bytes, "{start} {bytes}");
                        assert!(lo % h == 0 && len % h == 0 && len >= 2 * h);
                        // and it is the largest such span
                        assert!(lo < start + h && start + bytes - (lo + len) < h);
                    }
                    None => {
                        let lo = start.div_ceil(h) * h;
                        assert!((start + bytes) / h * h < lo + 2 * h, "{start} {bytes}");
                    }
                }
            }
        }
        assert_eq!(huge_page_span(usize::MAX - 5, 10), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn advise_huge_pages_keeps_the_contents_and_marks_the_mapping() {
        let mut v: Vec<u64> = (0..3_000_000u64).collect();
        let want: u64 = v.iter().sum();
        advise_huge_pages(&mut v);
        v.resize(4_000_000, 7);
        assert_eq!(v[..3_000_000].iter().sum::<u64>(), want);
        assert!(v[3_000_000..].iter().all(|&x| x == 7));
        // the mapping holding the buffer's middle carries the hint ("hg" in VmFlags) when the
        // kernel offers THP at all
        let thp = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled")
            .is_ok_and(|s| !s.contains("[never]"));
        let mut small: Vec<u8> = vec![0; 100];
        advise_huge_pages(&mut small); // too small: nothing to do, no failure
        if !thp {
            return;
        }
        let mut w: Vec<u64> = Vec::with_capacity(1 << 21); // 16 MiB
        advise_huge_pages(&mut w);
        let mid = w.as_ptr() as usize + (1 << 23);
        let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap_or_default();
        let mut inside = false;
        let mut flagged = None;
        for line in smaps.lines() {
            if let Some((range, _)) = line.split_once(' ') {
                if let Some((a, b)) = range.split_once('-') {
                    if let (Ok(a), Ok(b)) =
                        (usize::from_str_radix(a, 16), usize::from_str_radix(b, 16))
                    {
                        inside = a <= mid && mid < b;
                        continue;
                    }
                }
            }
            if inside && line.starts_with("VmFlags:") {
                flagged = Some(line.split_whitespace().any(|f| f == "hg"));
            }
        }
        assert_eq!(
            flagged,
            Some(true),
            "no MADV_HUGEPAGE on the buffer's mapping"
        );
        w.push(1);
    }

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

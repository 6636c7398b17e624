//! How much memory a reader may allocate (issue 17 item 7): a limit from what the machine
//! has, checked against an estimate **before** the allocation, so a small compressed file
//! that claims a huge volume or decompresses into gigabytes of text fails at once with an
//! `error:` naming the limit, instead of exhausting memory.
//!
//! The limit is, in this order: the value given to [`set_limit`] (the CLI's `--memory-limit`),
//! the environment variable `MORPHO_MEMORY_LIMIT` (bytes, or with a `K`, `M`, `G`, `T` suffix,
//! powers of 1024), else three quarters of the memory the machine has — on Linux the smaller of
//! the physical memory and the cgroup limit (`/sys/fs/cgroup/memory.max`), elsewhere 8 GiB.
//!
//! Estimates are deliberately pessimistic and simple:
//! - a whole-file read (points, meshes, polygons) holds the (decompressed) bytes and what is
//!   parsed from them: at most [`PARSE_FACTOR`] times the bytes in all (measured worst case:
//!   a gzipped CSV of `0,0` rows, 1 GiB of text, peaked at 15.8 GB — 59 bytes per 4-byte row);
//! - a volume holds its samples as `f32` plus the file's sample bytes while decoding.

use crate::{Error, Result};
use std::sync::atomic::{AtomicU64, Ordering};

/// Peak bytes held per byte of a whole-file read, the bytes themselves included (the measured
/// worst case of the text readers, see the module documentation).
pub const PARSE_FACTOR: u64 = 16;

/// 0: not set by [`set_limit`].
static LIMIT: AtomicU64 = AtomicU64::new(0);

/// Sets the memory limit in bytes for the rest of the program (0 restores the default).
pub fn set_limit(bytes: u64) {
    LIMIT.store(bytes, Ordering::SeqCst);
}

/// The memory limit in bytes (see the module documentation for where it comes from).
pub fn limit() -> u64 {
    match LIMIT.load(Ordering::SeqCst) {
        0 => std::env::var("MORPHO_MEMORY_LIMIT")
            .ok()
            .and_then(|v| parse_size(&v))
            .filter(|&b| b > 0)
            .unwrap_or_else(default_limit),
        b => b,
    }
}

/// Parses `123`, `512M`, `4G`, `1.5G` (powers of 1024; case-insensitive; an optional `B` or
/// `iB` after the suffix). `None` for anything else.
pub fn parse_size(s: &str) -> Option<u64> {
    let t = s.trim().to_ascii_uppercase();
    let t = t
        .strip_suffix("IB")
        .or_else(|| t.strip_suffix('B'))
        .unwrap_or(&t);
    let (num, shift) = match t.chars().last()? {
        'K' => (&t[..t.len() - 1], 10),
        'M' => (&t[..t.len() - 1], 20),
        'G' => (&t[..t.len() - 1], 30),
        'T' => (&t[..t.len() - 1], 40),
        _ => (t, 0),
    };
    let v: f64 = num.trim().parse().ok()?;
    let bytes = v * (1u64 << shift) as f64;
    (v.is_finite() && v >= 0.0 && bytes < 1.8e19).then_some(bytes as u64)
}

/// Three quarters of the machine's memory (physical, or the cgroup's limit when smaller).
fn default_limit() -> u64 {
    let machine = physical_memory().unwrap_or(8 << 30);
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    let have = cgroup.map_or(machine, |c| c.min(machine));
    have / 4 * 3
}

#[cfg(unix)]
fn physical_memory() -> Option<u64> {
    // SAFETY: sysconf only reads system constants.
    let (pages, size) = unsafe {
        (
            libc::sysconf(libc::_SC_PHYS_PAGES),
            libc::sysconf(libc::_SC_PAGESIZE),
        )
    };
    (pages > 0 && size > 0).then(|| pages as u64 * size as u64)
}

#[cfg(not(unix))]
fn physical_memory() -> Option<u64> {
    None
}

/// Refuses an allocation estimated at `bytes` when it exceeds the limit; `what` says what
/// needs it ("the volume's samples", "the decompressed file").
pub fn check(bytes: u64, what: &str) -> Result<()> {
    let lim = limit();
    if bytes <= lim {
        return Ok(());
    }
    Err(Error::invalid(format!(
        "{what} would need about {}, more than the memory limit of {} \
         (--memory-limit or MORPHO_MEMORY_LIMIT)",
        human(bytes),
        human(lim)
    )))
}

/// The largest number of bytes a whole-file read may decompress to under the limit.
pub fn max_read_bytes() -> u64 {
    limit() / PARSE_FACTOR
}

/// `1.5 GiB`, `300 MiB`, `12 KiB`, `17 B`.
pub fn human(bytes: u64) -> String {
    let units = [(40, "TiB"), (30, "GiB"), (20, "MiB"), (10, "KiB")];
    for (shift, name) in units {
        if bytes >= 1u64 << shift {
            let v = bytes as f64 / (1u64 << shift) as f64;
            return if v >= 10.0 {
                format!("{v:.0} {name}")
            } else {
                format!("{v:.1} {name}")
            };
        }
    }
    format!("{bytes} B")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_powers_of_1024() {
        assert_eq!(parse_size("123"), Some(123));
        assert_eq!(parse_size("4k"), Some(4096));
        assert_eq!(parse_size("512M"), Some(512 << 20));
        assert_eq!(parse_size("1.5GiB"), Some(3 << 29));
        assert_eq!(parse_size("2 GB"), Some(2 << 30));
        assert_eq!(parse_size("-1G"), None);
        assert_eq!(parse_size("lots"), None);
        assert_eq!(parse_size("1e30T"), None);
        assert_eq!(human(3 << 29), "1.5 GiB");
        assert_eq!(human(300 << 20), "300 MiB");
    }

    #[test]
    fn the_default_is_below_the_machine() {
        let d = default_limit();
        assert!(d > 0);
        if let Some(m) = physical_memory() {
            assert!(d < m);
        }
    }
}

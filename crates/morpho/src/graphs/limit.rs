//! How many candidate triples a 3D γ-graph beyond the tetrahedralization may test (issue 17
//! item 8): a documented, overridable bound on the work of [`super::beyond3::beyond_dt_3d`],
//! checked **before** its triple loop, so an input whose enumeration would run for hours
//! fails at once with an `error:` naming the limit (as the memory limit of
//! [`crate::io::memory`] does for allocations).
//!
//! Why a limit and not a faster algorithm: with c < 0 the γ-graph is bounded only by O(N³)
//! triangles (V Lemma 3.4), and it reaches that order — 150 random points of a sphere give
//! 537k of the 551k triples. `beyond_dt_3d` tests the triples of the vertices whose flood
//! region leaves the grid ("open" vertices: near the hull, or anywhere on samples of a
//! surface) without a local bound, Θ(N³) cheap tests on such input, uniform points in a cube
//! included (its module documentation, "Complexity"). The count it checks is exact for its own
//! enumeration (`candidate_triples`, an upper bound of the triples it visits), known after
//! the floods, which cost O(N) cells per vertex.
//!
//! The same limit bounds a second measure, counted while the loop runs: the points it adds to
//! the triples' intervals (`GraphError::TooMuchWork`). On nearly cospherical input (points of a
//! sphere rounded to doubles) every candidate is decided by a scan of every point with near-tie
//! in-sphere tests, so a count of triples under the limit can still mean minutes (300 points:
//! 4.5·10⁶ triples, ≈ 1.3·10⁹ points); the loop stops once the points pass the limit (≈ 17 s
//! of one core there).
//!
//! The limit is, in this order: the value given to [`set_triple_limit`] (the CLI's
//! `graph --max-triples`), the environment variable `MORPHO_TRIPLE_LIMIT` (an integer, `1e9`
//! accepted), else [`DEFAULT_TRIPLE_LIMIT`].

use std::sync::atomic::{AtomicU64, Ordering};

/// The default bound on candidate triples: 10⁸. Measured on this project's machine (AMD EPYC,
/// one core, bench/README "γ beyond the Delaunay triangulation on the fandisk"): 1.7–2.8·10⁻⁷ s
/// per candidate triple of surface samples (400 points: 1.06·10⁷ triples in 2.95 s; 1 600
/// points: 6.8·10⁸ in 114 s), so the default admits about 20–30 s of one core (half that on
/// two) and refuses the whole fandisk (6 475 points, 4.5·10¹⁰ triples, about two hours).
pub const DEFAULT_TRIPLE_LIMIT: u64 = 100_000_000;

/// 0: not set by [`set_triple_limit`].
static LIMIT: AtomicU64 = AtomicU64::new(0);

/// Sets the candidate-triple limit for the rest of the program (0 restores the default).
pub fn set_triple_limit(triples: u64) {
    LIMIT.store(triples, Ordering::SeqCst);
}

/// The candidate-triple limit (see the module documentation for where it comes from).
pub fn triple_limit() -> u64 {
    match LIMIT.load(Ordering::SeqCst) {
        0 => std::env::var("MORPHO_TRIPLE_LIMIT")
            .ok()
            .and_then(|v| parse_count(&v))
            .unwrap_or(DEFAULT_TRIPLE_LIMIT),
        t => t,
    }
}

/// Parses a positive count: `123`, `1e9`, `2.5e8` (rounded down). `None` for anything else,
/// zero, negative, NaN or beyond `u64`.
pub fn parse_count(s: &str) -> Option<u64> {
    let t = s.trim();
    if let Ok(v) = t.parse::<u64>() {
        return (v > 0).then_some(v);
    }
    let v: f64 = t.parse().ok()?;
    (v.is_finite() && v >= 1.0 && v < u64::MAX as f64).then_some(v as u64)
}

/// The number of triples (a, b, c), a < b < c, that [`super::beyond3::beyond_dt_3d`]'s loop
/// may visit, from its per-vertex data: for a vertex with `p` partners, of which `q` are open
/// vertices above it, and `o` open vertices above it in all, the pairs (b, c) with b, c both
/// partners, plus — when the vertex is open — both open: `C(p,2) + C(o,2) − C(q,2)`.
pub(crate) fn triples_of_vertex(
    partners: u64,
    open_above: u64,
    open_partners: u64,
    open: bool,
) -> u64 {
    let c2 = |k: u64| k * k.saturating_sub(1) / 2;
    let mut t = c2(partners);
    if open {
        t = t.saturating_add(c2(open_above) - c2(open_partners));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_parse_and_refuse_garbage() {
        assert_eq!(parse_count("123"), Some(123));
        assert_eq!(parse_count(" 1e9 "), Some(1_000_000_000));
        assert_eq!(parse_count("2.5e8"), Some(250_000_000));
        for bad in ["0", "-5", "x", "", "nan", "inf", "1e30", "0.5"] {
            assert_eq!(parse_count(bad), None, "{bad}");
        }
    }

    /// The per-vertex count against enumerating the pairs.
    #[test]
    fn vertex_count_is_the_enumerated_pairs() {
        // vertex 0; others 1..=12: partners {1,2,3,5,8,9}, open {2,3,4,6,8,10,11}
        let partners = [1u32, 2, 3, 5, 8, 9];
        let open = [2u32, 3, 4, 6, 8, 10, 11];
        for a_open in [false, true] {
            let mut pairs = 0u64;
            for b in 1..=12u32 {
                for c in b + 1..=12 {
                    let both_p = partners.contains(&b) && partners.contains(&c);
                    let both_o = a_open && open.contains(&b) && open.contains(&c);
                    pairs += u64::from(both_p || both_o);
                }
            }
            let q = partners.iter().filter(|b| open.contains(b)).count() as u64;
            assert_eq!(triples_of_vertex(6, 7, q, a_open), pairs);
        }
    }
}

//! Oracle tests of the γ machinery against the literal definitions, and the inclusion hierarchy
//! of Veltkamp Fig. 3.2 with Lemmas 3.1–3.3.
//!
//! Size (over 800 lines): test code only (oracles and property tests of the whole family).

use super::brute::*;
use super::gamma::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeSet;

fn random_2d(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| [r.gen::<f64>(), r.gen::<f64>()]).collect()
}

fn random_3d(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| [r.gen::<f64>(), r.gen::<f64>(), r.gen::<f64>()])
        .collect()
}

fn grid_2d(k: usize) -> Vec<[f64; 2]> {
    (0..k * k)
        .map(|i| [(i % k) as f64, (i / k) as f64])
        .collect()
}

/// The 12 points with integer coordinates on the circle x² + y² = 25 (cocircular test data,
/// shared with the other modules' unit tests).
pub(super) const CIRCLE5: [[f64; 2]; 12] = [
    [5., 0.],
    [4., 3.],
    [3., 4.],
    [0., 5.],
    [-3., 4.],
    [-4., 3.],
    [-5., 0.],
    [-4., -3.],
    [-3., -4.],
    [0., -5.],
    [3., -4.],
    [4., -3.],
];

fn circle_2d(n: usize) -> Vec<[f64; 2]> {
    // the first n points on the circle x² + y² = 25 with integer coordinates
    CIRCLE5[..n.min(12)].to_vec()
}

/// Parameter pairs with |c0| ≤ |c1| covering every case of Def. 3.1.
const PARAMS: [(f64, f64); 16] = [
    (0.0, 0.0),
    (-1.0, 1.0),
    (1.0, 1.0),
    (-1.0, -1.0),
    (0.3, 0.5),
    (-0.2, 0.4),
    (0.2, -0.4),
    (-0.3, -0.3),
    (0.0, -0.5),
    (0.0, 0.6),
    (-0.5, 0.5),
    (0.5, -0.5),
    (0.1, 0.1),
    (-0.9, -0.95),
    (0.25, -0.25),
    (0.7, 0.9),
];

fn set2(v: Vec<[u32; 2]>) -> BTreeSet<[u32; 2]> {
    v.into_iter().collect()
}

fn via_values_2d(p: &[[f64; 2]], c0: f64, c1: f64) -> BTreeSet<[u32; 2]> {
    gamma_values_2d(p)
        .into_iter()
        .filter(|(_, v)| in_gamma(*v, c0, c1))
        .map(|(e, _)| e)
        .collect()
}

#[test]
fn gamma_values_and_lemmas_match_the_definition_2d() {
    let mut sets = vec![grid_2d(4), circle_2d(12)];
    for s in 0..6 {
        sets.push(random_2d(18, s));
    }
    // collinear triples
    sets.push(vec![
        [0., 0.],
        [1., 0.],
        [2., 0.],
        [0., 1.],
        [1., 2.],
        [3., 1.],
        [2., 2.],
    ]);
    for p in &sets {
        for &(c0, c1) in &PARAMS {
            let def = set2(gamma_2d_def(p, c0, c1));
            let fast = via_values_2d(p, c0, c1);
            assert_eq!(def, fast, "γ({c0}, {c1}) on {p:?}");
        }
    }
}

#[test]
fn interval_emptiness_matches_definition_for_each_side_2d() {
    for s in 0..4 {
        let p = random_2d(14, 100 + s);
        for i in 0..p.len() {
            for j in i + 1..p.len() {
                let iv = center_interval_2d(&p, i, j);
                for &(c0, c1) in &PARAMS {
                    for side in [1.0, -1.0] {
                        let def = !(0..p.len()).any(|x| {
                            x != i && x != j && def_contains_2d(p[i], p[j], c0, c1, side, p[x])
                        });
                        assert_eq!(
                            iv.neighborhood_empty(c0, c1, side),
                            def,
                            "edge {i},{j} γ({c0},{c1}) side {side}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn gamma_values_and_lemmas_match_the_definition_3d() {
    let mut sets = vec![];
    for s in 0..3 {
        sets.push(random_3d(10, s));
    }
    // cube corners plus centre: cospherical and coplanar
    let mut cube: Vec<[f64; 3]> = (0..8)
        .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
        .collect();
    cube.push([0.5, 0.5, 0.5]);
    sets.push(cube);
    for p in &sets {
        for &(c0, c1) in &PARAMS {
            let def: BTreeSet<[u32; 3]> = gamma_3d_def(p, c0, c1).into_iter().collect();
            let fast: BTreeSet<[u32; 3]> = gamma_values_3d(p)
                .into_iter()
                .filter(|(_, v)| in_gamma(*v, c0, c1))
                .map(|(t, _)| t)
                .collect();
            assert_eq!(def, fast, "3D γ({c0}, {c1})");
        }
    }
}

#[test]
fn special_gamma_graphs_2d() {
    for s in 0..5 {
        let p = random_2d(25, 7 + s);
        assert_eq!(
            via_values_2d(&p, 0.0, 0.0),
            set2(gabriel(&p)),
            "γ(0,0) = GG"
        );
        assert_eq!(
            via_values_2d(&p, -1.0, 1.0),
            set2(hull_2d(&p)),
            "γ(−1,1) = CH"
        );
        assert_eq!(
            via_values_2d(&p, 1.0, -1.0),
            set2(hull_2d(&p)),
            "γ(1,−1) = CH"
        );
        assert!(via_values_2d(&p, 1.0, 1.0).is_empty(), "γ(1,1) empty");
        assert_eq!(
            via_values_2d(&p, -1.0, -1.0).len(),
            25 * 24 / 2,
            "γ(−1,−1) complete"
        );
        // DT ⊆ γ([-1,1],[c,1]) for c ≤ 0, growing as c decreases (Lemma 3.3)
        let vals = gamma_values_2d(&p);
        let range = |c: f64| -> BTreeSet<[u32; 2]> {
            vals.iter()
                .filter(|(_, v)| in_gamma_range(*v, [-1.0, 1.0, c, 1.0]))
                .map(|(e, _)| *e)
                .collect()
        };
        let dt = range(0.0);
        // a triangulation of n points with h hull vertices has 3n − 3 − h edges
        let h = set2(hull_2d(&p)).len();
        assert_eq!(
            dt.len(),
            3 * 25 - 3 - h,
            "γ([-1,1],[0,1]) = DT in general position"
        );
        let mut prev = dt;
        for c in [-0.1, -0.2, -0.5, -1.0] {
            let g = range(c);
            assert!(prev.is_subset(&g));
            prev = g;
        }
        assert_eq!(prev.len(), 25 * 24 / 2);
        // complement of DT = γ([-1,1],[-1,0]) (V §3.4), here without ties
        let comp = range(-1.0).difference(&range(0.0)).count();
        let direct: usize = vals
            .iter()
            .filter(|(_, v)| in_gamma_range(*v, [-1.0, 1.0, -1.0, -1e-300]))
            .count();
        assert_eq!(comp, direct);
    }
}

#[test]
fn inclusion_hierarchy_2d_and_3d() {
    for s in 0..6 {
        let p = random_2d(40, 50 + s);
        let cp = set2(closest_pairs(&p));
        let nng = set2(nng(&p));
        let emst = set2(emst(&p));
        let rng_ = set2(rng(&p));
        let gg = set2(gabriel(&p));
        let dt = via_values_2d(&p, -1.0, 0.0)
            .union(&via_values_2d(&p, 0.0, 0.0))
            .cloned()
            .collect::<BTreeSet<_>>();
        assert!(cp.is_subset(&nng));
        assert!(nng.is_subset(&emst));
        assert!(emst.is_subset(&rng_));
        assert!(rng_.is_subset(&gg));
        assert!(gg.is_subset(&dt));
        assert!(nng.is_subset(&set2(sig(&p))));
        assert!(
            set2(strip(&p)).is_subset(&emst),
            "∞-SG ⊆ EMST in general position"
        );
        // β_l reduces to GG, RNG, ∞-SG (Def. 2.16 remarks)
        assert_eq!(set2(beta_lune(&p, 0.0)), gg);
        assert_eq!(set2(beta_lune(&p, 0.5)), rng_);
        assert_eq!(set2(beta_lune(&p, 1.0)), set2(strip(&p)));
        // β_c(b) = γ(b, b), and β_l(b) = β_c(b) for b < 0
        for b in [-0.6, -0.2] {
            assert_eq!(set2(beta_circle_2d(&p, b)), via_values_2d(&p, b, b));
        }
        // α-shapes: a = 0 is the hull, a < 0 (empty discs) inside DT, a > 0 on hull vertices
        assert_eq!(set2(alpha_2d(&p, 0.0)), set2(hull_2d(&p)));
        assert!(set2(alpha_2d(&p, -3.0)).is_subset(&dt));
    }
    for s in 0..3 {
        let p = random_3d(14, 80 + s);
        let nng = set2(nng(&p));
        let emst = set2(emst(&p));
        let rng_ = set2(rng(&p));
        let gg = set2(gabriel(&p));
        assert!(set2(closest_pairs(&p)).is_subset(&nng));
        assert!(nng.is_subset(&emst));
        assert!(emst.is_subset(&rng_));
        assert!(rng_.is_subset(&gg));
        assert_eq!(set2(beta_lune(&p, 0.5)), rng_);
        // 3D γ(−1, 1) = CH (triangles)
        let ch: BTreeSet<[u32; 3]> = hull_3d(&p).into_iter().collect();
        let g: BTreeSet<[u32; 3]> = gamma_values_3d(&p)
            .into_iter()
            .filter(|(_, v)| in_gamma(*v, -1.0, 1.0))
            .map(|(t, _)| t)
            .collect();
        assert_eq!(ch, g);
    }
}

#[test]
fn emst_is_a_minimum_spanning_tree() {
    // against brute force over all spanning trees is infeasible; check against Kruskal on all
    // pairs instead (a different algorithm)
    for s in 0..5 {
        let p = random_2d(30, 300 + s);
        let e = emst(&p);
        assert_eq!(e.len(), 29);
        let mut all: Vec<(f64, usize, usize)> = Vec::new();
        for i in 0..30 {
            for j in i + 1..30 {
                let d = ((p[i][0] - p[j][0]).powi(2) + (p[i][1] - p[j][1]).powi(2)).sqrt();
                all.push((d, i, j));
            }
        }
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut parent: Vec<usize> = (0..30).collect();
        fn find(p: &mut Vec<usize>, x: usize) -> usize {
            if p[x] != x {
                let r = find(p, p[x]);
                p[x] = r;
            }
            p[x]
        }
        let mut total = 0.0;
        for (d, i, j) in all {
            let (a, b) = (find(&mut parent, i), find(&mut parent, j));
            if a != b {
                parent[a] = b;
                total += d;
            }
        }
        assert!((length(&p, &e) - total).abs() < 1e-12);
    }
}

#[test]
fn gamma_values_are_the_largest_empty_parameters() {
    // slightly smaller parameters than the γ-values give an empty neighbourhood; a slightly
    // larger c1′ (with the same c0′) gives a non-empty one on both sides
    let eps = 1e-7;
    for s in 0..3 {
        let p = random_2d(15, 900 + s);
        for (e, (a, b)) in gamma_values_2d(&p) {
            let (i, j) = (e[0] as usize, e[1] as usize);
            let iv = center_interval_2d(&p, i, j);
            assert!(a.abs() <= b.abs() + 1e-15);
            let (a2, b2) = (a - eps, b - eps);
            if a2.abs() <= b2.abs() && b2 > -1.0 {
                assert!(
                    iv.neighborhood_empty(a2, b2, 1.0) || iv.neighborhood_empty(a2, b2, -1.0),
                    "edge {e:?} ({a}, {b})"
                );
            }
            let b3 = b + eps;
            if b3 < 1.0 && a.abs() <= b3.abs() && b >= 0.0 {
                assert!(
                    !iv.neighborhood_empty(a, b3, 1.0) && !iv.neighborhood_empty(a, b3, -1.0),
                    "edge {e:?} ({a}, {b})"
                );
            }
        }
    }
}

/// |c| of an offset (`abs_c`) is finite, in [0, 1], monotone in the offset and the inverse of
/// `offset_of` at every scale — including the ~1e300 offsets that a point nearly in the plane
/// of a triangle produces (they used to overflow to NaN and made γ decisions undecidable).
#[test]
fn abs_c_is_finite_monotone_and_inverts_offset_of_at_every_scale() {
    for r in [1e-300, 1e-12, 1.0, 954.8, 4e5, 1e300] {
        let mut prev = -1.0;
        for e in -320..=320 {
            let s = 10f64.powi(e);
            let c = abs_c(s, r);
            assert!((0.0..=1.0).contains(&c), "r {r} s {s}: {c}");
            assert!(c >= prev, "r {r} s {s}: {c} < {prev}");
            assert_eq!(abs_c(-s, r), c);
            prev = c;
        }
        assert_eq!(abs_c(0.0, r), 0.0);
        assert_eq!(abs_c(f64::INFINITY, r), 1.0);
        for c in [1e-9, 0.1, 0.5, 0.9, 0.999] {
            let back = abs_c(offset_of(c, r), r);
            assert!((back - c).abs() <= 1e-12, "r {r} c {c}: {back}");
        }
    }
    assert!(abs_c(4.15e300, 954.8) > 1.0 - 1e-12);
}

/// `CenterInterval::witness_offset`, the acceptance of the γ scans: adding the points in order
/// of distance from the triangle's circumcentre, whenever the next point lies beyond the witness
/// ball, the triangle must be in γ([-1,1],[c,1]) with *all* points added.
/// c is taken just below or just above the triangle's final c₁′ (a radius too small accepts
/// the "just above" cases); random and integer-grid sets (ties), and the acceptances must
/// happen early (before the last point) in many rounds.
#[test]
fn witness_ball_certifies_gamma_membership() {
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let (mut early, mut above_rounds) = (0, 0);
    for round in 0..600 {
        let pts: Vec<[f64; 3]> = if round % 3 == 0 {
            (0..40)
                .map(|_| [0, 0, 0].map(|_: i32| rng.gen_range(-4..=4) as f64))
                .collect()
        } else {
            let spread = if round % 3 == 1 { 1.0 } else { 0.2 };
            let mut v: Vec<[f64; 3]> = (0..3)
                .map(|_| [0, 0, 0].map(|_: i32| rng.gen_range(-0.5..0.5)))
                .collect();
            v.extend((0..40).map(|_| [0, 0, 0].map(|_: i32| rng.gen_range(-3.0..3.0) * spread)));
            v
        };
        let Some(f) = TriFrame::new(pts[0], pts[1], pts[2]) else {
            continue;
        };
        let (m, r2, _) = triangle_circle(pts[0], pts[1], pts[2]).unwrap();
        let dist = |x: [f64; 3]| (0..3).map(|i| (x[i] - m[i]).powi(2)).sum::<f64>().sqrt();
        let mut rest: Vec<(f64, [f64; 3])> = pts[3..]
            .iter()
            .filter(|x| !pts[..3].contains(x))
            .map(|&x| (dist(x), x))
            .collect();
        rest.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut full = f.start();
        for &(_, x) in &rest {
            f.add(&mut full, x);
        }
        let Some((_, c1)) = full.gamma_values() else {
            continue;
        };
        for c in [c1 - 0.01, c1 + 1e-6, c1 + 0.01, -0.3, -0.9] {
            if !(-1.0..=0.0).contains(&c) {
                continue;
            }
            let inside = c1 >= c;
            above_rounds += usize::from(!inside);
            let mut iv = f.start();
            for j in 0..=rest.len() {
                let next = rest.get(j).map_or(f64::INFINITY, |e| e.0);
                // the witness ball B(s) lies in B(m, r·(|s|/ρ₀ + √(1 + (s/ρ₀)²)))
                if let Some(s) = iv.witness_offset(c) {
                    let t = s / iv.r_over_n;
                    let radius = r2.sqrt() * (t.abs() + (1.0 + t * t).sqrt());
                    if radius * (1.0 + 1e-9) < next {
                        assert!(inside, "round {round}: c = {c}, final c1' = {c1}, at {j}");
                        early += usize::from(j < rest.len());
                        break;
                    }
                }
                if let Some(&(_, x)) = rest.get(j) {
                    f.add(&mut iv, x);
                }
            }
        }
    }
    assert!(early > 300 && above_rounds > 300, "{early} {above_rounds}");
}

// ---- 3D γ beyond the Delaunay tetrahedralization (graphs::beyond3) ----

mod beyond3_oracle {
    use super::super::beyond3::beyond_dt_3d;
    use super::super::brute::gamma_values_3d;
    use super::super::fast::{candidates_3d, coords3};
    use super::random_3d;
    use crate::delaunay::d3;
    use crate::geom::Point3;
    use std::collections::{BTreeMap, HashSet};

    /// beyond_dt_3d(c) against the brute force of Thm 3.1 over all triples: same triangles, same
    /// γ-values (up to rounding), for every c.
    pub(super) fn check(pts: &[[f64; 3]], cs: &[f64]) {
        let input: Vec<Point3> = pts.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let d = d3::triangulate(&input).unwrap();
        if d.degenerate.is_some() {
            return;
        }
        let p = coords3(&d);
        let cand = candidates_3d(&d);
        let known: HashSet<[u32; 3]> = cand.triangles.iter().copied().collect();
        let all = gamma_values_3d(&p);
        for &c in cs {
            // c₁′ ≥ c; within 1e-8 of a tie the rounded γ-value cannot tell (e.g. a gap's c₁′
            // that rounds to −0.0 at c = 0, or a γ-value of exactly −0.5 before rounding): the
            // exact oracle decides, as the library does (`TriFrame::c1_at_least`)
            let reaches = |t: [u32; 3], c1: f64| {
                if (c1 - c).abs() < 1e-8 {
                    super::exact_oracle::reaches_3d(&p, t, c).unwrap_or(false)
                } else {
                    c1 > c
                }
            };
            let want: BTreeMap<[u32; 3], (f64, f64)> = all
                .iter()
                .filter(|(t, v)| reaches(*t, v.1) && !known.contains(t))
                .map(|(t, v)| (*t, *v))
                .collect();
            let (tris, ivs) = beyond_dt_3d(&d, &cand, c, u64::MAX).unwrap();
            let mut got = BTreeMap::new();
            for (t, iv) in tris.iter().zip(&ivs) {
                let v = iv.gamma_values().expect("output triangle has γ-values");
                assert!(got.insert(*t, v).is_none(), "duplicate {t:?}");
            }
            let wk: Vec<_> = want.keys().collect();
            let gk: Vec<_> = got.keys().collect();
            assert_eq!(wk, gk, "c = {c}, {} points", p.len());
            for (t, v) in &want {
                let g = got[t];
                assert!(
                    (g.0 - v.0).abs() < 1e-9 && (g.1 - v.1).abs() < 1e-9,
                    "{t:?}: {g:?} vs {v:?}"
                );
            }
        }
    }

    #[test]
    fn beyond_3d_matches_brute_on_random_points() {
        for s in 0..2 {
            check(&random_3d(40, 4000 + s), &[-0.05, -0.2, -0.5, -0.9, -1.0]);
        }
        // a flat, elongated cloud (many near-collinear triangles, circumcentres far away)
        let mut flat = random_3d(30, 4100);
        for q in flat.iter_mut() {
            q[0] *= 6.0;
            q[2] *= 0.05;
        }
        check(&flat, &[-0.05, -0.5]);
    }

    /// Integer points with x² + y² + z² = 25 (30 of them).
    pub(super) fn sphere_lattice() -> Vec<[f64; 3]> {
        let mut v = Vec::new();
        for x in -5i32..=5 {
            for y in -5i32..=5 {
                for z in -5i32..=5 {
                    if x * x + y * y + z * z == 25 {
                        v.push([x as f64, y as f64, z as f64]);
                    }
                }
            }
        }
        v
    }

    #[test]
    fn beyond_3d_matches_brute_on_degenerate_sets() {
        let cs = [-0.05, -0.5];
        // integer grid (cospherical and coplanar everywhere)
        let grid: Vec<[f64; 3]> = (0..36)
            .map(|i| [(i % 4) as f64, ((i / 4) % 3) as f64, (i / 12) as f64])
            .collect();
        check(&grid, &cs);
        // points on a sphere lattice, with and without the centre
        let mut sph = sphere_lattice();
        assert_eq!(sph.len(), 30);
        check(&sph, &cs);
        sph.push([0.0, 0.0, 0.0]);
        sph.push([1.0, 1.0, 1.0]);
        check(&sph, &cs);
    }

    /// Integer points with x² + y² + z² = 50 (84 of them) times `scale`, rounded, then scaled by
    /// the power of two that `graph_3d` applies at extreme scales: no longer exactly cospherical
    /// (the rounding moves them by ~1e-16 relative; points with the same coordinate magnitudes
    /// stay on one sphere), so every in-sphere test is nearly or exactly degenerate.
    pub(super) fn rounded_sphere(scale: f64, max: usize) -> Vec<[f64; 3]> {
        let mut v = Vec::new();
        for x in -8i32..=8 {
            for y in -8i32..=8 {
                for z in -8i32..=8 {
                    if x * x + y * y + z * z == 50 {
                        v.push([x as f64, y as f64, z as f64].map(|c| c * scale));
                    }
                }
            }
        }
        v.truncate(max);
        let m = v.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        let s = crate::geom::exact::power_of_two_scale(m);
        v.iter().map(|q| q.map(|c| c * s)).collect()
    }

    /// Issue 17 (B): c = −1 (the brute force over every triple) on nearly cospherical points,
    /// where the in-sphere filter of `geom::near_sphere` decides most tests: the brute force's
    /// triangles and γ-values (the oracle computes its intervals without the filter).
    #[test]
    fn beyond_3d_matches_brute_on_rounded_cospherical_sets() {
        for scale in [1e-300, 1e150, 0.1] {
            let p = rounded_sphere(scale, 20);
            assert_eq!(p.len(), 20);
            check(&p, &[-1.0]);
        }
    }

    /// Issue 17 (B), c > −1 on nearly cospherical points: a point nearly on a triangle's
    /// circumcircle (exactly on it before rounding) lies nearly in its plane, and its offset
    /// τ = q / 2h, a quotient of two rounding-sized numbers, was meaningless in floating point:
    /// it made the oracle's γ-values wrong (the triangle 0, 1, 19 at 1e-300: c₁′ = −1 instead
    /// of ≈ −0.128, checked in exact rational arithmetic) and stopped `beyond_dt_3d`'s exact
    /// decisions early (2, 6, 17 and 3, 16, 18 missing). Those offsets now come from exact
    /// expansions (`gamma::exact_offset`). At c = 0 the oracle's filter must not take a gap's
    /// c₁′ that rounds to −0.0 for ≥ 0 (see `check`).
    #[test]
    fn beyond_3d_matches_brute_on_rounded_cospherical_sets_above_minus_one() {
        for scale in [1e-300, 1e-150, 1.0, 1e150, 1e300] {
            let p = rounded_sphere(scale, 20);
            assert_eq!(p.len(), 20);
            check(&p, &[-0.9, -0.5, 0.0, 0.5]);
        }
    }

    #[test]
    fn beyond_3d_matches_brute_with_duplicates_and_coplanar_points() {
        let cs = [-0.05, -0.2, -0.5, -1.0];
        // duplicates and coplanar points among random ones
        let mut r = random_3d(30, 4200);
        for i in 0..6 {
            r.push(r[i]);
        }
        for i in 0..5 {
            r.push([0.1 * i as f64, 0.5, 0.5]);
        }
        check(&r, &cs);
    }
}

mod beyond3_graphs {
    use super::random_3d;
    use crate::geom::Point3;
    use crate::graphs::brute::gamma_values_3d;
    use crate::graphs::gamma::{in_gamma, in_gamma_range};
    use crate::graphs::{graph_3d, Kind};
    use proptest::prelude::*;
    use std::collections::BTreeSet;

    fn pts(p: &[[f64; 3]]) -> Vec<Point3> {
        p.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect()
    }

    /// graph_3d against the brute force on input indices (no duplicates in `p`).
    fn check_graph(p: &[[f64; 3]], kinds: &[Kind]) {
        let vals = gamma_values_3d(p);
        for &kind in kinds {
            let g = graph_3d(&pts(p), kind).unwrap();
            let want: Vec<([u32; 3], (f64, f64))> = vals
                .iter()
                .copied()
                .filter(|(_, v)| match kind {
                    Kind::Gamma(c0, c1) => in_gamma(*v, c0, c1),
                    Kind::GammaRange(r) => in_gamma_range(*v, r),
                    _ => unreachable!(),
                })
                .collect();
            let wt: Vec<[u32; 3]> = want.iter().map(|x| x.0).collect();
            let gs: BTreeSet<[u32; 3]> = g.triangles.iter().copied().collect();
            let ws: BTreeSet<[u32; 3]> = wt.iter().copied().collect();
            let extra: Vec<_> = gs.difference(&ws).collect();
            let missing: Vec<_> = ws.difference(&gs).collect();
            let vals_of = |t: &[u32; 3]| vals.iter().find(|x| x.0 == *t).map(|x| x.1);
            assert!(
                extra.is_empty() && missing.is_empty(),
                "{kind:?}: extra {:?} missing {:?}",
                extra.iter().map(|t| (t, vals_of(t))).collect::<Vec<_>>(),
                missing.iter().map(|t| (t, vals_of(t))).collect::<Vec<_>>()
            );
            assert_eq!(g.triangles, wt, "{kind:?}");
            assert_eq!(g.gamma.len(), g.triangles.len());
            for (gv, (_, v)) in g.gamma.iter().zip(&want) {
                assert!((gv[0] - v.0).abs() < 1e-9 && (gv[1] - v.1).abs() < 1e-9);
            }
        }
    }

    const KINDS: [Kind; 7] = [
        Kind::Gamma(0.0, -0.2),
        Kind::Gamma(-0.1, -0.5),
        Kind::Gamma(0.3, -0.9),
        Kind::Gamma(-1.0, -1.0),
        Kind::GammaRange([-1.0, 1.0, -0.2, 1.0]),
        Kind::GammaRange([-1.0, 1.0, -0.05, -0.01]),
        Kind::GammaRange([-0.5, 0.5, -1.0, 0.5]),
    ];

    #[test]
    fn graph_3d_beyond_delaunay_matches_brute() {
        // the sphere lattice has coplanar points on hull triangles' circumcircles: decided by
        // the exact in-circle test of `TriFrame::add` (`in_circumcircle_3d`)
        check_graph(&super::beyond3_oracle::sphere_lattice(), &KINDS);
        check_graph(&random_3d(35, 4300), &KINDS);
        let mut flat = random_3d(30, 4301);
        for q in flat.iter_mut() {
            q[1] *= 0.1;
        }
        check_graph(&flat, &KINDS);
    }

    #[test]
    fn graph_3d_beyond_delaunay_is_monotone_and_unlimited() {
        // more points than the old brute-force limit (150)
        let p = random_3d(152, 4400);
        let mut prev: BTreeSet<[u32; 3]> = BTreeSet::new();
        for c in [-0.02, -0.1] {
            let g = graph_3d(&pts(&p), Kind::GammaRange([-1.0, 1.0, c, 1.0])).unwrap();
            let s: BTreeSet<[u32; 3]> = g.triangles.iter().copied().collect();
            assert!(prev.is_subset(&s), "c = {c}");
            for v in &g.gamma {
                assert!(v[1] >= c);
            }
            prev = s;
        }
        // γ with a parameter −1 is cubic: refused beyond the limit
        assert!(graph_3d(&pts(&p), Kind::Gamma(0.0, -1.0)).is_err());
    }

    #[test]
    fn alpha_3d_positive_uses_hull_vertices_only() {
        // a ball of radius 1/a containing every point touches only hull vertices
        for s in 0..2 {
            let p = random_3d(40, 4500 + s);
            for a in [0.8, 1.0, 1.4] {
                let g = graph_3d(&pts(&p), Kind::Alpha(a)).unwrap();
                let want = crate::graphs::brute::alpha_3d(&p, a);
                assert_eq!(g.triangles, want, "a = {a}");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(10))]
        #[test]
        fn beyond_3d_matches_brute_on_small_integer_sets(
            raw in proptest::collection::vec((0i32..5, 0i32..5, 0i32..4), 8..18),
            ci in 0usize..4,
        ) {
            let p: Vec<[f64; 3]> = raw.iter().map(|&(x, y, z)| [x as f64, y as f64, z as f64]).collect();
            let c = [-0.05, -0.2, -0.5, -0.9][ci];
            super::beyond3_oracle::check(&p, &[c]);
        }
    }
}

/// EMST and SIG against their definitions on sets full of exact ties and near-ties, with
/// duplicates (the fast paths compare floats first and fall back to exact predicates only near
/// a tie, and SIG looks for each pair from one end only).
mod emst_sig_oracle {
    use crate::geom::distance::{cmp_dist2, sum_of_roots_exceeds};
    use crate::geom::{Point2, Point3};
    use crate::graphs::{graph_2d, graph_3d, Kind};
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::cmp::Ordering;

    /// The first occurrence of every distinct point, as (input index, point).
    fn distinct<const D: usize>(p: &[[f64; D]]) -> Vec<(u32, [f64; D])> {
        let mut seen = std::collections::HashSet::new();
        p.iter()
            .enumerate()
            .filter(|(_, q)| seen.insert(q.map(|x| (x + 0.0).to_bits())))
            .map(|(i, q)| (i as u32, *q))
            .collect()
    }

    /// Kruskal over all pairs in the exact order (length, smaller input index, larger input
    /// index): the unique minimum spanning tree for that strict total order.
    fn emst_total_order<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
        let q = distinct(p);
        let mut pairs: Vec<(usize, usize)> = (0..q.len())
            .flat_map(|i| (i + 1..q.len()).map(move |j| (i, j)))
            .collect();
        pairs.sort_by(|&(a, b), &(c, d)| {
            cmp_dist2(&q[a].1, &q[b].1, &q[c].1, &q[d].1)
                .then((q[a].0, q[b].0).cmp(&(q[c].0, q[d].0)))
        });
        let mut parent: Vec<usize> = (0..q.len()).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        let mut out = Vec::new();
        for (a, b) in pairs {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            if ra != rb {
                parent[ra] = rb;
                out.push([q[a].0, q[b].0]);
            }
        }
        out.sort_unstable();
        out
    }

    /// Def. 2.7 over the distinct points, in input indices.
    fn sig_def<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
        let q = distinct(p);
        if q.len() < 2 {
            return vec![];
        }
        let nn: Vec<usize> = (0..q.len())
            .map(|i| {
                (0..q.len())
                    .filter(|&j| j != i)
                    .min_by(|&j, &k| cmp_dist2(&q[i].1, &q[j].1, &q[i].1, &q[k].1))
                    .unwrap_or(i)
            })
            .collect();
        let mut out = Vec::new();
        for i in 0..q.len() {
            for j in i + 1..q.len() {
                if sum_of_roots_exceeds(&q[i].1, &q[j].1, &q[nn[i]].1, &q[nn[j]].1) {
                    out.push([q[i].0, q[j].0]);
                }
            }
        }
        out.sort_unstable();
        out
    }

    fn tie_sets() -> Vec<(&'static str, Vec<[f64; 2]>)> {
        let mut v: Vec<(&'static str, Vec<[f64; 2]>)> = Vec::new();
        v.push((
            "grid9",
            (0..81).map(|i| [(i % 9) as f64, (i / 9) as f64]).collect(),
        ));
        v.push((
            "grid-tenths",
            (0..64)
                .map(|i| [(i % 8) as f64 * 0.1 + 0.3, (i / 8) as f64 * 0.1 + 0.7])
                .collect(),
        ));
        let mut r = ChaCha8Rng::seed_from_u64(17);
        v.push((
            "grid-ulps",
            (0..64)
                .map(|i| {
                    let mut jit = |x: f64| {
                        f64::from_bits((x.to_bits() as i64 + r.gen_range(-2i64..=2)) as u64)
                    };
                    [jit(1000.0 + (i % 8) as f64), jit(1000.0 + (i / 8) as f64)]
                })
                .collect(),
        ));
        let mut r = ChaCha8Rng::seed_from_u64(18);
        // many duplicates and equal lengths
        v.push((
            "snapped-duplicates",
            (0..150)
                .map(|_| [r.gen_range(0..7) as f64, r.gen_range(0..7) as f64])
                .collect(),
        ));
        // triangular lattice (every vertex has six equal nearest neighbours), shuffled input order
        let mut tri: Vec<[f64; 2]> = (0..70)
            .map(|i| {
                let (x, y) = ((i % 10) as f64, (i / 10) as f64);
                [x + 0.5 * (y % 2.0), y * 0.75f64.sqrt()]
            })
            .collect();
        for i in (1..tri.len()).rev() {
            tri.swap(i, r.gen_range(0..=i));
        }
        v.push(("triangular-lattice", tri));
        // |ab| = r_a + r_b exactly: pairs of points at distance 1, pairs 2 apart (not SIG edges)
        let mut touch: Vec<[f64; 2]> = (0..20).map(|i| [(i / 2 * 3 + i % 2) as f64, 0.0]).collect();
        touch.push([5.0, 40.0]);
        v.push(("touching-spheres", touch));
        // radii of very different sizes: a dense cluster and sparse far points
        let mut r = ChaCha8Rng::seed_from_u64(19);
        let mut cl: Vec<[f64; 2]> = (0..120)
            .map(|_| [r.gen::<f64>() * 0.01, r.gen::<f64>() * 0.01])
            .collect();
        cl.extend((0..25).map(|_| [r.gen::<f64>() * 10.0 - 5.0, r.gen::<f64>() * 10.0 - 5.0]));
        v.push(("cluster-and-outliers", cl));
        v.push((
            "line",
            (0..12).map(|i| [i as f64 * 0.5, 1.0 + i as f64]).collect(),
        ));
        v.push(("two", vec![[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]]));
        v
    }

    fn pts(p: &[[f64; 2]]) -> Vec<Point2> {
        p.iter().map(|q| Point2::new(q[0], q[1])).collect()
    }

    #[test]
    fn emst_is_the_total_order_tree_on_tie_sets_2d() {
        for (name, p) in tie_sets() {
            let g = graph_2d(&pts(&p), Kind::Emst).unwrap();
            assert_eq!(g.edges, emst_total_order(&p), "{name}");
        }
    }

    #[test]
    fn sig_matches_the_definition_on_tie_sets_2d() {
        for (name, p) in tie_sets() {
            let g = graph_2d(&pts(&p), Kind::Sig).unwrap();
            assert_eq!(g.edges, sig_def(&p), "{name}");
        }
    }

    #[test]
    fn emst_and_sig_match_on_larger_random_sets() {
        for s in 0..2 {
            let mut r = ChaCha8Rng::seed_from_u64(700 + s);
            let p: Vec<[f64; 2]> = (0..500).map(|_| [r.gen(), r.gen()]).collect();
            assert_eq!(
                graph_2d(&pts(&p), Kind::Emst).unwrap().edges,
                emst_total_order(&p)
            );
            assert_eq!(graph_2d(&pts(&p), Kind::Sig).unwrap().edges, sig_def(&p));
        }
    }

    #[test]
    fn emst_and_sig_3d_on_tie_sets() {
        let grid: Vec<[f64; 3]> = (0..64)
            .map(|i| [(i % 4) as f64, ((i / 4) % 4) as f64, (i / 16) as f64 * 0.1])
            .collect();
        let mut r = ChaCha8Rng::seed_from_u64(23);
        let snapped: Vec<[f64; 3]> = (0..60)
            .map(|_| {
                [
                    r.gen_range(0..4) as f64,
                    r.gen_range(0..4) as f64,
                    r.gen_range(0..3) as f64,
                ]
            })
            .collect();
        for (name, p) in [("grid", grid), ("snapped", snapped)] {
            let q: Vec<Point3> = p.iter().map(|x| Point3::new(x[0], x[1], x[2])).collect();
            assert_eq!(
                graph_3d(&q, Kind::Emst).unwrap().edges,
                emst_total_order(&p),
                "{name}"
            );
            assert_eq!(
                graph_3d(&q, Kind::Sig).unwrap().edges,
                sig_def(&p),
                "{name}"
            );
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn emst_and_sig_on_small_integer_sets(
            raw in proptest::collection::vec((0i32..6, 0i32..6), 2..40),
            scale in prop_oneof![Just(1.0), Just(0.1), Just(1e-3)],
        ) {
            let p: Vec<[f64; 2]> = raw.iter().map(|&(x, y)| [x as f64 * scale, y as f64 * scale]).collect();
            prop_assert_eq!(graph_2d(&pts(&p), Kind::Emst).unwrap().edges, emst_total_order(&p));
            prop_assert_eq!(graph_2d(&pts(&p), Kind::Sig).unwrap().edges, sig_def(&p));
        }
    }

    #[test]
    fn total_order_breaks_ties_by_input_index() {
        // a unit square: four equal sides; the tree takes the three with the smallest index pairs
        let p = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let t = emst_total_order(&p);
        assert_eq!(t, vec![[0, 1], [0, 3], [1, 2]]);
        assert_eq!(graph_2d(&pts(&p), Kind::Emst).unwrap().edges, t);
        let ord = |a: [f64; 2], b: [f64; 2]| cmp_dist2(&a, &b, &p[0], &p[1]);
        assert_eq!(ord(p[2], p[3]), Ordering::Equal);
    }
}

/// RNG (V Def. 2.8), lune-based β-skeletons (V Def. 2.16) and the Gabriel graph (Def. 2.9)
/// built from the Delaunay triangulation ([`super::lune`]) against the brute-force definitions,
/// on sets that put points on, just inside and just outside lune boundaries, near the edges'
/// ends, on integer grids and circles.
mod lune_oracle {
    use crate::delaunay::d2;
    use crate::geom::distance::in_lune_ball;
    use crate::geom::Point2;
    use crate::graphs::{brute, graph_2d, Kind};
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    const BS: [f64; 8] = [0.0, 0.05, 0.3, 0.5, 0.6, 0.8, 0.95, 0.999];

    fn pts(p: &[[f64; 2]]) -> Vec<Point2> {
        p.iter().map(|q| Point2::new(q[0], q[1])).collect()
    }

    /// The oracle on the first occurrences of the distinct points, in input indices.
    fn oracle(p: &[[f64; 2]], f: impl Fn(&[[f64; 2]]) -> Vec<[u32; 2]>) -> Vec<[u32; 2]> {
        let mut seen = std::collections::HashSet::new();
        let first: Vec<(u32, [f64; 2])> = p
            .iter()
            .enumerate()
            .filter(|(_, q)| seen.insert(q.map(|x| (x + 0.0).to_bits())))
            .map(|(i, q)| (i as u32, *q))
            .collect();
        let q: Vec<[f64; 2]> = first.iter().map(|x| x.1).collect();
        let mut out: Vec<[u32; 2]> = f(&q)
            .into_iter()
            .map(|[a, b]| {
                let (a, b) = (first[a as usize].0, first[b as usize].0);
                [a.min(b), a.max(b)]
            })
            .collect();
        out.sort_unstable();
        out
    }

    fn check(name: &str, p: &[[f64; 2]]) {
        let q = pts(p);
        let got = |k: Kind| graph_2d(&q, k).expect("graph").edges;
        assert_eq!(got(Kind::Rng), oracle(p, brute::rng), "{name}: RNG");
        assert_eq!(got(Kind::Gabriel), oracle(p, brute::gabriel), "{name}: GG");
        for b in BS {
            assert_eq!(
                got(Kind::BetaLune(b)),
                oracle(p, |x| brute::beta_lune(x, b)),
                "{name}: β-lune({b})"
            );
        }
    }

    fn random(n: usize, seed: u64) -> Vec<[f64; 2]> {
        let mut r = ChaCha8Rng::seed_from_u64(seed);
        (0..n).map(|_| [r.gen::<f64>(), r.gen::<f64>()]).collect()
    }

    fn up(x: f64) -> f64 {
        f64::from_bits(x.to_bits() + 1)
    }

    fn down(x: f64) -> f64 {
        f64::from_bits(x.to_bits() - 1)
    }

    /// Edges u v = (0,0)–(5,0) (copies shifted by 20) with points exactly on the RNG lune's
    /// boundary (|xu| = 5 or |xv| = 5 with integer coordinates), one ulp inside and one outside,
    /// and on the lunes' axis beyond the corners.
    fn boundary_set() -> Vec<[f64; 2]> {
        let on = [[3.0, 4.0], [4.0, 3.0], [2.0, 4.0], [1.0, 3.0]];
        let mut p = Vec::new();
        for (c, x) in on.iter().enumerate() {
            let dx = 20.0 * c as f64;
            for (k, y) in [x[1], down(x[1]), up(x[1])].into_iter().enumerate() {
                let dy = 20.0 * k as f64;
                p.push([dx, dy]);
                p.push([dx + 5.0, dy]);
                p.push([dx + x[0], dy + y]);
                p.push([dx + x[0], dy - y - 0.5]);
            }
        }
        // a lune corner region: (2.5, 5·√3/2) is irrational, so points a hair above and below
        let h = 5.0 * 0.75f64.sqrt();
        for (k, y) in [h, down(down(h)), up(up(h))].into_iter().enumerate() {
            let dx = 100.0 + 20.0 * k as f64;
            p.extend([[dx, 0.0], [dx + 5.0, 0.0], [dx + 2.5, y]]);
        }
        p
    }

    /// Points close to an edge's ends, on both sides of the lune's tangent at u (the normal
    /// to uv) and of the ball boundary at v.
    fn ends_set() -> Vec<[f64; 2]> {
        let mut p = vec![[0.0, 0.0], [1.0, 0.0], [0.5, -3.0], [0.5, 3.0]];
        for (i, e) in [1e-3, 1e-6, 1e-9].into_iter().enumerate() {
            let y = 0.1 * (i + 1) as f64;
            p.push([e * e, y * e]); // inside near u: (x − u)·(v − u) > 0
            p.push([-e * e, -y * e]); // outside near u
            p.push([1.0 + e * e, y * e]); // outside near v
            p.push([1.0 - e * e, -y * e]); // inside near v
        }
        p
    }

    /// A regular polygon-like cocircular set (integer points on x² + y² = 25 and 65²) with the
    /// centre, and some lattice points inside.
    fn circles_set() -> Vec<[f64; 2]> {
        let mut p: Vec<[f64; 2]> = Vec::new();
        for (a, b) in [
            (25.0, 60.0),
            (39.0, 52.0),
            (33.0, 56.0),
            (16.0, 63.0),
            (0.0, 65.0),
        ] {
            for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                p.push([sx * a, sy * b]);
                p.push([sy * b, sx * a]);
            }
        }
        p.push([0.0, 0.0]);
        p.extend([
            [3.0, 4.0],
            [-4.0, 3.0],
            [-3.0, -4.0],
            [4.0, -3.0],
            [5.0, 0.0],
        ]);
        p
    }

    #[test]
    fn lune_graphs_match_the_definitions_on_random_sets() {
        for (s, n) in [(1u64, 50usize), (2, 120), (3, 300), (4, 200), (5, 77)] {
            check(&format!("random {n}"), &random(n, 100 + s));
        }
        // points snapped to a coarse lattice (ties, duplicates, cocircular quadruples)
        let mut r = ChaCha8Rng::seed_from_u64(31);
        let snapped: Vec<[f64; 2]> = (0..250)
            .map(|_| [r.gen_range(0..13) as f64, r.gen_range(0..9) as f64])
            .collect();
        check("snapped", &snapped);
        let grid: Vec<[f64; 2]> = (0..100)
            .map(|i| [(i % 10) as f64, (i / 10) as f64])
            .collect();
        check("grid", &grid);
        // a triangular lattice: every lune of a lattice edge has lattice points on its boundary
        let tri: Vec<[f64; 2]> = (0..80)
            .map(|i| {
                let (x, y) = ((i % 10) as f64, (i / 10) as f64);
                [2.0 * x + (y % 2.0), 2.0 * y]
            })
            .collect();
        check("skewed lattice", &tri);
    }

    #[test]
    fn lune_graphs_match_the_definitions_on_boundary_sets() {
        check("lune boundaries", &boundary_set());
        // the same, small and far from the origin (coordinates ≫ edge lengths)
        let far: Vec<[f64; 2]> = boundary_set()
            .iter()
            .map(|q| [1e6 + q[0] * 1e-3, -3e6 + q[1] * 1e-3])
            .collect();
        check("lune boundaries far away", &far);
        let mut r = ChaCha8Rng::seed_from_u64(41);
        let far_random: Vec<[f64; 2]> = (0..150)
            .map(|_| [1e9 + r.gen::<f64>() * 1e-4, 1e9 + r.gen::<f64>() * 1e-4])
            .collect();
        check("random far away", &far_random);
        check("edge ends", &ends_set());
        check("circles", &circles_set());
        check(
            "collinear",
            &[[0.0, 0.0], [1.0, 1.0], [3.0, 3.0], [2.0, 2.0]],
        );
        check("two", &[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]);
    }

    /// The Delaunay neighbours of an edge's two ends do not decide its lune: here u v is a
    /// Delaunay (and Gabriel) edge, none of the neighbours of u or v lies in its RNG lune, but
    /// x = (0.5, 0.86), hidden behind y1 and y2, does — so u v is no RNG edge.
    #[test]
    fn one_ring_is_not_enough() {
        let p = [
            [0.0, 0.0],   // u
            [1.0, 0.0],   // v
            [0.1, 0.6],   // y1
            [0.9, 0.62],  // y2
            [0.5, 0.86],  // x
            [0.5, -0.95], // below
        ];
        let d = d2::triangulate(&pts(&p)).expect("triangulation");
        let edges: Vec<[u32; 2]> = d
            .edges()
            .into_iter()
            .map(|e| {
                let (a, b) = (
                    d.input_of_vertex[e[0] as usize],
                    d.input_of_vertex[e[1] as usize],
                );
                [a.min(b), a.max(b)]
            })
            .collect();
        assert!(edges.contains(&[0, 1]), "u v is a Delaunay edge");
        let in_lune = |x: usize| {
            in_lune_ball(&p[x], &p[0], &p[1], 0.5) && in_lune_ball(&p[x], &p[1], &p[0], 0.5)
        };
        for e in &edges {
            for (end, other) in [(e[0], e[1]), (e[1], e[0])] {
                if end <= 1 && other > 1 {
                    assert!(
                        !in_lune(other as usize),
                        "neighbour {other} lies outside the lune"
                    );
                }
            }
        }
        assert!(in_lune(4), "x lies in the lune");
        let rng = graph_2d(&pts(&p), Kind::Rng).expect("graph").edges;
        assert!(!rng.contains(&[0, 1]));
        assert!(graph_2d(&pts(&p), Kind::Gabriel)
            .expect("graph")
            .edges
            .contains(&[0, 1]));
        check("one ring", &p);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(40))]
        #[test]
        fn lune_graphs_on_small_integer_sets(
            raw in proptest::collection::vec((0i32..9, 0i32..7), 2..45),
        ) {
            let p: Vec<[f64; 2]> = raw.iter().map(|&(x, y)| [x as f64, y as f64]).collect();
            check("proptest", &p);
        }

        #[test]
        fn lune_graphs_on_jittered_sets(
            raw in proptest::collection::vec((0i32..6, 0i32..6, -2i64..=2, -2i64..=2), 3..30),
        ) {
            // lattice points moved by a few ulps: near-ties on every lune boundary
            let jit = |x: f64, k: i64| f64::from_bits((x.to_bits() as i64 + k) as u64);
            let p: Vec<[f64; 2]> = raw
                .iter()
                .map(|&(x, y, a, b)| [jit(100.0 + x as f64, a), jit(100.0 + y as f64, b)])
                .collect();
            check("jittered", &p);
        }
    }
}

// ---- exact oracle of c₁′ ≥ c (issue 17: exact γ-value decisions, 2D certified offsets) ----

mod exact_oracle {
    use super::super::beyond3::beyond_dt_3d;
    use super::super::brute::gamma_values_3d;
    use super::super::fast::{beyond_dt_2d, candidates_2d, candidates_3d, coords2, coords3};
    use super::super::gamma::{center_interval_3d, EdgeFrame, TriFrame};
    use super::random_3d;
    use crate::delaunay::{d2, d3};
    use crate::geom::exact::{big_cross, big_dot, float_parts, to_big_ints};
    use crate::geom::{Point2, Point3};
    use num_bigint::{BigInt, Sign};
    use std::collections::BTreeSet;

    /// The exact interval of one simplex in rationals: each end as (numerator, denominator) of
    /// its offset τ (denominator with the sign of the point's side), ρ₀² = r/q, and whether a
    /// point in the closed simplex blocks everything.
    struct Exact {
        lo: Option<(BigInt, BigInt)>,
        hi: Option<(BigInt, BigInt)>,
        rho2: (BigInt, BigInt),
        blocked: bool,
        /// a point in the plane strictly inside the circumcircle (3D): only half-spaces empty
        finite: bool,
    }

    /// n1/d1 < n2/d2 for d1, d2 of one sign.
    fn less(a: &(BigInt, BigInt), b: &(BigInt, BigInt)) -> bool {
        let s = &a.1 * &b.1; // > 0
        debug_assert!(s.sign() == Sign::Plus);
        &a.0 * &b.1 < &b.0 * &a.1
    }

    impl Exact {
        /// Narrows by a point with offset num/den (den ≠ 0, sign = side).
        fn add(&mut self, num: BigInt, den: BigInt) {
            let t = (num, den);
            if t.1.sign() == Sign::Plus {
                if self.hi.as_ref().is_none_or(|h| less(&t, h)) {
                    self.hi = Some(t);
                }
            } else if self.lo.as_ref().is_none_or(|l| less(l, &t)) {
                self.lo = Some(t);
            }
        }
        /// |c(τ)| ≥ |c| (+1), = (0) or < (−1) for the end τ, |c| = C/S:
        /// τ² (1 − |c|)² vs ρ₀² |c| (2 − |c|), cross-multiplied.
        fn reach(&self, t: &(BigInt, BigInt), cn: &BigInt, cs: &BigInt) -> std::cmp::Ordering {
            let k1 = cs - cn;
            let lhs = &t.0 * &t.0 * &k1 * &k1 * &self.rho2.1;
            let rhs = &t.1 * &t.1 * &self.rho2.0 * cn * (BigInt::from(2) * cs - cn);
            lhs.cmp(&rhs)
        }
        /// c₁′ ≥ c by Def. 3.3 on the exact ends (see `CenterInterval::gamma_values`).
        fn reaches(&self, c: f64) -> bool {
            use std::cmp::Ordering::*;
            if self.blocked || c > 1.0 {
                return false;
            }
            if self.finite {
                return self.lo.is_none() || self.hi.is_none();
            }
            // |c| = C/S exactly (for |c| ≥ 1 only the order of the cases below matters)
            let (cn, cs) = if c == 0.0 || c.abs() >= 1.0 {
                (BigInt::from(0), BigInt::from(1))
            } else {
                let (m, e) = float_parts(c.abs());
                (BigInt::from(m), BigInt::from(1) << ((-e) as usize))
            };
            match (&self.lo, &self.hi) {
                // an end without a binding point: a half-space is empty, c₁′ = 1
                (None, _) | (_, None) => true,
                (Some(l), Some(h)) => {
                    // lo ≤ hi ⇔ l.0/l.1 ≤ h.0/h.1 with l.1 < 0 < h.1
                    let lo_le_hi = &l.0 * &h.1 >= &h.0 * &l.1;
                    if lo_le_hi {
                        c <= 0.0
                            || (c < 1.0
                                && (self.reach(l, &cn, &cs) != Less
                                    || self.reach(h, &cn, &cs) != Less))
                    } else {
                        c < 0.0
                            && (c <= -1.0
                                || (self.reach(l, &cn, &cs) != Greater
                                    && self.reach(h, &cn, &cs) != Greater))
                    }
                }
            }
        }
    }

    /// The sign of an end's offset (an end without a binding point: lo = −∞, hi = +∞).
    fn tau_sign(t: &Option<(BigInt, BigInt)>, infinite: Sign) -> i32 {
        let s = |x: Sign| match x {
            Sign::Minus => -1,
            Sign::NoSign => 0,
            Sign::Plus => 1,
        };
        t.as_ref()
            .map_or(s(infinite), |t| s(t.0.sign()) * s(t.1.sign()))
    }

    impl Exact {
        /// |τ| of `a` ≤ |τ| of `b` (an end without a binding point is infinite).
        fn abs_le(a: &Option<(BigInt, BigInt)>, b: &Option<(BigInt, BigInt)>) -> bool {
            match (a, b) {
                (_, None) => true,
                (None, Some(_)) => false,
                (Some(a), Some(b)) => (&a.0 * &b.1).magnitude() <= (&b.0 * &a.1).magnitude(),
            }
        }
        /// (c₀′ vs c, c₁′ vs c) by Def. 3.3 literally on the exact ends, as
        /// `CenterInterval::gamma_values` describes it: the nearer end (smaller |τ|) gives
        /// |c₀′|, the farther |c₁′|; signs from the regime and the ends' signs. `None`: no
        /// γ-values.
        fn cmp_values(&self, c: f64) -> Option<(std::cmp::Ordering, std::cmp::Ordering)> {
            use std::cmp::Ordering::*;
            if self.blocked {
                return None;
            }
            if self.finite {
                let v0 = match (self.lo.is_none(), self.hi.is_none()) {
                    (true, true) => 1.0,
                    (false, false) => return None,
                    _ => -1.0,
                };
                return Some((v0.partial_cmp(&c)?, 1.0f64.partial_cmp(&c)?));
            }
            let (cn, cs) = if c == 0.0 || c.abs() >= 1.0 {
                (BigInt::from(0), BigInt::from(1))
            } else {
                let (m, e) = float_parts(c.abs());
                (BigInt::from(m), BigInt::from(1) << ((-e) as usize))
            };
            // |c(τ)| of an end vs |c|
            let abs_cmp = |t: &Option<(BigInt, BigInt)>| match t {
                None => 1.0f64.partial_cmp(&c.abs()).unwrap(),
                Some(_) if c.abs() >= 1.0 => Less,
                Some(t) => self.reach(t, &cn, &cs),
            };
            // (sign of the value, |value| vs |c|) against c
            let against = |positive: bool, m: std::cmp::Ordering| {
                if positive {
                    if c < 0.0 {
                        Greater
                    } else {
                        m
                    }
                } else if c > 0.0 {
                    Less
                } else {
                    m.reverse()
                }
            };
            let (sl, sh) = (
                tau_sign(&self.lo, Sign::Minus),
                tau_sign(&self.hi, Sign::Plus),
            );
            let lo_le_hi = match (&self.lo, &self.hi) {
                (Some(l), Some(h)) => &l.0 * &h.1 >= &h.0 * &l.1,
                _ => true,
            };
            let (near, far, sn, sf) = if Self::abs_le(&self.lo, &self.hi) {
                (&self.lo, &self.hi, sl, sh)
            } else {
                (&self.hi, &self.lo, sh, sl)
            };
            let (p0, p1) = if lo_le_hi {
                (sl <= 0 && sh >= 0, true)
            } else {
                (sn * sf > 0 || sn == 0, false)
            };
            Some((against(p0, abs_cmp(near)), against(p1, abs_cmp(far))))
        }
        /// σ ∈ γ(c₀, c₁) by Lemmas 3.1, 3.2 on the exact values.
        fn in_gamma(&self, c0: f64, c1: f64) -> bool {
            use std::cmp::Ordering::Less;
            let ge = |c: f64, k: usize| self.cmp_values(c).is_some_and(|o| [o.0, o.1][k] != Less);
            (ge(c0, 0) && ge(c1, 1)) || (c1 < 0.0 && ge(c1, 0) && ge(c0.abs(), 1))
        }
        /// σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\]) by Def. 3.3 on the exact values.
        fn in_range(&self, r: [f64; 4]) -> bool {
            use std::cmp::Ordering::*;
            let (a, b) = (self.cmp_values(r[0]), self.cmp_values(r[1]));
            let (c, d) = (self.cmp_values(r[2]), self.cmp_values(r[3]));
            match (a, b, c, d) {
                (Some(a), Some(b), Some(c), Some(d)) => {
                    a.0 != Less && b.0 != Greater && c.1 != Less && d.1 != Greater
                }
                _ => false,
            }
        }
    }

    /// The exact interval of the 2D edge (a, b) over the points `q` (integers after a common
    /// scaling): τ = (x − a)·(x − b) / 2 orient(a, b, x), ρ₀² = 1/4.
    fn exact_2d(q: &[[BigInt; 2]], a: usize, b: usize) -> Exact {
        let mut ex = Exact {
            lo: None,
            hi: None,
            rho2: (BigInt::from(1), BigInt::from(4)),
            blocked: false,
            finite: false,
        };
        let (pa, pb) = (&q[a], &q[b]);
        for (i, x) in q.iter().enumerate() {
            if i == a || i == b {
                continue;
            }
            let xa = [&x[0] - &pa[0], &x[1] - &pa[1]];
            let xb = [&x[0] - &pb[0], &x[1] - &pb[1]];
            let ba = [&pb[0] - &pa[0], &pb[1] - &pa[1]];
            let num = &xa[0] * &xb[0] + &xa[1] * &xb[1];
            let h = &ba[0] * &xa[1] - &ba[1] * &xa[0];
            if h.sign() == Sign::NoSign {
                // on the line: on the closed segment iff (x − a)·(x − b) ≤ 0
                if num.sign() != Sign::Plus {
                    ex.blocked = true;
                }
                continue;
            }
            ex.add(num, h * 2);
        }
        ex
    }

    /// The exact interval of triangle (a, b, c): τ = N / (2|n|² h) (see
    /// `geom::exact::offset_reach_sign_3d`), ρ₀² = |u|²|v|²|u − v|² / 4|n|⁴; a point in the
    /// plane blocks everything in the closed triangle, every finite ball strictly inside the
    /// circumcircle (N = |n|² (|x − m|² − r²) < 0). `None` for collinear corners.
    fn exact_3d(q: &[[BigInt; 3]], t: [usize; 3]) -> Option<Exact> {
        let d = |p: &[BigInt; 3], o: &[BigInt; 3]| -> [BigInt; 3] {
            [&p[0] - &o[0], &p[1] - &o[1], &p[2] - &o[2]]
        };
        let a = &q[t[0]];
        let (u, v) = (d(&q[t[1]], a), d(&q[t[2]], a));
        let n = big_cross(&u, &v);
        let (uu, vv, nn) = (big_dot(&u, &u), big_dot(&v, &v), big_dot(&n, &n));
        if nn.sign() == Sign::NoSign {
            return None;
        }
        let uv = d(&u, &v);
        let mut ex = Exact {
            lo: None,
            hi: None,
            rho2: (&uu * &vv * big_dot(&uv, &uv), BigInt::from(4) * &nn * &nn),
            blocked: false,
            finite: false,
        };
        for (i, x) in q.iter().enumerate() {
            if t.contains(&i) {
                continue;
            }
            let w = d(x, a);
            let h = big_dot(&w, &n);
            let num = big_dot(&w, &w) * &nn
                + &uu * big_dot(&n, &big_cross(&v, &w))
                + &vv * big_dot(&n, &big_cross(&w, &u));
            if h.sign() == Sign::NoSign {
                let side = |p: &[BigInt; 3], r: &[BigInt; 3]| {
                    big_dot(&n, &big_cross(&d(r, p), &d(x, p))).sign() != Sign::Minus
                };
                let (pa, pb, pc) = (&q[t[0]], &q[t[1]], &q[t[2]]);
                if side(pa, pb) && side(pb, pc) && side(pc, pa) {
                    ex.blocked = true;
                } else if num.sign() == Sign::Minus {
                    ex.finite = true;
                }
                continue;
            }
            ex.add(num, BigInt::from(2) * &nn * h);
        }
        Some(ex)
    }

    /// c₁′ ≥ c for triangle `t` of `p`, exactly (`None` for collinear corners): the oracle of
    /// the decisions near ties for the brute-force checks of `beyond3_oracle`.
    pub(super) fn reaches_3d(p: &[[f64; 3]], t: [u32; 3], c: f64) -> Option<bool> {
        let q = ints(p);
        exact_3d(&q, t.map(|v| v as usize)).map(|e| e.reaches(c))
    }

    fn ints<const D: usize>(p: &[[f64; D]]) -> Vec<[BigInt; D]> {
        let flat: Vec<f64> = p.iter().flatten().copied().collect();
        let v = to_big_ints(&flat);
        (0..p.len())
            .map(|i| std::array::from_fn(|k| v[D * i + k].clone()))
            .collect()
    }

    /// The 20 integer points with x² + y² = 625 (exactly cocircular) times `scale`, rounded,
    /// then scaled by a power of two to magnitude ≈ 1: no longer exactly cocircular (points
    /// with equal coordinate magnitudes stay on one circle), so every in-circle test is nearly
    /// or exactly degenerate and a point nearly on an edge's circle lies nearly on its line's
    /// circle family's degenerate member — both q and h of its offset are rounding-sized.
    fn rounded_circle(scale: f64) -> Vec<[f64; 2]> {
        let mut v = Vec::new();
        for x in -25i32..=25 {
            for y in -25i32..=25 {
                if x * x + y * y == 625 {
                    v.push([x as f64 * scale, y as f64 * scale]);
                }
            }
        }
        let m = v.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        let s = crate::geom::exact::power_of_two_scale(m);
        v.iter().map(|q| q.map(|c| c * s)).collect()
    }

    /// Every pair's c₁′ ≥ c from the library — the Delaunay candidates by
    /// `EdgeFrame::c1_at_least` on their intervals, the edges beyond by `beyond_dt_2d` (c < 0)
    /// — against the exact oracle over all pairs.
    fn check_2d(pts: &[[f64; 2]], cs: &[f64]) {
        let input: Vec<Point2> = pts.iter().map(|q| Point2::new(q[0], q[1])).collect();
        let d = d2::triangulate(&input).unwrap();
        let p = coords2(&d);
        let q = ints(&p);
        let cand = candidates_2d(&d);
        let n = p.len();
        let exact: Vec<([u32; 2], Exact)> = (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .map(|(a, b)| ([a as u32, b as u32], exact_2d(&q, a, b)))
            .collect();
        for &c in cs {
            let want: BTreeSet<[u32; 2]> = exact
                .iter()
                .filter(|(_, e)| e.reaches(c))
                .map(|(k, _)| *k)
                .collect();
            let mut got = BTreeSet::new();
            for (e, iv) in cand.edges.iter().zip(&cand.intervals) {
                let f = EdgeFrame::new(p[e[0] as usize], p[e[1] as usize]);
                if f.c1_at_least(iv, c) {
                    got.insert([e[0].min(e[1]), e[0].max(e[1])]);
                }
            }
            if c < 0.0 {
                let (be, _) = beyond_dt_2d(&d, &cand, c);
                got.extend(be.iter().map(|e| [e[0].min(e[1]), e[0].max(e[1])]));
            }
            let missing: Vec<_> = want.difference(&got).collect();
            let extra: Vec<_> = got.difference(&want).collect();
            assert!(
                missing.is_empty() && extra.is_empty(),
                "c = {c}: missing {missing:?}, extra {extra:?}"
            );
        }
    }

    /// Issue 17, 2D: rounded cocircular points at every scale, alone and with a twin of each
    /// point moved along the circle's tangent by a few units in the last place (still on the
    /// circle to rounding). The 2D analogue of a triangle's circumcircle is the edge's end
    /// pair: a twin of an end lies nearly on the edge's line *and* nearly on its diametral
    /// circle, so q and h of its offset are both rounding-sized and the old float quotient
    /// q / 2h (through the rounded midpoint) was meaningless — while the twin binds the
    /// interval of every edge at that end.
    #[test]
    fn beyond_2d_matches_exact_oracle_on_rounded_cocircular_sets() {
        for scale in [1e-300, 1e-150, 0.1, 1.0, 1e150, 1e300] {
            let p = rounded_circle(scale);
            assert_eq!(p.len(), 20);
            check_2d(&p, &[-0.9, -0.5, 0.0, 0.5]);
            let mut twins = p.clone();
            for (i, q) in p.iter().enumerate() {
                let d = [1e-15, 4e-15, 3e-14][i % 3];
                twins.push([q[0] - d * q[1], q[1] + d * q[0]]);
            }
            check_2d(&twins, &[-0.9, -0.5, 0.0, 0.5]);
        }
    }

    /// The exact decision: c within 1e-12 of triangles' γ-values (and equal to them) on random
    /// points, every triple by `TriFrame::c1_at_least` and the triangles beyond the Delaunay
    /// tetrahedralization by `beyond_dt_3d`, against the exact oracle. A float comparison of
    /// the rounded γ-value with c gets some of these wrong.
    #[test]
    fn gamma_decision_is_exact_near_gamma_values_3d() {
        let pts = random_3d(16, 4300);
        let input: Vec<Point3> = pts.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let d = d3::triangulate(&input).unwrap();
        let p = coords3(&d);
        let q = ints(&p);
        let cand = candidates_3d(&d);
        let known: BTreeSet<[u32; 3]> = cand.triangles.iter().copied().collect();
        let vals = gamma_values_3d(&p);
        let mut cs = Vec::new();
        for (k, (_, v)) in vals.iter().enumerate().filter(|(k, _)| k % 7 == 0) {
            let c1 = v.1;
            if c1.abs() < 0.95 && c1 != 0.0 {
                let ulp = f64::from_bits(c1.to_bits() + 1) - c1;
                cs.extend([c1, c1 + ulp, c1 - ulp]);
                if k % 2 == 0 {
                    cs.extend([c1 + 1e-13, c1 - 1e-13, c1 + 9e-13, c1 - 9e-13]);
                }
            }
        }
        assert!(cs.len() > 60);
        let n = p.len();
        let mut triples = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                for e in b + 1..n {
                    triples.push([a, b, e]);
                }
            }
        }
        let exact: Vec<Exact> = triples
            .iter()
            .map(|&t| exact_3d(&q, t).expect("random points: no three collinear"))
            .collect();
        let ivs: Vec<_> = triples
            .iter()
            .map(|t| {
                let f = TriFrame::new(p[t[0]], p[t[1]], p[t[2]]).unwrap();
                (f, center_interval_3d(&p, t[0], t[1], t[2]).unwrap())
            })
            .collect();
        let mut wrong = Vec::new();
        for &c in &cs {
            let mut want_beyond = BTreeSet::new();
            for ((t, ex), (f, iv)) in triples.iter().zip(&exact).zip(&ivs) {
                let w = ex.reaches(c);
                if f.c1_at_least(iv, c) != w {
                    wrong.push((c, *t, w));
                }
                let key = t.map(|v| v as u32);
                if w && !known.contains(&key) {
                    want_beyond.insert(key);
                }
            }
            if c < 0.0 {
                let (tris, _) = beyond_dt_3d(&d, &cand, c, u64::MAX).unwrap();
                let got: BTreeSet<[u32; 3]> = tris.into_iter().collect();
                assert_eq!(got, want_beyond, "beyond_dt_3d at c = {c:e}");
            }
        }
        assert!(
            wrong.is_empty(),
            "{} wrong decisions: {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(5)]
        );
    }

    /// Parameters at, and one ulp either side of, some of the (rounded) γ-values of `vals`.
    fn near_values(vals: &[f64], every: usize) -> Vec<f64> {
        let mut cs: Vec<f64> = Vec::new();
        for &v in vals.iter().step_by(every) {
            if v.abs() < 1.0 && v != 0.0 {
                let up = f64::from_bits(v.to_bits() + 1);
                let down = f64::from_bits(v.to_bits() - 1);
                cs.extend([v, up, down]);
            }
        }
        cs
    }

    /// The graph kinds that put a parameter at c: the four bounds of γ([c₀,c₁],[c₂,c₃]) and
    /// γ(c₀, c₁) with c as either parameter.
    fn kinds_at(c: f64) -> Vec<crate::graphs::Kind> {
        use crate::graphs::Kind::*;
        vec![
            GammaRange([c, 1.0, -1.0, 1.0]),
            GammaRange([-1.0, c, -1.0, 1.0]),
            GammaRange([-1.0, 1.0, c, 1.0]),
            GammaRange([-1.0, 1.0, -1.0, c]),
            Gamma(c, -1.0),
            Gamma(0.0, c),
            Gamma(c, c),
        ]
    }

    fn oracle_of(ex: &Exact, kind: crate::graphs::Kind) -> bool {
        match kind {
            crate::graphs::Kind::Gamma(c0, c1) => ex.in_gamma(c0, c1),
            crate::graphs::Kind::GammaRange(r) => ex.in_range(r),
            _ => unreachable!(),
        }
    }

    /// More than 300 graphs were compared and none differed from the exact oracle (`wrong`:
    /// each wrong graph's kind and the size of its symmetric difference).
    fn assert_none_wrong<K: std::fmt::Debug>(checked: usize, wrong: &[(K, usize)]) {
        assert!(checked > 300, "{checked}");
        assert!(
            wrong.is_empty(),
            "{} of {checked} graphs wrong: {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(6)]
        );
    }

    /// `morpho graph --kind gamma | gamma-range` (`graph_2d`) with a parameter at or one ulp
    /// from a γ-value (c₀′ or c₁′) of some edge, on rounded cocircular sets at every scale
    /// (with and without near twins, see above) and random points, against the exact oracle
    /// over all pairs. The decisions through the rounded γ-values (`in_gamma_range`) and the
    /// float offsets (`CenterInterval::neighborhood_empty`) get some of these wrong.
    #[test]
    fn gamma_graphs_2d_are_exact_at_gamma_values() {
        use crate::graphs::graph_2d;
        let mut sets = vec![super::random_2d(24, 7)];
        for scale in [1e-300, 0.1, 1e300] {
            let p = rounded_circle(scale);
            let mut twins = p.clone();
            for (i, q) in p.iter().enumerate() {
                let d = [1e-15, 4e-15, 3e-14][i % 3];
                twins.push([q[0] - d * q[1], q[1] + d * q[0]]);
            }
            sets.push(p);
            sets.push(twins);
        }
        let mut wrong = Vec::new();
        let mut checked = 0;
        for pts in &sets {
            let q = ints(pts);
            let n = pts.len();
            let exact: Vec<([u32; 2], Exact)> = (0..n)
                .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
                .map(|(a, b)| ([a as u32, b as u32], exact_2d(&q, a, b)))
                .collect();
            let vals: Vec<f64> = super::gamma_values_2d(pts)
                .iter()
                .flat_map(|(_, v)| [v.0, v.1])
                .collect();
            let input: Vec<Point2> = pts.iter().map(|q| Point2::new(q[0], q[1])).collect();
            for c in near_values(&vals, 89) {
                for kind in kinds_at(c) {
                    let want: BTreeSet<[u32; 2]> = exact
                        .iter()
                        .filter(|(_, e)| oracle_of(e, kind))
                        .map(|(k, _)| *k)
                        .collect();
                    let g = graph_2d(&input, kind).unwrap();
                    let got: BTreeSet<[u32; 2]> = g
                        .edges
                        .iter()
                        .map(|e| [e[0].min(e[1]), e[0].max(e[1])])
                        .collect();
                    checked += 1;
                    if got != want {
                        wrong.push((kind, want.symmetric_difference(&got).count()));
                    }
                }
            }
        }
        assert_none_wrong(checked, &wrong);
    }

    /// The 3D analogue (`graph_3d`, `morpho graph --kind gamma | gamma-range` on 3D points):
    /// parameters at and one ulp from triangles' γ-values on random points, against the exact
    /// oracle over all triples.
    #[test]
    fn gamma_graphs_3d_are_exact_at_gamma_values() {
        use crate::graphs::graph_3d;
        let pts = random_3d(14, 4301);
        let q = ints(&pts);
        let n = pts.len();
        let mut exact = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                for c in b + 1..n {
                    let t = [a, b, c];
                    exact.push((t.map(|v| v as u32), exact_3d(&q, t).unwrap()));
                }
            }
        }
        let vals: Vec<f64> = gamma_values_3d(&pts)
            .iter()
            .flat_map(|(_, v)| [v.0, v.1])
            .collect();
        let input: Vec<Point3> = pts.iter().map(|q| Point3::new(q[0], q[1], q[2])).collect();
        let mut wrong = Vec::new();
        let mut checked = 0;
        for c in near_values(&vals, 23) {
            for kind in kinds_at(c) {
                let want: BTreeSet<[u32; 3]> = exact
                    .iter()
                    .filter(|(_, e)| oracle_of(e, kind))
                    .map(|(k, _)| *k)
                    .collect();
                let g = graph_3d(&input, kind).unwrap();
                let got: BTreeSet<[u32; 3]> = g
                    .triangles
                    .iter()
                    .map(|t| {
                        let mut t = *t;
                        t.sort_unstable();
                        t
                    })
                    .collect();
                checked += 1;
                if got != want {
                    wrong.push((kind, want.symmetric_difference(&got).count()));
                }
            }
        }
        assert_none_wrong(checked, &wrong);
    }
}

//! Oracle tests of the γ machinery against the literal definitions, and the inclusion hierarchy
//! of Veltkamp Fig. 3.2 with Lemmas 3.1–3.3.

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

fn circle_2d(n: usize) -> Vec<[f64; 2]> {
    // points on the circle x² + y² = 25 with integer coordinates, plus the centre
    let mut v: Vec<[f64; 2]> = vec![
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
    v.truncate(n.min(12));
    v
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
            let want: BTreeMap<[u32; 3], (f64, f64)> = all
                .iter()
                .filter(|(t, v)| v.1 >= c && !known.contains(t))
                .map(|(t, v)| (*t, *v))
                .collect();
            let (tris, ivs) = beyond_dt_3d(&d, &cand, c);
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
    }
}

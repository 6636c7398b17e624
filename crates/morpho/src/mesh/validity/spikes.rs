//! Zero-area spikes of a polygon ring and their removal (the GIS repair of collinear
//! back-tracks; issue 18 follow-up).
//!
//! Map data often holds a *spike*: a vertex `v` whose two edges `u v` and `v w` lie on one line
//! and point back onto each other (`orient2d(u, v, w) = 0` and `(v − u)·(w − v) < 0`, both
//! exact), and repeated consecutive vertices. Neither encloses area, yet the ring is not simple
//! (the two edges overlap), so [`super::check_polygon`] refuses it. [`remove_spikes`] removes
//! every spike tip and every repeated consecutive vertex, re-examining the neighbours after
//! each removal (a spike of several back-tracks, or a tip whose removal makes the next vertex a
//! repeat, goes in one pass), around the closing edge too. Removing a tip replaces `u v w` by
//! `u w`, a sub-segment of the union of the two edges: the signed area is unchanged exactly
//! (the triangle `u v w` has area 0), and the point set of the boundary only loses the spike.
//! Nothing else is touched: a ring that crosses itself stays refused.
//!
//! Decisions are exact: `orient2d` and the sign of the dot product in expansion arithmetic
//! (only evaluated for collinear triples). O(n) time.

use crate::geom::expansion::Expansion;
use crate::geom::predicates::raw::orient2d;
use crate::geom::Point2;

/// The result of [`remove_spikes`].
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct SpikeRepair {
    /// Input indices of the vertices kept, in ring order (starting at the smallest).
    pub kept: Vec<usize>,
    /// Input indices of the vertices removed (spike tips and repeats), increasing.
    pub removed: Vec<usize>,
}

/// `(v − u)·(w − v) < 0`, exactly.
fn backtracks(u: [f64; 2], v: [f64; 2], w: [f64; 2]) -> bool {
    let d = |k: usize| Expansion::diff(v[k], u[k]).mul(&Expansion::diff(w[k], v[k]));
    d(0).add(&d(1)).sign() < 0
}

/// Is `v` the tip of a spike between `u` and `w`?
fn spike(u: [f64; 2], v: [f64; 2], w: [f64; 2]) -> bool {
    orient2d(u, v, w) == 0.0 && backtracks(u, v, w)
}

/// Removes the zero-area spikes and repeated consecutive vertices of the closed ring `points`
/// (see the module doc). When fewer than three vertices remain, the ring enclosed no area.
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::mesh::validity::remove_spikes;
/// // a square with a spike out of its top edge at vertex 3: (1, 2) → (1, 3) → (1, 2)
/// let p = [(0., 0.), (2., 0.), (2., 2.), (1., 2.), (1., 3.), (1., 2.), (0., 2.)]
///     .map(|(x, y)| Point2::new(x, y));
/// let r = remove_spikes(&p);
/// assert_eq!(r.removed, vec![4, 5]); // the tip, then the repeat of vertex 3
/// assert_eq!(r.kept, vec![0, 1, 2, 3, 6]);
/// ```
pub fn remove_spikes(points: &[Point2]) -> SpikeRepair {
    let p = |i: usize| [points[i].x, points[i].y];
    let (mut s, mut removed): (Vec<usize>, Vec<usize>) = (Vec::with_capacity(points.len()), vec![]);
    for i in 0..points.len() {
        s.push(i);
        loop {
            let m = s.len();
            if m >= 2 && p(s[m - 2]) == p(s[m - 1]) {
                removed.extend(s.pop());
            } else if m >= 3 && spike(p(s[m - 3]), p(s[m - 2]), p(s[m - 1])) {
                removed.push(s.remove(m - 2));
            } else {
                break;
            }
        }
    }
    // the closing edge: triples through s[m − 1] → s[0]
    loop {
        let m = s.len();
        if m < 3 {
            break;
        }
        if p(s[m - 1]) == p(s[0]) || spike(p(s[m - 2]), p(s[m - 1]), p(s[0])) {
            removed.extend(s.pop());
        } else if spike(p(s[m - 1]), p(s[0]), p(s[1])) {
            removed.push(s.remove(0));
        } else {
            break;
        }
    }
    removed.sort_unstable();
    SpikeRepair { kept: s, removed }
}

/// Twice the signed area of the ring `points[ring]`, exactly (shoelace sum in expansions).
#[cfg(test)]
pub(crate) fn area2_exact(points: &[Point2], ring: &[usize]) -> Expansion {
    let mut e = Expansion::zero();
    for k in 0..ring.len() {
        let (a, b) = (points[ring[k]], points[ring[(k + 1) % ring.len()]]);
        e = e
            .add(&Expansion::from(a.x).scale(b.y))
            .sub(&Expansion::from(b.x).scale(a.y));
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::validity::check_polygon;

    fn pts(v: &[(f64, f64)]) -> Vec<Point2> {
        v.iter().map(|&(x, y)| Point2::new(x, y)).collect()
    }

    fn same_area(p: &[Point2], r: &SpikeRepair) -> bool {
        let all: Vec<usize> = (0..p.len()).collect();
        area2_exact(p, &all).sub(&area2_exact(p, &r.kept)).sign() == 0
    }

    fn simple(p: &[Point2], kept: &[usize]) -> bool {
        let c: Vec<u32> = kept.iter().map(|&i| i as u32).collect();
        check_polygon(p, &c).simple
    }

    #[test]
    fn synthetic_spikes_go_and_the_area_stays() {
        // (ring, removed): a spike back-tracking three times back to its root (then a repeat),
        // a spike through the closing edge, a tip at vertex 0, a repeat, no spike, a diagonal
        // spike
        type Case = (Vec<(f64, f64)>, Vec<usize>);
        let cases: Vec<Case> = vec![
            (
                vec![
                    (0., 0.),
                    (4., 0.),
                    (4., 4.),
                    (2., 4.),
                    (2., 7.),
                    (2., 5.),
                    (2., 6.),
                    (2., 4.),
                    (0., 4.),
                ],
                vec![4, 5, 6, 7],
            ),
            (
                vec![(0., 0.), (4., 0.), (4., 4.), (0., 4.), (0., 6.)],
                vec![4],
            ),
            (
                vec![(0., 6.), (0., 0.), (4., 0.), (4., 4.), (0., 4.)],
                vec![0],
            ),
            (
                vec![(0., 0.), (4., 0.), (4., 0.), (4., 4.), (0., 4.)],
                vec![2],
            ),
            (
                vec![
                    (0., 0.),
                    (1., 0.),
                    (0.1 * 3.0, 0.7),
                    (1.0 / 3.0, 0.5),
                    (1., 1.),
                    (0., 1.),
                ],
                vec![],
            ),
            (
                vec![
                    (0., 0.),
                    (3., 0.),
                    (3., 3.),
                    (1.5, 1.5),
                    (2.5, 2.5),
                    (0., 3.),
                ],
                vec![3],
            ),
        ];
        for (ring, want) in cases {
            let p = pts(&ring);
            let r = remove_spikes(&p);
            assert_eq!(r.removed, want, "{ring:?}");
            assert!(same_area(&p, &r), "{ring:?}");
            if !want.is_empty() {
                let all: Vec<usize> = (0..p.len()).collect();
                assert!(!simple(&p, &all), "{ring:?}: spikes are not simple");
                assert!(simple(&p, &r.kept), "{ring:?}: {:?}", r.kept);
            }
        }
    }

    #[test]
    fn forward_collinear_vertices_and_crossings_are_kept() {
        // collinear but not back-tracking: kept
        let p = pts(&[(0., 0.), (1., 0.), (2., 0.), (2., 2.), (0., 2.)]);
        assert!(remove_spikes(&p).removed.is_empty());
        // a bow-tie is no spike: nothing removed, still not simple
        let b = pts(&[(0., 0.), (1., 1.), (1., 0.), (0., 1.)]);
        let r = remove_spikes(&b);
        assert!(r.removed.is_empty());
        assert!(!simple(&b, &r.kept));
        // a near-collinear back-track (not exactly collinear) is a real, thin triangle: kept
        let t = pts(&[
            (0., 0.),
            (4., 0.),
            (4., 4.),
            (2., 4.),
            (2.0 + 1e-15, 7.),
            (2., 5.),
            (0., 4.),
        ]);
        assert!(remove_spikes(&t).removed.is_empty());
        // all vertices on one line: the ring collapses
        let l = pts(&[(0., 0.), (1., 0.), (2., 0.), (1., 0.)]);
        assert!(remove_spikes(&l).kept.len() < 3);
    }

    #[test]
    fn australia_spikes_are_repaired_with_the_area_unchanged() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/data/polygons/coast_australia_mainland_ne10m.csv"
        );
        let Ok(s) = crate::io::read_shapes2(std::path::Path::new(path)) else {
            return;
        };
        let p = &s.polygons[0].rings[0];
        let r = remove_spikes(p);
        // data README: segments 5080/5082 and 7181/7183 overlap; the tips are 5081 and 7182
        assert_eq!(r.removed, vec![5081, 7182]);
        assert!(simple(p, &r.kept));
        assert!(same_area(p, &r));
    }
}

//! The 3D dispatch of [`super::build`]: [`graph_3d`] builds every [`Kind`] on 3D points from
//! the Delaunay tetrahedralization (Veltkamp 1992 §2.2 and ch. 3); degenerate input and γ with a
//! parameter −1 use the brute force of V Thm 3.1 ([`BRUTE_LIMIT_3D`] points), α with a > 0 the
//! hull vertices ([`ALPHA_HULL_LIMIT_3D`]).

use super::beyond3;
use super::brute;
use super::build::{extreme_scale, scaled_kind, Graph, Kind, ALPHA_HULL_LIMIT_3D, BRUTE_LIMIT_3D};
use super::distance::classic;
use super::fast;
use super::gamma::{CenterInterval, TriFrame};
use super::GraphError;
use crate::delaunay::d3;
use crate::geom::distance::dot_sign;
use crate::geom::grid::PointGrid as Grid;
use crate::geom::vec::dist2;
use crate::geom::Point3;

type Result<T, E = GraphError> = std::result::Result<T, E>;

/// A triangle with its γ-values when the graph kind has them.
type Simplex3 = ([u32; 3], Option<[f64; 2]>);
/// Decides a candidate triangle: `None` to drop it, `Some(γ-values)` to keep it.
type TriPredicate<'a> = dyn Fn(&CenterInterval, &[u32; 3]) -> Option<Option<[f64; 2]>> + 'a;

fn finish3(
    d: &d3::Delaunay3,
    edges: Vec<[u32; 2]>,
    mut tris: Vec<([u32; 3], Option<[f64; 2]>)>,
) -> Graph {
    let map = |v: u32| d.input_of_vertex[v as usize];
    let mut e: Vec<[u32; 2]> = edges
        .into_iter()
        .map(|[a, b]| {
            let (a, b) = (map(a), map(b));
            [a.min(b), a.max(b)]
        })
        .collect();
    e.sort_unstable();
    e.dedup();
    for (t, _) in tris.iter_mut() {
        *t = t.map(map);
        t.sort_unstable();
    }
    tris.sort_by_key(|x| x.0);
    tris.dedup_by(|x, y| x.0 == y.0);
    let gamma = if !tris.is_empty() && tris.iter().all(|x| x.1.is_some()) {
        tris.iter().map(|x| x.1.unwrap_or_default()).collect()
    } else {
        vec![]
    };
    Graph {
        dim: 3,
        edges: e,
        triangles: tris.into_iter().map(|x| x.0).collect(),
        gamma,
    }
}

/// Builds a graph on 3D points (duplicates merged). Kinds made of triangles (hull, Delaunay,
/// α, γ) fill `triangles`; the others `edges`. Circle-based β and lune-based β with b < 0 are
/// not defined in 3D (V §2.2.11).
///
/// Sets at extreme scales are first scaled exactly, as in [`graph_2d`](super::graph_2d). Complexity: see
/// [`crate::graphs`]; degenerate input and γ with a parameter −1 are limited to
/// [`BRUTE_LIMIT_3D`] points, α with a > 0 to [`ALPHA_HULL_LIMIT_3D`] hull vertices.
///
/// ```rust
/// use morpho::graphs::{graph_3d, GraphError, Kind};
/// use morpho::geom::Point3;
/// // a tetrahedron with a point inside: the hull has 4 triangles, the Delaunay
/// // tetrahedralization's 4 tetrahedra have 10 distinct triangles
/// let p = [[0., 0., 0.], [4., 0., 0.], [0., 4., 0.], [0., 0., 4.], [1., 1., 1.]]
///     .map(|[x, y, z]| Point3::new(x, y, z));
/// assert_eq!(graph_3d(&p, Kind::Hull).unwrap().triangles.len(), 4);
/// assert_eq!(graph_3d(&p, Kind::Delaunay).unwrap().triangles.len(), 10);
/// assert_eq!(graph_3d(&p, Kind::Emst).unwrap().edges.len(), 4);
/// let e = graph_3d(&p, Kind::BetaCircle(0.5)).unwrap_err();
/// assert!(matches!(e, GraphError::Only2d { kind: "beta-circle", .. }));
/// ```
pub fn graph_3d(points: &[Point3], kind: Kind) -> Result<Graph> {
    kind.validate()?;
    if let Some(s) = extreme_scale(points.iter().flat_map(|q| [q.x, q.y, q.z]))? {
        let scaled: Vec<Point3> = points.iter().map(|q| q * s).collect();
        return graph_3d(&scaled, scaled_kind(kind, s)?);
    }
    let d = d3::triangulate(points)?;
    let p = fast::coords3(&d);
    if let Some(why) = &d.degenerate {
        if p.len() > BRUTE_LIMIT_3D {
            return Err(GraphError::DegenerateTooLarge {
                why: why.clone(),
                points: p.len(),
                limit: BRUTE_LIMIT_3D,
            });
        }
        return brute_3d(&d, &p, kind);
    }
    // the triples of cospherical (and flat) groups — up to g³/6 of them — only for the kinds
    // made of such triangles; the others need the Delaunay faces and the groups' pairs. The
    // triangles of hull facets that only a half-space leaves empty (γ-values (−1, 1)) only
    // for the γ kinds with a parameter −1.
    let triples = match kind {
        Kind::Gamma(c0, c1) if c0 <= -1.0 || c1 <= -1.0 => fast::GroupTriples::All,
        Kind::GammaRange(r) if r[0] <= -1.0 => fast::GroupTriples::All,
        Kind::Gamma(..) | Kind::GammaRange(_) => fast::GroupTriples::Balls,
        Kind::Alpha(a) if a < 0.0 => fast::GroupTriples::Balls,
        _ => fast::GroupTriples::Faces,
    };
    let (cand, groups) = fast::candidates_3d_with(&d, triples);
    let mut dt_edges: Vec<[u32; 2]> = Vec::with_capacity(d.tets.len() * 2);
    for t in &d.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                dt_edges.push([t[i].min(t[j]), t[i].max(t[j])]);
            }
        }
    }
    dt_edges.sort_unstable();
    dt_edges.dedup();
    // the frame of a candidate triangle, for the exact γ decisions (the binding points and the
    // decisions do not depend on the order of the corners)
    let frame = |t: &[u32; 3]| TriFrame::new(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]);
    let tri_filter = |f: &TriPredicate<'_>| -> Vec<Simplex3> {
        cand.triangles
            .iter()
            .zip(&cand.intervals)
            .filter_map(|(t, iv)| f(iv, t).map(|g| (*t, g)))
            .collect()
    };
    let gabriel = || -> Vec<[u32; 2]> {
        // candidate pairs: Delaunay edges and pairs within cospherical (and flat) groups, each
        // decided exactly below (a superset of the Gabriel edges: every Gabriel edge is an edge
        // of the Delaunay subdivision)
        let mut pairs = dt_edges.clone();
        for vs in &groups {
            for i in 0..vs.len() {
                pairs.extend(vs[i + 1..].iter().map(|&w| [vs[i], w]));
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let grid = Grid::new(&p, 2.0);
        pairs
            .into_iter()
            .filter(|e| {
                let (u, v) = (p[e[0] as usize], p[e[1] as usize]);
                let m = [
                    0.5 * (u[0] + v[0]),
                    0.5 * (u[1] + v[1]),
                    0.5 * (u[2] + v[2]),
                ];
                grid.for_each_within(m, 0.5 * dist2(u, v).sqrt() * (1.0 + 1e-9), |x| {
                    x == e[0] || x == e[1] || dot_sign(&u, &v, &p[x as usize]) >= 0
                })
            })
            .collect()
    };
    Ok(match kind {
        Kind::Delaunay => finish3(
            &d,
            dt_edges,
            cand.triangles
                .iter()
                .zip(&cand.in_dt)
                .filter(|x| *x.1)
                .map(|x| (*x.0, None))
                .collect(),
        ),
        Kind::Hull => finish3(
            &d,
            vec![],
            hull_3d(&d, &p).into_iter().map(|t| (t, None)).collect(),
        ),
        Kind::Gamma(c0, c1) if c1 >= 0.0 => finish3(
            &d,
            vec![],
            tri_filter(&|iv, t| {
                let v = iv.gamma_values()?;
                frame(t)?.in_gamma(iv, c0, c1).then_some(Some([v.0, v.1]))
            }),
        ),
        Kind::GammaRange(r) if r[2] >= 0.0 => finish3(
            &d,
            vec![],
            tri_filter(&|iv, t| {
                let v = iv.gamma_values()?;
                frame(t)?.in_gamma_range(iv, r).then_some(Some([v.0, v.1]))
            }),
        ),
        Kind::Gamma(..) | Kind::GammaRange(_) => {
            // c₁ < 0 (c₂ < 0): the candidates plus the triangles beyond the tetrahedralization
            let (c, keep): (f64, &TriPredicate<'_>) = match kind {
                Kind::Gamma(c0, c1) => (c1, &move |iv: &CenterInterval, t: &[u32; 3]| {
                    let v = iv.gamma_values()?;
                    frame(t)?.in_gamma(iv, c0, c1).then_some(Some([v.0, v.1]))
                }),
                Kind::GammaRange(r) => (r[2], &move |iv: &CenterInterval, t: &[u32; 3]| {
                    let v = iv.gamma_values()?;
                    frame(t)?.in_gamma_range(iv, r).then_some(Some([v.0, v.1]))
                }),
                _ => unreachable!("matched above"),
            };
            if c <= -1.0 && p.len() > BRUTE_LIMIT_3D {
                return Err(GraphError::GammaMinusOneTooLarge {
                    points: p.len(),
                    limit: BRUTE_LIMIT_3D,
                });
            }
            let mut t = tri_filter(keep);
            let (bt, bi) = beyond3::beyond_dt_3d(&d, &cand, c, super::triple_limit())?;
            t.extend(
                bt.iter()
                    .zip(&bi)
                    .filter_map(|(t, iv)| keep(iv, t).map(|g| (*t, g))),
            );
            finish3(&d, vec![], t)
        }
        Kind::Alpha(a) if a < 0.0 => {
            let rad = 1.0 / a.abs();
            finish3(
                &d,
                vec![],
                tri_filter(&|iv, t| {
                    let (m, r2, n) = super::gamma::triangle_circle(
                        p[t[0] as usize],
                        p[t[1] as usize],
                        p[t[2] as usize],
                    )?;
                    let _ = m;
                    let h2 = rad * rad - r2;
                    if h2 < 0.0 {
                        return None;
                    }
                    let s = h2.sqrt() / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    (iv.ball_empty(s) || iv.ball_empty(-s)).then_some(None)
                }),
            )
        }
        Kind::Alpha(0.0) => finish3(
            &d,
            vec![],
            hull_3d(&d, &p).into_iter().map(|t| (t, None)).collect(),
        ),
        Kind::Alpha(a) => {
            let mut hv: Vec<u32> = d.hull.iter().flatten().copied().collect();
            hv.sort_unstable();
            hv.dedup();
            if hv.len() > ALPHA_HULL_LIMIT_3D {
                return Err(GraphError::AlphaHullTooLarge {
                    hull_vertices: hv.len(),
                    limit: ALPHA_HULL_LIMIT_3D,
                });
            }
            let hp: Vec<[f64; 3]> = hv.iter().map(|&v| p[v as usize]).collect();
            let t = brute::alpha_3d(&hp, a);
            finish3(
                &d,
                vec![],
                t.into_iter()
                    .map(|t| (t.map(|i| hv[i as usize]), None))
                    .collect(),
            )
        }
        Kind::BetaCircle(b) | Kind::BetaLune(b)
            if matches!(kind, Kind::BetaCircle(_)) || b < 0.0 =>
        {
            return Err(GraphError::Only2d {
                kind: kind.name(),
                b,
                degenerate: false,
            })
        }
        Kind::Gabriel => finish3(&d, gabriel(), vec![]),
        _ => {
            let g = gabriel();
            finish3(
                &d,
                classic(&p, &d.input_of_vertex, &dt_edges, &g, kind)?,
                vec![],
            )
        }
    })
}

/// The 3D hull triangles of Def. 2.10: the hull facets of the tetrahedralization, and for
/// coplanar facets with more than three points every empty non-degenerate triangle of them.
fn hull_3d(d: &d3::Delaunay3, p: &[[f64; 3]]) -> Vec<[u32; 3]> {
    use crate::geom::predicates::raw;
    let h = &d.hull;
    // group hull triangles that share an edge and are coplanar
    let mut parent: Vec<usize> = (0..h.len()).collect();
    fn root(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut by_edge: std::collections::HashMap<[u32; 2], usize> = std::collections::HashMap::new();
    for (i, t) in h.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = [a.min(b), a.max(b)];
            if let Some(&j) = by_edge.get(&key) {
                let other = h[j];
                let apex = other
                    .iter()
                    .copied()
                    .find(|&x| x != a && x != b)
                    .unwrap_or(a);
                let q = t.map(|x| p[x as usize]);
                if raw::orient3d(q[0], q[1], q[2], p[apex as usize]) == 0.0 {
                    let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ri] = rj;
                }
            } else {
                by_edge.insert(key, i);
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<u32>> = std::collections::BTreeMap::new();
    let mut out: Vec<[u32; 3]> = Vec::new();
    let mut gsize: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for i in 0..h.len() {
        *gsize.entry(root(&mut parent, i)).or_default() += 1;
    }
    for (i, t) in h.iter().enumerate() {
        let r = root(&mut parent, i);
        if gsize[&r] == 1 {
            let mut s = *t;
            s.sort_unstable();
            out.push(s);
        } else {
            groups.entry(r).or_default().extend_from_slice(t);
        }
    }
    for (_, mut vs) in groups {
        vs.sort_unstable();
        vs.dedup();
        let gp: Vec<[f64; 3]> = vs.iter().map(|&v| p[v as usize]).collect();
        // every empty triangle of the facet, O(1) each after O(g² log g) ([`super::facets`];
        // testing every triple against every point was O(g⁴): hours on the 1597 points of the
        // fandisk model's top facet)
        let start = out.len();
        super::facets::empty_triangles_3d(&gp, |i, j, k| {
            let mut t = [vs[i as usize], vs[j as usize], vs[k as usize]];
            t.sort_unstable();
            out.push(t);
        });
        // (as before: no triangle whose floating-point normal vanishes)
        let mut k = start;
        for i in start..out.len() {
            let t = out[i].map(|v| p[v as usize]);
            let n = crate::geom::vec::cross(
                crate::geom::vec::sub(t[1], t[0]),
                crate::geom::vec::sub(t[2], t[0]),
            );
            if n != [0.0, 0.0, 0.0] {
                out[k] = out[i];
                k += 1;
            }
        }
        out.truncate(k);
    }
    out
}

/// Brute-force 3D construction (V Thm 3.1) for small or degenerate inputs.
fn brute_3d(d: &d3::Delaunay3, p: &[[f64; 3]], kind: Kind) -> Result<Graph> {
    let tris = |t: Vec<([u32; 3], Option<[f64; 2]>)>| finish3(d, vec![], t);
    let edges = |e: Vec<[u32; 2]>| finish3(d, e, vec![]);
    Ok(match kind {
        // decided exactly on each triangle's interval (see `graph_3d`)
        Kind::Gamma(c0, c1) => tris(
            brute::gamma_filter_3d(p, |f, iv| f.in_gamma(iv, c0, c1))
                .into_iter()
                .map(|(t, v)| (t, Some([v.0, v.1])))
                .collect(),
        ),
        Kind::GammaRange(r) => tris(
            brute::gamma_filter_3d(p, |f, iv| f.in_gamma_range(iv, r))
                .into_iter()
                .map(|(t, v)| (t, Some([v.0, v.1])))
                .collect(),
        ),
        Kind::Hull => tris(brute::hull_3d(p).into_iter().map(|t| (t, None)).collect()),
        Kind::Delaunay => tris(
            brute::gamma_filter_3d(p, |f, iv| f.in_gamma_range(iv, [-1.0, 1.0, 0.0, 1.0]))
                .into_iter()
                .map(|(t, _)| (t, None))
                .collect(),
        ),
        Kind::Alpha(a) => tris(
            brute::alpha_3d(p, a)
                .into_iter()
                .map(|t| (t, None))
                .collect(),
        ),
        Kind::ClosestPairs => edges(brute::closest_pairs(p)),
        Kind::Nng => edges(brute::nng(p)),
        Kind::Emst => edges(brute::emst(p)),
        Kind::Strip => edges(brute::strip(p)),
        Kind::Sig => edges(brute::sig(p)),
        Kind::Rng => edges(brute::rng(p)),
        Kind::Gabriel => edges(brute::gabriel(p)),
        Kind::BetaLune(b) if b >= 0.0 => edges(brute::beta_lune(p, b)),
        Kind::BetaCircle(b) | Kind::BetaLune(b) => {
            return Err(GraphError::Only2d {
                kind: kind.name(),
                b,
                degenerate: true,
            })
        }
    })
}

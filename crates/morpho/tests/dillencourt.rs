//! V §5.4, Fig. 5.7: a two-connected, non-degenerate, non-Hamiltonian Delaunay triangulation
//! (after Dillencourt 1987; the point set is `samples::dillencourt_points`) and the
//! Hamiltonicity fallback of the γ-constriction through it.
//!
//! The Hamilton-cycle search used here is exhaustive (backtracking with pruning) and is itself
//! checked against a permutation brute force and on graphs whose Hamiltonicity is known.

use morpho::boundary::{boundary_2d, check_polygon, Boundary2, CParam, Options2, PolygonCheck};
use morpho::delaunay::{triangulate_2d, Delaunay2};
use morpho::geom::{incircle, orient2d, Point2};
use morpho::graphs::{graph_2d, Kind};
use morpho::samples::dillencourt_points;
use morpho::util::NONE;
use std::collections::HashSet;

/// Adjacency lists of an undirected simple graph on `n` vertices.
fn adjacency(n: usize, edges: &[[usize; 2]]) -> Vec<Vec<usize>> {
    let mut adj = vec![Vec::new(); n];
    for &[a, b] in edges {
        assert_ne!(a, b);
        if !adj[a].contains(&b) {
            adj[a].push(b);
            adj[b].push(a);
        }
    }
    adj
}

/// Exhaustive search for a Hamilton cycle: paths from vertex 0 are extended depth-first; a branch
/// is cut when an unvisited vertex has fewer than two neighbours that can still be its cycle
/// neighbours (unvisited vertices, the path's end, vertex 0). Returns the cycle if there is one.
fn hamilton_cycle(adj: &[Vec<usize>]) -> Option<Vec<usize>> {
    let n = adj.len();
    if n < 3 {
        return None;
    }
    let mut on_path = vec![false; n];
    let mut path = vec![0];
    on_path[0] = true;
    fn feasible(adj: &[Vec<usize>], on_path: &[bool], end: usize) -> bool {
        (0..adj.len()).filter(|&u| !on_path[u]).all(|u| {
            adj[u]
                .iter()
                .filter(|&&x| !on_path[x] || x == end || x == 0)
                .count()
                >= 2
        })
    }
    fn extend(adj: &[Vec<usize>], on_path: &mut [bool], path: &mut Vec<usize>) -> bool {
        let end = *path.last().unwrap();
        if path.len() == adj.len() {
            return adj[end].contains(&0);
        }
        for &x in &adj[end] {
            if on_path[x] {
                continue;
            }
            on_path[x] = true;
            path.push(x);
            if feasible(adj, on_path, x) && extend(adj, on_path, path) {
                return true;
            }
            path.pop();
            on_path[x] = false;
        }
        false
    }
    if extend(adj, &mut on_path, &mut path) {
        Some(path)
    } else {
        None
    }
}

/// The oracle: every cyclic order of the vertices (vertex 0 first), n ≤ 8.
fn brute_hamiltonian(adj: &[Vec<usize>]) -> bool {
    let n = adj.len();
    if n < 3 {
        return false;
    }
    let mut rest: Vec<usize> = (1..n).collect();
    fn permute(k: usize, rest: &mut Vec<usize>, adj: &[Vec<usize>]) -> bool {
        if k == rest.len() {
            let mut prev = 0;
            for &v in rest.iter() {
                if !adj[prev].contains(&v) {
                    return false;
                }
                prev = v;
            }
            return adj[prev].contains(&0);
        }
        for i in k..rest.len() {
            rest.swap(k, i);
            if permute(k + 1, rest, adj) {
                return true;
            }
            rest.swap(k, i);
        }
        false
    }
    permute(0, &mut rest, adj)
}

/// `cyc` visits every vertex once along edges of `adj`.
fn is_hamilton_cycle(adj: &[Vec<usize>], cyc: &[usize]) -> bool {
    let mut seen = vec![false; adj.len()];
    for &v in cyc {
        if v >= adj.len() || seen[v] {
            return false;
        }
        seen[v] = true;
    }
    cyc.len() == adj.len()
        && (0..cyc.len()).all(|i| adj[cyc[i]].contains(&cyc[(i + 1) % cyc.len()]))
}

fn connected_without(adj: &[Vec<usize>], removed: &[usize]) -> bool {
    let n = adj.len();
    let Some(start) = (0..n).find(|v| !removed.contains(v)) else {
        return true;
    };
    let mut seen = vec![false; n];
    for &r in removed {
        seen[r] = true;
    }
    seen[start] = true;
    let mut stack = vec![start];
    let mut count = 1;
    while let Some(u) = stack.pop() {
        for &x in &adj[u] {
            if !seen[x] {
                seen[x] = true;
                count += 1;
                stack.push(x);
            }
        }
    }
    count + removed.len() == n
}

fn complete(n: usize) -> Vec<Vec<usize>> {
    let mut e = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            e.push([a, b]);
        }
    }
    adjacency(n, &e)
}

/// Wheel: hub 0 joined to the cycle 1..=k.
fn wheel(k: usize) -> Vec<Vec<usize>> {
    let mut e = Vec::new();
    for i in 0..k {
        e.push([0, 1 + i]);
        e.push([1 + i, 1 + (i + 1) % k]);
    }
    adjacency(k + 1, &e)
}

/// The Herschel graph (graph of the enneahedron): poles N = 0, S = 1, equator E_i = 2 + i,
/// upper U_i = 5 + i ~ N, E_i, E_{i+1}; lower L_i = 8 + i ~ S, E_i, E_{i+1} (i = 0, 1, 2).
/// 11 vertices, 18 edges, 9 quadrilateral faces, bipartite with classes of 5 and 6.
fn herschel() -> Vec<Vec<usize>> {
    let mut e = Vec::new();
    for i in 0..3 {
        let (ei, ej) = (2 + i, 2 + (i + 1) % 3);
        e.extend([[0, 5 + i], [5 + i, ei], [5 + i, ej]]);
        e.extend([[1, 8 + i], [8 + i, ei], [8 + i, ej]]);
    }
    adjacency(11, &e)
}

/// Petersen graph: outer 5-cycle, inner pentagram, spokes.
fn petersen() -> Vec<Vec<usize>> {
    let mut e = Vec::new();
    for i in 0..5 {
        e.extend([[i, (i + 1) % 5], [5 + i, 5 + (i + 2) % 5], [i, 5 + i]]);
    }
    adjacency(10, &e)
}

#[test]
fn hamilton_search_on_known_graphs() {
    let k4 = complete(4);
    assert!(is_hamilton_cycle(&k4, &hamilton_cycle(&k4).unwrap()));
    for k in 3..12 {
        let w = wheel(k);
        assert!(is_hamilton_cycle(&w, &hamilton_cycle(&w).unwrap()), "W{k}");
    }
    // Herschel: planar, 11 vertices, 18 edges, bipartite 5 + 6 (so no Hamilton cycle), 3-connected
    let h = herschel();
    assert_eq!(h.iter().map(Vec::len).sum::<usize>(), 36);
    let mut side = [usize::MAX; 11];
    side[0] = 0;
    let mut stack = vec![0];
    while let Some(u) = stack.pop() {
        for &x in &h[u] {
            if side[x] == usize::MAX {
                side[x] = 1 - side[u];
                stack.push(x);
            }
            assert_ne!(side[x], side[u], "not bipartite");
        }
    }
    assert_eq!(side.iter().filter(|&&s| s == 0).count(), 5);
    for a in 0..11 {
        for b in a + 1..11 {
            assert!(connected_without(&h, &[a, b]), "Herschel cut {{{a}, {b}}}");
        }
    }
    assert!(hamilton_cycle(&h).is_none());
    assert!(hamilton_cycle(&petersen()).is_none());
    // a cycle with a pendant path is not Hamiltonian; a plain cycle is
    let mut c6 = adjacency(6, &[[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0]]);
    assert!(hamilton_cycle(&c6).is_some());
    c6.push(vec![2]);
    c6[2].push(6);
    assert!(hamilton_cycle(&c6).is_none());
    // K_{2,3}: not Hamiltonian
    let k23 = adjacency(5, &[[0, 2], [0, 3], [0, 4], [1, 2], [1, 3], [1, 4]]);
    assert!(hamilton_cycle(&k23).is_none());
}

#[test]
fn hamilton_search_agrees_with_brute_force() {
    // every graph from a fixed pseudo-random stream, 4..=8 vertices, various densities
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let (mut yes, mut no) = (0, 0);
    for round in 0..400 {
        let n = 4 + round % 5;
        let density = 30 + (next() % 50);
        let mut e = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                if next() % 100 < density {
                    e.push([a, b]);
                }
            }
        }
        let adj = adjacency(n, &e);
        let brute = brute_hamiltonian(&adj);
        match hamilton_cycle(&adj) {
            Some(c) => {
                assert!(brute, "{adj:?}");
                assert!(is_hamilton_cycle(&adj, &c), "{adj:?} {c:?}");
                yes += 1;
            }
            None => {
                assert!(!brute, "{adj:?}");
                no += 1;
            }
        }
    }
    assert!(yes > 50 && no > 50, "{yes} {no}");
}

fn delaunay() -> (Vec<Point2>, Delaunay2, Vec<Vec<usize>>) {
    let p = dillencourt_points();
    let d = triangulate_2d(&p).unwrap();
    assert_eq!(d.points.len(), p.len(), "no duplicates");
    // adjacency by input index
    let e: Vec<[usize; 2]> = d
        .edges()
        .iter()
        .map(|&[a, b]| {
            [
                d.input_of_vertex[a as usize] as usize,
                d.input_of_vertex[b as usize] as usize,
            ]
        })
        .collect();
    let adj = adjacency(p.len(), &e);
    (p, d, adj)
}

#[test]
fn delaunay_is_non_degenerate_and_two_connected() {
    let (p, d, adj) = delaunay();
    assert_eq!(p.len(), 20);
    // non-degenerate: no triangle is flat, and across every interior edge the fourth point is
    // strictly outside the circumcircle (exact): the Delaunay triangulation is unique
    let mut interior_edges = 0;
    for (t, tri) in d.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| d.points[v as usize]);
        assert!(orient2d(&a, &b, &c) > 0.0);
        for i in 0..3 {
            let nb = d.neighbors[t][i];
            if nb == NONE {
                continue;
            }
            interior_edges += 1;
            let opp = d.triangles[nb as usize]
                .iter()
                .find(|v| !tri.contains(v))
                .copied()
                .unwrap();
            assert!(incircle(&a, &b, &c, &d.points[opp as usize]) < 0.0);
        }
    }
    assert_eq!(interior_edges / 2 + d.hull.len(), d.edges().len());
    // two-connected: no cut vertex
    for v in 0..p.len() {
        assert!(connected_without(&adj, &[v]), "cut vertex {v}");
    }
    // but not three-connected: {s1, s2} = {2, 4} cuts off the ear h2 = 3
    assert!(!connected_without(&adj, &[2, 4]));
}

#[test]
fn delaunay_has_the_forcing_structure() {
    let (_, d, adj) = delaunay();
    let hull: Vec<usize> = d
        .hull
        .iter()
        .map(|&v| d.input_of_vertex[v as usize] as usize)
        .collect();
    // ears h1, h2, h3 (1, 3, 5): hull vertices of degree 2 between s0..s3 (0, 2, 4, 6)
    for (h, [a, b]) in [(1, [0, 2]), (3, [2, 4]), (5, [4, 6])] {
        assert!(hull.contains(&h));
        let mut nb = adj[h].clone();
        nb.sort();
        assert_eq!(nb, vec![a, b], "ear {h}");
    }
    // v (7) has degree 3: s1, s2 (both saturated by their ears) and w (8)
    let mut nv = adj[7].clone();
    nv.sort();
    assert_eq!(nv, vec![2, 4, 8]);
}

#[test]
fn delaunay_has_no_hamilton_cycle() {
    let (_, _, adj) = delaunay();
    assert!(hamilton_cycle(&adj).is_none());
    // the search is not blind on this graph: one more edge at v (v–h2, 7–3, not a Delaunay
    // edge) breaks the forcing argument, and the search then finds a Hamilton cycle
    let mut more = adj.clone();
    more[7].push(3);
    more[3].push(7);
    let c = hamilton_cycle(&more).expect("a cycle once v has a second usable edge");
    assert!(is_hamilton_cycle(&more, &c));
}

/// Runs the γ boundary with `c` and checks the result against the graph it was built from:
/// returns (boundary, polygon check, γ([-1,1],[c_used,1]) edges).
fn run(p: &[Point2], c: CParam) -> (Boundary2, PolygonCheck, HashSet<[u32; 2]>) {
    let b = boundary_2d(
        p,
        &Options2 {
            method: morpho::boundary::Method2::Gamma {
                c,
                keep: Vec::new(),
            },
        },
    )
    .unwrap();
    let chk = check_polygon(p, &b.polygon);
    let g = graph_2d(p, Kind::GammaRange([-1.0, 1.0, b.c_used, 1.0])).unwrap();
    let edges: HashSet<[u32; 2]> = g.edges.into_iter().collect();
    eprintln!(
        "{c:?}: c_used {} all_on_boundary {} vertices {} simple {} deletions {} polygon {:?}",
        b.c_used,
        b.all_on_boundary,
        b.polygon.len(),
        chk.simple,
        b.deleted.len(),
        b.polygon
    );
    (b, chk, edges)
}

fn polygon_edges(poly: &[u32]) -> Vec<[u32; 2]> {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            [a.min(b), a.max(b)]
        })
        .collect()
}

#[test]
fn delaunay_constriction_locks() {
    // c = 0 (Delaunay only, no fallback): a simple polygon that must miss a point — it misses v
    let p = dillencourt_points();
    let (b, chk, g) = run(&p, CParam::Fixed(0.0));
    assert_eq!(b.c_used, 0.0);
    assert!(!b.all_on_boundary);
    assert!(chk.simple);
    assert_eq!(chk.missing, vec![7]);
    assert_eq!(b.left_out, vec![7]);
    assert!(polygon_edges(&b.polygon).iter().all(|e| g.contains(e)));
}

#[test]
fn auto_fallback_finds_a_hamilton_polygon() {
    let p = dillencourt_points();
    let (b, chk, g) = run(&p, CParam::Auto);
    assert!(b.all_on_boundary);
    assert!(chk.simple && chk.missing.is_empty() && chk.area2 > 0.0);
    assert_eq!(b.polygon.len(), p.len());
    // the first augmentation step suffices (V: "γ([-1,1],[-0.1,1]) is already Hamiltonian")
    assert_eq!(b.c_used, -0.1);
    // every polygon edge is an edge of γ([-1,1],[-0.1,1]), and (the Delaunay graph having no
    // Hamilton cycle) at least one is not a Delaunay edge
    let dt: HashSet<[u32; 2]> = graph_2d(&p, Kind::Delaunay)
        .unwrap()
        .edges
        .into_iter()
        .collect();
    let pe = polygon_edges(&b.polygon);
    assert!(pe.iter().all(|e| g.contains(e)), "{pe:?}");
    assert!(pe.iter().any(|e| !dt.contains(e)));
}

#[test]
fn fixed_negative_c_as_in_fig_5_7() {
    // γ([-1,1],[c,1]) constricted from the convex hull for the three graphs of Fig. 5.7: each
    // gives a simple polygon through all 20 points made of its own edges
    let p = dillencourt_points();
    for c in [-0.1, -0.2, -0.3] {
        let (b, chk, g) = run(&p, CParam::Fixed(c));
        assert_eq!(b.c_used, c);
        assert!(b.all_on_boundary, "c = {c}");
        assert!(chk.simple && chk.missing.is_empty(), "c = {c}");
        assert!(
            polygon_edges(&b.polygon).iter().all(|e| g.contains(e)),
            "c = {c}"
        );
    }
}

#[test]
fn mirrored_and_reordered_copies_behave_alike() {
    // x → −x and a reversed input order are exact transformations: the triangulation stays
    // non-Hamiltonian and the fallback still reaches every point
    let base = dillencourt_points();
    let mirrored: Vec<Point2> = base.iter().map(|q| Point2::new(-q.x, q.y)).collect();
    let reversed: Vec<Point2> = base.iter().rev().copied().collect();
    for p in [mirrored, reversed] {
        let d = triangulate_2d(&p).unwrap();
        let e: Vec<[usize; 2]> = d
            .edges()
            .iter()
            .map(|&[a, b]| {
                [
                    d.input_of_vertex[a as usize] as usize,
                    d.input_of_vertex[b as usize] as usize,
                ]
            })
            .collect();
        assert!(hamilton_cycle(&adjacency(p.len(), &e)).is_none());
        let (b, chk, _) = run(&p, CParam::Auto);
        assert!(b.all_on_boundary && chk.simple && chk.missing.is_empty());
        let (b0, _, _) = run(&p, CParam::Fixed(0.0));
        assert_eq!(b0.polygon.len(), p.len() - 1);
    }
}

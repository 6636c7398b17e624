//! The three-split's local edge split: the macro edges the three-split cannot make G¹ (above
//! all the inflected ones) get a new vertex on the surface, and the macro triangles around
//! them are bisected and three-split again (a documented deviation from Veltkamp 1992, §9.6:
//! the text has no such case; issue 19, NOTES B.5).
//!
//! **Why.** On an inflected edge (both tangent planes on the same side of the chord,
//! `(n_a·d)(n_b·d) ≥ 0`) the degree-elevated quadratic boundary of `transversal.rs` does not
//! exist near the edge (the two tangent planes meet far away or not at all), so the edge keeps
//! its cubic boundary and (9.4); where (9.4) is ill-conditioned there is no cubic pair of
//! micro patches meeting a common normal field and the edge stays creased (reported).
//!
//! **The construction.** After a first three-split pass (unchanged, [`super::three_split`]),
//! every macro edge `ab` that its a-posteriori check lists as not G¹ is split at
//! `S = B(½)`, the midpoint of its first-pass boundary curve, with the normal
//! `n_S = (n_P + n_Q)/|n_P + n_Q|` of the two first-pass patches there (both are orthogonal to
//! the boundary tangent at `S`, so `n_S` is too, and it is the surface's normal wherever the
//! edge was nearly G¹). An S-shaped edge is split near its inflection, so each half is convex
//! (its end tangent planes on opposite sides of its chord) and gets a usable quadratic
//! boundary and the explicit G¹ construction of `transversal.rs`. Every macro triangle
//! `(a, b, c)` with split edges is bisected at each of them (`(a, S, c)`, `(S, b, c)`, and
//! again for a second split edge inside the sub-triangle that holds it), and the refined
//! mesh — still a closed, consistently oriented 2-manifold, since both triangles of a split
//! edge are bisected at the same `S` — is three-split again with the same options. So each
//! sub-triangle is an ordinary three-split macro triangle and every G¹ argument of `split3.rs`
//! and `transversal.rs` holds for it verbatim: the new edges `S–c` are macro edges of the
//! refined mesh (G¹ by the same construction, checked by the same a-posteriori check), and
//! each half of a split edge is G¹ by `transversal.rs` where it is not reported. Only the
//! macro triangles next to a split edge (their sub-triangles) and their neighbours (whose
//! Step 5 reads the changed first rows) change; elsewhere the second pass recomputes the same
//! numbers. So the passes after the first are local (`split3::three_split_pass` with the
//! previous pass as `Reuse`): the quadratic boundaries, fold-guard decisions, Step-5 results
//! and a-posteriori verdicts of the unchanged edges and the Step-4 patches of the unchanged
//! triangles are taken over, everything else recomputed; the result is the full re-run's bit
//! for bit (the reference `split_rounds(…, local = false)` of the tests).
//!
//! **Interpolation.** Every input vertex keeps its position and normal (Step 1–2 of the
//! second pass); `S` is a new interpolated point on the first-pass surface.
//!
//! **Output.** A macro triangle with `k` split edges has `3(k + 1)` micro patches (each
//! patch's `macro_tri` is the input triangle); the patches stay in input-triangle order and
//! [`SplitSurface::domain`] gives each patch's corners in its input triangle (the split point
//! is the domain midpoint of its edge), so the patch JSON (`{"macro": t, "control": …}`) is
//! unchanged in form, only longer. The edge lists are mapped back to input edges: a half
//! `a–S` of the split edge `ab` is reported as `[a, b]`; a non-G¹ edge inside an input
//! triangle (`S–c`) is reported by its triangle in [`SplitSurface::non_g1_inner`].
//! Up to [`ROUNDS`] rounds: the halves and inner edges still listed after a round are split
//! again. A mesh whose first pass is G¹ everywhere is returned untouched (byte-identical).

use super::split3::{three_split_pass, Reuse, SplitOptions, SplitSurface};
use super::triangle::BezierTriangle;
use super::SmoothError;
use crate::geom::{vec, Point3, Vector3};
use crate::mesh::TriMesh;
use crate::util::IdMap;
use std::collections::BTreeSet;

type P3 = [f64; 3];

/// Largest number of split rounds.
pub(crate) const ROUNDS: usize = 2;

/// A refined mesh and where its pieces come from.
struct Refined {
    mesh: TriMesh,
    normals: Vec<Vector3>,
    /// Per refined triangle: the input triangle and its corners' barycentric coordinates there.
    origin: Vec<(u32, [P3; 3])>,
    /// Per refined vertex: the input edge it lies on (`None` for input vertices and points
    /// inside an input triangle); input vertices are `0..nv`.
    on_edge: Vec<Option<[u32; 2]>>,
    /// The number of input vertices.
    nv: usize,
    /// Per refined triangle: the previous mesh's triangle it is (same corners, same order),
    /// `util::NONE` for a new (bisected) one.
    from: Vec<u32>,
}

/// The three-split with the local edge split (module doc).
pub(crate) fn three_split_split(
    mesh: &TriMesh,
    normals: &[Vector3],
    opts: &SplitOptions,
) -> Result<SplitSurface, SmoothError> {
    split_rounds(mesh, normals, opts, true)
}

/// The rounds of the edge split; with `local`, each pass after the first reuses the previous
/// one wherever its inputs are unchanged (`split3::three_split_pass`: bit for bit the full
/// pass, which `local = false` runs, the reference of the tests).
fn split_rounds(
    mesh: &TriMesh,
    normals: &[Vector3],
    opts: &SplitOptions,
    local: bool,
) -> Result<SplitSurface, SmoothError> {
    let (first, mut cache) = three_split_pass(mesh, normals, opts, None)?;
    if first.non_g1_edges.is_empty() {
        return Ok(first);
    }
    let nv = mesh.positions.len();
    let unit = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut cur = Refined {
        mesh: TriMesh {
            positions: mesh.positions.clone(),
            triangles: mesh.triangles.clone(),
            ..TriMesh::default()
        },
        normals: normals.to_vec(),
        origin: (0..mesh.triangles.len() as u32)
            .map(|t| (t, unit))
            .collect(),
        on_edge: vec![None; nv],
        nv,
        from: Vec::new(),
    };
    let mut surf = first;
    let mut split_input: BTreeSet<[u32; 2]> = BTreeSet::new();
    for _ in 0..ROUNDS {
        let Some(next) = refine(&cur, &surf, &mut split_input) else {
            break;
        };
        cur = next;
        let reuse = Reuse {
            cache: &cache,
            surf: &surf,
            from: &cur.from,
        };
        let (s, c) = three_split_pass(&cur.mesh, &cur.normals, opts, local.then_some(&reuse))?;
        surf = s;
        cache = c;
        if surf.non_g1_edges.is_empty() {
            break;
        }
    }
    Ok(map_back(surf, &cur, nv, split_input))
}

/// The input edge a refined edge `[x, y]` lies on, if any.
fn input_edge(r: &Refined, nv: usize, x: u32, y: u32) -> Option<[u32; 2]> {
    let on = |v: u32| r.on_edge[v as usize];
    let (xi, yi) = ((x as usize) < nv, (y as usize) < nv);
    match (xi, yi) {
        (true, true) => Some([x.min(y), x.max(y)]),
        (true, false) => on(y).filter(|e| e.contains(&x)),
        (false, true) => on(x).filter(|e| e.contains(&y)),
        (false, false) => on(x).filter(|e| Some(*e) == on(y)),
    }
}

/// One round: split every edge `surf` lists as not G¹ (and whose split point is usable);
/// `None` when no edge can be split.
fn refine(
    r: &Refined,
    surf: &SplitSurface,
    split_input: &mut BTreeSet<[u32; 2]>,
) -> Option<Refined> {
    let tris = &r.mesh.triangles;
    // the half-edges of the listed edges (both directions), found by one scan of the triangles
    let mut half: IdMap<(u32, u32), usize> = IdMap::default();
    for &[a, b] in &surf.non_g1_edges {
        half.insert((a, b), usize::MAX);
        half.insert((b, a), usize::MAX);
    }
    for (t, tri) in tris.iter().enumerate() {
        for i in 0..3 {
            if let Some(h) = half.get_mut(&(tri[i], tri[(i + 1) % 3])) {
                *h = 3 * t + i;
            }
        }
    }
    half.retain(|_, h| *h != usize::MAX);
    let mut positions = r.mesh.positions.clone();
    let mut normals = r.normals.clone();
    let mut on_edge = r.on_edge.clone();
    // split point of each chosen edge
    let mut split: IdMap<(u32, u32), u32> = IdMap::default();
    for &[a, b] in &surf.non_g1_edges {
        let (Some(&p), Some(&q)) = (half.get(&(a, b)), half.get(&(b, a))) else {
            continue;
        };
        let c = &surf.patches[p].control;
        // the boundary's midpoint (b300, b210, b120, b030 run a → b)
        let s = vec::scale(
            vec::add(vec::add(c[0], c[6]), vec::scale(vec::add(c[1], c[3]), 3.0)),
            0.125,
        );
        let np = BezierTriangle::new(3, c.to_vec()).normal([0.5, 0.5, 0.0]);
        let nq = BezierTriangle::new(3, surf.patches[q].control.to_vec()).normal([0.5, 0.5, 0.0]);
        let n = vec::add(np, nq);
        let l = vec::norm(n);
        if !(l > 1e-3 && s.iter().all(|x| x.is_finite()) && l.is_finite()) {
            continue;
        }
        let id = positions.len() as u32;
        positions.push(Point3::new(s[0], s[1], s[2]));
        normals.push(Vector3::new(n[0] / l, n[1] / l, n[2] / l));
        let ie = input_edge(r, r.nv, a, b);
        on_edge.push(ie);
        if let Some(e) = ie {
            split_input.insert(e);
        }
        split.insert((a, b), id);
        split.insert((b, a), id);
    }
    if split.is_empty() {
        return None;
    }
    let mut triangles = Vec::with_capacity(tris.len() + 2 * split.len());
    let mut origin = Vec::with_capacity(tris.len() + 2 * split.len());
    let mut from = Vec::with_capacity(tris.len() + 2 * split.len());
    for (t, tri) in tris.iter().enumerate() {
        let (o, dom) = r.origin[t];
        if (0..3).all(|i| !split.contains_key(&(tri[i], tri[(i + 1) % 3]))) {
            // not bisected (most triangles): the same triangle
            triangles.push(*tri);
            origin.push((o, dom));
            from.push(t as u32);
            continue;
        }
        let mut subs: Vec<([u32; 3], [P3; 3])> = vec![(*tri, dom)];
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            let Some(&s) = split.get(&(a, b)) else {
                continue;
            };
            // the sub-triangle that still holds the whole edge a → b
            let Some((k, j)) = subs.iter().enumerate().find_map(|(k, (v, _))| {
                (0..3)
                    .find(|&j| v[j] == a && v[(j + 1) % 3] == b)
                    .map(|j| (k, j))
            }) else {
                continue;
            };
            let (v, d) = subs[k];
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let ds = vec::scale(vec::add(d[j], d[j1]), 0.5);
            subs[k] = ([v[j], s, v[j2]], [d[j], ds, d[j2]]);
            subs.push(([s, v[j1], v[j2]], [ds, d[j1], d[j2]]));
        }
        let kept = if subs.len() == 1 {
            t as u32
        } else {
            crate::util::NONE
        };
        for (v, d) in subs {
            triangles.push(v);
            origin.push((o, d));
            from.push(kept);
        }
    }
    // keep the refined triangles grouped by input triangle (patch order = input order)
    let mut order: Vec<usize> = (0..triangles.len()).collect();
    order.sort_by_key(|&k| origin[k].0);
    let triangles = order.iter().map(|&k| triangles[k]).collect();
    let origin = order.iter().map(|&k| origin[k]).collect();
    let from = order.iter().map(|&k| from[k]).collect();
    Some(Refined {
        mesh: TriMesh {
            positions,
            triangles,
            ..TriMesh::default()
        },
        normals,
        origin,
        on_edge,
        nv: r.nv,
        from,
    })
}

/// The refined surface in terms of the input mesh (module doc, "Output").
fn map_back(
    mut s: SplitSurface,
    r: &Refined,
    nv: usize,
    split_input: BTreeSet<[u32; 2]>,
) -> SplitSurface {
    use rayon::prelude::*;
    s.domain = s
        .patches
        .par_iter_mut()
        .enumerate()
        .map(|(k, p)| {
            let (o, d) = r.origin[k / 3];
            let i = k % 3;
            let z = vec::scale(vec::add(vec::add(d[0], d[1]), d[2]), 1.0 / 3.0);
            p.macro_tri = o;
            [d[i], d[(i + 1) % 3], z]
        })
        .collect();
    let mut inner: BTreeSet<u32> = BTreeSet::new();
    let map = |list: &mut Vec<[u32; 2]>, inner: Option<&mut BTreeSet<u32>>| {
        let mut out: BTreeSet<[u32; 2]> = BTreeSet::new();
        let mut inside = Vec::new();
        for &[a, b] in list.iter() {
            match input_edge(r, nv, a, b) {
                Some(e) => {
                    out.insert(e);
                }
                None => inside.push([a, b]),
            }
        }
        if let Some(inner) = inner {
            for [a, b] in inside {
                // the input triangle of a refined edge inside it
                if let Some(k) = r
                    .mesh
                    .triangles
                    .iter()
                    .position(|t| t.contains(&a) && t.contains(&b))
                {
                    inner.insert(r.origin[k].0);
                }
            }
        }
        *list = out.into_iter().collect();
    };
    map(&mut s.non_g1_edges, Some(&mut inner));
    map(&mut s.singular_edges, None);
    map(&mut s.unresolved_edges, None);
    map(&mut s.sign_warnings, None);
    map(&mut s.fold_guarded, None);
    s.non_g1_inner = inner.into_iter().collect();
    s.split_edges = split_input.into_iter().collect();
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::smooth::split3::three_split_once;
    use crate::smooth::{continuity, non_g1_causes, visible_normals};

    /// Spot (CLI defaults: area normals, visibility repair, fold guard) has 16 inflected
    /// non-G¹ edges in the first pass. After the split: every split point is the midpoint of
    /// its first-pass boundary with the normalised sum of the two first-pass normals there
    /// (each term of the construction, checked on the output's patch corners), every input
    /// vertex and normal is interpolated, the domains tile their macro triangles, at most one
    /// inflected edge stays creased (main: 16), and every non-G¹ macro edge is listed.
    #[test]
    fn spot_inflected_edges_are_split_and_g1() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/data/meshes/spot.obj"
        );
        if !std::path::Path::new(path).exists() {
            eprintln!("note: {path} absent; skipping");
            return;
        }
        let m = crate::io::read_mesh(std::path::Path::new(path)).unwrap();
        let n0 = crate::mesh::vertex_normals(&m, crate::mesh::NormalWeighting::Area);
        let n = visible_normals(&m, &n0, 0.05).normals;
        let opts = SplitOptions { fold_guard: true };
        let first = three_split_once(&m, &n, &opts).unwrap();
        let s = three_split_split(&m, &n, &opts).unwrap();
        let c0 = continuity(&first, 20);
        let k0 = non_g1_causes(&first, &m, &n, &c0);
        assert!(k0.inflected >= 10, "{k0:?}");
        assert!(!s.split_edges.is_empty());
        // split points and normals from the first pass, found among the output's corners
        let corner_normals: Vec<(P3, P3)> = s
            .patches
            .iter()
            .flat_map(|p| {
                let t = p.triangle();
                [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].map(|b| (t.eval(b), t.normal(b)))
            })
            .collect();
        let tris = &m.triangles;
        for &[a, b] in &first.non_g1_edges {
            let (t, i) = (0..tris.len())
                .find_map(|t| {
                    (0..3)
                        .find(|&i| tris[t][i] == a && tris[t][(i + 1) % 3] == b)
                        .map(|i| (t, i))
                })
                .unwrap();
            let (u, j) = (0..tris.len())
                .find_map(|t| {
                    (0..3)
                        .find(|&i| tris[t][i] == b && tris[t][(i + 1) % 3] == a)
                        .map(|i| (t, i))
                })
                .unwrap();
            let (cp, cq) = (
                &first.patches[3 * t + i].control,
                &first.patches[3 * u + j].control,
            );
            let sp = BezierTriangle::new(3, cp.to_vec());
            let sq = BezierTriangle::new(3, cq.to_vec());
            let want = sp.eval([0.5, 0.5, 0.0]);
            let nn = vec::add(sp.normal([0.5, 0.5, 0.0]), sq.normal([0.5, 0.5, 0.0]));
            let nn = vec::scale(nn, 1.0 / vec::norm(nn));
            let hit = corner_normals
                .iter()
                .find(|(x, _)| vec::dist(*x, want) <= 1e-12 * (1.0 + vec::norm(want)));
            let (_, got_n) = hit.unwrap_or_else(|| panic!("no split point on edge {a}-{b}"));
            let ang = vec::norm(vec::cross(*got_n, nn)).atan2(vec::dot(*got_n, nn));
            assert!(ang <= 1e-10, "edge {a}-{b}: normal off by {ang}");
        }
        // interpolation of every input vertex and its normal at every patch corner there
        let pos: Vec<P3> = m.positions.iter().map(|p| (*p).into()).collect();
        let mut seen = vec![false; pos.len()];
        for (p, d) in s.patches.iter().zip(&s.domain) {
            let tri = m.triangles[p.macro_tri as usize];
            for (k, corner) in d.iter().take(2).enumerate() {
                let Some(v) = (0..3).find(|&v| corner[v] == 1.0) else {
                    continue;
                };
                let vi = tri[v] as usize;
                seen[vi] = true;
                let b = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]][k];
                let t = p.triangle();
                assert!(vec::dist(t.eval(b), pos[vi]) <= 1e-12 * (1.0 + vec::norm(pos[vi])));
                let nv = [n[vi].x, n[vi].y, n[vi].z];
                let nv = vec::scale(nv, 1.0 / vec::norm(nv));
                let got = t.normal(b);
                let ang = vec::norm(vec::cross(got, nv)).atan2(vec::dot(got, nv));
                assert!(ang <= 1e-10, "vertex {vi}: {ang}");
            }
        }
        assert!(seen.iter().all(|&x| x));
        // the domains tile their macro triangles: positive areas summing to 1 per triangle
        let mut area = vec![0.0; m.triangles.len()];
        for (p, d) in s.patches.iter().zip(&s.domain) {
            let e1 = vec::sub(d[1], d[0]);
            let e2 = vec::sub(d[2], d[0]);
            // signed area in the barycentric plane, relative to the whole triangle
            let a = vec::dot(vec::cross(e1, e2), [1.0; 3]) / 3.0;
            assert!(a > 0.0);
            area[p.macro_tri as usize] += a;
        }
        assert!(
            area.iter().all(|a| (a - 1.0).abs() <= 1e-12),
            "domain tiling"
        );
        let c = continuity(&s, 20);
        let k = non_g1_causes(&s, &m, &n, &c);
        eprintln!(
            "spot: first pass {:?}; split {:?}, {} split edges",
            k0,
            k,
            s.split_edges.len()
        );
        // 16 inflected edges before; one stays creased (spot's edge 327–1267: the half at
        // vertex 327 keeps an ill-conditioned end, reported), as do the 2 "other" edges
        // (1528–1531, 2622–2623: the quadratic handle at the vertex collapses)
        assert!(k.inflected <= 1 && k.inflected < k0.inflected, "{k:?}");
        assert_eq!(k.unlisted, 0, "{k:?}");
        assert!(c.non_g1_edges.len() <= 3, "{k:?}");
        assert_eq!(c.open_edges, 0);
        assert!(c.max_position_gap <= 1e-9);
    }

    /// Bit-for-bit equality of two split surfaces (every float by its bits).
    fn assert_same_bits(a: &SplitSurface, b: &SplitSurface, what: &str) {
        assert_eq!(a.patches.len(), b.patches.len(), "{what}: patch count");
        for (k, (p, q)) in a.patches.iter().zip(&b.patches).enumerate() {
            assert_eq!(p.macro_tri, q.macro_tri, "{what}: patch {k} macro");
            let bits = |c: &[P3; 10]| c.map(|x| x.map(f64::to_bits));
            assert_eq!(bits(&p.control), bits(&q.control), "{what}: patch {k}");
        }
        let dom = |s: &SplitSurface| -> Vec<u64> {
            s.domain
                .iter()
                .flatten()
                .flatten()
                .map(|x| x.to_bits())
                .collect()
        };
        assert_eq!(dom(a), dom(b), "{what}: domain");
        assert_eq!(a.singular_edges, b.singular_edges, "{what}: singular");
        assert_eq!(a.unresolved_edges, b.unresolved_edges, "{what}: unresolved");
        assert_eq!(a.sign_warnings, b.sign_warnings, "{what}: sign warnings");
        assert_eq!(a.fold_guarded, b.fold_guarded, "{what}: fold guarded");
        assert_eq!(a.non_g1_edges, b.non_g1_edges, "{what}: non-G1");
        assert_eq!(a.non_g1_inner, b.non_g1_inner, "{what}: non-G1 inner");
        assert_eq!(a.split_edges, b.split_edges, "{what}: split edges");
        assert_eq!(
            a.max_displacement.to_bits(),
            b.max_displacement.to_bits(),
            "{what}: displacement"
        );
    }

    /// The CLI's default normals: area weighting, then the visibility repair.
    fn cli_normals(m: &TriMesh) -> Vec<Vector3> {
        let n0 = crate::mesh::vertex_normals(m, crate::mesh::NormalWeighting::Area);
        visible_normals(m, &n0, 0.05).normals
    }

    /// The local passes against the full re-run on `m`, with and without the fold guard;
    /// returns how many edges the first pass split (with the guard).
    fn local_equals_full(m: &TriMesh, n: &[Vector3], what: &str) -> usize {
        let mut split = 0;
        for fold_guard in [false, true] {
            let opts = SplitOptions { fold_guard };
            let full = split_rounds(m, n, &opts, false).unwrap();
            let local = split_rounds(m, n, &opts, true).unwrap();
            assert_same_bits(&local, &full, &format!("{what}, fold guard {fold_guard}"));
            let cf = continuity(&full, 20);
            let cl = continuity(&local, 20);
            assert_eq!(cf.non_g1_edges, cl.non_g1_edges, "{what}");
            assert_eq!(
                cf.max_normal_jump_rad.to_bits(),
                cl.max_normal_jump_rad.to_bits(),
                "{what}"
            );
            if fold_guard {
                split = local.split_edges.len();
            }
        }
        split
    }

    /// The oracle of the local second pass (`split3::three_split_pass` with `Reuse`): the same
    /// surface, bit for bit, as the full re-run of the three-split on the refined mesh, and
    /// the same continuity figures, on the real meshes a test can afford.
    #[test]
    fn local_passes_equal_the_full_rerun_on_real_meshes() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data/meshes");
        // (the horse too, bit for bit, in 70 s under load: left to the CLI comparison in
        // bench/README "loc3", to keep the suite within its time)
        for name in ["spot.obj", "bunny_npm.obj", "fandisk.obj"] {
            let path = std::path::Path::new(dir).join(name);
            if !path.exists() {
                eprintln!("note: {} absent; skipping", path.display());
                continue;
            }
            let m = crate::io::read_mesh(&path).unwrap();
            let n = cli_normals(&m);
            let split = local_equals_full(&m, &n, name);
            eprintln!("{name}: {split} split edges, local = full");
            assert!(split > 0, "{name}: the test needs split edges");
        }
    }

    /// The same oracle on random closed meshes: icospheres with random radial noise (many
    /// inflected edges, hence splits in both rounds), area and visible normals.
    #[test]
    fn local_passes_equal_the_full_rerun_on_random_closed_meshes() {
        let mut rng = crate::util::Rng::new(19);
        let mut total = 0;
        for round in 0..6usize {
            let mut m = crate::mesh::generate::icosphere(2 + (round % 2) as u32);
            let amp = [0.05, 0.15, 0.3][round % 3];
            for p in &mut m.positions {
                let s = 1.0 + amp * (2.0 * rng.unit() - 1.0);
                *p = Point3::new(p.x * s, p.y * s, p.z * s);
            }
            let n = cli_normals(&m);
            total += local_equals_full(&m, &n, &format!("random mesh {round}"));
        }
        assert!(total > 0, "no split edges in the random meshes");
    }
}

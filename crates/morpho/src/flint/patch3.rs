//! The fallback division of an open or closed polyhedron into disc patches, used where the
//! shortest-path division of V §7.3.2 does not give parts bounded by their three paths
//! (genus > 0, several parts, coinciding or non-separating paths; see `region.rs`). A
//! deviation from the text, documented in `tree3.rs`.
//!
//! Patches grow breadth-first from the lowest unassigned triangle and take a neighbouring
//! triangle only when the patch stays a topological disc: the triangle brings a new vertex (an
//! ear), or it closes the notch at a boundary vertex (two of its edges on the patch). So every
//! patch has one simple boundary loop; its corners are three loop vertices a third of the loop
//! apart and its paths the three arcs between them, directed as the patch's triangles see them
//! (the patch lies left of them). Patches are capped at `cap` triangles so that every part is
//! smaller than the whole. O(n) expected for n triangles.

use crate::util::{IdMap, IdSet, NONE};
use std::collections::VecDeque;

/// Disc patches of `region` (each at most `cap` triangles, in growth order).
pub(crate) fn disc_patches(
    tris: &[[u32; 3]],
    nbr: &[[u32; 3]],
    region: &[u32],
    cap: usize,
) -> Vec<Vec<u32>> {
    let inside: IdSet<u32> = region.iter().copied().collect();
    let mut assigned: IdSet<u32> = IdSet::default();
    let mut out = Vec::new();
    for &seed in region {
        if assigned.contains(&seed) {
            continue;
        }
        let mut patch = vec![seed];
        let mut in_patch: IdSet<u32> = IdSet::default();
        let mut verts: IdSet<u32> = IdSet::default();
        in_patch.insert(seed);
        assigned.insert(seed);
        verts.extend(tris[seed as usize]);
        let mut queue: VecDeque<u32> = VecDeque::new();
        let push = |t: u32, q: &mut VecDeque<u32>, assigned: &IdSet<u32>| {
            for &n in &nbr[t as usize] {
                if n != NONE && inside.contains(&n) && !assigned.contains(&n) {
                    q.push_back(n);
                }
            }
        };
        push(seed, &mut queue, &assigned);
        while let Some(t) = queue.pop_front() {
            if patch.len() >= cap {
                break;
            }
            if assigned.contains(&t) {
                continue;
            }
            let tr = tris[t as usize];
            let on: Vec<usize> = (0..3)
                .filter(|&i| in_patch.contains(&nbr[t as usize][i]))
                .collect();
            let ok = match on.len() {
                // an ear: the vertex opposite the shared edge must be new
                1 => !verts.contains(&tr[(on[0] + 2) % 3]),
                // closes the notch at the vertex between the two shared edges
                2 => true,
                _ => false,
            };
            if !ok {
                continue;
            }
            in_patch.insert(t);
            assigned.insert(t);
            patch.push(t);
            verts.extend(tr);
            push(t, &mut queue, &assigned);
        }
        out.push(patch);
    }
    out
}

/// The boundary loop of a disc patch, directed as its triangles see it; `None` unless the
/// boundary edges form one simple loop of at least 3 vertices.
pub(crate) fn boundary_loop(
    tris: &[[u32; 3]],
    nbr: &[[u32; 3]],
    patch: &[u32],
) -> Option<Vec<u32>> {
    let inside: IdSet<u32> = patch.iter().copied().collect();
    let mut next: IdMap<u32, u32> = IdMap::default();
    let mut edges = 0usize;
    for &t in patch {
        let tr = tris[t as usize];
        for i in 0..3 {
            if !inside.contains(&nbr[t as usize][i]) {
                if next.insert(tr[i], tr[(i + 1) % 3]).is_some() {
                    return None; // a vertex twice on the boundary
                }
                edges += 1;
            }
        }
    }
    let &start = next.keys().min()?;
    let mut lp = vec![start];
    let mut v = *next.get(&start)?;
    while v != start {
        if lp.len() > edges {
            return None;
        }
        lp.push(v);
        v = *next.get(&v)?;
    }
    (lp.len() == edges && edges >= 3).then_some(lp)
}

/// The three corners and arcs of a loop (corners a third of the loop apart).
pub(crate) fn corners_and_arcs(lp: &[u32]) -> ([u32; 3], [Vec<u32>; 3]) {
    let m = lp.len();
    let (i1, i2) = (m / 3, (2 * m) / 3);
    let a0 = lp[..=i1].to_vec();
    let a1 = lp[i1..=i2].to_vec();
    let mut a2 = lp[i2..].to_vec();
    a2.push(lp[0]);
    ([lp[0], lp[i1], lp[i2]], [a0, a1, a2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{analyze_topology, generate};

    #[test]
    fn patches_are_discs_and_cover_a_torus() {
        let m = generate::torus(2.0, 0.7, 24, 12);
        let topo = analyze_topology(&m);
        let all: Vec<u32> = (0..m.triangles.len() as u32).collect();
        let ps = disc_patches(&m.triangles, &topo.neighbors, &all, all.len() / 2 + 1);
        let mut seen = vec![0; all.len()];
        for p in &ps {
            for &t in p {
                seen[t as usize] += 1;
            }
            let lp = boundary_loop(&m.triangles, &topo.neighbors, p);
            // a disc of k triangles with i interior vertices has a loop of k + 2 − 2i vertices
            assert!(
                lp.is_some() || p.len() == all.len(),
                "patch of {} is not a disc",
                p.len()
            );
        }
        assert!(seen.iter().all(|&c| c == 1));
        assert!(ps.len() >= 2, "a torus is no disc");
    }
}

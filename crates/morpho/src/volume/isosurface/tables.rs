//! Cell tables for the contour surface extraction (Hamann 1991, §3.2).
//!
//! * Cube geometry: corners `c = x + 2y + 4z`, the 12 edges (id `4·axis + j`, `j` numbering the
//!   two other coordinate bits in increasing axis order), the 6 faces (id `2·axis + side`) with
//!   their corners listed counter-clockwise seen from outside the cell.
//! * Contour polygons of a cell (H §3.2): for every sign configuration (bit c set ⇔ corner c has
//!   f ≥ α after the perturbation of Rem. 3.8) and every choice on the ambiguous faces (Eq. 3.5),
//!   the closed polygons through the cut edges. On a face, a segment runs from the edge where the
//!   counter-clockwise traversal enters the region f > α to the edge where it leaves it; this keeps
//!   the region f > α on the right of every segment seen from outside the cell, so the polygons —
//!   and the triangles built from them in polygon order — have normals pointing out of {f > α}.
//!   Each polygon records the first face carrying two of its segments (Thm. 3.4 (ii)); such
//!   polygons are triangulated as a fan around an interior contour point (Thm. 3.5–3.6).
//! * The six tetrahedra T¹…T⁶ of H §3.2 and, for each tetrahedron and each of its 16 sign
//!   configurations, the oriented triangles of the planar cut.
//!
//! All tables are built once (lazily) from these definitions, not typed in: 256 · 64 polygon sets
//! (O(1) each) and 6 · 16 tetrahedron cases.

use std::sync::OnceLock;

/// Corners of each face, counter-clockwise seen from outside (outward normal ∓ axis).
pub const FACE_CORNERS: [[u8; 4]; 6] = [
    [0, 4, 6, 2], // x = 0
    [1, 3, 7, 5], // x = 1
    [0, 1, 5, 4], // y = 0
    [2, 6, 7, 3], // y = 1
    [0, 2, 3, 1], // z = 0
    [4, 5, 7, 6], // z = 1
];

/// The two corners of cube edge `e` (lower corner first).
#[cfg(test)]
pub const fn edge_corners(e: u8) -> (u8, u8) {
    let axis = e / 4;
    let j = e % 4;
    let (lo, hi) = (j & 1, (j >> 1) & 1);
    let c = match axis {
        0 => (lo << 1) | (hi << 2),
        1 => lo | (hi << 2),
        _ => lo | (hi << 1),
    };
    (c, c | (1 << axis))
}

/// The cube edge joining corners `a` and `b`, which must differ in exactly one bit.
pub fn edge_of(a: u8, b: u8) -> u8 {
    let d = a ^ b;
    debug_assert!(d.count_ones() == 1);
    let axis = d.trailing_zeros() as u8;
    let c = a & !d;
    let j = match axis {
        0 => ((c >> 1) & 1) | (((c >> 2) & 1) << 1),
        1 => (c & 1) | (((c >> 2) & 1) << 1),
        _ => (c & 1) | (((c >> 1) & 1) << 1),
    };
    4 * axis + j
}

/// One contour polygon of a cell: cube edges in order; `fan_face` is the first face (0..6) holding
/// two of its segments, or `NO_FACE`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellPolygon {
    pub edges: Vec<u8>,
    pub fan_face: u8,
}

/// Marks "no face".
pub const NO_FACE: u8 = u8::MAX;

/// Faces of `cfg` in the ambiguous case (Eq. 3.5), as a 6-bit mask.
pub fn ambiguous_faces(cfg: u8) -> u8 {
    let mut m = 0;
    for (f, fc) in FACE_CORNERS.iter().enumerate() {
        let s: Vec<bool> = fc.iter().map(|&c| cfg >> c & 1 == 1).collect();
        if s[0] == s[2] && s[1] == s[3] && s[0] != s[1] {
            m |= 1 << f;
        }
    }
    m
}

/// The contour polygons of a cell with sign configuration `cfg`; bit f of `connect` set means
/// that on ambiguous face f the two positive corners are joined (the segments cut off the
/// negative corners), clear means the positive corners are cut off.
pub fn cell_polygons(cfg: u8, connect: u8) -> Vec<CellPolygon> {
    // next[e] = edge following e; face_of_seg[e] = face carrying the segment e -> next[e].
    let mut next = [u8::MAX; 12];
    let mut seg_face = [u8::MAX; 12];
    let pos = |c: u8| cfg >> c & 1 == 1;
    for (f, fc) in FACE_CORNERS.iter().enumerate() {
        let e = |k: usize| edge_of(fc[k % 4], fc[(k + 1) % 4]);
        let s: [bool; 4] = [pos(fc[0]), pos(fc[1]), pos(fc[2]), pos(fc[3])];
        let cuts = (0..4).filter(|&k| s[k] != s[(k + 1) % 4]).count();
        let mut add = |a: u8, b: u8| {
            next[a as usize] = b;
            seg_face[a as usize] = f as u8;
        };
        if cuts == 2 {
            let ein = (0..4).find(|&k| !s[k] && s[(k + 1) % 4]).unwrap_or(0);
            let eout = (0..4).find(|&k| s[k] && !s[(k + 1) % 4]).unwrap_or(0);
            add(e(ein), e(eout));
        } else if cuts == 4 {
            let join_pos = connect >> f & 1 == 1;
            for k in 0..4 {
                let km1 = (k + 3) % 4;
                if s[k] && !join_pos {
                    // cut off positive corner k: from edge (k-1,k) to edge (k,k+1)
                    add(e(km1), e(k));
                } else if !s[k] && join_pos {
                    // cut off negative corner k: from edge (k,k+1) to edge (k-1,k)
                    add(e(k), e(km1));
                }
            }
        }
    }
    let mut used = [false; 12];
    let mut polys = Vec::new();
    for start in 0..12u8 {
        if next[start as usize] == u8::MAX || used[start as usize] {
            continue;
        }
        let mut edges = Vec::new();
        let mut faces = Vec::new();
        let mut e = start;
        while !used[e as usize] {
            used[e as usize] = true;
            edges.push(e);
            faces.push(seg_face[e as usize]);
            e = next[e as usize];
            if e == u8::MAX {
                break;
            }
        }
        let mut fan_face = NO_FACE;
        for f in 0..6u8 {
            if faces.iter().filter(|&&x| x == f).count() >= 2 {
                fan_face = f;
                break;
            }
        }
        polys.push(CellPolygon { edges, fan_face });
    }
    polys
}

/// Lorensen–Cline's cell-local choice on ambiguous faces: the corners of the cell's minority
/// sign (positive ones on a 4–4 tie) are cut off, as the 15-case table built with complementary
/// symmetry does. Neighbouring cells may disagree, which produces the holes of H Fig. 3.2.
pub fn lorensen_connect(cfg: u8) -> u8 {
    if cfg.count_ones() > 4 {
        ambiguous_faces(cfg) // positives are the majority: join them, cut off negatives
    } else {
        0
    }
}

/// A [`CellPolygon`] without heap storage.
#[derive(Debug, Clone, Copy)]
pub struct FlatPolygon {
    pub edges: [u8; 12],
    pub len: u8,
    pub fan_face: u8,
}

/// Precomputed polygons for all (cfg, connect) pairs: entry `cfg * 64 + connect` is
/// `polys[offsets[entry]..offsets[entry + 1]]`.
pub struct PolygonTable {
    pub offsets: Vec<u32>,
    pub polys: Vec<FlatPolygon>,
    pub ambiguous: [u8; 256],
}

impl PolygonTable {
    /// The polygons of a cell.
    #[inline]
    pub fn get(&self, cfg: u8, connect: u8) -> &[FlatPolygon] {
        let e = cfg as usize * 64 + connect as usize;
        &self.polys[self.offsets[e] as usize..self.offsets[e + 1] as usize]
    }
}

/// The polygon table (built on first use).
pub fn polygon_table() -> &'static PolygonTable {
    static T: OnceLock<PolygonTable> = OnceLock::new();
    T.get_or_init(|| {
        let mut offsets = Vec::with_capacity(256 * 64 + 1);
        let mut polys = Vec::new();
        let mut ambiguous = [0u8; 256];
        offsets.push(0);
        for cfg in 0..=255u8 {
            let amb = ambiguous_faces(cfg);
            ambiguous[cfg as usize] = amb;
            for connect in 0..64u8 {
                if connect & !amb == 0 {
                    for p in cell_polygons(cfg, connect) {
                        let mut edges = [0u8; 12];
                        edges[..p.edges.len()].copy_from_slice(&p.edges);
                        polys.push(FlatPolygon {
                            edges,
                            len: p.edges.len() as u8,
                            fan_face: p.fan_face,
                        });
                    }
                }
                offsets.push(polys.len() as u32);
            }
        }
        PolygonTable {
            offsets,
            polys,
            ambiguous,
        }
    })
}

/// The six tetrahedra of H §3.2 as cube corners (T¹…T⁶).
pub const TETS: [[u8; 4]; 6] = [
    [0, 1, 2, 4],
    [1, 2, 4, 6],
    [1, 5, 4, 6],
    [1, 3, 2, 6],
    [1, 3, 5, 6],
    [3, 5, 6, 7],
];

/// Entities of a cell carrying tetrahedron contour points: 0..12 cube edges, 12 + f the
/// diagonal of face f, 18 the body diagonal (corner 1 to corner 6).
pub fn entity_of(a: u8, b: u8) -> u8 {
    let d = a ^ b;
    match d.count_ones() {
        1 => edge_of(a, b),
        2 => {
            // the face whose axis bit is equal in both corners
            let axis = (!d & 7).trailing_zeros() as u8;
            let side = (a >> axis) & 1;
            12 + 2 * axis + side
        }
        _ => 18,
    }
}

/// The two corners of face diagonal / body diagonal entity `ent` (12..19), in the order used for
/// interpolation: from the corner with the higher lowest-differing coordinate, as in H's split
/// (e.g. face z = 0: corner (1,0,0) to corner (0,1,0)).
#[cfg(test)]
pub fn diagonal_corners(ent: u8) -> (u8, u8) {
    match ent {
        12 => (2, 4),
        13 => (3, 5),
        14 => (1, 4),
        15 => (3, 6),
        16 => (1, 2),
        17 => (5, 6),
        _ => (1, 6),
    }
}

/// Oriented triangles (as entity triples) of each tetrahedron for each 4-bit sign configuration.
pub struct TetTable {
    pub tris: Vec<Vec<[u8; 3]>>, // index tet * 16 + cfg4
}

/// The tetrahedron table (built on first use).
pub fn tet_table() -> &'static TetTable {
    static T: OnceLock<TetTable> = OnceLock::new();
    T.get_or_init(|| {
        let corner = |c: u8| [(c & 1) as f64, (c >> 1 & 1) as f64, (c >> 2 & 1) as f64];
        let mid = |a: u8, b: u8| {
            let (p, q) = (corner(a), corner(b));
            [
                (p[0] + q[0]) / 2.0,
                (p[1] + q[1]) / 2.0,
                (p[2] + q[2]) / 2.0,
            ]
        };
        let mut tris = Vec::with_capacity(96);
        for tet in TETS {
            for cfg4 in 0..16u8 {
                let posv: Vec<u8> = (0..4)
                    .filter(|&i| cfg4 >> i & 1 == 1)
                    .map(|i| tet[i])
                    .collect();
                let negv: Vec<u8> = (0..4)
                    .filter(|&i| cfg4 >> i & 1 == 0)
                    .map(|i| tet[i])
                    .collect();
                let mut out = Vec::new();
                let mut loops: Vec<(u8, u8)> = Vec::new();
                match (posv.len(), negv.len()) {
                    (1, 3) => loops.extend(negv.iter().map(|&n| (posv[0], n))),
                    (3, 1) => loops.extend(posv.iter().map(|&p| (p, negv[0]))),
                    (2, 2) => {
                        let (a, b, c, d) = (posv[0], posv[1], negv[0], negv[1]);
                        loops.extend([(a, c), (a, d), (b, d), (b, c)]);
                    }
                    _ => {}
                }
                if !loops.is_empty() {
                    let centre = |v: &[u8]| {
                        let mut s = [0.0; 3];
                        for &c in v {
                            let p = corner(c);
                            for k in 0..3 {
                                s[k] += p[k] / v.len() as f64;
                            }
                        }
                        s
                    };
                    let (cp, cn) = (centre(&posv), centre(&negv));
                    let dir = [cn[0] - cp[0], cn[1] - cp[1], cn[2] - cp[2]];
                    for i in 1..loops.len() - 1 {
                        let idx = [0, i, i + 1];
                        let p: Vec<[f64; 3]> =
                            idx.iter().map(|&k| mid(loops[k].0, loops[k].1)).collect();
                        let u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
                        let v = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
                        let n = [
                            u[1] * v[2] - u[2] * v[1],
                            u[2] * v[0] - u[0] * v[2],
                            u[0] * v[1] - u[1] * v[0],
                        ];
                        let d = n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2];
                        let ents = idx.map(|k| entity_of(loops[k].0, loops[k].1));
                        if d > 0.0 {
                            out.push(ents);
                        } else {
                            out.push([ents[0], ents[2], ents[1]]);
                        }
                    }
                }
                tris.push(out);
            }
        }
        TetTable { tris }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corner(c: u8) -> [i32; 3] {
        [(c & 1) as i32, (c >> 1 & 1) as i32, (c >> 2 & 1) as i32]
    }

    #[test]
    fn faces_are_ccw_from_outside() {
        for (f, fc) in FACE_CORNERS.iter().enumerate() {
            let axis = f / 2;
            let mut n = [0i32; 3];
            n[axis] = if f % 2 == 0 { -1 } else { 1 };
            for k in 0..4 {
                let (a, b, c) = (
                    corner(fc[k]),
                    corner(fc[(k + 1) % 4]),
                    corner(fc[(k + 2) % 4]),
                );
                let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let v = [c[0] - b[0], c[1] - b[1], c[2] - b[2]];
                let cr = [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ];
                assert_eq!(cr[0] * n[0] + cr[1] * n[1] + cr[2] * n[2], 1, "face {f}");
                assert_eq!(corner(fc[k])[axis], (f % 2) as i32);
            }
        }
    }

    #[test]
    fn edges_round_trip() {
        for e in 0..12u8 {
            let (a, b) = edge_corners(e);
            assert_eq!(edge_of(a, b), e);
            assert_eq!(edge_of(b, a), e);
            assert_eq!((a ^ b).count_ones(), 1);
            assert!(a < b);
        }
    }

    #[test]
    fn polygons_cover_cut_edges_once() {
        for cfg in 0..=255u8 {
            let amb = ambiguous_faces(cfg);
            for connect in 0..64u8 {
                if connect & !amb != 0 {
                    continue;
                }
                let polys = cell_polygons(cfg, connect);
                let mut seen = [0; 12];
                for p in &polys {
                    assert!((3..=12).contains(&p.edges.len()), "cfg {cfg} {p:?}");
                    for &e in &p.edges {
                        seen[e as usize] += 1;
                    }
                }
                for e in 0..12u8 {
                    let (a, b) = edge_corners(e);
                    let cut = (cfg >> a & 1) != (cfg >> b & 1);
                    assert_eq!(seen[e as usize], cut as i32, "cfg {cfg} edge {e}");
                }
            }
        }
    }

    #[test]
    fn tetrahedra_fill_the_cube() {
        // Volumes of the six tetrahedra add up to 1 and all are positive-volume (non-degenerate).
        let mut total = 0.0;
        for t in TETS {
            let p: Vec<[i32; 3]> = t.iter().map(|&c| corner(c)).collect();
            let u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
            let v = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
            let w = [p[3][0] - p[0][0], p[3][1] - p[0][1], p[3][2] - p[0][2]];
            let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]);
            assert_ne!(det, 0);
            total += det.abs() as f64 / 6.0;
        }
        assert!((total - 1.0).abs() < 1e-12);
        for e in 12..19u8 {
            let (a, b) = diagonal_corners(e);
            assert_eq!(entity_of(a, b), e);
        }
    }
}

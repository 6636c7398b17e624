//! VTK writers read back by a small independent parser of both containers (XML `.vtu` inline
//! ASCII or appended raw in either byte order; legacy `.vtk` ASCII or big-endian binary):
//! the points, the cells, their types and the point/cell data must come back exactly, and the
//! tetrahedra of a Delaunay tetrahedralization must have a positive volume in VTK's corner
//! convention. (Checked by hand against meshio 5.3 and VTK 9.7's readers, see the commit.)

use morpho::geom::{Point3, Vector3};
use morpho::io::{vtk, Encoding};
use morpho::mesh::{Property, ScalarKind, TetMesh, TriMesh};
use std::collections::BTreeMap;

/// What a VTK file holds, as read back.
#[derive(Debug, Default, PartialEq)]
struct Grid {
    points: Vec<[f64; 3]>,
    cells: Vec<Vec<u64>>,
    types: Vec<u8>,
    /// name → (components, values)
    point_data: BTreeMap<String, (usize, Vec<f64>)>,
    cell_data: BTreeMap<String, (usize, Vec<f64>)>,
}

fn find(hay: &[u8], needle: &[u8], from: usize) -> Option<usize> {
    hay[from..]
        .windows(needle.len())
        .position(|w| w == needle)
        .map(|i| i + from)
}

fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    let j = tag[i..].find('"')? + i;
    Some(&tag[i..j])
}

/// Decodes `n` values of VTK type `ty` from `b`.
fn decode(b: &[u8], ty: &str, big: bool) -> Vec<f64> {
    let size = match ty {
        "Float64" | "Int64" => 8,
        "UInt8" => 1,
        t => panic!("unexpected type {t}"),
    };
    b.chunks_exact(size)
        .map(|c| match ty {
            "Float64" => {
                let a: [u8; 8] = c.try_into().unwrap();
                if big {
                    f64::from_be_bytes(a)
                } else {
                    f64::from_le_bytes(a)
                }
            }
            "Int64" => {
                let a: [u8; 8] = c.try_into().unwrap();
                (if big {
                    i64::from_be_bytes(a)
                } else {
                    i64::from_le_bytes(a)
                }) as f64
            }
            _ => c[0] as f64,
        })
        .collect()
}

/// Parses a `.vtu` file of one piece.
fn parse_vtu(bytes: &[u8]) -> Grid {
    let head_end = find(bytes, b"<AppendedData", 0).unwrap_or(bytes.len());
    let head = std::str::from_utf8(&bytes[..head_end]).unwrap();
    assert!(head.starts_with("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\""));
    let big = head.contains("byte_order=\"BigEndian\"");
    assert!(head.contains("header_type=\"UInt64\""));
    // appended block: after '_' up to "\n</AppendedData>"
    let appended = find(bytes, b"<AppendedData encoding=\"raw\">\n_", 0).map(|i| {
        let start = i + b"<AppendedData encoding=\"raw\">\n_".len();
        let end = find(bytes, b"\n</AppendedData>", start).unwrap();
        &bytes[start..end]
    });
    let mut arrays: Vec<(String, String, usize, Vec<f64>)> = Vec::new(); // section, name, comps
    let mut section = String::new();
    let mut rest = head;
    while let Some(i) = rest.find('<') {
        let j = rest[i..].find('>').unwrap() + i;
        let tag = &rest[i + 1..j];
        rest = &rest[j + 1..];
        let name: String = tag.chars().take_while(|c| c.is_alphanumeric()).collect();
        if ["PointData", "CellData", "Points", "Cells"].contains(&name.as_str()) {
            section = name;
            continue;
        }
        if name != "DataArray" {
            continue;
        }
        let ty = attr(tag, "type").unwrap().to_string();
        let comps: usize = attr(tag, "NumberOfComponents").unwrap().parse().unwrap();
        let values = match attr(tag, "format").unwrap() {
            "ascii" => {
                let k = rest.find("</DataArray>").unwrap();
                let v = rest[..k]
                    .split_whitespace()
                    .map(|t| t.parse::<f64>().unwrap())
                    .collect();
                rest = &rest[k..];
                v
            }
            "appended" => {
                let off: usize = attr(tag, "offset").unwrap().parse().unwrap();
                let data = appended.expect("appended data");
                let h: [u8; 8] = data[off..off + 8].try_into().unwrap();
                let n = if big {
                    u64::from_be_bytes(h)
                } else {
                    u64::from_le_bytes(h)
                } as usize;
                decode(&data[off + 8..off + 8 + n], &ty, big)
            }
            f => panic!("format {f}"),
        };
        arrays.push((
            section.clone(),
            attr(tag, "Name").unwrap().to_string(),
            comps,
            values,
        ));
    }
    let get = |n: &str| {
        arrays
            .iter()
            .find(|a| a.1 == n)
            .map(|a| a.3.clone())
            .unwrap()
    };
    let mut g = Grid {
        points: get("Points")
            .chunks(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
        types: get("types").iter().map(|&t| t as u8).collect(),
        ..Default::default()
    };
    let conn = get("connectivity");
    let mut start = 0;
    for &end in &get("offsets") {
        g.cells.push(
            conn[start..end as usize]
                .iter()
                .map(|&v| v as u64)
                .collect(),
        );
        start = end as usize;
    }
    assert_eq!(start, conn.len());
    for (sec, name, comps, values) in arrays {
        let map = match sec.as_str() {
            "PointData" => &mut g.point_data,
            "CellData" => &mut g.cell_data,
            _ => continue,
        };
        map.insert(name, (comps, values));
    }
    g
}

/// Parses a legacy `.vtk` unstructured grid (ASCII or binary).
fn parse_vtk(bytes: &[u8]) -> Grid {
    let mut pos = 0;
    let mut line = || {
        let e = find(bytes, b"\n", pos).unwrap();
        let l = std::str::from_utf8(&bytes[pos..e]).unwrap().to_string();
        pos = e + 1;
        l
    };
    assert_eq!(line(), "# vtk DataFile Version 3.0");
    let _title = line();
    let binary = match line().as_str() {
        "ASCII" => false,
        "BINARY" => true,
        o => panic!("{o}"),
    };
    assert_eq!(line(), "DATASET UNSTRUCTURED_GRID");
    // (tokens of ASCII blocks, or raw bytes of binary blocks)
    let read_block = |pos: &mut usize, n: usize, size: usize, float: bool| -> Vec<f64> {
        if binary {
            let b = &bytes[*pos..*pos + n * size];
            *pos += n * size;
            assert_eq!(bytes[*pos], b'\n', "a binary block ends with a newline");
            *pos += 1;
            b.chunks_exact(size)
                .map(|c| {
                    if float {
                        f64::from_be_bytes(c.try_into().unwrap())
                    } else {
                        i32::from_be_bytes(c.try_into().unwrap()) as f64
                    }
                })
                .collect()
        } else {
            let mut v = Vec::with_capacity(n);
            while v.len() < n {
                let e = find(bytes, b"\n", *pos).unwrap();
                let l = std::str::from_utf8(&bytes[*pos..e]).unwrap();
                v.extend(l.split_whitespace().map(|t| t.parse::<f64>().unwrap()));
                *pos = e + 1;
            }
            assert_eq!(v.len(), n);
            v
        }
    };
    let header = |pos: &mut usize| -> Option<Vec<String>> {
        let e = find(bytes, b"\n", *pos)?;
        let l = std::str::from_utf8(&bytes[*pos..e]).unwrap();
        *pos = e + 1;
        Some(l.split_whitespace().map(str::to_string).collect())
    };
    let mut g = Grid::default();
    let h = header(&mut pos).unwrap();
    assert_eq!((h[0].as_str(), h[2].as_str()), ("POINTS", "double"));
    let n: usize = h[1].parse().unwrap();
    g.points = read_block(&mut pos, 3 * n, 8, true)
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    let h = header(&mut pos).unwrap();
    assert_eq!(h[0], "CELLS");
    let (m, size): (usize, usize) = (h[1].parse().unwrap(), h[2].parse().unwrap());
    let c = read_block(&mut pos, size, 4, false);
    let mut i = 0;
    while i < c.len() {
        let k = c[i] as usize;
        g.cells
            .push(c[i + 1..i + 1 + k].iter().map(|&v| v as u64).collect());
        i += 1 + k;
    }
    assert_eq!(g.cells.len(), m);
    let h = header(&mut pos).unwrap();
    assert_eq!(h, ["CELL_TYPES", &m.to_string()]);
    g.types = read_block(&mut pos, m, 4, false)
        .iter()
        .map(|&t| t as u8)
        .collect();
    let mut count = 0;
    let mut in_points = true;
    while let Some(h) = header(&mut pos) {
        match h[0].as_str() {
            "POINT_DATA" | "CELL_DATA" => {
                in_points = h[0] == "POINT_DATA";
                count = h[1].parse().unwrap();
            }
            "SCALARS" | "VECTORS" => {
                let comps = if h[0] == "VECTORS" {
                    3
                } else {
                    assert_eq!(header(&mut pos).unwrap(), ["LOOKUP_TABLE", "default"]);
                    h[3].parse().unwrap()
                };
                let v = read_block(&mut pos, comps * count, 8, true);
                let map = if in_points {
                    &mut g.point_data
                } else {
                    &mut g.cell_data
                };
                map.insert(h[1].clone(), (comps, v));
            }
            o => panic!("unexpected section {o}"),
        }
    }
    g
}

fn write(t: &dyn Fn(&mut Vec<u8>, Encoding), enc: Encoding) -> Vec<u8> {
    let mut out = Vec::new();
    t(&mut out, enc);
    out
}

const ENCODINGS: [Encoding; 3] = [
    Encoding::Ascii,
    Encoding::BinaryLittleEndian,
    Encoding::BinaryBigEndian,
];

/// Points of a small random cloud with awkward coordinates (tiny, huge, negative zero).
fn cloud(n: usize) -> Vec<Point3> {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut r = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| Point3::new(r() * 1e-3 + 1e5, r() - 0.5, r() * 3e2))
        .collect()
}

fn vtk_volume(p: &[[f64; 3]], c: &[u64]) -> f64 {
    let q = |i: usize| Vector3::from(p[c[i] as usize]);
    (q(1) - q(0)).cross(&(q(2) - q(0))).dot(&(q(3) - q(0)))
}

#[test]
fn tetrahedra_read_back_exactly_with_positive_vtk_volume() {
    let pts = cloud(300);
    let d = morpho::delaunay::triangulate_3d(&pts).unwrap();
    let t = TetMesh {
        positions: pts.clone(),
        tets: d.to_input_indices(),
    };
    assert!(t.tets.len() > 1000);
    for enc in ENCODINGS {
        let vtu = parse_vtu(&write(&|w, e| vtk::write_tets_vtu(w, &t, e).unwrap(), enc));
        let legacy = parse_vtk(&write(&|w, e| vtk::write_tets_vtk(w, &t, e).unwrap(), enc));
        assert_eq!(vtu, legacy, "{enc:?}");
        let g = vtu;
        assert_eq!(g.points.len(), pts.len());
        for (a, b) in g.points.iter().zip(&pts) {
            assert_eq!(a, &[b.x, b.y, b.z], "coordinates round-trip exactly");
        }
        assert!(g.types.iter().all(|&ty| ty == 10));
        assert_eq!(g.cells.len(), t.tets.len());
        for (c, tet) in g.cells.iter().zip(&t.tets) {
            // the same corners, in VTK's order: positive volume
            let mut a = c.clone();
            let mut b: Vec<u64> = tet.iter().map(|&v| v as u64).collect();
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b);
            assert!(vtk_volume(&g.points, c) > 0.0, "{tet:?}");
        }
        assert!(g.point_data.is_empty() && g.cell_data.is_empty());
    }
}

#[test]
fn triangle_meshes_carry_normals_and_properties() {
    let pts = cloud(5);
    let m = TriMesh {
        positions: pts.clone(),
        triangles: vec![[0, 1, 2], [0, 2, 3], [3, 2, 4]],
        normals: Some(vec![Vector3::new(0.0, -0.0, 1.0); 5]),
        vertex_props: vec![Property {
            name: "quality value".into(),
            kind: ScalarKind::F32,
            values: vec![0.5, 1e-30, -3.0, f64::from(0.1f32), 7.0],
        }],
        face_props: vec![Property {
            name: "part".into(),
            kind: ScalarKind::U32,
            values: vec![0.0, 1.0, 1.0],
        }],
    };
    for enc in ENCODINGS {
        let vtu = parse_vtu(&write(&|w, e| vtk::write_mesh_vtu(w, &m, e).unwrap(), enc));
        let legacy = parse_vtk(&write(&|w, e| vtk::write_mesh_vtk(w, &m, e).unwrap(), enc));
        assert_eq!(vtu.cells, vec![vec![0, 1, 2], vec![0, 2, 3], vec![3, 2, 4]]);
        assert!(vtu.types.iter().all(|&ty| ty == 5));
        assert_eq!(vtu.point_data["Normals"].0, 3);
        assert_eq!(vtu.point_data["quality value"].1, m.vertex_props[0].values);
        assert_eq!(vtu.cell_data["part"], (1, vec![0.0, 1.0, 1.0]));
        // legacy names have no blanks
        assert_eq!(
            legacy.point_data["quality_value"].1,
            m.vertex_props[0].values
        );
        assert_eq!(legacy.points, vtu.points);
        assert_eq!(legacy.cells, vtu.cells);
        assert_eq!(legacy.point_data["Normals"], vtu.point_data["Normals"]);
    }
}

#[test]
fn empty_and_invalid_meshes() {
    let empty = TetMesh::default();
    for enc in ENCODINGS {
        let g = parse_vtu(&write(
            &|w, e| vtk::write_tets_vtu(w, &empty, e).unwrap(),
            enc,
        ));
        assert_eq!(g, Grid::default());
        let g = parse_vtk(&write(
            &|w, e| vtk::write_tets_vtk(w, &empty, e).unwrap(),
            enc,
        ));
        assert_eq!(g, Grid::default());
    }
    let bad = TriMesh::new(cloud(3), vec![[0, 1, 3]]);
    let mut out = Vec::new();
    assert!(vtk::write_mesh_vtu(&mut out, &bad, Encoding::Ascii).is_err());
    assert!(vtk::write_mesh_vtk(&mut out, &bad, Encoding::Ascii).is_err());
}

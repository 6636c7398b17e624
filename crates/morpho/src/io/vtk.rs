//! VTK unstructured grids (writing): tetrahedral meshes (cell type 10, `VTK_TETRA`) and
//! triangle meshes (cell type 5, `VTK_TRIANGLE`), the formats ParaView, VisIt and meshio read.
//!
//! Two containers (Kitware, *VTK File Formats*, VTK User's Guide ch. 19):
//! - **`.vtu`**, XML `UnstructuredGrid` (version 1.0): with [`Encoding::Ascii`] every
//!   `DataArray` is inline text (`format="ascii"`); otherwise all arrays follow in one
//!   `<AppendedData encoding="raw">` block (`format="appended"`), each preceded by its byte
//!   count as `UInt64` (`header_type="UInt64"`), in the byte order of the encoding
//!   (`byte_order="LittleEndian"` unless [`Encoding::BinaryBigEndian`]). Points are `Float64`,
//!   `connectivity` and `offsets` `Int64`, `types` `UInt8`.
//! - **`.vtk`**, legacy format (`# vtk DataFile Version 3.0`, `DATASET UNSTRUCTURED_GRID`):
//!   `POINTS n double`, `CELLS m size` (each cell its corner count then the corners, `int`),
//!   `CELL_TYPES m`. ASCII with [`Encoding::Ascii`], otherwise `BINARY`, which the format
//!   defines as big endian whatever the encoding asks.
//!
//! Corner order: VTK wants the first three corners of a tetrahedron to turn counter-clockwise
//! seen from the fourth (right-hand normal towards it), the opposite of a positively oriented
//! [`TetMesh`] tetrahedron (`orient3d(a, b, c, d) > 0` in Shewchuk's convention). The writers
//! take the mesh's documented orientation and write `[a, c, b, d]`, so that tetrahedra from
//! [`crate::delaunay::triangulate_3d`] have a positive volume in ParaView; no geometric test is made.
//! Triangles keep their order.
//!
//! Triangle meshes carry their data along: vertex normals as point data `Normals` (three
//! components; the active normals of a `.vtu`, `VECTORS` in a legacy file, since meshio does
//! not read the legacy `NORMALS` section), each vertex property as a one-component point-data array and each face
//! property as a cell-data array of its name (`Float64`; in legacy files blanks in names become
//! `_`). Numbers in ASCII use the shortest round-trip form. Indices must fit the format (`int`,
//! below 2^31, in legacy files). Time and memory are linear in the mesh size.

use super::obj::F64;
use super::{werr, Encoding};
use crate::geom::Point3;
use crate::mesh::{TetMesh, TriMesh};
use crate::{Error, Result};
use std::io::Write;

/// `VTK_TRIANGLE`.
const TRIANGLE: u8 = 5;
/// `VTK_TETRA`.
const TETRA: u8 = 10;

/// A named array of `Float64` values with `components` values per point or cell.
struct Array {
    name: String,
    components: usize,
    values: Vec<f64>,
}

/// The unstructured grid to write: points, cells of one type, point and cell data.
struct Grid<'a> {
    points: &'a [Point3],
    /// Corners of every cell, `corners` per cell.
    connectivity: Vec<u32>,
    corners: usize,
    cell_type: u8,
    point_data: Vec<Array>,
    cell_data: Vec<Array>,
    /// Title line of a legacy file.
    title: &'static str,
}

impl Grid<'_> {
    fn num_cells(&self) -> usize {
        self.connectivity.len() / self.corners
    }
}

fn tet_grid(t: &TetMesh) -> Result<Grid<'_>> {
    let n = t.positions.len();
    if let Some((i, tet)) = t
        .tets
        .iter()
        .enumerate()
        .find(|(_, tet)| tet.iter().any(|&v| v as usize >= n))
    {
        return Err(Error::invalid(format!(
            "tetrahedron {i} {tet:?} refers to a vertex beyond the {n} vertices"
        )));
    }
    Ok(Grid {
        points: &t.positions,
        connectivity: t
            .tets
            .iter()
            .flat_map(|&[a, b, c, d]| [a, c, b, d])
            .collect(),
        corners: 4,
        cell_type: TETRA,
        point_data: Vec::new(),
        cell_data: Vec::new(),
        title: "morpho tetrahedral mesh",
    })
}

fn tri_grid(m: &TriMesh) -> Result<Grid<'_>> {
    m.validate()?;
    let mut point_data = Vec::new();
    if let Some(nr) = &m.normals {
        point_data.push(Array {
            name: "Normals".into(),
            components: 3,
            values: nr.iter().flat_map(|v| [v.x, v.y, v.z]).collect(),
        });
    }
    let one = |p: &crate::mesh::Property| Array {
        name: p.name.clone(),
        components: 1,
        values: p.values.clone(),
    };
    point_data.extend(m.vertex_props.iter().map(one));
    Ok(Grid {
        points: &m.positions,
        connectivity: m.triangles.iter().flatten().copied().collect(),
        corners: 3,
        cell_type: TRIANGLE,
        point_data,
        cell_data: m.face_props.iter().map(one).collect(),
        title: "morpho triangle mesh",
    })
}

/// Writes a tetrahedral mesh as a `.vtu` XML unstructured grid (see the module documentation).
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::io::{vtk, Encoding};
/// use morpho::mesh::TetMesh;
/// let t = TetMesh {
///     positions: vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///                     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)],
///     tets: vec![[0, 1, 3, 2]],
/// };
/// let mut out = Vec::new();
/// vtk::write_tets_vtu(&mut out, &t, Encoding::Ascii).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">"));
/// assert!(text.contains(">\n0 3 1 2\n</DataArray>")); // VTK's corner order
/// ```
pub fn write_tets_vtu(w: &mut dyn Write, t: &TetMesh, enc: Encoding) -> Result<()> {
    write_vtu(w, &tet_grid(t)?, enc)
}

/// Writes a tetrahedral mesh as a legacy `.vtk` unstructured grid (see the module
/// documentation).
pub fn write_tets_vtk(w: &mut dyn Write, t: &TetMesh, enc: Encoding) -> Result<()> {
    write_legacy(w, &tet_grid(t)?, enc)
}

/// Writes a triangle mesh (with its normals and properties) as a `.vtu` XML unstructured grid.
pub fn write_mesh_vtu(w: &mut dyn Write, m: &TriMesh, enc: Encoding) -> Result<()> {
    write_vtu(w, &tri_grid(m)?, enc)
}

/// Writes a triangle mesh (with its normals and properties) as a legacy `.vtk` unstructured
/// grid.
pub fn write_mesh_vtk(w: &mut dyn Write, m: &TriMesh, enc: Encoding) -> Result<()> {
    write_legacy(w, &tri_grid(m)?, enc)
}

// ---------------------------------------------------------------------------------------------
// Shared encoding helpers

/// Values of one array as the writers encode them.
enum Values<'a> {
    F64(&'a [f64]),
    /// Points, flattened on the fly.
    Points(&'a [Point3]),
    /// Vertex indices (written as `Int64` in `.vtu`, `int` in legacy files).
    Index(&'a [u32]),
    /// Cell end offsets `k·corners`, k = 1…cells.
    Offsets {
        cells: usize,
        corners: usize,
    },
    /// The cell type, `cells` times.
    Types {
        cells: usize,
        ty: u8,
    },
}

impl Values<'_> {
    /// Calls `f` with every value as f64 (exact for the integers written here).
    fn for_each(&self, mut f: impl FnMut(f64)) {
        match *self {
            Values::F64(v) => v.iter().for_each(|&x| f(x)),
            Values::Points(p) => p.iter().for_each(|q| {
                f(q.x);
                f(q.y);
                f(q.z);
            }),
            Values::Index(v) => v.iter().for_each(|&x| f(x as f64)),
            Values::Offsets { cells, corners } => (1..=cells).for_each(|k| f((k * corners) as f64)),
            Values::Types { cells, ty } => (0..cells).for_each(|_| f(ty as f64)),
        }
    }
    fn len(&self) -> usize {
        match *self {
            Values::F64(v) => v.len(),
            Values::Points(p) => 3 * p.len(),
            Values::Index(v) => v.len(),
            Values::Offsets { cells, .. } | Values::Types { cells, .. } => cells,
        }
    }
}

/// Binary scalar kinds of the writers.
#[derive(Clone, Copy)]
enum Kind {
    F64,
    I64,
    I32,
    U8,
}

impl Kind {
    fn size(self) -> usize {
        match self {
            Kind::F64 | Kind::I64 => 8,
            Kind::I32 => 4,
            Kind::U8 => 1,
        }
    }
    fn vtu_name(self) -> &'static str {
        match self {
            Kind::F64 => "Float64",
            Kind::I64 => "Int64",
            Kind::I32 => "Int32",
            Kind::U8 => "UInt8",
        }
    }
}

/// Buffered binary/ASCII encoder onto a writer.
struct Out<'w> {
    w: &'w mut dyn Write,
    buf: Vec<u8>,
}

impl<'w> Out<'w> {
    fn new(w: &'w mut dyn Write) -> Self {
        Out {
            w,
            buf: Vec::with_capacity(1 << 16),
        }
    }
    fn text(&mut self, s: &str) -> Result<()> {
        self.buf.extend_from_slice(s.as_bytes());
        self.spill()
    }
    fn spill(&mut self) -> Result<()> {
        if self.buf.len() >= 1 << 16 {
            self.flush()?;
        }
        Ok(())
    }
    fn flush(&mut self) -> Result<()> {
        self.w.write_all(&self.buf).map_err(werr)?;
        self.buf.clear();
        Ok(())
    }
    /// Values in binary, `kind` each, big or little endian.
    fn binary(&mut self, v: &Values, kind: Kind, big: bool) -> Result<()> {
        let mut result = Ok(());
        v.for_each(|x| {
            if result.is_err() {
                return;
            }
            macro_rules! put {
                ($e:expr) => {{
                    let e = $e;
                    if big {
                        self.buf.extend_from_slice(&e.to_be_bytes())
                    } else {
                        self.buf.extend_from_slice(&e.to_le_bytes())
                    }
                }};
            }
            match kind {
                Kind::F64 => put!(x),
                Kind::I64 => put!(x as i64),
                Kind::I32 => put!(x as i32),
                Kind::U8 => self.buf.push(x as u8),
            }
            result = self.spill();
        });
        result
    }
    /// Values as text, `per_line` on a line separated by spaces (integers without decimals).
    fn ascii(&mut self, v: &Values, per_line: usize) -> Result<()> {
        let mut result = Ok(());
        let mut k = 0;
        v.for_each(|x| {
            if result.is_err() {
                return;
            }
            if k > 0 {
                self.buf.push(if k % per_line == 0 { b'\n' } else { b' ' });
            }
            k += 1;
            // Writing into a Vec cannot fail.
            let _ = write!(self.buf, "{}", F64(x));
            result = self.spill();
        });
        if k > 0 {
            self.buf.push(b'\n');
        }
        result
    }
}

/// `&`, `<`, `>`, `"` and `'` escaped for an XML attribute.
fn xml_escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            c if (c as u32) < 0x20 => o.push('_'),
            c => o.push(c),
        }
    }
    o
}

// ---------------------------------------------------------------------------------------------
// XML (.vtu)

/// One `DataArray` of a `.vtu` file.
struct XmlArray<'a> {
    name: String,
    kind: Kind,
    components: usize,
    values: Values<'a>,
    /// Values on one line of an ASCII array.
    per_line: usize,
}

fn write_vtu(w: &mut dyn Write, g: &Grid, enc: Encoding) -> Result<()> {
    let cells = g.num_cells();
    fn data(a: &Array) -> XmlArray<'_> {
        XmlArray {
            name: a.name.clone(),
            kind: Kind::F64,
            components: a.components,
            values: Values::F64(&a.values),
            per_line: a.components,
        }
    }
    let point_data: Vec<XmlArray> = g.point_data.iter().map(data).collect();
    let cell_data: Vec<XmlArray> = g.cell_data.iter().map(data).collect();
    let points = XmlArray {
        name: "Points".into(),
        kind: Kind::F64,
        components: 3,
        values: Values::Points(g.points),
        per_line: 3,
    };
    let topology = [
        XmlArray {
            name: "connectivity".into(),
            kind: Kind::I64,
            components: 1,
            values: Values::Index(&g.connectivity),
            per_line: g.corners,
        },
        XmlArray {
            name: "offsets".into(),
            kind: Kind::I64,
            components: 1,
            values: Values::Offsets {
                cells,
                corners: g.corners,
            },
            per_line: 1,
        },
        XmlArray {
            name: "types".into(),
            kind: Kind::U8,
            components: 1,
            values: Values::Types {
                cells,
                ty: g.cell_type,
            },
            per_line: 1,
        },
    ];
    let ascii = enc == Encoding::Ascii;
    let big = enc == Encoding::BinaryBigEndian;
    let mut out = Out::new(w);
    out.text(&format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
         byte_order=\"{}\" header_type=\"UInt64\">\n<UnstructuredGrid>\n\
         <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{cells}\">\n",
        if big { "BigEndian" } else { "LittleEndian" },
        g.points.len(),
    ))?;
    // Appended offsets run over the arrays in the order they are declared.
    let mut offset = 0u64;
    let mut sections: Vec<(&str, &[XmlArray])> = Vec::new();
    if !point_data.is_empty() {
        sections.push(("PointData", &point_data));
    }
    if !cell_data.is_empty() {
        sections.push(("CellData", &cell_data));
    }
    sections.push(("Points", std::slice::from_ref(&points)));
    sections.push(("Cells", &topology));
    for (tag, arrays) in &sections {
        // Vertex normals are the active normals of the point data.
        let active = if *tag == "PointData" && g.point_data.iter().any(|a| a.name == "Normals") {
            " Normals=\"Normals\""
        } else {
            ""
        };
        out.text(&format!("<{tag}{active}>\n"))?;
        for a in arrays.iter() {
            let head = format!(
                "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"",
                a.kind.vtu_name(),
                xml_escape(&a.name),
                a.components
            );
            if ascii {
                out.text(&format!("{head} format=\"ascii\">\n"))?;
                out.ascii(&a.values, a.per_line)?;
                out.text("</DataArray>\n")?;
            } else {
                out.text(&format!(
                    "{head} format=\"appended\" offset=\"{offset}\"/>\n"
                ))?;
                offset += 8 + (a.values.len() * a.kind.size()) as u64;
            }
        }
        out.text(&format!("</{tag}>\n"))?;
    }
    out.text("</Piece>\n</UnstructuredGrid>\n")?;
    if !ascii {
        out.text("<AppendedData encoding=\"raw\">\n_")?;
        for (_, arrays) in &sections {
            for a in arrays.iter() {
                let bytes = (a.values.len() * a.kind.size()) as u64;
                out.buf.extend_from_slice(&if big {
                    bytes.to_be_bytes()
                } else {
                    bytes.to_le_bytes()
                });
                out.binary(&a.values, a.kind, big)?;
            }
        }
        out.text("\n</AppendedData>\n")?;
    }
    out.text("</VTKFile>\n")?;
    out.flush()
}

// ---------------------------------------------------------------------------------------------
// Legacy (.vtk)

/// A name usable in a legacy file: blanks and control characters replaced by `_`.
fn legacy_name(s: &str) -> String {
    let n: String = s
        .chars()
        .map(|c| {
            if c.is_whitespace() || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    if n.is_empty() {
        "data".into()
    } else {
        n
    }
}

fn write_legacy(w: &mut dyn Write, g: &Grid, enc: Encoding) -> Result<()> {
    if g.points.len() > i32::MAX as usize {
        return Err(Error::invalid(
            "more than 2^31-1 vertices cannot be indexed by legacy VTK 'int' indices",
        ));
    }
    let ascii = enc == Encoding::Ascii;
    let cells = g.num_cells();
    let mut out = Out::new(w);
    // Binary legacy files are big endian by definition; every block ends with a newline.
    let block = |out: &mut Out, v: &Values, kind: Kind, per_line: usize| -> Result<()> {
        if ascii {
            out.ascii(v, per_line)
        } else {
            out.binary(v, kind, true)?;
            out.text("\n")
        }
    };
    out.text(&format!(
        "# vtk DataFile Version 3.0\n{}\n{}\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n",
        g.title,
        if ascii { "ASCII" } else { "BINARY" },
        g.points.len()
    ))?;
    block(&mut out, &Values::Points(g.points), Kind::F64, 3)?;
    // CELLS: each cell as its corner count followed by its corners.
    let with_counts: Vec<u32> = g
        .connectivity
        .chunks_exact(g.corners)
        .flat_map(|c| std::iter::once(g.corners as u32).chain(c.iter().copied()))
        .collect();
    out.text(&format!("CELLS {cells} {}\n", with_counts.len()))?;
    block(
        &mut out,
        &Values::Index(&with_counts),
        Kind::I32,
        g.corners + 1,
    )?;
    out.text(&format!("CELL_TYPES {cells}\n"))?;
    block(
        &mut out,
        &Values::Types {
            cells,
            ty: g.cell_type,
        },
        Kind::I32,
        1,
    )?;
    for (section, count, arrays) in [
        ("POINT_DATA", g.points.len(), &g.point_data),
        ("CELL_DATA", cells, &g.cell_data),
    ] {
        if arrays.is_empty() {
            continue;
        }
        out.text(&format!("{section} {count}\n"))?;
        for a in arrays {
            let name = legacy_name(&a.name);
            if a.components == 3 {
                // VECTORS rather than NORMALS: meshio does not read the NORMALS section
                out.text(&format!("VECTORS {name} double\n"))?;
            } else {
                out.text(&format!(
                    "SCALARS {name} double {}\nLOOKUP_TABLE default\n",
                    a.components
                ))?;
            }
            block(&mut out, &Values::F64(&a.values), Kind::F64, a.components)?;
        }
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tet() -> TetMesh {
        TetMesh {
            positions: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(0.0, 0.0, 1e300),
            ],
            tets: vec![[0, 1, 3, 2]],
        }
    }

    #[test]
    fn legacy_ascii_layout() {
        let mut out = Vec::new();
        write_tets_vtk(&mut out, &tet(), Encoding::Ascii).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "# vtk DataFile Version 3.0\nmorpho tetrahedral mesh\nASCII\n\
             DATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1e300\n\
             CELLS 1 5\n4 0 3 1 2\nCELL_TYPES 1\n10\n"
        );
    }

    #[test]
    fn legacy_binary_is_big_endian() {
        let mut out = Vec::new();
        write_tets_vtk(&mut out, &tet(), Encoding::BinaryLittleEndian).unwrap();
        let head = b"# vtk DataFile Version 3.0\nmorpho tetrahedral mesh\nBINARY\n\
                     DATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n";
        assert!(out.starts_with(head));
        let p = &out[head.len()..];
        assert_eq!(&p[24..32], &1.0f64.to_be_bytes());
        let cells = b"\nCELLS 1 5\n";
        let at = head.len() + 96;
        assert_eq!(&out[at..at + cells.len()], cells);
        let c = &out[at + cells.len()..];
        let ints: Vec<i32> = c[..20]
            .chunks(4)
            .map(|b| i32::from_be_bytes(b.try_into().unwrap()))
            .collect();
        assert_eq!(ints, [4, 0, 3, 1, 2]);
        assert!(out.ends_with(b"CELL_TYPES 1\n\x00\x00\x00\x0a\n"));
    }

    #[test]
    fn out_of_range_tetrahedron_is_an_error() {
        let mut t = tet();
        t.tets.push([0, 1, 2, 4]);
        let mut out = Vec::new();
        let e = write_tets_vtu(&mut out, &t, Encoding::Ascii).unwrap_err();
        assert!(e.to_string().contains("tetrahedron 1"), "{e}");
    }

    #[test]
    fn names_are_escaped() {
        assert_eq!(xml_escape("a<b&\"c\""), "a&lt;b&amp;&quot;c&quot;");
        assert_eq!(legacy_name("my value"), "my_value");
        assert_eq!(legacy_name(""), "data");
    }
}

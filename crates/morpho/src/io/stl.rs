//! STL meshes, binary (little endian, `f32`) and ASCII.
//!
//! Detection: a file is ASCII when it starts with `solid` and its first kilobyte is plain text
//! containing `facet` or `endsolid`; every other file of at least 84 bytes is binary — also
//! when it starts with `solid`, as many exporters write. (So a binary file is recognised by
//! the `84 + 50·n` layout, `n` the little-endian `u32` at bytes 80..84, whatever its header.)
//! ASCII STL is `solid name / facet normal nx ny nz / outer loop / vertex x y z … / endloop /
//! endfacet / endsolid`, one statement per line; several solids are allowed and loops with more than three vertices
//! are fan-triangulated. In binary files a length shorter than `84 + 50·n` is a truncation
//! error naming the byte offset (extra trailing bytes are ignored).
//!
//! STL stores each triangle with its own three corners. Corners with exactly the same position
//! (same bit pattern after reading; `-0` and `+0` are the same) are merged into one vertex, in
//! the order of first appearance, so that the mesh's topology (edges, parts, genus) is that
//! of the surface that was written. Facet normals are ignored on reading. Expected linear
//! time (one hash-map lookup per corner).
//!
//! Writing: binary STL with `f32` coordinates and the facet normal computed from the corners
//! (zero for degenerate triangles), or ASCII STL with round-trip `f64` numbers. Big-endian STL
//! does not exist, so that encoding is refused.
use super::obj::{clip, numbered_lines, parse_f64, tokens, utf8_text, F64};
use super::Encoding;
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;
use crate::util::KeyedIdState;
use crate::{Error, Result};
use std::collections::hash_map::{Entry, HashMap};
use std::io::Write;

/// Merges corner positions into vertices by bit pattern, in order of first appearance.
struct Merger {
    /// Keyed: the keys come from the file ([`KeyedIdState`]).
    map: HashMap<(u64, u64, u64), u32, KeyedIdState>,
    positions: Vec<Point3>,
}

impl Merger {
    fn with_capacity(n: usize) -> Self {
        Merger {
            map: HashMap::with_capacity_and_hasher(n, KeyedIdState::new()),
            positions: Vec::with_capacity(n),
        }
    }
    fn add(&mut self, p: [f64; 3]) -> Result<u32> {
        // Adding +0.0 turns -0.0 into +0.0, so both zeros are one key.
        let key = (
            (p[0] + 0.0).to_bits(),
            (p[1] + 0.0).to_bits(),
            (p[2] + 0.0).to_bits(),
        );
        let next = self.positions.len();
        match self.map.entry(key) {
            Entry::Occupied(e) => Ok(*e.get()),
            Entry::Vacant(e) => {
                let i = u32::try_from(next)
                    .ok()
                    .filter(|&i| i != u32::MAX)
                    .ok_or_else(|| Error::invalid("more than 2^32-1 distinct vertices"))?;
                e.insert(i);
                self.positions.push(Point3::new(p[0], p[1], p[2]));
                Ok(i)
            }
        }
    }
}

/// True when `bytes` looks like ASCII STL text rather than a binary file with a `solid` header.
fn looks_ascii(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1024)];
    let text = head
        .iter()
        .all(|&b| b == b'\n' || b == b'\r' || b == b'\t' || (0x20..0x7f).contains(&b));
    let has = |w: &[u8]| head.windows(w.len()).any(|x| x == w);
    text && (has(b"facet") || has(b"endsolid"))
}

/// Reads ASCII or binary STL; coincident corner positions are merged into shared vertices.
pub fn read(bytes: &[u8]) -> Result<TriMesh> {
    if bytes.is_empty() {
        return Err(Error::format("empty file, expected STL"));
    }
    let trimmed = bytes.trim_ascii_start();
    let solid = trimmed.len() >= 5 && trimmed[..5].eq_ignore_ascii_case(b"solid");
    if bytes.len() >= 84 && !(solid && looks_ascii(bytes)) {
        return read_binary(bytes);
    }
    if solid {
        read_ascii(bytes)
    } else {
        Err(Error::format(format!(
            "{} bytes: too short for binary STL (84-byte header) and not ASCII STL",
            bytes.len()
        )))
    }
}

fn read_binary(bytes: &[u8]) -> Result<TriMesh> {
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
    let need = 84 + 50 * n;
    let have = bytes.len() as u64;
    if need > have {
        let full = (have - 84) / 50;
        return Err(Error::at_byte(
            84 + 50 * full,
            format!(
                "binary STL is truncated: header says {n} triangles ({need} bytes), the file has \
                 {have} bytes ({full} complete triangles)"
            ),
        ));
    }
    let n = n as usize;
    let mut merger = Merger::with_capacity(n.min(1 << 24));
    let mut triangles = Vec::with_capacity(n);
    for (t, rec) in bytes[84..84 + 50 * n].chunks_exact(50).enumerate() {
        let mut tri = [0u32; 3];
        for (k, v) in tri.iter_mut().enumerate() {
            let o = 12 + 12 * k;
            let f = |i: usize| {
                let j = o + 4 * i;
                f32::from_le_bytes([rec[j], rec[j + 1], rec[j + 2], rec[j + 3]]) as f64
            };
            let p = [f(0), f(1), f(2)];
            if !p.iter().all(|c| c.is_finite()) {
                return Err(Error::at_byte(
                    (84 + 50 * t + o) as u64,
                    format!("triangle {t}, corner {k} has a non-finite coordinate"),
                ));
            }
            *v = merger.add(p)?;
        }
        triangles.push(tri);
    }
    Ok(TriMesh::new(merger.positions, triangles))
}

/// Where the ASCII parser is in the grammar.
#[derive(PartialEq, Eq)]
enum State {
    Outside,
    Solid,
    Facet,
    Loop,
    EndFacet,
}

fn read_ascii(bytes: &[u8]) -> Result<TriMesh> {
    let text = utf8_text(bytes, 1)?;
    let mut st = State::Outside;
    let mut merger = Merger::with_capacity(1024);
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut solids = 0;
    let mut last = 1;
    for (line, l) in numbered_lines(text, 1) {
        last = line;
        let mut t = tokens(l);
        let Some(kw) = t.next() else { continue };
        let is = |w: &str| kw.eq_ignore_ascii_case(w);
        let unexpected =
            |want: &str| Error::at_line(line, format!("expected {want}, found '{}'", clip(kw)));
        match st {
            State::Outside => {
                if !is("solid") {
                    return Err(unexpected("'solid'"));
                }
                solids += 1;
                st = State::Solid;
            }
            State::Solid => {
                if is("facet") {
                    if let Some(w) = t.next() {
                        if !w.eq_ignore_ascii_case("normal") {
                            return Err(unexpected("'facet normal'"));
                        }
                        for _ in 0..3 {
                            let c = t.next().ok_or_else(|| {
                                Error::at_line(line, "facet normal needs 3 components")
                            })?;
                            parse_f64(c, line, "facet normal")?;
                        }
                    }
                    st = State::Facet;
                } else if is("endsolid") {
                    st = State::Outside;
                } else {
                    return Err(unexpected("'facet' or 'endsolid'"));
                }
            }
            State::Facet => {
                if !(is("outer") && t.next().is_some_and(|w| w.eq_ignore_ascii_case("loop"))) {
                    return Err(unexpected("'outer loop'"));
                }
                corners.clear();
                st = State::Loop;
            }
            State::Loop => {
                if is("vertex") {
                    let mut p = [0.0; 3];
                    for c in &mut p {
                        let tok = t
                            .next()
                            .ok_or_else(|| Error::at_line(line, "a vertex needs 3 coordinates"))?;
                        *c = parse_f64(tok, line, "vertex")?;
                    }
                    if !p.iter().all(|c| c.is_finite()) {
                        return Err(Error::at_line(
                            line,
                            format!(
                                "triangle {}, corner {} has a non-finite coordinate",
                                triangles.len(),
                                corners.len()
                            ),
                        ));
                    }
                    corners.push(merger.add(p)?);
                } else if is("endloop") {
                    if corners.len() < 3 {
                        return Err(Error::at_line(
                            line,
                            format!(
                                "facet with {} vertices; a facet needs at least 3",
                                corners.len()
                            ),
                        ));
                    }
                    for k in 1..corners.len() - 1 {
                        triangles.push([corners[0], corners[k], corners[k + 1]]);
                    }
                    st = State::EndFacet;
                } else {
                    return Err(unexpected("'vertex' or 'endloop'"));
                }
            }
            State::EndFacet => {
                if !is("endfacet") {
                    return Err(unexpected("'endfacet'"));
                }
                st = State::Solid;
            }
        }
    }
    if solids == 0 {
        return Err(Error::format("empty ASCII STL file"));
    }
    // A missing final `endsolid` is tolerated; a file ending inside a facet is not.
    if st != State::Outside && st != State::Solid {
        return Err(Error::at_line(
            last,
            "file ends inside a facet (data is truncated)",
        ));
    }
    Ok(TriMesh::new(merger.positions, triangles))
}

/// Unit normal of a triangle (zero if degenerate).
fn facet_normal(p: [Point3; 3]) -> Vector3 {
    let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
    let l = n.norm();
    if l > 0.0 && l.is_finite() {
        n / l
    } else {
        Vector3::zeros()
    }
}

/// Writes binary STL (`Ascii` encoding: ASCII STL; big endian is not an STL variant → error).
pub fn write(w: &mut dyn Write, mesh: &TriMesh, enc: Encoding) -> Result<()> {
    mesh.validate()?;
    match enc {
        Encoding::BinaryBigEndian => Err(Error::unsupported(
            "STL has no big-endian variant; use binary (little endian) or ASCII",
        )),
        Encoding::BinaryLittleEndian => write_binary(w, mesh),
        Encoding::Ascii => write_ascii(w, mesh).map_err(super::werr),
    }
}

fn corners(mesh: &TriMesh, t: &[u32; 3]) -> [Point3; 3] {
    t.map(|v| mesh.positions[v as usize])
}

fn write_binary(w: &mut dyn Write, mesh: &TriMesh) -> Result<()> {
    let n = u32::try_from(mesh.triangles.len())
        .map_err(|_| Error::invalid("binary STL holds at most 2^32-1 triangles"))?;
    let mut header = [b' '; 80];
    let tag = b"binary STL written by morpho";
    header[..tag.len()].copy_from_slice(tag);
    let mut buf = Vec::with_capacity(1 << 16);
    buf.extend_from_slice(&header);
    buf.extend_from_slice(&n.to_le_bytes());
    for t in &mesh.triangles {
        let p = corners(mesh, t);
        let nr = facet_normal(p);
        for c in [nr.x, nr.y, nr.z] {
            buf.extend_from_slice(&(c as f32).to_le_bytes());
        }
        for q in p {
            for c in [q.x, q.y, q.z] {
                buf.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        buf.extend_from_slice(&[0, 0]);
        if buf.len() >= 1 << 16 {
            w.write_all(&buf).map_err(super::werr)?;
            buf.clear();
        }
    }
    w.write_all(&buf).map_err(super::werr)
}

fn write_ascii(w: &mut dyn Write, mesh: &TriMesh) -> std::io::Result<()> {
    writeln!(w, "solid morpho")?;
    for t in &mesh.triangles {
        let p = corners(mesh, t);
        let n = facet_normal(p);
        writeln!(w, "  facet normal {} {} {}", F64(n.x), F64(n.y), F64(n.z))?;
        writeln!(w, "    outer loop")?;
        for q in p {
            writeln!(w, "      vertex {} {} {}", F64(q.x), F64(q.y), F64(q.z))?;
        }
        writeln!(w, "    endloop")?;
        writeln!(w, "  endfacet")?;
    }
    writeln!(w, "endsolid morpho")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> TriMesh {
        TriMesh::new(
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(0.0, 0.0, 1.0),
            ],
            vec![[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]],
        )
    }

    #[test]
    fn binary_and_ascii_round_trip() {
        let m = tetra();
        for enc in [Encoding::BinaryLittleEndian, Encoding::Ascii] {
            let mut buf = Vec::new();
            write(&mut buf, &m, enc).unwrap();
            assert_eq!(read(&buf).unwrap(), m, "{enc:?}");
        }
        assert!(write(&mut Vec::new(), &m, Encoding::BinaryBigEndian).is_err());
    }

    #[test]
    fn binary_starting_with_solid_is_binary() {
        let mut buf = Vec::new();
        write(&mut buf, &tetra(), Encoding::BinaryLittleEndian).unwrap();
        buf[..6].copy_from_slice(b"solid ");
        assert_eq!(read(&buf).unwrap(), tetra());
        // Truncated: error names the byte where the incomplete triangle starts.
        let e = read(&buf[..buf.len() - 10]).unwrap_err().to_string();
        assert!(e.contains("byte 234"), "{e}");
    }

    #[test]
    fn ascii_variants_and_errors() {
        let quad =
            "solid q\r\nfacet normal 0 0 1\r\nouter loop\r\nvertex 0 0 0\r\nvertex 1 0 0\r\n\
                    vertex 1 1 0\r\nvertex 0 1 0\r\nendloop\r\nendfacet\r\nendsolid q\r\n\
                    solid second\nendsolid\n";
        let m = read(quad.as_bytes()).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        let nan = "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n";
        let e = read(nan.as_bytes()).unwrap_err().to_string();
        assert!(e.contains("line 5") && e.contains("corner 1"), "{e}");
        let cut = "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
        assert!(read(cut.as_bytes()).is_err());
        assert!(read(b"").is_err());
        assert!(read(b"solid \xff\n").is_err());
    }
}

//! Wavefront OBJ meshes (the geometry subset: `v`, `vn`, `f`).
//!
//! Reading: `v x y z [w]` (further numbers such as vertex colours and `w` are ignored), `vn`
//! normals, `f` with corners `i`, `i/t`, `i//n`, `i/t/n`, negative indices counting back from
//! the last vertex defined so far, polygons fan-triangulated (`v0 v(k) v(k+1)`). `vt`, `vp`, `l`,
//! `p`, `o`, `g`, `s`, `usemtl`, `mtllib`, comments and any other identifier-like statement are
//! ignored. Errors name the 1-based line. Per-corner normals become per-vertex normals when
//! every vertex gets exactly one normal (from the corners, or `vn` i for vertex i when the
//! counts agree); otherwise normals are dropped.
//!
//! Writing: `v` with Rust's shortest round-trip representation of each `f64` (so a write/read
//! round trip is exact), `vn` when the mesh has normals, `f` with 1-based indices
//! (`a//a` form with normals). Vertex and face properties have no place in OBJ and are dropped.
//!
//! Linear time; one pass over the text, no per-line allocation.
//!
//! This file also holds small text helpers shared by the other text mesh formats.
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;
use crate::{Error, Result};
use std::fmt;
use std::io::Write;

/// The whole input as UTF-8 text, or an error naming the first line that is not.
/// A leading byte-order mark is dropped.
pub(crate) fn utf8_text(bytes: &[u8], first_line: u64) -> Result<&str> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let before = bytes.get(..e.valid_up_to()).unwrap_or(&[]);
        let line = before.iter().filter(|&&b| b == b'\n').count() as u64 + first_line;
        Error::at_line(line, "not valid UTF-8 text")
    })?;
    Ok(text.strip_prefix('\u{feff}').unwrap_or(text))
}

/// The lines of a text, numbered from `first`, without the `\n` and a trailing `\r`.
///
/// Hand-written rather than `str::split` + `split_ascii_whitespace` so that parsing stays fast
/// in unoptimised (test) builds too.
pub(crate) struct Lines<'a> {
    text: &'a str,
    pos: usize,
    next: u64,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(text: &'a str, first: u64) -> Self {
        Lines {
            text,
            pos: 0,
            next: first,
        }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (u64, &'a str);
    #[inline]
    fn next(&mut self) -> Option<(u64, &'a str)> {
        let b = self.text.as_bytes();
        if self.pos > b.len() || (self.pos == b.len() && self.pos > 0) {
            return None;
        }
        let start = self.pos;
        let mut j = start;
        while j < b.len() && b[j] != b'\n' {
            j += 1;
        }
        self.pos = j + 1;
        let end = if j > start && b[j - 1] == b'\r' {
            j - 1
        } else {
            j
        };
        let n = self.next;
        self.next += 1;
        // `\n` and `\r` are ASCII, so these are character boundaries.
        Some((n, self.text.get(start..end).unwrap_or("")))
    }
}

/// Numbered lines (see [`Lines`]).
pub(crate) fn numbered_lines(text: &str, first: u64) -> Lines<'_> {
    Lines::new(text, first)
}

/// Number of lines of `text` (the last one may lack its `\n`).
pub(crate) fn count_lines(text: &str) -> u64 {
    let mut n = 1;
    for &b in text.as_bytes() {
        n += (b == b'\n') as u64;
    }
    n
}

/// The whitespace-separated tokens of a line (see [`Lines`] for why it is hand-written).
#[derive(Clone)]
pub(crate) struct Tokens<'a> {
    s: &'a str,
    pos: usize,
}

/// Tokens of `s`.
pub(crate) fn tokens(s: &str) -> Tokens<'_> {
    Tokens { s, pos: 0 }
}

#[inline]
fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t' || b == b'\r' || b == 0x0b || b == 0x0c || b == b'\n'
}

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a str;
    #[inline]
    fn next(&mut self) -> Option<&'a str> {
        let b = self.s.as_bytes();
        let mut i = self.pos;
        while i < b.len() && is_space(b[i]) {
            i += 1;
        }
        if i >= b.len() {
            self.pos = i;
            return None;
        }
        let start = i;
        while i < b.len() && !is_space(b[i]) {
            i += 1;
        }
        self.pos = i;
        // Token boundaries are next to ASCII whitespace or the ends: character boundaries.
        self.s.get(start..i)
    }
}

/// Shortest representation of an `f64` that parses back to the same value: plain decimal for
/// moderate magnitudes, exponent notation for very large or small ones.
#[derive(Clone, Copy)]
pub(crate) struct F64(pub f64);

impl fmt::Display for F64 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-5..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Shortest representation of an `f32` that parses (as `f32`) back to the same value.
#[derive(Clone, Copy)]
pub(crate) struct F32(pub f32);

impl fmt::Display for F32 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-5..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Parses a number token, naming the line on failure.
pub(crate) fn parse_f64(tok: &str, line: u64, what: &str) -> Result<f64> {
    tok.parse::<f64>()
        .map_err(|_| Error::at_line(line, format!("{what}: '{}' is not a number", clip(tok))))
}

/// A token shortened for an error message.
pub(crate) fn clip(tok: &str) -> String {
    if tok.chars().count() > 24 {
        let s: String = tok.chars().take(24).collect();
        format!("{s}…")
    } else {
        tok.to_string()
    }
}

/// Resolves one OBJ index (1-based, or negative = relative to `count` elements defined so far)
/// to a 0-based index. Positive indices are not range-checked here.
fn resolve(tok: &str, count: usize, line: u64, what: &str) -> Result<u32> {
    let i: i64 = tok.parse().map_err(|_| {
        Error::at_line(
            line,
            format!("{what} index '{}' is not an integer", clip(tok)),
        )
    })?;
    let r = if i > 0 {
        i - 1
    } else if i < 0 {
        let r = count as i64 + i;
        if r < 0 {
            return Err(Error::at_line(
                line,
                format!("relative {what} index {i}, but only {count} are defined before this line"),
            ));
        }
        r
    } else {
        return Err(Error::at_line(
            line,
            format!("{what} index 0 (OBJ indices start at 1)"),
        ));
    };
    u32::try_from(r)
        .ok()
        .filter(|&r| r != u32::MAX)
        .ok_or_else(|| Error::at_line(line, format!("{what} index {i} is too large")))
}

const NO_NORMAL: u32 = u32::MAX;

/// Reads a mesh (polygons are fan-triangulated).
pub fn read(bytes: &[u8]) -> Result<TriMesh> {
    let bytes = &*super::unify_line_ends(bytes);
    let text = utf8_text(bytes, 1)?;
    let mut positions: Vec<Point3> = Vec::new();
    let mut vn: Vec<Vector3> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    // Normal index of each triangle corner (only filled once a corner refers to a normal).
    let mut tri_normals: Vec<[u32; 3]> = Vec::new();
    let mut any_corner_normal = false;
    // Largest positive vertex / normal reference and its line (checked at the end, so that
    // files defining vertices after the faces are accepted).
    let mut max_v: Option<(u32, u64, usize)> = None;
    let mut max_n: Option<(u32, u64)> = None;
    let mut faces = 0usize;
    let mut corners: Vec<(u32, u32)> = Vec::new();

    for (line, raw) in numbered_lines(text, 1) {
        let l = raw.trim_start();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let mut toks = tokens(l);
        let kw = toks.next().unwrap_or("");
        match kw {
            "v" => {
                let mut c = [0.0; 3];
                for (k, c) in c.iter_mut().enumerate() {
                    let t = toks.next().filter(|t| !t.starts_with('#')).ok_or_else(|| {
                        Error::at_line(
                            line,
                            format!("vertex {} has {k} coordinates, needs 3", positions.len()),
                        )
                    })?;
                    *c = parse_f64(t, line, "vertex")?;
                }
                if !c.iter().all(|c| c.is_finite()) {
                    return Err(Error::at_line(
                        line,
                        format!("vertex {} has a non-finite coordinate", positions.len()),
                    ));
                }
                positions.push(Point3::new(c[0], c[1], c[2]));
            }
            "vn" => {
                let mut c = [0.0; 3];
                for (k, c) in c.iter_mut().enumerate() {
                    let t = toks.next().filter(|t| !t.starts_with('#')).ok_or_else(|| {
                        Error::at_line(
                            line,
                            format!("normal {} has {k} components, needs 3", vn.len()),
                        )
                    })?;
                    *c = parse_f64(t, line, "normal")?;
                }
                vn.push(Vector3::new(c[0], c[1], c[2]));
            }
            "f" | "fo" => {
                corners.clear();
                for t in toks {
                    if t.starts_with('#') {
                        break;
                    }
                    let mut parts = t.split('/');
                    let v = resolve(parts.next().unwrap_or(""), positions.len(), line, "vertex")?;
                    if max_v.map_or(true, |(m, _, _)| v > m) {
                        max_v = Some((v, line, faces));
                    }
                    let tex = parts.next();
                    if let Some(tex) = tex.filter(|s| !s.is_empty()) {
                        if tex.parse::<i64>().is_err() {
                            return Err(Error::at_line(
                                line,
                                format!("texture index '{}' is not an integer", clip(tex)),
                            ));
                        }
                    }
                    let n = match parts.next().filter(|s| !s.is_empty()) {
                        Some(n) => {
                            let n = resolve(n, vn.len(), line, "normal")?;
                            if max_n.map_or(true, |(m, _)| n > m) {
                                max_n = Some((n, line));
                            }
                            any_corner_normal = true;
                            n
                        }
                        None => NO_NORMAL,
                    };
                    if parts.next().is_some() {
                        return Err(Error::at_line(
                            line,
                            format!("face corner '{}' has more than three parts", clip(t)),
                        ));
                    }
                    corners.push((v, n));
                }
                if corners.len() < 3 {
                    return Err(Error::at_line(
                        line,
                        format!(
                            "face {faces} has {} corners; a face needs at least 3",
                            corners.len()
                        ),
                    ));
                }
                if any_corner_normal && tri_normals.len() < triangles.len() {
                    tri_normals.resize(triangles.len(), [NO_NORMAL; 3]);
                }
                let (v0, n0) = corners[0];
                for w in corners[1..].windows(2) {
                    triangles.push([v0, w[0].0, w[1].0]);
                    if any_corner_normal {
                        tri_normals.push([n0, w[0].1, w[1].1]);
                    }
                }
                faces += 1;
            }
            _ => {
                if !kw.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
                    return Err(Error::at_line(
                        line,
                        format!("unrecognised OBJ statement '{}'", clip(kw)),
                    ));
                }
            }
        }
    }
    if positions.is_empty() {
        return Err(Error::format("OBJ file has no vertices"));
    }
    let nv = positions.len();
    if let Some((m, line, face)) = max_v {
        if m as usize >= nv {
            return Err(Error::at_line(
                line,
                format!(
                    "face {face} refers to vertex {}, but the file has only {nv} vertices",
                    m as u64 + 1
                ),
            ));
        }
    }
    if let Some((m, line)) = max_n {
        if m as usize >= vn.len() {
            return Err(Error::at_line(
                line,
                format!(
                    "face refers to normal {}, but the file has only {} normals",
                    m as u64 + 1,
                    vn.len()
                ),
            ));
        }
    }
    let normals = vertex_normals(nv, &vn, &triangles, &tri_normals, any_corner_normal);
    Ok(TriMesh {
        positions,
        triangles,
        normals,
        ..Default::default()
    })
}

/// Per-vertex normals from per-corner references: each vertex must get one normal value.
fn vertex_normals(
    nv: usize,
    vn: &[Vector3],
    triangles: &[[u32; 3]],
    tri_normals: &[[u32; 3]],
    any_corner_normal: bool,
) -> Option<Vec<Vector3>> {
    if vn.is_empty() {
        return None;
    }
    if !any_corner_normal {
        return (vn.len() == nv).then(|| vn.to_vec());
    }
    let mut map = vec![NO_NORMAL; nv];
    for (t, ns) in triangles.iter().zip(tri_normals) {
        for k in 0..3 {
            let (v, n) = (t[k] as usize, ns[k]);
            if n == NO_NORMAL {
                continue;
            }
            let m = map.get_mut(v)?;
            if *m == NO_NORMAL {
                *m = n;
            } else if *m != n && vn.get(*m as usize) != vn.get(n as usize) {
                return None; // two different normals at one vertex
            }
        }
    }
    map.iter()
        .enumerate()
        .map(|(i, &n)| {
            if n != NO_NORMAL {
                vn.get(n as usize).copied()
            } else if vn.len() == nv {
                vn.get(i).copied()
            } else {
                None
            }
        })
        .collect()
}

/// Writes a mesh.
pub fn write(w: &mut dyn Write, mesh: &TriMesh) -> Result<()> {
    mesh.validate()?;
    write_body(w, mesh).map_err(super::werr)
}

fn write_body(w: &mut dyn Write, mesh: &TriMesh) -> std::io::Result<()> {
    writeln!(w, "# written by morpho")?;
    for p in &mesh.positions {
        writeln!(w, "v {} {} {}", F64(p.x), F64(p.y), F64(p.z))?;
    }
    if let Some(ns) = &mesh.normals {
        for n in ns {
            writeln!(w, "vn {} {} {}", F64(n.x), F64(n.y), F64(n.z))?;
        }
        for &[a, b, c] in &mesh.triangles {
            let (a, b, c) = (a as u64 + 1, b as u64 + 1, c as u64 + 1);
            writeln!(w, "f {a}//{a} {b}//{b} {c}//{c}")?;
        }
    } else {
        for &[a, b, c] in &mesh.triangles {
            writeln!(w, "f {} {} {}", a as u64 + 1, b as u64 + 1, c as u64 + 1)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_all_face_forms_and_ignores_the_rest() {
        let src = "# cube corner\r\nmtllib a.mtl\no thing\ng grp\ns off\nusemtl m\n\
                   v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                   f 1 2 3\nf 1/1 3/1 4/1\nf -4//1 -3//1 -2//1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nl 1 2\n";
        let m = read(src.as_bytes()).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.positions[2], Point3::new(1.0, 1.0, 0.0));
        assert_eq!(
            m.triangles,
            vec![[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 1, 2], [0, 2, 3]]
        );
        // Vertex 3 (index 3) got normal 1 through the quad; all vertices share one normal.
        assert_eq!(m.normals.unwrap()[3], Vector3::new(0.0, 0.0, 1.0));
    }

    #[test]
    fn normals_without_corner_references_and_conflicts() {
        let m = read(
            "\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 1 0\nf 1 2 3\n".as_bytes(),
        )
        .unwrap();
        assert_eq!(m.normals.unwrap()[2], Vector3::new(0.0, 1.0, 0.0));
        // Vertex 1 gets two different normals: no per-vertex normals.
        let m = read(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 1 0 0\nf 1//1 2//1 3//1\nf 1//1 3//1 2//2\n",
        )
        .unwrap();
        assert!(m.normals.is_none());
        // Fewer normals than vertices and vertex 4 without one: none either.
        let m = read(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvn 0 0 1\nf 1//1 2//1 3//1\n").unwrap();
        assert!(m.normals.is_none());
        assert!(read(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n").is_err());
    }

    #[test]
    fn errors_name_the_line() {
        let e = read(b"v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("2 corners"), "{e}");
        let e = read(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 4") && e.contains("vertex 9"), "{e}");
        let e = read(b"v 0 0 0\nv 1 nan 0\n").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("vertex 1"), "{e}");
        let e = read(b"v 0 0 0\nf -2 1 1\n").unwrap_err().to_string();
        assert!(e.contains("line 2"), "{e}");
        let e = read(b"v 0 0 0\nf 0 1 1\n").unwrap_err().to_string();
        assert!(e.contains("index 0"), "{e}");
        let e = read(b"v 0 0 0\nv 1 \xff 0\n").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("UTF-8"), "{e}");
        assert!(read(b"").is_err());
        assert!(read(b"\x00\x01\x02garbage").is_err());
    }

    #[test]
    fn write_read_is_exact() {
        let mut m = TriMesh::new(
            vec![
                Point3::new(0.1, -1e-300, 1e300),
                Point3::new(1.0 / 3.0, -0.0, 123456789.12345679),
                Point3::new(f64::MIN_POSITIVE, f64::MAX, 2.5e-7),
            ],
            vec![[0, 1, 2]],
        );
        let mut buf = Vec::new();
        write(&mut buf, &m).unwrap();
        assert_eq!(read(&buf).unwrap(), m);
        m.normals = Some(vec![Vector3::new(0.0, 0.0, 1.0); 3]);
        buf.clear();
        write(&mut buf, &m).unwrap();
        assert_eq!(read(&buf).unwrap(), m);
    }
}

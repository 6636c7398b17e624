//! OFF meshes (Geomview object file format), ASCII.
//!
//! Header keyword `[ST][C][N][4][n]OFF` (so `OFF`, `COFF`, `NOFF`, `CNOFF`, `4OFF`, `STCNOFF`,
//! …; the prefixes are accepted in any order, e.g. `NCOFF`), for `nOFF` a dimension that must be 3, then `NVertices NFaces [NEdges]` (on the keyword's
//! line or the next), then one vertex per line — `x y z [w]`, then the normal if `N`, then
//! colour and texture coordinates, which are ignored — and one face per line
//! `n i0 … i(n-1) [colour]`. Polygons are fan-triangulated; `#` starts a comment. With `N`
//! the per-vertex normals are read. With `4` the coordinates are divided by `w`.
//! `OFF BINARY` is not supported.
//!
//! The counts are checked against the number of lines in the file before anything is
//! allocated. Errors name the 1-based line. Linear time.
//!
//! Writing: plain `OFF` with Rust's shortest round-trip representation of each coordinate
//! (a write/read round trip is exact). Normals and properties are not written.
use super::obj::{clip, count_lines, numbered_lines, parse_f64, tokens, utf8_text, F64};
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;
use crate::{Error, Result};
use std::io::Write;

/// What the header keyword announces.
#[derive(Debug, Default, Clone, Copy)]
struct Variant {
    normals: bool,
    homogeneous: bool,
    ndim: bool,
}

fn parse_keyword(kw: &str, line: u64) -> Result<Variant> {
    let bad = || {
        Error::at_line(
            line,
            format!("not an OFF file: header keyword '{}'", clip(kw)),
        )
    };
    let mut rest = kw.strip_suffix("OFF").ok_or_else(bad)?;
    let mut v = Variant::default();
    // Geomview's order is ST C N 4 n; other writers use e.g. NCOFF, so any order is accepted.
    let mut seen = [false; 5];
    while !rest.is_empty() {
        let (k, len) = match rest.as_bytes()[0] {
            b'S' if rest.starts_with("ST") => (0, 2),
            b'C' => (1, 1),
            b'N' => (2, 1),
            b'4' => (3, 1),
            b'n' => (4, 1),
            _ => return Err(bad()),
        };
        if std::mem::replace(&mut seen[k], true) {
            return Err(bad());
        }
        rest = &rest[len..];
    }
    v.normals = seen[2];
    v.homogeneous = seen[3];
    v.ndim = seen[4];
    Ok(v)
}

fn parse_count(tok: Option<&str>, line: u64, what: &str) -> Result<u64> {
    let tok = tok.ok_or_else(|| Error::at_line(line, format!("missing {what}")))?;
    tok.parse::<u64>().map_err(|_| {
        Error::at_line(
            line,
            format!("{what} '{}' is not a non-negative integer", clip(tok)),
        )
    })
}

/// Reads a mesh (polygons are fan-triangulated).
pub fn read(bytes: &[u8]) -> Result<TriMesh> {
    let bytes = &*super::unify_line_ends(bytes);
    let text = utf8_text(bytes, 1)?;
    let total_lines = count_lines(text);
    // Significant lines: comments stripped, blank lines skipped.
    let mut lines = numbered_lines(text, 1).filter_map(|(n, l)| {
        let l = l.split('#').next().unwrap_or("").trim();
        (!l.is_empty()).then_some((n, l))
    });
    let (hline, header) = lines
        .next()
        .ok_or_else(|| Error::format("empty file, expected an OFF header"))?;
    let mut toks = tokens(header);
    let variant = parse_keyword(toks.next().unwrap_or(""), hline)?;
    // Counts may follow the keyword on its line or come on the next lines.
    let mut pending: Vec<(u64, &str)> = toks.map(|t| (hline, t)).collect();
    if pending.first().is_some_and(|t| t.1 == "BINARY") {
        return Err(Error::unsupported("binary OFF is not supported"));
    }
    let needed = if variant.ndim { 3 } else { 2 };
    while pending.len() < needed {
        let (n, l) = lines.next().ok_or_else(|| {
            Error::at_line(total_lines, "file ends before the vertex and face counts")
        })?;
        pending.extend(tokens(l).map(|t| (n, t)));
    }
    let mut it = pending.into_iter();
    if variant.ndim {
        let (n, t) = it.next().unwrap_or((hline, ""));
        let dim = parse_count(Some(t), n, "dimension")?;
        if dim != 3 {
            return Err(Error::unsupported(format!(
                "nOFF with dimension {dim}; only 3D meshes are supported"
            )));
        }
    }
    let (cline, t) = it.next().unwrap_or((hline, ""));
    let nv = parse_count(Some(t), cline, "vertex count")?;
    let (cline, t) = it.next().unwrap_or((cline, ""));
    let nf = parse_count(Some(t), cline, "face count")?;
    let left = total_lines - cline;
    if nv.saturating_add(nf) > left {
        return Err(Error::at_line(
            cline,
            format!("header claims {nv} vertices and {nf} faces, but only {left} lines follow"),
        ));
    }
    if nv > u32::MAX as u64 - 1 {
        return Err(Error::at_line(cline, format!("{nv} vertices are too many")));
    }
    let ncoord = if variant.homogeneous { 4 } else { 3 };
    let nneed = ncoord + if variant.normals { 3 } else { 0 };
    let mut positions = Vec::with_capacity(nv as usize);
    let mut normals = variant.normals.then(|| Vec::with_capacity(nv as usize));
    let mut vals = [0.0f64; 7];
    for i in 0..nv {
        let (line, l) = lines.next().ok_or_else(|| {
            Error::at_line(total_lines, format!("file ends after {i} of {nv} vertices"))
        })?;
        let mut toks = tokens(l);
        for (k, v) in vals.iter_mut().take(nneed).enumerate() {
            let t = toks.next().ok_or_else(|| {
                Error::at_line(line, format!("vertex {i} has {k} values, needs {nneed}"))
            })?;
            *v = parse_f64(t, line, "vertex")?;
        }
        let mut p = [vals[0], vals[1], vals[2]];
        if variant.homogeneous {
            let w = vals[3];
            p = [p[0] / w, p[1] / w, p[2] / w];
        }
        if !p.iter().all(|c| c.is_finite()) {
            return Err(Error::at_line(
                line,
                format!("vertex {i} has a non-finite coordinate"),
            ));
        }
        positions.push(Point3::new(p[0], p[1], p[2]));
        if let Some(ns) = &mut normals {
            ns.push(Vector3::new(
                vals[ncoord],
                vals[ncoord + 1],
                vals[ncoord + 2],
            ));
        }
    }
    let mut triangles = Vec::with_capacity(nf as usize);
    for f in 0..nf {
        let (line, l) = lines.next().ok_or_else(|| {
            Error::at_line(total_lines, format!("file ends after {f} of {nf} faces"))
        })?;
        let mut toks = tokens(l);
        let n = parse_count(toks.next(), line, "face corner count")?;
        if n < 3 {
            return Err(Error::at_line(
                line,
                format!("face {f} has {n} corners; a face needs at least 3"),
            ));
        }
        let mut corner = |k: u64| -> Result<u32> {
            let t = toks.next().ok_or_else(|| {
                Error::at_line(line, format!("face {f} lists {k} of its {n} corners"))
            })?;
            let v: u64 = t.parse().map_err(|_| {
                Error::at_line(
                    line,
                    format!(
                        "face {f}: index '{}' is not a non-negative integer",
                        clip(t)
                    ),
                )
            })?;
            if v >= nv {
                return Err(Error::at_line(
                    line,
                    format!("face {f} refers to vertex {v}, but there are only {nv} vertices"),
                ));
            }
            Ok(v as u32)
        };
        let v0 = corner(0)?;
        let mut prev = corner(1)?;
        for k in 2..n {
            let v = corner(k)?;
            triangles.push([v0, prev, v]);
            prev = v;
        }
    }
    Ok(TriMesh {
        positions,
        triangles,
        normals,
        ..Default::default()
    })
}

/// Writes a mesh.
pub fn write(w: &mut dyn Write, mesh: &TriMesh) -> Result<()> {
    mesh.validate()?;
    write_body(w, mesh).map_err(super::werr)
}

fn write_body(w: &mut dyn Write, mesh: &TriMesh) -> std::io::Result<()> {
    writeln!(w, "OFF")?;
    writeln!(w, "{} {} 0", mesh.positions.len(), mesh.triangles.len())?;
    for p in &mesh.positions {
        writeln!(w, "{} {} {}", F64(p.x), F64(p.y), F64(p.z))?;
    }
    for &[a, b, c] in &mesh.triangles {
        writeln!(w, "3 {a} {b} {c}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_variants() {
        let plain = "OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n";
        let m = read(plain.as_bytes()).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        let coff = "COFF 3 1 3\r\n0 0 0 255 0 0 255\r\n1 0 0 0 255 0 255\r\n0 1 0 0 0 255 255\r\n3 0 1 2\r\n";
        let m = read(coff.as_bytes()).unwrap();
        assert_eq!(m.positions[1], Point3::new(1.0, 0.0, 0.0));
        assert!(m.normals.is_none());
        let ncoff = "NCOFF\n3 1 0\n0 0 0 0 0 1 1 0 0 1\n2 0 0 0 0 1 1 0 0 1\n0 2 0 0 0 -1 1 0 0 1\n3 0 1 2\n";
        let m = read(ncoff.as_bytes()).unwrap();
        assert_eq!(m.positions[1], Point3::new(2.0, 0.0, 0.0));
        assert_eq!(m.normals.unwrap()[2], Vector3::new(0.0, 0.0, -1.0));
        let four = "4OFF\n3 1 0\n0 0 0 1\n2 0 0 2\n0 4 0 2\n3 0 1 2\n";
        assert_eq!(
            read(four.as_bytes()).unwrap().positions[2],
            Point3::new(0.0, 2.0, 0.0)
        );
        let n = "nOFF 3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(read(n.as_bytes()).unwrap().triangles.len(), 1);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(read(b"").is_err());
        let e = read(b"OFF\n1000000000000 1 0\n0 0 0\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2") && e.contains("lines follow"), "{e}");
        let e = read(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 6") && e.contains("face 0"), "{e}");
        let e = read(b"OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 4") && e.contains("vertex 1"), "{e}");
        let e = read(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("2 corners"), "{e}");
        assert!(read(b"OFF\n3 1 0\n0 0 0\n1 0 0\n").is_err());
        assert!(read(b"OFF\n3 1 0\n0 0 \xfe\n1 0 0\n0 1 0\n3 0 1 2\n").is_err());
        assert!(read(b"PLY\n3 1 0\n").is_err());
    }

    #[test]
    fn write_read_is_exact() {
        let m = TriMesh::new(
            vec![
                Point3::new(0.1, 0.2, 0.3),
                Point3::new(1e-300, -7.0, 1.0 / 7.0),
                Point3::new(3.0, 1e22, -0.0),
            ],
            vec![[0, 1, 2], [2, 1, 0]],
        );
        let mut buf = Vec::new();
        write(&mut buf, &m).unwrap();
        assert_eq!(read(&buf).unwrap(), m);
    }
}

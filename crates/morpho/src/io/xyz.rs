//! Whitespace-separated coordinates, one point per line, no header (`.xyz`, `.txt`, `.p2d`,
//! `.pts`).
//!
//! - Fields are separated by spaces, tabs or commas; `#` starts a comment (whole line or
//!   rest of line); blank lines are skipped; `\r\n` line ends and a UTF-8 BOM are tolerated.
//! - The first data line fixes the column count: 2 → 2D points, 3 → 3D points, more → 3D
//!   points plus value columns named `c3`, `c4`, … (0-based column index). If the last comment
//!   line before the first data line lists exactly that many names starting `x y`, those names
//!   are used instead, and a third name other than `z` makes the points 2D with value columns
//!   from the third on (this is what [`write()`] emits, so columns round-trip).
//! - Every later line must have the same count; coordinates must be finite numbers; value
//!   columns may hold `nan`/`NA` (missing). Errors name the line.
//!
//! Complexity: linear in the file size.

use super::csv::{is_missing, numbered_lines, text};
use crate::mesh::{Column, PointSet};
use crate::{Error, Result};
use std::io::Write;

/// Reads 2 or 3 numbers per line (the first line fixes the dimension).
pub fn read(bytes: &[u8]) -> Result<PointSet> {
    let bytes = &*super::unify_line_ends(bytes);
    let s = text(bytes)?;
    let mut ncol = 0usize;
    let mut dim = 0usize;
    let mut names: Option<Vec<String>> = None;
    let mut last_comment: Option<&str> = None;
    let mut coords = Vec::new();
    let mut extra: Vec<Vec<f64>> = Vec::new();
    let mut fields: Vec<&str> = Vec::new();
    for (no, line) in numbered_lines(s) {
        let (data, comment) = match line.find('#') {
            Some(i) => (&line[..i], Some(&line[i + 1..])),
            None => (line, None),
        };
        fields.clear();
        fields.extend(
            data.split(|c: char| c.is_whitespace() || c == ',')
                .filter(|f| !f.is_empty()),
        );
        if fields.is_empty() {
            if ncol == 0 {
                if let Some(c) = comment {
                    last_comment = Some(c);
                }
            }
            continue;
        }
        if ncol == 0 {
            ncol = fields.len();
            if ncol < 2 {
                return Err(Error::at_line(
                    no,
                    "expected at least 2 numbers (x y) per line",
                ));
            }
            let mut n: Vec<String> = (0..ncol)
                .map(|i| match i {
                    0 => "x".into(),
                    1 => "y".into(),
                    2 => "z".into(),
                    _ => format!("c{i}"),
                })
                .collect();
            dim = ncol.min(3);
            if let Some(c) = last_comment {
                let toks: Vec<&str> = c.split_whitespace().collect();
                if toks.len() == ncol
                    && toks[0].eq_ignore_ascii_case("x")
                    && toks[1].eq_ignore_ascii_case("y")
                {
                    if ncol > 2 && !toks[2].eq_ignore_ascii_case("z") {
                        dim = 2;
                    }
                    n = toks.iter().map(|t| t.to_string()).collect();
                }
            }
            names = Some(n);
            extra = vec![Vec::new(); ncol - dim];
        } else if fields.len() != ncol {
            return Err(Error::at_line(
                no,
                format!(
                    "{} numbers on this line, the first data line has {ncol}",
                    fields.len()
                ),
            ));
        }
        for (k, f) in fields.iter().enumerate() {
            if k < dim {
                let v: f64 = f
                    .parse()
                    .map_err(|_| Error::at_line(no, format!("coordinate '{f}' is not a number")))?;
                if !v.is_finite() {
                    return Err(Error::at_line(
                        no,
                        format!("coordinate '{f}' is not finite"),
                    ));
                }
                coords.push(v);
            } else {
                let v = if is_missing(f) {
                    f64::NAN
                } else {
                    f.parse()
                        .map_err(|_| Error::at_line(no, format!("value '{f}' is not a number")))?
                };
                extra[k - dim].push(v);
            }
        }
    }
    if ncol == 0 {
        return Err(Error::format("no points (empty file)"));
    }
    let names = names.unwrap_or_default();
    let columns = extra
        .into_iter()
        .zip(names.into_iter().skip(dim))
        .map(|(values, name)| Column { name, values })
        .collect();
    Ok(PointSet {
        dim,
        coords,
        columns,
    })
}

/// Writes one point per line (a `# x y [z] names…` comment first when there are columns;
/// column names must be non-empty without blanks or `#`).
pub fn write(w: &mut dyn Write, pts: &PointSet) -> Result<()> {
    pts.validate()?;
    let e = super::werr;
    if !pts.columns.is_empty() {
        let ok = |n: &str| !n.is_empty() && !n.contains(|c: char| c.is_whitespace() || c == '#');
        if let Some(c) = pts.columns.iter().find(|c| !ok(&c.name)) {
            return Err(Error::unsupported(format!(
                "column name '{}' cannot be written to XYZ (empty, blank or '#'); use CSV",
                c.name
            )));
        }
        let names: Vec<&str> = pts.columns.iter().map(|c| c.name.as_str()).collect();
        let xyz = if pts.dim == 3 { "x y z" } else { "x y" };
        writeln!(w, "# {xyz} {}", names.join(" ")).map_err(e)?;
    }
    let mut row = String::new();
    for i in 0..pts.len() {
        row.clear();
        for (k, c) in pts.point(i).iter().enumerate() {
            if k > 0 {
                row.push(' ');
            }
            row.push_str(&format!("{c}"));
        }
        for c in &pts.columns {
            row.push_str(&format!(" {}", c.values[i]));
        }
        writeln!(w, "{row}").map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_comments_blank_lines_and_columns() {
        let p = read(b"# hello\n\n1 2\r\n3\t4 # tail\n\n\n").unwrap();
        assert_eq!((p.dim, p.coords.clone()), (2, vec![1., 2., 3., 4.]));
        let p = read(b"1 2 3 4 5\n6 7 8 9 nan\n").unwrap();
        assert_eq!(p.dim, 3);
        assert_eq!(p.columns[1].name, "c4");
        assert!(p.columns[1].values[1].is_nan());
    }

    #[test]
    fn errors_name_lines() {
        let err = read(b"1 2\n3 4 5\n").unwrap_err().to_string();
        assert!(err.contains("line 2"), "{err}");
        let err = read(b"1 2\n\n3 nan\n").unwrap_err().to_string();
        assert!(err.contains("line 3"), "{err}");
        let err = read(b"1\n").unwrap_err().to_string();
        assert!(err.contains("line 1"), "{err}");
        assert!(read(b"").is_err());
        assert!(read(b"# only a comment\n").is_err());
    }

    #[test]
    fn two_d_points_with_named_columns() {
        let p = read(b"# x y zinc\n1 2 3\n4 5 NA\n").unwrap();
        assert_eq!((p.dim, p.len()), (2, 2));
        assert_eq!(p.columns[0].name, "zinc");
        let mut out = Vec::new();
        write(&mut out, &p).unwrap();
        let q = read(&out).unwrap();
        assert_eq!(q.coords, p.coords);
        assert_eq!(q.columns[0].values[0], 3.0);
        assert!(q.columns[0].values[1].is_nan());
    }

    #[test]
    fn round_trip_with_named_columns() {
        let p = PointSet {
            dim: 3,
            coords: vec![0.1, 0.2, 0.3, 1e-300, -5.0, 7.25],
            columns: vec![Column {
                name: "value".into(),
                values: vec![1.5, f64::NAN],
            }],
        };
        let mut out = Vec::new();
        write(&mut out, &p).unwrap();
        let q = read(&out).unwrap();
        assert_eq!(q.coords, p.coords);
        assert_eq!(q.columns[0].name, "value");
        assert_eq!(q.columns[0].values[0], 1.5);
        assert!(q.columns[0].values[1].is_nan());
    }
}

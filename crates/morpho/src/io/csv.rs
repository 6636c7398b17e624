//! CSV points (header `x,y[,z][,more columns]`) and polygons/polylines (ordered vertices).
//!
//! # Reading
//! - Text must be UTF-8 (a BOM is skipped); lines may end in `\n` or `\r\n`; blank lines are
//!   skipped anywhere.
//! - The first non-blank line is the header. Its delimiter is detected: the most frequent of
//!   `,`, `;` and tab outside quotes; if none occurs, runs of spaces separate the fields. Fields
//!   may be quoted with `"` (a doubled `""` is a quote); a quoted field cannot span lines.
//! - Coordinate columns are found by name, case-insensitively, in this order of preference:
//!   `x`/`y`, `xloc`/`yloc`, `lon`/`lat`, `long`/`lat`, `lng`/`lat`, `longitude`/`latitude`,
//!   `easting`/`northing`; a `z` (or `zloc`, with `x`/`xloc`) column makes the points 3D.
//!   A header whose fields are all numbers is taken as data of a header-less file with the
//!   columns `x, y[, z], c3, c4, …` (as in [`super::xyz`]).
//! - Every other column whose cells are numbers becomes a [`Column`] with its header name.
//!   Empty cells and `NA`, `N/A`, `NaN`, `null` (any case) are missing values, read as NaN —
//!   allowed in value columns only; a missing or non-finite coordinate is an error naming the
//!   line. A column's kind is fixed by its first non-missing cell: **text columns (e.g. a
//!   land-use or rock code) are dropped** (they carry no number, and inventing codes would
//!   invent an order); a later non-number in a numeric column is an error naming the line.
//!   Numbers use `.` as decimal point (a decimal comma is read as text).
//!
//! # Polygons ([`read_polygon`])
//! Rows are vertices in order. Optional integer columns (case-insensitive names):
//! - `component`: rows with the same value (in order of first appearance) form one shape;
//! - `closed`: per component, `0` → an open [`Polyline`], anything else → a [`Polygon`];
//!   without the column every shape is a polygon (a polygon file);
//! - `ring`: inside a polygon, rows with the same value form one ring (first ring = outer
//!   boundary, later rings = holes);
//! - `order`: vertices of a component are sorted by it (stable) before grouping.
//!
//! A ring whose last vertex repeats its first has the repeat dropped; a ring needs at least 3
//! vertices after that, an open polyline at least 2 (errors name the line).
//!
//! # Writing
//! [`write_points`]: header `x,y[,z],<column names>` and one row per point, numbers with Rust's
//! shortest round-trip formatting, NaN as an empty cell. [`write_polygon`]: a single polygon is
//! written as `x,y` rows (plus a `ring` column when it has holes), closing vertex **not**
//! repeated; anything else as `component,closed,ring,x,y`. Limitation: a closed [`Polyline`]
//! is written with `closed = 1` and therefore reads back as a one-ring [`Polygon`].
//! [`write_boundary_2d`]: a boundary polygon through input points as `index,x,y` rows in
//! boundary order.
//!
//! Complexity: linear in the file size (plus a stable sort when `order` is present).

use crate::boundary::Boundary2;
use crate::geom::Point2;
use crate::mesh::{Column, PointSet, Polygon, Polyline, Shapes2};
use crate::{Error, Result};
use std::borrow::Cow;
use std::io::Write;

/// The input as UTF-8 text without BOM; invalid UTF-8 is an error naming its line.
pub(crate) fn text(bytes: &[u8]) -> Result<&str> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let line = bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            Err(Error::at_line(line as u64, "text is not valid UTF-8"))
        }
    }
}

/// Lines with their 1-based numbers, `\r` stripped.
pub(crate) fn numbered_lines(s: &str) -> impl Iterator<Item = (u64, &str)> {
    s.split('\n')
        .enumerate()
        .map(|(i, l)| (i as u64 + 1, l.strip_suffix('\r').unwrap_or(l)))
}

/// True for the spellings of a missing value.
pub(crate) fn is_missing(cell: &str) -> bool {
    cell.is_empty()
        || cell.eq_ignore_ascii_case("na")
        || cell.eq_ignore_ascii_case("n/a")
        || cell.eq_ignore_ascii_case("nan")
        || cell.eq_ignore_ascii_case("null")
}

#[derive(Clone, Copy, PartialEq)]
enum Delim {
    Char(char),
    Spaces,
}

fn detect_delim(header: &str) -> Delim {
    let (mut c, mut s, mut t, mut inq) = (0, 0, 0, false);
    for ch in header.chars() {
        match ch {
            '"' => inq = !inq,
            ',' if !inq => c += 1,
            ';' if !inq => s += 1,
            '\t' if !inq => t += 1,
            _ => {}
        }
    }
    if c == 0 && s == 0 && t == 0 {
        Delim::Spaces
    } else if c >= s && c >= t {
        Delim::Char(',')
    } else if s >= t {
        Delim::Char(';')
    } else {
        Delim::Char('\t')
    }
}

/// Splits one line into trimmed, unquoted fields.
fn split<'a>(line: &'a str, delim: Delim, lineno: u64, out: &mut Vec<Cow<'a, str>>) -> Result<()> {
    out.clear();
    let d = match delim {
        Delim::Spaces => {
            out.extend(
                line.split_whitespace()
                    .map(|f| Cow::Borrowed(unquote_simple(f))),
            );
            return Ok(());
        }
        Delim::Char(d) => d,
    };
    if !line.contains('"') {
        out.extend(line.split(d).map(|f| Cow::Borrowed(f.trim())));
        return Ok(());
    }
    let mut rest = line;
    loop {
        let t = rest.trim_start_matches([' ', '\t'].as_slice());
        if let Some(q) = t.strip_prefix('"') {
            let mut s = String::new();
            let mut it = q.char_indices();
            let mut end = None;
            while let Some((i, ch)) = it.next() {
                if ch == '"' {
                    if q[i + 1..].starts_with('"') {
                        s.push('"');
                        it.next();
                    } else {
                        end = Some(i + 1);
                        break;
                    }
                } else {
                    s.push(ch);
                }
            }
            let end = end.ok_or_else(|| {
                Error::at_line(
                    lineno,
                    "unterminated quoted field (fields cannot span lines)",
                )
            })?;
            out.push(Cow::Owned(s));
            let after = q[end..].trim_start_matches([' ', '\t'].as_slice());
            if after.is_empty() {
                return Ok(());
            }
            match after.strip_prefix(d) {
                Some(r) => rest = r,
                None => {
                    return Err(Error::at_line(
                        lineno,
                        "unexpected text after a closing quote",
                    ))
                }
            }
        } else {
            match t.find(d) {
                Some(i) => {
                    out.push(Cow::Borrowed(t[..i].trim()));
                    rest = &t[i + d.len_utf8()..];
                }
                None => {
                    out.push(Cow::Borrowed(t.trim()));
                    return Ok(());
                }
            }
        }
    }
}

fn unquote_simple(f: &str) -> &str {
    f.strip_prefix('"')
        .and_then(|f| f.strip_suffix('"'))
        .unwrap_or(f)
}

enum ColData {
    /// No non-missing cell yet: count of missing cells so far.
    Pending(usize),
    Num(Vec<f64>),
    /// Text column (dropped); line of its first text cell.
    Text(u64),
}

/// A parsed CSV table: numeric columns kept, text columns marked.
struct Table {
    names: Vec<String>,
    cols: Vec<ColData>,
    rows: usize,
    lines: Vec<u64>,
}

impl Table {
    fn index(&self, names: &[&str]) -> Option<usize> {
        names.iter().find_map(|n| {
            self.names
                .iter()
                .position(|h| h.trim().eq_ignore_ascii_case(n))
        })
    }

    /// Values of a column that must be numeric and complete (coordinates, ids).
    fn required(&self, c: usize, what: &str) -> Result<Vec<f64>> {
        let name = &self.names[c];
        match &self.cols[c] {
            ColData::Text(line) => Err(Error::at_line(
                *line,
                format!("{what} column '{name}' holds text"),
            )),
            ColData::Pending(_) => Err(Error::at_line(
                self.lines.first().copied().unwrap_or(1),
                format!("{what} column '{name}' has no values"),
            )),
            ColData::Num(v) => {
                if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                    return Err(Error::at_line(
                        self.lines[i],
                        format!("{what} '{name}' is missing or not finite"),
                    ));
                }
                Ok(v.clone())
            }
        }
    }
}

fn parse_table(bytes: &[u8]) -> Result<Table> {
    let bytes = &*super::unify_line_ends(bytes);
    let s = text(bytes)?;
    let mut lines = numbered_lines(s).filter(|(_, l)| !l.trim().is_empty());
    let (hline, header) = lines
        .next()
        .ok_or_else(|| Error::format("empty CSV file (no header line)"))?;
    let delim = detect_delim(header);
    let mut fields = Vec::new();
    split(header, delim, hline, &mut fields)?;
    let headerless = fields.iter().all(|f| f.parse::<f64>().is_ok());
    let ncol = fields.len();
    let names: Vec<String> = if headerless {
        (0..ncol)
            .map(|i| match i {
                0 => "x".to_string(),
                1 => "y".to_string(),
                2 => "z".to_string(),
                _ => format!("c{i}"),
            })
            .collect()
    } else {
        fields.iter().map(|f| f.to_string()).collect()
    };
    let mut t = Table {
        names,
        cols: (0..ncol).map(|_| ColData::Pending(0)).collect(),
        rows: 0,
        lines: Vec::new(),
    };
    let first = if headerless {
        Some((hline, header))
    } else {
        None
    };
    for (no, line) in first.into_iter().chain(lines) {
        split(line, delim, no, &mut fields)?;
        if fields.len() != ncol {
            return Err(Error::at_line(
                no,
                format!("{} fields, the header has {ncol}", fields.len()),
            ));
        }
        for (col, cell) in t.cols.iter_mut().zip(&fields) {
            let cell: &str = cell;
            let value = if is_missing(cell) {
                None
            } else {
                Some(cell.parse::<f64>())
            };
            match (col, value) {
                (ColData::Text(_), _) => {}
                (ColData::Pending(n), None) => *n += 1,
                (ColData::Num(v), None) => v.push(f64::NAN),
                (col @ ColData::Pending(_), Some(Ok(x))) => {
                    let n = match col {
                        ColData::Pending(n) => *n,
                        _ => 0,
                    };
                    let mut v = vec![f64::NAN; n];
                    v.push(x);
                    *col = ColData::Num(v);
                }
                (ColData::Num(v), Some(Ok(x))) => v.push(x),
                (col @ ColData::Pending(_), Some(Err(_))) => *col = ColData::Text(no),
                (ColData::Num(_), Some(Err(_))) => {
                    return Err(Error::at_line(
                        no,
                        format!("'{cell}' is not a number, but earlier rows of its column are"),
                    ));
                }
            }
        }
        t.rows += 1;
        t.lines.push(no);
    }
    for col in &mut t.cols {
        if let ColData::Pending(n) = col {
            *col = ColData::Num(vec![f64::NAN; *n]);
        }
    }
    Ok(t)
}

/// Indices of the x, y and optional z columns.
fn coord_columns(t: &Table) -> Result<(usize, usize, Option<usize>)> {
    const PAIRS: [(&str, &str, &str); 7] = [
        ("x", "y", "z"),
        ("xloc", "yloc", "zloc"),
        ("lon", "lat", ""),
        ("long", "lat", ""),
        ("lng", "lat", ""),
        ("longitude", "latitude", ""),
        ("easting", "northing", ""),
    ];
    for (xn, yn, zn) in PAIRS {
        if let (Some(x), Some(y)) = (t.index(&[xn]), t.index(&[yn])) {
            let z = if zn.is_empty() { None } else { t.index(&[zn]) };
            return Ok((x, y, z));
        }
    }
    Err(Error::at_line(
        1,
        format!(
            "the header must name x and y columns (found: {})",
            t.names.join(", ")
        ),
    ))
}

/// Points with header; columns other than x, y, z become named value columns.
pub fn read_points(bytes: &[u8]) -> Result<PointSet> {
    let t = parse_table(bytes)?;
    let (xi, yi, zi) = coord_columns(&t)?;
    let xs = t.required(xi, "coordinate")?;
    let ys = t.required(yi, "coordinate")?;
    let zs = match zi {
        Some(z) => Some(t.required(z, "coordinate")?),
        None => None,
    };
    let dim = if zs.is_some() { 3 } else { 2 };
    let mut coords = Vec::with_capacity(t.rows * dim);
    for i in 0..t.rows {
        coords.push(xs[i]);
        coords.push(ys[i]);
        if let Some(z) = &zs {
            coords.push(z[i]);
        }
    }
    let mut columns = Vec::new();
    for (c, (name, data)) in t.names.iter().zip(t.cols).enumerate() {
        if c == xi || c == yi || Some(c) == zi {
            continue;
        }
        if let ColData::Num(values) = data {
            columns.push(Column {
                name: name.clone(),
                values,
            });
        }
    }
    Ok(PointSet {
        dim,
        coords,
        columns,
    })
}

fn quote(name: &str) -> Cow<'_, str> {
    if name.is_empty()
        || name
            .chars()
            .any(|c| matches!(c, ',' | ';' | '"' | '\t' | '\n' | '\r' | ' '))
    {
        Cow::Owned(format!("\"{}\"", name.replace('"', "\"\"")))
    } else {
        Cow::Borrowed(name)
    }
}

fn e(err: std::io::Error) -> Error {
    super::werr(err)
}

/// Writes points with a header.
pub fn write_points(w: &mut dyn Write, pts: &PointSet) -> Result<()> {
    pts.validate()?;
    let mut header = vec!["x", "y"];
    if pts.dim == 3 {
        header.push("z");
    }
    let mut line: Vec<Cow<str>> = header.into_iter().map(Cow::Borrowed).collect();
    line.extend(pts.columns.iter().map(|c| quote(&c.name)));
    writeln!(w, "{}", line.join(",")).map_err(e)?;
    let mut row = String::new();
    for i in 0..pts.len() {
        row.clear();
        for (k, c) in pts.point(i).iter().enumerate() {
            if k > 0 {
                row.push(',');
            }
            row.push_str(&format!("{c}"));
        }
        for c in &pts.columns {
            row.push(',');
            let v = c.values[i];
            if !v.is_nan() {
                row.push_str(&format!("{v}"));
            }
        }
        writeln!(w, "{row}").map_err(e)?;
    }
    Ok(())
}

/// Integer ids of a grouping column.
fn ids(t: &Table, c: usize, what: &str) -> Result<Vec<i64>> {
    let v = t.required(c, what)?;
    v.iter()
        .enumerate()
        .map(|(i, &x)| {
            if x.fract() == 0.0 && x.abs() < 9.0e15 {
                Ok(x as i64)
            } else {
                Err(Error::at_line(
                    t.lines[i],
                    format!("{what} '{x}' is not an integer"),
                ))
            }
        })
        .collect()
}

/// Groups indices by key in order of first appearance.
fn group_by(idx: &[usize], key: &[i64]) -> Vec<(i64, Vec<usize>)> {
    let mut groups: Vec<(i64, Vec<usize>)> = Vec::new();
    let mut pos = std::collections::HashMap::new();
    for &i in idx {
        let k = key[i];
        let g = *pos.entry(k).or_insert_with(|| {
            groups.push((k, Vec::new()));
            groups.len() - 1
        });
        groups[g].1.push(i);
    }
    groups
}

fn drop_closing_repeat(mut ring: Vec<Point2>) -> Vec<Point2> {
    if ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    ring
}

/// A polygon as ordered vertices (a repeated first vertex at the end closes the ring).
pub fn read_polygon(bytes: &[u8]) -> Result<Shapes2> {
    let t = parse_table(bytes)?;
    if t.rows == 0 {
        return Err(Error::format("no vertices"));
    }
    let (xi, yi, _) = coord_columns(&t)?;
    let xs = t.required(xi, "coordinate")?;
    let ys = t.required(yi, "coordinate")?;
    let opt = |name: &str| -> Result<Option<Vec<i64>>> {
        match t.index(&[name]) {
            Some(c) => Ok(Some(ids(&t, c, name)?)),
            None => Ok(None),
        }
    };
    let comp = opt("component")?;
    let closed = opt("closed")?;
    let ring = opt("ring")?;
    let order = opt("order")?;
    let all: Vec<usize> = (0..t.rows).collect();
    let comps = match &comp {
        Some(c) => group_by(&all, c),
        None => vec![(0, all)],
    };
    let mut out = Shapes2::default();
    for (_, mut rows) in comps {
        if let Some(o) = &order {
            rows.sort_by_key(|&i| o[i]);
        }
        let is_closed = match &closed {
            None => true,
            Some(c) => {
                let v = c[rows[0]];
                if let Some(&bad) = rows.iter().find(|&&i| (c[i] != 0) != (v != 0)) {
                    return Err(Error::at_line(
                        t.lines[bad],
                        "the 'closed' value changes inside one component",
                    ));
                }
                v != 0
            }
        };
        let pt = |i: usize| Point2::new(xs[i], ys[i]);
        if is_closed {
            let rings = match &ring {
                Some(r) => group_by(&rows, r),
                None => vec![(0, rows)],
            };
            let mut poly = Polygon::default();
            for (_, r) in rings {
                let first_line = t.lines[r[0]];
                let ring = drop_closing_repeat(r.into_iter().map(pt).collect());
                if ring.len() < 3 {
                    return Err(Error::at_line(
                        first_line,
                        format!(
                            "the ring starting here has {} vertices; a polygon ring needs 3",
                            ring.len()
                        ),
                    ));
                }
                poly.rings.push(ring);
            }
            out.polygons.push(poly);
        } else {
            if let Some(r) = &ring {
                if let Some(&bad) = rows.iter().find(|&&i| r[i] != r[rows[0]]) {
                    return Err(Error::at_line(
                        t.lines[bad],
                        "an open polyline (closed = 0) cannot have several rings",
                    ));
                }
            }
            if rows.len() < 2 {
                return Err(Error::at_line(
                    t.lines[rows[0]],
                    "an open polyline needs at least 2 vertices",
                ));
            }
            out.polylines.push(Polyline {
                points: rows.into_iter().map(pt).collect(),
                closed: false,
            });
        }
    }
    Ok(out)
}

fn check_finite(p: &Point2) -> Result<()> {
    if p.x.is_finite() && p.y.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid("cannot write a non-finite coordinate"))
    }
}

/// Writes the rings/polylines as ordered vertices.
pub fn write_polygon(w: &mut dyn Write, shapes: &Shapes2) -> Result<()> {
    let simple = shapes.polylines.is_empty() && shapes.polygons.len() == 1;
    if simple {
        let poly = &shapes.polygons[0];
        let rings = poly.rings.len() > 1;
        writeln!(w, "{}", if rings { "x,y,ring" } else { "x,y" }).map_err(e)?;
        for (r, ring) in poly.rings.iter().enumerate() {
            for p in ring {
                check_finite(p)?;
                if rings {
                    writeln!(w, "{},{},{r}", p.x, p.y).map_err(e)?;
                } else {
                    writeln!(w, "{},{}", p.x, p.y).map_err(e)?;
                }
            }
        }
        return Ok(());
    }
    writeln!(w, "component,closed,ring,x,y").map_err(e)?;
    let mut comp = 0usize;
    for poly in &shapes.polygons {
        for (r, ring) in poly.rings.iter().enumerate() {
            for p in ring {
                check_finite(p)?;
                writeln!(w, "{comp},1,{r},{},{}", p.x, p.y).map_err(e)?;
            }
        }
        comp += 1;
    }
    for line in &shapes.polylines {
        for p in &line.points {
            check_finite(p)?;
            writeln!(w, "{comp},{},0,{},{}", line.closed as u8, p.x, p.y).map_err(e)?;
        }
        comp += 1;
    }
    Ok(())
}

/// Writes a 2D boundary polygon through `points` as `index,x,y` rows (the input index and the
/// coordinates of each polygon vertex, in boundary order; the first vertex is not repeated).
///
/// ```
/// use morpho::boundary::{boundary_2d, Options2};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// let b = boundary_2d(&p, &Options2::default()).unwrap();
/// let mut out = Vec::new();
/// morpho::io::csv::write_boundary_2d(&mut out, &p, &b).unwrap();
/// assert_eq!(String::from_utf8(out).unwrap(), "index,x,y\n0,0,0\n1,1,0\n2,0,1\n");
/// ```
pub fn write_boundary_2d(w: &mut dyn Write, points: &[Point2], b: &Boundary2) -> Result<()> {
    writeln!(w, "index,x,y").map_err(e)?;
    for &i in &b.polygon {
        let p = points[i as usize];
        writeln!(w, "{i},{},{}", p.x, p.y).map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_with_columns_bom_crlf_and_missing() {
        let s = "\u{feff}\"X\";Y;Z;zinc;soil\r\n1;2;3;4.5;Ah\r\n5;6;7;;B\r\n\r\n\r\n";
        let p = read_points(s.as_bytes()).unwrap();
        assert_eq!(p.dim, 3);
        assert_eq!(p.coords, vec![1., 2., 3., 5., 6., 7.]);
        assert_eq!(p.columns.len(), 1);
        assert_eq!(p.columns[0].name, "zinc");
        assert_eq!(p.columns[0].values[0], 4.5);
        assert!(p.columns[0].values[1].is_nan());
    }

    #[test]
    fn coordinate_errors_name_the_line() {
        let err = read_points(b"x,y\n1,2\n\n3,NA\n").unwrap_err().to_string();
        assert!(err.contains("line 4"), "{err}");
        let err = read_points(b"x,y\n1,2\n3,nan\n").unwrap_err().to_string();
        assert!(err.contains("line 3"), "{err}");
        let err = read_points(b"x,y\n1,2\n3\n").unwrap_err().to_string();
        assert!(err.contains("line 3"), "{err}");
        let err = read_points(b"x,y,v\n1,2,3\n3,4,abc\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("line 3"), "{err}");
        assert!(read_points(b"").is_err());
        assert!(read_points(b"a,b\n1,2\n").is_err());
        let err = read_points(b"x,y\n1,2\n\xff,3\n").unwrap_err().to_string();
        assert!(err.contains("line 3"), "{err}");
    }

    #[test]
    fn quoted_fields_and_headerless() {
        let p = read_points(b"\"x\",\"y\",\"a \"\"b\"\"\"\n1,2,\"3\"\n").unwrap();
        assert_eq!(p.columns[0].name, "a \"b\"");
        assert_eq!(p.columns[0].values, vec![3.0]);
        let p = read_points(b"1,2\n3,4\n").unwrap();
        assert_eq!(p.coords, vec![1., 2., 3., 4.]);
        let p = read_points(b"x\ty\n1\t2\n").unwrap();
        assert_eq!(p.coords, vec![1., 2.]);
    }

    #[test]
    fn polygon_components_rings_and_closing_repeat() {
        let s = "x,y\n0,0\n1,0\n1,1\n0,0\n";
        let sh = read_polygon(s.as_bytes()).unwrap();
        assert_eq!(sh.polygons.len(), 1);
        assert_eq!(sh.polygons[0].rings[0].len(), 3);
        let s =
            "component,closed,order,x,y\n0,0,1,1,0\n0,0,0,0,0\n1,1,0,5,5\n1,1,1,6,5\n1,1,2,6,6\n";
        let sh = read_polygon(s.as_bytes()).unwrap();
        assert_eq!(sh.polylines.len(), 1);
        assert_eq!(sh.polylines[0].points[0], Point2::new(0., 0.));
        assert_eq!(sh.polygons.len(), 1);
        let err = read_polygon(b"component,closed,x,y\n0,0,1,1\n0,1,2,2\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("line 3"), "{err}");
    }
}

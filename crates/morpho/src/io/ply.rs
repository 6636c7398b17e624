//! PLY (Stanford polygon file format): ASCII, binary little and big endian.
//!
//! Size (over 800 lines): the house rule is one file per format; PLY has three encodings (ASCII,
//! binary LE/BE), user-defined properties and list types, and a writer for each result type, all
//! sharing one header model; about 250 of the lines are its tests.
//!
//! Reading follows the format description of Turk (1994): a text header — `ply`,
//! `format ascii|binary_little_endian|binary_big_endian 1.0`, `comment`/`obj_info` lines,
//! `element name count` each followed by its `property type name` and
//! `property list count_type item_type name` lines, `end_header` — then the elements' records
//! in header order. All scalar types (`char uchar short ushort int uint float double` and
//! `int8 … float64`) are accepted anywhere, for list counts and items too.
//!
//! * `vertex`: `x y z` (any numeric type) are the positions, `nx ny nz` (all three) the normals,
//!   every other scalar property is kept as a [`Property`] with its [`ScalarKind`]; vertex list
//!   properties are skipped.
//! * `face`: the list `vertex_indices` (or `vertex_index`) gives the polygon, fan-triangulated
//!   (`v0 v(k) v(k+1)`); a face with fewer than 3 corners is an error. Other scalar face
//!   properties are kept, repeated for each triangle of a polygon.
//! * `tristrips` (as in the Cyberware/Stanford scans): `-1`-separated triangle strips in the
//!   list `vertex_indices`, expanded with alternating orientation, degenerate joints dropped.
//! * Any other element (edges, materials, …) is skipped, parsing its lists in binary files.
//!
//! * `tetra` ([`read_tets`] only): the list `vertex_indices` (or `vertex_index`) of exactly 4
//!   vertices per record, as [`write_tets`] writes it.
//!
//! A vertex element without `z` gives `z = 0` (planar data; [`read_points`] makes it 2D).
//!
//! Untrusted input: before an element is allocated, its count is checked against what is left
//! of the file — in binary `count × minimum record size ≤ bytes left`, in ASCII (one record per
//! line) `count ≤ lines left` — so a header claiming 10^12 vertices fails at once. A missing
//! `end_header`, truncated data (the error names the byte offset, or the line in ASCII), face
//! indices out of range (naming the face), non-finite coordinates (naming the vertex) and
//! non-UTF-8 header or ASCII text are errors. Data after the last element is ignored.
//! Windows line endings are accepted. Time and extra memory are linear in the file size.
//!
//! Writing: `x y z` (and `nx ny nz`) as `double` so that values round-trip exactly, extra
//! properties with their own kinds (values must be representable in them), faces as
//! `list uchar int vertex_indices`. ASCII numbers use the shortest round-trip representation.
//! Besides meshes ([`write_mesh`]) and points ([`write_points`]): tetrahedral meshes with a
//! `tetra` element ([`write_tets`]) and geometric graphs with an `edge` element
//! ([`write_graph`]).
use super::obj::{clip, count_lines, tokens, Lines, Tokens, F32, F64};
use super::Encoding;
use crate::geom::{Point3, Vector3};
use crate::graphs::Graph;
use crate::mesh::{Column, PointSet, Property, ScalarKind, TetMesh, TriMesh};
use crate::{Error, Result};
use std::io::Write;

// ---------------------------------------------------------------------------------------------
// Header

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Fmt {
    Ascii,
    Le,
    Be,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PropType {
    Scalar(ScalarKind),
    List(ScalarKind, ScalarKind),
}

#[derive(Debug, Clone)]
struct PropDef {
    name: String,
    ty: PropType,
}

#[derive(Debug, Clone)]
struct ElementDef {
    name: String,
    count: u64,
    props: Vec<PropDef>,
}

impl ElementDef {
    /// Smallest possible size of one binary record (lists may be empty).
    fn min_size(&self) -> u64 {
        self.props
            .iter()
            .map(|p| match p.ty {
                PropType::Scalar(k) | PropType::List(k, _) => size(k) as u64,
            })
            .sum()
    }
    fn scalar(&self, name: &str) -> Option<(usize, ScalarKind)> {
        self.props.iter().enumerate().find_map(|(i, p)| match p.ty {
            PropType::Scalar(k) if p.name == name => Some((i, k)),
            _ => None,
        })
    }
}

#[derive(Debug)]
struct Header {
    fmt: Fmt,
    elements: Vec<ElementDef>,
    /// Byte offset of the first data byte.
    data_start: usize,
    /// Number of header lines (the data of an ASCII file starts on the next line).
    lines: u64,
}

fn size(k: ScalarKind) -> usize {
    match k {
        ScalarKind::I8 | ScalarKind::U8 => 1,
        ScalarKind::I16 | ScalarKind::U16 => 2,
        ScalarKind::I32 | ScalarKind::U32 | ScalarKind::F32 => 4,
        ScalarKind::F64 => 8,
    }
}

fn parse_kind(s: &str) -> Option<ScalarKind> {
    Some(match s {
        "char" | "int8" => ScalarKind::I8,
        "uchar" | "uint8" => ScalarKind::U8,
        "short" | "int16" => ScalarKind::I16,
        "ushort" | "uint16" => ScalarKind::U16,
        "int" | "int32" => ScalarKind::I32,
        "uint" | "uint32" => ScalarKind::U32,
        "float" | "float32" => ScalarKind::F32,
        "double" | "float64" => ScalarKind::F64,
        _ => return None,
    })
}

fn kind_name(k: ScalarKind) -> &'static str {
    match k {
        ScalarKind::I8 => "char",
        ScalarKind::U8 => "uchar",
        ScalarKind::I16 => "short",
        ScalarKind::U16 => "ushort",
        ScalarKind::I32 => "int",
        ScalarKind::U32 => "uint",
        ScalarKind::F32 => "float",
        ScalarKind::F64 => "double",
    }
}

/// True when `v` can be stored in `k` without changing it (floats: without overflowing).
fn fits(k: ScalarKind, v: f64) -> bool {
    let int = |lo: f64, hi: f64| v.fract() == 0.0 && v >= lo && v <= hi;
    match k {
        ScalarKind::I8 => int(i8::MIN as f64, i8::MAX as f64),
        ScalarKind::U8 => int(0.0, u8::MAX as f64),
        ScalarKind::I16 => int(i16::MIN as f64, i16::MAX as f64),
        ScalarKind::U16 => int(0.0, u16::MAX as f64),
        ScalarKind::I32 => int(i32::MIN as f64, i32::MAX as f64),
        ScalarKind::U32 => int(0.0, u32::MAX as f64),
        ScalarKind::F32 => !v.is_finite() || (v as f32).is_finite(),
        ScalarKind::F64 => true,
    }
}

fn parse_header(bytes: &[u8]) -> Result<Header> {
    if !bytes.starts_with(b"ply") {
        return Err(Error::at_line(
            1,
            "not a PLY file: it does not start with 'ply'",
        ));
    }
    let mut pos = 0usize;
    let mut line = 0u64;
    let mut fmt = None;
    let mut elements: Vec<ElementDef> = Vec::new();
    loop {
        if pos >= bytes.len() {
            return Err(Error::at_line(line, "PLY header has no 'end_header' line"));
        }
        let rest = &bytes[pos..];
        // a header line ends at LF, CRLF or a bare CR (old Mac text)
        let (raw, next) = match rest.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(e) if rest[e] == b'\r' && rest.get(e + 1) == Some(&b'\n') => {
                (&rest[..e], pos + e + 2)
            }
            Some(e) => (&rest[..e], pos + e + 1),
            None => (rest, bytes.len()),
        };
        line += 1;
        pos = next;
        let s = std::str::from_utf8(raw)
            .map_err(|_| Error::at_line(line, "PLY header line is not valid UTF-8 text"))?;
        let s = s.strip_suffix('\r').unwrap_or(s);
        let mut t = tokens(s);
        let Some(kw) = t.next() else { continue };
        match kw {
            "ply" if line == 1 => {}
            "comment" | "obj_info" => {}
            "format" => {
                let f = match t.next() {
                    Some("ascii") => Fmt::Ascii,
                    Some("binary_little_endian") => Fmt::Le,
                    Some("binary_big_endian") => Fmt::Be,
                    other => {
                        return Err(Error::at_line(
                            line,
                            format!("unknown PLY format '{}'", clip(other.unwrap_or(""))),
                        ))
                    }
                };
                match t.next() {
                    Some(v) if v.starts_with('1') => {}
                    v => {
                        return Err(Error::unsupported(format!(
                            "PLY version '{}' (only 1.0 is supported)",
                            clip(v.unwrap_or(""))
                        )))
                    }
                }
                if fmt.replace(f).is_some() {
                    return Err(Error::at_line(line, "second 'format' line"));
                }
            }
            "element" => {
                let (Some(name), Some(count)) = (t.next(), t.next()) else {
                    return Err(Error::at_line(line, "expected 'element <name> <count>'"));
                };
                let count: u64 = count.parse().map_err(|_| {
                    Error::at_line(
                        line,
                        format!(
                            "element count '{}' is not a non-negative integer",
                            clip(count)
                        ),
                    )
                })?;
                if elements.iter().any(|e| e.name == name) {
                    return Err(Error::at_line(
                        line,
                        format!("element '{}' is declared twice", clip(name)),
                    ));
                }
                elements.push(ElementDef {
                    name: name.to_string(),
                    count,
                    props: Vec::new(),
                });
            }
            "property" => {
                let el = elements
                    .last_mut()
                    .ok_or_else(|| Error::at_line(line, "'property' before the first 'element'"))?;
                let bad_type =
                    |s: &str| Error::at_line(line, format!("unknown property type '{}'", clip(s)));
                let ty = t.next().unwrap_or("");
                let ty = if ty == "list" {
                    let c = t.next().unwrap_or("");
                    let i = t.next().unwrap_or("");
                    PropType::List(
                        parse_kind(c).ok_or_else(|| bad_type(c))?,
                        parse_kind(i).ok_or_else(|| bad_type(i))?,
                    )
                } else {
                    PropType::Scalar(parse_kind(ty).ok_or_else(|| bad_type(ty))?)
                };
                let name = t
                    .next()
                    .ok_or_else(|| Error::at_line(line, "property without a name"))?;
                if el.props.iter().any(|p| p.name == name) {
                    return Err(Error::at_line(
                        line,
                        format!(
                            "property '{}' appears twice in element '{}'",
                            clip(name),
                            el.name
                        ),
                    ));
                }
                el.props.push(PropDef {
                    name: name.to_string(),
                    ty,
                });
            }
            "end_header" => break,
            other => {
                return Err(Error::at_line(
                    line,
                    format!("unexpected PLY header line starting with '{}'", clip(other)),
                ))
            }
        }
    }
    let fmt = fmt.ok_or_else(|| Error::format("PLY header has no 'format' line"))?;
    Ok(Header {
        fmt,
        elements,
        data_start: pos,
        lines: line,
    })
}

// ---------------------------------------------------------------------------------------------
// Record sources: ASCII lines or binary bytes

/// Reads the values of one element's records, one record at a time.
trait Source {
    /// Starts reading element `el`: checks that `el.count` records can still be in the file
    /// (before the caller allocates anything).
    fn start(&mut self, el: &ElementDef) -> Result<()>;
    /// Starts record `i` of the current element.
    fn begin(&mut self, i: u64) -> Result<()>;
    /// Binary sources: the next `len` bytes (which [`Source::start`] checked to be present),
    /// their offset in the file and whether they are big endian; the source moves past them.
    fn fixed(&mut self, len: u64) -> Option<(&[u8], usize, bool)>;
    /// Binary sources: all bytes left, their offset in the file and whether they are big
    /// endian (the source does not move; use [`Source::fixed`] to move past them).
    fn rest(&self) -> Option<(&[u8], usize, bool)>;
    /// The next scalar of the current record.
    fn scalar(&mut self, k: ScalarKind) -> Result<f64>;
    /// The next list length of the current record (checked against what is left).
    fn list_len(&mut self, count: ScalarKind, item: ScalarKind) -> Result<u64>;
    /// Ends the current record.
    fn end(&mut self) -> Result<()>;
    /// An error located at the current record.
    fn err(&self, msg: String) -> Error;
    /// Skips all records of `el`.
    fn skip_element(&mut self, el: &ElementDef) -> Result<()>;
}

struct Ascii<'a> {
    lines: Lines<'a>,
    /// Number of the line of the current record (the last header line before the first).
    line: u64,
    last_line: u64,
    toks: Tokens<'a>,
    el: String,
    rec: u64,
}

impl<'a> Ascii<'a> {
    fn new(text: &'a str, header_lines: u64) -> Self {
        Ascii {
            lines: Lines::new(text, header_lines + 1),
            line: header_lines,
            last_line: header_lines + count_lines(text),
            toks: tokens(""),
            el: String::new(),
            rec: 0,
        }
    }
    /// The next non-blank line, or `None` at the end.
    fn next_line(&mut self) -> Option<&'a str> {
        for (n, l) in self.lines.by_ref() {
            self.line = n;
            if tokens(l).next().is_some() {
                return Some(l);
            }
        }
        None
    }
    fn truncated(&self) -> Error {
        Error::at_line(
            self.last_line,
            format!(
                "file ends before {} {} (data is truncated)",
                self.el, self.rec
            ),
        )
    }
}

fn parse_ascii(tok: &str, k: ScalarKind) -> Option<f64> {
    match k {
        ScalarKind::F32 => tok.parse::<f32>().ok().map(f64::from),
        ScalarKind::F64 => tok.parse::<f64>().ok(),
        _ => {
            let v = match tok.parse::<i64>() {
                Ok(v) => v as f64,
                Err(_) => tok.parse::<f64>().ok()?,
            };
            fits(k, v).then_some(v)
        }
    }
}

impl Source for Ascii<'_> {
    fn start(&mut self, el: &ElementDef) -> Result<()> {
        self.el.clone_from(&el.name);
        let left = self.last_line - self.line;
        if !el.props.is_empty() && el.count > left {
            return Err(Error::at_line(
                self.line + 1,
                format!(
                    "header claims {} {} records, but only {left} line(s) are left",
                    el.count, el.name
                ),
            ));
        }
        Ok(())
    }
    fn begin(&mut self, i: u64) -> Result<()> {
        self.rec = i;
        match self.next_line() {
            Some(l) => {
                self.toks = tokens(l);
                Ok(())
            }
            None => Err(self.truncated()),
        }
    }
    fn fixed(&mut self, _len: u64) -> Option<(&[u8], usize, bool)> {
        None
    }
    fn rest(&self) -> Option<(&[u8], usize, bool)> {
        None
    }
    fn scalar(&mut self, k: ScalarKind) -> Result<f64> {
        let tok = self
            .toks
            .next()
            .ok_or_else(|| self.err("too few values on the line".into()))?;
        parse_ascii(tok, k).ok_or_else(|| {
            self.err(format!(
                "'{}' is not a valid {} value",
                clip(tok),
                kind_name(k)
            ))
        })
    }
    fn list_len(&mut self, count: ScalarKind, _item: ScalarKind) -> Result<u64> {
        let n = self.scalar(count)?;
        if n < 0.0 || n.fract() != 0.0 {
            return Err(self.err(format!("bad list length {n}")));
        }
        Ok(n as u64)
    }
    fn end(&mut self) -> Result<()> {
        match self.toks.next() {
            Some(t) => Err(self.err(format!("unexpected extra value '{}' on the line", clip(t)))),
            None => Ok(()),
        }
    }
    fn err(&self, msg: String) -> Error {
        Error::at_line(self.line, format!("{} {}: {msg}", self.el, self.rec))
    }
    fn skip_element(&mut self, el: &ElementDef) -> Result<()> {
        if el.props.is_empty() {
            return Ok(());
        }
        self.start(el)?;
        for i in 0..el.count {
            self.rec = i;
            if self.next_line().is_none() {
                return Err(self.truncated());
            }
        }
        Ok(())
    }
}

struct Binary<'a> {
    data: &'a [u8],
    pos: usize,
    big: bool,
    rec_start: usize,
    el: String,
    rec: u64,
}

#[inline]
fn decode(k: ScalarKind, b: &[u8], big: bool) -> f64 {
    macro_rules! rd {
        ($t:ty, $n:expr) => {{
            let mut a = [0u8; $n];
            a.copy_from_slice(&b[..$n]);
            (if big {
                <$t>::from_be_bytes(a)
            } else {
                <$t>::from_le_bytes(a)
            }) as f64
        }};
    }
    match k {
        ScalarKind::I8 => b[0] as i8 as f64,
        ScalarKind::U8 => b[0] as f64,
        ScalarKind::I16 => rd!(i16, 2),
        ScalarKind::U16 => rd!(u16, 2),
        ScalarKind::I32 => rd!(i32, 4),
        ScalarKind::U32 => rd!(u32, 4),
        ScalarKind::F32 => rd!(f32, 4),
        ScalarKind::F64 => rd!(f64, 8),
    }
}

impl Binary<'_> {
    fn left(&self) -> u64 {
        (self.data.len() - self.pos) as u64
    }
}

impl Source for Binary<'_> {
    fn start(&mut self, el: &ElementDef) -> Result<()> {
        self.el.clone_from(&el.name);
        let need = el.count.checked_mul(el.min_size());
        let left = self.left();
        if need.map_or(true, |n| n > left) {
            return Err(Error::at_byte(
                self.pos as u64,
                format!(
                    "header claims {} {} records of at least {} bytes, but only {left} bytes are left",
                    el.count,
                    el.name,
                    el.min_size()
                ),
            ));
        }
        Ok(())
    }
    fn begin(&mut self, i: u64) -> Result<()> {
        self.rec = i;
        self.rec_start = self.pos;
        Ok(())
    }
    fn fixed(&mut self, len: u64) -> Option<(&[u8], usize, bool)> {
        let start = self.pos;
        let end = start.checked_add(usize::try_from(len).ok()?)?;
        let block = self.data.get(start..end)?;
        self.pos = end;
        Some((block, start, self.big))
    }
    fn rest(&self) -> Option<(&[u8], usize, bool)> {
        Some((self.data.get(self.pos..)?, self.pos, self.big))
    }
    #[inline]
    fn scalar(&mut self, k: ScalarKind) -> Result<f64> {
        let n = size(k);
        match self.data.get(self.pos..self.pos + n) {
            Some(b) => {
                self.pos += n;
                Ok(decode(k, b, self.big))
            }
            None => Err(Error::at_byte(
                self.pos as u64,
                format!(
                    "file ends inside {} {} (data is truncated)",
                    self.el, self.rec
                ),
            )),
        }
    }
    fn list_len(&mut self, count: ScalarKind, item: ScalarKind) -> Result<u64> {
        let at = self.pos;
        let n = self.scalar(count)?;
        if n < 0.0 || n.fract() != 0.0 {
            return Err(Error::at_byte(
                at as u64,
                format!("{} {}: bad list length {n}", self.el, self.rec),
            ));
        }
        let n = n as u64;
        if n.checked_mul(size(item) as u64)
            .map_or(true, |b| b > self.left())
        {
            return Err(Error::at_byte(
                at as u64,
                format!(
                    "{} {}: list of {n} items runs past the end of the file (data is truncated)",
                    self.el, self.rec
                ),
            ));
        }
        Ok(n)
    }
    fn end(&mut self) -> Result<()> {
        Ok(())
    }
    fn err(&self, msg: String) -> Error {
        Error::at_byte(
            self.rec_start as u64,
            format!("{} {}: {msg}", self.el, self.rec),
        )
    }
    fn skip_element(&mut self, el: &ElementDef) -> Result<()> {
        self.start(el)?;
        if el.props.iter().all(|p| matches!(p.ty, PropType::Scalar(_))) {
            // Fixed-size records: checked by `start` to fit.
            self.pos += (el.count * el.min_size()) as usize;
            return Ok(());
        }
        for i in 0..el.count {
            self.begin(i)?;
            for p in &el.props {
                skip_prop(self, p.ty)?;
            }
        }
        Ok(())
    }
}

fn skip_prop<S: Source>(src: &mut S, ty: PropType) -> Result<()> {
    match ty {
        PropType::Scalar(k) => {
            src.scalar(k)?;
        }
        PropType::List(c, i) => {
            let n = src.list_len(c, i)?;
            for _ in 0..n {
                src.scalar(i)?;
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Element readers

/// What a vertex property is used for.
#[derive(Clone, Copy)]
enum VRole {
    /// 0..3 position, 3..6 normal.
    Slot(usize),
    Extra(usize),
    Skip,
}

struct Vertices {
    coords: Vec<[f64; 3]>,
    normals: Option<Vec<Vector3>>,
    extras: Vec<Property>,
    dim: usize,
}

fn read_vertices<S: Source>(src: &mut S, el: &ElementDef) -> Result<Vertices> {
    let x = el.scalar("x");
    let y = el.scalar("y");
    let z = el.scalar("z");
    if x.is_none() || y.is_none() {
        return Err(Error::format(format!(
            "PLY vertex element has no scalar {} property",
            if x.is_none() { "x" } else { "y" }
        )));
    }
    let normals = ["nx", "ny", "nz"].iter().all(|n| el.scalar(n).is_some());
    let mut roles = Vec::with_capacity(el.props.len());
    let mut extras = Vec::new();
    for p in &el.props {
        let role = match (p.name.as_str(), p.ty) {
            (_, PropType::List(..)) => VRole::Skip,
            ("x", _) => VRole::Slot(0),
            ("y", _) => VRole::Slot(1),
            ("z", _) => VRole::Slot(2),
            ("nx", _) if normals => VRole::Slot(3),
            ("ny", _) if normals => VRole::Slot(4),
            ("nz", _) if normals => VRole::Slot(5),
            (_, PropType::Scalar(k)) => {
                extras.push(Property {
                    name: p.name.clone(),
                    kind: k,
                    values: Vec::new(),
                });
                VRole::Extra(extras.len() - 1)
            }
        };
        roles.push(role);
    }
    src.start(el)?;
    if el.count > u32::MAX as u64 - 1 {
        return Err(Error::invalid(format!(
            "{} vertices are too many",
            el.count
        )));
    }
    let n = el.count as usize;
    let mut coords = Vec::with_capacity(n);
    let mut nrm = normals.then(|| Vec::with_capacity(n));
    for e in &mut extras {
        e.values.reserve_exact(n);
    }
    if el.props.iter().all(|p| matches!(p.ty, PropType::Scalar(_))) {
        // Fast path for binary files: fixed-size records decoded straight from the bytes.
        let rs = el.min_size() as usize;
        let mut layout = Vec::with_capacity(el.props.len());
        let mut off = 0;
        for (p, role) in el.props.iter().zip(&roles) {
            if let PropType::Scalar(k) = p.ty {
                layout.push((off, k, *role));
                off += size(k);
            }
        }
        if let Some((block, base, big)) = src.fixed(el.count * rs as u64) {
            for (i, rec) in block.chunks_exact(rs.max(1)).enumerate() {
                let mut s = [0.0f64; 6];
                for &(off, k, role) in &layout {
                    let v = decode(k, &rec[off..], big);
                    match role {
                        VRole::Slot(j) => s[j] = v,
                        VRole::Extra(j) => {
                            if let Some(e) = extras.get_mut(j) {
                                e.values.push(v);
                            }
                        }
                        VRole::Skip => {}
                    }
                }
                if !(s[0].is_finite() && s[1].is_finite() && s[2].is_finite()) {
                    return Err(Error::at_byte(
                        (base + i * rs) as u64,
                        format!("vertex {i}: non-finite coordinate"),
                    ));
                }
                coords.push([s[0], s[1], s[2]]);
                if let Some(nr) = &mut nrm {
                    nr.push(Vector3::new(s[3], s[4], s[5]));
                }
            }
            return Ok(Vertices {
                coords,
                normals: nrm,
                extras,
                dim: if z.is_some() { 3 } else { 2 },
            });
        }
    }
    for i in 0..el.count {
        src.begin(i)?;
        let mut s = [0.0f64; 6];
        for (p, role) in el.props.iter().zip(&roles) {
            match (*role, p.ty) {
                (VRole::Slot(j), PropType::Scalar(k)) => s[j] = src.scalar(k)?,
                (VRole::Extra(j), PropType::Scalar(k)) => {
                    let v = src.scalar(k)?;
                    if let Some(e) = extras.get_mut(j) {
                        e.values.push(v);
                    }
                }
                (_, ty) => skip_prop(src, ty)?,
            }
        }
        src.end()?;
        if !(s[0].is_finite() && s[1].is_finite() && s[2].is_finite()) {
            return Err(src.err("non-finite coordinate".into()));
        }
        coords.push([s[0], s[1], s[2]]);
        if let Some(nr) = &mut nrm {
            nr.push(Vector3::new(s[3], s[4], s[5]));
        }
    }
    Ok(Vertices {
        coords,
        normals: nrm,
        extras,
        dim: if z.is_some() { 3 } else { 2 },
    })
}

struct Faces {
    triangles: Vec<[u32; 3]>,
    extras: Vec<Property>,
}

fn read_faces<S: Source>(src: &mut S, el: &ElementDef, nv: u64) -> Result<Faces> {
    let list = el
        .props
        .iter()
        .position(|p| {
            matches!(p.ty, PropType::List(..))
                && (p.name == "vertex_indices" || p.name == "vertex_index")
        })
        .ok_or_else(|| Error::format("PLY face element has no 'vertex_indices' list property"))?;
    let mut roles = Vec::with_capacity(el.props.len());
    let mut extras = Vec::new();
    for (i, p) in el.props.iter().enumerate() {
        roles.push(match p.ty {
            _ if i == list => VRole::Slot(0),
            PropType::Scalar(k) => {
                extras.push(Property {
                    name: p.name.clone(),
                    kind: k,
                    values: Vec::new(),
                });
                VRole::Extra(extras.len() - 1)
            }
            PropType::List(..) => VRole::Skip,
        });
    }
    src.start(el)?;
    let n = el.count as usize;
    let mut triangles = Vec::with_capacity(n);
    for e in &mut extras {
        e.values.reserve(n);
    }
    if let [PropDef {
        ty: PropType::List(c, it),
        ..
    }] = el.props.as_slice()
    {
        let (c, it) = (*c, *it);
        if let Some((data, base, big)) = src.rest() {
            let used = binary_index_lists(data, base, big, c, it, el.count, nv, &mut triangles)?;
            src.fixed(used as u64);
            return Ok(Faces { triangles, extras });
        }
    }
    let mut corners: Vec<u32> = Vec::new();
    let mut vals = vec![0.0; extras.len()];
    for f in 0..el.count {
        src.begin(f)?;
        corners.clear();
        for (p, role) in el.props.iter().zip(&roles) {
            match (*role, p.ty) {
                (VRole::Slot(_), PropType::List(c, it)) => {
                    let len = src.list_len(c, it)?;
                    for _ in 0..len {
                        let v = src.scalar(it)?;
                        let v = vertex_index(v, nv).ok_or_else(|| {
                            src.err(format!(
                                "refers to vertex {v}, but there are only {nv} vertices"
                            ))
                        })?;
                        corners.push(v);
                    }
                }
                (VRole::Extra(j), PropType::Scalar(k)) => {
                    let v = src.scalar(k)?;
                    if let Some(x) = vals.get_mut(j) {
                        *x = v;
                    }
                }
                (_, ty) => skip_prop(src, ty)?,
            }
        }
        src.end()?;
        if corners.len() < 3 {
            return Err(src.err(format!(
                "face has {} corners; a face needs at least 3",
                corners.len()
            )));
        }
        for k in 1..corners.len() - 1 {
            triangles.push([corners[0], corners[k], corners[k + 1]]);
            for (e, &v) in extras.iter_mut().zip(&vals) {
                e.values.push(v);
            }
        }
    }
    Ok(Faces { triangles, extras })
}

/// `v` as a vertex index when it is a whole number in `0..nv` (without a call to `trunc`,
/// which is a library call on baseline x86-64).
#[inline]
fn vertex_index(v: f64, nv: u64) -> Option<u32> {
    if v >= 0.0 && v < nv as f64 {
        let i = v as u32;
        (i as f64 == v).then_some(i)
    } else {
        None
    }
}

/// Fast path for binary face elements that hold only the index list: decodes `count` lists
/// from `data` (at file offset `base`), fan-triangulates them into `triangles`, and returns the
/// number of bytes used. Errors and messages are those of the general path.
#[allow(clippy::too_many_arguments)]
fn binary_index_lists(
    data: &[u8],
    base: usize,
    big: bool,
    count_kind: ScalarKind,
    item: ScalarKind,
    count: u64,
    nv: u64,
    triangles: &mut Vec<[u32; 3]>,
) -> Result<usize> {
    let (cs, is) = (size(count_kind), size(item));
    let mut p = 0usize;
    for f in 0..count {
        let at = base + p;
        let truncated = |q: usize| {
            Error::at_byte(
                (base + q) as u64,
                format!("file ends inside face {f} (data is truncated)"),
            )
        };
        let len = decode(
            count_kind,
            data.get(p..p + cs).ok_or_else(|| truncated(p))?,
            big,
        );
        if len < 0.0 || len.fract() != 0.0 {
            return Err(Error::at_byte(
                at as u64,
                format!("face {f}: bad list length {len}"),
            ));
        }
        let len = len as u64;
        let bytes = len
            .checked_mul(is as u64)
            .filter(|&b| b <= (data.len() - p - cs) as u64)
            .ok_or_else(|| {
                Error::at_byte(
                    at as u64,
                    format!(
                        "face {f}: list of {len} items runs past the end of the file (data is truncated)"
                    ),
                )
            })? as usize;
        let items = &data[p + cs..p + cs + bytes];
        if len < 3 {
            return Err(Error::at_byte(
                at as u64,
                format!("face {f}: face has {len} corners; a face needs at least 3"),
            ));
        }
        let (mut first, mut prev) = (0u32, 0u32);
        for (k, b) in items.chunks_exact(is).enumerate() {
            let v = decode(item, b, big);
            let v = vertex_index(v, nv).ok_or_else(|| {
                Error::at_byte(
                    at as u64,
                    format!("face {f}: refers to vertex {v}, but there are only {nv} vertices"),
                )
            })?;
            match k {
                0 => first = v,
                1 => {}
                _ => triangles.push([first, prev, v]),
            }
            prev = v;
        }
        p += cs + bytes;
    }
    Ok(p)
}

/// Triangles of a `tristrips` element (Cyberware/Stanford scans): each record's
/// `vertex_indices` list holds strips separated by `-1`; strip `s0 s1 s2 …` gives triangles
/// `(s_i, s_i+1, s_i+2)` with every other one flipped to keep the orientation, and triangles
/// with a repeated corner (strip joints) are dropped.
fn read_tristrips<S: Source>(src: &mut S, el: &ElementDef, nv: u64) -> Result<Vec<[u32; 3]>> {
    let list = el
        .props
        .iter()
        .position(|p| matches!(p.ty, PropType::List(..)) && p.name == "vertex_indices")
        .ok_or_else(|| Error::format("PLY tristrips element has no 'vertex_indices' list"))?;
    src.start(el)?;
    let mut triangles = Vec::new();
    for r in 0..el.count {
        src.begin(r)?;
        for (i, p) in el.props.iter().enumerate() {
            match p.ty {
                PropType::List(c, it) if i == list => {
                    let len = src.list_len(c, it)?;
                    // (second-to-last, last, position in the current strip)
                    let (mut a, mut b, mut k) = (0u32, 0u32, 0u64);
                    for _ in 0..len {
                        let v = src.scalar(it)?;
                        if v == -1.0 {
                            k = 0;
                            continue;
                        }
                        let v = vertex_index(v, nv).ok_or_else(|| {
                            src.err(format!(
                                "refers to vertex {v}, but there are only {nv} vertices"
                            ))
                        })?;
                        if k >= 2 && a != b && b != v && a != v {
                            triangles.push(if k % 2 == 0 { [a, b, v] } else { [b, a, v] });
                        }
                        (a, b, k) = (b, v, k + 1);
                    }
                }
                ty => skip_prop(src, ty)?,
            }
        }
        src.end()?;
    }
    Ok(triangles)
}

/// Tetrahedra of a `tetra` element: the list `vertex_indices` (or `vertex_index`) of each
/// record holds exactly 4 vertex indices; other properties are skipped.
fn read_tetra<S: Source>(src: &mut S, el: &ElementDef, nv: u64) -> Result<Vec<[u32; 4]>> {
    let list = el
        .props
        .iter()
        .position(|p| {
            matches!(p.ty, PropType::List(..))
                && (p.name == "vertex_indices" || p.name == "vertex_index")
        })
        .ok_or_else(|| Error::format("PLY tetra element has no 'vertex_indices' list property"))?;
    src.start(el)?;
    let mut tets = Vec::with_capacity(el.count as usize);
    for r in 0..el.count {
        src.begin(r)?;
        let mut tet = [0u32; 4];
        for (i, p) in el.props.iter().enumerate() {
            match p.ty {
                PropType::List(c, it) if i == list => {
                    let len = src.list_len(c, it)?;
                    if len != 4 {
                        return Err(
                            src.err(format!("tetrahedron has {len} corners; it needs exactly 4"))
                        );
                    }
                    for corner in &mut tet {
                        let v = src.scalar(it)?;
                        *corner = vertex_index(v, nv).ok_or_else(|| {
                            src.err(format!(
                                "refers to vertex {v}, but there are only {nv} vertices"
                            ))
                        })?;
                    }
                }
                ty => skip_prop(src, ty)?,
            }
        }
        src.end()?;
        tets.push(tet);
    }
    Ok(tets)
}

/// Which elements [`read_body`] decodes (the others are skipped).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Want {
    /// The vertices only (reading stops after them).
    Points,
    /// Vertices, faces and triangle strips.
    Mesh,
    /// Vertices and tetrahedra.
    Tets,
}

/// What to read from the body.
struct Body {
    vertices: Option<Vertices>,
    faces: Option<Faces>,
    strips: Option<Vec<[u32; 3]>>,
    tets: Option<Vec<[u32; 4]>>,
}

fn read_body<S: Source>(src: &mut S, h: &Header, want: Want) -> Result<Body> {
    let nv = h
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .map(|e| e.count)
        .ok_or_else(|| Error::format("PLY file has no vertex element"))?;
    let mut body = Body {
        vertices: None,
        faces: None,
        strips: None,
        tets: None,
    };
    for el in &h.elements {
        match el.name.as_str() {
            "vertex" => {
                body.vertices = Some(read_vertices(src, el)?);
                if want == Want::Points {
                    break;
                }
            }
            "face" if want == Want::Mesh => body.faces = Some(read_faces(src, el, nv)?),
            "tristrips" if want == Want::Mesh => body.strips = Some(read_tristrips(src, el, nv)?),
            "tetra" if want == Want::Tets => body.tets = Some(read_tetra(src, el, nv)?),
            _ => src.skip_element(el)?,
        }
    }
    Ok(body)
}

fn read_file(bytes: &[u8], want: Want) -> Result<Body> {
    let h = parse_header(bytes)?;
    let data = &bytes[h.data_start..];
    match h.fmt {
        Fmt::Ascii => {
            // CR, LF and CRLF line ends alike (bare CRs become LFs, byte for byte)
            let data = super::unify_line_ends(data);
            let text = super::obj::utf8_text(&data, h.lines + 1)?;
            read_body(&mut Ascii::new(text, h.lines), &h, want)
        }
        Fmt::Le | Fmt::Be => {
            let mut src = Binary {
                data: bytes,
                pos: h.data_start,
                big: h.fmt == Fmt::Be,
                rec_start: h.data_start,
                el: String::new(),
                rec: 0,
            };
            read_body(&mut src, &h, want)
        }
    }
}

/// Reads vertices and faces (polygons are fan-triangulated); extra properties are kept.
pub fn read_mesh(bytes: &[u8]) -> Result<TriMesh> {
    let body = read_file(bytes, Want::Mesh)?;
    let v = body
        .vertices
        .ok_or_else(|| Error::format("PLY file has no vertex element"))?;
    let (mut triangles, mut face_props) = match body.faces {
        Some(f) => (f.triangles, f.extras),
        None => (Vec::new(), Vec::new()),
    };
    if let Some(strips) = body.strips {
        triangles.extend_from_slice(&strips);
        for p in &mut face_props {
            p.values.resize(triangles.len(), 0.0);
        }
    }
    Ok(TriMesh {
        positions: v
            .coords
            .iter()
            .map(|c| Point3::new(c[0], c[1], c[2]))
            .collect(),
        triangles,
        normals: v.normals,
        vertex_props: v.extras,
        face_props,
    })
}

/// Reads the vertices only, as points (3D, or 2D when there is no `z`; extra vertex
/// properties other than normals become columns).
pub fn read_points(bytes: &[u8]) -> Result<PointSet> {
    let body = read_file(bytes, Want::Points)?;
    let v = body
        .vertices
        .ok_or_else(|| Error::format("PLY file has no vertex element"))?;
    let coords = if v.dim == 3 {
        v.coords.iter().flatten().copied().collect()
    } else {
        v.coords.iter().flat_map(|c| [c[0], c[1]]).collect()
    };
    Ok(PointSet {
        dim: v.dim,
        coords,
        columns: v
            .extras
            .into_iter()
            .map(|p| Column {
                name: p.name,
                values: p.values,
            })
            .collect(),
    })
}

/// True when the header declares a `tetra` element (a tetrahedral mesh, see [`read_tets`]).
pub fn has_tets(bytes: &[u8]) -> Result<bool> {
    Ok(parse_header(bytes)?
        .elements
        .iter()
        .any(|e| e.name == "tetra"))
}

/// Reads a tetrahedral mesh: the vertices and the `tetra` element (as [`write_tets`] writes
/// it; a file without one is an error). Corner order is kept as in the file.
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::io::{ply, Encoding};
/// use morpho::mesh::TetMesh;
/// let t = TetMesh {
///     positions: vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///                     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)],
///     tets: vec![[0, 1, 3, 2]],
/// };
/// let mut out = Vec::new();
/// ply::write_tets(&mut out, &t, Encoding::Ascii).unwrap();
/// assert_eq!(ply::read_tets(&out).unwrap(), t);
/// ```
pub fn read_tets(bytes: &[u8]) -> Result<TetMesh> {
    let body = read_file(bytes, Want::Tets)?;
    let v = body
        .vertices
        .ok_or_else(|| Error::format("PLY file has no vertex element"))?;
    let tets = body
        .tets
        .ok_or_else(|| Error::format("PLY file has no 'tetra' element (no tetrahedra)"))?;
    Ok(TetMesh {
        positions: v
            .coords
            .iter()
            .map(|c| Point3::new(c[0], c[1], c[2]))
            .collect(),
        tets,
    })
}

// ---------------------------------------------------------------------------------------------
// Writers

/// Buffered value encoder for one encoding.
struct Enc {
    fmt: Fmt,
    buf: Vec<u8>,
}

impl Enc {
    fn new(enc: Encoding) -> Self {
        Enc {
            fmt: match enc {
                Encoding::Ascii => Fmt::Ascii,
                Encoding::BinaryLittleEndian => Fmt::Le,
                Encoding::BinaryBigEndian => Fmt::Be,
            },
            buf: Vec::with_capacity(1 << 16),
        }
    }
    fn format_line(&self) -> &'static str {
        match self.fmt {
            Fmt::Ascii => "ascii",
            Fmt::Le => "binary_little_endian",
            Fmt::Be => "binary_big_endian",
        }
    }
    /// Appends three doubles (a position or a normal): one branch on the encoding for the
    /// three, the hot loop of every mesh writer.
    #[inline]
    fn put_f64x3(&mut self, a: [f64; 3]) {
        match self.fmt {
            Fmt::Le => {
                let mut b = [0u8; 24];
                for k in 0..3 {
                    b[8 * k..8 * k + 8].copy_from_slice(&a[k].to_le_bytes());
                }
                self.buf.extend_from_slice(&b);
            }
            Fmt::Be => {
                let mut b = [0u8; 24];
                for k in 0..3 {
                    b[8 * k..8 * k + 8].copy_from_slice(&a[k].to_be_bytes());
                }
                self.buf.extend_from_slice(&b);
            }
            Fmt::Ascii => {
                for x in a {
                    self.put(ScalarKind::F64, x);
                }
            }
        }
    }
    /// Appends a triangle as `uchar 3` and three `int` indices (each < 2³¹, checked by the
    /// caller).
    #[inline]
    fn put_triangle(&mut self, t: [u32; 3]) {
        match self.fmt {
            Fmt::Le | Fmt::Be => {
                let mut b = [3u8; 13];
                for k in 0..3 {
                    let v = t[k] as i32;
                    let x = if self.fmt == Fmt::Le {
                        v.to_le_bytes()
                    } else {
                        v.to_be_bytes()
                    };
                    b[1 + 4 * k..5 + 4 * k].copy_from_slice(&x);
                }
                self.buf.extend_from_slice(&b);
            }
            Fmt::Ascii => {
                self.put(ScalarKind::U8, 3.0);
                for v in t {
                    self.put(ScalarKind::I32, v as f64);
                }
            }
        }
    }
    /// Appends `v` as kind `k` (the caller made sure it [`fits`]).
    fn put(&mut self, k: ScalarKind, v: f64) {
        macro_rules! b {
            ($x:expr) => {{
                let x = $x;
                if self.fmt == Fmt::Be {
                    self.buf.extend_from_slice(&x.to_be_bytes())
                } else {
                    self.buf.extend_from_slice(&x.to_le_bytes())
                }
            }};
        }
        if self.fmt == Fmt::Ascii {
            if !self.buf.is_empty() && self.buf.last() != Some(&b'\n') {
                self.buf.push(b' ');
            }
            // Writing into a Vec cannot fail.
            let _ = match k {
                ScalarKind::F32 => write!(self.buf, "{}", F32(v as f32)),
                ScalarKind::F64 => write!(self.buf, "{}", F64(v)),
                _ => write!(self.buf, "{}", v as i64),
            };
            return;
        }
        match k {
            ScalarKind::I8 => b!(v as i8),
            ScalarKind::U8 => b!(v as u8),
            ScalarKind::I16 => b!(v as i16),
            ScalarKind::U16 => b!(v as u16),
            ScalarKind::I32 => b!(v as i32),
            ScalarKind::U32 => b!(v as u32),
            ScalarKind::F32 => b!(v as f32),
            ScalarKind::F64 => b!(v),
        }
    }
    fn end_record(&mut self, w: &mut dyn Write) -> Result<()> {
        if self.fmt == Fmt::Ascii {
            self.buf.push(b'\n');
        }
        if self.buf.len() >= 1 << 20 {
            self.flush(w)?;
        }
        Ok(())
    }
    fn flush(&mut self, w: &mut dyn Write) -> Result<()> {
        w.write_all(&self.buf).map_err(super::werr)?;
        self.buf.clear();
        Ok(())
    }
}

fn check_name(name: &str, reserved: &[&str], what: &str) -> Result<()> {
    if name.is_empty() || name.chars().any(|c| c.is_whitespace() || c.is_control()) {
        return Err(Error::invalid(format!(
            "{what} property name '{name}' cannot be written to PLY (empty or with spaces)"
        )));
    }
    if reserved.contains(&name) {
        return Err(Error::invalid(format!(
            "{what} property name '{name}' is reserved in PLY"
        )));
    }
    Ok(())
}

fn check_props(props: &[Property], reserved: &[&str], what: &str) -> Result<()> {
    for (i, p) in props.iter().enumerate() {
        check_name(&p.name, reserved, what)?;
        if props[..i].iter().any(|q| q.name == p.name) {
            return Err(Error::invalid(format!(
                "two {what} properties are called '{}'",
                p.name
            )));
        }
        if let Some((j, v)) = p.values.iter().enumerate().find(|(_, &v)| !fits(p.kind, v)) {
            return Err(Error::invalid(format!(
                "{what} property '{}': value {v} of element {j} is not a valid {}",
                p.name,
                kind_name(p.kind)
            )));
        }
    }
    Ok(())
}

/// Writes a mesh with its normals and extra properties.
///
/// ```
/// use morpho::io::{ply, Encoding};
/// use morpho::mesh::generate;
/// let m = generate::cube();
/// for enc in [Encoding::Ascii, Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
///     let mut bytes = Vec::new();
///     ply::write_mesh(&mut bytes, &m, enc).unwrap();
///     let back = ply::read_mesh(&bytes).unwrap();
///     assert_eq!((back.positions, back.triangles), (m.positions.clone(), m.triangles.clone()));
/// }
/// ```
pub fn write_mesh(w: &mut dyn Write, mesh: &TriMesh, enc: Encoding) -> Result<()> {
    mesh.validate()?;
    let has_normals = mesh.normals.is_some();
    let all_n = ["nx", "ny", "nz"]
        .iter()
        .all(|n| mesh.vertex_prop(n).is_some());
    let reserved: &[&str] = if has_normals || all_n {
        &["x", "y", "z", "nx", "ny", "nz"]
    } else {
        &["x", "y", "z"]
    };
    check_props(&mesh.vertex_props, reserved, "vertex")?;
    check_props(
        &mesh.face_props,
        &["vertex_indices", "vertex_index"],
        "face",
    )?;
    if mesh.positions.len() > i32::MAX as usize {
        return Err(Error::invalid(
            "more than 2^31-1 vertices cannot be indexed by PLY 'int' indices",
        ));
    }
    let mut e = Enc::new(enc);
    let h = mesh_header(
        &e,
        mesh.positions.len() as u64,
        has_normals,
        &mesh.vertex_props,
        mesh.triangles.len() as u64,
        &mesh.face_props,
    );
    e.buf.extend_from_slice(h.as_bytes());
    for (i, p) in mesh.positions.iter().enumerate() {
        e.put_f64x3([p.x, p.y, p.z]);
        if let Some(n) = mesh.normals.as_ref().and_then(|n| n.get(i)) {
            e.put_f64x3([n.x, n.y, n.z]);
        }
        for p in &mesh.vertex_props {
            e.put(p.kind, p.values.get(i).copied().unwrap_or(0.0));
        }
        e.end_record(w)?;
    }
    for (t, tri) in mesh.triangles.iter().enumerate() {
        e.put_triangle(*tri);
        for p in &mesh.face_props {
            e.put(p.kind, p.values.get(t).copied().unwrap_or(0.0));
        }
        e.end_record(w)?;
    }
    e.flush(w)
}

/// The header [`write_mesh`] writes (the properties' values are not looked at).
fn mesh_header(
    e: &Enc,
    nv: u64,
    normals: bool,
    vprops: &[Property],
    nf: u64,
    fprops: &[Property],
) -> String {
    let mut h = format!(
        "ply\nformat {} 1.0\ncomment written by morpho\nelement vertex {nv}\n\
         property double x\nproperty double y\nproperty double z\n",
        e.format_line(),
    );
    if normals {
        h.push_str("property double nx\nproperty double ny\nproperty double nz\n");
    }
    for p in vprops {
        h.push_str(&format!("property {} {}\n", kind_name(p.kind), p.name));
    }
    h.push_str(&format!(
        "element face {nf}\nproperty list uchar int vertex_indices\n"
    ));
    for p in fprops {
        h.push_str(&format!("property {} {}\n", kind_name(p.kind), p.name));
    }
    h.push_str("end_header\n");
    h
}

/// A triangle mesh written as it is produced, when it is too large to hold (the streaming
/// contour surface): vertex records are encoded into one temporary file, a second run of
/// vertices (appended after the first) into another, triangles into a third as raw indices;
/// [`MeshSpool::finish`] writes the PLY — header with the final counts, the vertices, the
/// faces with their indices resolved and an optional `part` property — atomically onto the
/// output, byte for byte what [`write_mesh`] writes for the same mesh. The temporary files
/// live in the output's folder and are removed on drop and on signals
/// ([`super::guard::remove_temporaries`]).
pub struct MeshSpool {
    enc: Encoding,
    normals: bool,
    files: [std::io::BufWriter<tempfile::NamedTempFile>; 3],
    counts: [u64; 3],
    e: Enc,
}

impl MeshSpool {
    /// Spools in `dir` (the output's folder) a mesh with or without vertex normals.
    pub fn new(dir: &std::path::Path, enc: Encoding, normals: bool) -> Result<MeshSpool> {
        let tmp = || -> Result<std::io::BufWriter<tempfile::NamedTempFile>> {
            let f = super::guard::create_temporary(dir).map_err(|e| Error::io(dir, e))?;
            Ok(std::io::BufWriter::with_capacity(1 << 20, f))
        };
        Ok(MeshSpool {
            enc,
            normals,
            files: [tmp()?, tmp()?, tmp()?],
            counts: [0; 3],
            e: Enc::new(enc),
        })
    }

    fn put_vertices(&mut self, k: usize, p: &[Point3], n: &[Vector3]) -> Result<()> {
        let mut sink: Vec<u8> = Vec::new();
        for (i, q) in p.iter().enumerate() {
            self.e.put_f64x3([q.x, q.y, q.z]);
            if self.normals {
                let m = n.get(i).copied().unwrap_or_else(Vector3::zeros);
                self.e.put_f64x3([m.x, m.y, m.z]);
            }
            self.e.end_record(&mut sink)?;
            if !sink.is_empty() {
                self.files[k].write_all(&sink).map_err(super::werr)?;
                sink.clear();
            }
        }
        self.e.flush(&mut sink)?;
        self.files[k].write_all(&sink).map_err(super::werr)?;
        self.counts[k] += p.len() as u64;
        Ok(())
    }

    /// Appends vertices (with their normals when the mesh has normals).
    pub fn vertices(&mut self, p: &[Point3], n: &[Vector3]) -> Result<()> {
        self.put_vertices(0, p, n)
    }

    /// Appends vertices of the second run (written after every vertex of the first).
    pub fn late_vertices(&mut self, p: &[Point3], n: &[Vector3]) -> Result<()> {
        self.put_vertices(1, p, n)
    }

    /// Appends triangles; their corners are resolved by [`finish`](Self::finish).
    pub fn triangles(&mut self, t: &[[u32; 3]]) -> Result<()> {
        let mut b = Vec::with_capacity(12 * t.len());
        for tri in t {
            for v in tri {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
        self.files[2].write_all(&b).map_err(super::werr)?;
        self.counts[2] += t.len() as u64;
        Ok(())
    }

    /// Vertices of the first run, of the second, and triangles so far.
    pub fn counts(&self) -> [u64; 3] {
        self.counts
    }

    /// Writes the PLY onto `path`: `resolve` maps a spooled corner to its vertex number,
    /// `part` (when given) labels triangle t (a `uint part` face property).
    pub fn finish(
        self,
        path: &std::path::Path,
        resolve: impl Fn(u32) -> u32,
        part: Option<&dyn Fn(usize) -> u32>,
    ) -> Result<()> {
        use std::io::{Read, Seek};
        let nv = self.counts[0] + self.counts[1];
        if nv > i32::MAX as u64 {
            return Err(Error::invalid(
                "more than 2^31-1 vertices cannot be indexed by PLY 'int' indices",
            ));
        }
        let mut files = Vec::new();
        for f in self.files {
            let mut f = f
                .into_inner()
                .map_err(|e| Error::io(path, e.into_error()))?;
            f.as_file_mut()
                .seek(std::io::SeekFrom::Start(0))
                .map_err(|e| Error::io(path, e))?;
            files.push(f);
        }
        let fprops: Vec<Property> = part
            .is_some()
            .then(|| Property {
                name: "part".into(),
                kind: ScalarKind::U32,
                values: Vec::new(),
            })
            .into_iter()
            .collect();
        let (enc, normals, nf) = (self.enc, self.normals, self.counts[2]);
        super::write_atomic(path, |w| {
            let mut e = Enc::new(enc);
            let h = mesh_header(&e, nv, normals, &[], nf, &fprops);
            w.write_all(h.as_bytes()).map_err(super::werr)?;
            for f in files.iter_mut().take(2) {
                std::io::copy(f.as_file_mut(), w).map_err(super::werr)?;
            }
            let mut r = std::io::BufReader::with_capacity(1 << 20, files[2].as_file_mut());
            let mut rec = [0u8; 12];
            for t in 0..nf as usize {
                r.read_exact(&mut rec).map_err(super::werr)?;
                let c: [u32; 3] = std::array::from_fn(|k| {
                    resolve(u32::from_le_bytes([
                        rec[4 * k],
                        rec[4 * k + 1],
                        rec[4 * k + 2],
                        rec[4 * k + 3],
                    ]))
                });
                e.put_triangle(c);
                if let Some(p) = part {
                    e.put(ScalarKind::U32, p(t) as f64);
                }
                e.end_record(w)?;
            }
            e.flush(w)
        })?;
        for f in &files {
            super::guard::temporary_gone(f.path());
        }
        Ok(())
    }
}

/// Writes points (with their columns as `double` vertex properties).
pub fn write_points(w: &mut dyn Write, pts: &PointSet, enc: Encoding) -> Result<()> {
    pts.validate()?;
    let axes: &[&str] = if pts.dim == 2 {
        &["x", "y"]
    } else {
        &["x", "y", "z"]
    };
    for (i, c) in pts.columns.iter().enumerate() {
        check_name(&c.name, &["x", "y", "z"], "vertex")?;
        if pts.columns[..i].iter().any(|d| d.name == c.name) {
            return Err(Error::invalid(format!(
                "two columns are called '{}'",
                c.name
            )));
        }
    }
    let mut e = Enc::new(enc);
    let mut h = format!(
        "ply\nformat {} 1.0\ncomment written by morpho\nelement vertex {}\n",
        e.format_line(),
        pts.len()
    );
    for a in axes
        .iter()
        .copied()
        .chain(pts.columns.iter().map(|c| c.name.as_str()))
    {
        h.push_str(&format!("property double {a}\n"));
    }
    h.push_str("end_header\n");
    e.buf.extend_from_slice(h.as_bytes());
    for i in 0..pts.len() {
        for &c in pts
            .coords
            .get(i * pts.dim..(i + 1) * pts.dim)
            .unwrap_or(&[])
        {
            e.put(ScalarKind::F64, c);
        }
        for c in &pts.columns {
            e.put(ScalarKind::F64, c.values.get(i).copied().unwrap_or(0.0));
        }
        e.end_record(w)?;
    }
    e.flush(w)
}

/// Writes a tetrahedral mesh: `vertex` (x, y, z as `double`) and a `tetra` element with the
/// list `vertex_indices` (`uchar` count 4, `int` indices), corners in the mesh's order. Binary
/// little endian is what `morpho triangulate --tets` writes; meshio and trimesh do not read the
/// `tetra` element (use [`super::vtk`] for them).
pub fn write_tets(w: &mut dyn Write, t: &TetMesh, enc: Encoding) -> Result<()> {
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
    if n > i32::MAX as usize {
        return Err(Error::invalid(
            "more than 2^31-1 vertices cannot be indexed by PLY 'int' indices",
        ));
    }
    let mut e = Enc::new(enc);
    let h = format!(
        "ply\nformat {} 1.0\ncomment morpho tetrahedralization\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement tetra {}\n\
         property list uchar int vertex_indices\nend_header\n",
        e.format_line(),
        n,
        t.tets.len()
    );
    e.buf.extend_from_slice(h.as_bytes());
    for p in &t.positions {
        for c in [p.x, p.y, p.z] {
            e.put(ScalarKind::F64, c);
        }
        e.end_record(w)?;
    }
    for tet in &t.tets {
        e.put(ScalarKind::U8, 4.0);
        for &v in tet {
            e.put(ScalarKind::I32, v as f64);
        }
        e.end_record(w)?;
    }
    e.flush(w)
}

/// Writes a geometric graph on `points` as ASCII PLY (graphs are small files): the vertices
/// (`double` x, y, z), the graph's triangles as a `face` element and its edges as an `edge`
/// element (`int vertex1`, `int vertex2`). Numbers in Rust's shortest round-trip form.
pub fn write_graph(w: &mut dyn Write, points: &[Point3], g: &Graph) -> Result<()> {
    write_graph_body(w, points, g).map_err(super::werr)
}

fn write_graph_body(w: &mut dyn Write, p: &[Point3], g: &Graph) -> std::io::Result<()> {
    writeln!(
        w,
        "ply\nformat ascii 1.0\ncomment morpho graph\nelement vertex {}",
        p.len()
    )?;
    writeln!(w, "property double x\nproperty double y\nproperty double z")?;
    writeln!(
        w,
        "element face {}\nproperty list uchar int vertex_indices",
        g.triangles.len()
    )?;
    writeln!(
        w,
        "element edge {}\nproperty int vertex1\nproperty int vertex2\nend_header",
        g.edges.len()
    )?;
    for q in p {
        writeln!(w, "{} {} {}", q.x, q.y, q.z)?;
    }
    for t in &g.triangles {
        writeln!(w, "3 {} {} {}", t[0], t[1], t[2])?;
    }
    for e in &g.edges {
        writeln!(w, "{} {}", e[0], e[1])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> TriMesh {
        TriMesh {
            positions: vec![
                Point3::new(0.1, 0.2, 0.3),
                Point3::new(1.0 / 3.0, -0.0, 1e300),
                Point3::new(-5.0, 2.5e-310, 7.0),
                Point3::new(1.0, 1.0, 1.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            normals: Some(vec![Vector3::new(0.0, 0.6, 0.8); 4]),
            vertex_props: vec![
                Property {
                    name: "quality".into(),
                    kind: ScalarKind::F32,
                    values: vec![0.5, f64::from(0.1f32), -3.0, 1e-30f32 as f64],
                },
                Property {
                    name: "red".into(),
                    kind: ScalarKind::U8,
                    values: vec![0.0, 255.0, 17.0, 3.0],
                },
                Property {
                    name: "label".into(),
                    kind: ScalarKind::I32,
                    values: vec![-7.0, 2147483647.0, -2147483648.0, 0.0],
                },
            ],
            face_props: vec![Property {
                name: "part".into(),
                kind: ScalarKind::I16,
                values: vec![-2.0, 300.0],
            }],
        }
    }

    #[test]
    fn round_trip_all_encodings() {
        let m = sample();
        for enc in [
            Encoding::Ascii,
            Encoding::BinaryLittleEndian,
            Encoding::BinaryBigEndian,
        ] {
            let mut buf = Vec::new();
            write_mesh(&mut buf, &m, enc).unwrap();
            assert_eq!(read_mesh(&buf).unwrap(), m, "{enc:?}");
            let p = read_points(&buf).unwrap();
            assert_eq!(p.len(), 4);
            assert_eq!(p.columns.len(), 3);
            assert_eq!(p.column("red").unwrap().values[1], 255.0);
        }
    }

    #[test]
    fn all_types_polygons_and_skipped_elements() {
        let src = "ply\r\nformat ascii 1.0\r\ncomment hi\r\nobj_info x\r\n\
            element material 2\r\nproperty list int float rgb\r\nproperty uint8 id\r\n\
            element vertex 4\r\nproperty int8 a\r\nproperty float32 x\r\nproperty int y\r\n\
            property uint16 z\r\nproperty list uchar uchar junk\r\nproperty float64 nx\r\n\
            element face 1\r\nproperty uchar flags\r\nproperty list uint short vertex_index\r\n\
            element edge 1\r\nproperty int v1\r\nproperty int v2\r\nend_header\r\n\
            3 1 2 3 5\r\n0 6\r\n-1 0.5 -3 2 2 9 9 0.25\r\n2 1 0 0 0 0\r\n3 1 1 1 1 7 0\r\n\
            4 0 1 1 0 0\r\n7 4 0 1 2 3\r\n0 1\r\n";
        let m = read_mesh(src.as_bytes()).unwrap();
        assert_eq!(m.positions[0], Point3::new(0.5, -3.0, 2.0));
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(
            m.vertex_prop("a").unwrap().values,
            vec![-1.0, 2.0, 3.0, 4.0]
        );
        assert_eq!(m.vertex_prop("nx").unwrap().values[0], 0.25);
        assert!(m.normals.is_none());
        assert_eq!(m.face_prop("flags").unwrap().values, vec![7.0, 7.0]);
        assert_eq!(m.face_prop("flags").unwrap().kind, ScalarKind::U8);
        // The same file in both binary encodings.
        for enc in [Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
            let mut buf = Vec::new();
            write_mesh(&mut buf, &m, enc).unwrap();
            assert_eq!(read_mesh(&buf).unwrap(), m);
        }
    }

    #[test]
    fn binary_lists_in_skipped_elements() {
        // element junk with a list before the vertices, big endian.
        let mut b =
            b"ply\nformat binary_big_endian 1.0\nelement junk 2\nproperty list ushort int v\n\
            element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
            element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
                .to_vec();
        b.extend_from_slice(&2u16.to_be_bytes());
        b.extend_from_slice(&[0; 8]);
        b.extend_from_slice(&0u16.to_be_bytes());
        for v in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
            b.extend_from_slice(&v.to_be_bytes());
        }
        b.push(3);
        for i in [0u32, 1, 2] {
            b.extend_from_slice(&i.to_be_bytes());
        }
        let m = read_mesh(&b).unwrap();
        assert_eq!(m.positions[2], Point3::new(0.0, 1.0, 0.0));
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        // Truncations at every length are errors, never panics.
        for n in 0..b.len() {
            assert!(read_mesh(&b[..n]).is_err(), "{n}");
        }
    }

    #[test]
    fn tristrips_planar_vertices_and_crlf_binary_header() {
        // Strip 0 1 2 3 4, then a second strip 4 3 5 after -1; 2 2 5 makes a degenerate joint.
        let src = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n\
                   element tristrips 1\nproperty list int int vertex_indices\nend_header\n\
                   0 0\n1 0\n0 1\n1 1\n0 2\n1 2\n10 0 1 2 3 4 -1 4 3 5 5\n";
        let m = read_mesh(src.as_bytes()).unwrap();
        assert_eq!(m.positions[5], Point3::new(1.0, 2.0, 0.0));
        assert_eq!(
            m.triangles,
            vec![[0, 1, 2], [2, 1, 3], [2, 3, 4], [4, 3, 5]]
        );
        let p = read_points(src.as_bytes()).unwrap();
        assert_eq!((p.dim, p.len()), (2, 6));
        // Little-endian binary with a skipped list element and Windows line endings.
        let mut b = b"ply\r\nformat binary_little_endian 1.0\r\nelement junk 1\r\n\
            property list uint short v\r\nproperty double w\r\nelement vertex 3\r\n\
            property double x\r\nproperty double y\r\nproperty double z\r\n\
            element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
            .to_vec();
        b.extend_from_slice(&3u32.to_le_bytes());
        b.extend_from_slice(&[1, 0, 2, 0, 3, 0]);
        b.extend_from_slice(&9.5f64.to_le_bytes());
        for v in [0f64, 0., 0., 1., 0., 0., 0., 1., 0.] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.push(3);
        for i in [0i32, 1, 2] {
            b.extend_from_slice(&i.to_le_bytes());
        }
        let m = read_mesh(&b).unwrap();
        assert_eq!(m.positions[1], Point3::new(1.0, 0.0, 0.0));
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn hostile_headers() {
        let t = std::time::Instant::now();
        let e = read_mesh(b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("1000000000000") && e.contains("bytes are left"),
            "{e}"
        );
        let e = read_mesh(b"ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line(s) are left"), "{e}");
        assert!(t.elapsed().as_secs_f64() < 1.0);
        let e = read_mesh(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("end_header"), "{e}");
        let e = read_mesh(b"ply\nformat ascii 1.0\ncomment \xff\nend_header\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 3") && e.contains("UTF-8"), "{e}");
    }

    fn cube_tets() -> TetMesh {
        let positions = (0..8)
            .map(|i| Point3::new((i & 1) as f64, (i >> 1 & 1) as f64, 0.1 * (i >> 2) as f64))
            .collect();
        TetMesh {
            positions,
            tets: vec![
                [0, 1, 3, 7],
                [0, 3, 2, 7],
                [0, 2, 6, 7],
                [0, 6, 4, 7],
                [0, 4, 5, 7],
            ],
        }
    }

    #[test]
    fn tets_round_trip_in_every_encoding() {
        let t = cube_tets();
        for enc in [
            Encoding::Ascii,
            Encoding::BinaryLittleEndian,
            Encoding::BinaryBigEndian,
        ] {
            let mut out = Vec::new();
            write_tets(&mut out, &t, enc).unwrap();
            assert_eq!(read_tets(&out).unwrap(), t, "{enc:?}");
            // the vertices alone are points; a tetra PLY has no faces
            assert_eq!(read_points(&out).unwrap().len(), 8);
            assert!(read_mesh(&out).unwrap().triangles.is_empty());
        }
    }

    #[test]
    fn tets_errors() {
        let mut t = cube_tets();
        t.tets.push([0, 1, 2, 8]);
        let mut out = Vec::new();
        let e = write_tets(&mut out, &t, Encoding::Ascii).unwrap_err();
        assert!(e.to_string().contains("tetrahedron 5"), "{e}");
        let mut out = Vec::new();
        write_mesh(&mut out, &sample(), Encoding::Ascii).unwrap();
        let e = read_tets(&out).unwrap_err().to_string();
        assert!(e.contains("no 'tetra' element"), "{e}");
        let bad = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
property float z\nelement tetra 1\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n";
        let e = read_tets(bad).unwrap_err().to_string();
        assert!(e.contains("line 14") && e.contains("exactly 4"), "{e}");
        let bad = String::from_utf8(bad.to_vec())
            .unwrap()
            .replace("3 0 1 2", "4 0 1 2 4");
        let e = read_tets(bad.as_bytes()).unwrap_err().to_string();
        assert!(e.contains("refers to vertex 4"), "{e}");
    }

    #[test]
    fn graph_ply_has_faces_and_edges() {
        let g = Graph {
            dim: 3,
            edges: vec![[0, 1], [1, 2]],
            triangles: vec![[0, 1, 2]],
            gamma: vec![],
        };
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.5),
            Point3::new(0.0, 1.0, 0.0),
        ];
        let mut out = Vec::new();
        write_graph(&mut out, &p, &g).unwrap();
        let m = read_mesh(&out).unwrap();
        assert_eq!(m.triangles, g.triangles);
        assert_eq!(m.positions, p);
        assert!(String::from_utf8(out).unwrap().ends_with("element edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n0 0 0\n1 0 0.5\n0 1 0\n3 0 1 2\n0 1\n1 2\n"));
    }
}

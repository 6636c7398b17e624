//! NRRD volumes (teem's "nearly raw raster data", format versions `NRRD0001`…`NRRD0005`).
//!
//! # Reading
//! The header is read line by line, each line bounded to 64 KiB and the whole header to
//! 4 MiB, so a huge header line is refused without buffering it. Header fields (names
//! case-insensitive, `# comments` and `key:=value` pairs ignored, duplicates refused):
//! - `type`: every NRRD spelling of int8/uint8/int16/uint16/int32/uint32/float/double
//!   (`uchar`, `unsigned char`, `uint8_t`, `short int`, `signed short`, …). int8 is read with
//!   source type `I16`, uint32 with `F64` (see [`super::rawjson`]); 64-bit integers and
//!   `block` are refused.
//! - `dimension`: 3, or 2 (then nz = 1); `sizes`: one positive integer per axis.
//! - `endian`: `little`/`big`; optional (default little).
//! - `encoding`: `raw`, `gzip`/`gz`, `text`/`txt`/`ascii`; others (bzip2, hex) are refused.
//! - `spacings` (`nan` → 1), else `space directions` (`none` → 1): the spacing of an axis is
//!   the Euclidean norm of its direction vector, and (3D volumes) the unit vectors are kept as
//!   [`crate::volume::Orientation::directions`] with `space` as its name, so that a conversion
//!   keeps an oblique, permuted or mirrored grid; a negative spacing is taken by absolute value.
//! - `space origin` `(x,y,z)`, else `axis mins` (`nan` → 0); default 0.
//! - `byte skip` (≥ 0, or −1 with raw encoding = the data are the last bytes of the file;
//!   with gzip the skip is applied after decompression), `line skip` (lines skipped in the
//!   data file before decoding).
//! - `data file` / `datafile`: detached data, relative to the header's folder (the header ends
//!   at end of file or at a blank line); `LIST` and `%d` file series are refused. Without it,
//!   the data follow the blank line that ends the header.
//!
//! The data must have exactly the size the header implies (after skips and decompression);
//! decompression stops one byte past that size.
//!
//! # Writing
//! An attached, gzip-encoded, little-endian `NRRD0004` file with `space` (when the volume names
//! one, else `space dimension: 3`), `space directions` (spacing × unit direction of each axis;
//! diagonal for axis-aligned volumes) and `space origin` — the spec forbids `spacings` together with a space, so
//! the spacings travel as the diagonal. Samples are in the source type if that is lossless,
//! else `float`.
//!
//! Complexity: linear in the data size.

use super::rawjson::{
    beside, data_size, encode, header_line, memory_for, open_data, output_type, read_samples,
    uniform, Codec, Sample,
};
use super::volstream::{Data, Head, VolumeStream};
use crate::volume::{Axes, Orientation, Volume};
use crate::{Error, Result};
use std::collections::HashMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;

fn nrrd_type(s: &str) -> Result<Sample> {
    let t = s.split_whitespace().collect::<Vec<_>>().join(" ");
    Ok(match t.to_ascii_lowercase().as_str() {
        "signed char" | "int8" | "int8_t" => Sample::I8,
        "uchar" | "unsigned char" | "uint8" | "uint8_t" => Sample::U8,
        "short" | "short int" | "signed short" | "signed short int" | "int16" | "int16_t" => {
            Sample::I16
        }
        "ushort" | "unsigned short" | "unsigned short int" | "uint16" | "uint16_t" => Sample::U16,
        "int" | "signed int" | "int32" | "int32_t" => Sample::I32,
        "uint" | "unsigned int" | "uint32" | "uint32_t" => Sample::U32,
        "float" => Sample::F32,
        "double" => Sample::F64,
        "longlong"
        | "long long"
        | "long long int"
        | "signed long long"
        | "signed long long int"
        | "int64"
        | "int64_t"
        | "ulonglong"
        | "unsigned long long"
        | "unsigned long long int"
        | "uint64"
        | "uint64_t" => {
            return Err(Error::unsupported(format!(
                "NRRD type '{t}' (64-bit integers) is not supported"
            )))
        }
        "block" => return Err(Error::unsupported("NRRD type 'block' is not supported")),
        _ => return Err(Error::format(format!("unknown NRRD type '{t}'"))),
    })
}

fn type_name(t: Sample) -> &'static str {
    match t {
        Sample::I8 => "int8",
        Sample::U8 => "uint8",
        Sample::I16 => "int16",
        Sample::U16 => "uint16",
        Sample::I32 => "int32",
        Sample::U32 => "uint32",
        Sample::F32 => "float",
        Sample::F64 => "double",
    }
}

/// Parses NRRD vectors `(a,b,c)` and `none` tokens.
fn vectors(s: &str, line: u64) -> Result<Vec<Option<Vec<f64>>>> {
    let mut out = Vec::new();
    let mut rest = s.trim();
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix("none") {
            out.push(None);
            rest = r.trim_start();
        } else if let Some(r) = rest.strip_prefix('(') {
            let end = r
                .find(')')
                .ok_or_else(|| Error::at_line(line, "vector without ')'"))?;
            let v = r[..end]
                .split(',')
                .map(|x| {
                    x.trim()
                        .parse::<f64>()
                        .map_err(|_| Error::at_line(line, format!("bad number '{}'", x.trim())))
                })
                .collect::<Result<Vec<f64>>>()?;
            out.push(Some(v));
            rest = r[end + 1..].trim_start();
        } else {
            return Err(Error::at_line(
                line,
                "expected a vector '(x,y,z)' or 'none'",
            ));
        }
    }
    Ok(out)
}

fn numbers(s: &str, line: u64, what: &str) -> Result<Vec<f64>> {
    s.split_whitespace()
        .map(|x| {
            x.parse::<f64>()
                .map_err(|_| Error::at_line(line, format!("{what}: bad number '{x}'")))
        })
        .collect()
}

/// Skips `n` lines of a data stream without buffering them.
fn skip_lines(r: &mut impl BufRead, n: u64, consumed: &mut u64) -> Result<()> {
    for _ in 0..n {
        loop {
            let buf = r
                .fill_buf()
                .map_err(|e| Error::format(format!("cannot read data: {e}")))?;
            if buf.is_empty() {
                return Err(Error::format("data ends inside the skipped lines"));
            }
            match buf.iter().position(|&b| b == b'\n') {
                Some(i) => {
                    r.consume(i + 1);
                    *consumed += i as u64 + 1;
                    break;
                }
                None => {
                    let l = buf.len();
                    r.consume(l);
                    *consumed += l as u64;
                }
            }
        }
    }
    Ok(())
}

/// The header fields: lower-case name (`datafile` spelled `data file`) → (line, value).
struct Fields(HashMap<String, (u64, String)>);

impl Fields {
    fn get(&self, k: &str) -> Option<(u64, &str)> {
        self.0.get(k).map(|(l, v)| (*l, v.as_str()))
    }
    fn need(&self, k: &str) -> Result<(u64, &str)> {
        self.get(k)
            .ok_or_else(|| Error::format(format!("NRRD header has no '{k}'")))
    }
}

/// Data encodings read.
enum Enc {
    Raw,
    Gzip,
    Text,
}

/// What the header says about the samples.
struct Header {
    ty: Sample,
    dims: [usize; 3],
    /// Number of samples and their size in bytes.
    n: usize,
    nbytes: usize,
    big: bool,
    enc: Enc,
    spacing: [f64; 3],
    origin: [f64; 3],
    orientation: Orientation,
    byte_skip: i64,
    line_skip: u64,
}

/// Reads a volume (detached data is found relative to `path`).
pub fn read(path: &Path) -> Result<Volume> {
    let (h, mut data_r, available, _) = source(path)?;
    memory_for(h.dims, h.ty)?;
    let data = read_samples_of(&h, &mut data_r, available)?;
    Ok(Volume {
        dims: h.dims,
        axes: Axes::Uniform {
            origin: h.origin,
            spacing: h.spacing,
        },
        data,
        source_dtype: h.ty.source_dtype(),
        orientation: h.orientation,
    })
}

/// Opens the samples for reading slice by slice ([`super::open_volume_stream`]); raw and gzip
/// encodings only.
pub(crate) fn open_stream(path: &Path) -> Result<VolumeStream> {
    let (h, data_r, available, dpath) = source(path)?;
    let (codec, skip) = match h.enc {
        Enc::Raw if h.byte_skip == -1 => (
            Codec::Raw,
            available.checked_sub(h.nbytes as u64).ok_or_else(|| {
                Error::format(format!(
                    "data has {available} bytes, the header needs {}",
                    h.nbytes
                ))
            })?,
        ),
        Enc::Raw => (Codec::Raw, h.byte_skip as u64),
        Enc::Gzip if h.byte_skip < 0 => {
            return Err(Error::format("byte skip -1 needs raw encoding"))
        }
        Enc::Gzip => (Codec::Gzip, h.byte_skip as u64),
        Enc::Text => {
            return Err(Error::unsupported(
                "NRRD text data cannot be read slice by slice (use raw or gzip encoding)",
            ))
        }
    };
    let head = Head {
        dims: h.dims,
        axes: Axes::Uniform {
            origin: h.origin,
            spacing: h.spacing,
        },
        orientation: h.orientation,
        ty: h.ty,
        big: h.big,
    };
    VolumeStream::new(
        head,
        Data {
            reader: Box::new(data_r),
            available,
            codec,
            skip,
            path: dpath,
        },
    )
}

/// The header and the data stream with its length (the detached data file, or the rest of
/// the header file after the line skip), and the path of the file the data is in.
fn source(path: &Path) -> Result<(Header, Box<dyn BufRead>, u64, std::path::PathBuf)> {
    let (f, file_len) = open_data(path)?;
    let mut r = BufReader::new(f);
    let mut consumed = 0u64;
    let fields = read_fields(&mut r, &mut consumed)?;
    let h = parse_header(&fields)?;
    match fields.get("data file") {
        Some((l, v)) => {
            let first = v.split_whitespace().next().unwrap_or("");
            if first.eq_ignore_ascii_case("LIST") || v.contains('%') {
                return Err(Error::unsupported(format!(
                    "line {l}: NRRD data file lists and series are not supported"
                )));
            }
            let dpath = beside(path, v)?;
            let (df, dlen) = open_data(&dpath)?;
            let mut dr = BufReader::new(df);
            let mut c = 0;
            skip_lines(&mut dr, h.line_skip, &mut c).map_err(|e| e.with_path(&dpath))?;
            Ok((h, Box::new(dr), dlen.saturating_sub(c), dpath))
        }
        None => {
            skip_lines(&mut r, h.line_skip, &mut consumed)?;
            Ok((
                h,
                Box::new(r),
                file_len.saturating_sub(consumed),
                path.to_path_buf(),
            ))
        }
    }
}

/// The magic line and the header fields up to the blank line (or the end of the file);
/// comments and `key:=value` pairs are skipped, a field given twice is an error.
fn read_fields(r: &mut impl BufRead, consumed: &mut u64) -> Result<Fields> {
    let magic = header_line(r, consumed, 1)?.unwrap_or_default();
    let ok_magic =
        magic.len() == 8 && magic.starts_with("NRRD000") && magic.as_bytes()[7].is_ascii_digit();
    if !ok_magic {
        return Err(Error::at_line(
            1,
            "not a NRRD file (first line must be NRRD000X)",
        ));
    }
    let mut fields: HashMap<String, (u64, String)> = HashMap::new();
    let mut lineno = 1;
    loop {
        lineno += 1;
        let Some(line) = header_line(r, consumed, lineno)? else {
            break;
        };
        if line.trim().is_empty() {
            break;
        }
        if line.starts_with('#') || line.contains(":=") {
            continue;
        }
        let (k, v) = line
            .split_once(':')
            .ok_or_else(|| Error::at_line(lineno, "expected 'field: value'"))?;
        let k = k.trim().to_ascii_lowercase();
        let k = if k == "datafile" {
            "data file".to_string()
        } else {
            k
        };
        if fields
            .insert(k.clone(), (lineno, v.trim().to_string()))
            .is_some()
        {
            return Err(Error::at_line(lineno, format!("field '{k}' given twice")));
        }
    }
    Ok(Fields(fields))
}

/// A format error at `line` (other errors as they are).
fn at(line: u64) -> impl Fn(Error) -> Error {
    move |e| match e {
        Error::Format { msg, .. } => Error::at_line(line, msg),
        e => e,
    }
}

/// The header's type, sizes, endianness, encoding, geometry and skips, checked in this order.
fn parse_header(fields: &Fields) -> Result<Header> {
    let (tl, tv) = fields.need("type")?;
    let ty = nrrd_type(tv).map_err(at(tl))?;
    let (dim, dims) = sizes(fields)?;
    let (sl, _) = fields.need("sizes")?;
    let (n, nbytes) = data_size(dims, ty).map_err(at(sl))?;
    let big = match fields.get("endian") {
        None => false,
        Some((l, v)) => match v.to_ascii_lowercase().as_str() {
            "little" => false,
            "big" => true,
            _ => return Err(Error::at_line(l, format!("bad endian '{v}'"))),
        },
    };
    let (el, ev) = fields.need("encoding")?;
    let enc = match ev.to_ascii_lowercase().as_str() {
        "raw" => Enc::Raw,
        "gzip" | "gz" => Enc::Gzip,
        "text" | "txt" | "ascii" => Enc::Text,
        other => {
            return Err(Error::unsupported(format!(
                "NRRD encoding '{other}' (line {el}); use raw, gzip or text"
            )))
        }
    };
    let spacing = spacing(fields, dim)?;
    let origin = origin(fields, dim)?;
    let orientation = orientation(fields, dim)?;
    let byte_skip: i64 = match fields.get("byte skip") {
        None => 0,
        Some((l, v)) => v
            .parse()
            .ok()
            .filter(|&b: &i64| b >= -1)
            .ok_or_else(|| Error::at_line(l, format!("bad byte skip '{v}'")))?,
    };
    let line_skip: u64 = match fields.get("line skip") {
        None => 0,
        Some((l, v)) => v
            .parse()
            .map_err(|_| Error::at_line(l, format!("bad line skip '{v}'")))?,
    };
    Ok(Header {
        ty,
        dims,
        n,
        nbytes,
        big,
        enc,
        spacing,
        origin,
        orientation,
        byte_skip,
        line_skip,
    })
}

/// `dimension` (2 or 3) and `sizes` (nz = 1 in 2D).
fn sizes(fields: &Fields) -> Result<(usize, [usize; 3])> {
    let (dl, dv) = fields.need("dimension")?;
    let dim: usize = dv
        .parse()
        .map_err(|_| Error::at_line(dl, format!("bad dimension '{dv}'")))?;
    if dim != 2 && dim != 3 {
        return Err(Error::unsupported(format!(
            "NRRD dimension {dim}: only 2 and 3 are supported"
        )));
    }
    let (sl, sv) = fields.need("sizes")?;
    let sizes: Vec<usize> = sv
        .split_whitespace()
        .map(|x| x.parse::<usize>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| Error::at_line(sl, format!("bad sizes '{sv}'")))?;
    if sizes.len() != dim {
        return Err(Error::at_line(
            sl,
            format!("{} sizes for dimension {dim}", sizes.len()),
        ));
    }
    let mut dims = [1usize; 3];
    dims[..dim].copy_from_slice(&sizes);
    Ok((dim, dims))
}

/// `spacings` (`nan` → 1), else the norms of the `space directions` (`none` → 1); each
/// positive and finite.
fn spacing(fields: &Fields, dim: usize) -> Result<[f64; 3]> {
    let mut spacing = [1.0f64; 3];
    if let Some((l, v)) = fields.get("spacings") {
        let s = numbers(v, l, "spacings")?;
        if s.len() != dim {
            return Err(Error::at_line(
                l,
                format!("{} spacings for dimension {dim}", s.len()),
            ));
        }
        for k in 0..dim {
            spacing[k] = if s[k].is_nan() { 1.0 } else { s[k].abs() };
        }
    } else if let Some((l, v)) = fields.get("space directions") {
        let d = vectors(v, l)?;
        if d.len() != dim {
            return Err(Error::at_line(
                l,
                format!("{} space directions for dimension {dim}", d.len()),
            ));
        }
        for k in 0..dim {
            if let Some(vec) = &d[k] {
                spacing[k] = vec.iter().map(|x| x * x).sum::<f64>().sqrt();
            }
        }
    }
    if let Some(k) = (0..3).find(|&k| !(spacing[k].is_finite() && spacing[k] > 0.0)) {
        return Err(Error::format(format!(
            "spacing of axis {k} is {}; it must be positive and finite",
            spacing[k]
        )));
    }
    Ok(spacing)
}

/// `space` (kept by name) and the unit `space directions` of a 3D volume (a 2D volume's
/// directions are dropped).
fn orientation(fields: &Fields, dim: usize) -> Result<Orientation> {
    let space = fields.get("space").map(|(_, v)| v.trim().to_string());
    let mut directions = None;
    if let (Some((l, v)), 3) = (fields.get("space directions"), dim) {
        if let [Some(a), Some(b), Some(c)] = vectors(v, l)?.as_slice() {
            if a.len() == 3 && b.len() == 3 && c.len() == 3 {
                let m = [[a[0], a[1], a[2]], [b[0], b[1], b[2]], [c[0], c[1], c[2]]];
                directions = Orientation::unit_directions(m).map_err(|e| Error::at_line(l, e))?;
            }
        }
    }
    Ok(Orientation {
        space,
        anatomical: None,
        directions,
    })
}

/// `space origin`, else `axis mins` (`nan` → 0), else 0; finite.
fn origin(fields: &Fields, dim: usize) -> Result<[f64; 3]> {
    let mut origin = [0.0f64; 3];
    if let Some((l, v)) = fields.get("space origin") {
        let o = vectors(v, l)?;
        let o = match o.as_slice() {
            [Some(o)] if o.len() == dim || (dim == 2 && o.len() == 3) => o.clone(),
            _ => {
                return Err(Error::at_line(
                    l,
                    format!("space origin must be one vector of {dim} numbers"),
                ))
            }
        };
        origin[..dim].copy_from_slice(&o[..dim]);
    } else if let Some((l, v)) = fields.get("axis mins") {
        let m = numbers(v, l, "axis mins")?;
        if m.len() != dim {
            return Err(Error::at_line(
                l,
                format!("{} axis mins for dimension {dim}", m.len()),
            ));
        }
        for k in 0..dim {
            origin[k] = if m[k].is_nan() { 0.0 } else { m[k] };
        }
    }
    if origin.iter().any(|o| !o.is_finite()) {
        return Err(Error::format("space origin is not finite"));
    }
    Ok(origin)
}

/// The samples from the data stream (`available` bytes), decoded as the header says.
fn read_samples_of(h: &Header, data_r: &mut Box<dyn BufRead>, available: u64) -> Result<Vec<f32>> {
    let (nbytes, byte_skip) = (h.nbytes, h.byte_skip);
    debug_assert_eq!(nbytes, h.n * h.ty.size());
    match h.enc {
        Enc::Raw => {
            let skip = if byte_skip == -1 {
                available.checked_sub(nbytes as u64).ok_or_else(|| {
                    Error::format(format!(
                        "data has {available} bytes, the header needs {nbytes}"
                    ))
                })?
            } else {
                byte_skip as u64
            };
            read_samples(data_r, available, Codec::Raw, skip, h.n, h.ty, h.big)
        }
        Enc::Gzip => {
            if byte_skip < 0 {
                return Err(Error::format("byte skip -1 needs raw encoding"));
            }
            let skip = byte_skip as u64;
            read_samples(data_r, available, Codec::Gzip, skip, h.n, h.ty, h.big)
        }
        Enc::Text => read_text(data_r, available, h.n),
    }
}

/// Text data: exactly `n` numbers separated by blanks or commas.
fn read_text(data_r: &mut Box<dyn BufRead>, available: u64, n: usize) -> Result<Vec<f32>> {
    let mut text = String::new();
    data_r
        .take(available)
        .read_to_string(&mut text)
        .map_err(|_| Error::format("text data is not valid UTF-8"))?;
    let mut vals = Vec::with_capacity(n.min(text.len() / 2 + 1));
    for tok in text
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
    {
        if vals.len() == n {
            return Err(Error::format(format!(
                "text data has more than the {n} samples of the header"
            )));
        }
        let x: f64 = tok
            .parse()
            .map_err(|_| Error::format(format!("text data: bad number '{tok}'")))?;
        vals.push(x as f32);
    }
    if vals.len() != n {
        return Err(Error::format(format!(
            "text data has {} samples, the header needs {n}",
            vals.len()
        )));
    }
    Ok(vals)
}

/// Writes a volume (with its data file beside it where the format has one), atomically.
pub fn write(path: &Path, v: &Volume) -> Result<()> {
    v.validate()?;
    let (o, s) = uniform(v)?;
    let ty = output_type(v);
    super::write_atomic(path, |w| {
        let e = super::werr;
        let space = match &v.orientation.space {
            Some(name) if !name.contains('\n') => format!("space: {name}"),
            _ => "space dimension: 3".to_string(),
        };
        let d =
            v.orientation
                .directions
                .unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let dirs = (0..3)
            .map(|a| {
                let x = d[a].map(|c| c * s[a] + 0.0);
                format!("({:?},{:?},{:?})", x[0], x[1], x[2])
            })
            .collect::<Vec<_>>()
            .join(" ");
        write!(
            w,
            "NRRD0004\n# written by morpho\ntype: {}\ndimension: 3\n{space}\n\
             sizes: {} {} {}\nspace directions: {dirs}\n\
             kinds: domain domain domain\nendian: little\nencoding: gzip\n\
             space origin: ({:?},{:?},{:?})\n\n",
            type_name(ty),
            v.dims[0],
            v.dims[1],
            v.dims[2],
            o[0],
            o[1],
            o[2]
        )
        .map_err(e)?;
        let mut gz = flate2::write::GzEncoder::new(&mut *w, flate2::Compression::new(6));
        for chunk in v.data.chunks(1 << 16) {
            gz.write_all(&encode(chunk, ty, false)).map_err(e)?;
        }
        gz.finish().map_err(e)?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_synonyms() {
        assert_eq!(nrrd_type("unsigned  char").unwrap(), Sample::U8);
        assert_eq!(nrrd_type("short int").unwrap(), Sample::I16);
        assert_eq!(nrrd_type("uint32_t").unwrap(), Sample::U32);
        assert_eq!(nrrd_type("signed char").unwrap(), Sample::I8);
        assert!(matches!(nrrd_type("int64"), Err(Error::Unsupported { .. })));
        assert!(nrrd_type("quaternion").is_err());
    }

    #[test]
    fn vector_parsing() {
        let v = vectors("(1,0,0) none (0, 0,2.5)", 3).unwrap();
        assert_eq!(v.len(), 3);
        assert!(v[1].is_none());
        assert_eq!(v[2].as_deref(), Some(&[0.0, 0.0, 2.5][..]));
        assert!(vectors("(1,0", 3).is_err());
        assert!(vectors("1,0,0", 3).is_err());
    }
}

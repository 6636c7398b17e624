//! Raw volume + JSON sidecar, and the sample decoding shared by the volume formats
//! (NRRD, MetaImage, sidecar).
//!
//! # Sidecar
//! The SPEC form is
//! `{"data":"NAME.raw","dims":[nx,ny,nz],"spacing":[…],"origin":[…],"dtype":"u8|i16|u16|i32|f32|f64","endian":"little|big"}`.
//! The sidecars shipped with the real data (`/work/shared/data/volumes/*.json`) use other
//! names, so each key has synonyms:
//!
//! | meaning | keys | notes |
//! |---|---|---|
//! | data file | `data`, `data_file`, `datafile`, `file` | relative to the sidecar's folder; gunzipped when the name ends in `.gz`, when `compression` starts with `gzip`, or when the data starts with the gzip magic |
//! | sizes | `dims`, `dims_xyz`, `sizes` | 3 positive integers (2 → nz = 1), x fastest |
//! | sample type | `dtype`, `type`, `data_type` | `u8 uint8 uchar`, `i8 int8`, `i16 int16 short`, `u16 uint16 ushort`, `i32 int32 int`, `u32 uint32 uint`, `f32 float32 float`, `f64 float64 double` |
//! | byte order | `endian`, `endianness`, `byte_order` | `little`/`big` (`le`/`be`); optional, default little; ignored for 1-byte types |
//! | spacing | `spacing`, `spacing_xyz`, `voxel_size` | optional, default 1 |
//! | origin | `origin`, `origin_xyz`, `offset` | optional, default 0; else the translation of an `affine*` 4×4 matrix |
//! | orientation | `space`, `directions`, `anatomical_orientation` | optional: the world space's NRRD name, the direction of each grid axis (3 vectors), MetaImage's code — see [`crate::volume::Orientation`]; written when the volume has them. Without them, an `affine*` matrix gives the axis directions (its columns, normalised; oblique allowed), its column lengths the spacing when no spacing key is given, and its key the space (`…ras…` → RAS, `…lps…` → LPS) |
//! | header bytes | `header_bytes`, `byte_skip`, `header_size` | bytes skipped at the start of the (decompressed) data |
//! | raw size | `raw_bytes` | optional; must equal header bytes + samples × sample size |
//!
//! Unknown keys (descriptions, checksums, iso levels) are ignored.
//!
//! # Samples
//! Samples become `f32` ([`Volume::data`]). `i8` is stored with source type `I16` and `u32`
//! with source type `F64` (the narrowest [`DType`] holding all their values); 64-bit integer
//! types are refused. Sizes claimed by a header are checked (with overflow checks and against
//! [`MAX_FILE_BYTES`](super::MAX_FILE_BYTES)) before anything is allocated, compressed data is
//! inflated to at most the expected size + 1 byte, and the data must have exactly the expected
//! size.
//!
//! # Writing
//! `NAME.json` + `NAME.raw`, both atomically (raw first). Samples are written in the source
//! type when every value converts back exactly, else as `f32`; always little endian. Volumes
//! with per-index axis coordinates cannot be written (these formats have uniform axes only).

use super::volstream::{Data, Head, VolumeStream};
use crate::volume::{Axes, DType, Volume};
use crate::{Error, Result};
use serde_json::{json, Map, Value};
use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};

/// Longest header line accepted by the text headers (NRRD, MetaImage).
pub(crate) const MAX_HEADER_LINE: usize = 64 << 10;
/// Most header bytes accepted.
pub(crate) const MAX_HEADER_BYTES: u64 = 4 << 20;

/// Sample types found in volume files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Sample {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Sample {
    pub(crate) fn size(self) -> usize {
        match self {
            Sample::I8 | Sample::U8 => 1,
            Sample::I16 | Sample::U16 => 2,
            Sample::I32 | Sample::U32 | Sample::F32 => 4,
            Sample::F64 => 8,
        }
    }
    pub(crate) fn source_dtype(self) -> DType {
        match self {
            Sample::U8 => DType::U8,
            Sample::I8 | Sample::I16 => DType::I16,
            Sample::U16 => DType::U16,
            Sample::I32 => DType::I32,
            Sample::F32 => DType::F32,
            Sample::U32 | Sample::F64 => DType::F64,
        }
    }
    fn of_dtype(d: DType) -> Sample {
        match d {
            DType::U8 => Sample::U8,
            DType::I16 => Sample::I16,
            DType::U16 => Sample::U16,
            DType::I32 => Sample::I32,
            DType::F32 => Sample::F32,
            DType::F64 => Sample::F64,
        }
    }
    /// The SPEC name (`u8`, `i16`, …).
    pub(crate) fn name(self) -> &'static str {
        match self {
            Sample::I8 => "i8",
            Sample::U8 => "u8",
            Sample::I16 => "i16",
            Sample::U16 => "u16",
            Sample::I32 => "i32",
            Sample::U32 => "u32",
            Sample::F32 => "f32",
            Sample::F64 => "f64",
        }
    }
    /// Parses the usual names of a sample type (case-insensitive).
    pub(crate) fn parse(s: &str) -> Result<Sample> {
        let s = s.trim().to_ascii_lowercase();
        Ok(match s.as_str() {
            "u8" | "uint8" | "uchar" | "unsigned char" | "uint8_t" => Sample::U8,
            "i8" | "int8" | "char" | "signed char" | "int8_t" => Sample::I8,
            "i16" | "int16" | "short" | "int16_t" => Sample::I16,
            "u16" | "uint16" | "ushort" | "unsigned short" | "uint16_t" => Sample::U16,
            "i32" | "int32" | "int" | "int32_t" => Sample::I32,
            "u32" | "uint32" | "uint" | "unsigned int" | "uint32_t" => Sample::U32,
            "f32" | "float32" | "float" | "single" => Sample::F32,
            "f64" | "float64" | "double" => Sample::F64,
            "i64" | "int64" | "u64" | "uint64" => {
                return Err(Error::unsupported(format!(
                    "sample type '{s}' (64-bit integers) is not supported"
                )))
            }
            _ => return Err(Error::unsupported(format!("unknown sample type '{s}'"))),
        })
    }
}

/// Number of samples and of data bytes for `dims`, refusing empty volumes and sizes that
/// overflow. Whether they fit in memory is [`memory_for`]'s question (a streamed volume
/// never is in memory whole).
pub(crate) fn data_size(dims: [usize; 3], ty: Sample) -> Result<(usize, usize)> {
    if dims.contains(&0) {
        return Err(Error::format(format!("volume sizes {dims:?} contain 0")));
    }
    let n = dims[0]
        .checked_mul(dims[1])
        .and_then(|v| v.checked_mul(dims[2]));
    let bytes = n.and_then(|n| n.checked_mul(ty.size()));
    match (n, bytes) {
        (Some(n), Some(b)) if b as u64 <= u64::MAX / 8 => Ok((n, b)),
        _ => Err(Error::invalid(format!(
            "volume sizes {dims:?} of {} overflow",
            ty.name()
        ))),
    }
}

/// Refuses to read a whole volume of `dims` samples of `ty` into memory when its samples (as
/// f32, plus the file's bytes while decoding) pass the memory limit or [`super::MAX_FILE_BYTES`].
pub(crate) fn memory_for(dims: [usize; 3], ty: Sample) -> Result<()> {
    let (n, b) = data_size(dims, ty)?;
    let need = (n as u64).saturating_mul(4).saturating_add(b as u64);
    super::memory::check(need, &format!("a {dims:?} volume of {}", ty.name()))?;
    if b as u64 > super::MAX_FILE_BYTES {
        return Err(Error::invalid(format!(
            "volume sizes {dims:?} of {} need more memory than morpho reads",
            ty.name()
        )));
    }
    Ok(())
}

/// Converts exactly `n` samples from `bytes` (whose length must be `n * size`).
pub(crate) fn decode(bytes: &[u8], ty: Sample, big: bool) -> Vec<f32> {
    let mut out = Vec::with_capacity(bytes.len() / ty.size());
    decode_into(bytes, ty, big, &mut out);
    out
}

/// Appends the samples of `bytes` (a whole number of them) to `out`.
pub(crate) fn decode_into(bytes: &[u8], ty: Sample, big: bool, out: &mut Vec<f32>) {
    macro_rules! conv {
        ($t:ty, $n:expr) => {
            out.extend(bytes.chunks_exact($n).map(|c| {
                let mut a = [0u8; $n];
                a.copy_from_slice(c);
                (if big {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }) as f32
            }))
        };
    }
    match ty {
        Sample::U8 => out.extend(bytes.iter().map(|&b| b as f32)),
        Sample::I8 => out.extend(bytes.iter().map(|&b| b as i8 as f32)),
        Sample::I16 => conv!(i16, 2),
        Sample::U16 => conv!(u16, 2),
        Sample::I32 => conv!(i32, 4),
        Sample::U32 => conv!(u32, 4),
        Sample::F32 => conv!(f32, 4),
        Sample::F64 => conv!(f64, 8),
    }
}

/// Compression of a data stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Codec {
    Raw,
    Gzip,
    Zlib,
}

/// The sample bytes of a data stream: checks that `available` raw or compressed bytes can hold
/// `skip` bytes to discard and then `expected` bytes (raw data must have exactly that size;
/// deflate cannot compress better than about 1032:1), discards the `skip` bytes (after
/// decompression for `codec` ≠ Raw), and returns the reader positioned at the first sample
/// byte — limited to the expected bytes for raw data, the decompressor otherwise (whose end
/// the caller checks). Shared by the whole read ([`read_samples`]) and the slice-by-slice
/// stream ([`super::VolumeStream`]).
pub(crate) fn sample_reader<'a>(
    r: impl Read + 'a,
    available: u64,
    codec: Codec,
    skip: u64,
    expected: u64,
) -> Result<Box<dyn Read + 'a>> {
    let want = skip
        .checked_add(expected)
        .ok_or_else(|| Error::format("bytes to skip are out of range"))?;
    match codec {
        Codec::Raw => {
            if available != want {
                return Err(Error::format(format!(
                    "data has {} bytes, the header needs {want} ({} of samples{})",
                    available,
                    expected,
                    if skip > 0 {
                        format!(" after {skip} skipped")
                    } else {
                        String::new()
                    }
                )));
            }
            let mut r = r.take(want);
            std::io::copy(&mut (&mut r).take(skip), &mut std::io::sink())
                .map_err(|e| Error::format(format!("cannot read data: {e}")))?;
            Ok(Box::new(r))
        }
        Codec::Gzip | Codec::Zlib => {
            if want > available.saturating_mul(1100).saturating_add(1 << 16) {
                return Err(Error::format(format!(
                    "{available} compressed bytes cannot hold the {want} bytes the header needs"
                )));
            }
            let src = r.take(available);
            let mut dec: Box<dyn Read + 'a> = match codec {
                Codec::Gzip => Box::new(flate2::read::MultiGzDecoder::new(src)),
                _ => Box::new(flate2::read::ZlibDecoder::new(src)),
            };
            let copied = std::io::copy(&mut (&mut dec).take(skip), &mut std::io::sink())
                .map_err(|e| Error::format(format!("bad compressed data: {e}")))?;
            if copied < skip {
                return Err(Error::format(
                    "decompressed data is shorter than the bytes to skip",
                ));
            }
            Ok(dec)
        }
    }
}

/// Reads `skip` bytes to discard and then exactly `n` samples of type `ty` from `r` (at most
/// `available` compressed or raw bytes), decompressing with `codec` ([`sample_reader`]) and
/// decoding to `f32` as the bytes arrive: they pass through a 1 MiB buffer, so the volume is
/// held once, not once as bytes and again as samples (issue 23 item 4). Decompression stops
/// one byte after the expected size, so a gzip bomb cannot allocate more; too little or too
/// much data is an error. The caller has checked `n` samples against the memory limit.
pub(crate) fn read_samples(
    r: impl Read,
    available: u64,
    codec: Codec,
    skip: u64,
    n: usize,
    ty: Sample,
    big: bool,
) -> Result<Vec<f32>> {
    let size = ty.size();
    let expected = n
        .checked_mul(size)
        .ok_or_else(|| Error::format("sample count is out of range"))?;
    let dec = sample_reader(r, available, codec, skip, expected as u64)?;
    let mut dec = dec.take(expected as u64 + 1);
    let bad = |e: std::io::Error| match codec {
        Codec::Raw => Error::format(format!("cannot read data: {e}")),
        _ => Error::format(format!("bad compressed data: {e}")),
    };
    let mut out: Vec<f32> = Vec::with_capacity(n);
    // filled completely: one page fault per 2 MiB instead of per 4 KiB (issue 23 item 4)
    crate::util::advise_huge_pages(&mut out);
    // `have` bytes at its start (less than one sample) are not decoded yet; there is always
    // room for more
    let mut buf = vec![0u8; (1 << 20).min(expected.saturating_add(8))];
    let (mut have, mut total) = (0usize, 0usize);
    loop {
        let k = match dec.read(&mut buf[have..]) {
            Ok(0) => break,
            Ok(k) => k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(bad(e)),
        };
        total += k;
        if total > expected {
            break;
        }
        have += k;
        let whole = have - have % size;
        decode_into(&buf[..whole], ty, big, &mut out);
        buf.copy_within(whole..have, 0);
        have -= whole;
    }
    if total != expected {
        return Err(Error::format(format!(
            "data has {}{} bytes, dims × sample size need {expected}",
            if total > expected { "more than " } else { "" },
            total.min(expected)
        )));
    }
    debug_assert_eq!(out.len(), n);
    Ok(out)
}

/// Opens a data file (or a header) and returns it with its length ([`super::guard::open_input`]).
pub(crate) fn open_data(path: &Path) -> Result<(std::fs::File, u64)> {
    super::guard::open_input(path)
}

/// True when the file starts with the gzip magic bytes.
pub(crate) fn has_gzip_magic(path: &Path) -> bool {
    let mut m = [0u8; 2];
    open_data(path).is_ok_and(|(mut f, _)| f.read_exact(&mut m).is_ok()) && m == [0x1f, 0x8b]
}

/// Reads one header line (without line end) of at most [`MAX_HEADER_LINE`] bytes; `None` at
/// end of input. `consumed` counts the bytes read.
pub(crate) fn header_line(
    r: &mut impl BufRead,
    consumed: &mut u64,
    lineno: u64,
) -> Result<Option<String>> {
    let cannot = |e: std::io::Error| Error::at_line(lineno, format!("cannot read header: {e}"));
    let mut buf = Vec::new();
    // the line's end: LF, CRLF or a bare CR (old Mac text); None at the end of the stream
    let mut ended = None;
    while ended.is_none() {
        let avail = r.fill_buf().map_err(cannot)?;
        if avail.is_empty() {
            break;
        }
        let room = MAX_HEADER_LINE + 1 - buf.len();
        let window = &avail[..avail.len().min(room)];
        let (take, end) = match window.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(e) => (e + 1, Some(window[e])),
            None => (window.len(), None),
        };
        buf.extend_from_slice(&window[..take]);
        r.consume(take);
        *consumed += take as u64;
        ended = end;
        if ended.is_none() && buf.len() > MAX_HEADER_LINE {
            return Err(Error::at_line(
                lineno,
                format!("header line longer than {MAX_HEADER_LINE} bytes"),
            ));
        }
    }
    if buf.is_empty() {
        return Ok(None);
    }
    if ended == Some(b'\r') {
        // CRLF: the LF belongs to this line
        let avail = r.fill_buf().map_err(cannot)?;
        if avail.first() == Some(&b'\n') {
            r.consume(1);
            *consumed += 1;
        }
    }
    if ended.is_some() {
        buf.pop();
    }
    if *consumed > MAX_HEADER_BYTES {
        return Err(Error::at_line(lineno, "header is too long"));
    }
    String::from_utf8(buf)
        .map(Some)
        .map_err(|_| Error::at_line(lineno, "header line is not valid UTF-8 text"))
}

/// Origin and spacing of a uniform volume (per-index axes cannot be written).
pub(crate) fn uniform(v: &Volume) -> Result<([f64; 3], [f64; 3])> {
    match &v.axes {
        Axes::Uniform { origin, spacing } => Ok((*origin, *spacing)),
        Axes::Coords(_) => Err(Error::unsupported(
            "this volume format stores uniform axes only; the volume has per-index coordinates",
        )),
    }
}

/// The type to write: the source type when all samples convert back exactly, else f32.
pub(crate) fn output_type(v: &Volume) -> Sample {
    let ty = Sample::of_dtype(v.source_dtype);
    let fits = |lo: f64, hi: f64| {
        v.data
            .iter()
            .all(|&x| x.fract() == 0.0 && (x as f64) >= lo && (x as f64) <= hi)
    };
    let ok = match ty {
        Sample::U8 => fits(0.0, 255.0),
        Sample::I8 => fits(-128.0, 127.0),
        Sample::I16 => fits(-32768.0, 32767.0),
        Sample::U16 => fits(0.0, 65535.0),
        Sample::I32 => fits(-2147483648.0, 2147483647.0),
        Sample::U32 => fits(0.0, 4294967295.0),
        Sample::F32 | Sample::F64 => true,
    };
    if ok {
        ty
    } else {
        Sample::F32
    }
}

/// Encodes the samples as `ty` (which [`output_type`] chose), little or big endian.
pub(crate) fn encode(data: &[f32], ty: Sample, big: bool) -> Vec<u8> {
    let mut out = Vec::with_capacity(data.len() * ty.size());
    macro_rules! put {
        ($v:expr) => {
            if big {
                out.extend_from_slice(&$v.to_be_bytes())
            } else {
                out.extend_from_slice(&$v.to_le_bytes())
            }
        };
    }
    for &x in data {
        match ty {
            Sample::U8 => out.push(x as u8),
            Sample::I8 => out.push(x as i8 as u8),
            Sample::I16 => put!(x as i16),
            Sample::U16 => put!(x as u16),
            Sample::I32 => put!(x as i32),
            Sample::U32 => put!(x as u32),
            Sample::F32 => put!(x),
            Sample::F64 => put!(x as f64),
        }
    }
    out
}

/// Resolves a data file name relative to the folder of `header`, never outside it
/// ([`super::guard::data_file`]).
pub(crate) fn beside(header: &Path, name: &str) -> Result<PathBuf> {
    super::guard::data_file(header, name)
}

fn get<'a>(o: &'a Map<String, Value>, keys: &[&str]) -> Option<(&'a str, &'a Value)> {
    keys.iter()
        .find_map(|k| o.get_key_value(*k).map(|(k, v)| (k.as_str(), v)))
}

fn numbers(key: &str, v: &Value, n: usize) -> Result<Vec<f64>> {
    let a = v
        .as_array()
        .ok_or_else(|| Error::format(format!("\"{key}\" must be an array of numbers")))?;
    if a.len() != n {
        return Err(Error::format(format!(
            "\"{key}\" has {} numbers, expected {n}",
            a.len()
        )));
    }
    a.iter()
        .map(|x| {
            x.as_f64()
                .filter(|f| f.is_finite())
                .ok_or_else(|| Error::format(format!("\"{key}\" holds a non-number")))
        })
        .collect()
}

/// A 4×4 (or 3×4) voxel-to-world affine from a sidecar key starting with `affine`
/// (`affine_ijk_to_ras_mm`, `affine_ijk_to_world_mm`, …): column `a` of its 3×3 part is
/// spacing × direction of grid axis `a`, the last column the origin.
struct Affine {
    origin: [f64; 3],
    spacing: [f64; 3],
    /// Unit axis directions, `None` when they are the identity.
    directions: Option<[[f64; 3]; 3]>,
    /// The NRRD space named by the key (`…ras…` → RAS, `…lps…` → LPS), else unnamed.
    space: Option<&'static str>,
}

fn affine(o: &Map<String, Value>) -> Result<Option<Affine>> {
    let Some((key, v)) = o.iter().find(|(k, _)| k.starts_with("affine")) else {
        return Ok(None);
    };
    let bad = || Error::format(format!("\"{key}\" must be a 4×4 matrix of finite numbers"));
    let rows = v
        .as_array()
        .filter(|r| r.len() == 3 || r.len() == 4)
        .ok_or_else(bad)?;
    let mut m = [[0.0; 4]; 3];
    for i in 0..3 {
        let r = rows[i]
            .as_array()
            .filter(|r| r.len() == 4)
            .ok_or_else(bad)?;
        for j in 0..4 {
            m[i][j] = r[j].as_f64().filter(|x| x.is_finite()).ok_or_else(bad)?;
        }
    }
    let column = |a: usize| [m[0][a], m[1][a], m[2][a]];
    let spacing = [0, 1, 2].map(|a| column(a).iter().map(|x| x * x).sum::<f64>().sqrt());
    let directions = crate::volume::Orientation::unit_directions([column(0), column(1), column(2)])
        .map_err(|e| Error::format(format!("\"{key}\": {e}")))?;
    let k = key.to_ascii_lowercase();
    let space = if k.contains("ras") {
        Some("right-anterior-superior")
    } else if k.contains("lps") {
        Some("left-posterior-superior")
    } else {
        None
    };
    Ok(Some(Affine {
        origin: [m[0][3], m[1][3], m[2][3]],
        spacing,
        directions,
        space,
    }))
}

/// True when a parsed JSON document looks like a volume sidecar (an object with one of the
/// size keys `dims`, `dims_xyz`, `sizes`) — for dispatch in [`super::read_any`], which today
/// only checks `dims` and so misses the shipped `*.json` sidecars (`dims_xyz`).
pub(crate) fn is_sidecar(v: &Value) -> bool {
    v.as_object()
        .is_some_and(|o| get(o, &["dims", "dims_xyz", "sizes"]).is_some())
}

/// The sidecar parsed, and its data file opened (found relative to `path`).
fn source(path: &Path) -> Result<(Head, Data)> {
    let mut bytes = Vec::new();
    let (f, _) = open_data(path)?;
    f.take(MAX_HEADER_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > MAX_HEADER_BYTES {
        return Err(Error::invalid(
            "sidecar JSON is too large (more than 4 MiB)",
        ));
    }
    let v: Value = serde_json::from_slice(&bytes)
        .map_err(|e| Error::at_line(e.line() as u64, format!("bad JSON: {e}")))?;
    let o = v
        .as_object()
        .ok_or_else(|| Error::format("a volume sidecar must be a JSON object"))?;
    let (_, data) = get(o, &["data", "data_file", "datafile", "file"])
        .ok_or_else(|| Error::format("sidecar has no \"data\" (data file name)"))?;
    let data = data
        .as_str()
        .ok_or_else(|| Error::format("\"data\" must be a file name"))?;
    let (dkey, dims_v) = get(o, &["dims", "dims_xyz", "sizes"])
        .ok_or_else(|| Error::format("sidecar has no \"dims\""))?;
    let dims_a = dims_v
        .as_array()
        .ok_or_else(|| Error::format(format!("\"{dkey}\" must be an array")))?;
    if dims_a.len() != 3 && dims_a.len() != 2 {
        return Err(Error::format(format!(
            "\"{dkey}\" has {} sizes, expected 3 (or 2)",
            dims_a.len()
        )));
    }
    let mut dims = [1usize; 3];
    for (k, d) in dims_a.iter().enumerate() {
        dims[k] = d
            .as_u64()
            .filter(|&d| d > 0 && d <= u32::MAX as u64)
            .ok_or_else(|| Error::format(format!("\"{dkey}\" must hold positive integers")))?
            as usize;
    }
    let nd = dims_a.len();
    let (_, ty) = get(o, &["dtype", "type", "data_type"])
        .ok_or_else(|| Error::format("sidecar has no \"dtype\""))?;
    let ty = Sample::parse(
        ty.as_str()
            .ok_or_else(|| Error::format("\"dtype\" must be a string"))?,
    )?;
    let big = match get(o, &["endian", "endianness", "byte_order"]) {
        None => false,
        Some((k, e)) => {
            let e = e
                .as_str()
                .ok_or_else(|| Error::format(format!("\"{k}\" must be a string")))?
                .to_ascii_lowercase();
            match e.as_str() {
                "little" | "le" | "little-endian" | "little_endian" => false,
                "big" | "be" | "big-endian" | "big_endian" => true,
                _ if ty.size() == 1 => false,
                _ => {
                    return Err(Error::format(format!(
                        "\"{k}\" must be \"little\" or \"big\", not \"{e}\""
                    )))
                }
            }
        }
    };
    let affine = if nd == 3 { affine(o)? } else { None };
    let mut spacing = [1.0; 3];
    match get(o, &["spacing", "spacing_xyz", "voxel_size"]) {
        Some((k, s)) => spacing[..nd].copy_from_slice(&numbers(k, s, nd)?),
        None => {
            if let Some(a) = &affine {
                spacing = a.spacing;
            }
        }
    }
    let mut origin = [0.0; 3];
    match get(o, &["origin", "origin_xyz", "offset"]) {
        Some((k, s)) => origin[..nd].copy_from_slice(&numbers(k, s, nd)?),
        None => {
            if let Some(a) = &affine {
                origin = a.origin;
            }
        }
    }
    let skip = match get(o, &["header_bytes", "byte_skip", "header_size"]) {
        None => 0,
        Some((k, s)) => s
            .as_u64()
            .ok_or_else(|| Error::format(format!("\"{k}\" must be a non-negative integer")))?,
    };
    let (n, nbytes) = data_size(dims, ty)?;
    if let Some((k, rb)) = get(o, &["raw_bytes"]) {
        let rb = rb
            .as_u64()
            .ok_or_else(|| Error::format(format!("\"{k}\" must be an integer")))?;
        if Some(rb) != skip.checked_add(nbytes as u64) {
            return Err(Error::format(format!(
                "\"raw_bytes\" is {rb}, but dims {dims:?} of {} need {}",
                ty.name(),
                skip as u128 + nbytes as u128
            )));
        }
    }
    let gz_key = get(o, &["compression"])
        .and_then(|(_, c)| c.as_str())
        .map(|c| c.trim().to_ascii_lowercase());
    let dpath = beside(path, data)?;
    let codec = match gz_key.as_deref() {
        Some(c) if c.starts_with("gzip") || c.starts_with("gz") => Codec::Gzip,
        Some(c) if c.starts_with("zlib") => Codec::Zlib,
        Some(c) if c.starts_with("none") || c.starts_with("raw") => Codec::Raw,
        Some(c) => return Err(Error::unsupported(format!("compression \"{c}\""))),
        None if data.to_ascii_lowercase().ends_with(".gz") || has_gzip_magic(&dpath) => Codec::Gzip,
        None => Codec::Raw,
    };
    let text = |k: &str| o.get(k).and_then(|v| v.as_str()).map(str::to_string);
    // explicit `space`/`directions` keys win over what an affine implies
    let mut orientation = crate::volume::Orientation {
        space: text("space").or_else(|| affine.as_ref()?.space.map(str::to_string)),
        anatomical: text("anatomical_orientation"),
        directions: affine.as_ref().and_then(|a| a.directions),
    };
    if let Some(d) = o.get("directions") {
        let rows = d
            .as_array()
            .filter(|r| r.len() == 3)
            .and_then(|r| {
                r.iter()
                    .map(|row| {
                        let row = row.as_array().filter(|x| x.len() == 3)?;
                        Some([row[0].as_f64()?, row[1].as_f64()?, row[2].as_f64()?])
                    })
                    .collect::<Option<Vec<_>>>()
            })
            .ok_or_else(|| {
                Error::format("\"directions\" must be three vectors of three numbers")
            })?;
        orientation.directions =
            crate::volume::Orientation::unit_directions([rows[0], rows[1], rows[2]])
                .map_err(|e| Error::format(format!("\"directions\": {e}")))?;
    }
    let _ = (n, nbytes);
    let (f, len) = open_data(&dpath)?;
    Ok((
        Head {
            dims,
            axes: Axes::Uniform { origin, spacing },
            orientation,
            ty,
            big,
        },
        Data {
            reader: Box::new(std::io::BufReader::new(f)),
            available: len,
            codec,
            skip,
            path: dpath,
        },
    ))
}

/// Reads a volume from its sidecar (the data file is found relative to `path`).
pub fn read(path: &Path) -> Result<Volume> {
    let (h, d) = source(path)?;
    load(h, d)
}

/// The whole volume from a parsed header and its opened data (MetaImage and sidecars; NRRD
/// has its text encoding besides): the memory check, then every sample decoded to `f32`.
pub(crate) fn load(h: Head, d: Data) -> Result<Volume> {
    memory_for(h.dims, h.ty)?;
    let (n, nbytes) = data_size(h.dims, h.ty)?;
    debug_assert_eq!(nbytes, n * h.ty.size());
    let samples = read_samples(d.reader, d.available, d.codec, d.skip, n, h.ty, h.big)
        .map_err(|e| e.with_path(&d.path))?;
    Ok(Volume {
        dims: h.dims,
        axes: h.axes,
        data: samples,
        source_dtype: h.ty.source_dtype(),
        orientation: h.orientation,
    })
}

/// Opens the samples for reading slice by slice ([`super::open_volume_stream`]).
pub(crate) fn open_stream(path: &Path) -> Result<VolumeStream> {
    let (h, d) = source(path)?;
    VolumeStream::new(h, d)
}

/// Writes a volume (with its data file beside it where the format has one), atomically.
pub fn write(path: &Path, v: &Volume) -> Result<()> {
    v.validate()?;
    let (origin, spacing) = uniform(v)?;
    let raw_path = path.with_extension("raw");
    let raw_name = raw_path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| Error::invalid("the sidecar name must be valid UTF-8"))?
        .to_string();
    let ty = output_type(v);
    // both files may be written, and neither is an input, before either is
    super::guard::check_outputs(&[&raw_path, path])?;
    super::write_atomic(&raw_path, |w| {
        for chunk in v.data.chunks(1 << 16) {
            w.write_all(&encode(chunk, ty, false))
                .map_err(super::werr)?;
        }
        Ok(())
    })
    .map_err(|e| e.with_path(&raw_path))?;
    let mut doc = json!({
        "data": raw_name,
        "dims": v.dims,
        "spacing": spacing,
        "origin": origin,
        "dtype": ty.name(),
        "endian": "little",
    });
    if let Some(space) = &v.orientation.space {
        doc["space"] = json!(space);
    }
    if let Some(d) = v.orientation.directions {
        doc["directions"] = json!(d);
    }
    if let Some(a) = &v.orientation.anatomical {
        doc["anatomical_orientation"] = json!(a);
    }
    super::write_atomic(path, |w| {
        serde_json::to_writer_pretty(&mut *w, &doc)
            .map_err(|e| Error::invalid(format!("JSON: {e}")))?;
        writeln!(w).map_err(super::werr)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decode_encode_all_types_both_endians() {
        let vals = [0.0f32, 1.0, 100.0, 127.0];
        for ty in [
            Sample::U8,
            Sample::I8,
            Sample::I16,
            Sample::U16,
            Sample::I32,
            Sample::U32,
            Sample::F32,
            Sample::F64,
        ] {
            for big in [false, true] {
                let b = encode(&vals, ty, big);
                assert_eq!(b.len(), vals.len() * ty.size());
                assert_eq!(decode(&b, ty, big), vals.to_vec(), "{ty:?} {big}");
            }
        }
        assert_eq!(decode(&[0xff], Sample::I8, false), vec![-1.0]);
        assert_eq!(decode(&[0x01, 0x00], Sample::I16, true), vec![256.0]);
    }

    #[test]
    fn sidecar_detection() {
        assert!(is_sidecar(&json!({"dims_xyz": [1, 2, 3]})));
        assert!(is_sidecar(&json!({"dims": [1, 2, 3]})));
        assert!(!is_sidecar(&json!({"type": "Polygon"})));
        assert!(!is_sidecar(&json!([[0, 1]])));
    }

    #[test]
    fn sizes_are_checked_before_allocation() {
        assert!(memory_for([100000, 100000, 100000], Sample::U8).is_err());
        assert!(data_size([usize::MAX, 2, 2], Sample::F64).is_err());
        assert!(data_size([0, 2, 2], Sample::U8).is_err());
        assert_eq!(data_size([2, 3, 4], Sample::I16).unwrap(), (24, 48));
        // claimed 8 GB from 100 compressed bytes: refused before inflating
        let err = read_samples(
            &[0u8; 100][..],
            100,
            Codec::Gzip,
            0,
            1 << 32,
            Sample::U8,
            false,
        )
        .unwrap_err();
        assert!(err.to_string().contains("compressed"), "{err}");
    }

    #[test]
    fn bomb_is_cut_at_expected_plus_one() {
        use std::io::Write;
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&vec![0u8; 1 << 20]).unwrap();
        let gz = enc.finish().unwrap();
        let n = gz.len() as u64;
        let u8s = |bytes: &[u8], avail: u64, count: usize| {
            read_samples(bytes, avail, Codec::Gzip, 0, count, Sample::U8, false)
        };
        let err = u8s(&gz, n, 1000).unwrap_err();
        assert!(err.to_string().contains("more than"), "{err}");
        let ok = u8s(&gz, n, 1 << 20).unwrap();
        assert_eq!(ok.len(), 1 << 20);
        assert!(u8s(&gz[..gz.len() / 2], n / 2, 1 << 20).is_err());
    }

    /// A reader handing out `step` bytes per call: samples straddle every read.
    struct Trickle<'a> {
        bytes: &'a [u8],
        step: usize,
    }

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let k = self.step.min(buf.len()).min(self.bytes.len());
            buf[..k].copy_from_slice(&self.bytes[..k]);
            self.bytes = &self.bytes[k..];
            Ok(k)
        }
    }

    #[test]
    fn streamed_samples_equal_the_whole_decode() {
        // every type and byte order, reads of 1..9 bytes (samples split across reads), more
        // than one 1 MiB buffer, a skip: the streamed decode equals decoding the whole array
        let vals: Vec<f32> = (0..300_000).map(|i| ((i * 7919) % 255) as f32).collect();
        for ty in [
            Sample::U8,
            Sample::I16,
            Sample::U16,
            Sample::F32,
            Sample::F64,
        ] {
            for big in [false, true] {
                let mut b = vec![9u8; 3];
                b.extend(encode(&vals, ty, big));
                for step in [1, 3, 5, 8, 9, usize::MAX] {
                    let r = Trickle { bytes: &b, step };
                    let got = read_samples(r, b.len() as u64, Codec::Raw, 3, vals.len(), ty, big)
                        .unwrap();
                    assert_eq!(got, decode(&b[3..], ty, big), "{ty:?} {big} {step}");
                }
                // one byte short of the last sample: refused
                let r = Trickle {
                    bytes: &b[..b.len() - 1],
                    step: 7,
                };
                let short = read_samples(r, b.len() as u64, Codec::Raw, 3, vals.len(), ty, big);
                assert!(short.is_err());
            }
        }
    }
}

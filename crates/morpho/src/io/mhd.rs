//! MetaImage volumes (ITK/VTK `.mhd` header + data file, or `.mha` with the data inside).
//!
//! # Reading
//! `Key = Value` lines (keys case-insensitive; each line bounded to 64 KiB, the header to
//! 4 MiB); the header ends with `ElementDataFile`, which must come last.
//! - `ObjectType` (if present) must be `Image`; `NDims` 3, or 2 (then nz = 1);
//!   `DimSize` one positive integer per axis; `ElementNumberOfChannels` must be 1;
//!   `BinaryData = False` (ASCII data) is refused.
//! - `ElementSpacing`, else `ElementSize` (default 1); `Offset`, else `Origin`, else `Position`
//!   (default 0). `TransformMatrix` (the i-th triple is the direction of grid axis i, as ITK
//!   reads it) becomes [`crate::volume::Orientation::directions`] (normalized),
//!   `AnatomicalOrientation` is kept as given, and the world space is LPS (ITK's convention);
//!   `CenterOfRotation` is ignored.
//! - `ElementType`: `MET_UCHAR`, `MET_CHAR`, `MET_SHORT`, `MET_USHORT`, `MET_INT`, `MET_UINT`,
//!   `MET_FLOAT`, `MET_DOUBLE` (`MET_CHAR` → source type `I16`, `MET_UINT` → `F64`, see
//!   [`super::rawjson`]); 64-bit types are refused.
//! - `ElementByteOrderMSB` / `BinaryDataByteOrderMSB` (`True` = big endian; default little).
//! - `CompressedData = True`: the data are a **zlib** stream (RFC 1950, not gzip), optionally
//!   of `CompressedDataSize` bytes.
//! - `HeaderSize`: bytes skipped at the start of the data file; `-1` (uncompressed only) means
//!   the data are the last bytes of the file.
//! - `ElementDataFile = LOCAL`: the data follow the header line in the same file; otherwise a
//!   file name relative to the header's folder (`LIST` and `%d` series are refused).
//!
//! The data must have exactly the size implied by `DimSize` × element size (after decompression,
//! which stops one byte past that size).
//!
//! # Writing
//! `TransformMatrix` when the directions are not the identity and `AnatomicalOrientation` when
//! known; a volume in RAS or LAS space (from NRRD) is converted to LPS (x, and y for RAS,
//! negated in the origin and the directions). `NAME.mhd` + `NAME.raw` beside it (both atomic, raw first), or a single `NAME.mha` with
//! `ElementDataFile = LOCAL`; uncompressed, little endian, samples in the source type when
//! lossless, else `MET_FLOAT`.
//!
//! Complexity: linear in the data size.

use super::rawjson::{
    beside, data_size, encode, header_line, open_data, output_type, uniform, Codec, Sample,
};
use super::volstream::{Data, Head, VolumeStream};
use crate::volume::{Axes, Orientation, Volume};
use crate::{Error, Result};
use std::collections::HashMap;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

fn met_type(s: &str) -> Result<Sample> {
    Ok(match s.trim().to_ascii_uppercase().as_str() {
        "MET_UCHAR" => Sample::U8,
        "MET_CHAR" => Sample::I8,
        "MET_SHORT" => Sample::I16,
        "MET_USHORT" => Sample::U16,
        "MET_INT" => Sample::I32,
        "MET_UINT" => Sample::U32,
        "MET_FLOAT" => Sample::F32,
        "MET_DOUBLE" => Sample::F64,
        "MET_LONG_LONG" | "MET_ULONG_LONG" | "MET_LONG" | "MET_ULONG" => {
            return Err(Error::unsupported(format!(
                "MetaImage element type {s} (64-bit or platform-sized integers) is not supported"
            )))
        }
        _ => return Err(Error::format(format!("unknown ElementType '{s}'"))),
    })
}

fn met_name(t: Sample) -> &'static str {
    match t {
        Sample::U8 => "MET_UCHAR",
        Sample::I8 => "MET_CHAR",
        Sample::I16 => "MET_SHORT",
        Sample::U16 => "MET_USHORT",
        Sample::I32 => "MET_INT",
        Sample::U32 => "MET_UINT",
        Sample::F32 => "MET_FLOAT",
        Sample::F64 => "MET_DOUBLE",
    }
}

fn boolean(v: &str, line: u64) -> Result<bool> {
    match v.trim().to_ascii_lowercase().as_str() {
        "true" | "1" | "yes" => Ok(true),
        "false" | "0" | "no" => Ok(false),
        _ => Err(Error::at_line(
            line,
            format!("expected True or False, not '{v}'"),
        )),
    }
}

/// The header parsed, and its data opened (a detached file is found relative to `path`).
fn source(path: &Path) -> Result<(Head, Data)> {
    let (f, file_len) = open_data(path)?;
    let mut r = BufReader::new(f);
    let mut consumed = 0u64;
    let mut fields: HashMap<String, (u64, String)> = HashMap::new();
    let mut lineno = 0;
    let data_file = loop {
        lineno += 1;
        let line = header_line(&mut r, &mut consumed, lineno)?.ok_or_else(|| {
            if lineno == 1 {
                Error::format("empty MetaImage header")
            } else {
                Error::at_line(lineno, "header ends without ElementDataFile")
            }
        })?;
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let (k, v) = t
            .split_once('=')
            .ok_or_else(|| Error::at_line(lineno, "expected 'Key = Value'"))?;
        let k = k.trim().to_ascii_lowercase();
        let v = v.trim().to_string();
        if k == "elementdatafile" {
            break (lineno, v);
        }
        if fields.insert(k.clone(), (lineno, v)).is_some() {
            return Err(Error::at_line(lineno, format!("key '{k}' given twice")));
        }
    };
    let field = |k: &str| fields.get(k).map(|(l, v)| (*l, v.as_str()));
    let need =
        |k: &str, n: &str| field(k).ok_or_else(|| Error::format(format!("header has no {n}")));
    if let Some((l, v)) = field("objecttype") {
        if !v.eq_ignore_ascii_case("image") {
            return Err(Error::at_line(
                l,
                format!("ObjectType '{v}' is not an Image"),
            ));
        }
    }
    if let Some((l, v)) = field("elementnumberofchannels") {
        if v.trim() != "1" {
            return Err(Error::unsupported(format!(
                "line {l}: only 1 channel per element is supported, not {v}"
            )));
        }
    }
    if let Some((l, v)) = field("binarydata") {
        if !boolean(v, l)? {
            return Err(Error::unsupported(
                "ASCII MetaImage data (BinaryData = False)",
            ));
        }
    }
    let (nl, nv) = need("ndims", "NDims")?;
    let nd: usize = nv
        .parse()
        .map_err(|_| Error::at_line(nl, format!("bad NDims '{nv}'")))?;
    if nd != 2 && nd != 3 {
        return Err(Error::unsupported(format!(
            "NDims {nd}: only 2 and 3 are supported"
        )));
    }
    let nums = |k: &str| -> Result<Option<Vec<f64>>> {
        match field(k) {
            None => Ok(None),
            Some((l, v)) => {
                let x = v
                    .split_whitespace()
                    .map(|t| t.parse::<f64>())
                    .collect::<std::result::Result<Vec<_>, _>>()
                    .map_err(|_| Error::at_line(l, format!("bad numbers '{v}'")))?;
                if x.len() != nd || x.iter().any(|v| !v.is_finite()) {
                    return Err(Error::at_line(
                        l,
                        format!("expected {nd} finite numbers, got '{v}'"),
                    ));
                }
                Ok(Some(x))
            }
        }
    };
    let (sl, sv) = need("dimsize", "DimSize")?;
    let sizes: Vec<usize> = sv
        .split_whitespace()
        .map(|x| x.parse::<usize>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| Error::at_line(sl, format!("bad DimSize '{sv}'")))?;
    if sizes.len() != nd {
        return Err(Error::at_line(
            sl,
            format!("{} sizes for NDims {nd}", sizes.len()),
        ));
    }
    let mut dims = [1usize; 3];
    dims[..nd].copy_from_slice(&sizes);
    let (tl, tv) = need("elementtype", "ElementType")?;
    let ty = met_type(tv).map_err(|e| match e {
        Error::Format { msg, .. } => Error::at_line(tl, msg),
        e => e,
    })?;
    let (_, nbytes) = data_size(dims, ty).map_err(|e| match e {
        Error::Format { msg, .. } => Error::at_line(sl, msg),
        e => e,
    })?;
    let mut spacing = [1.0; 3];
    if let Some(s) = nums("elementspacing")?.or(nums("elementsize")?) {
        spacing[..nd].copy_from_slice(&s);
    }
    if let Some(k) = spacing.iter().position(|&s| s <= 0.0) {
        return Err(Error::format(format!(
            "spacing of axis {k} is not positive"
        )));
    }
    let mut origin = [0.0; 3];
    if let Some(o) = nums("offset")?.or(nums("origin")?).or(nums("position")?) {
        origin[..nd].copy_from_slice(&o);
    }
    // MetaImage world coordinates are LPS (ITK); the i-th triple of TransformMatrix is the
    // direction of grid axis i (ITK's MetaImageIO reads it so)
    let mut orientation = Orientation {
        space: Some("left-posterior-superior".into()),
        anatomical: field("anatomicalorientation").map(|(_, v)| v.trim().to_string()),
        directions: None,
    };
    if let (Some((l, v)), 3) = (field("transformmatrix"), nd) {
        let m = v
            .split_whitespace()
            .map(|t| t.parse::<f64>())
            .collect::<std::result::Result<Vec<_>, _>>()
            .map_err(|_| Error::at_line(l, format!("bad TransformMatrix '{v}'")))?;
        if m.len() != 9 {
            return Err(Error::at_line(
                l,
                format!("TransformMatrix needs 9 numbers, got {}", m.len()),
            ));
        }
        let rows = [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]];
        orientation.directions =
            Orientation::unit_directions(rows).map_err(|e| Error::at_line(l, e))?;
    }
    let big = match field("elementbyteordermsb").or(field("binarydatabyteordermsb")) {
        Some((l, v)) => boolean(v, l)?,
        None => false,
    };
    let compressed = match field("compresseddata") {
        Some((l, v)) => boolean(v, l)?,
        None => false,
    };
    let header_size: i64 = match field("headersize") {
        None => 0,
        Some((l, v)) => v
            .parse()
            .ok()
            .filter(|&h: &i64| h >= -1)
            .ok_or_else(|| Error::at_line(l, format!("bad HeaderSize '{v}'")))?,
    };
    let (dl, dv) = data_file;
    let first = dv.split_whitespace().next().unwrap_or("");
    let (mut reader, mut available, data_path): (Box<dyn std::io::BufRead>, u64, PathBuf) =
        if dv.eq_ignore_ascii_case("LOCAL") {
            (
                Box::new(r),
                file_len.saturating_sub(consumed),
                path.to_path_buf(),
            )
        } else if dv.is_empty() || first.eq_ignore_ascii_case("LIST") || dv.contains('%') {
            return Err(Error::unsupported(format!(
                "line {dl}: ElementDataFile '{dv}' (lists and series are not supported)"
            )));
        } else {
            let dpath = beside(path, &dv)?;
            let (df, dlen) = open_data(&dpath)?;
            (Box::new(BufReader::new(df)), dlen, dpath)
        };
    let skip = match header_size {
        -1 => {
            if compressed {
                return Err(Error::format("HeaderSize -1 needs uncompressed data"));
            }
            available.checked_sub(nbytes as u64).ok_or_else(|| {
                Error::format(format!(
                    "data has {available} bytes, the header needs {nbytes}"
                ))
            })?
        }
        h => h as u64,
    };
    if compressed {
        // HeaderSize bytes of the file precede the zlib stream
        if skip > available {
            return Err(Error::format("HeaderSize is larger than the data file"));
        }
        std::io::copy(&mut (&mut reader).take(skip), &mut std::io::sink())
            .map_err(|e| Error::format(format!("cannot read data: {e}")))?;
        available -= skip;
        if let Some((l, v)) = field("compresseddatasize") {
            let c: u64 = v
                .parse()
                .map_err(|_| Error::at_line(l, format!("bad CompressedDataSize '{v}'")))?;
            if c > available {
                return Err(Error::at_line(
                    l,
                    format!("CompressedDataSize {c} but only {available} bytes follow"),
                ));
            }
            available = c;
        }
    }
    let (codec, skip) = if compressed {
        (Codec::Zlib, 0)
    } else {
        (Codec::Raw, skip)
    };
    Ok((
        Head {
            dims,
            axes: Axes::Uniform { origin, spacing },
            orientation,
            ty,
            big,
        },
        Data {
            reader,
            available,
            codec,
            skip,
            path: data_path,
        },
    ))
}

/// Reads a volume (the data file is found relative to `path`).
pub fn read(path: &Path) -> Result<Volume> {
    let (h, d) = source(path)?;
    super::rawjson::load(h, d)
}

/// Opens the samples for reading slice by slice ([`super::open_volume_stream`]).
pub(crate) fn open_stream(path: &Path) -> Result<VolumeStream> {
    let (h, d) = source(path)?;
    VolumeStream::new(h, d)
}

fn header(v: &Volume, ty: Sample, data_file: &str) -> Result<String> {
    let (o, s) = uniform(v)?;
    // MetaImage is LPS: a volume in RAS or LAS is converted; another named space is written as
    // it is (its name does not survive: MetaImage has no field for it)
    let (o, d) = v.orientation.to_lps(o).unwrap_or((
        o,
        v.orientation
            .directions
            .unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
    ));
    let identity = (0..3).all(|a| (0..3).all(|b| d[a][b] == if a == b { 1.0 } else { 0.0 }));
    let mut extra = String::new();
    if !identity {
        let t: Vec<String> = d.iter().flatten().map(|x| format!("{x:?}")).collect();
        extra.push_str(&format!("TransformMatrix = {}\n", t.join(" ")));
    }
    if let Some(a) = v
        .orientation
        .anatomical
        .as_deref()
        .filter(|a| !a.contains('\n'))
    {
        extra.push_str(&format!("AnatomicalOrientation = {a}\n"));
    }
    Ok(format!(
        "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n\
         CompressedData = False\n{extra}Offset = {:?} {:?} {:?}\nElementSpacing = {:?} {:?} {:?}\n\
         DimSize = {} {} {}\nElementType = {}\nElementDataFile = {}\n",
        o[0],
        o[1],
        o[2],
        s[0],
        s[1],
        s[2],
        v.dims[0],
        v.dims[1],
        v.dims[2],
        met_name(ty),
        data_file
    ))
}

/// The data file [`write()`] creates beside the header `path`: the same name with `.raw`; `None`
/// for `.mha`, which holds its data after the header.
pub fn data_file(path: &Path) -> Option<std::path::PathBuf> {
    let local = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("mha"));
    (!local).then(|| path.with_extension("raw"))
}

/// Writes a volume (with its data file beside it where the format has one), atomically.
pub fn write(path: &Path, v: &Volume) -> Result<()> {
    v.validate()?;
    let ty = output_type(v);
    let Some(raw_path) = data_file(path) else {
        let h = header(v, ty, "LOCAL")?;
        return super::write_atomic(path, |w| {
            w.write_all(h.as_bytes()).map_err(super::werr)?;
            for chunk in v.data.chunks(1 << 16) {
                w.write_all(&encode(chunk, ty, false))
                    .map_err(super::werr)?;
            }
            Ok(())
        });
    };
    let raw_name = raw_path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| Error::invalid("the file name must be valid UTF-8"))?
        .to_string();
    if raw_name.contains(char::is_whitespace) {
        return Err(Error::invalid(
            "MetaImage data file names cannot contain spaces",
        ));
    }
    let h = header(v, ty, &raw_name)?;
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
    super::write_atomic(path, |w| w.write_all(h.as_bytes()).map_err(super::werr))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_types() {
        assert_eq!(met_type("MET_UCHAR").unwrap(), Sample::U8);
        assert_eq!(met_type(" met_uint ").unwrap(), Sample::U32);
        assert!(matches!(
            met_type("MET_LONG_LONG"),
            Err(Error::Unsupported { .. })
        ));
        assert!(met_type("MET_QUUX").is_err());
        for t in [Sample::U8, Sample::I16, Sample::F32, Sample::F64] {
            assert_eq!(met_type(met_name(t)).unwrap(), t);
        }
    }
}

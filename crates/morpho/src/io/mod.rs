//! File formats, one file per format, and dispatch by file extension.
//!
//! Every parser treats its input as untrusted: sizes claimed by headers are checked against the
//! bytes actually present before anything is allocated, and malformed input gives an
//! [`Error::Format`] naming the line or byte. Writers go through [`write_atomic`], so a failed
//! write never leaves a half-written file.

pub mod csv;
pub mod geojson;
pub mod mhd;
pub mod nrrd;
pub mod obj;
pub mod off;
pub mod ply;
pub mod rawjson;
pub mod stl;
pub mod xyz;

use crate::mesh::{PointSet, Shapes2, TriMesh};
use crate::volume::Volume;
use crate::{Error, Result};
use std::io::Write;
use std::path::Path;

/// Largest file morpho reads into memory (8 GiB); larger inputs are refused with an error.
pub const MAX_FILE_BYTES: u64 = 8 << 30;

/// File formats known by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Csv,
    Xyz,
    Ply,
    Obj,
    Off,
    Stl,
    GeoJson,
    Json,
    Nrrd,
    Nhdr,
    Mhd,
    Svg,
    Png,
    Html,
}

impl Format {
    /// The format of `path` by its extension (case-insensitive; a trailing `.gz` is not a format).
    pub fn of(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        Ok(match ext.as_str() {
            "csv" => Format::Csv,
            "xyz" | "txt" | "p2d" | "pts" => Format::Xyz,
            "ply" => Format::Ply,
            "obj" => Format::Obj,
            "off" => Format::Off,
            "stl" => Format::Stl,
            "geojson" => Format::GeoJson,
            "json" => Format::Json,
            "nrrd" => Format::Nrrd,
            "nhdr" => Format::Nhdr,
            "mhd" | "mha" => Format::Mhd,
            "svg" => Format::Svg,
            "png" => Format::Png,
            "html" | "htm" => Format::Html,
            "gz" => {
                let stem = path.file_stem().map(Path::new).unwrap_or(Path::new(""));
                return Format::of(stem);
            }
            "" => {
                return Err(Error::unsupported(
                    "file has no extension; use one of .csv .xyz .ply .obj .off .stl .geojson .json .nrrd .nhdr .mhd",
                )
                .with_path(path))
            }
            other => {
                return Err(Error::unsupported(format!("unknown file extension '.{other}'")).with_path(path))
            }
        })
    }
}

/// Reads a whole file, refusing files larger than [`MAX_FILE_BYTES`], and decompresses it when
/// its name ends in `.gz` or it starts with the gzip magic bytes.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    if meta.is_dir() {
        return Err(Error::invalid("is a directory, not a file").with_path(path));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(Error::invalid(format!(
            "file is {} bytes, more than morpho reads",
            meta.len()
        ))
        .with_path(path));
    }
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    if bytes.len() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b {
        return gunzip(&bytes, MAX_FILE_BYTES).map_err(|e| e.with_path(path));
    }
    Ok(bytes)
}

/// Decompresses a gzip stream, refusing output larger than `limit` bytes.
pub fn gunzip(bytes: &[u8], limit: u64) -> Result<Vec<u8>> {
    use std::io::Read;
    let mut out = Vec::new();
    flate2::read::MultiGzDecoder::new(bytes)
        .take(limit + 1)
        .read_to_end(&mut out)
        .map_err(|e| Error::format(format!("bad gzip data: {e}")))?;
    if out.len() as u64 > limit {
        return Err(Error::invalid("decompressed data is larger than allowed"));
    }
    Ok(out)
}

/// Writes `path` atomically: the content goes to a temporary file in the same folder, which is
/// renamed over `path` only when `write` succeeded. On error nothing is left behind.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::Builder::new()
        .prefix(".morpho-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .map_err(|e| Error::io(path, e))?;
    {
        let mut w = std::io::BufWriter::new(tmp.as_file_mut());
        write(&mut w)?;
        w.flush().map_err(|e| Error::io(path, e))?;
    }
    tmp.as_file().sync_all().ok();
    // temporary files are created private (0600); a result file gets ordinary permissions
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let _ = tmp
            .as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644));
    }
    tmp.persist(path).map_err(|e| Error::io(path, e.error))?;
    Ok(())
}

/// Converts an I/O error during writing into an [`Error`] (the caller adds the path).
pub(crate) fn werr(e: std::io::Error) -> Error {
    Error::Io {
        path: String::new(),
        source: e,
    }
}

/// Mesh encodings that have a choice (PLY and STL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Encoding {
    Ascii,
    #[default]
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// Reads a triangle mesh from PLY, OBJ, OFF or STL (optionally gzipped).
pub fn read_mesh(path: &Path) -> Result<TriMesh> {
    let fmt = Format::of(path)?;
    let bytes = read_bytes(path)?;
    let mesh = match fmt {
        Format::Ply => ply::read_mesh(&bytes),
        Format::Obj => obj::read(&bytes),
        Format::Off => off::read(&bytes),
        Format::Stl => stl::read(&bytes),
        _ => Err(Error::unsupported(
            "not a mesh format (use .ply .obj .off .stl)",
        )),
    }
    .map_err(|e| e.with_path(path))?;
    mesh.validate().map_err(|e| e.with_path(path))?;
    Ok(mesh)
}

/// Writes a triangle mesh as PLY (binary little endian by default), OBJ, OFF or STL (binary).
pub fn write_mesh(path: &Path, mesh: &TriMesh, encoding: Encoding) -> Result<()> {
    let fmt = Format::of(path)?;
    if !matches!(fmt, Format::Ply | Format::Obj | Format::Off | Format::Stl) {
        return Err(
            Error::unsupported("not a mesh format (use .ply .obj .off .stl)").with_path(path),
        );
    }
    write_atomic(path, |w| match fmt {
        Format::Ply => ply::write_mesh(w, mesh, encoding),
        Format::Obj => obj::write(w, mesh),
        Format::Off => off::write(w, mesh),
        _ => stl::write(w, mesh, encoding),
    })
    .map_err(|e| e.with_path(path))
}

/// Reads a point set from CSV (with header), whitespace XYZ or PLY (vertices).
pub fn read_points(path: &Path) -> Result<PointSet> {
    let fmt = Format::of(path)?;
    let bytes = read_bytes(path)?;
    let pts = match fmt {
        Format::Csv => csv::read_points(&bytes),
        Format::Xyz => xyz::read(&bytes),
        Format::Ply => ply::read_points(&bytes),
        Format::Json => json_points(&bytes),
        Format::Obj | Format::Off | Format::Stl => {
            let m = match fmt {
                Format::Obj => obj::read(&bytes)?,
                Format::Off => off::read(&bytes)?,
                _ => stl::read(&bytes)?,
            };
            Ok(PointSet::from_points3(&m.positions))
        }
        _ => Err(Error::unsupported(
            "not a point format (use .csv .xyz .ply .json)",
        )),
    }
    .map_err(|e| e.with_path(path))?;
    if pts.is_empty() {
        return Err(Error::invalid("no points").with_path(path));
    }
    pts.validate().map_err(|e| e.with_path(path))?;
    Ok(pts)
}

/// A JSON array of `[x, y]` or `[x, y, z]` numbers (the delaunator fixtures' format), or an
/// object with a `"points"` array of that form.
pub fn json_points(bytes: &[u8]) -> Result<PointSet> {
    let v: serde_json::Value = serde_json::from_slice(bytes)
        .map_err(|e| Error::at_line(e.line() as u64, format!("bad JSON: {e}")))?;
    let arr = match &v {
        serde_json::Value::Array(a) => a,
        serde_json::Value::Object(o) => match o.get("points") {
            Some(serde_json::Value::Array(a)) => a,
            _ => {
                return Err(Error::format(
                    "expected an array of points or an object with \"points\"",
                ))
            }
        },
        _ => return Err(Error::format("expected an array of points")),
    };
    let mut dim = 0;
    let mut coords = Vec::with_capacity(arr.len() * 3);
    for (i, p) in arr.iter().enumerate() {
        let p = p
            .as_array()
            .ok_or_else(|| Error::format(format!("point {i} is not an array")))?;
        if dim == 0 {
            dim = p.len();
            if dim != 2 && dim != 3 {
                return Err(Error::format(format!(
                    "point {i} has {dim} coordinates; expected 2 or 3"
                )));
            }
        } else if p.len() != dim {
            return Err(Error::format(format!(
                "point {i} has {} coordinates, the first had {dim}",
                p.len()
            )));
        }
        for c in p {
            let c = c
                .as_f64()
                .ok_or_else(|| Error::format(format!("point {i} has a non-number coordinate")))?;
            coords.push(c);
        }
    }
    Ok(PointSet {
        dim: dim.max(2),
        coords,
        columns: vec![],
    })
}

/// Writes a point set as CSV, XYZ or PLY.
pub fn write_points(path: &Path, pts: &PointSet) -> Result<()> {
    let fmt = Format::of(path)?;
    write_atomic(path, |w| match fmt {
        Format::Csv => csv::write_points(w, pts),
        Format::Xyz => xyz::write(w, pts),
        Format::Ply => ply::write_points(w, pts, Encoding::BinaryLittleEndian),
        _ => Err(Error::unsupported(
            "not a point format (use .csv .xyz .ply)",
        )),
    })
    .map_err(|e| e.with_path(path))
}

/// Reads 2D polygons/polylines from CSV (ordered vertices) or GeoJSON.
pub fn read_shapes2(path: &Path) -> Result<Shapes2> {
    let fmt = Format::of(path)?;
    let bytes = read_bytes(path)?;
    match fmt {
        Format::Csv => csv::read_polygon(&bytes),
        Format::GeoJson | Format::Json => geojson::read(&bytes),
        _ => Err(Error::unsupported(
            "not a polygon format (use .csv .geojson)",
        )),
    }
    .map_err(|e| e.with_path(path))
}

/// Writes 2D shapes as CSV (single ring or polyline) or GeoJSON.
pub fn write_shapes2(path: &Path, shapes: &Shapes2) -> Result<()> {
    let fmt = Format::of(path)?;
    write_atomic(path, |w| match fmt {
        Format::Csv => csv::write_polygon(w, shapes),
        Format::GeoJson | Format::Json => geojson::write(w, shapes),
        _ => Err(Error::unsupported(
            "not a polygon format (use .csv .geojson)",
        )),
    })
    .map_err(|e| e.with_path(path))
}

/// Reads a volume: NRRD (attached or detached `.nhdr`), MetaImage `.mhd`, or a raw + JSON sidecar.
pub fn read_volume(path: &Path) -> Result<Volume> {
    let fmt = Format::of(path)?;
    let v = match fmt {
        Format::Nrrd | Format::Nhdr => nrrd::read(path),
        Format::Mhd => mhd::read(path),
        Format::Json => rawjson::read(path),
        _ => Err(Error::unsupported(
            "not a volume format (use .nrrd .nhdr .mhd or a .json sidecar)",
        )),
    }
    .map_err(|e| e.with_path(path))?;
    v.validate().map_err(|e| e.with_path(path))?;
    Ok(v)
}

/// Writes a volume as NRRD (gzip-encoded, attached), MetaImage (`.mhd` + `.raw`) or JSON sidecar
/// (`.json` + `.raw`).
pub fn write_volume(path: &Path, v: &Volume) -> Result<()> {
    let fmt = Format::of(path)?;
    match fmt {
        Format::Nrrd => nrrd::write(path, v),
        Format::Mhd => mhd::write(path, v),
        Format::Json => rawjson::write(path, v),
        _ => Err(Error::unsupported(
            "not a volume format (use .nrrd .mhd .json)",
        )),
    }
    .map_err(|e| e.with_path(path))
}

/// An array of rings (arrays of `[x, y]`), the format of the earcut polygon fixtures.
fn is_ring_array(v: &serde_json::Value) -> bool {
    v.as_array()
        .and_then(|a| a.first())
        .and_then(|r| r.as_array())
        .and_then(|r| r.first())
        .is_some_and(|p| p.is_array())
}

/// What a file holds, as far as morpho can tell from its extension and content.
#[derive(Debug, Clone)]
pub enum Data {
    Points(PointSet),
    Shapes(Shapes2),
    Mesh(TriMesh),
    Volume(Volume),
}

/// Reads any supported file. PLY files without faces are points; CSV files with an `x,y`
/// header are points unless `as_polygon`; JSON files are volumes when they are a sidecar
/// (`"dims"` key), points when they are an array of coordinates, shapes when GeoJSON.
pub fn read_any(path: &Path) -> Result<Data> {
    let fmt = Format::of(path)?;
    match fmt {
        Format::Obj | Format::Off | Format::Stl => Ok(Data::Mesh(read_mesh(path)?)),
        Format::Ply => {
            let bytes = read_bytes(path)?;
            let m = ply::read_mesh(&bytes).map_err(|e| e.with_path(path))?;
            m.validate().map_err(|e| e.with_path(path))?;
            if m.triangles.is_empty() {
                Ok(Data::Points(read_points(path)?))
            } else {
                Ok(Data::Mesh(m))
            }
        }
        Format::Csv | Format::Xyz => Ok(Data::Points(read_points(path)?)),
        Format::GeoJson => Ok(Data::Shapes(read_shapes2(path)?)),
        Format::Nrrd | Format::Nhdr | Format::Mhd => Ok(Data::Volume(read_volume(path)?)),
        Format::Json => {
            let bytes = read_bytes(path)?;
            let v: serde_json::Value = serde_json::from_slice(&bytes).map_err(|e| {
                Error::at_line(e.line() as u64, format!("bad JSON: {e}")).with_path(path)
            })?;
            if rawjson::is_sidecar(&v) {
                Ok(Data::Volume(read_volume(path)?))
            } else if v.get("type").is_some() || is_ring_array(&v) {
                Ok(Data::Shapes(read_shapes2(path)?))
            } else {
                Ok(Data::Points(read_points(path)?))
            }
        }
        _ => Err(Error::unsupported("cannot read this kind of file").with_path(path)),
    }
}

//! File formats, one file per format, readers and writers, and dispatch by file extension.
//!
//! Every parser treats its input as untrusted: sizes claimed by headers are checked against the
//! bytes actually present before anything is allocated, and malformed input gives an
//! [`Error::Format`] naming the line or byte.
//!
//! Every result type is written by a function in its format's file (`ply::write_tets`,
//! `geojson::write_boundary_2d`, `json::write_graph`, `vtk::write_tets_vtu`, …) onto a
//! `&mut dyn Write`; the functions of this module choose the format by the file's extension
//! and write through [`write_atomic`], so a failed write never leaves a half-written file.
//! Write failures are [`Error::Io`] with the output path, whatever the format (one mapping,
//! `werr`). Pictures of results (SVG, PNG) are in [`crate::render`].
//!
//! | result | dispatch | formats |
//! |---|---|---|
//! | points | [`write_points`], [`write_points_as`] | `.csv .xyz .ply .geojson` |
//! | polygons, polylines | [`write_shapes2`] | `.csv .geojson .json` |
//! | triangle meshes | [`write_mesh`] | `.ply .obj .off .stl .vtu .vtk` |
//! | tetrahedral meshes | [`write_tets`] | `.vtu .vtk .ply` |
//! | volumes | [`write_volume`] | `.nrrd .mhd .json` (+ `.raw`) |
//! | 2D / 3D triangulations | [`write_triangulation_2d`], [`write_triangulation_3d`] | `.json`, mesh formats |
//! | geometric graphs | [`write_graph`] | `.json .ply` |
//! | 2D boundaries, interiors | [`write_boundary_2d`], [`write_interior_2d`] | `.csv .geojson .json`; `.json`, mesh formats |
//! | 3D boundaries | [`write_boundary_3d`] | `.json`, mesh formats |
//! | plane contours | [`write_contour_2d`] | `.geojson .json` |

// One public module per format: each is a real namespace (`io::ply::read_tets`,
// `io::nrrd::write`, `io::vtk::write_tets_vtu`, …) for format-specific readers, writers and
// options; the functions of this module dispatch to them by extension.
pub mod csv;
pub mod geojson;
// What may be read and written (regular files, size caps, atomic replacement): a namespace
// because the CLI switches its policies on (`guard::protect_inputs`, …).
pub mod guard;
pub mod html;
pub mod json;
pub mod memory;
pub mod mhd;
pub mod nrrd;
pub mod obj;
pub mod off;
pub mod ply;
pub mod rawjson;
pub mod stl;
mod volstream;
pub mod vtk;
pub mod xyz;

pub use volstream::VolumeStream;

use crate::boundary::{Boundary2, Boundary3};
use crate::contour::PlaneContour;
use crate::geom::{Point2, Point3};
use crate::graphs::{Graph, Kind};
use crate::mesh::{PointSet, Shapes2, TetMesh, TriMesh};
use crate::volume::Volume;
use crate::{Error, Result};
use std::io::Write;
use std::path::Path;

/// Largest file morpho reads into memory (8 GiB); larger inputs are refused with an error.
pub const MAX_FILE_BYTES: u64 = 8 << 30;

/// File formats known by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values (`.csv`): points with columns, or polygon rings.
    Csv,
    /// Whitespace-separated coordinates (`.xyz`, `.txt`).
    Xyz,
    /// Stanford PLY (`.ply`), ASCII or binary.
    Ply,
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// Object File Format (`.off`).
    Off,
    /// STL (`.stl`), ASCII or binary.
    Stl,
    /// GeoJSON (`.geojson`): points, polygons, line strings.
    GeoJson,
    /// JSON (`.json`): point objects, or a volume sidecar with its raw data file.
    Json,
    /// NRRD with attached data (`.nrrd`).
    Nrrd,
    /// NRRD header with detached data (`.nhdr`).
    Nhdr,
    /// MetaImage header (`.mhd`) with its data file.
    Mhd,
    /// SVG picture (`.svg`, writing only).
    Svg,
    /// PNG picture (`.png`, writing only).
    Png,
    /// HTML page (`.html`, writing only).
    Html,
    /// VTK XML unstructured grid (writing only).
    Vtu,
    /// Legacy VTK (writing only).
    Vtk,
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
            "vtu" => Format::Vtu,
            "vtk" => Format::Vtk,
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
    use std::io::Read;
    let (f, len) = guard::open_input(path)?;
    memory::check(
        len.saturating_mul(memory::PARSE_FACTOR),
        "reading this file",
    )
    .map_err(|e| e.with_path(path))?;
    let mut bytes = Vec::with_capacity(len as usize);
    // a file that grows while it is read is cut at the limit, not followed
    f.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(Error::invalid("file grew past the size morpho reads").with_path(path));
    }
    if bytes.len() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b {
        // what it decompresses to is parsed in memory too (memory::PARSE_FACTOR)
        let cap = MAX_FILE_BYTES.min(memory::max_read_bytes());
        return gunzip(&bytes, cap).map_err(|e| match e {
            Error::Invalid { .. } if cap < MAX_FILE_BYTES => Error::invalid(format!(
                "the file decompresses to more than {}, which with what is parsed from it \
                 exceeds the memory limit of {} (--memory-limit or MORPHO_MEMORY_LIMIT)",
                memory::human(cap),
                memory::human(memory::limit())
            ))
            .with_path(path),
            e => e.with_path(path),
        });
    }
    Ok(bytes)
}

/// Text with its bare carriage returns (old Mac OS line ends) made line feeds, byte for byte:
/// the length is unchanged, so byte offsets and line numbers in errors stay those of the file;
/// LF and CRLF are left as they are. Every text reader starts with it, so CR, LF and CRLF are
/// accepted everywhere (issue 17 item 10).
pub fn unify_line_ends(bytes: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    let bare = |i: usize| bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n');
    match (0..bytes.len()).position(bare) {
        None => std::borrow::Cow::Borrowed(bytes),
        Some(first) => {
            let mut v = bytes.to_vec();
            for i in first..bytes.len() {
                if bare(i) {
                    v[i] = b'\n';
                }
            }
            std::borrow::Cow::Owned(v)
        }
    }
}

/// Decompresses a gzip stream, refusing output larger than `limit` bytes.
pub(crate) fn gunzip(bytes: &[u8], limit: u64) -> Result<Vec<u8>> {
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
/// renamed over `path` only when `write` succeeded. On error nothing is left behind, and the
/// error names `path` (unless `write` named another file). Which paths may be written, and
/// how links, FIFOs and devices are treated, is decided by [`guard::output_target`].
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("hello.txt");
/// morpho::io::write_atomic(&path, |w| morpho::io::write_all(w, b"hello\n")).unwrap();
/// assert_eq!(std::fs::read(&path).unwrap(), b"hello\n");
/// ```
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    write_atomic_inner(path, write).map_err(|e| e.with_path(path))
}

fn write_atomic_inner(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let target = match guard::output_target(path)? {
        guard::Target::Replace(t) => t,
        guard::Target::Stream => {
            // a FIFO or a character device: written straight into, never replaced
            let f = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(|e| Error::io(path, e))?;
            let mut w = std::io::BufWriter::new(f);
            write_maybe_gzip(path, &mut w, write)?;
            w.flush().map_err(|e| Error::io(path, e))?;
            return Ok(());
        }
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let tmp = guard::create_temporary(dir).map_err(|e| {
        // tempfile names its own random file in the message; say what the user can act on
        let e = match e.kind() {
            std::io::ErrorKind::NotFound => std::io::Error::new(
                e.kind(),
                format!("the folder {} does not exist", dir.display()),
            ),
            std::io::ErrorKind::PermissionDenied => std::io::Error::new(
                e.kind(),
                format!("no permission to create files in {}", dir.display()),
            ),
            _ => std::io::Error::new(
                e.kind(),
                format!("cannot create a file in {}", dir.display()),
            ),
        };
        Error::io(path, e)
    })?;
    let tmp_path = tmp.path().to_path_buf();
    let result = fill_and_persist(tmp, &target, path, write);
    // renamed onto the target, or removed by the temporary's drop on failure
    guard::temporary_gone(&tmp_path);
    result?;
    guard::written(&target);
    Ok(())
}

/// Runs `write` onto `w`, through a gzip encoder when `path` ends in `.gz` (any case): what a
/// reader gunzips by that name is written compressed (before, `x.ply.gz` was plain PLY).
fn write_maybe_gzip(
    path: &Path,
    w: &mut dyn Write,
    write: impl FnOnce(&mut dyn Write) -> Result<()>,
) -> Result<()> {
    let gz = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
    if !gz {
        return write(w);
    }
    let mut enc = flate2::write::GzEncoder::new(w, flate2::Compression::new(6));
    write(&mut enc)?;
    enc.finish().map_err(|e| Error::io(path, e))?;
    Ok(())
}

/// The body of [`write_atomic`] once the temporary file exists: write, flush, sync, rename.
fn fill_and_persist(
    mut tmp: tempfile::NamedTempFile,
    target: &Path,
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<()>,
) -> Result<()> {
    {
        let mut w = std::io::BufWriter::new(tmp.as_file_mut());
        write_maybe_gzip(path, &mut w, write)?;
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
    tmp.persist(target).map_err(|e| Error::io(path, e.error))?;
    Ok(())
}

/// The one mapping of write failures: an I/O error while writing becomes [`Error::Io`]
/// ([`write_atomic`] adds the path).
pub(crate) fn werr(e: std::io::Error) -> Error {
    Error::Io {
        path: String::new(),
        source: e,
    }
}

/// Writes all of `bytes` (a failure is [`Error::Io`]; [`write_atomic`] adds the path).
pub fn write_all(w: &mut dyn Write, bytes: &[u8]) -> Result<()> {
    w.write_all(bytes).map_err(werr)
}

/// Writes a text file (an SVG picture, an HTML page, …) atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |w| write_all(w, text.as_bytes()))
}

/// Mesh encodings that have a choice (PLY and STL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Encoding {
    /// Text.
    Ascii,
    #[default]
    /// Binary, least significant byte first (the default).
    BinaryLittleEndian,
    /// Binary, most significant byte first.
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
    mesh.validate()
        .map_err(|e| Error::from(e).with_path(path))?;
    Ok(mesh)
}

/// Writes a triangle mesh as PLY (binary little endian by default), OBJ, OFF, STL (binary),
/// or VTK (`.vtu` XML, `.vtk` legacy; triangles as cell type 5, binary unless
/// [`Encoding::Ascii`]).
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::io::{read_mesh, write_mesh, Encoding};
/// use morpho::mesh::TriMesh;
/// let m = TriMesh::new(
///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
///     vec![[0, 1, 2]],
/// );
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("t.ply");
/// write_mesh(&path, &m, Encoding::default()).unwrap();
/// assert_eq!(read_mesh(&path).unwrap().triangles, m.triangles);
/// ```
pub fn write_mesh(path: &Path, mesh: &TriMesh, encoding: Encoding) -> Result<()> {
    let fmt = Format::of(path)?;
    if !is_mesh_format(fmt) {
        return Err(
            Error::unsupported("not a mesh format (use .ply .obj .off .stl)").with_path(path),
        );
    }
    write_atomic(path, |w| match fmt {
        Format::Ply => ply::write_mesh(w, mesh, encoding),
        Format::Obj => obj::write(w, mesh),
        Format::Off => off::write(w, mesh),
        Format::Vtu => vtk::write_mesh_vtu(w, mesh, encoding),
        Format::Vtk => vtk::write_mesh_vtk(w, mesh, encoding),
        _ => stl::write(w, mesh, encoding),
    })
}

/// True for the formats [`write_mesh`] writes.
pub fn is_mesh_format(fmt: Format) -> bool {
    matches!(
        fmt,
        Format::Ply | Format::Obj | Format::Off | Format::Stl | Format::Vtu | Format::Vtk
    )
}

/// Reads a tetrahedral mesh from a PLY file with a `tetra` element (as
/// [`write_tets`] writes it).
pub fn read_tets(path: &Path) -> Result<TetMesh> {
    let fmt = Format::of(path)?;
    if fmt != Format::Ply {
        return Err(Error::unsupported(
            "tetrahedral meshes are read from .ply files with a 'tetra' element",
        )
        .with_path(path));
    }
    let bytes = read_bytes(path)?;
    ply::read_tets(&bytes).map_err(|e| e.with_path(path))
}

/// A tetrahedral mesh when `path` is a PLY file with a `tetra` element, `None` for any other
/// file (which [`read_any`] reads).
pub fn read_tets_if_present(path: &Path) -> Result<Option<TetMesh>> {
    if Format::of(path)? != Format::Ply {
        return Ok(None);
    }
    let bytes = read_bytes(path)?;
    if !ply::has_tets(&bytes).map_err(|e| e.with_path(path))? {
        return Ok(None);
    }
    ply::read_tets(&bytes)
        .map(Some)
        .map_err(|e| e.with_path(path))
}

/// Writes a tetrahedral mesh as VTK (`.vtu` XML unstructured grid, `.vtk` legacy unstructured
/// grid; cell type 10, readable by ParaView and meshio) or as PLY with a `tetra` element.
/// Binary unless `encoding` is [`Encoding::Ascii`] (legacy VTK binary is big endian by the
/// format's definition; the `.vtu` and PLY byte orders follow `encoding`).
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::io::{write_tets, Encoding};
/// use morpho::mesh::TetMesh;
/// let t = TetMesh {
///     positions: vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///                     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)],
///     tets: vec![[0, 1, 3, 2]],
/// };
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("t.vtk");
/// write_tets(&path, &t, Encoding::Ascii).unwrap();
/// let text = std::fs::read_to_string(&path).unwrap();
/// assert!(text.contains("CELLS 1 5\n4 0 3 1 2\n") && text.contains("CELL_TYPES 1\n10\n"));
/// ```
pub fn write_tets(path: &Path, tets: &TetMesh, encoding: Encoding) -> Result<()> {
    let fmt = Format::of(path)?;
    if !matches!(fmt, Format::Vtu | Format::Vtk | Format::Ply) {
        return Err(
            Error::unsupported("not a tetrahedral mesh format (use .vtu .vtk .ply)")
                .with_path(path),
        );
    }
    write_atomic(path, |w| match fmt {
        Format::Vtu => vtk::write_tets_vtu(w, tets, encoding),
        Format::Vtk => vtk::write_tets_vtk(w, tets, encoding),
        _ => ply::write_tets(w, tets, encoding),
    })
}

/// The lifted triangle mesh of a plane triangulation (z = 0).
fn lifted(points: &[Point2], triangles: &[[u32; 3]]) -> TriMesh {
    TriMesh::new(
        points.iter().map(|p| Point3::new(p.x, p.y, 0.0)).collect(),
        triangles.to_vec(),
    )
}

/// Writes a 2D (constrained) triangulation: `.json` ([`json::write_triangulation_2d`]) or a
/// mesh format ([`write_mesh`]: the triangles with z = 0, binary where there is a choice).
/// The SVG picture is [`crate::render::delaunay_svg`].
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::io::{json::Triangulation2, write_triangulation_2d};
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// let d = morpho::delaunay::triangulate_2d(&p).unwrap();
/// let (tris, hull) = (d.to_input_indices(), d.hull.clone());
/// let t = Triangulation2 { points: &p, triangles: &tris, hull: &hull, constrained: None };
/// let dir = tempfile::tempdir().unwrap();
/// write_triangulation_2d(&dir.path().join("t.json"), &t).unwrap();
/// write_triangulation_2d(&dir.path().join("t.off"), &t).unwrap();
/// assert!(write_triangulation_2d(&dir.path().join("t.nrrd"), &t).is_err());
/// ```
pub fn write_triangulation_2d(path: &Path, t: &json::Triangulation2) -> Result<()> {
    match Format::of(path)? {
        Format::Json => write_atomic(path, |w| json::write_triangulation_2d(w, t)),
        f if is_mesh_format(f) => write_mesh(
            path,
            &lifted(t.points, t.triangles),
            Encoding::BinaryLittleEndian,
        ),
        _ => Err(
            Error::unsupported("not a triangulation format (use .json or a mesh format)")
                .with_path(path),
        ),
    }
}

/// Writes a 3D Delaunay tetrahedralization: `.json` ([`json::write_triangulation_3d`]); with
/// `tets` the tetrahedra in a tetrahedral mesh format ([`write_tets`]: `.vtu .vtk .ply`),
/// otherwise the hull surface in a mesh format ([`write_mesh`]). Binary where there is a
/// choice.
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::io::{json::Triangulation3, write_triangulation_3d};
/// let p = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///          Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
/// let d = morpho::delaunay::triangulate_3d(&p).unwrap();
/// let tets = d.to_input_indices();
/// let hull: Vec<[u32; 3]> = d.hull.iter().map(|t| t.map(|v| d.input_of_vertex[v as usize])).collect();
/// let t = Triangulation3 { points: &p, tets: &tets, hull: &hull };
/// let dir = tempfile::tempdir().unwrap();
/// write_triangulation_3d(&dir.path().join("t.vtu"), &t, true).unwrap(); // the tetrahedra
/// write_triangulation_3d(&dir.path().join("h.ply"), &t, false).unwrap(); // the hull
/// assert_eq!(morpho::io::read_mesh(&dir.path().join("h.ply")).unwrap().triangles.len(), 4);
/// ```
pub fn write_triangulation_3d(path: &Path, t: &json::Triangulation3, tets: bool) -> Result<()> {
    match Format::of(path)? {
        Format::Json => write_atomic(path, |w| json::write_triangulation_3d(w, t)),
        Format::Ply | Format::Vtu | Format::Vtk if tets => write_tets(
            path,
            &TetMesh {
                positions: t.points.to_vec(),
                tets: t.tets.to_vec(),
            },
            Encoding::BinaryLittleEndian,
        ),
        f if tets && is_mesh_format(f) => Err(Error::unsupported(
            "--tets writes tetrahedra: use .ply (tetra element), .vtu, .vtk or .json (this format holds triangles only)",
        )
        .with_path(path)),
        f if is_mesh_format(f) => write_mesh(
            path,
            &TriMesh::new(t.points.to_vec(), t.hull.to_vec()),
            Encoding::BinaryLittleEndian,
        ),
        _ => Err(Error::unsupported(
            "not a tetrahedralization format (use .json, .vtu, .vtk or a mesh format)",
        )
        .with_path(path)),
    }
}

/// Writes a geometric graph of `points`: `.json` ([`json::write_graph`]) or `.ply`
/// ([`ply::write_graph`], 2D points with z = 0). The SVG picture is
/// [`crate::render::graph_svg`].
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::graphs::{graph_2d, Kind};
/// use morpho::mesh::PointSet;
/// let p = [Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(1.0, 3.0)];
/// let g = graph_2d(&p, Kind::Rng).unwrap();
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("rng.ply");
/// morpho::io::write_graph(&path, Kind::Rng, &PointSet::from_points2(&p), &g).unwrap();
/// assert!(std::fs::read_to_string(&path).unwrap().contains("element edge 3\n"));
/// ```
pub fn write_graph(path: &Path, kind: Kind, points: &PointSet, g: &Graph) -> Result<()> {
    match Format::of(path)? {
        Format::Json => write_atomic(path, |w| json::write_graph(w, kind, points, g)),
        Format::Ply => write_atomic(path, |w| ply::write_graph(w, &points.to_points3(), g)),
        _ => Err(Error::unsupported("not a graph format (use .json .ply)").with_path(path)),
    }
}

/// Writes a 2D boundary polygon through `points`: `.csv` ([`csv::write_boundary_2d`]),
/// `.geojson` ([`geojson::write_boundary_2d`]) or `.json` ([`json::write_boundary_2d`]). The
/// SVG picture is [`crate::render::boundary_svg`].
///
/// ```
/// use morpho::boundary::{boundary_2d, Options2};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(1.0, 0.5), Point2::new(1.0, 2.0)];
/// let b = boundary_2d(&p, &Options2::default()).unwrap();
/// let dir = tempfile::tempdir().unwrap();
/// morpho::io::write_boundary_2d(&dir.path().join("b.geojson"), &p, &b).unwrap();
/// morpho::io::write_interior_2d(&dir.path().join("i.off"), &p, &b).unwrap();
/// let back = morpho::io::read_shapes2(&dir.path().join("b.geojson")).unwrap();
/// assert_eq!(back.polygons[0].rings[0].len(), b.polygon.len());
/// ```
pub fn write_boundary_2d(path: &Path, points: &[Point2], b: &Boundary2) -> Result<()> {
    match Format::of(path)? {
        Format::Csv => write_atomic(path, |w| csv::write_boundary_2d(w, points, b)),
        Format::GeoJson => write_atomic(path, |w| geojson::write_boundary_2d(w, points, b)),
        Format::Json => write_atomic(path, |w| json::write_boundary_2d(w, b)),
        _ => Err(
            Error::unsupported("not a boundary format (use .csv .geojson .json)").with_path(path),
        ),
    }
}

/// Writes the interior triangulation of a 2D boundary: `.json` ([`json::write_interior_2d`])
/// or any mesh format ([`write_mesh`], z = 0, binary where there is a choice).
pub fn write_interior_2d(path: &Path, points: &[Point2], b: &Boundary2) -> Result<()> {
    if Format::of(path)? == Format::Json {
        return write_atomic(path, |w| json::write_interior_2d(w, b));
    }
    write_mesh(path, &lifted(points, &b.interior), Encoding::default())
}

/// Writes a 3D boundary surface through `points`: `.json` ([`json::write_boundary_3d`]) or any
/// mesh format ([`write_mesh`], every point a vertex in input order).
pub fn write_boundary_3d(path: &Path, points: &[Point3], b: &Boundary3) -> Result<()> {
    if Format::of(path)? == Format::Json {
        return write_atomic(path, |w| json::write_boundary_3d(w, b));
    }
    let mesh = TriMesh::new(points.to_vec(), b.triangles.clone());
    write_mesh(path, &mesh, Encoding::default())
}

/// Writes a plane contour: `.geojson` ([`geojson::write_contour`]: its regions with the
/// `threshold` and `below` that made them) or `.json` ([`json::write_contour_cycles`]). The
/// SVG picture is [`crate::render::contour_svg`].
///
/// ```
/// use morpho::contour::{contour_samples, SampleContour, SampleOptions};
/// use morpho::mesh::{Column, PointSet};
/// let mut s = PointSet { dim: 2, coords: vec![0., 0., 1., 0., 1., 1., 0., 1., 0.5, 0.5], columns: vec![] };
/// s.columns.push(Column { name: "value".into(), values: vec![0., 0., 0., 0., 10.] });
/// let opts = SampleOptions { threshold: 1.0, ..Default::default() };
/// let SampleContour::Plane(r) = contour_samples(&s, &opts).unwrap() else { unreachable!() };
/// let dir = tempfile::tempdir().unwrap();
/// morpho::io::write_contour_2d(&dir.path().join("c.geojson"), &r, 1.0, false).unwrap();
/// assert_eq!(morpho::io::read_shapes2(&dir.path().join("c.geojson")).unwrap().polygons.len(), 1);
/// ```
pub fn write_contour_2d(path: &Path, r: &PlaneContour, threshold: f64, below: bool) -> Result<()> {
    match Format::of(path)? {
        Format::GeoJson => write_atomic(path, |w| geojson::write_contour(w, r, threshold, below)),
        Format::Json => write_atomic(path, |w| json::write_contour_cycles(w, r)),
        _ => Err(Error::unsupported("not a contour format (use .geojson .json)").with_path(path)),
    }
}

/// Reads a point set from CSV (with header), whitespace XYZ or PLY (vertices).
pub fn read_points(path: &Path) -> Result<PointSet> {
    let fmt = Format::of(path)?;
    let bytes = read_bytes(path)?;
    let pts = match fmt {
        Format::Csv => csv::read_points(&bytes),
        Format::Xyz => xyz::read(&bytes),
        Format::Ply => ply::read_points(&bytes),
        Format::Json => json::read_points(&bytes),
        Format::GeoJson => geojson::read_points(&bytes),
        Format::Obj | Format::Off | Format::Stl => {
            let m = match fmt {
                Format::Obj => obj::read(&bytes)?,
                Format::Off => off::read(&bytes)?,
                _ => stl::read(&bytes)?,
            };
            Ok(PointSet::from_points3(&m.positions))
        }
        _ => Err(Error::unsupported(
            "not a point format (use .csv .xyz .ply .json .geojson)",
        )),
    }
    .map_err(|e| e.with_path(path))?;
    if pts.is_empty() {
        return Err(Error::invalid("no points").with_path(path));
    }
    pts.validate().map_err(|e| Error::from(e).with_path(path))?;
    Ok(pts)
}

/// Writes a point set as CSV, XYZ, PLY (binary little endian) or GeoJSON (`Point` features).
pub fn write_points(path: &Path, pts: &PointSet) -> Result<()> {
    write_points_as(path, pts, Encoding::BinaryLittleEndian)
}

/// [`write_points`] with the PLY encoding chosen (`convert --ascii`, `--big-endian`); the
/// encoding does not affect the text formats.
pub fn write_points_as(path: &Path, pts: &PointSet, enc: Encoding) -> Result<()> {
    let fmt = Format::of(path)?;
    write_atomic(path, |w| match fmt {
        Format::Csv => csv::write_points(w, pts),
        Format::Xyz => xyz::write(w, pts),
        Format::Ply => ply::write_points(w, pts, enc),
        Format::GeoJson => geojson::write_points(w, pts),
        _ => Err(Error::unsupported(
            "not a point format (use .csv .xyz .ply .geojson)",
        )),
    })
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
    v.validate().map_err(|e| Error::from(e).with_path(path))?;
    Ok(v)
}

/// Opens a volume file for reading its samples a few z-slices at a time ([`VolumeStream`]):
/// NRRD (raw or gzip), MetaImage (raw or zlib) or a JSON sidecar. The header is checked as by
/// [`read_volume`]; the samples are not read.
pub fn open_volume_stream(path: &Path) -> Result<VolumeStream> {
    let fmt = Format::of(path)?;
    let s = match fmt {
        Format::Nrrd | Format::Nhdr => nrrd::open_stream(path),
        Format::Mhd => mhd::open_stream(path),
        Format::Json => rawjson::open_stream(path),
        _ => Err(Error::unsupported(
            "not a volume format (use .nrrd .nhdr .mhd or a .json sidecar)",
        )),
    }
    .map_err(|e| e.with_path(path))?;
    crate::volume::validate_axes(&s.grid().axes, s.dims())
        .map_err(|e| Error::from(e).with_path(path))?;
    Ok(s)
}

/// Writes a volume as NRRD (gzip-encoded, attached), MetaImage (`.mhd` + `.raw`) or JSON sidecar
/// (`.json` + `.raw`).
pub fn write_volume(path: &Path, v: &Volume) -> Result<()> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"))
    {
        // volume headers are read as text; NRRD compresses its own data (gzip encoding)
        return Err(Error::unsupported(
            "a volume is not written as .gz: .nrrd is gzip-encoded already (or use .mhd/.json with a .raw file)",
        )
        .with_path(path));
    }
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
    /// A point set with its value columns.
    Points(PointSet),
    /// 2D polygons and polylines.
    Shapes(Shapes2),
    /// A triangle mesh.
    Mesh(TriMesh),
    /// A scalar volume.
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
            m.validate().map_err(|e| Error::from(e).with_path(path))?;
            if m.triangles.is_empty() {
                Ok(Data::Points(read_points(path)?))
            } else {
                Ok(Data::Mesh(m))
            }
        }
        Format::Csv | Format::Xyz => Ok(Data::Points(read_points(path)?)),
        Format::GeoJson => {
            let shapes = read_shapes2(path)?;
            if shapes.polygons.is_empty() && shapes.polylines.is_empty() {
                let bytes = read_bytes(path)?;
                let pts = geojson::read_points(&bytes).map_err(|e| e.with_path(path))?;
                if !pts.is_empty() {
                    return Ok(Data::Points(read_points(path)?));
                }
            }
            Ok(Data::Shapes(shapes))
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 17 item 10: files with bare CR line ends (old Mac OS) were read as one line
    /// ("points: 1"). Every text format now reads CR, LF and CRLF files alike, and errors keep
    /// the file's line numbers.
    #[test]
    fn cr_lf_and_crlf_line_ends_read_alike() {
        let cases: [(&str, &str); 7] = [
            (
                "m.ply",
                "ply\nformat ascii 1.0\ncomment CR test\nelement vertex 4\nproperty float x\n\
                 property float y\nproperty float z\nelement face 1\n\
                 property list uchar int vertex_indices\nend_header\n\
                 0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n",
            ),
            (
                "v.nrrd",
                "NRRD0004\n# comment\ntype: float\ndimension: 3\nsizes: 2 2 2\n\
                 spacings: 1 2 3\nencoding: ascii\n\n0 1 2 3\n4 5 6 7\n",
            ),
            (
                "v.mhd",
                "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = 1 2 3\n\
                 ElementType = MET_UCHAR\nElementDataFile = LOCAL\n\
                 \u{0}\u{1}\u{2}\u{3}\u{4}\u{5}\u{6}\u{7}",
            ),
            ("p.csv", "x,y\n0,0\n1,0\n0,1\n0.5,0.25\n"),
            ("p.xyz", "# pts\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"),
            (
                "m.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
            ),
            (
                "m.off",
                "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
            ),
        ];
        let dir = tempfile::tempdir().unwrap();
        for (name, lf) in cases {
            let mut got = Vec::new();
            for (k, end) in ["\n", "\r", "\r\n"].iter().enumerate() {
                let p = dir.path().join(format!("{k}{name}"));
                std::fs::write(&p, lf.replace('\n', end)).unwrap();
                got.push(match read_any(&p).unwrap() {
                    Data::Points(ps) => format!("{} {:?}", ps.dim, ps.coords),
                    Data::Mesh(m) => format!("{:?} {:?}", m.positions, m.triangles),
                    Data::Volume(v) => format!("{:?} {:?} {:?}", v.dims, v.axes, v.data),
                    Data::Shapes(_) => panic!("{name}"),
                });
            }
            assert!(got[0].len() > 20, "{name}: {}", got[0]);
            assert_eq!(got[0], got[1], "{name}: CR");
            assert_eq!(got[0], got[2], "{name}: CRLF");
        }
        // an error on line 3 of a CR file is reported on line 3
        let p = dir.path().join("bad.csv");
        std::fs::write(&p, "x,y\r0,0\r1,zz\r").unwrap();
        let e = read_points(&p).unwrap_err().to_string();
        assert!(e.contains("line 3"), "{e}");
        assert_eq!(&*unify_line_ends(b"a\rb\r\nc\n\r"), b"a\nb\r\nc\n\n");
    }

    #[test]
    fn write_failures_are_io_errors_naming_the_output() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x.json");
        // a failing writer inside the closure: Error::Io with the output's path, nothing left
        let e = write_atomic(&out, |_| {
            Err(werr(std::io::Error::new(
                std::io::ErrorKind::StorageFull,
                "disk full",
            )))
        })
        .unwrap_err();
        assert!(matches!(&e, Error::Io { path, .. } if *path == out.display().to_string()));
        assert!(!e.is_input_error());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        // a folder that does not exist
        let missing = dir.path().join("no/such/dir/x.ply");
        let e = write_points(&missing, &PointSet::from_points2(&[Point2::new(0.0, 0.0)]));
        assert!(matches!(e, Err(Error::Io { path, .. }) if path.contains("x.ply")));
    }
}

//! Where morpho may read and write: the one place that decides whether a path may be opened as
//! an input or replaced as an output (issue 17, items 1–4).
//!
//! # Inputs
//! Every reader opens its files through `open_input`: only regular files are read (a FIFO, a
//! device, a socket or a directory is refused before it is opened, so a FIFO cannot hang a read
//! and a link to the zero device cannot fill memory), no file larger than
//! [`super::MAX_FILE_BYTES`]. Detached data files named by a header (NRRD `data file`, MHD
//! `ElementDataFile`, the sidecar's `data`) are resolved by `data_file`: relative to the
//! header's folder, and never outside it — an absolute name or a `..` that leaves the folder is
//! refused unless the program called [`allow_data_outside_header_folder`] (the CLI's
//! `--allow-outside-data`). The check is on the name the header gives; links inside the
//! folder are the user's own and are followed.
//!
//! # Outputs
//! [`super::write_atomic`] asks [`output_target`] what to do with a path: a new path or a
//! regular file is replaced atomically (through a link, the file the link points to is
//! replaced and the link kept); a FIFO or a character device (`/dev/stdout`, `/dev/null`) is
//! written straight into, never replaced; anything else is refused.
//!
//! # The input guard
//! A program that reads and writes files named by untrusted input (the CLI) calls
//! [`protect_inputs`] once at start. From then on every file opened by `open_input` is
//! remembered by identity (device and inode, so links and other spellings of the same path
//! are caught), and no output may replace a remembered input or a file already written by this
//! process. Library users who do not call it can read and rewrite the same file as before.
//!
//! # Temporary files
//! [`super::write_atomic`] writes into a temporary file beside the target and renames it at the
//! end. While it exists the temporary file's path is listed here; a program that ends on a
//! signal calls [`remove_temporaries`] first (the CLI does on SIGTERM, SIGHUP and SIGINT), so
//! no `.morpho-*.tmp` file is left behind. SIGKILL cannot be caught: after `kill -9` a
//! temporary file may remain (the target itself is never half-written).

use crate::{Error, Result};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// The identity of an existing file: device and inode on Unix, the canonical path elsewhere.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FileKey(Key);

#[derive(Debug, Clone, PartialEq, Eq)]
enum Key {
    #[cfg(unix)]
    Inode(u64, u64),
    #[allow(dead_code)]
    Path(PathBuf),
}

impl FileKey {
    /// The identity of `path` after following links; `None` when it does not exist.
    pub fn of(path: &Path) -> Option<FileKey> {
        let meta = std::fs::metadata(path).ok()?;
        Some(Self::from_meta(path, &meta))
    }

    fn from_meta(_path: &Path, _meta: &std::fs::Metadata) -> FileKey {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            FileKey(Key::Inode(_meta.dev(), _meta.ino()))
        }
        #[cfg(not(unix))]
        {
            FileKey(Key::Path(
                std::fs::canonicalize(_path).unwrap_or_else(|_| _path.to_path_buf()),
            ))
        }
    }
}

/// Two paths name the same file: the same identity when both exist, otherwise the same
/// absolute path once `.` and `..` are resolved and the existing folder's links followed.
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (FileKey::of(a), FileKey::of(b)) {
        (Some(x), Some(y)) => x == y,
        (None, None) => normalized(a) == normalized(b),
        _ => false,
    }
}

/// `path` made absolute: its folder canonical when it exists, the last component kept.
fn normalized(path: &Path) -> PathBuf {
    let abs = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir()
            .map(|d| d.join(path))
            .unwrap_or_else(|_| path.to_path_buf())
    };
    match (abs.parent(), abs.file_name()) {
        (Some(d), Some(n)) => std::fs::canonicalize(d)
            .map(|d| d.join(n))
            .unwrap_or_else(|_| abs.clone()),
        _ => abs,
    }
}

struct Registry {
    inputs: Vec<(FileKey, PathBuf)>,
    written: Vec<(FileKey, PathBuf)>,
}

static GUARD: Mutex<Option<Registry>> = Mutex::new(None);
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
static ENDING: AtomicBool = AtomicBool::new(false);

/// Creates the temporary file of an atomic write in `dir` and lists it, both under the list's
/// lock, so [`remove_temporaries`] sees every temporary file that exists. Refused once
/// [`remove_temporaries`] ran (the program is ending).
pub(crate) fn create_temporary(dir: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let mut list = TEMPORARIES.lock().unwrap_or_else(|p| p.into_inner());
    if ENDING.load(Ordering::SeqCst) {
        return Err(std::io::Error::other("the program is ending"));
    }
    let tmp = tempfile::Builder::new()
        .prefix(".morpho-")
        .suffix(".tmp")
        .tempfile_in(dir)?;
    list.push(tmp.path().to_path_buf());
    Ok(tmp)
}

/// Takes a temporary file off the list (it was renamed onto its target or removed).
pub(crate) fn temporary_gone(path: &Path) {
    let mut t = TEMPORARIES.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(i) = t.iter().rposition(|q| q == path) {
        t.swap_remove(i);
    }
}

/// Removes every temporary file of an unfinished [`super::write_atomic`] and returns how many
/// were removed. Meant for a signal-handling thread just before the process exits: from then
/// on no new temporary file is created (a write that starts afterwards fails).
pub fn remove_temporaries() -> usize {
    let mut list = TEMPORARIES.lock().unwrap_or_else(|p| p.into_inner());
    ENDING.store(true, Ordering::SeqCst);
    list.drain(..)
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count()
}
static ALLOW_OUTSIDE: AtomicBool = AtomicBool::new(false);

fn registry() -> std::sync::MutexGuard<'static, Option<Registry>> {
    GUARD.lock().unwrap_or_else(|e| e.into_inner())
}

/// Turns the input guard on for the rest of the process (see the module documentation).
pub fn protect_inputs() {
    let mut g = registry();
    if g.is_none() {
        *g = Some(Registry {
            inputs: Vec::new(),
            written: Vec::new(),
        });
    }
}

/// Lets headers name data files outside their own folder (absolute paths, `..`), for the rest
/// of the process. Off by default.
pub fn allow_data_outside_header_folder(allow: bool) {
    ALLOW_OUTSIDE.store(allow, Ordering::Relaxed);
}

/// Opens `path` for reading: a regular file of at most [`super::MAX_FILE_BYTES`] bytes
/// (anything else is an error naming it), remembered by the input guard when it is on.
/// Returns the file and its length.
pub(crate) fn open_input(path: &Path) -> Result<(std::fs::File, u64)> {
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    check_regular(path, &meta)?;
    let f = open_no_block(path).map_err(|e| Error::io(path, e))?;
    // the file opened is the one checked (not swapped for a FIFO or device in between)
    let meta = f.metadata().map_err(|e| Error::io(path, e))?;
    check_regular(path, &meta)?;
    if meta.len() > super::MAX_FILE_BYTES {
        return Err(Error::invalid(format!(
            "file is {} bytes, more than morpho reads ({} bytes)",
            meta.len(),
            super::MAX_FILE_BYTES
        ))
        .with_path(path));
    }
    if let Some(r) = registry().as_mut() {
        let key = FileKey::from_meta(path, &meta);
        if !r.inputs.iter().any(|(k, _)| *k == key) {
            r.inputs.push((key, path.to_path_buf()));
        }
    }
    Ok((f, meta.len()))
}

#[cfg(unix)]
fn open_no_block(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

#[cfg(not(unix))]
fn open_no_block(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::File::open(path)
}

fn check_regular(path: &Path, meta: &std::fs::Metadata) -> Result<()> {
    if meta.is_file() {
        return Ok(());
    }
    let what = if meta.is_dir() {
        "a directory"
    } else {
        special_kind(meta)
    };
    Err(Error::invalid(format!(
        "is {what}, not a regular file; morpho reads regular files only"
    ))
    .with_path(path))
}

fn special_kind(_meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = _meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}

/// The path of the data file `name` that the header `header` refers to: relative to the
/// header's folder. An empty name, an absolute name or one whose `..` leaves the folder is
/// refused (unless [`allow_data_outside_header_folder`]).
pub(crate) fn data_file(header: &Path, name: &str) -> Result<PathBuf> {
    let p = Path::new(name);
    let folder = match header.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if ALLOW_OUTSIDE.load(Ordering::Relaxed) {
        return Ok(if p.is_absolute() {
            p.to_path_buf()
        } else {
            folder.join(p)
        });
    }
    let mut depth = 0i64;
    let mut escapes = p.as_os_str().is_empty();
    for c in p.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => {
                depth -= 1;
                escapes |= depth < 0;
            }
            Component::RootDir | Component::Prefix(_) => escapes = true,
        }
    }
    if escapes || depth < 1 {
        return Err(Error::invalid(format!(
            "the data file '{}' is outside the header's folder; morpho reads data files beside \
             their header only (--allow-outside-data to permit it)",
            name.escape_debug()
        ))
        .with_path(header));
    }
    Ok(folder.join(p))
}

/// What [`super::write_atomic`] does with an output path.
#[derive(Debug)]
pub enum Target {
    /// Write a temporary file in this path's folder and rename it over this path (the path
    /// itself, or the file a link points to).
    Replace(PathBuf),
    /// Write straight into it (a FIFO or a character device).
    Stream,
}

/// Decides how `path` may be written (see the module documentation), refusing an input
/// remembered by the guard, a file this process already wrote, and paths that are neither
/// new, regular files, FIFOs nor character devices.
pub fn output_target(path: &Path) -> Result<Target> {
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        // a new path (or a dangling link, which is replaced)
        Err(_) => return Ok(Target::Replace(path.to_path_buf())),
    };
    let key = FileKey::from_meta(path, &meta);
    if let Some(r) = registry().as_ref() {
        if let Some((_, i)) = r.inputs.iter().find(|(k, _)| *k == key) {
            return Err(Error::invalid(format!(
                "output would overwrite the input {}; choose another output",
                i.display()
            ))
            .with_path(path));
        }
        if r.written.iter().any(|(k, _)| *k == key) {
            return Err(Error::invalid(
                "this command already wrote another result to this file; choose distinct outputs",
            )
            .with_path(path));
        }
    }
    if meta.is_file() {
        let link = std::fs::symlink_metadata(path)
            .map(|m| m.file_type().is_symlink())
            .unwrap_or(false);
        return Ok(Target::Replace(if link {
            std::fs::canonicalize(path).map_err(|e| Error::io(path, e))?
        } else {
            path.to_path_buf()
        }));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() || t.is_char_device() {
            return Ok(Target::Stream);
        }
    }
    let what = if meta.is_dir() {
        "a directory"
    } else {
        special_kind(&meta)
    };
    Err(Error::invalid(format!(
        "is {what}; morpho writes regular files, FIFOs and character devices only"
    ))
    .with_path(path))
}

/// Remembers that `path` was written (when the guard is on).
pub(crate) fn written(path: &Path) {
    // only called after an atomic replace, so `path` is a regular file (streams such as
    // /dev/null or a pipe are never remembered and may take several results)
    if let Some(r) = registry().as_mut() {
        if let Some(key) = FileKey::of(path) {
            r.written.push((key, path.to_path_buf()));
        }
    }
}

/// Bytes read and written so far in this run, when the guard is on (`None` otherwise): the
/// length of each distinct input file opened (data files named by headers included) and of
/// each file written by an atomic replace, as they are now. For the report's throughput
/// figures; a file that has gone since counts 0.
pub fn traffic() -> Option<(u64, u64)> {
    let r = registry();
    let r = r.as_ref()?;
    let size = |l: &[(FileKey, PathBuf)]| -> u64 {
        l.iter()
            .map(|(_, p)| std::fs::metadata(p).map_or(0, |m| m.len()))
            .sum()
    };
    Some((size(&r.inputs), size(&r.written)))
}

/// Checks, before anything is written, that no two paths of `paths` are the same file and
/// that every one may be written ([`output_target`]) — for a command's outputs and for writers
/// that create several files (a header and its data file).
pub fn check_outputs<P: AsRef<Path>>(paths: &[P]) -> Result<()> {
    for (i, p) in paths.iter().map(AsRef::as_ref).enumerate() {
        if let Some(q) = paths[..i]
            .iter()
            .map(AsRef::as_ref)
            .find(|q| same_file(p, q))
        {
            return Err(Error::invalid(format!(
                "{} and {} are the same file; choose distinct outputs",
                q.display(),
                p.display()
            )));
        }
        output_target(p)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_files_stay_in_the_header_folder() {
        let h = Path::new("/data/vol/a.nhdr");
        assert_eq!(data_file(h, "a.raw").unwrap(), Path::new("/data/vol/a.raw"));
        assert_eq!(
            data_file(h, "sub/../a.raw").unwrap(),
            Path::new("/data/vol/sub/../a.raw")
        );
        assert_eq!(
            data_file(h, "./sub/a.raw").unwrap(),
            Path::new("/data/vol/./sub/a.raw")
        );
        for bad in [
            "/etc/passwd",
            "../a.raw",
            "sub/../../a.raw",
            "",
            ".",
            "sub/..",
        ] {
            assert!(data_file(h, bad).is_err(), "{bad}");
        }
        assert_eq!(
            data_file(Path::new("a.mhd"), "a.raw").unwrap(),
            Path::new("./a.raw")
        );
    }

    #[cfg(unix)]
    #[test]
    fn special_files_are_not_read() {
        for p in ["/dev/zero", "/dev/null", "/"] {
            let e = open_input(Path::new(p)).unwrap_err().to_string();
            assert!(e.contains("not a regular file"), "{p}: {e}");
        }
    }

    #[test]
    fn same_file_sees_new_and_existing_paths() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.txt");
        std::fs::write(&a, "x").unwrap();
        let sub = dir.path().join("s");
        std::fs::create_dir(&sub).unwrap();
        assert!(same_file(&a, &sub.join("../a.txt")));
        assert!(same_file(&dir.path().join("n.txt"), &sub.join("../n.txt")));
        assert!(!same_file(&a, &dir.path().join("n.txt")));
    }
}

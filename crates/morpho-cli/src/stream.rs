//! `-` on the command line: standard input for an input, standard output for an output
//! (issue 17 item 4), for every command.
//!
//! Readers and writers pick their format by the file's extension, and some need to seek or
//! reread (PLY headers, NRRD's detached data, the atomic writes of `io::write_atomic`). So a
//! stream is staged through a private temporary folder: standard input is copied into
//! `stdin.EXT` before the command runs (at most the memory limit of `--memory-limit`; the
//! format is `--input-format EXT`, else recognised from the first bytes), and an output named
//! `-` is written to `stdout.EXT` (`--format EXT`, required) and copied to standard output
//! once the command succeeded — a failed command writes nothing there. Messages name `-`,
//! never the staging path. The folder is removed at exit and on SIGTERM/SIGHUP/SIGINT.
//!
//! The rewrite happens on the raw arguments, before clap sees them: the value of `-o`,
//! `--output`, `--report` or `--interior` that is `-` is the output stream; any other
//! argument that is exactly `-` is the input stream. At most one of each.

use std::ffi::{OsStr, OsString};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The staging folder of this run, for the signal handler.
static STAGING: Mutex<Option<PathBuf>> = Mutex::new(None);

/// Options whose value is an output path.
const OUTPUT_OPTIONS: [&str; 4] = ["-o", "--output", "--report", "--interior"];

/// The arguments with `-` replaced by staging paths, and what to do at the end.
pub struct Staged {
    /// The rewritten command line (for clap).
    pub args: Vec<OsString>,
    dir: Option<tempfile::TempDir>,
    stdin: Option<PathBuf>,
    stdout: Option<PathBuf>,
}

/// The value of `--NAME VALUE` or `--NAME=VALUE` in the raw arguments.
fn option_value(args: &[OsString], name: &str) -> Option<String> {
    let eq = format!("{name}=");
    for (i, a) in args.iter().enumerate() {
        let a = a.to_string_lossy();
        if a == name {
            return args.get(i + 1).map(|v| v.to_string_lossy().into_owned());
        }
        if let Some(v) = a.strip_prefix(&eq) {
            return Some(v.to_string());
        }
    }
    None
}

/// An extension as the format flags accept it: `ply`, `.ply`, `PLY` → `ply`.
fn extension(flag: &str, v: &str) -> Result<String, String> {
    let e = v.trim().trim_start_matches('.').to_ascii_lowercase();
    if e.is_empty() || !e.chars().all(|c| c.is_ascii_alphanumeric() || c == '.') {
        return Err(format!(
            "{flag} needs a file extension such as ply or csv, not '{v}'"
        ));
    }
    Ok(e)
}

/// The format of a stream from its first bytes: PLY, OFF, NRRD, MetaImage (`.mha`: its data
/// must be inside), binary or ASCII STL, GeoJSON or morpho JSON, OBJ, CSV (a comma in the first
/// line) or whitespace-separated XYZ. `head` is the whole stream.
pub fn sniff(head: &[u8]) -> &'static str {
    let text = String::from_utf8_lossy(&head[..head.len().min(4096)]);
    let t = text.trim_start_matches('\u{feff}').trim_start();
    let first = t.lines().next().unwrap_or("").trim();
    if first == "ply" {
        "ply"
    } else if first.starts_with("OFF") || first.starts_with("COFF") || first.starts_with("NOFF") {
        "off"
    } else if first.starts_with("NRRD") {
        "nrrd"
    } else if t.starts_with("ObjectType") || t.starts_with("NDims") {
        "mha"
    } else if first.starts_with("solid") && t.contains("facet") {
        "stl"
    } else if t.starts_with('{') || t.starts_with('[') {
        if t.contains("\"Feature") || t.contains("\"Polygon\"") || t.contains("\"LineString\"") {
            "geojson"
        } else {
            "json"
        }
    } else if is_binary_stl(head) {
        "stl"
    } else if t
        .lines()
        .take(50)
        .any(|l| l.starts_with("v ") || l.starts_with("f "))
    {
        "obj"
    } else if first.contains(',') {
        "csv"
    } else {
        "xyz"
    }
}

/// An 80-byte header, a triangle count and 50 bytes per triangle: a stream whose length is
/// exactly what its first 84 bytes announce is a binary STL (`data` is the whole stream).
fn is_binary_stl(data: &[u8]) -> bool {
    data.len() >= 84 && {
        let n = u32::from_le_bytes([data[80], data[81], data[82], data[83]]) as u64;
        84 + 50 * n == data.len() as u64
    }
}

/// Rewrites `-` in `args` (see the module documentation).
pub fn stage(args: Vec<OsString>) -> Result<Staged, String> {
    let out_fmt = option_value(&args, "--format");
    let in_fmt = option_value(&args, "--input-format");
    let mut args = args;
    let mut out_at = None;
    let mut in_at = None;
    for i in 1..args.len() {
        if args[i] != OsStr::new("-") {
            continue;
        }
        let prev = args[i - 1].to_string_lossy();
        if OUTPUT_OPTIONS.contains(&prev.as_ref()) {
            if out_at.replace(i).is_some() {
                return Err("only one output can go to standard output ('-')".into());
            }
        } else if prev == "--format" || prev == "--input-format" {
            return Err(format!("{prev} needs a file extension, not '-'"));
        } else if in_at.replace(i).is_some() {
            return Err("only one input can come from standard input ('-')".into());
        }
    }
    if out_fmt.is_some() && out_at.is_none() {
        return Err(
            "--format names the format of an output '-' (standard output); there is none".into(),
        );
    }
    if in_fmt.is_some() && in_at.is_none() {
        return Err(
            "--input-format names the format of an input '-' (standard input); there is none"
                .into(),
        );
    }
    if out_at.is_none() && in_at.is_none() {
        return Ok(Staged {
            args,
            dir: None,
            stdin: None,
            stdout: None,
        });
    }
    let dir = tempfile::Builder::new()
        .prefix("morpho-stream-")
        .tempdir()
        .map_err(|e| format!("cannot create a staging folder for '-': {e}"))?;
    *STAGING.lock().unwrap_or_else(|e| e.into_inner()) = Some(dir.path().to_path_buf());
    let mut staged = Staged {
        args: Vec::new(),
        dir: None,
        stdin: None,
        stdout: None,
    };
    if let Some(i) = out_at {
        let is_report = args[i - 1] == OsStr::new("--report");
        let ext = match (&out_fmt, is_report) {
            (_, true) => "json".to_string(),
            (Some(f), false) => extension("--format", f)?,
            (None, false) => {
                return Err(
                    "an output '-' (standard output) needs --format EXT, e.g. --format ply".into(),
                )
            }
        };
        if ext == "mhd" || ext == "nhdr" {
            return Err(format!(
                "--format {ext} writes a header and a separate data file: use mha or nrrd for \
                 standard output"
            ));
        }
        let p = dir.path().join(format!("stdout.{ext}"));
        args[i] = p.clone().into_os_string();
        staged.stdout = Some(p);
    }
    if let Some(i) = in_at {
        let mut data = Vec::new();
        let limit = morpho::io::memory::limit();
        std::io::stdin()
            .lock()
            .take(limit.saturating_add(1))
            .read_to_end(&mut data)
            .map_err(|e| format!("-: cannot read standard input: {e}"))?;
        if data.len() as u64 > limit {
            return Err(format!(
                "-: standard input is larger than the memory limit {} (--memory-limit)",
                morpho::io::memory::human(limit)
            ));
        }
        let ext = match &in_fmt {
            Some(f) => extension("--input-format", f)?,
            None => sniff(&data).to_string(),
        };
        let p = dir.path().join(format!("stdin.{ext}"));
        std::fs::write(&p, &data).map_err(|e| format!("-: cannot stage standard input: {e}"))?;
        args[i] = p.clone().into_os_string();
        staged.stdin = Some(p);
    }
    staged.args = args;
    staged.dir = Some(dir);
    Ok(staged)
}

impl Staged {
    /// `msg` with the staging paths written as `-`.
    pub fn unmap(&self, msg: &str) -> String {
        let mut m = msg.to_string();
        for p in [&self.stdin, &self.stdout].into_iter().flatten() {
            m = m.replace(&*p.to_string_lossy(), "-");
        }
        m
    }

    /// Copies the staged output to standard output (after the command succeeded).
    pub fn finish(&self) -> Result<(), String> {
        let Some(p) = &self.stdout else {
            return Ok(());
        };
        let mut f = match std::fs::File::open(p) {
            Ok(f) => f,
            // the command chose not to write (nothing to say): standard output stays empty
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
            Err(e) => return Err(format!("-: cannot read the staged output: {e}")),
        };
        let mut out = std::io::stdout().lock();
        std::io::copy(&mut f, &mut out)
            .and_then(|_| out.flush())
            .map_err(|e| format!("-: cannot write standard output: {e}"))?;
        Ok(())
    }
}

/// Removes the staging folder (for the signal handler: the process ends right after).
pub fn remove_staging() {
    if let Some(p) = STAGING.lock().unwrap_or_else(|e| e.into_inner()).take() {
        let _ = std::fs::remove_dir_all(Path::new(&p));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sniffs_every_format_by_its_first_bytes() {
        assert_eq!(sniff(b"ply\nformat ascii 1.0\n"), "ply");
        assert_eq!(sniff(b"OFF\n3 1 0\n"), "off");
        assert_eq!(sniff(b"NRRD0004\ntype: uint8\n"), "nrrd");
        assert_eq!(sniff(b"ObjectType = Image\nNDims = 3\n"), "mha");
        assert_eq!(sniff(b"solid x\nfacet normal 0 0 1\n"), "stl");
        assert_eq!(
            sniff(br#"{"type":"FeatureCollection","features":[]}"#),
            "geojson"
        );
        assert_eq!(sniff(br#"{"dims":[2,2,2]}"#), "json");
        assert_eq!(sniff(b"# obj\nv 0 0 0\nv 1 0 0\nf 1 2 3\n"), "obj");
        assert_eq!(sniff(b"x,y\n0,0\n"), "csv");
        assert_eq!(sniff(b"0 0 0\n1 0 0\n"), "xyz");
        let mut stl = vec![0u8; 134];
        stl[80] = 1;
        assert_eq!(sniff(&stl), "stl");
        assert_eq!(sniff(&stl[..120]), "xyz", "length disagrees with the count");
    }

    #[test]
    fn rewrites_outputs_and_refuses_two_streams() {
        let a = |v: &[&str]| v.iter().map(OsString::from).collect::<Vec<_>>();
        let s = stage(a(&[
            "morpho", "convert", "x.ply", "-o", "-", "--format", "obj",
        ]))
        .unwrap();
        let out = s.args[4].to_string_lossy().into_owned();
        assert!(out.ends_with("stdout.obj"), "{out}");
        assert_eq!(s.unmap(&format!("{out}: bad")), "-: bad");
        assert!(stage(a(&["morpho", "convert", "x.ply", "-o", "-"])).is_err());
        assert!(stage(a(&[
            "morpho", "x", "a", "-o", "-", "--report", "-", "--format", "ply"
        ]))
        .is_err());
        assert!(stage(a(&[
            "morpho", "convert", "x.ply", "-o", "-", "--format", "mhd"
        ]))
        .is_err());
        let plain = stage(a(&["morpho", "info", "x.ply"])).unwrap();
        assert_eq!(plain.args, a(&["morpho", "info", "x.ply"]));
    }
}

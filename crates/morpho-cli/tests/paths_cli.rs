//! Where the CLI may read and write (issue 17 items 1–4, each reproducer of the issue a test):
//! no output replaces an input, a data file a header names, another output of the same run or
//! a device; headers never make us read outside their folder; FIFOs and devices are never
//! read. Each test checks the files are untouched afterwards, not only the exit code.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn morpho(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_morpho"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run morpho")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code 2, one `error:` line containing `needle`, no panic.
fn refused(o: &Output, needle: &str) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.starts_with("error: ") && e.lines().count() == 1, "{e}");
    assert!(e.contains(needle), "expected `{needle}` in: {e}");
}

const SQUARE: &str = "x,y\n0,0\n1,0\n0,1\n1,1\n0.5,0.4\n";
const CUBE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

fn put(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn the_report_never_replaces_an_input_or_another_output() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    put(d, "b.obj", CUBE.as_bytes());
    put(d, "a.json", b"{}");
    put(d, "a.csv", SQUARE.as_bytes());
    std::fs::create_dir(d.join("sub")).unwrap();
    // info b.obj --report b.obj replaced the mesh with JSON
    refused(
        &morpho(d, &["info", "b.obj", "--report", "b.obj"]),
        "overwrite the input",
    );
    refused(
        &morpho(d, &["info", "b.obj", "--report", "./sub/../b.obj"]),
        "overwrite the input",
    );
    // -o refused but the report still written over the input
    refused(
        &morpho(
            d,
            &[
                "triangulate",
                "a.json",
                "-o",
                "a.json",
                "--report",
                "a.json",
            ],
        ),
        "overwrite the input",
    );
    // the report over the -o output, the --interior output over -o
    refused(
        &morpho(
            d,
            &["triangulate", "a.csv", "-o", "t.json", "--report", "t.json"],
        ),
        "same file",
    );
    refused(
        &morpho(
            d,
            &[
                "boundary",
                "a.csv",
                "-o",
                "o.json",
                "--interior",
                "./o.json",
            ],
        ),
        "same file",
    );
    // a link to the input is the input
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(d.join("a.csv"), d.join("link.csv")).unwrap();
        refused(
            &morpho(d, &["graph", "a.csv", "--kind", "rng", "-o", "link.csv"]),
            "overwrite the input",
        );
        std::fs::hard_link(d.join("a.csv"), d.join("hard.csv")).unwrap();
        refused(
            &morpho(d, &["convert", "a.csv", "-o", "hard.csv"]),
            "overwrite the input",
        );
    }
    assert_eq!(std::fs::read_to_string(d.join("b.obj")).unwrap(), CUBE);
    assert_eq!(std::fs::read_to_string(d.join("a.json")).unwrap(), "{}");
    assert_eq!(std::fs::read_to_string(d.join("a.csv")).unwrap(), SQUARE);
    // nothing was written by any refused command
    let mut want = vec!["a.csv", "a.json", "b.obj", "sub"];
    if cfg!(unix) {
        want.extend(["hard.csv", "link.csv"]);
    }
    want.sort();
    assert_eq!(files(d), want);
    // distinct paths still work, and the report is written
    let o = morpho(
        d,
        &["triangulate", "a.csv", "-o", "t.json", "--report", "r.json"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(d.join("t.json").is_file() && d.join("r.json").is_file());
}

/// A small volume as a sidecar JSON + raw data.
fn volume(d: &Path) -> Vec<u8> {
    let raw: Vec<u8> = (0..64u8).collect();
    put(d, "v.raw", &raw);
    put(
        d,
        "v.json",
        br#"{"data": "v.raw", "dims": [4, 4, 4], "dtype": "uint8", "spacing": [1, 1, 1], "origin": [0, 0, 0]}"#,
    );
    raw
}

#[test]
fn volume_writers_never_replace_the_inputs_data_file() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let raw = volume(d);
    // convert v.json -o v.mhd rewrote v.raw, which v.json points to
    refused(
        &morpho(d, &["convert", "v.json", "-o", "v.mhd"]),
        "overwrite the input",
    );
    assert_eq!(std::fs::read(d.join("v.raw")).unwrap(), raw);
    assert!(!d.join("v.mhd").exists(), "no header without its data");
    // .mhd -> .json likewise
    let o = morpho(d, &["convert", "v.json", "-o", "w.mhd"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let w_raw = std::fs::read(d.join("w.raw")).unwrap();
    refused(
        &morpho(d, &["convert", "w.mhd", "-o", "w.json"]),
        "overwrite the input",
    );
    assert_eq!(std::fs::read(d.join("w.raw")).unwrap(), w_raw);
    assert!(!d.join("w.json").exists());
    // an MHD whose data file is x.nrrd, written with -o x.nrrd
    let o = morpho(d, &["convert", "v.json", "-o", "x.nrrd"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let nrrd = std::fs::read(d.join("x.nrrd")).unwrap();
    put(
        d,
        "m.mhd",
        b"ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\nElementDataFile = v.raw\n",
    );
    put(
        d,
        "n.mhd",
        b"ObjectType = Image\nNDims = 3\nDimSize = 1 1 1\nElementType = MET_UCHAR\nHeaderSize = -1\nElementDataFile = x.nrrd\n",
    );
    refused(
        &morpho(d, &["convert", "n.mhd", "-o", "x.nrrd"]),
        "overwrite the input",
    );
    assert_eq!(std::fs::read(d.join("x.nrrd")).unwrap(), nrrd);
    // a header's data file is never replaced by a mesh output either
    put(d, "d.ply", &raw);
    put(
        d,
        "p.mhd",
        b"ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\nElementDataFile = d.ply\n",
    );
    refused(
        &morpho(d, &["isosurface", "p.mhd", "--level", "30", "-o", "d.ply"]),
        "overwrite the input",
    );
    assert_eq!(std::fs::read(d.join("d.ply")).unwrap(), raw);
    let o = morpho(d, &["isosurface", "m.mhd", "--level", "30", "-o", "e.ply"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn headers_cannot_name_data_outside_their_folder() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let inner = d.join("in");
    std::fs::create_dir(&inner).unwrap();
    let secret: Vec<u8> = (100..116u8).collect();
    put(d, "secret.raw", &secret);
    let abs = d.join("secret.raw");
    let abs = abs.to_str().unwrap();
    let mhd = |name: &str, file: &str| {
        put(
            &inner,
            name,
            format!(
                "ObjectType = Image\nNDims = 3\nDimSize = 4 4 1\nElementType = MET_UCHAR\nElementDataFile = {file}\n"
            )
            .as_bytes(),
        );
    };
    mhd("abs.mhd", abs);
    mhd("up.mhd", "../secret.raw");
    mhd("deep.mhd", "a/../../secret.raw");
    put(
        &inner,
        "s.nhdr",
        format!(
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 1\nencoding: raw\ndata file: {abs}\n"
        )
        .as_bytes(),
    );
    put(
        &inner,
        "s.json",
        br#"{"data": "../secret.raw", "dims": [4, 4, 1], "dtype": "uint8"}"#,
    );
    for h in ["abs.mhd", "up.mhd", "deep.mhd", "s.nhdr", "s.json"] {
        refused(
            &morpho(&inner, &["convert", h, "-o", "copy.nrrd"]),
            "outside the header's folder",
        );
        assert!(!inner.join("copy.nrrd").exists(), "{h}");
    }
    // the explicit flag allows it
    let o = morpho(
        &inner,
        &[
            "convert",
            "up.mhd",
            "-o",
            "copy.mhd",
            "--allow-outside-data",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(std::fs::read(inner.join("copy.raw")).unwrap(), secret);
}

#[cfg(unix)]
#[test]
fn fifos_and_devices_are_never_read_or_replaced() {
    use std::time::{Duration, Instant};
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    put(d, "a.csv", SQUARE.as_bytes());
    // a link to the zero device read until memory ran out
    std::os::unix::fs::symlink("/dev/zero", d.join("z.csv")).unwrap();
    refused(&morpho(d, &["info", "z.csv"]), "not a regular file");
    // a FIFO as an input or as a volume's data file hung
    let mk = |p: &Path| {
        let st = Command::new("mkfifo").arg(p).status().unwrap();
        assert!(st.success());
    };
    mk(&d.join("f.csv"));
    mk(&d.join("f.raw"));
    put(
        d,
        "f.mhd",
        b"ObjectType = Image\nNDims = 3\nDimSize = 4 4 1\nElementType = MET_UCHAR\nElementDataFile = f.raw\n",
    );
    put(
        d,
        "f.nhdr",
        b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 1\nencoding: raw\ndata file: f.raw\n",
    );
    put(
        d,
        "f.json",
        br#"{"data": "f.raw", "dims": [4, 4, 1], "dtype": "uint8"}"#,
    );
    for args in [
        vec!["info", "f.csv"],
        vec!["convert", "f.mhd", "-o", "o.nrrd"],
        vec!["convert", "f.nhdr", "-o", "o.nrrd"],
        vec!["convert", "f.json", "-o", "o.nrrd"],
    ] {
        let t0 = Instant::now();
        refused(&morpho(d, &args), "FIFO");
        assert!(t0.elapsed() < Duration::from_secs(20), "{args:?}");
    }
    // a directory as an output is refused before anything is computed
    std::fs::create_dir(d.join("out.json")).unwrap();
    refused(
        &morpho(d, &["triangulate", "a.csv", "-o", "out.json"]),
        "directory",
    );
    // the standard-output device path is written into, never replaced by a regular file
    let o = morpho(d, &["info", "a.csv", "--report", "/dev/stdout"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("\"command\": \"info\""), "{out}");
    assert!(std::fs::symlink_metadata("/dev/stdout")
        .map(|m| !m.is_file())
        .unwrap_or(true));
    // a link to a regular output file: the file is replaced, the link kept
    put(d, "real.json", b"old");
    std::os::unix::fs::symlink(d.join("real.json"), d.join("l.json")).unwrap();
    let o = morpho(d, &["triangulate", "a.csv", "-o", "l.json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(d.join("l.json"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(d.join("real.json"))
        .unwrap()
        .contains("triangles"));
}

/// Issue 17 item 5: `morpho info X | head -1` panicked with "failed printing to stdout: Broken
/// pipe"; a closed pipe now ends the program quietly (SIGPIPE, as for every Unix filter).
#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_quietly() {
    use std::process::Stdio;
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    // enough points that reading them outlasts closing the pipe
    let mut csv = String::from("x,y\n");
    for i in 0..200_000u32 {
        csv.push_str(&format!("{},{}\n", i % 997, i / 997));
    }
    put(d, "p.csv", csv.as_bytes());
    let mut child = Command::new(env!("CARGO_BIN_EXE_morpho"))
        .current_dir(d)
        .args(["info", "p.csv"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader goes away before anything is printed
    let o = child.wait_with_output().unwrap();
    let e = stderr(&o);
    assert!(!e.contains("panicked") && !e.contains("Broken pipe"), "{e}");
    assert_ne!(o.status.code(), Some(101), "{e}");
}

/// Issue 17 item 12: a SIGTERM (or SIGHUP, SIGINT) during a write leaves no temporary file and
/// no target; the exit status is 128 + the signal, as the default action would give. The
/// signal is sent once the temporary file exists, so the test fails on a binary that does not
/// clean up (the baseline left `.morpho-*.tmp` behind).
#[cfg(unix)]
#[test]
fn a_signal_during_a_write_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::with_capacity(40 << 20);
    for i in 0..1_500_000u64 {
        let (x, y) = ((i * 7919) % 100_003, (i * 104_729) % 99_991);
        text.push_str(&format!("{x}.25 {y}.75 {}.5\n", i % 977));
    }
    put(dir.path(), "p.xyz", text.as_bytes());
    let mut proved = 0;
    for sig in [libc::SIGTERM, libc::SIGHUP, libc::SIGINT] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_morpho"))
            .current_dir(dir.path())
            .args(["convert", "p.xyz", "-o", "q.csv"])
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        let tmp_seen = loop {
            let tmp = files(dir.path()).iter().any(|f| f.ends_with(".tmp"));
            if tmp || start.elapsed().as_secs() > 60 {
                break tmp;
            }
            if child.try_wait().unwrap().is_some() {
                break false;
            }
            std::thread::sleep(std::time::Duration::from_micros(200));
        };
        // SAFETY: sending a signal to our own child process.
        unsafe { libc::kill(child.id() as i32, sig) };
        let status = child.wait().unwrap();
        use std::os::unix::process::ExitStatusExt;
        let ended_by_signal = status.code() == Some(128 + sig) || status.signal() == Some(sig);
        assert!(
            ended_by_signal || status.success(),
            "signal {sig}: {status:?}"
        );
        let left: Vec<String> = files(dir.path())
            .into_iter()
            .filter(|f| f.ends_with(".tmp"))
            .collect();
        assert!(left.is_empty(), "signal {sig} left {left:?}");
        if tmp_seen && ended_by_signal {
            proved += 1;
        }
        std::fs::remove_file(dir.path().join("q.csv")).ok();
    }
    // at least one signal landed while the temporary file existed
    assert!(proved > 0, "no signal arrived during a write");
}

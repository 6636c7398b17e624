//! The CLI contract of issue 17 item 12: negative numbers are option values, a usage error
//! names what is missing on one `error:` line, nothing from an input reaches the terminal as a
//! control character.

#[path = "../../morpho/tests/common/mod.rs"]
mod common;
use std::path::Path;
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

/// Twelve points on a wobbly circle (2D, CSV).
fn ring(dir: &Path) {
    let mut s = String::from("x,y\n");
    for i in 0..12 {
        let t = i as f64 * std::f64::consts::TAU / 12.0;
        let r = 1.0 + 0.1 * (i % 3) as f64;
        s.push_str(&format!("{},{}\n", r * t.cos(), r * t.sin()));
    }
    std::fs::write(dir.join("p.csv"), s).unwrap();
}

#[test]
fn negative_numbers_are_option_values() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    ring(d);
    // `--c -0.5` was "unexpected argument '-0' found"; `--c=-0.5` always worked
    for args in [
        &["boundary", "p.csv", "--c", "-0.5", "-o", "b.csv"][..],
        &["boundary", "p.csv", "--c=-0.5", "-o", "b.csv"][..],
        &[
            "graph",
            "p.csv",
            "--kind",
            "beta-lune",
            "--b",
            "-0.5",
            "-o",
            "g.json",
        ][..],
    ] {
        let o = morpho(d, args);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    }
    // a non-finite threshold reaches the command's own check instead of clap's tokenizer
    let o = morpho(
        d,
        &["contour", "p.csv", "--threshold", "-inf", "-o", "c.geojson"],
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("--threshold"), "{e}");
    assert!(!e.contains("unexpected argument"), "{e}");
}

#[test]
fn a_usage_error_names_every_missing_argument_on_one_line() {
    let t = tempfile::tempdir().unwrap();
    let o = morpho(t.path(), &["contour"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    let lines: Vec<&str> = e.lines().collect();
    assert_eq!(lines.len(), 2, "{e}");
    assert!(
        lines[0].starts_with("error: the following required arguments"),
        "{e}"
    );
    for name in ["--output <OUTPUT>", "--threshold <THRESHOLD>", "<INPUT>"] {
        assert!(lines[0].contains(name), "{name} missing in: {e}");
    }
    assert_eq!(lines[1], "(see 'morpho contour --help')");
    // a value left out names its option
    let o = morpho(t.path(), &["graph", "p.csv", "--kind"]);
    let e = stderr(&o);
    assert!(e.starts_with("error: ") && e.contains("--kind"), "{e}");
}

#[test]
fn control_characters_from_inputs_are_escaped() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    // a file name and a header line carrying an escape sequence and a carriage return
    let o = morpho(d, &["info", "no\u{1b}[31mfile\r.xyz"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(!e.contains('\u{1b}') && !e.contains('\r'), "{e:?}");
    assert!(e.contains("\\u{1b}"), "{e:?}");
    std::fs::write(
        d.join("m.ply"),
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float \u{1b}]0;owned\u{7} x\nend_header\n0\n",
    )
    .unwrap();
    let o = morpho(d, &["info", "m.ply"]);
    let e = stderr(&o);
    assert!(
        !e.chars().any(|c| c.is_control() && c != '\n'),
        "control character echoed: {e:?}"
    );
    assert_eq!(e.lines().count(), 1, "{e:?}");
}

/// Issue 17 item 10: `x y 1` rows are 3D points on a plane; the note says which coordinate is
/// constant and `--dims 2` reads them as the 2D set they are.
#[test]
fn a_constant_third_column_is_named_and_dims_2_reads_it_as_2d() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let rows: String = (0..30)
        .map(|i| format!("{} {} 1\n", (i * 7) % 11, (i * 5) % 13))
        .collect();
    std::fs::write(d.join("flat.xyz"), rows).unwrap();
    let o = morpho(d, &["triangulate", "flat.xyz", "-o", "t.json"]);
    let e = stderr(&o);
    assert!(
        e.contains("every point has z = 1") && e.contains("--dims 2"),
        "{e}"
    );
    let o = morpho(
        d,
        &[
            "triangulate",
            "flat.xyz",
            "--dims",
            "2",
            "-o",
            "t.json",
            "--report",
            "r.json",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r = std::fs::read_to_string(d.join("r.json")).unwrap();
    assert!(!stderr(&o).contains("coplanar"), "{}", stderr(&o));
    assert!(r.contains("\"triangles\""), "{r}");
    let o = morpho(
        d,
        &[
            "graph", "flat.xyz", "--dims", "2", "--kind", "emst", "-o", "g.json",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = morpho(
        d,
        &[
            "graph", "flat.xyz", "--dims", "4", "--kind", "emst", "-o", "g.json",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

/// Issue 17 item 12: a NRRD whose spacing makes the coordinates overflow is blamed on the
/// input, not on the output file the writer refused ("s.ply: vertex 1 has a non-finite
/// coordinate" before).
#[test]
fn an_overflowing_volume_extent_is_blamed_on_the_input() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let mut bytes = b"NRRD0004\ntype: float\ndimension: 3\nsizes: 3 3 3\n\
        spacings: 1e308 1e308 1e308\nencoding: ascii\n\n"
        .to_vec();
    for i in 0..27 {
        bytes.extend_from_slice(if i == 13 { b"2\n" } else { b"0\n" });
    }
    std::fs::write(d.join("huge.nrrd"), bytes).unwrap();
    let o = morpho(
        d,
        &["isosurface", "huge.nrrd", "--level", "1", "-o", "s.ply"],
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.starts_with("error: huge.nrrd: ") && !e.contains("s.ply"),
        "{e}"
    );
    assert!(!d.join("s.ply").exists());
}

/// Issue 17 item 12: the 2D boundary report says how many duplicate points it merged.
#[test]
fn the_2d_boundary_report_counts_merged_duplicates() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    ring(d);
    let mut s = std::fs::read_to_string(d.join("p.csv")).unwrap();
    let copies: Vec<String> = s.lines().skip(1).take(3).map(String::from).collect();
    for c in &copies {
        s.push_str(c);
        s.push('\n');
    }
    s.push_str("-0,0.5\n0,0.5\n");
    std::fs::write(d.join("d.csv"), s).unwrap();
    let o = morpho(
        d,
        &["boundary", "d.csv", "-o", "b.csv", "--report", "r.json"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r = std::fs::read_to_string(d.join("r.json")).unwrap();
    assert!(r.contains("\"duplicates_merged\": 4"), "{r}");
}

/// Issue 17 item 7: a small compressed file that claims a huge volume, or decompresses into
/// far more text than the memory limit allows, fails at once naming the limit.
#[test]
fn allocation_bombs_fail_at_once_naming_the_memory_limit() {
    use std::io::Write;
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    // a NRRD header claiming 2000×1000×1000 u8 (about 9.3 GiB in memory) over a tiny gzip
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(&[0u8; 1 << 16]).unwrap();
    let mut nrrd = b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2000 1000 1000\n\
        encoding: gzip\n\n"
        .to_vec();
    nrrd.extend(gz.finish().unwrap());
    std::fs::write(d.join("bomb.nrrd"), nrrd).unwrap();
    // 64 MiB of `0,0` rows in a 64 KiB gzip
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(b"x,y\n").unwrap();
    let rows = b"0,0\n".repeat(1 << 20);
    for _ in 0..16 {
        gz.write_all(&rows).unwrap();
    }
    std::fs::write(d.join("rows.csv.gz"), gz.finish().unwrap()).unwrap();
    for (file, what) in [("bomb.nrrd", "volume"), ("rows.csv.gz", "decompresses")] {
        let o = Command::new(env!("CARGO_BIN_EXE_morpho"))
            .current_dir(d)
            .args(["info", file, "--memory-limit", "256M"])
            .output()
            .unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(e.starts_with(&format!("error: {file}: ")), "{e}");
        assert!(
            e.contains(what) && e.contains("memory limit of 256 MiB"),
            "{e}"
        );
        // the environment variable sets the same limit
        let o = Command::new(env!("CARGO_BIN_EXE_morpho"))
            .current_dir(d)
            .env("MORPHO_MEMORY_LIMIT", "256M")
            .args(["info", file])
            .output()
            .unwrap();
        assert!(
            stderr(&o).contains("memory limit of 256 MiB"),
            "{}",
            stderr(&o)
        );
    }
    // under a generous limit the compressed rows are read
    let o = morpho(d, &["info", "rows.csv.gz", "--memory-limit", "4G"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = morpho(d, &["info", "rows.csv.gz", "--memory-limit", "lots"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

/// Issue 17 item 11: GeoJSON never claims WGS84 on its own; `--crs` names the system.
#[test]
fn geojson_names_the_crs_it_is_given() {
    let dir = tempfile::tempdir().unwrap();
    ring(dir.path());
    let o = morpho(dir.path(), &["boundary", "p.csv", "-o", "plain.geojson"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let plain = std::fs::read_to_string(dir.path().join("plain.geojson")).unwrap();
    assert!(!plain.contains("crs"), "{plain}");
    let o = morpho(
        dir.path(),
        &[
            "boundary",
            "p.csv",
            "-o",
            "rd.geojson",
            "--crs",
            "EPSG:28992",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("rd.geojson")).unwrap()).unwrap();
    assert_eq!(
        v["crs"]["properties"]["name"],
        "urn:ogc:def:crs:EPSG::28992"
    );
    // an input's crs is carried to the outputs (never replaced by an implied WGS84)
    let o = morpho(
        dir.path(),
        &["convert", "rd.geojson", "-o", "carried.geojson"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("carried.geojson")).unwrap())
            .unwrap();
    assert_eq!(
        v["crs"]["properties"]["name"],
        "urn:ogc:def:crs:EPSG::28992"
    );
    let o = morpho(
        dir.path(),
        &["boundary", "p.csv", "-o", "bad.geojson", "--crs", " "],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).starts_with("error: "), "{}", stderr(&o));
}

/// Issue 17 item 11: `convert` of the MNI template (RAS) to MetaImage keeps it in place
/// (SimpleITK showed it mirrored in x and y when the orientation was dropped).
#[test]
fn volume_conversion_keeps_the_orientation() {
    let Some(src) = common::data("volumes/mni_icbm152_t1_2009a_197x233x189.nhdr") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let o = morpho(
        dir.path(),
        &["convert", src.to_str().unwrap(), "-o", "mni.mhd"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let h = std::fs::read_to_string(dir.path().join("mni.mhd")).unwrap();
    assert!(
        h.contains("TransformMatrix = -1.0 0.0 0.0 0.0 -1.0 0.0 0.0 0.0 1.0"),
        "{h}"
    );
    assert!(h.contains("Offset = 98.0 134.0 -72.0"), "{h}");
    let o = morpho(dir.path(), &["convert", "mni.mhd", "-o", "back.nrrd"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// `morpho` with `input` on its standard input.
fn morpho_stdin(dir: &Path, args: &[&str], input: &[u8]) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_morpho"))
        .current_dir(dir)
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run morpho");
    child.stdin.take().unwrap().write_all(input).unwrap();
    child.wait_with_output().unwrap()
}

/// Issue 17 item 4: `-` is standard input (format from `--input-format` or the first bytes)
/// and standard output (`--format` required); the result equals the one through files; a
/// failed command writes nothing to standard output; messages name `-`; nothing is left in
/// the working folder.
#[test]
fn dash_is_standard_input_and_output() {
    let dir = tempfile::tempdir().unwrap();
    ring(dir.path());
    let o = morpho(dir.path(), &["boundary", "p.csv", "-o", "file.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let want = std::fs::read(dir.path().join("file.csv")).unwrap();
    let csv = std::fs::read(dir.path().join("p.csv")).unwrap();
    let o = morpho_stdin(
        dir.path(),
        &["boundary", "-", "-o", "-", "--format", "csv"],
        &csv,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(o.stdout, want);
    // the same rows as whitespace-separated XYZ, recognised without a flag
    let xyz: String = String::from_utf8(csv.clone())
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.replace(',', " ") + "\n")
        .collect();
    let o = morpho_stdin(
        dir.path(),
        &["boundary", "-", "-o", "-", "--format", ".CSV"],
        xyz.as_bytes(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(o.stdout, want);
    // a mesh through a pipe: PLY in, OFF out, read back by info
    let o = morpho(dir.path(), &["triangulate", "p.csv", "-o", "t.ply"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = morpho_stdin(
        dir.path(),
        &["convert", "-", "-o", "-", "--format", "off"],
        &std::fs::read(dir.path().join("t.ply")).unwrap(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        o.stdout.starts_with(b"OFF"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    // the report to standard output
    let o = morpho(
        dir.path(),
        &["boundary", "p.csv", "-o", "r.csv", "--report", "-"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(r["command"], "boundary");
    // failures: exit 2, `error:` naming `-`, nothing on standard output
    let o = morpho_stdin(
        dir.path(),
        &["boundary", "-", "-o", "-", "--format", "csv"],
        b"x,y\n1,nan\n",
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("error: -:"), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    for args in [
        &["boundary", "p.csv", "-o", "-"][..],
        &["boundary", "p.csv", "-o", "x.csv", "--format", "csv"][..],
        &["boundary", "p.csv", "-o", "-", "--format", "mhd"][..],
        &[
            "boundary", "p.csv", "-o", "-", "--report", "-", "--format", "csv",
        ][..],
    ] {
        let o = morpho(dir.path(), args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&o).starts_with("error: "),
            "{args:?}: {}",
            stderr(&o)
        );
        assert!(o.stdout.is_empty(), "{args:?}");
    }
    let mut left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    left.sort();
    assert_eq!(left, ["file.csv", "p.csv", "r.csv", "t.ply"]);
}

/// Tetrahedra are never written silently as something else: `triangulate --tets -o x.obj`
/// (the hull was written) and `boundary --interior x.obj` (JSON was written whatever the
/// extension) are refused; `--interior x.ply` is a tetrahedral PLY.
#[test]
fn tetrahedra_are_written_as_tetrahedra_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = String::new();
    for i in 0..60 {
        let (t, p) = (
            i as f64 * 2.399963,
            ((i as f64 + 0.5) / 60.0 * 2.0 - 1.0).acos(),
        );
        s.push_str(&format!(
            "{} {} {}\n",
            p.sin() * t.cos(),
            p.sin() * t.sin(),
            p.cos()
        ));
    }
    s.push_str("0 0 0.1\n");
    std::fs::write(dir.path().join("s.xyz"), s).unwrap();
    for args in [
        &["triangulate", "s.xyz", "--tets", "-o", "t.obj"][..],
        &["triangulate", "s.xyz", "--tets", "-o", "t.stl"][..],
        &["boundary", "s.xyz", "-o", "b.ply", "--interior", "i.obj"][..],
    ] {
        let o = morpho(dir.path(), args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).starts_with("error: "),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    assert!(
        !dir.path().join("b.ply").exists(),
        "refused before anything was written"
    );
    let o = morpho(
        dir.path(),
        &[
            "boundary",
            "s.xyz",
            "-o",
            "b.ply",
            "--interior",
            "i.ply",
            "--until",
            "locked",
        ],
    );
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let head = std::fs::read(dir.path().join("i.ply")).unwrap();
    let head = String::from_utf8_lossy(&head[..head.len().min(400)]).into_owned();
    assert!(head.contains("element tetra"), "{head}");
}

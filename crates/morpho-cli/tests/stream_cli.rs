//! Issue 24: `morpho isosurface --stream` reads a volume slab by slab and writes, byte for
//! byte, the PLY the in-memory path writes — for every slab thickness, each data encoding
//! (raw, gzip NRRD, zlib MetaImage, raw sidecar), each method and normal mode — and treats
//! bad input as the in-memory path does (`error:`, exit 2, no output left).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn morpho(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_morpho"))
        .args(args)
        .output()
        .expect("run morpho")
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("morpho-stream-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A 23×19×17 f32 volume: a bumpy ball plus noise, with a NaN sample and plateaus at 0.
fn samples() -> ([usize; 3], Vec<f32>) {
    let d = [23usize, 19, 17];
    let mut v = Vec::new();
    let mut seed = 7u64;
    for z in 0..d[2] {
        for y in 0..d[1] {
            for x in 0..d[0] {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let r = (seed >> 40) as f32 / (1u64 << 24) as f32 - 0.5;
                let (fx, fy, fz) = (
                    x as f32 / 11.0 - 1.0,
                    y as f32 / 9.0 - 1.0,
                    z as f32 / 8.0 - 1.0,
                );
                let f = 0.6 - (fx * fx + fy * fy + fz * fz) + 0.15 * (7.0 * fx).sin() + 0.05 * r;
                v.push(if (x + y + z) % 31 == 0 { 0.0 } else { f });
            }
        }
    }
    v[d[0] * d[1] * 8 + d[0] * 9 + 11] = f32::NAN;
    (d, v)
}

fn bytes(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// The volume in four files: raw NRRD, gzip NRRD, zlib MetaImage (oblique, mirrored), sidecar.
fn volumes(dir: &Path) -> Vec<PathBuf> {
    use flate2::write::{GzEncoder, ZlibEncoder};
    use std::io::Write;
    let (d, v) = samples();
    let raw = bytes(&v);
    let head = |enc: &str| {
        format!(
            "NRRD0004\ntype: float\ndimension: 3\nsizes: {} {} {}\nspacings: 0.5 0.7 1.1\nencoding: {enc}\nendian: little\n\n",
            d[0], d[1], d[2]
        )
    };
    let mut out = Vec::new();
    let p = dir.join("raw.nrrd");
    let mut f = head("raw").into_bytes();
    f.extend_from_slice(&raw);
    std::fs::write(&p, f).unwrap();
    out.push(p);
    let p = dir.join("gz.nrrd");
    let mut f = head("gzip").into_bytes();
    let mut g = GzEncoder::new(Vec::new(), flate2::Compression::fast());
    g.write_all(&raw).unwrap();
    f.extend_from_slice(&g.finish().unwrap());
    std::fs::write(&p, f).unwrap();
    out.push(p);
    let mut z = ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    z.write_all(&raw).unwrap();
    std::fs::write(dir.join("z.zraw"), z.finish().unwrap()).unwrap();
    let p = dir.join("z.mhd");
    std::fs::write(
        &p,
        format!(
            "ObjectType = Image\nNDims = 3\nDimSize = {} {} {}\nElementType = MET_FLOAT\n\
             ElementSpacing = 1 1 1.5\nOffset = 3 -2 1\nTransformMatrix = -0.6 0.8 0 0.8 0.6 0 0 0 1\n\
             CompressedData = True\nElementDataFile = z.zraw\n",
            d[0], d[1], d[2]
        ),
    )
    .unwrap();
    out.push(p);
    std::fs::write(dir.join("s.raw"), &raw).unwrap();
    let p = dir.join("s.json");
    std::fs::write(
        &p,
        format!(
            "{{\"data\":\"s.raw\",\"dims\":[{},{},{}],\"dtype\":\"f32\",\"spacing\":[1,2,1]}}",
            d[0], d[1], d[2]
        ),
    )
    .unwrap();
    out.push(p);
    out
}

fn run_ok(args: &[&str]) {
    let o = morpho(args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn streamed_file_equals_in_memory_file() {
    let dir = tmpdir("eq");
    for vol in volumes(&dir) {
        let v = vol.to_str().unwrap();
        for (method, normals, level) in [
            ("decider", "zucker", "0.0"),
            ("decider", "mesh", "0.05"),
            ("tetra", "central", "0.0"),
            ("lorensen", "none", "0.1"),
        ] {
            let a = dir.join("a.ply");
            let a = a.to_str().unwrap();
            let common = [
                "isosurface",
                v,
                "--level",
                level,
                "--method",
                method,
                "--normals",
                normals,
            ];
            run_ok(&[&common[..], &["-o", a]].concat());
            let want = std::fs::read(a).unwrap();
            assert!(want.len() > 10_000, "{v}: a real surface");
            // one slice per slab, a few, all
            for mib in ["0.000001", "0.005", "100"] {
                let b = dir.join("b.ply");
                let b = b.to_str().unwrap();
                run_ok(&[&common[..], &["-o", b, "--stream", "--slab-mib", mib]].concat());
                let got = std::fs::read(b).unwrap();
                assert!(
                    got == want,
                    "{v} {method} {normals} slab {mib} MiB: files differ"
                );
            }
            // ASCII too
            let (a2, b2) = (dir.join("a2.ply"), dir.join("b2.ply"));
            run_ok(&[&common[..], &["-o", a2.to_str().unwrap(), "--ascii"]].concat());
            run_ok(
                &[
                    &common[..],
                    &[
                        "-o",
                        b2.to_str().unwrap(),
                        "--ascii",
                        "--stream",
                        "--slab-mib",
                        "0.01",
                    ],
                ]
                .concat(),
            );
            assert!(
                std::fs::read(a2).unwrap() == std::fs::read(b2).unwrap(),
                "{v} ascii"
            );
        }
    }
    // no temporary file is left beside the outputs
    let left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

fn assert_refused(o: &Output, what: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{what}: {err}");
    assert!(
        err.starts_with("error: ") && !err.contains("panicked"),
        "{what}: {err}"
    );
}

#[test]
fn bad_input_is_refused_without_output() {
    let dir = tmpdir("bad");
    let vols = volumes(&dir);
    let out = dir.join("o.ply");
    let o = out.to_str().unwrap();
    let raw = vols[0].to_str().unwrap();
    let s = |extra: &[&str], v: &str| {
        morpho(
            &[
                &["isosurface", v, "--level", "0", "-o", o, "--stream"][..],
                extra,
            ]
            .concat(),
        )
    };
    assert_refused(&s(&["--largest-part"], raw), "largest part");
    let obj = dir.join("o.obj");
    assert_refused(
        &morpho(&[
            "isosurface",
            raw,
            "--level",
            "0",
            "-o",
            obj.to_str().unwrap(),
            "--stream",
        ]),
        "obj",
    );
    // truncated raw data, truncated gzip data, trailing gzip data
    let full = std::fs::read(&vols[0]).unwrap();
    let cut = dir.join("cut.nrrd");
    std::fs::write(&cut, &full[..full.len() - 100]).unwrap();
    assert_refused(&s(&[], cut.to_str().unwrap()), "short raw");
    let gz = std::fs::read(&vols[1]).unwrap();
    let cutgz = dir.join("cut_gz.nrrd");
    std::fs::write(&cutgz, &gz[..gz.len() - 200]).unwrap();
    assert_refused(&s(&[], cutgz.to_str().unwrap()), "short gzip");
    // text encoding cannot be streamed: said so
    let text = dir.join("t.nrrd");
    std::fs::write(
        &text,
        "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: text\n\n1 2 3 4 5 6 7 8\n",
    )
    .unwrap();
    let e = s(&[], text.to_str().unwrap());
    assert_refused(&e, "text");
    assert!(String::from_utf8_lossy(&e.stderr).contains("text"));
    assert!(!out.exists(), "no output after a failure");
    let left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_volume_over_the_memory_limit_is_streamed() {
    let dir = tmpdir("limit");
    let vols = volumes(&dir);
    let v = vols[0].to_str().unwrap();
    let (a, b) = (dir.join("a.ply"), dir.join("b.ply"));
    run_ok(&["isosurface", v, "--level", "0", "-o", a.to_str().unwrap()]);
    // 23·19·17 samples need ~59 KiB in memory: over a 40 KiB limit the whole read is refused
    // and says how to go on; the stream reads one slice at a time and gives the same file
    let limited = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_morpho"))
            .args(args)
            .env("MORPHO_MEMORY_LIMIT", "40K")
            .output()
            .expect("run morpho")
    };
    let o = limited(&["isosurface", v, "--level", "0", "-o", b.to_str().unwrap()]);
    assert_refused(&o, "over the limit");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("memory limit") && err.contains("--stream"),
        "{err}"
    );
    let o = limited(&[
        "isosurface",
        v,
        "--level",
        "0",
        "-o",
        b.to_str().unwrap(),
        "--stream",
        "--slab-mib",
        "0.001",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

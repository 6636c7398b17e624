//! Byte-mutation fuzzing of every parser (issue 17, "a fuzzing campaign in the test suite").
//!
//! Seeds: the real files of `../shared/data` (cut to their first 24 KiB so that a case stays
//! cheap; the header and the first records are what a mutation finds bugs in) and files written
//! by morpho's own writers in every encoding. Each seed is mutated deterministically (seeded
//! ChaCha: flip, insert, delete, duplicate, splice in a hostile token, truncate) and every case
//! asserts three things:
//! - **no panic**: the parser is run under `catch_unwind`; a panic fails the test with the
//!   format, the seed and the case number (re-run one with `FUZZ_CASE=format:seed:case`);
//! - **a time bound**: [`CASE_SECONDS`] per case (release build; inputs are < 40 KiB);
//! - **bounded allocation**: a counting global allocator records the peak of live bytes on the
//!   parsing thread; a case fails when that peak exceeds [`ALLOC_FACTOR`] × its input size
//!   plus [`ALLOC_SLACK`] — a header that claims a billion vertices must be refused before the
//!   allocation, not after.
//!
//! `FUZZ_CASES` sets the cases per seed (default 1000: with the seeds below, 1000–6000 cases per
//! format per run).

mod common;
use common::data_dir;
use morpho::io;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Allowed peak of live bytes per input byte (the widest in-memory form of a text record is
/// ~60 bytes per input byte; see `io::memory::PARSE_FACTOR`).
const ALLOC_FACTOR: usize = 64;
/// Allowed peak on top of that (buffers, maps, the error message).
const ALLOC_SLACK: usize = 8 << 20;
/// Wall-clock bound per case.
const CASE_SECONDS: f64 = 2.0;

struct Counting;

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn note(delta: isize) {
    // `try_with`: the allocator runs during thread teardown too.
    let _ = LIVE.try_with(|l| {
        let v = l.get() + delta;
        l.set(v);
        let _ = PEAK.try_with(|p| {
            if v > p.get() {
                p.set(v)
            }
        });
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            note(layout.size() as isize);
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc_zeroed(layout);
        if !p.is_null() {
            note(layout.size() as isize);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        note(-(layout.size() as isize));
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = System.realloc(ptr, layout, new_size);
        if !p.is_null() {
            note(new_size as isize - layout.size() as isize);
        }
        p
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Runs `f` and returns the peak of bytes it held live above what was live before.
fn peak_of<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = LIVE.with(|l| l.get());
    PEAK.with(|p| p.set(base));
    let out = f();
    let peak = PEAK.with(|p| p.get());
    (out, (peak - base).max(0) as usize)
}

/// The first `max` bytes of a file (gunzipped when it ends in `.gz`).
fn head(path: &Path, max: usize) -> Option<Vec<u8>> {
    use std::io::Read;
    let f = std::fs::File::open(path).ok()?;
    let mut out = Vec::new();
    if path.extension().is_some_and(|e| e == "gz") {
        flate2::read::GzDecoder::new(f)
            .take(max as u64)
            .read_to_end(&mut out)
            .ok()?;
    } else {
        f.take(max as u64).read_to_end(&mut out).ok()?;
    }
    Some(out)
}

const TOKENS: &[&[u8]] = &[
    b"4294967295",
    b"18446744073709551615",
    b"-1",
    b"1e308",
    b"1e999",
    b"nan",
    b"-inf",
    b"0",
    b"999999999",
    b"\0",
    b"\r",
    b"\n",
    b"\xef\xbb\xbf",
    b"\xff\xfe",
    b"element vertex 2000000000\n",
    b"element face 2000000000\n",
    b"property list uint uint vertex_indices\n",
    b"f 1 1 2\n",
    b"v 1e300 -1e300 nan\n",
    b"{\"type\":\"Polygon\",\"coordinates\":[[[",
    b"]]]}",
    b"sizes: 100000 100000 100000\n",
    b"DimSize = 100000 100000 100000\n",
    b"\"dims\":[100000,100000,100000]",
    b"encoding: gzip\n",
    b"data file: /etc/passwd\n",
    b"ElementDataFile = ../../x.raw\n",
];

/// One mutation of `seed` (1–4 edits).
fn mutate(seed: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut b = seed.to_vec();
    for _ in 0..rng.gen_range(1..=4) {
        let n = b.len();
        match rng.gen_range(0..7) {
            0 if n > 0 => {
                let i = rng.gen_range(0..n);
                b[i] ^= 1 << rng.gen_range(0..8);
            }
            1 => {
                let i = rng.gen_range(0..=n);
                b.insert(i, rng.gen());
            }
            2 if n > 0 => {
                let i = rng.gen_range(0..n);
                let j = (i + rng.gen_range(1..64)).min(n);
                b.drain(i..j);
            }
            3 if n > 0 => {
                let i = rng.gen_range(0..n);
                let j = (i + rng.gen_range(1..256)).min(n);
                let piece = b[i..j].to_vec();
                let k = rng.gen_range(0..=b.len());
                b.splice(k..k, piece);
            }
            4 => {
                let t = TOKENS[rng.gen_range(0..TOKENS.len())];
                let i = rng.gen_range(0..=n);
                // replace the number-ish run at i, if any, else insert
                let mut j = i;
                while j < n && (b[j].is_ascii_alphanumeric() || b[j] == b'.' || b[j] == b'-') {
                    j += 1;
                }
                b.splice(i..j, t.iter().copied());
            }
            5 if n > 0 => {
                b.truncate(rng.gen_range(0..n));
            }
            _ if n > 0 => {
                // a digit changed: counts and indices go out of range
                if let Some(i) = (0..8)
                    .map(|_| rng.gen_range(0..n))
                    .find(|&i| b[i].is_ascii_digit())
                {
                    b[i] = b'0' + rng.gen_range(0..10);
                }
            }
            _ => {}
        }
    }
    b
}

type Parser = fn(&[u8], &Path) -> bool;

/// A format: its parser on bytes (volumes: on a file written into `dir`) and its seeds.
struct Target {
    name: &'static str,
    parse: Parser,
    seeds: Vec<(String, Vec<u8>)>,
}

fn ok<T>(r: morpho::Result<T>) -> bool {
    r.is_ok()
}

fn parse_volume(bytes: &[u8], dir: &Path, name: &str) -> bool {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    ok(io::read_volume(&p))
}

fn cases_per_seed() -> usize {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000)
}

/// Generated seeds: small meshes, point sets and volumes in every encoding morpho writes.
fn generated(name: &str) -> Vec<(String, Vec<u8>)> {
    use morpho::io::Encoding;
    use morpho::mesh::generate;
    let mesh = generate::torus(1.0, 0.4, 8, 5);
    let mut pts = morpho::mesh::PointSet::from_points3(&mesh.positions);
    pts.columns.push(morpho::mesh::Column {
        name: "value".into(),
        values: (0..mesh.positions.len()).map(|i| i as f64 * 0.5).collect(),
    });
    let buf = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut v = Vec::new();
        f(&mut v);
        v
    };
    let mut out = Vec::new();
    match name {
        "ply" => {
            for enc in [
                Encoding::Ascii,
                Encoding::BinaryLittleEndian,
                Encoding::BinaryBigEndian,
            ] {
                out.push((
                    format!("mesh {enc:?}"),
                    buf(&|w| io::ply::write_mesh(w, &mesh, enc).unwrap()),
                ));
                out.push((
                    format!("points {enc:?}"),
                    buf(&|w| io::ply::write_points(w, &pts, enc).unwrap()),
                ));
            }
        }
        "obj" => out.push(("torus".into(), buf(&|w| io::obj::write(w, &mesh).unwrap()))),
        "off" => out.push(("torus".into(), buf(&|w| io::off::write(w, &mesh).unwrap()))),
        "stl" => {
            for enc in [Encoding::Ascii, Encoding::BinaryLittleEndian] {
                out.push((
                    format!("{enc:?}"),
                    buf(&|w| io::stl::write(w, &mesh, enc).unwrap()),
                ));
            }
        }
        "csv" => out.push((
            "points".into(),
            buf(&|w| io::csv::write_points(w, &pts).unwrap()),
        )),
        "xyz" => out.push(("points".into(), buf(&|w| io::xyz::write(w, &pts).unwrap()))),
        "nrrd" | "mhd" | "json" => {
            let v = morpho::volume::Volume::new(
                [5, 4, 3],
                [0.0, 1.0, 2.0],
                [0.5, 1.0, 2.0],
                (0..60).map(|i| i as f32).collect(),
            )
            .unwrap();
            let dir = tempfile::tempdir().unwrap();
            let p = dir.path().join(format!("v.{name}"));
            io::write_volume(&p, &v).unwrap();
            // the header only: the data file stays beside it under its own name
            out.push(("header".into(), std::fs::read(&p).unwrap()));
        }
        _ => {}
    }
    out
}

fn real(dir: &Option<PathBuf>, rel: &[&str]) -> Vec<(String, Vec<u8>)> {
    let Some(d) = dir else { return Vec::new() };
    rel.iter()
        .filter_map(|r| head(&d.join(r), 24 << 10).map(|b| (r.to_string(), b)))
        .collect()
}

fn targets() -> Vec<Target> {
    let d = data_dir();
    let mk = |name: &'static str, parse: Parser, real_files: &[&str]| {
        let mut seeds = generated(name);
        seeds.extend(real(&d, real_files));
        Target { name, parse, seeds }
    };
    vec![
        mk(
            "ply",
            |b, _| {
                ok(io::ply::read_mesh(b)) | ok(io::ply::read_points(b)) | ok(io::ply::read_tets(b))
            },
            &[],
        ),
        mk(
            "obj",
            |b, _| ok(io::obj::read(b)),
            &[
                "meshes/bunny_npm.obj",
                "meshes/spot.obj",
                "meshes/horse.obj.gz",
            ],
        ),
        mk("off", |b, _| ok(io::off::read(b)), &[]),
        mk("stl", |b, _| ok(io::stl::read(b)), &[]),
        mk(
            "csv",
            |b, _| ok(io::csv::read_points(b)) | ok(io::csv::read_polygon(b)),
            &[
                "geostat/meuse.csv",
                "geostat/jura_val.csv",
                "polygons/benelux_mainland_ne50m.csv",
            ],
        ),
        mk(
            "xyz",
            |b, _| ok(io::xyz::read(b)),
            &[
                "curves2d/ohrhallinger_fitconnect/fish.txt",
                "curves2d/ohrhallinger_hnncrust/mushroom.p2d",
            ],
        ),
        mk(
            "geojson",
            |b, _| ok(io::geojson::read(b)) | ok(io::json::read_points(b)),
            &[
                "polygons/benelux_mainland_ne50m.geojson",
                "polygons/benelux_countries_ne10m.geojson",
            ],
        ),
        mk(
            "nrrd",
            |b, dir| parse_volume(b, dir, "f.nrrd") | parse_volume(b, dir, "f.nhdr"),
            &[
                "volumes/cthead_8bit_256x256x99.nhdr",
                "volumes/dipy_aniso_vox_58x58x24_i16.nhdr",
            ],
        ),
        mk("mhd", |b, dir| parse_volume(b, dir, "f.mhd"), &[]),
        mk(
            "json",
            |b, dir| parse_volume(b, dir, "f.json"),
            &["volumes/mni_icbm152_t1_2009a_197x233x189.json"],
        ),
    ]
}

/// Runs every case of one format; returns (cases, accepted) or panics naming the first failure.
fn campaign(t: &Target, only: Option<(usize, usize)>) -> (usize, usize) {
    let dir = tempfile::tempdir().unwrap();
    // the data files a mutated header may name: present, small, in the header's folder
    std::fs::write(dir.path().join("v.raw"), vec![0u8; 60 * 4]).unwrap();
    std::fs::write(dir.path().join("v.nrrd.raw"), vec![0u8; 60 * 4]).unwrap();
    let per_seed = cases_per_seed();
    let (mut cases, mut accepted) = (0, 0);
    for (si, (seed_name, seed)) in t.seeds.iter().enumerate() {
        for case in 0..per_seed {
            if let Some((s, c)) = only {
                if (s, c) != (si, case) {
                    continue;
                }
            }
            let mut rng = ChaCha8Rng::seed_from_u64(((si as u64) << 32) | case as u64);
            let input = if case == 0 {
                seed.clone()
            } else {
                mutate(seed, &mut rng)
            };
            let start = Instant::now();
            let (r, peak) =
                peak_of(|| catch_unwind(AssertUnwindSafe(|| (t.parse)(&input, dir.path()))));
            let secs = start.elapsed().as_secs_f64();
            let id = format!("{}:{si}:{case} (seed {seed_name})", t.name);
            match r {
                // a seed morpho wrote itself must read back: otherwise the campaign mutates junk
                Ok(false) if case == 0 && !seed_name.contains('/') => {
                    panic!("{id}: morpho's own file is refused")
                }
                Ok(a) => accepted += a as usize,
                Err(_) => panic!("{id}: the parser panicked on {} bytes", input.len()),
            }
            assert!(
                secs < CASE_SECONDS,
                "{id}: {secs:.2} s on {} bytes",
                input.len()
            );
            let bound = ALLOC_FACTOR * input.len() + ALLOC_SLACK;
            assert!(
                peak <= bound,
                "{id}: {} bytes of input held {} bytes live (bound {bound})",
                input.len(),
                peak
            );
            cases += 1;
        }
    }
    (cases, accepted)
}

#[test]
fn every_parser_survives_byte_mutations() {
    // A mutated header may claim gigabytes: the documented limit is what stops it first.
    std::env::set_var("MORPHO_MEMORY_LIMIT", "256M");
    // Panics are caught and reported by `campaign`; keep the default hook quiet meanwhile.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let only = std::env::var("FUZZ_CASE").ok();
    let mut lines = Vec::new();
    let result = catch_unwind(AssertUnwindSafe(|| {
        for t in targets() {
            let sel = only.as_deref().and_then(|s| {
                let mut it = s.split(':');
                (it.next() == Some(t.name)).then(|| {
                    let si = it.next().and_then(|x| x.parse().ok()).unwrap_or(0);
                    let c = it.next().and_then(|x| x.parse().ok()).unwrap_or(0);
                    (si, c)
                })
            });
            if only.is_some() && sel.is_none() {
                continue;
            }
            assert!(!t.seeds.is_empty(), "{}: no seed", t.name);
            let start = Instant::now();
            let (cases, accepted) = campaign(&t, sel);
            lines.push(format!(
                "{:8} {:3} seeds {:6} cases {:6} accepted {:6.2} s",
                t.name,
                t.seeds.len(),
                cases,
                accepted,
                start.elapsed().as_secs_f64()
            ));
        }
    }));
    std::panic::set_hook(hook);
    for l in &lines {
        eprintln!("{l}");
    }
    if let Err(e) = result {
        let msg = e
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        panic!("{msg}");
    }
}

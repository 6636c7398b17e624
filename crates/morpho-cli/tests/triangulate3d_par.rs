//! `morpho triangulate` on 3D input uses both cores on large inputs (issue 23 item 3): with two
//! rayon threads the facade splits and merges (`morpho::delaunay` `par3.rs`); the tetrahedron set
//! must be the one-thread set, each order deterministic.

use std::process::Command;

fn run(threads: &str, input: &str, out: &str) -> Vec<[u64; 4]> {
    let o = Command::new(env!("CARGO_BIN_EXE_morpho"))
        .env("RAYON_NUM_THREADS", threads)
        .args(["triangulate", input, "-o", out])
        .output()
        .expect("run morpho");
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(out).unwrap()).unwrap();
    v["tetrahedra"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            let a = t.as_array().unwrap();
            [0, 1, 2, 3].map(|i| a[i].as_u64().unwrap())
        })
        .collect()
}

fn canon(t: &[[u64; 4]]) -> Vec<[u64; 4]> {
    let mut v: Vec<[u64; 4]> = t
        .iter()
        .map(|x| {
            let mut s = *x;
            s.sort_unstable();
            s
        })
        .collect();
    v.sort_unstable();
    v
}

#[test]
fn two_threads_give_the_one_thread_tetrahedra() {
    let dir = tempfile::tempdir().unwrap();
    // 80 000 points (above the split threshold) from a fixed linear congruential sequence,
    // on a coarse lattice in one coordinate so that ties cross the split
    let mut s: u64 = 12345;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut txt = String::new();
    for _ in 0..80_000 {
        let (x, y, z) = ((next() * 400.0).floor() / 400.0, next(), next());
        txt.push_str(&format!("{x} {y} {z}\n"));
    }
    let input = dir.path().join("p.xyz");
    std::fs::write(&input, txt).unwrap();
    let inp = input.to_str().unwrap();
    let one = run("1", inp, dir.path().join("one.json").to_str().unwrap());
    let two = run("2", inp, dir.path().join("two.json").to_str().unwrap());
    let two_again = run("2", inp, dir.path().join("two2.json").to_str().unwrap());
    assert_eq!(canon(&one), canon(&two));
    assert_eq!(two, two_again, "the two-thread output is deterministic");
    // the split path ran: its order (final parts, then the seam) is not the engine's
    assert_ne!(one, two);
}

//! `morpho triangulate` on two threads takes the split path of `delaunay/par2.rs` (issue 23 item
//! 3) for large inputs: the same triangles as on one thread, as a set (the order differs).

use std::process::Command;

/// The triangles of an OFF file, each rotated to start at its smallest index, in file order.
fn off_faces(path: &std::path::Path) -> Vec<[u32; 3]> {
    let s = std::fs::read_to_string(path).unwrap();
    let mut lines = s
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    assert_eq!(lines.next().map(str::trim), Some("OFF"));
    let counts: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let mut lines = lines.skip(counts[0]);
    (0..counts[1])
        .map(|_| {
            let f: Vec<u32> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            assert_eq!(f[0], 3);
            let t = [f[1], f[2], f[3]];
            let k = (0..3).min_by_key(|&i| t[i]).unwrap();
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect()
}

#[test]
fn two_threads_give_the_one_thread_triangles() {
    let dir = tempfile::tempdir().unwrap();
    // 65 000 points (above the split threshold): a uniform cloud through which runs a
    // jittered curve (few enough curve points for the seam predictor to accept the split)
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut csv = String::from("x,y\n");
    for k in 0..5_000 {
        let t = k as f64 * std::f64::consts::TAU / 5_000.0;
        let r = 1.0 + 0.3 * (5.0 * t).sin();
        csv += &format!("{},{}\n", r * t.cos() + 1e-9 * next(), r * t.sin());
    }
    for _ in 0..60_000 {
        csv += &format!("{},{}\n", 4.0 * next() - 2.0, 4.0 * next() - 2.0);
    }
    let input = dir.path().join("p.csv");
    std::fs::write(&input, csv).unwrap();
    let run = |threads: &str| {
        let out = dir.path().join(format!("t{threads}.off"));
        let o = Command::new(env!("CARGO_BIN_EXE_morpho"))
            .env("RAYON_NUM_THREADS", threads)
            .args(["triangulate", input.to_str().unwrap(), "-o"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        off_faces(&out)
    };
    let (one, two) = (run("1"), run("2"));
    assert_ne!(
        one, two,
        "two threads should take the split path (another order)"
    );
    let sorted = |mut v: Vec<[u32; 3]>| {
        v.sort_unstable();
        v
    };
    assert_eq!(sorted(one), sorted(two));
}

//! Hamann 1991, Tables 4.1 (p. 74) and 4.2 (p. 88) recomputed beside the thesis's numbers
//! (notes C.4, C.5; `morpho::curvature::tables`): RMS over the determined vertices, the ratio
//! to the thesis, and the interior-only RMS.
//!
//! ```text
//! cargo run --release -p morpho --example curvature_tables [-- M2 M3]
//! ```
//! (grid sizes, default 51 and 26 as in the thesis).
use morpho::curvature::tables::{table_4_1, table_4_2, TableRow};
use std::time::Instant;

fn print(title: &str, cols: &[&str], rows: &[TableRow], n: usize, interior: usize) {
    println!("\n{title}\n");
    let mut head = String::from("| # | function | undet. |");
    let mut rule = String::from("|---|---|---|");
    for c in cols {
        head += &format!(" {c} thesis | {c} morpho | ratio |");
        rule += "---|---|---|";
    }
    for c in cols {
        head += &format!(" {c} interior |");
        rule += "---|";
    }
    println!("{head}\n{rule}");
    for r in rows {
        let mut line = format!("| {} | {} | {} |", r.row, r.name, r.undetermined);
        for i in 0..cols.len() {
            let ratio = if r.thesis[i] > 0.0 {
                format!("{:.2}", r.rms[i] / r.thesis[i])
            } else {
                format!("({:.0e})", r.rms[i])
            };
            line += &format!(" {:.6} | {:.6} | {ratio} |", r.thesis[i], r.rms[i]);
        }
        for i in 0..cols.len() {
            line += &format!(" {:.6} |", r.rms_interior[i]);
        }
        println!("{line}");
    }
    println!(
        "\nRMS over the {} determined of {n} grid points; interior: the {interior} points off \
         the grid's border. ratio = morpho / thesis (≤ 1: at most the thesis's error).",
        n - rows.first().map_or(0, |r| r.undetermined),
    );
}

fn main() {
    let a: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let (m2, m3) = (
        a.first().copied().unwrap_or(51),
        a.get(1).copied().unwrap_or(26),
    );
    let t = Instant::now();
    let t41 = table_4_1(m2);
    let s41 = t.elapsed().as_secs_f64();
    print(
        &format!(
            "Table 4.1 (H p. 74): {m2}×{m2} grid over [-1,1]², exact normals, 1-ring paraboloid \
             ({s41:.3} s)"
        ),
        &["κ1", "κ2", "H", "K"],
        &t41,
        m2 * m2,
        (m2 - 2) * (m2 - 2),
    );
    let t = Instant::now();
    let t42 = table_4_2(m3);
    let s42 = t.elapsed().as_secs_f64();
    print(
        &format!(
            "Table 4.2 (H p. 88): {m3}³ grid over [-1,1]³, exact gradients, 6-tetrahedra \
             platelet ({s42:.3} s)"
        ),
        &["H", "K"],
        &t42,
        m3 * m3 * m3,
        (m3 - 2).pow(3),
    );
}

//! Hamann 1991, Table 5.1 (notes D.4): RMS (5.41) at the 2601 knots after keeping 50/20/10 %
//! of the 5000 triangles, beside the thesis's values. `cargo run --release --example table51`.
use morpho::reduce::table51;

fn main() {
    println!("| # | function | 50% | thesis | 80% | thesis | 90% | thesis |");
    println!("|---|---|---|---|---|---|---|---|");
    for (k, (name, _, _)) in table51::functions().iter().enumerate() {
        let mut row = format!("| {} | {name} |", k + 1);
        for (c, keep) in [50.0, 20.0, 10.0].into_iter().enumerate() {
            let (rms, n) = table51::rms(k, keep).expect("reduce");
            row += &format!(" {rms:.6} ({n}) | {:.6} |", table51::THESIS[k][c]);
        }
        println!("{row}");
    }
}

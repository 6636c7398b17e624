//! Hamann 1991, Table 5.1 (notes D.4): RMS (5.41) at the 2601 knots after keeping 50/20/10 %
//! of the 5000 triangles, beside the thesis's values and their ratio.
//! `cargo run --release --example table51 -p morpho [-- --last-step]`: `--last-step` uses the
//! narrow reading of Rem. 5.9 (only the last step's triangles are "new") for comparison;
//! `--levels` removes in the error-levels order (`Order::ErrorLevels`, the CLI's default).
use morpho::reduce::table51;

fn main() {
    let last = std::env::args().any(|a| a == "--last-step");
    let order = if std::env::args().any(|a| a == "--levels") {
        morpho::reduce::Order::ErrorLevels
    } else {
        morpho::reduce::Order::Hamann
    };
    println!("| # | function | 50 % removed | thesis | ratio | 80 % | thesis | ratio | 90 % | thesis | ratio |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let t0 = std::time::Instant::now();
    let mut worst: f64 = 0.0;
    for (k, (name, f, _)) in table51::functions().iter().enumerate() {
        let mut row = format!("| {} | {name} |", k + 1);
        for (c, keep) in [50.0, 20.0, 10.0].into_iter().enumerate() {
            let new = if last {
                morpho::reduce::NewTriangles::LastStep
            } else {
                morpho::reduce::NewTriangles::Generations
            };
            let r = table51::reduce_function_ordered(k, keep, new, order).expect("reduce");
            let (rms, _, miss) = table51::knot_rms(&r.mesh, *f);
            assert_eq!(miss, 0, "domain not covered");
            let th = table51::THESIS[k][c];
            let ratio = if th > 0.0 { rms / th } else { 0.0 };
            worst = worst.max(ratio);
            let ratio = if th > 0.0 {
                format!("{ratio:.2}")
            } else {
                format!("{rms:.0e}")
            };
            row += &format!(" {rms:.6} | {th:.6} | {ratio} |");
        }
        println!("{row}");
    }
    println!(
        "\nworst ratio {worst:.3}; 27 reductions in {:.2} s",
        t0.elapsed().as_secs_f64()
    );
}

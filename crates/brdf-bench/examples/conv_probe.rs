use brdf_core::split_sum::converged::DfgGgxRow;
use brdf_core::split_sum::polar::DfgGgxPolarRow;
use std::time::Instant;
fn main() {
    let pts: [(f64, f64); 0] = [];
    for (mu, r) in pts {
        let p = DfgGgxPolarRow::new(r).texel(mu, 1e-12);
        for tol in [1e-6, 1e-7, 1e-8, 1e-10] {
            let c = DfgGgxRow::new(r).texel(mu, tol);
            println!("mu {mu} r {r} tol {tol:e}: dA {:.3e} dB {:.3e} est {:.1e} {:.1e} pol est {:.1e} rows {} evals {}",
                c.value[0]-p.value[0], c.value[1]-p.value[1], c.error[0], c.error[1], p.error[1], c.rows, c.evals);
        }
    }
    // grid
    let n = if std::env::args().len() > 1 { 24 } else { 0 };
    let (mut worst, mut bad, mut tt, mut cnt) = (0f64, 0, 0.0, 0);
    for j in 0..n { for i in 0..n {
        let (mu, r) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
        let p = DfgGgxPolarRow::new(r).texel(mu, 1e-10);
        let t0 = Instant::now();
        let c = DfgGgxRow::new(r).texel(mu, 1e-6);
        tt += t0.elapsed().as_secs_f64(); cnt += 1;
        for ch in 0..2 {
            let d = (c.value[ch] - p.value[ch]).abs();
            worst = worst.max(d);
            if d > c.error[ch] + p.error[ch] { bad += 1; if bad < 40 { println!("  mu {mu:.4} r {r:.4} ch {ch} d {:.2e} est {:.1e} {:.1e}", c.value[ch]-p.value[ch], c.error[ch], p.error[ch]); } }
        }
    }}
    println!("grid {n}x{n} tol 1e-6: max |conv - polar| {worst:.2e}, over sum of estimates {bad}, conv {:.0} us/texel", tt / cnt as f64 * 1e6);
}

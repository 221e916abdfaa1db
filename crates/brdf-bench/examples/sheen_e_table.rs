//! The sheen albedo E_sheen(μ, r) (`brdf_lut::generate::sheen_e`, both visibilities at once)
//! at the texel centres of a size × size grid (μ = (i + ½)/size, r = (j + ½)/size, the
//! Khronos axes), every `stride`-th row, on one thread: time per texel, D evaluations per
//! texel and the largest error estimate, so the cost of a full 1024² texture can be
//! extrapolated (a measurement, not a claim in a test).
//!
//! With `grid` as the first argument it times the grid route instead
//! (`brdf_lut::generate::sheen_grid`, the engine textures' texels, on all cores, at the
//! Khronos tolerances: ½ LSB of u16 for Estevez–Kulla, of u8 for Ashikhmin): wall time,
//! nodes, patches, D evaluations per texel and the estimate (run it under `time` for
//! user + sys).
//!
//! ```text
//! cargo run --release -p brdf-bench --example sheen_e_table -- [size] [stride] [tol]
//! cargo run --release -p brdf-bench --example sheen_e_table -- grid [size]
//! ```

use brdf_lut::generate::{sheen_e, sheen_grid, SHEEN_TOL};
use std::time::Instant;

/// The grid route at `size`² (see the module docs).
fn grid(size: usize) {
    let t0 = Instant::now();
    let g = sheen_grid(size, [7e-6, 1.9e-3]);
    println!(
        "sheen_grid {size}²: {:.2} s wall, {} nodes in {} patches, {} D evaluations/texel \
         ({} per node), estimate [EK, Ashikhmin] {:.2e} {:.2e}",
        t0.elapsed().as_secs_f64(),
        g.nodes,
        g.patches,
        g.evals / (size * size).max(1) as u64,
        g.evals / g.nodes.max(1) as u64,
        g.bound[0],
        g.bound[1]
    );
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    if a.get(1).map(String::as_str) == Some("grid") {
        grid(a.get(2).and_then(|s| s.parse().ok()).unwrap_or(1024));
        return;
    }
    let size: usize = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(1024);
    let stride: usize = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(64).max(1);
    let tol: f64 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(SHEEN_TOL);
    let t0 = Instant::now();
    let (mut texels, mut evals, mut worst) = (0u64, 0u64, 0f64);
    for j in (0..size).step_by(stride) {
        let r = (j as f64 + 0.5) / size as f64;
        for i in 0..size {
            let mu = (i as f64 + 0.5) / size as f64;
            let e = sheen_e(mu, r, tol);
            texels += 1;
            evals += e.evals;
            worst = worst.max(e.error[0]).max(e.error[1]);
        }
    }
    let dt = t0.elapsed().as_secs_f64();
    let per = dt / texels as f64;
    println!(
        "{texels} texels (every {stride}th of {size} rows), tol {tol:e}: {:.1} us/texel, \
         {} D evaluations/texel, largest estimate {worst:.2e}; a full {size}² grid on one \
         core: {:.0} s",
        per * 1e6,
        evals / texels,
        per * (size * size) as f64
    );
}

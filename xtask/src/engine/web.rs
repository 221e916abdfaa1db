//! Inputs of the WebGL2 engine-LUT test (examples/web/test/lut_engine.test.mjs): the khronos
//! table at 64² with its GLSL function, and random (μ, r) points with the f64 integral and
//! the error bound the GPU sample must meet.

use super::{centre, compute_grid, integral, report, write_set, OutFile};
use anyhow::Result;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::path::Path;

/// Table edge of the browser test.
pub const N: usize = 64;
/// Points sampled by the fragment shader (a 64 × 32 render target).
pub const POINTS: usize = 2048;

/// Writes `dir/lut_ggx.png`, `dir/lut_ggx.glsl`, … and `dir/points.json`.
pub fn prepare(dir: &Path) -> Result<()> {
    let grid = compute_grid(N, true);
    let files = super::encode::files(super::Target::Khronos, &grid)?;
    let exact = report::Table {
        n: N,
        a: grid.a.clone(),
        b: grid.b.clone(),
    };
    let lo = centre(0, N);
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x0EB6_1011);
    let pts: Vec<(f64, f64)> = (0..POINTS)
        .map(|_| {
            (
                rng.random_range(lo..1.0 - lo),
                rng.random_range(lo..1.0 - lo),
            )
        })
        .collect();
    let rows: Vec<serde_json::Value> = pts
        .par_iter()
        .map(|&(mu, r)| {
            let (a, b) = integral(mu, r);
            let (xa, xb) = exact.sample(mu, r);
            // Spread of the four texels around the point, for the GPU's fixed-point
            // bilinear weights (8 fractional bits: weight error ≤ 2⁻⁹ per axis).
            let (sa, sb) = spread(&exact, mu, r);
            // Bound: interpolation error of exact texels + half an 8-bit unit + weight
            // quantisation (2 axes × 2⁻⁹ × spread) + f32 arithmetic in the shader (1e-6).
            let bound_a = (xa - a).abs() + 0.5 / 255.0 + sa * 2f64.powi(-8) + 1e-6;
            let bound_b = (xb - b).abs() + 0.5 / 255.0 + sb * 2f64.powi(-8) + 1e-6;
            serde_json::json!([mu, r, a, b, bound_a, bound_b])
        })
        .collect();
    let mut files = files;
    files.push(OutFile {
        name: "points.json".into(),
        bytes: serde_json::to_vec(&serde_json::json!({ "n": N, "points": rows }))?,
    });
    write_set(dir, &files, true)
}

fn spread(t: &report::Table, mu: f64, r: f64) -> (f64, f64) {
    let n = t.n;
    let ax = |x: f64| {
        let p = (x * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let i0 = p.floor() as usize;
        (i0, (i0 + 1).min(n - 1))
    };
    let (x0, x1) = ax(mu);
    let (y0, y1) = ax(r);
    let f = |v: &[f64]| {
        let s = [
            v[y0 * n + x0],
            v[y0 * n + x1],
            v[y1 * n + x0],
            v[y1 * n + x1],
        ];
        let mx = s.iter().cloned().fold(f64::MIN, f64::max);
        let mn = s.iter().cloned().fold(f64::MAX, f64::min);
        mx - mn
    };
    (f(&t.a), f(&t.b))
}

//! The converged GGX split-sum table (`brdf_core::split_sum::converged`) at the texel centres
//! of a size × size table (μ = (i + ½)/size, r = (j + ½)/size, the Khronos axes), timed, with
//! its work counts, next to today's fixed rule `split_sum::dfg_ggx` on a sample of texels.
//!
//! ```text
//! cargo run --release -p brdf-bench --example dfg_converged -- \
//!     [--size 1024] [--tol 1e-6] [--threads 1] [--stride 1] [--fixed 2000] [--out FILE]
//! ```
//!
//! `--stride s` computes every s-th roughness row only (timing on a sample of rows);
//! `--threads t` splits the rows over t threads (interleaved, so each gets a similar mix);
//! `--fixed k` times `dfg_ggx::<f64, OuterRule, InnerRule>` on k texels spread over the grid;
//! `--out FILE` writes the computed rows as raw little-endian f64 [row][i][A, B] (for
//! `peer/dfg_mc_peer.py --stride s --reference FILE`).

use brdf_core::split_sum::converged::DfgGgxRow;
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use std::time::Instant;

brdf_bench::example_options! {
    struct Args {
        size: usize = 1024, "--size";
        tol: f64 = 1e-6, "--tol";
        threads: usize = 1, "--threads";
        stride: usize = 1, "--stride";
        fixed: usize = 2000, "--fixed";
        out: Option<String> = None, "--out";
    }
}

/// Per-thread result: (row j, [A, B] per μ), evaluations, max evaluations, max estimate.
type Part = (Vec<(usize, Vec<[f64; 2]>)>, u64, u32, f64);

fn rows(size: usize, tol: f64, js: Vec<usize>) -> Part {
    let c = |k: usize| (k as f64 + 0.5) / size as f64;
    let (mut evals, mut max_evals, mut max_err) = (0u64, 0u32, 0f64);
    let mut out = Vec::with_capacity(js.len());
    for j in js {
        let row = DfgGgxRow::new(c(j));
        let vals = (0..size)
            .map(|i| {
                let t = row.texel(c(i), tol);
                evals += t.evals as u64;
                max_evals = max_evals.max(t.evals);
                max_err = max_err.max(t.error[0]).max(t.error[1]);
                t.value
            })
            .collect();
        out.push((j, vals));
    }
    (out, evals, max_evals, max_err)
}

fn main() {
    let a = Args::from_args();
    let js: Vec<usize> = (0..a.size).step_by(a.stride).collect();
    let texels = js.len() * a.size;
    let t0 = Instant::now();
    let parts: Vec<Part> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..a.threads)
            .map(|t| {
                let mine: Vec<usize> = js.iter().copied().skip(t).step_by(a.threads).collect();
                s.spawn(move || rows(a.size, a.tol, mine))
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let dt = t0.elapsed().as_secs_f64();
    let evals: u64 = parts.iter().map(|p| p.1).sum();
    let max_evals = parts.iter().map(|p| p.2).max().unwrap_or(0);
    let max_err = parts.iter().map(|p| p.3).fold(0f64, f64::max);
    println!(
        "converged: size {} rows {} texels {texels} threads {} tol {:e}: {dt:.3} s, {:.2} us/texel \
         (whole table at this rate: {:.2} s), evals/texel mean {:.1} max {max_evals}, max estimate {max_err:.2e}",
        a.size,
        js.len(),
        a.threads,
        a.tol,
        dt / texels as f64 * 1e6,
        dt / texels as f64 * (a.size * a.size) as f64,
        evals as f64 / texels as f64,
    );
    if a.fixed > 0 {
        let c = |k: usize| (k as f64 + 0.5) / a.size as f64;
        let n = a.fixed;
        let t0 = Instant::now();
        let mut acc = 0.0;
        for k in 0..n {
            let (i, j) = ((k * 7919) % a.size, (k * 104_729 / 3) % a.size);
            let (x, y) = dfg_ggx::<f64, OuterRule, InnerRule>(c(i), c(j));
            acc += x + y;
        }
        let dt = t0.elapsed().as_secs_f64();
        println!(
            "fixed rule dfg_ggx (32 x 16, 3 pieces x 4 panels): {n} texels, {:.2} us/texel (checksum {acc:.6})",
            dt / n as f64 * 1e6
        );
    }
    if let Some(path) = a.out {
        let mut table = vec![[0f64; 2]; js.len() * a.size];
        for (j, vals) in parts.into_iter().flat_map(|p| p.0) {
            let k = j / a.stride;
            table[k * a.size..(k + 1) * a.size].copy_from_slice(&vals);
        }
        let bytes: Vec<u8> = table
            .iter()
            .flat_map(|v| v.iter().flat_map(|x| x.to_le_bytes()))
            .collect();
        std::fs::write(&path, bytes).expect("write --out");
        println!("wrote {path}");
    }
}

#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN counts as over tol: `!(e <= tol)`.
//! The polar split-sum integrator (`brdf_core::split_sum::polar`) timed and counted on
//! texel centres, next to the converged visible-cap integrator (`split_sum::converged`) on
//! the same texels.
//!
//! ```text
//! cargo run --release -p brdf-bench --example polar_probe -- \
//!     [--tol 2e-6] [--grid 64] [--size 1024] [--samples 4096] [--converged 512] [--seed 22]
//! cargo run --release -p brdf-bench --example polar_probe -- --rows 64 \
//!     [--tol 2e-6] [--size 1024] [--converged 64] [--ref-tol 1e-9] [--full 1] [--seed 22]
//! ```
//!
//! With `--rows K` the row API (`split_sum::rows`, `DfgGgxPolarRow::texels`) instead: K
//! rows of the size × size Khronos table (the first two, the last, and K − 3 drawn by the
//! linear congruential sequence), each whole row timed (CPU time), with evaluations per
//! texel (mean over all, and the largest row mean), nodes and pieces per row, the largest
//! estimate and texels over `tol`; then `--converged` texels drawn from those rows against
//! the converged integrator at `--ref-tol` (largest |row − converged| per channel and
//! whether each difference is within the sum of both estimates); the projected time of the
//! whole table on 2 cores; and with `--full 1` the whole table computed on 2 threads
//! (std::thread::scope, rows interleaved), timed by wall clock and process CPU time (on a
//! loaded machine the wall clock exceeds CPU time / 2).
//!
//! Sets: (1) every texel centre of a grid × grid table (μ = (i + ½)/grid, r = (j + ½)/grid);
//! (2) the edges of the size × size Khronos axes (α = r²): the first two and the last
//! column and row, every texel; (3) `--samples` random texels of those axes (a fixed linear
//! congruential sequence). For each set: µs per texel (one thread, wall clock around the
//! loop, and CPU time of the process from /proc/self/stat, which a loaded machine
//! inflates less), evaluations per texel (mean, max), rows, the largest estimate and how many
//! texels miss `tol`. Then the converged integrator at the same `tol` on the first
//! `--converged` texels of set (3): its µs per texel and the largest |polar − converged|
//! per channel, next to the sum of the two estimates there.

use brdf_core::split_sum::converged::DfgGgxRow;
use brdf_core::split_sum::polar::{DfgGgxPolarRow, Polar};
use brdf_core::split_sum::rows::RowWork;
use std::time::Instant;

brdf_bench::example_options! {
    struct Args {
        tol: f64 = 2e-6, "--tol";
        grid: usize = 64, "--grid";
        size: usize = 1024, "--size";
        samples: usize = 4096, "--samples";
        converged: usize = 512, "--converged";
        seed: u64 = 22, "--seed";
        rows: usize = 0, "--rows";
        ref_tol: f64 = 1e-9, "--ref-tol";
        full: bool = false, "--full";
    }
}

/// Texel indices (i, j).
type Texels = Vec<(usize, usize)>;

/// Texel indices (i: μ column, j: r row): `n` drawn by a fixed linear congruential
/// sequence, and the edges (the first two and the last column and row, every texel).
fn khronos_sample(size: usize, n: usize, seed: u64) -> (Texels, Texels) {
    let mut edges = Vec::new();
    for e in [0, 1, size - 1] {
        for k in 0..size {
            edges.push((e, k));
            if ![0, 1, size - 1].contains(&k) {
                edges.push((k, e));
            }
        }
    }
    let mut s = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 33) % size as u64) as usize
    };
    let random = (0..n).map(|_| (next(), next())).collect();
    (random, edges)
}

/// This process's CPU time (user + system) in seconds, from /proc/self/stat (clock ticks
/// of 1/100 s, the Linux USER_HZ); None where that file is absent.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: u64 = f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 / 100.0)
}

/// Runs the polar rule on (μ, r) points; prints the statistics; returns the results.
fn polar_set(name: &str, pts: &[(f64, f64)], tol: f64) -> Vec<Polar<f64>> {
    let (t0, c0) = (Instant::now(), cpu_seconds());
    let res: Vec<Polar<f64>> = pts
        .iter()
        .map(|&(mu, r)| DfgGgxPolarRow::new(r).texel(mu, tol))
        .collect();
    let dt = t0.elapsed().as_secs_f64();
    let cpu = cpu_seconds().zip(c0).map_or(f64::NAN, |(a, b)| a - b);
    let n = pts.len() as f64;
    let evals: u64 = res.iter().map(|p| p.evals as u64).sum();
    let max_evals = res.iter().map(|p| p.evals).max().unwrap_or(0);
    let rows: u64 = res.iter().map(|p| p.rows as u64).sum();
    let max_rows = res.iter().map(|p| p.rows).max().unwrap_or(0);
    let max_est = res
        .iter()
        .map(|p| p.error[0].max(p.error[1]))
        .fold(0f64, f64::max);
    let missed = res
        .iter()
        .filter(|p| {
            p.error[0].max(p.error[1]).partial_cmp(&tol) != Some(std::cmp::Ordering::Less)
                && p.error[0].max(p.error[1]) != tol
        })
        .count();
    println!(
        "{name}: {} texels, tol {tol:e}: {:.2} us/texel wall, {:.2} us/texel CPU, evals/texel mean {:.0} max {max_evals}, \
         rows mean {:.1} max {max_rows}, max estimate {max_est:.2e}, texels over tol {missed}",
        pts.len(),
        dt / n * 1e6,
        cpu / n * 1e6,
        evals as f64 / n,
        rows as f64 / n,
    );
    res
}

fn main() {
    let a = Args::from_args();
    if a.rows > 0 {
        return rows_mode(&a);
    }
    let g = a.grid;
    let grid: Vec<(f64, f64)> = (0..g * g)
        .map(|k| {
            let (i, j) = (k % g, k / g);
            ((i as f64 + 0.5) / g as f64, (j as f64 + 0.5) / g as f64)
        })
        .collect();
    polar_set(&format!("grid {g}x{g}"), &grid, a.tol);

    let c = |k: usize| (k as f64 + 0.5) / a.size as f64;
    let (random, edges) = khronos_sample(a.size, a.samples, a.seed);
    let to_pts = |v: &[(usize, usize)]| -> Vec<(f64, f64)> {
        v.iter().map(|&(i, j)| (c(i), c(j))).collect()
    };
    let edge_pts = to_pts(&edges);
    polar_set(
        &format!(
            "Khronos {0}x{0} edges (first two, last column and row)",
            a.size
        ),
        &edge_pts,
        a.tol,
    );
    let pts = to_pts(&random);
    let polar = polar_set(
        &format!("Khronos {0}x{0} random sample", a.size),
        &pts,
        a.tol,
    );

    let m = a.converged.min(pts.len());
    if m == 0 {
        return;
    }
    let (t0, c0) = (Instant::now(), cpu_seconds());
    let conv: Vec<_> = pts[..m]
        .iter()
        .map(|&(mu, r)| DfgGgxRow::new(r).texel(mu, a.tol))
        .collect();
    let dt = t0.elapsed().as_secs_f64();
    let cpu = cpu_seconds().zip(c0).map_or(f64::NAN, |(a, b)| a - b);
    let (mut diff, mut worst_ratio, mut over) = ([0f64; 2], 0f64, 0usize);
    for (p, q) in polar[..m].iter().zip(&conv) {
        for (ch, dc) in diff.iter_mut().enumerate() {
            let d = (p.value[ch] - q.value[ch]).abs();
            *dc = dc.max(d);
            let both = p.error[ch] + q.error[ch];
            worst_ratio = worst_ratio.max(d / both);
            over += usize::from(d > both);
        }
    }
    let evals: u64 = conv
        .iter()
        .map(|q| q.evals as u64 + q.cut_evals as u64)
        .sum();
    println!(
        "converged (visible cap) on the first {m} sample texels, tol {:e}: {:.2} us/texel wall, {:.2} us/texel CPU, \
         evals+cut evals/texel mean {:.0}; max |polar - converged| A {:.2e} B {:.2e}; \
         max difference / (sum of both estimates) {worst_ratio:.2e}, channels over it {over}",
        a.tol,
        dt / m as f64 * 1e6,
        cpu / m as f64 * 1e6,
        evals as f64 / m as f64,
        diff[0],
        diff[1],
    );
}

/// A fixed linear congruential sequence of indices below `n`.
fn lcg(seed: u64, n: usize) -> impl FnMut() -> usize {
    let mut s = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 33) % n as u64) as usize
    }
}

/// One row of the Khronos table (r = (j + ½)/size) by the row API.
fn khronos_row(j: usize, mus: &[f64], tol: f64, out: &mut [Polar<f64>]) -> RowWork {
    let r = (j as f64 + 0.5) / mus.len() as f64;
    DfgGgxPolarRow::new(r)
        .texels(mus, tol, out)
        .expect("row lengths and tol are valid")
}

/// The `--rows` mode (module docs).
fn rows_mode(a: &Args) {
    let n = a.size;
    let mus: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
    let mut next = lcg(a.seed, n);
    let mut js = vec![0, 1, n - 1];
    js.extend((3..a.rows).map(|_| next()));
    js.truncate(a.rows);
    let mut out = vec![vec![Polar::default(); n]; js.len()];
    let (t0, c0) = (Instant::now(), cpu_seconds());
    let work: Vec<RowWork> = js
        .iter()
        .zip(out.iter_mut())
        .map(|(&j, o)| khronos_row(j, &mus, a.tol, o))
        .collect();
    let dt = t0.elapsed().as_secs_f64();
    let cpu = cpu_seconds().zip(c0).map_or(f64::NAN, |(x, y)| x - y);
    if std::env::var_os("POLAR_PROBE_ROWS").is_some() {
        for (j, w) in js.iter().zip(&work) {
            println!(
                "  row j {j}: {w:?}, evals/node {:.0}",
                w.evals as f64 / w.nodes.max(1) as f64
            );
        }
    }
    let texels = (js.len() * n) as f64;
    let evals: u64 = work.iter().map(|w| w.evals).sum();
    let max_row = work
        .iter()
        .map(|w| w.evals as f64 / n as f64)
        .fold(0.0, f64::max);
    let nodes: u64 = work.iter().map(|w| w.nodes as u64).sum();
    let max_nodes = work.iter().map(|w| w.nodes).max().unwrap_or(0);
    let pieces: u64 = work.iter().map(|w| w.pieces as u64).sum();
    let direct: u64 = work.iter().map(|w| w.direct as u64).sum();
    let flat = out.iter().flatten();
    let max_est = flat
        .clone()
        .map(|p| p.error[0].max(p.error[1]))
        .fold(0f64, f64::max);
    let over = flat
        .filter(|p| !(p.error[0].max(p.error[1]) <= a.tol))
        .count();
    let us = cpu / texels * 1e6;
    println!(
        "rows: {} rows x {n} texels, tol {:e}: {:.2} us/texel wall, {us:.2} us/texel CPU, \
         evals/texel mean {:.1} (largest row mean {max_row:.1}), nodes/row mean {:.1} max {max_nodes}, \
         pieces/row {:.2}, direct texels {direct}, max estimate {max_est:.2e}, texels over tol {over}; \
         projected {n}x{n} on 2 cores {:.2} s",
        js.len(),
        a.tol,
        dt / texels * 1e6,
        evals as f64 / texels,
        nodes as f64 / js.len() as f64,
        pieces as f64 / js.len() as f64,
        us * 1e-6 * (n * n) as f64 / 2.0,
    );
    compare_converged(a, &js, &mus, &out);
    if a.full {
        full_table(a, &mus);
    }
}

/// `--converged` texels drawn from the computed rows against the converged integrator at
/// `--ref-tol`, and the same texels against the polar rule per texel at 1e-10.
fn compare_converged(a: &Args, js: &[usize], mus: &[f64], out: &[Vec<Polar<f64>>]) {
    let mut next = lcg(a.seed ^ 0x5eed, js.len() * mus.len());
    let picks: Vec<(usize, usize)> = (0..a.converged)
        .map(|_| {
            let k = next();
            (k / mus.len(), k % mus.len())
        })
        .collect();
    let t0 = Instant::now();
    let conv: Vec<[[f64; 2]; 2]> = picks
        .iter()
        .map(|&(row, i)| {
            let r = (js[row] as f64 + 0.5) / mus.len() as f64;
            let q = DfgGgxRow::new(r).texel(mus[i], a.ref_tol);
            [q.value, q.error]
        })
        .collect();
    let dt = t0.elapsed().as_secs_f64();
    let polar: Vec<[[f64; 2]; 2]> = picks
        .iter()
        .map(|&(row, i)| {
            let r = (js[row] as f64 + 0.5) / mus.len() as f64;
            let q = DfgGgxPolarRow::new(r).texel(mus[i], 1e-10);
            [q.value, q.error]
        })
        .collect();
    let name = format!("converged (tol {:e}, {dt:.1} s)", a.ref_tol);
    report_against(&name, js, mus, out, &picks, &conv);
    report_against("polar per texel (tol 1e-10)", js, mus, out, &picks, &polar);
}

/// max |row − reference| per channel over the picked texels, and the largest difference
/// relative to the sum of both estimates.
fn report_against(
    name: &str,
    js: &[usize],
    mus: &[f64],
    out: &[Vec<Polar<f64>>],
    picks: &[(usize, usize)],
    refs: &[[[f64; 2]; 2]],
) {
    let (mut diff, mut worst_ratio, mut over) = ([0f64; 2], 0f64, 0usize);
    let mut worst_at = (0.0, 0.0, 0, 0.0, 0.0, 0.0);
    for (&(row, i), q) in picks.iter().zip(refs) {
        let p = &out[row][i];
        let r = (js[row] as f64 + 0.5) / mus.len() as f64;
        for (ch, dc) in diff.iter_mut().enumerate() {
            let d = (p.value[ch] - q[0][ch]).abs();
            *dc = dc.max(d);
            let both = p.error[ch] + q[1][ch];
            if d / both > worst_ratio {
                worst_ratio = d / both;
                worst_at = (mus[i], r, ch, d, p.error[ch], q[1][ch]);
            }
            over += usize::from(d > both);
        }
    }
    let (wm, wr, wch, wd, we, wq) = worst_at;
    println!(
        "row vs {name} on {} texels of those rows: max |row - reference| A {:.2e} B {:.2e}; \
         max difference / (sum of both estimates) {worst_ratio:.2e} (mu {wm} r {wr} channel {wch}: \
         |difference| {wd:.2e}, row estimate {we:.2e}, reference's {wq:.2e}), channels over it {over}",
        picks.len(),
        diff[0],
        diff[1],
    );
}

/// The whole size × size table on 2 threads (rows interleaved), wall clock.
fn full_table(a: &Args, mus: &[f64]) {
    let n = mus.len();
    let (t0, c0) = (Instant::now(), cpu_seconds());
    let results: Vec<(u64, f64, usize)> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..2)
            .map(|t| {
                s.spawn(move || {
                    let mut out = vec![Polar::default(); n];
                    let (mut evals, mut max_est, mut over) = (0u64, 0f64, 0usize);
                    for j in (t..n).step_by(2) {
                        evals += khronos_row(j, mus, a.tol, &mut out).evals;
                        for p in &out {
                            let e = p.error[0].max(p.error[1]);
                            max_est = max_est.max(e);
                            over += usize::from(!(e <= a.tol));
                        }
                    }
                    (evals, max_est, over)
                })
            })
            .collect();
        hs.into_iter()
            .map(|h| h.join().expect("row thread"))
            .collect()
    });
    let dt = t0.elapsed().as_secs_f64();
    let cpu = cpu_seconds().zip(c0).map_or(f64::NAN, |(x, y)| x - y);
    let evals: u64 = results.iter().map(|r| r.0).sum();
    let max_est = results.iter().map(|r| r.1).fold(0f64, f64::max);
    let over: usize = results.iter().map(|r| r.2).sum();
    println!(
        "full {n}x{n} table on 2 threads: {dt:.2} s wall, {cpu:.2} s CPU (both threads), evals/texel mean {:.1}, max estimate {max_est:.2e}, texels over tol {over}",
        evals as f64 / (n * n) as f64,
    );
}

//! Generation and verification of the tables.

use super::assets::{self, Spec};
use super::GenArgs;
use anyhow::{bail, Context, Result};
use brdf_core::masking::ModifiedG;
use brdf_lut::write::{self, ErrorAccumulator};
use brdf_lut::{
    Convention, Encoding, ErrorStats, GTable, GTable3, Generator, List, LutView, TableKind,
};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::io::IsTerminal;
use std::time::Instant;

/// The generator's name in the headers (no version number: regenerating must not change
/// bytes when only the crate version changes).
pub const TOOL: &str = "brdf-kernels xtask lut";
/// Seed of the generator's error measurement.
pub const SEED: u64 = 0x5EED_0001;

pub struct Row {
    pub file: String,
    pub bytes: usize,
    pub stats: ErrorStats,
    pub secs: Option<f64>,
}

fn progress(len: u64, msg: String) -> ProgressBar {
    let pb = ProgressBar::new(len);
    let hide = !std::io::stderr().is_terminal()
        || std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
    if hide {
        pb.set_draw_target(ProgressDrawTarget::hidden());
    }
    pb.set_style(
        ProgressStyle::with_template("{msg:28} [{bar:30}] {pos}/{len} {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_message(msg);
    pb
}

fn apply_overrides(specs: &mut [Spec], g: &GenArgs) -> Result<()> {
    for s in specs.iter_mut() {
        if let Some(res) = &g.res {
            let n: Vec<u32> = res
                .split('x')
                .map(|t| t.trim().parse::<u32>())
                .collect::<Result<_, _>>()
                .with_context(|| format!("--res `{res}` is not like 64x64"))?;
            if n.len() != s.axes.len() {
                bail!(
                    "--res `{res}` has {} numbers, {} has {} axes",
                    n.len(),
                    s.file,
                    s.axes.len()
                );
            }
            for (a, &c) in s.axes.iter_mut().zip(&n) {
                a.count = c;
            }
        }
        if let Some(e) = &g.encoding {
            s.encoding = match e.as_str() {
                "u16" => Encoding::Unorm16,
                "f16" => Encoding::F16,
                "f32" => Encoding::F32,
                o => bail!("unknown encoding `{o}` (u16, f16 or f32)"),
            };
        }
    }
    Ok(())
}

/// `cargo xtask lut [generate]`.
pub fn generate(g: GenArgs) -> Result<()> {
    let mut specs = assets::default_set();
    if let Some(only) = &g.only {
        specs.retain(|s| s.file.contains(only.as_str()));
        if specs.is_empty() {
            bail!("--only `{only}` matches no asset");
        }
    }
    apply_overrides(&mut specs, &g)?;
    let out = if g.check {
        let d = std::env::temp_dir().join(format!("brdf-lut-check-{}", std::process::id()));
        std::fs::create_dir_all(&d)?;
        d
    } else {
        g.out.clone().unwrap_or_else(super::assets_dir)
    };
    std::fs::create_dir_all(&out)?;
    let t0 = Instant::now();
    let mut rows = Vec::new();
    for s in &specs {
        let t = Instant::now();
        let bytes = build(s)?;
        let view = LutView::parse(&bytes).context("generated file does not parse")?;
        rows.push(Row {
            file: s.file.clone(),
            bytes: bytes.len(),
            stats: view.header().error,
            secs: Some(t.elapsed().as_secs_f64()),
        });
        std::fs::write(out.join(&s.file), &bytes)?;
    }
    print_table(&rows);
    println!("total generation time {:.1} s", t0.elapsed().as_secs_f64());
    if g.check {
        let committed = g.out.clone().unwrap_or_else(super::assets_dir);
        let mut bad = Vec::new();
        for s in &specs {
            let a = std::fs::read(out.join(&s.file))?;
            match std::fs::read(committed.join(&s.file)) {
                Ok(b) if a == b => {}
                Ok(_) => bad.push(format!("{} differs", s.file)),
                Err(_) => bad.push(format!(
                    "{} is missing from {}",
                    s.file,
                    committed.display()
                )),
            }
        }
        let _ = std::fs::remove_dir_all(&out);
        if !bad.is_empty() {
            bail!(
                "committed assets do not match a fresh generation:\n  {}",
                bad.join("\n  ")
            );
        }
        println!(
            "check: {} assets byte-identical to {}",
            specs.len(),
            committed.display()
        );
    } else {
        println!("wrote {} files to {}", specs.len(), out.display());
    }
    Ok(())
}

/// Quadrature node counts the direct kernels use, recorded in the header.
fn quadrature_nodes(kind: TableKind) -> List<u16, { brdf_lut::MAX_GENERATOR_NODES }> {
    let counts: &[u16] = match kind {
        TableKind::PassingFactor => &[brdf_core::quadrature::DEFAULT_NODES as u16],
        TableKind::AverageAlbedo => &[24, 32, 16, 4],
        _ => &[32, 16, 4],
    };
    List::from_slice(counts).unwrap_or_default()
}

/// Computes the nodes and hands them to the library writer, which quantises them, measures
/// the error (with [`measure`]) and encodes the file.
pub fn build(s: &Spec) -> Result<Vec<u8>> {
    let spec = write::Spec {
        kind: s.kind,
        axes: &s.axes,
        channels: &s.channels,
        encoding: s.encoding,
        interpolation: s.interpolation,
        generator: Generator {
            model: s.model,
            convention: Convention::Reciprocal,
            sigma: s.sigma,
            nodes: quadrature_nodes(s.kind),
            tool: TOOL,
        },
    };
    let total = spec.nodes();
    let pb = progress(total as u64, s.file.clone());
    let values: Vec<f64> = (0..total)
        .into_par_iter()
        .flat_map_iter(|k| {
            let v = assets::node_value(s.kind, s.model, s.sigma, &write::node_coords(&s.axes, k));
            pb.inc(1);
            v
        })
        .collect();
    pb.finish_and_clear();
    write::build(&spec, &values, |view| measure(view, s.samples, SEED, true))
        .map_err(|e| anyhow::anyhow!("{}: {e}", s.file))
}

/// Max and RMS |table − direct kernel| at `n` random points (seeded), over all channels.
/// Passing-factor tables are measured on G = min(GM, GS) at random (θi, θr[, σ]).
pub fn measure(view: &LutView<'_>, n: u32, seed: u64, bar: bool) -> ErrorStats {
    let h = view.header();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let kind = h.kind;
    let dims = h.axes.len();
    // Uniform in [lo, hi]; a range rand cannot sample (empty, or a span that overflows) gives
    // its lower end instead of a panic. A parsed header's ranges are finite, increasing and
    // finite in f32, so this only guards the tool.
    let uniform = |rng: &mut rand_pcg::Pcg64, lo: f64, hi: f64| -> f64 {
        if lo < hi && (hi - lo).is_finite() {
            rng.random_range(lo..=hi)
        } else {
            lo
        }
    };
    let pts: Vec<Vec<f64>> = (0..n)
        .map(|_| {
            if kind == TableKind::PassingFactor {
                let mut p = vec![
                    uniform(&mut rng, 0.0, std::f64::consts::FRAC_PI_2),
                    uniform(
                        &mut rng,
                        -std::f64::consts::FRAC_PI_2,
                        std::f64::consts::FRAC_PI_2,
                    ),
                ];
                if dims == 3 {
                    p.push(uniform(&mut rng, h.axes[2].lo, h.axes[2].hi));
                }
                p
            } else {
                h.axes
                    .iter()
                    .map(|a| {
                        let (lo, hi) = assets::verify_range(kind, a);
                        uniform(&mut rng, lo, hi)
                    })
                    .collect()
            }
        })
        .collect();
    let pb = progress(if bar { n as u64 } else { 0 }, "  verifying".into());
    if !bar {
        pb.set_draw_target(ProgressDrawTarget::hidden());
    }
    let g2 = if kind == TableKind::PassingFactor && dims == 2 {
        GTable::from_view(*view).ok()
    } else {
        None
    };
    let g3 = if kind == TableKind::PassingFactor && dims == 3 {
        GTable3::from_view(*view).ok()
    } else {
        None
    };
    let errs: Vec<Vec<f64>> = pts
        .par_iter()
        .map(|p| {
            let e = if kind == TableKind::PassingFactor {
                let s = h
                    .generator
                    .sigma
                    .unwrap_or_else(|| p.get(2).copied().unwrap_or(0.3));
                let direct = ModifiedG::<f64>::new(s)
                    .map(|g| g.g(p[0], p[1]))
                    .unwrap_or(f64::NAN);
                let t = match (&g2, &g3) {
                    (Some(t), _) => t.g(p[0] as f32, p[1] as f32) as f64,
                    (_, Some(t)) => t.g(p[0] as f32, p[1] as f32, s as f32) as f64,
                    _ => f64::NAN,
                };
                vec![(t - direct).abs()]
            } else {
                let x: Vec<f32> = p.iter().map(|&v| v as f32).collect();
                // Evaluate the direct kernel at the f32-rounded point the table sees.
                let xd: Vec<f64> = x.iter().map(|&v| v as f64).collect();
                let d = assets::node_value(kind, h.generator.model, h.generator.sigma, &xd);
                let t = view.sample(&x);
                d.iter()
                    .zip(t.iter())
                    .map(|(a, &b)| (b as f64 - a).abs())
                    .collect()
            };
            pb.inc(1);
            e
        })
        .collect();
    pb.finish_and_clear();
    let mut acc = ErrorAccumulator::default();
    for &x in errs.iter().flatten() {
        acc.add(x);
    }
    acc.finish(n, seed)
}

pub fn print_table(rows: &[Row]) {
    println!(
        "{:<28} {:>9} {:>11} {:>11} {:>8} {:>8}",
        "table", "bytes", "max |err|", "RMS err", "points", "time s"
    );
    for r in rows {
        println!(
            "{:<28} {:>9} {:>11.3e} {:>11.3e} {:>8} {:>8}",
            r.file,
            r.bytes,
            r.stats.max_abs,
            r.stats.rms,
            r.stats.samples,
            r.secs.map_or("-".to_string(), |s| format!("{s:.1}"))
        );
    }
}

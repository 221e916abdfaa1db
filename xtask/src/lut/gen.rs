//! Generation and verification of the tables.

use super::assets::{self, Spec};
use super::GenArgs;
use anyhow::{bail, Context, Result};
use brdf_core::lut::{
    encode_into, f32_to_f16, Channel, Encoding, ErrorStats, GTable, GTable3, Generator, Header,
    LutView, TableKind, FORMAT_VERSION, MAGIC,
};
use brdf_core::masking::{Convention, ModifiedG};
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
    let check_dir = if g.check {
        Some(tempfile::tempdir().context("creating a temporary folder")?)
    } else {
        None
    };
    let (out, policy) = write_target(&g, check_dir.as_ref().map(|d| d.path()))?;
    let paths: Vec<std::path::PathBuf> = specs.iter().map(|s| out.join(&s.file)).collect();
    crate::fsio::check(
        &paths.iter().map(|p| p.as_path()).collect::<Vec<_>>(),
        &policy,
    )?;
    let mut files = Vec::new();
    let t0 = Instant::now();
    let mut rows = Vec::new();
    for s in &specs {
        let t = Instant::now();
        let bytes = build(s)?;
        let stats = LutView::parse(&bytes)
            .context("generated file does not parse")?
            .header()
            .error;
        rows.push(Row {
            file: s.file.clone(),
            bytes: bytes.len(),
            stats,
            secs: Some(t.elapsed().as_secs_f64()),
        });
        files.push((out.join(&s.file), bytes));
    }
    crate::fsio::write_together(&files, &policy)?;
    print_table(&rows);
    println!("total generation time {:.1} s", t0.elapsed().as_secs_f64());
    if g.check {
        let committed = g.out.clone().unwrap_or_else(super::assets_dir);
        let mut bad = Vec::new();
        for s in &specs {
            let a = &files
                .iter()
                .find(|f| f.0 == out.join(&s.file))
                .expect("written")
                .1;
            match std::fs::read(committed.join(&s.file)) {
                Ok(b) if *a == b => {}
                Ok(_) => bad.push(format!("{} differs", s.file)),
                Err(_) => bad.push(format!(
                    "{} is missing from {}",
                    s.file,
                    committed.display()
                )),
            }
        }
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

/// Where the tables go and what may be replaced there: the unmodified default set replaces
/// the files in assets/ (its home, under version control); anything else (`--res`,
/// `--encoding`) needs `--out` outside assets/, and replaces existing files only with
/// `--force`.
fn write_target(
    g: &GenArgs,
    check_dir: Option<&std::path::Path>,
) -> Result<(std::path::PathBuf, crate::fsio::Policy)> {
    use crate::fsio::Policy;
    if let Some(d) = check_dir {
        return Ok((d.to_path_buf(), Policy::default()));
    }
    let modified = g.res.is_some() || g.encoding.is_some();
    let assets = super::assets_dir();
    let out = match (&g.out, modified) {
        (Some(o), _) => o.clone(),
        (None, false) => assets.clone(),
        (None, true) => bail!(
            "--res and --encoding change the tables, and assets/ holds the committed default \
             set: give --out DIR for the modified tables"
        ),
    };
    let in_assets = match (out.canonicalize(), assets.canonicalize()) {
        (Ok(o), Ok(a)) => o == a,
        _ => false,
    };
    if in_assets && !modified {
        // Regenerating the default set in its own folder: replace it.
        return Ok((
            out,
            Policy {
                force: true,
                ..Policy::default()
            },
        ));
    }
    Ok((out, Policy::new(g.force, &[])))
}

fn header_for<'a>(s: &'a Spec, channels: &[Channel<'a>], error: ErrorStats) -> Result<Header<'a>> {
    let mut nodes = heapless::Vec::new();
    let counts: &[u16] = match s.kind {
        TableKind::PassingFactor => &[brdf_core::quadrature::DEFAULT_NODES as u16],
        TableKind::AverageAlbedo => &[24, 32, 16, 4],
        _ => &[32, 16, 4],
    };
    for &c in counts {
        let _ = nodes.push(c);
    }
    Ok(Header {
        magic: MAGIC,
        version: FORMAT_VERSION,
        kind: s.kind,
        axes: s.axes.iter().copied().collect(),
        channels: channels.iter().copied().collect(),
        encoding: s.encoding,
        interpolation: s.interpolation,
        generator: Generator {
            model: s.model,
            convention: Convention::Reciprocal,
            sigma: s.sigma,
            nodes,
            tool: TOOL,
        },
        error,
        checksum: [0; 4],
    })
}

fn encode(h: &Header<'_>, payload: &[u8]) -> Result<Vec<u8>> {
    let mut buf = vec![0u8; payload.len() + 4096];
    let n = encode_into(h, payload, &mut buf).map_err(|e| anyhow::anyhow!("{e}"))?;
    buf.truncate(n);
    Ok(buf)
}

/// Computes the nodes, quantises, measures the error and encodes one table.
pub fn build(s: &Spec) -> Result<Vec<u8>> {
    let dims: Vec<u32> = s.axes.iter().map(|a| a.count).collect();
    let total: usize = dims.iter().map(|&n| n as usize).product();
    let coords = |flat: usize| -> Vec<f64> {
        let mut r = flat;
        s.axes
            .iter()
            .map(|a| {
                let i = (r % a.count as usize) as u32;
                r /= a.count as usize;
                a.node(i)
            })
            .collect()
    };
    let pb = progress(total as u64, s.file.clone());
    let values: Vec<Vec<f64>> = (0..total)
        .into_par_iter()
        .map(|k| {
            let v = assets::node_value(s.kind, s.model, s.sigma, &coords(k));
            pb.inc(1);
            v
        })
        .collect();
    pb.finish_and_clear();
    let nc = s.channels.len();
    // Per-channel scale and offset (u16: [min, max] → [0, 65535]; floats: identity).
    let mut chans = Vec::new();
    for (c, &name) in s.channels.iter().enumerate() {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in &values {
            if !v[c].is_finite() {
                bail!("{}: non-finite value at a node", s.file);
            }
            lo = lo.min(v[c]);
            hi = hi.max(v[c]);
        }
        let (scale, offset) = match s.encoding {
            Encoding::Unorm16 => {
                let span = (hi - lo) as f32;
                (if span > 0.0 { span } else { 1.0 }, lo as f32)
            }
            _ => (1.0f32, 0.0f32),
        };
        chans.push(Channel {
            name,
            scale,
            offset,
        });
    }
    let mut payload = Vec::with_capacity(total * nc * s.encoding.bytes());
    for v in &values {
        for (c, ch) in chans.iter().enumerate() {
            match s.encoding {
                Encoding::Unorm16 => {
                    let q = ((v[c] - ch.offset as f64) / ch.scale as f64 * 65535.0)
                        .round()
                        .clamp(0.0, 65535.0) as u16;
                    payload.extend_from_slice(&q.to_le_bytes());
                }
                Encoding::F16 => payload.extend_from_slice(&f32_to_f16(v[c] as f32).to_le_bytes()),
                Encoding::F32 => payload.extend_from_slice(&(v[c] as f32).to_le_bytes()),
            }
        }
    }
    let zero = ErrorStats {
        max_abs: 0.0,
        rms: 0.0,
        samples: 0,
        seed: 0,
    };
    let first = encode(&header_for(s, &chans, zero)?, &payload)?;
    let stats = {
        let view = LutView::parse(&first).map_err(|e| anyhow::anyhow!("{e}"))?;
        measure(&view, s.samples, SEED, true)
    };
    encode(&header_for(s, &chans, stats)?, &payload)
}

/// Max and RMS |table − direct kernel| at `n` random points (seeded), over all channels.
/// Passing-factor tables are measured on G = min(GM, GS) at random (θi, θr[, σ]).
pub fn measure(view: &LutView<'_>, n: u32, seed: u64, bar: bool) -> ErrorStats {
    let h = view.header();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let kind = h.kind;
    let dims = h.axes.len();
    let pts: Vec<Vec<f64>> = (0..n)
        .map(|_| {
            if kind == TableKind::PassingFactor {
                let mut p = vec![
                    rng.random_range(0.0..=std::f64::consts::FRAC_PI_2),
                    rng.random_range(-std::f64::consts::FRAC_PI_2..=std::f64::consts::FRAC_PI_2),
                ];
                if dims == 3 {
                    p.push(rng.random_range(h.axes[2].lo..=h.axes[2].hi));
                }
                p
            } else {
                h.axes
                    .iter()
                    .map(|a| {
                        let (lo, hi) = assets::verify_range(kind, a);
                        rng.random_range(lo..=hi)
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
        GTable::from_view(view.clone()).ok()
    } else {
        None
    };
    let g3 = if kind == TableKind::PassingFactor && dims == 3 {
        GTable3::from_view(view.clone()).ok()
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
    let (mut max, mut sum, mut cnt) = (0f64, 0f64, 0u64);
    for e in &errs {
        for &x in e {
            let x = if x.is_nan() { f64::INFINITY } else { x };
            max = max.max(x);
            sum += x * x;
            cnt += 1;
        }
    }
    ErrorStats {
        max_abs: max as f32,
        rms: (sum / cnt.max(1) as f64).sqrt() as f32,
        samples: n,
        seed,
    }
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

//! `cargo xtask lut engine <target>`: the split-sum (A, B) table for GGX with height-correlated
//! Smith, α = r² (r = perceptual roughness), written in the container, channel layout,
//! orientation, texel placement and roughness convention that one engine's shader samples,
//! with a JSON sidecar and WGSL/GLSL sampling functions. `report` compares our files with the
//! engines' shipped tables and writes docs/engines.md.
//!
//! Every texel holds the integral at its own texel centre, computed there in f64
//! ([`brdf_core::split_sum::dfg_ggx`], 32-point outer × 16-point inner Gauss–Legendre), then
//! rounded to nearest in the target encoding.

mod encode;
mod report;
mod shaders;
pub mod web;

use anyhow::{bail, Context, Result};
use brdf_core::quadrature::GaussLegendre;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// Outer (ξ / θh) rule of the table integrals.
pub type Outer = GaussLegendre<32>;
/// Inner (φ) rule of the table integrals.
pub type Inner = GaussLegendre<16>;

/// The largest table edge accepted (a 4096² table is 16 Mi integrals: hours of CPU).
pub const MAX_SIZE: usize = 4096;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// glTF Sample Viewer `lut_ggx.png` (8-bit, plus 16-bit RGB and 16-bit per-channel PNGs).
    Khronos,
    /// Bevy `dfg.ktx2` (KTX2 R16G16_SFLOAT, Zstandard).
    Bevy,
    /// Filament `cmgen --ibl-dfg-multiscatter` DDS (R16G16B16A16_FLOAT, R = B, G = A + B).
    Filament,
    /// three.js DFG LUT: raw little-endian RG16F pairs (A, B), memory row = μ, and a JS module.
    Threejs,
    /// 32-bit float OpenEXR (R = A, G = B), μ along x, r down the rows.
    Exr,
    /// Every target above, each into its own sub-folder of --out.
    All,
    /// Compare our files (from `--out`, generated when missing) with the engines' shipped
    /// tables and write docs/engines.md.
    Report,
}

#[derive(clap::Args)]
pub struct Args {
    /// Engine target.
    #[arg(value_enum)]
    target: Target,
    /// Table edge N (N × N texels; default: the engine's own size: khronos 1024, bevy,
    /// filament and exr 64, threejs 16). The engines' shaders need no change for another N
    /// (all placements are texel centres), but a drop-in replacement keeps the engine's size.
    #[arg(long)]
    size: Option<usize>,
    /// Output folder (default: target/lut-engine/<target> in the workspace).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Replace existing output files.
    #[arg(long)]
    force: bool,
    /// `report` only: folder of the engines' shipped tables (default: each table from
    /// .cache/anchors, as fetched by `cargo xtask anchors`, else ../shared/anchors).
    #[arg(long)]
    anchors: Option<PathBuf>,
    /// `report` only: the Markdown file to write (default: docs/engines.md).
    #[arg(long)]
    doc: Option<PathBuf>,
}

impl Target {
    pub const ENGINES: [Target; 5] = [
        Target::Khronos,
        Target::Bevy,
        Target::Filament,
        Target::Threejs,
        Target::Exr,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Target::Khronos => "khronos",
            Target::Bevy => "bevy",
            Target::Filament => "filament",
            Target::Threejs => "threejs",
            Target::Exr => "exr",
            Target::All => "all",
            Target::Report => "report",
        }
    }
    /// The engine's own table edge.
    pub fn native_size(self) -> usize {
        match self {
            Target::Khronos => 1024,
            Target::Bevy | Target::Filament | Target::Exr => 64,
            Target::Threejs => 16,
            Target::All | Target::Report => 0,
        }
    }
}

/// Exact texel values: `a[row * n + col]`, `b[..]` with col = μ index, row = r index, both at
/// texel centres (i + ½)/n.
pub struct Grid {
    pub n: usize,
    pub a: Vec<f64>,
    pub b: Vec<f64>,
}

/// Texel centre i of an n-wide axis.
pub fn centre(i: usize, n: usize) -> f64 {
    (i as f64 + 0.5) / n as f64
}

/// The converged split sum (A, B) at (μ, r).
pub fn integral(mu: f64, r: f64) -> (f64, f64) {
    brdf_core::split_sum::dfg_ggx::<f64, Outer, Inner>(mu, r)
}

/// All n² texel-centre integrals, in parallel, with a progress bar for large tables.
pub fn compute_grid(n: usize, quiet: bool) -> Grid {
    let bar = if !quiet && n >= 128 {
        let b = ProgressBar::new((n * n) as u64);
        b.set_style(
            ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} texels, eta {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b.set_message(format!("{n}×{n} split-sum integrals"));
        Some(b)
    } else {
        None
    };
    let rows: Vec<(Vec<f64>, Vec<f64>)> = (0..n)
        .into_par_iter()
        .map(|row| {
            let r = centre(row, n);
            let (mut a, mut b) = (Vec::with_capacity(n), Vec::with_capacity(n));
            for col in 0..n {
                let (x, y) = integral(centre(col, n), r);
                a.push(x);
                b.push(y);
            }
            if let Some(bar) = &bar {
                bar.inc(n as u64);
            }
            (a, b)
        })
        .collect();
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let mut g = Grid {
        n,
        a: Vec::with_capacity(n * n),
        b: Vec::with_capacity(n * n),
    };
    for (a, b) in rows {
        g.a.extend(a);
        g.b.extend(b);
    }
    g
}

/// One output file of a target.
pub struct OutFile {
    pub name: String,
    pub bytes: Vec<u8>,
}

/// Writes `bytes` to `path` through a temporary file in the same folder, so a crash or a
/// full disk leaves any previous file intact and no partial file. Without `force` an
/// existing file is never replaced (the final step is a hard link, which fails if the
/// name exists, even when it appeared after the check).
fn write_atomic(path: &Path, bytes: &[u8], force: bool) -> Result<()> {
    use std::io::Write;
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .with_context(|| format!("{}: not a file name", path.display()))?;
    let tmp = dir.join(format!(
        ".{}.tmp{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let res = (|| -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        drop(f);
        if force {
            std::fs::rename(&tmp, path)
        } else {
            std::fs::hard_link(&tmp, path)?;
            std::fs::remove_file(&tmp)
        }
    })();
    if let Err(e) = res {
        let _ = std::fs::remove_file(&tmp);
        if e.kind() == std::io::ErrorKind::AlreadyExists {
            bail!("{} exists (use --force to replace it)", path.display());
        }
        bail!("writing {}: {e}", path.display());
    }
    Ok(())
}

/// Writes a whole set (data files, sidecar, shaders): refuses up front when any exists
/// without `force`; on a failure removes the files of this set written so far, so the set
/// succeeds or fails together.
pub fn write_set(dir: &Path, files: &[OutFile], force: bool) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    if !force {
        for f in files {
            let p = dir.join(&f.name);
            if p.exists() {
                bail!("{} exists (use --force to replace it)", p.display());
            }
        }
    }
    let mut done: Vec<PathBuf> = Vec::new();
    for f in files {
        let p = dir.join(&f.name);
        if let Err(e) = write_atomic(&p, &f.bytes, force) {
            if !force {
                for d in &done {
                    let _ = std::fs::remove_file(d);
                }
            }
            return Err(e);
        }
        done.push(p);
    }
    Ok(())
}

fn default_out(t: Target) -> PathBuf {
    crate::lut::workspace_root()
        .join("target/lut-engine")
        .join(t.name())
}

/// Generates one target into `dir`; returns (files, seconds for the integrals).
pub fn generate(t: Target, n: usize, dir: &Path, force: bool, quiet: bool) -> Result<f64> {
    if !(2..=MAX_SIZE).contains(&n) {
        bail!("--size {n}: the table edge must be between 2 and {MAX_SIZE}");
    }
    let t0 = std::time::Instant::now();
    let grid = compute_grid(n, quiet);
    let secs = t0.elapsed().as_secs_f64();
    let files = encode::files(t, &grid)?;
    write_set(dir, &files, force)?;
    if !quiet {
        println!(
            "{}: {n}×{n} in {secs:.1} s → {}",
            t.name(),
            files
                .iter()
                .map(|f| dir.join(&f.name).display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(secs)
}

pub fn run(a: Args) -> Result<()> {
    match a.target {
        Target::Report => report::run(
            a.out.unwrap_or_else(|| default_out(Target::All)),
            a.anchors,
            a.doc,
        ),
        Target::All => {
            if a.size.is_some() {
                bail!("--size applies to one target, not to `all` (each engine has its own size)");
            }
            let out = a.out.unwrap_or_else(|| default_out(Target::All));
            for t in Target::ENGINES {
                generate(t, t.native_size(), &out.join(t.name()), a.force, false)?;
            }
            Ok(())
        }
        t => {
            let n = a.size.unwrap_or(t.native_size());
            let out = a.out.unwrap_or_else(|| default_out(t));
            generate(t, n, &out, a.force, false).map(|_| ())
        }
    }
}

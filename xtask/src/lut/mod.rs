//! `cargo xtask lut`: LUT generation (default), verification, inspection and export.
//! Format, readers and writer: the `brdf-lut` crate (`docs/lut-format.md`).

mod export;
mod export_shaders;
mod gen;
mod generate;

use anyhow::{bail, Context, Result};
use clap::Subcommand;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct Args {
    #[command(subcommand)]
    cmd: Option<Cmd>,
    #[command(flatten)]
    gen: GenArgs,
}

#[derive(clap::Args, Clone, Default)]
pub struct GenArgs {
    /// Regenerate into a temporary directory and compare byte for byte with the committed
    /// assets (exit status 1 on any difference).
    #[arg(long)]
    check: bool,
    /// Output directory of the default set (default: `assets/` of the workspace); with
    /// `--kind`/`--config`, the output file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Only the assets whose file name contains this text (e.g. `g_modified`, `dfg`, `kc_`).
    #[arg(long)]
    only: Option<String>,
    /// Override the grid, e.g. `128x64` or `64x64x31` (applies to every selected asset, or
    /// the nodes per axis of a table built to order).
    #[arg(long)]
    res: Option<String>,
    /// Override the encoding: `u16`, `f16` or `f32`.
    #[arg(long)]
    encoding: Option<String>,
    /// Replace existing files in `--out` (assets/ itself only takes the unmodified default set).
    #[arg(long)]
    force: bool,
    /// Fail (non-zero exit, nothing written) when a table's measured max |error| exceeds E.
    #[arg(long, value_name = "E")]
    max_error: Option<f64>,
}

#[derive(Subcommand)]
enum Cmd {
    /// Generate the default asset set (the default when no subcommand is given), or with
    /// `--kind`/`--config FILE.toml` one table built to order.
    Generate(Box<generate::Args>),
    /// Recompute each table's error against the direct kernel at fresh random points; exit
    /// non-zero when a table is worse than its header says (see `--tolerance`).
    Verify {
        /// Files (default: every `*.blut` in assets/).
        files: Vec<PathBuf>,
        /// Random points per table (default: as recorded in each header, at most
        /// 200000; the work never depends on a number read from the file beyond that cap).
        #[arg(long)]
        samples: Option<u32>,
        /// Seed of the random points (default: a different one from the generator's).
        #[arg(long, default_value_t = 0x5EED_0002)]
        seed: u64,
        /// Allowed excess of the measured max |err| over the recorded one, relative: fail
        /// when measured > recorded × (1 + tolerance) + 1e-6. The default 0.1 covers the
        /// spread of a maximum over a different random sample of the same kind.
        #[arg(long, default_value_t = 0.1)]
        tolerance: f64,
    },
    /// Print the header in words.
    Inspect { file: PathBuf },
    /// Export the node values for GPU engines, with a JSON sidecar.
    Export(export::ExportArgs),
    /// Write the split-sum table in one engine's own container and layout (docs/engines.md).
    Engine(crate::engine::Args),
}

/// The workspace root (xtask's parent).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask has a parent")
        .to_path_buf()
}

pub fn assets_dir() -> PathBuf {
    workspace_root().join("assets")
}

pub fn run(a: Args) -> Result<()> {
    match a.cmd {
        None => gen::generate(a.gen),
        Some(Cmd::Generate(g)) => generate::run(*g),
        Some(Cmd::Verify {
            files,
            samples,
            seed,
            tolerance,
        }) => verify(files, samples, seed, tolerance),
        Some(Cmd::Inspect { file }) => {
            let lut = crate::fsio::load_lut(&file)?;
            print!("{}", lut.summary());
            Ok(())
        }
        Some(Cmd::Export(e)) => export::run(e),
        Some(Cmd::Engine(e)) => crate::engine::run(e),
    }
}

/// Most random points `lut verify` evaluates per table (the direct kernels cost up to
/// milliseconds per point; memory is a few hundred bytes per point).
pub const MAX_VERIFY_SAMPLES: u32 = 200_000;

fn verify(files: Vec<PathBuf>, samples: Option<u32>, seed: u64, tolerance: f64) -> Result<()> {
    if let Some(n) = samples {
        if n == 0 || n > MAX_VERIFY_SAMPLES {
            bail!("--samples must be in 1..={MAX_VERIFY_SAMPLES}, got {n}");
        }
    }
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        bail!("--tolerance must be a finite number >= 0");
    }
    let files = if files.is_empty() {
        list_assets(&assets_dir())?
    } else {
        files
    };
    let mut rows = Vec::new();
    let mut worse = Vec::new();
    for f in &files {
        // Size-capped read (an endless file such as /dev/zero stops at the loader's cap).
        let lut = crate::fsio::load_lut(f)?;
        let recorded = lut.header().error;
        let n = samples.unwrap_or(recorded.samples.clamp(1, MAX_VERIFY_SAMPLES));
        let view = lut.view()?;
        // Every table is measured with the kernels its header names (library generator).
        let st = gen::measure(&view, n, seed);
        let name = f.file_name().map_or_else(
            || f.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        );
        let limit = recorded.max_abs as f64 * (1.0 + tolerance) + 1e-6;
        if st.max_abs.is_nan() || st.max_abs as f64 > limit {
            worse.push(format!(
                "{name}: measured max |err| {:.3e} > recorded {:.3e} x (1 + {tolerance}) + 1e-6",
                st.max_abs, recorded.max_abs
            ));
        }
        rows.push(gen::Row {
            file: name,
            bytes: lut.bytes().len(),
            stats: st,
            secs: None,
        });
    }
    gen::print_table(&rows);
    if !worse.is_empty() {
        bail!(
            "tables worse than their headers say:\n  {}",
            worse.join("\n  ")
        );
    }
    Ok(())
}

pub fn list_assets(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("listing {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "blut"))
        .collect();
    v.sort();
    if v.is_empty() {
        bail!("no .blut files in {}", dir.display());
    }
    Ok(v)
}

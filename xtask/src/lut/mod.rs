//! `cargo xtask lut`: LUT generation (default), verification, inspection and export.
//! Format: `docs/lut-format.md`; readers: `brdf_core::lut` (no_std) and `brdf-lut` (std).

mod assets;
mod export;
mod gen;

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
    /// Output directory (default: `assets/` of the workspace).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Only the assets whose file name contains this text (e.g. `g_modified`, `dfg`, `kc_`).
    #[arg(long)]
    only: Option<String>,
    /// Override the grid, e.g. `128x64` or `64x64x31` (applies to every selected asset).
    #[arg(long)]
    res: Option<String>,
    /// Override the encoding: `u16`, `f16` or `f32`.
    #[arg(long)]
    encoding: Option<String>,
}

#[derive(Subcommand)]
enum Cmd {
    /// Generate the default asset set (the default when no subcommand is given).
    Generate(GenArgs),
    /// Recompute each table's error against the direct kernel at random points.
    Verify {
        /// Files (default: every `*.blut` in assets/).
        files: Vec<PathBuf>,
        /// Random points per table (default: as recorded in each header).
        #[arg(long)]
        samples: Option<u32>,
        /// Seed of the random points (default: a different one from the generator's).
        #[arg(long, default_value_t = 0x5EED_0002)]
        seed: u64,
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
        Some(Cmd::Generate(g)) => gen::generate(g),
        Some(Cmd::Verify {
            files,
            samples,
            seed,
        }) => {
            let files = if files.is_empty() {
                list_assets(&assets_dir())?
            } else {
                files
            };
            let mut rows = Vec::new();
            for f in &files {
                let bytes = std::fs::read(f).with_context(|| format!("reading {}", f.display()))?;
                let lut = brdf_lut::Lut::from_bytes(bytes)
                    .with_context(|| format!("loading {}", f.display()))?;
                let n = samples.unwrap_or(lut.header().error.samples).max(1);
                let st = gen::measure(&lut.view(), n, seed, false);
                rows.push(gen::Row {
                    file: f.file_name().unwrap().to_string_lossy().into_owned(),
                    bytes: lut.bytes().len(),
                    stats: st,
                    secs: None,
                });
            }
            gen::print_table(&rows);
            Ok(())
        }
        Some(Cmd::Inspect { file }) => {
            let lut = brdf_lut::Lut::from_path(&file)
                .with_context(|| format!("loading {}", file.display()))?;
            print!("{}", lut.summary());
            Ok(())
        }
        Some(Cmd::Export(e)) => export::run(e),
        Some(Cmd::Engine(e)) => crate::engine::run(e),
    }
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

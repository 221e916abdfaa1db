//! `cargo xtask lut`: LUT generation (default), verification, inspection and export.
//! Format, readers and writer: the `brdf-lut` crate (`docs/lut-format.md`).

mod export;
mod gen;
mod generate;

use anyhow::{bail, Context, Result};
use clap::Subcommand;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, after_help = LIMITS_HELP)]
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
        /// Random points per table, 1..=200000 and within the kind's time budget (default: as
        /// recorded in each header, capped by the same limits, with a note when capped; see
        /// `cargo xtask lut --help` and docs/lut-format.md, Limits).
        #[arg(long, value_parser = generate::samples_arg)]
        samples: Option<u32>,
        /// Seed of the random points (default: a different one from the generator's).
        #[arg(long, default_value_t = 0x5EED_0002)]
        seed: u64,
        /// Allowed excess over the recorded max |err|, relative: fail when more fresh points
        /// lie above recorded × (1 + tolerance) + 1e-6 than would by chance in a table that
        /// is as recorded (false-alarm rate 1e-3 whatever the errors' law;
        /// docs/lut-format.md, section 7).
        #[arg(long, default_value_t = 0.1)]
        tolerance: f64,
    },
    /// Print the header in words (strings escaped: control, format and bidirectional
    /// characters are shown as `\u{…}`). FILE must be a regular file.
    Inspect { file: PathBuf },
    /// Export the node values for GPU engines, with a JSON sidecar.
    Export(export::ExportArgs),
    /// Write the split-sum table in one engine's own container and layout (docs/engines.md).
    Engine(crate::engine::Args),
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

/// The work-size limits, for `--help` (docs/lut-format.md, Limits).
pub const LIMITS_HELP: &str = "Limits (checked before any work; docs/lut-format.md, Limits): \
error-measurement points (--samples, a header's count) 1..=200000; nodes per axis 2..=65536; \
nodes x channels of a table built <= 2^25; estimated work of one generation <= 600 s of one \
core, of verifying one table <= 20 s of one core (more recorded points are verified at as \
many as fit, with a note); input files <= 64 MiB (TOML 1 MiB), regular files only.";

/// How many points `lut verify` measures on a table (the library's
/// [`brdf_lut::generate::verify_points`]), with a note when the header's count is capped.
fn verify_points(name: &str, h: &brdf_lut::Header<'_>, samples: Option<u32>) -> Result<u32> {
    let p = brdf_lut::generate::verify_points(h, samples)
        .map_err(|e| anyhow::anyhow!("{name}: --samples {e}"))?;
    if let Some(recorded) = p.capped_from {
        eprintln!(
            "note: {name}: verifying {} of the {recorded} recorded points (about {} us a \
             point for a {:?} table; the limit is {} s of one core per table)",
            p.n,
            p.cost_us,
            h.kind,
            brdf_lut::limits::MAX_VERIFY_SECONDS
        );
    }
    Ok(p.n)
}

fn verify(files: Vec<PathBuf>, samples: Option<u32>, seed: u64, tolerance: f64) -> Result<()> {
    use brdf_lut::generate::{measure_table, worse_than_recorded};
    if let Some(n) = samples {
        brdf_lut::limits::check_samples("--samples", n as u64)?;
    }
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        bail!("--tolerance must be a finite number >= 0");
    }
    let files = if files.is_empty() {
        list_assets(&crate::fsio::assets_dir())?
    } else {
        files
    };
    let mut rows = Vec::new();
    let mut worse = Vec::new();
    for f in &files {
        // Size-capped read of a regular file; the parser rejects error statistics that are
        // not finite and >= 0, so `recorded` is a claim that can be checked.
        let lut = crate::fsio::load_lut(f)?;
        let recorded = lut.header().error;
        let name = f.file_name().map_or_else(
            || f.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        );
        let view = lut.view()?;
        let h = view.header();
        let n = verify_points(&name, h, samples)?;
        eprintln!("verifying {name}: {n} points");
        // Every table is measured with the kernels its header names (library generator).
        let m = measure_table(&view, n, seed);
        let own = measure_table(&view, n.min(recorded.samples), recorded.seed);
        if let Some(w) = worse_than_recorded(&own, &m, &recorded, tolerance) {
            worse.push(worse_text(&name, w, n, recorded.max_abs, tolerance));
        }
        let st = m.stats;
        worse.extend(verify_nodes(&name, &view));
        rows.push(gen::Row {
            file: name,
            bytes: lut.bytes().len(),
            stats: st,
            integration: h.integration,
            evals: None,
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

/// The line `lut verify` prints for a table worse than its header's maximum.
fn worse_text(name: &str, w: brdf_lut::generate::Worse, n: u32, rec: f32, tol: f64) -> String {
    use brdf_lut::generate::Worse;
    let limit = format!("the recorded max |err| {rec:.3e} x (1 + {tol}) + 1e-6");
    match w {
        Worse::NotANumber => format!("{name}: an error is not a number"),
        Worse::OwnPoints { max } => {
            format!("{name}: {max:.3e} at the header's own points, above {limit}")
        }
        Worse::FreshPoints { above, allowed } => format!(
            "{name}: {above} of {n} fresh points above {limit} (at most {allowed} would be by \
             chance)"
        ),
    }
}

/// Nodes `lut verify` recomputes per table (plus the smallest-μ column's).
pub const VERIFY_NODES: usize = 64;

/// The recorded integration bound checked at [`VERIFY_NODES`] spread nodes (and the
/// smallest-μ column) against an independent, much finer rule
/// ([`brdf_lut::generate::check_recorded_bound`]): the failure, naming its node. A version
/// 1 file records no bound (a note, no failure); a header the generator cannot describe
/// fails.
fn verify_nodes(name: &str, view: &brdf_lut::LutView<'_>) -> Option<String> {
    use brdf_lut::generate::BoundCheck;
    let (bound, worst, count) = match brdf_lut::generate::check_recorded_bound(view, VERIFY_NODES) {
        BoundCheck::NotRecorded => {
            eprintln!("note: {name}: no integration bound recorded (a version 1 file)");
            return None;
        }
        BoundCheck::NoSpec => {
            return Some(format!(
                "{name}: the header describes no table the generator builds"
            ))
        }
        BoundCheck::Checked {
            bound,
            worst,
            count,
        } => (bound, worst, count),
    };
    let diff = (worst.stored - worst.reference).abs();
    eprintln!(
        "{name}: {count} node values within the recorded integration bound {bound:.3e} \
         (closest: |diff| {diff:.3e} of {:.3e} allowed)",
        worst.allowed
    );
    if worst.ok() {
        return None;
    }
    Some(format!(
        "{name}: node {} at {:?}, channel {}: stored {:.9e}, reference {:.9e}, |diff| {diff:.3e} \
         > {:.3e} allowed (recorded integration bound {bound:.3e} + half a quantisation step + \
         the reference's estimate)",
        worst.node, worst.at, worst.channel, worst.stored, worst.reference, worst.allowed
    ))
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

#[cfg(test)]
mod tests {
    use brdf_lut::limits::*;

    /// `--help` states the limits the code enforces.
    #[test]
    fn help_lists_the_limits() {
        let h = super::LIMITS_HELP;
        for n in [
            format!("1..={MAX_SAMPLES}"),
            format!("2..={MAX_NODES_PER_AXIS}"),
            format!("2^{}", MAX_BUILD_VALUES.trailing_zeros()),
            format!("{MAX_GENERATE_SECONDS} s"),
            format!("{MAX_VERIFY_SECONDS} s"),
            format!("{} MiB", brdf_lut::MAX_FILE_BYTES >> 20),
            format!("TOML {} MiB", MAX_CONFIG_BYTES >> 20),
        ] {
            assert!(h.contains(&n), "{n} missing from: {h}");
        }
        assert_eq!(MAX_BUILD_VALUES, brdf_lut::generate::MAX_GENERATED_VALUES);
    }
}

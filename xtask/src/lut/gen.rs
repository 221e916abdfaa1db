//! `cargo xtask lut`: the default asset set ([`brdf_lut::generate::default_set`]), built by
//! the library generator, written together (or compared with the committed files).

use super::GenArgs;
use anyhow::{anyhow, bail, Context, Result};
use brdf_lut::generate::{self, Asset};
use brdf_lut::{ErrorStats, LutView};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use brdf_engine_assets::fsio::Policy as WritePolicy;

pub struct Row {
    pub file: String,
    pub bytes: usize,
    pub stats: ErrorStats,
    /// The recorded integration error bound (None: a version 1 file).
    pub integration: Option<f32>,
    /// Integrand evaluations per node (generation only).
    pub evals: Option<f64>,
    pub secs: Option<f64>,
}

/// A progress bar over `len` nodes with the elapsed time and an ETA, on stderr when it is a
/// terminal; hidden otherwise and when `CI` is `true` or `1`.
pub fn progress(len: u64, msg: String) -> ProgressBar {
    let pb = ProgressBar::new(len);
    let hide = !std::io::stderr().is_terminal()
        || std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
    if hide {
        pb.set_draw_target(ProgressDrawTarget::hidden());
    }
    pb.set_style(
        ProgressStyle::with_template("{msg:28} [{bar:30}] {pos}/{len} nodes {elapsed}, ETA {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_message(msg);
    pb
}

/// `--res` and `--encoding` applied to every selected asset (the library's reading of a
/// description, [`brdf_lut::generate::Description::apply`]), each then checked against the
/// work-size limits before anything is computed.
fn apply_overrides(assets: &mut [Asset], g: &GenArgs) -> Result<()> {
    let desc = generate::Description {
        res: g.res.clone(),
        encoding: g.encoding.clone(),
        ..Default::default()
    };
    for a in assets.iter_mut() {
        let at = |e: generate::DescribeError| anyhow!("{}: {}", a.file, e.with_flags());
        desc.apply(&a.file, &mut a.spec).map_err(at)?;
        if g.res.is_some() {
            generate::check_limits(&a.spec).map_err(at)?;
        }
    }
    Ok(())
}

/// The selected default assets, with the overrides applied.
fn selection(g: &GenArgs) -> Result<Vec<Asset>> {
    let mut assets = generate::default_set();
    if let Some(only) = &g.only {
        assets.retain(|a| a.file.contains(only.as_str()));
        if assets.is_empty() {
            bail!("--only `{only}` matches no asset");
        }
    }
    apply_overrides(&mut assets, g)?;
    if let Some(e) = g.max_error {
        if !(e.is_finite() && e > 0.0) {
            bail!("--max-error must be a positive number (got {e})");
        }
    }
    Ok(assets)
}

/// `cargo xtask lut [generate]`.
pub fn generate(g: GenArgs) -> Result<()> {
    let assets = selection(&g)?;
    let check_dir = if g.check {
        Some(tempfile::tempdir().context("creating a temporary folder")?)
    } else {
        None
    };
    let (out, policy) = write_target(&g, check_dir.as_ref().map(|d| d.path()))?;
    let paths: Vec<PathBuf> = assets.iter().map(|a| out.join(&a.file)).collect();
    crate::fsio::check(
        &paths.iter().map(|p| p.as_path()).collect::<Vec<_>>(),
        &policy,
    )?;
    let t0 = Instant::now();
    let mut files = Vec::new();
    let mut rows = Vec::new();
    for a in &assets {
        let t = Instant::now();
        let g = build(a)?;
        let bytes = g.bytes;
        let h = *LutView::parse(&bytes)
            .context("generated file does not parse")?
            .header();
        rows.push(Row {
            file: a.file.clone(),
            bytes: bytes.len(),
            stats: h.error,
            integration: h.integration,
            evals: Some(g.evals as f64 / h.nodes().max(1) as f64),
            secs: Some(t.elapsed().as_secs_f64()),
        });
        files.push((out.join(&a.file), bytes));
    }
    if let Some(lim) = g.max_error {
        let over: Vec<String> = rows
            .iter()
            .filter(|r| r.stats.max_abs.is_nan() || r.stats.max_abs as f64 > lim)
            .map(|r| format!("{} ({:.3e})", r.file, r.stats.max_abs))
            .collect();
        if !over.is_empty() {
            print_table(&rows);
            bail!(
                "measured max |error| exceeds --max-error {lim:.3e}: {}; nothing written",
                over.join(", ")
            );
        }
    }
    crate::fsio::write_together(&files, &policy)?;
    print_table(&rows);
    println!("total generation time {:.1} s", t0.elapsed().as_secs_f64());
    if g.check {
        let committed = g.out.clone().unwrap_or_else(crate::fsio::assets_dir);
        return compare(&files, &committed);
    }
    println!("wrote {} files to {}", assets.len(), out.display());
    Ok(())
}

/// `--check`: every fresh file byte for byte against the committed one of the same name.
fn compare(files: &[(PathBuf, Vec<u8>)], committed: &Path) -> Result<()> {
    let mut bad = Vec::new();
    for (path, fresh) in files {
        let name = path.file_name().unwrap_or_default();
        let shown = name.to_string_lossy();
        match std::fs::read(committed.join(name)) {
            Ok(b) if *fresh == b => {}
            Ok(_) => bad.push(format!("{shown} differs")),
            Err(_) => bad.push(format!("{shown} is missing from {}", committed.display())),
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
        files.len(),
        committed.display()
    );
    Ok(())
}

/// Where the tables go and what may be replaced there: the unmodified default set replaces
/// the files in assets/ (its home, under version control); anything else (`--res`,
/// `--encoding`) needs `--out` outside assets/, and replaces existing files only with
/// `--force`.
fn write_target(g: &GenArgs, check_dir: Option<&Path>) -> Result<(PathBuf, WritePolicy)> {
    use brdf_engine_assets::fsio::Policy;
    if let Some(d) = check_dir {
        return Ok((d.to_path_buf(), Policy::default()));
    }
    let modified = g.res.is_some() || g.encoding.is_some();
    let assets = crate::fsio::assets_dir();
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
    Ok((out, crate::fsio::Policy::new(g.force, &[])))
}

/// One asset through the library generator, with a progress bar over its nodes.
fn build(a: &Asset) -> Result<generate::Generated> {
    let total: u64 = a.spec.axes.iter().map(|x| x.count as u64).product();
    let pb = progress(total, a.file.clone());
    let res = generate::generate(&a.spec, &|k| pb.inc(k));
    pb.finish_and_clear();
    res.map_err(|e| anyhow!("{}: {e}", a.file))
}

/// The table of generated or verified files: size, interpolation error (max, RMS, points),
/// the recorded integration bound, evaluations per node and time.
pub fn print_table(rows: &[Row]) {
    println!(
        "{:<28} {:>9} {:>11} {:>11} {:>8} {:>11} {:>10} {:>8}",
        "table", "bytes", "max |err|", "RMS err", "points", "integ. err", "evals/node", "time s"
    );
    let dash = || "-".to_string();
    for r in rows {
        println!(
            "{:<28} {:>9} {:>11.3e} {:>11.3e} {:>8} {:>11} {:>10} {:>8}",
            r.file,
            r.bytes,
            r.stats.max_abs,
            r.stats.rms,
            r.stats.samples,
            r.integration.map_or_else(dash, |e| format!("{e:.3e}")),
            r.evals.map_or_else(dash, |e| format!("{e:.0}")),
            r.secs.map_or_else(dash, |s| format!("{s:.1}"))
        );
    }
}

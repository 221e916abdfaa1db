//! `cargo xtask lut engine <target>`: the split-sum (A, B) table for GGX with height-correlated
//! Smith, α = r² (r = perceptual roughness), in one engine's container and layout, with a JSON
//! sidecar and WGSL/GLSL sampling functions: made by the `brdf-engine-assets` library (texels
//! from the one generator, `brdf_lut::generate`), written here. `report` compares our files
//! with the engines' shipped tables and writes docs/engines.md.

mod report;

use anyhow::{bail, Context, Result};
pub use brdf_engine_assets::{Engine, File, SplitSumTexels, MAX_SIZE};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

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
    /// Every split-sum target above, each into its own sub-folder of --out.
    All,
    /// Rough glass: 3-D KTX2 (R16G16_SFLOAT: reflected R, transmitted T over μ × roughness ×
    /// η) + BLUT + JSON sidecar, light from outside (`glass_e`, η ∈ [1, 3]) and from inside
    /// (`glass_e_inv`, η ∈ [1/3, 1]), and their averages over μ as 2-D KTX2 (`glass_e_avg`,
    /// `glass_e_avg_inv`, roughness × η); --size N gives N³ and N² (default 32).
    Glass,
    /// Blender Cycles' rough-glass albedo tables (`table_ggx_glass_E`, `_inv_E`, `_Eavg`,
    /// `_inv_Eavg`) as C arrays in Cycles' nodes and index order + JSON sidecar; --size N
    /// gives N nodes per axis (default and drop-in: 16). Values: Cycles' own closure
    /// integrand, height-correlated G (`glass::correlated`; the sidecar's `masking`).
    Cycles,
    /// Blender EEVEE's rough-glass tables (`bsdf_ggx`, `btdf_ggx` of `eevee_lut.cc`) as C++
    /// arrays in EEVEE's nodes and order + JSON sidecar: each channel the converged integral
    /// of what EEVEE's generator averages; --size N gives N × N × max(2, N/4) (EEVEE: 64).
    Eevee,
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
    #[arg(long, value_parser = size_arg)]
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
    /// The library's engine of a single-engine target.
    pub fn engine(self) -> Option<Engine> {
        Engine::ALL.into_iter().find(|e| e.name() == self.name())
    }
    pub fn name(self) -> &'static str {
        match self {
            Target::Khronos => "khronos",
            Target::Bevy => "bevy",
            Target::Filament => "filament",
            Target::Threejs => "threejs",
            Target::Exr => "exr",
            Target::All => "all",
            Target::Glass => "glass",
            Target::Cycles => "cycles",
            Target::Eevee => "eevee",
            Target::Report => "report",
        }
    }
}

/// All n² texel-centre integrals (library generator), with a progress bar for large tables.
/// `--size`: a whole number; one too large for any integer type is refused naming the
/// limit (2..=[`MAX_SIZE`]), as every other size flag is.
fn size_arg(s: &str) -> Result<usize, String> {
    match crate::args::whole::<usize>(s) {
        Ok(Some(n)) => Ok(n),
        Ok(None) => Err(format!(
            "{s}: the table edge must be between 2 and {MAX_SIZE}"
        )),
        Err(e) => Err(format!("`{s}` is not a whole number: {e}")),
    }
}

pub fn compute_grid(n: usize, quiet: bool) -> Result<SplitSumTexels> {
    let bar = (!quiet && n >= 128).then(|| {
        let b = ProgressBar::new((n * n) as u64);
        b.set_style(
            ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} texels, eta {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b.set_message(format!("{n}×{n} split-sum integrals"));
        b
    });
    let t = brdf_engine_assets::split_sum_texels(n, &|k| {
        if let Some(b) = &bar {
            b.inc(k);
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(t?)
}

/// Writes a whole set (data files, sidecar, shaders) into `dir` through the one safe writer
/// ([`crate::fsio::write_together`]: temporary files and renames, all or nothing; existing
/// files replaced only with `force`).
pub fn write_set(dir: &Path, files: &[File], force: bool) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let files: Vec<(PathBuf, Vec<u8>)> = files
        .iter()
        .map(|f| (dir.join(&f.name), f.bytes.clone()))
        .collect();
    crate::fsio::write_together(&files, &crate::fsio::Policy::new(force, &[]))
}

fn default_out(t: Target) -> PathBuf {
    crate::fsio::workspace_root()
        .join("target/lut-engine")
        .join(t.name())
}

/// Generates one engine's files into `dir`; returns the seconds spent on the integrals.
pub fn generate(e: Engine, n: usize, dir: &Path, force: bool, quiet: bool) -> Result<f64> {
    if !(2..=MAX_SIZE).contains(&n) {
        bail!("--size {n}: the table edge must be between 2 and {MAX_SIZE}");
    }
    let t0 = std::time::Instant::now();
    let grid = compute_grid(n, quiet)?;
    let files = e.target_files(&grid)?;
    let secs = t0.elapsed().as_secs_f64();
    write_set(dir, &files, force)?;
    if !quiet {
        println!(
            "{}: {n}×{n} in {secs:.1} s → {}",
            e.name(),
            files
                .iter()
                .map(|f| dir.join(&f.name).display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(secs)
}

/// The rough-glass files (both directions of light) into `dir`: E at N³ texels and E_avg
/// at N² each.
fn glass(n: usize, dir: &Path, force: bool) -> Result<()> {
    if !(2..=256).contains(&n) {
        bail!("--size {n}: a glass table's edge must be between 2 and 256");
    }
    for inside in [false, true] {
        for shape in [&[n; 3][..], &[n; 2][..]] {
            let t0 = std::time::Instant::now();
            let files = brdf_engine_assets::glass(shape, inside, &|_| {})?;
            let size = format!("{n}{}", if shape.len() == 3 { "³" } else { "²" });
            write_and_report("glass", &size, t0, dir, &files, force)?;
        }
    }
    Ok(())
}

/// Writes `files` into `dir` and prints what was written (`size`: the table's shape) and how
/// long it took since `t0`.
fn write_and_report(
    what: &str,
    size: &str,
    t0: std::time::Instant,
    dir: &Path,
    files: &[brdf_engine_assets::File],
    force: bool,
) -> Result<()> {
    write_set(dir, files, force)?;
    let names: Vec<String> = files
        .iter()
        .map(|f| dir.join(&f.name).display().to_string())
        .collect();
    let secs = t0.elapsed().as_secs_f64();
    println!("{what}: {size} in {secs:.1} s → {}", names.join(", "));
    Ok(())
}

/// The Cycles E and E_avg tables into `dir` (both directions), n nodes per axis.
fn cycles(n: usize, dir: &Path, force: bool) -> Result<()> {
    let cap = brdf_engine_assets::cycles::CYCLES_MAX_EDGE;
    if !(2..=cap).contains(&n) {
        bail!("--size {n}: a Cycles table's edge must be between 2 and {cap} (Cycles: 16)");
    }
    let bar = ProgressBar::new((2 * n * n * (n + 1)) as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} nodes, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(format!("Cycles glass {n}³"));
    let t0 = std::time::Instant::now();
    let files = brdf_engine_assets::cycles(n, true, &|k| bar.inc(k));
    bar.finish_and_clear();
    write_and_report("cycles", &format!("{n}³"), t0, dir, &files?, force)
}

/// EEVEE's glass tables into `dir`: n × n nodes on (η, μ), max(2, n/4) roughness slices.
fn eevee(n: usize, dir: &Path, force: bool) -> Result<()> {
    let cap = brdf_engine_assets::eevee::EEVEE_EDGE;
    if !(2..=cap).contains(&n) {
        bail!("--size {n}: an EEVEE table's edge must be between 2 and {cap} (EEVEE: 64)");
    }
    let m = (n / 4).max(2);
    let bar = ProgressBar::new((2 * n * n * m) as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} nodes, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(format!("EEVEE glass {n}×{n}×{m}"));
    let t0 = std::time::Instant::now();
    let files = brdf_engine_assets::eevee::eevee(n, m, &|k| bar.inc(k));
    bar.finish_and_clear();
    write_and_report("eevee", &format!("{n}×{n}×{m}"), t0, dir, &files?, force)
}

pub fn run(a: Args) -> Result<()> {
    if a.target == Target::Eevee {
        let out = a.out.unwrap_or_else(|| default_out(a.target));
        return eevee(a.size.unwrap_or(64), &out, a.force);
    }
    if a.target == Target::Cycles {
        let out = a.out.unwrap_or_else(|| default_out(a.target));
        return cycles(a.size.unwrap_or(16), &out, a.force);
    }
    if a.target == Target::Glass {
        let out = a.out.unwrap_or_else(|| default_out(a.target));
        return glass(a.size.unwrap_or(32), &out, a.force);
    }
    match (a.target, a.target.engine()) {
        (Target::Report, _) => report::run(
            a.out.unwrap_or_else(|| default_out(Target::All)),
            a.anchors,
            a.doc,
        ),
        (_, Some(e)) => {
            let n = a.size.unwrap_or(e.native_size());
            let out = a.out.unwrap_or_else(|| default_out(a.target));
            generate(e, n, &out, a.force, false).map(|_| ())
        }
        _ => {
            if a.size.is_some() {
                bail!("--size applies to one target, not to `all` (each engine has its own size)");
            }
            let out = a.out.unwrap_or_else(|| default_out(Target::All));
            for e in Engine::ALL {
                generate(e, e.native_size(), &out.join(e.name()), a.force, false)?;
            }
            Ok(())
        }
    }
}

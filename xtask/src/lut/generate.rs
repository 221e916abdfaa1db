//! `cargo xtask lut generate`: without table options, the default asset set (as plain
//! `cargo xtask lut`); with `--kind` or `--config FILE.toml`, one table built to order
//! through the library call `brdf_lut::generate::generate`.
//!
//! A TOML file holds the same options as the flags (flags win), so an asset pipeline can
//! keep its tables under version control; both are read into one
//! `brdf_lut::generate::Description` (names, defaults and errors are the library's):
//!
//! ```toml
//! kind = "split-sum"          # g-per-sigma | g-over-sigma | split-sum | e | e-avg
//! model = "ggx"               # ggx | beckmann | torrance-sparrow
//! masking = "smith-correlated" # smith-separable | smith-correlated | v-cavity | modified
//! roughness = "perceptual"    # perceptual | alpha | sigma
//! encoding = "f16"            # u16 | f16 | f32
//! interpolation = "linear"    # linear | catmull-rom
//! samples = 5000              # error-measurement points
//! max-error = 1e-3            # fail (and write nothing) above this measured max |error|
//! out = "dfg_ggx_32.blut"     # relative to this file's folder
//! [axes.mu]
//! count = 32
//! lo = 0.0174524
//! hi = 1.0
//! warp = "log"                # linear | log | sqrt | cos | sqrt-cos
//! placement = "texel-centre"  # endpoint | texel-centre
//! [axes.roughness]
//! count = 32
//! ```

use super::GenArgs;
use anyhow::{anyhow, bail, Result};
use brdf_lut::generate::describe::AxisDescription;
use brdf_lut::generate::{check_limits, DescribeError, Description, Value};
use brdf_lut::limits::{self, MAX_CONFIG_BYTES};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
#[command(after_help = super::LIMITS_HELP)]
pub struct Args {
    #[command(flatten)]
    set: GenArgs,
    /// A TOML file with the table options (see `xtask/src/lut/generate.rs`); flags override it.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Build one table of this kind: g-per-sigma, g-over-sigma, split-sum, e, e-avg.
    #[arg(long)]
    kind: Option<String>,
    /// Distribution: ggx, beckmann, torrance-sparrow (Gaussian slopes, Beckmann m = √2σ).
    #[arg(long)]
    model: Option<String>,
    /// G: smith-separable, smith-correlated (GGX/Beckmann default), v-cavity, modified
    /// (Torrance–Sparrow default; G tables).
    #[arg(long)]
    masking: Option<String>,
    /// The roughness axis: perceptual (r, width r²), alpha (the width: GGX α, Beckmann m) or
    /// sigma (RMS slope, m = √2σ).
    #[arg(long)]
    roughness: Option<String>,
    /// σ of a g-per-sigma table.
    #[arg(long)]
    sigma: Option<f64>,
    /// An axis range, e.g. `--range mu=0.0174524:1` (repeatable).
    #[arg(long = "range", value_name = "AXIS=LO:HI")]
    ranges: Vec<String>,
    /// An axis warp: linear, log, sqrt, cos, sqrt-cos, e.g. `--warp mu=log`; without `AXIS=`
    /// for every axis (repeatable).
    #[arg(long = "warp", value_name = "[AXIS=]WARP")]
    warps: Vec<String>,
    /// Node placement: endpoint or texel-centre, e.g. `--placement texel-centre` for every
    /// axis or `--placement mu=endpoint` (repeatable).
    #[arg(long = "placement", value_name = "[AXIS=]PLACEMENT")]
    placements: Vec<String>,
    /// linear or catmull-rom (default).
    #[arg(long)]
    interpolation: Option<String>,
    /// Random points of the error measurement, 1..=200000 (default 2000).
    #[arg(long, value_parser = samples_arg)]
    samples: Option<u32>,
    /// Seed of the error measurement.
    #[arg(long)]
    seed: Option<u64>,
}

/// A `--samples` count: a number too wide for u32 is refused naming the limit (clap's own
/// message would say only "too large"); counts within u32 meet the limit check later.
pub(super) fn samples_arg(s: &str) -> Result<u32, String> {
    match crate::args::whole::<u32>(s) {
        Ok(Some(n)) => Ok(n),
        Ok(None) => Err(format!(
            "{s} points; the limit is 1..={} (docs/lut-format.md, Limits)",
            limits::MAX_SAMPLES
        )),
        Err(e) => Err(format!("`{s}` is not a whole number of points: {e}")),
    }
}

/// A library error, with the fields named as this command's flags.
fn flags(e: DescribeError) -> anyhow::Error {
    anyhow!(e.with_flags())
}

/// Whether any table option is given (they need `--kind` or `--config`).
fn table_options(a: &Args) -> bool {
    a.model.is_some()
        || a.masking.is_some()
        || a.roughness.is_some()
        || a.sigma.is_some()
        || !a.ranges.is_empty()
        || !a.warps.is_empty()
        || !a.placements.is_empty()
        || a.interpolation.is_some()
        || a.samples.is_some()
}

pub fn run(a: Args) -> Result<()> {
    if a.config.is_none() && a.kind.is_none() {
        if table_options(&a) {
            bail!("table options need --kind (or --config FILE) to say which table to build");
        }
        return super::gen::generate(a.set);
    }
    if a.set.only.is_some() || a.set.check {
        bail!("--only and --check apply to the default set, not to a table built to order");
    }
    let (mut desc, cfg_dir) = read_config(a.config.as_deref())?;
    overlay(&a, &mut desc)?;
    let spec = desc.spec().map_err(flags)?;
    let out = match (&a.set.out, &desc.out) {
        (Some(o), _) => o.clone(),
        (None, Some(o)) => cfg_dir.join(o),
        (None, None) => bail!("give the output file with --out FILE (or `out` in the TOML file)"),
    };
    let inputs: Vec<&Path> = a.config.iter().map(PathBuf::as_path).collect();
    let policy = crate::fsio::Policy::new(a.set.force, &inputs);
    crate::fsio::check(&[&out], &policy)?;
    check_limits(&spec).map_err(flags)?;
    let total: u64 = spec.axes.iter().map(|x| x.count as u64).product();
    let pb = super::gen::progress(total, out.display().to_string());
    let t0 = std::time::Instant::now();
    let res = brdf_lut::generate::generate(&spec, &|k| pb.inc(k));
    pb.finish_and_clear();
    let t = res.map_err(|e| anyhow!("{e}"))?;
    let e = t.error;
    let summary = format!(
        "{}: {} bytes, max |error| {:.3e}, RMS {:.3e} over {} random points, integration \
         bound {:.3e}, {:.0} integrand evaluations per node ({:.1} s)",
        out.display(),
        t.bytes.len(),
        e.max_abs,
        e.rms,
        e.samples,
        t.integration,
        t.evals as f64 / total.max(1) as f64,
        t0.elapsed().as_secs_f64()
    );
    desc.check_max_error(&spec, e.max_abs).map_err(flags)?;
    crate::fsio::write_together(&[(out.clone(), t.bytes)], &policy)?;
    println!("wrote {summary}");
    Ok(())
}

/// A TOML value as the library's.
fn value(v: toml::Value) -> Value {
    match v {
        toml::Value::String(s) => Value::Text(s),
        toml::Value::Integer(i) => Value::Int(i),
        toml::Value::Float(x) => Value::Float(x),
        o => Value::Other(o.type_str().to_string()),
    }
}

/// The TOML file (size-capped, UTF-8) read into a description, and the folder its relative
/// `out` is taken from; the empty description without a file.
fn read_config(path: Option<&Path>) -> Result<(Description, PathBuf)> {
    let mut d = Description::default();
    let Some(p) = path else {
        return Ok((d, PathBuf::new()));
    };
    let bytes = crate::fsio::read_limited(p, MAX_CONFIG_BYTES)?;
    let text = String::from_utf8(bytes).map_err(|_| anyhow!("{}: not UTF-8 text", p.display()))?;
    let t: toml::Table = toml::from_str(&text).map_err(|e| anyhow!("{}: {e}", p.display()))?;
    let at = |e: DescribeError| anyhow!("{}: {e}", p.display());
    for (k, v) in t {
        match (k.as_str(), v) {
            ("axes", toml::Value::Table(axes)) => {
                for (name, axis) in axes {
                    let toml::Value::Table(fields) = axis else {
                        bail!("{}: `axes.{name}` must be a table", p.display());
                    };
                    d.name_axis(&name);
                    for (f, v) in fields {
                        d.set_axis(&name, &f, value(v)).map_err(at)?;
                    }
                }
            }
            (k, v) => d.set(k, value(v)).map_err(at)?,
        }
    }
    Ok((d, p.parent().map(Path::to_path_buf).unwrap_or_default()))
}

/// The flags over the file's description (flags win; an axis-less `--warp` or
/// `--placement` also replaces the file's per-axis ones).
fn overlay(a: &Args, d: &mut Description) -> Result<()> {
    let set = |to: &mut Option<String>, flag: &Option<String>| {
        if flag.is_some() {
            to.clone_from(flag);
        }
    };
    set(&mut d.kind, &a.kind);
    set(&mut d.model, &a.model);
    set(&mut d.masking, &a.masking);
    set(&mut d.roughness, &a.roughness);
    set(&mut d.res, &a.set.res);
    set(&mut d.encoding, &a.set.encoding);
    set(&mut d.interpolation, &a.interpolation);
    d.sigma = a.sigma.or(d.sigma);
    d.samples = a.samples.map(u64::from).or(d.samples);
    d.seed = a.seed.or(d.seed);
    d.max_error = a.set.max_error.or(d.max_error);
    for r in &a.ranges {
        let bad = || anyhow!("--range `{r}` is not AXIS=LO:HI");
        let (name, v) = r.split_once('=').ok_or_else(bad)?;
        let (lo, hi) = v.split_once(':').ok_or_else(bad)?;
        let num = |t: &str| -> Result<f64> {
            t.trim()
                .parse()
                .map_err(|_| anyhow!("--range `{r}`: `{t}` is not a number"))
        };
        let x = d.axes.entry(name.trim().to_string()).or_default();
        (x.lo, x.hi) = (Some(num(lo)?), Some(num(hi)?));
    }
    let warps = a.warps.iter().map(|w| (w, true));
    for (flag, warp) in warps.chain(a.placements.iter().map(|p| (p, false))) {
        match flag.split_once('=') {
            Some((name, v)) => {
                let x = d.axes.entry(name.trim().to_string()).or_default();
                *slot(x, warp) = Some(v.trim().into());
            }
            None => {
                d.axes.values_mut().for_each(|x| *slot(x, warp) = None);
                let all = if warp { &mut d.warp } else { &mut d.placement };
                *all = Some(flag.trim().into());
            }
        }
    }
    Ok(())
}

/// An axis' warp (`warp`) or placement.
fn slot(x: &mut AxisDescription, warp: bool) -> &mut Option<String> {
    if warp {
        &mut x.warp
    } else {
        &mut x.placement
    }
}

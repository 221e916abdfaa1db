//! `cargo xtask lut generate`: without table options, the default asset set (as plain
//! `cargo xtask lut`); with `--kind` or `--config FILE.toml`, one table built to order
//! through the library call `brdf_lut::generate::generate`.
//!
//! A TOML file holds the same options as the flags (flags win), so an asset pipeline can
//! keep its tables under version control:
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
use anyhow::{anyhow, bail, Context, Result};
use brdf_lut::generate::{distribution_options, Distribution, Kind, Masking, Roughness, Spec};
use brdf_lut::{Encoding, Interpolation, Placement, Warp};
use serde::Deserialize;
use std::collections::BTreeMap;
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

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
struct Config {
    kind: Option<String>,
    model: Option<String>,
    masking: Option<String>,
    roughness: Option<String>,
    sigma: Option<f64>,
    res: Option<String>,
    encoding: Option<String>,
    interpolation: Option<String>,
    samples: Option<u32>,
    seed: Option<u64>,
    max_error: Option<f64>,
    out: Option<PathBuf>,
    #[serde(default)]
    axes: BTreeMap<String, AxisConfig>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct AxisConfig {
    count: Option<u32>,
    lo: Option<f64>,
    hi: Option<f64>,
    warp: Option<String>,
    placement: Option<String>,
}

use brdf_lut::limits::{self, MAX_CONFIG_BYTES};

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

/// One node count of `--res`: a whole number within the tool's limit per axis, checked here
/// so that a number too large for any integer type names the limit too (not only "not a
/// number").
fn res_count(res: &str, t: &str) -> Result<u32> {
    let t = t.trim();
    let max = limits::MAX_NODES_PER_AXIS as u64;
    let n = match crate::args::whole::<u64>(t) {
        Ok(n) => n.unwrap_or(u64::MAX),
        Err(_) => bail!("--res `{res}`: `{t}` is not a whole number of nodes"),
    };
    limits::check_range("nodes per axis", n, 2, max)
        .map_err(|e| anyhow!("--res `{res}`: `{t}`: {e}"))?;
    Ok(n as u32)
}

pub fn run(a: Args) -> Result<()> {
    if a.config.is_none() && a.kind.is_none() {
        let extra = a.model.is_some()
            || a.masking.is_some()
            || a.roughness.is_some()
            || a.sigma.is_some()
            || !a.ranges.is_empty()
            || !a.warps.is_empty()
            || !a.placements.is_empty()
            || a.interpolation.is_some()
            || a.samples.is_some();
        if extra {
            bail!("table options need --kind (or --config FILE) to say which table to build");
        }
        super::check_set_limits(&a.set)?;
        return super::gen::generate(a.set);
    }
    if a.set.only.is_some() || a.set.check {
        bail!("--only and --check apply to the default set, not to a table built to order");
    }
    let (cfg, cfg_dir) = read_config(a.config.as_deref())?;
    let pick = |flag: &Option<String>, file: &Option<String>| flag.clone().or(file.clone());
    let spec = build_spec(&a, &cfg, pick)?;
    let out = match (&a.set.out, &cfg.out) {
        (Some(o), _) => o.clone(),
        (None, Some(o)) => cfg_dir.join(o),
        (None, None) => bail!("give the output file with --out FILE (or `out` in the TOML file)"),
    };
    let max_error = a.set.max_error.or(cfg.max_error);
    if let Some(e) = max_error {
        if !(e.is_finite() && e > 0.0) {
            bail!("--max-error must be a positive number (got {e})");
        }
    }
    let inputs: Vec<&Path> = a.config.iter().map(PathBuf::as_path).collect();
    let policy = crate::fsio::Policy::new(a.set.force, &inputs);
    crate::fsio::check(&[&out], &policy)?;
    spec.validate().map_err(|e| anyhow!("{e}"))?;
    check_limits(&spec)?;
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
    check_max_error(&spec, e.max_abs, max_error)?;
    crate::fsio::write_together(&[(out.clone(), t.bytes)], &policy)?;
    println!("wrote {summary}");
    Ok(())
}

/// The TOML file (size-capped, UTF-8) and the folder its relative `out` is taken from; the
/// defaults without a file.
fn read_config(path: Option<&Path>) -> Result<(Config, PathBuf)> {
    let Some(p) = path else {
        return Ok((Config::default(), PathBuf::new()));
    };
    let bytes = crate::fsio::read_limited(p, MAX_CONFIG_BYTES)?;
    let text = String::from_utf8(bytes).map_err(|_| anyhow!("{}: not UTF-8 text", p.display()))?;
    let c: Config = toml::from_str(&text).map_err(|e| anyhow!("{}: {e}", p.display()))?;
    Ok((c, p.parent().map(Path::to_path_buf).unwrap_or_default()))
}

/// Fails (nothing written) when the measured max |error| `max_abs` exceeds `--max-error`,
/// with a hint fitting the spec's interpolation.
fn check_max_error(spec: &Spec, max_abs: f32, max_error: Option<f64>) -> Result<()> {
    let Some(lim) = max_error else { return Ok(()) };
    if max_abs.is_nan() || max_abs as f64 > lim {
        let hint = match spec.interpolation {
            Interpolation::Linear => "more nodes per axis, another warp or catmull-rom",
            Interpolation::CatmullRom => "more nodes per axis or another warp",
        };
        bail!(
            "measured max |error| {max_abs:.3e} exceeds --max-error {lim:.3e}; nothing written \
             ({hint} lower it)"
        );
    }
    Ok(())
}

/// Every number of `spec` that sizes memory or time, against the tool's limits
/// (`brdf_lut::limits`), before anything is allocated or computed.
fn check_limits(spec: &Spec) -> Result<()> {
    limits::check_samples("--samples", spec.samples as u64)?;
    let counts: Vec<u64> = spec.axes.iter().map(|x| x.count as u64).collect();
    let channels = spec.kind.def().channels.len() as u64;
    let nodes = limits::check_grid(&counts, channels)?;
    let kind = spec.kind.def().table;
    let model = spec.model().map_err(|e| anyhow!("{e}"))?;
    limits::check_generate(kind, model, nodes, spec.samples as u64)?;
    Ok(())
}

fn choose<T: Copy>(what: &str, v: &str, options: &[(&str, T)]) -> Result<T> {
    options
        .iter()
        .find(|(n, _)| *n == v)
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
            anyhow!("unknown {what} `{v}` (one of: {})", names.join(", "))
        })
}

fn warp(v: &str) -> Result<Warp> {
    choose(
        "warp",
        v,
        &[
            ("linear", Warp::Linear),
            ("log", Warp::Log),
            ("sqrt", Warp::Sqrt),
            ("cos", Warp::Cos),
            ("sqrt-cos", Warp::SqrtCos),
        ],
    )
}

fn placement(v: &str) -> Result<Placement> {
    choose(
        "placement",
        v,
        &[
            ("endpoint", Placement::Endpoint),
            ("texel-centre", Placement::TexelCentre),
            ("texel-center", Placement::TexelCentre),
        ],
    )
}

/// The table's kind, distribution and masking from the flags and the TOML file (`pick`:
/// the flag if given, else the file's value), with their defaults.
fn kind_and_model(
    a: &Args,
    cfg: &Config,
    pick: &impl Fn(&Option<String>, &Option<String>) -> Option<String>,
) -> Result<(String, Spec)> {
    let kind_s = pick(&a.kind, &cfg.kind).unwrap_or_default();
    let sigma = a.sigma.or(cfg.sigma);
    let kind = match kind_s.as_str() {
        "g-per-sigma" => Kind::GPerSigma {
            sigma: sigma.ok_or_else(|| anyhow!("a g-per-sigma table needs --sigma S"))?,
        },
        "g-over-sigma" => Kind::GOverSigma,
        "split-sum" => Kind::SplitSum,
        "e" => Kind::Albedo,
        "e-avg" => Kind::AverageAlbedo,
        // The sheen albedo; its visibility in the kind's name (the model's only option).
        "sheen-e" | "sheen-e-estevez-kulla" => Kind::SheenAlbedo {
            visibility: brdf_lut::generate::SheenVisibility::EstevezKulla,
        },
        "sheen-e-ashikhmin" => Kind::SheenAlbedo {
            visibility: brdf_lut::generate::SheenVisibility::Ashikhmin,
        },
        "glass-e" => Kind::GlassAlbedo,
        "glass-e-avg" => Kind::GlassAverageAlbedo,
        "" => bail!("--kind is missing (g-per-sigma, g-over-sigma, split-sum, e, e-avg, sheen-e, sheen-e-ashikhmin, glass-e, glass-e-avg)"),
        o => bail!("unknown kind `{o}` (one of: g-per-sigma, g-over-sigma, split-sum, e, e-avg, sheen-e, sheen-e-ashikhmin, glass-e, glass-e-avg)"),
    };
    let sheen = matches!(kind, Kind::SheenAlbedo { .. });
    if sigma.is_some() && !matches!(kind, Kind::GPerSigma { .. }) {
        bail!("--sigma is the fixed σ of a g-per-sigma table; other kinds take a σ axis");
    }
    let g_table = matches!(kind, Kind::GPerSigma { .. } | Kind::GOverSigma);
    let dist = match pick(&a.model, &cfg.model) {
        Some(m) => choose("model", &m, &distribution_options())?,
        None if g_table => Distribution::TorranceSparrow,
        // (A sheen table's distribution is Charlie; the option does not apply.)
        None if sheen => Distribution::Ggx,
        None => bail!("--model is missing (ggx, beckmann, torrance-sparrow)"),
    };
    let masking = match pick(&a.masking, &cfg.masking) {
        Some(m) => choose("masking", &m, &Masking::options())?,
        None if dist == Distribution::TorranceSparrow => Masking::Modified,
        None => Masking::SmithCorrelated,
    };
    Ok((kind_s, Spec::new(kind, dist, masking)))
}

/// The spec of a table built to order: the TOML file's options, overridden by the flags.
fn build_spec(
    a: &Args,
    cfg: &Config,
    pick: impl Fn(&Option<String>, &Option<String>) -> Option<String>,
) -> Result<Spec> {
    let (kind_s, mut spec) = kind_and_model(a, cfg, &pick)?;
    if let Some(r) = pick(&a.roughness, &cfg.roughness) {
        spec.roughness = choose("roughness", &r, &Roughness::ALL.map(|r| (r.name(), r)))?;
        spec.axes = spec.default_axes();
    }
    apply_axes(a, cfg, &kind_s, &mut spec)?;
    if let Some(e) = pick(&a.set.encoding, &cfg.encoding) {
        spec.encoding = choose(
            "encoding",
            &e,
            &[
                ("u16", Encoding::Unorm16),
                ("f16", Encoding::F16),
                ("f32", Encoding::F32),
            ],
        )?;
    }
    if let Some(i) = pick(&a.interpolation, &cfg.interpolation) {
        spec.interpolation = choose(
            "interpolation",
            &i,
            &[
                ("linear", Interpolation::Linear),
                ("catmull-rom", Interpolation::CatmullRom),
            ],
        )?;
    }
    if let Some(n) = a.samples.or(cfg.samples) {
        spec.samples = n;
    }
    if let Some(s) = a.seed.or(cfg.seed) {
        spec.seed = s;
    }
    Ok(spec)
}

/// The axes' options: the TOML file's `[axes.NAME]` tables, then `--res`, `--range`,
/// `--warp` and `--placement` (a `kind_s` table's axes are named in the errors).
fn apply_axes(a: &Args, cfg: &Config, kind_s: &str, spec: &mut Spec) -> Result<()> {
    let names = spec.axis_names();
    let axis_index = |name: &str| -> Result<usize> {
        names.iter().position(|n| *n == name).ok_or_else(|| {
            anyhow!(
                "no axis `{name}`: this {kind_s} table's axes are {}",
                names.join(", ")
            )
        })
    };
    // The TOML file's axes first, then the flags.
    for (name, ac) in &cfg.axes {
        let x = &mut spec.axes[axis_index(name)?];
        x.count = ac.count.unwrap_or(x.count);
        x.lo = ac.lo.unwrap_or(x.lo);
        x.hi = ac.hi.unwrap_or(x.hi);
        if let Some(w) = &ac.warp {
            x.warp = warp(w).with_context(|| format!("axis {name}"))?;
        }
        if let Some(p) = &ac.placement {
            x.placement = placement(p).with_context(|| format!("axis {name}"))?;
        }
    }
    if let Some(res) = a.set.res.as_ref().or(cfg.res.as_ref()) {
        let counts: Vec<u32> = res
            .split('x')
            .map(|t| res_count(res, t))
            .collect::<Result<_>>()?;
        if counts.len() != names.len() {
            bail!(
                "--res `{res}` gives {} size(s); a {kind_s} table has {} axes ({}), e.g. {}",
                counts.len(),
                names.len(),
                names.join(", "),
                vec!["64"; names.len()].join("x")
            );
        }
        for (x, c) in spec.axes.iter_mut().zip(counts) {
            x.count = c;
        }
    }
    for r in &a.ranges {
        let bad = || anyhow!("--range `{r}` is not AXIS=LO:HI");
        let (name, v) = r.split_once('=').ok_or_else(bad)?;
        let (lo, hi) = v.split_once(':').ok_or_else(bad)?;
        let num = |t: &str| -> Result<f64> {
            t.trim()
                .parse()
                .map_err(|_| anyhow!("--range `{r}`: `{t}` is not a number"))
        };
        let i = axis_index(name.trim())?;
        spec.axes[i].lo = num(lo)?;
        spec.axes[i].hi = num(hi)?;
    }
    for w in &a.warps {
        match w.split_once('=') {
            Some((name, v)) => spec.axes[axis_index(name.trim())?].warp = warp(v.trim())?,
            None => {
                let v = warp(w.trim())?;
                spec.axes.iter_mut().for_each(|x| x.warp = v);
            }
        }
    }
    for p in &a.placements {
        match p.split_once('=') {
            Some((name, v)) => spec.axes[axis_index(name.trim())?].placement = placement(v.trim())?,
            None => {
                let v = placement(p.trim())?;
                spec.axes.iter_mut().for_each(|x| x.placement = v);
            }
        }
    }
    Ok(())
}

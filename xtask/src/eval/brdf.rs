//! `cargo xtask eval brdf`: rows `wi_x,wi_y,wi_z,wo_x,wo_y,wo_z` (local frame, z = normal,
//! wi toward the light, wo toward the viewer; normalised on input) in, the same columns plus
//! `r,g,b` out, from the f64 models of `brdf_core::models`, named and configured by the
//! model catalogue `brdf_core::catalogue` (old spellings such as `shirley` and `coupled` are
//! accepted). `--list` prints every model with its parameters, units, ranges and defaults. A Dirac part (mirror) is not in r,g,b: the
//! columns are the model's `eval`, i.e. f in 1/sr (the standard lighting model gives its lit
//! colour, see `--list`). Directions below the surface (z < 0) are accepted: a BRDF gives 0
//! there, the BSDF `rough-dielectric` its transmitted part when wi and wo lie on opposite
//! sides (radiance convention, with the η_o² factor; docs/conventions.md §12) and its internal
//! reflection when both lie below.

use anyhow::{anyhow, bail, Context, Result};
use brdf_core::catalogue::{self, ModelSpec, ParamKind, ParamSpec, MODELS};
use brdf_core::models::Brdf;
use brdf_core::Vec3;
use std::collections::BTreeMap;
use std::io::Write;

#[derive(clap::Args)]
pub struct Args {
    /// Model name (see `--list`).
    #[arg(long)]
    model: Option<String>,
    /// A model parameter as key=value (repeatable). Colours take one value or r,g,b.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    params: Vec<String>,
    /// Print every model with its parameters and exit.
    #[arg(long)]
    list: bool,
}

/// The output header.
pub const HEADER: &str = "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,r,g,b";

/// The parameters given on the command line, checked against a model's catalogue entry and
/// laid out as its flat array (defaults for those not given).
fn flat_params(spec: &'static ModelSpec, raw: &[String]) -> Result<Vec<f64>> {
    let mut flat: Vec<f64> = spec.defaults::<f64>()[..spec.slots()].to_vec();
    let mut seen = BTreeMap::new();
    for r in raw {
        let (k, v) = r
            .split_once('=')
            .ok_or_else(|| anyhow!("--param `{r}`: expected KEY=VALUE"))?;
        let (k, v) = (k.trim(), v.trim());
        let Some((at, p)) = spec.param_by_name(k) else {
            let keys: Vec<&str> = spec.params.iter().map(|p| p.name).collect();
            bail!(
                "model `{}` has no parameter `{k}` (parameters: {})",
                spec.name,
                keys.join(", ")
            );
        };
        if seen.insert(k.to_string(), ()).is_some() {
            bail!("--param `{k}` given twice");
        }
        let number = |s: &str| -> Result<f64> {
            s.trim()
                .parse::<f64>()
                .map_err(|_| anyhow!("parameter `{k}`: `{v}` is not a number"))
        };
        match p.kind {
            ParamKind::Scalar => flat[at] = number(v)?,
            ParamKind::Rgb(_) => {
                let parts: Vec<&str> = v.split(',').collect();
                match parts.as_slice() {
                    [x] => flat[at..at + 3].fill(number(x)?),
                    [r, g, b] => {
                        flat[at] = number(r)?;
                        flat[at + 1] = number(g)?;
                        flat[at + 2] = number(b)?;
                    }
                    _ => bail!("parameter `{k}`: `{v}` needs 1 or 3 values"),
                }
            }
            ParamKind::Choice(options) => {
                let i = options.iter().position(|o| *o == v).ok_or_else(|| {
                    anyhow!(
                        "parameter `{k}`: `{v}` is not one of {}",
                        options.join(" | ")
                    )
                })?;
                flat[at] = i as f64;
            }
        }
    }
    Ok(flat)
}

/// Builds a model by catalogue name (or an old spelling) with `key=value` parameters.
pub fn build(name: &str, raw: &[String]) -> Result<Box<dyn Brdf<f64>>> {
    let spec = catalogue::find(name).ok_or_else(|| {
        let names: Vec<&str> = MODELS.iter().map(|m| m.name).collect();
        anyhow!("unknown model `{name}` (models: {})", names.join(", "))
    })?;
    let flat = flat_params(spec, raw)?;
    let m = spec
        .build::<f64>(&flat)
        .map_err(|e| anyhow!("{e}"))
        .with_context(|| format!("model `{name}`"))?;
    Ok(Box::new(m))
}

fn default_text(p: &ParamSpec) -> String {
    match p.kind {
        ParamKind::Scalar => format!("{}", p.default[0]),
        ParamKind::Rgb(_) if p.default[0] == p.default[1] && p.default[1] == p.default[2] => {
            format!("{}", p.default[0])
        }
        ParamKind::Rgb(_) => format!("{},{},{}", p.default[0], p.default[1], p.default[2]),
        ParamKind::Choice(o) => o[p.default[0] as usize].to_string(),
    }
}

fn print_list(out: &mut impl Write) -> Result<()> {
    for m in MODELS {
        writeln!(out, "{}\n    {}", m.name, m.about())?;
        if !m.aliases.is_empty() {
            writeln!(out, "    also accepted as: {}", m.aliases.join(", "))?;
        }
        for p in m.params {
            let range = match p.kind {
                ParamKind::Rgb(_) => format!("{} per channel (v or r,g,b)", p.range()),
                _ => p.range().to_string(),
            };
            writeln!(
                out,
                "    --param {}=…  unit {}; range {}; default {}; {}",
                p.name,
                p.unit(),
                range,
                default_text(p),
                p.help()
            )?;
        }
    }
    Ok(())
}

/// One parsed row: the six fields as typed, and the normalised wi and wo.
type Row<'a> = ([&'a str; 6], Vec3<f64>, Vec3<f64>);

/// The input columns.
const COLUMNS: [&str; 6] = ["wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z"];

/// Parses one row's six fields (read by `super::for_each_row`).
fn parse_row<'a>(f: &[&'a str], lineno: usize) -> Result<Option<Row<'a>>> {
    let mut v = [0.0; 6];
    for (i, s) in f.iter().enumerate() {
        let x: f64 = s
            .parse()
            .map_err(|_| anyhow!("line {lineno}: field {} `{s}` is not a number", i + 1))?;
        if !x.is_finite() {
            bail!("line {lineno}: field {} is not finite", i + 1);
        }
        v[i] = x;
    }
    let wi = Vec3::new(v[0], v[1], v[2])
        .normalize()
        .ok_or_else(|| anyhow!("line {lineno}: wi is a zero vector"))?;
    let wo = Vec3::new(v[3], v[4], v[5])
        .normalize()
        .ok_or_else(|| anyhow!("line {lineno}: wo is a zero vector"))?;
    Ok(Some(([f[0], f[1], f[2], f[3], f[4], f[5]], wi, wo)))
}

pub fn run(a: Args) -> Result<()> {
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if a.list {
        print_list(&mut out)?;
        out.flush()?;
        return Ok(());
    }
    let name = a
        .model
        .ok_or_else(|| anyhow!("--model NAME is required (see --list)"))?;
    let model = build(&name, &a.params)?;
    writeln!(out, "{HEADER}")?;
    super::for_each_row(std::io::stdin().lock(), &COLUMNS, |lineno, f| {
        let Some((fields, wi, wo)) = parse_row(f, lineno)? else {
            return Ok(());
        };
        let c = model.eval(wi, wo);
        writeln!(
            out,
            "{},{:.16e},{:.16e},{:.16e}",
            fields.join(","),
            c.r,
            c.g,
            c.b
        )?;
        Ok(())
    })?;
    out.flush()?;
    Ok(())
}

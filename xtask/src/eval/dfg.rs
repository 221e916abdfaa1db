//! `cargo xtask eval dfg`: rows `mu,roughness` in, `mu,roughness,A,B` out: the split sum for
//! GGX with height-correlated Smith (conventions.md §8), looked up in the default table
//! `assets/dfg_ggx.blut` (f32, as a shader would) or, with `--direct`, integrated by the
//! f64 kernel `brdf_core::split_sum::dfg_ggx` (17 significant digits).

use anyhow::{bail, Context, Result};
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use std::io::{BufRead, Write};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Integrate with the direct kernel instead of reading the table.
    #[arg(long)]
    direct: bool,
    /// The table to read (default: assets/dfg_ggx.blut).
    #[arg(long)]
    lut: Option<PathBuf>,
}

/// The output header.
pub const HEADER: &str = "mu,roughness,A,B";

/// Parses `mu,roughness`; `Ok(None)` for a header or blank line. μ ∈ [0, 1], r ∈ [0, 1].
pub fn parse_row(line: &str, lineno: usize) -> Result<Option<([&str; 2], f64, f64)>> {
    let t = line.trim();
    if t.is_empty() || (lineno == 1 && t.starts_with("mu")) {
        return Ok(None);
    }
    let f: Vec<&str> = t.split(',').map(str::trim).collect();
    if f.len() != 2 {
        bail!(
            "line {lineno}: expected 2 fields mu,roughness, found {}",
            f.len()
        );
    }
    let num = |i: usize, name: &str| -> Result<f64> {
        let v: f64 = f[i]
            .parse()
            .with_context(|| format!("line {lineno}: {name} `{}` is not a number", f[i]))?;
        if !(0.0..=1.0).contains(&v) {
            bail!("line {lineno}: {name} {v} outside [0, 1]");
        }
        Ok(v)
    };
    Ok(Some(([f[0], f[1]], num(0, "mu")?, num(1, "roughness")?)))
}

pub fn run(a: Args) -> Result<()> {
    let bytes;
    let table = if a.direct {
        None
    } else {
        let p = a
            .lut
            .clone()
            .unwrap_or_else(|| crate::lut::assets_dir().join("dfg_ggx.blut"));
        bytes = brdf_lut::read_capped(&p).with_context(|| format!("reading {}", p.display()))?;
        Some(
            brdf_lut::DfgTable::parse(&bytes)
                .map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?,
        )
    };
    let stdin = std::io::stdin();
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    writeln!(out, "{HEADER}")?;
    for (i, line) in stdin.lock().lines().enumerate() {
        let line = line.with_context(|| format!("line {}: unreadable input", i + 1))?;
        let Some((fields, mu, r)) = parse_row(&line, i + 1)? else {
            continue;
        };
        let (av, bv) = match &table {
            Some(t) => {
                let (x, y) = t.ab(mu as f32, r as f32);
                (x as f64, y as f64)
            }
            None => dfg_ggx::<f64, OuterRule, InnerRule>(mu, r),
        };
        writeln!(out, "{},{},{:.16e},{:.16e}", fields[0], fields[1], av, bv)?;
    }
    out.flush()?;
    Ok(())
}

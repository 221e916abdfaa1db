//! `cargo xtask eval g`: rows `theta_i_deg,theta_r_deg,sigma` in, the modified G with Blinn's
//! and Smith's G out, computed with the f64 kernels and printed to 17 significant digits.

use anyhow::{bail, Context, Result};
use brdf_core::masking::{g_blinn, Convention, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic};
use brdf_core::quadrature::{GaussLegendre, Rule, DEFAULT_NODES, NODE_COUNTS};
use std::io::Write;

#[derive(clap::Args)]
pub struct Args {
    /// `reciprocal` (default) or `printed` (eq 12 as printed).
    #[arg(long, default_value = "reciprocal")]
    convention: String,
    /// Gauss–Legendre node count per integral, one of those compiled in.
    #[arg(long, default_value_t = DEFAULT_NODES)]
    nodes: usize,
    /// Answer GM, GS and G from a G table instead of the kernel (f32 lookups; the Blinn and
    /// Smith columns stay direct). Default table: assets/g_modified.blut (σ ∈ [0.05, 1]); a
    /// row with σ outside the table's range is an error (the table would clamp σ).
    #[arg(long)]
    lut: bool,
    /// The G table for `--lut` (a 3-D table, or a per-σ table whose σ every row must match).
    #[arg(long, requires = "lut")]
    lut_file: Option<std::path::PathBuf>,
}

/// The output header.
pub const HEADER: &str =
    "theta_i_deg,theta_r_deg,sigma,GM,GS,G,G_blinn,G_smith_separable,G_smith_correlated";

/// Formats to 17 significant digits (round-trips every f64).
pub fn fmt17(x: f64) -> String {
    format!("{x:.16e}")
}

/// One parsed input row: the three fields as typed and their values.
pub struct Row<'a> {
    pub fields: [&'a str; 3],
    pub ti_deg: f64,
    pub tr_deg: f64,
    pub sigma: f64,
}

/// The input columns.
pub const COLUMNS: [&str; 3] = ["theta_i_deg", "theta_r_deg", "sigma"];

/// Checks a row's fields: θi ∈ [0, 90]°, θr ∈ [−90, 90]°, σ > 0.
pub fn parse_row<'a>(f: &[&'a str], lineno: usize) -> Result<Row<'a>> {
    let num = |i: usize| super::number(f, i, COLUMNS[i], lineno);
    let (ti, tr, s) = (num(0)?, num(1)?, num(2)?);
    if !(0.0..=90.0).contains(&ti) {
        bail!("line {lineno}: theta_i_deg {ti} outside [0, 90]");
    }
    if !(-90.0..=90.0).contains(&tr) {
        bail!("line {lineno}: theta_r_deg {tr} outside [-90, 90]");
    }
    if s <= 0.0 {
        bail!("line {lineno}: sigma {s} must be > 0");
    }
    Ok(Row {
        fields: [f[0], f[1], f[2]],
        ti_deg: ti,
        tr_deg: tr,
        sigma: s,
    })
}

/// The direct-kernel columns GM, GS, G, G_blinn, G_smith_separable, G_smith_correlated.
pub fn direct_columns<R: Rule>(row: &Row<'_>, conv: Convention) -> Result<[f64; 6]> {
    let (ti, tr) = (row.ti_deg.to_radians(), row.tr_deg.to_radians());
    let g = ModifiedG::<f64, R>::new(row.sigma)
        .map_err(|e| anyhow::anyhow!("{e}"))?
        .with_convention(conv);
    let t = g.terms(ti, tr);
    let m = brdf_core::roughness::beckmann_m_from_sigma(row.sigma);
    let (ci, co) = (ti.cos(), tr.cos());
    Ok([
        t.gm,
        t.gs,
        t.g,
        g_blinn(ti, tr),
        Beckmann::g_separable_cos(ci, co, m),
        Beckmann::g_correlated_cos(ci, co, m),
    ])
}

/// Parses `--convention`.
pub fn parse_convention(s: &str) -> Result<Convention> {
    match s {
        "reciprocal" => Ok(Convention::Reciprocal),
        "printed" => Ok(Convention::Printed),
        other => bail!("unknown convention `{other}` (expected reciprocal or printed)"),
    }
}

/// The command's output: the header, then for each input row its fields and the six
/// columns `columns(row, lineno)` gives, to 17 significant digits.
fn write_rows(mut columns: impl FnMut(&Row<'_>, usize) -> Result<[f64; 6]>) -> Result<()> {
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    writeln!(out, "{HEADER}")?;
    super::for_each_row(std::io::stdin().lock(), &COLUMNS, |lineno, f| {
        let row = parse_row(f, lineno)?;
        let cols: Vec<String> = columns(&row, lineno)?.iter().map(|&x| fmt17(x)).collect();
        writeln!(out, "{},{}", row.fields.join(","), cols.join(","))?;
        Ok(())
    })?;
    out.flush()?;
    Ok(())
}

fn run_with<R: Rule>(conv: Convention) -> Result<()> {
    write_rows(|row, lineno| {
        direct_columns::<R>(row, conv).with_context(|| format!("line {lineno}"))
    })
}

/// `--lut`: the direct columns with GM, GS, G replaced by the table's. A 3-D table answers
/// σ inside its σ axis only: a row outside is an error naming the line and the range (the
/// lookup would clamp σ and answer for another surface); a per-σ table needs its own σ.
fn run_lut(path: &std::path::Path, conv: Convention) -> Result<()> {
    if conv != Convention::Reciprocal {
        bail!("--lut tables hold the reciprocal convention only");
    }
    let lut = crate::fsio::load_lut(path)?;
    let h = lut.header();
    let sigma_axis = h.axes.get(2).map(|a| (a.lo, a.hi));
    write_rows(|row, lineno| {
        if let Some((lo, hi)) = sigma_axis {
            let s = row.sigma as f32;
            if s < lo as f32 || s > hi as f32 {
                bail!(
                    "line {lineno}: sigma {} is outside the table's range [{lo}, {hi}] \
                     ({}); leave out --lut for the direct kernel",
                    row.sigma,
                    path.display()
                );
            }
        }
        let mut cols = direct_columns::<GaussLegendre<4>>(row, conv)
            .with_context(|| format!("line {lineno}"))?;
        let (gm, gs, g) = lut
            .g_terms(
                row.ti_deg.to_radians() as f32,
                row.tr_deg.to_radians() as f32,
                row.sigma as f32,
            )
            .map_err(|e| anyhow::anyhow!("line {lineno}: {e}"))?;
        cols[0] = gm as f64;
        cols[1] = gs as f64;
        cols[2] = g as f64;
        Ok(cols)
    })
}

pub fn run(a: Args) -> Result<()> {
    let conv = parse_convention(&a.convention)?;
    if a.lut {
        let p = a
            .lut_file
            .clone()
            .unwrap_or_else(|| crate::fsio::assets_dir().join("g_modified.blut"));
        return run_lut(&p, conv);
    }
    match a.nodes {
        4 => run_with::<GaussLegendre<4>>(conv),
        6 => run_with::<GaussLegendre<6>>(conv),
        8 => run_with::<GaussLegendre<8>>(conv),
        10 => run_with::<GaussLegendre<10>>(conv),
        12 => run_with::<GaussLegendre<12>>(conv),
        16 => run_with::<GaussLegendre<16>>(conv),
        20 => run_with::<GaussLegendre<20>>(conv),
        24 => run_with::<GaussLegendre<24>>(conv),
        32 => run_with::<GaussLegendre<32>>(conv),
        n => bail!("--nodes {n} is not compiled in; choose one of {NODE_COUNTS:?}"),
    }
}

//! `cargo xtask eval dfg`: rows `mu,roughness` in, `mu,roughness,A,B` out: the split sum for
//! GGX with height-correlated Smith (docs/conventions.md §8), looked up in the default table
//! `assets/dfg_ggx.blut` (f32, as a shader would) or, with `--direct`, integrated by the
//! f64 kernel `brdf_core::split_sum::dfg_ggx` (17 significant digits).
//!
//! The table covers μ ≥ cos 89° ≈ 0.01745 only (the accuracy target's domain): below that it
//! answers with its value at its smallest μ, while `--direct` integrates at the given μ, so
//! the two differ there. The command warns on stderr when any row was clamped.

use anyhow::{bail, Result};
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use std::io::Write;
use std::path::PathBuf;

#[derive(clap::Args)]
#[command(
    after_help = "Grazing angles: the default table covers mu >= cos 89 deg = 0.0174524. \
Rows below (or outside any table's axis ranges) are answered at the table's edge (clamped) and \
a warning says how many; --direct integrates at the given mu instead."
)]
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

/// The input columns.
const COLUMNS: [&str; 2] = ["mu", "roughness"];

/// Checks a row's `mu,roughness` values: μ ∈ [0, 1], r ∈ [0, 1].
fn values(f: &[&str], lineno: usize) -> Result<(f64, f64)> {
    let num = |i: usize| -> Result<f64> {
        let v = super::number(f, i, COLUMNS[i], lineno)?;
        if !(0.0..=1.0).contains(&v) {
            bail!("line {lineno}: {} {v} outside [0, 1]", COLUMNS[i]);
        }
        Ok(v)
    };
    Ok((num(0)?, num(1)?))
}

pub fn run(a: Args) -> Result<()> {
    let bytes;
    let table = if a.direct {
        None
    } else {
        let p = a
            .lut
            .clone()
            .unwrap_or_else(|| crate::fsio::assets_dir().join("dfg_ggx.blut"));
        bytes = crate::fsio::read_limited(&p, brdf_lut::MAX_FILE_BYTES)?;
        Some(
            brdf_lut::DfgTable::parse(&bytes)
                .map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?,
        )
    };
    // The table's axis ranges (μ, roughness): rows outside are clamped by the lookup.
    let ranges = match &table {
        Some(t) => {
            let v = t.view().map_err(|e| anyhow::anyhow!("{e}"))?;
            let ax = &v.header().axes;
            Some([(ax[0].lo, ax[0].hi), (ax[1].lo, ax[1].hi)])
        }
        None => None,
    };
    let (mut clamped, mut first) = (0usize, 0usize);
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    writeln!(out, "{HEADER}")?;
    super::for_each_row(std::io::stdin().lock(), &COLUMNS, |lineno, f| {
        let (mu, r) = values(f, lineno)?;
        if let Some([m, g]) = ranges {
            let outside =
                |x: f64, (lo, hi): (f64, f64)| (x as f32) < lo as f32 || (x as f32) > hi as f32;
            if outside(mu, m) || outside(r, g) {
                clamped += 1;
                if first == 0 {
                    first = lineno;
                }
            }
        }
        let (av, bv) = match &table {
            Some(t) => {
                let (x, y) = t.ab(mu as f32, r as f32);
                (x as f64, y as f64)
            }
            None => dfg_ggx::<f64, OuterRule, InnerRule>(mu, r),
        };
        writeln!(out, "{},{},{:.16e},{:.16e}", f[0], f[1], av, bv)?;
        Ok(())
    })?;
    out.flush()?;
    if let (Some([m, g]), true) = (ranges, clamped > 0) {
        eprintln!(
            "warning: {clamped} row(s) (the first on line {first}) lie outside the table \
             (mu in [{}, {}], roughness in [{}, {}]); the table answered them at its edge \
             (clamped), --direct integrates there instead",
            m.0, m.1, g.0, g.1
        );
    }
    Ok(())
}

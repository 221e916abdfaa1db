//! Host recomputation of every value the firmware printed (the firmware's own `kernels.rs`,
//! compiled for the host) and the comparison: bit for bit with libm, within a per-kernel
//! relative tolerance with micromath.

use super::runner::{Res, TableRef};
use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// The firmware's kernels, compiled for the host: the very source the device runs.
#[path = "../../../crates/brdf-firmware/src/kernels.rs"]
#[allow(dead_code)]
mod fw_kernels;

/// Largest relative difference accepted between the micromath firmware and the host's libm
/// `f32`, per kernel: |fw − host| ≤ tol · max(|host|, 1e-3). Set a little above the largest
/// difference measured at the firmware's inputs (see `micromath_tol`'s comments).
pub(crate) fn micromath_tol(kernel: &str) -> f64 {
    match kernel {
        // The micromath build computes in `brdf_core::real::Micro`: micromath's exp (and ln,
        // atan, …), libm's sqrt and powf. Measured at the firmware's inputs, about 2× below:
        // Modified G: measured at most 5.2e-5 (direct, σ = 1) and 2.6e-4 (dots, σ = 0.3,
        // grazing backscatter), all from micromath's exp.
        "g_direct" => 1e-4,
        "g_dots" => 5e-4,
        // Torrance–Sparrow (Beckmann D and the modified G through exp): measured at most
        // 2.5e-4 (σ = 0.3, grazing backscatter).
        "ts" => 5e-4,
        // The LUT lookup and Ashikhmin–Shirley (powf, sqrt) use no micromath function:
        // bit-identical to the libm build.
        _ => 0.0,
    }
}

pub(crate) struct Row {
    pub(crate) kernel: String,
    pub(crate) label: String,
    pub(crate) fw: f32,
    pub(crate) host: f32,
    /// |fw − host| in units in the last place of the host value.
    pub(crate) ulps: u64,
    pub(crate) rel: f64,
    pub(crate) pass: bool,
}

/// The host's copy of the embedded G table (the same file from `assets/`).
pub(crate) struct HostTables {
    pub(crate) g: Option<(String, Vec<u8>)>,
}

impl HostTables {
    /// Loads every table the firmware named and checks its length and stored CRC-32.
    pub(crate) fn load(root: &Path, refs: &[TableRef]) -> Result<Self> {
        let mut g = None;
        for r in refs {
            if r.file.contains('/') || r.file.contains("..") {
                bail!("table name {:?} must be a plain file name", r.file);
            }
            let path = root.join("assets").join(&r.file);
            let bytes =
                std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
            let t = brdf_lut::GTable::parse(&bytes)
                .map_err(|e| anyhow::anyhow!("{}: {e:?}", path.display()))?;
            let crc = t.view().map_or(0, |v| v.header().checksum);
            if bytes.len() != r.len || crc != r.crc {
                bail!(
                    "{}: host file has {} bytes, CRC {crc:08x}; firmware embeds {} bytes, CRC {:08x}",
                    r.file,
                    bytes.len(),
                    r.len,
                    r.crc
                );
            }
            g = Some((r.file.clone(), bytes));
        }
        Ok(Self { g })
    }
}

pub(crate) fn host_value(tables: &HostTables, kernel: &str, a: &[f32]) -> Result<f32> {
    let want = |n: usize| -> Result<()> {
        if a.len() != n {
            bail!("kernel {kernel} takes {n} arguments, got {}", a.len());
        }
        Ok(())
    };
    Ok(match kernel {
        "g_direct" => {
            want(3)?;
            fw_kernels::g_direct(a[0], a[1], a[2])
        }
        "g_lut" => {
            want(3)?;
            let (file, bytes) = tables
                .g
                .as_ref()
                .context("g_lut results without a TABLE line")?;
            let t = fw_kernels::g_table(bytes)
                .with_context(|| format!("{file} does not parse on the host"))?;
            if t.sigma() != a[0] {
                bail!(
                    "{file} has σ = {}, the firmware printed σ = {}",
                    t.sigma(),
                    a[0]
                );
            }
            fw_kernels::g_lut(&t, a[1], a[2])
        }
        "g_dots" => {
            want(4)?;
            fw_kernels::g_dots(a[0], a[1], a[2], a[3])
        }
        "ts" => {
            want(6)?;
            fw_kernels::torrance_sparrow(a[0], a[1], a[2], a[3], a[4], a[5])
        }
        "ashikhmin_shirley" => {
            want(10)?;
            fw_kernels::ashikhmin_shirley(
                a[0],
                a[1],
                a[2],
                a[3],
                [a[4], a[5], a[6]],
                [a[7], a[8], a[9]],
            )
        }
        other => bail!("the host does not know firmware kernel {other:?}"),
    })
}

/// Distance in representable f32 values (0 for identical bits; both must be finite).
pub(crate) fn ulp_distance(a: f32, b: f32) -> u64 {
    fn key(x: f32) -> i64 {
        let b = x.to_bits() as i32;
        (if b < 0 { i32::MIN - b } else { b }) as i64
    }
    (key(a) - key(b)).unsigned_abs()
}

pub(crate) fn compare(results: &[Res], tables: &HostTables, micromath: bool) -> Result<Vec<Row>> {
    let mut rows = Vec::with_capacity(results.len());
    for r in results {
        let host = host_value(tables, &r.kernel, &r.args)?;
        let fw = r.value;
        let (ulps, rel) = if fw.is_finite() && host.is_finite() {
            let d = (fw as f64 - host as f64).abs();
            (ulp_distance(fw, host), d / (host.abs() as f64).max(1e-3))
        } else {
            (u64::MAX, f64::INFINITY)
        };
        let bit_exact = fw.to_bits() == host.to_bits() || (fw.is_nan() && host.is_nan());
        let pass = if micromath {
            bit_exact || rel <= micromath_tol(&r.kernel)
        } else {
            bit_exact
        };
        let args: Vec<String> = r.args.iter().map(|x| format!("{x}")).collect();
        rows.push(Row {
            kernel: r.kernel.clone(),
            label: format!("{}({})", r.kernel, args.join(", ")),
            fw,
            host,
            ulps: if bit_exact { 0 } else { ulps },
            rel: if bit_exact { 0.0 } else { rel },
            pass,
        });
    }
    Ok(rows)
}

pub(crate) fn print_comparison(rows: &[Row], verbose: bool, micromath: bool) {
    if verbose {
        println!(
            "{:<64} {:>21} {:>21} {:>10} {:>8}",
            "value", "firmware", "host (f32, libm)", "rel diff", "ulps"
        );
        for r in rows {
            println!(
                "{:<64} {:08x} {:<12} {:08x} {:<12} {:>10.2e} {:>8}{}",
                r.label,
                r.fw.to_bits(),
                r.fw,
                r.host.to_bits(),
                r.host,
                r.rel,
                r.ulps,
                if r.pass { "" } else { "  MISMATCH" }
            );
        }
    }
    // Summary per kernel.
    let mut per: BTreeMap<&str, (usize, usize, u64, f64)> = BTreeMap::new();
    for r in rows {
        let e = per.entry(r.kernel.as_str()).or_default();
        e.0 += 1;
        e.1 += usize::from(r.fw.to_bits() == r.host.to_bits());
        e.2 = e.2.max(r.ulps);
        e.3 = e.3.max(r.rel);
    }
    println!("| kernel | values | bit-identical | max ulps | max rel. diff | required | verdict |");
    println!("|---|---:|---:|---:|---:|---|---|");
    for (k, (n, same, ulps, rel)) in &per {
        let ok = rows.iter().filter(|r| r.kernel == *k).all(|r| r.pass);
        let req = if micromath {
            format!("rel ≤ {:.1e}", micromath_tol(k))
        } else {
            "bit-exact".into()
        };
        println!(
            "| {k} | {n} | {same} | {ulps} | {rel:.2e} | {req} | {} |",
            if ok { "pass" } else { "FAIL" }
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::firmware::runner::Res;

    #[test]
    fn ulp_distance_counts_representable_steps() {
        assert_eq!(ulp_distance(1.0, 1.0), 0);
        assert_eq!(ulp_distance(1.0, f32::from_bits(1.0f32.to_bits() + 3)), 3);
        // Across zero: −min_positive .. +min_positive is 2 steps apart through ±0.
        let tiny = f32::from_bits(1);
        assert_eq!(ulp_distance(-tiny, tiny), 2);
    }

    #[test]
    fn compare_flags_a_one_ulp_difference_only_in_the_bit_exact_mode() {
        let tables = HostTables { g: None };
        let args = vec![0.3f32, 0.5, -0.7];
        let host = host_value(&tables, "g_direct", &args).unwrap();
        assert!(host > 0.0 && host <= 1.0);
        let same = Res {
            kernel: "g_direct".into(),
            args: args.clone(),
            value: host,
        };
        let off = Res {
            kernel: "g_direct".into(),
            args,
            value: f32::from_bits(host.to_bits() - 1),
        };
        let rows = compare(&[same, off], &tables, false).unwrap();
        assert!(rows[0].pass && rows[0].ulps == 0);
        assert!(!rows[1].pass && rows[1].ulps == 1);
        let off_mm = Res {
            kernel: "g_direct".into(),
            args: vec![0.3, 0.5, -0.7],
            value: f32::from_bits(host.to_bits() - 1),
        };
        assert!(compare(&[off_mm], &tables, true).unwrap()[0].pass);
        // An unknown kernel or a wrong argument count is an error, not a pass.
        let bad = Res {
            kernel: "g_direct".into(),
            args: vec![0.3],
            value: 1.0,
        };
        assert!(compare(&[bad], &tables, false).is_err());
    }
}

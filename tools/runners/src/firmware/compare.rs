//! The firmware's side of the comparison: reads its numbers (`bits/decimal`) and tables,
//! recomputes every value it printed with the firmware's own kernels compiled for the host
//! (crate `brdf-firmware-kernels`), and compares them through [`crate::device::protocol::Row`]: bit
//! for bit with libm, within a per-kernel relative tolerance with micromath.

use crate::device::protocol::{self, Output, Row, Val};
use anyhow::{bail, Context, Result};
use std::path::Path;

/// The firmware's kernels, compiled for the host: the very source the device runs.
use brdf_firmware_kernels as fw_kernels;

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

/// Parses `bits/decimal`, and checks that the device's decimal text reads back to the same
/// bits (this exercises core::fmt's float printing on the target).
pub(crate) fn parse_num(tok: &str) -> Result<f32> {
    let (hex, dec) = tok
        .split_once('/')
        .with_context(|| format!("number {tok:?} is not bits/decimal"))?;
    let bits = u32::from_str_radix(hex, 16).with_context(|| format!("bad hex in {tok:?}"))?;
    let v = f32::from_bits(bits);
    let d: f32 = dec
        .parse()
        .with_context(|| format!("bad decimal in {tok:?}"))?;
    if d.to_bits() != bits && !(d.is_nan() && v.is_nan()) {
        bail!("decimal {dec} does not read back to bits {hex}");
    }
    Ok(v)
}

/// The host's copy of the embedded G table (the same file from `assets/`).
pub(crate) struct HostTables {
    pub(crate) g: Option<(String, Vec<u8>)>,
}

impl HostTables {
    /// Loads every table a `TABLE <file> <bytes> <crc32>` line names and checks its length
    /// and stored CRC-32.
    pub(crate) fn load(root: &Path, tables: &[Vec<String>]) -> Result<Self> {
        let mut g = None;
        for words in tables {
            let [file, len, crc] = &words[..] else {
                bail!("TABLE line needs <file> <bytes> <crc32>: {words:?}");
            };
            let len: usize = len.parse().with_context(|| format!("bad length {len:?}"))?;
            let crc = u32::from_str_radix(crc, 16).with_context(|| format!("bad CRC {crc:?}"))?;
            let bytes = protocol::asset(root, file)?;
            let t = brdf_lut::GTable::parse(&bytes)
                .map_err(|e| anyhow::anyhow!("assets/{file}: {e:?}"))?;
            let stored = t.view().map_or(0, |v| v.header().checksum);
            if bytes.len() != len || stored != crc {
                bail!(
                    "{file}: host file has {} bytes, CRC {stored:08x}; firmware embeds {len} bytes, CRC {crc:08x}",
                    bytes.len()
                );
            }
            g = Some((file.clone(), bytes));
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

/// Every printed value against the host's: bit for bit (libm) or within
/// [`micromath_tol`] (micromath).
pub(crate) fn compare(out: &Output, tables: &HostTables, micromath: bool) -> Result<Vec<Row>> {
    let mut rows = Vec::with_capacity(out.results.len());
    for r in &out.results {
        let [value] = &r.values[..] else {
            bail!("R line must end with '= <value>': {}", r.line);
        };
        let args = r
            .args
            .iter()
            .map(|t| parse_num(t))
            .collect::<Result<Vec<_>>>()?;
        let fw = parse_num(value)?;
        let host = host_value(tables, &r.kernel, &args)?;
        let tol = if micromath {
            micromath_tol(&r.kernel)
        } else {
            0.0
        };
        let shown: Vec<String> = args.iter().map(|x| format!("{x}")).collect();
        let label = format!("{}({})", r.kernel, shown.join(", "));
        let (fw, host) = (Val::F32(fw.to_bits()), Val::F32(host.to_bits()));
        rows.push(Row::new(&r.kernel, label, fw, host, tol));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::protocol::RawResult;

    fn output(results: Vec<RawResult>) -> Output {
        Output {
            results,
            ..Output::default()
        }
    }

    fn res(args: &[f32], value: f32) -> RawResult {
        let num = |x: &f32| format!("{:08x}/{x}", x.to_bits());
        RawResult {
            kernel: "g_direct".into(),
            args: args.iter().map(num).collect(),
            values: vec![num(&value)],
            line: String::new(),
        }
    }

    #[test]
    fn parse_num_rejects_inconsistent_decimal() {
        assert_eq!(parse_num("3e99999a/0.3").unwrap(), 0.3f32);
        assert!(parse_num("3e99999a/0.31").is_err());
        assert!(parse_num("zz/0.3").is_err());
    }

    #[test]
    fn compare_flags_a_one_ulp_difference_only_in_the_bit_exact_mode() {
        let tables = HostTables { g: None };
        let args = [0.3f32, 0.5, -0.7];
        let host = host_value(&tables, "g_direct", &args).unwrap();
        assert!(host > 0.0 && host <= 1.0);
        let off = f32::from_bits(host.to_bits() - 1);
        let rows = compare(
            &output(vec![res(&args, host), res(&args, off)]),
            &tables,
            false,
        );
        let rows = rows.unwrap();
        assert!(rows[0].pass && rows[0].ulps == 0);
        assert!(!rows[1].pass && rows[1].ulps == 1);
        let mm = compare(&output(vec![res(&args, off)]), &tables, true).unwrap();
        assert!(mm[0].pass);
        // A wrong argument count or a malformed number is an error, not a pass.
        assert!(compare(&output(vec![res(&args[..1], 1.0)]), &tables, false).is_err());
        let mut bad = res(&args, host);
        bad.values = vec!["3f800000/2".into()];
        assert!(compare(&output(vec![bad]), &tables, false).is_err());
    }
}

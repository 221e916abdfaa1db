//! What the Rust firmware (`crates/brdf-firmware/src/report.rs`) and the C program
//! (`examples/c/brdf_example.c`) print over semihosting or stdout, and how a run is judged:
//! one line parser, one list of run errors and one value comparison for both runners
//! (`cargo xtask firmware`, `cargo xtask cffi`). The runners only read their own tokens
//! (the firmware's `bits/decimal` numbers, the C program's `u:<n>` and hex bit patterns).
//!
//! Lines: `<BANNER> …`, `TABLE <words…>`, `R <kernel> <args…> = <values…>`,
//! `CHECK <name> ok|FAIL`, `STACK <bytes>`, `END <results>`; anything else is ignored.

use super::RunOut;
use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;

/// One `R` line, its tokens not yet read.
pub(crate) struct RawResult {
    pub(crate) kernel: String,
    pub(crate) args: Vec<String>,
    pub(crate) values: Vec<String>,
    pub(crate) line: String,
}

/// One `CHECK` line: a self-check the program ran.
pub(crate) struct Check {
    pub(crate) ok: bool,
    pub(crate) line: String,
}

/// A program's output, line by line.
#[derive(Default)]
pub(crate) struct Output {
    /// The words after the banner.
    pub(crate) banner: Vec<String>,
    /// The words after each `TABLE`.
    pub(crate) tables: Vec<Vec<String>>,
    pub(crate) results: Vec<RawResult>,
    pub(crate) checks: Vec<Check>,
    /// Peak stack in bytes (`STACK`).
    pub(crate) stack: Option<u64>,
    /// The result count `END` declares.
    pub(crate) declared: Option<usize>,
    pub(crate) ended: bool,
}

fn words(it: std::str::SplitWhitespace<'_>) -> Vec<String> {
    it.map(str::to_string).collect()
}

fn result(mut it: std::str::SplitWhitespace<'_>, line: &str) -> Result<RawResult> {
    let kernel = it.next().context("R line without kernel")?.to_string();
    let toks = words(it);
    let eq = toks
        .iter()
        .position(|t| t == "=")
        .with_context(|| format!("R line without '=': {line}"))?;
    Ok(RawResult {
        kernel,
        args: toks[..eq].to_vec(),
        values: toks[eq + 1..].to_vec(),
        line: line.to_string(),
    })
}

/// Parses a program's output; an output without the `banner` line is an error.
pub(crate) fn parse(stdout: &str, banner: &str) -> Result<Output> {
    let mut p = Output::default();
    let mut seen = false;
    for line in stdout.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some(b) if b == banner => {
                seen = true;
                p.banner = words(it);
            }
            Some("TABLE") => p.tables.push(words(it)),
            Some("R") => p.results.push(result(it, line)?),
            Some("CHECK") => {
                let _name = it.next();
                p.checks.push(Check {
                    ok: it.next() == Some("ok"),
                    line: line.to_string(),
                });
            }
            Some("STACK") => p.stack = it.next().and_then(|s| s.parse().ok()),
            Some("END") => {
                p.ended = true;
                p.declared = it.next().and_then(|s| s.parse().ok());
            }
            _ => {}
        }
    }
    if !seen {
        bail!("no {banner} banner in the output:\n{stdout}");
    }
    Ok(p)
}

/// What is wrong with a run apart from its values: a timeout or a failing exit status, a
/// missing `END`, a result count other than the declared one, no results, failed checks.
pub(crate) fn run_errors(name: &str, run: &RunOut, out: &Output) -> Vec<String> {
    let mut errors = Vec::new();
    if run.timed_out {
        errors.push(format!("{name}: timed out after {} s", run.timeout_s));
    } else if run.status != Some(0) {
        errors.push(format!("{name}: exit status {:?}", run.status));
    }
    if !out.ended {
        errors.push(format!("{name}: no END line (crashed or cut off)"));
    }
    if out.declared != Some(out.results.len()) {
        errors.push(format!(
            "{name}: END declares {:?} results, {} parsed",
            out.declared,
            out.results.len()
        ));
    }
    if out.results.is_empty() {
        errors.push(format!("{name}: no results printed"));
    }
    for c in out.checks.iter().filter(|c| !c.ok) {
        errors.push(format!("{name}: self-check failed: {}", c.line));
    }
    errors
}

/// The bytes of `assets/<file>`, a table a `TABLE` line names (a plain file name only).
pub(crate) fn asset(root: &std::path::Path, file: &str) -> Result<Vec<u8>> {
    if file.contains('/') || file.contains('\\') || file.contains("..") {
        bail!("table name {file:?} must be a plain file name");
    }
    let path = root.join("assets").join(file);
    std::fs::read(&path).with_context(|| format!("reading {}", path.display()))
}

/// A printed value's bits, by width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Val {
    F32(u32),
    F64(u64),
}

impl Val {
    pub(crate) fn hex(&self) -> String {
        match self {
            Val::F32(b) => format!("{b:08x}"),
            Val::F64(b) => format!("{b:016x}"),
        }
    }
    fn value(&self) -> f64 {
        match *self {
            Val::F32(b) => f32::from_bits(b) as f64,
            Val::F64(b) => f64::from_bits(b),
        }
    }
    fn is_nan(&self) -> bool {
        self.value().is_nan()
    }
}

/// Distance in representable values of one width (0 for identical bits; `u64::MAX` for
/// mixed widths or a non-finite value).
pub(crate) fn ulp_distance(a: Val, b: Val) -> u64 {
    fn key32(b: u32) -> i64 {
        let b = b as i32;
        (if b < 0 { i32::MIN - b } else { b }) as i64
    }
    fn key64(b: u64) -> i128 {
        let b = b as i64;
        (if b < 0 { i64::MIN - b } else { b }) as i128
    }
    if !a.value().is_finite() || !b.value().is_finite() {
        return u64::MAX;
    }
    match (a, b) {
        (Val::F32(x), Val::F32(y)) => (key32(x) - key32(y)).unsigned_abs(),
        (Val::F64(x), Val::F64(y)) => {
            u64::try_from((key64(x) - key64(y)).unsigned_abs()).unwrap_or(u64::MAX)
        }
        _ => u64::MAX,
    }
}

/// One compared value: the device's, the host's, and the verdict.
pub(crate) struct Row {
    pub(crate) kernel: String,
    pub(crate) label: String,
    pub(crate) device: Val,
    pub(crate) host: Val,
    /// |device − host| in units in the last place (0 when bit-identical).
    pub(crate) ulps: u64,
    /// |device − host| / max(|host|, 1e-3) (0 when bit-identical).
    pub(crate) rel: f64,
    pub(crate) pass: bool,
}

impl Row {
    /// Compares one value: bit-identical (any NaN matching any NaN) passes; otherwise, for
    /// `tol` > 0, a relative difference within `tol` passes (`tol` 0 asks for bit-exactness,
    /// so +0 and −0 differ).
    pub(crate) fn new(kernel: &str, label: String, device: Val, host: Val, tol: f64) -> Self {
        let same = device == host || (device.is_nan() && host.is_nan());
        let (d, h) = (device.value(), host.value());
        let rel = if same {
            0.0
        } else if d.is_finite() && h.is_finite() {
            (d - h).abs() / h.abs().max(1e-3)
        } else {
            f64::INFINITY
        };
        Row {
            kernel: kernel.to_string(),
            label,
            device,
            host,
            ulps: if same { 0 } else { ulp_distance(device, host) },
            rel,
            pass: same || (tol > 0.0 && rel <= tol),
        }
    }
}

/// Prints every row (with `verbose`) and the per-kernel table: values, bit-identical ones,
/// the largest ULP and relative differences, what was required and the verdict.
pub(crate) fn print_rows(rows: &[Row], verbose: bool, required: impl Fn(&str) -> String) {
    if verbose {
        for r in rows {
            println!(
                "{} {} device {} host {} rel {:.2e} ulps {}",
                if r.pass { "  same" } else { "  DIFF" },
                r.label,
                r.device.hex(),
                r.host.hex(),
                r.rel,
                r.ulps
            );
        }
    }
    let mut per: BTreeMap<&str, (usize, usize, u64, f64, bool)> = BTreeMap::new();
    for r in rows {
        let e = per.entry(r.kernel.as_str()).or_insert((0, 0, 0, 0.0, true));
        e.0 += 1;
        e.1 += usize::from(r.device == r.host);
        e.2 = e.2.max(r.ulps);
        e.3 = e.3.max(r.rel);
        e.4 &= r.pass;
    }
    println!("| kernel | values | bit-identical | max ulps | max rel. diff | required | verdict |");
    println!("|---|---:|---:|---:|---:|---|---|");
    for (k, (n, same, ulps, rel, ok)) in &per {
        let verdict = if *ok { "pass" } else { "FAIL" };
        println!(
            "| {k} | {n} | {same} | {ulps} | {rel:.2e} | {} | {verdict} |",
            required(k)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ulp_distance_counts_representable_steps() {
        let f = |x: f32| Val::F32(x.to_bits());
        assert_eq!(ulp_distance(f(1.0), f(1.0)), 0);
        assert_eq!(ulp_distance(f(1.0), Val::F32(1.0f32.to_bits() + 3)), 3);
        // Across zero: −min_positive .. +min_positive is 2 steps apart through ±0.
        assert_eq!(ulp_distance(Val::F32(1 | 1 << 31), Val::F32(1)), 2);
        assert_eq!(
            ulp_distance(Val::F64(1.0f64.to_bits()), Val::F64(1.0f64.to_bits() - 2)),
            2
        );
        assert_eq!(ulp_distance(f(1.0), Val::F64(1.0f64.to_bits())), u64::MAX);
    }

    #[test]
    fn one_ulp_fails_bit_exactness_and_passes_a_tolerance() {
        let host = Val::F32(0.7f32.to_bits());
        let off = Val::F32(0.7f32.to_bits() + 1);
        let exact = Row::new("k", "k()".into(), off, host, 0.0);
        assert!(!exact.pass && exact.ulps == 1);
        assert!(Row::new("k", "k()".into(), off, host, 1e-6).pass);
        let nan = Val::F32(f32::NAN.to_bits());
        assert!(Row::new("k", "k()".into(), nan, Val::F32(0x7fc0_0001), 0.0).pass);
        assert!(!Row::new("k", "k()".into(), nan, host, 1.0).pass);
        let (p0, m0) = (Val::F32(0), Val::F32(1 << 31));
        assert!(!Row::new("k", "k()".into(), p0, m0, 0.0).pass);
    }

    #[test]
    fn parse_reads_every_line_kind_and_run_errors_reports_gaps() {
        let text = "noise\nBRDF-C 1\nTABLE g a.blut 10 ff\nR k u:1 3f800000 = 3f800000\n\
                    CHECK x ok\nCHECK y FAIL\nSTACK 96\nEND 2\n";
        let p = parse(text, "BRDF-C").unwrap();
        assert_eq!(p.banner, ["1"]);
        assert_eq!(p.tables, [["g", "a.blut", "10", "ff"]]);
        assert_eq!(p.results[0].args, ["u:1", "3f800000"]);
        assert_eq!(p.results[0].values, ["3f800000"]);
        assert_eq!((p.stack, p.declared, p.ended), (Some(96), Some(2), true));
        let run = RunOut {
            stdout: String::new(),
            stderr: String::new(),
            status: Some(0),
            timed_out: false,
            timeout_s: 1,
        };
        let e = run_errors("dev", &run, &p);
        assert_eq!(e.len(), 2, "{e:?}"); // 2 declared, 1 parsed; one failed check
        assert!(parse("R k = 1\n", "BRDF-C").is_err());
        assert!(parse("BRDF-C 1\nR k 1 2\n", "BRDF-C").is_err());
    }
}

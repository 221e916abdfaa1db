//! The kernel-target rows and the Python package's section of the report.

use super::{fmt_ns, ns, ratio, row, Data};
use minijinja::{context, Value};

/// "**met**" when `measured` is within `limit` (at most, or at least), else "**missed**";
/// "not measured" without a figure.
fn judge(measured: Option<f64>, limit: f64, at_most: bool) -> &'static str {
    match measured {
        None => "not measured",
        Some(x) if (at_most && x <= limit) || (!at_most && x >= limit) => "**met**",
        Some(_) => "**missed**",
    }
}

/// "a / b = x×" of two criterion times.
fn times(a: Option<f64>, b: Option<f64>) -> Option<String> {
    Some(a?)
        .zip(b)
        .map(|(a, b)| format!("{} / {} = {:.2}×", fmt_ns(a), fmt_ns(b), a / b))
}

/// Instruction ratio of kernel `k` over `base`, at most `limit`; `extra` follows the ratio.
fn ratio_row(d: &Data, what: String, k: &str, base: &str, limit: f64, extra: String) -> String {
    let measured = match (d.ir(k), d.ir(base)) {
        (Some(a), Some(b)) => format!("{a:.0} / {b:.0} = {:.2}×{extra}", a / b),
        _ => "–".into(),
    };
    let x = ratio(d.ir(k), d.ir(base));
    row(&[
        what,
        measured,
        format!("≤ {limit}×"),
        judge(x, limit, true).into(),
    ])
}

/// The floor ratios, then every `_std` entry against its no_std twin (the named ones always,
/// others when present; judged on instructions, since both run the same lookup code: the
/// times of this run are shown beside them).
fn instruction_rows(d: &Data) -> String {
    let mut rows = String::new();
    for (k, what, limit) in [
        (
            "dfg_lut",
            "`dfg_lut` instructions vs the floor `floor_bilinear2`",
            1.5,
        ),
        (
            "g_lut2d_linear",
            "`g_lut2d_linear` instructions vs the floor",
            2.0,
        ),
        (
            "g_lut3d_linear",
            "`g_lut3d_linear` instructions vs the floor",
            3.0,
        ),
    ] {
        rows += &ratio_row(d, what.into(), k, "floor_bilinear2", limit, String::new());
    }
    let mut std_names: Vec<String> = vec!["dfg_lut_std".into(), "g_lut2d_linear_std".into()];
    if let Ok(cg) = &d.cg {
        for (k, _, _) in cg {
            if k.ends_with("_std") && !std_names.contains(k) {
                std_names.push(k.clone());
            }
        }
    }
    for k in &std_names {
        let twin = k.trim_end_matches("_std");
        let time = times(d.per(&format!("lut/{k}")), d.per(&format!("lut/{twin}")));
        let what = format!("`{k}` instructions vs its no_std twin `{twin}`");
        let extra = time.map_or(String::new(), |t| format!("; time {t}"));
        rows += &ratio_row(d, what, k, twin, 1.2, extra);
    }
    rows
}

/// Batch entry points against their scalar twins: throughput ratio from criterion (the
/// verdict), instructions per lookup from callgrind (a `_batch` call covers BATCH inputs).
fn batch_rows(d: &Data) -> String {
    let mut rows = String::new();
    for k in [
        "g_lut2d_linear",
        "g_lut3d_linear",
        "dfg_lut",
        "e_lut",
        "eavg_lut",
    ] {
        let (ts, tb) = (d.per(&format!("lut/{k}")), d.per(&format!("lut/{k}_batch")));
        let ins = match (d.ir(k), d.ir(&format!("{k}_batch"))) {
            (Some(s), Some(b)) => {
                let b = b / crate::BATCH as f64;
                format!("; instructions {s:.0} / {b:.0} = {:.2}×", s / b)
            }
            _ => String::new(),
        };
        rows += &row(&[
            format!("`{k}_batch` throughput vs scalar `{k}` (criterion)"),
            times(ts, tb).map_or("–".into(), |t| format!("{t}{ins}")),
            "≥ 3×".into(),
            judge(ratio(ts, tb), 3.0, false).into(),
        ]);
    }
    rows
}

/// The DFG lookup against Karis's fit (timed in two groups of the run, `dfg/` and `lut/`;
/// the verdict takes the larger ratio), the direct G's budget and the SciPy peer.
fn time_rows(d: &Data) -> String {
    let (dfg_lut_ns, karis_ns) = (d.per("dfg/lut_linear_f32"), d.per("dfg/karis_approx_f32"));
    let (lut_ns, lut_karis_ns) = (d.per("lut/dfg_lut"), d.per("lut/dfg_karis"));
    let t = ratio(dfg_lut_ns, karis_ns).zip(ratio(lut_ns, lut_karis_ns));
    let pair = |a, b| times(a, b).unwrap_or_else(|| "–".into());
    let mut rows = row(&[
        "`dfg_lut` time (speed tier) vs Karis's analytic fit (criterion: `dfg/lut_linear_f32` vs `dfg/karis_approx_f32`, and `lut/dfg_lut` vs `lut/dfg_karis`)".to_string(),
        format!("{}; {}", pair(dfg_lut_ns, karis_ns), pair(lut_ns, lut_karis_ns)),
        "≤ 1×".into(),
        judge(t.map(|(a, b)| a.max(b)), 1.0, true).into(),
    ]);
    let dr = d.ir("g_direct_f32");
    rows += &row(&[
        "`g_direct_f32` instructions per G (10 nodes)".to_string(),
        dr.map_or("–".into(), |x| format!("{x:.0}")),
        "≤ 1,500".into(),
        judge(dr, 1500.0, true).into(),
    ]);
    let direct64 = d.per(&format!(
        "g_direct_f64/n{:02}",
        brdf_core::quadrature::DEFAULT_NODES
    ));
    let peer_ns = match &d.peer {
        super::Peer::Ran { ns_per_g, .. } => Some(*ns_per_g),
        super::Peer::Skipped(_) => None,
    };
    let p = ratio(peer_ns, direct64);
    rows += &row(&[
        "SciPy peer time vs direct G (f64)".to_string(),
        p.map_or("–".into(), |x| format!("{x:.0}×")),
        "≥ 1000×".into(),
        judge(p, 1000.0, false).into(),
    ]);
    rows
}

/// One row per kernel target: instruction ratios against the floor or a twin, batch
/// throughput, the DFG lookup's time against Karis's fit, the direct G's instruction
/// budget, the SciPy peer.
pub(super) fn kernel_target_rows(d: &Data) -> String {
    instruction_rows(d) + &batch_rows(d) + &time_rows(d)
}

/// "Python …, NumPy …, brdf_kernels …" of bench.py's figures.
fn python_versions(v: &serde_json::Value) -> String {
    format!(
        "Python {}, NumPy {}, brdf_kernels {}",
        v["python"].as_str().unwrap_or("?"),
        v["numpy"].as_str().unwrap_or("?"),
        v["brdf_kernels"].as_str().unwrap_or("?")
    )
}

/// The template's `python` object from bench.py's figures (ns per element or per call).
pub(super) fn python_context(b: &Result<serde_json::Value, String>) -> Value {
    let v = match b {
        Ok(v) => v,
        Err(why) => return context! { ran => false, why => why },
    };
    let f = |k: &str| v[k].as_f64().filter(|x| x.is_finite());
    let n = |k: &str| ns(f(k));
    let ok = |x: Option<bool>| match x {
        Some(true) => "**met**",
        Some(false) => "**missed**",
        None => "not measured",
    };
    let (ratio, speedup, overhead) = (f("ratio"), f("quad_speedup"), f("scalar_overhead_ns"));
    let quad = match (f("quad_ns"), speedup) {
        (Some(q), Some(x)) => format!("{} / {} = {x:.0}×", fmt_ns(q), n("python_ns")),
        _ => format!(
            "not run ({})",
            v["quad_skipped"].as_str().unwrap_or("no figure")
        ),
    };
    context! {
        ran => true,
        versions => python_versions(v),
        sigma => v["sigma"].to_string(),
        pairs => v["pairs"].as_u64().unwrap_or(0),
        reps => v["reps"].as_u64().unwrap_or(0),
        quad_pairs => v["quad_pairs"].as_u64().unwrap_or(0),
        py_ns => n("python_ns"),
        rust_ns => n("rust_ns"),
        ratio => ratio.map_or("–".into(), |x| format!("{x:.2}×")),
        v_ratio => ok(ratio.map(|x| x <= 1.3)),
        quad,
        v_quad => ok(speedup.map(|x| x >= 1000.0)),
        scalar => format!("{} − {} = {}", n("scalar_g_modified_ns"), n("rust_ns"), n("scalar_overhead_ns")),
        v_scalar => ok(overhead.map(|x| x <= 1000.0)),
        blinn => n("scalar_g_blinn_ns"),
    }
}

#[cfg(test)]
mod tests {
    use super::super::render::{fill, TEMPLATE};
    use super::*;
    use brdf_core::quadrature::DEFAULT_NODES;

    /// The template's Python section alone.
    fn python_section() -> &'static str {
        let start = TEMPLATE.find("## Python package").expect("section");
        let end = start + TEMPLATE[start..].find("\n## DFG").expect("next section");
        &TEMPLATE[start..end]
    }

    fn render(b: std::result::Result<serde_json::Value, String>) -> String {
        let ctx = context! { python => python_context(&b), dn => DEFAULT_NODES };
        fill(python_section(), ctx).expect("renders")
    }

    #[test]
    fn python_section_states_each_figure_and_judges_it_against_its_goal() {
        // 1.25 ≤ 1.3 met; 950× < 1000× missed; 1,100 ns overhead > 1 µs missed.
        let b = serde_json::json!({
            "pairs": 1000000, "reps": 5, "sigma": 0.3, "python": "3.11.7",
            "numpy": "2.3.0", "brdf_kernels": "0.1.0", "rust_ns": 400.0,
            "python_ns": 500.0, "ratio": 1.25, "quad_ns": 475000.0, "quad_pairs": 64,
            "quad_skipped": null, "quad_speedup": 950.0, "scalar_g_modified_ns": 1500.0,
            "scalar_overhead_ns": 1100.0, "scalar_g_blinn_ns": 300.0
        });
        let md = render(Ok(b));
        assert!(
            md.contains("| 500 ns / 400 ns = 1.25× | ≤ 1.3× | **met** |"),
            "{md}"
        );
        assert!(
            md.contains("| 475.0 µs / 500 ns = 950× | ≥ 1000× | **missed** |"),
            "{md}"
        );
        assert!(
            md.contains("| 1500 ns − 400 ns = 1100 ns | ≤ 1 µs | **missed** |"),
            "{md}"
        );
        assert!(
            md.contains("Python 3.11.7, NumPy 2.3.0, brdf_kernels 0.1.0"),
            "{md}"
        );
        assert!(!md.contains("Skipped"), "{md}");
    }

    #[test]
    fn python_section_without_scipy_or_package_says_why() {
        let b = serde_json::json!({"python_ns": 500.0, "rust_ns": 400.0, "ratio": 1.25,
            "quad_ns": null, "quad_skipped": "No module named 'scipy'"});
        let md = render(Ok(b));
        assert!(
            md.contains("not run (No module named 'scipy') | ≥ 1000× | not measured"),
            "{md}"
        );
        let md = render(Err("pip install ./crates/brdf-py failed: no cargo".into()));
        assert!(
            md.contains("Skipped in this run: pip install ./crates/brdf-py failed: no cargo."),
            "{md}"
        );
    }
}

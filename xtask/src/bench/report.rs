//! `docs/benchmarks.md` from the Markdown template `xtask/templates/benchmarks.md`: the prose
//! lives in the template; this module computes the numbers, verdicts and table rows it
//! fills in (rendered with minijinja, undefined names are errors).

use super::{fmt_ns, Data as Report, Est, Peer};
use anyhow::{Context, Result};
use brdf_bench::SIGMA;
use brdf_core::quadrature::DEFAULT_NODES;
use minijinja::{context, AutoEscape, Environment, UndefinedBehavior, Value};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const TEMPLATE: &str = include_str!("../../templates/benchmarks.md");

/// A Markdown table row `| a | b | … |` with its newline.
fn row<S: AsRef<str>>(cells: &[S]) -> String {
    let mut s = String::from("|");
    for c in cells {
        s.push(' ');
        s.push_str(c.as_ref());
        s.push_str(" |");
    }
    s.push('\n');
    s
}

fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => Some(a / b),
        _ => None,
    }
}

/// "12.3× — **met**" when `x ≥ t`, else "0.45× — **missed**", or "not measured".
fn verdict(x: Option<f64>, t: f64) -> String {
    match x {
        Some(x) if x >= t => format!("{x:.1}× — **met**"),
        Some(x) => format!("{x:.2}× — **missed**"),
        None => "not measured".into(),
    }
}

pub(super) fn render(r: &Report) -> Result<String> {
    let e = &r.est;
    let per = |id: &str| e.get(id).map(Est::per_call);
    let ns = |x: Option<f64>| x.map_or("–".into(), fmt_ns);
    let m = &r.machine;
    let a = &r.acc;
    let dn = DEFAULT_NODES;

    let direct32 = per(&format!("g_direct_f32_libm/n{dn:02}"));
    let direct64 = per(&format!("g_direct_f64/n{dn:02}"));
    let lut3 = per("g_lut/table3d");
    let lut2 = per("g_lut/table2d_sigma0.3");
    let lut3f = per("g_lut/table3d_linear");
    let lut2f = per("g_lut/table2d_sigma0.3_linear");
    let dfg_lut = per("dfg/lut_f32");
    let dfg_direct = per("dfg_direct/split_sum_f64");
    let dfg_alb = per("dfg_direct/directional_albedo_f64");
    let peer_ns = match &r.peer {
        Peer::Ran { ns_per_g, .. } => Some(*ns_per_g),
        Peer::Skipped(_) => None,
    };

    // Matched accuracy: node table and table-versus-direct table.
    let mut node_rows = String::new();
    for &(n, e64, e32) in &a.g_direct {
        let c = |id: String| ns(per(&id));
        node_rows += &row(&[
            format!("{n}{}", if n == dn { " (default)" } else { "" }),
            format!("{e64:.1e}"),
            format!("{e32:.1e}"),
            c(format!("g_direct_f64/n{n:02}")),
            c(format!("g_direct_f32_libm/n{n:02}")),
            c(format!("g_direct_f32_micromath/n{n:02}")),
        ]);
    }
    let matched = |err: Option<f64>| -> Option<usize> {
        let err = err?;
        a.g_direct.iter().find(|x| x.2 <= err).map(|x| x.0)
    };
    let mut table_rows = String::new();
    for (name, err, t) in [
        ("3-D (θ, φ, σ) tricubic, `g_modified.blut`", a.g_lut3, lut3),
        (
            "per-σ 2-D bicubic, `g_modified_sigma0.3.blut`",
            a.g_lut2,
            lut2,
        ),
        (
            "3-D trilinear, `g_modified_linear.blut`",
            a.g_lut3_linear,
            lut3f,
        ),
        (
            "per-σ 2-D bilinear, `g_modified_sigma0.3_linear.blut`",
            a.g_lut2_linear,
            lut2f,
        ),
    ] {
        let mn = matched(err);
        let tm = mn.and_then(|n| per(&format!("g_direct_f32_libm/n{n:02}")));
        table_rows += &row(&[
            name.to_string(),
            err.map_or("–".into(), |x| format!("{x:.1e}")),
            ns(t),
            mn.map_or("–".into(), |n| format!("{n} nodes")),
            ns(tm),
            ratio(tm, t).map_or("–".into(), |x| format!("{x:.2}×")),
            ratio(direct32, t).map_or("–".into(), |x| format!("{x:.2}×")),
        ]);
    }

    // What limits the G-table ratios (instruction counts).
    let ir = |k: &str| r.cg.as_ref().ok()?.iter().find(|x| x.0 == k).map(|x| x.2);
    let limits = match (
        ir("g_direct_f32"),
        ir("g_lut3d"),
        ir("g_lut2d"),
        ir("g_lut3d_linear"),
        ir("g_lut2d_linear"),
    ) {
        (Some(d), Some(l3), Some(l2), Some(f3), Some(f2)) => Some(BTreeMap::from([
            ("d", format!("{d:.0}")),
            ("l3", format!("{l3:.0}")),
            ("l2", format!("{l2:.0}")),
            ("f3", format!("{f3:.0}")),
            ("f2", format!("{f2:.0}")),
            ("r3", format!("{:.1}", d / f3)),
            ("r2", format!("{:.1}", d / f2)),
            ("need30", format!("{:.0}", d / 30.0)),
        ])),
        _ => None,
    };

    let mut closed_rows = String::new();
    for k in [
        "smith_beckmann_correlated",
        "smith_beckmann_separable",
        "blinn_dots",
        &format!("modified_dots_n{dn}"),
    ] {
        let c = |g: &str| ns(per(&format!("{g}/{k}")));
        closed_rows += &row(&[
            k.to_string(),
            c("g_closed_f32_libm"),
            c("g_closed_f32_micromath"),
            c("g_closed_f64"),
        ]);
    }

    let peer = match &r.peer {
        Peer::Ran {
            ns_per_g,
            evaluations,
            max_diff,
            versions,
        } => context! {
            ran => true,
            versions => versions,
            ns => fmt_ns(*ns_per_g),
            evaluations => evaluations,
            max_diff => format!("{max_diff:.1e}"),
            speedup => ratio(peer_ns, direct64).map_or("–".into(), |x| format!("{x:.0}×")),
        },
        Peer::Skipped(why) => context! { ran => false, why => why },
    };

    let fe = |x: Option<(f64, f64)>| {
        x.map_or(("–".to_string(), "–".to_string()), |(p, q)| {
            (format!("{p:.1e}"), format!("{q:.1e}"))
        })
    };
    let (la, lb) = fe(a.dfg_lut);
    let (fa, fb) = fe(a.dfg_lut_linear);
    let (ka, kb) = fe(Some(a.dfg_karis));
    let dfg = context! {
        lut_ns => ns(dfg_lut), lut_a => la, lut_b => lb,
        linear_ns => ns(per("dfg/lut_linear_f32")), linear_a => fa, linear_b => fb,
        karis_ns => ns(per("dfg/karis_approx_f32")), karis_a => ka, karis_b => kb,
        direct_ns => ns(dfg_direct),
        direct32_ns => ns(per("dfg_direct/split_sum_f32")),
        albedo_ns => ns(dfg_alb),
    };

    let mut model_rows = String::new();
    let mut names: Vec<&str> = e
        .keys()
        .filter_map(|k| k.strip_prefix("model_eval_f32_libm/"))
        .collect();
    names.sort();
    for n in names {
        model_rows += &row(&[
            n.to_string(),
            ns(per(&format!("model_eval_f32_libm/{n}"))),
            ns(per(&format!("model_sample_f32_libm/{n}"))),
        ]);
    }

    let mut batch_rows = String::new();
    let mut bnames: Vec<&str> = e
        .keys()
        .filter_map(|k| k.strip_prefix("batch_f64/"))
        .collect();
    bnames.sort();
    for n in bnames {
        let c = |g: &str| {
            per(&format!("{g}/{n}"))
                .map_or("–".into(), |x| format!("{} — {:.1}", fmt_ns(x), 1e3 / x))
        };
        batch_rows += &row(&[
            n.to_string(),
            c("batch_f32_libm"),
            c("batch_f32_micromath"),
            c("batch_f64"),
        ]);
    }

    let mut parse_rows = String::new();
    let mut files: Vec<&str> = e
        .keys()
        .filter_map(|k| k.strip_prefix("lut_parse/view/"))
        .collect();
    files.sort();
    for f in files {
        let v = &e[&format!("lut_parse/view/{f}")];
        let sl = e.get(&format!("lut_parse/std_loader/{f}"));
        let bytes = v.bytes.unwrap_or(f64::NAN);
        let mib = |x: &Est| fmt_ns(x.mean / bytes * 1_048_576.0);
        parse_rows += &row(&[
            format!("`{f}`"),
            format!("{:.1} KiB", bytes / 1024.0),
            fmt_ns(v.mean),
            mib(v),
            sl.map_or("–".into(), |x| fmt_ns(x.mean)),
            sl.map_or("–".into(), mib),
        ]);
    }
    let gen = r.gen.map(|(secs, bytes, files)| {
        context! {
            files => files,
            kib => format!("{:.0}", bytes as f64 / 1024.0),
            secs => format!("{secs:.1}"),
        }
    });

    let cg = match &r.cg {
        Ok(rows) => {
            let mut s = String::new();
            for (k, what, per) in rows {
                s += &row(&[format!("`{k}`"), what.clone(), format!("{per:.0}")]);
            }
            context! { ok => true, rows => s }
        }
        Err(why) => context! { ok => false, why => why },
    };

    let mut raw_rows = String::new();
    for (id, x) in e {
        let (lo, hi) = x.per_call_ci();
        let (mean, lo, hi) = if x.bytes.is_some() {
            (x.mean, x.lo, x.hi)
        } else {
            (x.per_call(), lo, hi)
        };
        raw_rows += &row(&[
            format!("`{id}`"),
            fmt_ns(mean),
            format!("{} – {}", fmt_ns(lo), fmt_ns(hi)),
        ]);
    }

    let ctx = context! {
        cpu => m.cpu, cores => m.cores, os => m.os, rustc => m.rustc,
        warm_up => r.warm_up.to_string(),
        measurement => r.measurement.to_string(),
        sample_size => r.sample_size,
        secs => format!("{:.0}", r.secs),
        t_crit => format!("{:.0}", r.t_crit),
        dn => dn,
        sigma => SIGMA.to_string(),
        batch => brdf_bench::BATCH,
        batch_len => brdf_bench::BATCH_LEN,
        g3_linear_asset => brdf_bench::G3_LINEAR_ASSET,
        g2_linear_asset => brdf_bench::G2_LINEAR_ASSET,
        g3_asset => brdf_bench::G3_ASSET,
        g2_asset => brdf_bench::G2_ASSET,
        v_g3_linear => verdict(ratio(direct32, lut3f), 10.0),
        v_g2_linear => verdict(ratio(direct32, lut2f), 30.0),
        v_g3 => verdict(ratio(direct32, lut3), 10.0),
        v_g2 => verdict(ratio(direct32, lut2), 30.0),
        v_peer => match peer_ns {
            Some(_) => verdict(ratio(peer_ns, direct64), 1000.0),
            None => "peer skipped (SciPy not importable)".into(),
        },
        v_dfg_direct => verdict(ratio(dfg_direct, dfg_lut), 50.0),
        v_dfg_albedo => verdict(ratio(dfg_alb, dfg_lut), 50.0),
        direct32 => ns(direct32),
        direct64 => ns(direct64),
        dfg_linear_asset => brdf_bench::DFG_LINEAR_ASSET,
        dfg_asset => brdf_bench::DFG_ASSET,
        kernel_target_rows => kernel_target_rows(r, per("dfg/lut_linear_f32"), per("dfg/karis_approx_f32"), peer_ns, direct64),
        g_points => a.g_points,
        dfg_points => a.dfg_points,
        python => python_context(&r.python),
        node_rows, table_rows, limits => Value::from_serialize(&limits), closed_rows, peer, dfg,
        model_rows, batch_rows, parse_rows, gen, cg, raw_rows,
    };
    fill(TEMPLATE, ctx)
}

/// One row per kernel target: instruction ratios against the floor or a twin, the DFG
/// lookup's time against Karis's fit, the direct G's instruction budget, the SciPy peer.
fn kernel_target_rows(
    r: &Report,
    dfg_lut_ns: Option<f64>,
    karis_ns: Option<f64>,
    peer_ns: Option<f64>,
    direct64_ns: Option<f64>,
) -> String {
    let ir = |k: &str| r.cg.as_ref().ok()?.iter().find(|x| x.0 == k).map(|x| x.2);
    let judge = |measured: Option<f64>, limit: f64, at_most: bool| match measured {
        None => "not measured",
        Some(x) if (at_most && x <= limit) || (!at_most && x >= limit) => "**met**",
        Some(_) => "**missed**",
    };
    let per = |id: &str| r.est.get(id).map(Est::per_call);
    // "a / b = x×" of two criterion times.
    let times = |a: Option<f64>, b: Option<f64>| {
        Some(a?)
            .zip(b)
            .map(|(a, b)| format!("{} / {} = {:.2}×", fmt_ns(a), fmt_ns(b), a / b))
    };
    let mut rows = String::new();
    // Instruction ratio of `k` over `base`, at most `limit`; `extra` follows the ratio.
    let mut ratio_row = |what: String, k: &str, base: &str, limit: f64, extra: String| {
        let x = ratio(ir(k), ir(base));
        let measured = match (ir(k), ir(base)) {
            (Some(a), Some(b)) => format!("{a:.0} / {b:.0} = {:.2}×{extra}", a / b),
            _ => "–".into(),
        };
        rows.push_str(&row(&[
            what,
            measured,
            format!("≤ {limit}×"),
            judge(x, limit, true).into(),
        ]));
    };
    ratio_row(
        "`dfg_lut` instructions vs the floor `floor_bilinear2`".into(),
        "dfg_lut",
        "floor_bilinear2",
        1.5,
        String::new(),
    );
    ratio_row(
        "`g_lut2d_linear` instructions vs the floor".into(),
        "g_lut2d_linear",
        "floor_bilinear2",
        2.0,
        String::new(),
    );
    ratio_row(
        "`g_lut3d_linear` instructions vs the floor".into(),
        "g_lut3d_linear",
        "floor_bilinear2",
        3.0,
        String::new(),
    );
    // Every `_std` entry against its no_std twin: the named ones always, others when present.
    let mut std_names: Vec<String> = vec!["dfg_lut_std".into(), "g_lut2d_linear_std".into()];
    if let Ok(cg) = &r.cg {
        for (k, _, _) in cg {
            if k.ends_with("_std") && !std_names.contains(k) {
                std_names.push(k.clone());
            }
        }
    }
    // (The verdict is on instructions: both run the same lookup code, so their times differ
    // by the run's noise; the times of this run are shown beside them.)
    for k in &std_names {
        let twin = k.trim_end_matches("_std");
        let time = times(per(&format!("lut/{k}")), per(&format!("lut/{twin}")));
        ratio_row(
            format!("`{k}` instructions vs its no_std twin `{twin}`"),
            k,
            twin,
            1.2,
            time.map_or(String::new(), |t| format!("; time {t}")),
        );
    }
    // Batch entry points against their scalar twins: throughput ratio from criterion (the
    // verdict), instructions per lookup from callgrind (a `_batch` call covers BATCH inputs).
    for k in [
        "g_lut2d_linear",
        "g_lut3d_linear",
        "dfg_lut",
        "e_lut",
        "eavg_lut",
    ] {
        let (ts, tb) = (per(&format!("lut/{k}")), per(&format!("lut/{k}_batch")));
        let x = ratio(ts, tb);
        let ins = match (ir(k), ir(&format!("{k}_batch"))) {
            (Some(s), Some(b)) => {
                let b = b / brdf_bench::BATCH as f64;
                format!("; instructions {s:.0} / {b:.0} = {:.2}×", s / b)
            }
            _ => String::new(),
        };
        rows.push_str(&row(&[
            format!("`{k}_batch` throughput vs scalar `{k}` (criterion)"),
            times(ts, tb).map_or("–".into(), |t| format!("{t}{ins}")),
            "≥ 3×".into(),
            judge(x, 3.0, false).into(),
        ]));
    }
    // The same two functions are timed in two groups of the run (`dfg/` and `lut/`); the
    // verdict takes the larger ratio.
    let (lut_ns, lut_karis_ns) = (per("lut/dfg_lut"), per("lut/dfg_karis"));
    let t = ratio(dfg_lut_ns, karis_ns).zip(ratio(lut_ns, lut_karis_ns));
    let pair = |a, b| times(a, b).unwrap_or_else(|| "–".into());
    rows.push_str(&row(&[
        "`dfg_lut` time (speed tier) vs Karis's analytic fit (criterion: `dfg/lut_linear_f32` vs `dfg/karis_approx_f32`, and `lut/dfg_lut` vs `lut/dfg_karis`)".to_string(),
        format!(
            "{}; {}",
            pair(dfg_lut_ns, karis_ns),
            pair(lut_ns, lut_karis_ns)
        ),
        "≤ 1×".into(),
        judge(t.map(|(a, b)| a.max(b)), 1.0, true).into(),
    ]));
    let d = ir("g_direct_f32");
    rows.push_str(&row(&[
        "`g_direct_f32` instructions per G (10 nodes)".to_string(),
        d.map_or("–".into(), |x| format!("{x:.0}")),
        "≤ 1,500".into(),
        judge(d, 1500.0, true).into(),
    ]));
    let p = ratio(peer_ns, direct64_ns);
    rows.push_str(&row(&[
        "SciPy peer time vs direct G (f64)".to_string(),
        p.map_or("–".into(), |x| format!("{x:.0}×")),
        "≥ 1000×".into(),
        judge(p, 1000.0, false).into(),
    ]));
    rows
}

/// The Python package's interpreter: `.cache/python-venv` (made by `.ci/python.sh`) with
/// `brdf_kernels` importable, built there from `crates/brdf-py` when it is not (`python3 -m
/// venv`, then `pip install numpy ./crates/brdf-py`; needs cargo and PyPI).
fn package_python(root: &Path) -> std::result::Result<std::path::PathBuf, String> {
    let pkg = root.join("crates/brdf-py");
    super::venv_python(
        root,
        ".cache/python-venv",
        "brdf_kernels",
        &["numpy".as_ref(), pkg.as_os_str()],
    )
}

/// Runs `crates/brdf-py/bench/bench.py --json` (the SciPy peer through `.cache/scipy-venv`
/// when that exists) and returns its figures.
pub(super) fn python_bench(root: &Path) -> std::result::Result<serde_json::Value, String> {
    eprintln!("== Python package");
    let py = package_python(root)?;
    let mut cmd = Command::new(&py);
    cmd.arg(root.join("crates/brdf-py/bench/bench.py"))
        .arg("--json")
        .current_dir(root);
    let peer = root.join(".cache/scipy-venv/bin/python3");
    if peer.exists() {
        cmd.arg("--peer-python").arg(peer);
    }
    let o = cmd.output().map_err(|e| format!("bench.py: {e}"))?;
    if !o.status.success() {
        let err = String::from_utf8_lossy(&o.stderr);
        return Err(format!(
            "bench.py failed: {}",
            err.lines().last().unwrap_or("").trim()
        ));
    }
    serde_json::from_slice(&o.stdout).map_err(|e| format!("unreadable bench.py output ({e})"))
}

/// The template's `python` object from bench.py's figures (ns per element or per call).
fn python_context(b: &std::result::Result<serde_json::Value, String>) -> Value {
    let v = match b {
        Ok(v) => v,
        Err(why) => return context! { ran => false, why => why },
    };
    let f = |k: &str| v[k].as_f64().filter(|x| x.is_finite());
    let ns = |k: &str| f(k).map_or("–".into(), fmt_ns);
    let judge = |ok: Option<bool>| match ok {
        Some(true) => "**met**",
        Some(false) => "**missed**",
        None => "not measured",
    };
    let ratio = f("ratio");
    let speedup = f("quad_speedup");
    let overhead = f("scalar_overhead_ns");
    let quad = match (f("quad_ns"), speedup) {
        (Some(q), Some(x)) => format!("{} / {} = {x:.0}×", fmt_ns(q), ns("python_ns")),
        _ => format!(
            "not run ({})",
            v["quad_skipped"].as_str().unwrap_or("no figure")
        ),
    };
    context! {
        ran => true,
        versions => format!(
            "Python {}, NumPy {}, brdf_kernels {}",
            v["python"].as_str().unwrap_or("?"),
            v["numpy"].as_str().unwrap_or("?"),
            v["brdf_kernels"].as_str().unwrap_or("?")
        ),
        sigma => v["sigma"].to_string(),
        pairs => v["pairs"].as_u64().unwrap_or(0),
        reps => v["reps"].as_u64().unwrap_or(0),
        quad_pairs => v["quad_pairs"].as_u64().unwrap_or(0),
        py_ns => ns("python_ns"),
        rust_ns => ns("rust_ns"),
        ratio => ratio.map_or("–".into(), |x| format!("{x:.2}×")),
        v_ratio => judge(ratio.map(|x| x <= 1.3)),
        quad,
        v_quad => judge(speedup.map(|x| x >= 1000.0)),
        scalar => format!("{} − {} = {}", ns("scalar_g_modified_ns"), ns("rust_ns"), ns("scalar_overhead_ns")),
        v_scalar => judge(overhead.map(|x| x <= 1000.0)),
        blinn => ns("scalar_g_blinn_ns"),
    }
}

/// Renders a Markdown template: no escaping, undefined names are errors, a block tag's own
/// line break is dropped (so `{% if %}` lines leave no blank lines).
pub(crate) fn fill(template: &str, ctx: Value) -> Result<String> {
    let mut env = Environment::new();
    env.set_auto_escape_callback(|_| AutoEscape::None);
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_trim_blocks(true);
    env.set_keep_trailing_newline(true);
    env.add_template("report.md", template)
        .context("parsing the report template")?;
    env.get_template("report.md")?
        .render(ctx)
        .context("rendering the report template")
}

#[cfg(test)]
mod tests {
    use super::*;

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

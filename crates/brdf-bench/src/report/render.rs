//! `docs/benchmarks.md` from the Markdown template `templates/benchmarks.md`: the prose and
//! the tables' heads live in the template; this module computes the numbers, verdicts and
//! table rows it fills in (minijinja, undefined names are errors).

use super::tablegen::{self, TableGen, Timing};
use super::{fmt_ns, ns, ratio, row, targets, Data, Est, Peer};
use crate::SIGMA;
use brdf_core::quadrature::DEFAULT_NODES;
use minijinja::{context, Value};
use std::collections::BTreeMap;

pub(super) const TEMPLATE: &str = include_str!("../../templates/benchmarks.md");

/// "12.3× — **met**" when `x ≥ t`, else "0.45× — **missed**", or "not measured".
fn verdict(x: Option<f64>, t: f64) -> String {
    match x {
        Some(x) if x >= t => format!("{x:.1}× — **met**"),
        Some(x) => format!("{x:.2}× — **missed**"),
        None => "not measured".into(),
    }
}

/// `{x:.1e}` or "–".
fn e1(x: Option<f64>) -> String {
    x.map_or("–".into(), |x| format!("{x:.1e}"))
}

/// The direct G's error and time at each node count.
fn node_rows(d: &Data) -> String {
    let dn = DEFAULT_NODES;
    let mut s = String::new();
    for &(n, e64, e32) in &d.acc.g_direct {
        let c = |id: String| ns(d.per(&id));
        s += &row(&[
            format!("{n}{}", if n == dn { " (default)" } else { "" }),
            format!("{e64:.1e}"),
            format!("{e32:.1e}"),
            c(format!("g_direct_f64/n{n:02}")),
            c(format!("g_direct_f32_libm/n{n:02}")),
            c(format!("g_direct_f32_micromath/n{n:02}")),
        ]);
    }
    s
}

/// Each G table against the direct G (f32) of no larger error.
fn table_rows(d: &Data) -> String {
    let a = &d.acc;
    let direct32 = d.per(&format!("g_direct_f32_libm/n{DEFAULT_NODES:02}"));
    let matched = |err: Option<f64>| {
        let err = err?;
        a.g_direct.iter().find(|x| x.2 <= err).map(|x| x.0)
    };
    let mut s = String::new();
    for (name, err, id) in [
        (
            "3-D (θ, φ, σ) tricubic, `g_modified.blut`",
            a.g_lut3,
            "g_lut/table3d",
        ),
        (
            "per-σ 2-D bicubic, `g_modified_sigma0.3.blut`",
            a.g_lut2,
            "g_lut/table2d_sigma0.3",
        ),
        (
            "3-D trilinear, `g_modified_linear.blut`",
            a.g_lut3_linear,
            "g_lut/table3d_linear",
        ),
        (
            "per-σ 2-D bilinear, `g_modified_sigma0.3_linear.blut`",
            a.g_lut2_linear,
            "g_lut/table2d_sigma0.3_linear",
        ),
    ] {
        let t = d.per(id);
        let mn = matched(err);
        let tm = mn.and_then(|n| d.per(&format!("g_direct_f32_libm/n{n:02}")));
        let x = |r: Option<f64>| r.map_or("–".into(), |x| format!("{x:.2}×"));
        s += &row(&[
            name.to_string(),
            e1(err),
            ns(t),
            mn.map_or("–".into(), |n| format!("{n} nodes")),
            ns(tm),
            x(ratio(tm, t)),
            x(ratio(direct32, t)),
        ]);
    }
    s
}

/// What limits the G-table ratios (instruction counts), when callgrind ran.
fn limits(d: &Data) -> Option<BTreeMap<&'static str, String>> {
    let (dr, l3, l2) = (d.ir("g_direct_f32")?, d.ir("g_lut3d")?, d.ir("g_lut2d")?);
    let (f3, f2) = (d.ir("g_lut3d_linear")?, d.ir("g_lut2d_linear")?);
    Some(BTreeMap::from([
        ("d", format!("{dr:.0}")),
        ("l3", format!("{l3:.0}")),
        ("l2", format!("{l2:.0}")),
        ("f3", format!("{f3:.0}")),
        ("f2", format!("{f2:.0}")),
        ("r3", format!("{:.1}", dr / f3)),
        ("r2", format!("{:.1}", dr / f2)),
        ("need30", format!("{:.0}", dr / 30.0)),
    ]))
}

/// The closed-form G kernels, per build.
fn closed_rows(d: &Data) -> String {
    let mut s = String::new();
    for k in [
        "smith_beckmann_correlated",
        "smith_beckmann_separable",
        "blinn_dots",
        &format!("modified_dots_n{DEFAULT_NODES}"),
    ] {
        let c = |g: &str| ns(d.per(&format!("{g}/{k}")));
        s += &row(&[
            k.to_string(),
            c("g_closed_f32_libm"),
            c("g_closed_f32_micromath"),
            c("g_closed_f64"),
        ]);
    }
    s
}

/// The template's `peer` object.
fn peer(d: &Data) -> Value {
    let direct64 = d.per(&format!("g_direct_f64/n{DEFAULT_NODES:02}"));
    match &d.peer {
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
            speedup => ratio(d.peer_ns(), direct64).map_or("–".into(), |x| format!("{x:.0}×")),
        },
        Peer::Skipped(why) => context! { ran => false, why => why },
    }
}

/// The template's `dfg` object.
fn dfg(d: &Data) -> Value {
    let a = &d.acc;
    let fe = |x: Option<(f64, f64)>| (e1(x.map(|p| p.0)), e1(x.map(|p| p.1)));
    let (la, lb) = fe(a.dfg_lut);
    let (fa, fb) = fe(a.dfg_lut_linear);
    let (ka, kb) = fe(Some(a.dfg_karis));
    let t = |id: &str| ns(d.per(id));
    context! {
        lut_ns => t("dfg/lut_f32"), lut_a => la, lut_b => lb,
        linear_ns => t("dfg/lut_linear_f32"), linear_a => fa, linear_b => fb,
        karis_ns => t("dfg/karis_approx_f32"), karis_a => ka, karis_b => kb,
        direct_ns => t("dfg_direct/split_sum_f64"),
        direct32_ns => t("dfg_direct/split_sum_f32"),
        albedo_ns => t("dfg_direct/directional_albedo_f64"),
    }
}

/// Models (eval, sample) and batch entry points (per build).
fn model_and_batch_rows(d: &Data) -> (String, String) {
    let mut models = String::new();
    for n in d.names("model_eval_f32_libm/") {
        models += &row(&[
            n.to_string(),
            ns(d.per(&format!("model_eval_f32_libm/{n}"))),
            ns(d.per(&format!("model_sample_f32_libm/{n}"))),
        ]);
    }
    let mut batch = String::new();
    for n in d.names("batch_f64/") {
        let c = |g: &str| {
            d.per(&format!("{g}/{n}"))
                .map_or("–".into(), |x| format!("{} — {:.1}", fmt_ns(x), 1e3 / x))
        };
        batch += &row(&[
            n.to_string(),
            c("batch_f32_libm"),
            c("batch_f32_micromath"),
            c("batch_f64"),
        ]);
    }
    (models, batch)
}

/// LUT parse times per file: view and std loader, per call and per MiB.
fn parse_rows(d: &Data) -> String {
    let mut s = String::new();
    for f in d.names("lut_parse/view/") {
        let v = &d.est[&format!("lut_parse/view/{f}")];
        let sl = d.est.get(&format!("lut_parse/std_loader/{f}"));
        let bytes = v.bytes.unwrap_or(f64::NAN);
        let mib = |x: &Est| fmt_ns(x.mean / bytes * 1_048_576.0);
        s += &row(&[
            format!("`{f}`"),
            format!("{:.1} KiB", bytes / 1024.0),
            fmt_ns(v.mean),
            mib(v),
            sl.map_or("–".into(), |x| fmt_ns(x.mean)),
            sl.map_or("–".into(), mib),
        ]);
    }
    s
}

/// The callgrind section's object and the table of every criterion result.
fn cg_and_raw(d: &Data) -> (Value, String) {
    let cg = match &d.cg {
        Ok(rows) => {
            let mut s = String::new();
            for (k, what, per) in rows {
                s += &row(&[format!("`{k}`"), what.clone(), format!("{per:.0}")]);
            }
            context! { ok => true, rows => s }
        }
        Err(why) => context! { ok => false, why => why },
    };
    let mut raw = String::new();
    for (id, x) in &d.est {
        let (lo, hi) = x.per_call_ci();
        let (mean, lo, hi) = if x.bytes.is_some() {
            (x.mean, x.lo, x.hi)
        } else {
            (x.per_call(), lo, hi)
        };
        raw += &row(&[
            format!("`{id}`"),
            fmt_ns(mean),
            format!("{} – {}", fmt_ns(lo), fmt_ns(hi)),
        ]);
    }
    (cg, raw)
}

/// The machine, the settings, the constants the prose names and the headline verdicts.
fn head(d: &Data) -> Value {
    let m = &d.machine;
    let dn = DEFAULT_NODES;
    let direct32 = d.per(&format!("g_direct_f32_libm/n{dn:02}"));
    let direct64 = d.per(&format!("g_direct_f64/n{dn:02}"));
    let lut = |id: &str, t: f64| verdict(ratio(direct32, d.per(id)), t);
    let dfg_lut = d.per("dfg/lut_f32");
    let dfg = |id: &str| verdict(ratio(d.per(id), dfg_lut), 50.0);
    context! {
        cpu => m.cpu, cores => m.cores, os => m.os, rustc => m.rustc,
        warm_up => d.warm_up.to_string(),
        measurement => d.measurement.to_string(),
        sample_size => d.sample_size,
        secs => format!("{:.0}", d.secs),
        t_crit => format!("{:.0}", d.t_crit),
        dn => dn,
        sigma => SIGMA.to_string(),
        batch => crate::BATCH,
        batch_len => crate::BATCH_LEN,
        g3_linear_asset => crate::G3_LINEAR_ASSET,
        g2_linear_asset => crate::G2_LINEAR_ASSET,
        g3_asset => crate::G3_ASSET,
        g2_asset => crate::G2_ASSET,
        v_g3_linear => lut("g_lut/table3d_linear", 10.0),
        v_g2_linear => lut("g_lut/table2d_sigma0.3_linear", 30.0),
        v_g3 => lut("g_lut/table3d", 10.0),
        v_g2 => lut("g_lut/table2d_sigma0.3", 30.0),
        v_peer => match d.peer_ns() {
            Some(p) => verdict(ratio(Some(p), direct64), 1000.0),
            None => "peer skipped (SciPy not importable)".into(),
        },
        v_dfg_direct => dfg("dfg_direct/split_sum_f64"),
        v_dfg_albedo => dfg("dfg_direct/directional_albedo_f64"),
        direct32 => ns(direct32),
        direct64 => ns(direct64),
        dfg_linear_asset => crate::DFG_LINEAR_ASSET,
        dfg_asset => crate::DFG_ASSET,
        g_points => d.acc.g_points,
        dfg_points => d.acc.dfg_points,
    }
}

/// The report's Markdown.
pub fn render(d: &Data) -> Result<String, minijinja::Error> {
    let (model_rows, batch_rows) = model_and_batch_rows(d);
    let (cg, raw_rows) = cg_and_raw(d);
    let gen = d.gen.map(|(secs, bytes, files)| {
        context! {
            files => files,
            kib => format!("{:.0}", bytes as f64 / 1024.0),
            secs => format!("{secs:.1}"),
        }
    });
    let ctx = context! {
        kernel_target_rows => targets::kernel_target_rows(d),
        python => targets::python_context(&d.python),
        node_rows => node_rows(d),
        table_rows => table_rows(d),
        limits => Value::from_serialize(limits(d)),
        closed_rows => closed_rows(d),
        peer => peer(d),
        dfg => dfg(d),
        parse_rows => parse_rows(d),
        table_generation => d.tablegen.as_ref().map(render_tablegen).transpose()?,
        model_rows, batch_rows, gen, cg, raw_rows,
        ..head(d)
    };
    fill(TEMPLATE, ctx)
}

const TABLE_GENERATION: &str = include_str!("../../templates/table_generation.md");

/// One generation row's cells: wall time, µs per node (wall and per core), evaluations per
/// node.
fn timing(t: &Timing, threads: usize) -> Value {
    let us = t.secs / t.nodes as f64 * 1e6;
    context! {
        name => format!("`{}`", t.name),
        nodes => t.nodes,
        secs => format!("{:.2} s", t.secs),
        us => format!("{us:.2}"),
        us_core => format!("{:.2}", us * threads as f64),
        evals => t.evals.map_or("—".into(), |e| format!("{:.0}", e as f64 / t.nodes as f64)),
    }
}

/// The "Table generation" section (template `templates/table_generation.md`).
pub fn render_tablegen(t: &TableGen) -> Result<String, minijinja::Error> {
    let tables: Vec<Value> = t.tables.iter().map(|x| timing(x, t.threads)).collect();
    let (nodes, secs) = t
        .tables
        .iter()
        .fold((0, 0.0), |a, x| (a.0 + x.nodes, a.1 + x.secs));
    let k_us = t.khronos.secs / t.khronos.nodes as f64 * 1e6;
    let x = |r: f64| format!("{r:.2}×");
    let peer = match &t.peer {
        Ok(p) => context! {
            ran => true, versions => p.versions, us => format!("{:.2}", p.us_per_texel),
            max_error => format!("{:.1e}", p.max_error),
            grazing => format!("{:.1e}", p.grazing_max_error),
        },
        Err(why) => context! { ran => false, why => why },
    };
    let p_us = t.peer.as_ref().map_or(f64::NAN, |p| p.us_per_texel);
    let ctx = context! {
        threads => t.threads, stride => t.stride, shrunk => t.shrunk,
        th => if t.stride == 1 { "" } else { "th" },
        k_rows => tablegen::KHRONOS_SIZE.div_ceil(t.stride.max(1)),
        tables, n_tables => t.tables.len(), total_nodes => nodes,
        total_secs => format!("{secs:.2} s"),
        total_us => format!("{:.2}", secs / nodes as f64 * 1e6),
        khronos => timing(&t.khronos, t.threads),
        samples => tablegen::PEER_SAMPLES,
        tol => format!("{:.0e}", tablegen::REFERENCE_TOL),
        peer, ratio_wall => x(k_us / p_us), ratio_core => x(k_us * t.threads as f64 / p_us),
    };
    fill(TABLE_GENERATION, ctx)
}

/// The one Markdown-template renderer of the workspace (`brdf_engine_assets::report::fill`).
pub use brdf_engine_assets::report::fill;

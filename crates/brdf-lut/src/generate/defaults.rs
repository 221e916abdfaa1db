//! The default asset set (the committed `assets/*.blut`), as specs of the one generator.
//! `cargo xtask lut` builds it and `cargo xtask lut --check` compares it byte for byte with
//! the committed files.

use super::{AxisSpec, Distribution, Kind, Masking, Spec, MU_MIN};
use crate::{Interpolation, Warp};
use core::f64::consts::FRAC_PI_2;
use std::format;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

/// The generator name recorded in the default set's headers (no version number:
/// regenerating must not change bytes when only a crate version changes).
pub const DEFAULT_SET_TOOL: &str = "brdf-kernels xtask lut";

/// One table of the default set: its file name and spec.
#[derive(Clone, Debug, PartialEq)]
pub struct Asset {
    /// The file name in `assets/`.
    pub file: String,
    /// What to build.
    pub spec: Spec,
}

fn asset(file: impl Into<String>, mut spec: Spec, axes: Vec<AxisSpec>, samples: u32) -> Asset {
    spec.axes = axes;
    spec.samples = samples;
    spec.tool = DEFAULT_SET_TOOL.to_string();
    Asset {
        file: file.into(),
        spec,
    }
}

fn theta_phi(nt: u32, np: u32) -> Vec<AxisSpec> {
    vec![
        AxisSpec::endpoint(nt, 0.0, FRAC_PI_2, Warp::SqrtCos),
        AxisSpec::endpoint(np, -FRAC_PI_2, FRAC_PI_2, Warp::Linear),
    ]
}

/// μ from cos 89° to 1 and perceptual roughness from 0 to 1.
fn mu_r(n: u32, mu_warp: Warp, r_warp: Warp) -> Vec<AxisSpec> {
    vec![
        AxisSpec::endpoint(n, MU_MIN, 1.0, mu_warp),
        AxisSpec::endpoint(n, 0.0, 1.0, r_warp),
    ]
}

fn linear(mut s: Spec) -> Spec {
    s.interpolation = Interpolation::Linear;
    s
}

/// The modified G's passing-factor tables: Catmull–Rom (accuracy) and linear on denser
/// grids (speed), over σ and for fixed σ.
fn g_tables(v: &mut Vec<Asset>) {
    let ts = |k| Spec::new(k, Distribution::TorranceSparrow, Masking::Modified);
    let over = |nt, np, ns| {
        let mut a = theta_phi(nt, np);
        a.push(AxisSpec::endpoint(ns, 0.05, 1.0, Warp::Log));
        a
    };
    // G's interpolation error has a heavy tail near the kinks θr = ±θi and at small σ: the
    // G tables are measured at 1–2 million points, so that the recorded maximum is one that
    // `lut verify` at fresh points stays within.
    let g3 = ts(Kind::GOverSigma);
    v.push(asset(
        "g_modified.blut",
        g3.clone(),
        over(64, 64, 31),
        2_000_000,
    ));
    for s in [0.1, 0.3, 0.5] {
        let g2 = ts(Kind::GPerSigma { sigma: s });
        let file = format!("g_modified_sigma{s}.blut");
        v.push(asset(file, g2, theta_phi(128, 126), 1_000_000));
    }
    // The speed tier: two taps per axis instead of four (docs/benchmarks.md: ~10x and ~30x
    // faster than direct G at ~1e-4 rather than ~1e-5), within the cubic tables' size
    // budgets. The 3-D table's max |G error| is set by the bilinear error across the kinks
    // θr = ±θi, which falls only linearly with the spacing: about 1.7e-3 at this size.
    let lin3 = linear(g3);
    v.push(asset(
        "g_modified_linear.blut",
        lin3,
        over(56, 79, 28),
        2_000_000,
    ));
    let lin2 = linear(ts(Kind::GPerSigma { sigma: 0.3 }));
    let file = "g_modified_sigma0.3_linear.blut";
    v.push(asset(file, lin2, theta_phi(96, 127), 1_000_000));
}

/// The split-sum and Kulla–Conty tables.
fn split_sum_tables(v: &mut Vec<Asset>) {
    let ggx = |k| Spec::new(k, Distribution::Ggx, Masking::SmithCorrelated);
    v.push(asset(
        "dfg_ggx.blut",
        ggx(Kind::SplitSum),
        mu_r(64, Warp::Log, Warp::Linear),
        20_000,
    ));
    // The speed tier of the split-sum table: bilinear on √-warped axes (denser toward
    // grazing μ and small roughness, where A and B bend most): a lookup is two square
    // roots and four two-channel taps.
    v.push(asset(
        "dfg_ggx_linear.blut",
        linear(ggx(Kind::SplitSum)),
        mu_r(256, Warp::Sqrt, Warp::Sqrt),
        20_000,
    ));
    let ts_axes = || {
        vec![
            AxisSpec::endpoint(48, MU_MIN, 1.0, Warp::Log),
            AxisSpec::endpoint(32, 0.05, 1.0, Warp::Log),
        ]
    };
    for (file, masking, n) in [
        ("dfg_ts_modified.blut", Masking::Modified, 2_000),
        ("dfg_ts_smith.blut", Masking::SmithCorrelated, 10_000),
    ] {
        let s = Spec::new(Kind::SplitSum, Distribution::TorranceSparrow, masking);
        v.push(asset(file, s, ts_axes(), n));
    }
    for (name, d) in [
        ("ggx", Distribution::Ggx),
        ("beckmann", Distribution::Beckmann),
    ] {
        let e = Spec::new(Kind::Albedo, d, Masking::SmithCorrelated);
        let axes = mu_r(64, Warp::Log, Warp::Linear);
        v.push(asset(format!("kc_e_{name}.blut"), e, axes, 10_000));
        let avg = Spec::new(Kind::AverageAlbedo, d, Masking::SmithCorrelated);
        let axis = vec![AxisSpec::endpoint(32, 0.0, 1.0, Warp::Linear)];
        v.push(asset(format!("kc_eavg_{name}.blut"), avg, axis, 500));
    }
}

/// The default set, in the order `cargo xtask lut` builds it.
pub fn default_set() -> Vec<Asset> {
    let mut v = Vec::new();
    g_tables(&mut v);
    split_sum_tables(&mut v);
    v
}

//! The default asset set: what each table holds, its grid and its direct kernel.

use brdf_core::masking::ModifiedG;
use brdf_core::split_sum::{
    dfg_ggx, dfg_ts_modified, dfg_ts_smith, e_avg_beckmann, e_avg_ggx, e_beckmann, e_ggx,
    InnerRule, OuterRule,
};
use brdf_lut::{Axis, Encoding, Interpolation, Model, Placement, TableKind, Warp};
use std::f64::consts::FRAC_PI_2;

/// cos 89°: the smallest μ the split-sum accuracy target covers.
pub const MU_MIN: f64 = 0.017_452_406_437_283_5;

/// One table to generate.
#[derive(Clone, Debug)]
pub struct Spec {
    pub file: String,
    pub kind: TableKind,
    pub model: Model,
    pub sigma: Option<f64>,
    pub axes: Vec<Axis<'static>>,
    pub channels: Vec<&'static str>,
    pub encoding: Encoding,
    pub interpolation: Interpolation,
    pub samples: u32,
}

fn axis(
    name: &'static str,
    count: u32,
    lo: f64,
    hi: f64,
    warp: Warp,
    placement: Placement,
) -> Axis<'static> {
    Axis {
        name,
        count,
        lo,
        hi,
        warp,
        placement,
    }
}

/// Axes of a passing-factor table F(θ, φ).
fn g_axes(nt: u32, np: u32) -> Vec<Axis<'static>> {
    vec![
        axis(
            "theta",
            nt,
            0.0,
            FRAC_PI_2,
            Warp::SqrtCos,
            Placement::Endpoint,
        ),
        axis(
            "phi",
            np,
            -FRAC_PI_2,
            FRAC_PI_2,
            Warp::Linear,
            Placement::Endpoint,
        ),
    ]
}

/// The default set.
pub fn default_set() -> Vec<Spec> {
    let mut v = Vec::new();
    // G's interpolation error has a heavy tail near the kinks θr = ±θi and at small σ: the
    // G tables are measured at 1–2 million points, so that the recorded maximum is one that
    // `lut verify` at fresh points stays within.
    let mut ax3 = g_axes(64, 64);
    ax3.push(axis("sigma", 31, 0.05, 1.0, Warp::Log, Placement::Endpoint));
    v.push(Spec {
        file: "g_modified.blut".into(),
        kind: TableKind::PassingFactor,
        model: Model::ModifiedG,
        sigma: None,
        axes: ax3,
        channels: vec!["F"],
        encoding: Encoding::Unorm16,
        interpolation: Interpolation::CatmullRom,
        samples: 2_000_000,
    });
    for s in [0.1, 0.3, 0.5] {
        v.push(Spec {
            file: format!("g_modified_sigma{s}.blut"),
            kind: TableKind::PassingFactor,
            model: Model::ModifiedG,
            sigma: Some(s),
            axes: g_axes(128, 126),
            channels: vec!["F"],
            encoding: Encoding::Unorm16,
            interpolation: Interpolation::CatmullRom,
            samples: 1_000_000,
        });
    }
    // The speed tier: the same passing factor read with (bi/tri)linear interpolation, two taps
    // per axis instead of four (docs/benchmarks.md: ~10x and ~30x faster than direct G, at
    // ~1e-4 rather than ~1e-5 accuracy), within the same size budgets as the cubic tables.
    // The 3-D table's max |G error| is set by the bilinear error across the kinks
    // θr = ±θi, which falls only linearly with the spacing: about 1.7e-3 at this size (no
    // grid within 256 KiB reaches 1e-3), so its error is measured at 2,000,000 points to make
    // the recorded maximum one that fresh points do not exceed (`lut verify`).
    let mut ax3 = g_axes(56, 79);
    ax3.push(axis("sigma", 28, 0.05, 1.0, Warp::Log, Placement::Endpoint));
    v.push(Spec {
        file: "g_modified_linear.blut".into(),
        kind: TableKind::PassingFactor,
        model: Model::ModifiedG,
        sigma: None,
        axes: ax3,
        channels: vec!["F"],
        encoding: Encoding::Unorm16,
        interpolation: Interpolation::Linear,
        samples: 2_000_000,
    });
    v.push(Spec {
        file: "g_modified_sigma0.3_linear.blut".into(),
        kind: TableKind::PassingFactor,
        model: Model::ModifiedG,
        sigma: Some(0.3),
        axes: g_axes(96, 127),
        channels: vec!["F"],
        encoding: Encoding::Unorm16,
        interpolation: Interpolation::Linear,
        samples: 1_000_000,
    });
    let dfg_axes = |n: u32| {
        vec![
            axis("mu", n, MU_MIN, 1.0, Warp::Log, Placement::Endpoint),
            axis("roughness", n, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
        ]
    };
    v.push(Spec {
        file: "dfg_ggx.blut".into(),
        kind: TableKind::SplitSum,
        model: Model::GgxSmithCorrelated,
        sigma: None,
        axes: dfg_axes(64),
        channels: vec!["A", "B"],
        encoding: Encoding::Unorm16,
        interpolation: Interpolation::CatmullRom,
        samples: 20_000,
    });
    // The speed tier of the split-sum table: bilinear on √-warped axes (denser toward
    // grazing μ and small roughness, where A and B bend most), so that a lookup is two
    // square roots and four two-channel taps, with max |ΔA|, |ΔB| still ~1000× below
    // Karis's analytic fit (docs/benchmarks.md).
    v.push(Spec {
        file: "dfg_ggx_linear.blut".into(),
        kind: TableKind::SplitSum,
        model: Model::GgxSmithCorrelated,
        sigma: None,
        axes: vec![
            axis("mu", 256, MU_MIN, 1.0, Warp::Sqrt, Placement::Endpoint),
            axis("roughness", 256, 0.0, 1.0, Warp::Sqrt, Placement::Endpoint),
        ],
        channels: vec!["A", "B"],
        encoding: Encoding::Unorm16,
        interpolation: Interpolation::Linear,
        samples: 20_000,
    });
    let ts_axes = || {
        vec![
            axis("mu", 48, MU_MIN, 1.0, Warp::Log, Placement::Endpoint),
            axis("sigma", 32, 0.05, 1.0, Warp::Log, Placement::Endpoint),
        ]
    };
    for (file, model, n) in [
        (
            "dfg_ts_modified.blut",
            Model::TorranceSparrowModifiedG,
            2_000,
        ),
        ("dfg_ts_smith.blut", Model::TorranceSparrowSmith, 10_000),
    ] {
        v.push(Spec {
            file: file.into(),
            kind: TableKind::SplitSum,
            model,
            sigma: None,
            axes: ts_axes(),
            channels: vec!["A", "B"],
            encoding: Encoding::Unorm16,
            interpolation: Interpolation::CatmullRom,
            samples: n,
        });
    }
    for (name, model) in [
        ("ggx", Model::GgxSmithCorrelated),
        ("beckmann", Model::BeckmannSmithCorrelated),
    ] {
        v.push(Spec {
            file: format!("kc_e_{name}.blut"),
            kind: TableKind::DirectionalAlbedo,
            model,
            sigma: None,
            axes: vec![
                axis("mu", 64, MU_MIN, 1.0, Warp::Log, Placement::Endpoint),
                axis("roughness", 64, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
            ],
            channels: vec!["E"],
            encoding: Encoding::Unorm16,
            interpolation: Interpolation::CatmullRom,
            samples: 10_000,
        });
        v.push(Spec {
            file: format!("kc_eavg_{name}.blut"),
            kind: TableKind::AverageAlbedo,
            model,
            sigma: None,
            axes: vec![axis(
                "roughness",
                32,
                0.0,
                1.0,
                Warp::Linear,
                Placement::Endpoint,
            )],
            channels: vec!["Eavg"],
            encoding: Encoding::Unorm16,
            interpolation: Interpolation::CatmullRom,
            samples: 500,
        });
    }
    v
}

/// The direct kernel at a grid node: one value per channel (f64).
pub fn node_value(kind: TableKind, model: Model, sigma: Option<f64>, x: &[f64]) -> Vec<f64> {
    match kind {
        TableKind::PassingFactor => {
            let s = sigma.unwrap_or_else(|| x[2]);
            let g = ModifiedG::<f64>::new(s).expect("sigma > 0");
            let (theta, phi) = (x[0], x[1]);
            vec![g.passing(theta, (theta - phi) * 0.5)]
        }
        TableKind::SplitSum => {
            let (a, b) = dfg(model, x[0], x[1]);
            vec![a, b]
        }
        TableKind::DirectionalAlbedo => vec![albedo(model, x[0], x[1])],
        TableKind::AverageAlbedo => vec![match model {
            Model::BeckmannSmithCorrelated => e_avg_beckmann::<f64, OuterRule, InnerRule>(x[0]),
            _ => e_avg_ggx::<f64, OuterRule, InnerRule>(x[0]),
        }],
    }
}

pub fn dfg(model: Model, mu: f64, r: f64) -> (f64, f64) {
    match model {
        Model::TorranceSparrowModifiedG => dfg_ts_modified::<f64, OuterRule, InnerRule>(mu, r),
        Model::TorranceSparrowSmith => dfg_ts_smith::<f64, OuterRule, InnerRule>(mu, r),
        _ => dfg_ggx::<f64, OuterRule, InnerRule>(mu, r),
    }
}

pub fn albedo(model: Model, mu: f64, r: f64) -> f64 {
    match model {
        Model::BeckmannSmithCorrelated => e_beckmann::<f64, OuterRule, InnerRule>(mu, r),
        _ => e_ggx::<f64, OuterRule, InnerRule>(mu, r),
    }
}

/// The verification domain of one axis: its range, except μ ≥ cos 89° for split sums and
/// albedos (the accuracy target's domain) when the axis reaches that far.
pub fn verify_range(kind: TableKind, a: &Axis<'_>) -> (f64, f64) {
    if a.name == "mu" && kind != TableKind::PassingFactor && a.hi > MU_MIN {
        (a.lo.max(MU_MIN), a.hi)
    } else {
        (a.lo, a.hi)
    }
}

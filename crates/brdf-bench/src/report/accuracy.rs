//! Accuracy on the benchmark's own domain, so that "matched accuracy" is measured, not
//! assumed.

use crate::{angle_pairs, env_brdf_approx, mu_roughness, read_asset, SIGMA};
use brdf_core::masking::ModifiedG;
use brdf_core::quadrature::{GaussLegendre, NODE_COUNTS};
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use brdf_lut::{DfgTable, GTable, GTable3};
use serde::{Deserialize, Serialize};

/// Max errors of each G and DFG method against its f64 reference.
#[derive(Serialize, Deserialize)]
pub struct Accuracy {
    /// (node count, max |G_N − G_32| in f64, in f32).
    pub g_direct: Vec<(usize, f64, f64)>,
    /// The 3-D G table (tricubic).
    pub g_lut3: Option<f64>,
    /// The per-σ 2-D G table (bicubic).
    pub g_lut2: Option<f64>,
    /// The 3-D G table, speed tier.
    pub g_lut3_linear: Option<f64>,
    /// The per-σ 2-D G table, speed tier.
    pub g_lut2_linear: Option<f64>,
    /// max |ΔA|, |ΔB| against the split-sum integral (f64).
    pub dfg_lut: Option<(f64, f64)>,
    /// The same for the speed tier (bilinear) table.
    pub dfg_lut_linear: Option<(f64, f64)>,
    /// The same for Karis's analytic fit.
    pub dfg_karis: (f64, f64),
    /// In-plane pairs of the G errors.
    pub g_points: usize,
    /// (μ, r) points of the DFG errors.
    pub dfg_points: usize,
}

/// G errors: max |G − G₃₂| over `n` in-plane pairs ([`angle_pairs`], σ = [`SIGMA`]) of the
/// direct quadrature at each node count (f64 and f32) and of the default set's G tables
/// (`None` where the asset is missing).
#[allow(clippy::type_complexity)]
fn g_errors(n: usize) -> (Vec<(usize, f64, f64)>, [Option<f64>; 4]) {
    let (ti, tr) = angle_pairs::<f64>(n);
    let reference = ModifiedG::<f64, GaussLegendre<32>>::new(SIGMA).expect("sigma > 0");
    let gref: Vec<f64> = ti
        .iter()
        .zip(&tr)
        .map(|(&a, &b)| reference.g(a, b))
        .collect();
    let max_err = |f: &dyn Fn(f64, f64) -> f64| {
        ti.iter()
            .zip(&tr)
            .zip(&gref)
            .map(|((&a, &b), &r)| (f(a, b) - r).abs())
            .fold(0.0, f64::max)
    };
    let mut g_direct = Vec::new();
    macro_rules! at {
        ($($n:literal),*) => {$({
            let g64 = ModifiedG::<f64, GaussLegendre<$n>>::new(SIGMA).unwrap();
            let g32 = ModifiedG::<f32, GaussLegendre<$n>>::new(SIGMA as f32).unwrap();
            g_direct.push((
                $n,
                max_err(&|a, b| g64.g(a, b)),
                max_err(&|a, b| g32.g(a as f32, b as f32) as f64),
            ));
        })*};
    }
    at!(4, 6, 8, 10, 12, 16, 20, 24, 32);
    debug_assert_eq!(g_direct.len(), NODE_COUNTS.len());
    let err3 = |asset: &str| {
        let b = read_asset(asset)?;
        let t = GTable3::parse(&b).ok()?;
        Some(max_err(&|a, c| {
            t.g(a as f32, c as f32, SIGMA as f32) as f64
        }))
    };
    let err2 = |asset: &str| {
        let b = read_asset(asset)?;
        let t = GTable::parse(&b).ok()?;
        Some(max_err(&|a, c| t.g(a as f32, c as f32) as f64))
    };
    let tables = [
        err3(crate::G3_ASSET),
        err2(crate::G2_ASSET),
        err3(crate::G3_LINEAR_ASSET),
        err2(crate::G2_LINEAR_ASSET),
    ];
    (g_direct, tables)
}

/// DFG errors over `n` (μ, r) points ([`mu_roughness`]) against the f64 split-sum integral:
/// the accuracy tier table, the speed tier table, Karis's fit.
#[allow(clippy::type_complexity)]
fn dfg_errors(n: usize) -> (Option<(f64, f64)>, Option<(f64, f64)>, (f64, f64)) {
    let pts = mu_roughness(n);
    let exact: Vec<(f64, f64)> = pts
        .iter()
        .map(|&(m, r)| dfg_ggx::<f64, OuterRule, InnerRule>(m, r))
        .collect();
    let dfg_err = |f: &dyn Fn(f64, f64) -> (f64, f64)| {
        pts.iter()
            .zip(&exact)
            .fold((0.0f64, 0.0f64), |acc, (&(m, r), &(ea, eb))| {
                let (a, b) = f(m, r);
                (acc.0.max((a - ea).abs()), acc.1.max((b - eb).abs()))
            })
    };
    let table = |asset: &str| {
        let b = read_asset(asset)?;
        let t = DfgTable::parse(&b).ok()?;
        Some(dfg_err(&|m, r| {
            let (a, b) = t.ab(m as f32, r as f32);
            (a as f64, b as f64)
        }))
    };
    let karis = dfg_err(&|m, r| {
        let (a, b) = env_brdf_approx(m as f32, r as f32);
        (a as f64, b as f64)
    });
    (
        table(crate::DFG_ASSET),
        table(crate::DFG_LINEAR_ASSET),
        karis,
    )
}

/// The accuracy figures of the report: 4,000 G pairs, 96 DFG points.
pub fn accuracy() -> Accuracy {
    let (g_points, dfg_points) = (4000, 96);
    let (g_direct, [g_lut3, g_lut2, g_lut3_linear, g_lut2_linear]) = g_errors(g_points);
    let (dfg_lut, dfg_lut_linear, dfg_karis) = dfg_errors(dfg_points);
    Accuracy {
        g_direct,
        g_lut3,
        g_lut2,
        g_lut3_linear,
        g_lut2_linear,
        dfg_lut,
        dfg_lut_linear,
        dfg_karis,
        g_points,
        dfg_points,
    }
}

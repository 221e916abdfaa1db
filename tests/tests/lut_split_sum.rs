//! The split-sum kernels (`brdf_core::split_sum`, what the tables are generated from) against
//! an independent route: adaptive Gauss–Kronrod over the LIGHT direction (θl, φl) of
//! D · G · F / (4 μ) (the BRDF times cos θl), instead of the kernels' half-vector CDF
//! parametrisation with fixed rules.

use brdf_core::masking::ModifiedG;
use brdf_core::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use brdf_core::split_sum::{
    dfg_ggx, dfg_ts_modified, dfg_ts_smith, e_avg, e_ggx, InnerRule, OuterRule,
};
use brdf_core::{Dots, Vec3};
use brdf_tests::reference::integrate;
use std::f64::consts::PI;

/// (A, B) by adaptive quadrature over the light hemisphere; `f(nh, nl, dots)` = D·G/(4μ·nl)·nl
/// without F, i.e. the BRDF's F-free part times cos θl.
fn reference(mu: f64, f: &dyn Fn(f64, f64, Dots<f64>) -> f64) -> (f64, f64) {
    let sv = (1.0 - mu * mu).sqrt();
    let v = Vec3::new(sv, 0.0, mu);
    let theta_v = sv.atan2(mu);
    let ch = |fc_weight: bool| {
        integrate(
            |tl| {
                2.0 * integrate(
                    |pl| {
                        let l = Vec3::new(tl.sin() * pl.cos(), tl.sin() * pl.sin(), tl.cos());
                        let Some(h) = l.add(v).normalize() else {
                            return 0.0;
                        };
                        let vh = v.dot(h);
                        let fc = (1.0 - vh).max(0.0).powi(5);
                        let w = if fc_weight { fc } else { 1.0 - fc };
                        // v.z = μ exactly.
                        let d = Dots::from_local(l, v);
                        w * f(h.z, l.z, d) * tl.sin()
                    },
                    0.0,
                    PI,
                    &[0.05, 0.2],
                    1e-10,
                )
            },
            0.0,
            PI / 2.0,
            &[theta_v * 0.9, theta_v, (theta_v * 1.1).min(1.5), 1.5, 1.55],
            1e-9,
        )
    };
    (ch(false), ch(true))
}

#[test]
fn ggx_split_sum_matches_light_direction_quadrature() {
    let mut worst = 0f64;
    for &mu in &[0.017_452_406_437_283_5, 0.1, 0.5, 0.9] {
        for &r in &[0.3, 0.5, 0.8, 1.0] {
            let alpha = r * r;
            let (ra, rb) = reference(mu, &|nh, nl, _| {
                TrowbridgeReitz::d_cos(nh, alpha)
                    * TrowbridgeReitz::v_correlated_cos(nl, mu, alpha)
                    * nl
            });
            let (a, b) = dfg_ggx::<f64, OuterRule, InnerRule>(mu, r);
            let e = (a - ra).abs().max((b - rb).abs());
            println!(
                "GGX mu {mu:.4} r {r}: A {a:.6} ref {ra:.6}  B {b:.6} ref {rb:.6}  |d| {e:.1e}"
            );
            worst = worst.max(e);
        }
    }
    assert!(worst <= 1e-4, "worst {worst:e}");
}

#[test]
fn torrance_sparrow_split_sums_match_light_direction_quadrature() {
    for &(mu, s) in &[(0.05, 0.3), (0.5, 0.3), (0.3, 0.7), (0.9, 1.0)] {
        let m = std::f64::consts::SQRT_2 * s;
        let (ra, rb) = reference(mu, &|nh, nl, _| {
            Beckmann::d_cos(nh, m) * Beckmann::g_correlated_cos(nl, mu, m) / (4.0 * mu)
        });
        let (a, b) = dfg_ts_smith::<f64, OuterRule, InnerRule>(mu, s);
        println!("TS-Smith mu {mu} s {s}: A {a:.6} ref {ra:.6}  B {b:.6} ref {rb:.6}");
        assert!((a - ra).abs() <= 1e-4 && (b - rb).abs() <= 1e-4);
        let g = ModifiedG::<f64>::new(s).unwrap();
        let (ra, rb) = reference(mu, &|nh, _, d| {
            Beckmann::d_cos(nh, m) * g.g_dots(d) / (4.0 * mu)
        });
        let (a, b) = dfg_ts_modified::<f64, OuterRule, InnerRule>(mu, s);
        println!("TS-modified mu {mu} s {s}: A {a:.6} ref {ra:.6}  B {b:.6} ref {rb:.6}");
        assert!((a - ra).abs() <= 1e-4 * ra.max(1.0) && (b - rb).abs() <= 1e-4 * rb.max(1.0));
    }
}

#[test]
fn mirror_limit_and_average_albedo() {
    // r = 0: a perfect mirror, A + B = 1, B = (1 − μ)⁵ (Schlick at the mirror direction).
    for &mu in &[0.02, 0.3, 1.0] {
        let (a, b) = dfg_ggx::<f64, OuterRule, InnerRule>(mu, 0.0);
        assert!((a + b - 1.0).abs() < 1e-12 && (b - (1.0f64 - mu).powi(5)).abs() < 1e-12);
    }
    // E_avg of a constant E is E itself (2∫μ dμ = 1).
    let c = e_avg::<f64, brdf_core::quadrature::GaussLegendre<24>>(|_| 0.7);
    assert!((c - 0.7).abs() < 1e-12);
    // Energy conservation: E(μ, r) ≤ 1 for the Smith models; E ≈ 1 for a smooth surface.
    for &mu in &[0.02, 0.2, 0.7, 1.0] {
        for &r in &[0.05, 0.4, 1.0] {
            let e = e_ggx::<f64, OuterRule, InnerRule>(mu, r);
            assert!(e <= 1.0 + 1e-6 && e > 0.0, "E({mu},{r}) = {e}");
        }
    }
    assert!(e_ggx::<f64, OuterRule, InnerRule>(0.8, 0.05) > 0.999);
}

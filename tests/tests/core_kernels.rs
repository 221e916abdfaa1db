//! Blinn, Smith, Fresnel, the distributions, the 3-D extension of the modified G, the
//! Torrance–Sparrow BRDF, and bad input — each against an independent reference or law.

use brdf_core::fresnel::{f_dielectric, f_schlick, r0_from_ior, Fresnel};
use brdf_core::geometry::{in_plane_directions, Dots, Vec3};
use brdf_core::masking::{g_blinn, g_blinn_dots, Convention, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use brdf_core::models::{GeometricTerm, TorranceSparrow};
use brdf_core::ParamError;
use brdf_tests::reference::{integrate, lambda_beckmann_ref};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};

const DEG: f64 = PI / 180.0;

/// A random upper-hemisphere direction: cos θ uniform in [1e-3, 1), φ uniform.
fn dir_upper(rng: &mut Pcg64) -> Vec3<f64> {
    let z = rng.random::<f64>().max(1e-3);
    let phi = 2.0 * PI * rng.random::<f64>();
    let r = (1.0 - z * z).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

#[test]
fn blinn_matches_eq4_geometry() {
    // Eq 4 evaluated from the vectors of Fig. 1: h = (wi + wo)/|wi + wo|.
    for i in 0..=18 {
        for j in -18..=18 {
            let (ti, tr) = (i as f64 * 5.0 * DEG, j as f64 * 5.0 * DEG);
            let (wi, wo) = in_plane_directions(ti, tr);
            let Some(h) = wi.add(wo).normalize() else {
                continue;
            };
            let n = Vec3::new(0.0, 0.0, 1.0);
            let want = 1f64
                .min(2.0 * n.dot(h) * n.dot(wo) / wo.dot(h))
                .min(2.0 * n.dot(h) * n.dot(wi) / wo.dot(h))
                .max(0.0);
            let got = g_blinn(ti, tr);
            assert!((got - want).abs() < 1e-12, "({i},{j}): {got} vs {want}");
            let gd = g_blinn_dots(Dots::from_local(wi, wo));
            if ti < FRAC_PI_2 && tr.abs() < FRAC_PI_2 {
                assert!((gd - want).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn smith_beckmann_lambda_matches_slope_integral() {
    for m in [0.07, 0.3, 0.8, 1.4] {
        for t in [5.0, 30.0, 60.0, 80.0, 88.0] {
            let got = Beckmann::lambda_cos(f64::cos(t * DEG), m);
            let want = lambda_beckmann_ref(t * DEG, m);
            assert!(
                (got - want).abs() < 1e-9 * (1.0 + want),
                "m={m} θ={t}: {got} vs {want}"
            );
            let g32 = Beckmann::lambda_cos(f32::cos((t * DEG) as f32), m as f32) as f64;
            // micromath's exp/sqrt are approximations (README accuracy table).
            let tol32 = if cfg!(feature = "micromath") {
                1e-2
            } else {
                1e-4
            };
            assert!(
                (g32 - want).abs() < tol32 * (1.0 + want),
                "f32 m={m} θ={t}: {g32} {want}"
            );
        }
    }
    assert_eq!(Beckmann::g1_cos(1.0, 0.3), 1.0);
    assert_eq!(Beckmann::g1_cos(0.0, 0.3), 0.0);
}

#[test]
fn smith_ggx_closed_forms_agree() {
    // G1 = 2/(1 + √(1 + α² tan²θ)) and V = G2/(4 cos cos) for the correlated form.
    for a in [0.05, 0.3, 1.0] {
        for (ci, co) in [(0.9, 0.2), (0.05, 0.5), (1.0, 1.0), (0.3, 0.3)] {
            let tan2 = |c: f64| (1.0 - c * c) / (c * c);
            let g1 = |c: f64| 2.0 / (1.0 + (1.0 + a * a * tan2(c)).sqrt());
            assert!((TrowbridgeReitz::g1_cos(ci, a) - g1(ci)).abs() < 1e-14);
            let g2 = TrowbridgeReitz::g_correlated_cos(ci, co, a);
            let v = TrowbridgeReitz::v_correlated_cos(ci, co, a);
            assert!(
                (v - g2 / (4.0 * ci * co)).abs() < 1e-12 * v,
                "α={a} {ci} {co}"
            );
            assert!((TrowbridgeReitz::g_separable_cos(ci, co, a) - g1(ci) * g1(co)).abs() < 1e-14);
        }
    }
}

/// ∫ D(h) cos θh dω_h = 1 (projected-area normalisation) for Beckmann and GGX.
#[test]
fn normal_distributions_are_normalised() {
    for r in [0.05f64, 0.2, 0.6, 1.0] {
        let beck = integrate(
            |t| 2.0 * PI * Beckmann::d_cos(t.cos(), r) * t.cos() * t.sin(),
            0.0,
            FRAC_PI_2,
            &[r.atan(), (3.0 * r).atan()],
            1e-12,
        );
        let ggx = integrate(
            |t| 2.0 * PI * TrowbridgeReitz::d_cos(t.cos(), r) * t.cos() * t.sin(),
            0.0,
            FRAC_PI_2,
            &[r.atan(), (3.0 * r).atan(), (30.0 * r).atan()],
            1e-12,
        );
        assert!((beck - 1.0).abs() < 1e-9, "Beckmann m={r}: {beck}");
        assert!((ggx - 1.0).abs() < 1e-9, "GGX α={r}: {ggx}");
    }
}

/// The normals' radial CDF in tan²θh is ∫₀^θ D cos θh dω (adaptive Gauss–Kronrod of D, the
/// same integral as the normalisation above, stopped at θ), and its inverse returns tan²θ.
#[test]
fn normal_cdf_in_tan2_is_the_integral_of_d_cos() {
    for r in [0.05f64, 0.2, 0.6, 1.0] {
        for theta in [0.01f64, 0.1, 0.4, 0.8, 1.2, 1.5] {
            let t2 = theta.tan().powi(2);
            let upto = |d: &dyn Fn(f64) -> f64| {
                let br: Vec<f64> = [r.atan(), (3.0 * r).atan()]
                    .into_iter()
                    .filter(|&b| b < theta)
                    .collect();
                integrate(
                    |t| 2.0 * PI * d(t.cos()) * t.cos() * t.sin(),
                    0.0,
                    theta,
                    &br,
                    1e-13,
                )
            };
            let cases = [
                (
                    "Beckmann",
                    upto(&|c| Beckmann::d_cos(c, r)),
                    Beckmann::normal_cdf_tan2(t2, r),
                    Beckmann::normal_tan2_at_cdf(Beckmann::normal_cdf_tan2(t2, r), r),
                ),
                (
                    "GGX",
                    upto(&|c| TrowbridgeReitz::d_cos(c, r)),
                    TrowbridgeReitz::normal_cdf_tan2(t2, r),
                    TrowbridgeReitz::normal_tan2_at_cdf(TrowbridgeReitz::normal_cdf_tan2(t2, r), r),
                ),
            ];
            for (name, want, got, back) in cases {
                assert!(
                    (got - want).abs() < 1e-10,
                    "{name} α={r} θ={theta}: {got} vs {want}"
                );
                // The round trip loses what 1 − ξ loses: relative 1e-9 until ξ nears 1.
                if want < 1.0 - 1e-6 {
                    assert!(
                        (back - t2).abs() <= 1e-8 * t2,
                        "{name} α={r} θ={theta}: {back}"
                    );
                }
            }
        }
    }
}

#[test]
fn fresnel_terms() {
    // Schlick: exact at both ends.
    assert_eq!(f_schlick(0.04, 1.0), 0.04);
    assert_eq!(f_schlick(0.04, 0.0), 1.0);
    // Exact dielectric: normal incidence equals ((η−1)/(η+1))², grazing 1, Brewster's angle
    // zeroes the p component so F = Rs/2 there.
    for eta in [1.33f64, 1.5, 2.4] {
        assert!((f_dielectric(eta, 1.0) - r0_from_ior(eta)).abs() < 1e-15);
        assert!((f_dielectric(eta, 0.0) - 1.0).abs() < 1e-12);
        let tb = f64::atan(eta);
        let (ci, st) = (tb.cos(), tb.sin() / eta);
        let ct = (1.0 - st * st).sqrt();
        let rs = ((ci - eta * ct) / (ci + eta * ct)).powi(2);
        assert!((f_dielectric(eta, ci) - rs / 2.0).abs() < 1e-12);
        // Schlick is an approximation (Schlick 1994): measured within 0.02 for cos θ ≥ 0.5
        // and up to ≈ 0.075 near grazing (largest for high indices).
        for k in 0..=20 {
            let c = k as f64 / 20.0;
            let d = (f_schlick(r0_from_ior(eta), c) - f_dielectric(eta, c)).abs();
            let tol = if c >= 0.5 { 0.025 } else { 0.08 };
            assert!(d < tol, "η={eta} cos={c}: {d}");
        }
    }
    // Total internal reflection from the dense side.
    assert_eq!(f_dielectric(1.0 / 1.5, 0.3), 1.0);
    assert!(Fresnel::schlick(1.5f64).is_err());
    assert!(Fresnel::dielectric(f64::NAN).is_err());
}

/// The 3-D entry point: coplanar pairs at any azimuth give the in-plane G exactly;
/// out-of-plane pairs are reciprocal and in [0, 1].
#[test]
fn modified_g_3d_extension() {
    let mut rng = Pcg64::seed_from_u64(7);
    for s in [0.1, 0.4, 1.0] {
        let k = ModifiedG::<f64>::new(s).unwrap();
        for _ in 0..300 {
            let ti = 89.0 * rng.random::<f64>() * DEG;
            let tr = (-89.0 + 178.0 * rng.random::<f64>()) * DEG;
            let phi = 2.0 * PI * rng.random::<f64>();
            let (wi, wo) = in_plane_directions(ti, tr);
            let rot = |v: Vec3<f64>| {
                Vec3::new(
                    v.x * phi.cos() - v.y * phi.sin(),
                    v.x * phi.sin() + v.y * phi.cos(),
                    v.z,
                )
            };
            let g3 = k
                .g_vectors(rot(wi), rot(wo), Vec3::new(0.0, 0.0, 1.0))
                .unwrap();
            assert!(
                (g3 - k.g(ti, tr)).abs() < 1e-9,
                "σ={s}: {g3} vs {}",
                k.g(ti, tr)
            );
        }
        for _ in 0..300 {
            let (wi, wo) = (dir_upper(&mut rng), dir_upper(&mut rng));
            let a = k.g_dots(Dots::from_local(wi, wo));
            let b = k.g_dots(Dots::from_local(wo, wi));
            assert!((a - b).abs() < 1e-12 && (0.0..=1.0).contains(&a));
        }
    }
}

#[test]
fn torrance_sparrow_matches_eq3_and_is_reciprocal() {
    let sigma = 0.3;
    let m = SQRT_2 * sigma;
    for g in GeometricTerm::ALL {
        let ts = TorranceSparrow::<f64>::specular(sigma, g).unwrap();
        let kg = ModifiedG::<f64>::new(sigma).unwrap();
        for i in 1..=17 {
            for j in -17..=17 {
                let (ti, tr) = (i as f64 * 5.0 * DEG, j as f64 * 5.0 * DEG);
                // Eq 3 (docs/conventions.md §5) in the paper's angles: α = (θr−θi)/2.
                let alpha = 0.5 * (tr - ti);
                let d = (-(alpha.tan().powi(2)) / (2.0 * sigma * sigma)).exp()
                    / (2.0 * PI * sigma * sigma * alpha.cos().powi(4));
                let gv = match g {
                    GeometricTerm::None => 1.0,
                    GeometricTerm::Blinn => g_blinn(ti, tr),
                    GeometricTerm::SmithSeparable => {
                        Beckmann::g_separable_cos(ti.cos(), tr.cos(), m)
                    }
                    GeometricTerm::SmithCorrelated => {
                        Beckmann::g_correlated_cos(ti.cos(), tr.cos(), m)
                    }
                    GeometricTerm::Modified => kg.g(ti, tr),
                    GeometricTerm::ModifiedPrinted => {
                        kg.with_convention(Convention::Printed).g(ti, tr)
                    }
                };
                let want = d * gv / (4.0 * ti.cos() * tr.cos());
                let got = ts.eval_in_plane(ti, tr);
                assert!(
                    (got - want).abs() <= 1e-9 * want.max(1.0),
                    "{g:?} ({i},{j}) {got} {want}"
                );
                if g != GeometricTerm::ModifiedPrinted {
                    let back = ts.eval_in_plane(tr.abs(), if tr < 0.0 { -ti } else { ti });
                    assert!(
                        (got - back).abs() <= 1e-9 * got.max(1e-12),
                        "{g:?} not reciprocal"
                    );
                }
            }
        }
    }
}

/// With no G, F = 1 and normal incidence, ∫ f cos θo dωo equals the fraction of D's projected
/// area whose mirror direction stays above the horizon (≤ 1); G only lowers it.
#[test]
fn torrance_sparrow_albedo_at_normal_incidence_is_below_one() {
    for sigma in [0.1, 0.3, 0.6] {
        for g in [
            GeometricTerm::None,
            GeometricTerm::Modified,
            GeometricTerm::SmithCorrelated,
        ] {
            let ts = TorranceSparrow::<f64>::specular(sigma, g).unwrap();
            let wi = Vec3::new(0.0, 0.0, 1.0);
            let albedo = integrate(
                |t| {
                    let wo = Vec3::new(t.sin(), 0.0, t.cos());
                    2.0 * PI * ts.eval(wi, wo) * t.cos() * t.sin()
                },
                0.0,
                FRAC_PI_2,
                &[sigma, 2.0 * sigma, 4.0 * sigma],
                1e-10,
            );
            assert!(
                albedo <= 1.0 + 1e-6 && albedo > 0.5,
                "σ={sigma} {g:?}: {albedo}"
            );
        }
    }
}

#[test]
fn checked_constructors_reject_bad_parameters() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = ModifiedG::<f64>::new(bad).unwrap_err();
        assert!(matches!(
            e,
            ParamError::NotFinite { .. } | ParamError::OutOfRange { .. }
        ));
        assert!(TorranceSparrow::<f32>::specular(bad as f32, GeometricTerm::Blinn).is_err());
    }
    assert!(
        TorranceSparrow::<f64>::new(0.3, GeometricTerm::Blinn, Fresnel::One, 1.0, 1.5).is_err()
    );
    assert!(
        TorranceSparrow::<f64>::new(0.3, GeometricTerm::Blinn, Fresnel::One, -1.0, 0.5).is_err()
    );
}

/// Documented results for bad evaluation input.
#[test]
fn documented_results_for_bad_input() {
    let k = ModifiedG::<f64>::new(0.3).unwrap();
    // NaN in, NaN out.
    assert!(k.g(f64::NAN, 0.1).is_nan() && k.g(0.1, f64::NAN).is_nan());
    // Out-of-range angles are clamped to the valid range.
    assert_eq!(k.g(2.0, 0.3), k.g(FRAC_PI_2, 0.3));
    assert_eq!(k.g(-0.5, 0.3), k.g(0.0, 0.3));
    assert_eq!(k.g(0.3, -7.0), k.g(0.3, -FRAC_PI_2));
    assert_eq!(k.g(f64::INFINITY, 0.3), k.g(FRAC_PI_2, 0.3));
    // Zero and non-finite vectors: None.
    let z = Vec3::new(0.0, 0.0, 0.0);
    let up = Vec3::new(0.0, 0.0, 1.0);
    assert_eq!(k.g_vectors(z, up, up), None);
    assert_eq!(k.g_vectors(up, Vec3::new(f64::NAN, 0.0, 1.0), up), None);
    // Non-unit vectors are normalised.
    let (wi, wo) = in_plane_directions(0.4, 0.9);
    assert!(
        (k.g_vectors(wi.scale(3.0), wo.scale(0.2), up.scale(7.0))
            .unwrap()
            - k.g(0.4, 0.9))
        .abs()
            < 1e-12
    );
    // Below the horizon: G = 0 and the BRDF is 0.
    assert_eq!(k.g_dots(Dots::new(-0.2, 0.5, 0.0)), 0.0);
    let ts =
        TorranceSparrow::<f64>::new(0.3, GeometricTerm::Modified, Fresnel::One, 1.0, 0.5).unwrap();
    assert_eq!(ts.eval(Vec3::new(0.0, 0.6, -0.8), up), 0.0);
    // Degenerate pairs: wi = −wo (grazing, opposite), wi = wo = n, grazing both.
    let g1 = Vec3::new(1.0, 0.0, 0.0);
    for (a, b) in [(up, up), (g1, g1.scale(-1.0)), (g1, g1), (up, g1)] {
        for g in GeometricTerm::ALL {
            let ts = TorranceSparrow::<f64>::specular(0.3, g).unwrap();
            let v = ts.eval(a, b);
            assert!(v.is_finite() && v >= 0.0, "{g:?} {a:?} {b:?}: {v}");
        }
    }
    // Tiny and huge σ: finite and in [0, 1].
    for s in [1e-9, 1e-4, 10.0, 1e6] {
        let k = ModifiedG::<f64>::new(s).unwrap();
        let k32 = ModifiedG::<f32>::new(s as f32).unwrap();
        for (ti, tr) in [(0.1, 0.2), (1.5, -1.5), (FRAC_PI_2, FRAC_PI_2), (0.0, 1.0)] {
            let g = k.g(ti, tr);
            let g32 = k32.g(ti as f32, tr as f32);
            assert!(
                (0.0..=1.0).contains(&g) && (0.0..=1.0).contains(&g32),
                "σ={s}: {g} {g32}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Any f64 input (including NaN, ±∞, subnormals): no panic; the result is NaN exactly
    /// when an angle is NaN, and otherwise lies in [0, 1].
    #[test]
    fn any_input_gives_documented_result(ti in proptest::num::f64::ANY, tr in proptest::num::f64::ANY, s in 1e-6f64..1e6) {
        let k = ModifiedG::<f64>::new(s).unwrap();
        for conv in [Convention::Reciprocal, Convention::Printed] {
            let g = k.with_convention(conv).g(ti, tr);
            if ti.is_nan() || tr.is_nan() {
                prop_assert!(g.is_nan());
            } else {
                prop_assert!((0.0..=1.0).contains(&g), "{} {} {} -> {}", ti, tr, s, g);
            }
        }
        let b = g_blinn(ti, tr);
        prop_assert!(b.is_nan() == (ti.is_nan() || tr.is_nan()));
    }

    /// Arbitrary dot-product triples (even inconsistent ones) never panic nor leave [0, 1].
    #[test]
    fn any_dots_give_documented_result(a in -2.0f32..2.0, b in -2.0f32..2.0, c in -2.0f32..2.0) {
        let k = ModifiedG::<f32>::new(0.3).unwrap();
        let g = k.g_dots(Dots::new(a, b, c));
        prop_assert!((0.0..=1.0).contains(&g));
        let ts = TorranceSparrow::<f32>::specular(0.3, GeometricTerm::Modified).unwrap();
        let f = ts.eval_dots(Dots::new(a, b, c));
        prop_assert!(f >= 0.0 && !f.is_nan());
    }
}

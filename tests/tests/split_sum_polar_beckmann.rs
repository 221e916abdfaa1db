//! The polar split-sum rule for Beckmann lobes (`brdf_core::split_sum::polar`,
//! `PolarModel::BeckmannCorrelated` / `BeckmannSeparable`: τ = m s, horizon cut in closed
//! form, K15/G7 panels, nested trapezoid rows in ψ) against independent references:
//!
//! * [`split_sum_beckmann_ref`]: nested adaptive Gauss–Kronrod in the Beckmann CDF variable
//!   q = exp(−tan²θh/m²) (D cos θh dωh = dq dφ/(2π), so the peak of D is flat in q) and the
//!   azimuth φ, cut in closed form per θh, with Λ written out here from its closed form
//!   (Heitz 2014, "Understanding the masking-shadowing function", eq 72, via `libm::erfc`);
//!   tolerance 1e-11 on sums of |K15 − G7| terms (`REF_UNCERTAINTY` allows 1e-10);
//! * the fixed Gauss–Legendre rule `brdf_core::split_sum::split_sum` (a different
//!   parametrisation: ξ = the CDF, φ up to φmax) at the widths where the reference is slow;
//! * the mirror limit m → 0 (A = 1 − (1 − μ)⁵, B = (1 − μ)⁵), the white furnace E ≤ 1
//!   (G ≤ 1), and E_avg against 2∫E μ dμ of the reference-checked texels.
//!
//! Asserted at every point: |value − reference| ≤ tol per channel, and the rule's own
//! estimate ≥ |value − reference| − REF_UNCERTAINTY (the claim a table's header makes).

use brdf_core::split_sum::polar::{Polar, PolarModel, PolarRow};
use brdf_tests::reference::{check_polar, split_sum_polar_ref, PolarLobe};
use std::f64::consts::PI;

/// The reference's own uncertainty allowed when checking the estimate (module docs).
const REF_UNCERTAINTY: f64 = 1e-10;

/// Smith's Λ for Beckmann m at direction cosine z: a = z/(m√(1 − z²)),
/// Λ = (e^{−a²}/(a√π) − erfc a)/2 (Heitz 2014 eq 72).
fn lambda(z: f64, m: f64) -> f64 {
    let s = ((1.0 - z) * (1.0 + z)).max(0.0).sqrt();
    if s == 0.0 {
        return 0.0;
    }
    let a = z / (m * s);
    ((-(a * a)).exp() / (a * PI.sqrt()) - libm::erfc(a)) * 0.5
}

/// The Beckmann lobe of width m for [`split_sum_polar_ref`]: q = exp(−tan²θh/m²),
/// tan²θh = −m² ln q, Λ of [`lambda`], either Smith form.
struct BeckmannLobe {
    m: f64,
    separable: bool,
}

impl PolarLobe for BeckmannLobe {
    fn q(&self, tan2: f64) -> f64 {
        (-tan2 / (self.m * self.m)).exp()
    }
    fn tan2(&self, q: f64) -> f64 {
        -(self.m * self.m) * q.ln()
    }
    fn lambda(&self, z: f64) -> f64 {
        lambda(z, self.m)
    }
    fn separable(&self) -> bool {
        self.separable
    }
}

/// The Beckmann split sum (A, B) with height-correlated (or separable) Smith by nested
/// adaptive Gauss–Kronrod in q = exp(−tan²θh/m²) ∈ (0, 1] and φ ∈ [0, π] (module docs).
fn split_sum_beckmann_ref(mu: f64, m: f64, separable: bool, tol: f64) -> (f64, f64) {
    split_sum_polar_ref(mu, &BeckmannLobe { m, separable }, tol)
}

fn model(m: f64, separable: bool) -> PolarModel<f64> {
    if separable {
        PolarModel::BeckmannSeparable(m)
    } else {
        PolarModel::BeckmannCorrelated(m)
    }
}

/// Grazing (cos 89°), low, mid and normal views at the default tables' widths (m = √2σ for
/// σ = 0.05 … 1, and m = r² of the E table), both Smith forms, at tol 2e-6 and 1e-8.
#[test]
fn matches_reference() {
    let pts = [
        (89f64.to_radians().cos(), 0.0707),
        (89f64.to_radians().cos(), 1.414),
        (0.05, 0.3),
        (0.2, 0.01),
        (0.4, 0.7),
        (0.7, 1.414),
        (1.0, 0.25),
    ];
    let mut worst = [0f64; 2];
    for &(mu, m) in &pts {
        for separable in [false, true] {
            let want = split_sum_beckmann_ref(mu, m, separable, 1e-11);
            let row = PolarRow::with_model(model(m, separable));
            for (k, tol) in [2e-6, 1e-8].into_iter().enumerate() {
                let p = row.texel(mu, tol);
                let what = format!("mu {mu} m {m} separable {separable} tol {tol:e}");
                worst[k] = worst[k].max(check_polar(
                    &p,
                    [want.0, want.1],
                    tol,
                    REF_UNCERTAINTY,
                    &what,
                ));
            }
        }
    }
    println!(
        "max error/estimate: tol 2e-6 {:.2e}, tol 1e-8 {:.2e}",
        worst[0], worst[1]
    );
}

/// Up to the largest width the generator uses the rule for (m = 2) against the fixed rule at
/// 4 × 32 outer and 64 inner nodes (its own difference from 3 × 32 × 32 is ≤ 1e-8 there).
#[test]
fn matches_fixed_rule_at_wide_lobes() {
    use brdf_core::microfacet::{Beckmann, Isotropic};
    use brdf_core::quadrature::GaussLegendre;
    use brdf_core::split_sum::{split_sum, Ndf};
    for m in [1.0, 2.0] {
        for mu in [0.03, 0.5, 1.0] {
            let fixed = |mu: f64| {
                split_sum::<f64, GaussLegendre<32>, GaussLegendre<32>>(mu, Ndf::Beckmann(m), |d| {
                    Beckmann::g_correlated_cos(d.n_i, d.n_o, m)
                })
            };
            let (a, b) = fixed(mu);
            let p = PolarRow::with_model(PolarModel::BeckmannCorrelated(m)).texel(mu, 1e-8);
            for (ch, want) in [a, b].into_iter().enumerate() {
                let err = (p.value[ch] - want).abs();
                assert!(
                    err < 1e-6,
                    "m {m} mu {mu} ch {ch}: {} vs {want}",
                    p.value[ch]
                );
            }
        }
    }
}

/// m → 0: the mirror limit A = 1 − (1 − μ)⁵, B = (1 − μ)⁵ (G2 → 1 away from grazing; at
/// m = 1e-4 and μ ≥ 0.1 the masking and the lobe's spread change A, B by < 1e-6), and the
/// white furnace E = A + B ≤ 1 everywhere (G ≤ 1, D normalised).
#[test]
fn mirror_limit_and_white_furnace() {
    for separable in [false, true] {
        let row = PolarRow::with_model(model(1e-4, separable));
        for mu in [0.1, 0.5, 1.0] {
            let p = row.texel(mu, 1e-9);
            let fc = (1.0 - mu).powi(5);
            assert!(
                (p.value[0] - (1.0 - fc)).abs() < 1e-6,
                "A at mu {mu}: {:?}",
                p.value
            );
            assert!(
                (p.value[1] - fc).abs() < 1e-6,
                "B at mu {mu}: {:?}",
                p.value
            );
        }
        for m in [0.05, 0.3, 1.0, 2.0] {
            let row = PolarRow::with_model(model(m, separable));
            for mu in [0.0175, 0.1, 0.5, 1.0] {
                let (e, est) = row.texel(mu, 1e-8).sum();
                assert!(e <= 1.0 + est, "E {e} at m {m} mu {mu}");
            }
        }
    }
}

/// A whole row (Chebyshev interpolation in ln μ over polar nodes) agrees with texel-by-texel
/// polar integrals at 1e-10 within the row's tolerance, and each estimate stays ≤ tol; E_avg
/// agrees with 2∫E μ dμ by a 32-point Gauss–Legendre rule in μ = t² over texels at 1e-10.
#[test]
fn rows_and_average() {
    use brdf_core::quadrature::{GaussLegendre, Rule};
    let tol = 2e-6;
    for m in [0.0025, 0.1, 0.5, 1.414] {
        let row = PolarRow::with_model(PolarModel::BeckmannCorrelated(m));
        let mus: Vec<f64> = (0..64)
            .map(|k| 0.0175f64 * (1.0 / 0.0175f64).powf(k as f64 / 63.0))
            .collect();
        let mut out = vec![Polar::default(); mus.len()];
        row.texels(&mus, tol, &mut out).unwrap();
        for (mu, p) in mus.iter().zip(&out) {
            let want = row.texel(*mu, 1e-10);
            for ch in 0..2 {
                let err = (p.value[ch] - want.value[ch]).abs();
                assert!(err <= tol, "m {m} mu {mu} ch {ch}: {err:.2e}");
                assert!(
                    p.error[ch] <= tol && err <= p.error[ch] + 1e-9,
                    "m {m} mu {mu}"
                );
            }
        }
        let (avg, est) = row.e_avg(1e-6);
        let want = GaussLegendre::<32>::integrate(0.0, 1.0, |t: f64| {
            4.0 * t * t * t * row.texel(t * t, 1e-10).sum().0
        });
        assert!(
            (avg - want).abs() <= 1e-6 && (avg - want).abs() <= est + 1e-9,
            "m {m}: {avg} vs {want}"
        );
    }
}

//! Known-answer checks of the ray-traced ground truth and of the single-neighbour
//! simulation. Every comparison is with something independent of the simulator: an exact
//! geometric fact (vertical rays, the projected-area identity, reciprocity), a closed form
//! (Smith's Λ, the coupled model's albedo) or the paper's formulas evaluated by brdf-core.

use brdf_core::masking::ModifiedG;
use brdf_core::microfacet::{Beckmann, Isotropic};
use brdf_validate::facet::g_single_neighbour;
use brdf_validate::profile::Profile;
use brdf_validate::smith1d;
use brdf_validate::stats::Estimate;
use brdf_validate::surface::{mix_seed, Surface};
use brdf_validate::textbook;
use std::sync::OnceLock;

fn profiles() -> &'static [Profile] {
    static P: OnceLock<Vec<Profile>> = OnceLock::new();
    P.get_or_init(|| (0..2).map(|i| Profile::generate(18, 40 + i)).collect())
}

/// A surface of the shared profiles at RMS slope `sigma`.
fn surface(sigma: f64) -> Surface<'static> {
    Surface {
        profiles: profiles(),
        sigma,
    }
}

fn d(x: f64) -> f64 {
    x.to_radians()
}

/// |a − b| within k standard errors, plus 3/n: when every sample agrees (SE = 0) an event
/// of probability below ~3/n may simply not have occurred (the 95% "rule of three").
fn agree(a: Estimate, b: f64, k: f64) -> bool {
    (a.mean - b).abs() <= k * a.se() + 3.0 / a.n as f64
}

/// Two independent estimates differ by less than `k` standard errors of the difference
/// (√(SE_a² + SE_b²)).
fn agree_both(a: Estimate, b: Estimate, k: f64) -> bool {
    (a.mean - b.mean).abs() < k * (a.se().powi(2) + b.se().powi(2)).sqrt()
}

#[test]
fn profile_has_the_stated_statistics() {
    for p in profiles() {
        let rms = p.realised_slope_rms();
        assert!((rms - 1.0).abs() < 0.02, "slope RMS {rms}");
        // Gaussian autocorrelation exp(−τ²/ℓ²): e⁻¹ at τ = ℓ (8 nodes), e⁻⁴ at 2ℓ.
        let r1 = p.realised_autocorrelation(8);
        let r2 = p.realised_autocorrelation(16);
        assert!((r1 - (-1f64).exp()).abs() < 0.03, "ACF(ℓ) {r1}");
        assert!((r2 - (-4f64).exp()).abs() < 0.03, "ACF(2ℓ) {r2}");
    }
}

#[test]
fn vertical_rays_are_never_blocked() {
    for sigma in [0.1, 0.5, 1.0] {
        let s = surface(sigma);
        let g = s.g(0.0, 0.0, 500, 2, 1);
        assert_eq!(g.g.mean, 1.0);
        // Normal incidence with any exit: only masking can act, so G = GM.
        let g = s.g(0.0, d(70.0), 500, 2, 2);
        assert_eq!(g.gs.mean, 1.0);
        assert_eq!(g.g.mean, g.gm.mean);
    }
}

#[test]
fn projected_area_identity_holds() {
    // For any height field the visible projected width seen from θ equals cos θ.
    for (k, sigma) in [0.3, 1.0].into_iter().enumerate() {
        let s = surface(sigma);
        for th in [30.0, 60.0, 80.0] {
            let (g1, id) = s.g1_area(d(th), 5000, 4, mix_seed(&[9, k as u64, th as u64]));
            assert!(agree(id, 1.0, 4.5), "σ {sigma} θ {th}: identity {id:?}");
            // Hence the area-weighted G1 is Smith's 1/(1 + Λ) with the Gaussian slopes.
            let sm = smith1d::g1(d(th), sigma);
            assert!(
                (g1.mean - sm).abs() < 4.5 * g1.se() + 0.004,
                "σ {sigma} θ {th}: {g1:?} vs {sm}"
            );
        }
    }
}

#[test]
fn simulated_g_is_reciprocal() {
    let s = surface(0.5);
    for (ti, tr, mi, mr) in [
        (30.0, 70.0, 70.0, 30.0),
        (40.0, -65.0, 65.0, -40.0),
        (75.0, 80.0, 80.0, 75.0),
    ] {
        let a = s.g(d(ti), d(tr), 2000, 4, 11).g;
        let b = s.g(d(mi), d(mr), 2000, 4, 12).g;
        assert!(
            agree_both(a, b, 4.5),
            "({ti},{tr}) {a:?} vs ({mi},{mr}) {b:?}"
        );
    }
}

#[test]
fn one_sided_masking_is_close_to_smith() {
    // G(0°, θr) = G1(θr | α = θr/2). Smith's G1 ignores the correlation between a facet's
    // slope and its visibility; for Gaussian surfaces it is known to be accurate to a few
    // hundredths at these angles.
    for sigma in [0.1, 0.3, 1.0] {
        let s = surface(sigma);
        for tr in [40.0, 60.0, 70.0] {
            let g = s.g(0.0, d(tr), 2000, 4, 21).g;
            let sm = smith1d::g1(d(tr), sigma);
            assert!(
                (g.mean - sm).abs() < 0.03 + 3.0 * g.se(),
                "σ {sigma} θr {tr}: {g:?} vs {sm}"
            );
        }
    }
}

#[test]
fn slope_bin_agrees_with_conditioning() {
    let s = surface(0.3);
    for (ti, tr) in [(60.0, 60.0), (70.0, 80.0), (30.0, 75.0)] {
        let c = s.g(d(ti), d(tr), 2000, 4, 31).g;
        let b = s.g_slope_bin(d(ti), d(tr), 0.05, 2000, 4, 32);
        assert!(b.n > 4000, "too few facets in the bin: {}", b.n);
        assert!(agree_both(c, b, 4.5), "({ti},{tr}) {c:?} vs {b:?}");
    }
}

#[test]
fn paper_formulas_match_their_own_single_neighbour_model() {
    // brdf-core's M (eqs 6–12, reciprocal convention) against the geometric simulation of
    // the assumptions the formulas are derived from.
    for sigma in [0.1, 0.3, 1.0] {
        let g = ModifiedG::<f64>::new(sigma).unwrap();
        for (ti, tr) in [
            (30.0, 80.0),
            (60.0, 60.0),
            (85.0, -30.0),
            (70.0, 20.0),
            (45.0, -80.0),
        ] {
            let sim = g_single_neighbour(
                d(ti),
                d(tr),
                sigma,
                5000,
                8,
                mix_seed(&[ti as u64, tr as i64 as u64]),
            );
            let t = g.terms(d(ti), d(tr));
            assert!(
                agree(sim.gm, t.gm, 4.5),
                "σ {sigma} ({ti},{tr}) GM {:?} vs {}",
                sim.gm,
                t.gm
            );
            assert!(
                agree(sim.gs, t.gs, 4.5),
                "σ {sigma} ({ti},{tr}) GS {:?} vs {}",
                sim.gs,
                t.gs
            );
            // The joint probability can never exceed eq 13's min.
            assert!(
                sim.g.mean <= t.g + 4.5 * sim.g.se() + 3.0 / sim.g.n as f64,
                "σ {sigma} ({ti},{tr}) joint {:?} vs min {}",
                sim.g,
                t.g
            );
        }
    }
}

#[test]
fn smith_1d_matches_beckmann_lambda() {
    for sigma in [0.05, 0.3, 1.0] {
        for th in [10.0, 45.0, 80.0, 89.0] {
            let a = smith1d::lambda(d(th), sigma);
            let b = Beckmann::lambda_cos(d(th).cos(), std::f64::consts::SQRT_2 * sigma);
            assert!(
                (a - b).abs() <= 1e-9 * (1.0 + b),
                "σ {sigma} θ {th}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn textbook_coupled_albedo_closed_form() {
    // At normal incidence F = R0 and the matte albedo is 2πk·(10/21): printed k gives
    // R0 + 1/(1 − R0), the conserving one R0 + (1 − R0) = 1.
    let r0 = 0.04;
    let ap = textbook::coupled_albedo(0.0, r0, textbook::k_printed(r0));
    let ac = textbook::coupled_albedo(0.0, r0, textbook::k_conserving(r0));
    assert!((ap - (r0 + 1.0 / (1.0 - r0))).abs() < 1e-6, "{ap}");
    assert!((ac - 1.0).abs() < 1e-6, "{ac}");
    // Eq 24.9 with the denominator outside the exponent is eq 24.5.
    let (e5, _, fixed) = textbook::eq_24_9_forms(100.0, d(30.0), d(40.0));
    assert!((e5 - fixed).abs() < 1e-12 * e5);
}

//! The one-sided passing factor M(θ, a) is at least ½ for every θ ≤ π/2, as documented
//! (`ModifiedG::passing_cs`), also for very rough surfaces, where the semi-passing part is
//! far smaller than the rounding of the normaliser (the case: θ = a = π/2 with
//! σ ≥ 1e4 in f64 gave 0.4999996586, σ = 1e6 in f32 gave 0.4999999).
//!
//! Reference: at θ = a = π/2 the fully passing range is γ < 0 (mass ½) and the semi-passing
//! range [0, π/2] has r = 1 − sin γ, so M = ½ + ∫₀^{π/2} p (1 − sin γ) dγ; in x = tan γ,
//! p dγ ∝ √(1 + x²) e^{−x²/(2σ²)} dx and √(1 + x²)(1 − sin γ) = 1/(√(1 + x²) + x):
//!
//! M(π/2, π/2) = ½ + ½ · ∫₀^∞ e^{−x²/2σ²}/(√(1 + x²) + x) dx / ∫₀^∞ √(1 + x²) e^{−x²/2σ²} dx,
//!
//! integrated here by adaptive Gauss–Kronrod (`brdf_tests::reference::integrate`), and
//! cross-checked against the same integrals in 30-digit arithmetic (mpmath `quad`).

use brdf_core::masking::ModifiedG;
use brdf_tests::reference::integrate;
use std::f64::consts::FRAC_PI_2;

/// M(π/2, π/2) for RMS slope σ, by the formula of the module docs (x = σt).
fn reference(sigma: f64) -> f64 {
    let w = |t: f64| (-0.5 * t * t).exp();
    let br = [1.0 / sigma, 10.0 / sigma, 100.0 / sigma, 0.1, 1.0, 3.0, 6.0];
    let num = integrate(
        |t| w(t) / ((1.0 + sigma * sigma * t * t).sqrt() + sigma * t),
        0.0,
        40.0,
        &br,
        1e-16,
    );
    let den = integrate(
        |t| (1.0 + sigma * sigma * t * t).sqrt() * w(t),
        0.0,
        40.0,
        &br,
        1e-13 * sigma,
    );
    0.5 + 0.5 * num / den
}

/// (σ, M(π/2, π/2)) in 30-digit arithmetic (mpmath 1.3, `quad` over the same integrals).
const MPMATH: [(f64, f64); 6] = [
    (1.0, 0.705475668406708),
    (10.0, 0.508739120721205),
    (100.0, 0.500146365971554),
    (1e4, 0.500000026153632),
    (1e5, 0.500000000319101),
    (1e6, 0.500000000003767),
];

#[test]
fn reference_agrees_with_high_precision_values() {
    for (s, m) in MPMATH {
        let r = reference(s);
        assert!((r - m).abs() < 1e-12, "σ = {s}: {r} vs {m}");
    }
}

#[test]
fn passing_at_grazing_is_at_least_half_and_near_the_reference() {
    for (s, m) in MPMATH {
        let g = ModifiedG::<f64>::new(s).unwrap();
        let p = g.passing(FRAC_PI_2, FRAC_PI_2);
        assert!(
            (0.5..=1.0).contains(&p),
            "f64, σ = {s}: M = {p:.12} not in [1/2, 1]"
        );
        // The documented accuracy (README: 1e-6 in f64, 2e-6 in f32) holds on the documented
        // σ range [0.05, 1] only; beyond it (σ = 10: 1.6e-4 off, measured) just the bound is
        // promised, which is what row 7 of the hostile-input issue asks.
        let documented = s <= 1.0;
        assert!(
            !documented || (p - m).abs() < 1e-6,
            "f64, σ = {s}: M = {p:.12}, reference {m:.12}"
        );
        let g = ModifiedG::<f32>::new(s as f32).unwrap();
        let p = g.passing(FRAC_PI_2 as f32, FRAC_PI_2 as f32);
        assert!(
            (0.5..=1.0).contains(&p),
            "f32, σ = {s}: M = {p:.9} not in [1/2, 1]"
        );
        assert!(
            !documented || (p as f64 - m).abs() < 2e-6,
            "f32, σ = {s}: M = {p:.9}, reference {m:.12}"
        );
    }
}

/// The bound everywhere near grazing: θ within 1e-3 of π/2, every tilt, rough surfaces.
#[test]
fn passing_is_at_least_half_for_every_theta_up_to_grazing() {
    for s in [0.05, 1.0, 1e2, 1e4, 1e5, 1e6] {
        let g64 = ModifiedG::<f64>::new(s).unwrap();
        let g32 = ModifiedG::<f32>::new(s as f32).unwrap();
        for i in 0..=20 {
            let theta = FRAC_PI_2 - 1e-3 * (i as f64 / 20.0);
            for j in 0..=40 {
                let a = -FRAC_PI_2 + std::f64::consts::PI * j as f64 / 40.0;
                let p = g64.passing(theta, a);
                assert!((0.5..=1.0).contains(&p), "f64 σ={s} θ={theta} a={a}: {p}");
                let p = g32.passing(theta as f32, a as f32);
                assert!((0.5..=1.0).contains(&p), "f32 σ={s} θ={theta} a={a}: {p}");
            }
        }
    }
}

//! Roughness: one vocabulary, and every conversion between its four names as a named function.
//!
//! | name | symbol | where it is used | relation |
//! |---|---|---|---|
//! | RMS slope | σ | the paper's Gaussian surface (eqs 2, 5) | tan γ has standard deviation σ per in-plane axis |
//! | Beckmann width | m | Beckmann D, Smith–Beckmann Λ (Torrance–Sparrow eq 3) | m = √2 σ |
//! | microfacet width | α | GGX D and Λ; the crate's `alpha` parameter of every microfacet model | α = m for Beckmann |
//! | perceptual roughness | r | engines' material inputs (glTF, Filament, Unreal) and the split-sum tables | α = r² |
//!
//! Why √2: the paper's σ is the RMS of the slope along one in-plane axis, so the 2-D slope
//! density is a Gaussian with variance σ² per axis, exp(−tan²θ/(2σ²)). Beckmann's D is
//! written exp(−tan²θ/m²): the two agree for m² = 2σ² (docs/conventions.md §5).
//!
//! The perceptual mapping α = r² is the one of Burley (2012) and of the glTF 2.0 metallic–
//! roughness model; the split-sum and albedo tables take r on their roughness axis.
//!
//! Each function is one IEEE operation (or two), written once here so that every caller —
//! kernels, tables, the C ABI, WASM, the command line — converts the same way, bit for bit.

use crate::Real;

/// Beckmann width from the paper's RMS slope: m = √2 σ (docs/conventions.md §5).
#[inline]
pub fn beckmann_m_from_sigma<T: Real>(sigma: T) -> T {
    T::from_f64(core::f64::consts::SQRT_2) * sigma
}

/// The paper's RMS slope from a Beckmann width: σ = m / √2 (inverse of
/// [`beckmann_m_from_sigma`]).
#[inline]
pub fn sigma_from_beckmann_m<T: Real>(m: T) -> T {
    m / T::from_f64(core::f64::consts::SQRT_2)
}

/// Microfacet width from perceptual roughness: α = r² (Burley 2012; glTF 2.0).
#[inline]
pub fn alpha_from_perceptual<T: Real>(r: T) -> T {
    r * r
}

/// Perceptual roughness from a microfacet width: r = √α (inverse of
/// [`alpha_from_perceptual`] on α ≥ 0; NaN for α < 0).
#[inline]
pub fn perceptual_from_alpha<T: Real>(alpha: T) -> T {
    alpha.sqrt()
}

/// The paper's RMS slope that gives the Beckmann width α = r²: σ = r² / √2.
#[inline]
pub fn sigma_from_perceptual<T: Real>(r: T) -> T {
    sigma_from_beckmann_m(alpha_from_perceptual(r))
}

/// How a roughness number is given: the option names of a table's roughness axis (the
/// generator's `roughness`, command line, TOML specs, Python), one per row of the table
/// above that a user types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Roughness {
    /// Perceptual r ∈ [0, 1]: width α = r² ([`alpha_from_perceptual`]).
    Perceptual,
    /// The distribution width itself: GGX α, Beckmann m.
    Alpha,
    /// The paper's RMS slope σ: Beckmann m = √2 σ ([`beckmann_m_from_sigma`]).
    Sigma,
}

impl Roughness {
    /// Every option, in the order of [`Roughness::NAMES`].
    pub const ALL: [Roughness; 3] = [Roughness::Perceptual, Roughness::Alpha, Roughness::Sigma];
    /// The options' names.
    pub const NAMES: [&'static str; 3] = ["perceptual", "alpha", "sigma"];
    /// Its name.
    pub const fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
    /// Parses [`Roughness::name`].
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|r| r.name() == s)
    }
    /// The distribution width (α, or Beckmann m) and the RMS slope σ = width/√2 of a value
    /// `x` given this way: (r², r²/√2), (x, x/√2) or (√2 x, x) — each through the named
    /// conversions, so that σ is `x` itself when `x` is σ.
    pub fn width_and_sigma<T: Real>(self, x: T) -> (T, T) {
        match self {
            Roughness::Perceptual => (alpha_from_perceptual(x), sigma_from_perceptual(x)),
            Roughness::Alpha => (x, sigma_from_beckmann_m(x)),
            Roughness::Sigma => (beckmann_m_from_sigma(x), x),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The σ → m relation against the definition: the 2-D Gaussian slope density with
    /// per-axis variance σ² is exp(−t²/(2σ²)); Beckmann's is exp(−t²/m²). They must agree at
    /// every slope t, which pins m² = 2σ² independently of the √2 constant in the code.
    #[test]
    fn beckmann_m_matches_the_slope_variance() {
        for &sigma in &[0.05f64, 0.1, 0.3, 0.5, 1.0, 3.0] {
            let m = beckmann_m_from_sigma(sigma);
            for k in 0..20 {
                let t = k as f64 * 0.1 * sigma;
                let paper = (-(t * t) / (2.0 * sigma * sigma)).exp();
                let beck = (-(t * t) / (m * m)).exp();
                assert!(
                    (paper - beck).abs() <= 4.0 * f64::EPSILON,
                    "σ={sigma} t={t}"
                );
            }
            let back = sigma_from_beckmann_m(m);
            assert!((back - sigma).abs() <= 2.0 * f64::EPSILON * sigma);
        }
    }

    /// The three ways of giving roughness agree on one surface: r = 0.5 is α = 0.25 and
    /// σ = 0.25/√2 whichever way it is given (σ checked by m² = 2σ², not by the constant).
    #[test]
    fn parameterisations_agree() {
        let (r, alpha) = (0.5f64, 0.25f64);
        let sigma = (alpha * alpha / 2.0).sqrt();
        for (p, x) in [
            (Roughness::Perceptual, r),
            (Roughness::Alpha, alpha),
            (Roughness::Sigma, sigma),
        ] {
            let (w, s) = p.width_and_sigma(x);
            assert!((w - alpha).abs() <= 2.0 * f64::EPSILON * alpha, "{p:?}");
            assert!((s - sigma).abs() <= 2.0 * f64::EPSILON * sigma, "{p:?}");
            assert_eq!(Roughness::from_name(p.name()), Some(p));
        }
        assert_eq!(Roughness::from_name("m"), None);
    }

    /// Perceptual roughness: α = r² and back, in f32 and f64, with the documented NaN for
    /// negative α.
    #[test]
    fn perceptual_round_trip() {
        for k in 0..=100 {
            let r = k as f64 / 100.0;
            assert_eq!(alpha_from_perceptual(r), r * r);
            let back = perceptual_from_alpha(alpha_from_perceptual(r));
            assert!((back - r).abs() <= f64::EPSILON, "r={r}");
            let rf = r as f32;
            assert!((perceptual_from_alpha(alpha_from_perceptual(rf)) - rf).abs() <= f32::EPSILON);
        }
        assert!(perceptual_from_alpha(-1e-3f64).is_nan());
        // σ from r: Beckmann width α = r² = √2 σ.
        let s = sigma_from_perceptual(0.5f64);
        assert!((core::f64::consts::SQRT_2 * s - 0.25).abs() < 1e-16);
    }
}

//! Facet-slope distributions.
//!
//! * The paper's slope-angle density p(γ; σ) (Acta Phys. Sin. 64 184213, eqs 2 and 5) with
//!   its 1-D normalisation C(σ) (docs/conventions.md §2).
//!
//! The normal distributions D themselves (Beckmann, the D of the Torrance–Sparrow BRDF, eq 3,
//! docs/conventions.md §5, with m = √2 σ; Trowbridge–Reitz/GGX) are in
//! [`crate::microfacet`]; in the dot products, [`crate::microfacet::Isotropic::d_cos`].
//!
//! Working variable. With u = tan γ and v = u/(√2 σ), p(γ) dγ ∝ √(1 + u²) e^{−v²} dv. The
//! width of the integrand in v does not depend on σ, which is what lets a 10-point rule reach
//! 1e-6 for every σ. Integrals are cut at v = [`V_CUT`], where the tail is below 2e-10 of the
//! total; the same cut is used for the normaliser, so "everything passes" gives exactly 1.

use crate::error::{check_range, ParamError};
use crate::quadrature::{DefaultRule, GaussLegendre, Rule};
use crate::Real;
use core::marker::PhantomData;

/// Upper limit of the working variable v = tan γ/(√2 σ): ∫_{V_CUT}^∞ e^{−v²} dv < 2e-10.
pub const V_CUT: f64 = 4.5;

/// Integrand of the slope density in the working variable: √(1 + u²) e^{−v²}, u = √2σ v.
#[inline]
pub(crate) fn slope_weight<T: Real>(v: T, sqrt2_sigma: T) -> T {
    let u = sqrt2_sigma * v;
    (T::ONE + u * u).sqrt() * (-(v * v)).exp()
}

/// The paper's Gaussian slope-angle density for one RMS slope σ, with its normaliser
/// precomputed. `R` is the quadrature rule (compile-time node count).
#[derive(Clone, Copy, Debug)]
pub struct SlopeDistribution<T, R = DefaultRule> {
    sigma: T,
    sqrt2_sigma: T,
    /// 1/(2Z), Z = ∫₀^{V_CUT} √(1+u²) e^{−v²} dv by the rule `R` itself: the half-line mass
    /// in the working variable, evaluated as the modified G evaluates its integrals (f64:
    /// [`Rule::integrate_slope_weight`]). Using the same rule for the normaliser as for M
    /// makes "everything passes" exactly 1.
    inv_2z: T,
    /// C(σ) from Z evaluated to full precision (two 32-point panels), for [`Self::pdf`] and
    /// [`Self::normalisation_c`].
    c: T,
    _rule: PhantomData<R>,
}

impl<T: Real, R: Rule> SlopeDistribution<T, R> {
    /// Checked constructor: σ must be finite and > 0. Accuracy is specified for
    /// σ ∈ [0.05, 1]; any finite σ > 0 gives finite results.
    pub fn new(sigma: T) -> Result<Self, ParamError> {
        let sigma = check_range("sigma", sigma, T::ZERO, true, T::INFINITY, "(0, ∞)")?;
        let sqrt2_sigma = crate::roughness::beckmann_m_from_sigma(sigma);
        let vc = T::from_f64(V_CUT);
        let w = |v| slope_weight(v, sqrt2_sigma);
        // f64: the integration the modified G uses (bit for bit the same for the same
        // interval); f32: the one-pass rule, as there.
        let z = if T::EPSILON < T::from_f64(1e-10) {
            R::integrate_slope_weight(vc, sqrt2_sigma * sqrt2_sigma)
        } else {
            R::integrate(T::ZERO, vc, w)
        };
        let mid = vc * T::HALF;
        let z_exact = GaussLegendre::<32>::integrate(T::ZERO, mid, w)
            + GaussLegendre::<32>::integrate(mid, vc, w);
        // C = πσ/(√2 Z)
        let c = T::PI * sigma / (T::from_f64(core::f64::consts::SQRT_2) * z_exact);
        Ok(Self {
            sigma,
            sqrt2_sigma,
            inv_2z: T::ONE / (T::TWO * z),
            c,
            _rule: PhantomData,
        })
    }
    /// The RMS slope σ.
    #[inline]
    pub fn sigma(&self) -> T {
        self.sigma
    }
    /// √2 σ: the Beckmann roughness m of the same surface.
    #[inline]
    pub fn sqrt2_sigma(&self) -> T {
        self.sqrt2_sigma
    }
    /// 1/(2Z), the factor that turns a working-variable integral into a probability.
    #[inline]
    pub(crate) fn inv_2z(&self) -> T {
        self.inv_2z
    }
    /// The normalisation constant C(σ) of eq 2 under ∫p dγ = 1 over [−π/2, π/2]:
    /// C = πσ/(√2 Z) (docs/conventions.md §2; C → √(2π)σ as σ → 0).
    pub fn normalisation_c(&self) -> T {
        self.c
    }
    /// p(γ; σ) = C/(2πσ² cos³γ) · exp(−tan²γ/(2σ²)), eqs 2/5, in 1/rad. 0 outside
    /// (−π/2, π/2); NaN for NaN.
    pub fn pdf(&self, gamma: T) -> T {
        if gamma.is_nan() {
            return T::NAN;
        }
        let c = gamma.cos();
        if !(gamma.abs() < T::FRAC_PI_2) || c <= T::ZERO {
            return T::ZERO;
        }
        let v = gamma.tan() / self.sqrt2_sigma;
        (-(v * v)).exp() / (c * c * c) * self.c / (T::TWO * T::PI * self.sigma.sq())
    }
    /// P(γ' ≤ γ) = ∫_{−π/2}^{γ} p dγ' (the fully-passing mass of eq 6 with γ = π/2 − θ).
    pub fn cdf(&self, gamma: T) -> T {
        if gamma.is_nan() {
            return T::NAN;
        }
        let g = gamma.clamp(-T::FRAC_PI_2, T::FRAC_PI_2);
        let v = self.v_of_tan(g.sin(), g.cos());
        // The rule's half-line integral can exceed ½ by its rounding (1.4e-7 in f32): the
        // probability is clamped into [0, 1].
        let half = (R::integrate(T::ZERO, v.abs(), |v| slope_weight(v, self.sqrt2_sigma))
            * self.inv_2z)
            .min(T::HALF);
        if v >= T::ZERO {
            T::HALF + half
        } else {
            T::HALF - half
        }
    }
    /// The working variable for tan γ = s/c, clamped to ±V_CUT.
    #[inline]
    pub(crate) fn v_of_tan(&self, s: T, c: T) -> T {
        let vc = T::from_f64(V_CUT);
        // s/(c·√2σ) without dividing by c = 0.
        if s.abs() >= vc * c * self.sqrt2_sigma {
            if s >= T::ZERO {
                vc
            } else {
                -vc
            }
        } else {
            s / (c * self.sqrt2_sigma)
        }
    }
}

//! The "Charlie" sheen distribution of Estevez and Kulla, "Production Friendly Microfacet
//! Sheen BRDF" (Sony Pictures Imageworks, 2017), with the two visibility terms the engines
//! use. Width α = r², r the perceptual sheen roughness of the glTF `KHR_materials_sheen`
//! specification.
//!
//! * **D** (E&K eq 2): D(h) = (2 + 1/α) sin^{1/α}θh / (2π), isotropic, normalised for every
//!   α > 0: ∫ D cos θh dω = (2 + 1/α) ∫₀¹ s^{1+1/α} ds = 1 (s = sin θh). The power is
//!   evaluated as exp(ln(sin²θh)/(2α)), with ln(sin²θh) taken from whichever of cos²θh and
//!   sin²θh is the smaller: ln(sin²) directly where sin² < ½, ln_1p(−cos²) otherwise. Each
//!   input then carries a relative error of a few ε, so the exponent has an absolute error
//!   of a few ε·min(sin², cos²)/α: D keeps a relative error of a few ε where it matters,
//!   also at grazing half vectors (where a naive ln(1 − cos²) would lose ε/α).
//! * **r → 0.** D tends to a ring on the horizon that no finite width represents. α is
//!   clamped to at least [`ALPHA_FLOOR`] = 1e-4 (r = 0.01), the crate's smallest slope width
//!   ([`super::ALPHA_MIN`]): there 1/α = 1e4, D ≤ (2 + 1e4)/(2π) ≈ 1.6e3, every quantity is
//!   finite in `f32`, D stays exactly normalised (the clamp only changes the shape), and the
//!   exponent's conditioning 1/(2α) turns an `f32` input rounding of a few ε into at most
//!   about 1e-3 relative, the accuracy an `f32` shader can hold. r ∈ [0, 0.01] therefore
//!   all give the r = 0.01 lobe.
//! * **Λ, Estevez–Kulla fit** (E&K §3, Table 1; the form of the glTF specification's "sheen
//!   visibility"): L(x) = a/(1 + b x^c) + d x + e with each coefficient interpolated between
//!   the α = 1 and α = 0 rows by t = (1 − α)²; Λ(μ) = exp(L(μ)) for μ < ½ and
//!   exp(2 L(½) − L(1 − μ)) for μ ≥ ½ (continuous at ½, Λ(1) ≈ 0). G2 = 1/(1 + Λ(μi) +
//!   Λ(μo)), the height-correlated Smith form the glTF specification uses (E&K's own
//!   "terminator softening" Λ^{1 + 2(1 − μ)⁸} of the light side is not applied, as in the
//!   specification). The fit replaces the exact Smith Λ of D, which has no closed form; see
//!   tests/tests/sheen.rs for its measured distance from the exact Λ.
//! * **Ashikhmin's visibility** (Ashikhmin and Premože 2007, "Distribution-based BRDFs", in
//!   the simplified form of Neubelt and Pettineo 2013, used by Filament): V = 1/(4(μi + μo −
//!   μi μo)).
//! * **Sampling.** No closed-form visible-normal sampler exists for D. The distribution of
//!   normals D cos θh has the closed-form CDF F(s) = s^{2 + 1/α} in s = sin θh, so
//!   sin θh = u^{α/(1 + 2α)}, cos²θh = −expm1((2α/(1 + 2α)) ln u): an exact sampler with the
//!   exact pdf D(h) cos θh ([`Charlie::sample_normal`], [`Charlie::normal_pdf`]).
//!
//! Directions and cosines follow [`super`]: unit vectors in the local frame, z the normal;
//! a cosine below [`min_cos`] is at or below the horizon (Λ = ∞, G2 = 0, V = 0).

use crate::geometry::{min_cos, Vec3};
use crate::{ParamError, Real};

/// The smallest width α the distribution uses (module docs: r → 0).
pub const ALPHA_FLOOR: f64 = 1e-4;

/// The Estevez–Kulla fit coefficients (a, b, c, d, e) at α = 0 and at α = 1 (E&K Table 1).
const FIT_ALPHA0: [f64; 5] = [25.3245, 3.32435, 0.16801, -1.27393, -4.85967];
const FIT_ALPHA1: [f64; 5] = [21.5473, 3.82987, 0.19823, -1.97760, -4.32054];

/// The Charlie sheen distribution for one width α (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Charlie<T> {
    alpha: T,
    /// 1/(2α): the exponent's factor on ln sin²θh.
    half_inv_alpha: T,
    /// (2 + 1/α)/(2π).
    norm: T,
    /// The fit coefficients (a, b, c, d, e) at this α.
    fit: [T; 5],
    /// L(½), the seam of the fit.
    l_half: T,
}

impl<T: Real> Charlie<T> {
    /// Checked constructor from the perceptual roughness r ∈ [0, 1] (α = r², clamped to at
    /// least [`ALPHA_FLOOR`]).
    pub fn from_roughness(r: T) -> Result<Self, ParamError> {
        let r = crate::error::check_range("roughness", r, T::ZERO, false, T::ONE, "[0, 1]")?;
        Ok(Self::clamped(crate::roughness::alpha_from_perceptual(r)))
    }
    /// Any width, clamped into [[`ALPHA_FLOOR`], 1] (the range of the Λ fit); NaN stays NaN
    /// (every result is then NaN).
    pub fn clamped(alpha: T) -> Self {
        let a = alpha.clamp(T::from_f64(ALPHA_FLOOR), T::ONE);
        let t = (T::ONE - a).sq();
        let fit = core::array::from_fn(|k| {
            let (c0, c1) = (T::from_f64(FIT_ALPHA0[k]), T::from_f64(FIT_ALPHA1[k]));
            c1 + (c0 - c1) * t
        });
        let mut s = Self {
            alpha: a,
            half_inv_alpha: T::HALF / a,
            norm: (T::TWO + T::ONE / a) / (T::TWO * T::PI),
            fit,
            l_half: T::ZERO,
        };
        s.l_half = s.fit_l(T::HALF);
        s
    }
    /// The width α actually used.
    pub fn alpha(&self) -> T {
        self.alpha
    }
    /// D from cos θh and sin²θh as a shader has them (both of one unit half vector):
    /// (2 + 1/α)/(2π) · exp(ln(sin²θh)/(2α)), the logarithm from the smaller of sin² and
    /// cos² (module docs). 0 for cos θh ≤ 0 (and at sin θh = 0); NaN in, NaN out.
    pub fn d_cos_sin2(&self, cos_h: T, sin2_h: T) -> T {
        if cos_h.is_nan() || sin2_h.is_nan() || self.alpha.is_nan() {
            return T::NAN;
        }
        if !(cos_h > T::ZERO) {
            return T::ZERO;
        }
        let c2 = cos_h * cos_h;
        let s2 = sin2_h.clamp(T::ZERO, T::ONE);
        let ln_s2 = if s2 < T::HALF {
            s2.ln()
        } else {
            ln_1p(-c2.min(T::ONE))
        };
        self.norm * (ln_s2 * self.half_inv_alpha).exp()
    }
    /// D(h) for a unit half vector (sin²θh = h_x² + h_y²); 0 for h_z ≤ 0.
    pub fn d(&self, h: Vec3<T>) -> T {
        self.d_cos_sin2(h.z, h.x * h.x + h.y * h.y)
    }
    /// D(h) cos θh: the density of [`Charlie::sample_normal`] per unit solid angle of h.
    pub fn normal_pdf(&self, h: Vec3<T>) -> T {
        self.d(h) * h.z.max(T::ZERO)
    }
    /// Samples h with density D(h) cos θh: sin θh = u0^{α/(1 + 2α)} (the inverse of the CDF
    /// s^{2 + 1/α}), azimuth 2π u1; u clamped into [0, 1). Always a unit vector with
    /// h_z ≥ 0.
    pub fn sample_normal(&self, u: [T; 2]) -> Vec3<T> {
        let u0 = crate::sampling::unit(u[0]);
        let (cp, sp) = super::azimuth(u[1]);
        let k = T::TWO * self.alpha / (T::ONE + T::TWO * self.alpha);
        // ln sin²θh = k ln u0 ≤ 0 (−∞ at u0 = 0: h = n).
        let ln_s2 = k * u0.ln();
        let s2 = ln_s2.exp();
        let c2 = -exp_m1(ln_s2);
        let s = s2.sqrt();
        Vec3::new(s * cp, s * sp, c2.max(T::ZERO).sqrt())
            .normalize()
            .unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ONE))
    }
    /// The fit's L(x) = a/(1 + b x^c) + d x + e (x ∈ [0, 1]).
    fn fit_l(&self, x: T) -> T {
        let [a, b, c, d, e] = self.fit;
        let xc = if x > T::ZERO { x.powf(c) } else { T::ZERO };
        a / (T::ONE + b * xc) + d * x + e
    }
    /// The Estevez–Kulla Λ(μ) (module docs): exp(L(μ)) for μ < ½, exp(2L(½) − L(1 − μ))
    /// otherwise; μ > 1 is taken as 1; ∞ below [`min_cos`]; NaN for NaN.
    pub fn lambda(&self, mu: T) -> T {
        if mu.is_nan() || self.alpha.is_nan() {
            return T::NAN;
        }
        if !(mu >= min_cos()) {
            return T::INFINITY;
        }
        let mu = mu.min(T::ONE);
        if mu < T::HALF {
            self.fit_l(mu).exp()
        } else {
            (T::TWO * self.l_half - self.fit_l(T::ONE - mu)).exp()
        }
    }
    /// G2 = 1/(1 + Λ(μi) + Λ(μo)), the height-correlated Smith form with the fitted Λ
    /// (0 at or below the horizon).
    pub fn g2(&self, mu_i: T, mu_o: T) -> T {
        // Λi + Λo first: symmetric to the bit (the model is exactly reciprocal).
        T::ONE / (T::ONE + (self.lambda(mu_i) + self.lambda(mu_o)))
    }
    /// The Estevez–Kulla visibility V = G2/(4 μi μo) (0 at or below the horizon; NaN in,
    /// NaN out).
    pub fn v_estevez_kulla(&self, mu_i: T, mu_o: T) -> T {
        let g = self.g2(mu_i, mu_o);
        if g.is_nan() || g == T::ZERO {
            return g;
        }
        g / (T::from_f64(4.0) * (mu_i.min(T::ONE) * mu_o.min(T::ONE)))
    }
}

/// Ashikhmin's visibility V = 1/(4(μi + μo − μi μo)) (module docs): μi μo ≤ (μi + μo)/2
/// for μ ∈ [0, 1], so the difference loses at most one bit, and it is symmetric to the bit.
/// 0 when either cosine is below [`min_cos`]; cosines above 1 are taken as 1; NaN in, NaN
/// out.
pub fn v_ashikhmin<T: Real>(mu_i: T, mu_o: T) -> T {
    if mu_i.is_nan() || mu_o.is_nan() {
        return T::NAN;
    }
    if !(mu_i >= min_cos()) || !(mu_o >= min_cos()) {
        return T::ZERO;
    }
    let (mi, mo) = (mu_i.min(T::ONE), mu_o.min(T::ONE));
    T::ONE / (T::from_f64(4.0) * ((mi + mo) - mi * mo))
}

/// ln(1 + x) for x ≥ −1 to a few ε, also for small |x|: ln(u)·x/(u − 1) with u = 1 + x
/// rounded (Goldberg, "What every computer scientist should know about floating-point
/// arithmetic", 1991, Theorem 4); x when u rounds to 1.
#[inline]
pub(crate) fn ln_1p<T: Real>(x: T) -> T {
    let u = T::ONE + x;
    let d = u - T::ONE;
    if d == T::ZERO {
        x
    } else {
        u.ln() * (x / d)
    }
}

/// eˣ − 1 to a few ε, also for small |x|: (u − 1)·x/ln u with u = eˣ rounded (Kahan's
/// method, the counterpart of [`ln_1p`]); x when u rounds to 1, −1 when u underflows.
#[inline]
pub(crate) fn exp_m1<T: Real>(x: T) -> T {
    let u = x.exp();
    if u == T::ONE {
        x
    } else if u == T::ZERO {
        -T::ONE
    } else {
        let l = u.ln();
        if l == T::ZERO || !l.is_finite() {
            u - T::ONE
        } else {
            (u - T::ONE) * (x / l)
        }
    }
}

//! Smith masking (conventions.md §6) for the Beckmann and the Trowbridge–Reitz (GGX)
//! distributions. Every function takes cosines (n·w); a direction at or below the horizon is
//! fully masked (G1 = 0, Λ = ∞).

use crate::distribution::FRAC_1_SQRT_PI;
use crate::Real;

/// Smith's Λ for Beckmann roughness m: with a = 1/(m tan θ) = cos θ/(m sin θ),
/// Λ = (erf(a) − 1)/2 + exp(−a²)/(2a√π). Written with erfc to avoid the cancellation.
#[inline]
pub fn lambda_beckmann<T: Real>(cos_t: T, m: T) -> T {
    if cos_t.is_nan() || m.is_nan() {
        return T::NAN;
    }
    if !(cos_t > T::ZERO) {
        return T::INFINITY;
    }
    let c = cos_t.min(T::ONE);
    let s = (T::ONE - c * c).sqrt();
    if !(s * m > T::ZERO) {
        return T::ZERO;
    }
    let a = c / (m * s);
    if a > T::from_f64(8.0) {
        return T::ZERO; // Λ < 1e-29
    }
    ((-(a * a)).exp() * T::from_f64(FRAC_1_SQRT_PI) / a - a.erfc()) * T::HALF
}

/// One-sided Smith–Beckmann masking G1 = 1/(1 + Λ).
#[inline]
pub fn g1_smith_beckmann<T: Real>(cos_t: T, m: T) -> T {
    T::ONE / (T::ONE + lambda_beckmann(cos_t, m))
}

/// Separable Smith–Beckmann G = G1(θi) G1(θo).
#[inline]
pub fn g_smith_beckmann_separable<T: Real>(cos_i: T, cos_o: T, m: T) -> T {
    g1_smith_beckmann(cos_i, m) * g1_smith_beckmann(cos_o, m)
}

/// Height-correlated Smith–Beckmann G = 1/(1 + Λ(θi) + Λ(θo)).
#[inline]
pub fn g_smith_beckmann_correlated<T: Real>(cos_i: T, cos_o: T, m: T) -> T {
    T::ONE / (T::ONE + lambda_beckmann(cos_i, m) + lambda_beckmann(cos_o, m))
}

/// Smith's Λ for GGX roughness α: Λ = (√(1 + α² tan²θ) − 1)/2.
#[inline]
pub fn lambda_ggx<T: Real>(cos_t: T, alpha: T) -> T {
    if cos_t.is_nan() || alpha.is_nan() {
        return T::NAN;
    }
    if !(cos_t > T::ZERO) {
        return T::INFINITY;
    }
    let c2 = (cos_t * cos_t).min(T::ONE);
    let tan2 = (T::ONE - c2) / c2;
    ((T::ONE + alpha * alpha * tan2).sqrt() - T::ONE) * T::HALF
}

/// One-sided Smith–GGX masking G1 = 1/(1 + Λ) = 2/(1 + √(1 + α² tan²θ)).
#[inline]
pub fn g1_smith_ggx<T: Real>(cos_t: T, alpha: T) -> T {
    T::ONE / (T::ONE + lambda_ggx(cos_t, alpha))
}

/// Separable Smith–GGX G = G1(θi) G1(θo).
#[inline]
pub fn g_smith_ggx_separable<T: Real>(cos_i: T, cos_o: T, alpha: T) -> T {
    g1_smith_ggx(cos_i, alpha) * g1_smith_ggx(cos_o, alpha)
}

/// Height-correlated Smith–GGX G = 1/(1 + Λ(θi) + Λ(θo)).
#[inline]
pub fn g_smith_ggx_correlated<T: Real>(cos_i: T, cos_o: T, alpha: T) -> T {
    T::ONE / (T::ONE + lambda_ggx(cos_i, alpha) + lambda_ggx(cos_o, alpha))
}

/// The height-correlated visibility V = G/(4 (n·wi)(n·wo)) in the closed form that stays
/// finite at grazing: V = ½ / (n·wi √((n·wo)²(1−α²)+α²) + n·wo √((n·wi)²(1−α²)+α²)).
/// Returns 0 when either cosine is ≤ 0.
#[inline]
pub fn v_smith_ggx_correlated<T: Real>(cos_i: T, cos_o: T, alpha: T) -> T {
    if cos_i.is_nan() || cos_o.is_nan() || alpha.is_nan() {
        return T::NAN;
    }
    if !(cos_i > T::ZERO) || !(cos_o > T::ZERO) {
        return T::ZERO;
    }
    let a2 = alpha * alpha;
    let gv = cos_i * (cos_o * cos_o * (T::ONE - a2) + a2).sqrt();
    let gl = cos_o * (cos_i * cos_i * (T::ONE - a2) + a2).sqrt();
    let den = gv + gl;
    if den > T::ZERO {
        T::HALF / den
    } else {
        T::ZERO
    }
}

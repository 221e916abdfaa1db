//! Smith masking for the Beckmann and the Trowbridge–Reitz (GGX) distributions, in the
//! isotropic dot-product form (cosines n·w and one roughness α; Beckmann m = α = √2σ). These
//! are thin forms of [`crate::microfacet::Beckmann`] and
//! [`crate::microfacet::TrowbridgeReitz`] (α clamped into their [ε², 1/ε²]). A direction
//! at or below the horizon (cosine below [`crate::geometry::min_cos`]) is fully masked
//! (G1 = 0, Λ = ∞); α ≤ 0 gives Λ = 0; NaN in, NaN out.

use crate::microfacet::ggx::{iso_a2, lambda_finish, lambda_radicand, v_finish};
use crate::microfacet::{from_cos, Beckmann, Distribution, TrowbridgeReitz};
use crate::Real;

/// Smith's Λ for Beckmann roughness m: with a = 1/(m tan θ) = cos θ/(m sin θ),
/// Λ = (erf(a) − 1)/2 + exp(−a²)/(2a√π), written with erfc to avoid the cancellation.
#[inline]
pub fn lambda_beckmann<T: Real>(cos_t: T, m: T) -> T {
    if cos_t.is_nan() || m.is_nan() {
        return T::NAN;
    }
    if !(m > T::ZERO) {
        return if cos_t > T::ZERO {
            T::ZERO
        } else {
            T::INFINITY
        };
    }
    Beckmann::clamped(m, m).lambda(from_cos(cos_t))
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

/// Smith's Λ for GGX roughness α: Λ = (√(1 + α² tan²θ) − 1)/2, evaluated as
/// a²/(2c(c + √(c² + a²))) with a² = α² sin²θ (no cancellation, no overflow at grazing).
#[inline]
pub fn lambda_ggx<T: Real>(cos_t: T, alpha: T) -> T {
    if alpha.is_nan() {
        return T::NAN;
    }
    let a2 = if alpha > T::ZERO {
        iso_a2(cos_t, alpha)
    } else {
        T::ZERO
    };
    lambda_finish(cos_t, a2, lambda_radicand(cos_t, a2).sqrt())
}

/// One-sided Smith–GGX masking G1 = 1/(1 + Λ) = 2/(1 + √(1 + α² tan²θ)), evaluated as
/// 2c/(c + √(c² + α² sin²θ)).
#[inline]
pub fn g1_smith_ggx<T: Real>(cos_t: T, alpha: T) -> T {
    if cos_t.is_nan() || alpha.is_nan() {
        return T::NAN;
    }
    if !(alpha > T::ZERO) {
        return if cos_t >= crate::geometry::min_cos() {
            T::ONE
        } else {
            T::ZERO
        };
    }
    TrowbridgeReitz::clamped(alpha, alpha).g1(from_cos(cos_t))
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
/// finite at grazing: V = ½ / (n·wi √((n·wo)² + α² sin²θo) + n·wo √((n·wi)² + α² sin²θi))
/// (= ½/(n·wi √((n·wo)²(1−α²)+α²) + n·wo √((n·wi)²(1−α²)+α²))). Returns 0 when either cosine
/// is below [`crate::geometry::min_cos`].
#[inline]
pub fn v_smith_ggx_correlated<T: Real>(cos_i: T, cos_o: T, alpha: T) -> T {
    let (ai, ao) = v_a2(cos_i, cos_o, alpha);
    v_finish(
        cos_i,
        cos_o,
        lambda_radicand(cos_i, ai).sqrt(),
        lambda_radicand(cos_o, ao).sqrt(),
        alpha,
    )
}

/// The a² of both directions for [`v_smith_ggx_correlated`] (shared with the batch form).
#[inline]
pub(crate) fn v_a2<T: Real>(cos_i: T, cos_o: T, alpha: T) -> (T, T) {
    if alpha > T::ZERO {
        (iso_a2(cos_i, alpha), iso_a2(cos_o, alpha))
    } else {
        (T::ZERO, T::ZERO)
    }
}

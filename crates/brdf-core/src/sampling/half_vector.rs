//! Half-vector sampling (FCG §24.5.3).
//!
//! A half vector h drawn with density p_h(h) gives wi = −wo + 2(wo·h)h (eq 24.11), whose
//! density is p(wi) = p_h(h)/(4 wo·h) (eq 24.12).

use super::unit;
use crate::geometry::Vec3;
use crate::Real;

/// wi = 2(wo·h)h − wo (FCG eq 24.11) for unit h.
#[inline]
pub fn reflect_about<T: Real>(wo: Vec3<T>, h: Vec3<T>) -> Vec3<T> {
    wo.reflect(h)
}

/// p(wi) = p_h/(4 wo·h) (FCG eq 24.12); 0 when wo·h ≤ 0.
#[inline]
pub fn wi_pdf_from_h<T: Real>(p_h: T, wo_dot_h: T) -> T {
    if wo_dot_h > T::ZERO {
        p_h / (T::from_f64(4.0) * wo_dot_h)
    } else {
        T::ZERO
    }
}

/// φ in the first quadrant from eq 24.13: φ = atan(√((nu+1)/(nv+1)) tan(π ξ/2)), ξ ∈ [0, 1].
#[inline]
fn phi_quadrant<T: Real>(nu: T, nv: T, xi: T) -> T {
    let a = ((nu + T::ONE) / (nv + T::ONE)).sqrt();
    // atan2 form of atan(a tan x), exact at x = π/2.
    let x = xi.clamp(T::ZERO, T::ONE) * T::FRAC_PI_2;
    (a * x.sin()).atan2(x.cos())
}

/// The Ashikhmin–Shirley half vector: φ from eq 24.13 with the quadrant mapping of
/// §24.5.3 (ξ1 in [0, ¼): φ(4ξ1); [¼, ½): π − φ(1 − 4(½ − ξ1)), the "flip about π/2";
/// [½, ¾): π + φ(4ξ1 − 2); [¾, 1): 2π − φ(4(1 − ξ1))), and
/// cos θ = (1 − ξ2)^{1/(nu cos²φ + nv sin²φ + 1)} (eq 24.14). Exponents nu, nv ≥ 0.
/// Returns a unit h with h.z > 0; its density is [`ashikhmin_shirley_pdf_h`].
pub fn sample_ashikhmin_shirley_h<T: Real>(nu: T, nv: T, u: [T; 2]) -> Vec3<T> {
    let x1 = unit(u[0]);
    let q = T::from_f64(0.25);
    let four = T::from_f64(4.0);
    let phi = if x1 < q {
        phi_quadrant(nu, nv, four * x1)
    } else if x1 < T::HALF {
        T::PI - phi_quadrant(nu, nv, T::ONE - four * (T::HALF - x1))
    } else if x1 < T::from_f64(0.75) {
        T::PI + phi_quadrant(nu, nv, four * x1 - T::TWO)
    } else {
        T::TWO * T::PI - phi_quadrant(nu, nv, four * (T::ONE - x1))
    };
    let (sp, cp) = (phi.sin(), phi.cos());
    let e = nu * cp * cp + nv * sp * sp;
    let c = (T::ONE - unit(u[1]))
        .powf(T::ONE / (e + T::ONE))
        .min(T::ONE);
    let s = (T::ONE - c * c).max(T::ZERO).sqrt();
    Vec3::new(s * cp, s * sp, c)
}

/// p_h(h) = √((nu+1)(nv+1))/(2π) · (n·h)^{nu cos²φ + nv sin²φ} (FCG eq 24.10), per unit
/// solid angle of h, with the exponent written without trigonometry as
/// (nu h_x² + nv h_y²)/(1 − h_z²). 0 for h.z ≤ 0.
pub fn ashikhmin_shirley_pdf_h<T: Real>(nu: T, nv: T, h: Vec3<T>) -> T {
    if !(h.z > T::ZERO) {
        return if h.z.is_nan() { T::NAN } else { T::ZERO };
    }
    let c = h.z.min(T::ONE);
    ((nu + T::ONE) * (nv + T::ONE)).sqrt() / (T::TWO * T::PI) * c.powf(as_exponent(nu, nv, h))
}

/// The anisotropic exponent (nu h_x² + nv h_y²)/(1 − h_z²) (FCG eq 24.9, the part in the
/// exponent per docs/conventions.md §7); at h = n, where it is undefined and (n·h)^e = 1 for any
/// e, it returns (nu + nv)/2.
#[inline]
pub(crate) fn as_exponent<T: Real>(nu: T, nv: T, h: Vec3<T>) -> T {
    let t2 = h.x * h.x + h.y * h.y;
    if t2 > T::ZERO {
        (nu * h.x * h.x + nv * h.y * h.y) / t2
    } else {
        (nu + nv) * T::HALF
    }
}

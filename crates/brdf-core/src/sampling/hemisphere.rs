//! Uniform and cosine-weighted hemisphere sampling (FCG §24.2: p = 1/2π and p = cos θ/π).

use super::unit;
use crate::geometry::Vec3;
use crate::Real;

/// Uniform over the upper hemisphere: cos θ = u0, φ = 2π u1. Pdf 1/(2π).
pub fn sample_uniform_hemisphere<T: Real>(u: [T; 2]) -> Vec3<T> {
    let z = T::ONE - unit(u[0]);
    let r = (T::ONE - z * z).max(T::ZERO).sqrt();
    let phi = T::TWO * T::PI * unit(u[1]);
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// 1/(2π) for w.z ≥ 0, else 0.
#[inline]
pub fn uniform_hemisphere_pdf<T: Real>(w: Vec3<T>) -> T {
    if w.z >= T::ZERO {
        T::ONE / (T::TWO * T::PI)
    } else {
        T::ZERO
    }
}

/// Cosine-weighted over the upper hemisphere (a uniform disc point lifted to the sphere):
/// r = √u0, φ = 2π u1, z = √(1 − r²). Pdf cos θ/π.
pub fn sample_cosine_hemisphere<T: Real>(u: [T; 2]) -> Vec3<T> {
    let r2 = unit(u[0]);
    let r = r2.sqrt();
    let phi = T::TWO * T::PI * unit(u[1]);
    Vec3::new(
        r * phi.cos(),
        r * phi.sin(),
        (T::ONE - r2).max(T::ZERO).sqrt(),
    )
}

/// max(cos θ, 0)/π.
#[inline]
pub fn cosine_hemisphere_pdf<T: Real>(w: Vec3<T>) -> T {
    w.z.max(T::ZERO) / T::PI
}

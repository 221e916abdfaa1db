//! A cosine-power lobe around an arbitrary unit axis (the Phong lobe (v·r)^n of the standard
//! lighting model notes): p(w) = (n + 1)/(2π) · max(w·axis, 0)^n per unit solid angle, sampled by
//! cos α = u0^{1/(n+1)}, φ = 2π u1 about the axis.

use super::unit;
use crate::geometry::{Frame, Vec3};
use crate::Real;

/// Samples the lobe about unit `axis` with exponent n ≥ 0. `None` for a degenerate axis.
pub fn sample_cosine_lobe<T: Real>(axis: Vec3<T>, n: T, u: [T; 2]) -> Option<Vec3<T>> {
    let f = Frame::new(axis, Vec3::new(T::ONE, T::ZERO, T::ZERO))?;
    // 1 − u0 ∈ (0, 1] so that cos α > 0 even for huge n.
    let c = (T::ONE - unit(u[0]))
        .powf(T::ONE / (n + T::ONE))
        .min(T::ONE);
    let s = (T::ONE - c * c).max(T::ZERO).sqrt();
    let phi = T::TWO * T::PI * unit(u[1]);
    Some(f.to_world(Vec3::new(s * phi.cos(), s * phi.sin(), c)))
}

/// (n + 1)/(2π) · max(w·axis, 0)^n.
pub fn cosine_lobe_pdf<T: Real>(axis: Vec3<T>, n: T, w: Vec3<T>) -> T {
    let c = w.dot(axis).min(T::ONE);
    if !(c > T::ZERO) {
        return T::ZERO;
    }
    (n + T::ONE) / (T::TWO * T::PI) * c.powf(n)
}

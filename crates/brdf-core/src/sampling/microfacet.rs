//! Microfacet normal sampling.
//!
//! * Beckmann, anisotropic widths (ax, ay): D(h) = exp(−tan²θh (cos²φh/ax² + sin²φh/ay²))
//!   / (π ax ay cos⁴θh) (conventions.md §5 with m = ax = ay; Ward's lobe of seed 002 uses the
//!   same D). Sampled as D(h) cos θh: φ = atan2(ay sin 2πu1, ax cos 2πu1),
//!   tan²θh = −ln(1 − u0)/(cos²φ/ax² + sin²φ/ay²).
//! * GGX (Trowbridge–Reitz), isotropic α: h distributed as D(h) cos θh, tan²θh = α² u0/(1 − u0).
//! * GGX visible normals: h distributed as G1(wo) max(wo·h, 0) D(h)/cos θo (the slope-space
//!   stretch of the view direction, a uniform point on the projected hemisphere, unstretch).
//!   Beckmann visible normals are in [`super::visible_beckmann`] (no closed-form inverse;
//!   solved numerically).

use super::unit;
use crate::distribution::d_ggx;
use crate::geometry::Vec3;
use crate::masking::g1_smith_ggx;
use crate::Real;

/// Anisotropic Beckmann D(h) in 1/sr (widths ax, ay > 0); 0 for h.z ≤ 0.
pub fn beckmann_aniso_d<T: Real>(h: Vec3<T>, ax: T, ay: T) -> T {
    if !(h.z > T::ZERO) {
        return if h.z.is_nan() { T::NAN } else { T::ZERO };
    }
    let c2 = (h.z * h.z).min(T::ONE);
    let e = (h.x * h.x / (ax * ax) + h.y * h.y / (ay * ay)) / c2;
    (-e).exp() / (T::PI * ax * ay * c2 * c2)
}

/// Samples h with density D(h) cos θh for the anisotropic Beckmann D.
pub fn sample_beckmann_normal<T: Real>(ax: T, ay: T, u: [T; 2]) -> Vec3<T> {
    let a = T::TWO * T::PI * unit(u[1]);
    let phi = (ay * a.sin()).atan2(ax * a.cos());
    let (sp, cp) = (phi.sin(), phi.cos());
    let tan2 = -(T::ONE - unit(u[0])).ln() / (cp * cp / (ax * ax) + sp * sp / (ay * ay));
    let c = T::ONE / (T::ONE + tan2).sqrt();
    let s = (T::ONE - c * c).max(T::ZERO).sqrt();
    Vec3::new(s * cp, s * sp, c)
}

/// D(h) cos θh for the anisotropic Beckmann D.
#[inline]
pub fn beckmann_normal_pdf<T: Real>(h: Vec3<T>, ax: T, ay: T) -> T {
    beckmann_aniso_d(h, ax, ay) * h.z.max(T::ZERO)
}

/// Samples h with density D(h) cos θh for GGX roughness α.
pub fn sample_ggx_normal<T: Real>(alpha: T, u: [T; 2]) -> Vec3<T> {
    let u0 = unit(u[0]);
    // cos²θ = (1 − u0)/(1 + (α² − 1)u0)
    let c2 = ((T::ONE - u0) / (T::ONE + (alpha * alpha - T::ONE) * u0)).clamp(T::ZERO, T::ONE);
    let c = c2.sqrt();
    let s = (T::ONE - c2).max(T::ZERO).sqrt();
    let phi = T::TWO * T::PI * unit(u[1]);
    Vec3::new(s * phi.cos(), s * phi.sin(), c)
}

/// D(h) cos θh for GGX.
#[inline]
pub fn ggx_normal_pdf<T: Real>(h: Vec3<T>, alpha: T) -> T {
    d_ggx(h.z, alpha) * h.z.max(T::ZERO)
}

/// Samples a GGX visible normal for the view direction `wo` (wo.z > 0). `None` for
/// degenerate input.
pub fn sample_ggx_visible_normal<T: Real>(wo: Vec3<T>, alpha: T, u: [T; 2]) -> Option<Vec3<T>> {
    // The view direction in the stretched (α = 1) configuration.
    let v = Vec3::new(alpha * wo.x, alpha * wo.y, wo.z).normalize()?;
    let l2 = v.x * v.x + v.y * v.y;
    let t1 = if l2 > T::ZERO {
        Vec3::new(-v.y, v.x, T::ZERO).scale(T::ONE / l2.sqrt())
    } else {
        Vec3::new(T::ONE, T::ZERO, T::ZERO)
    };
    let t2 = v.cross(t1);
    // A uniform point on the unit disc, its second coordinate compressed onto the part of
    // the disc that is the projection of the visible half of the hemisphere.
    let r = unit(u[0]).sqrt();
    let phi = T::TWO * T::PI * unit(u[1]);
    let p1 = r * phi.cos();
    let mut p2 = r * phi.sin();
    let s = T::HALF * (T::ONE + v.z);
    p2 = (T::ONE - s) * (T::ONE - p1 * p1).max(T::ZERO).sqrt() + s * p2;
    let pz = (T::ONE - p1 * p1 - p2 * p2).max(T::ZERO).sqrt();
    let nh = t1.scale(p1).add(t2.scale(p2)).add(v.scale(pz));
    // Back to the rough configuration.
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(T::ZERO)).normalize()
}

/// G1(wo) max(wo·h, 0) D(h)/cos θo: the density of [`sample_ggx_visible_normal`].
pub fn ggx_visible_normal_pdf<T: Real>(wo: Vec3<T>, h: Vec3<T>, alpha: T) -> T {
    if !(wo.z > T::ZERO) {
        return T::ZERO;
    }
    let oh = wo.dot(h);
    if !(oh > T::ZERO) {
        return T::ZERO;
    }
    g1_smith_ggx(wo.z, alpha) * oh * d_ggx(h.z, alpha) / wo.z
}

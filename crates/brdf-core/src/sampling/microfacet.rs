//! Microfacet normal sampling in the free-function form used before the distributions got a
//! home of their own: each function is a thin form of [`crate::microfacet::Beckmann`] or
//! [`crate::microfacet::TrowbridgeReitz`] (widths clamped into their [ε², 1/ε²]).
//!
//! * Beckmann, anisotropic widths (ax, ay), distributed as D(h) cos θh (Ward's lobe uses the
//!   same D).
//! * GGX (Trowbridge–Reitz), isotropic α: D(h) cos θh, and visible normals
//!   G1(wo) max(wo·h, 0) D(h)/cos θo.
//!
//! Beckmann visible normals are in [`crate::microfacet::beckmann_visible`].

use crate::geometry::Vec3;
use crate::microfacet::{Beckmann, Distribution, TrowbridgeReitz};
use crate::Real;

/// Anisotropic Beckmann D(h) in 1/sr (widths ax, ay > 0); 0 for h.z ≤ 0.
pub fn beckmann_aniso_d<T: Real>(h: Vec3<T>, ax: T, ay: T) -> T {
    Beckmann::clamped(ax, ay).d(h)
}

/// Samples h with density D(h) cos θh for the anisotropic Beckmann D.
pub fn sample_beckmann_normal<T: Real>(ax: T, ay: T, u: [T; 2]) -> Vec3<T> {
    Beckmann::clamped(ax, ay).sample_normal(u)
}

/// D(h) cos θh for the anisotropic Beckmann D.
#[inline]
pub fn beckmann_normal_pdf<T: Real>(h: Vec3<T>, ax: T, ay: T) -> T {
    Beckmann::clamped(ax, ay).normal_pdf(h)
}

/// Samples h with density D(h) cos θh for GGX roughness α.
pub fn sample_ggx_normal<T: Real>(alpha: T, u: [T; 2]) -> Vec3<T> {
    TrowbridgeReitz::clamped(alpha, alpha).sample_normal(u)
}

/// D(h) cos θh for GGX.
#[inline]
pub fn ggx_normal_pdf<T: Real>(h: Vec3<T>, alpha: T) -> T {
    TrowbridgeReitz::clamped(alpha, alpha).normal_pdf(h)
}

/// Samples a GGX visible normal for the view direction `wo`. `None` for wo at or below the
/// horizon, or otherwise degenerate input (as the Beckmann sampler).
pub fn sample_ggx_visible_normal<T: Real>(wo: Vec3<T>, alpha: T, u: [T; 2]) -> Option<Vec3<T>> {
    TrowbridgeReitz::clamped(alpha, alpha).sample_visible_normal(wo, u)
}

/// G1(wo) max(wo·h, 0) D(h)/cos θo: the density of [`sample_ggx_visible_normal`].
pub fn ggx_visible_normal_pdf<T: Real>(wo: Vec3<T>, h: Vec3<T>, alpha: T) -> T {
    TrowbridgeReitz::clamped(alpha, alpha).visible_normal_pdf(wo, h)
}

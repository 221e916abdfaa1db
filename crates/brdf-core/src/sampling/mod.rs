//! Importance sampling of directions, each sampler with its exact pdf.
//!
//! All samplers take two uniform numbers u ∈ [0, 1)² (clamped into that range; callers
//! reject NaN) and work in the local frame (z = normal). Densities are per unit solid angle.
//!
//! * [`hemisphere`]: uniform (1/2π) and cosine-weighted (cos θ/π) hemispheres (FCG §24.2).
//! * [`lobe`]: a cosine-power lobe around any axis (Phong, (n+1)/2π cos^n).
//! * [`half_vector`]: reflection of wo about a half vector (FCG eq 24.11) with the pdf
//!   conversion p(wi) = p_h(h)/(4 wo·h) (eq 24.12), and the Ashikhmin–Shirley half-vector
//!   sampling with its quadrant mapping (eqs 24.10, 24.13, 24.14).
//! * Microfacet normals (D(h) cos θh) and visible normals have their home with each
//!   distribution: [`crate::microfacet::Beckmann`] and [`crate::microfacet::TrowbridgeReitz`]
//!   (`sample_normal`, `sample_visible_normal` and their pdfs); the Beckmann visible-normal
//!   free functions are re-exported here.

// `!(x > 0)` is deliberate throughout: it is true for NaN as well.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod half_vector;
pub mod hemisphere;
pub mod lobe;
pub use half_vector::{
    ashikhmin_shirley_pdf_h, reflect_about, sample_ashikhmin_shirley_h, wi_pdf_from_h,
};
pub use hemisphere::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_hemisphere,
    uniform_hemisphere_pdf,
};
pub use lobe::{cosine_lobe_pdf, sample_cosine_lobe};

use crate::Real;

/// Clamps u into [0, 1): u = 1.0 (a routine output of `f32` random-number conversion) and
/// u < 0 become 1 − ε and 0.
#[inline]
pub(crate) fn unit<T: Real>(u: T) -> T {
    u.clamp(T::ZERO, T::ONE - T::EPSILON)
}

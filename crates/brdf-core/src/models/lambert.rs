//! The Lambertian BRDF f = ρ/π (the diffuse term of the standard lighting model notes as a
//! BRDF; FCG §24.2), sampled with the cosine-weighted hemisphere.

use super::rgb::check_rgb;
use super::{above_or_zero, Brdf, BrdfFlags, BrdfSample, Rgb};
use super::{cosine_only_pdf, sample_delta_or_cosine};
use crate::geometry::Vec3;
use crate::{ParamError, Real};

/// Lambertian reflector with albedo ρ ∈ [0, 1] per channel. Reciprocal and energy conserving;
/// its directional albedo is exactly ρ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambert<T> {
    /// ρ, checked by [`Lambert::new`] (a sibling model holding a checked ρ may build the
    /// Lambertian term of its own BRDF from it).
    pub(super) albedo: Rgb<T>,
}

impl<T: Real> Lambert<T> {
    /// Checked constructor: each channel of ρ in [0, 1].
    pub fn new(albedo: Rgb<T>) -> Result<Self, ParamError> {
        Ok(Self {
            albedo: check_rgb("albedo", albedo, T::ZERO, T::ONE, "[0, 1]")?,
        })
    }
    /// The albedo ρ.
    pub fn albedo(&self) -> Rgb<T> {
        self.albedo
    }
}

impl<T: Real> Brdf<T> for Lambert<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, true, false)
    }
    /// f = ρ/π.
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || self.albedo.scale(T::ONE / T::PI))
    }
    /// cos θi/π.
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        cosine_only_pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        sample_delta_or_cosine(self, wo, u)
    }
}

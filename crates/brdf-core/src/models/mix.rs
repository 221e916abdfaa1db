//! The Lambertian-plus-specular mix of FCG §24.4: ρ = R_d/π + R_s ρ_s, ρ_s the normalised
//! mirror (a Dirac delta), with R_d + R_s ≤ 1 (Ward's condition quoted there) enforced by the
//! constructor. Reciprocal and energy conserving; the directional albedo is R_d + R_s for
//! every angle. The Dirac part is reported by [`Brdf::delta`] and sampled with probability
//! R_s/(R_s + mean R_d).

use super::rgb::check_rgb;
use super::{
    cosine_only_pdf, lobe_prob, mirror, sample_delta_or_cosine, valid_wo, Brdf, BrdfFlags,
    BrdfSample, DeltaLobe, Lambert, Rgb,
};
use crate::error::check_range;
use crate::geometry::Vec3;
use crate::{ParamError, Real};

/// Lambertian-plus-mirror mix (FCG §24.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LambertSpecularMix<T> {
    rd: Rgb<T>,
    rs: T,
}

impl<T: Real> LambertSpecularMix<T> {
    /// Checked constructor: R_d ∈ [0, 1] per channel, R_s ∈ [0, 1], R_d + R_s ≤ 1 per channel.
    pub fn new(rd: Rgb<T>, rs: T) -> Result<Self, ParamError> {
        let rd = check_rgb("rd", rd, T::ZERO, T::ONE, "[0, 1]")?;
        let rs = check_range("rs", rs, T::ZERO, false, T::ONE, "[0, 1]")?;
        if rd.max_channel() + rs > T::ONE {
            return Err(ParamError::OutOfRange {
                name: "rd + rs",
                range: "[0, 1] per channel",
            });
        }
        Ok(Self { rd, rs })
    }
    fn prob(&self) -> T {
        lobe_prob(self.rs, self.rd.mean())
    }
}

impl<T: Real> Brdf<T> for LambertSpecularMix<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, true, true)
    }
    /// R_d/π, the [`Lambert`] BRDF of albedo R_d (the Dirac part is in [`Brdf::delta`]).
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        Lambert { albedo: self.rd }.eval(wi, wo)
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        (T::ONE - self.prob()) * cosine_only_pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        sample_delta_or_cosine(self, wo, u)
    }
    /// The mirror direction with reflectance R_s.
    fn delta(&self, wo: Vec3<T>) -> Option<DeltaLobe<T>> {
        if !valid_wo(wo) {
            return None;
        }
        Some(DeltaLobe {
            wi: mirror(wo),
            reflectance: Rgb::splat(self.rs),
            prob: self.prob(),
        })
    }
}

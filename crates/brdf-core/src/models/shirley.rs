//! Shirley's (1991) damped model, FCG §24.4:
//!
//! ρ = R_f(θ) ρ_s + R_d (1 − R_f(θ))/π,  R_f(θ) = R0 + (1 − R0)(1 − cos θ)^5 (Schlick),
//!
//! ρ_s the mirror (a Dirac delta). **Not reciprocal by design**: exchanging the directions
//! changes the damping factor (FCG says so); the type flags it and the reciprocity test
//! skips it by that flag. Here θ is the angle of `wo`, the direction held fixed in the
//! directional albedo R(wo) = ∫ f cos θi dωi (for the FCG statement with the fixed direction
//! as the first argument); with that reading the albedo is R_f(θo) + R_d(1 − R_f(θo)) ≤ 1,
//! so the model is energy conserving.

use super::rgb::check_rgb;
use super::{above_or_zero, Brdf, BrdfFlags, BrdfSample, DeltaLobe, Rgb};
use crate::error::check_range;
use crate::fresnel::f_schlick;
use crate::geometry::Vec3;
use crate::{ParamError, Real};

/// Shirley's damped Lambert-plus-mirror model (non-reciprocal, see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShirleyDamped<T> {
    rd: Rgb<T>,
    r0: T,
}

impl<T: Real> ShirleyDamped<T> {
    /// Checked constructor: R_d ∈ [0, 1] per channel, R0 ∈ [0, 1].
    pub fn new(rd: Rgb<T>, r0: T) -> Result<Self, ParamError> {
        Ok(Self {
            rd: check_rgb("rd", rd, T::ZERO, T::ONE, "[0, 1]")?,
            r0: check_range("r0", r0, T::ZERO, false, T::ONE, "[0, 1]")?,
        })
    }
}

impl<T: Real> Brdf<T> for ShirleyDamped<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(false, true, true)
    }
    /// R_d (1 − R_f(θo))/π.
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            let rf = f_schlick(self.r0, wo.z);
            self.rd.scale((T::ONE - rf) / T::PI)
        })
    }
    smooth_layered_sampling!(rd);
}

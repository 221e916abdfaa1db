//! The coupled smooth-layered model of FCG §24.4 (Shirley, Smits, Hu & Lafortune 1997):
//!
//! ρ = [R0 + (1 − cos θ)^5 (1 − R0)] ρ_s + k R_m [1 − (1 − cos θ)^5][1 − (1 − cos θ')^5]
//! (FCG eq 24.3), ρ_s the mirror (a Dirac delta, reported by [`Brdf::delta`]).
//!
//! The constant k (docs/conventions.md §7). Constraint 24.1 with f(θ) = 1 − (1 − cos θ)^5 and
//! 1 − R_f(θ) = (1 − R0) f(θ) needs 2πk ∫₀¹ f(c) c dc = 1 − R0; ∫₀¹ f c dc = 1/2 − 1/42 =
//! 10/21, so k = 21(1 − R0)/(20π) ([`CoupledK::Conserving`], the default: with R_m = 1 the
//! albedo is then exactly 1 for every angle). FCG eq 24.2 prints k = 21/(20π(1 − R0))
//! ([`CoupledK::Printed`], kept as an option): its albedo is R_f(θ) + f(θ)/(1 − R0), which is
//! R0 + 1/(1 − R0) ≈ 1.0817 at normal incidence for R0 = 0.04, R_m = 1, so that variant is
//! flagged as not energy conserving. Both are reciprocal.

use super::rgb::check_rgb;
use super::{above_or_zero, Brdf, BrdfFlags, BrdfSample, DeltaLobe, Rgb};
use crate::error::check_range;
use crate::geometry::Vec3;
use crate::{ParamError, Real};

/// Which constant k multiplies the matte term.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CoupledK {
    /// k = 21(1 − R0)/(20π), from constraint 24.1 (energy conserving). Default.
    #[default]
    Conserving,
    /// k = 21/(20π(1 − R0)) as printed in FCG eq 24.2 (reflects more than arrives).
    Printed,
}

/// The coupled smooth-layered model (FCG eq 24.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoupledSmooth<T> {
    rm: Rgb<T>,
    r0: T,
    which: CoupledK,
    k: T,
}

/// f(θ) = 1 − (1 − cos θ)^5.
#[inline]
fn matte_shape<T: Real>(c: T) -> T {
    T::ONE - (T::ONE - c.clamp(T::ZERO, T::ONE)).powi(5)
}

impl<T: Real> CoupledSmooth<T> {
    /// Checked constructor: R_m ∈ [0, 1] per channel, R0 ∈ [0, 1) (the printed k divides by
    /// 1 − R0), and the choice of k.
    pub fn new(rm: Rgb<T>, r0: T, which: CoupledK) -> Result<Self, ParamError> {
        let rm = check_rgb("rm", rm, T::ZERO, T::ONE, "[0, 1]")?;
        let r0 = check_range("r0", r0, T::ZERO, false, T::ONE, "[0, 1)")?;
        if r0 >= T::ONE {
            return Err(ParamError::OutOfRange {
                name: "r0",
                range: "[0, 1)",
            });
        }
        let twenty_pi = T::from_f64(20.0) * T::PI;
        let k = match which {
            CoupledK::Conserving => T::from_f64(21.0) * (T::ONE - r0) / twenty_pi,
            CoupledK::Printed => T::from_f64(21.0) / (twenty_pi * (T::ONE - r0)),
        };
        Ok(Self { rm, r0, which, k })
    }
    /// The constant k in use.
    pub fn k(&self) -> T {
        self.k
    }
}

impl<T: Real> Brdf<T> for CoupledSmooth<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, self.which == CoupledK::Conserving, true)
    }
    /// k R_m f(θi) f(θo) (the matte term of eq 24.3).
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            self.rm
                .scale(self.k * matte_shape(wi.z) * matte_shape(wo.z))
        })
    }
    smooth_layered_sampling!(rm);
}

//! Ward's anisotropic model (named in the Cook–Torrance and Bank notes §10.4; Ward 1992,
//! "Measuring and modeling anisotropic reflection"):
//!
//! f = ρ_d/π + ρ_s · exp(−tan²θh (cos²φh/αx² + sin²φh/αy²)) / (4π αx αy √(cos θi cos θo)),
//!
//! h the half vector, φh its azimuth from the local x axis. Reciprocal. **Not energy
//! conserving**, and flagged so: the 1/√(cos θi cos θo) normalisation is exact only for small
//! roughness near normal incidence; at grazing views the albedo exceeds 1 (measured with
//! [`crate::albedo`], ρ_s = 1, ρ_d = 0, θo = 89.9°: 1.04 for αx = αy = 0.3, 1.50 for 1; the
//! plausibility suite checks the excess). Sampling: h with
//! the anisotropic Beckmann density D(h) cos θh of the same exponent
//! ([`crate::microfacet::Beckmann`], widths αx, αy) and eq 24.12, with probability
//! mean ρ_s/(mean ρ_s + mean ρ_d), else the cosine-weighted hemisphere.

use super::rgb::check_rgb;
use super::{above_or_zero, half_vector, lobe_prob, Brdf, BrdfFlags, BrdfSample, LobeHint, Rgb};
use super::{mixture_pdf, mixture_sample};
use crate::error::check_range;
use crate::geometry::Vec3;
use crate::microfacet::{Beckmann, Distribution};
use crate::{ParamError, Real};

/// Ward's anisotropic BRDF (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ward<T> {
    rd: Rgb<T>,
    rs: Rgb<T>,
    ax: T,
    ay: T,
}

impl<T: Real> Ward<T> {
    /// Checked constructor: ρ_d, ρ_s ∈ [0, 1] per channel, αx, αy ∈ [1e-4, 1e4] (RMS slopes).
    pub fn new(rd: Rgb<T>, rs: Rgb<T>, ax: T, ay: T) -> Result<Self, ParamError> {
        let (lo, hi) = (T::from_f64(1e-4), T::from_f64(1e4));
        Ok(Self {
            rd: check_rgb("rd", rd, T::ZERO, T::ONE, "[0, 1]")?,
            rs: check_rgb("rs", rs, T::ZERO, T::ONE, "[0, 1]")?,
            ax: check_range("ax", ax, lo, false, hi, "[1e-4, 1e4]")?,
            ay: check_range("ay", ay, lo, false, hi, "[1e-4, 1e4]")?,
        })
    }
    fn p_lobe(&self) -> T {
        lobe_prob(self.rs.mean(), self.rd.mean())
    }
    /// The specular lobe of the module docs for directions above the horizon,
    /// exp(−((h_x/αx)² + (h_y/αy)²)/h_z²)/(4π αx αy √(cos θi cos θo)); 0 for a half vector
    /// at or below the horizon.
    fn spec(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        match half_vector(wi, wo) {
            Some(h) if h.z > T::ZERO => {
                let c2 = (h.z * h.z).min(T::ONE);
                let e = (h.x * h.x / (self.ax * self.ax) + h.y * h.y / (self.ay * self.ay)) / c2;
                let g = (-e).exp();
                if g > T::ZERO {
                    // √cos θi √cos θo: both cosines are ≥ min_cos, whose square root is a
                    // normal number; the product of the roots cannot underflow to 0.
                    g / (T::from_f64(4.0) * T::PI * self.ax * self.ay * wi.z.sqrt() * wo.z.sqrt())
                } else {
                    T::ZERO
                }
            }
            _ => T::ZERO,
        }
    }
}

impl<T: Real> Brdf<T> for Ward<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, false, false)
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            self.rd
                .scale(T::ONE / T::PI)
                .add(self.rs.scale(self.spec(wi, wo)))
        })
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        let dist = Beckmann::clamped(self.ax, self.ay);
        mixture_pdf(self.p_lobe(), wo, wi, |h| dist.normal_pdf(h))
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        let dist = Beckmann::clamped(self.ax, self.ay);
        mixture_sample(self, self.p_lobe(), wo, u, |v| dist.sample_normal(v))
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::aniso(self.ax, self.ay)
    }
}

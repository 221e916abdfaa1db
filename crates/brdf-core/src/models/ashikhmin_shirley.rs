//! The Ashikhmin–Shirley anisotropic Phong model, FCG §24.5 (eqs 24.5–24.9):
//!
//! ρ_s = √((nu+1)(nv+1))/(8π) · (n·h)^{(nu (h·u)² + nv (h·v)²)/(1 − (h·n)²)}
//!       / ((h·k)·max(cos θi, cos θo)) · F(k·h)                      (eq 24.9 = eq 24.5),
//! F(k·h) = R_s + (1 − R_s)(1 − k·h)^5                                (eq 24.6),
//! ρ_d = 28 R_d/(23π) (1 − R_s)(1 − (1 − cos θi/2)^5)(1 − (1 − cos θo/2)^5)   (eq 24.7),
//! ρ = ρ_s + ρ_d                                                       (eq 24.8).
//!
//! u = x, v = y of the local frame; k·h = wi·h = wo·h. Eq 24.9 as printed puts the
//! denominator (h·k) max(cos θi, cos θo) inside the exponent, a typo (docs/conventions.md §7): here
//! it divides, as in eq 24.5. R_s and R_d are per channel.
//!
//! Reciprocal. Flagged energy conserving when R_s + R_d ≤ 1 per channel, the claim of the
//! model's authors; measured with [`crate::albedo`] over R_s/R_d ∈ {1/0, 0/1, ½/½, 0.05/0.95},
//! nu, nv from 0 to 10⁴ and θo up to 89°, the largest albedo is 0.9996 (R_s = 1,
//! nu = nv = 10⁴, normal incidence); the plausibility suite re-checks its cases. Sampling: the half vector of eqs 24.10, 24.13, 24.14 (with the quadrant mapping)
//! and eq 24.12, with probability mean(R_s)/(mean(R_s) + mean(R_d)(1 − mean(R_s))), else the
//! cosine-weighted hemisphere.

use super::rgb::check_rgb;
use super::{above_or_zero, half_vector, lobe_prob, Brdf, BrdfFlags, BrdfSample, LobeHint, Rgb};
use crate::error::check_range;
use crate::fresnel::f_schlick;
use crate::geometry::Vec3;
use crate::sampling::half_vector::as_exponent;
use crate::{ParamError, Real};

/// Ashikhmin–Shirley model (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AshikhminShirley<T> {
    rs: Rgb<T>,
    rd: Rgb<T>,
    nu: T,
    nv: T,
}

impl<T: Real> AshikhminShirley<T> {
    /// Checked constructor: R_s, R_d ∈ [0, 1] per channel, exponents nu, nv ∈ [0, 1e6].
    /// R_d = 0 gives the specular lobe alone (metals).
    pub fn new(rs: Rgb<T>, rd: Rgb<T>, nu: T, nv: T) -> Result<Self, ParamError> {
        let big = T::from_f64(1e6);
        Ok(Self {
            rs: check_rgb("rs", rs, T::ZERO, T::ONE, "[0, 1]")?,
            rd: check_rgb("rd", rd, T::ZERO, T::ONE, "[0, 1]")?,
            nu: check_range("nu", nu, T::ZERO, false, big, "[0, 1e6]")?,
            nv: check_range("nv", nv, T::ZERO, false, big, "[0, 1e6]")?,
        })
    }
    /// The specular lobe ρ_s (eq 24.9 with the denominator outside the exponent).
    pub fn specular(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            let h = match half_vector(wi, wo) {
                Some(h) => h,
                None => return Rgb::zero(),
            };
            let kh = wi.dot(h);
            if !(kh > T::ZERO) || !(h.z > T::ZERO) {
                return Rgb::zero();
            }
            let e = as_exponent(self.nu, self.nv, h);
            let norm =
                ((self.nu + T::ONE) * (self.nv + T::ONE)).sqrt() / (T::from_f64(8.0) * T::PI);
            let s = norm * h.z.min(T::ONE).powf(e) / (kh * wi.z.max(wo.z));
            self.rs.map(|r| s * f_schlick(r, kh))
        })
    }
    /// The coupled diffuse term ρ_d (eq 24.7).
    pub fn diffuse(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            let g = |c: T| T::ONE - (T::ONE - c.min(T::ONE) * T::HALF).powi(5);
            let s = T::from_f64(28.0) / (T::from_f64(23.0) * T::PI) * g(wi.z) * g(wo.z);
            self.rd.mul(self.rs.map(|r| T::ONE - r)).scale(s)
        })
    }
    fn p_lobe(&self) -> T {
        let s = self.rs.mean();
        lobe_prob(s, self.rd.mean() * (T::ONE - s))
    }
}

impl<T: Real> Brdf<T> for AshikhminShirley<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, self.rs.add(self.rd).max_channel() <= T::ONE, false)
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        self.specular(wi, wo).add(self.diffuse(wi, wo))
    }
    ashikhmin_shirley_sampling!(nu, nv);
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::aniso(
            (T::TWO / (self.nu + T::TWO)).sqrt(),
            (T::TWO / (self.nv + T::TWO)).sqrt(),
        )
    }
}

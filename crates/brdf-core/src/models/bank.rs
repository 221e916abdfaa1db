//! The Bank anisotropic BRDF of the Cook–Torrance and Bank notes (§10.3), specular part
//!
//! f_s = k_s (√(1 − (L·T)²) √(1 − (V·T)²) − (L·T)(V·T))^{n_s},
//!
//! L = wi, V = wo, T the tangent, plus a Lambertian k_d/π. The base is cos(α_L + α_V) with
//! α the angles from T; a negative base is dropped (0), as is any pair with a direction at or
//! below the horizon.
//!
//! The tangent ([`BankTangent`]): the notes take T = n × V ("the vertex normal crossed with
//! the view direction"), which makes T depend on the viewer: then V·T = 0, f_s =
//! k_s (1 − (L·T)²)^{n_s/2}, and the model is **not reciprocal** (flagged). A fixed material
//! tangent at azimuth φ_T in the tangent plane ([`BankTangent::Azimuth`], the default, φ_T = 0
//! i.e. T = x) makes it reciprocal. The lobe is not normalised, so the model is never flagged
//! energy conserving. Sampled with the cosine-weighted hemisphere.

use super::rgb::check_rgb;
use super::{above_or_zero, Brdf, BrdfFlags, BrdfSample, Rgb};
use super::{cosine_only_pdf, sample_delta_or_cosine};
use crate::error::check_range;
use crate::geometry::Vec3;
use crate::{ParamError, Real};

/// Where the Bank tangent comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BankTangent<T> {
    /// A fixed tangent (cos φ_T, sin φ_T, 0), φ_T in radians. Reciprocal.
    Azimuth(T),
    /// T = normalize(n × wo) as in the Cook–Torrance and Bank notes (x axis when wo = n).
    /// Not reciprocal.
    NormalCrossView,
}

impl<T: Real> Default for BankTangent<T> {
    fn default() -> Self {
        BankTangent::Azimuth(T::ZERO)
    }
}

/// Bank anisotropic BRDF (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bank<T> {
    kd: Rgb<T>,
    ks: Rgb<T>,
    ns: T,
    tangent: BankTangent<T>,
}

impl<T: Real> Bank<T> {
    /// Checked constructor: k_d ∈ [0, 1], k_s ∈ [0, ∞) per channel, n_s ∈ [0, 1e6], a finite
    /// tangent azimuth.
    pub fn new(kd: Rgb<T>, ks: Rgb<T>, ns: T, tangent: BankTangent<T>) -> Result<Self, ParamError> {
        if let BankTangent::Azimuth(a) = tangent {
            if !a.is_finite() {
                return Err(ParamError::NotFinite {
                    name: "tangent_azimuth",
                });
            }
        }
        Ok(Self {
            kd: check_rgb("kd", kd, T::ZERO, T::ONE, "[0, 1]")?,
            ks: check_rgb("ks", ks, T::ZERO, T::INFINITY, "[0, ∞)")?,
            ns: check_range("ns", ns, T::ZERO, false, T::from_f64(1e6), "[0, 1e6]")?,
            tangent,
        })
    }
    /// The tangent used for this viewer.
    pub fn tangent(&self, wo: Vec3<T>) -> Vec3<T> {
        match self.tangent {
            BankTangent::Azimuth(a) => Vec3::new(a.cos(), a.sin(), T::ZERO),
            BankTangent::NormalCrossView => Vec3::new(-wo.y, wo.x, T::ZERO)
                .normalize()
                .unwrap_or(Vec3::new(T::ONE, T::ZERO, T::ZERO)),
        }
    }
}

impl<T: Real> Brdf<T> for Bank<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(
            matches!(self.tangent, BankTangent::Azimuth(_)),
            false,
            false,
        )
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            let t = self.tangent(wo);
            let a = wi.dot(t).clamp(-T::ONE, T::ONE);
            let b = wo.dot(t).clamp(-T::ONE, T::ONE);
            let base = (T::ONE - a * a).sqrt() * (T::ONE - b * b).sqrt() - a * b;
            let s = if base > T::ZERO {
                base.min(T::ONE).powf(self.ns)
            } else {
                T::ZERO
            };
            self.kd.scale(T::ONE / T::PI).add(self.ks.scale(s))
        })
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        cosine_only_pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        sample_delta_or_cosine(self, wo, u)
    }
}

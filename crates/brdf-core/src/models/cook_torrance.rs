//! The Cook–Torrance model of the Cook–Torrance and Bank notes (§10.1):
//! I = I_diff + k_s I_l R_s, written as a BRDF
//!
//! f = k_d/π + k_s ⊗ R_s,  R_s = D(h) F(wi·h) G / (4 cos θi cos θo),
//!
//! with the Beckmann D of roughness m (docs/conventions.md §5), Schlick's F from R0 (FCG §24.3)
//! and by default Blinn's V-groove G (paper eq 4); R_s is the core's
//! [`TorranceSparrow`] specular term (paper eq 3), so any of its G can be chosen.
//! (Cook and Torrance's paper writes π instead of 4 in the denominator; the notes do not
//! give R_s, and the 4 of the microfacet derivation is used, as in the core.)
//!
//! Reciprocal unless the paper's printed G is chosen. Flagged energy conserving when
//! k_d + k_s ≤ 1 per channel and G is the V-groove G or a Smith G (single-scattering
//! microsurface models with F ≤ 1); the paper's modified G and G = 1 are not claimed.
//! Sampling: Beckmann normals (D cos θh; default) or Beckmann visible normals
//! ([`CookTorrance::with_sampling`]) with probability mean(k_s)/(mean(k_s) + mean(k_d)),
//! else the cosine-weighted hemisphere.

use super::rgb::check_rgb;
use super::MicrofacetSampling;
use super::{
    above_or_zero, lobe_prob, Brdf, BrdfFlags, BrdfSample, GeometricTerm, LobeHint, Rgb,
    TorranceSparrow,
};
use super::{mixture_pdf, mixture_sample};
use crate::error::check_range;
use crate::fresnel::Fresnel;
use crate::geometry::Vec3;
use crate::microfacet::Distribution;
use crate::{ParamError, Real};

/// Cook–Torrance BRDF (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct CookTorrance<T> {
    kd: Rgb<T>,
    ks: Rgb<T>,
    m: T,
    ts: TorranceSparrow<T>,
    sampling: MicrofacetSampling,
}

impl<T: Real> CookTorrance<T> {
    /// Checked constructor: k_d, k_s ∈ [0, 1] per channel, Beckmann roughness
    /// m ∈ [1e-4, 1e4], R0 ∈ [0, 1], and the G to use.
    pub fn new(kd: Rgb<T>, ks: Rgb<T>, m: T, r0: T, g: GeometricTerm) -> Result<Self, ParamError> {
        let kd = check_rgb("kd", kd, T::ZERO, T::ONE, "[0, 1]")?;
        let ks = check_rgb("ks", ks, T::ZERO, T::ONE, "[0, 1]")?;
        let m = check_range(
            "m",
            m,
            T::from_f64(1e-4),
            false,
            T::from_f64(1e4),
            "[1e-4, 1e4]",
        )?;
        let fresnel = Fresnel::schlick(r0)?;
        let ts = TorranceSparrow::from_alpha(m, g, fresnel, T::ONE, T::ZERO)?;
        Ok(Self {
            kd,
            ks,
            m,
            ts,
            sampling: MicrofacetSampling::Normals,
        })
    }
    /// The half-vector density of the specular lobe's sampler (default: Beckmann normals,
    /// D cos θh, as Cook and Torrance's D suggests; visible normals give lower variance
    /// at grazing wo). Evaluation does not change.
    pub fn with_sampling(mut self, sampling: MicrofacetSampling) -> Self {
        self.sampling = sampling;
        self
    }
    /// The specular term R_s = D F G/(4 cos θi cos θo) (scalar, before k_s), half vector
    /// from the vectors.
    pub fn r_s(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        self.ts.eval_specular_local(wi, wo)
    }
    fn p_lobe(&self) -> T {
        lobe_prob(self.ks.mean(), self.kd.mean())
    }
}

impl<T: Real> Brdf<T> for CookTorrance<T> {
    fn flags(&self) -> BrdfFlags {
        let g = self.ts.g_term();
        BrdfFlags {
            reciprocal: g != GeometricTerm::ModifiedPrinted,
            energy_conserving: matches!(
                g,
                GeometricTerm::Blinn
                    | GeometricTerm::SmithSeparable
                    | GeometricTerm::SmithCorrelated
            ) && self.kd.add(self.ks).max_channel() <= T::ONE,
            has_delta: false,
        }
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            let rs = self.r_s(wi, wo);
            self.kd.scale(T::ONE / T::PI).add(self.ks.scale(rs))
        })
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        let dist = self.ts.distribution();
        mixture_pdf(self.p_lobe(), wo, wi, |h| match self.sampling {
            MicrofacetSampling::Normals => dist.normal_pdf(h),
            MicrofacetSampling::VisibleNormals => dist.visible_normal_pdf(wo, h),
        })
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        let dist = self.ts.distribution();
        mixture_sample(self, self.p_lobe(), wo, u, |v| match self.sampling {
            MicrofacetSampling::Normals => dist.sample_normal(v),
            // A failed sample becomes h = 0, which the mixture rejects (wo·h = 0 → None).
            MicrofacetSampling::VisibleNormals => dist
                .sample_visible_normal(wo, v)
                .unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ZERO)),
        })
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(self.m)
    }
}

//! Trowbridge–Reitz (GGX) microfacet BRDF with Smith masking, isotropic or anisotropic:
//!
//! f = D(h) F(wi·h) G / (4 cos θi cos θo),
//! D = 1/(π αx αy ((h_x/αx)² + (h_y/αy)² + h_z²)²) ([`crate::microfacet::TrowbridgeReitz`];
//! α²/(π((n·h)²(α² − 1) + 1)²) when αx = αy = α),
//! F = F0 + (1 − F0)(1 − wi·h)^5 per channel (Schlick, F90 = 1, docs/conventions.md §8),
//! G = G1(θi) G1(θo) ([`SmithForm::Separable`]) or the height-correlated
//! 1/(1 + Λ(θi) + Λ(θo)) ([`SmithForm::Correlated`], default, written as the visibility
//! [`TrowbridgeReitz::v_correlated`]).
//!
//! Reciprocal and energy conserving (a single-scattering microsurface model with F ≤ 1).
//! Sampling: visible normals (default) or the distribution of normals D(h) cos θh
//! ([`MicrofacetSampling`]), converted with eq 24.12; reflected directions below the horizon
//! get weight 0.

use super::rgb::check_rgb;
use super::{
    above_or_zero, finish, half_vector, u_ok, valid_wo, Brdf, BrdfFlags, BrdfSample, LobeHint, Rgb,
};
use crate::fresnel::f_schlick;
use crate::geometry::{half_vector_and_cos, Vec3};
use crate::microfacet::{Distribution, TrowbridgeReitz};
use crate::sampling::{reflect_about, wi_pdf_from_h};
use crate::{ParamError, Real};

/// Which Smith form masks the microfacets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SmithForm {
    /// G = G1(θi) G1(θo).
    Separable,
    /// G = 1/(1 + Λ(θi) + Λ(θo)). Default.
    #[default]
    Correlated,
}

/// Which half-vector density the sampler uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MicrofacetSampling {
    /// Visible normals, G1(wo) max(wo·h, 0) D(h)/cos θo. Default.
    #[default]
    VisibleNormals,
    /// The distribution of normals D(h) cos θh.
    Normals,
}

/// GGX BRDF (see the module docs): the [`TrowbridgeReitz`] distribution, isotropic or
/// anisotropic, composed with a Smith G ([`SmithForm`]) and Schlick's Fresnel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx<T> {
    f0: Rgb<T>,
    dist: TrowbridgeReitz<T>,
    smith: SmithForm,
    sampling: MicrofacetSampling,
}

impl<T: Real> Ggx<T> {
    /// Checked constructor: F0 ∈ [0, 1] per channel, α ∈ [1e-4, 1e4].
    pub fn new(
        f0: Rgb<T>,
        alpha: T,
        smith: SmithForm,
        sampling: MicrofacetSampling,
    ) -> Result<Self, ParamError> {
        let alpha = crate::microfacet::check_alpha("alpha", alpha)?;
        Self::anisotropic(f0, alpha, alpha, smith, sampling)
    }
    /// Anisotropic checked constructor: widths αx (along the local x axis) and αy, each in
    /// [1e-4, 1e4].
    pub fn anisotropic(
        f0: Rgb<T>,
        alpha_x: T,
        alpha_y: T,
        smith: SmithForm,
        sampling: MicrofacetSampling,
    ) -> Result<Self, ParamError> {
        Ok(Self {
            f0: check_rgb("f0", f0, T::ZERO, T::ONE, "[0, 1]")?,
            dist: TrowbridgeReitz::new(alpha_x, alpha_y)?,
            smith,
            sampling,
        })
    }
    /// The roughness α (αx for an anisotropic surface).
    pub fn alpha(&self) -> T {
        self.dist.alpha().0
    }
    /// The distribution of normals.
    pub fn distribution(&self) -> TrowbridgeReitz<T> {
        self.dist
    }
}

impl<T: Real> Brdf<T> for Ggx<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, true, false)
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || {
            let (h, ih) = match half_vector_and_cos(wi, wo) {
                Some((h, ih)) if h.z > T::ZERO => (h, ih),
                _ => return Rgb::zero(),
            };
            let d = self.dist.d(h);
            let v = match self.smith {
                SmithForm::Correlated => self.dist.v_correlated(wi, wo),
                SmithForm::Separable => {
                    self.dist.g_separable(wi, wo) / (T::from_f64(4.0) * wi.z * wo.z)
                }
            };
            self.f0.map(|f| d * v * f_schlick(f, ih))
        })
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        if !valid_wo(wo) {
            return T::ZERO;
        }
        let h = match half_vector(wi, wo) {
            Some(h) => h,
            None => return T::ZERO,
        };
        let oh = wo.dot(h);
        match self.sampling {
            MicrofacetSampling::VisibleNormals => {
                wi_pdf_from_h(self.dist.visible_normal_pdf(wo, h), oh)
            }
            MicrofacetSampling::Normals => wi_pdf_from_h(self.dist.normal_pdf(h), oh),
        }
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        if !valid_wo(wo) || !u_ok(u) {
            return None;
        }
        let h = match self.sampling {
            MicrofacetSampling::VisibleNormals => self.dist.sample_visible_normal(wo, u)?,
            MicrofacetSampling::Normals => self.dist.sample_normal(u),
        };
        if !(wo.dot(h) > T::ZERO) {
            return None;
        }
        finish(self, wo, reflect_about(wo, h))
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        let (ax, ay) = self.dist.alpha();
        LobeHint::aniso(ax, ay)
    }
}

//! Trowbridge–Reitz (GGX) microfacet BRDF with Smith masking:
//!
//! f = D(h) F(wi·h) G / (4 cos θi cos θo),
//! D = α²/(π((n·h)²(α² − 1) + 1)²) ([`crate::distribution::d_ggx`]),
//! F = F0 + (1 − F0)(1 − wi·h)^5 per channel (Schlick, F90 = 1, conventions.md §8),
//! G = G1(θi) G1(θo) ([`SmithForm::Separable`]) or the height-correlated
//! 1/(1 + Λ(θi) + Λ(θo)) ([`SmithForm::Correlated`], default, written as the visibility
//! [`crate::masking::v_smith_ggx_correlated`]).
//!
//! Reciprocal and energy conserving (a single-scattering microsurface model with F ≤ 1).
//! Sampling: visible normals (default) or the distribution of normals D(h) cos θh
//! ([`MicrofacetSampling`]), converted with eq 24.12; reflected directions below the horizon
//! get weight 0.

use super::rgb::check_rgb;
use super::{
    above, finish, half_vector, u_ok, valid_wo, Brdf, BrdfFlags, BrdfSample, LobeHint, Rgb,
};
use crate::distribution::d_ggx;
use crate::error::check_range;
use crate::fresnel::f_schlick;
use crate::geometry::Vec3;
use crate::masking::{g_smith_ggx_separable, v_smith_ggx_correlated};
use crate::sampling::{
    ggx_normal_pdf, ggx_visible_normal_pdf, reflect_about, sample_ggx_normal,
    sample_ggx_visible_normal, wi_pdf_from_h,
};
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

/// GGX BRDF (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx<T> {
    f0: Rgb<T>,
    alpha: T,
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
        Ok(Self {
            f0: check_rgb("f0", f0, T::ZERO, T::ONE, "[0, 1]")?,
            alpha: check_range(
                "alpha",
                alpha,
                T::from_f64(1e-4),
                false,
                T::from_f64(1e4),
                "[1e-4, 1e4]",
            )?,
            smith,
            sampling,
        })
    }
    /// The roughness α.
    pub fn alpha(&self) -> T {
        self.alpha
    }
}

impl<T: Real> Brdf<T> for Ggx<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags {
            reciprocal: true,
            energy_conserving: true,
            has_delta: false,
        }
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        if !above(wi, wo) {
            return Rgb::zero();
        }
        let h = match half_vector(wi, wo) {
            Some(h) if h.z > T::ZERO => h,
            _ => return Rgb::zero(),
        };
        let d = d_ggx(h.z, self.alpha);
        let v = match self.smith {
            SmithForm::Correlated => v_smith_ggx_correlated(wi.z, wo.z, self.alpha),
            SmithForm::Separable => {
                g_smith_ggx_separable(wi.z, wo.z, self.alpha) / (T::from_f64(4.0) * wi.z * wo.z)
            }
        };
        let ih = wi.dot(h);
        self.f0.map(|f| d * v * f_schlick(f, ih))
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
                wi_pdf_from_h(ggx_visible_normal_pdf(wo, h, self.alpha), oh)
            }
            MicrofacetSampling::Normals => wi_pdf_from_h(ggx_normal_pdf(h, self.alpha), oh),
        }
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        if !valid_wo(wo) || !u_ok(u) {
            return None;
        }
        let h = match self.sampling {
            MicrofacetSampling::VisibleNormals => sample_ggx_visible_normal(wo, self.alpha, u)?,
            MicrofacetSampling::Normals => sample_ggx_normal(self.alpha, u),
        };
        if !(wo.dot(h) > T::ZERO) {
            return None;
        }
        finish(self, wo, reflect_about(wo, h))
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(self.alpha)
    }
}

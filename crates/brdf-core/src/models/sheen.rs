//! The microfacet sheen of Estevez and Kulla, "Production Friendly Microfacet Sheen BRDF"
//! (2017), as the glTF `KHR_materials_sheen` specification and Filament use it:
//!
//! f = color · D(h) · V(μi, μo),
//!
//! D the Charlie distribution ([`Charlie`]) of width α = r² (r the perceptual roughness,
//! clamped to α ≥ [`crate::microfacet::charlie::ALPHA_FLOOR`]), and V one of
//! ([`SheenVisibility`]):
//!
//! * `estevez-kulla`: V = G2/(4 μi μo), G2 = 1/(1 + Λ(μi) + Λ(μo)) with Estevez and Kulla's
//!   fitted Λ (the glTF specification's "sheen visibility");
//! * `ashikhmin`: V = 1/(4(μi + μo − μi μo)) (Ashikhmin and Premože 2007 in the form of
//!   Neubelt and Pettineo 2013; Filament's cloth).
//!
//! Both are symmetric in μi and μo and D depends on h only, so the model is reciprocal. It
//! is a layer meant to sit on a base BRDF, not an energy-conserving BRDF: no Fresnel term,
//! and V is not the visibility of D (the fitted Λ is not D's exact Smith Λ, Ashikhmin's V is
//! not a Smith term at all); the measured directional albedo exceeds 1 for rough sheen at
//! grazing (docs/conventions.md §11), so the model is flagged not energy conserving.
//!
//! Sampling: with probability ½ the half vector from D cos θh ([`Charlie::sample_normal`],
//! reflected about, FCG eqs 24.11–24.12), else the cosine-weighted hemisphere; the pdf is
//! that exact mixture. (Charlie has no visible-normal sampler; the D cos θh lobe alone would
//! put most of its samples below the horizon for a viewer near the normal and small r, the
//! cosine lobe covers those.) Half vectors facing away from wo are failed samples (`None`).

use super::rgb::check_rgb;
use super::{above_or_zero, mixture_pdf, mixture_sample, Brdf, BrdfFlags, BrdfSample, Rgb};
use crate::geometry::{half_vector_and_cos, min_cos, Dots, Vec3};
use crate::microfacet::charlie::{v_ashikhmin, Charlie};
use crate::{ParamError, Real};

/// Defines [`SheenVisibility`] from one list of (variant, option name): the catalogue and
/// the front ends read [`SheenVisibility::ALL`], [`SheenVisibility::NAMES`] and
/// [`SheenVisibility::RANGE`], so the names are spelled once.
macro_rules! visibility_options {
    ($(#[$m0:meta])* $v0:ident = $s0:literal $(, $(#[$m:meta])* $v:ident = $s:literal)* $(,)?) => {
        /// The visibility term of the sheen ([`Sheen`]).
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub enum SheenVisibility {
            $(#[$m0])*
            #[default]
            $v0,
            $($(#[$m])* $v,)*
        }
        impl SheenVisibility {
            /// Every option, in catalogue order (a choice's index is its position here).
            pub const ALL: &'static [Self] = &[Self::$v0 $(, Self::$v)*];
            /// The options' names, in the order of [`SheenVisibility::ALL`].
            pub const NAMES: &'static [&'static str] = &[$s0 $(, $s)*];
            /// The names joined by " | " (the catalogue's range text).
            pub const RANGE: &'static str = concat!($s0 $(, " | ", $s)*);
        }
    };
}

visibility_options! {
    /// G2/(4 μi μo) with Estevez and Kulla's fitted Λ (glTF `KHR_materials_sheen`). Default.
    EstevezKulla = "estevez-kulla",
    /// Ashikhmin's 1/(4(μi + μo − μi μo)) (Filament's cloth).
    Ashikhmin = "ashikhmin",
}

/// The Charlie sheen BRDF (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheen<T> {
    color: Rgb<T>,
    dist: Charlie<T>,
    visibility: SheenVisibility,
}

impl<T: Real> Sheen<T> {
    /// Checked constructor: color ∈ [0, 1] per channel, perceptual roughness r ∈ [0, 1]
    /// (α = r², at least 1e-4).
    pub fn new(
        color: Rgb<T>,
        roughness: T,
        visibility: SheenVisibility,
    ) -> Result<Self, ParamError> {
        Ok(Self {
            color: check_rgb("color", color, T::ZERO, T::ONE, "[0, 1]")?,
            dist: Charlie::from_roughness(roughness)?,
            visibility,
        })
    }
    /// The distribution.
    pub fn distribution(&self) -> Charlie<T> {
        self.dist
    }
    /// The visibility term.
    pub fn visibility(&self) -> SheenVisibility {
        self.visibility
    }
    /// The sheen colour.
    pub fn color(&self) -> Rgb<T> {
        self.color
    }
    /// D·V (1/sr) from μi, μo and the half vector's cos θh and sin²θh: the scalar lobe the
    /// colour multiplies. 0 when either cosine is below [`min_cos`]; NaN in, NaN out.
    pub fn dv(&self, mu_i: T, mu_o: T, cos_h: T, sin2_h: T) -> T {
        if mu_i.is_nan() || mu_o.is_nan() || cos_h.is_nan() || sin2_h.is_nan() {
            return T::NAN;
        }
        if !(mu_i >= min_cos()) || !(mu_o >= min_cos()) {
            return T::ZERO;
        }
        let d = self.dist.d_cos_sin2(cos_h, sin2_h);
        if d == T::ZERO {
            return T::ZERO;
        }
        let v = match self.visibility {
            SheenVisibility::EstevezKulla => self.dist.v_estevez_kulla(mu_i, mu_o),
            SheenVisibility::Ashikhmin => v_ashikhmin(mu_i, mu_o),
        };
        d * v
    }
    /// f per channel from dot products (shader form): cos θh = [`Dots::n_h`] and
    /// sin²θh = |H_t|²/|H|² ([`Dots::ht2`], [`Dots::hh`]); precision as `d`'s |H_t|² (exact
    /// to rounding from the vectors or angles, see [`Dots`]). 0 when either direction is at
    /// or below the horizon; NaN in, NaN out.
    pub fn eval_dots(&self, d: Dots<T>) -> Rgb<T> {
        let hh = d.hh();
        let sin2 = if hh > T::ZERO { d.ht2 / hh } else { T::ONE };
        let s = self.dv(d.n_i, d.n_o, d.n_h(), sin2);
        self.color.scale(s)
    }
}

/// The sheen as a [`Brdf`]: `eval` is 0 when either direction is at or below the horizon
/// and NaN (every channel) when any component of wi or wo is NaN.
impl<T: Real> Brdf<T> for Sheen<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, false, false)
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        let nan = |w: Vec3<T>| w.x.is_nan() || w.y.is_nan() || w.z.is_nan();
        if nan(wi) || nan(wo) {
            return Rgb::splat(T::NAN);
        }
        above_or_zero(wi, wo, || {
            let Some((h, _)) = half_vector_and_cos(wi, wo) else {
                return Rgb::zero();
            };
            let s = self.dv(wi.z, wo.z, h.z, h.x * h.x + h.y * h.y);
            self.color.scale(s)
        })
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        mixture_pdf(T::HALF, wo, wi, |h| self.dist.normal_pdf(h))
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        mixture_sample(self, T::HALF, wo, u, |v| self.dist.sample_normal(v))
    }
}

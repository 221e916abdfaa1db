//! Reflection models built from the distribution, masking and Fresnel pieces.
//!
//! Every model implements [`Brdf`]: evaluation in the local shading frame (z = normal,
//! both directions pointing away from the surface, `wi` toward the light, `wo` toward the
//! viewer), importance sampling and the matching pdf, a Dirac part kept apart
//! ([`Brdf::delta`]), and [`BrdfFlags`] saying whether the model is reciprocal, energy
//! conserving and has a Dirac part — the plausibility tests read those flags.
//!
//! | model | source |
//! |---|---|
//! | [`StandardLighting`] | the standard lighting model notes (Phong / Blinn-Phong lighting equation) |
//! | [`Lambert`], [`PhongNormalized`], [`BlinnPhongNormalized`] | the standard lighting model notes / FCG §24.2 |
//! | [`CookTorrance`] | the Cook–Torrance and Bank notes §10.1, with [`TorranceSparrow`] (paper eq 3) |
//! | [`LambertSpecularMix`], [`ShirleyDamped`], [`CoupledSmooth`] | FCG §24.4, eq 24.3 |
//! | [`AshikhminShirley`] | FCG eqs 24.5–24.9 |
//! | [`Bank`], [`Ward`] | the Cook–Torrance and Bank notes §10.3–10.4 |
//! | [`Ggx`] | Trowbridge–Reitz, isotropic or anisotropic, with Smith masking (docs/conventions.md §8) |
//! | [`TorranceSparrow`] | paper eq 3: Beckmann D, any [`GeometricTerm`], a [`crate::fresnel::Fresnel`] |
//! | [`Sheen`] | Estevez and Kulla 2017 (Charlie sheen), glTF `KHR_materials_sheen` (docs/conventions.md §11) |
//! | [`RoughDielectric`] | Walter et al. 2007, a BSDF: reflection and refraction through a rough interface (docs/conventions.md §12) |
//!
//! The microfacet models compose a distribution of [`crate::microfacet`] with a G and a
//! Fresnel term; every model is listed, with its parameters, in [`crate::catalogue`].

// `!(x > 0)` is deliberate throughout: it is true for NaN as well.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

/// The sampling half of a smooth-layered model's [`Brdf`] impl (FCG §24.4), for a model
/// with fields `r0` (Schlick's R0) and `$matte` (the matte reflectance): `delta` is the
/// mirror with reflectance R_f(θo) ([`schlick_mirror`]), chosen with probability
/// R_f/(R_f + mean(matte)(1 − R_f)) ([`lobe_prob`]), else the cosine-weighted hemisphere
/// ([`sample_delta_or_cosine`]); `pdf` is that hemisphere's share.
macro_rules! smooth_layered_sampling {
    ($matte:ident) => {
        fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
            if !$crate::models::valid_wo(wo) {
                return T::ZERO;
            }
            let rf = $crate::fresnel::f_schlick(self.r0, wo.z);
            let p = $crate::models::lobe_prob(rf, self.$matte.mean() * (T::ONE - rf));
            (T::ONE - p) * $crate::sampling::cosine_hemisphere_pdf(wi)
        }
        fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
            $crate::models::sample_delta_or_cosine(self, wo, u)
        }
        fn delta(&self, wo: Vec3<T>) -> Option<DeltaLobe<T>> {
            $crate::models::schlick_mirror(self.r0, wo, |rf| {
                $crate::models::lobe_prob(rf, self.$matte.mean() * (T::ONE - rf))
            })
        }
    };
}

/// The sampling half of a [`Brdf`] impl whose glossy lobe is sampled by the
/// Ashikhmin–Shirley half vector (FCG eqs 24.10, 24.13, 24.14) of exponents
/// (`self.$nu`, `self.$nv`), chosen with probability `self.p_lobe()`, else the
/// cosine-weighted hemisphere: `pdf` is [`mixture_pdf`] with
/// [`crate::sampling::ashikhmin_shirley_pdf_h`], `sample` is [`mixture_sample`] with
/// [`crate::sampling::sample_ashikhmin_shirley_h`].
macro_rules! ashikhmin_shirley_sampling {
    ($nu:ident, $nv:ident) => {
        fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
            $crate::models::mixture_pdf(self.p_lobe(), wo, wi, |h| {
                $crate::sampling::ashikhmin_shirley_pdf_h(self.$nu, self.$nv, h)
            })
        }
        fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
            $crate::models::mixture_sample(self, self.p_lobe(), wo, u, |v| {
                $crate::sampling::sample_ashikhmin_shirley_h(self.$nu, self.$nv, v)
            })
        }
    };
}

pub mod ashikhmin_shirley;
pub mod bank;
pub mod cook_torrance;
pub mod coupled;
pub mod ggx;
pub mod lambert;
pub mod mix;
pub mod phong;
pub mod rgb;
pub mod rough_dielectric;
pub mod sheen;
pub mod shirley;
pub mod standard;
pub mod torrance_sparrow;
pub mod ward;

pub use ashikhmin_shirley::AshikhminShirley;
pub use bank::{Bank, BankTangent};
pub use cook_torrance::CookTorrance;
pub use coupled::{CoupledK, CoupledSmooth};
pub use ggx::{Ggx, MicrofacetSampling, SmithForm};
pub use lambert::Lambert;
pub use mix::LambertSpecularMix;
pub use phong::{BlinnPhongNormalized, PhongNormalized};
pub use rgb::Rgb;
pub use rough_dielectric::{DielectricDistribution, RoughDielectric};
pub use sheen::{Sheen, SheenVisibility};
pub use shirley::ShirleyDamped;
pub use standard::{Highlight, Light, StandardLighting};
pub use torrance_sparrow::{GeometricTerm, TorranceSparrow};
pub use ward::Ward;

use crate::geometry::Vec3;
use crate::Real;

/// What a model claims about itself. The plausibility suite reads these: reciprocity is
/// tested only where `reciprocal`, albedo ≤ 1 only where `energy_conserving`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BrdfFlags {
    /// f(wi, wo) = f(wo, wi) for all pairs.
    pub reciprocal: bool,
    /// Directional albedo ≤ 1 for every wo (for the parameters given).
    pub energy_conserving: bool,
    /// The model has a Dirac (mirror) part, reported by [`Brdf::delta`] and not by
    /// [`Brdf::eval`].
    pub has_delta: bool,
}

impl BrdfFlags {
    /// The flags in field order: reciprocal, energy conserving, with a Dirac part.
    pub const fn new(reciprocal: bool, energy_conserving: bool, has_delta: bool) -> Self {
        Self {
            reciprocal,
            energy_conserving,
            has_delta,
        }
    }
}

/// One importance sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfSample<T> {
    /// The sampled direction toward the light (unit, local frame). May lie below the horizon;
    /// its weight is then 0.
    pub wi: Vec3<T>,
    /// For a continuous sample: the pdf of `wi` per unit solid angle, equal to
    /// [`Brdf::pdf`]`(wo, wi)`. For a specular sample: the probability of choosing the Dirac
    /// part, [`DeltaLobe::prob`].
    pub pdf: T,
    /// f(wi, wo)·max(cos θi, 0)/pdf (for a specular sample: the Dirac reflectance / prob).
    pub weight: Rgb<T>,
    /// `true` when the sample is the Dirac part.
    pub specular: bool,
}

/// The Dirac (mirror) part of a model for one wo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeltaLobe<T> {
    /// The mirror direction 2(n·wo)n − wo.
    pub wi: Vec3<T>,
    /// Its reflectance: the Dirac part's contribution to ∫ f cos θi dωi.
    pub reflectance: Rgb<T>,
    /// The probability that [`Brdf::sample`] returns it.
    pub prob: T,
}

/// The shape of a model's sharpest lobe in half-vector slope space, used by
/// [`crate::albedo`] to place its quadrature: the lobe around h = n is about `ax` wide
/// along x and `ay` along y (slopes, i.e. tan θh). Wide lobes use 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeHint<T> {
    /// Slope width along the local x axis.
    pub ax: T,
    /// Slope width along the local y axis.
    pub ay: T,
}

impl<T: Real> LobeHint<T> {
    /// A lobe as wide as the hemisphere (diffuse models).
    pub fn wide() -> Self {
        Self {
            ax: T::ONE,
            ay: T::ONE,
        }
    }
    /// An isotropic lobe of slope width `a`, clamped to [1e-4, 1].
    pub fn iso(a: T) -> Self {
        Self::aniso(a, a)
    }
    /// An anisotropic lobe, each width clamped to [1e-4, 1].
    pub fn aniso(ax: T, ay: T) -> Self {
        let c = |a: T| {
            if a.is_nan() {
                T::ONE
            } else {
                a.clamp(T::from_f64(1e-4), T::ONE)
            }
        };
        Self {
            ax: c(ax),
            ay: c(ay),
        }
    }
}

/// A reflection model in the local shading frame (z = normal, directions away from the
/// surface; `wi` toward the light, `wo` toward the viewer). Object safe.
pub trait Brdf<T: Real> {
    /// What the model claims (read by the tests).
    fn flags(&self) -> BrdfFlags;
    /// f(wi, wo) in 1/sr, per channel, without the Dirac part. 0 when either direction is at
    /// or below the horizon. (The standard lighting model returns a lit colour instead, see
    /// its docs.)
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T>;
    /// The pdf per unit solid angle over the whole sphere with which [`Brdf::sample`]
    /// returns a continuous (non-specular) `wi`; it includes directions below the horizon
    /// that the sampler can produce. Integrates to 1 − (Dirac probability) − (failure
    /// probability).
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T;
    /// Draws wi for the given wo from two uniform numbers in [0, 1). `None` when wo is at or
    /// below the horizon, not finite, or the sample fails (e.g. a half vector facing away
    /// from wo).
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>>;
    /// The Dirac part for this wo, if the model has one.
    fn delta(&self, _wo: Vec3<T>) -> Option<DeltaLobe<T>> {
        None
    }
    /// Where the sharpest lobe is, for the albedo quadrature.
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::wide()
    }
}

/// `true` when both directions are above the horizon: cosines at least
/// [`crate::geometry::min_cos`] (so subnormal cosines count as the horizon) and not NaN.
#[inline]
pub(crate) fn above<T: Real>(wi: Vec3<T>, wo: Vec3<T>) -> bool {
    let m = crate::geometry::min_cos();
    wi.z >= m && wo.z >= m
}

/// f(wi, wo) under [`Brdf::eval`]'s horizon rule: `f()` when both directions are above the
/// horizon ([`above`]), else 0 (every channel).
#[inline]
pub(crate) fn above_or_zero<T: Real>(
    wi: Vec3<T>,
    wo: Vec3<T>,
    f: impl FnOnce() -> Rgb<T>,
) -> Rgb<T> {
    if above(wi, wo) {
        f()
    } else {
        Rgb::zero()
    }
}

/// `true` when `w` is finite and above the horizon (cosine at least
/// [`crate::geometry::min_cos`]).
#[inline]
pub(crate) fn valid_wo<T: Real>(w: Vec3<T>) -> bool {
    w.x.is_finite() && w.y.is_finite() && w.z.is_finite() && w.z >= crate::geometry::min_cos()
}

pub(crate) use crate::geometry::half_vector;

/// Completes a continuous sample: pdf from the model, weight f·max(cos θi, 0)/pdf (0 below
/// the horizon). `None` when the pdf is not positive and finite, or the weight is not finite
/// (a direction the sampler reaches with a vanishing density).
pub(crate) fn finish<T: Real, B: Brdf<T> + ?Sized>(
    b: &B,
    wo: Vec3<T>,
    wi: Vec3<T>,
) -> Option<BrdfSample<T>> {
    let pdf = b.pdf(wo, wi);
    if !(pdf > T::ZERO) || !pdf.is_finite() {
        return None;
    }
    let weight = if wi.z > T::ZERO {
        b.eval(wi, wo).scale(wi.z / pdf)
    } else {
        Rgb::zero()
    };
    if !(weight.r.is_finite() && weight.g.is_finite() && weight.b.is_finite()) {
        return None;
    }
    Some(BrdfSample {
        wi,
        pdf,
        weight,
        specular: false,
    })
}

/// pdf of the two-component mixture used by the glossy models: a half-vector lobe with
/// probability `p`, the cosine-weighted hemisphere otherwise:
/// p · p_h(h)/(4 wo·h) + (1 − p) cos θi/π (the lobe part is FCG eq 24.12).
pub(crate) fn mixture_pdf<T: Real>(
    p: T,
    wo: Vec3<T>,
    wi: Vec3<T>,
    pdf_h: impl Fn(Vec3<T>) -> T,
) -> T {
    if !valid_wo(wo) {
        return T::ZERO;
    }
    let lobe = match half_vector(wi, wo) {
        Some(h) => crate::sampling::wi_pdf_from_h(pdf_h(h), wo.dot(h)),
        None => T::ZERO,
    };
    p * lobe + (T::ONE - p) * crate::sampling::cosine_hemisphere_pdf(wi)
}

/// Samples the mixture of [`mixture_pdf`]: with probability `p` a half vector from
/// `sample_h` reflected about (FCG eq 24.11), else a cosine-weighted direction. `None` when
/// the half vector faces away from wo.
pub(crate) fn mixture_sample<T: Real, B: Brdf<T> + ?Sized>(
    b: &B,
    p: T,
    wo: Vec3<T>,
    u: [T; 2],
    sample_h: impl Fn([T; 2]) -> Vec3<T>,
) -> Option<BrdfSample<T>> {
    if !valid_wo(wo) || !u_ok(u) {
        return None;
    }
    let (lobe, u0) = pick(u[0], p);
    let wi = if lobe {
        let h = sample_h([u0, u[1]]);
        if !(wo.dot(h) > T::ZERO) {
            return None;
        }
        crate::sampling::reflect_about(wo, h)
    } else {
        crate::sampling::sample_cosine_hemisphere([u0, u[1]])
    };
    finish(b, wo, wi)
}

/// Splits u0 between two lobes chosen with probabilities p and 1 − p, returning which lobe
/// (`true` = the first) and u0 rescaled to [0, 1). u0 is first clamped into [0, 1) (so
/// u0 = 1.0 and u0 < 0 behave as 1 − ε and 0): a lobe of probability 0 is never chosen.
#[inline]
pub(crate) fn pick<T: Real>(u0: T, p: T) -> (bool, T) {
    let u0 = crate::sampling::unit(u0);
    if u0 < p {
        (true, (u0 / p).min(T::ONE - T::EPSILON))
    } else {
        let q = T::ONE - p;
        let v = if q > T::ZERO { (u0 - p) / q } else { T::ZERO };
        (false, v.clamp(T::ZERO, T::ONE - T::EPSILON))
    }
}

/// Probability of the first of two lobes from their (mean) weights; ½ when both are 0.
#[inline]
pub(crate) fn lobe_prob<T: Real>(w1: T, w2: T) -> T {
    let s = w1 + w2;
    if s > T::ZERO {
        (w1 / s).clamp(T::ZERO, T::ONE)
    } else {
        T::HALF
    }
}

/// `true` when every u is finite.
#[inline]
pub(crate) fn u_ok<T: Real>(u: [T; 2]) -> bool {
    u[0].is_finite() && u[1].is_finite()
}

/// Sampling of the models whose only lobes are a Dirac part ([`Brdf::delta`]) and the
/// cosine-weighted hemisphere: the Dirac part with probability `delta.prob`, else the
/// hemisphere; a model without a Dirac part (`delta` is `None`) samples the hemisphere
/// with `u` as given.
pub(crate) fn sample_delta_or_cosine<T: Real, B: Brdf<T> + ?Sized>(
    b: &B,
    wo: Vec3<T>,
    u: [T; 2],
) -> Option<BrdfSample<T>> {
    if !valid_wo(wo) || !u_ok(u) {
        return None;
    }
    let Some(d) = b.delta(wo) else {
        return finish(b, wo, crate::sampling::sample_cosine_hemisphere(u));
    };
    let (spec, u0) = pick(u[0], d.prob);
    if spec {
        return Some(BrdfSample {
            wi: d.wi,
            pdf: d.prob,
            weight: d.reflectance.scale(T::ONE / d.prob),
            specular: true,
        });
    }
    finish(b, wo, crate::sampling::sample_cosine_hemisphere([u0, u[1]]))
}

/// pdf of models sampled by the cosine-weighted hemisphere alone: cos θi/π (0 for an
/// invalid wo).
pub(crate) fn cosine_only_pdf<T: Real>(wo: Vec3<T>, wi: Vec3<T>) -> T {
    if !valid_wo(wo) {
        return T::ZERO;
    }
    crate::sampling::cosine_hemisphere_pdf(wi)
}

/// The Dirac part of the smooth-layered models (FCG §24.4): the mirror direction with
/// Schlick reflectance R_f(θo) = R0 + (1 − cos θo)^5 (1 − R0), chosen with probability
/// `prob(R_f)`. `None` for an invalid wo.
pub(crate) fn schlick_mirror<T: Real>(
    r0: T,
    wo: Vec3<T>,
    prob: impl Fn(T) -> T,
) -> Option<DeltaLobe<T>> {
    if !valid_wo(wo) {
        return None;
    }
    let rf = crate::fresnel::f_schlick(r0, wo.z);
    Some(DeltaLobe {
        wi: mirror(wo),
        reflectance: Rgb::splat(rf),
        prob: prob(rf),
    })
}

/// The mirror direction 2(n·w)n − w about the local normal.
#[inline]
pub(crate) fn mirror<T: Real>(w: Vec3<T>) -> Vec3<T> {
    Vec3::new(-w.x, -w.y, w.z)
}

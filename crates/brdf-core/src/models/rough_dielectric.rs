//! The rough dielectric BSDF of Walter, Marschner, Li and Torrance, "Microfacet Models for
//! Refraction through Rough Surfaces" (EGSR 2007): reflection from and refraction through a
//! rough interface between two dielectrics, with the exact unpolarised Fresnel reflectance
//! ([`f_dielectric`], total internal reflection included).
//!
//! **Media.** The local frame's +z side is "outside", the −z side "inside"; η = η_inside /
//! η_outside ([`RoughDielectric::eta`]). η > 1: light arriving from outside enters a denser
//! medium (air → glass, 1.5); η < 1: the outside is the denser medium (glass → air seen from
//! the glass, 1/1.5), and total internal reflection happens past the critical angle. A
//! direction w lies in the medium of index η(w) = 1 for w_z > 0 and η for w_z < 0 (only the
//! ratio matters). η_i = η(wi), η_o = η(wo).
//!
//! **Reflection** (wi, wo on the same side; paper eqs 13, 20):
//! f_r = F(|wi·h_r|) D(h_r) G(wi, wo) / (4 |wi·n| |wo·n|), h_r = sign(wi·n)(wi + wo)/|wi + wo|.
//!
//! **Transmission** (opposite sides; paper eqs 16, 21), radiance convention (with η_o²):
//! f_t = |wi·h_t| |wo·h_t| / (|wi·n| |wo·n|) · η_o² (1 − F(|wi·h_t|)) D(h_t) G(wi, wo)
//!       / (η_i wi·h_t + η_o wo·h_t)²,
//! h_t = −(η_i wi + η_o wo)/|η_i wi + η_o wo|, flipped to the +n side; the pair is a
//! refraction pair only when wi·h_t and wo·h_t have the signs of wi·n and wo·n (else 0).
//! `wi` is toward the light and `wo` toward the viewer, so L(wo) = ∫ f L(wi) |cos θi| dωi
//! transports radiance: crossing into the denser medium multiplies radiance by (η_o/η_i)².
//! The **adjoint** (importance transport) is f_t*(wi, wo) = f_t(wo, wi) = (η_i/η_o)² f_t(wi,
//! wo) ([`RoughDielectric::eval_adjoint`]): the generalised reciprocity
//! f_t(wi, wo)/η_o² = f_t(wo, wi)/η_i² (paper §5.2; Veach's thesis §5.2).
//! ∫ f_t* |cos θi| dωi is the fraction of the energy arriving along wo that is transmitted
//! (≤ 1 − reflected).
//!
//! F is the exact dielectric Fresnel from wi's side, with relative index η_o/η_i (for a
//! refraction pair F(|wi·h|) = F(|wo·h|) from wo's side: the Fresnel equations are symmetric
//! under reversal of the ray).
//!
//! **Distribution and masking.** D is GGX ([`TrowbridgeReitz`]) or Beckmann ([`Beckmann`]),
//! isotropic with width α ([`DielectricDistribution`]), from [`crate::microfacet`]. G is the
//! **separable** Smith G = G1(wi) G1(wo) (paper eq 23), each G1 of the direction mirrored to
//! the +n side (Λ depends on |w_z|). Not the height-correlated form of the [`super::Ggx`]
//! default: for transmission that form is B(1 + Λ(wi), 1 + Λ(wo)) (the Beta function; Heitz
//! 2014, "Understanding the Masking-Shadowing Function", §6), which needs a log-gamma the
//! crate does not carry, and the reflection-only 1/(1 + Λi + Λo) used for refraction would
//! not be the height-correlated transmission term.
//!
//! **α floor.** α ∈ [0, 1e4] is accepted and floored to [`ALPHA_FLOOR`] = 1e-4 (as the
//! sheen floors its α): at the floor the lobes are 1e-4 wide in slope, the smooth interface
//! to the precision any table of the crate resolves, and D stays finite in f32.
//!
//! **η = 1** (an index-matched interface, which is invisible): F = 0, no reflection, and all
//! light continues straight on: the transmission is a Dirac in direction −wo
//! ([`Brdf::delta`] returns it with transmittance 1 and probability 1; `eval` is 0). The
//! formula above is no density there (η_i wi + η_o wo → 0 along the lobe).
//!
//! **Sampling** (wo outside, w_z > 0; for wo inside build the model with 1/η and mirror the
//! frame z → −z): a visible normal h of wo (Heitz 2018, "Sampling the GGX Distribution of
//! Visible Normals"; Beckmann: [`crate::microfacet::beckmann_visible`]), then reflection
//! about h with probability F(wo·h), refraction through h otherwise (Walter §5.3 with
//! Heitz's visible normals). pdf (per solid angle of wi, paper eqs 14, 17):
//! reflection F D_v(h_r)/(4 |wo·h_r|), transmission (1 − F) D_v(h_t) η_i² |wi·h_t| /
//! (η_i wi·h_t + η_o wo·h_t)², D_v(h) = G1(wo) max(wo·h, 0) D(h)/cos θo. The weight is
//! f |cos θi|/pdf (both hemispheres). The choice needs a third uniform number:
//! [`RoughDielectric::sample_with_choice`] takes it; the two-number [`Brdf::sample`] derives
//! it from the low-order digits of u0, c = frac(2^k u0) (k = 20 in f64, 12 in f32), so the
//! choice is exact only to the variation of F across a 2^−k-wide strip of u0 (below what the
//! chi-square test of 10⁶ samples resolves, docs/conventions.md §12).

use super::{u_ok, valid_wo, Brdf, BrdfFlags, BrdfSample, DeltaLobe, LobeHint, Rgb};
use crate::error::check_range;
use crate::fresnel::f_dielectric;
use crate::geometry::{min_cos, Vec3};
use crate::microfacet::{Beckmann, Distribution, TrowbridgeReitz};
use crate::{ParamError, Real};

/// The smallest width α the model uses; smaller α (down to 0) is raised to it.
pub const ALPHA_FLOOR: f64 = crate::microfacet::ALPHA_MIN;

/// The microfacet distribution of a [`RoughDielectric`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DielectricDistribution {
    /// Trowbridge–Reitz (GGX). Default.
    #[default]
    Ggx,
    /// Beckmann.
    Beckmann,
}

impl DielectricDistribution {
    /// Every option, in catalogue order (a choice's index is its position here).
    pub const ALL: &'static [Self] = &[Self::Ggx, Self::Beckmann];
    /// The options' names, in the order of [`DielectricDistribution::ALL`].
    pub const NAMES: &'static [&'static str] = &["ggx", "beckmann"];
    /// The names joined by " | " (the catalogue's range text).
    pub const RANGE: &'static str = "ggx | beckmann";
}

/// GGX or Beckmann, forwarding every [`Distribution`] function to the crate's own.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Micro<T> {
    Ggx(TrowbridgeReitz<T>),
    Beckmann(Beckmann<T>),
}

macro_rules! fwd {
    ($s:expr, $d:ident => $e:expr) => {
        match $s {
            Micro::Ggx($d) => $e,
            Micro::Beckmann($d) => $e,
        }
    };
}

impl<T: Real> Distribution<T> for Micro<T> {
    fn alpha(&self) -> (T, T) {
        fwd!(self, d => d.alpha())
    }
    fn d(&self, h: Vec3<T>) -> T {
        fwd!(self, d => d.d(h))
    }
    fn lambda(&self, w: Vec3<T>) -> T {
        fwd!(self, d => d.lambda(w))
    }
    fn g1(&self, w: Vec3<T>) -> T {
        fwd!(self, d => d.g1(w))
    }
    fn sample_normal(&self, u: [T; 2]) -> Vec3<T> {
        fwd!(self, d => d.sample_normal(u))
    }
    fn sample_visible_normal(&self, wo: Vec3<T>, u: [T; 2]) -> Option<Vec3<T>> {
        fwd!(self, d => d.sample_visible_normal(wo, u))
    }
}

/// The rough dielectric BSDF (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDielectric<T> {
    dist: Micro<T>,
    kind: DielectricDistribution,
    eta: T,
}

/// w mirrored to the +n side: (w_x, w_y, |w_z|) (Smith's Λ of a direction below).
#[inline]
fn up<T: Real>(w: Vec3<T>) -> Vec3<T> {
    Vec3::new(w.x, w.y, w.z.abs())
}

/// The refracted direction of wo through the facet h (wo·h = c > 0), Snell's law with
/// relative index e = η_t/η_wo: t = −wo/e + (c/e − √(1 − (1 − c²)/e²)) h. `None` past the
/// critical angle (total internal reflection). Public for the rough-glass albedo tables
/// (brdf-lut `generate/glass.rs`), which integrate this model's refraction.
pub fn refract<T: Real>(wo: Vec3<T>, h: Vec3<T>, c: T, e: T) -> Option<Vec3<T>> {
    let s2 = (T::ONE - c) * (T::ONE + c) / (e * e);
    if !(s2 < T::ONE) {
        return None;
    }
    let ct = ((T::ONE - s2).max(T::ZERO)).sqrt();
    wo.scale(-T::ONE / e).add(h.scale(c / e - ct)).normalize()
}

impl<T: Real> RoughDielectric<T> {
    /// Checked constructor: α ∈ [0, 1e4] (floored to [`ALPHA_FLOOR`]), η ∈ [0.1, 10].
    pub fn new(distribution: DielectricDistribution, alpha: T, eta: T) -> Result<Self, ParamError> {
        let a = check_range("alpha", alpha, T::ZERO, false, T::from_f64(1e4), "[0, 1e4]")?;
        let a = a.max(T::from_f64(ALPHA_FLOOR));
        let eta = check_range(
            "eta",
            eta,
            T::from_f64(0.1),
            false,
            T::from_f64(10.0),
            "[0.1, 10]",
        )?;
        let dist = match distribution {
            DielectricDistribution::Ggx => Micro::Ggx(TrowbridgeReitz::isotropic(a)?),
            DielectricDistribution::Beckmann => Micro::Beckmann(Beckmann::isotropic(a)?),
        };
        Ok(Self {
            dist,
            kind: distribution,
            eta,
        })
    }
    /// η = η_inside/η_outside.
    pub fn eta(&self) -> T {
        self.eta
    }
    /// The width α in use (after the floor).
    pub fn alpha(&self) -> T {
        self.dist.alpha().0
    }
    /// Which distribution.
    pub fn distribution(&self) -> DielectricDistribution {
        self.kind
    }
    /// The index of the medium of a direction with cosine `z` (1 outside, η inside).
    #[inline]
    fn side_eta(&self, z: T) -> T {
        if z > T::ZERO {
            T::ONE
        } else {
            self.eta
        }
    }
    /// The half vector of a pair, −(η_i wi + η_o wo)/|η_i wi + η_o wo| flipped to the +n side
    /// (for a same-side pair, η_i = η_o, this is sign(wi·n)(wi + wo)/|wi + wo|, eq 13; across
    /// the interface h_t, eq 16), and |η_i wi + η_o wo|² (the squared denominator of eqs 17,
    /// 21); `None` when it is undefined or horizontal.
    fn half_t(wi: Vec3<T>, ei: T, wo: Vec3<T>, eo: T) -> Option<(Vec3<T>, T)> {
        let s = wi.scale(ei).add(wo.scale(eo));
        let h = s.normalize()?;
        let h = if h.z < T::ZERO { h.scale(-T::ONE) } else { h };
        (h.z > T::ZERO).then(|| (h, s.length_sq()))
    }
    /// The BSDF f(wi, wo) in the radiance convention (module docs): f_r (eq 20) for a
    /// same-side pair, f_t (eq 21) across the interface. 0 at the horizon (|cos| below
    /// [`min_cos`]), with a NaN, for η = 1 (the Dirac is [`Brdf::delta`]), and when wi·h or
    /// wo·h does not have the sign of wi·n or wo·n (no reflection or refraction pair: eq 21's
    /// χ+ terms). For a reflection pair wi·h = |wi + wo|/2 (symmetric: reciprocal to the bit).
    pub fn eval_bsdf(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        let (ci, co) = (wi.z, wo.z);
        if !(ci.abs() >= min_cos()) || !(co.abs() >= min_cos()) || self.eta == T::ONE {
            return T::ZERO;
        }
        let (ei, eo) = (self.side_eta(ci), self.side_eta(co));
        let Some((h, den)) = Self::half_t(wi, ei, wo, eo) else {
            return T::ZERO;
        };
        let side = |w: Vec3<T>| {
            let d = w.dot(h);
            d != T::ZERO && (d > T::ZERO) == (w.z > T::ZERO)
        };
        if !(side(wi) && side(wo)) {
            return T::ZERO;
        }
        let reflect = (ci > T::ZERO) == (co > T::ZERO);
        let ih = if reflect {
            den.sqrt() / (T::TWO * ei)
        } else {
            wi.dot(h).abs()
        };
        // Relative index from wi's side: the medium across the interface over wi's.
        let f = f_dielectric(self.side_eta(-ci) / ei, ih);
        let lobe = if reflect {
            f / T::from_f64(4.0)
        } else {
            ih * wo.dot(h).abs() * (eo * eo / den) * (T::ONE - f)
        };
        let g = self.dist.g1(up(wi)) * self.dist.g1(up(wo));
        let v = lobe * self.dist.d(h) * g / (ci.abs() * co.abs());
        if v.is_finite() {
            v
        } else {
            T::ZERO
        }
    }
    /// The adjoint BSDF f*(wi, wo) = f(wo, wi) (importance transport): f_r unchanged,
    /// f_t* = (η_i/η_o)² f_t(wi, wo) (generalised reciprocity, module docs).
    pub fn eval_adjoint(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        let r = self.side_eta(wi.z) / self.side_eta(wo.z);
        self.eval_bsdf(wi, wo) * r * r
    }
    /// One part of the sampler's density at wi (either hemisphere: a reflection about a tilted
    /// facet may go below the surface, a refraction above), h = h_t of (wi, e_i; wo, 1):
    /// reflection (e_i = 1, h = (wi + wo)/|wi + wo|) F(wo·h) D_v(h)/(4 wo·h) (paper eq 14 with
    /// visible normals); refraction (e_i = η, the refracted ray in the medium η whichever side
    /// wi lies on) (1 − F(wo·h)) D_v(h) η² |wi·h|/|η wi + wo|² (eq 17), 0 unless wi·h < 0.
    fn pdf_part(&self, wo: Vec3<T>, wi: Vec3<T>, refract: bool) -> T {
        let ei = if refract { self.eta } else { T::ONE };
        let Some((h, den)) = Self::half_t(wi, ei, wo, T::ONE) else {
            return T::ZERO;
        };
        let (c, ih) = (wo.dot(h), wi.dot(h));
        if !(c > T::ZERO) || (refract && !(ih < T::ZERO)) {
            return T::ZERO;
        }
        let f = f_dielectric(self.eta, c);
        let pv = self.dist.visible_normal_pdf(wo, h);
        if refract {
            (T::ONE - f) * pv * ei * ei * (-ih) / den
        } else {
            f * pv / (T::from_f64(4.0) * c)
        }
    }
    /// Sampling with an explicit third uniform number `uc` for the choice between reflection
    /// (uc < F(wo·h)) and refraction (module docs); exact. `None` for wo not outside
    /// (w_z < [`min_cos`]) or not finite, non-finite u, or a sample the pdf does not cover.
    pub fn sample_with_choice(&self, wo: Vec3<T>, u: [T; 2], uc: T) -> Option<BrdfSample<T>> {
        if !valid_wo(wo) || !u_ok(u) || !uc.is_finite() {
            return None;
        }
        if self.eta == T::ONE {
            return self.delta(wo).map(|d| BrdfSample {
                wi: d.wi,
                pdf: d.prob,
                weight: d.reflectance,
                specular: true,
            });
        }
        let h = self.dist.sample_visible_normal(wo, u)?;
        let c = wo.dot(h);
        if !(c > T::ZERO) {
            return None;
        }
        let f = f_dielectric(self.eta, c);
        let wi = if crate::sampling::unit(uc) < f {
            wo.reflect(h)
        } else {
            refract(wo, h, c, self.eta)?
        };
        self.finish(wo, wi)
    }
    /// A continuous sample at wi: pdf from [`Brdf::pdf`], weight f |cos θi|/pdf.
    fn finish(&self, wo: Vec3<T>, wi: Vec3<T>) -> Option<BrdfSample<T>> {
        let pdf = self.pdf(wo, wi);
        if !(pdf > T::ZERO) || !pdf.is_finite() {
            return None;
        }
        let w = self.eval_bsdf(wi, wo) * wi.z.abs() / pdf;
        w.is_finite().then(|| BrdfSample {
            wi,
            pdf,
            weight: Rgb::splat(w),
            specular: false,
        })
    }
}

/// The BSDF as a [`Brdf`]: `eval` is [`RoughDielectric::eval_bsdf`] over the whole sphere
/// (wi or wo below the surface gives the transmitted or internally reflected part), the
/// sampler covers both hemispheres for wo outside, and the weight is f |cos θi|/pdf.
/// `reciprocal` refers to the reflection part (transmission obeys the generalised
/// reciprocity instead); `energy_conserving`: the reflected plus the adjoint-transmitted
/// energy is at most 1 (tests/tests/rough_dielectric.rs).
impl<T: Real> Brdf<T> for RoughDielectric<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(true, true, self.eta == T::ONE)
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        Rgb::splat(self.eval_bsdf(wi, wo))
    }
    /// pdf of [`Brdf::sample`] per solid angle of wi (module docs); 0 for wo not outside.
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        if !valid_wo(wo) || self.eta == T::ONE || wi.z.is_nan() {
            return T::ZERO;
        }
        let p = self.pdf_part(wo, wi, false) + self.pdf_part(wo, wi, true);
        if p.is_finite() {
            p
        } else {
            T::ZERO
        }
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        let k = if T::EPSILON.to_f64() > 1e-10 {
            4096.0
        } else {
            1048576.0
        };
        let x = crate::sampling::unit(u[0]) * T::from_f64(k);
        self.sample_with_choice(wo, u, x - x.floor())
    }
    /// For η = 1 (and wo outside): the straight-through Dirac −wo with transmittance 1,
    /// chosen with probability 1. `None` otherwise.
    fn delta(&self, wo: Vec3<T>) -> Option<DeltaLobe<T>> {
        (self.eta == T::ONE && valid_wo(wo)).then(|| DeltaLobe {
            wi: wo.scale(-T::ONE),
            reflectance: Rgb::splat(T::ONE),
            prob: T::ONE,
        })
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(self.alpha())
    }
}

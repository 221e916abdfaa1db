//! The standard lighting model (Phong / Blinn-Phong lighting), as in the standard lighting
//! model notes (docs/conventions.md §10):
//!
//! c_lit = Σ_k [ (s_k ⊗ m_spec) max(cos, 0)^{m_gls} + (s_k ⊗ m_diff) max(n·l_k, 0) ]
//!         + g_amb ⊗ m_amb + m_emis,
//!
//! with cos = v·r_k, r_k = 2(n·l_k)n − l_k (Phong), or cos = n·h_k,
//! h_k = (v + l_k)/|v + l_k| (Blinn-Phong); ⊗ is the per-channel product.
//!
//! Departures from the notes, on purpose:
//! * The notes' summary equation prints the diffuse term as max(n·l, 0)^{m_gls}; the
//!   diffuse section of the same notes (Lambert's law) has (n·l) with no exponent. The
//!   exponent is a typo and is not applied.
//! * "When cos θ < 0, ignore c_spec" (the notes) is applied, and a light at or below the
//!   horizon (n·l ≤ 0) contributes neither term, nor does a viewer at or below the horizon.
//!
//! This is a lighting equation, not a BRDF: the diffuse term carries n·l. Through the
//! [`Brdf`] trait, `eval(wi, wo)` returns the colour lit by one white unit light in
//! direction wi seen from wo (no ambient, no emission); the type is flagged neither
//! reciprocal nor energy conserving, and samples with the cosine-weighted hemisphere.

use super::rgb::check_rgb;
use super::{cosine_only_pdf, sample_delta_or_cosine};
use super::{Brdf, BrdfFlags, BrdfSample, LobeHint, Rgb};
use crate::error::check_range;
use crate::geometry::Vec3;
use crate::{ParamError, Real};

/// Which highlight the specular term uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Highlight {
    /// (v·r)^{m_gls}.
    #[default]
    Phong,
    /// (n·h)^{m_gls}.
    BlinnPhong,
}

/// One light: unit direction toward the light (local or world frame, the same as the
/// normal's) and its colour/intensity s (the standard lighting model notes: s_spec = s_diff).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light<T> {
    /// Unit direction toward the light.
    pub dir: Vec3<T>,
    /// Colour/intensity s of the light, per channel.
    pub color: Rgb<T>,
}

/// Material of the standard lighting model. Colours ≥ 0 per channel, gloss m_gls ≥ 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StandardLighting<T> {
    emission: Rgb<T>,
    ambient: Rgb<T>,
    diffuse: Rgb<T>,
    specular: Rgb<T>,
    gloss: T,
    highlight: Highlight,
}

impl<T: Real> StandardLighting<T> {
    /// Checked constructor: m_emis, m_amb, m_diff, m_spec ∈ [0, ∞) per channel,
    /// m_gls ∈ [0, 1e6].
    pub fn new(
        emission: Rgb<T>,
        ambient: Rgb<T>,
        diffuse: Rgb<T>,
        specular: Rgb<T>,
        gloss: T,
        highlight: Highlight,
    ) -> Result<Self, ParamError> {
        let inf = T::INFINITY;
        Ok(Self {
            emission: check_rgb("emission", emission, T::ZERO, inf, "[0, ∞)")?,
            ambient: check_rgb("ambient", ambient, T::ZERO, inf, "[0, ∞)")?,
            diffuse: check_rgb("diffuse", diffuse, T::ZERO, inf, "[0, ∞)")?,
            specular: check_rgb("specular", specular, T::ZERO, inf, "[0, ∞)")?,
            gloss: check_range("gloss", gloss, T::ZERO, false, T::from_f64(1e6), "[0, 1e6]")?,
            highlight,
        })
    }

    /// The specular cosine: v·r (Phong) or n·h (Blinn-Phong), for unit n, l, v.
    fn spec_cos(&self, n: Vec3<T>, l: Vec3<T>, v: Vec3<T>) -> T {
        match self.highlight {
            Highlight::Phong => v.dot(l.reflect(n)),
            Highlight::BlinnPhong => match l.add(v).normalize() {
                Some(h) => n.dot(h),
                None => T::ZERO,
            },
        }
    }

    /// The contribution of one light: (s ⊗ m_spec) max(cos, 0)^{m_gls} + (s ⊗ m_diff)(n·l),
    /// 0 when n·l ≤ 0 or n·v ≤ 0 (the standard lighting model notes, with the diffuse
    /// exponent typo fixed).
    pub fn light_term(&self, n: Vec3<T>, v: Vec3<T>, light: &Light<T>) -> Rgb<T> {
        let nl = n.dot(light.dir);
        let nv = n.dot(v);
        if nl.is_nan() || nv.is_nan() {
            return Rgb::splat(T::NAN);
        }
        if !(nl > T::ZERO) || !(nv > T::ZERO) {
            return Rgb::zero();
        }
        let c = self.spec_cos(n, light.dir, v);
        let spec = if c > T::ZERO {
            c.min(T::ONE).powf(self.gloss)
        } else {
            T::ZERO
        };
        light
            .color
            .mul(self.specular.scale(spec).add(self.diffuse.scale(nl)))
    }

    /// The full lighting equation c_lit for unit normal `n`, unit direction to the viewer
    /// `v`, any number of lights and the global ambient g_amb (the standard lighting model notes).
    pub fn shade(&self, n: Vec3<T>, v: Vec3<T>, lights: &[Light<T>], g_amb: Rgb<T>) -> Rgb<T> {
        let mut c = g_amb.mul(self.ambient).add(self.emission);
        for l in lights {
            c = c.add(self.light_term(n, v, l));
        }
        c
    }
}

impl<T: Real> Brdf<T> for StandardLighting<T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags::new(false, false, false)
    }
    /// The lit colour for one white unit light at wi seen from wo (not a BRDF, see the
    /// module docs).
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        let light = Light {
            dir: wi,
            color: Rgb::splat(T::ONE),
        };
        self.light_term(Vec3::new(T::ZERO, T::ZERO, T::ONE), wo, &light)
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        cosine_only_pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        sample_delta_or_cosine(self, wo, u)
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(T::ONE / (T::TWO * self.gloss + T::TWO).sqrt())
    }
}

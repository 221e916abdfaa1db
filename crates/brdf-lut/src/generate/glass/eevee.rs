//! Blender EEVEE's rough-glass channels (EEVEE Next, Blender ≥ 4.2: the arrays `btdf_ggx`
//! and `bsdf_ggx` of `eevee_lut.hh`), each the converged integral of exactly what EEVEE's
//! generator averages, by the ring rule of `glass/rings.rs`.
//!
//! **What EEVEE averages** (blender/blender
//! `source/blender/draw/engines/eevee/shaders/eevee_lut_comp.glsl`, functions
//! `ggx_btdf_gt_one` and `ggx_bsdf_split_sum`, with the sampling and weights of
//! `eevee_bxdf_microfacet_lib.glsl`; read, not copied). Each value is the mean over 512²
//! Hammersley points of a sample weight times a Schlick factor:
//!
//! * refraction: a GGX visible normal h (Dupuy & Benyoub 2023, density
//!   p(h) = G1(v)(v·h)₊D(h)/μ), t the refraction of −v through h; the weight is
//!   f_t |cos| / pdf = G1(|t_z|) (separable Smith G1·G1, Fresnel left out), kept only where
//!   t_z < 0 (a ray leaving on the wrong side, or the zero vector GLSL's `refract` returns
//!   under total internal reflection, adds nothing);
//! * reflection (η < 1 only): a bounded visible normal (Eto & Tokuyoshi 2023), whose pdf
//!   covers every l with l_z > 0, weight f_r |cos| / pdf = G1(v)G1(l)/(4μ) over the bounded
//!   pdf: its mean converges to ∫ p(h) G1(l) dh over l_z > 0, the same integral as with
//!   plain visible normals; rays with l_z ≤ 0 add nothing;
//! * Schlick factors S = (1 − cos)⁵: for `btdf_ggx` (η > 1) cos = |h·v| = c; for `bsdf_ggx`
//!   (η < 1) cos = |h·t| = s/η (s = √(η² − 1 + c²): the cosine of the refracted ray on the
//!   outer side), in both the transmission and the reflection factor. Under total internal
//!   reflection `refract` returns 0, so |h·t| = 0 and S = 1: all of the reflection goes to
//!   `bias`, none to `scale` or transmission.
//!
//! Hence, with the ring rule's p(h) and c = v·h (all functions of c on a ring):
//!
//! ```text
//! transmission_factor = ∫ p(h) (1 − S) G1(|t_z|) [t_z < 0] dh
//! scale               = ∫ p(h) (1 − S) G1(l_z) [l_z > 0] dh      (η < 1)
//! bias                = ∫ p(h) S G1(l_z) [l_z > 0] dh            (S = 1 under TIR)
//! ```
//!
//! The shader reads them as T = (1 − F0) transmission_factor and R = F0 scale + F90 bias.
//! scale + bias = ∫ p G1(l) over l_z > 0: GGX's directional albedo without Fresnel (the
//! split sum's A + B), independent of η.
//!
//! **α = 0** (EEVEE's slice r = 0): the facets are the mean surface, h = n, c = μ, every
//! G1 = 1: [`eevee_smooth`] (closed form). Other α below brdf-core's
//! [`ALPHA_FLOOR`] are floored to it, as [`super::glass_e`] does; μ is clamped to
//! [1e-9, 1].

use super::super::work::Work;
use super::rings::{glass_rings_with, Weights};
use brdf_core::models::rough_dielectric::ALPHA_FLOOR;

/// Schlick's factor (1 − cos)⁵, cos clamped to [0, 1].
fn schlick(cos: f64) -> f64 {
    (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

/// The α = 0 limit of EEVEE's channels at (μ, η): [scale, bias, transmission without
/// Fresnel, transmission_factor]. With h = n: s² = η² − 1 + μ²; under total internal
/// reflection (s² ≤ 0) [0, 1, 0, 0]; else scale = 1 − (1 − s/η)⁵, bias = (1 − s/η)⁵,
/// transmission 1 and transmission_factor = 1 − (1 − μ)⁵ (η > 1) or 1 − (1 − s/η)⁵ (η ≤ 1).
pub fn eevee_smooth(mu: f64, eta: f64) -> [f64; 4] {
    let s2 = (eta - 1.0) * (eta + 1.0) + mu * mu;
    if !(s2 > 0.0) {
        return [0.0, 1.0, 0.0, 0.0];
    }
    let ht = s2.sqrt() / eta;
    let sr = schlick(ht);
    let st = schlick(if eta > 1.0 { mu } else { ht });
    [1.0 - sr, sr, 1.0, 1.0 - st]
}

/// The ring rule with `weights` at (μ, α, η), or `smooth(μ, η)` at α = 0; NaN for NaN
/// input or η ≤ 0 (module docs: clamps).
fn channels(
    mu: f64,
    alpha: f64,
    eta: f64,
    weights: Weights,
    tol: f64,
    smooth: impl Fn([f64; 4]) -> [f64; 2],
) -> ([f64; 2], Work) {
    let mu = mu.clamp(1e-9, 1.0);
    if mu.is_nan() || !(alpha >= 0.0) || !(eta > 0.0) {
        return ([f64::NAN; 2], Work::default());
    }
    if alpha == 0.0 {
        return (smooth(eevee_smooth(mu, eta)), Work::default());
    }
    glass_rings_with(mu, alpha.max(ALPHA_FLOOR), eta, weights, tol)
}

/// EEVEE's transmission at (μ, α, η) to the absolute tolerance `tol` per channel:
/// [∫ p G1(|t|) (no Fresnel), `transmission_factor`] (module docs), with the estimate and
/// evaluations. The factor's Schlick cosine is |h·v| for η > 1 (`btdf_ggx`), |h·t| for
/// η ≤ 1 (`bsdf_ggx`).
pub fn eevee_transmission(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    let w = Weights::SchlickTransmission;
    channels(mu, alpha, eta, w, tol, |s| [s[2], s[3]])
}

/// EEVEE's reflection split at (μ, α, η) to `tol` per channel: [`scale`, `bias`] of
/// `bsdf_ggx` (module docs; Schlick cosine |h·t|, S = 1 under total internal reflection).
pub fn eevee_reflection(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    let w = Weights::SchlickSplit;
    channels(mu, alpha, eta, w, tol, |s| [s[0], s[1]])
}

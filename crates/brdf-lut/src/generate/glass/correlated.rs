//! The rough-glass albedo of Blender Cycles' GGX glass closure: the height-correlated
//! integrand whose E and E_avg Cycles tabulates (`table_ggx_glass_E`, `_inv_E`, `_Eavg`,
//! `_inv_Eavg`; brdf-engine-assets `cycles`).
//!
//! **Cycles' integrand** (pinned, read not copied, from blender/blender
//! `intern/cycles/kernel/closure/bsdf_microfacet.h`, `bsdf_microfacet_sample` and
//! `bsdf_microfacet_eval`, and `intern/cycles/app/cycles_precompute.cpp`,
//! `precompute_ggx_glass_E`). The precompute samples the closure from wo = (sin θ, 0, μ) with
//! path flag 0 and averages eval/pdf. The sampler draws h from the GGX visible normals
//! (Heitz 2018) and picks reflection with probability F(wo·h) (exact dielectric Fresnel; 1
//! under total internal reflection), so the lobe probability cancels F and 1 − F; eval is
//! F·common/(1 + Λi + Λo) for both lobes (the height-correlated Smith G2 of Heitz 2014,
//! eq. 99) and pdf is common·lobe/(1 + Λi), common the same D-and-Jacobian factor. So
//!
//! ```text
//! E = ∫ p(h) [ F w(l) 1{n·l > 0} + (1 − F) w(t) 1{t exists} ] dω_h,
//! w(o) = G2(wo, o)/G1(wo) = (1 + Λ(μ))/(1 + Λ(μ) + Λ(|n·o|)),
//! ```
//!
//! p(h) the visible-normal density of glass.rs's module docs, l the reflected and t the
//! refracted ray, E = R + T with R, T the two terms. The reflected ray must leave above
//! the surface (the sampler rejects n·l ≤ 0); the refracted ray is not tested (the test is
//! commented out in the sampler), so from inside (η < 1) rays refracted back upwards count,
//! with Λ(|n·t|) (Λ is even in the cosine). [`glass_e_correlated`] integrates this with the
//! generator's ring rule (`rings::Weights::HeightCorrelated`; every edge of the separable
//! integrand stays an edge, the refracted horizon n·t = 0 now a |n·t| kink inside T's
//! support, which starts at the TIR edge).
//!
//! **Limits.** η = 1: straight refraction, t = −wo, Λ(t) = Λ(μ): E = (1 + Λ)/(1 + 2Λ),
//! Λ = (√(1 + α²(1 − μ²)/μ²) − 1)/2 (at α = 1: E = (1 + μ)/2, E_avg = 5/6). α → 0 (the
//! α floor 1e-4 as in [`super::glass_e`]): R → F(μ), R + T → 1. What Cycles itself stores
//! differs where it leaves the rough path: α² ≤ 5e-7 (its singular path: E = 1) and
//! |η − 1| < 1e-4 (singular refraction: the refracted lobe's weight is 1).

use super::rings::{glass_rings_with, Weights};
use super::{e_avg, Row, Work};

/// (R, T) of Cycles' glass integrand (module docs) at (μ, α, η) to the absolute tolerance
/// `tol` per channel by the ring rule: values, the larger estimate, and the integrand
/// evaluations. Clamped as [`super::glass_e`]: μ to [1e-9, 1], α floored at 1e-4.
pub fn glass_e_correlated(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    super::clamped(mu, alpha, eta, |mu, alpha| {
        glass_rings_with(mu, alpha, eta, Weights::HeightCorrelated, tol)
    })
}

/// (R_avg, T_avg)(α, η) = 2∫₀¹ (R, T)(μ) μ dμ of [`glass_e_correlated`] to `tol` per
/// channel: [`super::glass_e_avg`]'s μ rule with this E.
pub fn glass_e_avg_correlated(alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    e_avg(
        Row {
            alpha,
            eta,
            e: glass_e_correlated,
        },
        tol,
    )
}

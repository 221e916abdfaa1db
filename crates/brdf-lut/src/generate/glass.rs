#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware: `!(x > 0)` is true for NaN.
//! Rough-glass albedo tables (kinds `glass-e`, `glass-e-avg`): the directional albedo of
//! brdf-core's rough dielectric ([`brdf_core::models::rough_dielectric`], Walter et al.
//! 2007, separable Smith G) split into its reflected part R and transmitted part T, and
//! their cosine-weighted averages.
//!
//! **Integrals.** Light arrives along wo = (sin θ, 0, μ) from the side whose index is 1;
//! η is the index of the far side over the near side (η ≥ 1: entering the denser medium;
//! η < 1: from inside glass, total internal reflection included — the same as the kernel
//! with η' = 1/η and the frame mirrored). With the visible-normal density
//! p(h) = G1(wo) (wo·h) D(h)/μ (Heitz 2018, "Sampling the GGX distribution of visible
//! normals", JCGT 7(4), §2), and wi_r = 2(wo·h)h − wo, wi_t the refraction of wo through h:
//!
//! ```text
//! R(μ) = ∫ f_r(wi, wo) |cos θi| dωi          = ∫ F(wo·h) G1(wi_r) p(h) dω_h   (n·wi_r > 0),
//! T(μ) = ∫ f_t*(wi, wo) |cos θi| dωi         = ∫ (1 − F(wo·h)) G1(wi_t) p(h) dω_h  (n·wi_t < 0),
//! ```
//!
//! f_t* the adjoint (importance) transmission (docs/conventions.md §12: without the η²
//! radiance factor), so T is the **energy fraction** transmitted and R + T ≤ 1, with
//! R + T = 1 − (energy lost to masking) → 1 and R → F(μ) as α → 0. (Walter 2007, eqs 14,
//! 17 and 20–21: f |cos θi| over the sampling density leaves the weights F G1(wi) and
//! (1 − F) G1(wi), bounded by 1.) Per channel: E_avg = 2∫₀¹ E(μ) μ dμ.
//!
//! **Rule (the generator's, [`glass_e`]).** Rings of the half vector around the normal
//! (`glass/rings.rs`): on a ring the integrand depends on wo·h alone, so the visibility edge, both
//! horizons and the total-internal-reflection edge are closed-form cuts; each piece is
//! integrated in a sin² substitution that makes the square roots at its ends (the ring's
//! ends, the TIR edge) analytic, the outer integral over the ring radius is broken where
//! the ring's structure changes (closed-form roots), and both levels are adaptive K15 with
//! an estimate of K15's own error. Measured: ~4.6k integrand evaluations per node for light
//! from outside, ~7k from inside (tests/glass_measure.rs), against ~279k for the cap rule.
//!
//! **Reference ([`glass_e_radial`], `lut verify`, both sides).** The same two integrals in
//! the other order, in other variables and with other integrand code (`glass/radial.rs`):
//! the half vector's azimuth φ outer, its radial variable inner (τ = tan θh near 0, ln τ,
//! then 1/τ toward the horizon); at each φ every edge is cut at its closed-form root in τ
//! (visibility, reflected horizon, TIR with its square root made analytic by the pieces'
//! sin² substitution, refracted horizon) and graded toward the two horizons (where G1 varies
//! on the scale α); the φ integral is broken where the inner structure changes (closed forms
//! in cos φ) and graded toward the complex ones next to the real axis; both levels are the
//! ring rule's adaptive K15 driver, the integrand brdf-core's `f_dielectric`, `refract` and
//! `TrowbridgeReitz::g1` on the half vector. Measured at 400 seeded random points per side
//! against the ring rule at 1e-10 (tests/glass_radial.rs): its error ≤ 0.64× its estimate
//! from inside and ≤ 0.063× from outside, ~30k integrand evaluations (~2 ms) per node from
//! inside and ~16k (~1.4 ms) from outside. The cap integrator ([`glass_e_cap`]: one
//! converged integral per channel over the spherical cap of the GGX visible-normal map,
//! [`brdf_core::split_sum::converged::integrate_cap`], rows cut where the support changes
//! sign) stays as a second cross-check in tests: it takes ~814k evaluations (~52 ms) from
//! inside and ~32k (~3 ms) from outside (150 points per side), and its estimate does not bound
//! its error: from inside at 85 of the 300 values, up to 1.9e-6 off (1.0e3× its estimate;
//! its R is 5.4e-6 off near the TIR edge where an 8000² brute-force rule agrees with both
//! other rules to 3e-8: tests/glass_tables.rs, tests/glass_measure.rs), from outside at 2
//! of 300, at most 2e-9 off but up to 8.5e2× a tiny estimate.
//!
//! **E_avg** (either rule's E) integrates E in μ by the ring rule's globally adaptive K15
//! (`glass/rings.rs`, its estimate) on panels broken at μ_c = √(1 − η²) for η < 1 (where
//! TIR sets in at normal incidence on the mean surface and E(μ) has a square-root edge
//! rounded over ~α) and graded toward it at α·8ʲ
//! (without the grading the estimate missed 8.6e-7 at (α, η) = (1e-4, 0.7)), each mapped by
//! a sin² substitution; each node's E is asked for the share of the tolerance its weight
//! allows, and its estimate enters through the weights (`mu_integral`).
//!
//! **Narrow limit.** The kernel floors α at [`brdf_core::models::rough_dielectric::ALPHA_FLOOR`]
//! = 1e-4; so do the tables (roughness 0 is α = 1e-4). There R = F(μ) + O(α²/μ²) and
//! R + T = 1 − O(α²/μ²) (GGX's tail of facets tilted beyond θ; tested).
//! **η = 1**: no reflection, straight refraction through every facet: R = 0 and T = G1(μ)
//! (the limit η → 1 of the rough integrals; the kernel's own η = 1 is a Dirac with T = 1,
//! which the separable G's second G1 does not reach: a property of the model).
//!
//! GGX only: Beckmann has no spherical-cap map in brdf-core yet (a typed error says so).

use super::work::{Work, REFERENCE_TOL, TOL};
use super::{Distribution, GenError, Kind, Spec};
use brdf_core::fresnel::f_dielectric;
use brdf_core::geometry::Vec3;
use brdf_core::microfacet::visible_cap::GgxVisibleCap;
use brdf_core::microfacet::{Distribution as _, TrowbridgeReitz};
use brdf_core::models::rough_dielectric::{refract, ALPHA_FLOOR};
use brdf_core::split_sum::converged::{integrate_cap, CapIntegrand, GgxSplitSum};
use std::format;

pub mod correlated;
pub mod eevee;
mod radial;
mod rings;

/// Tolerance of `lut verify`'s E_avg reference: 10× below the generator's [`TOL`].
pub const AVERAGE_REFERENCE_TOL: f64 = 2e-7;

/// The cap edge's graded breaks (`CapIntegrand::edge_grades`) for η ≥ 1: down to a gap of
/// ~α, the ring in which the GGX map's tail facets turn to the horizon (θ_max/4ᵏ ≤ α,
/// θ_max ≤ π), and at least 2; the last panel's own halvings resolve the rest.
fn cap_edge_grades(alpha: f64) -> u32 {
    let k = libm::ceil(libm::log(core::f64::consts::PI / alpha) / libm::log(4.0));
    (k as u32).max(2)
}

/// The cap edge grading of both parts (`CapIntegrand::edge_grades`): η ≥ 1 `grades`
/// (= [`cap_edge_grades`]); η < 1 the default (to the last bit): with the TIR kink inside
/// the pieces the coarser grading let the reflected estimate miss 2.6e-5 at
/// (μ, α, η) = (0.0314, 0.684, 0.349).
fn edge_grades_for(eta: f64, grades: u32) -> u32 {
    if eta < 1.0 {
        brdf_core::split_sum::converged::MAX_GRADE
    } else {
        grades
    }
}

/// The reflected part on visible normals: F(wo·h) G1(wi_r) where n·wi_r > 0.
struct Reflected {
    wo: Vec3<f64>,
    eta: f64,
    dist: TrowbridgeReitz<f64>,
    /// `cap_edge_grades(α)`.
    grades: u32,
    /// The GGX split sum's integrand on the same map: its support is also n·wi_r, and its
    /// row form gives the horizon cuts exactly.
    form: GgxSplitSum<f64>,
}

impl CapIntegrand<f64> for Reflected {
    /// n·wi_r = 2(wo·h)h_z − μ.
    fn support(&self, h: Vec3<f64>) -> f64 {
        let c = self.wo.dot(h);
        if !(c > 0.0) {
            return -1.0;
        }
        2.0 * c * h.z - self.wo.z
    }
    /// The row form of n·wi_r: the split sum's ([`GgxSplitSum`], the same support).
    fn row_form(&self, cp: f64, sp: f64) -> Option<[f64; 6]> {
        self.form.row_form(cp, sp)
    }
    // Only the horizon is cut. Cutting the TIR cone too, as a second quadratic
    // form (a square-root kink of F for η < 1) was tried and left out: at (μ, α, η) =
    // (0.2, 1, 0.34) the φ integral of the unmerged pieces did not converge (open).
    // Splitting R into its TIR and non-TIR parts, each cut by the scan of
    // min(n·wi_r, ±(1 − η² − (wo·h)²)) (`lit_intervals`, as T is), was tried too: R at
    // (μ, r, η) = (0.71875, 0.39091, 0.62958) came out 6.6e-6 below the 8000² brute-force
    // value with an estimate of 5e-10, and 1.4e-6 below it at (0.60529, 0.94848, 0.46407)
    // (tests/glass_tables.rs's two brute-force points).
    /// [`edge_grades_for`].
    fn edge_grades(&self) -> u32 {
        edge_grades_for(self.eta, self.grades)
    }
    /// F(wo·h) G1(wi_r).
    fn value(&self, h: Vec3<f64>, _s: f64) -> [f64; 2] {
        let wi = self.wo.reflect(h);
        [
            f_dielectric(self.eta, self.wo.dot(h)) * self.dist.g1(wi),
            0.0,
        ]
    }
}

/// The transmitted part on visible normals: (1 − F(wo·h)) G1(wi_t) where wi_t exists and
/// n·wi_t < 0.
struct Refracted {
    wo: Vec3<f64>,
    eta: f64,
    dist: TrowbridgeReitz<f64>,
    /// `cap_edge_grades(α)`.
    grades: u32,
}

impl Refracted {
    /// wo·h and the refracted direction, if any.
    fn ray(&self, h: Vec3<f64>) -> Option<(f64, Vec3<f64>)> {
        let c = self.wo.dot(h);
        if !(c > 0.0) {
            return None;
        }
        Some((c, refract(self.wo, h, c, self.eta)?))
    }
}

impl CapIntegrand<f64> for Refracted {
    /// min(η² − 1 + (wo·h)², −n·wi_t): positive where a refracted ray exists (no total
    /// internal reflection) and goes below the surface; continuous through the TIR edge.
    fn support(&self, h: Vec3<f64>) -> f64 {
        let c = self.wo.dot(h);
        if !(c > 0.0) {
            return -1.0;
        }
        let tir = self.eta * self.eta - 1.0 + c * c;
        if !(tir > 0.0) {
            return tir;
        }
        match self.ray(h) {
            Some((_, t)) => tir.min(-t.z),
            None => -1.0,
        }
    }
    /// η ≥ 1: uncut (the support is positive on the whole visible cap): one piece per row
    /// and a denser φ transition scan. η < 1: the scan of the support
    /// (`converged::lit_intervals`) with the full edge grading. The TIR edge and the
    /// refracted horizon as exact cuts with square-root end substitutions (tried, not
    /// kept) were measured 7.1e-7 off at (μ, r, η) = (0.661, 0.659, 0.690) with an
    /// estimate of 4.2e-7, where the scan is 1.4e-7 off (brute-force midpoint rule, 8000²;
    /// tests/glass_measure.rs).
    fn uncut(&self) -> bool {
        !(self.eta < 1.0)
    }
    /// [`edge_grades_for`].
    fn edge_grades(&self) -> u32 {
        edge_grades_for(self.eta, self.grades)
    }
    /// (1 − F(wo·h)) G1(wi_t mirrored to the +n side).
    fn value(&self, h: Vec3<f64>, _s: f64) -> [f64; 2] {
        match self.ray(h) {
            Some((c, t)) => {
                let up = Vec3::new(t.x, t.y, -t.z);
                [(1.0 - f_dielectric(self.eta, c)) * self.dist.g1(up), 0.0]
            }
            None => [0.0; 2],
        }
    }
}

/// (R, T) at (μ, α, η) to the absolute tolerance `tol` per channel by the generator's
/// ring rule (`glass/rings.rs`): values, the larger estimate, and the integrand evaluations. μ is
/// clamped to [1e-9, 1] and α floored at 1e-4 (module docs).
pub fn glass_e(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    clamped(mu, alpha, eta, |mu, alpha| {
        rings::glass_e_rings(mu, alpha, eta, tol)
    })
}

/// `rule(μ, α)` with μ clamped to [1e-9, 1] and α floored at the kernel's
/// [`ALPHA_FLOOR`], as every rough-glass rule takes them; NaN values (no work) for a NaN μ
/// or α or η ≤ 0.
fn clamped(
    mu: f64,
    alpha: f64,
    eta: f64,
    rule: impl FnOnce(f64, f64) -> ([f64; 2], Work),
) -> ([f64; 2], Work) {
    let mu = mu.clamp(1e-9, 1.0);
    let alpha = alpha.max(ALPHA_FLOOR);
    if mu.is_nan() || alpha.is_nan() || !(eta > 0.0) {
        return ([f64::NAN; 2], Work::default());
    }
    rule(mu, alpha)
}

/// (R, T) at (μ, α, η) to `tol` by the radial rule (`glass/radial.rs`: the half vector's
/// azimuth outer, its radial variable inner, brdf-core's F, refraction and G1): `lut
/// verify`'s independent reference for [`glass_e`] (module docs, **Reference**). Values,
/// the larger estimate, and the integrand evaluations. μ clamped to [1e-9, 1], α floored at
/// 1e-4.
pub fn glass_e_radial(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    clamped(mu, alpha, eta, |mu, alpha| {
        radial::glass_e_radial(mu, alpha, eta, tol)
    })
}

/// (R, T) at (μ, α, η) to `tol` by the cap integrator (module docs, **Reference**): a
/// second cross-check of [`glass_e`] in tests (no longer `lut verify`'s reference). Values, the larger estimate, and the
/// work (integrand plus cut-search evaluations). μ clamped to [1e-9, 1], α floored at 1e-4.
pub fn glass_e_cap(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    let mu = mu.clamp(1e-9, 1.0);
    let alpha = alpha.max(ALPHA_FLOOR);
    let Ok(dist) = TrowbridgeReitz::isotropic(alpha) else {
        return ([f64::NAN; 2], Work::default());
    };
    let sv = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let wo = Vec3::new(sv, 0.0, mu);
    let map = GgxVisibleCap::new(alpha, mu);
    let form = GgxSplitSum::new(alpha, mu);
    let grades = cap_edge_grades(alpha);
    let r = integrate_cap(
        &map,
        &Reflected {
            wo,
            eta,
            dist,
            form,
            grades,
        },
        tol,
    );
    let t = integrate_cap(
        &map,
        &Refracted {
            wo,
            eta,
            dist,
            grades,
        },
        tol,
    );
    let evals = (r.evals + r.cut_evals + t.evals + t.cut_evals) as u64;
    let error = r.error[0].max(t.error[0]);
    ([r.value[0], t.value[0]], Work { error, evals })
}

/// The share of an E_avg's tolerance given to the E(μ) at its nodes (their estimates enter
/// through the quadrature weights, which sum to ∫ 2μ dμ = 1 over [0, 1]).
const E_SHARE: f64 = 0.4;

/// 2∫ (R, T)(μ) μ dμ over the panels between `breaks`, each mapped by μ = a + (b − a) sin²β
/// (the square-root edge of E at μ_c, a break, becomes analytic in β), globally adaptive
/// K15 ([`rings`]'s rule and estimate) held to 0.9 tol. The E(μ) at a node of weight
/// W·jac (Σ W = number of pieces) is asked for [`E_SHARE`] tol/(jac · pieces) (at most
/// 1e-3), so the weighted sum of their estimates, which enters the panels' estimates, is
/// ≤ E_SHARE tol: (values, estimate, work). Measured: 1.65× fewer evaluations than
/// locally adaptive K15/G7 panels with every E at tol/4 (tests/glass_measure.rs).
fn mu_integral(breaks: &[f64], row: Row, tol: f64) -> ([f64; 2], Work) {
    let (alpha, eta) = (row.alpha, row.eta);
    let pieces = breaks.len() - 1;
    let mut evals = 0u64;
    let mut f = |t: f64, j: Option<usize>| {
        let (i, sb, cb) = rings::substitution(t, j, pieces - 1);
        let (a, b) = (breaks[i], breaks[i + 1]);
        let mu = a + (b - a) * sb * sb;
        let jac = 2.0 * mu * (b - a) * 2.0 * sb * cb * core::f64::consts::FRAC_PI_2;
        if !(jac > 0.0) {
            return ([0.0; 2], [0.0; 2]);
        }
        // The node's E enters with weight ~W·jac (Σ W = pieces): its own share.
        let e_tol = (E_SHARE * tol / (jac * pieces as f64)).min(1e-3);
        let (v, w) = (row.e)(mu, alpha, eta, e_tol);
        evals += w.evals;
        (v.map(|v| v * jac), [w.error * jac; 2])
    };
    let (v, e) = rings::adaptive(pieces, 0.9 * tol, &mut f);
    let round = 64.0 * f64::EPSILON * v[0].abs().max(v[1].abs());
    let error = e[0].max(e[1]) + round;
    (v, Work { error, evals })
}

/// (R_avg, T_avg)(α, η) = 2∫₀¹ (R, T)(μ) μ dμ to `tol` per channel, broken at
/// μ_c = √(1 − η²) for η < 1 (module docs).
pub fn glass_e_avg(alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    e_avg(
        Row {
            alpha,
            eta,
            e: glass_e,
        },
        tol,
    )
}

/// [`glass_e_avg`] with the radial rule's E ([`glass_e_radial`]): `lut verify`'s reference.
pub fn glass_e_avg_radial(alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    e_avg(
        Row {
            alpha,
            eta,
            e: glass_e_radial,
        },
        tol,
    )
}

/// [`glass_e_avg`] with the cap integrator's E ([`glass_e_cap`]): a second cross-check
/// (tests).
pub fn glass_e_avg_cap(alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    e_avg(
        Row {
            alpha,
            eta,
            e: glass_e_cap,
        },
        tol,
    )
}

/// An E(μ) to tolerance: [`glass_e`], [`glass_e_radial`] or [`glass_e_cap`].
type EFn = fn(f64, f64, f64, f64) -> ([f64; 2], Work);

/// The (α, η) of an E_avg and the rule of its E(μ).
#[derive(Clone, Copy)]
struct Row {
    alpha: f64,
    eta: f64,
    e: EFn,
}

/// E_avg of `row` (see [`glass_e_avg`]).
fn e_avg(row: Row, tol: f64) -> ([f64; 2], Work) {
    let breaks = mu_breaks(row.alpha.max(ALPHA_FLOOR), row.eta);
    mu_integral(&breaks, row, tol)
}

/// The μ panels of E_avg: [0, 1], for η < 1 broken at μ_c = √(1 − η²) (where TIR sets in
/// at normal incidence on the mean surface: E has a square-root edge there, rounded over
/// ~α) and graded toward it on both sides at μ_c ± α·8ʲ while that is closer than 0.1
/// (the narrow limit: T(μ) ≈ 1 − F(μ) ∝ √(μ − μ_c) beyond a rounding of width ~α), and at
/// μ = η, below which the TIR cone wo·h = √(1 − η²) crosses the half vectors' horizon
/// (h_z = 0, where wo·h ≤ sin θo): E(μ) is not analytic there for rough surfaces (without
/// this break E_avg at (α, η) = (0.3, 1/1.5) missed 4e-7, past its estimate: étendue test),
/// and at μ = 2μ_c, where the ring rule's crossing of the TIR edge and the reflected horizon
/// (1 + τ² = 4μ_c²/μ², [`rings`]) enters at τ = 0. (The other outer breaks of the ring rule
/// are roots of quadratics whose discriminants, k²(1 − k²) and μ²η², never vanish; their
/// leading and constant terms change sign at μ = η and μ = μ_c.) Graded toward μ_c at
/// α·8ʲ (4ʲ: 792k instead of 687k evaluations at (α, η) = (1e-4, 0.7), the same errors).
fn mu_breaks(alpha: f64, eta: f64) -> std::vec::Vec<f64> {
    let mut b = std::vec![0.0, 1.0];
    let mc = if eta < 1.0 {
        ((1.0 - eta) * (1.0 + eta)).sqrt()
    } else {
        0.0
    };
    if mc > 0.0 && mc < 1.0 {
        b.extend([mc, eta, 2.0 * mc].into_iter().filter(|m| *m < 1.0));
        let mut d = alpha;
        while d < 0.1 {
            b.extend(
                [mc - d, mc + d]
                    .into_iter()
                    .filter(|m| *m > 0.0 && *m < 1.0),
            );
            d *= 8.0;
        }
    }
    b.sort_by(|x, y| x.total_cmp(y));
    b.dedup_by(|x, y| (*x - *y).abs() < 1e-12);
    b
}

/// Whether the kind is a rough-glass kind.
pub fn is_glass(kind: Kind) -> bool {
    matches!(kind, Kind::GlassAlbedo | Kind::GlassAverageAlbedo)
}

/// The rough-glass node at `x` to tolerance `tol` with the E rule `e` ([`glass_e`] or
/// [`glass_e_radial`]): (μ, roughness, η) or (roughness, η).
fn at(spec: &Spec, x: &[f64], tol: f64, e: EFn) -> ([f64; 2], Work) {
    match (spec.kind, x) {
        (Kind::GlassAlbedo, &[mu, r, eta]) => e(mu, spec.width_sigma(r).0, eta, tol),
        (Kind::GlassAverageAlbedo, &[r, eta]) => {
            let alpha = spec.width_sigma(r).0;
            e_avg(Row { alpha, eta, e }, tol)
        }
        _ => ([f64::NAN; 2], Work::default()),
    }
}

/// The generator's node (channels R, T in `out`) and its [`Work`], to [`TOL`] per channel;
/// `None` for a kind that is not rough glass.
pub fn node(spec: &Spec, x: &[f64], out: &mut [f64]) -> Option<Work> {
    if !is_glass(spec.kind) {
        return None;
    }
    let (v, w) = at(spec, x, TOL, glass_e);
    for (o, v) in out.iter_mut().zip(v) {
        *o = v;
    }
    Some(w)
}

/// `lut verify`'s reference at `x`: the radial rule ([`glass_e_radial`], the other order of
/// integration in other variables and other integrand code from the generator's
/// [`glass_e`]) at [`REFERENCE_TOL`] (100× tighter; E_avg at [`AVERAGE_REFERENCE_TOL`], whose
/// μ panels multiply the cost): (values, its estimate);
/// `None` for a kind that is not rough glass.
pub fn reference(spec: &Spec, x: &[f64]) -> Option<([f64; 2], f64)> {
    if !is_glass(spec.kind) {
        return None;
    }
    let tol = if spec.kind == Kind::GlassAverageAlbedo {
        AVERAGE_REFERENCE_TOL
    } else {
        REFERENCE_TOL
    };
    let (v, w) = at(spec, x, tol, glass_e_radial);
    Some((v, w.error))
}

/// The model options of a rough-glass spec: GGX (the separable Smith G of the kernel is
/// implied; the masking option is not used).
pub fn validate(spec: &Spec) -> Result<(), GenError> {
    if !is_glass(spec.kind) {
        return Ok(());
    }
    if spec.distribution != Distribution::Ggx {
        return Err(GenError::Invalid(
            "rough-glass tables are GGX only: brdf-core has no spherical-cap visible-normal \
             map for Beckmann yet"
                .into(),
        ));
    }
    match spec.axes.last() {
        Some(a) if a.lo < 1.0 && a.hi > 1.0 => Err(GenError::Invalid(format!(
            "axis eta: [{}, {}] spans 1; light from outside (η ≥ 1) and from inside (η ≤ 1) \
             are two tables (total internal reflection sets in below 1: not smooth across it)",
            a.lo, a.hi
        ))),
        _ => Ok(()),
    }
}

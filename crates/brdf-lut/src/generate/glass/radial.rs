#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware: `!(x > 0)` is true for NaN.
//! `lut verify`'s reference for the rough-glass albedo (R, T)(μ, α, η): the integrals of
//! glass.rs's module docs in the other order from the generator's ring rule
//! (`glass/rings.rs`): the half vector's azimuth φ outer, its radial variable inner, every
//! edge cut at its closed-form root in τ = tan θh, and the integrand evaluated by brdf-core's
//! own [`f_dielectric`], [`refract`], `Vec3::reflect` and `TrowbridgeReitz::g1` on the half
//! vector itself (no shared integrand code with the ring rule).
//!
//! **Coordinates.** h = (sin θ cos φ, sin θ sin φ, cos θ), τ = tan θ, u = τ/α. The GGX
//! density gives D cos θ sin θ dθ = u du/(π(1 + u²)²) (D = 1/(π α² cos⁴θ (1 + u²)²),
//! dτ = dθ/cos²θ), and with v·h = h_z x, x = μ + sv τ cos φ (sv = sin θv), the visible-normal
//! density p(h) = G1(v)(v·h)₊D/μ (Heitz 2018, §2) turns the two integrals into
//!
//! ```text
//! (R, T) = 2 G1(v)/(π μ) ∫₀^π ∫₀^∞ x₊ (F G1(l), (1 − F) G1(|t|)) u/(1 + u²)² du dφ
//! ```
//!
//! (φ and −φ give the same value). The inner integral runs in three variables: τ on
//! [0, τ_L] (τ_L = min(α/2, 1/2, the first cut/e): the weight's poles τ = ±iα and h_z's
//! τ = ±i stay ≥ 2 piece lengths away), ζ = ln τ on [τ_L, τ_R] (weight u²/(1 + u²)² =
//! 1/(4 cosh²(ζ − ln α)) and h_z analytic in the strip |Im ζ| < π/2; pieces at most
//! [`MAX_LOG_STEP`] long) and v = 1/τ on [0, 1/τ_R] (τ_R = max([`FAR_TAU`], e × the last
//! cut): x u du/(1 + u²)² = α²(μ v + sv cos φ)/(1 + α² v²)² dv, h_z = v/√(1 + v²), analytic
//! down to v = 0).
//!
//! **Edges at fixed φ** (p = sv cos φ), each a closed-form root in τ, a cut of the inner
//! integral:
//!
//! | edge | equation in τ | behaviour |
//! |---|---|---|
//! | visibility v·h = 0 | μ + p τ = 0 | x₊ linear |
//! | reflected horizon l_z = 2(v·h)h_z − μ = 0 | μ τ² − 2p τ − μ = 0 | G1(l) ∝ l_z |
//! | TIR (η < 1, k = √(1 − η²)), (v·h)² = k² | (p² − k²) τ² + 2μp τ + μ² − k² = 0 | F, 1 − F ∝ √ |
//! | refracted horizon t_z = 0 (η < 1) | μ² τ² − 2μp τ + k² − μ² = 0 | G1(t) ∝ −t_z |
//!
//! (the last from (c h_z − μ)² = (c² − k²) h_z², c = v·h, Walter et al. 2007 eq 40; the
//! squared equations' spurious roots are kept as cuts too: a cut where the integrand is
//! smooth costs a piece, never accuracy.) Each piece [a, b] is mapped by a + (b − a) sin²β,
//! β ∈ [0, π/2], which makes the square roots at its ends (the TIR edge) analytic in β.
//! At the two horizons G1 of the leaving ray varies on the scale α of its n·l (its branch
//! points n·l = ±iα/√(1 − α²)): the pieces are graded toward them at δ·[`GRADE`]ʲ in ζ,
//! δ = α/|d(n·l)/dζ| (the reflected horizon on its lit side τ < τ_r; the refracted one, where
//! k h_z ≥ μ makes the root a horizon, on both). Without the grading the estimate missed
//! 2.5e-8 (6.7× itself) at (μ, r, η) = (0.2476, 0.0997, 0.395).
//!
//! **Outer breaks in φ.** The inner integral I(φ) is analytic in φ except where the inner
//! structure changes: a root through τ = ∞ (cos φ = 0 for the visibility edge; p² = k² for
//! the TIR edge), a double root (the TIR and the refracted-horizon discriminants both
//! vanish at p² = k² − μ², for μ < k; the reflected one, p² + μ², never), and two edges
//! crossing (reflected horizon and TIR at 1 + τ² = 4k²/μ², refracted horizon and TIR at
//! 1 + τ² = k²/μ²; from c = k on each; visibility meets no other edge, and no root passes
//! τ = 0 as φ varies: the constant terms do not depend on φ). All are closed forms in cos φ;
//! every panel between them is mapped by the same sin² substitution (I(φ) ~ |φ − φ₀|^{n/2}
//! there).
//! The same events at complex φ next to the real axis make I(φ) nearly singular: the
//! reflected horizon's root (p + √(p² + μ²))/μ branches at cos φ = ±iμ/sv (grazing μ: near
//! φ = π/2), the TIR discriminant at cos φ = ±i√(μ² − k²)/sv for μ > k, and a break cos φ₀
//! just beyond ±1 sits at imaginary distance acosh|cos φ₀| from φ = 0 or π. The panels are
//! graded toward each at d·[`GRADE`]ʲ < [`NEAR_GRADED`] (d its imaginary distance): without
//! it the estimate missed 2.1e-9 (1.01× itself) at (μ, r, η) = (0.0376, 0.241, 0.688).
//!
//! **Rule and estimate.** Both levels are the ring rule's globally adaptive K15 driver
//! (`rings::adaptive`, its estimate: K15's own error from the decay of the Legendre
//! coefficients, else QUADPACK's). Each inner integral gets [`INNER_SHARE`] of the
//! tolerance through its outer weight; the whole is held to 0.9 tol; + 64ε|value|.

use super::super::work::Work;
use super::rings::{adaptive, substitution};
use brdf_core::fresnel::f_dielectric;
use brdf_core::geometry::Vec3;
use brdf_core::microfacet::{Distribution as _, Isotropic, TrowbridgeReitz};
use brdf_core::models::rough_dielectric::refract;
use core::f64::consts::{FRAC_PI_2, PI};
use std::vec;
use std::vec::Vec;

/// The inner integral switches to v = 1/τ at τ ≥ this (h_z's poles, 1/τ = ±i, stay 4
/// piece lengths away).
pub const FAR_TAU: f64 = 4.0;
/// The longest inner piece in ζ = ln τ.
pub const MAX_LOG_STEP: f64 = 3.0;
/// The ratio of the graded breaks toward a horizon edge (δ, 4δ, 16δ, … from it).
pub const GRADE: f64 = 4.0;
/// Graded φ breaks toward a complex break at imaginary distance d stop at this distance.
pub const NEAR_GRADED: f64 = 0.5;
/// The share of the tolerance given to the inner integrals (through the outer weights).
pub const INNER_SHARE: f64 = 0.5;

/// The variable of an inner piece (module docs).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Var {
    /// τ on [0, τ_L].
    Tau,
    /// ζ = ln τ.
    LogTau,
    /// v = 1/τ on [0, 1/τ_R].
    InvTau,
}

/// Per-node constants.
struct Setup {
    mu: f64,
    sv: f64,
    alpha: f64,
    eta: f64,
    /// √(1 − η²) for η < 1, else 0.
    k: f64,
    wo: Vec3<f64>,
    dist: TrowbridgeReitz<f64>,
}

/// The positive finite roots of a τ² + b τ + c = 0 (a = 0 allowed), appended to `out`.
/// (rings.rs has its own private one; kept apart on purpose: the reference shares no edge
/// code with the rule it checks.)
fn push_roots(a: f64, b: f64, c: f64, out: &mut Vec<f64>) {
    let mut keep = |t: f64| {
        if t > 0.0 && t.is_finite() {
            out.push(t);
        }
    };
    if a == 0.0 {
        if b != 0.0 {
            keep(-c / b);
        }
        return;
    }
    let d = b * b - 4.0 * a * c;
    if d < 0.0 {
        return;
    }
    // The stable pair: q = −(b + sign(b)√d)/2, roots q/a and c/q.
    let q = -0.5 * (b + if b < 0.0 { -d.sqrt() } else { d.sqrt() });
    keep(q / a);
    if q != 0.0 {
        keep(c / q);
    }
}

impl Setup {
    /// The edges at p = sv cos φ (module docs' table): their positive roots in τ, and the
    /// horizons among them with the scale δ in ζ = ln τ on which G1 of the ray leaving
    /// there varies (α/|d(n·l)/dζ|) and whether the ray's lit side is below only.
    fn edges(&self, p: f64) -> (Vec<f64>, Vec<(f64, f64, bool)>) {
        let (mu, k) = (self.mu, self.k);
        let mut e = Vec::with_capacity(7);
        push_roots(0.0, p, mu, &mut e);
        let n = e.len();
        push_roots(mu, -2.0 * p, -mu, &mut e);
        let mut horizons: Vec<(f64, f64, bool)> = e[n..]
            .iter()
            .map(|&t| {
                // n·l = 2x/(1 + τ²) − μ, x = μ + pτ: lit (n·l > 0) below its root.
                let q = 1.0 + t * t;
                let d = t * (2.0 * p / q - 4.0 * (mu + p * t) * t / (q * q));
                (t, self.alpha / d.abs(), true)
            })
            .collect();
        if k > 0.0 {
            push_roots((p - k) * (p + k), 2.0 * mu * p, (mu - k) * (mu + k), &mut e);
            let n = e.len();
            push_roots(mu * mu, -2.0 * mu * p, (k - mu) * (k + mu), &mut e);
            for &t in &e[n..] {
                // A root of the squared equation is the horizon where k h_z ≥ μ.
                if k >= mu * (1.0 + t * t).sqrt() {
                    let h: f64 = 1e-6;
                    let d = (self.refracted_z(p, t * h.exp()) - self.refracted_z(p, t / h.exp()))
                        / (2.0 * h);
                    horizons.push((t, self.alpha / d.abs(), false));
                }
            }
        }
        e.sort_by(f64::total_cmp);
        (e, horizons)
    }

    /// n·t of the refracted ray at (p, τ) in the plane of incidence's terms:
    /// ((c − s) h_z − μ)/η, c = x h_z, s = √(c² − k²) (Walter et al. 2007, eq 40; NaN under
    /// total internal reflection). For the grading only; the integrand uses brdf-core's
    /// refraction.
    fn refracted_z(&self, p: f64, tau: f64) -> f64 {
        let hz = 1.0 / (1.0 + tau * tau).sqrt();
        let c = (self.mu + p * tau) * hz;
        let s = ((c - self.k) * (c + self.k)).sqrt();
        ((c - s) * hz - self.mu) / self.eta
    }

    /// The inner pieces at p (module docs): (variable, a, b).
    fn pieces(&self, p: f64) -> Vec<(Var, f64, f64)> {
        let (e, horizons) = self.edges(p);
        let mut z: Vec<f64> = e.iter().map(|t| t.ln()).collect();
        for (t, d, below) in horizons {
            let (zt, mut d) = (t.ln(), d);
            while d < MAX_LOG_STEP && z.len() < 200 {
                z.push(zt - d);
                if !below {
                    z.push(zt + d);
                }
                d *= GRADE;
            }
        }
        z.sort_by(f64::total_cmp);
        let first = z.first().map_or(f64::INFINITY, |z| (z - 1.0).exp());
        let last = z.last().map_or(0.0, |z| (z + 1.0).exp());
        let tl = (0.5 * self.alpha.min(1.0)).min(first);
        let tr = FAR_TAU.max(last);
        z.insert(0, tl.ln());
        z.push(tr.ln());
        let mut out = vec![(Var::Tau, 0.0, tl)];
        for w in z.windows(2) {
            let (a, b) = (w[0], w[1]);
            if !(b - a > 1e-14 * (1.0 + a.abs())) {
                continue;
            }
            let m = ((b - a) / MAX_LOG_STEP).ceil().max(1.0);
            for i in 0..m as usize {
                let lo = a + (b - a) * i as f64 / m;
                let hi = a + (b - a) * (i + 1) as f64 / m;
                out.push((Var::LogTau, lo, hi));
            }
        }
        out.push((Var::InvTau, 0.0, 1.0 / tr));
        out
    }

    /// (F G1(l), (1 − F) G1(|t|)) at the half vector h with v·h = c > 0: brdf-core's
    /// functions (the kernel's own).
    fn weights(&self, h: Vec3<f64>, c: f64) -> [f64; 2] {
        let f = f_dielectric(self.eta, c);
        let wi = self.wo.reflect(h);
        let r = if wi.z > 0.0 {
            f * self.dist.g1(wi)
        } else {
            0.0
        };
        let t = match refract(self.wo, h, c, self.eta) {
            Some(t) if t.z < 0.0 => (1.0 - f) * self.dist.g1(Vec3::new(t.x, t.y, -t.z)),
            _ => 0.0,
        };
        [r, t]
    }

    /// The inner integrand at `y` of a piece in `var`, per unit of y: x₊ (weights) × the
    /// radial weight (module docs), at azimuth (cos φ, sin φ).
    fn value(&self, var: Var, y: f64, cp: f64, sp: f64) -> [f64; 2] {
        let p = self.sv * cp;
        let (hz, st, xw) = match var {
            Var::Tau | Var::LogTau => {
                let tau = if var == Var::Tau { y } else { y.exp() };
                let u = tau / self.alpha;
                let d = 1.0 + u * u;
                let du = if var == Var::Tau { 1.0 / self.alpha } else { u };
                let hz = 1.0 / (1.0 + tau * tau).sqrt();
                (hz, tau * hz, (self.mu + p * tau) * u * du / (d * d))
            }
            Var::InvTau => {
                let a2 = self.alpha * self.alpha;
                let d = 1.0 + a2 * y * y;
                let n = 1.0 / (1.0 + y * y).sqrt();
                (y * n, n, a2 * (self.mu * y + p) / (d * d))
            }
        };
        if !(xw > 0.0) {
            return [0.0; 2];
        }
        let h = Vec3::new(st * cp, st * sp, hz);
        let c = self.wo.dot(h).min(1.0);
        if !(c > 0.0) {
            return [0.0; 2];
        }
        self.weights(h, c).map(|w| w * xw)
    }

    /// ∫₀^∞ of the inner integrand at azimuth φ to `tol`: (value, estimate, evaluations).
    fn inner(&self, phi: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
        let (sp, cp) = phi.sin_cos();
        let pieces = self.pieces(self.sv * cp);
        let n = pieces.len();
        let mut evals = 0u64;
        let mut f = |t: f64, j: Option<usize>| {
            let (i, sb, cb) = substitution(t, j, n - 1);
            let (var, a, b) = pieces[i];
            let y = a + (b - a) * sb * sb;
            let jac = (b - a) * 2.0 * sb * cb * FRAC_PI_2;
            evals += 1;
            let v = self.value(var, y, cp, sp);
            (v.map(|v| v * jac), [0.0; 2])
        };
        let (v, e) = adaptive(n, tol, &mut f);
        (v, e, evals)
    }

    /// The outer breaks in φ ∈ [0, π] (module docs): 0, π and the closed-form cos φ.
    fn phi_breaks(&self) -> Vec<f64> {
        let (mu, sv, k) = (self.mu, self.sv, self.k);
        let mut c = vec![0.0];
        if k > 0.0 {
            c.extend([k / sv, -k / sv]);
            if k > mu {
                let d = ((k - mu) * (k + mu)).sqrt() / sv;
                c.extend([d, -d]);
                // Refracted horizon × TIR: 1 + τ² = k²/μ², x = k²/μ.
                let t = d * sv / mu;
                c.push((k * k / mu - mu) / (sv * t));
            }
            if 2.0 * k > mu {
                // Reflected horizon × TIR: 1 + τ² = 4k²/μ², x = μ(1 + τ²)/2.
                let t = (4.0 * k * k / (mu * mu) - 1.0).sqrt();
                c.push(mu * (t * t - 1.0) / (2.0 * sv * t));
            }
        }
        // Complex double roots near the real φ axis: (φ₀, imaginary distance).
        let mut near = vec![(FRAC_PI_2, (mu / sv).asinh())];
        if k > 0.0 && k <= mu {
            near.push((FRAC_PI_2, (((mu - k) * (mu + k)).sqrt() / sv).asinh()));
        }
        let mut b = Vec::with_capacity(32);
        for c in c {
            if c.abs() < 1.0 {
                b.push(c.acos());
            } else {
                near.push((if c > 0.0 { 0.0 } else { PI }, c.abs().acosh()));
            }
        }
        for (p0, d) in near {
            let mut d = d.max(1e-9);
            while d < NEAR_GRADED {
                b.extend([p0 - d, p0 + d].into_iter().filter(|p| *p > 0.0 && *p < PI));
                d *= GRADE;
            }
        }
        b.extend([0.0, PI]);
        b.sort_by(f64::total_cmp);
        b.dedup_by(|x, y| (*x - *y).abs() < 1e-13);
        b
    }
}

/// (R, T) at (μ, α, η) to `tol` per channel by the radial rule (module docs): values, the
/// larger estimate, and the integrand evaluations. μ ∈ (0, 1], α > 0, η > 0 as given.
pub(super) fn glass_e_radial(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    let Ok(dist) = TrowbridgeReitz::isotropic(alpha) else {
        return ([f64::NAN; 2], Work::default());
    };
    let sv = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let k = if eta < 1.0 {
        ((1.0 - eta) * (1.0 + eta)).sqrt()
    } else {
        0.0
    };
    let s = Setup {
        mu,
        sv,
        alpha,
        eta,
        k,
        wo: Vec3::new(sv, 0.0, mu),
        dist,
    };
    let pref = 2.0 * <TrowbridgeReitz<f64> as Isotropic<f64>>::g1_cos(mu, alpha) / (PI * mu);
    let b = s.phi_breaks();
    let n = b.len() - 1;
    let mut evals = 0u64;
    let mut f = |t: f64, j: Option<usize>| {
        let (i, sb, cb) = substitution(t, j, n - 1);
        let phi = b[i] + (b[i + 1] - b[i]) * sb * sb;
        let scale = pref * (b[i + 1] - b[i]) * 2.0 * sb * cb * FRAC_PI_2;
        if !(scale > 0.0) {
            return ([0.0; 2], [0.0; 2]);
        }
        let (v, e, m) = s.inner(phi, INNER_SHARE * tol / (n as f64 * scale));
        evals += m;
        (v.map(|v| v * scale), e.map(|e| e * scale))
    };
    let (v, e) = adaptive(n, 0.9 * tol, &mut f);
    let round = 64.0 * f64::EPSILON * v[0].abs().max(v[1].abs());
    let error = e[0].max(e[1]) + round;
    (v, Work { error, evals })
}

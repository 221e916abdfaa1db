#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware: `!(x > 0)` is true for NaN.
//! The generator's rule for the rough-glass albedo (R, T)(μ, α, η): rings of the half vector
//! around the normal, every kink of the integrand cut in closed form.
//!
//! **Coordinates.** h = (sin θ cos φ, sin θ sin φ, cos θ), τ = tan θ = α sinh w (the GGX
//! radial map of `brdf_core::split_sum::polar`: D sin θ (v·h) dθ = tanh w sech² w
//! (μ + sv τ cos φ)/π dw, sv = sin θv). With p(h) = G1(v)(v·h)₊D/μ (Heitz 2018, §2) the
//! integrals of glass.rs's module docs become
//!
//! ```text
//! (R, T) = 2 G1(v)/(π μ) ∫₀^∞ tanh w sech² w ∫₀^π x₊ (F G1(l_z), (1 − F) G1(|t_z|)) dφ dw,
//! x = μ + sv τ cos φ = (v·h)/h_z,   c = v·h = h_z x,   h_z = 1/√(1 + τ²),
//! l_z = 2 c h_z − μ,   t_z = ((c − s) h_z − μ)/η,   s = √(η² − 1 + c²),
//! ```
//!
//! (l the reflected and t the refracted ray, Walter et al. 2007 eqs 39–40; F the exact
//! dielectric Fresnel of c). On a ring (w fixed) **everything is a function of x alone**,
//! and every edge of the integrand is a closed-form x:
//!
//! | edge | x | behaviour |
//! |---|---|---|
//! | visibility v·h = 0 | 0 | T ∝ x² (η ≥ 1) |
//! | reflected horizon l_z = 0 | μ(1 + τ²)/2 | G1(l) ∝ l_z |
//! | total internal reflection (η < 1), c = k = √(1 − η²) | k √(1 + τ²) | F, 1 − F ∝ √(x − x_k) |
//! | refracted horizon t_z = 0 (η < 1, only if k h_z > μ) | (μ²(1 + τ²) + k²)/(2μ) | G1(t) ∝ −t_z |
//!
//! (the last from (c h_z − μ)² = s² h_z², valid where c h_z ≥ μ.) With dφ = dx/√((x₊ − x)(x −
//! x₋)), x± = μ ± sv τ, each piece [a, b] between edges is mapped by x = a + (b − a) sin²β,
//! β ∈ [0, π/2]: the square roots at the ring's ends (x±) and at the TIR edge become
//! analytic in β, the linear edges stay analytic.
//!
//! **Outer integral.** The ring integral I(w) is analytic between the w where an edge meets
//! x± or two edges cross, all closed-form roots of quadratics in τ: x_r = x∓ at τ = (1 ∓ sv)/μ,
//! x = 0 at τ = μ/sv, k²(1 + τ²) = (μ ± sv τ)², μ²τ² ∓ 2μ sv τ + k² − μ² = 0 (x_t = x±),
//! x_k = x_r at (1 + τ²) = 4k²/μ², x_k = x_t at (1 + τ²) = k²/μ². Across them I(w) behaves
//! like |w − w₀|^{n/2}; each panel between breaks (at most [`MAX_PANEL`] long) is mapped by
//! the same sin² substitution. Past the last break (and past τ = 4/α·α, where the ring's
//! geometry in 1/τ has converged) the tail w ∈ [w_end, ∞) is integrated in u = e^{−w}, in
//! which I(w)/u is analytic down to u = 0 (the weight is 4u(1 − u²)/(1 + u²)³ du, x ~ 1/u).
//!
//! **Rule and estimate.** Both levels by the globally adaptive K15/G7 of `generate/sheen.rs`:
//! a panel is halved (in β) while |K15 − G7| exceeds its share of the tolerance; each ring's
//! own estimate enters the outer estimate through the Kronrod weights; + 64ε|value|. Rings
//! are asked for tol/4 (spread over the outer length), the outer panels for tol/2.

use super::super::sheen::adaptive;
use super::super::work::Work;
use brdf_core::fresnel::f_dielectric;
use brdf_core::microfacet::{Isotropic, TrowbridgeReitz};
use core::f64::consts::{FRAC_PI_2, PI};
use std::vec;
use std::vec::Vec;

/// The longest outer panel in w (the integrand varies on the scale of ln τ).
pub const MAX_PANEL: f64 = 1.5;

/// Per-node constants.
struct Node {
    mu: f64,
    sv: f64,
    alpha: f64,
    eta: f64,
    /// √(1 − η²) for η < 1 (the TIR cosine), else 0.
    k: f64,
    /// 2 G1(v)/(π μ).
    pref: f64,
}

/// One ring: h_z, its x range [x₋, x₊] and the pieces' ends (x₋, the edges inside, x₊).
struct Ring {
    hz: f64,
    lo: f64,
    hi: f64,
    ends: [f64; 6],
    n: usize,
}

/// The positive real roots of a t² + b t + c (NaN where there is none); a = 0 allowed.
fn positive_roots(a: f64, b: f64, c: f64) -> [f64; 2] {
    let mut r = [f64::NAN; 2];
    if a == 0.0 {
        if b != 0.0 {
            r[0] = -c / b;
        }
    } else {
        let d = b * b - 4.0 * a * c;
        if d >= 0.0 {
            let q = -0.5 * (b + b.signum() * d.sqrt());
            r = [q / a, if q != 0.0 { c / q } else { f64::NAN }];
        }
    }
    r.map(|t| if t > 0.0 && t.is_finite() { t } else { f64::NAN })
}

impl Node {
    fn new(mu: f64, alpha: f64, eta: f64) -> Self {
        let sv = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
        let k = if eta < 1.0 {
            ((1.0 - eta) * (1.0 + eta)).sqrt()
        } else {
            0.0
        };
        let g1v = <TrowbridgeReitz<f64> as Isotropic<f64>>::g1_cos(mu, alpha);
        Self {
            mu,
            sv,
            alpha,
            eta,
            k,
            pref: 2.0 * g1v / (PI * mu),
        }
    }

    /// x₊ (F G1(l_z), (1 − F) G1(|t_z|)) at x on a ring of h_z (module docs).
    #[inline]
    fn value(&self, hz: f64, x: f64) -> [f64; 2] {
        let c = hz * x;
        if !(c > 0.0) {
            return [0.0; 2];
        }
        let g1 = |z: f64| <TrowbridgeReitz<f64> as Isotropic<f64>>::g1_cos(z, self.alpha);
        let f = f_dielectric(self.eta, c);
        let lz = 2.0 * c * hz - self.mu;
        let r = if lz > 0.0 { f * g1(lz) } else { 0.0 };
        let s2 = (self.eta - 1.0) * (self.eta + 1.0) + c * c;
        let mut t = 0.0;
        if s2 > 0.0 {
            let tz = ((c - s2.sqrt()) * hz - self.mu) / self.eta;
            if tz < 0.0 {
                t = (1.0 - f) * g1(-tz);
            }
        }
        [x * r, x * t]
    }

    /// The ring at τ with its edges (module docs' table).
    fn ring(&self, tau: f64) -> Ring {
        let q2 = 1.0 + tau * tau;
        let hz = 1.0 / q2.sqrt();
        let (lo, hi) = (self.mu - self.sv * tau, self.mu + self.sv * tau);
        let mut ends = [lo, hi, hi, hi, hi, hi];
        let mut n = 1;
        let (mu, k) = (self.mu, self.k);
        let xt = if k * hz > mu {
            (mu * mu * q2 + k * k) / (2.0 * mu)
        } else {
            f64::NAN
        };
        let xk = if k > 0.0 { k * q2.sqrt() } else { f64::NAN };
        for x in [0.0, 0.5 * mu * q2, xk, xt] {
            if x > lo && x < hi {
                ends[n] = x;
                n += 1;
            }
        }
        ends[n] = hi;
        ends[1..n].sort_by(|a, b| a.total_cmp(b));
        Ring {
            hz,
            lo,
            hi,
            ends,
            n: n + 1,
        }
    }

    /// ∫₀^π of the ring's integrand dφ to `tol` (absolute): (value, estimate, evaluations).
    fn ring_integral(&self, tau: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
        let r = self.ring(tau);
        if !(r.hi - r.lo > 0.0) {
            return (self.value(r.hz, self.mu).map(|v| PI * v), [0.0; 2], 1);
        }
        let pieces = r.n - 1;
        let mut evals = 0u64;
        let mut f = |t: f64| {
            let i = (t as usize).min(pieces - 1);
            let (a, b) = (r.ends[i], r.ends[i + 1]);
            let beta = (t - i as f64) * FRAC_PI_2;
            let (sb, cb) = beta.sin_cos();
            let (s2, c2) = (sb * sb, cb * cb);
            let x = a + (b - a) * s2;
            let den = (((a - r.lo) + (b - a) * s2) * ((r.hi - b) + (b - a) * c2)).sqrt();
            let jac = (b - a) * 2.0 * sb * cb * FRAC_PI_2 / den;
            evals += 1;
            let v = self.value(r.hz, x);
            if !(den > 0.0) {
                return ([0.0; 2], [0.0; 2]);
            }
            ([v[0] * jac, v[1] * jac], [0.0; 2])
        };
        let breaks: Vec<f64> = (0..=pieces).map(|i| i as f64).collect();
        let (v, e) = adaptive(&breaks, tol / pieces as f64, &mut f);
        (v, e, evals)
    }
}

impl Node {
    /// The τ where an edge meets a ring end or two edges cross (module docs): NaN where absent.
    fn tau_breaks(&self) -> [f64; 13] {
        let (mu, sv, k) = (self.mu, self.sv, self.k);
        let mut t = [f64::NAN; 13];
        t[0] = mu / sv;
        t[1] = (1.0 - sv) / mu;
        t[2] = (1.0 + sv) / mu;
        if k > 0.0 {
            for (j, sg) in [1.0, -1.0].into_iter().enumerate() {
                let xk = positive_roots(k * k - sv * sv, -2.0 * sg * mu * sv, k * k - mu * mu);
                let xt = positive_roots(mu * mu, -2.0 * sg * mu * sv, k * k - mu * mu);
                t[3 + 4 * j..5 + 4 * j].copy_from_slice(&xk);
                t[5 + 4 * j..7 + 4 * j].copy_from_slice(&xt);
            }
            t[11] = (4.0 * k * k / (mu * mu) - 1.0).sqrt();
            t[12] = (k * k / (mu * mu) - 1.0).sqrt();
        }
        t
    }

    /// The outer panels' ends in w: 0, the breaks, the bump break 1.5, each gap split into
    /// panels of at most [`MAX_PANEL`]; the last is w_end (module docs).
    fn w_breaks(&self) -> Vec<f64> {
        let mut b: Vec<f64> = self
            .tau_breaks()
            .into_iter()
            .filter(|t| *t > 0.0 && t.is_finite())
            .map(|t| (t / self.alpha).asinh())
            .collect();
        b.push(1.5);
        b.push((4.0 / self.alpha).asinh());
        b.sort_by(|a, b| a.total_cmp(b));
        let mut w = vec![0.0];
        for x in b {
            let last = *w.last().unwrap_or(&0.0);
            if x - last < 1e-12 * (1.0 + x) {
                continue;
            }
            let m = ((x - last) / MAX_PANEL).ceil().max(1.0);
            for i in 1..=m as usize {
                w.push(last + (x - last) * i as f64 / m);
            }
        }
        w
    }

    /// The outer weight per unit of the outer variable at w: tanh w sech² w (panel) or
    /// tanh w sech² w / u (tail, u = e^{−w}), from u = e^{−w}.
    fn weight(w: f64, tail: bool) -> f64 {
        let u = (-w).exp();
        let u2 = u * u;
        let d = 1.0 + u2;
        let base = 4.0 * u * (1.0 - u2) / (d * d * d);
        if tail {
            base
        } else {
            base * u
        }
    }
}

/// (R, T) at (μ, α, η) to `tol` per channel by the ring rule (module docs): values, the
/// larger estimate and the integrand evaluations. μ ∈ (0, 1], α > 0, η > 0 as given.
pub(super) fn glass_e_rings(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    let node = Node::new(mu, alpha, eta);
    let w = node.w_breaks();
    let w_end = *w.last().unwrap_or(&0.0);
    let panels = w.len() - 1;
    let segs = (panels + 1) as f64;
    let u_end = (-w_end).exp();
    let ring_tol = 0.25 * tol / segs;
    let mut evals = 0u64;
    let mut f = |t: f64| {
        let i = t as usize;
        let beta = (t - i as f64) * FRAC_PI_2;
        let (sb, cb) = beta.sin_cos();
        let s2 = sb * sb;
        let dsub = 2.0 * sb * cb * FRAC_PI_2;
        let (wv, jac, tail) = if i < panels {
            let (a, b) = (w[i], w[i + 1]);
            (a + (b - a) * s2, (b - a) * dsub, false)
        } else {
            // u from u_end down to 0 (β = 0 at w_end).
            let u = u_end * (1.0 - s2);
            (-u.ln(), u_end * dsub, true)
        };
        let scale = node.pref * Node::weight(wv, tail) * jac;
        if !(scale > 0.0) || !wv.is_finite() {
            return ([0.0; 2], [0.0; 2]);
        }
        let tau = node.alpha * wv.sinh();
        let (v, e, n) = node.ring_integral(tau, ring_tol / scale);
        evals += n;
        (v.map(|v| v * scale), e.map(|e| e * scale))
    };
    let breaks: Vec<f64> = (0..=panels + 1).map(|i| i as f64).collect();
    let (v, e) = adaptive(&breaks, 0.5 * tol / segs, &mut f);
    let round = 64.0 * f64::EPSILON * v[0].abs().max(v[1].abs());
    let error = e[0].max(e[1]) + round;
    (v, Work { error, evals })
}

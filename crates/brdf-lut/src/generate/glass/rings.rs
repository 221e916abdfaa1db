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
//! Above x_k (η < 1) a piece is integrated in σ = √(x − x_k) before the same
//! substitution: F and s are analytic in σ, so a TIR edge just outside a piece (x_t and x_k
//! close together, near k h_z = μ) is no near-singularity.
//!
//! **Outer integral.** The ring integral I(w) is analytic between the w where an edge meets
//! x± or two edges cross, all closed-form roots of quadratics in τ: x_r = x∓ at
//! τ = (1 ∓ sv)/μ, x = 0 at τ = μ/sv, k²(1 + τ²) = (μ ± sv τ)² (x_k = x±),
//! μ²τ² ∓ 2μ sv τ + k² − μ² = 0 (x_t = x±), x_k = x_r at 1 + τ² = 4k²/μ², x_k = x_t at
//! 1 + τ² = k²/μ²; a root is kept where the ring's structure (its edges in order) differs on
//! its two sides. Across them I(w) behaves like |w − w₀|^{n/2}; each panel between breaks
//! (at most [`MAX_PANEL`] long) is mapped by the same sin² substitution. Past the last break
//! and past τ = [`TAIL_TAU`] (where the ring's geometry, a function of 1/τ with its nearest
//! singularity at 1/τ = ±i, has settled) the tail is integrated in u = e^{−w} ∈ [0, u_end],
//! in which I/u is analytic down to u = 0 (the weight is 4u(1 − u²)/(1 + u²)³ du, x ~ 1/u).
//!
//! **Rule and estimate.** Both levels are globally adaptive K15 (the panel with the largest
//! estimate is halved until the sum is within tolerance). A panel's estimate is K15's own
//! error where the 15 values show it converging (Legendre coefficients c₀…c₁₁ from the
//! Kronrod weights, decaying geometrically by q < ½ per degree: the terms K15 misses,
//! degree ≥ 24, are bounded by 20 h max|c₁₀, c₁₁| q¹², 10× their size), else QUADPACK's
//! r·min(1, (200|K15 − G7|/r)^{3/2}) (Piessens et al. 1983). Each ring's estimate enters the
//! outer one through the Kronrod weights; the rings get [`RING_SHARE`] of the tolerance,
//! the whole is held to 0.9 tol; + 64ε|value|. Measured against the cap integrator and an
//! independent brute-force rule: tests/glass_tables.rs and tests/glass_measure.rs.

use super::super::work::Work;
use brdf_core::microfacet::{Isotropic, TrowbridgeReitz};
use brdf_core::quadrature::kronrod::{gk15_combine, gk15_nodes};
use core::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;
use std::vec;
use std::vec::Vec;

/// Panels of one adaptive integral at most (each 15 evaluations).
pub const MAX_PANELS: usize = 400;

/// One panel [a, b] of [`adaptive`]: its K15 value and estimate per channel.
#[derive(Clone, Copy)]
struct Panel {
    a: f64,
    b: f64,
    v: [f64; 2],
    e: [f64; 2],
}

/// The Legendre coefficients c_k = (2k + 1)/2 ∫₋₁¹ f P_k of the 15 Kronrod values, by the
/// K15 weights (exact for polynomials f of degree ≤ 22 − k), k = 0 … 11: row k holds
/// (2k + 1)/2 · W_j P_k(x_j) at [`gk15_nodes`]'s order.
fn legendre_table() -> &'static [[f64; 15]; 12] {
    static T: OnceLock<[[f64; 15]; 12]> = OnceLock::new();
    T.get_or_init(|| {
        let x = gk15_nodes(-1.0f64, 1.0);
        let mut t = [[0.0; 15]; 12];
        for j in 0..15 {
            let mut unit = [[0.0; 2]; 15];
            unit[j] = [1.0, 0.0];
            let w = gk15_combine(&unit, 1.0).0[0];
            let (mut p0, mut p1) = (1.0, x[j]);
            for (k, row) in t.iter_mut().enumerate() {
                row[j] = (2 * k + 1) as f64 * 0.5 * w * p0;
                let p2 = ((2 * k + 3) as f64 * x[j] * p1 - (k + 1) as f64 * p0) / (k + 2) as f64;
                (p0, p1) = (p1, p2);
            }
        }
        t
    })
}

/// The K15 error estimate of one channel on a panel of half length h (values `y`):
/// where the Legendre coefficients decay geometrically (q = (max|c₁₀,c₁₁| / max|c₆,c₇|)^{1/4}
/// < ½: f analytic in a Bernstein ellipse of parameter 1/q), the first terms K15 misses
/// (degree ≥ 24) are ~ max|c₁₀,c₁₁| q^{13} each, |K15(P_k)| ≤ 2: estimate 20 h max|c₁₀,c₁₁|
/// q^{12} (10× that). Otherwise the QUADPACK estimate r·min(1, (200 d/r)^{3/2}) (Piessens
/// et al. 1983, QK15; d = |K15 − G7|, r = ∫|f − mean|).
fn k15_error(y: &[f64; 15], h: f64, d: f64, r: f64) -> f64 {
    let t = legendre_table();
    let c = |k: usize| t[k].iter().zip(y).map(|(t, y)| t * y).sum::<f64>().abs();
    let (e0, e1) = (c(6).max(c(7)), c(10).max(c(11)));
    if !(e1 > 0.0) {
        return d;
    }
    // q⁴ = e1/e0 < 1/16, q¹² = (e1/e0)³.
    let q4 = if e0 > 0.0 { e1 / e0 } else { 1.0 };
    if q4 < 1.0 / 16.0 {
        return 20.0 * h * e1 * q4 * q4 * q4;
    }
    if r > 0.0 {
        let z = 200.0 * d / r;
        r * (z * z.sqrt()).min(1.0)
    } else {
        d
    }
}

/// The integrand of [`adaptive`]: f(t, j) with j = Some(node index) on a unit panel
/// [i, i + 1] (whose sin/cos of the substitution are tabulated: [`substitution`]).
pub(super) trait Integrand: FnMut(f64, Option<usize>) -> ([f64; 2], [f64; 2]) {}
impl<F: FnMut(f64, Option<usize>) -> ([f64; 2], [f64; 2])> Integrand for F {}

/// The piece i ≤ `last` of t and (sin β, cos β) of its sin² substitution, β = (t − i)π/2;
/// tabulated at the nodes of unit panels (node index j).
#[inline]
pub(super) fn substitution(t: f64, j: Option<usize>, last: usize) -> (usize, f64, f64) {
    static UNIT: OnceLock<[(f64, f64); 15]> = OnceLock::new();
    let i = (t as usize).min(last);
    if let Some(j) = j {
        let u = UNIT.get_or_init(|| gk15_nodes(0.0f64, 1.0).map(|x| (x * FRAC_PI_2).sin_cos()));
        return (i, u[j].0, u[j].1);
    }
    let (sb, cb) = ((t - i as f64) * FRAC_PI_2).sin_cos();
    (i, sb, cb)
}

/// K15 over [a, b] of f (values and their own errors): the value and its estimate per
/// channel ([`k15_error`]) + the Kronrod-weighted errors f reports.
fn panel(a: f64, b: f64, f: &mut impl Integrand) -> Panel {
    let (mut y, mut ye) = ([[0.0; 2]; 15], [[0.0; 2]; 15]);
    let unit = b - a == 1.0 && a.fract() == 0.0;
    for (j, x) in gk15_nodes(a, b).into_iter().enumerate() {
        (y[j], ye[j]) = f(x, unit.then_some(j));
    }
    let h = 0.5 * (b - a);
    let (v, d) = gk15_combine(&y, h);
    let (inner, _) = gk15_combine(&ye, h);
    let mean = [v[0] / (b - a), v[1] / (b - a)];
    let dev = y.map(|y| [(y[0] - mean[0]).abs(), (y[1] - mean[1]).abs()]);
    let (r, _) = gk15_combine(&dev, h);
    let mut e = [0.0; 2];
    for c in 0..2 {
        e[c] = k15_error(&y.map(|y| y[c]), h, d[c], r[c]) + inner[c].abs();
    }
    Panel { a, b, v, e }
}

/// ∫ of f over the unit panels [i, i + 1], i < n, to the absolute tolerance `tol` per
/// channel: globally adaptive K15 (the panel with the largest estimate is halved until the
/// sum of the estimates is ≤ tol, or [`MAX_PANELS`]). (value, estimate) per channel.
pub(super) fn adaptive(n: usize, tol: f64, f: &mut impl Integrand) -> ([f64; 2], [f64; 2]) {
    let mut ps: Vec<Panel> = (0..n).map(|i| panel(i as f64, i as f64 + 1.0, f)).collect();
    loop {
        let (mut v, mut e) = ([0.0; 2], [0.0; 2]);
        let (mut worst, mut at) = (0.0, 0);
        for (i, p) in ps.iter().enumerate() {
            for c in 0..2 {
                v[c] += p.v[c];
                e[c] += p.e[c];
            }
            let pe = p.e[0].max(p.e[1]);
            if pe > worst && p.b - p.a > 1e-12 {
                (worst, at) = (pe, i);
            }
        }
        if e[0].max(e[1]) <= tol || ps.len() >= MAX_PANELS || !(worst > 0.0) {
            return (v, e);
        }
        let p = ps[at];
        let m = 0.5 * (p.a + p.b);
        ps[at] = panel(p.a, m, f);
        ps.push(panel(m, p.b, f));
    }
}

/// The longest outer panel in w (the integrand varies on the scale of ln τ).
pub const MAX_PANEL: f64 = 3.0;
/// The tail in u = e^{−w} starts at τ ≥ this (module docs).
pub const TAIL_TAU: f64 = 4.0;
/// The share of the tolerance given to the rings (the outer estimate, which includes the
/// rings' Kronrod-weighted estimates, is held to 0.9 tol).
pub const RING_SHARE: f64 = 0.5;

/// What the ring rule integrates per visible normal besides the geometry: the weights of
/// the reflected and the transmitted ray (both functions of v·h alone on a ring, so every
/// variant keeps the edges of the module docs' table). One variant per integrand; each is
/// documented where its public entry point is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Weights {
    /// The generator's glass integrand (glass.rs module docs): F G1(l), (1 − F) G1(|t|),
    /// the separable Smith G of brdf-core's rough dielectric.
    #[default]
    Separable,
    /// Blender EEVEE's reflection split (glass/eevee.rs): (1 − S) G1(l), S G1(l) with
    /// Schlick's S = (1 − |h·t|)⁵, |h·t| = s/η the refracted cosine (S = 1 under total
    /// internal reflection): the `scale` and `bias` of `bsdf_ggx`.
    SchlickSplit,
    /// Blender EEVEE's transmission (glass/eevee.rs): G1(|t|) without Fresnel, and
    /// (1 − S) G1(|t|) with S = (1 − |h·v|)⁵ for η > 1, (1 − |h·t|)⁵ for η ≤ 1: the
    /// `transmission_factor` of `btdf_ggx` / `bsdf_ggx`.
    SchlickTransmission,
    /// Blender Cycles' glass closure (`glass/correlated.rs`): the sampled weight
    /// eval/pdf = G2(v, o)/G1(v) with the height-correlated G2 = 1/(1 + Λ(v) + Λ(o)), times
    /// F (reflected, where l_z > 0) or 1 − F (refracted, wherever the refraction exists:
    /// Cycles does not test the side of the refracted ray, so for η < 1 rays refracted
    /// upwards, t_z > 0, count with Λ(|t_z|)).
    HeightCorrelated,
}

/// The rays of one visible normal, as [`Weights::at`] takes them.
#[derive(Clone, Copy)]
pub struct Rays {
    /// c = v·h > 0.
    pub c: f64,
    /// s = √(η² − 1 + c²) (= η cos θt), NaN under total internal reflection.
    pub s: f64,
    /// The exact dielectric Fresnel F(c) (1 under total internal reflection).
    pub f: f64,
    /// n·l of the reflected ray (its weight is 0 where l_z ≤ 0).
    pub lz: f64,
    /// n·t of the refracted ray (0 under TIR; the separable weight is 0 where t_z ≥ 0).
    pub tz: f64,
    /// η (|h·t| = s/η).
    pub eta: f64,
    /// Λ(v) of the node (Smith's masking exponent at μ; the correlated weights use it).
    pub lambda_v: f64,
}

impl Weights {
    /// (reflected, transmitted) weight at `r` for a node of squared width `a2`; the ring
    /// rule multiplies by x and the node's 2 G1(v)/(π μ).
    #[inline]
    pub fn at(self, r: &Rays, a2: f64) -> [f64; 2] {
        match self {
            Weights::Separable => [
                if r.lz > 0.0 { r.f * g1(r.lz, a2) } else { 0.0 },
                if r.tz < 0.0 {
                    (1.0 - r.f) * g1(-r.tz, a2)
                } else {
                    0.0
                },
            ],
            Weights::SchlickSplit => {
                let g = if r.lz > 0.0 { g1(r.lz, a2) } else { 0.0 };
                let sch = if r.s > 0.0 { schlick(r.s / r.eta) } else { 1.0 };
                [(1.0 - sch) * g, sch * g]
            }
            Weights::SchlickTransmission => {
                if !(r.tz < 0.0) {
                    return [0.0; 2];
                }
                let g = g1(-r.tz, a2);
                let cos = if r.eta > 1.0 { r.c } else { r.s / r.eta };
                [g, (1.0 - schlick(cos)) * g]
            }
            Weights::HeightCorrelated => [
                if r.lz > 0.0 {
                    r.f * g2_over_g1v(r.lz, a2, r.lambda_v)
                } else {
                    0.0
                },
                if r.s >= 0.0 {
                    (1.0 - r.f) * g2_over_g1v(r.tz.abs(), a2, r.lambda_v)
                } else {
                    0.0
                },
            ],
        }
    }

    /// Whether rays refracted upwards (t_z > 0, η < 1) carry weight: T's support on a ring
    /// then starts at the TIR edge x_k, not at the refracted horizon x_t.
    fn counts_upward_refraction(self) -> bool {
        matches!(self, Weights::HeightCorrelated)
    }
}

/// G2(v, o)/G1(v) = (1 + Λ(v))/(1 + Λ(v) + Λ(z)) at polar cosine z = |n·o| ∈ [0, 1] of the
/// other ray, with GGX's Λ(z) = (√(1 + α²(1 − z²)/z²) − 1)/2 (Heitz 2014, eq. 72; G2 his §6):
/// with q = 1 + 2Λ(v), (1 + q) z/(q z + √(z² + α²(1 − z²))), which → 0 linearly at z = 0.
#[inline]
fn g2_over_g1v(z: f64, a2: f64, lambda_v: f64) -> f64 {
    let z = z.min(1.0);
    let q = 1.0 + 2.0 * lambda_v;
    (1.0 + q) * z / (q * z + (z * z + a2 * (1.0 - z) * (1.0 + z)).sqrt())
}

/// Schlick's factor (1 − cos)⁵ (Schlick 1994), cos clamped to [0, 1] as EEVEE saturates it.
#[inline]
fn schlick(cos: f64) -> f64 {
    let m = 1.0 - cos.clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

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
    /// Λ(v) = 1/G1(v) − 1.
    lambda_v: f64,
    /// The integrand's weights.
    weights: Weights,
}

/// One ring: h_z, its x range [x₋, x₊] and the pieces' ends (x₋, the edges inside, x₊).
struct Ring {
    hz: f64,
    lo: f64,
    hi: f64,
    ends: [f64; 6],
    n: usize,
    /// The TIR edge x_k (NaN for η ≥ 1): pieces above it are integrated in √(x − x_k).
    xk: f64,
}

impl Ring {
    /// The point of piece [a, b] at β given (sin β, cos β) (its sin² substitution, in √(x − x_k) above x_k) and
    /// the weight dφ/dβ / (π/2 per unit t) there: (x, weight).
    #[inline]
    fn point(&self, a: f64, b: f64, sb: f64, cb: f64) -> (f64, f64) {
        let (s2, c2) = (sb * sb, cb * cb);
        let d = 2.0 * sb * cb * FRAC_PI_2;
        if a >= self.xk {
            let (sa, sbb) = ((a - self.xk).sqrt(), (b - self.xk).sqrt());
            let w = sbb - sa;
            let sg = sa + w * s2;
            let x = self.xk + sg * sg;
            let den = ((a - self.lo) + w * s2 * (sg + sa)) * ((self.hi - b) + w * c2 * (sbb + sg));
            return (x, 2.0 * sg * w * d / den.sqrt());
        }
        let x = a + (b - a) * s2;
        let den = ((a - self.lo) + (b - a) * s2) * ((self.hi - b) + (b - a) * c2);
        (x, (b - a) * d / den.sqrt())
    }
}

/// GGX Smith G1 at polar cosine z > 0: 2z/(z + √(z² + α²(1 − z²))) (Heitz 2014,
/// "Understanding the masking-shadowing function", eqs 43 and 72): brdf-core's
/// `Isotropic::g1_cos`, written out for the inner loop (tests: equal to it).
#[inline]
fn g1(z: f64, a2: f64) -> f64 {
    let z = z.min(1.0);
    2.0 * z / (z + (z * z + a2 * (1.0 - z) * (1.0 + z)).sqrt())
}

/// The exact unpolarised dielectric Fresnel at c = cos θ > 0 given s = √(η² − 1 + c²) > 0
/// (= η cos θt): F = ½[((c − s)/(c + s))² + ((η²c − s)/(η²c + s))²], brdf-core's
/// `f_dielectric` with its square root shared with the refraction (tests: equal to it).
#[inline]
fn fresnel(eta: f64, c: f64, s: f64) -> f64 {
    let rs = (c - s) / (c + s);
    let e2c = eta * eta * c;
    let rp = (e2c - s) / (e2c + s);
    (0.5 * (rs * rs + rp * rp)).min(1.0)
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
    r.map(|t| {
        if t > 0.0 && t.is_finite() {
            t
        } else {
            f64::NAN
        }
    })
}

impl Node {
    fn new(mu: f64, alpha: f64, eta: f64, weights: Weights) -> Self {
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
            lambda_v: <TrowbridgeReitz<f64> as Isotropic<f64>>::lambda_cos(mu, alpha),
            weights,
        }
    }

    /// x₊ × the weights ([`Weights::at`]; the generator's: (F G1(l_z), (1 − F) G1(|t_z|)))
    /// at x on a ring of h_z (module docs).
    #[inline]
    fn value(&self, hz: f64, x: f64) -> [f64; 2] {
        let c = (hz * x).min(1.0);
        if !(c > 0.0) {
            return [0.0; 2];
        }
        let s2 = (self.eta - 1.0) * (self.eta + 1.0) + c * c;
        let lz = 2.0 * c * hz - self.mu;
        let rays = if s2 > 0.0 {
            let s = s2.sqrt();
            Rays {
                c,
                s,
                f: fresnel(self.eta, c, s),
                lz,
                tz: ((c - s) * hz - self.mu) / self.eta,
                eta: self.eta,
                lambda_v: self.lambda_v,
            }
        } else {
            Rays {
                c,
                s: f64::NAN,
                f: 1.0,
                lz,
                tz: 0.0,
                eta: self.eta,
                lambda_v: self.lambda_v,
            }
        };
        let [r, t] = self.weights.at(&rays, self.alpha * self.alpha);
        [x * r, x * t]
    }

    /// The ring at τ with its edges (module docs' table) and its structure: the edges
    /// inside (visibility 1, reflected horizon 2, TIR 3, refracted horizon 4) in x order,
    /// three bits each. The pieces start where R or T can first be nonzero: min(x_r, T's
    /// first x: 0 for η ≥ 1, else x_t where k h_z > μ, else x_k; always x_k for weights
    /// that count upward refraction), or at x₋.
    fn ring(&self, tau: f64) -> (Ring, u32) {
        let q2 = 1.0 + tau * tau;
        let hz = 1.0 / q2.sqrt();
        let (lo, hi) = (self.mu - self.sv * tau, self.mu + self.sv * tau);
        let (mu, k) = (self.mu, self.k);
        let xr = 0.5 * mu * q2;
        let (xk, xt) = if k > 0.0 {
            let xt = (mu * mu * q2 + k * k) / (2.0 * mu);
            (k * q2.sqrt(), if k * hz > mu { xt } else { f64::NAN })
        } else {
            (f64::NAN, f64::NAN)
        };
        let t0 = match (k > 0.0, self.weights.counts_upward_refraction()) {
            (false, _) => 0.0,
            (true, false) => xt.max(xk),
            (true, true) => xk,
        };
        let start = xr.min(t0);
        let mut e = [(0.0, 0u32); 4];
        let mut n = 0;
        for (id, x) in [0.0, xr, xk, xt].into_iter().enumerate() {
            if x > lo && x < hi && x >= start {
                e[n] = (x, id as u32 + 1);
                n += 1;
            }
        }
        e[..n].sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut ends = [hi; 6];
        ends[0] = lo;
        let mut code = 0u32;
        let mut m = 1;
        for (x, id) in e[..n].iter() {
            code = code << 3 | id;
            if *x > start {
                ends[m] = *x;
                m += 1;
            } else {
                ends[0] = *x;
            }
        }
        let n = if start >= hi { 1 } else { m + 1 };
        (
            Ring {
                hz,
                lo,
                hi,
                ends,
                n,
                xk,
            },
            code,
        )
    }

    /// ∫₀^π of the ring's integrand dφ to `tol` (absolute): (value, estimate, evaluations).
    fn ring_integral(&self, tau: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
        let (r, _) = self.ring(tau);
        if !(r.hi - r.lo > 0.0) {
            return (self.value(r.hz, self.mu).map(|v| PI * v), [0.0; 2], 1);
        }
        let pieces = r.n - 1;
        if pieces == 0 {
            return ([0.0; 2], [0.0; 2], 0);
        }
        let mut evals = 0u64;
        let mut f = |t: f64, j: Option<usize>| {
            let (i, sb, cb) = substitution(t, j, pieces - 1);
            let (x, jac) = r.point(r.ends[i], r.ends[i + 1], sb, cb);
            evals += 1;
            if !(jac.is_finite()) {
                return ([0.0; 2], [0.0; 2]);
            }
            let v = self.value(r.hz, x);
            ([v[0] * jac, v[1] * jac], [0.0; 2])
        };
        let (v, e) = adaptive(pieces, tol, &mut f);
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

    /// Whether the ring's structure differs on the two sides of τ (a root of the squared
    /// equations that is not a crossing does not break the outer rule).
    fn changes_at(&self, tau: f64) -> bool {
        let d = 1e-7 * tau;
        self.ring(tau - d).1 != self.ring(tau + d).1
    }

    /// The outer panels' ends in w: 0, the breaks, the bump break 1.5, each gap split into
    /// panels of at most [`MAX_PANEL`]; the last is w_end (module docs).
    fn w_breaks(&self) -> Vec<f64> {
        let mut b: Vec<f64> = self
            .tau_breaks()
            .into_iter()
            .filter(|t| *t > 0.0 && t.is_finite() && self.changes_at(*t))
            .map(|t| (t / self.alpha).asinh())
            .collect();
        b.push(1.5);
        b.push((TAIL_TAU / self.alpha).asinh());
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

/// (R, T) at (μ, α, η) to `tol` per channel by the ring rule (module docs) with the
/// generator's weights ([`Weights::Separable`]): values, the larger estimate and the
/// integrand evaluations. μ ∈ (0, 1], α > 0, η > 0 as given.
pub(super) fn glass_e_rings(mu: f64, alpha: f64, eta: f64, tol: f64) -> ([f64; 2], Work) {
    glass_rings_with(mu, alpha, eta, Weights::Separable, tol)
}

/// The ring rule's two integrals (reflected, transmitted) of `weights` at (μ, α, η) to
/// `tol` per channel: values, the larger estimate and the integrand evaluations.
pub(super) fn glass_rings_with(
    mu: f64,
    alpha: f64,
    eta: f64,
    weights: Weights,
    tol: f64,
) -> ([f64; 2], Work) {
    let node = Node::new(mu, alpha, eta, weights);
    let w = node.w_breaks();
    let w_end = *w.last().unwrap_or(&0.0);
    let panels = w.len() - 1;
    let segs = (panels + 1) as f64;
    let u_end = (-w_end).exp();
    let ring_tol = RING_SHARE * tol / segs;
    let mut evals = 0u64;
    let mut f = |t: f64, j: Option<usize>| {
        let (i, sb, cb) = substitution(t, j, panels);
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
    let (v, e) = adaptive(panels + 1, 0.9 * tol, &mut f);
    let round = 64.0 * f64::EPSILON * v[0].abs().max(v[1].abs());
    let error = e[0].max(e[1]) + round;
    (v, Work { error, evals })
}

#[cfg(test)]
mod tests {
    use super::*;
    use brdf_core::fresnel::f_dielectric;

    /// The inlined G1 and Fresnel are brdf-core's, to rounding.
    #[test]
    fn inlined_terms_equal_the_kernels() {
        for &alpha in &[1e-4, 0.1, 0.5, 1.0] {
            for i in 1..=100 {
                let z = i as f64 / 100.0;
                let want = <TrowbridgeReitz<f64> as Isotropic<f64>>::g1_cos(z, alpha);
                assert!(
                    (g1(z, alpha * alpha) - want).abs() <= 1e-15,
                    "G1 {z} {alpha}"
                );
            }
        }
        for &eta in &[0.34, 0.7, 0.99, 1.0, 1.5, 3.0] {
            for i in 1..=1000 {
                let c = i as f64 / 1000.0;
                let s2 = (eta - 1.0) * (eta + 1.0) + c * c;
                if s2 > 0.0 {
                    let (f, want) = (fresnel(eta, c, s2.sqrt()), f_dielectric(eta, c));
                    assert!((f - want).abs() <= 1e-13, "F {eta} {c}: {f} {want}");
                }
            }
        }
    }

    /// The Legendre table gives c_k = δ_jk for f = P_j, j ≤ 11 (K15 integrates P_j P_k,
    /// degree ≤ 22, exactly).
    #[test]
    fn legendre_coefficients_of_legendre_polynomials() {
        let x = gk15_nodes(-1.0f64, 1.0);
        let t = legendre_table();
        for j in 0..12 {
            let y: Vec<f64> = x
                .iter()
                .map(|&x| {
                    let (mut p0, mut p1) = (1.0, x);
                    for k in 0..j {
                        let p2 =
                            ((2 * k + 3) as f64 * x * p1 - (k + 1) as f64 * p0) / (k + 2) as f64;
                        (p0, p1) = (p1, p2);
                    }
                    p0
                })
                .collect();
            for (k, row) in t.iter().enumerate() {
                let c: f64 = row.iter().zip(&y).map(|(a, b)| a * b).sum();
                let want = if k == j { 1.0 } else { 0.0 };
                assert!((c - want).abs() < 1e-13, "P{j}: c{k} = {c}");
            }
        }
    }

    /// An integrand f(x, d), its exact integral over [−1, 1] and the parameters d.
    type Case<'a> = (
        &'a dyn Fn(f64, f64) -> f64,
        &'a dyn Fn(f64) -> f64,
        &'a [f64],
    );

    /// The panel estimate bounds K15's true error on analytic integrands with their
    /// nearest singularity from far to very near the panel (1/(d − x), exact
    /// ln((d + 1)/(d − 1)); √(x + d), exact (2/3)((d + 1)^{3/2} − (d − 1)^{3/2})), and on
    /// e^{κx} (entire, exact 2 sinh κ/κ).
    #[test]
    fn panel_estimate_bounds_the_error() {
        let cases: [Case; 3] = [
            (
                &|x, d| 1.0 / (d - x),
                &|d| ((d + 1.0) / (d - 1.0)).ln(),
                &[1.0001, 1.001, 1.01, 1.05, 1.2, 1.5, 2.0, 4.0, 10.0],
            ),
            (
                &|x, d| (x + d).sqrt(),
                &|d| 2.0 / 3.0 * ((d + 1.0).powf(1.5) - (d - 1.0).powf(1.5)),
                &[1.0, 1.0001, 1.01, 1.1, 1.5, 3.0],
            ),
            (
                &|x, k| (k * x).exp(),
                &|k| 2.0 * k.sinh() / k,
                &[0.5, 2.0, 8.0, 20.0, 40.0],
            ),
        ];
        for (f, exact, ds) in cases {
            for &d in ds {
                let p = panel(-1.0, 1.0, &mut |x, _| ([f(x, d), 0.0], [0.0; 2]));
                let err = (p.v[0] - exact(d)).abs();
                assert!(
                    err <= p.e[0] + 1e-14 * exact(d).abs(),
                    "d {d}: error {err:e} > estimate {:e}",
                    p.e[0]
                );
            }
        }
    }
}

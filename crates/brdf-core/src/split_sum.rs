#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware tests: `!(x > 0)` is true for NaN.
//! Split-sum (DFG) and energy-compensation (Kulla–Conty) integrals by fixed-size
//! Gauss–Legendre quadrature: the "direct" kernels the LUT assets are generated from.
//!
//! For μ = n·v, the specular directional integral with Schlick F (F90 = 1),
//! F = F0 + (1 − F0) F_c, F_c = (1 − v·h)⁵ (docs/conventions.md §8), splits as
//!
//! ```text
//! E_spec = ∫ f cos θl dωl = F0·A + B,
//! A = ∫ D(h) cos θh · W(h) (1 − F_c) dωh,   B = ∫ D(h) cos θh · W(h) F_c dωh,
//! W(h) = G(l, v) (v·h) / (μ (n·h)),        l = 2(v·h)h − v,
//! ```
//!
//! using dωl = 4(v·h) dωh. With F = 1 the directional albedo is E(μ) = A + B, and the
//! Kulla–Conty average is E_avg = 2∫₀¹ E(μ) μ dμ.
//!
//! Quadrature. The half vector is parametrised by the NDF's own CDF ξ ∈ [0, 1) in θh and
//! by the azimuth φ ∈ [0, π] from the plane of v (the integrand is even in φ), so that
//! D cos θh dωh = dξ dφ/π. The light is above the horizon (n·l > 0) iff
//! cos φ > c₀ = −cot θv · cot 2θh, i.e. for every φ when θh ≤ π/4 − θv/2, for
//! φ < arccos c₀ when π/4 − θv/2 < θh < π/4 + θv/2, and never beyond. The ξ range is split
//! at those two angles; on the second piece ξ follows a smoothstep in the quadrature
//! variable, which removes the (ξ − ξ₁)^{3/2} and (ξ₂ − ξ)^{3/2} end behaviour. Each piece
//! uses an `RO`-point rule in ξ and an `RI`-point rule in φ.

pub mod converged;
pub mod polar;
pub mod rows;

use crate::geometry::Dots;
use crate::masking::ModifiedG;
use crate::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use crate::quadrature::{GaussLegendre, Rule};
use crate::roughness::{alpha_from_perceptual, beckmann_m_from_sigma};
use crate::Real;

/// The outer (ξ) rule of the default split-sum kernels.
pub type OuterRule = GaussLegendre<32>;
/// The inner (φ) rule of the default split-sum kernels.
pub type InnerRule = GaussLegendre<16>;

/// The split-sum kernels' choice of distribution at run time: which one, and its width
/// (GGX α, Beckmann m). Every formula is the distribution's own ([`Isotropic`]).
#[derive(Clone, Copy, Debug)]
pub enum Ndf<T> {
    /// GGX with roughness α ≥ 0.
    Ggx(T),
    /// Beckmann with roughness m ≥ 0.
    Beckmann(T),
}

impl<T: Real> Ndf<T> {
    /// ξ = P(θh < θ) from tan²θ: the distribution's [`Isotropic::normal_cdf_tan2`].
    fn cdf_tan2(self, t2: T) -> T {
        match self {
            Ndf::Ggx(a) => TrowbridgeReitz::normal_cdf_tan2(t2, a),
            Ndf::Beckmann(m) => Beckmann::normal_cdf_tan2(t2, m),
        }
    }
    /// tan²θ from ξ: the distribution's [`Isotropic::normal_tan2_at_cdf`].
    fn tan2_of(self, xi: T) -> T {
        match self {
            Ndf::Ggx(a) => TrowbridgeReitz::normal_tan2_at_cdf(xi, a),
            Ndf::Beckmann(m) => Beckmann::normal_tan2_at_cdf(xi, m),
        }
    }
    /// D(h) in 1/sr at n·h = `cos_h`: the distribution's [`Isotropic::d_cos`].
    pub fn d(self, cos_h: T) -> T {
        match self {
            Ndf::Ggx(a) => TrowbridgeReitz::d_cos(cos_h, a),
            Ndf::Beckmann(m) => Beckmann::d_cos(cos_h, m),
        }
    }
}

/// Panels per outer piece (composite rule).
pub const OUTER_PANELS: usize = 4;

/// Composite two-channel rule: `k` equal panels of the rule `R`.
fn integrate2k<T: Real, R: Rule>(a: T, b: T, k: usize, mut f: impl FnMut(T) -> (T, T)) -> (T, T) {
    let (mut s0, mut s1) = (T::ZERO, T::ZERO);
    let h = (b - a) / T::from_f64(k as f64);
    for j in 0..k {
        let lo = a + h * T::from_f64(j as f64);
        let (p, q) = integrate2::<T, R>(lo, lo + h, &mut f);
        s0 += p;
        s1 += q;
    }
    (s0, s1)
}

/// Two-channel Gauss–Legendre: (∫ₐᵇ f₀, ∫ₐᵇ f₁) with the rule `R`.
#[inline]
fn integrate2<T: Real, R: Rule>(a: T, b: T, mut f: impl FnMut(T) -> (T, T)) -> (T, T) {
    let h = (b - a) * T::HALF;
    let m = (a + b) * T::HALF;
    let (mut s0, mut s1) = (T::ZERO, T::ZERO);
    for (x, w) in R::half_nodes().iter().zip(R::half_weights()) {
        let dx = h * T::from_f64(*x);
        let w = T::from_f64(*w);
        let (p0, p1) = f(m - dx);
        let (q0, q1) = f(m + dx);
        s0 += w * (p0 + q0);
        s1 += w * (p1 + q1);
    }
    (s0 * h, s1 * h)
}

/// cos θh and sin θh at CDF value ξ (θh = π/2 when ξ reaches 1).
#[inline]
fn half_angle<T: Real>(ndf: Ndf<T>, xi: T) -> (T, T) {
    let tt = ndf.tan2_of(xi);
    if tt.is_finite() {
        let c = T::ONE / (T::ONE + tt).sqrt();
        (c, tt.sqrt() * c)
    } else {
        (T::ZERO, T::ONE)
    }
}

/// The largest azimuth with n·l ≥ 0: arccos(μ(1 − 2cos²θh)/(2 cos θh sin θv sin θh)).
#[inline]
fn phi_max<T: Real>(mu: T, sv: T, (ch, sh): (T, T)) -> T {
    let den = T::TWO * ch * sv * sh;
    if !(den > T::ZERO) {
        return if mu * (T::ONE - T::TWO * ch * ch) < T::ZERO {
            T::PI
        } else {
            T::ZERO
        };
    }
    (mu * (T::ONE - T::TWO * ch * ch) / den)
        .clamp(-T::ONE, T::ONE)
        .acos()
}

/// The two integrands W(1 − F_c), W F_c at (ξ, φ); zero where the light is below the horizon.
#[inline]
fn kernel<T: Real>(mu: T, sv: T, (ch, sh): (T, T), phi: T, g: &impl Fn(Dots<T>) -> T) -> (T, T) {
    let vh = sv * sh * phi.cos() + mu * ch;
    let nl = T::TWO * vh * ch - mu;
    if !(nl > T::ZERO) || !(vh > T::ZERO) || !(ch > T::ZERO) {
        return (T::ZERO, T::ZERO);
    }
    // l = 2(v·h)h − v, so l·v = 2(v·h)² − 1 and l + v = 2(v·h)h, whose tangential length
    // is 2(v·h) sin θh (without the cancellation of 2 + 2 l·v − (n·l + n·v)²).
    let two_vh = T::TWO * vh;
    let t = two_vh * sh;
    let gg = g(Dots {
        n_i: nl.min(T::ONE),
        n_o: mu,
        i_o: (two_vh * vh - T::ONE).clamp(-T::ONE, T::ONE),
        ht2: t * t,
    });
    let w = gg * vh / (mu * ch);
    let fc = (T::ONE - vh).max(T::ZERO).powi(5);
    (w * (T::ONE - fc), w * fc)
}

/// The split-sum pair (A, B) = (∫ W(1 − F_c) D cos θh dωh, ∫ W F_c D cos θh dωh) for the
/// distribution `ndf` and any masking function `g(Dots) → G` (module docs). μ ∈ (0, 1]
/// (clamped above; μ below [`crate::geometry::min_cos`] — μ ≤ 0, subnormal — gives (0, 0);
/// NaN gives NaN).
pub fn split_sum<T: Real, RO: Rule, RI: Rule>(
    mu: T,
    ndf: Ndf<T>,
    g: impl Fn(Dots<T>) -> T,
) -> (T, T) {
    if mu.is_nan() {
        return (T::NAN, T::NAN);
    }
    // μ below √(smallest normal) (subnormal included) is the horizon, as in the models.
    if !(mu >= crate::geometry::min_cos()) {
        return (T::ZERO, T::ZERO);
    }
    let mu = mu.min(T::ONE);
    let sv = (T::ONE - mu * mu).max(T::ZERO).sqrt();
    let theta_v = sv.atan2(mu);
    let quarter = T::FRAC_PI_2 * T::HALF;
    let t1 = quarter - theta_v * T::HALF;
    let t2 = quarter + theta_v * T::HALF;
    let xi1 = ndf.cdf_tan2(t1.tan().sq());
    let xi2 = if t2 >= T::FRAC_PI_2 {
        T::ONE
    } else {
        ndf.cdf_tan2(t2.tan().sq())
    };
    // Piece 1a: θh ∈ [0, θ1/2] in ξ (resolves the peak of D).
    let tm = t1 * T::HALF;
    let xim = ndf.cdf_tan2(tm.tan().sq());
    let (a1, b1) = if xim > T::ZERO {
        integrate2k::<T, RO>(T::ZERO, xim, OUTER_PANELS, |xi| {
            let cs = half_angle(ndf, xi);
            integrate2::<T, RI>(T::ZERO, T::PI, |phi| kernel(mu, sv, cs, phi, &g))
        })
    } else {
        (T::ZERO, T::ZERO)
    };
    // Piece 1b: θh ∈ [θ1/2, θ1] in θ, graded quadratically toward θ1, where the light
    // reaches the horizon and G changes on the scale of α: θ = θ1 − (θ1 − θm)(1 − t)²,
    // dξ = 2π D cos θ sin θ dθ.
    let (a3, b3) = if t1 > tm {
        let len = t1 - tm;
        integrate2k::<T, RO>(T::ZERO, T::ONE, OUTER_PANELS, |t| {
            let q = T::ONE - t;
            let th = t1 - len * q * q;
            let (ch, sh) = (th.cos(), th.sin());
            let jac = T::TWO * T::PI * ndf.d(ch) * ch * sh * T::TWO * len * q;
            let (a, b) =
                integrate2::<T, RI>(T::ZERO, T::PI, |phi| kernel(mu, sv, (ch, sh), phi, &g));
            (a * jac, b * jac)
        })
    } else {
        (T::ZERO, T::ZERO)
    };
    // Piece 2: θh ∈ [θ1, θ2], φ < φmax, ξ on a smoothstep.
    let (a2, b2) = if xi2 > xi1 {
        let span = xi2 - xi1;
        integrate2k::<T, RO>(T::ZERO, T::ONE, OUTER_PANELS, |t| {
            let s = t * t * (T::from_f64(3.0) - T::TWO * t);
            let ds = T::from_f64(6.0) * t * (T::ONE - t);
            let cs = half_angle(ndf, xi1 + span * s);
            let pm = phi_max(mu, sv, cs);
            let (a, b) = integrate2::<T, RI>(T::ZERO, pm, |phi| kernel(mu, sv, cs, phi, &g));
            (a * span * ds, b * span * ds)
        })
    } else {
        (T::ZERO, T::ZERO)
    };
    let inv_pi = T::ONE / T::PI;
    ((a1 + a2 + a3) * inv_pi, (b1 + b2 + b3) * inv_pi)
}

/// GGX split sum (A, B) with height-correlated Smith, α = r² (docs/conventions.md §8), for
/// μ ∈ (0, 1] and perceptual roughness r ∈ [0, 1] (clamped). r = 0 is the mirror limit
/// A = 1 − (1 − μ)⁵, B = (1 − μ)⁵.
pub fn dfg_ggx<T: Real, RO: Rule, RI: Rule>(mu: T, r: T) -> (T, T) {
    if r.is_nan() {
        return (T::NAN, T::NAN);
    }
    let r = r.clamp(T::ZERO, T::ONE);
    let alpha = alpha_from_perceptual(r);
    if !(alpha > T::from_f64(1e-7)) {
        return mirror(mu);
    }
    split_sum::<T, RO, RI>(mu, Ndf::Ggx(alpha), |d| {
        TrowbridgeReitz::g_correlated_cos(d.n_i, d.n_o, alpha)
    })
}

/// Beckmann split sum (A, B) with height-correlated Smith–Beckmann (docs/conventions.md §6) for
/// Beckmann roughness m ≥ 0 (m = 0: mirror limit).
pub fn dfg_beckmann<T: Real, RO: Rule, RI: Rule>(mu: T, m: T) -> (T, T) {
    if m.is_nan() {
        return (T::NAN, T::NAN);
    }
    let m = m.max(T::ZERO);
    if !(m > T::from_f64(1e-7)) {
        return mirror(mu);
    }
    split_sum::<T, RO, RI>(mu, Ndf::Beckmann(m), |d| {
        Beckmann::g_correlated_cos(d.n_i, d.n_o, m)
    })
}

/// Torrance–Sparrow split sum (A, B) for Gaussian slopes of RMS slope σ (Beckmann D,
/// m = √2σ, paper eq 3 / docs/conventions.md §5) with height-correlated Smith G (§6).
pub fn dfg_ts_smith<T: Real, RO: Rule, RI: Rule>(mu: T, sigma: T) -> (T, T) {
    dfg_beckmann::<T, RO, RI>(mu, beckmann_m_from_sigma(sigma))
}

/// Torrance–Sparrow split sum (A, B) for Gaussian slopes of RMS slope σ with the paper's
/// modified G (eqs 6–13, reciprocal 3-D extension [`ModifiedG::g_dots`]). σ must be > 0
/// (otherwise NaN). Because the modified G stays ≥ ½ at grazing, A + B grows like 1/μ as
/// μ → 0 (docs/conventions.md §4).
pub fn dfg_ts_modified<T: Real, RO: Rule, RI: Rule>(mu: T, sigma: T) -> (T, T) {
    let Ok(gm) = ModifiedG::<T>::new(sigma) else {
        return (T::NAN, T::NAN);
    };
    let m = beckmann_m_from_sigma(sigma);
    split_sum::<T, RO, RI>(mu, Ndf::Beckmann(m), |d| gm.g_dots(d))
}

fn mirror<T: Real>(mu: T) -> (T, T) {
    if mu.is_nan() {
        return (T::NAN, T::NAN);
    }
    if !(mu > T::ZERO) {
        return (T::ZERO, T::ZERO);
    }
    let fc = (T::ONE - mu.min(T::ONE)).powi(5);
    (T::ONE - fc, fc)
}

/// Kulla–Conty directional albedo E(μ, r) = A + B (F = 1) for GGX, α = r².
pub fn e_ggx<T: Real, RO: Rule, RI: Rule>(mu: T, r: T) -> T {
    let (a, b) = dfg_ggx::<T, RO, RI>(mu, r);
    a + b
}

/// Kulla–Conty directional albedo E(μ, r) = A + B (F = 1) for Beckmann with height-correlated
/// Smith, m = r².
pub fn e_beckmann<T: Real, RO: Rule, RI: Rule>(mu: T, r: T) -> T {
    if r.is_nan() {
        return T::NAN;
    }
    let r = r.clamp(T::ZERO, T::ONE);
    let (a, b) = dfg_beckmann::<T, RO, RI>(mu, alpha_from_perceptual(r));
    a + b
}

/// E_avg = 2∫₀¹ E(μ) μ dμ, by a `RM`-point rule in t with μ = t² (dμ = 2t dt), which makes
/// the integrand vanish smoothly at grazing.
pub fn e_avg<T: Real, RM: Rule>(e: impl Fn(T) -> T) -> T {
    let (s, _) = integrate2::<T, RM>(T::ZERO, T::ONE, |t| {
        let mu = t * t;
        (T::from_f64(4.0) * e(mu) * mu * t, T::ZERO)
    });
    s
}

/// Kulla–Conty E_avg(r) for GGX (α = r²), 24 points in μ.
pub fn e_avg_ggx<T: Real, RO: Rule, RI: Rule>(r: T) -> T {
    e_avg::<T, GaussLegendre<24>>(|mu| e_ggx::<T, RO, RI>(mu, r))
}

/// Kulla–Conty E_avg(r) for Beckmann (m = r²), 24 points in μ.
pub fn e_avg_beckmann<T: Real, RO: Rule, RI: Rule>(r: T) -> T {
    e_avg::<T, GaussLegendre<24>>(|mu| e_beckmann::<T, RO, RI>(mu, r))
}

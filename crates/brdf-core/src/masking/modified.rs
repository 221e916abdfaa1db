//! The paper's modified geometric attenuation factor (Acta Phys. Sin. 64 184213, eqs 6–13),
//! read as fixed in docs/conventions.md §§3–4 (the passing factor and the two conventions).
//!
//! One-sided passing factor, for a ray leaving at polar angle θ ≥ 0 from a facet tilted by a
//! signed angle a toward the ray's side, with the neighbour's tilt γ drawn from p(γ; σ):
//!
//! ```text
//! M(θ, a) = ∫_{−π/2}^{lo} p dγ + ∫_{lo}^{hi} p(γ) r(γ) dγ          (eqs 6–11)
//! lo = π/2 − θ,  hi = min(π/2, π − 2θ + a)
//! r(γ) = (cos(θ − a) + cos(γ + θ)) / cos(θ − a)                  (eq 9 × cos θ)
//! ```
//!
//! Masking and shadowing, default (reciprocal) convention:
//! GM = M(|θr|, sign(θr)·α), GS = M(θi, −α), G = min(GM, GS) (eq 13), α = (θr − θi)/2.
//! The printed eq 12 ([`Convention::Printed`]) uses GS = M(θi, α), and GM = 1 for θr ≤ 0.
//!
//! One integral per passing factor. In the working variable v = tan γ/(√2σ) (see
//! [`crate::distribution`]), u = √2σ v = tan γ, the density of eqs 2 and 5 becomes
//! p dγ = w(v) dv/(2Z) with w = √(1 + u²) e^{−v²} (dγ = √2σ dv/(1 + u²), 1/cos³γ =
//! (1 + u²)^{3/2}) and 2Z its mass, both halves cut at v = V_CUT. Then
//!
//! ```text
//! fully passing (eqs 6–7):  ∫_{−π/2}^{lo} p dγ = ½ + (1/2Z) ∫₀^{v_lo} w dv,  u_lo = cot θ
//! semi-passing (eqs 8–11):  r = 1 + cos(γ + θ)/cos(θ − a),
//!                           cos(γ + θ) = cos γ (cos θ − u sin θ) = −cos γ · √2σ sin θ (v − v_lo)
//!   so  w r = w − e^{−v²} √2σ sin θ (v − v_lo)/cos(θ − a)      (√(1 + u²) cos γ = 1)
//! M(θ, a) = ½ + (1/2Z) [ ∫₀^{v_hi} w dv − K ],   K = √2σ sin θ/cos(θ − a) · I(v_lo, v_hi − v_lo)
//! I(a, d) = ∫₀^d t e^{−(a+t)²} dt = (e^{−a²} − e^{−b²})/2 − a (√π/2)(erfc a − erfc b),  b = a + d
//! ```
//!
//! (v_hi = v_lo when the semi-passing range is empty.) The first term is the one `R`-point
//! Gauss–Legendre integral per M; the second is elementary (a Gaussian and a Gaussian times
//! v). When hi = π − 2θ + a < π/2 lies inside the cut, hi − lo = π/2 − (θ − a), so
//! cos(θ − a) = sin(hi − lo) = (tan hi − tan lo) cos hi cos lo with cos lo = sin θ, and
//! √2σ sin θ/cos(θ − a) = √(1 + u_hi²)/(v_hi − v_lo): K = √(1 + u_hi²) · I/d no longer divides
//! by the cos(θ − a) that cancels as the range closes, and tends to 0 like d. There the
//! closed form for I loses accuracy to cancellation (I ≈ e^{−a²}d²/2 while its terms are of
//! order e^{−a²}d), so for d below ½ (f32) or 1e-3 (f64) I is integrated by a 4-node rule.
//!
//! 3-D extension ([`ModifiedG::terms_dots`]): each ray sees the surface profile in its own
//! azimuthal plane, and the facet's tilt toward that ray is the slope of the half vector
//! projected on that plane: tan a_w = (h_t · ŵ_t)/h_z. For coplanar pairs this is exactly
//! ±α; because h is symmetric in (wi, wo) and G takes the minimum of the two sides, the
//! extension is reciprocal.

use crate::distribution::{SlopeDistribution, V_CUT};
use crate::error::ParamError;
use crate::geometry::{clamp_theta_i, clamp_theta_r, Dots, Vec3};
use crate::quadrature::{DefaultRule, Rule};

use crate::Real;

/// Which reading of eq 12 to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Convention {
    /// GS = M(θi, −α): the tilt toward the light (docs/conventions.md §4). Reciprocal.
    #[default]
    Reciprocal,
    /// Eq 12 as printed: GS = M(θi, α), GM = 1 for θr ≤ 0. Not reciprocal (kept for
    /// comparison with the paper's figures).
    Printed,
}

/// The masking term, the shadowing term and G = min(GM, GS).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GTerms<T> {
    /// Masking (the viewing side), eq 11.
    pub gm: T,
    /// Shadowing (the light's side), eq 12.
    pub gs: T,
    /// G = min(GM, GS), eq 13.
    pub g: T,
}

impl<T: Real> GTerms<T> {
    #[inline]
    fn new(gm: T, gs: T) -> Self {
        let g = if gm.is_nan() || gs.is_nan() {
            T::NAN
        } else {
            gm.min(gs)
        };
        Self { gm, gs, g }
    }
    #[inline]
    fn all(x: T) -> Self {
        Self { gm: x, gs: x, g: x }
    }
}

/// The modified G for one surface (one σ), with the normaliser precomputed.
///
/// `R` picks the quadrature rule (e.g. `GaussLegendre<16>`); the default has [`crate::quadrature::DEFAULT_NODES`] nodes.
#[derive(Clone, Copy, Debug)]
pub struct ModifiedG<T, R = DefaultRule> {
    dist: SlopeDistribution<T, R>,
    convention: Convention,
}

impl<T: Real, R: Rule> ModifiedG<T, R> {
    /// The largest RMS slope σ [`ModifiedG::new`] accepts.
    pub const SIGMA_MAX: f64 = 1e6;

    /// Checked constructor: σ (RMS slope) in (0, [`Self::SIGMA_MAX`]]; reciprocal convention.
    /// The accuracy bound (1e-6 in f64, 2e-6 in f32) is specified for σ ∈ [0.05, 1]; every
    /// accepted σ gives finite results in [0, 1]. Larger σ is rejected with
    /// [`ParamError::OutOfRange`]: the normaliser's integrand √(1 + 2σ²v²) overflows f32 from
    /// σ ≈ 3e18 (f64: 1.4e154), and long before that the surface is a forest of vertical
    /// facets the model was not written for.
    pub fn new(sigma: T) -> Result<Self, ParamError> {
        if sigma > T::from_f64(Self::SIGMA_MAX) && sigma.is_finite() {
            return Err(ParamError::OutOfRange {
                name: "sigma",
                range: "(0, 1e6]",
            });
        }
        Ok(Self {
            dist: SlopeDistribution::new(sigma)?,
            convention: Convention::Reciprocal,
        })
    }
    /// The same surface with another convention.
    pub fn with_convention(mut self, convention: Convention) -> Self {
        self.convention = convention;
        self
    }
    /// The convention in use.
    pub fn convention(&self) -> Convention {
        self.convention
    }
    /// The slope distribution (σ, C(σ), p, cdf).
    pub fn distribution(&self) -> &SlopeDistribution<T, R> {
        &self.dist
    }

    /// M(θ, a) from angles in radians: θ ∈ [0, π/2] (clamped), a ∈ [−π/2, π/2] (clamped).
    pub fn passing(&self, theta: T, a: T) -> T {
        let (st, ct) = clamp_theta_i(theta).sin_cos();
        let (sa, ca) = clamp_theta_r(a).sin_cos();
        self.passing_cs(ct, st, ca, sa)
    }

    /// M(θ, a) from cos θ, sin θ (sin θ ≥ 0) and cos a, sin a (cos a ≥ 0). Result in [½, 1]
    /// for every θ ≤ π/2 (a cos θ rounded below 0, as f32 cos(π/2) is, counts as 0); 1 at
    /// θ = 0. NaN in, NaN out.
    ///
    /// The bound is exact, and enforced: lo = π/2 − θ ≥ 0, so the fully passing part
    /// ∫_{−π/2}^{lo} p is at least ½ (p is even), and on the semi-passing range
    /// γ + θ ≤ hi + θ ≤ π − (θ − a), so cos(γ + θ) ≥ −cos(θ − a) and r ≥ 0. The computed sum
    /// can round below ½ where the semi-passing part is far smaller than the rounding of
    /// the normaliser (θ → π/2 with σ ≳ 1e4 in f64 or 1e6 in f32: M − ½ ≈ 3e-8 at σ = 1e4);
    /// it is clamped to [½, 1], which only moves it toward the exact value.
    ///
    /// One rule-`R` integral of √(1 + u²)e^{−v²} over [0, v_hi] plus the closed-form
    /// correction described in the module docs. In f64 the integral is skipped where its
    /// value is known by definition: lo beyond the cut (M = 1) and v_hi at the cut (the
    /// integral is the normaliser's Z, so M = 1 − K/(2Z)).
    pub fn passing_cs(&self, cos_t: T, sin_t: T, cos_a: T, sin_a: T) -> T {
        if T::EPSILON < T::from_f64(1e-10) {
            return self.passing_cs_f64(cos_t, sin_t, cos_a, sin_a);
        }
        let Some((cos_t, s2, vc, vlo)) = self.passing_bounds(cos_t, sin_t) else {
            return T::ONE;
        };
        let (vhi, corr) = self.semi_correction(cos_t, sin_t, cos_a, sin_a, vlo, vc, s2);
        // √(1 + u²)·e^{−v²}, one pass.
        let q = R::integrate(T::ZERO, vhi, |v| {
            let u = s2 * v;
            (T::ONE + u * u).sqrt() * (-(v * v)).exp_bounded()
        });
        (T::HALF + (q - corr) * self.dist.inv_2z()).clamp(T::HALF, T::ONE)
    }

    /// [`ModifiedG::passing_cs`] in f64: the same integrals, with two shortcuts that are
    /// exact by definition (lo beyond the cut: M = 1; the semi-passing range reaching the
    /// cut: the integral is Z itself) and the integral from the squared nodes
    /// ([`Rule::integrate_slope_weight`]).
    #[inline]
    fn passing_cs_f64(&self, cos_t: T, sin_t: T, cos_a: T, sin_a: T) -> T {
        let Some((cos_t, s2, vc, vlo)) = self.passing_bounds(cos_t, sin_t) else {
            return T::ONE;
        };
        // lo beyond the cut: every neighbour passes, M = 1 exactly (NaN goes on).
        if vlo >= vc {
            return T::ONE;
        }
        let (vhi, corr) = self.semi_correction(cos_t, sin_t, cos_a, sin_a, vlo, vc, s2);
        let inv_2z = self.dist.inv_2z();
        if vhi >= vc {
            // Semi-passing range up to the cut: the integral is the normaliser's own, Z
            // (by definition), so M = ½ + (Z − K)/(2Z) = 1 − K/(2Z).
            return (T::ONE - corr * inv_2z).clamp(T::HALF, T::ONE);
        }
        let q = R::integrate_slope_weight(vhi, s2 * s2);
        (T::HALF + (q - corr) * inv_2z).clamp(T::HALF, T::ONE)
    }

    /// The start shared by both precisions of [`ModifiedG::passing_cs`]: `None` for
    /// sin θ = 0 (M = 1), else (cos θ clamped to ≥ 0, √2σ, [`V_CUT`], v_lo), with the fully
    /// passing bound v_lo of eqs 6–7 (tan lo = cot θ).
    #[inline]
    fn passing_bounds(&self, cos_t: T, sin_t: T) -> Option<(T, T, T, T)> {
        if sin_t == T::ZERO {
            return None;
        }
        // θ ≤ π/2: a rounded cos θ < 0 (f32 π/2 exceeds π/2) would put v_lo below 0.
        let cos_t = if cos_t < T::ZERO { T::ZERO } else { cos_t };
        let vlo = self.dist.v_of_tan(cos_t, sin_t);
        Some((cos_t, self.dist.sqrt2_sigma(), T::from_f64(V_CUT), vlo))
    }

    /// The semi-passing range's end v_hi (v_lo when the range is empty) and the correction K
    /// of the module docs (eqs 8–11): K = f · I(v_lo, v_hi − v_lo) with
    /// f = √(1 + u_hi²)/(v_hi − v_lo) when hi lies inside the cut, else √2σ sin θ/cos(θ − a)
    /// (then cos(θ − a) ≥ sin θ when hi ≥ π/2, or v_lo lies so close to the cut that
    /// e^{−v_lo²} < 2e-9 bounds K).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn semi_correction(
        &self,
        cos_t: T,
        sin_t: T,
        cos_a: T,
        sin_a: T,
        vlo: T,
        vc: T,
        s2: T,
    ) -> (T, T) {
        // Semi-passing (eqs 9–10): non-empty iff cos(θ − a) > 0 and lo is inside the cut.
        let cb = cos_t * cos_a + sin_t * sin_a;
        if !(cb > T::ZERO) || !(vlo < vc) {
            return (vlo, T::ZERO);
        }
        // hi = π − φ with φ = 2θ − a ∈ (−π/2, π); hi ≥ π/2 when cos φ ≥ 0.
        let c2t = cos_t * cos_t - sin_t * sin_t;
        let s2t = T::TWO * sin_t * cos_t;
        let cphi = c2t * cos_a + s2t * sin_a;
        let sphi = s2t * cos_a - c2t * sin_a;
        // tan hi = sin φ/(−cos φ), in v: sin φ/(−cos φ · √2σ) when below the cut.
        let inside = cphi < T::ZERO && sphi < vc * (-cphi) * s2;
        let vhi = if inside { sphi / (-cphi * s2) } else { vc };
        if !(vhi > vlo) {
            return (vlo, T::ZERO);
        }
        let d = vhi - vlo;
        let i = gauss_tail_moment(vlo, d);
        let corr = if inside {
            let u = s2 * vhi;
            (T::ONE + u * u).sqrt() * (i / d)
        } else {
            s2 * sin_t * i / cb
        };
        (vhi, corr)
    }

    /// GM, GS and G from the paper's in-plane angles in radians (θi ∈ [0, π/2],
    /// θr ∈ [−π/2, π/2] signed; out-of-range angles are clamped, NaN gives NaN).
    pub fn terms(&self, theta_i: T, theta_r: T) -> GTerms<T> {
        if theta_i.is_nan() || theta_r.is_nan() {
            return GTerms::all(T::NAN);
        }
        let ti = clamp_theta_i(theta_i);
        let tr = clamp_theta_r(theta_r);
        let (si, ci, so, co) = if T::EPSILON < T::from_f64(1e-10) {
            // f64: the two angles side by side (same values).
            let ([si, so], [ci, co]) = T::sin_cos2([ti, tr.abs()]);
            (si, ci, so, co)
        } else {
            let (si, ci) = ti.sin_cos();
            let (so, co) = tr.abs().sin_cos();
            (si, ci, so, co)
        };
        // α = (θr − θi)/2 ∈ [−π/2, π/4] by the half-angle formulas from 2α = θr − θi,
        // each on the side where it does not cancel: |α| ≤ π/4 → cos α = √((1 + cos 2α)/2),
        // sin α = sin 2α/(2 cos α); α < −π/4 → sin α = −√((1 − cos 2α)/2),
        // cos α = sin 2α/(2 sin α).
        let sr = if tr < T::ZERO { -so } else { so };
        let c2a = co * ci + sr * si;
        let s2a = sr * ci - co * si;
        let (sa, ca) = if T::EPSILON < T::from_f64(1e-10) {
            // f64: the same values without a branch on the (unpredictable) side: one square
            // root r and one quotient q = sin 2α/(2r), then (q, r) or (−r, max(−q, 0))
            // (x/(−r) = −(x/r) exactly).
            let pos = c2a >= T::ZERO;
            let r = (if pos { T::ONE + c2a } else { T::ONE - c2a } * T::HALF).sqrt();
            let q = s2a * T::HALF / r;
            let nq = (-q).max(T::ZERO);
            (if pos { q } else { -r }, if pos { r } else { nq })
        } else if c2a >= T::ZERO {
            let ca = ((T::ONE + c2a) * T::HALF).sqrt();
            (s2a * T::HALF / ca, ca)
        } else {
            let sa = -((T::ONE - c2a) * T::HALF).sqrt();
            (sa, (s2a * T::HALF / sa).max(T::ZERO))
        };
        match self.convention {
            Convention::Reciprocal => {
                let sign = if tr < T::ZERO { -T::ONE } else { T::ONE };
                GTerms::new(
                    self.passing_cs(co, so, ca, sign * sa),
                    self.passing_cs(ci, si, ca, -sa),
                )
            }
            Convention::Printed => {
                let gm = if tr > T::ZERO {
                    self.passing_cs(co, so, ca, sa)
                } else {
                    T::ONE
                };
                GTerms::new(gm, self.passing_cs(ci, si, ca, sa))
            }
        }
    }

    /// G = min(GM, GS) from in-plane angles; see [`ModifiedG::terms`].
    #[inline]
    pub fn g(&self, theta_i: T, theta_r: T) -> T {
        self.terms(theta_i, theta_r).g
    }

    /// GM, GS and G from the dot products n·wi, n·wo, wi·wo of unit vectors (shader form),
    /// through the reciprocal 3-D extension described in the module docs. A direction at or
    /// below the horizon gives G = 0; NaN gives NaN. With [`Convention::Printed`] the pair is
    /// folded into its plane of incidence (θr > 0 when the tangential parts point apart).
    pub fn terms_dots(&self, d: Dots<T>) -> GTerms<T> {
        if d.n_i.is_nan() || d.n_o.is_nan() || d.i_o.is_nan() {
            return GTerms::all(T::NAN);
        }
        if !(d.n_i > T::ZERO) || !(d.n_o > T::ZERO) {
            return GTerms::all(T::ZERO);
        }
        let ci = d.n_i.min(T::ONE);
        let co = d.n_o.min(T::ONE);
        let si = (T::ONE - ci * ci).sqrt();
        let so = (T::ONE - co * co).sqrt();
        // wi_t · wo_t, the tangential parts' dot product.
        let tt = d.i_o.clamp(-T::ONE, T::ONE) - ci * co;
        if self.convention == Convention::Printed {
            let ti = si.atan2(ci);
            let to = so.atan2(co);
            let tr = if tt <= T::ZERO { to } else { -to };
            return self.terms(ti, tr);
        }
        let hz = ci + co;
        // Projected tilt toward w: tan a = (tt + s_w²)/(s_w · hz).
        let side = |c: T, s: T| -> T {
            let num = tt + s * s;
            let den = s * hz;
            let l = (num * num + den * den).sqrt();
            if l > T::ZERO {
                self.passing_cs(c, s, den / l, num / l)
            } else {
                T::ONE
            }
        };
        GTerms::new(side(co, so), side(ci, si))
    }

    /// G from dot products; see [`ModifiedG::terms_dots`].
    #[inline]
    pub fn g_dots(&self, d: Dots<T>) -> T {
        self.terms_dots(d).g
    }

    /// G for directions wi (toward the light) and wo (toward the viewer) and the normal n,
    /// in any frame. The vectors are normalised here; `None` when any is zero or not finite.
    pub fn g_vectors(&self, wi: Vec3<T>, wo: Vec3<T>, n: Vec3<T>) -> Option<T> {
        let (wi, wo, n) = (wi.normalize()?, wo.normalize()?, n.normalize()?);
        Some(self.g_dots(Dots::from_vectors(wi, wo, n)))
    }
}

/// Number of nodes of the short rule [`gauss_tail_moment`] uses below [`TAIL_SHORT`].
type TailRule = crate::quadrature::GaussLegendre<4>;
/// Interval length below which the f32 tail moment is integrated rather than taken in
/// closed form (the closed form's two terms cancel as d → 0).
const TAIL_SHORT: f64 = 0.5;
/// √π/2.
const SQRT_PI_2: f64 = 0.886_226_925_452_758;

/// I(a, d) = ∫₀^d t e^{−(a+t)²} dt for a ≥ 0, d > 0:
/// I = (e^{−a²} − e^{−b²})/2 − a (√π/2)(erfc a − erfc b), b = a + d,
/// from ∫ v e^{−v²} dv = −e^{−v²}/2 and ∫ e^{−v²} dv = −(√π/2) erfc v. For d < 1 the two
/// terms cancel (I ≈ e^{−a²}d²/2 while each is of order e^{−a²}d), so there a 6-node
/// Gauss–Legendre rule on [0, d] is used instead (the integrand is a Gaussian times t).
#[inline]
fn gauss_tail_moment<T: Real>(a: T, d: T) -> T {
    // f64: the closed form's cancellation costs ε·e^{−a²}/d, negligible above d = 1e-3.
    let short = if T::EPSILON < T::from_f64(1e-10) {
        T::from_f64(1e-3)
    } else {
        T::from_f64(TAIL_SHORT)
    };
    if d < short {
        TailRule::integrate(T::ZERO, d, |t| {
            let v = a + t;
            t * (-(v * v)).exp_bounded()
        })
    } else if T::EPSILON < T::from_f64(1e-10) {
        // I = F(a) − F(b) with F(x) = e^{−x²}/2 − a (√π/2) erfc x: the two ends as two
        // identical computations (one SIMD register in f64). a, b ∈ [0, V_CUT]: the
        // bounded exp and erfc apply.
        let b = a + d;
        let c = a * T::from_f64(SQRT_PI_2);
        let e = T::exp_neg2([a * a, b * b]);
        let x = T::erfcx2_bounded([a, b]);
        // F(x) = e^{−x²} (½ − c e^{x²} erfc x).
        e[0] * (T::HALF - c * x[0]) - e[1] * (T::HALF - c * x[1])
    } else {
        let b = a + d;
        ((-(a * a)).exp() - (-(b * b)).exp()) * T::HALF
            - a * T::from_f64(SQRT_PI_2) * (a.erfc() - b.erfc())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// GM and GS of [`ModifiedG::terms`] the straightforward way: one sin/cos per angle, α
    /// from the half-angle formulas of 2α = θr − θi with a branch per side (|α| ≤ π/4 or
    /// not), the one-sided factor [`ModifiedG::passing_cs`] called twice.
    fn sequential<R: Rule>(g: &ModifiedG<f64, R>, ti: f64, tr: f64) -> (f64, f64) {
        let ti = clamp_theta_i(ti);
        let tr = clamp_theta_r(tr);
        let (si, ci) = Real::sin_cos(ti);
        let (so, co) = Real::sin_cos(tr.abs());
        let sr = if tr < 0.0 { -so } else { so };
        let c2a = co * ci + sr * si;
        let s2a = sr * ci - co * si;
        let (sa, ca) = if c2a >= 0.0 {
            let ca = libm::sqrt((1.0 + c2a) * 0.5);
            (s2a * 0.5 / ca, ca)
        } else {
            let sa = -libm::sqrt((1.0 - c2a) * 0.5);
            (sa, (s2a * 0.5 / sa).max(0.0))
        };
        let sign = if tr < 0.0 { -1.0 } else { 1.0 };
        (
            g.passing_cs(co, so, ca, sign * sa),
            g.passing_cs(ci, si, ca, -sa),
        )
    }

    /// [`ModifiedG::terms`] in f64 (both angles' sin and cos side by side, the half angle
    /// without a branch) bit for bit against the straightforward evaluation (see
    /// `sequential`) on a dense grid of (θi, θr) including θ = 0,
    /// π/2, θr = ±θi (the kinks where GM = GS) and angles beyond the range (clamped); NaN.
    #[test]
    fn terms_match_sequential_one_sided_factors() {
        let h = core::f64::consts::FRAC_PI_2;
        let mut ti: std::vec::Vec<f64> = (0..=180).map(|j| h * j as f64 / 180.0).collect();
        ti.extend([1e-9, h - 1e-9, -0.1, h + 0.1]);
        for sigma in [0.02, 0.05, 0.2, 0.5, 1.0, 10.0] {
            let g = ModifiedG::<f64>::new(sigma).unwrap();
            for &a in &ti {
                let mut tr: std::vec::Vec<f64> =
                    (-180..=180).map(|j| h * j as f64 / 180.0).collect();
                tr.extend([a, -a, a + 1e-9, -a - 1e-9, a - 1e-9, -h - 0.1, h + 0.1]);
                for &r in &tr {
                    let t = g.terms(a, r);
                    let (gm, gs) = sequential(&g, a, r);
                    assert!(
                        t.gm.to_bits() == gm.to_bits() && t.gs.to_bits() == gs.to_bits(),
                        "σ={sigma} θi={a} θr={r}: {t:?} vs {gm}, {gs}"
                    );
                    assert_eq!(t.g.to_bits(), gm.min(gs).to_bits());
                }
            }
        }
        let t = ModifiedG::<f64>::new(0.3).unwrap().terms(f64::NAN, 0.2);
        assert!(t.gm.is_nan() && t.gs.is_nan() && t.g.is_nan());
    }
}

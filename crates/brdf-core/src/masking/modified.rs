//! The paper's modified geometric attenuation factor (Acta Phys. Sin. 64 184213, eqs 6–13),
//! read as fixed in conventions.md §§3–4.
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
//! Both integrals are evaluated in the working variable v = tan γ/(√2σ) (see
//! [`crate::distribution`]) with a fixed `R`-point Gauss–Legendre rule each, so one M costs
//! 2 × N exponentials and square roots. In that variable,
//! p·r ∝ e^{−v²}(√(1 + u²) + (cos θ − u sin θ)/cos(θ − a)), u = √2σ v.
//!
//! 3-D extension ([`ModifiedG::terms_dots`]): each ray sees the surface profile in its own
//! azimuthal plane, and the facet's tilt toward that ray is the slope of the half vector
//! projected on that plane: tan a_w = (h_t · ŵ_t)/h_z. For coplanar pairs this is exactly
//! ±α; because h is symmetric in (wi, wo) and G takes the minimum of the two sides, the
//! extension is reciprocal.

use crate::distribution::{slope_weight, SlopeDistribution, V_CUT};
use crate::error::ParamError;
use crate::geometry::{clamp_theta_i, clamp_theta_r, Dots, Vec3};
use crate::quadrature::{DefaultRule, Rule};
use crate::Real;

/// Which reading of eq 12 to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Convention {
    /// GS = M(θi, −α): the tilt toward the light (conventions.md §4). Reciprocal.
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
    /// Checked constructor: σ (RMS slope) finite and > 0; reciprocal convention.
    /// The accuracy bound (1e-6 in f64) is specified for σ ∈ [0.05, 1].
    pub fn new(sigma: T) -> Result<Self, ParamError> {
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
        let t = clamp_theta_i(theta);
        let a = clamp_theta_r(a);
        self.passing_cs(t.cos(), t.sin(), a.cos(), a.sin())
    }

    /// M(θ, a) from cos θ, sin θ (sin θ ≥ 0) and cos a, sin a (cos a ≥ 0). Result in [0, 1];
    /// 1 at θ = 0; at least ½ for every θ ≤ π/2. NaN in, NaN out.
    pub fn passing_cs(&self, cos_t: T, sin_t: T, cos_a: T, sin_a: T) -> T {
        if sin_t == T::ZERO {
            return T::ONE;
        }
        let s2 = self.dist.sqrt2_sigma();
        let k = self.dist.inv_2z();
        let vc = T::from_f64(V_CUT);
        // Fully passing (eqs 6–7): 1/2 + ∫₀^{v(lo)}, tan lo = cot θ.
        let vlo = self.dist.v_of_tan(cos_t, sin_t);
        let full = T::HALF + R::integrate(T::ZERO, vlo, |v| slope_weight(v, s2)) * k;
        // Semi-passing (eqs 9–10). Non-empty iff cos(θ − a) > 0.
        let cb = cos_t * cos_a + sin_t * sin_a;
        if !(cb > T::ZERO) || !(vlo < vc) {
            return full.clamp(T::ZERO, T::ONE);
        }
        // hi = π − φ with φ = 2θ − a ∈ (−π/2, π); hi ≥ π/2 when cos φ ≥ 0.
        let c2t = cos_t * cos_t - sin_t * sin_t;
        let s2t = T::TWO * sin_t * cos_t;
        let cphi = c2t * cos_a + s2t * sin_a;
        let sphi = s2t * cos_a - c2t * sin_a;
        let vhi = if cphi >= T::ZERO {
            vc
        } else {
            self.dist.v_of_tan(sphi, -cphi)
        };
        if !(vhi > vlo) {
            return full.clamp(T::ZERO, T::ONE);
        }
        let inv_cb = T::ONE / cb;
        let semi = R::integrate(vlo, vhi, |v| {
            let u = s2 * v;
            (-(v * v)).exp() * ((T::ONE + u * u).sqrt() + (cos_t - u * sin_t) * inv_cb)
        }) * k;
        (full + semi).clamp(T::ZERO, T::ONE)
    }

    /// GM, GS and G from the paper's in-plane angles in radians (θi ∈ [0, π/2],
    /// θr ∈ [−π/2, π/2] signed; out-of-range angles are clamped, NaN gives NaN).
    pub fn terms(&self, theta_i: T, theta_r: T) -> GTerms<T> {
        if theta_i.is_nan() || theta_r.is_nan() {
            return GTerms::all(T::NAN);
        }
        let ti = clamp_theta_i(theta_i);
        let tr = clamp_theta_r(theta_r);
        let alpha = (tr - ti) * T::HALF;
        let (ca, sa) = (alpha.cos(), alpha.sin());
        let (ci, si) = (ti.cos(), ti.sin());
        let (co, so) = (tr.cos(), tr.abs().sin());
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

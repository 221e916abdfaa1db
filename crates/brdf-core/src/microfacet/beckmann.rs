//! The Beckmann distribution (Gaussian slopes; the D of the Torrance–Sparrow BRDF, paper
//! eq 3, and of Cook–Torrance), anisotropic widths (αx, αy) = √2 × the RMS slopes.
//!
//! * D(h) = exp(−((h_x/αx)² + (h_y/αy)²)/h_z²) / (π αx αy h_z⁴).
//! * Smith's Λ(w) = (e^{−a²}/(a√π) − erfc a)/2 with a = w_z/√((αx w_x)² + (αy w_y)²)
//!   (a = 1/(α tan θ) for the width α projected on w's azimuth); written with erfc, so the
//!   difference has no cancellation for small a (grazing), and Λ < 1e-29 is returned as 0
//!   for a > 8.
//! * Normals, density D(h) cos θh: the stretched slopes (x/αx, y/αy) are a unit 2-D
//!   Gaussian e^{−r²}/π, so r² = −ln(1 − u0) and the azimuth is 2πu1; h ∝ (αx r cos, αy r
//!   sin, 1).
//! * Visible normals: [`super::beckmann_visible`] (no closed-form inverse; a bracketed
//!   Newton inversion of the visible-slope CDF).

use super::{from_cos, projected, stretched, Distribution, Isotropic, FRAC_1_SQRT_PI};
use crate::geometry::{min_cos, Vec3};
use crate::{ParamError, Real};

widths_distribution! {
    /// The anisotropic Beckmann distribution with Smith masking.
    Beckmann
}

impl<T: Real> Beckmann<T> {
    /// From the paper's RMS slope σ: α = √2 σ (isotropic, checked).
    pub fn from_sigma(sigma: T) -> Result<Self, ParamError> {
        Self::isotropic(crate::roughness::beckmann_m_from_sigma(sigma))
    }
}

/// Dot-product forms (paper eq 3 and Smith's Λ for Beckmann): D = exp(−tan²θh/m²)/(π m²
/// cos⁴θh); with a = 1/(m tan θ), Λ = (erf(a) − 1)/2 + exp(−a²)/(2a√π), written with erfc
/// to avoid the cancellation; G1 = 1/(1 + Λ).
impl<T: Real> Isotropic<T> for Beckmann<T> {
    #[inline]
    fn d_cos(cos_h: T, m: T) -> T {
        Self::d_iso(cos_h, m)
    }
    /// ξ = 1 − exp(−t/m²) (the unit Gaussian's radial CDF 1 − e^{−r²}, r² = t/m²).
    #[inline]
    fn normal_cdf_tan2(t2: T, m: T) -> T {
        let m2 = m * m;
        if m2 > T::ZERO {
            T::ONE - (-t2 / m2).exp()
        } else {
            T::ONE
        }
    }
    /// t = −m² ln(1 − ξ).
    #[inline]
    fn normal_tan2_at_cdf(xi: T, m: T) -> T {
        let q = (T::ONE - xi).max(T::ZERO);
        if q > T::ZERO {
            -(m * m) * q.ln()
        } else {
            T::INFINITY
        }
    }
    #[inline]
    fn lambda_cos(cos_t: T, m: T) -> T {
        if cos_t.is_nan() || m.is_nan() {
            return T::NAN;
        }
        if !(m > T::ZERO) {
            return if cos_t > T::ZERO {
                T::ZERO
            } else {
                T::INFINITY
            };
        }
        Self::clamped(m, m).lambda(from_cos(cos_t))
    }
}

impl<T: Real> Distribution<T> for Beckmann<T> {
    fn alpha(&self) -> (T, T) {
        (self.ax, self.ay)
    }
    fn d(&self, h: Vec3<T>) -> T {
        if let Some(v) = self.d_guard(h.z) {
            return v;
        }
        let c2 = h.z * h.z;
        if c2 == T::ZERO {
            return T::ZERO;
        }
        let g = (-(stretched(self.ax, self.ay, h) / c2)).exp();
        if g == T::ZERO {
            return T::ZERO;
        }
        // Divided in steps so that no intermediate overflows before the small factors.
        g / (T::PI * self.ax * self.ay) / c2 / c2
    }
    fn lambda(&self, w: Vec3<T>) -> T {
        if w.z.is_nan() || self.ax.is_nan() || self.ay.is_nan() {
            return T::NAN;
        }
        if !(w.z >= min_cos()) {
            return T::INFINITY;
        }
        let a2 = projected(self.ax, self.ay, w);
        if !(a2 > T::ZERO) {
            return T::ZERO;
        }
        let a = w.z.min(T::ONE) / a2.sqrt();
        if a > T::from_f64(8.0) {
            return T::ZERO;
        }
        ((-(a * a)).exp() * T::from_f64(FRAC_1_SQRT_PI) / a - a.erfc()) * T::HALF
    }
    fn sample_normal(&self, u: [T; 2]) -> Vec3<T> {
        let u0 = crate::sampling::unit(u[0]);
        let (c, s) = super::azimuth(u[1]);
        // 1 − u0 ≥ ε, so r is finite; ln(1 − u0) is exact near u0 = 0 only through the
        // subtraction, which is exact for u0 < ½.
        let r = (-(T::ONE - u0).ln()).max(T::ZERO).sqrt();
        Vec3::new(self.ax * r * c, self.ay * r * s, T::ONE)
            .normalize()
            .unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ONE))
    }
    fn sample_visible_normal(&self, wo: Vec3<T>, u: [T; 2]) -> Option<Vec3<T>> {
        if !(wo.x.is_finite() && wo.y.is_finite() && wo.z >= min_cos()) {
            return None;
        }
        super::beckmann_visible::sample(wo, self.ax, self.ay, u)
    }
}

//! The Trowbridge–Reitz (GGX) distribution, anisotropic widths (αx, αy).
//!
//! * D(h) = 1/(π αx αy s²), s = (h_x/αx)² + (h_y/αy)² + h_z² (the isotropic
//!   α²/(π((n·h)²(α² − 1) + 1)²) divided through by α⁴; no cancellation for any α).
//! * Smith's Λ(w) = (√(1 + a²/w_z²) − 1)/2 with a² = (αx w_x)² + (αy w_y)², written as
//!   Λ = a²/(2 w_z (w_z + √(w_z² + a²))) (multiplied by the conjugate: no cancellation for
//!   small a, no overflow at grazing), and G1 = 2 w_z/(w_z + √(w_z² + a²)).
//! * Height-correlated visibility V = G/(4 cos θi cos θo) = ½/(cos θo R_i + cos θi R_o),
//!   R = √(w_z² + a²) (from 1 + Λi + Λo = (cos θo R_i + cos θi R_o)/(2 cos θi cos θo)).
//! * Normals, density D(h) cos θh: the stretched slopes have density 1/(π(1 + r²)²), radial
//!   CDF r²/(1 + r²) = u0, so h ∝ (αx √u0 cos 2πu1, αy √u0 sin 2πu1, √(1 − u0)).
//! * Visible normals: stretch the view to the α = 1 configuration, take a uniform point on
//!   the projected visible hemisphere (a disc point whose second coordinate is compressed
//!   onto the visible half), lift it to the hemisphere and unstretch.

use super::{clamp_alpha, from_cos, projected, stretched, Distribution, Isotropic};
use crate::geometry::{min_cos, Vec3};
use crate::Real;

widths_distribution! {
    /// The anisotropic Trowbridge–Reitz (GGX) distribution with Smith masking.
    TrowbridgeReitz
}

impl<T: Real> TrowbridgeReitz<T> {
    /// The height-correlated visibility V = G/(4 cos θi cos θo) (module docs); 0 when
    /// either direction is at or below the horizon.
    pub fn v_correlated(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        let (ai, ao) = (
            projected(self.ax, self.ay, wi),
            projected(self.ax, self.ay, wo),
        );
        v_finish(
            wi.z,
            wo.z,
            lambda_radicand(wi.z, ai).sqrt(),
            lambda_radicand(wo.z, ao).sqrt(),
            ai + ao,
        )
    }
}

impl<T: Real> TrowbridgeReitz<T> {
    /// The height-correlated visibility in the dot products, V = G/(4 n·l n·v), closed
    /// form finite at grazing: V = ½/(n·l √((n·v)² + α² sin²θv) + n·v √((n·l)² + α² sin²θl))
    /// (Heitz 2014, eq 99, divided by 4 n·l n·v); 0 when either cosine is below
    /// [`min_cos`]; α as in [`Isotropic`].
    #[inline]
    pub fn v_correlated_cos(cos_i: T, cos_o: T, alpha: T) -> T {
        let (ai, ao) = v_a2(cos_i, cos_o, alpha);
        v_finish(
            cos_i,
            cos_o,
            lambda_radicand(cos_i, ai).sqrt(),
            lambda_radicand(cos_o, ao).sqrt(),
            alpha,
        )
    }
}

/// The a² of both directions for [`TrowbridgeReitz::v_correlated_cos`] (shared with the
/// batch form): 0 for α ≤ 0 (and NaN α, which `v_finish` catches through α itself).
#[inline]
pub(crate) fn v_a2<T: Real>(cos_i: T, cos_o: T, alpha: T) -> (T, T) {
    if alpha > T::ZERO {
        (iso_a2(cos_i, alpha), iso_a2(cos_o, alpha))
    } else {
        (T::ZERO, T::ZERO)
    }
}

/// Dot-product forms: D = α²/(π((n·h)²(α² − 1) + 1)²); Λ = (√(1 + α² tan²θ) − 1)/2
/// evaluated as a²/(2c(c + √(c² + a²))), a² = α² sin²θ (no cancellation, no overflow at
/// grazing); G1 = 2c/(c + √(c² + α² sin²θ)).
impl<T: Real> Isotropic<T> for TrowbridgeReitz<T> {
    #[inline]
    fn d_cos(cos_h: T, alpha: T) -> T {
        Self::d_iso(cos_h, alpha)
    }
    /// ξ = t/(α² + t) (the stretched slopes' radial CDF r²/(1 + r²), r² = t/α²).
    #[inline]
    fn normal_cdf_tan2(t2: T, a: T) -> T {
        let d = a * a + t2;
        if d > T::ZERO {
            t2 / d
        } else {
            T::ONE
        }
    }
    /// t = α² ξ/(1 − ξ).
    #[inline]
    fn normal_tan2_at_cdf(xi: T, a: T) -> T {
        let q = (T::ONE - xi).max(T::ZERO);
        if q > T::ZERO {
            a * a * xi / q
        } else {
            T::INFINITY
        }
    }
    #[inline]
    fn lambda_cos(cos_t: T, alpha: T) -> T {
        if alpha.is_nan() {
            return T::NAN;
        }
        let a2 = if alpha > T::ZERO {
            iso_a2(cos_t, alpha)
        } else {
            T::ZERO
        };
        lambda_finish(cos_t, a2, lambda_radicand(cos_t, a2).sqrt())
    }
    #[inline]
    fn g1_cos(cos_t: T, alpha: T) -> T {
        if cos_t.is_nan() || alpha.is_nan() {
            return T::NAN;
        }
        if !(alpha > T::ZERO) {
            return if cos_t >= min_cos() { T::ONE } else { T::ZERO };
        }
        Self::clamped(alpha, alpha).g1(from_cos(cos_t))
    }
}

/// a² = α²(1 − c)(1 + c) of an isotropic width α at polar cosine c (clamped to ≤ 1).
#[inline]
pub(crate) fn iso_a2<T: Real>(c: T, alpha: T) -> T {
    let c = if c > T::ONE { T::ONE } else { c };
    let a = clamp_alpha(alpha);
    a * a * ((T::ONE - c) * (T::ONE + c)).max(T::ZERO)
}

/// w_z² + a²: the radicand of Λ (and of V).
#[inline]
pub(crate) fn lambda_radicand<T: Real>(c: T, a2: T) -> T {
    c * c + a2
}

/// Λ from its square root `root` = √(w_z² + a²): a²/(2 w_z (w_z + root)); ∞ below
/// [`min_cos`], NaN for NaN.
#[inline]
pub(crate) fn lambda_finish<T: Real>(c: T, a2: T, root: T) -> T {
    if c.is_nan() || a2.is_nan() {
        T::NAN
    } else if !(c >= min_cos()) {
        T::INFINITY
    } else if !(a2 > T::ZERO) {
        T::ZERO
    } else {
        a2 / (T::TWO * c * (c + root))
    }
}

/// V = ½/(cos θo R_i + cos θi R_o) from the two roots; `nan_probe` is any sum of the
/// inputs' a² (NaN in, NaN out). 0 when either cosine is below [`min_cos`].
#[inline]
pub(crate) fn v_finish<T: Real>(ci: T, co: T, r_i: T, r_o: T, nan_probe: T) -> T {
    if ci.is_nan() || co.is_nan() || nan_probe.is_nan() {
        return T::NAN;
    }
    if !(ci >= min_cos()) || !(co >= min_cos()) {
        return T::ZERO;
    }
    T::HALF / (co * r_i + ci * r_o)
}

impl<T: Real> Distribution<T> for TrowbridgeReitz<T> {
    fn d(&self, h: Vec3<T>) -> T {
        if let Some(v) = self.d_guard(h.z) {
            return v;
        }
        let s = stretched(self.ax, self.ay, h) + h.z * h.z;
        // 1/(π αx αy) ≤ 1/(π ε⁴) is finite; dividing by s twice never overflows s².
        T::ONE / (T::PI * self.ax * self.ay) / s / s
    }
    fn alpha(&self) -> (T, T) {
        (self.ax, self.ay)
    }
    fn lambda(&self, w: Vec3<T>) -> T {
        let a2 = projected(self.ax, self.ay, w);
        lambda_finish(w.z, a2, lambda_radicand(w.z, a2).sqrt())
    }
    fn g1(&self, w: Vec3<T>) -> T {
        let a2 = projected(self.ax, self.ay, w);
        if w.z.is_nan() || a2.is_nan() {
            return T::NAN;
        }
        if !(w.z >= min_cos()) {
            return T::ZERO;
        }
        let c = w.z.min(T::ONE);
        T::TWO * c / (c + lambda_radicand(c, a2).sqrt())
    }
    fn sample_normal(&self, u: [T; 2]) -> Vec3<T> {
        let u0 = crate::sampling::unit(u[0]);
        let (c, s) = super::azimuth(u[1]);
        let r = u0.sqrt();
        Vec3::new(self.ax * r * c, self.ay * r * s, (T::ONE - u0).sqrt())
            .normalize()
            .unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ONE))
    }
    fn sample_visible_normal(&self, wo: Vec3<T>, u: [T; 2]) -> Option<Vec3<T>> {
        if !(wo.x.is_finite() && wo.y.is_finite() && wo.z >= min_cos()) {
            return None;
        }
        // The view direction in the stretched (α = 1) configuration.
        let v = Vec3::new(self.ax * wo.x, self.ay * wo.y, wo.z).normalize()?;
        let l2 = v.x * v.x + v.y * v.y;
        let t1 = if l2 > T::ZERO {
            Vec3::new(-v.y, v.x, T::ZERO).scale(T::ONE / l2.sqrt())
        } else {
            Vec3::new(T::ONE, T::ZERO, T::ZERO)
        };
        let t2 = v.cross(t1);
        // A uniform point on the unit disc, its second coordinate compressed onto the part
        // of the disc that is the projection of the visible half of the hemisphere.
        let r = crate::sampling::unit(u[0]).sqrt();
        let (c, s) = super::azimuth(u[1]);
        let p1 = r * c;
        let sv = T::HALF * (T::ONE + v.z);
        let p2 = (T::ONE - sv) * (T::ONE - p1 * p1).max(T::ZERO).sqrt() + sv * (r * s);
        let pz = (T::ONE - p1 * p1 - p2 * p2).max(T::ZERO).sqrt();
        let nh = t1.scale(p1).add(t2.scale(p2)).add(v.scale(pz));
        // Back to the rough configuration.
        Vec3::new(self.ax * nh.x, self.ay * nh.y, nh.z.max(T::ZERO)).normalize()
    }
}

//! Visible normals as points of a spherical cap: the coordinates in which the converged
//! integrators ([`crate::split_sum::converged`]) integrate a lobe.
//!
//! A [`VisibleNormalMap`] sends a point c = (sin θ cos φ, sin θ sin φ, cos θ) of the unit
//! sphere, θ ∈ [0, θ_max], to a microfacet normal h(c), such that c uniform on the cap
//! (area 2π(1 − cos θ_max)) gives h distributed by the map's density p(h). Then for any f
//!
//! ```text
//! ∫ f(h) dω_h = ∫_cap (f/p)(h(c)) dA(c) / (2π(1 − cos θ_max)),   dA = sin θ dθ dφ,
//! ```
//!
//! and for an f symmetric in φ ↦ −φ (the view in the x–z plane) the φ range halves to
//! [0, π] with [`VisibleNormalMap::measure`] = 1/(π(1 − cos θ_max)).
//!
//! [`GgxVisibleCap`] is the GGX map of Dupuy & Benyoub (2023, "Sampling visible GGX normals
//! with spherical caps", HPG 2023): in the configuration stretched to α = 1 the view is
//! V = normalise(α sin θv, 0, μ); a point c uniform on the cap c_z ≥ −V_z, pushed by H = c + V
//! and unstretched, h = normalise(α H_x, α H_y, H_z), is distributed as the visible normals
//! of Heitz (2018, "Sampling the GGX distribution of visible normals", JCGT 7(4), the
//! density D_ωi of its §2)
//! p(h) = G1(v) max(v·h, 0) D(h)/μ. The cap edge is θ_max = π − atan2(V_x, V_z). Unlike the
//! disc of Heitz (2018) (whose lift p_z = √(1 − r²) has a square root at the rim), a smooth
//! f/p stays smooth in (θ, φ) up to the rim: this is why the integrators use the cap.

use crate::geometry::Vec3;
use crate::Real;

/// A map from a spherical cap θ ∈ [0, θ_max] to microfacet normals (module docs).
pub trait VisibleNormalMap<T: Real> {
    /// The polar angle θ_max of the cap edge.
    fn theta_max(&self) -> T;
    /// 1/(π(1 − cos θ_max)): turns ∫₀^π ∫₀^θmax g sin θ dθ dφ into ∫ f dω_h for g = f/p
    /// even in φ (module docs).
    fn measure(&self) -> T;
    /// The normal h(c) at the cap point (cos θ, sin θ) × (cos φ, sin φ); `None` where the
    /// map is singular (a set of measure zero).
    fn normal(&self, ct: T, st: T, cp: T, sp: T) -> Option<Vec3<T>>;
}

/// The GGX spherical-cap map for an isotropic width α and the view v = (sin θv, 0, μ)
/// (module docs; Dupuy & Benyoub 2023, Heitz 2018).
#[derive(Clone, Copy, Debug)]
pub struct GgxVisibleCap<T> {
    alpha: T,
    /// The stretched view V = (vx, 0, vz).
    vx: T,
    vz: T,
    theta_max: T,
    measure: T,
}

impl<T: Real> GgxVisibleCap<T> {
    /// The map for width α > 0 and view cosine μ ∈ (0, 1] (sin θv = √((1 − μ)(1 + μ))).
    pub fn new(alpha: T, mu: T) -> Self {
        let sv = ((T::ONE - mu) * (T::ONE + mu)).max(T::ZERO).sqrt();
        let (x, z) = (alpha * sv, mu);
        let len = (x * x + z * z).sqrt();
        let (vx, vz) = (x / len, z / len);
        Self {
            alpha,
            vx,
            vz,
            theta_max: T::PI - x.atan2(z),
            measure: T::ONE / (T::PI * (T::ONE + vz)),
        }
    }
    /// The width α.
    pub fn alpha(&self) -> T {
        self.alpha
    }
}

impl<T: Real> VisibleNormalMap<T> for GgxVisibleCap<T> {
    #[inline]
    fn theta_max(&self) -> T {
        self.theta_max
    }
    #[inline]
    fn measure(&self) -> T {
        self.measure
    }
    /// h = normalise(α(c_x + V_x), α c_y, c_z + V_z) (Dupuy & Benyoub 2023).
    #[inline]
    fn normal(&self, ct: T, st: T, cp: T, sp: T) -> Option<Vec3<T>> {
        let hx = self.alpha * (st * cp + self.vx);
        let hy = self.alpha * (st * sp);
        let hz = ct + self.vz;
        Vec3::new(hx, hy, hz.max(T::ZERO)).normalize()
    }
}

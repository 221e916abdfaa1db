//! Fresnel reflectance. Every function takes cos of the angle between the direction and the
//! (micro)normal; for microfacet BRDFs that is wi·h = cos β (paper eq 3, docs/conventions.md §5).

use crate::error::{check_range, ParamError};
use crate::Real;

/// Schlick's approximation (FCG eq 24.6 / §24.1): F = R0 + (1 − R0)(1 − cos θ)^5.
/// `cos_t` is clamped to [0, 1].
#[inline]
pub fn f_schlick<T: Real>(r0: T, cos_t: T) -> T {
    let m = T::ONE - cos_t.clamp(T::ZERO, T::ONE);
    r0 + (T::ONE - r0) * m.powi(5)
}

/// Schlick with an explicit grazing value: F = F0 + (F90 − F0)(1 − cos θ)^5.
#[inline]
pub fn f_schlick_f90<T: Real>(f0: T, f90: T, cos_t: T) -> T {
    let m = T::ONE - cos_t.clamp(T::ZERO, T::ONE);
    f0 + (f90 - f0) * m.powi(5)
}

/// Normal-incidence reflectance from the relative index of refraction (FCG §24.1):
/// R0 = ((η − 1)/(η + 1))².
#[inline]
pub fn r0_from_ior<T: Real>(eta: T) -> T {
    ((eta - T::ONE) / (eta + T::ONE)).sq()
}

/// Exact unpolarised reflectance of a smooth dielectric interface with relative index η
/// (transmitted over incident medium), the mean of the s and p Fresnel equations. Total
/// internal reflection (η < 1 past the critical angle) gives 1. `cos_t` clamped to [0, 1].
pub fn f_dielectric<T: Real>(eta: T, cos_t: T) -> T {
    let ci = cos_t.clamp(T::ZERO, T::ONE);
    let sin2_t = (T::ONE - ci * ci) / (eta * eta);
    if sin2_t >= T::ONE {
        return T::ONE;
    }
    let ct = (T::ONE - sin2_t).sqrt();
    let rs = (ci - eta * ct) / (ci + eta * ct);
    let rp = (eta * ci - ct) / (eta * ci + ct);
    ((rs * rs + rp * rp) * T::HALF).clamp(T::ZERO, T::ONE)
}

/// A Fresnel term chosen at run time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fresnel<T> {
    /// F = 1 (no Fresnel weighting).
    One,
    /// Schlick from normal reflectance R0 ∈ [0, 1].
    Schlick {
        /// Reflectance at normal incidence.
        r0: T,
    },
    /// Exact unpolarised dielectric with relative index η > 0.
    Dielectric {
        /// Relative index of refraction.
        eta: T,
    },
}

impl<T: Real> Fresnel<T> {
    /// Checked Schlick from R0 ∈ [0, 1].
    pub fn schlick(r0: T) -> Result<Self, ParamError> {
        Ok(Fresnel::Schlick {
            r0: check_range("r0", r0, T::ZERO, false, T::ONE, "[0, 1]")?,
        })
    }
    /// Checked Schlick with R0 from the index η > 0.
    pub fn schlick_ior(eta: T) -> Result<Self, ParamError> {
        let eta = check_range("eta", eta, T::ZERO, true, T::INFINITY, "(0, ∞)")?;
        Ok(Fresnel::Schlick {
            r0: r0_from_ior(eta),
        })
    }
    /// Checked exact dielectric with η > 0.
    pub fn dielectric(eta: T) -> Result<Self, ParamError> {
        let eta = check_range("eta", eta, T::ZERO, true, T::INFINITY, "(0, ∞)")?;
        Ok(Fresnel::Dielectric { eta })
    }
    /// Evaluates at cos θ (clamped to [0, 1]).
    #[inline]
    pub fn eval(&self, cos_t: T) -> T {
        match *self {
            Fresnel::One => T::ONE,
            Fresnel::Schlick { r0 } => f_schlick(r0, cos_t),
            Fresnel::Dielectric { eta } => f_dielectric(eta, cos_t),
        }
    }
}

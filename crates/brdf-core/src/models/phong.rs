//! Energy-normalised Phong and Blinn-Phong lobes as BRDFs (the highlights of the standard
//! lighting model notes with a Lambertian term and a normalisation constant).
//!
//! * Phong: f = k_d/π + k_s (n+2)/(2π) max(wo·r_i, 0)^n, r_i = 2(n·wi)n − wi. The constant
//!   makes the lobe's albedo exactly 1 at normal incidence: 2π ∫₀¹ (n+2)/(2π) c^{n+1} dc = 1.
//! * Blinn-Phong: f = k_d/π + k_s C(n) (n·h)^n with C(n) = (n+2)(n+4)/(8π(n + 2^{−n/2})),
//!   derived here so that the lobe's albedo is exactly 1 at normal incidence: with
//!   dωi = 4(wo·h)dωh and cos θi = 2c² − 1 (c = cos θh ∈ [1/√2, 1] for wi above the
//!   horizon at normal incidence), 8πC ∫_{1/√2}^1 c^{n+1}(2c² − 1) dc = 8πC (n + 2^{−n/2})/((n+2)(n+4)) = 1.
//!   (The popular (n+8)/(8π) exceeds 1 for n > 4, e.g. 1.018 at n = 100.) n = 0 gives 1/π.
//!
//! Both are reciprocal; with k_d + k_s ≤ 1 per channel they are flagged energy conserving
//! (normal incidence is the albedo maximum; the suite checks every angle).
//! Sampling: a lobe chosen with probability mean(k_s)/(mean(k_s) + mean(k_d)), else the
//! cosine-weighted hemisphere. Phong samples the lobe (n+1)/(2π)(wi·r_o)^n about the mirror
//! direction r_o of wo; Blinn-Phong samples h with (n+1)/(2π)(n·h)^n (FCG eq 24.10 with
//! nu = nv = n) and converts with eq 24.12. Lobe samples below the horizon get weight 0.

use super::rgb::check_rgb;
use super::{
    above_or_zero, finish, half_vector, lobe_prob, mirror, pick, u_ok, valid_wo, Brdf, BrdfFlags,
    BrdfSample, LobeHint, Rgb,
};
use crate::error::check_range;
use crate::geometry::Vec3;
use crate::sampling::{
    cosine_hemisphere_pdf, cosine_lobe_pdf, sample_cosine_hemisphere, sample_cosine_lobe,
};
use crate::{ParamError, Real};

const MAX_EXP: f64 = 1e6;

fn check_common<T: Real>(kd: Rgb<T>, ks: Rgb<T>, n: T) -> Result<(Rgb<T>, Rgb<T>, T), ParamError> {
    Ok((
        check_rgb("kd", kd, T::ZERO, T::ONE, "[0, 1]")?,
        check_rgb("ks", ks, T::ZERO, T::ONE, "[0, 1]")?,
        check_range("n", n, T::ZERO, false, T::from_f64(MAX_EXP), "[0, 1e6]")?,
    ))
}

/// Both models' flags: reciprocal, energy conserving when k_d + k_s ≤ 1 per channel.
fn kd_ks_flags<T: Real>(kd: Rgb<T>, ks: Rgb<T>) -> BrdfFlags {
    BrdfFlags::new(true, kd.add(ks).max_channel() <= T::ONE, false)
}

/// f = k_d/π + k_s · `lobe()` for wi and wo above the horizon, else 0.
#[inline]
fn kd_plus_lobe<T: Real>(
    kd: Rgb<T>,
    ks: Rgb<T>,
    wi: Vec3<T>,
    wo: Vec3<T>,
    lobe: impl FnOnce() -> T,
) -> Rgb<T> {
    above_or_zero(wi, wo, || kd.scale(T::ONE / T::PI).add(ks.scale(lobe())))
}

/// Energy-normalised Phong BRDF (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhongNormalized<T> {
    kd: Rgb<T>,
    ks: Rgb<T>,
    n: T,
}

impl<T: Real> PhongNormalized<T> {
    /// Checked constructor: k_d, k_s ∈ [0, 1] per channel, exponent n ∈ [0, 1e6].
    pub fn new(kd: Rgb<T>, ks: Rgb<T>, n: T) -> Result<Self, ParamError> {
        let (kd, ks, n) = check_common(kd, ks, n)?;
        Ok(Self { kd, ks, n })
    }
    fn p_lobe(&self) -> T {
        lobe_prob(self.ks.mean(), self.kd.mean())
    }
}

impl<T: Real> Brdf<T> for PhongNormalized<T> {
    fn flags(&self) -> BrdfFlags {
        kd_ks_flags(self.kd, self.ks)
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        kd_plus_lobe(self.kd, self.ks, wi, wo, || {
            let c = wo.dot(mirror(wi)).min(T::ONE);
            if c > T::ZERO {
                (self.n + T::TWO) / (T::TWO * T::PI) * c.powf(self.n)
            } else {
                T::ZERO
            }
        })
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        if !valid_wo(wo) {
            return T::ZERO;
        }
        let p = self.p_lobe();
        p * cosine_lobe_pdf(mirror(wo), self.n, wi) + (T::ONE - p) * cosine_hemisphere_pdf(wi)
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        if !valid_wo(wo) || !u_ok(u) {
            return None;
        }
        let (lobe, u0) = pick(u[0], self.p_lobe());
        let wi = if lobe {
            sample_cosine_lobe(mirror(wo), self.n, [u0, u[1]])?
        } else {
            sample_cosine_hemisphere([u0, u[1]])
        };
        finish(self, wo, wi)
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(T::ONE / (T::TWO * self.n + T::TWO).sqrt())
    }
}

/// Energy-normalised Blinn-Phong BRDF (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlinnPhongNormalized<T> {
    kd: Rgb<T>,
    ks: Rgb<T>,
    n: T,
    c: T,
}

impl<T: Real> BlinnPhongNormalized<T> {
    /// Checked constructor: k_d, k_s ∈ [0, 1] per channel, exponent n ∈ [0, 1e6].
    pub fn new(kd: Rgb<T>, ks: Rgb<T>, n: T) -> Result<Self, ParamError> {
        let (kd, ks, n) = check_common(kd, ks, n)?;
        Ok(Self {
            kd,
            ks,
            n,
            c: Self::normalisation(n),
        })
    }
    /// C(n) = (n+2)(n+4)/(8π(n + 2^{−n/2})).
    pub fn normalisation(n: T) -> T {
        let four = T::from_f64(4.0);
        (n + T::TWO) * (n + four) / (T::from_f64(8.0) * T::PI * (n + T::TWO.powf(-n * T::HALF)))
    }
    fn p_lobe(&self) -> T {
        lobe_prob(self.ks.mean(), self.kd.mean())
    }
}

impl<T: Real> Brdf<T> for BlinnPhongNormalized<T> {
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        kd_plus_lobe(self.kd, self.ks, wi, wo, || match half_vector(wi, wo) {
            Some(h) if h.z > T::ZERO => self.c * h.z.min(T::ONE).powf(self.n),
            _ => T::ZERO,
        })
    }
    fn flags(&self) -> BrdfFlags {
        kd_ks_flags(self.kd, self.ks)
    }
    ashikhmin_shirley_sampling!(n, n);
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso((T::TWO / (self.n + T::TWO)).sqrt())
    }
}

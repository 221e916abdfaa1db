//! The microfacet family: one module per normal distribution, each holding D, Smith's Λ,
//! G1, the separable and the height-correlated G, sampling of the distribution of normals
//! (D(h) cos θh) and of the visible normals (G1(wo) max(wo·h, 0) D(h)/cos θo) with their
//! pdfs, all anisotropic.
//!
//! * [`Beckmann`]: D(h) = exp(−((h_x/αx)² + (h_y/αy)²)/h_z²)/(π αx αy h_z⁴).
//! * [`TrowbridgeReitz`] (GGX): D(h) = 1/(π αx αy ((h_x/αx)² + (h_y/αy)² + h_z²)²).
//! * [`Charlie`] (sheen, Estevez–Kulla): D(h) = (2 + 1/α) sin^{1/α}θh/(2π), isotropic, with
//!   its fitted Λ and Ashikhmin's visibility; it has no visible-normal sampler and so does
//!   not implement [`Distribution`] (module [`charlie`]).
//!
//! **Roughness convention (the one used everywhere in the crate).** Every distribution takes
//! the slope widths α = (αx, αy) along the local x and y axes (unitless, slopes = tan θh).
//! For Beckmann α is the RMS slope times √2, so the paper's RMS slope σ of the Gaussian
//! surface is σ = α/√2 (the Cook–Torrance "m" is this α). Isotropic surfaces have
//! αx = αy = α.
//!
//! Directions are unit vectors in the local frame (z = normal), pointing away from the
//! surface. A direction w with w_z below [`crate::geometry::min_cos`] is at or below the
//! horizon: G1(w) = 0, Λ(w) = ∞. Smith's Λ of a direction depends on the width projected on
//! its azimuth, through a² = (αx w_x)² + (αy w_y)² (the stretch of slope space).
//!
//! Parameter ranges: the checked constructors accept α ∈ [[`ALPHA_MIN`], [`ALPHA_MAX`]]
//! (per axis). [`Beckmann::clamped`] / [`TrowbridgeReitz::clamped`] (and the dot-product
//! forms of [`Isotropic`] built on them) accept any α and clamp it into [ε², 1/ε²] (ε the
//! type's machine epsilon: 1.4e-14 … 7.0e13 in `f32`, 4.9e-32 … 2.0e31 in `f64`), where
//! every quantity is finite; α → 0 and α → ∞ are limits the type cannot represent (D tends
//! to a Dirac delta, or G1 to 0).

/// Defines an anisotropic distribution with widths (αx, αy) and its constructors: checked
/// (αx, αy ∈ [1e-4, 1e4], [`ALPHA_MIN`], [`ALPHA_MAX`]), isotropic, and clamped; with
/// D's guards, and the isotropic D in the dot products its [`Isotropic`] impl returns.
macro_rules! widths_distribution {
    ($(#[$m:meta])* $name:ident) => {
        $(#[$m])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name<T> {
            ax: T,
            ay: T,
        }

        impl<T: Real> $name<T> {
            /// Checked constructor: αx, αy ∈ [1e-4, 1e4] ([`super::ALPHA_MIN`],
            /// [`super::ALPHA_MAX`]).
            pub fn new(ax: T, ay: T) -> Result<Self, crate::ParamError> {
                Ok(Self {
                    ax: super::check_alpha("alpha_x", ax)?,
                    ay: super::check_alpha("alpha_y", ay)?,
                })
            }
            /// Isotropic checked constructor, α ∈ [1e-4, 1e4].
            pub fn isotropic(alpha: T) -> Result<Self, crate::ParamError> {
                Self::new(alpha, alpha)
            }
            /// D's guards: NaN for a NaN h_z or width, 0 at or below the horizon;
            /// `None` where D is to be evaluated.
            #[inline]
            fn d_guard(&self, hz: T) -> Option<T> {
                if hz.is_nan() || self.ax.is_nan() || self.ay.is_nan() {
                    Some(T::NAN)
                } else if !(hz > T::ZERO) {
                    Some(T::ZERO)
                } else {
                    None
                }
            }
            /// Any widths, clamped into [ε², 1/ε²] (module docs of [`super`]); NaN stays NaN.
            pub fn clamped(ax: T, ay: T) -> Self {
                Self {
                    ax: super::clamp_alpha(ax),
                    ay: super::clamp_alpha(ay),
                }
            }
            /// [`super::Isotropic::d_cos`]: NaN for a NaN cosine or width, 0 for n·h ≤ 0
            /// or α ≤ 0, else D of the clamped isotropic distribution at
            /// [`super::from_cos`]`(cos_h)`.
            #[inline]
            fn d_iso(cos_h: T, alpha: T) -> T {
                if cos_h.is_nan() || alpha.is_nan() {
                    return T::NAN;
                }
                if !(cos_h > T::ZERO) || !(alpha > T::ZERO) {
                    return T::ZERO;
                }
                super::Distribution::d(&Self::clamped(alpha, alpha), super::from_cos(cos_h))
            }
        }
    };
}

pub mod beckmann;
pub mod beckmann_visible;
pub mod charlie;
pub mod ggx;
pub mod visible_cap;

pub use beckmann::Beckmann;
pub use charlie::Charlie;
pub use ggx::TrowbridgeReitz;

use crate::geometry::{min_cos, Vec3};
use crate::Real;

/// Smallest slope width the checked constructors accept.
pub const ALPHA_MIN: f64 = 1e-4;
/// Largest slope width the checked constructors accept.
pub const ALPHA_MAX: f64 = 1e4;

/// 1/√π.
pub(crate) const FRAC_1_SQRT_PI: f64 = 0.564_189_583_547_756_3;

/// A microfacet normal distribution with Smith masking.
pub trait Distribution<T: Real>: Copy + core::fmt::Debug {
    /// The widths (αx, αy).
    fn alpha(&self) -> (T, T);
    /// D(h) in 1/sr for unit h; 0 for h_z ≤ 0.
    fn d(&self, h: Vec3<T>) -> T;
    /// Smith's Λ(w); ∞ at or below the horizon.
    fn lambda(&self, w: Vec3<T>) -> T;
    /// Samples h with density D(h) cos θh from u ∈ [0, 1)² (clamped into that range).
    fn sample_normal(&self, u: [T; 2]) -> Vec3<T>;
    /// Samples a visible normal for `wo`; `None` when wo is at or below the horizon or
    /// not finite.
    fn sample_visible_normal(&self, wo: Vec3<T>, u: [T; 2]) -> Option<Vec3<T>>;

    /// G1(w) = 1/(1 + Λ(w)).
    #[inline]
    fn g1(&self, w: Vec3<T>) -> T {
        T::ONE / (T::ONE + self.lambda(w))
    }
    /// Separable G = G1(wi) G1(wo).
    #[inline]
    fn g_separable(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        self.g1(wi) * self.g1(wo)
    }
    /// Height-correlated G = 1/(1 + Λ(wi) + Λ(wo)).
    #[inline]
    fn g_correlated(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        T::ONE / (T::ONE + self.lambda(wi) + self.lambda(wo))
    }
    /// D(h) max(cos θh, 0): the density of [`Distribution::sample_normal`] per unit solid
    /// angle of h.
    #[inline]
    fn normal_pdf(&self, h: Vec3<T>) -> T {
        self.d(h) * h.z.max(T::ZERO)
    }
    /// G1(wo) max(wo·h, 0) D(h)/cos θo: the density of
    /// [`Distribution::sample_visible_normal`] per unit solid angle of h (0 for wo at or
    /// below the horizon).
    fn visible_normal_pdf(&self, wo: Vec3<T>, h: Vec3<T>) -> T {
        if wo.z.is_nan() {
            return T::NAN;
        }
        if !(wo.z >= min_cos()) {
            return T::ZERO;
        }
        let oh = wo.dot(h);
        if !(oh > T::ZERO) {
            return if oh.is_nan() { T::NAN } else { T::ZERO };
        }
        let d = self.d(h);
        if d == T::ZERO {
            return T::ZERO;
        }
        self.g1(wo) * (oh / wo.z) * d
    }
}

/// The isotropic forms in the dot products a shader has: n·h, n·w and one width α (for
/// Beckmann α = m = √2σ). They accept any α: NaN in, NaN out; α ≤ 0 is the smooth limit
/// (D = 0, Λ = 0, G1 = 1 above the horizon); any other α is clamped into [ε², 1/ε²] as by
/// `clamped`. A cosine below [`crate::geometry::min_cos`] is at or below the horizon
/// (Λ = ∞, G1 = 0, G = 0).
///
/// Call as `TrowbridgeReitz::g_correlated_cos(n_l, n_v, alpha)` (the trait in scope).
pub trait Isotropic<T: Real>: Distribution<T> {
    /// D(h) in 1/sr at n·h = `cos_h` (the isotropic D of the type's module docs); 0 for
    /// n·h ≤ 0 and for α ≤ 0.
    fn d_cos(cos_h: T, alpha: T) -> T;
    /// Smith's Λ at polar cosine `cos_t`.
    fn lambda_cos(cos_t: T, alpha: T) -> T;
    /// The radial CDF of the normals' density D(h) cos θh in t = tan²θh:
    /// ξ = P(tan²θh < t) (the CDF [`Distribution::sample_normal`] inverts); 1 when it is a
    /// step at θh = 0 (α ≤ 0).
    fn normal_cdf_tan2(t2: T, alpha: T) -> T;
    /// The inverse of [`Isotropic::normal_cdf_tan2`]: tan²θh at ξ ∈ [0, 1] (∞ at ξ = 1).
    fn normal_tan2_at_cdf(xi: T, alpha: T) -> T;
    /// One-sided Smith masking G1 = 1/(1 + Λ).
    #[inline]
    fn g1_cos(cos_t: T, alpha: T) -> T {
        T::ONE / (T::ONE + Self::lambda_cos(cos_t, alpha))
    }
    /// Separable Smith G = G1(θi) G1(θo).
    #[inline]
    fn g_separable_cos(cos_i: T, cos_o: T, alpha: T) -> T {
        Self::g1_cos(cos_i, alpha) * Self::g1_cos(cos_o, alpha)
    }
    /// Height-correlated Smith G = 1/(1 + Λ(θi) + Λ(θo)).
    #[inline]
    fn g_correlated_cos(cos_i: T, cos_o: T, alpha: T) -> T {
        T::ONE / (T::ONE + Self::lambda_cos(cos_i, alpha) + Self::lambda_cos(cos_o, alpha))
    }
}

/// Clamps a width into [ε², 1/ε²] (module docs); NaN stays NaN.
#[inline]
pub(crate) fn clamp_alpha<T: Real>(a: T) -> T {
    let e2 = T::EPSILON * T::EPSILON;
    a.clamp(e2, T::ONE / e2)
}

/// Checks a width against [`ALPHA_MIN`, `ALPHA_MAX`].
pub(crate) fn check_alpha<T: Real>(name: &'static str, a: T) -> Result<T, crate::ParamError> {
    crate::error::check_range(
        name,
        a,
        T::from_f64(ALPHA_MIN),
        false,
        T::from_f64(ALPHA_MAX),
        "[1e-4, 1e4]",
    )
}

/// The squared projected width times sin²θ of a direction: a² = (αx w_x)² + (αy w_y)².
#[inline]
pub(crate) fn projected<T: Real>(ax: T, ay: T, w: Vec3<T>) -> T {
    (ax * w.x).sq() + (ay * w.y).sq()
}

/// The stretched squared slope of h times cos²θh: q = (h_x/αx)² + (h_y/αy)², so that the
/// squared stretched slope is q/h_z².
#[inline]
pub(crate) fn stretched<T: Real>(ax: T, ay: T, h: Vec3<T>) -> T {
    (h.x / ax).sq() + (h.y / ay).sq()
}

/// A unit direction at polar cosine `c` in the x–z plane, (√((1 − c)(1 + c)), 0, c): the
/// isotropic stand-in used by the dot-product functions ((1 − c)(1 + c) has no cancellation
/// near c = 1, unlike 1 − c²), and by the front ends (C ABI, WASM) that take cosines. c is
/// clamped to ≤ 1; NaN in, NaN out.
#[inline]
pub fn from_cos<T: Real>(c: T) -> Vec3<T> {
    // Not `min`, which would turn NaN into 1: NaN in, NaN out.
    let c = if c > T::ONE { T::ONE } else { c };
    Vec3::new(
        ((T::ONE - c) * (T::ONE + c)).max(T::ZERO).sqrt(),
        T::ZERO,
        c,
    )
}

/// A uniform azimuth 2πu and its (cos, sin), u clamped into [0, 1).
#[inline]
pub(crate) fn azimuth<T: Real>(u: T) -> (T, T) {
    let phi = T::TWO * T::PI * crate::sampling::unit(u);
    (phi.cos(), phi.sin())
}

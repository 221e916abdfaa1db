//! The scalar type every kernel is generic over.
//!
//! Each kernel is written once, as a generic function over [`Real`], and instantiated for
//! `f32` (devices, shaders) and `f64` (table generation, references). Both use `libm`,
//! except for the f32 functions this module implements itself in f32 arithmetic
//! ([`sin_cos_f32`], [`exp_f32`], [`erfc_f32`]) and the f64 functions of the modified G's
//! inner loops ([`exp_bounded_f64`], [`exp_neg_f64`], [`erfc_bounded_f64`],
//! [`erfcx_bounded_f64`], and [`sin_cos_f64`] for |x| ≤ 1.6), written branch-free so that
//! two evaluations share one SIMD register (all within a few ulp of libm, [`exp_neg_f64`]
//! within (2 + z)·ε); the f64 pair functions [`Real::exp_neg2`], [`Real::erfcx2_bounded`],
//! [`Real::sin_cos2`] and, on x86-64, [`Real::sqrt2`] (the `wide` crate's two-lane square
//! root, correctly rounded like libm's) evaluate two arguments at once, in one SSE2
//! register on x86-64 and as two scalars with the same operations elsewhere (the same
//! values on every target). The `micromath` feature adds a third
//! scalar, `Micro` (an `f32` whose transcendental functions come from micromath where
//! that keeps the kernels within 2e-2 of libm); it never changes what `f32` computes, so
//! enabling it in one crate leaves every other crate's f32 results alone.

mod fast64;

pub use fast64::{
    erfc_bounded_f64, erfcx2_bounded_f64, erfcx_bounded_f64, exp_bounded_f64, exp_neg2_f64,
    exp_neg_f64, sin_cos2_f64, sin_cos_f64,
};

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A floating-point scalar with the transcendental functions the kernels need.
pub trait Real:
    Copy
    + Debug
    + Default
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + 'static
{
    /// π.
    const PI: Self;
    /// π/2.
    const FRAC_PI_2: Self;
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 1/2.
    const HALF: Self;
    /// Machine epsilon.
    const EPSILON: Self;
    /// +∞.
    const INFINITY: Self;
    /// Quiet NaN.
    const NAN: Self;

    /// Rounds an `f64` constant to this type.
    fn from_f64(x: f64) -> Self;
    /// Widens to `f64` (exact).
    fn to_f64(self) -> f64;

    /// |x|.
    fn abs(self) -> Self;
    /// √x (NaN for x < 0).
    fn sqrt(self) -> Self;
    /// [√x₀, √x₁], lane by lane the same values as [`Real::sqrt`] (`f64` on x86-64: both in
    /// one SSE2 `sqrtpd`, correctly rounded like `sqrtsd`).
    #[inline]
    fn sqrt2(x: [Self; 2]) -> [Self; 2] {
        [x[0].sqrt(), x[1].sqrt()]
    }
    /// eˣ.
    fn exp(self) -> Self;
    /// eˣ for x ∈ [−87, 0] (the range of e^{−v²} in the kernels' integrands), without the
    /// range checks of [`Real::exp`]; x below −87 is taken as −87 (result < 1.7e-38), x
    /// above 0 is not allowed (unspecified but finite below 88). (`f64`:
    /// [`exp_bounded_f64`]; `f32`: [`exp_f32`]'s kernel.)
    #[inline]
    fn exp_bounded(self) -> Self {
        self.exp()
    }
    /// [e^{−z₀}, e^{−z₁}] for z ∈ [0, 87] (the Gaussian factors e^{−v²} of the kernels'
    /// integrands, given z = v²; results outside that range unspecified but never a panic).
    /// (`f64`: [`exp_neg2_f64`], within (2 + z)·ε of libm, the two lanes side by side;
    /// otherwise [`Real::exp_bounded`] per lane.)
    #[inline]
    fn exp_neg2(z: [Self; 2]) -> [Self; 2] {
        [(-z[0]).exp_bounded(), (-z[1]).exp_bounded()]
    }
    /// Natural logarithm ln x (NaN for x < 0, −∞ at 0).
    fn ln(self) -> Self;
    /// sin x (x in radians).
    fn sin(self) -> Self;
    /// cos x (x in radians).
    fn cos(self) -> Self;
    /// (sin, cos) of the same argument, sharing the argument reduction (`f64`:
    /// [`sin_cos_f64`]; `f32`: [`sin_cos_f32`]).
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    /// [`Real::sin_cos`] of two arguments: ([sin x₀, sin x₁], [cos x₀, cos x₁]), lane by
    /// lane the same values (`f64` on x86-64: [`sin_cos2_f64`], the two side by side).
    #[inline]
    fn sin_cos2(x: [Self; 2]) -> ([Self; 2], [Self; 2]) {
        let (s0, c0) = x[0].sin_cos();
        let (s1, c1) = x[1].sin_cos();
        ([s0, s1], [c0, c1])
    }
    /// tan x (x in radians).
    fn tan(self) -> Self;
    /// arcsin x in [−π/2, π/2] (NaN outside [−1, 1]).
    fn asin(self) -> Self;
    /// arccos x in [0, π] (NaN outside [−1, 1]).
    fn acos(self) -> Self;
    /// arctan x in (−π/2, π/2).
    fn atan(self) -> Self;
    /// The angle of the point (x, self) in (−π, π], with `self` as the y coordinate.
    fn atan2(self, x: Self) -> Self;
    /// self raised to the real power `e`.
    fn powf(self, e: Self) -> Self;
    /// The largest integer not greater than x.
    fn floor(self) -> Self;
    /// The error function, always from `libm`.
    fn erf(self) -> Self;
    /// The complementary error function 1 − erf (`f64`: libm; `f32`: [`erfc_f32`]).
    fn erfc(self) -> Self;
    /// erfc x for x ∈ [0, 4.6] (the working variable's range, up to the cut at 4.5, in the
    /// kernels' Gaussian tail integrals), without range checks (`f64`:
    /// [`erfc_bounded_f64`], which takes x outside as the nearer end; otherwise
    /// [`Real::erfc`] itself).
    #[inline]
    fn erfc_bounded(self) -> Self {
        self.erfc()
    }
    /// The scaled complementary error function e^{x²} erfc x for x ∈ [0, 4.6] (results
    /// outside unspecified but never a panic) (`f64`: [`erfcx_bounded_f64`]; otherwise
    /// e^{x²} times [`Real::erfc`]).
    #[inline]
    fn erfcx_bounded(self) -> Self {
        (self * self).exp() * self.erfc()
    }
    /// [`Real::erfcx_bounded`] of two arguments, lane by lane the same values (`f64`:
    /// [`erfcx2_bounded_f64`], the two side by side).
    #[inline]
    fn erfcx2_bounded(x: [Self; 2]) -> [Self; 2] {
        [x[0].erfcx_bounded(), x[1].erfcx_bounded()]
    }

    /// `true` for NaN.
    #[inline]
    #[allow(clippy::eq_op)]
    fn is_nan(self) -> bool {
        self != self
    }
    /// `true` unless NaN or ±∞.
    #[inline]
    fn is_finite(self) -> bool {
        !self.is_nan() && self.abs() != Self::INFINITY
    }
    /// The smaller of two values; NaN only if both are NaN.
    #[inline]
    fn min(self, o: Self) -> Self {
        if o < self || self.is_nan() {
            o
        } else {
            self
        }
    }
    /// The larger of two values; NaN only if both are NaN.
    #[inline]
    fn max(self, o: Self) -> Self {
        if o > self || self.is_nan() {
            o
        } else {
            self
        }
    }
    /// Clamps to `[lo, hi]`; NaN stays NaN.
    #[inline]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        if self < lo {
            lo
        } else if self > hi {
            hi
        } else {
            self
        }
    }
    /// x².
    #[inline]
    fn sq(self) -> Self {
        self * self
    }
    /// Integer power by repeated squaring (no `powf`).
    #[inline]
    fn powi(self, mut n: u32) -> Self {
        let mut base = self;
        let mut acc = Self::ONE;
        while n > 0 {
            if n & 1 == 1 {
                acc *= base;
            }
            base *= base;
            n >>= 1;
        }
        acc
    }
}

macro_rules! consts {
    ($t:ty) => {
        const PI: Self = core::f64::consts::PI as $t;
        const FRAC_PI_2: Self = core::f64::consts::FRAC_PI_2 as $t;
        const ZERO: Self = 0.0;
        const ONE: Self = 1.0;
        const TWO: Self = 2.0;
        const HALF: Self = 0.5;
        const EPSILON: Self = <$t>::EPSILON;
        const INFINITY: Self = <$t>::INFINITY;
        const NAN: Self = <$t>::NAN;
        #[inline]
        fn from_f64(x: f64) -> Self {
            x as $t
        }
        #[inline]
        fn to_f64(self) -> f64 {
            self as f64
        }
        #[inline]
        fn abs(self) -> Self {
            if self < 0.0 {
                -self
            } else if self == 0.0 {
                0.0
            } else {
                self
            }
        }
    };
}

/// Inlined [`Real`] functions that call one function of the same signature:
/// `name => path` gives `fn name(self) -> Self { path(self) }`, and after `binary`
/// `fn name(self, b: Self) -> Self { path(self, b) }`; with a leading `Wrapper:` (a newtype
/// over the scalar) the call takes and returns the wrapped scalar.
macro_rules! forward {
    ($($name:ident => $path:path),* $(,)?) => {
        $(
            #[inline]
            fn $name(self) -> Self {
                $path(self)
            }
        )*
    };
    (binary $($name:ident => $path:path),* $(,)?) => {
        $(
            #[inline]
            fn $name(self, b: Self) -> Self {
                $path(self, b)
            }
        )*
    };
    ($w:ident: $($name:ident => $path:path),* $(,)?) => {
        $(
            #[inline]
            fn $name(self) -> Self {
                $w($path(self.0))
            }
        )*
    };
    ($w:ident binary: $($name:ident => $path:path),* $(,)?) => {
        $(
            #[inline]
            fn $name(self, b: Self) -> Self {
                $w($path(self.0, b.0))
            }
        )*
    };
}

impl Real for f64 {
    consts!(f64);
    #[cfg(target_arch = "x86_64")]
    #[inline]
    fn sqrt2(x: [Self; 2]) -> [Self; 2] {
        wide::f64x2::from(x).sqrt().to_array()
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        sin_cos_f64(self)
    }
    // Side by side where SSE2 gives two f64 lanes; elsewhere (soft-f64 devices) the default
    // two calls keep one copy of the code.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    fn sin_cos2(x: [Self; 2]) -> ([Self; 2], [Self; 2]) {
        sin_cos2_f64(x)
    }
    #[inline]
    fn erfcx2_bounded(x: [Self; 2]) -> [Self; 2] {
        erfcx2_bounded_f64(x)
    }
    #[inline]
    fn exp_neg2(z: [Self; 2]) -> [Self; 2] {
        exp_neg2_f64(z)
    }
    forward!(
        sqrt => libm::sqrt, exp => libm::exp, exp_bounded => exp_bounded_f64, ln => libm::log,
        sin => libm::sin, cos => libm::cos, tan => libm::tan, asin => libm::asin,
        acos => libm::acos, atan => libm::atan, floor => libm::floor, erf => libm::erf,
        erfc => libm::erfc, erfc_bounded => erfc_bounded_f64, erfcx_bounded => erfcx_bounded_f64,
    );
    forward!(binary
        atan2 => libm::atan2, powf => libm::pow,
    );
}

/// sin and cos of an `f32`, in f32 arithmetic only.
///
/// libm's `sinf`/`cosf` evaluate their polynomials in f64 and carry a Payne–Hanek reduction
/// for huge arguments: on a Cortex-M4F (single-precision FPU) that links about 4.5 KiB of
/// soft-f64 code. Here: k = round(2x/π); r = x − k·π/2 by a three-part Cody–Waite split
/// (π/2 = P1 + P2 + P3 with 8, 12 and 24 significant bits, so k·P1 and k·P2 are exact for
/// |x| < 6400); then the Taylor series of sin (to r⁹) and cos (to r¹⁰) on |r| ≤ π/4, whose
/// truncation errors (< 3e-9, < 2e-10) are below f32 rounding. Accuracy: within 2 ulp
/// (1.2e-7 absolute) of the exact values for |x| ≤ 6400 (tested against f64 libm); beyond
/// that the reduction is approximate but the result stays in [−1, 1]. NaN and ±∞ give NaN.
/// On bare metal and WASM it is never inlined: every caller (the kernels, the LUT reader's
/// cos-warped axes) then shares one copy (the firmware's 16 KiB flash and the WASM module's
/// 64 KiB budgets).
#[cfg_attr(any(target_os = "none", target_arch = "wasm32"), inline(never))]
#[cfg_attr(not(any(target_os = "none", target_arch = "wasm32")), inline)]
pub fn sin_cos_f32(x: f32) -> (f32, f32) {
    const FRAC_2_PI: f32 = 0.636_619_75;
    const P1: f32 = 1.570_312_5;
    const P2: f32 = 4.838_705_e-4;
    const P3: f32 = -4.371_139e-8;
    const TWO_PI: f32 = 6.283_185_5;
    if !x.is_finite() {
        return (f32::NAN, f32::NAN);
    }
    // Beyond the exact-reduction range, fold into one period first (approximate); where even
    // that fails (|x| ≳ 1e9, whose f32 phase is noise), use 0.
    let x = if x.abs() > 6400.0 {
        x - TWO_PI * libm::floorf(x / TWO_PI)
    } else {
        x
    };
    let x = if x.abs() > 6400.0 { 0.0 } else { x };
    let t = x * FRAC_2_PI;
    let k = if t >= 0.0 {
        (t + 0.5) as i32
    } else {
        (t - 0.5) as i32
    };
    let kf = k as f32;
    let r = ((x - kf * P1) - kf * P2) - kf * P3;
    let r2 = r * r;
    let s = r + r
        * r2
        * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362_880.0))));
    let c = 1.0
        + r2 * (-0.5
            + r2 * (1.0 / 24.0
                + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40_320.0 + r2 * (-1.0 / 3_628_800.0)))));
    match k & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// eˣ for an `f32`, in f32 arithmetic only, without a division or a float-to-int
/// conversion.
///
/// x = k·ln 2 + r with k = round(x/ln 2) (by adding and subtracting 1.5·2²³, which leaves
/// k in the low mantissa bits) and |r| ≤ ln 2/2, r by a two-part Cody–Waite split
/// (ln 2 = L1 + L2, L1 with 16 significant bits so k·L1 is exact for |k| < 2⁸); eʳ by the
/// degree-6 Chebyshev interpolant of eʳ on [−ln 2/2, ln 2/2] (relative error 2.6e-9, below
/// f32 rounding); 2ᵏ by building the exponent bits. Arguments outside [−87, 88] (subnormal
/// or overflowing results, NaN) take a separate path. Accuracy: within 2 ulp of the exact
/// value (tested against f64 libm); overflow gives +∞, x < −104 gives 0, NaN gives NaN.
#[inline]
pub fn exp_f32(x: f32) -> f32 {
    if (-87.0..=88.0).contains(&x) {
        let (p, k) = exp_f32_reduced(x);
        p * f32::from_bits(((k + 127) as u32) << 23)
    } else {
        exp_f32_edge(x)
    }
}

/// eʳ and k with eˣ = eʳ·2ᵏ, for |x| ≤ 126 ln 2.
#[inline(always)]
fn exp_f32_reduced(x: f32) -> (f32, i32) {
    const LOG2_E: f32 = core::f32::consts::LOG2_E;
    const MAGIC: f32 = 12_582_912.0; // 1.5·2²³
    const L1: f32 = 0.693_145_75; // 0x3f317200
    const L2: f32 = 1.428_606_8e-6; // ln 2 − L1
    let t = x * LOG2_E + MAGIC;
    let k = t.to_bits() as i32 - MAGIC.to_bits() as i32;
    let kf = t - MAGIC;
    let r = (x - kf * L1) - kf * L2;
    let p = 1.0
        + r * (1.000_000_04
            + r * (0.5
                + r * (0.166_664_15
                    + r * (0.041_666_35 + r * (0.008_375_126 + r * 0.001_394_110_8)))));
    (p, k)
}

/// [`exp_f32`] outside [−87, 88].
#[cold]
#[inline(never)]
fn exp_f32_edge(x: f32) -> f32 {
    if x.is_nan() {
        x
    } else if x > 88.8 {
        f32::INFINITY
    } else if x > 88.0 {
        // 2ᵏ = 2ᵏ⁻¹·2 (2¹²⁸ is not an f32).
        let (p, k) = exp_f32_reduced(x);
        p * f32::from_bits(((k - 1 + 127) as u32) << 23) * 2.0
    } else if x >= -104.0 {
        // Subnormal result: 2ᵏ = 2ᵏ⁺⁶⁴ · 2⁻⁶⁴.
        let (p, k) = exp_f32_reduced(x);
        p * f32::from_bits(((k + 64 + 127) as u32) << 23) * f32::from_bits((127 - 64) << 23)
    } else {
        0.0
    }
}

/// The complementary error function of an `f32`, in f32 arithmetic only.
///
/// For x ≥ 0, erfc x = e^{−x²} · t · q(t) with t = 1/(1 + x/2) ∈ (0, 1]: the scaled
/// function e^{x²} erfc x times 1 + x/2 is smooth in t on the whole half-line (it tends to
/// 1/(2√π) as x → ∞), and q is its degree-10 Chebyshev interpolant on x ∈ [0, 10] (fitted in
/// f64 against libm's `erfc`, written out in monomial form). For x < 0, erfc x = 2 − erfc(−x).
/// Beyond x = 10.2 the result underflows to 0. Accuracy: relative error below 5e-7
/// (about 4 ulp) for 0 ≤ x ≤ 4, growing as x²·2⁻²³ beyond (the rounding of x² in e^{−x²}), absolute below 7e-7 for x < 0 (the rounding of 2 − erfc(−x) near 2) (tested against f64 libm).
#[inline]
pub fn erfc_f32(x: f32) -> f32 {
    const Q: [f32; 11] = [
        0.282_085_85,
        0.282_318_43,
        0.244_479_1,
        0.189_795_47,
        0.039_057_51,
        0.074_567_96,
        -0.086_649_455,
        -0.218_993_28,
        0.332_568_65,
        -0.171_628_9,
        0.032_398_652,
    ];
    let ax = if x < 0.0 { -x } else { x };
    let t = 1.0 / (1.0 + 0.5 * ax);
    let mut q = Q[10];
    for &c in Q[..10].iter().rev() {
        q = q * t + c;
    }
    let r = exp_f32(-(ax * ax)) * t * q;
    if x < 0.0 {
        2.0 - r
    } else {
        r
    }
}

impl Real for f32 {
    consts!(f32);
    #[inline]
    fn exp_bounded(self) -> Self {
        let (p, k) = exp_f32_reduced(if self < -87.0 { -87.0 } else { self });
        p * f32::from_bits(((k + 127) as u32) << 23)
    }
    #[inline]
    fn sin(self) -> Self {
        sin_cos_f32(self).0
    }
    #[inline]
    fn cos(self) -> Self {
        sin_cos_f32(self).1
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        sin_cos_f32(self)
    }
    forward!(
        sqrt => libm::sqrtf, exp => exp_f32, ln => libm::logf, tan => libm::tanf,
        asin => libm::asinf, acos => libm::acosf, atan => libm::atanf, floor => libm::floorf,
        erf => libm::erff, erfc => erfc_f32,
    );
    forward!(binary
        atan2 => libm::atan2f, powf => libm::powf,
    );
}

#[cfg(feature = "micromath")]
mod micro;
#[cfg(feature = "micromath")]
pub use micro::Micro;

#[cfg(test)]
mod tests {
    extern crate std;

    /// The f64 pair square root, lane by lane bit for bit libm's (correctly rounded) `sqrt`:
    /// a dense grid over [0, 1e6] (the kernels take it of 1 + u², below 10 for σ ≤ 0.5), zeros,
    /// subnormals, ∞, negative numbers and NaN (both NaN).
    #[test]
    fn f64_sqrt2_is_libm_sqrt_per_lane() {
        use super::Real;
        let mut xs: std::vec::Vec<f64> = (0..200_000).map(|i| i as f64 * 5.000_1).collect();
        xs.extend([
            0.0,
            -0.0,
            5e-324,
            2.2e-308,
            1.0,
            2.0,
            f64::MAX,
            f64::INFINITY,
            -1.0,
        ]);
        xs.push(f64::NAN);
        let n = xs.len();
        for (j, &a) in xs.iter().enumerate() {
            let b = xs[(j * 7 + 3) % n];
            let r = <f64 as Real>::sqrt2([a, b]);
            for (k, x) in [a, b].into_iter().enumerate() {
                let want = libm::sqrt(x);
                assert!(
                    r[k].to_bits() == want.to_bits() || (r[k].is_nan() && want.is_nan()),
                    "lane {k}: √{x} = {} vs {want}",
                    r[k]
                );
            }
        }
    }

    /// The f32 complementary error function against f64 libm.
    #[test]
    fn erfc_f32_against_f64() {
        let (mut rel, mut abs_neg) = (0f64, 0f64);
        for i in 0..=1_000_000 {
            let x = (-6.0 + 15.0 * i as f64 / 1e6) as f32;
            let e = libm::erfc(x as f64);
            let got = super::erfc_f32(x) as f64;
            if x >= 0.0 {
                // The f32 argument's x² carries a rounding error of up to x²·2⁻²⁴, which
                // e^{−x²} turns into that relative error: allowed on top of 5e-7.
                let allow = 5e-7 + (x as f64).powi(2) * f32::EPSILON as f64;
                rel = rel.max((got - e).abs() / e / allow);
            } else {
                abs_neg = abs_neg.max((got - e).abs());
            }
        }
        assert!(rel <= 1.0, "max rel error / allowance {rel}");
        assert!(abs_neg < 7e-7, "max abs error for x < 0: {abs_neg:e}");
        assert_eq!(super::erfc_f32(f32::INFINITY), 0.0);
        assert_eq!(super::erfc_f32(f32::NEG_INFINITY), 2.0);
        assert!(super::erfc_f32(f32::NAN).is_nan());
    }

    /// The f32 exponential against f64 libm, relative error in units of f32 ε (2⁻²³).
    #[test]
    fn exp_f32_within_two_ulp_of_f64() {
        let mut worst = 0f64;
        let n = 2_000_000;
        for i in 0..=n {
            let x = (-87.0 + 175.0 * i as f64 / n as f64) as f32;
            let e = libm::exp(x as f64);
            if e > f32::MAX as f64 {
                continue;
            }
            let got = super::exp_f32(x) as f64;
            worst = worst.max((got - e).abs() / e);
        }
        // The kernels' range, densely: −v² for v ∈ [0, 4.5].
        for i in 0..=1_000_000 {
            let x = (-20.25 * i as f64 / 1e6) as f32;
            let e = libm::exp(x as f64);
            worst = worst.max((super::exp_f32(x) as f64 - e).abs() / e);
        }
        assert!(
            worst <= 2.0 * f32::EPSILON as f64,
            "max rel error {worst:e}"
        );
        // Subnormal results: absolute error below half the smallest subnormal step times 4.
        for x in [-88.0f32, -95.0, -100.0, -103.0] {
            let e = libm::exp(x as f64);
            let got = super::exp_f32(x) as f64;
            assert!(
                (got - e).abs() <= 4.0 * 1.4e-45 + 2.4e-7 * e,
                "x={x}: {got:e} vs {e:e}"
            );
        }
        assert_eq!(super::exp_f32(0.0), 1.0);
        assert_eq!(super::exp_f32(-200.0), 0.0);
        assert_eq!(super::exp_f32(100.0), f32::INFINITY);
        assert!(super::exp_f32(f32::NAN).is_nan());
        assert!(super::exp_f32(88.7) > 3.3e38 && super::exp_f32(88.7).is_finite());
    }

    /// The f32 sine and cosine against f64 libm (an independent, more precise reference).
    #[test]
    fn sin_cos_f32_within_two_ulp_of_f64() {
        let mut worst = 0f64;
        let n = 400_000;
        for i in 0..=n {
            let x = -6400.0 + 12800.0 * i as f64 / n as f64;
            let xf = x as f32;
            let (s, c) = super::sin_cos_f32(xf);
            let (es, ec) = (libm::sin(xf as f64), libm::cos(xf as f64));
            worst = worst.max((s as f64 - es).abs()).max((c as f64 - ec).abs());
            assert!(s.abs() <= 1.0 && c.abs() <= 1.0);
        }
        // Dense near the origin and the quadrant edges.
        for i in 0..=100_000 {
            let x = -7.0 + 14.0 * i as f64 / 100_000.0;
            let xf = x as f32;
            let (s, c) = super::sin_cos_f32(xf);
            worst = worst
                .max((s as f64 - libm::sin(xf as f64)).abs())
                .max((c as f64 - libm::cos(xf as f64)).abs());
        }
        assert!(worst <= 1.2e-7, "max abs error {worst}");
        let (s, c) = super::sin_cos_f32(f32::INFINITY);
        assert!(s.is_nan() && c.is_nan());
        assert_eq!(super::sin_cos_f32(0.0), (0.0, 1.0));
        let (s, c) = super::sin_cos_f32(1e30);
        assert!(s.abs() <= 1.0 && c.abs() <= 1.0);
    }
}

//! The scalar type every kernel is generic over.
//!
//! Each kernel is written once, as a generic function over [`Real`], and instantiated for
//! `f32` (devices, shaders) and `f64` (table generation, references). `f64` always uses
//! `libm`. `f32` uses `libm` by default and `micromath` when the `micromath` feature is on
//! (micromath has no `erf`, so `erf` stays on `libm` in both cases).

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

    fn abs(self) -> Self;
    fn sqrt(self) -> Self;
    fn exp(self) -> Self;
    fn ln(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn tan(self) -> Self;
    fn asin(self) -> Self;
    fn acos(self) -> Self;
    fn atan(self) -> Self;
    fn atan2(self, x: Self) -> Self;
    fn powf(self, e: Self) -> Self;
    fn floor(self) -> Self;
    /// The error function, always from `libm`.
    fn erf(self) -> Self;
    /// The complementary error function 1 − erf, always from `libm`.
    fn erfc(self) -> Self;

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

impl Real for f64 {
    consts!(f64);
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn exp(self) -> Self {
        libm::exp(self)
    }
    #[inline]
    fn ln(self) -> Self {
        libm::log(self)
    }
    #[inline]
    fn sin(self) -> Self {
        libm::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        libm::cos(self)
    }
    #[inline]
    fn tan(self) -> Self {
        libm::tan(self)
    }
    #[inline]
    fn asin(self) -> Self {
        libm::asin(self)
    }
    #[inline]
    fn acos(self) -> Self {
        libm::acos(self)
    }
    #[inline]
    fn atan(self) -> Self {
        libm::atan(self)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        libm::atan2(self, x)
    }
    #[inline]
    fn powf(self, e: Self) -> Self {
        libm::pow(self, e)
    }
    #[inline]
    fn floor(self) -> Self {
        libm::floor(self)
    }
    #[inline]
    fn erf(self) -> Self {
        libm::erf(self)
    }
    #[inline]
    fn erfc(self) -> Self {
        libm::erfc(self)
    }
}

#[cfg(not(feature = "micromath"))]
impl Real for f32 {
    consts!(f32);
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrtf(self)
    }
    #[inline]
    fn exp(self) -> Self {
        libm::expf(self)
    }
    #[inline]
    fn ln(self) -> Self {
        libm::logf(self)
    }
    #[inline]
    fn sin(self) -> Self {
        libm::sinf(self)
    }
    #[inline]
    fn cos(self) -> Self {
        libm::cosf(self)
    }
    #[inline]
    fn tan(self) -> Self {
        libm::tanf(self)
    }
    #[inline]
    fn asin(self) -> Self {
        libm::asinf(self)
    }
    #[inline]
    fn acos(self) -> Self {
        libm::acosf(self)
    }
    #[inline]
    fn atan(self) -> Self {
        libm::atanf(self)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        libm::atan2f(self, x)
    }
    #[inline]
    fn powf(self, e: Self) -> Self {
        libm::powf(self, e)
    }
    #[inline]
    fn floor(self) -> Self {
        libm::floorf(self)
    }
    #[inline]
    fn erf(self) -> Self {
        libm::erff(self)
    }
    #[inline]
    fn erfc(self) -> Self {
        libm::erfcf(self)
    }
}

// micromath's methods are called through the trait path: on a std host, `x.sqrt()` would
// silently pick the inherent std method instead.
#[cfg(feature = "micromath")]
impl Real for f32 {
    consts!(f32);
    #[inline]
    fn sqrt(self) -> Self {
        micromath::F32Ext::sqrt(self)
    }
    #[inline]
    fn exp(self) -> Self {
        micromath::F32Ext::exp(self)
    }
    #[inline]
    fn ln(self) -> Self {
        micromath::F32Ext::ln(self)
    }
    #[inline]
    fn sin(self) -> Self {
        micromath::F32Ext::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        micromath::F32Ext::cos(self)
    }
    #[inline]
    fn tan(self) -> Self {
        micromath::F32Ext::tan(self)
    }
    #[inline]
    fn asin(self) -> Self {
        micromath::F32Ext::asin(self)
    }
    #[inline]
    fn acos(self) -> Self {
        micromath::F32Ext::acos(self)
    }
    #[inline]
    fn atan(self) -> Self {
        micromath::F32Ext::atan(self)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        micromath::F32Ext::atan2(self, x)
    }
    #[inline]
    fn powf(self, e: Self) -> Self {
        micromath::F32Ext::powf(self, e)
    }
    #[inline]
    fn floor(self) -> Self {
        micromath::F32Ext::floor(self)
    }
    #[inline]
    fn erf(self) -> Self {
        libm::erff(self)
    }
    #[inline]
    fn erfc(self) -> Self {
        libm::erfcf(self)
    }
}

//! [`Micro`]: an `f32` whose transcendental functions come from micromath where that keeps
//! the kernels close to libm (feature `micromath`).

use super::{erfc_f32, sin_cos_f32, Real};
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// An `f32` computed with micromath's approximations (smaller and faster on an FPU-only
/// core, less accurate) for the functions where the kernels built on them stay within 2e-2
/// relative of the same kernels in `f32` with libm, and with the `f32` functions elsewhere.
///
/// Per function (the kernel errors they cause are measured by `cargo xtask firmware
/// --micromath` and listed in its tolerances):
///
/// | function | source | why |
/// |---|---|---|
/// | `exp`, `ln`, `atan`, `atan2`, `asin`, `acos`, `tan` | micromath | kernels within 2e-2 (modified G: 6.6e-4 from `exp`) |
/// | `sqrt` | libm | micromath's `sqrt` alone puts the modified G 2.2e-2 off |
/// | `powf` | libm | micromath's `powf` with exponents 10–1000 puts Ashikhmin–Shirley 69 % off |
/// | `sin`, `cos` | the crate's f32 kernel | as small, and exact to 2 ulp |
/// | `erf`, `erfc`, `floor` | libm / the crate's f32 `erfc` | micromath has none (or none exact) |
///
/// Arithmetic is plain `f32` arithmetic, so a kernel in `Micro` differs from the same kernel
/// in `f32` only through these functions. Using `Micro` is a choice made at the call site:
/// enabling the feature changes nothing that uses `f32`.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
#[repr(transparent)]
pub struct Micro(pub f32);

macro_rules! binop {
    ($tr:ident, $f:ident, $atr:ident, $af:ident, $op:tt) => {
        impl $tr for Micro {
            type Output = Micro;
            #[inline]
            fn $f(self, o: Micro) -> Micro {
                Micro(self.0 $op o.0)
            }
        }
        impl $atr for Micro {
            #[inline]
            fn $af(&mut self, o: Micro) {
                self.0 = self.0 $op o.0;
            }
        }
    };
}
binop!(Add, add, AddAssign, add_assign, +);
binop!(Sub, sub, SubAssign, sub_assign, -);
binop!(Mul, mul, MulAssign, mul_assign, *);

impl Div for Micro {
    type Output = Micro;
    #[inline]
    fn div(self, o: Micro) -> Micro {
        Micro(self.0 / o.0)
    }
}

impl Neg for Micro {
    type Output = Micro;
    #[inline]
    fn neg(self) -> Micro {
        Micro(-self.0)
    }
}

impl From<f32> for Micro {
    #[inline]
    fn from(x: f32) -> Micro {
        Micro(x)
    }
}

impl From<Micro> for f32 {
    #[inline]
    fn from(x: Micro) -> f32 {
        x.0
    }
}

// micromath's methods are called through the trait path: on a std host, `x.sqrt()` would
// pick the inherent std method instead.
use micromath::F32Ext as Mm;

impl Real for Micro {
    const PI: Self = Micro(core::f32::consts::PI);
    const FRAC_PI_2: Self = Micro(core::f32::consts::FRAC_PI_2);
    const ZERO: Self = Micro(0.0);
    const ONE: Self = Micro(1.0);
    const TWO: Self = Micro(2.0);
    const HALF: Self = Micro(0.5);
    const EPSILON: Self = Micro(f32::EPSILON);
    const INFINITY: Self = Micro(f32::INFINITY);
    const NAN: Self = Micro(f32::NAN);

    #[inline]
    fn from_f64(x: f64) -> Self {
        Micro(x as f32)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self.0 as f64
    }
    #[inline]
    fn abs(self) -> Self {
        Micro(<f32 as Real>::abs(self.0))
    }
    #[inline]
    fn sin(self) -> Self {
        Micro(sin_cos_f32(self.0).0)
    }
    #[inline]
    fn cos(self) -> Self {
        Micro(sin_cos_f32(self.0).1)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = sin_cos_f32(self.0);
        (Micro(s), Micro(c))
    }
    forward!(Micro:
        sqrt => libm::sqrtf, exp => Mm::exp, ln => Mm::ln, tan => Mm::tan, asin => Mm::asin,
        acos => Mm::acos, atan => Mm::atan, floor => libm::floorf, erf => libm::erff,
        erfc => erfc_f32,
    );
    forward!(Micro binary:
        atan2 => Mm::atan2, powf => libm::powf,
    );
}

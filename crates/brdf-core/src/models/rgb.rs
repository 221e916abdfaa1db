//! Per-channel (RGB) colour triples: the "⊗" of the standard lighting model notes.

use crate::Real;

/// An RGB triple. Products are per channel (the ⊗ of the standard lighting model notes).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb<T> {
    /// Red channel.
    pub r: T,
    /// Green channel.
    pub g: T,
    /// Blue channel.
    pub b: T,
}

impl<T: Real> Rgb<T> {
    /// Builds a triple.
    #[inline]
    pub const fn new(r: T, g: T, b: T) -> Self {
        Self { r, g, b }
    }
    /// The same value in every channel (a scalar model).
    #[inline]
    pub const fn splat(v: T) -> Self {
        Self { r: v, g: v, b: v }
    }
    /// Black.
    #[inline]
    pub const fn zero() -> Self {
        Self::splat(T::ZERO)
    }
    /// Channel-wise sum.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
    /// Channel-wise product (⊗).
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, o: Self) -> Self {
        Self::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
    /// Scales every channel by `s`.
    #[inline]
    pub fn scale(self, s: T) -> Self {
        Self::new(self.r * s, self.g * s, self.b * s)
    }
    /// Applies `f` to every channel.
    #[inline]
    pub fn map(self, mut f: impl FnMut(T) -> T) -> Self {
        Self::new(f(self.r), f(self.g), f(self.b))
    }
    /// Channel mean (used to pick lobes when sampling).
    #[inline]
    pub fn mean(self) -> T {
        (self.r + self.g + self.b) / T::from_f64(3.0)
    }
    /// Largest channel.
    #[inline]
    pub fn max_channel(self) -> T {
        self.r.max(self.g).max(self.b)
    }
    /// Smallest channel.
    #[inline]
    pub fn min_channel(self) -> T {
        self.r.min(self.g).min(self.b)
    }
    /// `true` when every channel is finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }
    /// The channels as an array.
    #[inline]
    pub fn to_array(self) -> [T; 3] {
        [self.r, self.g, self.b]
    }
}

/// Checks each channel of a colour parameter: finite and in `[lo, hi]`.
pub(crate) fn check_rgb<T: Real>(
    name: &'static str,
    c: Rgb<T>,
    lo: T,
    hi: T,
    range: &'static str,
) -> Result<Rgb<T>, crate::ParamError> {
    for v in c.to_array() {
        crate::error::check_range(name, v, lo, false, hi, range)?;
    }
    Ok(c)
}

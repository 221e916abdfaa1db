//! Typed errors for checked constructors.

use core::fmt;

/// A parameter that a checked constructor rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ParamError {
    /// The value was NaN or ±∞.
    NotFinite {
        /// Parameter name as documented.
        name: &'static str,
    },
    /// The value lies outside the documented range.
    OutOfRange {
        /// Parameter name as documented.
        name: &'static str,
        /// Human-readable range, e.g. `"(0, ∞)"`.
        range: &'static str,
    },
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamError::NotFinite { name } => write!(f, "parameter `{name}` is not finite"),
            ParamError::OutOfRange { name, range } => {
                write!(f, "parameter `{name}` is outside its range {range}")
            }
        }
    }
}

impl core::error::Error for ParamError {}

/// Checks `lo ≤ x ≤ hi` (or `lo < x` when `open_lo`), and finiteness.
pub(crate) fn check_range<T: crate::Real>(
    name: &'static str,
    x: T,
    lo: T,
    open_lo: bool,
    hi: T,
    range: &'static str,
) -> Result<T, ParamError> {
    if !x.is_finite() {
        return Err(ParamError::NotFinite { name });
    }
    let below = if open_lo { x <= lo } else { x < lo };
    if below || x > hi {
        return Err(ParamError::OutOfRange { name, range });
    }
    Ok(x)
}

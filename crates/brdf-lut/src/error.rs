//! Typed errors of the LUT reader.

use crate::header::TableKind;
use core::fmt;

/// Why a byte string is not a usable LUT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum LutError {
    /// The bytes end before the header does.
    Truncated,
    /// The first four bytes are not `BLUT`.
    BadMagic,
    /// A format version this reader does not know.
    UnsupportedVersion {
        /// The version found.
        found: u16,
    },
    /// The header is not a valid postcard encoding of the header struct (bad enum tag,
    /// bad UTF-8, too many axes or channels, …).
    MalformedHeader,
    /// The header decodes but contradicts itself or the format's limits.
    Inconsistent(&'static str),
    /// The payload length differs from what the header implies.
    PayloadLength {
        /// Bytes the header implies.
        expected: u64,
        /// Bytes present.
        found: u64,
    },
    /// The CRC-32 does not match.
    Checksum {
        /// Stored in the header.
        stored: u32,
        /// Computed from the file.
        computed: u32,
    },
    /// A typed wrapper was given a table of another kind or shape.
    WrongKind {
        /// What the wrapper needs.
        expected: TableKind,
        /// What the file holds.
        found: TableKind,
    },
    /// The writer's output buffer is too small.
    BufferTooSmall,
    /// A varint of the header is not in its shortest form (e.g. `81 00` for 1): every
    /// header has exactly one encoding.
    NonCanonical,
    /// An axis that is valid in f64 but degenerate in the f32 the reader computes in
    /// (docs/lut-format.md §6): every lookup would be NaN.
    DegenerateAxis {
        /// The axis (0 = fastest).
        axis: u8,
        /// Which part of the rule fails.
        why: &'static str,
    },
    /// A decoded node value is not finite or exceeds
    /// [`MAX_VALUE_MAGNITUDE`](crate::MAX_VALUE_MAGNITUDE) in magnitude.
    BadValue {
        /// Index of the stored number in the payload.
        index: u64,
    },
    /// The values given to the writer do not fit the table (count, or not finite).
    BadInput(&'static str),
    /// The header's error statistics are not a claim that can be checked: NaN, infinite or
    /// negative, RMS above the maximum, or no sample ([`ErrorStats::check`]).
    ///
    /// [`ErrorStats::check`]: crate::ErrorStats::check
    BadErrorStats {
        /// Which rule fails.
        field: &'static str,
    },
}

impl fmt::Display for LutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LutError::Truncated => write!(f, "LUT file is truncated"),
            LutError::BadMagic => write!(f, "not a LUT file (magic is not `BLUT`)"),
            LutError::UnsupportedVersion { found } => {
                write!(f, "unsupported LUT format version {found}")
            }
            LutError::MalformedHeader => write!(f, "malformed LUT header"),
            LutError::Inconsistent(why) => write!(f, "inconsistent LUT header: {why}"),
            LutError::PayloadLength { expected, found } => write!(
                f,
                "LUT payload is {found} bytes, the header implies {expected}"
            ),
            LutError::Checksum { stored, computed } => write!(
                f,
                "LUT checksum mismatch (stored {stored:#010x}, computed {computed:#010x})"
            ),
            LutError::WrongKind { expected, found } => {
                write!(f, "expected a {expected:?} table, found {found:?}")
            }
            LutError::BufferTooSmall => write!(f, "output buffer too small"),
            LutError::NonCanonical => write!(f, "LUT header varint not in its shortest form"),
            LutError::DegenerateAxis { axis, why } => {
                write!(f, "LUT axis {axis} is degenerate in f32: {why}")
            }
            LutError::BadValue { index } => write!(
                f,
                "LUT payload value {index} is not finite or exceeds the value limit"
            ),
            LutError::BadInput(why) => write!(f, "cannot write the table: {why}"),
            LutError::BadErrorStats { field } => {
                write!(f, "LUT header's error statistics are invalid: {field}")
            }
        }
    }
}

impl core::error::Error for LutError {}

//! Typed errors of the LUT reader.

use super::header::TableKind;
use core::fmt;

/// Why a byte string is not a usable LUT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
        }
    }
}

impl core::error::Error for LutError {}

#![doc = include_str!("../README.md")]
//!
// Targets of the README's links to feature-gated items: the local item when the feature is
// on, the published documentation otherwise (so the docs build warning-free on any features).
#![cfg_attr(feature = "alloc", doc = "[`write`]: mod@write")]
#![cfg_attr(
    not(feature = "alloc"),
    doc = "[`write`]: https://docs.rs/brdf-lut/latest/brdf_lut/write/index.html"
)]
#![cfg_attr(
    not(feature = "std"),
    doc = "[`Lut`]: https://docs.rs/brdf-lut/latest/brdf_lut/struct.Lut.html"
)]
#![no_std]
#![warn(missing_docs)]
// Every unsafe operation sits in its own `unsafe` block with a `// SAFETY:` comment, and
// every unsafe function states its contract under `# Safety` (all of them are in
// `lookup/simd.rs` and `lookup/mod.rs`: the x86-64 SIMD paths).
#![deny(unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]
#![deny(clippy::missing_safety_doc)]

#[cfg(feature = "alloc")]
extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

mod axis;
mod codec;
mod crc;
mod error;
mod f16;
mod header;
mod kernel;
pub mod limits;
mod lookup;
mod tables;
#[cfg(test)]
mod testing;
mod view;

#[cfg(feature = "std")]
mod file;
#[cfg(feature = "generate")]
pub mod generate;
/// Without the `generate` feature only the one list of table kinds of the generator is
/// compiled (its format half: [`TableKind`]'s codes and shapes).
#[cfg(not(feature = "generate"))]
mod generate {
    pub(crate) mod kinds;
}
#[cfg(feature = "alloc")]
pub mod write;

pub use axis::AxisMap;
pub use crc::{crc32, Crc32};
pub use error::LutError;
pub use f16::{f16_to_f32, f32_to_f16};
pub use header::{
    Axis, Channel, Convention, Encoding, ErrorStats, Generator, Header, Interpolation, List, Model,
    Placement, TableKind, Warp, FORMAT_VERSION, MAGIC, MAX_AXES, MAX_AXIS_COUNT, MAX_CHANNELS,
    MAX_GENERATOR_NODES, MAX_VALUES, MAX_VALUE_MAGNITUDE, MIN_FORMAT_VERSION,
};
pub use lookup::Values;
pub use tables::layout::TableLayout;
pub use tables::{
    AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, GlassAlbedoTable,
    GlassAverageTable, SheenAlbedoTable,
};
pub use view::{encode_into, header_len, LutView};

#[cfg(feature = "std")]
pub use file::{read_capped, summary, Error, Escaped, Lut, MAX_FILE_BYTES};

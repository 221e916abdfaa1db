#![doc = include_str!("../README.md")]
#![no_std]
#![warn(missing_docs)]

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
mod reader;
mod tables;
mod view;

#[cfg(feature = "std")]
mod file;
#[cfg(feature = "alloc")]
pub mod write;

pub use axis::AxisMap;
pub use crc::{crc32, Crc32};
pub use error::LutError;
pub use f16::{f16_to_f32, f32_to_f16};
pub use header::{
    Axis, Channel, Convention, Encoding, ErrorStats, Generator, Header, Interpolation, List, Model,
    Placement, TableKind, Warp, FORMAT_VERSION, MAGIC, MAX_AXES, MAX_AXIS_COUNT, MAX_CHANNELS,
    MAX_GENERATOR_NODES, MAX_VALUES, MAX_VALUE_MAGNITUDE,
};
pub use tables::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3};
pub use view::{encode_into, header_len, LutView, Values};

#[cfg(feature = "std")]
pub use file::{read_capped, summary, Error, Escaped, Lut, MAX_FILE_BYTES};

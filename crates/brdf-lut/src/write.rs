//! The writer (feature `alloc`): node coordinates, quantisation, error statistics, header and
//! CRC. What to tabulate stays with the caller: it evaluates its kernel at
//! [`node_coords`] and hands the values to [`build`], which quantises them, measures the
//! interpolated table with the caller's reference and encodes the file.
//!
//! ```
//! use brdf_lut::write::{self, Spec};
//! use brdf_lut::*;
//! // E_avg(r) = 1 − r/2 on 5 nodes, f32 (a made-up function: the writer does not care).
//! let axes = [Axis { name: "roughness", count: 5, lo: 0.0, hi: 1.0, ..Axis::default() }];
//! let spec = Spec {
//!     kind: TableKind::AverageAlbedo,
//!     axes: &axes,
//!     channels: &["Eavg"],
//!     encoding: Encoding::F32,
//!     interpolation: Interpolation::Linear,
//!     generator: Generator { tool: "doc example", ..Generator::default() },
//! };
//! let f = |r: f64| 1.0 - 0.5 * r;
//! let values: Vec<f64> = (0..5).map(|k| f(write::node_coords(&axes, k)[0])).collect();
//! let bytes = write::build(&spec, &values, |view| {
//!     let mut acc = write::ErrorAccumulator::default();
//!     for k in 0..100 {
//!         let r = k as f64 / 99.0;
//!         acc.add((view.sample1(r as f32)[0] as f64 - f(r)).abs());
//!     }
//!     acc.finish(100, 0)
//! })
//! .unwrap();
//! let t = AverageAlbedoTable::parse(&bytes[..]).unwrap();
//! assert!((t.e_avg(0.3) - 0.85).abs() < 1e-6);
//! ```

use crate::header::*;
use crate::view::{encode_into, LutView};
use crate::{f32_to_f16, LutError};
use alloc::vec::Vec;

/// What a table is, apart from its values.
#[derive(Clone, Copy, Debug)]
pub struct Spec<'a> {
    /// What the table holds.
    pub kind: TableKind,
    /// The axes, fastest first.
    pub axes: &'a [Axis<'a>],
    /// The channel names, in payload order.
    pub channels: &'a [&'a str],
    /// Number format of the payload.
    pub encoding: Encoding,
    /// Intended interpolation.
    pub interpolation: Interpolation,
    /// Generator record (model, convention, σ, quadrature nodes, tool).
    pub generator: Generator<'a>,
}

impl Spec<'_> {
    /// Number of grid nodes (saturating).
    pub fn nodes(&self) -> usize {
        self.axes
            .iter()
            .fold(1usize, |n, a| n.saturating_mul(a.count as usize))
    }
}

/// The physical coordinates of flat node `flat` (axis 0 fastest), one per axis.
pub fn node_coords(axes: &[Axis<'_>], flat: usize) -> List<f64, MAX_AXES> {
    let mut r = flat;
    let mut out = List::new();
    for a in axes.iter().take(MAX_AXES) {
        let n = (a.count as usize).max(1);
        let _ = out.push(a.node((r % n) as u32));
        r /= n;
    }
    out
}

/// Running max and RMS of absolute errors; a NaN error counts as +∞.
#[derive(Clone, Copy, Debug, Default)]
pub struct ErrorAccumulator {
    max: f64,
    sum_sq: f64,
    n: u64,
}

impl ErrorAccumulator {
    /// Adds one absolute error.
    pub fn add(&mut self, err: f64) {
        let e = if err.is_nan() { f64::INFINITY } else { err };
        self.max = self.max.max(e);
        self.sum_sq += e * e;
        self.n += 1;
    }
    /// Adds the errors of another accumulator.
    pub fn merge(&mut self, o: &Self) {
        self.max = self.max.max(o.max);
        self.sum_sq += o.sum_sq;
        self.n += o.n;
    }
    /// The statistics for the header: `samples` random points drawn with `seed`.
    pub fn finish(&self, samples: u32, seed: u64) -> ErrorStats {
        ErrorStats {
            max_abs: self.max as f32,
            rms: libm::sqrt(self.sum_sq / self.n.max(1) as f64) as f32,
            samples,
            seed,
        }
    }
}

/// Quantises node values (node-major, channels interleaved: `values[node × C + c]`) into
/// the payload and the channels' scale and offset. `Unorm16`: each channel's [min, max]
/// maps to [0, 65535] (round to nearest); `F16`: round to nearest even; `F32`: as f32.
pub fn quantise<'a>(
    spec: &Spec<'a>,
    values: &[f64],
) -> Result<(List<Channel<'a>, MAX_CHANNELS>, Vec<u8>), LutError> {
    let nc = spec.channels.len();
    if nc == 0 || nc > MAX_CHANNELS {
        return Err(LutError::BadInput("a table has 1 to 4 channels"));
    }
    if values.len() != spec.nodes().saturating_mul(nc) {
        return Err(LutError::BadInput("value count is not nodes × channels"));
    }
    if values.iter().any(|v| !v.is_finite()) {
        return Err(LutError::BadInput("non-finite value at a node"));
    }
    let mut chans = List::new();
    for (c, &name) in spec.channels.iter().enumerate() {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.iter().skip(c).step_by(nc) {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        let (scale, offset) = match spec.encoding {
            Encoding::Unorm16 => {
                let span = (hi - lo) as f32;
                (if span > 0.0 { span } else { 1.0 }, lo as f32)
            }
            _ => (1.0f32, 0.0f32),
        };
        let _ = chans.push(Channel {
            name,
            scale,
            offset,
        });
    }
    let mut payload = Vec::with_capacity(values.len() * spec.encoding.bytes());
    for node in values.chunks_exact(nc) {
        for (v, ch) in node.iter().zip(chans.iter()) {
            match spec.encoding {
                Encoding::Unorm16 => {
                    // libm's round and sqrt are exact like std's, also without std.
                    let q = libm::round((v - ch.offset as f64) / ch.scale as f64 * 65535.0)
                        .clamp(0.0, 65535.0) as u16;
                    payload.extend_from_slice(&q.to_le_bytes());
                }
                Encoding::F16 => payload.extend_from_slice(&f32_to_f16(*v as f32).to_le_bytes()),
                Encoding::F32 => payload.extend_from_slice(&(*v as f32).to_le_bytes()),
            }
        }
    }
    Ok((chans, payload))
}

/// Encodes a header and payload into a new file (CRC filled in; checked as a reader would).
pub fn encode(header: &Header<'_>, payload: &[u8]) -> Result<Vec<u8>, LutError> {
    let strings: usize = header.axes.iter().map(|a| a.name.len()).sum::<usize>()
        + header.channels.iter().map(|c| c.name.len()).sum::<usize>()
        + header.generator.tool.len();
    // Fixed fields take < 256 bytes (3 axes × 32, 4 channels × 13, generator and error < 80).
    let mut buf = alloc::vec![0u8; payload.len() + strings + 256];
    let n = encode_into(header, payload, &mut buf)?;
    buf.truncate(n);
    Ok(buf)
}

/// The header of `spec` with the given channels and error statistics.
pub fn header<'a>(
    spec: &Spec<'a>,
    channels: List<Channel<'a>, MAX_CHANNELS>,
    error: ErrorStats,
) -> Result<Header<'a>, LutError> {
    Ok(Header {
        kind: spec.kind,
        axes: List::from_slice(spec.axes).ok_or(LutError::BadInput("more than 3 axes"))?,
        channels,
        encoding: spec.encoding,
        interpolation: spec.interpolation,
        generator: spec.generator,
        error,
        integration: None,
        checksum: 0,
    })
}

/// Quantises `values` ([`quantise`]), encodes the table, measures it with `measure` (given
/// the table as it will be read) and encodes it again with the measured statistics. The
/// header records no integration error bound ([`build_with_bound`] records one).
pub fn build(
    spec: &Spec<'_>,
    values: &[f64],
    measure: impl FnOnce(&LutView<'_>) -> ErrorStats,
) -> Result<Vec<u8>, LutError> {
    build_with_bound(spec, values, None, measure)
}

/// [`build`], with `integration` (the largest estimated integration error of a node value,
/// docs/lut-format.md §3) recorded in the header; refused (`BadErrorStats`) unless finite
/// and ≥ 0.
pub fn build_with_bound(
    spec: &Spec<'_>,
    values: &[f64],
    integration: Option<f32>,
    measure: impl FnOnce(&LutView<'_>) -> ErrorStats,
) -> Result<Vec<u8>, LutError> {
    check_integration(integration)?;
    let (chans, payload) = quantise(spec, values)?;
    let first = encode(&header(spec, chans, ErrorStats::default())?, &payload)?;
    let stats = measure(&LutView::parse(&first)?);
    let h = Header {
        integration,
        ..header(spec, chans, stats)?
    };
    encode(&h, &payload)
}

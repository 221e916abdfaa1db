//! Compact look-up tables: a zero-copy, allocation-free view of a LUT file
//! (format: `docs/lut-format.md`).
//!
//! ```text
//! file = postcard(Header) ++ payload
//! ```
//!
//! [`LutView::parse`] validates a borrowed `&[u8]` (magic, version, header, limits, payload
//! length, CRC-32) and keeps only borrows, so firmware can `include_bytes!` a table straight
//! from flash. Queries take physical coordinates (radians, μ, roughness, σ), clamp them to
//! each axis' range and interpolate in the axes' unit coordinates ([`Interpolation`]).
//!
//! Typed wrappers: [`GTable`] (per-σ modified G), [`GTable3`] (modified G over σ),
//! [`DfgTable`] (split-sum A, B), [`AlbedoTable`] (E(μ, r)), [`AverageAlbedoTable`]
//! (E_avg(r)).
//!
//! ```no_run
//! # use brdf_core::lut::GTable;
//! static BYTES: &[u8] = include_bytes!("../../../../assets/g_modified_sigma0.3.blut");
//! let t = GTable::parse(BYTES).unwrap();
//! let g = t.g(0.5, -0.3);
//! # let _ = g;
//! ```

mod crc;
mod error;
mod f16;
mod header;
mod interp;
mod passing;
mod tables;

pub use crc::{crc32, Crc32};
pub use error::LutError;
pub use f16::{f16_to_f32, f32_to_f16};
pub use header::{
    Axis, Channel, Encoding, ErrorStats, Generator, Header, Interpolation, Model, Placement,
    TableKind, Warp, FORMAT_VERSION, MAGIC, MAX_AXES, MAX_AXIS_COUNT, MAX_CHANNELS, MAX_VALUES,
};
pub use interp::AxisMap;
pub use tables::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3};

/// Channel values returned by a lookup; entries past [`LutView::channels`] are 0.
pub type Values = [f32; MAX_CHANNELS];

/// A validated, borrowed LUT.
#[derive(Clone, Debug)]
pub struct LutView<'a> {
    header: Header<'a>,
    header_len: usize,
    payload: &'a [u8],
    maps: [AxisMap; MAX_AXES],
}

/// Reads the version varint that follows the magic (postcard u16, LEB128).
fn peek_version(bytes: &[u8]) -> Result<u16, LutError> {
    let mut v: u32 = 0;
    for (k, &b) in bytes.iter().skip(4).take(3).enumerate() {
        v |= ((b & 0x7F) as u32) << (7 * k);
        if b & 0x80 == 0 {
            return u16::try_from(v).map_err(|_| LutError::MalformedHeader);
        }
    }
    if bytes.len() < 7 {
        Err(LutError::Truncated)
    } else {
        Err(LutError::MalformedHeader)
    }
}

fn check_header(h: &Header<'_>) -> Result<(), LutError> {
    use LutError::Inconsistent as I;
    if h.axes.is_empty() {
        return Err(I("no axes"));
    }
    if h.channels.is_empty() {
        return Err(I("no channels"));
    }
    for a in &h.axes {
        if a.count < 2 || a.count > MAX_AXIS_COUNT {
            return Err(I("axis count outside [2, 65536]"));
        }
        if !(a.lo.is_finite() && a.hi.is_finite() && a.lo < a.hi) {
            return Err(I("axis range not finite or not increasing"));
        }
        match a.warp {
            Warp::Log if a.lo <= 0.0 => return Err(I("log axis must start above 0")),
            Warp::Cos if a.lo < 0.0 || a.hi > core::f64::consts::PI => {
                return Err(I("cos axis must lie in [0, π]"))
            }
            Warp::SqrtCos if a.lo < 0.0 || a.hi > core::f64::consts::FRAC_PI_2 => {
                return Err(I("sqrt-cos axis must lie in [0, π/2]"))
            }
            _ => {}
        }
    }
    for c in &h.channels {
        if !(c.scale.is_finite() && c.offset.is_finite()) {
            return Err(I("channel scale or offset not finite"));
        }
    }
    let values = h.nodes().saturating_mul(h.channels.len() as u64);
    if values > MAX_VALUES {
        return Err(I("table larger than the format allows"));
    }
    let (d, c) = (h.axes.len(), h.channels.len());
    let ok = match h.kind {
        TableKind::PassingFactor => c == 1 && (d == 2 || d == 3),
        TableKind::SplitSum => c == 2 && d == 2,
        TableKind::DirectionalAlbedo => c == 1 && d == 2,
        TableKind::AverageAlbedo => c == 1 && d == 1,
    };
    if !ok {
        return Err(I("axis or channel count does not fit the table kind"));
    }
    Ok(())
}

impl<'a> LutView<'a> {
    /// Validates `bytes` and borrows them. Never panics and never allocates; every defect
    /// is a [`LutError`].
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::parse_inner(bytes, true)
    }

    /// [`LutView::parse`] without recomputing the CRC-32, for owners of bytes that were
    /// validated before (every other check still runs, so this cannot panic either).
    pub fn parse_skip_checksum(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::parse_inner(bytes, false)
    }

    fn parse_inner(bytes: &'a [u8], crc: bool) -> Result<Self, LutError> {
        if bytes.len() < 4 {
            return Err(if MAGIC.starts_with(bytes) {
                LutError::Truncated
            } else {
                LutError::BadMagic
            });
        }
        if bytes[..4] != MAGIC {
            return Err(LutError::BadMagic);
        }
        let version = peek_version(bytes)?;
        if version != FORMAT_VERSION {
            return Err(LutError::UnsupportedVersion { found: version });
        }
        let (header, payload) =
            postcard::take_from_bytes::<Header<'a>>(bytes).map_err(|e| match e {
                postcard::Error::DeserializeUnexpectedEnd => LutError::Truncated,
                _ => LutError::MalformedHeader,
            })?;
        let header_len = bytes.len() - payload.len();
        check_header(&header)?;
        let expected = header.payload_len();
        if expected != payload.len() as u64 {
            return Err(LutError::PayloadLength {
                expected,
                found: payload.len() as u64,
            });
        }
        if crc {
            let stored = u32::from_le_bytes(header.checksum);
            let computed = Crc32::new()
                .update(&bytes[..header_len.saturating_sub(4)])
                .update(payload)
                .finish();
            if stored != computed {
                return Err(LutError::Checksum { stored, computed });
            }
        }
        let mut maps = [AxisMap::UNIT; MAX_AXES];
        for (m, a) in maps.iter_mut().zip(header.axes.iter()) {
            *m = AxisMap::new(a);
        }
        Ok(Self {
            header,
            header_len,
            payload,
            maps,
        })
    }

    /// The decoded header.
    pub fn header(&self) -> &Header<'a> {
        &self.header
    }
    /// Length of the encoded header in bytes (the payload starts here).
    pub fn header_len(&self) -> usize {
        self.header_len
    }
    /// The raw payload.
    pub fn payload(&self) -> &'a [u8] {
        self.payload
    }
    /// What the table holds.
    pub fn kind(&self) -> TableKind {
        self.header.kind
    }
    /// Number of axes (1–3).
    pub fn dims(&self) -> usize {
        self.header.axes.len()
    }
    /// Number of channels (1–4).
    pub fn channels(&self) -> usize {
        self.header.channels.len()
    }
    /// The coordinate map of axis `k` (panics if `k ≥ dims()`).
    pub fn axis_map(&self, k: usize) -> &AxisMap {
        &self.maps[k]
    }

    /// The decoded value at a flat node index (axis 0 fastest) and channel. Out-of-range
    /// indices give NaN.
    pub fn node_value(&self, flat: usize, ch: usize) -> f32 {
        let c = self.channels();
        if ch >= c {
            return f32::NAN;
        }
        let enc = self.header.encoding;
        let nb = enc.bytes();
        let off = (flat * c + ch) * nb;
        let Some(b) = self.payload.get(off..off + nb) else {
            return f32::NAN;
        };
        let stored = match enc {
            Encoding::Unorm16 => u16::from_le_bytes([b[0], b[1]]) as f32 * (1.0 / 65535.0),
            Encoding::F16 => f16_to_f32(u16::from_le_bytes([b[0], b[1]])),
            Encoding::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        };
        let chn = &self.header.channels[ch];
        chn.offset + chn.scale * stored
    }

    /// Interpolated channel values at physical coordinates `x` (one per axis; missing
    /// coordinates count as the axis' lower end, extra ones are ignored). Coordinates are
    /// clamped to each axis' range; a NaN coordinate gives NaN in every channel.
    pub fn sample(&self, x: &[f32]) -> Values {
        let d = self.dims();
        let mut taps = [[(0usize, 0f32); 4]; MAX_AXES];
        let mut ntaps = [1usize; MAX_AXES];
        let cubic = self.header.interpolation == Interpolation::CatmullRom;
        for k in 0..d {
            let xk = x.get(k).copied().unwrap_or(f32::NEG_INFINITY);
            if xk.is_nan() {
                return [f32::NAN; MAX_CHANNELS];
            }
            ntaps[k] = self.maps[k].taps(xk, cubic, &mut taps[k]);
        }
        let mut out = [0f32; MAX_CHANNELS];
        let c = self.channels();
        let n0 = self.maps[0].count();
        let n1 = if d > 1 { self.maps[1].count() } else { 1 };
        for &(i2, w2) in &taps[2][..ntaps[2]] {
            for &(i1, w1) in &taps[1][..ntaps[1]] {
                let w21 = if d > 2 { w2 } else { 1.0 } * if d > 1 { w1 } else { 1.0 };
                for &(i0, w0) in &taps[0][..ntaps[0]] {
                    let w = w21 * w0;
                    let flat = (i2 * n1 + i1) * n0 + i0;
                    for (ch, o) in out.iter_mut().enumerate().take(c) {
                        *o += w * self.node_value(flat, ch);
                    }
                }
            }
        }
        out
    }

    /// [`LutView::sample`] for a 1-D table.
    pub fn sample1(&self, x: f32) -> Values {
        self.sample(&[x])
    }
    /// [`LutView::sample`] for a 2-D table: `x` on axis 0, `y` on axis 1.
    pub fn sample2(&self, x: f32, y: f32) -> Values {
        self.sample(&[x, y])
    }
    /// [`LutView::sample`] for a 3-D table.
    pub fn sample3(&self, x: f32, y: f32, z: f32) -> Values {
        self.sample(&[x, y, z])
    }
}

/// Writes `postcard(header) ++ payload` into `out` with the checksum filled in (the
/// `checksum` field of `header` is ignored). Returns the number of bytes written. The header
/// is checked as a reader would check it.
pub fn encode_into(header: &Header<'_>, payload: &[u8], out: &mut [u8]) -> Result<usize, LutError> {
    check_header(header)?;
    if header.payload_len() != payload.len() as u64 {
        return Err(LutError::PayloadLength {
            expected: header.payload_len(),
            found: payload.len() as u64,
        });
    }
    let mut h = header.clone();
    h.checksum = [0; 4];
    let hl = postcard::to_slice(&h, out)
        .map_err(|_| LutError::BufferTooSmall)?
        .len();
    let total = hl + payload.len();
    if out.len() < total {
        return Err(LutError::BufferTooSmall);
    }
    let crc = Crc32::new().update(&out[..hl - 4]).update(payload).finish();
    out[hl - 4..hl].copy_from_slice(&crc.to_le_bytes());
    out[hl..total].copy_from_slice(payload);
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::masking::Convention;

    /// A 2-D f32 table of f(x, y) on the given axes, encoded.
    fn table(
        buf: &mut [u8],
        axes: [Axis<'static>; 2],
        interp: Interpolation,
        f: impl Fn(f64, f64) -> f64,
    ) -> usize {
        let mut payload = [0u8; 4 * 64];
        let (n0, n1) = (axes[0].count, axes[1].count);
        for j in 0..n1 {
            for i in 0..n0 {
                let v = f(axes[0].node(i), axes[1].node(j)) as f32;
                let k = ((j * n0 + i) * 4) as usize;
                payload[k..k + 4].copy_from_slice(&v.to_le_bytes());
            }
        }
        let len = (n0 * n1 * 4) as usize;
        let h = Header {
            magic: MAGIC,
            version: FORMAT_VERSION,
            kind: TableKind::DirectionalAlbedo,
            axes: axes.iter().copied().collect(),
            channels: [Channel {
                name: "E",
                scale: 1.0,
                offset: 0.0,
            }]
            .into_iter()
            .collect(),
            encoding: Encoding::F32,
            interpolation: interp,
            generator: Generator {
                model: Model::GgxSmithCorrelated,
                convention: Convention::Reciprocal,
                sigma: None,
                nodes: heapless::Vec::new(),
                tool: "test",
            },
            error: ErrorStats {
                max_abs: 0.0,
                rms: 0.0,
                samples: 0,
                seed: 0,
            },
            checksum: [0; 4],
        };
        encode_into(&h, &payload[..len], buf).unwrap()
    }

    fn ax(count: u32, lo: f64, hi: f64, warp: Warp, placement: Placement) -> Axis<'static> {
        Axis {
            name: "x",
            count,
            lo,
            hi,
            warp,
            placement,
        }
    }

    #[test]
    fn linear_reproduces_bilinear_functions_and_nodes() {
        let mut buf = [0u8; 1024];
        let axes = [
            ax(5, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
            ax(4, -1.0, 2.0, Warp::Linear, Placement::TexelCentre),
        ];
        let n = table(&mut buf, axes, Interpolation::Linear, |x, y| {
            2.0 * x - 3.0 * y + x * y
        });
        let v = LutView::parse(&buf[..n]).unwrap();
        // Inside the texel-centre span of axis 1 ([-0.625, 1.625]) bilinear is exact.
        for &(x, y) in &[(0.1f32, -0.5f32), (0.77, 1.2), (1.0, 0.0), (0.0, 1.6)] {
            let want = 2.0 * x - 3.0 * y + x * y;
            assert!((v.sample2(x, y)[0] - want).abs() < 1e-5, "{x} {y}");
        }
        // Outside it the value is clamped to the edge nodes.
        let edge = v.sample2(0.5, 1.625)[0];
        assert!((v.sample2(0.5, 2.0)[0] - edge).abs() < 1e-6);
        assert!(v.sample2(f32::NAN, 0.0)[0].is_nan());
    }

    #[test]
    fn catmull_rom_with_quadratic_ends_reproduces_quadratics() {
        let mut buf = [0u8; 1024];
        let axes = [
            ax(6, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
            ax(5, 0.1, 2.0, Warp::Log, Placement::Endpoint),
        ];
        // Quadratic in the unit coordinates of both axes.
        let s1 = |y: f64| (y / 0.1).ln() / 20f64.ln();
        let f = |x: f64, y: f64| 1.0 + x - 2.0 * x * x + 0.5 * s1(y) * s1(y) - x * s1(y);
        let n = table(&mut buf, axes, Interpolation::CatmullRom, f);
        let v = LutView::parse(&buf[..n]).unwrap();
        for &(x, y) in &[
            (0.01, 0.11),
            (0.5, 0.7),
            (0.93, 1.95),
            (0.3, 0.1),
            (1.0, 2.0),
        ] {
            let got = v.sample2(x as f32, y as f32)[0] as f64;
            assert!(
                (got - f(x, y)).abs() < 2e-5,
                "{x} {y}: {got} vs {}",
                f(x, y)
            );
        }
    }

    #[test]
    fn warps_invert() {
        for a in [
            ax(9, 0.05, 1.0, Warp::Log, Placement::Endpoint),
            ax(9, 0.0, 1.0, Warp::Sqrt, Placement::TexelCentre),
            ax(
                9,
                0.0,
                core::f64::consts::FRAC_PI_2,
                Warp::Cos,
                Placement::Endpoint,
            ),
            ax(
                9,
                0.0,
                core::f64::consts::FRAC_PI_2,
                Warp::SqrtCos,
                Placement::Endpoint,
            ),
        ] {
            let m = AxisMap::new(&a);
            for i in 0..9 {
                let t = m.index(a.node(i) as f32);
                assert!((t - i as f32).abs() < 2e-4, "{:?} node {i}: {t}", a.warp);
            }
        }
    }

    #[test]
    fn encode_checks_and_round_trips() {
        let mut buf = [0u8; 1024];
        let axes = [
            ax(3, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
            ax(2, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
        ];
        let n = table(&mut buf, axes, Interpolation::Linear, |x, y| x + y);
        let v = LutView::parse(&buf[..n]).unwrap();
        assert_eq!(v.payload().len(), 3 * 2 * 4);
        assert_eq!(v.header_len() + 24, n);
        assert_eq!(v.node_value(5, 0), 2.0);
        assert!(v.node_value(6, 0).is_nan() && v.node_value(0, 1).is_nan());
        let mut small = [0u8; 16];
        let h = v.header().clone();
        assert_eq!(
            encode_into(&h, v.payload(), &mut small),
            Err(LutError::BufferTooSmall)
        );
        assert!(matches!(
            encode_into(&h, &v.payload()[..8], &mut [0u8; 1024]),
            Err(LutError::PayloadLength { .. })
        ));
    }
}

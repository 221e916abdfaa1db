//! The zero-copy, allocation-free view of a LUT file (format: `docs/lut-format.md`).
//!
//! ```text
//! file = magic ++ version ++ header ++ payload
//! ```
//!
//! [`LutView::parse`] validates a borrowed `&[u8]` (magic, version, header, limits, the f32
//! rules of the axes, payload length, CRC-32, node values) and keeps only borrows, so
//! firmware can `include_bytes!` a table straight from flash. Queries take physical
//! coordinates (radians, μ, roughness, σ), clamp them to each axis' range and interpolate in
//! the axes' unit coordinates ([`Interpolation`]).

use crate::axis::AxisMap;
use crate::codec::{Reader as Decoder, Writer};
use crate::crc::Crc32;
use crate::header::*;
use crate::lookup::{Grid, Lane, Reader, Values};
use crate::LutError;

/// A validated, borrowed LUT.
#[derive(Clone, Copy, Debug)]
pub struct LutView<'a> {
    bytes: &'a [u8],
    header: Header<'a>,
    header_len: usize,
    payload: &'a [u8],
    grid: Grid,
    reader: Reader,
}

/// An integer whose order is the IEEE order of finite (and infinite) f64 values, −0 = +0:
/// the magnitude bits, negated for a set sign bit. The header checks compare with it so that
/// a target without a double-precision FPU links no soft-float comparisons for them.
/// Meaningless for NaN (the callers test `is_finite` first).
fn order_key(x: f64) -> i64 {
    let b = x.to_bits() as i64;
    if b < 0 {
        // b = i64::MIN + magnitude → −magnitude (−0.0 → 0).
        i64::MIN.wrapping_sub(b)
    } else {
        b
    }
}

/// Every check of the header alone (docs/lut-format.md §4–§6).
pub(crate) fn check_header(h: &Header<'_>) -> Result<(), LutError> {
    use LutError::Inconsistent as I;
    if h.axes.is_empty() {
        return Err(I("no axes"));
    }
    if h.channels.is_empty() {
        return Err(I("no channels"));
    }
    for (k, a) in h.axes.iter().enumerate() {
        if a.count < 2 || a.count > MAX_AXIS_COUNT {
            return Err(I("axis count outside [2, 65536]"));
        }
        let (lo, hi) = (order_key(a.lo), order_key(a.hi));
        if !(a.lo.is_finite() && a.hi.is_finite() && lo < hi) {
            return Err(I("axis range not finite or not increasing"));
        }
        match a.warp {
            Warp::Log if lo <= 0 => return Err(I("log axis must start above 0")),
            Warp::Cos if lo < 0 || hi > order_key(core::f64::consts::PI) => {
                return Err(I("cos axis must lie in [0, π]"))
            }
            Warp::SqrtCos if lo < 0 || hi > order_key(core::f64::consts::FRAC_PI_2) => {
                return Err(I("sqrt-cos axis must lie in [0, π/2]"))
            }
            _ => {}
        }
        // The f32 rule (docs/lut-format.md §3): the reader's own constants, checked here.
        Lane::new(a, 1).map_err(|why| LutError::DegenerateAxis { axis: k as u8, why })?;
    }
    for c in h.channels.iter() {
        if !(c.scale.is_finite() && c.offset.is_finite()) {
            return Err(I("channel scale or offset not finite"));
        }
        if h.encoding == Encoding::Unorm16 {
            // Decoded values run from offset to offset + scale.
            let top = c.offset + c.scale;
            if !(top.is_finite()
                && c.offset.abs() <= MAX_VALUE_MAGNITUDE
                && top.abs() <= MAX_VALUE_MAGNITUDE)
            {
                return Err(I("u16 channel range exceeds the value limit"));
            }
        }
    }
    let values = h.nodes().saturating_mul(h.channels.len() as u64);
    if values > MAX_VALUES {
        return Err(I("table larger than the format allows"));
    }
    let (d, c) = (h.axes.len(), h.channels.len());
    let ok = h.kind.fits(d, c);
    if !ok {
        return Err(I("axis or channel count does not fit the table kind"));
    }
    h.error.check()?;
    check_integration(h.integration)
}

/// Magic and version; the reader positioned after them.
fn open(bytes: &[u8]) -> Result<Decoder<'_>, LutError> {
    if bytes.len() < 4 {
        return Err(if MAGIC.starts_with(bytes) {
            LutError::Truncated
        } else {
            LutError::BadMagic
        });
    }
    let (magic, rest) = bytes.split_at_checked(4).ok_or(LutError::Truncated)?;
    if magic != MAGIC {
        return Err(LutError::BadMagic);
    }
    let mut r = Decoder::new(rest);
    let version = r.varint(16)? as u16;
    if !(MIN_FORMAT_VERSION..=FORMAT_VERSION).contains(&version) {
        return Err(LutError::UnsupportedVersion { found: version });
    }
    r.version = version;
    Ok(r)
}

/// Length of the encoded header (magic and version included) at the start of `bytes`: where
/// the payload starts. Decodes the header's syntax only (no limits, sizes or CRC), so tools
/// that edit a file (and the fuzz harness, which re-signs mutated files) can locate the
/// checksum: its 4 bytes end the header.
pub fn header_len(bytes: &[u8]) -> Result<usize, LutError> {
    let mut r = open(bytes)?;
    r.header()?;
    Ok(4 + r.pos())
}

impl<'a> LutView<'a> {
    /// Validates `bytes` and borrows them. Never panics and never allocates; every defect
    /// is a [`LutError`]. Work is linear in the length of `bytes`.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::parse_inner(bytes, true)
    }

    /// [`LutView::parse`] without recomputing the CRC-32, for owners of bytes that were
    /// validated before (every other check still runs, so this cannot panic either).
    pub fn parse_skip_checksum(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::parse_inner(bytes, false)
    }

    fn parse_inner(bytes: &'a [u8], crc: bool) -> Result<Self, LutError> {
        let mut r = open(bytes)?;
        let header = r.header()?;
        let header_len = 4 + r.pos();
        // The decoder consumed header_len − 4 ≥ 4 bytes (the checksum ends the header) of
        // `bytes[4..]`, so both splits exist; `Truncated` keeps the code free of panics.
        let (signed, payload) = bytes
            .split_at_checked(header_len)
            .ok_or(LutError::Truncated)?;
        let signed = signed
            .get(..header_len.saturating_sub(4))
            .ok_or(LutError::Truncated)?;
        check_header(&header)?;
        let expected = header.payload_len();
        if expected != payload.len() as u64 {
            return Err(LutError::PayloadLength {
                expected,
                found: payload.len() as u64,
            });
        }
        if crc {
            let stored = header.checksum;
            let computed = Crc32::new().update(signed).update(payload).finish();
            if stored != computed {
                return Err(LutError::Checksum { stored, computed });
            }
        }
        let grid = Grid::new(&header);
        // Cannot fail after `check_header` (same lane rule); kept total.
        let reader = Reader::new(&header).ok_or(LutError::Inconsistent("axis constants"))?;
        if header.encoding != Encoding::Unorm16 {
            // Float payloads: every decoded value finite and within the value limit.
            // Flat value index k = node × channels + channel, counted without a division.
            let n = payload.len() / header.encoding.bytes();
            let c = grid.channels.max(1);
            let (mut node, mut ch) = (0usize, 0usize);
            for k in 0..n {
                let v = grid.node_value(payload, node, ch);
                if v.is_nan() || v.abs() > MAX_VALUE_MAGNITUDE {
                    return Err(LutError::BadValue { index: k as u64 });
                }
                ch += 1;
                if ch == c {
                    ch = 0;
                    node += 1;
                }
            }
        }
        Ok(Self {
            bytes,
            header,
            header_len,
            payload,
            grid,
            reader,
        })
    }

    pub(crate) fn grid(&self) -> &Grid {
        &self.grid
    }
    pub(crate) fn reader(&self) -> &Reader {
        &self.reader
    }

    /// The whole file.
    pub fn bytes(&self) -> &'a [u8] {
        self.bytes
    }
    /// The decoded header.
    pub fn header(&self) -> &Header<'a> {
        &self.header
    }
    /// Length of the encoded header in bytes, magic and version included (the payload
    /// starts here).
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
        self.grid.dims
    }
    /// Number of channels (1–4).
    pub fn channels(&self) -> usize {
        self.grid.channels
    }
    /// The coordinate map of axis `k`; `None` if `k ≥ dims()`.
    pub fn axis_map(&self, k: usize) -> Option<&AxisMap> {
        self.grid.maps.iter().take(self.grid.dims).nth(k)
    }

    /// The decoded value at a flat node index (axis 0 fastest) and channel. Out-of-range
    /// indices give NaN.
    pub fn node_value(&self, flat: usize, ch: usize) -> f32 {
        self.grid.node_value(self.payload, flat, ch)
    }

    /// Interpolated channel values at physical coordinates `x` (one per axis; missing
    /// coordinates count as the axis' lower end, extra ones are ignored). Coordinates are
    /// clamped to each axis' range; a NaN coordinate gives NaN in every channel. The same
    /// prepared reader as the typed tables, so the values are theirs bit for bit (G tables
    /// before the G clamp to [0, 1]), with one exception: on hosted targets `GTable3` reads
    /// the log-warped σ axis of a linear u16 table (the speed tier) with an inline
    /// logarithm, which moves σ's node fraction by less than 1e-4 of a cell (so G by less
    /// than 1e-4; `tests/view_agrees.rs`).
    pub fn sample(&self, x: &[f32]) -> Values {
        let at = |k: usize| x.get(k).copied().unwrap_or(f32::NEG_INFINITY);
        if (0..self.grid.dims).any(|k| at(k).is_nan()) {
            return [f32::NAN; MAX_CHANNELS];
        }
        let (g, p, r) = (&self.grid, self.payload, &self.reader);
        let mut out = [0.0; MAX_CHANNELS];
        macro_rules! go {
            ($d:literal, $c:literal, $x:expr) => {
                out[..$c].copy_from_slice(&r.sample::<$d, $c>(g, p, $x))
            };
        }
        let (x0, x1, x2) = (at(0), at(1), at(2));
        // The shapes the table kinds allow (checked at parse); anything else cannot occur
        // and takes the general path.
        match (g.dims, g.channels) {
            (1, 1) => go!(1, 1, [x0]),
            (2, 1) => go!(2, 1, [x0, x1]),
            (2, 2) => go!(2, 2, [x0, x1]),
            (3, 1) => go!(3, 1, [x0, x1, x2]),
            (3, 2) => go!(3, 2, [x0, x1, x2]),
            _ => return g.sample(p, x),
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

/// Writes `magic ++ version ++ header ++ payload` into `out` with the checksum filled in
/// (the `checksum` field of `header` is ignored). Returns the number of bytes written. The
/// header is checked as a reader would check it. No allocation.
pub fn encode_into(header: &Header<'_>, payload: &[u8], out: &mut [u8]) -> Result<usize, LutError> {
    check_header(header)?;
    if header.payload_len() != payload.len() as u64 {
        return Err(LutError::PayloadLength {
            expected: header.payload_len(),
            found: payload.len() as u64,
        });
    }
    let mut w = Writer::new(out);
    w.header(header)?;
    let hl = w.pos();
    w.bytes(payload)?;
    let total = w.pos();
    let crc = Crc32::new().update(&out[..hl - 4]).update(payload).finish();
    out[hl - 4..hl].copy_from_slice(&crc.to_le_bytes());
    // A float payload must pass the same value check as on reading.
    LutView::parse_skip_checksum(&out[..total])?;
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

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
            kind: TableKind::DirectionalAlbedo,
            axes: List::from_slice(&axes).unwrap(),
            channels: List::from_slice(&[Channel {
                name: "E",
                scale: 1.0,
                offset: 0.0,
            }])
            .unwrap(),
            encoding: Encoding::F32,
            interpolation: interp,
            generator: Generator {
                model: Model::GgxSmithCorrelated,
                convention: Convention::Reciprocal,
                sigma: None,
                nodes: List::new(),
                tool: "test",
            },
            error: ErrorStats {
                max_abs: 0.0,
                rms: 0.0,
                samples: 0,
                seed: 0,
            },
            integration: None,
            checksum: 0,
        };
        encode_into(&h, &payload[..len], buf).unwrap()
    }

    use crate::testing::axis as ax;

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
    fn catmull_rom_tables_with_short_axes_interpolate_linearly_there() {
        // Axis 0 has 2 nodes (linear by the format's rule), axis 1 has 3 (Catmull–Rom with
        // both ends extrapolated quadratically): f = 1 + 2x + y² is reproduced exactly.
        let mut buf = [0u8; 1024];
        let axes = [
            ax(2, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
            ax(3, 0.0, 2.0, Warp::Linear, Placement::Endpoint),
        ];
        let f = |x: f64, y: f64| 1.0 + 2.0 * x + y * y / 4.0;
        let n = table(&mut buf, axes, Interpolation::CatmullRom, f);
        let v = LutView::parse(&buf[..n]).unwrap();
        for &(x, y) in &[(0.0f32, 0.0f32), (0.3, 0.7), (1.0, 2.0), (0.5, 1.9)] {
            let got = v.sample2(x, y)[0] as f64;
            let want = f(x as f64, y as f64);
            assert!((got - want).abs() < 1e-5, "({x}, {y}): {got} vs {want}");
        }
    }

    /// A flat index past the nodes, up to `usize::MAX`, gives NaN: no overflow panic, and
    /// no wrapped byte offset landing on a real node (2⁶² + 1 four-byte values wrap to
    /// offset 4, node 1, on 64-bit targets).
    /// A linear 3 × 2 table over [0, 1]² whose node (i, j) holds x + y = i/2 + j, in `buf`;
    /// its length.
    fn sum_table(buf: &mut [u8]) -> usize {
        let axes = [
            ax(3, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
            ax(2, 0.0, 1.0, Warp::Linear, Placement::Endpoint),
        ];
        table(buf, axes, Interpolation::Linear, |x, y| x + y)
    }

    #[test]
    fn node_value_past_the_nodes_is_nan() {
        let mut buf = [0u8; 1024];
        // Node (i, j) holds i/2 + j: flat 1 (i = 1, j = 0) is 0.5, the last (5) is 2.
        let n = sum_table(&mut buf);
        let v = LutView::parse(&buf[..n]).unwrap();
        assert_eq!((v.node_value(1, 0), v.node_value(5, 0)), (0.5, 2.0));
        let wraps = (usize::MAX / 4).wrapping_add(2);
        for flat in [
            6,
            7,
            wraps,
            usize::MAX / 4,
            usize::MAX / 2,
            usize::MAX - 1,
            usize::MAX,
        ] {
            for ch in [0, 1, usize::MAX] {
                assert!(v.node_value(flat, ch).is_nan(), "node {flat} channel {ch}");
            }
        }
    }

    #[test]
    fn order_key_orders_like_ieee() {
        // Against f64's own comparison on values spanning signs, zeros, subnormals and
        // infinities.
        let v = [
            f64::NEG_INFINITY,
            -f64::MAX,
            -1.5,
            -f64::MIN_POSITIVE,
            -5e-324,
            -0.0,
            0.0,
            5e-324,
            f64::MIN_POSITIVE,
            1.0,
            core::f64::consts::PI,
            f64::MAX,
            f64::INFINITY,
        ];
        for &a in &v {
            for &b in &v {
                assert_eq!(order_key(a) < order_key(b), a < b, "{a} < {b}");
                assert_eq!(order_key(a) <= order_key(b), a <= b, "{a} <= {b}");
            }
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
        let n = sum_table(&mut buf);
        let v = LutView::parse(&buf[..n]).unwrap();
        assert_eq!(v.payload().len(), 3 * 2 * 4);
        assert_eq!(v.header_len() + 24, n);
        assert_eq!(v.node_value(5, 0), 2.0);
        assert!(v.node_value(6, 0).is_nan() && v.node_value(0, 1).is_nan());
        let mut small = [0u8; 16];
        let h = *v.header();
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

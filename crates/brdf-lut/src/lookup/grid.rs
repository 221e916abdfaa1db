//! The per-tap general path of the lookup: every table a specialised loop of the engine
//! does not take (Catmull–Rom axes of 2 or 3 nodes; with feature `compact`, float
//! payloads), tap by tap from the axis maps' weights.

use crate::axis::AxisMap;
use crate::f16::f16_to_f32;
use crate::header::{Encoding, Header, Interpolation, MAX_AXES, MAX_CHANNELS};

/// Channel values returned by a lookup; entries past [`LutView::channels`](crate::LutView::channels) are 0.
pub type Values = [f32; MAX_CHANNELS];

/// What a lookup needs from the header, in f32, without borrows (the prepared form a typed
/// table keeps next to its bytes).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Grid {
    pub(crate) maps: [AxisMap; MAX_AXES],
    pub(crate) dims: usize,
    pub(crate) channels: usize,
    pub(crate) encoding: Encoding,
    pub(crate) cubic: bool,
    pub(crate) scale: [f32; MAX_CHANNELS],
    pub(crate) offset: [f32; MAX_CHANNELS],
}

impl Grid {
    /// The prepared form of a checked header.
    pub(crate) fn new(h: &Header<'_>) -> Self {
        let mut maps = [AxisMap::UNIT; MAX_AXES];
        for (m, a) in maps.iter_mut().zip(h.axes.iter()) {
            *m = AxisMap::new(a);
        }
        let (mut scale, mut offset) = ([1.0; MAX_CHANNELS], [0.0; MAX_CHANNELS]);
        for ((s, o), c) in scale
            .iter_mut()
            .zip(offset.iter_mut())
            .zip(h.channels.iter())
        {
            *s = c.scale;
            *o = c.offset;
        }
        Grid {
            maps,
            dims: h.axes.len(),
            channels: h.channels.len(),
            encoding: h.encoding,
            cubic: h.interpolation == Interpolation::CatmullRom,
            scale,
            offset,
        }
    }

    /// The decoded value at a flat node index and channel; NaN when out of range.
    #[inline]
    pub(crate) fn node_value(&self, payload: &[u8], flat: usize, ch: usize) -> f32 {
        let c = self.channels;
        if ch >= c {
            return f32::NAN;
        }
        let nb = self.encoding.bytes();
        // Checked: a flat index past the nodes (up to usize::MAX) is out of range, not an
        // overflow.
        let Some(off) = flat
            .checked_mul(c)
            .and_then(|v| v.checked_add(ch))
            .and_then(|v| v.checked_mul(nb))
        else {
            return f32::NAN;
        };
        let (Some(b), Some(offset), Some(scale)) = (
            off.checked_add(nb).and_then(|end| payload.get(off..end)),
            self.offset.get(ch),
            self.scale.get(ch),
        ) else {
            return f32::NAN;
        };
        let stored = match (self.encoding, b) {
            (Encoding::Unorm16, &[b0, b1]) => u16::from_le_bytes([b0, b1]) as f32 * (1.0 / 65535.0),
            (Encoding::F16, &[b0, b1]) => f16_to_f32(u16::from_le_bytes([b0, b1])),
            (Encoding::F32, &[b0, b1, b2, b3]) => f32::from_le_bytes([b0, b1, b2, b3]),
            // `b` has the encoding's width (taken above).
            _ => return f32::NAN,
        };
        offset + scale * stored
    }

    /// The per-tap general path (Catmull–Rom axes of 2 or 3 nodes; see the module documentation of `lookup`).
    pub(crate) fn sample(&self, payload: &[u8], x: &[f32]) -> Values {
        let d = self.dims;
        let mut taps = [[(0usize, 0f32); 4]; MAX_AXES];
        let mut ntaps = [1usize; MAX_AXES];
        for (k, ((map, t), nt)) in self
            .maps
            .iter()
            .zip(taps.iter_mut())
            .zip(ntaps.iter_mut())
            .enumerate()
            .take(d)
        {
            let xk = x.get(k).copied().unwrap_or(f32::NEG_INFINITY);
            if xk.is_nan() {
                return [f32::NAN; MAX_CHANNELS];
            }
            *nt = map.taps(xk, self.cubic, t);
        }
        let mut out = [0f32; MAX_CHANNELS];
        let c = self.channels;
        let [m0, m1, _] = &self.maps;
        let [t0, t1, t2] = &taps;
        let [n_t0, n_t1, n_t2] = ntaps;
        let n0 = m0.count();
        let n1 = if d > 1 { m1.count() } else { 1 };
        for &(i2, w2) in t2.iter().take(n_t2) {
            for &(i1, w1) in t1.iter().take(n_t1) {
                let w21 = if d > 2 { w2 } else { 1.0 } * if d > 1 { w1 } else { 1.0 };
                for &(i0, w0) in t0.iter().take(n_t0) {
                    let w = w21 * w0;
                    let flat = (i2 * n1 + i1) * n0 + i0;
                    for (ch, o) in out.iter_mut().enumerate().take(c) {
                        *o += w * self.node_value(payload, flat, ch);
                    }
                }
            }
        }
        out
    }
}

//! The prepared reader: one lookup for every table kind, with the table's layout fixed once.
//!
//! At preparation every axis becomes a [`Lane`]: the physical coordinate maps to the
//! fractional node index by t = a·w(x) + b, clamped to [0, n − 1], where w is the warp's
//! monotone part (x, ln x, √(x − lo), cos x or √cos x) and a, b fold in the range, the warp's
//! normalisation and the node placement (docs/lut-format.md §6). A query then touches only
//! the payload: the encoding, the channel count, the number of axes and the interpolant are
//! type parameters of the inner loops (decided once per query, not per tap), the taps of an
//! axis are contiguous (linear: 2; Catmull–Rom: 4, the end extrapolation of
//! docs/lut-format.md §7 folded into the weights), each row of taps is one bounds-checked
//! slice, and the channels' scale and offset are applied once at the end (the weights sum
//! to 1).
//!
//! Feature `compact` (for size budgets: the WASM module, firmware): only `Unorm16` payloads
//! get the specialised loops; `F16`/`F32` tables take the per-tap general path (the same
//! values up to f32 summation order).
//!
//! Inlining: forced on hosted targets (speed); left to the optimiser on bare metal and
//! WebAssembly, where code size has a budget.
//!
//! Arithmetic (the same for every kind, so batch and scalar lookups agree bit for bit):
//! linear interpolation nests v = v₀ + f (v₁ − v₀) from axis 0 outward; Catmull–Rom sums
//! Σ_j w1_j Σ_i w0_i v_ij per plane and Σ_k w2_k · plane_k over σ. A Catmull–Rom axis with
//! 2 or 3 nodes has no contiguous 4-tap window; such (unusual) tables are read by the
//! per-tap general path of [`Grid`], which gives the same values up to
//! f32 summation order.

use crate::axis::clamp;
use crate::f16::f16_to_f32;
use crate::header::{Axis, Encoding, Header, Interpolation, Placement, Warp, MAX_CHANNELS};

/// Chunked Catmull–Rom lookups for the batch entry points.
#[cfg(all(hosted, not(feature = "compact")))]
mod cubic;
mod grid;
/// All `core::arch` code (hosted targets).
#[cfg(hosted)]
pub(crate) mod simd;

pub(crate) use grid::Grid;
pub use grid::Values;
#[cfg(all(hosted, feature = "std", target_arch = "x86_64"))]
use simd::gather_words;
#[cfg(all(hosted, test, feature = "std"))]
pub(crate) use simd::BASELINE_ONLY;
#[cfg(hosted)]
pub(crate) use simd::{clamp_s, wide};
#[cfg(hosted)]
use simd::{min_s, sqrt_v, trunc_small};

/// cos x for x ∈ [0, π/2] as sin(π/2 − x) by its Taylor series to r¹¹ (truncation < 1e-9,
/// relative accuracy kept near π/2 where √cos x is steep). Only for the table warp, where an
/// error of a few 1e-8 moves the interpolation point by < 1e-4 of a cell.
#[cfg_attr(not(hosted), inline)]
#[cfg_attr(hosted, inline(always))]
fn cos_quadrant(x: f32) -> f32 {
    let r = core::f32::consts::FRAC_PI_2 - x;
    let r2 = r * r;
    r * (1.0
        + r2 * (-1.0 / 6.0
            + r2 * (1.0 / 120.0
                + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362_880.0 + r2 * (-1.0 / 39_916_800.0))))))
}

/// max(c, 0) with NaN staying NaN (one instruction; `f32::max` would turn NaN into 0 and
/// the lookup of a NaN coordinate into a number).
#[inline(always)]
fn nonneg(c: f32) -> f32 {
    if c < 0.0 {
        0.0
    } else {
        c
    }
}

/// The warp's monotone part w(x) (x already clamped to the axis range).
#[cfg_attr(not(hosted), inline)]
#[cfg_attr(hosted, inline(always))]
fn warp_w(warp: Warp, lo: f32, x: f32) -> f32 {
    match warp {
        Warp::Linear => x,
        // The axis lies within [0, π/2] (checked when the header was parsed); NaN stays NaN.
        Warp::SqrtCos => libm::sqrtf(nonneg(cos_quadrant(x))),
        Warp::Log => libm::logf(x),
        // x ≥ lo, so x − lo ≥ 0 (and NaN stays NaN).
        Warp::Sqrt => libm::sqrtf(x - lo),
        Warp::Cos => crate::axis::cos(x),
    }
}

/// [`warp_w`] for queries on hosted targets: the warps of the speed tiers (linear, √, √cos:
/// a few instructions) inline, `ln` and `cos` out of line, so that every lookup variant does
/// not carry copies of them.
#[cfg(hosted)]
#[inline(always)]
fn warp_q(warp: Warp, lo: f32, x: f32) -> f32 {
    match warp {
        Warp::Linear => x,
        Warp::Sqrt => libm::sqrtf(x - lo),
        Warp::SqrtCos => libm::sqrtf(nonneg(cos_quadrant(x))),
        _ => warp_far(warp, lo, x),
    }
}
#[cfg(hosted)]
#[inline(never)]
fn warp_far(warp: Warp, lo: f32, x: f32) -> f32 {
    warp_w(warp, lo, x)
}

// Devices: one copy of the warp (code size has a budget there).
#[cfg(not(hosted))]
use warp_w as warp_q;

/// One axis: physical coordinate → fractional node index.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lane {
    pub(crate) warp: Warp,
    pub(crate) lo: f32,
    pub(crate) hi: f32,
    pub(crate) a: f32,
    pub(crate) b: f32,
    /// n − 1.
    pub(crate) last: f32,
    /// n − 2, the last cell.
    #[cfg(not(hosted))]
    last_cell: i32,
    /// n − 2 as f32 (hosted targets: the node is found in f32, see [`Lane::cell`]).
    #[cfg(hosted)]
    last_cell_f: f32,

    /// Values (nodes × channels) between neighbouring nodes of this axis.
    pub(crate) stride: usize,
    pub(crate) n: usize,
}

impl Lane {
    /// The lane of an axis, or which part of the f32 rule of docs/lut-format.md §3 it
    /// breaks (every constant finite, the warped span and the scale non-zero).
    pub(crate) fn new(axis: &Axis<'_>, stride: usize) -> Result<Self, &'static str> {
        let (lo, hi) = (axis.lo as f32, axis.hi as f32);
        if !(lo.is_finite() && hi.is_finite()) {
            return Err("range end overflows f32");
        }
        if lo >= hi {
            return Err("range collapses to one f32 value");
        }
        let nf = axis.count as f32;
        // t = s·A + B with s the unit coordinate.
        let (big_a, big_b) = match axis.placement {
            Placement::Endpoint => (nf - 1.0, 0.0),
            Placement::TexelCentre => (nf, -0.5),
        };
        // s = (w(x) − w(lo)) / (w(hi) − w(lo)), w monotone.
        let (w0, w1) = (warp_w(axis.warp, lo, lo), warp_w(axis.warp, lo, hi));
        if !(w0.is_finite() && w1.is_finite()) {
            return Err("warped range end not finite in f32");
        }
        let span = w1 - w0;
        if !(span.is_finite() && span != 0.0) {
            return Err("warped span is zero or not finite in f32");
        }
        let a = big_a / span;
        let b = big_b - a * w0;
        if !(a.is_finite() && a != 0.0 && b.is_finite()) {
            return Err("index scale n / span overflows f32");
        }
        Ok(Lane {
            warp: axis.warp,
            lo,
            hi,
            a,
            b,
            last: nf - 1.0,
            #[cfg(not(hosted))]
            last_cell: axis.count as i32 - 2,
            #[cfg(hosted)]
            last_cell_f: (axis.count as i32 - 2) as f32,

            stride,
            n: axis.count as usize,
        })
    }

    /// For a √cos-warped axis: the same lane taking the warped value w = √cos x instead of
    /// x (a linear lane w ↦ a·w + b over [√cos hi, √cos lo]); `None` for other warps.
    /// The node index equals this lane's up to the rounding of the caller's √cos x.
    #[cfg(hosted)]
    fn prewarped(&self) -> Option<Lane> {
        if self.warp != Warp::SqrtCos {
            return None;
        }
        let (w_lo, w_hi) = (
            warp_w(self.warp, self.lo, self.lo),
            warp_w(self.warp, self.lo, self.hi),
        );
        Some(Lane {
            warp: Warp::Linear,
            lo: w_hi,
            hi: w_lo,
            ..*self
        })
    }

    /// A one-node placeholder for an axis the table does not have.
    const NONE: Lane = Lane {
        warp: Warp::Linear,
        lo: 0.0,
        hi: 1.0,
        a: 0.0,
        b: 0.0,
        last: 0.0,
        #[cfg(not(hosted))]
        last_cell: 0,
        #[cfg(hosted)]
        last_cell_f: 0.0,

        stride: 0,
        n: 1,
    };

    /// The fractional node index of x (x not NaN).
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn index(&self, x: f32) -> f32 {
        let x = clamp(x, self.lo, self.hi);
        clamp(
            self.a * warp_q(self.warp, self.lo, x) + self.b,
            0.0,
            self.last,
        )
    }

    /// Node i ≤ n − 2 and the fraction f ∈ [0, 1] of x.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn cell(&self, x: f32) -> (usize, f32) {
        let t = self.index(x);
        // t ∈ [0, n − 1] with n ≤ 65536: ⌊min(t, n − 2)⌋ = min(⌊t⌋, n − 2) (n − 2 is an
        // integer) by the truncating conversion (t ≥ 0), without saturation checks. NaN
        // takes node n − 2 (and f = NaN).
        // (As u32: the node's zero extension to usize is free.)
        #[cfg(hosted)]
        let i = trunc_small(if t < self.last_cell_f {
            t
        } else {
            self.last_cell_f
        }) as u32;
        // Devices: the form whose code size the firmware budget was measured with.
        #[cfg(not(hosted))]
        let i = (t as i32).min(self.last_cell).max(0);
        (i as usize, t - i as f32)
    }

    /// First node and the four Catmull–Rom weights (docs/lut-format.md §7) of x on an axis
    /// of n ≥ 4 nodes, the end extrapolation folded in.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn cubic(&self, x: f32) -> (usize, [f32; 4]) {
        self.cubic_with(|l| l.cell(x))
    }

    /// [`Lane::cubic`] with the cell `(i, f)` of x from `cell` (always inlined: on devices
    /// too, so that `Lane::cubic` compiles as one function).
    #[inline(always)]
    fn cubic_with(&self, cell: impl FnOnce(&Self) -> (usize, f32)) -> (usize, [f32; 4]) {
        let n = self.n;
        let (i, f) = cell(self);
        let (f2, f3) = (f * f, f * f * f);
        let wm = 0.5 * (-f3 + 2.0 * f2 - f);
        let w0 = 0.5 * (3.0 * f3 - 5.0 * f2 + 2.0);
        let w1 = 0.5 * (-3.0 * f3 + 4.0 * f2 + f);
        let w2 = 0.5 * (f3 - f2);
        if i == 0 {
            // v₋₁ = 3v₀ − 3v₁ + v₂, folded into nodes 0..2.
            (0, [w0 + 3.0 * wm, w1 - 3.0 * wm, w2 + wm, 0.0])
        } else if i == n - 2 {
            // v_n = 3v_{n−1} − 3v_{n−2} + v_{n−3}, folded into nodes n−3..n−1.
            (n - 4, [0.0, wm + w2, w0 - 3.0 * w2, w1 + 3.0 * w2])
        } else {
            (i - 1, [wm, w0, w1, w2])
        }
    }
}

/// How stored numbers become f32 (before the channel's scale and offset).
trait Store {
    const BYTES: usize;
    /// Stored number `k` of `b`. Callers pass a row taken with `get` that holds every `k`
    /// they ask for; a short row gives NaN (no panic path), like the other unreadable cases.
    fn at(b: &[u8], k: usize) -> f32;
}
struct U16;
#[cfg_attr(feature = "compact", allow(dead_code))]
struct F16;
#[cfg_attr(feature = "compact", allow(dead_code))]
struct F32;
/// One `Store` impl: `$bytes` bytes per stored number, bound to `[$b, ..]` and turned
/// into f32 by `$decode`.
macro_rules! store {
    ($t:ident, $bytes:literal, [$($b:ident),+], $decode:expr) => {
        impl Store for $t {
            const BYTES: usize = $bytes;
            #[cfg_attr(not(hosted), inline)]
            #[cfg_attr(hosted, inline(always))]
            fn at(b: &[u8], k: usize) -> f32 {
                match b.get($bytes * k..$bytes * k + $bytes) {
                    Some(&[$($b),+]) => $decode,
                    _ => f32::NAN,
                }
            }
        }
    };
}
store!(U16, 2, [b0, b1], u16::from_le_bytes([b0, b1]) as f32);
store!(F16, 2, [b0, b1], f16_to_f32(u16::from_le_bytes([b0, b1])));
store!(
    F32,
    4,
    [b0, b1, b2, b3],
    f32::from_le_bytes([b0, b1, b2, b3])
);

/// The reader's specialised loop for its layout: `$r.$lin` (linear) or `$r.$cub`
/// (Catmull–Rom) called with `$args`, its generic arguments the [`Store`] of the encoding
/// (`U16`; `F16` and `F32` only without feature `compact`) followed by the given ones
/// (`cubic::<D, C>`); `$other` for every other layout (short Catmull–Rom axes, and with
/// `compact` float payloads).
macro_rules! by_layout {
    ($r:expr, $lin:ident | $cub:ident $(::<$($g:ident),*>)? ($($args:expr),*), $other:block) => {
        match ($r.mode, $r.encoding) {
            (Mode::Linear, Encoding::Unorm16) => $r.$lin::<U16 $($(, $g)*)?>($($args),*),
            (Mode::Cubic, Encoding::Unorm16) => $r.$cub::<U16 $($(, $g)*)?>($($args),*),
            #[cfg(not(feature = "compact"))]
            (Mode::Linear, Encoding::F16) => $r.$lin::<F16 $($(, $g)*)?>($($args),*),
            #[cfg(not(feature = "compact"))]
            (Mode::Linear, Encoding::F32) => $r.$lin::<F32 $($(, $g)*)?>($($args),*),
            #[cfg(not(feature = "compact"))]
            (Mode::Cubic, Encoding::F16) => $r.$cub::<F16 $($(, $g)*)?>($($args),*),
            #[cfg(not(feature = "compact"))]
            (Mode::Cubic, Encoding::F32) => $r.$cub::<F32 $($(, $g)*)?>($($args),*),
            _ => $other,
        }
    };
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    Linear,
    Cubic,
    /// A Catmull–Rom axis of 2 or 3 nodes: the per-tap general path.
    General,
}

/// The per-table constants of a lookup.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Reader {
    pub(crate) lanes: [Lane; 3],
    pub(crate) encoding: Encoding,
    pub(crate) mode: Mode,
    /// Per channel: value = offset + scale × stored (u16: scale already divided by 65535).
    pub(crate) scale: [f32; MAX_CHANNELS],
    pub(crate) offset: [f32; MAX_CHANNELS],
}

impl Reader {
    /// The reader of a checked header; `None` if an axis breaks the f32 rule.
    pub(crate) fn new(h: &Header<'_>) -> Option<Self> {
        let c = h.channels.len();
        let mut lanes = [Lane::NONE; 3];
        let mut stride = c;
        let mut mode = match h.interpolation {
            Interpolation::Linear => Mode::Linear,
            Interpolation::CatmullRom => Mode::Cubic,
        };
        for (k, a) in h.axes.iter().enumerate().take(3) {
            lanes[k] = Lane::new(a, stride).ok()?;
            stride = stride.checked_mul(a.count as usize)?;
            if mode == Mode::Cubic && a.count < 4 {
                mode = Mode::General;
            }
        }
        let q = if h.encoding == Encoding::Unorm16 {
            1.0 / 65535.0
        } else {
            1.0
        };
        let (mut scale, mut offset) = ([1.0; MAX_CHANNELS], [0.0; MAX_CHANNELS]);
        for ((s, o), ch) in scale
            .iter_mut()
            .zip(offset.iter_mut())
            .zip(h.channels.iter())
        {
            *s = ch.scale * q;
            *o = ch.offset;
        }
        Some(Reader {
            lanes,
            encoding: h.encoding,
            mode,
            scale,
            offset,
        })
    }

    /// Interpolated channels at x (D = the table's axes, C = its channels; x not NaN).
    /// Out-of-range payload reads (impossible for a validated table) give NaN.
    ///
    /// Hosted targets test for the speed tiers' case (linear, u16) first and always inline
    /// it; the other cases follow, inlined or not as the optimiser decides (the same
    /// arithmetic either way).
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn sample<const D: usize, const C: usize>(
        &self,
        grid: &Grid,
        data: &[u8],
        x: [f32; D],
    ) -> [f32; C] {
        #[cfg(hosted)]
        if self.mode == Mode::Linear && self.encoding == Encoding::Unorm16 {
            return self.finish(self.linear::<U16, D, C>(data, x));
        }
        self.sample_any(grid, data, x)
    }

    /// Channel scale and offset applied to values in stored units.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn finish<const C: usize>(&self, raw: [f32; C]) -> [f32; C] {
        let mut out = [0.0; C];
        for c in 0..C {
            out[c] = self.offset[c] + self.scale[c] * raw[c];
        }
        out
    }

    /// [`Reader::sample`] for every layout.
    #[inline]
    fn sample_any<const D: usize, const C: usize>(
        &self,
        grid: &Grid,
        data: &[u8],
        x: [f32; D],
    ) -> [f32; C] {
        let raw = by_layout!(self, linear | cubic::<D, C>(data, x), {
            let v = grid.sample(data, &x);
            let mut out = [0.0; C];
            out.copy_from_slice(&v[..C]);
            return out;
        });
        self.finish(raw)
    }

    /// Two one-channel 3-D lookups that share the last coordinate (the two one-sided factors
    /// of G over σ): the σ taps are computed once. Equal to two [`Reader::sample`] calls.
    /// `IN_RANGE`: a and b lie in the ranges of axes 0 and 1 already (hosted targets skip
    /// their clamp; the same values).
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn pair3<const IN_RANGE: bool>(
        &self,
        grid: &Grid,
        data: &[u8],
        a: [f32; 2],
        b: [f32; 2],
        z: f32,
    ) -> (f32, f32) {
        #[cfg(hosted)]
        if self.chunked() {
            // Both sides side by side (the same arithmetic as `pair3_linear`).
            let [va, vb] = self.chunk3_in::<2, IN_RANGE>(
                &self.lanes[0],
                data,
                &[[a[0], b[0]], [a[1], b[1]]],
                z,
                false,
            );
            return (va, vb);
        }
        self.pair3_any(grid, data, a, b, z)
    }

    /// [`Reader::pair3`] for every layout.
    #[inline]
    fn pair3_any(&self, grid: &Grid, data: &[u8], a: [f32; 2], b: [f32; 2], z: f32) -> (f32, f32) {
        let (va, vb) = by_layout!(self, pair3_linear | pair3_cubic(data, a, b, z), {
            return (
                self.sample::<3, 1>(grid, data, [a[0], a[1], z])[0],
                self.sample::<3, 1>(grid, data, [b[0], b[1], z])[0],
            );
        });
        (
            self.offset[0] + self.scale[0] * va,
            self.offset[0] + self.scale[0] * vb,
        )
    }

    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn pair3_linear<S: Store>(&self, data: &[u8], a: [f32; 2], b: [f32; 2], z: f32) -> (f32, f32) {
        let l = &self.lanes;
        let (k, f2) = l[2].cell(z);
        let one = |x: [f32; 2]| {
            let (i0, f0) = l[0].cell(x[0]);
            let (i1, f1) = l[1].cell(x[1]);
            let at = i0 + i1 * l[1].stride + k * l[2].stride;
            #[cfg(hosted)]
            let plane = |at: usize| Self::plane::<S, 1>(data, at, l[1].stride, f0, f1)[0];
            #[cfg(not(hosted))]
            let plane = |at: usize| {
                let lo = Self::row::<S, 1>(data, at, f0);
                let hi = Self::row::<S, 1>(data, at + l[1].stride, f0);
                Self::lerp(lo, hi, f1)[0]
            };
            let (p0, p1) = (plane(at), plane(at + l[2].stride));
            p0 + f2 * (p1 - p0)
        };
        (one(a), one(b))
    }

    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn pair3_cubic<S: Store>(&self, data: &[u8], a: [f32; 2], b: [f32; 2], z: f32) -> (f32, f32) {
        let l = &self.lanes;
        let (b2, w2) = l[2].cubic(z);
        let one = |x: [f32; 2]| {
            let (b0, w0) = l[0].cubic(x[0]);
            let (b1, w1) = l[1].cubic(x[1]);
            let at = b0 + b1 * l[1].stride;
            let mut acc = 0.0;
            for (k, &wk) in w2.iter().enumerate() {
                if wk != 0.0 {
                    let mut p = 0.0;
                    for (j, wj) in w1.iter().enumerate() {
                        let start = at + j * l[1].stride + (b2 + k) * l[2].stride;
                        let Some(q) = data.get(start * S::BYTES..(start + 4) * S::BYTES) else {
                            return f32::NAN;
                        };
                        let mut r = 0.0;
                        for (i, wi) in w0.iter().enumerate() {
                            r += wi * S::at(q, i);
                        }
                        p += wj * r;
                    }
                    acc += wk * p;
                }
            }
            acc
        };
        (one(a), one(b))
    }

    /// Two neighbouring nodes (all channels) starting at value index `at`.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn pair<S: Store, const C: usize>(data: &[u8], at: usize) -> Option<([f32; C], [f32; C])> {
        let p = data.get(at * S::BYTES..(at + 2 * C) * S::BYTES)?;
        let (mut a, mut b) = ([0.0; C], [0.0; C]);
        for c in 0..C {
            a[c] = S::at(p, c);
            b[c] = S::at(p, C + c);
        }
        Some((a, b))
    }

    /// Linear along axis 0 in the row starting at value index `at`.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn row<S: Store, const C: usize>(data: &[u8], at: usize, f: f32) -> [f32; C] {
        match Self::pair::<S, C>(data, at) {
            Some((a, b)) => Self::lerp(a, b, f),
            None => [f32::NAN; C],
        }
    }

    /// Bilinear in the plane of the 2 × 2 nodes starting at value index `at`, rows `s` values
    /// apart: one bounds-checked block of the payload for both rows.
    #[cfg(hosted)]
    #[inline(always)]
    fn plane<S: Store, const C: usize>(
        data: &[u8],
        at: usize,
        s: usize,
        f0: f32,
        f1: f32,
    ) -> [f32; C] {
        let (s, w) = (s * S::BYTES, 2 * C * S::BYTES);
        let Some(blk) = data.get(at * S::BYTES..at * S::BYTES + s + w) else {
            return [f32::NAN; C];
        };
        let (lo, hi) = (blk.get(..w), blk.get(s..s + w));
        let mut v = [f32::NAN; C];
        if let (Some(lo), Some(hi)) = (lo, hi) {
            for (c, vc) in v.iter_mut().enumerate() {
                let (a0, a1) = (S::at(lo, c), S::at(lo, C + c));
                let (b0, b1) = (S::at(hi, c), S::at(hi, C + c));
                let r0 = a0 + f0 * (a1 - a0);
                let r1 = b0 + f0 * (b1 - b0);
                *vc = r0 + f1 * (r1 - r0);
            }
        }
        v
    }

    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn lerp<const C: usize>(a: [f32; C], b: [f32; C], f: f32) -> [f32; C] {
        let mut v = [0.0; C];
        for c in 0..C {
            v[c] = a[c] + f * (b[c] - a[c]);
        }
        v
    }

    /// (Bi/tri)linear in stored units.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn linear<S: Store, const D: usize, const C: usize>(
        &self,
        data: &[u8],
        x: [f32; D],
    ) -> [f32; C] {
        let l = &self.lanes;
        let (i0, f0) = l[0].cell(x[0]);
        if D == 1 {
            return Self::row::<S, C>(data, i0 * C, f0);
        }
        let (i1, f1) = l[1].cell(x[1]);
        let at = i0 * C + i1 * l[1].stride;
        #[cfg(hosted)]
        let plane = |at: usize| Self::plane::<S, C>(data, at, l[1].stride, f0, f1);
        // Devices: one bounds check per row (the form the firmware budget was measured
        // with; the same values).
        #[cfg(not(hosted))]
        let plane = |at: usize| {
            let lo = Self::row::<S, C>(data, at, f0);
            let hi = Self::row::<S, C>(data, at + l[1].stride, f0);
            Self::lerp(lo, hi, f1)
        };
        if D == 2 {
            return plane(at);
        }
        let (i2, f2) = l[2].cell(x[2]);
        let at = at + i2 * l[2].stride;
        Self::lerp(plane(at), plane(at + l[2].stride), f2)
    }

    /// Catmull–Rom in stored units.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn cubic<S: Store, const D: usize, const C: usize>(
        &self,
        data: &[u8],
        x: [f32; D],
    ) -> [f32; C] {
        let l = &self.lanes;
        let (b0, w0) = l[0].cubic(x[0]);
        let row = |at: usize| -> [f32; C] {
            let Some(p) = data.get(at * S::BYTES..(at + 4 * C) * S::BYTES) else {
                return [f32::NAN; C];
            };
            let mut r = [0.0; C];
            for (i, wi) in w0.iter().enumerate() {
                for (c, rc) in r.iter_mut().enumerate() {
                    *rc += wi * S::at(p, i * C + c);
                }
            }
            r
        };
        if D == 1 {
            return row(b0 * C);
        }
        let (b1, w1) = l[1].cubic(x[1]);
        let patch = |at: usize| -> [f32; C] {
            let mut acc = [0.0; C];
            for (j, wj) in w1.iter().enumerate() {
                let r = row(at + j * l[1].stride);
                for (a, rc) in acc.iter_mut().zip(r) {
                    *a += wj * rc;
                }
            }
            acc
        };
        let at = b0 * C + b1 * l[1].stride;
        if D == 2 {
            return patch(at);
        }
        let (b2, w2) = l[2].cubic(x[2]);
        let mut acc = [0.0; C];
        for (k, &wk) in w2.iter().enumerate() {
            if wk != 0.0 {
                let p = patch(at + (b2 + k) * l[2].stride);
                for c in 0..C {
                    acc[c] += wk * p[c];
                }
            }
        }
        acc
    }
}

/// Chunked lookups for the batch entry points (hosted targets): `N` queries at once, in
/// stages that are each a loop over the chunk (coordinate maps, then the payload reads, then
/// the blend), so that the compiler turns the arithmetic stages into packed instructions:
/// SSE, or AVX2 where the processor has it (the batch loops are compiled twice and one is
/// picked at run time, see [`wide`]; the payload rows are then read by AVX2 gathers, see
/// [`rows`]). Every query goes through exactly the scalar path's operations
/// ([`Lane::cell`], [`Reader::plane`], the channel scale and offset), so the results are
/// the scalar lookups' bit for bit.
#[cfg(hosted)]
impl Lane {
    /// [`Lane::cell`], with ln x of a log axis by [`ln_fast`] (inline, a few 1e-8 from
    /// libm's: the node index moves by far less than 1e-4 of a cell). For the σ lane of
    /// the 3-D G tables, computed once per query.
    #[inline(always)]
    fn cell_ln(&self, x: f32) -> (usize, f32) {
        if self.warp != Warp::Log || self.lo < f32::MIN_POSITIVE {
            return self.cell(x);
        }
        let x = clamp_s(x, self.lo, self.hi);
        let t = clamp_s(self.a * ln_fast(x) + self.b, 0.0, self.last);
        let i = trunc_small(min_s(t, self.last_cell_f));
        (i as usize, t - i as f32)
    }

    /// [`Lane::cell`] of `N` coordinates; `IN_RANGE`: the caller guarantees x ∈ [lo, hi]
    /// (the clamp would change nothing and is skipped); `MINMAX`: for N ≤ 2, the index
    /// clamp as scalar max/min instructions (the same values; which form the compiler turns
    /// into less code depends on the caller; longer chunks keep the vectorising form).
    #[inline(always)]
    pub(crate) fn cells<const N: usize, const IN_RANGE: bool, const MINMAX: bool>(
        &self,
        x: &[f32; N],
    ) -> ([u32; N], [f32; N]) {
        let (lo, hi) = (self.lo, self.hi);
        let mut w = *x;
        if !IN_RANGE {
            for w in &mut w {
                *w = clamp(*w, lo, hi);
            }
        }
        match self.warp {
            Warp::Linear => {}
            Warp::Sqrt => {
                for w in &mut w {
                    *w = sqrt_v(*w - lo);
                }
            }
            Warp::SqrtCos => {
                for w in &mut w {
                    *w = nonneg(cos_quadrant(*w));
                }
                for w in &mut w {
                    *w = sqrt_v(*w);
                }
            }
            _ => {
                for w in &mut w {
                    *w = warp_far(self.warp, lo, *w);
                }
            }
        }
        // The node ⌊t⌋ (at most n − 2) without a float → int conversion per query (those
        // do not vectorise): t + 2²³ − 2²³ is t rounded to an integer (t < 2¹⁶), one less
        // when that rounded up; the integer is read from the bits of ⌊t⌋ + 2²³. Equal to
        // `cell`'s conversion (both are the exact ⌊t⌋ capped at n − 2), NaN going to node 0.
        const MAGIC: f32 = 8_388_608.0;
        let last_cell = self.last_cell_f;
        let (mut i, mut f) = ([0u32; N], [0.0f32; N]);
        for k in 0..N {
            let t = self.a * w[k] + self.b;
            let t = if MINMAX && N <= 2 {
                clamp_s(t, 0.0, self.last)
            } else {
                clamp(t, 0.0, self.last)
            };
            if N <= 2 {
                // Too few queries for the stages below to pay: ⌊min(t, n − 2)⌋ (t ≥ 0, so the
                // truncating conversion is the floor, and n − 2 is an integer, so this is
                // `cell`'s min(⌊t⌋, n − 2); NaN: node n − 2 and f = NaN).
                let ik = trunc_small(min_s(t, last_cell));
                i[k] = ik as u32;
                f[k] = t - ik as f32;
                continue;
            }
            let tc = if t > 0.0 { t } else { 0.0 };
            let r = (tc + MAGIC) - MAGIC;
            let fl = if r > tc { r - 1.0 } else { r };
            let ik = if fl > last_cell { last_cell } else { fl };
            i[k] = (ik + MAGIC).to_bits().wrapping_sub(MAGIC.to_bits());
            f[k] = t - ik;
        }
        (i, f)
    }
}

#[cfg(hosted)]
impl Reader {
    /// Whether [`Reader::chunk`] applies (linear u16 tables); otherwise callers loop over
    /// the scalar lookup.
    #[inline(always)]
    pub(crate) fn chunked(&self) -> bool {
        self.mode == Mode::Linear && self.encoding == Encoding::Unorm16
    }

    /// Axis 0's lane taking √cos θ instead of θ (see [`Lane::prewarped`]) for
    /// [`Reader::pair_with`]; `None` unless axis 0 is √cos-warped and the table
    /// `chunked()`.
    pub(crate) fn prewarped(&self) -> Option<Lane> {
        if !self.chunked() {
            return None;
        }
        self.lanes[0].prewarped()
    }

    /// Two one-channel lookups (GM and GS sides) of a `chunked()` 2-D (`z` = None) or 3-D
    /// table with `l0` in place of axis 0's lane: [`Reader::chunk`] / [`Reader::pair3`].
    #[inline(always)]
    pub(crate) fn pair_with(
        &self,
        l0: &Lane,
        data: &[u8],
        a: [f32; 2],
        b: [f32; 2],
        z: Option<f32>,
    ) -> (f32, f32) {
        let x = [[a[0], b[0]], [a[1], b[1]]];
        let [va, vb] = match z {
            Some(z) => self.chunk3_in::<2, false>(l0, data, &x, z, false),
            None => self.chunk_in::<2, 1, 2, false, false>(l0, data, &x, false)[0],
        };
        (va, vb)
    }

    /// Whether axes 0 and 1 span exactly θ ∈ [0, π/2] and φ ∈ [−π/2, π/2] in f32 (the
    /// passing-factor convention), so that the in-plane G arguments, already clamped to
    /// those ranges, need no second clamp ([`Reader::chunk_in`], [`Reader::chunk3_in`]).
    pub(crate) fn g_ranges(&self) -> bool {
        use core::f32::consts::FRAC_PI_2;
        let [t, p, _] = &self.lanes;
        (t.lo, t.hi, p.lo, p.hi) == (0.0, FRAC_PI_2, -FRAC_PI_2, FRAC_PI_2)
    }

    /// `N` lookups of a 1-D, 2-D or 3-D linear u16 table (`chunked()` must hold): channel
    /// c of query k in `out[c][k]`, equal to [`Reader::sample`] bit for bit. `avx2`: the
    /// code is compiled for AVX2 (see [`wide`]).
    #[inline(always)]
    pub(crate) fn chunk<const D: usize, const C: usize, const N: usize>(
        &self,
        data: &[u8],
        x: &[[f32; N]; D],
        avx2: bool,
    ) -> [[f32; N]; C] {
        // (D is a constant: the 1-D and 2-D lookups compile without this branch.)
        if D == 3 {
            return self.chunk_3d::<C, N>(data, [&x[0], &x[1], &x[2]], avx2);
        }
        self.chunk_in::<D, C, N, false, false>(&self.lanes[0], data, x, avx2)
    }

    /// [`Reader::chunk`] of a 3-D table: the 2 × 2 × 2 nodes of every query as
    /// four rows of C 32-bit words (two nodes × C channels, stored number m = node × C + c
    /// in word m / 2, the low half if m is even) at value index i₀·C + i₁·s₁ + i₂·s₂ plus
    /// 0, s₁, s₂, s₁ + s₂; then [`Reader::linear`]'s arithmetic: per plane
    /// r = q₀ + f₀ (q₁ − q₀) per row and p = r₀ + f₁ (r₁ − r₀), v = p₀ + f₂ (p₁ − p₀), and
    /// offset + scale · v. A query whose block lies past the payload (impossible for a
    /// parsed table) gives NaN, like the scalar path.
    #[inline(always)]
    fn chunk_3d<const C: usize, const N: usize>(
        &self,
        data: &[u8],
        x: [&[f32; N]; 3],
        avx2: bool,
    ) -> [[f32; N]; C] {
        let l = &self.lanes;
        let (i0, f0) = l[0].cells::<N, false, false>(x[0]);
        let (i1, f1) = l[1].cells::<N, false, false>(x[1]);
        let (i2, f2) = l[2].cells::<N, false, false>(x[2]);
        // Strides in values (payloads hold < 2²⁶ values, so bytes fit in u32).
        let (s1, s2) = (l[1].stride as u32, l[2].stride as u32);
        let mut at = [0u32; N];
        for k in 0..N {
            at[k] = (i0[k] * C as u32 + i1[k] * s1 + i2[k] * s2) * 2;
        }
        let off = [0, 2 * s1, 2 * s2, 2 * (s1 + s2)];
        let (words, bad) = rows::<N, 4, C>(data, &at, off, avx2);
        let mut out = [[0.0f32; N]; C];
        for (c, oc) in out.iter_mut().enumerate() {
            // Stored numbers of nodes 0 and 1 of channel c (word and half of each).
            let (m0, m1) = (c, C + c);
            let half = |w: u32, m: usize| (if m % 2 == 0 { w & 0xffff } else { w >> 16 }) as f32;
            let (sc, of) = (self.scale[c], self.offset[c]);
            for k in 0..N {
                let row = |r: usize| {
                    let (a0, a1) = (half(words[r][m0 / 2][k], m0), half(words[r][m1 / 2][k], m1));
                    let a0 = if r == 0 { a0 + bad[k] } else { a0 };
                    a0 + f0[k] * (a1 - a0)
                };
                let plane = |p: usize| {
                    let (r0, r1) = (row(2 * p), row(2 * p + 1));
                    r0 + f1[k] * (r1 - r0)
                };
                let (p0, p1) = (plane(0), plane(1));
                oc[k] = of + sc * (p0 + f2[k] * (p1 - p0));
            }
        }
        out
    }

    /// [`Reader::chunk`]; `IN_RANGE`: every coordinate lies in its axis' range already.
    #[inline(always)]
    fn chunk_in<
        const D: usize,
        const C: usize,
        const N: usize,
        const IN_RANGE: bool,
        const MINMAX: bool,
    >(
        &self,
        l0: &Lane,
        data: &[u8],
        x: &[[f32; N]; D],
        avx2: bool,
    ) -> [[f32; N]; C] {
        let l = &self.lanes;
        let (i0, f0) = l0.cells::<N, IN_RANGE, MINMAX>(&x[0]);
        let (i1, f1) = if D > 1 {
            l[1].cells::<N, IN_RANGE, MINMAX>(&x[1])
        } else {
            ([0; N], [0.0; N])
        };
        // Stored numbers of the taps: [channel][tap][query], tap = 2 × row + node.
        let mut q = [[[0u32; N]; 4]; C];
        let mut bad = [0.0f32; N];
        let s = l[1].stride * 2;
        // Bytes of a row of taps (2 nodes × C channels) and of the block of both rows.
        let w = 4 * C;
        let span = if D > 1 { s + w } else { w };
        if N > 2 && C <= 2 {
            // Chunks: each row read as C little-endian 32-bit words (two stored numbers
            // each), then split into the stored numbers by one vectorising loop per tap.
            let mut at = [0u32; N];
            for k in 0..N {
                at[k] = (i0[k] * C as u32 + i1[k] * l[1].stride as u32) * 2;
            }
            let off1 = if D > 1 { s as u32 } else { 0 };
            let (words, nan) = rows::<N, 2, C>(data, &at, [0, off1], avx2);
            bad = nan;
            // Stored number m = node × C + channel of a row: word m / 2, low half if m even.
            for (r, wr) in words.iter().enumerate() {
                for m in 0..2 * C {
                    let (c, node) = (m % C, m / C);
                    let (src, dst) = (&wr[m / 2], &mut q[c][2 * r + node]);
                    for k in 0..N {
                        dst[k] = if m % 2 == 0 {
                            src[k] & 0xffff
                        } else {
                            src[k] >> 16
                        };
                    }
                }
            }
        }
        for k in 0..N {
            if N > 2 && C <= 2 {
                break;
            }
            let at = (i0[k] as usize * C + i1[k] as usize * l[1].stride) * 2;
            let rows = data
                .get(at..at + span)
                .and_then(|b| Some((b.get(..w)?, b.get(span - w..)?)));
            match rows {
                Some((r0, r1)) => {
                    for (c, qc) in q.iter_mut().enumerate() {
                        qc[0][k] = u16_at(r0, c) as u32;
                        qc[1][k] = u16_at(r0, C + c) as u32;
                        qc[2][k] = u16_at(r1, c) as u32;
                        qc[3][k] = u16_at(r1, C + c) as u32;
                    }
                }
                // A short payload (impossible for a parsed table) gives NaN, like `plane`.
                None => bad[k] = f32::NAN,
            }
        }
        self.blend::<D, C, N>(&q, &bad, &f0, &f1)
    }

    /// [`Reader::chunk_in`]'s interpolation of the stored numbers `q` ([channel][tap][query],
    /// tap = 2 × row + node; `bad` is NaN for a query whose taps were out of the payload):
    /// r = q₀ + f₀ (q₁ − q₀) per row, v = r₀ + f₁ (r₁ − r₀), then offset + scale · v.
    #[inline(always)]
    fn blend<const D: usize, const C: usize, const N: usize>(
        &self,
        q: &[[[u32; N]; 4]; C],
        bad: &[f32; N],
        f0: &[f32; N],
        f1: &[f32; N],
    ) -> [[f32; N]; C] {
        let mut out = [[0.0f32; N]; C];
        for c in 0..C {
            let (sc, of) = (self.scale[c], self.offset[c]);
            let [q0, q1, q2, q3] = &q[c];
            for k in 0..N {
                let (a0, a1) = (q0[k] as f32 + bad[k], q1[k] as f32);
                let r0 = a0 + f0[k] * (a1 - a0);
                let v = if D > 1 {
                    let (b0, b1) = (q2[k] as f32, q3[k] as f32);
                    let r1 = b0 + f0[k] * (b1 - b0);
                    r0 + f1[k] * (r1 - r0)
                } else {
                    r0
                };
                out[c][k] = of + sc * v;
            }
        }
        out
    }

    /// `N` pairs of one-channel 3-D lookups at one last coordinate z (the σ of a batch of
    /// G queries): [`Reader::pair3`] bit for bit, with the z lane computed once.
    #[inline(always)]
    pub(crate) fn chunk3<const N: usize>(
        &self,
        data: &[u8],
        x: &[[f32; N]; 2],
        z: f32,
        avx2: bool,
    ) -> [f32; N] {
        self.chunk3_in::<N, false>(&self.lanes[0], data, x, z, avx2)
    }

    /// [`Reader::chunk3`]; `IN_RANGE`: every x lies in its axis' range already.
    #[inline(always)]
    pub(crate) fn chunk3_in<const N: usize, const IN_RANGE: bool>(
        &self,
        l0: &Lane,
        data: &[u8],
        x: &[[f32; N]; 2],
        z: f32,
        avx2: bool,
    ) -> [f32; N] {
        let l = &self.lanes;
        let (k2, f2) = l[2].cell_ln(z);
        let (i0, mut f0) = l0.cells::<N, IN_RANGE, true>(&x[0]);
        let (i1, f1) = l[1].cells::<N, IN_RANGE, true>(&x[1]);
        let (s1, s2) = (l[1].stride * 2, l[2].stride * 2);
        let mut q = [[0u32; N]; 8];
        if N > 2 {
            // Chunks: the four rows (2 nodes each) as 32-bit words, split by vectorising
            // loops.
            let mut at = [0u32; N];
            let base = (k2 * l[2].stride) as u32;
            for k in 0..N {
                at[k] = (i0[k] + i1[k] * l[1].stride as u32 + base) * 2;
            }
            let (s1, s2) = (s1 as u32, s2 as u32);
            let ([[w0], [w1], [w2], [w3]], bad) =
                rows::<N, 4, 1>(data, &at, [0, s1, s2, s2 + s1], avx2);
            for (j, w) in [w0, w1, w2, w3].iter().enumerate() {
                for k in 0..N {
                    q[2 * j][k] = w[k] & 0xffff;
                    q[2 * j + 1][k] = w[k] >> 16;
                }
            }
            for k in 0..N {
                f0[k] += bad[k];
            }
        }
        for k in 0..N {
            if N > 2 {
                break;
            }
            let at = (i0[k] as usize + i1[k] as usize * l[1].stride + k2 * l[2].stride) * 2;
            let planes = data.get(at..at + s2 + s1 + 4).and_then(|b| {
                Some((
                    b.get(..4)?,
                    b.get(s1..s1 + 4)?,
                    b.get(s2..s2 + 4)?,
                    b.get(s2 + s1..s2 + s1 + 4)?,
                ))
            });
            match planes {
                Some((r0, r1, r2, r3)) => {
                    for (j, r) in [r0, r1, r2, r3].into_iter().enumerate() {
                        q[2 * j][k] = u16_at(r, 0) as u32;
                        q[2 * j + 1][k] = u16_at(r, 1) as u32;
                    }
                }
                None => f0[k] = f32::NAN,
            }
        }
        let mut out = [0.0f32; N];
        for k in 0..N {
            let v = |j: usize| q[j][k] as f32;
            let plane = |j: usize| {
                let r0 = v(j) + f0[k] * (v(j + 1) - v(j));
                let r1 = v(j + 2) + f0[k] * (v(j + 3) - v(j + 2));
                r0 + f1[k] * (r1 - r0)
            };
            let (p0, p1) = (plane(0), plane(4));
            out[k] = self.offset[0] + self.scale[0] * (p0 + f2 * (p1 - p0));
        }
        out
    }
}

/// ln x for a normal positive finite f32 x: x = 2ᵏ m with m ∈ [√½, √2), then
/// ln m = 2 atanh s = 2s (1 + s²/3 + s⁴/5 + s⁶/7 + …) with s = (m − 1)/(m + 1), |s| ≤ 0.1716
/// (series truncation < 2.9e-8; with the f32 rounding the error stays below
/// 1.5e-7 + 6e-8 |ln x|). Not correctly rounded like libm's `logf`, but inline and about
/// a third of its instructions.
#[cfg(hosted)]
#[inline(always)]
pub(crate) fn ln_fast(x: f32) -> f32 {
    // The bits of √½: adding 1.0's bits minus these carries into the exponent exactly when
    // the significand is ≥ √2.
    const SQRT_HALF: u32 = 0x3f35_04f3;
    let ix = x.to_bits().wrapping_add(0x3f80_0000 - SQRT_HALF);
    let k = (ix >> 23) as i32 - 127;
    let m = f32::from_bits((ix & 0x007f_ffff) + SQRT_HALF);
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let z = s * s;
    let p = 2.0 + z * (2.0 / 3.0 + z * (2.0 / 5.0 + z * (2.0 / 7.0)));
    k as f32 * core::f32::consts::LN_2 + s * p
}

/// The payload rows of `N` queries: word j of row r of query k is the little-endian 32-bit
/// word at byte `at[k] + off[r] + 4j` of `data` (`[row][word][query]`), and `bad[k]` is NaN
/// for a query whose rows lie past the payload (impossible for a parsed table: its words
/// are then 0) and 0 otherwise. `avx2`: the caller runs compiled for AVX2 (see [`wide`]),
/// so the words are read by gathers, eight queries at a time, after one bounds check per
/// query in vector form.
#[cfg(hosted)]
#[inline(always)]
#[allow(clippy::type_complexity)]
fn rows<const N: usize, const R: usize, const W: usize>(
    data: &[u8],
    at: &[u32; N],
    off: [u32; R],
    avx2: bool,
) -> ([[[u32; N]; W]; R], [f32; N]) {
    let mut words = [[[0u32; N]; W]; R];
    let mut bad = [0.0f32; N];
    // Bytes from a query's first word to the end of its last.
    let span = off.iter().max().map_or(0, |&o| o as usize) + 4 * W;
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if avx2 && N % 8 == 0 && data.len() <= i32::MAX as usize && data.len() >= span {
        // Queries whose rows end past the payload read the first word instead (and are
        // marked bad), so that every gathered word lies in `data`.
        let limit = (data.len() - span) as u32;
        let mut idx = [0u32; N];
        for k in 0..N {
            let ok = at[k] <= limit;
            idx[k] = if ok { at[k] } else { 0 };
            bad[k] = if ok { 0.0 } else { f32::NAN };
        }
        // SAFETY: the processor supports AVX2 (`avx2`: the caller was entered through
        // `wide`'s check), and every word read lies in `data`: idx[k] ≤ len − span and
        // off[r] + 4j + 4 ≤ span, with len ≤ i32::MAX so that the offsets are
        // non-negative i32.
        unsafe { gather_words(data.as_ptr(), &idx, &off, &mut words) };
        return (words, bad);
    }
    let _ = avx2;
    for k in 0..N {
        let at = at[k] as usize;
        match data.get(at..at + span) {
            Some(b) => {
                for (wr, &o) in words.iter_mut().zip(&off) {
                    for (j, w) in wr.iter_mut().enumerate() {
                        w[k] = u32_at(b, o as usize + 4 * j);
                    }
                }
            }
            None => bad[k] = f32::NAN,
        }
    }
    (words, bad)
}

/// The little-endian 32-bit word at byte `at` of `b` (0 past the end; callers pass rows
/// that hold it).
#[cfg(hosted)]
#[inline(always)]
fn u32_at(b: &[u8], at: usize) -> u32 {
    match b.get(at..at + 4) {
        Some(&[b0, b1, b2, b3]) => u32::from_le_bytes([b0, b1, b2, b3]),
        _ => 0,
    }
}

/// Stored u16 number `k` of `b` (0 past the end; callers pass rows that hold it).
#[cfg(hosted)]
#[inline(always)]
fn u16_at(b: &[u8], k: usize) -> u16 {
    match b.get(2 * k..2 * k + 2) {
        Some(&[b0, b1]) => u16::from_le_bytes([b0, b1]),
        _ => 0,
    }
}

#[cfg(all(test, hosted))]
mod tests {
    use super::*;

    /// `ln_fast` against the f64 logarithm over the normal f32 range (every 2⁻¹²th step of
    /// the exponent) and densely over σ-like values. Bound: series truncation 2.9e-8, plus
    /// f32 rounding of s, the polynomial and k·ln 2 (a few ulp of ln m ≤ 0.35 and of
    /// |k ln 2|), i.e. ≤ 1.5e-7 + 2.5e-7·|ln x|.
    #[test]
    fn ln_fast_matches_the_logarithm() {
        let mut worst = 0f64;
        let mut check = |x: f32| {
            let exact = (x as f64).ln();
            let err = (ln_fast(x) as f64 - exact).abs();
            assert!(err <= 1.5e-7 + 2.5e-7 * exact.abs(), "{x}: {err:e}");
            worst = worst.max(err / (1.0 + exact.abs()));
        };
        let mut e = -126.0f64;
        while e < 127.0 {
            check(libm::exp2(e) as f32);
            e += 1.0 / 4096.0;
        }
        for k in 0..=200_000 {
            check(0.01 + 10.0 * k as f32 / 200_000.0);
        }
        assert!(worst > 0.0);
    }

    /// A NaN coordinate on a √cos-warped axis gives a NaN fraction (so a NaN value), on
    /// both the scalar and the chunk path.
    #[test]
    fn nan_stays_nan_through_the_sqrt_cos_warp() {
        let axis = Axis {
            name: "theta",
            count: 9,
            lo: 0.0,
            hi: core::f64::consts::FRAC_PI_2,
            warp: Warp::SqrtCos,
            placement: Placement::Endpoint,
        };
        let lane = Lane::new(&axis, 1).unwrap();
        assert!(lane.cell(f32::NAN).1.is_nan());
        let (_, f) = lane.cells::<2, false, false>(&[f32::NAN, 0.5]);
        assert!(f[0].is_nan() && !f[1].is_nan());
        let (_, f) = lane.cells::<16, false, false>(&[f32::NAN; 16]);
        assert!(f.iter().all(|f| f.is_nan()));
    }

    /// The σ lane of a 3-D G table (28 nodes over [0.05, 1], log warp) through `ln_fast`
    /// moves the fractional node index by less than 1e-4 of a cell from libm's `logf`
    /// (a = 27/ln 20 ≈ 9 cells per unit of ln σ, times the error bound above).
    #[test]
    fn fast_log_lane_keeps_the_node_index() {
        let axis = Axis {
            name: "sigma",
            count: 28,
            lo: 0.05,
            hi: 1.0,
            warp: Warp::Log,
            placement: Placement::Endpoint,
        };
        let lane = Lane::new(&axis, 1).unwrap();
        for k in 0..=100_000 {
            let x = 0.04 + 1.0 * k as f32 / 100_000.0;
            let (i, f) = lane.cell(x);
            let (j, g) = lane.cell_ln(x);
            let (t, u) = (i as f32 + f, j as f32 + g);
            assert!((t - u).abs() < 1e-4, "σ = {x}: {t} vs {u}");
        }
    }
}

//! The G tables' lookup with the table layout fixed once, at construction.
//!
//! A G costs two passing-factor lookups, F(|θr|, ±θi) for GM and F(θi, θr) for GS
//! (conventions.md §4). The general reader ([`LutView::sample`]) decides per tap which
//! encoding and channel it reads; here that is decided once: a one-channel `Unorm16` table
//! of [`TableKind::PassingFactor`] is read with 2 taps per axis (linear) or 4
//! (Catmull–Rom, the end extrapolation of docs/lut-format.md §7 folded into the weights),
//! one bounds check per cell (linear) or per row of four (cubic), the (θ, φ) taps shared by
//! every σ plane and the channel's scale and offset applied once at the end (the weights
//! sum to 1).
//!
//! Inlining: forced on hosted targets (speed), left to the optimiser on bare metal
//! (`target_os = "none"`), where the firmware's flash budget matters more.
//!
//! The values are the general reader's up to f32 summation order (`tests/tests/lut_format.rs`
//! checks both against each other and against the direct kernel).

use super::{Axis, AxisMap, Encoding, Interpolation, LutView, Placement, TableKind, Warp};

/// One axis' physical coordinate → fractional node index, t = a·w(x) + b clamped to
/// [0, n − 1], with w the warp's monotone part (x, √cos x or ln x) folded into a and b; the
/// same map as [`AxisMap::index`] up to f32 rounding. Warps without a folded form (Sqrt,
/// Cos) go through [`AxisMap::index`].
#[derive(Clone, Copy, Debug)]
struct Lane {
    map: AxisMap,
    warp: Warp,
    lo: f32,
    hi: f32,
    a: f32,
    b: f32,
    last: f32,
    /// n − 2, the last cell.
    last_cell: i32,
}

/// cos x for x ∈ [0, π/2] as sin(π/2 − x) by its Taylor series to r¹¹ (truncation < 1e-9,
/// relative accuracy kept near π/2 where √cos x is steep). Only for the table warp, where
/// an error of a few 1e-8 moves the interpolation point by < 1e-4 of a cell.
#[inline(always)]
fn cos_quadrant(x: f32) -> f32 {
    let r = core::f32::consts::FRAC_PI_2 - x;
    let r2 = r * r;
    r * (1.0
        + r2 * (-1.0 / 6.0
            + r2 * (1.0 / 120.0
                + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362_880.0 + r2 * (-1.0 / 39_916_800.0))))))
}

/// min(max(x, lo), hi) for x not NaN, as two compares.
#[inline(always)]
fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    let x = if x < lo { lo } else { x };
    if x > hi {
        hi
    } else {
        x
    }
}

impl Lane {
    fn new(axis: &Axis<'_>, map: AxisMap) -> Self {
        let (lo, hi) = (axis.lo as f32, axis.hi as f32);
        let nf = map.count() as f32;
        // t = s·A + B with s the unit coordinate.
        let (big_a, big_b) = match axis.placement {
            Placement::Endpoint => (nf - 1.0, 0.0),
            Placement::TexelCentre => (nf, -0.5),
        };
        // s = (w(x) − w(lo)) / (w(hi) − w(lo)), w monotone.
        let w = |x: f32| match axis.warp {
            Warp::SqrtCos => libm::sqrtf(cos_quadrant(x).max(0.0)),
            Warp::Log => libm::logf(x),
            _ => x,
        };
        let (w0, w1) = (w(lo), w(hi));
        let a = big_a / (w1 - w0);
        Lane {
            map,
            warp: axis.warp,
            lo,
            hi,
            a,
            b: big_b - a * w0,
            last: nf - 1.0,
            last_cell: map.count() as i32 - 2,
        }
    }

    /// The fractional node index of x (x not NaN).
    #[cfg_attr(target_os = "none", inline)]
    #[cfg_attr(not(target_os = "none"), inline(always))]
    fn index(&self, x: f32) -> f32 {
        let x = clamp(x, self.lo, self.hi);
        let w = match self.warp {
            Warp::Linear => x,
            // The axis lies within [0, π/2] (checked when the header was parsed).
            Warp::SqrtCos => libm::sqrtf(cos_quadrant(x).max(0.0)),
            Warp::Log => libm::logf(x),
            _ => return self.map.index(x),
        };
        clamp(self.a * w + self.b, 0.0, self.last)
    }

    /// Node i ≤ n − 2 and the fraction f ∈ [0, 1] of x.
    #[cfg_attr(target_os = "none", inline)]
    #[cfg_attr(not(target_os = "none"), inline(always))]
    fn cell(&self, x: f32) -> (usize, f32) {
        let t = self.index(x);
        // t ∈ [0, n − 1] with n ≤ 65536: the i32 conversion is exact and in range.
        let i = (t as i32).min(self.last_cell).max(0);
        (i as usize, t - i as f32)
    }
}

/// First node and the four Catmull–Rom weights (docs/lut-format.md §7) of fractional
/// index `t` on an axis of `n ≥ 4` nodes, the end extrapolation folded in.
#[inline(always)]
fn cubic_taps(t: f32, n: usize) -> (usize, [f32; 4]) {
    let i = (t as usize).min(n - 2);
    let f = t - i as f32;
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

/// The per-table constants of the fixed-layout lookup.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PassingReader {
    lanes: [Lane; 3],
    n: [usize; 3],
    cubic: bool,
    scale: f32,
    offset: f32,
}

impl PassingReader {
    /// `None` unless the view is a one-channel `Unorm16` passing-factor table whose axes
    /// have enough nodes for its interpolant (2 linear, 4 Catmull–Rom); such tables are
    /// read by the general reader instead.
    pub(crate) fn new(v: &LutView<'_>) -> Option<Self> {
        let h = v.header();
        if v.kind() != TableKind::PassingFactor
            || v.channels() != 1
            || h.encoding != Encoding::Unorm16
        {
            return None;
        }
        let cubic = h.interpolation == Interpolation::CatmullRom;
        let dims = v.dims();
        let mut n = [1usize; 3];
        let unit = Axis {
            name: "",
            count: 2,
            lo: 0.0,
            hi: 1.0,
            warp: Warp::Linear,
            placement: Placement::Endpoint,
        };
        let mut lanes = [Lane::new(&unit, AxisMap::UNIT); 3];
        for k in 0..dims.min(3) {
            let map = *v.axis_map(k);
            lanes[k] = Lane::new(&h.axes[k], map);
            n[k] = map.count();
            if n[k] < if cubic { 4 } else { 2 } {
                return None;
            }
        }
        let values = n[0].checked_mul(n[1])?.checked_mul(n[2])?;
        if v.payload().len() < values.checked_mul(2)? {
            return None;
        }
        let c = &h.channels[0];
        Some(Self {
            lanes,
            n,
            cubic,
            scale: c.scale * (1.0 / 65535.0),
            offset: c.offset,
        })
    }

    /// (GM, GS) in [0, 1] from a 2-D table, for the already clamped argument pairs
    /// `m` = (|θr|, ±θi) and `s` = (θi, θr).
    #[inline]
    pub(crate) fn pair2(&self, data: &[u8], m: [f32; 2], s: [f32; 2]) -> (f32, f32) {
        let (gm, gs) = if self.cubic {
            let (am, m0, m1) = self.cubic_cell(m);
            let (as_, s0, s1) = self.cubic_cell(s);
            (
                self.patch(data, am, &m0, &m1),
                self.patch(data, as_, &s0, &s1),
            )
        } else {
            let (cm, cs) = (self.cell2(m), self.cell2(s));
            (self.bilinear(data, 0, cm), self.bilinear(data, 0, cs))
        };
        self.finish(gm, gs)
    }

    /// [`PassingReader::pair2`] for a 3-D table at σ.
    #[inline]
    pub(crate) fn pair3(&self, data: &[u8], m: [f32; 2], s: [f32; 2], sigma: f32) -> (f32, f32) {
        let (gm, gs) = if self.cubic {
            self.cubic3(data, m, s, sigma)
        } else {
            // Linear in σ between two (θ, φ) planes; the (θ, φ) cells are shared.
            let (cm, cs) = (self.cell2(m), self.cell2(s));
            let (k, f) = self.lanes[2].cell(sigma);
            let plane = self.n[0] * self.n[1];
            let (p0, p1) = (k * plane, (k + 1) * plane);
            let (m0, s0) = (self.bilinear(data, p0, cm), self.bilinear(data, p0, cs));
            let (m1, s1) = (self.bilinear(data, p1, cm), self.bilinear(data, p1, cs));
            (m0 + f * (m1 - m0), s0 + f * (s1 - s0))
        };
        self.finish(gm, gs)
    }

    /// Stored units → F, clamped to [0, 1].
    #[inline(always)]
    fn finish(&self, gm: f32, gs: f32) -> (f32, f32) {
        let f = |x: f32| clamp(self.offset + self.scale * x, 0.0, 1.0);
        (f(gm), f(gs))
    }

    /// The (θ, φ) cell of a lookup: flat offset of its lower corner and the two fractions.
    #[cfg_attr(target_os = "none", inline)]
    #[cfg_attr(not(target_os = "none"), inline(always))]
    fn cell2(&self, x: [f32; 2]) -> (usize, f32, f32) {
        let (i, f0) = self.lanes[0].cell(x[0]);
        let (j, f1) = self.lanes[1].cell(x[1]);
        (j * self.n[0] + i, f0, f1)
    }

    /// Bilinear F in stored units in cell `c` of the (θ, φ) plane starting at flat index
    /// `plane`; NaN if the payload is short.
    #[cfg_attr(target_os = "none", inline)]
    #[cfg_attr(not(target_os = "none"), inline(always))]
    fn bilinear(&self, data: &[u8], plane: usize, c: (usize, f32, f32)) -> f32 {
        let (cell, f0, f1) = c;
        let n0 = self.n[0];
        let at = 2 * (plane + cell);
        let Some(p) = data.get(at..at + 2 * n0 + 4) else {
            return f32::NAN;
        };
        let v = |k: usize| u16::from_le_bytes([p[k], p[k + 1]]) as f32;
        let (a0, a1, b0, b1) = (v(0), v(2), v(2 * n0), v(2 * n0 + 2));
        let lo = a0 + f0 * (a1 - a0);
        let hi = b0 + f0 * (b1 - b0);
        lo + f1 * (hi - lo)
    }

    /// Tricubic (GM, GS) in stored units: 4 σ planes, the (θ, φ) taps shared.
    #[inline]
    fn cubic3(&self, data: &[u8], m: [f32; 2], s: [f32; 2], sigma: f32) -> (f32, f32) {
        let (am, m0, m1) = self.cubic_cell(m);
        let (as_, s0, s1) = self.cubic_cell(s);
        let plane = self.n[0] * self.n[1];
        let (b2, w2) = cubic_taps(self.lanes[2].index(sigma), self.n[2]);
        let (mut gm, mut gs) = (0.0, 0.0);
        for (k, &wk) in w2.iter().enumerate() {
            if wk != 0.0 {
                let p = (b2 + k) * plane;
                gm += wk * self.patch(data, p + am, &m0, &m1);
                gs += wk * self.patch(data, p + as_, &s0, &s1);
            }
        }
        (gm, gs)
    }

    /// The flat offset of the 4×4 patch of (θ, φ) and its two weight vectors.
    #[inline]
    fn cubic_cell(&self, x: [f32; 2]) -> (usize, [f32; 4], [f32; 4]) {
        let (b0, w0) = cubic_taps(self.lanes[0].index(x[0]), self.n[0]);
        let (b1, w1) = cubic_taps(self.lanes[1].index(x[1]), self.n[1]);
        (b1 * self.n[0] + b0, w0, w1)
    }

    /// Σ_j w1[j] Σ_i w0[i] v[at + j·n0 + i] in stored units; NaN if the payload is short.
    #[inline]
    fn patch(&self, data: &[u8], at: usize, w0: &[f32; 4], w1: &[f32; 4]) -> f32 {
        let mut acc = 0.0;
        for (j, wj) in w1.iter().enumerate() {
            let start = 2 * (at + j * self.n[0]);
            let Some(b) = data.get(start..start + 8) else {
                return f32::NAN;
            };
            let mut r = 0.0;
            for (i, wi) in w0.iter().enumerate() {
                r += wi * u16::from_le_bytes([b[2 * i], b[2 * i + 1]]) as f32;
            }
            acc += wj * r;
        }
        acc
    }
}

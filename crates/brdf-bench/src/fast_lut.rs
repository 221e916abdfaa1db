//! A measurement prototype, not a library API: the same passing-factor tables and the same
//! Catmull–Rom interpolant as `brdf_core::lut` (docs/lut-format.md: cubic weights
//! w₋₁ = (−f³ + 2f² − f)/2, w₀ = (3f³ − 5f² + 2)/2, w₁ = (−3f³ + 4f² + f)/2, w₂ = (f³ − f²)/2,
//! a missing end node replaced by the quadratic extrapolation v₋₁ = 3v₀ − 3v₁ + v₂), read
//! with the table layout fixed at construction: always four taps per axis (the end
//! extrapolation folded into the weights), one-channel `u16` payload decoded in place, the
//! σ taps shared by GM and GS. It exists to measure how fast the lookup can be with the
//! committed tables, so that `docs/benchmarks.md` can say what limits the general reader.

use brdf_core::lut::{AxisMap, Encoding, LutView, TableKind};

/// Four node indices starting at `base` and their weights, for fractional index `t` on an
/// axis of `n ≥ 4` nodes.
#[inline]
fn taps4(t: f32, n: usize) -> (usize, [f32; 4]) {
    let i = (t as usize).min(n - 2);
    let f = t - i as f32;
    let (f2, f3) = (f * f, f * f * f);
    let wm = 0.5 * (-f3 + 2.0 * f2 - f);
    let w0 = 0.5 * (3.0 * f3 - 5.0 * f2 + 2.0);
    let w1 = 0.5 * (-3.0 * f3 + 4.0 * f2 + f);
    let w2 = 0.5 * (f3 - f2);
    if i == 0 {
        // nodes 0..3; v₋₁ folded into v₀, v₁, v₂
        (0, [w0 + 3.0 * wm, w1 - 3.0 * wm, w2 + wm, 0.0])
    } else if i == n - 2 {
        // nodes n−4..n−1; v_n folded into v_{n−1}, v_{n−2}, v_{n−3}
        (n - 4, [0.0, wm + w2, w0 - 3.0 * w2, w1 + 3.0 * w2])
    } else {
        (i - 1, [wm, w0, w1, w2])
    }
}

/// A one-channel, `u16`, Catmull–Rom passing-factor table (2-D or 3-D) read with a fixed
/// layout.
#[derive(Clone, Debug)]
pub struct FastPassing<'a> {
    data: &'a [u8],
    maps: [AxisMap; 3],
    n: [usize; 3],
    dims: usize,
    scale: f32,
    offset: f32,
}

impl<'a> FastPassing<'a> {
    /// `None` unless the view is a one-channel u16 passing-factor table with ≥ 4 nodes per
    /// axis.
    pub fn new(v: &LutView<'a>) -> Option<Self> {
        let h = v.header();
        if v.kind() != TableKind::PassingFactor
            || v.channels() != 1
            || h.encoding != Encoding::Unorm16
        {
            return None;
        }
        let dims = v.dims();
        let mut maps = [*v.axis_map(0); 3];
        let mut n = [1usize; 3];
        for k in 0..dims {
            maps[k] = *v.axis_map(k);
            n[k] = maps[k].count();
            if n[k] < 4 {
                return None;
            }
        }
        let c = &h.channels[0];
        let need = n[0] * n[1] * n[2] * 2;
        if v.payload().len() < need {
            return None;
        }
        Some(Self {
            data: v.payload(),
            maps,
            n,
            dims,
            scale: c.scale * (1.0 / 65535.0),
            offset: c.offset,
        })
    }

    /// Four consecutive stored values from flat index `at` (one bounds check).
    #[inline]
    fn row4(&self, at: usize) -> [f32; 4] {
        match self.data.get(2 * at..2 * at + 8) {
            Some(b) => [
                u16::from_le_bytes([b[0], b[1]]) as f32,
                u16::from_le_bytes([b[2], b[3]]) as f32,
                u16::from_le_bytes([b[4], b[5]]) as f32,
                u16::from_le_bytes([b[6], b[7]]) as f32,
            ],
            None => [f32::NAN; 4],
        }
    }

    /// The (θ, φ) taps of one lookup: computed once, reused on every σ slice.
    #[inline]
    fn taps2(&self, theta: f32, phi: f32) -> (usize, [f32; 4], [f32; 4]) {
        let (b0, w0) = taps4(self.maps[0].index(theta), self.n[0]);
        let (b1, w1) = taps4(self.maps[1].index(phi), self.n[1]);
        (b1 * self.n[0] + b0, w0, w1)
    }

    /// F over the 4×4 patch at flat offset `at` (σ slice start + patch corner).
    #[inline]
    fn patch(&self, at: usize, w0: &[f32; 4], w1: &[f32; 4]) -> f32 {
        let mut acc = 0.0;
        for (j, wj) in w1.iter().enumerate() {
            let v = self.row4(at + j * self.n[0]);
            let r = w0[0] * v[0] + w0[1] * v[1] + w0[2] * v[2] + w0[3] * v[3];
            acc += wj * r;
        }
        acc
    }

    /// G = min(GM, GS) at in-plane angles (radians) and σ (ignored by a 2-D table); the
    /// same arguments as `brdf_core::lut::GTable3::g`.
    pub fn g(&self, theta_i: f32, theta_r: f32, sigma: f32) -> f32 {
        use core::f32::consts::FRAC_PI_2;
        if theta_i.is_nan() || theta_r.is_nan() || sigma.is_nan() {
            return f32::NAN;
        }
        let ti = theta_i.clamp(0.0, FRAC_PI_2);
        let tr = theta_r.clamp(-FRAC_PI_2, FRAC_PI_2);
        let s = if tr < 0.0 { -ti } else { ti };
        let plane = self.n[0] * self.n[1];
        let (am, m0, m1) = self.taps2(tr.abs(), s);
        let (as_, s0, s1) = self.taps2(ti, tr);
        let (gm, gs) = if self.dims == 2 {
            (self.patch(am, &m0, &m1), self.patch(as_, &s0, &s1))
        } else {
            let (b2, w2) = taps4(self.maps[2].index(sigma), self.n[2]);
            let (mut gm, mut gs) = (0.0, 0.0);
            for (k, wk) in w2.iter().enumerate() {
                if *wk != 0.0 {
                    let p = (b2 + k) * plane;
                    gm += wk * self.patch(p + am, &m0, &m1);
                    gs += wk * self.patch(p + as_, &s0, &s1);
                }
            }
            (gm, gs)
        };
        let f = |x: f32| (self.offset + self.scale * x).clamp(0.0, 1.0);
        f(gm).min(f(gs))
    }
}

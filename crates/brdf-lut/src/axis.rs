//! Axis coordinate maps (docs/lut-format.md §6) and interpolation weights.
//!
//! A physical coordinate x is clamped to [lo, hi], mapped by the axis' [`Warp`] to
//! s ∈ [0, 1], then to the fractional node index t = s(n − 1) ([`Placement::Endpoint`]) or
//! t = sn − ½ clamped to [0, n − 1] ([`Placement::TexelCentre`]).
//!
//! * Linear: v = (1 − f) v_i + f v_{i+1}, i = ⌊t⌋ (i ≤ n − 2), f = t − i.
//! * Catmull–Rom: v = Σ_{k=−1..2} w_k(f) v_{i+k} with
//!   w_{−1} = (−f³ + 2f² − f)/2, w_0 = (3f³ − 5f² + 2)/2, w_1 = (−3f³ + 4f² + f)/2,
//!   w_2 = (f³ − f²)/2; a missing end node is replaced by the quadratic extrapolation
//!   v_{−1} = 3v_0 − 3v_1 + v_2 (and its mirror at the far end). Axes with two nodes
//!   interpolate linearly.

use crate::header::{Axis, Placement, Warp};

/// cos x in f32 arithmetic only: brdf-core's f32 sine/cosine kernel (Cody–Waite reduction,
/// Taylor polynomials; within 2 ulp for |x| ≤ 6400). libm's `cosf` evaluates in f64, which
/// on a single-precision FPU links kilobytes of soft-float code; this kernel is shared with
/// the direct kernels and gives the same bits on every target.
#[inline]
pub(crate) fn cos(x: f32) -> f32 {
    brdf_core::Real::sin_cos(x).1
}

/// min(max(x, lo), hi); NaN stays NaN and it cannot panic (`f32::clamp` asserts lo ≤ hi,
/// which also links float formatting into size-constrained builds).
#[inline(always)]
pub(crate) fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    let x = if x < lo { lo } else { x };
    if x > hi {
        hi
    } else {
        x
    }
}

/// The per-axis constants of a lookup, in f32.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisMap {
    lo: f32,
    hi: f32,
    /// Warp origin: lo, ln lo or cos lo.
    base: f32,
    /// 1/(warp(hi) − warp(lo)).
    inv: f32,
    warp: Warp,
    placement: Placement,
    n: u32,
}

impl AxisMap {
    pub(crate) const UNIT: AxisMap = AxisMap {
        lo: 0.0,
        hi: 1.0,
        base: 0.0,
        inv: 1.0,
        warp: Warp::Linear,
        placement: Placement::Endpoint,
        n: 2,
    };

    /// Precomputes the map of a (validated) axis. Computed in f32 from the f32-rounded range
    /// ends (the lookups are f32 anyway), so that a device build links no f64 math for it.
    pub fn new(a: &Axis<'_>) -> Self {
        let (lo, hi) = (a.lo as f32, a.hi as f32);
        let (base, span) = match a.warp {
            Warp::Linear | Warp::Sqrt => (lo, hi - lo),
            Warp::Log => (libm::logf(lo), libm::logf(hi) - libm::logf(lo)),
            Warp::Cos => (cos(lo), cos(lo) - cos(hi)),
            Warp::SqrtCos => {
                let (a, b) = (libm::sqrtf(cos(lo)), libm::sqrtf(cos(hi).max(0.0)));
                (a, a - b)
            }
        };
        AxisMap {
            lo,
            hi,
            base,
            inv: 1.0 / span,
            warp: a.warp,
            placement: a.placement,
            n: a.count,
        }
    }

    /// Number of nodes.
    pub fn count(&self) -> usize {
        self.n as usize
    }

    /// The unit coordinate s ∈ [0, 1] of x (clamped first).
    pub fn unit(&self, x: f32) -> f32 {
        let x = clamp(x, self.lo, self.hi);
        let s = match self.warp {
            Warp::Linear => (x - self.base) * self.inv,
            Warp::Sqrt => libm::sqrtf(((x - self.base) * self.inv).max(0.0)),
            Warp::Log => (libm::logf(x) - self.base) * self.inv,
            Warp::Cos => (self.base - cos(x)) * self.inv,
            Warp::SqrtCos => (self.base - libm::sqrtf(cos(x).max(0.0))) * self.inv,
        };
        clamp(s, 0.0, 1.0)
    }

    /// The fractional node index of x.
    pub fn index(&self, x: f32) -> f32 {
        let s = self.unit(x);
        let nf = self.n as f32;
        let t = match self.placement {
            Placement::Endpoint => s * (nf - 1.0),
            Placement::TexelCentre => s * nf - 0.5,
        };
        clamp(t, 0.0, nf - 1.0)
    }

    /// Writes the interpolation taps (node index, weight) of x; returns how many.
    pub(crate) fn taps(&self, x: f32, cubic: bool, out: &mut [(usize, f32); 4]) -> usize {
        let t = self.index(x);
        let n = self.n as usize;
        let i = (t as usize).min(n.saturating_sub(2));
        let f = t - i as f32;
        if !cubic || n < 3 {
            let [o0, o1, ..] = out;
            *o0 = (i, 1.0 - f);
            *o1 = (i + 1, f);
            return 2;
        }
        let (f2, f3) = (f * f, f * f * f);
        let w = [
            0.5 * (-f3 + 2.0 * f2 - f),
            0.5 * (3.0 * f3 - 5.0 * f2 + 2.0),
            0.5 * (-3.0 * f3 + 4.0 * f2 + f),
            0.5 * (f3 - f2),
        ];
        // At most 4 distinct nodes: the window i − 1..=i + 2, with an end extrapolation
        // folding into nodes of that window (n ≥ 3). `get_mut` keeps that unprovable to the
        // compiler bound free of a panic path; a fifth node cannot occur.
        let mut m = 0usize;
        let mut add = |idx: usize, wt: f32| {
            if let Some(t) = out.iter_mut().take(m).find(|t| t.0 == idx) {
                t.1 += wt;
            } else if let Some(slot) = out.get_mut(m) {
                *slot = (idx, wt);
                m += 1;
            }
        };
        for (k, &wk) in w.iter().enumerate() {
            let idx = i as isize - 1 + k as isize;
            if idx < 0 {
                // v_{−1} = 3v_0 − 3v_1 + v_2
                add(0, 3.0 * wk);
                add(1, -3.0 * wk);
                add(2, wk);
            } else if idx as usize >= n {
                // v_n = 3v_{n−1} − 3v_{n−2} + v_{n−3}
                add(n - 1, 3.0 * wk);
                add(n - 2, -3.0 * wk);
                add(n - 3, wk);
            } else {
                add(idx as usize, wk);
            }
        }
        m
    }
}

impl Axis<'_> {
    /// The unit coordinate s of node i (f64).
    pub fn node_unit(&self, i: u32) -> f64 {
        let n = self.count as f64;
        match self.placement {
            Placement::Endpoint => i as f64 / (n - 1.0),
            Placement::TexelCentre => (i as f64 + 0.5) / n,
        }
    }
    /// The physical coordinate of unit coordinate s (inverse warp, f64).
    pub fn from_unit(&self, s: f64) -> f64 {
        let (lo, hi) = (self.lo, self.hi);
        let x = match self.warp {
            Warp::Linear => lo + s * (hi - lo),
            Warp::Sqrt => lo + s * s * (hi - lo),
            Warp::Log => lo * libm::exp(s * libm::log(hi / lo)),
            Warp::Cos => {
                let c = libm::cos(lo) - s * (libm::cos(lo) - libm::cos(hi));
                libm::acos(c.clamp(-1.0, 1.0))
            }
            Warp::SqrtCos => {
                let a = libm::sqrt(libm::cos(lo));
                let q = a - s * (a - libm::sqrt(libm::cos(hi).max(0.0)));
                libm::acos((q * q).clamp(-1.0, 1.0))
            }
        };
        x.clamp(lo, hi)
    }
    /// The physical coordinate of node i.
    pub fn node(&self, i: u32) -> f64 {
        self.from_unit(self.node_unit(i))
    }
}

//! Typed tables: a table of one kind whose bytes were validated once and whose lookup
//! constants were prepared once, borrowed (`GTable<&[u8]>`, e.g. `&'static` bytes from
//! flash) or owned (`GTable<Vec<u8>>`, any `B: AsRef<[u8]>`). A query touches only the
//! payload.

use crate::header::{Convention, TableKind};
#[cfg(all(hosted, target_arch = "x86_64"))]
use crate::lookup::simd::{One, Two};
use crate::lookup::{Grid, Reader};
use crate::view::LutView;
use crate::LutError;
use core::f32::consts::FRAC_PI_2;

/// The two-lane lookup against the general reader (tables made with the writer).
#[cfg(all(test, feature = "std", hosted, target_arch = "x86_64"))]
mod fast2_tests;
pub(crate) mod layout;

/// What every query of a table needs, computed once from its header.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(crate) struct Prepared {
    pub(crate) header_len: usize,
    pub(crate) kind: TableKind,
    pub(crate) grid: Grid,
    pub(crate) reader: Reader,
    /// σ of a per-σ G table (NaN if the header does not say).
    pub(crate) sigma: f32,
    /// A passing-factor table in the reciprocal convention.
    pub(crate) reciprocal: bool,
    /// Range of the last axis (σ of a 3-D G table, roughness otherwise).
    pub(crate) last_range: (f32, f32),
    /// A passing-factor table whose θ and φ axes span exactly the ranges [`g_args`] clamps
    /// to: the lanes skip their own clamp of those arguments (hosted targets).
    #[cfg(hosted)]
    pub(crate) g_in_range: bool,
    /// The θ lane taking √cos θ (hosted targets; see [`Prepared::g_dots`]). Only the lane:
    /// a second reader would not fit the C interface's fixed table handles.
    #[cfg(hosted)]
    pub(crate) dots: Option<crate::lookup::Lane>,
    /// The two-lane lookup of [`Prepared::two`] (2-D two-channel linear u16 tables).
    #[cfg(all(hosted, target_arch = "x86_64"))]
    pub(crate) fast2: crate::lookup::simd::Fast2,
}

impl Prepared {
    /// Channels of `D`-axis lookups over slices (every slice the same length), through
    /// the fastest path the table has: linear u16 chunks, Catmull–Rom chunks, else
    /// `scalar` per query (the scalar lookup itself, so the results are the same bits).
    #[inline(always)]
    fn batch<const D: usize, const C: usize>(
        &self,
        payload: &[u8],
        x: [&[f32]; D],
        mut out: [&mut [f32]; C],
        scalar: impl Fn([f32; D]) -> [f32; C],
    ) {
        #[cfg(hosted)]
        let r = &self.reader;
        #[cfg(hosted)]
        if r.chunked() {
            return self.drive_batch::<D, C, CHUNK_SAMPLE>(x, out, payload, |xs, avx2| {
                r.chunk::<D, C, CHUNK_SAMPLE>(payload, xs, avx2)
            });
        }
        #[cfg(all(hosted, not(feature = "compact")))]
        if r.cubic_chunked() {
            return self.drive_batch::<D, C, CHUNK_CUBIC>(x, out, payload, |xs, _| {
                r.chunk_cubic::<D, C, CHUNK_CUBIC>(payload, xs)
            });
        }
        let _ = payload;
        // (Checked accesses: no panic path, whatever the compiler proves of the lengths.)
        for k in 0..out.first().map_or(0, |o| o.len()) {
            let v = scalar(core::array::from_fn(|d| {
                x.get(d)
                    .and_then(|xd| xd.get(k))
                    .copied()
                    .unwrap_or(f32::NAN)
            }));
            for (o, v) in out.iter_mut().zip(v) {
                if let Some(o) = o.get_mut(k) {
                    *o = v;
                }
            }
        }
    }

    /// The prepared form of a view.
    pub(crate) fn new(view: &LutView<'_>) -> Self {
        let h = view.header();
        let grid = *view.grid();
        let last = h
            .axes
            .last()
            .map_or((0.0, 1.0), |a| (a.lo as f32, a.hi as f32));
        // The view's own reader: the typed lookups are `LutView::sample`'s arithmetic, bit
        // for bit (the one exception: the σ lane of a linear 3-D G table, see
        // `LutView::sample`).
        let reader = *view.reader();
        Prepared {
            header_len: view.header_len(),
            kind: h.kind,
            grid,
            reader,
            sigma: h.generator.sigma.map_or(f32::NAN, |s| s as f32),
            last_range: last,
            reciprocal: h.generator.convention == Convention::Reciprocal,
            #[cfg(hosted)]
            g_in_range: h.kind == TableKind::PassingFactor && view.reader().g_ranges(),
            #[cfg(hosted)]
            dots: if h.kind == TableKind::PassingFactor {
                view.reader().prewarped()
            } else {
                None
            },
            #[cfg(all(hosted, target_arch = "x86_64"))]
            fast2: crate::lookup::simd::Fast2::new(view.reader(), grid.dims, grid.channels),
        }
    }

    /// `view` must hold `kind` with `dims` axes (G tables: the reciprocal convention).
    pub(crate) fn expect(
        view: &LutView<'_>,
        kind: TableKind,
        dims: usize,
    ) -> Result<Self, LutError> {
        if view.kind() != kind || view.dims() != dims {
            return Err(LutError::WrongKind {
                expected: kind,
                found: view.kind(),
            });
        }
        if kind == TableKind::PassingFactor
            && view.header().generator.convention != Convention::Reciprocal
        {
            return Err(LutError::Inconsistent(
                "G tables must use the reciprocal convention",
            ));
        }
        Ok(Self::new(view))
    }

    /// (GM, GS, G) of a 2-D passing-factor table.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn g2(&self, payload: &[u8], theta_i: f32, theta_r: f32) -> (f32, f32, f32) {
        if theta_i.is_nan() || theta_r.is_nan() {
            return (f32::NAN, f32::NAN, f32::NAN);
        }
        let (m, s) = g_args1(theta_i, theta_r);
        // (Skipping the lanes' clamp here, as `g3` does, measured more instructions: the
        // compiler then splits the two lanes.)
        let (gm, gs) = self.pair2(payload, m, s);
        let (gm, gs) = (unit01(gm), unit01(gs));
        (gm, gs, min_g(gm, gs))
    }

    /// The GM and GS lookups of a 2-D table. On hosted targets a linear u16 table reads
    /// both side by side through the chunk path (two lanes of the same arithmetic, so the
    /// same values as two [`Reader::sample`] calls).
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    fn pair2(&self, payload: &[u8], m: [f32; 2], s: [f32; 2]) -> (f32, f32) {
        let r = &self.reader;
        #[cfg(hosted)]
        if r.chunked() {
            let [[gm, gs]] = r.chunk::<2, 1, 2>(payload, &[[m[0], s[0]], [m[1], s[1]]], false);
            return (gm, gs);
        }
        (
            r.sample::<2, 1>(&self.grid, payload, m)[0],
            r.sample::<2, 1>(&self.grid, payload, s)[0],
        )
    }

    /// (GM, GS, G) of a 3-D passing-factor table.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn g3(
        &self,
        payload: &[u8],
        theta_i: f32,
        theta_r: f32,
        sigma: f32,
    ) -> (f32, f32, f32) {
        if theta_i.is_nan() || theta_r.is_nan() || sigma.is_nan() {
            return (f32::NAN, f32::NAN, f32::NAN);
        }
        let (m, s) = g_args1(theta_i, theta_r);
        #[cfg(hosted)]
        let (gm, gs) = if self.g_in_range {
            self.reader.pair3::<true>(&self.grid, payload, m, s, sigma)
        } else {
            self.reader.pair3::<false>(&self.grid, payload, m, s, sigma)
        };
        #[cfg(not(hosted))]
        let (gm, gs) = self.reader.pair3::<false>(&self.grid, payload, m, s, sigma);
        let (gm, gs) = (unit01(gm), unit01(gs));
        (gm, gs, min_g(gm, gs))
    }

    /// (GM, GS, G) of a 2-D or 3-D passing-factor table from the table arguments of the two
    /// sides.
    #[inline]
    pub(crate) fn g_from_args(
        &self,
        payload: &[u8],
        m: [f32; 2],
        s: [f32; 2],
        sigma: f32,
    ) -> (f32, f32, f32) {
        let r = &self.reader;
        let (gm, gs) = if self.grid.dims == 3 {
            r.pair3::<false>(&self.grid, payload, m, s, sigma)
        } else {
            self.pair2(payload, m, s)
        };
        let (gm, gs) = (unit01(gm), unit01(gs));
        (gm, gs, min_g(gm, gs))
    }

    /// G from dot products (see [`dots_args`]). On hosted targets a linear u16 table
    /// (speed tier) whose θ axis is √cos-warped reads that axis at √cos θ from the cosine
    /// itself (n·v, n·l) instead of at θ = atan2(sin θ, cos θ), whose cosine the lane would
    /// compute again by a polynomial: the node index differs from the θ route by f32
    /// rounding only (values within 2e-7 in the test below; φ still comes from θ).
    #[inline]
    pub(crate) fn g_dots(&self, payload: &[u8], n_l: f32, n_v: f32, l_v: f32, sigma: f32) -> f32 {
        if n_l.is_nan() || n_v.is_nan() || l_v.is_nan() || sigma.is_nan() {
            return f32::NAN;
        }
        match dots_args(n_l, n_v, l_v) {
            Some((m, s, (co, ci))) => {
                #[cfg(hosted)]
                if let Some(lane) = &self.dots {
                    let (m, s) = ([libm::sqrtf(co), m[1]], [libm::sqrtf(ci), s[1]]);
                    let z = (self.grid.dims == 3).then_some(sigma);
                    let (gm, gs) = self.reader.pair_with(lane, payload, m, s, z);
                    return min_g(unit01(gm), unit01(gs));
                }
                #[cfg(not(hosted))]
                let _ = (co, ci);
                self.g_from_args(payload, m, s, sigma).2
            }
            None => 0.0,
        }
    }

    /// Channels 0 and 1 of a 2-D table.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn two(&self, payload: &[u8], x: f32, y: f32) -> (f32, f32) {
        #[cfg(all(hosted, target_arch = "x86_64"))]
        if let Some(v) = self.fast2.lookup::<Two>(&self.reader, payload, 0, x, y) {
            return v;
        }
        let [a, b] = self.reader.sample::<2, 2>(&self.grid, payload, [x, y]);
        (a, b)
    }

    /// [`Prepared::two`] from the table's whole bytes (header, then payload from
    /// `header_len`): the two-lane lookup reads them directly, with the payload's start in
    /// its offsets.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub(crate) fn two_at(&self, bytes: &[u8], x: f32, y: f32) -> (f32, f32) {
        #[cfg(all(hosted, target_arch = "x86_64"))]
        if let Some(v) = self
            .fast2
            .lookup::<Two>(&self.reader, bytes, self.header_len, x, y)
        {
            return v;
        }
        self.two(bytes.get(self.header_len..).unwrap_or(&[]), x, y)
    }

    /// Channel 0 of a 2-D one-channel table: the values of [`LutView::sample2`] bit for bit
    /// (its function, or the two-lane lookup for linear u16 tables on linear or √ axes).
    #[inline]
    pub(crate) fn two1(&self, payload: &[u8], x: f32, y: f32) -> f32 {
        #[cfg(all(hosted, target_arch = "x86_64"))]
        if let Some(v) = self.fast2.lookup::<One>(&self.reader, payload, 0, x, y) {
            return v;
        }
        self.reader.sample::<2, 1>(&self.grid, payload, [x, y])[0]
    }

    /// Channel 0 of a 1-D table.
    #[inline]
    pub(crate) fn one(&self, payload: &[u8], x: f32) -> f32 {
        self.reader.sample::<1, 1>(&self.grid, payload, [x])[0]
    }

    /// `out[k] = G(ti[k], tr[k])` (at σ = `sigma` of a 3-D table) for k < `out.len()`:
    /// [`Prepared::g2`] / [`Prepared::g3`] (`.2`) bit for bit (a NaN σ fills `out` with
    /// NaN): chunks first where the table has a chunk path (hosted targets: `chunked()` or
    /// `cubic_chunked()`), then the scalar lookups.
    #[inline(always)]
    pub(crate) fn g_batch(
        &self,
        payload: &[u8],
        ti: &[f32],
        tr: &[f32],
        sigma: Option<f32>,
        out: &mut [f32],
    ) {
        if sigma.is_some_and(f32::is_nan) {
            return out.fill(f32::NAN);
        }
        #[cfg_attr(not(hosted), allow(unused_mut))]
        let mut done = 0;
        #[cfg(hosted)]
        let r = &self.reader;
        #[cfg(hosted)]
        if r.chunked() {
            done = self.g_drive::<CHUNK>(
                ti,
                tr,
                out,
                // (Inlined into the loop: compiled for AVX2 with it.)
                #[inline(always)]
                |x, avx2| match sigma {
                    Some(z) => r.chunk3::<CHUNK>(payload, x, z, avx2),
                    None => r.chunk::<2, 1, CHUNK>(payload, x, avx2)[0],
                },
            );
        } else {
            #[cfg(not(feature = "compact"))]
            if r.cubic_chunked() {
                // The σ taps once for the whole batch.
                let z = sigma.map(|z| r.lanes[2].cubic(z));
                done = self.g_drive::<CHUNK_CUBIC>(
                    ti,
                    tr,
                    out,
                    #[inline(always)]
                    |x, _| match &z {
                        Some(z) => r.chunk3_cubic::<CHUNK_CUBIC>(payload, x, z),
                        None => r.chunk_cubic::<2, 1, CHUNK_CUBIC>(payload, x)[0],
                    },
                );
            }
        }
        for ((o, &a), &b) in out.iter_mut().zip(ti).zip(tr).skip(done) {
            *o = match sigma {
                Some(z) => self.g3(payload, a, b, z).2,
                None => self.g2(payload, a, b).2,
            };
        }
    }
}

/// Queries per chunk of the G batch entry points (hosted targets; see `Reader::chunk`).
#[cfg(hosted)]
const CHUNK: usize = 32;
/// Queries per chunk of the other linear batch entry points: one AVX2 register (callgrind:
/// fewer instructions per DFG lookup than chunks of 16 or 32, whose stages the compiler
/// splits unevenly).
#[cfg(hosted)]
const CHUNK_SAMPLE: usize = 8;
/// Queries per chunk of the Catmull–Rom batch entry points.
#[cfg(all(hosted, not(feature = "compact")))]
const CHUNK_CUBIC: usize = 8;

/// The batch drivers (hosted targets): chunks of [`Reader::chunk`] (linear u16 tables) or
/// [`Reader::chunk_cubic`] (Catmull–Rom tables), then the scalar tail.
#[cfg(hosted)]
impl Prepared {
    /// The G chunk loop, compiled for AVX2 where the processor has it
    /// ([`crate::lookup::wide`]; `side`'s flag says so): chunks of `N` in-plane pairs
    /// ([`g_args_n`], then `side` of each side's `N` table arguments: its one-sided
    /// factors, then [`g_of_sides`]). Returns the number of queries written.
    #[inline(always)]
    fn g_drive<const N: usize>(
        &self,
        ti: &[f32],
        tr: &[f32],
        out: &mut [f32],
        side: impl Fn(&[[f32; N]; 2], bool) -> [f32; N],
    ) -> usize {
        crate::lookup::wide(
            #[inline(always)]
            |avx2| {
                let mut done = 0;
                for ((o, a), b) in out
                    .chunks_exact_mut(N)
                    .zip(ti.chunks_exact(N))
                    .zip(tr.chunks_exact(N))
                {
                    if let (Some(a), Some(b)) = (a.first_chunk(), b.first_chunk()) {
                        let (m, s, nan) = g_args_n(a, b);
                        let (gm, gs) = (side(&m, avx2), side(&s, avx2));
                        o.copy_from_slice(&g_of_sides(&gm, &gs, &nan));
                        done += N;
                    }
                }
                done
            },
        )
    }
    /// The batch driver shared by every chunked path, compiled for AVX2 where the processor
    /// has it ([`crate::lookup::wide`]; `chunk`'s flag says so): `chunk` computes `N`
    /// queries at once (bit for bit the scalar lookup), the tail of fewer than `N` goes
    /// through [`Reader::sample`]. `out[c][k]` = channel c at (x[0][k], …); every slice
    /// has the same length.
    #[inline(always)]
    fn drive_batch<const D: usize, const C: usize, const N: usize>(
        &self,
        x: [&[f32]; D],
        out: [&mut [f32]; C],
        payload: &[u8],
        chunk: impl Fn(&[[f32; N]; D], bool) -> [[f32; N]; C],
    ) {
        crate::lookup::wide(
            #[inline(always)]
            |avx2| {
                let n = out[0].len();
                let mut k = 0;
                while k + N <= n {
                    let mut xs = [[0.0f32; N]; D];
                    for (d, xd) in xs.iter_mut().enumerate() {
                        if let Some(c) = x[d].get(k..).and_then(|s| s.first_chunk::<N>()) {
                            *xd = *c;
                        }
                    }
                    let v = chunk(&xs, avx2);
                    for c in 0..C {
                        if let Some(o) = out[c].get_mut(k..k + N) {
                            o.copy_from_slice(&v[c]);
                        }
                    }
                    k += N;
                }
                while k < n {
                    let mut xk = [0.0f32; D];
                    for d in 0..D {
                        xk[d] = x[d].get(k).copied().unwrap_or(f32::NAN);
                    }
                    let v = self.reader.sample::<D, C>(&self.grid, payload, xk);
                    for c in 0..C {
                        if let Some(o) = out[c].get_mut(k) {
                            *o = v[c];
                        }
                    }
                    k += 1;
                }
            },
        );
    }
}

/// (GM, GS) arguments of the passing-factor table F(θ, φ) = M(θ, (θ − φ)/2) (reciprocal
/// convention, docs/conventions.md §4): GM = F(|θr|, sgn θr · θi), GS = F(θi, θr).
#[inline]
pub(crate) fn g_args(theta_i: f32, theta_r: f32) -> ([f32; 2], [f32; 2]) {
    let ti = crate::axis::clamp(theta_i, 0.0, FRAC_PI_2);
    let tr = crate::axis::clamp(theta_r, -FRAC_PI_2, FRAC_PI_2);
    let s = if tr < 0.0 { -ti } else { ti };
    ([tr.abs(), s], [ti, tr])
}

/// [`g_args`] of `N` queries (`[argument][query]` for each side) and which queries have a
/// NaN angle: the first stage of the G batch chunks.
#[cfg(hosted)]
#[inline(always)]
#[allow(clippy::type_complexity)]
pub(crate) fn g_args_n<const N: usize>(
    ti: &[f32; N],
    tr: &[f32; N],
) -> ([[f32; N]; 2], [[f32; N]; 2], [bool; N]) {
    let (mut m, mut s) = ([[0.0f32; N]; 2], [[0.0f32; N]; 2]);
    let mut nan = [false; N];
    for k in 0..N {
        nan[k] = ti[k].is_nan() || tr[k].is_nan();
        let (mk, sk) = g_args(ti[k], tr[k]);
        (m[0][k], m[1][k], s[0][k], s[1][k]) = (mk[0], mk[1], sk[0], sk[1]);
    }
    (m, s, nan)
}

/// G = min(GM, GS) (paper eq 13) of `N` queries from their one-sided factors, each
/// clamped to [0, 1], and NaN for the queries with a NaN angle: the last stage of the G
/// batch chunks ([`Prepared::g2`] / [`Prepared::g3`] per query).
#[cfg(hosted)]
#[inline(always)]
pub(crate) fn g_of_sides<const N: usize>(
    gm: &[f32; N],
    gs: &[f32; N],
    nan: &[bool; N],
) -> [f32; N] {
    let mut out = [0.0f32; N];
    for k in 0..N {
        let g = min_g(unit01(gm[k]), unit01(gs[k]));
        out[k] = if nan[k] { f32::NAN } else { g };
    }
    out
}

/// [`g_args`] for one query (the same values): on hosted targets the clamps as scalar
/// max/min instructions, which the compiler otherwise turns into a two-lane compare and
/// branches (the chunk loops keep [`g_args`], which vectorises).
#[inline(always)]
fn g_args1(theta_i: f32, theta_r: f32) -> ([f32; 2], [f32; 2]) {
    #[cfg(not(hosted))]
    return g_args(theta_i, theta_r);
    #[cfg(hosted)]
    {
        use crate::lookup::clamp_s as clamp;
        let ti = clamp(theta_i, 0.0, FRAC_PI_2);
        let tr = clamp(theta_r, -FRAC_PI_2, FRAC_PI_2);
        let s = if tr < 0.0 { -ti } else { ti };
        ([tr.abs(), s], [ti, tr])
    }
}

/// (GM arguments, GS arguments, (cos θ_v, cos θ_l)) of [`dots_args`].
type DotsArgs = ([f32; 2], [f32; 2], (f32, f32));

/// The table arguments (θ, φ) of both sides of G from the dot products of unit vectors
/// n·l, n·v, l·v, through the reciprocal 3-D extension of the modified G (the kernel's
/// `ModifiedG::terms_dots`): each side w ∈ {v (GM), l (GS)} is M(θ_w, a_w) with
/// tan a_w = (t + sin²θ_w) / (sin θ_w (cos θ_l + cos θ_v)), t = l·v − cos θ_l cos θ_v the
/// tangential dot product; the table stores F(θ, φ) = M(θ, (θ − φ)/2), so φ_w = θ_w − 2 a_w.
/// Also gives the two cosines (cos θ_v, cos θ_l) ∈ (0, 1].
/// `None` when a direction is at or below the horizon (G = 0 there); NaN is handled by the
/// caller. In the plane of incidence this gives the in-plane arguments.
#[inline]
fn dots_args(n_l: f32, n_v: f32, l_v: f32) -> Option<DotsArgs> {
    if !(n_l > 0.0 && n_v > 0.0) {
        return None;
    }
    let (ci, co) = (n_l.min(1.0), n_v.min(1.0));
    let (si, so) = (
        libm::sqrtf((1.0 - ci * ci).max(0.0)),
        libm::sqrtf((1.0 - co * co).max(0.0)),
    );
    let tt = crate::axis::clamp(l_v, -1.0, 1.0) - ci * co;
    let hz = ci + co;
    let side = |c: f32, s: f32| -> [f32; 2] {
        let theta = libm::atan2f(s, c);
        // With s = 0 the tilt does not matter (M(0, a) = 1): take a = 0.
        let a = if s > 0.0 {
            libm::atan2f(tt + s * s, s * hz)
        } else {
            0.0
        };
        [theta, theta - 2.0 * a]
    };
    Some((side(co, so), side(ci, si), (co, ci)))
}

/// G = min(GM, GS) (paper eq 13) as one select (the factors are not NaN: NaN queries
/// return before the lookup).
#[inline(always)]
pub(crate) fn min_g(gm: f32, gs: f32) -> f32 {
    if gs < gm {
        gs
    } else {
        gm
    }
}

#[inline]
pub(crate) fn unit01(x: f32) -> f32 {
    crate::axis::clamp(x, 0.0, 1.0)
}

macro_rules! typed_table {
    ($(#[$doc:meta])* $name:ident, $kind:expr, $dims:expr) => {
        $(#[$doc])*
        #[derive(Clone, Debug)]
        pub struct $name<B = &'static [u8]> {
            bytes: B,
            p: Prepared,
        }

        impl<B: AsRef<[u8]>> $name<B> {
            /// Validates `bytes` (every check of [`LutView::parse`], CRC included), checks
            /// the kind and shape, and prepares the lookup constants.
            pub fn parse(bytes: B) -> Result<Self, LutError> {
                let p = Prepared::expect(&LutView::parse(bytes.as_ref())?, $kind, $dims)?;
                Ok(Self { bytes, p })
            }
            /// The table's bytes.
            pub fn bytes(&self) -> &[u8] {
                self.bytes.as_ref()
            }
            /// Gives the bytes back.
            pub fn into_bytes(self) -> B {
                self.bytes
            }
            /// A view of the bytes (header, raw payload, general sampling). Re-decodes the
            /// header without the CRC; fails only if `B` no longer gives the bytes that
            /// were parsed.
            pub fn view(&self) -> Result<LutView<'_>, LutError> {
                LutView::parse_skip_checksum(self.bytes.as_ref())
            }
            #[cfg_attr(not(hosted), inline)]
            #[cfg_attr(hosted, inline(always))]
            fn payload(&self) -> &[u8] {
                self.bytes.as_ref().get(self.p.header_len..).unwrap_or(&[])
            }
        }

        impl<'a> $name<&'a [u8]> {
            /// Wraps a parsed view (no second validation).
            pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
                let p = Prepared::expect(&view, $kind, $dims)?;
                let bytes = view.bytes();
                Ok(Self { bytes, p })
            }
        }
    };
}

typed_table!(
    /// The modified G (reciprocal convention) for one fixed σ, from a 2-D passing-factor
    /// table over (θ, φ).
    GTable,
    TableKind::PassingFactor,
    2
);
typed_table!(
    /// The modified G (reciprocal convention) over σ, from a 3-D passing-factor table over
    /// (θ, φ, σ).
    GTable3,
    TableKind::PassingFactor,
    3
);
typed_table!(
    /// Split-sum (A, B) over (μ = n·v, roughness): specular E = F0·A + F90·B.
    DfgTable,
    TableKind::SplitSum,
    2
);
typed_table!(
    /// Directional albedo E(μ, r) with F = 1 (Kulla–Conty).
    AlbedoTable,
    TableKind::DirectionalAlbedo,
    2
);
typed_table!(
    /// Average albedo E_avg(r) = 2∫₀¹ E(μ, r) μ dμ (Kulla–Conty).
    AverageAlbedoTable,
    TableKind::AverageAlbedo,
    1
);

impl<B: AsRef<[u8]>> GTable<B> {
    /// The table's σ (NaN if the header does not say).
    pub fn sigma(&self) -> f32 {
        self.p.sigma
    }
    /// (GM, GS, G) at in-plane angles in radians, θi ∈ [0, π/2], θr ∈ [−π/2, π/2] signed
    /// (clamped; NaN gives NaN). G = min(GM, GS), each clamped to [0, 1] (paper eq 13).
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub fn terms(&self, theta_i: f32, theta_r: f32) -> (f32, f32, f32) {
        self.p.g2(self.payload(), theta_i, theta_r)
    }
    /// G = min(GM, GS); see [`GTable::terms`].
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub fn g(&self, theta_i: f32, theta_r: f32) -> f32 {
        self.terms(theta_i, theta_r).2
    }
    /// G from the dot products a shader has: n·l, n·v, l·v of unit vectors (l toward the
    /// light, v toward the viewer), through the reciprocal 3-D extension of the modified G
    /// (the kernel's `ModifiedG::g_dots`). A direction at or below the horizon gives 0; NaN
    /// gives NaN. In the plane of incidence equal to [`GTable::g`] at the same angles up to
    /// f32 rounding of the angles.
    #[inline]
    pub fn g_dots(&self, n_l: f32, n_v: f32, l_v: f32) -> f32 {
        self.p.g_dots(self.payload(), n_l, n_v, l_v, 0.0)
    }
    /// [`GTable::g`] over slices: `out[k] = g(theta_i[k], theta_r[k])` for k below the
    /// shortest length, which is returned. Bit-identical to the scalar lookup.
    pub fn g_batch(&self, theta_i: &[f32], theta_r: &[f32], out: &mut [f32]) -> usize {
        let p = self.payload();
        let n = theta_i.len().min(theta_r.len()).min(out.len());
        self.p.g_batch(p, theta_i, theta_r, None, &mut out[..n]);
        n
    }
}

impl<B: AsRef<[u8]>> GTable3<B> {
    /// The σ range [lo, hi] of the table (queries outside are clamped).
    pub fn sigma_range(&self) -> (f32, f32) {
        self.p.last_range
    }
    /// (GM, GS, G) at in-plane angles in radians and RMS slope σ (all clamped to the table's
    /// ranges; NaN gives NaN). G = min(GM, GS) (paper eq 13).
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub fn terms(&self, theta_i: f32, theta_r: f32, sigma: f32) -> (f32, f32, f32) {
        self.p.g3(self.payload(), theta_i, theta_r, sigma)
    }
    /// G = min(GM, GS); see [`GTable3::terms`].
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub fn g(&self, theta_i: f32, theta_r: f32, sigma: f32) -> f32 {
        self.terms(theta_i, theta_r, sigma).2
    }
    /// G from the dot products n·l, n·v, l·v at RMS slope σ; see [`GTable::g_dots`].
    #[inline]
    pub fn g_dots(&self, n_l: f32, n_v: f32, l_v: f32, sigma: f32) -> f32 {
        self.p.g_dots(self.payload(), n_l, n_v, l_v, sigma)
    }
    /// [`GTable3::g`] over slices at one σ; returns the number written (the shortest
    /// length). Bit-identical to the scalar lookup.
    pub fn g_batch(&self, theta_i: &[f32], theta_r: &[f32], sigma: f32, out: &mut [f32]) -> usize {
        let p = self.payload();
        let n = theta_i.len().min(theta_r.len()).min(out.len());
        self.p
            .g_batch(p, theta_i, theta_r, Some(sigma), &mut out[..n]);
        n
    }
}

impl<B: AsRef<[u8]>> DfgTable<B> {
    /// (A, B) at μ = n·v and roughness (perceptual r for GGX, σ for Torrance–Sparrow tables;
    /// see the header), clamped to the table's ranges; NaN gives NaN.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub fn ab(&self, mu: f32, roughness: f32) -> (f32, f32) {
        self.p.two_at(self.bytes.as_ref(), mu, roughness)
    }
    /// [`DfgTable::ab`] over slices: `a[k], b[k] = ab(mu[k], roughness[k])` for k below the
    /// shortest length, which is returned. Bit-identical to the scalar lookup.
    pub fn ab_batch(&self, mu: &[f32], roughness: &[f32], a: &mut [f32], b: &mut [f32]) -> usize {
        let p = self.payload();
        let n = mu.len().min(roughness.len()).min(a.len()).min(b.len());
        #[cfg(all(hosted, feature = "std", target_arch = "x86_64"))]
        if self.p.fast2.batch(
            &self.p.reader,
            self.bytes.as_ref(),
            self.p.header_len,
            &mu[..n],
            &roughness[..n],
            [&mut a[..n], &mut b[..n]],
        ) {
            return n;
        }
        let x = [&mu[..n], &roughness[..n]];
        self.p.batch(p, x, [&mut a[..n], &mut b[..n]], |[m, r]| {
            let (a, b) = self.p.two(p, m, r);
            [a, b]
        });
        n
    }
}

/// The two lookups of a 2-D one-channel albedo table over (μ, r): `e` (clamped
/// coordinates, NaN gives NaN) and `e_batch` (over slices, returning the number written,
/// the shortest length; bit-identical to `e`). `$what` names the value in the docs.
macro_rules! albedo_lookups {
    ($table:ident, $what:literal) => {
        impl<B: AsRef<[u8]>> $table<B> {
            #[doc = concat!($what, ", clamped coordinates; NaN gives NaN.")]
            #[inline]
            pub fn e(&self, mu: f32, roughness: f32) -> f32 {
                self.p.two1(self.payload(), mu, roughness)
            }
            #[doc = concat!("[`", stringify!($table), "::e`] over slices; returns the number \
                written (the shortest length). Bit-identical to the scalar lookup.")]
            pub fn e_batch(&self, mu: &[f32], roughness: &[f32], out: &mut [f32]) -> usize {
                let p = self.payload();
                let n = mu.len().min(roughness.len()).min(out.len());
                let x = [&mu[..n], &roughness[..n]];
                self.p
                    .batch(p, x, [&mut out[..n]], |[m, r]| [self.p.two1(p, m, r)]);
                n
            }
        }
    };
}
albedo_lookups!(AlbedoTable, "E(μ, r)");

typed_table!(
    /// Sheen directional albedo E_sheen(μ, r) = ∫ D V μl dωl of the Charlie sheen with
    /// colour 1 (the visibility is the header's model), over (μ = n·v, perceptual r).
    SheenAlbedoTable,
    TableKind::SheenAlbedo,
    2
);

albedo_lookups!(SheenAlbedoTable, "E_sheen(μ, r)");

impl<B: AsRef<[u8]>> AverageAlbedoTable<B> {
    /// E_avg(r), clamped coordinate; NaN gives NaN.
    #[inline]
    pub fn e_avg(&self, roughness: f32) -> f32 {
        self.p.one(self.payload(), roughness)
    }
    /// [`AverageAlbedoTable::e_avg`] over a slice; returns the number written (the shorter
    /// length). Bit-identical to the scalar lookup.
    pub fn e_avg_batch(&self, roughness: &[f32], out: &mut [f32]) -> usize {
        let p = self.payload();
        let n = roughness.len().min(out.len());
        self.p.batch(p, [&roughness[..n]], [&mut out[..n]], |[r]| {
            [self.p.one(p, r)]
        });
        n
    }
}

typed_table!(
    /// Rough-glass directional albedo (R, T) over (μ, roughness, η): the reflected part and
    /// the transmitted energy fraction of light arriving along μ from the side of index 1,
    /// η the far side's index over the near side's (docs/lut-format.md, "Rough glass").
    GlassAlbedoTable,
    TableKind::GlassAlbedo,
    3
);
typed_table!(
    /// Rough-glass average albedo (R_avg, T_avg)(roughness, η) = 2∫₀¹ (R, T)(μ) μ dμ.
    GlassAverageTable,
    TableKind::GlassAverageAlbedo,
    2
);

impl<B: AsRef<[u8]>> GlassAlbedoTable<B> {
    /// (R, T) at μ = cos θ, roughness and η (each clamped to the table's range; NaN gives
    /// NaN): the table's interpolation of its nodes, through the one lookup engine.
    #[cfg_attr(not(hosted), inline)]
    #[cfg_attr(hosted, inline(always))]
    pub fn rt(&self, mu: f32, roughness: f32, eta: f32) -> (f32, f32) {
        let [r, t] =
            self.p
                .reader
                .sample::<3, 2>(&self.p.grid, self.payload(), [mu, roughness, eta]);
        (r, t)
    }
    /// The η range [lo, hi] of the table.
    pub fn eta_range(&self) -> (f32, f32) {
        self.p.last_range
    }
    /// [`GlassAlbedoTable::rt`] over slices: `r[k], t[k] = rt(mu[k], roughness[k], eta[k])`
    /// for k below the shortest length, which is returned. Bit-identical to the scalar
    /// lookup.
    pub fn rt_batch(
        &self,
        (mu, roughness, eta): (&[f32], &[f32], &[f32]),
        r: &mut [f32],
        t: &mut [f32],
    ) -> usize {
        let p = self.payload();
        let n = mu.len().min(roughness.len()).min(eta.len());
        let n = n.min(r.len()).min(t.len());
        let x = [&mu[..n], &roughness[..n], &eta[..n]];
        self.p.batch(p, x, [&mut r[..n], &mut t[..n]], |[m, g, e]| {
            let (r, t) = self.rt(m, g, e);
            [r, t]
        });
        n
    }
}

impl<B: AsRef<[u8]>> GlassAverageTable<B> {
    /// (R_avg, T_avg) at roughness and η (clamped to the table's ranges; NaN gives NaN).
    #[inline]
    pub fn rt_avg(&self, roughness: f32, eta: f32) -> (f32, f32) {
        let [r, t] = self
            .p
            .reader
            .sample::<2, 2>(&self.p.grid, self.payload(), [roughness, eta]);
        (r, t)
    }
    /// [`GlassAverageTable::rt_avg`] over slices; returns the number written (the shortest
    /// length). Bit-identical to the scalar lookup.
    pub fn rt_avg_batch(
        &self,
        (roughness, eta): (&[f32], &[f32]),
        r: &mut [f32],
        t: &mut [f32],
    ) -> usize {
        let p = self.payload();
        let n = roughness.len().min(eta.len()).min(r.len()).min(t.len());
        let x = [&roughness[..n], &eta[..n]];
        self.p.batch(p, x, [&mut r[..n], &mut t[..n]], |[g, e]| {
            let (r, t) = self.rt_avg(g, e);
            [r, t]
        });
        n
    }
}

#[cfg(all(hosted, test, feature = "std"))]
mod tests {
    use super::*;
    use crate::header::Interpolation;
    use brdf_core::geometry::Dots;
    use brdf_core::masking::ModifiedG;

    use crate::testing::asset;

    /// The batch entry points through the baseline (non-AVX2) build of their chunk loops
    /// equal the scalar lookups bit for bit (tests/batch_bits.rs checks the build that
    /// this processor picks), over every kind, NaN, infinities and out-of-range values.
    #[test]
    fn baseline_batches_equal_scalar_lookups() {
        use std::vec::Vec;
        crate::lookup::BASELINE_ONLY.store(true, core::sync::atomic::Ordering::Relaxed);
        let n = 203;
        let special = [f32::NAN, f32::INFINITY, -f32::INFINITY, -0.1, 1.7, 0.0, 1.0];
        let xs = |seed: f32, lo: f32, hi: f32| -> Vec<f32> {
            (0..n)
                .map(|k| {
                    if k % 9 == 4 {
                        special[(k / 9) % special.len()]
                    } else {
                        lo + (hi - lo) * ((seed + 0.618_034 * k as f32) % 1.0)
                    }
                })
                .collect()
        };
        let same = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        let (u, v) = (xs(0.1, -0.1, 1.7), xs(0.4, -1.7, 1.7));
        let mut o = std::vec![0.0; n];
        let mut o2 = std::vec![0.0; n];
        for name in [
            "g_modified_sigma0.3_linear.blut",
            "g_modified_sigma0.3.blut",
        ] {
            let t = GTable::parse(asset(name)).unwrap();
            t.g_batch(&u, &v, &mut o);
            let s: Vec<f32> = u.iter().zip(&v).map(|(&a, &b)| t.g(a, b)).collect();
            assert!(same(&o, &s), "{name}");
        }
        for name in ["g_modified_linear.blut", "g_modified.blut"] {
            let t = GTable3::parse(asset(name)).unwrap();
            t.g_batch(&u, &v, 0.3, &mut o);
            let s: Vec<f32> = u.iter().zip(&v).map(|(&a, &b)| t.g(a, b, 0.3)).collect();
            assert!(same(&o, &s), "{name}");
        }
        let (u, v) = (xs(0.2, -0.1, 1.1), xs(0.7, -0.1, 1.1));
        for name in ["dfg_ggx_linear.blut", "dfg_ggx.blut"] {
            let t = DfgTable::parse(asset(name)).unwrap();
            t.ab_batch(&u, &v, &mut o, &mut o2);
            let (a, b): (Vec<f32>, Vec<f32>) = u.iter().zip(&v).map(|(&m, &r)| t.ab(m, r)).unzip();
            assert!(same(&o, &a) && same(&o2, &b), "{name}");
        }
        let t = AlbedoTable::parse(asset("kc_e_ggx.blut")).unwrap();
        t.e_batch(&u, &v, &mut o);
        let s: Vec<f32> = u.iter().zip(&v).map(|(&m, &r)| t.e(m, r)).collect();
        assert!(same(&o, &s), "E");
        let t = AverageAlbedoTable::parse(asset("kc_eavg_ggx.blut")).unwrap();
        t.e_avg_batch(&v, &mut o);
        let s: Vec<f32> = v.iter().map(|&r| t.e_avg(r)).collect();
        assert!(same(&o, &s), "E_avg");
        // The 3-D two-channel shape (no asset): built here, linear and Catmull–Rom.
        let w = xs(0.9, 0.7, 3.3);
        for interpolation in [Interpolation::Linear, Interpolation::CatmullRom] {
            let b = glass_table(interpolation);
            let t = GlassAlbedoTable::parse(&b[..]).unwrap();
            t.rt_batch((&u, &v, &w), &mut o, &mut o2);
            let (r, tt): (Vec<f32>, Vec<f32>) = (0..n).map(|k| t.rt(u[k], v[k], w[k])).unzip();
            assert!(same(&o, &r) && same(&o2, &tt), "glass {interpolation:?}");
        }
        crate::lookup::BASELINE_ONLY.store(false, core::sync::atomic::Ordering::Relaxed);
    }

    /// A u16 glass-e table of 5 × 4 × 6 nodes over [0, 1]², [1, 3] whose two channels are
    /// different polynomials in the node indices (i, j, l).
    fn glass_table(interpolation: Interpolation) -> std::vec::Vec<u8> {
        let axes = [(5, 0.0, 1.0), (4, 0.0, 1.0), (6, 1.0, 3.0)].map(|(count, lo, hi)| {
            crate::header::Axis {
                count,
                lo,
                hi,
                ..Default::default()
            }
        });
        let spec = crate::write::Spec {
            kind: TableKind::GlassAlbedo,
            axes: &axes,
            channels: &["R", "T"],
            encoding: crate::header::Encoding::Unorm16,
            interpolation,
            generator: Default::default(),
        };
        let values: std::vec::Vec<f64> = (0..120 * 2)
            .map(|k| {
                let (i, j, l) = ((k / 2 % 5) as f64, (k / 10 % 4) as f64, (k / 40) as f64);
                [i + 3.0 * j * j + 7.0 * l, 20.0 - i * l + 0.5 * j][k % 2]
            })
            .collect();
        crate::write::build(&spec, &values, |_| Default::default()).unwrap()
    }

    /// G from dot products through the cosine route (√cos θ straight from n·v, n·l) against
    /// (a) the θ route (θ = atan2, the lane's √cos polynomial) of the same table: the node
    /// indices differ by f32 rounding, ≲ 2e-5 of a cell at cos θ = 0.035 (a θ rounding of
    /// 1e-7 moves √cos θ by 1e-7/(2·0.19), times ~55 cells per unit of √cos θ), so the
    /// values by < 1e-4; (b) the direct kernel's shader form within the table's recorded
    /// max error plus 1e-4 for the f32 angle arithmetic.
    #[test]
    fn g_dots_from_cosines_matches_the_angle_route_and_the_kernel() {
        let direct = ModifiedG::<f64>::new(0.3).unwrap();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for name in [
            "g_modified_sigma0.3_linear.blut",
            "g_modified_sigma0.3.blut",
            "g_modified_linear.blut",
            "g_modified.blut",
        ] {
            let b = asset(name);
            let v = LutView::parse(&b).unwrap();
            let p = Prepared::new(&v);
            assert_eq!(p.dots.is_some(), name.contains("linear"), "{name}");
            let payload = &b[p.header_len..];
            let bound = v.header().error.max_abs as f64 + 1e-4;
            let (mut worst_route, mut worst_kernel) = (0f64, 0f64);
            for _ in 0..4000 {
                let mut dir = || {
                    let z = 0.035 + 0.965 * next();
                    let s = (1.0 - z * z).sqrt();
                    let a = 2.0 * core::f64::consts::PI * next();
                    [s * a.cos(), s * a.sin(), z]
                };
                let (l, w) = (dir(), dir());
                let lv = l[0] * w[0] + l[1] * w[1] + l[2] * w[2];
                let (nl, nv, lv32) = (l[2] as f32, w[2] as f32, lv as f32);
                let got = p.g_dots(payload, nl, nv, lv32, 0.3) as f64;
                let (m, s, _) = dots_args(nl, nv, lv32).unwrap();
                let theta_route = p.g_from_args(payload, m, s, 0.3).2 as f64;
                let want = direct.g_dots(Dots::new(l[2], w[2], lv));
                worst_route = worst_route.max((got - theta_route).abs());
                worst_kernel = worst_kernel.max((got - want).abs());
            }
            std::println!(
                "{name}: |cos − θ route| {worst_route:.1e}, |table − kernel| {worst_kernel:.1e}"
            );
            assert!(worst_route < 1e-4, "{name}: {worst_route}");
            assert!(worst_kernel <= bound, "{name}: {worst_kernel} > {bound}");
        }
    }
}

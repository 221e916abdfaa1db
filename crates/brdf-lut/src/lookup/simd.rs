//! Every use of `core::arch` in the crate (hosted targets only), behind one run-time
//! choice: [`wide`] runs a batch loop compiled for AVX2 when the processor has it (feature
//! `std`, x86-64), else for the baseline (SSE2 on x86-64). Here are the scalar steps as
//! single SSE instructions (`sse`), the AVX2 gathers of the chunk paths
//! ([`gather_words`]), and the two-lane lookup of 2-D one- and two-channel linear u16
//! tables ([`Fast2`], x86-64), whose two-channel batch runs eight queries per AVX2 register.
//!
//! The scalar lookup of a 2-D, two-channel, linear, u16 table (the split-sum speed tier)
//! on hosted x86-64, with the two axes side by side in the lanes of one SSE register.
//!
//! [`Reader::sample`] maps each axis on its own (clamp, warp, t = a·w + b, clamp, node,
//! fraction) and then blends the two channels one after the other. Here both axes go
//! through each of those steps in one packed instruction (SSE2 is part of the x86-64
//! baseline), the 2 × 2 nodes of both channels are read as two 8-byte rows (the payload
//! interleaves the channels, so a row of two nodes is A₀ B₀ A₁ B₁) behind one bounds check,
//! and both channels and both rows are blended at once. A one-channel table (the sheen
//! albedo's speed tier) takes the same steps with 4-byte rows ([`One`]).
//!
//! Bit for bit the values of [`Reader::sample`]: every lane performs the scalar path's IEEE
//! operations in the same order (no fused multiply–add; `maxps`/`minps` are the scalar
//! comparisons' selects, NaN included), apart from operations that provably change no
//! value for the tables that skip them (see `Fast2::cells`). Tables with linear or
//! √-warped axes (w = √(x − lo)) take this path; any other warp, encoding, interpolant or
//! shape keeps the general reader.

/// Runs `body` (a batch loop whose stages are written to vectorise) compiled for AVX2
/// when the processor has it (with feature `std` on x86-64, detected at run time; the
/// standard library caches the answer), else as compiled for the baseline (SSE2 on
/// x86-64). Only the vector width changes: AVX2 has no fused multiply-add (that is FMA,
/// which stays off, as it would round a·b + c once instead of twice), and packed add,
/// multiply, divide, square root, min/max and conversions round exactly like their scalar
/// forms, so the values are the same bit for bit.
#[inline(always)]
pub(crate) fn wide<R>(body: impl FnOnce(bool) -> R) -> R {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if std::is_x86_feature_detected!("avx2") && !baseline_only() {
        // SAFETY: `avx2` only requires that the processor support AVX2, checked just above.
        return unsafe { avx2(body) };
    }
    body(false)
}

/// Unit tests: the batch loops run their baseline build even where AVX2 is available.
#[cfg(all(test, feature = "std"))]
pub(crate) static BASELINE_ONLY: core::sync::atomic::AtomicBool =
    core::sync::atomic::AtomicBool::new(false);
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[inline(always)]
fn baseline_only() -> bool {
    #[cfg(all(test, feature = "std"))]
    return BASELINE_ONLY.load(core::sync::atomic::Ordering::Relaxed);
    #[cfg(not(all(test, feature = "std")))]
    false
}

/// `body(true)` compiled with AVX2 enabled (its stages are inlined into this function;
/// `true` tells them that they may use AVX2 instructions, e.g. [`rows`]' gathers).
///
/// # Safety
/// The processor must support AVX2.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
unsafe fn avx2<R>(body: impl FnOnce(bool) -> R) -> R {
    body(true)
}

/// Scalar steps of the lookups as single SSE instructions (x86-64, hosted targets):
/// `sqrt_v` √x, correctly rounded like `libm::sqrtf` (IEEE 754 square root, so the same
/// bits), but in a form the compiler can turn into packed `sqrtps` in the chunk loops
/// (libm's is inline assembly, which it cannot); `clamp_s` [`clamp`] as one max and one min
/// instruction (NaN stays NaN; the plain comparisons let the compiler turn a two-lane clamp
/// into a vector compare, a mask extraction and branches); `min_s` min(t, m) = (t < m ? t :
/// m); `trunc_small` ⌊x⌋ of x ∈ [0, 2¹⁶) as the processor's truncating conversion, without
/// the saturation checks of `as` (callers pass no NaN).
#[cfg(target_arch = "x86_64")]
mod sse {
    use core::arch::x86_64::{
        _mm_cvtss_f32, _mm_cvttss_si32, _mm_max_ss, _mm_min_ss, _mm_set_ss, _mm_sqrt_ss,
    };

    /// Evaluates an expression of the SSE intrinsics imported above.
    macro_rules! sse {
        ($e:expr) => {{
            // SAFETY: SSE is part of the x86_64 baseline, and these intrinsics only compute
            // on registers (no memory access). They are safe functions from Rust 1.87 on;
            // the block is for the crate's minimum Rust, 1.84.
            #[allow(unused_unsafe)]
            unsafe {
                $e
            }
        }};
    }

    #[inline(always)]
    pub(crate) fn sqrt_v(x: f32) -> f32 {
        sse!(_mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))))
    }

    /// maxss/minss return their second operand when either is NaN:
    /// (lo > x ? lo : x), then (hi < y ? hi : y).
    #[inline(always)]
    pub(crate) fn clamp_s(x: f32, lo: f32, hi: f32) -> f32 {
        let y = sse!(_mm_max_ss(_mm_set_ss(lo), _mm_set_ss(x)));
        sse!(_mm_cvtss_f32(_mm_min_ss(_mm_set_ss(hi), y)))
    }

    #[inline(always)]
    pub(crate) fn min_s(t: f32, m: f32) -> f32 {
        sse!(_mm_cvtss_f32(_mm_min_ss(_mm_set_ss(t), _mm_set_ss(m))))
    }

    #[inline(always)]
    pub(crate) fn trunc_small(x: f32) -> i32 {
        sse!(_mm_cvttss_si32(_mm_set_ss(x)))
    }
}

/// [`sse`]'s steps in portable form (the same values) on other hosted processors.
#[cfg(not(target_arch = "x86_64"))]
mod sse {
    pub(crate) use crate::axis::clamp as clamp_s;
    pub(crate) use libm::sqrtf as sqrt_v;

    #[inline(always)]
    pub(crate) fn min_s(t: f32, m: f32) -> f32 {
        if t < m {
            t
        } else {
            m
        }
    }

    #[inline(always)]
    pub(crate) fn trunc_small(x: f32) -> i32 {
        x as i32
    }
}

pub(crate) use sse::{clamp_s, min_s, sqrt_v, trunc_small};

/// [`rows`]' gathers: `words[r][j][k]` = the little-endian 32-bit word at byte
/// `idx[k] + off[r] + 4j` from `base`, eight queries per gather (`N` a multiple of 8).
///
/// # Safety
/// The processor supports AVX2, and every such word lies in one allocation at `base`,
/// with every offset below 2³¹.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn gather_words<const N: usize, const R: usize, const W: usize>(
    base: *const u8,
    idx: &[u32; N],
    off: &[u32; R],
    words: &mut [[[u32; N]; W]; R],
) {
    use core::arch::x86_64::{
        __m256i, _mm256_add_epi32, _mm256_i32gather_epi32, _mm256_loadu_si256, _mm256_set1_epi32,
        _mm256_storeu_si256,
    };
    for g in (0..N).step_by(8) {
        // SAFETY: the 8 lanes from g lie in `idx` (g < N, N a multiple of 8); AVX2 is
        // there (the contract).
        let v = unsafe { _mm256_loadu_si256(idx.as_ptr().add(g).cast::<__m256i>()) };
        for (wr, &o) in words.iter_mut().zip(off) {
            for (j, w) in wr.iter_mut().enumerate() {
                // SAFETY: register-only AVX2 (this function's contract: the processor
                // supports AVX2); a safe call from Rust 1.87 on, the block is for 1.84.
                #[allow(unused_unsafe)]
                let o =
                    unsafe { _mm256_add_epi32(v, _mm256_set1_epi32((o + 4 * j as u32) as i32)) };
                // SAFETY: the gathered words lie in the allocation at `base` (the
                // contract), and the store writes lanes g..g + 8 < N of `w`.
                unsafe {
                    let x = _mm256_i32gather_epi32::<1>(base.cast::<i32>(), o);
                    _mm256_storeu_si256(w.as_mut_ptr().add(g).cast::<__m256i>(), x);
                }
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
use super::{Lane, Mode, Reader};
#[cfg(target_arch = "x86_64")]
use crate::header::{Encoding, Warp};
#[cfg(target_arch = "x86_64")]
use core::arch::x86_64::{
    __m128, __m128i, _mm_add_ps, _mm_and_ps, _mm_andnot_ps, _mm_cvtepi32_ps, _mm_cvtsi128_si32,
    _mm_cvtsi32_si128, _mm_cvtss_f32, _mm_cvttps_epi32, _mm_loadl_epi64, _mm_max_ps, _mm_min_ps,
    _mm_movehl_ps, _mm_mul_ps, _mm_or_ps, _mm_setr_ps, _mm_setzero_ps, _mm_setzero_si128,
    _mm_shuffle_epi32, _mm_shuffle_ps, _mm_sqrt_ps, _mm_sub_epi32, _mm_sub_ps, _mm_unpackhi_epi16,
    _mm_unpacklo_epi16, _mm_unpacklo_epi32,
};

#[cfg(target_arch = "x86_64")]
/// Which form of the two-lane lookup a table takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Not this path (another shape, warp, encoding or interpolant).
    None,
    /// Both axes √-warped with endpoint nodes (b = 0), t at hi rounds to at most n − 1,
    /// and axis 0 has 2^k nodes: the split-sum speed tier. Inlined, with the constants
    /// below.
    Sqrt,
    /// Any other mix of linear and √ axes: the general form, out of line, with the
    /// constants read from the lanes.
    Mixed,
    /// [`Kind::Sqrt`] of a one-channel table ([`One`]).
    SqrtOne,
    /// [`Kind::Mixed`] of a one-channel table ([`One`]).
    MixedOne,
}

#[cfg(target_arch = "x86_64")]
/// The per-table constants of the `Sqrt` form: lane 0 is axis 0 (μ), lane 1 axis 1
/// (roughness). Small (40 bytes): the C interface keeps a prepared table in a fixed-size
/// handle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fast2 {
    lo: [f32; 2],
    /// hi − lo (rounded to f32).
    span: [f32; 2],
    a: [f32; 2],
    /// n − 2 per axis.
    last_cell: [f32; 2],
    /// Bytes between the rows of axis 1 (below 2³², see [`Fast2::new`]).
    row: u32,
    /// log₂ `row` (`Sqrt` tables, whose rows are a power of two bytes long).
    row_shift: u8,
    pub(crate) kind: Kind,
}

#[cfg(target_arch = "x86_64")]
/// Two constants in lanes 0 and 1 (one 8-byte load).
#[inline(always)]
fn pair(v: &[f32; 2]) -> __m128 {
    // SAFETY: register-only SSE (see `Fast2::cells`).
    #[allow(unused_unsafe)]
    unsafe {
        _mm_setr_ps(v[0], v[1], 0.0, 0.0)
    }
}

#[cfg(target_arch = "x86_64")]
/// Both channels NaN: a payload too short for the block (impossible for a parsed table;
/// the scalar reader gives NaN too). Out of line, so the fast path does not prepare it.
#[cold]
#[inline(never)]
fn short() -> (f32, f32) {
    (f32::NAN, f32::NAN)
}

#[cfg(target_arch = "x86_64")]
impl Fast2 {
    /// The form and constants of the two-lane lookup for `reader`'s table.
    pub(crate) fn new(reader: &Reader, dims: usize, channels: usize) -> Self {
        let [l0, l1, _] = &reader.lanes;
        let known = |l: &Lane| matches!(l.warp, Warp::Sqrt | Warp::Linear);
        // Offsets are computed in u32: a 2-D table holds at most `MAX_VALUES` (2²⁶) values of
        // 2 bytes, so every offset in the payload is below 2³².
        let row = u32::try_from(l1.stride * 2).ok();
        let fits = dims == 2
            && (channels == 1 || channels == 2)
            && reader.mode == Mode::Linear
            && reader.encoding == Encoding::Unorm16
            && known(l0)
            && known(l1)
            && row.is_some()
            // The scalar reader's layout: axis 0 innermost, the channels interleaved.
            && l0.stride == channels
            && l1.stride == channels * l0.n
            && l0.n >= 2
            && l1.n >= 2;
        // The `Sqrt` form: t = a·√(x − lo) (b = +0: endpoint nodes), and the clamp of t to
        // [0, n − 1] is free: t ≥ 0, and t at hi rounds to at most n − 1, so every x in
        // [lo, hi] gives t ≤ n − 1 (rounding is monotone, a > 0).
        let sqrt0 = |l: &Lane| {
            l.warp == Warp::Sqrt
                && l.b.to_bits() == 0
                && l.a > 0.0
                && l.a * libm::sqrtf(l.hi - l.lo) <= l.last
        };
        let kind = match (fits, channels == 1) {
            (false, _) => Kind::None,
            (true, one) if sqrt0(l0) && sqrt0(l1) && row.is_some_and(u32::is_power_of_two) => {
                [Kind::Sqrt, Kind::SqrtOne][one as usize]
            }
            (true, one) => [Kind::Mixed, Kind::MixedOne][one as usize],
        };
        Fast2 {
            lo: [l0.lo, l1.lo],
            span: [l0.hi - l0.lo, l1.hi - l1.lo],
            a: [l0.a, l1.a],
            last_cell: [l0.last_cell_f, l1.last_cell_f],
            row: row.unwrap_or(0),
            row_shift: row.unwrap_or(0).trailing_zeros() as u8,
            kind,
        }
    }

    /// The lookup at (x, y) of `reader`'s table of `K` nodes, whose payload starts at byte
    /// `base` of `data`: [`Reader::sample`] bit for bit (`::<2, 2>` channels 0 and 1 of a
    /// two-channel table, [`Two`]; `::<2, 1>` of a one-channel one, [`One`]); NaN in either
    /// coordinate gives NaN; coordinates are clamped to the axes' ranges. `None` if the
    /// table does not take this path.
    #[inline(always)]
    pub(crate) fn lookup<K: Node>(
        &self,
        reader: &Reader,
        data: &[u8],
        base: usize,
        x: f32,
        y: f32,
    ) -> Option<K::Out> {
        if self.kind == K::SQRT {
            let node = self.node_at::<true>(reader, x, y, K::BYTES);
            Some(self.read::<K>(reader, data, base, node))
        } else if self.kind == K::MIXED {
            Some(self.mixed::<K>(reader, data, base, x, y))
        } else {
            None
        }
    }

    /// [`Fast2::lookup`] of a two-channel table over slices of one length (`a[k], b[k]` at `(x[k], y[k])`), eight
    /// queries at a time with AVX2 when the processor has it: `false` (nothing written)
    /// unless the table takes the `Sqrt` form and AVX2 is there. Bit for bit the scalar
    /// lookup: the eight lanes perform its IEEE operations in its order, and the tail of
    /// fewer than eight queries is the scalar lookup itself.
    #[cfg(feature = "std")]
    #[inline(always)]
    pub(crate) fn batch(
        &self,
        reader: &Reader,
        data: &[u8],
        base: usize,
        x: &[f32],
        y: &[f32],
        out: [&mut [f32]; 2],
    ) -> bool {
        let n = x.len();
        let [a, b] = out;
        if self.kind != Kind::Sqrt || y.len() != n || a.len() != n || b.len() != n {
            return false;
        }
        let Some(limit) = self.limit(data, base) else {
            return false;
        };
        wide(
            #[inline(always)]
            // SAFETY: `avx2` is true only where the processor has AVX2 (`wide`'s check).
            |avx2| avx2 && unsafe { self.batch_avx2(reader, data, base, limit, x, y, [a, b]) },
        )
    }

    /// The largest row offset (from `base`) whose two rows (the second `row` bytes on) end
    /// in `data`, at most 2³¹ − 1; `None` if no row fits.
    #[cfg(feature = "std")]
    pub(crate) fn limit(&self, data: &[u8], base: usize) -> Option<u32> {
        let l = data.len().checked_sub(base + self.row as usize + 8)?;
        u32::try_from(l.min(i32::MAX as usize)).ok()
    }

    /// [`Fast2::batch`] past its checks: `limit` is the largest row offset whose two rows
    /// end in `data` (below 2³¹), the slices have one length, and the table takes the
    /// `Sqrt` form. Returns `true`.
    ///
    /// # Safety
    /// The processor supports AVX2.
    #[cfg(feature = "std")]
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) unsafe fn batch_avx2(
        &self,
        reader: &Reader,
        data: &[u8],
        base: usize,
        limit: u32,
        x: &[f32],
        y: &[f32],
        out: [&mut [f32]; 2],
    ) -> bool {
        let [a, b] = out;
        let n = x.len();
        // SAFETY: `data` from `base`, base ≤ len (`limit` exists).
        let p = unsafe { data.as_ptr().add(base) };
        let one =
            |x, y| self.read::<Two>(reader, data, base, self.node_at::<true>(reader, x, y, 4));
        let mut k = 0;
        while k + 8 <= n {
            let (xs, ys) = (&x[k..k + 8], &y[k..k + 8]);
            let (ak, bk) = (&mut a[k..k + 8], &mut b[k..k + 8]);
            // SAFETY: AVX2 (the caller's contract), eight values per slice, and a row offset
            // at ≤ limit reads bytes base + at up to base + at + row + 8 ≤ len; limit < 2³¹.
            let done = unsafe { wide8::eight(self, reader, p, limit, xs, ys, [ak, bk]) };
            if !done {
                for j in k..k + 8 {
                    (a[j], b[j]) = one(x[j], y[j]);
                }
            }
            k += 8;
        }
        for j in k..n {
            (a[j], b[j]) = one(x[j], y[j]);
        }
        true
    }

    /// [`Fast2::lookup`] of a `Mixed` or `MixedOne` table (no shipped table is one; marked
    /// cold so that the `Sqrt` test comes first).
    #[cold]
    #[inline(never)]
    fn mixed<K: Node>(&self, reader: &Reader, data: &[u8], base: usize, x: f32, y: f32) -> K::Out {
        self.read::<K>(
            reader,
            data,
            base,
            self.node_at::<false>(reader, x, y, K::BYTES),
        )
    }

    /// The node index (lanes 0, 1: axis 0, 1; a truncating conversion) and the fraction of
    /// both axes of [`Fast2::lookup`]'s query: clamp, warp, t = a·w + b, clamp of t, node.
    #[inline(always)]
    fn cells<const SQRT: bool>(&self, reader: &Reader, x: f32, y: f32) -> (__m128i, __m128) {
        let [l0, l1, _] = &reader.lanes;
        // SAFETY: SSE and SSE2 are part of the x86-64 baseline, and these intrinsics only
        // compute on registers (no memory access). They are safe functions from Rust 1.87
        // on; the block is for the crate's minimum Rust, 1.84.
        #[allow(unused_unsafe)]
        unsafe {
            // Lanes 2 and 3 repeat the query; their results are not used.
            let x = _mm_setr_ps(x, y, x, y);
            // `maxps`/`minps` return their second operand unless the comparison holds, so
            // these are [`crate::axis::clamp`]'s selects: (lo > x ? lo : x), then
            // (hi < x ? hi : x); NaN stays NaN.
            let t = if SQRT {
                // √(clamp(x, lo, hi) − lo) as √ of x − lo clamped to [0, hi − lo]: the same
                // f32 for every x. In range both subtract the same numbers; below lo, x − lo
                // is negative (a non-zero difference of two f32 is at least the smallest
                // subnormal, so it does not round to zero) and becomes +0 = lo − lo; above
                // hi, x − lo ≥ hi − lo (rounding is monotone) and becomes hi − lo; NaN passes
                // through both, and so does −0 (x = −0, lo = +0: −0 − 0 = −0).
                let d = _mm_max_ps(_mm_setzero_ps(), _mm_sub_ps(x, pair(&self.lo)));
                let w = _mm_sqrt_ps(_mm_min_ps(pair(&self.span), d));
                // b = +0: a·w + b = a·w except that a·w = −0 (w = −0 above) becomes +0
                // there; that only flips the sign of a zero fraction, and p₀ + (±0) = p₀
                // for the stored p₀ ≥ +0 below (and then for r₀ ≥ +0), so no value
                // changes. The clamp of t is free (see `Fast2::new`).
                _mm_mul_ps(pair(&self.a), w)
            } else {
                let c = |f: fn(&Lane) -> f32| _mm_setr_ps(f(l0), f(l1), 0.0, 0.0);
                let lo = c(|l| l.lo);
                let x = _mm_min_ps(c(|l| l.hi), _mm_max_ps(lo, x));
                // w = √(x − lo) or w = x per lane; t = a·w + b, clamped to [0, n − 1].
                let root = _mm_sqrt_ps(_mm_sub_ps(x, lo));
                let sq = |l: &Lane| f32::from_bits(if l.warp == Warp::Sqrt { !0 } else { 0 });
                let m = _mm_setr_ps(sq(l0), sq(l1), 0.0, 0.0);
                let w = _mm_or_ps(_mm_and_ps(m, root), _mm_andnot_ps(m, x));
                let t = _mm_add_ps(_mm_mul_ps(c(|l| l.a), w), c(|l| l.b));
                _mm_min_ps(c(|l| l.last), _mm_max_ps(_mm_setzero_ps(), t))
            };
            // Node ⌊min(t, n − 2)⌋ by the truncating conversion (t ≥ 0); NaN takes node
            // n − 2 (min returns its second operand) and keeps f = NaN.
            let i = _mm_cvttps_epi32(_mm_min_ps(t, pair(&self.last_cell)));
            (i, _mm_sub_ps(t, _mm_cvtepi32_ps(i)))
        }
    }

    /// The byte offset in the payload of the query's first node (nodes of `node` bytes:
    /// 4 for two u16 channels, 2 for one; a constant once inlined) and the fractions of both
    /// axes ([`Fast2::cells`]).
    #[inline(always)]
    fn node_at<const SQRT: bool>(
        &self,
        reader: &Reader,
        x: f32,
        y: f32,
        node: u32,
    ) -> (usize, __m128) {
        let (i, f) = self.cells::<SQRT>(reader, x, y);
        // SAFETY: as above (register-only SSE2).
        #[allow(unused_unsafe)]
        let (i0, i1) = unsafe {
            (
                _mm_cvtsi128_si32(i) as u32,
                _mm_cvtsi128_si32(_mm_shuffle_epi32(i, 0b01)) as u32,
            )
        };
        // Byte offset of node (i0, i1) in the payload: below 2³² for every node of the
        // table (see `Fast2::new`; the wrapping only matters for nodes the clamp never
        // gives), so the callers' sums cannot overflow a 64-bit usize (`base` is at most
        // `data.len()`).
        // (`Sqrt` tables: rows of 2^k bytes, a shift instead of the multiplication: one
        // step shorter on the way to the loads.)
        let r1 = if SQRT {
            i1.wrapping_shl(u32::from(self.row_shift))
        } else {
            i1.wrapping_mul(self.row)
        };
        (i0.wrapping_mul(node).wrapping_add(r1) as usize, f)
    }

    /// The value of the query whose first node is at byte `at` of the payload, with the
    /// fractions `f` of both axes (`node`: [`Fast2::node_at`]): one bounds check for both
    /// rows, then [`Node::blend`].
    #[inline(always)]
    fn read<K: Node>(
        &self,
        reader: &Reader,
        data: &[u8],
        base: usize,
        (at, f): (usize, __m128),
    ) -> K::Out {
        let row = self.row as usize;
        if base + at + row + 2 * K::BYTES as usize > data.len() {
            return K::short();
        }
        // SAFETY: base + at + row + 2·BYTES ≤ data.len() (checked above), so both rows of two
        // nodes lie in `data`.
        unsafe { K::blend(data.as_ptr().add(base + at), row, f, reader) }
    }
}

/// The nodes of a two-lane table: u16 numbers of two channels ([`Two`]) or one ([`One`]),
/// interleaved; their lookup's value, its forms and the blend of a query's 2 × 2 nodes.
#[cfg(target_arch = "x86_64")]
pub(crate) trait Node {
    /// The value: both channels, or the one.
    type Out;
    /// Bytes per node.
    const BYTES: u32;
    /// The inlined form of such a table.
    const SQRT: Kind;
    /// The out-of-line form.
    const MIXED: Kind;
    /// Every channel NaN (a payload too short for the block; see [`short`]).
    fn short() -> Self::Out;
    /// Blends the 2 × 2 nodes at `p` (row 0) and `p + row` (row 1) with the fractions of
    /// axis 0 and 1 in lanes 0 and 1 of `f`, then offset + scale per channel: the scalar
    /// path's operations in its order.
    ///
    /// # Safety
    /// `p` and `p + row` each start `2 · BYTES` readable bytes of one allocation.
    unsafe fn blend(p: *const u8, row: usize, f: __m128, reader: &Reader) -> Self::Out;
}

/// Two-channel nodes (the split-sum speed tier).
#[cfg(target_arch = "x86_64")]
pub(crate) struct Two;
/// One-channel nodes (the sheen albedo's speed tier).
#[cfg(target_arch = "x86_64")]
pub(crate) struct One;

#[cfg(target_arch = "x86_64")]
impl Node for Two {
    type Out = (f32, f32);
    const BYTES: u32 = 4;
    const SQRT: Kind = Kind::Sqrt;
    const MIXED: Kind = Kind::Mixed;
    #[inline(always)]
    fn short() -> (f32, f32) {
        short()
    }
    #[inline(always)]
    unsafe fn blend(p: *const u8, row: usize, f: __m128, reader: &Reader) -> (f32, f32) {
        let (sc, of) = (&reader.scale, &reader.offset);
        // SAFETY: both 8-byte reads lie in one allocation (the contract; `movq` has no
        // alignment requirement); the rest is register-only SSE2.
        #[allow(unused_unsafe)]
        unsafe {
            // Stored u16 (node, row): A₀₀ B₀₀ A₁₀ B₁₀ and A₀₁ B₀₁ A₁₁ B₁₁.
            let r0 = _mm_loadl_epi64(p.cast::<__m128i>());
            let r1 = _mm_loadl_epi64(p.add(row).cast::<__m128i>());
            // (A₀₀ B₀₀)(A₀₁ B₀₁)(A₁₀ B₁₀)(A₁₁ B₁₁): node 0 of both rows, then node 1, each
            // number widened to 32 bits (exact in f32).
            let q = _mm_unpacklo_epi32(r0, r1);
            let z = _mm_setzero_si128();
            let (q0, q1) = (_mm_unpacklo_epi16(q, z), _mm_unpackhi_epi16(q, z));
            // p₁ − p₀ of integers below 2¹⁶ is exact in f32, so it may be formed in the
            // integer unit (one step shorter than after the conversion; the same f32).
            let p0 = _mm_cvtepi32_ps(q0);
            let d = _mm_cvtepi32_ps(_mm_sub_epi32(q1, q0));
            // Along axis 0: r = p₀ + f₀ (p₁ − p₀) = (r₀A, r₀B, r₁A, r₁B).
            let f0 = _mm_shuffle_ps(f, f, 0);
            let r = _mm_add_ps(p0, _mm_mul_ps(f0, d));
            // Along axis 1: v = r₀ + f₁ (r₁ − r₀), then offset + scale · v per channel.
            let f1 = _mm_shuffle_ps(f, f, 0b0101_0101);
            let v = _mm_add_ps(r, _mm_mul_ps(f1, _mm_sub_ps(_mm_movehl_ps(r, r), r)));
            let v = _mm_add_ps(
                _mm_setr_ps(of[0], of[1], 0.0, 0.0),
                _mm_mul_ps(_mm_setr_ps(sc[0], sc[1], 0.0, 0.0), v),
            );
            let b = _mm_shuffle_ps(v, v, 0b01);
            (_mm_cvtss_f32(v), _mm_cvtss_f32(b))
        }
    }
}

#[cfg(target_arch = "x86_64")]
impl Node for One {
    type Out = f32;
    const BYTES: u32 = 2;
    const SQRT: Kind = Kind::SqrtOne;
    const MIXED: Kind = Kind::MixedOne;
    #[inline(always)]
    fn short() -> f32 {
        short().0
    }
    /// [`Two`]'s steps for one channel: the rows are two u16 nodes (4 bytes) each, so lanes
    /// 0 and 1 carry the two rows.
    #[inline(always)]
    unsafe fn blend(p: *const u8, row: usize, f: __m128, reader: &Reader) -> f32 {
        // SAFETY: both 4-byte reads lie in one allocation (the contract; unaligned reads);
        // the rest is register-only SSE2.
        #[allow(unused_unsafe)]
        let v = unsafe {
            // Stored u16 (node, row): A₀₀ A₁₀ and A₀₁ A₁₁.
            let r0 = _mm_cvtsi32_si128(p.cast::<i32>().read_unaligned());
            let r1 = _mm_cvtsi32_si128(p.add(row).cast::<i32>().read_unaligned());
            // (A₀₀ A₀₁ A₁₀ A₁₁): node 0 of both rows, then node 1, widened to 32 bits.
            let q = _mm_unpacklo_epi16(_mm_unpacklo_epi16(r0, r1), _mm_setzero_si128());
            // p₁ − p₀ in the integer unit, exact as in [`Two`]'s.
            let p0 = _mm_cvtepi32_ps(q);
            let d = _mm_cvtepi32_ps(_mm_sub_epi32(_mm_shuffle_epi32(q, 0b1110), q));
            // Along axis 0: r = p₀ + f₀ (p₁ − p₀) = (r₀, r₁).
            let r = _mm_add_ps(p0, _mm_mul_ps(_mm_shuffle_ps(f, f, 0), d));
            // Along axis 1: v = r₀ + f₁ (r₁ − r₀).
            let f1 = _mm_shuffle_ps(f, f, 0b0101_0101);
            let v = _mm_add_ps(r, _mm_mul_ps(f1, _mm_sub_ps(_mm_shuffle_ps(r, r, 0b01), r)));
            _mm_cvtss_f32(v)
        };
        reader.offset[0] + reader.scale[0] * v
    }
}

#[cfg(target_arch = "x86_64")]
/// Eight lookups at once: [`Fast2::batch`]'s AVX2 body.
#[cfg(feature = "std")]
mod wide8 {
    use super::{Fast2, Reader};
    use core::arch::x86_64::{
        __m256, __m256i, _mm256_add_epi32, _mm256_add_ps, _mm256_and_si256, _mm256_castps_si256,
        _mm256_castsi128_si256, _mm256_castsi256_ps, _mm256_cmpgt_epi32, _mm256_cvtepi32_ps,
        _mm256_cvttps_epi32, _mm256_extract_epi32, _mm256_inserti128_si256, _mm256_loadu_ps,
        _mm256_max_ps, _mm256_min_ps, _mm256_movemask_epi8, _mm256_mul_ps, _mm256_set1_epi32,
        _mm256_set1_ps, _mm256_setzero_ps, _mm256_shuffle_ps, _mm256_sll_epi32, _mm256_slli_epi32,
        _mm256_sqrt_ps, _mm256_srli_epi32, _mm256_storeu_ps, _mm256_sub_epi32, _mm256_sub_ps,
        _mm_castpd_si128, _mm_castsi128_pd, _mm_cvtsi32_si128, _mm_loadh_pd, _mm_loadl_epi64,
    };

    /// Node and fraction of eight coordinates on one `Sqrt` axis: [`Fast2::cells`]' lane
    /// steps (the same IEEE operations, eight lanes wide).
    ///
    /// # Safety
    /// The processor supports AVX2 (callers: [`eight`], entered through `wide`'s check).
    #[inline(always)]
    unsafe fn cells(f: &Fast2, k: usize, x: __m256) -> (__m256i, __m256) {
        // SAFETY: AVX instructions on registers only (no memory access), and the processor
        // supports AVX2 (this function's contract).
        unsafe {
            let d = _mm256_max_ps(
                _mm256_setzero_ps(),
                _mm256_sub_ps(x, _mm256_set1_ps(f.lo[k])),
            );
            let w = _mm256_sqrt_ps(_mm256_min_ps(_mm256_set1_ps(f.span[k]), d));
            let t = _mm256_mul_ps(_mm256_set1_ps(f.a[k]), w);
            let i = _mm256_cvttps_epi32(_mm256_min_ps(t, _mm256_set1_ps(f.last_cell[k])));
            (i, _mm256_sub_ps(t, _mm256_cvtepi32_ps(i)))
        }
    }

    /// The 8-byte rows at `p + at[k]` for queries (k, k + 1, k + 4, k + 5), k = 0 or 2:
    /// lanes 0–1 of the result hold queries k and k + 1, lanes 2–3 queries k + 4, k + 5.
    ///
    /// # Safety
    /// The processor supports AVX2, and the 8 bytes at `p + at[j]` lie in one allocation
    /// for j = k, k + 1, k + 4, k + 5.
    #[inline(always)]
    unsafe fn rows4(p: *const u8, at: &[u32; 8], k: usize) -> __m256i {
        let two = |j: usize| {
            // SAFETY: the 8 bytes at p + at[j] and p + at[j + 1] lie in one allocation
            // (this function's contract; `movq`/`movhpd` need no alignment); SSE2 is part
            // of the x86-64 baseline.
            unsafe {
                let lo = _mm_loadl_epi64(p.add(at[j] as usize).cast());
                _mm_castpd_si128(_mm_loadh_pd(
                    _mm_castsi128_pd(lo),
                    p.add(at[j + 1] as usize).cast(),
                ))
            }
        };
        // SAFETY: register-only AVX2 insertion; the processor supports AVX2 (the contract).
        unsafe { _mm256_inserti128_si256::<1>(_mm256_castsi128_si256(two(k)), two(k + 4)) }
    }

    /// Channels A and B of eight queries of a `Sqrt` table whose payload starts at `p`, or
    /// `None` when a row would lie past `limit` (the largest valid row offset; impossible
    /// for a parsed table).
    ///
    /// # Safety
    /// AVX2 is available; `x`, `y` and both `out` slices hold at least 8 values; and every
    /// 8-byte read at `p + at` and `p + at + row` with at ≤ `limit` lies in one allocation;
    /// `limit` < 2³¹.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) unsafe fn eight(
        f: &Fast2,
        reader: &Reader,
        p: *const u8,
        limit: u32,
        x: &[f32],
        y: &[f32],
        out: [&mut [f32]; 2],
    ) -> bool {
        // SAFETY: the processor supports AVX2, as `cells` and `rows4` require (this
        // function's contract); the loads read 8 values of `x` and `y` and the stores
        // write 8 values of each `out` slice, all of at least 8 (the contract); the row
        // reads at p + at and q + at = p + row + at lie in the allocation for every
        // at ≤ `limit`, which is checked for all eight offsets before any read.
        unsafe {
            let (i0, f0) = cells(f, 0, _mm256_loadu_ps(x.as_ptr()));
            let (i1, f1) = cells(f, 1, _mm256_loadu_ps(y.as_ptr()));
            // Byte offset of node (i0, i1): 4·i0 + i1 · 2^row_shift, as in the scalar path.
            let at = _mm256_add_epi32(
                _mm256_slli_epi32::<2>(i0),
                _mm256_sll_epi32(i1, _mm_cvtsi32_si128(i32::from(f.row_shift))),
            );
            if _mm256_movemask_epi8(_mm256_cmpgt_epi32(at, _mm256_set1_epi32(limit as i32))) != 0 {
                return false;
            }
            let o: [u32; 8] = [
                _mm256_extract_epi32::<0>(at) as u32,
                _mm256_extract_epi32::<1>(at) as u32,
                _mm256_extract_epi32::<2>(at) as u32,
                _mm256_extract_epi32::<3>(at) as u32,
                _mm256_extract_epi32::<4>(at) as u32,
                _mm256_extract_epi32::<5>(at) as u32,
                _mm256_extract_epi32::<6>(at) as u32,
                _mm256_extract_epi32::<7>(at) as u32,
            ];
            let q = p.add(f.row as usize);
            // Row words: node 0 (A₀ B₀) and node 1 (A₁ B₁) of each query, rows 0 and 1, in
            // query order (the shuffles pick the even, then the odd words of queries
            // 0 1 | 4 5 and 2 3 | 6 7).
            let (a0, b0) = (rows4(p, &o, 0), rows4(p, &o, 2));
            let (a1, b1) = (rows4(q, &o, 0), rows4(q, &o, 2));
            let split = |a: __m256i, b: __m256i, imm: bool| {
                let (a, b) = (_mm256_castsi256_ps(a), _mm256_castsi256_ps(b));
                _mm256_castps_si256(if imm {
                    _mm256_shuffle_ps::<0b11_01_11_01>(a, b)
                } else {
                    _mm256_shuffle_ps::<0b10_00_10_00>(a, b)
                })
            };
            let words = [
                [split(a0, b0, false), split(a0, b0, true)],
                [split(a1, b1, false), split(a1, b1, true)],
            ];
            let low = _mm256_set1_epi32(0xffff);
            for (c, o) in out.into_iter().enumerate() {
                let num = |w: __m256i| {
                    if c == 0 {
                        _mm256_and_si256(w, low)
                    } else {
                        _mm256_srli_epi32::<16>(w)
                    }
                };
                // Along axis 0 per row (p₁ − p₀ formed exactly in integers), then axis 1, then
                // offset + scale · v: the scalar path's operations in its order.
                let r = words.map(|[n0, n1]| {
                    let (q0, q1) = (num(n0), num(n1));
                    let d = _mm256_cvtepi32_ps(_mm256_sub_epi32(q1, q0));
                    _mm256_add_ps(_mm256_cvtepi32_ps(q0), _mm256_mul_ps(f0, d))
                });
                let v = _mm256_add_ps(r[0], _mm256_mul_ps(f1, _mm256_sub_ps(r[1], r[0])));
                let v = _mm256_add_ps(
                    _mm256_set1_ps(reader.offset[c]),
                    _mm256_mul_ps(_mm256_set1_ps(reader.scale[c]), v),
                );
                _mm256_storeu_ps(o.as_mut_ptr(), v);
            }
            true
        }
    }
}

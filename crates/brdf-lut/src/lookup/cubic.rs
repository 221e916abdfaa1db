//! Chunked Catmull–Rom lookups for the batch entry points of u16 tables (hosted targets,
//! not feature `compact`).
//!
//! `N` queries at once, in stages that are each a loop over the chunk, so that the compiler
//! turns the arithmetic stages into packed SSE instructions (AVX2 where the processor has
//! it, picked at run time by `lookup::wide`): the axis maps
//! ([`Lane::cells`]), the four Catmull–Rom weights and the first node of every axis (the
//! cubic polynomials of docs/lut-format.md §7 with the end extrapolation folded in, chosen
//! by selects instead of branches), the payload reads into arrays of stored numbers, and the
//! weighted sums. Every query goes through exactly the operations of the scalar lookup
//! (`Lane::cubic`, `Reader::cubic`: the same products and sums in the same order, the
//! channel scale and offset last), so the results are the scalar lookups' bit for bit.

use super::{Lane, Mode, Reader};
use crate::header::Encoding;

/// First node and the four weights of `N` coordinates on a Catmull–Rom axis of n ≥ 4 nodes:
/// `Lane::cubic` per query (weights `[tap][query]`).
#[inline(always)]
fn cubics<const N: usize>(l: &Lane, x: &[f32; N]) -> ([u32; N], [[f32; N]; 4]) {
    let (i, f) = l.cells::<N, false, false>(x);
    // n − 2, the last cell; n − 4, the first node of the far end's window.
    let (end, far) = ((l.n - 2) as u32, (l.n - 4) as u32);
    // The cubic polynomials, then the three cases of `Lane::cubic` (each with its own
    // arithmetic) chosen by selects: separate loops, each of which vectorises.
    let mut p = [[0.0f32; N]; 4];
    for k in 0..N {
        let f = f[k];
        let (f2, f3) = (f * f, f * f * f);
        p[0][k] = 0.5 * (-f3 + 2.0 * f2 - f);
        p[1][k] = 0.5 * (3.0 * f3 - 5.0 * f2 + 2.0);
        p[2][k] = 0.5 * (-3.0 * f3 + 4.0 * f2 + f);
        p[3][k] = 0.5 * (f3 - f2);
    }
    let mut b = [0u32; N];
    let mut ends = false;
    for k in 0..N {
        ends |= (i[k] == 0) | (i[k] == end);
        b[k] = i[k].wrapping_sub(1);
    }
    if !ends {
        // No query in an end cell (the common case): the interior weights as they are.
        return (b, p);
    }
    let mut w = [[0.0f32; N]; 4];
    for k in 0..N {
        let [wm, w0, w1, w2] = [p[0][k], p[1][k], p[2][k], p[3][k]];
        let (first, last) = (i[k] == 0, i[k] == end);
        let lo = [w0 + 3.0 * wm, w1 - 3.0 * wm, w2 + wm, 0.0];
        let hi = [0.0, wm + w2, w0 - 3.0 * w2, w1 + 3.0 * w2];
        let mid = [wm, w0, w1, w2];
        for t in 0..4 {
            let e = if last { hi[t] } else { mid[t] };
            w[t][k] = if first { lo[t] } else { e };
        }
        let e = if last { far } else { i[k].wrapping_sub(1) };
        b[k] = if first { 0 } else { e };
    }
    (b, w)
}

impl Reader {
    /// Whether [`Reader::chunk_cubic`] applies (Catmull–Rom u16 tables, every axis ≥ 4
    /// nodes).
    #[inline(always)]
    pub(crate) fn cubic_chunked(&self) -> bool {
        self.mode == Mode::Cubic && self.encoding == Encoding::Unorm16
    }

    /// `N` lookups of a 1-D, 2-D or 3-D Catmull–Rom u16 table (`cubic_chunked()` must
    /// hold): channel c of query k in `out[c][k]`, equal to [`Reader::sample`] bit for bit.
    #[inline(always)]
    pub(crate) fn chunk_cubic<const D: usize, const C: usize, const N: usize>(
        &self,
        data: &[u8],
        x: &[[f32; N]; D],
    ) -> [[f32; N]; C] {
        let l = &self.lanes;
        let a0 = cubics(&l[0], &x[0]);
        let a1 = if D > 1 {
            cubics(&l[1], &x[1])
        } else {
            ([0; N], [[0.0; N]; 4])
        };
        // (D is a constant: the 1-D and 2-D lookups compile without the 3-D branch.)
        let (acc, bad) = if D == 3 {
            self.sums3::<C, N>(data, &a0, &a1, &x[2])
        } else {
            self.sums::<D, C, N>(data, &a0, &a1, |_| 0)
        };
        let mut out = [[0.0f32; N]; C];
        for c in 0..C {
            let (sc, of) = (self.scale[c], self.offset[c]);
            for k in 0..N {
                out[c][k] = of + sc * acc[c][k];
            }
            if let Some(bad) = &bad {
                for (o, &bad) in out[c].iter_mut().zip(bad) {
                    if bad {
                        *o = f32::NAN;
                    }
                }
            }
        }
        out
    }

    /// Σ_k w2_k · plane_k over the four axis-2 planes of each query (axis 2's first node
    /// and weights from `x2`), a plane with a zero weight skipped, from 0: `Reader::cubic`'s
    /// sum over axis 2 in its order, the planes from [`Reader::sums`]. A query counts as
    /// past the payload only through a plane it uses, as on the scalar path.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn sums3<const C: usize, const N: usize>(
        &self,
        data: &[u8],
        a0: &([u32; N], [[f32; N]; 4]),
        a1: &([u32; N], [[f32; N]; 4]),
        x2: &[f32; N],
    ) -> ([[f32; N]; C], Option<[bool; N]>) {
        let s2 = self.lanes[2].stride;
        let (b2, w2) = cubics(&self.lanes[2], x2);
        let mut acc = [[0.0f32; N]; C];
        let (mut bad, mut any_bad) = ([false; N], false);
        for (j, wj) in w2.iter().enumerate() {
            let (p, b) = self.sums::<2, C, N>(data, a0, a1, |k| (b2[k] as usize + j) * s2);
            for (acc, p) in acc.iter_mut().zip(&p) {
                for k in 0..N {
                    if wj[k] != 0.0 {
                        acc[k] += wj[k] * p[k];
                    }
                }
            }
            if let Some(b) = b {
                for k in 0..N {
                    bad[k] |= b[k] && wj[k] != 0.0;
                    any_bad |= bad[k];
                }
            }
        }
        (acc, any_bad.then_some(bad))
    }

    /// Σ_j w1_j Σ_i w0_i v_ij in stored units (`Reader::cubic`'s plane sum, from 0, in its
    /// order) of `N` queries whose first nodes and weights on axes 0 and 1 are `a0`, `a1`,
    /// query k in the plane starting at value index `base(k)`; with the queries whose taps
    /// lie past the payload (impossible for a parsed table; NaN on the scalar path) if any.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn sums<const D: usize, const C: usize, const N: usize>(
        &self,
        data: &[u8],
        a0: &([u32; N], [[f32; N]; 4]),
        a1: &([u32; N], [[f32; N]; 4]),
        base: impl Fn(usize) -> usize,
    ) -> ([[f32; N]; C], Option<[bool; N]>) {
        let l = &self.lanes;
        let ((b0, w0), (b1, w1)) = (a0, a1);
        let rows = if D > 1 { 4 } else { 1 };
        // The rows of taps as read, 4 stored numbers per part: [row][part][query] (node i,
        // channel c is number i·C + c of the row).
        let mut q = [[[0u64; N]; C]; 4];
        let (mut bad, mut any_bad) = ([false; N], false);
        let s = l[1].stride * 2;
        // Bytes of the block of rows a query reads.
        let span = (rows - 1) * s + 8 * C;
        for k in 0..N {
            let at = (base(k) + b0[k] as usize * C + b1[k] as usize * l[1].stride) * 2;
            // A short payload (impossible for a parsed table) gives NaN, like the scalar
            // path's row read.
            let Some(blk) = data.get(at..at + span) else {
                (bad[k], any_bad) = (true, true);
                continue;
            };
            for (j, qj) in q.iter_mut().enumerate().take(rows) {
                for (part, qp) in qj.iter_mut().enumerate() {
                    let o = j * s + 8 * part;
                    match blk.get(o..o + 8).and_then(|r| r.first_chunk()) {
                        Some(&r) => qp[k] = u64::from_le_bytes(r),
                        None => (bad[k], any_bad) = (true, true),
                    }
                }
            }
        }
        // The stored numbers as f32: [channel][4 × row + node][query].
        let mut v = [[[0.0f32; N]; 16]; C];
        for (j, qj) in q.iter().enumerate().take(rows) {
            for (part, qp) in qj.iter().enumerate() {
                let mut put = |m: usize, x: [f32; N]| {
                    let u = 4 * part + m;
                    v[u % C][4 * j + u / C] = x;
                };
                put(0, unpack::<0, N>(qp));
                put(1, unpack::<16, N>(qp));
                put(2, unpack::<32, N>(qp));
                put(3, unpack::<48, N>(qp));
            }
        }
        let mut acc = [[0.0f32; N]; C];
        for (c, acc) in acc.iter_mut().enumerate() {
            for j in 0..rows {
                // Σ_i w0_i v_ij, from 0 like the scalar row.
                let mut r = [0.0f32; N];
                for i in 0..4 {
                    let v = &v[c][4 * j + i];
                    for k in 0..N {
                        r[k] += w0[i][k] * v[k];
                    }
                }
                if D > 1 {
                    for k in 0..N {
                        acc[k] += w1[j][k] * r[k];
                    }
                } else {
                    *acc = r;
                }
            }
        }
        (acc, any_bad.then_some(bad))
    }

    /// `N` pairs of one-channel 3-D Catmull–Rom lookups at one last coordinate z (the σ of
    /// a batch of G queries): [`Reader::pair3`] bit for bit (`pair3_cubic`: the σ weights
    /// once, planes with a zero σ weight skipped, Σ_k w2_k · plane_k from 0, then the
    /// channel scale and offset).
    #[inline(always)]
    pub(crate) fn chunk3_cubic<const N: usize>(
        &self,
        data: &[u8],
        x: &[[f32; N]; 2],
        w2: &(usize, [f32; 4]),
    ) -> [f32; N] {
        let l = &self.lanes;
        let a0 = cubics(&l[0], &x[0]);
        let a1 = cubics(&l[1], &x[1]);
        let (b2, w2) = w2;
        let mut acc = [0.0f32; N];
        let mut bad = [false; N];
        for (k, &wk) in w2.iter().enumerate() {
            if wk != 0.0 {
                let ([p], b) = self.sums::<2, 1, N>(data, &a0, &a1, |_| (b2 + k) * l[2].stride);
                for q in 0..N {
                    acc[q] += wk * p[q];
                }
                if let Some(b) = b {
                    for (bad, b) in bad.iter_mut().zip(b) {
                        *bad |= b;
                    }
                }
            }
        }
        let mut out = [0.0f32; N];
        for q in 0..N {
            let v = self.offset[0] + self.scale[0] * acc[q];
            out[q] = if bad[q] { f32::NAN } else { v };
        }
        out
    }
}

/// The stored number at bit `SH` of each packed part, as f32 (exact: < 2¹⁶).
#[inline(always)]
fn unpack<const SH: u32, const N: usize>(q: &[u64; N]) -> [f32; N] {
    let mut x = [0.0f32; N];
    for k in 0..N {
        x[k] = ((q[k] >> SH) as u16) as f32;
    }
    x
}

#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware tests: `!(x > 0)` is true for NaN.
//! A whole roughness row of the GGX or Beckmann split-sum table (A, B at one width, many μ) from a few
//! polar integrals ([`super::polar`]) by adaptive piecewise Chebyshev interpolation in
//! x = ln μ, with a per-texel error estimate.
//!
//! **Why ln μ.** At fixed α, A(μ) and B(μ) are analytic on (0, 1]: they are even in θv
//! (hence analytic in θv² and so in μ = cos θv at μ = 1), and their only fast change is
//! the masking transition at μ ~ α, whose width in ln μ is O(1) for every α; as μ → 0
//! they tend to limits with corrections in powers of μ (and μ ln μ), which are analytic
//! and decaying in x = ln μ. So A, B are smooth in x on [ln μ_min, 0] and a few
//! polynomial pieces resolve them. For α ≤ 0.2 the variable is x = ln(μ + α/8), which
//! spends fewer nodes below the transition: on the 1024² Khronos axes the Chebyshev
//! coefficients (nodes at 1e-9) fall below 1e-7 at degree 21–31 instead of 27–34 for
//! r = 0.1 … 0.4, while for larger α the shift slows the decay (measured with
//! `polar_probe`; 47 instead of 60 evaluations per texel over the table).
//!
//! **Rule.** On a piece [a, b] of x the values f_k at the Chebyshev points
//! x_k = (a + b)/2 + (b − a)/2 · cos(kπ/n), k = 0 … n (n = 8, 16, 32, 64: nested, every
//! doubling keeps the old nodes) give the interpolant p_n = Σ_j c_j T_j(t),
//! t = (2x − a − b)/(b − a), with c_j = (2/n) Σ''_k f_k cos(jkπ/n) (Σ'' halves the k = 0,
//! n terms; c_0, c_n halved too) (Trefethen, "Approximation Theory and Approximation
//! Practice" (ATAP), 2013, ch. 3: the interpolant's coefficients by the discrete cosine
//! transform of the values). The estimate of a texel per channel is
//!
//! ```text
//! e = I  +  Λ_n δ  +  64ε|p|,     Λ_n = 1 + (2/π) ln(n + 1),
//! I = 2 Σ_{j > 3n/4} |c_j|            if max_{j > 3n/4} |c_j| ≤ ½ max_{n/2 < j ≤ 3n/4} |c_j|,
//! I = Σ_j |c_j⁽ⁿ⁾ − c_j⁽ⁿᐟ²⁾|          otherwise.
//! ```
//!
//! I estimates the interpolation error, which is at most 2 Σ_{j > n} |a_j| (a_j the
//! Chebyshev coefficients of the function, ATAP ch. 4): when the last quarter of the
//! coefficients has decayed at least twofold from the quarter before, geometric decay
//! |a_j| ~ ρ^{−j} with ρ^{n/4} ≥ 2 makes the last quarter's sum at least the tail beyond n;
//! otherwise the difference of p_n and p_{n/2} (a bound on max |p_n − p_{n/2}|, |T_j| ≤ 1:
//! the error of the coarser interpolant, which bounds that of p_n once the coefficients
//! decay, as the polar rule's |T_N − T_{N/2}|). δ is the largest node estimate (each node by
//! the polar rule to tol/8) and Λ_n the Lebesgue constant bound of the Chebyshev points
//! (ATAP Theorem 15.2), which carries the node errors into the interpolant. A piece
//! is accepted when e ≤ tol in both channels; otherwise n is doubled up to
//! [`ROW_MAX_DEGREE`], then the piece is halved (at most [`ROW_MAX_DEPTH`] times). Where
//! interpolation cannot pay — a piece holding no more texels than [`NODE_COST`] × the nodes
//! the next step would add, depth exhausted, or node estimates too large for Λ_n δ < tol — its texels are
//! integrated directly by the polar rule to `tol` (their own estimates and work).

use super::converged::texel_edges;
use super::polar::{DfgGgxPolarRow, Polar, PolarRow};
use crate::Real;

/// The first interpolation degree of a piece (the first estimate is at twice this).
pub const ROW_FIRST_DEGREE: usize = 8;
/// The largest interpolation degree before a piece is halved.
pub const ROW_MAX_DEGREE: usize = 64;
/// Halvings of a piece at most.
pub const ROW_MAX_DEPTH: u32 = 10;
/// Node tolerance as a fraction of the row's `tol` (Λ_64 δ ≤ 0.46 tol: the rest is left
/// for the interpolation term).
pub const NODE_TOL_FRACTION: f64 = 0.125;

/// A node (the polar rule to tol/8) costs about this many texels (to tol): measured
/// 2–2.5× the evaluations with `polar_probe`; used to decide where interpolation pays.
pub const NODE_COST: usize = 2;

/// Nodes of the finest degree.
const NG: usize = ROW_MAX_DEGREE + 1;

/// Why a row was not computed (`out` is then left unchanged).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RowError {
    /// `mus` and `out` differ in length.
    LengthMismatch {
        /// `mus.len()`.
        mus: usize,
        /// `out.len()`.
        out: usize,
    },
    /// `tol` is not a positive number (≤ 0 or NaN).
    Tolerance,
}

/// The work of one row.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RowWork {
    /// Integrand evaluations in all (nodes and directly integrated texels).
    pub evals: u64,
    /// Polar integrals run as interpolation nodes.
    pub nodes: u32,
    /// Interpolation pieces accepted.
    pub pieces: u32,
    /// Texels integrated directly (not interpolated).
    pub direct: u32,
}

/// The values of one piece's nodes on the finest grid: index k ↔ cos(kπ/[`ROW_MAX_DEGREE`]).
struct Nodes<T> {
    a: T,
    b: T,
    f: [[T; 2]; NG],
    /// The largest node estimate per channel so far.
    delta: [T; 2],
    /// The degree filled.
    n: usize,
}

/// An accepted interpolant: Chebyshev coefficients of degree n on [a, b] and the estimate.
struct Fit<T> {
    c: [[T; 2]; NG],
    n: usize,
    est: [T; 2],
}

/// The row's fixed inputs, its output and the running work.
struct Job<'a, T> {
    row: PolarRow<T>,
    alpha: T,
    mus: &'a [T],
    out: &'a mut [Polar<T>],
    tol: T,
    /// The x = ln μ range of the interpolated texels.
    lo: T,
    hi: T,
    /// c of x = ln(μ + c) ([`shift_of`]).
    shift: T,
    /// cos(mπ/[`ROW_MAX_DEGREE`]), m = 0 … 2·ROW_MAX_DEGREE.
    cos: [T; 2 * ROW_MAX_DEGREE + 1],
    work: RowWork,
}

/// Lebesgue constant bound of the degree-n Chebyshev points: 1 + (2/π) ln(n + 1) (ATAP
/// Theorem 15.2).
fn lebesgue<T: Real>(n: usize) -> T {
    T::ONE + T::TWO / T::PI * T::from_f64((n + 1) as f64).ln()
}

/// Σ_j c_j T_j(t) by Clenshaw's recurrence b_j = c_j + 2t b_{j+1} − b_{j+2}, p = c_0 + t b_1 − b_2.
fn clenshaw<T: Real>(c: &[[T; 2]], t: T) -> [T; 2] {
    let mut out = [T::ZERO; 2];
    for (ch, o) in out.iter_mut().enumerate() {
        let (mut b1, mut b2) = (T::ZERO, T::ZERO);
        for cj in c[1..].iter().rev() {
            let b0 = cj[ch] + T::TWO * t * b1 - b2;
            b2 = b1;
            b1 = b0;
        }
        *o = c[0][ch] + t * b1 - b2;
    }
    out
}

/// The interpolation part of a piece's estimate in channel ch from the degree-n
/// coefficients c and the degree-n/2 ones h (module docs): 2 Σ_{j > 3n/4} |c_j| when the
/// last quarter has decayed at least twofold from the quarter before (max |c_j| over
/// (3n/4, n] ≤ ½ max over (n/2, 3n/4]), else Σ_j |c_j − h_j|.
fn tail<T: Real>(c: &[[T; 2]], h: &[[T; 2]], ch: usize) -> T {
    let n = c.len() - 1;
    let (q2, q3) = (n / 2, 3 * n / 4);
    let early = c[q2 + 1..=q3]
        .iter()
        .fold(T::ZERO, |m, v| m.max(v[ch].abs()));
    let late = c[q3 + 1..].iter().fold(T::ZERO, |m, v| m.max(v[ch].abs()));
    if late + late <= early {
        let s = c[q3 + 1..].iter().fold(T::ZERO, |s, v| s + v[ch].abs());
        return s + s;
    }
    c.iter()
        .zip(h)
        .fold(T::ZERO, |s, (a, b)| s + (a[ch] - b[ch]).abs())
}

/// The shift c of the interpolation variable x = ln(μ + c) at width α (module docs).
fn shift_of<T: Real>(alpha: T) -> T {
    if alpha <= T::from_f64(ROW_SHIFT_MAX_ALPHA) {
        alpha * T::from_f64(ROW_SHIFT_FRACTION)
    } else {
        T::ZERO
    }
}

/// c/α of the interpolation variable x = ln(μ + c) for α ≤ [`ROW_SHIFT_MAX_ALPHA`].
pub const ROW_SHIFT_FRACTION: f64 = 0.125;
/// Above this α the variable is x = ln μ (c = 0).
pub const ROW_SHIFT_MAX_ALPHA: f64 = 0.2;

impl<T: Real> Job<'_, T> {
    /// x = ln(μ + c).
    fn x_of(&self, mu: T) -> T {
        (mu + self.shift).ln()
    }
    /// μ = eˣ − c.
    fn mu_of(&self, x: T) -> T {
        x.exp() - self.shift
    }

    /// Whether texel i belongs to the piece [a, b] of x: interpolated (not an edge case of
    /// `texel_edges`) and a ≤ ln μ < b, the row's ends closed (compared in μ: e^a ≤ μ < e^b).
    fn member(&self, i: usize, (ma, mb): (T, T), (first, last): (bool, bool)) -> bool {
        let Ok(mu) = texel_edges(self.mus[i], self.alpha) else {
            return false;
        };
        (first || mu >= ma) && (last || mu < mb)
    }

    /// The texels of the piece [a, b]: (μ bounds, end flags) for [`Job::member`], count.
    fn span(&self, a: T, b: T) -> ((T, T), (bool, bool), usize) {
        let m = (self.mu_of(a), self.mu_of(b));
        let ends = (a == self.lo, b == self.hi);
        let count = (0..self.mus.len())
            .filter(|&i| self.member(i, m, ends))
            .count();
        (m, ends, count)
    }

    /// Every texel of the piece by the polar rule to `tol`.
    fn direct(&mut self, a: T, b: T) {
        let (m, ends, _) = self.span(a, b);
        for i in 0..self.mus.len() {
            if self.member(i, m, ends) {
                let p = self.row.texel(self.mus[i], self.tol);
                self.work.evals += u64::from(p.evals);
                self.work.direct += 1;
                self.out[i] = p;
            }
        }
    }

    /// Adds the nodes of degree n to `p` (those of degree n/2 are kept).
    fn fill(&mut self, p: &mut Nodes<T>, n: usize) {
        let s = ROW_MAX_DEGREE / n;
        let (mid, half) = ((p.a + p.b) * T::HALF, (p.b - p.a) * T::HALF);
        let node_tol = self.tol * T::from_f64(NODE_TOL_FRACTION);
        for k in (0..=n).filter(|k| p.n == 0 || k % 2 == 1) {
            let x = match k {
                0 => p.b,
                _ if k == n => p.a,
                _ => mid + half * self.cos[k * s],
            };
            let q = self.row.texel(self.mu_of(x), node_tol);
            self.work.evals += u64::from(q.evals);
            self.work.nodes += 1;
            p.f[k * s] = q.value;
            for ch in 0..2 {
                p.delta[ch] = p.delta[ch].max(q.error[ch]);
            }
        }
        p.n = n;
    }

    /// The Chebyshev coefficients of degree n from the nodes (module docs).
    fn coefficients(&self, p: &Nodes<T>, n: usize) -> [[T; 2]; NG] {
        let s = ROW_MAX_DEGREE / n;
        let mut c = [[T::ZERO; 2]; NG];
        let scale = T::TWO / T::from_f64(n as f64);
        for (j, cj) in c.iter_mut().enumerate().take(n + 1) {
            for k in 0..=n {
                let w = if k == 0 || k == n { T::HALF } else { T::ONE };
                let cs = self.cos[(j * k * s) % (2 * ROW_MAX_DEGREE)] * w * scale;
                for (c, f) in cj.iter_mut().zip(&p.f[k * s]) {
                    *c += *f * cs;
                }
            }
            if j == 0 || j == n {
                cj[0] *= T::HALF;
                cj[1] *= T::HALF;
            }
        }
        c
    }

    /// The interpolant of degree p.n and its estimate (module docs), if within `tol`.
    fn fit(&self, p: &Nodes<T>) -> Option<Fit<T>> {
        let n = p.n;
        let (c, h) = (self.coefficients(p, n), self.coefficients(p, n / 2));
        let mut est = [T::ZERO; 2];
        for (ch, e) in est.iter_mut().enumerate() {
            *e = tail(&c[..=n], &h[..=n], ch) + lebesgue::<T>(n) * p.delta[ch];
        }
        (est[0] <= self.tol && est[1] <= self.tol).then_some(Fit { c, n, est })
    }

    /// Writes the interpolant's values and estimates to the piece's texels.
    fn apply(&mut self, p: &Nodes<T>, fit: &Fit<T>) {
        let (m, ends, _) = self.span(p.a, p.b);
        let (sum, dif) = (p.a + p.b, p.b - p.a);
        let round = T::from_f64(64.0) * T::EPSILON;
        for i in 0..self.mus.len() {
            if !self.member(i, m, ends) {
                continue;
            }
            let x = self.x_of(self.mus[i].min(T::ONE));
            let t = ((x + x - sum) / dif).clamp(-T::ONE, T::ONE);
            let value = clenshaw(&fit.c[..=fit.n], t);
            let error = [
                fit.est[0] + round * value[0].abs(),
                fit.est[1] + round * value[1].abs(),
            ];
            self.out[i] = Polar {
                value,
                error,
                evals: 0,
                rows: 0,
                panels: 0,
            };
        }
        self.work.pieces += 1;
    }
}

impl<T: Real> Job<'_, T> {
    /// One piece [a, b] (module docs): degrees 8 … [`ROW_MAX_DEGREE`], then halves.
    fn piece(&mut self, a: T, b: T, depth: u32) {
        let (_, _, count) = self.span(a, b);
        if count == 0 {
            return;
        }
        if count <= NODE_COST * (ROW_FIRST_DEGREE + 1) || !(b > a) {
            return self.direct(a, b);
        }
        let mut p = Nodes {
            a,
            b,
            f: [[T::ZERO; 2]; NG],
            delta: [T::ZERO; 2],
            n: 0,
        };
        self.fill(&mut p, ROW_FIRST_DEGREE);
        let lam = lebesgue::<T>(ROW_MAX_DEGREE);
        if !(lam * p.delta[0].max(p.delta[1]) < self.tol) {
            return self.direct(a, b);
        }
        while p.n < ROW_MAX_DEGREE {
            if count <= NODE_COST * p.n {
                return self.direct(a, b);
            }
            let n = 2 * p.n;
            self.fill(&mut p, n);
            if let Some(fit) = self.fit(&p) {
                return self.apply(&p, &fit);
            }
        }
        if depth >= ROW_MAX_DEPTH {
            return self.direct(a, b);
        }
        let m = (a + b) * T::HALF;
        self.piece(a, m, depth + 1);
        self.piece(m, b, depth + 1);
    }
}

impl<T: Real> PolarRow<T> {
    /// (A, B) at every μ of `mus` into `out` (same length) to the absolute tolerance `tol`
    /// per channel, sharing work along the row (module docs). Each texel is as
    /// [`DfgGgxPolarRow::texel`] would answer it in its edge cases (NaN μ or r → NaN; μ
    /// below [`crate::geometry::min_cos`] → (0, 0); the mirror limit for α ≤
    /// [`super::polar::MIRROR_ALPHA`]; μ > 1 clamped); the others are interpolated
    /// (`evals`, `rows`, `panels` = 0: the row's work is in the returned [`RowWork`]) or
    /// integrated directly. Every estimate is ≤ `tol` unless a directly integrated texel
    /// exhausted the polar rule's storage. `mus` may be in any order. Errors (`out`
    /// unchanged): lengths differ, or `tol` not > 0.
    pub fn texels(&self, mus: &[T], tol: T, out: &mut [Polar<T>]) -> Result<RowWork, RowError> {
        if mus.len() != out.len() {
            return Err(RowError::LengthMismatch {
                mus: mus.len(),
                out: out.len(),
            });
        }
        if !(tol > T::ZERO) {
            return Err(RowError::Tolerance);
        }
        let alpha = self.width();
        let (mut lo, mut hi) = (T::INFINITY, -T::INFINITY);
        for (mu, o) in mus.iter().zip(out.iter_mut()) {
            match texel_edges(*mu, alpha) {
                Ok(mu) => {
                    lo = lo.min(mu);
                    hi = hi.max(mu);
                }
                Err((value, error)) => *o = Polar::exact(value, error),
            }
        }
        let shift = shift_of(alpha);
        let mut job = Job {
            row: *self,
            alpha,
            mus,
            out,
            tol,
            lo: (lo + shift).ln(),
            hi: (hi + shift).ln(),
            shift,
            cos: [T::ZERO; 2 * ROW_MAX_DEGREE + 1],
            work: RowWork::default(),
        };
        if !(lo <= hi) {
            return Ok(job.work);
        }
        for (m, c) in job.cos.iter_mut().enumerate() {
            *c = (T::PI * T::from_f64(m as f64) / T::from_f64(ROW_MAX_DEGREE as f64)).cos();
        }
        job.piece(job.lo, job.hi, 0);
        Ok(job.work)
    }
}

/// The GGX split sum (A, B) of the row of perceptual roughness r (α = r²) at every μ of
/// `mus` (see [`DfgGgxPolarRow::texels`]).
pub fn dfg_ggx_polar_row<T: Real>(
    r: T,
    mus: &[T],
    tol: T,
    out: &mut [Polar<T>],
) -> Result<RowWork, RowError> {
    DfgGgxPolarRow::new(r).texels(mus, tol, out)
}

/// The Kulla–Conty directional albedo E = A + B (F = 1) of a row: each channel to tol/2, so
/// that [`Polar::sum`] of every `out` texel is E with an estimate ≤ `tol`.
pub fn e_ggx_polar_row<T: Real>(
    r: T,
    mus: &[T],
    tol: T,
    out: &mut [Polar<T>],
) -> Result<RowWork, RowError> {
    dfg_ggx_polar_row(r, mus, tol * T::HALF, out)
}

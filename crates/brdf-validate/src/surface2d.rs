//! Periodic 2-D Gaussian random height fields, their triangle-pair representation, exact
//! conditioning on one facet's slope, and an exact ray tracer (the 3-D ground truth).
//!
//! **Construction.** White noise ξ_ij ~ N(0, 1) on an N × N periodic grid of spacing
//! Δ = ℓ/8 is convolved with the Gaussian kernel w(x, y) = exp(−2(x² + y²)/ℓ²), |x|, |y| ≤ 3ℓ.
//! The kernel is separable, w = w₁(x) w₁(y) with the 1-D profiles' kernel, so the
//! convolution is two 1-D passes (direct, periodic, no FFT) and the height covariance is the
//! product C(m, n) = C₁(m) C₁(n) of the 1-D discrete covariances
//! ([`crate::profile::kernel_covariance`]): an isotropic Gaussian autocorrelation
//! exp(−r²/ℓ²), up to the kernel's truncation at e⁻¹⁸.
//!
//! **Units.** Horizontal coordinates in nodes, heights scaled so that the *expected* node
//! difference h(i+1, j) − h(i, j) (the slope along x per node) has variance 1. A surface of
//! slope RMS (σx, σy) is z(x, y) = h(σx x/Δ, σy y/Δ)·Δ: the same field seen through the
//! linear map (x, y, z) → (σx x, σy y, z), under which a world direction (wx, wy, wz)
//! becomes (σx wx, σy wy, wz) and a world slope (px, py) becomes (px/σx, py/σy). So one field
//! serves every σ and anisotropy, and ray–surface intersections are preserved exactly.
//!
//! **Representation.** Each grid cell is split along its diagonal y = x into two planar
//! triangles (continuous, piecewise linear): "lower" (0,0)-(1,0)-(1,1) with slopes
//! (h₁₀ − h₀₀, h₁₁ − h₁₀), "upper" (0,0)-(1,1)-(0,1) with slopes (h₁₁ − h₀₁, h₀₁ − h₀₀). The
//! facet slopes are linear in the Gaussian heights, hence exactly Gaussian, each component
//! with variance 1; the two components of one triangle have a small correlation ρ
//! ([`Field::expected_slope_correlation`], −0.008 at Δ = ℓ/8), which the report measures.
//! All triangles have the same projected area, so "a facet chosen uniformly by area" is a
//! uniformly chosen triangle.
//!
//! **Conditioning.** Given one triangle's slope d = (d₁, d₂), the field is Gaussian with mean
//! shifted by K_m (s − d), K_m = cov(h_m, d) Σ_d⁻¹ (Σ_d the 2 × 2 covariance of d). Adding
//! K_m (s − d) to an unconditioned field is an exact sample of the field conditioned on
//! d = s (kriging), so G is measured at exactly the slope of the half vector — no bin.
//!
//! **Tracing.** Along a ray's horizontal path, (ray height − surface height) is piecewise
//! linear with kinks only where the path crosses a cell edge or a cell diagonal. A ray that
//! leaves a facet facing it starts above the surface, so it is blocked iff that difference
//! is negative at one of those break points: checking each break point (a 2-D DDA over the
//! cells, periodic) is exact for the triangle representation.

use crate::profile::{kernel_covariance, KERNEL_HALF};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_pcg::Pcg64;

/// Nodes per correlation length ℓ (Δ = ℓ/8, as the 1-D profiles).
pub const NODES_PER_ELL: usize = 8;
/// Half-width of the conditioning window in nodes (the covariance vanishes beyond 6ℓ = 48
/// nodes from each of the triangle's vertices).
pub const WIN: i64 = 2 * KERNEL_HALF as i64 + 2;
/// Width (in nodes) of the blocks of the block-maximum table used to skip ahead.
pub const BLK: usize = 8;

/// One periodic height field of N × N nodes (unit expected slope RMS per axis).
#[derive(Clone, Debug)]
pub struct Field {
    n: usize,
    h: Vec<f64>,
    gmax: f64,
    bmax: Vec<f64>,
    /// Per triangle type: K_m for offsets in [−WIN, WIN]², two components each.
    k: [Vec<[f64; 2]>; 2],
    /// Per triangle type: max over the window of |K_m,1| + |K_m,2|.
    k_abs: [f64; 2],
    /// Per triangle type and Chebyshev distance d ∈ [0, WIN + 1]: the max of |K_m|₁ over
    /// the nodes at distance ≥ d (non-increasing; 0 at WIN + 1).
    k_dist: [Vec<f64>; 2],
    /// Per triangle type: Σ_d (scaled units).
    sigma_d: [[[f64; 2]; 2]; 2],
}

/// The vertices (dx, dy) and coefficients of d₁ and d₂ of each triangle type.
const TRI: [[(i64, i64, f64, f64); 3]; 2] = [
    // lower: d1 = h10 − h00, d2 = h11 − h10
    [(0, 0, -1.0, 0.0), (1, 0, 1.0, -1.0), (1, 1, 0.0, 1.0)],
    // upper: d1 = h11 − h01, d2 = h01 − h00
    [(0, 0, 0.0, -1.0), (1, 1, 1.0, 0.0), (0, 1, -1.0, 1.0)],
];

/// The slopes (d₁, d₂) of triangle `t` (0 lower, 1 upper) from the heights `h(dx, dy)` of
/// its cell's corners ((0, 0) the cell's node): d = Σ over the triangle's three corners of
/// (a₁, a₂)·h, the [`TRI`] weights.
fn tri_slope_of(t: usize, h: impl Fn(i64, i64) -> f64) -> [f64; 2] {
    let mut d = [0.0; 2];
    for &(vx, vy, a1, a2) in &TRI[t] {
        let z = h(vx, vy);
        d[0] += a1 * z;
        d[1] += a2 * z;
    }
    d
}

/// 1-D separable periodic convolution pass with the Gaussian kernel (along x or y).
fn convolve(src: &[f64], n: usize, along_x: bool) -> Vec<f64> {
    let w: Vec<f64> = (0..=2 * KERNEL_HALF)
        .map(|i| {
            let x = (i as f64 - KERNEL_HALF as f64) / NODES_PER_ELL as f64;
            (-2.0 * x * x).exp()
        })
        .collect();
    let kh = KERNEL_HALF as isize;
    let mut out = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            let mut s = 0.0;
            for (q, wq) in w.iter().enumerate() {
                let o = q as isize - kh;
                let idx = if along_x {
                    j * n + (i as isize + o).rem_euclid(n as isize) as usize
                } else {
                    (j as isize + o).rem_euclid(n as isize) as usize * n + i
                };
                s += wq * src[idx];
            }
            out[j * n + i] = s;
        }
    }
    out
}

impl Field {
    /// Generates a field of 2^`log2_n` × 2^`log2_n` nodes from `seed` (deterministic).
    pub fn generate(log2_n: u32, seed: u64) -> Self {
        let n = 1usize << log2_n;
        let mut rng = Pcg64::seed_from_u64(seed);
        let xi: Vec<f64> = (0..n * n).map(|_| rng.sample(StandardNormal)).collect();
        let mut h = convolve(&convolve(&xi, n, true), n, false);
        let scale = 1.0 / Self::unscaled_slope_var().sqrt();
        h.iter_mut().for_each(|x| *x *= scale);
        let gmax = h.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let nb = n / BLK;
        let mut bmax = vec![f64::NEG_INFINITY; nb * nb];
        // A block's maximum covers the nodes of its cells: rows/columns b·BLK ..= b·BLK + BLK.
        for bj in 0..nb {
            for bi in 0..nb {
                let mut m = f64::NEG_INFINITY;
                for j in 0..=BLK {
                    for i in 0..=BLK {
                        m = m.max(h[((bj * BLK + j) % n) * n + (bi * BLK + i) % n]);
                    }
                }
                bmax[bj * nb + bi] = m;
            }
        }
        let (k0, a0, s0) = Self::kriging(0);
        let (k1, a1, s1) = Self::kriging(1);
        let k_dist = [Self::radial_bound(&k0), Self::radial_bound(&k1)];
        Self {
            n,
            h,
            gmax,
            bmax,
            k: [k0, k1],
            k_abs: [a0, a1],
            k_dist,
            sigma_d: [s0, s1],
        }
    }

    /// Variance of h(i+1, j) − h(i, j) before scaling: 2 C₁(0)(C₁(0) − C₁(1)).
    fn unscaled_slope_var() -> f64 {
        let c = kernel_covariance();
        2.0 * c[0] * (c[0] - c[1])
    }

    /// Covariance of heights at node offset (mx, my), scaled units.
    pub fn cov(mx: i64, my: i64) -> f64 {
        let c = kernel_covariance();
        let f = |m: i64| c.get(m.unsigned_abs() as usize).copied().unwrap_or(0.0);
        f(mx) * f(my) / Self::unscaled_slope_var()
    }

    /// K_m = cov(h_m, d) Σ_d⁻¹ over the window, max |K|₁ and Σ_d for triangle type `t`.
    fn kriging(t: usize) -> (Vec<[f64; 2]>, f64, [[f64; 2]; 2]) {
        let c = kernel_covariance();
        let s = Self::unscaled_slope_var();
        let cv = |mx: i64, my: i64| -> f64 {
            let f = |m: i64| c.get(m.unsigned_abs() as usize).copied().unwrap_or(0.0);
            f(mx) * f(my) / s
        };
        let tri = TRI[t];
        let mut sd = [[0.0; 2]; 2];
        for &(ax, ay, a1, a2) in &tri {
            for &(bx, by, b1, b2) in &tri {
                let cc = cv(ax - bx, ay - by);
                sd[0][0] += a1 * b1 * cc;
                sd[0][1] += a1 * b2 * cc;
                sd[1][0] += a2 * b1 * cc;
                sd[1][1] += a2 * b2 * cc;
            }
        }
        let det = sd[0][0] * sd[1][1] - sd[0][1] * sd[1][0];
        let inv = [
            [sd[1][1] / det, -sd[0][1] / det],
            [-sd[1][0] / det, sd[0][0] / det],
        ];
        let w = 2 * WIN + 1;
        let mut k = vec![[0.0; 2]; (w * w) as usize];
        let mut kmax = 0.0f64;
        for my in -WIN..=WIN {
            for mx in -WIN..=WIN {
                let (mut c1, mut c2) = (0.0, 0.0);
                for &(vx, vy, a1, a2) in &tri {
                    let cc = cv(mx - vx, my - vy);
                    c1 += a1 * cc;
                    c2 += a2 * cc;
                }
                let kk = [
                    c1 * inv[0][0] + c2 * inv[1][0],
                    c1 * inv[0][1] + c2 * inv[1][1],
                ];
                kmax = kmax.max(kk[0].abs() + kk[1].abs());
                k[((my + WIN) * w + mx + WIN) as usize] = kk;
            }
        }
        (k, kmax, sd)
    }

    /// max of |K_m|₁ over the nodes at Chebyshev distance ≥ d, d = 0 ..= WIN + 1.
    fn radial_bound(k: &[[f64; 2]]) -> Vec<f64> {
        let w = 2 * WIN + 1;
        let mut at = vec![0.0f64; (WIN + 2) as usize];
        for my in -WIN..=WIN {
            for mx in -WIN..=WIN {
                let kk = k[((my + WIN) * w + mx + WIN) as usize];
                let d = mx.abs().max(my.abs()) as usize;
                at[d] = at[d].max(kk[0].abs() + kk[1].abs());
            }
        }
        for d in (0..at.len() - 1).rev() {
            at[d] = at[d].max(at[d + 1]);
        }
        at
    }

    /// Nodes per side.
    pub fn side(&self) -> usize {
        self.n
    }
    /// Height at node (i, j) (periodic).
    #[inline]
    pub fn h(&self, i: i64, j: i64) -> f64 {
        let n = self.n as i64;
        self.h[(j.rem_euclid(n) * n + i.rem_euclid(n)) as usize]
    }
    /// Expected correlation of a triangle's two slope components (type 0; type 1 equal).
    pub fn expected_slope_correlation(&self) -> f64 {
        let s = self.sigma_d[0];
        s[0][1] / (s[0][0] * s[1][1]).sqrt()
    }
    /// The slopes (d₁, d₂) of triangle `t` of cell (i, j) in the unconditioned field.
    pub fn tri_slope(&self, i: i64, j: i64, t: usize) -> [f64; 2] {
        tri_slope_of(t, |x, y| self.h(i + x, j + y))
    }
    /// Realised RMS of the node differences along x and along y (target 1 each).
    pub fn realised_slope_rms(&self) -> (f64, f64) {
        let n = self.n as i64;
        let (mut sx, mut sy) = (0.0, 0.0);
        for j in 0..n {
            for i in 0..n {
                sx += (self.h(i + 1, j) - self.h(i, j)).powi(2);
                sy += (self.h(i, j + 1) - self.h(i, j)).powi(2);
            }
        }
        let m = (n * n) as f64;
        ((sx / m).sqrt(), (sy / m).sqrt())
    }
    /// Realised height autocorrelation at node lag (lx, ly), normalised by lag 0.
    pub fn realised_autocorrelation(&self, lx: i64, ly: i64) -> f64 {
        let n = self.n as i64;
        let mean = self.h.iter().sum::<f64>() / self.h.len() as f64;
        let (mut c0, mut cl) = (0.0, 0.0);
        for j in 0..n {
            for i in 0..n {
                let a = self.h(i, j) - mean;
                c0 += a * a;
                cl += a * (self.h(i + lx, j + ly) - mean);
            }
        }
        cl / c0
    }
    /// Realised correlation of the two slope components over all lower triangles.
    pub fn realised_slope_correlation(&self) -> f64 {
        let n = self.n as i64;
        let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
        for j in 0..n {
            for i in 0..n {
                let d = self.tri_slope(i, j, 0);
                a += d[0] * d[1];
                b += d[0] * d[0];
                c += d[1] * d[1];
            }
        }
        a / (b * c).sqrt()
    }
    /// All node differences along x then y (the facet slope components), for the
    /// distribution check.
    pub fn slope_samples(&self) -> Vec<f64> {
        let n = self.n as i64;
        let mut v = Vec::with_capacity(2 * self.h.len());
        for j in 0..n {
            for i in 0..n {
                v.push(self.h(i + 1, j) - self.h(i, j));
                v.push(self.h(i, j + 1) - self.h(i, j));
            }
        }
        v
    }
}

/// A field conditioned on triangle `t` of cell (ci, cj) having slope `s`: heights inside the
/// window carry the correction K_m · δ, δ = s − d.
pub struct Conditioned<'a> {
    f: &'a Field,
    ci: i64,
    cj: i64,
    t: usize,
    delta: [f64; 2],
    ceiling: f64,
    dmax: f64,
}

/// A traced ray: its origin (scaled units) and its direction (σx wx, σy wy, wz).
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Origin x, y (nodes) and z.
    pub o: [f64; 3],
    /// Direction (not normalised).
    pub d: [f64; 3],
}

impl<'a> Conditioned<'a> {
    /// Conditions `f` on triangle `t` of cell (ci, cj) having slope `s` (scaled units).
    pub fn new(f: &'a Field, ci: i64, cj: i64, t: usize, s: [f64; 2]) -> Self {
        let d = f.tri_slope(ci, cj, t);
        let delta = [s[0] - d[0], s[1] - d[1]];
        let dmax = delta[0].abs().max(delta[1].abs());
        let ceiling = f.gmax + f.k_abs[t] * dmax;
        Self {
            f,
            ci,
            cj,
            t,
            delta,
            ceiling,
            dmax,
        }
    }
    /// The unconditioned field itself (δ = 0).
    pub fn plain(f: &'a Field) -> Self {
        Self {
            f,
            ci: 0,
            cj: 0,
            t: 0,
            delta: [0.0; 2],
            ceiling: f.gmax,
            dmax: 0.0,
        }
    }

    /// Conditioned height at node (i, j).
    #[inline]
    fn node(&self, i: i64, j: i64) -> f64 {
        let n = self.f.n as i64;
        let wrap = |d: i64| (d + n / 2).rem_euclid(n) - n / 2;
        let (mx, my) = (wrap(i - self.ci), wrap(j - self.cj));
        let z = self.f.h(i, j);
        if mx.abs() <= WIN && my.abs() <= WIN && self.delta != [0.0; 2] {
            let w = 2 * WIN + 1;
            let k = self.f.k[self.t][((my + WIN) * w + mx + WIN) as usize];
            z + k[0] * self.delta[0] + k[1] * self.delta[1]
        } else {
            z
        }
    }

    /// Conditioned surface height at the point (x, y) of cell (i, j) (local coordinates
    /// x − i, y − j in [0, 1]).
    #[inline]
    pub fn height_in_cell(&self, i: i64, j: i64, x: f64, y: f64) -> f64 {
        let (lx, ly) = (x - i as f64, y - j as f64);
        let h00 = self.node(i, j);
        let h11 = self.node(i + 1, j + 1);
        if ly <= lx {
            let h10 = self.node(i + 1, j);
            h00 + (h10 - h00) * lx + (h11 - h10) * ly
        } else {
            let h01 = self.node(i, j + 1);
            h00 + (h11 - h01) * lx + (h01 - h00) * ly
        }
    }

    /// Slopes of triangle `t` of cell (i, j) in the conditioned field.
    pub fn slope(&self, i: i64, j: i64, t: usize) -> [f64; 2] {
        tri_slope_of(t, |x, y| self.node(i + x, j + y))
    }

    /// Is the ray unblocked (the surface never rises above it)? The origin must lie on the
    /// surface in cell (i, j) on a facet of slope `s_own` that faces the ray; a facet facing
    /// away blocks its own ray. Exact for the triangle representation (module docs).
    pub fn visible(&self, r: &Ray, cell: (i64, i64), s_own: [f64; 2]) -> bool {
        let [dx, dy, dz] = r.d;
        if dz - s_own[0] * dx - s_own[1] * dy <= 0.0 {
            return false;
        }
        if dx == 0.0 && dy == 0.0 {
            return true; // a height field cannot overhang a vertical ray
        }
        let (mut i, mut j) = cell;
        let (sx, sy) = (if dx > 0.0 { 1 } else { -1 }, if dy > 0.0 { 1 } else { -1 });
        let tcross = |p: f64, c: i64, d: f64, step: i64| -> f64 {
            if d == 0.0 {
                f64::INFINITY
            } else {
                ((c + (step > 0) as i64) as f64 - p) / d
            }
        };
        let mut t_in = 0.0f64;
        loop {
            let z_in = r.o[2] + t_in * dz;
            if z_in > self.ceiling {
                return true;
            }
            // Along the ray, the Chebyshev distance from its origin (in the conditioned cell)
            // grows like t·|d|∞, so every node ahead is at least that minus 2 from the
            // conditioned cell — until the ray nears a periodic copy of it, at travel
            // n − WIN − 2. Above the unconditioned maximum plus the largest correction that
            // far out, and above the global ceiling by the time a copy is near, nothing
            // ahead can block.
            let dinf = dx.abs().max(dy.abs());
            let dn = (t_in * dinf).floor() as i64 - 2;
            let t_wrap = (self.f.n as i64 - WIN - 2) as f64 / dinf;
            if z_in > self.f.gmax + self.corr_bound(dn) && r.o[2] + dz * t_wrap > self.ceiling {
                return true;
            }
            if let Some((t, ni, nj)) = self.block_skip(r, (i, j), t_in, z_in) {
                (t_in, i, j) = (t, ni, nj);
                continue;
            }
            let tx = tcross(r.o[0], i, dx, sx);
            let ty = tcross(r.o[1], j, dy, sy);
            let t_out = tx.min(ty);
            // Diagonal crossing inside the cell: (ox − i) + t dx = (oy − j) + t dy.
            let den = dy - dx;
            if den != 0.0 {
                let td = ((r.o[0] - i as f64) - (r.o[1] - j as f64)) / den;
                if td > t_in && td < t_out && self.below(r, i, j, td) {
                    return false;
                }
            }
            if self.below(r, i, j, t_out) {
                return false;
            }
            t_in = t_out;
            if tx <= ty {
                i += sx;
            } else {
                j += sy;
            }
        }
    }

    /// When the rising ray enters the block of cell `c` above the block's highest node (plus
    /// the conditioning's largest correction), the parameter and cell where it leaves the
    /// block: nothing inside can block it.
    fn block_skip(&self, r: &Ray, c: (i64, i64), t_in: f64, z_in: f64) -> Option<(f64, i64, i64)> {
        let b = BLK as i64;
        let nb = (self.f.n / BLK) as i64;
        let (bi, bj) = (c.0.div_euclid(b), c.1.div_euclid(b));
        let bm = self.f.bmax[(bj.rem_euclid(nb) * nb + bi.rem_euclid(nb)) as usize];
        // The conditioning changes only nodes within WIN of the conditioned cell.
        let corr = self.corr_bound(self.dist_to(bi * b, bj * b, b));
        if r.d[2] < 0.0 || z_in <= bm + corr {
            return None;
        }
        let exit = |o: f64, d: f64, blk: i64| -> f64 {
            if d > 0.0 {
                ((blk + 1) * b) as f64 - o
            } else if d < 0.0 {
                (blk * b) as f64 - o
            } else {
                f64::INFINITY
            }
        };
        let tx = exit(r.o[0], r.d[0], bi) / r.d[0];
        let ty = exit(r.o[1], r.d[1], bj) / r.d[1];
        let t = tx.min(ty);
        if !t.is_finite() || t <= t_in {
            return None;
        }
        let step = |d: f64, blk: i64| if d > 0.0 { (blk + 1) * b } else { blk * b - 1 };
        let inside = |p: f64, blk: i64| (p.floor() as i64).clamp(blk * b, blk * b + b - 1);
        let (px, py) = (r.o[0] + t * r.d[0], r.o[1] + t * r.d[1]);
        Some(if tx <= ty {
            (t, step(r.d[0], bi), inside(py, bj))
        } else {
            (t, inside(px, bi), step(r.d[1], bj))
        })
    }

    /// Bound on the conditioning's change of any node at Chebyshev distance ≥ d (periodic)
    /// from the conditioned cell's first node.
    fn corr_bound(&self, d: i64) -> f64 {
        let k = &self.f.k_dist[self.t];
        k[d.clamp(0, k.len() as i64 - 1) as usize] * self.dmax
    }

    /// Periodic Chebyshev distance from the conditioned cell to the nearest node of the
    /// node range [lo, lo + len] along each axis (lower bound).
    fn dist_to(&self, x0: i64, y0: i64, len: i64) -> i64 {
        let n = self.f.n as i64;
        let axis = |a: i64, c: i64| -> i64 {
            let lo = (a - c + n / 2).rem_euclid(n) - n / 2;
            if lo <= 0 && lo + len >= 0 {
                0
            } else {
                lo.abs().min((lo + len).abs())
            }
        };
        axis(x0, self.ci).max(axis(y0, self.cj))
    }

    /// Is the ray below the surface at parameter `t` (a point of cell (i, j))?
    #[inline]
    fn below(&self, r: &Ray, i: i64, j: i64, t: f64) -> bool {
        let (x, y) = (r.o[0] + t * r.d[0], r.o[1] + t * r.d[1]);
        let zr = r.o[2] + t * r.d[2];
        zr < self.height_in_cell(i, j, x, y) - 1e-9
    }
}

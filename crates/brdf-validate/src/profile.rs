//! Periodic 1-D random profiles with Gaussian height statistics.
//!
//! Construction: white noise ξ_j ~ N(0, 1) on a grid of spacing Δx is convolved (directly,
//! periodically, no FFT) with the Gaussian kernel w(x) = exp(−2x²/ℓ²), |x| ≤ 3ℓ. The heights
//! are Gaussian with autocorrelation C(τ) ∝ exp(−τ²/ℓ²) (the self-convolution of w), up to
//! the kernel's truncation at e⁻¹⁸. The profile is piecewise linear between the nodes; its
//! facets are the grid segments and their slopes d_j = (h_{j+1} − h_j)/Δx are exactly
//! Gaussian (a linear map of Gaussian noise).
//!
//! Units: ℓ = 1 and heights are scaled so that the *expected* facet-slope variance is 1
//! (from the discrete covariance, not from the realisation). A surface of RMS slope σ is the
//! same profile with heights multiplied by σ, so one profile serves every σ.
//!
//! Conditioning: given one facet's slope d = s, the rest of the profile is Gaussian with mean
//! shifted by k_m (s − d), where k_m = cov(h_{i0+m}, d)/var(d) = (C_{m−1} − C_m)/Δx for the
//! facet between nodes i0 and i0 + 1. Adding k_m (s − d_u) to an unconditioned profile gives an
//! exact sample of the conditioned one (conditioning by kriging), so G can be measured at any
//! slope, including slopes no facet of the realisation has.

use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_pcg::Pcg64;

/// Grid spacing Δx in units of the correlation length ℓ.
pub const DX: f64 = 0.125;
/// Kernel half-width in nodes (3ℓ).
pub const KERNEL_HALF: usize = 24;
/// Half-width of the conditioning window in nodes (the covariance vanishes beyond 2 × 3ℓ).
pub const WINDOW: usize = 2 * KERNEL_HALF + 1;
/// Nodes per block of the block-maximum table used to skip ahead while tracing.
pub const BLOCK: usize = 32;

/// A periodic random profile (unit expected slope RMS, ℓ = 1).
#[derive(Clone, Debug)]
pub struct Profile {
    h: Vec<f64>,
    mask: usize,
    block_max: Vec<f64>,
    global_max: f64,
    /// k_m for m ∈ [−WINDOW, WINDOW], stored at index m + WINDOW.
    cond: Vec<f64>,
    cond_abs_max: f64,
}

/// The discrete autocovariance C_m = Σ_k w_k w_{k+m} of unit white noise convolved with the
/// kernel, for m = 0 ..= 2·KERNEL_HALF (zero beyond).
pub fn kernel_covariance() -> Vec<f64> {
    let w = kernel();
    let n = w.len();
    (0..n)
        .map(|m| (0..n - m).map(|k| w[k] * w[k + m]).sum())
        .collect()
}

/// The Gaussian kernel w_k = exp(−2 (kΔx)²), k = −KERNEL_HALF ..= KERNEL_HALF.
fn kernel() -> Vec<f64> {
    (0..=2 * KERNEL_HALF)
        .map(|i| {
            let x = (i as f64 - KERNEL_HALF as f64) * DX;
            (-2.0 * x * x).exp()
        })
        .collect()
}

impl Profile {
    /// Generates a profile of 2^`log2_nodes` nodes from `seed` (deterministic).
    pub fn generate(log2_nodes: u32, seed: u64) -> Self {
        let n = 1usize << log2_nodes;
        let mask = n - 1;
        let mut rng = Pcg64::seed_from_u64(seed);
        let xi: Vec<f64> = (0..n).map(|_| rng.sample(StandardNormal)).collect();
        let w = kernel();
        let c = kernel_covariance();
        // Expected slope variance of the unscaled profile: 2(C0 − C1)/Δx².
        let var_d = 2.0 * (c[0] - c[1]) / (DX * DX);
        let scale = 1.0 / var_d.sqrt();
        let kh = KERNEL_HALF as isize;
        let h: Vec<f64> = (0..n)
            .map(|j| {
                let mut s = 0.0;
                for (i, wk) in w.iter().enumerate() {
                    let idx = (j as isize + i as isize - kh).rem_euclid(n as isize) as usize;
                    s += wk * xi[idx];
                }
                s * scale
            })
            .collect();
        let block_max: Vec<f64> = h
            .chunks(BLOCK)
            .map(|b| b.iter().cloned().fold(f64::NEG_INFINITY, f64::max))
            .collect();
        let global_max = block_max.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        // Conditioning weights in scaled units: C'_m = scale² C_m, var(d) = 1.
        let cov = |m: isize| -> f64 {
            let a = m.unsigned_abs();
            if a < c.len() {
                c[a] * scale * scale
            } else {
                0.0
            }
        };
        let cond: Vec<f64> = (-(WINDOW as isize)..=WINDOW as isize)
            .map(|m| (cov(m - 1) - cov(m)) / DX)
            .collect();
        let cond_abs_max = cond.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        Self {
            h,
            mask,
            block_max,
            global_max,
            cond,
            cond_abs_max,
        }
    }

    /// Number of nodes (= number of facets, periodic).
    pub fn len(&self) -> usize {
        self.h.len()
    }
    /// Always false (profiles have at least one node).
    pub fn is_empty(&self) -> bool {
        self.h.is_empty()
    }
    /// Node heights (scaled units).
    pub fn heights(&self) -> &[f64] {
        &self.h
    }
    /// Slope of facet j, (h_{j+1} − h_j)/Δx.
    #[inline]
    pub fn slope(&self, j: usize) -> f64 {
        (self.h[(j + 1) & self.mask] - self.h[j & self.mask]) / DX
    }
    /// The conditioning weight k_m (zero outside the window).
    #[inline]
    pub fn cond_weight(&self, m: isize) -> f64 {
        if m.unsigned_abs() <= WINDOW {
            self.cond[(m + WINDOW as isize) as usize]
        } else {
            0.0
        }
    }
    /// Realised RMS of the facet slopes (should be ≈ 1).
    pub fn realised_slope_rms(&self) -> f64 {
        let n = self.len();
        ((0..n).map(|j| self.slope(j).powi(2)).sum::<f64>() / n as f64).sqrt()
    }
    /// Realised height autocorrelation at a lag of `lag` nodes, normalised by lag 0.
    pub fn realised_autocorrelation(&self, lag: usize) -> f64 {
        let n = self.len();
        let mean = self.h.iter().sum::<f64>() / n as f64;
        let c0: f64 = self.h.iter().map(|x| (x - mean).powi(2)).sum();
        let cl: f64 = (0..n)
            .map(|j| (self.h[j] - mean) * (self.h[(j + lag) & self.mask] - mean))
            .sum();
        cl / c0
    }

    /// Is the point at fraction `t` ∈ [0, 1] along facet `i0` visible along a ray that rises
    /// `q` (scaled height units) per node toward +x (`forward`) or −x, when the profile is
    /// conditioned by adding k_m·`delta` around facet `i0`? `z0` is the point's height in the
    /// conditioned profile. q = ∞ (a vertical ray) is always visible: a height field cannot
    /// overhang. A facet that faces away from the ray blocks it (its own far node is above).
    pub fn visible(&self, i0: usize, t: f64, z0: f64, delta: f64, q: f64, forward: bool) -> bool {
        if q.is_infinite() {
            return true;
        }
        let n = self.len();
        let gmax = self.global_max;
        let win_ceiling = gmax + self.cond_abs_max * delta.abs();
        // Node j steps away from the point: forward nodes i0 + j (j ≥ 1) at distance j − t;
        // backward nodes i0 − j (j ≥ 0) at distance t + j.
        let (first, off) = if forward { (1usize, -t) } else { (0usize, t) };
        let node = |j: usize| -> usize {
            if forward {
                (i0 + j) & self.mask
            } else {
                (i0 + n - (j & self.mask)) & self.mask
            }
        };
        let mut j = first;
        // Inside the conditioning window: node by node with the correction.
        while j <= WINDOW {
            let zr = z0 + q * (j as f64 + off);
            if zr > win_ceiling {
                return true;
            }
            let m = if forward { j as isize } else { -(j as isize) };
            let hj = self.h[node(j)] + self.cond_weight(m) * delta;
            if hj > zr {
                return false;
            }
            j += 1;
        }
        // Beyond it: the unconditioned profile, skipping whole blocks below the ray.
        while j < n {
            let zr = z0 + q * (j as f64 + off);
            if zr > gmax {
                return true;
            }
            let p = node(j);
            let at_block_edge = if forward {
                p % BLOCK == 0
            } else {
                p % BLOCK == BLOCK - 1
            };
            if at_block_edge && zr > self.block_max[p / BLOCK] {
                j += BLOCK;
                continue;
            }
            if self.h[p] > zr {
                return false;
            }
            j += 1;
        }
        true
    }
}

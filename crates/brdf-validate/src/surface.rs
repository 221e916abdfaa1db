//! Ray-traced masking and shadowing on random profiles (the ground truth).
//!
//! For a pair (θi, θr) the facets that reflect the light into the viewer have tilt
//! α = (θr − θi)/2, i.e. slope −tan α (docs/conventions.md §1). G(θi, θr) is the fraction of such
//! facets — of their length, equivalently of their horizontal extent since all have the same
//! slope — that are both lit and seen. A sample picks a facet uniformly, conditions the profile
//! on that facet having exactly the required slope ([`crate::profile`]), picks a point
//! uniformly along it and traces one ray toward the light (−x side) and one toward the viewer.
//! Every ray looks at the whole profile: any part of the surface can block it.

use crate::profile::{Profile, DX};
use crate::stats::{ratio_estimate, Batches, Estimate};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Rise of a ray at polar angle θ (radians) per node, in the scaled units of a profile whose
/// heights are multiplied by σ: cot θ · Δx / σ (∞ at θ = 0).
pub fn rise_per_node(theta: f64, sigma: f64) -> f64 {
    let s = theta.abs().sin();
    if s == 0.0 {
        f64::INFINITY
    } else {
        theta.abs().cos() / s * DX / sigma
    }
}

/// One surface (σ) over a set of independent profiles; each profile is one or more batches.
pub struct Surface<'a> {
    /// The profiles (heights in units where the slope RMS is 1).
    pub profiles: &'a [Profile],
    /// RMS slope σ.
    pub sigma: f64,
}

/// Simulated masking terms for one (θi, θr).
#[derive(Clone, Copy, Debug, Default)]
pub struct GSample {
    /// P(lit and seen): G.
    pub g: Estimate,
    /// P(seen): the masking term alone.
    pub gm: Estimate,
    /// P(lit): the shadowing term alone.
    pub gs: Estimate,
}

/// Batch counts of lit, seen and both (the batch-means estimate of [`GSample`]'s three
/// probabilities), shared by every ray tracer of the crate.
#[derive(Default)]
pub struct GBatches {
    g: Batches,
    gm: Batches,
    gs: Batches,
}

impl GBatches {
    /// One batch of `n` samples, each `sample()` = (lit, seen), recorded as three counts.
    pub fn batch(&mut self, n: u64, mut sample: impl FnMut() -> (bool, bool)) {
        let (mut ng, mut nm, mut ns) = (0u64, 0u64, 0u64);
        for _ in 0..n {
            let (lit, seen) = sample();
            ns += lit as u64;
            nm += seen as u64;
            ng += (lit && seen) as u64;
        }
        self.g.push(ng as f64, n);
        self.gm.push(nm as f64, n);
        self.gs.push(ns as f64, n);
    }

    /// G, GM and GS over all batches so far.
    pub fn estimate(&self) -> GSample {
        GSample {
            g: self.g.estimate(),
            gm: self.gm.estimate(),
            gs: self.gs.estimate(),
        }
    }
}

/// Seeds derived from a base seed and a few indices (SplitMix64 mixing).
pub fn mix_seed(parts: &[u64]) -> u64 {
    let mut z = 0x9E37_79B9_7F4A_7C15u64;
    for &p in parts {
        z ^= p.wrapping_add(0x9E37_79B9_7F4A_7C15).wrapping_add(z << 6);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
    }
    z
}

impl Surface<'_> {
    /// G, GM and GS at (θi, θr) (radians; θi ∈ [0, π/2), θr ∈ (−π/2, π/2)) with
    /// `per_batch` samples in each of `batches_per_profile` batches per profile.
    pub fn g(
        &self,
        theta_i: f64,
        theta_r: f64,
        per_batch: u64,
        batches_per_profile: u64,
        seed: u64,
    ) -> GSample {
        let alpha = 0.5 * (theta_r - theta_i);
        let s = -alpha.tan() / self.sigma; // required slope in scaled units
        let qi = rise_per_node(theta_i, self.sigma);
        let qr = rise_per_node(theta_r, self.sigma);
        let mut counts = GBatches::default();
        for (pi, prof) in self.profiles.iter().enumerate() {
            for b in 0..batches_per_profile {
                let mut rng = Pcg64::seed_from_u64(mix_seed(&[seed, pi as u64, b]));
                counts.batch(per_batch, || {
                    let i0 = rng.random_range(0..prof.len());
                    let t: f64 = rng.random();
                    let delta = s - prof.slope(i0);
                    let z0 = prof.heights()[i0] + prof.cond_weight(0) * delta + t * s * DX;
                    let lit = prof.visible(i0, t, z0, delta, qi, false);
                    let seen = prof.visible(i0, t, z0, delta, qr, theta_r > 0.0);
                    (lit, seen)
                });
            }
        }
        counts.estimate()
    }

    /// The same G measured the direct way: scan the unconditioned profile for facets whose
    /// slope lies within ±`half_bin`·σ of −tan α (a slope bin of relative half-width
    /// `half_bin`), up to `per_batch` accepted facets per batch.
    pub fn g_slope_bin(
        &self,
        theta_i: f64,
        theta_r: f64,
        half_bin: f64,
        per_batch: u64,
        batches_per_profile: u64,
        seed: u64,
    ) -> Estimate {
        let alpha = 0.5 * (theta_r - theta_i);
        let s = -alpha.tan() / self.sigma;
        let qi = rise_per_node(theta_i, self.sigma);
        let qr = rise_per_node(theta_r, self.sigma);
        let mut bg = Batches::default();
        for (pi, prof) in self.profiles.iter().enumerate() {
            let n = prof.len();
            let chunk = n / batches_per_profile as usize;
            for b in 0..batches_per_profile as usize {
                let mut rng = Pcg64::seed_from_u64(mix_seed(&[seed, pi as u64, b as u64, 7]));
                let (mut ng, mut acc) = (0u64, 0u64);
                for i0 in b * chunk..(b + 1) * chunk {
                    if acc >= per_batch {
                        break;
                    }
                    let d = prof.slope(i0);
                    if (d - s).abs() > half_bin {
                        continue;
                    }
                    let t: f64 = rng.random();
                    let z0 = prof.heights()[i0] + t * d * DX;
                    let lit = prof.visible(i0, t, z0, 0.0, qi, false);
                    let seen = prof.visible(i0, t, z0, 0.0, qr, theta_r > 0.0);
                    acc += 1;
                    ng += (lit && seen) as u64;
                }
                bg.push(ng as f64, acc);
            }
        }
        bg.estimate()
    }

    /// One-sided masking over the whole surface, weighted by projected area: returns
    /// (G1 = E[vis·w]/E[w], identity ratio E[vis·w]/cos θ), with w = (cos θ − s sin θ)⁺ the
    /// projected width of a facet of slope s seen from θ (per unit horizontal width). For any
    /// height field the visible projected width equals the macro-surface's, cos θ, so the
    /// identity ratio is exactly 1 and G1 is exactly Smith's 1/(1 + Λ) whatever the
    /// correlation (the projected-area identity); this checks the ray tracer.
    pub fn g1_area(
        &self,
        theta: f64,
        per_batch: u64,
        batches_per_profile: u64,
        seed: u64,
    ) -> (Estimate, Estimate) {
        let q = rise_per_node(theta, self.sigma);
        let (ct, st) = (theta.cos(), theta.sin());
        let (mut num, mut den, mut idn) = (Vec::new(), Vec::new(), Vec::new());
        for (pi, prof) in self.profiles.iter().enumerate() {
            for b in 0..batches_per_profile {
                let mut rng = Pcg64::seed_from_u64(mix_seed(&[seed, pi as u64, b, 11]));
                let (mut sv, mut sw) = (0.0, 0.0);
                for _ in 0..per_batch {
                    let i0 = rng.random_range(0..prof.len());
                    let t: f64 = rng.random();
                    let d = prof.slope(i0);
                    let w = (ct - self.sigma * d * st).max(0.0);
                    sw += w;
                    if w > 0.0 {
                        let z0 = prof.heights()[i0] + t * d * DX;
                        if prof.visible(i0, t, z0, 0.0, q, true) {
                            sv += w;
                        }
                    }
                }
                num.push(sv);
                den.push(sw);
                idn.push(ct * per_batch as f64);
            }
        }
        (ratio_estimate(&num, &den), ratio_estimate(&num, &idn))
    }
}

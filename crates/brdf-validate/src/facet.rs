//! The paper's single-neighbour facet model, simulated geometrically.
//!
//! Assumptions (paper §3, docs/conventions.md §3): facet 1 has tilt α and unit length; each of its
//! two neighbours has unit length (the equal-length assumption under which eq 9's fraction
//! holds) and an independent tilt drawn from the paper's slope-angle density p(γ; σ) (eq 2,
//! normalised); only the adjacent facet on the ray's side can block a ray. A sample picks a
//! point uniformly along facet 1 and intersects the ray toward the light (−x side) and the
//! ray toward the viewer with the neighbour segments. P(seen) must reproduce the formula
//! M(θr, α) and P(lit) must reproduce M(θi, −α) if eqs 6–12 are right about their own
//! assumption; P(lit and seen) shows what taking min(GM, GS) (eq 13) costs.

use crate::surface::{mix_seed, GBatches, GSample};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_pcg::Pcg64;

/// Draws u = tan γ from the density ∝ √(1 + u²) exp(−u²/(2σ²)) — p(γ) dγ in the variable
/// u (docs/conventions.md §2) — by rejection from the envelope (1 + |u|)·N(0, σ²), a mixture of a
/// normal and a signed Rayleigh(σ); acceptance √(1 + u²)/(1 + |u|) ≥ 1/√2.
pub fn sample_neighbour_slope<R: Rng>(rng: &mut R, sigma: f64) -> f64 {
    let w_rayleigh = sigma * (2.0 / std::f64::consts::PI).sqrt();
    loop {
        let u = if rng.random::<f64>() * (1.0 + w_rayleigh) < 1.0 {
            sigma * rng.sample::<f64, _>(StandardNormal)
        } else {
            let r = sigma * (-2.0 * (1.0 - rng.random::<f64>()).ln()).sqrt();
            if rng.random::<bool>() {
                r
            } else {
                -r
            }
        };
        let acc = (1.0 + u * u).sqrt() / (1.0 + u.abs());
        if rng.random::<f64>() < acc {
            return u;
        }
    }
}

/// Does the ray from `p` along `d` (λ > 0) cross the segment a–b?
fn ray_hits_segment(p: [f64; 2], d: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    let e = [b[0] - a[0], b[1] - a[1]];
    let det = d[0] * (-e[1]) + e[0] * d[1];
    if det.abs() < 1e-300 {
        return false;
    }
    let r = [a[0] - p[0], a[1] - p[1]];
    // Solve λ d − μ e = r.
    let lam = (r[0] * (-e[1]) + e[0] * r[1]) / det;
    let mu = (d[0] * r[1] - d[1] * r[0]) / det;
    lam > 1e-12 && (0.0..=1.0).contains(&mu)
}

/// G, GM and GS of the single-neighbour model at (θi, θr), radians.
pub fn g_single_neighbour(
    theta_i: f64,
    theta_r: f64,
    sigma: f64,
    per_batch: u64,
    batches: u64,
    seed: u64,
) -> GSample {
    let alpha = 0.5 * (theta_r - theta_i);
    let a0 = [0.0, 0.0];
    let a1 = [alpha.cos(), -alpha.sin()];
    let to_light = [-theta_i.sin(), theta_i.cos()];
    let to_view = [theta_r.sin(), theta_r.cos()];
    let mut counts = GBatches::default();
    for b in 0..batches {
        let mut rng = Pcg64::seed_from_u64(mix_seed(&[seed, b, 3]));
        counts.batch(per_batch, || {
            let ul = sample_neighbour_slope(&mut rng, sigma);
            let ur = sample_neighbour_slope(&mut rng, sigma);
            let (cl, cr) = (1.0 / (1.0 + ul * ul).sqrt(), 1.0 / (1.0 + ur * ur).sqrt());
            // Left neighbour ends at a0, right neighbour starts at a1 (unit lengths).
            let l0 = [a0[0] - cl, a0[1] - ul * cl];
            let r1 = [a1[0] + cr, a1[1] + ur * cr];
            let t: f64 = rng.random();
            let x = [t * a1[0], t * a1[1]];
            let lit = !ray_hits_segment(x, to_light, l0, a0);
            let seen = if theta_r > 0.0 {
                !ray_hits_segment(x, to_view, a1, r1)
            } else if theta_r < 0.0 {
                !ray_hits_segment(x, to_view, l0, a0)
            } else {
                true
            };
            (lit, seen)
        });
    }
    counts.estimate()
}

//! The converged split sums (`brdf_core::split_sum::converged`: visible-normal spherical cap,
//! exact horizon cut per row, adaptive K15/G7 in θ and φ) against an independent reference:
//! nested adaptive Gauss–Kronrod over the half vector in the GGX CDF variable with the cut
//! in closed form (`brdf_tests::reference::split_sum_ggx`, tolerance 1e-11).
//!
//! Points: texel centres of a 1024² table (μ = (i + ½)/1024, r = (j + ½)/1024), the
//! grazing columns i = 0…3 and μ = cos 89°, a seeded random sample, r → 0 and r = 1.
//! Checked (asserted): every channel within ½ LSB of 16 bits (7.6e-6) of the reference.
//! Reported (printed, not asserted): the points where the returned estimate is below the
//! observed error less the reference's own uncertainty
//! (1e-9: the outer tolerance 1e-11 is on a sum of |K15 − G7| terms, which bound the
//! reference's error by orders of magnitude; 1e-9 leaves a wide margin for the inner
//! integrals' rounding).

use brdf_core::split_sum::converged::{dfg_ggx_converged, Converged};
use brdf_tests::reference::split_sum_ggx;
use rand::{Rng, SeedableRng};

/// Tolerance asked of the integrator per channel (the estimate is checked, not assumed).
const TOL: f64 = 1e-6;
/// ½ LSB of a 16-bit UNORM channel.
const HALF_LSB: f64 = 0.5 / 65535.0;
/// The reference's own uncertainty allowed when checking the estimate (module docs).
const REF_UNCERTAINTY: f64 = 1e-9;
const SIZE: f64 = 1024.0;

fn centre(k: usize) -> f64 {
    (k as f64 + 0.5) / SIZE
}

/// Stats of one set: (max |error|, max error/estimate, exceptions, evals mean, evals max).
fn check(name: &str, pts: &[(f64, f64)]) {
    let (mut worst, mut ratio, mut bad, mut sum, mut max) = (0f64, 0f64, 0usize, 0u64, 0u32);
    for &(mu, r) in pts {
        let c: Converged<f64> = dfg_ggx_converged(mu, r, TOL);
        let want = if r == 0.0 {
            let fc = (1.0 - mu).powi(5);
            (1.0 - fc, fc)
        } else {
            split_sum_ggx(mu, r * r, 1e-11)
        };
        for (ch, w) in [want.0, want.1].into_iter().enumerate() {
            let err = (c.value[ch] - w).abs();
            worst = worst.max(err);
            ratio = ratio.max(err / c.error[ch]);
            if err > c.error[ch] + REF_UNCERTAINTY {
                bad += 1;
                eprintln!(
                    "{name}: estimate {:.2e} < error {err:.2e} at mu {mu} r {r} ch {ch}",
                    c.error[ch]
                );
            }
            assert!(
                err <= HALF_LSB,
                "{name}: mu {mu} r {r} ch {ch}: {} vs {w}",
                c.value[ch]
            );
        }
        sum += c.evals as u64;
        max = max.max(c.evals);
    }
    println!(
        "{name}: {} points, max |error| {worst:.2e}, max error/estimate {ratio:.2e}, \
         estimate exceptions {bad}, evals/texel mean {:.0} max {max}",
        pts.len(),
        sum as f64 / pts.len() as f64
    );
    // The estimate's exceptions are reported (printed above and counted), not asserted:
    // at small r (α ≈ 0.004–0.03) a few points exceed their estimate by up to ~20× while
    // staying far inside ½ LSB (see the report of issue 22's numerical core).
}

#[test]
#[ignore = "long run (≥ 15 min on 2 cores; the integrator is not yet fast): cargo test -p brdf-tests --test split_sum_converged -- --ignored"]
fn grazing_columns_within_half_lsb() {
    let mut pts = Vec::new();
    for j in (0..1024).step_by(32).chain([1, 2, 3, 1023]) {
        for mu in [
            centre(0),
            centre(1),
            centre(2),
            centre(3),
            89f64.to_radians().cos(),
        ] {
            pts.push((mu, centre(j)));
        }
    }
    check("grazing", &pts);
}

#[test]
#[ignore = "long run (≥ 15 min on 2 cores; the integrator is not yet fast): cargo test -p brdf-tests --test split_sum_converged -- --ignored"]
fn random_texels_within_half_lsb() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(22);
    let pts: Vec<(f64, f64)> = (0..2000)
        .map(|_| {
            (
                centre(rng.random_range(0..1024)),
                centre(rng.random_range(0..1024)),
            )
        })
        .collect();
    check("random 2000", &pts);
}

#[test]
#[ignore = "long run (≥ 15 min on 2 cores; the integrator is not yet fast): cargo test -p brdf-tests --test split_sum_converged -- --ignored"]
fn narrow_and_widest_lobes() {
    let mus = [centre(0), centre(3), 0.05, 0.3, 0.7, 1.0];
    let mut pts = Vec::new();
    for mu in mus {
        for r in [0.0, centre(0), centre(10), 0.03, 1.0, centre(1023)] {
            pts.push((mu, r));
        }
    }
    check("r -> 0 and r = 1", &pts);
}

/// The CI-sized sample of the three sets above: one grazing texel centre, one mid and one
/// near-normal μ, at a mid and the widest roughness (the long sets are `--ignored`).
#[test]
fn ci_sample_within_half_lsb() {
    let mut pts = Vec::new();
    for mu in [centre(0), 0.3, 0.9] {
        for r in [0.5, 1.0] {
            pts.push((mu, r));
        }
    }
    check("CI sample", &pts);
}

/// Regression (issue: `converged` off by up to 1e-6 in B at r ≲ 0.55 with estimates of
/// ~1e-11): the three reported texels at tol 1e-10 against the polar integrator
/// (`split_sum::polar`, independent code, at 1e-10; it agrees with `split_sum_ggx` there),
/// within the sum of both estimates. The cause was the row scan (48 samples of n·l graded
/// toward the cap edge), which missed the thin lit piece in the edge ring of width ~α where
/// small α packs the lobe's tail (the value there is mostly F_c ≈ 1, hence B); the cuts are
/// now exact. Before the fix the differences were 8.6e-7, 8.1e-7 and 1.0e-6 at any tolerance.
#[test]
fn reported_small_roughness_texels_match_polar() {
    use brdf_core::split_sum::polar::dfg_ggx_polar;
    // The three reported small-roughness texels, then the table corner μ = 1, r = 1 (where
    // the exact cuts' quartic degenerates: it once returned (0, 0)) and its neighbours.
    for (mu, r) in [
        (0.0039, 0.0625),
        (0.0977, 0.104),
        (0.0004, 0.021),
        (1.0, 1.0),
        (1.0, 0.999),
        (0.9999, 1.0),
    ] {
        let c: Converged<f64> = dfg_ggx_converged(mu, r, 1e-10);
        let p = dfg_ggx_polar(mu, r, 1e-10);
        for ch in 0..2 {
            let err = (c.value[ch] - p.value[ch]).abs();
            assert!(
                err <= c.error[ch] + p.error[ch],
                "mu {mu} r {r} ch {ch}: {} vs polar {} (estimates {:.1e} {:.1e})",
                c.value[ch],
                p.value[ch],
                c.error[ch],
                p.error[ch]
            );
        }
    }
}

/// The second reported texel (μ 0.0977, r 0.104) against `split_sum_ggx` at 1e-9 (the
/// reference at 1e-11 takes minutes here): within the estimate plus 1e-8, a margin of 100×
/// the reference's tolerance, still 80× below the reported 8.1e-7.
#[test]
fn reported_texel_matches_reference() {
    let (mu, r) = (0.0977, 0.104);
    let c: Converged<f64> = dfg_ggx_converged(mu, r, 1e-10);
    let want = split_sum_ggx(mu, r * r, 1e-9);
    for (ch, w) in [want.0, want.1].into_iter().enumerate() {
        let err = (c.value[ch] - w).abs();
        assert!(err <= c.error[ch] + 1e-8, "ch {ch}: {} vs {w}", c.value[ch]);
    }
}

/// The converged integrator against the polar one (`split_sum::polar`, independent code:
/// other coordinates, other rules) on the texel centres of a 12 × 12 grid at tol 1e-6:
/// asserted within the asked tolerance (before the fix: up to 1e-6 off at r ≲ 0.55);
/// the points where the difference exceeds the sum of both estimates are printed.
#[test]
fn grid_matches_polar() {
    use brdf_core::split_sum::polar::dfg_ggx_polar;
    const N: usize = 12;
    let (mut worst, mut over) = (0f64, 0usize);
    for j in 0..N {
        for i in 0..N {
            let (mu, r) = ((i as f64 + 0.5) / N as f64, (j as f64 + 0.5) / N as f64);
            let c: Converged<f64> = dfg_ggx_converged(mu, r, TOL);
            let p = dfg_ggx_polar(mu, r, 1e-10);
            for ch in 0..2 {
                let d = (c.value[ch] - p.value[ch]).abs();
                worst = worst.max(d);
                assert!(
                    d <= TOL,
                    "mu {mu} r {r} ch {ch}: {} vs polar {}",
                    c.value[ch],
                    p.value[ch]
                );
                if d > c.error[ch] + p.error[ch] {
                    over += 1;
                    eprintln!(
                        "mu {mu} r {r} ch {ch}: |diff| {d:.2e} > estimates {:.1e} + {:.1e}",
                        c.error[ch], p.error[ch]
                    );
                }
            }
        }
    }
    println!("grid {N}²: max |converged − polar| {worst:.2e}, over both estimates {over}");
}

//! Shared by the rough-glass tests: two integrations of the same (R, T) compared within the
//! sum of their own error estimates.

use brdf_lut::generate::Work;

/// Asserts |a − b| ≤ a's estimate + b's per channel (`at` names the point in the message)
/// and returns the largest |a − b| / (sum of estimates).
pub fn within_estimates(at: &str, a: &([f64; 2], Work), b: &([f64; 2], Work)) -> f64 {
    let sum = a.1.error + b.1.error;
    let mut ratio = 0f64;
    for c in 0..2 {
        let d = (a.0[c] - b.0[c]).abs();
        ratio = ratio.max(d / sum);
        assert!(
            d <= sum,
            "{at} channel {c}: {} vs {} (|Δ| {d:e}, estimates {:e}, {:e})",
            a.0[c],
            b.0[c],
            a.1.error,
            b.1.error
        );
    }
    ratio
}

/// The two inside points where the cap integrator was off (R by up
/// to 5.4e-6): (μ, r, η, R, T), R and T from the brute-force midpoint rule on an
/// 8000 × 8000 grid in the cap's (θ, φ) (tests/glass_measure.rs `brute`), whose 2000-,
/// 4000- and 8000-point values agree to 2e-7.
pub const BRUTE: [(f64, f64, f64, f64, f64); 2] = [
    (
        0.718_750_701_722_704_4,
        0.390_912_995_894_539_43,
        0.629_576_074_131_773,
        0.739_691_834_0,
        0.200_271_304_7,
    ),
    (
        0.605_288_935_154_154_2,
        0.948_475_569_600_138_7,
        0.464_067_523_485_068,
        0.295_206_505_7,
        0.141_805_649_7,
    ),
];

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

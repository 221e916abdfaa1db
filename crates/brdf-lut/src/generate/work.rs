//! What every node integrator reports and the tolerances it is asked for: the vocabulary
//! the generator's integrators (the split-sum family in `integrate`, `sheen`, `glass`) share,
//! kept apart so that none of them imports another for it.

/// Absolute tolerance per channel asked of the converged rules.
pub const TOL: f64 = 2e-6;
/// Absolute tolerance per channel of `lut verify`'s GGX reference.
pub const REFERENCE_TOL: f64 = 2e-8;

/// A node's integration: the largest error estimate over its channels and the integrand
/// evaluations it took (0 where the rule does not count them: the polar E_avg).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Work {
    /// Estimated |value − exact integral|, largest over the channels.
    pub error: f64,
    /// Integrand evaluations.
    pub evals: u64,
}

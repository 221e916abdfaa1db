//! The work-size limits of the tools that build and check tables (`cargo xtask lut …`,
//! docs/lut-format.md "Limits"): every number read from the command line, a configuration
//! file or a table's header that sizes memory or time is checked here before any work or
//! allocation, so no input can make a tool abort on memory or run for hours.
//!
//! Memory is bounded by counts (points, nodes per axis, values per table); time by a cost
//! per point known per table kind and model, in microseconds of one core, estimated from the
//! project's own machine with a margin ([`cost_per_point_us`]), against a budget of seconds
//! of one core ([`MAX_GENERATE_SECONDS`], [`MAX_VERIFY_SECONDS`]). The checks are pure
//! arithmetic: `no_std`, no allocation.

use crate::header::{Model, TableKind, MAX_AXIS_COUNT};
use core::fmt;

/// Most random points of one error measurement (`lut generate --samples`, `lut verify
/// --samples`, and the count a header records, which `lut verify` reads): a few hundred
/// bytes of memory each.
pub const MAX_SAMPLES: u32 = 200_000;
/// Most nodes along one axis of a table a tool builds (the format's own limit).
pub const MAX_NODES_PER_AXIS: u32 = MAX_AXIS_COUNT;
/// Most stored values (nodes × channels) of a table a tool builds: 2²⁵, a 4096² two-channel
/// engine texture (256 MiB as f64 while it is built; the format itself reads up to
/// [`MAX_VALUES`](crate::MAX_VALUES)). The generator's own cap is this constant.
pub const MAX_BUILD_VALUES: u64 = 1 << 25;
/// Largest estimated work of one `lut generate` (nodes and error measurement), in seconds
/// of one core ([`cost_per_point_us`]); the wall time is this over the number of cores.
pub const MAX_GENERATE_SECONDS: u64 = 600;
/// Largest estimated work of `lut verify` on one table, in seconds of one core: a header
/// that records more points than this allows is verified at as many as it allows.
pub const MAX_VERIFY_SECONDS: u64 = 20;
/// Largest configuration (TOML) file read, in bytes.
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// A number over the tool's limit: what it is, its value and the limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LimitError {
    /// What was counted, e.g. `--samples`.
    pub what: &'static str,
    /// The number asked for (saturated at `u64::MAX`).
    pub value: u64,
    /// The smallest number allowed.
    pub min: u64,
    /// The largest number allowed.
    pub max: u64,
    /// The unit of `value`, `min` and `max` (empty for a count).
    pub unit: &'static str,
}

impl fmt::Display for LimitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (v, lo, hi, u) = (self.value, self.min, self.max, self.unit);
        write!(
            f,
            "{} is {v}{u}; the limit is {lo}..={hi}{u} (docs/lut-format.md, Limits)",
            self.what
        )
    }
}

impl core::error::Error for LimitError {}

/// `value` within `min..=max`, or the error naming `what`.
pub fn check_range(what: &'static str, value: u64, min: u64, max: u64) -> Result<(), LimitError> {
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(LimitError {
            what,
            value,
            min,
            max,
            unit: "",
        })
    }
}

/// A number of error-measurement points: 1..=[`MAX_SAMPLES`].
pub fn check_samples(what: &'static str, n: u64) -> Result<(), LimitError> {
    check_range(what, n, 1, MAX_SAMPLES as u64)
}

/// A grid to build: each axis 2..=[`MAX_NODES_PER_AXIS`] nodes, and nodes × `channels` at
/// most [`MAX_BUILD_VALUES`]. Returns the number of nodes.
pub fn check_grid(counts: &[u64], channels: u64) -> Result<u64, LimitError> {
    let mut nodes: u64 = 1;
    for &c in counts {
        check_range("nodes per axis", c, 2, MAX_NODES_PER_AXIS as u64)?;
        nodes = nodes.saturating_mul(c);
    }
    check_range(
        "stored values (nodes x channels)",
        nodes.saturating_mul(channels.max(1)),
        1,
        MAX_BUILD_VALUES,
    )?;
    Ok(nodes)
}

/// Estimated microseconds of one core to evaluate the direct kernel once (one node of a
/// table, or one point of its error measurement), by kind and model: upper estimates (an
/// average-albedo point of the default assets was measured at 6–9 ms). The albedo kinds
/// integrate the BRDF over the hemisphere (and E_avg once more over μ), and the modified
/// G costs more per evaluation than Smith's closed forms.
pub fn cost_per_point_us(kind: TableKind, model: Model) -> u64 {
    let modified = matches!(model, Model::ModifiedG | Model::TorranceSparrowModifiedG);
    kind.cost_per_point_us(modified)
}

/// Checks the estimated work of building a table with `nodes` nodes and measuring it at
/// `samples` points against [`MAX_GENERATE_SECONDS`].
pub fn check_generate(
    kind: TableKind,
    model: Model,
    nodes: u64,
    samples: u64,
) -> Result<(), LimitError> {
    let us = nodes
        .saturating_add(samples)
        .saturating_mul(cost_per_point_us(kind, model));
    let secs = us.div_ceil(1_000_000);
    if secs <= MAX_GENERATE_SECONDS {
        Ok(())
    } else {
        Err(LimitError {
            what: "the estimated work (nodes + points, x the kernel's cost per point)",
            value: secs,
            min: 0,
            max: MAX_GENERATE_SECONDS,
            unit: " s of one core",
        })
    }
}

/// Most points `lut verify` measures on a table of this kind within
/// [`MAX_VERIFY_SECONDS`] (at least 1, at most [`MAX_SAMPLES`]).
pub fn max_verify_points(kind: TableKind, model: Model) -> u32 {
    let n = MAX_VERIFY_SECONDS * 1_000_000 / cost_per_point_us(kind, model).max(1);
    n.clamp(1, MAX_SAMPLES as u64) as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn ranges_and_grids() {
        assert!(check_samples("s", 0).is_err());
        assert!(check_samples("s", 1).is_ok());
        assert!(check_samples("s", MAX_SAMPLES as u64).is_ok());
        let e = check_samples("--samples", 1_000_000_000).unwrap_err();
        assert_eq!(e.value, 1_000_000_000);
        assert!(e.to_string().contains("1..=200000"), "{e}");
        assert_eq!(check_grid(&[8, 8], 2), Ok(64));
        assert!(check_grid(&[1, 8], 2).is_err());
        assert!(check_grid(&[65_537, 2], 1).is_err());
        // 8192 x 4096 x 2 channels = 2^26 values: over 2^25; a 4096² RG texture fits.
        assert!(check_grid(&[8192, 4096], 2).is_err());
        assert!(check_grid(&[4096, 4096], 2).is_ok());
        // Saturating: no overflow whatever the counts.
        assert!(check_grid(&[65_536, 65_536, 65_536], 4).is_err());
    }

    #[test]
    fn work_budget() {
        let (k, m) = (TableKind::AverageAlbedo, Model::GgxSmithCorrelated);
        let n = max_verify_points(k, m);
        assert!(n >= 1 && (n as u64) * cost_per_point_us(k, m) <= MAX_VERIFY_SECONDS * 1_000_000);
        assert_eq!(
            max_verify_points(TableKind::PassingFactor, Model::ModifiedG),
            MAX_SAMPLES
        );
        assert!(check_generate(k, m, 64, 2000).is_ok());
        assert!(check_generate(k, m, 64, u64::MAX).is_err());
        assert!(check_generate(TableKind::SplitSum, m, 8 * 8, 1_000_000_000).is_err());
    }
}

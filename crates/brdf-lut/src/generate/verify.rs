//! `lut verify`'s check of a table's recorded integration error bound: a sample of nodes
//! recomputed by an independent, much finer rule ([`super::reference`]).

use super::reference;
use super::{Role, Spec};
use crate::write::node_coords;
use crate::{Encoding, LutView};
use std::vec;
use std::vec::Vec;

/// One checked node and channel.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeCheck {
    /// Flat node index (axis 0 fastest).
    pub node: usize,
    /// Its physical coordinates.
    pub at: Vec<f64>,
    /// The channel.
    pub channel: usize,
    /// The value the table decodes at the node.
    pub stored: f64,
    /// The reference value.
    pub reference: f64,
    /// The largest difference the header allows there: the recorded bound + half the
    /// encoding's quantisation step + the f32 rounding of the decoded value + the
    /// reference's own estimate.
    pub allowed: f64,
}

impl NodeCheck {
    /// Whether the node is within what the header allows.
    pub fn ok(&self) -> bool {
        (self.stored - self.reference).abs() <= self.allowed
    }
}

/// The nodes `lut verify` checks: `count` spread evenly over the flat index (first and
/// last included) and, where axis 0 is μ, the smallest-μ column at 16 rows spread over the
/// other axes; sorted, without repeats.
pub fn sample_nodes(spec: &Spec, total: usize, count: usize) -> Vec<usize> {
    let spread = |m: usize, n: usize| (0..m).map(move |k| k * (n - 1) / (m - 1).max(1));
    let mut v: Vec<usize> = spread(count.min(total), total).collect();
    let n0 = spec.axes.first().map_or(1, |a| a.count as usize).max(1);
    let rows = total / n0;
    if spec.kind.def().axes.first().map(|a| a.0) == Some(Role::Mu) && rows > 0 {
        v.extend(spread(16.min(rows), rows).map(|j| j * n0));
    }
    v.sort_unstable();
    v.dedup();
    v
}

/// Half the quantisation step of the stored number nearest `v` in `enc` (channel scale
/// `scale`): u16 scale/65535/2; binary16 and binary32 half a unit in the last place of v.
fn half_step(enc: Encoding, scale: f64, v: f64) -> f64 {
    let ulp = |mant: i32, min_exp: i32| {
        let e = if v == 0.0 {
            min_exp
        } else {
            (libm::floor(libm::log2(v.abs())) as i32).max(min_exp)
        };
        libm::exp2((e - mant) as f64)
    };
    match enc {
        Encoding::Unorm16 => scale.abs() / 65535.0 * 0.5,
        Encoding::F16 => ulp(10, -14) * 0.5,
        Encoding::F32 => ulp(23, -126) * 0.5,
    }
}

/// Recomputes the sampled nodes ([`sample_nodes`], `count` spread ones) of `view` (a table
/// this generator describes as `spec`) with the reference rule, channel by channel,
/// against the recorded integration bound `bound`. Runs on all cores; the result is in node
/// order.
pub fn check_nodes(spec: &Spec, view: &LutView<'_>, bound: f64, count: usize) -> Vec<NodeCheck> {
    let axes = &view.header().axes;
    let total = view.header().nodes() as usize;
    let nodes = sample_nodes(spec, total, count);
    let nc = view.channels();
    let mut refs = vec![([0.0; 2], 0.0); nodes.len()];
    super::par_chunks(&mut refs, 1, &|k, r| {
        r[0] = reference(spec, &node_coords(axes, nodes[k]));
    });
    let mut out = Vec::new();
    for (&k, (rv, est)) in nodes.iter().zip(refs) {
        for (c, &reference) in rv.iter().enumerate().take(nc) {
            let stored = view.node_value(k, c) as f64;
            let scale = view.header().channels[c].scale as f64;
            // The f32 arithmetic of the decode (offset + scale × stored) rounds once more.
            let f32_round = stored.abs() * f32::EPSILON as f64;
            let q = half_step(view.header().encoding, scale, stored);
            out.push(NodeCheck {
                node: k,
                at: node_coords(axes, k).to_vec(),
                channel: c,
                stored,
                reference,
                allowed: bound + q + f32_round + est,
            });
        }
    }
    out
}

/// How many random points `lut verify` measures a table at: the count asked for, else the
/// header's recorded count capped by the kind's time budget
/// ([`crate::limits::max_verify_points`], docs/lut-format.md, Limits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VerifyPoints {
    /// Points to measure.
    pub n: u32,
    /// The recorded count when the budget capped it to `n`.
    pub capped_from: Option<u32>,
    /// Estimated microseconds of one core per point.
    pub cost_us: u64,
}

/// A count asked for that does not fit the kind's verification budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OverBudget {
    /// Points asked for.
    pub asked: u32,
    /// The most that fit.
    pub cap: u32,
    /// Estimated microseconds of one core per point.
    pub cost_us: u64,
    /// The table's kind.
    pub kind: crate::TableKind,
    /// The table's model.
    pub model: crate::Model,
}

impl core::fmt::Display for OverBudget {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} points: a {:?} table of model {:?} costs about {} us a point; at most {} \
             points fit `lut verify`'s budget of {} s of one core (docs/lut-format.md, Limits)",
            self.asked,
            self.kind,
            self.model,
            self.cost_us,
            self.cap,
            crate::limits::MAX_VERIFY_SECONDS
        )
    }
}

impl std::error::Error for OverBudget {}

/// The points to verify the table of header `h` at ([`VerifyPoints`]): `asked` when it fits
/// the budget (an error otherwise), else the recorded count, capped.
pub fn verify_points(
    h: &crate::Header<'_>,
    asked: Option<u32>,
) -> Result<VerifyPoints, OverBudget> {
    use crate::limits;
    let (kind, model) = (h.kind, h.generator.model);
    let cap = limits::max_verify_points(kind, model);
    let cost_us = limits::cost_per_point_us(kind, model);
    if let Some(n) = asked {
        if n > cap {
            return Err(OverBudget {
                asked: n,
                cap,
                cost_us,
                kind,
                model,
            });
        }
        return Ok(VerifyPoints {
            n,
            capped_from: None,
            cost_us,
        });
    }
    let recorded = h.error.samples;
    let n = recorded.clamp(1, cap);
    Ok(VerifyPoints {
        n,
        capped_from: (n < recorded).then_some(recorded),
        cost_us,
    })
}

/// Max and RMS |table − direct kernel| at `n` random points (seeded by `seed`), measured
/// ([`super::measure`]) with the spec the table's header describes; NaN statistics when
/// it describes no table this generator builds (NaN fails every comparison).
pub fn measure_table(view: &LutView<'_>, n: u32, seed: u64) -> crate::ErrorStats {
    let h = view.header();
    match Spec::from_header(h) {
        Some(mut spec) => {
            (spec.samples, spec.seed) = (n, seed);
            super::measure(&spec, view, &h.axes)
        }
        None => crate::ErrorStats {
            max_abs: f32::NAN,
            rms: f32::NAN,
            samples: n,
            seed,
        },
    }
}

/// Whether a measured max |error| is worse than the recorded one allows: measured >
/// recorded × (1 + `tolerance`) + 1e-6, or not a number.
pub fn worse_than_recorded(measured: f32, recorded: f32, tolerance: f64) -> bool {
    let limit = recorded as f64 * (1.0 + tolerance) + 1e-6;
    measured.is_nan() || measured as f64 > limit
}

/// The recorded integration bound of a table checked at nodes ([`check_nodes`]).
#[derive(Clone, Debug, PartialEq)]
pub enum BoundCheck {
    /// The header records no bound (a version 1 file).
    NotRecorded,
    /// The header describes no table this generator builds.
    NoSpec,
    /// The bound and the nodes checked against it (at least one).
    Checked {
        /// The recorded bound.
        bound: f32,
        /// The checked node with the largest excess |stored − reference| − allowed.
        worst: NodeCheck,
        /// Node values checked.
        count: usize,
    },
}

/// The recorded integration bound of `view` at `count` spread nodes (and the smallest-μ
/// column), against the independent finer rule ([`check_nodes`]).
pub fn check_recorded_bound(view: &LutView<'_>, count: usize) -> BoundCheck {
    let h = view.header();
    let Some(bound) = h.integration else {
        return BoundCheck::NotRecorded;
    };
    let Some(spec) = Spec::from_header(h) else {
        return BoundCheck::NoSpec;
    };
    let checks = check_nodes(&spec, view, bound as f64, count);
    let excess = |c: &NodeCheck| (c.stored - c.reference).abs() - c.allowed;
    let worst = checks
        .iter()
        .max_by(|a, b| excess(a).total_cmp(&excess(b)))
        .cloned();
    match worst {
        Some(worst) => BoundCheck::Checked {
            bound,
            worst,
            count: checks.len(),
        },
        None => BoundCheck::NoSpec,
    }
}

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

/// A table measured afresh ([`measure_table`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// Max and RMS |table − direct kernel| over the points and channels.
    pub stats: crate::ErrorStats,
    /// Each point's largest |error| over its channels, in point order.
    pub point_max: Vec<f64>,
}

/// The table measured at `n` random points (seeded by `seed`) with the spec its header
/// describes ([`super::measure`]'s points and errors); NaN statistics and errors when it
/// describes no table this generator builds (NaN fails every comparison).
pub fn measure_table(view: &LutView<'_>, n: u32, seed: u64) -> Measured {
    let h = view.header();
    match Spec::from_header(h) {
        Some(mut spec) => {
            (spec.samples, spec.seed) = (n, seed);
            let errs = super::measure::errors(&spec, view, &h.axes);
            let nc = spec.kind.def().channels.len().max(1);
            Measured {
                stats: super::measure::stats(&spec, &errs),
                point_max: errs
                    .chunks(nc)
                    .map(|c| c.iter().fold(0.0, |m: f64, &e| m.max(e)))
                    .collect(),
            }
        }
        None => Measured {
            stats: crate::ErrorStats {
                max_abs: f32::NAN,
                rms: f32::NAN,
                samples: n,
                seed,
            },
            point_max: vec![f64::NAN; n as usize],
        },
    }
}

/// The false-alarm rate of [`worse_than_recorded`] for a table that is as its header says.
pub const FALSE_ALARM: f64 = 1e-3;

/// How many of `fresh` points may lie above the maximum recorded over `recorded` points
/// before a table is judged worse than its header: the smallest K with
/// P(K or more above) ≤ [`FALSE_ALARM`]. If the recorded and fresh points are drawn alike
/// (exchangeable: the same uniform law over the same table, whatever the law of the
/// errors), K given fresh points exceed the largest of all recorded ones with probability
/// Π_{i<K} (M − i)/(N + M − i) (M fresh, N recorded: the K largest of the N + M errors fall
/// among the fresh). Heavy-tailed errors (a kink the grid does not resolve) move the
/// maximum of a sample a lot and this count not at all.
pub fn allowed_above(fresh: u32, recorded: u32) -> u32 {
    let (m, n) = (fresh as f64, recorded.max(1) as f64);
    let mut p = 1.0;
    for k in 0..fresh {
        p *= (m - k as f64) / (n + m - k as f64);
        if p <= FALSE_ALARM {
            return k;
        }
    }
    fresh
}

/// How a table is worse than its header's maximum ([`worse_than_recorded`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Worse {
    /// An error is not a number.
    NotANumber,
    /// At the header's own points (its seed, a prefix of its count) the largest error is
    /// above the recorded maximum (× (1 + tolerance) + 1e-6): the claim is false.
    OwnPoints {
        /// The largest error found there.
        max: f64,
    },
    /// More fresh points lie above it than would by chance ([`allowed_above`]).
    FreshPoints {
        /// Fresh points above.
        above: u32,
        /// Those a table as recorded may have.
        allowed: u32,
    },
}

/// Whether a table is worse than its header's maximum allows (limit: recorded ×
/// (1 + `tolerance`) + 1e-6). Two checks: `own`, the table measured at the header's own
/// points (its seed and the first of its count: the points of the claim, so a true claim
/// can never fail), must stay within the limit; `fresh`, measured at other points, may have
/// at most [`allowed_above`] points above it (whether the recorded sample is
/// representative, at a false-alarm rate of [`FALSE_ALARM`] whatever the errors' law).
pub fn worse_than_recorded(
    own: &Measured,
    fresh: &Measured,
    recorded: &crate::ErrorStats,
    tolerance: f64,
) -> Option<Worse> {
    let limit = recorded.max_abs as f64 * (1.0 + tolerance) + 1e-6;
    let all = || own.point_max.iter().chain(&fresh.point_max);
    if own.stats.max_abs.is_nan() || fresh.stats.max_abs.is_nan() || all().any(|e| e.is_nan()) {
        return Some(Worse::NotANumber);
    }
    let max = own.point_max.iter().fold(0.0, |m: f64, &e| m.max(e));
    if max > limit {
        return Some(Worse::OwnPoints { max });
    }
    let above = fresh.point_max.iter().filter(|&&e| e > limit).count() as u32;
    let allowed = allowed_above(fresh.point_max.len() as u32, recorded.samples);
    (above > allowed).then_some(Worse::FreshPoints { above, allowed })
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

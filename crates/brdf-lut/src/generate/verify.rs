//! `lut verify`'s check of a table's recorded integration error bound: a sample of nodes
//! recomputed by an independent, much finer rule ([`super::reference`]).

use super::integrate::reference;
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

//! The error measurement of a generated table: the interpolated table against the direct
//! f64 kernel at seeded random points.

use super::{par_chunks, Check, Spec};
use crate::write::ErrorAccumulator;
use crate::{Axis, ErrorStats, GTable, GTable3, LutView, Placement};
use brdf_core::masking::ModifiedG;
use rand::{Rng, SeedableRng};
use std::vec;
use std::vec::Vec;

/// The range random points are drawn from on one axis: [lo, hi] for endpoint nodes; between
/// the first and last node for texel-centre nodes (beyond them the reader clamps).
fn range(a: &Axis<'_>) -> (f64, f64) {
    match a.placement {
        Placement::Endpoint => (a.lo, a.hi),
        Placement::TexelCentre => {
            let (p, q) = (a.node(0), a.node(a.count.saturating_sub(1)));
            (p.min(q), p.max(q))
        }
    }
}

/// Uniform in [lo, hi]; a range rand cannot sample (empty, or a span that overflows) gives
/// its lower end instead of a panic (a parsed header's ranges are finite and increasing).
fn uniform(rng: &mut rand_pcg::Pcg64, lo: f64, hi: f64) -> f64 {
    if lo < hi && (hi - lo).is_finite() {
        rng.random_range(lo..=hi)
    } else {
        lo
    }
}

/// Random points that share one σ in a table over σ (the modified G's normaliser C(σ) is
/// then computed once per group instead of once per point).
pub const SIGMA_GROUP: usize = 64;

/// The random points: uniform on each axis's range; on a σ axis of a passing-factor table
/// ([`Check::ModifiedG`], axis 2) σ is drawn once per [`SIGMA_GROUP`] consecutive points,
/// so every point is still uniform on the box.
fn points(spec: &Spec, axes: &[Axis<'_>]) -> Vec<Vec<f64>> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(spec.seed);
    let ranges: Vec<(f64, f64)> = axes.iter().map(range).collect();
    let grouped = spec.kind.def().check == Check::ModifiedG;
    let mut sigma = f64::NAN;
    (0..spec.samples as usize)
        .map(|i| {
            let mut p = Vec::with_capacity(ranges.len());
            for (a, &(lo, hi)) in ranges.iter().enumerate() {
                if grouped && a == 2 {
                    if i % SIGMA_GROUP == 0 {
                        sigma = uniform(&mut rng, lo, hi);
                    }
                    p.push(sigma);
                } else {
                    p.push(uniform(&mut rng, lo, hi));
                }
            }
            p
        })
        .collect()
}

/// Max and RMS |table − direct kernel| over all channels at `spec.samples` random points
/// (seeded by `spec.seed`), uniform on each of `axes` (the table's header axes). Passing-factor
/// tables are measured on the modified G = min(GM, GS) they serve, at random (θi, θr[, σ])
/// ([`Check::ModifiedG`]), each group of 64 points (`SIGMA_GROUP`) with one direct
/// `ModifiedG` (the same f64 kernel, its σ-dependent normaliser computed once per group);
/// every other kind channel by channel at the f32 point the table sees.
pub fn measure(spec: &Spec, view: &LutView<'_>, axes: &[Axis<'_>]) -> ErrorStats {
    stats(spec, &errors(spec, view, axes))
}

/// The max and RMS of `errs` ([`errors`]) as recorded for `spec`'s points and seed.
pub(super) fn stats(spec: &Spec, errs: &[f64]) -> ErrorStats {
    let mut acc = ErrorAccumulator::default();
    for &x in errs {
        acc.add(x);
    }
    acc.finish(spec.samples, spec.seed)
}

/// |table − direct kernel| at [`measure`]'s points, channel by channel (point k's channels
/// at k·channels …).
pub(super) fn errors(spec: &Spec, view: &LutView<'_>, axes: &[Axis<'_>]) -> Vec<f64> {
    let pts = points(spec, axes);
    let nc = spec.kind.def().channels.len();
    let mut errs = vec![0.0; pts.len() * nc];
    match spec.kind.def().check {
        Check::Values => par_chunks(&mut errs, nc, &|k, e| {
            let x: Vec<f32> = pts[k].iter().map(|&v| v as f32).collect();
            // The direct kernel at the f32-rounded point the table sees.
            let xd: Vec<f64> = x.iter().map(|&v| v as f64).collect();
            let t = view.sample(&x);
            for ((e, d), &t) in e.iter_mut().zip(spec.value(&xd)).zip(t.iter()) {
                *e = (t as f64 - d).abs();
            }
        }),
        Check::ModifiedG => {
            let g2 = GTable::from_view(*view).ok().filter(|_| axes.len() == 2);
            let g3 = GTable3::from_view(*view).ok().filter(|_| axes.len() == 3);
            let sigma = spec.fixed_sigma();
            par_chunks(&mut errs, SIGMA_GROUP, &|k, e| {
                let first = &pts[k * SIGMA_GROUP];
                let s = sigma.unwrap_or_else(|| first.get(2).copied().unwrap_or(f64::NAN));
                let g = ModifiedG::<f64>::new(s).ok();
                for (j, e) in e.iter_mut().enumerate() {
                    let p = &pts[k * SIGMA_GROUP + j];
                    let direct = g.map_or(f64::NAN, |g| g.g(p[0], p[1]));
                    let t = match (&g2, &g3) {
                        (Some(t), _) => t.g(p[0] as f32, p[1] as f32) as f64,
                        (_, Some(t)) => t.g(p[0] as f32, p[1] as f32, s as f32) as f64,
                        _ => f64::NAN,
                    };
                    *e = (t - direct).abs();
                }
            })
        }
    }
    errs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{generate, Distribution, Kind, Masking};

    /// The grouped measurement equals the per-point one: on a per-σ table and on a table
    /// over σ, a `ModifiedG` built afresh at every point (as before the grouping) gives the
    /// same max and RMS over the same points; the points lie in the axes' ranges, and on
    /// the σ axis each group of [`SIGMA_GROUP`] shares its σ while successive groups differ.
    #[test]
    fn grouped_measurement_is_the_per_point_one() {
        for kind in [Kind::GPerSigma { sigma: 0.3 }, Kind::GOverSigma] {
            let mut spec = Spec::new(kind, Distribution::TorranceSparrow, Masking::Modified);
            for a in spec.axes.iter_mut() {
                a.count = 9;
            }
            spec.samples = 3 * SIGMA_GROUP as u32 + 5;
            let t = generate(&spec, &|_| {}).unwrap();
            let view = LutView::parse(&t.bytes).unwrap();
            let axes = &view.header().axes;
            let pts = points(&spec, axes);
            let mut acc = ErrorAccumulator::default();
            for (i, p) in pts.iter().enumerate() {
                for (x, a) in p.iter().zip(axes.iter()) {
                    assert!(*x >= a.lo && *x <= a.hi, "{x} outside [{}, {}]", a.lo, a.hi);
                }
                if axes.len() == 3 && i % SIGMA_GROUP != 0 {
                    assert_eq!(p[2], pts[i - 1][2]);
                } else if axes.len() == 3 && i > 0 {
                    assert_ne!(p[2], pts[i - 1][2]);
                }
                let s = spec
                    .fixed_sigma()
                    .unwrap_or(p.get(2).copied().unwrap_or(f64::NAN));
                let direct = ModifiedG::<f64>::new(s).unwrap().g(p[0], p[1]);
                let table = if axes.len() == 2 {
                    GTable::from_view(view).unwrap().g(p[0] as f32, p[1] as f32)
                } else {
                    GTable3::from_view(view)
                        .unwrap()
                        .g(p[0] as f32, p[1] as f32, s as f32)
                };
                acc.add((table as f64 - direct).abs());
            }
            let want = acc.finish(spec.samples, spec.seed);
            let got = measure(&spec, &view, axes);
            assert_eq!(got, want, "{kind:?}");
            assert!(got.max_abs > 0.0);
        }
    }
}

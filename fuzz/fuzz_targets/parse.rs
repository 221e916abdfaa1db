//! Fuzzes the LUT parser and every typed table on whatever parses. The harness re-signs each
//! input (recomputes the CRC-32 over the mutated bytes) so that mutations reach validation
//! and the lookups instead of stopping at the checksum, and asserts the readers'
//! invariants (docs/fuzzing.md lists them):
//!
//! * no panic, at in-range, out-of-range, huge (±f32::MAX, 1e30), infinite, subnormal and
//!   NaN coordinates;
//! * G in [0, 1] for non-NaN input and NaN only for NaN input; finite values of every other
//!   table for non-NaN input (node values are bounded at parse);
//! * every typed lookup (`DfgTable::ab`, `AlbedoTable::e`, `AverageAlbedoTable::e_avg`,
//!   `GTable::terms`, `GTable3::terms`) equal, bit for bit, to `LutView::sample` at the
//!   same coordinates (G tables after their documented angle and [0, 1] clamps), as
//!   view.rs promises; its one documented exception, `GTable3` on a linear u16 table with a
//!   log-warped σ axis, within a bound derived from the inline logarithm's error;
//! * every batch lookup equal, bit for bit, to its scalar lookup (the chunked SIMD paths
//!   included); G from dot products in [0, 1] or NaN;
//! * `LutView::node_value` at any flat index and channel (up to `usize::MAX`): a finite
//!   value inside the table, NaN outside;
//! * a table rebuilt from its layout (`with_layout`) answering like the parsed one; every
//!   typed table's own constructor (`parse`) accepting exactly what `LutView::parse` +
//!   `from_view` accepts and answering bit for bit like it;
//! * the header's error statistics finite, >= 0 and RMS <= max (the claim rule); and the
//!   tool limits' checks (`brdf_lut::limits`) total on whatever grid a header states.
//!
//! Runs: `bash .ci/fuzz.sh` (the CI smoke run, 60 s) and `FUZZ_SECONDS=600 bash
//! .ci/fuzz.sh` (the documented long run, docs/fuzzing.md).
#![no_main]

use brdf_lut::{
    header_len, limits, AlbedoTable, AverageAlbedoTable, Crc32, DfgTable, GTable, GTable3, LutView,
};
use libfuzzer_sys::fuzz_target;

/// Query coordinates: inside and outside every shipped range, and the extremes (huge,
/// infinite, subnormal, signed zero). No NaN: the NaN cases are added where they are meant.
const PTS: [f32; 16] = [
    -1.0,
    0.0,
    -0.0,
    0.017,
    0.3,
    0.7853982,
    1.0,
    1.5707964,
    2.0,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    -f32::MAX,
    1e30,
    1e-45,
    -1e-30,
];
const P: usize = PTS.len();
/// Batch length: every point against every point, plus a NaN at both ends.
const B: usize = P * P + 2;

/// Batch inputs: every point against every point (so the chunked paths run full chunks and
/// a tail), NaN at both ends.
fn grid() -> ([f32; B], [f32; B]) {
    let (mut a, mut b) = ([f32::NAN; B], [f32::NAN; B]);
    for k in 0..P * P {
        a[k + 1] = PTS[k % P];
        b[k + 1] = PTS[k / P];
    }
    (a, b)
}

fn same_bits(batch: &[f32], scalar: impl Fn(usize) -> f32, what: &str) {
    for (k, &x) in batch.iter().enumerate() {
        let y = scalar(k);
        assert!(
            x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
            "{what}[{k}]: batch {x} vs scalar {y}"
        );
    }
}

fn unit_or_nan(g: f32, nan_in: bool) {
    if nan_in {
        assert!(g.is_nan(), "NaN input must give NaN, got {g}");
    } else {
        assert!((0.0..=1.0).contains(&g), "G = {g} outside [0, 1]");
    }
}

/// The typed constructors: `T::parse(bytes)` succeeds exactly when `T::from_view` of the
/// parsed view does, and both answer the same, bit for bit.
fn constructors(data: &[u8], v: LutView<'_>) {
    let agree = |a: bool, b: bool, what: &str| assert_eq!(a, b, "{what}: parse vs from_view");
    let g = GTable::parse(data);
    agree(g.is_ok(), GTable::from_view(v).is_ok(), "GTable");
    if let (Ok(a), Ok(b)) = (g, GTable::from_view(v)) {
        same_bits(&[a.g(0.4, -0.3)], |_| b.g(0.4, -0.3), "GTable::parse");
    }
    let g3 = GTable3::parse(data);
    agree(g3.is_ok(), GTable3::from_view(v).is_ok(), "GTable3");
    if let (Ok(a), Ok(b)) = (g3, GTable3::from_view(v)) {
        same_bits(
            &[a.g(0.4, 0.3, 0.2)],
            |_| b.g(0.4, 0.3, 0.2),
            "GTable3::parse",
        );
    }
    let d = DfgTable::parse(data);
    agree(d.is_ok(), DfgTable::from_view(v).is_ok(), "DfgTable");
    if let (Ok(a), Ok(b)) = (d, DfgTable::from_view(v)) {
        let (x, y) = (a.ab(0.5, 0.5), b.ab(0.5, 0.5));
        same_bits(
            &[x.0, x.1],
            |k| if k == 0 { y.0 } else { y.1 },
            "DfgTable::parse",
        );
        let r = DfgTable::with_layout(data, a.layout()).expect("own layout");
        same_bits(
            &[r.ab(0.3, 0.7).0],
            |_| a.ab(0.3, 0.7).0,
            "DfgTable::with_layout",
        );
    }
    let e = AlbedoTable::parse(data);
    agree(e.is_ok(), AlbedoTable::from_view(v).is_ok(), "AlbedoTable");
    if let (Ok(a), Ok(b)) = (e, AlbedoTable::from_view(v)) {
        same_bits(&[a.e(0.5, 0.5)], |_| b.e(0.5, 0.5), "AlbedoTable::parse");
        let r = AlbedoTable::with_layout(data, a.layout()).expect("own layout");
        same_bits(
            &[r.e(0.3, 0.7)],
            |_| a.e(0.3, 0.7),
            "AlbedoTable::with_layout",
        );
    }
    let ea = AverageAlbedoTable::parse(data);
    agree(
        ea.is_ok(),
        AverageAlbedoTable::from_view(v).is_ok(),
        "AverageAlbedoTable",
    );
    if let (Ok(a), Ok(b)) = (ea, AverageAlbedoTable::from_view(v)) {
        same_bits(
            &[a.e_avg(0.5)],
            |_| b.e_avg(0.5),
            "AverageAlbedoTable::parse",
        );
        let r = AverageAlbedoTable::with_layout(data, a.layout()).expect("own layout");
        same_bits(
            &[r.e_avg(0.3)],
            |_| a.e_avg(0.3),
            "AverageAlbedoTable::with_layout",
        );
    }
}

/// The claim rule and the tool limits on a parsed header.
fn header_rules(v: &LutView<'_>) {
    let h = v.header();
    let e = h.error;
    assert!(
        e.max_abs.is_finite() && e.max_abs >= 0.0,
        "max_abs {}",
        e.max_abs
    );
    assert!(
        e.rms.is_finite() && e.rms >= 0.0 && e.rms <= e.max_abs,
        "rms {}",
        e.rms
    );
    let counts: [u64; 3] = core::array::from_fn(|k| h.axes.get(k).map_or(2, |a| a.count as u64));
    let nodes = limits::check_grid(&counts[..h.axes.len()], h.channels.len() as u64);
    if let Ok(n) = nodes {
        assert!(n <= limits::MAX_BUILD_VALUES);
        let _ = limits::check_generate(h.kind, h.generator.model, n, e.samples as u64);
    }
    let cap = limits::max_verify_points(h.kind, h.generator.model);
    assert!((1..=limits::MAX_SAMPLES).contains(&cap));
}

/// Equal bits, or both NaN (a NaN's payload is not part of the lookups' contract).
fn same(x: f32, y: f32) -> bool {
    x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
}

/// The G tables' angle clamp (θi to [0, π/2], θr to [−π/2, π/2]), in the readers' order of
/// comparisons: (lo > x ? lo : x), then (hi < y ? hi : y).
fn clamp_angle(x: f32, lo: f32, hi: f32) -> f32 {
    let y = if lo > x { lo } else { x };
    if hi < y {
        hi
    } else {
        y
    }
}

/// (GM, GS, G) from the view, as the typed G tables document it: the angles clamped, then
/// the passing-factor table F read at GM = F(|θr|, sgn θr · θi) and GS = F(θi, θr)
/// (docs/conventions.md §4), each clamped to [0, 1], G = min (GS if GS < GM).
fn g_from_view(v: &LutView<'_>, ti: f32, tr: f32, sigma: Option<f32>) -> [f32; 3] {
    use core::f32::consts::FRAC_PI_2;
    if ti.is_nan() || tr.is_nan() || sigma.is_some_and(f32::is_nan) {
        return [f32::NAN; 3];
    }
    let (ti, tr) = (
        clamp_angle(ti, 0.0, FRAC_PI_2),
        clamp_angle(tr, -FRAC_PI_2, FRAC_PI_2),
    );
    let s = if tr < 0.0 { -ti } else { ti };
    let at = |x: f32, y: f32| {
        let f = match sigma {
            Some(z) => v.sample3(x, y, z)[0],
            None => v.sample2(x, y)[0],
        };
        clamp_angle(f, 0.0, 1.0)
    };
    let (gm, gs) = (at(tr.abs(), s), at(ti, tr));
    [gm, gs, if gs < gm { gs } else { gm }]
}

/// Largest |node value| of channel 0 (the G tables have one channel).
fn max_node(v: &LutView<'_>) -> f32 {
    let nodes = v.payload().len() / (v.header().encoding.bytes() * v.channels());
    (0..nodes).fold(0.0f32, |m, k| m.max(v.node_value(k, 0).abs()))
}

/// How far `GTable3` may be from the view on a linear u16 table with a log-warped σ axis
/// (the documented exception, view.rs `LutView::sample`): its inline ln σ is within
/// δ = 1.5e-7 + 2.5e-7·|ln σ| of libm's (lookup/mod.rs, `ln_fast`), so σ's node coordinate
/// t = a·ln σ + b moves by at most a·δ, with a ≤ n / ln(hi/lo) (n nodes over the f32 range
/// ends; 1e-3 relative slack for a's own f32 rounding). Linear interpolation in t is
/// Lipschitz with constant max |node difference| ≤ 2·max |node|, the [0, 1] clamps and the
/// minimum do not increase a difference, and f32 rounding of the blend adds at most
/// 16 ulp of max |node|. `None` when the table has no such exception.
fn g3_slack(v: &LutView<'_>) -> Option<f32> {
    let h = v.header();
    let z = h.axes.get(2)?;
    let exception = z.warp == brdf_lut::Warp::Log
        && h.encoding == brdf_lut::Encoding::Unorm16
        && h.interpolation == brdf_lut::Interpolation::Linear;
    if !exception {
        return None;
    }
    let (lo, hi) = ((z.lo as f32) as f64, (z.hi as f32) as f64);
    let a = z.count as f64 / (hi / lo).ln() * 1.001;
    let delta = 1.5e-7 + 2.5e-7 * lo.ln().abs().max(hi.ln().abs());
    let m = max_node(v) as f64;
    Some((a * delta * 2.0 * m + 16.0 * f32::EPSILON as f64 * m).min(1.0) as f32)
}

/// The promise of view.rs: every typed lookup equals [`LutView::sample`] bit for bit (G
/// tables after the documented angle and [0, 1] clamps), at in-range, out-of-range, huge,
/// infinite and NaN coordinates; one exception, `GTable3` on a linear u16 table with a
/// log-warped σ axis, within [`g3_slack`].
fn view_agrees(v: &LutView<'_>) {
    let mut pts = [f32::NAN; P + 1];
    pts[..P].copy_from_slice(&PTS);
    if let Ok(t) = DfgTable::from_view(*v) {
        for &x in &pts {
            for &y in &pts {
                let ((a, b), s) = (t.ab(x, y), v.sample2(x, y));
                assert!(same(a, s[0]) && same(b, s[1]), "DfgTable::ab({x}, {y}) vs view");
            }
        }
    }
    if let Ok(t) = AlbedoTable::from_view(*v) {
        for &x in &pts {
            for &y in &pts {
                let (e, s) = (t.e(x, y), v.sample2(x, y)[0]);
                assert!(same(e, s), "AlbedoTable::e({x}, {y}) = {e} vs view {s}");
            }
        }
    }
    if let Ok(t) = AverageAlbedoTable::from_view(*v) {
        for &x in &pts {
            let (e, s) = (t.e_avg(x), v.sample1(x)[0]);
            assert!(same(e, s), "AverageAlbedoTable::e_avg({x}) = {e} vs view {s}");
        }
    }
    if let Ok(t) = GTable::from_view(*v) {
        for &x in &pts {
            for &y in &pts {
                let (g, w) = (t.terms(x, y), g_from_view(v, x, y, None));
                let ok = same(g.0, w[0]) && same(g.1, w[1]) && same(g.2, w[2]);
                assert!(ok, "GTable::terms({x}, {y}) = {g:?} vs view {w:?}");
            }
        }
    }
    if let Ok(t) = GTable3::from_view(*v) {
        let slack = g3_slack(v);
        for &x in &pts {
            for &y in &pts {
                for &z in &[0.3, 1e-3, 0.0, f32::MAX, f32::NEG_INFINITY, f32::NAN] {
                    let (g, w) = (t.terms(x, y, z), g_from_view(v, x, y, Some(z)));
                    let close = |a: f32, b: f32| match slack {
                        None => same(a, b),
                        Some(e) => same(a, b) || (a - b).abs() <= e,
                    };
                    let ok = close(g.0, w[0]) && close(g.1, w[1]) && close(g.2, w[2]);
                    assert!(ok, "GTable3::terms({x}, {y}, {z}) = {g:?} vs view {w:?}");
                }
            }
        }
    }
}

/// `node_value` at any flat index and channel: a finite value inside the table (values
/// are bounded at parse), NaN outside it, including indices whose byte offset overflows.
fn node_values(v: &LutView<'_>) {
    let nodes = v.payload().len() / (v.header().encoding.bytes() * v.channels());
    let flats = [
        0,
        nodes / 2,
        nodes - 1,
        nodes,
        nodes + 1,
        (usize::MAX / 4).wrapping_add(2),
        usize::MAX / 2,
        usize::MAX - 1,
        usize::MAX,
    ];
    for &k in &flats {
        for ch in [0, 1, 2, 3, 4, usize::MAX] {
            let x = v.node_value(k, ch);
            if k < nodes && ch < v.channels() {
                assert!(x.is_finite(), "node_value({k}, {ch}) = {x}");
            } else {
                assert!(x.is_nan(), "node_value({k}, {ch}) = {x} outside the table");
            }
        }
    }
}

fn check(data: &[u8]) {
    let Ok(v) = LutView::parse(data) else {
        for r in [
            GTable::parse(data).is_ok(),
            GTable3::parse(data).is_ok(),
            DfgTable::parse(data).is_ok(),
            AlbedoTable::parse(data).is_ok(),
            AverageAlbedoTable::parse(data).is_ok(),
        ] {
            assert!(!r, "a typed table parsed bytes LutView::parse refuses");
        }
        return;
    };
    header_rules(&v);
    constructors(data, v);
    view_agrees(&v);
    node_values(&v);
    for &x in &PTS {
        for &y in &PTS {
            for s in v.sample(&[x, y, x]).iter().take(v.channels()) {
                assert!(s.is_finite(), "sample({x}, {y}) = {s}");
            }
        }
        assert!(v.sample1(f32::NAN)[0].is_nan());
    }
    g_table(data, v);
    g_table3(data, v);
    dfg_table(v);
    albedo_table(v);
    average_albedo_table(v);
}

/// The 2-D passing-factor table: G ∈ [0, 1] or NaN, batch == scalar bits, `g_dots` in
/// range, and its own layout re-reads it.
fn g_table(data: &[u8], v: LutView<'_>) {
    if let Ok(t) = GTable::from_view(v) {
        for &a in &PTS {
            for &b in &PTS {
                unit_or_nan(t.g(a, -b), false);
                unit_or_nan(t.g(a, b), false);
            }
        }
        unit_or_nan(t.g(f32::NAN, 0.3), true);
        unit_or_nan(t.g(0.3, f32::NAN), true);
        let (a, b) = grid();
        let mut out = [0.0f32; B];
        assert_eq!(t.g_batch(&a, &b, &mut out), B);
        same_bits(&out, |k| t.g(a[k], b[k]), "GTable::g_batch");
        for &(x, y) in &[(0.9f32, 0.5f32), (0.0, 0.0), (1e-30, 1.0)] {
            for &z in &[-1.0f32, 0.0, 0.5, 1.0] {
                let g = t.g_dots(x, y, z);
                assert!(g.is_nan() || (0.0..=1.0).contains(&g), "g_dots = {g}");
            }
        }
        let r = GTable::with_layout(data, t.layout()).expect("own layout");
        same_bits(&[r.g(0.3, -0.2)], |_| t.g(0.3, -0.2), "GTable::with_layout");
    }
}

/// The passing-factor table over σ: as for [`g_table`], with σ NaN and out of range.
fn g_table3(data: &[u8], v: LutView<'_>) {
    if let Ok(t) = GTable3::from_view(v) {
        for &a in &PTS {
            for &b in &PTS {
                unit_or_nan(t.g(a, -b, a), false);
                unit_or_nan(t.g(a, b, b), false);
            }
        }
        unit_or_nan(t.g(0.3, 0.2, f32::NAN), true);
        let (a, b) = grid();
        let mut out = [0.0f32; B];
        for &s in &[0.3f32, 1e-3, 2.0, f32::NAN] {
            assert_eq!(t.g_batch(&a, &b, s, &mut out), B);
            same_bits(&out, |k| t.g(a[k], b[k], s), "GTable3::g_batch");
        }
        let g = t.g_dots(0.5, 0.6, 0.1, 0.3);
        assert!(g.is_nan() || (0.0..=1.0).contains(&g), "g_dots = {g}");
        let r = GTable3::with_layout(data, t.layout()).expect("own layout");
        same_bits(
            &[r.g(0.3, -0.2, 0.3)],
            |_| t.g(0.3, -0.2, 0.3),
            "GTable3::with_layout",
        );
    }
}

/// The split-sum table: finite (A, B), NaN in NaN out, batch == scalar bits.
fn dfg_table(v: LutView<'_>) {
    if let Ok(t) = DfgTable::from_view(v) {
        for &a in &PTS {
            let (x, y) = t.ab(a, a);
            assert!(x.is_finite() && y.is_finite());
        }
        assert!(t.ab(f32::NAN, 0.5).0.is_nan());
        let (m, r) = grid();
        let (mut a, mut b) = ([0.0f32; B], [0.0f32; B]);
        assert_eq!(t.ab_batch(&m, &r, &mut a, &mut b), B);
        same_bits(&a, |k| t.ab(m[k], r[k]).0, "DfgTable::ab_batch A");
        same_bits(&b, |k| t.ab(m[k], r[k]).1, "DfgTable::ab_batch B");
    }
}

/// The directional-albedo table: finite E, batch == scalar bits.
fn albedo_table(v: LutView<'_>) {
    if let Ok(t) = AlbedoTable::from_view(v) {
        for &a in &PTS {
            assert!(t.e(a, 1.0 - a).is_finite());
        }
        let (m, r) = grid();
        let mut out = [0.0f32; B];
        assert_eq!(t.e_batch(&m, &r, &mut out), B);
        same_bits(&out, |k| t.e(m[k], r[k]), "AlbedoTable::e_batch");
    }
}

/// The average-albedo table: finite E_avg, batch == scalar bits.
fn average_albedo_table(v: LutView<'_>) {
    if let Ok(t) = AverageAlbedoTable::from_view(v) {
        for &a in &PTS {
            assert!(t.e_avg(a).is_finite());
        }
        let (r, _) = grid();
        let mut out = [0.0f32; B];
        assert_eq!(t.e_avg_batch(&r, &mut out), B);
        same_bits(&out, |k| t.e_avg(r[k]), "AverageAlbedoTable::e_avg_batch");
    }
}

fuzz_target!(|data: &[u8]| {
    // As given (exercises the CRC check itself) …
    check(data);
    // … and re-signed, so that every other check and the lookups see the mutation.
    if let Ok(hl) = header_len(data) {
        if hl >= 8 && hl <= data.len() {
            let mut d = data.to_vec();
            let crc = Crc32::new().update(&d[..hl - 4]).update(&d[hl..]).finish();
            d[hl - 4..hl].copy_from_slice(&crc.to_le_bytes());
            check(&d);
        }
    }
});

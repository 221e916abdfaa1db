//! Fuzzes the LUT parser and every typed table on whatever parses. The harness re-signs each
//! input (recomputes the CRC-32 over the mutated bytes) so that mutations reach validation
//! and the lookups instead of stopping at the checksum, and asserts the readers'
//! invariants: no panic; G in [0, 1] for non-NaN input and NaN only for NaN input; finite
//! values of every other table for finite input (node values are bounded at parse); every
//! batch lookup equal, bit for bit, to its scalar lookup (the chunked SIMD paths included);
//! G from dot products in [0, 1] or NaN; a table rebuilt from its layout (`with_layout`)
//! answering like the parsed one; every typed table's own constructor (`parse`) accepting
//! exactly what `LutView::parse` + `from_view` accepts and answering bit for bit like it;
//! the header's error statistics finite, >= 0 and RMS <= max (the claim rule); and the
//! tool limits' checks (`brdf_lut::limits`) total on whatever grid a header states.
//!
//! Runs: `cd fuzz && cargo +nightly fuzz run parse -- -max_total_time=60` (the CI smoke
//! run) and `-max_total_time=600` or longer (the documented long run, docs/lut-format.md).
#![no_main]

use brdf_lut::{
    header_len, limits, AlbedoTable, AverageAlbedoTable, Crc32, DfgTable, GTable, GTable3, LutView,
};
use libfuzzer_sys::fuzz_target;

const PTS: [f32; 9] = [
    -1.0,
    0.0,
    0.017,
    0.3,
    0.7853982,
    1.0,
    1.5707964,
    2.0,
    f32::INFINITY,
];

/// Batch inputs: every point against every point (81 entries, so the chunked paths run full
/// chunks and a tail), NaN at both ends.
fn grid() -> ([f32; 83], [f32; 83]) {
    let (mut a, mut b) = ([f32::NAN; 83], [f32::NAN; 83]);
    for k in 0..81 {
        a[k + 1] = PTS[k % 9];
        b[k + 1] = PTS[k / 9];
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
    for &x in &PTS {
        for &y in &PTS {
            for s in v.sample(&[x, y, x]).iter().take(v.channels()) {
                assert!(s.is_finite(), "sample({x}, {y}) = {s}");
            }
        }
        assert!(v.sample1(f32::NAN)[0].is_nan());
    }
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
        let mut out = [0.0f32; 83];
        assert_eq!(t.g_batch(&a, &b, &mut out), 83);
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
    if let Ok(t) = GTable3::from_view(v) {
        for &a in &PTS {
            for &b in &PTS {
                unit_or_nan(t.g(a, -b, a), false);
                unit_or_nan(t.g(a, b, b), false);
            }
        }
        unit_or_nan(t.g(0.3, 0.2, f32::NAN), true);
        let (a, b) = grid();
        let mut out = [0.0f32; 83];
        for &s in &[0.3f32, 1e-3, 2.0, f32::NAN] {
            assert_eq!(t.g_batch(&a, &b, s, &mut out), 83);
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
    if let Ok(t) = DfgTable::from_view(v) {
        for &a in &PTS {
            let (x, y) = t.ab(a, a);
            assert!(x.is_finite() && y.is_finite());
        }
        assert!(t.ab(f32::NAN, 0.5).0.is_nan());
        let (m, r) = grid();
        let (mut a, mut b) = ([0.0f32; 83], [0.0f32; 83]);
        assert_eq!(t.ab_batch(&m, &r, &mut a, &mut b), 83);
        same_bits(&a, |k| t.ab(m[k], r[k]).0, "DfgTable::ab_batch A");
        same_bits(&b, |k| t.ab(m[k], r[k]).1, "DfgTable::ab_batch B");
    }
    if let Ok(t) = AlbedoTable::from_view(v) {
        for &a in &PTS {
            assert!(t.e(a, 1.0 - a).is_finite());
        }
        let (m, r) = grid();
        let mut out = [0.0f32; 83];
        assert_eq!(t.e_batch(&m, &r, &mut out), 83);
        same_bits(&out, |k| t.e(m[k], r[k]), "AlbedoTable::e_batch");
    }
    if let Ok(t) = AverageAlbedoTable::from_view(v) {
        for &a in &PTS {
            assert!(t.e_avg(a).is_finite());
        }
        let (r, _) = grid();
        let mut out = [0.0f32; 83];
        assert_eq!(t.e_avg_batch(&r, &mut out), 83);
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

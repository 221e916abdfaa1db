//! Fuzzes the LUT parser and every typed table on whatever parses. The harness re-signs each
//! input (recomputes the CRC-32 over the mutated bytes) so that mutations reach validation
//! and the lookups instead of stopping at the checksum, and asserts the readers'
//! invariants: no panic; G in [0, 1] for non-NaN input and NaN only for NaN input; finite
//! values of every other table for finite input (node values are bounded at parse).
#![no_main]

use brdf_lut::{
    header_len, AlbedoTable, AverageAlbedoTable, Crc32, DfgTable, GTable, GTable3, LutView,
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

fn unit_or_nan(g: f32, nan_in: bool) {
    if nan_in {
        assert!(g.is_nan(), "NaN input must give NaN, got {g}");
    } else {
        assert!((0.0..=1.0).contains(&g), "G = {g} outside [0, 1]");
    }
}

fn check(data: &[u8]) {
    let Ok(v) = LutView::parse(data) else {
        return;
    };
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
    }
    if let Ok(t) = GTable3::from_view(v) {
        for &a in &PTS {
            for &b in &PTS {
                unit_or_nan(t.g(a, -b, a), false);
                unit_or_nan(t.g(a, b, b), false);
            }
        }
        unit_or_nan(t.g(0.3, 0.2, f32::NAN), true);
    }
    if let Ok(t) = DfgTable::from_view(v) {
        for &a in &PTS {
            let (x, y) = t.ab(a, a);
            assert!(x.is_finite() && y.is_finite());
        }
        assert!(t.ab(f32::NAN, 0.5).0.is_nan());
    }
    if let Ok(t) = AlbedoTable::from_view(v) {
        for &a in &PTS {
            assert!(t.e(a, 1.0 - a).is_finite());
        }
    }
    if let Ok(t) = AverageAlbedoTable::from_view(v) {
        for &a in &PTS {
            assert!(t.e_avg(a).is_finite());
        }
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

//! Fuzzes the LUT parser and every lookup on whatever parses: no input may panic.
#![no_main]

use brdf_core::lut::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, LutView};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(v) = LutView::parse(data) else {
        return;
    };
    let pts = [-1.0f32, 0.0, 0.3, 1.0, 2.0, f32::NAN, f32::INFINITY];
    for &x in &pts {
        for &y in &pts {
            let _ = v.sample(&[x, y, x]);
            let _ = v.sample1(x);
        }
    }
    if let Ok(t) = GTable::from_view(v.clone()) {
        let _ = t.g(0.3, -0.2);
    }
    if let Ok(t) = GTable3::from_view(v.clone()) {
        let _ = t.g(0.3, -0.2, 0.5);
    }
    if let Ok(t) = DfgTable::from_view(v.clone()) {
        let _ = t.ab(0.5, 0.5);
    }
    if let Ok(t) = AlbedoTable::from_view(v.clone()) {
        let _ = t.e(0.5, 0.5);
    }
    if let Ok(t) = AverageAlbedoTable::from_view(v) {
        let _ = t.e_avg(0.5);
    }
});

//! The fixed-layout prototype reader must give the library reader's G (same table, same
//! interpolant), up to f32 summation order; otherwise its timing would not be a fair
//! comparison. Skipped with a message when the default assets are absent.

use brdf_bench::fast_lut::FastPassing;
use brdf_bench::{angle_pairs, read_asset, G2_ASSET, G3_ASSET};
use brdf_core::lut::{GTable, GTable3};

#[test]
fn fixed_layout_reader_matches_the_library_reader() {
    let (ti, tr) = angle_pairs::<f32>(5000);
    let mut ran = false;
    if let Some(b) = read_asset(G3_ASSET) {
        let t = GTable3::parse(&b).unwrap();
        let f = FastPassing::new(t.view()).expect("u16 one-channel table");
        for sigma in [0.05f32, 0.13, 0.3, 0.77, 1.0] {
            for (&a, &r) in ti.iter().zip(&tr) {
                let (x, y) = (t.g(a, r, sigma), f.g(a, r, sigma));
                assert!(
                    (x - y).abs() <= 2e-6,
                    "3-D σ={sigma} ({a}, {r}): {x} vs {y}"
                );
            }
        }
        ran = true;
    }
    if let Some(b) = read_asset(G2_ASSET) {
        let t = GTable::parse(&b).unwrap();
        let f = FastPassing::new(t.view()).expect("u16 one-channel table");
        for (&a, &r) in ti.iter().zip(&tr) {
            let (x, y) = (t.g(a, r), f.g(a, r, 0.0));
            assert!((x - y).abs() <= 2e-6, "2-D ({a}, {r}): {x} vs {y}");
        }
        ran = true;
    }
    if !ran {
        eprintln!("assets missing: run `cargo xtask lut` first; test skipped");
    }
}

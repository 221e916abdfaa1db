//! The texels come from the one generator and agree with brdf-core's independent converged
//! split-sum integrator at each texel centre; bad sizes are refused before any work. The layouts themselves are checked
//! end to end, file by file with independent decoders, in `tests/engine_files.rs`.

use brdf_core::split_sum::converged::dfg_ggx_converged;
use brdf_engine_assets::{split_sum_texels, Engine, Error, MAX_SIZE};

/// Every texel of an 8² table is within the generator's tolerance (2e-6 per channel) plus
/// the reference's own estimate of the adaptive visible-normal integrator at 1e-9.
#[test]
fn texels_are_the_kernel_at_texel_centres() {
    let n = 8;
    let t = split_sum_texels(n, &|_| {}).unwrap();
    assert_eq!((t.a.len(), t.b.len()), (n * n, n * n));
    for row in 0..n {
        for col in 0..n {
            let c = |i: usize| (i as f64 + 0.5) / n as f64;
            let want = dfg_ggx_converged(c(col), c(row), 1e-9);
            let i = row * n + col;
            for (k, v) in [t.a[i], t.b[i]].into_iter().enumerate() {
                let d = (v - want.value[k]).abs();
                let tol = brdf_lut::generate::INTEGRATION_TOL + want.error[k];
                assert!(d <= tol, "texel (col {col}, row {row}) channel {k}: {d:e}");
            }
        }
    }
}

#[test]
fn bad_sizes_are_refused() {
    for n in [0, 1, MAX_SIZE + 1, usize::MAX] {
        let e = split_sum_texels(n, &|_| panic!("no work for a refused size")).unwrap_err();
        assert!(matches!(e, Error::Size(m) if m == n), "{n}: {e}");
    }
}

/// Every engine's files carry its sidecar and both samplers, named after its stem.
#[test]
fn every_layout_has_sidecar_and_samplers() {
    let t = split_sum_texels(2, &|_| {}).unwrap();
    for e in Engine::ALL {
        let files = e.files(&t).unwrap();
        let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
        for ext in [".json", ".glsl", ".wgsl"] {
            assert_eq!(
                names.iter().filter(|n| n.ends_with(ext)).count(),
                1,
                "{}: {names:?}",
                e.name()
            );
        }
        let json = files.iter().find(|f| f.name.ends_with(".json")).unwrap();
        let v: serde_json::Value = serde_json::from_slice(&json.bytes).unwrap();
        assert_eq!(v["target"], e.name());
        assert_eq!(v["size"], serde_json::json!([2, 2]));
    }
}

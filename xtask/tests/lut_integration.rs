//! The integration error bound end to end: `lut inspect` prints it, `lut verify` fails
//! (exit 1, naming the node) on a crafted file whose bound is too small for its values and
//! passes the file as generated, and `lut generate` writes the same bytes on one worker
//! thread as on two (`RAYON_NUM_THREADS`).

use brdf_lut::LutView;
use std::path::Path;
use std::process::{Command, Output, Stdio};

mod common;
use common::{fails_with, stderr as err, stdout as out};

/// `xtask lut generate args` in `cwd` with `RAYON_NUM_THREADS=threads`.
fn generate_on(threads: &str, args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args([&["lut", "generate"], args].concat())
        .env("RAYON_NUM_THREADS", threads)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .output()
        .expect("xtask runs")
}

const GGX: [&str; 12] = [
    "--kind",
    "split-sum",
    "--model",
    "ggx",
    "--res",
    "9x7",
    "--encoding",
    "f32",
    "--samples",
    "50",
    "--out",
    "t.blut",
];

/// One, two or three workers: identical files, for the converged polar rule (GGX split sum,
/// Beckmann albedo) and for the fixed rule of a V-cavity Torrance–Sparrow albedo table
/// (grids that do not split evenly between the workers).
#[test]
fn one_thread_and_two_write_the_same_bytes() {
    // An albedo table of the model given, on a 5 × 3 grid from 50 points.
    let albedo = |model: &[&'static str]| {
        [
            &["--kind", "e"],
            model,
            &["--res", "5x3", "--samples", "50", "--out", "t.blut"],
        ]
        .concat()
    };
    let beckmann = albedo(&["--model", "beckmann"]);
    let v_cavity = albedo(&["--model", "torrance-sparrow", "--masking", "v-cavity"]);
    for args in [&GGX[..], &beckmann[..], &v_cavity[..]] {
        let bytes: Vec<Vec<u8>> = ["1", "2", "3"]
            .iter()
            .map(|t| {
                let d = tempfile::tempdir().unwrap();
                let o = generate_on(t, args, d.path());
                assert!(o.status.success(), "{}", err(&o));
                std::fs::read(d.path().join("t.blut")).unwrap()
            })
            .collect();
        assert!(
            bytes[1..].iter().all(|b| *b == bytes[0]),
            "{args:?}: the files differ"
        );
    }
}

/// A crafted file: node 0 (smallest μ, always checked) moved by 5e-5, the generator's
/// bound (≤ 2e-6) kept. `lut verify` exits 1 naming node 0; the generated file passes; and
/// `lut inspect` prints the recorded bound.
#[test]
fn verify_fails_a_bound_too_small_and_names_the_node() {
    let d = tempfile::tempdir().unwrap();
    let o = generate_on("2", &GGX, d.path());
    assert!(o.status.success(), "{}", err(&o));
    let good = std::fs::read(d.path().join("t.blut")).unwrap();
    let v = LutView::parse(&good).unwrap();
    let bound = v.header().integration.unwrap();
    assert!(bound > 0.0 && bound <= 2e-6, "{bound}");
    let mut payload = v.payload().to_vec();
    let a = f32::from_le_bytes(payload[..4].try_into().unwrap()) + 5e-5;
    payload[..4].copy_from_slice(&a.to_le_bytes());
    let mut bad = vec![0u8; good.len() + 64];
    let n = brdf_lut::encode_into(v.header(), &payload, &mut bad).unwrap();
    std::fs::write(d.path().join("bad.blut"), &bad[..n]).unwrap();
    // The interpolation check is not under test (a 9 × 7 table's maximum over fresh points
    // may exceed the one recorded from 50): a wide --tolerance leaves the node check alone.
    let args = |f| ["lut", "verify", f, "--samples", "50", "--tolerance", "100"];
    let o = common::xtask(&args("bad.blut"), d.path());
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    fails_with(&o, "bad.blut: node 0 at [");
    let o = common::xtask(&args("t.blut"), d.path());
    assert!(o.status.success(), "{}", err(&o));
    assert!(err(&o).contains("within the recorded integration bound"));
    let o = common::xtask(&["lut", "inspect", "t.blut"], d.path());
    assert!(o.status.success(), "{}", err(&o));
    let line = format!("integration max estimated |node value - integral| {bound:.3e}");
    assert!(out(&o).contains(&line), "{}", out(&o));
}

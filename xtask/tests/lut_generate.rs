//! `cargo xtask lut generate` with table options: option errors, `--max-error`, the TOML
//! file, and the written table read back (values against closed forms). The reading of the
//! options itself, and the values of described tables against the direct integral, are
//! tested in the library (`crates/brdf-lut/tests/describe.rs`).

use brdf_lut::{Encoding, Model, Placement, Warp};
use std::path::Path;
use std::process::Output;

mod common;
use common::{fails_with, stderr as err, succeeds, GGX_SPLIT_SUM};

/// `cargo xtask lut generate args` in `cwd`.
fn xtask(args: &[&str], cwd: &Path) -> Output {
    common::xtask(&[&["lut", "generate"], args].concat(), cwd)
}

#[test]
fn option_errors_name_the_real_problem_and_write_nothing() {
    let d = tempfile::tempdir().unwrap();
    let with = |extra: &[&str]| {
        xtask(
            &[&GGX_SPLIT_SUM[..], &["--out", "t.blut"], extra].concat(),
            d.path(),
        )
    };
    fails_with(
        &with(&["--res", "1x1"]),
        "nodes per axis is 1; the limit is 2..=65536",
    );
    fails_with(&with(&["--res", "64"]), "has 2 axes (mu, roughness)");
    fails_with(&with(&["--res", "64xq"]), "`q` is not a whole number");
    fails_with(&with(&["--range", "sigma=0.1:1"]), "no axis `sigma`");
    fails_with(&with(&["--range", "mu=0:1"]), "a log warp needs lo > 0");
    fails_with(&with(&["--roughness", "sigma"]), "GGX has no RMS slope");
    fails_with(&with(&["--masking", "v-cavity"]), "Torrance–Sparrow");
    fails_with(&with(&["--encoding", "u8"]), "unknown encoding `u8`");
    fails_with(&with(&["--warp", "mu=cubic"]), "unknown warp `cubic`");
    fails_with(
        &with(&["--max-error", "0"]),
        "--max-error must be a positive",
    );
    fails_with(
        &xtask(&["--kind", "g-per-sigma", "--out", "g.blut"], d.path()),
        "needs --sigma",
    );
    fails_with(
        &xtask(&["--model", "ggx", "--out", "t.blut"], d.path()),
        "need --kind",
    );
    fails_with(
        &xtask(&["--kind", "e", "--model", "ggx"], d.path()),
        "--out FILE",
    );
    assert_eq!(std::fs::read_dir(d.path()).unwrap().count(), 0);
}

#[test]
fn max_error_fails_a_coarse_table_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let args = [
        &GGX_SPLIT_SUM[..],
        &[
            "--res",
            "2x2",
            "--interpolation",
            "linear",
            "--samples",
            "300",
            "--out",
            "coarse.blut",
        ],
    ]
    .concat();
    let strict = [&args[..], &["--max-error", "0.01"]].concat();
    let o = xtask(&strict, d.path());
    fails_with(&o, "exceeds --max-error");
    assert!(!d.path().join("coarse.blut").exists());
    // Without the limit the same table is written, and its header records the large error.
    succeeds(&xtask(&args, d.path()));
    let lut = brdf_lut::Lut::from_path(d.path().join("coarse.blut")).unwrap();
    assert!(lut.header().error.max_abs > 0.01);
}

#[test]
fn toml_file_with_flag_overrides() {
    let d = tempfile::tempdir().unwrap();
    let sub = d.path().join("pipeline");
    std::fs::create_dir(&sub).unwrap();
    std::fs::write(
        sub.join("eavg.toml"),
        r#"
kind = "e-avg"
model = "beckmann"
masking = "smith-separable"
encoding = "f32"
samples = 50
out = "eavg_beckmann.blut"
[axes.roughness]
count = 5
placement = "endpoint"
"#,
    )
    .unwrap();
    let o = xtask(
        &["--config", "pipeline/eavg.toml", "--encoding", "f16"],
        d.path(),
    );
    assert!(o.status.success(), "{}", err(&o));
    // `out` is relative to the TOML file's folder.
    let lut = brdf_lut::Lut::from_path(sub.join("eavg_beckmann.blut")).unwrap();
    let h = lut.header();
    assert_eq!(h.generator.model, Model::BeckmannSmithSeparable);
    assert_eq!(h.encoding, Encoding::F16); // the flag wins over the file
    assert_eq!(h.axes.len(), 1);
    let a = h.axes[0];
    assert_eq!((a.count, a.lo, a.hi), (5, 0.0, 1.0));
    assert_eq!((a.warp, a.placement), (Warp::Linear, Placement::Endpoint));
    // r = 0 is the mirror: E(μ) = A + B = 1, so E_avg = 2∫ μ dμ = 1 (closed form; the
    // Gauss–Legendre rule integrates the polynomial exactly; f16 storage: 2^-11).
    let e0 = lut.e_avg(0.0).unwrap();
    assert!((e0 - 1.0).abs() < 5e-4, "{e0}");
    // Rougher surfaces lose energy to masking: E_avg < 1 and decreasing.
    let (e5, e1) = (lut.e_avg(0.5).unwrap(), lut.e_avg(1.0).unwrap());
    assert!(e1 < e5 && e5 < 1.0, "{e5} {e1}");
    // A misspelt key is an error naming the file and the key.
    std::fs::write(sub.join("bad.toml"), "kind = \"e\"\nmodle = \"ggx\"\n").unwrap();
    let o = xtask(&["--config", "pipeline/bad.toml"], d.path());
    fails_with(&o, "bad.toml");
    fails_with(&o, "modle");
}

//! `cargo xtask lut engine <target>` end to end: the command writes the library's files
//! (`Engine::target_files`, whose contents are checked with independent decoders in
//! `crates/brdf-engine-assets/tests/engine_files.rs`) byte for byte, never over an existing
//! file without `--force`, and refuses sizes outside the limit.

use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("lut_engine")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn xtask(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(["lut", "engine"])
        .args(args)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.success(), text)
}

fn generate(target: &str, n: usize) -> PathBuf {
    let d = out_dir(&format!("{target}{n}"));
    let (ok, text) = xtask(&[
        target,
        "--size",
        &n.to_string(),
        "--out",
        d.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    d
}

/// Every target writes exactly the files the library makes for it, byte for byte.
#[test]
fn writes_the_librarys_files() {
    for e in brdf_engine_assets::Engine::ALL {
        let n = 8;
        let d = generate(e.name(), n);
        let grid = brdf_engine_assets::split_sum_texels(n, &|_| {}).unwrap();
        let want = e.target_files(&grid).unwrap();
        let mut names: Vec<String> = want.iter().map(|f| f.name.clone()).collect();
        names.sort();
        let mut got: Vec<String> = std::fs::read_dir(&d)
            .unwrap()
            .map(|f| f.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        got.sort();
        assert_eq!(got, names, "{}", e.name());
        for f in want {
            assert!(
                std::fs::read(d.join(&f.name)).unwrap() == f.bytes,
                "{}: {} differs from the library's",
                e.name(),
                f.name
            );
        }
    }
}

#[test]
fn refuses_to_overwrite_and_rejects_bad_sizes() {
    let d = generate("threejs", 4);
    let bin = d.join("dfg_lut.bin");
    std::fs::write(&bin, b"keep").unwrap();
    let (ok, text) = xtask(&["threejs", "--size", "4", "--out", d.to_str().unwrap()]);
    assert!(
        !ok && text.contains("exists") && text.contains("--force"),
        "{text}"
    );
    assert_eq!(std::fs::read(&bin).unwrap(), b"keep");
    let (ok, text) = xtask(&[
        "threejs",
        "--size",
        "4",
        "--out",
        d.to_str().unwrap(),
        "--force",
    ]);
    assert!(ok, "{text}");
    assert_eq!(std::fs::read(&bin).unwrap().len(), 4 * 4 * 4);
    // No temporary file left behind.
    assert!(std::fs::read_dir(&d).unwrap().all(|e| !e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .contains(".tmp")));
    for bad in ["1", "0", "100000"] {
        let (ok, text) = xtask(&["bevy", "--size", bad, "--out", d.to_str().unwrap()]);
        assert!(
            !ok && text.contains("table edge must be between 2 and"),
            "{bad}: {text}"
        );
    }
}

//! `cargo xtask ci`: the README's test command. Runs every check CI runs, in order, and
//! stops at the first failure.
//!
//! Each step is one command line. Steps that need tools a fresh machine may lack install them
//! themselves: the published LUTs (`cargo xtask anchors`, from npm and crates.io), the web
//! tools (`.ci/install-web.sh`), QEMU (`cargo xtask firmware` runs `.ci/install-qemu.sh`), the
//! MSRV toolchain (`rustup toolchain install`), SciPy for the benchmark's peer (a venv under
//! `.cache/`, made by `cargo xtask bench`), the Python package's build and test tools (a venv
//! under `.cache/`, made by `.ci/python.sh`), the nightly toolchain and cargo-fuzz for the
//! fuzz smoke run (`.ci/fuzz.sh`, docs/fuzzing.md).

use anyhow::{bail, Result};
use std::process::Command;

#[derive(clap::Args)]
pub struct Args {
    /// Skip the slow steps (browser, firmware, asset regeneration, fuzzing); for quick
    /// local runs.
    #[arg(long)]
    quick: bool,
}

/// The checks, in order: (name, slow, command line). Each is a plain command, words split
/// at spaces, so that it can be run by hand.
const STEPS: &[(&str, bool, &str)] = &[
    (
        "format",
        false,
        "cargo fmt --all -- --check",
    ),
    (
        "clippy",
        false,
        "cargo clippy --workspace --all-targets -- -D warnings",
    ),
    (
        "published LUTs for the comparison tests (npm, crates.io; pinned SHA-256)",
        false,
        "cargo xtask anchors",
    ),
    (
        "tests",
        false,
        "cargo test --workspace",
    ),
    (
        "no_std thumbv7em (libm)",
        false,
        "cargo build -p brdf-core --target thumbv7em-none-eabihf",
    ),
    (
        "no_std thumbv7em (micromath)",
        false,
        "cargo build -p brdf-core --target thumbv7em-none-eabihf --features micromath",
    ),
    (
        "wasm32 (libm)",
        false,
        "cargo build -p brdf-core --target wasm32-unknown-unknown",
    ),
    (
        "wasm32 (micromath)",
        false,
        "cargo build -p brdf-core --target wasm32-unknown-unknown --features micromath",
    ),
    (
        "publishable crates: warning-free docs, cargo package (each built from its archive)",
        false,
        "cargo xtask package",
    ),
    (
        "publishable crates on their declared rust-version (installs that toolchain)",
        true,
        "cargo xtask msrv",
    ),
    (
        "core tests with micromath",
        false,
        "cargo test -p brdf-tests --features micromath --test core_modified_g --test core_kernels",
    ),
    (
        "committed LUT assets are reproducible byte for byte",
        true,
        "cargo xtask lut --check",
    ),
    (
        "install web tools (binaryen, chromium, playwright-core) when missing",
        true,
        "bash .ci/install-web.sh",
    ),
    (
        "WASM module: size budget and Node comparison with native",
        true,
        "cargo xtask wasm",
    ),
    (
        "web page in headless Chromium against the native rendering",
        true,
        "cargo xtask web",
    ),
    (
        "benchmarks build and run once (smoke)",
        true,
        "cargo xtask bench --smoke",
    ),
    (
        "firmware on QEMU (libm, bit-exact, kernels within the 16 KiB flash budget)",
        true,
        "cargo xtask firmware --enforce-budget",
    ),
    (
        "C ABI: header up to date, C example on QEMU and host, bit-exact",
        true,
        "cargo xtask cffi",
    ),
    (
        "Python package: pip install ./crates/brdf-py into a venv under .cache/, pytest",
        true,
        "bash .ci/python.sh",
    ),
    (
        "firmware on QEMU (micromath, tolerance)",
        true,
        "cargo xtask firmware --micromath",
    ),
    (
        "fuzz smoke: BLUT parser and typed tables, 60 s (FUZZ_SECONDS; installs nightly, cargo-fuzz 0.13.2)",
        true,
        "bash .ci/fuzz.sh",
    ),
];

pub fn run(a: Args) -> Result<()> {
    for &(name, _, line) in STEPS.iter().filter(|s| !(a.quick && s.1)) {
        eprintln!("==> {name}: {line}");
        let mut words = line.split(' ');
        let program = words.next().unwrap_or_default();
        if !Command::new(program).args(words).status()?.success() {
            bail!("failed: {name}");
        }
    }
    eprintln!("==> all checks passed");
    Ok(())
}

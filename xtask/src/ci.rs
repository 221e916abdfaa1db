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

struct Step {
    name: &'static str,
    cmd: &'static [&'static str],
    slow: bool,
}

/// The checks, in order. Keep each a plain command so that it can be run by hand.
const STEPS: &[Step] = &[
    Step {
        name: "format",
        cmd: &["cargo", "fmt", "--all", "--", "--check"],
        slow: false,
    },
    Step {
        name: "clippy",
        cmd: &[
            "cargo",
            "clippy",
            "--workspace",
            "--all-targets",
            "--",
            "-D",
            "warnings",
        ],
        slow: false,
    },
    Step {
        name: "published LUTs for the comparison tests (npm, crates.io; pinned SHA-256)",
        cmd: &["cargo", "xtask", "anchors"],
        slow: false,
    },
    Step {
        name: "tests",
        cmd: &["cargo", "test", "--workspace"],
        slow: false,
    },
    Step {
        name: "no_std thumbv7em (libm)",
        cmd: &[
            "cargo",
            "build",
            "-p",
            "brdf-core",
            "--target",
            "thumbv7em-none-eabihf",
        ],
        slow: false,
    },
    Step {
        name: "no_std thumbv7em (micromath)",
        cmd: &[
            "cargo",
            "build",
            "-p",
            "brdf-core",
            "--target",
            "thumbv7em-none-eabihf",
            "--features",
            "micromath",
        ],
        slow: false,
    },
    Step {
        name: "wasm32 (libm)",
        cmd: &[
            "cargo",
            "build",
            "-p",
            "brdf-core",
            "--target",
            "wasm32-unknown-unknown",
        ],
        slow: false,
    },
    Step {
        name: "wasm32 (micromath)",
        cmd: &[
            "cargo",
            "build",
            "-p",
            "brdf-core",
            "--target",
            "wasm32-unknown-unknown",
            "--features",
            "micromath",
        ],
        slow: false,
    },
    Step {
        name: "publishable crates: warning-free docs, cargo package (each built from its archive)",
        cmd: &["cargo", "xtask", "package"],
        slow: false,
    },
    Step {
        name: "publishable crates on their declared rust-version (installs that toolchain)",
        cmd: &["cargo", "xtask", "msrv"],
        slow: true,
    },
    Step {
        name: "core tests with micromath",
        cmd: &[
            "cargo",
            "test",
            "-p",
            "brdf-tests",
            "--features",
            "micromath",
            "--test",
            "core_modified_g",
            "--test",
            "core_kernels",
        ],
        slow: false,
    },
    Step {
        name: "committed LUT assets are reproducible byte for byte",
        cmd: &["cargo", "xtask", "lut", "--check"],
        slow: true,
    },
    Step {
        name: "install web tools (binaryen, chromium, playwright-core) when missing",
        cmd: &["bash", ".ci/install-web.sh"],
        slow: true,
    },
    Step {
        name: "WASM module: size budget and Node comparison with native",
        cmd: &["cargo", "xtask", "wasm"],
        slow: true,
    },
    Step {
        name: "web page in headless Chromium against the native rendering",
        cmd: &["cargo", "xtask", "web"],
        slow: true,
    },
    Step {
        name: "benchmarks build and run once (smoke)",
        cmd: &["cargo", "xtask", "bench", "--smoke"],
        slow: true,
    },
    Step {
        name: "firmware on QEMU (libm, bit-exact, kernels within the 16 KiB flash budget)",
        cmd: &["cargo", "xtask", "firmware", "--enforce-budget"],
        slow: true,
    },
    Step {
        name: "C ABI: header up to date, C example on QEMU and host, bit-exact",
        cmd: &["cargo", "xtask", "cffi"],
        slow: true,
    },
    Step {
        name: "Python package: pip install ./crates/brdf-py into a venv under .cache/, pytest",
        cmd: &["bash", ".ci/python.sh"],
        slow: true,
    },
    Step {
        name: "firmware on QEMU (micromath, tolerance)",
        cmd: &["cargo", "xtask", "firmware", "--micromath"],
        slow: true,
    },
    Step {
        name: "fuzz smoke: BLUT parser and typed tables, 60 s (FUZZ_SECONDS; installs nightly, cargo-fuzz 0.13.2)",
        cmd: &["bash", ".ci/fuzz.sh"],
        slow: true,
    },
];

pub fn run(a: Args) -> Result<()> {
    let mut failed = Vec::new();
    for s in STEPS.iter().filter(|s| !(a.quick && s.slow)) {
        eprintln!("==> {}: {}", s.name, s.cmd.join(" "));
        let ok = Command::new(s.cmd[0]).args(&s.cmd[1..]).status()?.success();
        if !ok {
            failed.push(s.name);
            break;
        }
    }
    if !failed.is_empty() {
        bail!("failed: {}", failed.join(", "));
    }
    eprintln!("==> all checks passed");
    Ok(())
}

//! `cargo xtask wasm`: builds the WebAssembly module (release, wasm32-unknown-unknown,
//! size-optimised), shrinks it with `wasm-opt` ([`WASM_OPT_PASSES`], Debian's binaryen), prints the sizes
//! against the 64 KiB budget, writes the native expected values and runs the Node tests
//! (`node --test crates/brdf-wasm/test/`).
//!
//! Output: `crates/brdf-wasm/pkg/` (git-ignored): `brdf_wasm.wasm` (optimised),
//! `expected.json`, `web-expected.json`, `size.txt`.

use anyhow::{bail, Context, Result};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// Size budget for the optimised module.
pub const BUDGET: u64 = 64 * 1024;

#[derive(clap::Args)]
pub struct WasmArgs {
    /// Build, optimise and generate the expected values, but do not run `node --test`.
    #[arg(long)]
    pub no_test: bool,
}

/// The wasm-opt passes, in order.
pub const WASM_OPT_PASSES: [&str; 5] = ["-Oz", "--flatten", "--rereloop", "-Oz", "-Oz"];

/// Builds and optimises the module; returns (size before, size after) `wasm-opt`.
pub fn build(root: &Path) -> Result<(u64, u64)> {
    crate::run_in(
        root,
        crate::cargo().args([
            "build",
            "-p",
            "brdf-wasm",
            "--lib",
            "--release",
            "--target",
            "wasm32-unknown-unknown",
            // Size over speed for this artefact only; the workspace release profile is untouched.
            "--config",
            "profile.release.opt-level=\"z\"",
            "--config",
            "profile.release.lto=true",
            "--config",
            "profile.release.codegen-units=1",
            "--config",
            "profile.release.panic=\"abort\"",
        ]),
    )?;
    let raw = crate::target_dir(root).join("wasm32-unknown-unknown/release/brdf_wasm.wasm");
    let before = std::fs::metadata(&raw)
        .with_context(|| format!("{} missing after the build", raw.display()))?
        .len();
    let pkg = root.join("crates/brdf-wasm/pkg");
    std::fs::create_dir_all(&pkg)?;
    let out = pkg.join("brdf_wasm.wasm");
    if Command::new("wasm-opt").arg("--version").output().is_err() {
        bail!("wasm-opt not found: install Debian's binaryen (bash .ci/install-web.sh)");
    }
    crate::run_in(
        root,
        Command::new("wasm-opt")
            // -Oz, then flattened and re-reloop'ed and -Oz twice more: binaryen's own
            // semantics-preserving passes, about 1 % smaller than -Oz alone (measured: 65,463
            // against 66,182 bytes once the rough dielectric joined the catalogue).
            .args(WASM_OPT_PASSES)
            .args(["--strip-debug", "--strip-producers"])
            .arg(&raw)
            .arg("-o")
            .arg(&out),
    )?;
    let after = std::fs::metadata(&out)?.len();
    let report = format!(
        "brdf_wasm.wasm: {before} bytes ({:.1} KiB) from rustc (opt-level z, LTO), \
         {after} bytes ({:.1} KiB) after wasm-opt {}; budget {BUDGET} bytes (64 KiB): {}\n",
        before as f64 / 1024.0,
        after as f64 / 1024.0,
        WASM_OPT_PASSES.join(" "),
        if after <= BUDGET { "within" } else { "OVER" }
    );
    print!("{report}");
    brdf_engine_assets::fsio::replace(&pkg.join("size.txt"), report.as_bytes())?;
    if after > BUDGET {
        bail!("the optimised module ({after} bytes) exceeds the 64 KiB budget");
    }
    Ok((before, after))
}

/// Writes `expected.json` and `web-expected.json` with the host build.
pub fn expected(root: &Path) -> Result<()> {
    crate::run_in(
        root,
        crate::cargo()
            .args([
                "run",
                "--release",
                "-p",
                "brdf-wasm",
                "--example",
                "expected",
                "--",
            ])
            .arg(root.join("crates/brdf-wasm/pkg")),
    )
}

pub fn run(a: WasmArgs) -> Result<()> {
    let root = crate::workspace_root();
    let t0 = Instant::now();
    build(&root)?;
    expected(&root)?;
    let t1 = Instant::now();
    if !a.no_test {
        crate::run_in(
            &root,
            Command::new("node").args(["--test", "crates/brdf-wasm/test/"]),
        )?;
    }
    println!(
        "wasm: build + expected values {:.1} s, node tests {:.1} s",
        (t1 - t0).as_secs_f64(),
        t1.elapsed().as_secs_f64()
    );
    Ok(())
}

//! `cargo xtask msrv`: builds and tests the publishable crates with exactly the toolchain
//! their `rust-version` declares. Reads each crate's `rust-version` (`cargo metadata`),
//! installs that toolchain (`rustup toolchain install <ver> --profile minimal`, plus the
//! Cortex-M target), then runs `cargo +<ver> test -p <crate>` (unit tests and doctests) and
//! `cargo +<ver> build -p brdf-core --target thumbv7em-none-eabihf` into `target/msrv-<ver>`.

use anyhow::{bail, Context, Result};
use std::path::Path;
use std::process::Command;

/// The crates published to crates.io.
pub const PUBLISHABLE: &[&str] = &["brdf-core", "brdf-lut"];

#[derive(clap::Args)]
pub struct Args {}

fn root() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the repo root")
        .to_path_buf()
}

/// `1.81` → `1.81.0`; a full `1.81.2` stays.
fn toolchain_of(rust_version: &str) -> String {
    if rust_version.split('.').count() == 2 {
        format!("{rust_version}.0")
    } else {
        rust_version.to_string()
    }
}

fn status(cmd: &mut Command, what: &str) -> Result<()> {
    eprintln!("msrv: {what}");
    let st = cmd.status().with_context(|| format!("running {what}"))?;
    if !st.success() {
        bail!("{what} failed ({st})");
    }
    Ok(())
}

pub fn run(_a: Args) -> Result<()> {
    let root = root();
    let out = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .current_dir(&root)
        .args(["metadata", "--no-deps", "--format-version", "1"])
        .output()
        .context("running cargo metadata")?;
    if !out.status.success() {
        bail!("cargo metadata failed");
    }
    let meta: serde_json::Value = serde_json::from_slice(&out.stdout)?;
    let mut plan: Vec<(String, String)> = Vec::new();
    for name in PUBLISHABLE {
        let pkg = meta["packages"]
            .as_array()
            .and_then(|ps| ps.iter().find(|p| p["name"] == *name))
            .with_context(|| format!("{name} is not a workspace member"))?;
        let rv = pkg["rust_version"]
            .as_str()
            .with_context(|| format!("{name} declares no rust-version"))?;
        plan.push((name.to_string(), toolchain_of(rv)));
    }
    for (name, tc) in &plan {
        status(
            Command::new("rustup").args([
                "toolchain",
                "install",
                tc,
                "--profile",
                "minimal",
                "--target",
                "thumbv7em-none-eabihf",
            ]),
            &format!("rustup toolchain install {tc}"),
        )?;
        let tdir = root.join("target").join(format!("msrv-{tc}"));
        // A toolchain's own cargo, not the rustup proxy's choice from the environment.
        let cargo = |args: &[&str]| {
            let mut c = Command::new("rustup");
            c.current_dir(&root)
                .args(["run", tc, "cargo"])
                .args(args)
                .env("CARGO_TARGET_DIR", &tdir)
                .env_remove("RUSTC")
                .env_remove("CARGO")
                .env_remove("RUSTDOC");
            c
        };
        status(
            &mut cargo(&["test", "--locked", "-p", name]),
            &format!("cargo +{tc} test -p {name}"),
        )?;
        if name == "brdf-core" {
            status(
                &mut cargo(&[
                    "build",
                    "--locked",
                    "-p",
                    name,
                    "--target",
                    "thumbv7em-none-eabihf",
                ]),
                &format!("cargo +{tc} build -p {name} --target thumbv7em-none-eabihf"),
            )?;
        }
    }
    eprintln!(
        "msrv: OK ({})",
        plan.iter()
            .map(|(n, t)| format!("{n} {t}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::toolchain_of;

    #[test]
    fn rust_version_to_toolchain() {
        assert_eq!(toolchain_of("1.81"), "1.81.0");
        assert_eq!(toolchain_of("1.87.1"), "1.87.1");
    }
}

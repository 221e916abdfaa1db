//! `cargo xtask msrv`: builds and tests the publishable crates with exactly the toolchain
//! their `rust-version` declares. Reads each crate's `rust-version` (`cargo metadata`) and,
//! once per distinct toolchain:
//!
//! 1. installs it (`rustup toolchain install <ver> --profile minimal`, plus the Cortex-M
//!    target);
//! 2. `cargo +<ver> test --locked --all-features -p …` (unit, integration and doc tests, with
//!    `std`);
//! 3. builds the crates without their default features for `thumbv7em-none-eabihf`, which has
//!    no `std` at all: the `no_std` configuration the firmware, the WASM module and the C ABI
//!    use (its API floor differs from the `std` one: `f32::abs` is in `core` only since 1.84);
//!    brdf-lut also with `alloc,compact`;
//! 4. builds the unpublished `brdf-ffi` (`no_std` readers), which declares the same floor.
//!
//! Everything goes into `target/msrv-<ver>`, so the main build stays untouched.

use anyhow::{bail, Context, Result};
use std::process::Command;

/// The crates published to crates.io.
pub const PUBLISHABLE: &[&str] = &["brdf-core", "brdf-lut"];

/// Unpublished crates that declare a `rust-version` the check also holds them to (build only).
const ALSO_BUILT: &[&str] = &["brdf-ffi"];

/// The no_std target of the firmware.
const NO_STD_TARGET: &str = "thumbv7em-none-eabihf";

#[derive(clap::Args)]
pub struct Args {}

/// `1.81` → `1.81.0`; a full `1.81.2` stays.
fn toolchain_of(rust_version: &str) -> String {
    if rust_version.split('.').count() == 2 {
        format!("{rust_version}.0")
    } else {
        rust_version.to_string()
    }
}

/// Crates grouped by toolchain, in first-seen order: one install and one build per toolchain.
fn group(plan: &[(String, String)]) -> Vec<(String, Vec<String>)> {
    let mut out: Vec<(String, Vec<String>)> = Vec::new();
    for (name, tc) in plan {
        match out.iter_mut().find(|(t, _)| t == tc) {
            Some((_, names)) => names.push(name.clone()),
            None => out.push((tc.clone(), vec![name.clone()])),
        }
    }
    out
}

fn status(cmd: &mut Command, what: &str) -> Result<()> {
    eprintln!("msrv: {what}");
    let st = cmd.status().with_context(|| format!("running {what}"))?;
    if !st.success() {
        bail!("{what} failed ({st})");
    }
    Ok(())
}

fn rust_version(meta: &serde_json::Value, name: &str) -> Result<String> {
    let pkg = meta["packages"]
        .as_array()
        .and_then(|ps| ps.iter().find(|p| p["name"] == name))
        .with_context(|| format!("{name} is not a workspace member"))?;
    let rv = pkg["rust_version"]
        .as_str()
        .with_context(|| format!("{name} declares no rust-version"))?;
    Ok(toolchain_of(rv))
}

/// The toolchain of each crate to check: (crate, toolchain) for [`PUBLISHABLE`] and for
/// [`ALSO_BUILT`], from `cargo metadata`.
#[allow(clippy::type_complexity)]
fn plan(root: &std::path::Path) -> Result<(Vec<(String, String)>, Vec<(String, String)>)> {
    let out = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .current_dir(root)
        .args(["metadata", "--no-deps", "--format-version", "1"])
        .output()
        .context("running cargo metadata")?;
    if !out.status.success() {
        bail!("cargo metadata failed");
    }
    let meta: serde_json::Value = serde_json::from_slice(&out.stdout)?;
    let of = |names: &[&str]| -> Result<Vec<(String, String)>> {
        names
            .iter()
            .map(|n| Ok((n.to_string(), rust_version(&meta, n)?)))
            .collect()
    };
    Ok((of(PUBLISHABLE)?, of(ALSO_BUILT)?))
}

/// `cargo` of toolchain `tc` (its own, not the rustup proxy's choice from the environment),
/// building into `tdir`.
fn toolchain_cargo(root: &std::path::Path, tc: &str, tdir: &std::path::Path) -> Command {
    let mut c = Command::new("rustup");
    c.current_dir(root)
        .args(["run", tc, "cargo"])
        .env("CARGO_TARGET_DIR", tdir)
        .env_remove("RUSTC")
        .env_remove("CARGO")
        .env_remove("RUSTDOC")
        .env_remove("RUSTFLAGS")
        .env_remove("RUSTDOCFLAGS");
    c
}

/// Steps 2–3 for the publishable crates `names` on toolchain `tc`.
fn check_publishable(root: &std::path::Path, tc: &str, names: &[String]) -> Result<()> {
    let tdir = root.join("target").join(format!("msrv-{tc}"));
    let cargo = |args: &[&str]| {
        let mut c = toolchain_cargo(root, tc, &tdir);
        c.args(args);
        c
    };
    let pkgs: Vec<&str> = names.iter().flat_map(|n| ["-p", n.as_str()]).collect();
    let list = names.join(" ");
    let mut args = vec!["test", "--locked", "--all-features"];
    args.extend(&pkgs);
    status(
        &mut cargo(&args),
        &format!("cargo +{tc} test --all-features {list}"),
    )?;
    let mut args = vec!["build", "--locked", "--no-default-features"];
    args.extend(&pkgs);
    args.extend(["--target", NO_STD_TARGET]);
    let what = format!("cargo +{tc} build --no-default-features {list} --target {NO_STD_TARGET}");
    status(&mut cargo(&args), &what)?;
    if names.iter().any(|n| n == "brdf-lut") {
        let args = [
            "build",
            "--locked",
            "-p",
            "brdf-lut",
            "--no-default-features",
            "--features",
            "alloc,compact",
            "--target",
            NO_STD_TARGET,
        ];
        let what = format!("cargo +{tc} build brdf-lut --features alloc,compact (no_std)");
        status(&mut cargo(&args), &what)?;
    }
    Ok(())
}

pub fn run(_a: Args) -> Result<()> {
    let root = crate::workspace_root();
    let (plan, extra) = plan(&root)?;
    let mut toolchains = group(&plan);
    for (_, tc) in &extra {
        if !toolchains.iter().any(|(t, _)| t == tc) {
            toolchains.push((tc.clone(), Vec::new()));
        }
    }
    for (tc, names) in &toolchains {
        let install = [
            "toolchain",
            "install",
            tc,
            "--profile",
            "minimal",
            "--target",
        ];
        status(
            Command::new("rustup").args(install).arg(NO_STD_TARGET),
            &format!("rustup toolchain install {tc}"),
        )?;
        if !names.is_empty() {
            check_publishable(&root, tc, names)?;
        }
        let tdir = root.join("target").join(format!("msrv-{tc}"));
        for (name, _) in extra.iter().filter(|(_, t)| t == tc) {
            status(
                toolchain_cargo(&root, tc, &tdir).args(["build", "--locked", "-p", name]),
                &format!("cargo +{tc} build -p {name}"),
            )?;
        }
    }
    let all: Vec<String> = plan
        .iter()
        .chain(&extra)
        .map(|(n, t)| format!("{n} {t}"))
        .collect();
    eprintln!("msrv: OK ({})", all.join(", "));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{group, toolchain_of, PUBLISHABLE};

    /// The README states each publishable crate's minimum Rust; it must be the declared one.
    #[test]
    fn readme_states_the_declared_rust_versions() {
        let root = crate::workspace_root();
        let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
        for name in PUBLISHABLE {
            let manifest = root.join("crates").join(name).join("Cargo.toml");
            let t: toml::Table = std::fs::read_to_string(&manifest).unwrap().parse().unwrap();
            let rv = t["package"]["rust-version"]
                .as_str()
                .unwrap_or_else(|| panic!("{name}: rust-version must be a literal"));
            let at = readme
                .find(&format!("`{name}` ("))
                .unwrap_or_else(|| panic!("README.md does not describe `{name}`"));
            let sentence = &readme[at..readme.len().min(at + 120)];
            assert!(
                sentence.contains(&format!("Rust {rv} or later")),
                "README.md: `{name}` should say \"Rust {rv} or later\": {sentence:?}"
            );
        }
    }

    #[test]
    fn rust_version_to_toolchain() {
        assert_eq!(toolchain_of("1.81"), "1.81.0");
        assert_eq!(toolchain_of("1.87.1"), "1.87.1");
    }

    #[test]
    fn one_install_per_toolchain() {
        let p = |n: &str, t: &str| (n.to_string(), t.to_string());
        let g = group(&[p("a", "1.84.0"), p("b", "1.82.0"), p("c", "1.84.0")]);
        assert_eq!(
            g,
            vec![
                ("1.84.0".to_string(), vec!["a".to_string(), "c".to_string()]),
                ("1.82.0".to_string(), vec!["b".to_string()]),
            ]
        );
    }
}

//! `cargo xtask package`: what publishing the crates needs, checked without publishing.
//!
//! 1. The API docs of the publishable crates build without a warning (`RUSTDOCFLAGS=-D
//!    warnings cargo doc --no-deps`), with all features (what docs.rs shows) and brdf-lut also
//!    without its default features (its README links to feature-gated items).
//! 2. `cargo package -p brdf-core -p brdf-lut`: both archives are built and each is compiled
//!    from its archive alone. They are packaged together because brdf-lut depends on
//!    brdf-core by path and version: cargo resolves that dependency against the brdf-core
//!    archive it has just made (a temporary local registry), so the check does not need
//!    brdf-core on crates.io. `cargo package -p brdf-lut` on its own fails until brdf-core
//!    is published. Publishing is `cargo publish -p brdf-core`, then `cargo publish -p
//!    brdf-lut`.

use crate::msrv::PUBLISHABLE;
use anyhow::{bail, Context, Result};
use std::path::Path;
use std::process::Command;

#[derive(clap::Args)]
pub struct Args {
    /// Package a working tree with uncommitted changes (`cargo package --allow-dirty`).
    #[arg(long)]
    allow_dirty: bool,
}

fn cargo(root: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    c.current_dir(root).args(args);
    c
}

fn status(mut cmd: Command, what: &str) -> Result<()> {
    eprintln!("package: {what}");
    let st = cmd.status().with_context(|| format!("running {what}"))?;
    if !st.success() {
        bail!("{what} failed ({st})");
    }
    Ok(())
}

pub fn run(a: Args) -> Result<()> {
    let root = crate::workspace_root();
    let pkgs: Vec<&str> = PUBLISHABLE.iter().flat_map(|n| ["-p", *n]).collect();

    let mut args = vec!["doc", "--no-deps", "--all-features"];
    args.extend(&pkgs);
    let mut c = cargo(&root, &args);
    c.env("RUSTDOCFLAGS", "-D warnings");
    status(c, "cargo doc --all-features (warnings are errors)")?;
    let mut c = cargo(
        &root,
        &[
            "doc",
            "--no-deps",
            "--no-default-features",
            "-p",
            "brdf-lut",
        ],
    );
    c.env("RUSTDOCFLAGS", "-D warnings");
    status(c, "cargo doc -p brdf-lut --no-default-features")?;

    let mut args = vec!["package"];
    args.extend(&pkgs);
    if a.allow_dirty {
        args.push("--allow-dirty");
    }
    let what = args.join(" ");
    status(cargo(&root, &args), &format!("cargo {what}"))?;
    eprintln!("package: OK ({})", PUBLISHABLE.join(", "));
    Ok(())
}

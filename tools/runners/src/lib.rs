//! The target runners behind `cargo xtask firmware|cffi|wasm|web`: each builds a target the
//! repository ships (the Cortex-M firmware, the C example, the WebAssembly module, the web
//! page), runs it (QEMU, the host, Node, headless Chromium) and compares its values with
//! the host's. `device` holds what the firmware and C runners share: QEMU, the output
//! protocol, ELF sizes. xtask owns the command line and calls each module's `run`.

#![deny(unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]

pub mod cffi;
mod device;
pub mod firmware;
pub mod wasm;
pub mod web;

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root (this crate lives in `tools/runners`).
pub fn workspace_root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors().nth(2).unwrap_or(here).to_path_buf()
}

/// Cargo's target folder: `CARGO_TARGET_DIR` (relative to the workspace root when relative),
/// else `target/` of the workspace.
pub(crate) fn target_dir(root: &Path) -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from) {
        Some(d) if d.is_absolute() => d,
        Some(d) => root.join(d),
        None => root.join("target"),
    }
}

/// The cargo that runs xtask (`$CARGO`), for the child builds.
pub(crate) fn cargo() -> Command {
    Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
}

/// Runs a step (`what` names it in the messages) and fails unless it succeeds.
pub(crate) fn run_step(cmd: &mut Command, what: &str) -> Result<()> {
    let st = cmd.status().with_context(|| format!("running {what}"))?;
    if !st.success() {
        bail!("{what} failed ({st})");
    }
    Ok(())
}

/// Prints `cmd` and runs it in `dir` ([`run_step`], named by its command line).
pub(crate) fn run_in(dir: &Path, cmd: &mut Command) -> Result<()> {
    let line = format!("{cmd:?}");
    println!("$ {line}");
    run_step(cmd.current_dir(dir), &line)
}

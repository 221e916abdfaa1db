//! Repository upkeep behind `cargo xtask ci|msrv|package|anchors`: the list of CI steps, the
//! publishable crates built on their declared toolchain and packaged, and the engines'
//! published LUTs fetched with pinned hashes. xtask owns the command line and calls each
//! module's `run`.

pub mod anchors;
pub mod ci;
pub mod msrv;
pub mod package;

use std::path::{Path, PathBuf};

/// The workspace root (this crate lives in `tools/maint`).
pub fn workspace_root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors().nth(2).unwrap_or(here).to_path_buf()
}

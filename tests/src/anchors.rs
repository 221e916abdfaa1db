//! The engines' published split-sum tables the LUT comparison tests read.
//!
//! Looked up in `.cache/anchors/` (filled by `cargo xtask anchors`, which downloads them from
//! the npm and crates.io packages that ship them and checks pinned SHA-256 hashes), then in
//! `../shared/anchors/` beside the repository.

use std::path::PathBuf;

/// The command that fetches the required anchors.
pub const FETCH_COMMAND: &str = "cargo xtask anchors";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The places searched for `rel`, in order.
pub fn candidates(rel: &str) -> [PathBuf; 2] {
    let r = root();
    [
        r.join(".cache/anchors").join(rel),
        r.join("../shared/anchors").join(rel),
    ]
}

fn find(rel: &str) -> Option<Vec<u8>> {
    candidates(rel).iter().find_map(|p| std::fs::read(p).ok())
}

/// A required anchor (one `cargo xtask anchors` fetches). Panics, naming the file and the
/// fetch command, when it is in neither place.
pub fn anchor(rel: &str) -> Vec<u8> {
    find(rel).unwrap_or_else(|| {
        let [cache, shared] = candidates(rel);
        panic!(
            "anchor file {rel} not found (looked in {} and {}); fetch it with `{FETCH_COMMAND}`",
            cache.display(),
            shared.display()
        )
    })
}

/// An optional anchor (not in any package registry). `None`, after printing which file is
/// skipped and why, when it is in neither place.
pub fn optional_anchor(rel: &str) -> Option<Vec<u8>> {
    let found = find(rel);
    if found.is_none() {
        eprintln!(
            "SKIPPED: optional anchor {rel} is not in .cache/anchors/ or ../shared/anchors/ \
             (no package registry ships it, so `{FETCH_COMMAND}` cannot fetch it)"
        );
    }
    found
}

/// Decodes an IEEE 754 binary16 value stored little-endian at element `i` of `b`.
pub fn f16_le(b: &[u8], i: usize) -> f32 {
    half::f16::from_bits(u16::from_le_bytes([b[2 * i], b[2 * i + 1]])).to_f32()
}

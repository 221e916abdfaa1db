//! Helpers of the crate's unit tests: the committed assets and made-up axes.

use crate::header::{Axis, Placement, Warp};

/// The path of the committed asset `name` (the workspace's `assets/`).
#[cfg(feature = "std")]
pub(crate) fn asset_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name)
}

/// The bytes of the committed asset `name`; panics with the path if it cannot be read.
#[cfg(feature = "std")]
pub(crate) fn asset(name: &str) -> std::vec::Vec<u8> {
    let p = asset_path(name);
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// An axis named `x` of `count` nodes over [lo, hi].
pub(crate) fn axis(
    count: u32,
    lo: f64,
    hi: f64,
    warp: Warp,
    placement: Placement,
) -> Axis<'static> {
    Axis {
        name: "x",
        count,
        lo,
        hi,
        warp,
        placement,
    }
}

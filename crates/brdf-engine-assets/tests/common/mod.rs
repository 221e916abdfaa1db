//! Shared by the engine-asset tests.

/// The keys every table sidecar JSON carries (docs/engines.md: integral, model, axes,
/// orientation, encoding, linear).
pub const SIDECAR_KEYS: [&str; 6] = [
    "integral",
    "model",
    "axes",
    "orientation",
    "encoding",
    "linear",
];

//! What the callgrind part of the report measures: the harness's kernels and call counts,
//! and the instruction total of a callgrind output file.

/// Kernels of the callgrind harness, their call counts and descriptions.
pub const CALLGRIND: &[(&str, usize, &str)] = &[
    ("g_direct_f32", 500, "modified G, direct, f32, 10 nodes"),
    ("g_direct_f64", 500, "modified G, direct, f64, 10 nodes"),
    ("g_lut3d", 2000, "modified G, 3-D table (θ, φ, σ)"),
    ("g_lut2d", 2000, "modified G, per-σ 2-D table"),
    (
        "g_lut3d_linear",
        2000,
        "modified G, 3-D table, speed tier (trilinear)",
    ),
    (
        "g_lut2d_linear",
        2000,
        "modified G, per-σ 2-D table, speed tier (bilinear)",
    ),
    (
        "smith_beckmann_f32",
        5000,
        "Smith–Beckmann G, height-correlated, f32",
    ),
    ("blinn_f32", 5000, "Blinn G from dot products, f32"),
    ("dfg_lut", 2000, "DFG (A, B) table lookup"),
    ("dfg_karis", 5000, "DFG, Karis's analytic fit"),
    ("dfg_direct_f64", 8, "DFG, split-sum integral, f64"),
];

/// Harness kernels measured when this build's harness has them (`harness list`): the floor
/// and the `_std` twins of the kernel targets. Any other listed kernel is measured too, with
/// [`EXTRA_CALLS`] calls.
pub const OPTIONAL_CALLGRIND: &[(&str, usize, &str)] = &[
    (
        "floor_bilinear2",
        2000,
        "floor: one bilinear fetch of a two-channel u16 table",
    ),
    (
        "dfg_lut_std",
        2000,
        "DFG (A, B) lookup through the std loader",
    ),
    (
        "g_lut2d_linear_std",
        2000,
        "modified G, per-σ 2-D table, speed tier, through the std loader",
    ),
];

/// Calls of a listed kernel that neither list names.
pub const EXTRA_CALLS: usize = 200;

/// The kernels to measure, given the output of `harness list` (one name a line):
/// [`CALLGRIND`], then those listed and not in it (described by [`OPTIONAL_CALLGRIND`] when
/// named there).
pub fn kernels_to_measure(listed: &str) -> Vec<(String, usize, String)> {
    let mut ks: Vec<(String, usize, String)> = CALLGRIND
        .iter()
        .map(|(k, n, w)| (k.to_string(), *n, w.to_string()))
        .collect();
    for name in listed.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if ks.iter().any(|k| k.0 == name) {
            continue;
        }
        let (n, what) = OPTIONAL_CALLGRIND
            .iter()
            .find(|o| o.0 == name)
            .map_or((EXTRA_CALLS, "harness entry"), |o| (o.1, o.2));
        ks.push((name.to_string(), n, what.to_string()));
    }
    ks
}

/// The instruction total (first event) of a callgrind output file's `summary:` or
/// `totals:` line.
pub fn callgrind_total(text: &str) -> Option<f64> {
    text.lines()
        .find_map(|l| {
            l.strip_prefix("summary:")
                .or_else(|| l.strip_prefix("totals:"))
        })
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
}

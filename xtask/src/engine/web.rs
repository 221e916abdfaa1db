//! Inputs of the WebGL2 engine-LUT test (examples/web/test/lut_engine.test.mjs): the khronos
//! table at 64² with its GLSL function, and random (μ, r) points with the f64 integral and
//! the error bound the GPU sample must meet.

use super::{centre, compute_grid, integral, write_set, File as OutFile};
use anyhow::{bail, Context, Result};
use brdf_engine_assets::report::Table;
use brdf_engine_assets::sidecar::Mapping;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::path::Path;

/// Table edge of the browser test.
pub const N: usize = 64;
/// Points sampled by the fragment shader (a 64 × 32 render target).
pub const POINTS: usize = 2048;

/// Writes `dir/lut_ggx.png`, `dir/lut_ggx.glsl`, … and `dir/points.json`.
pub fn prepare(dir: &Path) -> Result<()> {
    let grid = compute_grid(N, true)?;
    let files = brdf_engine_assets::khronos(&grid)?;
    let exact = Table {
        n: N,
        a: grid.a.clone(),
        b: grid.b.clone(),
    };
    let lo = centre(0, N);
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x0EB6_1011);
    let pts: Vec<(f64, f64)> = (0..POINTS)
        .map(|_| {
            (
                rng.random_range(lo..1.0 - lo),
                rng.random_range(lo..1.0 - lo),
            )
        })
        .collect();
    let rows: Vec<serde_json::Value> = pts
        .par_iter()
        .map(|&(mu, r)| {
            let (a, b) = integral(mu, r);
            let (xa, xb) = exact.sample(mu, r);
            // Spread of the four texels around the point, for the GPU's fixed-point
            // bilinear weights (8 fractional bits: weight error ≤ 2⁻⁹ per axis).
            let (sa, sb) = spread(&exact, mu, r);
            // Bound: interpolation error of exact texels + half an 8-bit unit + weight
            // quantisation (2 axes × 2⁻⁹ × spread) + f32 arithmetic in the shader (1e-6).
            let bound_a = (xa - a).abs() + 0.5 / 255.0 + sa * 2f64.powi(-8) + 1e-6;
            let bound_b = (xb - b).abs() + 0.5 / 255.0 + sb * 2f64.powi(-8) + 1e-6;
            serde_json::json!([mu, r, a, b, bound_a, bound_b])
        })
        .collect();
    let mut files = files;
    files.push(OutFile {
        name: "points.json".into(),
        bytes: serde_json::to_vec(&serde_json::json!({ "n": N, "points": rows }))?,
    });
    write_set(dir, &files, true)
}

fn spread(t: &Table, mu: f64, r: f64) -> (f64, f64) {
    let n = t.n;
    let ax = |x: f64| {
        let p = (x * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let i0 = p.floor() as usize;
        (i0, (i0 + 1).min(n - 1))
    };
    let (x0, x1) = ax(mu);
    let (y0, y1) = ax(r);
    let f = |v: &[f64]| {
        let s = [
            v[y0 * n + x0],
            v[y0 * n + x1],
            v[y1 * n + x0],
            v[y1 * n + x1],
        ];
        let mx = s.iter().cloned().fold(f64::MIN, f64::max);
        let mn = s.iter().cloned().fold(f64::MAX, f64::min);
        mx - mn
    };
    (f(&t.a), f(&t.b))
}

/// The committed asset whose native export the browser test samples.
pub const NATIVE_ASSET: &str = "dfg_ggx.blut";
/// The exported file (raw little-endian binary16, uploaded as RG16F: half floats are
/// filterable in core WebGL2, unlike R32F/RG32F or 16-bit unorm).
pub const NATIVE_EXPORT: &str = "dfg_ggx.f16.bin";

/// GPU texture-coordinate error of the emitted GLSL's f32 arithmetic, in texels per axis.
/// GLSL ES 3.00 (Range and Precision, highp) allows `log` 3 ulp outside [0.5, 2] (≤ 3 × 2⁻²¹ for |ln μ| < 4.1 on
/// μ ≥ cos 89°) and 2⁻²¹ absolute inside; with the subtraction of the base and the product
/// with 1/span (≈ 0.25) t errs by < 2e-6, times N − 1 = 63 and the placement's two roundings:
/// < 1.5e-4 texels. 2e-4 covers it.
const COORD_TEXELS: f64 = 2e-4;

/// Writes, into `dir`, `lut export --raw-f16` of [`NATIVE_ASSET`] (data file, sidecar, GLSL
/// and WGSL functions, via the `lut export` command run in this process) and
/// `native_points.json`: random (μ, r), 5 % of them outside the axis ranges to exercise the
/// clamps, each as `[μ, r, A, B, bound A, bound B, A_lin, B_lin]`: the f64 integral at the
/// sidecar-clamped point, the bound the GPU value of the emitted GLSL function must meet,
/// and the bilinear value of the exact grid (for the report of the non-interpolation part).
///
/// The bound at a point is the sum of
/// - the interpolation error of the function's own scheme with exact texels: bilinear in the
///   sidecar's warped coordinate (log μ, r) between the nodes of its `inverse_mapping`, each
///   texel the f64 integral at its node, minus the integral at the point;
/// - the texel encoding: half a unit of the asset's encoding (unorm16 in the .blut) plus half
///   an f16 ulp at the texel's magnitude (the export), the largest of the four texels the
///   filter reads — every exported texel is checked against this before it is used;
/// - the GPU's filter weights, 8 fractional bits (error ≤ 2⁻⁹ per axis), and the f32
///   coordinate error [`COORD_TEXELS`], both times the spread of the four texels;
/// - 1e-6 for the f32 blend and decode of values ≤ 1.
pub fn prepare_native(dir: &Path) -> Result<()> {
    let asset = crate::fsio::assets_dir().join(NATIVE_ASSET);
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let out = dir.join(NATIVE_EXPORT);
    export_in_process(&asset, &out)?;
    let ex = read_export(&out)?;
    let exact = exact_grid(&ex.axes)?;
    let half_unit = node_half_unit(&asset)?;
    let worst_texel = check_texels(&ex, &exact, half_unit, &out)?;
    let pts = random_points(&ex.axes);
    let rows = point_rows(&ex, &exact, half_unit, &pts);
    let max_bound = rows.iter().map(|r| r.1).fold(0.0, f64::max);
    let max_interp = rows.iter().map(|r| r.2).fold(0.0, f64::max);
    let doc = serde_json::json!({
        "source": NATIVE_ASSET,
        "export": NATIVE_EXPORT,
        "max_texel_error": worst_texel,
        "max_bound": max_bound,
        "max_interpolation_error": max_interp,
        "points": rows.into_iter().map(|r| r.0).collect::<Vec<_>>(),
    });
    println!(
        "web: {NATIVE_EXPORT}: max |texel - integral at node| {worst_texel:.2e}, \
         max bilinear error of exact texels {max_interp:.2e}, max bound {max_bound:.2e} \
         over {POINTS} points"
    );
    write_set(
        dir,
        &[OutFile {
            name: "native_points.json".into(),
            bytes: serde_json::to_vec(&doc)?,
        }],
        true,
    )
}

/// The exported table as its sidecar describes it: the two axes and the decoded texels,
/// channel-planar (axis 0 fastest).
struct Export {
    axes: [Mapping; 2],
    tex: [Vec<f64>; 2],
}

/// Reads the export `out` and its sidecar `out.json`; decodes the texels with the `half`
/// crate (not the exporter's converter) and the sidecar's `channel_decode`.
fn read_export(out: &Path) -> Result<Export> {
    let side: serde_json::Value = serde_json::from_slice(
        &std::fs::read(format!("{}.json", out.display())).context("reading the sidecar")?,
    )?;
    let maps = side["inverse_mapping"]
        .as_array()
        .filter(|m| m.len() == 2)
        .context("sidecar: inverse_mapping of 2 axes")?;
    let m = |j: &serde_json::Value| Mapping::from_json(j).map_err(anyhow::Error::msg);
    let axes = [m(&maps[0])?, m(&maps[1])?];
    let decode: Vec<(f64, f64)> = side["channel_decode"]
        .as_array()
        .context("sidecar: channel_decode")?
        .iter()
        .map(|c| (c["offset"].as_f64(), c["scale"].as_f64()))
        .map(|(o, s)| o.zip(s).context("sidecar: channel_decode offset/scale"))
        .collect::<Result<_>>()?;
    if decode.len() != 2 || side["format"] != "raw-f16" {
        bail!("sidecar: expected a 2-channel raw-f16 export");
    }
    let (w, h) = (axes[0].count, axes[1].count);
    let raw = std::fs::read(out)?;
    if raw.len() != w * h * 2 * 2 {
        bail!(
            "{}: {} bytes, expected {w}×{h}×2 f16",
            out.display(),
            raw.len()
        );
    }
    let mut tex = [vec![0.0f64; w * h], vec![0.0f64; w * h]];
    for (k, b) in raw.chunks_exact(2).enumerate() {
        let x = half::f16::from_le_bytes([b[0], b[1]]).to_f64();
        let c = k % 2;
        tex[c][k / 2] = decode[c].0 + decode[c].1 * x;
    }
    Ok(Export { axes, tex })
}

/// The exact grid: the integral at the sidecar's nodes (axis 0 = columns, fastest).
fn exact_grid(axes: &[Mapping; 2]) -> Result<Table> {
    let (w, h) = (axes[0].count, axes[1].count);
    if w != h {
        bail!("the native export test expects a square table, got {w}×{h}");
    }
    let nodes: Vec<(f64, f64)> = (0..w * h)
        .into_par_iter()
        .map(|k| integral(axes[0].node(k % w), axes[1].node(k / w)))
        .collect();
    Ok(Table {
        n: w,
        a: nodes.iter().map(|v| v.0).collect(),
        b: nodes.iter().map(|v| v.1).collect(),
    })
}

/// Half a unit of the asset's stored encoding.
fn node_half_unit(asset: &Path) -> Result<f64> {
    let lut = crate::fsio::load_lut(asset)?;
    Ok(match lut.view()?.header().encoding {
        brdf_lut::Encoding::Unorm16 => 0.5 / 65535.0,
        brdf_lut::Encoding::F16 => 2f64.powi(-12),
        brdf_lut::Encoding::F32 => 2f64.powi(-24),
    })
}

/// The encoding bound of an exported texel of value v: half a unit of the asset's encoding,
/// half an f16 ulp at |v| (normal range; 2⁻²⁵ in the subnormals), plus 1e-7 for the f32 node
/// values the exporter rounds.
fn enc(half_unit: f64, v: f64) -> f64 {
    half_unit + half_ulp_f16(v) + 1e-7
}

/// Checks every exported texel against the integral at its node within [`enc`]; returns the
/// largest difference.
fn check_texels(ex: &Export, exact: &Table, half_unit: f64, out: &Path) -> Result<f64> {
    let w = ex.axes[0].count;
    let mut worst = 0.0f64;
    for k in 0..w * ex.axes[1].count {
        for (c, exv) in [&exact.a, &exact.b].into_iter().enumerate() {
            let (t, x) = (ex.tex[c][k], exv[k]);
            let e = (t - x).abs();
            if e > enc(half_unit, x) {
                bail!(
                    "{}: texel ({}, {}) channel {c} is {t}, the integral at its node {x} \
                     (error {e:e} > encoding bound {:e}): wrong value or placement",
                    out.display(),
                    k % w,
                    k / w,
                    enc(half_unit, x)
                );
            }
            worst = worst.max(e);
        }
    }
    Ok(worst)
}

/// The test's points, as the f32 values the shader receives: every 20th outside the table
/// (the function clamps to the axis ranges), the rest alternately uniform in the warped
/// coordinate (dense at grazing μ) and uniform in μ.
fn random_points(axes: &[Mapping; 2]) -> Vec<(f64, f64)> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x0EB6_1012);
    let (m0, m1) = (&axes[0], &axes[1]);
    (0..POINTS)
        .map(|k| {
            let (x, y) = if k % 20 == 19 {
                let x = if rng.random_bool(0.5) {
                    rng.random_range(0.0..m0.lo)
                } else {
                    rng.random_range(m0.hi..m0.hi + 0.05)
                };
                (x, rng.random_range(m1.lo - 0.05..m1.hi + 0.05))
            } else if k % 2 == 0 {
                (
                    m0.node_at(rng.random_range(0.0..1.0)),
                    rng.random_range(m1.lo..m1.hi),
                )
            } else {
                (
                    rng.random_range(m0.lo..m0.hi),
                    rng.random_range(m1.lo..m1.hi),
                )
            };
            (x as f32 as f64, y as f32 as f64)
        })
        .collect()
}

/// Per point: the JSON row `[x, y, A, B, bound A, bound B, A_lin, B_lin]`, the larger bound
/// and the larger bilinear error of the exact grid (the bound is the doc of
/// [`prepare_native`]).
fn point_rows(
    ex: &Export,
    exact: &Table,
    half_unit: f64,
    pts: &[(f64, f64)],
) -> Vec<(serde_json::Value, f64, f64)> {
    let (m0, m1) = (&ex.axes[0], &ex.axes[1]);
    let w = m0.count;
    // Spread of the four texels the filter reads, and their largest encoding bound.
    let spread = |u: f64, v: f64| {
        let ix = |c: f64| {
            let p = (c * w as f64 - 0.5).clamp(0.0, (w - 1) as f64);
            let i0 = p.floor() as usize;
            (i0, (i0 + 1).min(w - 1))
        };
        let ((x0, x1), (y0, y1)) = (ix(u), ix(v));
        let idx = [y0 * w + x0, y0 * w + x1, y1 * w + x0, y1 * w + x1];
        let f = |t: &[f64]| {
            let s = idx.map(|i| t[i]);
            let mx = s.iter().cloned().fold(f64::MIN, f64::max);
            let mn = s.iter().cloned().fold(f64::MAX, f64::min);
            mx - mn
        };
        let g = |t: &[f64]| {
            idx.iter()
                .map(|&i| enc(half_unit, t[i]))
                .fold(0.0, f64::max)
        };
        ((f(&ex.tex[0]), f(&ex.tex[1])), (g(&exact.a), g(&exact.b)))
    };
    pts.par_iter()
        .map(|&(x, y)| {
            let (xc, yc) = (m0.clamp(x), m1.clamp(y));
            let (a, b) = integral(xc, yc);
            let (u, v) = (m0.coord(xc), m1.coord(yc));
            let (xa, xb) = exact.sample(u, v);
            let ((sa, sb), (ea, eb)) = spread(u, v);
            let k = 2.0 * 2f64.powi(-9) + 2.0 * COORD_TEXELS;
            let bound_a = (xa - a).abs() + ea + sa * k + 1e-6;
            let bound_b = (xb - b).abs() + eb + sb * k + 1e-6;
            (
                serde_json::json!([x, y, a, b, bound_a, bound_b, xa, xb]),
                bound_a.max(bound_b),
                (xa - a).abs().max((xb - b).abs()),
            )
        })
        .collect()
}

/// Runs `cargo xtask lut export ASSET --raw-f16 -o OUT --force` in this process.
fn export_in_process(asset: &Path, out: &Path) -> Result<()> {
    use clap::{Args as _, FromArgMatches as _};
    let cmd = crate::lut::Args::augment_args(clap::Command::new("lut"));
    let m = cmd.try_get_matches_from([
        "lut".as_ref(),
        "export".as_ref(),
        asset.as_os_str(),
        "--raw-f16".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
        "--force".as_ref(),
    ])?;
    crate::lut::run(crate::lut::Args::from_arg_matches(&m)?)
}

/// Half an IEEE binary16 ulp at |v|: 2^(e − 11) for 2^e ≤ |v| < 2^(e+1) (normal range,
/// e ≥ −14), 2⁻²⁵ below; taken at |v|·(1 + 2⁻¹⁰) so a value just under a power of two that
/// rounds up to it is covered.
fn half_ulp_f16(v: f64) -> f64 {
    let a = v.abs() * (1.0 + 2f64.powi(-10));
    if a < 2f64.powi(-14) {
        2f64.powi(-25)
    } else {
        2f64.powi(a.log2().floor() as i32 - 11)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the `half` crate's round-to-nearest f32 → f16 conversion: the error of every
    /// value tried is within the half ulp stated, and the half ulp is at most twice that
    /// error's largest possible value (2⁻¹¹ relative), so the bound is not loose.
    #[test]
    fn half_ulp_f16_covers_the_rounding_error() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        for k in 0..100_000 {
            let v: f64 = if k < 10 {
                [
                    0.0,
                    1.0,
                    0.5,
                    1.0 - 1e-9,
                    0.999_8,
                    6.1e-5,
                    6.0e-5,
                    2.0,
                    1e-8,
                    0.25,
                ][k]
            } else {
                rng.random_range(-20.0f64..1.0).exp2()
            };
            // From f32, as the exporter converts (f64 → f16 in `half` may round twice).
            let v = v as f32 as f64;
            let r = half::f16::from_f32(v as f32).to_f64();
            let h = half_ulp_f16(v);
            assert!((r - v).abs() <= h, "{v}: {r} {h}");
            assert!(h <= v.abs() * 2f64.powi(-10) + 2f64.powi(-25), "{v}: {h}");
        }
    }
}

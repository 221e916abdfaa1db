//! Inputs of the WebGL2 engine-LUT tests (examples/web/test/lut_engine.test.mjs,
//! lut_sheen_glass.test.mjs): the tables as the engines' files hold them, with their GLSL
//! functions, and random points with the f64 integral and the error bound the GPU sample
//! must meet.

use anyhow::{bail, Context, Result};
use brdf_engine_assets::export::{export, Format};
use brdf_engine_assets::fsio::{write_together, Policy};
use brdf_engine_assets::report::Table;
use brdf_engine_assets::sidecar::Mapping;
use brdf_engine_assets::{centre, integral, File as OutFile};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::path::Path;

/// Table edge of the browser test.
pub const N: usize = 64;
/// Points sampled by the fragment shader (a 64 × 32 render target).
pub const POINTS: usize = 2048;

/// Writes `dir/lut_ggx.png`, `dir/lut_ggx.glsl`, … and `dir/points.json`.
pub fn prepare(dir: &Path) -> Result<()> {
    let grid = brdf_engine_assets::split_sum_texels(N, &|_| {})?;
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
    write_set(dir, &files)
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
    let asset = crate::workspace_root().join("assets").join(NATIVE_ASSET);
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let out = dir.join(NATIVE_EXPORT);
    export_raw_f16(&asset, &out)?;
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
    let lut = brdf_engine_assets::fsio::load_lut(asset)?;
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

/// `lut export ASSET --raw-f16 -o OUT --force`: the library's export (the one `cargo xtask
/// lut export` writes) as `out`, `out.json`, `out.glsl` and `out.wgsl`.
fn export_raw_f16(asset: &Path, out: &Path) -> Result<()> {
    let lut = brdf_engine_assets::fsio::load_lut(asset)?;
    let name = |p: &Path| {
        p.file_name()
            .map_or(String::new(), |s| s.to_string_lossy().into())
    };
    let e = export(&lut.view()?, Format::RawF16, &name(out), &name(asset))?;
    let (glsl, wgsl) = e.shaders.context("a 2-D table's export has shaders")?;
    let with = |ext: &str| format!("{}{ext}", name(out));
    let files = [
        (name(out), e.texture),
        (with(".json"), e.sidecar),
        (with(".glsl"), glsl.into_bytes()),
        (with(".wgsl"), wgsl.into_bytes()),
    ];
    let files = files.map(|(name, bytes)| OutFile { name, bytes });
    write_set(out.parent().context("an output folder")?, &files)
}

/// Writes a test's files into `dir` (created when missing) through the library's safe
/// writer, replacing the previous run's; `assets/` is never written.
fn write_set(dir: &Path, files: &[OutFile]) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let files: Vec<_> = files
        .iter()
        .map(|f| (dir.join(&f.name), f.bytes.clone()))
        .collect();
    let policy = Policy {
        force: true,
        inputs: Vec::new(),
        protected: Some(crate::workspace_root().join("assets")),
    };
    Ok(write_together(&files, &policy)?)
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

/// Edge of the sheen textures of the browser test: the texels cost about 0.9 ms each
/// ([`brdf_engine_assets::sheen_texels`]), 64² ≈ 4 s on one core.
pub const SHEEN_N: usize = 64;
/// Edge of the rough-glass 3-D texture of the browser test (about 10 ms a node; not a power
/// of two, so the upload's row and slice strides are exercised).
pub const GLASS_N: usize = 12;
/// The GPU's filter weights: 8 fractional bits, error ≤ 2⁻⁹ per axis (as in [`prepare`]).
const WEIGHT: f64 = 1.0 / 512.0;
/// f32 blend and decode of values ≤ 1 in the shader.
const F32_BLEND: f64 = 1e-6;

/// Multilinear lookup between texel centres with clamp to edge, as GL's LINEAR +
/// CLAMP_TO_EDGE on a D-dimensional texture of `dims` (axis 0 fastest): per axis
/// p = clamp(x·n − ½, 0, n − 1), corners ⌊p⌋ and ⌊p⌋ + 1 (clamped), weight p − ⌊p⌋.
/// Returns the value and the smallest and largest of the 2^D texels read.
fn lerp_nd<const D: usize>(dims: [usize; D], v: &[f64], x: [f64; D]) -> (f64, f64, f64) {
    let mut lo = [0usize; D];
    let mut hi = [0usize; D];
    let mut f = [0.0f64; D];
    for k in 0..D {
        let n = dims[k];
        let p = (x[k] * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        lo[k] = (p.floor() as usize).min(n - 1);
        hi[k] = (lo[k] + 1).min(n - 1);
        f[k] = p - lo[k] as f64;
    }
    let (mut sum, mut mn, mut mx) = (0.0, f64::MAX, f64::MIN);
    for corner in 0..1usize << D {
        let (mut idx, mut stride, mut w) = (0, 1, 1.0);
        for k in 0..D {
            let up = corner >> k & 1 == 1;
            idx += stride * if up { hi[k] } else { lo[k] };
            w *= if up { f[k] } else { 1.0 - f[k] };
            stride *= dims[k];
        }
        sum += w * v[idx];
        mn = mn.min(v[idx]);
        mx = mx.max(v[idx]);
    }
    (sum, mn, mx)
}

/// One channel of an n × n PNG, decoded by the `png` crate (not the writer's code) as
/// code / (2^depth − 1); `chan` the channel index, `want` the expected bit depth.
fn png_channel(bytes: &[u8], n: usize, chan: usize, want: png::BitDepth) -> Result<Vec<f64>> {
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    dec.set_transformations(png::Transformations::IDENTITY);
    let mut rd = dec.read_info()?;
    let info = rd.info();
    if (info.width as usize, info.height as usize) != (n, n)
        || info.color_type != png::ColorType::Rgb
        || info.bit_depth != want
    {
        bail!(
            "png: {}×{} {:?} {:?}, expected {n}×{n} Rgb {want:?}",
            info.width,
            info.height,
            info.color_type,
            info.bit_depth
        );
    }
    let mut buf = vec![0; rd.output_buffer_size()];
    rd.next_frame(&mut buf)?;
    Ok((0..n * n)
        .map(|i| match want {
            png::BitDepth::Eight => buf[i * 3 + chan] as f64 / 255.0,
            _ => {
                u16::from_be_bytes([buf[(i * 3 + chan) * 2], buf[(i * 3 + chan) * 2 + 1]]) as f64
                    / 65535.0
            }
        })
        .collect())
}

/// A sheen texture of the test: the exact texels (f64 integral at the texel centres,
/// clamped to [0, 1] as the UNORM encoding clamps), the values decoded from the PNG and the
/// half unit of its encoding (for R16F, plus the f16 rounding at the largest texel read).
struct SheenTex {
    exact: Vec<f64>,
    stored: Vec<f64>,
    half_unit: f64,
    f16: bool,
}

impl SheenTex {
    /// Checks every stored texel against the exact one within half a unit.
    fn new(exact: &[f64], stored: Vec<f64>, half_unit: f64, f16: bool, what: &str) -> Result<Self> {
        let exact: Vec<f64> = exact.iter().map(|v| v.clamp(0.0, 1.0)).collect();
        for (k, (s, x)) in stored.iter().zip(&exact).enumerate() {
            if (s - x).abs() > half_unit * (1.0 + 1e-9) {
                bail!("{what}: texel {k} stores {s}, the integral at its centre {x}");
            }
        }
        Ok(Self {
            exact,
            stored,
            half_unit,
            f16,
        })
    }

    /// At (μ, r) with `e` the converged value clamped to [0, 1]: (bound against e, GPU-side
    /// table value, bound against it). The first bound is the doc of [`prepare_sheen`]; the
    /// second drops the interpolation and encoding terms (the f16 rounding of the upload
    /// stays).
    fn bounds(&self, mu: f64, r: f64, e: f64) -> [f64; 3] {
        let (x, _, _) = lerp_nd([SHEEN_N; 2], &self.exact, [mu, r]);
        let (s, mn, mx) = lerp_nd([SHEEN_N; 2], &self.stored, [mu, r]);
        let h16 = if self.f16 { half_ulp_f16(mx) } else { 0.0 };
        // Spread of the values the GPU blends: the stored ones moved by the f16 rounding.
        let spread = mx - mn + 2.0 * h16;
        let weights = 2.0 * WEIGHT * spread;
        [
            (x - e).abs() + self.half_unit + h16 + weights + F32_BLEND,
            s,
            h16 + weights + F32_BLEND,
        ]
    }
}

/// Writes, into `dir`, the Khronos sheen textures at [`SHEEN_N`]² (`lut_charlie.png`,
/// `lut_sheen_E.png`, sidecars: `brdf_engine_assets::khronos_sheen` of `sheen_texels`) and
/// `sheen_points.json`: [`POINTS`] random (μ, r) (f32 values, inside the texel-centre
/// square), each `[μ, r, E_ek, E_ash, bound_ek, bound_ash, S_ek, S_ash, b_ek, b_ash]`:
/// E = min(1, the converged sheen albedo at the point) (`brdf_lut::generate::sheen_e` at
/// its 2e-6 tolerance; ek = Estevez–Kulla, sampled from lut_sheen_E.png's R, ash =
/// Ashikhmin from lut_charlie.png's B; the UNORM textures hold min(1, E) by design, their
/// sidecars say so), S the bilinear value of the texels decoded from the PNGs (`png` crate)
/// and b the bound of |GPU − S|.
///
/// The bound against E is the sum of
/// - the bilinear error of the exact texels clamped to [0, 1]: |bilinear − E|;
/// - half a unit of the encoding: 1/510 (8-bit) or 1/131070 (16-bit), plus for
///   lut_sheen_E.png half an f16 ulp at the largest texel read: the test uploads the 16-bit
///   codes as R16F (browsers decode 16-bit PNGs to 8 bits, and 16-bit UNORM is not
///   filterable in WebGL2), each code / 65535 rounded to nearest binary16 by `Float16Array`;
/// - the filter weights, 2 axes × 2⁻⁹ × the spread of the four texels read;
/// - 1e-6 for the shader's f32 arithmetic.
pub fn prepare_sheen(dir: &Path) -> Result<()> {
    let n = SHEEN_N;
    let [ek, ash] = brdf_engine_assets::sheen_texels(n)?;
    let mut files = brdf_engine_assets::khronos_sheen(n, &ek, &ash)?;
    let get = |name: &str| {
        files
            .iter()
            .find(|f| f.name == name)
            .map(|f| f.bytes.clone())
            .with_context(|| format!("khronos_sheen wrote no {name}"))
    };
    let charlie = png_channel(&get("lut_charlie.png")?, n, 2, png::BitDepth::Eight)?;
    let sheen_e = png_channel(&get("lut_sheen_E.png")?, n, 0, png::BitDepth::Sixteen)?;
    let tex = [
        SheenTex::new(&ek, sheen_e, 0.5 / 65535.0, true, "lut_sheen_E.png")?,
        SheenTex::new(&ash, charlie, 0.5 / 255.0, false, "lut_charlie.png")?,
    ];
    let lo = centre(0, n);
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x0EB6_1013);
    let pts: Vec<(f64, f64)> = (0..POINTS)
        .map(|_| {
            let mut u = || rng.random_range(lo..1.0 - lo) as f32 as f64;
            (u(), u())
        })
        .collect();
    let (rows, over): (Vec<serde_json::Value>, Vec<[bool; 2]>) = pts
        .par_iter()
        .map(|&(mu, r)| {
            let raw = brdf_lut::generate::sheen_e(mu, r, brdf_lut::generate::SHEEN_TOL).value;
            let e = raw.map(|v| v.clamp(0.0, 1.0));
            let [a0, s0, b0] = tex[0].bounds(mu, r, e[0]);
            let [a1, s1, b1] = tex[1].bounds(mu, r, e[1]);
            let row = serde_json::json!([mu, r, e[0], e[1], a0, a1, s0, s1, b0, b1]);
            (row, raw.map(|v| v > 1.0))
        })
        .unzip();
    let count = |c: usize| over.iter().filter(|o| o[c]).count();
    println!(
        "web: sheen {n}²: E above 1 (stored as 1) at {} (Estevez–Kulla) and {} (Ashikhmin) \
         of {POINTS} points",
        count(0),
        count(1)
    );
    files.push(OutFile {
        name: "sheen_points.json".into(),
        bytes: serde_json::to_vec(&serde_json::json!({ "n": n, "points": rows }))?,
    });
    write_set(dir, &files)
}

/// Coordinate error of `GlassAlbedoTable::rt`'s f32 arithmetic (η = lo + (hi − lo)w rounded to f32,
/// then (η − lo)/(hi − lo)·n − ½), in texels per axis: a few f32 ulps of values ≤ 3 times
/// n ≤ 256 is below 1e-4.
const RT_COORD_TEXELS: f64 = 1e-4;

/// Writes, into `dir`, the rough-glass textures (`brdf_engine_assets::glass`) for both
/// directions of light, from outside (η ∈ [1, 3]) and from inside (`_inv`, η ∈ [1/3, 1]):
/// E at [`GLASS_N`]³ (`glass_e`: μ, r, η) and E_avg at [`GLASS_N`]² (`glass_e_avg`: r, η).
/// Per table: its files, `<stem>.rg16f.bin` (the KTX2's level 0, Zstandard-decoded here,
/// checked equal to the BLUT payload: texel (x, y[, z]) at byte 4(x + N(y [+ N z])), R then
/// G as little-endian binary16) and `<stem>_points.json`: [`POINTS`] random texture
/// coordinates (the last one (η − lo)/(hi − lo)) as f32, every 20th outside the unit box
/// (clamp to edge), each `[coordinates…, R, T, bound R, bound T, R_blut, T_blut, b_R, b_T]`:
/// (R, T) the multilinear value in f64 of the f16 texels (clamp to edge), bound = D axes ×
/// 2⁻⁹ × the spread of the texels read + 1e-6 (f32 blend; the f16 texels are exact in f32);
/// (R, T)_blut = the BLUT's typed lookup (`GlassAlbedoTable::rt`, `GlassAverageTable::rt_avg`),
/// checked here within b = D × [`RT_COORD_TEXELS`] × spread + 1e-6 of the multilinear value
/// (its axis map is the texture's: texel centres, linear, clamped).
pub fn prepare_glass(dir: &Path) -> Result<()> {
    for inside in [false, true] {
        glass_set::<3>(dir, inside)?;
        glass_set::<2>(dir, inside)?;
    }
    Ok(())
}

/// The typed BLUT lookup of a glass table at texture coordinates with η physical.
type GlassLookup<'a> = Box<dyn Fn(&[f32]) -> (f32, f32) + 'a>;

/// One table of [`prepare_glass`]: D = 3 (E) or 2 (E_avg).
fn glass_set<const D: usize>(dir: &Path, inside: bool) -> Result<()> {
    let n = GLASS_N;
    let stem = match (D, inside) {
        (3, false) => "glass_e",
        (3, true) => "glass_e_inv",
        (_, false) => "glass_e_avg",
        (_, true) => "glass_e_avg_inv",
    };
    let mut files = brdf_engine_assets::glass(&[n; D], inside, &|_| {})?;
    let get = |name: String| {
        files
            .iter()
            .find(|f| f.name == name)
            .map(|f| f.bytes.clone())
            .with_context(|| format!("glass wrote no {name}"))
    };
    let level = ktx2_level0(&get(format!("{stem}.ktx2"))?, n, D)?;
    let blut_bytes = get(format!("{stem}.blut"))?;
    if brdf_lut::LutView::parse(&blut_bytes[..])?.payload() != &level[..] {
        bail!("{stem}.ktx2: level 0 differs from the BLUT payload");
    }
    let lookup: GlassLookup = if D == 3 {
        let t = brdf_lut::GlassAlbedoTable::parse(&blut_bytes[..])?;
        Box::new(move |x| t.rt(x[0], x[1], x[2]))
    } else {
        let t = brdf_lut::GlassAverageTable::parse(&blut_bytes[..])?;
        Box::new(move |x| t.rt_avg(x[0], x[1]))
    };
    let f = |o: usize| half::f16::from_le_bytes([level[o], level[o + 1]]).to_f64();
    let texels = n.pow(D as u32);
    let rt: [Vec<f64>; 2] = [0, 2].map(|c| (0..texels).map(|k| f(4 * k + c)).collect());
    let eta = if inside { (1.0 / 3.0, 1.0) } else { (1.0, 3.0) };
    let rows = glass_points::<D>()
        .iter()
        .map(|&x| glass_row(&rt, &lookup, eta, x))
        .collect::<Result<Vec<_>>>()?;
    files.push(OutFile {
        name: format!("{stem}.rg16f.bin"),
        bytes: level,
    });
    files.push(OutFile {
        name: format!("{stem}_points.json"),
        bytes: serde_json::to_vec(&serde_json::json!({ "n": vec![n; D], "points": rows }))?,
    });
    write_set(dir, &files)
}

/// Level 0 of a Zstandard-supercompressed R16G16_SFLOAT texture of `d` axes of n texels
/// (d = 3: n³; d = 2: n², depth 0), decompressed.
fn ktx2_level0(bytes: &[u8], n: usize, d: usize) -> Result<Vec<u8>> {
    let rd = ktx2::Reader::new(bytes).map_err(|e| anyhow::anyhow!("ktx2: {e:?}"))?;
    let h = rd.header();
    let dims = [h.pixel_width, h.pixel_height, h.pixel_depth].map(|d| d as usize);
    let want = [n, n, if d == 3 { n } else { 0 }];
    if h.format != Some(ktx2::Format::R16G16_SFLOAT)
        || dims != want
        || h.supercompression_scheme != Some(ktx2::SupercompressionScheme::Zstandard)
    {
        bail!("ktx2: expected a zstd R16G16_SFLOAT {want:?} texture, got {dims:?}");
    }
    let lv = rd.levels().next().context("ktx2: no level")?;
    let raw = zstd::decode_all(lv.data)?;
    let bytes = n.pow(d as u32) * 4;
    if raw.len() != bytes {
        bail!("ktx2: level 0 is {} bytes, expected {bytes}", raw.len());
    }
    Ok(raw)
}

/// The glass test's texture coordinates as f32: every 20th with each coordinate in
/// [−0.05, 1.05] (outside the texel-centre range, often outside [0, 1]), the rest uniform.
fn glass_points<const D: usize>() -> Vec<[f64; D]> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x0EB6_1014);
    (0..POINTS)
        .map(|k| {
            let (a, b) = if k % 20 == 19 {
                (-0.05, 1.05)
            } else {
                (0.0, 1.0)
            };
            [0; D].map(|_| rng.random_range(a..b) as f32 as f64)
        })
        .collect()
}

/// One row of `<stem>_points.json` (doc of [`prepare_glass`]) for the table over
/// η ∈ [lo, hi] (the last coordinate); fails when the BLUT lookup leaves its bound.
fn glass_row<const D: usize>(
    rt: &[Vec<f64>; 2],
    lookup: &GlassLookup,
    (lo, hi): (f64, f64),
    x: [f64; D],
) -> Result<serde_json::Value> {
    let mut at: Vec<f32> = x.iter().map(|&v| v as f32).collect();
    at[D - 1] = (lo + (hi - lo) * x[D - 1]) as f32;
    let (br, bt) = lookup(&at);
    let mut out = [[0.0f64; 2]; 4];
    for (c, b) in [(0, br as f64), (1, bt as f64)] {
        let (v, mn, mx) = lerp_nd([GLASS_N; D], &rt[c], x);
        let gpu = D as f64 * WEIGHT * (mx - mn) + F32_BLEND;
        let brt = D as f64 * RT_COORD_TEXELS * (mx - mn) + F32_BLEND;
        if (b - v).abs() > brt {
            bail!(
                "glass BLUT over η ∈ [{lo}, {hi}]: lookup at {x:?} channel {c} is {b}, the \
                 texture's multilinear value {v} (bound {brt:e}): the axis maps differ"
            );
        }
        for (k, y) in [v, gpu, b, brt].into_iter().enumerate() {
            out[k][c] = y;
        }
    }
    let mut row: Vec<f64> = x.to_vec();
    row.extend(out.iter().flatten());
    Ok(serde_json::json!(row))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `lerp_nd` in 2-D equals `report::Table::sample` (a separate bilinear with clamp to
    /// edge) at random points in and around [0, 1]²; in 3-D it reproduces an affine function
    /// of the texel coordinates inside the texel-centre box (multilinear interpolation is
    /// exact on affine functions) and the edge texels' values outside it.
    #[test]
    fn lerp_nd_matches_bilinear_and_is_exact_on_affine() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let n = 5;
        let a: Vec<f64> = (0..n * n).map(|_| rng.random_range(0.0..1.0)).collect();
        let t = Table {
            n,
            a: a.clone(),
            b: a.clone(),
        };
        for _ in 0..1000 {
            let (x, y) = (rng.random_range(-0.2..1.2), rng.random_range(-0.2..1.2));
            let (v, mn, mx) = lerp_nd([n; 2], &a, [x, y]);
            assert!((v - t.sample(x, y).0).abs() < 1e-12, "{x} {y}");
            assert!(mn <= v + 1e-12 && v <= mx + 1e-12);
        }
        let d = [3, 4, 6];
        let f = |p: [f64; 3]| 0.3 + 0.1 * p[0] - 0.2 * p[1] + 0.05 * p[2];
        let v: Vec<f64> = (0..72)
            .map(|k| f([(k % 3) as f64, (k / 3 % 4) as f64, (k / 12) as f64]))
            .collect();
        for _ in 0..1000 {
            let x: [f64; 3] = [0; 3].map(|_| rng.random_range(-0.3..1.3));
            // Texel coordinate, clamped to the centre box as clamp-to-edge does.
            let p = [0, 1, 2].map(|k| (x[k] * d[k] as f64 - 0.5).clamp(0.0, (d[k] - 1) as f64));
            assert!((lerp_nd(d, &v, x).0 - f(p)).abs() < 1e-12, "{x:?}");
        }
    }

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

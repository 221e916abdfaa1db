//! One function per engine layout: the data files in the engine's container, channel
//! layout and orientation, then the JSON sidecar and the GLSL/WGSL samplers.

use crate::containers::{dds_rgba16f, exr_rg32f, half_bits, ktx2_rg16f, png, unorm16, unorm8};
use crate::{centre, shaders, Engine, Error, File, SplitSumTexels};
use brdf_lut::generate;
use serde_json::{json, Map, Value};

use crate::Result;

/// What a layout adds to the common sidecar: the data files' descriptions and the
/// engine-specific keys (encoding, orientation, …).
struct Described {
    files: Vec<File>,
    data_files: Map<String, Value>,
    extra: Map<String, Value>,
}

impl Described {
    fn new() -> Self {
        Described {
            files: Vec::new(),
            data_files: Map::new(),
            extra: Map::new(),
        }
    }
    fn file(&mut self, name: &str, bytes: Vec<u8>, what: &str) {
        self.data_files.insert(name.into(), json!(what));
        self.files.push(File {
            name: name.into(),
            bytes,
        });
    }
    fn key(&mut self, k: &str, v: &str) {
        self.extra.insert(k.into(), json!(v));
    }
}

/// glTF Sample Viewer: `lut_ggx.png` (RGB 8-bit, as the viewer ships it), a 16-bit RGB PNG
/// and single-channel 16-bit PNGs of A and B; μ along x, r down the rows.
pub fn khronos(g: &SplitSumTexels) -> Result<Vec<File>> {
    let n = g.n;
    let mut rgb8 = Vec::with_capacity(n * n * 3);
    let mut rgb16 = Vec::with_capacity(n * n * 6);
    let (mut a16, mut b16) = (Vec::with_capacity(n * n * 2), Vec::with_capacity(n * n * 2));
    for i in 0..n * n {
        rgb8.extend_from_slice(&[unorm8(g.a[i]), unorm8(g.b[i]), 0]);
        let (x, y) = (unorm16(g.a[i]).to_be_bytes(), unorm16(g.b[i]).to_be_bytes());
        rgb16.extend_from_slice(&x);
        rgb16.extend_from_slice(&y);
        rgb16.extend_from_slice(&[0, 0]);
        a16.extend_from_slice(&x);
        b16.extend_from_slice(&y);
    }
    use png::{BitDepth::*, ColorType::*};
    let mut d = Described::new();
    for (name, color, depth, data, what) in [
        (
            "lut_ggx.png",
            Rgb,
            Eight,
            &rgb8,
            "RGB 8-bit: R = A, G = B, B = 0 (as the viewer ships it)",
        ),
        (
            "lut_ggx_16bit.png",
            Rgb,
            Sixteen,
            &rgb16,
            "RGB 16-bit: R = A, G = B, B = 0",
        ),
        (
            "lut_ggx_A_16bit.png",
            Grayscale,
            Sixteen,
            &a16,
            "grey 16-bit: A",
        ),
        (
            "lut_ggx_B_16bit.png",
            Grayscale,
            Sixteen,
            &b16,
            "grey 16-bit: B",
        ),
    ] {
        d.file(name, png(n, n, color, depth, data)?, what);
    }
    d.key("encoding", "UNORM: code = round(v · 255) (8-bit) or round(v · 65535) (16-bit); value = code / (2^bits − 1)");
    d.key("loaders", "Pillow (PIL) opens 16-bit RGB PNGs as 8-bit RGB without a warning, dropping the low 8 bits: read lut_ggx_A_16bit.png and lut_ggx_B_16bit.png (single-channel 16-bit, mode I;16 in Pillow) instead, or use a loader that keeps 16 bits (png, imageio, OpenCV with IMREAD_UNCHANGED). Browsers decode 16-bit PNGs to 8 bits.");
    d.key("orientation", "column x: mu = (x + 0.5)/N; PNG row y (top row first): r = (y + 0.5)/N. Uploaded without a vertical flip (first stored row at t = 0), the shader samples uv = (mu, r).");
    finish(Engine::Khronos, g, "lut_ggx", d)
}

/// Bevy: `dfg.ktx2`, R16G16_SFLOAT (R = A, G = B), Zstandard, row 0 = smallest r.
pub fn bevy(g: &SplitSumTexels) -> Result<Vec<File>> {
    let n = g.n;
    let mut tex = Vec::with_capacity(n * n * 4);
    for i in 0..n * n {
        tex.extend_from_slice(&half_bits(g.a[i]).to_le_bytes());
        tex.extend_from_slice(&half_bits(g.b[i]).to_le_bytes());
    }
    let mut d = Described::new();
    d.file("dfg.ktx2", ktx2_rg16f(n, &tex)?, "KTX2, vkFormat 83 = R16G16_SFLOAT, 1 level, Zstandard supercompression (level 22): R = A, G = B");
    d.key("encoding", "IEEE binary16, round to nearest even");
    d.key("orientation", "KTXorientation rd: row 0 (first stored) holds r = 0.5/N, column x holds mu = (x + 0.5)/N; the shader samples uv = (mu, r).");
    finish(Engine::Bevy, g, "dfg", d)
}

/// Filament: `dfg_multiscatter.dds`, RGBA16F with R = B, G = A + B, B = 0, rows stored
/// bottom-up as Filament's loader expects ([`filament_cloth`] fills B).
pub fn filament(g: &SplitSumTexels) -> Result<Vec<File>> {
    filament_dds(g, None)
}

/// Absolute tolerance of the cloth channel of [`filament_cloth`]: below half an f16 step for
/// every value ≥ 2^-6 (half a step there is 2^-6 · 2^-11 = 7.6e-6).
pub const CLOTH_TOL: f64 = 7e-6;

/// Filament with its cloth channel: [`filament`]'s texture with B = the sheen albedo with
/// Ashikhmin's visibility (cmgen's `DFV_Charlie`: Charlie D at α = r², V = 1/(4(μ + μl −
/// μ μl)); docs/engines.md, "Sheen") at the same texel centres, interpolated from converged
/// nodes by `brdf_lut::generate::sheen_grid` to [`CLOTH_TOL`]; the sidecar records its
/// estimated bound.
pub fn filament_cloth(g: &SplitSumTexels) -> Result<Vec<File>> {
    let s = brdf_lut::generate::sheen_grid(g.n, [SHEEN_TEXEL_TOL[1], CLOTH_TOL]);
    let [_, cloth] = &s.values;
    if cloth.len() != g.n * g.n {
        return Err(Error::Size(g.n));
    }
    filament_dds(g, Some((cloth, s.bound[1])))
}

/// The Filament texture with B = `cloth` (values, estimated bound) or 0.
fn filament_dds(g: &SplitSumTexels, cloth: Option<(&[f64], f64)>) -> Result<Vec<File>> {
    let n = g.n;
    let mut tex = Vec::with_capacity(n * n * 8);
    for y in 0..n {
        let row = n - 1 - y; // file row y (top-down) holds r = (N − y − ½)/N
        for x in 0..n {
            let i = row * n + x;
            let c = cloth.map_or(0.0, |(v, _)| v[i]);
            for v in [g.b[i], g.a[i] + g.b[i], c, 1.0] {
                tex.extend_from_slice(&half_bits(v).to_le_bytes());
            }
        }
    }
    let mut d = Described::new();
    let b = if cloth.is_some() {
        "B = cloth: the sheen albedo with Ashikhmin's visibility (Charlie D, alpha = r^2), A = 1"
    } else {
        "B = 0, A = 1"
    };
    d.file("dfg_multiscatter.dds", dds_rgba16f(n, &tex)?, &format!("DDS with DX10 header, DXGI_FORMAT_R16G16B16A16_FLOAT (10): R = B, G = A + B, {b} (A = G − R)"));
    if let Some((_, bound)) = cloth {
        d.key(
            "cloth_estimated_error",
            &format!("{bound:.2e} (largest estimate of |B − the integral| before f16 rounding; brdf_lut::generate::sheen_grid)"),
        );
    }
    d.key(
        "encoding",
        "IEEE binary16, round to nearest even; G = A + B is summed in f64 before rounding",
    );
    d.key("orientation", "column x: mu = (x + 0.5)/N; stored row y (top-down in the file): r = (N − y − 0.5)/N, so the GL row j = N − 1 − y that Filament's loader places at t = (j + 0.5)/N holds r = t and the shader's uv = (NoV, perceptualRoughness) reads the value at its own roughness. Filament's cmgen writes r = (N − y + 0.5)/N, one texel higher (top two GL rows both r = 1).");
    finish(Engine::Filament, g, "dfg_multiscatter", d)
}

/// three.js: `dfg_lut.bin`, raw little-endian RG16F pairs (A, B) with memory row = μ, and
/// the same half-float bits as an ES module `dfg_lut.js`.
pub fn threejs(g: &SplitSumTexels) -> Result<Vec<File>> {
    let n = g.n;
    let mut bin = Vec::with_capacity(n * n * 4);
    let mut words = Vec::with_capacity(n * n * 2);
    for imu in 0..n {
        for ir in 0..n {
            let i = ir * n + imu;
            for v in [g.a[i], g.b[i]] {
                let h = half_bits(v);
                bin.extend_from_slice(&h.to_le_bytes());
                words.push(h);
            }
        }
    }
    let data: String = words
        .chunks(16)
        .map(|c| {
            let s: Vec<String> = c.iter().map(|w| format!("0x{w:04x}")).collect();
            format!("  {},\n", s.join(", "))
        })
        .collect();
    let js = format!(
        "// Split-sum (A, B) for GGX with height-correlated Smith, alpha = r * r, as RG16F\n\
         // half-float bits: {n} x {n}, memory row = dot(N, V) index, column = roughness index,\n\
         // both at texel centres. Generated by `cargo xtask lut engine threejs`; see dfg_lut.json.\n\
         export const DFG_LUT_SIZE = {n};\n\
         export const DFG_LUT_DATA = new Uint16Array([\n\
         {data}]);\n"
    );
    let mut d = Described::new();
    d.file(
        "dfg_lut.bin",
        bin,
        "raw little-endian binary16 pairs (A, B), no header",
    );
    d.file("dfg_lut.js", js.into_bytes(), "ES module: DFG_LUT_SIZE, DFG_LUT_DATA (Uint16Array of the same half-float bits) for a DataTexture(RGFormat, HalfFloatType)");
    d.key("encoding", "IEEE binary16, round to nearest even");
    d.key("orientation", "memory row m: mu = (m + 0.5)/N; column c: r = (c + 0.5)/N. Uploaded as a texture (first row at t = 0) the shader samples uv = (roughness, dotNV).");
    finish(Engine::Threejs, g, "dfg_lut", d)
}

/// OpenEXR: `dfg_ggx.exr`, 32-bit float R = A, G = B, μ along x, r down the rows.
pub fn exr(g: &SplitSumTexels) -> Result<Vec<File>> {
    let mut d = Described::new();
    d.file(
        "dfg_ggx.exr",
        exr_rg32f(g)?,
        "OpenEXR, 32-bit float channels R = A, G = B, ZIP compression, one part",
    );
    d.key("encoding", "IEEE binary32, round to nearest even, of the f64 quadrature value (its measured error against an independent converged reference: `accuracy`)");
    d.key("orientation", "column x: mu = (x + 0.5)/N; row y (data window top = y 0): r = (y + 0.5)/N. Uploaded with row 0 at t = 0, the shader samples uv = (mu, r).");
    finish(Engine::Exr, g, "dfg_ggx", d)
}

/// Appends the sidecar `{stem}.json` and the samplers `{stem}.glsl`, `{stem}.wgsl`.
fn finish(e: Engine, g: &SplitSumTexels, stem: &str, d: Described) -> Result<Vec<File>> {
    let n = g.n;
    let sh = shaders::functions(e);
    let glsl_name = format!("{stem}.glsl");
    let wgsl_name = format!("{stem}.wgsl");
    let (lo, hi) = (centre(0, n), centre(n - 1, n));
    let mut side = Map::new();
    side.insert("target".into(), json!(e.name()));
    side.insert("files".into(), Value::Object(d.data_files));
    side.insert("size".into(), json!([n, n]));
    side.insert("quantity".into(), json!("split-sum pair (A, B): specular IBL = prefiltered radiance · (F0 · A + F90 · B); A + B = directional albedo E(mu) for F = 1"));
    side.insert("model".into(), json!("GGX (Trowbridge–Reitz) NDF, height-correlated Smith masking-shadowing, Schlick Fresnel weight (1 − v·h)^5"));
    side.insert(
        "roughness".into(),
        json!("perceptual roughness r in [0, 1]; GGX alpha = r^2"),
    );
    side.insert("values".into(), json!("linear: no transfer function; sample as linear data (UNORM or float), never as an sRGB texture"));
    side.insert(
        "placement".into(),
        json!("texel centres on both axes: texel i of N holds the value at (i + 0.5)/N"),
    );
    side.insert(
        "inverse_mapping".into(),
        json!({
            "mu": "texture coordinate along the mu axis = mu (clamp mu to [0, 1]); texel index = mu · N − 0.5",
            "r": "texture coordinate along the r axis = r (clamp r to [0, 1]); texel index = r · N − 0.5",
        }),
    );
    side.insert(
        "exact_range".into(),
        json!({ "mu": [lo, hi], "r": [lo, hi],
                "outside": "with clamp-to-edge the sampler returns the edge texel's value, i.e. the integral at 0.5/N or 1 − 0.5/N" }),
    );
    side.insert(
        "sampler".into(),
        json!("bilinear (LINEAR), clamp-to-edge on both axes, one level (no mipmaps)"),
    );
    side.insert("texel_values".into(), json!("each texel = the split-sum integral at its own centre, computed in f64 by the table generator's converged rule (brdf-core split_sum::polar: product rule in polar coordinates of the half vector with the horizon cut in closed form, refined per texel until its error estimate is below 2e-6 per channel), rounded to nearest in the encoding; its error is not assumed but measured against an independent integrator: see `accuracy`"));
    side.insert("accuracy".into(), accuracy(e, g));
    side.extend(d.extra);
    side.insert(
        "shaders".into(),
        json!({ "glsl": glsl_name, "wgsl": wgsl_name, "function": sh.name }),
    );
    let side_bytes = crate::sidecar::sidecar_bytes(&Value::Object(side))?;
    let mut out = d.files;
    out.push(File {
        name: format!("{stem}.json"),
        bytes: side_bytes,
    });
    out.push(File {
        name: glsl_name,
        bytes: sh.glsl.into_bytes(),
    });
    out.push(File {
        name: wgsl_name,
        bytes: sh.wgsl.into_bytes(),
    });
    Ok(out)
}

/// Absolute tolerance per channel asked of the reference integrals.
const REFERENCE_TOL: f64 = 1e-8;
/// Columns whose centre μ lies below this are all measured (the grazing columns, where the
/// integrand is sharpest and the horizon cuts it).
const GRAZING_MU: f64 = 0.025;

/// The measured texels of an n × n table: (columns μ, rows r). Columns: every column whose
/// centre μ < [`GRAZING_MU`], and 16 evenly spaced ones (k·(n − 1)/15, first and last
/// included); rows: 8 evenly spaced (k·(n − 1)/7) and row 1. Sorted, without repeats.
fn sample(n: usize) -> (Vec<usize>, Vec<usize>) {
    let spread = |m: usize| (0..m).map(move |k| k * (n - 1) / (m - 1));
    let mut cols: Vec<usize> = (0..n).take_while(|&i| centre(i, n) < GRAZING_MU).collect();
    cols.extend(spread(16));
    let mut rows: Vec<usize> = spread(8).chain([1]).collect();
    for v in [&mut cols, &mut rows] {
        v.sort_unstable();
        v.dedup();
    }
    (cols, rows)
}

/// The stored channels of an engine (from the texel's A and B) and its encodings (the value
/// a reader decodes from the stored code of an exact value).
type Channels = [(&'static str, fn(f64, f64) -> f64); 2];
type Encodings = &'static [(&'static str, fn(f64) -> f64)];

fn stored(e: Engine) -> (Channels, Encodings) {
    let ab: Channels = [("A", |a, _| a), ("B", |_, b| b)];
    let f16: Encodings = &[("binary16", |v| half::f16::from_bits(half_bits(v)).to_f64())];
    match e {
        Engine::Khronos => (
            ab,
            &[
                ("8-bit UNORM", |v| unorm8(v) as f64 / 255.0),
                ("16-bit UNORM", |v| unorm16(v) as f64 / 65535.0),
            ],
        ),
        Engine::Filament => ([("R = B", |_, b| b), ("G = A + B", |a, b| a + b)], f16),
        Engine::Bevy | Engine::Threejs => (ab, f16),
        Engine::Exr => (ab, &[("binary32", |v| v as f32 as f64)]),
    }
}

/// The sidecar's `accuracy`: max |value − reference| over the texels of [`sample`], per
/// stored channel, for the f64 quadrature value and for the value decoded from each of the
/// engine's encodings, against brdf-core's converged split sum
/// (`split_sum::converged::DfgGgxRow::texel`, an independent adaptive integrator over the
/// visible-normal cap) at [`REFERENCE_TOL`], with the reference's own largest error
/// estimate and the worst texel. Deterministic: fixed texels, serial f64 arithmetic.
fn accuracy(e: Engine, g: &SplitSumTexels) -> Value {
    use brdf_core::split_sum::converged::DfgGgxRow;
    let n = g.n;
    let (cols, rows) = sample(n);
    let (chans, encs) = stored(e);
    // worst[k][c]: encoding k (0 = the quadrature value), channel c.
    let mut worst = vec![[0f64; 2]; encs.len() + 1];
    let (mut ref_est, mut at) = (0f64, (0, 0, -1.0));
    for &j in &rows {
        let row = DfgGgxRow::new(centre(j, n));
        for &i in &cols {
            let r = row.texel(centre(i, n), REFERENCE_TOL);
            ref_est = ref_est.max(r.error[0].max(r.error[1]));
            let (a, b) = (g.a[j * n + i], g.b[j * n + i]);
            for (c, (_, f)) in chans.iter().enumerate() {
                let (v, want) = (f(a, b), f(r.value[0], r.value[1]));
                let q = (v - want).abs();
                if q > at.2 {
                    at = (i, j, q);
                }
                worst[0][c] = worst[0][c].max(q);
                for (k, (_, dec)) in encs.iter().enumerate() {
                    worst[k + 1][c] = worst[k + 1][c].max((dec(v) - want).abs());
                }
            }
        }
    }
    let per = |w: &[f64; 2]| {
        let mut m = Map::new();
        for (c, &x) in chans.iter().zip(w) {
            m.insert(c.0.into(), json!(x));
        }
        Value::Object(m)
    };
    let mut max = Map::new();
    max.insert("quadrature (f64, before encoding)".into(), per(&worst[0]));
    for (k, (name, _)) in encs.iter().enumerate() {
        max.insert(format!("stored {name}"), per(&worst[k + 1]));
    }
    json!({
        "measured": "max |value − reference| over the sampled texels, per stored channel: the f64 quadrature value, and the value decoded from each stored encoding; computed by the tool when it wrote these files",
        "reference": format!("brdf-core split_sum::converged (DfgGgxRow::texel): adaptive 15-point Gauss–Kronrod rows over the GGX visible-normal cap, cut at the horizon, trapezoid rule in azimuth doubled until converged; absolute tolerance {REFERENCE_TOL:e} per channel; its largest error estimate over the sample: {ref_est:.1e}"),
        "sample": format!("{} texels of {}: columns {cols:?} (every column with centre mu < {GRAZING_MU}, the grazing ones, and 16 evenly spaced), rows {rows:?} (8 evenly spaced and row 1); mu = (column + 0.5)/N, r = (row + 0.5)/N", cols.len() * rows.len(), n * n),
        "max_abs_error": Value::Object(max),
        "worst_quadrature_texel": { "column": at.0, "row": at.1, "mu": centre(at.0, n), "r": centre(at.1, n) },
    })
}

/// The tolerances of [`sheen_texels`] per channel [Estevez–Kulla, Ashikhmin]: just under ½
/// LSB of the encodings the Khronos textures store them in (u16: 7.63e-6; u8: 1.96e-3).
pub const SHEEN_TEXEL_TOL: [f64; 2] = [7e-6, 1.9e-3];

/// The sheen albedo at the texel centres of an n × n Khronos grid (column μ = (i + ½)/n,
/// row r = (j + ½)/n, row-major): [Estevez–Kulla, Ashikhmin], interpolated from converged
/// nodes by [`brdf_lut::generate::sheen_grid`] to `SHEEN_TEXEL_TOL` (its estimate; nodes on
/// all cores). About 4.3 s of CPU at n = 1024 (docs/lut-format.md, sheen grid route).
pub fn sheen_texels(n: usize) -> Result<[Vec<f64>; 2]> {
    if !(2..=crate::MAX_SIZE).contains(&n) {
        return Err(Error::Size(n));
    }
    let g = brdf_lut::generate::sheen_grid(n, SHEEN_TEXEL_TOL);
    let [ek, ash] = g.values;
    if ek.len() != n * n || ash.len() != n * n {
        return Err(Error::Size(n));
    }
    Ok([ek, ash])
}

/// glTF Sample Viewer sheen textures from [`sheen_texels`] (`ek`, `ash`: n² values,
/// row-major, μ along x, r down the rows, as `lut_ggx.png`): `lut_charlie.png` (RGB 8-bit,
/// B = the Ashikhmin E the viewer reads as its sheen "DG", R = G = 0) and `lut_sheen_E.png`
/// (RGB 16-bit, R = G = B = the Estevez–Kulla E, linear), each with a JSON sidecar. Values
/// above 1 (grazing μ, small r) are clamped to 1 by the UNORM encoding; the sidecar says so.
pub fn khronos_sheen(n: usize, ek: &[f64], ash: &[f64]) -> Result<Vec<File>> {
    if !(2..=crate::MAX_SIZE).contains(&n) || ek.len() != n * n || ash.len() != n * n {
        return Err(Error::Size(n));
    }
    use png::{BitDepth::*, ColorType::*};
    let charlie: Vec<u8> = ash.iter().flat_map(|&v| [0, 0, unorm8(v)]).collect();
    let sheen: Vec<u8> = ek
        .iter()
        .flat_map(|&v| {
            let b = unorm16(v).to_be_bytes();
            [b[0], b[1], b[0], b[1], b[0], b[1]]
        })
        .collect();
    let mut out = vec![
        File {
            name: "lut_charlie.png".into(),
            bytes: png(n, n, Rgb, Eight, &charlie)?,
        },
        File {
            name: "lut_sheen_E.png".into(),
            bytes: png(n, n, Rgb, Sixteen, &sheen)?,
        },
    ];
    for (stem, vis, enc) in [
        ("lut_charlie", "ashikhmin: V = 1/(4(mu + mu_l - mu mu_l)) (Filament's cloth, the viewer's sheen DG)", "RGB 8-bit UNORM, B = E (R = G = 0): code = round(clamp(E, 0, 1) · 255)"),
        ("lut_sheen_E", "estevez-kulla: V = 1/((1 + Lambda(mu) + Lambda(mu_l)) 4 mu mu_l), their fitted Lambda (glTF KHR_materials_sheen)", "RGB 16-bit UNORM, R = G = B = E: code = round(clamp(E, 0, 1) · 65535)"),
    ] {
        let side = json!({
            "target": "khronos",
            "size": [n, n],
            "integral": "E_sheen(mu, r) = integral over the upper hemisphere of D(h) V(mu, mu_l) mu_l d omega_l (sheen colour 1)",
            "model": "Charlie sheen (Estevez and Kulla 2017): D = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi), alpha = r^2 clamped at 1e-4",
            "visibility": vis,
            "axes": "column x: mu = (x + 0.5)/N; PNG row y (top row first): r = (y + 0.5)/N (texel centres, as lut_ggx.png)",
            "orientation": "uploaded without a vertical flip (first stored row at t = 0), the shader samples uv = (mu, r)",
            "encoding": enc,
            "linear": true,
            "values": "linear: no transfer function; sample as linear data, never as an sRGB texture; values above 1 (grazing mu, small r) are clamped to 1",
            "texel_values": "each texel = the integral at its own centre in f64, interpolated by brdf_lut::generate::sheen_grid (tensor Chebyshev patches in ln mu, ln r through nodes by brdf_lut::generate::sheen_e to 4e-7; estimated error below 7e-6 for Estevez-Kulla, 1.9e-3 for Ashikhmin), rounded to nearest",
        });
        let bytes = crate::sidecar::sidecar_bytes(&side)?;
        out.push(File {
            name: format!("{stem}.json"),
            bytes,
        });
    }
    Ok(out)
}

/// The generator spec of a rough-glass engine texture: for n = [N0, N1, N2] `glass-e`
/// (R, T) over μ ∈ [0, 1], r ∈ [0, 1] and η; for n = [N0, N1] `glass-e-avg` (R_avg, T_avg)
/// over r and η; GGX, perceptual roughness, texel centres, all linear, η ∈ [1, 3] (light
/// from outside) or [1/3, 1] (`inside`: light from inside the glass); binary16 nodes (the
/// texture's own encoding).
pub fn glass_spec(n: &[usize], inside: bool) -> generate::Spec {
    use brdf_lut::generate::{AxisSpec, Distribution, Kind, Masking, Spec};
    use brdf_lut::{Encoding, Interpolation, Placement, Warp};
    let avg = n.len() == 2;
    let kind = if avg {
        Kind::GlassAverageAlbedo
    } else {
        Kind::GlassAlbedo
    };
    let mut s = Spec::new(kind, Distribution::Ggx, Masking::SmithSeparable);
    let (elo, ehi) = if inside { (1.0 / 3.0, 1.0) } else { (1.0, 3.0) };
    let axis = |k: usize, lo, hi| AxisSpec {
        placement: Placement::TexelCentre,
        ..AxisSpec::endpoint(n[k].min(u32::MAX as usize) as u32, lo, hi, Warp::Linear)
    };
    s.axes = (0..n.len())
        .map(|k| match n.len() - k {
            1 => axis(k, elo, ehi),
            _ => axis(k, 0.0, 1.0),
        })
        .collect();
    s.encoding = Encoding::F16;
    s.interpolation = Interpolation::Linear;
    s.samples = if avg { 64 } else { 256 };
    s
}

/// Rough glass (GGX rough dielectric, Walter et al. 2007). For n = [N0, N1, N2]: a 3-D KTX2
/// texture `glass_e[_inv].ktx2` (R16G16_SFLOAT: R = reflected, G = transmitted energy
/// fraction; x = μ, y = roughness, z = η, texel centres); for n = [N0, N1]: the 2-D
/// `glass_e_avg[_inv].ktx2` of their averages over μ (x = roughness, y = η). Each with the
/// BLUT file of the same nodes and bits (`.blut`, binary16) and the JSON sidecar. The level
/// data of the KTX2 is the BLUT payload itself (both store axis 0 fastest, channels
/// interleaved), so the two cannot disagree.
pub fn glass(n: &[usize], inside: bool, progress: &(dyn Fn(u64) + Sync)) -> Result<Vec<File>> {
    if !(2..=3).contains(&n.len()) || n.iter().any(|&k| !(2..=256).contains(&k)) {
        return Err(Error::Size(*n.iter().max().unwrap_or(&0)));
    }
    let avg = n.len() == 2;
    let spec = glass_spec(n, inside);
    let g = generate::generate(&spec, progress).map_err(Error::Generate)?;
    let view = brdf_lut::LutView::parse(&g.bytes).map_err(|e| Error::Encode(e.to_string()))?;
    let stem = match (avg, inside) {
        (false, false) => "glass_e",
        (false, true) => "glass_e_inv",
        (true, false) => "glass_e_avg",
        (true, true) => "glass_e_avg_inv",
    };
    let dims = [n[0], n[1], n.get(2).copied().unwrap_or(0)];
    let ktx = crate::containers::ktx2_rg16f_dims(dims, view.payload())?;
    let eta = if inside { "[1/3, 1]" } else { "[1, 3]" };
    let mut side = glass_sidecar(avg, stem, inside, eta);
    let kind = if avg { "glass-e-avg" } else { "glass-e" };
    side["files"] = json!({
        format!("{stem}.ktx2"): format!("KTX2, vkFormat 83 = R16G16_SFLOAT, {}, 1 level, Zstandard supercompression (level 22): R = reflected, G = transmitted", if avg { "2-D (width = roughness, height = eta)" } else { "3-D (width = mu, height = roughness, depth = eta)" }),
        format!("{stem}.blut"): format!("the same nodes and binary16 bits as a BLUT file (kind {kind}; docs/lut-format.md), with its measured interpolation error and integration bound"),
    });
    side["size"] = json!(n);
    side["integration_bound"] = json!(g.integration);
    side["interpolation_error"] = json!({ "max_abs": g.error.max_abs, "rms": g.error.rms, "samples": g.error.samples, "what": format!("{} lookup of the binary16 texels against the direct integral at random points", if avg { "bilinear" } else { "trilinear" }) });
    let side_bytes = crate::sidecar::sidecar_bytes(&side)?;
    Ok(vec![
        File {
            name: format!("{stem}.ktx2"),
            bytes: ktx,
        },
        File {
            name: format!("{stem}.blut"),
            bytes: g.bytes,
        },
        File {
            name: format!("{stem}.json"),
            bytes: side_bytes,
        },
    ])
}

/// The words of a rough-glass sidecar ([`glass`]): E (`avg` false) or E_avg.
fn glass_sidecar(avg: bool, stem: &str, inside: bool, eta: &str) -> serde_json::Value {
    let eta_axis = |c: &str, n: &str| {
        format!("{c}: eta = lo + ({c} + 0.5)/{n} (hi - lo) over {eta}: the index of the far side over that of the side the light arrives from ({})", if inside { "light inside the glass going out: eta = 1/IOR" } else { "light outside entering the glass: eta = IOR" })
    };
    let r_axis = |c: &str, n: &str| {
        format!("{c}: perceptual roughness r = ({c} + 0.5)/{n}; GGX alpha = r^2, floored at 1e-4 as in the kernel")
    };
    let integral = "directional albedo of a rough dielectric interface split into reflected and transmitted parts, for light arriving along mu = cos(theta) from the side of index 1: R(mu) = integral of f_r |cos theta_i| over the near hemisphere; T(mu) = integral of the adjoint (importance) transmission f_t* |cos theta_i| over the far hemisphere, i.e. the energy fraction transmitted, without the eta^2 radiance factor; R + T <= 1 (equality as roughness -> 0; the rest is lost to masking). Radiance crossing into the far medium is T * eta^2 per unit solid angle.";
    let rule = "computed by brdf-lut's generator (generate/glass/rings.rs: rings of the half vector around the normal, every edge of the integrand cut in closed form, globally adaptive Gauss-Kronrod with each channel's estimate <= 2e-6; checked by lut verify against an independent radial rule, generate/glass/radial.rs)";
    let mut side = json!({
        "target": "glass",
        "model": "rough dielectric of Walter, Marschner, Li, Torrance (EGSR 2007): GGX (Trowbridge-Reitz) NDF, separable Smith G = G1(wi) G1(wo), exact unpolarised dielectric Fresnel (total internal reflection included); brdf-core models::rough_dielectric",
        "placement": "texel centres on every axis: texel i of N holds the value at (i + 0.5)/N of its range",
        "encoding": "IEEE binary16, round to nearest even, of the f64 integral",
        "linear": "linear data: no transfer function; never sample as sRGB",
    });
    if avg {
        side["integral"] = json!(format!("the cosine-weighted averages over mu of the {stem} directional albedo: R_avg = 2 int_0^1 R(mu) mu dmu, T_avg = 2 int_0^1 T(mu) mu dmu, where {integral}"));
        side["axes"] = json!({ "roughness": r_axis("x", "N0"), "eta": eta_axis("y", "N1") });
        side["orientation"] = json!("KTXorientation rd: texel (x, y) at byte offset 4 (x + N0 y); the shader samples uv = (r, (eta - lo)/(hi - lo)) with clamp-to-edge");
        side["sampler"] = json!("bilinear (LINEAR), clamp-to-edge, one level");
        side["texel_values"] = json!(format!("each texel = the average at its own centre, its mu integral globally adaptive (Gauss-Kronrod on panels broken at the critical cosine) over E(mu) {rule}, then rounded to binary16"));
    } else {
        side["integral"] = json!(integral);
        side["axes"] = json!({ "mu": "x: mu = (x + 0.5)/N0 in [0, 1]", "roughness": r_axis("y", "N1"), "eta": eta_axis("z", "N2") });
        side["orientation"] = json!("KTXorientation rdi: texel (x, y, z) at byte offset 4 (x + N0 (y + N1 z)); the shader samples uvw = (mu, r, (eta - lo)/(hi - lo)) with clamp-to-edge");
        side["sampler"] = json!("trilinear (LINEAR on all three axes), clamp-to-edge, one level");
        side["texel_values"] = json!(format!(
            "each texel = the integral at its own centre, {rule}, then rounded to binary16"
        ));
    }
    side
}

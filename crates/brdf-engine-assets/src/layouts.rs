//! One function per engine layout: the data files in the engine's container, channel
//! layout and orientation, then the JSON sidecar and the GLSL/WGSL samplers.

use crate::containers::{dds_rgba16f, exr_rg32f, half_bits, ktx2_rg16f, png, unorm16, unorm8};
use crate::{centre, shaders, Engine, Error, File, SplitSumTexels};
use serde_json::{json, Map, Value};

type Result<T> = std::result::Result<T, Error>;

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
    d.file(
        "lut_ggx.png",
        png(n, n, Rgb, Eight, &rgb8)?,
        "RGB 8-bit: R = A, G = B, B = 0 (as the viewer ships it)",
    );
    d.file(
        "lut_ggx_16bit.png",
        png(n, n, Rgb, Sixteen, &rgb16)?,
        "RGB 16-bit: R = A, G = B, B = 0",
    );
    d.file(
        "lut_ggx_A_16bit.png",
        png(n, n, Grayscale, Sixteen, &a16)?,
        "grey 16-bit: A",
    );
    d.file(
        "lut_ggx_B_16bit.png",
        png(n, n, Grayscale, Sixteen, &b16)?,
        "grey 16-bit: B",
    );
    d.key("encoding", "UNORM: code = round(v · 255) (8-bit) or round(v · 65535) (16-bit); value = code / (2^bits − 1)");
    d.key("loaders", "Pillow (PIL) opens 16-bit RGB PNGs as 8-bit RGB without a warning, dropping the low 8 bits: read lut_ggx_A_16bit.png and lut_ggx_B_16bit.png (single-channel 16-bit, mode I;16 in Pillow) instead, or use a loader that keeps 16 bits (png, imageio, OpenCV with IMREAD_UNCHANGED). Browsers decode 16-bit PNGs to 8 bits.");
    d.key("orientation", "column x: mu = (x + 0.5)/N; PNG row y (top row first): r = (y + 0.5)/N. Uploaded without a vertical flip (first stored row at t = 0), the shader samples uv = (mu, r).");
    finish(Engine::Khronos, n, "lut_ggx", d)
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
    finish(Engine::Bevy, n, "dfg", d)
}

/// Filament: `dfg_multiscatter.dds`, RGBA16F with R = B, G = A + B, rows stored bottom-up
/// as Filament's loader expects.
pub fn filament(g: &SplitSumTexels) -> Result<Vec<File>> {
    let n = g.n;
    let mut tex = Vec::with_capacity(n * n * 8);
    for y in 0..n {
        let row = n - 1 - y; // file row y (top-down) holds r = (N − y − ½)/N
        for x in 0..n {
            let i = row * n + x;
            for v in [g.b[i], g.a[i] + g.b[i], 0.0, 1.0] {
                tex.extend_from_slice(&half_bits(v).to_le_bytes());
            }
        }
    }
    let mut d = Described::new();
    d.file("dfg_multiscatter.dds", dds_rgba16f(n, &tex)?, "DDS with DX10 header, DXGI_FORMAT_R16G16B16A16_FLOAT (10): R = B, G = A + B, B = 0, A = 1 (A = G − R)");
    d.key(
        "encoding",
        "IEEE binary16, round to nearest even; G = A + B is summed in f64 before rounding",
    );
    d.key("orientation", "column x: mu = (x + 0.5)/N; stored row y (top-down in the file): r = (N − y − 0.5)/N, so the GL row j = N − 1 − y that Filament's loader places at t = (j + 0.5)/N holds r = t and the shader's uv = (NoV, perceptualRoughness) reads the value at its own roughness. Filament's cmgen writes r = (N − y + 0.5)/N, one texel higher (top two GL rows both r = 1).");
    finish(Engine::Filament, n, "dfg_multiscatter", d)
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
    finish(Engine::Threejs, n, "dfg_lut", d)
}

/// OpenEXR: `dfg_ggx.exr`, 32-bit float R = A, G = B, μ along x, r down the rows.
pub fn exr(g: &SplitSumTexels) -> Result<Vec<File>> {
    let mut d = Described::new();
    d.file(
        "dfg_ggx.exr",
        exr_rg32f(g)?,
        "OpenEXR, 32-bit float channels R = A, G = B, ZIP compression, one part",
    );
    d.key("encoding", "IEEE binary32, round to nearest even, of the quadrature value; the quadrature error (about 2.5e-7 absolute) is coarser than f32 resolution, so digits below ~1e-6 are not significant");
    d.key("orientation", "column x: mu = (x + 0.5)/N; row y (data window top = y 0): r = (y + 0.5)/N. Uploaded with row 0 at t = 0, the shader samples uv = (mu, r).");
    finish(Engine::Exr, g.n, "dfg_ggx", d)
}

/// Appends the sidecar `{stem}.json` and the samplers `{stem}.glsl`, `{stem}.wgsl`.
fn finish(e: Engine, n: usize, stem: &str, d: Described) -> Result<Vec<File>> {
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
    side.insert("texel_values".into(), json!("each texel = the split-sum integral at its own centre, computed in f64 by Gauss–Legendre quadrature (32-point outer rule on 3 × 4 panels × 16-point azimuth rule; converged to about 3e-7), rounded to nearest in the encoding"));
    side.extend(d.extra);
    side.insert(
        "shaders".into(),
        json!({ "glsl": glsl_name, "wgsl": wgsl_name, "function": sh.name }),
    );
    let mut side_bytes = serde_json::to_vec_pretty(&Value::Object(side))
        .map_err(|e| Error::Encode(format!("json: {e}")))?;
    side_bytes.push(b'\n');
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

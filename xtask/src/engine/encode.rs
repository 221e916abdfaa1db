//! The containers: PNG (`png`), KTX2 (a minimal writer of our own: no maintained Rust crate
//! writes KTX2; the `ktx2` crate reads it back in the tests) with Zstandard level 22 (`zstd`),
//! DDS with the DX10 header (`ddsfile`), raw f16 (`half`), OpenEXR (`exr`).

use super::{centre, shaders, Grid, OutFile, Target};
use anyhow::{anyhow, Result};
use half::f16;
use serde_json::json;

/// Nearest 8-bit UNORM code of v ∈ [0, 1].
pub fn unorm8(v: f64) -> u8 {
    (v * 255.0).round().clamp(0.0, 255.0) as u8
}
/// Nearest 16-bit UNORM code of v ∈ [0, 1].
pub fn unorm16(v: f64) -> u16 {
    (v * 65535.0).round().clamp(0.0, 65535.0) as u16
}
/// Nearest binary16 (round to nearest, ties to even). `half`'s conversion may go through
/// f32 (its F16C path rounds twice: 0.449829110654 lands on the f16 midpoint in f32 and ties
/// down), so its result is corrected against its two neighbours in f64.
pub fn half_bits(v: f64) -> u16 {
    let h = f16::from_f64(v).to_bits();
    let mut best = h;
    let mut err = (f16::from_bits(h).to_f64() - v).abs();
    for c in [h.wrapping_add(1), h.wrapping_sub(1)] {
        let cf = f16::from_bits(c);
        if !cf.is_finite() || (cf.to_f64() < 0.0) != (f16::from_bits(h).to_f64() < 0.0) {
            continue;
        }
        let e = (cf.to_f64() - v).abs();
        if e < err || (e == err && c & 1 == 0) {
            best = c;
            err = e;
        }
    }
    best
}

fn png(
    w: usize,
    h: usize,
    color: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
) -> Result<Vec<u8>> {
    let mut buf = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut buf, w as u32, h as u32);
        enc.set_color(color);
        enc.set_depth(depth);
        let mut wr = enc.write_header()?;
        wr.write_image_data(data)?;
        wr.finish()?;
    }
    Ok(buf)
}

/// KTX 2.0 container, one 2-D level, vkFormat 83 (R16G16_SFLOAT), linear BT.709 DFD, level
/// data Zstandard-supercompressed (scheme 2). Layout per the KTX 2.0 specification: 80-byte
/// header, 24-byte level index, data format descriptor, key/value data, level data.
fn ktx2_rg16f(n: usize, texels: &[u8]) -> Result<Vec<u8>> {
    let comp = zstd::bulk::compress(texels, 22).map_err(|e| anyhow!("zstd: {e}"))?;
    let u32le = |v: &mut Vec<u8>, x: u32| v.extend_from_slice(&x.to_le_bytes());
    let u64le = |v: &mut Vec<u8>, x: u64| v.extend_from_slice(&x.to_le_bytes());
    // Data format descriptor: total size, one basic block (24 bytes + 16 per sample).
    let mut dfd = Vec::new();
    u32le(&mut dfd, 4 + 24 + 2 * 16);
    u32le(&mut dfd, 0); // vendor 0 (Khronos), descriptor type 0 (basic)
    dfd.extend_from_slice(&2u16.to_le_bytes()); // version 2
    dfd.extend_from_slice(&(24u16 + 32).to_le_bytes()); // block size
    dfd.extend_from_slice(&[1, 1, 1, 0]); // RGBSDA, BT.709 primaries, linear, straight alpha
    dfd.extend_from_slice(&[0, 0, 0, 0]); // 1×1×1×1 texel block
    dfd.extend_from_slice(&[4, 0, 0, 0, 0, 0, 0, 0]); // 4 bytes in plane 0
    for (ch, off) in [(0u8, 0u16), (1, 16)] {
        dfd.extend_from_slice(&off.to_le_bytes());
        dfd.push(15); // bit length − 1
        dfd.push(ch | 0x80 | 0x40); // channel id, float, signed
        dfd.extend_from_slice(&[0, 0, 0, 0]);
        u32le(&mut dfd, (-1.0f32).to_bits());
        u32le(&mut dfd, 1.0f32.to_bits());
    }
    let mut kvd = Vec::new();
    for (k, v) in [
        ("KTXorientation", "rd"),
        ("KTXwriter", "brdf-kernels xtask lut engine"),
    ] {
        let len = k.len() + 1 + v.len() + 1;
        u32le(&mut kvd, len as u32);
        kvd.extend_from_slice(k.as_bytes());
        kvd.push(0);
        kvd.extend_from_slice(v.as_bytes());
        kvd.push(0);
        while kvd.len() % 4 != 0 {
            kvd.push(0);
        }
    }
    let dfd_off = 80 + 24;
    let kvd_off = dfd_off + dfd.len();
    let data_off = kvd_off + kvd.len();
    let mut out = Vec::new();
    out.extend_from_slice(&[
        0xAB, b'K', b'T', b'X', b' ', b'2', b'0', 0xBB, b'\r', b'\n', 0x1A, b'\n',
    ]);
    for x in [83u32, 2, n as u32, n as u32, 0, 0, 1, 1, 2] {
        u32le(&mut out, x); // vkFormat, typeSize, w, h, depth, layers, faces, levels, zstd
    }
    for x in [dfd_off, dfd.len(), kvd_off, kvd.len()] {
        u32le(&mut out, x as u32);
    }
    u64le(&mut out, 0); // no supercompression global data
    u64le(&mut out, 0);
    for x in [data_off, comp.len(), texels.len()] {
        u64le(&mut out, x as u64);
    }
    out.extend_from_slice(&dfd);
    out.extend_from_slice(&kvd);
    out.extend_from_slice(&comp);
    Ok(out)
}

fn dds_rgba16f(n: usize, texels: &[u8]) -> Result<Vec<u8>> {
    use ddsfile::{AlphaMode, D3D10ResourceDimension, Dds, DxgiFormat, NewDxgiParams};
    let mut dds = Dds::new_dxgi(NewDxgiParams {
        height: n as u32,
        width: n as u32,
        depth: None,
        format: DxgiFormat::R16G16B16A16_Float,
        mipmap_levels: Some(1),
        array_layers: None,
        caps2: None,
        is_cubemap: false,
        resource_dimension: D3D10ResourceDimension::Texture2D,
        alpha_mode: AlphaMode::Unknown,
    })
    .map_err(|e| anyhow!("dds: {e}"))?;
    if dds.data.len() != texels.len() {
        return Err(anyhow!(
            "dds: {} data bytes for {} texels",
            dds.data.len(),
            n * n
        ));
    }
    dds.data.copy_from_slice(texels);
    let mut out = Vec::new();
    dds.write(&mut out).map_err(|e| anyhow!("dds: {e}"))?;
    Ok(out)
}

fn exr_rg32f(g: &Grid) -> Result<Vec<u8>> {
    use exr::prelude::*;
    let n = g.n;
    let channels = SpecificChannels::build()
        .with_channel("G")
        .with_channel("R")
        .with_pixel_fn(|p: Vec2<usize>| {
            let i = p.y() * n + p.x();
            (g.b[i] as f32, g.a[i] as f32)
        });
    let img = Image::from_encoded_channels((n, n), Encoding::SMALL_LOSSLESS, channels);
    let mut cur = std::io::Cursor::new(Vec::new());
    img.write()
        .non_parallel()
        .to_buffered(&mut cur)
        .map_err(|e| anyhow!("exr: {e}"))?;
    Ok(cur.into_inner())
}

/// Data files + sidecar + shaders of one target.
pub fn files(t: Target, g: &Grid) -> Result<Vec<OutFile>> {
    let n = g.n;
    let mut out = Vec::new();
    let stem;
    let mut data_files = serde_json::Map::new();
    let mut extra = serde_json::Map::new();
    match t {
        Target::Khronos => {
            stem = "lut_ggx";
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
            let set = [
                (
                    "lut_ggx.png",
                    png(n, n, Rgb, Eight, &rgb8)?,
                    "RGB 8-bit: R = A, G = B, B = 0 (as the viewer ships it)",
                ),
                (
                    "lut_ggx_16bit.png",
                    png(n, n, Rgb, Sixteen, &rgb16)?,
                    "RGB 16-bit: R = A, G = B, B = 0",
                ),
                (
                    "lut_ggx_A_16bit.png",
                    png(n, n, Grayscale, Sixteen, &a16)?,
                    "grey 16-bit: A",
                ),
                (
                    "lut_ggx_B_16bit.png",
                    png(n, n, Grayscale, Sixteen, &b16)?,
                    "grey 16-bit: B",
                ),
            ];
            for (name, bytes, what) in set {
                data_files.insert(name.into(), json!(what));
                out.push(OutFile {
                    name: name.into(),
                    bytes,
                });
            }
            extra.insert(
                "encoding".into(),
                json!("UNORM: code = round(v · 255) (8-bit) or round(v · 65535) (16-bit); value = code / (2^bits − 1)"),
            );
            extra.insert(
                "loaders".into(),
                json!("Pillow (PIL) opens 16-bit RGB PNGs as 8-bit RGB without a warning, dropping the low 8 bits: read lut_ggx_A_16bit.png and lut_ggx_B_16bit.png (single-channel 16-bit, mode I;16 in Pillow) instead, or use a loader that keeps 16 bits (png, imageio, OpenCV with IMREAD_UNCHANGED). Browsers decode 16-bit PNGs to 8 bits."),
            );
            extra.insert(
                "orientation".into(),
                json!("column x: mu = (x + 0.5)/N; PNG row y (top row first): r = (y + 0.5)/N. Uploaded without a vertical flip (first stored row at t = 0), the shader samples uv = (mu, r)."),
            );
        }
        Target::Bevy => {
            stem = "dfg";
            let mut tex = Vec::with_capacity(n * n * 4);
            for i in 0..n * n {
                tex.extend_from_slice(&half_bits(g.a[i]).to_le_bytes());
                tex.extend_from_slice(&half_bits(g.b[i]).to_le_bytes());
            }
            out.push(OutFile {
                name: "dfg.ktx2".into(),
                bytes: ktx2_rg16f(n, &tex)?,
            });
            data_files.insert("dfg.ktx2".into(), json!("KTX2, vkFormat 83 = R16G16_SFLOAT, 1 level, Zstandard supercompression (level 22): R = A, G = B"));
            extra.insert(
                "encoding".into(),
                json!("IEEE binary16, round to nearest even"),
            );
            extra.insert(
                "orientation".into(),
                json!("KTXorientation rd: row 0 (first stored) holds r = 0.5/N, column x holds mu = (x + 0.5)/N; the shader samples uv = (mu, r)."),
            );
        }
        Target::Filament => {
            stem = "dfg_multiscatter";
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
            out.push(OutFile {
                name: "dfg_multiscatter.dds".into(),
                bytes: dds_rgba16f(n, &tex)?,
            });
            data_files.insert("dfg_multiscatter.dds".into(), json!("DDS with DX10 header, DXGI_FORMAT_R16G16B16A16_FLOAT (10): R = B, G = A + B, B = 0, A = 1 (A = G − R)"));
            extra.insert("encoding".into(), json!("IEEE binary16, round to nearest even; G = A + B is summed in f64 before rounding"));
            extra.insert(
                "orientation".into(),
                json!("column x: mu = (x + 0.5)/N; stored row y (top-down in the file): r = (N − y − 0.5)/N, so the GL row j = N − 1 − y that Filament's loader places at t = (j + 0.5)/N holds r = t and the shader's uv = (NoV, perceptualRoughness) reads the value at its own roughness. Filament's cmgen writes r = (N − y + 0.5)/N, one texel higher (top two GL rows both r = 1)."),
            );
        }
        Target::Threejs => {
            stem = "dfg_lut";
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
            let mut js = String::new();
            js.push_str("// Split-sum (A, B) for GGX with height-correlated Smith, alpha = r * r, as RG16F\n");
            js.push_str(&format!("// half-float bits: {n} x {n}, memory row = dot(N, V) index, column = roughness index,\n"));
            js.push_str("// both at texel centres. Generated by `cargo xtask lut engine threejs`; see dfg_lut.json.\n");
            js.push_str(&format!(
                "export const DFG_LUT_SIZE = {n};\nexport const DFG_LUT_DATA = new Uint16Array([\n"
            ));
            for chunk in words.chunks(16) {
                let s: Vec<String> = chunk.iter().map(|w| format!("0x{w:04x}")).collect();
                js.push_str(&format!("  {},\n", s.join(", ")));
            }
            js.push_str("]);\n");
            out.push(OutFile {
                name: "dfg_lut.bin".into(),
                bytes: bin,
            });
            out.push(OutFile {
                name: "dfg_lut.js".into(),
                bytes: js.into_bytes(),
            });
            data_files.insert(
                "dfg_lut.bin".into(),
                json!("raw little-endian binary16 pairs (A, B), no header"),
            );
            data_files.insert("dfg_lut.js".into(), json!("ES module: DFG_LUT_SIZE, DFG_LUT_DATA (Uint16Array of the same half-float bits) for a DataTexture(RGFormat, HalfFloatType)"));
            extra.insert(
                "encoding".into(),
                json!("IEEE binary16, round to nearest even"),
            );
            extra.insert(
                "orientation".into(),
                json!("memory row m: mu = (m + 0.5)/N; column c: r = (c + 0.5)/N. Uploaded as a texture (first row at t = 0) the shader samples uv = (roughness, dotNV)."),
            );
        }
        Target::Exr => {
            stem = "dfg_ggx";
            out.push(OutFile {
                name: "dfg_ggx.exr".into(),
                bytes: exr_rg32f(g)?,
            });
            data_files.insert(
                "dfg_ggx.exr".into(),
                json!("OpenEXR, 32-bit float channels R = A, G = B, ZIP compression, one part"),
            );
            extra.insert(
                "encoding".into(),
                json!("IEEE binary32, round to nearest even, of the quadrature value; the quadrature error (about 2.5e-7 absolute) is coarser than f32 resolution, so digits below ~1e-6 are not significant"),
            );
            extra.insert(
                "orientation".into(),
                json!("column x: mu = (x + 0.5)/N; row y (data window top = y 0): r = (y + 0.5)/N. Uploaded with row 0 at t = 0, the shader samples uv = (mu, r)."),
            );
        }
        Target::All | Target::Report => return Err(anyhow!("not a single engine target")),
    }
    let sh = shaders::functions(t);
    let glsl_name = format!("{stem}.glsl");
    let wgsl_name = format!("{stem}.wgsl");
    let lo = centre(0, n);
    let hi = centre(n - 1, n);
    let mut side = serde_json::Map::new();
    side.insert("target".into(), json!(t.name()));
    side.insert("files".into(), serde_json::Value::Object(data_files));
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
    side.insert(
        "texel_values".into(),
        json!("each texel = the split-sum integral at its own centre, computed in f64 by Gauss–Legendre quadrature (32-point outer rule on 3 × 4 panels × 16-point azimuth rule; converged to about 3e-7), rounded to nearest in the encoding"),
    );
    for (k, v) in extra {
        side.insert(k, v);
    }
    side.insert(
        "shaders".into(),
        json!({ "glsl": glsl_name, "wgsl": wgsl_name, "function": sh.name }),
    );
    let mut side_bytes = serde_json::to_vec_pretty(&serde_json::Value::Object(side))?;
    side_bytes.push(b'\n');
    out.push(OutFile {
        name: format!("{stem}.json"),
        bytes: side_bytes,
    });
    out.push(OutFile {
        name: glsl_name,
        bytes: sh.glsl.into_bytes(),
    });
    out.push(OutFile {
        name: wgsl_name,
        bytes: sh.wgsl.into_bytes(),
    });
    Ok(out)
}

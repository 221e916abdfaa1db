//! The containers: PNG (`png`), KTX2 (a minimal writer of our own: no maintained Rust crate
//! writes KTX2; the `ktx2` crate reads it back in the tests) with Zstandard level 22 (`zstd`),
//! DDS with the DX10 header (`ddsfile`), raw f16 (`half`), OpenEXR (`exr`).

use crate::{Error, SplitSumTexels};
use half::f16;

use crate::Result;

fn png_err(e: png::EncodingError) -> Error {
    Error::Encode(format!("png: {e}"))
}

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

pub(crate) fn png(
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
        let mut wr = enc.write_header().map_err(png_err)?;
        wr.write_image_data(data).map_err(png_err)?;
        wr.finish().map_err(png_err)?;
    }
    Ok(buf)
}

/// KTX 2.0 container, one n × n 2-D level, vkFormat 83 (R16G16_SFLOAT): [`ktx2_rg16f_dims`]
/// with depth 0.
pub(crate) fn ktx2_rg16f(n: usize, texels: &[u8]) -> Result<Vec<u8>> {
    ktx2_rg16f_dims([n, n, 0], texels)
}

/// KTX 2.0 container, one level of width × height (× depth for a 3-D texture; depth 0 =
/// 2-D), vkFormat 83 (R16G16_SFLOAT), linear BT.709 DFD, level data
/// Zstandard-supercompressed (scheme 2). Layout per the KTX 2.0 specification: 80-byte
/// header, 24-byte level index, data format descriptor, key/value data, level data;
/// KTXorientation "rd" (2-D) or "rdi" (3-D: slices in increasing depth).
pub(crate) fn ktx2_rg16f_dims([w, h, depth]: [usize; 3], texels: &[u8]) -> Result<Vec<u8>> {
    let comp = zstd::bulk::compress(texels, 22).map_err(|e| Error::Encode(format!("zstd: {e}")))?;
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
        ("KTXorientation", if depth > 0 { "rdi" } else { "rd" }),
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
    for x in [83u32, 2, w as u32, h as u32, depth as u32, 0, 1, 1, 2] {
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

pub(crate) fn dds_rgba16f(n: usize, texels: &[u8]) -> Result<Vec<u8>> {
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
    .map_err(|e| Error::Encode(format!("dds: {e}")))?;
    if dds.data.len() != texels.len() {
        return Err(Error::Encode(format!(
            "dds: {} data bytes for {} texels",
            dds.data.len(),
            n * n
        )));
    }
    dds.data.copy_from_slice(texels);
    let mut out = Vec::new();
    dds.write(&mut out)
        .map_err(|e| Error::Encode(format!("dds: {e}")))?;
    Ok(out)
}

pub(crate) fn exr_rg32f(g: &SplitSumTexels) -> Result<Vec<u8>> {
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
        .map_err(|e| crate::Error::Encode(format!("exr: {e}")))?;
    Ok(cur.into_inner())
}

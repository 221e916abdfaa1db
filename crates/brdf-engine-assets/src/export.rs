//! Any BLUT table as a texture a shader or a script can read: node values as a 16-bit PNG
//! or raw little-endian f16/f32, a JSON sidecar that states axes, orientation, texel
//! placement, the per-axis inverse mapping and that values are linear, and, for 2-D tables
//! with one or two channels, GLSL and WGSL sampling functions ([`crate::table_shaders`]).
//! [`export`] returns the bytes; writing them is the caller's (`cargo xtask lut export`).

use crate::table_shaders::{self, Decode};
use crate::Error;
use brdf_lut::{f32_to_f16, Header, Interpolation, LutView, Placement, Warp};
use serde_json::{json, Value};

/// The texture format of an export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// 16-bit PNG (1 channel: grey; 2: R, G with B = 0; 1- or 2-D tables only), values
    /// mapped to [0, 1] per channel (the sidecar states the mapping).
    Png16,
    /// Raw little-endian IEEE binary16, channels interleaved, axis 0 fastest.
    RawF16,
    /// Raw little-endian IEEE binary32, channels interleaved, axis 0 fastest.
    RawF32,
}

impl Format {
    /// The output's default extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Png16 => "png",
            Format::RawF16 => "f16.bin",
            Format::RawF32 => "f32.bin",
        }
    }
    /// The name the sidecar gives the format.
    pub fn name(self) -> &'static str {
        match self {
            Format::Png16 => "png16",
            Format::RawF16 => "raw-f16",
            Format::RawF32 => "raw-f32",
        }
    }
}

/// The bytes of one export. The caller names the files: the texture `out`, the sidecar
/// `out.json`, the shaders `out.glsl` and `out.wgsl`, each single-channel PNG by its
/// `name` in `out`'s folder (the sidecar lists them under these names).
#[derive(Clone, Debug)]
pub struct Export {
    /// The texture.
    pub texture: Vec<u8>,
    /// The JSON sidecar.
    pub sidecar: Vec<u8>,
    /// GLSL and WGSL sampling functions (2-D tables with one or two channels only).
    pub shaders: Option<(String, String)>,
    /// One 16-bit greyscale PNG per channel (PNG exports of two-channel tables): name, bytes.
    pub single_channel_pngs: Vec<(String, Vec<u8>)>,
}

/// Node values of `v`, channels interleaved, axis 0 fastest.
fn node_values(v: &LutView<'_>) -> Vec<f32> {
    let nodes: usize = v.header().axes.iter().map(|x| x.count as usize).product();
    let nc = v.channels();
    (0..nodes)
        .flat_map(|k| (0..nc).map(move |c| (k, c)))
        .map(|(k, c)| v.node_value(k, c))
        .collect()
}

/// Per channel (offset, scale) mapping the channel's values into [0, 1]: identity when they
/// already lie there.
fn unit_ranges(vals: &[f32], nc: usize) -> Decode {
    (0..nc)
        .map(|c| {
            let ch = || vals.iter().skip(c).step_by(nc);
            let lo = ch().fold(f32::INFINITY, |m, &x| m.min(x));
            let hi = ch().fold(f32::NEG_INFINITY, |m, &x| m.max(x));
            let (off, sc) = if lo >= 0.0 && hi <= 1.0 {
                (0.0, 1.0)
            } else {
                (lo, hi - lo)
            };
            (off, if sc > 0.0 { sc } else { 1.0 })
        })
        .collect()
}

/// A 16-bit PNG of `w` × `h` pixels with `spp` samples per pixel (1: grey, 3: RGB), the
/// samples given by `sample(pixel, s)` in [0, 1], rounded to nearest.
fn png16(
    w: u32,
    h: u32,
    spp: usize,
    sample: impl Fn(usize, usize) -> f32,
) -> Result<Vec<u8>, Error> {
    let n = w as usize * h as usize;
    let mut data = Vec::with_capacity(n * spp * 2);
    for k in 0..n {
        for s in 0..spp {
            let q = (sample(k, s).clamp(0.0, 1.0) * 65535.0).round() as u16;
            data.extend_from_slice(&q.to_be_bytes());
        }
    }
    let enc_err = |e: png::EncodingError| Error::Encode(format!("PNG: {e}"));
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(if spp == 1 {
        png::ColorType::Grayscale
    } else {
        png::ColorType::Rgb
    });
    enc.set_depth(png::BitDepth::Sixteen);
    let mut wr = enc.write_header().map_err(enc_err)?;
    wr.write_image_data(&data).map_err(enc_err)?;
    wr.finish().map_err(enc_err)?;
    Ok(out)
}

/// An encoded texture and what the sidecar says about its encoding.
struct Encoded {
    texture: Vec<u8>,
    /// Per channel (offset, scale): value = offset + scale · texel.
    decode: Decode,
    singles: Vec<(String, Vec<u8>)>,
    /// The sidecar's `png_value_mapping` (null for raw exports).
    png_map: Value,
}

/// The PNG export: the texture, the channel decode, the single-channel PNGs (named after
/// `stem`) and the sidecar's `png_value_mapping`.
fn png_export(h: &Header<'_>, vals: &[f32], stem: &str) -> Result<Encoded, Error> {
    let nc = h.channels.len();
    if h.axes.len() > 2 || nc > 2 {
        return Err(Error::Encode(
            "--png16 needs a 1- or 2-D table with at most 2 channels; use --raw-f32".into(),
        ));
    }
    let w = h.axes[0].count;
    let ht = h.axes.get(1).map_or(1, |a| a.count);
    let ranges = unit_ranges(vals, nc);
    let unit = |k: usize, c: usize| (vals[k * nc + c] - ranges[c].0) / ranges[c].1;
    let spp = if nc == 1 { 1 } else { 3 };
    let texture = png16(w, ht, spp, |k, s| if s < nc { unit(k, s) } else { 0.0 })?;
    // Single-channel 16-bit greyscale PNGs per channel: loaders that silently reduce 16-bit
    // RGB to 8 bits (Pillow) read 16-bit greyscale at full depth.
    let mut singles = Vec::new();
    if nc > 1 {
        for (c, ch) in h.channels.iter().enumerate() {
            let cname: String = ch
                .name
                .chars()
                .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            let bytes = png16(w, ht, 1, |k, _| unit(k, c))?;
            singles.push((format!("{stem}_{cname}.png"), bytes));
        }
    }
    let map = json!(ranges
        .iter()
        .zip(h.channels.iter())
        .map(|((o, s), c)| json!({"channel": c.name, "value": format!("{o} + {s} * png/65535")}))
        .collect::<Vec<_>>());
    Ok(Encoded {
        texture,
        decode: ranges,
        singles,
        png_map: map,
    })
}

/// Raw little-endian f16 or f32 node values.
fn raw_export(vals: &[f32], half: bool) -> Vec<u8> {
    let mut data = Vec::with_capacity(vals.len() * if half { 2 } else { 4 });
    for &x in vals {
        if half {
            data.extend_from_slice(&f32_to_f16(x).to_le_bytes());
        } else {
            data.extend_from_slice(&x.to_le_bytes());
        }
    }
    data
}

fn placement_formula(p: Placement) -> &'static str {
    match p {
        Placement::Endpoint => "s_i = i / (count - 1)",
        Placement::TexelCentre => "s_i = (i + 0.5) / count",
    }
}

fn warp_formula(w: Warp) -> &'static str {
    match w {
        Warp::Linear => "x = lo + s * (hi - lo)",
        Warp::Log => "x = lo * (hi / lo)^s",
        Warp::Sqrt => "x = lo + s^2 * (hi - lo)",
        Warp::Cos => "x = acos(cos(lo) - s * (cos(lo) - cos(hi)))",
        Warp::SqrtCos => "x = acos((sqrt(cos(lo)) - s * (sqrt(cos(lo)) - sqrt(cos(hi))))^2)",
    }
}

/// The sampling function's name: `sample_` + the output's first name part, lower-cased,
/// other characters as `_`.
fn function_name(out_name: &str) -> String {
    let base: String = out_name
        .split('.')
        .next()
        .unwrap_or_default()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    format!("sample_{base}")
}

/// The sidecar's `shaders` object.
fn shaders_json(h: &Header<'_>, fname: &str, out_name: &str, emitted: bool) -> Value {
    let nc = h.channels.len();
    if !emitted {
        return json!({
            "function": null,
            "note": format!("no shader emitted: sampling functions are generated for 2-D tables with 1 or 2 channels only; this table has {} axes. Use inverse_mapping per axis (a 1-D table as a Nx1 texture, a 3-D table as a 3-D texture or layers along axis 2)", h.axes.len()),
        });
    }
    json!({
        "function": fname,
        "glsl": format!("{out_name}.glsl"),
        "wgsl": format!("{out_name}.wgsl"),
        "signature_glsl": format!("{} {fname}(sampler2D lut, float p0, float p1)", if nc == 1 { "float" } else { "vec2" }),
        "signature_wgsl": format!("fn {fname}(lut: texture_2d<f32>, samp: sampler, p0: f32, p1: f32) -> {}", if nc == 1 { "f32" } else { "vec2<f32>" }),
        "arguments": "p0 = physical value on axis 0, p1 = on axis 1 (clamped to the axis ranges)",
        "texture_setup": "width = axis 0 count, height = axis 1 count, first data row at v = 0 (no vertical flip on upload), linear (UNORM or float, never sRGB) format, bilinear filtering, clamp-to-edge, no mipmaps",
        "interpolation": if h.interpolation == Interpolation::Linear {
            "the table is meant for linear interpolation: bilinear sampling at these uv reproduces it up to the texture format's rounding (and the GPU's filter-weight precision)"
        } else {
            "the table is meant for Catmull-Rom interpolation: bilinear sampling gives its linear interpolation instead, and the header's error figure is for Catmull-Rom"
        },
    })
}

/// The sidecar's `axes` list.
fn axes_json(h: &Header<'_>) -> Value {
    json!(h
        .axes
        .iter()
        .enumerate()
        .map(|(k, x)| json!({
            "index": k,
            "name": x.name,
            "count": x.count,
            "lo": x.lo,
            "hi": x.hi,
            "warp": format!("{:?}", x.warp),
            "placement": format!("{:?}", x.placement),
            "node_formula": format!("{}; {}", placement_formula(x.placement), warp_formula(x.warp)),
        }))
        .collect::<Vec<_>>())
}

/// What the sidecar states besides the header's own fields.
struct SidecarParts<'a> {
    format: Format,
    source: &'a str,
    decode: &'a Decode,
    singles: &'a [(String, Vec<u8>)],
    shaders: Value,
    png_map: Value,
}

/// The JSON sidecar of an export.
fn sidecar(h: &Header<'_>, p: SidecarParts<'_>) -> Vec<u8> {
    let png = p.format == Format::Png16;
    let nc = h.channels.len();
    let side = json!({
        "inverse_mapping": h.axes.iter().enumerate().map(|(k, x)| table_shaders::axis_mapping(k, x)).collect::<Vec<_>>(),
        "inverse_mapping_note": "t is the warped unit coordinate; endpoint nodes i sit at t = i/(N-1) = texel centre (i + 0.5)/N, hence u = (t*(N-1) + 0.5)/N; texel-centre nodes at t = (i + 0.5)/N, hence u = t",
        "roughness": table_shaders::roughness_convention(h.generator.model),
        "clamp_ranges": h.axes.iter().map(|x| json!({"name": x.name, "lo": x.lo, "hi": x.hi})).collect::<Vec<_>>(),
        "channel_decode": h.channels.iter().zip(p.decode.iter()).map(|(c, (o, s))| json!({"channel": c.name, "offset": o, "scale": s, "value": "offset + scale * texel"})).collect::<Vec<_>>(),
        "single_channel_pngs": p.singles.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
        "single_channel_pngs_note": if png && nc > 1 { "one 16-bit greyscale PNG per channel is written besides the RGB one: Pillow and some other loaders silently read 16-bit RGB PNGs as 8-bit, 16-bit greyscale at full depth" } else { "not needed: the PNG is already single-channel 16-bit greyscale (or the export is raw)" },
        "shaders": p.shaders,
        "source": p.source,
        "format": p.format.name(),
        "kind": format!("{:?}", h.kind),
        "model": format!("{:?}", h.generator.model),
        "channels": h.channels.iter().map(|c| c.name).collect::<Vec<_>>(),
        "channel_mapping": if nc == 2 && png { "R = first channel, G = second, B = 0" } else { "in channel order" },
        "axes": axes_json(h),
        "orientation": if png {
            "image column x = node index along axis 0; image row y counted from the TOP row = node index along axis 1 (no flip)"
        } else {
            "axis 0 varies fastest, then axis 1, then axis 2; channels interleaved innermost"
        },
        "values": "linear (NOT sRGB): load the texture with a linear/UNORM format, never an sRGB one",
        "sampling": "node values at the axis nodes; a GPU must sample texel centres ((i + 0.5)/count) for TexelCentre axes, and map x through the warp for the others",
        "png_value_mapping": p.png_map,
        "byte_order": if png { "PNG (big-endian samples)" } else { "little-endian" },
        "error_vs_direct_kernel": {"max_abs": h.error.max_abs, "rms": h.error.rms},
    });
    let text = serde_json::to_string_pretty(&side).unwrap_or_default() + "\n";
    text.into_bytes()
}

/// Exports table `v` as `format`. `out_name` is the texture's file name (it names the
/// sampling function, the shader files and the single-channel PNGs in the sidecar);
/// `source` is the table's file name, recorded in the sidecar.
pub fn export(
    v: &LutView<'_>,
    format: Format,
    out_name: &str,
    source: &str,
) -> Result<Export, Error> {
    let h = v.header();
    let vals = node_values(v);
    let nc = v.channels();
    let stem = std::path::Path::new(out_name)
        .file_stem()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    let Encoded {
        texture,
        decode,
        singles,
        png_map,
    } = match format {
        Format::Png16 => png_export(h, &vals, &stem)?,
        Format::RawF16 | Format::RawF32 => Encoded {
            texture: raw_export(&vals, format == Format::RawF16),
            decode: vec![(0.0, 1.0); nc],
            singles: Vec::new(),
            png_map: Value::Null,
        },
    };
    let fname = function_name(out_name);
    let shaders = table_shaders::shaders(h, &fname, &decode);
    let parts = SidecarParts {
        format,
        source,
        decode: &decode,
        singles: &singles,
        shaders: shaders_json(h, &fname, out_name, shaders.is_some()),
        png_map,
    };
    Ok(Export {
        sidecar: sidecar(h, parts),
        texture,
        shaders,
        single_channel_pngs: singles,
    })
}

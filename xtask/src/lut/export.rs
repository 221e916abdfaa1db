//! `cargo xtask lut export`: node values as a 16-bit PNG or raw little-endian f16/f32, with
//! a JSON sidecar that states axes, orientation, texel placement and that values are linear.

use anyhow::{bail, Result};
use brdf_lut::{f32_to_f16, LutView, Placement, Warp};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct ExportArgs {
    /// The LUT file.
    file: PathBuf,
    /// 16-bit PNG (1 channel: grey; 2: R, G with B = 0; 1- or 2-D tables only).
    #[arg(long, group = "fmt")]
    png16: bool,
    /// Raw little-endian IEEE binary16, channels interleaved, axis 0 fastest.
    #[arg(long, group = "fmt")]
    raw_f16: bool,
    /// Raw little-endian IEEE binary32, channels interleaved, axis 0 fastest.
    #[arg(long, group = "fmt")]
    raw_f32: bool,
    /// Output path (default: the input's file name with the format's extension, in the
    /// current folder, never in assets/); the sidecar is `<output>.json`. The input is never
    /// overwritten.
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Replace an existing output and sidecar.
    #[arg(long)]
    force: bool,
}

/// The default output: the input's file name with `ext`, in the current folder.
fn default_out(input: &Path, ext: &str) -> PathBuf {
    let name = input
        .file_name()
        .map(Path::new)
        .unwrap_or(Path::new("table"));
    PathBuf::from(name.with_extension(ext).file_name().unwrap_or_default())
}

/// `p` with `suffix` appended to its last component (`t.bin` → `t.bin.json`), byte for
/// byte (no lossy conversion of a non-UTF-8 name).
fn with_suffix(p: &Path, suffix: &str) -> PathBuf {
    let mut s = p.as_os_str().to_os_string();
    s.push(suffix);
    PathBuf::from(s)
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

pub fn run(a: ExportArgs) -> Result<()> {
    let lut = crate::fsio::load_lut(&a.file)?;
    let v: LutView<'_> = lut.view()?;
    let h = v.header();
    let nodes: usize = h.axes.iter().map(|x| x.count as usize).product();
    let nc = v.channels();
    let vals: Vec<f32> = (0..nodes)
        .flat_map(|k| (0..nc).map(move |c| (k, c)))
        .map(|(k, c)| v.node_value(k, c))
        .collect();
    let (ext, fmt) = if a.png16 {
        ("png", "png16")
    } else if a.raw_f16 {
        ("f16.bin", "raw-f16")
    } else if a.raw_f32 {
        ("f32.bin", "raw-f32")
    } else {
        bail!("choose one of --png16, --raw-f16, --raw-f32");
    };
    let out = a.out.clone().unwrap_or_else(|| default_out(&a.file, ext));
    let side_path = with_suffix(&out, ".json");
    let policy = crate::fsio::Policy::new(a.force, &[&a.file]);
    crate::fsio::check(
        &[
            &out,
            &side_path,
            &with_suffix(&out, ".glsl"),
            &with_suffix(&out, ".wgsl"),
        ],
        &policy,
    )?;
    let payload: Vec<u8>;
    let mut png_map = serde_json::Value::Null;
    // Channel decode of the texture: identity for float exports, the PNG's offset/scale.
    let mut decode: super::export_shaders::Decode = vec![(0.0, 1.0); nc];
    let mut singles: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if a.png16 {
        if h.axes.len() > 2 || nc > 2 {
            bail!("--png16 needs a 1- or 2-D table with at most 2 channels; use --raw-f32");
        }
        let w = h.axes[0].count;
        let ht = if h.axes.len() == 2 {
            h.axes[1].count
        } else {
            1
        };
        let mut ranges = Vec::new();
        for c in 0..nc {
            let lo = vals
                .iter()
                .skip(c)
                .step_by(nc)
                .fold(f32::INFINITY, |m, &x| m.min(x));
            let hi = vals
                .iter()
                .skip(c)
                .step_by(nc)
                .fold(f32::NEG_INFINITY, |m, &x| m.max(x));
            let (off, sc) = if lo >= 0.0 && hi <= 1.0 {
                (0.0, 1.0)
            } else {
                (lo, hi - lo)
            };
            ranges.push((off, if sc > 0.0 { sc } else { 1.0 }));
        }
        let spp = if nc == 1 { 1 } else { 3 };
        let mut data = Vec::with_capacity(nodes * spp * 2);
        for k in 0..nodes {
            for s in 0..spp {
                let x = if s < nc {
                    let (off, sc) = ranges[s];
                    ((vals[k * nc + s] - off) / sc).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let q = (x * 65535.0).round() as u16;
                data.extend_from_slice(&q.to_be_bytes());
            }
        }
        let mut encoded = Vec::new();
        let mut enc = png::Encoder::new(&mut encoded, w, ht);
        enc.set_color(if nc == 1 {
            png::ColorType::Grayscale
        } else {
            png::ColorType::Rgb
        });
        enc.set_depth(png::BitDepth::Sixteen);
        let mut wr = enc.write_header()?;
        wr.write_image_data(&data)?;
        wr.finish()?;
        payload = encoded;
        decode = ranges.clone();
        // Single-channel 16-bit greyscale PNGs per channel: loaders that silently reduce
        // 16-bit RGB to 8 bits (Pillow) read 16-bit greyscale at full depth.
        if nc > 1 {
            let stem = out
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            for (c, ch) in h.channels.iter().enumerate() {
                let (off, sc) = ranges[c];
                let mut d = Vec::with_capacity(nodes * 2);
                for k in 0..nodes {
                    let x = ((vals[k * nc + c] - off) / sc).clamp(0.0, 1.0);
                    d.extend_from_slice(&((x * 65535.0).round() as u16).to_be_bytes());
                }
                let mut e = Vec::new();
                let mut enc = png::Encoder::new(&mut e, w, ht);
                enc.set_color(png::ColorType::Grayscale);
                enc.set_depth(png::BitDepth::Sixteen);
                let mut wr = enc.write_header()?;
                wr.write_image_data(&d)?;
                wr.finish()?;
                let cname: String = ch
                    .name
                    .chars()
                    .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                singles.push((out.with_file_name(format!("{stem}_{cname}.png")), e));
            }
        }
        png_map = serde_json::json!(ranges
            .iter()
            .zip(h.channels.iter())
            .map(|((o, s), c)| serde_json::json!({"channel": c.name, "value": format!("{o} + {s} * png/65535")}))
            .collect::<Vec<_>>());
    } else {
        let mut data = Vec::new();
        for &x in &vals {
            if a.raw_f16 {
                data.extend_from_slice(&f32_to_f16(x).to_le_bytes());
            } else {
                data.extend_from_slice(&x.to_le_bytes());
            }
        }
        payload = data;
    }
    let axes: Vec<_> = h
        .axes
        .iter()
        .enumerate()
        .map(|(k, x)| {
            serde_json::json!({
                "index": k,
                "name": x.name,
                "count": x.count,
                "lo": x.lo,
                "hi": x.hi,
                "warp": format!("{:?}", x.warp),
                "placement": format!("{:?}", x.placement),
                "node_formula": format!("{}; {}", placement_formula(x.placement), warp_formula(x.warp)),
            })
        })
        .collect();
    let orientation = if a.png16 {
        "image column x = node index along axis 0; image row y counted from the TOP row = node index along axis 1 (no flip)"
    } else {
        "axis 0 varies fastest, then axis 1, then axis 2; channels interleaved innermost"
    };
    let fname: String = out
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
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
    let fname = format!("sample_{fname}");
    let shaders = super::export_shaders::shaders(h, &fname, &decode);
    let glsl_path = with_suffix(&out, ".glsl");
    let wgsl_path = with_suffix(&out, ".wgsl");
    let shaders_json = match &shaders {
        Some(_) => serde_json::json!({
            "function": fname,
            "glsl": glsl_path.file_name().map(|s| s.to_string_lossy().into_owned()),
            "wgsl": wgsl_path.file_name().map(|s| s.to_string_lossy().into_owned()),
            "signature_glsl": format!("{} {fname}(sampler2D lut, float p0, float p1)", if nc == 1 { "float" } else { "vec2" }),
            "signature_wgsl": format!("fn {fname}(lut: texture_2d<f32>, samp: sampler, p0: f32, p1: f32) -> {}", if nc == 1 { "f32" } else { "vec2<f32>" }),
            "arguments": "p0 = physical value on axis 0, p1 = on axis 1 (clamped to the axis ranges)",
            "texture_setup": "width = axis 0 count, height = axis 1 count, first data row at v = 0 (no vertical flip on upload), linear (UNORM or float, never sRGB) format, bilinear filtering, clamp-to-edge, no mipmaps",
            "interpolation": if h.interpolation == brdf_lut::Interpolation::Linear {
                "the table is meant for linear interpolation: bilinear sampling at these uv reproduces it up to the texture format's rounding (and the GPU's filter-weight precision)"
            } else {
                "the table is meant for Catmull-Rom interpolation: bilinear sampling gives its linear interpolation instead, and the header's error figure is for Catmull-Rom"
            },
        }),
        None => serde_json::json!({
            "function": null,
            "note": format!("no shader emitted: sampling functions are generated for 2-D tables with 1 or 2 channels only; this table has {} axes. Use inverse_mapping per axis (a 1-D table as a Nx1 texture, a 3-D table as a 3-D texture or layers along axis 2)", h.axes.len()),
        }),
    };
    let side = serde_json::json!({
        "inverse_mapping": h.axes.iter().enumerate().map(|(k, x)| super::export_shaders::axis_mapping(k, x)).collect::<Vec<_>>(),
        "inverse_mapping_note": "t is the warped unit coordinate; endpoint nodes i sit at t = i/(N-1) = texel centre (i + 0.5)/N, hence u = (t*(N-1) + 0.5)/N; texel-centre nodes at t = (i + 0.5)/N, hence u = t",
        "roughness": super::export_shaders::roughness_convention(h.generator.model),
        "clamp_ranges": h.axes.iter().map(|x| serde_json::json!({"name": x.name, "lo": x.lo, "hi": x.hi})).collect::<Vec<_>>(),
        "channel_decode": h.channels.iter().zip(decode.iter()).map(|(c, (o, s))| serde_json::json!({"channel": c.name, "offset": o, "scale": s, "value": "offset + scale * texel"})).collect::<Vec<_>>(),
        "single_channel_pngs": singles.iter().map(|(p, _)| p.file_name().map(|s| s.to_string_lossy().into_owned())).collect::<Vec<_>>(),
        "single_channel_pngs_note": if a.png16 && nc > 1 { "one 16-bit greyscale PNG per channel is written besides the RGB one: Pillow and some other loaders silently read 16-bit RGB PNGs as 8-bit, 16-bit greyscale at full depth" } else { "not needed: the PNG is already single-channel 16-bit greyscale (or the export is raw)" },
        "shaders": shaders_json,
        "source": a.file.file_name().map(|s| s.to_string_lossy().into_owned()),
        "format": fmt,
        "kind": format!("{:?}", h.kind),
        "model": format!("{:?}", h.generator.model),
        "channels": h.channels.iter().map(|c| c.name).collect::<Vec<_>>(),
        "channel_mapping": if nc == 2 && a.png16 { "R = first channel, G = second, B = 0" } else { "in channel order" },
        "axes": axes,
        "orientation": orientation,
        "values": "linear (NOT sRGB): load the texture with a linear/UNORM format, never an sRGB one",
        "sampling": "node values at the axis nodes; a GPU must sample texel centres ((i + 0.5)/count) for TexelCentre axes, and map x through the warp for the others",
        "png_value_mapping": png_map,
        "byte_order": if a.png16 { "PNG (big-endian samples)" } else { "little-endian" },
        "error_vs_direct_kernel": {"max_abs": h.error.max_abs, "rms": h.error.rms},
    });
    let side_bytes = (serde_json::to_string_pretty(&side)? + "\n").into_bytes();
    let single_paths: Vec<PathBuf> = singles.iter().map(|(p, _)| p.clone()).collect();
    crate::fsio::check(
        &single_paths.iter().map(|p| p.as_path()).collect::<Vec<_>>(),
        &policy,
    )?;
    let mut files = vec![(out.clone(), payload), (side_path.clone(), side_bytes)];
    files.extend(singles);
    if let Some((g, w)) = shaders {
        files.push((glsl_path, g.into_bytes()));
        files.push((wgsl_path, w.into_bytes()));
    }
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    crate::fsio::write_together(&files, &policy)?;
    println!("wrote {}", names.join(", "));
    Ok(())
}

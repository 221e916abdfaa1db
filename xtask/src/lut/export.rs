//! `cargo xtask lut export`: node values as a 16-bit PNG or raw little-endian f16/f32, with
//! a JSON sidecar that states axes, orientation, texel placement and that values are linear.

use anyhow::{bail, Context, Result};
use brdf_lut::{f32_to_f16, LutView, Placement, Warp};
use std::path::PathBuf;

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
    /// Output path (default: the input with the format's extension); the sidecar is
    /// `<output>.json`.
    #[arg(long, short)]
    out: Option<PathBuf>,
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
    let lut = brdf_lut::Lut::from_path(&a.file)
        .with_context(|| format!("loading {}", a.file.display()))?;
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
    let out = a.out.clone().unwrap_or_else(|| a.file.with_extension(ext));
    let mut png_map = serde_json::Value::Null;
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
        let f = std::fs::File::create(&out)?;
        let mut enc = png::Encoder::new(std::io::BufWriter::new(f), w, ht);
        enc.set_color(if nc == 1 {
            png::ColorType::Grayscale
        } else {
            png::ColorType::Rgb
        });
        enc.set_depth(png::BitDepth::Sixteen);
        let mut wr = enc.write_header()?;
        wr.write_image_data(&data)?;
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
        std::fs::write(&out, data)?;
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
    let side = serde_json::json!({
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
    let side_path = PathBuf::from(format!("{}.json", out.display()));
    std::fs::write(&side_path, serde_json::to_string_pretty(&side)? + "\n")?;
    println!("wrote {} and {}", out.display(), side_path.display());
    Ok(())
}

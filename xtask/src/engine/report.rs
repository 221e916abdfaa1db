//! `cargo xtask lut engine report`: our engine files and the engines' shipped tables, both
//! decoded and sampled as the engine's shader samples them (uv = physical value at texel
//! centres, bilinear, clamp to edge), against the f64 integral at the same random points.
//! Writes docs/engines.md.

use super::{generate, integral, Engine as Target};
use anyhow::{anyhow, bail, Context, Result};
use half::f16;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A decoded table in shader order: `a[row * n + col]`, column = μ index, row = r index
/// (row k at texture coordinate (k + ½)/n).
pub struct Table {
    pub n: usize,
    pub a: Vec<f64>,
    pub b: Vec<f64>,
}

/// Largest table edge decoded (files are sized by this limit, never by their header alone).
const MAX_EDGE: usize = 4096;

impl Table {
    /// Bilinear between texel centres with clamp to edge at (μ, r).
    pub fn sample(&self, mu: f64, r: f64) -> (f64, f64) {
        let n = self.n;
        let idx = |x: f64| {
            let p = (x.clamp(0.0, 1.0) * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
            let i0 = (p.floor() as usize).min(n - 1);
            let i1 = (i0 + 1).min(n - 1);
            (i0, i1, p - i0 as f64)
        };
        let (x0, x1, fx) = idx(mu);
        let (y0, y1, fy) = idx(r);
        let bl = |v: &[f64]| {
            let top = v[y0 * n + x0] * (1.0 - fx) + v[y0 * n + x1] * fx;
            let bot = v[y1 * n + x0] * (1.0 - fx) + v[y1 * n + x1] * fx;
            top * (1.0 - fy) + bot * fy
        };
        (bl(&self.a), bl(&self.b))
    }
}

fn check_edge(w: usize, h: usize, what: &str) -> Result<usize> {
    if w != h || !(2..=MAX_EDGE).contains(&w) {
        bail!("{what}: {w}×{h} is not a square table of edge 2..={MAX_EDGE}");
    }
    Ok(w)
}

fn f16v(lo: u8, hi: u8) -> f64 {
    f16::from_bits(u16::from_le_bytes([lo, hi])).to_f64()
}

/// lut_ggx.png (8- or 16-bit RGB): R = A, G = B, column μ, top row = smallest r.
pub fn decode_khronos(bytes: &[u8]) -> Result<Table> {
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    dec.set_transformations(png::Transformations::IDENTITY);
    let mut rd = dec.read_info()?;
    let info = rd.info();
    let n = check_edge(info.width as usize, info.height as usize, "png")?;
    let (ct, bd) = (info.color_type, info.bit_depth);
    let mut buf = vec![0; rd.output_buffer_size()];
    rd.next_frame(&mut buf)?;
    let (chan, bytes_per) = match (ct, bd) {
        (png::ColorType::Rgb, png::BitDepth::Eight) => (3, 1),
        (png::ColorType::Rgba, png::BitDepth::Eight) => (4, 1),
        (png::ColorType::Rgb, png::BitDepth::Sixteen) => (3, 2),
        _ => bail!("png: {ct:?} {bd:?} is not an 8/16-bit RGB(A) table"),
    };
    let get = |i: usize, c: usize| -> f64 {
        let o = (i * chan + c) * bytes_per;
        if bytes_per == 1 {
            buf[o] as f64 / 255.0
        } else {
            u16::from_be_bytes([buf[o], buf[o + 1]]) as f64 / 65535.0
        }
    };
    let a = (0..n * n).map(|i| get(i, 0)).collect();
    let b = (0..n * n).map(|i| get(i, 1)).collect();
    Ok(Table { n, a, b })
}

/// dfg.ktx2 (R16G16_SFLOAT, optionally Zstandard): R = A, G = B, row 0 = smallest r.
pub fn decode_bevy(bytes: &[u8]) -> Result<Table> {
    let rd = ktx2::Reader::new(bytes).map_err(|e| anyhow!("ktx2: {e:?}"))?;
    let h = rd.header();
    if h.format != Some(ktx2::Format::R16G16_SFLOAT) {
        bail!("ktx2: format {:?} is not R16G16_SFLOAT", h.format);
    }
    let n = check_edge(h.pixel_width as usize, h.pixel_height as usize, "ktx2")?;
    let level = rd
        .levels()
        .next()
        .ok_or_else(|| anyhow!("ktx2: no level"))?;
    let raw = match h.supercompression_scheme {
        None => level.data.to_vec(),
        Some(ktx2::SupercompressionScheme::Zstandard) => {
            zstd::bulk::decompress(level.data, n * n * 4).map_err(|e| anyhow!("ktx2 zstd: {e}"))?
        }
        Some(s) => bail!("ktx2: supercompression {s:?} not supported"),
    };
    if raw.len() != n * n * 4 {
        bail!("ktx2: {} bytes of level data for {n}×{n} RG16F", raw.len());
    }
    let a = (0..n * n)
        .map(|i| f16v(raw[4 * i], raw[4 * i + 1]))
        .collect();
    let b = (0..n * n)
        .map(|i| f16v(raw[4 * i + 2], raw[4 * i + 3]))
        .collect();
    Ok(Table { n, a, b })
}

/// Filament DDS (R16G16B16A16_FLOAT, R = B, G = A + B): GL row j = stored row n − 1 − j.
pub fn decode_filament(bytes: &[u8]) -> Result<Table> {
    let dds = ddsfile::Dds::read(std::io::Cursor::new(bytes)).map_err(|e| anyhow!("dds: {e}"))?;
    if dds.get_dxgi_format() != Some(ddsfile::DxgiFormat::R16G16B16A16_Float) {
        bail!(
            "dds: format {:?} is not R16G16B16A16_FLOAT",
            dds.get_dxgi_format()
        );
    }
    let n = check_edge(dds.get_width() as usize, dds.get_height() as usize, "dds")?;
    let data = dds.get_data(0).map_err(|e| anyhow!("dds: {e}"))?;
    if data.len() < n * n * 8 {
        bail!("dds: {} data bytes for {n}×{n} RGBA16F", data.len());
    }
    let (mut a, mut b) = (vec![0.0; n * n], vec![0.0; n * n]);
    for y in 0..n {
        let j = n - 1 - y;
        for x in 0..n {
            let o = (y * n + x) * 8;
            let r = f16v(data[o], data[o + 1]);
            let g = f16v(data[o + 2], data[o + 3]);
            a[j * n + x] = g - r;
            b[j * n + x] = r;
        }
    }
    Ok(Table { n, a, b })
}

/// three.js raw RG16F (A, B), memory row = μ index, column = r index.
pub fn decode_threejs(bytes: &[u8]) -> Result<Table> {
    let texels = bytes.len() / 4;
    let n = (texels as f64).sqrt().round() as usize;
    if n * n * 4 != bytes.len() {
        bail!(
            "bin: {} bytes is not a square table of RG16F pairs",
            bytes.len()
        );
    }
    check_edge(n, n, "bin")?;
    let (mut a, mut b) = (vec![0.0; n * n], vec![0.0; n * n]);
    for m in 0..n {
        for c in 0..n {
            let o = (m * n + c) * 4;
            a[c * n + m] = f16v(bytes[o], bytes[o + 1]);
            b[c * n + m] = f16v(bytes[o + 2], bytes[o + 3]);
        }
    }
    Ok(Table { n, a, b })
}

/// Max |ΔA|, |ΔB| overall and for μ < 0.1 at the points.
#[derive(Clone, Copy, Default)]
pub struct Errs {
    pub a: f64,
    pub b: f64,
    pub a_low: f64,
    pub b_low: f64,
}

/// Random points in the texel-centre range of an n-edge table (half of them with μ < 0.1)
/// and the integral at each.
pub fn points(n: usize, count: usize, seed: u64) -> Vec<(f64, f64, f64, f64)> {
    let lo = 0.5 / n as f64;
    let hi = 1.0 - lo;
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let pts: Vec<(f64, f64)> = (0..count)
        .map(|k| {
            let mu_hi = if k % 2 == 0 { hi } else { 0.1f64.max(lo) };
            (rng.random_range(lo..mu_hi), rng.random_range(lo..hi))
        })
        .collect();
    pts.par_iter()
        .map(|&(mu, r)| {
            let (a, b) = integral(mu, r);
            (mu, r, a, b)
        })
        .collect()
}

pub fn errors(t: &Table, pts: &[(f64, f64, f64, f64)]) -> Errs {
    let mut e = Errs::default();
    for &(mu, r, a, b) in pts {
        let (sa, sb) = t.sample(mu, r);
        let (da, db) = ((sa - a).abs(), (sb - b).abs());
        e.a = e.a.max(da);
        e.b = e.b.max(db);
        if mu < 0.1 {
            e.a_low = e.a_low.max(da);
            e.b_low = e.b_low.max(db);
        }
    }
    e
}

/// Max |ΔA|, |ΔB| of the texel values themselves against the integral at each texel's centre
/// (where bilinear sampling returns the texel), on every `step`-th row and column.
pub fn texel_errors(t: &Table, step: usize) -> Errs {
    let n = t.n;
    let idx: Vec<(usize, usize)> = (step / 2..n)
        .step_by(step)
        .flat_map(|row| (step / 2..n).step_by(step).map(move |col| (row, col)))
        .collect();
    let v: Vec<(f64, f64, f64)> = idx
        .par_iter()
        .map(|&(row, col)| {
            let mu = super::centre(col, n);
            let (a, b) = integral(mu, super::centre(row, n));
            let i = row * n + col;
            (mu, (t.a[i] - a).abs(), (t.b[i] - b).abs())
        })
        .collect();
    let mut e = Errs::default();
    for (mu, da, db) in v {
        e.a = e.a.max(da);
        e.b = e.b.max(db);
        if mu < 0.1 {
            e.a_low = e.a_low.max(da);
            e.b_low = e.b_low.max(db);
        }
    }
    e
}

struct Engine {
    t: Target,
    ours: &'static str,
    theirs: &'static str,
    decode: fn(&[u8]) -> Result<Table>,
    label: &'static str,
}

const ENGINES: [Engine; 4] = [
    Engine {
        t: Target::Khronos,
        ours: "lut_ggx.png",
        theirs: "khronos/lut_ggx.png",
        decode: decode_khronos,
        label: "glTF Sample Viewer `lut_ggx.png` (1024², RGB 8-bit)",
    },
    Engine {
        t: Target::Bevy,
        ours: "dfg.ktx2",
        theirs: "bevy/dfg.ktx2",
        decode: decode_bevy,
        label: "Bevy `dfg.ktx2` (64², R16G16_SFLOAT, Zstandard)",
    },
    Engine {
        t: Target::Filament,
        ours: "dfg_multiscatter.dds",
        theirs: "filament/filament_dfg_multiscatter_64_rgba16f.dds",
        decode: decode_filament,
        label: "Filament `cmgen --ibl-dfg-multiscatter` DDS (64², RGBA16F)",
    },
    Engine {
        t: Target::Threejs,
        ours: "dfg_lut.bin",
        theirs: "threejs/three_dfg_lut_16x16_rg16f.bin",
        decode: decode_threejs,
        label: "three.js `DFGLUT.js` (16², RG16F)",
    },
];

/// Points per engine (half with μ < 0.1).
pub const POINTS: usize = 4000;
const SEED: u64 = 0x0E16_11E5;

pub fn run(out: PathBuf, anchors: Option<PathBuf>, doc: Option<PathBuf>) -> Result<()> {
    let root = crate::fsio::workspace_root();
    // Each engine's table from `--anchors`, else from the first default folder that has it.
    let anchor_dirs = match anchors {
        Some(a) => vec![a],
        None => vec![root.join(".cache/anchors"), root.join("../shared/anchors")],
    };
    let doc = doc.unwrap_or_else(|| root.join("docs/engines.md"));
    let mut rows = String::new();
    let mut khr16 = String::new();
    let mut trows = String::new();
    for e in &ENGINES {
        let dir = out.join(e.t.name());
        let ours_path = dir.join(e.ours);
        if !ours_path.exists() {
            println!("report: {} missing, generating it", ours_path.display());
            generate(e.t, e.t.native_size(), &dir, false, false)?;
        }
        let ours = read_table(&ours_path, e.decode)?;
        if ours.n != e.t.native_size() {
            bail!(
                "{}: {}² is not the engine's size {}² (regenerate without --size)",
                ours_path.display(),
                ours.n,
                e.t.native_size()
            );
        }
        let pts = points(ours.n, POINTS, SEED);
        let eo = errors(&ours, &pts);
        let step = (ours.n / 64).max(1);
        let to = texel_errors(&ours, step);
        let theirs_path = anchor_dirs
            .iter()
            .map(|d| d.join(e.theirs))
            .find(|p| p.exists())
            .unwrap_or_else(|| anchor_dirs[0].join(e.theirs));
        let (theirs, theirs_t) = if theirs_path.exists() {
            let t = read_table(&theirs_path, e.decode)?;
            (Some(errors(&t, &pts)), Some(texel_errors(&t, step)))
        } else {
            println!(
                "report: {} absent: engine's row skipped",
                theirs_path.display()
            );
            (None, None)
        };
        let fmt = |x: f64| format!("{x:.2e}");
        let cells = |x: Option<Errs>| match x {
            Some(x) => [fmt(x.a), fmt(x.b), fmt(x.a_low), fmt(x.b_low)],
            None => ["—".to_string(), "—".into(), "—".into(), "—".into()],
        };
        for (who, c) in [("shipped", cells(theirs)), ("ours", cells(Some(eo)))] {
            writeln!(
                rows,
                "| {} | {who} | {} | {} | {} | {} |",
                e.label, c[0], c[1], c[2], c[3]
            )?;
        }
        let every = if step > 1 {
            format!(" (every {step}th row and column)")
        } else {
            String::new()
        };
        for (who, c) in [("shipped", cells(theirs_t)), ("ours", cells(Some(to)))] {
            writeln!(
                trows,
                "| {}{every} | {who} | {} | {} | {} | {} |",
                e.label, c[0], c[1], c[2], c[3]
            )?;
        }
        if e.t == Target::Khronos {
            let p16 = dir.join("lut_ggx_16bit.png");
            let e16 = errors(&read_table(&p16, decode_khronos)?, &pts);
            writeln!(
                khr16,
                "| glTF Sample Viewer layout, our 16-bit PNG | ours | {} | {} | {} | {} |",
                fmt(e16.a),
                fmt(e16.b),
                fmt(e16.a_low),
                fmt(e16.b_low)
            )?;
        }
    }
    let text = format!(
        "# Engine LUTs: drop-in split-sum tables\n\n\
         <!-- Generated by `cargo xtask lut engine report`; do not edit by hand. -->\n\n\
         `cargo xtask lut engine <target> [--size N] [--out DIR] [--force]` writes the split-sum pair\n\
         (A, B) for GGX with height-correlated Smith, α = r² (r = perceptual roughness), in the\n\
         container, channel layout, orientation and texel placement that each engine's shader\n\
         samples, with a JSON sidecar (inverse mapping, roughness convention, clamp range, linear\n\
         values) and a GLSL and a WGSL function that sample it. Every texel is the integral at its\n\
         own texel centre, computed in f64 and rounded to nearest in the file's encoding.\n\n\
         | target | files | layout |\n|---|---|---|\n\
         | `khronos` | `lut_ggx.png`, `lut_ggx_16bit.png`, `lut_ggx_A_16bit.png`, `lut_ggx_B_16bit.png` | 1024², R = A, G = B, B = 0; μ along x, r down the rows from the top |\n\
         | `bevy` | `dfg.ktx2` | 64², KTX2 R16G16_SFLOAT, Zstandard level 22; R = A, G = B; row 0 = smallest r |\n\
         | `filament` | `dfg_multiscatter.dds` | 64², DDS DX10 R16G16B16A16_FLOAT; R = B, G = A + B, B = 0, A = 1 |\n\
         | `threejs` | `dfg_lut.bin`, `dfg_lut.js` | 16², raw little-endian RG16F (A, B); memory row = μ |\n\
         | `exr` | `dfg_ggx.exr` | 64², OpenEXR 32-bit float R = A, G = B; μ along x, r down the rows |\n\n\
         Each target also writes `<stem>.json`, `<stem>.glsl`, `<stem>.wgsl`. Pillow opens 16-bit RGB\n\
         PNGs as 8-bit without a warning; the single-channel 16-bit PNGs read correctly.\n\n\
         ## Accuracy against the converged integral\n\n\
         Both files decoded and sampled as the engine's shader samples them (uv = (μ, r), or (r, μ)\n\
         for three.js, bilinear between texel centres, clamp to edge) at {POINTS} random (μ, r) in the\n\
         texel-centre range of the engine's size (half of them with μ < 0.1), against the f64\n\
         integral at the same points. Our error is the bilinear interpolation error of the table\n\
         plus at most half a unit of the encoding; the shipped tables add their sampling noise\n\
         (Monte Carlo or too few samples near grazing) and, for Filament, a one-texel roughness shift.\n\n\
         | table | file | max abs(ΔA) | max abs(ΔB) | max abs(ΔA), μ < 0.1 | max abs(ΔB), μ < 0.1 |\n\
         |---|---|---|---|---|---|\n{rows}{khr16}\n\
         At random points the bilinear interpolation error of a 64² or 16² table dominates both\n\
         files near grazing (B changes by ~0.1 per texel there), so they differ little; the\n\
         table's own error shows at the texel centres, where the sampler returns the texel:\n\
         each texel against the integral at the centre the shader reads it at (Filament's GL row\n\
         j at r = (j + ½)/64).\n\n\
         | table | file | max abs(ΔA) | max abs(ΔB) | max abs(ΔA), μ < 0.1 | max abs(ΔB), μ < 0.1 |\n\
         |---|---|---|---|---|---|\n{trows}\n\
         ## Filament's one-texel roughness shift\n\n\
         Filament's shader reads the DFG texture at uv = (n·v, perceptual roughness), and the GL row\n\
         j (t = (j + ½)/64) is the stored DDS row y = 63 − j. cmgen fills stored row y with the\n\
         integral at r = (64 − y + ½)/64, i.e. GL row j holds r = (j + 1.5)/64: every row one texel\n\
         (1/64 in r) too rough, and the top two GL rows both r = 1 (clamped). Our\n\
         `dfg_multiscatter.dds` fills stored row y with r = (64 − y − ½)/64, so GL row j holds\n\
         r = (j + ½)/64, the texel centre the shader samples; the channel layout (R = B, G = A + B,\n\
         B = 0, A = 1) is Filament's.\n\n\
         ## Sampling functions\n\n\
         All placements are texel centres, so for every target the texture coordinate is the\n\
         physical value clamped to [0, 1]: `uv = (n·v, r)` (three.js: `(r, n·v)`), linear filtering,\n\
         clamp to edge, level 0. Filament decodes A = G − R, B = R. The WGSL functions are\n\
         validated with naga in the tests; the khronos GLSL function runs in the WebGL2 test\n\
         (`cargo xtask web`).\n"
    );
    let tmp = doc.with_extension("md.tmp");
    std::fs::write(&tmp, text).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, &doc).with_context(|| format!("writing {}", doc.display()))?;
    println!("report: wrote {}", doc.display());
    Ok(())
}

fn read_table(p: &Path, decode: fn(&[u8]) -> Result<Table>) -> Result<Table> {
    let meta = std::fs::metadata(p).with_context(|| format!("reading {}", p.display()))?;
    if meta.len() > 64 << 20 {
        bail!(
            "{}: {} bytes is too large for a table",
            p.display(),
            meta.len()
        );
    }
    let bytes = std::fs::read(p).with_context(|| format!("reading {}", p.display()))?;
    decode(&bytes).with_context(|| format!("decoding {}", p.display()))
}

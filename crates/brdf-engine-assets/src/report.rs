//! Engine files read back and compared with the integral: decoders of each engine's
//! container and layout into one shader-order [`Table`], the bilinear sampling every engine's
//! shader does, the error measures of `docs/engines.md`, and the report's Markdown (template
//! `templates/engines.md`, rendered by [`fill`]).

use crate::{centre, integral, Engine};
use half::f16;
use minijinja::{context, AutoEscape, Environment, UndefinedBehavior, Value};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::fmt;

pub mod sheen;

/// A decoded table in shader order: `a[row * n + col]`, column = μ index, row = r index
/// (row k at texture coordinate (k + ½)/n).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The table edge.
    pub n: usize,
    /// A at each texel.
    pub a: Vec<f64>,
    /// B at each texel.
    pub b: Vec<f64>,
}

/// Why a file could not be decoded.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodeError(pub String);

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DecodeError {}

fn bad<T>(s: String) -> Result<T, DecodeError> {
    Err(DecodeError(s))
}

/// Largest table edge decoded (files are sized by this limit, never by their header alone).
pub const MAX_EDGE: usize = 4096;

impl Table {
    /// Bilinear between texel centres with clamp to edge at (μ, r): the texel coordinate
    /// p = clamp(x·n − ½, 0, n − 1) on each axis, weights p − ⌊p⌋.
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

fn check_edge(w: usize, h: usize, what: &str) -> Result<usize, DecodeError> {
    if w != h || !(2..=MAX_EDGE).contains(&w) {
        return bad(format!(
            "{what}: {w}×{h} is not a square table of edge 2..={MAX_EDGE}"
        ));
    }
    Ok(w)
}

fn f16v(lo: u8, hi: u8) -> f64 {
    f16::from_bits(u16::from_le_bytes([lo, hi])).to_f64()
}

/// An 8- or 16-bit RGB(A) square PNG as unit values: (edge n, channels per pixel, values
/// row-major from the top row, channels interleaved, each `stored / (2^bits − 1)`).
pub fn png_units(bytes: &[u8]) -> Result<(usize, usize, Vec<f64>), DecodeError> {
    let e = |e: png::DecodingError| DecodeError(format!("png: {e}"));
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    dec.set_transformations(png::Transformations::IDENTITY);
    let mut rd = dec.read_info().map_err(e)?;
    let info = rd.info();
    let n = check_edge(info.width as usize, info.height as usize, "png")?;
    let (ct, bd) = (info.color_type, info.bit_depth);
    let (chan, bytes_per) = match (ct, bd) {
        (png::ColorType::Rgb, png::BitDepth::Eight) => (3, 1),
        (png::ColorType::Rgba, png::BitDepth::Eight) => (4, 1),
        (png::ColorType::Rgb, png::BitDepth::Sixteen) => (3, 2),
        _ => {
            return bad(format!(
                "png: {ct:?} {bd:?} is not an 8/16-bit RGB(A) table"
            ))
        }
    };
    let mut buf = vec![0; rd.output_buffer_size()];
    rd.next_frame(&mut buf).map_err(e)?;
    let v = if bytes_per == 1 {
        buf.iter()
            .take(n * n * chan)
            .map(|&b| b as f64 / 255.0)
            .collect()
    } else {
        buf.chunks_exact(2)
            .take(n * n * chan)
            .map(|b| u16::from_be_bytes([b[0], b[1]]) as f64 / 65535.0)
            .collect()
    };
    Ok((n, chan, v))
}

/// lut_ggx.png (8- or 16-bit RGB): R = A, G = B, column μ, top row = smallest r.
pub fn decode_khronos(bytes: &[u8]) -> Result<Table, DecodeError> {
    let (n, chan, v) = png_units(bytes)?;
    let a = v.iter().step_by(chan).copied().collect();
    let b = v.iter().skip(1).step_by(chan).copied().collect();
    Ok(Table { n, a, b })
}

/// dfg.ktx2 (R16G16_SFLOAT, optionally Zstandard): R = A, G = B, row 0 = smallest r.
pub fn decode_bevy(bytes: &[u8]) -> Result<Table, DecodeError> {
    let rd = ktx2::Reader::new(bytes).map_err(|e| DecodeError(format!("ktx2: {e:?}")))?;
    let h = rd.header();
    if h.format != Some(ktx2::Format::R16G16_SFLOAT) {
        return bad(format!("ktx2: format {:?} is not R16G16_SFLOAT", h.format));
    }
    let n = check_edge(h.pixel_width as usize, h.pixel_height as usize, "ktx2")?;
    let Some(level) = rd.levels().next() else {
        return bad("ktx2: no level".into());
    };
    let raw = match h.supercompression_scheme {
        None => level.data.to_vec(),
        Some(ktx2::SupercompressionScheme::Zstandard) => {
            zstd::bulk::decompress(level.data, n * n * 4)
                .map_err(|e| DecodeError(format!("ktx2 zstd: {e}")))?
        }
        Some(s) => return bad(format!("ktx2: supercompression {s:?} not supported")),
    };
    if raw.len() != n * n * 4 {
        return bad(format!(
            "ktx2: {} bytes of level data for {n}×{n} RG16F",
            raw.len()
        ));
    }
    let raw = &raw;
    let ch = |c: usize| (0..n * n).map(move |i| f16v(raw[4 * i + c], raw[4 * i + c + 1]));
    Ok(Table {
        n,
        a: ch(0).collect(),
        b: ch(2).collect(),
    })
}

/// Filament DDS (R16G16B16A16_FLOAT, R = B, G = A + B): GL row j = stored row n − 1 − j.
pub fn decode_filament(bytes: &[u8]) -> Result<Table, DecodeError> {
    let dds = ddsfile::Dds::read(std::io::Cursor::new(bytes))
        .map_err(|e| DecodeError(format!("dds: {e}")))?;
    let format = dds.get_dxgi_format();
    if format != Some(ddsfile::DxgiFormat::R16G16B16A16_Float) {
        return bad(format!("dds: format {format:?} is not R16G16B16A16_FLOAT"));
    }
    let n = check_edge(dds.get_width() as usize, dds.get_height() as usize, "dds")?;
    let data = dds
        .get_data(0)
        .map_err(|e| DecodeError(format!("dds: {e}")))?;
    if data.len() < n * n * 8 {
        return bad(format!(
            "dds: {} data bytes for {n}×{n} RGBA16F",
            data.len()
        ));
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
pub fn decode_threejs(bytes: &[u8]) -> Result<Table, DecodeError> {
    let n = ((bytes.len() / 4) as f64).sqrt().round() as usize;
    if n * n * 4 != bytes.len() {
        return bad(format!(
            "bin: {} bytes is not a square table of RG16F pairs",
            bytes.len()
        ));
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

/// Max |ΔA|, |ΔB| overall and for μ < 0.1.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Errs {
    /// max |ΔA|.
    pub a: f64,
    /// max |ΔB|.
    pub b: f64,
    /// max |ΔA| for μ < 0.1.
    pub a_low: f64,
    /// max |ΔB| for μ < 0.1.
    pub b_low: f64,
}

impl Errs {
    /// Takes one point's errors at μ into the maxima.
    fn add(&mut self, mu: f64, da: f64, db: f64) {
        self.a = self.a.max(da);
        self.b = self.b.max(db);
        if mu < 0.1 {
            self.a_low = self.a_low.max(da);
            self.b_low = self.b_low.max(db);
        }
    }
}

/// Random points in the texel-centre range of an n-edge table (half of them with μ < 0.1)
/// and the integral at each: (μ, r, A, B).
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

/// The table sampled as the shader samples it ([`Table::sample`]) against the integral at
/// the points.
pub fn errors(t: &Table, pts: &[(f64, f64, f64, f64)]) -> Errs {
    let mut e = Errs::default();
    for &(mu, r, a, b) in pts {
        let (sa, sb) = t.sample(mu, r);
        e.add(mu, (sa - a).abs(), (sb - b).abs());
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
            let mu = centre(col, n);
            let (a, b) = integral(mu, centre(row, n));
            let i = row * n + col;
            (mu, (t.a[i] - a).abs(), (t.b[i] - b).abs())
        })
        .collect();
    let mut e = Errs::default();
    for (mu, da, db) in v {
        e.add(mu, da, db);
    }
    e
}

/// An engine's shipped table and ours, compared in `docs/engines.md`.
pub struct Shipped {
    /// The engine.
    pub engine: Engine,
    /// Our file's name.
    pub ours: &'static str,
    /// The shipped file, relative to the anchors folder.
    pub theirs: &'static str,
    /// The decoder of both.
    pub decode: fn(&[u8]) -> Result<Table, DecodeError>,
    /// The report's label.
    pub label: &'static str,
}

/// The engines whose shipped tables the report compares.
pub const SHIPPED: [Shipped; 4] = [
    Shipped {
        engine: Engine::Khronos,
        ours: "lut_ggx.png",
        theirs: "khronos/lut_ggx.png",
        decode: decode_khronos,
        label: "glTF Sample Viewer `lut_ggx.png` (1024², RGB 8-bit)",
    },
    Shipped {
        engine: Engine::Bevy,
        ours: "dfg.ktx2",
        theirs: "bevy/dfg.ktx2",
        decode: decode_bevy,
        label: "Bevy `dfg.ktx2` (64², R16G16_SFLOAT, Zstandard)",
    },
    Shipped {
        engine: Engine::Filament,
        ours: "dfg_multiscatter.dds",
        theirs: "filament/filament_dfg_multiscatter_64_rgba16f.dds",
        decode: decode_filament,
        label: "Filament `cmgen --ibl-dfg-multiscatter` DDS (64², RGBA16F)",
    },
    Shipped {
        engine: Engine::Threejs,
        ours: "dfg_lut.bin",
        theirs: "threejs/three_dfg_lut_16x16_rg16f.bin",
        decode: decode_threejs,
        label: "three.js `DFGLUT.js` (16², RG16F)",
    },
];

/// Points per engine (half with μ < 0.1) and their seed.
pub const POINTS: usize = 4000;
/// The seed of [`points`] in the report.
pub const SEED: u64 = 0x0E16_11E5;

/// One engine's row of the report: errors at the random points and at the texel centres
/// (every `step`-th row and column), ours and the shipped table's (when it was found).
pub struct EngineRow {
    /// The report's label.
    pub label: String,
    /// The texel-centre sampling step.
    pub step: usize,
    /// The shipped table at the points.
    pub shipped: Option<Errs>,
    /// Ours at the points.
    pub ours: Errs,
    /// The shipped table at the texel centres.
    pub shipped_texels: Option<Errs>,
    /// Ours at the texel centres.
    pub ours_texels: Errs,
}

impl EngineRow {
    /// The row of engine `e`: our table `ours` and the shipped one `theirs` (when found) at
    /// the report's [`POINTS`] random points ([`points`] with [`SEED`]) and at every
    /// `n/64`-th texel centre, `n` being the engine's native size. With `extra`, that
    /// table's errors at the same points too (the report's 16-bit Khronos PNG).
    pub fn compute(
        e: &Shipped,
        ours: &Table,
        theirs: Option<&Table>,
        extra: Option<&Table>,
    ) -> (EngineRow, Option<Errs>) {
        let n = e.engine.native_size();
        let pts = points(n, POINTS, SEED);
        let step = (n / 64).max(1);
        let row = EngineRow {
            label: e.label.to_string(),
            step,
            shipped: theirs.map(|t| errors(t, &pts)),
            ours: errors(ours, &pts),
            shipped_texels: theirs.map(|t| texel_errors(t, step)),
            ours_texels: texel_errors(ours, step),
        };
        (row, extra.map(|t| errors(t, &pts)))
    }
}

/// The data of `docs/engines.md`.
pub struct EnginesReport {
    /// Random points per engine.
    pub points: usize,
    /// One row per engine of [`SHIPPED`].
    pub rows: Vec<EngineRow>,
    /// Our 16-bit Khronos PNG at the Khronos points.
    pub khronos_16bit: Option<Errs>,
    /// The shipped Khronos sheen textures against the converged sheen albedo, when found.
    pub sheen: Option<sheen::SheenCompare>,
}

/// `v` to two significant digits in fixed notation (0.72, 0.055, 0.0014).
fn sig2(v: f64) -> String {
    let digits = if v > 0.0 && v.is_finite() {
        (1 - v.log10().floor() as i32).max(0) as usize
    } else {
        2
    };
    format!("{v:.digits$}")
}

/// "a | b | a_low | b_low" to two significant digits, or "—" cells.
fn cells(x: Option<Errs>) -> String {
    match x {
        Some(x) => [x.a, x.b, x.a_low, x.b_low]
            .map(|v| format!("{v:.2e}"))
            .join(" | "),
        None => ["—"; 4].join(" | "),
    }
}

const ENGINES_TEMPLATE: &str = include_str!("../templates/engines.md");

/// `docs/engines.md` for these figures.
pub fn render_engines(r: &EnginesReport) -> Result<String, minijinja::Error> {
    let rows: Vec<Value> = r
        .rows
        .iter()
        .map(|e| {
            context! {
                label => e.label,
                every => if e.step > 1 { format!(" (every {}th row and column)", e.step) } else { String::new() },
                shipped => cells(e.shipped),
                ours => cells(Some(e.ours)),
                shipped_texels => cells(e.shipped_texels),
                ours_texels => cells(Some(e.ours_texels)),
            }
        })
        .collect();
    let khronos_16bit = r.khronos_16bit.map(|e| cells(Some(e)));
    let sheen = r.sheen.as_ref().map(|c| {
        let rows: Vec<Value> = c
            .diffs
            .iter()
            .map(|d| {
                context! {
                    label => d.label,
                    texels => d.texels.len(),
                    max => sig2(d.max),
                    mu => format!("{:.3}", d.at.0),
                    r => format!("{:.4}", d.at.1),
                    median => sig2(d.median),
                }
            })
            .collect();
        context! {
            n => c.n,
            step => c.step,
            sampled => c.sampled,
            above_ek => c.above_one[0],
            above_ash => c.above_one[1],
            max_ek => format!("{:.0}", c.max_converged[0]),
            max_ash => format!("{:.0}", c.max_converged[1]),
            rows,
        }
    });
    fill(
        ENGINES_TEMPLATE,
        context! { points => r.points, rows, khronos_16bit, sheen },
    )
}

/// Renders a Markdown (or other text) template: no escaping, undefined names are errors, a
/// block tag's own line break is dropped (so `{% if %}` lines leave no blank lines).
pub fn fill(template: &str, ctx: Value) -> Result<String, minijinja::Error> {
    let mut env = Environment::new();
    env.set_auto_escape_callback(|_| AutoEscape::None);
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_trim_blocks(true);
    env.set_keep_trailing_newline(true);
    env.add_template("t", template)?;
    env.get_template("t")?.render(ctx)
}

//! Difference images: each engine's published split-sum (DFG) table, read from the first of
//! the anchor folders that holds it (`.cache/anchors/` from `cargo xtask anchors`, then
//! `../shared/anchors/`; layouts in docs/engines.md) minus the project's converged table, i.e.
//! `brdf_core::split_sum::dfg_ggx` (GGX, height-correlated Smith, α = r², F90 = 1,
//! docs/conventions.md §8) with 32 × 32-point Gauss–Legendre rules, at the table's own (μ, r).

use crate::figures::{self, DiffMaps, DiffPanel};
use anyhow::{bail, Context, Result};
use brdf_core::quadrature::GaussLegendre;
use brdf_core::split_sum::dfg_ggx;
use brdf_lut::f16_to_f32;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One published table, decoded to (μ, r, A, B) texels (possibly subsampled).
pub struct Table {
    /// Short name.
    pub name: &'static str,
    /// What it is and how it differs from the project's model.
    pub note: &'static str,
    /// (μ, r, A, B).
    pub texels: Vec<(f64, f64, f64, f64)>,
    /// Texel pitch in μ and r of the shown grid.
    pub pitch: (f64, f64),
}

fn f16(b: &[u8], i: usize) -> f64 {
    f16_to_f32(u16::from_le_bytes([b[2 * i], b[2 * i + 1]])) as f64
}

fn read_png(bytes: &[u8]) -> Result<(usize, usize, usize, Vec<u8>)> {
    let dec = png::Decoder::new(bytes);
    let mut r = dec.read_info().map_err(|e| anyhow::anyhow!("png: {e}"))?;
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r
        .next_frame(&mut buf)
        .map_err(|e| anyhow::anyhow!("png: {e}"))?;
    buf.truncate(info.buffer_size());
    Ok((
        info.width as usize,
        info.height as usize,
        info.color_type.samples(),
        buf,
    ))
}

/// `rel` from the first folder of `dirs` that has it.
fn read_first(dirs: &[PathBuf], rel: &str) -> std::io::Result<Vec<u8>> {
    let mut last = std::io::Error::from(std::io::ErrorKind::NotFound);
    for d in dirs {
        match std::fs::read(d.join(rel)) {
            Ok(b) => return Ok(b),
            Err(e) => last = e,
        }
    }
    Err(last)
}

/// Texel centre k of n: (k + ½)/n.
fn centre(k: usize, n: usize) -> f64 {
    (k as f64 + 0.5) / n as f64
}

/// The texels `texel(row, col)` of an image of `h` rows and `w` columns, every `step`-th
/// row and column from `step / 2`, in row order.
fn sample_grid(
    w: usize,
    h: usize,
    step: usize,
    texel: impl Fn(usize, usize) -> (f64, f64, f64, f64),
) -> Vec<(f64, f64, f64, f64)> {
    let texel = &texel;
    (step / 2..h)
        .step_by(step)
        .flat_map(|i| (step / 2..w).step_by(step).map(move |j| texel(i, j)))
        .collect()
}

/// An 8-bit PNG table (A, B in the red and green channels, μ along x), every `step`-th
/// texel; r along y grows downwards, or upwards when `r_up`.
fn png8(
    f: &[u8],
    step: usize,
    r_up: bool,
    name: &'static str,
    note: &'static str,
) -> Result<Table> {
    let (w, h, spp, px) = read_png(f)?;
    if spp < 2 {
        bail!("{name}: {spp} channel(s), want red and green");
    }
    let texels = sample_grid(w, h, step, |i, j| {
        let k = (i * w + j) * spp;
        let r = centre(i, h);
        let r = if r_up { 1.0 - r } else { r };
        (
            centre(j, w),
            r,
            px[k] as f64 / 255.0,
            px[k + 1] as f64 / 255.0,
        )
    });
    let pitch = (step as f64 / w as f64, step as f64 / h as f64);
    Ok(Table {
        name,
        note,
        texels,
        pitch,
    })
}

/// A `w` × `h` two-channel f16 table (A, B), μ along the rows (`mu_rows`) or the columns.
fn f16_grid(raw: &[u8], w: usize, h: usize, mu_rows: bool) -> Vec<(f64, f64, f64, f64)> {
    sample_grid(w, h, 1, |i, j| {
        let k = (i * w + j) * 2;
        let (row, col) = (centre(i, h), centre(j, w));
        let (mu, r) = if mu_rows { (row, col) } else { (col, row) };
        (mu, r, f16(raw, k), f16(raw, k + 1))
    })
}

fn threejs(f: &[u8]) -> Result<Table> {
    if f.len() < 16 * 16 * 4 {
        bail!("threejs DFG table: {} bytes, want 1024", f.len());
    }
    Ok(Table {
        name: "three.js DFGLUT 16×16 (f16)",
        note: "same model, 4096 samples per texel",
        texels: f16_grid(f, 16, 16, true),
        pitch: (1.0 / 16.0, 1.0 / 16.0),
    })
}

/// Bevy's KTX2 (one zstd-compressed level of w × h RG16F; header offsets per the KTX2
/// specification: width at 20, height at 24, level 0's offset and length at 80 and 88).
fn bevy(f: &[u8]) -> Result<Table> {
    if f.len() < 96 || &f[1..7] != b"KTX 20" {
        bail!("bevy/dfg.ktx2: not KTX2");
    }
    let u32le = |o: usize| u32::from_le_bytes([f[o], f[o + 1], f[o + 2], f[o + 3]]) as usize;
    let u64le = |o: usize| u32le(o) + (u32le(o + 4) << 32);
    let (w, h) = (u32le(20), u32le(24));
    let (off, len) = (u64le(80), u64le(88));
    let level = off
        .checked_add(len)
        .and_then(|end| f.get(off..end))
        .context("bevy/dfg.ktx2: level 0 outside the file")?;
    let mut dec = ruzstd::decoding::StreamingDecoder::new(level)
        .map_err(|e| anyhow::anyhow!("zstd: {e:?}"))?;
    let mut raw = Vec::new();
    std::io::Read::read_to_end(&mut dec, &mut raw).context("zstd")?;
    if raw.len() < w * h * 4 {
        bail!(
            "bevy/dfg.ktx2: level 0 holds {} bytes, want {}",
            raw.len(),
            w * h * 4
        );
    }
    Ok(Table {
        name: "Bevy dfg.ktx2 64×64 (f16)",
        note: "same model",
        texels: f16_grid(&raw, w, h, false),
        pitch: (1.0 / w as f64, 1.0 / h as f64),
    })
}

/// Filament's DDS (148-byte header, 64 × 64 RGBA16F, multiscatter layout: (A + B, B) in
/// red and green, r = 1 at the top).
fn filament(f: &[u8]) -> Result<Table> {
    let Some(px) = f.get(148..148 + 64 * 64 * 8) else {
        bail!("filament DFG table: {} bytes, too short", f.len());
    };
    let mut t = Vec::new();
    // Row 0 is skipped: a duplicate r = 1 row (MANIFEST: the top two rows both hold r = 1).
    for y in 1..64 {
        let r = ((64.0 - y as f64 + 0.5) / 64.0).clamp(0.0, 1.0);
        for x in 0..64 {
            let k = (y * 64 + x) * 4;
            let (bb, ab) = (f16(px, k), f16(px, k + 1));
            t.push((centre(x, 64), r, ab - bb, bb));
        }
    }
    Ok(Table {
        name: "Filament cmgen DFG 64×64 (f16, multiscatter layout)",
        note: "same model; its rows are shifted by one texel in r (MANIFEST)",
        texels: t,
        pitch: (1.0 / 64.0, 1.0 / 64.0),
    })
}

/// The anchors: file (below an anchor folder) and decoder.
type Decoder = fn(&[u8]) -> Result<Table>;
const ANCHORS: [(&str, Decoder); 5] = [
    ("khronos/lut_ggx.png", |f| {
        let name = "Khronos glTF viewer lut_ggx.png (8-bit, every 32nd texel)";
        png8(
            f,
            32,
            false,
            name,
            "same model; 8-bit quantisation and sampling noise near grazing",
        )
    }),
    ("threejs/three_dfg_lut_16x16_rg16f.bin", threejs),
    ("bevy/dfg.ktx2", bevy),
    (
        "filament/filament_dfg_multiscatter_64_rgba16f.dds",
        filament,
    ),
    ("karis_legacy/brdfLUT_256_rgb8.png", |f| {
        let name = "legacy glTF/Karis brdfLUT.png 256×256 (8-bit, every 8th texel)";
        let note = "a different model: separable Schlick–GGX visibility, k = α/2 — the \
                    difference is mostly the model";
        png8(f, 8, true, name, note)
    }),
];

/// Decodes the anchors found in `dirs` (each file from the first folder that has it; missing
/// files are skipped).
pub fn load(dirs: &[PathBuf]) -> Result<Vec<Table>> {
    let mut v = Vec::new();
    for (rel, decode) in ANCHORS {
        if let Ok(f) = read_first(dirs, rel) {
            v.push(decode(&f).with_context(|| rel.to_string())?);
        }
    }
    Ok(v)
}

/// (ΔA, ΔB) = published − converged for every texel.
pub fn differences(t: &Table) -> Vec<(f64, f64, f64, f64)> {
    t.texels
        .par_iter()
        .map(|&(mu, r, a, b)| {
            let (ca, cb) = dfg_ggx::<f64, GaussLegendre<32>, GaussLegendre<32>>(mu, r);
            (mu, r, a - ca, b - cb)
        })
        .collect()
}

/// Writes `dfg_difference.svg|png` and returns the markdown section (or a note when no
/// anchor is found).
pub fn write(dir: &Path, anchors: &[PathBuf]) -> Result<String> {
    let tables = load(anchors)?;
    if tables.is_empty() {
        return Ok(
            "No published DFG table found in `.cache/anchors/` or `../shared/anchors/` \
                   (fetch them with `cargo xtask anchors`); the difference images were skipped."
                .to_string(),
        );
    }
    let mut md = String::from(
        "Published split-sum (DFG) tables minus the project's converged table (`brdf_core::split_sum::dfg_ggx`, GGX with \
         height-correlated Smith, α = r², 32 × 32-point Gauss–Legendre), at each table's own texel centres \
         (layouts: docs/conventions.md §8). Red: the published table is higher.\n\n\
         ![DFG differences](figures/dfg_difference.svg)\n\n\
         | table | texels | max \\|ΔA\\| | max \\|ΔA\\|, μ ≥ 0.1 | max \\|ΔB\\| | RMS ΔA | note |\n|---|---|---|---|---|---|---|\n",
    );
    let mut rows = Vec::new();
    for t in &tables {
        let d = differences(t);
        let ma = d.iter().fold(0.0f64, |m, p| m.max(p.2.abs()));
        let ma1 = d
            .iter()
            .filter(|p| p.0 >= 0.1)
            .fold(0.0f64, |m, p| m.max(p.2.abs()));
        let mb = d.iter().fold(0.0f64, |m, p| m.max(p.3.abs()));
        let rms = (d.iter().map(|p| p.2 * p.2).sum::<f64>() / d.len() as f64).sqrt();
        let _ = writeln!(
            md,
            "| {} | {} | {:.4} | {:.4} | {:.4} | {:.4} | {} |",
            t.name,
            d.len(),
            ma,
            ma1,
            mb,
            rms,
            t.note
        );
        let lim = ma.max(mb).max(1e-3);
        let lim = (lim * 1000.0).ceil() / 1000.0;
        rows.push((t, d, lim));
    }
    let n = rows.len() as u32;
    let panels = rows
        .iter()
        .flat_map(|(t, d, lim)| {
            (0..2).map(move |c| DiffPanel {
                caption: format!(
                    "{} {} (colour limit ±{:.3})",
                    if c == 0 { "ΔA" } else { "ΔB" },
                    t.name,
                    lim
                ),
                cells: d
                    .iter()
                    .map(|&(mu, r, da, db)| (mu, r, if c == 0 { da } else { db }))
                    .collect(),
                half: (t.pitch.0 / 2.0, t.pitch.1 / 2.0),
                lim: *lim,
            })
        })
        .collect();
    figures::write(
        dir,
        "dfg_difference",
        (1100, 330 * n),
        &DiffMaps { panels, cols: 2 },
    )?;
    Ok(md)
}

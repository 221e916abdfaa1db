//! `cargo xtask lut engine report`: our engine files and the engines' shipped tables, both
//! decoded and sampled as the engine's shader samples them, against the f64 integral at the
//! same random points (`brdf_engine_assets::report`). Writes docs/engines.md.

use super::generate;
use anyhow::{bail, Context, Result};
use brdf_engine_assets::report::sheen::{compare_sheen, SheenCompare};
use brdf_engine_assets::report::{
    decode_khronos, errors, points, render_engines, texel_errors, DecodeError, EngineRow,
    EnginesReport, Errs, Shipped, Table, POINTS, SEED, SHIPPED,
};
use brdf_validate::figures::{DiffMaps, DiffPanel};
use std::path::{Path, PathBuf};

pub fn run(out: PathBuf, anchors: Option<PathBuf>, doc: Option<PathBuf>) -> Result<()> {
    let root = crate::fsio::workspace_root();
    // Each engine's table from `--anchors`, else from the first default folder that has it.
    let anchor_dirs = match anchors {
        Some(a) => vec![a],
        None => vec![root.join(".cache/anchors"), root.join("../shared/anchors")],
    };
    let doc = doc.unwrap_or_else(|| root.join("docs/engines.md"));
    let mut report = EnginesReport {
        points: POINTS,
        rows: Vec::new(),
        khronos_16bit: None,
        sheen: None,
    };
    for e in &SHIPPED {
        let (row, k16) = compare(e, &out.join(e.engine.name()), &anchor_dirs)?;
        report.rows.push(row);
        report.khronos_16bit = report.khronos_16bit.or(k16);
    }
    let figures = doc.parent().unwrap_or(Path::new(".")).join("figures");
    report.sheen = sheen(&anchor_dirs, &figures)?;
    let tmp = doc.with_extension("md.tmp");
    std::fs::write(&tmp, render_engines(&report)?)
        .with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, &doc).with_context(|| format!("writing {}", doc.display()))?;
    println!("report: wrote {}", doc.display());
    Ok(())
}

/// One engine's row: our file in `dir` (generated when missing) and the shipped one from the
/// first anchors folder that has it; for Khronos also our 16-bit PNG at the same points.
fn compare(e: &Shipped, dir: &Path, anchor_dirs: &[PathBuf]) -> Result<(EngineRow, Option<Errs>)> {
    let n = e.engine.native_size();
    let ours_path = dir.join(e.ours);
    if !ours_path.exists() {
        println!("report: {} missing, generating it", ours_path.display());
        generate(e.engine, n, dir, false, false)?;
    }
    let ours = read_table(&ours_path, e.decode)?;
    if ours.n != n {
        bail!(
            "{}: {}² is not the engine's size {n}² (regenerate without --size)",
            ours_path.display(),
            ours.n
        );
    }
    let pts = points(n, POINTS, SEED);
    let step = (n / 64).max(1);
    let theirs_path = anchor_dirs
        .iter()
        .map(|d| d.join(e.theirs))
        .find(|p| p.exists())
        .unwrap_or_else(|| anchor_dirs[0].join(e.theirs));
    let theirs = if theirs_path.exists() {
        Some(read_table(&theirs_path, e.decode)?)
    } else {
        println!(
            "report: {} absent: engine's row skipped",
            theirs_path.display()
        );
        None
    };
    let k16 = match e.engine {
        brdf_engine_assets::Engine::Khronos => {
            let t = read_table(&dir.join("lut_ggx_16bit.png"), decode_khronos)?;
            Some(errors(&t, &pts))
        }
        _ => None,
    };
    let row = EngineRow {
        label: e.label.to_string(),
        step,
        shipped: theirs.as_ref().map(|t| errors(t, &pts)),
        ours: errors(&ours, &pts),
        shipped_texels: theirs.as_ref().map(|t| texel_errors(t, step)),
        ours_texels: texel_errors(&ours, step),
    };
    Ok((row, k16))
}

fn read_table(p: &Path, decode: fn(&[u8]) -> Result<Table, DecodeError>) -> Result<Table> {
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

/// The shipped Khronos sheen textures against the converged sheen albedo (every 16th texel)
/// and their difference maps, `figures/sheen_difference.svg|png`; `None` when the anchors
/// folders lack them.
fn sheen(anchor_dirs: &[PathBuf], figures: &Path) -> Result<Option<SheenCompare>> {
    let find = |rel: &str| anchor_dirs.iter().map(|d| d.join(rel)).find(|p| p.exists());
    let (Some(c), Some(s)) = (
        find("khronos/lut_charlie.png"),
        find("khronos/lut_sheen_E.png"),
    ) else {
        println!("report: shipped Khronos sheen textures absent: their comparison skipped");
        return Ok(None);
    };
    let read = |p: &Path| -> Result<Vec<u8>> {
        let len = std::fs::metadata(p)?.len();
        if len > 64 << 20 {
            bail!("{}: {len} bytes is too large for a table", p.display());
        }
        std::fs::read(p).with_context(|| format!("reading {}", p.display()))
    };
    let cmp = compare_sheen(&read(&c)?, &read(&s)?, 16)?;
    let panels = cmp
        .diffs
        .iter()
        .map(|d| {
            // Colour limit: the 99th percentile of |difference| (two digits), saturating beyond.
            let mut a: Vec<f64> = d.texels.iter().map(|t| t.2.abs()).collect();
            a.sort_by(f64::total_cmp);
            let p99 = a.get(a.len() * 99 / 100).copied().unwrap_or(1.0).max(1e-4);
            let lim = sig2_up(p99);
            DiffPanel {
                caption: format!("{} (colour ±{lim})", d.label),
                cells: d.texels.clone(),
                half: (
                    0.5 * cmp.step as f64 / cmp.n as f64,
                    0.5 * cmp.step as f64 / cmp.n as f64,
                ),
                lim,
            }
        })
        .collect();
    brdf_validate::figures::write(
        figures,
        "sheen_difference",
        (1500, 460),
        &DiffMaps { panels, cols: 3 },
    )?;
    println!(
        "report: wrote {}/sheen_difference.svg|png",
        figures.display()
    );
    Ok(Some(cmp))
}

/// `v` rounded up to two significant digits.
fn sig2_up(v: f64) -> f64 {
    let scale = 10f64.powi(1 - v.log10().floor() as i32);
    (v * scale).ceil() / scale
}

//! `cargo xtask lut engine report`: our engine files and the engines' shipped tables, both
//! decoded and sampled as the engine's shader samples them, against the f64 integral at the
//! same random points (`brdf_engine_assets::report`). Writes docs/engines.md.

use super::generate;
use anyhow::{bail, Context, Result};
use brdf_engine_assets::report::sheen::{compare_sheen, SheenCompare};
use brdf_engine_assets::report::{
    decode_khronos, render_engines, DecodeError, EngineRow, EnginesReport, Errs, Shipped, Table,
    POINTS, SHIPPED,
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
    brdf_engine_assets::fsio::replace(&doc, render_engines(&report)?.as_bytes())?;
    println!("report: wrote {}", doc.display());
    Ok(())
}

/// One engine's row ([`EngineRow::compute`]): our file in `dir` (generated when missing)
/// and the shipped one from the first anchors folder that has it; for Khronos also our
/// 16-bit PNG at the same points.
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
            Some(read_table(&dir.join("lut_ggx_16bit.png"), decode_khronos)?)
        }
        _ => None,
    };
    Ok(EngineRow::compute(e, &ours, theirs.as_ref(), k16.as_ref()))
}

/// A table file (a regular file of at most 64 MiB) decoded by `decode`.
fn read_table(p: &Path, decode: fn(&[u8]) -> Result<Table, DecodeError>) -> Result<Table> {
    let bytes = crate::fsio::read_limited(p, MAX_TABLE_BYTES)?;
    decode(&bytes).with_context(|| format!("decoding {}", p.display()))
}

/// The largest engine table file read.
const MAX_TABLE_BYTES: u64 = 64 << 20;

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
    let read = |p: &Path| crate::fsio::read_limited(p, MAX_TABLE_BYTES);
    let cmp = compare_sheen(&read(&c)?, &read(&s)?, 16)?;
    let panels = cmp
        .diffs
        .iter()
        .map(|d| {
            let lim = d.colour_limit();
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

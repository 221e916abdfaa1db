//! The device ELF of the C example: flash and RAM by part (library kernels, LUT readers,
//! tables, C program), the README's C size table, and the functions that can reach core's
//! panic machinery.

use crate::device::elf::{elf_sections, elf_symbols, stdout_of, tidy, with_commas as thousands};
use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// Prints the sizes, checks (or with `update`, rewrites) the README's table and lists the
/// panic paths; a panic path outside brdf-lut goes to `errors`.
pub(crate) fn report(
    root: &Path,
    elf: &Path,
    stack: Option<u64>,
    update: bool,
    errors: &mut Vec<String>,
) -> Result<()> {
    let sz = sizes(elf)?;
    print_sizes(&sz, stack);
    readme_sizes(&root.join("README.md"), &sz, stack, update)?;
    let callers = panic_callers(elf)?;
    let (lut, other): (Vec<_>, Vec<_>) = callers.iter().partition(|c| c.contains("brdf_lut::"));
    if callers.is_empty() {
        println!("panic paths: none (no function calls into core's panic machinery)");
    } else {
        println!(
            "panic paths: {} bounds checks kept by the optimiser in brdf-lut ({}); none in brdf-core, brdf-ffi or the C program",
            lut.len(),
            lut.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")
        );
    }
    if !other.is_empty() {
        let names: Vec<&str> = other.iter().map(|s| s.as_str()).collect();
        errors.push(format!(
            "functions outside brdf-lut call into the panic machinery: {}",
            names.join(", ")
        ));
    }
    Ok(())
}

/// The functions of the device ELF (demangled, without hashes) that branch directly to
/// core's panic entry points or to a core function that does; core's own functions are not
/// listed.
fn panic_callers(elf: &Path) -> Result<Vec<String>> {
    let mut objdump = Command::new("arm-none-eabi-objdump");
    let text = stdout_of(objdump.args(["-d", "-C"]).arg(elf), "arm-none-eabi-objdump")?;
    // function → the functions it branches to
    let mut calls: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut cur = String::new();
    for l in text.lines() {
        if let Some(name) = l
            .strip_suffix(">:")
            .and_then(|h| h.split_once(" <"))
            .map(|x| x.1)
        {
            cur = tidy(name);
            calls.entry(cur.clone()).or_default();
        } else if l.contains("\tbl\t") || l.contains("\tb.w\t") || l.contains("\tb\t") {
            if let Some(target) = l.rsplit_once('<').map(|x| x.1.trim_end_matches('>')) {
                let target = tidy(target.split('+').next().unwrap_or(target));
                calls.entry(cur.clone()).or_default().push(target);
            }
        }
    }
    let is_core = |n: &str| n.starts_with("core::") || n.starts_with("<core::");
    let is_entry = |n: &str| {
        n.contains("panic") || n.contains("slice_index_fail") || n.contains("unwrap_failed")
    };
    // core functions that reach a panic entry, to a fixed point.
    let mut panicky: std::collections::BTreeSet<String> =
        calls.keys().filter(|n| is_entry(n)).cloned().collect();
    loop {
        let before = panicky.len();
        for (f, ts) in &calls {
            if is_core(f) && ts.iter().any(|t| panicky.contains(t)) {
                panicky.insert(f.clone());
            }
        }
        if panicky.len() == before {
            break;
        }
    }
    Ok(calls
        .iter()
        .filter(|(f, ts)| {
            !is_core(f)
                && !panicky.contains(*f)
                && ts.iter().any(|t| panicky.contains(t) || is_entry(t))
        })
        .map(|(f, _)| f.clone())
        .collect())
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Part {
    /// The library's kernels and their math (brdf-core, brdf-ffi, libm, soft-float helpers).
    Kernels,
    /// The LUT readers (parse, CRC, interpolation; serde/postcard code they instantiate).
    Readers,
    /// The embedded table bytes.
    Tables,
    /// The C program, its start-up and newlib-nano (memcpy, memset).
    Program,
}

struct Sizes {
    sections: BTreeMap<String, u64>,
    parts: BTreeMap<Part, u64>,
}

fn part(name: &str) -> Part {
    let has = |s: &str| name.contains(s);
    if name.starts_with("table_") {
        Part::Tables
    } else if (name.starts_with("brdf_") && (has("table") || has("parse")))
        || has("::lut::")
        || has("brdf_ffi::lut")
        || has("postcard")
        || has("serde")
        || has("heapless")
        || has("brdf_lut")
    {
        Part::Readers
    } else if name.starts_with("brdf_")
        || has("brdf_core")
        || has("brdf_ffi")
        || has("libm::")
        || has("compiler_builtins")
        || name.starts_with("__aeabi_")
        || name.ends_with("df3")
        || name.ends_with("sf2")
        || name.ends_with("df2")
        || name.ends_with("dfsi")
        || name.ends_with("sidf")
        || has("core::")
    {
        Part::Kernels
    } else {
        Part::Program
    }
}

fn sizes(elf: &Path) -> Result<Sizes> {
    let sections = elf_sections(elf)?
        .into_iter()
        .map(|(k, (len, _))| (k, len))
        .collect();
    let mut parts = BTreeMap::new();
    for sym in elf_symbols(elf)? {
        // Flash: code and read-only data (t/T, r/R) and initialised data (d/D, its load image).
        if matches!(sym.ty.as_str(), "t" | "T" | "r" | "R" | "d" | "D") {
            *parts.entry(part(&sym.name)).or_default() += sym.size;
        }
    }
    Ok(Sizes { sections, parts })
}

fn print_sizes(s: &Sizes, stack: Option<u64>) {
    let sec = |n: &str| s.sections.get(n).copied().unwrap_or(0);
    let flash = sec(".vectors") + sec(".text") + sec(".rodata") + sec(".ARM.exidx") + sec(".data");
    let ram = sec(".data") + sec(".bss");
    println!();
    println!("C firmware sizes (llvm-size -A, llvm-nm; bytes):");
    println!(
        "  flash {flash} B (.text {}, .rodata {}, .data {}), static RAM {ram} B (.data + .bss), peak stack {} B, heap none",
        sec(".text"),
        sec(".rodata"),
        sec(".data"),
        stack.map_or("?".into(), |v| v.to_string())
    );
    println!("| part | flash B |");
    println!("|---|---:|");
    for (p, label) in [
        (
            Part::Kernels,
            "libbrdf_ffi kernels (modified G, Blinn, Smith, Torrance–Sparrow, GGX, sheen, rough dielectric, albedo; libm, soft-f64)",
        ),
        (
            Part::Readers,
            "libbrdf_ffi LUT readers (parse, CRC-32, interpolation)",
        ),
        (Part::Tables, "embedded tables (4 files)"),
        (
            Part::Program,
            "C program, start-up, newlib-nano",
        ),
    ] {
        println!("| {label} | {} |", s.parts.get(&p).copied().unwrap_or(0));
    }
    println!(
        "library (kernels + readers): {} B of flash",
        s.parts.get(&Part::Kernels).copied().unwrap_or(0)
            + s.parts.get(&Part::Readers).copied().unwrap_or(0)
    );
}

/// The README's C-build size table: (row prefix, flash cell, RAM cell or None) as measured.
fn readme_rows(s: &Sizes, stack: Option<u64>) -> Vec<(&'static str, String, Option<String>)> {
    let sec = |n: &str| s.sections.get(n).copied().unwrap_or(0);
    let part = |p: Part| s.parts.get(&p).copied().unwrap_or(0);
    let flash = sec(".vectors") + sec(".text") + sec(".rodata") + sec(".ARM.exidx") + sec(".data");
    let ram = sec(".data") + sec(".bss");
    let ram_cell = format!(
        "{} B static, {} B peak stack, no heap",
        thousands(ram),
        stack.map_or("?".into(), thousands)
    );
    vec![
        (
            "| C ABI library: kernels",
            thousands(part(Part::Kernels)),
            None,
        ),
        (
            "| C ABI library: LUT readers",
            thousands(part(Part::Readers)),
            None,
        ),
        ("| embedded tables", thousands(part(Part::Tables)), None),
        (
            "| C program, start-up",
            thousands(part(Part::Program)),
            None,
        ),
        ("| whole C firmware", thousands(flash), Some(ram_cell)),
    ]
}

/// Checks (or with `update`, rewrites) the README's C-build size table against the
/// measurement, so that no size in the README is a figure copied by hand.
fn readme_sizes(path: &Path, s: &Sizes, stack: Option<u64>, update: bool) -> Result<()> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let mut out = String::with_capacity(text.len());
    let mut stale = Vec::new();
    let rows = readme_rows(s, stack);
    let mut seen = vec![false; rows.len()];
    for line in text.split_inclusive('\n') {
        let Some(k) = rows.iter().position(|r| line.starts_with(r.0)) else {
            out.push_str(line);
            continue;
        };
        seen[k] = true;
        let (_, flash, ram) = &rows[k];
        let cells: Vec<&str> = line.trim_end().split('|').collect();
        // "| label | flash | ram |" splits into ["", label, flash, ram, ""].
        if cells.len() != 5 {
            bail!(
                "README.md: size row {:?} is not a 3-column table row",
                line.trim_end()
            );
        }
        let want_ram = ram.clone().unwrap_or_default();
        if cells[2].trim() != flash || cells[3].trim() != want_ram {
            stale.push(format!(
                "{}: README {} / {:?}, measured {flash} / {want_ram:?}",
                cells[1].trim(),
                cells[2].trim(),
                cells[3].trim()
            ));
        }
        out.push_str(&format!("|{}| {flash} | {want_ram} |\n", cells[1]));
    }
    if let Some(k) = seen.iter().position(|&b| !b) {
        bail!("README.md has no C size row starting with {:?}", rows[k].0);
    }
    if stale.is_empty() {
        println!("README.md: C size table matches the measurement");
        return Ok(());
    }
    if update {
        brdf_engine_assets::fsio::replace(path, out.as_bytes())?;
        println!(
            "README.md: C size table rewritten ({} rows changed)",
            stale.len()
        );
        return Ok(());
    }
    bail!(
        "README.md's C size table disagrees with the measurement (run `cargo xtask cffi --update-readme`):\n  {}",
        stale.join("\n  ")
    )
}

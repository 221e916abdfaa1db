//! `cargo xtask firmware [--micromath]`: builds `crates/brdf-firmware` for the Cortex-M4F,
//! runs it on QEMU's `mps2-an386` under a timeout, recomputes every value it printed with the
//! host's `f32` brdf-core (the same `brdf-firmware-kernels` source, compiled for the host), compares
//! them (bit for bit with libm; within a per-kernel tolerance with micromath) and reports
//! flash and RAM from `llvm-size`/`llvm-nm`, with the kernels' code separated from the
//! formatting code. Fails when a value differs, a device self-check fails or QEMU times out,
//! and with `--enforce-budget` also when the libm kernels exceed [`KERNEL_FLASH_BUDGET`].
//!
//! Parts: [`compare`] (the firmware's numbers and the host recomputation), [`size`] (the
//! flash/RAM report by part and the README's figures), here the build; QEMU, the output
//! lines, run errors, value comparison and ELF reading are `crate::device`'s, shared with
//! `cargo xtask cffi`.
//!
//! QEMU comes from `.ci/install-qemu.sh` (unpacks Debian's qemu-system-arm into
//! `.cache/qemu` without touching the installed qemu-utils).

pub mod compare;
pub mod size;

use crate::device::protocol::{self, print_rows};
use crate::device::{ensure_qemu, run_qemu};
use crate::run_step;
use anyhow::{bail, Result};
use compare::{compare, micromath_tol, HostTables};
use size::{print_sizes, sizes, Sizes, KERNEL_FLASH_BUDGET};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct FirmwareArgs {
    /// Build the firmware with brdf-core's `micromath` feature (compared with a tolerance).
    #[arg(long)]
    pub micromath: bool,
    /// Print every compared value, not only the summary table.
    #[arg(long)]
    pub verbose: bool,
    /// Fail when the kernels exceed the 16 KiB flash budget (libm build only).
    #[arg(long)]
    pub enforce_budget: bool,
    /// Rewrite the README's kernel-flash and static-RAM figures with the measured ones
    /// (libm build). Without it, a README that disagrees with the measurement is an error.
    #[arg(long)]
    pub update_readme: bool,
}

/// The version of `krate` recorded in a Cargo.lock (the first entry), if any.
fn locked_version(lock: &Path, krate: &str) -> Option<String> {
    let text = std::fs::read_to_string(lock).ok()?;
    let want = format!("name = \"{krate}\"");
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        if l.trim() == want {
            let v = lines.next()?.trim().strip_prefix("version = \"")?;
            return Some(v.trim_end_matches('"').to_string());
        }
    }
    None
}

/// Builds `crates/brdf-firmware` (its own Cargo.lock, its own target folder per math
/// crate) for the Cortex-M4F; returns the ELF.
fn build(root: &Path, micromath: bool) -> Result<PathBuf> {
    let variant = if micromath { "micromath" } else { "libm" };
    let tdir = crate::target_dir(root).join("firmware").join(variant);
    let mut cmd = crate::cargo();
    cmd.current_dir(root.join("crates/brdf-firmware"))
        .args(["build", "--release", "--locked"])
        .args(["--target", "thumbv7em-none-eabihf"])
        .env("CARGO_TARGET_DIR", &tdir);
    if micromath {
        cmd.args(["--features", "micromath"]);
    }
    run_step(&mut cmd, "the firmware build (cargo build)")?;
    Ok(tdir.join("thumbv7em-none-eabihf/release/brdf-firmware"))
}

/// Notes a math crate whose version differs between the host's and the firmware's
/// Cargo.lock (the bit-exact comparison assumes the same code on both sides).
fn note_lock_differences(root: &Path) {
    for krate in ["libm", "micromath"] {
        let host = locked_version(&root.join("Cargo.lock"), krate);
        let fw = locked_version(&root.join("crates/brdf-firmware/Cargo.lock"), krate);
        if host != fw {
            println!(
                "note: {krate} is {} on the host and {} in the firmware's Cargo.lock",
                host.as_deref().unwrap_or("absent"),
                fw.as_deref().unwrap_or("absent")
            );
        }
    }
}

pub fn run(a: FirmwareArgs) -> Result<()> {
    let root = crate::workspace_root();
    let math = if a.micromath { "micromath" } else { "libm" };

    // 1. QEMU (idempotent installer; prints the binary on its last line).
    let t = Instant::now();
    let qemu = ensure_qemu(&root)?;
    let t_install = t.elapsed();

    // 2. Build (the firmware has its own Cargo.lock: its math crates must match the host's
    // for the bit-exact comparison to mean what it says).
    note_lock_differences(&root);
    let t = Instant::now();
    let elf = build(&root, a.micromath)?;
    let t_build = t.elapsed();

    // 3. Run under a timeout.
    let t = Instant::now();
    let run = run_qemu(&qemu, &elf)?;
    let t_run = t.elapsed();

    // 4. Parse and compare.
    let out = protocol::parse(&run.stdout, "BRDF-FW")?;
    let tables = HostTables::load(&root, &out.tables)?;
    let rows = compare(&out, &tables, a.micromath)?;
    print_rows(&rows, a.verbose, |k| {
        if a.micromath {
            format!("rel ≤ {:.1e}", micromath_tol(k))
        } else {
            "bit-exact".into()
        }
    });

    // 5. Sizes.
    let sizes = sizes(&elf)?;
    print_sizes(&sizes, out.stack, math);
    println!(
        "firmware[{math}]: QEMU check {:.2} s, build {:.1} s, run {:.2} s (QEMU wall clock)",
        t_install.as_secs_f64(),
        t_build.as_secs_f64(),
        t_run.as_secs_f64()
    );

    // 6. Verdict.
    let mut errors = protocol::run_errors("firmware", &run, &out);
    for r in rows.iter().filter(|r| !r.pass) {
        errors.push(format!(
            "mismatch: {} fw={} host={} (rel {:.2e})",
            r.label,
            r.device.hex(),
            r.host.hex(),
            r.rel
        ));
    }
    errors.extend(size_errors(&root, &a, &sizes)?);
    if !errors.is_empty() {
        eprintln!("---- firmware output ----\n{}{}", run.stdout, run.stderr);
        bail!("firmware[{math}]: {}", errors.join("; "));
    }
    println!(
        "firmware[{math}]: OK: {} values compared ({}), {} device checks passed",
        rows.len(),
        if a.micromath {
            "within the per-kernel micromath tolerances"
        } else {
            "bit-exact"
        },
        out.checks.len()
    );
    Ok(())
}

/// The flash budget, the README's figures (libm build) and the no-heap rule.
fn size_errors(root: &Path, a: &FirmwareArgs, sizes: &Sizes) -> Result<Vec<String>> {
    let mut errors = Vec::new();
    if a.enforce_budget && !a.micromath && sizes.kernels_flash() > KERNEL_FLASH_BUDGET {
        errors.push(format!(
            "kernels use {} B of flash, over the {} B budget",
            sizes.kernels_flash(),
            KERNEL_FLASH_BUDGET
        ));
    }
    if !a.micromath {
        if let Some(e) = readme_error(root, a.update_readme, sizes)? {
            errors.push(e);
        }
    }
    if sizes.has_allocator {
        errors.push("an allocator symbol is linked in (the firmware must not use a heap)".into());
    }
    Ok(errors)
}

/// Checks (or with `update`, rewrites) the README's kernel-flash and static-RAM figures.
fn readme_error(root: &Path, update: bool, sizes: &Sizes) -> Result<Option<String>> {
    let path = root.join("README.md");
    let readme = std::fs::read_to_string(&path)?;
    let measured = (sizes.kernels_flash(), sizes.static_ram());
    Ok(match size::readme_sizes(&readme) {
        None => Some("README.md has no \"B of flash with libm\" / \"B of static RAM\" figures".into()),
        Some(claimed) if claimed == measured => None,
        Some(claimed) if update => {
            let text = size::readme_with_sizes(&readme, measured.0, measured.1)
                .expect("the figures were just found");
            brdf_engine_assets::fsio::replace(&path, text.as_bytes())?;
            println!(
                "README.md: kernel flash {} → {} B, static RAM {} → {} B",
                claimed.0, measured.0, claimed.1, measured.1
            );
            None
        }
        Some(claimed) => Some(format!(
            "README.md says the kernels take {} B of flash and {} B of static RAM; measured {} B and {} B (run `cargo xtask firmware --update-readme`)",
            claimed.0, claimed.1, measured.0, measured.1
        )),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locked_version_reads_the_entry_after_the_name() {
        let dir = std::env::temp_dir().join(format!("xtask-fw-lock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let lock = dir.join("Cargo.lock");
        std::fs::write(
            &lock,
            "[[package]]\nname = \"libmx\"\nversion = \"9\"\n\n[[package]]\nname = \"libm\"\nversion = \"0.2.16\"\n",
        )
        .unwrap();
        assert_eq!(locked_version(&lock, "libm").as_deref(), Some("0.2.16"));
        assert_eq!(locked_version(&lock, "micromath"), None);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! `cargo xtask firmware [--micromath]`: builds `crates/brdf-firmware` for the Cortex-M4F,
//! runs it on QEMU's `mps2-an386` under a timeout, recomputes every value it printed with the
//! host's `f32` brdf-core (the same `kernels.rs` source, compiled for the host), compares
//! them (bit for bit with libm; within a per-kernel tolerance with micromath) and reports
//! flash and RAM from `llvm-size`/`llvm-nm`, with the kernels' code separated from the
//! formatting code. Fails when a value differs, a device self-check fails or QEMU times out,
//! and with `--enforce-budget` also when the libm kernels exceed [`KERNEL_FLASH_BUDGET`].
//!
//! Parts: [`runner`] (QEMU install, firmware build, run under a timeout, output protocol),
//! [`compare`] (host recomputation, ULP comparison), [`size`] (flash/RAM report).
//!
//! QEMU comes from `.ci/install-qemu.sh` (unpacks Debian's qemu-system-arm into
//! `.cache/qemu` without touching the installed qemu-utils).

pub mod compare;
pub mod runner;
pub mod size;

use anyhow::{bail, Result};
use compare::{compare, print_comparison, HostTables};
use runner::{build, ensure_qemu, locked_version, parse, run_qemu, QEMU_TIMEOUT_S};
use size::{print_sizes, sizes, KERNEL_FLASH_BUDGET};
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

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the repo root")
        .to_path_buf()
}

pub fn run(a: FirmwareArgs) -> Result<()> {
    let root = repo_root();
    let math = if a.micromath { "micromath" } else { "libm" };

    // 1. QEMU (idempotent installer; prints the binary on its last line).
    let t = Instant::now();
    let qemu = ensure_qemu(&root)?;
    let t_install = t.elapsed();

    // 2. Build (the firmware has its own Cargo.lock: its math crates must match the host's
    // for the bit-exact comparison to mean what it says).
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
    let t = Instant::now();
    let elf = build(&root, a.micromath)?;
    let t_build = t.elapsed();

    // 3. Run under a timeout.
    let t = Instant::now();
    let out = run_qemu(&qemu, &elf)?;
    let t_run = t.elapsed();

    // 4. Parse and compare.
    let parsed = parse(&out.stdout)?;
    let tables = HostTables::load(&root, &parsed.tables)?;
    let cmp = compare(&parsed.results, &tables, a.micromath)?;
    print_comparison(&cmp, a.verbose, a.micromath);

    // 5. Sizes.
    let sizes = sizes(&elf)?;
    print_sizes(&sizes, parsed.stack, math);

    println!(
        "firmware[{math}]: QEMU check {:.2} s, build {:.1} s, run {:.2} s (QEMU wall clock)",
        t_install.as_secs_f64(),
        t_build.as_secs_f64(),
        t_run.as_secs_f64()
    );

    // 6. Verdict.
    let mut errors = Vec::new();
    if out.timed_out {
        errors.push(format!("QEMU timed out after {QEMU_TIMEOUT_S} s"));
    } else if out.status != Some(0) {
        errors.push(format!("firmware exited with status {:?}", out.status));
    }
    if !parsed.ended {
        errors.push("no END line (firmware crashed or was cut off)".into());
    }
    if let Some(n) = parsed.declared_results {
        if n as usize != parsed.results.len() {
            errors.push(format!(
                "END declares {n} results, {} parsed",
                parsed.results.len()
            ));
        }
    }
    if parsed.results.is_empty() {
        errors.push("no results printed".into());
    }
    for c in parsed.checks.iter().filter(|c| !c.ok) {
        errors.push(format!("device self-check failed: {}", c.line));
    }
    let bad: Vec<_> = cmp.iter().filter(|r| !r.pass).collect();
    for r in &bad {
        errors.push(format!(
            "mismatch: {} fw={:08x} ({}) host={:08x} ({})",
            r.label,
            r.fw.to_bits(),
            r.fw,
            r.host.to_bits(),
            r.host
        ));
    }
    if a.enforce_budget && !a.micromath && sizes.kernels_flash() > KERNEL_FLASH_BUDGET {
        errors.push(format!(
            "kernels use {} B of flash, over the {} B budget",
            sizes.kernels_flash(),
            KERNEL_FLASH_BUDGET
        ));
    }
    if !a.micromath {
        let path = root.join("README.md");
        let readme = std::fs::read_to_string(&path)?;
        let measured = (sizes.kernels_flash(), sizes.static_ram());
        match size::readme_sizes(&readme) {
            None => errors.push("README.md has no \"B of flash with libm\" / \"B of static RAM\" figures".into()),
            Some(claimed) if claimed == measured => {}
            Some(claimed) if a.update_readme => {
                let text = size::readme_with_sizes(&readme, measured.0, measured.1)
                    .expect("the figures were just found");
                let tmp = path.with_extension("md.tmp");
                std::fs::write(&tmp, text)?;
                std::fs::rename(&tmp, &path)?;
                println!(
                    "README.md: kernel flash {} → {} B, static RAM {} → {} B",
                    claimed.0, measured.0, claimed.1, measured.1
                );
            }
            Some(claimed) => errors.push(format!(
                "README.md says the kernels take {} B of flash and {} B of static RAM; measured {} B and {} B (run `cargo xtask firmware --update-readme`)",
                claimed.0, claimed.1, measured.0, measured.1
            )),
        }
    }
    if sizes.has_allocator {
        errors.push("an allocator symbol is linked in (the firmware must not use a heap)".into());
    }
    if !errors.is_empty() {
        eprintln!("---- firmware output ----\n{}{}", out.stdout, out.stderr);
        bail!("firmware[{math}]: {}", errors.join("; "));
    }
    println!(
        "firmware[{math}]: OK: {} values compared ({}), {} device checks passed",
        cmp.len(),
        if a.micromath {
            "within the per-kernel micromath tolerances"
        } else {
            "bit-exact"
        },
        parsed.checks.len()
    );
    Ok(())
}

//! `cargo xtask cffi [--write-header] [--verbose]`: the C ABI end to end.
//!
//! 1. Generates `crates/brdf-ffi/include/brdf.h` with cbindgen (as a library) and fails when
//!    the committed header differs (`--write-header` rewrites it instead).
//! 2. Installs the cross compiler when missing (Debian's `gcc-arm-none-eabi` and
//!    `libnewlib-arm-none-eabi`) and QEMU (through the firmware runner's installer).
//! 3. Builds `libbrdf_ffi.a` for `thumbv7em-none-eabihf` (opt-level z, fat LTO, panic =
//!    abort) and for the host (static and shared), then `examples/c` with `make`: the device
//!    ELF with `arm-none-eabi-gcc`, two host programs with the system `gcc`.
//! 4. Runs the device ELF on QEMU `mps2-an386` and both host programs, each under a timeout.
//! 5. Recomputes every printed value on the host through the same exports called from Rust
//!    and requires all three C runs to match it bit for bit; every C-side check (bad input)
//!    must pass, on the device and on the host.
//! 6. Reports flash and RAM of the device build, split into the library (kernels, readers),
//!    the embedded tables and the C program with its runtime, and lists the functions that
//!    can reach core's panic machinery: none may belong to brdf-core, brdf-ffi or the C
//!    program.
//!
//! Parts: [`build`] (header, tools, builds), [`host`] (the host recomputation), [`elf`]
//! (sizes, README table, panic paths). Running programs, reading their output and comparing
//! values are shared with the firmware runner (`crate::device`).

mod build;
mod elf;
mod host;

use crate::device::protocol::{self, print_rows, Output, Row, Val};
use crate::device::{ensure_qemu, run_qemu, run_timed, RunOut};
use anyhow::{bail, Context, Result};
use brdf_ffi::BRDF_ABI_VERSION;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

pub use build::generate_header;

#[derive(clap::Args)]
pub struct Args {
    /// Rewrite crates/brdf-ffi/include/brdf.h instead of failing when it is out of date.
    #[arg(long)]
    pub write_header: bool,
    /// Print every compared value.
    #[arg(long)]
    pub verbose: bool,
    /// Rewrite the README's C-build size table with the measured figures. Without it, a
    /// README that disagrees with the measurement is an error.
    #[arg(long)]
    pub update_readme: bool,
}

/// Wall-clock limit for one run of a C program on the host.
const RUN_TIMEOUT_S: u32 = 120;
const HEADER: &str = "crates/brdf-ffi/include/brdf.h";

/// Step 1: regenerates the header; a difference is an error unless `write` asks to rewrite.
fn check_header(root: &Path, write: bool) -> Result<()> {
    let header = generate_header(root)?;
    let path = root.join(HEADER);
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed == header {
        println!("cffi: {HEADER} is up to date");
    } else if write {
        brdf_engine_assets::fsio::replace(&path, header.as_bytes())?;
        println!("cffi: wrote {HEADER}");
    } else {
        bail!("{HEADER} is out of date: run `cargo xtask cffi --write-header` and commit it");
    }
    Ok(())
}

/// Steps 2 and 3: the tools, both libraries and the programs; returns the output folder.
fn build_all(root: &Path) -> Result<PathBuf> {
    build::ensure_arm_gcc()?;
    let base = crate::target_dir(root);
    let out = base.join("cffi");
    let device_lib = build::build_device_lib(root, &base)?;
    let host_dir = build::build_host_lib(root, &base)?;
    build::make_examples(root, &out, &device_lib, &host_dir)?;
    Ok(out)
}

/// Every value of one run against the host's; an error for an unreadable token or a value
/// count other than the host's.
fn compare(out: &Output, tables: &host::HostTables) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    for r in &out.results {
        let args = r
            .args
            .iter()
            .map(|t| host::parse_tok(t))
            .collect::<Result<Vec<_>>>()?;
        let vals = r
            .values
            .iter()
            .map(|t| host::parse_val(t))
            .collect::<Result<Vec<Val>>>()?;
        let want = host::host_values(tables, &r.kernel, &args)
            .with_context(|| format!("recomputing {}", r.line))?;
        if vals.len() != want.len() {
            bail!(
                "{}: {} values, the host has {}",
                r.line,
                vals.len(),
                want.len()
            );
        }
        for (k, (d, h)) in vals.into_iter().zip(want).enumerate() {
            rows.push(Row::new(&r.kernel, format!("{} [{k}]", r.line), d, h, 0.0));
        }
    }
    Ok(rows)
}

/// Reads one run's output and compares it; its errors go to `errors`.
fn judge(
    root: &Path,
    name: &str,
    run: &RunOut,
    errors: &mut Vec<String>,
) -> Result<(Output, Vec<Row>)> {
    let out = protocol::parse(&run.stdout, "BRDF-C")
        .with_context(|| format!("parsing the {name} output"))?;
    let abi: u32 = out
        .banner
        .first()
        .context("BRDF-C line without ABI")?
        .parse()?;
    if abi != BRDF_ABI_VERSION {
        bail!("{name}: the C program reports ABI {abi}, the library {BRDF_ABI_VERSION}");
    }
    errors.extend(protocol::run_errors(name, run, &out));
    let tables = host::HostTables::load(root, &out.tables)?;
    let rows = compare(&out, &tables)?;
    for r in rows.iter().filter(|r| !r.pass) {
        errors.push(format!(
            "{name}: {} is {}, the host's Rust value {}",
            r.label,
            r.device.hex(),
            r.host.hex()
        ));
    }
    Ok((out, rows))
}

pub fn run(a: Args) -> Result<()> {
    let root = crate::workspace_root();
    let t = Instant::now();
    check_header(&root, a.write_header)?;
    let t_header = t.elapsed();
    let qemu = ensure_qemu(&root)?;
    let t = Instant::now();
    let out = build_all(&root)?;
    let t_build = t.elapsed();

    // 4. Runs.
    let t = Instant::now();
    let elf = out.join("brdf_example_device.elf");
    let dev = run_qemu(&qemu, &elf)?;
    let t_qemu = t.elapsed();
    let host_run = |bin: &str| run_timed(&mut Command::new(out.join(bin)), RUN_TIMEOUT_S);
    let runs = [
        ("device (QEMU)", dev),
        ("host (static)", host_run("brdf_example_host_static")?),
        ("host (shared)", host_run("brdf_example_host_shared")?),
    ];

    // 5. Compare.
    let mut errors = Vec::new();
    let mut judged = Vec::new();
    for (name, r) in &runs {
        judged.push(judge(&root, name, r, &mut errors)?);
    }
    let counts: Vec<usize> = judged.iter().map(|j| j.0.results.len()).collect();
    if counts.iter().any(|&c| c != counts[0]) {
        errors.push(format!(
            "the device and host runs printed different numbers of results: {counts:?}"
        ));
    }
    let (dev_out, dev_rows) = &judged[0];
    println!("C on the Cortex-M4F (QEMU) vs the host's Rust:");
    print_rows(dev_rows, a.verbose, |_| "bit-exact".into());

    // 6. Sizes and the panic check.
    elf::report(&root, &elf, dev_out.stack, a.update_readme, &mut errors)?;
    println!(
        "cffi: header {:.1} s, builds {:.1} s, QEMU run {:.2} s",
        t_header.as_secs_f64(),
        t_build.as_secs_f64(),
        t_qemu.as_secs_f64()
    );
    if !errors.is_empty() {
        eprintln!(
            "---- device output ----\n{}{}",
            runs[0].1.stdout, runs[0].1.stderr
        );
        bail!("cffi: {}", errors.join("\n  "));
    }
    println!(
        "cffi: OK: {} values bit-exact (device, host static, host shared vs host Rust), {} C checks passed on each",
        dev_rows.len(),
        dev_out.checks.len()
    );
    Ok(())
}

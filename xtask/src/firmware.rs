//! `cargo xtask firmware [--micromath]`: builds `crates/brdf-firmware` for the Cortex-M4F,
//! runs it on QEMU's `mps2-an386` under a timeout, recomputes every value it printed with the
//! host's `f32` brdf-core (the same `kernels.rs` source, compiled for the host), compares
//! them (bit for bit with libm; within a per-kernel tolerance with micromath) and reports
//! flash and RAM from `llvm-size`/`llvm-nm`, with the kernels' code separated from the
//! formatting code. Fails when a value differs, a device self-check fails or QEMU times out,
//! and with `--enforce-budget` also when the libm kernels exceed [`KERNEL_FLASH_BUDGET`].
//!
//! QEMU comes from `.ci/install-qemu.sh` (unpacks Debian's qemu-system-arm into
//! `.cache/qemu` without touching the installed qemu-utils).

use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The firmware's kernels, compiled for the host: the very source the device runs.
#[path = "../../crates/brdf-firmware/src/kernels.rs"]
#[allow(dead_code)]
mod fw_kernels;

/// Flash budget for the kernels (G, Torrance–Sparrow, the LUT view, with libm), bytes.
pub const KERNEL_FLASH_BUDGET: u64 = 16 * 1024;
/// Largest relative difference accepted between the micromath firmware and the host's libm
/// `f32`, per kernel: |fw − host| ≤ tol · max(|host|, 1e-3). Set a little above the largest
/// difference measured at the firmware's inputs (see `micromath_tol`'s comments).
fn micromath_tol(kernel: &str) -> f64 {
    match kernel {
        // G in [0, 1]: measured at most 1.5e-2 (g_dots, σ = 1). The LUT lookup calls libm
        // directly and is bit-exact even in the micromath build.
        "g_direct" | "g_dots" | "g_lut" => 2.5e-2,
        // Torrance–Sparrow: measured at most 7.2e-2 (grazing backscatter, σ = 0.3).
        "ts" => 1e-1,
        // Ashikhmin–Shirley: micromath's powf with exponents 10–1000 is far off; measured at
        // most 0.70 (nu = 100, nv = 10, mirror pair). Not usable with micromath.
        "ashikhmin_shirley" => 0.75,
        _ => 0.0,
    }
}
/// Wall-clock limit for one QEMU run.
const QEMU_TIMEOUT_S: u32 = 60;

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

// ---------------------------------------------------------------------------------------
// QEMU, build, run

pub(crate) fn ensure_qemu(root: &Path) -> Result<PathBuf> {
    let script = root.join(".ci/install-qemu.sh");
    let out = Command::new("bash")
        .arg(&script)
        .output()
        .with_context(|| format!("running {}", script.display()))?;
    if !out.status.success() {
        bail!(
            "{} failed:\n{}",
            script.display(),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let stdout = String::from_utf8_lossy(&out.stdout);
    let bin = stdout
        .lines()
        .last()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .context("install-qemu.sh printed no binary path")?;
    Ok(PathBuf::from(bin))
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

pub(crate) fn target_base(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"))
}

fn build(root: &Path, micromath: bool) -> Result<PathBuf> {
    let krate = root.join("crates/brdf-firmware");
    let variant = if micromath { "micromath" } else { "libm" };
    let tdir = target_base(root).join("firmware").join(variant);
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(&krate)
        .args([
            "build",
            "--release",
            "--locked",
            "--target",
            "thumbv7em-none-eabihf",
        ])
        .env("CARGO_TARGET_DIR", &tdir);
    if micromath {
        cmd.args(["--features", "micromath"]);
    }
    let st = cmd
        .status()
        .context("running cargo build for the firmware")?;
    if !st.success() {
        bail!("firmware build failed ({st})");
    }
    Ok(tdir.join("thumbv7em-none-eabihf/release/brdf-firmware"))
}

pub(crate) struct QemuOut {
    pub(crate) stdout: String,
    pub(crate) stderr: String,
    pub(crate) status: Option<i32>,
    pub(crate) timed_out: bool,
}

pub(crate) fn run_qemu(qemu: &Path, elf: &Path) -> Result<QemuOut> {
    // Libraries unpacked beside an unpacked QEMU (see install-qemu.sh).
    let mut ld = String::new();
    let unpacked = !qemu.starts_with("/usr") && !qemu.starts_with("/bin");
    if let Some(prefix) = qemu.parent().and_then(Path::parent).and_then(Path::parent) {
        for d in ["usr/lib/x86_64-linux-gnu", "lib/x86_64-linux-gnu"] {
            let p = prefix.join(d);
            if unpacked && p.is_dir() {
                ld.push_str(&p.to_string_lossy());
                ld.push(':');
            }
        }
    }
    if let Ok(old) = std::env::var("LD_LIBRARY_PATH") {
        ld.push_str(&old);
    }
    let out = Command::new("timeout")
        .args(["--kill-after=5", &QEMU_TIMEOUT_S.to_string()])
        .arg(qemu)
        .args([
            "-machine",
            "mps2-an386",
            "-cpu",
            "cortex-m4",
            "-nographic",
            "-monitor",
            "none",
            "-serial",
            "none",
            "-semihosting-config",
            "enable=on,target=native",
            "-kernel",
        ])
        .arg(elf)
        .env("LD_LIBRARY_PATH", ld.trim_end_matches(':'))
        .output()
        .context("running timeout/qemu-system-arm")?;
    let status = out.status.code();
    Ok(QemuOut {
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        status,
        // timeout(1) exits 124 on expiry (137 if it had to SIGKILL).
        timed_out: matches!(status, Some(124) | Some(137)),
    })
}

// ---------------------------------------------------------------------------------------
// Parsing the protocol (crates/brdf-firmware/src/report.rs)

struct Res {
    kernel: String,
    args: Vec<f32>,
    value: f32,
}

struct Check {
    ok: bool,
    line: String,
}

/// A `TABLE` line: an embedded table the host must load from `assets/`.
struct TableRef {
    file: String,
    len: usize,
    crc: u32,
}

struct Parsed {
    tables: Vec<TableRef>,
    results: Vec<Res>,
    checks: Vec<Check>,
    stack: Option<u64>,
    declared_results: Option<u32>,
    ended: bool,
}

/// Parses `bits/decimal`, and checks that the device's decimal text reads back to the same
/// bits (this exercises core::fmt's float printing on the target).
fn parse_num(tok: &str) -> Result<f32> {
    let (hex, dec) = tok
        .split_once('/')
        .with_context(|| format!("number {tok:?} is not bits/decimal"))?;
    let bits = u32::from_str_radix(hex, 16).with_context(|| format!("bad hex in {tok:?}"))?;
    let v = f32::from_bits(bits);
    let d: f32 = dec
        .parse()
        .with_context(|| format!("bad decimal in {tok:?}"))?;
    if d.to_bits() != bits && !(d.is_nan() && v.is_nan()) {
        bail!("decimal {dec} does not read back to bits {hex}");
    }
    Ok(v)
}

fn parse(stdout: &str) -> Result<Parsed> {
    let mut p = Parsed {
        tables: Vec::new(),
        results: Vec::new(),
        checks: Vec::new(),
        stack: None,
        declared_results: None,
        ended: false,
    };
    let mut banner = false;
    for line in stdout.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("BRDF-FW") => banner = true,
            Some("TABLE") => {
                let (Some(file), Some(len), Some(crc)) = (it.next(), it.next(), it.next()) else {
                    bail!("TABLE line needs <file> <bytes> <crc32>: {line}");
                };
                p.tables.push(TableRef {
                    file: file.to_string(),
                    len: len
                        .parse()
                        .with_context(|| format!("bad length in {line}"))?,
                    crc: u32::from_str_radix(crc, 16)
                        .with_context(|| format!("bad CRC in {line}"))?,
                });
            }
            Some("R") => {
                let kernel = it.next().context("R line without kernel")?.to_string();
                let toks: Vec<&str> = it.collect();
                let eq = toks
                    .iter()
                    .position(|t| *t == "=")
                    .with_context(|| format!("R line without '=': {line}"))?;
                if eq + 2 != toks.len() {
                    bail!("R line must end with '= <value>': {line}");
                }
                let args = toks[..eq]
                    .iter()
                    .map(|t| parse_num(t))
                    .collect::<Result<Vec<_>>>()?;
                let value = parse_num(toks[eq + 1])?;
                p.results.push(Res {
                    kernel,
                    args,
                    value,
                });
            }
            Some("CHECK") => {
                let _name = it.next();
                p.checks.push(Check {
                    ok: it.next() == Some("ok"),
                    line: line.to_string(),
                });
            }
            Some("STACK") => p.stack = it.next().and_then(|s| s.parse().ok()),
            Some("END") => {
                p.ended = true;
                p.declared_results = it.next().and_then(|s| s.parse().ok());
            }
            _ => {}
        }
    }
    if !banner {
        bail!("no BRDF-FW banner in the firmware output:\n{stdout}");
    }
    Ok(p)
}

// ---------------------------------------------------------------------------------------
// Host recomputation and comparison

struct Row {
    kernel: String,
    label: String,
    fw: f32,
    host: f32,
    /// |fw − host| in units in the last place of the host value.
    ulps: u64,
    rel: f64,
    pass: bool,
}

/// The host's copy of the embedded G table (the same file from `assets/`).
struct HostTables {
    g: Option<(String, Vec<u8>)>,
}

impl HostTables {
    /// Loads every table the firmware named and checks its length and stored CRC-32.
    fn load(root: &Path, refs: &[TableRef]) -> Result<Self> {
        let mut g = None;
        for r in refs {
            if r.file.contains('/') || r.file.contains("..") {
                bail!("table name {:?} must be a plain file name", r.file);
            }
            let path = root.join("assets").join(&r.file);
            let bytes =
                std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
            let t = brdf_lut::GTable::parse(&bytes)
                .map_err(|e| anyhow::anyhow!("{}: {e:?}", path.display()))?;
            let crc = t.view().map_or(0, |v| v.header().checksum);
            if bytes.len() != r.len || crc != r.crc {
                bail!(
                    "{}: host file has {} bytes, CRC {crc:08x}; firmware embeds {} bytes, CRC {:08x}",
                    r.file,
                    bytes.len(),
                    r.len,
                    r.crc
                );
            }
            g = Some((r.file.clone(), bytes));
        }
        Ok(Self { g })
    }
}

fn host_value(tables: &HostTables, kernel: &str, a: &[f32]) -> Result<f32> {
    let want = |n: usize| -> Result<()> {
        if a.len() != n {
            bail!("kernel {kernel} takes {n} arguments, got {}", a.len());
        }
        Ok(())
    };
    Ok(match kernel {
        "g_direct" => {
            want(3)?;
            fw_kernels::g_direct(a[0], a[1], a[2])
        }
        "g_lut" => {
            want(3)?;
            let (file, bytes) = tables
                .g
                .as_ref()
                .context("g_lut results without a TABLE line")?;
            let t = fw_kernels::g_table(bytes)
                .with_context(|| format!("{file} does not parse on the host"))?;
            if t.sigma() != a[0] {
                bail!(
                    "{file} has σ = {}, the firmware printed σ = {}",
                    t.sigma(),
                    a[0]
                );
            }
            fw_kernels::g_lut(&t, a[1], a[2])
        }
        "g_dots" => {
            want(4)?;
            fw_kernels::g_dots(a[0], a[1], a[2], a[3])
        }
        "ts" => {
            want(6)?;
            fw_kernels::torrance_sparrow(a[0], a[1], a[2], a[3], a[4], a[5])
        }
        "ashikhmin_shirley" => {
            want(10)?;
            fw_kernels::ashikhmin_shirley(
                a[0],
                a[1],
                a[2],
                a[3],
                [a[4], a[5], a[6]],
                [a[7], a[8], a[9]],
            )
        }
        other => bail!("the host does not know firmware kernel {other:?}"),
    })
}

/// Distance in representable f32 values (0 for identical bits; both must be finite).
fn ulp_distance(a: f32, b: f32) -> u64 {
    fn key(x: f32) -> i64 {
        let b = x.to_bits() as i32;
        (if b < 0 { i32::MIN - b } else { b }) as i64
    }
    (key(a) - key(b)).unsigned_abs()
}

fn compare(results: &[Res], tables: &HostTables, micromath: bool) -> Result<Vec<Row>> {
    let mut rows = Vec::with_capacity(results.len());
    for r in results {
        let host = host_value(tables, &r.kernel, &r.args)?;
        let fw = r.value;
        let (ulps, rel) = if fw.is_finite() && host.is_finite() {
            let d = (fw as f64 - host as f64).abs();
            (ulp_distance(fw, host), d / (host.abs() as f64).max(1e-3))
        } else {
            (u64::MAX, f64::INFINITY)
        };
        let bit_exact = fw.to_bits() == host.to_bits() || (fw.is_nan() && host.is_nan());
        let pass = if micromath {
            bit_exact || rel <= micromath_tol(&r.kernel)
        } else {
            bit_exact
        };
        let args: Vec<String> = r.args.iter().map(|x| format!("{x}")).collect();
        rows.push(Row {
            kernel: r.kernel.clone(),
            label: format!("{}({})", r.kernel, args.join(", ")),
            fw,
            host,
            ulps: if bit_exact { 0 } else { ulps },
            rel: if bit_exact { 0.0 } else { rel },
            pass,
        });
    }
    Ok(rows)
}

fn print_comparison(rows: &[Row], verbose: bool, micromath: bool) {
    if verbose {
        println!(
            "{:<64} {:>21} {:>21} {:>10} {:>8}",
            "value", "firmware", "host (f32, libm)", "rel diff", "ulps"
        );
        for r in rows {
            println!(
                "{:<64} {:08x} {:<12} {:08x} {:<12} {:>10.2e} {:>8}{}",
                r.label,
                r.fw.to_bits(),
                r.fw,
                r.host.to_bits(),
                r.host,
                r.rel,
                r.ulps,
                if r.pass { "" } else { "  MISMATCH" }
            );
        }
    }
    // Summary per kernel.
    let mut per: BTreeMap<&str, (usize, usize, u64, f64)> = BTreeMap::new();
    for r in rows {
        let e = per.entry(r.kernel.as_str()).or_default();
        e.0 += 1;
        e.1 += usize::from(r.fw.to_bits() == r.host.to_bits());
        e.2 = e.2.max(r.ulps);
        e.3 = e.3.max(r.rel);
    }
    println!("| kernel | values | bit-identical | max ulps | max rel. diff | required | verdict |");
    println!("|---|---:|---:|---:|---:|---|---|");
    for (k, (n, same, ulps, rel)) in &per {
        let ok = rows.iter().filter(|r| r.kernel == *k).all(|r| r.pass);
        let req = if micromath {
            format!("rel ≤ {:.1e}", micromath_tol(k))
        } else {
            "bit-exact".into()
        };
        println!(
            "| {k} | {n} | {same} | {ulps} | {rel:.2e} | {req} | {} |",
            if ok { "pass" } else { "FAIL" }
        );
    }
}

// ---------------------------------------------------------------------------------------
// Sizes

/// Where a symbol's bytes are counted. The first three make up "the kernels" of the budget.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Group {
    /// Direct G and Torrance–Sparrow: brdf-core outside `lut`, the firmware's wrappers.
    KernelG,
    /// The LUT view: `brdf_core::lut` (header decoding, validation, CRC, interpolation) and
    /// the serde/postcard/heapless code it instantiates.
    KernelLut,
    /// Math shared by the kernels: libm or micromath, soft-float f64 helpers (libm's f32
    /// functions compute internally in f64).
    KernelMath,
    /// The anisotropic model (Ashikhmin–Shirley) and `powf`, which only it uses here; outside
    /// the kernel budget.
    Aniso,
    /// Embedded table bytes.
    TableData,
    /// core::fmt, float printing, the firmware's report module, semihosting, panics.
    Formatting,
    /// cortex-m-rt start-up, main, stack painting, memcpy and friends.
    Runtime,
    /// Unnamed constants (`.Lanon.*`: string pieces, numeric tables) of any origin.
    Anonymous,
}

impl Group {
    fn is_kernel(self) -> bool {
        matches!(self, Group::KernelG | Group::KernelLut | Group::KernelMath)
    }
}

/// Finishes what llvm-nm's demangler leaves of Rust's legacy mangling (`$LT$`, `..`, …)
/// and drops the trailing `::h<hash>`.
fn tidy(name: &str) -> String {
    let mut n = name
        .strip_prefix('_')
        .filter(|r| r.starts_with('$'))
        .unwrap_or(name)
        .to_string();
    for (from, to) in [
        ("$LT$", "<"),
        ("$GT$", ">"),
        ("$u20$", " "),
        ("$C$", ","),
        ("$RF$", "&"),
        ("$BP$", "*"),
        ("$SP$", "@"),
        ("$u27$", "'"),
        ("$u5b$", "["),
        ("$u5d$", "]"),
        ("$u7b$", "{"),
        ("$u7d$", "}"),
        ("$u3b$", ";"),
        ("$u21$", "!"),
        ("$u2b$", "+"),
        ("..", "::"),
    ] {
        n = n.replace(from, to);
    }
    if let Some(i) = n.rfind("::h") {
        let h = &n[i + 3..];
        if h.len() == 16 && h.bytes().all(|b| b.is_ascii_hexdigit()) {
            n.truncate(i);
        }
    }
    n
}

fn classify(name: &str) -> Group {
    let has = |s: &str| name.contains(s);
    if has("brdf_firmware::TABLE_") {
        Group::TableData
    } else if name.starts_with(".L") {
        Group::Anonymous
    } else if has("ashikhmin") || has("AshikhminShirley") || has("::powf") {
        Group::Aniso
    } else if has("brdf_lut::")
        || has("kernels::g_table")
        || has("kernels::g_lut")
        || has("serde")
        || has("postcard::")
        || has("heapless::")
    {
        Group::KernelLut
    } else if has("brdf_core::") || has("brdf_firmware::kernels::") {
        Group::KernelG
    } else if has("libm::")
        || has("micromath::")
        || has("compiler_builtins::float::")
        || name.starts_with("__aeabi_d")
        || name.starts_with("__aeabi_f")
        || name.starts_with("__aeabi_i2d")
        || name.starts_with("__aeabi_ui2d")
        || name.starts_with("__aeabi_l2d")
        || name.starts_with("__aeabi_ul2d")
        || [
            "__adddf3",
            "__subdf3",
            "__muldf3",
            "__divdf3",
            "__extendsfdf2",
            "__truncdfsf2",
            "__fixdfsi",
            "__fixunsdfsi",
            "__floatsidf",
            "__floatunsidf",
            "__eqdf2",
            "__nedf2",
            "__ltdf2",
            "__ledf2",
            "__gtdf2",
            "__gedf2",
            "__unorddf2",
            "__cmpdf2",
        ]
        .contains(&name)
    {
        Group::KernelMath
    } else if has("core::fmt")
        || has("core::num::flt2dec")
        || has("core::num::fmt")
        || has("core::num::")
        || has("as core::fmt::")
        || has("brdf_firmware::report::")
        || has("cortex_m_semihosting::")
        || has("core::panicking")
        || has("core::panic")
        || has("core::str::")
        || has("core::slice::index")
        || has("core::result::unwrap_failed")
        || has("core::option::")
        || has("brdf_firmware::panic")
    {
        Group::Formatting
    } else {
        Group::Runtime
    }
}

struct Sizes {
    /// Section name → size from `llvm-size -A`.
    sections: BTreeMap<String, u64>,
    /// Group → (text bytes, rodata bytes) attributed through symbols.
    groups: BTreeMap<Group, (u64, u64)>,
    /// Flash bytes in .text + .rodata not attributed to any sized symbol.
    unattributed: u64,
    /// The largest kernel symbols (name, bytes).
    top_kernels: Vec<(String, u64)>,
    has_allocator: bool,
}

impl Sizes {
    fn sec(&self, s: &str) -> u64 {
        self.sections.get(s).copied().unwrap_or(0)
    }
    fn flash(&self) -> u64 {
        self.sec(".vector_table") + self.sec(".text") + self.sec(".rodata") + self.sec(".data")
    }
    fn static_ram(&self) -> u64 {
        self.sec(".data") + self.sec(".bss") + self.sec(".uninit")
    }
    fn group(&self, g: Group) -> u64 {
        self.groups.get(&g).map_or(0, |(t, r)| t + r)
    }
    fn kernels_flash(&self) -> u64 {
        self.group(Group::KernelG) + self.group(Group::KernelLut) + self.group(Group::KernelMath)
    }
}

pub(crate) fn llvm_tool(name: &str) -> Result<PathBuf> {
    let mut cands: Vec<PathBuf> = vec![PathBuf::from(format!("/usr/bin/{name}"))];
    for v in (14..=21).rev() {
        cands.push(PathBuf::from(format!("/usr/lib/llvm-{v}/bin/{name}")));
    }
    if let Some(p) = std::env::var_os("PATH") {
        for d in std::env::split_paths(&p) {
            cands.push(d.join(name));
        }
    }
    cands
        .into_iter()
        .find(|p| p.is_file())
        .with_context(|| format!("{name} not found (apt-get install llvm)"))
}

fn sizes(elf: &Path) -> Result<Sizes> {
    let out = Command::new(llvm_tool("llvm-size")?)
        .arg("-A")
        .arg(elf)
        .output()
        .context("running llvm-size")?;
    if !out.status.success() {
        bail!("llvm-size failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    let mut sections = BTreeMap::new();
    // (name, start, end) of the allocated flash sections, to attribute symbols by address.
    let mut ranges: Vec<(String, u64, u64)> = Vec::new();
    for l in String::from_utf8_lossy(&out.stdout).lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.len() == 3 && f[0].starts_with('.') {
            if let (Ok(n), Ok(addr)) = (f[1].parse::<u64>(), f[2].parse::<u64>()) {
                sections.insert(f[0].to_string(), n);
                if f[0] == ".text" || f[0] == ".rodata" {
                    ranges.push((f[0].to_string(), addr, addr + n));
                }
            }
        }
    }
    let out = Command::new(llvm_tool("llvm-nm")?)
        .args([
            "--print-size",
            "--size-sort",
            "--demangle",
            "--defined-only",
        ])
        .arg(elf)
        .output()
        .context("running llvm-nm")?;
    if !out.status.success() {
        bail!("llvm-nm failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    let mut groups: BTreeMap<Group, (u64, u64)> = BTreeMap::new();
    let mut kernels: Vec<(String, u64)> = Vec::new();
    let mut has_allocator = false;
    let (mut text_attr, mut ro_attr) = (0u64, 0u64);
    for l in String::from_utf8_lossy(&out.stdout).lines() {
        // "<addr> <size> <type> <name…>"
        let mut it = l.splitn(4, ' ');
        let (Some(addr), Some(size), Some(_ty), Some(raw)) =
            (it.next(), it.next(), it.next(), it.next())
        else {
            continue;
        };
        let (Ok(addr), Ok(size)) = (u64::from_str_radix(addr, 16), u64::from_str_radix(size, 16))
        else {
            continue;
        };
        let name = tidy(raw);
        if name.contains("__rust_alloc") || name.contains("__rg_alloc") {
            has_allocator = true;
        }
        let addr = addr & !1; // Thumb bit
        let Some((sec, _, _)) = ranges.iter().find(|(_, lo, hi)| (*lo..*hi).contains(&addr)) else {
            continue; // vector table, RAM, debug info
        };
        let g = classify(&name);
        let e = groups.entry(g).or_default();
        if sec == ".text" {
            e.0 += size;
            text_attr += size;
        } else {
            e.1 += size;
            ro_attr += size;
        }
        if g.is_kernel() || g == Group::Aniso {
            kernels.push((name, size));
        }
    }
    kernels.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    kernels.truncate(12);
    let text_ro =
        sections.get(".text").copied().unwrap_or(0) + sections.get(".rodata").copied().unwrap_or(0);
    Ok(Sizes {
        sections,
        groups,
        unattributed: text_ro.saturating_sub(text_attr + ro_attr),
        top_kernels: kernels,
        has_allocator,
    })
}

fn print_sizes(s: &Sizes, stack: Option<u64>, math: &str) {
    println!();
    println!("firmware[{math}] sizes (llvm-size -A; bytes):");
    for (k, v) in &s.sections {
        if !k.starts_with(".debug") && *v > 0 && k != ".comment" && k != ".ARM.attributes" {
            println!("  {k:<16} {v:>8}");
        }
    }
    println!(
        "  flash total {} B, static RAM (.data+.bss+.uninit) {} B, peak stack {} B, heap none",
        s.flash(),
        s.static_ram(),
        stack.map_or("?".into(), |v| v.to_string())
    );
    println!("| part ({math}) | code B | rodata B | flash B |");
    println!("|---|---:|---:|---:|");
    for (g, label) in [
        (Group::KernelG, "kernels: direct G, Torrance–Sparrow"),
        (
            Group::KernelLut,
            "kernels: LUT view (parse, CRC, lookup; serde/postcard)",
        ),
        (
            Group::KernelMath,
            "kernels: libm/micromath + soft-f64 helpers",
        ),
        (Group::Aniso, "anisotropic model (Ashikhmin–Shirley + powf)"),
        (Group::TableData, "embedded table bytes"),
        (
            Group::Formatting,
            "formatting (core::fmt, float printing, semihosting, panics)",
        ),
        (Group::Runtime, "runtime (cortex-m-rt, main, memcpy, …)"),
        (
            Group::Anonymous,
            "unnamed constants (.Lanon.*: strings, tables)",
        ),
    ] {
        let (t, r) = s.groups.get(&g).copied().unwrap_or((0, 0));
        println!("| {label} | {t} | {r} | {} |", t + r);
    }
    println!(
        "| unattributed (.text+.rodata without a sized symbol) | | | {} |",
        s.unattributed
    );
    println!(
        "| vector table | | | {} |",
        s.sections.get(".vector_table").copied().unwrap_or(0)
    );
    let k = s.kernels_flash();
    let verdict = if math != "libm" {
        "the budget applies to the libm build".to_string()
    } else if k <= KERNEL_FLASH_BUDGET {
        format!("within the {} KiB budget", KERNEL_FLASH_BUDGET / 1024)
    } else {
        format!(
            "OVER the {} KiB budget by {} B",
            KERNEL_FLASH_BUDGET / 1024,
            k - KERNEL_FLASH_BUDGET
        )
    };
    println!(
        "kernels (G, Torrance–Sparrow, LUT view): {k} B of flash ({:.1} KiB): {verdict}",
        k as f64 / 1024.0
    );
    println!("largest kernel symbols:");
    for (n, b) in &s.top_kernels {
        println!("  {b:>6}  {n}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ulp_distance_counts_representable_steps() {
        assert_eq!(ulp_distance(1.0, 1.0), 0);
        assert_eq!(ulp_distance(1.0, f32::from_bits(1.0f32.to_bits() + 3)), 3);
        // Across zero: −min_positive .. +min_positive is 2 steps apart through ±0.
        let tiny = f32::from_bits(1);
        assert_eq!(ulp_distance(-tiny, tiny), 2);
    }

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

    #[test]
    fn compare_flags_a_one_ulp_difference_only_in_the_bit_exact_mode() {
        let tables = HostTables { g: None };
        let args = vec![0.3f32, 0.5, -0.7];
        let host = host_value(&tables, "g_direct", &args).unwrap();
        assert!(host > 0.0 && host <= 1.0);
        let same = Res {
            kernel: "g_direct".into(),
            args: args.clone(),
            value: host,
        };
        let off = Res {
            kernel: "g_direct".into(),
            args,
            value: f32::from_bits(host.to_bits() - 1),
        };
        let rows = compare(&[same, off], &tables, false).unwrap();
        assert!(rows[0].pass && rows[0].ulps == 0);
        assert!(!rows[1].pass && rows[1].ulps == 1);
        let off_mm = Res {
            kernel: "g_direct".into(),
            args: vec![0.3, 0.5, -0.7],
            value: f32::from_bits(host.to_bits() - 1),
        };
        assert!(compare(&[off_mm], &tables, true).unwrap()[0].pass);
        // An unknown kernel or a wrong argument count is an error, not a pass.
        let bad = Res {
            kernel: "g_direct".into(),
            args: vec![0.3],
            value: 1.0,
        };
        assert!(compare(&[bad], &tables, false).is_err());
    }

    #[test]
    fn parse_num_rejects_inconsistent_decimal() {
        assert_eq!(parse_num("3e99999a/0.3").unwrap(), 0.3f32);
        assert!(parse_num("3e99999a/0.31").is_err());
        assert!(parse_num("zz/0.3").is_err());
    }

    #[test]
    fn classify_separates_kernels_from_formatting() {
        assert_eq!(
            classify("brdf_core::masking::modified::ModifiedG<T,R>::passing_cs"),
            Group::KernelG
        );
        assert_eq!(classify("brdf_lut::LutView::sample"), Group::KernelLut);
        assert_eq!(classify("libm::math::expf::expf"), Group::KernelMath);
        assert_eq!(classify("__aeabi_dmul"), Group::KernelMath);
        assert_eq!(classify("libm::math::powf::powf"), Group::Aniso);
        assert_eq!(
            classify("brdf_firmware::kernels::ashikhmin_shirley"),
            Group::Aniso
        );
        assert_eq!(
            classify("core::fmt::float::float_to_decimal_common_shortest"),
            Group::Formatting
        );
        assert_eq!(classify("Reset"), Group::Runtime);
        assert_eq!(
            tidy("_$LT$brdf_firmware..report..Num$u20$as$u20$core..fmt..Display$GT$::fmt::h89d7b88652567c93"),
            "<brdf_firmware::report::Num as core::fmt::Display>::fmt"
        );
        assert_eq!(
            classify(&tidy(
                "_$LT$$RF$T$u20$as$u20$core..fmt..Display$GT$::fmt::hf5eaf33a05909de8"
            )),
            Group::Formatting
        );
    }
}

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

use crate::firmware::runner::{ensure_qemu, run_qemu, target_base};
use crate::firmware::size::{llvm_tool, with_commas as thousands};
use anyhow::{bail, Context, Result};
use brdf_ffi::*;
use std::collections::BTreeMap;
use std::mem::MaybeUninit;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

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

/// Wall-clock limit for one run of a C program (QEMU or host).
const RUN_TIMEOUT_S: u32 = 120;
const HEADER: &str = "crates/brdf-ffi/include/brdf.h";

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the repo root")
        .to_path_buf()
}

pub fn run(a: Args) -> Result<()> {
    let root = repo_root();

    // 1. Header.
    let t = Instant::now();
    let header = generate_header(&root)?;
    let path = root.join(HEADER);
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != header {
        if a.write_header {
            write_atomic(&path, header.as_bytes())?;
            println!("cffi: wrote {HEADER}");
        } else {
            bail!("{HEADER} is out of date: run `cargo xtask cffi --write-header` and commit it");
        }
    } else {
        println!("cffi: {HEADER} is up to date");
    }
    let t_header = t.elapsed();

    // 2. Tools.
    ensure_arm_gcc()?;
    let qemu = ensure_qemu(&root)?;

    // 3. Builds.
    let t = Instant::now();
    let base = target_base(&root);
    let out = base.join("cffi");
    let device_lib = build_device_lib(&root, &base)?;
    let host_dir = build_host_lib(&root, &base)?;
    let st = Command::new("make")
        .arg("-B")
        .arg("-C")
        .arg(root.join("examples/c"))
        .arg("all")
        .arg(format!("ROOT={}", root.display()))
        .arg(format!("OUT={}", out.display()))
        .arg(format!("DEVICE_LIB={}", device_lib.display()))
        .arg(format!("HOST_LIB_DIR={}", host_dir.display()))
        .arg("EXTRA_CFLAGS=-Werror")
        .status()
        .context("running make for examples/c")?;
    if !st.success() {
        bail!("building examples/c failed ({st})");
    }
    let t_build = t.elapsed();

    // 4. Runs.
    let t = Instant::now();
    let elf = out.join("brdf_example_device.elf");
    let dev = run_qemu(&qemu, &elf)?;
    let t_qemu = t.elapsed();
    let host_static = run_host(&out.join("brdf_example_host_static"))?;
    let host_shared = run_host(&out.join("brdf_example_host_shared"))?;

    // 5. Compare.
    let mut errors = Vec::new();
    let runs = [
        ("device (QEMU)", &dev.stdout, dev.status, dev.timed_out),
        (
            "host (static)",
            &host_static.0,
            host_static.1,
            host_static.2,
        ),
        (
            "host (shared)",
            &host_shared.0,
            host_shared.1,
            host_shared.2,
        ),
    ];
    let mut parsed = Vec::new();
    for (name, stdout, status, timed_out) in runs {
        if timed_out {
            errors.push(format!("{name}: timed out after {RUN_TIMEOUT_S} s"));
        } else if status != Some(0) {
            errors.push(format!("{name}: exit status {status:?}"));
        }
        let p = parse(stdout).with_context(|| format!("parsing the {name} output"))?;
        if !p.ended {
            errors.push(format!("{name}: no END line"));
        }
        if p.declared != Some(p.results.len()) {
            errors.push(format!(
                "{name}: END declares {:?} results, {} parsed",
                p.declared,
                p.results.len()
            ));
        }
        for c in p.checks.iter().filter(|c| !c.1) {
            errors.push(format!("{name}: C check failed: {}", c.0));
        }
        parsed.push((name, p));
    }
    let tables = HostTables::load(&root, &parsed[0].1.tables)?;
    let mut per: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    for (name, p) in &parsed {
        for r in &p.results {
            let host = host_values(&tables, &r.kernel, &r.args)
                .with_context(|| format!("recomputing {}", r.line))?;
            let same = host == r.values;
            if *name == "device (QEMU)" {
                let e = per.entry(r.kernel.clone()).or_default();
                e.0 += 1;
                e.1 += usize::from(same);
                if a.verbose {
                    println!("{} {}", if same { "  same" } else { "  DIFF" }, r.line);
                }
            }
            if !same {
                errors.push(format!(
                    "{name}: {} differs from the host's Rust values {:?}",
                    r.line,
                    host.iter().map(Val::hex).collect::<Vec<_>>()
                ));
            }
        }
    }
    if parsed[0].1.results.len() != parsed[1].1.results.len()
        || parsed[0].1.results.len() != parsed[2].1.results.len()
    {
        errors.push("the device and host runs printed different numbers of results".into());
    }
    println!("| kernel (C on the Cortex-M4F vs host Rust) | values | bit-identical |");
    println!("|---|---:|---:|");
    let (mut n, mut same) = (0, 0);
    for (k, (a, b)) in &per {
        println!("| {k} | {a} | {b} |");
        n += a;
        same += b;
    }
    println!("| all | {n} | {same} |");

    // 6. Sizes and the panic check.
    let sz = sizes(&elf)?;
    print_sizes(&sz, parsed[0].1.stack);
    readme_sizes(
        &root.join("README.md"),
        &sz,
        parsed[0].1.stack,
        a.update_readme,
    )?;
    let callers = panic_callers(&elf)?;
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
        errors.push(format!(
            "functions outside brdf-lut call into the panic machinery: {}",
            other
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    println!(
        "cffi: header {:.1} s, builds {:.1} s, QEMU run {:.2} s",
        t_header.as_secs_f64(),
        t_build.as_secs_f64(),
        t_qemu.as_secs_f64()
    );
    if !errors.is_empty() {
        eprintln!("---- device output ----\n{}{}", dev.stdout, dev.stderr);
        bail!("cffi: {}", errors.join("\n  "));
    }
    println!(
        "cffi: OK: {n} values bit-exact (device, host static, host shared vs host Rust), {} C checks passed on each",
        parsed[0].1.checks.len()
    );
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Header, tools, builds

/// The header cbindgen generates from crates/brdf-ffi with its cbindgen.toml.
pub fn generate_header(root: &Path) -> Result<String> {
    let krate = root.join("crates/brdf-ffi");
    let config = cbindgen::Config::from_file(krate.join("cbindgen.toml"))
        .map_err(|e| anyhow::anyhow!("reading cbindgen.toml: {e}"))?;
    let bindings = cbindgen::Builder::new()
        .with_crate(&krate)
        .with_config(config)
        .generate()
        .map_err(|e| anyhow::anyhow!("cbindgen: {e}"))?;
    let mut buf = Vec::new();
    bindings.write(&mut buf);
    String::from_utf8(buf).context("cbindgen wrote non-UTF-8")
}

/// Writes through a temporary file in the same folder and a rename.
fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, bytes).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("renaming to {}", path.display()))
}

fn have(cmd: &str) -> bool {
    Command::new(cmd)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// arm-none-eabi-gcc and newlib from Debian when missing (CI machines start without them).
fn ensure_arm_gcc() -> Result<()> {
    // newlib-nano for the Cortex-M4F hard-float multilib (gcc prints the bare name when absent).
    let newlib = Command::new("arm-none-eabi-gcc")
        .args([
            "-mcpu=cortex-m4",
            "-mthumb",
            "-mfloat-abi=hard",
            "-mfpu=fpv4-sp-d16",
        ])
        .arg("-print-file-name=libc_nano.a")
        .output()
        .is_ok_and(|o| Path::new(String::from_utf8_lossy(&o.stdout).trim()).is_file());
    if have("arm-none-eabi-gcc") && newlib && have("make") {
        return Ok(());
    }
    println!("cffi: installing gcc-arm-none-eabi and libnewlib-arm-none-eabi");
    let root = is_root();
    let apt = |args: &[&str]| -> Result<()> {
        let mut c = if root {
            Command::new("apt-get")
        } else {
            let mut c = Command::new("sudo");
            c.arg("apt-get");
            c
        };
        let st = c
            .args(["-o", "DPkg::Lock::Timeout=600"])
            .args(args)
            .env("DEBIAN_FRONTEND", "noninteractive")
            .status()
            .context("running apt-get")?;
        if !st.success() {
            bail!("apt-get {} failed ({st})", args.join(" "));
        }
        Ok(())
    };
    apt(&["update", "-qq"])?;
    apt(&[
        "install",
        "-y",
        "-qq",
        "--no-install-recommends",
        "gcc-arm-none-eabi",
        "libnewlib-arm-none-eabi",
        "make",
    ])?;
    if !have("arm-none-eabi-gcc") {
        bail!("arm-none-eabi-gcc still missing after the install");
    }
    Ok(())
}

/// `true` when running as root (from `id -u`; no libc call needed).
fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

/// libbrdf_ffi.a for the Cortex-M4F, in its own target folder (size-optimised, fat LTO).
fn build_device_lib(root: &Path, base: &Path) -> Result<PathBuf> {
    let tdir = base.join("cffi-rust-device");
    let st = Command::new(cargo())
        .current_dir(root)
        .args([
            "rustc",
            "-p",
            "brdf-ffi",
            "--release",
            "--locked",
            "--target",
            "thumbv7em-none-eabihf",
            "--crate-type",
            "staticlib",
            "--config",
            "profile.release.opt-level=\"z\"",
            "--config",
            "profile.release.lto=\"fat\"",
            "--config",
            "profile.release.codegen-units=1",
            "--config",
            "profile.release.panic=\"abort\"",
        ])
        .env("CARGO_TARGET_DIR", &tdir)
        .status()
        .context("running cargo rustc for the device library")?;
    if !st.success() {
        bail!("building libbrdf_ffi.a for thumbv7em-none-eabihf failed ({st})");
    }
    Ok(tdir.join("thumbv7em-none-eabihf/release/libbrdf_ffi.a"))
}

/// libbrdf_ffi.a and libbrdf_ffi.so for the host (the workspace's release profile).
fn build_host_lib(root: &Path, base: &Path) -> Result<PathBuf> {
    let st = Command::new(cargo())
        .current_dir(root)
        .args(["build", "-p", "brdf-ffi", "--release", "--locked"])
        .status()
        .context("running cargo build for the host library")?;
    if !st.success() {
        bail!("building libbrdf_ffi for the host failed ({st})");
    }
    Ok(base.join("release"))
}

/// (stdout, exit status, timed out) of a host program run under `timeout`.
fn run_host(bin: &Path) -> Result<(String, Option<i32>, bool)> {
    let out = Command::new("timeout")
        .args(["--kill-after=5", &RUN_TIMEOUT_S.to_string()])
        .arg(bin)
        .output()
        .with_context(|| format!("running {}", bin.display()))?;
    let status = out.status.code();
    Ok((
        String::from_utf8_lossy(&out.stdout).into_owned(),
        status,
        matches!(status, Some(124) | Some(137)),
    ))
}

// ---------------------------------------------------------------------------------------
// The output protocol (examples/c/brdf_example.c)

#[derive(Clone, Copy, Debug, PartialEq)]
enum Arg {
    U(u32),
    F32(u32),
    F64(u64),
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Val {
    F32(u32),
    F64(u64),
}

impl Val {
    fn hex(&self) -> String {
        match self {
            Val::F32(b) => format!("{b:08x}"),
            Val::F64(b) => format!("{b:016x}"),
        }
    }
}

struct Rec {
    kernel: String,
    args: Vec<Arg>,
    values: Vec<Val>,
    line: String,
}

struct TableRef {
    role: String,
    file: String,
    len: usize,
    fnv: u32,
}

#[derive(Default)]
struct Parsed {
    tables: Vec<TableRef>,
    results: Vec<Rec>,
    checks: Vec<(String, bool)>,
    stack: Option<u64>,
    declared: Option<usize>,
    ended: bool,
}

fn parse_tok(t: &str) -> Result<Arg> {
    if let Some(d) = t.strip_prefix("u:") {
        return Ok(Arg::U(d.parse().with_context(|| format!("bad u32 {t:?}"))?));
    }
    match t.len() {
        8 => Ok(Arg::F32(
            u32::from_str_radix(t, 16).with_context(|| format!("bad f32 bits {t:?}"))?,
        )),
        16 => Ok(Arg::F64(
            u64::from_str_radix(t, 16).with_context(|| format!("bad f64 bits {t:?}"))?,
        )),
        _ => bail!("token {t:?} is neither u:<n>, 8 nor 16 hex digits"),
    }
}

fn parse(stdout: &str) -> Result<Parsed> {
    let mut p = Parsed::default();
    let mut banner = false;
    for line in stdout.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("BRDF-C") => {
                banner = true;
                let abi: u32 = it.next().context("BRDF-C line without ABI")?.parse()?;
                if abi != BRDF_ABI_VERSION {
                    bail!("the C program reports ABI {abi}, the library {BRDF_ABI_VERSION}");
                }
            }
            Some("TABLE") => {
                let f: Vec<&str> = it.collect();
                let [role, file, len, fnv] = f[..] else {
                    bail!("TABLE line needs <role> <file> <bytes> <fnv1a>: {line}");
                };
                p.tables.push(TableRef {
                    role: role.into(),
                    file: file.into(),
                    len: len.parse()?,
                    fnv: u32::from_str_radix(fnv, 16)?,
                });
            }
            Some("R") => {
                let kernel = it.next().context("R line without kernel")?.to_string();
                let toks: Vec<&str> = it.collect();
                let eq = toks
                    .iter()
                    .position(|t| *t == "=")
                    .with_context(|| format!("R line without '=': {line}"))?;
                let args = toks[..eq]
                    .iter()
                    .map(|t| parse_tok(t))
                    .collect::<Result<Vec<_>>>()?;
                let values = toks[eq + 1..]
                    .iter()
                    .map(|t| match parse_tok(t)? {
                        Arg::F32(b) => Ok(Val::F32(b)),
                        Arg::F64(b) => Ok(Val::F64(b)),
                        Arg::U(_) => bail!("a result must be a float: {line}"),
                    })
                    .collect::<Result<Vec<_>>>()?;
                p.results.push(Rec {
                    kernel,
                    args,
                    values,
                    line: line.to_string(),
                });
            }
            Some("CHECK") => {
                let name = it.next().unwrap_or("?").to_string();
                p.checks.push((name, it.next() == Some("ok")));
            }
            Some("STACK") => p.stack = it.next().and_then(|s| s.parse().ok()),
            Some("END") => {
                p.ended = true;
                p.declared = it.next().and_then(|s| s.parse().ok());
            }
            _ => {}
        }
    }
    if !banner {
        bail!("no BRDF-C banner in:\n{stdout}");
    }
    Ok(p)
}

// ---------------------------------------------------------------------------------------
// Host recomputation through the same exports

fn fnv1a(bytes: &[u8]) -> u32 {
    let mut h: u32 = 2_166_136_261;
    for &b in bytes {
        h = (h ^ b as u32).wrapping_mul(16_777_619);
    }
    h
}

/// The tables the C program embedded, parsed on the host from `assets/`.
struct HostTables {
    g: Option<Box<BrdfGTable>>,
    dfg: Option<Box<BrdfDfgTable>>,
    e: Option<Box<BrdfAlbedoTable>>,
    eavg: Option<Box<BrdfAverageAlbedoTable>>,
}

/// A boxed handle filled by `parse`, which borrows `bytes` for the program's lifetime.
fn parse_boxed<H>(
    bytes: &'static [u8],
    parse: unsafe extern "C" fn(*mut H, *const u8, usize) -> BrdfStatus,
) -> Result<Box<H>> {
    let mut h = Box::new(MaybeUninit::<H>::uninit());
    // SAFETY: the pointer is valid for writes; `bytes` lives for the rest of the program.
    let st = unsafe { parse(h.as_mut_ptr(), bytes.as_ptr(), bytes.len()) };
    if st != BRDF_STATUS_OK {
        bail!("parse failed with status {st}");
    }
    // SAFETY: a successful parse initialised the handle.
    Ok(unsafe { Box::from_raw(Box::into_raw(h).cast::<H>()) })
}

impl HostTables {
    fn load(root: &Path, refs: &[TableRef]) -> Result<Self> {
        let mut t = HostTables {
            g: None,
            dfg: None,
            e: None,
            eavg: None,
        };
        for r in refs {
            if r.file.contains('/') || r.file.contains("..") {
                bail!("table name {:?} must be a plain file name", r.file);
            }
            let path = root.join("assets").join(&r.file);
            let bytes =
                std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
            if bytes.len() != r.len || fnv1a(&bytes) != r.fnv {
                bail!(
                    "{}: the C program embeds {} bytes (FNV-1a {:08x}), assets/ holds {} ({:08x})",
                    r.file,
                    r.len,
                    r.fnv,
                    bytes.len(),
                    fnv1a(&bytes)
                );
            }
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            let ctx = || format!("{} on the host", r.file);
            match r.role.as_str() {
                "g" => t.g = Some(parse_boxed(bytes, brdf_g_table_parse).with_context(ctx)?),
                "dfg" => t.dfg = Some(parse_boxed(bytes, brdf_dfg_table_parse).with_context(ctx)?),
                "e" => t.e = Some(parse_boxed(bytes, brdf_albedo_table_parse).with_context(ctx)?),
                "eavg" => {
                    t.eavg = Some(
                        parse_boxed(bytes, brdf_average_albedo_table_parse).with_context(ctx)?,
                    )
                }
                other => bail!("unknown table role {other:?}"),
            }
        }
        Ok(t)
    }
}

fn f(a: &Arg) -> Result<f32> {
    match a {
        Arg::F32(b) => Ok(f32::from_bits(*b)),
        _ => bail!("expected an f32 argument, got {a:?}"),
    }
}
fn d(a: &Arg) -> Result<f64> {
    match a {
        Arg::F64(b) => Ok(f64::from_bits(*b)),
        _ => bail!("expected an f64 argument, got {a:?}"),
    }
}
fn u(a: &Arg) -> Result<u32> {
    match a {
        Arg::U(v) => Ok(*v),
        _ => bail!("expected an integer argument, got {a:?}"),
    }
}
fn vf(x: f32) -> Val {
    Val::F32(x.to_bits())
}
fn vd(x: f64) -> Val {
    Val::F64(x.to_bits())
}

/// Initialises a handle with `init` (which must return OK) and runs `query` on it.
fn with_handle<H, R>(
    init: impl FnOnce(*mut H) -> BrdfStatus,
    query: impl FnOnce(*const H) -> R,
) -> Result<R> {
    let mut h = MaybeUninit::<H>::uninit();
    let st = init(h.as_mut_ptr());
    if st != BRDF_STATUS_OK {
        bail!("init failed with status {st}");
    }
    Ok(query(h.as_ptr()))
}

fn host_values(t: &HostTables, kernel: &str, a: &[Arg]) -> Result<Vec<Val>> {
    let n = |k: usize| -> Result<()> {
        if a.len() != k {
            bail!("{kernel} takes {k} arguments, got {}", a.len());
        }
        Ok(())
    };
    fn tbl<T>(x: &Option<Box<T>>, name: &str) -> Result<*const T> {
        x.as_deref()
            .map(|r| r as *const T)
            .with_context(|| format!("{name} results without a TABLE line"))
    }
    // SAFETY (all blocks below): handles come from `with_handle`/`HostTables`, initialised
    // by a successful init/parse; everything else is passed by value.
    unsafe {
        Ok(match kernel {
            "mg_terms_f32" | "mg_terms_dots_f32" => {
                let dots = kernel == "mg_terms_dots_f32";
                n(if dots { 5 } else { 4 })?;
                let (s, c) = (f(&a[0])?, u(&a[1])?);
                let r = with_handle(
                    |h| brdf_modified_g_init_f32(h, s, c),
                    |h| {
                        if dots {
                            Ok(brdf_modified_g_terms_dots_f32(
                                h,
                                f(&a[2])?,
                                f(&a[3])?,
                                f(&a[4])?,
                            ))
                        } else {
                            Ok::<_, anyhow::Error>(brdf_modified_g_terms_f32(
                                h,
                                f(&a[2])?,
                                f(&a[3])?,
                            ))
                        }
                    },
                )??;
                vec![vf(r.gm), vf(r.gs), vf(r.g)]
            }
            "mg_terms_f64" => {
                n(4)?;
                let (s, c, ti, tr) = (d(&a[0])?, u(&a[1])?, d(&a[2])?, d(&a[3])?);
                let r = with_handle(
                    |h| brdf_modified_g_init_f64(h, s, c),
                    |h| brdf_modified_g_terms_f64(h, ti, tr),
                )?;
                vec![vd(r.gm), vd(r.gs), vd(r.g)]
            }
            "blinn_f32" => {
                n(2)?;
                vec![vf(brdf_g_blinn_f32(f(&a[0])?, f(&a[1])?))]
            }
            "blinn_dots_f32" => {
                n(3)?;
                vec![vf(brdf_g_blinn_dots_f32(f(&a[0])?, f(&a[1])?, f(&a[2])?))]
            }
            "g1_smith_f32" => {
                n(3)?;
                vec![vf(brdf_g1_smith_f32(u(&a[0])?, f(&a[1])?, f(&a[2])?))]
            }
            "g_smith_f32" => {
                n(5)?;
                vec![vf(brdf_g_smith_f32(
                    u(&a[0])?,
                    u(&a[1])?,
                    f(&a[2])?,
                    f(&a[3])?,
                    f(&a[4])?,
                ))]
            }
            "ts_f32" => {
                n(10)?;
                let (s, g, fr, p, ks, al) = (
                    f(&a[0])?,
                    u(&a[1])?,
                    u(&a[2])?,
                    f(&a[3])?,
                    f(&a[4])?,
                    f(&a[5])?,
                );
                let (x, y, z) = (f(&a[6])?, f(&a[7])?, f(&a[8])?);
                let nh = f(&a[9])?;
                let (v, sp, vh) = with_handle(
                    |h| brdf_torrance_sparrow_init_f32(h, s, g, fr, p, ks, al),
                    |h| {
                        (
                            brdf_torrance_sparrow_eval_f32(h, x, y, z),
                            brdf_torrance_sparrow_specular_f32(h, x, y, z),
                            brdf_torrance_sparrow_eval_nh_f32(h, x, y, z, nh),
                        )
                    },
                )?;
                vec![vf(v), vf(sp), vf(vh)]
            }
            "ts_f64" => {
                n(10)?;
                let (s, g, fr, p, ks, al) = (
                    d(&a[0])?,
                    u(&a[1])?,
                    u(&a[2])?,
                    d(&a[3])?,
                    d(&a[4])?,
                    d(&a[5])?,
                );
                let (x, y, z) = (d(&a[6])?, d(&a[7])?, d(&a[8])?);
                let nh = d(&a[9])?;
                let (v, sp, vh) = with_handle(
                    |h| brdf_torrance_sparrow_init_f64(h, s, g, fr, p, ks, al),
                    |h| {
                        (
                            brdf_torrance_sparrow_eval_f64(h, x, y, z),
                            brdf_torrance_sparrow_specular_f64(h, x, y, z),
                            brdf_torrance_sparrow_eval_nh_f64(h, x, y, z, nh),
                        )
                    },
                )?;
                vec![vd(v), vd(sp), vd(vh)]
            }
            "ts_albedo_f32" => {
                n(7)?;
                let (s, g, fr, p, ks, al, mu) = (
                    f(&a[0])?,
                    u(&a[1])?,
                    u(&a[2])?,
                    f(&a[3])?,
                    f(&a[4])?,
                    f(&a[5])?,
                    f(&a[6])?,
                );
                vec![vf(with_handle(
                    |h| brdf_torrance_sparrow_init_f32(h, s, g, fr, p, ks, al),
                    |h| brdf_torrance_sparrow_albedo_f32(h, mu),
                )?)]
            }
            "ggx_f32" | "ggx_albedo_f32" => {
                let albedo = kernel == "ggx_albedo_f32";
                n(if albedo { 6 } else { 11 })?;
                let f0 = BrdfRgbF32 {
                    r: f(&a[0])?,
                    g: f(&a[1])?,
                    b: f(&a[2])?,
                };
                let (alpha, form) = (f(&a[3])?, u(&a[4])?);
                let c = if albedo {
                    let mu = f(&a[5])?;
                    with_handle(
                        |h| brdf_ggx_init_f32(h, f0, alpha, form),
                        |h| brdf_ggx_albedo_f32(h, mu),
                    )?
                } else {
                    let v = |k: usize| -> Result<BrdfVec3F32> {
                        Ok(BrdfVec3F32 {
                            x: f(&a[k])?,
                            y: f(&a[k + 1])?,
                            z: f(&a[k + 2])?,
                        })
                    };
                    let (wi, wo) = (v(5)?, v(8)?);
                    with_handle(
                        |h| brdf_ggx_init_f32(h, f0, alpha, form),
                        |h| brdf_ggx_eval_f32(h, wi, wo),
                    )?
                };
                vec![vf(c.r), vf(c.g), vf(c.b)]
            }
            "g_table" => {
                n(2)?;
                let r = brdf_g_table_terms(tbl(&t.g, "g_table")?, f(&a[0])?, f(&a[1])?);
                vec![vf(r.gm), vf(r.gs), vf(r.g)]
            }
            "g_table_dots" => {
                n(3)?;
                vec![vf(brdf_g_table_g_dots(
                    tbl(&t.g, "g_table_dots")?,
                    f(&a[0])?,
                    f(&a[1])?,
                    f(&a[2])?,
                ))]
            }
            "dfg" => {
                n(2)?;
                let r = brdf_dfg_table_ab(tbl(&t.dfg, "dfg")?, f(&a[0])?, f(&a[1])?);
                vec![vf(r.a), vf(r.b)]
            }
            "e" => {
                n(2)?;
                vec![vf(brdf_albedo_table_e(
                    tbl(&t.e, "e")?,
                    f(&a[0])?,
                    f(&a[1])?,
                ))]
            }
            "eavg" => {
                n(1)?;
                vec![vf(brdf_average_albedo_table_e_avg(
                    tbl(&t.eavg, "eavg")?,
                    f(&a[0])?,
                ))]
            }
            other => bail!("the host does not know kernel {other:?}"),
        })
    }
}

// ---------------------------------------------------------------------------------------
// Panic paths

/// The functions of the device ELF (demangled, without hashes) that branch directly to
/// core's panic entry points or to a core function that does; core's own functions are not
/// listed.
fn panic_callers(elf: &Path) -> Result<Vec<String>> {
    let out = Command::new("arm-none-eabi-objdump")
        .args(["-d", "-C"])
        .arg(elf)
        .output()
        .context("running arm-none-eabi-objdump")?;
    if !out.status.success() {
        bail!("objdump failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    // function → the functions it branches to
    let mut calls: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut cur = String::new();
    for l in text.lines() {
        if let Some(name) = l
            .strip_suffix(">:")
            .and_then(|h| h.split_once(" <"))
            .map(|x| x.1)
        {
            cur = strip_hash(name);
            calls.entry(cur.clone()).or_default();
        } else if l.contains("\tbl\t") || l.contains("\tb.w\t") || l.contains("\tb\t") {
            if let Some(target) = l.rsplit_once('<').map(|x| x.1.trim_end_matches('>')) {
                let target = strip_hash(target.split('+').next().unwrap_or(target));
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

/// Drops a trailing `::h<16 hex>` of Rust's legacy mangling.
fn strip_hash(name: &str) -> String {
    match name.rsplit_once("::h") {
        Some((head, h)) if h.len() == 16 && h.bytes().all(|b| b.is_ascii_hexdigit()) => {
            head.to_string()
        }
        _ => name.to_string(),
    }
}

// ---------------------------------------------------------------------------------------
// Sizes

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
    let out = Command::new(llvm_tool("llvm-size")?)
        .arg("-A")
        .arg(elf)
        .output()
        .context("running llvm-size")?;
    if !out.status.success() {
        bail!("llvm-size failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    let mut sections = BTreeMap::new();
    for l in String::from_utf8_lossy(&out.stdout).lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.len() == 3 && f[0].starts_with('.') {
            if let Ok(n) = f[1].parse::<u64>() {
                sections.insert(f[0].to_string(), n);
            }
        }
    }
    let out = Command::new(llvm_tool("llvm-nm")?)
        .args(["--print-size", "--demangle", "--defined-only"])
        .arg(elf)
        .output()
        .context("running llvm-nm")?;
    if !out.status.success() {
        bail!("llvm-nm failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    let mut parts = BTreeMap::new();
    for l in String::from_utf8_lossy(&out.stdout).lines() {
        // "<addr> <size> <type> <name…>"
        let mut it = l.splitn(4, ' ');
        let (Some(_addr), Some(size), Some(ty), Some(name)) =
            (it.next(), it.next(), it.next(), it.next())
        else {
            continue;
        };
        let Ok(size) = u64::from_str_radix(size, 16) else {
            continue;
        };
        // Flash: code and read-only data (t/T, r/R) and initialised data (d/D, its load image).
        if matches!(ty, "t" | "T" | "r" | "R" | "d" | "D") {
            *parts.entry(part(name)).or_default() += size;
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
            "libbrdf_ffi kernels (modified G, Blinn, Smith, Torrance–Sparrow, GGX, albedo; libm, soft-f64)",
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
        crate::fsio::replace(path, out.as_bytes())?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        // FNV-1a 32-bit test vectors from the algorithm's reference description.
        assert_eq!(fnv1a(b""), 0x811c_9dc5);
        assert_eq!(fnv1a(b"a"), 0xe40c_292c);
        assert_eq!(fnv1a(b"foobar"), 0xbf9c_f968);
    }

    #[test]
    fn protocol_tokens_parse_by_width() {
        assert_eq!(parse_tok("u:7").unwrap(), Arg::U(7));
        assert_eq!(parse_tok("3e99999a").unwrap(), Arg::F32(0.3f32.to_bits()));
        assert_eq!(
            parse_tok("3fd3333333333333").unwrap(),
            Arg::F64(0.3f64.to_bits())
        );
        assert!(parse_tok("3e9999").is_err());
        assert!(parse_tok("zz99999a").is_err());
    }

    #[test]
    fn a_one_ulp_difference_is_reported() {
        let t = HostTables {
            g: None,
            dfg: None,
            e: None,
            eavg: None,
        };
        let args = [Arg::F32(0.5f32.to_bits()), Arg::F32(0.2f32.to_bits())];
        let host = host_values(&t, "blinn_f32", &args).unwrap();
        let Val::F32(b) = host[0] else { panic!() };
        assert_ne!(host, vec![Val::F32(b ^ 1)]);
        // Wrong argument counts and unknown kernels are errors, not passes.
        assert!(host_values(&t, "blinn_f32", &args[..1]).is_err());
        assert!(host_values(&t, "nope", &args).is_err());
        assert!(host_values(&t, "g_table", &args).is_err());
    }
}

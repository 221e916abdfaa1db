//! The C ABI's build steps: the header (rustc's macro expansion read by cbindgen), the
//! cross compiler, the device and host libraries and `examples/c`.

use crate::run_step;
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The header cbindgen generates from crates/brdf-ffi with its cbindgen.toml.
///
/// The crate's typed exports come from one macro (`typed_abi!`, instantiated for `f32` and
/// `f64`), and cbindgen reads source text without expanding macros. So rustc expands the
/// crate first (`-Zunpretty=expanded`: a nightly flag, allowed on the stable toolchain for
/// this one child process by `RUSTC_BOOTSTRAP=1`; nothing is compiled to code), with
/// `--cfg brdf_header` to leave the Rust-only `# Safety` sections out, and cbindgen reads the
/// expanded file.
pub fn generate_header(root: &Path) -> Result<String> {
    let krate = root.join("crates/brdf-ffi");
    let expanded = expand_ffi(root)?;
    let dir = tempfile::tempdir().context("creating a folder for the expanded crate")?;
    let src = dir.path().join("lib.rs");
    std::fs::write(&src, expanded).with_context(|| format!("writing {}", src.display()))?;
    let config = cbindgen::Config::from_file(krate.join("cbindgen.toml"))
        .map_err(|e| anyhow::anyhow!("reading cbindgen.toml: {e}"))?;
    let bindings = cbindgen::Builder::new()
        .with_src(&src)
        .with_config(config)
        .generate()
        .map_err(|e| anyhow::anyhow!("cbindgen: {e}"))?;
    let mut buf = Vec::new();
    bindings.write(&mut buf);
    String::from_utf8(buf).context("cbindgen wrote non-UTF-8")
}

/// brdf-ffi's source with every macro expanded, as rustc prints it (host target).
fn expand_ffi(root: &Path) -> Result<String> {
    let out = crate::cargo()
        .current_dir(root)
        .args([
            "rustc",
            "-p",
            "brdf-ffi",
            "--lib",
            "--profile=check",
            "--locked",
        ])
        .args([
            "--quiet",
            "--",
            "-Zunpretty=expanded",
            "--cfg",
            "brdf_header",
        ])
        .env("RUSTC_BOOTSTRAP", "1")
        .env(
            "CARGO_TARGET_DIR",
            crate::target_dir(root).join("cffi-expand"),
        )
        .output()
        .context("running cargo rustc -Zunpretty=expanded for brdf-ffi")?;
    if !out.status.success() || out.stdout.is_empty() {
        bail!(
            "expanding brdf-ffi failed ({}):\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    }
    String::from_utf8(out.stdout).context("rustc printed non-UTF-8 source")
}

fn have(cmd: &str) -> bool {
    Command::new(cmd)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// arm-none-eabi-gcc and newlib from Debian when missing (CI machines start without them).
pub(crate) fn ensure_arm_gcc() -> Result<()> {
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

/// libbrdf_ffi.a for the Cortex-M4F, in its own target folder (size-optimised, fat LTO).
pub(crate) fn build_device_lib(root: &Path, base: &Path) -> Result<PathBuf> {
    let tdir = base.join("cffi-rust-device");
    let mut cmd = crate::cargo();
    cmd.current_dir(root)
        .args(["rustc", "-p", "brdf-ffi", "--release", "--locked"])
        .args(["--target", "thumbv7em-none-eabihf"])
        .args(["--crate-type", "staticlib"])
        .args(["--config", "profile.release.opt-level=\"z\""])
        .args(["--config", "profile.release.lto=\"fat\""])
        .args(["--config", "profile.release.codegen-units=1"])
        .args(["--config", "profile.release.panic=\"abort\""])
        .env("CARGO_TARGET_DIR", &tdir);
    run_step(&mut cmd, "building libbrdf_ffi.a for thumbv7em-none-eabihf")?;
    Ok(tdir.join("thumbv7em-none-eabihf/release/libbrdf_ffi.a"))
}

/// libbrdf_ffi.a and libbrdf_ffi.so for the host (the workspace's release profile).
pub(crate) fn build_host_lib(root: &Path, base: &Path) -> Result<PathBuf> {
    let mut cmd = crate::cargo();
    cmd.current_dir(root)
        .args(["build", "-p", "brdf-ffi", "--release", "--locked"]);
    run_step(&mut cmd, "building libbrdf_ffi for the host")?;
    Ok(base.join("release"))
}

/// Builds `examples/c` with `make` into `out`: the device ELF and the two host programs.
pub(crate) fn make_examples(
    root: &Path,
    out: &Path,
    device_lib: &Path,
    host_dir: &Path,
) -> Result<()> {
    let mut make = Command::new("make");
    make.arg("-B")
        .arg("-C")
        .arg(root.join("examples/c"))
        .arg("all")
        .arg(format!("ROOT={}", root.display()))
        .arg(format!("OUT={}", out.display()))
        .arg(format!("DEVICE_LIB={}", device_lib.display()))
        .arg(format!("HOST_LIB_DIR={}", host_dir.display()))
        .arg("EXTRA_CFLAGS=-Werror");
    run_step(&mut make, "building examples/c (make)")
}

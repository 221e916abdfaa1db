//! What the firmware runner (`cargo xtask firmware`, Rust on the Cortex-M4F) and the C
//! runner (`cargo xtask cffi`, C on the Cortex-M4F and on the host) share: installing QEMU
//! (`.ci/install-qemu.sh`), running an ELF on `mps2-an386` with semihosting and a host
//! program, each under a timeout; what the programs print
//! and how a run is judged ([`protocol`]); flash and RAM read from an ELF ([`elf`]).

pub(crate) mod elf;
pub(crate) mod protocol;

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Wall-clock limit for one QEMU run.
pub const QEMU_TIMEOUT_S: u32 = 60;

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

/// A finished (or timed-out) run.
pub(crate) struct RunOut {
    pub(crate) stdout: String,
    pub(crate) stderr: String,
    pub(crate) status: Option<i32>,
    pub(crate) timed_out: bool,
    /// The limit it ran under, seconds.
    pub(crate) timeout_s: u32,
}

/// Runs `cmd` under timeout(1) with a wall-clock limit of `timeout_s` seconds.
pub(crate) fn run_timed(cmd: &mut Command, timeout_s: u32) -> Result<RunOut> {
    let mut t = Command::new("timeout");
    t.args(["--kill-after=5", &timeout_s.to_string()])
        .arg(cmd.get_program())
        .args(cmd.get_args());
    for (k, v) in cmd.get_envs() {
        match v {
            Some(v) => t.env(k, v),
            None => t.env_remove(k),
        };
    }
    let out = t
        .output()
        .with_context(|| format!("running {}", cmd.get_program().to_string_lossy()))?;
    let status = out.status.code();
    Ok(RunOut {
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        status,
        // timeout(1) exits 124 on expiry (137 if it had to SIGKILL).
        timed_out: matches!(status, Some(124) | Some(137)),
        timeout_s,
    })
}

/// Runs `elf` on QEMU's `mps2-an386` (Cortex-M4F) with semihosting on stdout.
pub(crate) fn run_qemu(qemu: &Path, elf: &Path) -> Result<RunOut> {
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
    let mut cmd = Command::new(qemu);
    cmd.args(["-machine", "mps2-an386", "-cpu", "cortex-m4", "-nographic"])
        .args(["-monitor", "none", "-serial", "none"])
        .args(["-semihosting-config", "enable=on,target=native", "-kernel"])
        .arg(elf)
        .env("LD_LIBRARY_PATH", ld.trim_end_matches(':'));
    run_timed(&mut cmd, QEMU_TIMEOUT_S)
}

//! Running programs for the firmware and C runners: installs QEMU (`.ci/install-qemu.sh`),
//! builds the firmware for the Cortex-M4F, runs an ELF on `mps2-an386` with semihosting and
//! a host program, each under a timeout. What they print is read by [`super::protocol`].

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Wall-clock limit for one QEMU run.
pub const QEMU_TIMEOUT_S: u32 = 60;

/// The repository root (xtask lives in it).
pub(crate) fn repo_root() -> PathBuf {
    crate::fsio::workspace_root()
}

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
pub(crate) fn locked_version(lock: &Path, krate: &str) -> Option<String> {
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

pub(crate) fn build(root: &Path, micromath: bool) -> Result<PathBuf> {
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

//! QEMU and the firmware run: installs QEMU (`.ci/install-qemu.sh`), builds the firmware for
//! the Cortex-M4F, runs an ELF on `mps2-an386` under a timeout with semihosting, and parses
//! the line protocol the firmware prints (`crates/brdf-firmware/src/report.rs`).

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

pub(crate) struct Res {
    pub(crate) kernel: String,
    pub(crate) args: Vec<f32>,
    pub(crate) value: f32,
}

pub(crate) struct Check {
    pub(crate) ok: bool,
    pub(crate) line: String,
}

/// A `TABLE` line: an embedded table the host must load from `assets/`.
pub(crate) struct TableRef {
    pub(crate) file: String,
    pub(crate) len: usize,
    pub(crate) crc: u32,
}

pub(crate) struct Parsed {
    pub(crate) tables: Vec<TableRef>,
    pub(crate) results: Vec<Res>,
    pub(crate) checks: Vec<Check>,
    pub(crate) stack: Option<u64>,
    pub(crate) declared_results: Option<u32>,
    pub(crate) ended: bool,
}

/// Parses `bits/decimal`, and checks that the device's decimal text reads back to the same
/// bits (this exercises core::fmt's float printing on the target).
pub(crate) fn parse_num(tok: &str) -> Result<f32> {
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

pub(crate) fn parse(stdout: &str) -> Result<Parsed> {
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

    #[test]
    fn parse_num_rejects_inconsistent_decimal() {
        assert_eq!(parse_num("3e99999a/0.3").unwrap(), 0.3f32);
        assert!(parse_num("3e99999a/0.31").is_err());
        assert!(parse_num("zz/0.3").is_err());
    }
}

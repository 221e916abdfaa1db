//! The Python parts of the benchmark run: the virtual environments, the SciPy peer
//! (`crates/brdf-bench/peer/g_peer.py`) and the Python package's own benchmark.

use crate::report::Peer;
use crate::{angle_pairs, SIGMA};
use std::path::{Path, PathBuf};
use std::process::Command;

/// SciPy for the peer, installed from PyPI into `.cache/scipy-venv` (pinned: the peer's
/// time depends on its version).
const SCIPY: &str = "scipy==1.16.3";

/// The Python of the virtual environment `venv` (under the workspace) in which `module`
/// imports, creating the environment (`python3 -m venv`) and installing `packages` with pip
/// when it does not. Idempotent: an environment where `module` imports is reused.
fn venv_python(
    root: &Path,
    venv: &str,
    module: &str,
    packages: &[&std::ffi::OsStr],
) -> std::result::Result<PathBuf, String> {
    let venv = root.join(venv);
    let py = venv.join("bin/python3");
    let imports = |py: &Path| {
        Command::new(py)
            .args(["-c", &format!("import {module}")])
            .output()
            .is_ok_and(|o| o.status.success())
    };
    if imports(&py) {
        return Ok(py);
    }
    let run = |cmd: &mut Command, what: &str| -> std::result::Result<(), String> {
        let o = cmd.output().map_err(|e| format!("{what}: {e}"))?;
        if o.status.success() {
            return Ok(());
        }
        let err = String::from_utf8_lossy(&o.stderr);
        Err(format!(
            "{what} failed: {}",
            err.lines().last().unwrap_or("").trim()
        ))
    };
    eprintln!("installing {module} into {}", venv.display());
    if !py.exists() {
        run(
            Command::new("python3").args(["-m", "venv"]).arg(&venv),
            "python3 -m venv",
        )?;
    }
    let pip = [
        "-m",
        "pip",
        "install",
        "--quiet",
        "--disable-pip-version-check",
    ];
    run(Command::new(&py).args(pip).args(packages), "pip install")?;
    if imports(&py) {
        Ok(py)
    } else {
        Err(format!(
            "installed into {} but `import {module}` fails",
            venv.display()
        ))
    }
}

/// The Python with SciPy importable for the peer (`.cache/scipy-venv`).
pub(super) fn scipy_python(root: &Path) -> std::result::Result<PathBuf, String> {
    venv_python(
        root,
        ".cache/scipy-venv",
        "scipy.integrate",
        &[SCIPY.as_ref()],
    )
}

pub(super) fn run_peer(root: &Path, n: usize, repeat: usize) -> Peer {
    let python = match scipy_python(root) {
        Ok(p) => p,
        Err(why) => {
            eprintln!("SciPy peer skipped: {why}");
            return Peer::Skipped(why);
        }
    };
    let script = root.join("crates/brdf-bench/peer/g_peer.py");
    let (ti, tr) = angle_pairs::<f64>(n);
    let pairs: Vec<String> = ti
        .iter()
        .zip(&tr)
        .map(|(a, b)| format!("{a:.17},{b:.17}"))
        .collect();
    let out = Command::new(&python)
        .arg(&script)
        .args([
            "--sigma",
            &SIGMA.to_string(),
            "--repeat",
            &repeat.to_string(),
        ])
        .arg("--pairs")
        .arg(pairs.join(";"))
        .output();
    let out = match out {
        Ok(o) => o,
        Err(e) => return Peer::Skipped(format!("python3 not runnable ({e})")),
    };
    if !out.status.success() {
        let msg = String::from_utf8_lossy(&out.stderr).trim().to_string();
        eprintln!("SciPy peer skipped: {msg}");
        return Peer::Skipped(msg);
    }
    match serde_json::from_slice(&out.stdout) {
        Ok(v) => Peer::from_json(&v, n),
        Err(e) => Peer::Skipped(format!("unreadable peer output ({e})")),
    }
}

/// The Python package's interpreter: `.cache/python-venv` (made by `.ci/python.sh`) with
/// `brdf_kernels` importable, built there from `crates/brdf-py` when it is not (`python3 -m
/// venv`, then `pip install numpy ./crates/brdf-py`; needs cargo and PyPI).
fn package_python(root: &Path) -> std::result::Result<std::path::PathBuf, String> {
    let pkg = root.join("crates/brdf-py");
    venv_python(
        root,
        ".cache/python-venv",
        "brdf_kernels",
        &["numpy".as_ref(), pkg.as_os_str()],
    )
}

/// Runs `crates/brdf-py/bench/bench.py --json` (the SciPy peer through `.cache/scipy-venv`
/// when that exists) and returns its figures.
pub(super) fn python_bench(root: &Path) -> std::result::Result<serde_json::Value, String> {
    eprintln!("== Python package");
    let py = package_python(root)?;
    let mut cmd = Command::new(&py);
    cmd.arg(root.join("crates/brdf-py/bench/bench.py"))
        .arg("--json")
        .current_dir(root);
    let peer = root.join(".cache/scipy-venv/bin/python3");
    if peer.exists() {
        cmd.arg("--peer-python").arg(peer);
    }
    let o = cmd.output().map_err(|e| format!("bench.py: {e}"))?;
    if !o.status.success() {
        let err = String::from_utf8_lossy(&o.stderr);
        return Err(format!(
            "bench.py failed: {}",
            err.lines().last().unwrap_or("").trim()
        ));
    }
    serde_json::from_slice(&o.stdout).map_err(|e| format!("unreadable bench.py output ({e})"))
}

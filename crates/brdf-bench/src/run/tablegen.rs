//! The "Table generation" figures: the default set and the Khronos target through the
//! generator, the converged reference rows, and the numpy Monte Carlo peer on them.

use super::{python, Env};
use crate::report::tablegen::{self as tg, TableGen, KHRONOS_SIZE, PEER_SAMPLES};
use anyhow::Result;
use std::process::Command;

/// Every table of the default set (on grids of at most `shrink` nodes per axis when given)
/// and every `stride`-th row of the Khronos target, timed; the peer on the same rows.
pub(super) fn measure(env: &Env, stride: usize, shrink: Option<u32>) -> Result<TableGen> {
    eprintln!("== table generation: the default set");
    let tables = tg::time_default_set(shrink)?;
    eprintln!("== table generation: Khronos 1024², every {stride}th row");
    let khronos = tg::time_table("Khronos `lut_ggx` 1024² (A, B)", &tg::khronos_spec(stride))?;
    eprintln!("== Monte Carlo peer (numpy)");
    let peer = mc_peer(env, stride);
    if let Err(why) = &peer {
        eprintln!("Monte Carlo peer skipped: {why}");
    }
    Ok(TableGen {
        tables,
        khronos,
        stride,
        peer,
        threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
        shrunk: shrink,
    })
}

/// `peer/dfg_mc_peer.py` on every `stride`-th row of the Khronos grid against the converged
/// rows (written to `<target>/bench/`), in the SciPy environment (which has NumPy).
fn mc_peer(env: &Env, stride: usize) -> std::result::Result<tg::McPeer, String> {
    let py = python::scipy_python(&env.root)?;
    let dir = env.target.join("bench");
    let reference = dir.join(format!("dfg_converged_stride{stride}.f64"));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    brdf_engine_assets::fsio::replace(&reference, &tg::converged_rows(stride))
        .map_err(|e| e.to_string())?;
    let n = |x: usize| x.to_string();
    let o = Command::new(&py)
        .arg(env.root.join("crates/brdf-bench/peer/dfg_mc_peer.py"))
        .args(["--size", &n(KHRONOS_SIZE), "--samples", &n(PEER_SAMPLES)])
        .args(["--stride", &n(stride), "--reference"])
        .arg(&reference)
        .output()
        .map_err(|e| format!("dfg_mc_peer.py: {e}"))?;
    if !o.status.success() {
        let err = String::from_utf8_lossy(&o.stderr);
        return Err(format!(
            "dfg_mc_peer.py failed: {}",
            err.lines().last().unwrap_or("")
        ));
    }
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).map_err(|e| format!("unreadable peer output ({e})"))?;
    let versions = Command::new(&py)
        .args(["-c", "import sys, numpy; print(f'Python {sys.version.split()[0]}, NumPy {numpy.__version__}')"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    tg::mc_peer_from_json(&v, versions)
}

//! `cargo xtask bench`: runs the criterion suite of `crates/brdf-bench` with short settings
//! (libm, then the f32 kernels again with micromath), the SciPy peer, callgrind instruction
//! counts and the LUT generation timing, all in one run, saves the raw results
//! (`<target>/bench/report.json`) and writes `docs/benchmarks.md` (`brdf_bench::report`).
//!
//! `cargo xtask bench --smoke` only checks that everything builds and runs once (CI).
//! `cargo xtask bench --from FILE` re-renders the report from saved raw results.

mod python;
mod tablegen;

use crate::report::{self, Counts, Data, Machine, Peer};
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// Build every benchmark and run each once, without measuring or writing the report
    /// (what CI runs).
    #[arg(long)]
    smoke: bool,
    /// Criterion warm-up time per benchmark, in seconds.
    #[arg(long, default_value_t = 0.2)]
    warm_up: f64,
    /// Criterion measurement time per benchmark, in seconds.
    #[arg(long, default_value_t = 0.6)]
    measurement: f64,
    /// Criterion samples per benchmark.
    #[arg(long, default_value_t = 15)]
    sample_size: usize,
    /// Do not time the generation of the default asset set.
    #[arg(long)]
    skip_generation: bool,
    /// Report path (default: docs/benchmarks.md of the workspace).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Re-render the report from the raw results a run saved (`<target>/bench/report.json`)
    /// instead of measuring.
    #[arg(long)]
    from: Option<PathBuf>,
}

/// The f32 benchmarks run a second time with micromath (criterion filter, a regex).
const MICROMATH_FILTER: &str = "^(g_direct_f32|g_closed_f32|batch_f32)";

/// The Khronos target and its peer are timed on every FULL_STRIDE-th roughness row in a
/// full run, every SMOKE_STRIDE-th in the smoke run.
const FULL_STRIDE: usize = 8;
const SMOKE_STRIDE: usize = 64;
/// The smoke run's default set: at most this many nodes per axis (a check, not a timing).
const SMOKE_NODES: u32 = 8;

/// The workspace, cargo and the target folder of this build.
struct Env {
    root: PathBuf,
    cargo: String,
    target: PathBuf,
}

impl Env {
    fn new() -> Env {
        let root = crate::workspace_root();
        let target = match std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from) {
            Some(t) if t.is_absolute() => t,
            Some(t) => root.join(t),
            None => root.join("target"),
        };
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        Env {
            root,
            cargo,
            target,
        }
    }
}

pub fn run(a: Args) -> Result<()> {
    let env = Env::new();
    if a.smoke {
        return smoke(&env);
    }
    let data: Data = match &a.from {
        Some(from) => serde_json::from_slice(
            &std::fs::read(from).with_context(|| format!("reading {}", from.display()))?,
        )?,
        None => measure(&env, &a)?,
    };
    let md = report::render(&data)?;
    let out = a.out.unwrap_or_else(|| env.root.join("docs/benchmarks.md"));
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    brdf_engine_assets::fsio::replace(&out, md.as_bytes())
        .with_context(|| format!("writing {}", out.display()))?;
    eprintln!("wrote {}", out.display());
    Ok(())
}

/// One whole run: criterion (libm, micromath), the peers, accuracy, callgrind, generation;
/// saves the raw results as JSON under the target folder.
fn measure(env: &Env, a: &Args) -> Result<Data> {
    let t_start = Instant::now();
    let crit_dir = env.target.join("criterion");
    if crit_dir.exists() {
        std::fs::remove_dir_all(&crit_dir).context("clearing old criterion results")?;
    }
    let settings: Vec<String> = [
        ("--warm-up-time", a.warm_up.to_string()),
        ("--measurement-time", a.measurement.to_string()),
        ("--sample-size", a.sample_size.to_string()),
        ("--nresamples", "20000".into()),
    ]
    .into_iter()
    .flat_map(|(k, v)| [k.to_string(), v])
    .collect();
    eprintln!("== criterion, libm");
    cargo_bench(env, &[], &settings, None)?;
    eprintln!("== criterion, micromath (f32 kernels)");
    cargo_bench(
        env,
        &["--features", "micromath"],
        &settings,
        Some(MICROMATH_FILTER),
    )?;
    let est = report::read_estimates(&crit_dir).map_err(anyhow::Error::msg)?;
    let t_crit = t_start.elapsed().as_secs_f64();
    eprintln!("== SciPy peer");
    let peer = python::run_peer(&env.root, crate::BATCH, 7);
    eprintln!("== accuracy");
    let acc = report::accuracy();
    eprintln!("== callgrind");
    let cg = callgrind(env);
    let gen = if a.skip_generation {
        None
    } else {
        eprintln!("== generation of the default asset set");
        Some(time_generation()?)
    };
    let tablegen = Some(tablegen::measure(env, FULL_STRIDE, None)?);
    let python = python::python_bench(&env.root);
    let data = Data {
        est,
        peer,
        acc,
        cg,
        gen,
        machine: Machine::detect(),
        warm_up: a.warm_up,
        measurement: a.measurement,
        sample_size: a.sample_size,
        secs: t_start.elapsed().as_secs_f64(),
        t_crit,
        python,
        tablegen,
    };
    let raw = env.target.join("bench/report.json");
    std::fs::create_dir_all(env.target.join("bench"))?;
    brdf_engine_assets::fsio::replace(&raw, &serde_json::to_vec_pretty(&data)?)?;
    eprintln!("raw results: {}", raw.display());
    Ok(data)
}

fn smoke(env: &Env) -> Result<()> {
    let t0 = Instant::now();
    let test = ["--test".to_string()];
    cargo_bench(env, &[], &test, None)?;
    cargo_bench(
        env,
        &["--features", "micromath"],
        &test,
        Some(MICROMATH_FILTER),
    )?;
    let h = build_harness(env)?;
    for (k, _, _) in harness_kernels(&h)? {
        let st = Command::new(&h).args([k.as_str(), "3"]).status()?;
        if !st.success() {
            bail!("harness {k} failed");
        }
    }
    match python::run_peer(&env.root, 2, 1) {
        Peer::Ran { ns_per_g, .. } => eprintln!("SciPy peer ran ({ns_per_g:.0} ns per G)"),
        Peer::Skipped(why) => bail!("SciPy peer did not run: {why}"),
    }
    let t = tablegen::measure(env, SMOKE_STRIDE, Some(SMOKE_NODES))?;
    if let Err(why) = &t.peer {
        bail!("the Monte Carlo peer did not run: {why}");
    }
    let section = report::render_tablegen(&t)?;
    let out = env.target.join("bench/table-generation.md");
    brdf_engine_assets::fsio::replace(&out, section.as_bytes())
        .with_context(|| format!("writing {}", out.display()))?;
    eprintln!("{section}(written to {})", out.display());
    eprintln!(
        "bench smoke test passed in {:.0} s",
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}

fn cargo_bench(
    env: &Env,
    features: &[&str],
    settings: &[String],
    filter: Option<&str>,
) -> Result<()> {
    let mut c = Command::new(&env.cargo);
    c.current_dir(&env.root)
        .args(["bench", "-p", "brdf-bench", "--bench", "kernels"])
        .args(features)
        .arg("--")
        .args(settings)
        .args(filter);
    let st = c.status().context("running cargo bench")?;
    if !st.success() {
        bail!("cargo bench failed ({st})");
    }
    Ok(())
}

/// The kernels to measure ([`report::kernels_to_measure`] of `harness list`).
fn harness_kernels(harness: &Path) -> Result<Vec<(String, usize, String)>> {
    let out = Command::new(harness)
        .arg("list")
        .output()
        .context("running `harness list`")?;
    if !out.status.success() {
        bail!("`harness list` failed ({})", out.status);
    }
    Ok(report::kernels_to_measure(&String::from_utf8_lossy(
        &out.stdout,
    )))
}

fn build_harness(env: &Env) -> Result<PathBuf> {
    let st = Command::new(&env.cargo)
        .current_dir(&env.root)
        .args(["build", "--release", "-p", "brdf-bench", "--bin", "harness"])
        .status()
        .context("building the callgrind harness")?;
    if !st.success() {
        bail!("building the harness failed");
    }
    Ok(env.target.join("release").join("harness"))
}

/// Instructions per call of each harness kernel: (Ir(N) − Ir(0))/N under callgrind.
fn callgrind(env: &Env) -> Counts {
    if Command::new("valgrind").arg("--version").output().is_err() {
        let msg = "valgrind not found (install it with `apt-get install valgrind`)".to_string();
        eprintln!("callgrind skipped: {msg}");
        return Err(msg);
    }
    let h = build_harness(env).map_err(|e| e.to_string())?;
    let tmp = std::env::temp_dir().join(format!("brdf-callgrind-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).map_err(|e| e.to_string())?;
    let ir = |k: &str, n: usize| -> std::result::Result<f64, String> {
        let f = tmp.join(format!("cg.{k}.{n}"));
        let o = Command::new("valgrind")
            .arg("--tool=callgrind")
            .arg(format!("--callgrind-out-file={}", f.display()))
            .arg(&h)
            .args([k, &n.to_string()])
            .output()
            .map_err(|e| e.to_string())?;
        if !o.status.success() {
            return Err(format!("harness {k} failed under valgrind"));
        }
        let text = std::fs::read_to_string(&f).map_err(|e| e.to_string())?;
        report::callgrind_total(&text).ok_or_else(|| "no totals in the callgrind output".into())
    };
    let mut rows = Vec::new();
    for (k, n, what) in harness_kernels(&h).map_err(|e| e.to_string())? {
        let per = (ir(&k, n)? - ir(&k, 0)?) / n as f64;
        rows.push((k, what, per));
    }
    let _ = std::fs::remove_dir_all(&tmp);
    Ok(rows)
}

/// Wall time of `cargo xtask lut` (the running xtask binary) writing the default set to a temporary
/// directory, and the set's size.
fn time_generation() -> Result<(f64, u64, usize)> {
    let exe = std::env::current_exe()?;
    let dir = std::env::temp_dir().join(format!("brdf-bench-gen-{}", std::process::id()));
    let t0 = Instant::now();
    let st = Command::new(exe)
        .args(["lut", "--out"])
        .arg(&dir)
        .stdout(std::process::Stdio::null())
        .status()?;
    let secs = t0.elapsed().as_secs_f64();
    if !st.success() {
        bail!("`cargo xtask lut` failed");
    }
    let mut bytes = 0;
    let mut files = 0;
    for e in std::fs::read_dir(&dir)? {
        bytes += e?.metadata()?.len();
        files += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok((secs, bytes, files))
}

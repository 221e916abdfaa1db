//! `cargo xtask bench`: runs the criterion suite of `crates/brdf-bench` with short settings
//! (libm, then the f32 kernels again with micromath), the SciPy peer, callgrind instruction
//! counts and the LUT generation timing, all in one run, and writes `docs/benchmarks.md`.
//!
//! `cargo xtask bench --smoke` only checks that everything builds and runs once (CI).

mod report;

use anyhow::{bail, Context, Result};
use brdf_bench::{angle_pairs, env_brdf_approx, mu_roughness, read_asset, SIGMA};
use brdf_core::masking::ModifiedG;
use brdf_core::quadrature::{GaussLegendre, NODE_COUNTS};
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use brdf_lut::{DfgTable, GTable, GTable3};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
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

/// Kernels of the callgrind harness and their call counts.
const CALLGRIND: &[(&str, usize, &str)] = &[
    ("g_direct_f32", 500, "modified G, direct, f32, 10 nodes"),
    ("g_direct_f64", 500, "modified G, direct, f64, 10 nodes"),
    ("g_lut3d", 2000, "modified G, 3-D table (θ, φ, σ)"),
    ("g_lut2d", 2000, "modified G, per-σ 2-D table"),
    (
        "g_lut3d_linear",
        2000,
        "modified G, 3-D table, speed tier (trilinear)",
    ),
    (
        "g_lut2d_linear",
        2000,
        "modified G, per-σ 2-D table, speed tier (bilinear)",
    ),
    (
        "smith_beckmann_f32",
        5000,
        "Smith–Beckmann G, height-correlated, f32",
    ),
    ("blinn_f32", 5000, "Blinn G from dot products, f32"),
    ("dfg_lut", 2000, "DFG (A, B) table lookup"),
    ("dfg_karis", 5000, "DFG, Karis's analytic fit"),
    ("dfg_direct_f64", 8, "DFG, split-sum integral, f64"),
];

/// Harness kernels measured when this build's harness has them (`harness list`): the floor
/// and the `_std` twins of the kernel targets. Any other listed kernel is measured too, with
/// [`EXTRA_CALLS`] calls.
const OPTIONAL_CALLGRIND: &[(&str, usize, &str)] = &[
    (
        "floor_bilinear2",
        2000,
        "floor: one bilinear fetch of a two-channel u16 table",
    ),
    (
        "dfg_lut_std",
        2000,
        "DFG (A, B) lookup through the std loader",
    ),
    (
        "g_lut2d_linear_std",
        2000,
        "modified G, per-σ 2-D table, speed tier, through the std loader",
    ),
];
const EXTRA_CALLS: usize = 200;

/// The kernels to measure: [`CALLGRIND`], then those of `harness list` not in it (described
/// by [`OPTIONAL_CALLGRIND`] when named there).
fn harness_kernels(harness: &Path) -> Result<Vec<(String, usize, String)>> {
    let out = Command::new(harness)
        .arg("list")
        .output()
        .context("running `harness list`")?;
    if !out.status.success() {
        bail!("`harness list` failed ({})", out.status);
    }
    let listed = String::from_utf8_lossy(&out.stdout).into_owned();
    let mut ks: Vec<(String, usize, String)> = CALLGRIND
        .iter()
        .map(|(k, n, w)| (k.to_string(), *n, w.to_string()))
        .collect();
    for name in listed.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if ks.iter().any(|k| k.0 == name) {
            continue;
        }
        let (n, what) = OPTIONAL_CALLGRIND
            .iter()
            .find(|o| o.0 == name)
            .map_or((EXTRA_CALLS, "harness entry".to_string()), |o| {
                (o.1, o.2.to_string())
            });
        ks.push((name.to_string(), n, what));
    }
    Ok(ks)
}

pub fn run(a: Args) -> Result<()> {
    let root = crate::fsio::workspace_root();
    let target = match std::env::var_os("CARGO_TARGET_DIR") {
        Some(t) => {
            let t = PathBuf::from(t);
            if t.is_absolute() {
                t
            } else {
                root.join(t)
            }
        }
        None => root.join("target"),
    };
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    if a.smoke {
        return smoke(&root, &cargo, &target);
    }
    if let Some(from) = &a.from {
        let data: Data = serde_json::from_slice(
            &std::fs::read(from).with_context(|| format!("reading {}", from.display()))?,
        )?;
        return write_report(&root, &a, &data);
    }
    let t_start = Instant::now();
    let crit_dir = target.join("criterion");
    if crit_dir.exists() {
        std::fs::remove_dir_all(&crit_dir).context("clearing old criterion results")?;
    }
    let settings = [
        "--warm-up-time".to_string(),
        a.warm_up.to_string(),
        "--measurement-time".into(),
        a.measurement.to_string(),
        "--sample-size".into(),
        a.sample_size.to_string(),
        "--nresamples".into(),
        "20000".into(),
    ];
    eprintln!("== criterion, libm");
    cargo_bench(&root, &cargo, &[], &settings, None)?;
    eprintln!("== criterion, micromath (f32 kernels)");
    cargo_bench(
        &root,
        &cargo,
        &["--features", "micromath"],
        &settings,
        Some(MICROMATH_FILTER),
    )?;
    let est = read_estimates(&crit_dir)?;
    let t_crit = t_start.elapsed().as_secs_f64();

    eprintln!("== SciPy peer");
    let peer = run_peer(&root, brdf_bench::BATCH, 7);
    eprintln!("== accuracy");
    let acc = accuracy();
    eprintln!("== callgrind");
    let cg = callgrind(&root, &cargo, &target);
    let gen = if a.skip_generation {
        None
    } else {
        eprintln!("== generation of the default asset set");
        Some(time_generation()?)
    };
    let python = report::python_bench(&root);
    let data = Data {
        est,
        peer,
        acc,
        cg,
        gen,
        machine: machine(),
        warm_up: a.warm_up,
        measurement: a.measurement,
        sample_size: a.sample_size,
        secs: t_start.elapsed().as_secs_f64(),
        t_crit,
        python,
    };
    let raw = target.join("bench").join("report.json");
    std::fs::create_dir_all(target.join("bench"))?;
    std::fs::write(&raw, serde_json::to_vec_pretty(&data)?)?;
    eprintln!("raw results: {}", raw.display());
    write_report(&root, &a, &data)
}

fn write_report(root: &Path, a: &Args, data: &Data) -> Result<()> {
    let md = report::render(data)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| root.join("docs").join("benchmarks.md"));
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&out, md).with_context(|| format!("writing {}", out.display()))?;
    eprintln!("wrote {}", out.display());
    Ok(())
}

fn smoke(root: &Path, cargo: &str, target: &Path) -> Result<()> {
    let t0 = Instant::now();
    cargo_bench(root, cargo, &[], &["--test".into()], None)?;
    cargo_bench(
        root,
        cargo,
        &["--features", "micromath"],
        &["--test".into()],
        Some(MICROMATH_FILTER),
    )?;
    let h = build_harness(root, cargo, target)?;
    for (k, _, _) in harness_kernels(&h)? {
        let st = Command::new(&h).args([k.as_str(), "3"]).status()?;
        if !st.success() {
            bail!("harness {k} failed");
        }
    }
    match run_peer(root, 2, 1) {
        Peer::Ran { ns_per_g, .. } => eprintln!("SciPy peer ran ({ns_per_g:.0} ns per G)"),
        Peer::Skipped(why) => bail!("SciPy peer did not run: {why}"),
    }
    eprintln!(
        "bench smoke test passed in {:.0} s",
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}

fn cargo_bench(
    root: &Path,
    cargo: &str,
    features: &[&str],
    settings: &[String],
    filter: Option<&str>,
) -> Result<()> {
    let mut c = Command::new(cargo);
    c.current_dir(root)
        .args(["bench", "-p", "brdf-bench", "--bench", "kernels"])
        .args(features)
        .arg("--")
        .args(settings);
    if let Some(f) = filter {
        c.arg(f);
    }
    let st = c.status().context("running cargo bench")?;
    if !st.success() {
        bail!("cargo bench failed ({st})");
    }
    Ok(())
}

/// One criterion result: median time per iteration (ns) with its 95 % interval, and the
/// iteration's elements or bytes.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct Est {
    #[serde(with = "nan")]
    mean: f64,
    #[serde(with = "nan")]
    lo: f64,
    #[serde(with = "nan")]
    hi: f64,
    elements: Option<f64>,
    bytes: Option<f64>,
}

impl Est {
    /// ns per element (per call).
    fn per_call(&self) -> f64 {
        self.mean / self.elements.unwrap_or(1.0)
    }
    fn per_call_ci(&self) -> (f64, f64) {
        let e = self.elements.unwrap_or(1.0);
        (self.lo / e, self.hi / e)
    }
}

fn read_estimates(dir: &Path) -> Result<BTreeMap<String, Est>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).with_context(|| format!("reading {}", d.display()))? {
            let p = e?.path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n == "new") {
                    let bj: serde_json::Value =
                        serde_json::from_slice(&std::fs::read(p.join("benchmark.json"))?)?;
                    let ej: serde_json::Value =
                        serde_json::from_slice(&std::fs::read(p.join("estimates.json"))?)?;
                    let id = bj["full_id"].as_str().unwrap_or_default().to_string();
                    // The median: robust against the load spikes of a shared machine.
                    let m = &ej["median"];
                    out.insert(
                        id,
                        Est {
                            mean: m["point_estimate"].as_f64().unwrap_or(f64::NAN),
                            lo: m["confidence_interval"]["lower_bound"]
                                .as_f64()
                                .unwrap_or(f64::NAN),
                            hi: m["confidence_interval"]["upper_bound"]
                                .as_f64()
                                .unwrap_or(f64::NAN),
                            elements: bj["throughput"]["Elements"].as_f64(),
                            bytes: bj["throughput"]["Bytes"].as_f64(),
                        },
                    );
                } else {
                    stack.push(p);
                }
            }
        }
    }
    if out.is_empty() {
        bail!("no criterion estimates under {}", dir.display());
    }
    Ok(out)
}

#[derive(Serialize, Deserialize)]
enum Peer {
    Ran {
        #[serde(with = "nan")]
        ns_per_g: f64,
        evaluations: u64,
        /// max |G_peer − G_direct(f64, default nodes)| over the peer's points.
        max_diff: f64,
        versions: String,
    },
    Skipped(String),
}

/// SciPy for the peer, installed from PyPI into `.cache/scipy-venv` (pinned: the peer's
/// time depends on its version).
const SCIPY: &str = "scipy==1.16.3";

/// The Python of the virtual environment `venv` (under the workspace) in which `module`
/// imports, creating the environment (`python3 -m venv`) and installing `packages` with pip
/// when it does not. Idempotent: an environment where `module` imports is reused.
pub(crate) fn venv_python(
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
fn scipy_python(root: &Path) -> std::result::Result<PathBuf, String> {
    venv_python(
        root,
        ".cache/scipy-venv",
        "scipy.integrate",
        &[SCIPY.as_ref()],
    )
}

fn run_peer(root: &Path, n: usize, repeat: usize) -> Peer {
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
    let v: serde_json::Value = match serde_json::from_slice(&out.stdout) {
        Ok(v) => v,
        Err(e) => return Peer::Skipped(format!("unreadable peer output ({e})")),
    };
    let g = ModifiedG::<f64>::new(SIGMA).expect("sigma > 0");
    let vals = v["values"].as_array().cloned().unwrap_or_default();
    let max_diff = vals
        .iter()
        .zip(ti.iter().zip(&tr))
        .map(|(p, (&a, &b))| (p.as_f64().unwrap_or(f64::NAN) - g.g(a, b)).abs())
        .fold(0.0, f64::max);
    Peer::Ran {
        ns_per_g: v["ns_per_g"].as_f64().unwrap_or(f64::NAN),
        evaluations: v["evaluations"].as_u64().unwrap_or(0),
        max_diff,
        versions: format!(
            "Python {}, SciPy {}",
            v["python"].as_str().unwrap_or("?"),
            v["scipy"].as_str().unwrap_or("?")
        ),
    }
}

/// Accuracy on the benchmark's own domain, so that "matched accuracy" is measured, not
/// assumed.
#[derive(Serialize, Deserialize)]
struct Accuracy {
    /// (node count, max |G_N − G_32| in f64, in f32).
    g_direct: Vec<(usize, f64, f64)>,
    g_lut3: Option<f64>,
    g_lut2: Option<f64>,
    g_lut3_linear: Option<f64>,
    g_lut2_linear: Option<f64>,
    /// max |ΔA|, |ΔB| against the split-sum integral (f64).
    dfg_lut: Option<(f64, f64)>,
    /// The same for the speed tier (bilinear) table.
    dfg_lut_linear: Option<(f64, f64)>,
    dfg_karis: (f64, f64),
    g_points: usize,
    dfg_points: usize,
}

fn accuracy() -> Accuracy {
    let n = 4000;
    let (ti, tr) = angle_pairs::<f64>(n);
    let reference = ModifiedG::<f64, GaussLegendre<32>>::new(SIGMA).expect("sigma > 0");
    let gref: Vec<f64> = ti
        .iter()
        .zip(&tr)
        .map(|(&a, &b)| reference.g(a, b))
        .collect();
    let max_err = |f: &dyn Fn(f64, f64) -> f64| {
        ti.iter()
            .zip(&tr)
            .zip(&gref)
            .map(|((&a, &b), &r)| (f(a, b) - r).abs())
            .fold(0.0, f64::max)
    };
    let mut g_direct = Vec::new();
    macro_rules! at {
        ($($n:literal),*) => {$({
            let g64 = ModifiedG::<f64, GaussLegendre<$n>>::new(SIGMA).unwrap();
            let g32 = ModifiedG::<f32, GaussLegendre<$n>>::new(SIGMA as f32).unwrap();
            g_direct.push((
                $n,
                max_err(&|a, b| g64.g(a, b)),
                max_err(&|a, b| g32.g(a as f32, b as f32) as f64),
            ));
        })*};
    }
    at!(4, 6, 8, 10, 12, 16, 20, 24, 32);
    debug_assert_eq!(g_direct.len(), NODE_COUNTS.len());
    let err3 = |asset: &str| {
        read_asset(asset).and_then(|b| {
            let t = GTable3::parse(&b).ok()?;
            Some(max_err(&|a, c| {
                t.g(a as f32, c as f32, SIGMA as f32) as f64
            }))
        })
    };
    let err2 = |asset: &str| {
        read_asset(asset).and_then(|b| {
            let t = GTable::parse(&b).ok()?;
            Some(max_err(&|a, c| t.g(a as f32, c as f32) as f64))
        })
    };
    let (g_lut3, g_lut3_linear) = (
        err3(brdf_bench::G3_ASSET),
        err3(brdf_bench::G3_LINEAR_ASSET),
    );
    let (g_lut2, g_lut2_linear) = (
        err2(brdf_bench::G2_ASSET),
        err2(brdf_bench::G2_LINEAR_ASSET),
    );
    let pts = mu_roughness(96);
    let exact: Vec<(f64, f64)> = pts
        .iter()
        .map(|&(m, r)| dfg_ggx::<f64, OuterRule, InnerRule>(m, r))
        .collect();
    let dfg_err = |f: &dyn Fn(f64, f64) -> (f64, f64)| {
        pts.iter()
            .zip(&exact)
            .fold((0.0f64, 0.0f64), |acc, (&(m, r), &(ea, eb))| {
                let (a, b) = f(m, r);
                (acc.0.max((a - ea).abs()), acc.1.max((b - eb).abs()))
            })
    };
    let dfg_table = |asset: &str| {
        read_asset(asset).and_then(|b| {
            let t = DfgTable::parse(&b).ok()?;
            Some(dfg_err(&|m, r| {
                let (a, b) = t.ab(m as f32, r as f32);
                (a as f64, b as f64)
            }))
        })
    };
    let dfg_lut = dfg_table(brdf_bench::DFG_ASSET);
    let dfg_lut_linear = dfg_table(brdf_bench::DFG_LINEAR_ASSET);
    let dfg_karis = dfg_err(&|m, r| {
        let (a, b) = env_brdf_approx(m as f32, r as f32);
        (a as f64, b as f64)
    });
    Accuracy {
        g_direct,
        g_lut3,
        g_lut2,
        g_lut3_linear,
        g_lut2_linear,
        dfg_lut,
        dfg_lut_linear,
        dfg_karis,
        g_points: n,
        dfg_points: pts.len(),
    }
}

fn build_harness(root: &Path, cargo: &str, target: &Path) -> Result<PathBuf> {
    let st = Command::new(cargo)
        .current_dir(root)
        .args(["build", "--release", "-p", "brdf-bench", "--bin", "harness"])
        .status()
        .context("building the callgrind harness")?;
    if !st.success() {
        bail!("building the harness failed");
    }
    Ok(target.join("release").join("harness"))
}

/// (kernel, description, instructions per call) or why callgrind was skipped.
type Counts = std::result::Result<Vec<(String, String, f64)>, String>;

fn callgrind(root: &Path, cargo: &str, target: &Path) -> Counts {
    if Command::new("valgrind").arg("--version").output().is_err() {
        let msg = "valgrind not found (install it with `apt-get install valgrind`)".to_string();
        eprintln!("callgrind skipped: {msg}");
        return Err(msg);
    }
    let h = build_harness(root, cargo, target).map_err(|e| e.to_string())?;
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
        text.lines()
            .find_map(|l| {
                l.strip_prefix("summary:")
                    .or_else(|| l.strip_prefix("totals:"))
            })
            .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
            .ok_or_else(|| "no totals in the callgrind output".to_string())
    };
    let mut rows = Vec::new();
    for (k, n, what) in harness_kernels(&h).map_err(|e| e.to_string())? {
        let per = (ir(&k, n)? - ir(&k, 0)?) / n as f64;
        rows.push((k, what, per));
    }
    let _ = std::fs::remove_dir_all(&tmp);
    Ok(rows)
}

/// Wall time of `cargo xtask lut` (this binary) writing the default set to a temporary
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

#[derive(Serialize, Deserialize)]
struct Machine {
    cpu: String,
    cores: usize,
    rustc: String,
    os: String,
}

fn machine() -> Machine {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let cpu = cpuinfo
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name")?
                .split_once(':')
                .map(|x| x.1.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    let mhz = cpuinfo.lines().find_map(|l| {
        l.strip_prefix("cpu MHz")?
            .split_once(':')
            .map(|x| x.1.trim().to_string())
    });
    let cmd = |c: &str, a: &[&str]| {
        Command::new(c)
            .args(a)
            .output()
            .ok()
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
            .unwrap_or_else(|| "unknown".into())
    };
    Machine {
        cpu: match mhz {
            Some(m) => format!("{cpu} ({m} MHz)"),
            None => cpu,
        },
        cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
        rustc: cmd("rustc", &["--version"]),
        os: cmd("uname", &["-srm"]),
    }
}

/// Everything one run measured: what the report is rendered from, saved as JSON.
#[derive(Serialize, Deserialize)]
struct Data {
    est: BTreeMap<String, Est>,
    peer: Peer,
    acc: Accuracy,
    cg: Counts,
    gen: Option<(f64, u64, usize)>,
    machine: Machine,
    warm_up: f64,
    measurement: f64,
    sample_size: usize,
    secs: f64,
    t_crit: f64,
    python: std::result::Result<serde_json::Value, String>,
}

/// f64 fields that may be NaN (no figure): JSON `null` both ways.
mod nan {
    use serde::{Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        if x.is_finite() {
            s.serialize_f64(*x)
        } else {
            s.serialize_none()
        }
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

fn fmt_ns(x: f64) -> String {
    if !x.is_finite() {
        "–".into()
    } else if x >= 1e6 {
        format!("{:.2} ms", x / 1e6)
    } else if x >= 1e4 {
        format!("{:.1} µs", x / 1e3)
    } else if x >= 100.0 {
        format!("{x:.0} ns")
    } else {
        format!("{x:.1} ns")
    }
}

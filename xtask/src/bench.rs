//! `cargo xtask bench`: runs the criterion suite of `crates/brdf-bench` with short settings
//! (libm, then the f32 kernels again with micromath), the SciPy peer, callgrind instruction
//! counts and the LUT generation timing, all in one run, and writes `docs/benchmarks.md`.
//!
//! `cargo xtask bench --smoke` only checks that everything builds and runs once (CI).

use anyhow::{bail, Context, Result};
use brdf_bench::{angle_pairs, env_brdf_approx, mu_roughness, read_asset, SIGMA};
use brdf_core::masking::ModifiedG;
use brdf_core::quadrature::{GaussLegendre, DEFAULT_NODES, NODE_COUNTS};
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use brdf_lut::{DfgTable, GTable, GTable3};
use std::collections::BTreeMap;
use std::fmt::Write as _;
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

pub fn run(a: Args) -> Result<()> {
    let root = super::lut::workspace_root();
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
    let machine = machine();
    let md = report(&Report {
        est: &est,
        peer: &peer,
        acc: &acc,
        cg: &cg,
        gen,
        machine: &machine,
        args: &a,
        secs: t_start.elapsed().as_secs_f64(),
        t_crit,
    });
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| root.join("docs").join("benchmarks.md"));
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&out, md).with_context(|| format!("writing {}", out.display()))?;
    eprintln!(
        "wrote {} ({:.0} s in all)",
        out.display(),
        t_start.elapsed().as_secs_f64()
    );
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
    for (k, _, _) in CALLGRIND {
        let st = Command::new(&h).args([k, "3"]).status()?;
        if !st.success() {
            bail!("harness {k} failed");
        }
    }
    match run_peer(root, 2, 1) {
        Peer::Ran { ns_per_g, .. } => eprintln!("SciPy peer ran ({ns_per_g:.0} ns per G)"),
        Peer::Skipped(why) => eprintln!("SciPy peer skipped: {why}"),
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
#[derive(Clone, Debug)]
struct Est {
    mean: f64,
    lo: f64,
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

enum Peer {
    Ran {
        ns_per_g: f64,
        evaluations: u64,
        /// max |G_peer − G_direct(f64, default nodes)| over the peer's points.
        max_diff: f64,
        versions: String,
    },
    Skipped(String),
}

fn run_peer(root: &Path, n: usize, repeat: usize) -> Peer {
    let script = root.join("crates/brdf-bench/peer/g_peer.py");
    let (ti, tr) = angle_pairs::<f64>(n);
    let pairs: Vec<String> = ti
        .iter()
        .zip(&tr)
        .map(|(a, b)| format!("{a:.17},{b:.17}"))
        .collect();
    let out = Command::new("python3")
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
struct Accuracy {
    /// (node count, max |G_N − G_32| in f64, in f32).
    g_direct: Vec<(usize, f64, f64)>,
    g_lut3: Option<f64>,
    g_lut2: Option<f64>,
    g_lut3_linear: Option<f64>,
    g_lut2_linear: Option<f64>,
    /// max |ΔA|, |ΔB| against the split-sum integral (f64).
    dfg_lut: Option<(f64, f64)>,
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
    let dfg_lut = read_asset(brdf_bench::DFG_ASSET).and_then(|b| {
        let t = DfgTable::parse(&b).ok()?;
        Some(dfg_err(&|m, r| {
            let (a, b) = t.ab(m as f32, r as f32);
            (a as f64, b as f64)
        }))
    });
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
    for &(k, n, what) in CALLGRIND {
        let per = (ir(k, n)? - ir(k, 0)?) / n as f64;
        rows.push((k.to_string(), what.to_string(), per));
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

struct Report<'a> {
    est: &'a BTreeMap<String, Est>,
    peer: &'a Peer,
    acc: &'a Accuracy,
    cg: &'a Counts,
    gen: Option<(f64, u64, usize)>,
    machine: &'a Machine,
    args: &'a Args,
    secs: f64,
    t_crit: f64,
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

fn report(r: &Report<'_>) -> String {
    let e = r.est;
    let per = |id: &str| e.get(id).map(|x| x.per_call());
    let mut s = String::new();
    let w = &mut s;
    let m = r.machine;
    let dn = DEFAULT_NODES;
    let _ = writeln!(w, "# Benchmarks\n");
    let _ = writeln!(
        w,
        "Generated by `cargo xtask bench` (do not edit by hand). Every number below comes from \
         one run: criterion for times, valgrind's callgrind for instruction counts, the SciPy \
         script `crates/brdf-bench/peer/g_peer.py` for the peer. Times are wall-clock medians \
         on one core; the machine is shared, so read them with their 95 % intervals, and prefer \
         the instruction counts for comparisons across runs.\n"
    );
    let _ = writeln!(w, "## Machine\n");
    let _ = writeln!(w, "| | |\n|---|---|");
    let _ = writeln!(w, "| CPU | {} |", m.cpu);
    let _ = writeln!(w, "| logical cores | {} (benchmarks run on one) |", m.cores);
    let _ = writeln!(w, "| OS | {} |", m.os);
    let _ = writeln!(
        w,
        "| compiler | {} (release profile, `opt-level = 3`) |",
        m.rustc
    );
    let _ = writeln!(
        w,
        "| criterion settings | warm-up {} s, measurement {} s, {} samples per benchmark |",
        r.args.warm_up, r.args.measurement, r.args.sample_size
    );
    let _ = writeln!(
        w,
        "| run time | {:.0} s in all, of which {:.0} s criterion (both builds included) |\n",
        r.secs, r.t_crit
    );

    // ---- Targets
    let direct32 = per(&format!("g_direct_f32_libm/n{dn:02}"));
    let direct64 = per(&format!("g_direct_f64/n{dn:02}"));
    let lut3 = per("g_lut/table3d");
    let lut2 = per("g_lut/table2d_sigma0.3");
    let lut3f = per("g_lut/table3d_linear");
    let lut2f = per("g_lut/table2d_sigma0.3_linear");
    let dfg_lut = per("dfg/lut_f32");
    let dfg_direct = per("dfg_direct/split_sum_f64");
    let dfg_alb = per("dfg_direct/directional_albedo_f64");
    let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => Some(a / b),
        _ => None,
    };
    let verdict = |x: Option<f64>, t: f64| match x {
        Some(x) if x >= t => format!("{x:.1}× — **met**"),
        Some(x) => format!("{x:.2}× — **missed**"),
        None => "not measured".into(),
    };
    let peer_ns = match r.peer {
        Peer::Ran { ns_per_g, .. } => Some(*ns_per_g),
        Peer::Skipped(_) => None,
    };
    let _ = writeln!(w, "## Targets (ratios from this run)\n");
    let _ = writeln!(w, "| target | measured | needed |\n|---|---|---|");
    let _ = writeln!(
        w,
        "| 3-D G table lookup vs direct G (f32, {dn} nodes), speed tier `{}` (trilinear) | {} | ≥ 10× |",
        brdf_bench::G3_LINEAR_ASSET,
        verdict(ratio(direct32, lut3f), 10.0)
    );
    let _ = writeln!(
        w,
        "| per-σ 2-D G table lookup vs direct G (f32, {dn} nodes), speed tier `{}` (bilinear) | {} | ≥ 30× |",
        brdf_bench::G2_LINEAR_ASSET,
        verdict(ratio(direct32, lut2f), 30.0)
    );
    let _ = writeln!(
        w,
        "| *same, accuracy tier `{}` (tricubic)* | {} | ≥ 10× |",
        brdf_bench::G3_ASSET,
        verdict(ratio(direct32, lut3), 10.0)
    );
    let _ = writeln!(
        w,
        "| *same, accuracy tier `{}` (bicubic)* | {} | ≥ 30× |",
        brdf_bench::G2_ASSET,
        verdict(ratio(direct32, lut2), 30.0)
    );
    let _ = writeln!(
        w,
        "| direct G (f64, {dn} nodes) vs the SciPy peer | {} | ≥ 1000× |",
        match peer_ns {
            Some(_) => verdict(ratio(peer_ns, direct64), 1000.0),
            None => "peer skipped (SciPy not importable)".into(),
        }
    );
    let _ = writeln!(
        w,
        "| DFG table lookup vs the direct split-sum integral (f64, as generated) | {} | ≥ 50× |",
        verdict(ratio(dfg_direct, dfg_lut), 50.0)
    );
    let _ = writeln!(
        w,
        "| DFG table lookup vs the directional-albedo integral of the GGX model (f64) | {} | ≥ 50× |\n",
        verdict(ratio(dfg_alb, dfg_lut), 50.0)
    );
    let _ = writeln!(
        w,
        "First measured time per G evaluation, direct, {dn} nodes, σ = {SIGMA}: \
         **f32 {}**, **f64 {}** (median time per iteration over {} in-plane pairs spread over θi ∈ [0, 89°], \
         θr ∈ [−89°, 89°]).\n",
        direct32.map_or("–".into(), fmt_ns),
        direct64.map_or("–".into(), fmt_ns),
        brdf_bench::BATCH
    );

    // ---- Matched accuracy
    let a = r.acc;
    let _ = writeln!(
        w,
        "## G: direct quadrature against the tables at matched accuracy\n"
    );
    let _ = writeln!(
        w,
        "Error = max |G − G₃₂| over {} pairs (σ = {SIGMA}), G₃₂ the 32-node f64 quadrature \
         (it agrees with the SciPy peer to the peer's tolerance, see below). ns per call from \
         criterion; the f32 rows use libm, the micromath column the same f32 code with \
         micromath.\n",
        a.g_points
    );
    let _ = writeln!(
        w,
        "| nodes | error f64 | error f32 (libm) | ns/call f64 | ns/call f32 libm | ns/call f32 micromath |\n|---|---|---|---|---|---|"
    );
    for &(n, e64, e32) in &a.g_direct {
        let c = |id: String| per(&id).map_or("–".into(), fmt_ns);
        let _ = writeln!(
            w,
            "| {n}{} | {e64:.1e} | {e32:.1e} | {} | {} | {} |",
            if n == dn { " (default)" } else { "" },
            c(format!("g_direct_f64/n{n:02}")),
            c(format!("g_direct_f32_libm/n{n:02}")),
            c(format!("g_direct_f32_micromath/n{n:02}")),
        );
    }
    let _ = writeln!(w);
    let matched = |err: Option<f64>| -> Option<usize> {
        let err = err?;
        a.g_direct.iter().find(|x| x.2 <= err).map(|x| x.0)
    };
    let _ = writeln!(w, "| table | error (f32 lookup) | ns/call | direct G of no larger error (f32) | its ns/call | speed-up at matched accuracy | speed-up vs {dn} nodes |\n|---|---|---|---|---|---|---|");
    for (name, err, t) in [
        ("3-D (θ, φ, σ) tricubic, `g_modified.blut`", a.g_lut3, lut3),
        (
            "per-σ 2-D bicubic, `g_modified_sigma0.3.blut`",
            a.g_lut2,
            lut2,
        ),
        (
            "3-D trilinear, `g_modified_linear.blut`",
            a.g_lut3_linear,
            lut3f,
        ),
        (
            "per-σ 2-D bilinear, `g_modified_sigma0.3_linear.blut`",
            a.g_lut2_linear,
            lut2f,
        ),
    ] {
        let mn = matched(err);
        let tm = mn.and_then(|n| per(&format!("g_direct_f32_libm/n{n:02}")));
        let _ = writeln!(
            w,
            "| {name} | {} | {} | {} | {} | {} | {} |",
            err.map_or("–".into(), |x| format!("{x:.1e}")),
            t.map_or("–".into(), fmt_ns),
            mn.map_or("–".into(), |n| format!("{n} nodes")),
            tm.map_or("–".into(), fmt_ns),
            ratio(tm, t).map_or("–".into(), |x| format!("{x:.2}×")),
            ratio(direct32, t).map_or("–".into(), |x| format!("{x:.2}×")),
        );
    }
    let _ = writeln!(w);

    // ---- Limits
    if let Ok(rows) = r.cg {
        let ir = |k: &str| rows.iter().find(|x| x.0 == k).map(|x| x.2);
        if let (Some(d), Some(l3), Some(l2), Some(f3), Some(f2)) = (
            ir("g_direct_f32"),
            ir("g_lut3d"),
            ir("g_lut2d"),
            ir("g_lut3d_linear"),
            ir("g_lut2d_linear"),
        ) {
            let _ = writeln!(
                w,
                "### What limits the G-table ratios (callgrind, instructions per G)\n"
            );
            let _ = writeln!(
                w,
                "* Direct G, f32, {dn} nodes: **{d:.0}** (two passing factors, each two {dn}-node \
                 integrals: 40 `exp` and 40 `sqrt` per G).\n\
                 * A table G is two passing-factor lookups, F(|θr|, ±θi) for GM and F(θi, θr) for \
                 GS, each with the √cos θ axis warp (a short polynomial cosine and a `sqrtf`). \
                 `GTable`/`GTable3` read one-channel u16 tables with the layout fixed when they \
                 are parsed (`crates/brdf-core/src/lut/passing.rs`: taps per axis known, end \
                 extrapolation folded into the weights, one bounds check per row, the (θ, φ) \
                 cell shared by every σ plane).\n\
                 * Accuracy tier (Catmull–Rom, 4 taps per axis): **{l3:.0}** (3-D, 2 × 64 taps) \
                 and **{l2:.0}** (2-D, 2 × 16 taps).\n\
                 * Speed tier (linear, 2 taps per axis, on denser grids of the same size budget): \
                 **{f3:.0}** (3-D, 2 × 8 taps plus `logf` for the σ axis) and **{f2:.0}** (2-D, \
                 2 × 4 taps), i.e. {:.1}× and {:.1}× fewer instructions than direct G.\n\
                 * What is left in the 2-D speed tier is fixed cost, not taps: per G two warped \
                 and two linear axis maps (clamp, scale, float→int, fraction: ~35 instructions \
                 each with the cosine), four bounds-checked u16 pairs, the argument folding of \
                 conventions.md §4 and the final clamps. Reaching 30× would need under \
                 {:.0} instructions per G, i.e. a G that skips the angle warp (inputs already \
                 as table coordinates) and reads one fetch for GM and GS; the ratios above are \
                 what this layout reaches, measured, not a bound.\n",
                d / f3,
                d / f2,
                d / 30.0
            );
        }
    }

    // ---- Closed forms
    let _ = writeln!(w, "## G: closed forms (shader inputs: dot products)\n");
    let _ = writeln!(
        w,
        "| kernel | f32 libm | f32 micromath | f64 |\n|---|---|---|---|"
    );
    for k in [
        "smith_beckmann_correlated",
        "smith_beckmann_separable",
        "blinn_dots",
        &format!("modified_dots_n{dn}"),
    ] {
        let c = |g: &str| per(&format!("{g}/{k}")).map_or("–".into(), fmt_ns);
        let _ = writeln!(
            w,
            "| {k} | {} | {} | {} |",
            c("g_closed_f32_libm"),
            c("g_closed_f32_micromath"),
            c("g_closed_f64")
        );
    }
    let _ = writeln!(w);

    // ---- Peer
    let _ = writeln!(w, "## The SciPy peer\n");
    match r.peer {
        Peer::Ran {
            ns_per_g,
            evaluations,
            max_diff,
            versions,
        } => {
            let _ = writeln!(
                w,
                "`peer/g_peer.py` evaluates the same G (conventions.md §§2–4) with \
                 `scipy.integrate.quad` at default tolerances ({versions}): **{}** per G (median over \
                 7 sweeps of the direct benchmark's {} pairs, {evaluations} evaluations); max |G_peer − G_direct(f64, {dn} nodes)| = {max_diff:.1e}. \
                 Direct f64 is {} faster.\n",
                fmt_ns(*ns_per_g),
                brdf_bench::BATCH,
                ratio(peer_ns, direct64).map_or("–".into(), |x| format!("{x:.0}×"))
            );
        }
        Peer::Skipped(why) => {
            let _ = writeln!(
                w,
                "Skipped in this run: {why}. Install with `pip install scipy`.\n"
            );
        }
    }

    // ---- DFG
    let _ = writeln!(w, "## DFG (split-sum A, B for GGX)\n");
    let _ = writeln!(
        w,
        "Errors: max |ΔA|, |ΔB| against the f64 split-sum integral over {} (μ, r) points, \
         μ ∈ [cos 89°, 1], r ∈ [0, 1].\n",
        a.dfg_points
    );
    let _ = writeln!(
        w,
        "| method | ns/call | max |ΔA| | max |ΔB| |\n|---|---|---|---|"
    );
    let fe = |x: Option<(f64, f64)>| {
        x.map_or(("–".into(), "–".into()), |(p, q)| {
            (format!("{p:.1e}"), format!("{q:.1e}"))
        })
    };
    let (la, lb) = fe(a.dfg_lut);
    let (ka, kb) = fe(Some(a.dfg_karis));
    let _ = writeln!(
        w,
        "| table lookup (`dfg_ggx.blut`, f32) | {} | {la} | {lb} |",
        dfg_lut.map_or("–".into(), fmt_ns)
    );
    let _ = writeln!(
        w,
        "| Karis's analytic fit (f32) | {} | {ka} | {kb} |",
        per("dfg/karis_approx_f32").map_or("–".into(), fmt_ns)
    );
    let _ = writeln!(
        w,
        "| split-sum integral, f64 (the generator's) | {} | 0 (reference) | 0 (reference) |",
        dfg_direct.map_or("–".into(), fmt_ns)
    );
    let _ = writeln!(
        w,
        "| split-sum integral, f32 | {} | | |",
        per("dfg_direct/split_sum_f32").map_or("–".into(), fmt_ns)
    );
    let _ = writeln!(
        w,
        "| directional albedo of the GGX model (F = 1, A + B), f64 | {} | | |\n",
        dfg_alb.map_or("–".into(), fmt_ns)
    );

    // ---- Models
    let _ = writeln!(w, "## BRDF models (f32 libm, ns per call)\n");
    let _ = writeln!(w, "| model | eval | sample |\n|---|---|---|");
    let mut names: Vec<&str> = e
        .keys()
        .filter_map(|k| k.strip_prefix("model_eval_f32_libm/"))
        .collect();
    names.sort();
    for n in names {
        let _ = writeln!(
            w,
            "| {n} | {} | {} |",
            per(&format!("model_eval_f32_libm/{n}")).map_or("–".into(), fmt_ns),
            per(&format!("model_sample_f32_libm/{n}")).map_or("–".into(), fmt_ns)
        );
    }
    let _ = writeln!(w);

    // ---- Batch
    let _ = writeln!(
        w,
        "## Batch entry points (`brdf_core::batch`, {} elements per call, one core)\n",
        brdf_bench::BATCH_LEN
    );
    let _ = writeln!(
        w,
        "Each entry point equals its scalar kernel bit for bit (`tests/tests/batch.rs`). The \
         Smith–GGX G and V entry points are written in chunks (radicands, packed square root, \
         branch-free selects) and compile to packed SSE instructions; the others call scalar \
         `exp`/`erf` or the quadrature and run at the scalar rate. Throughput is per core \
         (one thread).\n"
    );
    let _ = writeln!(w, "| entry point | f32 libm: ns/element, M elements/s | f32 micromath | f64 |\n|---|---|---|---|");
    let mut bnames: Vec<&str> = e
        .keys()
        .filter_map(|k| k.strip_prefix("batch_f64/"))
        .collect();
    bnames.sort();
    for n in bnames {
        let c = |g: &str| {
            per(&format!("{g}/{n}"))
                .map_or("–".into(), |x| format!("{} — {:.1}", fmt_ns(x), 1e3 / x))
        };
        let _ = writeln!(
            w,
            "| {n} | {} | {} | {} |",
            c("batch_f32_libm"),
            c("batch_f32_micromath"),
            c("batch_f64")
        );
    }
    let _ = writeln!(w);

    // ---- Parse
    let _ = writeln!(w, "## LUT parse and validate (header, limits, CRC-32)\n");
    let _ = writeln!(w, "| file | size | no_std view | per MiB | std loader (copy + view) | per MiB |\n|---|---|---|---|---|---|");
    let mut files: Vec<&str> = e
        .keys()
        .filter_map(|k| k.strip_prefix("lut_parse/view/"))
        .collect();
    files.sort();
    for f in files {
        let v = &e[&format!("lut_parse/view/{f}")];
        let sl = e.get(&format!("lut_parse/std_loader/{f}"));
        let bytes = v.bytes.unwrap_or(f64::NAN);
        let mib = |x: &Est| fmt_ns(x.mean / bytes * 1_048_576.0);
        let _ = writeln!(
            w,
            "| `{f}` | {:.1} KiB | {} | {} | {} | {} |",
            bytes / 1024.0,
            fmt_ns(v.mean),
            mib(v),
            sl.map_or("–".into(), |x| fmt_ns(x.mean)),
            sl.map_or("–".into(), mib)
        );
    }
    let _ = writeln!(w);
    match r.gen {
        Some((secs, bytes, files)) => {
            let _ = writeln!(
                w,
                "Generation of the default asset set (`cargo xtask lut`, {files} files, \
                 {:.0} KiB, on all {} cores, with its built-in verification): **{secs:.1} s** wall time.\n",
                bytes as f64 / 1024.0,
                m.cores
            );
        }
        None => {
            let _ = writeln!(
                w,
                "Generation of the default asset set: not timed in this run.\n"
            );
        }
    }

    // ---- Callgrind
    let _ = writeln!(w, "## Instructions per call (callgrind)\n");
    match r.cg {
        Ok(rows) => {
            let _ = writeln!(
                w,
                "`crates/brdf-bench/src/bin/harness.rs` calls one kernel N times; \
                 instructions per call = (Ir(N) − Ir(0))/N, so start-up, input set-up and \
                 table parsing cancel.\n"
            );
            let _ = writeln!(w, "| kernel | what | instructions/call |\n|---|---|---|");
            for (k, what, per) in rows {
                let _ = writeln!(w, "| `{k}` | {what} | {per:.0} |");
            }
        }
        Err(why) => {
            let _ = writeln!(w, "Skipped in this run: {why}.");
        }
    }
    let _ = writeln!(w);

    // ---- All raw
    let _ = writeln!(w, "## All criterion results\n");
    let _ = writeln!(
        w,
        "| benchmark | per call (median) | 95 % interval |\n|---|---|---|"
    );
    for (id, x) in e {
        let (lo, hi) = x.per_call_ci();
        let (mean, lo, hi) = if x.bytes.is_some() {
            (x.mean, x.lo, x.hi)
        } else {
            (x.per_call(), lo, hi)
        };
        let _ = writeln!(
            w,
            "| `{id}` | {} | {} – {} |",
            fmt_ns(mean),
            fmt_ns(lo),
            fmt_ns(hi)
        );
    }
    s
}

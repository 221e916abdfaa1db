//! The data of one benchmark run and its report, `docs/benchmarks.md`.
//!
//! [`Data`] is everything a run measured (criterion medians, callgrind counts, the peers,
//! accuracy on the benchmark's own inputs, table-generation times); it round-trips through
//! JSON (`cargo xtask bench` saves it, `--from FILE` re-renders from it). [`render`] fills
//! the Markdown template `templates/benchmarks.md` (minijinja, the template engine of the
//! shader snippets in `brdf-engine-assets`).

mod accuracy;
mod harness;
mod render;
pub mod tablegen;
mod targets;

pub use accuracy::{accuracy, Accuracy};
pub use harness::{
    callgrind_total, kernels_to_measure, CALLGRIND, EXTRA_CALLS, OPTIONAL_CALLGRIND,
};
pub use render::{fill, render, render_tablegen};

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// One criterion result: median time per iteration (ns) with its 95 % interval, and the
/// iteration's elements or bytes.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Est {
    /// Median time per iteration, ns (NaN when criterion gave none).
    #[serde(with = "nan")]
    pub mean: f64,
    /// Lower end of the 95 % interval, ns.
    #[serde(with = "nan")]
    pub lo: f64,
    /// Upper end of the 95 % interval, ns.
    #[serde(with = "nan")]
    pub hi: f64,
    /// Elements per iteration (throughput), if declared.
    pub elements: Option<f64>,
    /// Bytes per iteration (throughput), if declared.
    pub bytes: Option<f64>,
}

impl Est {
    /// ns per element (per call): median / elements.
    pub fn per_call(&self) -> f64 {
        self.mean / self.elements.unwrap_or(1.0)
    }
    /// The 95 % interval per element.
    pub fn per_call_ci(&self) -> (f64, f64) {
        let e = self.elements.unwrap_or(1.0);
        (self.lo / e, self.hi / e)
    }
}

/// The SciPy peer's result (`peer/g_peer.py`), or why it did not run.
#[derive(Serialize, Deserialize)]
pub enum Peer {
    /// It ran.
    Ran {
        /// Time per G, ns.
        #[serde(with = "nan")]
        ns_per_g: f64,
        /// Integrand evaluations of `quad`.
        evaluations: u64,
        /// max |G_peer − G_direct(f64, default nodes)| over the peer's points.
        max_diff: f64,
        /// "Python x, SciPy y".
        versions: String,
    },
    /// It did not run; why.
    Skipped(String),
}

impl Peer {
    /// The peer's result from its JSON output (`ns_per_g`, `evaluations`, `values`,
    /// `python`, `scipy`) for the first `n` pairs of [`crate::angle_pairs`]: max_diff is
    /// max |G_peer − G_direct(f64, default nodes)| at σ = [`crate::SIGMA`].
    pub fn from_json(v: &serde_json::Value, n: usize) -> Peer {
        let (ti, tr) = crate::angle_pairs::<f64>(n);
        let g = brdf_core::masking::ModifiedG::<f64>::new(crate::SIGMA).expect("sigma > 0");
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
}

/// The machine a run measured on.
#[derive(Serialize, Deserialize)]
pub struct Machine {
    /// CPU model and clock.
    pub cpu: String,
    /// Logical cores.
    pub cores: usize,
    /// `rustc --version`.
    pub rustc: String,
    /// `uname -srm`.
    pub os: String,
}

/// (kernel, description, instructions per call) or why callgrind was skipped.
pub type Counts = Result<Vec<(String, String, f64)>, String>;

/// Everything one run measured: what the report is rendered from.
#[derive(Serialize, Deserialize)]
pub struct Data {
    /// Criterion results by full id.
    pub est: BTreeMap<String, Est>,
    /// The SciPy peer.
    pub peer: Peer,
    /// Accuracy on the benchmark's domain.
    pub acc: Accuracy,
    /// Callgrind instruction counts.
    pub cg: Counts,
    /// Default set generation: (seconds, bytes, files).
    pub gen: Option<(f64, u64, usize)>,
    /// Where it ran.
    pub machine: Machine,
    /// Criterion warm-up, s.
    pub warm_up: f64,
    /// Criterion measurement time, s.
    pub measurement: f64,
    /// Criterion samples.
    pub sample_size: usize,
    /// Wall time of the whole run, s.
    pub secs: f64,
    /// Wall time of the criterion part, s.
    pub t_crit: f64,
    /// `crates/brdf-py/bench/bench.py --json`'s figures, or why it did not run.
    pub python: Result<serde_json::Value, String>,
    /// Table generation beside the Monte Carlo peer (absent in runs saved before it).
    #[serde(default)]
    pub tablegen: Option<tablegen::TableGen>,
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

/// A time in ns as text: "1.23 ms", "45.6 µs", "789 ns", "12.3 ns", or "–" when not finite.
pub fn fmt_ns(x: f64) -> String {
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

/// One criterion result from its `new/benchmark.json` and `new/estimates.json`: the median
/// (robust against the load spikes of a shared machine) and its interval.
fn estimate(bj: &serde_json::Value, ej: &serde_json::Value) -> Est {
    let m = &ej["median"];
    let f = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
    Est {
        mean: f(&m["point_estimate"]),
        lo: f(&m["confidence_interval"]["lower_bound"]),
        hi: f(&m["confidence_interval"]["upper_bound"]),
        elements: bj["throughput"]["Elements"].as_f64(),
        bytes: bj["throughput"]["Bytes"].as_f64(),
    }
}

/// Every criterion result under `dir` (criterion's output folder), by full id.
pub fn read_estimates(dir: &Path) -> Result<BTreeMap<String, Est>, String> {
    let read = |p: &Path| -> Result<serde_json::Value, String> {
        let b = std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()))?;
        serde_json::from_slice(&b).map_err(|e| format!("{}: {e}", p.display()))
    };
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries = std::fs::read_dir(&d).map_err(|e| format!("{}: {e}", d.display()))?;
        for e in entries {
            let p = e.map_err(|e| e.to_string())?.path();
            if !p.is_dir() {
                continue;
            }
            if p.file_name().is_some_and(|n| n == "new") {
                let bj = read(&p.join("benchmark.json"))?;
                let ej = read(&p.join("estimates.json"))?;
                let id = bj["full_id"].as_str().unwrap_or_default().to_string();
                out.insert(id, estimate(&bj, &ej));
            } else {
                stack.push(p);
            }
        }
    }
    if out.is_empty() {
        return Err(format!("no criterion estimates under {}", dir.display()));
    }
    Ok(out)
}

impl Machine {
    /// This machine: CPU model and clock from `/proc/cpuinfo`, cores, `rustc --version`,
    /// `uname -srm` ("unknown" where one is unavailable).
    pub fn detect() -> Machine {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let field = |key: &str| {
            cpuinfo.lines().find_map(|l| {
                l.strip_prefix(key)?
                    .split_once(':')
                    .map(|x| x.1.trim().to_string())
            })
        };
        let cpu = field("model name").unwrap_or_else(|| "unknown".into());
        let cmd = |c: &str, a: &[&str]| {
            std::process::Command::new(c)
                .args(a)
                .output()
                .ok()
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
                .unwrap_or_else(|| "unknown".into())
        };
        Machine {
            cpu: match field("cpu MHz") {
                Some(m) => format!("{cpu} ({m} MHz)"),
                None => cpu,
            },
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            rustc: cmd("rustc", &["--version"]),
            os: cmd("uname", &["-srm"]),
        }
    }
}

/// A Markdown table row `| a | b | … |` with its newline.
pub(crate) fn row<S: AsRef<str>>(cells: &[S]) -> String {
    let mut s = String::from("|");
    for c in cells {
        s.push(' ');
        s.push_str(c.as_ref());
        s.push_str(" |");
    }
    s.push('\n');
    s
}

/// a / b when both are known and b > 0.
pub(crate) fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => Some(a / b),
        _ => None,
    }
}

/// `fmt_ns` of a figure that may be missing ("–").
pub(crate) fn ns(x: Option<f64>) -> String {
    x.map_or("–".into(), fmt_ns)
}

impl Data {
    /// ns per call of criterion result `id`.
    pub fn per(&self, id: &str) -> Option<f64> {
        self.est.get(id).map(Est::per_call)
    }
    /// Callgrind instructions per call of kernel `k`.
    pub fn ir(&self, k: &str) -> Option<f64> {
        self.cg
            .as_ref()
            .ok()?
            .iter()
            .find(|x| x.0 == k)
            .map(|x| x.2)
    }
    /// The SciPy peer's ns per G, when it ran.
    fn peer_ns(&self) -> Option<f64> {
        match &self.peer {
            Peer::Ran { ns_per_g, .. } => Some(*ns_per_g),
            Peer::Skipped(_) => None,
        }
    }
    /// Criterion ids under `group/`, the rest of each id, sorted.
    fn names(&self, group: &str) -> Vec<&str> {
        let mut v: Vec<&str> = self
            .est
            .keys()
            .filter_map(|k| k.strip_prefix(group))
            .collect();
        v.sort();
        v
    }
}

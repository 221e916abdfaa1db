//! Table generation, timed (issue 22 item 4): each table of the default set and the Khronos
//! 1024² split-sum target through the one generator ([`brdf_lut::generate::generate`]),
//! beside the numpy Monte Carlo peer `peer/dfg_mc_peer.py` (Hammersley, 1,024 samples per
//! texel) on the same Khronos grid, both judged against the converged split sum
//! ([`brdf_core::split_sum::converged`]).

use brdf_core::split_sum::converged::DfgGgxRow;
use brdf_lut::generate::{generate, AxisSpec, GenError, Generated, Spec};
use brdf_lut::{Placement, Warp};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// The Khronos target's edge.
pub const KHRONOS_SIZE: usize = 1024;
/// Samples per texel of the Monte Carlo peer.
pub const PEER_SAMPLES: usize = 1024;
/// Tolerance of the converged reference (per texel, both channels).
pub const REFERENCE_TOL: f64 = 1e-8;

/// One table generated once: its name, nodes, wall time and integrand evaluations.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Timing {
    /// File name (default set) or target name.
    pub name: String,
    /// Nodes computed.
    pub nodes: u64,
    /// Wall time of `generate` (all cores), s.
    pub secs: f64,
    /// Integrand evaluations, when the generator reports them.
    pub evals: Option<u64>,
}

/// The numpy Monte Carlo peer on the Khronos grid's sampled rows.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct McPeer {
    /// Wall time per texel, µs (one core, numpy vectorised over texels).
    pub us_per_texel: f64,
    /// max |error| over both channels against the converged values.
    pub max_error: f64,
    /// The same on the four grazing columns (μ < 4/1024).
    pub grazing_max_error: f64,
    /// "Python x, NumPy y".
    pub versions: String,
}

/// The generation section's data.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TableGen {
    /// The default set, one row per table.
    pub tables: Vec<Timing>,
    /// The Khronos 1024² target on every `stride`-th roughness row.
    pub khronos: Timing,
    /// Roughness rows sampled: every `stride`-th of [`KHRONOS_SIZE`].
    pub stride: usize,
    /// The peer, or why it did not run.
    pub peer: Result<McPeer, String>,
    /// Worker threads of the generator.
    pub threads: usize,
    /// The default set on shrunken grids (see [`time_default_set`]), when not a measurement.
    #[serde(default)]
    pub shrunk: Option<u32>,
}

/// Integrand evaluations of one generated table, as the generator counts them (`None`
/// when it counted none: the polar E_avg does not count its evaluations).
pub fn evaluations(g: &Generated) -> Option<u64> {
    (g.evals > 0).then_some(g.evals)
}

/// Generates `spec` once (bytes discarded) and times it.
pub fn time_table(name: &str, spec: &Spec) -> Result<Timing, GenError> {
    let nodes = spec.axes.iter().map(|a| a.count as u64).product();
    let t0 = Instant::now();
    let g = generate(spec, &|_| {})?;
    Ok(Timing {
        name: name.to_string(),
        nodes,
        secs: t0.elapsed().as_secs_f64(),
        evals: evaluations(&g),
    })
}

/// Each table of the default set, timed; with `shrink`, on grids of at most `shrink` nodes
/// per axis and as many error samples (a check that every table goes through, not a
/// measurement: the smoke run).
pub fn time_default_set(shrink: Option<u32>) -> Result<Vec<Timing>, GenError> {
    let mut set = brdf_lut::generate::default_set();
    if let Some(m) = shrink {
        for a in &mut set {
            a.spec
                .axes
                .iter_mut()
                .for_each(|x| x.count = x.count.min(m));
            a.spec.samples = a.spec.samples.min(m);
        }
    }
    set.iter().map(|a| time_table(&a.file, &a.spec)).collect()
}

/// Texel centre k of the Khronos axes.
fn centre(k: usize) -> f64 {
    (k as f64 + 0.5) / KHRONOS_SIZE as f64
}

/// The Khronos target's spec ([`brdf_engine_assets::split_sum_spec`] of 1024) on every
/// `stride`-th roughness row: rows r = (j·stride + ½)/1024, an endpoint axis from the first to
/// the last of them (the same nodes; the whole grid for stride 1).
pub fn khronos_spec(stride: usize) -> Spec {
    let mut s = brdf_engine_assets::split_sum_spec(KHRONOS_SIZE);
    let stride = stride.max(1);
    if stride > 1 {
        let rows = KHRONOS_SIZE.div_ceil(stride);
        let hi = centre((rows - 1) * stride);
        s.axes[1] = AxisSpec {
            placement: Placement::Endpoint,
            ..AxisSpec::endpoint(rows as u32, centre(0), hi, Warp::Linear)
        };
    }
    s
}

/// The converged (A, B) of the Khronos grid's every `stride`-th row, as raw little-endian f64
/// `[row][μ column][A, B]` (the peer's `--reference` layout), on all cores.
pub fn converged_rows(stride: usize) -> Vec<u8> {
    let js: Vec<usize> = (0..KHRONOS_SIZE).step_by(stride.max(1)).collect();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut out = vec![0u8; js.len() * KHRONOS_SIZE * 16];
    let per = js.len().div_ceil(threads).max(1);
    std::thread::scope(|s| {
        for (chunk, rows) in out.chunks_mut(per * KHRONOS_SIZE * 16).zip(js.chunks(per)) {
            s.spawn(move || {
                for (buf, &j) in chunk.chunks_mut(KHRONOS_SIZE * 16).zip(rows) {
                    let row = DfgGgxRow::new(centre(j));
                    for (i, t) in buf.chunks_mut(16).enumerate() {
                        let v = row.texel(centre(i), REFERENCE_TOL).value;
                        t[..8].copy_from_slice(&v[0].to_le_bytes());
                        t[8..].copy_from_slice(&v[1].to_le_bytes());
                    }
                }
            });
        }
    });
    out
}

/// The peer's result from `dfg_mc_peer.py`'s JSON output.
pub fn mc_peer_from_json(v: &serde_json::Value, versions: String) -> Result<McPeer, String> {
    let f = |k: &str| {
        v[k].as_f64()
            .ok_or_else(|| format!("peer output has no {k}"))
    };
    Ok(McPeer {
        us_per_texel: f("us_per_texel")?,
        max_error: f("max_error")?,
        grazing_max_error: f("grazing_max_error")?,
        versions,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The strided spec's roughness nodes are the peer's rows, r = (j·s + ½)/1024 for
    /// j = 0, s, 2s, … (`centres[::stride]` in dfg_mc_peer.py); stride 1 is the whole target.
    #[test]
    fn khronos_spec_samples_the_peer_rows() {
        assert_eq!(khronos_spec(1), brdf_engine_assets::split_sum_spec(1024));
        for s in [8, 64] {
            let a = khronos_spec(s).axes[1];
            let rows = 1024 / s;
            assert_eq!(a.count as usize, rows);
            for k in 0..rows {
                let node = a.lo + (a.hi - a.lo) * k as f64 / (rows - 1) as f64;
                let r = (k * s) as f64 / 1024.0 + 0.5 / 1024.0;
                assert!((node - r).abs() < 1e-15, "{s} {k}: {node} {r}");
            }
        }
    }

    /// The reference rows are laid out as the peer reads them ([row][μ][A, B]) and agree with
    /// the fixed-rule split sum away from grazing (there within its 3e-7 accuracy; 1e-6).
    #[test]
    fn converged_rows_hold_the_split_sum_in_the_peers_layout() {
        let b = converged_rows(512);
        assert_eq!(b.len(), 2 * 1024 * 16);
        let at = |o: usize| f64::from_le_bytes(b[o..o + 8].try_into().unwrap());
        for (row, j) in [(0usize, 0usize), (1, 512)] {
            for i in [200usize, 700, 1023] {
                let (mu, r) = ((i as f64 + 0.5) / 1024.0, (j as f64 + 0.5) / 1024.0);
                let (ea, eb) = brdf_core::split_sum::dfg_ggx::<
                    f64,
                    brdf_core::split_sum::OuterRule,
                    brdf_core::split_sum::InnerRule,
                >(mu, r);
                let o = (row * 1024 + i) * 16;
                assert!((at(o) - ea).abs() < 1e-6, "A {i} {j}: {} {ea}", at(o));
                assert!(
                    (at(o + 8) - eb).abs() < 1e-6,
                    "B {i} {j}: {} {eb}",
                    at(o + 8)
                );
            }
        }
    }

    fn timing(name: &str, nodes: u64, secs: f64) -> Timing {
        Timing {
            name: name.into(),
            nodes,
            secs,
            evals: None,
        }
    }

    /// The section's figures from made-up timings, computed by hand: 131,072 nodes in 1 s is
    /// 7.63 µs per node; against a 30 µs peer 0.25× wall clock, 0.51× per core on 2 threads.
    #[test]
    fn section_states_rates_ratios_and_missing_counts() {
        let mut t = TableGen {
            tables: vec![timing("a.blut", 1000, 0.5), timing("b.blut", 3000, 0.5)],
            khronos: timing("khronos", 131_072, 1.0),
            stride: 8,
            peer: Ok(McPeer {
                us_per_texel: 30.0,
                max_error: 1.1e-2,
                grazing_max_error: 1.1e-2,
                versions: "Python 3, NumPy 2".into(),
            }),
            threads: 2,
            shrunk: None,
        };
        let md = super::super::render_tablegen(&t).unwrap();
        assert!(
            md.contains("| `a.blut` | 1000 | 0.50 s | 500.00 | — |"),
            "{md}"
        );
        assert!(md.contains("| 4000 | 1.00 s | 250.00 | |"), "{md}");
        assert!(md.contains("| 131072 | 1.00 s | 7.63 | — |"), "{md}");
        assert!(
            md.contains("**0.25×** wall clock, **0.51×** per core"),
            "{md}"
        );
        assert!(
            md.contains("128 of its 1,024 roughness rows (every 8th row"),
            "{md}"
        );
        t.peer = Err("numpy missing".into());
        let md = super::super::render_tablegen(&t).unwrap();
        assert!(md.contains("The peer did not run: numpy missing."), "{md}");
    }
}

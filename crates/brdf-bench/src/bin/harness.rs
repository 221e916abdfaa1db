//! Callgrind harness: `harness <kernel> <n>` calls one kernel `n` times over the benchmark
//! inputs (cycling through [`brdf_bench::BATCH`] of them). Run it under
//! `valgrind --tool=callgrind` with `n` and with 0: instructions per call =
//! (Ir(n) − Ir(0))/n, which removes start-up, input preparation and table loading.
//! `harness list` prints the kernel names. The `*_batch` kernels make one batch call over all
//! [`brdf_bench::BATCH`] inputs per call: divide their per-call figure by `BATCH` for the
//! cost per lookup.

use brdf_bench::*;
use brdf_core::masking::{self, ModifiedG};
use brdf_core::roughness::beckmann_m_from_sigma;
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use brdf_lut::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, SheenAlbedoTable};
use std::hint::black_box;

const KERNELS: &[&str] = &[
    "g_direct_f32",
    "g_direct_f64",
    "g_lut3d",
    "g_lut2d",
    "g_lut3d_linear",
    "g_lut2d_linear",
    "smith_beckmann_f32",
    "blinn_f32",
    "dfg_lut",
    "dfg_karis",
    "dfg_direct_f64",
    "floor_bilinear2",
    "dfg_lut_std",
    "g_lut2d_linear_std",
    "g_lut2d_linear_batch",
    "g_lut3d_linear_batch",
    "dfg_lut_batch",
    "e_lut_batch",
    "eavg_lut_batch",
    "e_lut",
    "eavg_lut",
    "g_lut2d_linear_dots",
    "g_lut3d_linear_dots",
    "sheen_e_lut",
    "glass_e_lut3d",
];

/// The benchmark inputs, prepared before any kernel runs (the (n) − (0) difference removes
/// their cost).
struct Inputs {
    ti32: Vec<f32>,
    tr32: Vec<f32>,
    ti64: Vec<f64>,
    tr64: Vec<f64>,
    d32: Vec<brdf_core::Dots<f32>>,
    mr: Vec<(f64, f64)>,
    /// μ and r of `mr` as f32 slices, for the batch kernels.
    mu: Vec<f32>,
    r: Vec<f32>,
}

impl Inputs {
    fn new() -> Self {
        let (ti32, tr32) = angle_pairs::<f32>(BATCH);
        let (ti64, tr64) = angle_pairs::<f64>(BATCH);
        let mr = mu_roughness(BATCH);
        Inputs {
            ti32,
            tr32,
            ti64,
            tr64,
            d32: dots_pairs::<f32>(BATCH),
            mu: mr.iter().map(|p| p.0 as f32).collect(),
            r: mr.iter().map(|p| p.1 as f32).collect(),
            mr,
        }
    }
    /// (μ, r) of input `k` in f32.
    fn mr32(&self, k: usize) -> (f32, f32) {
        (
            black_box(self.mr[k].0 as f32),
            black_box(self.mr[k].1 as f32),
        )
    }
}

/// Calls `f(k % BATCH)` for k in 0..n and sums the results (so no call is optimised away).
#[inline(always)]
fn run<T: Into<f64>>(n: usize, mut f: impl FnMut(usize) -> T) -> f64 {
    let mut acc = 0f64;
    for k in 0..n {
        acc += f(k % BATCH).into();
    }
    acc
}

/// The bytes of asset `a`; exits with a message if it is missing.
fn asset(a: &str) -> Vec<u8> {
    read_asset(a).unwrap_or_else(|| {
        eprintln!("asset {a} missing");
        std::process::exit(1)
    })
}

/// The direct kernels (no table).
fn direct(name: &str, n: usize, i: &Inputs) -> Option<f64> {
    Some(match name {
        "g_direct_f32" => {
            let g = ModifiedG::<f32>::new(SIGMA as f32).unwrap();
            run(n, |k| g.g(black_box(i.ti32[k]), black_box(i.tr32[k])))
        }
        "g_direct_f64" => {
            let g = ModifiedG::<f64>::new(SIGMA).unwrap();
            run(n, |k| g.g(black_box(i.ti64[k]), black_box(i.tr64[k])))
        }
        "smith_beckmann_f32" => {
            let m = beckmann_m_from_sigma(SIGMA) as f32;
            run(n, |k| {
                let d = i.d32[k];
                masking::g_smith_beckmann_correlated(black_box(d.n_i), black_box(d.n_o), m)
            })
        }
        "blinn_f32" => run(n, |k| masking::g_blinn_dots(black_box(i.d32[k]))),
        "dfg_karis" => run(n, |k| {
            let (mu, r) = i.mr32(k);
            let (a, b) = env_brdf_approx(mu, r);
            a + b
        }),
        "dfg_direct_f64" => run(n, |k| {
            let (a, b) =
                dfg_ggx::<f64, OuterRule, InnerRule>(black_box(i.mr[k].0), black_box(i.mr[k].1));
            a + b
        }),
        _ => return None,
    })
}

/// `GTable::g` over the angles `ti`, `tr`, from the table's bytes `b`. Out of line, as
/// [`g3`]: how the compiler arranges a lookup's loop depends on the function around it (the
/// 3-D linear lookup measured 390 instructions inlined into [`g_tables`], 378 here, 354 in
/// the single `main` of before; the library code is the same).
#[inline(never)]
fn g2(b: &[u8], n: usize, ti: &[f32], tr: &[f32]) -> f64 {
    let t = GTable::parse(b).unwrap();
    run(n, |k| t.g(black_box(ti[k]), black_box(tr[k])))
}

/// `GTable3::g` over the angles `ti`, `tr` at σ = [`SIGMA`], from the table's bytes `b`
/// (as [`g2`]).
#[inline(never)]
fn g3(b: &[u8], n: usize, ti: &[f32], tr: &[f32]) -> f64 {
    let t = GTable3::parse(b).unwrap();
    run(n, |k| t.g(black_box(ti[k]), black_box(tr[k]), SIGMA as f32))
}

/// The passing-factor (G) table lookups, scalar.
fn g_tables(name: &str, n: usize, i: &Inputs) -> Option<f64> {
    Some(match name {
        "g_lut3d" => g3(&asset(G3_ASSET), n, &i.ti32, &i.tr32),
        "g_lut2d" => g2(&asset(G2_ASSET), n, &i.ti32, &i.tr32),
        "g_lut3d_linear" => g3(&asset(G3_LINEAR_ASSET), n, &i.ti32, &i.tr32),
        "g_lut2d_linear" => g2(&asset(G2_LINEAR_ASSET), n, &i.ti32, &i.tr32),
        "g_lut2d_linear_std" => {
            let t = brdf_lut::Lut::from_path(assets_dir().join(G2_LINEAR_ASSET)).unwrap();
            run(n, |k| {
                t.g(black_box(i.ti32[k]), black_box(i.tr32[k]), SIGMA as f32)
                    .unwrap()
            })
        }
        "g_lut2d_linear_dots" => {
            let b = asset(G2_LINEAR_ASSET);
            let t = GTable::parse(&b).unwrap();
            run(n, |k| {
                let d = i.d32[k];
                t.g_dots(black_box(d.n_i), black_box(d.n_o), black_box(d.i_o))
            })
        }
        "g_lut3d_linear_dots" => {
            let b = asset(G3_LINEAR_ASSET);
            let t = GTable3::parse(&b).unwrap();
            run(n, |k| {
                let d = i.d32[k];
                let (ni, no, io) = (black_box(d.n_i), black_box(d.n_o), black_box(d.i_o));
                t.g_dots(ni, no, io, SIGMA as f32)
            })
        }
        _ => return None,
    })
}

/// The (μ, r) table lookups, scalar: split sum, albedos, sheen, glass, and the floor.
fn mu_r_tables(name: &str, n: usize, i: &Inputs) -> Option<f64> {
    Some(match name {
        "dfg_lut" => {
            let b = asset(DFG_LINEAR_ASSET);
            let t = DfgTable::parse(&b).unwrap();
            run(n, |k| {
                let (mu, r) = i.mr32(k);
                let (a, b) = t.ab(mu, r);
                a + b
            })
        }
        "floor_bilinear2" => {
            let t = FloorBilinear2::new();
            run(n, |k| {
                let (mu, r) = i.mr32(k);
                let (a, b) = t.fetch(mu, r);
                a + b
            })
        }
        "dfg_lut_std" => {
            let t = brdf_lut::Lut::from_path(assets_dir().join(DFG_LINEAR_ASSET)).unwrap();
            run(n, |k| {
                let (mu, r) = i.mr32(k);
                let (a, b) = t.dfg(mu, r).unwrap();
                a + b
            })
        }
        "e_lut" => {
            let b = asset(E_ASSET);
            let t = AlbedoTable::parse(&b[..]).unwrap();
            run(n, |k| {
                let (mu, r) = i.mr32(k);
                t.e(mu, r)
            })
        }
        "eavg_lut" => {
            let b = asset(EAVG_ASSET);
            let t = AverageAlbedoTable::parse(&b[..]).unwrap();
            run(n, |k| t.e_avg(black_box(i.mr[k].1 as f32)))
        }
        "sheen_e_lut" => {
            let b = sheen_table();
            let t = SheenAlbedoTable::parse(&b[..]).unwrap();
            run(n, |k| {
                let (mu, r) = i.mr32(k);
                t.e(mu, r)
            })
        }
        "glass_e_lut3d" => {
            let b = glass_table_32();
            let t = brdf_lut::GlassAlbedoTable::parse(&b[..]).unwrap();
            run(n, |k| {
                let eta = 1.0 + 0.02 * (k % 97) as f32;
                let (mu, r) = i.mr32(k);
                let (r, t) = t.rt(mu, r, eta);
                r + t
            })
        }
        _ => return None,
    })
}

/// The batch lookups: one call covers all `BATCH` inputs.
fn batches(name: &str, n: usize, i: &Inputs) -> Option<f64> {
    let (mut a, mut bb) = (vec![0f32; BATCH], vec![0f32; BATCH]);
    let (mu, r) = (&i.mu[..], &i.r[..]);
    Some(match name {
        "g_lut2d_linear_batch" => {
            let b = asset(G2_LINEAR_ASSET);
            let t = GTable::parse(&b[..]).unwrap();
            run(n, |_| {
                t.g_batch(black_box(&i.ti32), black_box(&i.tr32), &mut a);
                a[0]
            })
        }
        "g_lut3d_linear_batch" => {
            let b = asset(G3_LINEAR_ASSET);
            let t = GTable3::parse(&b[..]).unwrap();
            run(n, |_| {
                t.g_batch(black_box(&i.ti32), black_box(&i.tr32), SIGMA as f32, &mut a);
                a[0]
            })
        }
        "dfg_lut_batch" => {
            let b = asset(DFG_LINEAR_ASSET);
            let t = DfgTable::parse(&b[..]).unwrap();
            run(n, |_| {
                t.ab_batch(black_box(mu), black_box(r), &mut a, &mut bb);
                a[0] + bb[0]
            })
        }
        "e_lut_batch" => {
            let b = asset(E_ASSET);
            let t = AlbedoTable::parse(&b[..]).unwrap();
            run(n, |_| {
                t.e_batch(black_box(mu), black_box(r), &mut a);
                a[0]
            })
        }
        "eavg_lut_batch" => {
            let b = asset(EAVG_ASSET);
            let t = AverageAlbedoTable::parse(&b[..]).unwrap();
            run(n, |_| {
                t.e_avg_batch(black_box(r), &mut a);
                a[0]
            })
        }
        _ => return None,
    })
}

/// One group of kernels: the sum of kernel `name`'s results over `n` calls, or `None` if
/// the group has no kernel of that name.
type Group = fn(&str, usize, &Inputs) -> Option<f64>;

/// `harness <kernel> <n>` or `harness list`; exits with status 2 on a usage error.
fn args() -> (String, usize) {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 2 && args[1] == "list" {
        println!("{}", KERNELS.join("\n"));
        std::process::exit(0);
    }
    if args.len() != 3 {
        eprintln!("usage: harness <kernel> <n> | harness list");
        std::process::exit(2);
    }
    match args[2].parse() {
        Ok(n) => (args[1].clone(), n),
        Err(_) => {
            eprintln!("n must be a non-negative integer");
            std::process::exit(2);
        }
    }
}

fn main() {
    let (name, n) = args();
    let inputs = Inputs::new();
    let groups: [Group; 4] = [direct, g_tables, mu_r_tables, batches];
    match groups.iter().find_map(|g| g(&name, n, &inputs)) {
        Some(acc) => {
            black_box(acc);
        }
        None => {
            eprintln!("unknown kernel {name}; `harness list` prints the names");
            std::process::exit(2);
        }
    }
}

/// A sheen albedo table for `sheen_e_lut`, built at start-up (no asset holds one; the
/// (n) − (0) difference removes its cost) on the default spec's axes (μ ∈ [cos 89°, 1]
/// √-warped, r ∈ [0, 1] linear: `Role::default_axis`), Estevez–Kulla visibility, in the
/// speed tier's form: linear u16 like `dfg_lut`'s asset. 32 × 32 nodes instead of the
/// default 64 × 64 keep the start-up short under callgrind (the lookup's instructions do
/// not depend on the node count).
fn sheen_table() -> Vec<u8> {
    use brdf_lut::generate::{generate, Distribution, Kind, Masking, SheenVisibility, Spec};
    let mut s = Spec::new(
        Kind::SheenAlbedo {
            visibility: SheenVisibility::EstevezKulla,
        },
        Distribution::Ggx,
        Masking::SmithCorrelated,
    );
    for a in s.axes.iter_mut() {
        a.count = 32;
    }
    s.interpolation = brdf_lut::Interpolation::Linear;
    s.samples = 16;
    generate(&s, &|_| {}).unwrap().bytes
}

/// A 32³ two-channel linear u16 `GlassAlbedo` table (the default grid and the
/// texture's interpolation) over μ ∈ [cos 89°, 1] (log), r ∈ [0, 1], η ∈ [1, 3], for the
/// lookup's instruction count: the values are a smooth stand-in (the lookup's work does
/// not depend on them; generating the converged table takes minutes).
fn glass_table_32() -> Vec<u8> {
    use brdf_lut::{
        write, Axis, Encoding, Generator, Interpolation, Model, Placement, TableKind, Warp,
    };
    let ax = |name, lo, hi, warp| Axis {
        name,
        count: 32,
        lo,
        hi,
        warp,
        placement: Placement::Endpoint,
    };
    let axes = [
        ax("mu", brdf_lut::generate::MU_MIN, 1.0, Warp::Log),
        ax("roughness", 0.0, 1.0, Warp::Linear),
        ax("eta", 1.0, 3.0, Warp::Linear),
    ];
    let mut v = Vec::with_capacity(2 * 32 * 32 * 32);
    for k in 0..32 * 32 * 32 {
        let (i, j, l) = ((k % 32) as f64, ((k / 32) % 32) as f64, (k / 1024) as f64);
        let r = 0.04 + 0.5 * (1.0 - i / 31.0).powi(4) * (1.0 - 0.3 * j / 31.0) + 0.01 * l / 31.0;
        v.extend_from_slice(&[r, 0.95 - r]);
    }
    let spec = write::Spec {
        kind: TableKind::GlassAlbedo,
        axes: &axes,
        channels: &["R", "T"],
        encoding: Encoding::Unorm16,
        interpolation: Interpolation::Linear,
        generator: Generator {
            model: Model::RoughDielectricGgx,
            tool: "harness",
            ..Generator::default()
        },
    };
    write::build(&spec, &v, |_| brdf_lut::ErrorStats::default()).unwrap()
}

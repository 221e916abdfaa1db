//! Callgrind harness: `harness <kernel> <n>` calls one kernel `n` times over the benchmark
//! inputs (cycling through [`brdf_bench::BATCH`] of them). Run it under
//! `valgrind --tool=callgrind` with `n` and with 0: instructions per call =
//! (Ir(n) − Ir(0))/n, which removes start-up, input preparation and table loading.
//! `harness list` prints the kernel names. The `*_batch` kernels make one batch call over all
//! [`brdf_bench::BATCH`] inputs per call: divide their per-call figure by `BATCH` for the
//! cost per lookup.

use brdf_bench::*;
use brdf_core::masking::{self, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic};
use brdf_core::roughness::beckmann_m_from_sigma;
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use brdf_lut::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, SheenAlbedoTable};
use std::hint::black_box;

/// The kernels, one row each, in `harness list` order: name, `{ set-up }` (run once, outside
/// the count) and `|k| per-call expression` over input index `k`. Hands the rows to the
/// callback macro `$cb!`: [`KERNELS`] takes their names, `main` makes them its match arms.
/// The bracketed idents are the inputs the rows read (`main`'s locals: macro hygiene keeps
/// a row from naming them itself): angle pairs (f32, f64), dot products, (μ, roughness)
/// points and the asset reader.
macro_rules! kernel_table {
    ($cb:ident![$ti32:ident $tr32:ident $ti64:ident $tr64:ident $d32:ident $mr:ident $asset:ident]) => {
        $cb! {
            "g_direct_f32" {
                let g = ModifiedG::<f32>::new(SIGMA as f32).unwrap();
            } |k| g.g(black_box($ti32[k]), black_box($tr32[k])),
            "g_direct_f64" {
                let g = ModifiedG::<f64>::new(SIGMA).unwrap();
            } |k| g.g(black_box($ti64[k]), black_box($tr64[k])),
            "g_lut3d" {
                let b = $asset(G3_ASSET);
                let t = GTable3::parse(&b).unwrap();
            } |k| t.g(black_box($ti32[k]), black_box($tr32[k]), SIGMA as f32),
            "g_lut2d" {
                let b = $asset(G2_ASSET);
                let t = GTable::parse(&b).unwrap();
            } |k| t.g(black_box($ti32[k]), black_box($tr32[k])),
            "g_lut3d_linear" {
                let b = $asset(G3_LINEAR_ASSET);
                let t = GTable3::parse(&b).unwrap();
            } |k| t.g(black_box($ti32[k]), black_box($tr32[k]), SIGMA as f32),
            "g_lut2d_linear" {
                let b = $asset(G2_LINEAR_ASSET);
                let t = GTable::parse(&b).unwrap();
            } |k| t.g(black_box($ti32[k]), black_box($tr32[k])),
            "smith_beckmann_f32" {
                let m = beckmann_m_from_sigma(SIGMA) as f32;
            } |k| Beckmann::g_correlated_cos(black_box($d32[k].n_i), black_box($d32[k].n_o), m),
            "blinn_f32" {} |k| masking::g_blinn_dots(black_box($d32[k])),
            "dfg_lut" {
                let b = $asset(DFG_LINEAR_ASSET);
                let t = DfgTable::parse(&b).unwrap();
            } |k| {
                let (a, b) = t.ab(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32));
                a + b
            },
            "dfg_karis" {} |k| {
                let (a, b) = env_brdf_approx(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32));
                a + b
            },
            "dfg_direct_f64" {} |k| {
                let (a, b) =
                    dfg_ggx::<f64, OuterRule, InnerRule>(black_box($mr[k].0), black_box($mr[k].1));
                a + b
            },
            "floor_bilinear2" {
                let t = FloorBilinear2::new();
            } |k| {
                let (a, b) = t.fetch(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32));
                a + b
            },
            "dfg_lut_std" {
                let t = brdf_lut::Lut::from_path(assets_dir().join(DFG_LINEAR_ASSET)).unwrap();
            } |k| {
                let (a, b) = t
                    .dfg(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32))
                    .unwrap();
                a + b
            },
            "g_lut2d_linear_std" {
                let t = brdf_lut::Lut::from_path(assets_dir().join(G2_LINEAR_ASSET)).unwrap();
            } |k| t.g(black_box($ti32[k]), black_box($tr32[k]), SIGMA as f32).unwrap(),
            "g_lut2d_linear_batch" {
                let b = $asset(G2_LINEAR_ASSET);
                let t = GTable::parse(&b[..]).unwrap();
                let mut out = vec![0f32; BATCH];
            } |_k| {
                t.g_batch(black_box(&$ti32), black_box(&$tr32), &mut out);
                out[0]
            },
            "g_lut3d_linear_batch" {
                let b = $asset(G3_LINEAR_ASSET);
                let t = GTable3::parse(&b[..]).unwrap();
                let mut out = vec![0f32; BATCH];
            } |_k| {
                t.g_batch(black_box(&$ti32), black_box(&$tr32), SIGMA as f32, &mut out);
                out[0]
            },
            "dfg_lut_batch" {
                let b = $asset(DFG_LINEAR_ASSET);
                let t = DfgTable::parse(&b[..]).unwrap();
                let ((mu, r), mut a, mut bb) = (mu_r(&$mr), vec![0f32; BATCH], vec![0f32; BATCH]);
            } |_k| {
                t.ab_batch(black_box(&mu), black_box(&r), &mut a, &mut bb);
                a[0] + bb[0]
            },
            "e_lut_batch" {
                let b = $asset(E_ASSET);
                let t = AlbedoTable::parse(&b[..]).unwrap();
                let ((mu, r), mut a) = (mu_r(&$mr), vec![0f32; BATCH]);
            } |_k| {
                t.e_batch(black_box(&mu), black_box(&r), &mut a);
                a[0]
            },
            "eavg_lut_batch" {
                let b = $asset(EAVG_ASSET);
                let t = AverageAlbedoTable::parse(&b[..]).unwrap();
                let ((_, r), mut a) = (mu_r(&$mr), vec![0f32; BATCH]);
            } |_k| {
                t.e_avg_batch(black_box(&r), &mut a);
                a[0]
            },
            "e_lut" {
                let b = $asset(E_ASSET);
                let t = AlbedoTable::parse(&b[..]).unwrap();
            } |k| t.e(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32)),
            "eavg_lut" {
                let b = $asset(EAVG_ASSET);
                let t = AverageAlbedoTable::parse(&b[..]).unwrap();
            } |k| t.e_avg(black_box($mr[k].1 as f32)),
            "g_lut2d_linear_dots" {
                let b = $asset(G2_LINEAR_ASSET);
                let t = GTable::parse(&b).unwrap();
            } |k| t.g_dots(black_box($d32[k].n_i), black_box($d32[k].n_o), black_box($d32[k].i_o)),
            "g_lut3d_linear_dots" {
                let b = $asset(G3_LINEAR_ASSET);
                let t = GTable3::parse(&b).unwrap();
            } |k| t.g_dots(
                black_box($d32[k].n_i),
                black_box($d32[k].n_o),
                black_box($d32[k].i_o),
                SIGMA as f32
            ),
            "sheen_e_lut" {
                let b = sheen_table();
                let t = SheenAlbedoTable::parse(&b[..]).unwrap();
            } |k| t.e(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32)),
            "glass_e_lut3d" {
                let b = glass_table_32();
                let t = brdf_lut::GlassAlbedoTable::parse(&b[..]).unwrap();
            } |k| {
                let eta = 1.0 + 0.02 * (k % 97) as f32;
                let (r, t) = t.rt(black_box($mr[k].0 as f32), black_box($mr[k].1 as f32), eta);
                r + t
            },
        }
    };
}

/// [`kernel_table`] callback: the names, as the `const KERNELS` item.
macro_rules! kernel_names {
    ($($name:literal { $($setup:tt)* } |$k:ident| $body:expr,)*) => {
        /// The kernel names, in [`kernel_table`] order (`harness list`).
        const KERNELS: &[&str] = &[$($name),*];
    };
}

kernel_table!(kernel_names![ti32 tr32 ti64 tr64 d32 mr asset]);

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 2 && args[1] == "list" {
        println!("{}", KERNELS.join("\n"));
        return;
    }
    if args.len() != 3 {
        eprintln!("usage: harness <kernel> <n> | harness list");
        std::process::exit(2);
    }
    let name = args[1].as_str();
    let n: usize = match args[2].parse() {
        Ok(n) => n,
        Err(_) => {
            eprintln!("n must be a non-negative integer");
            std::process::exit(2);
        }
    };
    let (ti32, tr32) = angle_pairs::<f32>(BATCH);
    let (ti64, tr64) = angle_pairs::<f64>(BATCH);
    let d32 = dots_pairs::<f32>(BATCH);
    let mr = mu_roughness(BATCH);
    let mut acc = 0f64;
    let asset = |a: &str| {
        read_asset(a).unwrap_or_else(|| {
            eprintln!("asset {a} missing");
            std::process::exit(1)
        })
    };
    // One match arm a row of the table: its set-up, then `n` calls cycling over the inputs.
    macro_rules! dispatch {
        ($($name:literal { $($setup:tt)* } |$k:ident| $body:expr,)*) => {
            match name {
                $($name => {
                    $($setup)*
                    #[allow(unused_mut)]
                    let mut f = |$k: usize| $body;
                    for k in 0..n {
                        acc += f(k % BATCH) as f64;
                    }
                })*
                _ => {
                    eprintln!("unknown kernel {name}; `harness list` prints the names");
                    std::process::exit(2);
                }
            }
        };
    }
    kernel_table!(dispatch![ti32 tr32 ti64 tr64 d32 mr asset]);
    black_box(acc);
}

/// The batch kernels' (μ, roughness) inputs as two f32 slices.
fn mu_r(mr: &[(f64, f64)]) -> (Vec<f32>, Vec<f32>) {
    mr.iter().map(|p| (p.0 as f32, p.1 as f32)).unzip()
}

/// A sheen albedo table for `sheen_e_lut`, built at start-up (no asset holds one; the
/// (n) − (0) difference removes its cost): Estevez–Kulla visibility, 32 × 32 nodes, linear
/// u16 like `dfg_lut`'s asset (the lookup's instructions do not depend on the node count).
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

//! The criterion suite. `cargo xtask bench` runs it with short settings and turns
//! `target/criterion/**/new/estimates.json` into `docs/benchmarks.md`; every group declares
//! its elements per iteration as criterion throughput, so ns per call = mean / elements.
//!
//! Group names carry the scalar type and, for f32 kernels, the math library
//! (`libm` or `micromath`, brdf-bench's feature `micromath`), so the two runs of the binary
//! write to different directories.

use brdf_bench::*;
use brdf_core::batch::{self, DotsSoa, Vec3Soa};
use brdf_core::fresnel::Fresnel;
use brdf_core::masking::{self, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic};
use brdf_core::models::*;
use brdf_core::quadrature::{GaussLegendre, DEFAULT_NODES};
use brdf_core::roughness::{alpha_from_perceptual, beckmann_m_from_sigma};
use brdf_core::split_sum::{dfg_ggx, InnerRule, OuterRule};
use brdf_core::{albedo, Real, Vec3};
use brdf_lut::{DfgTable, GTable, GTable3, LutView};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;

/// "libm" or "micromath": which library the f32 transcendental functions come from.
const F32_MATH: &str = if cfg!(feature = "micromath") {
    "micromath"
} else {
    "libm"
};

/// The f32 scalar the direct and closed-form kernels are measured in: `f32` (libm) or, with
/// the `micromath` feature, brdf-core's `Micro` (micromath's exp and inverse trigonometric
/// functions; `f32` itself always uses libm).
#[cfg(feature = "micromath")]
type F32 = brdf_core::real::Micro;
#[cfg(not(feature = "micromath"))]
type F32 = f32;

fn type_tag<T: Real>() -> String {
    if core::mem::size_of::<T>() == 4 {
        format!("f32_{F32_MATH}")
    } else {
        "f64".into()
    }
}

/// One pass over `pts` per iteration: `f` at every point (through `black_box`).
fn each<P: Copy, R>(b: &mut criterion::Bencher, pts: &[P], f: impl Fn(P) -> R) {
    b.iter(|| {
        for &p in pts {
            black_box(f(black_box(p)));
        }
    })
}

/// The pairs `(a[k], b[k])`, for [`each`].
fn zip<A: Copy, B: Copy>(a: &[A], b: &[B]) -> Vec<(A, B)> {
    a.iter().copied().zip(b.iter().copied()).collect()
}

/// `grp.bench_function(name, |b| b.iter(|| body))` for one-call-per-iteration entries.
macro_rules! once {
    ($grp:expr, $name:expr, $body:expr) => {
        $grp.bench_function($name, |b| b.iter(|| black_box($body)))
    };
}

/// Direct G (modified, by quadrature) at every compiled node count.
fn g_direct<T: Real>(c: &mut Criterion) {
    let (ti, tr) = angle_pairs::<T>(BATCH);
    let pairs = zip(&ti, &tr);
    let mut grp = c.benchmark_group(format!("g_direct_{}", type_tag::<T>()));
    grp.throughput(Throughput::Elements(BATCH as u64));
    macro_rules! at {
        ($($n:literal),*) => {$(
            let g = ModifiedG::<T, GaussLegendre<$n>>::new(T::from_f64(SIGMA)).unwrap();
            grp.bench_function(BenchmarkId::from_parameter(format!("n{:02}", $n)), |b| {
                each(b, &pairs, |(a, r)| g.g(a, r))
            });
        )*};
    }
    at!(4, 6, 8, 10, 12, 16, 20, 24, 32);
    grp.finish();
}

/// Closed forms (Smith, Blinn) and the modified G from dot products, shader inputs.
fn g_closed<T: Real>(c: &mut Criterion) {
    let d = dots_pairs::<T>(BATCH);
    let m = beckmann_m_from_sigma(T::from_f64(SIGMA));
    let mut grp = c.benchmark_group(format!("g_closed_{}", type_tag::<T>()));
    grp.throughput(Throughput::Elements(BATCH as u64));
    grp.bench_function("smith_beckmann_correlated", |b| {
        each(b, &d, |x| Beckmann::g_correlated_cos(x.n_i, x.n_o, m))
    });
    grp.bench_function("smith_beckmann_separable", |b| {
        each(b, &d, |x| Beckmann::g_separable_cos(x.n_i, x.n_o, m))
    });
    grp.bench_function("blinn_dots", |b| each(b, &d, masking::g_blinn_dots));
    let g = ModifiedG::<T>::new(T::from_f64(SIGMA)).unwrap();
    grp.bench_function(format!("modified_dots_n{DEFAULT_NODES}"), |b| {
        each(b, &d, |x| g.g_dots(x))
    });
    grp.finish();
}

/// LUT lookups of G: the 3-D (θ, φ, σ) tables and the per-σ 2-D tables (f32 by design), each
/// in its accuracy tier (Catmull–Rom) and its speed tier (linear).
fn g_lut(c: &mut Criterion) {
    let (ti, tr) = angle_pairs::<f32>(BATCH);
    let pairs = zip(&ti, &tr);
    let mut grp = c.benchmark_group("g_lut");
    grp.throughput(Throughput::Elements(BATCH as u64));
    for (id, asset) in [("table3d", G3_ASSET), ("table3d_linear", G3_LINEAR_ASSET)] {
        if let Some(bytes) = read_asset(asset) {
            let t = GTable3::parse(&bytes).unwrap();
            let s = SIGMA as f32;
            grp.bench_function(id, |b| each(b, &pairs, |(a, r)| t.g(a, r, s)));
        }
    }
    for (id, asset) in [
        ("table2d_sigma0.3", G2_ASSET),
        ("table2d_sigma0.3_linear", G2_LINEAR_ASSET),
    ] {
        if let Some(bytes) = read_asset(asset) {
            let t = GTable::parse(&bytes).unwrap();
            grp.bench_function(id, |b| each(b, &pairs, |(a, r)| t.g(a, r)));
        }
    }
    grp.finish();
}

/// Every BRDF model: evaluation at BATCH direction pairs, importance sampling of BATCH wi.
fn models(c: &mut Criterion) {
    type T = f32;
    let wi = directions::<T>(BATCH);
    let mut wo = directions::<T>(BATCH + 13);
    wo.drain(..13);
    let us: Vec<[T; 2]> = (0..BATCH)
        .map(|k| {
            let (a, b) = r2(k + 500);
            [a as T, b as T]
        })
        .collect();
    let wio = zip(&wi, &wo);
    let wou = zip(&wo, &us);
    let rgb = |r: f64, g: f64, b: f64| Rgb::new(r as T, g as T, b as T);
    let (kd, ks) = (rgb(0.5, 0.4, 0.3), rgb(0.04, 0.04, 0.04));
    // Every model of the catalogue at its defaults, then the G variants of Cook–Torrance.
    let mut list: Vec<(&str, Box<dyn Brdf<T>>)> = brdf_core::catalogue::MODELS
        .iter()
        .map(|m| {
            let b: Box<dyn Brdf<T>> = Box::new(m.build::<T>(&m.defaults::<T>()).unwrap());
            (m.name, b)
        })
        .collect();
    list.extend([
        (
            "cook-torrance/modified-g",
            Box::new(CookTorrance::new(kd, ks, 0.3, 0.04, GeometricTerm::Modified).unwrap())
                as Box<dyn Brdf<T>>,
        ),
        (
            "cook-torrance/smith",
            Box::new(CookTorrance::new(kd, ks, 0.3, 0.04, GeometricTerm::SmithCorrelated).unwrap()),
        ),
        (
            "cook-torrance/smith-visible-normals",
            Box::new(
                CookTorrance::new(kd, ks, 0.3, 0.04, GeometricTerm::SmithCorrelated)
                    .unwrap()
                    .with_sampling(MicrofacetSampling::VisibleNormals),
            ),
        ),
    ]);
    let mut ev = c.benchmark_group(format!("model_eval_{}", type_tag::<T>()));
    ev.throughput(Throughput::Elements(BATCH as u64));
    for (name, m) in &list {
        ev.bench_function(*name, |b| each(b, &wio, |(a, o)| m.eval(a, o)));
    }
    for gt in GeometricTerm::ALL {
        let ts =
            TorranceSparrow::<T>::new(SIGMA as T, gt, Fresnel::schlick(0.04).unwrap(), 1.0, 0.2)
                .unwrap();
        ev.bench_function(format!("torrance_sparrow_{}", gt.name()), |b| {
            each(b, &wio, |(a, o)| ts.eval(a, o))
        });
    }
    ev.finish();
    let mut sm = c.benchmark_group(format!("model_sample_{}", type_tag::<T>()));
    sm.throughput(Throughput::Elements(BATCH as u64));
    for (name, m) in &list {
        sm.bench_function(*name, |b| each(b, &wou, |(o, u)| m.sample(o, u)));
    }
    sm.finish();
}

/// DFG: table lookup, Karis's fit, the split-sum integral and the directional albedo.
fn dfg(c: &mut Criterion) {
    let pts = mu_roughness(BATCH);
    let pts32: Vec<(f32, f32)> = pts.iter().map(|&(m, r)| (m as f32, r as f32)).collect();
    let mut grp = c.benchmark_group("dfg");
    grp.throughput(Throughput::Elements(BATCH as u64));
    for (name, asset) in [("lut_f32", DFG_ASSET), ("lut_linear_f32", DFG_LINEAR_ASSET)] {
        if let Some(bytes) = read_asset(asset) {
            let t = DfgTable::parse(&bytes).unwrap();
            grp.bench_function(name, |b| each(b, &pts32, |(m, r)| t.ab(m, r)));
        }
    }
    grp.bench_function("karis_approx_f32", |b| {
        each(b, &pts32, |(m, r)| env_brdf_approx(m, r))
    });
    grp.finish();
    dfg_direct(c, &pts[..4]);
}

/// The integrals behind the DFG table (slow: 4 points per iteration).
fn dfg_direct(c: &mut Criterion, few: &[(f64, f64)]) {
    let mut slow = c.benchmark_group("dfg_direct");
    slow.throughput(Throughput::Elements(few.len() as u64));
    slow.sample_size(10);
    slow.bench_function("split_sum_f64", |b| {
        each(b, few, |(m, r)| dfg_ggx::<f64, OuterRule, InnerRule>(m, r))
    });
    slow.bench_function("split_sum_f32", |b| {
        each(b, few, |(m, r)| {
            dfg_ggx::<f32, OuterRule, InnerRule>(m as f32, r as f32)
        })
    });
    let models: Vec<(f64, Ggx<f64>)> = few
        .iter()
        .map(|&(m, r)| {
            let a = alpha_from_perceptual(r).max(1e-4);
            let g = Ggx::new(
                Rgb::splat(1.0),
                a,
                SmithForm::Correlated,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap();
            (m, g)
        })
        .collect();
    slow.bench_function("directional_albedo_f64", |b| {
        b.iter(|| {
            for (m, g) in &models {
                let wo = Vec3::new((1.0 - m * m).sqrt(), 0.0, *m);
                black_box(albedo::directional_albedo(g, black_box(wo)));
            }
        })
    });
    slow.finish();
}

/// Batch entry points over BATCH_LEN elements.
fn batches<T: brdf_core::batch::BatchReal>(c: &mut Criterion) {
    let (ti, tr) = angle_pairs::<T>(BATCH_LEN);
    let d = dots_pairs::<T>(BATCH_LEN);
    let n_i: Vec<T> = d.iter().map(|x| x.n_i).collect();
    let n_o: Vec<T> = d.iter().map(|x| x.n_o).collect();
    let i_o: Vec<T> = d.iter().map(|x| x.i_o).collect();
    let soa = DotsSoa {
        n_i: &n_i,
        n_o: &n_o,
        i_o: &i_o,
    };
    let mut out = vec![T::ZERO; BATCH_LEN];
    let g = ModifiedG::<T>::new(T::from_f64(SIGMA)).unwrap();
    let m = beckmann_m_from_sigma(T::from_f64(SIGMA));
    let alpha = T::from_f64(0.3);
    let ts = TorranceSparrow::<T>::new(
        T::from_f64(SIGMA),
        GeometricTerm::SmithCorrelated,
        Fresnel::schlick(T::from_f64(0.04)).unwrap(),
        T::ONE,
        T::from_f64(0.2),
    )
    .unwrap();
    let mut grp = c.benchmark_group(format!("batch_{}", type_tag::<T>()));
    grp.throughput(Throughput::Elements(BATCH_LEN as u64));
    once!(
        grp,
        "g_modified",
        batch::g_modified(&g, black_box(&ti), &tr, &mut out)
    );
    once!(
        grp,
        "g_modified_dots",
        batch::g_modified_dots(&g, black_box(soa), &mut out)
    );
    once!(
        grp,
        "g_blinn_dots",
        batch::g_blinn_dots(black_box(soa), &mut out)
    );
    once!(
        grp,
        "g_smith_beckmann_correlated",
        batch::g_smith_beckmann_correlated(black_box(&n_i), &n_o, m, &mut out)
    );
    once!(
        grp,
        "g_smith_ggx_correlated",
        batch::g_smith_ggx_correlated(black_box(&n_i), &n_o, alpha, &mut out)
    );
    once!(
        grp,
        "v_smith_ggx_correlated",
        batch::v_smith_ggx_correlated(black_box(&n_i), &n_o, alpha, &mut out)
    );
    once!(
        grp,
        "torrance_sparrow_smith",
        batch::torrance_sparrow(&ts, black_box(soa), &mut out)
    );
    batch_eval::<T>(&mut grp);
    grp.finish();
}

/// The batch BRDF evaluation (GGX, SoA directions).
fn batch_eval<T: brdf_core::batch::BatchReal>(grp: &mut Group) {
    let wi = directions::<T>(BATCH_LEN);
    let wo: Vec<Vec3<T>> = directions::<T>(BATCH_LEN + 9).split_off(9);
    let comp =
        |v: &[Vec3<T>], k: usize| -> Vec<T> { v.iter().map(|w| [w.x, w.y, w.z][k]).collect() };
    let (wix, wiy, wiz) = (comp(&wi, 0), comp(&wi, 1), comp(&wi, 2));
    let (wox, woy, woz) = (comp(&wo, 0), comp(&wo, 1), comp(&wo, 2));
    let mut out = vec![T::ZERO; BATCH_LEN];
    let (mut o1, mut o2) = (vec![T::ZERO; BATCH_LEN], vec![T::ZERO; BATCH_LEN]);
    let alpha = T::from_f64(0.3);
    let ggx = Ggx::new(
        Rgb::splat(T::from_f64(0.04)),
        alpha,
        SmithForm::Correlated,
        MicrofacetSampling::VisibleNormals,
    )
    .unwrap();
    let wi = Vec3Soa {
        x: &wix,
        y: &wiy,
        z: &wiz,
    };
    let wo = Vec3Soa {
        x: &wox,
        y: &woy,
        z: &woz,
    };
    once!(
        grp,
        "ggx_eval",
        batch::brdf_eval(&ggx, black_box(wi), wo, [&mut out, &mut o1, &mut o2])
    );
}

/// Parse + validate (CRC included) of the default assets: the no_std view and the std loader.
fn lut_parse(c: &mut Criterion) {
    let mut grp = c.benchmark_group("lut_parse");
    for name in [G3_ASSET, G2_ASSET, DFG_ASSET] {
        let Some(bytes) = read_asset(name) else {
            continue;
        };
        grp.throughput(Throughput::Bytes(bytes.len() as u64));
        grp.bench_function(format!("view/{name}"), |b| {
            b.iter(|| black_box(LutView::parse(black_box(&bytes)).unwrap().kind()))
        });
        grp.bench_function(format!("std_loader/{name}"), |b| {
            b.iter(|| {
                let lut = brdf_lut::Lut::from_bytes(black_box(bytes.clone())).unwrap();
                black_box(lut.bytes().len())
            })
        });
    }
    grp.finish();
}

/// The LUT-layer figures under fixed names (compared across changes): the plain bilinear
/// floor, the prepared no_std tables, the std crate's owned tables loaded from files, the
/// analytic DFG fit and the direct G, over the same inputs as the callgrind harness.
fn lut_targets(c: &mut Criterion) {
    let (ti, tr) = angle_pairs::<f32>(BATCH);
    let angles = zip(&ti, &tr);
    let pts: Vec<(f32, f32)> = mu_roughness(BATCH)
        .iter()
        .map(|&(m, r)| (m as f32, r as f32))
        .collect();
    let mut grp = c.benchmark_group("lut");
    grp.throughput(Throughput::Elements(BATCH as u64));
    let floor = FloorBilinear2::new();
    grp.bench_function("floor_bilinear2", |b| {
        each(b, &pts, |(m, r)| floor.fetch(m, r))
    });
    if let Some(bytes) = read_asset(DFG_LINEAR_ASSET) {
        let t = DfgTable::parse(&bytes).unwrap();
        grp.bench_function("dfg_lut", |b| each(b, &pts, |(m, r)| t.ab(m, r)));
        let t = brdf_lut::Lut::from_path(assets_dir().join(DFG_LINEAR_ASSET)).unwrap();
        grp.bench_function("dfg_lut_std", |b| {
            each(b, &pts, |(m, r)| t.dfg(m, r).unwrap())
        });
    }
    grp.bench_function("dfg_karis", |b| {
        each(b, &pts, |(m, r)| env_brdf_approx(m, r))
    });
    if let Some(bytes) = read_asset(G2_LINEAR_ASSET) {
        let t = GTable::parse(&bytes).unwrap();
        grp.bench_function("g_lut2d_linear", |b| each(b, &angles, |(a, r)| t.g(a, r)));
        let t = brdf_lut::Lut::from_path(assets_dir().join(G2_LINEAR_ASSET)).unwrap();
        grp.bench_function("g_lut2d_linear_std", |b| {
            each(b, &angles, |(a, r)| t.g(a, r, SIGMA as f32).unwrap())
        });
    }
    if let Some(bytes) = read_asset(G3_LINEAR_ASSET) {
        let t = GTable3::parse(&bytes).unwrap();
        grp.bench_function("g_lut3d_linear", |b| {
            each(b, &angles, |(a, r)| t.g(a, r, SIGMA as f32))
        });
    }
    lut_albedo(&mut grp, &pts);
    lut_batches(&mut grp, (&ti, &tr), &pts);
    let g = ModifiedG::<f32>::new(SIGMA as f32).unwrap();
    grp.bench_function("g_direct_f32", |b| each(b, &angles, |(a, r)| g.g(a, r)));
    grp.finish();
}

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

/// The albedo tables' scalar lookups, E(μ, r) and E_avg(r).
fn lut_albedo(grp: &mut Group, pts: &[(f32, f32)]) {
    if let Some(bytes) = read_asset(E_ASSET) {
        let t = brdf_lut::AlbedoTable::parse(&bytes[..]).unwrap();
        grp.bench_function("e_lut", |b| each(b, pts, |(m, r)| t.e(m, r)));
    }
    if let Some(bytes) = read_asset(EAVG_ASSET) {
        let t = brdf_lut::AverageAlbedoTable::parse(&bytes[..]).unwrap();
        grp.bench_function("eavg_lut", |b| each(b, pts, |(_, r)| t.e_avg(r)));
    }
}

/// Batch entries: one call over all BATCH inputs per iteration (same element count).
fn lut_batches(grp: &mut Group, (ti, tr): (&[f32], &[f32]), pts: &[(f32, f32)]) {
    let mu: Vec<f32> = pts.iter().map(|p| p.0).collect();
    let rr: Vec<f32> = pts.iter().map(|p| p.1).collect();
    let (mut o1, mut o2) = (vec![0f32; BATCH], vec![0f32; BATCH]);
    if let Some(bytes) = read_asset(G2_LINEAR_ASSET) {
        let t = GTable::parse(&bytes[..]).unwrap();
        once!(
            grp,
            "g_lut2d_linear_batch",
            t.g_batch(black_box(ti), tr, &mut o1)
        );
    }
    if let Some(bytes) = read_asset(G3_LINEAR_ASSET) {
        let t = GTable3::parse(&bytes[..]).unwrap();
        let s = SIGMA as f32;
        once!(
            grp,
            "g_lut3d_linear_batch",
            t.g_batch(black_box(ti), tr, s, &mut o1)
        );
    }
    if let Some(bytes) = read_asset(DFG_LINEAR_ASSET) {
        let t = DfgTable::parse(&bytes[..]).unwrap();
        once!(
            grp,
            "dfg_lut_batch",
            t.ab_batch(black_box(&mu), &rr, &mut o1, &mut o2)
        );
    }
    if let Some(bytes) = read_asset(E_ASSET) {
        let t = brdf_lut::AlbedoTable::parse(&bytes[..]).unwrap();
        once!(grp, "e_lut_batch", t.e_batch(black_box(&mu), &rr, &mut o1));
    }
    if let Some(bytes) = read_asset(EAVG_ASSET) {
        let t = brdf_lut::AverageAlbedoTable::parse(&bytes[..]).unwrap();
        once!(
            grp,
            "eavg_lut_batch",
            t.e_avg_batch(black_box(&rr), &mut o1)
        );
    }
}

fn all(c: &mut Criterion) {
    lut_targets(c);
    g_direct::<F32>(c);
    g_direct::<f64>(c);
    g_closed::<F32>(c);
    g_closed::<f64>(c);
    g_lut(c);
    batches::<f32>(c);
    batches::<f64>(c);
    models(c);
    dfg(c);
    lut_parse(c);
}

criterion_group!(benches, all);
criterion_main!(benches);

//! Measurements (ignored, run with `--release --ignored --nocapture`): the rough-glass
//! albedo by the generator's ring rule (`glass_e`, at the generator's tolerance) against the
//! cap integrator (`glass_e_cap`, 100× tighter) at seeded random points
//! (`measure_random_points`: GLASS_N points per side, μ log-uniform in [cos 89°, 1], r
//! uniform, α = r², η uniform in [1/3, 1] and [1, 3]; or the one point GLASS_P = "μ,r,η"),
//! printed with a summary (largest difference, points beyond the two estimates, evaluations
//! and time per node); an independent brute-force value (`brute`, P = "μ,r,η") to settle a
//! disagreement; and the default 32³ table's generation (`time_default_table`).
#![cfg(feature = "generate")]

use brdf_lut::generate::glass::{glass_e, glass_e_cap};
use brdf_lut::generate::INTEGRATION_TOL;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

#[test]
#[ignore = "a measurement"]
fn measure_random_points() {
    let n: usize = std::env::var("GLASS_N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let mut g = Pcg64::seed_from_u64(0x5eed_61a5);
    let mu_lo = 89f64.to_radians().cos();
    let mut pts = vec![
        (0.0314, 0.684, 0.349),
        (0.0314, 0.684f64.sqrt(), 0.349),
        (
            0.718_750_701_722_704_4,
            0.390_912_995_894_539_43,
            0.629_576_074_131_773,
        ),
        (
            0.605_288_935_154_154_2,
            0.948_475_569_600_138_7,
            0.464_067_523_485_068,
        ),
    ];
    for side in 0..2 {
        for _ in 0..n {
            let mu = mu_lo * (1.0 / mu_lo).powf(g.random::<f64>());
            let r = g.random::<f64>();
            let eta = if side == 0 {
                1.0 / 3.0 + g.random::<f64>() * (2.0 / 3.0)
            } else {
                1.0 + 2.0 * g.random::<f64>()
            };
            pts.push((mu, r, eta));
        }
    }
    if let Ok(p) = std::env::var("GLASS_P") {
        let v: Vec<f64> = p.split(',').map(|x| x.parse().unwrap()).collect();
        pts = vec![(v[0], v[1], v[2])];
    }
    let (mut worst, mut worst_ratio, mut bad) = (0f64, 0f64, 0usize);
    let (mut evals, mut secs) = ([0u64; 2], [0f64; 2]);
    for (mu, r, eta) in pts.iter().copied() {
        let t0 = std::time::Instant::now();
        let (v, w) = glass_e(mu, r * r, eta, INTEGRATION_TOL);
        let dt = t0.elapsed().as_secs_f64();
        let side = usize::from(eta >= 1.0);
        evals[side] += w.evals;
        secs[side] += dt;
        let (rf, wr) = glass_e_cap(mu, r * r, eta, INTEGRATION_TOL / 100.0);
        let d = (v[0] - rf[0]).abs().max((v[1] - rf[1]).abs());
        worst = worst.max(d);
        worst_ratio = worst_ratio.max(d / (w.error + wr.error));
        bad += usize::from(d > w.error + wr.error);
        println!(
            "P {mu:.17e} {r:.17e} {eta:.17e} {:.17e} {:.17e} {:.3e} {} {:.4e} {:.17e} {:.17e} {:.3e} diff {d:.3e}",
            v[0], v[1], w.error, w.evals, dt, rf[0], rf[1], wr.error
        );
    }
    let n = (pts.len() / 2).max(1) as f64;
    println!(
        "{} points: max |rings − cap| {worst:.3e}, max ratio to the two estimates {worst_ratio:.3}, \
         {bad} beyond; inside {:.0} evals {:.3} ms per node, outside {:.0} evals {:.3} ms",
        pts.len(),
        evals[0] as f64 / n,
        secs[0] / n * 1e3,
        evals[1] as f64 / n,
        secs[1] / n * 1e3
    );
}
/// The midpoint rule on n × n grids (n = 1000 … 8000) in the cap's (θ, φ), the integrands
/// written directly from F, G1 and the refraction: no cuts, no adaptivity. Its error falls
/// as O(1/n²) away from the integrands' edges and O(n^-1.5) across them; the spread of the
/// last values shows it.
#[test]
#[ignore = "a measurement"]
fn brute() {
    use brdf_core::fresnel::f_dielectric;
    use brdf_core::geometry::Vec3;
    use brdf_core::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
    use brdf_core::microfacet::{Distribution as _, TrowbridgeReitz};
    use brdf_core::models::rough_dielectric::refract;
    let v: Vec<f64> = std::env::var("P")
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let (mu, r, eta) = (v[0], v[1], v[2]);
    let alpha = r * r;
    let dist = TrowbridgeReitz::isotropic(alpha).unwrap();
    let map = GgxVisibleCap::new(alpha, mu);
    let sv = ((1.0 - mu) * (1.0 + mu)).sqrt();
    let wo = Vec3::new(sv, 0.0, mu);
    for n in [1000usize, 2000, 4000, 8000] {
        let tm = map.theta_max();
        let (dt, dp) = (tm / n as f64, std::f64::consts::PI / n as f64);
        let mut sum = [0f64; 2];
        for j in 0..n {
            let p = (j as f64 + 0.5) * dp;
            let (sp, cp) = p.sin_cos();
            for i in 0..n {
                let t = (i as f64 + 0.5) * dt;
                let (st, ct) = t.sin_cos();
                let Some(h) = map.normal(ct, st, cp, sp) else {
                    continue;
                };
                let c = wo.dot(h);
                if c.is_nan() || c <= 0.0 {
                    continue;
                }
                let wi = wo.reflect(h);
                if wi.z > 0.0 {
                    sum[0] += f_dielectric(eta, c) * dist.g1(wi) * st;
                }
                if let Some(tt) = refract(wo, h, c, eta) {
                    if tt.z < 0.0 {
                        let up = Vec3::new(tt.x, tt.y, -tt.z);
                        sum[1] += (1.0 - f_dielectric(eta, c)) * dist.g1(up) * st;
                    }
                }
            }
        }
        let m = map.measure() * dt * dp;
        println!("n {n}: R {:.10} T {:.10}", sum[0] * m, sum[1] * m);
    }
}

/// Wall time and evaluations per node of the default 32³ glass-e table on one side
/// (GLASS_SIDE = "inside": η ∈ [1/3, 1], else η ∈ [1, 3]); threads from RAYON_NUM_THREADS.
/// GLASS_KIND = "avg": the 32² glass-e-avg table instead.
/// Run under `/usr/bin/time` for the CPU time (the wall time depends on the machine's load).
#[test]
#[ignore = "a measurement"]
fn time_default_table() {
    use brdf_lut::generate::{generate, Distribution, Kind, Masking, Spec};
    let inside = std::env::var("GLASS_SIDE").is_ok_and(|s| s == "inside");
    let (lo, hi) = if inside { (1.0 / 3.0, 1.0) } else { (1.0, 3.0) };
    let avg = std::env::var("GLASS_KIND").is_ok_and(|s| s == "avg");
    let kind = if avg {
        Kind::GlassAverageAlbedo
    } else {
        Kind::GlassAlbedo
    };
    let mut spec = Spec::new(kind, Distribution::Ggx, Masking::SmithSeparable);
    if let Some(a) = spec.axes.last_mut() {
        (a.lo, a.hi) = (lo, hi);
    }
    let t0 = std::time::Instant::now();
    let g = generate(&spec, &|_| {}).unwrap();
    let secs = t0.elapsed().as_secs_f64();
    let nodes: usize = spec.axes.iter().map(|a| a.count as usize).product();
    println!(
        "{kind:?} η ∈ [{lo:.3}, {hi}]: {nodes} nodes in {secs:.2} s wall on {} threads, {:.0} evals/node, bound {:e}",
        brdf_lut::generate::threads(),
        g.evals as f64 / nodes as f64,
        g.integration
    );
}

/// E_avg at a sample of (α, η), both sides: value, estimate and evaluations (`glass_e_avg`
/// at the generator's tolerance), printed.
#[test]
#[ignore = "a measurement"]
fn average_points() {
    use brdf_lut::generate::glass::glass_e_avg;
    for &alpha in &[1e-4, 0.01, 0.1, 0.3, 0.6, 1.0] {
        for &eta in &[1.0 / 3.0, 0.7, 0.99, 1.01, 1.5, 3.0] {
            let t0 = std::time::Instant::now();
            let (v, w) = glass_e_avg(alpha, eta, 2e-6);
            println!(
                "α {alpha} η {eta:.3}: R {:.9} T {:.9} est {:.2e} evals {} {:.0} ms",
                v[0],
                v[1],
                w.error,
                w.evals,
                t0.elapsed().as_secs_f64() * 1e3
            );
        }
    }
}

/// One E_avg, P = "α,η,tol": values and work, printed (to compare tolerances).
#[test]
#[ignore = "a measurement"]
fn average_one() {
    let v: Vec<f64> = std::env::var("P")
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let (r, w) = brdf_lut::generate::glass::glass_e_avg(v[0], v[1], v[2]);
    println!("{r:?} {w:?}");
}

//! Probe (temporary): evals/node and values at fixed random points.
#![cfg(feature = "generate")]
use brdf_lut::generate::glass::glass_e;
use std::io::Write;

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn points(n: usize, seed: u64) -> Vec<(f64, f64, f64)> {
    let mut rng = Rng(seed);
    let lo = (89f64.to_radians().cos()).ln();
    (0..n)
        .map(|k| {
            let mu = (lo * rng.next()).exp();
            let r = rng.next();
            let e = if k % 2 == 0 { 1.0 + 2.0 * rng.next() } else { 1.0 / (1.0 + 2.0 * rng.next()) };
            (mu, r, e)
        })
        .collect()
}

#[test]
#[ignore]
fn probe() {
    let n: usize = std::env::var("N").ok().and_then(|s| s.parse().ok()).unwrap_or(100);
    let tol: f64 = std::env::var("TOL").ok().and_then(|s| s.parse().ok()).unwrap_or(2e-6);
    let out = std::env::var("OUT").ok();
    let inp = std::env::var("IN").ok();
    let refs: Vec<[f64; 2]> = inp
        .map(|p| {
            std::fs::read_to_string(p)
                .unwrap()
                .lines()
                .map(|l| {
                    let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
                    [v[3], v[4]]
                })
                .collect()
        })
        .unwrap_or_default();
    let mut f = out.map(|p| std::fs::File::create(p).unwrap());
    let t0 = std::time::Instant::now();
    let (mut ev, mut worst, mut west) = ([0u64; 2], 0f64, 0f64);
    let mut worst_at = (0.0, 0.0, 0.0);
    for (k, &(mu, r, eta)) in points(n, 0x5EED).iter().enumerate() {
        let (v, w) = glass_e(mu, r * r, eta, tol);
        ev[k % 2] += w.evals;
        west = west.max(w.error);
        if let Some(rf) = refs.get(k) {
            let e = (v[0] - rf[0]).abs().max((v[1] - rf[1]).abs());
            if e > worst {
                worst = e;
                worst_at = (mu, r, eta);
            }
        }
        if let Some(f) = f.as_mut() {
            writeln!(f, "{mu:e} {r:e} {eta:e} {:.17e} {:.17e} {:e} {}", v[0], v[1], w.error, w.evals).unwrap();
        }
    }
    println!(
        "n {n} tol {tol:e}: {:.2} s, evals/node outside {:.0} inside {:.0}, max est {west:e}, max err vs IN {worst:e} at {worst_at:?}",
        t0.elapsed().as_secs_f64(),
        ev[0] as f64 / (n / 2) as f64,
        ev[1] as f64 / (n / 2) as f64
    );
}

#[test]
#[ignore]
fn brute() {
    use brdf_core::fresnel::f_dielectric;
    use brdf_core::geometry::Vec3;
    use brdf_core::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
    use brdf_core::microfacet::{Distribution as _, TrowbridgeReitz};
    use brdf_core::models::rough_dielectric::refract;
    let v: Vec<f64> = std::env::var("P").unwrap().split(',').map(|x| x.parse().unwrap()).collect();
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
                let Some(h) = map.normal(ct, st, cp, sp) else { continue };
                let c = wo.dot(h);
                if !(c > 0.0) { continue; }
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

#[test]
#[ignore]
fn cuts() {
    use brdf_core::geometry::Vec3;
    use brdf_core::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
    use brdf_core::models::rough_dielectric::refract;
    use brdf_core::split_sum::converged::ggx_cap_row_form;
    let v: Vec<f64> = std::env::var("P").unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    let (mu, r, eta) = (v[0], v[1], v[2]);
    let alpha = r * r;
    let map = GgxVisibleCap::new(alpha, mu);
    let sv = ((1.0 - mu) * (1.0 + mu)).sqrt();
    let wo = Vec3::new(sv, 0.0, mu);
    let (x, z) = (alpha * sv, mu);
    let len = (x * x + z * z).sqrt();
    let vv = (x / len, z / len);
    let k = (1.0 - eta) * (1.0 + eta);
    let m2 = mu * mu;
    let ms = [
        [sv * sv - k, -k, mu * mu - k, sv * mu],
        [-m2, -m2, (eta - 1.0) * (eta + 1.0) + m2, mu * sv],
    ];
    let tm = map.theta_max();
    let n = 20000;
    for j in 0..100 {
        let p = (j as f64 + 0.5) * std::f64::consts::PI / 100.0;
        let (sp, cp) = p.sin_cos();
        let sup = |t: f64| {
            let (st, ct) = t.sin_cos();
            let Some(h) = map.normal(ct, st, cp, sp) else { return -1.0 };
            let c = wo.dot(h);
            if !(c > 0.0) { return -1.0; }
            let tir = eta * eta - 1.0 + c * c;
            if !(tir > 0.0) { return tir; }
            match refract(wo, h, c, eta) { Some(t) => tir.min(-t.z), None => -1.0 }
        };
        let forms: Vec<[f64; 6]> = ms.iter().map(|m| ggx_cap_row_form(*m, alpha, vv, cp, sp)).collect();
        let pf = |k: &[f64; 6], t: f64| { let (s, c) = t.sin_cos(); k[0] + k[1]*c + k[2]*s + k[3]*c*c + k[4]*s*s + k[5]*s*c };
        let (mut sc, mut fc) = (vec![], vec![]);
        let mut prev = None::<(bool, Vec<bool>)>;
        for i in 0..=n {
            let t = tm * i as f64 / n as f64;
            let s = sup(t) > 0.0;
            let f: Vec<bool> = forms.iter().map(|k| pf(k, t) > 0.0).collect();
            if let Some((ps, pfv)) = &prev {
                if *ps != s { sc.push(t); }
                for q in 0..2 { if pfv[q] != f[q] { fc.push((q, t)); } }
            }
            prev = Some((s, f));
        }
        let miss: Vec<f64> = sc.iter().copied().filter(|t| !fc.iter().any(|(_, u)| (u - t).abs() < 2.0 * tm / n as f64)).collect();
        if !miss.is_empty() { println!("phi {p:.4}: support changes {sc:?} forms {fc:?}"); }
    }
}

#[test]
#[ignore]
fn rows() {
    use brdf_core::fresnel::f_dielectric;
    use brdf_core::geometry::Vec3;
    use brdf_core::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
    use brdf_core::microfacet::{Distribution as _, TrowbridgeReitz};
    use brdf_core::models::rough_dielectric::refract;
    let v: Vec<f64> = std::env::var("P").unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    let (mu, r, eta) = (v[0], v[1], v[2]);
    let alpha = r * r;
    let dist = TrowbridgeReitz::isotropic(alpha).unwrap();
    let map = GgxVisibleCap::new(alpha, mu);
    let sv = ((1.0 - mu) * (1.0 + mu)).sqrt();
    let wo = Vec3::new(sv, 0.0, mu);
    let tm = map.theta_max();
    let n = 200000;
    for j in 0..200 {
        let p = (j as f64 + 0.5) * std::f64::consts::PI / 200.0;
        let (sp, cp) = p.sin_cos();
        let mut s = 0.0;
        for i in 0..n {
            let t = (i as f64 + 0.5) * tm / n as f64;
            let (st, ct) = t.sin_cos();
            let Some(h) = map.normal(ct, st, cp, sp) else { continue };
            let c = wo.dot(h);
            if !(c > 0.0) { continue; }
            if let Some(tt) = refract(wo, h, c, eta) {
                if tt.z < 0.0 {
                    let up = Vec3::new(tt.x, tt.y, -tt.z);
                    s += (1.0 - f_dielectric(eta, c)) * dist.g1(up) * st;
                }
            }
        }
        s *= tm / n as f64;
        let (q, np) = brdf_lut::generate::glass::debug_rows(mu, alpha, eta, p, 1e-10);
        if (q[0] - s).abs() > 1e-7 { println!("phi {p:.5} brute {s:.9} row {:.9} pieces {np}", q[0]); }
    }
}

#[test]
#[ignore]
fn phis() {
    use brdf_core::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
    let v: Vec<f64> = std::env::var("P").unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    let (mu, r, eta) = (v[0], v[1], v[2]);
    let alpha = r * r;
    let map = GgxVisibleCap::new(alpha, mu);
    let n = 4000;
    let mut s = 0.0;
    let mut prevn = 99;
    for j in 0..n {
        let p = (j as f64 + 0.5) * std::f64::consts::PI / n as f64;
        let (q, np) = brdf_lut::generate::glass::debug_rows(mu, alpha, eta, p, 1e-10);
        if np != prevn { println!("phi {p:.5} pieces {np}"); prevn = np; }
        s += q[0];
    }
    s *= std::f64::consts::PI / n as f64 * map.measure();
    let (g, w) = glass_e(mu, alpha, eta, 5e-9);
    println!("phi-sum T {s:.10} glass_e T {:.10} est {:e}", g[1], w.error);
}

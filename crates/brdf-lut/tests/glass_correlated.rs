//! Blender Cycles' rough-glass integrand (`brdf_lut::generate::glass::correlated`): the
//! height-correlated albedo against closed forms (η = 1: straight refraction; the α floor:
//! a smooth interface), against an independent brute-force integral of Cycles' own eval
//! formula over outgoing directions, and against values of the tables Cycles ships.
#![cfg(feature = "generate")]

use brdf_lut::generate::glass::correlated::{glass_e_avg_correlated, glass_e_correlated};
use brdf_lut::generate::glass::glass_e;
use brdf_lut::generate::INTEGRATION_TOL;
use std::f64::consts::PI;

/// GGX Smith Λ at polar cosine z (Heitz 2014, eq. 72): (√(1 + α²(1 − z²)/z²) − 1)/2.
fn lambda(z: f64, alpha: f64) -> f64 {
    let z = z.abs();
    ((1.0 + alpha * alpha * (1.0 - z * z) / (z * z)).sqrt() - 1.0) / 2.0
}

/// Exact unpolarised dielectric Fresnel reflectance at cos c for relative index η (Walter
/// et al. 2007, eq. 22), 1 under total internal reflection: brdf-core's, not the ring
/// rule's inlined copy.
fn fresnel(c: f64, eta: f64) -> f64 {
    brdf_core::fresnel::f_dielectric(eta, c)
}

/// At η = 1 every facet refracts straight through (t = −wo, F = 0), so R = 0 and
/// T = E[G2/G1(wo)] = (1 + Λ(μ))/(1 + 2Λ(μ)) (the weight is constant, the visible normals
/// integrate to 1). Also at η = 1 ± 1e-9 (the inside path with its TIR cone of cosine
/// √(1 − η²) = 4.5e-5: its visible measure and the bending there are O(1 − η²) = 2e-9).
/// Tolerance 4e-6: two channels at the integrator's 2e-6.
#[test]
fn eta_one_is_straight_refraction() {
    for eta in [1.0 - 1e-9, 1.0, 1.0 + 1e-9] {
        for mu in [0.05, 0.25, 0.5, 1.0] {
            for alpha in [0.05, 0.3, 0.7, 1.0] {
                let ([r, t], _) = glass_e_correlated(mu, alpha, eta, INTEGRATION_TOL);
                let l = lambda(mu, alpha);
                let want = (1.0 + l) / (1.0 + 2.0 * l);
                let at = format!("eta {eta}, mu {mu}, alpha {alpha}: R {r}, T {t}");
                assert!(r.abs() < 4e-6, "{at}");
                assert!((r + t - want).abs() < 4e-6, "{at}: want {want}");
            }
        }
    }
}

/// E_avg at η = 1: 2∫₀¹ (1 + Λ)/(1 + 2Λ) μ dμ = ½ + ∫₀¹ μ²/√(aμ² + b) dμ with a = 1 − α²,
/// b = α² (since 1 + 2Λ = √(aμ² + b)/μ), = ½ + 1/(2a) − b/(2a^{3/2}) ln((√a + 1)/√b)
/// (the standard antiderivative); at α = 1, 5/6. Tolerance 4e-6.
#[test]
fn eta_one_average_is_the_closed_form() {
    for alpha in [0.5f64, 0.8, 1.0] {
        let (a, b) = (1.0 - alpha * alpha, alpha * alpha);
        let want = if a == 0.0 {
            5.0 / 6.0
        } else {
            0.5 + 1.0 / (2.0 * a) - b / (2.0 * a.powf(1.5)) * ((a.sqrt() + 1.0) / b.sqrt()).ln()
        };
        let ([r, t], _) = glass_e_avg_correlated(alpha, 1.0, INTEGRATION_TOL);
        assert!(
            (r + t - want).abs() < 4e-6,
            "alpha {alpha}: {} vs {want}",
            r + t
        );
    }
}

/// At the α floor (α = 1e-8 is floored to 1e-4, as `glass_e`) the surface is smooth: R is
/// the exact Fresnel reflectance of μ (1 under total internal reflection) and R + T = 1,
/// from outside and inside, up to Cycles' ior extremes. Tolerance 1e-5: two channels at
/// the integrator's 2e-6 and the O(α²/μ²) = 4e-8 rough residue.
#[test]
fn alpha_floor_is_the_smooth_interface() {
    for ior in [1.0089, 1.5, 99.5] {
        for eta in [ior, 1.0 / ior] {
            for mu in [0.5, 0.8, 1.0] {
                let ([r, t], w) = glass_e_correlated(mu, 1e-8, eta, INTEGRATION_TOL);
                let f = fresnel(mu, eta);
                let at = format!("eta {eta}, mu {mu}: R {r}, T {t}, Fresnel {f}");
                assert!(w.error.is_finite(), "{at}");
                assert!((r - f).abs() < 1e-5, "{at}");
                assert!((r + t - 1.0).abs() < 1e-5, "{at}");
            }
        }
    }
}

/// (R, T) of Cycles' integrand by the midpoint rule on an n × n grid of the spherical cap
/// of GGX visible normals (brdf-core's `GgxVisibleCap`, Dupuy & Benyoub 2023: uniform on
/// the cap ⇔ h distributed as p(h)), the weights written directly from the rays:
/// F G2/G1(wo) where the reflected ray leaves above, (1 − F) G2/G1(wo) wherever the
/// refraction (brdf-core's `refract`) exists, G2/G1(wo) = (1 + Λ(μ))/(1 + Λ(μ) + Λ(|n·o|)).
/// No rings, no cuts, no adaptivity: tests/glass_measure.rs's `brute` with Cycles' weights.
fn brute(mu: f64, alpha: f64, eta: f64, n: usize) -> [f64; 2] {
    use brdf_core::geometry::Vec3;
    use brdf_core::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
    use brdf_core::models::rough_dielectric::refract;
    let map = GgxVisibleCap::new(alpha, mu);
    let wo = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
    let lv = lambda(mu, alpha);
    let w = |z: f64| (1.0 + lv) / (1.0 + lv + lambda(z, alpha));
    let (dt, dp) = (map.theta_max() / n as f64, PI / n as f64);
    let mut sum = [0f64; 2];
    for j in 0..n {
        let (sp, cp) = ((j as f64 + 0.5) * dp).sin_cos();
        for i in 0..n {
            let (st, ct) = ((i as f64 + 0.5) * dt).sin_cos();
            let Some(h) = map.normal(ct, st, cp, sp) else {
                continue;
            };
            let c = wo.dot(h);
            if c.is_nan() || c <= 0.0 {
                continue;
            }
            let l = wo.reflect(h);
            if l.z > 0.0 {
                sum[0] += fresnel(c, eta) * w(l.z) * st;
            }
            if let Some(t) = refract(wo, h, c, eta) {
                sum[1] += (1.0 - fresnel(c, eta)) * w(t.z) * st;
            }
        }
    }
    sum.map(|s| s * map.measure() * dt * dp)
}

/// The ring rule against [`brute`] at n = 1000 and 2000, outside and inside (TIR and rays
/// refracted upwards included), grazing to normal, α 0.1 … 1: each channel within
/// |brute(2000) − brute(1000)| (the midpoint rule's error at 2000 is below its last change
/// where it converges at order ≥ 1: O(n⁻²) away from the integrand's kinks, O(n^-1.5)
/// across them) + 4e-6 (the ring rule's 2e-6 and rounding). Measured: largest
/// |rings − brute(4000)| 4.7e-7 (μ = 0.05, α = 0.1), the others ≤ 7e-8; 3 s at n = 2000.
#[test]
fn rings_agree_with_brute_force() {
    for (mu, alpha, eta) in [
        (0.5, 0.5, 1.5),
        (0.2, 1.0, 1.2),
        (0.05, 0.1, 2.0),
        (0.8, 0.3, 1.0 / 1.5),
        (0.3, 0.8, 1.0 / 1.5),
        (0.15, 0.4, 0.95),
        (1.0 / 3.0, 4.0 / 9.0, 12.0 / 13.0),
    ] {
        let coarse = brute(mu, alpha, eta, 1000);
        let fine = brute(mu, alpha, eta, 2000);
        let (v, _) = glass_e_correlated(mu, alpha, eta, INTEGRATION_TOL);
        for c in 0..2 {
            let tol = (fine[c] - coarse[c]).abs() + 4e-6;
            assert!(
                (v[c] - fine[c]).abs() <= tol,
                "(mu, alpha, eta) = ({mu}, {alpha}, {eta}) channel {c}: rings {} brute {} \
                 (n = 1000: {}), tol {tol:e}",
                v[c],
                fine[c],
                coarse[c]
            );
        }
    }
}

/// Cycles' node coordinates (cycles_precompute.cpp): r, μ = clamp(i/15, 1e-4, 1), ior of z
/// node k = ior_from_F0(t⁴) = (1 + t²)/(1 − t²), t = clamp(k/15, 1e-4, 0.99).
fn cycles_ior(k: usize) -> f64 {
    let t = (k as f64 / 15.0).clamp(1e-4, 0.99);
    (1.0 + t * t) / (1.0 - t * t)
}

fn cycles_u(i: usize) -> f64 {
    (i as f64 / 15.0).clamp(1e-4, 1.0)
}

/// Values of Blender's shipped tables, blender/blender `intern/cycles/scene/shader.tables`
/// at commit 09cf4924cc65e989ffde4965b87302c0ec431c96: (inv, k, j, i, value) of
/// `table_ggx_glass_E` (inv = false) or `table_ggx_glass_inv_E` (inv = true) at flat index
/// i + 16 (j + 16 k), i.e. r = i/15, μ = j/15 (clamped to 1e-4), z node k; light inside
/// (η = 1/ior) for inv. Chosen across roughness, grazing to normal μ and ior 1.0089 … 4.6,
/// away from Cycles' singular paths (r = 1e-4, ior = 1).
const SHIPPED_E: [(bool, usize, usize, usize, f64); 25] = [
    (false, 1, 1, 15, 0.558556),
    (false, 1, 4, 15, 0.638515),
    (false, 1, 0, 15, 0.960025),
    (false, 1, 2, 9, 0.707130),
    (false, 9, 1, 15, 0.806635),
    (false, 9, 1, 5, 0.927944),
    (false, 9, 7, 10, 0.893583),
    (false, 9, 15, 15, 0.809330),
    (false, 9, 15, 3, 0.999679),
    (false, 13, 2, 4, 0.949106),
    (false, 13, 2, 15, 0.750826),
    (false, 13, 12, 13, 0.670705),
    (true, 1, 1, 15, 0.497139),
    (true, 1, 1, 4, 0.702110),
    (true, 1, 1, 8, 0.504458),
    (true, 1, 4, 15, 0.616216),
    (true, 1, 4, 4, 0.964275),
    (true, 1, 0, 15, 0.945694),
    (true, 2, 1, 15, 0.428417),
    (true, 2, 2, 8, 0.563787),
    (true, 2, 8, 15, 0.715942),
    (true, 3, 1, 15, 0.430697),
    (true, 3, 15, 15, 0.831849),
    (true, 3, 5, 10, 0.655004),
    (true, 4, 1, 5, 0.873821),
];

/// The same file's `table_ggx_glass_Eavg` (light entering) at flat index i + 16 k:
/// (k, i, value).
const SHIPPED_EAVG: [(usize, usize, f64); 4] = [
    (15, 15, 0.426737),
    (15, 8, 0.866457),
    (10, 12, 0.841769),
    (5, 15, 0.821371),
];

/// The tolerance against one shipped value v: Cycles' values are means of 2²³ samples per
/// E node (2²⁶ per E_avg node) of the sampled weight in f32, printed with 6 decimals:
/// 3σ of a plain Monte Carlo mean, σ = √(v(1 − v)/N) (the weight is in [0, 1]: its variance
/// is at most v(1 − v); Cycles' Sobol–Burley points do better), + 5e-7 printing + 4e-6
/// for our two channels at 2e-6.
fn shipped_tol(v: f64, samples: f64) -> f64 {
    3.0 * (v * (1.0 - v) / samples).sqrt() + 5e-7 + 4e-6
}

/// glass_e_correlated at Cycles' nodes reproduces Cycles' shipped E (both directions) and
/// E_avg (entering) within their sampling noise (measured: largest difference 9.1e-6, at
/// inv k = 1, μ = 1/15, r = 4/15; far below the 3σ bound, Sobol points being better than
/// Monte Carlo), while the separable generator (`glass_e`) misses the grazing r = 1 nodes
/// by far more (0.1376 for 0.5586): the comparison tells the two models apart.
#[test]
fn correlated_e_matches_cycles_shipped_tables() {
    let mut worst = 0f64;
    for (inv, k, j, i, want) in SHIPPED_E {
        let (mu, r) = (cycles_u(j), cycles_u(i));
        let eta = if inv {
            1.0 / cycles_ior(k)
        } else {
            cycles_ior(k)
        };
        let (v, _) = glass_e_correlated(mu, r * r, eta, INTEGRATION_TOL);
        let d = (v[0] + v[1] - want).abs();
        worst = worst.max(d);
        let tol = shipped_tol(want, (1u64 << 23) as f64);
        assert!(
            d <= tol,
            "inv {inv} [{k}][{j}][{i}] (mu {mu}, r {r}, eta {eta}): {} vs shipped {want}, tol {tol:e}",
            v[0] + v[1]
        );
    }
    for (k, i, want) in SHIPPED_EAVG {
        let r = cycles_u(i);
        let (v, _) = glass_e_avg_correlated(r * r, cycles_ior(k), INTEGRATION_TOL);
        let d = (v[0] + v[1] - want).abs();
        worst = worst.max(d);
        let tol = shipped_tol(want, (1u64 << 26) as f64);
        assert!(d <= tol, "Eavg [{k}][{i}]: {} vs {want}", v[0] + v[1]);
    }
    println!("largest |ours − shipped| over the compared nodes: {worst:.2e}");
    let (sep, _) = glass_e(1.0 / 15.0, 1.0, cycles_ior(1), INTEGRATION_TOL);
    let tol = shipped_tol(SHIPPED_E[0].4, (1u64 << 23) as f64);
    assert!((sep[0] + sep[1] - SHIPPED_E[0].4).abs() > 100.0 * tol);
}

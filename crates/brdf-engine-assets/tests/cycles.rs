//! Blender Cycles' rough-glass tables (`brdf_engine_assets::cycles`): the C arrays parsed
//! back hold, in Cycles' index order, R + T of Cycles' height-correlated glass integrand at
//! the coordinates this test derives from Cycles' own formulas (cycles_precompute.cpp:
//! endpoint nodes, ior = ior_from_F0(t⁴)), and meet closed forms where they exist: the
//! smooth limit (α at the floor: E = 1, R = the exact Fresnel reflectance), the η → 1 limit
//! (E = (1 + Λ)/(1 + 2Λ): straight refraction, Λ(t) = Λ(μ)), and the extremes of Cycles' ior
//! range (1 + 2e-8 and 99.5, both directions). Against Cycles' shipped values:
//! brdf-lut tests/glass_correlated.rs.

use brdf_lut::generate::glass::correlated::glass_e_correlated;
use brdf_lut::generate::INTEGRATION_TOL;
use std::sync::OnceLock;

mod common;

/// The arrays of a `.tables` file: name → values, parsed with no knowledge of the writer.
fn parse_tables(text: &str) -> Vec<(String, Vec<f32>)> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(p) = rest.find("static const float table_") {
        let s = &rest[p + "static const float table_".len()..];
        let name = &s[..s.find('[').unwrap()];
        let len: usize = s[s.find('[').unwrap() + 1..s.find(']').unwrap()]
            .parse()
            .unwrap();
        let body = &s[s.find('{').unwrap() + 1..s.find("};").unwrap()];
        let vals: Vec<f32> = body
            .split(',')
            .map(|v| v.trim().trim_end_matches('f').parse::<f32>().unwrap())
            .collect();
        assert_eq!(
            vals.len(),
            len,
            "{name}: declared {len}, holds {}",
            vals.len()
        );
        out.push((name.to_string(), vals));
        rest = &s[s.find("};").unwrap()..];
    }
    out
}

/// Cycles' node i of n on an axis clamped to [lo, hi] (cycles_precompute.cpp).
fn node(i: usize, n: usize, lo: f64, hi: f64) -> f64 {
    (i as f64 / (n - 1) as f64).clamp(lo, hi)
}

/// Cycles' ior of z node k: ior_from_F0(F0) = (1 + √F0)/(1 − √F0) at F0 = t⁴ (bsdf_util.h).
fn ior(k: usize, n: usize) -> f64 {
    let f0 = node(k, n, 1e-4, 0.99).powi(4);
    (1.0 + f0.sqrt()) / (1.0 - f0.sqrt())
}

/// Exact unpolarised dielectric Fresnel reflectance at cos c for relative index η (Walter
/// et al. 2007, eq. 22), 1 under total internal reflection: brdf-core's, not the ring
/// rule's inlined copy.
fn fresnel(c: f64, eta: f64) -> f64 {
    brdf_core::fresnel::f_dielectric(eta, c)
}

/// E at η = 1: (1 + Λ)/(1 + 2Λ), GGX Λ(μ) = (√(1 + α²(1 − μ²)/μ²) − 1)/2 (Heitz 2014,
/// eq. 72): every facet refracts straight through and the sample weight G2/G1 is constant.
fn straight(mu: f64, alpha: f64) -> f64 {
    let l = ((1.0 + alpha * alpha * (1.0 - mu * mu) / (mu * mu)).sqrt() - 1.0) / 2.0;
    (1.0 + l) / (1.0 + 2.0 * l)
}

/// Half an f32 ulp of v in (0, 1], plus the integrator's tolerance on two channels.
fn value_tol(v: f64) -> f64 {
    let half_ulp = 2f64.powf(v.abs().max(1e-30).log2().floor() - 24.0);
    half_ulp + 2.0 * INTEGRATION_TOL
}

const N: usize = 3;

/// One 3-node run without E_avg, shared by the tests below.
fn small() -> &'static Vec<(String, Vec<f32>)> {
    static T: OnceLock<Vec<(String, Vec<f32>)>> = OnceLock::new();
    T.get_or_init(|| {
        let files = brdf_engine_assets::cycles(N, false, &|_| {}).unwrap();
        let f = files
            .iter()
            .find(|f| f.name == "cycles_ggx_glass.tables")
            .unwrap();
        let side = files
            .iter()
            .find(|f| f.name == "cycles_ggx_glass.json")
            .unwrap();
        let side: serde_json::Value = serde_json::from_slice(&side.bytes).unwrap();
        for k in common::SIDECAR_KEYS.iter().chain(&["masking"]) {
            assert!(side.get(k).is_some(), "sidecar key {k}");
        }
        parse_tables(std::str::from_utf8(&f.bytes).unwrap())
    })
}

fn table(name: &str) -> &'static [f32] {
    &small().iter().find(|t| t.0 == name).unwrap().1
}

/// Each texel, at flat index i + N (j + N k), is saturate(R + T) of `glass_e_correlated` at
/// (μ_j, r_i², ior_k) (E) or 1/ior_k (inv E), rounded to f32; no E_avg arrays when not asked.
#[test]
fn cycles_texels_are_the_integrals_at_cycles_nodes_in_cycles_order() {
    let names: Vec<&str> = small().iter().map(|t| t.0.as_str()).collect();
    assert_eq!(names, ["ggx_glass_E", "ggx_glass_inv_E"]);
    for (name, inside) in [("ggx_glass_E", false), ("ggx_glass_inv_E", true)] {
        let t = table(name);
        assert_eq!(t.len(), N * N * N);
        for k in 0..N {
            let eta = if inside { 1.0 / ior(k, N) } else { ior(k, N) };
            for j in 0..N {
                let mu = node(j, N, 1e-4, 1.0);
                for i in 0..N {
                    let r = node(i, N, 1e-4, 1.0);
                    let (v, _) = glass_e_correlated(mu, r * r, eta, INTEGRATION_TOL);
                    let want = (v[0] + v[1]).clamp(0.0, 1.0);
                    let got = t[i + N * (j + N * k)] as f64;
                    assert!(
                        (got - want).abs() <= value_tol(want),
                        "{name}[{k}][{j}][{i}] (mu {mu}, r {r}, eta {eta}): {got} vs {want}"
                    );
                }
            }
        }
    }
}

/// Closed forms on the written file. Column r = 1e-4 (α floored at 1e-4: a smooth interface,
/// E = 1 − O(α²/μ²)) holds E = 1 for μ ≥ 0.5; slice z = 0 (η = 1 + 2e-8, both directions)
/// holds E = (1 + Λ)/(1 + 2Λ) (no reflection, straight refraction: [`straight`]) for
/// μ ≥ 0.5. Tolerance 1e-5: two channels at the integrator's 2e-6, f32 rounding 6e-8, and
/// the O(α²/μ²) = 4e-8 and O(η − 1) residues.
#[test]
fn cycles_texels_meet_the_smooth_and_index_matched_limits() {
    for name in ["ggx_glass_E", "ggx_glass_inv_E"] {
        let t = table(name);
        for j in (0..N).filter(|&j| node(j, N, 1e-4, 1.0) >= 0.5) {
            let mu = node(j, N, 1e-4, 1.0);
            for k in 0..N {
                let e = t[N * (j + N * k)] as f64;
                assert!(
                    (e - 1.0).abs() < 1e-5,
                    "{name} r = 1e-4, mu {mu}, k {k}: {e}"
                );
            }
            for i in 0..N {
                let alpha = node(i, N, 1e-4, 1.0).powi(2).max(1e-4);
                let e = t[i + N * j] as f64;
                let want = straight(mu, alpha);
                assert!(
                    (e - want).abs() < 1e-5,
                    "{name} z = 0, mu {mu}, alpha {alpha}: {e} vs (1 + L)/(1 + 2L) {want}"
                );
            }
        }
    }
}

/// glass_e_correlated at the ends of Cycles' ior range, beyond the generator Spec's η ∈ [0.1, 10]:
/// η = 1 + 2e-8, 99.5 and their reciprocals. Everywhere finite, 0 ≤ R, T and R + T ≤ 1 (to
/// the tolerance on two channels); at the α floor with μ ≥ 0.5, R is the exact Fresnel
/// reflectance (1 under total internal reflection) and R + T = 1, within 1e-5 (the
/// integrator's 2e-6 per channel and the O(α²/μ²) rough residue).
#[test]
fn glass_e_behaves_at_cycles_ior_extremes() {
    let t = 0.99f64 * 0.99;
    let top = (1.0 + t) / (1.0 - t);
    let near = 1.0 + 2e-8;
    for eta in [near, top, 1.0 / near, 1.0 / top] {
        for mu in [1e-4, 0.5, 0.9, 1.0] {
            for alpha in [1e-8, 0.25, 1.0] {
                let ([r, tr], w) = glass_e_correlated(mu, alpha, eta, INTEGRATION_TOL);
                let tol = 2.0 * INTEGRATION_TOL;
                let at = format!("eta {eta}, mu {mu}, alpha {alpha}: R {r}, T {tr}");
                assert!(
                    r.is_finite() && tr.is_finite() && w.error.is_finite(),
                    "{at}"
                );
                assert!(r >= -tol && tr >= -tol && r + tr <= 1.0 + tol, "{at}");
                if alpha < 1e-4 && mu >= 0.5 {
                    let f = fresnel(mu, eta);
                    assert!((r - f).abs() < 1e-5, "{at}: Fresnel {f}");
                    assert!((r + tr - 1.0).abs() < 1e-5, "{at}");
                }
            }
        }
    }
}

/// Sizes outside 2..=64 are typed errors, not panics.
#[test]
fn cycles_sizes_are_checked() {
    for n in [0, 1, 65, usize::MAX] {
        assert!(
            brdf_engine_assets::cycles(n, false, &|_| {}).is_err(),
            "{n}"
        );
    }
}

/// The E_avg arrays (2 nodes per axis): n² values each, x = r fastest; at the α floor
/// E_avg = 1 (E = 1 but for the O(α²/μ²) residue, whose 2∫μ-weighted integral is ~α²
/// ln(1/α) = 1e-7), and at η = 1 + 2e-8 with α = 1, E_avg = 2∫₀¹ E μ dμ with E = (1 + μ)/2
/// ([`straight`] at α = 1: 1 + 2Λ = 1/μ), i.e. 5/6, from both sides. Tolerance 1e-5: the integrator's 2e-6 per
/// channel and f32 rounding. (0.24 s in release: E_avg from inside at η = 1/99.5, α = 1 is
/// 2.4e5 integrand evaluations.)
#[test]
fn cycles_e_avg_meets_its_closed_forms() {
    let files = brdf_engine_assets::cycles(2, true, &|_| {}).unwrap();
    let f = files
        .iter()
        .find(|f| f.name == "cycles_ggx_glass.tables")
        .unwrap();
    let t = parse_tables(std::str::from_utf8(&f.bytes).unwrap());
    let names: Vec<&str> = t.iter().map(|t| t.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "ggx_glass_E",
            "ggx_glass_inv_E",
            "ggx_glass_Eavg",
            "ggx_glass_inv_Eavg"
        ]
    );
    let closed = 5.0 / 6.0;
    for (name, v) in &t[2..] {
        assert_eq!(v.len(), 4, "{name}");
        // index i + 2 k: (r, z) = (1e-4, 0), (1, 0), (1e-4, 0.99), (1, 0.99)
        for k in 0..2 {
            assert!(
                (v[2 * k] as f64 - 1.0).abs() < 1e-5,
                "{name} r = 1e-4, k {k}: {}",
                v[2 * k]
            );
        }
        assert!(
            (v[1] as f64 - closed).abs() < 1e-5,
            "{name} r = 1, eta ~ 1: {} vs {closed}",
            v[1]
        );
    }
}

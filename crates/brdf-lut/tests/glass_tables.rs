//! Rough-glass albedo tables (kinds `glass-e`, `glass-e-avg`; `generate/glass.rs`), checked
//! against closed forms, a physical law and an independent Monte Carlo estimate through the
//! kernel's own sampler and BSDF.
#![cfg(feature = "generate")]

use brdf_core::fresnel::f_dielectric;
use brdf_core::models::rough_dielectric::{DielectricDistribution, RoughDielectric};
use brdf_core::Vec3;
use brdf_lut::generate::glass::{glass_e, glass_e_avg, glass_e_cap, glass_e_radial};
use brdf_lut::generate::{
    check_nodes, generate, Distribution, GenError, Kind, Masking, Spec, Work, INTEGRATION_TOL,
};
use brdf_lut::{GlassAlbedoTable, GlassAverageTable, Lut};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

mod common;
use common::{within_estimates, BRUTE};

/// The generator's tolerance per channel.
const TOL: f64 = INTEGRATION_TOL;

/// The generator's rule (ring rule, [`TOL`]) and `lut verify`'s reference (radial rule,
/// 2e-8): (rule, tolerance, name).
type Rule = (
    fn(f64, f64, f64, f64) -> ([f64; 2], Work),
    f64,
    &'static str,
);
const RULES: [Rule; 2] = [(glass_e, TOL, "ring"), (glass_e_radial, 2e-8, "radial")];

/// α → 0 (the kernel's floor α = 1e-4): R → F(μ) (exact dielectric Fresnel) and
/// R + T → 1, for both rules. The tabulated integral differs from the limit by the visible
/// normals' spread: the share of facets tilted by more than ~θ_μ (the angle that changes F
/// or the horizon test noticeably) is O(α²/μ²) for GGX's tail, ≤ 2.5e-7 at μ ≥ 0.2; so
/// |R − F| ≤ 2 tol + 10 α²/μ². μ is kept 0.1 away from TIR's critical cosine
/// μ_c = √(1 − η²): F's curvature grows as |μ − μ_c|^{-3/2} toward it, and at
/// (μ, η) = (0.8, 0.7), 0.086 from it, R − F is 4.2e-7 (both rules at 1e-11 agree to
/// 1e-12), past 10 α²/μ² = 1.6e-7.
#[test]
fn narrow_limit_is_fresnel_and_conserves_energy() {
    let a = 1e-4;
    for (rule, tol, name) in RULES {
        for eta in [1.5f64, 2.5, 1.05, 0.7, 0.5] {
            let mc = if eta < 1.0 {
                ((1.0 - eta) * (1.0 + eta)).sqrt()
            } else {
                -1.0
            };
            for mu in [0.2f64, 0.35, 0.5, 0.8, 1.0] {
                if (mu - mc).abs() < 0.1 {
                    continue;
                }
                let ([r, t], w) = rule(mu, a, eta, tol);
                let f = f_dielectric(eta, mu);
                let bound = 2.0 * tol + 10.0 * a * a / (mu * mu);
                assert!(
                    (r - f).abs() <= bound,
                    "{name} η {eta} μ {mu}: R {r} vs F {f}"
                );
                assert!(
                    (r + t - 1.0).abs() <= bound,
                    "{name} η {eta} μ {mu}: R + T = {}",
                    r + t
                );
                assert!(w.error <= tol, "{name}: estimate {}", w.error);
            }
        }
    }
}

/// η = 1: F = 0 on every facet and every ray goes straight on, so R = 0 and T = G1(μ), the
/// GGX Smith G1 = 2μ/(μ + √(μ² + α²(1 − μ²))) of the exit direction (the separable G's
/// second factor; the limit η → 1 of the rough integrals), for both rules. The integrand
/// is then constant on the visible normals: exact to rounding and the rule's estimate.
#[test]
fn index_matched_interface_is_g1() {
    for (rule, tol, name) in RULES {
        for alpha in [1e-4, 0.05, 0.3, 1.0] {
            for mu in [0.017_452_4, 0.1, 0.5, 1.0] {
                let ([r, t], w) = rule(mu, alpha, 1.0, tol);
                let g1 = 2.0 * mu / (mu + (mu * mu + alpha * alpha * (1.0 - mu * mu)).sqrt());
                assert!(r.abs() <= 1e-12, "{name} α {alpha} μ {mu}: R {r}");
                let err = (t - g1).abs();
                assert!(
                    err <= 1e-9 && err <= w.error + 1e-12,
                    "{name} α {alpha} μ {mu}: T {t} vs G1 {g1} (estimate {:e})",
                    w.error
                );
            }
        }
    }
}

/// Energy: 0 ≤ R, T and R + T ≤ 1 (the adjoint transmission is an energy fraction; the
/// separable G loses energy to masking, never gains it), up to the integration tolerance,
/// on a spread of (μ, α, η) in both directions of light, grazing μ included.
#[test]
fn reflected_plus_transmitted_at_most_one() {
    for eta in [0.34, 0.6, 0.95, 1.0, 1.1, 1.5, 3.0] {
        for alpha in [1e-4, 0.02, 0.2, 0.6, 1.0] {
            for mu in [0.017_452_4, 0.2, 0.6, 1.0] {
                let ([r, t], _) = glass_e(mu, alpha, eta, TOL);
                assert!(r >= -TOL && t >= -TOL, "{mu} {alpha} {eta}: {r} {t}");
                assert!(r + t <= 1.0 + 2.0 * TOL, "{mu} {alpha} {eta}: {}", r + t);
            }
        }
    }
}

/// An independent estimate: the kernel's own importance sampler (Heitz's disc of visible
/// normals, Fresnel choice) and its BSDF and pdf, N samples; a sample below the surface
/// counts toward T with the adjoint factor η² (f* = η² f for wi inside, wo outside). The
/// table's integral must lie within 5 standard errors of the mean (plus the integration
/// tolerance): a false failure has probability below 1e-6 per channel.
#[test]
fn agrees_with_monte_carlo_through_the_kernel_sampler() {
    const N: usize = 400_000;
    let mut rng = Pcg64::seed_from_u64(0x61A55);
    for &(mu, alpha, eta) in &[
        (0.5f64, 0.3, 1.5),
        (0.1, 0.5, 1.5),
        (0.8, 0.15, 0.7),
        (0.3, 0.8, 0.5),
        (0.05, 1.0, 2.5),
    ] {
        let m = RoughDielectric::new(DielectricDistribution::Ggx, alpha, eta).unwrap();
        let wo = Vec3::new(((1.0 - mu) * (1.0 + mu)).sqrt(), 0.0, mu);
        let (mut s, mut s2) = ([0f64; 2], [0f64; 2]);
        for _ in 0..N {
            let u = [rng.random::<f64>(), rng.random::<f64>()];
            let Some(x) = m.sample_with_choice(wo, u, rng.random::<f64>()) else {
                continue;
            };
            let (c, w) = if x.wi.z > 0.0 {
                (0, x.weight.r)
            } else {
                (1, x.weight.r * eta * eta)
            };
            s[c] += w;
            s2[c] += w * w;
        }
        let ([r, t], _) = glass_e(mu, alpha, eta, TOL);
        for (c, v) in [r, t].into_iter().enumerate() {
            let mean = s[c] / N as f64;
            let se = ((s2[c] / N as f64 - mean * mean).max(0.0) / N as f64).sqrt();
            assert!(
                (v - mean).abs() <= 5.0 * se + TOL,
                "({mu}, {alpha}, {eta}) channel {c}: table integral {v}, MC {mean} ± {se}"
            );
        }
    }
}

/// Étendue (generalised reciprocity of the BSDF, f_t(wi, wo)/η_o² = f_t(wo, wi)/η_i²,
/// Walter et al. 2007 §5.2): under uniform diffuse illumination the flux crossing into the
/// denser medium equals the flux crossing out of it, so T_avg(η) = η² T_avg(1/η) — true of
/// the smooth interface (1 − F_avg(η) = η² (1 − F_avg(1/η))) and of the rough one. Two
/// independent E_avg integrals (the TIR break only in the second), within their estimates.
#[test]
fn average_transmission_obeys_etendue() {
    etendue(&[(0.3, 1.5), (0.7, 2.2), (0.05, 1.3)]);
}

/// The same law at the narrow limit α = 1e-4: T_avg(1.5) = 0.9082221 (the smooth
/// interface's 0.90822204 to 1e-7) must equal 1.5² T_avg(1/1.5). The inside integral has a
/// square-root edge at μ_c = √(1 − η²) rounded over ~α: with E_avg's μ panels broken only at
/// μ_c it came out 4e-6 low (past its estimate); graded toward μ_c at α·4ʲ it holds.
#[test]
fn average_transmission_obeys_etendue_at_the_narrow_limit() {
    etendue(&[(1e-4, 1.5)]);
}

fn etendue(cases: &[(f64, f64)]) {
    for &(alpha, eta) in cases {
        let (a, wa) = glass_e_avg(alpha, eta, TOL);
        let (b, wb) = glass_e_avg(alpha, 1.0 / eta, TOL);
        let lhs = a[1];
        let rhs = eta * eta * b[1];
        let allowed = wa.error + eta * eta * wb.error + 1e-12;
        assert!(
            (lhs - rhs).abs() <= allowed,
            "α {alpha} η {eta}: T_avg {lhs} vs η² T_avg(1/η) {rhs} (allowed {allowed:e})"
        );
    }
}

fn small_spec(kind: Kind) -> Spec {
    let mut s = Spec::new(kind, Distribution::Ggx, Masking::SmithSeparable);
    for a in s.axes.iter_mut() {
        a.count = 4;
    }
    s.samples = 64;
    s
}

/// Generation time, evaluations per node and error of the default 32³ glass-e table for
/// light from outside (η ∈ [1, 3]) and from inside (η ∈ [1/3, 1]) and of the 32²
/// glass-e-avg table: a measurement, printed (run with `--release --ignored --nocapture`).
#[test]
#[ignore = "a measurement: minutes"]
fn measure_default_tables() {
    let third = 1.0 / 3.0;
    for (kind, lo, hi) in [
        (Kind::GlassAlbedo, 1.0, 3.0),
        (Kind::GlassAlbedo, third, 1.0),
        (Kind::GlassAverageAlbedo, 1.0, 3.0),
        (Kind::GlassAverageAlbedo, third, 1.0),
    ] {
        let mut spec = Spec::new(kind, Distribution::Ggx, Masking::SmithSeparable);
        spec.samples = 200;
        if let Some(a) = spec.axes.last_mut() {
            (a.lo, a.hi) = (lo, hi);
        }
        let t0 = std::time::Instant::now();
        let g = generate(&spec, &|_| {}).unwrap();
        let secs = t0.elapsed().as_secs_f64();
        let lut = Lut::from_bytes(g.bytes.clone()).unwrap();
        let nodes = lut.header().nodes();
        let view = brdf_lut::LutView::parse(&g.bytes).unwrap();
        let checks = check_nodes(&spec, &view, g.integration as f64, 24);
        let worst = checks
            .iter()
            .map(|c| (c.stored - c.reference).abs())
            .fold(0f64, f64::max);
        println!(
            "{kind:?} η ∈ [{lo:.3}, {hi}]: {nodes} nodes in {secs:.1} s on {} threads, {:.0} evals/node, bound {:e}, \
             interpolation max {:e} rms {:e}, worst node vs reference {worst:e} ({} checked, all ok: {})",
            brdf_lut::generate::threads(),
            g.evals as f64 / nodes as f64,
            g.integration,
            g.error.max_abs,
            g.error.rms,
            checks.len(),
            checks.iter().all(|c| c.ok())
        );
    }
}

/// A generated glass-e table: every node within the header's integration bound + ½ LSB of
/// the direct integral, `lut verify`'s reference check passes, the typed lookup gives the
/// node values at the nodes, its batch and the view equal the scalar lookup bit for bit, and
/// the header names the kind and model.
#[test]
fn glass_table_nodes_lookups_and_verify() {
    for (lo, hi) in [(1.0, 3.0), (1.0 / 3.0, 1.0)] {
        let mut spec = small_spec(Kind::GlassAlbedo);
        spec.axes[2].lo = lo;
        spec.axes[2].hi = hi;
        let g = generate(&spec, &|_| {}).unwrap();
        let lut = Lut::from_bytes(g.bytes.clone()).unwrap();
        assert_eq!(Spec::from_header(&lut.header()).as_ref(), Some(&spec));
        let t = GlassAlbedoTable::parse(&g.bytes[..]).unwrap();
        let view = t.view().unwrap();
        let checks = check_nodes(&spec, &view, g.integration as f64, 8);
        assert!(checks.len() >= 16);
        for c in &checks {
            assert!(c.ok(), "{c:?}");
        }
        let axes = &view.header().axes;
        let lsb = 0.5 / 65535.0;
        let (mut xs, mut rs, mut ts) = ([vec![], vec![], vec![]], vec![], vec![]);
        for k in 0..64u32 {
            let i = [k % 4, (k / 4) % 4, k / 16];
            let x: Vec<f64> = (0..3).map(|d| axes[d].node(i[d])).collect();
            let ([r, tt], _) = glass_e(x[0], x[1] * x[1], x[2], TOL);
            let (lr, lt) = t.rt(x[0] as f32, x[1] as f32, x[2] as f32);
            // The zero-copy view reads the same prepared lookup: the same bits.
            let v = view.sample(&[x[0] as f32, x[1] as f32, x[2] as f32]);
            assert_eq!(
                (v[0].to_bits(), v[1].to_bits()),
                (lr.to_bits(), lt.to_bits())
            );
            // The node's own value, read at its f32 coordinates: ½ LSB + the bound + f32.
            let allowed = lsb + g.integration as f64 + 1e-6;
            assert!((lr as f64 - r).abs() <= allowed, "{x:?}: R {lr} vs {r}");
            assert!((lt as f64 - tt).abs() <= allowed, "{x:?}: T {lt} vs {tt}");
            for d in 0..3 {
                xs[d].push(x[d] as f32);
            }
            rs.push(lr);
            ts.push(lt);
        }
        let (mut br, mut bt) = (vec![0f32; 64], vec![0f32; 64]);
        let n = t.rt_batch((&xs[0], &xs[1], &xs[2]), &mut br, &mut bt);
        assert_eq!(n, 64);
        assert_eq!((br, bt), (rs, ts));
    }
}

/// A generated glass-e-avg table: nodes pass `lut verify`'s reference check and the typed
/// lookup reads them back.
#[test]
fn glass_average_table_verifies() {
    let mut spec = small_spec(Kind::GlassAverageAlbedo);
    spec.axes[0].count = 2;
    spec.axes[1].count = 2;
    spec.axes[1].hi = 2.0;
    let g = generate(&spec, &|_| {}).unwrap();
    let t = GlassAverageTable::parse(&g.bytes[..]).unwrap();
    let view = t.view().unwrap();
    for c in check_nodes(&spec, &view, g.integration as f64, 4) {
        assert!(c.ok(), "{c:?}");
    }
    let (r, tt) = t.rt_avg(0.0, 1.0);
    // α → 0, η = 1: nothing reflected; T_avg = 2∫ G1(μ) μ dμ → 1.
    assert!(r.abs() < 1e-5 && (tt - 1.0).abs() < 1e-5, "{r} {tt}");
}

/// Bad specs are typed errors: an η axis across 1, Beckmann (not tabulated yet).
#[test]
fn bad_glass_specs_are_refused() {
    let mut s = small_spec(Kind::GlassAlbedo);
    s.axes[2].lo = 0.5;
    assert!(matches!(generate(&s, &|_| {}), Err(GenError::Invalid(m)) if m.contains("spans 1")));
    let mut s = small_spec(Kind::GlassAlbedo);
    s.distribution = Distribution::Beckmann;
    assert!(matches!(generate(&s, &|_| {}), Err(GenError::Invalid(_))));
    let mut s = small_spec(Kind::GlassAlbedo);
    s.axes[2].hi = 20.0;
    assert!(matches!(generate(&s, &|_| {}), Err(GenError::Invalid(_))));
}

/// The hard points, both sides: grazing light (μ = cos 89°) and the narrow floor α = 1e-4
/// (the lobe's edge ring at τ ≈ μ/2: the reflected horizon and the visibility edge both
/// cross the GGX bump), and the default 32³ table's node where the cap integrator at 2e-6
/// was 6.3e-6 off. The ring rule at the generator's tolerance lies within the two
/// estimates of the cap integrator (other coordinates, other cuts) at 2e-8; the radial
/// rule at `lut verify`'s 2e-8 (its estimate within it) within the two estimates of the
/// ring rule at 1e-10.
#[test]
fn hard_points_agree_with_both_references() {
    let mu = 89f64.to_radians().cos();
    for &(mu, alpha, eta) in &[
        (mu, 1e-4, 1.5),
        (mu, 1e-4, 0.5),
        (mu, 0.01, 2.5),
        (mu, 0.3, 0.7),
        (0.9, 1e-4, 0.6),
        (0.3, 1e-4, 3.0),
        (
            0.270_929_661_462_933_4,
            (16.0f64 / 31.0).powi(2),
            55.0 / 31.0,
        ),
    ] {
        let at = format!("({mu}, {alpha}, {eta})");
        let ring = glass_e(mu, alpha, eta, TOL);
        within_estimates(&at, &ring, &glass_e_cap(mu, alpha, eta, 2e-8));
        let radial = glass_e_radial(mu, alpha, eta, 2e-8);
        assert!(
            radial.1.error <= 2e-8,
            "{at}: estimate {:e}",
            radial.1.error
        );
        within_estimates(&at, &glass_e(mu, alpha, eta, 1e-10), &radial);
    }
}

/// Two inside points where the lit set of a row changes several times within a few
/// hundredths of a radian in φ (2 → 3 → 1 → 0 pieces), so a φ panel's rows can all miss a
/// narrow bump of the row integral I(φ) unless every change is a panel break. Reference
/// values from an independent brute-force rule: the midpoint rule on an 8000 × 8000 grid
/// in the cap's (θ, φ) with the same integrand written directly from F, G1 and the
/// refraction (no cuts, no adaptivity); its 2000-, 4000- and 8000-point values agree to
/// 2e-7, which with the generator's estimate bounds the allowed difference. T only; R:
/// `inside_reflection_agrees_with_a_brute_force_rule`.
#[test]
fn inside_points_agree_with_a_brute_force_rule() {
    brute_force_points(&[1]);
}

/// R at the same points (the cap integrator, whose R rows keep the TIR kink of F inside
/// their pieces, is 2.4e-6 off at the second: the ring rule cuts it exactly).
#[test]
fn inside_reflection_agrees_with_a_brute_force_rule() {
    brute_force_points(&[0]);
}

fn brute_force_points(channels: &[usize]) {
    for &(mu, r, eta, rr, tt) in &BRUTE {
        let (v, w) = glass_e(mu, r * r, eta, TOL);
        for (c, want) in [rr, tt].into_iter().enumerate() {
            if !channels.contains(&c) {
                continue;
            }
            assert!(
                (v[c] - want).abs() <= w.error + 1e-6,
                "({mu}, {r}, {eta}) channel {c}: {} vs brute force {want}",
                v[c]
            );
        }
    }
}

/// An independent E_avg: composite K15 in μ on fixed panels (no adaptivity), broken at 0,
/// μ_c = √(1 − η²), η (η < 1) and 1, each piece mapped by μ = a + (b − a) sin²β and cut
/// geometrically toward both ends at 2⁻ʲ (j ≤ 16) of its β range plus 8 uniform panels,
/// with E at 1e-9. Returns the values and Σ|K15 − G7| (the embedded Gauss rule's
/// difference, a pessimistic bound of the composite rule's error).
fn dense_average(alpha: f64, eta: f64) -> ([f64; 2], f64) {
    use brdf_core::quadrature::kronrod::{gk15_combine, gk15_nodes};
    let mut pts = vec![0.0, 1.0];
    if eta < 1.0 {
        pts.extend([((1.0 - eta) * (1.0 + eta)).sqrt(), eta]);
    }
    pts.sort_by(f64::total_cmp);
    let mut cuts: Vec<f64> = (0..=8).map(|i| i as f64 / 8.0).collect();
    for j in 4..=16 {
        let d = 0.5f64.powi(j);
        cuts.extend([d, 1.0 - d]);
    }
    cuts.sort_by(f64::total_cmp);
    let (mut v, mut err) = ([0.0; 2], 0.0);
    for p in pts.windows(2) {
        let (a, b) = (p[0], p[1]);
        for c in cuts.windows(2) {
            let y = gk15_nodes(c[0], c[1]).map(|t| {
                let (sb, cb) = (t * std::f64::consts::FRAC_PI_2).sin_cos();
                let mu = a + (b - a) * sb * sb;
                let jac = 2.0 * mu * (b - a) * 2.0 * sb * cb * std::f64::consts::FRAC_PI_2;
                let (e, _) = glass_e(mu, alpha, eta, 1e-9);
                [e[0] * jac, e[1] * jac]
            });
            let (pv, pe) = gk15_combine(&y, 0.5 * (c[1] - c[0]));
            v = [v[0] + pv[0], v[1] + pv[1]];
            err += pe[0].max(pe[1]);
        }
    }
    (v, err)
}

/// E_avg's estimate bounds its true error against [`dense_average`] (other panels, no
/// adaptivity, E 2000× tighter) at the narrow floor α = 1e-4, η near 1 on both sides, from
/// inside with μ_c and η inside (0, 1), and rough: |E_avg − dense| ≤ estimate + the dense
/// rule's |K15 − G7| sum (asserted below 1e-7 so that the check has teeth).
#[test]
fn average_estimate_bounds_its_error() {
    for &(alpha, eta) in &[
        (1e-4, 0.7),
        (1e-4, 1.5),
        (1e-4, 0.99),
        (0.05, 1.01),
        (0.3, 1.0 / 1.5),
        (0.6, 1.0 / 3.0),
        (1.0, 2.5),
    ] {
        let (v, w) = glass_e_avg(alpha, eta, TOL);
        let (rf, re) = dense_average(alpha, eta);
        assert!(re < 1e-7, "({alpha}, {eta}): dense rule's bound {re:e}");
        println!(
            "({alpha}, {eta:.4}): |ΔR| {:.1e} |ΔT| {:.1e} estimate {:.1e} dense {re:.1e} evals {}",
            (v[0] - rf[0]).abs(),
            (v[1] - rf[1]).abs(),
            w.error,
            w.evals
        );
        for c in 0..2 {
            assert!(
                (v[c] - rf[c]).abs() <= w.error + re,
                "({alpha}, {eta}) channel {c}: {} vs dense {} (estimate {:e}, dense {re:e})",
                v[c],
                rf[c],
                w.error
            );
        }
    }
}

//! The physical-plausibility suite of the reflection models.
//!
//! * Chi-square goodness of fit of every sampler against its own pdf (histogram over the
//!   whole sphere; expected counts from adaptive integration of the pdf per cell; cells with
//!   expected < 5 pooled; Dirac samples and failed samples in cells of their own; significance
//!   0.01 with Šidák's correction over all cases).
//! * eval/pdf/weight consistency of every sample drawn.
//! * Reciprocity to 1e-5 relative for every model flagged reciprocal, and a demonstration
//!   that those flagged otherwise are not.
//! * Energy: albedo ≤ 1 for every model flagged energy conserving (the albedo maxima table is
//!   printed), Lambert's white furnace, the coupled model's printed k shows its excess.
//! * Robustness: no NaN or ∞ for grazing, below-horizon and degenerate pairs, extreme
//!   parameters; zero roughness is a typed error.
//!
//! Run with `--nocapture` to see the p-values and the albedo table.

use brdf_core::albedo::directional_albedo;
use brdf_core::microfacet::{Beckmann, Distribution};
use brdf_core::models::*;
use brdf_core::quadrature::{GaussLegendre, Rule};
use brdf_core::sampling;
use brdf_core::{ParamError, Real, Vec3};
use rand::Rng;
use rand::SeedableRng;
use rand_pcg::Pcg64;
use std::f64::consts::PI;

// ---------------------------------------------------------------- models under test

fn w(v: f64) -> Rgb<f64> {
    Rgb::splat(v)
}

struct Named {
    name: String,
    model: Box<dyn Brdf<f64>>,
}

fn named(name: impl Into<String>, model: impl Brdf<f64> + 'static) -> Named {
    Named {
        name: name.into(),
        model: Box::new(model),
    }
}

/// Every model of the catalogue at its default parameters (the configurations the command
/// line, the WASM module and the benches start from).
fn catalogue_models() -> Vec<Named> {
    brdf_core::catalogue::MODELS
        .iter()
        .map(|spec| {
            let m = spec
                .build::<f64>(&spec.defaults::<f64>())
                .unwrap_or_else(|e| panic!("catalogue default of {}: {e}", spec.name));
            named(format!("catalogue {} (defaults)", spec.name), m)
        })
        .collect()
}

/// Every model, in typical and extreme-but-valid configurations, then the catalogue's
/// defaults.
fn all_models() -> Vec<Named> {
    let mut v = hand_models();
    v.extend(catalogue_models());
    v
}

fn hand_models() -> Vec<Named> {
    let c = Rgb::new(0.6, 0.4, 0.2);
    vec![
        named("lambert", Lambert::new(c).unwrap()),
        named(
            "standard phong",
            StandardLighting::new(w(0.0), w(0.1), c, w(0.5), 20.0, Highlight::Phong).unwrap(),
        ),
        named(
            "standard blinn-phong",
            StandardLighting::new(w(0.0), w(0.1), c, w(0.5), 20.0, Highlight::BlinnPhong).unwrap(),
        ),
        named(
            "phong-normalized n=1",
            PhongNormalized::new(w(0.3), w(0.7), 1.0).unwrap(),
        ),
        named(
            "phong-normalized n=50",
            PhongNormalized::new(c, w(0.4), 50.0).unwrap(),
        ),
        named(
            "blinn-phong-normalized n=2",
            BlinnPhongNormalized::new(w(0.0), w(1.0), 2.0).unwrap(),
        ),
        named(
            "blinn-phong-normalized n=100",
            BlinnPhongNormalized::new(w(0.2), w(0.8), 100.0).unwrap(),
        ),
        named(
            "cook-torrance m=0.2 blinn G",
            CookTorrance::new(c.scale(0.5), w(0.5), 0.2, 0.04, GeometricTerm::Blinn).unwrap(),
        ),
        named(
            "cook-torrance m=0.6 smith G",
            CookTorrance::new(w(0.0), w(1.0), 0.6, 1.0, GeometricTerm::SmithCorrelated).unwrap(),
        ),
        named(
            "cook-torrance m=0.3 smith G, visible-normal sampling",
            CookTorrance::new(w(0.0), w(1.0), 0.3, 1.0, GeometricTerm::SmithCorrelated)
                .unwrap()
                .with_sampling(MicrofacetSampling::VisibleNormals),
        ),
        named(
            "cook-torrance m=0.4 modified G",
            CookTorrance::new(w(0.1), w(0.9), 0.4, 0.5, GeometricTerm::Modified).unwrap(),
        ),
        named(
            "lambert+mirror mix",
            LambertSpecularMix::new(c, 0.3).unwrap(),
        ),
        named("shirley damped", ShirleyDamped::new(c, 0.04).unwrap()),
        named(
            "coupled conserving k",
            CoupledSmooth::new(w(1.0), 0.04, CoupledK::Conserving).unwrap(),
        ),
        named(
            "coupled printed k",
            CoupledSmooth::new(w(1.0), 0.04, CoupledK::Printed).unwrap(),
        ),
        named(
            "ashikhmin-shirley 10/1000 metal",
            AshikhminShirley::new(w(1.0), w(0.0), 10.0, 1000.0).unwrap(),
        ),
        named(
            "ashikhmin-shirley 100/100 plastic",
            AshikhminShirley::new(w(0.05), c, 100.0, 100.0).unwrap(),
        ),
        named(
            "ashikhmin-shirley 1/1 rough",
            AshikhminShirley::new(w(0.5), w(0.5), 1.0, 1.0).unwrap(),
        ),
        named(
            "bank fixed tangent",
            Bank::new(c.scale(0.5), w(0.3), 30.0, BankTangent::Azimuth(0.4)).unwrap(),
        ),
        named(
            "bank n×v tangent",
            Bank::new(c.scale(0.5), w(0.3), 30.0, BankTangent::NormalCrossView).unwrap(),
        ),
        named("ward 0.1/0.4", Ward::new(w(0.2), w(0.3), 0.1, 0.4).unwrap()),
        named(
            "ward 0.6/0.6 rs=1",
            Ward::new(w(0.0), w(1.0), 0.6, 0.6).unwrap(),
        ),
        named(
            "ggx a=0.05 separable",
            Ggx::new(
                w(1.0),
                0.05,
                SmithForm::Separable,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap(),
        ),
        named(
            "ggx a=0.5 correlated",
            Ggx::new(
                c,
                0.5,
                SmithForm::Correlated,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap(),
        ),
        named(
            "ggx anisotropic 0.05/0.5 correlated, visible normals",
            Ggx::anisotropic(
                c,
                0.05,
                0.5,
                SmithForm::Correlated,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap(),
        ),
        named(
            "ggx anisotropic 0.6/0.15 separable, normals",
            Ggx::anisotropic(
                w(1.0),
                0.6,
                0.15,
                SmithForm::Separable,
                MicrofacetSampling::Normals,
            )
            .unwrap(),
        ),
        named(
            "torrance-sparrow sigma=0.2 smith G, kd 0.3",
            TorranceSparrow::<f64>::new(
                0.2,
                GeometricTerm::SmithCorrelated,
                brdf_core::fresnel::Fresnel::schlick(0.04).unwrap(),
                0.7,
                0.3,
            )
            .unwrap(),
        ),
        named(
            "torrance-sparrow sigma=0.3 modified G",
            TorranceSparrow::<f64>::specular(0.3, GeometricTerm::Modified).unwrap(),
        ),
        named(
            "ggx a=1 correlated",
            Ggx::new(
                w(1.0),
                1.0,
                SmithForm::Correlated,
                MicrofacetSampling::Normals,
            )
            .unwrap(),
        ),
        named(
            "sheen r=0.1 estevez-kulla",
            Sheen::new(c, 0.1, SheenVisibility::EstevezKulla).unwrap(),
        ),
        named(
            "sheen r=1 ashikhmin",
            Sheen::new(w(1.0), 1.0, SheenVisibility::Ashikhmin).unwrap(),
        ),
    ]
}

// ---------------------------------------------------------------- chi-square machinery

/// ln Γ(x) for x > 0 (Lanczos, g = 7, n = 9), accurate to ~1e-15 relative.
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// The regularised upper incomplete gamma Q(a, x) (series below a + 1, continued fraction
/// above).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let lg = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        1.0 - sum * lg.exp()
    } else {
        // Modified Lentz.
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        lg.exp() * h
    }
}

#[test]
fn gamma_q_matches_closed_forms() {
    // dof 2: Q(1, x) = e^{−x}; dof 1: Q(½, x) = erfc(√x).
    for x in [0.1, 1.0, 3.0, 10.0, 40.0] {
        assert!((gamma_q(1.0, x) - (-x).exp()).abs() < 1e-13);
        let e = libm::erfc(x.sqrt());
        assert!((gamma_q(0.5, x) - e).abs() < 1e-12 * (1.0 + 1.0 / e.max(1e-300)).min(1e3));
    }
    // Integer a: Q(a, x) = e^{−x} Σ_{k<a} x^k/k! (the Poisson tail), both branches.
    for (a, x) in [(3usize, 1.5f64), (10, 15.0), (50, 50.0), (200, 180.0)] {
        let (mut term, mut sum) = (1.0f64, 0.0f64);
        for k in 0..a {
            if k > 0 {
                term *= x / k as f64;
            }
            sum += term;
        }
        let want = (-x).exp() * sum;
        let got = gamma_q(a as f64, x);
        assert!((got - want).abs() < 1e-10, "Q({a}, {x}) = {got} vs {want}");
    }
}

const NZ: usize = 16; // cells in cos θ over [−1, 1] (an edge at the horizon)
const NP: usize = 32; // cells in φ
const SAMPLES: usize = 200_000;

struct ChiResult {
    chi2: f64,
    dof: usize,
    p: f64,
    bad_samples: usize,
}

/// Draws SAMPLES samples for `wo`, checks each against eval/pdf/delta, and runs the
/// chi-square test of the histogram against the integrated pdf.
fn chi_square(b: &dyn Brdf<f64>, wo: Vec3<f64>, seed: u64) -> ChiResult {
    let cell_of = |v: Vec3<f64>| {
        let iz = (((v.z + 1.0) * 0.5 * NZ as f64) as usize).min(NZ - 1);
        let phi = v.y.atan2(v.x).rem_euclid(2.0 * PI);
        iz * NP + ((phi / (2.0 * PI) * NP as f64) as usize).min(NP - 1)
    };
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut hist = vec![0usize; NZ * NP];
    let (mut n_delta, mut n_fail, mut bad) = (0usize, 0usize, 0usize);
    let delta = b.delta(wo);
    for _ in 0..SAMPLES {
        let u = [rng.random::<f64>(), rng.random::<f64>()];
        let s = match b.sample(wo, u) {
            Some(s) => s,
            None => {
                n_fail += 1;
                continue;
            }
        };
        let wi = s.wi;
        let unit_ok = (wi.length_sq() - 1.0).abs() < 1e-9;
        if s.specular {
            n_delta += 1;
            let d = delta.expect("specular sample from a model without a Dirac part");
            let ok = unit_ok
                && wi.sub(d.wi).length_sq() < 1e-20
                && s.pdf == d.prob
                && close_rgb(s.weight, d.reflectance.scale(1.0 / d.prob), 1e-12);
            if !ok {
                bad += 1;
            }
            continue;
        }
        let pdf = b.pdf(wo, wi);
        let f = b.eval(wi, wo);
        // f |cos θi|/pdf: below the horizon eval is 0 for a BRDF, the transmitted part for
        // a BSDF (rough-dielectric).
        let want_w = f.scale(wi.z.abs() / pdf);
        let ok = unit_ok
            && s.pdf > 0.0
            && (s.pdf - pdf).abs() <= 1e-9 * pdf
            && close_rgb(s.weight, want_w, 1e-9)
            && s.weight.is_finite();
        if !ok {
            bad += 1;
        }
        hist[cell_of(wi)] += 1;
    }
    // Expected counts. Half-vector pdfs have an integrable point singularity at wi = −wo
    // (below the horizon, where wo·h → 0); that cell is not integrated but merged with the
    // failure cell, whose expected count is then the exact remainder.
    let singular = cell_of(wo.scale(-1.0));
    let n = SAMPLES as f64;
    let mut cells: Vec<(f64, f64)> = Vec::with_capacity(NZ * NP + 2);
    let mut total_p = 0.0;
    for iz in 0..NZ {
        let z0 = -1.0 + 2.0 * iz as f64 / NZ as f64;
        let z1 = -1.0 + 2.0 * (iz + 1) as f64 / NZ as f64;
        for ip in 0..NP {
            if iz * NP + ip == singular {
                continue;
            }
            let p0 = 2.0 * PI * ip as f64 / NP as f64;
            let p1 = 2.0 * PI * (ip + 1) as f64 / NP as f64;
            let prob = adapt(
                &mut |z: f64| {
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    adapt(
                        &mut |phi: f64| b.pdf(wo, Vec3::new(r * phi.cos(), r * phi.sin(), z)),
                        p0,
                        p1,
                        1e-10,
                    )
                },
                z0,
                z1,
                1e-8,
            );
            total_p += prob;
            cells.push((hist[iz * NP + ip] as f64, prob * n));
        }
    }
    let p_delta = delta.map(|d| d.prob).unwrap_or(0.0);
    cells.push((n_delta as f64, p_delta * n));
    cells.push((
        (n_fail + hist[singular]) as f64,
        (1.0 - total_p - p_delta).max(0.0) * n,
    ));
    if std::env::var("CHI_DEBUG").is_ok() {
        let mut v: Vec<(usize, f64, f64)> = cells
            .iter()
            .enumerate()
            .map(|(i, c)| (i, c.0, c.1))
            .collect();
        v.sort_by(|a, b| {
            ((b.1 - b.2).powi(2) / b.2.max(1e-9))
                .partial_cmp(&((a.1 - a.2).powi(2) / a.2.max(1e-9)))
                .unwrap()
        });
        for x in v.iter().take(8) {
            println!(
                "cell {} (iz {}, ip {}): obs {} exp {:.2}",
                x.0,
                x.0 / NP,
                x.0 % NP,
                x.1,
                x.2
            );
        }
    }
    let (chi2, dof) = pooled_chi2(cells);
    ChiResult {
        chi2,
        dof,
        p: if dof == 0 {
            1.0
        } else {
            gamma_q(dof as f64 / 2.0, chi2 / 2.0)
        },
        bad_samples: bad,
    }
}

/// ∫ₐᵇ f by bisection with the 8-point Gauss–Legendre rule, comparing each panel with its
/// two halves, to absolute tolerance `tol` or 9 levels (the cap bounds the cost near the
/// integrable point singularity of half-vector pdfs at wi = −wo, below the horizon).
fn adapt(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    fn gl(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64) -> f64 {
        GaussLegendre::<8>::integrate(a, b, |x: f64| f(x))
    }
    fn rec(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, whole: f64, tol: f64, depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let (l, r) = (gl(f, a, m), gl(f, m, b));
        if depth == 0 || (l + r - whole).abs() <= tol {
            return l + r;
        }
        rec(f, a, m, l, 0.5 * tol, depth - 1) + rec(f, m, b, r, 0.5 * tol, depth - 1)
    }
    let whole = gl(f, a, b);
    rec(f, a, b, whole, tol, 9)
}

fn close_rgb(a: Rgb<f64>, b: Rgb<f64>, rel: f64) -> bool {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .all(|(x, y)| (x - y).abs() <= rel * y.abs().max(x.abs()) + 1e-300)
}

/// Pools cells with expected < 5 into one cell (merged into the smallest remaining cell if
/// the pool itself stays below 5) and returns (χ², degrees of freedom).
fn pooled_chi2(cells: Vec<(f64, f64)>) -> (f64, usize) {
    let mut keep: Vec<(f64, f64)> = Vec::new();
    let (mut po, mut pe) = (0.0, 0.0);
    for (o, e) in cells {
        if e < 5.0 {
            po += o;
            pe += e;
        } else {
            keep.push((o, e));
        }
    }
    if po > 0.0 || pe > 0.0 {
        if pe >= 5.0 || keep.is_empty() {
            keep.push((po, pe));
        } else {
            let i = (0..keep.len())
                .min_by(|&a, &b| keep[a].1.partial_cmp(&keep[b].1).unwrap())
                .unwrap();
            keep[i].0 += po;
            keep[i].1 += pe;
        }
    }
    let mut chi2 = 0.0;
    for (o, e) in &keep {
        if *e > 0.0 {
            chi2 += (o - e) * (o - e) / e;
        } else if *o > 0.0 {
            chi2 = f64::INFINITY;
        }
    }
    (chi2, keep.len().saturating_sub(1))
}

fn dir(theta_deg: f64, phi: f64) -> Vec3<f64> {
    Vec3::from_spherical(theta_deg.to_radians(), phi)
}

#[test]
fn samplers_fit_their_pdfs() {
    // Near-normal, oblique and grazing views; azimuths off the axes so anisotropy shows.
    let views = [(5.0, 0.3), (50.0, 1.1), (85.0, 2.4)];
    let only = std::env::var("CHI_ONLY").ok();
    // (The modified-G Cook–Torrance case shares its sampler with the other two.)
    let models: Vec<Named> = all_models()
        .into_iter()
        .filter(|m| !m.name.contains("modified G"))
        .collect();
    let cases = models.len() * views.len();
    let alpha = 1.0 - (1.0f64 - 0.01).powf(1.0 / cases as f64);
    println!("chi-square: {cases} cases, Šidák-corrected per-case significance {alpha:.3e}");
    println!(
        "{:36} {:>6} {:>10} {:>5} {:>10}",
        "model", "θo", "χ²", "dof", "p"
    );
    let mut failures = Vec::new();
    let mut seed = 1u64;
    for m in &models {
        for &(th, ph) in &views {
            seed += 1;
            if only.as_deref().is_some_and(|o| !m.name.contains(o)) {
                continue;
            }
            let r = chi_square(m.model.as_ref(), dir(th, ph), seed);
            println!(
                "{:36} {:>6.1} {:>10.2} {:>5} {:>10.4}",
                m.name, th, r.chi2, r.dof, r.p
            );
            if r.bad_samples > 0 {
                failures.push(format!(
                    "{} θo={th}: {} inconsistent samples",
                    m.name, r.bad_samples
                ));
            }
            if r.p.is_nan() || r.p <= alpha {
                failures.push(format!(
                    "{} θo={th}: p = {:.3e} (χ² {:.1}, dof {})",
                    m.name, r.p, r.chi2, r.dof
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A sampler fed into the chi-square test directly (the plain hemisphere samplers).
struct RawSampler {
    cosine: bool,
}

impl Brdf<f64> for RawSampler {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags {
            reciprocal: true,
            energy_conserving: true,
            has_delta: false,
        }
    }
    fn eval(&self, wi: Vec3<f64>, wo: Vec3<f64>) -> Rgb<f64> {
        if wi.z > 0.0 && wo.z > 0.0 {
            Rgb::splat(1.0 / PI)
        } else {
            Rgb::zero()
        }
    }
    fn pdf(&self, _wo: Vec3<f64>, wi: Vec3<f64>) -> f64 {
        if self.cosine {
            brdf_core::sampling::cosine_hemisphere_pdf(wi)
        } else {
            brdf_core::sampling::uniform_hemisphere_pdf(wi)
        }
    }
    fn sample(&self, wo: Vec3<f64>, u: [f64; 2]) -> Option<BrdfSample<f64>> {
        let wi = if self.cosine {
            brdf_core::sampling::sample_cosine_hemisphere(u)
        } else {
            brdf_core::sampling::sample_uniform_hemisphere(u)
        };
        let pdf = self.pdf(wo, wi);
        Some(BrdfSample {
            wi,
            pdf,
            weight: self.eval(wi, wo).scale(wi.z / pdf),
            specular: false,
        })
    }
}

#[test]
fn hemisphere_samplers_fit() {
    for cosine in [false, true] {
        let r = chi_square(&RawSampler { cosine }, dir(30.0, 0.0), 99);
        println!(
            "hemisphere cosine={cosine}: χ² {:.2} dof {} p {:.4}",
            r.chi2, r.dof, r.p
        );
        // Two cases: Šidák over two.
        assert!(r.p > 1.0 - 0.99f64.sqrt() && r.bad_samples == 0);
    }
}

// ---------------------------------------------------------------- reciprocity

fn random_upper(rng: &mut Pcg64) -> Vec3<f64> {
    let z: f64 = rng.random_range(1e-3..1.0);
    let phi: f64 = rng.random_range(0.0..2.0 * PI);
    let r = (1.0 - z * z).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

#[test]
fn reciprocity_where_claimed_and_only_there() {
    let mut rng = Pcg64::seed_from_u64(7);
    for m in all_models() {
        let mut worst: f64 = 0.0;
        for _ in 0..20_000 {
            let (a, b) = (random_upper(&mut rng), random_upper(&mut rng));
            let f1 = m.model.eval(a, b).to_array();
            let f2 = m.model.eval(b, a).to_array();
            for (x, y) in f1.iter().zip(f2) {
                let scale = x.abs().max(y.abs());
                if scale > 1e-300 {
                    worst = worst.max((x - y).abs() / scale);
                }
            }
        }
        let flags = m.model.flags();
        println!(
            "{:36} reciprocal={:5}  worst relative asymmetry {worst:.2e}",
            m.name, flags.reciprocal
        );
        if flags.reciprocal {
            assert!(worst <= 1e-5, "{} claims reciprocity: {worst:e}", m.name);
        } else {
            assert!(
                worst > 1e-3,
                "{} says it is not reciprocal but is: {worst:e}",
                m.name
            );
        }
    }
}

// ---------------------------------------------------------------- energy

#[test]
fn energy_conservation_where_claimed() {
    let thetas = [0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.5];
    println!(
        "{:36} {:>9} {:>8} {:>7}",
        "model", "max R", "at θo", "claims"
    );
    for m in all_models() {
        let flags = m.model.flags();
        let mut best = (f64::MIN, 0.0);
        for &th in &thetas {
            for ph in [0.0, 0.7] {
                let a = directional_albedo(m.model.as_ref(), dir(th, ph)).max_channel();
                assert!(a.is_finite() && a >= 0.0, "{} θo={th}: albedo {a}", m.name);
                if a > best.0 {
                    best = (a, th);
                }
            }
        }
        println!(
            "{:36} {:>9.5} {:>8.1} {:>7}",
            m.name, best.0, best.1, flags.energy_conserving
        );
        if flags.energy_conserving {
            assert!(
                best.0 <= 1.0 + 1e-4,
                "{} claims conservation: max albedo {}",
                m.name,
                best.0
            );
        }
    }
}

#[test]
fn printed_coupled_k_exceeds_and_corrected_does_not() {
    let n = Vec3::new(0.0, 0.0, 1.0);
    let printed = CoupledSmooth::new(w(1.0), 0.04, CoupledK::Printed).unwrap();
    let fixed = CoupledSmooth::new(w(1.0), 0.04, CoupledK::Conserving).unwrap();
    let ap = directional_albedo(&printed, n).r;
    let af = directional_albedo(&fixed, n).r;
    println!("coupled R0=0.04 Rm=1 at normal incidence: printed k {ap:.5}, corrected k {af:.5}");
    // Independent closed forms: R0 + 1/(1 − R0) and exactly 1.
    assert!((ap - (0.04 + 1.0 / 0.96)).abs() < 1e-6 && ap > 1.08);
    assert!((af - 1.0).abs() < 1e-6);
    assert!(!printed.flags().energy_conserving && fixed.flags().energy_conserving);
}

#[test]
fn ward_flag_is_honest_its_albedo_exceeds_one_at_grazing() {
    let m = Ward::new(w(0.0), w(1.0), 1.0, 1.0).unwrap();
    let a = directional_albedo(&m, dir(89.9, 0.4)).r;
    println!("ward ax=ay=1 rs=1 at θo=89.9°: albedo {a:.4}");
    assert!(a > 1.2 && !m.flags().energy_conserving);
}

#[test]
fn white_furnace_lambert() {
    let l = Lambert::new(w(1.0)).unwrap();
    for th in [0.0, 30.0, 60.0, 85.0, 89.9] {
        let a = directional_albedo(&l, dir(th, 0.2));
        assert!((a.r - 1.0).abs() < 1e-6, "{th}: {a:?}");
    }
    // And by Monte Carlo with its own sampler: every weight is exactly ρ.
    let mut rng = Pcg64::seed_from_u64(3);
    for _ in 0..1000 {
        let s = l
            .sample(dir(40.0, 0.0), [rng.random(), rng.random()])
            .unwrap();
        assert!((s.weight.r - 1.0).abs() < 1e-12);
    }
}

// ---------------------------------------------------------------- robustness

fn awkward_pairs() -> Vec<(Vec3<f64>, Vec3<f64>)> {
    let n = Vec3::new(0.0, 0.0, 1.0);
    let g = Vec3::new((1.0f64 - 1e-14).sqrt(), 0.0, 1e-7);
    let g2 = Vec3::new(0.0, -(1.0f64 - 1e-14).sqrt(), 1e-7);
    let hz = Vec3::new(1.0, 0.0, 0.0);
    let below = Vec3::new(0.3, 0.0, -(1.0f64 - 0.09).sqrt());
    let mid = dir(40.0, 0.5);
    vec![
        (n, n),
        (g, g),
        (g, n),
        (n, g),
        (g, g2),
        (g.scale(-1.0).add(Vec3::new(0.0, 0.0, 2e-7)), g),
        (mid, Vec3::new(-mid.x, -mid.y, -mid.z)),
        (Vec3::new(-mid.x, -mid.y, -mid.z), mid),
        (hz, n),
        (n, hz),
        (below, n),
        (n, below),
        (mid, Vec3::new(-mid.x, -mid.y, mid.z)),
    ]
}

fn check_finite<T: Real>(name: &str, b: &dyn Brdf<T>, pairs: &[(Vec3<T>, Vec3<T>)]) {
    let us = [0.0, 1e-12, 0.25, 0.5, 0.999_999, 1.0 - 1e-16, 1.0];
    for &(wi, wo) in pairs {
        let f = b.eval(wi, wo);
        assert!(
            f.is_finite() && f.min_channel() >= T::ZERO,
            "{name}: eval({wi:?}, {wo:?}) = {f:?}"
        );
        let p = b.pdf(wo, wi);
        assert!(p.is_finite() && p >= T::ZERO, "{name}: pdf = {p:?}");
        for &u0 in &us {
            for &u1 in &us {
                if let Some(s) = b.sample(wo, [T::from_f64(u0), T::from_f64(u1)]) {
                    assert!(
                        s.weight.is_finite() && s.pdf.is_finite() && s.pdf > T::ZERO,
                        "{name}: sample({wo:?}, {u0}, {u1}) = {s:?}"
                    );
                    assert!(s.wi.x.is_finite() && s.wi.y.is_finite() && s.wi.z.is_finite());
                }
            }
        }
        // wo at or below the horizon (or on it) never samples.
        if wo.z <= T::ZERO {
            assert!(
                b.sample(wo, [T::from_f64(0.3), T::from_f64(0.6)]).is_none(),
                "{name}"
            );
        }
        let a = directional_albedo(b, wo);
        assert!(a.is_finite(), "{name}: albedo {a:?}");
    }
}

fn extreme_models<T: Real>() -> Vec<(String, Box<dyn Brdf<T>>)> {
    let one = Rgb::splat(T::ONE);
    let half = Rgb::splat(T::HALF);
    let f = T::from_f64;
    let mut v: Vec<(String, Box<dyn Brdf<T>>)> = Vec::new();
    for a in [1e-4, 1.0, 1e4] {
        for smith in [SmithForm::Separable, SmithForm::Correlated] {
            for s in [
                MicrofacetSampling::VisibleNormals,
                MicrofacetSampling::Normals,
            ] {
                v.push((
                    format!("ggx {a} {smith:?} {s:?}"),
                    Box::new(Ggx::new(one, f(a), smith, s).unwrap()),
                ));
            }
        }
        v.push((
            format!("ward {a}"),
            Box::new(Ward::new(half, half, f(a), f(1e4 / a.max(1.0))).unwrap()),
        ));
        for g in GeometricTerm::ALL {
            if a < 1e4 {
                v.push((
                    format!("cook-torrance {a} {g:?}"),
                    Box::new(CookTorrance::new(half, half, f(a), f(0.04), g).unwrap()),
                ));
            }
        }
    }
    for n in [0.0, 1.0, 1e6] {
        v.push((
            format!("phong {n}"),
            Box::new(PhongNormalized::new(half, half, f(n)).unwrap()),
        ));
        v.push((
            format!("blinn-phong {n}"),
            Box::new(BlinnPhongNormalized::new(half, half, f(n)).unwrap()),
        ));
        v.push((
            format!("as {n}/0"),
            Box::new(AshikhminShirley::new(one, half, f(n), T::ZERO).unwrap()),
        ));
        v.push((
            format!("as {n}/1e6"),
            Box::new(AshikhminShirley::new(half, half, f(n), f(1e6)).unwrap()),
        ));
        v.push((
            format!("bank {n}"),
            Box::new(Bank::new(half, one, f(n), BankTangent::Azimuth(T::ZERO)).unwrap()),
        ));
        v.push((
            format!("bank nxv {n}"),
            Box::new(Bank::new(half, one, f(n), BankTangent::NormalCrossView).unwrap()),
        ));
        for h in [Highlight::Phong, Highlight::BlinnPhong] {
            v.push((
                format!("standard {n} {h:?}"),
                Box::new(StandardLighting::new(one, one, one, one, f(n), h).unwrap()),
            ));
        }
    }
    for r in [0.0, 1.0] {
        for vis in SheenVisibility::ALL {
            v.push((
                format!("sheen {r} {vis:?}"),
                Box::new(Sheen::new(one, f(r), *vis).unwrap()),
            ));
        }
    }
    v.push(("lambert".into(), Box::new(Lambert::new(one).unwrap())));
    v.push((
        "mix".into(),
        Box::new(LambertSpecularMix::new(half, T::HALF).unwrap()),
    ));
    v.push((
        "mix black".into(),
        Box::new(LambertSpecularMix::new(Rgb::zero(), T::ZERO).unwrap()),
    ));
    v.push((
        "mix mirror".into(),
        Box::new(LambertSpecularMix::new(Rgb::zero(), T::ONE).unwrap()),
    ));
    v.push((
        "shirley".into(),
        Box::new(ShirleyDamped::new(one, T::ONE).unwrap()),
    ));
    v.push((
        "coupled".into(),
        Box::new(CoupledSmooth::new(one, T::ZERO, CoupledK::Printed).unwrap()),
    ));
    v
}

#[test]
fn no_nan_or_inf_anywhere() {
    let pairs = awkward_pairs();
    for (name, m) in extreme_models::<f64>() {
        check_finite(&name, m.as_ref(), &pairs);
    }
    let pairs32: Vec<(Vec3<f32>, Vec3<f32>)> = pairs
        .iter()
        .map(|(a, b)| {
            let c = |v: &Vec3<f64>| Vec3::new(v.x as f32, v.y as f32, v.z as f32);
            (c(a), c(b))
        })
        .collect();
    for (name, m) in extreme_models::<f32>() {
        check_finite(&format!("f32 {name}"), m.as_ref(), &pairs32);
    }
}

#[test]
fn bad_parameters_are_typed_errors() {
    let one = Rgb::splat(1.0);
    let oor = |e: ParamError| matches!(e, ParamError::OutOfRange { .. });
    let nf = |e: ParamError| matches!(e, ParamError::NotFinite { .. });
    let v = MicrofacetSampling::VisibleNormals;
    assert!(oor(
        Ggx::new(one, 0.0, SmithForm::Correlated, v).unwrap_err()
    ));
    assert!(nf(
        Ggx::new(one, f64::NAN, SmithForm::Correlated, v).unwrap_err()
    ));
    assert!(oor(Ward::new(one, one, 0.0, 0.1).unwrap_err()));
    assert!(oor(CookTorrance::new(
        one,
        one,
        0.0,
        0.04,
        GeometricTerm::Blinn
    )
    .unwrap_err()));
    assert!(oor(PhongNormalized::new(one, one, -1.0).unwrap_err()));
    assert!(nf(
        BlinnPhongNormalized::new(one, one, f64::INFINITY).unwrap_err()
    ));
    assert!(oor(Lambert::new(Rgb::new(0.5, 1.5, 0.5)).unwrap_err()));
    assert!(oor(
        LambertSpecularMix::new(Rgb::splat(0.7), 0.4).unwrap_err()
    ));
    assert!(oor(
        CoupledSmooth::new(one, 1.0, CoupledK::Printed).unwrap_err()
    ));
    assert!(oor(AshikhminShirley::new(one, one, -1.0, 1.0).unwrap_err()));
    assert!(nf(
        Bank::new(one, one, 1.0, BankTangent::Azimuth(f64::NAN)).unwrap_err()
    ));
    assert!(oor(StandardLighting::new(
        one,
        one,
        one,
        Rgb::splat(-1.0),
        1.0,
        Highlight::Phong
    )
    .unwrap_err()));
}

// ------------------------------------------- Beckmann visible normals, anisotropic

/// The Beckmann visible-normal sampler seen as a "BRDF": h is reflected into wi as every
/// microfacet model does, pdf = the sampler's density converted to wi (FCG eq 24.12),
/// eval = pdf/cos θi so that every weight above the horizon is 1. This lets the chi-square
/// harness above test the anisotropic sampler against its own pdf.
struct VisibleBeckmannProbe {
    ax: f64,
    ay: f64,
}

impl Brdf<f64> for VisibleBeckmannProbe {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags {
            reciprocal: false,
            energy_conserving: false,
            has_delta: false,
        }
    }
    fn eval(&self, wi: Vec3<f64>, wo: Vec3<f64>) -> Rgb<f64> {
        if wi.z > 0.0 {
            Rgb::splat(self.pdf(wo, wi) / wi.z)
        } else {
            Rgb::zero()
        }
    }
    fn pdf(&self, wo: Vec3<f64>, wi: Vec3<f64>) -> f64 {
        match wi.add(wo).normalize() {
            Some(h) => sampling::wi_pdf_from_h(
                Beckmann::clamped(self.ax, self.ay).visible_normal_pdf(wo, h),
                wo.dot(h),
            ),
            None => 0.0,
        }
    }
    fn sample(&self, wo: Vec3<f64>, u: [f64; 2]) -> Option<BrdfSample<f64>> {
        let h = Beckmann::clamped(self.ax, self.ay).sample_visible_normal(wo, u)?;
        let wi = sampling::reflect_about(wo, h);
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BrdfSample {
            wi,
            pdf,
            weight: if wi.z > 0.0 {
                self.eval(wi, wo).scale(wi.z / pdf)
            } else {
                Rgb::zero()
            },
            specular: false,
        })
    }
}

#[test]
fn beckmann_visible_normal_pdf_is_normalised() {
    // ∫ G1(wo) max(wo·h, 0) D(h)/cos θo dω_h = 1 is the Smith G1 of this D, so this checks
    // the pdf (D, the projected width and Λ together) against the definition of G1.
    for (ax, ay) in [(0.3, 0.3), (0.15, 0.6), (1.0, 0.4)] {
        for (t, p) in [(0.0, 0.0), (40.0, 0.5), (80.0, 1.3), (89.0, 2.9)] {
            let wo = dir(t, p);
            let total = adapt(
                &mut |z: f64| {
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    adapt(
                        &mut |phi: f64| {
                            Beckmann::clamped(ax, ay)
                                .visible_normal_pdf(wo, Vec3::new(r * phi.cos(), r * phi.sin(), z))
                        },
                        0.0,
                        2.0 * PI,
                        1e-11,
                    )
                },
                0.0,
                1.0,
                1e-9,
            );
            assert!(
                (total - 1.0).abs() < 2e-4,
                "ax {ax} ay {ay} view ({t}°, {p}): ∫pdf = {total}"
            );
        }
    }
}

#[test]
fn beckmann_visible_normal_sampler_fits_its_pdf() {
    let cases = [(0.2, 0.6), (0.8, 0.3)];
    let views = [(5.0, 0.3), (60.0, 1.1), (85.0, 2.4), (89.0, 0.7)];
    let alpha = 1.0 - (1.0f64 - 0.01).powf(1.0 / (cases.len() * views.len()) as f64);
    for (k, &(ax, ay)) in cases.iter().enumerate() {
        for (j, &(t, p)) in views.iter().enumerate() {
            let r = chi_square(
                &VisibleBeckmannProbe { ax, ay },
                dir(t, p),
                9000 + (k * 10 + j) as u64,
            );
            println!(
                "visible Beckmann ax {ax} ay {ay} view {t}°: chi2 {:.1} dof {} p {:.3}",
                r.chi2, r.dof, r.p
            );
            assert_eq!(r.bad_samples, 0);
            assert!(r.p > alpha, "ax {ax} ay {ay} view {t}°: p = {}", r.p);
        }
    }
    // Degenerate input is None, never NaN.
    let b = Beckmann::isotropic(0.3).unwrap();
    let s = |wo: Vec3<f64>| b.sample_visible_normal(wo, [0.5, 0.5]);
    assert!(s(Vec3::new(0.0, 0.0, -1.0)).is_none());
    assert!(s(Vec3::new(f64::NAN, 0.0, 1.0)).is_none());
    // A zero width is refused by the checked constructor (the typed error, not a NaN sample).
    assert!(Beckmann::new(0.0, 0.3).is_err());
    // u at the ends of [0, 1] stays finite.
    for u in [[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]] {
        let h = Beckmann::new(0.5, 0.2)
            .unwrap()
            .sample_visible_normal(dir(70.0, 0.4), u)
            .unwrap();
        assert!(h.x.is_finite() && h.y.is_finite() && h.z > 0.0);
    }
}

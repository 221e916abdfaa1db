//! The kernels at their edges: mirror pairs at the horizon against an extended-precision
//! evaluation of the same formulas, extreme parameters, samplers at u = 0, 1 − ε and 1.0,
//! subnormal cosines, the orthonormal frame, and the probability ranges.
//!
//! The extended-precision reference: the only step of a microfacet BRDF that cancels near
//! the horizon is the half vector of a nearly opposite pair (wi ≈ −wo). The reference forms
//! H = wi + wo, |H|², H_z² and H_x² + H_y² in double-double arithmetic (error-free sums and
//! products, about 106 bits), so tan²θh, cos θh and wi·h = |H|/2 are correct to f64
//! rounding; the rest of each formula (exp, erfc, square roots of non-cancelling arguments,
//! each a few ulp) is evaluated in f64 from those, written out here independently of the
//! kernels. Its relative error is below 1e-13 for every pair used, far under the 1e-9 the
//! kernels are held to. The dot-product (shader) entry points are held to the same bounds
//! when their [`Dots`] come from the vectors, and to their documented bounds when they come
//! from the three dots alone or with a shader's n·h.

use brdf_core::distribution::SlopeDistribution;
use brdf_core::microfacet::{Beckmann, Distribution, Isotropic, TrowbridgeReitz};
use brdf_core::models::*;
use brdf_core::quadrature::DefaultRule;
use brdf_core::sampling;
use brdf_core::split_sum::dfg_ggx;
use brdf_core::{Dots, Frame, Real, Vec3};
use proptest::prelude::*;
use rand::Rng;
use rand::SeedableRng;
use rand_pcg::Pcg64;
use std::f64::consts::PI;

// ---------------------------------------------------------------- double-double

#[derive(Clone, Copy, Debug)]
struct Dd(f64, f64);

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd(s, (a - (s - bb)) + (b - bb))
}
fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    Dd(p, a.mul_add(b, -p))
}
impl Dd {
    fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.0, o.0);
        let e = s.1 + self.1 + o.1;
        two_sum(s.0, e)
    }
    fn mul(self, o: Dd) -> Dd {
        let p = two_prod(self.0, o.0);
        two_sum(p.0, p.1 + self.0 * o.1 + self.1 * o.0)
    }
    fn div(self, o: Dd) -> Dd {
        let q1 = self.0 / o.0;
        let r = self.add(o.mul(Dd(-q1, 0.0)));
        let q2 = r.0 / o.0;
        two_sum(q1, q2)
    }
    fn f(self) -> f64 {
        self.0 + self.1
    }
}

/// The half-vector quantities of (wi, wo) to f64 rounding: (tan²θh, cos θh, wi·h).
fn half_ref(wi: [f64; 3], wo: [f64; 3]) -> (f64, f64, f64) {
    let hx = two_sum(wi[0], wo[0]);
    let hy = two_sum(wi[1], wo[1]);
    let hz = two_sum(wi[2], wo[2]);
    let xy = hx.mul(hx).add(hy.mul(hy));
    let zz = hz.mul(hz);
    let all = xy.add(zz);
    let tan2 = xy.div(zz).f();
    let cos_h = zz.div(all).f().sqrt();
    let i_h = all.f().sqrt() / 2.0;
    (tan2, cos_h, i_h)
}

/// Smith–Beckmann Λ at polar cosine c for width α (c ≤ 0.5 here, so sin θ has no
/// cancellation): a = c/(α sin θ), Λ = (e^{−a²}/(a√π) − erfc a)/2.
fn lambda_beckmann_ref(c: f64, alpha: f64) -> f64 {
    let a = c / (alpha * (1.0 - c * c).sqrt());
    ((-a * a).exp() / (a * PI.sqrt()) - libm::erfc(a)) / 2.0
}

/// Smith–GGX Λ = (√(1 + α² tan²θ) − 1)/2 (tan²θ ≥ 1 here, no cancellation).
fn lambda_ggx_ref(c: f64, alpha: f64) -> f64 {
    let t2 = (1.0 - c * c) / (c * c);
    ((1.0 + alpha * alpha * t2).sqrt() - 1.0) / 2.0
}

#[derive(Clone, Copy, Debug)]
enum RefG {
    None,
    Blinn,
    BeckmannSeparable,
    BeckmannCorrelated,
    GgxSeparable,
    GgxCorrelated,
}

#[derive(Clone, Copy, Debug)]
enum RefD {
    Beckmann,
    Ggx,
}

/// D F G/(4 cos θi cos θo) with Schlick F from r0 (r0 = 1: F = 1).
fn brdf_ref(wi: [f64; 3], wo: [f64; 3], alpha: f64, d: RefD, g: RefG, r0: f64) -> f64 {
    let (tan2, cos_h, i_h) = half_ref(wi, wo);
    let a2 = alpha * alpha;
    let c4 = cos_h.powi(4);
    let dv = match d {
        RefD::Beckmann => (-tan2 / a2).exp() / (PI * a2 * c4),
        RefD::Ggx => 1.0 / (PI * a2 * c4 * (1.0 + tan2 / a2).powi(2)),
    };
    let (ni, no) = (wi[2], wo[2]);
    let gv = match g {
        RefG::None => 1.0,
        RefG::Blinn => 1f64.min(2.0 * cos_h * no / i_h).min(2.0 * cos_h * ni / i_h),
        RefG::BeckmannSeparable => {
            1.0 / ((1.0 + lambda_beckmann_ref(ni, alpha)) * (1.0 + lambda_beckmann_ref(no, alpha)))
        }
        RefG::BeckmannCorrelated => {
            1.0 / (1.0 + lambda_beckmann_ref(ni, alpha) + lambda_beckmann_ref(no, alpha))
        }
        RefG::GgxSeparable => {
            1.0 / ((1.0 + lambda_ggx_ref(ni, alpha)) * (1.0 + lambda_ggx_ref(no, alpha)))
        }
        RefG::GgxCorrelated => 1.0 / (1.0 + lambda_ggx_ref(ni, alpha) + lambda_ggx_ref(no, alpha)),
    };
    let f = r0 + (1.0 - r0) * (1.0 - i_h).powi(5);
    dv * f * gv / (4.0 * ni * no)
}

fn v3<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
}
fn widen<T: Real>(v: Vec3<T>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

// ---------------------------------------------------------------- the microfacet models

/// A model under test and the reference formula it implements.
struct Case<T> {
    name: String,
    eval: Box<dyn Fn(Vec3<T>, Vec3<T>) -> T>,
    alpha: f64,
    d: RefD,
    g: RefG,
    r0: f64,
}

impl<T: Real> Case<T> {
    /// A case: `name`, the reference's (α, D, G, r0), and the model's f.
    fn new(
        name: String,
        (alpha, d, g, r0): (f64, RefD, RefG, f64),
        eval: impl Fn(Vec3<T>, Vec3<T>) -> T + 'static,
    ) -> Self {
        Case {
            name,
            eval: Box::new(eval),
            alpha,
            d,
            g,
            r0,
        }
    }
}

fn cases<T: Real>() -> Vec<Case<T>> {
    let f = T::from_f64;
    let mut v: Vec<Case<T>> = Vec::new();
    for alpha in [0.05, 0.2, 0.5] {
        let sigma = alpha / 2f64.sqrt();
        for (gt, g) in [
            (GeometricTerm::SmithSeparable, RefG::BeckmannSeparable),
            (GeometricTerm::SmithCorrelated, RefG::BeckmannCorrelated),
            (GeometricTerm::Blinn, RefG::Blinn),
            (GeometricTerm::None, RefG::None),
        ] {
            let ts = TorranceSparrow::<T>::specular(f(sigma), gt).unwrap();
            v.push(Case::new(
                format!("torrance-sparrow alpha {alpha} {gt:?}"),
                (f(alpha).to_f64(), RefD::Beckmann, g, 1.0),
                move |wi, wo| ts.eval(wi, wo),
            ));
            // The shader form, with the dots taken from the vectors (local frame, and a
            // general frame whose normal happens to be +z).
            v.push(Case::new(
                format!("torrance-sparrow dots alpha {alpha} {gt:?}"),
                (f(alpha).to_f64(), RefD::Beckmann, g, 1.0),
                move |wi, wo| ts.eval_dots(Dots::from_local(wi, wo)),
            ));
            let n = Vec3::new(T::ZERO, T::ZERO, T::ONE);
            v.push(Case::new(
                format!("torrance-sparrow from_vectors alpha {alpha} {gt:?}"),
                (f(alpha).to_f64(), RefD::Beckmann, g, 1.0),
                move |wi, wo| ts.eval_dots(Dots::from_vectors(wi, wo, n)),
            ));
        }
        for (gt, g) in [
            (GeometricTerm::Blinn, RefG::Blinn),
            (GeometricTerm::SmithCorrelated, RefG::BeckmannCorrelated),
        ] {
            let ct = CookTorrance::<T>::new(
                Rgb::splat(f(0.0)),
                Rgb::splat(f(1.0)),
                f(alpha),
                f(0.04),
                gt,
            )
            .unwrap();
            v.push(Case::new(
                format!("cook-torrance m {alpha} {gt:?}"),
                (f(alpha).to_f64(), RefD::Beckmann, g, f(0.04).to_f64()),
                move |wi, wo| ct.eval(wi, wo).r,
            ));
        }
        for (sf, g) in [
            (SmithForm::Separable, RefG::GgxSeparable),
            (SmithForm::Correlated, RefG::GgxCorrelated),
        ] {
            let m = Ggx::<T>::new(
                Rgb::splat(f(1.0)),
                f(alpha),
                sf,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap();
            v.push(Case::new(
                format!("ggx alpha {alpha} {sf:?}"),
                (f(alpha).to_f64(), RefD::Ggx, g, 1.0),
                move |wi, wo| m.eval(wi, wo).r,
            ));
        }
    }
    v
}

/// A near-mirror pair near the horizon: cos θo log-uniform in [1e-7, 1e-2], cos θi within
/// a factor 2 of it on either side, azimuths opposite up to ±α (cos θi + cos θo). At the
/// horizon the half vector's tilt from an azimuth mismatch δ is about δ/(cos θi + cos θo),
/// so this keeps tan θh within about one width α and D far from negligible.
fn near_mirror_pair(rng: &mut Pcg64, alpha: f64) -> ([f64; 3], [f64; 3]) {
    let co = 10f64.powf(rng.random_range(-7.0..-2.0));
    let ci = co * 2f64.powf(rng.random_range(-1.0..1.0));
    let po = rng.random_range(0.0..2.0 * PI);
    let pi = po + PI + rng.random_range(-1.0..1.0) * alpha * (ci + co);
    let dir = |c: f64, p: f64| {
        let s = (1.0 - c * c).sqrt();
        [s * p.cos(), s * p.sin(), c]
    };
    (dir(ci, pi), dir(co, po))
}

/// A pair of unit directions near the horizon and f there, as published with the defect
/// report (12 significant digits).
struct HorizonPair {
    wi: [f64; 3],
    wo: [f64; 3],
    published: f64,
}

/// The defect report's pairs (Beckmann, α = 0.05000000074505806, separable Smith, F = 1).
const HORIZON_PAIRS: &[HorizonPair] = &[
    HorizonPair {
        wi: [
            -0.5536822645109706,
            -0.8327280167406141,
            1.0062167677184382e-05,
        ],
        wo: [0.5536824247997054, 0.8327279101650903, 1e-05],
        published: 154134.432937,
    },
    HorizonPair {
        wi: [
            0.39298152400471775,
            0.9195463673952927,
            1.02502789627328e-06,
        ],
        wo: [-0.39298152558074945, -0.9195463667217801, 1e-06],
        published: 159942.898969,
    },
];

#[test]
fn published_horizon_pairs_are_exact() {
    // Beckmann, α = 0.05000000074505806, separable Smith, F = 1. Values published with the
    // defect report (12 significant digits): the old kernel gave 154210.656671 and
    // 153510.447778 (5e-4 and 4e-2 off).
    let alpha = 0.05000000074505806;
    let ts = TorranceSparrow::<f64>::specular(alpha / 2f64.sqrt(), GeometricTerm::SmithSeparable)
        .unwrap();
    for &HorizonPair { wi, wo, published } in HORIZON_PAIRS {
        let r = brdf_ref(wi, wo, alpha, RefD::Beckmann, RefG::BeckmannSeparable, 1.0);
        // The published value has 12 significant digits: ±5e-12 relative from rounding.
        assert!(
            ((r - published) / published).abs() < 1e-11,
            "reference {r} vs {published}"
        );
        let (vi, vo) = (v3::<f64>(wi), v3::<f64>(wo));
        let n = Vec3::new(0.0, 0.0, 1.0);
        // Cook–Torrance with ks = 1, kd = 0, Schlick r0 = 1 (F = 1) is the same lobe.
        let ct = CookTorrance::<f64>::new(
            Rgb::splat(0.0),
            Rgb::splat(1.0),
            alpha,
            1.0,
            GeometricTerm::SmithSeparable,
        )
        .unwrap();
        let forms = [
            ("vectors", ts.eval(vi, vo)),
            ("dots from_local", ts.eval_dots(Dots::from_local(vi, vo))),
            (
                "dots from_vectors",
                ts.eval_dots(Dots::from_vectors(vi, vo, n)),
            ),
            ("cook-torrance vectors", ct.eval(vi, vo).r),
        ];
        for (form, got) in forms {
            let rel = ((got - r) / r).abs();
            println!("pair, {form}: kernel {got:.6} reference {r:.6} rel {rel:.1e}");
            assert!(
                rel < 1e-12,
                "{form}: kernel {got} vs reference {r}: {rel:e}"
            );
        }
        // The shader form with n·h from normalize(wi + wo) in f64: bounded by n·h's own
        // rounding (see `shader_n_h_form_within_its_bound`), 1.8e-13 relative here.
        let d = Dots::from_local(vi, vo);
        let nh = vi.add(vo).normalize().unwrap().z;
        let got = ts.eval_dots(Dots::with_n_h(d.n_i, d.n_o, d.i_o, nh));
        let rel = ((got - r) / r).abs();
        println!("pair, dots with_n_h: kernel {got:.6} rel {rel:.1e}");
        assert!(
            rel < 1e-11,
            "with_n_h: kernel {got} vs reference {r}: {rel:e}"
        );
    }
}

/// In-plane mirror pairs θi = θr = θ: H is exactly along n (tan θh = 0), so the reference is
/// the closed form D(0) G/(4 cos²θ) = G/(π α² 4 cos²θ) with the separable Smith G; the
/// angle form must reach it down to cos θ = 1e-6 (2 + 2 cos 2θ cancels there: the old
/// in-plane dots were 4e-2 off at cos θ = 1e-6).
#[test]
fn in_plane_mirror_pairs_at_the_horizon() {
    let alpha = 0.05;
    let ts = TorranceSparrow::<f64>::specular(alpha / 2f64.sqrt(), GeometricTerm::SmithSeparable)
        .unwrap();
    for c in [1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
        let theta = c.acos();
        let c = theta.cos();
        let l = lambda_beckmann_ref(c, alpha);
        let r = 1.0 / ((1.0 + l) * (1.0 + l)) / (PI * alpha * alpha * 4.0 * c * c);
        let got = ts.eval_in_plane(theta, theta);
        let rel = ((got - r) / r).abs();
        // A few ε from D, Λ (exp, erfc) and the products.
        assert!(rel < 1e-13, "cos θ {c:e}: kernel {got} vs {r}: {rel:e}");
    }
}

fn horizon_property<T: Real>(min_cos_checked: f64, tol: f64) -> f64 {
    let mut rng = Pcg64::seed_from_u64(0x12a);
    let mut worst: f64 = 0.0;
    for case in cases::<T>() {
        let mut case_worst: f64 = 0.0;
        for _ in 0..2000 {
            let (wi, wo) = near_mirror_pair(&mut rng, case.alpha);
            if let Some(rel) = pair_error(&case, wi, wo, min_cos_checked) {
                assert!(
                    rel <= tol,
                    "{}: wi {wi:?} wo {wo:?}: rel {rel:e}",
                    case.name
                );
                case_worst = case_worst.max(rel);
            }
        }
        println!("{}: worst rel {case_worst:.2e}", case.name);
        worst = worst.max(case_worst);
    }
    worst
}

#[test]
fn near_horizon_mirror_pairs_f64_within_1e9() {
    let w = horizon_property::<f64>(1e-6, 1e-9);
    println!("f64 worst relative error (cos θ ≥ 1e-6): {w:.2e}");
}

#[test]
fn near_horizon_mirror_pairs_f32_within_1e4() {
    let w = horizon_property::<f32>(1e-3, 1e-4);
    println!("f32 worst relative error (cos θ ≥ 1e-3): {w:.2e}");
}

/// Relative error of the kernel against the reference evaluated at exactly the kernel's
/// input (the pair rounded to T), or `None` below `min_cos_checked` (the kernel is then only
/// required to be finite and ≥ 0).
fn pair_error<T: Real>(
    case: &Case<T>,
    wi: [f64; 3],
    wo: [f64; 3],
    min_cos_checked: f64,
) -> Option<f64> {
    let (wi_t, wo_t) = (v3::<T>(wi), v3::<T>(wo));
    let (wi, wo) = (widen(wi_t), widen(wo_t));
    let got = (case.eval)(wi_t, wo_t).to_f64();
    assert!(got.is_finite() && got >= 0.0, "{}: {got}", case.name);
    if wi[2].min(wo[2]) < min_cos_checked {
        return None;
    }
    let r = brdf_ref(wi, wo, case.alpha, case.d, case.g, case.r0);
    assert!(
        r > 0.0,
        "{}: the pair must lie in the lobe: {wi:?} {wo:?}",
        case.name
    );
    let rel = ((got - r) / r).abs();
    if rel > 1e-3 {
        println!(
            "{}: {wi:?} {wo:?}: kernel {got:e} reference {r:e}",
            case.name
        );
    }
    Some(rel)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Near-horizon, near-mirror pairs (cos θo from 1e-7 to 1e-2, cos θi within a factor 2
    /// either side, any azimuth, azimuth mismatch within ±α(cos θi + cos θo)): every
    /// microfacet model, in its vector and its dot-product form, within 1e-9 (f64, both
    /// cosines ≥ 1e-6) and 1e-4 (f32, ≥ 1e-3) of the double-double reference. The f64 bound
    /// is far above the measured 2e-15; the f32 one covers the f32 rounding of the inputs'
    /// exponent tan²θh/α² (a few ε_f32 ≈ 1e-6 relative) with margin.
    #[test]
    fn near_horizon_pairs_every_model(
        lc in -7.0f64..-2.0, ratio in -1.0f64..1.0, po in 0.0..2.0 * PI, mis in -1.0f64..1.0,
    ) {
        let co = 10f64.powf(lc);
        let ci = co * 2f64.powf(ratio);
        let dir = |c: f64, p: f64| {
            let s = (1.0 - c * c).sqrt();
            [s * p.cos(), s * p.sin(), c]
        };
        for case in cases::<f64>() {
            let pi = po + PI + mis * case.alpha * (ci + co);
            if let Some(rel) = pair_error(&case, dir(ci, pi), dir(co, po), 1e-6) {
                prop_assert!(rel <= 1e-9, "{}: co {:e} ci {:e}: rel {:e}", case.name, co, ci, rel);
            }
        }
        for case in cases::<f32>() {
            let pi = po + PI + mis * case.alpha * (ci + co);
            if let Some(rel) = pair_error(&case, dir(ci, pi), dir(co, po), 1e-3) {
                prop_assert!(rel <= 1e-4, "{}: co {:e} ci {:e}: rel {:e}", case.name, co, ci, rel);
            }
        }
    }
}

/// The three-dots form ([`Dots::new`]) is limited by its input wi·wo, whose absolute
/// rounding error (≈ 2ε for a sum of three products near −1) becomes an absolute error of
/// ≈ 4ε on |H_t|² = 2 + 2 wi·wo − s² (s = cos θi + cos θo), so on the exponent
/// |H_t|²/(α² s²) of D ≈ 4ε/(α² s²): the documented loss, bounded here by 8ε/(α² s²).
/// At cos θ = 1e-3 and α = 0.05 that is ≈ 1e-7; the vector-built dots are at 1e-15.
#[test]
fn three_dots_form_within_its_bound() {
    let mut rng = Pcg64::seed_from_u64(7);
    let alpha = 0.05;
    let ts = TorranceSparrow::<f64>::specular(alpha / 2f64.sqrt(), GeometricTerm::SmithSeparable)
        .unwrap();
    let mut worst_ratio: f64 = 0.0;
    for _ in 0..2000 {
        let (wi, wo) = near_mirror_pair(&mut rng, alpha);
        if wi[2].min(wo[2]) < 1e-4 {
            continue;
        }
        let l = Dots::from_local(v3::<f64>(wi), v3::<f64>(wo));
        let d = Dots::new(l.n_i, l.n_o, l.i_o);
        let r = brdf_ref(wi, wo, alpha, RefD::Beckmann, RefG::BeckmannSeparable, 1.0);
        let rel = ((ts.eval_dots(d) - r) / r).abs();
        let s = wi[2] + wo[2];
        let bound = 8.0 * f64::EPSILON / (alpha * alpha * s * s) + 1e-13;
        assert!(rel <= bound, "{wi:?} {wo:?}: rel {rel:e} > {bound:e}");
        worst_ratio = worst_ratio.max(rel / bound);
    }
    println!("three-dots form: worst error / bound {worst_ratio:.2}");
}

/// The shader form with n·h ([`Dots::with_n_h`]), n·h = n·normalize(wi + wo) computed in the
/// kernel's precision: n·h carries a relative error of a few ε (sum, squares, square root,
/// division; ≤ 4ε), so 1 − n·h ≈ tan²θh/2 an absolute one of 4ε, and the exponent
/// tan²θh/α² of D an absolute error of ≈ 8ε/α²; bounded here by 16ε/α² (f64 at α = 0.05:
/// 1.4e-12; f32: 7.6e-4), whatever the cosines.
fn shader_n_h_form<T: Real>(min_cos: f64) {
    let mut rng = Pcg64::seed_from_u64(9);
    let eps = T::EPSILON.to_f64();
    for alpha in [0.05, 0.2] {
        let ts = TorranceSparrow::<T>::specular(
            T::from_f64(alpha / 2f64.sqrt()),
            GeometricTerm::SmithSeparable,
        )
        .unwrap();
        let a = T::from_f64(alpha).to_f64();
        let mut worst: f64 = 0.0;
        for _ in 0..1000 {
            let (wi, wo) = near_mirror_pair(&mut rng, alpha);
            let (wi_t, wo_t) = (v3::<T>(wi), v3::<T>(wo));
            let (wi, wo) = (widen(wi_t), widen(wo_t));
            if wi[2].min(wo[2]) < min_cos {
                continue;
            }
            let nh = wi_t.add(wo_t).normalize().unwrap().z;
            let l = Dots::from_local(wi_t, wo_t);
            let got = ts
                .eval_dots(Dots::with_n_h(l.n_i, l.n_o, l.i_o, nh))
                .to_f64();
            let r = brdf_ref(wi, wo, a, RefD::Beckmann, RefG::BeckmannSeparable, 1.0);
            let rel = ((got - r) / r).abs();
            let bound = 16.0 * eps / (a * a);
            assert!(
                rel <= bound,
                "α {alpha}: {wi:?} {wo:?}: rel {rel:e} > {bound:e}"
            );
            worst = worst.max(rel);
        }
        println!("with_n_h, α {alpha}: worst rel {worst:.2e}");
    }
}

#[test]
fn shader_n_h_form_within_its_bound() {
    shader_n_h_form::<f64>(1e-7);
    shader_n_h_form::<f32>(1e-5);
}

/// Every [`Dots`] constructor against the double-double half vector on generic pairs
/// (random directions in the upper hemisphere, 1 + wi·wo ≥ 1e-2, where none of them
/// cancels): n·h and wi·h within 1e-13 (a few ε, times at most 1/(1 + wi·wo) = 100 for the
/// three-dots form). The vector form is also taken in a random rotated frame, and the
/// angle form for in-plane pairs.
#[test]
fn dots_constructors_agree_on_generic_pairs() {
    let mut rng = Pcg64::seed_from_u64(11);
    let dir = |rng: &mut Pcg64| {
        let c: f64 = rng.random_range(0.05..1.0);
        let p: f64 = rng.random_range(0.0..2.0 * PI);
        let s = (1.0 - c * c).sqrt();
        [s * p.cos(), s * p.sin(), c]
    };
    let close = |name: &str, d: Dots<f64>, cos_h: f64, i_h: f64| {
        assert!(
            (d.n_h() - cos_h).abs() <= 1e-13,
            "{name}: n·h {} vs {cos_h}",
            d.n_h()
        );
        assert!(
            (d.i_h() - i_h).abs() <= 1e-13,
            "{name}: wi·h {} vs {i_h}",
            d.i_h()
        );
    };
    for _ in 0..2000 {
        let (wi, wo) = (dir(&mut rng), dir(&mut rng));
        let (vi, vo) = (v3::<f64>(wi), v3::<f64>(wo));
        if 1.0 + vi.dot(vo) < 1e-2 {
            continue;
        }
        let (_, cos_h, i_h) = half_ref(wi, wo);
        let l = Dots::from_local(vi, vo);
        close("from_local", l, cos_h, i_h);
        close("new", Dots::new(l.n_i, l.n_o, l.i_o), cos_h, i_h);
        let nh = vi.add(vo).normalize().unwrap().z;
        close(
            "with_n_h",
            Dots::with_n_h(l.n_i, l.n_o, l.i_o, nh),
            cos_h,
            i_h,
        );
        let axis = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let f = Frame::from_normal(axis.normalize().unwrap());
        let d = Dots::from_vectors(f.to_world(vi), f.to_world(vo), f.n);
        close("from_vectors", d, cos_h, i_h);
        // In-plane pairs: θi ∈ [0, π/2), θr signed.
        let ti: f64 = rng.random_range(0.0..1.5);
        let tr: f64 = rng.random_range(-1.5..1.5);
        let (pi, po) = brdf_core::geometry::in_plane_directions(ti, tr);
        let (_, cos_h, i_h) = half_ref(widen(pi), widen(po));
        if 1.0 + pi.dot(po) >= 1e-2 {
            close("in_plane", Dots::in_plane(ti, tr), cos_h, i_h);
        }
    }
}

// ---------------------------------------------------------------- extreme parameters

#[test]
fn extreme_roughness_is_rejected_or_finite() {
    let n = Vec3::new(0.0, 0.0, 1.0);
    // Checked constructors reject what the types cannot represent (the old kernel gave inf
    // at σ = 1e-160 and NaN at 1e-300, f32: 1e-20 and 1e-30).
    for s in [1e-160, 1e-300, 1e-5, 1e5, 1e300] {
        assert!(TorranceSparrow::<f64>::specular(s, GeometricTerm::SmithSeparable).is_err());
    }
    for s in [1e-20f32, 1e-30, 1e20] {
        assert!(TorranceSparrow::<f32>::specular(s, GeometricTerm::SmithSeparable).is_err());
    }
    // The ends of the accepted range are finite at the mirror direction.
    for s in [1e-4 / 2f64.sqrt() * 1.0001, 1e4 / 2f64.sqrt() * 0.9999] {
        for g in GeometricTerm::ALL {
            let t = TorranceSparrow::<f64>::specular(s, g).unwrap();
            let v = t.eval(n, n);
            assert!(v.is_finite() && v > 0.0, "{s} {g:?}: {v}");
            let t32 = TorranceSparrow::<f32>::specular(s as f32, g).unwrap();
            let v = t32.eval(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, 1.0));
            assert!(v.is_finite() && v > 0.0, "f32 {s} {g:?}: {v}");
        }
    }
    // The unchecked functions clamp α into [ε², 1/ε²]: finite, non-negative, G1 in [0, 1],
    // unit samples, for any α > 0 (an earlier GGX D was NaN at α ≤ 1e-170 and ≥ 1e155).
    for a in [1e-300, 1e-171, 1e-30, 1e-4, 1.0, 1e4, 1e30, 1e155, 1e300] {
        check_unchecked::<f64>(a);
    }
    for a in [
        1e-40f32 as f64,
        1e-30,
        1e-20,
        1e-4,
        1.0,
        1e4,
        1e20,
        1e30,
        3e38,
    ] {
        check_unchecked::<f32>(a);
    }
}

/// An isotropic distribution's name with its dot-product D and G1 (n·h or cos θ, α).
type IsotropicKernels<T> = (&'static str, fn(T, T) -> T, fn(T, T) -> T);

/// The [`Isotropic`] D and G1 of GGX and Beckmann.
fn isotropic_kernels<T: Real>() -> [IsotropicKernels<T>; 2] {
    [
        (
            "TrowbridgeReitz",
            TrowbridgeReitz::d_cos,
            TrowbridgeReitz::g1_cos,
        ),
        ("Beckmann", Beckmann::d_cos, Beckmann::g1_cos),
    ]
}

fn check_unchecked<T: Real>(a: f64) {
    let a = T::from_f64(a);
    for c in [1.0, 0.999999, 0.5, 1e-3, 1e-10] {
        let c = T::from_f64(c);
        for (name, d_cos, g1_cos) in isotropic_kernels::<T>() {
            let d = d_cos(c, a);
            assert!(
                d.is_finite() && d >= T::ZERO,
                "{name}::d_cos({c:?}, {a:?}) = {d:?}"
            );
            let g = g1_cos(c, a);
            assert!(
                g >= T::ZERO && g <= T::ONE,
                "{name}::g1_cos({c:?}, {a:?}) = {g:?}"
            );
        }
    }
    let wo = Vec3::new(T::from_f64(0.6), T::ZERO, T::from_f64(0.8));
    for u in [[0.0, 0.0], [0.5, 0.5], [1.0, 1.0], [0.999999, 0.3]] {
        let u = [T::from_f64(u[0]), T::from_f64(u[1])];
        for h in [
            Some(TrowbridgeReitz::clamped(a, a).sample_normal(u)),
            TrowbridgeReitz::clamped(a, a).sample_visible_normal(wo, u),
            Some(Beckmann::clamped(a, a).sample_normal(u)),
            Beckmann::clamped(a, a).sample_visible_normal(wo, u),
        ]
        .into_iter()
        .flatten()
        {
            let l = h.length_sq().to_f64();
            assert!((l - 1.0).abs() < 1e-5 && h.z >= T::ZERO, "α {a:?}: h {h:?}");
        }
    }
}

// ---------------------------------------------------------------- samplers at u's ends

fn us<T: Real>() -> [T; 4] {
    [T::ZERO, T::ONE - T::EPSILON, T::ONE, -T::from_f64(0.5)]
}

fn sampler_models<T: Real>() -> Vec<(String, Box<dyn Brdf<T>>)> {
    let f = T::from_f64;
    let w = |x: f64| Rgb::splat(f(x));
    let mut v: Vec<(String, Box<dyn Brdf<T>>)> = vec![
        ("lambert".into(), Box::new(Lambert::new(w(0.5)).unwrap())),
        (
            "phong kd0".into(),
            Box::new(PhongNormalized::new(w(0.0), w(1.0), f(32.0)).unwrap()),
        ),
        (
            "phong mix".into(),
            Box::new(PhongNormalized::new(w(0.3), w(0.5), f(1e5)).unwrap()),
        ),
        (
            "blinn-phong".into(),
            Box::new(BlinnPhongNormalized::new(w(0.0), w(1.0), f(32.0)).unwrap()),
        ),
        (
            "mix".into(),
            Box::new(LambertSpecularMix::new(w(0.5), f(0.3)).unwrap()),
        ),
        (
            "shirley r0=0".into(),
            Box::new(ShirleyDamped::new(w(0.5), f(0.0)).unwrap()),
        ),
        (
            "coupled r0=0".into(),
            Box::new(CoupledSmooth::new(w(0.5), f(0.0), CoupledK::Conserving).unwrap()),
        ),
        (
            "ashikhmin-shirley".into(),
            Box::new(AshikhminShirley::new(w(1.0), w(0.0), f(10.0), f(1e4)).unwrap()),
        ),
        (
            "bank".into(),
            Box::new(Bank::new(w(0.2), w(0.3), f(30.0), BankTangent::NormalCrossView).unwrap()),
        ),
        (
            "ward".into(),
            Box::new(Ward::new(w(0.0), w(1.0), f(0.1), f(0.4)).unwrap()),
        ),
        (
            "torrance-sparrow".into(),
            Box::new(
                TorranceSparrow::<T>::specular(f(0.2), GeometricTerm::SmithCorrelated).unwrap(),
            ),
        ),
    ];
    for vis in SheenVisibility::ALL {
        v.push((
            format!("sheen {vis:?}"),
            Box::new(Sheen::new(w(1.0), f(0.0), *vis).unwrap()),
        ));
    }
    for s in [
        MicrofacetSampling::Normals,
        MicrofacetSampling::VisibleNormals,
    ] {
        v.push((
            format!("cook-torrance {s:?}"),
            Box::new(
                CookTorrance::new(w(0.0), w(1.0), f(0.3), f(0.04), GeometricTerm::Blinn)
                    .unwrap()
                    .with_sampling(s),
            ),
        ));
        v.push((
            format!("ggx aniso {s:?}"),
            Box::new(Ggx::anisotropic(w(1.0), f(0.05), f(0.5), SmithForm::Correlated, s).unwrap()),
        ));
    }
    v
}

fn samplers_at_u_ends<T: Real>() {
    let wos = [
        [-0.969, -0.243, 0.0434],
        [0.0, 0.0, 1.0],
        [0.6, 0.0, 0.8],
        [0.99995, 0.0, 0.01],
    ];
    for (name, m) in sampler_models::<T>() {
        for wo in wos {
            let wo = Vec3::<T>::new(T::from_f64(wo[0]), T::from_f64(wo[1]), T::from_f64(wo[2]))
                .normalize()
                .unwrap();
            for u0 in us::<T>() {
                for u1 in us::<T>() {
                    let Some(s) = m.sample(wo, [u0, u1]) else {
                        continue;
                    };
                    let ok = s.pdf.is_finite()
                        && s.pdf > T::ZERO
                        && s.weight.is_finite()
                        && s.weight.min_channel() >= T::ZERO;
                    assert!(ok, "{name}: wo {wo:?} u [{u0:?}, {u1:?}]: {s:?}");
                    let l = s.wi.length_sq().to_f64();
                    assert!((l - 1.0).abs() < 1e-5, "{name}: |wi|² = {l}");
                    if !s.specular {
                        // The pdf of the sample is the model's pdf: a weight of f cos/pdf
                        // bounded by what the model can reflect, not a near-zero-pdf blow-up.
                        let p = m.pdf(wo, s.wi);
                        assert!(p > T::ZERO, "{name}: pdf {p:?}");
                    }
                }
            }
        }
    }
    // The plain samplers.
    for u0 in us::<T>() {
        for u1 in us::<T>() {
            for w in [
                sampling::sample_cosine_hemisphere([u0, u1]),
                sampling::sample_uniform_hemisphere([u0, u1]),
                sampling::sample_ashikhmin_shirley_h(
                    T::from_f64(10.0),
                    T::from_f64(100.0),
                    [u0, u1],
                ),
                sampling::sample_cosine_lobe(
                    Vec3::new(T::from_f64(0.6), T::ZERO, T::from_f64(0.8)),
                    T::from_f64(50.0),
                    [u0, u1],
                )
                .unwrap(),
            ] {
                let l = w.length_sq().to_f64();
                assert!((l - 1.0).abs() < 1e-5, "{w:?}");
            }
        }
    }
}

#[test]
fn samplers_at_u_ends_f64() {
    samplers_at_u_ends::<f64>();
}

#[test]
fn samplers_at_u_ends_f32() {
    samplers_at_u_ends::<f32>();
}

#[test]
fn published_sampler_cases() {
    // f32 normalised Phong, kd = 0: u = [1.0, 0.5] returned pdf 1.33e-43 and weight inf.
    let ph = PhongNormalized::<f32>::new(Rgb::splat(0.0), Rgb::splat(1.0), 32.0).unwrap();
    let s = ph.sample(Vec3::new(-0.969, -0.243, 0.0434), [1.0, 0.5]);
    if let Some(s) = s {
        assert!(s.weight.is_finite() && s.pdf > 1e-30, "{s:?}");
    }
    // Coupled and Shirley with r0 = 0 at wo = n and u0 < 0: the Dirac part has probability
    // 0 and must not be returned (it was, with pdf 0 and NaN weight).
    let n = Vec3::new(0.0, 0.0, 1.0);
    let c = CoupledSmooth::<f64>::new(Rgb::splat(0.5), 0.0, CoupledK::Conserving).unwrap();
    let s = c.sample(n, [-0.5, 0.5]).unwrap();
    assert!(!s.specular && s.weight.is_finite(), "{s:?}");
    let sh = ShirleyDamped::<f64>::new(Rgb::splat(0.5), 0.0).unwrap();
    let s = sh.sample(n, [-0.5, 0.5]).unwrap();
    assert!(!s.specular && s.weight.is_finite(), "{s:?}");
}

// ---------------------------------------------------------------- frames

fn orthonormal_error<T: Real>(f: &Frame<T>) -> f64 {
    let d = |a: Vec3<T>, b: Vec3<T>| a.dot(b).to_f64();
    [
        (d(f.s, f.s) - 1.0).abs(),
        (d(f.t, f.t) - 1.0).abs(),
        (d(f.n, f.n) - 1.0).abs(),
        d(f.s, f.t).abs(),
        d(f.s, f.n).abs(),
        d(f.t, f.n).abs(),
        // Right-handed: s × t = n.
        (d(f.s.cross(f.t), f.n) - 1.0).abs(),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

#[test]
fn frames_are_orthonormal_to_a_few_ulp() {
    // The published f32 axis nearly parallel to x (errors up to 2.2e-4 before).
    let x = Vec3::new(1.0f32, 0.0, 0.0);
    let f = Frame::new(Vec3::new(0.9999999f32, 0.0, 0.00044721), x).unwrap();
    let e = orthonormal_error(&f);
    assert!(e < 8.0 * f32::EPSILON as f64, "{e}");
    // Random axes and hints, and the hint-free frame, in both types; 8ε allows the few
    // roundings of a dot product of unit vectors.
    let mut rng = Pcg64::seed_from_u64(5);
    for k in 0..20000 {
        let n: [f64; 3] = if k % 3 == 0 {
            // Nearly parallel to an axis, either sign.
            let i = rng.random_range(0..3);
            let mut v = [
                rng.random_range(-1e-3..1e-3),
                rng.random_range(-1e-3..1e-3),
                0.0,
            ];
            v.swap(2, i);
            v[i] = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            v
        } else {
            [
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ]
        };
        let hint = [1.0, 0.0, 0.0];
        let f64f = Frame::new(v3::<f64>(n), v3::<f64>(hint));
        let f32f = Frame::new(v3::<f32>(n), v3::<f32>(hint));
        if let (Some(a), Some(b)) = (f64f, f32f) {
            assert!(orthonormal_error(&a) < 8.0 * f64::EPSILON, "{n:?}");
            assert!(orthonormal_error(&b) < 8.0 * f32::EPSILON as f64, "{n:?}");
            let a = Frame::from_normal(a.n);
            let b = Frame::from_normal(b.n);
            assert!(orthonormal_error(&a) < 8.0 * f64::EPSILON, "{n:?}");
            assert!(orthonormal_error(&b) < 8.0 * f32::EPSILON as f64, "{n:?}");
        }
    }
    // Phong's sampled wi is unit for the published axis (it was 1.0001936 long).
    let wo = Vec3::new(-0.9999999f32, 0.0, 0.00044721)
        .normalize()
        .unwrap();
    for u in [[0.1f32, 0.2], [0.7, 0.9], [0.999, 0.5]] {
        let w = sampling::sample_cosine_lobe(Vec3::new(-wo.x, -wo.y, wo.z), 32.0, u).unwrap();
        assert!((w.length_sq() - 1.0).abs() < 4.0 * f32::EPSILON, "{w:?}");
    }
}

// ---------------------------------------------------------------- subnormal cosines

fn subnormal_models<T: Real>() -> Vec<(String, Box<dyn Brdf<T>>)> {
    let mut v = sampler_models::<T>();
    let f = T::from_f64;
    let w = |x: f64| Rgb::splat(f(x));
    v.push((
        "ggx iso".into(),
        Box::new(
            Ggx::new(
                w(1.0),
                f(0.3),
                SmithForm::Correlated,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap(),
        ),
    ));
    v.push((
        "cook-torrance smith".into(),
        Box::new(
            CookTorrance::new(
                w(0.2),
                w(0.8),
                f(0.3),
                f(0.04),
                GeometricTerm::SmithSeparable,
            )
            .unwrap(),
        ),
    ));
    v
}

fn subnormal_cosines<T: Real>(zs: &[f64]) {
    for (name, m) in subnormal_models::<T>() {
        for &z in zs {
            let z = T::from_f64(z);
            let dirs = [
                Vec3::new(T::ONE, T::ZERO, z),
                Vec3::new(-T::ONE, T::ZERO, z),
                Vec3::new(T::from_f64(0.6), T::from_f64(0.8), z),
                Vec3::new(T::ZERO, T::ZERO, T::ONE),
            ];
            for wi in dirs {
                for wo in dirs {
                    let f = m.eval(wi, wo);
                    assert!(
                        f.is_finite() && f.min_channel() >= T::ZERO,
                        "{name}: eval {wi:?} {wo:?} = {f:?}"
                    );
                    let p = m.pdf(wo, wi);
                    assert!(
                        p.is_finite() && p >= T::ZERO,
                        "{name}: pdf {wo:?} {wi:?} = {p:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn subnormal_cosines_are_the_horizon() {
    subnormal_cosines::<f64>(&[5e-324, 1e-310, 1e-300, 1e-160, 1e-20]);
    subnormal_cosines::<f32>(&[1e-45, 1e-40, 1e-38, 1e-20, 1e-10]);
    // f32 Cook–Torrance at wi = wo = (1, 0, 1e-20) was NaN.
    let ct = CookTorrance::<f32>::new(
        Rgb::splat(0.0),
        Rgb::splat(1.0),
        0.3,
        0.04,
        GeometricTerm::Blinn,
    )
    .unwrap();
    let w = Vec3::new(1.0f32, 0.0, 1e-20);
    assert!(ct.eval(w, w).is_finite());
    // dfg_ggx at a subnormal μ agrees with μ = 1e-300 (it was NaN).
    let a = dfg_ggx::<f64, DefaultRule, DefaultRule>(5e-324, 0.5);
    let b = dfg_ggx::<f64, DefaultRule, DefaultRule>(1e-300, 0.5);
    assert_eq!(a, b);
    assert_eq!(a, (0.0, 0.0));
}

// ---------------------------------------------------------------- agreement of the samplers

#[test]
fn visible_normal_samplers_refuse_wo_below_the_horizon() {
    for wo in [
        Vec3::new(0.6, 0.0, -0.8),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 5e-324),
        Vec3::new(f64::NAN, 0.0, 0.5),
    ] {
        for u in [[0.5, 0.5], [0.0, 0.0], [1.0, 1.0]] {
            assert!(
                TrowbridgeReitz::clamped(0.3, 0.3)
                    .sample_visible_normal(wo, u)
                    .is_none(),
                "{wo:?}"
            );
            assert!(Beckmann::clamped(0.3, 0.3)
                .sample_visible_normal(wo, u)
                .is_none());
            assert!(TrowbridgeReitz::new(0.3, 0.1)
                .unwrap()
                .sample_visible_normal(wo, u)
                .is_none());
            assert!(Beckmann::new(0.3, 0.1)
                .unwrap()
                .sample_visible_normal(wo, u)
                .is_none());
        }
    }
}

#[test]
fn slope_cdf_is_a_probability() {
    for sigma in [0.05, 0.1, 0.3, 1.0, 3.0] {
        let d64 = SlopeDistribution::<f64>::new(sigma).unwrap();
        let d32 = SlopeDistribution::<f32>::new(sigma as f32).unwrap();
        for k in 0..=4000 {
            let g = -2.0 + 4.0 * k as f64 / 4000.0;
            let a = d64.cdf(g);
            let b = d32.cdf(g as f32);
            assert!((0.0..=1.0).contains(&a), "σ {sigma} γ {g}: {a}");
            assert!((0.0..=1.0).contains(&b), "σ {sigma} γ {g}: {b}");
        }
    }
}

// ---------------------------------------------------------------- anisotropic GGX

/// The anisotropic GGX D integrates to 1 in projected area (∫ D cos θh dω = 1) and reduces to
/// the isotropic closed form α²/(π((n·h)²(α² − 1) + 1)²) when αx = αy.
#[test]
fn anisotropic_ggx_is_normalised_and_reduces_to_isotropic() {
    for (ax, ay) in [(0.05, 0.5), (0.3, 0.3), (1.0, 0.2)] {
        let d = TrowbridgeReitz::<f64>::new(ax, ay).unwrap();
        // In the stretched slope variables the integral is ∫∫ 1/(π(1 + r²)²) r dr dφ = 1; here
        // it is done over the hemisphere in (u = tan²θh/(1 + tan²θh) … ) by a product rule
        // in (cos θh, φ) with cos θh = 1/√(1 + t), t = tan²θh = τ/(1 − τ), τ ∈ [0, 1).
        let n = 2000;
        let mut sum = 0.0;
        for i in 0..n {
            let tau = (i as f64 + 0.5) / n as f64;
            let t = tau / (1.0 - tau);
            let c = 1.0 / (1.0 + t).sqrt();
            let s = (1.0 - c * c).sqrt();
            // dω = sin θ dθ dφ; d(cos θ) = −sin θ dθ; c = (1 − τ)^{1/2} → dc = −dτ/(2c).
            let dc = 1.0 / (2.0 * c) / n as f64;
            for j in 0..400 {
                let phi = 2.0 * PI * (j as f64 + 0.5) / 400.0;
                let h = Vec3::new(s * phi.cos(), s * phi.sin(), c);
                sum += d.d(h) * c * dc * 2.0 * PI / 400.0;
            }
        }
        // Midpoint rule in τ on a smooth integrand: error well under 1e-4 for these widths.
        assert!((sum - 1.0).abs() < 2e-3, "αx {ax} αy {ay}: ∫D cos = {sum}");
    }
    let iso = TrowbridgeReitz::<f64>::new(0.3, 0.3).unwrap();
    for c in [1.0, 0.9, 0.5, 0.1] {
        let h = Vec3::new((1.0f64 - c * c).sqrt(), 0.0, c);
        let a2: f64 = 0.09;
        let closed = a2 / (PI * (c * c * (a2 - 1.0) + 1.0).powi(2));
        assert!(((iso.d(h) - closed) / closed).abs() < 1e-13);
    }
}

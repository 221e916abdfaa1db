//! The batch (structure-of-arrays) entry points of `brdf_core::batch` against the scalar
//! kernels, bit for bit. The scalar kernels are themselves tested against independent
//! references (core_modified_g.rs, core_kernels.rs), so equality here carries that accuracy
//! over to the batch forms. Inputs include the awkward cases: NaN, grazing, below the
//! horizon, normal incidence, wi = −wo.

use brdf_core::batch::{self, BatchError, BatchReal, DotsSoa, Vec3Soa};
use brdf_core::fresnel::Fresnel;
use brdf_core::masking::{self, Convention, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use brdf_core::models::{
    Brdf, GeometricTerm, Ggx, Lambert, MicrofacetSampling, Rgb, SmithForm, TorranceSparrow,
};
use brdf_core::quadrature::{GaussLegendre, Rule};
use brdf_core::{Dots, Real, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Bitwise equality, NaN payloads included.
fn same<T: Real>(a: T, b: T) -> bool {
    a.to_f64().to_bits() == b.to_f64().to_bits() || (a.is_nan() && b.is_nan())
}

fn assert_same<T: Real>(what: &str, batch: &[T], scalar: impl Fn(usize) -> T) {
    for (k, &b) in batch.iter().enumerate() {
        let s = scalar(k);
        assert!(same(b, s), "{what}[{k}]: batch {b:?} != scalar {s:?}");
    }
}

/// In-plane angle pairs: random ones plus edge cases.
fn angles<T: Real>(n: usize, seed: u64) -> (Vec<T>, Vec<T>) {
    let mut r = Pcg64::seed_from_u64(seed);
    let h = core::f64::consts::FRAC_PI_2;
    let mut ti: Vec<f64> = vec![0.0, h, 0.3, 1.2, 0.0, h, -0.1, 2.0, f64::NAN, 0.5];
    let mut tr: Vec<f64> = vec![0.0, h, -0.3, 1.2, -h, -h, 0.4, -2.0, 0.2, f64::NAN];
    while ti.len() < n {
        ti.push(r.random::<f64>() * h);
        tr.push((2.0 * r.random::<f64>() - 1.0) * h);
    }
    (
        ti.into_iter().map(T::from_f64).collect(),
        tr.into_iter().map(T::from_f64).collect(),
    )
}

/// Local unit directions: random upper-hemisphere ones plus edge cases.
fn dirs(n: usize, seed: u64) -> Vec<Vec3<f64>> {
    let mut r = Pcg64::seed_from_u64(seed);
    let mut v = vec![
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.6, 0.0, -0.8),
        Vec3::new(0.0, 0.6, 0.8),
        Vec3::new(f64::NAN, 0.0, 1.0),
    ];
    while v.len() < n {
        let z: f64 = r.random::<f64>();
        let phi = 2.0 * core::f64::consts::PI * r.random::<f64>();
        let s = (1.0 - z * z).sqrt();
        v.push(Vec3::new(s * phi.cos(), s * phi.sin(), z));
    }
    v
}

struct Pairs<T> {
    wi: [Vec<T>; 3],
    wo: [Vec<T>; 3],
    n_i: Vec<T>,
    n_o: Vec<T>,
    i_o: Vec<T>,
}

fn pairs<T: Real>(n: usize, seed: u64) -> Pairs<T> {
    let a = dirs(n, seed);
    let mut b = dirs(n, seed ^ 0xABCD);
    b.rotate_left(2); // different edge cases meet
    b[7] = Vec3::new(-a[7].x, -a[7].y, -a[7].z); // wi = −wo
    let c = |v: &[Vec3<f64>], f: fn(&Vec3<f64>) -> f64| -> Vec<T> {
        v.iter().map(|w| T::from_f64(f(w))).collect()
    };
    let wi = [c(&a, |w| w.x), c(&a, |w| w.y), c(&a, |w| w.z)];
    let wo = [c(&b, |w| w.x), c(&b, |w| w.y), c(&b, |w| w.z)];
    let mut n_i = Vec::new();
    let mut n_o = Vec::new();
    let mut i_o = Vec::new();
    for k in 0..n {
        let vi = Vec3::new(wi[0][k], wi[1][k], wi[2][k]);
        let vo = Vec3::new(wo[0][k], wo[1][k], wo[2][k]);
        let d = Dots::from_local(vi, vo);
        n_i.push(d.n_i);
        n_o.push(d.n_o);
        i_o.push(d.i_o);
    }
    Pairs {
        wi,
        wo,
        n_i,
        n_o,
        i_o,
    }
}

fn check_modified<T: Real, R: Rule>(conv: Convention) {
    let g = ModifiedG::<T, R>::new(T::from_f64(0.3))
        .unwrap()
        .with_convention(conv);
    let (ti, tr) = angles::<T>(300, 7);
    let mut out = vec![T::ZERO; ti.len()];
    batch::g_modified(&g, &ti, &tr, &mut out).unwrap();
    assert_same("g_modified", &out, |k| g.g(ti[k], tr[k]));
    let p = pairs::<T>(300, 11);
    let d = DotsSoa {
        n_i: &p.n_i,
        n_o: &p.n_o,
        i_o: &p.i_o,
    };
    batch::g_modified_dots(&g, d, &mut out).unwrap();
    assert_same("g_modified_dots", &out, |k| {
        g.g_dots(Dots::new(p.n_i[k], p.n_o[k], p.i_o[k]))
    });
}

#[test]
fn modified_g_batch_equals_scalar() {
    for conv in [Convention::Reciprocal, Convention::Printed] {
        check_modified::<f32, GaussLegendre<10>>(conv);
        check_modified::<f64, GaussLegendre<10>>(conv);
        check_modified::<f32, GaussLegendre<4>>(conv);
        check_modified::<f64, GaussLegendre<32>>(conv);
    }
}

/// A batch Smith term and the scalar kernel it must equal bit for bit.
type SmithPair<T> = (
    &'static str,
    fn(&[T], &[T], T, &mut [T]) -> Result<(), BatchError>,
    fn(T, T, T) -> T,
);

/// The correlated Smith terms (Beckmann G2, GGX G2, GGX V) with their scalar kernels.
fn smith_pairs<T: Real + BatchReal>() -> [SmithPair<T>; 3] {
    [
        (
            "smith_beckmann",
            batch::g_smith_beckmann_correlated,
            Beckmann::g_correlated_cos,
        ),
        (
            "smith_ggx",
            batch::g_smith_ggx_correlated,
            TrowbridgeReitz::g_correlated_cos,
        ),
        (
            "v_smith_ggx",
            batch::v_smith_ggx_correlated,
            TrowbridgeReitz::v_correlated_cos,
        ),
    ]
}

/// Runs each pair's batch form on (`ci`, `co`) at width `a` and checks it against the
/// scalar kernel element by element.
fn check_smith<T: Real>(
    pairs: &[SmithPair<T>],
    ci: &[T],
    co: &[T],
    a: T,
    out: &mut [T],
    what: &str,
) {
    for (name, batch_form, scalar) in pairs {
        batch_form(ci, co, a, out).unwrap();
        assert_same(&format!("{name}{what}"), out, |k| scalar(ci[k], co[k], a));
    }
}

fn check_closed_forms<T: Real + BatchReal>() {
    let p = pairs::<T>(500, 3);
    let n = p.n_i.len();
    let d = DotsSoa {
        n_i: &p.n_i,
        n_o: &p.n_o,
        i_o: &p.i_o,
    };
    let dk = |k: usize| Dots::new(p.n_i[k], p.n_o[k], p.i_o[k]);
    let mut out = vec![T::ZERO; n];

    batch::g_blinn_dots(d, &mut out).unwrap();
    assert_same("g_blinn_dots", &out, |k| masking::g_blinn_dots(dk(k)));

    for rough in [0.05, 0.3, 1.0] {
        check_smith(
            &smith_pairs(),
            &p.n_i,
            &p.n_o,
            T::from_f64(rough),
            &mut out,
            "",
        );
    }

    for gt in GeometricTerm::ALL {
        let ts = TorranceSparrow::<T>::new(
            T::from_f64(0.3),
            gt,
            Fresnel::schlick(T::from_f64(0.04)).unwrap(),
            T::ONE,
            T::from_f64(0.2),
        )
        .unwrap();
        batch::torrance_sparrow(&ts, d, &mut out).unwrap();
        assert_same(gt.name(), &out, |k| ts.eval_dots(dk(k)));
    }
}

#[test]
fn closed_forms_and_torrance_sparrow_batch_equal_scalar() {
    check_closed_forms::<f32>();
    check_closed_forms::<f64>();
}

fn check_brdf<T: Real, B: Brdf<T>>(b: &B) {
    let p = pairs::<T>(400, 5);
    let n = p.n_i.len();
    let (mut r, mut g, mut bl) = (vec![T::ZERO; n], vec![T::ZERO; n], vec![T::ZERO; n]);
    let wi = Vec3Soa {
        x: &p.wi[0],
        y: &p.wi[1],
        z: &p.wi[2],
    };
    let wo = Vec3Soa {
        x: &p.wo[0],
        y: &p.wo[1],
        z: &p.wo[2],
    };
    batch::brdf_eval(b, wi, wo, [&mut r, &mut g, &mut bl]).unwrap();
    for k in 0..n {
        let vi = Vec3::new(p.wi[0][k], p.wi[1][k], p.wi[2][k]);
        let vo = Vec3::new(p.wo[0][k], p.wo[1][k], p.wo[2][k]);
        let f = b.eval(vi, vo);
        assert!(
            same(r[k], f.r) && same(g[k], f.g) && same(bl[k], f.b),
            "brdf_eval[{k}]: ({:?}, {:?}, {:?}) != {f:?}",
            r[k],
            g[k],
            bl[k]
        );
    }
}

#[test]
fn brdf_eval_batch_equals_scalar() {
    fn both<T: Real>() {
        let f0 = Rgb::new(T::from_f64(0.04), T::from_f64(0.5), T::from_f64(0.9));
        for a in [0.05, 0.5] {
            let ggx = Ggx::new(
                f0,
                T::from_f64(a),
                SmithForm::Correlated,
                MicrofacetSampling::VisibleNormals,
            )
            .unwrap();
            check_brdf(&ggx);
        }
        check_brdf(&Lambert::new(f0).unwrap());
    }
    both::<f32>();
    both::<f64>();
}

#[test]
fn unequal_lengths_are_an_error_and_write_nothing() {
    let a = [0.1f64, 0.2, 0.3];
    let b = [0.1f64, 0.2];
    let mut out = [7.0f64; 3];
    let e = batch::v_smith_ggx_correlated(&a, &b, 0.5, &mut out);
    assert_eq!(
        e,
        Err(BatchError::LengthMismatch {
            expected: 3,
            found: 2
        })
    );
    assert_eq!(out, [7.0; 3]);
    let mut short = [7.0f64; 2];
    let d = DotsSoa {
        n_i: &a,
        n_o: &a,
        i_o: &a,
    };
    assert_eq!(
        batch::g_blinn_dots(d, &mut short),
        Err(BatchError::LengthMismatch {
            expected: 3,
            found: 2
        })
    );
    assert_eq!(short, [7.0; 2]);
    // Empty slices are a valid (empty) batch.
    let g = ModifiedG::<f64>::new(0.3).unwrap();
    assert_eq!(batch::g_modified(&g, &[], &[], &mut []), Ok(()));
}

/// Every special cosine against every other, for several α (NaN, 0, > 1 included): the
/// chunked, branch-free forms must reproduce the scalar kernels' early returns exactly.
#[test]
fn smith_ggx_batch_special_values_equal_scalar() {
    fn run<T: BatchReal>() {
        let specials = [
            f64::NAN,
            -1.0,
            -0.0,
            0.0,
            1e-30,
            1e-4,
            0.017,
            0.5,
            1.0,
            1.5,
            f64::INFINITY,
        ];
        let mut ci = Vec::new();
        let mut co = Vec::new();
        for &a in &specials {
            for &b in &specials {
                ci.push(T::from_f64(a));
                co.push(T::from_f64(b));
            }
        }
        let mut out = vec![T::ZERO; ci.len()];
        for alpha in [f64::NAN, 0.0, 1e-4, 0.3, 1.0, 2.5] {
            let a = T::from_f64(alpha);
            check_smith(&smith_pairs()[1..], &ci, &co, a, &mut out, " special");
        }
    }
    run::<f32>();
    run::<f64>();
}

//! The model catalogue: one consistent table, every entry buildable, its flat layout mapped
//! to the right constructor arguments (checked against constructions written out here).

use brdf_core::catalogue::{self, ParamKind, MAX_SLOTS, MODELS};
use brdf_core::fresnel::Fresnel;
use brdf_core::models::*;
use brdf_core::Vec3;
use std::collections::BTreeSet;

#[test]
fn names_are_one_set_with_the_old_spellings_as_aliases() {
    let mut seen = BTreeSet::new();
    for m in MODELS {
        for n in std::iter::once(&m.name).chain(m.aliases) {
            assert!(seen.insert(*n), "name {n} used twice");
        }
        let mut p = BTreeSet::new();
        for q in m.params {
            assert!(p.insert(q.name), "{}: parameter {} twice", m.name, q.name);
        }
    }
    assert_eq!(catalogue::find("shirley").unwrap().name, "shirley-damped");
    assert_eq!(catalogue::find("coupled").unwrap().name, "coupled-smooth");
    assert_eq!(catalogue::find("charlie").unwrap().name, "sheen");
    assert!(catalogue::find("torrance-sparrow").is_some());
    assert!(catalogue::find("nosuch").is_none());
}

#[test]
fn every_entry_builds_at_defaults_and_at_its_slider_ends() {
    for m in MODELS {
        let n = m.slots();
        assert!(n <= MAX_SLOTS, "{}", m.name);
        assert!(m.slot(n).is_none());
        let d = m.defaults::<f64>();
        m.build::<f64>(&d[..n])
            .unwrap_or_else(|e| panic!("{} defaults: {e}", m.name));
        m.build::<f32>(&m.defaults::<f32>()[..n])
            .unwrap_or_else(|e| panic!("{} f32 defaults: {e}", m.name));
        assert!(m.build::<f64>(&d[..n - 1]).is_err(), "{}: too few", m.name);
        for k in 0..n {
            let s = m.slot(k).unwrap();
            assert!(
                s.param.ui.0 <= s.default && s.default <= s.param.ui.1,
                "{} {}",
                m.name,
                s.name
            );
            for x in [s.param.ui.0, s.param.ui.1] {
                let mut q = d;
                q[k] = x;
                m.build::<f64>(&q[..n])
                    .unwrap_or_else(|e| panic!("{} {} = {x}: {e}", m.name, s.name));
            }
            let mut q = d;
            q[k] = f64::NAN;
            assert!(
                m.build::<f64>(&q[..n]).is_err(),
                "{} {} NaN",
                m.name,
                s.name
            );
            if let ParamKind::Choice(o) = s.param.kind {
                for bad in [0.5, -1.0, o.len() as f64] {
                    let mut q = d;
                    q[k] = bad;
                    assert!(
                        m.build::<f64>(&q[..n]).is_err(),
                        "{} {} = {bad}",
                        m.name,
                        s.name
                    );
                }
            }
        }
    }
}

/// A catalogue name, a flat parameter array and the model built directly.
type Case = (&'static str, Vec<f64>, Box<dyn Brdf<f64>>);

/// The flat layout reaches the constructors' arguments in the right order: each entry at
/// non-default settings against the model built directly.
#[test]
fn the_layout_maps_to_the_constructors() {
    let dirs = [
        (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.48, 0.36, 0.8)),
        (
            Vec3::new(0.0, 0.28, 0.96),
            Vec3::new(0.3, -0.1, (1.0f64 - 0.1).sqrt()),
        ),
        (Vec3::new(0.8, 0.0, 0.6), Vec3::new(-0.8, 0.0, 0.6)),
    ];
    let c = |r, g, b| Rgb::new(r, g, b);
    let cases: Vec<Case> = vec![
        (
            "torrance-sparrow",
            vec![0.2, 3.0, 0.1, 0.7, 0.25],
            Box::new(
                TorranceSparrow::<f64>::new(
                    0.2,
                    GeometricTerm::SmithCorrelated,
                    Fresnel::schlick(0.1).unwrap(),
                    0.7,
                    0.25,
                )
                .unwrap(),
            ),
        ),
        (
            "phong",
            vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 17.0],
            Box::new(PhongNormalized::new(c(0.1, 0.2, 0.3), c(0.4, 0.5, 0.6), 17.0).unwrap()),
        ),
        (
            "cook-torrance",
            vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.35, 0.2, 2.0, 1.0],
            Box::new(
                CookTorrance::new(
                    c(0.1, 0.2, 0.3),
                    c(0.4, 0.5, 0.6),
                    0.35,
                    0.2,
                    GeometricTerm::SmithSeparable,
                )
                .unwrap(),
            ),
        ),
        (
            "coupled",
            vec![0.3, 0.6, 0.9, 0.2, 1.0],
            Box::new(CoupledSmooth::new(c(0.3, 0.6, 0.9), 0.2, CoupledK::Printed).unwrap()),
        ),
        (
            "ashikhmin-shirley",
            vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 30.0, 300.0],
            Box::new(
                AshikhminShirley::new(c(0.1, 0.2, 0.3), c(0.4, 0.5, 0.6), 30.0, 300.0).unwrap(),
            ),
        ),
        (
            "bank",
            vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 12.0, 0.0, 0.7],
            Box::new(
                Bank::new(
                    c(0.1, 0.2, 0.3),
                    c(0.4, 0.5, 0.6),
                    12.0,
                    BankTangent::Azimuth(0.7),
                )
                .unwrap(),
            ),
        ),
        (
            "ward",
            vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.15, 0.45],
            Box::new(Ward::new(c(0.1, 0.2, 0.3), c(0.4, 0.5, 0.6), 0.15, 0.45).unwrap()),
        ),
        (
            "ggx-anisotropic",
            vec![0.5, 0.6, 0.7, 0.08, 0.6, 0.0, 1.0],
            Box::new(
                Ggx::anisotropic(
                    c(0.5, 0.6, 0.7),
                    0.08,
                    0.6,
                    SmithForm::Separable,
                    MicrofacetSampling::Normals,
                )
                .unwrap(),
            ),
        ),
        (
            "lambert-mirror",
            vec![0.2, 0.3, 0.4, 0.5],
            Box::new(LambertSpecularMix::new(c(0.2, 0.3, 0.4), 0.5).unwrap()),
        ),
        (
            "charlie",
            vec![0.7, 0.3, 0.1, 0.35, 1.0],
            Box::new(Sheen::new(c(0.7, 0.3, 0.1), 0.35, SheenVisibility::Ashikhmin).unwrap()),
        ),
    ];
    for (name, q, direct) in cases {
        let m = catalogue::find(name).unwrap();
        assert_eq!(q.len(), m.slots(), "{name}");
        let built = m.build::<f64>(&q).unwrap();
        for (wi, wo) in dirs {
            assert_eq!(built.eval(wi, wo), direct.eval(wi, wo), "{name} eval");
            assert_eq!(built.pdf(wo, wi), direct.pdf(wo, wi), "{name} pdf");
            assert_eq!(
                built.sample(wo, [0.3, 0.7]),
                direct.sample(wo, [0.3, 0.7]),
                "{name} sample"
            );
            assert_eq!(built.delta(wo), direct.delta(wo), "{name} delta");
        }
        assert_eq!(built.flags(), direct.flags(), "{name} flags");
    }
}

//! `lut verify`'s interpolation check (`worse_than_recorded`, `allowed_above`): its
//! false-alarm rate on a table that is as recorded, checked by simulation against the
//! exchangeability law it rests on, and its failure on a table whose header understates
//! the error.

use brdf_lut::generate::{
    allowed_above, generate, measure_table, worse_than_recorded, Distribution, Kind, Masking,
    Measured, Spec, Worse, FALSE_ALARM,
};
use brdf_lut::{ErrorStats, LutView};
use rand::{Rng, SeedableRng};

/// |Cauchy| errors: heavy-tailed, like a grid that does not resolve a kink.
fn heavy(rng: &mut rand_pcg::Pcg64) -> f64 {
    let u: f64 = rng.random_range(0.0..1.0);
    (core::f64::consts::PI * (u - 0.5)).tan().abs()
}

/// Recorded and fresh samples drawn alike (N recorded, M fresh, heavy-tailed): the share of
/// trials in which `worse_than_recorded` fails stays within the stated false-alarm rate
/// (+ 4 binomial σ), and the share with at least one fresh point above the recorded
/// maximum is M/(N + M) (the law's K = 1 term) within 4 σ.
#[test]
fn false_alarm_rate_of_a_table_as_recorded() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
    let trials = 20_000;
    for (n, m) in [(256u32, 256u32), (2000, 300), (64, 640)] {
        let (mut fails, mut any) = (0u32, 0u32);
        for _ in 0..trials {
            let rec = (0..n).map(|_| heavy(&mut rng)).fold(0.0f64, f64::max);
            let fresh: Vec<f64> = (0..m).map(|_| heavy(&mut rng)).collect();
            let measured = Measured {
                stats: ErrorStats {
                    max_abs: fresh.iter().cloned().fold(0.0, f64::max) as f32,
                    rms: 0.0,
                    samples: m,
                    seed: 0,
                },
                point_max: fresh.clone(),
            };
            // Tolerance 0 and the recorded max as stored (f32, rounded up so that the
            // stored maximum is not below the true one); the 1e-6 absolute term is
            // negligible against |Cauchy| values.
            let stored = next_up(rec as f32);
            let recorded = ErrorStats {
                max_abs: stored,
                rms: 0.0,
                samples: n,
                seed: 0,
            };
            let own = Measured {
                stats: recorded,
                point_max: vec![rec],
            };
            fails += worse_than_recorded(&own, &measured, &recorded, 0.0).is_some() as u32;
            any += fresh.iter().any(|&e| e > rec) as u32;
        }
        let t = trials as f64;
        let rate = fails as f64 / t;
        let bound = FALSE_ALARM + 4.0 * (FALSE_ALARM / t).sqrt();
        assert!(rate <= bound, "N {n} M {m}: false alarms {rate} > {bound}");
        let p1 = m as f64 / (n + m) as f64;
        let got = any as f64 / t;
        let sigma = (p1 * (1.0 - p1) / t).sqrt();
        assert!(
            (got - p1).abs() <= 4.0 * sigma,
            "N {n} M {m}: P(≥1) {got} vs {p1}"
        );
        // The count allowed is the law's smallest: one fewer would exceed the rate.
        let k = allowed_above(m, n);
        let p_k: f64 = (0..k)
            .map(|i| (m - i) as f64 / (n + m - i) as f64)
            .product();
        assert!(
            k == 0 || p_k > FALSE_ALARM,
            "N {n} M {m}: K − 1 = {k} not minimal"
        );
    }
}

/// The next f32 above a positive finite x.
fn next_up(x: f32) -> f32 {
    f32::from_bits(x.to_bits() + 1)
}

/// A real table: as recorded it passes, and its header's own points reproduce the recorded
/// maximum; with the maximum understated 3× the own-point check fails (a false claim
/// cannot pass), and a NaN error fails.
#[test]
fn a_table_whose_header_understates_fails() {
    let mut s = Spec::new(Kind::Albedo, Distribution::Ggx, Masking::SmithSeparable);
    for a in s.axes.iter_mut() {
        a.count = 12;
    }
    s.samples = 400;
    let t = generate(&s, &|_| {}).unwrap();
    let view = LutView::parse(&t.bytes).unwrap();
    let recorded = view.header().error;
    let own = measure_table(&view, recorded.samples, recorded.seed);
    assert_eq!(own.stats.max_abs, recorded.max_abs);
    let fresh = measure_table(&view, 400, 0x5EED_0002);
    assert_eq!(worse_than_recorded(&own, &fresh, &recorded, 0.1), None);
    let under = ErrorStats {
        max_abs: recorded.max_abs / 3.0,
        ..recorded
    };
    assert!(matches!(
        worse_than_recorded(&own, &fresh, &under, 0.1),
        Some(Worse::OwnPoints { .. })
    ));
    let nan = Measured {
        point_max: vec![f64::NAN],
        ..fresh
    };
    assert_eq!(
        worse_than_recorded(&own, &nan, &recorded, 0.1),
        Some(Worse::NotANumber)
    );
}

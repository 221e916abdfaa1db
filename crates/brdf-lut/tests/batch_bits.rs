//! The batch entry points of the typed tables against their scalar lookups, bit for bit,
//! over the committed assets (linear and Catmull–Rom; the chunked and the per-query paths),
//! over inputs that include NaN, ±∞, out-of-range and boundary values, and over lengths
//! that are not multiples of the chunk size.

use brdf_lut::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3};

fn asset(name: &str) -> Vec<u8> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name);
    std::fs::read(p).unwrap()
}

/// `n` values spread over [lo, hi] (an additive recurrence), with special values mixed in.
fn inputs(n: usize, lo: f32, hi: f32, seed: f64) -> Vec<f32> {
    let special = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        -0.0,
        0.0,
        lo,
        hi,
        lo - 1.0,
        hi + 1.0,
        f32::MAX,
        -f32::MAX,
        f32::MIN_POSITIVE,
        1e-30,
    ];
    (0..n)
        .map(|k| {
            if k % 7 == 3 {
                special[(k / 7) % special.len()]
            } else {
                let u = (seed + 0.618_033_988_749_895 * k as f64).fract() as f32;
                lo + (hi - lo) * u
            }
        })
        .collect()
}

const LENGTHS: [usize; 13] = [0, 1, 3, 5, 7, 8, 9, 15, 17, 24, 33, 64, 1001];

fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits()
}

/// Runs `batch` on an output of `n + pad` slots preset to −1, checks that it reports `n`
/// results, that result k equals `scalar(k)` bit for bit, and that nothing past n is
/// written.
fn check_batch(
    what: &str,
    n: usize,
    pad: usize,
    batch: impl FnOnce(&mut [f32]) -> usize,
    scalar: impl Fn(usize) -> f32,
) {
    let mut out = vec![-1.0; n + pad];
    assert_eq!(batch(&mut out), n, "{what}");
    for (k, &got) in out[..n].iter().enumerate() {
        let v = scalar(k);
        assert!(same(got, v), "{what} {k}: {got} vs {v}");
    }
    assert!(out[n..].iter().all(|&x| x == -1.0), "{what}: wrote past n");
}

#[test]
fn g_batches_equal_scalar_lookups() {
    let h = std::f32::consts::FRAC_PI_2;
    for name in [
        "g_modified_sigma0.3_linear.blut",
        "g_modified_sigma0.3.blut",
    ] {
        let b = asset(name);
        let t = GTable::parse(&b[..]).unwrap();
        for n in LENGTHS {
            let (ti, tr) = (
                inputs(n, -0.2, h + 0.2, 0.1),
                inputs(n, -h - 0.2, h + 0.2, 0.7),
            );
            check_batch(
                name,
                n,
                3,
                |o| t.g_batch(&ti, &tr, o),
                |k| t.g(ti[k], tr[k]),
            );
        }
    }
    for name in ["g_modified_linear.blut", "g_modified.blut"] {
        let b = asset(name);
        let t = GTable3::parse(&b[..]).unwrap();
        for sigma in [0.3, 0.05, 1.0, 0.0, 7.0, f32::NAN, f32::INFINITY] {
            for n in LENGTHS {
                let (ti, tr) = (
                    inputs(n, -0.2, h + 0.2, 0.3),
                    inputs(n, -h - 0.2, h + 0.2, 0.9),
                );
                check_batch(
                    &format!("{name} σ {sigma}"),
                    n,
                    0,
                    |o| t.g_batch(&ti, &tr, sigma, o),
                    |k| t.g(ti[k], tr[k], sigma),
                );
            }
        }
    }
}

#[test]
fn dfg_and_albedo_batches_equal_scalar_lookups() {
    for name in [
        "dfg_ggx_linear.blut",
        "dfg_ggx.blut",
        "dfg_ts_smith.blut",
        "dfg_ts_modified.blut",
    ] {
        let b = asset(name);
        let t = DfgTable::parse(&b[..]).unwrap();
        for n in LENGTHS {
            let (mu, r) = (inputs(n, -0.1, 1.1, 0.2), inputs(n, -0.1, 1.1, 0.5));
            let (mut a, mut bb) = (vec![0.0; n], vec![0.0; n + 2]);
            assert_eq!(t.ab_batch(&mu, &r, &mut a, &mut bb), n);
            for k in 0..n {
                let (x, y) = t.ab(mu[k], r[k]);
                assert!(same(a[k], x) && same(bb[k], y), "{name} {k}");
            }
        }
    }
    // Catmull–Rom (the chunked cubic path) over a log-warped μ axis and linear roughness.
    for (e_name, eavg_name) in [
        ("kc_e_ggx.blut", "kc_eavg_ggx.blut"),
        ("kc_e_beckmann.blut", "kc_eavg_beckmann.blut"),
    ] {
        let b = asset(e_name);
        let e = AlbedoTable::parse(&b[..]).unwrap();
        let b = asset(eavg_name);
        let ea = AverageAlbedoTable::parse(&b[..]).unwrap();
        for n in LENGTHS {
            let (mu, r) = (inputs(n, -0.1, 1.1, 0.4), inputs(n, -0.1, 1.1, 0.6));
            check_batch(
                e_name,
                n,
                3,
                |o| e.e_batch(&mu, &r, o),
                |k| e.e(mu[k], r[k]),
            );
            check_batch(
                eavg_name,
                n,
                0,
                |o| ea.e_avg_batch(&r, o),
                |k| ea.e_avg(r[k]),
            );
        }
    }
    // A NaN coordinate gives NaN on every path (the typed tables' contract).
    let b = asset("kc_e_ggx.blut");
    let e = AlbedoTable::parse(&b[..]).unwrap();
    let mu = [f32::NAN, 0.5, f32::NAN, 0.2, 0.7, 0.9, 0.1, 0.3, 0.4];
    let r = [0.5, f32::NAN, f32::NAN, 0.2, 0.7, 0.9, 0.1, 0.3, 0.4];
    let mut out = [0.0; 9];
    e.e_batch(&mu, &r, &mut out);
    assert!(out[..3].iter().all(|v| v.is_nan()), "{out:?}");
    assert!(out[3..].iter().all(|v| (0.0..=1.0).contains(v)), "{out:?}");
}

/// "NaN gives NaN" (the typed tables' contract) on a table whose axes are √-warped: the
/// warp must not turn a NaN coordinate into the axis' lower end.
#[test]
fn nan_coordinates_give_nan_on_sqrt_warped_axes() {
    let b = asset("dfg_ggx_linear.blut");
    let t = DfgTable::parse(&b[..]).unwrap();
    for (m, r) in [(f32::NAN, 0.5), (0.5, f32::NAN), (f32::NAN, f32::NAN)] {
        let (a, bb) = t.ab(m, r);
        assert!(a.is_nan() && bb.is_nan(), "({m}, {r}) -> ({a}, {bb})");
    }
    // And a real query stays finite: A + B ≤ 1 is the directional albedo with F = 1.
    let (a, bb) = t.ab(0.5, 0.5);
    assert!(a > 0.0 && bb > 0.0 && a + bb <= 1.0, "{a} {bb}");
}

/// Albedo tables read their log μ axis with the reader's inline logarithm (scalar and batch
/// lookups alike); `LutView::sample`, which the table's recorded error was measured with,
/// keeps libm's `logf`. The node index then moves by at most a·ε + 2 ulp(t): ε = 1.2e-6 the
/// logarithm's error bound at |ln x| ≤ ln(1/sin 1°) = 4.05 (1.5e-7 + 2.5e-7·4.05, tested
/// against the f64 logarithm in the reader's unit tests), a = (n − 1)/ln(hi/lo) nodes per
/// unit of ln μ, and t < 64 rounded in f32 (ulp 3.8e-6). The Catmull–Rom interpolant's
/// slope per cell, in Hermite form p' = (6f² − 6f)(v_i − v_{i+1}) + (3f² − 4f + 1) m_i +
/// (3f² − 2f) m_{i+1} with tangents m = (v_{i+1} − v_{i−1})/2, is at most 1.5 + 2 + 2 = 5.5
/// times the largest step between neighbouring nodes (|m| ≤ 1 step inside, ≤ 2 steps
/// with the end extrapolation 3v₀ − 3v₁ + v₂), and the f32 sums add < 1e-6: so typed and
/// view lookups differ by at most (a·ε + 8e-6)·6·step + 1e-6, far below the tables'
/// recorded error.
#[test]
fn albedo_lookups_stay_within_the_log_bound_of_the_measured_reader() {
    use brdf_lut::LutView;
    for name in ["kc_e_ggx.blut", "kc_e_beckmann.blut"] {
        let b = asset(name);
        let t = AlbedoTable::parse(&b[..]).unwrap();
        let v = LutView::parse(&b[..]).unwrap();
        let axes = &v.header().axes;
        let (mu, r) = (&axes[0], &axes[1]);
        assert_eq!(mu.warp, brdf_lut::Warp::Log);
        let a = (mu.count - 1) as f64 / (mu.hi / mu.lo).ln();
        let eps = 1.5e-7 + 2.5e-7 * (mu.hi / mu.lo).ln();
        // Largest step between neighbouring μ nodes over a grid of roughness values.
        let mut step = 0f64;
        for j in 0..=40 {
            let rr = (r.lo + (r.hi - r.lo) * j as f64 / 40.0) as f32;
            for i in 0..mu.count - 1 {
                let x0 = (mu.lo * (mu.hi / mu.lo).powf(i as f64 / (mu.count - 1) as f64)) as f32;
                let x1 =
                    (mu.lo * (mu.hi / mu.lo).powf((i + 1) as f64 / (mu.count - 1) as f64)) as f32;
                let d = v.sample(&[x1, rr])[0] - v.sample(&[x0, rr])[0];
                step = step.max(d.abs() as f64);
            }
        }
        let bound = (a * eps + 8e-6) * 6.0 * step + 1e-6;
        let mut worst = 0f64;
        for k in 0..20_000 {
            let m = (mu.lo + (mu.hi - mu.lo) * ((0.3 + 0.618_033_988_7 * k as f64) % 1.0)) as f32;
            let rr = (r.lo + (r.hi - r.lo) * ((0.1 + 0.414_213_562_3 * k as f64) % 1.0)) as f32;
            let d = (t.e(m, rr) as f64 - v.sample(&[m, rr])[0] as f64).abs();
            worst = worst.max(d);
        }
        println!("{name}: typed − view ≤ {worst:.1e} (bound {bound:.1e})");
        assert!(worst <= bound, "{name}: {worst:e} > {bound:e}");
        assert!(
            bound < 0.1 * v.header().error.max_abs as f64,
            "{name}: bound {bound:e}"
        );
    }
}

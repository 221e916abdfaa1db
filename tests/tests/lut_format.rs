//! The LUT readers: both give the same values, the assets meet their accuracy targets
//! against the direct kernels at fresh random points, and bad input gives typed errors.

use brdf_core::masking::ModifiedG;
use brdf_core::quadrature::GaussLegendre;
use brdf_core::split_sum::{
    dfg_ggx, dfg_ts_modified, dfg_ts_smith, e_avg_beckmann, e_avg_ggx, e_beckmann, e_ggx,
};
use brdf_lut::Lut;
use brdf_lut::{AlbedoTable, AverageAlbedoTable};
use brdf_lut::{DfgTable, GTable, GTable3, LutError, LutView};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::PathBuf;

fn asset(name: &str) -> Vec<u8> {
    std::fs::read(
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../assets")
            .join(name),
    )
    .unwrap()
}

/// A tiny deterministic generator (xorshift) for test points.
struct Xs(u64);
impl Xs {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn loader_and_view_agree() {
    let b = asset("g_modified_sigma0.3.blut");
    let lut = Lut::from_bytes(b.clone()).unwrap();
    let t = GTable::parse(&b).unwrap();
    let mut x = Xs(7);
    for _ in 0..1000 {
        let (ti, tr) = ((x.next() * 1.6) as f32, (x.next() * 3.2 - 1.6) as f32);
        assert_eq!(lut.g(ti, tr, 0.3).unwrap().to_bits(), t.g(ti, tr).to_bits());
    }
    let b = asset("dfg_ggx.blut");
    let lut = Lut::from_bytes(b.clone()).unwrap();
    let t = DfgTable::parse(&b).unwrap();
    for _ in 0..1000 {
        let (mu, r) = (x.next() as f32, x.next() as f32);
        assert_eq!(lut.dfg(mu, r).unwrap(), t.ab(mu, r));
    }
    assert!(matches!(
        lut.g(0.1, 0.1, 0.3),
        Err(brdf_lut::Error::WrongKind { .. })
    ));
}

#[test]
fn g_tables_meet_1e3_at_fresh_points() {
    let b3 = asset("g_modified.blut");
    assert!(b3.len() <= 256 * 1024);
    let mut x = Xs(99);
    let worst = g3_errors(&b3, &mut x, 3000)
        .into_iter()
        .fold(0f64, f64::max);
    println!("3-D G table: max |err| {worst:.3e}");
    assert!(worst <= 1e-3);
    for s in [0.1, 0.3, 0.5] {
        let b = asset(&format!("g_modified_sigma{s}.blut"));
        assert!(b.len() <= 32 * 1024);
        let worst = g_table_worst(&b, s, &mut x, 2000);
        println!("sigma {s}: max |err| {worst:.3e}");
        assert!(worst <= 1e-3);
    }
}

/// |G table − direct modified G (32 × 32 Gauss–Legendre)| of the 3-D (θi, θr, σ) table
/// `b3` at `n` fresh points from `x` (σ ∈ [0.05, 1]).
fn g3_errors(b3: &[u8], x: &mut Xs, n: usize) -> Vec<f64> {
    let t3 = GTable3::parse(b3).unwrap();
    (0..n)
        .map(|_| {
            let (ti, tr) = (x.next() * FRAC_PI_2, x.next() * PI - FRAC_PI_2);
            let s = 0.05 + 0.95 * x.next();
            let direct = ModifiedG::<f64, GaussLegendre<32>>::new(s)
                .unwrap()
                .g(ti, tr);
            (t3.g(ti as f32, tr as f32, s as f32) as f64 - direct).abs()
        })
        .collect()
}

/// The largest |G table − direct modified G (32 × 32 Gauss–Legendre)| of the per-σ table
/// `b` at `n` fresh (θi, θr) from `x`.
fn g_table_worst(b: &[u8], sigma: f64, x: &mut Xs, n: usize) -> f64 {
    let t = GTable::parse(b).unwrap();
    let g = ModifiedG::<f64, GaussLegendre<32>>::new(sigma).unwrap();
    let mut worst = 0f64;
    for _ in 0..n {
        let (ti, tr) = (x.next() * FRAC_PI_2, x.next() * PI - FRAC_PI_2);
        worst = worst.max((t.g(ti as f32, tr as f32) as f64 - g.g(ti, tr)).abs());
    }
    worst
}

#[test]
fn speed_tier_g_tables_meet_their_accuracy_at_fresh_points() {
    let b3 = asset("g_modified_linear.blut");
    assert!(b3.len() <= 256 * 1024);
    let mut x = Xs(4242);
    let errs = g3_errors(&b3, &mut x, 3000);
    let worst = errs.iter().copied().fold(0f64, f64::max);
    let rms = (errs.iter().map(|e| e * e).sum::<f64>() / errs.len() as f64).sqrt();
    println!("3-D trilinear G table: max |err| {worst:.3e}, RMS {rms:.3e}");
    // The claim is the header's: its max over 2,000,000 generator points (about 1.7e-3, the
    // bilinear error across the kinks θr = ±θi); fresh points stay within it.
    let claim = LutView::parse(&b3).unwrap().header().error.max_abs as f64;
    assert!(
        claim <= 2e-3 && worst <= claim && rms <= 3e-4,
        "{worst} vs {claim}"
    );
    let b = asset("g_modified_sigma0.3_linear.blut");
    assert!(b.len() <= 32 * 1024);
    let worst = g_table_worst(&b, 0.3, &mut x, 3000);
    println!("2-D bilinear G table (sigma 0.3): max |err| {worst:.3e}");
    assert!(worst <= 1e-4);
}

/// GM = F(|θr|, sgn θr · θi), GS = F(θi, θr) through the general reader (docs/conventions.md §4),
/// written out here independently of `GTable`.
fn g_by_general_reader(v: &LutView<'_>, ti: f32, tr: f32, sigma: f32) -> (f32, f32) {
    let ti = ti.clamp(0.0, FRAC_PI_2 as f32);
    let tr = tr.clamp(-FRAC_PI_2 as f32, FRAC_PI_2 as f32);
    let s = if tr < 0.0 { -ti } else { ti };
    let gm = v.sample(&[tr.abs(), s, sigma])[0].clamp(0.0, 1.0);
    let gs = v.sample(&[ti, tr, sigma])[0].clamp(0.0, 1.0);
    (gm, gs)
}

#[test]
fn fixed_layout_lookup_equals_the_general_reader() {
    // GTable/GTable3 read u16 passing-factor tables through their own fixed-layout path;
    // LutView::sample is the general per-tap reader (checked against closed forms in the
    // core's unit tests). Both must agree up to f32 rounding on every shipped G table.
    let mut x = Xs(31337);
    let mut pts: Vec<(f32, f32, f32)> = (0..4000)
        .map(|_| {
            (
                (x.next() * 1.7 - 0.05) as f32,
                (x.next() * 3.4 - 1.7) as f32,
                (x.next() * 1.1) as f32,
            )
        })
        .collect();
    // Nodes, range ends and the kink lines θr = ±θi.
    for &(a, b) in &[
        (0.0, 0.0),
        (1.5707964, 1.5707964),
        (0.7, 0.7),
        (0.7, -0.7),
        (1.2, -1.5707964),
    ] {
        for s in [0.05f32, 0.3, 1.0] {
            pts.push((a, b, s));
        }
    }
    let mut checked = 0;
    for e in std::fs::read_dir(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets")).unwrap()
    {
        let name = e.unwrap().file_name().into_string().unwrap();
        if !name.starts_with("g_modified") {
            continue;
        }
        let b = asset(&name);
        let v = LutView::parse(&b).unwrap();
        let mut worst = 0f32;
        for &(ti, tr, s) in &pts {
            let (gm, gs, _) = if v.dims() == 3 {
                GTable3::from_view(v).unwrap().terms(ti, tr, s)
            } else {
                GTable::from_view(v).unwrap().terms(ti, tr)
            };
            let (rm, rs) = g_by_general_reader(&v, ti, tr, s);
            worst = worst.max((gm - rm).abs()).max((gs - rs).abs());
        }
        println!("{name}: max |fixed − general| {worst:.2e}");
        assert!(worst <= 3e-6, "{name}: {worst}");
        checked += 1;
    }
    assert!(checked >= 6, "only {checked} G tables found");
}

#[test]
fn dfg_table_meets_1e3_including_grazing() {
    let b = asset("dfg_ggx.blut");
    let t = DfgTable::parse(&b).unwrap();
    let mut x = Xs(5);
    let mut worst = 0f64;
    for k in 0..400 {
        // Every fourth point at grazing (μ ∈ [cos 89°, 0.05]).
        let mu = if k % 4 == 0 {
            0.017452406 + 0.033 * x.next()
        } else {
            0.017452406 + 0.98 * x.next()
        };
        let r = x.next();
        let (mu32, r32) = (mu as f32, r as f32);
        // A finer rule than the generator's as the converged reference.
        let (a, bb) = dfg_ggx::<f64, GaussLegendre<32>, GaussLegendre<32>>(mu32 as f64, r32 as f64);
        let (ta, tb) = t.ab(mu32, r32);
        worst = worst.max((ta as f64 - a).abs()).max((tb as f64 - bb).abs());
    }
    println!("DFG GGX: max |err| {worst:.3e}");
    assert!(worst <= 1e-3);
}

#[test]
fn torrance_sparrow_and_kulla_conty_tables_match_their_kernels() {
    type O = GaussLegendre<32>;
    type I = GaussLegendre<24>;
    let mut x = Xs(11);
    let ts_s = asset("dfg_ts_smith.blut");
    let ts_m = asset("dfg_ts_modified.blut");
    let (ts_s, ts_m) = (
        DfgTable::parse(&ts_s).unwrap(),
        DfgTable::parse(&ts_m).unwrap(),
    );
    let (mut ws, mut wm) = (0f64, 0f64);
    for k in 0..60 {
        let mu = (0.017_452_406 + 0.98 * x.next()) as f32;
        let s = (0.05 + 0.95 * x.next()) as f32;
        let (a, b) = dfg_ts_smith::<f64, O, I>(mu as f64, s as f64);
        let (ta, tb) = ts_s.ab(mu, s);
        ws = ws.max((ta as f64 - a).abs()).max((tb as f64 - b).abs());
        if k % 3 == 0 {
            let (a, b) = dfg_ts_modified::<f64, O, I>(mu as f64, s as f64);
            let (ta, tb) = ts_m.ab(mu, s);
            wm = wm.max((ta as f64 - a).abs()).max((tb as f64 - b).abs());
        }
    }
    println!("TS Smith max |err| {ws:.2e}, TS modified {wm:.2e}");
    assert!(ws <= 1e-3 && wm <= 2e-3);
    let (eg, eb) = (asset("kc_e_ggx.blut"), asset("kc_e_beckmann.blut"));
    let (eg, eb) = (
        AlbedoTable::parse(&eg).unwrap(),
        AlbedoTable::parse(&eb).unwrap(),
    );
    let (ag, ab) = (asset("kc_eavg_ggx.blut"), asset("kc_eavg_beckmann.blut"));
    let (ag, ab) = (
        AverageAlbedoTable::parse(&ag).unwrap(),
        AverageAlbedoTable::parse(&ab).unwrap(),
    );
    let mut we = 0f64;
    for _ in 0..60 {
        let mu = (0.017_452_406 + 0.98 * x.next()) as f32;
        let r = x.next() as f32;
        we = we
            .max((eg.e(mu, r) as f64 - e_ggx::<f64, O, I>(mu as f64, r as f64)).abs())
            .max((eb.e(mu, r) as f64 - e_beckmann::<f64, O, I>(mu as f64, r as f64)).abs());
    }
    let mut wa = 0f64;
    for _ in 0..8 {
        let r = x.next() as f32;
        wa = wa
            .max((ag.e_avg(r) as f64 - e_avg_ggx::<f64, O, I>(r as f64)).abs())
            .max((ab.e_avg(r) as f64 - e_avg_beckmann::<f64, O, I>(r as f64)).abs());
    }
    println!("E max |err| {we:.2e}, E_avg {wa:.2e}");
    assert!(we <= 1e-3 && wa <= 1e-4);
}

#[test]
fn bad_input_gives_typed_errors() {
    let good = asset("g_modified_sigma0.1.blut");
    assert_eq!(LutView::parse(&[]).unwrap_err(), LutError::Truncated);
    assert_eq!(LutView::parse(b"BL").unwrap_err(), LutError::Truncated);
    assert_eq!(
        LutView::parse(b"PNG\x0d1234").unwrap_err(),
        LutError::BadMagic
    );
    let mut v = good.clone();
    v[4] = 3; // version 3 (1 and 2 are read)
    assert_eq!(
        LutView::parse(&v).unwrap_err(),
        LutError::UnsupportedVersion { found: 3 }
    );
    for cut in [5, 20, 60, good.len() - 1] {
        assert!(LutView::parse(&good[..cut]).is_err(), "cut {cut}");
    }
    let mut v = good.clone();
    v.push(0); // oversized payload
    assert!(matches!(
        LutView::parse(&v),
        Err(LutError::PayloadLength { .. })
    ));
    let mut v = good.clone();
    let n = v.len();
    v[n - 1] ^= 1; // payload corruption
    assert!(matches!(LutView::parse(&v), Err(LutError::Checksum { .. })));
    let d = asset("dfg_ggx.blut");
    assert!(matches!(GTable::parse(&d), Err(LutError::WrongKind { .. })));
    assert!(matches!(
        Lut::from_reader(std::io::repeat(0).take(brdf_lut::MAX_FILE_BYTES + 10)),
        Err(brdf_lut::Error::TooLarge { .. }) | Err(brdf_lut::Error::Format(_))
    ));
}

use std::io::Read;

#[test]
fn every_single_bit_flip_of_a_header_is_rejected() {
    let good = asset("g_modified_sigma0.5.blut");
    let hl = LutView::parse(&good).unwrap().header_len();
    for byte in 0..hl + 64 {
        for bit in 0..8 {
            let mut v = good.clone();
            v[byte] ^= 1 << bit;
            assert!(LutView::parse(&v).is_err(), "flip {byte}:{bit} accepted");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        let _ = LutView::parse(&bytes);
        let mut v = b"BLUT\x01".to_vec();
        v.extend_from_slice(&bytes);
        let _ = LutView::parse(&v);
    }
    #[test]
    fn g_table_lookups_are_nan_or_in_unit_range(ti in any::<f32>(), tr in any::<f32>(), s in any::<f32>(), which in 0usize..4) {
        let names = ["g_modified.blut", "g_modified_linear.blut", "g_modified_sigma0.3.blut", "g_modified_sigma0.3_linear.blut"];
        let b = asset(names[which]);
        let g = if which < 2 {
            GTable3::parse(&b).unwrap().g(ti, tr, s)
        } else {
            GTable::parse(&b).unwrap().g(ti, tr)
        };
        let nan_in = ti.is_nan() || tr.is_nan() || (which < 2 && s.is_nan());
        prop_assert_eq!(g.is_nan(), nan_in, "{} {} {} -> {}", ti, tr, s, g);
        prop_assert!(g.is_nan() || (0.0..=1.0).contains(&g));
    }
    #[test]
    fn bit_flips_of_real_assets_are_errors(idx in 0usize..1_000_000, bit in 0u8..8, which in 0usize..4) {
        let names = ["g_modified_sigma0.1.blut", "dfg_ggx.blut", "kc_eavg_ggx.blut", "dfg_ts_smith.blut"];
        let mut v = asset(names[which]);
        let i = idx % v.len();
        v[i] ^= 1 << bit;
        prop_assert!(LutView::parse(&v).is_err());
    }
}

/// Counts the bytes allocated on the current thread.
struct Counting;
thread_local! {
    static ALLOCATED: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}
unsafe impl std::alloc::GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: std::alloc::Layout) -> *mut u8 {
        let _ = ALLOCATED.try_with(|c| c.set(c.get() + l.size()));
        unsafe { std::alloc::System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: std::alloc::Layout) {
        unsafe { std::alloc::System.dealloc(p, l) }
    }
}
#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn the_view_never_allocates() {
    let names = ["g_modified.blut", "dfg_ggx.blut", "kc_eavg_beckmann.blut"];
    let files: Vec<Vec<u8>> = names.iter().map(|n| asset(n)).collect();
    let mut bad = files[1].clone();
    bad[10] ^= 0x40;
    let before = ALLOCATED.with(|c| c.get());
    let mut acc = 0f32;
    for f in files.iter().chain(std::iter::once(&bad)) {
        if let Ok(v) = LutView::parse(f) {
            acc += v.sample(&[0.3, 0.2, 0.5])[0];
        }
        let _ = LutView::parse(&f[..f.len() / 3]);
    }
    let after = ALLOCATED.with(|c| c.get());
    assert_eq!(
        after - before,
        0,
        "parse/sample allocated {} bytes",
        after - before
    );
    assert!(acc.is_finite());
}

/// Re-signs a file after an edit (recomputes the CRC-32), so that the edit reaches the checks
/// behind the checksum.
fn resign(v: &mut [u8]) {
    let hl = brdf_lut::header_len(v).unwrap();
    let crc = brdf_lut::Crc32::new()
        .update(&v[..hl - 4])
        .update(&v[hl..])
        .finish();
    v[hl - 4..hl].copy_from_slice(&crc.to_le_bytes());
}

/// Headers valid in f64 but degenerate in the f32 the reader computes in are rejected at
/// parse with a typed error (each case made every lookup NaN before).
#[test]
fn f32_degenerate_axes_are_rejected() {
    use brdf_lut::Warp;
    // A one-axis table: axis "roughness"; lo, hi follow its node count (one varint byte).
    let good = asset("kc_eavg_ggx.blut");
    let v = LutView::parse(&good).unwrap();
    assert!(v.header().axes[0].count < 128);
    let p = good.windows(9).position(|w| w == b"roughness").unwrap();
    let lo_at = p + 9 + 1;
    let pi2 = std::f64::consts::FRAC_PI_2;
    let cases: [(f64, f64, Warp); 8] = [
        (0.5, 0.5 + 1e-12, Warp::Linear),
        (-1e300, 1e300, Warp::Linear),
        (-1e39, 1e39, Warp::Linear),
        (1e-50, 1.0, Warp::Log),
        (1e-300, 1.0, Warp::Log),
        (0.0, 1e-20, Warp::Cos),
        (pi2 - 1e-12, pi2, Warp::SqrtCos),
        (-3e38, 3e38, Warp::Linear), // finite ends, span overflows f32
    ];
    for (lo, hi, warp) in cases {
        let mut b = good.clone();
        b[lo_at..lo_at + 8].copy_from_slice(&lo.to_le_bytes());
        b[lo_at + 8..lo_at + 16].copy_from_slice(&hi.to_le_bytes());
        b[lo_at + 16] = warp as u8;
        resign(&mut b);
        let e = LutView::parse(&b).unwrap_err();
        assert!(
            matches!(e, LutError::DegenerateAxis { axis: 0, .. }),
            "[{lo}, {hi}] {warp:?}: {e:?}"
        );
    }
    // The unmodified range still parses after re-signing (the edit is what is rejected).
    let mut b = good.clone();
    resign(&mut b);
    assert!(LutView::parse(&b).is_ok());
}

/// A varint not in its shortest form (`82 00` for version 2) is rejected.
#[test]
fn non_canonical_varints_are_rejected() {
    let good = asset("kc_eavg_ggx.blut");
    assert_eq!(good[4], 2);
    let mut b = good[..4].to_vec();
    b.extend_from_slice(&[0x82, 0x00]);
    b.extend_from_slice(&good[5..]);
    assert_eq!(LutView::parse(&b).unwrap_err(), LutError::NonCanonical);
}

/// One axis `name` of `count` nodes on [0, 1] (linear, endpoints).
fn unit_axis(name: &str, count: u32) -> [brdf_lut::Axis<'_>; 1] {
    [brdf_lut::Axis {
        name,
        count,
        lo: 0.0,
        hi: 1.0,
        ..Default::default()
    }]
}

/// An f32, linearly interpolated average-albedo table over `axes`.
fn eavg_spec<'a>(
    axes: &'a [brdf_lut::Axis<'a>],
    channels: &'a [&'a str],
    generator: brdf_lut::Generator<'a>,
) -> brdf_lut::write::Spec<'a> {
    use brdf_lut::{Encoding, Interpolation, TableKind};
    brdf_lut::write::Spec {
        kind: TableKind::AverageAlbedo,
        axes,
        channels,
        encoding: Encoding::F32,
        interpolation: Interpolation::Linear,
        generator,
    }
}

/// NaN or infinite node values in a float payload are rejected at parse (one rule for every
/// path: a table that parses has finite nodes, so lookups give finite values for finite
/// input and G stays in [0, 1]).
#[test]
fn non_finite_payload_values_are_rejected() {
    use brdf_lut::write;
    use brdf_lut::*;
    let axes = unit_axis("roughness", 4);
    let spec = eavg_spec(&axes, &["Eavg"], Generator::default());
    // The writer refuses them …
    assert!(matches!(
        write::quantise(&spec, &[1.0, f64::NAN, 0.5, 0.2]),
        Err(LutError::BadInput(_))
    ));
    // … and a crafted file carrying them is refused by the reader.
    let good = write::build(&spec, &[1.0, 0.9, 0.5, 0.2], |_| ErrorStats::default()).unwrap();
    for bad in [f32::NAN, f32::INFINITY, -1e31] {
        let mut b = good.clone();
        let n = b.len();
        b[n - 8..n - 4].copy_from_slice(&bad.to_le_bytes());
        resign(&mut b);
        assert_eq!(
            LutView::parse(&b).unwrap_err(),
            LutError::BadValue { index: 2 }
        );
    }
}

/// Header strings reach the terminal escaped.
#[test]
fn summary_escapes_control_characters() {
    use brdf_lut::write;
    use brdf_lut::*;
    let axes = unit_axis("r\u{1b}[2J", 2);
    let generator = Generator {
        tool: "t\r\n",
        ..Generator::default()
    };
    let spec = eavg_spec(&axes, &["E\u{7}"], generator);
    let b = write::build(&spec, &[1.0, 0.5], |_| ErrorStats::default()).unwrap();
    let s = Lut::from_bytes(b).unwrap().summary();
    assert!(!s.contains('\u{1b}') && !s.contains('\u{7}') && !s.contains('\r'));
    assert!(s.contains("r\\u{1b}[2J") && s.contains("E\\u{7}") && s.contains("t\\r\\n"));
}

/// Reading an endless file stops at the size cap.
#[test]
fn endless_files_are_bounded() {
    if std::path::Path::new("/dev/zero").exists() {
        assert!(matches!(
            Lut::from_path("/dev/zero"),
            Err(brdf_lut::Error::TooLarge { .. })
        ));
    }
}

/// Batch lookups equal the scalar ones bit for bit, for every table kind.
#[test]
fn batch_lookups_equal_scalar_lookups() {
    let mut x = Xs(11);
    let n = 300;
    let a: Vec<f32> = (0..n).map(|_| (x.next() * 1.7 - 0.05) as f32).collect();
    let b: Vec<f32> = (0..n).map(|_| (x.next() * 3.3 - 1.65) as f32).collect();
    let u: Vec<f32> = (0..n).map(|_| x.next() as f32).collect();
    let mut o = vec![0f32; n];
    let mut o2 = vec![0f32; n];
    for f in [
        "g_modified_sigma0.3.blut",
        "g_modified_sigma0.3_linear.blut",
    ] {
        let bytes = asset(f);
        let t = GTable::parse(&bytes[..]).unwrap();
        assert_eq!(t.g_batch(&a, &b, &mut o), n);
        for k in 0..n {
            assert_eq!(o[k].to_bits(), t.g(a[k], b[k]).to_bits(), "{f} {k}");
        }
    }
    for f in ["g_modified.blut", "g_modified_linear.blut"] {
        let bytes = asset(f);
        let t = GTable3::parse(&bytes[..]).unwrap();
        assert_eq!(t.g_batch(&a, &b, 0.42, &mut o), n);
        for k in 0..n {
            assert_eq!(o[k].to_bits(), t.g(a[k], b[k], 0.42).to_bits(), "{f} {k}");
        }
    }
    let bytes = asset("dfg_ggx.blut");
    let t = DfgTable::parse(&bytes[..]).unwrap();
    assert_eq!(t.ab_batch(&u, &a, &mut o, &mut o2), n);
    for k in 0..n {
        let (p, q) = t.ab(u[k], a[k]);
        assert_eq!(
            (o[k].to_bits(), o2[k].to_bits()),
            (p.to_bits(), q.to_bits())
        );
    }
    let bytes = asset("kc_e_ggx.blut");
    let t = AlbedoTable::parse(&bytes[..]).unwrap();
    assert_eq!(t.e_batch(&u, &a, &mut o), n);
    for k in 0..n {
        assert_eq!(o[k].to_bits(), t.e(u[k], a[k]).to_bits());
    }
    let bytes = asset("kc_eavg_ggx.blut");
    let t = AverageAlbedoTable::parse(&bytes[..]).unwrap();
    assert_eq!(t.e_avg_batch(&a, &mut o), n);
    for k in 0..n {
        assert_eq!(o[k].to_bits(), t.e_avg(a[k]).to_bits());
    }
    // Short outputs bound the work.
    assert_eq!(t.e_avg_batch(&a, &mut o[..5]), 5);
}

/// G from the dot products a shader has: against the direct kernel's shader form (same 3-D
/// extension) within the table's accuracy target (1e-3) plus 1e-4 for the f32 angle
/// arithmetic; in the plane of incidence against the angle form at the same angles.
#[test]
fn g_from_dot_products_matches_the_kernel() {
    use brdf_core::geometry::Dots;
    let b2 = asset("g_modified_sigma0.3.blut");
    let b3 = asset("g_modified.blut");
    let t2 = GTable::parse(&b2[..]).unwrap();
    let t3 = GTable3::parse(&b3[..]).unwrap();
    let direct = ModifiedG::<f64>::new(0.3).unwrap();
    let mut x = Xs(5);
    let mut worst = 0f64;
    for _ in 0..3000 {
        // Random unit l, v above the horizon (z up), cos θ ≥ cos 88°.
        let dir = |x: &mut Xs| {
            let z = 0.035 + 0.965 * x.next();
            let s = (1.0 - z * z).sqrt();
            let p = 2.0 * PI * x.next();
            brdf_core::Vec3::new(s * p.cos(), s * p.sin(), z)
        };
        let (l, v) = (dir(&mut x), dir(&mut x));
        let n = brdf_core::Vec3::new(0.0, 0.0, 1.0);
        let d = Dots::from_vectors(l, v, n);
        let want = direct.g_dots(d);
        let got2 = t2.g_dots(d.n_i as f32, d.n_o as f32, d.i_o as f32) as f64;
        let got3 = t3.g_dots(d.n_i as f32, d.n_o as f32, d.i_o as f32, 0.3) as f64;
        worst = worst.max((got2 - want).abs()).max((got3 - want).abs());
    }
    println!("g_dots max |table - kernel| {worst:.2e}");
    assert!(worst <= 1.1e-3, "{worst}");
    // In-plane: the dot products of in-plane angles give the angle form's value.
    for (ti, tr) in [(0.3f64, 0.5f64), (0.9, -0.4), (1.2, 1.3), (0.1, -1.4)] {
        let d = Dots::<f64>::in_plane(ti, tr);
        let a = t2.g(ti as f32, tr as f32);
        let b = t2.g_dots(d.n_i as f32, d.n_o as f32, d.i_o as f32);
        assert!((a - b).abs() < 2e-4, "({ti}, {tr}): {a} vs {b}");
    }
    assert_eq!(t2.g_dots(0.0, 0.5, 0.1), 0.0);
    assert!(t2.g_dots(f32::NAN, 0.5, 0.1).is_nan());
}

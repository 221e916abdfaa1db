//! The C ABI called from Rust: values against closed forms, handle semantics, table status
//! codes. (The C program in examples/c checks the same contract from C, on the device and
//! the host; `cargo xtask cffi` runs it.)

use brdf_ffi::*;
use std::mem::MaybeUninit;

/// A handle filled by `f`, which must report success.
fn init<H>(f: impl FnOnce(*mut H) -> BrdfStatus) -> H {
    let mut h = MaybeUninit::<H>::uninit();
    assert_eq!(f(h.as_mut_ptr()), BRDF_STATUS_OK);
    unsafe { h.assume_init() }
}

/// The colour with every channel `v`.
fn grey32(v: f32) -> BrdfRgbF32 {
    BrdfRgbF32 { r: v, g: v, b: v }
}

/// The colour with every channel `v`.
fn grey64(v: f64) -> BrdfRgbF64 {
    BrdfRgbF64 { r: v, g: v, b: v }
}

/// The vector (x, y, z).
fn vec32(x: f32, y: f32, z: f32) -> BrdfVec3F32 {
    BrdfVec3F32 { x, y, z }
}

/// The vector (x, y, z).
fn vec64(x: f64, y: f64, z: f64) -> BrdfVec3F64 {
    BrdfVec3F64 { x, y, z }
}

fn modified(sigma: f32, conv: BrdfConvention) -> Box<BrdfModifiedGF32> {
    Box::new(init(|h| unsafe {
        brdf_modified_g_init_f32(h, sigma, conv)
    }))
}

#[test]
fn smith_ggx_g1_matches_its_closed_form() {
    // G1 = 2/(1 + √(1 + α² tan²θ)) (Smith masking for the Trowbridge–Reitz distribution).
    // Tolerance: a few f32 roundings of a value in [0, 1].
    for &(c, a) in &[(0.9f64, 0.1f64), (0.5, 0.3), (0.2, 0.8), (0.05, 0.5)] {
        let t2 = (1.0 - c * c) / (c * c);
        let want = 2.0 / (1.0 + (1.0 + a * a * t2).sqrt());
        let got = brdf_g1_smith_f32(BRDF_SMITH_GGX, c as f32, a as f32) as f64;
        assert!((got - want).abs() < 4e-7, "{c} {a}: {got} vs {want}");
        let got64 = brdf_g1_smith_f64(BRDF_SMITH_GGX, c, a);
        assert!((got64 - want).abs() < 1e-15);
    }
}

#[test]
fn blinn_matches_eq_4_at_a_pair_worked_by_hand() {
    // θi = 0, θr = 60°: α = 30°, β = 30°; 2 cos α cos θr / cos β = 2 cos 60° = 1, and
    // 2 cos α cos θi / cos β = 2: G = min(1, 1, 2) = 1. At θr = 80°: α = β = 40°,
    // 2 cos 80° = 0.347296…
    let g = brdf_g_blinn_f64(0.0, 80f64.to_radians());
    assert!((g - 2.0 * 80f64.to_radians().cos()).abs() < 1e-15);
    assert!((brdf_g_blinn_f32(0.0, 60f32.to_radians()) - 1.0).abs() < 2e-7);
}

#[test]
fn modified_g_is_one_at_normal_incidence_and_f32_tracks_f64() {
    let g = modified(0.3, BRDF_CONVENTION_RECIPROCAL);
    let mut g64 = MaybeUninit::<BrdfModifiedGF64>::uninit();
    assert_eq!(
        unsafe { brdf_modified_g_init_f64(g64.as_mut_ptr(), 0.3, BRDF_CONVENTION_RECIPROCAL) },
        BRDF_STATUS_OK
    );
    // M(0, a) = 1 exactly (the fully passing integral covers the whole density, eq 6).
    assert_eq!(unsafe { brdf_modified_g_f32(&*g, 0.0, 0.0) }, 1.0);
    // The f32 instantiation against the f64 one: quadrature in f32 over ~16 nodes, 1e-5.
    for &(ti, tr) in &[(0.3f32, 0.5f32), (1.2, -0.9), (0.7, 1.4)] {
        let a = unsafe { brdf_modified_g_f32(&*g, ti, tr) } as f64;
        let b = unsafe { brdf_modified_g_f64(g64.as_ptr(), ti as f64, tr as f64) };
        assert!((a - b).abs() < 1e-5, "{ti} {tr}: {a} vs {b}");
        assert!((0.0..=1.0).contains(&b));
    }
}

#[test]
fn handles_refuse_null_zeroed_failed_and_foreign_handles() {
    let zero = MaybeUninit::<BrdfModifiedGF32>::zeroed();
    assert!(unsafe { brdf_modified_g_f32(zero.as_ptr(), 0.1, 0.1) }.is_nan());
    assert!(unsafe { brdf_modified_g_f32(std::ptr::null(), 0.1, 0.1) }.is_nan());
    let mut g = *modified(0.3, BRDF_CONVENTION_PRINTED);
    // A failed re-init clears a valid handle.
    assert_eq!(
        unsafe { brdf_modified_g_init_f32(&mut g, f32::NAN, 0) },
        BRDF_STATUS_INVALID_ARGUMENT
    );
    assert!(unsafe { brdf_modified_g_f32(&g, 0.1, 0.1) }.is_nan());
    // The handle of a GGX surface is not a modified-G handle.
    let gx: BrdfGgxF32 =
        init(|h| unsafe { brdf_ggx_init_f32(h, grey32(0.04), 0.3, BRDF_SMITH_FORM_CORRELATED) });
    let foreign = std::ptr::from_ref(&gx).cast::<BrdfModifiedGF32>();
    assert!(unsafe { brdf_modified_g_f32(foreign, 0.1, 0.1) }.is_nan());
}

#[test]
fn a_copied_handle_answers_like_the_original() {
    let g = modified(0.6, BRDF_CONVENTION_RECIPROCAL);
    let mut copy = MaybeUninit::<BrdfModifiedGF32>::uninit();
    unsafe {
        std::ptr::copy_nonoverlapping(&*g, copy.as_mut_ptr(), 1);
        let a = brdf_modified_g_dots_f32(&*g, 0.4, 0.8, 0.1);
        let b = brdf_modified_g_dots_f32(copy.as_ptr(), 0.4, 0.8, 0.1);
        assert_eq!(a.to_bits(), b.to_bits());
    }
}

#[test]
fn batch_checks_arrays_and_allows_in_place_output() {
    let g = modified(0.3, BRDF_CONVENTION_RECIPROCAL);
    let (ni, no, io) = ([0.9f32, 0.5, 0.3], [0.7f32, 0.5, 0.95], [0.5f32, 0.2, 0.1]);
    let mut buf = io;
    unsafe {
        let p = buf.as_mut_ptr();
        assert_eq!(
            brdf_modified_g_dots_batch_f32(&*g, ni.as_ptr(), no.as_ptr(), p, p, 3),
            BRDF_STATUS_OK
        );
        for k in 0..3 {
            let single = brdf_modified_g_dots_f32(&*g, ni[k], no[k], io[k]);
            assert_eq!(buf[k].to_bits(), single.to_bits());
        }
        let o = buf.as_mut_ptr();
        assert_eq!(
            brdf_modified_g_dots_batch_f32(&*g, ni.as_ptr(), std::ptr::null(), io.as_ptr(), o, 3),
            BRDF_STATUS_NULL_POINTER
        );
        assert_eq!(
            brdf_modified_g_dots_batch_f32(
                &*g,
                ni.as_ptr(),
                no.as_ptr(),
                io.as_ptr(),
                o,
                usize::MAX
            ),
            BRDF_STATUS_BAD_LENGTH
        );
    }
}

fn asset(name: &str) -> &'static [u8] {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name);
    Box::leak(std::fs::read(p).unwrap().into_boxed_slice())
}

/// The table handle `parse` fills from the committed asset `name` (which must parse).
fn table<H>(parse: unsafe extern "C" fn(*mut H, *const u8, usize) -> BrdfStatus, name: &str) -> H {
    let bytes = asset(name);
    init(|h| unsafe { parse(h, bytes.as_ptr(), bytes.len()) })
}

#[test]
fn table_status_codes_follow_the_format() {
    let bytes = asset("kc_eavg_ggx.blut");
    let mut t = MaybeUninit::<BrdfAverageAlbedoTable>::uninit();
    let parse = |t: &mut MaybeUninit<BrdfAverageAlbedoTable>, b: &[u8]| unsafe {
        brdf_average_albedo_table_parse(t.as_mut_ptr(), b.as_ptr(), b.len())
    };
    assert_eq!(parse(&mut t, bytes), BRDF_STATUS_OK);
    // E_avg = 2∫ E μ dμ ∈ (0, 1] for F = 1 (energy conservation), and falls with roughness.
    let (smooth, rough) = unsafe {
        (
            brdf_average_albedo_table_e_avg(t.as_ptr(), 0.05),
            brdf_average_albedo_table_e_avg(t.as_ptr(), 1.0),
        )
    };
    assert!(smooth <= 1.0 + 1e-3 && rough > 0.0 && rough < smooth);
    let mut bad = bytes.to_vec();
    *bad.last_mut().unwrap() ^= 1;
    assert_eq!(parse(&mut t, &bad), BRDF_STATUS_TABLE_CHECKSUM);
    assert!(unsafe { brdf_average_albedo_table_e_avg(t.as_ptr(), 0.5) }.is_nan());
    assert_eq!(
        parse(&mut t, &bytes[..bytes.len() - 1]),
        BRDF_STATUS_TABLE_PAYLOAD_LENGTH
    );
    assert_eq!(parse(&mut t, &bytes[..2]), BRDF_STATUS_TABLE_TRUNCATED);
    assert_eq!(parse(&mut t, b"NOPE...."), BRDF_STATUS_TABLE_BAD_MAGIC);
    let mut g = MaybeUninit::<BrdfGTable>::uninit();
    assert_eq!(
        unsafe { brdf_g_table_parse(g.as_mut_ptr(), bytes.as_ptr(), bytes.len()) },
        BRDF_STATUS_TABLE_WRONG_KIND
    );
    assert_eq!(
        unsafe { brdf_g_table_parse(g.as_mut_ptr(), std::ptr::null(), 0) },
        BRDF_STATUS_NULL_POINTER
    );
}

#[test]
fn g_table_agrees_with_the_direct_g_within_its_stated_error() {
    // The table's header states its interpolation error (max |ΔG| over random points,
    // 9.8e-4 or less for the committed G tables); allow twice that.
    let t = table(brdf_g_table_parse, "g_modified_sigma0.3.blut");
    let g = modified(0.3, BRDF_CONVENTION_RECIPROCAL);
    assert_eq!(unsafe { brdf_g_table_sigma(&t) }, 0.3);
    for &(ti, tr) in &[(0.2f32, 0.4f32), (1.0, -0.7), (0.6, 1.3), (1.4, 1.4)] {
        let a = unsafe { brdf_g_table_g(&t, ti, tr) };
        let b = unsafe { brdf_modified_g_f32(&*g, ti, tr) };
        assert!((a - b).abs() < 2e-3, "{ti} {tr}: table {a}, direct {b}");
    }
}

#[test]
fn every_status_has_a_name() {
    for s in -1..=20 {
        let p = brdf_status_str(s);
        assert!(!p.is_null());
        let name = unsafe { std::ffi::CStr::from_ptr(p) }.to_str().unwrap();
        assert!(!name.is_empty());
    }
    assert_eq!(brdf_abi_version(), BRDF_ABI_VERSION);
}

#[test]
fn g_table_over_sigma_agrees_with_the_direct_g_within_its_stated_error() {
    // The 3-D table states max |ΔG| = 4.0e-4 over random points (README table); the direct
    // f32 G adds ~1e-5. Allowed: 2e-3.
    let t = table(brdf_g_table3_parse, "g_modified.blut");
    let (mut lo, mut hi) = (0f32, 0f32);
    assert_eq!(
        unsafe { brdf_g_table3_sigma_range(&t, &mut lo, &mut hi) },
        BRDF_STATUS_OK
    );
    assert!(lo < 0.3 && 0.6 < hi);
    for &s in &[0.3f32, 0.6] {
        let g = modified(s, BRDF_CONVENTION_RECIPROCAL);
        for &(ti, tr) in &[(0.2f32, 0.4f32), (1.0, -0.7), (0.6, 1.3)] {
            let a = unsafe { brdf_g_table3_g(&t, ti, tr, s) };
            let b = unsafe { brdf_modified_g_f32(&*g, ti, tr) };
            assert!(
                (a - b).abs() < 2e-3,
                "σ {s} {ti} {tr}: table {a}, direct {b}"
            );
        }
        let (ni, no, io) = (0.8f32, 0.6f32, 0.3f32);
        let a = unsafe { brdf_g_table3_g_dots(&t, ni, no, io, s) };
        let b = unsafe { brdf_modified_g_dots_f32(&*g, ni, no, io) };
        assert!((a - b).abs() < 2e-3, "σ {s} dots: table {a}, direct {b}");
    }
    assert!(unsafe { brdf_g_table3_g(&t, f32::NAN, 0.1, 0.3) }.is_nan());
}

#[test]
fn table_batches_equal_their_single_queries_bit_for_bit() {
    let g = table(brdf_g_table_parse, "g_modified_sigma0.3.blut");
    let (ti, tr) = ([0.2f32, 1.0, 0.6, f32::NAN], [0.4f32, -0.7, 1.3, 0.1]);
    let mut out = [0f32; 4];
    let st = unsafe { brdf_g_table_g_batch(&g, ti.as_ptr(), tr.as_ptr(), out.as_mut_ptr(), 4) };
    assert_eq!(st, BRDF_STATUS_OK);
    for k in 0..4 {
        let single = unsafe { brdf_g_table_g(&g, ti[k], tr[k]) };
        assert_eq!(out[k].to_bits(), single.to_bits(), "{k}");
    }
    // Two outputs, both in place over the inputs: each element is read before it is written.
    let dfg = table(brdf_dfg_table_parse, "dfg_ggx.blut");
    let (mu, r) = ([0.1f32, 0.5, 0.9], [0.2f32, 0.5, 0.8]);
    let (mut a, mut b) = (mu, r);
    let st = unsafe {
        brdf_dfg_table_ab_batch(
            &dfg,
            a.as_ptr(),
            b.as_ptr(),
            a.as_mut_ptr(),
            b.as_mut_ptr(),
            3,
        )
    };
    assert_eq!(st, BRDF_STATUS_OK);
    for k in 0..3 {
        let single = unsafe { brdf_dfg_table_ab(&dfg, mu[k], r[k]) };
        assert_eq!(
            (a[k].to_bits(), b[k].to_bits()),
            (single.a.to_bits(), single.b.to_bits())
        );
    }
    // Bad handle before bad arrays; nothing is written on an error.
    let zero = MaybeUninit::<BrdfDfgTable>::zeroed();
    let p = std::ptr::null_mut();
    let st = unsafe { brdf_dfg_table_ab_batch(zero.as_ptr(), mu.as_ptr(), r.as_ptr(), p, p, 3) };
    assert_eq!(st, BRDF_STATUS_NOT_INITIALISED);
    let mut untouched = [7f32; 3];
    let o = untouched.as_mut_ptr();
    let st = unsafe { brdf_dfg_table_ab_batch(&dfg, mu.as_ptr(), r.as_ptr(), o, p, 3) };
    assert_eq!(st, BRDF_STATUS_NULL_POINTER);
    assert_eq!(untouched, [7.0; 3]);
    let st = unsafe { brdf_dfg_table_ab_batch(&dfg, p, p, p, p, 0) };
    assert_eq!(st, BRDF_STATUS_OK);
}

#[test]
fn torrance_sparrow_with_n_h_is_exact_for_near_mirror_pairs_at_the_horizon() {
    // Beckmann, α = 0.05000000074505806 (σ = α/√2), separable Smith, F = 1, ks = 1, no
    // diffuse part: values published with a defect report against an established renderer
    // (12 significant digits). From the three dot products alone 2 + 2 wi·wo cancels and
    // the f64 result is 5e-4 and 4e-2 off; with n·h it must match to the published digits.
    let alpha = 0.05000000074505806f64;
    let sigma = alpha / 2f64.sqrt();
    let (g, f) = (BRDF_GEOMETRIC_SMITH_SEPARABLE, BRDF_FRESNEL_ONE);
    let ts = init(|h| unsafe { brdf_torrance_sparrow_init_f64(h, sigma, g, f, 0.0, 1.0, 0.0) });
    let pairs = [
        (
            [
                -0.5536822645109706,
                -0.8327280167406141,
                1.0062167677184382e-05,
            ],
            [0.5536824247997054, 0.8327279101650903, 1e-05],
            154134.432937,
        ),
        (
            [
                0.39298152400471775,
                0.9195463673952927,
                1.02502789627328e-06,
            ],
            [-0.39298152558074945, -0.9195463667217801, 1e-06],
            159942.898969,
        ),
    ];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (wi, wo, published) in pairs {
        // n·h as a shader computes it: normalize(wi + wo).z. The sums' x and y parts are
        // exact (Sterbenz), so n·h carries only a few roundings.
        let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
        let n_h = h[2] / dot(h, h).sqrt();
        let got = unsafe { brdf_torrance_sparrow_eval_nh_f64(&ts, wi[2], wo[2], dot(wi, wo), n_h) };
        // 12 published digits (±5e-12) plus n·h's rounding, amplified by tan²θh/α² ≈ 0.1
        // in D's exponent: 1e-9 relative.
        assert!(
            ((got - published) / published).abs() < 1e-9,
            "{got} vs {published}"
        );
        let lossy = unsafe { brdf_torrance_sparrow_eval_f64(&ts, wi[2], wo[2], dot(wi, wo)) };
        assert!(
            ((lossy - published) / published).abs() > 1e-5,
            "three dots: {lossy}"
        );
        // Bad n·h: NaN, as for the other inputs.
        assert!(unsafe {
            brdf_torrance_sparrow_eval_nh_f64(&ts, wi[2], wo[2], dot(wi, wo), f64::NAN)
        }
        .is_nan());
    }
    // The f32 entry point at the first pair. Here tan²θh ≈ 9.2e-5, 1 − n·h ≈ 4.6e-5 and
    // tan²θh/α² ≈ 0.037: n·h rounded to f32 (6e-8) is 1.3e-3 of 1 − n·h, i.e. of tan²θh,
    // which moves D's exponent by 0.037 × 1.3e-3 ≈ 5e-5; bound 1e-4. The three dot
    // products alone are off by 4e-2 in f32 (2 + 2 wi·wo is a few ulps of 2).
    let t32 =
        init(|h| unsafe { brdf_torrance_sparrow_init_f32(h, sigma as f32, g, f, 0.0, 1.0, 0.0) });
    let (wi, wo) = (pairs[0].0, pairs[0].1);
    let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
    let n_h = h[2] / dot(h, h).sqrt();
    let got = unsafe {
        brdf_torrance_sparrow_eval_nh_f32(
            &t32,
            wi[2] as f32,
            wo[2] as f32,
            dot(wi, wo) as f32,
            n_h as f32,
        )
    } as f64;
    let rel = ((got - pairs[0].2) / pairs[0].2).abs();
    assert!(rel < 1e-4, "f32 with n·h: {got}, {rel:e} relative");
    let lossy = unsafe {
        brdf_torrance_sparrow_eval_f32(&t32, wi[2] as f32, wo[2] as f32, dot(wi, wo) as f32)
    } as f64;
    assert!(
        ((lossy - pairs[0].2) / pairs[0].2).abs() > 1e-3,
        "f32 three dots: {lossy}"
    );
}

#[test]
fn sheen_through_the_abi() {
    // The visibility constants are the catalogue's option indices.
    use brdf_core::models::SheenVisibility;
    assert_eq!(
        SheenVisibility::ALL[BRDF_SHEEN_VISIBILITY_ESTEVEZ_KULLA as usize],
        SheenVisibility::EstevezKulla
    );
    assert_eq!(
        SheenVisibility::ALL[BRDF_SHEEN_VISIBILITY_ASHIKHMIN as usize],
        SheenVisibility::Ashikhmin
    );
    let white = grey64(1.0);
    let s: BrdfSheenF64 =
        init(|p| unsafe { brdf_sheen_init_f64(p, white, 1.0, BRDF_SHEEN_VISIBILITY_ASHIKHMIN) });
    // r = 1 (α = 1): D = 3 sin θh/(2π); wi = wo = (0.6, 0, 0.8): h = wo, sin θh = 0.6,
    // V = 1/(4(0.8 + 0.8 − 0.64)) = 1/3.84.
    let w = vec64(0.6, 0.0, 0.8);
    let want = 3.0 * 0.6 / (2.0 * std::f64::consts::PI) / 3.84;
    let got = unsafe { brdf_sheen_eval_f64(&s, w, w) };
    assert!(
        (got.r - want).abs() < 1e-15 && got.g == got.r,
        "{got:?} vs {want}"
    );
    let dots = unsafe { brdf_sheen_eval_dots_f64(&s, 0.8, 0.8, 1.0) };
    assert!((dots.r - want).abs() < 1e-14, "{dots:?}");
    // Bad input: status codes and NaN.
    let mut h = MaybeUninit::<BrdfSheenF32>::uninit();
    let one = grey32(1.0);
    assert_eq!(
        unsafe { brdf_sheen_init_f32(h.as_mut_ptr(), one, 0.5, 2) },
        BRDF_STATUS_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { brdf_sheen_init_f32(h.as_mut_ptr(), one, 1.5, 0) },
        BRDF_STATUS_INVALID_ARGUMENT
    );
    assert!(unsafe { brdf_sheen_albedo_f32(h.as_ptr(), 0.5) }.r.is_nan());
    assert!(unsafe { brdf_sheen_albedo_f64(std::ptr::null(), 0.5) }
        .r
        .is_nan());
    // The albedo at normal incidence, f32 against f64 (the same quadrature).
    let s32: BrdfSheenF32 =
        init(|p| unsafe { brdf_sheen_init_f32(p, one, 1.0, BRDF_SHEEN_VISIBILITY_ASHIKHMIN) });
    let a64 = unsafe { brdf_sheen_albedo_f64(&s, 1.0) }.r;
    let a32 = unsafe { brdf_sheen_albedo_f32(&s32, 1.0) }.r as f64;
    assert!(
        a64 > 0.0 && a64 < 1.0 && (a32 - a64).abs() < 1e-4,
        "{a32} {a64}"
    );
    assert_eq!(unsafe { brdf_sheen_albedo_f64(&s, 0.0) }.r, 0.0);
}

/// Stratified estimate of the reflected and transmitted integrals ∫ f |n·wi| dωi of a rough
/// dielectric at α = 0 (raised to its 1e-4 floor) for a viewer at `wo`: N samples with the
/// choice numbers uc = (k + 1/2)/N.
fn dielectric_energy(eta: f64, wo: BrdfVec3F64, n: usize) -> (f64, f64) {
    let m: BrdfRoughDielectricF64 = init(|p| unsafe {
        brdf_rough_dielectric_init_f64(p, BRDF_DIELECTRIC_DISTRIBUTION_GGX, 0.0, eta)
    });
    let (mut er, mut et) = (0.0, 0.0);
    for k in 0..n {
        let (u0, u1, uc) = (
            (k as f64 * 0.618_033_988_75).fract(),
            (k as f64 + 0.25) / n as f64,
            (k as f64 + 0.5) / n as f64,
        );
        let mut s = MaybeUninit::<BrdfBsdfSampleF64>::uninit();
        let st = unsafe { brdf_rough_dielectric_sample_f64(&m, wo, u0, u1, uc, s.as_mut_ptr()) };
        assert_eq!(st, BRDF_STATUS_OK);
        let s = unsafe { s.assume_init() };
        if s.wi.z > 0.0 {
            er += s.weight.r;
        } else {
            et += s.weight.r;
        }
    }
    (er / n as f64, et / n as f64)
}

#[test]
fn rough_dielectric_smooth_limit_matches_fresnel_and_snell() {
    // Normal incidence, η = 1.5: reflected R0 = ((η − 1)/(η + 1))² = 0.04, and in the
    // radiance convention η² ∫ f_t |cos| = 1 − R0. Each estimate is a count over N (the
    // weights are G1 = 1 at the α floor) within 1/(2N) of its fraction: tolerance 1/N.
    let n = 4096;
    let up = vec64(0.0, 0.0, 1.0);
    let (er, et) = dielectric_energy(1.5, up, n);
    assert!((er - 0.04).abs() <= 1.0 / n as f64, "{er}");
    assert!((er + 2.25 * et - 1.0).abs() < 1e-9, "{er} {et}");
    // Seen from glass (η = 1/1.5) at 60° from the normal, past the critical angle
    // asin(1/1.5) = 41.8°: total internal reflection, everything comes back, each weight
    // the mirror direction's Smith G1 = 2/(1 + √(1 + α² tan²60°)) = 1 − 7.5e-9 at α = 1e-4:
    // tolerance 1e-7.
    let wo = vec64(0.75f64.sqrt(), 0.0, 0.5);
    let (er, et) = dielectric_energy(1.0 / 1.5, wo, 256);
    assert!((er - 1.0).abs() < 1e-7 && et == 0.0, "{er} {et}");
}

#[test]
fn rough_dielectric_adjoint_is_the_swapped_eval_and_bad_input_is_refused() {
    // Generalised reciprocity (Walter et al. 2007 §5.2): f*(wi, wo) = f(wo, wi), here for a
    // pair across the interface, where f itself is not symmetric (factor η²).
    let m: BrdfRoughDielectricF64 = init(|p| unsafe {
        brdf_rough_dielectric_init_f64(p, BRDF_DIELECTRIC_DISTRIBUTION_BECKMANN, 0.3, 1.5)
    });
    let wi = vec64(0.3, 0.1, -0.9f64.sqrt());
    let wo = vec64(-0.5, 0.0, 0.75f64.sqrt());
    let fa = unsafe { brdf_rough_dielectric_eval_adjoint_f64(&m, wi, wo) };
    let fs = unsafe { brdf_rough_dielectric_eval_f64(&m, wo, wi) };
    let f = unsafe { brdf_rough_dielectric_eval_f64(&m, wi, wo) };
    assert!(f > 0.0 && ((fa - fs) / fs).abs() < 1e-12, "{fa} {fs}");
    // wi is inside (η_i = 1.5), wo outside: f* = (η_i/η_o)² f = 2.25 f.
    assert!(((fa / f) - 2.25).abs() < 1e-12, "{fa} {f}");
    // A viewer at the horizon has no sample; the output is left as it was.
    let grazing = vec64(1.0, 0.0, 1e-300);
    let mut s = MaybeUninit::<BrdfBsdfSampleF64>::zeroed();
    let st =
        unsafe { brdf_rough_dielectric_sample_f64(&m, grazing, 0.5, 0.5, 0.5, s.as_mut_ptr()) };
    assert_eq!(st, BRDF_STATUS_NO_SAMPLE);
    assert_eq!(unsafe { s.assume_init() }.pdf, 0.0);
    let mut h = MaybeUninit::<BrdfRoughDielectricF32>::uninit();
    let st = unsafe { brdf_rough_dielectric_init_f32(h.as_mut_ptr(), 2, 0.3, 1.5) };
    assert_eq!(st, BRDF_STATUS_INVALID_ARGUMENT);
    let w = vec32(0.0, 0.0, 1.0);
    assert!(unsafe { brdf_rough_dielectric_eval_f32(h.as_ptr(), w, w) }.is_nan());
}

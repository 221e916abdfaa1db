//! f64 kernels for the hot loops of the f64 instantiation: eˣ on the bounded range of the
//! integrands ([`exp_bounded_f64`]) and sin/cos on the clamped angle range
//! ([`sin_cos_f64`]). Both are branch-free on their fast range (so the compiler can keep
//! them inline and evaluate two of them in one SSE2 register) and fall back to libm
//! elsewhere.

/// eˣ for x ∈ [−87, 0] in f64, branch-free; the f64 [`crate::Real::exp_bounded`].
///
/// x below −87 is taken as −87 (the trait's contract); NaN gives NaN. Arguments up to 709
/// also give finite results (not used by the kernels).
///
/// x = k·ln 2 + r with k = round(x/ln 2) (by adding and subtracting 1.5·2⁵², which leaves
/// k in the low mantissa bits) and |r| ≤ ln 2/2; r by a two-part Cody–Waite split
/// ln 2 = L1 + L2, L1 = ln 2 cut to 32 significant bits (so k·L1 is exact for |k| < 2²¹
/// and x − k·L1 is exact), L2 = ln 2 − L1 rounded to f64 (the split's residual
/// 1.2e-26·|k| ≤ 1.5e-24 is far below an ulp of r). eʳ by the degree-11 Chebyshev
/// interpolant of eʳ on [−ln 2/2, ln 2/2] (fitted in 50-digit arithmetic, written out in
/// monomial form): relative error 3.2e-18 with exact coefficients, 1.7e-17 (0.08 ulp)
/// with the coefficients rounded to f64. Horner's rule adds at most about 1 ulp, and 2ᵏ is
/// exact (built from the exponent bits). Accuracy: within 2 ulp of the exact value
/// (measured against libm's `exp` in the tests: see [`tests`]).
#[inline(always)]
pub fn exp_bounded_f64(x: f64) -> f64 {
    const LOG2_E: f64 = core::f64::consts::LOG2_E;
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²
    const L1: f64 = 0.693_147_180_369_123_8; // 0x1.62e42fee00000p-1
    const L2: f64 = 1.908_214_929_270_587_7e-10; // ln 2 − L1
    const C: [f64; 12] = [
        1.0,
        1.0,
        0.500_000_000_000_001_9,
        0.166_666_666_666_666_8,
        0.041_666_666_666_488_1,
        0.008_333_333_333_319_601,
        0.001_388_888_895_231_477_5,
        0.000_198_412_698_900_471_13,
        2.480_148_548_232_849e-5,
        2.755_724_091_857_897e-6,
        2.763_263_963_904_116_6e-7,
        2.511_003_760_596_388_3e-8,
    ];
    // NaN fails the comparison and stays NaN (it then propagates through r).
    let x = if x < -87.0 { -87.0 } else { x };
    let t = x * LOG2_E + MAGIC;
    let k = t.to_bits().wrapping_sub(MAGIC.to_bits());
    let kf = t - MAGIC;
    let r = (x - kf * L1) - kf * L2;
    let mut p = C[11];
    for &c in C[..11].iter().rev() {
        p = p * r + c;
    }
    // p ∈ [0.70, 1.42] has a biased exponent of 1022 or 1023: adding k to it gives p·2ᵏ
    // (k ≥ −126 keeps it a normal number).
    f64::from_bits(p.to_bits().wrapping_add(k << 52))
}

/// The complementary error function for x ∈ [0, 4.6] in f64, branch-free; the f64
/// [`crate::Real::erfc_bounded`].
///
/// Outside [0, 4.6], x is taken as the nearer end; NaN gives NaN. As in
/// [`super::erfc_f32`], erfc x = e^{−x²} · t · q(t) with t = 1/(1 + x/2) ∈ [0.303, 1]:
/// q(t) = e^{x²} erfc x · (1 + x/2) is smooth in t, and here q is its degree-20 Chebyshev
/// interpolant on that interval (fitted in 60-digit arithmetic, written out in powers of
/// s = t − 0.6515…, the interval's midpoint, where the sum of the terms' magnitudes is at
/// most 2.6 times the value, so Horner's rule loses no more than a few ulp): relative
/// error 2.8e-18 with exact coefficients, 1.1e-16 with the coefficients rounded to f64.
/// e^{−x²} by [`exp_bounded_f64`], from x² rounded to f64: that rounding (relative ε/2)
/// becomes a relative error of up to x²·ε/2 in the result (libm avoids it by splitting x;
/// here it is at most 1.2e-15 on [0, 4.6]). Accuracy: relative error within
/// (4 + x²/2)·ε of libm's `erfc` (measured in the tests), ε = 2⁻⁵².
#[inline(always)]
pub fn erfc_bounded_f64(x: f64) -> f64 {
    const TC: f64 = 0.651_515_151_515_151_5;
    const Q: [f64; 21] = [
        0.628_147_531_665_595_7,
        0.863_960_141_210_234_1,
        0.598_736_902_895_665_4,
        0.025_170_561_803_797_883,
        -0.213_097_891_555_835_14,
        -0.003_790_290_076_424_988,
        0.105_197_706_218_370_46,
        -0.033_343_035_177_471_7,
        -0.046_152_687_885_946_043,
        0.046_181_386_099_028_06,
        0.000_613_496_570_400_524_8,
        -0.032_051_163_216_475_484,
        0.024_784_482_122_266_405,
        0.002_577_266_379_485_377,
        -0.021_228_326_666_224_182,
        0.018_617_384_919_109_074,
        -0.001_443_871_141_057_632,
        -0.015_829_224_097_889_068,
        0.016_989_153_722_049_59,
        0.001_819_390_477_577_440_4,
        -0.011_053_263_304_961_829,
    ];
    // NaN fails both comparisons and stays NaN.
    let x = if x < 0.0 { 0.0 } else { x };
    let x = if x > 4.6 { 4.6 } else { x };
    let t = 1.0 / (1.0 + 0.5 * x);
    let s = t - TC;
    let mut q = Q[20];
    for &c in Q[..20].iter().rev() {
        q = q * s + c;
    }
    exp_bounded_f64(-(x * x)) * (t * q)
}

/// sin x and cos x in f64; for |x| ≤ π/2 (the clamped angles of the kernels) by a short
/// branch-free evaluation, beyond that by libm's `sincos`. NaN gives NaN.
///
/// For |x| ≤ 1.6 (a little beyond π/2): k = round(2x/π) ∈ {−1, 0, 1} and
/// r = (x − k·P1) − k·P2 with π/2 = P1 + P2 (P1 = π/2 rounded to f64, P2 the rounding error
/// rounded to f64; x − k·P1 is exact by Sterbenz's lemma when k ≠ 0, and the split's
/// residual 1.5e-33 is far below an ulp of r), so |r| ≤ π/4. Then the Taylor series
/// sin r = r − r³/3! + … + r¹⁷/17! and cos r = 1 − r²/2! + … + r¹⁶/16!: the first omitted
/// terms, r¹⁹/19! and r¹⁸/18!, are below 1e-19·|r| and 2e-18 on |r| ≤ π/4, far below
/// f64 rounding. Both polynomials run in r² side by side (one SSE2 register). The quadrant
/// k = ±1 swaps them: sin(±π/2 + r) = ±cos r, cos(±π/2 + r) = ∓sin r. Accuracy: within
/// 2 ulp (absolute 2.3e-16) of the exact values (measured against libm in the tests).
#[inline]
pub fn sin_cos_f64(x: f64) -> (f64, f64) {
    const FRAC_2_PI: f64 = core::f64::consts::FRAC_2_PI;
    const P1: f64 = core::f64::consts::FRAC_PI_2;
    const P2: f64 = 6.123_233_995_736_766e-17; // π/2 − P1
                                               // 1/(2j+1)! for sin (j = 1…8) and 1/(2j)! for cos (j = 1…8), alternating in sign.
    const S: [f64; 8] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 1_307_674_368_000.0,
        1.0 / 355_687_428_096_000.0,
    ];
    const K: [f64; 8] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 20_922_789_888_000.0,
    ];
    if !(x.abs() <= 1.6) {
        return libm::sincos(x);
    }
    let t = x * FRAC_2_PI;
    let k = if t > 0.5 {
        1.0
    } else if t < -0.5 {
        -1.0
    } else {
        0.0
    };
    let r = (x - k * P1) - k * P2;
    let r2 = r * r;
    let (mut ps, mut pc) = (S[7], K[7]);
    for j in (0..7).rev() {
        ps = ps * r2 + S[j];
        pc = pc * r2 + K[j];
    }
    let s = r + r * (r2 * ps);
    let c = 1.0 + r2 * pc;
    if k == 0.0 {
        (s, c)
    } else {
        (k * c, -k * s)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{erfc_bounded_f64, exp_bounded_f64, sin_cos_f64};

    /// The distance of `got` from `want` in units of the ulp of `want` (2^(e−52) for
    /// |want| ∈ [2^e, 2^(e+1))).
    fn ulps(got: f64, want: f64) -> f64 {
        if got == want {
            return 0.0;
        }
        let e = libm::floor(libm::log2(want.abs()));
        (got - want).abs() / libm::exp2(e - 52.0)
    }

    /// The f64 bounded exponential against libm's `exp` (itself within 1 ulp of exact):
    /// ≤ 2 ulp over a dense grid of [−87, 0] and densely over the kernels' range −v²,
    /// v ∈ [0, 4.5], plus the edge points.
    #[test]
    fn exp_bounded_f64_within_two_ulp_of_libm() {
        let mut worst = 0f64;
        let n = 4_000_000;
        for i in 0..=n {
            let x = -87.0 * i as f64 / n as f64;
            worst = worst.max(ulps(exp_bounded_f64(x), libm::exp(x)));
        }
        for i in 0..=2_000_000 {
            let v = 4.5 * i as f64 / 2e6;
            let x = -(v * v);
            worst = worst.max(ulps(exp_bounded_f64(x), libm::exp(x)));
        }
        // Around the reduction's switch points x = (k + ½) ln 2, where |r| is largest.
        for k in 0..126 {
            let x0 = -(k as f64 + 0.5) * core::f64::consts::LN_2;
            let mut x = x0;
            for _ in 0..64 {
                worst = worst.max(ulps(exp_bounded_f64(x), libm::exp(x)));
                x = libm::nextafter(x, 0.0);
            }
            let mut x = x0;
            for _ in 0..64 {
                worst = worst.max(ulps(exp_bounded_f64(x), libm::exp(x)));
                x = libm::nextafter(x, -1e3);
            }
        }
        std::println!("exp_bounded_f64: max error {worst} ulp");
        assert!(worst <= 2.0, "max error {worst} ulp");
        assert_eq!(exp_bounded_f64(0.0), 1.0);
        assert_eq!(exp_bounded_f64(-0.0), 1.0);
        assert!(ulps(exp_bounded_f64(-20.25), libm::exp(-20.25)) <= 2.0);
        assert!(ulps(exp_bounded_f64(-87.0), libm::exp(-87.0)) <= 2.0);
        // Tiny arguments: e^x = 1 + x to within 2 ulp.
        for x in [-1e-300, -5e-324, -1e-17, -1e-9] {
            assert!(ulps(exp_bounded_f64(x), libm::exp(x)) <= 2.0, "x={x:e}");
        }
        // Below the range: taken as −87.
        assert_eq!(exp_bounded_f64(-1e4), exp_bounded_f64(-87.0));
        assert_eq!(exp_bounded_f64(f64::NEG_INFINITY), exp_bounded_f64(-87.0));
        assert!(exp_bounded_f64(f64::NAN).is_nan());
        // Slightly positive arguments stay accurate (the contract only promises finite).
        for x in [1e-12, 0.3, 1.0, 10.0, 88.0] {
            assert!(ulps(exp_bounded_f64(x), libm::exp(x)) <= 2.0, "x={x}");
        }
    }

    /// The f64 sine and cosine against libm's `sin` and `cos` (each within 1 ulp of exact):
    /// ≤ 2 ulp over a dense grid of the fast range [−1.6, 1.6], plus the edge points and the libm
    /// fall-back.
    #[test]
    fn sin_cos_f64_within_two_ulp_of_libm() {
        let h = core::f64::consts::FRAC_PI_2;
        let (mut ws, mut wc, mut wabs) = (0f64, 0f64, 0f64);
        let n = 4_000_000;
        let mut check = |x: f64| {
            let (s, c) = sin_cos_f64(x);
            let (es, ec) = (libm::sin(x), libm::cos(x));
            ws = ws.max(ulps(s, es));
            // cos near ±π/2 is ~1e-17 while its argument is only known to ulp(π/2) = 2.2e-16:
            // there the error is also counted in absolute terms (against 2⁻⁵³).
            if ec > 1e-3 {
                wc = wc.max(ulps(c, ec));
            }
            wabs = wabs.max((s - es).abs()).max((c - ec).abs());
        };
        for i in 0..=n {
            check(-1.6 + 3.2 * i as f64 / n as f64);
        }
        // Around the quadrant switch 2x/π = ±½ and near the ends.
        for x0 in [h / 2.0, -h / 2.0, h, -h, 0.0] {
            let (mut a, mut b) = (x0, x0);
            for _ in 0..1000 {
                check(a);
                check(b);
                a = libm::nextafter(a, 10.0);
                b = libm::nextafter(b, -10.0);
            }
        }
        for i in 0..=100_000 {
            check(1e-8 * i as f64);
        }
        std::println!("sin_cos_f64: max sin {ws} ulp, cos {wc} ulp, abs {wabs:e}");
        assert!(ws <= 2.0, "sin: {ws} ulp");
        assert!(wc <= 2.0, "cos: {wc} ulp");
        assert!(wabs <= 2.3e-16, "abs {wabs:e}");
        assert_eq!(sin_cos_f64(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_f64(-0.0), (0.0, 1.0));
        let (s, c) = sin_cos_f64(h);
        assert!(s == 1.0 && ulps(c, libm::cos(h)) <= 2.0, "cos(π/2) = {c:e}");
        let (s, c) = sin_cos_f64(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos_f64(f64::INFINITY);
        assert!(s.is_nan() && c.is_nan());
        // Beyond π/2: libm's values.
        for x in [1.61, 3.0, -100.0, 1e10] {
            assert_eq!(sin_cos_f64(x), (libm::sin(x), libm::cos(x)));
        }
    }

    /// The f64 bounded complementary error function against libm's `erfc` (within 1 ulp of
    /// exact on this range): relative error within (4 + x²/2)·ε over a dense grid of
    /// [0, 4.6] and at the ends (x²ε/2 from the rounding of x² in e^{−x²}, 4ε for the
    /// polynomial, its coefficients, t and the products); clamping outside; NaN.
    #[test]
    fn erfc_bounded_f64_against_libm() {
        let (mut worst, mut worst_plain) = (0f64, 0f64);
        let n = 2_000_000;
        for i in 0..=n {
            let x = 4.6 * i as f64 / n as f64;
            let e = libm::erfc(x);
            let rel = (erfc_bounded_f64(x) - e).abs() / e / f64::EPSILON;
            worst = worst.max(rel / (4.0 + 0.5 * x * x));
            worst_plain = worst_plain.max(rel);
        }
        std::println!(
            "erfc_bounded_f64: max relative error {worst_plain} ε, {worst} of the allowance"
        );
        assert!(worst <= 1.0, "max error / allowance {worst}");
        assert!(ulps(erfc_bounded_f64(0.0), 1.0) <= 2.0);
        let e = libm::erfc(4.5);
        assert!((erfc_bounded_f64(4.5) - e).abs() <= (4.0 + 0.5 * 4.5 * 4.5) * f64::EPSILON * e);
        assert_eq!(erfc_bounded_f64(-1.0), erfc_bounded_f64(0.0));
        assert_eq!(erfc_bounded_f64(10.0), erfc_bounded_f64(4.6));
        assert!(erfc_bounded_f64(f64::NAN).is_nan());
    }
}

//! f64 kernels for the hot loops of the f64 instantiation: eˣ on the bounded range of the
//! integrands ([`exp_bounded_f64`], and e^{−z} from z = v² by [`exp_neg_f64`]), the scaled
//! complementary error function of the tail integrals ([`erfcx_bounded_f64`]) and sin/cos
//! on the clamped angle range ([`sin_cos_f64`]). All are branch-free on their fast range
//! (so the compiler can keep them inline and evaluate two of them in one SSE2 register;
//! the pair versions are written once over [`Lanes`], one f64 or two side by side) and
//! fall back to libm elsewhere.

/// 2^(j/256) for j = 0…255, each the f64 nearest to the exact value (computed in 50-digit
/// arithmetic; checked against libm's `exp2` in the tests).
/// (Entry 128 is √2: written as a digit string like the rest.)
#[rustfmt::skip]
#[allow(clippy::approx_constant)]
static EXP2_J_256: [f64; 256] = [
    1.0, 1.0027112750502025, 1.0054299011128027, 1.0081558981184175,
    1.0108892860517005, 1.0136300849514894, 1.016378314910953, 1.019133996077738,
    1.0218971486541166, 1.0246677928971357, 1.0274459491187637, 1.030231637686041,
    1.0330248790212284, 1.0358256936019572, 1.0386341019613787, 1.041450124688316,
    1.0442737824274138, 1.0471050958792898, 1.0499440858006872, 1.0527907730046264,
    1.0556451783605572, 1.0585073227945128, 1.061377227289262, 1.0642549128844645,
    1.0671404006768237, 1.0700337118202419, 1.0729348675259756, 1.075843889062791,
    1.0787607977571199, 1.0816856149932152, 1.0846183622133092, 1.0875590609177697,
    1.0905077326652577, 1.0934643990728858, 1.0964290818163769, 1.099401802630222,
    1.102382583307841, 1.1053714457017412, 1.1083684117236787, 1.1113735033448175,
    1.1143867425958924, 1.1174081515673693, 1.1204377524096067, 1.12347556733302,
    1.1265216186082418, 1.129575928566288, 1.1326385195987192, 1.1357094141578055,
    1.1387886347566916, 1.1418762039695616, 1.1449721444318042, 1.148076478840179,
    1.1511892299529827, 1.154310420590216, 1.1574400736337511, 1.1605782120274988,
    1.1637248587775775, 1.1668800369524817, 1.1700437696832502, 1.1732160801636373,
    1.1763969916502812, 1.1795865274628758, 1.182784710984341, 1.1859915656609938,
    1.189207115002721, 1.1924313825831512, 1.1956643920398273, 1.1989061670743806,
    1.202156731452703, 1.2054161090051239, 1.2086843236265816, 1.2119613992768012,
    1.215247359980469, 1.2185422298274085, 1.2218460329727576, 1.2251587936371455,
    1.22848053610687, 1.2318112847340759, 1.2351510639369334, 1.2384998981998165,
    1.241857812073484, 1.245224830175258, 1.2486009771892048, 1.2519862778663162,
    1.255380757024691, 1.2587844395497165, 1.2621973503942507, 1.2656195145788063,
    1.2690509571917332, 1.2724917033894028, 1.275941778396392, 1.2794012075056693,
    1.2828700160787783, 1.2863482295460256, 1.2898358734066657, 1.2933329732290895,
    1.2968395546510096, 1.3003556433796506, 1.3038812651919358, 1.3074164459346773,
    1.3109612115247644, 1.3145155879493546, 1.318079601266064, 1.3216532776031575,
    1.3252366431597413, 1.3288297242059544, 1.3324325470831615, 1.3360451382041458,
    1.339667524053303, 1.3432997311868353, 1.3469417862329458, 1.3505937158920345,
    1.3542555469368927, 1.3579273062129011, 1.3616090206382248, 1.365300717204012,
    1.3690024229745905, 1.3727141650876684, 1.3764359707545302, 1.380167867260238,
    1.383909881963832, 1.387662042298529, 1.3914243757719262, 1.3951969099662003,
    1.3989796725383112, 1.4027726912202048, 1.4065759938190154, 1.4103896082172707,
    1.4142135623730951, 1.4180478843204152, 1.4218926021691656, 1.4257477441054942,
    1.42961333839197, 1.433489413367789, 1.4373759974489824, 1.4412731191286257,
    1.4451808069770467, 1.449099089642035, 1.4530279958490526, 1.4569675544014438,
    1.460917794180647, 1.4648787441464057, 1.4688504333369818, 1.4728328908693675,
    1.4768261459394993, 1.4808302278224719, 1.4848451658727524, 1.488870989524397,
    1.4929077282912648, 1.4969554117672355, 1.5010140696264256, 1.5050837316234065,
    1.5091644275934228, 1.5132561874526098, 1.5173590411982147, 1.5214730189088146,
    1.5255981507445384, 1.529734466947287, 1.533881997840956, 1.5380407738316568,
    1.5422108254079407, 1.5463921831410214, 1.550584877685, 1.5547889397770887,
    1.559004400237837, 1.5632312899713576, 1.567469639965553, 1.5717194812923414,
    1.5759808451078865, 1.5802537626528246, 1.5845382652524937, 1.588834384317164,
    1.593142151342267, 1.597461597908627, 1.6017927556826934, 1.606135656416771,
    1.6104903319492543, 1.6148568142048607, 1.6192351351948637, 1.6236253270173289,
    1.6280274218573478, 1.632441451987275, 1.6368674497669644, 1.6413054476440063,
    1.645755478153965, 1.6502175739206177, 1.6546917676561943, 1.6591780921616162,
    1.6636765803267364, 1.6681872651305825, 1.6727101796415966, 1.6772453570178785,
    1.681792830507429, 1.6863526334483934, 1.6909247992693053, 1.6955093614893326,
    1.7001063537185235, 1.7047158096580513, 1.709337763100463, 1.713972247929926,
    1.718619298122478, 1.723278947746274, 1.7279512309618377, 1.732636182022311,
    1.7373338352737062, 1.7420442251551564, 1.746767386199169, 1.7515033530318782,
    1.7562521603732995, 1.761013843037584, 1.7657884359332727, 1.7705759740635547,
    1.7753764925265212, 1.7801900265154245, 1.785016611318935, 1.789856282321401,
    1.7947090750031072, 1.7995750249405351, 1.804454167806624, 1.809346539371032,
    1.8142521755003989, 1.8191711121586085, 1.8241033854070534, 1.8290490314048973,
    1.8340080864093424, 1.8389805867758937, 1.843966568958626, 1.8489660695104508,
    1.8539791250833855, 1.8590057724288205, 1.864046048397789, 1.8690999899412386,
    1.8741676341103, 1.8792490180565602, 1.8843441790323345, 1.8894531543909392,
    1.8945759815869656, 1.8997126981765553, 1.9048633418176741, 1.9100279502703899,
    1.9152065613971474, 1.9203992131630474, 1.925605943636125, 1.930826790987627,
    1.9360617934922943, 1.9413109895286405, 1.9465744175792332, 1.9518521162309783,
    1.9571441241754002, 1.9624504802089273, 1.9677712232331759, 1.9731063922552343,
    1.978456026387951, 1.9838201648502194, 1.9891988469672663, 1.9945921121709402,
];

/// q(r) ≈ (eʳ − 1)/r on |r| ≤ ln 2/512: its degree-3 Chebyshev interpolant, fitted in 50-digit
/// arithmetic (relative error of 1 + r·q below 4.9e-18 with the coefficients rounded to f64).
const EXP_Q: [f64; 4] = [
    0.999_999_999_999_996_4,
    0.499_999_999_999_999_4,
    0.166_666_681_939_886_37,
    0.041_666_669_212_203_26,
];

/// eˣ for x ∈ [−87, 0] in f64, branch-free; the f64 [`crate::Real::exp_bounded`].
///
/// x below −87 is taken as −87 (the trait's contract); NaN gives NaN. Arguments up to 709
/// also give finite results (not used by the kernels).
///
/// x = (256·m + j)·ln 2/256 + r with n = 256m + j = round(256x/ln 2) (by adding and
/// subtracting 1.5·2⁵², which leaves n in the low mantissa bits), j ∈ [0, 255] and
/// |r| ≤ ln 2/512; r by a two-part Cody–Waite split ln 2/256 = L1 + L2, L1 cut to 32
/// significant bits (so n·L1 is exact for |n| < 2²¹ and x − n·L1 is exact), L2 the rest
/// rounded to f64 (residual 4.5e-29·|n|, far below an ulp of r). Then
/// eˣ = 2ᵐ · 2^(j/256) · eʳ with 2^(j/256) from a table and eʳ = 1 + r·q(r), q the degree-3
/// Chebyshev interpolant of (eʳ − 1)/r on |r| ≤ ln 2/512 (fitted in 50-digit arithmetic):
/// relative error of 1 + r·q below 4.9e-18 with the coefficients rounded to f64. The
/// result is formed as T + T·(r·q) with T = 2ᵐ·2^(j/256) exact from the exponent bits, so
/// the error is the table entry's rounding (≤ ½ ulp) plus the final addition's (≤ ½ ulp)
/// plus terms of order |r| ulp: within 1.01 ulp of the exact value, within 2 ulp of libm's
/// `exp` (measured in the tests).
#[inline(always)]
pub fn exp_bounded_f64(x: f64) -> f64 {
    const N_LN2: f64 = 369.329_930_467_574_6; // 256/ln 2
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²
    const L1: f64 = 0.002_707_606_173_316_89; // ln 2/256 to 32 bits
    const L2: f64 = 7.453_964_567_463_233e-13; // ln 2/256 − L1
    const Q: [f64; 4] = EXP_Q;
    // NaN fails the comparison and stays NaN (it then propagates through r).
    let x = if x < -87.0 { -87.0 } else { x };
    let t = x * N_LN2 + MAGIC;
    let n = t.to_bits().wrapping_sub(MAGIC.to_bits());
    let nf = t - MAGIC;
    let r = (x - nf * L1) - nf * L2;
    let q = Q[0] + r * (Q[1] + r * (Q[2] + r * Q[3]));
    // 2ᵐ·2^(j/256): m = ⌊n/256⌋ added to the table entry's exponent (n & !255 = 256m in
    // two's complement, so (n & !255) << 44 = m << 52); m ≥ −126 keeps it normal.
    let scale = f64::from_bits(
        EXP2_J_256[(n & 0xff) as usize]
            .to_bits()
            .wrapping_add((n & !0xff) << 44),
    );
    scale + scale * (r * q)
}

/// e^{−z} for z ∈ [0, 700] in f64, branch-free and without a clamp: the Gaussian factor
/// e^{−v²} of the kernels' integrands, given z = v² (v ≤ 4.6 there, so z ≤ 21.2).
///
/// Outside [0, 700] the result is unspecified (finite or NaN, never a panic); NaN gives NaN.
/// The same scheme as [`exp_bounded_f64`] with a one-part reduction: n = round(−256z/ln 2)
/// (by adding and subtracting 1.5·2⁵²), r = n·(−L) − z with L = ln 2/256 rounded to f64,
/// so |r| ≤ ln 2/512 up to rounding, and e^{−z} = 2^(n/256)·eʳ with 2^(n/256) from the
/// exponent bits and the table, eʳ = 1 + r·q(r) (the same degree-3 interpolant). Error of
/// r: L's rounding (relative 3.3e-17) times |n|·L ≤ z + L plus the rounding of the
/// product n·L (at most ½ ulp of z + L); the subtraction is exact (Sterbenz: n·L and z
/// are within L/2 of each other). Both together are below (z + L)·ε in absolute terms,
/// i.e. a relative error of at most (z + L)·ε in the result, ε = 2⁻⁵²; the rest as in
/// [`exp_bounded_f64`] (≤ 1.01 ulp). The input z = v² itself carries a rounding of z·ε/2,
/// which e^{−z} turns into the same kind of relative error, so the shorter reduction costs
/// no more than the squaring already did. Accuracy: relative error within (2 + z)·ε of
/// libm's `exp(−z)` (measured in the tests).
#[inline(always)]
pub fn exp_neg_f64(z: f64) -> f64 {
    const N_LN2: f64 = 369.329_930_467_574_6; // 256/ln 2
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²
    const L: f64 = 0.002_707_606_174_062_286_3; // ln 2/256
                                                // The top 12 bits of an f64 (sign and exponent).
    const EXP_BITS: u64 = 0xfff0_0000_0000_0000;
    let q = EXP_Q;
    let t = z * -N_LN2 + MAGIC;
    let nf = t - MAGIC;
    let r = nf * -L - z;
    let p = q[0] + r * (q[1] + r * (q[2] + r * q[3]));
    // t's bits are MAGIC's plus n (two's complement, same binade), and MAGIC's low 52 bits
    // shifted left by 44 vanish: the low byte of the bits is j = n mod 256, and bits << 44
    // are n << 44 = m << 52 + j << 44 (n = 256m + j), whose top 12 bits are m << 52.
    let b = t.to_bits();
    let scale = f64::from_bits(
        EXP2_J_256[(b & 0xff) as usize]
            .to_bits()
            .wrapping_add((b << 44) & EXP_BITS),
    );
    scale + scale * (r * p)
}

/// [`exp_neg_f64`] of two arguments, lane by lane the same values (each step serves both
/// lanes where the target has two-lane f64 SIMD).
#[inline(always)]
pub fn exp_neg2_f64(z: [f64; 2]) -> [f64; 2] {
    if BARE_METAL {
        // Soft f64: one out-of-line copy (smaller, the same values).
        [exp_neg_once(z[0]), exp_neg_once(z[1])]
    } else {
        [exp_neg_f64(z[0]), exp_neg_f64(z[1])]
    }
}

/// Bare-metal devices (`target_os = "none"`, soft f64): the pair kernels call one
/// out-of-line copy of the scalar kernel instead of inlining two (code size; the same
/// values). A constant, so the branch not taken is compiled away.
const BARE_METAL: bool = cfg!(target_os = "none");

/// [`exp_neg_f64`], not inlined.
#[inline(never)]
fn exp_neg_once(z: f64) -> f64 {
    exp_neg_f64(z)
}

/// The complementary error function for x ∈ [0, 4.6] in f64, branch-free; the f64
/// [`crate::Real::erfc_bounded`].
///
/// Outside [0, 4.6], x is taken as the nearer end; NaN gives NaN. erfc x = e^{−x²} times
/// [`erfcx_bounded_f64`]'s polynomial, e^{−x²} by [`exp_bounded_f64`], from x² rounded to
/// f64: that rounding (relative ε/2) becomes a relative error of up to x²·ε/2 in the result
/// (libm avoids it by splitting x; here it is at most 1.2e-15 on [0, 4.6]). Accuracy:
/// relative error within (6 + x²/2)·ε of libm's `erfc` (measured in the tests), ε = 2⁻⁵².
#[inline(always)]
pub fn erfc_bounded_f64(x: f64) -> f64 {
    // NaN fails both comparisons and stays NaN.
    let x = if x < 0.0 { 0.0 } else { x };
    let x = if x > 4.6 { 4.6 } else { x };
    exp_bounded_f64(-(x * x)) * erfcx_poly(x)
}

/// The scaled complementary error function e^{x²} erfc x for x ∈ [0, 4.6] in f64,
/// branch-free and without a clamp; the f64 [`crate::Real::erfcx_bounded`].
///
/// Outside [0, 4.6] the result is unspecified (finite or NaN, never a panic); NaN gives
/// NaN. The polynomial part of [`erfc_bounded_f64`] alone (which see), so without the
/// rounding of x² in e^{−x²}: relative error within 6ε of e^{x²} erfc x (measured in the
/// tests against libm's `erfc` times `exp`, whose own error x²ε/2 is added there).
#[inline(always)]
pub fn erfcx_bounded_f64(x: f64) -> f64 {
    erfcx_poly(x)
}

/// [`erfcx_bounded_f64`] of two arguments, lane by lane the same values (the two side by
/// side: each step of the polynomial serves both lanes).
#[inline(always)]
pub fn erfcx2_bounded_f64(x: [f64; 2]) -> [f64; 2] {
    if BARE_METAL {
        [erfcx_once(x[0]), erfcx_once(x[1])]
    } else {
        erfcx_poly(F2::new(x)).get()
    }
}

/// [`erfcx_bounded_f64`], not inlined ([`BARE_METAL`] devices).
#[inline(never)]
fn erfcx_once(x: f64) -> f64 {
    erfcx_poly(x)
}

/// Arithmetic on one f64 or on two side by side ([`F2`]), with the same IEEE operations
/// per lane, so that a function written once over it gives the pair version bit for bit
/// the scalar values on every target (and SIMD where the target has two f64 lanes).
trait Lanes:
    Copy
    + core::ops::Add<Output = Self>
    + core::ops::Sub<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::Div<Output = Self>
{
    /// The constant in every lane.
    fn splat(x: f64) -> Self;
    /// Lane by lane `odd` where k ≠ 0 and `even` where k = 0 (NaN counts as ≠ 0), without a
    /// branch.
    fn pick_nonzero(k: Self, odd: Self, even: Self) -> Self;
}

/// [`Lanes::pick_nonzero`] of one lane, as a bit mask.
#[inline(always)]
fn pick1(k: f64, odd: f64, even: f64) -> f64 {
    let m = if k == 0.0 { 0 } else { u64::MAX };
    f64::from_bits((odd.to_bits() & m) | (even.to_bits() & !m))
}

impl Lanes for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn pick_nonzero(k: Self, odd: Self, even: Self) -> Self {
        pick1(k, odd, even)
    }
}

/// Two f64 lanes: one SSE2 register on x86-64 (the `wide` crate's `f64x2`, whose
/// operations are the packed IEEE instructions), a pair of scalars elsewhere.
#[derive(Clone, Copy, Debug)]
struct F2(Pair);

#[cfg(target_arch = "x86_64")]
type Pair = wide::f64x2;
#[cfg(not(target_arch = "x86_64"))]
type Pair = [f64; 2];

impl F2 {
    #[inline(always)]
    fn new(x: [f64; 2]) -> Self {
        #[cfg(target_arch = "x86_64")]
        return F2(wide::f64x2::from(x));
        #[cfg(not(target_arch = "x86_64"))]
        return F2(x);
    }
    #[inline(always)]
    fn get(self) -> [f64; 2] {
        #[cfg(target_arch = "x86_64")]
        return self.0.to_array();
        #[cfg(not(target_arch = "x86_64"))]
        return self.0;
    }
}

macro_rules! f2_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl core::ops::$tr for F2 {
            type Output = F2;
            #[inline(always)]
            fn $f(self, o: F2) -> F2 {
                #[cfg(target_arch = "x86_64")]
                return F2(self.0 $op o.0);
                #[cfg(not(target_arch = "x86_64"))]
                return F2([self.0[0] $op o.0[0], self.0[1] $op o.0[1]]);
            }
        }
    };
}
f2_op!(Add, add, +);
f2_op!(Sub, sub, -);
f2_op!(Mul, mul, *);
f2_op!(Div, div, /);

impl Lanes for F2 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        F2::new([x, x])
    }
    #[inline(always)]
    fn pick_nonzero(k: Self, odd: Self, even: Self) -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            use wide::CmpNe;
            F2(k.0.cmp_ne(wide::f64x2::ZERO).blend(odd.0, even.0))
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let (k, o, e) = (k.0, odd.0, even.0);
            F2([pick1(k[0], o[0], e[0]), pick1(k[1], o[1], e[1])])
        }
    }
}

/// e^{x²} erfc x for x ∈ [0, 4.6] as t·q(t), t = 1/(1 + x/2) ∈ [0.303, 1].
///
/// As in [`super::erfc_f32`], q(t) = e^{x²} erfc x · (1 + x/2) is smooth in t, and here q
/// is its degree-20 Chebyshev interpolant on that interval (fitted in 60-digit arithmetic,
/// written out in powers of s = t − 0.6515…, the interval's midpoint, where the sum of the
/// terms' magnitudes is at most 2.6 times the value, so the evaluation loses no more than a
/// few ulp): relative error 2.8e-18 with exact coefficients, 1.1e-16 with the coefficients
/// rounded to f64.
#[inline(always)]
fn erfcx_poly<V: Lanes>(x: V) -> V {
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
    let c = V::splat;
    let t = c(1.0) / (c(1.0) + c(0.5) * x);
    let s = t - c(TC);
    // q = Σ Qᵢ sⁱ as four interleaved Horner chains in s⁴ (Qᵢ with i ≡ j mod 4, times sʲ):
    // a quarter of the dependent steps of one chain. Chain 0 starts at Q₂₀ s⁴ + Q₁₆,
    // chains 1–3 at Q₁₇, Q₁₈, Q₁₉.
    let s2 = s * s;
    let s4 = s2 * s2;
    let mut h = [c(Q[20]) * s4 + c(Q[16]), c(Q[17]), c(Q[18]), c(Q[19])];
    // Chunks i = 3, 2, 1, 0 of Q[0..16] (no indexing: no bounds check left in size-optimised
    // builds).
    for q in Q[..16].chunks_exact(4).rev() {
        for (hj, &qj) in h.iter_mut().zip(q) {
            *hj = *hj * s4 + c(qj);
        }
    }
    let q = (h[0] + s * h[1]) + s2 * (h[2] + s * h[3]);
    t * q
}

/// sin x and cos x in f64; for |x| ≤ π/2 (the clamped angles of the kernels) by a short
/// branch-free evaluation, beyond that by libm's `sincos`. NaN gives NaN.
///
/// For |x| ≤ 1.6 (a little beyond π/2): k = round(2x/π) ∈ {−1, 0, 1} (ties to even) and
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
    // (−1.6..=1.6).contains rather than f64::abs, which `core` has only since Rust 1.84.
    if !(-1.6..=1.6).contains(&x) {
        return libm::sincos(x);
    }
    sin_cos_short(x)
}

/// [`sin_cos_f64`] of two arguments, lane by lane the same values; when both lie in
/// [−1.6, 1.6] the two evaluations run side by side (each step of the polynomials serves
/// both lanes). Returns ([sin x₀, sin x₁], [cos x₀, cos x₁]).
#[inline]
pub fn sin_cos2_f64(x: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    if !((-1.6..=1.6).contains(&x[0]) && (-1.6..=1.6).contains(&x[1])) {
        let (s0, c0) = sin_cos_f64(x[0]);
        let (s1, c1) = sin_cos_f64(x[1]);
        return ([s0, s1], [c0, c1]);
    }
    let (s, c) = sin_cos_short(F2::new(x));
    (s.get(), c.get())
}

/// The body of [`sin_cos_f64`] for |x| ≤ 1.6 (always inlined, so that two calls can share
/// SIMD registers).
#[inline(always)]
fn sin_cos_short<V: Lanes>(x: V) -> (V, V) {
    const FRAC_2_PI: f64 = core::f64::consts::FRAC_2_PI;
    const P1: f64 = core::f64::consts::FRAC_PI_2;
    const P2: f64 = 6.123_233_995_736_766e-17; // π/2 − P1
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²

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
    let l = V::splat;
    // k = round(2x/π) by adding and subtracting 1.5·2⁵² (|2x/π| < 1.02 here).
    let k = (x * l(FRAC_2_PI) + l(MAGIC)) - l(MAGIC);
    let r = (x - k * l(P1)) - k * l(P2);
    let r2 = r * r;
    let (mut ps, mut pc) = (l(S[7]), l(K[7]));
    for j in (0..7).rev() {
        ps = ps * r2 + l(S[j]);
        pc = pc * r2 + l(K[j]);
    }
    let s = r + r * (r2 * ps);
    let c = l(1.0) + r2 * pc;
    // The quadrant swap as a selection rather than a branch (the angles are not
    // predictable); −k·s as (0 − k)·s, the same value.
    (
        V::pick_nonzero(k, k * c, s),
        V::pick_nonzero(k, (l(0.0) - k) * s, c),
    )
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{
        erfc_bounded_f64, erfcx2_bounded_f64, erfcx_bounded_f64, exp_bounded_f64, exp_neg2_f64,
        exp_neg_f64, sin_cos2_f64, sin_cos_f64,
    };

    /// The distance of `got` from `want` in units of the ulp of `want` (2^(e−52) for
    /// |want| ∈ [2^e, 2^(e+1))).
    fn ulps(got: f64, want: f64) -> f64 {
        if got == want {
            return 0.0;
        }
        let e = libm::floor(libm::log2(want.abs()));
        (got - want).abs() / libm::exp2(e - 52.0)
    }

    /// The table of 2^(j/256) against libm's `exp2` (within 1 ulp of exact): each entry is
    /// the nearest f64, so it may differ from libm by at most 1 ulp; and the entries rise
    /// by the factor 2^(1/256) each (to 2 ulp).
    #[test]
    fn exp2_table_against_libm() {
        for (j, &t) in super::EXP2_J_256.iter().enumerate() {
            assert!(ulps(t, libm::exp2(j as f64 / 256.0)) <= 1.0, "j={j}");
            if j > 0 {
                let ratio = t / super::EXP2_J_256[j - 1];
                assert!(
                    (ratio - libm::exp2(1.0 / 256.0)).abs() <= 4.0 * f64::EPSILON,
                    "j={j}"
                );
            }
        }
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
        // Around the reduction's switch points x = (n + ½) ln 2/256, where |r| is largest.
        for k in (0..32_128).step_by(7) {
            let x0 = -(k as f64 + 0.5) * core::f64::consts::LN_2 / 256.0;
            let mut x = x0;
            for _ in 0..8 {
                worst = worst.max(ulps(exp_bounded_f64(x), libm::exp(x)));
                x = libm::nextafter(x, 0.0);
            }
            let mut x = x0;
            for _ in 0..8 {
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

    /// e^{−z} with the one-part reduction against libm's `exp` (within 1 ulp of exact):
    /// relative error within (2 + z)·ε (z·ε from the reduction, see the docs; 1 ε for the
    /// table, the polynomial and the last addition; 1 ε for libm) over a dense grid of the
    /// kernels' range z = v², v ∈ [0, 4.6], around the reduction's switch points, and
    /// sparsely up to 700; the pair version lane by lane bit for bit the scalar one; NaN.
    #[test]
    fn exp_neg_f64_against_libm() {
        let mut worst = 0f64;
        let mut check = |z: f64| {
            let e = libm::exp(-z);
            let got = exp_neg_f64(z);
            let rel = (got - e).abs() / e / f64::EPSILON;
            worst = worst.max(rel / (2.0 + z));
            let other = 21.16 - z;
            let pair = exp_neg2_f64([z, other]);
            assert_eq!(pair[0].to_bits(), got.to_bits(), "z={z}");
            assert_eq!(pair[1].to_bits(), exp_neg_f64(other).to_bits(), "z={other}");
        };
        let n = 4_000_000;
        for i in 0..=n {
            let v = 4.6 * i as f64 / n as f64;
            check(v * v);
        }
        for i in 0..=1_000_000 {
            check(21.16 * i as f64 / 1e6);
        }
        // Around the switch points z = (n + ½) ln 2/256, where |r| is largest.
        for k in (0..7_900).step_by(3) {
            let z0 = (k as f64 + 0.5) * core::f64::consts::LN_2 / 256.0;
            let (mut a, mut b) = (z0, z0);
            for _ in 0..8 {
                check(a);
                check(b);
                a = libm::nextafter(a, 0.0);
                b = libm::nextafter(b, 1e3);
            }
        }
        for i in 0..=100_000 {
            check(700.0 * i as f64 / 1e5);
        }
        for z in [0.0, -0.0, 5e-324, 1e-300, 1e-17, 1e-9] {
            check(z);
        }
        std::println!("exp_neg_f64: max error {worst} of the allowance (2 + z)ε");
        assert!(worst <= 1.0, "max error / allowance {worst}");
        assert_eq!(exp_neg_f64(0.0), 1.0);
        assert!(exp_neg_f64(f64::NAN).is_nan());
        // Outside the range: no panic (values unspecified).
        for z in [-1e3, 1e4, f64::INFINITY, f64::NEG_INFINITY, f64::MAX] {
            let _ = exp_neg_f64(z);
        }
    }

    /// The scaled complementary error function against libm's `erfc(x)·exp(x²)`: relative
    /// error within (9 + x²/2)·ε over a dense grid of [0, 4.6] (6ε for the polynomial as in
    /// [`erfc_bounded_f64`]; for the reference, x²ε/2 from the rounding of x² in exp(x²), and
    /// 1 ε each for libm's exp and erfc and the product); the pair version lane by lane bit
    /// for bit the scalar one; NaN.
    #[test]
    fn erfcx_bounded_f64_against_libm() {
        let mut worst = 0f64;
        let n = 2_000_000;
        for i in 0..=n {
            let x = 4.6 * i as f64 / n as f64;
            let e = libm::erfc(x) * libm::exp(x * x);
            let got = erfcx_bounded_f64(x);
            let rel = (got - e).abs() / e / f64::EPSILON;
            worst = worst.max(rel / (9.0 + 0.5 * x * x));
            // The pair version, lane by lane bit for bit.
            let other = 4.6 - x;
            let pair = erfcx2_bounded_f64([x, other]);
            assert_eq!(pair[0].to_bits(), got.to_bits(), "x={x}");
            assert_eq!(pair[1].to_bits(), erfcx_bounded_f64(other).to_bits());
        }
        std::println!("erfcx_bounded_f64: max error {worst} of the allowance");
        assert!(worst <= 1.0, "max error / allowance {worst}");
        assert!(erfcx_bounded_f64(f64::NAN).is_nan());
        for x in [-1e3, 10.0, f64::INFINITY] {
            let _ = erfcx_bounded_f64(x);
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

    /// The pair version, lane by lane bit for bit equal to [`sin_cos_f64`] (which is
    /// checked against libm above): both lanes on the short path, one or both beyond it,
    /// NaN, on a grid where the two lanes run at different paces.
    #[test]
    fn sin_cos2_f64_is_two_sin_cos_f64() {
        let mut xs: std::vec::Vec<f64> = (-2000..=2000).map(|i| i as f64 * 1.7e-3).collect();
        xs.extend([0.0, -0.0, 1.6, -1.6, 3.0, f64::NAN, 1e300]);
        xs.extend([
            core::f64::consts::FRAC_PI_2,
            f64::from_bits(1.6f64.to_bits() + 1),
            -f64::from_bits(1.6f64.to_bits() + 1),
        ]);
        let n = xs.len();
        for (j, &a) in xs.iter().enumerate() {
            for b in [xs[(j * 7 + 11) % n], xs[n - 1 - j], a] {
                let (s, c) = sin_cos2_f64([a, b]);
                for (k, x) in [a, b].into_iter().enumerate() {
                    let (s1, c1) = sin_cos_f64(x);
                    assert!(
                        (s[k].to_bits() == s1.to_bits() || (s[k].is_nan() && s1.is_nan()))
                            && (c[k].to_bits() == c1.to_bits() || (c[k].is_nan() && c1.is_nan())),
                        "lane {k} of ({a}, {b})"
                    );
                }
            }
        }
    }

    /// The f64 bounded complementary error function against libm's `erfc` (within 1 ulp of
    /// exact on this range): relative error within (6 + x²/2)·ε over a dense grid of
    /// [0, 4.6] and at the ends (x²ε/2 from the rounding of x² in e^{−x²}, 6ε for the
    /// polynomial, its coefficients, t, the products and libm's own error); clamping
    /// outside; NaN.
    #[test]
    fn erfc_bounded_f64_against_libm() {
        let (mut worst, mut worst_plain) = (0f64, 0f64);
        let n = 2_000_000;
        for i in 0..=n {
            let x = 4.6 * i as f64 / n as f64;
            let e = libm::erfc(x);
            let rel = (erfc_bounded_f64(x) - e).abs() / e / f64::EPSILON;
            worst = worst.max(rel / (6.0 + 0.5 * x * x));
            worst_plain = worst_plain.max(rel);
        }
        std::println!(
            "erfc_bounded_f64: max relative error {worst_plain} ε, {worst} of the allowance"
        );
        assert!(worst <= 1.0, "max error / allowance {worst}");
        assert!(ulps(erfc_bounded_f64(0.0), 1.0) <= 2.0);
        let e = libm::erfc(4.5);
        assert!((erfc_bounded_f64(4.5) - e).abs() <= (6.0 + 0.5 * 4.5 * 4.5) * f64::EPSILON * e);
        assert_eq!(erfc_bounded_f64(-1.0), erfc_bounded_f64(0.0));
        assert_eq!(erfc_bounded_f64(10.0), erfc_bounded_f64(4.6));
        assert!(erfc_bounded_f64(f64::NAN).is_nan());
    }
}

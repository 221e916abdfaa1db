//! High-accuracy reference quadrature and reference kernels (f64, std).

use std::f64::consts::{FRAC_PI_2, PI};

/// Gauss–Kronrod 7–15 nodes (Kronrod abscissae; Gauss nodes are every other one).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_728_8,
];
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

fn gk15(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[7] * fc;
    let mut g = WG[3] * fc;
    for j in 0..7 {
        let x = h * XGK[j];
        let s = f(c - x) + f(c + x);
        k += WGK[j] * s;
        if j % 2 == 1 {
            g += WG[j / 2] * s;
        }
    }
    (k * h, ((k - g) * h).abs())
}

fn adapt(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
    let (v, e) = gk15(f, a, b);
    // Stop at the tolerance, at round-off level, or at depth 40 (2^40 splits is never reached
    // for the smooth integrands here; the cap only protects against a pathological input).
    if e <= tol || e <= 1e-15 * v.abs() || depth > 40 || (b - a).abs() < 1e-14 {
        return v;
    }
    let m = 0.5 * (a + b);
    adapt(f, a, m, tol * 0.5, depth + 1) + adapt(f, m, b, tol * 0.5, depth + 1)
}

/// ∫ₐᵇ f with adaptive Gauss–Kronrod to absolute tolerance `tol`, splitting first at the
/// given interior break points (those outside (a, b) are ignored).
pub fn integrate(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, breaks: &[f64], tol: f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let mut pts = vec![a];
    let mut bs: Vec<f64> = breaks.iter().copied().filter(|&x| x > a && x < b).collect();
    bs.sort_by(|x, y| x.partial_cmp(y).unwrap());
    pts.extend(bs);
    pts.push(b);
    let n = (pts.len() - 1) as f64;
    pts.windows(2)
        .map(|w| adapt(&mut f, w[0], w[1], tol / n, 0))
        .sum()
}

/// Unnormalised eq 5 integrand exp(−tan²γ/(2σ²))/cos³γ.
fn q(gamma: f64, sigma: f64) -> f64 {
    let c = gamma.cos();
    if c <= 0.0 {
        return 0.0;
    }
    let t = gamma.tan();
    (-(t * t) / (2.0 * sigma * sigma)).exp() / (c * c * c)
}

fn breaks(sigma: f64) -> Vec<f64> {
    let mut v = vec![0.0];
    for k in [0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 9.0] {
        let g = (k * sigma).atan();
        v.push(g);
        v.push(-g);
    }
    v
}

/// The reference slope density of one σ: the normaliser by adaptive quadrature over
/// [−π/2, π/2].
#[derive(Clone, Debug)]
pub struct RefDensity {
    pub sigma: f64,
    /// ∫ q dγ over [−π/2, π/2].
    pub mass: f64,
    br: Vec<f64>,
}

impl RefDensity {
    pub fn new(sigma: f64) -> Self {
        let br = breaks(sigma);
        let mass = integrate(|g| q(g, sigma), -FRAC_PI_2, FRAC_PI_2, &br, 1e-15);
        Self { sigma, mass, br }
    }
    /// C(σ) = 2πσ²/mass (eq 2 with ∫p dγ = 1).
    pub fn c(&self) -> f64 {
        2.0 * PI * self.sigma * self.sigma / self.mass
    }
    /// p(γ).
    pub fn pdf(&self, g: f64) -> f64 {
        q(g, self.sigma) / self.mass
    }
    /// ∫ₐᵇ p · w dγ.
    pub fn integral(&self, a: f64, b: f64, w: impl Fn(f64) -> f64) -> f64 {
        integrate(
            |g| q(g, self.sigma) * w(g),
            a,
            b,
            &self.br,
            1e-14 * self.mass,
        ) / self.mass
    }
    /// M(θ, a) straight from docs/conventions.md §3 (eqs 6–11 with r = eq 9 × cos θ).
    pub fn passing(&self, theta: f64, a: f64) -> f64 {
        if theta == 0.0 {
            return 1.0;
        }
        let lo = (FRAC_PI_2 - theta).clamp(-FRAC_PI_2, FRAC_PI_2);
        let hi = (PI - 2.0 * theta + a).clamp(-FRAC_PI_2, FRAC_PI_2);
        // ∫_{−π/2}^{lo} p = 1 − ∫_{lo}^{π/2} p (better conditioned for small tails).
        let full = 1.0 - self.integral(lo, FRAC_PI_2, |_| 1.0);
        if hi <= lo {
            return full;
        }
        let cb = (theta - a).cos();
        full + self.integral(lo, hi, |g| (cb + (g + theta).cos()) / cb)
    }
    /// (GM, GS, G) in the reciprocal convention (docs/conventions.md §4).
    pub fn g_reciprocal(&self, ti: f64, tr: f64) -> (f64, f64, f64) {
        let alpha = 0.5 * (tr - ti);
        let gm = if tr == 0.0 {
            1.0
        } else {
            self.passing(tr.abs(), tr.signum() * alpha)
        };
        let gs = self.passing(ti, -alpha);
        (gm, gs, gm.min(gs))
    }
    /// (GM, GS, G) with eq 12 as printed.
    pub fn g_printed(&self, ti: f64, tr: f64) -> (f64, f64, f64) {
        let alpha = 0.5 * (tr - ti);
        let gm = if tr > 0.0 {
            self.passing(tr, alpha)
        } else {
            1.0
        };
        let gs = self.passing(ti, alpha);
        (gm, gs, gm.min(gs))
    }
}

/// Smith–Beckmann Λ by direct integration of its definition
/// Λ(wo) = (1/cos θo) ∫ (wo·m − ... ) — here through the slope form: Λ = ∫_{q>μ} (q − μ) P(q) dq / μ
/// with P the 1-D marginal slope density (Gaussian with variance m²/2) and μ = cot θ.
pub fn lambda_beckmann_ref(theta: f64, m: f64) -> f64 {
    if theta <= 0.0 {
        return 0.0;
    }
    let mu = 1.0 / theta.tan();
    let s = m / 2f64.sqrt();
    let pdf = |x: f64| (-(x * x) / (2.0 * s * s)).exp() / (s * (2.0 * PI).sqrt());
    let upper = mu.max(0.0) + 40.0 * s;
    integrate(
        |x| (x - mu) * pdf(x),
        mu,
        upper,
        &[mu + s, mu + 3.0 * s],
        1e-15,
    ) / mu
}

/// The GGX split sum (A, B) with height-correlated Smith G2 = 1/(1 + Λ(l) + Λ(v)),
/// Λ(w) = (√(1 + α² tan²θw) − 1)/2, F_c = (1 − v·h)⁵, by nested adaptive Gauss–Kronrod in
/// the half vector, independent of the kernels' visible-normal coordinates: the polar
/// variable is q = α²/(α² + tan²θh) (1 − q is the GGX CDF of D cos θh, so
/// D cos θh dωh = dq dφ/(2π) and the peak of D is flat in q), the azimuth φ ∈ [0, π] from
/// the plane of v (even integrand, factor 2). For each θh the light is above the horizon
/// for cos φ > μ(1 − 2cos²θh)/(2 cos θh sin θv sin θh), so the inner range is cut there in
/// closed form, and the outer range is split where that cut starts and ends
/// (θh = π/4 ∓ θv/2). Integrand per unit dωh: D cos θh · G2 (v·h)/(μ cos θh) · (1 − F_c, F_c).
/// `tol` is the absolute tolerance of the outer integral (the inner ones get tol/100).
pub fn split_sum_ggx(mu: f64, alpha: f64, tol: f64) -> (f64, f64) {
    let sv = ((1.0 - mu) * (1.0 + mu)).sqrt();
    let a2 = alpha * alpha;
    let lambda = |z: f64| {
        let t2 = (1.0 - z * z).max(0.0) / (z * z);
        0.5 * ((1.0 + a2 * t2).sqrt() - 1.0)
    };
    let lv = lambda(mu);
    let theta_v = sv.atan2(mu);
    let q_of = |th: f64| {
        let t = th.tan();
        a2 / (a2 + t * t)
    };
    let breaks = [
        q_of(0.25 * PI - 0.5 * theta_v),
        q_of((0.25 * PI + 0.5 * theta_v).min(FRAC_PI_2)),
    ];
    let channel = |which: usize| {
        let inner = |q: f64| {
            // tan²θh = α²(1 − q)/q; cos θh = 1/√(1 + tan²).
            let t2 = a2 * (1.0 - q) / q;
            let ch = 1.0 / (1.0 + t2).sqrt();
            let sh = (t2 / (1.0 + t2)).sqrt();
            let den = 2.0 * ch * sv * sh;
            let c0 = if den > 0.0 {
                mu * (1.0 - 2.0 * ch * ch) / den
            } else if 1.0 - 2.0 * ch * ch < 0.0 {
                -1.0
            } else {
                1.0
            };
            let pmax = c0.clamp(-1.0, 1.0).acos();
            let f = |phi: f64| {
                let vh = sv * sh * phi.cos() + mu * ch;
                let nl = 2.0 * vh * ch - mu;
                if nl <= 0.0 || vh <= 0.0 {
                    return 0.0;
                }
                let g2 = 1.0 / (1.0 + lv + lambda(nl.min(1.0)));
                let fc = (1.0 - vh).powi(5);
                let w = g2 * vh / (mu * ch);
                w * if which == 0 { 1.0 - fc } else { fc }
            };
            integrate(f, 0.0, pmax, &[], tol * 1e-2) / PI
        };
        integrate(inner, 0.0, 1.0, &breaks, tol)
    };
    (channel(0), channel(1))
}

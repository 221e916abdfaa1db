#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware tests: `!(x > 0)` is true for NaN.
//! The GGX and Beckmann split sums (A, B), E = A + B and E_avg by a product rule in polar coordinates of
//! the half vector, with the horizon cut in closed form and a per-texel error estimate.
//!
//! **Integrand.** With v = (sin θv, 0, μ), h = (sin θ cos φ, sin θ sin φ, cos θ) and
//! l = 2(v·h)h − v, the split-sum integrals (module docs of [`crate::split_sum`]) are
//! A, B = ∫ D(h) G2(v, l) (v·h)/μ · (1 − F_c, F_c) dω_h over the lit set n·l > 0, with
//! F_c = (1 − v·h)⁵ and height-correlated Smith G2 (Heitz 2014, "Understanding the
//! masking-shadowing function", eq 99: G2 = 1/(1 + Λ(v) + Λ(l))). In τ = tan θ,
//!
//! ```text
//! n·l = μ (τc − τ)(τ + 1/τc)/(1 + τ²),   τc = (sv c + √(sv² c² + μ²))/μ = e^ζ,
//! ζ = asinh(T c),  T = tan θv,  c = cos φ,  sv = sin θv,
//! ```
//!
//! (n·l = sv sin 2θ c + μ cos 2θ, a quadratic in τ over 1 + τ² whose roots are τc and
//! −1/τc), so each azimuth's lit range is θ < atan τc, and n·l > 0 implies v·h > 0.
//! G2 = 2μ n·l/(n·l R_v + μ R_l), R_w = √(w_z² + α²(1 − w_z²)), is analytic through the
//! cut (it vanishes linearly there).
//!
//! **Radial variable.** τ = α sinh w turns the GGX peak into a fixed bump:
//! D sin θ (v·h) dθ = tanh w sech² w · (sv τ c + μ)/π dw (GGX D = α²(1+τ²)²/(π(α²+τ²)²)),
//! analytic in |Im w| < π/2 for every α, so
//!
//! ```text
//! I(φ) = ∫₀^{wc} tanh w sech² w · 2 (sv τ c + μ) n·l / (π (n·l R_v + μ R_l)) · (1 − F_c, F_c) dw,
//! wc = asinh(τc/α),    (A, B) = 2 ∫₀^π I(φ) dφ.
//! ```
//!
//! Near the cut n·l ≈ μ coth(wc)(wc − w), so G2's branch points n·l = ±iα/√(1 − α²) lie at
//! distance d = α tanh(wc)/(μ√(1 − α²)) from wc: the rows are graded toward wc at that
//! scale (panel ends wc − 2d·6^k) unless a bound on the integrand there shows the zone
//! cannot matter (the bound is then added to the row's estimate).
//!
//! **Beckmann.** The same rule integrates Beckmann lobes (D = e^{−τ²/m²}/(π m² cos⁴θ),
//! Walter et al. 2007, "Microfacet models for refraction", eq 25) with height-correlated
//! Smith G2 = 1/(1 + Λ(v) + Λ(l)) or separable G1(v) G1(l) (Λ from [`Beckmann`]'s
//! [`Isotropic::lambda_cos`]; Heitz 2014 eqs 72, 98–99). Their radial map is
//! linear: with τ = m s, D sin θ (v·h) dθ = D cos⁴θ τ (sv τ c + μ) dτ = s e^{−s²}(sv τ c + μ)/π ds,
//! an entire function of s with the same shape for every m, so
//!
//! ```text
//! I(φ) = ∫₀^{sc} s e^{−s²} (sv τ c + μ) G2 / (π μ) · (1 − F_c, F_c) ds,   sc = min(τc/m, S),
//! ```
//!
//! cut at S = [`BECKMANN_S_MAX`] (the tail beyond, ≤ (S² + 1) e^{−S²}/(2S) · (sv m + μ)/(πμ)
//! per row, is added to the row's estimate). Near the cut n·l ≈ μ(sc − s)/sc, and G2's
//! nearest singularity is the zero of 1 + Λ(v) + Λ(l) (separable: of 1 + Λ(l)): with
//! Λ(l) ≈ 1/(2√π a) − ½ for a = n·l/(m√(1 − n·l²)) → 0, at n·l ≈ −m/(√π(1 + 2Λ(v)))
//! (separable −m/√π), so the rows are graded toward sc at d = sc·m/(√π(1 + 2Λ(v))μ).
//!
//! **Azimuthal variable.** At grazing views τc(φ) jumps by a factor ~4/μ² across
//! |cos φ| < 1/T. The substitution ζ = Z cos ψ, Z = asinh T, ψ ∈ [0, π] (so
//! T cos φ = sinh(Z cos ψ)) makes ln τc = ζ linear and removes the square-root end
//! behaviour of dφ/dζ: dφ/dψ = cosh ζ / √(shc(a) shc(b)), a = 2Z cos²(ψ/2),
//! b = 2Z sin²(ψ/2), shc(x) = sinh(x)/x (from T² − sinh²ζ = sinh a sinh b). ψ = φ when
//! θv → 0. The ψ-integrand is even and 2π-periodic and analytic, so the trapezoid rule
//! converges geometrically and its node sets nest under doubling.
//!
//! **Rule and estimate.** Rows (ψ nodes) at N = 4, 8, 16, … intervals; each row on
//! panels in w by the 15-point Kronrod rule, |K15 − G7| per panel. The estimate per channel
//! is |T_N − T_{N/2}| (the error of the coarser sum, which bounds that of T_N once the
//! sums converge geometrically) + Σ_k W_k Σ_p |K15 − G7|_{k,p} (W_k the trapezoid
//! weights × dφ/dψ) + the zone bounds + 64ε|value|. Refinement is global: while the
//! rows' part exceeds tol/2, the panel with the largest weighted estimate is halved; then,
//! while the outer part exceeds tol/2, N is doubled. Fixed-size storage: at most
//! [`MAX_INTERVALS`] + 1 rows and [`MAX_PANELS`] panels; when either is exhausted the
//! result is returned with its (then larger than `tol`) estimate.

use super::converged::{row_alpha, texel_edges};
use crate::microfacet::{Beckmann, Isotropic};
use crate::quadrature::kronrod::{gk15_combine, gk15_nodes};
use crate::Real;

/// The finest trapezoid level in ψ (intervals on [0, π]).
pub const MAX_INTERVALS: usize = 256;
/// Panels (in w, over all rows) at most.
pub const MAX_PANELS: usize = 640;
/// The first trapezoid level (the second, 2 × this, is the first with an estimate).
pub const FIRST_INTERVALS: usize = 4;
/// The fixed break in w between the GGX bump and its tail.
pub const BUMP_BREAK: f64 = 1.5;
/// Ratio of successive panel lengths graded toward the cut.
pub const GRADE_RATIO: f64 = 6.0;
/// Grading toward the cut stops at this distance (in w).
pub const GRADE_MAX: f64 = 1.0;
/// Below this width α the split sum is its mirror limit (the same as `converged`'s).
pub use super::converged::MIRROR_ALPHA;
/// Where the Beckmann radial variable s = τ/m is cut (module docs): e^{−S²} = 4.5e-19.
pub const BECKMANN_S_MAX: f64 = 6.5;

/// The lobe of a polar integral: the distribution (its radial map) and its Smith masking.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PolarModel<T> {
    /// GGX of width α with height-correlated Smith G2 (module docs).
    GgxCorrelated(T),
    /// Beckmann of width m with height-correlated Smith G2 = 1/(1 + Λ(v) + Λ(l)).
    BeckmannCorrelated(T),
    /// Beckmann of width m with separable Smith G2 = G1(v) G1(l) = 1/((1 + Λ(v))(1 + Λ(l))).
    BeckmannSeparable(T),
}

impl<T: Real> PolarModel<T> {
    /// The distribution width (GGX α, Beckmann m).
    pub fn width(self) -> T {
        match self {
            Self::GgxCorrelated(w) | Self::BeckmannCorrelated(w) | Self::BeckmannSeparable(w) => w,
        }
    }
    fn is_ggx(self) -> bool {
        matches!(self, Self::GgxCorrelated(_))
    }
}

/// A texel's integral: the two channels, their estimates and the work done.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Polar<T> {
    /// (A, B).
    pub value: [T; 2],
    /// Error estimate per channel (module docs).
    pub error: [T; 2],
    /// Integrand evaluations.
    pub evals: u32,
    /// ψ rows used (N + 1 of the final level).
    pub rows: u32,
    /// w panels used.
    pub panels: u32,
}

impl<T: Real> Polar<T> {
    /// A texel answered without integrating (no work).
    pub(crate) fn exact(value: [T; 2], error: [T; 2]) -> Self {
        Self {
            value,
            error,
            evals: 0,
            rows: 0,
            panels: 0,
        }
    }
    /// E = A + B and its estimate (the sum of the channels' estimates).
    pub fn sum(&self) -> (T, T) {
        (self.value[0] + self.value[1], self.error[0] + self.error[1])
    }
}

/// sinh x: the Taylor series to x¹³ for |x| < ½ (relative error < 3e-17), else (eˣ − e⁻ˣ)/2.
fn sinh<T: Real>(x: T) -> T {
    if x.abs() < T::HALF {
        // Horner form of Σ x^{2k}/(2k + 1)!: s ← 1 + x²/((2k)(2k + 1)) · s, k = 6 … 1.
        const INV: [f64; 6] = [
            1.0 / 6.0,
            1.0 / 20.0,
            1.0 / 42.0,
            1.0 / 72.0,
            1.0 / 110.0,
            1.0 / 156.0,
        ];
        let x2 = x * x;
        let mut s = T::ONE;
        for k in INV.iter().rev() {
            s = T::ONE + x2 * T::from_f64(*k) * s;
        }
        x * s
    } else {
        let e = x.exp();
        (e - T::ONE / e) * T::HALF
    }
}

/// (sinh w, cosh w) for w ≥ 0 from one exponential: for w ≥ ½, e = e^{−w} by
/// [`Real::exp_bounded`] (w ≤ 87) and sinh = (1/e − e)/2, cosh = (1/e + e)/2 (no
/// cancellation: e^{−w} ≤ 0.61 e^{w}); below ½ the series of [`sinh`] and cosh = √(1 + sinh²).
#[inline]
fn sinh_cosh<T: Real>(w: T) -> (T, T) {
    if w >= T::HALF && w <= T::from_f64(87.0) {
        let e = (-w).exp_bounded();
        let ie = T::ONE / e;
        ((ie - e) * T::HALF, (ie + e) * T::HALF)
    } else {
        let sh = sinh(w);
        (sh, (T::ONE + sh * sh).sqrt())
    }
}

/// asinh x for x ≥ 0: the series to x⁹ below 0.05, ln(2x) above 1e150, else ln(x + √(1 + x²)).
fn asinh<T: Real>(x: T) -> T {
    if x < T::from_f64(0.05) {
        let x2 = x * x;
        let c = [-1.0 / 6.0, 3.0 / 40.0, -15.0 / 336.0, 105.0 / 3456.0];
        let mut s = T::ZERO;
        for k in c.iter().rev() {
            s = (s + T::from_f64(*k)) * x2;
        }
        x * (T::ONE + s)
    } else if x > T::from_f64(1e150) {
        T::from_f64(core::f64::consts::LN_2) + x.ln()
    } else {
        (x + (T::ONE + x * x).sqrt()).ln()
    }
}

/// shc(x) e^{−x} = (1 − e^{−2x})/(2x) for x ≥ 0 (shc(x) = sinh x / x; 1 at 0).
fn shc_scaled<T: Real>(x: T) -> T {
    if x < T::HALF {
        if x > T::ZERO {
            sinh(x) / x * (-x).exp()
        } else {
            T::ONE
        }
    } else {
        (T::ONE - (-(x + x)).exp()) / (x + x)
    }
}

/// Per-texel constants.
#[derive(Clone, Copy, Debug)]
struct Texel<T> {
    model: PolarModel<T>,
    mu: T,
    sv: T,
    /// The width (GGX α, Beckmann m).
    alpha: T,
    /// Beckmann: Λ(v) (0 for GGX).
    lv: T,
    a2: T,
    /// R_v = √(μ² + α² sv²).
    rv: T,
    /// T = tan θv and Z = asinh T.
    t: T,
    z: T,
    /// Distance scale of G2's singularities from the cut, per unit tanh(wc) (GGX) or per
    /// unit sc (Beckmann) (module docs).
    d_cut: T,
}

/// One ψ row: cos φ, τc, 1/τc, wc, its weight factor b = dφ/dψ (× ½ at ψ = 0, π), the
/// panel sums and the bound of an ungraded cut zone.
#[derive(Clone, Copy, Debug, Default)]
struct Row<T> {
    c: T,
    tc: T,
    itc: T,
    wc: T,
    b: T,
    v: [T; 2],
    e: [T; 2],
    extra: T,
}

/// One w panel of a row with its K15 value and |K15 − G7|.
#[derive(Clone, Copy, Debug, Default)]
struct Panel<T> {
    row: u16,
    a: T,
    b: T,
    v: [T; 2],
    e: [T; 2],
}

impl<T: Real> Texel<T> {
    fn new(mu: T, model: PolarModel<T>) -> Self {
        let alpha = model.width();
        let sv = ((T::ONE - mu) * (T::ONE + mu)).max(T::ZERO).sqrt();
        let a2 = alpha * alpha;
        let t = sv / mu;
        let one_m = (T::ONE - a2).max(T::ZERO);
        let inv_sqrt_pi = T::from_f64(0.564_189_583_547_756_3);
        let (lv, d_cut) = match model {
            PolarModel::GgxCorrelated(_) if one_m > T::ZERO => {
                (T::ZERO, alpha / (one_m.sqrt() * mu))
            }
            PolarModel::GgxCorrelated(_) => (T::ZERO, T::INFINITY),
            PolarModel::BeckmannCorrelated(_) => {
                let lv = Beckmann::lambda_cos(mu, alpha);
                (lv, alpha * inv_sqrt_pi / ((T::ONE + lv + lv) * mu))
            }
            PolarModel::BeckmannSeparable(_) => {
                (Beckmann::lambda_cos(mu, alpha), alpha * inv_sqrt_pi / mu)
            }
        };
        Self {
            model,
            mu,
            sv,
            alpha,
            lv,
            a2,
            rv: (mu * mu + a2 * sv * sv).sqrt(),
            t,
            z: asinh(t),
            d_cut,
        }
    }

    /// The row at ψ: (cos φ, ζ = ln τc, dφ/dψ) with T cos φ = sinh(Z cos ψ) and
    /// dφ/dψ = cosh ζ/√(shc(a) shc(b)), a = 2Z cos²(ψ/2), b = 2Z sin²(ψ/2) (module docs),
    /// evaluated as (cosh ζ e^{−Z})/√(shc(a)e^{−a} shc(b)e^{−b}) (a + b = 2Z: no overflow).
    fn row_geometry(&self, psi: T) -> (T, T, T) {
        if !(self.t > T::ZERO) {
            return (psi.cos(), T::ZERO, T::ONE);
        }
        let (sh, ch) = (psi * T::HALF).sin_cos();
        let zeta = self.z * (ch * ch - sh * sh);
        let c = (sinh(zeta) / sinh(self.z)).clamp(-T::ONE, T::ONE);
        let a = T::TWO * self.z * ch * ch;
        let b = T::TWO * self.z * sh * sh;
        let cosh_scaled = ((zeta - self.z).exp() + (-zeta - self.z).exp()) * T::HALF;
        let j = cosh_scaled / (shc_scaled(a) * shc_scaled(b)).sqrt();
        (c, zeta, j)
    }

    /// The integrand of I(φ) at w on row `r` (module docs): tanh w sech² w ·
    /// 2(sv τ c + μ) n·l/(π(n·l R_v + μ R_l)) · (1 − F_c, F_c), τ = α sinh w; 0 outside the
    /// lit range.
    #[inline]
    fn integrand(&self, r: &Row<T>, w: T) -> [T; 2] {
        if !self.model.is_ggx() {
            return self.integrand_beckmann(r, w);
        }
        let (sh, ch) = sinh_cosh(w);
        let tau = self.alpha * sh;
        let d = T::ONE + tau * tau;
        let nl = self.mu * (r.tc - tau) * (tau + r.itc) / d;
        if !(nl > T::ZERO) {
            return [T::ZERO; 2];
        }
        let nl = nl.min(T::ONE);
        let rl = (nl * nl + self.a2 * (T::ONE - nl) * (T::ONE + nl)).sqrt();
        let num = self.sv * r.c * tau + self.mu;
        let vh = num / d.sqrt();
        let q = sh / (ch * ch * ch);
        let val =
            q * T::from_f64(2.0 / core::f64::consts::PI) * num * nl / (nl * self.rv + self.mu * rl);
        let fc = (T::ONE - vh).max(T::ZERO).powi(5);
        [val * (T::ONE - fc), val * fc]
    }

    /// The Beckmann integrand of I(φ) at s on row `r` (module docs):
    /// s e^{−s²} (sv τ c + μ) G2/(π μ) · (1 − F_c, F_c), τ = m s; 0 outside the lit range.
    #[inline]
    fn integrand_beckmann(&self, r: &Row<T>, s: T) -> [T; 2] {
        let tau = self.alpha * s;
        let d = T::ONE + tau * tau;
        let nl = self.mu * (r.tc - tau) * (tau + r.itc) / d;
        if !(nl > T::ZERO) {
            return [T::ZERO; 2];
        }
        let ll = Beckmann::lambda_cos(nl.min(T::ONE), self.alpha);
        let g2 = match self.model {
            PolarModel::BeckmannSeparable(_) => T::ONE / ((T::ONE + self.lv) * (T::ONE + ll)),
            _ => T::ONE / (T::ONE + self.lv + ll),
        };
        let num = self.sv * r.c * tau + self.mu;
        let vh = num / d.sqrt();
        let val = s * (-(s * s)).exp() * num * g2 / (T::PI * self.mu);
        let fc = (T::ONE - vh).max(T::ZERO).powi(5);
        [val * (T::ONE - fc), val * fc]
    }

    /// The radial end wc of a row whose cut is at τc, whether the cut lies inside the range
    /// (Beckmann rows are cut at [`BECKMANN_S_MAX`]), and the grading scale d there.
    fn radial_end(&self, tc: T) -> (T, bool, T) {
        let x = tc / self.alpha;
        if self.model.is_ggx() {
            // tanh(wc) = x/√(1 + x²).
            return (asinh(x), true, self.d_cut * x / (T::ONE + x * x).sqrt());
        }
        let smax = T::from_f64(BECKMANN_S_MAX);
        if x > smax {
            (smax, false, T::ZERO)
        } else {
            (x, true, self.d_cut * x)
        }
    }

    /// A bound on the Beckmann integrand beyond s = [`BECKMANN_S_MAX`] on row `r`:
    /// s e^{−s²}(sv|c| m s + μ)/(πμ) ≤ s² e^{−s²}(sv m + μ)/(πμ) for s ≥ 1, and
    /// ∫_S^∞ s² e^{−s²} ds ≤ (S² + 1) e^{−S²}/(2S).
    fn tail_bound(&self) -> T {
        let s = T::from_f64(BECKMANN_S_MAX);
        (s * s + T::ONE) * (-(s * s)).exp() / (s + s) * (self.sv * self.alpha + self.mu)
            / (T::PI * self.mu)
    }

    /// K15 over [a, b] on row `r`: (value, |K15 − G7|) per channel.
    fn panel(&self, r: &Row<T>, a: T, b: T) -> ([T; 2], [T; 2]) {
        let t = gk15_nodes(a, b);
        let mut y = [[T::ZERO; 2]; 15];
        for (y, t) in y.iter_mut().zip(&t) {
            *y = self.integrand(r, *t);
        }
        gk15_combine(&y, (b - a) * T::HALF)
    }

    /// A bound on ∫ over [wc − len, wc] of the integrand's channels on row `r`: the
    /// integrand is ≤ 2 tanh w sech² w (sv|c|τc + μ)/(πμ) (G2 ≤ 1 since n·l R_v + μ R_l ≥
    /// μ n·l), and tanh w sech² w decreases for w ≥ asinh(1/√2) ≈ 0.658.
    /// Beckmann: the same with s e^{−s²}, which decreases for s ≥ 1/√2 (and the Beckmann
    /// integrand ≤ s e^{−s²}(sv|c|τc + μ)/(πμ), half the bound taken).
    fn zone_bound(&self, r: &Row<T>, len: T) -> T {
        let q = if self.model.is_ggx() {
            let w = (r.wc - len).max(T::from_f64(0.6585));
            let sh = sinh(w);
            let ch2 = T::ONE + sh * sh;
            sh / (ch2 * ch2.sqrt())
        } else {
            let s = (r.wc - len).max(T::from_f64(core::f64::consts::FRAC_1_SQRT_2));
            s * (-(s * s)).exp()
        };
        T::TWO * q * (self.sv * r.c.abs() * r.tc + self.mu) / (T::PI * self.mu) * len
    }
}

/// The integrator's working state (fixed-size: about 56 KB for f64).
struct State<T> {
    tex: Texel<T>,
    tol: T,
    rows: [Row<T>; MAX_INTERVALS + 1],
    panels: [Panel<T>; MAX_PANELS],
    np: usize,
    evals: u32,
}

/// The rows of trapezoid level `n` (n | [`MAX_INTERVALS`]): indices k·(MAX/n), k = 0..=n.
fn level(n: usize) -> impl Iterator<Item = usize> {
    (0..=n).map(move |k| k * (MAX_INTERVALS / n))
}

impl<T: Real> State<T> {
    /// Appends the K15 panel [a, b] of row k; false when the panel store is full.
    fn add_panel(&mut self, k: usize, a: T, b: T) -> bool {
        if self.np >= MAX_PANELS {
            return false;
        }
        let (v, e) = self.tex.panel(&self.rows[k], a, b);
        self.evals += 15;
        self.panels[self.np] = Panel {
            row: k as u16,
            a,
            b,
            v,
            e,
        };
        self.np += 1;
        for ch in 0..2 {
            self.rows[k].v[ch] += v[ch];
            self.rows[k].e[ch] += e[ch];
        }
        true
    }

    /// Creates row k (ψ = kπ/MAX) with its initial panels: [0, 1.5], the tail, and the tail
    /// graded toward wc at the branch-point scale d (module docs), unless the bound on the
    /// zone [wc − min(1, wc − 1.5), wc] shows it below 10⁻³·tol (then 2 × the bound is the
    /// row's extra estimate).
    fn make_row(&mut self, k: usize) -> bool {
        let psi = T::PI * T::from_f64(k as f64) / T::from_f64(MAX_INTERVALS as f64);
        let (c, zeta, j) = self.tex.row_geometry(psi);
        let tc = zeta.exp();
        let (wc, cut, d) = self.tex.radial_end(tc);
        let end = k == 0 || k == MAX_INTERVALS;
        self.rows[k] = Row {
            c,
            tc,
            itc: (-zeta).exp(),
            wc,
            b: if end { j * T::HALF } else { j },
            extra: if cut { T::ZERO } else { self.tex.tail_bound() },
            ..Row::default()
        };
        let bump = T::from_f64(BUMP_BREAK);
        let lo = if wc > bump { bump } else { T::ZERO };
        if lo > T::ZERO && !self.add_panel(k, T::ZERO, lo) {
            return false;
        }
        let zone = T::from_f64(GRADE_MAX).min(wc - lo);
        let mut pts = [T::ZERO; 24];
        let mut n = 0;
        let mut g = T::TWO * d;
        while cut && wc - g > lo + g * T::HALF && g < T::from_f64(GRADE_MAX) && n < pts.len() {
            pts[n] = wc - g;
            n += 1;
            g *= T::from_f64(GRADE_RATIO);
        }
        if n > 0 {
            let bound = self.tex.zone_bound(&self.rows[k], zone);
            if T::TWO * bound <= T::from_f64(1e-3) * self.tol {
                self.rows[k].extra += T::TWO * bound;
                n = 0;
            }
        }
        let mut a = lo;
        for i in (0..n).rev() {
            if !self.add_panel(k, a, pts[i]) {
                return false;
            }
            a = pts[i];
        }
        self.add_panel(k, a, wc)
    }

    /// Halves the splittable panel with the largest weighted estimate b_k·max(e); false if
    /// there is none or the store is full.
    fn refine_worst(&mut self) -> bool {
        if self.np + 1 > MAX_PANELS {
            return false;
        }
        let mut best: Option<(usize, T)> = None;
        for (i, p) in self.panels[..self.np].iter().enumerate() {
            let key = self.rows[p.row as usize].b * p.e[0].max(p.e[1]);
            let wide = (p.b - p.a) > T::from_f64(64.0) * T::EPSILON * (p.a.abs() + p.b.abs());
            if wide && best.is_none_or(|(_, k)| key > k) {
                best = Some((i, key));
            }
        }
        let Some((i, _)) = best else {
            return false;
        };
        let p = self.panels[i];
        let k = p.row as usize;
        let m = (p.a + p.b) * T::HALF;
        for ch in 0..2 {
            self.rows[k].v[ch] -= p.v[ch];
            self.rows[k].e[ch] -= p.e[ch];
        }
        // The left half takes the old slot, the right half is appended.
        let (v, e) = self.tex.panel(&self.rows[k], p.a, m);
        self.evals += 15;
        self.panels[i] = Panel { b: m, v, e, ..p };
        for ch in 0..2 {
            self.rows[k].v[ch] += v[ch];
            self.rows[k].e[ch] += e[ch];
        }
        self.add_panel(k, m, p.b)
    }
}

impl<T: Real> State<T> {
    /// (T_n, the rows' weighted estimate) per channel at level n, rows recomputed from the
    /// panels (no drift from the running sums).
    fn sums(&self, n: usize) -> ([T; 2], [T; 2]) {
        let h2 = T::TWO * T::PI / T::from_f64(n as f64);
        let (mut v, mut e) = ([T::ZERO; 2], [T::ZERO; 2]);
        for k in level(n) {
            let r = &self.rows[k];
            for ch in 0..2 {
                v[ch] += h2 * r.b * r.v[ch];
                e[ch] += h2 * r.b * (r.e[ch] + r.extra);
            }
        }
        (v, e)
    }

    /// Recomputes every row's panel sums from the panels.
    fn resum(&mut self) {
        for r in self.rows.iter_mut() {
            r.v = [T::ZERO; 2];
            r.e = [T::ZERO; 2];
        }
        for p in &self.panels[..self.np] {
            let r = &mut self.rows[p.row as usize];
            for ch in 0..2 {
                r.v[ch] += p.v[ch];
                r.e[ch] += p.e[ch];
            }
        }
    }

    /// The global refinement loop (module docs): returns (value, estimate, final level).
    fn run(&mut self) -> ([T; 2], [T; 2], usize) {
        let mut n = 2 * FIRST_INTERVALS;
        let mut full = false;
        for k in level(n) {
            full |= !self.make_row(k);
        }
        let half_tol = self.tol * T::HALF;
        loop {
            let (fine, rows_e) = self.sums(n);
            let (coarse, _) = self.sums(n / 2);
            let outer = [(fine[0] - coarse[0]).abs(), (fine[1] - coarse[1]).abs()];
            let done = (0..2).all(|ch| outer[ch] + rows_e[ch] <= self.tol);
            if done || full {
                return self.finish(n);
            }
            let need_rows = rows_e[0].max(rows_e[1]) > half_tol;
            if need_rows && self.refine_worst() {
                continue;
            }
            let need_outer = !(outer[0].max(outer[1]) <= half_tol);
            if !need_outer || n >= MAX_INTERVALS {
                return self.finish(n);
            }
            n *= 2;
            for k in level(n).skip(1).step_by(2) {
                full |= !self.make_row(k);
            }
        }
    }

    /// The result at level n: T_n, |T_n − T_{n/2}| + rows + 64ε|T_n|.
    fn finish(&mut self, n: usize) -> ([T; 2], [T; 2], usize) {
        self.resum();
        let (fine, rows_e) = self.sums(n);
        let (coarse, _) = self.sums(n / 2);
        let mut err = [T::ZERO; 2];
        for ch in 0..2 {
            err[ch] = (fine[ch] - coarse[ch]).abs()
                + rows_e[ch]
                + T::from_f64(64.0) * T::EPSILON * fine[ch].abs();
        }
        (fine, err, n)
    }
}

/// (A, B) of the split sum of `model` at view cosine μ ∈ (0, 1] and width > 0 to the
/// absolute tolerance `tol` per channel (module docs).
fn integrate<T: Real>(mu: T, model: PolarModel<T>, tol: T) -> Polar<T> {
    let mut s = State {
        tex: Texel::new(mu, model),
        tol,
        rows: [Row::default(); MAX_INTERVALS + 1],
        panels: [Panel::default(); MAX_PANELS],
        np: 0,
        evals: 0,
    };
    let (value, error, n) = s.run();
    Polar {
        value,
        error,
        evals: s.evals,
        rows: (n + 1) as u32,
        panels: s.np as u32,
    }
}

/// One roughness row of a split-sum table by the polar rule: the lobe ([`PolarModel`], its
/// width) is fixed along it, μ varies.
#[derive(Clone, Copy, Debug)]
pub struct PolarRow<T> {
    model: PolarModel<T>,
}

/// The GGX row ([`PolarRow::new`] takes the perceptual roughness r, α = r²).
pub type DfgGgxPolarRow<T> = PolarRow<T>;

impl<T: Real> PolarRow<T> {
    /// The GGX row (height-correlated Smith) of perceptual roughness r: α = r², r clamped to
    /// [0, 1] (docs/conventions.md §8; NaN stays NaN).
    pub fn new(r: T) -> Self {
        Self::with_model(PolarModel::GgxCorrelated(row_alpha(r)))
    }

    /// The row of any [`PolarModel`] (its width as given: NaN gives NaN texels, a width
    /// ≤ [`MIRROR_ALPHA`] the mirror limit).
    pub fn with_model(model: PolarModel<T>) -> Self {
        Self { model }
    }

    /// The row's width (GGX α = r², Beckmann m).
    pub(crate) fn width(&self) -> T {
        self.model.width()
    }

    /// (A, B) at μ to the absolute tolerance `tol` per channel, with the estimate and the
    /// work. NaN μ or width gives NaN; μ below [`crate::geometry::min_cos`] gives (0, 0); μ > 1 is clamped.
    /// A width ≤ [`MIRROR_ALPHA`] is the mirror limit A = 1 − (1 − μ)⁵, B = (1 − μ)⁵ with the
    /// estimate (width/μ)² (G2 = 1 − O((α/μ)²)). A `tol` that cannot be met (≤ 0, NaN, or
    /// beyond the fixed storage) returns the best result with its estimate.
    pub fn texel(&self, mu: T, tol: T) -> Polar<T> {
        match texel_edges(mu, self.width()) {
            Ok(mu) => integrate(mu, self.model, tol),
            Err((v, e)) => Polar::exact(v, e),
        }
    }

    /// The Kulla–Conty average E_avg = 2∫₀¹ E(μ) μ dμ of the row and its estimate, to `tol`
    /// (see [`e_avg_ggx_polar`]).
    pub fn e_avg(&self, tol: T) -> (T, T) {
        e_avg_panel(self, (T::ZERO, T::ONE), tol * T::HALF, tol * T::HALF, 0)
    }
}

/// The GGX split sum (A, B) at (μ, r) by the polar rule (see [`DfgGgxPolarRow::texel`]).
pub fn dfg_ggx_polar<T: Real>(mu: T, r: T, tol: T) -> Polar<T> {
    DfgGgxPolarRow::new(r).texel(mu, tol)
}

/// The Kulla–Conty directional albedo E = A + B (F = 1, α = r²) and its estimate, each
/// channel to tol/2.
pub fn e_ggx_polar<T: Real>(mu: T, r: T, tol: T) -> (T, T) {
    dfg_ggx_polar(mu, r, tol * T::HALF).sum()
}

/// Halvings of an E_avg panel at most.
pub const MAX_EAVG_DEPTH: u32 = 8;

/// The Kulla–Conty average E_avg(r) = 2∫₀¹ E(μ) μ dμ = ∫₀¹ 4t³ E(t²) dt (μ = t²) and its
/// estimate, to `tol`: K15 in t, a panel halved while its |K15 − G7| exceeds its share of
/// tol/2; every E to tol/2 (the weights 4t³ integrate to 1), its estimates integrated with
/// the same K15 weights and added.
pub fn e_avg_ggx_polar<T: Real>(r: T, tol: T) -> (T, T) {
    DfgGgxPolarRow::new(r).e_avg(tol)
}

/// ∫ₐᵇ 4t³ E(t²) dt on one panel (see [`e_avg_ggx_polar`]): (value, estimate).
fn e_avg_panel<T: Real>(
    row: &PolarRow<T>,
    (a, b): (T, T),
    node_tol: T,
    tol: T,
    depth: u32,
) -> (T, T) {
    let t = gk15_nodes(a, b);
    let mut y = [[T::ZERO; 2]; 15];
    for (y, t) in y.iter_mut().zip(&t) {
        let (e, est) = row.texel(*t * *t, node_tol * T::HALF).sum();
        let w = T::from_f64(4.0) * *t * *t * *t;
        *y = [w * e, w * est];
    }
    let (v, d) = gk15_combine(&y, (b - a) * T::HALF);
    if d[0] <= tol || depth >= MAX_EAVG_DEPTH {
        return (v[0], d[0] + v[1].abs());
    }
    let m = (a + b) * T::HALF;
    let (v0, e0) = e_avg_panel(row, (a, m), node_tol, tol * T::HALF, depth + 1);
    let (v1, e1) = e_avg_panel(row, (m, b), node_tol, tol * T::HALF, depth + 1);
    (v0 + v1, e0 + e1)
}

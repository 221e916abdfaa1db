//! The sheen directional albedo of the `sheen-e` tables (docs/lut-format.md, kind
//! `SheenAlbedo`), with its error estimate, and `lut verify`'s independent reference.
//!
//! E(μ, r) = ∫ D(h) V(μ, μl) μl dωl over the upper hemisphere of light directions l, the
//! directional albedo of the Estevez–Kulla sheen with colour 1 (brdf-core
//! `models::sheen`, docs/conventions.md §11): D the Charlie distribution of width
//! α = r² (clamped at `charlie::ALPHA_FLOOR` = 1e-4, so every r ≤ 0.01 holds the r = 0.01
//! value; the r = 0 column is that value, not the undefined limit), V either visibility.
//! Both visibilities are computed together (they share D's integral).
//!
//! **Generator** ([`sheen_e`]), in the light direction's own coordinates (μl, φ): V depends
//! on μl only, so E = ∫₀¹ V(μ, μl) μl I(μ, μl) dμl with I = ∫₀^{2π} D dφ. With
//! w = 1 + v·l = 1 + μ μl + s sl cos φ (s, sl the sines), cos θh = (μ + μl)/√(2w) and
//! sin²θh = (s² + sl² + 2 s sl cos φ)/(2w): D is an even, periodic, analytic function of φ
//! (decreasing on [0, π]), so the trapezoid rule on [0, π] converges geometrically (in an
//! azimuth stretched toward the mirror direction φ = π for wide lobes, [`cluster`], and
//! folded toward it for narrow ones, [`fold`]: both analytic bijections of the circle); it
//! doubles from 8 intervals until two levels agree to the inner tolerance (their
//! difference is the estimate, which for a geometrically converging rule bounds the finer
//! level's error; a peak at φ = 0 narrower than the grid shows as a factor-2 disagreement,
//! so it is never missed). The outer μl integral is globally adaptive Gauss–Kronrod
//! (15/7 points, brdf-core `quadrature::kronrod`), panels first cut at 1e-3, 1e-2, 0.1
//! and at μl = μ (for α > ½, D is not smooth at θh = 0, which l meets at μl = μ), each
//! panel halved until |K15 − G7| ≤ tol × its length; the first panel [0, 1e-3] is taken in
//! s = ln(1e-3/μl) up to a cut-off with a stated bound (the Estevez–Kulla Λ fit turns on
//! like μl^0.17 near 0, which halving in μl chased to the depth limit; [`LOG_PANEL`]), cut
//! at μl = μ when μ < 1e-3. The node's estimate is the sum of the panels' |K15 − G7| plus
//! the Kronrod-weighted inner estimates (plus the cut-off's bound).
//!
//! **Grid** ([`sheen_grid`], the engine textures' texels): E is smooth in x = ln μ (the
//! fitted Λ's μ^c terms are e^{cx}, analytic) and y = ln r on r ∈ [0.01, 1] (r ≤ 0.01 holds
//! the r = 0.01 value: a kink, so a domain edge), except at μ = ½, where the fitted Λ
//! switches branch (continuous with its first derivative only): the domain x ∈
//! [ln(½/n), ln ½] ∪ [ln ½, 0] × y ∈ [ln 0.01, 0] is covered by patches carrying the tensor
//! interpolant of degree 16 through the Chebyshev–Lobatto nodes, each node by [`sheen_e`] to
//! [`GRID_NODE_TOL`]; a patch is halved along the axis with the larger tail until the tails
//! fit half the tolerance. Each pending patch first gets only the degree-8 nodes (every
//! other degree-16 node, so all are kept); when the degree-16 tails these predict
//! ([`predicted_tails`]) exceed the tolerance [`PROBE_SLACK`]-fold, the patch is halved
//! without its other nodes (a saving only: acceptance is by the degree-16 tails). A texel takes the barycentric value of the patch holding its
//! centre. **Estimate** per patch and channel: Σ|c_jk| over the last two orders j ∈ {N−1, N}
//! (all k) plus the same along k, plus Λ² × the largest node estimate. The tail part bounds
//! the truncation and aliasing error 2Σ_{j>N}|a_j| when the coefficients decay at least
//! geometrically with ratio ≤ ½ from order N − 1 on (|a_{N−1}| ≥ 2|a_N| and the tail beyond N
//! ≤ |a_N|); Λ ≤ (2/π) ln(N + 1) + 1 is the Lobatto points' Lebesgue constant (Rivlin), which
//! carries the nodes' errors into the interpolant. The estimate is not a proof (the decay is
//! read off the computed coefficients), so tests/sheen_e.rs checks it against
//! [`sheen_e_reference`] at texel centres.
//!
//! **Reference** ([`sheen_e_reference`]): the same integral in the half vector's
//! coordinates (θh, φh): E = ∫₀^{π/2} D(θh) sin θh ∫_{lit} 4 (v·h) V(μ, l_z) l_z dφh dθh,
//! l = 2(v·h)h − v, the lit azimuths |φh| ≤ φmax cut exactly (l_z > 0 ⇔
//! s sin θh cos φh > μ/(2 cos θh) − μ cos θh), both levels adaptive Gauss–Kronrod. Other
//! variables, another rule: it shares only the kernel (D and V) with the generator.

use super::work::Work;
use brdf_core::geometry::min_cos;
use brdf_core::microfacet::charlie::{v_ashikhmin, Charlie};
use brdf_core::models::SheenVisibility;
use brdf_core::quadrature::kronrod::{gk15_combine, gk15_nodes};
use core::f64::consts::{FRAC_PI_2, PI};
use std::vec;
use std::vec::Vec;

/// Absolute tolerance per node of the generator (¼ of a u16 step of a unit channel).
pub const TOL: f64 = 2e-6;
/// Absolute tolerance of `lut verify`'s reference.
pub const REFERENCE_TOL: f64 = 2e-8;

/// The channel of `v` in the two-channel results: 0 Estevez–Kulla, 1 Ashikhmin.
pub fn channel(v: SheenVisibility) -> usize {
    match v {
        SheenVisibility::EstevezKulla => 0,
        SheenVisibility::Ashikhmin => 1,
    }
}

/// One node: E for both visibilities ([Estevez–Kulla, Ashikhmin]), the estimates of their
/// errors and the D evaluations it took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SheenE {
    /// E per visibility.
    pub value: [f64; 2],
    /// Estimated |value − exact| per visibility.
    pub error: [f64; 2],
    /// Evaluations of D.
    pub evals: u64,
}

/// [V_EK(μ, μl)·μl, V_A(μ, μl)·μl] (brdf-core's two visibilities times the cosine).
fn v_mu(ch: &Charlie<f64>, mu: f64, mul: f64) -> [f64; 2] {
    [
        ch.v_estevez_kulla(mu, mul) * mul,
        v_ashikhmin(mu, mul) * mul,
    ]
}

/// I(μ, μl) = ∫₀^{2π} D dφ = 2∫₀^π D(φ(ψ)) φ'(ψ) dψ by the doubling trapezoid rule in the
/// stretched azimuth ψ ([`cluster`]; module docs):
/// (value, |T_N − T_{N/2}|, evaluations), to the absolute tolerance `tol` or 4096
/// intervals.
fn azimuthal(ch: &Charlie<f64>, mu: f64, mul: f64, tol: f64) -> (f64, f64, u64) {
    let (s, sl) = (
        (1.0 - mu * mu).max(0.0).sqrt(),
        (1.0 - mul * mul).max(0.0).sqrt(),
    );
    // 2w = (μ + μl)² + (s − sl)² + 2 s sl (1 + cos φ) and the numerator of sin²θh is
    // (s − sl)² + 2 s sl (1 + cos φ): no cancellation near φ = π.
    let (c, ds2, b) = (mu + mul, (s - sl) * (s - sl), 2.0 * s * sl);
    let kappa = cluster(ch.alpha(), c * c + ds2, s * sl);
    let a = fold(ch.alpha());
    let d = |chi: f64| {
        // χ → ψ = χ + a sin χ (dψ/dχ = 1 + a cos χ), then ψ → φ.
        let psi = chi + a * chi.sin();
        let jac = 1.0 + a * chi.cos();
        let (s2, c2) = (0.5 * psi).sin_cos();
        let den = c2 * c2 + kappa * kappa * s2 * s2;
        let one_plus_cos = 2.0 * c2 * c2 / den;
        let two_w = c * c + ds2 + b * one_plus_cos;
        let num = ds2 + b * one_plus_cos;
        ch.d_cos_sin2(c / two_w.sqrt(), num / two_w) * (kappa / den) * jac
    };
    let mut n = 8usize;
    let mut sum = 0.5 * (d(0.0) + d(PI)) + (1..n).map(|k| d(PI * k as f64 / n as f64)).sum::<f64>();
    let mut evals = (n + 1) as u64;
    let mut t = 2.0 * PI / n as f64 * sum;
    loop {
        let odd: f64 = (0..n)
            .map(|k| d(PI * (2 * k + 1) as f64 / (2 * n) as f64))
            .sum();
        evals += n as u64;
        sum += odd;
        n *= 2;
        let t2 = 2.0 * PI / n as f64 * sum;
        let est = (t2 - t).abs();
        t = t2;
        if est <= tol || n >= 4096 {
            return (t, est, evals);
        }
    }
}

/// The stretch κ ≥ 1 of the azimuth substitution φ = 2 atan(κ tan(ψ/2)) (an analytic
/// bijection of the circle, so the trapezoid rule in ψ keeps its geometric convergence;
/// dφ/dψ = κ/(cos²(ψ/2) + κ² sin²(ψ/2)), 1/κ at φ = π): near the mirror azimuth φ = π
/// the half vector swings toward the normal within ε = √(gap/(s sl)) (gap = (μ + μl)² +
/// (s − sl)², the value of 2w there), a feature D shows for the wide lobes (α ≥ 0.09); κ =
/// ½/ε, between 1 and 32, spreads it over the grid. Narrow lobes keep κ = 1 (their peak is
/// at φ = 0, which the stretch would thin).
fn cluster(alpha: f64, gap: f64, ssl: f64) -> f64 {
    if alpha < 0.09 || ssl <= 0.0 {
        return 1.0;
    }
    (0.5 * (ssl / gap).sqrt()).clamp(1.0, 32.0)
}

/// The fold a of the azimuth substitution ψ = χ + a sin χ (dψ/dχ = 1 + a cos χ ≥ 0: an
/// entire, odd-about-0-and-π bijection of the circle, so the integrand stays periodic and
/// analytic and the trapezoid rule in χ keeps its geometric convergence): a = 1 for the
/// narrow lobes (α < 0.09), where π − ψ ≈ (π − χ)³/6 clusters the nodes at the mirror
/// azimuth. There, at grazing μ and small μl, h swings up to the normal within
/// δ ≈ (μ + μl)/√(2α) of φ = π (D ≈ D_max·exp(−(μ + μl)²/(2α(π − φ)²)) there): a dip of D
/// narrower than the plain grid (δ ≈ 0.007 at μ = 5e-4, α = 0.01, which took 4096
/// intervals), which the fold widens to (6δ)^{1/3}. Wide lobes keep a = 0 ([`cluster`]).
fn fold(alpha: f64) -> f64 {
    if alpha < 0.09 {
        1.0
    } else {
        0.0
    }
}

/// One accepted or pending panel of the outer rule.
struct Panel {
    a: f64,
    b: f64,
    depth: u32,
}

/// Globally adaptive two-channel Gauss–Kronrod on the panels cut at `breaks`: `f(x)` gives
/// the two channels and the two channels' own error at x (weighted into the estimate by
/// the Kronrod weights). Each panel is halved until max |K15 − G7| ≤ tol × its length
/// (or its depth reaches 40). Returns (value, estimate) per channel.
fn adaptive(
    breaks: &[f64],
    tol: f64,
    f: &mut dyn FnMut(f64) -> ([f64; 2], [f64; 2]),
) -> ([f64; 2], [f64; 2]) {
    let (mut v, mut e) = ([0.0; 2], [0.0; 2]);
    let mut stack: Vec<Panel> = breaks
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| Panel {
            a: w[0],
            b: w[1],
            depth: 0,
        })
        .collect();
    while let Some(p) = stack.pop() {
        let (mut y, mut ye) = ([[0.0; 2]; 15], [[0.0; 2]; 15]);
        for (k, x) in gk15_nodes(p.a, p.b).into_iter().enumerate() {
            (y[k], ye[k]) = f(x);
        }
        let h = 0.5 * (p.b - p.a);
        let (pv, pe) = gk15_combine(&y, h);
        let (inner, _) = gk15_combine(&ye, h);
        if pe[0].max(pe[1]) <= tol * (p.b - p.a) || p.depth >= 40 {
            for c in 0..2 {
                v[c] += pv[c];
                e[c] += pe[c] + inner[c].abs();
            }
        } else {
            let m = 0.5 * (p.a + p.b);
            stack.push(Panel {
                a: p.a,
                b: m,
                depth: p.depth + 1,
            });
            stack.push(Panel {
                a: m,
                b: p.b,
                depth: p.depth + 1,
            });
        }
    }
    (v, e)
}

/// E(μ, r) for both visibilities, by the generator's rule (module docs), to the absolute
/// tolerance `tol` per visibility. μ above 1 is taken as 1; μ below brdf-core's `min_cos`
/// (at or below the horizon) gives 0; NaN gives NaN. r is clamped into the Charlie
/// width range (α = r² ∈ [1e-4, 1]).
pub fn sheen_e(mu: f64, r: f64, tol: f64) -> SheenE {
    let ch = Charlie::clamped(r * r);
    let mu = mu.min(1.0);
    if mu.is_nan() || r.is_nan() {
        return SheenE {
            value: [f64::NAN; 2],
            error: [f64::NAN; 2],
            evals: 0,
        };
    }
    if mu < min_cos::<f64>() {
        return SheenE::default();
    }
    let mut evals = 0u64;
    let mut f = |mul: f64| {
        // An inner error δ ≤ tol/(4·max V·μl) at every node adds at most tol/4 to E (the
        // outer variable spans [0, 1]).
        let w = v_mu(&ch, mu, mul);
        let inner_tol = tol * 0.25 / w[0].max(w[1]).max(1e-300);
        let (i, est, n) = azimuthal(&ch, mu, mul, inner_tol);
        evals += n;
        ([w[0] * i, w[1] * i], [w[0] * est, w[1] * est])
    };
    let mut breaks: Vec<f64> = [LOG_PANEL, 1e-2, 0.1, mu.max(LOG_PANEL), 1.0].into();
    breaks.sort_by(f64::total_cmp);
    let (mut value, mut error) = adaptive(&breaks, tol * 0.5, &mut f);
    // [0, LOG_PANEL] in s = ln(LOG_PANEL/μl) (module docs), cut at s = S where the rest,
    // ∫₀^{LOG_PANEL e^{−S}} f ≤ LOG_PANEL e^{−S}·(2 + 1/α)/(4μ) (f = V μl I with V μl ≤ 1/(4μ)
    // for both visibilities and I ≤ 2π D_max), is tol/20 (added to the estimate); the same
    // tolerance per unit of μl as the panels above.
    let bound = (2.0 + 1.0 / ch.alpha()) / (4.0 * mu);
    let s_max = (LOG_PANEL * bound / (0.05 * tol)).ln().max(1.0);
    let mut sb = vec![0.0, s_max];
    if mu < LOG_PANEL {
        sb.insert(1, (LOG_PANEL / mu).ln().min(s_max));
    }
    let tol_s = tol * 0.5 * LOG_PANEL / s_max;
    let (v, e) = adaptive(&sb, tol_s, &mut |s| {
        let mul = LOG_PANEL * (-s).exp();
        let (y, ye) = f(mul);
        ([y[0] * mul, y[1] * mul], [ye[0] * mul, ye[1] * mul])
    });
    for c in 0..2 {
        value[c] += v[c];
        error[c] += e[c] + 0.05 * tol;
    }
    SheenE {
        value,
        error,
        evals,
    }
}

/// The first panel of [`sheen_e`]'s outer rule, [0, 1e-3], is integrated in s = ln(1e-3/μl):
/// the fitted Λ holds a term μl^c with c ≈ 0.17–0.20, whose Gauss–Kronrod error on
/// [0, h] shrinks only like h^{1+c}, so halving toward 0 ran to the depth limit (40
/// levels, 1200 of the 1545 outer nodes at μ = 5e-4, r = 0.01); in s that term is
/// e^{−cs}, analytic.
const LOG_PANEL: f64 = 1e-3;

/// `lut verify`'s reference: E(μ, r) for both visibilities in the half vector's
/// coordinates (module docs) to the absolute tolerance `tol`: (value, estimate).
pub fn sheen_e_reference(mu: f64, r: f64, tol: f64) -> ([f64; 2], [f64; 2]) {
    let ch = Charlie::clamped(r * r);
    let mu = mu.min(1.0);
    if mu.is_nan() || r.is_nan() {
        return ([f64::NAN; 2], [f64::NAN; 2]);
    }
    if mu < min_cos::<f64>() {
        return ([0.0; 2], [0.0; 2]);
    }
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    // ∫₀^{π/2} D sin θh dθh ≤ norm·√(π/(2n)), n = 1/α + 1 (Wallis): an inner error δ adds at
    // most 2·that·δ.
    let alpha = ch.alpha();
    let weight = (2.0 + 1.0 / alpha) / (2.0 * PI) * (PI / (2.0 * (1.0 / alpha + 1.0))).sqrt();
    let inner_tol = tol / (8.0 * weight);
    let r_eff = alpha.sqrt();
    let mut breaks: Vec<f64> = [1.0, 2.0, 4.0, 8.0]
        .iter()
        .map(|k| FRAC_PI_2 - k * r_eff)
        .filter(|&x| x > 0.0)
        .chain([0.0, FRAC_PI_2])
        .collect();
    breaks.sort_by(f64::total_cmp);
    adaptive(&breaks, tol * 0.5, &mut |th| {
        let (st, ct) = th.sin_cos();
        let dw = ch.d_cos_sin2(ct, st * st) * st;
        let a = s * st;
        let k = mu / (2.0 * ct) - mu * ct;
        let phi_max = if a <= 0.0 || ct <= 0.0 {
            if k < 0.0 && ct > 0.0 {
                PI
            } else {
                0.0
            }
        } else {
            (k / a).clamp(-1.0, 1.0).acos()
        };
        if dw == 0.0 || phi_max <= 0.0 {
            return ([0.0; 2], [0.0; 2]);
        }
        let (v, e) = adaptive(&[0.0, phi_max], inner_tol * 0.5, &mut |phi| {
            let w = a * phi.cos() + mu * ct;
            let lz = 2.0 * w * ct - mu;
            let g = v_mu(&ch, mu, lz);
            ([4.0 * w * g[0], 4.0 * w * g[1]], [0.0; 2])
        });
        (
            [2.0 * dw * v[0], 2.0 * dw * v[1]],
            [2.0 * dw * e[0], 2.0 * dw * e[1]],
        )
    })
}

/// The `sheen-e` table's node at (μ, r) for `visibility`: E and its [`Work`] (the
/// generator's rule at [`TOL`]).
pub fn node(visibility: SheenVisibility, mu: f64, r: f64, out: &mut [f64]) -> Work {
    let e = sheen_e(mu, r, TOL);
    let c = channel(visibility);
    if let Some(o) = out.first_mut() {
        *o = e.value[c];
    }
    Work {
        error: e.error[c],
        evals: e.evals,
    }
}

/// `lut verify`'s reference of a `sheen-e` node: (E in the first slot, its estimate), by
/// [`sheen_e_reference`] at [`REFERENCE_TOL`].
pub fn reference(visibility: SheenVisibility, mu: f64, r: f64) -> ([f64; 2], f64) {
    let (v, e) = sheen_e_reference(mu, r, REFERENCE_TOL);
    let c = channel(visibility);
    ([v[c], 0.0], e[c])
}

/// Degree of the tensor Chebyshev patches of [`sheen_grid`] (N + 1 Lobatto nodes per axis).
pub const GRID_DEGREE: usize = 16;
/// Absolute tolerance of each node of [`sheen_grid`] (5× below [`TOL`]: times the tensor
/// Lebesgue constant ≤ 7.8 of degree 16, 3.1e-6).
pub const GRID_NODE_TOL: f64 = 4e-7;
/// The smallest r of [`sheen_grid`]'s domain: α = r² reaches the floor 1e-4 there, and every
/// smaller r holds the r = 0.01 value (a kink of E in r, so a domain edge).
pub const GRID_R_MIN: f64 = 0.01;

/// The sheen albedo at the centres of an n × n texel grid, by [`sheen_grid`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SheenGrid {
    /// [Estevez–Kulla, Ashikhmin], each n² values row-major: column i at μ = (i + ½)/n,
    /// row j at r = (j + ½)/n.
    pub values: [Vec<f64>; 2],
    /// Estimated max |value − E| per channel over the grid (the largest patch estimate).
    pub bound: [f64; 2],
    /// Evaluations of D over all nodes.
    pub evals: u64,
    /// Nodes computed by [`sheen_e`].
    pub nodes: usize,
    /// Patches of the final partition.
    pub patches: usize,
}

/// One patch [x0, x1] × [y0, y1] in the warped coordinates x = ln μ, y = ln r, with its
/// node values (x-node major) once computed.
#[derive(Clone, Debug)]
struct Patch {
    x: [f64; 2],
    y: [f64; 2],
    f: Vec<[f64; 2]>,
    est: [f64; 2],
}

/// The k-th of the N + 1 Chebyshev–Lobatto nodes of [a, b] (k = 0 at b).
fn lobatto(a: f64, b: f64, k: usize) -> f64 {
    lobatto_n(a, b, k, GRID_DEGREE)
}

/// The k-th of the n + 1 Chebyshev–Lobatto nodes of [a, b] (k = 0 at b): those of degree n/2
/// are those of degree n with even k.
fn lobatto_n(a: f64, b: f64, k: usize, n: usize) -> f64 {
    0.5 * (a + b) + 0.5 * (b - a) * (PI * k as f64 / n as f64).cos()
}

/// Computes [`sheen_e`] at `pts` (μ, r) on [`super::threads`] workers (each takes the next
/// free point).
fn nodes_parallel(pts: &[(f64, f64)]) -> Vec<SheenE> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;
    let next = AtomicUsize::new(0);
    let out = Mutex::new(vec![SheenE::default(); pts.len()]);
    std::thread::scope(|s| {
        for _ in 0..super::threads() {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&(mu, r)) = pts.get(k) else { break };
                let e = sheen_e(mu, r, GRID_NODE_TOL);
                if let Ok(mut o) = out.lock() {
                    o[k] = e;
                }
            });
        }
    });
    out.into_inner().unwrap_or_default()
}

/// Chebyshev coefficients c[j][k] (x order j, y order k) of the tensor interpolant through
/// the patch's Lobatto values (the DCT-I along each axis), flattened j-major.
fn coefficients(f: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    let m = n + 1;
    let cosine: Vec<f64> = (0..m * m)
        .map(|t| (PI * ((t / m) * (t % m)) as f64 / n as f64).cos())
        .collect();
    let w = |k: usize| if k == 0 || k == n { 0.5 } else { 1.0 };
    let s = |j: usize| if j == 0 || j == n { 1.0 } else { 2.0 } / n as f64;
    let dct = |g: &dyn Fn(usize) -> [f64; 2], j: usize| {
        let mut c = [0.0; 2];
        for k in 0..m {
            let (v, ck) = (g(k), w(k) * cosine[j * m + k]);
            c = [c[0] + ck * v[0], c[1] + ck * v[1]];
        }
        [c[0] * s(j), c[1] * s(j)]
    };
    // Along y (inner index) for every x node, then along x.
    let mut a = vec![[0.0; 2]; m * m];
    for i in 0..m {
        for k in 0..m {
            a[i * m + k] = dct(&|q| f[i * m + q], k);
        }
    }
    let mut c = vec![[0.0; 2]; m * m];
    for k in 0..m {
        for j in 0..m {
            c[j * m + k] = dct(&|q| a[q * m + k], j);
        }
    }
    c
}

/// The sums of |c| per order of each axis, per channel: (x[j] = Σ_k |c_jk|, y[k] = Σ_j |c_jk|)
/// for degree n.
fn order_sums(c: &[[f64; 2]], n: usize) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let m = n + 1;
    let (mut sx, mut sy) = (vec![[0.0; 2]; m], vec![[0.0; 2]; m]);
    for j in 0..m {
        for k in 0..m {
            for ch in 0..2 {
                let a = c[j * m + k][ch].abs();
                sx[j][ch] += a;
                sy[k][ch] += a;
            }
        }
    }
    (sx, sy)
}

/// The tail of a patch's coefficients per channel: (x tail, y tail), each the sum of |c| over
/// the last two orders of that axis (all orders of the other).
fn tails(c: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let n = GRID_DEGREE;
    let (sx, sy) = order_sums(c, n);
    let last2 = |v: &[[f64; 2]]| [0, 1].map(|ch| v[n - 1][ch] + v[n][ch]);
    (last2(&sx), last2(&sy))
}

/// The degree-N tails predicted from the degree-N/2 interpolant through every other Lobatto
/// node (a subset of the degree-N nodes, so none is wasted): with the order sums decaying
/// like ρ^j, the last two orders' sum T at N/2 over that at the two before gives ρ², and the
/// degree-N tail is T·ρ^{N/2} (ρ taken ≤ 1). Only steers the partition ([`refine`]).
fn predicted_tails(f: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let n = GRID_DEGREE / 2;
    let (sx, sy) = order_sums(&coefficients(f, n), n);
    let predict = |v: &[[f64; 2]]| {
        [0, 1].map(|ch| {
            let (t, before) = (v[n - 1][ch] + v[n][ch], v[n - 3][ch] + v[n - 2][ch]);
            let rho2 = if before > 0.0 {
                (t / before).min(1.0)
            } else {
                1.0
            };
            t * rho2.powi(n as i32 / 2)
        })
    };
    (predict(&sx), predict(&sy))
}

/// How a patch with tails (tx, ty) is treated: `None` accepted (the tails fit half of `tol`, or
/// the patch is 2⁻⁸ of the domain wide along the axis to cut), `Some(true)` halved in x,
/// `Some(false)` halved in y (the axis with the larger tail relative to `tol`).
fn split(p: &Patch, t: ([f64; 2], [f64; 2]), tol: [f64; 2], width: [f64; 2]) -> Option<bool> {
    let (tx, ty) = t;
    // Half of `tol` for the tails, the rest is left to the nodes' share (splitting does
    // not reduce that).
    let rx = (2.0 * tx[0] / tol[0]).max(2.0 * tx[1] / tol[1]);
    let ry = (2.0 * ty[0] / tol[0]).max(2.0 * ty[1] / tol[1]);
    let split_x = rx >= ry && p.x[1] - p.x[0] > width[0] / 256.0;
    let split_y = !split_x && p.y[1] - p.y[0] > width[1] / 256.0;
    if rx + ry <= 1.0 || !(split_x || split_y) {
        None
    } else {
        Some(split_x)
    }
}

/// The two halves of `p` along x (`along_x`) or y, without node values.
fn halves(p: Patch, along_x: bool) -> [Patch; 2] {
    let r = if along_x { p.x } else { p.y };
    let h = 0.5 * (r[0] + r[1]);
    [[r[0], h], [h, r[1]]].map(|half| {
        let (x, y) = if along_x { (half, p.y) } else { (p.x, half) };
        Patch {
            x,
            y,
            f: Vec::new(),
            est: p.est,
        }
    })
}

/// The (μ, r) of the patch's tensor Lobatto nodes of degree `n` (x-node major).
fn node_points(p: &Patch, n: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
    let m = n + 1;
    (0..m * m).map(move |t| {
        (
            lobatto_n(p.x[0], p.x[1], t / m, n).exp(),
            lobatto_n(p.y[0], p.y[1], t % m, n).exp(),
        )
    })
}

/// The normalised barycentric weights at t of the Lobatto nodes of [a, b] (second form,
/// Berrut & Trefethen 2004, "Barycentric Lagrange interpolation", eq. 5.2): wₖ = (−1)ᵏ,
/// halved at both ends; the unit vector when t is a node.
fn bary(a: f64, b: f64, t: f64) -> [f64; GRID_DEGREE + 1] {
    let mut w = [0.0; GRID_DEGREE + 1];
    let mut sum = 0.0;
    for (k, wk) in w.iter_mut().enumerate() {
        let d = t - lobatto(a, b, k);
        if d == 0.0 {
            let mut e = [0.0; GRID_DEGREE + 1];
            e[k] = 1.0;
            return e;
        }
        let end = if k == 0 || k == GRID_DEGREE { 0.5 } else { 1.0 };
        *wk = if k % 2 == 0 { end } else { -end } / d;
        sum += *wk;
    }
    w.map(|x| x / sum)
}

/// How far the predicted tails may exceed the tolerance before [`refine`] halves a patch
/// without computing its other nodes (the prediction only saves work; the degree-N tails
/// decide acceptance).
const PROBE_SLACK: f64 = 8.0;

/// Computes [`sheen_e`] at `pts`, counting nodes and evaluations into `g`.
fn compute(pts: &[(f64, f64)], g: &mut SheenGrid) -> Vec<SheenE> {
    let nodes = nodes_parallel(pts);
    g.nodes += pts.len();
    g.evals += nodes.iter().map(|e| e.evals).sum::<u64>();
    nodes
}

/// Computes the pending patches' nodes, accepts those whose estimate meets `tol` (or that
/// are 2⁻⁸ of the domain wide) into `leaves` and returns the halves of the others. First the
/// degree-N/2 nodes (every other degree-N node): a patch whose predicted tails
/// ([`predicted_tails`]) fail is halved without its other nodes; the rest get all their
/// nodes, and the degree-N tails decide.
fn refine(
    pending: Vec<Patch>,
    tol: [f64; 2],
    width: [f64; 2],
    g: &mut SheenGrid,
    leaves: &mut Vec<Patch>,
) -> Vec<Patch> {
    let (n, m) = (GRID_DEGREE, GRID_DEGREE + 1);
    let h = n / 2 + 1;
    let pts: Vec<(f64, f64)> = pending.iter().flat_map(|p| node_points(p, n / 2)).collect();
    let probe = compute(&pts, g);
    let mut next = Vec::new();
    let mut kept = Vec::new();
    for (mut p, e) in pending.into_iter().zip(probe.chunks(h * h)) {
        let f: Vec<[f64; 2]> = e.iter().map(|e| e.value).collect();
        match split(&p, predicted_tails(&f), tol.map(|t| t * PROBE_SLACK), width) {
            Some(along_x) => next.extend(halves(p, along_x)),
            None => {
                // Degree-N slots (2i, 2k) hold the probe's node (i, k).
                p.f = vec![[f64::NAN; 2]; m * m];
                for (t, v) in e.iter().enumerate() {
                    p.f[(2 * (t / h)) * m + 2 * (t % h)] = v.value;
                }
                p.est = e.iter().fold([0f64; 2], |a, e| {
                    [a[0].max(e.error[0]), a[1].max(e.error[1])]
                });
                kept.push(p);
            }
        }
    }
    let missing = |p: &Patch| {
        (0..m * m)
            .filter(|&t| p.f[t][0].is_nan())
            .collect::<Vec<_>>()
    };
    let pts: Vec<(f64, f64)> = kept
        .iter()
        .flat_map(|p| {
            let all: Vec<(f64, f64)> = node_points(p, n).collect();
            missing(p).into_iter().map(move |t| all[t])
        })
        .collect();
    let mut rest = compute(&pts, g).into_iter();
    // Lebesgue constant of the N + 1 Chebyshev–Lobatto points ≤ (2/π) ln(N + 1) + 1
    // (Rivlin 1974); squared for the tensor product.
    let leb = (2.0 / PI * (m as f64).ln() + 1.0).powi(2);
    for mut p in kept {
        for t in missing(&p) {
            let e = rest.next().unwrap_or_default();
            p.f[t] = e.value;
            p.est = [0, 1].map(|c| p.est[c].max(e.error[c]));
        }
        let (tx, ty) = tails(&coefficients(&p.f, n));
        match split(&p, (tx, ty), tol, width) {
            Some(along_x) => next.extend(halves(p, along_x)),
            None => {
                p.est = [0, 1].map(|c| tx[c] + ty[c] + leb * p.est[c]);
                leaves.push(p);
            }
        }
    }
    next
}

/// Fills `g.values` from the leaves: every texel centre lies in exactly one half-open patch
/// (the last closed), where the tensor barycentric interpolant gives its value.
fn fill(n: usize, leaves: &[Patch], g: &mut SheenGrid) {
    let m = GRID_DEGREE + 1;
    let xs: Vec<f64> = (0..n).map(|i| ((i as f64 + 0.5) / n as f64).ln()).collect();
    let ys: Vec<f64> = (0..n)
        .map(|j| ((j as f64 + 0.5) / n as f64).max(GRID_R_MIN).ln())
        .collect();
    let range =
        |v: &[f64], a: [f64; 2]| v.partition_point(|&t| t < a[0])..v.partition_point(|&t| t < a[1]);
    g.values = [vec![0.0; n * n], vec![0.0; n * n]];
    for p in leaves {
        let (cols, rows) = (range(&xs, p.x), range(&ys, p.y));
        let bx: Vec<_> = cols.clone().map(|i| bary(p.x[0], p.x[1], xs[i])).collect();
        for j in rows {
            let by = bary(p.y[0], p.y[1], ys[j]);
            let col: Vec<[f64; 2]> = (0..m)
                .map(|a| {
                    (0..m).fold([0.0; 2], |s, k| {
                        [
                            s[0] + by[k] * p.f[a * m + k][0],
                            s[1] + by[k] * p.f[a * m + k][1],
                        ]
                    })
                })
                .collect();
            for (i, w) in cols.clone().zip(&bx) {
                let v = (0..m).fold([0.0; 2], |s, a| {
                    [s[0] + w[a] * col[a][0], s[1] + w[a] * col[a][1]]
                });
                g.values[0][j * n + i] = v[0];
                g.values[1][j * n + i] = v[1];
            }
        }
        g.bound = [g.bound[0].max(p.est[0]), g.bound[1].max(p.est[1])];
    }
    g.patches = leaves.len();
}

/// E(μ, r) for both visibilities at the centres of an n × n texel grid (column i at
/// μ = (i + ½)/n, row j at r = (j + ½)/n, every r ≤ [`GRID_R_MIN`] holding the r = 0.01
/// value), to the absolute tolerance `tol` per channel, from converged nodes instead of a
/// quadrature per texel (module docs, **Grid**). n = 0 or a tolerance that is not a positive
/// number gives the empty grid.
pub fn sheen_grid(n: usize, tol: [f64; 2]) -> SheenGrid {
    let mut g = SheenGrid::default();
    if n == 0 || !tol.iter().all(|t| *t > 0.0) {
        return g;
    }
    let mut xb: Vec<f64> = vec![(0.5 / n as f64).ln(), 0.5f64.ln(), 0.0];
    xb.dedup_by(|b, a| *b <= *a);
    let y = [GRID_R_MIN.ln(), 0.0];
    let width = [-xb[0], y[1] - y[0]];
    let mut pending: Vec<Patch> = xb
        .windows(2)
        .map(|w| Patch {
            x: [w[0], w[1]],
            y,
            f: Vec::new(),
            est: [0.0; 2],
        })
        .collect();
    let mut leaves = Vec::new();
    while !pending.is_empty() {
        pending = refine(pending, tol, width, &mut g, &mut leaves);
    }
    fill(n, &leaves, &mut g);
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At r = 1 (α = 1) and μ = 1 the integrand is elementary: v = n, so h_z = (1 + μl)/√(2 + 2μl)
    /// = √((1 + μl)/2), sin θh = √((1 − μl)/2), D = (3/2π) sin θh independent of φ, and with
    /// Ashikhmin's V = 1/4 at μ = 1: E = 2π ∫₀¹ (3/2π)·√((1 − x)/2)·x/4 dx
    /// = (3/(4√2)) ∫₀¹ x √(1 − x) dx = (3/(4√2))·(4/15) = 1/(5√2).
    #[test]
    fn closed_form_at_normal_incidence_r1() {
        let want = 1.0 / (5.0 * 2f64.sqrt());
        let g = sheen_e(1.0, 1.0, TOL);
        assert!((g.value[1] - want).abs() < 1e-7, "{} vs {want}", g.value[1]);
        let (r, _) = sheen_e_reference(1.0, 1.0, 1e-9);
        assert!((r[1] - want).abs() < 1e-8, "reference {} vs {want}", r[1]);
    }
}

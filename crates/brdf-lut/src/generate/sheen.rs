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
//! azimuth stretched toward the mirror direction φ = π for wide lobes, [`cluster`]); it
//! doubles from 8 intervals until two levels agree to the inner tolerance (their
//! difference is the estimate, which for a geometrically converging rule bounds the finer
//! level's error; a peak at φ = 0 narrower than the grid shows as a factor-2 disagreement,
//! so it is never missed). The outer μl integral is globally adaptive Gauss–Kronrod
//! (15/7 points, brdf-core `quadrature::kronrod`), panels first cut at 1e-3, 1e-2, 0.1
//! (the Estevez–Kulla Λ fit turns on like μl^0.17 near 0) and at μl = μ (for α > ½, D is
//! not smooth at θh = 0, which l meets at μl = μ), each panel halved until |K15 − G7| ≤
//! tol × its length. The node's estimate is the sum of the panels' |K15 − G7| plus the
//! Kronrod-weighted inner estimates.
//!
//! **Reference** ([`sheen_e_reference`]): the same integral in the half vector's
//! coordinates (θh, φh): E = ∫₀^{π/2} D(θh) sin θh ∫_{lit} 4 (v·h) V(μ, l_z) l_z dφh dθh,
//! l = 2(v·h)h − v, the lit azimuths |φh| ≤ φmax cut exactly (l_z > 0 ⇔
//! s sin θh cos φh > μ/(2 cos θh) − μ cos θh), both levels adaptive Gauss–Kronrod. Other
//! variables, another rule: it shares only the kernel (D and V) with the generator.

use super::integrate::Work;
use brdf_core::geometry::min_cos;
use brdf_core::microfacet::charlie::{v_ashikhmin, Charlie};
use brdf_core::models::SheenVisibility;
use brdf_core::quadrature::kronrod::{gk15_combine, gk15_nodes};
use core::f64::consts::{FRAC_PI_2, PI};
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
    let d = |psi: f64| {
        let (s2, c2) = (0.5 * psi).sin_cos();
        let den = c2 * c2 + kappa * kappa * s2 * s2;
        let one_plus_cos = 2.0 * c2 * c2 / den;
        let two_w = c * c + ds2 + b * one_plus_cos;
        let num = ds2 + b * one_plus_cos;
        ch.d_cos_sin2(c / two_w.sqrt(), num / two_w) * (kappa / den)
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
    let mut breaks: Vec<f64> = [0.0, 1e-3, 1e-2, 0.1, mu, 1.0].into();
    breaks.sort_by(f64::total_cmp);
    let (value, error) = adaptive(&breaks, tol * 0.5, &mut |mul| {
        // An inner error δ ≤ tol/(4·max V·μl) at every node adds at most tol/4 to E (the
        // outer variable spans [0, 1]).
        let w = v_mu(&ch, mu, mul);
        let inner_tol = tol * 0.25 / w[0].max(w[1]).max(1e-300);
        let (i, est, n) = azimuthal(&ch, mu, mul, inner_tol);
        evals += n;
        ([w[0] * i, w[1] * i], [w[0] * est, w[1] * est])
    });
    SheenE {
        value,
        error,
        evals,
    }
}

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

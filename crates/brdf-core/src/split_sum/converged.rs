#![allow(clippy::neg_cmp_op_on_partial_ord)] // NaN-aware tests: `!(x > 0)` is true for NaN.
//! Converged split sums: an integrator over the spherical cap of a lobe's visible-normal map
//! ([`crate::microfacet::visible_cap`]) with a per-integral error estimate, and the GGX
//! split sum (A, B) and Kulla–Conty E = A + B through it.
//!
//! **Coordinates.** With p(h) the density of the visible-normal map, the split-sum
//! integrals (module docs of [`crate::split_sum`]) become, for the GGX map and
//! height-correlated Smith (Heitz 2018: p(h) = G1(v)(v·h)D(h)/μ; dω_l = 4(v·h)dω_h),
//!
//! ```text
//! A = ∫ (G2/G1(v)) (1 − F_c) p dω_h,   B = ∫ (G2/G1(v)) F_c p dω_h,   F_c = (1 − v·h)⁵,
//! ```
//!
//! an integrand bounded by 1 with no peak at any roughness. On the cap (θ, φ), θ ∈ [0, θ_max],
//! φ ∈ [0, π] (the view in the x–z plane: even in φ), it is smooth except where the light
//! crosses the horizon, n·l = 0.
//!
//! **Rule.** Each φ-row is cut exactly. For the GGX split sum the sign of n·l along a row is
//! that of a trigonometric quadratic P(θ) ([`CapIntegrand::row_form`]), a quartic in
//! t = tan(θ/2) (or tan((π − θ)/2) past π/2), whose sign changes are isolated by the
//! derivative sequence and bisected (`row_cuts`); a generic integrand falls back to a
//! scan of s graded toward the cap edge refined by the Illinois method (`lit_intervals`;
//! it can miss a lit piece narrower than the scan spacing). An integrand whose support is
//! positive on the whole visible cap says so ([`CapIntegrand::uncut`]): each row is then
//! one piece [0, θ_max], and every change of the piece count between the φ scan's samples
//! becomes a φ break (`transitions`). On each lit piece the row
//! integral ∫ g sin θ dθ is taken on panels graded toward the cap edge (breaks at
//! θ_max − θ_max/4ᵏ: for small α the lobe's tail lies in a ring of width ~α there) by the
//! 15-point Gauss–Kronrod rule with its embedded 7-point Gauss–Legendre rule
//! ([`crate::quadrature::kronrod`]), halving where |K15 − G7| exceeds the panel's share of
//! the tolerance. Along φ ∈ [0, π], broken where a row's number of lit pieces changes
//! (`transitions`: I(φ) is not smooth there), the row integrals are taken by adaptive
//! K15/G7 panels whose estimate adds the panel width × its largest row estimate. The error
//! estimate returned is measure · Σ (panel estimates) + 64ε|value|: a bound as long as
//! |K15 − G7| exceeds the K15 error (it can fall short by a few times at the loosest
//! tolerances: tests/tests/split_sum_converged.rs reports such points).

use crate::geometry::{min_cos, Vec3};
use crate::microfacet::ggx::{iso_a2, lambda_radicand};
use crate::microfacet::visible_cap::{GgxVisibleCap, VisibleNormalMap};
use crate::quadrature::kronrod::{gk15_combine, gk15_nodes};
use crate::roughness::alpha_from_perceptual;
use crate::Real;

/// Halvings of a φ panel at most.
pub const MAX_PHI_DEPTH: u32 = 20;
/// Halvings of a θ interval at most.
pub const MAX_ROW_DEPTH: u32 = 30;
/// Regula falsi steps at most when locating a row's cut.
pub const MAX_CUT_STEPS: u32 = 80;
/// Below this width α the GGX split sum is its mirror limit (as [`crate::split_sum::dfg_ggx`]).
pub const MIRROR_ALPHA: f64 = 1e-7;

/// A two-channel integrand over visible normals, divided by the map's density p(h).
pub trait CapIntegrand<T: Real> {
    /// The support function: the integrand vanishes where s(h) ≤ 0 (for reflection n·l).
    fn support(&self, h: Vec3<T>) -> T;
    /// (f/p)(h) in both channels, given s = `support(h)` > 0 ([`CapIntegrand::support`]).
    fn value(&self, h: Vec3<T>, s: T) -> [T; 2];
    /// A row form of the support (for the map the integrand is paired with): coefficients
    /// k of P(θ) = k₀ + k₁ cos θ + k₂ sin θ + k₃ cos²θ + k₄ sin²θ + k₅ sin θ cos θ, a
    /// function of the sign of s along the row (cos φ, sin φ) = `(cp, sp)`, from which the
    /// cuts are found exactly (`row_cuts`). `None` (the default): the cuts are found by
    /// scanning s (`lit_intervals`).
    fn row_form(&self, _cp: T, _sp: T) -> Option<[T; 6]> {
        None
    }
    /// Whether the support is positive wherever the map is defined (no cuts): each row is
    /// then the one piece [0, θ_max] (if lit at its middle), and the φ transitions are
    /// searched on a denser scan (`transitions`). `false` (the default): the rows are cut
    /// by [`CapIntegrand::row_form`] or the scan.
    fn uncut(&self) -> bool {
        false
    }
    /// How many graded breaks θ_max − θ_max/4ᵏ a row gets toward the cap edge (`piece`):
    /// [`MAX_GRADE`] by default (to the last bit). An integrand that knows the scale of its
    /// edge ring (~α for the GGX map: deeper than that it is smooth on the panel's scale and
    /// the last panel's own halvings resolve it) may stop sooner.
    fn edge_grades(&self) -> u32 {
        MAX_GRADE
    }
}

/// A converged integral: the value, its error estimate and the work it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Converged<T> {
    /// The two channels (A, B for the split sum).
    pub value: [T; 2],
    /// The error estimate of each channel (module docs).
    pub error: [T; 2],
    /// Integrand evaluations ([`CapIntegrand::value`] calls, one per quadrature node).
    pub evals: u32,
    /// Support evaluations spent locating the cuts.
    pub cut_evals: u32,
    /// φ-rows integrated.
    pub rows: u32,
}

impl<T: Real> Converged<T> {
    fn exact(value: [T; 2], error: [T; 2]) -> Self {
        Self {
            value,
            error,
            evals: 0,
            cut_evals: 0,
            rows: 0,
        }
    }
    /// The sum of the channels and the sum of their estimates (E = A + B for the split sum).
    pub fn sum(&self) -> (T, T) {
        (self.value[0] + self.value[1], self.error[0] + self.error[1])
    }
}

/// Work counters of one integral.
#[derive(Default)]
struct Work {
    evals: u32,
    cut_evals: u32,
    rows: u32,
}

/// g(θ) sin θ at θ on the row (cos φ, sin φ): the integrand with the cap's area element.
#[inline]
fn node<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    theta: T,
    cp: T,
    sp: T,
) -> [T; 2] {
    let (st, ct) = theta.sin_cos();
    let Some(h) = map.normal(ct, st, cp, sp) else {
        return [T::ZERO; 2];
    };
    let s = f.support(h);
    if !(s > T::ZERO) {
        return [T::ZERO; 2];
    }
    let v = f.value(h, s);
    [v[0] * st, v[1] * st]
}

/// The support s along the row, −1 where the map is singular.
#[inline]
fn support_at<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    theta: T,
    cp: T,
    sp: T,
) -> T {
    let (st, ct) = theta.sin_cos();
    map.normal(ct, st, cp, sp).map_or(-T::ONE, |h| f.support(h))
}

/// The root of s in [a, b] with s(a) > 0 ≥ s(b), by the Illinois method (regula falsi
/// whose retained end's value is halved when it is kept twice in a row), to a bracket of
/// 16ε.
#[allow(clippy::too_many_arguments)]
fn refine<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    (cp, sp): (T, T),
    (mut a, mut fa): (T, T),
    (mut b, mut fb): (T, T),
    work: &mut Work,
) -> T {
    let flip = fa <= T::ZERO;
    if flip {
        // Keep s(a) > 0 by negating s.
        fa = -fa;
        fb = -fb;
    }
    let sign = if flip { -T::ONE } else { T::ONE };
    let tol = T::from_f64(16.0) * T::EPSILON;
    let mut side = 0i8;
    for _ in 0..MAX_CUT_STEPS {
        if (b - a).abs() <= tol {
            break;
        }
        let mut x = (a * fb - b * fa) / (fb - fa);
        if !((x - a) * (x - b) < T::ZERO) {
            x = (a + b) * T::HALF;
        }
        let fx = sign * support_at(map, f, x, cp, sp);
        work.cut_evals = work.cut_evals.saturating_add(1);
        if fx == T::ZERO {
            return x;
        }
        if fx > T::ZERO {
            (a, fa) = (x, fx);
            if side == 1 {
                fb *= T::HALF;
            }
            side = 1;
        } else {
            (b, fb) = (x, fx);
            if side == -1 {
                fa *= T::HALF;
            }
            side = -1;
        }
    }
    (a + b) * T::HALF
}

/// Support samples per row when looking for the lit intervals.
pub const SCAN: usize = 48;

/// The lit intervals of the row (cos φ, sin φ) (at most [`MAX_PIECES`]): s is sampled at
/// θ_k = θ_max(1 − (1 − k/SCAN)²), graded toward the cap edge, where the map's singular
/// point lies and the lit set of grazing views can fold back; each sign change is refined
/// by [`refine`].
fn lit_intervals<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    cs: (T, T),
    work: &mut Work,
) -> ([(T, T); MAX_PIECES], usize) {
    let tmax = map.theta_max();
    let mut out = [(T::ZERO, T::ZERO); MAX_PIECES];
    let mut n = 0;
    let (mut t0, mut s0) = (T::ZERO, support_at(map, f, T::ZERO, cs.0, cs.1));
    let mut start = if s0 > T::ZERO { Some(T::ZERO) } else { None };
    for k in 1..=SCAN {
        let u = T::ONE - T::from_f64(k as f64) / T::from_f64(SCAN as f64);
        let t1 = tmax * (T::ONE - u * u);
        let s1 = support_at(map, f, t1, cs.0, cs.1);
        work.cut_evals = work.cut_evals.saturating_add(1);
        if (s0 > T::ZERO) != (s1 > T::ZERO) {
            let x = refine(map, f, cs, (t0, s0), (t1, s1), work);
            match start.take() {
                Some(a) if n < MAX_PIECES => {
                    out[n] = (a, x);
                    n += 1;
                }
                Some(_) => {}
                None => start = Some(x),
            }
        }
        (t0, s0) = (t1, s1);
    }
    if let Some(a) = start {
        if n < MAX_PIECES {
            out[n] = (a, tmax);
            n += 1;
        }
    }
    (out, n)
}

/// Σ c_k x^k by Horner's rule.
#[inline]
fn horner<T: Real>(c: &[T], x: T) -> T {
    c.iter().rev().fold(T::ZERO, |acc, &ck| acc * x + ck)
}

/// Bisection steps at most per polynomial root.
pub const MAX_ROOT_STEPS: u32 = 80;

/// The points of [lo, hi] where the polynomial p = Σ c_k x^k (degree ≤ 4) changes sign
/// (from positive to not positive or back), in increasing order: isolated by the derivative
/// sequence (between consecutive sign changes of p′, found recursively, p is monotone, so
/// it changes sign at most once there), each then bisected to the last bit or
/// [`MAX_ROOT_STEPS`]. Touching zeros (no sign change) are not returned: they bound no
/// region of either sign.
fn poly_sign_changes<T: Real>(c: &[T], lo: T, hi: T, out: &mut [T; 4]) -> usize {
    let deg = c.len().saturating_sub(1).min(4);
    if deg == 0 {
        return 0;
    }
    let mut d = [T::ZERO; 4];
    for k in 1..=deg {
        d[k - 1] = c[k] * T::from_f64(k as f64);
    }
    let mut crit = [T::ZERO; 4];
    let nc = poly_sign_changes(&d[..deg], lo, hi, &mut crit);
    let (mut n, mut a) = (0, lo);
    let mut pa = horner(c, lo) > T::ZERO;
    for &b in crit[..nc].iter().chain(core::iter::once(&hi)) {
        let pb = horner(c, b) > T::ZERO;
        if pa != pb && n < 4 {
            let (mut x0, mut x1) = (a, b);
            for _ in 0..MAX_ROOT_STEPS {
                let m = (x0 + x1) * T::HALF;
                if !(m > x0 && m < x1) {
                    break;
                }
                if (horner(c, m) > T::ZERO) == pa {
                    x0 = m;
                } else {
                    x1 = m;
                }
            }
            out[n] = (x0 + x1) * T::HALF;
            n += 1;
        }
        (a, pa) = (b, pb);
    }
    n
}

/// The sign changes of P(θ) (the row form k of [`CapIntegrand::row_form`]) in (0, θ_max],
/// unsorted: with t = tan(θ/2) on θ ≤ π/2 and t = tan((π − θ)/2) on θ ≥ π/2 (t ≤ 1 on
/// both), (1 + t²)² P is the quartic q₀ + q₁t + … + q₄t⁴ with q₀ = k₀ ± k₁ + k₃,
/// q₁ = 2(k₂ ± k₅), q₂ = 2k₀ − 2k₃ + 4k₄, q₃ = 2(k₂ ∓ k₅), q₄ = k₀ ∓ k₁ + k₃ (upper signs
/// for θ ≤ π/2; cos θ = (1 − t²)/(1 + t²), sin θ = 2t/(1 + t²)), whose sign changes
/// [`poly_sign_changes`] finds.
fn row_cuts<T: Real>(k: [T; 6], tmax: T, out: &mut [T; 8]) -> usize {
    let mut n = 0;
    for (side, (lo, hi)) in [
        (T::ONE, (T::ZERO, (tmax.min(T::FRAC_PI_2) * T::HALF).tan())),
        (-T::ONE, (((T::PI - tmax) * T::HALF).tan(), T::ONE)),
    ] {
        if !(hi > lo) {
            continue;
        }
        let (k1, k5) = (side * k[1], side * k[5]);
        let q = [
            k[0] + k1 + k[3],
            T::TWO * (k[2] + k5),
            T::TWO * (k[0] - k[3]) + T::from_f64(4.0) * k[4],
            T::TWO * (k[2] - k5),
            k[0] - k1 + k[3],
        ];
        let mut r = [T::ZERO; 4];
        let nr = poly_sign_changes(&q, lo, hi, &mut r);
        for &t in &r[..nr] {
            let th = T::TWO * t.atan();
            out[n] = if side > T::ZERO { th } else { T::PI - th };
            n += 1;
        }
    }
    n
}

/// The lit intervals of the row (cos φ, sin φ) from the exact cuts of its row form `k`
/// ([`row_cuts`]; `None`: no cuts): the breakpoints 0, the cuts and θ_max, sorted; a gap
/// between two is lit where s > 0 at its midpoint, and adjacent lit gaps are merged (at
/// most [`MAX_PIECES`]).
fn lit_from_form<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    cs: (T, T),
    k: Option<[T; 6]>,
    work: &mut Work,
) -> ([(T, T); MAX_PIECES], usize) {
    let tmax = map.theta_max();
    let mut br = [T::ZERO; 10];
    let mut nc = 0;
    if let Some(k) = k {
        let mut cuts = [T::ZERO; 8];
        nc = row_cuts(k, tmax, &mut cuts);
        br[1..1 + nc].copy_from_slice(&cuts[..nc]);
    }
    br[nc + 1] = tmax;
    let br = &mut br[..nc + 2];
    br.sort_unstable_by(|a, b| a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal));
    let mut out = [(T::ZERO, T::ZERO); MAX_PIECES];
    let mut n = 0;
    for w in br.windows(2) {
        let (a, b) = (w[0].max(T::ZERO), w[1].min(tmax));
        if !(b > a) {
            continue;
        }
        work.cut_evals = work.cut_evals.saturating_add(1);
        if !(support_at(map, f, (a + b) * T::HALF, cs.0, cs.1) > T::ZERO) {
            continue;
        }
        if n > 0 && out[n - 1].1 == a {
            out[n - 1].1 = b;
        } else if n < MAX_PIECES {
            out[n] = (a, b);
            n += 1;
        }
    }
    (out, n)
}

/// Lit intervals per row at most (adjacent ones merged).
pub const MAX_PIECES: usize = 4;

/// ∫ₐᵇ g sin θ dθ on one row panel by K15, halving where |K15 − G7| > `tol` (per
/// channel; [`bisect`] to [`MAX_ROW_DEPTH`]): (value, estimate).
fn row_adapt<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    (cp, sp): (T, T),
    ab: (T, T),
    tol: T,
    work: &mut Work,
) -> ([T; 2], [T; 2]) {
    bisect(ab, tol, 0, MAX_ROW_DEPTH, &mut |a, b, tol| {
        let t = gk15_nodes(a, b);
        let mut y = [[T::ZERO; 2]; 15];
        for (y, t) in y.iter_mut().zip(&t) {
            *y = node(map, f, *t, cp, sp);
        }
        work.evals = work.evals.saturating_add(15);
        let (v, e) = gk15_combine(&y, (b - a) * T::HALF);
        // The tolerance halves with each split, so it is floored at the rounding level of
        // the panel's value: below it the estimate cannot fall, and every branch would split
        // to MAX_ROW_DEPTH (2^30 panels).
        let tol = tol.max(T::from_f64(64.0) * T::EPSILON * (v[0].abs() + v[1].abs()));
        (v, e, tol)
    })
}

/// Adaptive bisection shared by the row panels ([`row_adapt`]) and the φ panels
/// ([`phi_adapt`]): `panel(a, b, tol)` integrates [a, b] and gives (value, estimate, the
/// tolerance the panel is judged by). The panel is kept when both estimates are within
/// that tolerance, at `max_depth`, or when its midpoint no longer splits it (a panel a few
/// ulps wide); otherwise each half gets half the tolerance and the halves are summed.
fn bisect<T: Real>(
    (a, b): (T, T),
    tol: T,
    depth: u32,
    max_depth: u32,
    panel: &mut impl FnMut(T, T, T) -> ([T; 2], [T; 2], T),
) -> ([T; 2], [T; 2]) {
    let (v, e, tol) = panel(a, b, tol);
    let m = (a + b) * T::HALF;
    if (e[0] <= tol && e[1] <= tol) || depth >= max_depth || !(a < m && m < b) {
        return (v, e);
    }
    let h = tol * T::HALF;
    let (v0, e0) = bisect((a, m), h, depth + 1, max_depth, panel);
    let (v1, e1) = bisect((m, b), h, depth + 1, max_depth, panel);
    (
        [v0[0] + v1[0], v0[1] + v1[1]],
        [e0[0] + e1[0], e0[1] + e1[1]],
    )
}

/// The lit intervals of the row (cos φ, sin φ): the whole row for an uncut integrand
/// ([`CapIntegrand::uncut`]), else from the exact cuts of its row form ([`lit_from_form`]),
/// else by scanning ([`lit_intervals`]). A form that finds nothing lit is checked by the
/// scan: where the form degenerates (at μ = 1, α = 1 its quartic in tan(θ/2) loses its
/// leading term and the only cut falls on the cap edge) the scan still finds the lit cap.
fn lit<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    cs: (T, T),
    work: &mut Work,
) -> ([(T, T); MAX_PIECES], usize) {
    if f.uncut() {
        return lit_from_form(map, f, cs, None, work);
    }
    match f.row_form(cs.0, cs.1) {
        Some(k) => match lit_from_form(map, f, cs, Some(k), work) {
            (_, 0) => lit_intervals(map, f, cs, work),
            found => found,
        },
        None => lit_intervals(map, f, cs, work),
    }
}

/// One row at azimuth φ: its lit intervals, each by [`row_adapt`].
fn row<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    phi: T,
    tol: T,
    work: &mut Work,
) -> ([T; 2], [T; 2]) {
    let (sp, cp) = phi.sin_cos();
    work.rows += 1;
    let (pieces, n) = lit(map, f, (cp, sp), work);
    let (mut v, mut e) = ([T::ZERO; 2], [T::ZERO; 2]);
    for &(a, b) in &pieces[..n] {
        let (pv, pe) = piece(map, f, (cp, sp), (a, b), tol, work);
        for c in 0..2 {
            v[c] += pv[c];
            e[c] += pe[c];
        }
    }
    (v, e)
}

/// One lit piece [a, b] of a row, on panels graded toward the cap edge (module docs):
/// breaks at θ_max − θ_max/4ᵏ. Panel j gets tol · (length share + 1/K)/2 of the K panels
/// (the shares sum to tol; the tiny panels at the edge are not held to a tiny tolerance).
fn piece<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    cs: (T, T),
    (a, b): (T, T),
    tol: T,
    work: &mut Work,
) -> ([T; 2], [T; 2]) {
    let tmax = map.theta_max();
    let grades = f.edge_grades().min(MAX_GRADE);
    let mut panels = 1u32;
    let mut gap = tmax;
    for _ in 0..grades {
        gap *= T::from_f64(1.0 / EDGE_GRADE);
        let x = tmax - gap;
        if x >= b {
            break;
        }
        if x > a {
            panels += 1;
        }
    }
    let even = T::ONE / T::from_f64(panels as f64);
    let share = |len: T| tol * T::HALF * (len / (b - a) + even);
    let (mut v, mut e) = ([T::ZERO; 2], [T::ZERO; 2]);
    let mut panel = |lo: T, hi: T, work: &mut Work| {
        let (pv, pe) = row_adapt(map, f, cs, (lo, hi), share(hi - lo), work);
        for c in 0..2 {
            v[c] += pv[c];
            e[c] += pe[c];
        }
    };
    let mut lo = a;
    let mut gap = tmax;
    for _ in 0..grades {
        gap *= T::from_f64(1.0 / EDGE_GRADE);
        let hi = (tmax - gap).min(b);
        if hi > lo {
            panel(lo, hi, work);
            lo = hi;
        }
        if lo >= b {
            break;
        }
    }
    if b > lo {
        panel(lo, b, work);
    }
    (v, e)
}

/// The ratio of successive gaps θ_max − θ of the row panels' breaks (`row`).
pub const EDGE_GRADE: f64 = 4.0;
/// Graded breaks per row at most (θ_max/4³⁰ ≈ 3e-18: below the last bit).
pub const MAX_GRADE: u32 = 30;

/// ∫ₐᵇ I(φ) dφ of the row integrals I by K15 in φ, halving where the panel's estimate
/// (|K15 − G7| plus (b − a) × the largest row estimate) exceeds `tol` in either channel
/// ([`bisect`] to [`MAX_PHI_DEPTH`]).
fn phi_adapt<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    ab: (T, T),
    tol: T,
    row_tol: T,
    work: &mut Work,
) -> ([T; 2], [T; 2]) {
    bisect(ab, tol, 0, MAX_PHI_DEPTH, &mut |a, b, tol| {
        let t = gk15_nodes(a, b);
        let mut y = [[T::ZERO; 2]; 15];
        let mut worst = [T::ZERO; 2];
        for (y, t) in y.iter_mut().zip(&t) {
            let (v, e) = row(map, f, *t, row_tol, work);
            *y = v;
            worst = [worst[0].max(e[0]), worst[1].max(e[1])];
        }
        let (v, mut e) = gk15_combine(&y, (b - a) * T::HALF);
        for c in 0..2 {
            e[c] += (b - a) * worst[c];
        }
        (v, e, tol)
    })
}

/// Azimuths sampled for changes of the number of lit pieces per row (`transitions`).
pub const TRANSITION_SCAN: usize = 64;
/// Transitions located per integral at most (uncut integrands; the array's size).
pub const MAX_TRANSITIONS: usize = 24;
/// Transitions located per integral at most otherwise.
pub const SCAN_TRANSITIONS: usize = 8;

/// The lit pieces of the row at azimuth φ: (cos φ, sin φ) and how many.
fn pieces_at<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    phi: T,
    work: &mut Work,
) -> usize {
    let (sp, cp) = phi.sin_cos();
    lit(map, f, (cp, sp), work).1
}

/// The breaks of [0, π] for the φ panels: 0, the azimuths where the number of lit pieces
/// of a row changes (a piece is born or two merge: I(φ) is not smooth there, e.g. grows as
/// (φ − φ₀)^{3/2}), and π, in order; returns their count. The count is sampled at
/// [`TRANSITION_SCAN`] + 1 azimuths and each change bisected to the last bit (two changes
/// between neighbouring samples go unseen). For an uncut integrand
/// ([`CapIntegrand::uncut`]: a count is 0 or 1 and costs one support evaluation) the scan
/// is the denser [`UNCUT_TRANSITION_SCAN`], with up to [`MAX_TRANSITIONS`] breaks.
fn transitions<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    out: &mut [T; MAX_TRANSITIONS + 2],
    work: &mut Work,
) -> usize {
    let (scan, most) = if f.uncut() {
        (UNCUT_TRANSITION_SCAN, MAX_TRANSITIONS)
    } else {
        (TRANSITION_SCAN, SCAN_TRANSITIONS)
    };
    let step = T::PI / T::from_f64(scan as f64);
    let mut n = 1;
    let mut prev = pieces_at(map, f, T::ZERO, work);
    for k in 1..=scan {
        let phi = step * T::from_f64(k as f64);
        let cur = pieces_at(map, f, phi, work);
        if prev != cur && n <= most {
            let (mut a, mut b) = (phi - step, phi);
            for _ in 0..MAX_ROOT_STEPS {
                let m = (a + b) * T::HALF;
                if !(m > a && m < b) {
                    break;
                }
                if pieces_at(map, f, m, work) == prev {
                    a = m;
                } else {
                    b = m;
                }
            }
            out[n] = (a + b) * T::HALF;
            n += 1;
        }
        prev = cur;
    }
    out[n] = T::PI;
    n + 1
}

/// Azimuths sampled for transitions of an uncut integrand (`transitions`).
pub const UNCUT_TRANSITION_SCAN: usize = 256;

/// ∫ f dω_h = measure · ∫₀^π ∫₀^θc (f/p) sin θ dθ dφ for an f even in φ, to the absolute
/// tolerance `tol` per channel (module docs: K15/G7 rows, K15/G7 panels in φ, both
/// adaptive).
pub fn integrate_cap<T: Real, M: VisibleNormalMap<T>, F: CapIntegrand<T>>(
    map: &M,
    f: &F,
    tol: T,
) -> Converged<T> {
    let mut work = Work::default();
    let scale = map.measure();
    // Rows get a quarter of the tolerance in all (the panel weights sum to π), the panels
    // the rest.
    let inner = tol / scale;
    let row_tol = inner * T::from_f64(0.25) / T::PI;
    let mut brk = [T::ZERO; MAX_TRANSITIONS + 2];
    let nb = transitions(map, f, &mut brk, &mut work);
    let (mut v, mut e) = ([T::ZERO; 2], [T::ZERO; 2]);
    for w in brk[..nb].windows(2) {
        let t = inner * T::from_f64(0.75) * (w[1] - w[0]) / T::PI;
        let (pv, pe) = phi_adapt(map, f, (w[0], w[1]), t, row_tol, &mut work);
        for c in 0..2 {
            v[c] += pv[c];
            e[c] += pe[c];
        }
    }
    let mut out = Converged::exact([v[0] * scale, v[1] * scale], [T::ZERO; 2]);
    for (err, (e, v)) in out.error.iter_mut().zip(e.iter().zip(out.value)) {
        *err = *e * scale + T::from_f64(64.0) * T::EPSILON * v.abs();
    }
    out.evals = work.evals;
    out.cut_evals = work.cut_evals;
    out.rows = work.rows;
    out
}

/// The GGX split-sum integrand on visible normals: (G2/G1(v)) (1 − F_c, F_c) with
/// height-correlated Smith (module docs; Heitz 2014, "Understanding the masking-shadowing
/// function", G2 = 1/(1 + Λ(v) + Λ(l))). With R(w) = √(w_z² + α²(1 − w_z²)),
/// 1 + Λ(w) = (1 + R/w_z)/2, so G2/G1(v) = n·l (μ + R_v)/(n·l R_v + μ R_l), which
/// vanishes linearly at the cut n·l = 0.
#[derive(Clone, Copy, Debug)]
pub struct GgxSplitSum<T> {
    mu: T,
    sv: T,
    a2: T,
    rv: T,
    alpha: T,
    /// The stretched view V = (vx, 0, vz) of [`GgxVisibleCap`] for the same (α, μ).
    vx: T,
    vz: T,
}

impl<T: Real> GgxSplitSum<T> {
    /// For width α > 0 and view cosine μ ∈ (0, 1].
    pub fn new(alpha: T, mu: T) -> Self {
        let a2 = alpha * alpha;
        let sv = ((T::ONE - mu) * (T::ONE + mu)).max(T::ZERO).sqrt();
        let (x, z) = (alpha * sv, mu);
        let len = (x * x + z * z).sqrt();
        Self {
            mu,
            sv,
            a2,
            rv: lambda_radicand(mu, iso_a2(mu, alpha)).sqrt(),
            alpha,
            vx: x / len,
            vz: z / len,
        }
    }
}

impl<T: Real> CapIntegrand<T> for GgxSplitSum<T> {
    /// n·l = 2(v·h)(n·h) − μ (l = 2(v·h)h − v).
    #[inline]
    fn support(&self, h: Vec3<T>) -> T {
        let vh = self.sv * h.x + self.mu * h.z;
        T::TWO * vh * h.z - self.mu
    }
    #[inline]
    fn value(&self, h: Vec3<T>, nl: T) -> [T; 2] {
        let vh = self.sv * h.x + self.mu * h.z;
        if !(vh > T::ZERO) {
            return [T::ZERO; 2];
        }
        let nl = nl.min(T::ONE);
        let rl = (nl * nl + self.a2 * (T::ONE - nl) * (T::ONE + nl)).sqrt();
        let w = nl * (self.mu + self.rv) / (nl * self.rv + self.mu * rl);
        let fc = (T::ONE - vh).max(T::ZERO).powi(5);
        [w * (T::ONE - fc), w * fc]
    }
    /// For the map [`GgxVisibleCap`] of the same (α, μ): h ∝ h̃ = (αH_x, αH_y, H_z) with
    /// H = c + V, so n·l = 2(v·h)(n·h) − μ has the sign of
    /// P = 2(v·h̃)h̃_z − μ|h̃|² = μH_z² + 2s_vαH_xH_z − μα²(H_x² + H_y²), s_v = √(1 − μ²);
    /// with H = (sin θ cos φ + V_x, sin θ sin φ, cos θ + V_z) the row form is
    /// k = (μV_z² + 2s_vαV_xV_z − μα²V_x², 2μV_z + 2s_vαV_x, 2(s_vαV_z − μα²V_x) cos φ,
    /// μ, −μα², 2s_vα cos φ).
    fn row_form(&self, cp: T, _sp: T) -> Option<[T; 6]> {
        let (mu, sa, ma2) = (self.mu, self.sv * self.alpha, self.mu * self.a2);
        let (vx, vz) = (self.vx, self.vz);
        Some([
            mu * vz * vz + T::TWO * sa * vx * vz - ma2 * vx * vx,
            T::TWO * (mu * vz + sa * vx),
            T::TWO * (sa * vz - ma2 * vx) * cp,
            mu,
            -ma2,
            T::TWO * sa * cp,
        ])
    }
}

/// α of the split-sum row of perceptual roughness r: r clamped to [0, 1], then α = r²
/// (docs/conventions.md §8); NaN stays NaN. Shared by every texel rule of a row.
pub(crate) fn row_alpha<T: Real>(r: T) -> T {
    let r = if r.is_nan() {
        r
    } else {
        r.clamp(T::ZERO, T::ONE)
    };
    alpha_from_perceptual(r)
}

/// The texels every split-sum rule answers without integrating: NaN μ or α give NaN, μ below
/// [`min_cos`] gives (0, 0), and α ≤ [`MIRROR_ALPHA`] the mirror limit A = 1 − (1 − μ)⁵,
/// B = (1 − μ)⁵ with the estimate (α/μ)² — as `Err((values, estimates))`. Otherwise `Ok(μ)`
/// with μ clamped to 1.
pub(crate) fn texel_edges<T: Real>(mu: T, alpha: T) -> Result<T, ([T; 2], [T; 2])> {
    if mu.is_nan() || alpha.is_nan() {
        return Err(([T::NAN; 2], [T::NAN; 2]));
    }
    if !(mu >= min_cos()) {
        return Err(([T::ZERO; 2], [T::ZERO; 2]));
    }
    let mu = mu.min(T::ONE);
    if !(alpha > T::from_f64(MIRROR_ALPHA)) {
        let fc = (T::ONE - mu).powi(5);
        let e = (alpha / mu).sq();
        return Err(([T::ONE - fc, fc], [e, e]));
    }
    Ok(mu)
}

/// One roughness row of the converged GGX split-sum table: α = r² (perceptual r clamped to
/// [0, 1], docs/conventions.md §8) is fixed along it, μ varies.
#[derive(Clone, Copy, Debug)]
pub struct DfgGgxRow<T> {
    alpha: T,
}

impl<T: Real> DfgGgxRow<T> {
    /// The row of perceptual roughness r (NaN stays NaN).
    pub fn new(r: T) -> Self {
        Self {
            alpha: row_alpha(r),
        }
    }
    /// (A, B) at μ to the absolute tolerance `tol` per channel. NaN μ or r gives NaN; μ
    /// below [`min_cos`] gives (0, 0); μ > 1 is clamped. α ≤ [`MIRROR_ALPHA`] is the mirror
    /// limit A = 1 − (1 − μ)⁵, B = (1 − μ)⁵: the lobe is then narrower than the smallest
    /// angle that changes F_c, and G2/G1(v) differs from 1 by O((α/μ)²) (Λ(w) ≈
    /// α²(1 − w_z²)/(4w_z²) for small α), which is the estimate returned with it.
    pub fn texel(&self, mu: T, tol: T) -> Converged<T> {
        let mu = match texel_edges(mu, self.alpha) {
            Ok(mu) => mu,
            Err((v, e)) => return Converged::exact(v, e),
        };
        let map = GgxVisibleCap::new(self.alpha, mu);
        integrate_cap(&map, &GgxSplitSum::new(self.alpha, mu), tol)
    }
}

/// The converged GGX split sum (A, B) at (μ, r) (see [`DfgGgxRow::texel`]).
pub fn dfg_ggx_converged<T: Real>(mu: T, r: T, tol: T) -> Converged<T> {
    DfgGgxRow::new(r).texel(mu, tol)
}

/// The converged Kulla–Conty directional albedo E = A + B of GGX (α = r², F = 1) and its
/// error estimate.
pub fn e_ggx_converged<T: Real>(mu: T, r: T, tol: T) -> (T, T) {
    dfg_ggx_converged(mu, r, tol * T::HALF).sum()
}

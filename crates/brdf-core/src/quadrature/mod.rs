//! Fixed-size Gauss–Legendre quadrature.
//!
//! The node count is a compile-time constant: [`GaussLegendre<N>`] exists for the counts in
//! [`NODE_COUNTS`]. Nodes and weights live in static tables (see `tables.rs`); nothing
//! allocates. An `N`-point rule integrates polynomials of degree ≤ 2N − 1 exactly.

pub mod kronrod;
mod tables;

use crate::Real;

/// The node counts compiled in.
pub const NODE_COUNTS: [usize; 9] = [4, 6, 8, 10, 12, 16, 20, 24, 32];

/// The node count the kernels use unless told otherwise. The table in the README gives the
/// measured error of the modified G against node count; 10 is the smallest count that keeps
/// it below 1e-6 on the whole domain.
pub const DEFAULT_NODES: usize = 10;

/// An `N`-point Gauss–Legendre rule on `[-1, 1]`.
#[derive(Clone, Copy, Debug, Default)]
pub struct GaussLegendre<const N: usize>;

/// A symmetric quadrature rule given by its positive nodes.
pub trait Rule: Copy + Default {
    /// Number of nodes.
    const N: usize;
    /// Positive nodes on `[-1, 1]`, largest first (each stands for ±x).
    fn half_nodes() -> &'static [f64];
    /// Weights of [`Rule::half_nodes`].
    fn half_weights() -> &'static [f64];
    /// For each half node x, the squares of the nodes of the rule mapped to [0, 1]:
    /// [((1 − x)/2)², ((1 + x)/2)²] (computed from [`Rule::half_nodes`] in f64).
    fn half_y2() -> &'static [[f64; 2]];

    /// ∫₀ᵇ √(1 + c v²) e^{−v²} dv by this rule, for b ∈ [0, 4.6] and c ≥ 0: the slope
    /// density's integral in the working variable (see [`crate::distribution`]), with
    /// c = 2σ².
    ///
    /// On [0, b] the nodes are v = b·y with y = (1 ∓ x)/2, so v² = b²·y² and
    /// u² = c·v²: the integrand needs only z = b²·y² per node (one product with the table
    /// [`Rule::half_y2`]), e^{−z} by [`Real::exp_neg2`] and √(1 + c z) by [`Real::sqrt2`],
    /// the two nodes of a half node side by side. The sum is kept in two partial sums (the
    /// − and + nodes), added at the end. The same rule as [`Rule::integrate`] of the same
    /// integrand, differing only in rounding (relative 1e-14 in f64, from e^{−z}).
    #[inline]
    fn integrate_slope_weight<T: Real>(b: T, c: T) -> T {
        let bb = b * b;
        let mut acc = [T::ZERO; 2];
        for (y, w) in Self::half_y2().iter().zip(Self::half_weights()) {
            let z = [bb * T::from_f64(y[0]), bb * T::from_f64(y[1])];
            let e = T::exp_neg2(z);
            let s = T::sqrt2([T::ONE + c * z[0], T::ONE + c * z[1]]);
            let w = T::from_f64(*w);
            acc[0] += w * (s[0] * e[0]);
            acc[1] += w * (s[1] * e[1]);
        }
        (acc[0] + acc[1]) * (b * T::HALF)
    }

    /// ∫ₐᵇ f(x) dx. Returns 0 for `b == a`; an inverted interval gives the negated integral.
    #[inline]
    fn integrate<T: Real, F: FnMut(T) -> T>(a: T, b: T, mut f: F) -> T {
        let h = (b - a) * T::HALF;
        let m = (a + b) * T::HALF;
        let mut acc = T::ZERO;
        for (x, w) in Self::half_nodes().iter().zip(Self::half_weights()) {
            let dx = h * T::from_f64(*x);
            acc += T::from_f64(*w) * (f(m - dx) + f(m + dx));
        }
        acc * h
    }

    /// ∫ₐᵇ f(x)·g(x) dx, with the same nodes, products and order of summation as
    /// [`Rule::integrate`] applied to the integrand `g(x) * f(x)` (so the same result, bit
    /// for bit), but evaluated in passes over the nodes: the abscissae first, then f at all
    /// of them, then g. A branch-free f then runs on several nodes at once (SIMD lanes),
    /// while g, given the two abscissae m ∓ dx of a half node as a pair and returning
    /// [g(m − dx), g(m + dx)], may use two-lane operations the compiler would not form
    /// itself (such as [`Real::sqrt2`]). f is called once per node and g once per half
    /// node, in an unspecified order.
    #[inline]
    fn integrate_product<T: Real, F: FnMut(T) -> T, G: FnMut([T; 2]) -> [T; 2]>(
        a: T,
        b: T,
        mut f: F,
        mut g: G,
    ) -> T {
        // Half nodes per pass: every rule here fits in one.
        const CHUNK: usize = 16;
        let h = (b - a) * T::HALF;
        let m = (a + b) * T::HALF;
        let mut acc = T::ZERO;
        for (xs, ws) in Self::half_nodes()
            .chunks(CHUNK)
            .zip(Self::half_weights().chunks(CHUNK))
        {
            let n = 2 * xs.len().min(ws.len());
            // The abscissae m − dx, m + dx of each half node, side by side.
            let mut t = [T::ZERO; 2 * CHUNK];
            for (p, x) in t.chunks_exact_mut(2).zip(xs) {
                let dx = h * T::from_f64(*x);
                p[0] = m - dx;
                p[1] = m + dx;
            }
            let mut y = [T::ZERO; 2 * CHUNK];
            for (y, t) in y[..n].iter_mut().zip(&t[..n]) {
                *y = f(*t);
            }
            for (y, t) in y[..n].chunks_exact_mut(2).zip(t[..n].chunks_exact(2)) {
                let gt = g([t[0], t[1]]);
                y[0] = gt[0] * y[0];
                y[1] = gt[1] * y[1];
            }
            for (p, w) in y[..n].chunks_exact(2).zip(ws) {
                acc += T::from_f64(*w) * (p[0] + p[1]);
            }
        }
        acc * h
    }
}

/// [((1 − x)/2)², ((1 + x)/2)²] for each half node x (see [`Rule::half_y2`]).
const fn y2<const H: usize>(x: &[f64; H]) -> [[f64; 2]; H] {
    let mut out = [[0.0; 2]; H];
    let mut i = 0;
    while i < H {
        let lo = (1.0 - x[i]) * 0.5;
        let hi = (1.0 + x[i]) * 0.5;
        out[i] = [lo * lo, hi * hi];
        i += 1;
    }
    out
}

macro_rules! rule {
    ($n:literal, $x:ident, $w:ident) => {
        impl Rule for GaussLegendre<$n> {
            const N: usize = $n;
            #[inline]
            fn half_nodes() -> &'static [f64] {
                &tables::$x
            }
            #[inline]
            fn half_weights() -> &'static [f64] {
                &tables::$w
            }
            #[inline]
            fn half_y2() -> &'static [[f64; 2]] {
                static Y2: [[f64; 2]; $n / 2] = y2(&tables::$x);
                &Y2
            }
        }
    };
}
rule!(4, X4, W4);
rule!(6, X6, W6);
rule!(8, X8, W8);
rule!(10, X10, W10);
rule!(12, X12, W12);
rule!(16, X16, W16);
rule!(20, X20, W20);
rule!(24, X24, W24);
rule!(32, X32, W32);

/// The default rule.
pub type DefaultRule = GaussLegendre<DEFAULT_NODES>;

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Calls `$f::<GaussLegendre<N>>()` for every tabulated N (the `rule!` list above).
    macro_rules! for_every_rule {
        ($f:ident) => {
            $f::<GaussLegendre<4>>();
            $f::<GaussLegendre<6>>();
            $f::<GaussLegendre<8>>();
            $f::<GaussLegendre<10>>();
            $f::<GaussLegendre<12>>();
            $f::<GaussLegendre<16>>();
            $f::<GaussLegendre<20>>();
            $f::<GaussLegendre<24>>();
            $f::<GaussLegendre<32>>();
        };
    }
    use std::vec::Vec;

    /// Legendre P_n and P_n' by the three-term recurrence.
    fn legendre(n: usize, x: f64) -> (f64, f64) {
        let (mut p0, mut p1) = (1.0, x);
        for k in 2..=n {
            let k = k as f64;
            let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
            p0 = p1;
            p1 = p2;
        }
        let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
        (p1, dp)
    }

    /// Independent recomputation: bracket each root of P_n by sign changes on a fine grid,
    /// bisect, then weight from the derivative.
    fn recompute(n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut xs = Vec::new();
        let steps = 20000;
        let mut prev = legendre(n, 1.0 - 1e-15).0;
        for i in 1..=steps {
            let x = 1.0 - 1e-15 - (i as f64) * (1.0 - 1e-15) / steps as f64;
            let p = legendre(n, x).0;
            if p == 0.0 || p.signum() != prev.signum() {
                let (mut lo, mut hi) = (x, x + (1.0 - 1e-15) / steps as f64);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if legendre(n, mid).0.signum() == legendre(n, hi).0.signum() {
                        hi = mid
                    } else {
                        lo = mid
                    }
                }
                xs.push(0.5 * (lo + hi));
            }
            prev = p;
            if xs.len() == n / 2 {
                break;
            }
        }
        let ws = xs
            .iter()
            .map(|&x| {
                let dp = legendre(n, x).1;
                2.0 / ((1.0 - x * x) * dp * dp)
            })
            .collect();
        (xs, ws)
    }

    fn check<R: Rule>() {
        let (xs, ws) = recompute(R::N);
        assert_eq!(xs.len(), R::half_nodes().len());
        for (a, b) in xs.iter().zip(R::half_nodes()) {
            assert!((a - b).abs() < 1e-14, "N={} node {a} vs {b}", R::N);
        }
        for (a, b) in ws.iter().zip(R::half_weights()) {
            assert!((a - b).abs() < 1e-13, "N={} weight {a} vs {b}", R::N);
        }
        // Exactness on x^k, k ≤ 2N−1, over [0, 1]: ∫ x^k = 1/(k+1).
        for k in 0..(2 * R::N) {
            let got: f64 = R::integrate(0.0, 1.0, |x: f64| x.powi(k as i32));
            assert!(
                (got - 1.0 / (k as f64 + 1.0)).abs() < 1e-13,
                "N={} k={k}",
                R::N
            );
        }
    }

    #[test]
    fn tables_match_recomputation() {
        for_every_rule!(check);
    }

    /// The split-pass product rule: against the closed form ∫₀¹ x eˣ dx = 1, and bit for bit
    /// against the one-pass rule on the product integrand (its documented promise), in f64
    /// and f32, for a rule of one pass (10 nodes) and one of two passes (32 nodes).
    #[test]
    fn integrate_product_matches_closed_form_and_one_pass_rule() {
        // tol: the rule's own error on x eˣ over [0, 1] (4 nodes: 7.9e-9 measured; ≥ 10
        // nodes: below rounding).
        fn both<R: Rule>(tol: f64) {
            let split: f64 = R::integrate_product(0.0, 1.0, |x: f64| x.exp(), |x: [f64; 2]| x);
            let one: f64 = R::integrate(0.0, 1.0, |x: f64| x * x.exp());
            assert_eq!(split.to_bits(), one.to_bits(), "N={}", R::N);
            assert!((split - 1.0).abs() < tol, "N={}: {split}", R::N);
            let split32: f32 = R::integrate_product(
                0.25f32,
                2.0,
                |x: f32| (-x * x).exp(),
                |x: [f32; 2]| [x[0].sqrt(), x[1].sqrt()],
            );
            let one32: f32 = R::integrate(0.25f32, 2.0, |x: f32| x.sqrt() * (-x * x).exp());
            assert_eq!(split32.to_bits(), one32.to_bits(), "N={}", R::N);
        }
        both::<GaussLegendre<10>>(1e-14);
        both::<GaussLegendre<32>>(1e-14);
        both::<GaussLegendre<4>>(1e-8);
    }

    /// The slope-weight integral in f64 (squared nodes from the table, the two-lane
    /// exponential) against the one-pass rule on the same integrand with libm's `exp` and
    /// `sqrt` (the same rule, so they differ by rounding only: the integrand's relative
    /// error is below 25ε ≈ 5.6e-15, see [`crate::real::exp_neg_f64`], and the sum of
    /// positive terms keeps it; 1e-14 relative allowed), for every rule, b ∈ [0, 4.6] and
    /// c from 0 to 2·10² (σ up to 10); and at c = 0 against the closed form
    /// ∫₀ᵇ e^{−v²} dv = (√π/2) erf b with the 32-point rule (whose own error on this
    /// Gaussian is below 1e-15 for b ≤ 4.6). In f32 it is the one-pass rule on
    /// √(1 + c v²)·e^{−v²} with the f32 exponential, to f32 rounding.
    #[test]
    fn slope_weight_integral_matches_one_pass_rule_and_closed_form() {
        fn one<R: Rule>() {
            let mut worst = 0f64;
            for i in 0..=460 {
                let b = i as f64 * 0.01;
                for c in [0.0, 0.005, 0.18, 2.0, 200.0] {
                    let got = R::integrate_slope_weight(b, c);
                    let want = R::integrate(0.0, b, |v: f64| {
                        libm::sqrt(1.0 + c * v * v) * libm::exp(-(v * v))
                    });
                    if want > 0.0 {
                        worst = worst.max((got - want).abs() / want);
                    } else {
                        assert_eq!(got, 0.0);
                    }
                    let got32 = R::integrate_slope_weight(b as f32, c as f32) as f64;
                    assert!((got32 - want).abs() <= 1e-5 * want, "N={} f32", R::N);
                }
            }
            assert!(
                worst <= 1e-14,
                "N={}: max relative difference {worst:e}",
                R::N
            );
        }
        for_every_rule!(one);
        for i in 0..=46 {
            let b = i as f64 * 0.1;
            let got = GaussLegendre::<32>::integrate_slope_weight(b, 0.0);
            let want = 0.5 * core::f64::consts::PI.sqrt() * libm::erf(b);
            assert!((got - want).abs() <= 1e-15, "b={b}: {got} vs {want}");
        }
        assert!(GaussLegendre::<10>::integrate_slope_weight(f64::NAN, 0.1).is_nan());
    }

    #[test]
    fn integrates_a_transcendental_to_closed_form() {
        // ∫₀^π sin = 2
        let got: f64 = GaussLegendre::<16>::integrate(0.0, core::f64::consts::PI, |x: f64| x.sin());
        assert!((got - 2.0).abs() < 1e-14);
        let got32: f32 = GaussLegendre::<12>::integrate(0.0f32, 1.0, |x: f32| x.exp());
        assert!((got32 as f64 - (1f64.exp() - 1.0)).abs() < 1e-6);
    }
}

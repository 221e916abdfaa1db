//! Beckmann visible normals: h distributed as G1(wo) max(wo·h, 0) D(h)/cos θo, with the
//! anisotropic Beckmann D of widths (ax, ay) ([`super::Beckmann`]) and the Smith
//! G1 = 1/(1 + Λ) of the projected width (docs/conventions.md §6).
//!
//! Derivation (slope space, the same stretch as for GGX): scaling the slopes by 1/ax, 1/ay
//! turns D into the unit-width P22(x, y) = e^{−x²−y²}/π and wo into v = normalise(ax wo.x,
//! ay wo.y, wo.z). In the frame where v lies in the x–z plane at polar angle θ, a facet of
//! slope (x, y) has normal ∝ (−x, −y, 1) and projected area ∝ (cos θ − x sin θ)₊, so the
//! visible slopes have density ∝ (cos θ − x sin θ)₊ e^{−x²} e^{−y²}:
//!
//! ```text
//! y: (1 + erf y)/2 = u₁                                      (a standard normal / √2)
//! x: F(x) = u₀ F(cot θ),  F(x) = cos θ (1 + erf x)/2 + sin θ e^{−x²}/(2√π),  x ≤ cot θ
//! ```
//!
//! (F′(x) = (cos θ − x sin θ) e^{−x²}/√π.) Neither inverse has a closed form; both are
//! solved by Newton's method kept inside a shrinking bracket (bisection when a step leaves
//! it), which converges for every u because F is increasing on the bracket. The slopes are
//! then rotated back by v's azimuth and unstretched, and h = normalise(−x, −y, 1).

use crate::geometry::Vec3;
use crate::sampling::unit;
use crate::Real;

/// 1/√π.
const FRAC_1_SQRT_PI: f64 = 0.564_189_583_547_756_3;
/// Slopes beyond ±6 carry less than e^{−36} of the density: the search bracket.
const SLOPE_MAX: f64 = 6.0;
/// Newton/bisection steps; convergence is quadratic, so this bound is never reached in
/// f64 for reasonable tolerances and bounds the work in f32.
const MAX_STEPS: usize = 60;

/// Solves F(x) = target for x in [lo, hi] with F increasing, F′ = `dfx`.
fn solve_increasing<T: Real>(
    fx: impl Fn(T) -> T,
    dfx: impl Fn(T) -> T,
    target: T,
    mut lo: T,
    mut hi: T,
) -> T {
    let tol = T::EPSILON * T::from_f64(16.0);
    let mut x = T::ZERO.clamp(lo, hi);
    for _ in 0..MAX_STEPS {
        let r = fx(x) - target;
        if r > T::ZERO {
            hi = x;
        } else {
            lo = x;
        }
        let d = dfx(x);
        let newton = x - r / d;
        let next = if d > T::ZERO && newton > lo && newton < hi {
            newton
        } else {
            T::HALF * (lo + hi)
        };
        let done = (next - x).abs() <= tol * (T::ONE + x.abs()) || hi - lo <= tol;
        x = next;
        if done {
            break;
        }
    }
    x
}

/// The y slope of the unit-width configuration: (1 + erf y)/2 = u.
fn unit_gaussian_slope<T: Real>(u: T) -> T {
    let c = T::from_f64(FRAC_1_SQRT_PI);
    let m = T::from_f64(SLOPE_MAX);
    solve_increasing(
        |y: T| T::HALF * (T::ONE + y.erf()),
        |y: T| c * (-(y * y)).exp(),
        u,
        -m,
        m,
    )
}

/// The x slope for a view at polar angle θ (cos θ = `c`, sin θ = `s`, both ≥ 0) in the
/// unit-width configuration.
fn visible_x_slope<T: Real>(c: T, s: T, u: T) -> T {
    let k = T::from_f64(FRAC_1_SQRT_PI);
    let m = T::from_f64(SLOPE_MAX);
    let f = |x: T| c * T::HALF * (T::ONE + x.erf()) + s * T::HALF * k * (-(x * x)).exp();
    let df = |x: T| (c - x * s).max(T::ZERO) * k * (-(x * x)).exp();
    // The slope x = cot θ faces away from v: the upper end of the support.
    let hi = if s * m > c { c / s } else { m };
    solve_increasing(f, df, u * f(hi), -m, hi)
}

/// The sampler behind [`super::Beckmann`]'s visible normals (wo checked by the caller).
pub(crate) fn sample<T: Real>(wo: Vec3<T>, ax: T, ay: T, u: [T; 2]) -> Option<Vec3<T>> {
    // Stretch to unit width.
    let v = Vec3::new(ax * wo.x, ay * wo.y, wo.z).normalize()?;
    let s = (v.x * v.x + v.y * v.y).sqrt();
    let (cp, sp) = if s > T::ZERO {
        (v.x / s, v.y / s)
    } else {
        (T::ONE, T::ZERO)
    };
    let x = visible_x_slope(v.z, s, unit(u[0]));
    let y = unit_gaussian_slope(unit(u[1]));
    // Rotate back by v's azimuth, unstretch.
    let sx = ax * (cp * x - sp * y);
    let sy = ay * (sp * x + cp * y);
    Vec3::new(-sx, -sy, T::ONE).normalize()
}

//! Directional albedo R(wo) = ∫ f(wi, wo) cos θi dωi over the upper hemisphere, by a
//! fixed-size quadrature that follows the lobe (no Monte Carlo, no allocation). Reused by
//! the tables.
//!
//! Parametrisation. Every lobe here (Phong about the mirror direction, Blinn-Phong,
//! Beckmann, GGX, Ward, Ashikhmin–Shirley) peaks at the half vector h = n. The integral is
//! taken over h, written by its slopes x = (p, q), h = (p, q, 1)/√(1 + p² + q²), with
//! wi = 2(wo·h)h − wo (FCG eq 24.11), dωi = 4(wo·h) dωh (eq 24.12) and
//! dωh = cos³θh dp dq. Then:
//!
//! * The horizon is exact. wi·n > 0 ⇔ |x − c|² < 1/B², c = wo_t/B, B = cos θo (a disc in
//!   slope space that contains the lobe centre x = 0), so along a ray x = t e from the lobe
//!   centre the upper limit is t_max = c·e + √((c·e)² + 1): the integrand is smooth on the
//!   whole domain, with no kink at the horizon.
//! * The lobe is followed. Slopes are stretched by the model's [`LobeHint`] (ax, ay):
//!   x = s (ax cos ψ, ay sin ψ), so a lobe of any width or anisotropy has unit width in s.
//!   s runs over geometrically graded panels [0, 1/8], [1/8, √2/8], … up to s_max/2 (at
//!   most [`RADIAL_PANELS`] panels, enough for widths down to 1e-4 and any grazing angle),
//!   then over [`HORIZON_LEVELS`] panels graded toward s_max (the horizon of wi, where
//!   height-correlated masking changes on the scale of cos θo for grazing views);
//!   ψ runs over four quarters split where c·e = 0 (where t_max changes fastest for grazing
//!   wo) and where e points along ±c (toward the back-scattering region h ≈ wo, where
//!   the integrand varies on a scale 1/tan θo), each quarter graded toward both ends
//!   ([`AZIMUTH_LEVELS`] levels per end).
//! * Each panel uses the 16-point Gauss–Legendre rule: 8·AZIMUTH_LEVELS·16 azimuths times
//!   at most (RADIAL_PANELS + HORIZON_LEVELS)·16 radii; typically 1024 × 400 evaluations.
//!
//! Measured against an adaptive reference (tests/tests/models_albedo.rs): ≤ 5e-6 for GGX,
//! Phong, Blinn-Phong, Ashikhmin–Shirley, Ward and the layered models up to θo = 89°;
//! ≤ 3.2e-5 for Cook–Torrance, whose V-groove G has kinks inside the panels.
//!
//! A Dirac part ([`Brdf::delta`]) adds its reflectance. wo at or below the horizon (or not
//! finite) gives 0.

// `!(x > 0)` is deliberate throughout: it is true for NaN as well.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::geometry::Vec3;
use crate::models::{Brdf, LobeHint, Rgb};
use crate::quadrature::{GaussLegendre, Rule};
use crate::Real;

/// Graded azimuth levels per arc end.
pub const AZIMUTH_LEVELS: usize = 8;
/// Radial panels at most from the lobe centre to s_max/2 (edges 1/8 · √2^j of the lobe
/// width).
pub const RADIAL_PANELS: usize = 60;
/// Radial panels graded toward the horizon end, from s_max/2 to s_max (edges
/// s_max − (s_max/2)·√2^{−k}).
pub const HORIZON_LEVELS: usize = 16;

type Gl = GaussLegendre<16>;

/// R(wo) for the model's own lobe hint (see the module docs).
pub fn directional_albedo<T: Real, B: Brdf<T> + ?Sized>(b: &B, wo: Vec3<T>) -> Rgb<T> {
    directional_albedo_with(b, wo, b.lobe_hint())
}

/// R(wo) with an explicit lobe hint.
pub fn directional_albedo_with<T: Real, B: Brdf<T> + ?Sized>(
    b: &B,
    wo: Vec3<T>,
    hint: LobeHint<T>,
) -> Rgb<T> {
    let wo = match wo.normalize() {
        Some(w) if w.z > T::ZERO => w,
        _ => return Rgb::zero(),
    };
    let mut acc = continuous(b, wo, hint);
    if let Some(d) = b.delta(wo) {
        acc = acc.add(d.reflectance);
    }
    acc
}

/// The continuous part ∫ f cos θi dωi.
fn continuous<T: Real, B: Brdf<T> + ?Sized>(b: &B, wo: Vec3<T>, hint: LobeHint<T>) -> Rgb<T> {
    let (ax, ay) = (hint.ax, hint.ay);
    let bz = wo.z;
    let (cx, cy) = (wo.x / bz, wo.y / bz);
    // The stretched azimuth where the ray direction is perpendicular to wo_t.
    let psi0 = if wo.x * wo.x + wo.y * wo.y > T::ZERO {
        (-(ax * wo.x)).atan2(ay * wo.y)
    } else {
        T::ZERO
    };
    let eighth = T::FRAC_PI_2 * T::HALF;
    let mut acc = Rgb::zero();
    for quarter in 0..4 {
        let start = psi0 + T::FRAC_PI_2 * T::from_f64(quarter as f64);
        // Edges graded toward both ends of [start, start + π/2]: offsets
        // (π/4)·2^{-(L-1)}, …, π/4, then mirrored.
        let mut d_prev = T::ZERO;
        for k in 0..(2 * AZIMUTH_LEVELS) {
            let d_next = if k < AZIMUTH_LEVELS {
                eighth / T::TWO.powi((AZIMUTH_LEVELS - 1 - k) as u32)
            } else {
                let j = 2 * AZIMUTH_LEVELS - 1 - k; // AZIMUTH_LEVELS-1 … 0
                if j == 0 {
                    T::FRAC_PI_2
                } else {
                    T::FRAC_PI_2 - eighth / T::TWO.powi(j as u32)
                }
            };
            let (a, c) = (start + d_prev, start + d_next);
            d_prev = d_next;
            acc = acc.add(integrate_rgb(a, c, |psi| {
                radial(b, wo, ax, ay, cx, cy, psi)
            }));
        }
    }
    acc
}

/// ∫ over s along one stretched azimuth ψ.
#[allow(clippy::too_many_arguments)]
fn radial<T: Real, B: Brdf<T> + ?Sized>(
    b: &B,
    wo: Vec3<T>,
    ax: T,
    ay: T,
    cx: T,
    cy: T,
    psi: T,
) -> Rgb<T> {
    let (ex, ey) = (ax * psi.cos(), ay * psi.sin());
    let l = (ex * ex + ey * ey).sqrt();
    if !(l > T::ZERO) {
        return Rgb::zero();
    }
    let ce = (cx * ex + cy * ey) / l;
    let t_max = ce + (ce * ce + T::ONE).sqrt();
    // For ce ≫ 1 the sum above is exact; for ce ≪ −1 use the cancellation-free form.
    let t_max = if ce < T::ZERO {
        T::ONE / ((ce * ce + T::ONE).sqrt() - ce)
    } else {
        t_max
    };
    let s_max = t_max / l;
    let four = T::from_f64(4.0);
    let g = |s: T| -> Rgb<T> {
        let (p, q) = (s * ex, s * ey);
        let n2 = T::ONE + p * p + q * q;
        let inv = T::ONE / n2.sqrt();
        let h = Vec3::new(p * inv, q * inv, inv);
        let oh = wo.dot(h);
        let wi = h.scale(T::TWO * oh).sub(wo);
        if !(wi.z > T::ZERO) || !(oh > T::ZERO) {
            return Rgb::zero();
        }
        // dωi = 4(wo·h) cos³θh · ax ay s ds dψ
        let jac = four * oh * inv * inv * inv * ax * ay * s;
        b.eval(wi, wo).scale(wi.z * jac)
    };
    let mut acc = Rgb::zero();
    // Panels graded away from the lobe centre, up to half of s_max …
    let split = s_max * T::HALF;
    let mut lo = T::ZERO;
    let mut hi = T::from_f64(0.125);
    for _ in 0..RADIAL_PANELS {
        if lo >= split {
            break;
        }
        let top = hi.min(split);
        acc = acc.add(integrate_rgb(lo, top, g));
        lo = top;
        hi *= T::from_f64(core::f64::consts::SQRT_2);
    }
    if lo < split {
        acc = acc.add(integrate_rgb(lo, split, g));
    }
    // … then graded toward the horizon end s_max, where masking terms change on the scale
    // of cos θo at grazing views.
    let span = s_max - split;
    let mut a = split;
    for k in 1..=HORIZON_LEVELS {
        let b2 = if k == HORIZON_LEVELS {
            s_max
        } else {
            s_max - span * T::from_f64(core::f64::consts::FRAC_1_SQRT_2).powi(k as u32)
        };
        acc = acc.add(integrate_rgb(a, b2, g));
        a = b2;
    }
    acc
}

/// The Gauss–Legendre rule `Gl` applied to a colour-valued integrand.
#[inline]
fn integrate_rgb<T: Real, F: FnMut(T) -> Rgb<T>>(a: T, b: T, mut f: F) -> Rgb<T> {
    let h = (b - a) * T::HALF;
    let m = (a + b) * T::HALF;
    let mut acc = Rgb::zero();
    for (x, w) in Gl::half_nodes().iter().zip(Gl::half_weights()) {
        let dx = h * T::from_f64(*x);
        let w = T::from_f64(*w);
        acc = acc.add(f(m - dx).add(f(m + dx)).scale(w));
    }
    acc.scale(h)
}

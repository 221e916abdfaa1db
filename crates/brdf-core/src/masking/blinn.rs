//! Blinn's V-groove geometric attenuation factor, eq 4 of the paper (after Blinn 1977):
//! G = min(1, 2 cos α cos θr / cos β, 2 cos α cos θi / cos β).

use crate::geometry::Dots;
use crate::Real;

/// Eq 4 from the paper's in-plane angles (radians; θi ∈ [0, π/2], θr ∈ [−π/2, π/2] signed,
/// clamped to those ranges). α = (θr − θi)/2 and β = (θi + θr)/2. NaN in, NaN out.
pub fn g_blinn<T: Real>(theta_i: T, theta_r: T) -> T {
    let ti = crate::geometry::clamp_theta_i(theta_i);
    let tr = crate::geometry::clamp_theta_r(theta_r);
    let ca = ((tr - ti) * T::HALF).cos();
    let cb = ((tr + ti) * T::HALF).cos();
    g_blinn_cos(ca, ti.cos(), tr.cos(), cb)
}

/// Eq 4 from dot products (shader form): n·h = cos α, wo·h = cos β, both from
/// [`Dots::n_h`]/[`Dots::i_h`] (accurate near the horizon when the dots were built from the
/// vectors or with n·h). Returns 0 for a pair with either direction at or below the horizon.
pub fn g_blinn_dots<T: Real>(d: Dots<T>) -> T {
    g_blinn_cos(d.n_h(), d.n_i, d.n_o, d.i_h())
}

/// min(1, 2(n·h)(n·wo)/(wo·h), 2(n·h)(n·wi)/(wo·h)), clamped to [0, 1].
#[inline]
pub(crate) fn g_blinn_cos<T: Real>(n_h: T, n_i: T, n_o: T, o_h: T) -> T {
    if n_h.is_nan() || n_i.is_nan() || n_o.is_nan() || o_h.is_nan() {
        return T::NAN;
    }
    if !(n_i > T::ZERO) || !(n_o > T::ZERO) || !(o_h > T::ZERO) {
        return T::ZERO;
    }
    let k = T::TWO * n_h / o_h;
    T::ONE.min(k * n_o).min(k * n_i).max(T::ZERO)
}

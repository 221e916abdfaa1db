//! The brdf-core kernels the Cortex-M4F firmware (`crates/brdf-firmware`) runs, each behind
//! one non-inlined function taking and returning plain `f32`s.
//!
//! A library of its own so that the device and the host run the very same source: the
//! firmware links it for the device, and `cargo xtask firmware` links it on the host to
//! recompute every value the device printed. Keeping every call into brdf-core in this crate
//! (and out of the firmware's `main`) lets the size report attribute flash to "kernels"
//! (symbols of `brdf_core`, `libm`, `micromath` and this crate) separately from the
//! formatting code (`core::fmt`, semihosting) by symbol name. Invalid parameters give NaN,
//! never a panic.
//!
//! With the `micromath` feature the kernels compute in [`brdf_core::real::Micro`] (micromath
//! where it keeps a kernel within 2e-2 of libm, libm elsewhere); otherwise in `f32` with libm.
//! The functions' signatures are plain `f32` either way.

#![no_std]
// In the libm build `F` is `f32` and the conversions are the identity.
#![allow(clippy::useless_conversion)]

/// The scalar the kernels compute in.
#[cfg(feature = "micromath")]
type F = brdf_core::real::Micro;
/// The scalar the kernels compute in.
#[cfg(not(feature = "micromath"))]
type F = f32;

#[inline(always)]
fn f(x: f32) -> F {
    F::from(x)
}

use brdf_core::fresnel::Fresnel;
use brdf_core::masking::ModifiedG;
use brdf_core::models::{AshikhminShirley, Brdf, GeometricTerm, Rgb, TorranceSparrow};
use brdf_core::{Dots, Vec3};
use brdf_lut::GTable;

/// The paper's modified G = min(GM, GS) (eq 13, reciprocal convention, docs/conventions.md §4)
/// for RMS slope `sigma` and in-plane angles θi ∈ [0, π/2], θr ∈ [−π/2, π/2] (radians).
#[inline(never)]
pub fn g_direct(sigma: f32, theta_i: f32, theta_r: f32) -> f32 {
    match ModifiedG::<F>::new(f(sigma)) {
        Ok(g) => g.g(f(theta_i), f(theta_r)).into(),
        Err(_) => f32::NAN,
    }
}

/// Validates a per-σ G table (magic, version, header limits, payload length, CRC-32;
/// docs/lut-format.md) and borrows it: zero-copy, no allocation. `None` on any defect.
#[inline(never)]
pub fn g_table(bytes: &[u8]) -> Option<GTable<&[u8]>> {
    GTable::parse(bytes).ok()
}

/// The modified G (reciprocal convention) looked up in a per-σ table at in-plane angles
/// θi, θr (radians), interpolated as the table's header says.
#[inline(never)]
pub fn g_lut(table: &GTable<&[u8]>, theta_i: f32, theta_r: f32) -> f32 {
    table.g(theta_i, theta_r)
}

/// The modified G from the dot products n·wi, n·wo, wi·wo (shader form, 3-D extension).
#[inline(never)]
pub fn g_dots(sigma: f32, n_i: f32, n_o: f32, i_o: f32) -> f32 {
    match ModifiedG::<F>::new(f(sigma)) {
        Ok(g) => g.g_dots(Dots::new(f(n_i), f(n_o), f(i_o))).into(),
        Err(_) => f32::NAN,
    }
}

/// The Torrance–Sparrow BRDF (paper eq 3, docs/conventions.md §5) in 1/sr with the modified G,
/// Beckmann D (m = √2σ), Schlick Fresnel with normal reflectance `r0`, k_s = 1 and a
/// Lambertian term of albedo `albedo`, from the dot products.
#[inline(never)]
pub fn torrance_sparrow(sigma: f32, r0: f32, albedo: f32, n_i: f32, n_o: f32, i_o: f32) -> f32 {
    let Ok(fresnel) = Fresnel::schlick(f(r0)) else {
        return f32::NAN;
    };
    match TorranceSparrow::<F>::new(
        f(sigma),
        GeometricTerm::Modified,
        fresnel,
        f(1.0),
        f(albedo),
    ) {
        Ok(ts) => ts.eval_dots(Dots::new(f(n_i), f(n_o), f(i_o))).into(),
        Err(_) => f32::NAN,
    }
}

/// The anisotropic Ashikhmin–Shirley BRDF (FCG eqs 24.5–24.9) in 1/sr, grey (the same R_s,
/// R_d in every channel; the red channel is returned), exponents `nu` along the local x axis
/// and `nv` along y, for local-frame unit directions wi = `wi`, wo = `wo` (z = normal).
#[inline(never)]
pub fn ashikhmin_shirley(rs: f32, rd: f32, nu: f32, nv: f32, wi: [f32; 3], wo: [f32; 3]) -> f32 {
    match AshikhminShirley::<F>::new(Rgb::splat(f(rs)), Rgb::splat(f(rd)), f(nu), f(nv)) {
        Ok(m) => m
            .eval(
                Vec3::new(f(wi[0]), f(wi[1]), f(wi[2])),
                Vec3::new(f(wo[0]), f(wo[1]), f(wo[2])),
            )
            .r
            .into(),
        Err(_) => f32::NAN,
    }
}

//! The brdf-core kernels this firmware runs, each behind one non-inlined function taking and
//! returning plain `f32`s.
//!
//! Keeping every call into brdf-core in this module (and out of `main`) lets
//! `cargo xtask firmware` attribute flash to "kernels" (symbols of `brdf_core`, `libm`,
//! `micromath` and this module) separately from the formatting code (`core::fmt`,
//! semihosting) by symbol name. Invalid parameters give NaN, never a panic.

use brdf_core::fresnel::Fresnel;
use brdf_core::masking::ModifiedG;
use brdf_core::models::{AshikhminShirley, Brdf, GeometricTerm, Rgb, TorranceSparrow};
use brdf_core::{Dots, Vec3};
use brdf_lut::GTable;

/// The paper's modified G = min(GM, GS) (eq 13, reciprocal convention, conventions.md §4)
/// for RMS slope `sigma` and in-plane angles θi ∈ [0, π/2], θr ∈ [−π/2, π/2] (radians).
#[inline(never)]
pub fn g_direct(sigma: f32, theta_i: f32, theta_r: f32) -> f32 {
    match ModifiedG::<f32>::new(sigma) {
        Ok(g) => g.g(theta_i, theta_r),
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
    match ModifiedG::<f32>::new(sigma) {
        Ok(g) => g.g_dots(Dots { n_i, n_o, i_o }),
        Err(_) => f32::NAN,
    }
}

/// The Torrance–Sparrow BRDF (paper eq 3, conventions.md §5) in 1/sr with the modified G,
/// Beckmann D (m = √2σ), Schlick Fresnel with normal reflectance `r0`, k_s = 1 and a
/// Lambertian term of albedo `albedo`, from the dot products.
#[inline(never)]
pub fn torrance_sparrow(sigma: f32, r0: f32, albedo: f32, n_i: f32, n_o: f32, i_o: f32) -> f32 {
    let Ok(fresnel) = Fresnel::schlick(r0) else {
        return f32::NAN;
    };
    match TorranceSparrow::<f32>::new(sigma, GeometricTerm::Modified, fresnel, 1.0, albedo) {
        Ok(ts) => ts.eval_dots(Dots { n_i, n_o, i_o }),
        Err(_) => f32::NAN,
    }
}

/// The anisotropic Ashikhmin–Shirley BRDF (FCG eqs 24.5–24.9) in 1/sr, grey (the same R_s,
/// R_d in every channel; the red channel is returned), exponents `nu` along the local x axis
/// and `nv` along y, for local-frame unit directions wi = `wi`, wo = `wo` (z = normal).
#[inline(never)]
pub fn ashikhmin_shirley(rs: f32, rd: f32, nu: f32, nv: f32, wi: [f32; 3], wo: [f32; 3]) -> f32 {
    match AshikhminShirley::<f32>::new(Rgb::splat(rs), Rgb::splat(rd), nu, nv) {
        Ok(m) => {
            m.eval(
                Vec3::new(wi[0], wi[1], wi[2]),
                Vec3::new(wo[0], wo[1], wo[2]),
            )
            .r
        }
        Err(_) => f32::NAN,
    }
}

//! A lit sphere, rendered per pixel with a model's BRDF (what the web example draws).
//!
//! Orthographic camera looking down −z at a unit sphere that fills the square image; viewer
//! direction V = +z. Pixel (px, py) (row py from the top) has its centre at
//! x = 2(px + ½)/size − 1, y = 1 − 2(py + ½)/size; inside the disc the normal is
//! n = (x, y, √(1 − x² − y²)). The shading frame has the normal as z and the world x axis,
//! projected off n, as tangent ([`Frame::new`]). One distant light of irradiance E = π at
//! normal incidence comes from [`LIGHT`]: radiance L = π f(wi, wo) cos θi, so a white
//! Lambertian surface (f = 1/π) shows L = cos θi (the standard lighting model, whose value
//! is already a lit colour, is shown as it is). Display value: L clamped to [0, 1],
//! sRGB-encoded (IEC 61966-2-1) and rounded to 8 bits; alpha 255. Background pixels are
//! [`BACKGROUND`].

use crate::memory::usable;
use crate::models::{Model, MODELS};
use crate::status::{BAD_BUFFER, BAD_PARAM};
use brdf_core::{Frame, Real, Vec3};

// Math goes through `Real` (libm) explicitly: on a std host, `x.sqrt()` would pick std's
// implementation and the native reference would differ from the module.

/// Largest image side accepted by [`brdf_render_sphere`] (512² RGBA = the scratch buffer).
pub const MAX_SIZE: u32 = 512;

/// Direction toward the light (world frame, unnormalised; normalised on use): upper left,
/// in front.
pub const LIGHT: [f32; 3] = [-0.45, 0.55, 0.7];

/// RGBA of pixels outside the sphere.
pub const BACKGROUND: [u8; 4] = [24, 26, 32, 255];

/// sRGB encoding of a linear value in [0, 1] to 8 bits (IEC 61966-2-1, round half up).
pub fn srgb8(l: f32) -> u8 {
    let l = l.clamp(0.0, 1.0); // NaN stays NaN and maps to 0 below
    let c = if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * Real::powf(l, 1.0 / 2.4) - 0.055
    };
    let v = Real::floor(c * 255.0 + 0.5);
    if v >= 0.0 {
        v.min(255.0) as u8
    } else {
        0
    }
}

/// The linear RGB radiance π f cos θi at pixel (px, py) of a `size`² image, or `None`
/// outside the sphere.
pub fn radiance(m: &Model, size: u32, px: u32, py: u32) -> Option<[f32; 3]> {
    let s = size as f32;
    let x = 2.0 * (px as f32 + 0.5) / s - 1.0;
    let y = 1.0 - 2.0 * (py as f32 + 0.5) / s;
    let r2 = x * x + y * y;
    if r2 >= 1.0 {
        return None;
    }
    let n = Vec3::new(x, y, Real::sqrt(1.0 - r2));
    let frame = Frame::new(n, Vec3::new(1.0, 0.0, 0.0))?;
    let l = Vec3::new(LIGHT[0], LIGHT[1], LIGHT[2]).normalize()?;
    let wi = frame.to_local(l);
    let wo = frame.to_local(Vec3::new(0.0, 0.0, 1.0));
    if wi.z.is_nan() || wi.z <= 0.0 {
        return Some([0.0; 3]);
    }
    if m.is_lit_colour() {
        return Some(m.eval(wi, wo));
    }
    Some(m.eval(wi, wo).map(|f| f32::PI * f * wi.z))
}

/// RGBA of pixel (px, py) (see the module docs).
pub fn pixel(m: &Model, size: u32, px: u32, py: u32) -> [u8; 4] {
    match radiance(m, size, px, py) {
        None => BACKGROUND,
        Some([r, g, b]) => [srgb8(r), srgb8(g), srgb8(b), 255],
    }
}

/// Renders the sphere for model `id` with parameters at `params` into `out`
/// (size × size × 4 bytes, RGBA, rows from the top). Returns 0, [`BAD_PARAM`] for a bad model
/// or parameters, [`BAD_BUFFER`] for a null `out` or size outside 1..=512.
///
/// # Safety
/// When they pass the null and alignment checks, `params` must be valid for reads of the
/// model's parameter count of f32 and `out` for writes of size² × 4 bytes; they must not
/// overlap.
#[no_mangle]
pub unsafe extern "C" fn brdf_render_sphere(
    id: u32,
    params: *const f32,
    size: u32,
    out: *mut u8,
) -> i32 {
    if size == 0 || size > MAX_SIZE || !usable(out.cast_const()) || !usable(params) {
        return BAD_BUFFER;
    }
    let Some(spec) = MODELS.get(id as usize) else {
        return BAD_PARAM;
    };
    // SAFETY: `params` is non-null and aligned (checked) and valid for the model's
    // parameter count (the contract); the slice is dropped before `out` is written.
    let params = unsafe { core::slice::from_raw_parts(params, spec.slots()) };
    let Some(m) = Model::new(id, params) else {
        return BAD_PARAM;
    };
    for py in 0..size {
        for px in 0..size {
            let rgba = pixel(&m, size, px, py);
            // SAFETY: `out` is non-null (checked) and valid for size² × 4 bytes (the
            // contract); pixel (px, py) is in bounds since both are below `size`.
            unsafe {
                let o = out.add(4 * (py * size + px) as usize);
                for (c, v) in rgba.iter().enumerate() {
                    *o.add(c) = *v;
                }
            }
        }
    }
    0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_endpoints_and_a_midpoint() {
        assert_eq!(srgb8(0.0), 0);
        assert_eq!(srgb8(1.0), 255);
        assert_eq!(srgb8(7.0), 255);
        assert_eq!(srgb8(-1.0), 0);
        assert_eq!(srgb8(f32::NAN), 0);
        // Linear 0.5 is sRGB 1.055·0.5^(1/2.4) − 0.055 = 0.735357 (IEC 61966-2-1): 187.52 → 188;
        // linear 0.002 is on the linear segment: 12.92·0.002·255 = 6.59 → 7.
        assert_eq!(srgb8(0.5), 188);
        assert_eq!(srgb8(0.002), 7);
    }

    /// Pure Lambert (k_s = 0, ρ_d = 1): the radiance is cos θi = n·l, computed here from the
    /// pixel geometry directly.
    #[test]
    fn lambertian_sphere_is_n_dot_l() {
        let m = Model::new(0, &[0.3, 4.0, 0.04, 0.0, 1.0]).unwrap();
        let size = 64;
        let l = {
            let [a, b, c] = LIGHT;
            let n = (a * a + b * b + c * c).sqrt();
            [a / n, b / n, c / n]
        };
        let mut inside = 0;
        for (px, py) in [(32, 32), (10, 20), (50, 40), (20, 50), (0, 0), (63, 32)] {
            let x = 2.0 * (px as f64 + 0.5) / 64.0 - 1.0;
            let y = 1.0 - 2.0 * (py as f64 + 0.5) / 64.0;
            let r2 = x * x + y * y;
            let got = radiance(&m, size, px, py);
            if r2 >= 1.0 {
                assert_eq!(got, None);
                assert_eq!(pixel(&m, size, px, py), BACKGROUND);
                continue;
            }
            inside += 1;
            let z = (1.0 - r2).sqrt();
            let want = (x * l[0] as f64 + y * l[1] as f64 + z * l[2] as f64).max(0.0);
            for got in got.unwrap() {
                let got = got as f64;
                assert!((got - want).abs() < 1e-5, "({px},{py}): {got} vs {want}");
            }
        }
        assert!(inside >= 4);
    }

    #[test]
    fn bad_arguments() {
        let q = [0.3f32, 4.0, 0.04, 1.0, 0.5];
        let mut img = [0u8; 16];
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_render_sphere(0, q.as_ptr(), 0, img.as_mut_ptr()) };
        assert_eq!(s, BAD_BUFFER);
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_render_sphere(0, q.as_ptr(), 513, img.as_mut_ptr()) };
        assert_eq!(s, BAD_BUFFER);
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_render_sphere(5, q.as_ptr(), 2, img.as_mut_ptr()) };
        assert_eq!(s, BAD_PARAM);
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_render_sphere(0, q.as_ptr(), 2, img.as_mut_ptr()) };
        assert_eq!(s, 0);
        // 2×2: every pixel centre is at r² = 0.5, inside.
        assert!(img
            .chunks(4)
            .all(|p| p[3] == 255 && p[0] == p[1] && p[1] == p[2]));
    }
}

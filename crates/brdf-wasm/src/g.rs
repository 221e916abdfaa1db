//! The geometric attenuation factor G, computed directly (no table).
//!
//! `kind` selects the G by its index in [`GeometricTerm::ALL`]:
//! 0 none (G = 1), 1 Blinn's V-groove (paper eq 4), 2 Smith–Beckmann separable, 3 Smith–Beckmann
//! height-correlated (docs/conventions.md §6, m = √2σ), 4 the paper's modified G (eqs 6–13,
//! reciprocal convention, docs/conventions.md §4), 5 the modified G with eq 12 as printed.
//! σ is the RMS slope (finite, > 0; accuracy specified for [0.05, 1]).

use crate::memory::{batch, map2};
use crate::status::BAD_PARAM;
use brdf_core::geometry::{clamp_theta_i, clamp_theta_r};
use brdf_core::masking::{g_blinn, Convention, ModifiedG};
use brdf_core::microfacet::{from_cos, Beckmann, Distribution};
use brdf_core::models::{GeometricTerm, TorranceSparrow};
use brdf_core::Dots;

/// A G prepared for one (kind, σ): the modified G's normaliser is computed once.
#[derive(Clone, Copy, Debug)]
pub enum PreparedG {
    /// G = 1.
    One,
    /// Blinn's V-groove G.
    Blinn,
    /// Smith–Beckmann with m = √2σ, separable or height-correlated.
    Smith {
        /// The Beckmann distribution of width m = √2σ.
        dist: Beckmann<f32>,
        /// Height-correlated instead of separable.
        correlated: bool,
    },
    /// The paper's modified G (either convention), with its Torrance–Sparrow wrapper for the
    /// dot-product form.
    Modified(ModifiedG<f32>, TorranceSparrow<f32>),
}

impl PreparedG {
    /// Prepares G number `kind` for RMS slope σ; `None` for an unknown kind, or a σ that is
    /// NaN, infinite or ≤ 0 (for every kind, so that the σ argument is always checked).
    pub fn new(kind: u32, sigma: f32) -> Option<Self> {
        let term = *GeometricTerm::ALL.get(kind as usize)?;
        // The Torrance–Sparrow constructor checks σ and gives m = √2σ exactly as the BRDF uses it.
        let ts = TorranceSparrow::<f32>::specular(sigma, term).ok()?;
        Some(match term {
            GeometricTerm::None => PreparedG::One,
            GeometricTerm::Blinn => PreparedG::Blinn,
            GeometricTerm::SmithSeparable | GeometricTerm::SmithCorrelated => PreparedG::Smith {
                dist: Beckmann::clamped(ts.beckmann_m(), ts.beckmann_m()),
                correlated: term == GeometricTerm::SmithCorrelated,
            },
            GeometricTerm::Modified | GeometricTerm::ModifiedPrinted => {
                let conv = if term == GeometricTerm::ModifiedPrinted {
                    Convention::Printed
                } else {
                    Convention::Reciprocal
                };
                PreparedG::Modified(ModifiedG::new(sigma).ok()?.with_convention(conv), ts)
            }
        })
    }

    /// G from the paper's in-plane angles (radians; clamped to θi ∈ [0, π/2],
    /// θr ∈ [−π/2, π/2]; NaN in, NaN out).
    pub fn in_plane(&self, theta_i: f32, theta_r: f32) -> f32 {
        if theta_i.is_nan() || theta_r.is_nan() {
            return f32::NAN;
        }
        match *self {
            PreparedG::One => 1.0,
            PreparedG::Blinn => g_blinn(theta_i, theta_r),
            PreparedG::Smith { dist, correlated } => {
                let ci = libm_cos(clamp_theta_i(theta_i));
                let co = libm_cos(clamp_theta_r(theta_r));
                smith(dist, correlated, ci, co)
            }
            PreparedG::Modified(g, _) => g.g(theta_i, theta_r),
        }
    }

    /// G from the dot products n·wi, n·wo, wi·wo (shader form; the modified G through its
    /// reciprocal 3-D extension). A direction at or below the horizon gives 0.
    pub fn dots(&self, d: Dots<f32>) -> f32 {
        match *self {
            PreparedG::One => {
                if d.n_i.is_nan() || d.n_o.is_nan() || d.i_o.is_nan() {
                    f32::NAN
                } else {
                    1.0
                }
            }
            PreparedG::Blinn => brdf_core::masking::g_blinn_dots(d),
            PreparedG::Smith { dist, correlated } => smith(dist, correlated, d.n_i, d.n_o),
            PreparedG::Modified(_, ts) => ts.g(d),
        }
    }
}

/// Smith's G of `dist` at the cosines n·wi = `ci`, n·wo = `co` (the directions
/// [`from_cos`]): G1(wi) G1(wo), or 1/(1 + Λ(wi) + Λ(wo)) when `correlated`.
fn smith(dist: Beckmann<f32>, correlated: bool, ci: f32, co: f32) -> f32 {
    let (wi, wo) = (from_cos(ci), from_cos(co));
    if correlated {
        dist.g_correlated(wi, wo)
    } else {
        dist.g_separable(wi, wo)
    }
}

/// cos through the same `Real` path the kernels use (libm or micromath).
#[inline]
fn libm_cos(x: f32) -> f32 {
    <f32 as brdf_core::Real>::cos(x)
}

/// G of kind `kind` (see the module docs) at in-plane angles θi, θr (radians) for RMS slope
/// σ. NaN for an unknown kind, a bad σ or NaN angles.
#[no_mangle]
pub extern "C" fn brdf_g(kind: u32, sigma: f32, theta_i: f32, theta_r: f32) -> f32 {
    match PreparedG::new(kind, sigma) {
        Some(g) => g.in_plane(theta_i, theta_r),
        None => f32::NAN,
    }
}

/// G of kind `kind` from the dot products n·wi, n·wo, wi·wo of unit vectors. NaN for an
/// unknown kind or a bad σ; 0 when a direction is at or below the horizon.
#[no_mangle]
pub extern "C" fn brdf_g_dots(kind: u32, sigma: f32, n_i: f32, n_o: f32, i_o: f32) -> f32 {
    match PreparedG::new(kind, sigma) {
        Some(g) => g.dots(Dots::new(n_i, n_o, i_o)),
        None => f32::NAN,
    }
}

/// Batch [`brdf_g`]: `out[k] = G(theta_i[k], theta_r[k])` for k < n, one σ for all. The
/// arrays are f32, 4-byte aligned, and may coincide (in place). Returns n, or
/// [`BAD_PARAM`] / [`BAD_BUFFER`] (nothing written).
///
/// # Safety
/// Each pointer that passes the null and alignment checks must be valid for n f32 (reads
/// for `theta_i`, `theta_r`, writes for `out`).
#[no_mangle]
pub unsafe extern "C" fn brdf_g_batch(
    kind: u32,
    sigma: f32,
    theta_i: *const f32,
    theta_r: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    batch(n, &[theta_i, theta_r, out.cast_const()], || {
        let Some(g) = PreparedG::new(kind, sigma) else {
            return BAD_PARAM;
        };
        // SAFETY: the pointers passed `batch`'s check and are valid for n f32 (the contract).
        unsafe { map2(theta_i, theta_r, out, n, |a, b| g.in_plane(a, b)) }
    })
}

/// Batch [`brdf_g_dots`]: `dots` holds n triples (n·wi, n·wo, wi·wo), `out` n values.
/// Returns n, or a negative status (nothing written).
///
/// # Safety
/// `dots` must be valid for reads of 3n f32 and `out` for writes of n f32, when they pass
/// the null and alignment checks.
#[no_mangle]
pub unsafe extern "C" fn brdf_g_dots_batch(
    kind: u32,
    sigma: f32,
    dots: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    batch(n, &[dots, out.cast_const()], || {
        let Some(g) = PreparedG::new(kind, sigma) else {
            return BAD_PARAM;
        };
        // SAFETY: both pointers are non-null and aligned (checked) and valid for 3n and n
        // f32 (the contract); row k is read before element k is written.
        unsafe {
            for k in 0..n as usize {
                let p = dots.add(3 * k);
                let v = g.dots(Dots::new(*p, *p.add(1), *p.add(2)));
                *out.add(k) = v;
            }
        }
        n as i32
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::BAD_BUFFER;

    #[test]
    fn bad_parameters_give_nan_and_status() {
        assert!(brdf_g(4, 0.0, 0.5, 0.5).is_nan());
        assert!(brdf_g(4, f32::NAN, 0.5, 0.5).is_nan());
        assert!(brdf_g(6, 0.3, 0.5, 0.5).is_nan());
        assert!(brdf_g(1, -1.0, 0.5, 0.5).is_nan());
        assert!(brdf_g_dots(9, 0.3, 1.0, 1.0, 1.0).is_nan());
        let x = [0.1f32; 4];
        let mut out = [7.0f32; 4];
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_g_batch(4, -0.3, x.as_ptr(), x.as_ptr(), out.as_mut_ptr(), 4) };
        assert_eq!(s, BAD_PARAM);
        assert_eq!(out, [7.0; 4], "nothing written on error");
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_g_batch(4, 0.3, core::ptr::null(), x.as_ptr(), out.as_mut_ptr(), 4) };
        assert_eq!(s, BAD_BUFFER);
    }

    /// Blinn's G (eq 4): at the mirror direction θr = θi, α = 0 and β = θi, so
    /// 2 cos α cos θr / cos β = 2 and G = 1; at retro-reflection θr = −θi, α = −θi and β = 0,
    /// so G = 2 cos²θi (closed form).
    #[test]
    fn blinn_closed_form() {
        let r = |d: f32| d.to_radians();
        assert_eq!(brdf_g(1, 0.3, r(30.0), r(30.0)), 1.0);
        assert_eq!(brdf_g(1, 0.3, r(80.0), r(80.0)), 1.0);
        let g = brdf_g(1, 0.3, r(80.0), r(-80.0)) as f64;
        let want = 2.0 * 80f64.to_radians().cos().powi(2);
        assert!((g - want).abs() < 1e-6, "{g} vs {want}");
    }

    /// Smith separable equals the product of the one-sided closed forms Λ(a) with erfc
    /// (docs/conventions.md §6), computed here in f64 independently of brdf-core.
    #[test]
    fn smith_matches_closed_form() {
        fn lambda(theta: f64, m: f64) -> f64 {
            let a = 1.0 / (m * theta.tan());
            (libm_erf(a) - 1.0) / 2.0 + (-a * a).exp() / (2.0 * a * core::f64::consts::PI.sqrt())
        }
        fn libm_erf(x: f64) -> f64 {
            // Maclaurin series of erf; accurate in f64 for the a ≤ 5 used here.
            let mut sum = 0.0;
            let mut term = x;
            let mut k = 0.0;
            while term.abs() > 1e-17 && k < 200.0 {
                sum += term / (2.0 * k + 1.0);
                k += 1.0;
                term *= -x * x / k;
            }
            sum * 2.0 / core::f64::consts::PI.sqrt()
        }
        let sigma = 0.3f64;
        let m = core::f64::consts::SQRT_2 * sigma;
        for (ti, tr) in [(30.0f64, 60.0f64), (70.0, -45.0), (50.0, 85.0)] {
            let (ti, tr) = (ti.to_radians(), tr.to_radians());
            let want = 1.0 / (1.0 + lambda(ti, m)) / (1.0 + lambda(tr.abs(), m));
            let got = brdf_g(2, sigma as f32, ti as f32, tr as f32) as f64;
            assert!((got - want).abs() < 2e-6, "{got} vs {want}");
        }
    }

    #[test]
    fn batch_equals_scalar_and_works_in_place() {
        let ti: [f32; 5] = [0.0, 0.3, 0.7, 1.2, 1.5];
        let mut tr: [f32; 5] = [-1.5, -0.2, 0.4, 1.0, 1.57];
        let want: [f32; 5] = core::array::from_fn(|k| brdf_g(4, 0.3, ti[k], tr[k]));
        let p = tr.as_mut_ptr();
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe { brdf_g_batch(4, 0.3, ti.as_ptr(), p, p, 5) };
        assert_eq!(s, 5);
        assert_eq!(tr, want);
    }
}

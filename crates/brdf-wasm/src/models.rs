//! Every reflection model of brdf-core behind one C-ABI entry point.
//!
//! A model is picked by its id (its index in [`MODELS`]) and configured by an array of f32
//! parameters in the order of its [`ParamSpec`](brdf_core::catalogue::ParamSpec)s. The host discovers names, ranges and
//! defaults at run time through `brdf_model_count`, `brdf_model_str_ptr/len` and
//! `brdf_model_param`, so the JavaScript side carries no copy of this table.
//!
//! Directions are unit vectors in the local shading frame (z = normal, x = tangent for the
//! anisotropic models), pointing away from the surface. Values in 1/sr.

use crate::memory::{batch, usable};
use crate::status::BAD_PARAM;
use brdf_core::catalogue::AnyBrdf;
use brdf_core::fresnel::Fresnel;
use brdf_core::models::{Brdf, GeometricTerm, TorranceSparrow};
use brdf_core::{Dots, Vec3};

/// Every model, by id: the core's model catalogue (names, parameters, slider ranges,
/// defaults). A model's f32 parameter array is the catalogue's flat layout (a colour takes
/// three slots `*_r`, `*_g`, `*_b`, a choice one slot holding the option's index).
pub use brdf_core::catalogue::MODELS;

/// A model built from its parameters (validated once, evaluated many times).
#[derive(Clone, Copy, Debug)]
pub struct Model(AnyBrdf<f32>);

impl Model {
    /// Builds model `id` from `params` (at least as many as the model has slots); `None` for
    /// an unknown id, a choice that is not one of its indices, or a parameter its checked
    /// constructor rejects (not finite, outside its range, or e.g. R_d + R_s > 1). The slider
    /// ranges are advice for a user interface, not a limit.
    pub fn new(id: u32, params: &[f32]) -> Option<Self> {
        let spec = MODELS.get(id as usize)?;
        let q = params.get(..spec.slots())?;
        spec.build::<f32>(q).ok().map(Model)
    }

    /// `true` when [`Model::eval`] is already a lit colour (the standard lighting equation,
    /// which carries n·l itself) rather than a BRDF in 1/sr.
    pub fn is_lit_colour(&self) -> bool {
        self.0.is_lit_colour()
    }

    /// f(wi, wo) in 1/sr per RGB channel, for local-frame unit directions (a scalar model
    /// repeats its value; the Dirac parts of the mirror models are not included). For the
    /// standard lighting model: the colour lit by a white unit light from wi.
    pub fn eval(&self, wi: Vec3<f32>, wo: Vec3<f32>) -> [f32; 3] {
        let c = self.0.eval(wi, wo);
        [c.r, c.g, c.b]
    }
}

/// Number of models (ids are 0..count).
#[no_mangle]
pub extern "C" fn brdf_model_count() -> u32 {
    MODELS.len() as u32
}

/// Number of parameters of model `id` (0 for an unknown id).
#[no_mangle]
pub extern "C" fn brdf_model_param_count(id: u32) -> u32 {
    MODELS.get(id as usize).map_or(0, |m| m.slots() as u32)
}

fn model_str(id: u32, k: u32) -> &'static str {
    match MODELS.get(id as usize) {
        Some(m) if k == u32::MAX => m.name,
        Some(m) => m.slot(k as usize).map_or("", |s| s.name),
        None => "",
    }
}

/// Address of a UTF-8 name: model `id`'s name for `k = 0xFFFF_FFFF`, else its parameter
/// `k`'s name (see `brdf_model_str_len`).
#[no_mangle]
pub extern "C" fn brdf_model_str_ptr(id: u32, k: u32) -> *const u8 {
    model_str(id, k).as_ptr()
}

/// Length in bytes of the name `brdf_model_str_ptr` points to (0 when unknown).
#[no_mangle]
pub extern "C" fn brdf_model_str_len(id: u32, k: u32) -> u32 {
    model_str(id, k).len() as u32
}

/// Field `field` of parameter slot `k` of model `id`: 0 slider min, 1 slider max,
/// 2 default, 3 step (1 for a choice); NaN when unknown.
#[no_mangle]
pub extern "C" fn brdf_model_param(id: u32, k: u32, field: u32) -> f32 {
    let Some(s) = MODELS.get(id as usize).and_then(|m| m.slot(k as usize)) else {
        return f32::NAN;
    };
    (match field {
        0 => s.param.ui.0,
        1 => s.param.ui.1,
        2 => s.default,
        3 => s.param.step,
        _ => f64::NAN,
    }) as f32
}

/// Reads model `id`'s parameter array.
///
/// # Safety
/// `params`, when it passes the null and alignment checks, must be valid for reads of the
/// model's parameter count of f32, not written while this runs.
unsafe fn build(id: u32, params: *const f32) -> Option<Model> {
    let n = MODELS.get(id as usize)?.slots();
    if !usable(params) {
        return None;
    }
    // SAFETY: `params` is non-null and aligned (checked) and valid for `n` f32 (the contract).
    Model::new(id, unsafe { core::slice::from_raw_parts(params, n) })
}

/// f(wi, wo) of model `id` with parameters at `params`, for local-frame unit directions:
/// writes r, g, b (1/sr) to `out` and returns 0, or returns [`BAD_PARAM`] (unknown model or
/// bad parameters) / [`BAD_BUFFER`] with nothing written.
///
/// # Safety
/// When they pass the null and alignment checks, `params` must be valid for reads of the
/// model's parameter count of f32 (see `brdf_model_param_count`) and `out` for writes of
/// 3 f32.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn brdf_eval(
    id: u32,
    params: *const f32,
    out: *mut f32,
    wi_x: f32,
    wi_y: f32,
    wi_z: f32,
    wo_x: f32,
    wo_y: f32,
    wo_z: f32,
) -> i32 {
    // A batch of one row: the same checks, in the same order, and the same value.
    let row = [wi_x, wi_y, wi_z, wo_x, wo_y, wo_z];
    // SAFETY: `params` and `out` as the batch needs for n = 1 (the contract); `row` holds 6
    // f32 on the stack.
    match unsafe { brdf_eval_batch(id, params, row.as_ptr(), out, 1) } {
        1 => 0,
        status => status,
    }
}

/// Batch [`brdf_eval`]: `dirs` holds n rows (wi_x, wi_y, wi_z, wo_x, wo_y, wo_z), `out` gets
/// n rows (r, g, b). `out` may coincide with `dirs` (row k is read before it is written).
/// Returns n, or [`BAD_PARAM`] / [`BAD_BUFFER`] (nothing written).
///
/// # Safety
/// When they pass the null and alignment checks, `params` must be valid for reads of the
/// parameter count of f32, `dirs` for reads of 6n f32 and `out` for writes of 3n f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_eval_batch(
    id: u32,
    params: *const f32,
    dirs: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    batch(n, &[dirs, out.cast_const()], || {
        // SAFETY: `params` is as `build` needs (the contract).
        let Some(m) = (unsafe { build(id, params) }) else {
            return BAD_PARAM;
        };
        // SAFETY: `dirs` and `out` are non-null and aligned (checked) and valid for 6n and 3n
        // f32 (the contract); row k of `dirs` is read before row k of `out` is written, and
        // that row of `out` only overlaps rows of `dirs` already read.
        unsafe {
            for k in 0..n as usize {
                let r = dirs.add(6 * k);
                let v = m.eval(
                    Vec3::new(*r, *r.add(1), *r.add(2)),
                    Vec3::new(*r.add(3), *r.add(4), *r.add(5)),
                );
                for (c, x) in v.iter().enumerate() {
                    *out.add(3 * k + c) = *x;
                }
            }
        }
        n as i32
    })
}

/// The Torrance–Sparrow BRDF (paper eq 3, docs/conventions.md §5) in shader form:
/// k_s·D·F·G/(4 n·wi n·wo) + ρ_d/π with Beckmann D (m = √2σ), Schlick F(R0) at wi·h and G of
/// kind `g_kind` (see [`crate::g`]), from n·wi, n·wo, wi·wo. NaN for bad parameters; 0 below
/// the horizon.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn brdf_torrance_sparrow(
    sigma: f32,
    g_kind: u32,
    r0: f32,
    ks: f32,
    albedo: f32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
) -> f32 {
    torrance_sparrow(sigma, g_kind, r0, ks, albedo, Dots::new(n_i, n_o, i_o))
}

/// [`brdf_torrance_sparrow`] with n·h as well (h = normalize(wi + wo), as a shader has it):
/// exact for near-mirror pairs near the horizon, where 2 + 2 wi·wo cancels and the three dot
/// products alone lose n·h ([`Dots::with_n_h`]). A non-finite n·h gives NaN.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn brdf_torrance_sparrow_nh(
    sigma: f32,
    g_kind: u32,
    r0: f32,
    ks: f32,
    albedo: f32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
    n_h: f32,
) -> f32 {
    if !n_h.is_finite() {
        return f32::NAN;
    }
    let d = Dots::with_n_h(n_i, n_o, i_o, n_h);
    torrance_sparrow(sigma, g_kind, r0, ks, albedo, d)
}

/// The two Torrance–Sparrow exports' body: the model, then its value at `d`.
fn torrance_sparrow(sigma: f32, g_kind: u32, r0: f32, ks: f32, albedo: f32, d: Dots<f32>) -> f32 {
    let Some(&g) = GeometricTerm::ALL.get(g_kind as usize) else {
        return f32::NAN;
    };
    let Ok(f) = Fresnel::schlick(r0) else {
        return f32::NAN;
    };
    match TorranceSparrow::<f32>::new(sigma, g, f, ks, albedo) {
        Ok(m) => m.eval_dots(d),
        Err(_) => f32::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the host reads through the exports builds every model: the defaults (field 2)
    /// of `brdf_model_param_count` slots, each with a positive slider step (field 3). The
    /// catalogue's own consistency (defaults inside the slider ranges, …) is checked once,
    /// in tests/tests/catalogue.rs.
    #[test]
    fn exported_defaults_build() {
        for id in 0..brdf_model_count() {
            let n = brdf_model_param_count(id);
            let d: Vec<f32> = (0..n).map(|k| brdf_model_param(id, k, 2)).collect();
            assert!(Model::new(id, &d).is_some(), "{}", MODELS[id as usize].name);
            assert!((0..n).all(|k| brdf_model_param(id, k, 3) > 0.0));
        }
    }

    #[test]
    fn bad_parameters_are_rejected() {
        let ok = [0.3f32, 4.0, 0.04, 1.0, 0.5];
        assert!(Model::new(0, &ok).is_some());
        assert!(Model::new(0, &ok[..4]).is_none(), "too few parameters");
        assert!(Model::new(99, &ok).is_none());
        for (k, bad) in [
            (0, 0.0f32),
            (0, f32::NAN),
            (1, 4.5),
            (1, 6.0),
            (2, 1.5),
            (4, -0.1),
        ] {
            let mut q = ok;
            q[k] = bad;
            assert!(Model::new(0, &q).is_none(), "param {k} = {bad}");
            let mut out = [7.0f32; 3];
            // SAFETY: the pointers are to live local arrays of the lengths the call states.
            let s = unsafe {
                brdf_eval(
                    0,
                    q.as_ptr(),
                    out.as_mut_ptr(),
                    0.0,
                    0.0,
                    1.0,
                    0.0,
                    0.0,
                    1.0,
                )
            };
            assert_eq!((s, out), (BAD_PARAM, [7.0; 3]));
        }
        let mut out = [7.0f32; 3];
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe {
            brdf_eval(
                0,
                core::ptr::null(),
                out.as_mut_ptr(),
                0.0,
                0.0,
                1.0,
                0.0,
                0.0,
                1.0,
            )
        };
        assert_eq!(s, BAD_PARAM);
    }

    /// A pure Lambertian surface (k_s = 0) gives ρ_d/π for every pair above the horizon.
    #[test]
    fn lambertian_limit() {
        let q = [0.3f32, 4.0, 0.04, 0.0, 0.8];
        let mut v = [7.0f32; 3];
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = unsafe {
            brdf_eval(
                0,
                q.as_ptr(),
                v.as_mut_ptr(),
                0.6,
                0.0,
                0.8,
                -0.28,
                0.96,
                0.0,
            )
        };
        assert_eq!((s, v), (0, [0.0; 3]), "wo on the horizon");
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        unsafe { brdf_eval(0, q.as_ptr(), v.as_mut_ptr(), 0.6, 0.0, 0.8, 0.0, 0.6, 0.8) };
        for c in v {
            assert!((c - 0.8 / core::f32::consts::PI).abs() < 1e-7);
        }
    }

    /// The Lambert model returns ρ/π per channel (closed form), for any pair above the horizon.
    #[test]
    fn lambert_is_albedo_over_pi() {
        let id = MODELS.iter().position(|m| m.name == "lambert").unwrap() as u32;
        let q = [0.8f32, 0.5, 0.25];
        let m = Model::new(id, &q).unwrap();
        let v = m.eval(Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, -0.28, 0.96));
        for c in 0..3 {
            assert!((v[c] - q[c] / core::f32::consts::PI).abs() < 1e-7);
        }
        assert!(!m.is_lit_colour());
    }

    #[test]
    fn names_are_exported() {
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        let s = |id, k| unsafe {
            core::str::from_utf8(core::slice::from_raw_parts(
                brdf_model_str_ptr(id, k),
                brdf_model_str_len(id, k) as usize,
            ))
            .unwrap()
        };
        assert_eq!(s(0, u32::MAX), "torrance-sparrow");
        assert_eq!(s(0, 0), "sigma");
        assert_eq!(s(99, 0), "");
        assert_eq!(s(0, 99), "");
        assert_eq!(brdf_model_param(0, 0, 2), 0.3);
        assert!(brdf_model_param(0, 9, 0).is_nan());
    }
}

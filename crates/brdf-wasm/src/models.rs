//! Every reflection model of brdf-core behind one C-ABI entry point.
//!
//! A model is picked by its id (its index in [`MODELS`]) and configured by an array of f32
//! parameters in the order of its [`ParamSpec`]s. The host discovers names, ranges and
//! defaults at run time through `brdf_model_count`, `brdf_model_str_ptr/len` and
//! `brdf_model_param`, so the JavaScript side carries no copy of this table.
//!
//! Directions are unit vectors in the local shading frame (z = normal, x = tangent for the
//! anisotropic models), pointing away from the surface. Values in 1/sr.

use crate::g::MAX_BATCH;
use crate::memory::usable;
use crate::status::{BAD_BUFFER, BAD_PARAM};
use brdf_core::fresnel::Fresnel;
use brdf_core::models::{
    AshikhminShirley, Bank, BankTangent, BlinnPhongNormalized, Brdf, CookTorrance, CoupledK,
    CoupledSmooth, GeometricTerm, Ggx, Highlight, Lambert, LambertSpecularMix, MicrofacetSampling,
    PhongNormalized, Rgb, ShirleyDamped, SmithForm, StandardLighting, TorranceSparrow, Ward,
};
use brdf_core::{Dots, Vec3};

/// One parameter of a model: name, range, default and the slider step a UI should use
/// (1 for integer-valued choices).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Short name.
    pub name: &'static str,
    /// Smallest accepted value.
    pub min: f32,
    /// Largest accepted value.
    pub max: f32,
    /// Default value.
    pub default: f32,
    /// UI step; 1 means the parameter is an integer choice.
    pub step: f32,
}

/// A model's name and parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelSpec {
    /// Short name.
    pub name: &'static str,
    /// Parameters, in the order of the f32 array the exports take.
    pub params: &'static [ParamSpec],
}

const fn p(name: &'static str, min: f32, max: f32, default: f32, step: f32) -> ParamSpec {
    ParamSpec {
        name,
        min,
        max,
        default,
        step,
    }
}

/// Every model, by id. Colours are RGB triples of sliders (`*_r`, `*_g`, `*_b`); the
/// ranges are the constructors' ranges narrowed to what a UI needs.
pub const MODELS: &[ModelSpec] = &[
    ModelSpec {
        // Paper eq 3 / conventions.md §5: k_s D F G/(4 cos θi cos θo) + ρ_d/π, Schlick F(R0);
        // g = index into GeometricTerm::ALL (4 = the paper's modified G).
        name: "torrance-sparrow",
        params: &[
            p("sigma", 0.05, 1.0, 0.3, 0.01),
            p("g", 0.0, 5.0, 4.0, 1.0),
            p("r0", 0.0, 1.0, 0.04, 0.01),
            p("ks", 0.0, 4.0, 1.0, 0.01),
            p("albedo", 0.0, 1.0, 0.5, 0.01),
        ],
    },
    ModelSpec {
        // ρ/π (seed 003, FCG §24.2).
        name: "lambert",
        params: &[
            p("albedo_r", 0.0, 1.0, 0.8, 0.01),
            p("albedo_g", 0.0, 1.0, 0.5, 0.01),
            p("albedo_b", 0.0, 1.0, 0.3, 0.01),
        ],
    },
    ModelSpec {
        // Energy-normalised Phong lobe (seed 003).
        name: "phong",
        params: &[
            p("kd_r", 0.0, 1.0, 0.5, 0.01),
            p("kd_g", 0.0, 1.0, 0.2, 0.01),
            p("kd_b", 0.0, 1.0, 0.1, 0.01),
            p("ks", 0.0, 1.0, 0.3, 0.01),
            p("n", 0.0, 500.0, 40.0, 1.0),
        ],
    },
    ModelSpec {
        // Energy-normalised Blinn-Phong lobe (seed 003).
        name: "blinn-phong",
        params: &[
            p("kd_r", 0.0, 1.0, 0.1, 0.01),
            p("kd_g", 0.0, 1.0, 0.3, 0.01),
            p("kd_b", 0.0, 1.0, 0.5, 0.01),
            p("ks", 0.0, 1.0, 0.3, 0.01),
            p("n", 0.0, 500.0, 80.0, 1.0),
        ],
    },
    ModelSpec {
        // Seed 002 §10.1: k_d/π + k_s R_s, Beckmann m, Schlick R0, G by index (1 = V-groove).
        name: "cook-torrance",
        params: &[
            p("kd_r", 0.0, 1.0, 0.4, 0.01),
            p("kd_g", 0.0, 1.0, 0.1, 0.01),
            p("kd_b", 0.0, 1.0, 0.1, 0.01),
            p("ks", 0.0, 1.0, 0.6, 0.01),
            p("m", 0.02, 1.0, 0.25, 0.01),
            p("r0", 0.0, 1.0, 0.04, 0.01),
            p("g", 0.0, 5.0, 1.0, 1.0),
        ],
    },
    ModelSpec {
        // FCG §24.4 Lambert + mirror (the Dirac part is not drawn); R_d + R_s ≤ 1.
        name: "lambert-mirror",
        params: &[
            p("rd_r", 0.0, 0.5, 0.4, 0.01),
            p("rd_g", 0.0, 0.5, 0.4, 0.01),
            p("rd_b", 0.0, 0.5, 0.2, 0.01),
            p("rs", 0.0, 0.5, 0.3, 0.01),
        ],
    },
    ModelSpec {
        // FCG §24.4 Shirley's damped model (not reciprocal).
        name: "shirley-damped",
        params: &[
            p("rd_r", 0.0, 1.0, 0.6, 0.01),
            p("rd_g", 0.0, 1.0, 0.3, 0.01),
            p("rd_b", 0.0, 1.0, 0.2, 0.01),
            p("r0", 0.0, 1.0, 0.05, 0.01),
        ],
    },
    ModelSpec {
        // FCG eq 24.3; k: 0 energy-conserving, 1 as printed.
        name: "coupled-smooth",
        params: &[
            p("rm_r", 0.0, 1.0, 0.2, 0.01),
            p("rm_g", 0.0, 1.0, 0.5, 0.01),
            p("rm_b", 0.0, 1.0, 0.3, 0.01),
            p("r0", 0.0, 0.95, 0.05, 0.01),
            p("k", 0.0, 1.0, 0.0, 1.0),
        ],
    },
    ModelSpec {
        // FCG eqs 24.5–24.9 (anisotropic: nu along the tangent x, nv along y).
        name: "ashikhmin-shirley",
        params: &[
            p("rd_r", 0.0, 1.0, 0.3, 0.01),
            p("rd_g", 0.0, 1.0, 0.1, 0.01),
            p("rd_b", 0.0, 1.0, 0.1, 0.01),
            p("rs", 0.0, 1.0, 0.4, 0.01),
            p("nu", 1.0, 1000.0, 100.0, 1.0),
            p("nv", 1.0, 1000.0, 10.0, 1.0),
        ],
    },
    ModelSpec {
        // Seed 002 §10.3, fixed tangent at azimuth phi (radians) in the tangent plane.
        name: "bank",
        params: &[
            p("kd_r", 0.0, 1.0, 0.3, 0.01),
            p("kd_g", 0.0, 1.0, 0.2, 0.01),
            p("kd_b", 0.0, 1.0, 0.1, 0.01),
            p("ks", 0.0, 1.0, 0.5, 0.01),
            p("ns", 1.0, 500.0, 30.0, 1.0),
            p("phi", 0.0, core::f32::consts::PI, 0.0, 0.01),
        ],
    },
    ModelSpec {
        // Seed 002 §10.4, Ward's anisotropic Gaussian (RMS slopes ax, ay).
        name: "ward",
        params: &[
            p("rd_r", 0.0, 1.0, 0.2, 0.01),
            p("rd_g", 0.0, 1.0, 0.2, 0.01),
            p("rd_b", 0.0, 1.0, 0.3, 0.01),
            p("rs", 0.0, 1.0, 0.3, 0.01),
            p("ax", 0.01, 1.0, 0.1, 0.01),
            p("ay", 0.01, 1.0, 0.4, 0.01),
        ],
    },
    ModelSpec {
        // Trowbridge–Reitz with Smith masking; smith: 0 separable, 1 height-correlated.
        name: "ggx",
        params: &[
            p("f0_r", 0.0, 1.0, 0.95, 0.01),
            p("f0_g", 0.0, 1.0, 0.64, 0.01),
            p("f0_b", 0.0, 1.0, 0.54, 0.01),
            p("alpha", 0.01, 1.0, 0.3, 0.01),
            p("smith", 0.0, 1.0, 1.0, 1.0),
        ],
    },
    ModelSpec {
        // Seed 003 lighting equation: the lit colour for a white unit light (includes n·l);
        // highlight: 0 Phong (v·r), 1 Blinn-Phong (n·h).
        name: "standard",
        params: &[
            p("diffuse_r", 0.0, 1.0, 0.5, 0.01),
            p("diffuse_g", 0.0, 1.0, 0.3, 0.01),
            p("diffuse_b", 0.0, 1.0, 0.2, 0.01),
            p("specular", 0.0, 1.0, 0.5, 0.01),
            p("gloss", 0.0, 500.0, 30.0, 1.0),
            p("highlight", 0.0, 1.0, 1.0, 1.0),
        ],
    },
];

/// A model built from its parameters (validated once, evaluated many times).
#[derive(Clone, Copy, Debug)]
pub enum Model {
    /// Torrance–Sparrow with a selectable G and Schlick Fresnel.
    TorranceSparrow(TorranceSparrow<f32>),
    /// Lambert.
    Lambert(Lambert<f32>),
    /// Normalised Phong.
    Phong(PhongNormalized<f32>),
    /// Normalised Blinn-Phong.
    BlinnPhong(BlinnPhongNormalized<f32>),
    /// Cook–Torrance.
    CookTorrance(CookTorrance<f32>),
    /// Lambert plus mirror.
    Mix(LambertSpecularMix<f32>),
    /// Shirley's damped model.
    Shirley(ShirleyDamped<f32>),
    /// Coupled smooth-layered model.
    Coupled(CoupledSmooth<f32>),
    /// Ashikhmin–Shirley.
    AshikhminShirley(AshikhminShirley<f32>),
    /// Bank.
    Bank(Bank<f32>),
    /// Ward.
    Ward(Ward<f32>),
    /// GGX.
    Ggx(Ggx<f32>),
    /// The standard lighting equation.
    Standard(StandardLighting<f32>),
}

/// `Some(k)` when x is an integer in [0, n).
fn choice(x: f32, n: usize) -> Option<usize> {
    if x >= 0.0 && x < n as f32 && x == (x as u32) as f32 {
        Some(x as usize)
    } else {
        None
    }
}

impl Model {
    /// Builds model `id` from `params` (at least as many as the model has); `None` for an
    /// unknown id or a parameter that is not finite or outside its range (or rejected by
    /// the model's checked constructor, e.g. R_d + R_s > 1).
    pub fn new(id: u32, params: &[f32]) -> Option<Self> {
        let spec = MODELS.get(id as usize)?;
        let q = params.get(..spec.params.len())?;
        for (x, s) in q.iter().zip(spec.params) {
            if !(x.is_finite() && *x >= s.min && *x <= s.max) {
                return None;
            }
        }
        let rgb = |k: usize| Rgb::new(q[k], q[k + 1], q[k + 2]);
        let g_term = |x: f32| Some(GeometricTerm::ALL[choice(x, GeometricTerm::ALL.len())?]);
        Some(match spec.name {
            "torrance-sparrow" => Model::TorranceSparrow(
                TorranceSparrow::new(
                    q[0],
                    g_term(q[1])?,
                    Fresnel::schlick(q[2]).ok()?,
                    q[3],
                    q[4],
                )
                .ok()?,
            ),
            "lambert" => Model::Lambert(Lambert::new(rgb(0)).ok()?),
            "phong" => Model::Phong(PhongNormalized::new(rgb(0), Rgb::splat(q[3]), q[4]).ok()?),
            "blinn-phong" => {
                Model::BlinnPhong(BlinnPhongNormalized::new(rgb(0), Rgb::splat(q[3]), q[4]).ok()?)
            }
            "cook-torrance" => Model::CookTorrance(
                CookTorrance::new(rgb(0), Rgb::splat(q[3]), q[4], q[5], g_term(q[6])?).ok()?,
            ),
            "lambert-mirror" => Model::Mix(LambertSpecularMix::new(rgb(0), q[3]).ok()?),
            "shirley-damped" => Model::Shirley(ShirleyDamped::new(rgb(0), q[3]).ok()?),
            "coupled-smooth" => {
                let k = [CoupledK::Conserving, CoupledK::Printed][choice(q[4], 2)?];
                Model::Coupled(CoupledSmooth::new(rgb(0), q[3], k).ok()?)
            }
            "ashikhmin-shirley" => Model::AshikhminShirley(
                AshikhminShirley::new(Rgb::splat(q[3]), rgb(0), q[4], q[5]).ok()?,
            ),
            "bank" => Model::Bank(
                Bank::new(rgb(0), Rgb::splat(q[3]), q[4], BankTangent::Azimuth(q[5])).ok()?,
            ),
            "ward" => Model::Ward(Ward::new(rgb(0), Rgb::splat(q[3]), q[4], q[5]).ok()?),
            "ggx" => {
                let smith = [SmithForm::Separable, SmithForm::Correlated][choice(q[4], 2)?];
                Model::Ggx(Ggx::new(rgb(0), q[3], smith, MicrofacetSampling::VisibleNormals).ok()?)
            }
            "standard" => {
                let h = [Highlight::Phong, Highlight::BlinnPhong][choice(q[5], 2)?];
                Model::Standard(
                    StandardLighting::new(
                        Rgb::zero(),
                        Rgb::zero(),
                        rgb(0),
                        Rgb::splat(q[3]),
                        q[4],
                        h,
                    )
                    .ok()?,
                )
            }
            _ => return None,
        })
    }

    /// `true` when [`Model::eval`] is already a lit colour (the standard lighting equation,
    /// which carries n·l itself) rather than a BRDF in 1/sr.
    pub fn is_lit_colour(&self) -> bool {
        matches!(self, Model::Standard(_))
    }

    /// f(wi, wo) in 1/sr per RGB channel, for local-frame unit directions (a scalar model
    /// repeats its value; the Dirac parts of the mirror models are not included). For the
    /// standard lighting model: the colour lit by a white unit light from wi.
    pub fn eval(&self, wi: Vec3<f32>, wo: Vec3<f32>) -> [f32; 3] {
        let c: Rgb<f32> = match self {
            Model::TorranceSparrow(m) => return [m.eval(wi, wo); 3],
            Model::Lambert(m) => m.eval(wi, wo),
            Model::Phong(m) => m.eval(wi, wo),
            Model::BlinnPhong(m) => m.eval(wi, wo),
            Model::CookTorrance(m) => m.eval(wi, wo),
            Model::Mix(m) => m.eval(wi, wo),
            Model::Shirley(m) => m.eval(wi, wo),
            Model::Coupled(m) => m.eval(wi, wo),
            Model::AshikhminShirley(m) => m.eval(wi, wo),
            Model::Bank(m) => m.eval(wi, wo),
            Model::Ward(m) => m.eval(wi, wo),
            Model::Ggx(m) => m.eval(wi, wo),
            Model::Standard(m) => m.eval(wi, wo),
        };
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
    MODELS.get(id as usize).map_or(0, |m| m.params.len() as u32)
}

fn model_str(id: u32, k: u32) -> &'static str {
    match MODELS.get(id as usize) {
        Some(m) if k == u32::MAX => m.name,
        Some(m) => m.params.get(k as usize).map_or("", |p| p.name),
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

/// Field `field` of parameter `k` of model `id`: 0 min, 1 max, 2 default, 3 step;
/// NaN when unknown.
#[no_mangle]
pub extern "C" fn brdf_model_param(id: u32, k: u32, field: u32) -> f32 {
    let Some(s) = MODELS
        .get(id as usize)
        .and_then(|m| m.params.get(k as usize))
    else {
        return f32::NAN;
    };
    match field {
        0 => s.min,
        1 => s.max,
        2 => s.default,
        3 => s.step,
        _ => f32::NAN,
    }
}

/// Reads model `id`'s parameter array.
///
/// # Safety
/// `params` must be valid for the model's parameter count.
unsafe fn build(id: u32, params: *const f32) -> Option<Model> {
    let n = MODELS.get(id as usize)?.params.len();
    if !usable(params) {
        return None;
    }
    Model::new(id, core::slice::from_raw_parts(params, n))
}

/// f(wi, wo) of model `id` with parameters at `params`, for local-frame unit directions:
/// writes r, g, b (1/sr) to `out` and returns 0, or returns [`BAD_PARAM`] (unknown model or
/// bad parameters) / [`BAD_BUFFER`] with nothing written.
///
/// # Safety
/// `params` must be valid for the model's parameter count (see `brdf_model_param_count`),
/// `out` for 3 f32.
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
    if !usable(out.cast_const()) {
        return BAD_BUFFER;
    }
    let Some(m) = build(id, params) else {
        return BAD_PARAM;
    };
    let v = m.eval(Vec3::new(wi_x, wi_y, wi_z), Vec3::new(wo_x, wo_y, wo_z));
    for (c, x) in v.iter().enumerate() {
        *out.add(c) = *x;
    }
    0
}

/// Batch [`brdf_eval`]: `dirs` holds n rows (wi_x, wi_y, wi_z, wo_x, wo_y, wo_z), `out` gets
/// n rows (r, g, b). `out` may coincide with `dirs` (row k is read before it is written).
/// Returns n, or [`BAD_PARAM`] / [`BAD_BUFFER`] (nothing written).
///
/// # Safety
/// `params` valid for the parameter count, `dirs` for 6n f32, `out` for 3n f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_eval_batch(
    id: u32,
    params: *const f32,
    dirs: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    if n > MAX_BATCH || !usable(dirs) || !usable(out.cast_const()) {
        return BAD_BUFFER;
    }
    let Some(m) = build(id, params) else {
        return BAD_PARAM;
    };
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
    n as i32
}

/// The Torrance–Sparrow BRDF (paper eq 3, conventions.md §5) in shader form:
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
    let Some(&g) = GeometricTerm::ALL.get(g_kind as usize) else {
        return f32::NAN;
    };
    let Ok(f) = Fresnel::schlick(r0) else {
        return f32::NAN;
    };
    match TorranceSparrow::<f32>::new(sigma, g, f, ks, albedo) {
        Ok(m) => m.eval_dots(Dots { n_i, n_o, i_o }),
        Err(_) => f32::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_inside_their_ranges_and_build() {
        for (id, m) in MODELS.iter().enumerate() {
            for s in m.params {
                assert!(
                    s.min <= s.default && s.default <= s.max,
                    "{} {}",
                    m.name,
                    s.name
                );
                assert!(s.step > 0.0);
            }
            let d: [f32; 16] = core::array::from_fn(|k| m.params.get(k).map_or(0.0, |s| s.default));
            assert!(Model::new(id as u32, &d).is_some(), "{}", m.name);
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

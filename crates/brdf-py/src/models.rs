//! Every model of `brdf_core::catalogue` by name: evaluation, importance sampling and
//! directional albedo over NumPy arrays of directions, and the catalogue itself.

use crate::arrays::{self, dir, Float, Kernel};
use brdf_core::albedo::directional_albedo;
use brdf_core::catalogue::{self, ModelSpec, ParamKind, MODELS};
use brdf_core::models::Brdf;
use brdf_core::{Real, Vec3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};

/// A model by name (or old spelling), or `ValueError` listing the names.
fn find(name: &str) -> PyResult<&'static ModelSpec> {
    catalogue::find(name).ok_or_else(|| {
        let names: Vec<&str> = MODELS.iter().map(|m| m.name).collect();
        PyValueError::new_err(format!(
            "argument `model`: unknown model {name:?} (models: {})",
            names.join(", ")
        ))
    })
}

/// One keyword value into the flat slots at `at`.
fn put(p: &catalogue::ParamSpec, v: &Bound<'_, PyAny>, flat: &mut [f64]) -> PyResult<()> {
    let bad = |what: String| PyValueError::new_err(format!("parameter `{}`: {what}", p.name));
    match p.kind {
        ParamKind::Scalar => {
            flat[0] = v
                .extract::<f64>()
                .map_err(|_| bad("expected a number".into()))?
        }
        ParamKind::Rgb(_) => {
            if let Ok(x) = v.extract::<f64>() {
                flat[..3].fill(x);
            } else {
                let c: Vec<f64> = v
                    .extract()
                    .map_err(|_| bad("expected a number or three numbers (r, g, b)".into()))?;
                let [r, g, b] = c[..] else {
                    return Err(bad(format!(
                        "expected 3 numbers (r, g, b), got {}",
                        c.len()
                    )));
                };
                flat[..3].copy_from_slice(&[r, g, b]);
            }
        }
        ParamKind::Choice(options) => {
            let s: String = v
                .extract()
                .map_err(|_| bad(format!("expected one of {}", options.join(" | "))))?;
            let i = options
                .iter()
                .position(|o| *o == s)
                .ok_or_else(|| bad(format!("{s:?} is not one of {}", options.join(" | "))))?;
            flat[0] = i as f64;
        }
    }
    Ok(())
}

/// The flat parameter array of `spec` from keyword arguments (defaults for the others),
/// checked by building the f64 model once.
fn params(spec: &'static ModelSpec, kw: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<f64>> {
    let mut flat = spec.defaults::<f64>()[..spec.slots()].to_vec();
    if let Some(kw) = kw {
        for (k, v) in kw.iter() {
            let k: String = k.extract()?;
            let Some((at, p)) = spec.param_by_name(&k) else {
                let keys: Vec<&str> = spec.params.iter().map(|p| p.name).collect();
                return Err(PyValueError::new_err(format!(
                    "model {:?} has no parameter `{k}` (parameters: {})",
                    spec.name,
                    keys.join(", ")
                )));
            };
            put(p, &v, &mut flat[at..])?;
        }
    }
    spec.build::<f64>(&flat)
        .map_err(|e| PyValueError::new_err(format!("model {:?}: {e}", spec.name)))?;
    Ok(flat)
}

/// What to compute for each element.
#[derive(Clone, Copy)]
enum Job {
    /// f(wi, wo) per channel (3 outputs).
    Eval,
    /// (wi, weight, pdf) from wo and u (7 outputs).
    Sample,
    /// Directional albedo per channel (3 outputs).
    Albedo,
}

struct ModelKernel {
    spec: &'static ModelSpec,
    flat: Vec<f64>,
    job: Job,
}

impl ModelKernel {
    /// The model by name with its keyword parameters checked, for `job`.
    fn new(model: &str, kw: Option<&Bound<'_, PyDict>>, job: Job) -> PyResult<Self> {
        let spec = find(model)?;
        Ok(Self {
            spec,
            flat: params(spec, kw)?,
            job,
        })
    }
}

/// A unit vector from three components, or `None` (zero, non-finite).
fn unit<T: Real>(x: &[&[T]], k: usize) -> Option<Vec3<T>> {
    Vec3::new(x[0][k], x[1][k], x[2][k]).normalize()
}

impl Kernel for ModelKernel {
    fn run<T: Float>(&self, inp: &[&[T]], out: &mut [&mut [T]]) -> Result<(), String> {
        let flat: Vec<T> = self.flat.iter().map(|&x| T::from_f64(x)).collect();
        let m = self
            .spec
            .build::<T>(&flat)
            .map_err(|e| format!("model {:?} in {}: {e}", self.spec.name, T::DTYPE))?;
        let n = out.first().map_or(0, |o| o.len());
        for k in 0..n {
            let vals: [T; 7] = match self.job {
                Job::Eval => match (unit(&inp[0..3], k), unit(&inp[3..6], k)) {
                    (Some(wi), Some(wo)) => {
                        let c = m.eval(wi, wo);
                        [c.r, c.g, c.b, T::NAN, T::NAN, T::NAN, T::NAN]
                    }
                    _ => [T::NAN; 7],
                },
                Job::Albedo => match unit(&inp[0..3], k) {
                    Some(wo) => {
                        let c = directional_albedo(&m, wo);
                        [c.r, c.g, c.b, T::NAN, T::NAN, T::NAN, T::NAN]
                    }
                    None => [T::NAN; 7],
                },
                Job::Sample => {
                    let s = unit(&inp[0..3], k).and_then(|wo| m.sample(wo, [inp[3][k], inp[4][k]]));
                    match s {
                        Some(s) => [
                            s.wi.x, s.wi.y, s.wi.z, s.weight.r, s.weight.g, s.weight.b, s.pdf,
                        ],
                        None => [T::NAN; 7],
                    }
                }
            };
            for (o, v) in out.iter_mut().zip(vals) {
                o[k] = v;
            }
        }
        Ok(())
    }

    /// An albedo is a quadrature of a few hundred evaluations: smaller chunks, so that
    /// Ctrl-C is seen within a fraction of a second.
    fn chunk(&self) -> usize {
        match self.job {
            Job::Albedo => 256,
            Job::Eval | Job::Sample => arrays::CHUNK,
        }
    }
}

/// Defines a Python function `$name(model, <directions>, **params)`: job `$job` of the
/// catalogue model over the direction arrays `$arg` (shape (..., 3) each), one (..., 3)
/// result (one definition of what evaluation and albedo share).
macro_rules! model_function {
    ($(#[doc = $doc:literal])* $name:ident($($arg:ident),+) => $job:expr) => {
        $(#[doc = $doc])*
        #[pyfunction]
        #[pyo3(signature = (model, $($arg,)+ **params))]
        pub fn $name<'py>(
            py: Python<'py>,
            model: &str,
            $($arg: &Bound<'py, PyAny>,)+
            params: Option<&Bound<'py, PyDict>>,
        ) -> PyResult<Bound<'py, PyAny>> {
            let k = ModelKernel::new(model, params, $job)?;
            let args = [$(dir(stringify!($arg), $arg)),+];
            arrays::single(arrays::run(py, &args, &[3], &k)?)
        }
    };
}

model_function!(
    /// Evaluates a catalogue model f(wi, wo) (1/sr per channel; the Dirac part of a model with
    /// a mirror is not included).
    ///
    /// Parameters
    /// ----------
    /// model : str
    ///     Catalogue name (see :func:`models`), e.g. "ggx", "torrance-sparrow".
    /// wi, wo : array_like, shape (..., 3)
    ///     Directions toward the light and the viewer in the local frame (z = normal);
    ///     normalised here; the leading shapes broadcast. A zero or non-finite vector gives NaN.
    ///     Below the surface (z < 0) a BRDF gives 0; the BSDF "rough-dielectric" gives its
    ///     transmitted part when wi and wo lie on opposite sides (radiance convention).
    /// **params
    ///     The model's parameters by name (defaults for the others); a colour takes one number
    ///     or three, a choice its option name.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (..., 3)
    ///     f per RGB channel; float32 when wi and wo are float32, float64 otherwise.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     Unknown model or parameter, a parameter outside its range (the message names it and
    ///     the range), a last axis that is not 3, shapes that do not broadcast.
    eval(wi, wo) => Job::Eval
);

/// Importance-samples a catalogue model.
///
/// Parameters
/// ----------
/// model : str
///     Catalogue name.
/// wo : array_like, shape (..., 3)
///     Direction toward the viewer (normalised here).
/// u : array_like, shape (..., 2)
///     Two uniform numbers in [0, 1) per sample; the leading shapes broadcast with wo's.
/// **params
///     The model's parameters, as in :func:`eval`.
///
/// Returns
/// -------
/// wi : numpy.ndarray, shape (..., 3)
///     The sampled direction toward the light.
/// weight : numpy.ndarray, shape (..., 3)
///     f(wi, wo) |cos θi| / pdf per channel (for a sample of a mirror or other Dirac part:
///     its reflectance or transmittance divided by the probability of choosing it).
/// pdf : numpy.ndarray
///     The pdf of wi per unit solid angle (mirror part: the probability of choosing it).
///
/// u is clamped into [0, 1) as the kernels do (u = 1.0, a routine output of a float
/// random-number conversion, samples as the largest float below 1). All three are NaN
/// where sampling fails (a NaN u, wo below the horizon or zero).
///
/// Raises
/// ------
/// ValueError
///     As in :func:`eval`; u's last axis not 2.
#[pyfunction]
#[pyo3(signature = (model, wo, u, **params))]
pub fn sample<'py>(
    py: Python<'py>,
    model: &str,
    wo: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let k = ModelKernel::new(model, params, Job::Sample)?;
    let np = py.import("numpy")?;
    let ua = np.call_method1("asarray", (u,))?;
    let shape: Vec<usize> = ua.getattr("shape")?.extract()?;
    if shape.last() != Some(&2) {
        return Err(PyValueError::new_err(format!(
            "argument `u` must have shape (..., 2); got shape {}",
            arrays::shape_text(&shape)
        )));
    }
    let (u0, u1) = (
        ua.get_item((pyo3::types::PyEllipsis::get(py), 0))?,
        ua.get_item((pyo3::types::PyEllipsis::get(py), 1))?,
    );
    let args = [dir("wo", wo), arrays::num("u", &u0), arrays::num("u", &u1)];
    let r = arrays::run(py, &args, &[3, 3, arrays::SCALAR], &k)?;
    arrays::one_or_tuple(py, r)
}

model_function!(
    /// Directional albedo R(wo) = ∫ f(wi, wo) cos θi dωi of a catalogue model (fixed-size
    /// lobe-following quadrature; the Dirac part is not included).
    ///
    /// Parameters
    /// ----------
    /// model : str
    ///     Catalogue name.
    /// wo : array_like, shape (..., 3)
    ///     Direction toward the viewer (normalised here).
    /// **params
    ///     The model's parameters, as in :func:`eval`.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (..., 3)
    ///     Albedo per channel; dtype follows wo.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     As in :func:`eval`.
    albedo(wo) => Job::Albedo
);

/// One parameter as a dict.
fn param_dict<'py>(py: Python<'py>, p: &catalogue::ParamSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", p.name)?;
    d.set_item("unit", p.unit())?;
    d.set_item("range", p.range())?;
    d.set_item("ui_range", p.ui)?;
    d.set_item("help", p.help())?;
    match p.kind {
        ParamKind::Scalar => {
            d.set_item("kind", "scalar")?;
            d.set_item("default", p.default[0])?;
        }
        ParamKind::Rgb(names) => {
            d.set_item("kind", "rgb")?;
            d.set_item("channels", names.to_vec())?;
            d.set_item("default", p.default.to_vec())?;
        }
        ParamKind::Choice(o) => {
            d.set_item("kind", "choice")?;
            d.set_item("options", o.to_vec())?;
            d.set_item(
                "default",
                o.get(p.default[0] as usize).copied().unwrap_or(""),
            )?;
        }
    }
    Ok(d)
}

/// The model catalogue.
///
/// Returns
/// -------
/// list of dict
///     One dict per model: ``name``, ``aliases``, ``about``, ``lit_colour``, ``has_delta``,
///     ``anisotropic`` and ``params``, a list of dicts with ``name``, ``kind`` ("scalar",
///     "rgb" or "choice"), ``unit``, ``range`` (the accepted range in words), ``ui_range``,
///     ``default`` (a number, three numbers, or an option name), ``help`` and, for a choice,
///     ``options``.
#[pyfunction]
pub fn models(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let list = PyList::empty(py);
    for m in MODELS {
        let d = PyDict::new(py);
        d.set_item("name", PyString::new(py, m.name))?;
        d.set_item("aliases", m.aliases.to_vec())?;
        d.set_item("about", m.about())?;
        d.set_item("lit_colour", m.flags.lit_colour)?;
        d.set_item("has_delta", m.flags.has_delta)?;
        d.set_item("anisotropic", m.flags.anisotropic)?;
        let ps = PyList::empty(py);
        for p in m.params {
            ps.append(param_dict(py, p)?)?;
        }
        d.set_item("params", ps)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(eval, m)?)?;
    m.add_function(wrap_pyfunction!(sample, m)?)?;
    m.add_function(wrap_pyfunction!(albedo, m)?)?;
    m.add_function(wrap_pyfunction!(models, m)?)?;
    Ok(())
}

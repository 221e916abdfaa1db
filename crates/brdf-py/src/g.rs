//! The geometric attenuation factors: the paper's modified G (in-plane angles and the 3-D
//! extension from dot products), Blinn's V-groove G and Smith's G, each a thin [`Kernel`]
//! over `brdf_core::batch` or the scalar kernels of `brdf_core::masking`.

use crate::arrays::{self, dir, num, Float, Kernel, SCALAR};
use brdf_core::batch::{self, DotsSoa};
use brdf_core::masking::{self, Convention, GTerms, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use brdf_core::quadrature::{GaussLegendre, Rule, DEFAULT_NODES, NODE_COUNTS};
use brdf_core::ParamError;
use brdf_core::{Dots, Vec3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::any::{Any, TypeId};
use std::cell::RefCell;

/// Calls `$body` with `$r` bound to the Gauss–Legendre rule of `$n` nodes (one arm per
/// count of `brdf_core::quadrature::NODE_COUNTS`).
macro_rules! with_rule {
    ($n:expr, $r:ident => $body:expr) => {
        with_rule!(@arms $n, $r, $body, 4 6 8 10 12 16 20 24 32)
    };
    (@arms $n:expr, $r:ident, $body:expr, $($k:literal)*) => {
        match $n {
            $($k => {
                type $r = GaussLegendre<$k>;
                $body
            })*
            n => Err(format!(
                "argument `nodes` = {n} is not one of {NODE_COUNTS:?}"
            )),
        }
    };
}

fn convention(s: &str) -> PyResult<Convention> {
    match s {
        "reciprocal" => Ok(Convention::Reciprocal),
        "printed" => Ok(Convention::Printed),
        o => Err(PyValueError::new_err(format!(
            "argument `convention` = {o:?} is not one of \"reciprocal\", \"printed\""
        ))),
    }
}

/// What the arrays of a G call hold.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Input {
    /// In-plane angles (θi, θr).
    Angles,
    /// Dot products (n·wi, n·wo, wi·wo).
    Dots,
    /// Directions wi, wo (x, y, z each) and, with `true`, a normal n (else n = +z).
    Vectors(bool),
}

/// The modified G's inputs besides the arrays.
struct Modified {
    sigma: f64,
    convention: Convention,
    nodes: usize,
    input: Input,
    /// Write GM, GS, G (three outputs) instead of G.
    terms: bool,
}

/// Recently built surfaces, per thread: building one integrates the normaliser C(σ), which
/// costs more than a G value, so repeated calls with the same σ (a scalar loop) reuse it.
type Cached = (TypeId, u64, Box<dyn Any>);
thread_local! {
    static SURFACES: RefCell<Vec<Cached>> = const { RefCell::new(Vec::new()) };
}

/// `ModifiedG::<T, R>::new(σ)`, from the per-thread cache when built before.
fn surface<T: Float, R: Rule + 'static>(sigma: f64) -> Result<ModifiedG<T, R>, ParamError> {
    let key = (TypeId::of::<ModifiedG<T, R>>(), sigma.to_bits());
    let hit = SURFACES.with(|c| {
        c.borrow()
            .iter()
            .find(|(t, s, _)| (*t, *s) == key)
            .and_then(|(_, _, g)| g.downcast_ref::<ModifiedG<T, R>>().copied())
    });
    if let Some(g) = hit {
        return Ok(g);
    }
    let g = ModifiedG::<T, R>::new(T::from_f64(sigma))?;
    SURFACES.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() >= 8 {
            c.remove(0);
        }
        c.push((key.0, key.1, Box::new(g)));
    });
    Ok(g)
}

/// The `ValueError` text for a σ the constructor refused, with the accepted range as the
/// constructor states it for a σ above it.
fn sigma_error(sigma: f64, e: ParamError) -> String {
    let range = match ModifiedG::<f64>::new(2.0 * ModifiedG::<f64>::SIGMA_MAX) {
        Err(ParamError::OutOfRange { range, .. }) => range,
        _ => "(0, ∞)",
    };
    format!("argument `sigma` = {sigma} is outside its range {range} ({e})")
}

/// GM, GS, G of one element of a [`Input::Vectors`] call: the vectors normalised as
/// `ModifiedG::g_vectors` does, NaN when one is zero or not finite.
fn vector_terms<T: Float, R: Rule>(g: &ModifiedG<T, R>, x: &[&[T]], k: usize) -> GTerms<T> {
    let v = |c: usize| Vec3::new(x[c][k], x[c + 1][k], x[c + 2][k]).normalize();
    let n = if x.len() == 9 {
        v(6)
    } else {
        Some(Vec3::new(T::ZERO, T::ZERO, T::ONE))
    };
    match (v(0), v(3), n) {
        (Some(wi), Some(wo), Some(n)) => g.terms_dots(Dots::from_vectors(wi, wo, n)),
        _ => GTerms {
            gm: T::NAN,
            gs: T::NAN,
            g: T::NAN,
        },
    }
}

impl Modified {
    /// The elementwise kernel: `terms(k)` gives GM, GS, G of element k (used where
    /// `brdf_core::batch` has no entry point for the input form).
    fn each<T: Float>(out: &mut [&mut [T]], n: usize, terms: impl Fn(usize) -> GTerms<T>) {
        for k in 0..n {
            let t = terms(k);
            match out {
                [g] => g[k] = t.g,
                [gm, gs, g] => (gm[k], gs[k], g[k]) = (t.gm, t.gs, t.g),
                _ => {}
            }
        }
    }

    fn with<T: Float, R: Rule + 'static>(
        &self,
        inp: &[&[T]],
        out: &mut [&mut [T]],
    ) -> Result<(), String> {
        let g = surface::<T, R>(self.sigma)
            .map_err(|e| sigma_error(self.sigma, e))?
            .with_convention(self.convention);
        let e = |e: batch::BatchError| e.to_string();
        let n = out.first().map_or(0, |o| o.len());
        match (self.input, self.terms, inp, &mut *out) {
            (Input::Angles, false, [ti, tr], [o]) => batch::g_modified(&g, ti, tr, o).map_err(e),
            (Input::Dots, false, [a, b, c], [o]) => {
                let d = DotsSoa {
                    n_i: a,
                    n_o: b,
                    i_o: c,
                };
                batch::g_modified_dots(&g, d, o).map_err(e)
            }
            (Input::Angles, _, [ti, tr], _) => {
                Self::each(out, n, |k| g.terms(ti[k], tr[k]));
                Ok(())
            }
            (Input::Dots, _, [a, b, c], _) => {
                Self::each(out, n, |k| g.terms_dots(Dots::new(a[k], b[k], c[k])));
                Ok(())
            }
            (Input::Vectors(_), _, x, _) if x.len() >= 6 => {
                Self::each(out, n, |k| vector_terms(&g, x, k));
                Ok(())
            }
            _ => Err("internal: argument count".into()),
        }
    }
}

impl Kernel for Modified {
    fn run<T: Float>(&self, inp: &[&[T]], out: &mut [&mut [T]]) -> Result<(), String> {
        with_rule!(self.nodes, R => self.with::<T, R>(inp, out))
    }
}

/// Checks σ, the convention and the node count before any array work.
fn modified(sigma: f64, conv: &str, nodes: usize, input: Input, terms: bool) -> PyResult<Modified> {
    if let Err(e) = surface::<f64, GaussLegendre<DEFAULT_NODES>>(sigma) {
        return Err(PyValueError::new_err(sigma_error(sigma, e)));
    }
    if !NODE_COUNTS.contains(&nodes) {
        return Err(PyValueError::new_err(format!(
            "argument `nodes` = {nodes} is not one of {NODE_COUNTS:?}"
        )));
    }
    Ok(Modified {
        sigma,
        convention: convention(conv)?,
        nodes,
        input,
        terms,
    })
}

/// Runs a modified-G call: one output, or three with `terms`.
fn run_modified<'py>(
    py: Python<'py>,
    k: &Modified,
    args: &[arrays::Arg<'_, 'py>],
) -> PyResult<Bound<'py, PyAny>> {
    let widths: &[usize] = if k.terms { &[SCALAR; 3] } else { &[SCALAR] };
    arrays::one_or_tuple(py, arrays::run(py, args, widths, k)?)
}

/// Defines a Python function `$name(<arrays>, sigma, *, [n=None,] convention="reciprocal",
/// nodes=10, terms=False)`: the modified G of input form `$input`, its array arguments `$arg`
/// read by `$read` ([`num`] or [`dir`]) and, for the vector form, an optional normal `$n`
/// (one definition of the parameters the three forms share and of their body).
macro_rules! modified_function {
    (
        $(#[doc = $doc:literal])*
        $name:ident($($arg:ident: $read:ident),+ $(; $n:ident)?) => $input:expr
    ) => {
        $(#[doc = $doc])*
        #[pyfunction]
        #[pyo3(signature = (
            $($arg,)+ sigma, *, $($n=None,)? convention="reciprocal", nodes=10, terms=false
        ))]
        #[allow(clippy::too_many_arguments)]
        pub fn $name<'py>(
            py: Python<'py>,
            $($arg: &Bound<'py, PyAny>,)+
            sigma: f64,
            $($n: Option<&Bound<'py, PyAny>>,)?
            convention: &str,
            nodes: usize,
            terms: bool,
        ) -> PyResult<Bound<'py, PyAny>> {
            let k = modified(sigma, convention, nodes, $input, terms)?;
            #[allow(unused_mut)]
            let mut args = vec![$($read(stringify!($arg), $arg)),+];
            $(args.extend($n.map(|v| dir(stringify!($n), v)));)?
            run_modified(py, &k, &args)
        }
    };
}

modified_function!(
    /// The paper's modified geometric attenuation factor G = min(GM, GS) (eqs 6–13).
    ///
    /// Parameters
    /// ----------
    /// theta_i, theta_r : array_like
    ///     Incidence angle θi ∈ [0, π/2] and signed reflection angle θr ∈ [−π/2, π/2] in radians
    ///     (θr > 0 on the forward side); broadcast together. Out-of-range angles are clamped,
    ///     NaN gives NaN.
    /// sigma : float
    ///     RMS slope σ ∈ (0, 1e6] of the Gaussian surface.
    /// convention : {"reciprocal", "printed"}
    ///     "reciprocal" (default) or eq 12 as printed in the paper.
    /// nodes : int
    ///     Gauss–Legendre nodes per integral: 4, 6, 8, 10 (default), 12, 16, 20, 24 or 32.
    /// terms : bool
    ///     Return the tuple (GM, GS, G) instead of G.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray or float
    ///     G (or GM, GS, G) in the broadcast shape, float32 when every array argument is float32,
    ///     float64 otherwise (a NumPy scalar when that shape is ``()``); a Python float when
    ///     every argument is a Python number.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     σ outside (0, 1e6], unknown convention or node count, shapes that do not broadcast.
    g_modified(theta_i: num, theta_r: num) => Input::Angles
);

modified_function!(
    /// The modified G from dot products: the reciprocal 3-D extension (shader form).
    ///
    /// Parameters
    /// ----------
    /// n_i, n_o, i_o : array_like
    ///     n·wi, n·wo and wi·wo of unit vectors (z up); broadcast together. A direction at or
    ///     below the horizon gives 0, NaN gives NaN.
    /// sigma : float
    ///     RMS slope σ ∈ (0, 1e6].
    /// convention : {"reciprocal", "printed"}
    ///     As in :func:`g_modified`.
    /// nodes : int
    ///     As in :func:`g_modified`.
    /// terms : bool
    ///     Return (GM, GS, G) instead of G.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray or float
    ///     G (or GM, GS, G), dtype as in :func:`g_modified`.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     As in :func:`g_modified`.
    g_modified_dots(n_i: num, n_o: num, i_o: num) => Input::Dots
);

modified_function!(
    /// The modified G from directions: the reciprocal 3-D extension of
    /// :func:`g_modified_dots` with the dot products taken from the vectors
    /// (``brdf_core::masking::ModifiedG::g_vectors``).
    ///
    /// Parameters
    /// ----------
    /// wi, wo : array_like, shape (..., 3)
    ///     Directions toward the light and the viewer, any length (normalised here); the leading
    ///     shapes broadcast. A zero or non-finite vector gives NaN; a direction at or below the
    ///     horizon gives 0.
    /// sigma : float
    ///     RMS slope σ ∈ (0, 1e6].
    /// n : array_like, shape (..., 3), optional
    ///     The surface normal (normalised here; default +z, the local frame), broadcast with
    ///     wi and wo.
    /// convention : {"reciprocal", "printed"}
    ///     As in :func:`g_modified`.
    /// nodes : int
    ///     As in :func:`g_modified`.
    /// terms : bool
    ///     Return (GM, GS, G) instead of G.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     G (or GM, GS, G) in the broadcast leading shape; float32 when every array argument is
    ///     float32, float64 otherwise.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     As in :func:`g_modified`; a last axis that is not 3.
    g_modified_vectors(wi: dir, wo: dir; n) => Input::Vectors(n.is_some())
);

/// Blinn's V-groove G (paper eq 4), from angles or from dot products.
struct Blinn {
    dots: bool,
}

impl Kernel for Blinn {
    fn run<T: Float>(&self, inp: &[&[T]], out: &mut [&mut [T]]) -> Result<(), String> {
        match (self.dots, inp, out) {
            (false, [ti, tr], [o]) => {
                for ((o, &a), &b) in o.iter_mut().zip(*ti).zip(*tr) {
                    *o = masking::g_blinn(a, b);
                }
                Ok(())
            }
            (true, [a, b, c], [o]) => {
                let d = DotsSoa {
                    n_i: a,
                    n_o: b,
                    i_o: c,
                };
                batch::g_blinn_dots(d, o).map_err(|e| e.to_string())
            }
            _ => Err("internal: argument count".into()),
        }
    }
}

/// Blinn's V-groove geometric attenuation factor (paper eq 4) from in-plane angles.
///
/// Parameters
/// ----------
/// theta_i, theta_r : array_like
///     θi ∈ [0, π/2] and signed θr ∈ [−π/2, π/2] in radians, broadcast together.
///
/// Returns
/// -------
/// numpy.ndarray or float
///     G in [0, 1]; dtype as in :func:`g_modified`.
///
/// Raises
/// ------
/// ValueError
///     Shapes that do not broadcast.
/// TypeError
///     An array of another kind than numbers (complex, strings, objects).
#[pyfunction]
pub fn g_blinn<'py>(
    py: Python<'py>,
    theta_i: &Bound<'py, PyAny>,
    theta_r: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let args = [num("theta_i", theta_i), num("theta_r", theta_r)];
    arrays::one_or_tuple(
        py,
        arrays::run(py, &args, &[SCALAR], &Blinn { dots: false })?,
    )
}

/// Blinn's V-groove G from dot products n·wi, n·wo, wi·wo.
///
/// Parameters
/// ----------
/// n_i, n_o, i_o : array_like
///     Dot products of unit vectors, broadcast together.
///
/// Returns
/// -------
/// numpy.ndarray or float
///     G in [0, 1]; dtype as in :func:`g_modified`.
///
/// Raises
/// ------
/// ValueError
///     Shapes that do not broadcast.
/// TypeError
///     An array of another kind than numbers (complex, strings, objects).
#[pyfunction]
pub fn g_blinn_dots<'py>(
    py: Python<'py>,
    n_i: &Bound<'py, PyAny>,
    n_o: &Bound<'py, PyAny>,
    i_o: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let args = [num("n_i", n_i), num("n_o", n_o), num("i_o", i_o)];
    arrays::one_or_tuple(
        py,
        arrays::run(py, &args, &[SCALAR], &Blinn { dots: true })?,
    )
}

/// Smith's G for Beckmann (width m) or GGX (width α), separable or height-correlated.
struct Smith {
    width: f64,
    ggx: bool,
    correlated: bool,
}

impl Kernel for Smith {
    fn run<T: Float>(&self, inp: &[&[T]], out: &mut [&mut [T]]) -> Result<(), String> {
        let w = T::from_f64(self.width);
        let [ci, co] = inp else {
            return Err("internal: argument count".into());
        };
        let [o] = out else {
            return Err("internal: output count".into());
        };
        let f: fn(T, T, T) -> T = match (self.ggx, self.correlated) {
            (false, false) => Beckmann::<T>::g_separable_cos,
            (false, true) => Beckmann::<T>::g_correlated_cos,
            (true, false) => TrowbridgeReitz::<T>::g_separable_cos,
            (true, true) => TrowbridgeReitz::<T>::g_correlated_cos,
        };
        for ((o, &a), &b) in o.iter_mut().zip(*ci).zip(*co) {
            *o = f(a, b, w);
        }
        Ok(())
    }
}

fn smith<'py>(
    py: Python<'py>,
    cos_i: &Bound<'py, PyAny>,
    cos_o: &Bound<'py, PyAny>,
    width: f64,
    distribution: &str,
    correlated: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let ggx = match distribution {
        "beckmann" => false,
        "ggx" => true,
        o => {
            return Err(PyValueError::new_err(format!(
                "argument `distribution` = {o:?} is not one of \"beckmann\", \"ggx\""
            )))
        }
    };
    if !(width.is_finite() && width > 0.0) {
        return Err(PyValueError::new_err(format!(
            "argument `width` = {width} is outside its range (0, inf)"
        )));
    }
    let k = Smith {
        width,
        ggx,
        correlated,
    };
    let args = [num("cos_i", cos_i), num("cos_o", cos_o)];
    arrays::one_or_tuple(py, arrays::run(py, &args, &[SCALAR], &k)?)
}

/// Defines a Python function `$name(cos_i, cos_o, width, *, distribution="beckmann")`:
/// Smith's G in the form `correlated` picks, documented by `$summary` and the shared
/// parameter sections (one definition for both forms).
macro_rules! smith_function {
    ($summary:literal, $name:ident, correlated = $correlated:literal) => {
        #[doc = $summary]
        ///
        /// Parameters
        /// ----------
        /// cos_i, cos_o : array_like
        ///     cos θi = n·wi and cos θo = n·wo, broadcast together.
        /// width : float
        ///     Beckmann m (= √2 σ for RMS slope σ) or GGX α, > 0.
        /// distribution : {"beckmann", "ggx"}
        ///     The microfacet distribution (default "beckmann").
        ///
        /// Returns
        /// -------
        /// numpy.ndarray or float
        ///     G in [0, 1]; dtype as in :func:`g_modified`.
        ///
        /// Raises
        /// ------
        /// ValueError
        ///     width not finite and > 0, unknown distribution, shapes that do not broadcast.
        #[pyfunction]
        #[pyo3(signature = (cos_i, cos_o, width, *, distribution="beckmann"))]
        pub fn $name<'py>(
            py: Python<'py>,
            cos_i: &Bound<'py, PyAny>,
            cos_o: &Bound<'py, PyAny>,
            width: f64,
            distribution: &str,
        ) -> PyResult<Bound<'py, PyAny>> {
            smith(py, cos_i, cos_o, width, distribution, $correlated)
        }
    };
}

smith_function!(
    " Smith's separable G = G1(θi) G1(θo).",
    g_smith_separable,
    correlated = false
);
smith_function!(
    " Smith's height-correlated G = 1/(1 + Λ(θi) + Λ(θo)).",
    g_smith_correlated,
    correlated = true
);

/// The functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(g_modified, m)?)?;
    m.add_function(wrap_pyfunction!(g_modified_dots, m)?)?;
    m.add_function(wrap_pyfunction!(g_modified_vectors, m)?)?;
    m.add_function(wrap_pyfunction!(g_blinn, m)?)?;
    m.add_function(wrap_pyfunction!(g_blinn_dots, m)?)?;
    m.add_function(wrap_pyfunction!(g_smith_separable, m)?)?;
    m.add_function(wrap_pyfunction!(g_smith_correlated, m)?)?;
    Ok(())
}

//! BLUT tables: build from a spec dict (the fields of `cargo xtask lut generate`'s TOML file)
//! through `brdf_lut::generate::generate`, load and save (temporary file, then rename), look
//! up with broadcasting through `brdf_lut::LutView::sample`, and the header as a dict.

use crate::arrays::{self, num, Float, Kernel};
use brdf_lut::generate::{self, Distribution, Kind, Masking, Roughness, Spec};
use brdf_lut::{Encoding, Interpolation, Lut, Placement, Warp};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

create_exception!(
    brdf_kernels,
    LutError,
    PyValueError,
    "A BLUT file or byte string that is not a valid table (bad magic, version, header, size \
     or checksum), or a table that cannot be built from its spec."
);

pub(crate) fn lut_err(e: impl std::fmt::Display) -> PyErr {
    LutError::new_err(e.to_string())
}

fn load_err(e: brdf_lut::Error) -> PyErr {
    match e {
        brdf_lut::Error::Io(io) => PyOSError::new_err(io.to_string()),
        other => lut_err(other),
    }
}

/// One of `options` by name, or `ValueError` naming the field and the options.
fn choose<T: Copy>(field: &str, v: &str, options: &[(&str, T)]) -> PyResult<T> {
    options
        .iter()
        .find(|(n, _)| *n == v)
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
            PyValueError::new_err(format!(
                "spec field `{field}`: {v:?} is not one of {}",
                names.join(", ")
            ))
        })
}

const WARPS: &[(&str, Warp)] = &[
    ("linear", Warp::Linear),
    ("log", Warp::Log),
    ("sqrt", Warp::Sqrt),
    ("cos", Warp::Cos),
    ("sqrt-cos", Warp::SqrtCos),
];
const PLACEMENTS: &[(&str, Placement)] = &[
    ("endpoint", Placement::Endpoint),
    ("texel-centre", Placement::TexelCentre),
    ("texel-center", Placement::TexelCentre),
];

/// The spec's fields by their TOML name (`max-error`; `max_error` also accepted).
struct Fields<'py> {
    d: Bound<'py, PyDict>,
}

const KEYS: &[&str] = &[
    "kind",
    "model",
    "masking",
    "roughness",
    "sigma",
    "res",
    "encoding",
    "interpolation",
    "samples",
    "seed",
    "max-error",
    "axes",
    "out",
];

impl<'py> Fields<'py> {
    fn new(d: &Bound<'py, PyDict>) -> PyResult<Self> {
        let norm = PyDict::new(d.py());
        for (k, v) in d.iter() {
            let k: String = k.extract()?;
            let k = k.replace('_', "-");
            if !KEYS.contains(&k.as_str()) {
                return Err(PyValueError::new_err(format!(
                    "spec: unknown field `{k}` (fields: {})",
                    KEYS.join(", ")
                )));
            }
            norm.set_item(k, v)?;
        }
        Ok(Self { d: norm })
    }
    fn get<T: for<'a> FromPyObject<'a, 'py>>(&self, k: &str) -> PyResult<Option<T>> {
        match self.d.get_item(k)? {
            None => Ok(None),
            Some(v) => v.extract::<T>().map(Some).map_err(|_| {
                PyValueError::new_err(format!(
                    "spec field `{k}`: {} has the wrong type",
                    v.repr().map(|r| r.to_string()).unwrap_or_default()
                ))
            }),
        }
    }
}

/// Kind, distribution and masking, with xtask's defaults.
fn kind_model(f: &Fields<'_>) -> PyResult<Spec> {
    let kind_s: String = f.get("kind")?.ok_or_else(|| {
        PyValueError::new_err(
            "spec field `kind` is missing (g-per-sigma, g-over-sigma, split-sum, e, e-avg)",
        )
    })?;
    let sigma: Option<f64> = f.get("sigma")?;
    let kind = match kind_s.as_str() {
        "g-per-sigma" => Kind::GPerSigma {
            sigma: sigma
                .ok_or_else(|| PyValueError::new_err("a g-per-sigma spec needs field `sigma`"))?,
        },
        "g-over-sigma" => Kind::GOverSigma,
        "split-sum" => Kind::SplitSum,
        "e" => Kind::Albedo,
        "e-avg" => Kind::AverageAlbedo,
        o => {
            return Err(PyValueError::new_err(format!(
            "spec field `kind`: {o:?} is not one of g-per-sigma, g-over-sigma, split-sum, e, e-avg"
        )))
        }
    };
    if sigma.is_some() && !matches!(kind, Kind::GPerSigma { .. }) {
        return Err(PyValueError::new_err(
            "spec field `sigma` is the fixed σ of a g-per-sigma table; other kinds take a σ axis",
        ));
    }
    let g_table = matches!(kind, Kind::GPerSigma { .. } | Kind::GOverSigma);
    let dist = match f.get::<String>("model")? {
        Some(m) => choose("model", &m, &generate::distribution_options())?,
        None if g_table => Distribution::TorranceSparrow,
        None => {
            return Err(PyValueError::new_err(
                "spec field `model` is missing (ggx, beckmann, torrance-sparrow)",
            ))
        }
    };
    let masking = match f.get::<String>("masking")? {
        Some(m) => choose("masking", &m, &Masking::options())?,
        None if dist == Distribution::TorranceSparrow => Masking::Modified,
        None => Masking::SmithCorrelated,
    };
    let mut spec = Spec::new(kind, dist, masking);
    if let Some(r) = f.get::<String>("roughness")? {
        spec.roughness = choose("roughness", &r, &Roughness::ALL.map(|r| (r.name(), r)))?;
        spec.axes = spec.default_axes();
    }
    Ok(spec)
}

/// The `axes` table, then `res`.
fn axes(f: &Fields<'_>, spec: &mut Spec) -> PyResult<()> {
    let names = spec.axis_names();
    let index = |name: &str| {
        names.iter().position(|n| *n == name).ok_or_else(|| {
            PyValueError::new_err(format!(
                "spec: no axis `{name}`; this table's axes are {}",
                names.join(", ")
            ))
        })
    };
    if let Some(ax) = f.get::<Bound<'_, PyDict>>("axes")? {
        let mut items: Vec<(String, Bound<'_, PyAny>)> = Vec::new();
        for (k, v) in ax.iter() {
            items.push((k.extract()?, v));
        }
        items.sort_by(|a, b| a.0.cmp(&b.0));
        for (name, v) in items {
            let i = index(&name)?;
            let a = Fields {
                d: v.cast_into::<PyDict>().map_err(|_| {
                    PyValueError::new_err(format!("spec axis `{name}` must be a dict"))
                })?,
            };
            for (k, _) in a.d.iter() {
                let k: String = k.extract()?;
                if !["count", "lo", "hi", "warp", "placement"].contains(&k.as_str()) {
                    return Err(PyValueError::new_err(format!(
                        "spec axis `{name}`: unknown field `{k}` (count, lo, hi, warp, placement)"
                    )));
                }
            }
            let x = &mut spec.axes[i];
            x.count = a.get("count")?.unwrap_or(x.count);
            x.lo = a.get("lo")?.unwrap_or(x.lo);
            x.hi = a.get("hi")?.unwrap_or(x.hi);
            if let Some(w) = a.get::<String>("warp")? {
                x.warp = choose("warp", &w, WARPS)?;
            }
            if let Some(p) = a.get::<String>("placement")? {
                x.placement = choose("placement", &p, PLACEMENTS)?;
            }
        }
    }
    if let Some(res) = f.get::<String>("res")? {
        let counts: Vec<u32> = res
            .split('x')
            .map(|t| {
                t.trim().parse::<u32>().map_err(|_| {
                    PyValueError::new_err(format!(
                        "spec field `res` {res:?}: {t:?} is not a whole number"
                    ))
                })
            })
            .collect::<PyResult<_>>()?;
        if counts.len() != names.len() {
            return Err(PyValueError::new_err(format!(
                "spec field `res` {res:?} gives {} sizes; this table has {} axes ({})",
                counts.len(),
                names.len(),
                names.join(", ")
            )));
        }
        for (x, c) in spec.axes.iter_mut().zip(counts) {
            x.count = c;
        }
    }
    Ok(())
}

/// A `Spec` from the dict, as `cargo xtask lut generate --config` reads its TOML file.
fn spec_from(d: &Bound<'_, PyDict>) -> PyResult<(Spec, Option<f64>, Option<PathBuf>)> {
    let f = Fields::new(d)?;
    let mut spec = kind_model(&f)?;
    axes(&f, &mut spec)?;
    if let Some(e) = f.get::<String>("encoding")? {
        spec.encoding = choose(
            "encoding",
            &e,
            &[
                ("u16", Encoding::Unorm16),
                ("f16", Encoding::F16),
                ("f32", Encoding::F32),
            ],
        )?;
    }
    if let Some(i) = f.get::<String>("interpolation")? {
        spec.interpolation = choose(
            "interpolation",
            &i,
            &[
                ("linear", Interpolation::Linear),
                ("catmull-rom", Interpolation::CatmullRom),
            ],
        )?;
    }
    if let Some(n) = f.get::<u32>("samples")? {
        spec.samples = n;
    }
    if let Some(s) = f.get::<u64>("seed")? {
        spec.seed = s;
    }
    let max_error: Option<f64> = f.get("max-error")?;
    if let Some(e) = max_error {
        if !(e.is_finite() && e > 0.0) {
            return Err(PyValueError::new_err(format!(
                "spec field `max-error` = {e} must be a positive number"
            )));
        }
    }
    spec.validate()
        .map_err(|e| PyValueError::new_err(format!("spec: {e}")))?;
    Ok((spec, max_error, f.get::<PathBuf>("out")?))
}

thread_local! {
    /// The stop flag of the build this thread runs, so that the panic hook stays quiet about
    /// the unwinding that stops a cancelled build.
    static STOP: std::cell::RefCell<Option<Arc<AtomicBool>>> = const { std::cell::RefCell::new(None) };
}

/// Installs (once) a panic hook that is silent while a cancelled build unwinds and defers
/// to the previous hook otherwise.
fn quiet_cancel_hook() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let prev = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let stopping = STOP.with(|s| {
                s.borrow()
                    .as_ref()
                    .is_some_and(|a| a.load(Ordering::Relaxed))
            });
            if !stopping {
                prev(info);
            }
        }));
    });
}

/// The unwinding payload of a cancelled build.
struct Cancelled;

/// Runs `job` (a table computation taking a progress callback) on a worker thread; every
/// 50 ms the calling thread takes the GIL and checks for signals (Ctrl-C). On a signal the
/// workers stop at their next progress report (the callback unwinds with [`Cancelled`],
/// which `std::thread::scope` passes on to the worker, where it is caught) and the signal's
/// exception is raised. `Ok(None)`: the job panicked for another reason.
pub(crate) fn run_cancellable<R: Send + 'static>(
    py: Python<'_>,
    job: impl FnOnce(&(dyn Fn(u64) + Sync)) -> R + Send + 'static,
) -> PyResult<Option<R>> {
    quiet_cancel_hook();
    let stop = Arc::new(AtomicBool::new(false));
    let (tx, rx) = std::sync::mpsc::channel();
    let stop_w = Arc::clone(&stop);
    let worker = std::thread::spawn(move || {
        STOP.with(|s| *s.borrow_mut() = Some(Arc::clone(&stop_w)));
        let progress = |_k: u64| {
            if stop_w.load(Ordering::Relaxed) {
                std::panic::resume_unwind(Box::new(Cancelled));
            }
        };
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| job(&progress)));
        let _ = tx.send(r.ok());
    });
    let mut rx = rx;
    loop {
        let (got, back) = py.detach(move || (rx.recv_timeout(Duration::from_millis(50)), rx));
        rx = back;
        match got {
            Ok(r) => {
                let _ = worker.join();
                return Ok(r);
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    stop.store(true, Ordering::Relaxed);
                    let _ = py.detach(|| worker.join());
                    return Err(e);
                }
            }
            Err(_) => return Err(lut_err("the table computation stopped unexpectedly")),
        }
    }
}

/// The generator, interruptible ([`run_cancellable`]).
fn run_generate(py: Python<'_>, spec: Spec) -> PyResult<generate::Generated> {
    match run_cancellable(py, move |p| generate::generate(&spec, p))? {
        Some(Ok(g)) => Ok(g),
        Some(Err(e)) => Err(lut_err(e)),
        None => Err(lut_err("the table generator failed (internal error)")),
    }
}

/// Writes `bytes` to a temporary file beside `path` (same folder, so that a rename is
/// atomic), synced; returns its path. On an error the temporary file is removed.
pub(crate) fn write_temp(path: &Path, bytes: &[u8]) -> std::io::Result<PathBuf> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let res = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()
    })();
    match res {
        Ok(()) => Ok(tmp),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// Writes `bytes` to `path` through a temporary file in the same folder (synced, then
/// renamed into place): an error leaves any previous file untouched and no partial file.
fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = write_temp(path, bytes)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// A loaded, validated BLUT table (docs/lut-format.md): made by :func:`build_table`,
/// :meth:`Table.load` or :meth:`Table.from_bytes`; immutable.
#[pyclass(module = "brdf_kernels", frozen)]
pub struct Table {
    lut: Lut,
}

/// Interpolated lookups at physical coordinates (one argument per axis).
struct Lookup<'a> {
    lut: &'a Lut,
}

impl Kernel for Lookup<'_> {
    fn run<T: Float>(&self, inp: &[&[T]], out: &mut [&mut [T]]) -> Result<(), String> {
        let view = self.lut.view().map_err(|e| e.to_string())?;
        let n = out.first().map_or(0, |o| o.len());
        let mut x = [0f32; 3];
        for k in 0..n {
            for (xi, c) in x.iter_mut().zip(inp) {
                *xi = c[k].to_f64() as f32;
            }
            let v = view.sample(&x[..inp.len()]);
            for (o, &val) in out.iter_mut().zip(v.iter()) {
                o[k] = T::from_f64(f64::from(val));
            }
        }
        Ok(())
    }
}

#[pymethods]
impl Table {
    /// Loads and validates a BLUT file.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     The file.
    ///
    /// Returns
    /// -------
    /// Table
    ///
    /// Raises
    /// ------
    /// LutError
    ///     The file is not a valid table (magic, version, header, size, checksum).
    /// OSError
    ///     It cannot be read.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let lut = py.detach(|| Lut::from_path(&path)).map_err(load_err)?;
        Ok(Self { lut })
    }

    /// Validates a table from its bytes.
    ///
    /// Parameters
    /// ----------
    /// data : bytes
    ///
    /// Returns
    /// -------
    /// Table
    ///
    /// Raises
    /// ------
    /// LutError
    ///     Not a valid table.
    #[staticmethod]
    fn from_bytes(data: Vec<u8>) -> PyResult<Self> {
        Ok(Self {
            lut: Lut::from_bytes(data).map_err(load_err)?,
        })
    }

    /// Saves the table: written to a temporary file in the target folder, synced, then
    /// renamed over `path`, so that an error leaves no partial file.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///
    /// Raises
    /// ------
    /// OSError
    ///     The file cannot be written.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let bytes = self.lut.bytes();
        py.detach(|| write_atomic(&path, bytes))
            .map_err(|e| PyOSError::new_err(format!("{}: {e}", path.display())))
    }

    /// The file's bytes.
    ///
    /// Returns
    /// -------
    /// bytes
    ///     The whole BLUT file (header, payload, checksum), as :meth:`save` writes it.
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, self.lut.bytes())
    }

    /// The decoded header as a dict: ``kind``, ``axes`` (list of dicts with ``name``,
    /// ``count``, ``lo``, ``hi``, ``warp``, ``placement``), ``channels``, ``encoding``,
    /// ``interpolation``, ``model``, ``convention``, ``sigma``, ``nodes``, ``tool``,
    /// ``max_error``, ``rms_error``, ``error_samples``, ``error_seed``, ``checksum``.
    ///
    /// Returns
    /// -------
    /// dict
    ///     A new dict on every access (changing it does not change the table).
    #[getter]
    fn header<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let h = self.lut.header();
        let d = PyDict::new(py);
        d.set_item("kind", format!("{:?}", h.kind))?;
        let axes = PyList::empty(py);
        for a in h.axes.iter() {
            let ad = PyDict::new(py);
            ad.set_item("name", a.name)?;
            ad.set_item("count", a.count)?;
            ad.set_item("lo", a.lo)?;
            ad.set_item("hi", a.hi)?;
            ad.set_item("warp", format!("{:?}", a.warp))?;
            ad.set_item("placement", format!("{:?}", a.placement))?;
            axes.append(ad)?;
        }
        d.set_item("axes", axes)?;
        let ch: Vec<&str> = h.channels.iter().map(|c| c.name).collect();
        d.set_item("channels", ch)?;
        d.set_item("encoding", format!("{:?}", h.encoding))?;
        d.set_item("interpolation", format!("{:?}", h.interpolation))?;
        d.set_item("model", format!("{:?}", h.generator.model))?;
        d.set_item("convention", format!("{:?}", h.generator.convention))?;
        d.set_item("sigma", h.generator.sigma)?;
        d.set_item("nodes", h.generator.nodes.as_slice().to_vec())?;
        d.set_item("tool", h.generator.tool)?;
        d.set_item("max_error", h.error.max_abs)?;
        d.set_item("rms_error", h.error.rms)?;
        d.set_item("error_samples", h.error.samples)?;
        d.set_item("error_seed", h.error.seed)?;
        d.set_item("checksum", h.checksum)?;
        Ok(d)
    }

    /// Interpolated channel values at physical coordinates, one array per axis (in the
    /// header's order), broadcast together. Coordinates are clamped to each axis' range; NaN
    /// gives NaN. The values are the f32 reader's (``brdf_lut::LutView::sample``), returned
    /// in the dtype of the coordinates.
    ///
    /// Parameters
    /// ----------
    /// *coords : array_like
    ///     One per axis.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (..., channels)
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     Wrong number of coordinates, shapes that do not broadcast.
    #[pyo3(signature = (*coords))]
    fn lookup<'py>(
        &self,
        py: Python<'py>,
        coords: Vec<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let h = self.lut.header();
        // The axis names of the generator, for messages (arguments need static names).
        const KNOWN: [&str; 7] = ["theta", "phi", "sigma", "mu", "roughness", "alpha", "m"];
        let names: Vec<&'static str> = h
            .axes
            .iter()
            .map(|a| {
                KNOWN
                    .iter()
                    .find(|k| **k == a.name)
                    .copied()
                    .unwrap_or("coordinate")
            })
            .collect();
        if coords.len() != h.axes.len() {
            let an: Vec<&str> = h.axes.iter().map(|a| a.name).collect();
            return Err(PyValueError::new_err(format!(
                "lookup takes {} coordinates ({}), {} given",
                h.axes.len(),
                an.join(", "),
                coords.len()
            )));
        }
        let args: Vec<_> = coords.iter().zip(names).map(|(c, n)| num(n, c)).collect();
        let widths = [h.channels.len()];
        let k = Lookup { lut: &self.lut };
        arrays::single(arrays::run(py, &args, &widths, &k)?)
    }

    fn __repr__(&self) -> String {
        let h = self.lut.header();
        let axes: Vec<String> = h
            .axes
            .iter()
            .map(|a| format!("{}[{}]", a.name, a.count))
            .collect();
        format!(
            "<brdf_kernels.Table {:?} {} {} bytes>",
            h.kind,
            axes.join("×"),
            self.lut.bytes().len()
        )
    }
}

/// Builds a table from a spec with the fields of `cargo xtask lut generate`'s TOML file
/// (``kind``, ``model``, ``masking``, ``roughness``, ``sigma``, ``res``, ``encoding``,
/// ``interpolation``, ``samples``, ``seed``, ``max-error``, ``out``, and ``axes``: a dict from
/// axis name to a dict of ``count``, ``lo``, ``hi``, ``warp``, ``placement``); the same spec
/// gives the same bytes as the command. Ctrl-C stops the build.
///
/// Parameters
/// ----------
/// spec : dict
///     As above; ``max_error`` is accepted for ``max-error``. With ``out`` the table is also
///     saved there (temporary file, then rename).
///
/// Returns
/// -------
/// Table
///
/// Raises
/// ------
/// ValueError
///     An unknown or invalid field (the message names it and the valid values).
/// LutError
///     The measured max |error| exceeds ``max-error`` (nothing is written), or the generator
///     failed.
/// KeyboardInterrupt
///     Interrupted.
#[pyfunction]
pub fn build_table(py: Python<'_>, spec: &Bound<'_, PyDict>) -> PyResult<Table> {
    let (spec, max_error, out) = spec_from(spec)?;
    let g = run_generate(py, spec)?;
    if let Some(lim) = max_error {
        let e = f64::from(g.error.max_abs);
        if e.is_nan() || e > lim {
            return Err(lut_err(format!(
                "measured max |error| {e:.3e} exceeds max-error {lim:.3e}; nothing written"
            )));
        }
    }
    let lut = Lut::from_bytes(g.bytes).map_err(load_err)?;
    if let Some(p) = out {
        py.detach(|| write_atomic(&p, lut.bytes()))
            .map_err(|e| PyOSError::new_err(format!("{}: {e}", p.display())))?;
    }
    Ok(Table { lut })
}

/// The class, function and exception of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Table>()?;
    m.add_function(wrap_pyfunction!(build_table, m)?)?;
    m.add("LutError", m.py().get_type::<LutError>())?;
    Ok(())
}

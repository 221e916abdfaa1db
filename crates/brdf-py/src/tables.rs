//! BLUT tables: build from a spec dict (the fields of `cargo xtask lut generate`'s TOML file)
//! through `brdf_lut::generate::generate`, load and save (temporary file, then rename), look
//! up with broadcasting through `brdf_lut::LutView::sample`, and the header as a dict.

use crate::arrays::{self, num, Float, Kernel};
use brdf_lut::generate::{self, DescribeError, Description, Spec, Value};
use brdf_lut::Lut;
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyList};
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

/// A Python value as the library's description value.
fn value(v: &Bound<'_, PyAny>) -> Value {
    if v.is_instance_of::<PyBool>() {
        return Value::Other("bool".into());
    }
    if let Ok(s) = v.extract::<String>() {
        return Value::Text(s);
    }
    if let Ok(i) = v.extract::<i64>() {
        return Value::Int(i);
    }
    if let Ok(x) = v.extract::<f64>() {
        return Value::Float(x);
    }
    let t = v.get_type().name().map(|n| n.to_string()).unwrap_or_default();
    Value::Other(t)
}

fn spec_err(e: DescribeError) -> PyErr {
    PyValueError::new_err(format!("spec: {e}"))
}

/// The dict read into the library's description (the fields of `cargo xtask lut generate`'s
/// TOML file, `brdf_lut::generate::Description`); `out` may be any path-like.
fn description(d: &Bound<'_, PyDict>) -> PyResult<Description> {
    let mut desc = Description::default();
    for (k, v) in d.iter() {
        let k: String = k.extract()?;
        match k.as_str() {
            "axes" => {
                let axes = v
                    .cast_into::<PyDict>()
                    .map_err(|_| PyValueError::new_err("spec field `axes` must be a dict"))?;
                for (name, fields) in axes.iter() {
                    let name: String = name.extract()?;
                    let fields = fields.cast_into::<PyDict>().map_err(|_| {
                        PyValueError::new_err(format!("spec axis `{name}` must be a dict"))
                    })?;
                    desc.name_axis(&name);
                    for (f, x) in fields.iter() {
                        let f: String = f.extract()?;
                        desc.set_axis(&name, &f, value(&x)).map_err(spec_err)?;
                    }
                }
            }
            "out" => desc.out = Some(v.extract::<PathBuf>()?),
            _ => desc.set(&k, value(&v)).map_err(spec_err)?,
        }
    }
    Ok(desc)
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
    let desc = description(spec)?;
    let spec = desc.spec().map_err(spec_err)?;
    let g = run_generate(py, spec.clone())?;
    desc.check_max_error(&spec, g.error.max_abs).map_err(lut_err)?;
    let lut = Lut::from_bytes(g.bytes).map_err(load_err)?;
    if let Some(p) = desc.out {
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

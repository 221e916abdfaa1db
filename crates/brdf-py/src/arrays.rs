//! NumPy in, NumPy out: the dtype rule, broadcasting, and one generic driver that runs a
//! [`Kernel`] over equally long contiguous slices with the GIL released.
//!
//! Dtype rule: the result is float32 when every array argument is float32 (or float16) and
//! float64 otherwise; Python numbers do not vote (as in NumPy 2). Integer and boolean arrays
//! are converted to float64; any other dtype is refused with `TypeError`.

use brdf_core::Real;
use numpy::ndarray::{ArrayViewD, Axis, IxDyn};
use numpy::{
    Element, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyMemoryError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyFloat, PyInt, PyTuple};

/// The two element types of the API.
pub trait Float: Real + Element + Send + Sync + 'static {
    /// NumPy's name of the dtype.
    const DTYPE: &'static str;
}
impl Float for f32 {
    const DTYPE: &'static str = "float32";
}
impl Float for f64 {
    const DTYPE: &'static str = "float64";
}

/// A computation over equally long contiguous slices: `inp` holds one slice per scalar
/// input component (a direction contributes three: x, y, z), `out` one per output component.
/// Generic over the element type, so f32 and f64 share one source.
pub trait Kernel: Sync {
    /// Runs the kernel; an error text becomes `ValueError`.
    fn run<T: Float>(&self, inp: &[&[T]], out: &mut [&mut [T]]) -> Result<(), String>;
    /// Elements per chunk (at most [`CHUNK`]): a kernel that costs microseconds per element
    /// takes fewer, so that Ctrl-C is seen within a fraction of a second.
    fn chunk(&self) -> usize {
        CHUNK
    }
}

/// Elements per chunk of an array call: the size of the temporaries (one chunk per input
/// and output component, whatever the broadcast size) and the unit of work between two
/// checks for signals.
pub const CHUNK: usize = 65_536;

/// The width of an output that is one number per element (shape = the broadcast shape); a
/// width `w` ≥ 1 adds a last axis of length `w`.
pub const SCALAR: usize = 0;

/// One argument: its name (for messages), the object, and 1 (a number per element) or 3
/// (a direction per element: the last axis has length 3).
pub struct Arg<'a, 'py> {
    pub name: &'static str,
    pub obj: &'a Bound<'py, PyAny>,
    pub width: usize,
}

/// Shorthand for an [`Arg`] of width 1.
pub fn num<'a, 'py>(name: &'static str, obj: &'a Bound<'py, PyAny>) -> Arg<'a, 'py> {
    Arg {
        name,
        obj,
        width: 1,
    }
}

/// Shorthand for an [`Arg`] of width 3.
pub fn dir<'a, 'py>(name: &'static str, obj: &'a Bound<'py, PyAny>) -> Arg<'a, 'py> {
    Arg {
        name,
        obj,
        width: 3,
    }
}

fn is_number(o: &Bound<'_, PyAny>) -> bool {
    (o.is_exact_instance_of::<PyFloat>() || o.is_exact_instance_of::<PyInt>())
        && !o.is_instance_of::<pyo3::types::PyBool>()
}

fn numpy_fn<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    static NP: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
    let np = NP.get_or_try_init(py, || py.import("numpy").map(Bound::unbind))?;
    np.bind(py).getattr(name)
}

/// Whether one argument asks for float32 (`Some(true)`), float64 (`Some(false)`) or does not
/// vote (a Python number).
fn vote(py: Python<'_>, a: &Arg<'_, '_>) -> PyResult<Option<bool>> {
    if is_number(a.obj) {
        return Ok(None);
    }
    let converted;
    let arr = match a.obj.cast::<PyUntypedArray>() {
        Ok(arr) => arr,
        Err(_) => {
            converted = numpy_fn(py, "asarray")?.call1((a.obj,))?;
            converted.cast::<PyUntypedArray>()?
        }
    };
    let dt = arr.dtype();
    let (kind, size) = (dt.kind(), dt.itemsize());
    match kind {
        b'f' if size <= 4 => Ok(Some(true)),
        b'f' | b'b' | b'i' | b'u' => Ok(Some(false)),
        _ => Err(PyTypeError::new_err(format!(
            "argument `{}` has dtype {}; give float32 or float64 numbers",
            a.name,
            dt.str()?
        ))),
    }
}

/// True when the result is float32 (every array argument float32/float16).
pub fn wants_f32(py: Python<'_>, args: &[Arg<'_, '_>]) -> PyResult<bool> {
    let mut any = false;
    for a in args {
        match vote(py, a)? {
            Some(false) => return Ok(false),
            Some(true) => any = true,
            None => {}
        }
    }
    Ok(any)
}

/// The broadcast shape of `shapes` under NumPy's rules, or `ValueError` naming the shapes.
pub fn broadcast(names: &[&str], shapes: &[Vec<usize>]) -> PyResult<Vec<usize>> {
    let nd = shapes.iter().map(Vec::len).max().unwrap_or(0);
    let mut out = vec![1usize; nd];
    for s in shapes {
        for (k, &d) in s.iter().rev().enumerate() {
            let o = &mut out[nd - 1 - k];
            if *o == 1 {
                *o = d;
            } else if d != 1 && d != *o {
                let list: Vec<String> = names
                    .iter()
                    .zip(shapes)
                    .map(|(n, s)| format!("`{n}` {}", shape_text(s)))
                    .collect();
                return Err(PyValueError::new_err(format!(
                    "shapes do not broadcast: {}",
                    list.join(", ")
                )));
            }
        }
    }
    Ok(out)
}

/// `(2, 3)` in Python's notation.
pub fn shape_text(s: &[usize]) -> String {
    match s {
        [a] => format!("({a},)"),
        _ => {
            let p: Vec<String> = s.iter().map(usize::to_string).collect();
            format!("({})", p.join(", "))
        }
    }
}

/// A vector of `n` elements or `MemoryError`.
pub fn alloc<T: Float>(n: usize) -> PyResult<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| {
        PyMemoryError::new_err(format!(
            "cannot allocate {n} {} values for the result",
            T::DTYPE
        ))
    })?;
    v.resize(n, T::NAN);
    Ok(v)
}

/// Each argument converted to a `T` array (a read-only NumPy array the views borrow from).
fn convert<'py, T: Float>(
    py: Python<'py>,
    args: &[Arg<'_, 'py>],
) -> PyResult<Vec<Bound<'py, PyArrayDyn<T>>>> {
    let asarray = numpy_fn(py, "asarray")?;
    args.iter()
        .map(|a| {
            let arr = match a.obj.cast::<PyArrayDyn<T>>() {
                Ok(arr) => arr.clone(),
                Err(_) => {
                    let kw = [("dtype", T::DTYPE)].into_py_dict(py)?;
                    asarray
                        .call((a.obj,), Some(&kw))?
                        .cast_into::<PyArrayDyn<T>>()?
                }
            };
            let sh = arr.shape();
            if a.width == 3 && sh.last() != Some(&3) {
                return Err(PyValueError::new_err(format!(
                    "argument `{}` must hold directions, shape (..., 3); got shape {}",
                    a.name,
                    shape_text(sh)
                )));
            }
            Ok(arr)
        })
        .collect()
}

use pyo3::types::IntoPyDict;

/// The scalar components of every argument (x, y, z for a direction) as views.
fn components<'a, T: Float>(
    args: &[Arg<'_, '_>],
    views: &'a [ArrayViewD<'a, T>],
) -> Vec<(ArrayViewD<'a, T>, &'static str)> {
    let mut v = Vec::new();
    for (a, view) in args.iter().zip(views) {
        if a.width == 3 {
            let last = Axis(view.ndim() - 1);
            for k in 0..3 {
                v.push((view.index_axis(last, k), a.name));
            }
        } else {
            v.push((view.view(), a.name));
        }
    }
    v
}

/// Where one input component's values come from, chunk by chunk.
enum Source<'a, T> {
    /// Already contiguous in the broadcast shape: each chunk is a sub-slice, no copy.
    Slice(&'a [T]),
    /// Any other layout (strided, transposed, broadcast): read in logical (C) order, one
    /// run of the last axis at a time, into a chunk-sized buffer.
    Lanes(Lanes<'a, T>),
}

/// The lanes (runs along the last axis) of a broadcast view, and the position reached.
struct Lanes<'a, T> {
    iter: numpy::ndarray::iter::LanesIter<'a, T, IxDyn>,
    lane: Option<numpy::ndarray::ArrayView1<'a, T>>,
    at: usize,
}

impl<'a, T: Copy> Lanes<'a, T> {
    /// `view` must have at least one axis.
    fn new(view: &'a ArrayViewD<'a, T>) -> Self {
        Self {
            iter: view.lanes(Axis(view.ndim() - 1)).into_iter(),
            lane: None,
            at: 0,
        }
    }

    /// Appends the next `m` values to `buf` (fewer only when the view is exhausted).
    fn read(&mut self, m: usize, buf: &mut Vec<T>) {
        let mut left = m;
        while left > 0 {
            let lane = match &self.lane {
                Some(l) if self.at < l.len() => l,
                _ => match self.iter.next() {
                    Some(l) => {
                        self.at = 0;
                        self.lane.insert(l)
                    }
                    None => return,
                },
            };
            let k = left.min(lane.len() - self.at);
            buf.extend((self.at..self.at + k).map(|j| lane[j]));
            self.at += k;
            left -= k;
        }
    }
}

/// The product of `shape`, or `MemoryError` when it does not fit in `usize`.
fn element_count(shape: &[usize], width: usize) -> PyResult<usize> {
    shape
        .iter()
        .try_fold(width.max(1), |n, &d| n.checked_mul(d))
        .ok_or_else(|| {
            PyMemoryError::new_err(format!(
                "a result of shape {} × {width} does not fit in memory",
                shape_text(shape)
            ))
        })
}

/// The result arrays: a [`SCALAR`] output has the broadcast shape (a NumPy scalar when that
/// is `()`), a width-`w` output the broadcast shape + `(w,)` (its components interleaved).
fn assemble<'py, T: Float>(
    py: Python<'py>,
    shape: &[usize],
    widths: &[usize],
    finals: Vec<Vec<T>>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    widths
        .iter()
        .zip(finals)
        .map(|(&w, v)| {
            let mut sh = shape.to_vec();
            if w != SCALAR {
                sh.push(w);
            }
            let a = numpy::PyArray1::from_vec(py, v)
                .reshape(&sh[..])?
                .into_any();
            if sh.is_empty() {
                // A 0-d result is a NumPy scalar, as a ufunc returns.
                return a.get_item(PyTuple::empty(py));
            }
            Ok(a)
        })
        .collect()
}

/// Fills `out` (one chunk per component, outputs in turn) for elements `at..at + m`: the
/// inputs are chunk slices (borrowed or read into `bufs`), a [`SCALAR`] output is written in
/// place, a wider one into `tmp` and then interleaved into its result.
#[allow(clippy::too_many_arguments)]
fn run_chunk<T: Float, K: Kernel>(
    k: &K,
    sources: &mut [Source<'_, T>],
    bufs: &mut [Vec<T>],
    tmp: &mut [Vec<T>],
    finals: &mut [Vec<T>],
    widths: &[usize],
    at: usize,
    m: usize,
) -> Result<(), String> {
    let mut ins: Vec<&[T]> = Vec::with_capacity(sources.len());
    for (src, buf) in sources.iter_mut().zip(bufs.iter_mut()) {
        ins.push(match src {
            Source::Slice(s) => &s[at..at + m],
            Source::Lanes(l) => {
                buf.clear();
                l.read(m, buf);
                &buf[..]
            }
        });
    }
    let mut tmp_it = tmp.iter_mut();
    let mut outs: Vec<&mut [T]> = Vec::new();
    for (&w, fin) in widths.iter().zip(finals.iter_mut()) {
        if w == SCALAR {
            outs.push(&mut fin[at..at + m]);
        } else {
            for t in tmp_it.by_ref().take(w) {
                t.resize(m, T::NAN);
                outs.push(&mut t[..]);
            }
        }
    }
    k.run(&ins, &mut outs)?;
    drop(outs);
    let mut t = tmp.iter();
    for (&w, fin) in widths.iter().zip(finals.iter_mut()) {
        if w == SCALAR {
            continue;
        }
        for c in 0..w {
            let Some(src) = t.next() else { break };
            for (i, &x) in src.iter().enumerate() {
                fin[(at + i) * w + c] = x;
            }
        }
    }
    Ok(())
}

/// Runs `k` over the broadcast arguments in `T`, [`Kernel::chunk`] elements at a time: the
/// temporaries are one chunk per component whatever the broadcast size (only the result
/// scales with it), the GIL is released while a chunk computes, and signals (Ctrl-C) are
/// checked between chunks.
fn run_typed<'py, T: Float, K: Kernel>(
    py: Python<'py>,
    args: &[Arg<'_, 'py>],
    widths: &[usize],
    k: &K,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let arrays = convert::<T>(py, args)?;
    let ro: Vec<_> = arrays.iter().map(|a| a.readonly()).collect();
    let views: Vec<ArrayViewD<'_, T>> = ro.iter().map(|r| r.as_array()).collect();
    let comps = components(args, &views);
    let names: Vec<&str> = args.iter().map(|a| a.name).collect();
    let shapes: Vec<Vec<usize>> = args
        .iter()
        .zip(&views)
        .map(|(a, v)| {
            let lead = if a.width == 3 { v.ndim() - 1 } else { v.ndim() };
            v.shape()[..lead].to_vec()
        })
        .collect();
    let shape = broadcast(&names, &shapes)?;
    let n = element_count(&shape, 1)?;
    // At least one axis, so that every view has lanes (a 0-d call is one element).
    let shape1: Vec<usize> = if shape.is_empty() {
        vec![1]
    } else {
        shape.clone()
    };
    let bviews: Vec<ArrayViewD<'_, T>> = comps
        .iter()
        .map(|(v, _)| {
            v.broadcast(IxDyn(&shape1))
                .ok_or_else(|| PyValueError::new_err("internal: broadcast failed"))
        })
        .collect::<PyResult<_>>()?;
    let mut sources: Vec<Source<'_, T>> = comps
        .iter()
        .zip(&bviews)
        .map(|((v, _), b)| match v.as_slice() {
            Some(s) if v.shape() == &shape[..] => Source::Slice(s),
            _ => Source::Lanes(Lanes::new(b)),
        })
        .collect();
    let mut finals = Vec::with_capacity(widths.len());
    for &w in widths {
        finals.push(alloc::<T>(element_count(&shape, w)?)?);
    }
    let size = k.chunk().clamp(1, CHUNK);
    let mut bufs: Vec<Vec<T>> = sources.iter().map(|_| Vec::new()).collect();
    let wide = widths.iter().filter(|&&w| w != SCALAR).sum::<usize>();
    let mut tmp: Vec<Vec<T>> = (0..wide).map(|_| Vec::new()).collect();
    let mut at = 0;
    while at < n {
        let m = size.min(n - at);
        py.check_signals()?;
        py.detach(|| {
            run_chunk(
                k,
                &mut sources,
                &mut bufs,
                &mut tmp,
                &mut finals,
                widths,
                at,
                m,
            )
        })
        .map_err(PyValueError::new_err)?;
        at += m;
    }
    assemble(py, &shape, widths, finals)
}

/// Evaluates `k` on `args` with NumPy broadcasting and returns one object per output width
/// (an array; a Python float when every argument is a Python number and every output is
/// [`SCALAR`]).
pub fn run<'py, K: Kernel>(
    py: Python<'py>,
    args: &[Arg<'_, 'py>],
    widths: &[usize],
    k: &K,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    if args.iter().all(|a| a.width == 1 && is_number(a.obj)) && widths.iter().all(|&w| w == SCALAR)
    {
        return run_scalar(py, args, widths, k);
    }
    if wants_f32(py, args)? {
        run_typed::<f32, K>(py, args, widths, k)
    } else {
        run_typed::<f64, K>(py, args, widths, k)
    }
}

/// The scalar path: Python numbers in, Python floats out (f64), no NumPy call.
fn run_scalar<'py, K: Kernel>(
    py: Python<'py>,
    args: &[Arg<'_, 'py>],
    widths: &[usize],
    k: &K,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let mut vals = [0.0f64; 8];
    let nin = args.len().min(8);
    for (v, a) in vals.iter_mut().zip(args) {
        *v = a.obj.extract::<f64>()?;
    }
    let ins: [&[f64]; 8] = std::array::from_fn(|i| &vals[i..=i]);
    let mut outv = [f64::NAN; 8];
    let nout = widths.len().min(8);
    {
        let mut it = outv.chunks_mut(1);
        let mut os: [&mut [f64]; 8] = std::array::from_fn(|_| it.next().unwrap_or_default());
        k.run(&ins[..nin], &mut os[..nout])
            .map_err(PyValueError::new_err)?;
    }
    Ok(outv[..nout]
        .iter()
        .map(|&x| PyFloat::new(py, x).into_any())
        .collect())
}

/// The one result of a call with one output.
pub fn single(mut v: Vec<Bound<'_, PyAny>>) -> PyResult<Bound<'_, PyAny>> {
    v.pop()
        .ok_or_else(|| PyValueError::new_err("internal: no result"))
}

/// One result, or a tuple of several.
pub fn one_or_tuple<'py>(
    py: Python<'py>,
    mut v: Vec<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    if v.len() == 1 {
        if let Some(x) = v.pop() {
            return Ok(x);
        }
    }
    Ok(PyTuple::new(py, v)?.into_any())
}

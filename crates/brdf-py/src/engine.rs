//! Engine lookup textures: the split-sum (A, B) table in one engine's container and layout,
//! made by the `brdf-engine-assets` library (the same calls as `cargo xtask lut engine`, so
//! the same bytes) and written through temporary files.

use crate::tables::{lut_err, run_cancellable, write_temp};
use brdf_engine_assets::{split_sum_texels, Engine, File, SplitSumTexels, MAX_SIZE};
use pyo3::exceptions::{PyFileExistsError, PyOSError, PyValueError};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// The engines by name (`"all"`: every one, each into its own sub-folder).
fn engines(name: &str) -> PyResult<Vec<(Engine, bool)>> {
    if name == "all" {
        return Ok(Engine::ALL.iter().map(|&e| (e, true)).collect());
    }
    Engine::ALL
        .iter()
        .find(|e| e.name() == name)
        .map(|&e| vec![(e, false)])
        .ok_or_else(|| {
            let names: Vec<&str> = Engine::ALL.iter().map(|e| e.name()).collect();
            PyValueError::new_err(format!(
                "argument `engine` = {name:?} is not one of {}, all",
                names.join(", ")
            ))
        })
}

/// The n × n texels through the library's generator, interruptible by Ctrl-C.
fn texels(py: Python<'_>, n: usize) -> PyResult<SplitSumTexels> {
    match run_cancellable(py, move |p| split_sum_texels(n, p))? {
        Some(Ok(t)) => Ok(t),
        Some(Err(e)) => Err(lut_err(e)),
        None => Err(lut_err(
            "the engine table computation failed (internal error)",
        )),
    }
}

/// Writes one set of files into `dir`: every file first to a temporary file beside its
/// target (synced), and only when all are written, each renamed into place; on an error
/// the temporaries are removed. Without `force` an existing target is an error (nothing
/// written).
fn write_set(py: Python<'_>, dir: &Path, files: &[File], force: bool) -> PyResult<Vec<PathBuf>> {
    let os = |p: &Path, e: std::io::Error| PyOSError::new_err(format!("{}: {e}", p.display()));
    std::fs::create_dir_all(dir).map_err(|e| os(dir, e))?;
    let targets: Vec<PathBuf> = files.iter().map(|f| dir.join(&f.name)).collect();
    if !force {
        if let Some(p) = targets.iter().find(|p| p.exists()) {
            return Err(PyFileExistsError::new_err(format!(
                "{} exists (pass force=True to replace it)",
                p.display()
            )));
        }
    }
    py.detach(|| {
        let mut temps = Vec::new();
        let res = (|| {
            for (f, p) in files.iter().zip(&targets) {
                temps.push(write_temp(p, &f.bytes).map_err(|e| (p.clone(), e))?);
            }
            for (t, p) in temps.iter().zip(&targets) {
                std::fs::rename(t, p).map_err(|e| (p.clone(), e))?;
            }
            Ok(())
        })();
        if res.is_err() {
            for t in &temps {
                let _ = std::fs::remove_file(t);
            }
        }
        res
    })
    .map_err(|(p, e)| os(&p, e))?;
    Ok(targets)
}

/// Writes the split-sum lookup texture of a game or web engine: GGX with height-correlated
/// Smith, α = r² (r = perceptual roughness), each texel the integral at its own centre, in
/// the engine's container, channel layout and orientation, with a JSON sidecar and GLSL/WGSL
/// sampling functions. The files are byte for byte those of
/// ``cargo xtask lut engine <engine> --size <size>`` (both call the ``brdf-engine-assets``
/// library). Ctrl-C stops the computation.
///
/// Parameters
/// ----------
/// engine : {"khronos", "bevy", "filament", "threejs", "exr", "all"}
///     The engine (see docs/engines.md); "all" writes every engine into its own sub-folder
///     of `out_dir`, each at its native size.
/// out_dir : str or os.PathLike
///     The folder (created when missing).
/// size : int, optional
///     The table edge N (N × N texels), 2 … 4096; default the engine's own (khronos 1024;
///     bevy, filament, exr 64; threejs 16). Not with "all".
/// force : bool
///     Replace existing files (default: an existing file is an error and nothing is
///     written).
///
/// Returns
/// -------
/// list of str
///     The paths written.
///
/// Raises
/// ------
/// ValueError
///     Unknown engine, size outside 2 … 4096, a size with "all".
/// FileExistsError
///     A file exists and `force` is false.
/// OSError
///     A file cannot be written (no partial file is left: temporary files, then renames).
/// LutError
///     The generator or a container encoder failed.
/// KeyboardInterrupt
///     Interrupted.
#[pyfunction]
#[pyo3(signature = (engine, out_dir, *, size=None, force=false))]
pub fn export_engine(
    py: Python<'_>,
    engine: &str,
    out_dir: PathBuf,
    size: Option<usize>,
    force: bool,
) -> PyResult<Vec<String>> {
    let list = engines(engine)?;
    if let Some(n) = size {
        if engine == "all" {
            return Err(PyValueError::new_err(
                "argument `size` applies to one engine, not to \"all\" (each has its own size)",
            ));
        }
        if !(2..=MAX_SIZE).contains(&n) {
            return Err(PyValueError::new_err(format!(
                "argument `size` = {n} is outside its range 2 … {MAX_SIZE}"
            )));
        }
    }
    let mut written = Vec::new();
    let mut grid: Option<SplitSumTexels> = None;
    for (e, sub) in list {
        let n = size.unwrap_or(e.native_size());
        if grid.as_ref().is_none_or(|g| g.n != n) {
            grid = Some(texels(py, n)?);
        }
        let Some(t) = grid.as_ref() else { continue };
        let files = e.target_files(t).map_err(lut_err)?;
        let dir = if sub {
            out_dir.join(e.name())
        } else {
            out_dir.clone()
        };
        for p in write_set(py, &dir, &files, force)? {
            written.push(p.to_string_lossy().into_owned());
        }
    }
    Ok(written)
}

/// The function of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(export_engine, m)?)
}

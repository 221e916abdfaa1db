//! `brdf_kernels`: the brdf-kernels reflection models, G factors and BLUT tables for Python
//! and NumPy. Every function is a thin layer over the Rust crates (`brdf_core::batch`, the
//! scalar kernels, `brdf_core::catalogue`, `brdf_lut::generate`, `brdf_lut::Lut`,
//! `brdf_engine_assets`): the values are theirs bit for bit.

mod arrays;
mod engine;
mod g;
mod models;
mod tables;

use pyo3::prelude::*;

/// The native module (re-exported by the `brdf_kernels` package).
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    g::register(m)?;
    models::register(m)?;
    tables::register(m)?;
    engine::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

//! Engine lookup textures: the split-sum pair (A, B) for GGX with height-correlated Smith,
//! α = r² (r = perceptual roughness), in the container, channel layout, orientation, texel
//! placement and roughness convention that one engine's shader samples, with a JSON sidecar
//! and GLSL/WGSL sampling functions. One function per engine layout returns the files'
//! names and bytes ([`khronos`], [`bevy`], [`filament`], [`threejs`], [`exr()`]); writing them
//! is the caller's; [`fsio::write_together`] writes them safely (temporary file + rename,
//! no partial files, nothing replaced without `force`).
//!
//! Every texel holds the integral at its own texel centre, computed in f64 by the one table
//! generator ([`brdf_lut::generate`]: brdf-core's converged polar rule, each texel refined
//! until its error estimate is below 2e-6 per channel), then rounded to nearest in the
//! target encoding.
//!
//! ```
//! let t = brdf_engine_assets::split_sum_texels(4, &|_| {}).unwrap();
//! let files = brdf_engine_assets::khronos(&t).unwrap();
//! assert!(files.iter().any(|f| f.name == "lut_ggx.png"));
//! ```
//!
//! Crate, not a `brdf-lut` feature: the containers need Zstandard (a C library), OpenEXR,
//! PNG, DDS and JSON code that the `no_std` format crate and its size and MSRV budgets should
//! not carry.

mod containers;
pub mod cycles;
pub mod eevee;
pub mod export;
pub mod fsio;
mod layouts;
pub mod report;
mod shaders;
pub mod sidecar;
pub mod table_shaders;

pub use containers::{half_bits, unorm16, unorm8};
pub use cycles::cycles;
pub use layouts::{
    bevy, exr, filament, filament_cloth, glass, glass_spec, khronos, khronos_sheen, sheen_texels,
    threejs, CLOTH_TOL,
};
pub use shaders::{functions, Functions};

use brdf_lut::generate::{self, AxisSpec, Distribution, GenError, Kind, Masking, Spec};
use brdf_lut::{Placement, Warp};
use std::fmt;

/// The largest table edge accepted (a 4096² table is 16 Mi integrals: hours of CPU).
pub const MAX_SIZE: usize = 4096;

/// One output file: its name (no folders) and bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct File {
    /// The file name.
    pub name: String,
    /// The file's bytes.
    pub bytes: Vec<u8>,
}

/// The crate's results.
pub(crate) type Result<T> = std::result::Result<T, Error>;

/// Why an engine table could not be made.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// The table edge is outside 2..=[`MAX_SIZE`].
    Size(usize),
    /// The generator refused the table.
    Generate(GenError),
    /// A container encoder failed; the text says which and why.
    Encode(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Size(n) => write!(
                f,
                "--size {n}: the table edge must be between 2 and {MAX_SIZE}"
            ),
            Error::Generate(e) => write!(f, "generating the table: {e}"),
            Error::Encode(s) => f.write_str(s),
        }
    }
}

impl std::error::Error for Error {}

/// The engines this crate writes for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// glTF Sample Viewer `lut_ggx.png` (8-bit, plus 16-bit RGB and 16-bit per-channel PNGs).
    Khronos,
    /// Bevy `dfg.ktx2` (KTX2 R16G16_SFLOAT, Zstandard).
    Bevy,
    /// Filament `cmgen --ibl-dfg-multiscatter` DDS (R16G16B16A16_FLOAT, R = B, G = A + B).
    Filament,
    /// three.js DFG LUT: raw little-endian RG16F pairs (A, B), memory row = μ, and a JS module.
    Threejs,
    /// 32-bit float OpenEXR (R = A, G = B), μ along x, r down the rows.
    Exr,
}

impl Engine {
    /// Every engine.
    pub const ALL: [Engine; 5] = [
        Engine::Khronos,
        Engine::Bevy,
        Engine::Filament,
        Engine::Threejs,
        Engine::Exr,
    ];
    /// The engine's name on the command line and in sidecars.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Khronos => "khronos",
            Engine::Bevy => "bevy",
            Engine::Filament => "filament",
            Engine::Threejs => "threejs",
            Engine::Exr => "exr",
        }
    }
    /// The engine's own table edge.
    pub fn native_size(self) -> usize {
        match self {
            Engine::Khronos => 1024,
            Engine::Bevy | Engine::Filament | Engine::Exr => 64,
            Engine::Threejs => 16,
        }
    }
    /// The engine's files for these texels (its layout function).
    pub fn files(self, t: &SplitSumTexels) -> Result<Vec<File>> {
        match self {
            Engine::Khronos => khronos(t),
            Engine::Bevy => bevy(t),
            Engine::Filament => filament(t),
            Engine::Threejs => threejs(t),
            Engine::Exr => exr(t),
        }
    }
    /// Everything the engine's target writes for these texels (what `cargo xtask lut engine`
    /// and the Python package's `export_engine` write): [`Engine::files`] with Filament's
    /// cloth channel filled ([`filament_cloth`]) and, for Khronos, the two sheen textures
    /// ([`sheen_texels`], [`khronos_sheen`]) at the same edge. The sheen values cost about 4 s
    /// of CPU whatever the edge (their converged nodes).
    pub fn target_files(self, t: &SplitSumTexels) -> Result<Vec<File>> {
        let mut files = match self {
            Engine::Filament => filament_cloth(t)?,
            _ => self.files(t)?,
        };
        if self == Engine::Khronos {
            let [ek, ash] = sheen_texels(t.n)?;
            files.extend(khronos_sheen(t.n, &ek, &ash)?);
        }
        Ok(files)
    }
}

/// Exact texel values: `a[row * n + col]`, `b[..]` with col = μ index, row = r index, both at
/// texel centres (i + ½)/n.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitSumTexels {
    /// The table edge.
    pub n: usize,
    /// A at each texel.
    pub a: Vec<f64>,
    /// B at each texel.
    pub b: Vec<f64>,
}

/// Texel centre i of an n-wide axis.
pub fn centre(i: usize, n: usize) -> f64 {
    (i as f64 + 0.5) / n as f64
}

/// The generator spec of an n × n engine table: split sum, GGX, height-correlated Smith,
/// perceptual roughness, μ (fastest) and r on [0, 1] at texel centres.
pub fn split_sum_spec(n: usize) -> Spec {
    let mut s = Spec::new(Kind::SplitSum, Distribution::Ggx, Masking::SmithCorrelated);
    let axis = AxisSpec {
        placement: Placement::TexelCentre,
        ..AxisSpec::endpoint(n.min(u32::MAX as usize) as u32, 0.0, 1.0, Warp::Linear)
    };
    s.axes = vec![axis, axis];
    s
}

/// The converged split sum (A, B) at (μ, r), from the generator's kernel.
pub fn integral(mu: f64, r: f64) -> (f64, f64) {
    let v = split_sum_spec(2).value(&[mu, r]);
    (v[0], v[1])
}

/// All n² texel-centre integrals through the generator, on all cores; `progress(k)` is
/// called with the number of texels just finished.
pub fn split_sum_texels(n: usize, progress: &(dyn Fn(u64) + Sync)) -> Result<SplitSumTexels> {
    if !(2..=MAX_SIZE).contains(&n) {
        return Err(Error::Size(n));
    }
    let v = generate::evaluate(&split_sum_spec(n), progress).map_err(Error::Generate)?;
    Ok(SplitSumTexels {
        n,
        a: v.iter().step_by(2).copied().collect(),
        b: v.iter().skip(1).step_by(2).copied().collect(),
    })
}

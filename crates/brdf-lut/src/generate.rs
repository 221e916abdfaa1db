//! Tables built to order: one call from a [`Spec`] (table kind, model, roughness
//! parameterisation, axes, encoding) to the bytes of a validated LUT file with its measured
//! error in the header.
//!
//! ```
//! use brdf_lut::generate::{generate, Spec, Kind, Distribution, Masking};
//! let mut spec = Spec::new(Kind::AverageAlbedo, Distribution::Ggx, Masking::SmithCorrelated);
//! spec.axes[0].count = 4;
//! spec.samples = 16;
//! let t = generate(&spec, &|_| {}).unwrap();
//! let lut = brdf_lut::Lut::from_bytes(t.bytes).unwrap();
//! assert!(lut.e_avg(0.5).unwrap() > 0.8);
//! ```
//!
//! Every node holds the direct f64 kernel at that node:
//! - split sum (A, B) = (∫ W(1 − F_c) D cos θh dωh, ∫ W F_c D cos θh dωh) with Schlick F
//!   (F90 = 1) [`brdf_core::split_sum::split_sum`];
//! - directional albedo E(μ) = A + B (F = 1), and its cosine-weighted average
//!   E_avg = 2∫₀¹ E(μ) μ dμ (Kulla–Conty energy compensation);
//! - the passing factor F(θ, φ) = M(θ, (θ − φ)/2) of the modified G (the 2015 Acta Physica
//!   Sinica paper, eqs 6–13) for one σ or over a σ axis.
//!
//! Roughness parameterisation of the roughness axis: perceptual r (distribution width r²),
//! the width itself (GGX α, Beckmann m), or the RMS slope σ of Gaussian slopes (Beckmann
//! m = √2 σ; undefined for GGX, whose slope variance is infinite). The axis is named
//! `roughness`, `alpha`/`m` or `sigma` in the file accordingly.

//!
//! This module is the only code that computes table node values: the default asset set
//! ([`default_set`]), `cargo xtask lut generate`, the engine textures (through
//! [`evaluate`]) and `lut verify` (through [`measure`]) all build a [`Spec`] and call it.
//! The kinds it knows are one list ([`Kind::def`], `generate/kinds.rs`).

mod defaults;
pub mod describe;
pub(crate) mod entry;
pub mod glass;
mod integrate;
pub(crate) mod kinds;
mod measure;
pub(crate) mod sheen;
mod verify;
mod work;

pub use defaults::{default_set, Asset, DEFAULT_SET_TOOL};
pub use describe::{check_limits, DescribeError, Description, Value};
pub use entry::{Check, KindDef, Role};
pub use integrate::{ggx_converged, GgxQuery, Work, REFERENCE_TOL, TOL as INTEGRATION_TOL};
pub use measure::measure;
pub use sheen::{
    sheen_e, sheen_e_reference, sheen_grid, SheenE, SheenGrid, GRID_DEGREE as SHEEN_GRID_DEGREE,
    GRID_NODE_TOL as SHEEN_GRID_NODE_TOL, GRID_R_MIN as SHEEN_GRID_R_MIN,
    REFERENCE_TOL as SHEEN_REFERENCE_TOL, TOL as SHEEN_TOL,
};
pub use verify::{
    allowed_above, check_nodes, check_recorded_bound, measure_table, sample_nodes, verify_points,
    worse_than_recorded, BoundCheck, Measured, NodeCheck, OverBudget, VerifyPoints, Worse,
    FALSE_ALARM,
};

use crate::write;
use crate::{
    Axis, Convention, Encoding, ErrorStats, Generator, Header, Interpolation, List, Model,
    Placement, Warp, MAX_AXIS_COUNT,
};
use brdf_core::masking::ModifiedG;
use brdf_core::models::GeometricTerm;
pub use brdf_core::models::SheenVisibility;
use core::f64::consts::FRAC_PI_2;
use std::fmt;
use std::format;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

/// cos 89°: the default smallest μ of split-sum and albedo tables.
pub const MU_MIN: f64 = 0.017_452_406_437_283_5;

/// The largest table this generator builds (nodes × channels: a 4096² two-channel engine
/// texture); larger requests are refused before any work. The values are held as f64
/// (256 MiB at this limit). The tools' limit [`crate::limits::MAX_BUILD_VALUES`] itself.
pub const MAX_GENERATED_VALUES: u64 = crate::limits::MAX_BUILD_VALUES;

/// The generator's name in the headers of tables built to order.
pub const TOOL: &str = "brdf-lut generate";

/// What the table holds, and the one list of kinds (`generate/kinds.rs`).
pub use kinds::{Kind, KINDS};

/// The microfacet distribution: the model catalogue's
/// ([`brdf_core::catalogue::DISTRIBUTIONS`]; names, other spellings and the G terms each
/// is tabulated with are there).
pub use brdf_core::catalogue::DistributionId as Distribution;

/// The shadowing–masking function G of a generated table: the catalogue's G terms
/// ([`brdf_core::catalogue::MASKINGS`]) that the generator integrates. Names are the
/// catalogue's ([`Masking::name`], [`Masking::from_name`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Masking {
    /// Smith, separable: G1(i) G1(o).
    SmithSeparable,
    /// Smith, height-correlated: 1/(1 + Λ(i) + Λ(o)).
    SmithCorrelated,
    /// The V-cavity G of Torrance–Sparrow in Blinn's form (catalogue name `blinn`).
    Blinn,
    /// The paper's modified G (reciprocal 3-D extension).
    Modified,
}

#[allow(non_upper_case_globals)]
impl Masking {
    /// The old name of [`Masking::Blinn`], kept for callers.
    pub const VCavity: Masking = Masking::Blinn;
    /// Every option.
    pub const ALL: [Masking; 4] = [
        Masking::SmithSeparable,
        Masking::SmithCorrelated,
        Masking::Blinn,
        Masking::Modified,
    ];
    /// The catalogue's G term.
    pub const fn term(self) -> GeometricTerm {
        match self {
            Masking::SmithSeparable => GeometricTerm::SmithSeparable,
            Masking::SmithCorrelated => GeometricTerm::SmithCorrelated,
            Masking::Blinn => GeometricTerm::Blinn,
            Masking::Modified => GeometricTerm::Modified,
        }
    }
    /// The option of a catalogue G term; `None` for a term the generator does not integrate.
    pub fn from_term(g: GeometricTerm) -> Option<Masking> {
        Masking::ALL.into_iter().find(|m| m.term() == g)
    }
    /// The catalogue's name.
    pub const fn name(self) -> &'static str {
        self.term().name()
    }
    /// Parses a catalogue name or other spelling (`v-cavity` is `blinn`); `None` for an
    /// unknown name or a term the generator does not integrate.
    pub fn from_name(s: &str) -> Option<Masking> {
        GeometricTerm::from_name(s).and_then(Masking::from_term)
    }
    /// Every option by the catalogue's name and other spellings (`v-cavity`), for parsers
    /// that list the accepted names.
    pub fn options() -> Vec<(&'static str, Masking)> {
        let m = brdf_core::catalogue::MASKINGS.iter();
        m.filter_map(|m| Some((m, Masking::from_term(m.term)?)))
            .flat_map(|(m, g)| {
                core::iter::once(&m.name)
                    .chain(m.aliases)
                    .map(move |n| (*n, g))
            })
            .collect()
    }
}

/// Every distribution by the catalogue's name and other spellings, for parsers that list
/// the accepted names.
pub fn distribution_options() -> Vec<(&'static str, Distribution)> {
    let d = brdf_core::catalogue::DISTRIBUTIONS.iter();
    d.flat_map(|d| {
        core::iter::once(&d.name)
            .chain(d.aliases)
            .map(|n| (*n, d.id))
    })
    .collect()
}

/// What the roughness axis (or `Kind::GPerSigma`'s σ) means: brdf-core's one vocabulary
/// ([`brdf_core::roughness::Roughness`], names and conversions there).
pub use brdf_core::roughness::Roughness;

/// One axis of the requested grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisSpec {
    /// Number of nodes (≥ 2).
    pub count: u32,
    /// Smallest value.
    pub lo: f64,
    /// Largest value.
    pub hi: f64,
    /// How the unit coordinate maps to the value.
    pub warp: Warp,
    /// Where the nodes sit in the unit coordinate.
    pub placement: Placement,
}

impl AxisSpec {
    /// `count` nodes from `lo` to `hi` inclusive (endpoint placement).
    pub fn endpoint(count: u32, lo: f64, hi: f64, warp: Warp) -> Self {
        AxisSpec {
            count,
            lo,
            hi,
            warp,
            placement: Placement::Endpoint,
        }
    }
}

/// A table to build: the one description shared by the library, the command line and TOML
/// files (`cargo xtask lut generate`) and the default asset set.
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// What the table holds.
    pub kind: Kind,
    /// The distribution.
    pub distribution: Distribution,
    /// The masking function.
    pub masking: Masking,
    /// The roughness parameterisation.
    pub roughness: Roughness,
    /// The axes, in the kind's order (see [`Spec::axis_names`]).
    pub axes: Vec<AxisSpec>,
    /// The stored encoding.
    pub encoding: Encoding,
    /// The interpolation readers use.
    pub interpolation: Interpolation,
    /// Random points of the error measurement (≥ 1).
    pub samples: u32,
    /// Seed of the error measurement.
    pub seed: u64,
    /// The generator's name recorded in the header ([`TOOL`] unless set).
    pub tool: String,
}

/// Why a spec cannot be built; each names the real problem.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum GenError {
    /// An option is invalid; the text says which and why.
    Invalid(String),
    /// A node value came out non-finite (a defect of the kernel at that node).
    NonFinite {
        /// The node's coordinates.
        at: Vec<f64>,
    },
    /// The encoder refused the table (should not happen for a validated spec).
    Encode(String),
}

impl fmt::Display for GenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GenError::Invalid(s) => f.write_str(s),
            GenError::NonFinite { at } => write!(f, "non-finite kernel value at the node {at:?}"),
            GenError::Encode(s) => write!(f, "encoding the table: {s}"),
        }
    }
}

impl std::error::Error for GenError {}

fn invalid<T>(s: impl Into<String>) -> Result<T, GenError> {
    Err(GenError::Invalid(s.into()))
}

/// A generated table.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// The measured error (also in the header).
    pub error: ErrorStats,
    /// The largest integration error estimate over all nodes, as recorded in the header.
    pub integration: f32,
    /// Integrand evaluations over all nodes (as [`Evaluated::evals`]).
    pub evals: u64,
}

impl Spec {
    /// A spec with the default grid of `kind` for this model (the default roughness
    /// parameterisation: σ for Torrance–Sparrow and the G tables, perceptual r otherwise).
    pub fn new(kind: Kind, distribution: Distribution, masking: Masking) -> Self {
        let roughness = if distribution == Distribution::TorranceSparrow
            || kind.def().check == Check::ModifiedG
        {
            Roughness::Sigma
        } else {
            Roughness::Perceptual
        };
        let mut s = Spec {
            kind,
            distribution,
            masking,
            roughness,
            axes: vec![],
            encoding: Encoding::Unorm16,
            interpolation: Interpolation::CatmullRom,
            samples: 2_000,
            seed: 0x5EED_0001,
            tool: TOOL.to_string(),
        };
        s.axes = s.default_axes();
        s
    }

    /// The default axes of this kind and roughness parameterisation.
    pub fn default_axes(&self) -> Vec<AxisSpec> {
        let def = self.kind.def();
        def.axes
            .iter()
            .map(|&(role, n)| role.default_axis(self, n))
            .collect()
    }

    /// The axis names of this kind, in order.
    pub fn axis_names(&self) -> Vec<&'static str> {
        let def = self.kind.def();
        def.axes.iter().map(|&(role, _)| role.name(self)).collect()
    }

    /// The name of the roughness axis in this parameterisation.
    fn roughness_name(&self) -> &'static str {
        match (self.roughness, self.distribution) {
            (Roughness::Perceptual, _) => "roughness",
            (Roughness::Alpha, d) => d.spec().width,
            (Roughness::Sigma, _) => "sigma",
        }
    }

    /// σ of a per-σ G table.
    fn fixed_sigma(&self) -> Option<f64> {
        match self.kind {
            Kind::GPerSigma { sigma } => Some(sigma),
            _ => None,
        }
    }

    /// The header's model code of this spec (its kind's rule, [`KindDef::model`]).
    pub fn model(&self) -> Result<Model, GenError> {
        (self.kind.def().model)(self)
    }

    /// The header's model code for this distribution and G (the catalogue's mapping,
    /// [`Model::from_catalogue`]): the microfacet kinds' [`KindDef::model`].
    pub fn microfacet_model(&self) -> Result<Model, GenError> {
        let g = self.masking.term();
        let d = (self.kind.def().check != Check::ModifiedG).then_some(self.distribution);
        match Model::from_catalogue(d, g) {
            Some((m, _)) => Ok(m),
            None => invalid(format!(
                "the {} G goes with the Torrance–Sparrow (Gaussian-slope) distribution only, \
                 not {}; {} takes {}",
                g.name(),
                self.distribution.name(),
                self.distribution.name(),
                tabulated_names(self.distribution).join(" or ")
            )),
        }
    }

    /// Checks every option; the error names the real problem.
    pub fn validate(&self) -> Result<(), GenError> {
        let names = self.axis_names();
        if self.axes.len() != names.len() {
            return invalid(format!(
                "a {:?} table has {} axes ({}), {} given",
                self.kind,
                names.len(),
                names.join(", "),
                self.axes.len()
            ));
        }
        self.validate_model()?;
        let mut values: u64 = self.kind.def().channels.len() as u64;
        for (a, &(role, _)) in self.axes.iter().zip(self.kind.def().axes) {
            self.validate_axis(a, role)?;
            values = values.saturating_mul(a.count as u64);
        }
        if values > MAX_GENERATED_VALUES {
            return invalid(format!(
                "{values} values (nodes × channels) is more than this generator builds \
                 ({MAX_GENERATED_VALUES})"
            ));
        }
        if self.samples == 0 {
            return invalid("the error measurement needs at least 1 sample");
        }
        Ok(())
    }

    /// The model options: the kind's own ([`KindDef::validate`]; its model for every kind
    /// but the G tables, which hold no BRDF); GGX has no σ.
    fn validate_model(&self) -> Result<(), GenError> {
        let def = self.kind.def();
        if def.check != Check::ModifiedG {
            self.model()?;
        }
        (def.validate)(self)?;
        if self.distribution == Distribution::Ggx && self.roughness == Roughness::Sigma {
            return invalid(
                "GGX has no RMS slope σ (its slope variance is infinite): choose the \
                 perceptual or alpha parameterisation",
            );
        }
        Ok(())
    }

    /// One axis: node count, range within the role's domain, warp.
    fn validate_axis(&self, a: &AxisSpec, role: Role) -> Result<(), GenError> {
        let name = role.name(self);
        if a.count < 2 {
            return invalid(format!(
                "axis {name}: {} node(s); an axis needs at least 2 nodes",
                a.count
            ));
        }
        if a.count > MAX_AXIS_COUNT {
            return invalid(format!(
                "axis {name}: {} nodes; the format allows at most {MAX_AXIS_COUNT}",
                a.count
            ));
        }
        if !(a.lo.is_finite() && a.hi.is_finite()) {
            return invalid(format!("axis {name}: the range must be finite"));
        }
        if a.lo >= a.hi {
            return invalid(format!(
                "axis {name}: the range [{}, {}] is empty; lo must be below hi",
                a.lo, a.hi
            ));
        }
        let (min, max, what) = role.domain(self);
        if a.lo < min || a.hi > max {
            return invalid(format!(
                "axis {name}: [{}, {}] leaves the domain {what} [{min}, {max}]",
                a.lo, a.hi
            ));
        }
        match a.warp {
            Warp::Log if a.lo <= 0.0 => invalid(format!(
                "axis {name}: a log warp needs lo > 0 (got {})",
                a.lo
            )),
            Warp::Cos if a.hi > core::f64::consts::PI || a.lo < 0.0 => {
                invalid(format!("axis {name}: a cos warp needs an angle in [0, π]"))
            }
            Warp::SqrtCos if a.hi > FRAC_PI_2 || a.lo < 0.0 => invalid(format!(
                "axis {name}: a sqrt-cos warp needs an angle in [0, π/2]"
            )),
            _ => Ok(()),
        }
    }

    /// The distribution width (GGX α, Beckmann m) and the RMS slope σ (m/√2; NaN-free only
    /// where defined) of a roughness-axis value. σ is the axis value itself when the axis is
    /// σ, so the modified G sees exactly the tabulated σ.
    fn width_sigma(&self, x: f64) -> (f64, f64) {
        self.roughness.width_and_sigma(x)
    }

    /// The direct f64 kernel at a point of the table's domain: one value per channel.
    pub fn value(&self, x: &[f64]) -> Vec<f64> {
        let def = self.kind.def();
        let mut out = vec![0.0; def.channels.len()];
        (def.point)(self, x, &mut out);
        out
    }

    /// The direct f64 kernel at a point of the table's domain (one value per channel) and
    /// its integration [`Work`]: the estimate of its error and the evaluations it took
    /// (`generate/integrate.rs`).
    pub fn integral(&self, x: &[f64]) -> (Vec<f64>, Work) {
        let def = self.kind.def();
        let mut out = vec![0.0; def.channels.len()];
        let w = (def.value)(self, x, &mut out);
        (out, w)
    }

    /// The quadrature node counts the header records ([`KindDef::record`]).
    fn nodes_record(&self) -> &'static [u16] {
        (self.kind.def().record)(self)
    }

    fn header_axes(&self) -> Vec<Axis<'static>> {
        self.axes
            .iter()
            .zip(self.axis_names())
            .map(|(a, name)| Axis {
                name,
                count: a.count,
                lo: a.lo,
                hi: a.hi,
                warp: a.warp,
                placement: a.placement,
            })
            .collect()
    }
}

impl Spec {
    /// The spec a table's header describes (its kind, model, roughness axis, grid, encoding,
    /// error-measurement settings and tool), so a file can be re-measured or rebuilt; `None`
    /// for a header this generator cannot describe.
    pub fn from_header(h: &Header<'_>) -> Option<Spec> {
        let def = KINDS
            .iter()
            .map(|(_, k)| k.def())
            .find(|d| d.table == h.kind && d.axes.len() == h.axes.len())?;
        let (kind, distribution, masking) = (def.from_header)(def, h)?;
        // The roughness parameterisation is the roughness axis's name; a kind without one
        // (the G tables: σ) keeps its default.
        let mut spec = Spec::new(kind, distribution, masking);
        if let Some(i) = def.axes.iter().position(|a| a.0 == Role::Roughness) {
            spec.roughness = match h.axes.get(i).map(|a| a.name) {
                Some("roughness") => Roughness::Perceptual,
                Some("alpha") | Some("m") => Roughness::Alpha,
                Some("sigma") => Roughness::Sigma,
                _ => return None,
            };
        }
        spec.axes = h
            .axes
            .iter()
            .map(|a| AxisSpec {
                placement: a.placement,
                ..AxisSpec::endpoint(a.count, a.lo, a.hi, a.warp)
            })
            .collect();
        (spec.encoding, spec.interpolation) = (h.encoding, h.interpolation);
        (spec.samples, spec.seed) = (h.error.samples.max(1), h.error.seed);
        spec.tool = h.generator.tool.to_string();
        let names = spec.axis_names();
        if h.axes.iter().zip(&names).any(|(a, n)| a.name != *n) {
            return None;
        }
        Some(spec)
    }
}

/// The names of the G terms tables are made with over `d` (the catalogue's list).
fn tabulated_names(d: Distribution) -> Vec<&'static str> {
    let t = d
        .spec()
        .tabulated
        .iter()
        .filter_map(|&g| Masking::from_term(g));
    t.map(Masking::name).collect()
}

/// The modified G's one-sided passing factor F(θ, φ) = M(θ, (θ − φ)/2) for RMS slope σ
/// (the 2015 Acta Physica Sinica paper, eqs 6–13), its integral by the rule `R`.
fn passing_with<R: brdf_core::quadrature::Rule>(sigma: f64, theta: f64, phi: f64) -> f64 {
    ModifiedG::<f64, R>::new(sigma)
        .map(|g| g.passing(theta, (theta - phi) * 0.5))
        .unwrap_or(f64::NAN)
}

/// The worker threads of `par_chunks`: `RAYON_NUM_THREADS` when set to a whole number
/// ≥ 1 (the usual spelling, though this is not rayon), else every core. The results do not
/// depend on it (each value is computed alone and lands in its own slot).
pub fn threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .filter(|&n| n >= 1)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// Calls `f(k, chunk)` for every `len`-long chunk `k` of `out`, on [`threads`] workers;
/// each worker takes one contiguous run of chunks, so results land in order whatever the
/// thread count.
pub(crate) fn par_chunks<T: Send>(out: &mut [T], len: usize, f: &(dyn Fn(usize, &mut [T]) + Sync)) {
    par_chunks_on(threads(), out, len, f)
}

/// [`par_chunks`] on `threads` workers (at least 1).
fn par_chunks_on<T: Send>(
    threads: usize,
    out: &mut [T],
    len: usize,
    f: &(dyn Fn(usize, &mut [T]) + Sync),
) {
    let len = len.max(1);
    let chunks = out.len().div_ceil(len);
    let threads = threads.max(1);
    let per = chunks.div_ceil(threads).max(1);
    std::thread::scope(|s| {
        for (t, block) in out.chunks_mut(per * len).enumerate() {
            s.spawn(move || {
                for (j, c) in block.chunks_mut(len).enumerate() {
                    f(t * per + j, c);
                }
            });
        }
    });
}

/// A table's node values with their integration record.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluated {
    /// Node-major (axis 0 fastest), channels interleaved (`values[node × C + c]`).
    pub values: Vec<f64>,
    /// The largest integration error estimate over all nodes and channels.
    pub integration: f64,
    /// Integrand evaluations over all nodes (those the rule counts: not the polar E_avg).
    pub evals: u64,
}

/// Validates the spec and computes every node's values on all cores: node-major (axis 0
/// fastest), channels interleaved (`values[node × C + c]`). `progress(k)` is called with
/// the number of nodes just finished. A non-finite value is an error naming its node.
pub fn evaluate(spec: &Spec, progress: &(dyn Fn(u64) + Sync)) -> Result<Vec<f64>, GenError> {
    Ok(evaluate_with_error(spec, progress)?.values)
}

/// [`evaluate`], with each node's integration estimate and work ([`Evaluated`]).
pub fn evaluate_with_error(
    spec: &Spec,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Evaluated, GenError> {
    evaluate_on(threads(), spec, progress)
}

/// [`evaluate_with_error`] on `threads` workers. The values, the maximum and the sum do
/// not depend on the thread count: each node is computed alone into its own slot, and the
/// reductions (max, integer sum) are exact in any order.
fn evaluate_on(
    threads: usize,
    spec: &Spec,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Evaluated, GenError> {
    spec.validate()?;
    let axes = spec.header_axes();
    let def = spec.kind.def();
    let nc = def.channels.len();
    let total: usize = axes.iter().map(|a| a.count as usize).product();
    let n0 = axes[0].count as usize;
    // Rows along axis 0, so a worker's unit of work shares everything but the fastest
    // axis. Each node's slot: its channels, then its estimate and evaluations.
    let stride = nc + 2;
    let mut flat = vec![0.0; total * stride];
    par_chunks_on(threads, &mut flat, n0 * stride, &|r, v| {
        let coords = |i| write::node_coords(&axes, r * n0 + i);
        let mus: Vec<f64> = (0..n0).map(|i| coords(i)[0]).collect();
        let rx = coords(0).get(1).copied().unwrap_or(f64::NAN);
        let row = def.row.and_then(|row| row(spec, &mus, rx, stride, v));
        if row.is_none() {
            for (i, out) in v.chunks_mut(stride).enumerate() {
                let w = (def.value)(spec, &coords(i), &mut out[..nc]);
                (out[nc], out[nc + 1]) = (w.error, w.evals as f64);
            }
        }
        progress(n0 as u64);
    });
    let mut values = Vec::with_capacity(total * nc);
    let (mut integration, mut evals) = (0f64, 0u64);
    for (k, node) in flat.chunks_exact(stride).enumerate() {
        if node.iter().any(|x| !x.is_finite()) {
            return Err(GenError::NonFinite {
                at: write::node_coords(&axes, k).to_vec(),
            });
        }
        values.extend_from_slice(&node[..nc]);
        integration = integration.max(node[nc]);
        evals += node[nc + 1] as u64;
    }
    Ok(Evaluated {
        values,
        integration,
        evals,
    })
}

/// `lut verify`'s independent reference at `x`: (values, its own error estimate), by the
/// kind's rule ([`KindDef::reference`]).
pub fn reference(spec: &Spec, x: &[f64]) -> ([f64; 2], f64) {
    (spec.kind.def().reference)(spec, x)
}

/// Builds the table: validates, computes every node ([`evaluate_with_error`]), quantises,
/// measures the interpolation error at `samples` random points ([`measure`]), records the
/// largest integration error estimate (rounded up to f32) and encodes. Deterministic: the
/// same spec gives the same bytes, whatever the thread count.
pub fn generate(spec: &Spec, progress: &(dyn Fn(u64) + Sync)) -> Result<Generated, GenError> {
    let ev = evaluate_with_error(spec, progress)?;
    let axes = spec.header_axes();
    let def = spec.kind.def();
    let ws = write::Spec {
        kind: def.table,
        axes: &axes,
        channels: def.channels,
        encoding: spec.encoding,
        interpolation: spec.interpolation,
        generator: Generator {
            model: spec.model()?,
            convention: Convention::Reciprocal,
            sigma: spec.fixed_sigma(),
            nodes: List::from_slice(spec.nodes_record()).unwrap_or_default(),
            tool: &spec.tool,
        },
    };
    let mut error = ErrorStats::default();
    let bound = f32_up(ev.integration);
    let bytes = write::build_with_bound(&ws, &ev.values, Some(bound), |view| {
        error = measure(spec, view, &view.header().axes);
        error
    })
    .map_err(|e| GenError::Encode(e.to_string()))?;
    Ok(Generated {
        bytes,
        error,
        integration: bound,
        evals: ev.evals,
    })
}

/// The smallest f32 ≥ x (x finite, ≥ 0), so the recorded bound never rounds below the
/// estimate.
fn f32_up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x {
        f32::from_bits(f.to_bits() + 1)
    } else {
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The node values, the bound and the evaluation count are the same on 1, 2 and 3
    /// workers (each node alone in its slot): a GGX split sum and a Beckmann albedo
    /// (converged polar rule) and a V-cavity Torrance–Sparrow albedo (fixed and coarser
    /// rules), on grids that do not split evenly.
    #[test]
    fn evaluation_does_not_depend_on_the_thread_count() {
        let mut a = Spec::new(Kind::SplitSum, Distribution::Ggx, Masking::SmithCorrelated);
        a.axes[0].count = 7;
        a.axes[1].count = 5;
        let mut b = Spec::new(
            Kind::Albedo,
            Distribution::Beckmann,
            Masking::SmithCorrelated,
        );
        b.axes[0].count = 3;
        b.axes[1].count = 5;
        let mut c = b.clone();
        (c.distribution, c.masking) = (Distribution::TorranceSparrow, Masking::VCavity);
        c.roughness = Roughness::Sigma;
        c.axes = c.default_axes();
        c.axes[0].count = 3;
        c.axes[1].count = 5;
        for s in [a, b, c] {
            let one = evaluate_on(1, &s, &|_| {}).unwrap();
            for t in [2, 3] {
                assert_eq!(evaluate_on(t, &s, &|_| {}).unwrap(), one, "{t} threads");
            }
            assert!(one.integration > 0.0 && one.evals > 0);
        }
    }
}

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

use crate::write::{self, ErrorAccumulator};
use crate::{
    Axis, Convention, Encoding, ErrorStats, Generator, Header, Interpolation, List, LutView, Model,
    Placement, TableKind, Warp, MAX_AXIS_COUNT,
};
use brdf_core::geometry::Dots;
use brdf_core::masking::{
    g_blinn_dots, g_smith_beckmann_correlated, g_smith_beckmann_separable, g_smith_ggx_correlated,
    g_smith_ggx_separable, ModifiedG,
};
use brdf_core::quadrature::{GaussLegendre, DEFAULT_NODES};
use brdf_core::split_sum::{e_avg, split_sum, InnerRule, Ndf, OuterRule};
use core::f64::consts::{FRAC_PI_2, SQRT_2};
use rand::{Rng, SeedableRng};
use std::fmt;
use std::format;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

/// cos 89°: the default smallest μ of split-sum and albedo tables.
pub const MU_MIN: f64 = 0.017_452_406_437_283_5;

/// The largest table this generator builds (nodes × channels); larger requests are refused
/// before any work.
pub const MAX_GENERATED_VALUES: u64 = 1 << 24;

/// The generator's name in the headers.
pub const TOOL: &str = "brdf-lut generate";

/// What the table holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// The modified G's passing factor F(θ, φ) for one σ (2 axes: theta, phi).
    GPerSigma {
        /// The RMS slope σ > 0.
        sigma: f64,
    },
    /// The modified G's passing factor F(θ, φ, σ) (3 axes: theta, phi, sigma).
    GOverSigma,
    /// Split-sum (A, B) (2 axes: mu, roughness).
    SplitSum,
    /// Directional albedo E(μ) with F = 1 (2 axes: mu, roughness).
    Albedo,
    /// Average albedo E_avg (1 axis: roughness).
    AverageAlbedo,
}

/// The microfacet distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// GGX (Trowbridge–Reitz).
    Ggx,
    /// Beckmann.
    Beckmann,
    /// Torrance–Sparrow: Gaussian slopes of RMS slope σ, i.e. Beckmann with m = √2 σ.
    TorranceSparrow,
}

/// The shadowing–masking function G.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Masking {
    /// Smith, separable: G1(i) G1(o).
    SmithSeparable,
    /// Smith, height-correlated: 1/(1 + Λ(i) + Λ(o)).
    SmithCorrelated,
    /// The V-cavity G of Torrance–Sparrow (Blinn's form).
    VCavity,
    /// The paper's modified G (reciprocal 3-D extension).
    Modified,
}

/// What the roughness axis (or `Kind::GPerSigma`'s σ) means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Roughness {
    /// Perceptual r ∈ [0, 1]: width = r².
    Perceptual,
    /// The distribution width itself: GGX α, Beckmann m.
    Alpha,
    /// RMS slope σ of Gaussian slopes: Beckmann m = √2 σ.
    Sigma,
}

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

/// A table to build.
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
}

fn ax(count: u32, lo: f64, hi: f64, warp: Warp) -> AxisSpec {
    AxisSpec {
        count,
        lo,
        hi,
        warp,
        placement: Placement::Endpoint,
    }
}

impl Spec {
    /// A spec with the default grid of `kind` for this model (the default roughness
    /// parameterisation: σ for Torrance–Sparrow and the G tables, perceptual r otherwise).
    pub fn new(kind: Kind, distribution: Distribution, masking: Masking) -> Self {
        let roughness = if distribution == Distribution::TorranceSparrow
            || matches!(kind, Kind::GPerSigma { .. } | Kind::GOverSigma)
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
        };
        s.axes = s.default_axes();
        s
    }

    /// The default axes of this kind and roughness parameterisation.
    pub fn default_axes(&self) -> Vec<AxisSpec> {
        // The modified G needs a width > 0.
        let r0 = if self.masking == Masking::Modified {
            0.05
        } else {
            0.0
        };
        let rough = |n| match self.roughness {
            Roughness::Perceptual | Roughness::Alpha => ax(n, r0, 1.0, Warp::Linear),
            Roughness::Sigma => ax(n, 0.05, 1.0, Warp::Log),
        };
        let theta = |n| ax(n, 0.0, FRAC_PI_2, Warp::SqrtCos);
        let phi = |n| ax(n, -FRAC_PI_2, FRAC_PI_2, Warp::Linear);
        match self.kind {
            Kind::GPerSigma { .. } => vec![theta(128), phi(126)],
            Kind::GOverSigma => vec![theta(64), phi(64), ax(31, 0.05, 1.0, Warp::Log)],
            Kind::SplitSum | Kind::Albedo => vec![ax(64, MU_MIN, 1.0, Warp::Log), rough(64)],
            Kind::AverageAlbedo => vec![rough(32)],
        }
    }

    /// The axis names of this kind, in order.
    pub fn axis_names(&self) -> Vec<&'static str> {
        let rough = match (self.roughness, self.distribution) {
            (Roughness::Perceptual, _) => "roughness",
            (Roughness::Alpha, Distribution::Ggx) => "alpha",
            (Roughness::Alpha, _) => "m",
            (Roughness::Sigma, _) => "sigma",
        };
        match self.kind {
            Kind::GPerSigma { .. } => vec!["theta", "phi"],
            Kind::GOverSigma => vec!["theta", "phi", "sigma"],
            Kind::SplitSum | Kind::Albedo => vec!["mu", rough],
            Kind::AverageAlbedo => vec![rough],
        }
    }

    /// The header's model name for this distribution and G.
    pub fn model(&self) -> Result<Model, GenError> {
        use Distribution as D;
        use Masking as M;
        if matches!(self.kind, Kind::GPerSigma { .. } | Kind::GOverSigma) {
            return Ok(Model::ModifiedG);
        }
        Ok(match (self.distribution, self.masking) {
            (D::Ggx, M::SmithCorrelated) => Model::GgxSmithCorrelated,
            (D::Ggx, M::SmithSeparable) => Model::GgxSmithSeparable,
            (D::Beckmann, M::SmithCorrelated) => Model::BeckmannSmithCorrelated,
            (D::Beckmann, M::SmithSeparable) => Model::BeckmannSmithSeparable,
            (D::TorranceSparrow, M::SmithCorrelated) => Model::TorranceSparrowSmith,
            (D::TorranceSparrow, M::SmithSeparable) => Model::TorranceSparrowSmithSeparable,
            (D::TorranceSparrow, M::VCavity) => Model::TorranceSparrowVCavity,
            (D::TorranceSparrow, M::Modified) => Model::TorranceSparrowModifiedG,
            (d, m) => {
                return invalid(format!(
                    "{m:?} G goes with the Torrance–Sparrow (Gaussian-slope) distribution only, \
                     not {d:?}; GGX and Beckmann take smith-separable or smith-correlated"
                ))
            }
        })
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
        let g_table = matches!(self.kind, Kind::GPerSigma { .. } | Kind::GOverSigma);
        if g_table {
            if self.masking != Masking::Modified {
                return invalid(
                    "G tables hold the modified G's passing factor: choose the modified G \
                     (the Smith and V-cavity G are closed forms that need no table)",
                );
            }
            if self.roughness != Roughness::Sigma {
                return invalid("G tables are parameterised by the RMS slope σ only");
            }
        } else {
            self.model()?;
        }
        if self.distribution == Distribution::Ggx && self.roughness == Roughness::Sigma {
            return invalid(
                "GGX has no RMS slope σ (its slope variance is infinite): choose the \
                 perceptual or alpha parameterisation",
            );
        }
        if let Kind::GPerSigma { sigma } = self.kind {
            if !(sigma.is_finite() && sigma > 0.0) {
                return invalid(format!("σ of a per-σ G table must be > 0 (got {sigma})"));
            }
        }
        let mut values: u64 = self.channels().len() as u64;
        for (a, name) in self.axes.iter().zip(&names) {
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
            values = values.saturating_mul(a.count as u64);
            if !(a.lo.is_finite() && a.hi.is_finite()) {
                return invalid(format!("axis {name}: the range must be finite"));
            }
            if a.lo >= a.hi {
                return invalid(format!(
                    "axis {name}: the range [{}, {}] is empty; lo must be below hi",
                    a.lo, a.hi
                ));
            }
            let (min, max, what) = self.domain(name);
            if a.lo < min || a.hi > max {
                return invalid(format!(
                    "axis {name}: [{}, {}] leaves the domain {what} [{min}, {max}]",
                    a.lo, a.hi
                ));
            }
            match a.warp {
                Warp::Log if a.lo <= 0.0 => {
                    return invalid(format!(
                        "axis {name}: a log warp needs lo > 0 (got {})",
                        a.lo
                    ))
                }
                Warp::Cos if a.hi > core::f64::consts::PI || a.lo < 0.0 => {
                    return invalid(format!("axis {name}: a cos warp needs an angle in [0, π]"))
                }
                Warp::SqrtCos if a.hi > FRAC_PI_2 || a.lo < 0.0 => {
                    return invalid(format!(
                        "axis {name}: a sqrt-cos warp needs an angle in [0, π/2]"
                    ))
                }
                _ => {}
            }
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

    /// The admissible range of an axis, and its description.
    fn domain(&self, name: &str) -> (f64, f64, &'static str) {
        let sigma_min = if self.masking == Masking::Modified {
            f64::MIN_POSITIVE
        } else {
            0.0
        };
        match name {
            "theta" => (0.0, FRAC_PI_2, "θ (radians)"),
            "phi" => (-FRAC_PI_2, FRAC_PI_2, "φ (radians)"),
            "mu" => (0.0, 1.0, "μ = cos θ"),
            "roughness" => (sigma_min, 1.0, "perceptual r (the modified G needs r > 0)"),
            "sigma" => (sigma_min, 4.0, "σ (the modified G needs σ > 0)"),
            _ => (
                sigma_min,
                4.0,
                "width α or m (the modified G needs a width > 0)",
            ),
        }
    }

    fn channels(&self) -> Vec<&'static str> {
        match self.kind {
            Kind::GPerSigma { .. } | Kind::GOverSigma => vec!["F"],
            Kind::SplitSum => vec!["A", "B"],
            Kind::Albedo => vec!["E"],
            Kind::AverageAlbedo => vec!["Eavg"],
        }
    }

    /// The distribution width (GGX α, Beckmann m) of a roughness-axis value.
    fn width(&self, x: f64) -> f64 {
        match self.roughness {
            Roughness::Perceptual => x * x,
            Roughness::Alpha => x,
            Roughness::Sigma => SQRT_2 * x,
        }
    }

    /// The split sum (A, B) at μ for roughness-axis value `x`.
    fn ab(&self, mu: f64, x: f64) -> (f64, f64) {
        let w = self.width(x);
        if w <= 1e-7 && self.masking != Masking::Modified {
            // Mirror limit: D → δ, G → 1: A = 1 − (1 − μ)⁵, B = (1 − μ)⁵.
            if mu <= 0.0 {
                return (0.0, 0.0);
            }
            let fc = (1.0 - mu.min(1.0)).powi(5);
            return (1.0 - fc, fc);
        }
        type Ss = fn(f64, Ndf<f64>, &dyn Fn(Dots<f64>) -> f64) -> (f64, f64);
        let ss: Ss = |mu, ndf, g| split_sum::<f64, OuterRule, InnerRule>(mu, ndf, g);
        let ndf = match self.distribution {
            Distribution::Ggx => Ndf::Ggx(w),
            _ => Ndf::Beckmann(w),
        };
        match (self.distribution, self.masking) {
            (Distribution::Ggx, Masking::SmithSeparable) => {
                ss(mu, ndf, &|d| g_smith_ggx_separable(d.n_i, d.n_o, w))
            }
            (Distribution::Ggx, _) => ss(mu, ndf, &|d| g_smith_ggx_correlated(d.n_i, d.n_o, w)),
            (_, Masking::SmithSeparable) => {
                ss(mu, ndf, &|d| g_smith_beckmann_separable(d.n_i, d.n_o, w))
            }
            (_, Masking::SmithCorrelated) => {
                ss(mu, ndf, &|d| g_smith_beckmann_correlated(d.n_i, d.n_o, w))
            }
            (_, Masking::VCavity) => ss(mu, ndf, &g_blinn_dots),
            (_, Masking::Modified) => match ModifiedG::<f64>::new(w / SQRT_2) {
                Ok(g) => ss(mu, ndf, &|d| g.g_dots(d)),
                Err(_) => (f64::NAN, f64::NAN),
            },
        }
    }

    /// The direct f64 kernel at a point of the table's domain: one value per channel.
    pub fn value(&self, x: &[f64]) -> Vec<f64> {
        match self.kind {
            Kind::GPerSigma { sigma } => vec![passing(sigma, x[0], x[1])],
            Kind::GOverSigma => vec![passing(x[2], x[0], x[1])],
            Kind::SplitSum => {
                let (a, b) = self.ab(x[0], x[1]);
                vec![a, b]
            }
            Kind::Albedo => {
                let (a, b) = self.ab(x[0], x[1]);
                vec![a + b]
            }
            Kind::AverageAlbedo => vec![e_avg::<f64, GaussLegendre<24>>(|mu| {
                let (a, b) = self.ab(mu, x[0]);
                a + b
            })],
        }
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
    /// The spec a table's header describes (its kind, model, roughness axis, grid, encoding
    /// and error-measurement settings), so a file can be re-measured or rebuilt; `None` for a
    /// header this generator cannot describe.
    pub fn from_header(h: &Header<'_>) -> Option<Spec> {
        use Distribution as D;
        use Masking as M;
        let kind = match (h.kind, h.axes.len()) {
            (TableKind::PassingFactor, 2) => Kind::GPerSigma {
                sigma: h.generator.sigma?,
            },
            (TableKind::PassingFactor, 3) => Kind::GOverSigma,
            (TableKind::SplitSum, 2) => Kind::SplitSum,
            (TableKind::DirectionalAlbedo, 2) => Kind::Albedo,
            (TableKind::AverageAlbedo, 1) => Kind::AverageAlbedo,
            _ => return None,
        };
        let (distribution, masking) = match h.generator.model {
            Model::ModifiedG | Model::TorranceSparrowModifiedG => (D::TorranceSparrow, M::Modified),
            Model::GgxSmithCorrelated => (D::Ggx, M::SmithCorrelated),
            Model::GgxSmithSeparable => (D::Ggx, M::SmithSeparable),
            Model::BeckmannSmithCorrelated => (D::Beckmann, M::SmithCorrelated),
            Model::BeckmannSmithSeparable => (D::Beckmann, M::SmithSeparable),
            Model::TorranceSparrowSmith => (D::TorranceSparrow, M::SmithCorrelated),
            Model::TorranceSparrowSmithSeparable => (D::TorranceSparrow, M::SmithSeparable),
            Model::TorranceSparrowVCavity => (D::TorranceSparrow, M::VCavity),
        };
        let roughness = match h.axes.last().map(|a| a.name) {
            _ if matches!(kind, Kind::GPerSigma { .. } | Kind::GOverSigma) => Roughness::Sigma,
            Some("roughness") => Roughness::Perceptual,
            Some("alpha") | Some("m") => Roughness::Alpha,
            Some("sigma") => Roughness::Sigma,
            _ => return None,
        };
        let spec = Spec {
            kind,
            distribution,
            masking,
            roughness,
            axes: h
                .axes
                .iter()
                .map(|a| AxisSpec {
                    count: a.count,
                    lo: a.lo,
                    hi: a.hi,
                    warp: a.warp,
                    placement: a.placement,
                })
                .collect(),
            encoding: h.encoding,
            interpolation: h.interpolation,
            samples: h.error.samples.max(1),
            seed: h.error.seed,
        };
        let names = spec.axis_names();
        if h.axes.iter().zip(&names).any(|(a, n)| a.name != *n) {
            return None;
        }
        Some(spec)
    }
}

/// The modified G's one-sided passing factor F(θ, φ) = M(θ, (θ − φ)/2) for RMS slope σ
/// (the 2015 Acta Physica Sinica paper, eqs 6–13).
fn passing(sigma: f64, theta: f64, phi: f64) -> f64 {
    ModifiedG::<f64>::new(sigma)
        .map(|g| g.passing(theta, (theta - phi) * 0.5))
        .unwrap_or(f64::NAN)
}

/// Builds the table: validates, computes every node (on all cores; `progress(k)` is called
/// with the number of nodes just finished), quantises, measures the error at `samples`
/// random points and encodes. Deterministic: the same spec gives the same bytes.
pub fn generate(spec: &Spec, progress: &(dyn Fn(u64) + Sync)) -> Result<Generated, GenError> {
    spec.validate()?;
    let axes = spec.header_axes();
    let total: usize = axes.iter().map(|a| a.count as usize).product();
    let coords = |flat: usize| -> Vec<f64> {
        let mut r = flat;
        axes.iter()
            .map(|a| {
                let i = (r % a.count as usize) as u32;
                r /= a.count as usize;
                a.node(i)
            })
            .collect()
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = total.div_ceil(threads).max(1);
    let mut values: Vec<Vec<f64>> = vec![Vec::new(); total];
    std::thread::scope(|s| {
        for (c, part) in values.chunks_mut(chunk).enumerate() {
            let coords = &coords;
            s.spawn(move || {
                for (k, v) in part.iter_mut().enumerate() {
                    *v = spec.value(&coords(c * chunk + k));
                    progress(1);
                }
            });
        }
    });
    let mut flat = Vec::with_capacity(total * spec.channels().len());
    for (k, v) in values.iter().enumerate() {
        if v.iter().any(|x| !x.is_finite()) {
            return Err(GenError::NonFinite { at: coords(k) });
        }
        flat.extend_from_slice(v);
    }
    let mut nodes = List::new();
    let counts: &[u16] = match spec.kind {
        Kind::GPerSigma { .. } | Kind::GOverSigma => &[DEFAULT_NODES as u16],
        Kind::AverageAlbedo => &[24, 32, 16],
        _ => &[32, 16],
    };
    for &c in counts {
        let _ = nodes.push(c);
    }
    let channels = spec.channels();
    let ws = write::Spec {
        kind: match spec.kind {
            Kind::GPerSigma { .. } | Kind::GOverSigma => TableKind::PassingFactor,
            Kind::SplitSum => TableKind::SplitSum,
            Kind::Albedo => TableKind::DirectionalAlbedo,
            Kind::AverageAlbedo => TableKind::AverageAlbedo,
        },
        axes: &axes,
        channels: &channels,
        encoding: spec.encoding,
        interpolation: spec.interpolation,
        generator: Generator {
            model: spec.model()?,
            convention: Convention::Reciprocal,
            sigma: match spec.kind {
                Kind::GPerSigma { sigma } => Some(sigma),
                _ => None,
            },
            nodes,
            tool: TOOL,
        },
    };
    let mut error = ErrorStats::default();
    let bytes = write::build(&ws, &flat, |view| {
        error = measure(spec, view, &axes);
        error
    })
    .map_err(|e| GenError::Encode(e.to_string()))?;
    Ok(Generated { bytes, error })
}

/// Max and RMS |table − direct kernel| over all channels at `spec.samples` random points
/// (seeded) between each axis's first and last node (beyond them the reader clamps).
pub fn measure(spec: &Spec, view: &LutView<'_>, axes: &[Axis<'_>]) -> ErrorStats {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(spec.seed);
    let ranges: Vec<(f64, f64)> = axes
        .iter()
        .map(|a| {
            let (p, q) = (a.node(0), a.node(a.count - 1));
            (p.min(q), p.max(q))
        })
        .collect();
    let pts: Vec<Vec<f32>> = (0..spec.samples)
        .map(|_| {
            ranges
                .iter()
                .map(|&(lo, hi)| rng.random_range(lo..=hi) as f32)
                .collect()
        })
        .collect();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = pts.len().div_ceil(threads).max(1);
    let mut errs: Vec<Vec<f64>> = vec![Vec::new(); pts.len()];
    std::thread::scope(|s| {
        for (part, ps) in errs.chunks_mut(chunk).zip(pts.chunks(chunk)) {
            s.spawn(move || {
                for (e, p) in part.iter_mut().zip(ps) {
                    // The direct kernel at the f32 point the table sees.
                    let x: Vec<f64> = p.iter().map(|&v| v as f64).collect();
                    let d = spec.value(&x);
                    let t = view.sample(p);
                    *e = d
                        .iter()
                        .zip(t.iter())
                        .map(|(a, &b)| (b as f64 - a).abs())
                        .collect();
                }
            });
        }
    });
    let mut acc = ErrorAccumulator::default();
    for &x in errs.iter().flatten() {
        acc.add(x);
    }
    acc.finish(spec.samples, spec.seed)
}

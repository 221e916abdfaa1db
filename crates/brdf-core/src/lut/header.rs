//! The LUT file header (docs/lut-format.md §3): a postcard-encoded struct, decoded without
//! allocation (strings are borrowed from the file, lists are `heapless::Vec`).

use crate::masking::Convention;
use serde::{Deserialize, Serialize};

/// The four bytes every LUT file starts with.
pub const MAGIC: [u8; 4] = *b"BLUT";
/// The format version this crate reads and writes.
pub const FORMAT_VERSION: u16 = 1;
/// Most axes a table may have.
pub const MAX_AXES: usize = 3;
/// Most channels a table may have.
pub const MAX_CHANNELS: usize = 4;
/// Most nodes along one axis.
pub const MAX_AXIS_COUNT: u32 = 65_536;
/// Most stored values (nodes × channels) in one table: 2²⁶ (a 256 MiB f32 payload).
pub const MAX_VALUES: u64 = 1 << 26;

/// What a table holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum TableKind {
    /// The paper's one-sided passing factor F(θ, φ[, σ]) = M(θ, (θ − φ)/2) (channel `F`);
    /// G = min(F(|θr|, sgn θr · θi), F(θi, θr)).
    PassingFactor,
    /// Split-sum (A, B) (channels `A`, `B`), conventions.md §8.
    SplitSum,
    /// Directional albedo E(μ, r) with F = 1 (channel `E`), Kulla–Conty.
    DirectionalAlbedo,
    /// Cosine-weighted average albedo E_avg(r) = 2∫ E(μ) μ dμ (channel `Eavg`).
    AverageAlbedo,
}

/// How a physical coordinate x ∈ [lo, hi] maps to the unit coordinate s ∈ [0, 1].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Warp {
    /// s = (x − lo)/(hi − lo).
    Linear,
    /// s = ln(x/lo)/ln(hi/lo); requires 0 < lo < hi.
    Log,
    /// s = √((x − lo)/(hi − lo)): denser near lo.
    Sqrt,
    /// s = (cos lo − cos x)/(cos lo − cos hi), x in radians within [0, π]: denser toward π/2
    /// than toward 0.
    Cos,
    /// s = (√cos lo − √cos x)/(√cos lo − √cos hi), x in radians within [0, π/2]: denser
    /// still toward π/2 (node spacing ∝ √cos x there).
    SqrtCos,
}

/// Where the nodes sit in the unit coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Placement {
    /// Node i at s = i/(n − 1): the first and last nodes are the range ends.
    Endpoint,
    /// Node i at s = (i + ½)/n (GPU texel centres).
    TexelCentre,
}

/// One axis of the grid. Axis 0 varies fastest in the payload.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Axis<'a> {
    /// Name of the physical variable, e.g. `theta`, `mu`, `roughness`, `sigma`.
    pub name: &'a str,
    /// Number of nodes, 2 ≤ count ≤ [`MAX_AXIS_COUNT`].
    pub count: u32,
    /// Lower end of the physical range.
    pub lo: f64,
    /// Upper end of the physical range (> lo).
    pub hi: f64,
    /// The map from x to s.
    pub warp: Warp,
    /// The node positions in s.
    pub placement: Placement,
}

/// One stored channel; the value is `offset + scale × stored`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Channel<'a> {
    /// Channel name, e.g. `F`, `A`, `B`, `E`.
    pub name: &'a str,
    /// Multiplier applied to the stored number (for u16: to q/65535).
    pub scale: f32,
    /// Added after scaling.
    pub offset: f32,
}

/// How each stored number is written (little-endian).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Encoding {
    /// u16, stored number = q/65535 ∈ [0, 1].
    Unorm16,
    /// IEEE binary16.
    F16,
    /// IEEE binary32.
    F32,
}

impl Encoding {
    /// Bytes per stored number.
    pub const fn bytes(self) -> usize {
        match self {
            Encoding::Unorm16 | Encoding::F16 => 2,
            Encoding::F32 => 4,
        }
    }
}

/// The interpolation the table is meant for (and its error was measured with).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Interpolation {
    /// Multilinear in the unit coordinates.
    Linear,
    /// Catmull–Rom cubic in each unit coordinate (tensor product), clamped ends.
    CatmullRom,
}

/// The reflection model a table was generated from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Model {
    /// The paper's modified G (Acta Phys. Sin. 64 184213, eqs 6–13).
    ModifiedG,
    /// GGX (α = r²) with height-correlated Smith, Schlick F (F90 = 1).
    GgxSmithCorrelated,
    /// Beckmann (m = r²) with height-correlated Smith, Schlick F (F90 = 1).
    BeckmannSmithCorrelated,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), the paper's modified G.
    TorranceSparrowModifiedG,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), height-correlated Smith G.
    TorranceSparrowSmith,
    /// GGX with separable Smith G = G1(i) G1(o), Schlick F (F90 = 1).
    GgxSmithSeparable,
    /// Beckmann with separable Smith G, Schlick F (F90 = 1).
    BeckmannSmithSeparable,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), separable Smith G.
    TorranceSparrowSmithSeparable,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), the V-cavity G of Torrance and
    /// Sparrow as used by Blinn.
    TorranceSparrowVCavity,
}

/// How the table was generated.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Generator<'a> {
    /// The model.
    pub model: Model,
    /// The reading of eq 12 (meaningful for the modified G).
    pub convention: Convention,
    /// The fixed RMS slope σ of a per-σ table, if any.
    pub sigma: Option<f64>,
    /// Quadrature node counts used by the direct kernel (outer first).
    pub nodes: heapless::Vec<u16, 4>,
    /// Free text naming the generator, e.g. `brdf-kernels xtask lut 0.1.0`.
    pub tool: &'a str,
}

/// Error of the interpolated table against the direct kernel, measured by the generator at
/// random points (not at nodes).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Largest absolute error over all channels and samples.
    pub max_abs: f32,
    /// Root-mean-square error over all channels and samples.
    pub rms: f32,
    /// Number of random points.
    pub samples: u32,
    /// Seed of the random points.
    pub seed: u64,
}

/// The decoded header. `checksum` is the CRC-32 of the encoded header bytes that precede it
/// followed by the whole payload.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header<'a> {
    /// [`MAGIC`].
    pub magic: [u8; 4],
    /// [`FORMAT_VERSION`].
    pub version: u16,
    /// What the table holds.
    pub kind: TableKind,
    /// The grid axes, fastest first.
    #[serde(borrow)]
    pub axes: heapless::Vec<Axis<'a>, MAX_AXES>,
    /// The channels, interleaved innermost.
    #[serde(borrow)]
    pub channels: heapless::Vec<Channel<'a>, MAX_CHANNELS>,
    /// Number format.
    pub encoding: Encoding,
    /// Intended interpolation.
    pub interpolation: Interpolation,
    /// Generator parameters.
    #[serde(borrow)]
    pub generator: Generator<'a>,
    /// Measured error.
    pub error: ErrorStats,
    /// CRC-32 (little-endian bytes), see above.
    pub checksum: [u8; 4],
}

impl Header<'_> {
    /// Number of grid nodes (product of the axis counts), saturating.
    pub fn nodes(&self) -> u64 {
        self.axes
            .iter()
            .fold(1u64, |n, a| n.saturating_mul(a.count as u64))
    }
    /// Payload length in bytes this header implies, saturating.
    pub fn payload_len(&self) -> u64 {
        self.nodes()
            .saturating_mul(self.channels.len() as u64)
            .saturating_mul(self.encoding.bytes() as u64)
    }
}

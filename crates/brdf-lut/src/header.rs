//! The LUT file header (docs/lut-format.md §3), decoded without allocation: strings are
//! borrowed from the file, lists are [`List`]s of fixed capacity. The byte encoding is in
//! `codec.rs`.

use core::fmt;

/// The four bytes every LUT file starts with.
pub const MAGIC: [u8; 4] = *b"BLUT";
/// The format version this crate writes. Version 2 added the header's `integration` field
/// (docs/lut-format.md §3); version 1 files (without it) are still read, with
/// [`Header::integration`] `None`.
pub const FORMAT_VERSION: u16 = 2;
/// The oldest format version this crate reads.
pub const MIN_FORMAT_VERSION: u16 = 1;
/// Most axes a table may have.
pub const MAX_AXES: usize = 3;
/// Most channels a table may have.
pub const MAX_CHANNELS: usize = 4;
/// Most nodes along one axis.
pub const MAX_AXIS_COUNT: u32 = 65_536;
/// Most stored values (nodes × channels) in one table: 2²⁶ (a 256 MiB f32 payload).
pub const MAX_VALUES: u64 = 1 << 26;
/// Most quadrature node counts recorded in [`Generator::nodes`].
pub const MAX_GENERATOR_NODES: usize = 4;
/// Largest magnitude a decoded node value may have (docs/lut-format.md §4): far above any
/// physical quantity a table holds, far enough below `f32::MAX` that no interpolation sum
/// of at most 64 taps with Catmull–Rom weights (|w| ≤ 1.25 after end folding) overflows.
pub const MAX_VALUE_MAGNITUDE: f32 = 1e30;

/// The reading of eq 12 of the 2015 Acta Physica Sinica paper on the modified G that a table
/// was generated with. The format's own enum: `brdf_core::masking::Convention` converts to
/// and from it (`From` both ways).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Convention {
    /// GS = M(θi, −α): reciprocal (docs/conventions.md §4).
    #[default]
    Reciprocal,
    /// Eq 12 as printed (not reciprocal).
    Printed,
}

/// A list of at most `N` items stored inline (the header's axes, channels and node counts).
/// Dereferences to a slice.
#[derive(Clone, Copy)]
pub struct List<T, const N: usize> {
    len: u8,
    items: [T; N],
}

impl<T: Copy + Default, const N: usize> Default for List<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy + Default, const N: usize> List<T, N> {
    /// The empty list.
    pub fn new() -> Self {
        Self {
            len: 0,
            items: [T::default(); N],
        }
    }
    /// A list holding `items`; `None` if there are more than `N`.
    pub fn from_slice(items: &[T]) -> Option<Self> {
        let mut l = Self::new();
        for &t in items {
            l.push(t).ok()?;
        }
        Some(l)
    }
    /// Appends `item`; gives it back when the list is full.
    pub fn push(&mut self, item: T) -> Result<(), T> {
        match self.items.get_mut(self.len as usize) {
            Some(slot) => {
                *slot = item;
                self.len += 1;
                Ok(())
            }
            None => Err(item),
        }
    }
    /// The items.
    pub fn as_slice(&self) -> &[T] {
        &self.items[..self.len as usize]
    }
}

impl<T, const N: usize> core::ops::Deref for List<T, N> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        // len ≤ N is kept by `push`, the only writer of `len`.
        self.items.get(..self.len as usize).unwrap_or(&[])
    }
}

impl<T: PartialEq, const N: usize> PartialEq for List<T, N> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: fmt::Debug, const N: usize> fmt::Debug for List<T, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// What a table holds: the one list of kinds (`generate/kinds.rs`).
pub use crate::generate::kinds::TableKind;

/// How a physical coordinate x ∈ [lo, hi] maps to the unit coordinate s ∈ [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Warp {
    /// s = (x − lo)/(hi − lo).
    #[default]
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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Placement {
    /// Node i at s = i/(n − 1): the first and last nodes are the range ends.
    #[default]
    Endpoint,
    /// Node i at s = (i + ½)/n (GPU texel centres).
    TexelCentre,
}

/// One axis of the grid. Axis 0 varies fastest in the payload.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Channel<'a> {
    /// Channel name, e.g. `F`, `A`, `B`, `E`.
    pub name: &'a str,
    /// Multiplier applied to the stored number (for u16: to q/65535).
    pub scale: f32,
    /// Added after scaling.
    pub offset: f32,
}

/// How each stored number is written (little-endian).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Encoding {
    /// u16, stored number = q/65535 ∈ [0, 1].
    #[default]
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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    /// Multilinear in the unit coordinates.
    #[default]
    Linear,
    /// Catmull–Rom cubic in each unit coordinate (tensor product), clamped ends.
    CatmullRom,
}

/// Defines [`Model`] from one list of `Variant = code`: the discriminant is the code on
/// disk, [`Model::from_code`] its inverse.
macro_rules! model_codes {
    ($($(#[$m:meta])* $v:ident = $c:literal,)*) => {
        /// The reflection model a table was generated from. The discriminant is the code on
        /// disk (docs/lut-format.md §3; [`Model::code`], [`Model::from_code`]); what each
        /// code means in the model catalogue's words (distribution and G term) is the one
        /// table in `kernel.rs` ([`Model::catalogue`], [`Model::from_catalogue`]).
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #[repr(u8)]
        pub enum Model {
            $($(#[$m])* $v = $c,)*
        }
        impl Model {
            /// Every model, in code order.
            pub const ALL: &'static [Model] = &[$(Model::$v),*];
            /// The model of a code on disk; `None` for an unknown code.
            pub const fn from_code(code: u32) -> Option<Model> {
                match code {
                    $($c => Some(Model::$v),)*
                    _ => None,
                }
            }
        }
    };
}

model_codes! {
    /// The paper's modified G (Acta Phys. Sin. 64 184213, eqs 6–13).
    #[default]
    ModifiedG = 0,
    /// GGX (α = r²) with height-correlated Smith, Schlick F (F90 = 1).
    GgxSmithCorrelated = 1,
    /// Beckmann (m = r²) with height-correlated Smith, Schlick F (F90 = 1).
    BeckmannSmithCorrelated = 2,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), the paper's modified G.
    TorranceSparrowModifiedG = 3,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), height-correlated Smith G.
    TorranceSparrowSmith = 4,
    /// GGX with separable Smith G = G1(i) G1(o), Schlick F (F90 = 1).
    GgxSmithSeparable = 5,
    /// Beckmann with separable Smith G, Schlick F (F90 = 1).
    BeckmannSmithSeparable = 6,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), separable Smith G.
    TorranceSparrowSmithSeparable = 7,
    /// Torrance–Sparrow, Gaussian slopes (Beckmann m = √2σ), the V-cavity G of Torrance and
    /// Sparrow as used by Blinn.
    TorranceSparrowVCavity = 8,
    /// The Charlie sheen (Estevez and Kulla 2017, α = r²) with their fitted-Λ visibility
    /// (glTF `KHR_materials_sheen`).
    SheenEstevezKulla = 9,
    /// The Charlie sheen (α = r²) with Ashikhmin's visibility 1/(4(μi + μo − μi μo))
    /// (Filament's cloth).
    SheenAshikhmin = 10,
    /// The rough dielectric of Walter et al. (2007) with GGX (α = r²), separable Smith G,
    /// exact dielectric Fresnel (brdf-core `rough_dielectric`).
    RoughDielectricGgx = 11,
    /// The rough dielectric of Walter et al. (2007) with Beckmann, separable Smith G.
    RoughDielectricBeckmann = 12,
}

impl Model {
    /// The code on disk.
    pub const fn code(self) -> u8 {
        self as u8
    }
}

/// How the table was generated.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Generator<'a> {
    /// The model.
    pub model: Model,
    /// The reading of eq 12 (meaningful for the modified G).
    pub convention: Convention,
    /// The fixed RMS slope σ of a per-σ table, if any.
    pub sigma: Option<f64>,
    /// Quadrature node counts used by the direct kernel (outer first).
    pub nodes: List<u16, MAX_GENERATOR_NODES>,
    /// Free text naming the generator, e.g. `brdf-kernels xtask lut 0.1.0`.
    pub tool: &'a str,
}

/// Error of the interpolated table against the direct kernel, measured by the generator at
/// random points (not at nodes).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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

impl ErrorStats {
    /// The rule for what a file states about its own error (docs/lut-format.md §3): max and
    /// RMS finite and ≥ 0 (−0 counts as 0), and RMS ≤ max (a root mean square never exceeds
    /// the largest term). Checked at parse and by the writer, so a reader never sees a claim
    /// that cannot be re-checked; the error states the rule. (A sample count
    /// of 0 is accepted: `lut verify` measures at least one point whatever it says.)
    pub fn check(&self) -> Result<(), crate::LutError> {
        // One comparison chain (NaN fails every comparison; +inf fails the last; a negative
        // value fails the first two): 0 <= RMS <= max |error| <= f32::MAX.
        if 0.0 <= self.rms && self.rms <= self.max_abs && self.max_abs <= f32::MAX {
            return Ok(());
        }
        Err(crate::LutError::BadErrorStats {
            field: "max |error| and RMS error must be finite, >= 0, with RMS <= max",
        })
    }
}

/// The decoded header (without the magic and version, which are always [`MAGIC`] and a
/// version in [`MIN_FORMAT_VERSION`]..=[`FORMAT_VERSION`]). `checksum` is the CRC-32 of the encoded header bytes that precede it
/// followed by the whole payload; the writer fills it in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Header<'a> {
    /// What the table holds.
    pub kind: TableKind,
    /// The grid axes, fastest first.
    pub axes: List<Axis<'a>, MAX_AXES>,
    /// The channels, interleaved innermost.
    pub channels: List<Channel<'a>, MAX_CHANNELS>,
    /// Number format.
    pub encoding: Encoding,
    /// Intended interpolation.
    pub interpolation: Interpolation,
    /// Generator parameters.
    pub generator: Generator<'a>,
    /// Measured error.
    pub error: ErrorStats,
    /// The largest estimated integration error of a node value over all nodes and channels
    /// (absolute, in the channels' units): how far each stored value may be from the exact
    /// integral before quantisation, as the generator's error estimate states it. `None`
    /// in version 1 files, which do not record it; the writer always writes it.
    pub integration: Option<f32>,
    /// CRC-32 of the file (see above).
    pub checksum: u32,
}

/// The rule for the recorded integration error (docs/lut-format.md §3, the claim rule):
/// finite and ≥ 0 (−0 counts as 0); `None` (a version 1 file) passes. The same comparison
/// chain as [`ErrorStats::check`], with the bound as the maximum and 0 as the RMS.
pub fn check_integration(e: Option<f32>) -> Result<(), crate::LutError> {
    match e {
        // NaN, +inf and negative values are outside the range (−0 is inside).
        Some(e) if !(0.0..=f32::MAX).contains(&e) => Err(crate::LutError::BadErrorStats {
            field: "the integration error bound must be finite and >= 0",
        }),
        _ => Ok(()),
    }
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

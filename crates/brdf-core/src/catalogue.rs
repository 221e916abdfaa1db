//! The model catalogue: every reflection model of [`crate::models`] once, as static data —
//! name (plus accepted old spellings), a one-line description, its parameters with units,
//! the constructor's ranges, slider ranges and defaults, and static flags — with one
//! constructor, [`ModelSpec::build`], from a flat array of numbers. The command line
//! (`cargo xtask eval brdf`), the WASM module, the plausibility tests and the benches all
//! read this table, so names and parameters cannot drift apart.
//!
//! Flat layout: a scalar parameter takes one slot, a colour three (r, g, b, named by
//! [`ParamKind::Rgb`]), a choice one (the option's index, an integer). [`ModelSpec::slots`]
//! is the total, at most [`MAX_SLOTS`].
//!
//! Roughness follows the crate's convention ([`crate::microfacet`]): Beckmann and GGX widths
//! α; the Torrance–Sparrow model takes the paper's RMS slope σ = α/√2.

use crate::error::check_range;
use crate::fresnel::Fresnel;
use crate::geometry::Vec3;
use crate::models::*;
use crate::{ParamError, Real};

/// The most slots a model may have ([`ModelSpec::slots`]): 16, what the WASM module's
/// JavaScript side reserves for a parameter array (64 bytes of f32).
pub const MAX_SLOTS: usize = 16;

/// How a parameter occupies the flat array.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamKind {
    /// One number.
    Scalar,
    /// A colour: three numbers, with these per-channel names.
    Rgb([&'static str; 3]),
    /// One of these options, given as its index (an integer).
    Choice(&'static [&'static str]),
}

/// One parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Name (the command line's `--param` key).
    pub name: &'static str,
    /// Layout and meaning of its slots.
    pub kind: ParamKind,
    /// Unit ("1" for unitless, "rad", "-" for a choice).
    #[cfg(feature = "catalogue-text")]
    unit: &'static str,
    /// The range the model's checked constructor accepts (per channel), in words.
    #[cfg(feature = "catalogue-text")]
    range: &'static str,
    /// Slider range for a user interface (inside the accepted range).
    pub ui: (f64, f64),
    /// Slider step (1 for a choice).
    pub step: f64,
    /// Default, per channel (a scalar or a choice uses the first).
    pub default: [f64; 3],
    /// What it is.
    #[cfg(feature = "catalogue-text")]
    help: &'static str,
}

/// The texts of the catalogue are kept only with the `catalogue-text` feature (so that the
/// WASM module and the firmware do not carry them); without it these return "".
macro_rules! text {
    ($self:ident . $f:ident) => {{
        #[cfg(feature = "catalogue-text")]
        {
            $self.$f
        }
        #[cfg(not(feature = "catalogue-text"))]
        {
            let _ = $self;
            ""
        }
    }};
}

impl ParamSpec {
    /// Unit ("1" for unitless, "rad", "-" for a choice); "" without `catalogue-text`.
    pub fn unit(&self) -> &'static str {
        text!(self.unit)
    }
    /// The range the constructor accepts, in words; "" without `catalogue-text`.
    pub fn range(&self) -> &'static str {
        text!(self.range)
    }
    /// What it is; "" without `catalogue-text`.
    pub fn help(&self) -> &'static str {
        text!(self.help)
    }
    /// Slots taken in the flat array.
    pub const fn width(&self) -> usize {
        match self.kind {
            ParamKind::Rgb(_) => 3,
            _ => 1,
        }
    }
}

/// Static facts about a model (the parameter-dependent ones are [`BrdfFlags`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelFlags {
    /// `eval` is a lit colour (it carries n·l itself), not a BRDF in 1/sr.
    pub lit_colour: bool,
    /// The model can have a Dirac (mirror) part.
    pub has_delta: bool,
    /// The model depends on the azimuth about the normal (x = tangent).
    pub anisotropic: bool,
}

/// Which constructor a spec uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelId {
    /// [`TorranceSparrow`]: Beckmann D with a chosen geometric term and Fresnel term.
    TorranceSparrow,
    /// [`Lambert`]: ideal diffuse.
    Lambert,
    /// [`PhongNormalized`]: energy-normalised Phong.
    Phong,
    /// [`BlinnPhongNormalized`]: energy-normalised Blinn–Phong.
    BlinnPhong,
    /// [`CookTorrance`]: Cook–Torrance (Beckmann D, Schlick F, V-groove G by default).
    CookTorrance,
    /// [`LambertSpecularMix`]: Lambertian plus mirror.
    LambertMirror,
    /// [`ShirleyDamped`]: Shirley's damped Lambert-plus-mirror model.
    ShirleyDamped,
    /// [`CoupledSmooth`]: the coupled smooth-layered model.
    CoupledSmooth,
    /// [`AshikhminShirley`]: the Ashikhmin–Shirley anisotropic Phong model.
    AshikhminShirley,
    /// [`Bank`]: the Bank model.
    Bank,
    /// [`Ward`]: the anisotropic Ward model.
    Ward,
    /// [`Ggx`]: isotropic GGX microfacet model.
    Ggx,
    /// [`Ggx`] with separate roughness along tangent and bitangent.
    GgxAnisotropic,
    /// [`StandardLit`]: the standard lighting model (a lit colour, not a BRDF).
    Standard,
    /// [`Sheen`]: the Charlie microfacet sheen (Estevez–Kulla 2017, glTF).
    Sheen,
    /// [`RoughDielectric`]: Walter et al. 2007, reflection and refraction (a BSDF).
    RoughDielectric,
}

/// One model of the catalogue.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelSpec {
    /// Name.
    pub name: &'static str,
    /// Older spellings still accepted by [`find`].
    pub aliases: &'static [&'static str],
    /// One-line description with its source ([`ModelSpec::about`]).
    #[cfg(feature = "catalogue-text")]
    about: &'static str,
    /// Parameters, in flat-array order.
    pub params: &'static [ParamSpec],
    /// Static flags.
    pub flags: ModelFlags,
    /// The constructor.
    pub id: ModelId,
}

/// One slot of the flat array, for interfaces that list scalars (the WASM module).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slot {
    /// Slot name (a colour's channel name, else the parameter's).
    pub name: &'static str,
    /// The parameter it belongs to.
    pub param: &'static ParamSpec,
    /// Default value.
    pub default: f64,
}

impl ModelSpec {
    /// One-line description with its source; "" without `catalogue-text`.
    pub fn about(&self) -> &'static str {
        text!(self.about)
    }
    /// Number of slots of the flat array.
    pub fn slots(&self) -> usize {
        self.params.iter().map(|p| p.width()).sum()
    }
    /// Slot `k` of the flat array.
    pub fn slot(&self, k: usize) -> Option<Slot> {
        let mut at = 0;
        for p in self.params {
            let w = p.width();
            if k < at + w {
                let c = k - at;
                let name = match p.kind {
                    ParamKind::Rgb(names) => names[c],
                    _ => p.name,
                };
                return Some(Slot {
                    name,
                    param: p,
                    default: p.default[c],
                });
            }
            at += w;
        }
        None
    }
    /// The defaults as a flat array (the first [`ModelSpec::slots`] entries are used).
    pub fn defaults<T: Real>(&self) -> [T; MAX_SLOTS] {
        core::array::from_fn(|k| self.slot(k).map_or(T::ZERO, |s| T::from_f64(s.default)))
    }
    /// Builds the model from a flat array of at least [`ModelSpec::slots`] numbers. Every
    /// range is the model's checked constructor's; a choice must be an integer index.
    pub fn build<T: Real>(&self, v: &[T]) -> Result<AnyBrdf<T>, ParamError> {
        let n = self.slots();
        let Some(v) = v.get(..n) else {
            return Err(ParamError::OutOfRange {
                name: self.name,
                range: "too few parameters",
            });
        };
        // Choices first, in one place: an integer index into the options.
        let mut at = 0;
        for p in self.params {
            if let ParamKind::Choice(o) = p.kind {
                check_choice(p.name, v[at], o.len())?;
            }
            at += p.width();
        }
        // The slots by position (the layout of the table above; the catalogue tests check
        // each entry against its constructor).
        let x = |k: usize| v[k];
        let c = |k: usize| Rgb::new(v[k], v[k + 1], v[k + 2]);
        let i = |k: usize| Real::to_f64(v[k]) as usize;
        Ok(match self.id {
            ModelId::TorranceSparrow => {
                let f = Fresnel::schlick(x(2))?;
                let g = GeometricTerm::ALL[i(1)];
                AnyBrdf::TorranceSparrow(TorranceSparrow::new(x(0), g, f, x(3), x(4))?)
            }
            ModelId::Lambert => AnyBrdf::Lambert(Lambert::new(c(0))?),
            ModelId::Phong => AnyBrdf::Phong(PhongNormalized::new(c(0), c(3), x(6))?),
            ModelId::BlinnPhong => {
                AnyBrdf::BlinnPhong(BlinnPhongNormalized::new(c(0), c(3), x(6))?)
            }
            ModelId::CookTorrance => {
                let g = GeometricTerm::ALL[i(8)];
                let m = CookTorrance::new(c(0), c(3), x(6), x(7), g)?;
                AnyBrdf::CookTorrance(m.with_sampling(SAMPLINGS[i(9)]))
            }
            ModelId::LambertMirror => AnyBrdf::LambertMirror(LambertSpecularMix::new(c(0), x(3))?),
            ModelId::ShirleyDamped => AnyBrdf::ShirleyDamped(ShirleyDamped::new(c(0), x(3))?),
            ModelId::CoupledSmooth => {
                let k = [CoupledK::Conserving, CoupledK::Printed][i(4)];
                AnyBrdf::CoupledSmooth(CoupledSmooth::new(c(0), x(3), k)?)
            }
            ModelId::AshikhminShirley => {
                AnyBrdf::AshikhminShirley(AshikhminShirley::new(c(0), c(3), x(6), x(7))?)
            }
            ModelId::Bank => {
                let t = if i(7) == 0 {
                    BankTangent::Azimuth(x(8))
                } else {
                    BankTangent::NormalCrossView
                };
                AnyBrdf::Bank(Bank::new(c(0), c(3), x(6), t)?)
            }
            ModelId::Ward => AnyBrdf::Ward(Ward::new(c(0), c(3), x(6), x(7))?),
            ModelId::Ggx => {
                let (smith, s) = (SMITH[i(4)], SAMPLINGS[i(5)]);
                AnyBrdf::Ggx(Ggx::new(c(0), x(3), smith, s)?)
            }
            ModelId::GgxAnisotropic => {
                let (smith, s) = (SMITH[i(5)], SAMPLINGS[i(6)]);
                AnyBrdf::Ggx(Ggx::anisotropic(c(0), x(3), x(4), smith, s)?)
            }
            ModelId::Standard => {
                let h = [Highlight::Phong, Highlight::BlinnPhong][i(14)];
                let m = StandardLighting::new(c(0), c(3), c(7), c(10), x(13), h)?;
                let g_amb = check_range("g_amb", x(6), T::ZERO, false, T::INFINITY, "[0, ∞)")?;
                AnyBrdf::Standard(StandardLit {
                    m,
                    g_amb: Rgb::splat(g_amb),
                })
            }
            ModelId::Sheen => AnyBrdf::Sheen(Sheen::new(c(0), x(3), SheenVisibility::ALL[i(4)])?),
            ModelId::RoughDielectric => AnyBrdf::RoughDielectric(RoughDielectric::new(
                DielectricDistribution::ALL[i(2)],
                x(0),
                x(1),
            )?),
        })
    }
}

const SMITH: [SmithForm; 2] = [SmithForm::Separable, SmithForm::Correlated];
const SAMPLINGS: [MicrofacetSampling; 2] = [
    MicrofacetSampling::VisibleNormals,
    MicrofacetSampling::Normals,
];

/// A choice slot must hold an integer index below `n`.
fn check_choice<T: Real>(name: &'static str, x: T, n: usize) -> Result<(), ParamError> {
    let xf: f64 = Real::to_f64(x);
    if xf >= 0.0 && xf < n as f64 && xf == (xf as usize) as f64 {
        Ok(())
    } else if !x.is_finite() {
        Err(ParamError::NotFinite { name })
    } else {
        Err(ParamError::OutOfRange {
            name,
            range: "an option index",
        })
    }
}

/// One masking–shadowing term G: the options of the models' `g` choice, the generator's
/// `masking` (command line, TOML specs, Python), the C ABI's `BRDF_GEOMETRIC_*` values and
/// [`GeometricTerm::name`] all read [`MASKINGS`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaskingSpec {
    /// Name.
    pub name: &'static str,
    /// Other spellings accepted by [`find_masking`].
    pub aliases: &'static [&'static str],
    /// The term.
    pub term: GeometricTerm,
    #[cfg(feature = "catalogue-text")]
    about: &'static str,
}

impl MaskingSpec {
    /// What it is, with its source; "" without `catalogue-text`.
    pub fn about(&self) -> &'static str {
        text!(self.about)
    }
}

/// Defines [`MASKINGS`] and the `g` choice's option names and range text from one list of
/// `Term = "name" [aliases] "about"`.
macro_rules! maskings {
    ($t0:ident = $n0:literal [$($a0:literal),*] $h0:literal,
     $($t:ident = $n:literal [$($a:literal),*] $h:literal,)*) => {
        /// Every masking term, in [`GeometricTerm::ALL`] order (a choice's index, and the C
        /// ABI's value, is its position here).
        pub const MASKINGS: &[MaskingSpec] = &[
            masking(GeometricTerm::$t0, $n0, &[$($a0),*], $h0),
            $(masking(GeometricTerm::$t, $n, &[$($a),*], $h),)*
        ];
        const G_TERMS: &[&str] = &[$n0 $(, $n)*];
        const G_RANGE: &str = concat!($n0 $(, " | ", $n)*);
    };
}

const fn masking(
    term: GeometricTerm,
    name: &'static str,
    aliases: &'static [&'static str],
    about: &'static str,
) -> MaskingSpec {
    let _ = about;
    MaskingSpec {
        name,
        aliases,
        term,
        #[cfg(feature = "catalogue-text")]
        about,
    }
}

maskings! {
    None = "none" [] "G = 1",
    Blinn = "blinn" ["v-cavity", "v-groove"]
        "the V-cavity G of Torrance and Sparrow in Blinn's form (paper eq 4)",
    SmithSeparable = "smith-separable" [] "Smith G1(i) G1(o) of the distribution's Lambda",
    SmithCorrelated = "smith-correlated" []
        "height-correlated Smith 1/(1 + Lambda(i) + Lambda(o))",
    Modified = "modified" [] "the paper's modified G, reciprocal reading (eqs 6-13)",
    ModifiedPrinted = "modified-printed" [] "the paper's modified G, eq 12 as printed",
}

// The catalogue's order is the enum's: `GeometricTerm::name` indexes `MASKINGS` by the
// discriminant.
const _: () = {
    let mut k = 0;
    while k < MASKINGS.len() {
        assert!(MASKINGS[k].term as usize == k);
        k += 1;
    }
    assert!(MASKINGS.len() == GeometricTerm::ALL.len());
};

/// Finds a masking term by name or other spelling (`v-cavity` is `blinn`).
pub fn find_masking(name: &str) -> Option<&'static MaskingSpec> {
    MASKINGS
        .iter()
        .find(|m| m.name == name || m.aliases.contains(&name))
}

/// A microfacet distribution D that tables are made of (the generator's and the command
/// line's `model`), in [`DISTRIBUTIONS`] order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DistributionId {
    /// Trowbridge–Reitz (GGX), width α.
    Ggx,
    /// Beckmann, width m.
    Beckmann,
    /// Torrance–Sparrow: Gaussian slopes of RMS slope σ, i.e. Beckmann with m = √2 σ.
    TorranceSparrow,
}

/// One distribution of the catalogue.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistributionSpec {
    /// Name.
    pub name: &'static str,
    /// Other spellings accepted by [`find_distribution`].
    pub aliases: &'static [&'static str],
    /// The distribution.
    pub id: DistributionId,
    /// Name of its width (a table's roughness axis when it holds the width itself).
    pub width: &'static str,
    /// The G terms tables are made with over this distribution (each has a BLUT model code).
    pub tabulated: &'static [GeometricTerm],
    #[cfg(feature = "catalogue-text")]
    about: &'static str,
}

impl DistributionSpec {
    /// What it is; "" without `catalogue-text`.
    pub fn about(&self) -> &'static str {
        text!(self.about)
    }
}

impl DistributionId {
    /// Its catalogue entry.
    pub const fn spec(self) -> &'static DistributionSpec {
        &DISTRIBUTIONS[self as usize]
    }
    /// Its name ([`DistributionSpec::name`]).
    pub const fn name(self) -> &'static str {
        self.spec().name
    }
}

const SMITHS: &[GeometricTerm] = &[
    GeometricTerm::SmithSeparable,
    GeometricTerm::SmithCorrelated,
];

/// Every distribution, in [`DistributionId`] order.
pub const DISTRIBUTIONS: &[DistributionSpec] = &[
    DistributionSpec {
        name: "ggx",
        aliases: &["trowbridge-reitz"],
        id: DistributionId::Ggx,
        width: "alpha",
        tabulated: SMITHS,
        #[cfg(feature = "catalogue-text")]
        about: "Trowbridge-Reitz (GGX) D = alpha^2/(pi cos^4 (alpha^2 + tan^2)^2)",
    },
    DistributionSpec {
        name: "beckmann",
        aliases: &[],
        id: DistributionId::Beckmann,
        width: "m",
        tabulated: SMITHS,
        #[cfg(feature = "catalogue-text")]
        about: "Beckmann D = exp(-tan^2/m^2)/(pi m^2 cos^4)",
    },
    DistributionSpec {
        name: "torrance-sparrow",
        aliases: &[],
        id: DistributionId::TorranceSparrow,
        width: "m",
        tabulated: &[
            GeometricTerm::Blinn,
            GeometricTerm::SmithSeparable,
            GeometricTerm::SmithCorrelated,
            GeometricTerm::Modified,
            GeometricTerm::ModifiedPrinted,
        ],
        #[cfg(feature = "catalogue-text")]
        about: "Gaussian slopes of RMS slope sigma (paper eqs 2, 5): Beckmann with m = sqrt2 sigma",
    },
];

const _: () = {
    let mut k = 0;
    while k < DISTRIBUTIONS.len() {
        assert!(DISTRIBUTIONS[k].id as usize == k);
        k += 1;
    }
};

/// Finds a distribution by name or other spelling.
pub fn find_distribution(name: &str) -> Option<&'static DistributionSpec> {
    DISTRIBUTIONS
        .iter()
        .find(|d| d.name == name || d.aliases.contains(&name))
}

/// Finds a model by name or old spelling.
pub fn find(name: &str) -> Option<&'static ModelSpec> {
    MODELS
        .iter()
        .find(|m| m.name == name || m.aliases.contains(&name))
}

/// The standard lighting model as the catalogue evaluates it: the lit colour for one white
/// unit light at wi and viewer wo, with emission and global ambient g_amb (not a BRDF).
#[derive(Clone, Copy, Debug)]
pub struct StandardLit<T> {
    /// The model.
    pub m: StandardLighting<T>,
    /// The global ambient colour.
    pub g_amb: Rgb<T>,
}

impl<T: Real> Brdf<T> for StandardLit<T> {
    fn flags(&self) -> BrdfFlags {
        self.m.flags()
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        let light = Light {
            dir: wi,
            color: Rgb::splat(T::ONE),
        };
        let n = Vec3::new(T::ZERO, T::ZERO, T::ONE);
        self.m.shade(n, wo, &[light], self.g_amb)
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        self.m.pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        self.m.sample(wo, u)
    }
}

/// Defines [`AnyBrdf`] and its [`Brdf`] impl (each function forwarded to the variant's
/// model) from one list of `Variant(Model)`.
macro_rules! any_brdf {
    ($($(#[$m:meta])* $v:ident($t:ident),)*) => {
        /// Any model of the catalogue (what [`ModelSpec::build`] returns).
        #[derive(Clone, Copy, Debug)]
        #[allow(clippy::large_enum_variant)]
        pub enum AnyBrdf<T> {
            $($(#[$m])* $v($t<T>),)*
        }

        impl<T: Real> Brdf<T> for AnyBrdf<T> {
            fn flags(&self) -> BrdfFlags {
                match self { $(AnyBrdf::$v(m) => Brdf::flags(m),)* }
            }
            fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
                match self { $(AnyBrdf::$v(m) => Brdf::eval(m, wi, wo),)* }
            }
            fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
                match self { $(AnyBrdf::$v(m) => Brdf::pdf(m, wo, wi),)* }
            }
            fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
                match self { $(AnyBrdf::$v(m) => Brdf::sample(m, wo, u),)* }
            }
            fn delta(&self, wo: Vec3<T>) -> Option<DeltaLobe<T>> {
                match self { $(AnyBrdf::$v(m) => Brdf::delta(m, wo),)* }
            }
            fn lobe_hint(&self) -> LobeHint<T> {
                match self { $(AnyBrdf::$v(m) => Brdf::lobe_hint(m),)* }
            }
        }
    };
}

any_brdf! {
    /// A [`TorranceSparrow`] (from [`ModelId::TorranceSparrow`]).
    TorranceSparrow(TorranceSparrow),
    /// A [`Lambert`] (from [`ModelId::Lambert`]).
    Lambert(Lambert),
    /// A [`PhongNormalized`] (from [`ModelId::Phong`]).
    Phong(PhongNormalized),
    /// A [`BlinnPhongNormalized`] (from [`ModelId::BlinnPhong`]).
    BlinnPhong(BlinnPhongNormalized),
    /// A [`CookTorrance`] (from [`ModelId::CookTorrance`]).
    CookTorrance(CookTorrance),
    /// A [`LambertSpecularMix`] (from [`ModelId::LambertMirror`]).
    LambertMirror(LambertSpecularMix),
    /// A [`ShirleyDamped`] (from [`ModelId::ShirleyDamped`]).
    ShirleyDamped(ShirleyDamped),
    /// A [`CoupledSmooth`] (from [`ModelId::CoupledSmooth`]).
    CoupledSmooth(CoupledSmooth),
    /// A [`AshikhminShirley`] (from [`ModelId::AshikhminShirley`]).
    AshikhminShirley(AshikhminShirley),
    /// A [`Bank`] (from [`ModelId::Bank`]).
    Bank(Bank),
    /// A [`Ward`] (from [`ModelId::Ward`]).
    Ward(Ward),
    /// A [`Ggx`] (from [`ModelId::Ggx`] or [`ModelId::GgxAnisotropic`]).
    Ggx(Ggx),
    /// A [`StandardLit`] (from [`ModelId::Standard`]).
    Standard(StandardLit),
    /// A [`Sheen`] (from [`ModelId::Sheen`]).
    Sheen(Sheen),
    /// A [`RoughDielectric`] (from [`ModelId::RoughDielectric`]).
    RoughDielectric(RoughDielectric),
}

impl<T: Real> AnyBrdf<T> {
    /// `true` for the standard lighting model, whose `eval` is a lit colour.
    pub fn is_lit_colour(&self) -> bool {
        matches!(self, AnyBrdf::Standard(_))
    }
}

// ---------------------------------------------------------------- the table

const fn num(
    name: &'static str,
    unit: &'static str,
    range: &'static str,
    ui: (f64, f64),
    step: f64,
    default: f64,
    help: &'static str,
) -> ParamSpec {
    let _ = (unit, range, help);
    ParamSpec {
        name,
        kind: ParamKind::Scalar,
        #[cfg(feature = "catalogue-text")]
        unit,
        #[cfg(feature = "catalogue-text")]
        range,
        ui,
        step,
        default: [default; 3],
        #[cfg(feature = "catalogue-text")]
        help,
    }
}

const fn colour(
    name: &'static str,
    channels: [&'static str; 3],
    range: &'static str,
    ui: (f64, f64),
    default: [f64; 3],
    help: &'static str,
) -> ParamSpec {
    let _ = (range, help);
    ParamSpec {
        name,
        kind: ParamKind::Rgb(channels),
        #[cfg(feature = "catalogue-text")]
        unit: "1",
        #[cfg(feature = "catalogue-text")]
        range,
        ui,
        step: 0.01,
        default,
        #[cfg(feature = "catalogue-text")]
        help,
    }
}

/// `rgb!("kd", range, ui, default, help)`: a colour parameter whose channels are named
/// `kd_r`, `kd_g`, `kd_b`.
macro_rules! rgb {
    ($n:literal, $($rest:expr),+) => {
        colour($n, [concat!($n, "_r"), concat!($n, "_g"), concat!($n, "_b")], $($rest),+)
    };
}

const fn choice(
    name: &'static str,
    options: &'static [&'static str],
    range: &'static str,
    default: usize,
    help: &'static str,
) -> ParamSpec {
    let _ = (range, help);
    ParamSpec {
        name,
        kind: ParamKind::Choice(options),
        #[cfg(feature = "catalogue-text")]
        unit: "-",
        #[cfg(feature = "catalogue-text")]
        range,
        ui: (0.0, options.len() as f64 - 1.0),
        step: 1.0,
        default: [default as f64; 3],
        #[cfg(feature = "catalogue-text")]
        help,
    }
}

const fn model(
    id: ModelId,
    name: &'static str,
    aliases: &'static [&'static str],
    flags: ModelFlags,
    about: &'static str,
    params: &'static [ParamSpec],
) -> ModelSpec {
    let _ = about;
    ModelSpec {
        name,
        aliases,
        #[cfg(feature = "catalogue-text")]
        about,
        params,
        flags,
        id,
    }
}

const fn flags(lit_colour: bool, has_delta: bool, anisotropic: bool) -> ModelFlags {
    ModelFlags {
        lit_colour,
        has_delta,
        anisotropic,
    }
}

/// Flags of a model: plain (a BRDF, no Dirac part, isotropic), with a Dirac part,
/// anisotropic, a lit colour.
const PLAIN: ModelFlags = flags(false, false, false);
const DELTA: ModelFlags = flags(false, true, false);
const ANISO: ModelFlags = flags(false, false, true);
const LIT: ModelFlags = flags(true, false, false);

const SMITH_NAMES: &[&str] = &["separable", "correlated"];
const SAMPLING_NAMES: &[&str] = &["visible-normals", "normals"];
const SAMPLING_RANGE: &str = "visible-normals | normals";
const SAMPLING_HELP: &str = "half-vector density of the sampler";
const U01: &str = "[0, 1]";
const U0INF: &str = "[0, inf)";
const EXP: &str = "[0, 1e6]";
const ALPHA: &str = "[1e-4, 1e4]";
const F0_HELP: &str = "Fresnel reflectance at normal incidence";
/// The GGX models' shared parameters: f0, and the Smith and sampling choices.
const GGX_F0: ParamSpec = rgb!("f0", U01, (0.0, 1.0), [0.95, 0.64, 0.54], F0_HELP);
const GGX_SMITH: ParamSpec = choice(
    "smith",
    SMITH_NAMES,
    "separable | correlated",
    1,
    "Smith masking form",
);
const GGX_SAMPLING: ParamSpec =
    choice("sampling", SAMPLING_NAMES, SAMPLING_RANGE, 0, SAMPLING_HELP);

/// Defines [`MODELS`] from one list of `Id "name" [aliases] FLAGS "about" [parameters]`
/// (rustfmt leaves the list as written: one line a parameter).
macro_rules! models {
    ($($id:ident $name:literal [$($alias:literal),*] $flags:ident $about:literal
        [$($p:expr,)*])*) => {
        /// Every model, in listing order (the WASM module's model ids are indices here).
        pub const MODELS: &[ModelSpec] = &[
            $(model(ModelId::$id, $name, &[$($alias),*], $flags, $about, &[$($p),*]),)*
        ];
    };
}

models! {
    TorranceSparrow "torrance-sparrow" [] PLAIN
    "Torrance-Sparrow (paper eq 3): ks D F G/(4 cos_i cos_o) + albedo/pi, Beckmann D with \
     alpha = sqrt2 sigma, Schlick F(r0), G selectable" [
        num("sigma", "1 (RMS slope)", "[7.07e-5, 7.07e3]", (0.05, 1.0), 0.01, 0.3,
            "RMS slope of the Gaussian surface (alpha = sqrt2 sigma)"),
        choice("g", G_TERMS, G_RANGE, 4, "geometric term (modified = the paper's G)"),
        num("r0", "1", U01, (0.0, 1.0), 0.01, 0.04, F0_HELP),
        num("ks", "1", U0INF, (0.0, 4.0), 0.01, 1.0, "specular scale"),
        num("albedo", "1", U01, (0.0, 1.0), 0.01, 0.5, "Lambertian albedo of the diffuse term"),
    ]
    Lambert "lambert" [] PLAIN
    "Lambertian f = albedo/pi (standard lighting model diffuse, FCG 24.2)" [
        rgb!("albedo", U01, (0.0, 1.0), [0.8, 0.5, 0.3], "hemispherical reflectance"),
    ]
    Phong "phong" ["phong-normalized"] PLAIN
    "energy-normalised Phong kd/pi + ks (n+2)/(2pi) max(wo.r_i,0)^n" [
        rgb!("kd", U01, (0.0, 1.0), [0.5, 0.2, 0.1], "diffuse reflectance"),
        rgb!("ks", U01, (0.0, 1.0), [0.3; 3], "specular reflectance"),
        num("n", "1", EXP, (0.0, 500.0), 1.0, 40.0, "Phong exponent"),
    ]
    BlinnPhong "blinn-phong" ["blinn-phong-normalized"] PLAIN
    "energy-normalised Blinn-Phong kd/pi + ks (n+2)(n+4)/(8pi(n+2^(-n/2))) (n.h)^n" [
        rgb!("kd", U01, (0.0, 1.0), [0.1, 0.3, 0.5], "diffuse reflectance"),
        rgb!("ks", U01, (0.0, 1.0), [0.3; 3], "specular reflectance"),
        num("n", "1", EXP, (0.0, 500.0), 1.0, 80.0, "Blinn-Phong exponent"),
    ]
    CookTorrance "cook-torrance" [] PLAIN
    "Cook-Torrance kd/pi + ks D F G/(4 cos_i cos_o), Beckmann D of width m = alpha, Schlick F" [
        rgb!("kd", U01, (0.0, 1.0), [0.4, 0.1, 0.1], "Lambertian reflectance"),
        rgb!("ks", U01, (0.0, 1.0), [0.6; 3], "specular scale"),
        num("m", "1 (alpha = RMS slope * sqrt 2)", ALPHA, (0.02, 1.0), 0.01, 0.25,
            "Beckmann roughness"),
        num("r0", "1", U01, (0.0, 1.0), 0.01, 0.04, F0_HELP),
        choice("g", G_TERMS, G_RANGE, 1, "geometric term (blinn = V-groove, paper eq 4)"),
        choice("sampling", SAMPLING_NAMES, SAMPLING_RANGE, 1, SAMPLING_HELP),
    ]
    LambertMirror "lambert-mirror" [] DELTA
    "Lambert plus mirror (FCG 24.4): rd/pi (+ rs times a Dirac mirror)" [
        rgb!("rd", "[0, 1], rd + rs <= 1", (0.0, 0.5), [0.4, 0.4, 0.2], "matte reflectance"),
        num("rs", "1", "[0, 1], rd + rs <= 1", (0.0, 0.5), 0.01, 0.3, "mirror reflectance"),
    ]
    ShirleyDamped "shirley-damped" ["shirley"] DELTA
    "Shirley's damped model (FCG 24.4): rd (1 - R_f(theta_o))/pi (+ Dirac); NOT reciprocal" [
        rgb!("rd", U01, (0.0, 1.0), [0.6, 0.3, 0.2], "matte reflectance"),
        num("r0", "1", U01, (0.0, 1.0), 0.01, 0.05, F0_HELP),
    ]
    CoupledSmooth "coupled-smooth" ["coupled"] DELTA
    "coupled smooth-layered model (FCG eq 24.3): k rm f(theta_i) f(theta_o) (+ Dirac)" [
        rgb!("rm", U01, (0.0, 1.0), [1.0; 3], "matte reflectance R_m"),
        num("r0", "1", "[0, 1)", (0.0, 0.95), 0.01, 0.05, F0_HELP),
        choice("k", &["conserving", "printed"], "conserving | printed", 0,
            "conserving: 21(1-R0)/(20pi); printed (FCG 24.2): 21/(20pi(1-R0)), albedo > 1"),
    ]
    AshikhminShirley "ashikhmin-shirley" [] ANISO
    "Ashikhmin-Shirley anisotropic Phong (FCG 24.5-24.9) + coupled diffuse (24.7); u = x, v = y" [
        rgb!("rs", U01, (0.0, 1.0), [0.4; 3], "specular reflectance at normal incidence"),
        rgb!("rd", U01, (0.0, 1.0), [0.3, 0.1, 0.1], "diffuse reflectance"),
        num("nu", "1", EXP, (1.0, 1000.0), 1.0, 100.0, "exponent along x"),
        num("nv", "1", EXP, (1.0, 1000.0), 1.0, 10.0, "exponent along y"),
    ]
    Bank "bank" [] ANISO
    "Bank anisotropic BRDF: kd/pi + ks (sqrt(1-(L.T)^2) sqrt(1-(V.T)^2) - (L.T)(V.T))^ns" [
        rgb!("kd", U01, (0.0, 1.0), [0.3, 0.2, 0.1], "Lambertian reflectance"),
        rgb!("ks", U0INF, (0.0, 1.0), [0.5; 3], "specular coefficient"),
        num("ns", "1", EXP, (1.0, 500.0), 1.0, 30.0, "specular exponent"),
        choice("tangent", &["fixed", "n-cross-v"], "fixed | n-cross-v", 0,
            "fixed material tangent (reciprocal) or T = n x wo (not reciprocal)"),
        num("tangent_azimuth", "rad", "finite", (0.0, core::f64::consts::PI), 0.01, 0.0,
            "azimuth of the fixed tangent from x"),
    ]
    Ward "ward" [] ANISO
    "Ward anisotropic: rd/pi + rs exp(-tan^2 h (cos^2/ax^2 + sin^2/ay^2))/(4pi ax ay \
     sqrt(cos_i cos_o))" [
        rgb!("rd", U01, (0.0, 1.0), [0.2, 0.2, 0.3], "diffuse reflectance"),
        rgb!("rs", U01, (0.0, 1.0), [0.3; 3], "specular reflectance"),
        num("ax", "1 (RMS slope)", ALPHA, (0.01, 1.0), 0.01, 0.1, "roughness along x"),
        num("ay", "1 (RMS slope)", ALPHA, (0.01, 1.0), 0.01, 0.4, "roughness along y"),
    ]
    Ggx "ggx" [] PLAIN
    "Trowbridge-Reitz (GGX) D F G/(4 cos_i cos_o), Schlick F (F90 = 1), Smith G" [
        GGX_F0,
        num("alpha", "1", ALPHA, (0.01, 1.0), 0.01, 0.3, "GGX width (perceptual roughness squared)"),
        GGX_SMITH,
        GGX_SAMPLING,
    ]
    GgxAnisotropic "ggx-anisotropic" [] ANISO
    "anisotropic GGX: D = 1/(pi ax ay ((h_x/ax)^2 + (h_y/ay)^2 + h_z^2)^2), Smith G of the \
     projected width, Schlick F" [
        GGX_F0,
        num("alpha_x", "1", ALPHA, (0.01, 1.0), 0.01, 0.1, "GGX width along x"),
        num("alpha_y", "1", ALPHA, (0.01, 1.0), 0.01, 0.4, "GGX width along y"),
        GGX_SMITH,
        GGX_SAMPLING,
    ]
    Standard "standard" [] LIT
    "standard lighting model: lit colour for one white unit light at wi, viewer wo: m_emis + \
     g_amb*m_amb + m_diff max(n.l,0) + m_spec max(cos,0)^gloss (not a BRDF)" [
        rgb!("emission", U0INF, (0.0, 1.0), [0.0; 3], "m_emis"),
        rgb!("ambient", U0INF, (0.0, 1.0), [0.0; 3], "m_amb"),
        num("g_amb", "1", U0INF, (0.0, 1.0), 0.01, 0.0, "global ambient g_amb (grey)"),
        rgb!("diffuse", U0INF, (0.0, 1.0), [0.5, 0.3, 0.2], "m_diff"),
        rgb!("specular", U0INF, (0.0, 1.0), [0.5; 3], "m_spec"),
        num("gloss", "1", EXP, (0.0, 500.0), 1.0, 30.0, "m_gls"),
        choice("highlight", &["phong", "blinn-phong"], "phong | blinn-phong", 1,
            "(v.r)^gloss or (n.h)^gloss"),
    ]
    Sheen "sheen" ["charlie"] PLAIN
    "Charlie sheen (Estevez-Kulla 2017, glTF KHR_materials_sheen): color D V, D = (2 + \
     1/alpha) sin^(1/alpha) theta_h/(2pi), alpha = r^2 (>= 1e-4); not energy conserving (a \
     layer)" [
        rgb!("color", U01, (0.0, 1.0), [1.0; 3], "sheen colour"),
        num("roughness", "1 (perceptual, alpha = r^2)", U01, (0.0, 1.0), 0.01, 0.5,
            "sheen roughness r (alpha = r^2, clamped to >= 1e-4)"),
        choice("visibility", SheenVisibility::NAMES, SheenVisibility::RANGE, 0,
            "visibility V, in option order: G2/(4 mu_i mu_o) with the fitted Smith Lambda \
             (glTF), or 1/(4(mu_i + mu_o - mu_i mu_o)) (Filament)"),
    ]
    RoughDielectric "rough-dielectric" ["walter", "rough-glass"] DELTA
    "rough dielectric BSDF (Walter et al. 2007): reflection F D G/(4|cos i cos o|) and \
     refraction (eq 21, radiance convention, eta_o^2) with exact Fresnel and total internal \
     reflection, separable Smith G; wo below the surface (z < 0) gives the transmitted part" [
        num("alpha", "1", "[0, 1e4]", (0.0, 1.0), 0.01, 0.3,
            "microfacet width alpha (floored to 1e-4)"),
        num("eta", "1", "[0.1, 10]", (0.5, 2.5), 0.01, 1.5,
            "eta_inside/eta_outside (below 1: the outside is denser, total internal \
             reflection; 1: invisible interface, a straight-through Dirac)"),
        choice("distribution", DielectricDistribution::NAMES, DielectricDistribution::RANGE, 0,
            "microfacet distribution D, in option order"),
    ]
}

impl ModelSpec {
    /// The parameter named `name` and the index of its first slot in the flat array (the
    /// widths of the parameters before it summed); `None` when the model has none of that
    /// name. How the command line and the Python binding place a named value.
    pub fn param_by_name(&self, name: &str) -> Option<(usize, &'static ParamSpec)> {
        let mut at = 0;
        for p in self.params {
            if p.name == name {
                return Some((at, p));
            }
            at += p.width();
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each name of the masking list parses back to its term, old spellings included, and
    /// the models' `g` choice offers exactly these names in this order: a choice index
    /// builds the term its option names (checked through the built model's G at a point
    /// where the six terms differ).
    #[test]
    fn masking_names_are_one_list() {
        for g in GeometricTerm::ALL {
            assert_eq!(GeometricTerm::from_name(g.name()), Some(g));
        }
        assert_eq!(
            GeometricTerm::from_name("v-cavity"),
            Some(GeometricTerm::Blinn)
        );
        assert_eq!(GeometricTerm::from_name("nonsense"), None);
        let ts = find("torrance-sparrow").unwrap();
        let ParamKind::Choice(options) = ts.params[1].kind else {
            panic!("g is a choice")
        };
        assert_eq!(options.len(), MASKINGS.len());
        let (wi, wo) = (
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(-0.95, 0.1, 0.3).normalize().unwrap(),
        );
        let mut seen: [f64; 6] = [0.0; 6];
        for (k, name) in options.iter().enumerate() {
            let mut v = ts.defaults::<f64>();
            v[1] = k as f64;
            let AnyBrdf::TorranceSparrow(m) = ts.build(&v).unwrap() else {
                panic!("a Torrance-Sparrow model")
            };
            let g = GeometricTerm::from_name(name).unwrap();
            let f = Fresnel::schlick(v[2]).unwrap();
            let want: TorranceSparrow<f64> = TorranceSparrow::new(v[0], g, f, v[3], v[4]).unwrap();
            assert_eq!(m.eval(wi, wo), want.eval(wi, wo), "{name}");
            seen[k] = m.eval(wi, wo);
        }
        for i in 0..6 {
            for j in 0..i {
                assert!(
                    seen[i] != seen[j],
                    "{} and {} agree here",
                    options[i],
                    options[j]
                );
            }
        }
    }

    /// Distribution names parse back, and each distribution's tabulated G terms are
    /// catalogue terms.
    #[test]
    fn distribution_names_are_one_list() {
        for d in DISTRIBUTIONS {
            assert_eq!(find_distribution(d.name).map(|s| s.id), Some(d.id));
            assert_eq!(d.id.name(), d.name);
            for a in d.aliases {
                assert_eq!(find_distribution(a).map(|s| s.id), Some(d.id));
            }
        }
        assert!(find_distribution("blinn").is_none());
    }
}

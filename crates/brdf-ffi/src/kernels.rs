//! Kernel exports: the modified G, Blinn's and Smith's G, the Torrance–Sparrow, GGX and
//! sheen BRDFs and their directional albedo, and the rough dielectric BSDF (eval, adjoint,
//! pdf, sampling), each in `f32` and `f64`: one definition (the `typed_abi!`, `sheen_abi!`
//! and `rough_dielectric_abi!` macros below, GGX and sheen sharing `rgb_brdf_abi!`, every
//! init, query and batch export written by the crate's `init_export!`, `query_export!` and
//! `batch_export!`, over generic helpers) instantiated for each scalar type.
//!
//! Conventions (docs/conventions.md): local frame with z the normal, both directions
//! pointing away from the surface, `wi` toward the light and `wo` toward the viewer; the
//! in-plane angles of the 2015 Acta Physica Sinica paper on the modified G: θi ∈ [0, π/2],
//! θr ∈ [−π/2, π/2] signed (θr > 0 on the far side of the normal from the light, θr = θi the
//! mirror direction). Dot-product forms take n·wi, n·wo and wi·wo of unit vectors; n·h and
//! wi·h are computed from those three (`brdf_core::Dots::new`), which for a near-mirror
//! pair near the horizon (wi ≈ −wo) carries wi·wo's rounding error ε as a relative error of
//! about ε/(1 + wi·wo). The C interface keeps the three dots; a caller that has the vectors
//! of such pairs should evaluate in higher precision or avoid the dot-product form there.

use crate::{
    batch_export, handle, init_export, query_export, BrdfStatus, BRDF_STATUS_INVALID_ARGUMENT,
    BRDF_STATUS_NOT_INITIALISED, BRDF_STATUS_NO_SAMPLE, BRDF_STATUS_NULL_POINTER, BRDF_STATUS_OK,
};
use brdf_core::albedo::directional_albedo;
use brdf_core::fresnel::Fresnel;
use brdf_core::masking::{self, Convention, ModifiedG};
use brdf_core::microfacet::{from_cos, Beckmann, Distribution, TrowbridgeReitz};
use brdf_core::models::{
    Brdf, BrdfFlags, BrdfSample, DeltaLobe, DielectricDistribution, GeometricTerm, Ggx, LobeHint,
    MicrofacetSampling, Rgb, RoughDielectric, Sheen, SheenVisibility, SmithForm, TorranceSparrow,
};
use brdf_core::{Dots, Real, Vec3};

// `masking_index!`, `sheen_visibility_index!`, `dielectric_distribution_index!`: an option
// name of the model catalogue to its index there, as an integer literal (build.rs).
include!(concat!(env!("OUT_DIR"), "/catalogue_index.rs"));

/// Which reading of the paper's eq 12 the modified G uses (a `BRDF_CONVENTION_*` value).
pub type BrdfConvention = u32;
/// GS = M(θi, −α): the tilt toward the light; reciprocal (the default reading).
pub const BRDF_CONVENTION_RECIPROCAL: BrdfConvention = 0;
/// Eq 12 as printed: GS = M(θi, α), GM = 1 for θr ≤ 0; not reciprocal.
pub const BRDF_CONVENTION_PRINTED: BrdfConvention = 1;

/// The microfacet distribution of a Smith G (a `BRDF_SMITH_*` distribution value).
pub type BrdfSmithDistribution = u32;
/// Beckmann; roughness is the Beckmann m (RMS slope × √2).
pub const BRDF_SMITH_BECKMANN: BrdfSmithDistribution = 0;
/// Trowbridge–Reitz (GGX); roughness is α.
pub const BRDF_SMITH_GGX: BrdfSmithDistribution = 1;

/// How the two one-sided Smith terms combine (a `BRDF_SMITH_FORM_*` value).
pub type BrdfSmithForm = u32;
/// G = G1(θi) G1(θo).
pub const BRDF_SMITH_FORM_SEPARABLE: BrdfSmithForm = 0;
/// G = 1/(1 + Λ(θi) + Λ(θo)), height-correlated.
pub const BRDF_SMITH_FORM_CORRELATED: BrdfSmithForm = 1;

/// The G of the Torrance–Sparrow BRDF (a `BRDF_GEOMETRIC_*` value).
pub type BrdfGeometricTerm = u32;
/// G = 1.
pub const BRDF_GEOMETRIC_NONE: BrdfGeometricTerm = masking_index!("none");
/// Blinn's V-groove G (paper eq 4).
pub const BRDF_GEOMETRIC_BLINN: BrdfGeometricTerm = masking_index!("blinn");
/// Smith–Beckmann, separable, m = √2σ.
pub const BRDF_GEOMETRIC_SMITH_SEPARABLE: BrdfGeometricTerm = masking_index!("smith-separable");
/// Smith–Beckmann, height-correlated, m = √2σ.
pub const BRDF_GEOMETRIC_SMITH_CORRELATED: BrdfGeometricTerm = masking_index!("smith-correlated");
/// The paper's modified G, reciprocal convention.
pub const BRDF_GEOMETRIC_MODIFIED: BrdfGeometricTerm = masking_index!("modified");
/// The paper's modified G with eq 12 as printed.
pub const BRDF_GEOMETRIC_MODIFIED_PRINTED: BrdfGeometricTerm = masking_index!("modified-printed");

/// The Fresnel term of the Torrance–Sparrow BRDF (a `BRDF_FRESNEL_*` value), evaluated at
/// wi·h; its parameter is passed beside it.
pub type BrdfFresnel = u32;
/// F = 1 (the parameter is ignored).
pub const BRDF_FRESNEL_ONE: BrdfFresnel = 0;
/// Schlick, F = R0 + (1 − R0)(1 − cos)^5 (Fundamentals of Computer Graphics eq 24.6);
/// parameter R0 ∈ [0, 1].
pub const BRDF_FRESNEL_SCHLICK: BrdfFresnel = 1;
/// Schlick with R0 = ((η − 1)/(η + 1))²; parameter the relative index η > 0.
pub const BRDF_FRESNEL_SCHLICK_IOR: BrdfFresnel = 2;
/// The exact unpolarised dielectric reflectance; parameter the relative index η > 0.
pub const BRDF_FRESNEL_DIELECTRIC: BrdfFresnel = 3;

/// The visibility term of the sheen BRDF (a `BRDF_SHEEN_VISIBILITY_*` value): the index of
/// the option in the model catalogue's `visibility` choice.
pub type BrdfSheenVisibility = u32;
/// V = G2/(4 (n·wi)(n·wo)) with Estevez and Kulla's fitted Smith Λ (glTF
/// `KHR_materials_sheen`).
pub const BRDF_SHEEN_VISIBILITY_ESTEVEZ_KULLA: BrdfSheenVisibility =
    sheen_visibility_index!("estevez-kulla");
/// Ashikhmin's V = 1/(4 (n·wi + n·wo − (n·wi)(n·wo))) (Filament's cloth).
pub const BRDF_SHEEN_VISIBILITY_ASHIKHMIN: BrdfSheenVisibility =
    sheen_visibility_index!("ashikhmin");

/// The microfacet distribution of the rough dielectric BSDF (a
/// `BRDF_DIELECTRIC_DISTRIBUTION_*` value): the index of the option in the model catalogue's
/// `distribution` choice.
pub type BrdfDielectricDistribution = u32;
/// Trowbridge–Reitz (GGX), width α.
pub const BRDF_DIELECTRIC_DISTRIBUTION_GGX: BrdfDielectricDistribution =
    dielectric_distribution_index!("ggx");
/// Beckmann, width α.
pub const BRDF_DIELECTRIC_DISTRIBUTION_BECKMANN: BrdfDielectricDistribution =
    dielectric_distribution_index!("beckmann");

/// Storage words (8 bytes each) of the modified-G handles.
pub const BRDF_MODIFIED_G_WORDS: usize = 8;
/// Storage words (8 bytes each) of the Torrance–Sparrow handles.
pub const BRDF_TORRANCE_SPARROW_WORDS: usize = 16;
/// Storage words (8 bytes each) of the GGX handles.
pub const BRDF_GGX_WORDS: usize = 8;
/// Storage words (8 bytes each) of the sheen handles.
pub const BRDF_SHEEN_WORDS: usize = 16;
/// Storage words (8 bytes each) of the rough dielectric handles.
pub const BRDF_ROUGH_DIELECTRIC_WORDS: usize = 8;

fn convention(c: BrdfConvention) -> Option<Convention> {
    match c {
        BRDF_CONVENTION_RECIPROCAL => Some(Convention::Reciprocal),
        BRDF_CONVENTION_PRINTED => Some(Convention::Printed),
        _ => None,
    }
}

/// A `BRDF_GEOMETRIC_*` value is the term's index in the model catalogue's list of masking
/// terms (`brdf_core::catalogue::MASKINGS`, through `masking_index!`; tests/catalogue.rs
/// checks that brdf.h names every term).
fn geometric_term(g: BrdfGeometricTerm) -> Option<GeometricTerm> {
    GeometricTerm::ALL.get(g as usize).copied()
}

fn fresnel<T: Real>(kind: BrdfFresnel, p: T) -> Option<Fresnel<T>> {
    match kind {
        BRDF_FRESNEL_ONE => Some(Fresnel::One),
        BRDF_FRESNEL_SCHLICK => Fresnel::schlick(p).ok(),
        BRDF_FRESNEL_SCHLICK_IOR => Fresnel::schlick_ior(p).ok(),
        BRDF_FRESNEL_DIELECTRIC => Fresnel::dielectric(p).ok(),
        _ => None,
    }
}

fn smith_form(f: BrdfSmithForm) -> Option<SmithForm> {
    match f {
        BRDF_SMITH_FORM_SEPARABLE => Some(SmithForm::Separable),
        BRDF_SMITH_FORM_CORRELATED => Some(SmithForm::Correlated),
        _ => None,
    }
}

fn modified_new<T: Real>(sigma: T, c: BrdfConvention) -> Result<ModifiedG<T>, BrdfStatus> {
    let c = convention(c).ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    let g = ModifiedG::new(sigma).map_err(|_| BRDF_STATUS_INVALID_ARGUMENT)?;
    Ok(g.with_convention(c))
}

fn rough_ok<T: Real>(r: T) -> bool {
    r.is_finite() && r > T::ZERO
}

/// One-sided Smith G1 = 1/(1 + Λ) of the microfacet distribution `d` of width `r` at
/// cos θ = n·w (the direction [`from_cos`]); NaN for a bad width or distribution.
fn g1_smith<T: Real>(d: BrdfSmithDistribution, cos_t: T, r: T) -> T {
    if !rough_ok(r) {
        return T::NAN;
    }
    let w = from_cos(cos_t);
    match d {
        BRDF_SMITH_BECKMANN => Beckmann::clamped(r, r).g1(w),
        BRDF_SMITH_GGX => TrowbridgeReitz::clamped(r, r).g1(w),
        _ => T::NAN,
    }
}

/// Smith's G of the pair n·wi = `ci`, n·wo = `co` for the distribution `d` of width `r` in
/// form `f`; NaN for a bad width, distribution or form.
fn g_smith<T: Real>(d: BrdfSmithDistribution, f: BrdfSmithForm, ci: T, co: T, r: T) -> T {
    if !rough_ok(r) {
        return T::NAN;
    }
    let Some(f) = smith_form(f) else {
        return T::NAN;
    };
    match d {
        BRDF_SMITH_BECKMANN => g_of_form(Beckmann::clamped(r, r), f, ci, co),
        BRDF_SMITH_GGX => g_of_form(TrowbridgeReitz::clamped(r, r), f, ci, co),
        _ => T::NAN,
    }
}

/// G = G1(wi) G1(wo) or 1/(1 + Λ(wi) + Λ(wo)) of `m` at the cosines `ci`, `co`.
fn g_of_form<T: Real, D: Distribution<T>>(m: D, f: SmithForm, ci: T, co: T) -> T {
    let (wi, wo) = (from_cos(ci), from_cos(co));
    match f {
        SmithForm::Separable => m.g_separable(wi, wo),
        SmithForm::Correlated => m.g_correlated(wi, wo),
    }
}

fn ts_new<T: Real>(
    sigma: T,
    g: BrdfGeometricTerm,
    f: BrdfFresnel,
    fp: T,
    ks: T,
    albedo: T,
) -> Result<TorranceSparrow<T>, BrdfStatus> {
    let g = geometric_term(g).ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    let f = fresnel(f, fp).ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    TorranceSparrow::new(sigma, g, f, ks, albedo).map_err(|_| BRDF_STATUS_INVALID_ARGUMENT)
}

/// The Torrance–Sparrow BRDF seen as a [`Brdf`] for the albedo quadrature, which only
/// evaluates it (no sampling).
struct TsLobe<'a, T>(&'a TorranceSparrow<T>);

impl<T: Real> Brdf<T> for TsLobe<'_, T> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags {
            reciprocal: self.0.g_term() != GeometricTerm::ModifiedPrinted,
            energy_conserving: false,
            has_delta: false,
        }
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        Rgb::splat(self.0.eval(wi, wo))
    }
    fn pdf(&self, _wo: Vec3<T>, _wi: Vec3<T>) -> T {
        T::ZERO
    }
    fn sample(&self, _wo: Vec3<T>, _u: [T; 2]) -> Option<BrdfSample<T>> {
        None
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(self.0.beckmann_m())
    }
}

/// wo = (√(1 − μ²), 0, μ) for μ = n·wo ∈ (0, 1] (clamped above); `None` for NaN, `Some(None)`
/// at or below the horizon.
fn wo_of_mu<T: Real>(mu: T) -> Option<Option<Vec3<T>>> {
    if mu.is_nan() {
        return None;
    }
    if !(mu > T::ZERO) {
        return Some(None);
    }
    let c = mu.min(T::ONE);
    Some(Some(Vec3::new((T::ONE - c * c).sqrt(), T::ZERO, c)))
}

/// Directional albedo per channel of a prepared model for a viewer at μ = n·wo (clamped to
/// ≤ 1): 0 for μ ≤ 0; all NaN for NaN μ or a missing handle.
fn albedo_of<T: Real, M: Brdf<T>>(m: Option<&M>, mu: T) -> Rgb<T> {
    match (m, wo_of_mu(mu)) {
        (Some(m), Some(Some(wo))) => directional_albedo(m, wo),
        (Some(_), Some(None)) => Rgb::zero(),
        _ => Rgb::splat(T::NAN),
    }
}

/// f per channel of a prepared model at unit directions `wi`, `wo`; all NaN for a missing
/// handle or a non-finite component.
fn eval_at<T: Real, M: Brdf<T>>(m: Option<&M>, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
    match m {
        Some(m) if vec_ok(wi) && vec_ok(wo) => m.eval(wi, wo),
        _ => Rgb::splat(T::NAN),
    }
}

fn ggx_new<T: Real>(f0: Rgb<T>, alpha: T, form: BrdfSmithForm) -> Result<Ggx<T>, BrdfStatus> {
    let form = smith_form(form).ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    Ggx::new(f0, alpha, form, MicrofacetSampling::VisibleNormals)
        .map_err(|_| BRDF_STATUS_INVALID_ARGUMENT)
}

fn sheen_new<T: Real>(color: Rgb<T>, r: T, v: BrdfSheenVisibility) -> Result<Sheen<T>, BrdfStatus> {
    let v = *SheenVisibility::ALL
        .get(v as usize)
        .ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    Sheen::new(color, r, v).map_err(|_| BRDF_STATUS_INVALID_ARGUMENT)
}

fn finite3<T: Real>(a: T, b: T, c: T) -> bool {
    a.is_finite() && b.is_finite() && c.is_finite()
}

fn vec_ok<T: Real>(v: Vec3<T>) -> bool {
    finite3(v.x, v.y, v.z)
}

fn dielectric_new<T: Real>(
    d: BrdfDielectricDistribution,
    alpha: T,
    eta: T,
) -> Result<RoughDielectric<T>, BrdfStatus> {
    let d = *DielectricDistribution::ALL
        .get(d as usize)
        .ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    RoughDielectric::new(d, alpha, eta).map_err(|_| BRDF_STATUS_INVALID_ARGUMENT)
}

/// `f(m, a, b)` of a prepared rough dielectric at two directions; NaN for a missing handle or
/// a non-finite component.
fn dielectric_at<T: Real>(
    m: Option<&RoughDielectric<T>>,
    a: Vec3<T>,
    b: Vec3<T>,
    f: impl Fn(&RoughDielectric<T>, Vec3<T>, Vec3<T>) -> T,
) -> T {
    match m {
        Some(m) if vec_ok(a) && vec_ok(b) => f(m, a, b),
        _ => T::NAN,
    }
}

/// [`RoughDielectric::sample_with_choice`] with the C status codes: not initialised (bad
/// handle), invalid argument (a non-finite input, or wo at or below the surface, n·wo ≤ 0),
/// no sample (the sampler returned none: wo within brdf-core's `min_cos` of the horizon, or
/// a sampled direction the pdf does not cover).
fn dielectric_sample<T: Real>(
    m: Option<&RoughDielectric<T>>,
    wo: Vec3<T>,
    u: [T; 2],
    uc: T,
) -> Result<BrdfSample<T>, BrdfStatus> {
    let m = m.ok_or(BRDF_STATUS_NOT_INITIALISED)?;
    if !vec_ok(wo) || !finite3(u[0], u[1], uc) || !(wo.z > T::ZERO) {
        return Err(BRDF_STATUS_INVALID_ARGUMENT);
    }
    m.sample_with_choice(wo, u, uc).ok_or(BRDF_STATUS_NO_SAMPLE)
}

/// The Dirac part of a prepared rough dielectric for wo (η = 1 only), or a zero lobe
/// (probability 0) when it has none; statuses as for [`dielectric_sample`].
fn dielectric_delta<T: Real>(
    m: Option<&RoughDielectric<T>>,
    wo: Vec3<T>,
) -> Result<DeltaLobe<T>, BrdfStatus> {
    let m = m.ok_or(BRDF_STATUS_NOT_INITIALISED)?;
    if !vec_ok(wo) {
        return Err(BRDF_STATUS_INVALID_ARGUMENT);
    }
    Ok(m.delta(wo).unwrap_or(DeltaLobe {
        wi: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        reflectance: Rgb::zero(),
        prob: T::ZERO,
    }))
}

/// Writes `r`'s value through `out` (converted) and returns its status; writes nothing on an
/// error or for a null `out` (`BRDF_STATUS_NULL_POINTER`, checked first).
///
/// # Safety
/// `out` is null or valid for writes of one `C`.
unsafe fn put_result<V, C: From<V>>(
    out: *mut C,
    r: impl FnOnce() -> Result<V, BrdfStatus>,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    match r() {
        Ok(v) => {
            // SAFETY: `out` is non-null and valid for writes (this function's contract);
            // `write_unaligned` needs no alignment.
            unsafe { out.write_unaligned(C::from(v)) };
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// `f` of a prepared model at the dot products `d` = [n·wi, n·wo, wi·wo] ([`Dots::new`]);
/// `nan` for a missing handle or a non-finite dot product.
fn at_dots<T: Real, M, R>(m: Option<&M>, d: [T; 3], nan: R, f: impl Fn(&M, Dots<T>) -> R) -> R {
    match m {
        Some(m) if finite3(d[0], d[1], d[2]) => f(m, Dots::new(d[0], d[1], d[2])),
        _ => nan,
    }
}

// ---------------------------------------------------------------------------------------
// The typed exports, written once and instantiated for `f32` and `f64` below. The C names
// are passed in (macro_rules cannot build identifiers); the doc text names the sibling
// functions through them, so both instantiations read as the hand-written halves did.

/// Emits the structs, handles and exports of one scalar type `$t`.
macro_rules! typed_abi {
    (
        $t:ident;
        $Terms:ident, $Vec3:ident, $Rgb:ident;
        $MG:ident, $TS:ident, $Ggx:ident;
        $mg_init:ident, $mg_terms:ident, $mg_g:ident, $mg_terms_dots:ident, $mg_dots:ident,
        $mg_batch:ident, $blinn:ident, $blinn_dots:ident, $g1_smith:ident, $g_smith:ident,
        $ts_init:ident, $ts_eval:ident, $ts_eval_nh:ident, $ts_specular:ident, $ts_batch:ident,
        $ts_albedo:ident, $ggx_init:ident, $ggx_eval:ident, $ggx_albedo:ident $(,)?
    ) => {
        /// GM, GS and G = min(GM, GS) of the modified G (paper eqs 11–13), each in [0, 1]; all NaN
        /// for bad input.
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $Terms {
            /// Masking, the viewing side (eq 11).
            pub gm: $t,
            /// Shadowing, the light's side (eq 12).
            pub gs: $t,
            /// G = min(GM, GS) (eq 13).
            pub g: $t,
        }

        /// A 3-vector in the local shading frame (z = normal).
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $Vec3 {
            /// x (tangent).
            pub x: $t,
            /// y (bitangent).
            pub y: $t,
            /// z (normal).
            pub z: $t,
        }

        /// An RGB triple (per-channel values, e.g. a BRDF in 1/sr or a reflectance).
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $Rgb {
            /// Red.
            pub r: $t,
            /// Green.
            pub g: $t,
            /// Blue.
            pub b: $t,
        }

        handle! {
            /// A prepared modified G for one surface (σ, convention). Fill it with
            #[doc = concat!(" `", stringify!($mg_init), "`; the fields are private to the library.")]
            $MG[BRDF_MODIFIED_G_WORDS] = ModifiedG<$t>, crate::scalar_tag::<$t>(*b"MG")
        }

        handle! {
            #[doc = concat!(" A prepared Torrance–Sparrow BRDF. Fill it with `", stringify!($ts_init), "`; the")]
            /// fields are private to the library.
            $TS[BRDF_TORRANCE_SPARROW_WORDS] = TorranceSparrow<$t>, crate::scalar_tag::<$t>(*b"TS")
        }

        impl From<masking::GTerms<$t>> for $Terms {
            fn from(t: masking::GTerms<$t>) -> Self {
                Self { gm: t.gm, gs: t.gs, g: t.g }
            }
        }

        impl $Terms {
            const NAN: Self = Self { gm: <$t>::NAN, gs: <$t>::NAN, g: <$t>::NAN };
        }

        impl From<Rgb<$t>> for $Rgb {
            fn from(c: Rgb<$t>) -> Self {
                Self { r: c.r, g: c.g, b: c.b }
            }
        }

        impl From<$Rgb> for Rgb<$t> {
            fn from(c: $Rgb) -> Self {
                Rgb::new(c.r, c.g, c.b)
            }
        }

        impl From<$Vec3> for Vec3<$t> {
            fn from(v: $Vec3) -> Self {
                Vec3::new(v.x, v.y, v.z)
            }
        }

        init_export! {
            /// Prepares the modified G of the 2015 Acta Physica Sinica paper (eqs 6–13) for RMS slope
            /// `sigma` (finite, > 0; accuracy specified for σ ∈ [0.05, 1]) and `convention`
            /// (`BRDF_CONVENTION_*`). Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` (`out` null)
            /// or `BRDF_STATUS_INVALID_ARGUMENT` (σ NaN, infinite or ≤ 0, unknown convention); on error
            /// `*out` is left not initialised.
            init $mg_init($MG; sigma: $t, convention: BrdfConvention) = modified_new(sigma, convention)
        }

        query_export! {
            /// GM, GS and G from the paper's in-plane angles in radians: θi ∈ [0, π/2], θr ∈ [−π/2, π/2]
            /// signed (out-of-range and infinite angles are clamped to those ranges). NaN angles, a null
            /// or uninitialised handle give all NaN.
            $mg_terms(g: $MG, theta_i: $t, theta_r: $t) -> $Terms =
                g.map_or($Terms::NAN, |m| m.terms(theta_i, theta_r).into());
        }

        #[doc = concat!(" G = min(GM, GS) ∈ [0, 1] from in-plane angles; see `", stringify!($mg_terms), "` (NaN for")]
        /// NaN angles or a bad handle).
        #[cfg_attr(not(brdf_header), doc = crate::safety!(query))]
        #[no_mangle]
        pub unsafe extern "C" fn $mg_g(g: *const $MG, theta_i: $t, theta_r: $t) -> $t {
            // SAFETY: the caller's contract, passed on unchanged.
            unsafe { $mg_terms(g, theta_i, theta_r) }.g
        }

        query_export! {
            /// GM, GS and G from the dot products n·wi, n·wo, wi·wo of unit vectors (the reciprocal
            /// 3-D extension; with the printed convention the pair is folded into its plane). A direction
            /// at or below the horizon (n·w ≤ 0) gives 0; a non-finite dot product, a null or
            /// uninitialised handle give all NaN.
            $mg_terms_dots(g: $MG, n_i: $t, n_o: $t, i_o: $t) -> $Terms =
                at_dots(g, [n_i, n_o, i_o], $Terms::NAN, |m, d| m.terms_dots(d).into());
        }

        #[doc = concat!(" G ∈ [0, 1] from dot products; see `", stringify!($mg_terms_dots), "`.")]
        #[cfg_attr(not(brdf_header), doc = crate::safety!(query))]
        #[no_mangle]
        pub unsafe extern "C" fn $mg_dots(g: *const $MG, n_i: $t, n_o: $t, i_o: $t) -> $t {
            // SAFETY: the caller's contract, passed on unchanged.
            unsafe { $mg_terms_dots(g, n_i, n_o, i_o) }.g
        }

        batch_export! {
            #[doc = concat!(" `out[k] = ", stringify!($mg_dots), "(g, n_i[k], n_o[k], i_o[k])` for k < n. Returns")]
            /// `BRDF_STATUS_NOT_INITIALISED` (bad handle; nothing written), `BRDF_STATUS_NULL_POINTER`
            /// (an array null with n > 0; nothing written), `BRDF_STATUS_BAD_LENGTH` (n too large) or
            /// `BRDF_STATUS_OK`. `out` may alias an input.
            $mg_batch(g: $MG; n_i, n_o, i_o => out: $t) = |m, d| [at_dots(Some(m), d, <$t>::NAN, ModifiedG::g_dots)]
        }

        /// Blinn's V-groove G (paper eq 4) ∈ [0, 1] from in-plane angles in radians (clamped like
        #[doc = concat!(" `", stringify!($mg_terms), "`); NaN in, NaN out.")]
        #[no_mangle]
        pub extern "C" fn $blinn(theta_i: $t, theta_r: $t) -> $t {
            masking::g_blinn(theta_i, theta_r)
        }

        /// Blinn's V-groove G ∈ [0, 1] from n·wi, n·wo, wi·wo of unit vectors; 0 when a direction is
        /// at or below the horizon; NaN when a dot product is not finite.
        #[no_mangle]
        pub extern "C" fn $blinn_dots(n_i: $t, n_o: $t, i_o: $t) -> $t {
            if !finite3(n_i, n_o, i_o) {
                return <$t>::NAN;
            }
            masking::g_blinn_dots(Dots::new(n_i, n_o, i_o))
        }

        /// One-sided Smith masking G1 = 1/(1 + Λ) ∈ [0, 1] at cos θ = n·w (≤ 0 gives 0), for
        /// `distribution` (`BRDF_SMITH_BECKMANN` with Beckmann m, `BRDF_SMITH_GGX` with α as
        /// `roughness`). NaN for NaN cos θ, roughness NaN, infinite or ≤ 0, or an unknown
        /// distribution.
        #[no_mangle]
        pub extern "C" fn $g1_smith(
            distribution: BrdfSmithDistribution,
            cos_theta: $t,
            roughness: $t,
        ) -> $t {
            g1_smith(distribution, cos_theta, roughness)
        }

        /// Smith's G ∈ [0, 1] for the pair n·wi = `cos_i`, n·wo = `cos_o` (either ≤ 0 gives 0), in
        #[doc = concat!(" `form` (`BRDF_SMITH_FORM_*`); `distribution` and `roughness` as for `", stringify!($g1_smith), "`.")]
        /// NaN for NaN input, bad roughness or an unknown distribution or form.
        #[no_mangle]
        pub extern "C" fn $g_smith(
            distribution: BrdfSmithDistribution,
            form: BrdfSmithForm,
            cos_i: $t,
            cos_o: $t,
            roughness: $t,
        ) -> $t {
            g_smith(distribution, form, cos_i, cos_o, roughness)
        }

        init_export! {
            /// Prepares the Torrance–Sparrow BRDF of the paper (eq 3):
            /// f = k_s D F G / (4 (n·wi)(n·wo)) + ρ_d/π, D Beckmann with m = √2σ, F chosen by `fresnel`
            /// (`BRDF_FRESNEL_*`) with parameter `fresnel_param` (R0 ∈ [0, 1] or η > 0; ignored for
            /// `BRDF_FRESNEL_ONE`), G by `g_term` (`BRDF_GEOMETRIC_*`). σ finite > 0, k_s ∈ [0, ∞)
            /// finite, ρ_d = `albedo` ∈ [0, 1]. Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` or
            /// `BRDF_STATUS_INVALID_ARGUMENT` (any parameter out of range, NaN, infinite, or an unknown
            /// choice); on error `*out` is left not initialised.
            init $ts_init(
                $TS;
                sigma: $t,
                g_term: BrdfGeometricTerm,
                fresnel: BrdfFresnel,
                fresnel_param: $t,
                ks: $t,
                albedo: $t,
            ) = ts_new(sigma, g_term, fresnel, fresnel_param, ks, albedo)
        }

        query_export! {
            /// The Torrance–Sparrow BRDF in 1/sr (specular + ρ_d/π) from n·wi, n·wo, wi·wo of unit
            /// vectors; 0 when a direction is at or below the horizon; NaN for a non-finite dot product
            /// or a null or uninitialised handle.
            $ts_eval(ts: $TS, n_i: $t, n_o: $t, i_o: $t) -> $t =
                at_dots(ts, [n_i, n_o, i_o], <$t>::NAN, TorranceSparrow::eval_dots);

            #[doc = concat!(" `", stringify!($ts_eval), "` with n·h as well, h = normalize(wi + wo) as a shader")]
            /// has it. Exact where the three dot products alone are not: for a near-mirror pair near
            /// the horizon 2 + 2 wi·wo cancels, and |wi + wo| (hence h, D and the BRDF) is then
            /// recovered from n·h instead (`Dots::with_n_h`). Bad input as for
            #[doc = concat!(" `", stringify!($ts_eval), "`; a non-finite n·h gives NaN.")]
            $ts_eval_nh(ts: $TS, n_i: $t, n_o: $t, i_o: $t, n_h: $t) -> $t =
                match ts {
                    Some(t) if finite3(n_i, n_o, i_o) && n_h.is_finite() => {
                        t.eval_dots(Dots::with_n_h(n_i, n_o, i_o, n_h))
                    }
                    _ => <$t>::NAN,
                };

            /// The specular lobe k_s D F G / (4 (n·wi)(n·wo)) alone, in 1/sr; bad input as for
            #[doc = concat!(" `", stringify!($ts_eval), "`.")]
            $ts_specular(ts: $TS, n_i: $t, n_o: $t, i_o: $t) -> $t =
                at_dots(ts, [n_i, n_o, i_o], <$t>::NAN, TorranceSparrow::eval_specular);
        }

        batch_export! {
            #[doc = concat!(" `out[k] = ", stringify!($ts_eval), "(ts, n_i[k], n_o[k], i_o[k])` for k < n; status")]
            #[doc = concat!(" codes as for `", stringify!($mg_batch), "`.")]
            $ts_batch(ts: $TS; n_i, n_o, i_o => out: $t) = |t, d| [at_dots(Some(t), d, <$t>::NAN, TorranceSparrow::eval_dots)]
        }

        query_export! {
            /// Directional albedo R(μ) = ∫ f cos θi dωi over the upper hemisphere (including ρ_d), for
            /// a viewer at μ = n·wo ∈ (0, 1] (values above 1 count as 1), by brdf-core's fixed
            /// quadrature (about 4·10⁵ BRDF evaluations: slow on a microcontroller). μ ≤ 0 gives 0; NaN
            /// μ, a null or uninitialised handle give NaN.
            $ts_albedo(ts: $TS, mu: $t) -> $t =
                albedo_of(ts.map(TsLobe).as_ref(), mu).r;
        }

        rgb_brdf_abi! {
            $t; $Vec3, $Rgb;
            #[doc = concat!(" A prepared GGX BRDF. Fill it with `", stringify!($ggx_init), "`; the fields are private to the")]
            /// library.
            $Ggx[BRDF_GGX_WORDS] = Ggx, *b"GX";

            /// Prepares the GGX (Trowbridge–Reitz) BRDF f = D F G / (4 (n·wi)(n·wo)) with per-channel
            /// Schlick F (F0 = `f0`, each in [0, 1]) and Smith masking in `smith_form`
            /// (`BRDF_SMITH_FORM_*`); α ∈ [1e-4, 1e4]. Returns `BRDF_STATUS_OK`,
            /// `BRDF_STATUS_NULL_POINTER` or `BRDF_STATUS_INVALID_ARGUMENT`; on error `*out` is left not
            /// initialised.
            $ggx_init(f0: $Rgb, alpha: $t, smith_form: BrdfSmithForm) = ggx_new(f0.into(), alpha, smith_form);

            /// The GGX BRDF in 1/sr per channel for unit local-frame directions `wi` (toward the light)
            /// and `wo` (toward the viewer); not normalised here. 0 when either is at or below the
            /// horizon; all NaN for a non-finite component or a null or uninitialised handle.
            $ggx_eval(g);

            /// Directional albedo per channel of the GGX BRDF for a viewer at μ = n·wo; arguments and
            #[doc = concat!(" bad input as for `", stringify!($ts_albedo), "`.")]
            $ggx_albedo;
        }
    };
}

/// Emits the handle `$h` of a model `$m<$t>` (a [`Brdf`] with per-channel values, tag
/// `scalar_tag::<$t>($kind)`) and its exports for one scalar type `$t`: `$init(out, $arg, …)`
/// fills the handle with `$new` (a `Result<$m<$t>, BrdfStatus>` of the arguments),
/// `$eval($hv, wi, wo)` is [`eval_at`], `$albedo($hv, mu)` is [`albedo_of`], and the items in
/// the optional `{ … }` between the two (a model's further exports) are emitted there. Each
/// export's docs are passed in.
macro_rules! rgb_brdf_abi {
    (
        $t:ident; $Vec3:ident, $Rgb:ident;
        $(#[$hdoc:meta])* $h:ident[$words:ident] = $m:ident, $kind:expr;
        $(#[$idoc:meta])* $init:ident($($arg:ident: $ty:ty),+) = $new:expr;
        $(#[$edoc:meta])* $eval:ident($hv:ident);
        $({ $($extra:item)* })?
        $(#[$adoc:meta])* $albedo:ident;
    ) => {
        handle! {
            $(#[$hdoc])*
            $h[$words] = $m<$t>, crate::scalar_tag::<$t>($kind)
        }

        init_export! {
            $(#[$idoc])*
            init $init($h; $($arg: $ty),+) = $new
        }

        query_export! {
            $(#[$edoc])*
            $eval($hv: $h, wi: $Vec3, wo: $Vec3) -> $Rgb = eval_at($hv, wi.into(), wo.into()).into();
        }

        $($($extra)*)?

        query_export! {
            $(#[$adoc])*
            $albedo($hv: $h, mu: $t) -> $Rgb = albedo_of($hv, mu).into();
        }
    };
}

/// Emits the sheen handle and its exports for one scalar type `$t` (the vector and colour
/// structs come from `typed_abi!`).
macro_rules! sheen_abi {
    (
        $t:ident; $Vec3:ident, $Rgb:ident; $Sheen:ident;
        $init:ident, $eval:ident, $eval_dots:ident, $albedo:ident $(,)?
    ) => {
        rgb_brdf_abi! {
            $t; $Vec3, $Rgb;
            #[doc = concat!(" A prepared sheen BRDF. Fill it with `", stringify!($init), "`; the fields are private to the")]
            /// library.
            $Sheen[BRDF_SHEEN_WORDS] = Sheen, *b"SH";

            /// Prepares the Charlie sheen BRDF of Estevez and Kulla (2017), f = color · D · V, with
            /// D = (2 + 1/α) sin^(1/α)θh / (2π), α = r² (perceptual roughness `roughness` ∈ [0, 1];
            /// α is clamped to at least 1e-4), `color` ∈ [0, 1] per channel and `visibility` a
            /// `BRDF_SHEEN_VISIBILITY_*` value. Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER`
            /// or `BRDF_STATUS_INVALID_ARGUMENT`; on error `*out` is left not initialised.
            $init(color: $Rgb, roughness: $t, visibility: BrdfSheenVisibility) =
                sheen_new(color.into(), roughness, visibility);

            /// The sheen BRDF in 1/sr per channel for unit local-frame directions `wi` (toward the
            /// light) and `wo` (toward the viewer), half vector from the vectors. 0 when either is
            /// at or below the horizon; all NaN for a non-finite component or a null or
            /// uninitialised handle.
            $eval(s);
            {
                query_export! {
                    /// The sheen BRDF from the dot products n·wi, n·wo and wi·wo of unit vectors (the module
                    /// docs say what the three-dot form loses for nearly opposite pairs at the horizon);
                    /// 0 at or below the horizon; all NaN for a non-finite input or a bad handle.
                    $eval_dots(s: $Sheen, n_i: $t, n_o: $t, i_o: $t) -> $Rgb =
                        at_dots(s, [n_i, n_o, i_o], Rgb::splat(<$t>::NAN), Sheen::eval_dots).into();
                }
            }

            /// Directional albedo per channel of the sheen BRDF for a viewer at μ = n·wo ∈ (0, 1]
            /// (clamped above); 0 for μ ≤ 0; all NaN for NaN or a bad handle.
            $albedo;
        }
    };
}

/// Emits the rough dielectric handle, its sample and Dirac structs and its exports for one
/// scalar type `$t` (the vector and colour structs come from `typed_abi!`).
macro_rules! rough_dielectric_abi {
    (
        $t:ident; $Vec3:ident, $Rgb:ident; $RD:ident, $Sample:ident, $Delta:ident;
        $init:ident, $eval:ident, $eval_adjoint:ident, $pdf:ident, $sample:ident,
        $delta:ident $(,)?
    ) => {
        handle! {
            #[doc = concat!(" A prepared rough dielectric BSDF. Fill it with `", stringify!($init), "`; the fields are")]
            /// private to the library.
            $RD[BRDF_ROUGH_DIELECTRIC_WORDS] = RoughDielectric<$t>, crate::scalar_tag::<$t>(*b"RD")
        }

        /// A sampled direction of a BSDF for a given wo.
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $Sample {
            /// The sampled direction toward the light (unit, local frame; either hemisphere).
            pub wi: $Vec3,
            /// For a continuous sample the pdf of `wi` per unit solid angle (the pdf export's
            /// value); for a Dirac sample the probability of choosing the Dirac.
            pub pdf: $t,
            /// f(wi, wo) |n·wi| / pdf per channel (for a Dirac sample: its transmittance or
            /// reflectance over its probability).
            pub weight: $Rgb,
            /// 1 when the sample is the Dirac part, else 0.
            pub specular: u32,
        }

        /// The Dirac part of a BSDF for a given wo: `prob` 0 (and the other fields 0) when it
        /// has none.
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $Delta {
            /// The Dirac direction toward the light.
            pub wi: $Vec3,
            /// Its contribution to ∫ f |n·wi| dωi per channel.
            pub reflectance: $Rgb,
            /// The probability that the sampler returns it.
            pub prob: $t,
        }

        impl From<Vec3<$t>> for $Vec3 {
            fn from(v: Vec3<$t>) -> Self {
                Self { x: v.x, y: v.y, z: v.z }
            }
        }

        impl From<BrdfSample<$t>> for $Sample {
            fn from(s: BrdfSample<$t>) -> Self {
                let specular = u32::from(s.specular);
                Self { wi: s.wi.into(), pdf: s.pdf, weight: s.weight.into(), specular }
            }
        }

        impl From<DeltaLobe<$t>> for $Delta {
            fn from(d: DeltaLobe<$t>) -> Self {
                Self { wi: d.wi.into(), reflectance: d.reflectance.into(), prob: d.prob }
            }
        }

        init_export! {
            /// Prepares the rough dielectric BSDF of Walter, Marschner, Li and Torrance (EGSR 2007):
            /// reflection (eq 20) and refraction (eq 21) at a rough interface, exact dielectric
            /// Fresnel, separable Smith G (eq 23), radiance convention (f_t carries η_o²;
            /// docs/conventions.md §12). `distribution` is a `BRDF_DIELECTRIC_DISTRIBUTION_*`
            /// value, α ∈ [0, 1e4] (floored to 1e-4), η = η_inside/η_outside ∈ [0.1, 10] (the +z side
            /// is outside). Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` or
            /// `BRDF_STATUS_INVALID_ARGUMENT`; on error `*out` is left not initialised.
            init $init($RD; distribution: BrdfDielectricDistribution, alpha: $t, eta: $t) =
                dielectric_new(distribution, alpha, eta)
        }

        query_export! {
            /// The BSDF f(wi, wo) in 1/sr over the whole sphere, `wi` toward the light and `wo`
            /// toward the viewer (unit, local frame): f_r for a pair on one side, f_t for a pair
            /// across the surface (wo below the surface gives the part transmitted from outside).
            /// 0 at the horizon (|n·w| below 2^−63 in f32, 2^−511 in f64), for η = 1 (see the
            /// delta export)
            /// and for a pair no facet connects; NaN for a non-finite component or a bad handle.
            $eval(m: $RD, wi: $Vec3, wo: $Vec3) -> $t =
                dielectric_at(m, wi.into(), wo.into(), RoughDielectric::eval_bsdf);

            /// The adjoint BSDF f*(wi, wo) = f(wo, wi) (importance transport): f_r unchanged,
            /// f_t* = (η_i/η_o)² f_t; arguments and bad input as for
            #[doc = concat!(" `", stringify!($eval), "`.")]
            $eval_adjoint(m: $RD, wi: $Vec3, wo: $Vec3) -> $t =
                dielectric_at(m, wi.into(), wo.into(), RoughDielectric::eval_adjoint);

            #[doc = concat!(" The density of `", stringify!($sample), "` per unit solid angle of `wi` (either")]
            /// hemisphere) for a viewer at `wo` (note the order: wo first); 0 for wo not above the
            /// surface and for η = 1; NaN for a non-finite component or a bad handle.
            $pdf(m: $RD, wo: $Vec3, wi: $Vec3) -> $t =
                dielectric_at(m, wo.into(), wi.into(), |m, wo, wi| m.pdf(wo, wi));
        }

        /// Samples wi for a viewer at `wo` (above the surface): a visible normal h from
        /// (u0, u1), then reflection about h when `uc` < F(wo·h), refraction through h
        /// otherwise (Walter §5.3 with Heitz 2018's visible normals); u0, u1, uc ∈ [0, 1). For
        /// η = 1 the Dirac −wo (`specular` = 1). Returns `BRDF_STATUS_OK` (sample in `*out`),
        /// `BRDF_STATUS_NULL_POINTER` (`out` null), `BRDF_STATUS_NOT_INITIALISED`,
        /// `BRDF_STATUS_INVALID_ARGUMENT` (a non-finite input, n·wo ≤ 0) or
        /// `BRDF_STATUS_NO_SAMPLE` (the sampler found none, e.g. n·wo below 2^−63 in f32,
        /// 2^−511 in f64); `*out` is written only on success.
        #[cfg_attr(not(brdf_header), doc = crate::safety!(sample))]
        #[no_mangle]
        pub unsafe extern "C" fn $sample(
            m: *const $RD,
            wo: $Vec3,
            u0: $t,
            u1: $t,
            uc: $t,
            out: *mut $Sample,
        ) -> BrdfStatus {
            // SAFETY: `m` is null or a readable handle (the caller's contract).
            let m = unsafe { $RD::get(m) };
            // SAFETY: `out` is null or valid for writes (the caller's contract).
            unsafe { put_result(out, || dielectric_sample(m, wo.into(), [u0, u1], uc)) }
        }

        /// The Dirac part for a viewer at `wo`: for η = 1 (an index-matched, invisible interface)
        /// and wo above the surface the straight-through −wo with transmittance 1 and
        /// probability 1; otherwise all zero (prob 0). Returns `BRDF_STATUS_OK`,
        /// `BRDF_STATUS_NULL_POINTER`, `BRDF_STATUS_NOT_INITIALISED` or
        /// `BRDF_STATUS_INVALID_ARGUMENT` (a non-finite component); `*out` is written only on
        /// success.
        #[cfg_attr(not(brdf_header), doc = crate::safety!(sample))]
        #[no_mangle]
        pub unsafe extern "C" fn $delta(m: *const $RD, wo: $Vec3, out: *mut $Delta) -> BrdfStatus {
            // SAFETY: `m` is null or a readable handle (the caller's contract).
            let m = unsafe { $RD::get(m) };
            // SAFETY: `out` is null or valid for writes (the caller's contract).
            unsafe { put_result(out, || dielectric_delta(m, wo.into())) }
        }
    };
}

/// Instantiates every typed export for the scalar type `$t` (`f32` or `f64`): the C names
/// are the base names with the suffix `_f32`/`_f64` (types: `F32`/`F64`), built here once so
/// the two instantiations cannot drift apart.
macro_rules! scalar_abi {
    ($t:ident) => {
        paste::paste! {
            typed_abi! {
                $t; [<BrdfGTerms $t:upper>], [<BrdfVec3 $t:upper>], [<BrdfRgb $t:upper>];
                [<BrdfModifiedG $t:upper>], [<BrdfTorranceSparrow $t:upper>], [<BrdfGgx $t:upper>];
                [<brdf_modified_g_init_ $t>], [<brdf_modified_g_terms_ $t>],
                [<brdf_modified_g_ $t>], [<brdf_modified_g_terms_dots_ $t>],
                [<brdf_modified_g_dots_ $t>], [<brdf_modified_g_dots_batch_ $t>],
                [<brdf_g_blinn_ $t>], [<brdf_g_blinn_dots_ $t>], [<brdf_g1_smith_ $t>],
                [<brdf_g_smith_ $t>], [<brdf_torrance_sparrow_init_ $t>],
                [<brdf_torrance_sparrow_eval_ $t>], [<brdf_torrance_sparrow_eval_nh_ $t>],
                [<brdf_torrance_sparrow_specular_ $t>], [<brdf_torrance_sparrow_eval_batch_ $t>],
                [<brdf_torrance_sparrow_albedo_ $t>], [<brdf_ggx_init_ $t>],
                [<brdf_ggx_eval_ $t>], [<brdf_ggx_albedo_ $t>],
            }
        }
    };
    (@sheen $t:ident) => {
        paste::paste! {
            sheen_abi! {
                $t; [<BrdfVec3 $t:upper>], [<BrdfRgb $t:upper>];
                [<BrdfSheen $t:upper>];
                [<brdf_sheen_init_ $t>], [<brdf_sheen_eval_ $t>], [<brdf_sheen_eval_dots_ $t>],
                [<brdf_sheen_albedo_ $t>],
            }
        }
    };
    (@rough_dielectric $t:ident) => {
        paste::paste! {
            rough_dielectric_abi! {
                $t; [<BrdfVec3 $t:upper>], [<BrdfRgb $t:upper>];
                [<BrdfRoughDielectric $t:upper>],
                [<BrdfBsdfSample $t:upper>], [<BrdfDeltaLobe $t:upper>];
                [<brdf_rough_dielectric_init_ $t>], [<brdf_rough_dielectric_eval_ $t>],
                [<brdf_rough_dielectric_eval_adjoint_ $t>], [<brdf_rough_dielectric_pdf_ $t>],
                [<brdf_rough_dielectric_sample_ $t>], [<brdf_rough_dielectric_delta_ $t>],
            }
        }
    };
}

// The header lists the items in this order: each family's f32 half, then its f64 half.
scalar_abi!(f32);
scalar_abi!(f64);
scalar_abi!(@sheen f32);
scalar_abi!(@sheen f64);
scalar_abi!(@rough_dielectric f32);
scalar_abi!(@rough_dielectric f64);

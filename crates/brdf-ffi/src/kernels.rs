//! Kernel exports: the modified G, Blinn's and Smith's G, the Torrance–Sparrow and GGX
//! BRDFs and their directional albedo, each in `f32` and `f64` (one generic brdf-core source,
//! two instantiations; the two blocks below differ only in the scalar type).
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
    handle, rd, wr, BrdfStatus, BRDF_STATUS_INVALID_ARGUMENT, BRDF_STATUS_NOT_INITIALISED,
    BRDF_STATUS_NULL_POINTER, BRDF_STATUS_OK,
};
use brdf_core::albedo::directional_albedo;
use brdf_core::fresnel::Fresnel;
use brdf_core::masking::{self, Convention, ModifiedG};
use brdf_core::models::{
    Brdf, BrdfFlags, BrdfSample, GeometricTerm, Ggx, LobeHint, MicrofacetSampling, Rgb, SmithForm,
    TorranceSparrow,
};
use brdf_core::{Dots, Real, Vec3};

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
pub const BRDF_GEOMETRIC_NONE: BrdfGeometricTerm = 0;
/// Blinn's V-groove G (paper eq 4).
pub const BRDF_GEOMETRIC_BLINN: BrdfGeometricTerm = 1;
/// Smith–Beckmann, separable, m = √2σ.
pub const BRDF_GEOMETRIC_SMITH_SEPARABLE: BrdfGeometricTerm = 2;
/// Smith–Beckmann, height-correlated, m = √2σ.
pub const BRDF_GEOMETRIC_SMITH_CORRELATED: BrdfGeometricTerm = 3;
/// The paper's modified G, reciprocal convention.
pub const BRDF_GEOMETRIC_MODIFIED: BrdfGeometricTerm = 4;
/// The paper's modified G with eq 12 as printed.
pub const BRDF_GEOMETRIC_MODIFIED_PRINTED: BrdfGeometricTerm = 5;

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

/// Storage words (8 bytes each) of the modified-G handles.
pub const BRDF_MODIFIED_G_WORDS: usize = 8;
/// Storage words (8 bytes each) of the Torrance–Sparrow handles.
pub const BRDF_TORRANCE_SPARROW_WORDS: usize = 16;
/// Storage words (8 bytes each) of the GGX handles.
pub const BRDF_GGX_WORDS: usize = 8;

const TAG_MODIFIED_G_F32: u64 = 0x4252_4446_4d47_3332;
const TAG_MODIFIED_G_F64: u64 = 0x4252_4446_4d47_3634;
const TAG_TS_F32: u64 = 0x4252_4446_5453_3332;
const TAG_TS_F64: u64 = 0x4252_4446_5453_3634;
const TAG_GGX_F32: u64 = 0x4252_4446_4758_3332;
const TAG_GGX_F64: u64 = 0x4252_4446_4758_3634;

fn convention(c: BrdfConvention) -> Option<Convention> {
    match c {
        BRDF_CONVENTION_RECIPROCAL => Some(Convention::Reciprocal),
        BRDF_CONVENTION_PRINTED => Some(Convention::Printed),
        _ => None,
    }
}

fn geometric_term(g: BrdfGeometricTerm) -> Option<GeometricTerm> {
    Some(match g {
        BRDF_GEOMETRIC_NONE => GeometricTerm::None,
        BRDF_GEOMETRIC_BLINN => GeometricTerm::Blinn,
        BRDF_GEOMETRIC_SMITH_SEPARABLE => GeometricTerm::SmithSeparable,
        BRDF_GEOMETRIC_SMITH_CORRELATED => GeometricTerm::SmithCorrelated,
        BRDF_GEOMETRIC_MODIFIED => GeometricTerm::Modified,
        BRDF_GEOMETRIC_MODIFIED_PRINTED => GeometricTerm::ModifiedPrinted,
        _ => return None,
    })
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

fn g1_smith<T: Real>(d: BrdfSmithDistribution, cos_t: T, r: T) -> T {
    if !rough_ok(r) {
        return T::NAN;
    }
    match d {
        BRDF_SMITH_BECKMANN => masking::g1_smith_beckmann(cos_t, r),
        BRDF_SMITH_GGX => masking::g1_smith_ggx(cos_t, r),
        _ => T::NAN,
    }
}

fn g_smith<T: Real>(d: BrdfSmithDistribution, f: BrdfSmithForm, ci: T, co: T, r: T) -> T {
    if !rough_ok(r) {
        return T::NAN;
    }
    match (d, f) {
        (BRDF_SMITH_BECKMANN, BRDF_SMITH_FORM_SEPARABLE) => {
            masking::g_smith_beckmann_separable(ci, co, r)
        }
        (BRDF_SMITH_BECKMANN, BRDF_SMITH_FORM_CORRELATED) => {
            masking::g_smith_beckmann_correlated(ci, co, r)
        }
        (BRDF_SMITH_GGX, BRDF_SMITH_FORM_SEPARABLE) => masking::g_smith_ggx_separable(ci, co, r),
        (BRDF_SMITH_GGX, BRDF_SMITH_FORM_CORRELATED) => masking::g_smith_ggx_correlated(ci, co, r),
        _ => T::NAN,
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

fn ts_albedo<T: Real>(ts: &TorranceSparrow<T>, mu: T) -> T {
    match wo_of_mu(mu) {
        None => T::NAN,
        Some(None) => T::ZERO,
        Some(Some(wo)) => directional_albedo(&TsLobe(ts), wo).r,
    }
}

fn ggx_new<T: Real>(f0: Rgb<T>, alpha: T, form: BrdfSmithForm) -> Result<Ggx<T>, BrdfStatus> {
    let form = smith_form(form).ok_or(BRDF_STATUS_INVALID_ARGUMENT)?;
    Ggx::new(f0, alpha, form, MicrofacetSampling::VisibleNormals)
        .map_err(|_| BRDF_STATUS_INVALID_ARGUMENT)
}

fn ggx_albedo<T: Real>(g: &Ggx<T>, mu: T) -> Rgb<T> {
    match wo_of_mu(mu) {
        None => Rgb::splat(T::NAN),
        Some(None) => Rgb::zero(),
        Some(Some(wo)) => directional_albedo(g, wo),
    }
}

fn finite3<T: Real>(a: T, b: T, c: T) -> bool {
    a.is_finite() && b.is_finite() && c.is_finite()
}

// ---------------------------------------------------------------------------------------
// f32

/// GM, GS and G = min(GM, GS) of the modified G (paper eqs 11–13), each in [0, 1]; all NaN
/// for bad input.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfGTermsF32 {
    /// Masking, the viewing side (eq 11).
    pub gm: f32,
    /// Shadowing, the light's side (eq 12).
    pub gs: f32,
    /// G = min(GM, GS) (eq 13).
    pub g: f32,
}

/// A 3-vector in the local shading frame (z = normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfVec3F32 {
    /// x (tangent).
    pub x: f32,
    /// y (bitangent).
    pub y: f32,
    /// z (normal).
    pub z: f32,
}

/// An RGB triple (per-channel values, e.g. a BRDF in 1/sr or a reflectance).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfRgbF32 {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
}

/// A prepared modified G for one surface (σ, convention). Fill it with
/// `brdf_modified_g_init_f32`; the fields are private to the library.
#[repr(C)]
pub struct BrdfModifiedGF32 {
    tag: u64,
    storage: [u64; BRDF_MODIFIED_G_WORDS],
}
handle!(BrdfModifiedGF32, ModifiedG<f32>, TAG_MODIFIED_G_F32);

/// A prepared Torrance–Sparrow BRDF. Fill it with `brdf_torrance_sparrow_init_f32`; the
/// fields are private to the library.
#[repr(C)]
pub struct BrdfTorranceSparrowF32 {
    tag: u64,
    storage: [u64; BRDF_TORRANCE_SPARROW_WORDS],
}
handle!(BrdfTorranceSparrowF32, TorranceSparrow<f32>, TAG_TS_F32);

/// A prepared GGX BRDF. Fill it with `brdf_ggx_init_f32`; the fields are private to the
/// library.
#[repr(C)]
pub struct BrdfGgxF32 {
    tag: u64,
    storage: [u64; BRDF_GGX_WORDS],
}
handle!(BrdfGgxF32, Ggx<f32>, TAG_GGX_F32);

const NAN_TERMS_F32: BrdfGTermsF32 = BrdfGTermsF32 {
    gm: f32::NAN,
    gs: f32::NAN,
    g: f32::NAN,
};

fn terms_f32(t: masking::GTerms<f32>) -> BrdfGTermsF32 {
    BrdfGTermsF32 {
        gm: t.gm,
        gs: t.gs,
        g: t.g,
    }
}

/// Prepares the modified G of the 2015 Acta Physica Sinica paper (eqs 6–13) for RMS slope
/// `sigma` (finite, > 0; accuracy specified for σ ∈ [0.05, 1]) and `convention`
/// (`BRDF_CONVENTION_*`). Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` (`out` null)
/// or `BRDF_STATUS_INVALID_ARGUMENT` (σ NaN, infinite or ≤ 0, unknown convention); on error
/// `*out` is left not initialised.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_init_f32(
    out: *mut BrdfModifiedGF32,
    sigma: f32,
    convention: BrdfConvention,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    BrdfModifiedGF32::clear(out);
    match modified_new(sigma, convention) {
        Ok(g) => {
            BrdfModifiedGF32::put(out, g);
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// GM, GS and G from the paper's in-plane angles in radians: θi ∈ [0, π/2], θr ∈ [−π/2, π/2]
/// signed (out-of-range and infinite angles are clamped to those ranges). NaN angles, a null
/// or uninitialised handle give all NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_terms_f32(
    g: *const BrdfModifiedGF32,
    theta_i: f32,
    theta_r: f32,
) -> BrdfGTermsF32 {
    match BrdfModifiedGF32::get(g) {
        Some(m) => terms_f32(m.terms(theta_i, theta_r)),
        None => NAN_TERMS_F32,
    }
}

/// G = min(GM, GS) ∈ [0, 1] from in-plane angles; see `brdf_modified_g_terms_f32` (NaN for
/// NaN angles or a bad handle).
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_f32(
    g: *const BrdfModifiedGF32,
    theta_i: f32,
    theta_r: f32,
) -> f32 {
    brdf_modified_g_terms_f32(g, theta_i, theta_r).g
}

/// GM, GS and G from the dot products n·wi, n·wo, wi·wo of unit vectors (the reciprocal
/// 3-D extension; with the printed convention the pair is folded into its plane). A direction
/// at or below the horizon (n·w ≤ 0) gives 0; a non-finite dot product, a null or
/// uninitialised handle give all NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_terms_dots_f32(
    g: *const BrdfModifiedGF32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
) -> BrdfGTermsF32 {
    match BrdfModifiedGF32::get(g) {
        Some(m) if finite3(n_i, n_o, i_o) => terms_f32(m.terms_dots(Dots::new(n_i, n_o, i_o))),
        _ => NAN_TERMS_F32,
    }
}

/// G ∈ [0, 1] from dot products; see `brdf_modified_g_terms_dots_f32`.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_dots_f32(
    g: *const BrdfModifiedGF32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
) -> f32 {
    brdf_modified_g_terms_dots_f32(g, n_i, n_o, i_o).g
}

/// `out[k] = brdf_modified_g_dots_f32(g, n_i[k], n_o[k], i_o[k])` for k < n. Returns
/// `BRDF_STATUS_NOT_INITIALISED` (bad handle; nothing written), `BRDF_STATUS_NULL_POINTER`
/// (an array null with n > 0; nothing written), `BRDF_STATUS_BAD_LENGTH` (n too large) or
/// `BRDF_STATUS_OK`. `out` may alias an input.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_dots_batch_f32(
    g: *const BrdfModifiedGF32,
    n_i: *const f32,
    n_o: *const f32,
    i_o: *const f32,
    out: *mut f32,
    n: usize,
) -> BrdfStatus {
    let Some(m) = BrdfModifiedGF32::get(g) else {
        return BRDF_STATUS_NOT_INITIALISED;
    };
    let s = crate::check_arrays(
        &[n_i.is_null(), n_o.is_null(), i_o.is_null(), out.is_null()],
        n,
        4,
    );
    if s != BRDF_STATUS_OK {
        return s;
    }
    for k in 0..n {
        let (a, b, c) = (rd(n_i, k), rd(n_o, k), rd(i_o, k));
        let v = if finite3(a, b, c) {
            m.g_dots(Dots::new(a, b, c))
        } else {
            f32::NAN
        };
        wr(out, k, v);
    }
    BRDF_STATUS_OK
}

/// Blinn's V-groove G (paper eq 4) ∈ [0, 1] from in-plane angles in radians (clamped like
/// `brdf_modified_g_terms_f32`); NaN in, NaN out.
#[no_mangle]
pub extern "C" fn brdf_g_blinn_f32(theta_i: f32, theta_r: f32) -> f32 {
    masking::g_blinn(theta_i, theta_r)
}

/// Blinn's V-groove G ∈ [0, 1] from n·wi, n·wo, wi·wo of unit vectors; 0 when a direction is
/// at or below the horizon; NaN when a dot product is not finite.
#[no_mangle]
pub extern "C" fn brdf_g_blinn_dots_f32(n_i: f32, n_o: f32, i_o: f32) -> f32 {
    if !finite3(n_i, n_o, i_o) {
        return f32::NAN;
    }
    masking::g_blinn_dots(Dots::new(n_i, n_o, i_o))
}

/// One-sided Smith masking G1 = 1/(1 + Λ) ∈ [0, 1] at cos θ = n·w (≤ 0 gives 0), for
/// `distribution` (`BRDF_SMITH_BECKMANN` with Beckmann m, `BRDF_SMITH_GGX` with α as
/// `roughness`). NaN for NaN cos θ, roughness NaN, infinite or ≤ 0, or an unknown
/// distribution.
#[no_mangle]
pub extern "C" fn brdf_g1_smith_f32(
    distribution: BrdfSmithDistribution,
    cos_theta: f32,
    roughness: f32,
) -> f32 {
    g1_smith(distribution, cos_theta, roughness)
}

/// Smith's G ∈ [0, 1] for the pair n·wi = `cos_i`, n·wo = `cos_o` (either ≤ 0 gives 0), in
/// `form` (`BRDF_SMITH_FORM_*`); `distribution` and `roughness` as for `brdf_g1_smith_f32`.
/// NaN for NaN input, bad roughness or an unknown distribution or form.
#[no_mangle]
pub extern "C" fn brdf_g_smith_f32(
    distribution: BrdfSmithDistribution,
    form: BrdfSmithForm,
    cos_i: f32,
    cos_o: f32,
    roughness: f32,
) -> f32 {
    g_smith(distribution, form, cos_i, cos_o, roughness)
}

/// Prepares the Torrance–Sparrow BRDF of the paper (eq 3):
/// f = k_s D F G / (4 (n·wi)(n·wo)) + ρ_d/π, D Beckmann with m = √2σ, F chosen by `fresnel`
/// (`BRDF_FRESNEL_*`) with parameter `fresnel_param` (R0 ∈ [0, 1] or η > 0; ignored for
/// `BRDF_FRESNEL_ONE`), G by `g_term` (`BRDF_GEOMETRIC_*`). σ finite > 0, k_s ∈ [0, ∞)
/// finite, ρ_d = `albedo` ∈ [0, 1]. Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` or
/// `BRDF_STATUS_INVALID_ARGUMENT` (any parameter out of range, NaN, infinite, or an unknown
/// choice); on error `*out` is left not initialised.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_init_f32(
    out: *mut BrdfTorranceSparrowF32,
    sigma: f32,
    g_term: BrdfGeometricTerm,
    fresnel: BrdfFresnel,
    fresnel_param: f32,
    ks: f32,
    albedo: f32,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    BrdfTorranceSparrowF32::clear(out);
    match ts_new(sigma, g_term, fresnel, fresnel_param, ks, albedo) {
        Ok(t) => {
            BrdfTorranceSparrowF32::put(out, t);
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// The Torrance–Sparrow BRDF in 1/sr (specular + ρ_d/π) from n·wi, n·wo, wi·wo of unit
/// vectors; 0 when a direction is at or below the horizon; NaN for a non-finite dot product
/// or a null or uninitialised handle.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_eval_f32(
    ts: *const BrdfTorranceSparrowF32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
) -> f32 {
    match BrdfTorranceSparrowF32::get(ts) {
        Some(t) if finite3(n_i, n_o, i_o) => t.eval_dots(Dots::new(n_i, n_o, i_o)),
        _ => f32::NAN,
    }
}

/// `brdf_torrance_sparrow_eval_f32` with n·h as well, h = normalize(wi + wo) as a shader
/// has it. Exact where the three dot products alone are not: for a near-mirror pair near
/// the horizon 2 + 2 wi·wo cancels, and |wi + wo| (hence h, D and the BRDF) is then
/// recovered from n·h instead (`Dots::with_n_h`). Bad input as for
/// `brdf_torrance_sparrow_eval_f32`; a non-finite n·h gives NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_eval_nh_f32(
    ts: *const BrdfTorranceSparrowF32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
    n_h: f32,
) -> f32 {
    match BrdfTorranceSparrowF32::get(ts) {
        Some(t) if finite3(n_i, n_o, i_o) && n_h.is_finite() => {
            t.eval_dots(Dots::with_n_h(n_i, n_o, i_o, n_h))
        }
        _ => f32::NAN,
    }
}

/// The specular lobe k_s D F G / (4 (n·wi)(n·wo)) alone, in 1/sr; bad input as for
/// `brdf_torrance_sparrow_eval_f32`.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_specular_f32(
    ts: *const BrdfTorranceSparrowF32,
    n_i: f32,
    n_o: f32,
    i_o: f32,
) -> f32 {
    match BrdfTorranceSparrowF32::get(ts) {
        Some(t) if finite3(n_i, n_o, i_o) => t.eval_specular(Dots::new(n_i, n_o, i_o)),
        _ => f32::NAN,
    }
}

/// `out[k] = brdf_torrance_sparrow_eval_f32(ts, n_i[k], n_o[k], i_o[k])` for k < n; status
/// codes as for `brdf_modified_g_dots_batch_f32`.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_eval_batch_f32(
    ts: *const BrdfTorranceSparrowF32,
    n_i: *const f32,
    n_o: *const f32,
    i_o: *const f32,
    out: *mut f32,
    n: usize,
) -> BrdfStatus {
    if BrdfTorranceSparrowF32::get(ts).is_none() {
        return BRDF_STATUS_NOT_INITIALISED;
    }
    let s = crate::check_arrays(
        &[n_i.is_null(), n_o.is_null(), i_o.is_null(), out.is_null()],
        n,
        4,
    );
    if s != BRDF_STATUS_OK {
        return s;
    }
    for k in 0..n {
        let v = brdf_torrance_sparrow_eval_f32(ts, rd(n_i, k), rd(n_o, k), rd(i_o, k));
        wr(out, k, v);
    }
    BRDF_STATUS_OK
}

/// Directional albedo R(μ) = ∫ f cos θi dωi over the upper hemisphere (including ρ_d), for
/// a viewer at μ = n·wo ∈ (0, 1] (values above 1 count as 1), by brdf-core's fixed
/// quadrature (about 4·10⁵ BRDF evaluations: slow on a microcontroller). μ ≤ 0 gives 0; NaN
/// μ, a null or uninitialised handle give NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_albedo_f32(
    ts: *const BrdfTorranceSparrowF32,
    mu: f32,
) -> f32 {
    match BrdfTorranceSparrowF32::get(ts) {
        Some(t) => ts_albedo(t, mu),
        None => f32::NAN,
    }
}

/// Prepares the GGX (Trowbridge–Reitz) BRDF f = D F G / (4 (n·wi)(n·wo)) with per-channel
/// Schlick F (F0 = `f0`, each in [0, 1]) and Smith masking in `smith_form`
/// (`BRDF_SMITH_FORM_*`); α ∈ [1e-4, 1e4]. Returns `BRDF_STATUS_OK`,
/// `BRDF_STATUS_NULL_POINTER` or `BRDF_STATUS_INVALID_ARGUMENT`; on error `*out` is left not
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn brdf_ggx_init_f32(
    out: *mut BrdfGgxF32,
    f0: BrdfRgbF32,
    alpha: f32,
    smith_form: BrdfSmithForm,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    BrdfGgxF32::clear(out);
    match ggx_new(Rgb::new(f0.r, f0.g, f0.b), alpha, smith_form) {
        Ok(g) => {
            BrdfGgxF32::put(out, g);
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// The GGX BRDF in 1/sr per channel for unit local-frame directions `wi` (toward the light)
/// and `wo` (toward the viewer); not normalised here. 0 when either is at or below the
/// horizon; all NaN for a non-finite component or a null or uninitialised handle.
#[no_mangle]
pub unsafe extern "C" fn brdf_ggx_eval_f32(
    g: *const BrdfGgxF32,
    wi: BrdfVec3F32,
    wo: BrdfVec3F32,
) -> BrdfRgbF32 {
    let nan = BrdfRgbF32 {
        r: f32::NAN,
        g: f32::NAN,
        b: f32::NAN,
    };
    match BrdfGgxF32::get(g) {
        Some(m) if finite3(wi.x, wi.y, wi.z) && finite3(wo.x, wo.y, wo.z) => {
            let c = m.eval(Vec3::new(wi.x, wi.y, wi.z), Vec3::new(wo.x, wo.y, wo.z));
            BrdfRgbF32 {
                r: c.r,
                g: c.g,
                b: c.b,
            }
        }
        _ => nan,
    }
}

/// Directional albedo per channel of the GGX BRDF for a viewer at μ = n·wo; arguments and
/// bad input as for `brdf_torrance_sparrow_albedo_f32`.
#[no_mangle]
pub unsafe extern "C" fn brdf_ggx_albedo_f32(g: *const BrdfGgxF32, mu: f32) -> BrdfRgbF32 {
    let c = match BrdfGgxF32::get(g) {
        Some(m) => ggx_albedo(m, mu),
        None => Rgb::splat(f32::NAN),
    };
    BrdfRgbF32 {
        r: c.r,
        g: c.g,
        b: c.b,
    }
}

// ---------------------------------------------------------------------------------------
// f64 (the f32 block with the scalar type replaced)

/// GM, GS and G = min(GM, GS) of the modified G (paper eqs 11–13), each in [0, 1]; all NaN
/// for bad input.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfGTermsF64 {
    /// Masking, the viewing side (eq 11).
    pub gm: f64,
    /// Shadowing, the light's side (eq 12).
    pub gs: f64,
    /// G = min(GM, GS) (eq 13).
    pub g: f64,
}

/// A 3-vector in the local shading frame (z = normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfVec3F64 {
    /// x (tangent).
    pub x: f64,
    /// y (bitangent).
    pub y: f64,
    /// z (normal).
    pub z: f64,
}

/// An RGB triple (per-channel values, e.g. a BRDF in 1/sr or a reflectance).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfRgbF64 {
    /// Red.
    pub r: f64,
    /// Green.
    pub g: f64,
    /// Blue.
    pub b: f64,
}

/// A prepared modified G for one surface (σ, convention). Fill it with
/// `brdf_modified_g_init_f64`; the fields are private to the library.
#[repr(C)]
pub struct BrdfModifiedGF64 {
    tag: u64,
    storage: [u64; BRDF_MODIFIED_G_WORDS],
}
handle!(BrdfModifiedGF64, ModifiedG<f64>, TAG_MODIFIED_G_F64);

/// A prepared Torrance–Sparrow BRDF. Fill it with `brdf_torrance_sparrow_init_f64`; the
/// fields are private to the library.
#[repr(C)]
pub struct BrdfTorranceSparrowF64 {
    tag: u64,
    storage: [u64; BRDF_TORRANCE_SPARROW_WORDS],
}
handle!(BrdfTorranceSparrowF64, TorranceSparrow<f64>, TAG_TS_F64);

/// A prepared GGX BRDF. Fill it with `brdf_ggx_init_f64`; the fields are private to the
/// library.
#[repr(C)]
pub struct BrdfGgxF64 {
    tag: u64,
    storage: [u64; BRDF_GGX_WORDS],
}
handle!(BrdfGgxF64, Ggx<f64>, TAG_GGX_F64);

const NAN_TERMS_F64: BrdfGTermsF64 = BrdfGTermsF64 {
    gm: f64::NAN,
    gs: f64::NAN,
    g: f64::NAN,
};

fn terms_f64(t: masking::GTerms<f64>) -> BrdfGTermsF64 {
    BrdfGTermsF64 {
        gm: t.gm,
        gs: t.gs,
        g: t.g,
    }
}

/// Prepares the modified G of the 2015 Acta Physica Sinica paper (eqs 6–13) for RMS slope
/// `sigma` (finite, > 0; accuracy specified for σ ∈ [0.05, 1]) and `convention`
/// (`BRDF_CONVENTION_*`). Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` (`out` null)
/// or `BRDF_STATUS_INVALID_ARGUMENT` (σ NaN, infinite or ≤ 0, unknown convention); on error
/// `*out` is left not initialised.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_init_f64(
    out: *mut BrdfModifiedGF64,
    sigma: f64,
    convention: BrdfConvention,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    BrdfModifiedGF64::clear(out);
    match modified_new(sigma, convention) {
        Ok(g) => {
            BrdfModifiedGF64::put(out, g);
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// GM, GS and G from the paper's in-plane angles in radians: θi ∈ [0, π/2], θr ∈ [−π/2, π/2]
/// signed (out-of-range and infinite angles are clamped to those ranges). NaN angles, a null
/// or uninitialised handle give all NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_terms_f64(
    g: *const BrdfModifiedGF64,
    theta_i: f64,
    theta_r: f64,
) -> BrdfGTermsF64 {
    match BrdfModifiedGF64::get(g) {
        Some(m) => terms_f64(m.terms(theta_i, theta_r)),
        None => NAN_TERMS_F64,
    }
}

/// G = min(GM, GS) ∈ [0, 1] from in-plane angles; see `brdf_modified_g_terms_f64` (NaN for
/// NaN angles or a bad handle).
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_f64(
    g: *const BrdfModifiedGF64,
    theta_i: f64,
    theta_r: f64,
) -> f64 {
    brdf_modified_g_terms_f64(g, theta_i, theta_r).g
}

/// GM, GS and G from the dot products n·wi, n·wo, wi·wo of unit vectors (the reciprocal
/// 3-D extension; with the printed convention the pair is folded into its plane). A direction
/// at or below the horizon (n·w ≤ 0) gives 0; a non-finite dot product, a null or
/// uninitialised handle give all NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_terms_dots_f64(
    g: *const BrdfModifiedGF64,
    n_i: f64,
    n_o: f64,
    i_o: f64,
) -> BrdfGTermsF64 {
    match BrdfModifiedGF64::get(g) {
        Some(m) if finite3(n_i, n_o, i_o) => terms_f64(m.terms_dots(Dots::new(n_i, n_o, i_o))),
        _ => NAN_TERMS_F64,
    }
}

/// G ∈ [0, 1] from dot products; see `brdf_modified_g_terms_dots_f64`.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_dots_f64(
    g: *const BrdfModifiedGF64,
    n_i: f64,
    n_o: f64,
    i_o: f64,
) -> f64 {
    brdf_modified_g_terms_dots_f64(g, n_i, n_o, i_o).g
}

/// `out[k] = brdf_modified_g_dots_f64(g, n_i[k], n_o[k], i_o[k])` for k < n. Returns
/// `BRDF_STATUS_NOT_INITIALISED` (bad handle; nothing written), `BRDF_STATUS_NULL_POINTER`
/// (an array null with n > 0; nothing written), `BRDF_STATUS_BAD_LENGTH` (n too large) or
/// `BRDF_STATUS_OK`. `out` may alias an input.
#[no_mangle]
pub unsafe extern "C" fn brdf_modified_g_dots_batch_f64(
    g: *const BrdfModifiedGF64,
    n_i: *const f64,
    n_o: *const f64,
    i_o: *const f64,
    out: *mut f64,
    n: usize,
) -> BrdfStatus {
    let Some(m) = BrdfModifiedGF64::get(g) else {
        return BRDF_STATUS_NOT_INITIALISED;
    };
    let s = crate::check_arrays(
        &[n_i.is_null(), n_o.is_null(), i_o.is_null(), out.is_null()],
        n,
        4,
    );
    if s != BRDF_STATUS_OK {
        return s;
    }
    for k in 0..n {
        let (a, b, c) = (rd(n_i, k), rd(n_o, k), rd(i_o, k));
        let v = if finite3(a, b, c) {
            m.g_dots(Dots::new(a, b, c))
        } else {
            f64::NAN
        };
        wr(out, k, v);
    }
    BRDF_STATUS_OK
}

/// Blinn's V-groove G (paper eq 4) ∈ [0, 1] from in-plane angles in radians (clamped like
/// `brdf_modified_g_terms_f64`); NaN in, NaN out.
#[no_mangle]
pub extern "C" fn brdf_g_blinn_f64(theta_i: f64, theta_r: f64) -> f64 {
    masking::g_blinn(theta_i, theta_r)
}

/// Blinn's V-groove G ∈ [0, 1] from n·wi, n·wo, wi·wo of unit vectors; 0 when a direction is
/// at or below the horizon; NaN when a dot product is not finite.
#[no_mangle]
pub extern "C" fn brdf_g_blinn_dots_f64(n_i: f64, n_o: f64, i_o: f64) -> f64 {
    if !finite3(n_i, n_o, i_o) {
        return f64::NAN;
    }
    masking::g_blinn_dots(Dots::new(n_i, n_o, i_o))
}

/// One-sided Smith masking G1 = 1/(1 + Λ) ∈ [0, 1] at cos θ = n·w (≤ 0 gives 0), for
/// `distribution` (`BRDF_SMITH_BECKMANN` with Beckmann m, `BRDF_SMITH_GGX` with α as
/// `roughness`). NaN for NaN cos θ, roughness NaN, infinite or ≤ 0, or an unknown
/// distribution.
#[no_mangle]
pub extern "C" fn brdf_g1_smith_f64(
    distribution: BrdfSmithDistribution,
    cos_theta: f64,
    roughness: f64,
) -> f64 {
    g1_smith(distribution, cos_theta, roughness)
}

/// Smith's G ∈ [0, 1] for the pair n·wi = `cos_i`, n·wo = `cos_o` (either ≤ 0 gives 0), in
/// `form` (`BRDF_SMITH_FORM_*`); `distribution` and `roughness` as for `brdf_g1_smith_f64`.
/// NaN for NaN input, bad roughness or an unknown distribution or form.
#[no_mangle]
pub extern "C" fn brdf_g_smith_f64(
    distribution: BrdfSmithDistribution,
    form: BrdfSmithForm,
    cos_i: f64,
    cos_o: f64,
    roughness: f64,
) -> f64 {
    g_smith(distribution, form, cos_i, cos_o, roughness)
}

/// Prepares the Torrance–Sparrow BRDF of the paper (eq 3):
/// f = k_s D F G / (4 (n·wi)(n·wo)) + ρ_d/π, D Beckmann with m = √2σ, F chosen by `fresnel`
/// (`BRDF_FRESNEL_*`) with parameter `fresnel_param` (R0 ∈ [0, 1] or η > 0; ignored for
/// `BRDF_FRESNEL_ONE`), G by `g_term` (`BRDF_GEOMETRIC_*`). σ finite > 0, k_s ∈ [0, ∞)
/// finite, ρ_d = `albedo` ∈ [0, 1]. Returns `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` or
/// `BRDF_STATUS_INVALID_ARGUMENT` (any parameter out of range, NaN, infinite, or an unknown
/// choice); on error `*out` is left not initialised.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_init_f64(
    out: *mut BrdfTorranceSparrowF64,
    sigma: f64,
    g_term: BrdfGeometricTerm,
    fresnel: BrdfFresnel,
    fresnel_param: f64,
    ks: f64,
    albedo: f64,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    BrdfTorranceSparrowF64::clear(out);
    match ts_new(sigma, g_term, fresnel, fresnel_param, ks, albedo) {
        Ok(t) => {
            BrdfTorranceSparrowF64::put(out, t);
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// The Torrance–Sparrow BRDF in 1/sr (specular + ρ_d/π) from n·wi, n·wo, wi·wo of unit
/// vectors; 0 when a direction is at or below the horizon; NaN for a non-finite dot product
/// or a null or uninitialised handle.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_eval_f64(
    ts: *const BrdfTorranceSparrowF64,
    n_i: f64,
    n_o: f64,
    i_o: f64,
) -> f64 {
    match BrdfTorranceSparrowF64::get(ts) {
        Some(t) if finite3(n_i, n_o, i_o) => t.eval_dots(Dots::new(n_i, n_o, i_o)),
        _ => f64::NAN,
    }
}

/// `brdf_torrance_sparrow_eval_f64` with n·h as well, h = normalize(wi + wo) as a shader
/// has it. Exact where the three dot products alone are not: for a near-mirror pair near
/// the horizon 2 + 2 wi·wo cancels, and |wi + wo| (hence h, D and the BRDF) is then
/// recovered from n·h instead (`Dots::with_n_h`). Bad input as for
/// `brdf_torrance_sparrow_eval_f64`; a non-finite n·h gives NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_eval_nh_f64(
    ts: *const BrdfTorranceSparrowF64,
    n_i: f64,
    n_o: f64,
    i_o: f64,
    n_h: f64,
) -> f64 {
    match BrdfTorranceSparrowF64::get(ts) {
        Some(t) if finite3(n_i, n_o, i_o) && n_h.is_finite() => {
            t.eval_dots(Dots::with_n_h(n_i, n_o, i_o, n_h))
        }
        _ => f64::NAN,
    }
}

/// The specular lobe k_s D F G / (4 (n·wi)(n·wo)) alone, in 1/sr; bad input as for
/// `brdf_torrance_sparrow_eval_f64`.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_specular_f64(
    ts: *const BrdfTorranceSparrowF64,
    n_i: f64,
    n_o: f64,
    i_o: f64,
) -> f64 {
    match BrdfTorranceSparrowF64::get(ts) {
        Some(t) if finite3(n_i, n_o, i_o) => t.eval_specular(Dots::new(n_i, n_o, i_o)),
        _ => f64::NAN,
    }
}

/// `out[k] = brdf_torrance_sparrow_eval_f64(ts, n_i[k], n_o[k], i_o[k])` for k < n; status
/// codes as for `brdf_modified_g_dots_batch_f64`.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_eval_batch_f64(
    ts: *const BrdfTorranceSparrowF64,
    n_i: *const f64,
    n_o: *const f64,
    i_o: *const f64,
    out: *mut f64,
    n: usize,
) -> BrdfStatus {
    if BrdfTorranceSparrowF64::get(ts).is_none() {
        return BRDF_STATUS_NOT_INITIALISED;
    }
    let s = crate::check_arrays(
        &[n_i.is_null(), n_o.is_null(), i_o.is_null(), out.is_null()],
        n,
        4,
    );
    if s != BRDF_STATUS_OK {
        return s;
    }
    for k in 0..n {
        let v = brdf_torrance_sparrow_eval_f64(ts, rd(n_i, k), rd(n_o, k), rd(i_o, k));
        wr(out, k, v);
    }
    BRDF_STATUS_OK
}

/// Directional albedo R(μ) = ∫ f cos θi dωi over the upper hemisphere (including ρ_d), for
/// a viewer at μ = n·wo ∈ (0, 1] (values above 1 count as 1), by brdf-core's fixed
/// quadrature (about 4·10⁵ BRDF evaluations: slow on a microcontroller). μ ≤ 0 gives 0; NaN
/// μ, a null or uninitialised handle give NaN.
#[no_mangle]
pub unsafe extern "C" fn brdf_torrance_sparrow_albedo_f64(
    ts: *const BrdfTorranceSparrowF64,
    mu: f64,
) -> f64 {
    match BrdfTorranceSparrowF64::get(ts) {
        Some(t) => ts_albedo(t, mu),
        None => f64::NAN,
    }
}

/// Prepares the GGX (Trowbridge–Reitz) BRDF f = D F G / (4 (n·wi)(n·wo)) with per-channel
/// Schlick F (F0 = `f0`, each in [0, 1]) and Smith masking in `smith_form`
/// (`BRDF_SMITH_FORM_*`); α ∈ [1e-4, 1e4]. Returns `BRDF_STATUS_OK`,
/// `BRDF_STATUS_NULL_POINTER` or `BRDF_STATUS_INVALID_ARGUMENT`; on error `*out` is left not
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn brdf_ggx_init_f64(
    out: *mut BrdfGgxF64,
    f0: BrdfRgbF64,
    alpha: f64,
    smith_form: BrdfSmithForm,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    BrdfGgxF64::clear(out);
    match ggx_new(Rgb::new(f0.r, f0.g, f0.b), alpha, smith_form) {
        Ok(g) => {
            BrdfGgxF64::put(out, g);
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// The GGX BRDF in 1/sr per channel for unit local-frame directions `wi` (toward the light)
/// and `wo` (toward the viewer); not normalised here. 0 when either is at or below the
/// horizon; all NaN for a non-finite component or a null or uninitialised handle.
#[no_mangle]
pub unsafe extern "C" fn brdf_ggx_eval_f64(
    g: *const BrdfGgxF64,
    wi: BrdfVec3F64,
    wo: BrdfVec3F64,
) -> BrdfRgbF64 {
    let nan = BrdfRgbF64 {
        r: f64::NAN,
        g: f64::NAN,
        b: f64::NAN,
    };
    match BrdfGgxF64::get(g) {
        Some(m) if finite3(wi.x, wi.y, wi.z) && finite3(wo.x, wo.y, wo.z) => {
            let c = m.eval(Vec3::new(wi.x, wi.y, wi.z), Vec3::new(wo.x, wo.y, wo.z));
            BrdfRgbF64 {
                r: c.r,
                g: c.g,
                b: c.b,
            }
        }
        _ => nan,
    }
}

/// Directional albedo per channel of the GGX BRDF for a viewer at μ = n·wo; arguments and
/// bad input as for `brdf_torrance_sparrow_albedo_f64`.
#[no_mangle]
pub unsafe extern "C" fn brdf_ggx_albedo_f64(g: *const BrdfGgxF64, mu: f64) -> BrdfRgbF64 {
    let c = match BrdfGgxF64::get(g) {
        Some(m) => ggx_albedo(m, mu),
        None => Rgb::splat(f64::NAN),
    };
    BrdfRgbF64 {
        r: c.r,
        g: c.g,
        b: c.b,
    }
}

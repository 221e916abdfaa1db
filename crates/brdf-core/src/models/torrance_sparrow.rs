//! The Torrance–Sparrow specular BRDF of the paper (eq 3, docs/conventions.md §5) with a
//! selectable G and Fresnel term, plus an explicit Lambertian diffuse term.
//!
//! f(wi, wo) = k_s · D(h) F(wi·h) G / (4 cos θi cos θo) + ρ_d/π,
//! D the Beckmann density with α = √2σ ([`crate::microfacet::Beckmann`]).
//!
//! The paper's diffuse term "a/dωi" is garbled in the source; it is modelled here as a
//! Lambertian term with its own albedo ρ_d (default 0).

use super::{above_or_zero, lobe_prob, mixture_pdf, mixture_sample, Brdf, BrdfFlags, BrdfSample};
use super::{LobeHint, Rgb};
use crate::error::{check_range, ParamError};
use crate::fresnel::Fresnel;
use crate::geometry::{half_vector_and_cos, min_cos, Dots, Vec3};
use crate::masking::blinn::g_blinn_cos;
use crate::masking::{Convention, ModifiedG};
use crate::microfacet::{from_cos, Beckmann, Distribution, ALPHA_MAX, ALPHA_MIN};
use crate::quadrature::{DefaultRule, Rule};
use crate::Real;

/// Which geometric attenuation factor the BRDF uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum GeometricTerm {
    /// G = 1.
    None,
    /// Blinn's V-groove G (eq 4).
    Blinn,
    /// Smith–Beckmann, separable.
    SmithSeparable,
    /// Smith–Beckmann, height-correlated.
    SmithCorrelated,
    /// The paper's modified G, reciprocal convention (default).
    #[default]
    Modified,
    /// The paper's modified G with eq 12 as printed.
    ModifiedPrinted,
}

impl GeometricTerm {
    /// Every variant, in a fixed order (for tables and command lines).
    pub const ALL: [GeometricTerm; 6] = [
        GeometricTerm::None,
        GeometricTerm::Blinn,
        GeometricTerm::SmithSeparable,
        GeometricTerm::SmithCorrelated,
        GeometricTerm::Modified,
        GeometricTerm::ModifiedPrinted,
    ];
    /// Its name in the catalogue ([`crate::catalogue::MASKINGS`]).
    pub const fn name(self) -> &'static str {
        crate::catalogue::MASKINGS[self as usize].name
    }
    /// Parses a name or other spelling of the catalogue ([`crate::catalogue::find_masking`]).
    pub fn from_name(s: &str) -> Option<Self> {
        crate::catalogue::find_masking(s).map(|m| m.term)
    }
}

/// Torrance–Sparrow BRDF for one surface: the Beckmann distribution
/// ([`crate::microfacet::Beckmann`], α = √2σ) composed with a [`GeometricTerm`] and a
/// [`Fresnel`] term.
#[derive(Clone, Copy, Debug)]
pub struct TorranceSparrow<T, R = DefaultRule> {
    dist: Beckmann<T>,
    g_term: GeometricTerm,
    modified: ModifiedG<T, R>,
    fresnel: Fresnel<T>,
    ks: T,
    albedo: T,
}

impl<T: Real, R: Rule> TorranceSparrow<T, R> {
    /// Checked constructor: RMS slope σ with α = √2σ ∈ [1e-4, 1e4] (σ ∈ [7.07e-5, 7.07e3];
    /// outside that range D at the mirror direction leaves the range of `f32`/`f64` or tends
    /// to a delta, so such σ is a typed error), the G to use, a Fresnel term, specular scale
    /// k_s ∈ [0, ∞) and Lambertian albedo ρ_d ∈ [0, 1].
    pub fn new(
        sigma: T,
        g_term: GeometricTerm,
        fresnel: Fresnel<T>,
        ks: T,
        albedo: T,
    ) -> Result<Self, ParamError> {
        use crate::roughness::sigma_from_beckmann_m as sigma_of;
        let sigma = check_range(
            "sigma",
            sigma,
            T::from_f64(sigma_of(ALPHA_MIN)),
            false,
            T::from_f64(sigma_of(ALPHA_MAX)),
            "[7.07e-5, 7.07e3] (alpha = sqrt2 sigma in [1e-4, 1e4])",
        )?;
        Self::build(
            sigma,
            crate::roughness::beckmann_m_from_sigma(sigma),
            g_term,
            fresnel,
            ks,
            albedo,
        )
    }
    /// Checked constructor from the Beckmann width α = √2σ ∈ [1e-4, 1e4] (the crate's
    /// roughness convention), otherwise as [`TorranceSparrow::new`].
    pub fn from_alpha(
        alpha: T,
        g_term: GeometricTerm,
        fresnel: Fresnel<T>,
        ks: T,
        albedo: T,
    ) -> Result<Self, ParamError> {
        let alpha = crate::microfacet::check_alpha("alpha", alpha)?;
        let sigma = crate::roughness::sigma_from_beckmann_m(alpha);
        Self::build(sigma, alpha, g_term, fresnel, ks, albedo)
    }
    fn build(
        sigma: T,
        alpha: T,
        g_term: GeometricTerm,
        fresnel: Fresnel<T>,
        ks: T,
        albedo: T,
    ) -> Result<Self, ParamError> {
        let modified = ModifiedG::new(sigma)?.with_convention(match g_term {
            GeometricTerm::ModifiedPrinted => Convention::Printed,
            _ => Convention::Reciprocal,
        });
        let ks = check_range("ks", ks, T::ZERO, false, T::INFINITY, "[0, ∞)")?;
        let albedo = check_range("albedo", albedo, T::ZERO, false, T::ONE, "[0, 1]")?;
        Ok(Self {
            dist: Beckmann::clamped(alpha, alpha),
            g_term,
            modified,
            fresnel,
            ks,
            albedo,
        })
    }
    /// Specular only, F = 1, k_s = 1, no diffuse: the form the paper plots.
    pub fn specular(sigma: T, g_term: GeometricTerm) -> Result<Self, ParamError> {
        Self::new(sigma, g_term, Fresnel::One, T::ONE, T::ZERO)
    }
    /// The geometric term in use.
    pub fn g_term(&self) -> GeometricTerm {
        self.g_term
    }
    /// The Beckmann roughness m = α = √2σ.
    pub fn beckmann_m(&self) -> T {
        self.dist.alpha().0
    }
    /// The distribution of normals.
    pub fn distribution(&self) -> Beckmann<T> {
        self.dist
    }
    /// The Lambertian albedo ρ_d.
    pub fn diffuse_albedo(&self) -> T {
        self.albedo
    }
    /// The specular scale k_s.
    pub fn ks(&self) -> T {
        self.ks
    }
    /// The Fresnel term.
    pub fn fresnel(&self) -> Fresnel<T> {
        self.fresnel
    }
    /// The selected G for a pair given by its dot products.
    pub fn g(&self, d: Dots<T>) -> T {
        self.g_parts(d, d.n_h(), d.i_h(), from_cos(d.n_i), from_cos(d.n_o))
    }
    fn g_parts(&self, d: Dots<T>, n_h: T, i_h: T, wi: Vec3<T>, wo: Vec3<T>) -> T {
        match self.g_term {
            GeometricTerm::None => T::ONE,
            GeometricTerm::Blinn => g_blinn_cos(n_h, d.n_i, d.n_o, i_h),
            GeometricTerm::SmithSeparable => self.dist.g_separable(wi, wo),
            GeometricTerm::SmithCorrelated => self.dist.g_correlated(wi, wo),
            GeometricTerm::Modified | GeometricTerm::ModifiedPrinted => self.modified.g_dots(d),
        }
    }
    /// D F G/(4 cos θi cos θo) from the pair's dots, its unit half vector h and wi·h. Kept
    /// out of line: both entry points share it (the modified G inside is large), which keeps
    /// the WASM module and the firmware within their size budgets.
    #[inline(never)]
    fn specular_parts(&self, d: Dots<T>, h: Vec3<T>, i_h: T, wi: Vec3<T>, wo: Vec3<T>) -> T {
        let dval = self.dist.d(h);
        if dval == T::ZERO {
            return T::ZERO;
        }
        let f = self.fresnel.eval(i_h);
        let g = self.g_parts(d, h.z, i_h, wi, wo);
        self.ks * dval * f * g / (T::from_f64(4.0) * d.n_i * d.n_o)
    }
    /// The specular lobe D F G / (4 cos θi cos θo) alone, in 1/sr, from dot products, with
    /// the half vector from [`Dots::half_vector_iso`] and wi·h from [`Dots::i_h`]. Its
    /// precision is that of `d`'s |H_t|² ([`Dots::ht2`]): exact to rounding, also for
    /// mirror pairs at the horizon, when `d` comes from the vectors ([`Dots::from_local`],
    /// [`Dots::from_vectors`]) or the angles ([`Dots::in_plane`]); with a shader's n·h
    /// ([`Dots::with_n_h`]) the exponent of D carries an absolute error of a few ε/α²
    /// (measured 2e-13 in f64 and 1e-4 in f32 at α = 0.05); from the three dots alone
    /// ([`Dots::new`]) near-mirror pairs near the horizon lose about ε/(α²(cos θi +
    /// cos θo)²) (measured 7e-8 at cos θ = 1e-3 and 9e-2 at 1e-6 in f64, α = 0.05). 0 when
    /// either cosine is below [`crate::geometry::min_cos`] (at or below the horizon, or
    /// subnormal).
    pub fn eval_specular(&self, d: Dots<T>) -> T {
        if d.n_i.is_nan() || d.n_o.is_nan() || d.i_o.is_nan() {
            return T::NAN;
        }
        if !(d.n_i >= min_cos()) || !(d.n_o >= min_cos()) {
            return T::ZERO;
        }
        self.specular_parts(
            d,
            d.half_vector_iso(),
            d.i_h(),
            from_cos(d.n_i),
            from_cos(d.n_o),
        )
    }
    /// The specular lobe for unit local-frame directions, with the half vector taken from
    /// the vectors: exact to rounding also for mirror pairs at the horizon.
    pub fn eval_specular_local(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        let d = Dots::from_local(wi, wo);
        if d.n_i.is_nan() || d.n_o.is_nan() || d.i_o.is_nan() {
            return T::NAN;
        }
        if !(d.n_i >= min_cos()) || !(d.n_o >= min_cos()) {
            return T::ZERO;
        }
        let Some((h, i_h)) = half_vector_and_cos(wi, wo) else {
            return T::ZERO;
        };
        self.specular_parts(d, h, i_h, wi, wo)
    }
    /// The full BRDF from dot products (shader form), in 1/sr; precision as
    /// [`TorranceSparrow::eval_specular`]. 0 when either direction is at or below the
    /// horizon; NaN in, NaN out.
    pub fn eval_dots(&self, d: Dots<T>) -> T {
        let s = self.eval_specular(d);
        if !(d.n_i >= min_cos()) || !(d.n_o >= min_cos()) {
            return s;
        }
        s + self.albedo / T::PI
    }
    /// The full BRDF for unit local-frame directions (z = normal), half vector from the
    /// vectors.
    pub fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        let s = self.eval_specular_local(wi, wo);
        if !(wi.z >= min_cos()) || !(wo.z >= min_cos()) {
            return s;
        }
        s + self.albedo / T::PI
    }
    /// The full BRDF from the paper's in-plane angles (radians, θr signed).
    pub fn eval_in_plane(&self, theta_i: T, theta_r: T) -> T {
        self.eval_dots(Dots::in_plane(theta_i, theta_r))
    }
}

/// Torrance–Sparrow as a [`Brdf`]: reciprocal unless the paper's printed G is chosen;
/// energy conserving (flag) when G is the V-groove G or a Smith G and k_s + ρ_d ≤ 1 (a
/// single-scattering microsurface model; every [`Fresnel`] here is ≤ 1); sampled by Beckmann visible normals
/// with probability k_s/(k_s + ρ_d), else the cosine-weighted hemisphere.
impl<T: Real, R: Rule> Brdf<T> for TorranceSparrow<T, R> {
    fn flags(&self) -> BrdfFlags {
        BrdfFlags {
            reciprocal: self.g_term != GeometricTerm::ModifiedPrinted,
            energy_conserving: matches!(
                self.g_term,
                GeometricTerm::Blinn
                    | GeometricTerm::SmithSeparable
                    | GeometricTerm::SmithCorrelated
            ) && self.ks + self.albedo <= T::ONE,
            has_delta: false,
        }
    }
    fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> Rgb<T> {
        above_or_zero(wi, wo, || Rgb::splat(TorranceSparrow::eval(self, wi, wo)))
    }
    fn pdf(&self, wo: Vec3<T>, wi: Vec3<T>) -> T {
        mixture_pdf(lobe_prob(self.ks, self.albedo), wo, wi, |h| {
            self.dist.visible_normal_pdf(wo, h)
        })
    }
    fn sample(&self, wo: Vec3<T>, u: [T; 2]) -> Option<BrdfSample<T>> {
        mixture_sample(self, lobe_prob(self.ks, self.albedo), wo, u, |v| {
            self.dist
                .sample_visible_normal(wo, v)
                .unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ZERO))
        })
    }
    fn lobe_hint(&self) -> LobeHint<T> {
        LobeHint::iso(self.beckmann_m())
    }
}

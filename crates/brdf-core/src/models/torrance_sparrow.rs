//! The Torrance–Sparrow specular BRDF of the paper (eq 3, conventions.md §5) with a
//! selectable G and Fresnel term, plus an explicit Lambertian diffuse term.
//!
//! f(wi, wo) = k_s · D(h) F(wi·h) G / (4 cos θi cos θo) + ρ_d/π,
//! D the Beckmann density with m = √2σ ([`crate::distribution::d_beckmann`]).
//!
//! The paper's diffuse term "a/dωi" is garbled in the source; it is modelled here as a
//! Lambertian term with its own albedo ρ_d (default 0).

use crate::distribution::d_beckmann;
use crate::error::{check_range, ParamError};
use crate::fresnel::Fresnel;
use crate::geometry::{Dots, Vec3};
use crate::masking::{
    g_blinn_dots, g_smith_beckmann_correlated, g_smith_beckmann_separable, Convention, ModifiedG,
};
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
    /// Short lower-case name used on command lines.
    pub const fn name(self) -> &'static str {
        match self {
            GeometricTerm::None => "none",
            GeometricTerm::Blinn => "blinn",
            GeometricTerm::SmithSeparable => "smith-separable",
            GeometricTerm::SmithCorrelated => "smith-correlated",
            GeometricTerm::Modified => "modified",
            GeometricTerm::ModifiedPrinted => "modified-printed",
        }
    }
    /// Parses [`GeometricTerm::name`].
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|g| g.name() == s)
    }
}

/// Torrance–Sparrow BRDF for one surface.
#[derive(Clone, Copy, Debug)]
pub struct TorranceSparrow<T, R = DefaultRule> {
    m: T,
    g_term: GeometricTerm,
    modified: ModifiedG<T, R>,
    fresnel: Fresnel<T>,
    ks: T,
    albedo: T,
}

impl<T: Real, R: Rule> TorranceSparrow<T, R> {
    /// Checked constructor: RMS slope σ > 0 (finite), the G to use, a Fresnel term, specular
    /// scale k_s ∈ [0, ∞) and Lambertian albedo ρ_d ∈ [0, 1].
    pub fn new(
        sigma: T,
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
        let m = T::from_f64(core::f64::consts::SQRT_2) * sigma;
        Ok(Self {
            m,
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
    /// The Beckmann roughness m = √2σ.
    pub fn beckmann_m(&self) -> T {
        self.m
    }
    /// The selected G for a pair given by its dot products.
    pub fn g(&self, d: Dots<T>) -> T {
        match self.g_term {
            GeometricTerm::None => T::ONE,
            GeometricTerm::Blinn => g_blinn_dots(d),
            GeometricTerm::SmithSeparable => g_smith_beckmann_separable(d.n_i, d.n_o, self.m),
            GeometricTerm::SmithCorrelated => g_smith_beckmann_correlated(d.n_i, d.n_o, self.m),
            GeometricTerm::Modified | GeometricTerm::ModifiedPrinted => self.modified.g_dots(d),
        }
    }
    /// The specular lobe D F G / (4 cos θi cos θo) alone, in 1/sr.
    pub fn eval_specular(&self, d: Dots<T>) -> T {
        if d.n_i.is_nan() || d.n_o.is_nan() || d.i_o.is_nan() {
            return T::NAN;
        }
        if !(d.n_i > T::ZERO) || !(d.n_o > T::ZERO) {
            return T::ZERO;
        }
        let n_h = d.n_h();
        let dval = d_beckmann(n_h, self.m);
        if dval == T::ZERO {
            return T::ZERO;
        }
        let f = self.fresnel.eval(d.i_h());
        self.ks * dval * f * self.g(d) / (T::from_f64(4.0) * d.n_i * d.n_o)
    }
    /// The full BRDF from dot products (shader form), in 1/sr. 0 when either direction is at
    /// or below the horizon; NaN in, NaN out.
    pub fn eval_dots(&self, d: Dots<T>) -> T {
        let s = self.eval_specular(d);
        if !(d.n_i > T::ZERO) || !(d.n_o > T::ZERO) {
            return s;
        }
        s + self.albedo / T::PI
    }
    /// The full BRDF for unit local-frame directions (z = normal).
    pub fn eval(&self, wi: Vec3<T>, wo: Vec3<T>) -> T {
        self.eval_dots(Dots::from_local(wi, wo))
    }
    /// The full BRDF from the paper's in-plane angles (radians, θr signed).
    pub fn eval_in_plane(&self, theta_i: T, theta_r: T) -> T {
        self.eval_dots(Dots::in_plane(theta_i, theta_r))
    }
}

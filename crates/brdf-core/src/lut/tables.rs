//! Typed wrappers over [`LutView`]: the query each table kind answers, in physical units.

use super::passing::PassingReader;
use super::{LutError, LutView, TableKind};
use crate::masking::Convention;
use core::f32::consts::FRAC_PI_2;

fn expect(view: &LutView<'_>, kind: TableKind, dims: usize) -> Result<(), LutError> {
    if view.kind() != kind || view.dims() != dims {
        return Err(LutError::WrongKind {
            expected: kind,
            found: view.kind(),
        });
    }
    Ok(())
}

/// (GM, GS) arguments of the passing-factor table F(θ, φ) = M(θ, (θ − φ)/2)
/// (conventions.md §4, reciprocal): GM = F(|θr|, sgn θr · θi), GS = F(θi, θr).
#[inline]
fn g_args(theta_i: f32, theta_r: f32) -> ([f32; 2], [f32; 2]) {
    let ti = theta_i.clamp(0.0, FRAC_PI_2);
    let tr = theta_r.clamp(-FRAC_PI_2, FRAC_PI_2);
    let s = if tr < 0.0 { -ti } else { ti };
    ([tr.abs(), s], [ti, tr])
}

/// A G table is a passing-factor table of `dims` axes in the reciprocal convention.
fn expect_g_table(view: &LutView<'_>, dims: usize) -> Result<(), LutError> {
    expect(view, TableKind::PassingFactor, dims)?;
    if view.header().generator.convention != Convention::Reciprocal {
        return Err(LutError::Inconsistent(
            "G tables must use the reciprocal convention",
        ));
    }
    Ok(())
}

#[inline]
fn unit01(x: f32) -> f32 {
    x.clamp(0.0, 1.0)
}

/// The modified G (reciprocal convention) for one fixed σ, from a 2-D passing-factor table.
#[derive(Clone, Debug)]
pub struct GTable<'a> {
    view: LutView<'a>,
    fast: Option<PassingReader>,
}

impl<'a> GTable<'a> {
    /// Parses and checks that the bytes hold a 2-D passing-factor table.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::from_view(LutView::parse(bytes)?)
    }
    /// Wraps a parsed view.
    pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
        expect_g_table(&view, 2)?;
        let fast = PassingReader::new(&view);
        Ok(Self { view, fast })
    }
    /// The underlying view.
    pub fn view(&self) -> &LutView<'a> {
        &self.view
    }
    /// The table's σ (NaN if the header does not say).
    pub fn sigma(&self) -> f32 {
        self.view
            .header()
            .generator
            .sigma
            .map_or(f32::NAN, |s| s as f32)
    }
    /// (GM, GS, G) at in-plane angles in radians, θi ∈ [0, π/2], θr ∈ [−π/2, π/2] signed
    /// (clamped; NaN gives NaN). G = min(GM, GS), each clamped to [0, 1] (paper eq 13).
    pub fn terms(&self, theta_i: f32, theta_r: f32) -> (f32, f32, f32) {
        if theta_i.is_nan() || theta_r.is_nan() {
            return (f32::NAN, f32::NAN, f32::NAN);
        }
        let (m, s) = g_args(theta_i, theta_r);
        let (gm, gs) = match &self.fast {
            Some(f) => f.pair2(self.view.payload(), m, s),
            None => (
                unit01(self.view.sample(&m)[0]),
                unit01(self.view.sample(&s)[0]),
            ),
        };
        (gm, gs, gm.min(gs))
    }
    /// G = min(GM, GS); see [`GTable::terms`].
    pub fn g(&self, theta_i: f32, theta_r: f32) -> f32 {
        self.terms(theta_i, theta_r).2
    }
}

/// The modified G (reciprocal convention) over σ, from a 3-D passing-factor table.
#[derive(Clone, Debug)]
pub struct GTable3<'a> {
    view: LutView<'a>,
    fast: Option<PassingReader>,
}

impl<'a> GTable3<'a> {
    /// Parses and checks that the bytes hold a 3-D passing-factor table.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::from_view(LutView::parse(bytes)?)
    }
    /// Wraps a parsed view.
    pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
        expect_g_table(&view, 3)?;
        let fast = PassingReader::new(&view);
        Ok(Self { view, fast })
    }
    /// The underlying view.
    pub fn view(&self) -> &LutView<'a> {
        &self.view
    }
    /// The σ range [lo, hi] of the table (queries outside are clamped).
    pub fn sigma_range(&self) -> (f32, f32) {
        let a = &self.view.header().axes[2];
        (a.lo as f32, a.hi as f32)
    }
    /// (GM, GS, G) at in-plane angles in radians and RMS slope σ (all clamped to the table's
    /// ranges; NaN gives NaN). G = min(GM, GS) (paper eq 13).
    pub fn terms(&self, theta_i: f32, theta_r: f32, sigma: f32) -> (f32, f32, f32) {
        if theta_i.is_nan() || theta_r.is_nan() || sigma.is_nan() {
            return (f32::NAN, f32::NAN, f32::NAN);
        }
        let (m, s) = g_args(theta_i, theta_r);
        let (gm, gs) = match &self.fast {
            Some(f) => f.pair3(self.view.payload(), m, s, sigma),
            None => (
                unit01(self.view.sample(&[m[0], m[1], sigma])[0]),
                unit01(self.view.sample(&[s[0], s[1], sigma])[0]),
            ),
        };
        (gm, gs, gm.min(gs))
    }
    /// G = min(GM, GS); see [`GTable3::terms`].
    pub fn g(&self, theta_i: f32, theta_r: f32, sigma: f32) -> f32 {
        self.terms(theta_i, theta_r, sigma).2
    }
}

/// Split-sum (A, B) over (μ = n·v, roughness), conventions.md §8.
#[derive(Clone, Debug)]
pub struct DfgTable<'a> {
    view: LutView<'a>,
}

impl<'a> DfgTable<'a> {
    /// Parses and checks that the bytes hold a split-sum table.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::from_view(LutView::parse(bytes)?)
    }
    /// Wraps a parsed view.
    pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
        expect(&view, TableKind::SplitSum, 2)?;
        Ok(Self { view })
    }
    /// The underlying view.
    pub fn view(&self) -> &LutView<'a> {
        &self.view
    }
    /// (A, B) at μ = n·v and roughness (perceptual r for GGX, σ for Torrance–Sparrow tables;
    /// see the header), clamped to the table's ranges; NaN gives NaN.
    /// Specular E = F0·A + F90·B.
    pub fn ab(&self, mu: f32, roughness: f32) -> (f32, f32) {
        let v = self.view.sample2(mu, roughness);
        (v[0], v[1])
    }
}

/// Directional albedo E(μ, r) with F = 1 (Kulla–Conty).
#[derive(Clone, Debug)]
pub struct AlbedoTable<'a> {
    view: LutView<'a>,
}

impl<'a> AlbedoTable<'a> {
    /// Parses and checks that the bytes hold an E(μ, r) table.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::from_view(LutView::parse(bytes)?)
    }
    /// Wraps a parsed view.
    pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
        expect(&view, TableKind::DirectionalAlbedo, 2)?;
        Ok(Self { view })
    }
    /// The underlying view.
    pub fn view(&self) -> &LutView<'a> {
        &self.view
    }
    /// E(μ, r), clamped coordinates; NaN gives NaN.
    pub fn e(&self, mu: f32, roughness: f32) -> f32 {
        self.view.sample2(mu, roughness)[0]
    }
}

/// Average albedo E_avg(r) = 2∫₀¹ E(μ, r) μ dμ (Kulla–Conty).
#[derive(Clone, Debug)]
pub struct AverageAlbedoTable<'a> {
    view: LutView<'a>,
}

impl<'a> AverageAlbedoTable<'a> {
    /// Parses and checks that the bytes hold an E_avg(r) table.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LutError> {
        Self::from_view(LutView::parse(bytes)?)
    }
    /// Wraps a parsed view.
    pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
        expect(&view, TableKind::AverageAlbedo, 1)?;
        Ok(Self { view })
    }
    /// The underlying view.
    pub fn view(&self) -> &LutView<'a> {
        &self.view
    }
    /// E_avg(r), clamped coordinate; NaN gives NaN.
    pub fn e_avg(&self, roughness: f32) -> f32 {
        self.view.sample1(roughness)[0]
    }
}

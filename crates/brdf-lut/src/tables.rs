//! Typed tables: a table of one kind whose bytes were validated once and whose lookup
//! constants were prepared once, borrowed (`GTable<&[u8]>`, e.g. `&'static` bytes from
//! flash) or owned (`GTable<Vec<u8>>`, any `B: AsRef<[u8]>`). A query touches only the
//! payload.

use crate::header::{Convention, TableKind};
use crate::reader::Reader;
use crate::view::{Grid, LutView};
use crate::LutError;
use core::f32::consts::FRAC_PI_2;

/// What every query of a table needs, computed once from its header.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(crate) struct Prepared {
    pub(crate) header_len: usize,
    pub(crate) kind: TableKind,
    pub(crate) grid: Grid,
    pub(crate) reader: Reader,
    /// σ of a per-σ G table (NaN if the header does not say).
    pub(crate) sigma: f32,
    /// A passing-factor table in the reciprocal convention.
    pub(crate) reciprocal: bool,
    /// Range of the last axis (σ of a 3-D G table, roughness otherwise).
    pub(crate) last_range: (f32, f32),
}

impl Prepared {
    /// The prepared form of a view.
    pub(crate) fn new(view: &LutView<'_>) -> Self {
        let h = view.header();
        let grid = *view.grid();
        let last = h
            .axes
            .last()
            .map_or((0.0, 1.0), |a| (a.lo as f32, a.hi as f32));
        Prepared {
            header_len: view.header_len(),
            kind: h.kind,
            grid,
            reader: *view.reader(),
            sigma: h.generator.sigma.map_or(f32::NAN, |s| s as f32),
            last_range: last,
            reciprocal: h.generator.convention == Convention::Reciprocal,
        }
    }

    /// `view` must hold `kind` with `dims` axes (G tables: the reciprocal convention).
    pub(crate) fn expect(
        view: &LutView<'_>,
        kind: TableKind,
        dims: usize,
    ) -> Result<Self, LutError> {
        if view.kind() != kind || view.dims() != dims {
            return Err(LutError::WrongKind {
                expected: kind,
                found: view.kind(),
            });
        }
        if kind == TableKind::PassingFactor
            && view.header().generator.convention != Convention::Reciprocal
        {
            return Err(LutError::Inconsistent(
                "G tables must use the reciprocal convention",
            ));
        }
        Ok(Self::new(view))
    }

    /// (GM, GS, G) of a 2-D passing-factor table.
    #[inline]
    pub(crate) fn g2(&self, payload: &[u8], theta_i: f32, theta_r: f32) -> (f32, f32, f32) {
        if theta_i.is_nan() || theta_r.is_nan() {
            return (f32::NAN, f32::NAN, f32::NAN);
        }
        let (m, s) = g_args(theta_i, theta_r);
        let r = &self.reader;
        let gm = unit01(r.sample::<2, 1>(&self.grid, payload, m)[0]);
        let gs = unit01(r.sample::<2, 1>(&self.grid, payload, s)[0]);
        (gm, gs, gm.min(gs))
    }

    /// (GM, GS, G) of a 3-D passing-factor table.
    #[inline]
    pub(crate) fn g3(
        &self,
        payload: &[u8],
        theta_i: f32,
        theta_r: f32,
        sigma: f32,
    ) -> (f32, f32, f32) {
        if theta_i.is_nan() || theta_r.is_nan() || sigma.is_nan() {
            return (f32::NAN, f32::NAN, f32::NAN);
        }
        let (m, s) = g_args(theta_i, theta_r);
        let r = &self.reader;
        let gm = unit01(r.sample::<3, 1>(&self.grid, payload, [m[0], m[1], sigma])[0]);
        let gs = unit01(r.sample::<3, 1>(&self.grid, payload, [s[0], s[1], sigma])[0]);
        (gm, gs, gm.min(gs))
    }

    /// Channels 0 and 1 of a 2-D table.
    #[inline]
    pub(crate) fn two(&self, payload: &[u8], x: f32, y: f32) -> (f32, f32) {
        let [a, b] = self.reader.sample::<2, 2>(&self.grid, payload, [x, y]);
        (a, b)
    }

    /// Channel 0 of a 2-D one-channel table.
    #[inline]
    pub(crate) fn two1(&self, payload: &[u8], x: f32, y: f32) -> f32 {
        self.reader.sample::<2, 1>(&self.grid, payload, [x, y])[0]
    }

    /// Channel 0 of a 1-D table.
    #[inline]
    pub(crate) fn one(&self, payload: &[u8], x: f32) -> f32 {
        self.reader.sample::<1, 1>(&self.grid, payload, [x])[0]
    }
}

/// (GM, GS) arguments of the passing-factor table F(θ, φ) = M(θ, (θ − φ)/2) (reciprocal
/// convention, docs/conventions.md): GM = F(|θr|, sgn θr · θi), GS = F(θi, θr).
#[inline]
fn g_args(theta_i: f32, theta_r: f32) -> ([f32; 2], [f32; 2]) {
    let ti = crate::axis::clamp(theta_i, 0.0, FRAC_PI_2);
    let tr = crate::axis::clamp(theta_r, -FRAC_PI_2, FRAC_PI_2);
    let s = if tr < 0.0 { -ti } else { ti };
    ([tr.abs(), s], [ti, tr])
}

#[inline]
fn unit01(x: f32) -> f32 {
    crate::axis::clamp(x, 0.0, 1.0)
}

macro_rules! typed_table {
    ($(#[$doc:meta])* $name:ident, $kind:expr, $dims:expr) => {
        $(#[$doc])*
        #[derive(Clone, Debug)]
        pub struct $name<B = &'static [u8]> {
            bytes: B,
            p: Prepared,
        }

        impl<B: AsRef<[u8]>> $name<B> {
            /// Validates `bytes` (every check of [`LutView::parse`], CRC included), checks
            /// the kind and shape, and prepares the lookup constants.
            pub fn parse(bytes: B) -> Result<Self, LutError> {
                let p = Prepared::expect(&LutView::parse(bytes.as_ref())?, $kind, $dims)?;
                Ok(Self { bytes, p })
            }
            /// The table's bytes.
            pub fn bytes(&self) -> &[u8] {
                self.bytes.as_ref()
            }
            /// Gives the bytes back.
            pub fn into_bytes(self) -> B {
                self.bytes
            }
            /// A view of the bytes (header, raw payload, general sampling). Re-decodes the
            /// header without the CRC; fails only if `B` no longer gives the bytes that
            /// were parsed.
            pub fn view(&self) -> Result<LutView<'_>, LutError> {
                LutView::parse_skip_checksum(self.bytes.as_ref())
            }
            #[inline(always)]
            fn payload(&self) -> &[u8] {
                self.bytes.as_ref().get(self.p.header_len..).unwrap_or(&[])
            }
        }

        impl<'a> $name<&'a [u8]> {
            /// Wraps a parsed view (no second validation).
            pub fn from_view(view: LutView<'a>) -> Result<Self, LutError> {
                let p = Prepared::expect(&view, $kind, $dims)?;
                let bytes = view.bytes();
                Ok(Self { bytes, p })
            }
        }
    };
}

typed_table!(
    /// The modified G (reciprocal convention) for one fixed σ, from a 2-D passing-factor
    /// table over (θ, φ).
    GTable,
    TableKind::PassingFactor,
    2
);
typed_table!(
    /// The modified G (reciprocal convention) over σ, from a 3-D passing-factor table over
    /// (θ, φ, σ).
    GTable3,
    TableKind::PassingFactor,
    3
);
typed_table!(
    /// Split-sum (A, B) over (μ = n·v, roughness): specular E = F0·A + F90·B.
    DfgTable,
    TableKind::SplitSum,
    2
);
typed_table!(
    /// Directional albedo E(μ, r) with F = 1 (Kulla–Conty).
    AlbedoTable,
    TableKind::DirectionalAlbedo,
    2
);
typed_table!(
    /// Average albedo E_avg(r) = 2∫₀¹ E(μ, r) μ dμ (Kulla–Conty).
    AverageAlbedoTable,
    TableKind::AverageAlbedo,
    1
);

impl<B: AsRef<[u8]>> GTable<B> {
    /// The table's σ (NaN if the header does not say).
    pub fn sigma(&self) -> f32 {
        self.p.sigma
    }
    /// (GM, GS, G) at in-plane angles in radians, θi ∈ [0, π/2], θr ∈ [−π/2, π/2] signed
    /// (clamped; NaN gives NaN). G = min(GM, GS), each clamped to [0, 1] (paper eq 13).
    #[inline]
    pub fn terms(&self, theta_i: f32, theta_r: f32) -> (f32, f32, f32) {
        self.p.g2(self.payload(), theta_i, theta_r)
    }
    /// G = min(GM, GS); see [`GTable::terms`].
    #[inline]
    pub fn g(&self, theta_i: f32, theta_r: f32) -> f32 {
        self.terms(theta_i, theta_r).2
    }
}

impl<B: AsRef<[u8]>> GTable3<B> {
    /// The σ range [lo, hi] of the table (queries outside are clamped).
    pub fn sigma_range(&self) -> (f32, f32) {
        self.p.last_range
    }
    /// (GM, GS, G) at in-plane angles in radians and RMS slope σ (all clamped to the table's
    /// ranges; NaN gives NaN). G = min(GM, GS) (paper eq 13).
    #[inline]
    pub fn terms(&self, theta_i: f32, theta_r: f32, sigma: f32) -> (f32, f32, f32) {
        self.p.g3(self.payload(), theta_i, theta_r, sigma)
    }
    /// G = min(GM, GS); see [`GTable3::terms`].
    #[inline]
    pub fn g(&self, theta_i: f32, theta_r: f32, sigma: f32) -> f32 {
        self.terms(theta_i, theta_r, sigma).2
    }
}

impl<B: AsRef<[u8]>> DfgTable<B> {
    /// (A, B) at μ = n·v and roughness (perceptual r for GGX, σ for Torrance–Sparrow tables;
    /// see the header), clamped to the table's ranges; NaN gives NaN.
    #[inline]
    pub fn ab(&self, mu: f32, roughness: f32) -> (f32, f32) {
        self.p.two(self.payload(), mu, roughness)
    }
}

impl<B: AsRef<[u8]>> AlbedoTable<B> {
    /// E(μ, r), clamped coordinates; NaN gives NaN.
    #[inline]
    pub fn e(&self, mu: f32, roughness: f32) -> f32 {
        self.p.two1(self.payload(), mu, roughness)
    }
}

impl<B: AsRef<[u8]>> AverageAlbedoTable<B> {
    /// E_avg(r), clamped coordinate; NaN gives NaN.
    #[inline]
    pub fn e_avg(&self, roughness: f32) -> f32 {
        self.p.one(self.payload(), roughness)
    }
}

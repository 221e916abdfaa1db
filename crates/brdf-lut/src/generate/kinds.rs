//! The one list of table kinds. Everything the generator knows about a kind — its name on
//! the command line and in TOML files, its BLUT kind code, its axes (with their default
//! grids and admissible domains), its channels, how its error is
//! measured and the f64 kernel at a node — is in its entry of [`Kind::def`]. A new kind is
//! a new `Kind` variant and its entry there.

use super::integrate::{node, Work};
use super::{AxisSpec, Kind, Masking, Roughness, Spec, MU_MIN};
use crate::{TableKind, Warp};
use core::f64::consts::FRAC_PI_2;
use Role::{Eta, Mu, Phi, Sigma, Theta};
use TableKind as T;

/// What an axis holds: its name, default range and warp, and admissible domain follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// An incidence angle θ in radians, [0, π/2] (sqrt-cos warp by default).
    Theta,
    /// The neighbouring facet's angle φ in radians, [−π/2, π/2].
    Phi,
    /// μ = cos θ of the view direction, [cos 89°, 1] (log warp by default; √ warp for the
    /// sheen albedo, whose roughness axis is √-warped too).
    Mu,
    /// The model's roughness in the spec's [`Roughness`] parameterisation.
    Roughness,
    /// The RMS slope σ of the modified G's Gaussian slopes, [0.05, 1] (log warp by default).
    Sigma,
    /// The relative index η of a rough-glass table (the far side's index over the near
    /// side's), [1, 3] by default (light entering the denser medium; [1/3, 1] is light from
    /// inside), within [0.1, 10] and not spanning 1 (`generate/glass.rs`).
    Eta,
}

/// How a table's error is measured at random points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Check {
    /// |table − kernel| per channel at random points of the axes' ranges.
    Values,
    /// The passing-factor tables: |G_table − G| of the modified G = min(GM, GS) at random
    /// (θi from the theta range, θr from the phi range[, σ]): the error a G lookup makes.
    ModifiedG,
}

/// One kind's entry in the list.
pub struct KindDef {
    /// Its name on the command line and in TOML files.
    pub name: &'static str,
    /// Its BLUT kind code.
    pub table: TableKind,
    /// Its axes, fastest first, each with its default node count.
    pub axes: &'static [(Role, u32)],
    /// Its channels, in payload order.
    pub channels: &'static [&'static str],
    /// How its error is measured.
    pub check: Check,
    /// The f64 kernel at a point `x` (one coordinate per axis): one value per channel in
    /// `out`, with its integration estimate and work (`generate/integrate.rs`).
    pub value: fn(&Spec, &[f64], &mut [f64]) -> Work,
}

impl KindDef {
    /// The entry of a kind whose nodes are the f64 kernel's values ([`node`]), measured
    /// against it at random points ([`Check::Values`]).
    const fn values(
        name: &'static str,
        table: TableKind,
        axes: &'static [(Role, u32)],
        channels: &'static [&'static str],
    ) -> KindDef {
        let check = Check::Values;
        KindDef {
            name,
            table,
            axes,
            channels,
            check,
            value: node,
        }
    }

    /// The entry of a passing-factor table of the modified G: one channel `F`, its error
    /// that of a G lookup ([`Check::ModifiedG`]).
    const fn passing_factor(name: &'static str, axes: &'static [(Role, u32)]) -> KindDef {
        let check = Check::ModifiedG;
        KindDef {
            check,
            ..KindDef::values(name, TableKind::PassingFactor, axes, &["F"])
        }
    }
}

impl Kind {
    /// This kind's entry in the one list of kinds.
    pub fn def(&self) -> &'static KindDef {
        match self {
            Kind::GPerSigma { .. } => &G_PER_SIGMA,
            Kind::GOverSigma => &G_OVER_SIGMA,
            Kind::SplitSum => &SPLIT_SUM,
            Kind::Albedo => &ALBEDO,
            Kind::AverageAlbedo => &AVERAGE_ALBEDO,
            Kind::SheenAlbedo { .. } => &SHEEN_ALBEDO,
            Kind::GlassAlbedo => &GLASS_ALBEDO,
            Kind::GlassAverageAlbedo => &GLASS_AVERAGE_ALBEDO,
        }
    }
}

// The entries: name, kind code, axes with their default node counts, channels.
/// The roughness axis.
const R: Role = Role::Roughness;
const MU_R: &[(Role, u32)] = &[(Mu, 64), (R, 64)];
const G_PER_SIGMA: KindDef = KindDef::passing_factor("g-per-sigma", &[(Theta, 128), (Phi, 126)]);
const G_OVER_SIGMA: KindDef =
    KindDef::passing_factor("g-over-sigma", &[(Theta, 64), (Phi, 64), (Sigma, 31)]);
const SPLIT_SUM: KindDef = KindDef::values("split-sum", T::SplitSum, MU_R, &["A", "B"]);
const ALBEDO: KindDef = KindDef::values("e", T::DirectionalAlbedo, MU_R, &["E"]);
const AVERAGE_ALBEDO: KindDef = KindDef::values("e-avg", T::AverageAlbedo, &[(R, 32)], &["Eavg"]);
const SHEEN_ALBEDO: KindDef = KindDef {
    value: sheen_node,
    ..KindDef::values("sheen-e", T::SheenAlbedo, MU_R, &["E"])
};
const GLASS_AXES: &[(Role, u32)] = &[(Mu, 32), (R, 32), (Eta, 32)];
const GLASS_ALBEDO: KindDef = KindDef::values("glass-e", T::GlassAlbedo, GLASS_AXES, &["R", "T"]);
const GLASS_AVERAGE_ALBEDO: KindDef = KindDef::values(
    "glass-e-avg",
    T::GlassAverageAlbedo,
    &[(R, 32), (Eta, 32)],
    &["R", "T"],
);

/// The `sheen-e` node at x = (μ, r) (`generate/sheen.rs`).
fn sheen_node(s: &Spec, x: &[f64], out: &mut [f64]) -> Work {
    match s.kind {
        Kind::SheenAlbedo { visibility } => super::sheen::node(visibility, x[0], x[1], out),
        _ => Work::default(),
    }
}

impl Role {
    /// The axis name in the file.
    pub fn name(self, s: &Spec) -> &'static str {
        match self {
            Role::Theta => "theta",
            Role::Phi => "phi",
            Role::Mu => "mu",
            Role::Sigma => "sigma",
            Role::Eta => "eta",
            Role::Roughness => s.roughness_name(),
        }
    }

    /// The default range and warp of `count` endpoint nodes.
    pub fn default_axis(self, s: &Spec, count: u32) -> AxisSpec {
        let sheen = matches!(s.kind, Kind::SheenAlbedo { .. });
        let (lo, hi, warp) = match self {
            Role::Theta => (0.0, FRAC_PI_2, Warp::SqrtCos),
            Role::Phi => (-FRAC_PI_2, FRAC_PI_2, Warp::Linear),
            // The sheen table's axes are both √-warped (nodes at lo + s²(hi − lo), denser
            // toward grazing μ and small r, where E bends most, like the split-sum speed
            // tier's): its lookup is two square roots, where a log warp's is a call of
            // `logf`, and its linear u16 form takes the inlined two-lane lookup (harness
            // `sheen_e_lut`).
            Role::Mu if sheen => (MU_MIN, 1.0, Warp::Sqrt),
            Role::Mu => (MU_MIN, 1.0, Warp::Log),
            Role::Sigma => (0.05, 1.0, Warp::Log),
            Role::Eta => (1.0, 3.0, Warp::Linear),
            Role::Roughness => match s.roughness {
                Roughness::Sigma => (0.05, 1.0, Warp::Log),
                _ if sheen => (0.0, 1.0, Warp::Sqrt),
                // The modified G needs a width > 0.
                _ if s.masking == Masking::Modified => (0.05, 1.0, Warp::Linear),
                _ => (0.0, 1.0, Warp::Linear),
            },
        };
        AxisSpec::endpoint(count, lo, hi, warp)
    }

    /// The admissible range of the axis, and its description.
    pub fn domain(self, s: &Spec) -> (f64, f64, &'static str) {
        let width_min = if s.masking == Masking::Modified {
            f64::MIN_POSITIVE
        } else {
            0.0
        };
        match (self, s.roughness) {
            (Role::Theta, _) => (0.0, FRAC_PI_2, "θ (radians)"),
            (Role::Phi, _) => (-FRAC_PI_2, FRAC_PI_2, "φ (radians)"),
            (Role::Mu, _) => (0.0, 1.0, "μ = cos θ"),
            (Role::Eta, _) => (0.1, 10.0, "η (the rough dielectric's range)"),
            (Role::Sigma, _) | (Role::Roughness, Roughness::Sigma) => {
                (width_min, 4.0, "σ (the modified G needs σ > 0)")
            }
            (Role::Roughness, Roughness::Perceptual) => {
                (width_min, 1.0, "perceptual r (the modified G needs r > 0)")
            }
            (Role::Roughness, Roughness::Alpha) => (
                width_min,
                4.0,
                "width α or m (the modified G needs a width > 0)",
            ),
        }
    }
}

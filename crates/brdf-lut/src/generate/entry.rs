//! What an entry of the one list of table kinds holds ([`KindDef`], the list itself is
//! `generate/kinds.rs`), the roles of its axes ([`Role`]) and the microfacet kernels' defaults
//! that most entries take ([`KindDef::microfacet`]).

use super::integrate::{self, Work};
use super::{AxisSpec, Distribution, GenError, Kind, Masking, Roughness, Spec, MU_MIN};
use crate::{Convention, Header, Model, TableKind, Warp};
use core::f64::consts::FRAC_PI_2;

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

/// The kind, distribution and masking a header describes.
pub type HeaderModel = (Kind, Distribution, Masking);

/// A whole row of nodes along axis 0: (spec, the row's μ values, its roughness-axis value,
/// the stride of a node's slot, the slots), `None` when the row is done node by node.
pub type RowFn = fn(&Spec, &[f64], f64, usize, &mut [f64]) -> Option<()>;

/// One kind's entry in the list (`generate/kinds.rs`). The function fields are the kind's
/// kernel, reference and model rules; [`KindDef::microfacet`] fills them with the
/// microfacet kernels' (`generate/integrate.rs`).
pub struct KindDef {
    /// Its name on the command line and in TOML files.
    pub name: &'static str,
    /// The kind itself (with default parameters).
    pub kind: Kind,
    /// Its BLUT kind code.
    pub table: TableKind,
    /// Its axes, fastest first, each with its default node count.
    pub axes: &'static [(Role, u32)],
    /// The default warp of its μ and roughness axes, if not their role's own.
    pub warp: Option<Warp>,
    /// Its channels, in payload order.
    pub channels: &'static [&'static str],
    /// How its error is measured.
    pub check: Check,
    /// The f64 kernel at a node `x` (one coordinate per axis): one value per channel in
    /// `out`, with its integration estimate and work.
    pub value: fn(&Spec, &[f64], &mut [f64]) -> Work,
    /// The f64 kernel at a point without an estimate: what the error measurement at
    /// random points compares the table with.
    pub point: fn(&Spec, &[f64], &mut [f64]),
    /// `lut verify`'s independent reference at a point: (values, its own error estimate).
    pub reference: fn(&Spec, &[f64]) -> ([f64; 2], f64),
    /// The header's model code of a spec, or why the spec's model does not fit the kind.
    pub model: fn(&Spec) -> Result<Model, GenError>,
    /// The kind's own option checks (beyond axes and model).
    pub validate: fn(&Spec) -> Result<(), GenError>,
    /// The quadrature node counts the header records (empty: adaptive).
    pub record: fn(&Spec) -> &'static [u16],
    /// The kind, distribution and masking a header of this kind describes.
    pub from_header: fn(&KindDef, &Header<'_>) -> Option<HeaderModel>,
    /// The distribution a description without `model` gets (`None`: `model` is required).
    pub default_distribution: Option<Distribution>,
    /// A whole row of nodes along axis 0 at once (`integrate::converged_row`'s contract),
    /// for kinds that share work along a row; `None`: node by node.
    pub row: Option<RowFn>,
}

impl KindDef {
    /// The entry of a microfacet kind: nodes by `generate/integrate.rs` (the converged
    /// polar rule or brdf-core's fixed rules), measured against the kernel at random points
    /// ([`Check::Values`]), the model from the spec's distribution and G.
    pub const fn microfacet(
        name: &'static str,
        kind: Kind,
        table: TableKind,
        axes: &'static [(Role, u32)],
        channels: &'static [&'static str],
    ) -> KindDef {
        KindDef {
            name,
            kind,
            table,
            axes,
            warp: None,
            channels,
            check: Check::Values,
            value: integrate::node,
            point: integrate::value,
            reference: integrate::reference,
            model: Spec::microfacet_model,
            validate: |_| Ok(()),
            record: integrate::nodes_record,
            from_header: microfacet_from_header,
            default_distribution: None,
            row: None,
        }
    }

    /// The node counts of an adaptive rule: none recorded.
    pub fn adaptive(_: &Spec) -> &'static [u16] {
        &[]
    }
}

/// A whole row of split-sum or albedo nodes (`integrate::converged_row`).
pub fn converged_row(s: &Spec, mus: &[f64], rx: f64, stride: usize, out: &mut [f64]) -> Option<()> {
    integrate::converged_row(s, mus, rx, stride, out)
}

/// The kind, distribution and masking of a microfacet table's header: the catalogue's
/// model (the generator writes the reciprocal modified G; a file's convention is not part
/// of its spec).
pub fn microfacet_from_header(def: &KindDef, h: &Header<'_>) -> Option<HeaderModel> {
    let (d, g) = h.generator.model.catalogue(Convention::Reciprocal);
    let d = d.unwrap_or(Distribution::TorranceSparrow);
    Some((def.kind, d, Masking::from_term(g)?))
}

/// The model options of a passing-factor table: the modified G over σ, σ > 0.
pub fn validate_passing_factor(s: &Spec) -> Result<(), GenError> {
    let invalid = |m: &str| Err(GenError::Invalid(m.into()));
    if s.masking != Masking::Modified {
        return invalid(
            "G tables hold the modified G's passing factor: choose the modified G \
             (the Smith and V-cavity G are closed forms that need no table)",
        );
    }
    if s.roughness != Roughness::Sigma {
        return invalid("G tables are parameterised by the RMS slope σ only");
    }
    match s.kind {
        Kind::GPerSigma { sigma } if !(sigma.is_finite() && sigma > 0.0) => Err(GenError::Invalid(
            std::format!("σ of a per-σ G table must be > 0 (got {sigma})"),
        )),
        _ => Ok(()),
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
        let own = s.kind.def().warp;
        let (lo, hi, warp) = match self {
            Role::Theta => (0.0, FRAC_PI_2, Warp::SqrtCos),
            Role::Phi => (-FRAC_PI_2, FRAC_PI_2, Warp::Linear),
            Role::Mu => (MU_MIN, 1.0, own.unwrap_or(Warp::Log)),
            Role::Sigma => (0.05, 1.0, Warp::Log),
            Role::Eta => (1.0, 3.0, Warp::Linear),
            Role::Roughness => match s.roughness {
                Roughness::Sigma => (0.05, 1.0, Warp::Log),
                _ if own.is_some() => (0.0, 1.0, own.unwrap_or(Warp::Linear)),
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

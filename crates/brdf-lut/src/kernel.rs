//! Conversions between the format's enums and the kernel types of `brdf-core`: the format
//! records which kernel filled a table, but does not depend on the kernels' own types.

use crate::header::{Convention, Model};
use brdf_core::catalogue::DistributionId;
use brdf_core::masking::Convention as KernelConvention;
use brdf_core::models::{GeometricTerm, SheenVisibility};

impl From<KernelConvention> for Convention {
    fn from(c: KernelConvention) -> Self {
        match c {
            KernelConvention::Reciprocal => Convention::Reciprocal,
            KernelConvention::Printed => Convention::Printed,
        }
    }
}

impl From<Convention> for KernelConvention {
    fn from(c: Convention) -> Self {
        match c {
            Convention::Reciprocal => KernelConvention::Reciprocal,
            Convention::Printed => KernelConvention::Printed,
        }
    }
}

/// The one table between the model catalogue and the header's model codes: each row is a
/// model code with its convention, and the catalogue's distribution
/// ([`brdf_core::catalogue::DISTRIBUTIONS`]) and G term ([`brdf_core::catalogue::MASKINGS`])
/// it was generated from. No distribution: the G term's own passing factor (a G table).
/// The convention matters for the modified G only; a row with the printed convention
/// exists only where the catalogue has a printed term.
#[rustfmt::skip]
const MODEL_TABLE: [(Model, Convention, Option<DistributionId>, GeometricTerm); 11] = {
    use Convention::{Printed as P, Reciprocal as R};
    use DistributionId::{Beckmann, Ggx, TorranceSparrow as Ts};
    use GeometricTerm as G;
    use Model as M;
    [
        (M::ModifiedG, R, None, G::Modified),
        (M::ModifiedG, P, None, G::ModifiedPrinted),
        (M::GgxSmithCorrelated, R, Some(Ggx), G::SmithCorrelated),
        (M::GgxSmithSeparable, R, Some(Ggx), G::SmithSeparable),
        (M::BeckmannSmithCorrelated, R, Some(Beckmann), G::SmithCorrelated),
        (M::BeckmannSmithSeparable, R, Some(Beckmann), G::SmithSeparable),
        (M::TorranceSparrowModifiedG, R, Some(Ts), G::Modified),
        (M::TorranceSparrowModifiedG, P, Some(Ts), G::ModifiedPrinted),
        (M::TorranceSparrowSmith, R, Some(Ts), G::SmithCorrelated),
        (M::TorranceSparrowSmithSeparable, R, Some(Ts), G::SmithSeparable),
        (M::TorranceSparrowVCavity, R, Some(Ts), G::Blinn),
    ]
};

impl Model {
    /// The model code and convention of a catalogue distribution (`None`: a G table of the
    /// term alone) and G term; `None` for a pair no table is made of.
    pub fn from_catalogue(
        distribution: Option<DistributionId>,
        g: GeometricTerm,
    ) -> Option<(Model, Convention)> {
        MODEL_TABLE
            .iter()
            .find(|r| r.2 == distribution && r.3 == g)
            .map(|r| (r.0, r.1))
    }

    /// The catalogue's distribution (`None` for a G table) and G term of this model under
    /// `convention` (which matters for the modified G only).
    pub fn catalogue(self, convention: Convention) -> (Option<DistributionId>, GeometricTerm) {
        let row = |c| MODEL_TABLE.iter().find(|r| r.0 == self && r.1 == c);
        // Every model has a reciprocal row (the table test checks it).
        let r = row(convention).or_else(|| row(Convention::Reciprocal));
        r.map_or((None, GeometricTerm::Modified), |r| (r.2, r.3))
    }

    /// The geometric attenuation factor of a Torrance–Sparrow model under `convention`;
    /// `None` for the other models (GGX and Beckmann tables use Smith, the
    /// per-σ G tables are the modified G itself).
    pub fn torrance_sparrow_g(self, convention: Convention) -> Option<GeometricTerm> {
        match self.catalogue(convention) {
            (Some(DistributionId::TorranceSparrow), g) => Some(g),
            _ => None,
        }
    }
}

/// The sheen tables' codes: the catalogue's `sheen` model with each of its visibility
/// options ([`SheenVisibility::ALL`]), one row each.
const SHEEN_TABLE: [(Model, SheenVisibility); 2] = [
    (Model::SheenEstevezKulla, SheenVisibility::EstevezKulla),
    (Model::SheenAshikhmin, SheenVisibility::Ashikhmin),
];

impl Model {
    /// The code of a sheen table with visibility `v`.
    pub fn from_sheen(v: SheenVisibility) -> Model {
        SHEEN_TABLE
            .iter()
            .find(|r| r.1 == v)
            .map_or(Model::SheenEstevezKulla, |r| r.0)
    }

    /// The visibility of a sheen table's model; `None` for the microfacet models.
    pub fn sheen(self) -> Option<SheenVisibility> {
        SHEEN_TABLE.iter().find(|r| r.0 == self).map(|r| r.1)
    }
}

/// The rough-glass tables' codes: the catalogue's `rough-dielectric` model with each of its
/// distributions, one row each.
const DIELECTRIC_TABLE: [(Model, DistributionId); 2] = [
    (Model::RoughDielectricGgx, DistributionId::Ggx),
    (Model::RoughDielectricBeckmann, DistributionId::Beckmann),
];

impl Model {
    /// The code of a rough-glass table over distribution `d`; `None` where the rough
    /// dielectric does not take it (Torrance–Sparrow).
    pub fn from_dielectric(d: DistributionId) -> Option<Model> {
        DIELECTRIC_TABLE.iter().find(|r| r.1 == d).map(|r| r.0)
    }

    /// The distribution of a rough-glass table's model; `None` for the other models.
    pub fn dielectric(self) -> Option<DistributionId> {
        DIELECTRIC_TABLE.iter().find(|r| r.0 == self).map(|r| r.1)
    }
}

//! Conversions between the format's enums and the kernel types of `brdf-core`: the format
//! records which kernel filled a table, but does not depend on the kernels' own types.

use crate::header::{Convention, Model};
use brdf_core::masking::Convention as KernelConvention;
use brdf_core::models::GeometricTerm;

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

impl Model {
    /// The geometric attenuation factor of a Torrance–Sparrow model under `convention`;
    /// `None` for the other models (GGX and Beckmann tables use height-correlated Smith, the
    /// per-σ G tables are the modified G itself).
    pub fn torrance_sparrow_g(self, convention: Convention) -> Option<GeometricTerm> {
        match (self, convention) {
            (Model::TorranceSparrowModifiedG, Convention::Reciprocal) => {
                Some(GeometricTerm::Modified)
            }
            (Model::TorranceSparrowModifiedG, Convention::Printed) => {
                Some(GeometricTerm::ModifiedPrinted)
            }
            (Model::TorranceSparrowSmith, _) => Some(GeometricTerm::SmithCorrelated),
            _ => None,
        }
    }
}

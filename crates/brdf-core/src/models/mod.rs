//! Reflection models built from the distribution, masking and Fresnel pieces.

pub mod torrance_sparrow;

pub use torrance_sparrow::{GeometricTerm, TorranceSparrow};

//! Cross-crate integration tests, and the high-accuracy references they check against.
//!
//! The references here are deliberately built by a different route from the kernels: the
//! kernels integrate in the working variable v = tan γ/(√2σ) with a fixed Gauss–Legendre
//! rule; the references integrate the paper's formulas as printed (in γ, eqs 5–11 with the
//! readings of docs/conventions.md §§2–3) with adaptive Gauss–Kronrod to 1e-13.

pub mod anchors;
pub mod reference;

/// The repository README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeExamples;

//! Masking and shadowing: the geometric attenuation factor G.
//!
//! * [`modified`]: the paper's integral G = min(GM, GS) (eqs 6–13), both conventions.
//! * [`blinn`]: Blinn's V-groove G (eq 4).
//!
//! Smith's G for Beckmann and GGX (separable and height-correlated) belongs to the
//! distributions: [`crate::microfacet::Distribution`], and in the dot products
//! [`crate::microfacet::Isotropic`].

pub mod blinn;
pub mod modified;

pub use blinn::{g_blinn, g_blinn_dots};
pub use modified::{Convention, GTerms, ModifiedG};

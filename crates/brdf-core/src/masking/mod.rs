//! Masking and shadowing: the geometric attenuation factor G.
//!
//! * [`modified`]: the paper's integral G = min(GM, GS) (eqs 6–13), both conventions.
//! * [`blinn`]: Blinn's V-groove G (eq 4).
//! * [`smith`]: Smith's G for Beckmann and GGX, separable and height-correlated.

pub mod blinn;
pub mod modified;
pub mod smith;

pub use blinn::{g_blinn, g_blinn_dots};
pub use modified::{Convention, GTerms, ModifiedG};
pub use smith::{
    g1_smith_beckmann, g1_smith_ggx, g_smith_beckmann_correlated, g_smith_beckmann_separable,
    g_smith_ggx_correlated, g_smith_ggx_separable, lambda_beckmann, lambda_ggx,
    v_smith_ggx_correlated,
};

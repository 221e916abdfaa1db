//! # brdf-core
//!
//! `no_std`, allocation-free reflection-model kernels in `f32` and `f64`:
//!
//! * [`masking::ModifiedG`]: the modified geometric attenuation factor of
//!   *Acta Physica Sinica* 64, 184213 (2015), eqs 6–13, by fixed-size Gauss–Legendre
//!   quadrature ([`quadrature`]), with the readings of `conventions.md`;
//! * Blinn's V-groove G (eq 4) and Smith's G ([`masking`]);
//! * the Torrance–Sparrow BRDF (eq 3) with any of those G ([`models`]);
//! * Fresnel terms ([`fresnel`]) and normal distributions ([`distribution`]).
//!
//! Local shading frame: z is the normal; directions point away from the surface.
//!
//! ```
//! use brdf_core::masking::ModifiedG;
//! let g = ModifiedG::<f64>::new(0.3).unwrap();
//! let t = g.terms(30f64.to_radians(), 60f64.to_radians());
//! assert!(t.g > 0.0 && t.g <= 1.0 && t.g == t.gm.min(t.gs));
//! ```
#![no_std]
#![deny(missing_debug_implementations)]
// `!(x > 0)` is the deliberate idiom here: unlike `x <= 0` it is also true for NaN, which is
// how the kernels route NaN input to its documented result.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod albedo;
pub mod batch;
pub mod distribution;
pub mod error;
pub mod fresnel;
pub mod geometry;
pub mod masking;
pub mod models;
pub mod quadrature;
pub mod real;
pub mod sampling;
pub mod split_sum;

pub use error::ParamError;
pub use geometry::{Dots, Frame, Vec3};
pub use real::Real;

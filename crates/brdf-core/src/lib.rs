#![doc = include_str!("../README.md")]
#![no_std]
#![deny(missing_debug_implementations)]
#![warn(missing_docs)]
// `!(x > 0)` is the deliberate idiom here: unlike `x <= 0` it is also true for NaN, which is
// how the kernels route NaN input to its documented result.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod albedo;
pub mod batch;
pub mod catalogue;
pub mod distribution;
pub mod error;
pub mod fresnel;
pub mod geometry;
pub mod masking;
pub mod microfacet;
pub mod models;
pub mod quadrature;
pub mod real;
pub mod roughness;
pub mod sampling;
pub mod split_sum;

pub use error::ParamError;
pub use geometry::{Dots, Frame, Vec3};
pub use real::Real;

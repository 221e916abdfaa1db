//! Transitional: the Smith forms moved to [`crate::microfacet::Isotropic`]; removed once
//! every caller uses the distribution types.
#![allow(missing_docs)]
use crate::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use crate::Real;
#[inline]
pub fn lambda_beckmann<T: Real>(c: T, m: T) -> T { Beckmann::lambda_cos(c, m) }
#[inline]
pub fn g1_smith_beckmann<T: Real>(c: T, m: T) -> T { Beckmann::g1_cos(c, m) }
#[inline]
pub fn g_smith_beckmann_separable<T: Real>(i: T, o: T, m: T) -> T { Beckmann::g_separable_cos(i, o, m) }
#[inline]
pub fn g_smith_beckmann_correlated<T: Real>(i: T, o: T, m: T) -> T { Beckmann::g_correlated_cos(i, o, m) }
#[inline]
pub fn lambda_ggx<T: Real>(c: T, a: T) -> T { TrowbridgeReitz::lambda_cos(c, a) }
#[inline]
pub fn g1_smith_ggx<T: Real>(c: T, a: T) -> T { TrowbridgeReitz::g1_cos(c, a) }
#[inline]
pub fn g_smith_ggx_separable<T: Real>(i: T, o: T, a: T) -> T { TrowbridgeReitz::g_separable_cos(i, o, a) }
#[inline]
pub fn g_smith_ggx_correlated<T: Real>(i: T, o: T, a: T) -> T { TrowbridgeReitz::g_correlated_cos(i, o, a) }
#[inline]
pub fn v_smith_ggx_correlated<T: Real>(i: T, o: T, a: T) -> T { TrowbridgeReitz::v_correlated_cos(i, o, a) }

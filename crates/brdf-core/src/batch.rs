//! Batch entry points over slices, in structure-of-arrays form.
//!
//! Each function evaluates one scalar kernel of this crate over equally long input slices
//! and writes one output slice. The loops zip the slices (no index, no bounds check inside
//! the loop) and call the `#[inline]` scalar kernel, so every element gets exactly the
//! scalar kernel's operations in the scalar kernel's order: batch results equal the scalar
//! results bit for bit (tested in `tests/tests/batch.rs`). Branches of the kernels become
//! selects where the compiler can prove that both sides are cheap and side-effect free;
//! that, not a different formula, is what lets it vectorise the arithmetic.
//!
//! Square roots: `libm`'s `sqrt`/`sqrtf` is one `sqrtsd`/`sqrtss` instruction in inline
//! assembly on x86-64, which the compiler cannot vectorise. The closed forms that need only
//! square roots (Smith–GGX G and V) are therefore written in two passes over chunks of
//! [`CHUNK`] elements: the radicands, then [`BatchReal::sqrt_chunk`] (packed `sqrtps`/`sqrtpd`
//! on x86-64 with `libm`; IEEE square roots are correctly rounded, so the bits are the
//! scalar `sqrt`'s), then the rest of the kernel's arithmetic in the kernel's order.
//!
//! Limits: `exp`, `erf` and the quadrature of the modified G are scalar library calls, so
//! those loops run at the scalar rate; the batch form still saves the call overhead.
//! `docs/benchmarks.md` reports the measured throughput per core of each entry point.
//!
//! No allocation: the caller owns every slice. Slices of unequal length are a
//! [`BatchError`], never a panic and never a partial write.

use crate::geometry::{Dots, Vec3};
use crate::masking::{self, ModifiedG};
use crate::microfacet::ggx::{lambda_finish, lambda_radicand, v_a2, v_finish};
use crate::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use crate::models::{Brdf, TorranceSparrow};
use crate::quadrature::Rule;
use crate::Real;
use core::fmt;

/// Elements per chunk of the two-pass closed forms.
pub const CHUNK: usize = 8;

/// The scalar types the batch entry points take: [`Real`] plus a chunked square root that
/// returns exactly [`Real::sqrt`]'s bits.
pub trait BatchReal: Real {
    /// `x[k] = x[k].sqrt()` for every k, bit-identical to [`Real::sqrt`].
    fn sqrt_chunk(x: &mut [Self; CHUNK]);
}

impl BatchReal for f64 {
    #[inline]
    fn sqrt_chunk(x: &mut [f64; CHUNK]) {
        #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
        {
            use core::arch::x86_64::{_mm_loadu_pd, _mm_sqrt_pd, _mm_storeu_pd};
            for p in x.chunks_exact_mut(2) {
                // SAFETY: SSE2 is enabled (cfg above); `p` holds exactly two f64, and the
                // unaligned load/store read and write only those.
                unsafe { _mm_storeu_pd(p.as_mut_ptr(), _mm_sqrt_pd(_mm_loadu_pd(p.as_ptr()))) };
            }
        }
        #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
        for v in x.iter_mut() {
            *v = Real::sqrt(*v);
        }
    }
}

impl BatchReal for f32 {
    #[inline]
    fn sqrt_chunk(x: &mut [f32; CHUNK]) {
        // With micromath, f32 `sqrt` is micromath's approximation (plain arithmetic, which
        // vectorises by itself); the packed instruction would change the bits.
        #[cfg(all(
            target_arch = "x86_64",
            target_feature = "sse",
            not(feature = "micromath")
        ))]
        {
            use core::arch::x86_64::{_mm_loadu_ps, _mm_sqrt_ps, _mm_storeu_ps};
            for p in x.chunks_exact_mut(4) {
                // SAFETY: SSE is enabled (cfg above); `p` holds exactly four f32, and the
                // unaligned load/store read and write only those.
                unsafe { _mm_storeu_ps(p.as_mut_ptr(), _mm_sqrt_ps(_mm_loadu_ps(p.as_ptr()))) };
            }
        }
        #[cfg(not(all(
            target_arch = "x86_64",
            target_feature = "sse",
            not(feature = "micromath")
        )))]
        for v in x.iter_mut() {
            *v = Real::sqrt(*v);
        }
    }
}

/// Two-pass map over chunks: radicands `pre(a, b)`, chunked square roots, then
/// `post(a, b, √r₁, √r₂)`; the tail (fewer than [`CHUNK`]) uses `scalar`.
#[inline]
fn map2_sqrt<T: BatchReal>(
    a: &[T],
    b: &[T],
    out: &mut [T],
    pre: impl Fn(T, T) -> (T, T),
    post: impl Fn(T, T, T, T) -> T,
    scalar: impl Fn(T, T) -> T,
) {
    let mut ac = a.chunks_exact(CHUNK);
    let mut bc = b.chunks_exact(CHUNK);
    let mut oc = out.chunks_exact_mut(CHUNK);
    for ((ca, cb), co) in (&mut ac).zip(&mut bc).zip(&mut oc) {
        let mut r1 = [T::ZERO; CHUNK];
        let mut r2 = [T::ZERO; CHUNK];
        for ((p, q), (&x, &y)) in r1.iter_mut().zip(r2.iter_mut()).zip(ca.iter().zip(cb)) {
            (*p, *q) = pre(x, y);
        }
        T::sqrt_chunk(&mut r1);
        T::sqrt_chunk(&mut r2);
        let ins = ca.iter().zip(cb).zip(r1.iter().zip(&r2));
        for (o, ((&x, &y), (&s1, &s2))) in co.iter_mut().zip(ins) {
            *o = post(x, y, s1, s2);
        }
    }
    for ((o, &x), &y) in oc
        .into_remainder()
        .iter_mut()
        .zip(ac.remainder())
        .zip(bc.remainder())
    {
        *o = scalar(x, y);
    }
}

/// The Smith–GGX closed forms over cosine pairs, after the length check: [`map2_sqrt`] of
/// the two Λ radicands R² = c² + a², a² = α²(1 − c)(1 + c) (0 for α ≤ 0; the scalar
/// kernel's `v_a2` and `lambda_radicand`), then `post(cos_i, cos_o, R_i, R_o)`; the tail
/// uses `scalar`.
#[inline]
fn map_ggx_roots<T: BatchReal>(
    cos_i: &[T],
    cos_o: &[T],
    alpha: T,
    out: &mut [T],
    post: impl Fn(T, T, T, T) -> T,
    scalar: impl Fn(T, T) -> T,
) -> Result<(), BatchError> {
    same_len(&[cos_i.len(), cos_o.len(), out.len()])?;
    let pre = |ci, co| {
        let (ai, ao) = v_a2(ci, co, alpha);
        (lambda_radicand(ci, ai), lambda_radicand(co, ao))
    };
    map2_sqrt(cos_i, cos_o, out, pre, post, scalar);
    Ok(())
}

/// `out[k] = f(d[k])` over dot-product pairs, after the length check.
#[inline]
fn map_dots<T: Real>(
    d: DotsSoa<'_, T>,
    out: &mut [T],
    f: impl Fn(Dots<T>) -> T,
) -> Result<(), BatchError> {
    d.len_with(out.len())?;
    for (o, dk) in out.iter_mut().zip(d.iter()) {
        *o = f(dk);
    }
    Ok(())
}

/// `out[k] = f(a[k], b[k])`, after the length check.
#[inline]
fn map2<T: Copy>(a: &[T], b: &[T], out: &mut [T], f: impl Fn(T, T) -> T) -> Result<(), BatchError> {
    same_len(&[a.len(), b.len(), out.len()])?;
    for ((o, &x), &y) in out.iter_mut().zip(a).zip(b) {
        *o = f(x, y);
    }
    Ok(())
}

/// Why a batch call was refused (nothing is written).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BatchError {
    /// An input or output slice has a length different from the first input's.
    LengthMismatch {
        /// The first input's length.
        expected: usize,
        /// The offending slice's length.
        found: usize,
    },
}

impl fmt::Display for BatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BatchError::LengthMismatch { expected, found } => write!(
                f,
                "batch slices differ in length: expected {expected}, found {found}"
            ),
        }
    }
}

impl core::error::Error for BatchError {}

/// Checks that every length equals the first.
#[inline]
fn same_len(lens: &[usize]) -> Result<usize, BatchError> {
    let expected = lens.first().copied().unwrap_or(0);
    for &found in lens {
        if found != expected {
            return Err(BatchError::LengthMismatch { expected, found });
        }
    }
    Ok(expected)
}

/// Defines a structure of three equal-length arrays and its iterator over the items
/// `$make(a[k], b[k], c[k])`.
macro_rules! soa3 {
    ($(#[$m:meta])* $name:ident -> $item:ident::$make:ident {
        $(#[$ma:meta])* $a:ident, $(#[$mb:meta])* $b:ident, $(#[$mc:meta])* $c:ident $(,)?
    }) => {
        $(#[$m])*
        #[derive(Clone, Copy, Debug)]
        pub struct $name<'a, T> {
            $(#[$ma])*
            pub $a: &'a [T],
            $(#[$mb])*
            pub $b: &'a [T],
            $(#[$mc])*
            pub $c: &'a [T],
        }

        impl<T: Real> $name<'_, T> {
            /// The three lengths.
            fn lens(&self) -> [usize; 3] {
                [self.$a.len(), self.$b.len(), self.$c.len()]
            }
            /// Iterator over the items.
            #[inline]
            fn iter(&self) -> impl Iterator<Item = $item<T>> + '_ {
                self.$a
                    .iter()
                    .zip(self.$b)
                    .zip(self.$c)
                    .map(|((&a, &b), &c)| $item::$make(a, b, c))
            }
        }
    };
}

soa3! {
    /// Pairs of directions given by their dot products, as structure of arrays:
    /// `n_i[k]` = n·wi, `n_o[k]` = n·wo, `i_o[k]` = wi·wo (the shader form of [`Dots`], built
    /// with [`Dots::new`]: near-mirror pairs near the horizon lose accuracy in n·h, as
    /// documented there).
    DotsSoa -> Dots::new {
        /// cos θi = n·wi.
        n_i,
        /// cos θo = n·wo.
        n_o,
        /// wi·wo.
        i_o,
    }
}

impl<T: Real> DotsSoa<'_, T> {
    /// The common length, or the first mismatch against `out_len`.
    fn len_with(&self, out_len: usize) -> Result<usize, BatchError> {
        let [a, b, c] = self.lens();
        same_len(&[a, b, c, out_len])
    }
}

soa3! {
    /// Unit local-frame directions as structure of arrays: `x[k]`, `y[k]`, `z[k]`.
    Vec3Soa -> Vec3::new {
        /// x components.
        x,
        /// y components.
        y,
        /// z components (along the normal).
        z,
    }
}

/// The paper's modified G = min(GM, GS) (eqs 6–13, docs/conventions.md §4) from in-plane angles
/// in radians (θi ∈ [0, π/2], θr ∈ [−π/2, π/2] signed): `out[k] = g.g(theta_i[k], theta_r[k])`.
pub fn g_modified<T: Real, R: Rule>(
    g: &ModifiedG<T, R>,
    theta_i: &[T],
    theta_r: &[T],
    out: &mut [T],
) -> Result<(), BatchError> {
    map2(theta_i, theta_r, out, |ti, tr| g.g(ti, tr))
}

/// The modified G from dot products (reciprocal 3-D extension, [`ModifiedG::g_dots`]):
/// `out[k] = g.g_dots(d[k])`; 0 for a direction at or below the horizon.
pub fn g_modified_dots<T: Real, R: Rule>(
    g: &ModifiedG<T, R>,
    d: DotsSoa<'_, T>,
    out: &mut [T],
) -> Result<(), BatchError> {
    map_dots(d, out, |dk| g.g_dots(dk))
}

/// Blinn's V-groove G (paper eq 4) from dot products:
/// `out[k] = min(1, 2(n·h)(n·wo)/(wo·h), 2(n·h)(n·wi)/(wo·h))`, see [`masking::g_blinn_dots`].
pub fn g_blinn_dots<T: Real>(d: DotsSoa<'_, T>, out: &mut [T]) -> Result<(), BatchError> {
    map_dots(d, out, |dk| masking::g_blinn_dots(dk))
}

/// Height-correlated Smith–Beckmann G = 1/(1 + Λ(θi) + Λ(θo)) (docs/conventions.md §6) for
/// Beckmann roughness `m` = √2σ, from the cosines n·wi and n·wo.
pub fn g_smith_beckmann_correlated<T: Real>(
    cos_i: &[T],
    cos_o: &[T],
    m: T,
    out: &mut [T],
) -> Result<(), BatchError> {
    map2(cos_i, cos_o, out, |ci, co| {
        Beckmann::g_correlated_cos(ci, co, m)
    })
}

/// Height-correlated Smith–GGX G = 1/(1 + Λ(θi) + Λ(θo)), Λ = (√(1 + α² tan²θ) − 1)/2,
/// from the cosines n·wi and n·wo: the scalar kernel's own pieces
/// ([`crate::microfacet::TrowbridgeReitz`]'s Λ split around its square root), so every value
/// equals [`TrowbridgeReitz::g_correlated_cos`] bit for bit.
pub fn g_smith_ggx_correlated<T: BatchReal>(
    cos_i: &[T],
    cos_o: &[T],
    alpha: T,
    out: &mut [T],
) -> Result<(), BatchError> {
    let a2 = |c: T| v_a2(c, c, alpha).0;
    map_ggx_roots(
        cos_i,
        cos_o,
        alpha,
        out,
        |ci, co, si, so| {
            let li = lambda_finish(ci, a2(ci), si);
            let lo = lambda_finish(co, a2(co), so);
            let g = T::ONE / (T::ONE + li + lo);
            if alpha.is_nan() {
                T::NAN
            } else {
                g
            }
        },
        |ci, co| TrowbridgeReitz::g_correlated_cos(ci, co, alpha),
    )
}

/// Height-correlated Smith–GGX visibility V = G/(4 cos θi cos θo) in its grazing-safe
/// closed form ([`TrowbridgeReitz::v_correlated_cos`], docs/conventions.md §8), in 1 (unitless),
/// from the scalar kernel's own pieces.
pub fn v_smith_ggx_correlated<T: BatchReal>(
    cos_i: &[T],
    cos_o: &[T],
    alpha: T,
    out: &mut [T],
) -> Result<(), BatchError> {
    map_ggx_roots(
        cos_i,
        cos_o,
        alpha,
        out,
        |ci, co, r_i, r_o| v_finish(ci, co, r_i, r_o, alpha),
        |ci, co| TrowbridgeReitz::v_correlated_cos(ci, co, alpha),
    )
}

/// The Torrance–Sparrow BRDF (paper eq 3, docs/conventions.md §5) from dot products, in 1/sr:
/// `out[k] = ts.eval_dots(d[k])`, with whichever G the model was built with.
pub fn torrance_sparrow<T: Real, R: Rule>(
    ts: &TorranceSparrow<T, R>,
    d: DotsSoa<'_, T>,
    out: &mut [T],
) -> Result<(), BatchError> {
    map_dots(d, out, |dk| ts.eval_dots(dk))
}

/// Any model's f(wi, wo) ([`Brdf::eval`], 1/sr per channel) over unit local-frame
/// directions; the three channels go to `out[0]`, `out[1]`, `out[2]`.
pub fn brdf_eval<T: Real, B: Brdf<T> + ?Sized>(
    b: &B,
    wi: Vec3Soa<'_, T>,
    wo: Vec3Soa<'_, T>,
    out: [&mut [T]; 3],
) -> Result<(), BatchError> {
    let [r, g, bl] = out;
    let ([ix, iy, iz], [ox, oy, oz]) = (wi.lens(), wo.lens());
    same_len(&[ix, iy, iz, ox, oy, oz, r.len(), g.len(), bl.len()])?;
    let outs = r.iter_mut().zip(g.iter_mut()).zip(bl.iter_mut());
    for (((or, og), ob), (i, o)) in outs.zip(wi.iter().zip(wo.iter())) {
        let f = b.eval(i, o);
        *or = f.r;
        *og = f.g;
        *ob = f.b;
    }
    Ok(())
}

//! Vectors, the local shading frame (z up) and the in-plane angle convention of the paper.
//!
//! In-plane convention (docs/conventions.md §1): light arrives from the −x side at polar angle
//! θi ∈ [0, π/2]; θr ∈ [−π/2, π/2] is signed, θr > 0 on the forward (+x) side. The mirror
//! direction is θr = θi, retro-reflection θr = −θi. Facet tilt α = (θr − θi)/2, half angle
//! between the directions β = (θi + θr)/2.

use crate::Real;

/// A 3-vector. Directions point away from the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<T> {
    /// x component (tangent direction in the local frame).
    pub x: T,
    /// y component (bitangent direction in the local frame).
    pub y: T,
    /// z component (normal direction in the local frame).
    pub z: T,
}

impl<T: Real> Vec3<T> {
    /// Builds a vector.
    #[inline]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product.
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Squared length.
    #[inline]
    pub fn length_sq(self) -> T {
        self.dot(self)
    }
    /// Scales by `s`.
    #[inline]
    pub fn scale(self, s: T) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
    /// Component-wise sum (a method, so that generic code needs no operator bounds).
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
    /// Component-wise difference.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
    /// Unit vector in the same direction; `None` for zero, subnormal-length or non-finite input.
    #[inline]
    pub fn normalize(self) -> Option<Self> {
        let l2 = self.length_sq();
        if !(l2 > T::EPSILON * T::EPSILON) || !l2.is_finite() {
            return None;
        }
        Some(self.scale(T::ONE / l2.sqrt()))
    }
    /// Unit direction from polar angle θ (from +z) and azimuth φ (from +x), radians.
    #[inline]
    pub fn from_spherical(theta: T, phi: T) -> Self {
        let s = theta.sin();
        Self::new(s * phi.cos(), s * phi.sin(), theta.cos())
    }
    /// Mirror reflection of `self` about unit `n`: 2(n·w)n − w.
    #[inline]
    pub fn reflect(self, n: Self) -> Self {
        n.scale(T::TWO * self.dot(n)).sub(self)
    }
}

/// An orthonormal frame: tangent `s`, bitangent `t`, normal `n` (z of the local frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<T> {
    /// Unit tangent (local x).
    pub s: Vec3<T>,
    /// Unit bitangent (local y), n × s.
    pub t: Vec3<T>,
    /// Unit normal (local z).
    pub n: Vec3<T>,
}

impl<T: Real> Frame<T> {
    /// A frame around `n` (normalised here), with the tangent taken from `tangent_hint`
    /// projected off `n` (Gram–Schmidt, applied twice so that the tangent is orthogonal to
    /// `n` to rounding even when the hint is nearly parallel to it); when the hint is within
    /// √ε (relative) of parallel to `n`, or degenerate, the tangent of [`Frame::from_normal`]
    /// is used. `None` when `n` is zero or not finite.
    pub fn new(n: Vec3<T>, tangent_hint: Vec3<T>) -> Option<Self> {
        let n = n.normalize()?;
        let off = |v: Vec3<T>| v.sub(n.scale(v.dot(n)));
        let h2 = tangent_hint.length_sq();
        let s1 = off(tangent_hint);
        let s = if h2.is_finite() && s1.length_sq() > T::EPSILON * h2 {
            off(s1.normalize()?).normalize()?
        } else {
            return Some(Self::from_normal(n));
        };
        let t = n.cross(s);
        Some(Self { s, t, n })
    }
    /// A branchless-style orthonormal frame around unit `n` (Duff et al. 2017, "Building an
    /// orthonormal basis, revisited"), derived as the columns of the rotation that takes z to
    /// n: R = I + K + K²/(1 + n_z) with K the cross-product matrix of z × n, so that with
    /// a = −1/(1 + n_z), b = a n_x n_y:
    /// s = R x = (1 + a n_x², b, −n_x), t = R y = (b, 1 + a n_y², −n_y).
    /// For n_z < 0 the rotation is built about −z instead (σ = sign n_z = −1):
    /// a = −1/(σ + n_z), b = a n_x n_y, s = (1 + σ a n_x², σ b, −σ n_x),
    /// t = (b, σ + a n_y², −n_y). Since |σ + n_z| ≥ 1 there is no cancellation: s and t are
    /// unit and orthogonal to n within a few ε for every unit n.
    pub fn from_normal(n: Vec3<T>) -> Self {
        let sign = if n.z >= T::ZERO { T::ONE } else { -T::ONE };
        let a = -T::ONE / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(T::ONE + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }
    /// World → local (z = normal).
    #[inline]
    pub fn to_local(&self, w: Vec3<T>) -> Vec3<T> {
        Vec3::new(w.dot(self.s), w.dot(self.t), w.dot(self.n))
    }
    /// Local → world.
    #[inline]
    pub fn to_world(&self, w: Vec3<T>) -> Vec3<T> {
        self.s
            .scale(w.x)
            .add(self.t.scale(w.y))
            .add(self.n.scale(w.z))
    }
}

/// The in-plane directions of the paper's Fig. 1 for (θi, θr): the direction toward the light
/// `(−sin θi, 0, cos θi)` and the viewing direction `(sin θr, 0, cos θr)` (θr signed).
#[inline]
pub fn in_plane_directions<T: Real>(theta_i: T, theta_r: T) -> (Vec3<T>, Vec3<T>) {
    (
        Vec3::new(-theta_i.sin(), T::ZERO, theta_i.cos()),
        Vec3::new(theta_r.sin(), T::ZERO, theta_r.cos()),
    )
}

/// Clamps an incidence angle to [0, π/2] (documented behaviour for out-of-range input;
/// NaN stays NaN).
#[inline]
pub fn clamp_theta_i<T: Real>(theta_i: T) -> T {
    theta_i.clamp(T::ZERO, T::FRAC_PI_2)
}

/// Clamps a signed exit angle to [−π/2, π/2] (NaN stays NaN).
#[inline]
pub fn clamp_theta_r<T: Real>(theta_r: T) -> T {
    theta_r.clamp(-T::FRAC_PI_2, T::FRAC_PI_2)
}

/// The dot products every isotropic kernel here needs: n·wi, n·wo and wi·wo, for unit
/// vectors, plus |H_t|², the squared length of the tangential part (perpendicular to n) of
/// the unnormalised half vector H = wi + wo. The first three fix the pair up to a rotation
/// about n, so a shader that has them needs nothing else in exact arithmetic; the fourth
/// keeps the half vector exact to rounding where the three cannot.
///
/// Why the fourth number: with s = n·wi + n·wo = H·n, the half vector enters a microfacet
/// model through |H|² = |H_t|² + s², n·h = s/|H|, wi·h = |H|/2 and tan²θh = |H_t|²/s². From
/// the three dots alone |H_t|² = 2 + 2 wi·wo − s². For a nearly opposite pair (wi ≈ −wo, a
/// mirror pair near the horizon) 1 + wi·wo → 0, and wi·wo, already rounded to an absolute
/// error of about ε, leaves |H|² with a relative error of about ε/(1 + wi·wo) (1e-4 at cos
/// θ = 1e-6 in f64); |H_t|² = |H|² − s² ≈ s² tan²θh gets the same absolute error of a few
/// ε, so the exponent tan²θh/α² of a lobe of width α one of a few ε/(α² s²): a Beckmann
/// Torrance–Sparrow lobe of α = 0.05 was 7e-8 off at cos θ = 1e-3 and 9e-2 at 1e-6 in f64,
/// and 30 % at cos θ = 1e-2 in f32. Near n·h = 1 the difference also loses about ε/sin²θh
/// at any angle, which the exponent of a narrow lobe turns into a few ε/α². No formula in
/// the three dots recovers what their rounding lost. The vectors do: each component of wi +
/// wo is one correctly rounded sum, so |H_t|² from them is exact to a few ε for every pair.
///
/// Constructors: [`Dots::from_local`] and [`Dots::from_vectors`] (vectors: exact to
/// rounding everywhere), [`Dots::in_plane`] (angles: likewise), [`Dots::with_n_h`] (the
/// three dots and n·h as a shader computes it from normalize(wi + wo): no loss near the
/// horizon, but n·h's own rounding costs a few ε/α² in the exponent of D), and
/// [`Dots::new`] (the three dots alone: loses accuracy for near-mirror pairs near the
/// horizon, as above). Code that changes a field must keep `ht2` consistent with the
/// others.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dots<T> {
    /// cos θi = n·wi.
    pub n_i: T,
    /// cos θo = n·wo.
    pub n_o: T,
    /// wi·wo.
    pub i_o: T,
    /// |H_t|² = |wi + wo|² − (n·wi + n·wo)² ≥ 0, the squared tangential length of the
    /// unnormalised half vector, from the vectors when they were known.
    pub ht2: T,
}

impl<T: Real> Dots<T> {
    /// From the three dot products alone, with |H_t|² = 2 + 2 wi·wo − (n·wi + n·wo)² (0 if
    /// that is negative). Loses accuracy for near-mirror pairs near the horizon: wi·wo's
    /// rounding error ε becomes a relative error of about ε/(1 + wi·wo) on |wi + wo|², and
    /// with it on n·h, wi·h and, amplified, a microfacet BRDF (see the type's
    /// documentation). Prefer [`Dots::from_local`],
    /// [`Dots::from_vectors`] or [`Dots::with_n_h`] when the vectors or n·h are at hand.
    #[inline]
    pub fn new(n_i: T, n_o: T, i_o: T) -> Self {
        let s = n_i + n_o;
        Self {
            n_i,
            n_o,
            i_o,
            ht2: (T::TWO + T::TWO * i_o - s * s).max(T::ZERO),
        }
    }
    /// From the three dot products and n·h as a shader has it (n·normalize(wi + wo)):
    /// |H| = (n·wi + n·wo)/n·h, so |H_t|² = (n·wi + n·wo)²(1 − n·h)(1 + n·h)/n·h². That is
    /// accurate where 2 + 2 wi·wo cancels (nearly opposite pairs, where n·h ≈ 1) and
    /// ill-conditioned where n·h → 0, so it is used when 2 + 2 wi·wo < 2|n·h| (relative
    /// errors about ε/(1 + wi·wo) against ε/|n·h|), else [`Dots::new`].
    #[inline]
    pub fn with_n_h(n_i: T, n_o: T, i_o: T, n_h: T) -> Self {
        if T::TWO + T::TWO * i_o < T::TWO * n_h.abs() {
            let r = (n_i + n_o) / n_h;
            let ht2 = r * r * (T::ONE - n_h) * (T::ONE + n_h);
            if ht2.is_finite() && ht2 >= T::ZERO {
                return Self { n_i, n_o, i_o, ht2 };
            }
        }
        Self::new(n_i, n_o, i_o)
    }
    /// From unit vectors in any frame with unit normal `n`: |H_t|² = |(wi + wo) × n|².
    /// Each component of the cross product is a difference of two products, so for h
    /// nearly along an arbitrary n it keeps a relative error of about ε/sin θh (exact to
    /// rounding in the local frame, [`Dots::from_local`]).
    #[inline]
    pub fn from_vectors(wi: Vec3<T>, wo: Vec3<T>, n: Vec3<T>) -> Self {
        Self {
            n_i: n.dot(wi),
            n_o: n.dot(wo),
            i_o: wi.dot(wo),
            ht2: wi.add(wo).cross(n).length_sq(),
        }
    }
    /// From unit vectors in the local frame (z = normal): |H_t|² = (wi_x + wo_x)² +
    /// (wi_y + wo_y)², exact to a few ε for every pair.
    #[inline]
    pub fn from_local(wi: Vec3<T>, wo: Vec3<T>) -> Self {
        let (hx, hy) = (wi.x + wo.x, wi.y + wo.y);
        Self {
            n_i: wi.z,
            n_o: wo.z,
            i_o: wi.dot(wo),
            ht2: hx * hx + hy * hy,
        }
    }
    /// From the paper's in-plane angles (θr signed): wi·wo = cos(θi + θr) and
    /// H_t = sin θr − sin θi = 2 cos((θi + θr)/2) sin((θr − θi)/2), a product form without
    /// cancellation.
    #[inline]
    pub fn in_plane(theta_i: T, theta_r: T) -> Self {
        let t =
            T::TWO * ((theta_i + theta_r) * T::HALF).cos() * ((theta_r - theta_i) * T::HALF).sin();
        Self {
            n_i: theta_i.cos(),
            n_o: theta_r.cos(),
            i_o: (theta_i + theta_r).cos(),
            ht2: t * t,
        }
    }
    /// |wi + wo|² = |H_t|² + (n·wi + n·wo)².
    #[inline]
    pub fn hh(&self) -> T {
        let s = self.n_i + self.n_o;
        self.ht2.max(T::ZERO) + s * s
    }
    /// n·h = (n·wi + n·wo)/|wi + wo|, clamped to ≤ 1; 0 when wi = −wo.
    ///
    /// Precision: as good as [`Dots::ht2`]: a few ε from [`Dots::from_local`],
    /// [`Dots::in_plane`] and [`Dots::with_n_h`]; from [`Dots::new`] a relative error of
    /// about ε/(1 + wi·wo) near a mirror pair at the horizon.
    #[inline]
    pub fn n_h(&self) -> T {
        let l = self.hh().sqrt();
        if l > T::ZERO {
            ((self.n_i + self.n_o) / l).min(T::ONE)
        } else {
            T::ZERO
        }
    }
    /// wi·h = wo·h = |wi + wo|/2 (= √((1 + wi·wo)/2); precision as [`Dots::n_h`]).
    #[inline]
    pub fn i_h(&self) -> T {
        (self.hh() * T::HALF * T::HALF).sqrt()
    }
    /// An isotropic stand-in for the half vector, (|H_t|, 0, n·wi + n·wo)/|H| (isotropic
    /// distributions only depend on θh); (1, 0, 0) when wi = −wo. Its tan²θh = |H_t|²/s²
    /// is as accurate as [`Dots::ht2`], also for narrow lobes.
    #[inline]
    pub fn half_vector_iso(&self) -> Vec3<T> {
        let l = self.hh().sqrt();
        if l > T::ZERO {
            Vec3::new(
                self.ht2.max(T::ZERO).sqrt() / l,
                T::ZERO,
                (self.n_i + self.n_o) / l,
            )
        } else {
            Vec3::new(T::ONE, T::ZERO, T::ZERO)
        }
    }
}

/// The unit half vector (wi + wo)/|wi + wo| from the vectors themselves; `None` when
/// wi = −wo (or nearly: |wi + wo|² ≤ ε²). Each component of wi + wo is one correctly rounded
/// sum of the inputs, so h is exact to a few ε even for mirror pairs at the horizon, where
/// [`Dots::n_h`] is only if the dots were built from the vectors.
#[inline]
pub fn half_vector<T: Real>(wi: Vec3<T>, wo: Vec3<T>) -> Option<Vec3<T>> {
    wi.add(wo).normalize()
}

/// The unit half vector and wi·h = wo·h = |wi + wo|/2 (symmetric in wi and wo, so a model
/// built on it is reciprocal to the last bit, and without the cancellation of the dot
/// product wi·h for nearly opposite directions); `None` as [`half_vector`].
#[inline]
pub fn half_vector_and_cos<T: Real>(wi: Vec3<T>, wo: Vec3<T>) -> Option<(Vec3<T>, T)> {
    let s = wi.add(wo);
    let h = s.normalize()?;
    Some((h, s.length_sq().sqrt() * T::HALF))
}

/// The smallest cosine the kernels treat as above the horizon: √(smallest normal number),
/// 1.08e-19 for `f32` and 1.49e-154 for `f64`. Products of two such cosines are still
/// normal numbers, so 1/(4 cos θi cos θo) never divides by zero or a subnormal. A direction
/// with a smaller (or subnormal) cosine counts as at the horizon: the models return 0 for it.
#[inline]
pub fn min_cos<T: Real>() -> T {
    if T::EPSILON.to_f64() > 1e-10 {
        T::from_f64(1.0842021724855044e-19) // 2^-63 = √(2^-126)
    } else {
        T::from_f64(1.4916681462400413e-154) // 2^-511 = √(2^-1022)
    }
}

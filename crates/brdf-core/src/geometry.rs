//! Vectors, the local shading frame (z up) and the in-plane angle convention of the paper.
//!
//! In-plane convention (conventions.md §1): light arrives from the −x side at polar angle
//! θi ∈ [0, π/2]; θr ∈ [−π/2, π/2] is signed, θr > 0 on the forward (+x) side. The mirror
//! direction is θr = θi, retro-reflection θr = −θi. Facet tilt α = (θr − θi)/2, half angle
//! between the directions β = (θi + θr)/2.

use crate::Real;

/// A 3-vector. Directions point away from the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<T> {
    pub x: T,
    pub y: T,
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
    pub s: Vec3<T>,
    pub t: Vec3<T>,
    pub n: Vec3<T>,
}

impl<T: Real> Frame<T> {
    /// A frame around `n` (normalised here), with the tangent taken from `tangent_hint`
    /// projected off `n`; when the hint is parallel to `n` (or degenerate), any perpendicular
    /// tangent is used. `None` when `n` is zero or not finite.
    pub fn new(n: Vec3<T>, tangent_hint: Vec3<T>) -> Option<Self> {
        let n = n.normalize()?;
        let s = tangent_hint
            .sub(n.scale(tangent_hint.dot(n)))
            .normalize()
            .or_else(|| {
                // Duff et al.-style branchless basis would do too; this is the plain choice.
                let a = if n.x.abs() > T::from_f64(0.9) {
                    Vec3::new(T::ZERO, T::ONE, T::ZERO)
                } else {
                    Vec3::new(T::ONE, T::ZERO, T::ZERO)
                };
                a.sub(n.scale(a.dot(n))).normalize()
            })?;
        let t = n.cross(s);
        Some(Self { s, t, n })
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

/// The three dot products every isotropic kernel here needs: n·wi, n·wo and wi·wo, for unit
/// vectors. They fix the pair up to a rotation about n, so a shader that has them needs
/// nothing else.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dots<T> {
    /// cos θi = n·wi.
    pub n_i: T,
    /// cos θo = n·wo.
    pub n_o: T,
    /// wi·wo.
    pub i_o: T,
}

impl<T: Real> Dots<T> {
    /// From unit vectors in any frame with unit normal `n`.
    #[inline]
    pub fn from_vectors(wi: Vec3<T>, wo: Vec3<T>, n: Vec3<T>) -> Self {
        Self {
            n_i: n.dot(wi),
            n_o: n.dot(wo),
            i_o: wi.dot(wo),
        }
    }
    /// From unit vectors in the local frame (z = normal).
    #[inline]
    pub fn from_local(wi: Vec3<T>, wo: Vec3<T>) -> Self {
        Self {
            n_i: wi.z,
            n_o: wo.z,
            i_o: wi.dot(wo),
        }
    }
    /// From the paper's in-plane angles (θr signed): wi·wo = cos(θi + θr).
    #[inline]
    pub fn in_plane(theta_i: T, theta_r: T) -> Self {
        Self {
            n_i: theta_i.cos(),
            n_o: theta_r.cos(),
            i_o: (theta_i + theta_r).cos(),
        }
    }
    /// n·h for the unnormalised half vector wi + wo, divided by |wi + wo|: (n·wi + n·wo)/|wi+wo|.
    /// Returns 0 when wi = −wo.
    #[inline]
    pub fn n_h(&self) -> T {
        let l = (T::TWO + T::TWO * self.i_o).max(T::ZERO).sqrt();
        if l > T::ZERO {
            (self.n_i + self.n_o) / l
        } else {
            T::ZERO
        }
    }
    /// wi·h = wo·h = |wi + wo|/2 = √((1 + wi·wo)/2).
    #[inline]
    pub fn i_h(&self) -> T {
        ((T::ONE + self.i_o) * T::HALF).max(T::ZERO).sqrt()
    }
}

//! Smith's one-sided masking for a 1-D surface with Gaussian slopes (RMS σ), derived here
//! independently of `brdf_core`: with μ = cot θ and slope density N(0, σ²),
//! Λ(θ) = (1/μ) ∫_μ^∞ (q − μ) p(q) dq = (e^{−a²}/(a√π) − erfc a)/2, a = μ/(√2σ),
//! and G1 = 1/(1 + Λ). For the in-plane case this equals the Beckmann Λ with m = √2σ
//! (docs/conventions.md §6).

/// Smith's Λ(θ) for RMS slope σ (θ in radians, |θ| < π/2; Λ(0) = 0).
pub fn lambda(theta: f64, sigma: f64) -> f64 {
    let t = theta.abs();
    if t == 0.0 {
        return 0.0;
    }
    let a = t.cos() / t.sin() / brdf_core::roughness::beckmann_m_from_sigma(sigma);
    if a > 26.0 {
        return 0.0;
    }
    0.5 * ((-a * a).exp() / (a * std::f64::consts::PI.sqrt()) - libm::erfc(a))
}

/// Smith's G1(θ) = 1/(1 + Λ(θ)).
pub fn g1(theta: f64, sigma: f64) -> f64 {
    1.0 / (1.0 + lambda(theta, sigma))
}

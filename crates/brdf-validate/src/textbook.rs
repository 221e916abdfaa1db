//! Numerical evidence for the two typos of Fundamentals of Computer Graphics ch. 24
//! (docs/conventions.md §7), computed here from the printed formulas with no project code.

/// Directional albedo at incidence θ of the coupled model eq 24.3 with R_m = 1 and an ideal
/// mirror as ρ_s (albedo 1), for the matte constant `k`:
/// a(θ) = F(θ) + 2πk [1 − (1 − cos θ)^5] ∫₀¹ [1 − (1 − c)^5] c dc, F(θ) = R0 + (1 − cos θ)^5 (1 − R0).
/// The integral is done by a 2000-point midpoint rule (exact value 10/21).
pub fn coupled_albedo(theta: f64, r0: f64, k: f64) -> f64 {
    let c = theta.cos();
    let f = r0 + (1.0 - c).powi(5) * (1.0 - r0);
    let n = 2000;
    let integral: f64 = (0..n)
        .map(|i| {
            let x = (i as f64 + 0.5) / n as f64;
            (1.0 - (1.0 - x).powi(5)) * x
        })
        .sum::<f64>()
        / n as f64;
    f + 2.0 * std::f64::consts::PI * k * (1.0 - (1.0 - c).powi(5)) * integral
}

/// The printed k of eq 24.2/24.3: 21/(20π(1 − R0)).
pub fn k_printed(r0: f64) -> f64 {
    21.0 / (20.0 * std::f64::consts::PI * (1.0 - r0))
}

/// The energy-conserving k: 21(1 − R0)/(20π).
pub fn k_conserving(r0: f64) -> f64 {
    21.0 * (1.0 - r0) / (20.0 * std::f64::consts::PI)
}

/// Eq 24.5 (Ashikhmin–Shirley specular, F = 1) for an isotropic lobe n_u = n_v = n with the
/// exponent n (1 − 0 · …) written with angles: √((n+1)(n+1))/(8π) (n·h)^n / ((h·k)max(cos θi, cos θo)).
/// Returns (eq 24.5, eq 24.9 as printed, eq 24.9 with the denominator outside the exponent)
/// for in-plane directions θi (light side) and θo (signed, forward positive), radians.
pub fn eq_24_9_forms(n: f64, theta_i: f64, theta_o: f64) -> (f64, f64, f64) {
    let ki = [-theta_i.sin(), theta_i.cos()];
    let ko = [theta_o.sin(), theta_o.cos()];
    let hl = ((ki[0] + ko[0]).powi(2) + (ki[1] + ko[1]).powi(2)).sqrt();
    let h = [(ki[0] + ko[0]) / hl, (ki[1] + ko[1]) / hl];
    let nh = h[1];
    let hk = h[0] * ki[0] + h[1] * ki[1];
    let den = hk * theta_i.cos().max(theta_o.cos());
    let pre = (n + 1.0) / (8.0 * std::f64::consts::PI);
    // In plane: h·u = sin θh, h·v = 0, so the exponent's numerator is n sin²θh/(1 − cos²θh) = n.
    let expo = n * h[0] * h[0] / (1.0 - nh * nh);
    let eq5 = pre * nh.powf(n) / den;
    let printed = pre * nh.powf(expo / den);
    let fixed = pre * nh.powf(expo) / den;
    (eq5, printed, fixed)
}

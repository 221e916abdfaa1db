//! Directional albedo R(θo) = ∫ f cos θi dωi of every reflection model of `brdf_core`,
//! computed with `brdf_core::albedo::directional_albedo` (mean over the RGB channels).

use crate::figures::{self, Lines};
use anyhow::Result;
use brdf_core::albedo::directional_albedo;
use brdf_core::geometry::Vec3;
use brdf_core::models::*;
use plotters::style::RGBColor;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

type Boxed = Box<dyn Brdf<f64> + Send + Sync>;

/// The models and the parameters the figure uses (white, F0/ks = 1 where a model has one so
/// that the curve shows the model's own energy behaviour).
pub fn models() -> Vec<(String, Boxed)> {
    let one = Rgb::splat(1.0);
    let zero = Rgb::splat(0.0);
    let m = brdf_core::roughness::beckmann_m_from_sigma(0.3);
    let mut v: Vec<(String, Boxed)> = Vec::new();
    let mut push = |name: &str, b: Result<Boxed, brdf_core::error::ParamError>| {
        if let Ok(b) = b {
            v.push((name.to_string(), b));
        }
    };
    push(
        "Lambert (ρ = 1)",
        Lambert::new(one).map(|b| Box::new(b) as Boxed),
    );
    push(
        "Phong normalised (ks = 1, n = 50)",
        PhongNormalized::new(zero, one, 50.0).map(|b| Box::new(b) as Boxed),
    );
    push(
        "Blinn-Phong normalised (ks = 1, n = 50)",
        BlinnPhongNormalized::new(zero, one, 50.0).map(|b| Box::new(b) as Boxed),
    );
    for g in [
        GeometricTerm::None,
        GeometricTerm::Blinn,
        GeometricTerm::Modified,
        GeometricTerm::SmithSeparable,
        GeometricTerm::SmithCorrelated,
    ] {
        push(
            &format!("Cook–Torrance, σ = 0.3, R0 = 1, G = {}", g.name()),
            CookTorrance::new(zero, one, m, 1.0, g).map(|b| Box::new(b) as Boxed),
        );
    }
    push(
        "Lambert + mirror mix (ρd = 1, rs = 0.04)",
        LambertSpecularMix::new(one, 0.04).map(|b| Box::new(b) as Boxed),
    );
    push(
        "Shirley damped (ρd = 1, R0 = 0.04)",
        ShirleyDamped::new(one, 0.04).map(|b| Box::new(b) as Boxed),
    );
    push(
        "coupled eq 24.3, k conserving (Rm = 1, R0 = 0.04)",
        CoupledSmooth::new(one, 0.04, CoupledK::Conserving).map(|b| Box::new(b) as Boxed),
    );
    push(
        "coupled eq 24.3, k as printed (Rm = 1, R0 = 0.04)",
        CoupledSmooth::new(one, 0.04, CoupledK::Printed).map(|b| Box::new(b) as Boxed),
    );
    push(
        "Ashikhmin–Shirley (Rs = 1, Rd = 0, n = 100)",
        AshikhminShirley::new(one, zero, 100.0, 100.0).map(|b| Box::new(b) as Boxed),
    );
    push(
        "Bank (ks = 1, n = 50)",
        Bank::new(zero, one, 50.0, BankTangent::Azimuth(0.0)).map(|b| Box::new(b) as Boxed),
    );
    push(
        "Ward (ρs = 1, α = 0.3)",
        Ward::new(zero, one, 0.3, 0.3).map(|b| Box::new(b) as Boxed),
    );
    push(
        "GGX (F0 = 1, α = 0.3, correlated)",
        Ggx::new(
            one,
            0.3,
            SmithForm::Correlated,
            MicrofacetSampling::VisibleNormals,
        )
        .map(|b| Box::new(b) as Boxed),
    );
    v
}

fn palette(i: usize) -> RGBColor {
    const C: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = C[i % C.len()];
    let k = (i / C.len()) as u8;
    RGBColor(
        r.saturating_sub(60 * k),
        g.saturating_sub(60 * k),
        b.saturating_sub(60 * k),
    )
}

/// Writes the albedo figure and returns the markdown paragraph (with a small table).
pub fn write(dir: &Path) -> Result<String> {
    let ms = models();
    // 0°, 5°, …, 85°, 87°, 89°: brdf-core's albedo quadrature is costly for the models whose
    // G is itself an integral, so the curves are sampled coarsely, in parallel.
    let mut angles: Vec<f64> = (0..=17).map(|k| 5.0 * k as f64).collect();
    angles.extend([87.0, 89.0]);
    let jobs: Vec<(usize, f64)> = (0..ms.len())
        .flat_map(|i| angles.iter().map(move |&t| (i, t)))
        .collect();
    let values: Vec<f64> = jobs
        .par_iter()
        .map(|&(i, t)| {
            let r = t.to_radians();
            let wo = Vec3::new(r.sin(), 0.0, r.cos());
            directional_albedo(ms[i].1.as_ref(), wo).mean()
        })
        .collect();
    let curves: Vec<(String, Vec<(f64, f64)>)> = ms
        .iter()
        .enumerate()
        .map(|(i, (name, _))| {
            let pts = angles
                .iter()
                .enumerate()
                .map(|(k, &t)| (t, values[i * angles.len() + k]))
                .collect();
            (name.clone(), pts)
        })
        .collect();
    let ymax = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| p.1))
        .filter(|x| x.is_finite())
        .fold(1.0f64, f64::max)
        .min(2.0);
    let fig = Lines {
        title: "Directional albedo R(θo) = ∫ f cos θi dωi".into(),
        x_desc: "θo (degrees)".into(),
        y_desc: "R".into(),
        x: (0.0, 90.0),
        y: (0.0, (ymax * 1.05 * 10.0).ceil() / 10.0),
        series: curves
            .iter()
            .enumerate()
            .map(|(i, (n, p))| (n.clone(), palette(i), p.clone()))
            .collect(),
    };
    figures::write(dir, "albedo_models", (1000, 720), &fig)?;
    let mut md = String::from(
        "Directional albedo of every reflection model in `brdf_core::models` (brdf-core's fixed quadrature, \
         `brdf_core::albedo::directional_albedo`; mean of the RGB channels):\n\n\
         ![Directional albedo](figures/albedo_models.svg)\n\n| model | R(0°) | R(60°) | R(85°) |\n|---|---|---|---|\n",
    );
    for (n, p) in &curves {
        let at = |t: f64| p.iter().find(|q| q.0 == t).map_or(f64::NAN, |q| q.1);
        let _ = writeln!(
            md,
            "| {n} | {:.4} | {:.4} | {:.4} |",
            at(0.0),
            at(60.0),
            at(85.0)
        );
    }
    Ok(md)
}

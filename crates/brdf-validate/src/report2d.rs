//! `cargo xtask plot --3d`: runs the 3-D study, writes `docs/validation-2d.json`, the error
//! maps in `docs/figures/` and §7 of `docs/validation.md` (between the markers below; the
//! 1-D report keeps that section when it rewrites the file). Every number of §7 is read from
//! the JSON value that is written, rounded to 4 decimals, so the JSON holds all of them.

use crate::figures::{self, diverging, model_color, pe, Figure};
use crate::smith1d;
use crate::study::Model;
use crate::study2d::{
    err2d, make_fields, reciprocity, sweep2d, Cell2d, Settings2d, Surface2d, Sweep2d,
};
use crate::surface::mix_seed;
use crate::surface2d::{Field, NODES_PER_ELL};
use anyhow::{Context as _, Result};
use minijinja::{AutoEscape, Environment, UndefinedBehavior, Value};
use plotters::coord::Shift;
use plotters::prelude::*;
use serde_json::{json, Value as Json};
use std::path::Path;
use std::time::Instant;

/// Standard error the identity rows are run to (below the 0.005).
const SE_TARGET: f64 = 0.0045;

pub use crate::document::{existing_section, splice, BEGIN, END};

/// What a 3-D run produced.
pub struct Outcome2d {
    /// The generated section (markers included).
    pub section: String,
    /// The JSON text written to docs/validation-2d.json.
    pub json: String,
    /// Wall time in seconds (printed, not written: the outputs are reproducible).
    pub seconds: f64,
}

/// Rounds to 4 decimals (the precision the report states).
fn r4(x: f64) -> f64 {
    if x.is_finite() {
        (x * 1e4).round() / 1e4
    } else {
        x
    }
}

/// Runs the study and writes its outputs under `root`.
pub fn run(root: &Path, s: &Settings2d) -> Result<Outcome2d> {
    let t0 = Instant::now();
    figures::register_font()?;
    let fields = make_fields(s);
    let n_cells = (s.grid().len() * s.run.sigmas.len()) as u64;
    let pb = crate::progress::bar(n_cells, "simulating (θi, θo, φ, σ)");
    let sweeps: Vec<Sweep2d> = s
        .run
        .sigmas
        .iter()
        .map(|&sg| sweep2d(s, &fields, sg, &pb))
        .collect();
    pb.finish_and_clear();
    let data = json!({
        "settings": settings_json(s),
        "surface": surface_json(&fields),
        "checks": checks_json(s, &fields, &sweeps),
        "errors": errors_json(&sweeps),
        "sweeps": sweeps.iter().map(sweep_json).collect::<Vec<_>>(),
    });
    let fig_dir = root.join("docs").join("figures");
    let mut figs = Vec::new();
    for &ti in s.theta_i.iter().filter(|&&t| t > 0.0) {
        let name = format!("g3_error_theta_i{ti}");
        figs.push(json!({"theta_i": ti, "file": format!("figures/{name}.svg")}));
        let h = 230 * sweeps.len() as u32 + 70;
        figures::write(
            &fig_dir,
            &name,
            (1600, h),
            &Map2d {
                sweeps: &sweeps,
                ti,
                lim: 0.5,
            },
        )?;
    }
    let mut data = data;
    data["figures"] = Json::from(figs);
    let json_text = serde_json::to_string_pretty(&data)? + "\n";
    crate::document::replace_file(
        &root.join("docs").join("validation-2d.json"),
        json_text.as_bytes(),
    )?;
    let section = fill(&data)?;
    let md_path = root.join("docs").join("validation.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    crate::document::replace_file(&md_path, splice(&old, &section).as_bytes())?;
    Ok(Outcome2d {
        section,
        json: json_text,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Re-renders §7 of `<root>/docs/validation.md` from `<root>/docs/validation-2d.json` (for
/// template changes without a new simulation; the full run renders from the same value).
pub fn rerender(root: &Path) -> Result<String> {
    let text = std::fs::read_to_string(root.join("docs").join("validation-2d.json"))?;
    let data: Json = serde_json::from_str(&text)?;
    let section = fill(&data)?;
    let md_path = root.join("docs").join("validation.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    crate::document::replace_file(&md_path, splice(&old, &section).as_bytes())?;
    Ok(section)
}

/// The section template.
const TEMPLATE: &str = include_str!("../templates/validation2d.md");

/// Renders the section from the JSON value.
fn fill(data: &Json) -> Result<String> {
    let mut env = Environment::new();
    env.set_auto_escape_callback(|_| AutoEscape::None);
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_trim_blocks(true);
    env.set_keep_trailing_newline(true);
    env.add_template("validation2d", TEMPLATE)
        .context("parsing the 3-D report template")?;
    let body = env
        .get_template("validation2d")?
        .render(Value::from_serialize(data))
        .context("rendering the 3-D report template")?;
    Ok(format!("{BEGIN}\n{}\n{END}\n", body.trim_end()))
}

fn settings_json(s: &Settings2d) -> Json {
    json!({
        "name": s.name,
        "nodes_per_side": 1u64 << s.run.log2_nodes,
        "nodes_per_ell": NODES_PER_ELL,
        "fields": s.run.surfaces,
        "batches": s.run.surfaces * s.run.batches_per_surface,
        "samples_per_cell": s.run.samples_per_cell(),
        "sigmas": s.run.sigmas,
        "theta_i": s.theta_i,
        "theta_o": s.theta_o,
        "phi": s.phi,
        "seed": s.run.seed,
    })
}

/// Kolmogorov–Smirnov distance of the slope samples from N(0, 1), and their excess kurtosis.
fn slope_distribution(f: &Field) -> (f64, f64) {
    let mut v = f.slope_samples();
    let n = v.len() as f64;
    let m2 = v.iter().map(|x| x * x).sum::<f64>() / n;
    let m4 = v.iter().map(|x| x.powi(4)).sum::<f64>() / n;
    v.sort_by(|a, b| a.total_cmp(b));
    let phi = |x: f64| 0.5 * libm::erfc(-x / std::f64::consts::SQRT_2);
    let ks = v.iter().enumerate().fold(0.0f64, |d, (k, &x)| {
        let c = phi(x);
        d.max((c - k as f64 / n).abs())
            .max(((k + 1) as f64 / n - c).abs())
    });
    (ks, m4 / (m2 * m2) - 3.0)
}

fn surface_json(fields: &[Field]) -> Json {
    let l = NODES_PER_ELL as i64;
    let rows: Vec<Json> = fields
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let (sx, sy) = f.realised_slope_rms();
            let (ks, kurt) = slope_distribution(f);
            json!({
                "field": i,
                "slope_rms_x": r4(sx), "slope_rms_y": r4(sy),
                "autocorrelation_x": r4(f.realised_autocorrelation(l, 0)),
                "autocorrelation_y": r4(f.realised_autocorrelation(0, l)),
                "autocorrelation_diagonal": r4(f.realised_autocorrelation(l, l)),
                "ks_distance": r4(ks), "excess_kurtosis": r4(kurt),
                "triangle_slope_correlation": r4(f.realised_slope_correlation()),
            })
        })
        .collect();
    json!({
        "fields": rows,
        "target_autocorrelation_axis": r4((-1.0f64).exp()),
        "target_autocorrelation_diagonal": r4((-2.0f64).exp()),
        "expected_triangle_slope_correlation": fields.first().map(|f| r4(f.expected_slope_correlation())),
    })
}

/// Projected-area identity and area-weighted G1 against Smith on isotropic surfaces (random
/// azimuth) and on one anisotropic surface (σx, σy) = (0.2, 0.5) at fixed azimuths.
fn identity_rows(s: &Settings2d, fields: &[Field]) -> Vec<Json> {
    let per_b = s.run.per_batch * 4;
    let mut cases: Vec<((f64, f64), bool, f64, f64)> = Vec::new();
    for &sg in s.run.sigmas.iter().filter(|x| [0.1, 0.3, 1.0].contains(*x)) {
        for th in [30.0, 60.0, 80.0, 88.0] {
            cases.push(((sg, sg), true, th, 0.0));
        }
    }
    for psi in [0.0, 45.0, 90.0] {
        for th in [60.0, 80.0] {
            cases.push(((0.2, 0.5), false, th, psi));
        }
    }
    cases
        .iter()
        .map(|&(sig, random_azimuth, th, psi)| {
            let surf = Surface2d { fields, sigma: sig, random_azimuth };
            let seed = mix_seed(&[s.run.seed, 77, th as u64, psi as u64, (sig.0 * 1e3) as u64, (sig.1 * 1e3) as u64]);
            let run = |per: u64| surf.g1_area(th.to_radians(), psi.to_radians(), per, s.run.batches_per_surface, seed);
            // A pilot run sets the sample count that brings both SEs to ≤ SE_TARGET.
            let (g1p, idp) = run(per_b);
            let k = (idp.se().max(g1p.se()) / SE_TARGET).powi(2).ceil().max(1.0) as u64;
            let (g1, id) = if k > 1 { run(per_b * k) } else { (g1p, idp) };
            let n = per_b * k.max(1) * s.run.batches_per_surface * fields.len() as u64;
            let p = psi.to_radians();
            let s_eff = (sig.0 * sig.0 * p.cos().powi(2) + sig.1 * sig.1 * p.sin().powi(2)).sqrt();
            json!({
                "sigma_x": sig.0, "sigma_y": sig.1, "azimuth": if random_azimuth { Json::from("random") } else { Json::from(psi) },
                "theta": th,
                "identity": r4(id.mean), "identity_se": r4(id.se()),
                "g1": r4(g1.mean), "g1_se": r4(g1.se()),
                "smith_g1": r4(smith1d::g1(th.to_radians(), s_eff)),
                "n": n,
            })
        })
        .collect()
}

fn checks_json(s: &Settings2d, fields: &[Field], sweeps: &[Sweep2d]) -> Json {
    let normal: Vec<Json> = sweeps
        .iter()
        .filter_map(|sw| {
            let c = sw.cells.iter().find(|c| c.geom[0] == 0.0 && c.geom[1] == 0.0)?;
            Some(json!({"sigma": sw.sigma, "g": r4(c.sim.g.mean), "gm": r4(c.sim.gm.mean), "gs": r4(c.sim.gs.mean), "n": c.sim.g.n}))
        })
        .collect();
    let recip: Vec<Json> = sweeps
        .iter()
        .map(|sw| {
            let (n, rms, max) = reciprocity(sw);
            json!({"sigma": sw.sigma, "pairs": n, "rms_z": r4(rms), "max_z": r4(max)})
        })
        .collect();
    let smith_g1: Vec<Json> = sweeps
        .iter()
        .map(|sw| {
            let mx = sw
                .cells
                .iter()
                .filter(|c| c.geom[0] == 0.0 && c.geom[1] <= 80.0)
                .map(|c| (c.sim.g.mean - smith1d::g1(c.geom[1].to_radians(), sw.sigma)).abs())
                .fold(0.0f64, f64::max);
            json!({"sigma": sw.sigma, "max_diff": r4(mx)})
        })
        .collect();
    let max_se = sweeps
        .iter()
        .flat_map(|sw| sw.cells.iter())
        .map(|c| c.sim.g.se().max(c.sim.gm.se()).max(c.sim.gs.se()))
        .fold(0.0f64, f64::max);
    let identity = identity_rows(s, fields);
    let max_se = identity
        .iter()
        .flat_map(|r| [r["identity_se"].as_f64(), r["g1_se"].as_f64()])
        .flatten()
        .fold(max_se, f64::max);
    json!({
        "normal_incidence": normal,
        "identity": identity,
        "reciprocity": recip,
        "g0_vs_smith_g1": smith_g1,
        "max_se": r4(max_se),
    })
}

/// A subset of the cells.
type Keep = Box<dyn Fn(&Cell2d) -> bool>;

fn errors_json(sweeps: &[Sweep2d]) -> Json {
    let both = |c: &Cell2d| c.geom[0] > 0.0 && c.geom[1] > 0.0;
    let subsets: [(&str, Keep); 7] = [
        ("all", Box::new(|_| true)),
        ("in_plane", Box::new(move |c| both(c) && c.in_plane())),
        ("out_of_plane", Box::new(move |c| both(c) && !c.in_plane())),
        (
            "in_plane_not_grazing",
            Box::new(move |c| both(c) && c.in_plane() && !c.grazing()),
        ),
        (
            "out_of_plane_not_grazing",
            Box::new(move |c| both(c) && !c.in_plane() && !c.grazing()),
        ),
        ("grazing", Box::new(|c| c.grazing())),
        ("not_grazing", Box::new(|c| !c.grazing())),
    ];
    let rows: Vec<Json> = sweeps
        .iter()
        .flat_map(|sw| {
            Model::ALL
                .iter()
                .enumerate()
                .map(move |(k, m)| (sw, k, *m))
                .collect::<Vec<_>>()
        })
        .map(|(sw, k, m)| {
            let mut o = serde_json::Map::new();
            o.insert("sigma".into(), json!(sw.sigma));
            o.insert("model".into(), json!(m.name()));
            for (name, keep) in &subsets {
                let e = err2d(sw, k, keep);
                o.insert(
                    (*name).into(),
                    json!({"rms": r4(e.rms), "max": r4(e.max), "argmax": e.argmax, "cells": e.n}),
                );
            }
            Json::Object(o)
        })
        .collect();
    json!({"models": rows, "modified_terms": sweeps.iter().map(terms_json).collect::<Vec<_>>()})
}

/// Why the modified G fails: its GM and GS against the simulated ones, and what taking
/// min(GM, GS) or GM·GS of the *true* terms costs against the true G.
fn terms_json(sw: &Sweep2d) -> Json {
    let rms = |f: &dyn Fn(&Cell2d) -> f64| {
        let s2: f64 = sw.cells.iter().map(|c| f(c).powi(2)).sum();
        r4((s2 / sw.cells.len().max(1) as f64).sqrt())
    };
    json!({
        "sigma": sw.sigma,
        "gm_rms": rms(&|c| c.modified_gm_gs.0 - c.sim.gm.mean),
        "gs_rms": rms(&|c| c.modified_gm_gs.1 - c.sim.gs.mean),
        "true_min_rms": rms(&|c| c.sim.gm.mean.min(c.sim.gs.mean) - c.sim.g.mean),
        "true_product_rms": rms(&|c| c.sim.gm.mean * c.sim.gs.mean - c.sim.g.mean),
    })
}

fn sweep_json(sw: &Sweep2d) -> Json {
    let cells: Vec<Json> = sw
        .cells
        .iter()
        .map(|c| {
            let models: serde_json::Map<String, Json> = Model::ALL
                .iter()
                .zip(c.models)
                .map(|(m, v)| (m.slug().to_string(), json!(r4(v))))
                .collect();
            json!({
                "theta_i": c.geom[0], "theta_o": c.geom[1], "phi": c.geom[2],
                "g": r4(c.sim.g.mean), "g_se": r4(c.sim.g.se()),
                "gm": r4(c.sim.gm.mean), "gm_se": r4(c.sim.gm.se()),
                "gs": r4(c.sim.gs.mean), "gs_se": r4(c.sim.gs.se()),
                "n": c.sim.g.n,
                "models": models,
                "modified_gm": r4(c.modified_gm_gs.0), "modified_gs": r4(c.modified_gm_gs.1),
            })
        })
        .collect();
    json!({"sigma": sw.sigma, "cells": cells})
}

/// Error maps G_model − G_true over (φ, θo) at one θi: one row per σ, one column per model.
pub struct Map2d<'a> {
    /// The sweeps.
    pub sweeps: &'a [Sweep2d],
    /// The fixed θi, degrees.
    pub ti: f64,
    /// Colour-scale limit.
    pub lim: f64,
}

/// Cell edges halfway between sorted grid values (the outer ones mirrored).
fn edges(v: &[f64]) -> Vec<(f64, f64)> {
    (0..v.len())
        .map(|k| {
            let lo = if k == 0 {
                v[0] - 0.5 * (v.get(1).unwrap_or(&v[0]) - v[0])
            } else {
                0.5 * (v[k - 1] + v[k])
            };
            let hi = if k + 1 == v.len() {
                v[k] + (v[k] - lo)
            } else {
                0.5 * (v[k] + v[k + 1])
            };
            (lo, hi)
        })
        .collect()
}

impl Figure for Map2d<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (body, bar) = root.split_vertically(root.dim_in_pixel().1 - 70);
        let panels = body.split_evenly((self.sweeps.len(), Model::ALL.len()));
        for (r, sw) in self.sweeps.iter().enumerate() {
            let row: Vec<&Cell2d> = sw.cells.iter().filter(|c| c.geom[0] == self.ti).collect();
            let mut tos: Vec<f64> = row.iter().map(|c| c.geom[1]).collect();
            let mut phis: Vec<f64> = row.iter().map(|c| c.geom[2]).collect();
            for v in [&mut tos, &mut phis] {
                v.sort_by(|a, b| a.total_cmp(b));
                v.dedup();
            }
            let (et, ep) = (edges(&tos), edges(&phis));
            for (k, m) in Model::ALL.iter().enumerate() {
                let title = format!("{}, σ = {}", m.name(), sw.sigma);
                let mut chart = ChartBuilder::on(&panels[r * Model::ALL.len() + k])
                    .caption(
                        title,
                        ("sans-serif", 14).into_font().color(&model_color(*m)),
                    )
                    .margin(6)
                    .x_label_area_size(28)
                    .y_label_area_size(32)
                    .build_cartesian_2d(ep[0].0..ep[ep.len() - 1].1, et[0].0..et[et.len() - 1].1)
                    .map_err(pe)?;
                chart
                    .configure_mesh()
                    .disable_mesh()
                    .x_desc("φ (0 back, 180 forward)")
                    .y_desc("θo")
                    .x_labels(7)
                    .y_labels(5)
                    .label_style(("sans-serif", 11))
                    .draw()
                    .map_err(pe)?;
                chart
                    .draw_series(row.iter().map(|c| {
                        let a = phis.iter().position(|&p| p == c.geom[2]).unwrap_or(0);
                        let b = tos.iter().position(|&t| t == c.geom[1]).unwrap_or(0);
                        let e = c.models[k] - c.sim.g.mean;
                        Rectangle::new(
                            [(ep[a].0, et[b].0), (ep[a].1, et[b].1)],
                            diverging(e, self.lim).filled(),
                        )
                    }))
                    .map_err(pe)?;
            }
        }
        colour_bar(&bar, self.lim, self.ti)
    }
}

/// The diverging colour bar under the maps.
fn colour_bar<DB: DrawingBackend>(bar: &DrawingArea<DB, Shift>, lim: f64, ti: f64) -> Result<()> {
    let mut cb = ChartBuilder::on(bar)
        .margin_left(300)
        .margin_right(300)
        .margin_bottom(8)
        .x_label_area_size(30)
        .build_cartesian_2d(-lim..lim, 0f64..1f64)
        .map_err(pe)?;
    cb.configure_mesh()
        .disable_mesh()
        .disable_y_axis()
        .x_desc(format!(
            "θi = {ti}°: G_model − G_ray-traced (red: model too high, blue: too low)"
        ))
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(pe)?;
    let n = 200;
    cb.draw_series((0..n).map(|i| {
        let a = -lim + 2.0 * lim * i as f64 / n as f64;
        let b = a + 2.0 * lim / n as f64;
        Rectangle::new([(a, 0.0), (b, 1.0)], diverging(0.5 * (a + b), lim).filled())
    }))
    .map_err(pe)?;
    Ok(())
}

//! `cargo xtask plot`: runs the study, writes the figures and `docs/validation.md`.
//! Every number in the report is computed here; none is typed by hand.

use crate::figures::{self, Fig6, Fig7, Heat};
use crate::profile::{Profile, DX};
use crate::smith1d;
use crate::study::{
    brdf_errors, err_stats, fine_row, formula_vs_single_neighbour, grid, make_profiles, sweep,
    Model, Settings, Sweep,
};
use crate::surface::Surface;
use crate::textbook;
use anyhow::{Context as _, Result};
use brdf_core::masking::{Convention, ModifiedG};
use minijinja::{context, AutoEscape, Environment, UndefinedBehavior, Value};
use std::path::Path;
use std::time::Instant;

/// Per σ: (term, RMS, max) of the normalised BRDF curve errors.
type BrdfRow = (f64, Vec<(brdf_core::models::GeometricTerm, f64, f64)>);

/// What a run produced (also used by the tests and the command line's summary).
pub struct Outcome {
    /// The markdown text written to docs/validation.md.
    pub markdown: String,
    /// Wall time in seconds.
    pub seconds: f64,
}

fn f4(x: f64) -> String {
    format!("{x:.4}")
}

/// Runs everything and writes `<root>/docs/validation.md` and `<root>/docs/figures/*`.
pub fn run(root: &Path, s: &Settings) -> Result<Outcome> {
    let t0 = Instant::now();
    figures::register_font()?;
    let fig_dir = root.join("docs").join("figures");
    let profiles = make_profiles(s);

    // Grid sweeps.
    let cells = grid(s.step_deg);
    let fine6 = fine_row(30.0, s.fine_step_deg);
    let fine7 = fine_row(10.0, s.fine_step_deg);
    let total = (cells.len() * s.run.sigmas.len() + fine6.len() + fine7.len()) as u64;
    let pb = crate::progress::bar(total, "simulating (θi, θr, σ)");
    let sweeps: Vec<Sweep> = s
        .run
        .sigmas
        .iter()
        .map(|&sg| sweep(s, &profiles, sg, &cells, 1, &pb))
        .collect();
    let fig6 = sweep(s, &profiles, 0.3, &fine6, 2, &pb);
    let fig7 = sweep(s, &profiles, 0.3, &fine7, 3, &pb);
    pb.finish_and_clear();

    write_figures(&fig_dir, s, &sweeps, &fig6, &fig7)?;
    let albedo_note = crate::albedo_fig::write(&fig_dir)?;
    let anchors = [
        root.join(".cache").join("anchors"),
        root.join("..").join("shared").join("anchors"),
    ];
    let dfg_note = crate::dfg_fig::write(&fig_dir, &anchors)?;
    let elapsed = t0.elapsed().as_secs_f64();

    let md = markdown(
        s,
        &profiles,
        &sweeps,
        &fig6,
        &fig7,
        &[&albedo_note, &dfg_note],
    )?;
    // Keep the 3-D study's section (§7, `cargo xtask plot --3d`) when rewriting the file.
    let md_path = root.join("docs").join("validation.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    let md = match crate::document::existing_section(&old) {
        Some(sec) => crate::document::splice(&md, sec),
        None => md,
    };
    crate::document::replace_file(&md_path, md.as_bytes())?;
    Ok(Outcome {
        markdown: md,
        seconds: elapsed,
    })
}

/// The in-plane figures: Fig. 6 (G at θi = 30°), Fig. 7 (the BRDF at θi = 10°) and the
/// heat maps of the G error for σ ∈ {0.1, 0.3, 1}.
fn write_figures(
    fig_dir: &Path,
    s: &Settings,
    sweeps: &[Sweep],
    fig6: &Sweep,
    fig7: &Sweep,
) -> Result<()> {
    figures::write(
        fig_dir,
        "fig6_g_theta_i30_sigma0.3",
        (900, 620),
        &Fig6 {
            sweep: fig6,
            ti: 30.0,
        },
    )?;
    figures::write(
        fig_dir,
        "fig7_brdf_theta_i10_sigma0.3",
        (900, 620),
        &Fig7 { sweep: fig7 },
    )?;
    let heat_sigmas: Vec<&Sweep> = sweeps
        .iter()
        .filter(|w| [0.1, 0.3, 1.0].iter().any(|x| (w.sigma - x).abs() < 1e-9))
        .collect();
    figures::write(
        fig_dir,
        "heatmap_g_error",
        (1600, 270 * heat_sigmas.len() as u32 + 70),
        &Heat {
            sweeps: heat_sigmas,
            step: s.step_deg,
            lim: 0.5,
        },
    )?;
    Ok(())
}

/// The report's prose, with placeholders for the numbers `markdown` computes.
const TEMPLATE: &str = include_str!("../templates/validation.md");
/// §§5–6 (defects of the sources, conclusions), with placeholders for their numbers.
const FINDINGS: &str = include_str!("../templates/findings.md");

/// Renders a Markdown template: no escaping, undefined names are errors, a block tag's own
/// line break is dropped (so `{% for %}` lines leave no blank lines).
fn fill(name: &str, template: &str, ctx: Value) -> Result<String> {
    let mut env = Environment::new();
    env.set_auto_escape_callback(|_| AutoEscape::None);
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_trim_blocks(true);
    env.set_keep_trailing_newline(true);
    env.add_template(name, template)
        .with_context(|| format!("parsing the report template {name}"))?;
    env.get_template(name)?
        .render(ctx)
        .with_context(|| format!("rendering the report template {name}"))
}

/// RMS / max (and over the populated cells) at 3 decimals.
fn err_cells(e: &crate::study::ErrStats) -> Value {
    context! {
        rms => format!("{:.3}", e.rms),
        max => format!("{:.3}", e.max),
        rms_pop => format!("{:.3}", e.rms_pop),
        max_pop => format!("{:.3}", e.max_pop),
    }
}

/// The report up to and including the error tables (from the template), then the defects
/// and conclusions. Runs the extra simulations the checks need (G1 identity, slope bins).
fn markdown(
    s: &Settings,
    profiles: &[Profile],
    sweeps: &[Sweep],
    fig6: &Sweep,
    fig7: &Sweep,
    notes: &[&str],
) -> Result<String> {
    let n_cell = s.run.samples_per_cell();
    let bin_sweep = sweeps.iter().find(|w| (w.sigma - 0.3).abs() < 1e-9);
    let brdf_table: Vec<BrdfRow> = sweeps
        .iter()
        .map(|sw| (sw.sigma, brdf_errors(sw)))
        .collect();
    let (fig6_rows, fig6_single) = fig6_numbers(fig6);
    let mut m = fill(
        "validation.md",
        TEMPLATE,
        context! {
            run_flag => if s.name == "quick" { " --quick" } else { "" },
            name => s.name,
            profiles => s.run.surfaces,
            log2_nodes => s.run.log2_nodes,
            n_cell => n_cell,
            nb => s.run.surfaces * s.run.batches_per_surface,
            sigmas => format!("{:?}", s.run.sigmas),
            step => s.step_deg.to_string(),
            seed => s.run.seed,
            inv_dx => format!("{:.0}", 1.0 / DX),
            profile_rows => profile_rows(profiles),
            se_max => format!("{:.4}", 0.5 / (n_cell as f64).sqrt()),
            normal_rows => normal_rows(sweeps),
            g1_rows => g1_rows(s, profiles),
            reciprocity_rows => sweeps.iter().map(reciprocity_row).collect::<Vec<_>>(),
            formula_rows => sweeps.iter().map(formula_row).collect::<Vec<_>>(),
            smith_rows => sweeps.iter().map(smith_row).collect::<Vec<_>>(),
            slope_bin => bin_sweep.is_some(),
            slope_bin_rows => bin_sweep.map(|sw| slope_bin_rows(s, profiles, sw)).unwrap_or_default(),
            notes => notes,
            fig6_rows => fig6_rows,
            fig6_single => fig6_single,
            model_names => Model::ALL.iter().map(|m| m.name()).collect::<Vec<_>>(),
            error_rows => sweeps.iter().map(error_row).collect::<Vec<_>>(),
            where_rows => sweeps.iter().map(where_row).collect::<Vec<_>>(),
            brdf_rows => brdf_table.iter().map(brdf_row).collect::<Vec<_>>(),
        },
    )?;

    // 5. Defects and 6. conclusions: the prose is the second template.
    m.push_str(&fill(
        "findings.md",
        FINDINGS,
        context! {
            d => defects(sweeps, fig6, fig7, &brdf_table),
            c => conclusions(sweeps, &brdf_table),
        },
    )?);
    Ok(m)
}

/// §1: each profile's realised slope RMS and autocorrelation at a lag of one unit length.
fn profile_rows(profiles: &[Profile]) -> Vec<Value> {
    let lag = (1.0 / DX).round() as usize;
    profiles
        .iter()
        .enumerate()
        .map(|(i, p)| {
            context! {
                i => i,
                slope_rms => f4(p.realised_slope_rms()),
                autocorrelation => f4(p.realised_autocorrelation(lag)),
            }
        })
        .collect()
}

/// §2 check: the simulated G at normal incidence and exitance (θi = θr = 0) per σ.
fn normal_rows(sweeps: &[Sweep]) -> Vec<Value> {
    sweeps
        .iter()
        .filter_map(|sw| {
            let c = sw.cells.iter().find(|c| c.ti == 0.0 && c.tr == 0.0)?;
            Some(context! {
                sigma => sw.sigma.to_string(),
                g => f4(c.sim.g.mean),
                n => c.sim.g.n,
            })
        })
        .collect()
}

/// §2 check: the one-sided G1 by area (and the area identity) against Smith's G1, at
/// σ ∈ {0.1, 0.3, 1} and θ ∈ {30°, 60°, 80°, 88°} (extra simulations, four times the
/// batch size).
fn g1_rows(s: &Settings, profiles: &[Profile]) -> Vec<Value> {
    let per_b = s.run.per_batch * 4;
    let mut rows = Vec::new();
    for &sg in s.run.sigmas.iter().filter(|x| [0.1, 0.3, 1.0].contains(*x)) {
        let surf = Surface {
            profiles,
            sigma: sg,
        };
        for th in [30.0f64, 60.0, 80.0, 88.0] {
            let seed = crate::surface::mix_seed(&[77, th as u64, (sg * 1000.0) as u64]);
            let (g1, id) = surf.g1_area(th.to_radians(), per_b, s.run.batches_per_surface, seed);
            rows.push(context! {
                theta => th.to_string(),
                sigma => sg.to_string(),
                identity => f4(id.mean),
                identity_se => f4(id.se()),
                smith => f4(smith1d::g1(th.to_radians(), sg)),
                g1 => f4(g1.mean),
                g1_se => f4(g1.se()),
            });
        }
    }
    rows
}

/// §2 check, reciprocity: z = |G(θi, θr) − G(mirror)| / combined standard error over the
/// cells whose mirrored cell (θr, θi) — or (−θr, −θi) — was simulated; RMS and max of z.
fn reciprocity_row(sw: &Sweep) -> Value {
    let (mut zmax, mut z2, mut n) = (0.0f64, 0.0, 0);
    for c in &sw.cells {
        let (mi, mr) = if c.tr >= 0.0 {
            (c.tr, c.ti)
        } else {
            (-c.tr, -c.ti)
        };
        if let Some(o) = sw.cells.iter().find(|o| o.ti == mi && o.tr == mr) {
            if o.ti == c.ti && o.tr == c.tr {
                continue;
            }
            let se = (c.sim.g.se().powi(2) + o.sim.g.se().powi(2))
                .sqrt()
                .max(1e-9);
            let z = (c.sim.g.mean - o.sim.g.mean).abs() / se;
            zmax = zmax.max(z);
            z2 += z * z;
            n += 1;
        }
    }
    context! {
        n => n,
        sigma => sw.sigma.to_string(),
        rms_z => format!("{:.2}", (z2 / n.max(1) as f64).sqrt()),
        max_z => format!("{zmax:.2}"),
    }
}

/// §2 check: the paper's formula against the single-neighbour count of the same rays
/// ([`formula_vs_single_neighbour`]'s z-scores).
fn formula_row(sw: &Sweep) -> Value {
    let (zm, zs, _) = formula_vs_single_neighbour(sw);
    context! {
        sigma => sw.sigma.to_string(),
        cells => sw.cells.len(),
        z_gm => format!("{zm:.2}"),
        z_gs => format!("{zs:.2}"),
    }
}

/// §2 check: max |G(0, θr) − Smith G1(θr)| over |θr| ≤ 80° (at θi = 0 the pair G is G1).
fn smith_row(sw: &Sweep) -> Value {
    let mut dmax = 0.0f64;
    for c in sw
        .cells
        .iter()
        .filter(|c| c.ti == 0.0 && c.tr.abs() <= 80.0)
    {
        dmax = dmax.max((c.sim.g.mean - smith1d::g1(c.tr.to_radians(), sw.sigma)).abs());
    }
    context! { sigma => sw.sigma.to_string(), max_diff => f4(dmax) }
}

/// §2, slope bin effect at σ = 0.3: the cell's G beside G simulated with slope bins of
/// 0.02, 0.1 and 0.3 (extra simulations), for six (θi, θr) cells that were simulated.
fn slope_bin_rows(s: &Settings, profiles: &[Profile], sw: &Sweep) -> Vec<Value> {
    let surf = Surface {
        profiles,
        sigma: 0.3,
    };
    let mut rows = Vec::new();
    for (ti, tr) in [
        (30.0f64, 60.0f64),
        (60.0, 60.0),
        (30.0, 80.0),
        (60.0, 0.0),
        (70.0, 80.0),
        (80.0, 80.0),
    ] {
        let Some(c) = sw.cells.iter().find(|c| c.ti == ti && c.tr == tr) else {
            continue;
        };
        let bins: Vec<Value> = [0.02, 0.1, 0.3]
            .into_iter()
            .map(|b| {
                let e = surf.g_slope_bin(
                    ti.to_radians(),
                    tr.to_radians(),
                    b,
                    s.run.per_batch,
                    s.run.batches_per_surface,
                    99,
                );
                context! { g => f4(e.mean), se => f4(e.se()), n => e.n }
            })
            .collect();
        rows.push(context! {
            ti => ti.to_string(),
            tr => tr.to_string(),
            g => f4(c.sim.g.mean),
            se => f4(c.sim.g.se()),
            bins => bins,
        });
    }
    rows
}

/// §3, Fig. 6's numbers: RMS and max error of each model, and of the single-neighbour
/// count, against the simulation.
fn fig6_numbers(fig6: &Sweep) -> (Vec<Value>, Value) {
    let rows = Model::ALL
        .iter()
        .enumerate()
        .map(|(k, md)| {
            let e = err_stats(fig6, |c| c.models[k]);
            context! { name => md.name(), rms => f4(e.rms), max => f4(e.max) }
        })
        .collect();
    let e = err_stats(fig6, |c| c.sn.g.mean);
    (rows, context! { rms => f4(e.rms), max => f4(e.max) })
}

/// §4 error table row: every model's errors, then the single-neighbour count's.
fn error_row(sw: &Sweep) -> Value {
    let mut errors: Vec<Value> = (0..Model::ALL.len())
        .map(|k| err_cells(&err_stats(sw, |c| c.models[k])))
        .collect();
    errors.push(err_cells(&err_stats(sw, |c| c.sn.g.mean)));
    context! { sigma => sw.sigma.to_string(), errors => errors }
}

/// §4, where the models differ: the formula's z-scores, the smallest difference, and the
/// single-neighbour and modified G errors side by side.
fn where_row(sw: &Sweep) -> Value {
    let (zm, zs, dmin) = formula_vs_single_neighbour(sw);
    let a = err_stats(sw, |c| c.sn.g.mean);
    let b = err_stats(sw, |c| c.models[1]);
    context! {
        sigma => sw.sigma.to_string(),
        z_gm => format!("{zm:.2}"),
        z_gs => format!("{zs:.2}"),
        min_diff => format!("{dmin:.3}"),
        sn_rms => format!("{:.3}", a.rms),
        sn_max => format!("{:.3}", a.max),
        mod_rms => format!("{:.3}", b.rms),
        mod_max => format!("{:.3}", b.max),
    }
}

/// §4 BRDF table row: RMS and max of each term's normalised BRDF curve error.
fn brdf_row((sigma, errs): &BrdfRow) -> Value {
    let cells: Vec<Value> = errs
        .iter()
        .map(|(_, r, x)| context! { rms => format!("{r:.2e}"), max => format!("{x:.2e}") })
        .collect();
    context! { sigma => sigma.to_string(), errors => cells }
}

/// The numbers of §5 (defects of the sources): eq 12's sign, the normalisation C, G ≥ ½ at
/// grazing, the paper's claim, textbook eqs 24.3 and 24.9.
fn defects(sweeps: &[Sweep], fig6: &Sweep, fig7: &Sweep, brdf_rows: &[BrdfRow]) -> Value {
    let asym = asym_rows(sweeps);
    let sigma = 0.3;
    let mass_c1 = mass_c1(sigma);
    let c_core = brdf_core::distribution::SlopeDistribution::<f64>::new(sigma)
        .map(|d| d.normalisation_c())
        .unwrap_or(f64::NAN);
    // G ≥ 1/2.
    let mg = ModifiedG::<f64>::new(0.3).expect("σ > 0");
    let mut min_m90 = f64::INFINITY;
    for k in -89..=89 {
        min_m90 = min_m90.min(mg.passing(std::f64::consts::FRAC_PI_2, (k as f64).to_radians()));
    }
    let grazing: Vec<String> = fig6
        .cells
        .iter()
        .filter(|c| c.tr >= 84.0)
        .map(|c| {
            format!(
                "θr = {}°: modified {:.3}, Smith (correlated) {:.3}, simulated {:.3} ± {:.3}",
                c.tr,
                c.models[1],
                c.models[4],
                c.sim.g.mean,
                c.sim.g.se()
            )
        })
        .collect();
    let curve: Vec<String> = [80.0f64, 85.0, 88.0, 89.5]
        .iter()
        .map(|&tr| {
            let f = |g| crate::study::ts_normalised(0.3, g, 10.0, tr);
            let fm = f(brdf_core::models::GeometricTerm::Modified);
            let fs = f(brdf_core::models::GeometricTerm::SmithCorrelated);
            format!(
                "θr = {tr}°: modified {fm:.4} (× cos θr = {:.4}), Smith {fs:.4}",
                fm * tr.to_radians().cos()
            )
        })
        .collect();
    let sim88 = fig7
        .cells
        .iter()
        .rev()
        .find(|c| c.tr <= 88.0)
        .map(|c| {
            format!(
                "the ray-traced G at θi = 10°, θr = {}° is {:.3} ± {:.3}",
                c.tr,
                c.sim.g.mean,
                c.sim.g.se()
            )
        })
        .unwrap_or_default();
    let claim = paper_claim(brdf_rows);
    // Textbook.
    let r0 = 0.04;
    let albedo = |theta: f64, k: f64| format!("{:.4}", textbook::coupled_albedo(theta, r0, k));
    let (e5, e9p, e9f) = textbook::eq_24_9_forms(100.0, 30f64.to_radians(), 40f64.to_radians());
    context! {
        asym => asym,
        mass_c1_4 => format!("{mass_c1:.4}"),
        mass_c1_3 => format!("{mass_c1:.3}"),
        c_core => format!("{c_core:.4}"),
        inv_c_core => format!("{:.4}", 1.0 / c_core),
        min_m90 => format!("{min_m90:.4}"),
        grazing => grazing.join("; "),
        curve => curve.join("; "),
        sim88 => sim88,
        claim => claim,
        r0 => r0.to_string(),
        ap => albedo(0.0, textbook::k_printed(r0)),
        ap60 => albedo(60f64.to_radians(), textbook::k_printed(r0)),
        ac => albedo(0.0, textbook::k_conserving(r0)),
        e5 => format!("{e5:.5e}"),
        e9p => format!("{e9p:.5e}"),
        e9f => format!("{e9f:.5e}"),
    }
}

/// §5, eq 12: per σ, the printed convention's largest asymmetry |G(a, b) − G(mirror)|, the
/// reciprocal one's, and the printed GS's largest distance from the simulated GS.
fn asym_rows(sweeps: &[Sweep]) -> Vec<Value> {
    sweeps
        .iter()
        .map(|sw| {
            let (mut ap, mut ar, mut gs_gap) = (0.0f64, 0.0f64, 0.0f64);
            let mg = ModifiedG::<f64>::new(sw.sigma).expect("σ > 0");
            let mp = mg.with_convention(Convention::Printed);
            for c in &sw.cells {
                let (a, b) = (c.ti.to_radians(), c.tr.to_radians());
                let (mi, mr) = if b >= 0.0 { (b, a) } else { (-b, -a) };
                ap = ap.max((mp.g(a, b) - mp.g(mi, mr)).abs());
                ar = ar.max((mg.g(a, b) - mg.g(mi, mr)).abs());
                gs_gap = gs_gap.max((mp.terms(a, b).gs - c.sn.gs.mean).abs());
            }
            context! {
                sigma => sw.sigma.to_string(),
                printed => format!("{ap:.3}"),
                reciprocal => format!("{ar:.1e}"),
                gs_gap => format!("{gs_gap:.3}"),
            }
        })
        .collect()
}

/// §5, the normalisation: ∫ p dγ with C = 1. With u = tan γ, p dγ = (1/(2πσ²)) √(1+u²)
/// e^{−u²/2σ²} du; midpoint rule on u ∈ [−12σ, 12σ] with 200 000 points.
fn mass_c1(sigma: f64) -> f64 {
    let n = 200_000;
    let (a, b) = (-12.0 * sigma, 12.0 * sigma);
    let h = (b - a) / n as f64;
    (0..n)
        .map(|i| {
            let u = a + (i as f64 + 0.5) * h;
            (1.0 + u * u).sqrt() * (-u * u / (2.0 * sigma * sigma)).exp()
        })
        .sum::<f64>()
        * h
        / (2.0 * std::f64::consts::PI * sigma * sigma)
}

/// §5, the paper's claim: each term's normalised BRDF curve RMS error against the
/// ray-traced truth at σ = 0.3 (None when σ = 0.3 was not swept).
fn paper_claim(brdf_rows: &[BrdfRow]) -> Option<Value> {
    brdf_rows
        .iter()
        .find(|(sg, _)| (*sg - 0.3).abs() < 1e-9)
        .map(|(_, errs)| {
            use brdf_core::models::GeometricTerm as T;
            let get = |t: T| {
                let e = errs.iter().find(|e| e.0 == t).map_or(f64::NAN, |e| e.1);
                format!("{e:.4}")
            };
            context! {
                none => get(T::None),
                blinn => get(T::Blinn),
                modified => get(T::Modified),
                printed => get(T::ModifiedPrinted),
                separable => get(T::SmithSeparable),
                correlated => get(T::SmithCorrelated),
            }
        })
}

/// The numbers of §6 (which G to use): the best two G by RMS over the populated cells per
/// σ, and the best normalised BRDF curves (ties within 5e-5).
fn conclusions(sweeps: &[Sweep], brdf_rows: &[BrdfRow]) -> Value {
    let mut best = Vec::new();
    for sw in sweeps {
        let mut v: Vec<(f64, Model)> = Model::ALL
            .iter()
            .enumerate()
            .map(|(k, &md)| (err_stats(sw, |c| c.models[k]).rms_pop, md))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        best.push(format!(
            "σ = {}: {} ({:.3}), then {} ({:.3})",
            sw.sigma,
            v[0].1.name(),
            v[0].0,
            v[1].1.name(),
            v[1].0
        ));
    }
    let mut bbest = Vec::new();
    for (sg, errs) in brdf_rows {
        let mut v = errs.clone();
        v.sort_by(|a, b| a.1.total_cmp(&b.1));
        let tied: Vec<&str> = v
            .iter()
            .filter(|e| e.1 <= v[0].1 + 5e-5)
            .map(|e| e.0.name())
            .collect();
        bbest.push(format!("σ = {sg}: {} ({:.4})", tied.join(" = "), v[0].1));
    }
    context! { best_g => best.join("; "), best_brdf => bbest.join("; ") }
}

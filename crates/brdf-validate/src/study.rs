//! The validation study: settings, the (θi, θr, σ) grids, the simulated ground truth, the
//! models evaluated on the same grids, and the error tables.

use crate::facet::g_single_neighbour;
use crate::profile::Profile;
use crate::stats::Estimate;
use crate::surface::{mix_seed, GSample, Surface};
use brdf_core::masking::{g_blinn, Convention, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic};
use brdf_core::models::{GeometricTerm, TorranceSparrow};
use brdf_core::roughness::beckmann_m_from_sigma;
use rayon::prelude::*;

/// The size of a simulation run, shared by the in-plane study ([`Settings`], surfaces
/// are profiles) and the 3-D one ([`crate::study2d::Settings2d`], surfaces are fields).
#[derive(Clone, Debug)]
pub struct RunSize {
    /// Each surface has 2^log2_nodes nodes along each side (Δ = ℓ/8).
    pub log2_nodes: u32,
    /// Number of independent surfaces.
    pub surfaces: u64,
    /// Batches per surface (batch means use surfaces × batches batches).
    pub batches_per_surface: u64,
    /// Samples per batch and cell.
    pub per_batch: u64,
    /// RMS slopes of the error tables.
    pub sigmas: Vec<f64>,
    /// Base seed.
    pub seed: u64,
}

impl RunSize {
    /// Samples per cell: surfaces × batches per surface × samples per batch.
    pub fn samples_per_cell(&self) -> u64 {
        self.surfaces * self.batches_per_surface * self.per_batch
    }
}

/// Run size and grids of the in-plane study.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Name printed in the report ("default" or "quick").
    pub name: &'static str,
    /// Profiles (2^log2_nodes nodes each), batches, samples, σ and seed.
    pub run: RunSize,
    /// Grid step in degrees; θi ∈ [0, 85], θr ∈ [−85, 85].
    pub step_deg: f64,
    /// Step of the fine θr grids of Figs 6 and 7, degrees (θr ∈ [−88, 88]).
    pub fine_step_deg: f64,
}

impl Settings {
    /// The default (report) settings: 4 profiles of 2^20 nodes, 64 000 samples per cell.
    pub fn default_run() -> Self {
        Self {
            name: "default",
            run: RunSize {
                log2_nodes: 20,
                surfaces: 4,
                batches_per_surface: 4,
                per_batch: 4000,
                sigmas: vec![0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0],
                seed: 2015,
            },
            step_deg: 5.0,
            fine_step_deg: 2.0,
        }
    }
    /// CI-sized settings: 2 profiles of 2^17 nodes, 2 000 samples per cell, 3 σ, 10° grid.
    pub fn quick() -> Self {
        Self {
            name: "quick",
            run: RunSize {
                log2_nodes: 17,
                surfaces: 2,
                batches_per_surface: 4,
                per_batch: 250,
                sigmas: vec![0.1, 0.3, 1.0],
                seed: 2015,
            },
            step_deg: 10.0,
            fine_step_deg: 4.0,
        }
    }
}

/// The geometric terms compared with the simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// Blinn's V-groove G (paper eq 4).
    Blinn,
    /// The paper's G, reciprocal convention (docs/conventions.md §4).
    Modified,
    /// The paper's G with eq 12 as printed.
    ModifiedPrinted,
    /// Smith–Beckmann separable, m = √2σ.
    SmithSeparable,
    /// Smith–Beckmann height-correlated, m = √2σ.
    SmithCorrelated,
}

impl Model {
    /// All compared models, in table order.
    pub const ALL: [Model; 5] = [
        Model::Blinn,
        Model::Modified,
        Model::ModifiedPrinted,
        Model::SmithSeparable,
        Model::SmithCorrelated,
    ];
    /// Display name.
    pub fn name(self) -> &'static str {
        match self {
            Model::Blinn => "Blinn",
            Model::Modified => "modified (reciprocal)",
            Model::ModifiedPrinted => "modified (printed eq 12)",
            Model::SmithSeparable => "Smith separable",
            Model::SmithCorrelated => "Smith height-correlated",
        }
    }
    /// Short name for file names and JSON keys: the term's name in the model catalogue
    /// ([`brdf_core::catalogue::MASKINGS`]).
    pub fn slug(self) -> &'static str {
        self.term().name()
    }
    /// The matching BRDF geometric term.
    pub fn term(self) -> GeometricTerm {
        match self {
            Model::Blinn => GeometricTerm::Blinn,
            Model::Modified => GeometricTerm::Modified,
            Model::ModifiedPrinted => GeometricTerm::ModifiedPrinted,
            Model::SmithSeparable => GeometricTerm::SmithSeparable,
            Model::SmithCorrelated => GeometricTerm::SmithCorrelated,
        }
    }
    /// G at (θi, θr) radians for RMS slope σ, from `brdf_core`.
    pub fn g(self, sigma: f64, ti: f64, tr: f64) -> f64 {
        self.g_with(
            sigma,
            [ti.cos(), tr.cos()],
            || g_blinn(ti, tr),
            |g| g.g(ti, tr),
        )
    }

    /// G for RMS slope σ, shared by the in-plane ([`Model::g`]) and the 3-D
    /// ([`crate::study2d::model_g3`]) forms: Smith–Beckmann (m = √2σ) from the cosines
    /// `[n·ωi, n·ωo]`, Blinn's G from `blinn`, the paper's G by `modified` applied to
    /// [`ModifiedG`] in the reciprocal or (ModifiedPrinted) the printed convention; NaN where
    /// σ is outside the modified G's range.
    pub(crate) fn g_with(
        self,
        sigma: f64,
        [ci, co]: [f64; 2],
        blinn: impl FnOnce() -> f64,
        modified: impl FnOnce(&ModifiedG<f64>) -> f64,
    ) -> f64 {
        let m = beckmann_m_from_sigma(sigma);
        let paper = |c: Convention| {
            ModifiedG::<f64>::new(sigma).map_or(f64::NAN, |g| modified(&g.with_convention(c)))
        };
        match self {
            Model::Blinn => blinn(),
            Model::Modified => paper(Convention::Reciprocal),
            Model::ModifiedPrinted => paper(Convention::Printed),
            Model::SmithSeparable => Beckmann::g_separable_cos(ci, co, m),
            Model::SmithCorrelated => Beckmann::g_correlated_cos(ci, co, m),
        }
    }
}

/// One grid cell: angles in degrees, the surface simulation, the single-neighbour
/// simulation and each model's G (in [`Model::ALL`] order).
#[derive(Clone, Debug)]
pub struct Cell {
    /// θi, degrees.
    pub ti: f64,
    /// θr, degrees (signed).
    pub tr: f64,
    /// Ray-traced random surface.
    pub sim: GSample,
    /// Paper's single-neighbour model, simulated.
    pub sn: GSample,
    /// Model values.
    pub models: [f64; 5],
    /// The paper's GM, GS (reciprocal convention) at this cell.
    pub formula_gm_gs: (f64, f64),
}

/// Everything simulated for one σ on one list of (θi, θr) pairs.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// RMS slope.
    pub sigma: f64,
    /// The cells.
    pub cells: Vec<Cell>,
}

/// The profiles of a run (generated in parallel, deterministic).
pub fn make_profiles(s: &Settings) -> Vec<Profile> {
    (0..s.run.surfaces)
        .into_par_iter()
        .map(|i| Profile::generate(s.run.log2_nodes, mix_seed(&[s.run.seed, 1000 + i])))
        .collect()
}

/// Runs the surface and single-neighbour simulations on `pairs` (degrees) for one σ.
pub fn sweep(
    s: &Settings,
    profiles: &[Profile],
    sigma: f64,
    pairs: &[(f64, f64)],
    tag: u64,
    pb: &indicatif::ProgressBar,
) -> Sweep {
    let surf = Surface { profiles, sigma };
    let mg = ModifiedG::<f64>::new(sigma).ok();
    let cells = pairs
        .par_iter()
        .enumerate()
        .map(|(k, &(ti, tr))| {
            let (a, b) = (ti.to_radians(), tr.to_radians());
            let seed = mix_seed(&[s.run.seed, tag, (sigma * 1e6) as u64, k as u64]);
            let sim = surf.g(a, b, s.run.per_batch, s.run.batches_per_surface, seed);
            let sn = g_single_neighbour(
                a,
                b,
                sigma,
                s.run.per_batch,
                s.run.batches_per_surface * s.run.surfaces,
                seed ^ 0x5555,
            );
            let models = Model::ALL.map(|m| m.g(sigma, a, b));
            let t = mg.map_or((f64::NAN, f64::NAN), |g| {
                let t = g.terms(a, b);
                (t.gm, t.gs)
            });
            pb.inc(1);
            Cell {
                ti,
                tr,
                sim,
                sn,
                models,
                formula_gm_gs: t,
            }
        })
        .collect();
    Sweep { sigma, cells }
}

/// The (θi, θr) grid of the error tables, degrees.
pub fn grid(step: f64) -> Vec<(f64, f64)> {
    let n_i = (85.0 / step + 1e-9).floor() as i64;
    let mut v = Vec::new();
    for i in 0..=n_i {
        for r in -n_i..=n_i {
            v.push((i as f64 * step, r as f64 * step));
        }
    }
    v
}

/// θr ∈ [−88, 88] with the given step at fixed θi, degrees, plus θr = 10° (the
/// normalisation point of Fig. 7) when the step misses it.
pub fn fine_row(ti: f64, step: f64) -> Vec<(f64, f64)> {
    let n = (88.0 / step + 1e-9).floor() as i64;
    let mut v: Vec<(f64, f64)> = (-n..=n).map(|r| (ti, r as f64 * step)).collect();
    if !v.iter().any(|p| (p.1 - 10.0).abs() < 1e-9) {
        v.push((ti, 10.0));
        v.sort_by(|a, b| a.1.total_cmp(&b.1));
    }
    v
}

/// Beckmann D(α)/D(0) for tilt α (radians) and σ: exp(−tan²α/(2σ²))/cos⁴α.
pub fn d_rel(alpha: f64, sigma: f64) -> f64 {
    let t = alpha.tan();
    (-t * t / (2.0 * sigma * sigma)).exp() / alpha.cos().powi(4)
}

/// RMS and max |error| of a model over cells, all cells and the "populated" ones
/// (D(α)/D(0) ≥ 1e-3, i.e. facets that exist with non-negligible probability).
#[derive(Clone, Copy, Debug, Default)]
pub struct ErrStats {
    /// RMS over all cells.
    pub rms: f64,
    /// Max |error| over all cells.
    pub max: f64,
    /// RMS over populated cells.
    pub rms_pop: f64,
    /// Max over populated cells.
    pub max_pop: f64,
    /// Where the max over all cells occurs (θi, θr).
    pub argmax: (f64, f64),
}

/// Error statistics of `value(cell)` against the surface simulation's G.
pub fn err_stats(sw: &Sweep, value: impl Fn(&Cell) -> f64) -> ErrStats {
    let (mut s2, mut n, mut mx, mut s2p, mut np, mut mxp) = (0.0, 0, 0.0f64, 0.0, 0, 0.0f64);
    let mut arg = (0.0, 0.0);
    for c in &sw.cells {
        let e = value(c) - c.sim.g.mean;
        s2 += e * e;
        n += 1;
        if e.abs() > mx {
            mx = e.abs();
            arg = (c.ti, c.tr);
        }
        if d_rel(0.5 * (c.tr - c.ti).to_radians(), sw.sigma) >= 1e-3 {
            s2p += e * e;
            np += 1;
            mxp = mxp.max(e.abs());
        }
    }
    ErrStats {
        rms: (s2 / n as f64).sqrt(),
        max: mx,
        rms_pop: (s2p / np.max(1) as f64).sqrt(),
        max_pop: mxp,
        argmax: arg,
    }
}

/// The normalised Torrance–Sparrow curve f(θr)/f(10°) at θi = 10° for a model term.
pub fn ts_normalised(sigma: f64, term: GeometricTerm, ti: f64, tr: f64) -> f64 {
    match TorranceSparrow::<f64>::specular(sigma, term) {
        Ok(ts) => {
            ts.eval_in_plane(ti.to_radians(), tr.to_radians())
                / ts.eval_in_plane(ti.to_radians(), 10f64.to_radians())
        }
        Err(_) => f64::NAN,
    }
}

/// The simulated normalised curve and its standard error at the cells of a θi = 10° row:
/// f_sim = f_none · G_sim, so f_sim/f_sim(10°) = (f_none/f_none(10°)) · G_sim/G_sim(10°).
pub fn sim_normalised(sigma: f64, row: &[&Cell]) -> Vec<(f64, f64, f64)> {
    let at10 = row.iter().find(|c| (c.tr - 10.0).abs() < 1e-9);
    let Some(c10) = at10 else {
        return Vec::new();
    };
    let g10 = c10.sim.g;
    row.iter()
        .map(|c| {
            let base = ts_normalised(sigma, GeometricTerm::None, c.ti, c.tr);
            let r = c.sim.g.mean / g10.mean;
            let rel = ((c.sim.g.se() / c.sim.g.mean.max(1e-12)).powi(2)
                + (g10.se() / g10.mean).powi(2))
            .sqrt();
            (c.tr, base * r, base * r * rel)
        })
        .collect()
}

/// RMS and max |error| of each BRDF term's normalised curve against the simulation over a
/// θi = 10° row (θr over the whole row). Returns rows in order None + [`Model::ALL`].
pub fn brdf_errors(sw: &Sweep) -> Vec<(GeometricTerm, f64, f64)> {
    let row: Vec<&Cell> = sw
        .cells
        .iter()
        .filter(|c| (c.ti - 10.0).abs() < 1e-9)
        .collect();
    let sim = sim_normalised(sw.sigma, &row);
    let mut terms = vec![GeometricTerm::None];
    terms.extend(Model::ALL.iter().map(|m| m.term()));
    terms
        .into_iter()
        .map(|t| {
            let (mut s2, mut mx) = (0.0, 0.0f64);
            for &(tr, f, _) in &sim {
                let e = ts_normalised(sw.sigma, t, 10.0, tr) - f;
                s2 += e * e;
                mx = mx.max(e.abs());
            }
            (t, (s2 / sim.len().max(1) as f64).sqrt(), mx)
        })
        .collect()
}

/// Largest |formula − single-neighbour simulation|/(SE + 3/n) over a sweep for GM and GS
/// (reciprocal convention), and the largest |min(GM, GS) − P(lit and seen)|.
pub fn formula_vs_single_neighbour(sw: &Sweep) -> (f64, f64, f64) {
    let (mut zm, mut zs, mut dmin) = (0.0f64, 0.0f64, 0.0f64);
    for c in &sw.cells {
        let (gm, gs) = c.formula_gm_gs;
        zm = zm.max(z(gm, c.sn.gm));
        zs = zs.max(z(gs, c.sn.gs));
        dmin = dmin.max((gm.min(gs) - c.sn.g.mean).abs());
    }
    (zm, zs, dmin)
}

/// |v − mean|/(SE + 3/n): the 3/n term (the 95 % "rule of three") keeps cells where an
/// event of probability ~1e-5 happened zero or a few times from producing huge ratios.
fn z(v: f64, e: Estimate) -> f64 {
    (v - e.mean).abs() / (e.se() + 3.0 / e.n.max(1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compared terms are distinct catalogue terms, and their file names are the
    /// catalogue's spellings, which are the names of the committed figures and report keys
    /// (docs/validation.md): blinn, modified, modified-printed, smith-separable,
    /// smith-correlated.
    #[test]
    fn models_are_catalogue_terms() {
        let slugs: Vec<&str> = Model::ALL.iter().map(|m| m.slug()).collect();
        let want = [
            "blinn",
            "modified",
            "modified-printed",
            "smith-separable",
            "smith-correlated",
        ];
        assert_eq!(slugs, want);
        for m in Model::ALL {
            let spec = brdf_core::catalogue::find_masking(m.slug()).unwrap();
            assert_eq!(spec.term, m.term());
        }
    }
}

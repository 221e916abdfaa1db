//! The 3-D study: G(ωi, ωo) ray-traced on 2-D Gaussian random height fields
//! ([`crate::surface2d`]) over a (θi, θo, φ) grid, and the models' 3-D forms on the same grid.
//!
//! Geometry: ωi = (sin θi cos ψ, sin θi sin ψ, cos θi), ωo at azimuth ψ + φ, so φ is the
//! azimuth between the tangential parts: φ = 180° is the in-plane forward side (θr > 0 of
//! docs/conventions.md), φ = 0 the in-plane backward side, other φ out of the plane. The
//! absolute azimuth ψ is drawn uniformly per sample for isotropic surfaces, which averages
//! out the grid's own directions (the triangles' slight anisotropy, §7.1 of the report).

use crate::stats::{ratio_estimate, Estimate};
use crate::study::{Model, RunSize};
use crate::surface::{mix_seed, GBatches, GSample};
use crate::surface2d::{Conditioned, Field, Ray};
use brdf_core::geometry::{Dots, Vec3};
use brdf_core::masking::{g_blinn_dots, ModifiedG};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Run size of the 3-D study.
#[derive(Clone, Debug)]
pub struct Settings2d {
    /// "default" or "quick".
    pub name: &'static str,
    /// Fields (2^log2_nodes × 2^log2_nodes nodes each), batches, samples, σ and seed.
    pub run: RunSize,
    /// θi values, degrees.
    pub theta_i: Vec<f64>,
    /// θo values, degrees.
    pub theta_o: Vec<f64>,
    /// φ values, degrees (0 = backward in-plane, 180 = forward in-plane).
    pub phi: Vec<f64>,
}

impl Settings2d {
    /// The report's settings.
    pub fn default_run() -> Self {
        Self {
            name: "default",
            run: RunSize {
                log2_nodes: 10,
                surfaces: 4,
                batches_per_surface: 8,
                per_batch: 750,
                sigmas: vec![0.1, 0.3, 0.5, 1.0],
                seed: 2014,
            },
            theta_i: vec![0.0, 30.0, 60.0, 80.0],
            theta_o: vec![0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.0],
            phi: vec![0.0, 45.0, 90.0, 135.0, 180.0],
        }
    }
    /// Test-sized settings (seconds).
    pub fn quick() -> Self {
        Self {
            name: "quick",
            run: RunSize {
                log2_nodes: 8,
                surfaces: 2,
                batches_per_surface: 4,
                per_batch: 60,
                sigmas: vec![0.3],
                seed: 2014,
            },
            theta_i: vec![0.0, 60.0],
            theta_o: vec![0.0, 60.0, 85.0],
            phi: vec![0.0, 90.0, 180.0],
        }
    }
    /// The (θi, θo, φ) grid, degrees, in a fixed order.
    pub fn grid(&self) -> Vec<[f64; 3]> {
        let mut v = Vec::new();
        for &a in &self.theta_i {
            for &b in &self.theta_o {
                for &p in &self.phi {
                    v.push([a, b, p]);
                }
            }
        }
        v
    }
}

/// The fields of a run (deterministic).
pub fn make_fields(s: &Settings2d) -> Vec<Field> {
    (0..s.run.surfaces)
        .into_par_iter()
        .map(|i| Field::generate(s.run.log2_nodes, mix_seed(&[s.run.seed, 2000 + i])))
        .collect()
}

/// Unit direction at polar angle θ and azimuth ψ (radians).
pub fn dir(theta: f64, psi: f64) -> [f64; 3] {
    let (st, ct) = theta.sin_cos();
    [st * psi.cos(), st * psi.sin(), ct]
}

/// (ωi, ωo) of a grid cell (degrees) rotated by the absolute azimuth ψ (radians).
pub fn pair(g: [f64; 3], psi: f64) -> ([f64; 3], [f64; 3]) {
    (
        dir(g[0].to_radians(), psi),
        dir(g[1].to_radians(), psi + g[2].to_radians()),
    )
}

/// A surface: fields seen with slope RMS (σx, σy); `random_azimuth` draws ψ per sample.
pub struct Surface2d<'a> {
    /// The fields (unit slope RMS).
    pub fields: &'a [Field],
    /// Slope RMS along x and y.
    pub sigma: (f64, f64),
    /// Draw the absolute azimuth uniformly per sample (isotropic surfaces).
    pub random_azimuth: bool,
}

impl Surface2d<'_> {
    /// A world direction in the field's scaled units.
    fn scaled(&self, w: [f64; 3]) -> [f64; 3] {
        [self.sigma.0 * w[0], self.sigma.1 * w[1], w[2]]
    }

    /// G, GM (seen) and GS (lit) at the grid cell `g` (degrees): the fraction of facets
    /// with normal h = (ωi + ωo)/|ωi + ωo| that are lit, seen, both. Each sample takes a
    /// uniformly chosen triangle, conditions the field on its slope being −h_t/h_z exactly,
    /// takes a uniform point on it and traces both rays.
    pub fn g(&self, g: [f64; 3], per_batch: u64, batches: u64, seed: u64) -> GSample {
        let mut counts = GBatches::default();
        for (fi, f) in self.fields.iter().enumerate() {
            let n = f.side() as i64;
            for b in 0..batches {
                let mut rng = Pcg64::seed_from_u64(mix_seed(&[seed, fi as u64, b]));
                counts.batch(per_batch, || {
                    let psi = if self.random_azimuth {
                        rng.random::<f64>() * 2.0 * PI
                    } else {
                        0.0
                    };
                    let (wi, wo) = pair(g, psi);
                    let hz = wi[2] + wo[2];
                    let s = [
                        -(wi[0] + wo[0]) / hz / self.sigma.0,
                        -(wi[1] + wo[1]) / hz / self.sigma.1,
                    ];
                    let (ci, cj) = (rng.random_range(0..n), rng.random_range(0..n));
                    let t = rng.random_range(0..2usize);
                    let c = Conditioned::new(f, ci, cj, t, s);
                    let (u1, u2): (f64, f64) = (rng.random(), rng.random());
                    let (x, y) = if t == 0 {
                        (u1.max(u2), u1.min(u2))
                    } else {
                        (u1.min(u2), u1.max(u2))
                    };
                    let (px, py) = (ci as f64 + x, cj as f64 + y);
                    let o = [px, py, c.height_in_cell(ci, cj, px, py)];
                    let lit = c.visible(
                        &Ray {
                            o,
                            d: self.scaled(wi),
                        },
                        (ci, cj),
                        s,
                    );
                    let seen = c.visible(
                        &Ray {
                            o,
                            d: self.scaled(wo),
                        },
                        (ci, cj),
                        s,
                    );
                    (lit, seen)
                });
            }
        }
        counts.estimate()
    }

    /// Area-weighted one-sided masking toward polar angle θ at azimuth ψ (radians; ψ is
    /// redrawn per sample when `random_azimuth`): (G1 = E[vis·w]/E[w], identity ratio
    /// E[vis·w]/cos θ), w = (cos θ − p·ω_t)⁺ the projected area of a facet of world slope p
    /// per unit horizontal area. Points are uniform over the unconditioned surface.
    pub fn g1_area(
        &self,
        theta: f64,
        psi0: f64,
        per_batch: u64,
        batches: u64,
        seed: u64,
    ) -> (Estimate, Estimate) {
        let (mut num, mut den, mut idn) = (Vec::new(), Vec::new(), Vec::new());
        for (fi, f) in self.fields.iter().enumerate() {
            let n = f.side() as i64;
            let c = Conditioned::plain(f);
            for b in 0..batches {
                let mut rng = Pcg64::seed_from_u64(mix_seed(&[seed, fi as u64, b, 11]));
                let (mut sv, mut sw) = (0.0, 0.0);
                for _ in 0..per_batch {
                    let psi = if self.random_azimuth {
                        rng.random::<f64>() * 2.0 * PI
                    } else {
                        psi0
                    };
                    let d = self.scaled(dir(theta, psi));
                    let (ci, cj) = (rng.random_range(0..n), rng.random_range(0..n));
                    let (x, y): (f64, f64) = (rng.random(), rng.random());
                    let t = if y <= x { 0 } else { 1 };
                    let s = f.tri_slope(ci, cj, t);
                    let w = (d[2] - s[0] * d[0] - s[1] * d[1]).max(0.0);
                    sw += w;
                    let (px, py) = (ci as f64 + x, cj as f64 + y);
                    let o = [px, py, c.height_in_cell(ci, cj, px, py)];
                    if w > 0.0 && c.visible(&Ray { o, d }, (ci, cj), s) {
                        sv += w;
                    }
                }
                num.push(sv);
                den.push(sw);
                idn.push(theta.cos() * per_batch as f64);
            }
        }
        (ratio_estimate(&num, &den), ratio_estimate(&num, &idn))
    }
}

/// A model's G for world directions (z up), from `brdf_core`'s 3-D forms: the modified G
/// through its reciprocal extension (`terms_dots`) or the printed convention's fold into the
/// plane of incidence, Blinn's V-groove G in Torrance–Sparrow's 3-D form (`g_blinn_dots`),
/// Smith–Beckmann with m = √2σ.
pub fn model_g3(m: Model, sigma: f64, wi: [f64; 3], wo: [f64; 3]) -> f64 {
    let v = |w: [f64; 3]| Vec3::new(w[0], w[1], w[2]);
    let d = Dots::from_local(v(wi), v(wo));
    m.g_with(sigma, [wi[2], wo[2]], || g_blinn_dots(d), |g| g.g_dots(d))
}

/// One grid cell of the 3-D study.
#[derive(Clone, Debug)]
pub struct Cell2d {
    /// (θi, θo, φ), degrees.
    pub geom: [f64; 3],
    /// The ray-traced G, GM, GS.
    pub sim: GSample,
    /// Each model's G, in [`Model::ALL`] order.
    pub models: [f64; 5],
    /// The modified G's (reciprocal) GM and GS.
    pub modified_gm_gs: (f64, f64),
}

impl Cell2d {
    /// In the plane of incidence (φ = 0 or 180°, or a normal direction).
    pub fn in_plane(&self) -> bool {
        let [a, b, p] = self.geom;
        a == 0.0 || b == 0.0 || p == 0.0 || p == 180.0
    }
    /// Grazing: θi or θo ≥ 80°.
    pub fn grazing(&self) -> bool {
        self.geom[0] >= 80.0 || self.geom[1] >= 80.0
    }
}

/// All cells for one σ.
#[derive(Clone, Debug)]
pub struct Sweep2d {
    /// RMS slope.
    pub sigma: f64,
    /// The cells, in [`Settings2d::grid`] order.
    pub cells: Vec<Cell2d>,
}

/// Simulates every grid cell for one isotropic σ.
pub fn sweep2d(
    s: &Settings2d,
    fields: &[Field],
    sigma: f64,
    pb: &indicatif::ProgressBar,
) -> Sweep2d {
    let surf = Surface2d {
        fields,
        sigma: (sigma, sigma),
        random_azimuth: true,
    };
    let mg = ModifiedG::<f64>::new(sigma).ok();
    let cells = s
        .grid()
        .par_iter()
        .enumerate()
        .map(|(k, &g)| {
            let seed = mix_seed(&[s.run.seed, (sigma * 1e6) as u64, k as u64]);
            let sim = surf.g(g, s.run.per_batch, s.run.batches_per_surface, seed);
            let (wi, wo) = pair(g, 0.0);
            let models = Model::ALL.map(|m| model_g3(m, sigma, wi, wo));
            let t = mg.map(|m| {
                let v = |w: [f64; 3]| Vec3::new(w[0], w[1], w[2]);
                m.terms_dots(Dots::from_local(v(wi), v(wo)))
            });
            pb.inc(1);
            Cell2d {
                geom: g,
                sim,
                models,
                modified_gm_gs: t.map_or((f64::NAN, f64::NAN), |t| (t.gm, t.gs)),
            }
        })
        .collect();
    Sweep2d { sigma, cells }
}

/// RMS and max |model − truth| over a subset of cells, with where the max is.
#[derive(Clone, Copy, Debug, Default)]
pub struct Err2d {
    /// RMS error.
    pub rms: f64,
    /// Max |error|.
    pub max: f64,
    /// (θi, θo, φ) of the max.
    pub argmax: [f64; 3],
    /// Number of cells.
    pub n: usize,
}

/// Error of model `k` ([`Model::ALL`] index) over the cells that `keep` selects.
pub fn err2d(sw: &Sweep2d, k: usize, keep: impl Fn(&Cell2d) -> bool) -> Err2d {
    let mut e = Err2d::default();
    let mut s2 = 0.0;
    for c in sw.cells.iter().filter(|c| keep(c)) {
        let d = c.models[k] - c.sim.g.mean;
        s2 += d * d;
        e.n += 1;
        if d.abs() > e.max {
            e.max = d.abs();
            e.argmax = c.geom;
        }
    }
    e.rms = (s2 / e.n.max(1) as f64).sqrt();
    e
}

/// Reciprocity of the simulated G: z = (G(a, b, φ) − G(b, a, φ))/√(SE² + SE²) over the
/// grid's mirrored pairs with a ≠ b (independent samples). Returns (pairs, RMS z, max |z|).
pub fn reciprocity(sw: &Sweep2d) -> (usize, f64, f64) {
    let (mut n, mut s2, mut mx) = (0usize, 0.0, 0.0f64);
    for c in &sw.cells {
        let [a, b, p] = c.geom;
        if a >= b {
            continue;
        }
        if let Some(d) = sw.cells.iter().find(|d| d.geom == [b, a, p]) {
            let se = (c.sim.g.se().powi(2) + d.sim.g.se().powi(2)).sqrt();
            if se > 0.0 {
                let z = (c.sim.g.mean - d.sim.g.mean) / se;
                n += 1;
                s2 += z * z;
                mx = mx.max(z.abs());
            }
        }
    }
    (n, (s2 / n.max(1) as f64).sqrt(), mx)
}

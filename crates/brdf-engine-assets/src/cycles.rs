//! Blender Cycles' rough-glass albedo tables (`table_ggx_glass_E`, `table_ggx_glass_inv_E`,
//! `table_ggx_glass_Eavg`, `table_ggx_glass_inv_Eavg` of `intern/cycles/scene/shader.tables`)
//! in Cycles' own nodes and index order, filled with the converged integrals of Cycles' own
//! closure ([`brdf_lut::generate::glass::correlated`]: GGX, exact Fresnel, the
//! height-correlated Smith G2 of `bsdf_microfacet.h`, the sampled weight Cycles' precompute
//! averages), written as the C arrays Cycles compiles, with a JSON sidecar.
//!
//! **Cycles' layout** (pinned from blender/blender `intern/cycles/app/cycles_precompute.cpp`,
//! the generator of those arrays, and `intern/cycles/kernel/closure/bsdf_microfacet.h`
//! `microfacet_ggx_preserve_energy` with `kernel/util/lookup_table.h`, the reader; read, not
//! copied). Endpoint nodes on every axis, index i of N = 16:
//!
//! ```text
//! x: r  = clamp(i/(N − 1), 1e-4, 1),     α = r²            (fastest)
//! y: μ  = clamp(j/(N − 1), 1e-4, 1)
//! z: t  = clamp(k/(N − 1), 1e-4, 0.99),  ior = ior_from_F0(t⁴) = (1 + t²)/(1 − t²)
//! E[k][j][i] at flat index i + N (j + N k);  E_avg[k][i] at i + N k
//! ```
//!
//! `ggx_glass_E` is E = R + T at η = ior (light entering), `ggx_glass_inv_E` at η = 1/ior
//! (light inside); `E_avg = 2∫₀¹ E μ dμ`. Cycles saturates each value to [0, 1] and reads
//! the tables with z = √(|ior − 1|/(ior + 1)) (its reciprocal for ior < 1), linear between
//! nodes.
//!
//! **Model.** Cycles' precompute averages the closure's sample weight eval/pdf; with its
//! lobe choice by F that is G2/G1(wo) = (1 + Λ(wo))/(1 + Λ(wo) + Λ(wi)) per visible normal,
//! times F (reflection above the surface) or 1 − F (refraction, either side: Cycles does
//! not test it); `glass_e_correlated` integrates exactly that (its module docs; its values
//! match 25 shipped E and 4 E_avg values within 9.1e-6, brdf-lut tests/glass_correlated.rs).
//! Two places differ from Cycles' shipped arrays by construction: x = 0 (r = 1e-4), where
//! Cycles takes its smooth path (α² ≤ 5e-7) and stores 1 while these hold the rough integral
//! at α = 1e-4 (1 − O(α²/μ²), but 0.72 to 0.92 at μ = 1e-4), and z = 0 (ior = 1 + 2e-8, 1 in f32),
//! where Cycles refracts singularly (|η − 1| < 1e-4, weight 1) and these hold the η → 1
//! limit (1 + Λ)/(1 + 2Λ).

use crate::{Error, File};
use brdf_lut::generate::glass::correlated::{glass_e_avg_correlated, glass_e_correlated};
use brdf_lut::generate::INTEGRATION_TOL;
use rayon::prelude::*;
use serde_json::json;
use std::fmt::Write as _;

use crate::Result;

/// Cycles' table edge (its lookups hard-code 16 × 16 × 16 and 16 × 16).
pub const CYCLES_EDGE: usize = 16;

/// Largest edge accepted by [`cycles`] (only [`CYCLES_EDGE`] is a drop-in).
pub const CYCLES_MAX_EDGE: usize = 64;

/// Cycles' node coordinates: (r, μ, ior) of index (i, j, k) on an n-node axis.
pub fn cycles_node(i: usize, j: usize, k: usize, n: usize) -> (f64, f64, f64) {
    let u = |i: usize| i as f64 / (n - 1) as f64;
    let t = u(k).clamp(1e-4, 0.99);
    let t2 = t * t;
    (
        u(i).clamp(1e-4, 1.0),
        u(j).clamp(1e-4, 1.0),
        (1.0 + t2) / (1.0 - t2),
    )
}

/// η of the table: ior (light entering) or 1/ior (`inside`, Cycles' `inv` tables).
fn eta_of(ior: f64, inside: bool) -> f64 {
    if inside {
        1.0 / ior
    } else {
        ior
    }
}

/// A table's f64 values (R + T before saturation) and the largest integration estimate.
struct Values {
    v: Vec<f64>,
    bound: f64,
}

/// E = R + T at every node of an n³ table (Cycles' index order), on all cores.
fn e_table(n: usize, inside: bool, progress: &(dyn Fn(u64) + Sync)) -> Values {
    table(n * n * n, progress, |idx| {
        let (r, mu, ior) = cycles_node(idx % n, idx / n % n, idx / (n * n), n);
        glass_e_correlated(mu, r * r, eta_of(ior, inside), INTEGRATION_TOL)
    })
}

/// E_avg = R_avg + T_avg at every node of an n² table (x = r fastest, z = ior), all cores.
fn avg_table(n: usize, inside: bool, progress: &(dyn Fn(u64) + Sync)) -> Values {
    table(n * n, progress, |idx| {
        let (r, _, ior) = cycles_node(idx % n, 0, idx / n, n);
        glass_e_avg_correlated(r * r, eta_of(ior, inside), INTEGRATION_TOL)
    })
}

/// R + T of `node(idx)` for `idx` in 0..count, on all cores, with the largest estimate.
fn table(
    count: usize,
    progress: &(dyn Fn(u64) + Sync),
    node: impl Fn(usize) -> ([f64; 2], brdf_lut::generate::Work) + Sync,
) -> Values {
    let out: Vec<(f64, f64)> = (0..count)
        .into_par_iter()
        .map(|idx| {
            let (rt, w) = node(idx);
            progress(1);
            (rt[0] + rt[1], w.error)
        })
        .collect();
    Values {
        v: out.iter().map(|p| p.0).collect(),
        bound: out.iter().map(|p| p.1).fold(0.0, f64::max),
    }
}

/// The stored value: saturate(v) as Cycles' precompute stores it, rounded to f32; an error
/// for a non-finite integral (never expected: tests/cycles.rs).
fn stored(v: f64, name: &str, idx: usize) -> Result<f32> {
    if !v.is_finite() {
        return Err(Error::Encode(format!(
            "{name}[{idx}]: the integral is not finite ({v})"
        )));
    }
    Ok(v.clamp(0.0, 1.0) as f32)
}

/// One C array as Cycles' `shader.tables` declares it: `static const float table_<name>[len]`,
/// one row of `row` values per line (x fastest), a blank line between 2-D slices of
/// `slice` values; each value the shortest decimal that reads back as the same f32.
fn c_array(name: &str, vals: &[f32], row: usize, slice: usize) -> String {
    let mut s = format!("static const float table_{name}[{}] = {{\n", vals.len());
    for (i, v) in vals.iter().enumerate() {
        if i % row == 0 {
            if i > 0 && i % slice == 0 {
                s.push('\n');
            }
            s.push_str("  ");
        }
        let _ = write!(s, "{v:?}f");
        if i + 1 < vals.len() {
            s.push_str(if (i + 1) % row == 0 { ",\n" } else { ", " });
        }
    }
    s.push_str("\n};\n");
    s
}

/// The tables of one run: (Cycles name, values), rows of n values (x fastest).
type Tables = Vec<(&'static str, Vec<f32>)>;

/// The `.tables` C source: a comment naming the source and the four (or two) arrays.
fn c_source(n: usize, tables: &Tables) -> String {
    let mut s = format!(
        "/* Rough-glass albedo tables for Cycles' microfacet_ggx_preserve_energy, {n}-node \
         axes,\n * written by brdf-kernels `cargo xtask lut engine cycles` \
         (brdf_engine_assets::cycles).\n * Values: converged integrals of Cycles' GGX glass \
         closure (height-correlated Smith G2,\n * exact Fresnel); they differ from Cycles' own \
         at r = 1e-4 and ior = 1 + 2e-8 (see\n * cycles_ggx_glass.json: narrow_limit, \
         eta_near_1) before replacing the arrays of the same\n * names in \
         intern/cycles/scene/shader.tables. */\n"
    );
    for (name, vals) in tables {
        s.push('\n');
        s.push_str(&c_array(name, vals, n, n * n));
    }
    s
}

/// Blender Cycles' rough-glass tables (module docs) at n nodes per axis (Cycles: 16;
/// 2..=[`CYCLES_MAX_EDGE`]): `cycles_ggx_glass.tables` (C arrays `table_ggx_glass_E`,
/// `table_ggx_glass_inv_E` of n³ values and, with `with_avg`, `table_ggx_glass_Eavg`,
/// `table_ggx_glass_inv_Eavg` of n²) and the sidecar `cycles_ggx_glass.json`. Every value is
/// R + T from [`glass_e_correlated`] / [`glass_e_avg_correlated`] at Cycles' node, each
/// channel converged to
/// [`INTEGRATION_TOL`], saturated to [0, 1] as Cycles does, rounded to f32. `progress(1)` per
/// node. Cost (release, 2 shared cores): both 16³ E tables 1.6 s, all four arrays 23 s
/// (docs/engines.md).
pub fn cycles(n: usize, with_avg: bool, progress: &(dyn Fn(u64) + Sync)) -> Result<Vec<File>> {
    if !(2..=CYCLES_MAX_EDGE).contains(&n) {
        return Err(Error::Size(n));
    }
    let mut tables: Tables = Vec::new();
    let mut bounds = serde_json::Map::new();
    let mut dirs: Vec<(&str, bool, bool)> = vec![("ggx_glass_E", false, false)];
    dirs.push(("ggx_glass_inv_E", true, false));
    if with_avg {
        dirs.push(("ggx_glass_Eavg", false, true));
        dirs.push(("ggx_glass_inv_Eavg", true, true));
    }
    for (name, inside, avg) in dirs {
        let t = if avg {
            avg_table(n, inside, progress)
        } else {
            e_table(n, inside, progress)
        };
        let vals =
            t.v.iter()
                .enumerate()
                .map(|(i, &v)| stored(v, name, i))
                .collect::<Result<Vec<f32>>>()?;
        bounds.insert(name.into(), json!(t.bound));
        tables.push((name, vals));
    }
    let side = sidecar(n, &tables, bounds)?;
    Ok(vec![
        File {
            name: "cycles_ggx_glass.tables".into(),
            bytes: c_source(n, &tables).into_bytes(),
        },
        File {
            name: "cycles_ggx_glass.json".into(),
            bytes: side,
        },
    ])
}

/// The JSON sidecar of [`cycles`].
fn sidecar(
    n: usize,
    tables: &Tables,
    bounds: serde_json::Map<String, serde_json::Value>,
) -> Result<Vec<u8>> {
    let arrays: serde_json::Map<_, _> = tables
        .iter()
        .map(|(name, v)| (format!("table_{name}"), json!(v.len())))
        .collect();
    let side = json!({
        "target": "cycles",
        "files": {
            "cycles_ggx_glass.tables": "C source: static const float arrays named as in Blender's intern/cycles/scene/shader.tables (replace the blocks of the same names); values as f32 decimal literals that read back to the stored f32 exactly",
        },
        "arrays": arrays,
        "size": n,
        "drop_in": if n == CYCLES_EDGE { "same names, sizes, nodes, index order and model as Cycles' tables (the closure's height-correlated sample weight), but for the x = 0 column and the z = 0 slice: see narrow_limit and eta_near_1" } else { "no: Cycles' lookups hard-code 16 nodes per axis" },
        "integral": "E(mu, r, eta) = R + T: the mean of the sample weight eval/pdf of Cycles' GGX glass closure for light arriving along mu = cos(theta) from the side of index 1 (what cycles_precompute.cpp averages): over the GGX visible normals h (Heitz 2018), F(wo.h) w(l) for the reflected ray l if it leaves above the surface plus (1 - F(wo.h)) w(t) for the refracted ray t wherever it exists (either side of the surface: Cycles does not test it), w(o) = G2/G1(wo) = (1 + Lambda(wo))/(1 + Lambda(wo) + Lambda(o)); the energy fraction (no eta^2 radiance factor). E_avg = 2 * integral over [0, 1] of E(mu) mu dmu",
        "model": "Blender Cycles' microfacet glass closure (bsdf_microfacet.h, after Walter, Marschner, Li, Torrance, EGSR 2007): GGX NDF, alpha = r^2, exact unpolarised dielectric Fresnel (total internal reflection included), height-correlated Smith G2; brdf_lut::generate::glass::correlated::{glass_e_correlated, glass_e_avg_correlated}",
        "masking": "HEIGHT-CORRELATED Smith G2 = 1/(1 + Lambda_i + Lambda_o), GGX Lambda(z) = (sqrt(1 + alpha^2 (1 - z^2)/z^2) - 1)/2 (Heitz 2014), as Cycles' closure evaluates it (eval = F D common/(1 + Lambda_i + Lambda_o), pdf = D common lobe/(1 + Lambda_i)); matches 25 shipped E values and 4 E_avg values of shader.tables within 9.1e-6 (brdf-lut tests/glass_correlated.rs). Not brdf-core's rough dielectric, which has the separable G1 G1 (brdf_lut::generate::glass::glass_e)",
        "axes": {
            "x": "fastest: r = clamp(i/(N - 1), 1e-4, 1), GGX alpha = r^2",
            "y": "mu = clamp(j/(N - 1), 1e-4, 1) (E tables only)",
            "z": "t = clamp(k/(N - 1), 1e-4, 0.99), ior = (1 + t^2)/(1 - t^2) (Cycles' ior_from_F0(t^4)), so ior runs from 1 + 2e-8 to 99.5; eta = ior (ggx_glass_E, ggx_glass_Eavg: light entering the glass) or 1/ior (the inv tables: light inside)",
        },
        "orientation": "E: flat index i + N (j + N k) (x = r fastest, then y = mu, then z); E_avg: i + N k. Cycles reads them with lookup_table_read_3D(rough, mu, z) / lookup_table_read_2D(rough, z), z = sqrt(|ior - 1|/(ior + 1)) for the ior >= 1 table or with 1/ior for the inv table, linear between endpoint nodes",
        "encoding": "IEEE binary32 (f32), round to nearest of the saturated f64 value; printed as the shortest decimal that reads back to the same f32 (Cycles' own file prints 6 decimals)",
        "linear": true,
        "texel_values": format!("each value = saturate(R + T) at its node, each channel converged by the generator's adaptive ring rule to {INTEGRATION_TOL:e} (largest estimates below), computed in f64 at the node coordinates above; Cycles' own values are Sobol means (2^23 samples, 2^26 for E_avg) of the closure's sample weight in f32, printed with 6 decimals"),
        "integration_bound": bounds,
        "narrow_limit": "x = 0 (r = 1e-4, alpha = 1e-8): the generator floors alpha at 1e-4 (brdf_core::models::rough_dielectric::ALPHA_FLOOR), so these texels hold the rough integral at alpha = 1e-4: E = 1 - O(alpha^2/mu^2), within 5.3e-6 of 1 for mu >= 1/15 (both directions, measured at 16 nodes; 1e-5 for mu >= 0.5 tested), but 0.89 to 0.92 at mu = 1e-4 from outside and 0.72 to 0.89 from inside. Cycles' precompute takes its singular (smooth) path there (alpha_x alpha_y <= 5e-7) and stores 1 (0.999985 at mu = 1e-4)",
        "eta_near_1": "z = 0 (ior = 1 + 2e-8): the rough integral's limit, R -> 0 and T -> (1 + Lambda(mu))/(1 + 2 Lambda(mu)) (facets refract straight through; = (1 + mu)/2 at r = 1), not 1; Cycles' ior there is 1 in f32 and it refracts singularly for |eta - 1| < 1e-4 (weight 1), storing ~1. Cycles interpolates this slice only for 1 < ior < 1.0089",
        "sources": "blender/blender intern/cycles/app/cycles_precompute.cpp (nodes, order, saturation, inv tables at 1/ior, the averaged sample weight), kernel/closure/bsdf_microfacet.h (bsdf_microfacet_sample and _eval: G2, lobe choice, no side test of the refracted ray; microfacet_ggx_preserve_energy), kernel/util/lookup_table.h (endpoint-node lookup), scene/shader.tables (the arrays; compared values from commit 09cf4924cc65); read, not copied",
    });
    crate::sidecar::sidecar_bytes(&side)
}

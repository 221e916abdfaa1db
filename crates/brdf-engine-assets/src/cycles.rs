//! Blender Cycles' rough-glass albedo tables (`table_ggx_glass_E`, `table_ggx_glass_inv_E`,
//! `table_ggx_glass_Eavg`, `table_ggx_glass_inv_Eavg` of `intern/cycles/scene/shader.tables`)
//! in Cycles' own nodes and index order, filled from brdf-lut's generator
//! ([`brdf_lut::generate::glass`]), written as the C arrays Cycles compiles, with a JSON
//! sidecar.
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

use crate::{Error, File};
use brdf_lut::generate::glass::{glass_e, glass_e_avg};
use brdf_lut::generate::INTEGRATION_TOL;
use rayon::prelude::*;
use serde_json::json;
use std::fmt::Write as _;

type Result<T> = std::result::Result<T, Error>;

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
        glass_e(mu, r * r, eta_of(ior, inside), INTEGRATION_TOL)
    })
}

/// E_avg = R_avg + T_avg at every node of an n² table (x = r fastest, z = ior), all cores.
fn avg_table(n: usize, inside: bool, progress: &(dyn Fn(u64) + Sync)) -> Values {
    table(n * n, progress, |idx| {
        let (r, _, ior) = cycles_node(idx % n, 0, idx / n, n);
        glass_e_avg(r * r, eta_of(ior, inside), INTEGRATION_TOL)
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
         (brdf_engine_assets::cycles).\n * Values: brdf-lut's converged GGX rough-dielectric \
         integrals with SEPARABLE Smith G;\n * Cycles' closure uses the height-correlated G: \
         see cycles_ggx_glass.json (\"masking\")\n * before replacing the arrays of the same \
         names in intern/cycles/scene/shader.tables. */\n"
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
/// R + T from [`glass_e`] / [`glass_e_avg`] at Cycles' node, each channel converged to
/// [`INTEGRATION_TOL`], saturated to [0, 1] as Cycles does, rounded to f32. `progress(1)` per
/// node. Cost (release, 2 shared cores): both 16³ E tables 143 s; E_avg from inside is the
/// bulk (~3e8 integrand evaluations per node at α = 1, η = 1/99.5; docs/engines.md).
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
        "drop_in": if n == CYCLES_EDGE { "same names, sizes, nodes and index order as Cycles' tables; NOT the same model: see masking" } else { "no: Cycles' lookups hard-code 16 nodes per axis" },
        "integral": "E(mu, r, eta) = R + T: the total single-scattering directional albedo of a GGX rough dielectric for light arriving along mu = cos(theta) from the side of index 1; R = integral of f_r |cos theta_i| over the near hemisphere, T = integral of the adjoint (energy) transmission f_t* |cos theta_i| over the far hemisphere (without the eta^2 radiance factor; Cycles' sample weight eval/pdf is the same energy fraction). E_avg = 2 * integral over [0, 1] of E(mu) mu dmu.",
        "model": "rough dielectric of Walter, Marschner, Li, Torrance (EGSR 2007): GGX NDF, alpha = r^2, exact unpolarised dielectric Fresnel (total internal reflection included); brdf-core models::rough_dielectric through brdf_lut::generate::glass::{glass_e, glass_e_avg}",
        "masking": "SEPARABLE Smith G = G1(wi) G1(wo) (the generator's only glass masking). Cycles' closure (bsdf_microfacet.h: eval = F D common / (1 + Lambda_i + Lambda_o)) uses the HEIGHT-CORRELATED G, and its shipped tables hold that model's E, which is larger at high roughness and grazing mu: at eta -> 1 the separable E is G1(mu) and the correlated E is (1 + Lambda)/(1 + 2 Lambda) (mu = 4/15, r = 1: limits 0.421 vs 0.633; at ior 1.0089 these arrays hold 0.427 where Cycles ships 0.6385). Used as is, these arrays make Cycles' energy compensation 1/E too strong there; a drop-in needs the correlated variant of the generator (not written: docs/engines.md).",
        "axes": {
            "x": "fastest: r = clamp(i/(N - 1), 1e-4, 1), GGX alpha = r^2",
            "y": "mu = clamp(j/(N - 1), 1e-4, 1) (E tables only)",
            "z": "t = clamp(k/(N - 1), 1e-4, 0.99), ior = (1 + t^2)/(1 - t^2) (Cycles' ior_from_F0(t^4)), so ior runs from 1 + 2e-8 to 99.5; eta = ior (ggx_glass_E, ggx_glass_Eavg: light entering the glass) or 1/ior (the inv tables: light inside)",
        },
        "orientation": "E: flat index i + N (j + N k) (x = r fastest, then y = mu, then z); E_avg: i + N k. Cycles reads them with lookup_table_read_3D(rough, mu, z) / lookup_table_read_2D(rough, z), z = sqrt(|ior - 1|/(ior + 1)) for the ior >= 1 table or with 1/ior for the inv table, linear between endpoint nodes",
        "encoding": "IEEE binary32 (f32), round to nearest of the saturated f64 value; printed as the shortest decimal that reads back to the same f32 (Cycles' own file prints 6 decimals)",
        "linear": true,
        "texel_values": format!("each value = saturate(R + T) at its node, each channel converged by the generator's adaptive cap rule to {INTEGRATION_TOL:e} (largest estimates below), computed in f64 at the node coordinates above; Cycles' own values are Monte Carlo means (2^23 samples, 2^26 for E_avg) of the closure's sample weight in f32"),
        "integration_bound": bounds,
        "narrow_limit": "x = 0 (r = 1e-4, alpha = 1e-8): the kernel floors alpha at 1e-4 (brdf_core::models::rough_dielectric::ALPHA_FLOOR), so these texels hold the rough integral at alpha = 1e-4: E = 1 - O(alpha^2/mu^2), i.e. within 5e-6 of 1 for mu >= 1/15 (both directions, measured at 16 nodes), but 0.66 to 0.90 at mu = 1e-4 (0.88 for most ior). Cycles' precompute takes its singular (smooth) path there (alpha_x alpha_y <= 5e-7) and stores 1.",
        "eta_near_1": "z = 0 (ior = 1 + 2e-8): the rough integral's limit, R -> 0 and T -> G1(mu) (separable G: facets refract straight through, the second G1 masks), not 1; Cycles treats |eta - 1| < 1e-4 as singular refraction and stores ~1 there. Cycles interpolates this slice only for 1 < ior < 1.0089.",
        "sources": "blender/blender intern/cycles/app/cycles_precompute.cpp (nodes, order, saturation, inv tables at 1/ior), kernel/closure/bsdf_microfacet.h (microfacet_ggx_preserve_energy; the closure's G), kernel/util/lookup_table.h (endpoint-node lookup), scene/shader.tables (the arrays); read, not copied",
    });
    let mut b =
        serde_json::to_vec_pretty(&side).map_err(|e| Error::Encode(format!("json: {e}")))?;
    b.push(b'\n');
    Ok(b)
}

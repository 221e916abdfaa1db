//! Blender EEVEE's rough-glass tables (EEVEE Next, Blender ≥ 4.2: `btdf_ggx[16][64][64][1]`
//! and `bsdf_ggx[16][64][64][3]` of `source/blender/draw/engines/eevee/eevee_lut.cc`,
//! declared in `eevee_lut.hh`) in EEVEE's own nodes and index order, each channel the
//! converged integral of what EEVEE's generator averages
//! ([`brdf_lut::generate::glass::eevee`]), written as the C++ arrays EEVEE compiles, with a
//! JSON sidecar.
//!
//! **EEVEE's layout** (pinned from blender/blender
//! `source/blender/draw/engines/eevee/shaders/eevee_lut_comp.glsl`, `main`,
//! `ggx_btdf_gt_one` and `ggx_bsdf_split_sum`; read, not copied). Endpoint nodes
//! u = i/(N − 1) on every axis; array index `[k][j][i][channel]` (x = i fastest):
//!
//! ```text
//! btdf_ggx (η > 1):  f = clamp(x², 1e-4, 0.9999),  η = (1 + f)/(1 − f)
//!                    μ = clamp(1 − y², 1e-4, 0.9999)
//! bsdf_ggx (η < 1):  η = clamp(√x, 1e-4, 0.9999),  c = √(1 − η²)  (critical cosine)
//!                    y' = 2y − 1,  μ = clamp(c + y'·(y' > 0 ? 1 − c : c), 1e-4, 0.9999)
//! both:              r = z,  α = r²
//! channels:          btdf [transmission_factor];  bsdf [scale, bias, transmission_factor]
//! ```

use crate::{Error, File};
use brdf_lut::generate::glass::eevee::{eevee_reflection, eevee_transmission};
use brdf_lut::generate::INTEGRATION_TOL;
use rayon::prelude::*;
use serde_json::json;
use std::fmt::Write as _;

use crate::Result;

/// EEVEE's x and y edge (64) and roughness slices (16).
pub const EEVEE_EDGE: usize = 64;
/// EEVEE's roughness slices.
pub const EEVEE_SLICES: usize = 16;

/// One of EEVEE's two glass tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    /// `btdf_ggx`: η > 1, one channel.
    Btdf,
    /// `bsdf_ggx`: η < 1, three channels.
    Bsdf,
}

impl Table {
    /// EEVEE's array name.
    pub fn name(self) -> &'static str {
        match self {
            Table::Btdf => "btdf_ggx",
            Table::Bsdf => "bsdf_ggx",
        }
    }
    /// Channels per node.
    pub fn channels(self) -> usize {
        match self {
            Table::Btdf => 1,
            Table::Bsdf => 3,
        }
    }
}

/// EEVEE's node of `table` at unit coordinates (x, y, z) = (i, j, k)/(N − 1): (μ, r, η)
/// (module docs; α = r²).
pub fn eevee_node(table: Table, x: f64, y: f64, z: f64) -> (f64, f64, f64) {
    match table {
        Table::Btdf => {
            let f = (x * x).clamp(1e-4, 0.9999);
            let mu = (1.0 - y * y).clamp(1e-4, 0.9999);
            (mu, z, (1.0 + f) / (1.0 - f))
        }
        Table::Bsdf => {
            let eta = x.sqrt().clamp(1e-4, 0.9999);
            let c = (1.0 - (eta * eta).clamp(0.0, 1.0)).sqrt();
            let y = 2.0 * y - 1.0;
            let mu = c + y * if y > 0.0 { 1.0 - c } else { c };
            (mu.clamp(1e-4, 0.9999), z, eta)
        }
    }
}

/// The channels of `table` at (μ, r, η) ([`Table::channels`] values) and the larger estimate.
pub fn eevee_values(table: Table, mu: f64, r: f64, eta: f64) -> (Vec<f64>, f64) {
    let a = r * r;
    let (t, wt) = eevee_transmission(mu, a, eta, INTEGRATION_TOL);
    match table {
        Table::Btdf => (vec![t[1]], wt.error),
        Table::Bsdf => {
            let (s, ws) = eevee_reflection(mu, a, eta, INTEGRATION_TOL);
            (vec![s[0], s[1], t[1]], wt.error.max(ws.error))
        }
    }
}

/// A table's values in EEVEE's order (k, j, i, channel) as f32 and the largest estimate;
/// an error for a non-finite integral. `dims` = (x and y edge, slices). All cores.
fn table_values(
    table: Table,
    dims: (usize, usize),
    progress: &(dyn Fn(u64) + Sync),
) -> Result<(Vec<f32>, f64)> {
    let (n, m) = dims;
    let u = |i: usize, n: usize| i as f64 / (n - 1) as f64;
    let nodes: Vec<(Vec<f64>, f64)> = (0..n * n * m)
        .into_par_iter()
        .map(|idx| {
            let (i, j, k) = (idx % n, idx / n % n, idx / (n * n));
            let (mu, r, eta) = eevee_node(table, u(i, n), u(j, n), u(k, m));
            let v = eevee_values(table, mu, r, eta);
            progress(1);
            v
        })
        .collect();
    let mut out = Vec::with_capacity(nodes.len() * table.channels());
    for (idx, (v, _)) in nodes.iter().enumerate() {
        for &x in v {
            if !x.is_finite() {
                return Err(Error::Encode(format!(
                    "{}[{idx}]: the integral is not finite ({x})",
                    table.name()
                )));
            }
            out.push(x as f32);
        }
    }
    let bound = nodes.iter().map(|p| p.1).fold(0.0, f64::max);
    Ok((out, bound))
}

/// One C++ array as `eevee_lut.cc` declares it: `const float <name>[m][n][n][ch] = {…};`,
/// nested braces, one y row per line; each value the shortest decimal that reads back as
/// the same f32, suffixed `f`.
fn cpp_array(table: Table, dims: (usize, usize), vals: &[f32]) -> String {
    let (n, m, ch) = (dims.0, dims.1, table.channels());
    let mut s = format!("const float {}[{m}][{n}][{n}][{ch}] = {{\n", table.name());
    for k in 0..m {
        s.push_str("    {");
        for j in 0..n {
            s.push_str(if j == 0 { "{" } else { "     {" });
            for i in 0..n {
                let at = ((k * n + j) * n + i) * ch;
                s.push('{');
                for (c, v) in vals[at..at + ch].iter().enumerate() {
                    let sep = if c + 1 < ch { ", " } else { "" };
                    let _ = write!(s, "{v:?}f{sep}");
                }
                s.push_str(if i + 1 < n { "}, " } else { "}" });
            }
            s.push_str(if j + 1 < n { "},\n" } else { "}" });
        }
        s.push_str(if k + 1 < m { "},\n" } else { "}\n" });
    }
    s.push_str("};\n");
    s
}

/// Blender EEVEE's rough-glass tables (module docs) with `edge` nodes on x and y (EEVEE:
/// 64) and `slices` roughness slices (EEVEE: 16), each 2..=[`EEVEE_EDGE`]:
/// `eevee_glass_lut.cc` (`btdf_ggx`, `bsdf_ggx` in namespace `blender::eevee::lut`) and the
/// sidecar `eevee_glass_lut.json`. Every value is converged to [`INTEGRATION_TOL`] per
/// channel in f64 at EEVEE's node, rounded to f32. `progress(1)` per node (2 × edge² ×
/// slices nodes; a `bsdf_ggx` node is two ring integrals).
pub fn eevee(edge: usize, slices: usize, progress: &(dyn Fn(u64) + Sync)) -> Result<Vec<File>> {
    for s in [edge, slices] {
        if !(2..=EEVEE_EDGE).contains(&s) {
            return Err(Error::Size(s));
        }
    }
    let dims = (edge, slices);
    let mut src = String::from(
        "/* Rough-glass tables for Blender EEVEE (eevee_lut.cc), written by brdf-kernels\n \
         * `cargo xtask lut engine eevee` (brdf_engine_assets::eevee): each value the converged\n \
         * integral of what eevee_lut_comp.glsl averages (see eevee_glass_lut.json). */\n\n\
         namespace blender::eevee::lut {\n\n",
    );
    let mut bounds = serde_json::Map::new();
    for table in [Table::Bsdf, Table::Btdf] {
        let (vals, bound) = table_values(table, dims, progress)?;
        bounds.insert(table.name().into(), json!(bound));
        src.push_str(&cpp_array(table, dims, &vals));
        src.push('\n');
    }
    src.push_str("}  // namespace blender::eevee::lut\n");
    Ok(vec![
        File {
            name: "eevee_glass_lut.cc".into(),
            bytes: src.into_bytes(),
        },
        File {
            name: "eevee_glass_lut.json".into(),
            bytes: sidecar(dims, bounds)?,
        },
    ])
}

/// The JSON sidecar of [`eevee`].
fn sidecar(
    dims: (usize, usize),
    bounds: serde_json::Map<String, serde_json::Value>,
) -> Result<Vec<u8>> {
    let (n, m) = dims;
    let side = json!({
        "target": "eevee",
        "files": {
            "eevee_glass_lut.cc": "C++ source: const float arrays bsdf_ggx and btdf_ggx as declared in Blender's source/blender/draw/engines/eevee/eevee_lut.hh (replace the blocks of the same names in eevee_lut.cc); values as f32 decimal literals that read back to the stored f32 exactly",
        },
        "arrays": { "bsdf_ggx": [m, n, n, 3], "btdf_ggx": [m, n, n, 1] },
        "drop_in": if n == EEVEE_EDGE && m == EEVEE_SLICES { "same names, shapes, nodes and index order as EEVEE's arrays, and the same integrands converged (EEVEE's own values are 512^2-sample Monte Carlo means)" } else { "no: EEVEE's texture is 64 x 64 x 16" },
        "integral": "p(h) = G1(v) (v.h)+ D(h)/mu (GGX visible normals), c = v.h, s = sqrt(eta^2 - 1 + c^2), S = Schlick factor (1 - cos)^5. transmission_factor = integral of p (1 - S) G1(|t_z|) over h with t_z < 0 (t the refraction of -v through h), cos = |h.v| = c for btdf_ggx (eta > 1), cos = |h.t| = s/eta for bsdf_ggx (eta < 1); scale = integral of p (1 - S) G1(l_z), bias = integral of p S G1(l_z) over h with l_z > 0 (l the reflection), cos = |h.t| = s/eta, S = 1 under total internal reflection (bsdf_ggx only). EEVEE reads T = (1 - F0) transmission_factor, R = F0 scale + F90 bias.",
        "model": "GGX NDF, alpha = r^2, separable Smith G1(v) G1(l) (EEVEE's bxdf_ggx_eval_reflection / _refraction), Fresnel replaced by Schlick's factors as EEVEE's generator does; brdf_lut::generate::glass::eevee::{eevee_transmission, eevee_reflection} (the ring rule)",
        "axes": {
            "x": "fastest, index i: u = i/(N - 1); btdf: f = clamp(u^2, 1e-4, 0.9999), eta = (1 + f)/(1 - f); bsdf: eta = clamp(sqrt(u), 1e-4, 0.9999)",
            "y": "index j: u = j/(N - 1); btdf: mu = clamp(1 - u^2, 1e-4, 0.9999); bsdf: c = sqrt(1 - eta^2), y' = 2u - 1, mu = clamp(c + y' (y' > 0 ? 1 - c : c), 1e-4, 0.9999)",
            "z": "index k: r = k/(slices - 1), alpha = r^2 (roughness slices)",
        },
        "orientation": "array[k][j][i][channel] (x = eta fastest, then y = mu, then z = roughness); EEVEE uploads slice k as one layer of a 64 x 64 RGBA16F array texture (rgb = bsdf_ggx, a = btdf_ggx), nodes on texel centres",
        "encoding": "IEEE binary32 (f32), round to nearest of the f64 integral; printed as the shortest decimal that reads back to the same f32 (EEVEE's own file prints 6 decimals)",
        "linear": true,
        "texel_values": format!("each channel converged by the ring rule to {INTEGRATION_TOL:e} (largest estimates below) in f64 at EEVEE's node; r = 0: the exact alpha = 0 limit (h = n)"),
        "integration_bound": bounds,
        "shipped": "EEVEE's own arrays (eevee_lut.cc) agree with these within 1e-4 at the 21 values of tests/eevee.rs (largest 7.1e-5), except the transmission near normal incidence on rough slices, where the shipped values are higher by up to 2.0e-3 (btdf_ggx[12][8][0] 0.977961 vs 0.976159, bsdf_ggx[15][58][63][2] 0.886356 vs 0.884310) while an f64 emulation of the generator as its sources stand reproduces these integrals to 3e-6 (docs/engines.md)",
        "sources": "blender/blender source/blender/draw/engines/eevee/shaders/eevee_lut_comp.glsl (integrands, nodes), eevee_bxdf_microfacet_lib.glsl (sampling, weights), eevee_lut.hh (array shapes); read, not copied",
    });
    crate::sidecar::sidecar_bytes(&side)
}

//! The glTF Sample Viewer's shipped sheen textures against the converged sheen albedo
//! (`brdf_lut::generate::sheen_e`, docs/lut-format.md kind `SheenAlbedo`) on the Khronos
//! axes: column μ = (i + ½)/n, PNG row j from the top r = (j + ½)/n.
//!
//! Three comparisons, each at every `step`-th texel of both axes (from texel 0):
//! `lut_charlie.png` B (the viewer's sheen "DG") against E with Ashikhmin's visibility, and
//! `lut_sheen_E.png` R against E with the Estevez–Kulla visibility, once as stored and once
//! after the sRGB → linear decode (IEC 61966-2-1) its values look encoded with. Only texels a
//! unit texture can hold (converged E ≤ 1) with μ ≥ cos 89° count.

use super::{png_units, DecodeError};
use crate::centre;
use brdf_lut::generate::sheen_e;
use rayon::prelude::*;

/// Absolute tolerance of the converged values: far below the 8-bit step (2e-3) and the
/// differences the comparison finds (medians ≥ 1e-3).
pub const TOL: f64 = 1e-5;

/// The smallest μ counted: cos 89°.
pub const MU_MIN: f64 = 0.017_452_406_437_283_5;

/// One shipped channel against one visibility's converged E.
#[derive(Clone, Debug, PartialEq)]
pub struct SheenDiff {
    /// What is compared.
    pub label: &'static str,
    /// (μ, r, shipped − converged) at each counted texel.
    pub texels: Vec<(f64, f64, f64)>,
    /// max |shipped − converged| over the counted texels.
    pub max: f64,
    /// (μ, r) where the max is.
    pub at: (f64, f64),
    /// Median |shipped − converged|.
    pub median: f64,
}

impl SheenDiff {
    /// The colour limit of this difference map: the 99th percentile of |difference| (at
    /// least 1e-4), rounded up to two significant digits; larger differences saturate.
    pub fn colour_limit(&self) -> f64 {
        let mut a: Vec<f64> = self.texels.iter().map(|t| t.2.abs()).collect();
        a.sort_by(f64::total_cmp);
        let p99 = a.get(a.len() * 99 / 100).copied().unwrap_or(1.0).max(1e-4);
        sig2_up(p99)
    }
}

/// `v` > 0 rounded up to two significant digits: ⌈v·s⌉/s with s = 10^(1 − ⌊log₁₀ v⌋).
pub fn sig2_up(v: f64) -> f64 {
    let scale = 10f64.powi(1 - v.log10().floor() as i32);
    (v * scale).ceil() / scale
}

/// The three comparisons and how many sampled texels no unit texture can hold.
#[derive(Clone, Debug, PartialEq)]
pub struct SheenCompare {
    /// Texture edge.
    pub n: usize,
    /// Every `step`-th texel of each axis is sampled.
    pub step: usize,
    /// Texels sampled.
    pub sampled: usize,
    /// Sampled texels whose converged E exceeds 1: [Estevez–Kulla, Ashikhmin].
    pub above_one: [usize; 2],
    /// Largest converged E (at the first texel centre): [Estevez–Kulla, Ashikhmin].
    pub max_converged: [f64; 2],
    /// `lut_charlie.png` B, `lut_sheen_E.png` R as stored, R after the sRGB decode.
    pub diffs: [SheenDiff; 3],
}

/// The sRGB decode (IEC 61966-2-1, §5.2): c/12.92 for c ≤ 0.04045, else ((c + 0.055)/1.055)^2.4.
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Compares the two shipped files (their bytes) with the converged integral (module docs).
/// Both must be square PNGs of one edge n; `step` is clamped into 1..=n.
pub fn compare_sheen(
    charlie: &[u8],
    sheen: &[u8],
    step: usize,
) -> Result<SheenCompare, DecodeError> {
    let (n, c_chan, c) = png_units(charlie)?;
    let (n2, s_chan, s) = png_units(sheen)?;
    if n != n2 {
        return Err(DecodeError(format!(
            "sheen files of edges {n} and {n2}: one edge expected"
        )));
    }
    let step = step.clamp(1, n);
    let idx: Vec<(usize, usize)> = (0..n)
        .step_by(step)
        .flat_map(|j| (0..n).step_by(step).map(move |i| (i, j)))
        .collect();
    let conv: Vec<[f64; 2]> = idx
        .par_iter()
        .map(|&(i, j)| sheen_e(centre(i, n), centre(j, n), TOL).value)
        .collect();
    let pick = |chan: usize, which: usize, v: &[f64], ch: usize, f: fn(f64) -> f64| {
        idx.iter()
            .zip(&conv)
            .filter(|&(&(i, _), e)| e[ch] <= 1.0 && centre(i, n) >= MU_MIN)
            .map(|(&(i, j), e)| {
                (
                    centre(i, n),
                    centre(j, n),
                    f(v[(j * n + i) * chan + which]) - e[ch],
                )
            })
            .collect::<Vec<_>>()
    };
    let count = |ch: usize| conv.iter().filter(|e| e[ch] > 1.0).count();
    Ok(SheenCompare {
        n,
        step,
        sampled: idx.len(),
        above_one: [count(0), count(1)],
        max_converged: conv
            .iter()
            .fold([0.0; 2], |m, e| [m[0].max(e[0]), m[1].max(e[1])]),
        diffs: [
            stats(
                "lut_charlie.png B (8-bit) vs Ashikhmin E",
                pick(c_chan, 2, &c, 1, |x| x),
            ),
            stats(
                "lut_sheen_E.png R as stored (16-bit) vs Estevez–Kulla E",
                pick(s_chan, 0, &s, 0, |x| x),
            ),
            stats(
                "lut_sheen_E.png R after the sRGB decode vs Estevez–Kulla E",
                pick(s_chan, 0, &s, 0, srgb_to_linear),
            ),
        ],
    })
}

/// Max (and where) and median of |d| over the texels.
fn stats(label: &'static str, texels: Vec<(f64, f64, f64)>) -> SheenDiff {
    let mut abs: Vec<f64> = texels.iter().map(|t| t.2.abs()).collect();
    abs.sort_by(f64::total_cmp);
    let top = texels
        .iter()
        .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
        .copied()
        .unwrap_or((f64::NAN, f64::NAN, f64::NAN));
    SheenDiff {
        label,
        max: top.2.abs(),
        at: (top.0, top.1),
        median: abs.get(abs.len() / 2).copied().unwrap_or(f64::NAN),
        texels,
    }
}

#[cfg(test)]
mod tests {
    /// Two significant digits, rounded up (hand-computed): 0.0123 → 0.013, 0.25 stays
    /// (exact in binary), 0.0101 → 0.011, 3.01 → 3.1.
    #[test]
    fn sig2_up_rounds_up_to_two_digits() {
        for (v, want) in [(0.0123, 0.013), (0.25, 0.25), (0.0101, 0.011), (3.01, 3.1)] {
            let got = super::sig2_up(v);
            assert!((got - want).abs() <= 1e-12 * want, "{v}: {got}");
        }
    }
}

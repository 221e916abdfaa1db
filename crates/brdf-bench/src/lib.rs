//! # brdf-bench
//!
//! Shared workloads of the benchmark suite (`benches/kernels.rs`, run by `cargo xtask bench`)
//! and of the callgrind harness (`src/bin/harness.rs`), so that criterion, callgrind and the
//! SciPy peer (`peer/g_peer.py`) all evaluate the same inputs.
//!
//! [`run`] is `cargo xtask bench`: it runs the suite, the harness and the peers and writes
//! the report ([`report`]) to docs/benchmarks.md.
//!
//! Also holds the one kernel that exists only as a point of comparison: Karis's analytic
//! approximation of the split-sum pair ([`env_brdf_approx`]).

pub mod report;
pub mod run;

use brdf_core::{Dots, Real};
use brdf_lut::LutView;
use std::path::PathBuf;

/// Inputs per benchmark iteration: every "per call" figure is an iteration's time divided
/// by this.
pub const BATCH: usize = 64;

/// The RMS slope used by the G benchmarks (one of the per-σ tables' σ).
pub const SIGMA: f64 = 0.3;

/// Elements per call of the batch entry points.
pub const BATCH_LEN: usize = 1024;

/// A deterministic low-discrepancy point in [0, 1)² (additive recurrence on the plastic
/// number), index `k`.
pub fn r2(k: usize) -> (f64, f64) {
    const G: f64 = 1.324_717_957_244_746;
    let (a1, a2) = (1.0 / G, 1.0 / (G * G));
    let k = k as f64 + 1.0;
    ((0.5 + a1 * k).fract(), (0.5 + a2 * k).fract())
}

/// `n` in-plane angle pairs (θi ∈ [0, 89°], θr ∈ [−89°, 89°]) spread over the whole domain,
/// so that every branch of the modified G (fully passing only, both integrals, both signs)
/// is timed in its natural proportion.
pub fn angle_pairs<T: Real>(n: usize) -> (Vec<T>, Vec<T>) {
    let lim = 89f64.to_radians();
    (0..n)
        .map(|k| {
            let (a, b) = r2(k);
            (T::from_f64(a * lim), T::from_f64((2.0 * b - 1.0) * lim))
        })
        .unzip()
}

/// The same pairs as shader dot products (n·wi, n·wo, wi·wo).
pub fn dots_pairs<T: Real>(n: usize) -> Vec<Dots<T>> {
    let (ti, tr) = angle_pairs::<f64>(n);
    ti.iter()
        .zip(&tr)
        .map(|(&a, &b)| {
            let d = Dots::<f64>::in_plane(a, b);
            Dots::new(T::from_f64(d.n_i), T::from_f64(d.n_o), T::from_f64(d.i_o))
        })
        .collect()
}

/// `n` (μ, roughness) points, μ ∈ [cos 89°, 1], roughness ∈ [0, 1].
pub fn mu_roughness(n: usize) -> Vec<(f64, f64)> {
    let mu_min = 89f64.to_radians().cos();
    (0..n)
        .map(|k| {
            let (a, b) = r2(k + 1000);
            (mu_min + (1.0 - mu_min) * a, b)
        })
        .collect()
}

/// `n` unit view directions above the horizon and `n` uniform pairs in [0, 1)² (for models'
/// evaluation and sampling).
pub fn directions<T: Real>(n: usize) -> Vec<brdf_core::Vec3<T>> {
    (0..n)
        .map(|k| {
            let (a, b) = r2(k + 77);
            let z = 0.02 + 0.98 * a; // cos θ ∈ [0.02, 1)
            let s = (1.0 - z * z).sqrt();
            let phi = 2.0 * std::f64::consts::PI * b;
            brdf_core::Vec3::new(
                T::from_f64(s * phi.cos()),
                T::from_f64(s * phi.sin()),
                T::from_f64(z),
            )
        })
        .collect()
}

/// Karis's analytic approximation of the GGX split-sum pair (A, B) for real-time mobile
/// shading ("EnvBRDFApprox", Karis 2014, after Lazarov 2013): a hand-fitted function of
/// μ = n·v and perceptual roughness r with no table and no integral.
///
/// The fit, in this crate's words: two linear functions of r,
/// c = (−1, −0.0275, −0.572, 0.022)·r + (1, 0.0425, 1.04, −0.04); an envelope
/// t = min(c₀², 2^(−9.28 μ))·c₀ + c₁ that falls off with μ like Schlick's (1 − μ)⁵ and is
/// capped by the roughness term; then A = −1.04 t + c₂ and B = 1.04 t + c₃.
/// Accuracy against the exact integral is reported in `docs/benchmarks.md`.
#[inline]
pub fn env_brdf_approx<T: Real>(mu: T, r: T) -> (T, T) {
    let f = T::from_f64;
    let c0 = f(1.0) - r;
    let c1 = f(0.0425) - f(0.0275) * r;
    let c2 = f(1.04) - f(0.572) * r;
    let c3 = f(0.022) * r - f(0.04);
    let t = (c0 * c0).min((f(-9.28 * core::f64::consts::LN_2) * mu).exp()) * c0 + c1;
    (f(-1.04) * t + c2, f(1.04) * t + c3)
}

/// The workspace root (this crate lives in `crates/brdf-bench`).
pub fn workspace_root() -> PathBuf {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors().nth(2).unwrap_or(here).to_path_buf()
}

/// The workspace's `assets/` directory (the default LUT set).
pub fn assets_dir() -> PathBuf {
    workspace_root().join("assets")
}

/// Reads one default asset; `None` (and a message on stderr) when it is missing or invalid,
/// so a bench run without generated assets skips the LUT benches instead of failing.
pub fn read_asset(name: &str) -> Option<Vec<u8>> {
    let p = assets_dir().join(name);
    match std::fs::read(&p) {
        Ok(b) if LutView::parse(&b).is_ok() => Some(b),
        Ok(_) => {
            eprintln!("skipping {name}: not a valid LUT (regenerate with `cargo xtask lut`)");
            None
        }
        Err(e) => {
            eprintln!("skipping {name}: {e} (generate with `cargo xtask lut`)");
            None
        }
    }
}

/// The 3-D modified-G table (θ, φ, σ) of the default set.
pub const G3_ASSET: &str = "g_modified.blut";
/// The per-σ modified-G table for [`SIGMA`].
pub const G2_ASSET: &str = "g_modified_sigma0.3.blut";
/// The speed tier of [`G3_ASSET`]: trilinear on a denser grid.
pub const G3_LINEAR_ASSET: &str = "g_modified_linear.blut";
/// The speed tier of [`G2_ASSET`]: bilinear on a denser grid.
pub const G2_LINEAR_ASSET: &str = "g_modified_sigma0.3_linear.blut";
/// The GGX split-sum table, accuracy tier (bicubic, 64², log μ axis).
pub const DFG_ASSET: &str = "dfg_ggx.blut";
/// The speed tier of [`DFG_ASSET`]: bilinear on a 256² grid with √-warped axes, the table
/// the `dfg_lut*` kernel targets time.
pub const DFG_LINEAR_ASSET: &str = "dfg_ggx_linear.blut";
/// The GGX directional-albedo table E(μ, r).
pub const E_ASSET: &str = "kc_e_ggx.blut";
/// The GGX average-albedo table E_avg(r).
pub const EAVG_ASSET: &str = "kc_eavg_ggx.blut";

/// The floor every table lookup is held against: a plain bilinear fetch from a 64×64
/// two-channel u16 array on linear, endpoint axes over [0, 1]², written as simply as
/// possible (no header, no warp, no per-channel scale beyond 1/65535).
pub struct FloorBilinear2 {
    data: Vec<[u16; 2]>,
}

impl Default for FloorBilinear2 {
    fn default() -> Self {
        Self::new()
    }
}

impl FloorBilinear2 {
    /// Nodes per axis.
    pub const N: usize = 64;

    /// A table of smooth made-up values (the content does not matter for the cost).
    pub fn new() -> Self {
        let n = Self::N;
        let data = (0..n * n)
            .map(|k| {
                let (i, j) = ((k % n) as f64, (k / n) as f64);
                let a = 0.5 + 0.4 * (0.1 * i).sin() * (0.07 * j).cos();
                let b = 0.3 + 0.2 * (0.05 * (i + j)).cos();
                [(a * 65535.0) as u16, (b * 65535.0) as u16]
            })
            .collect();
        Self { data }
    }

    /// Bilinear (channel 0, channel 1) at (x, y) ∈ [0, 1]² (clamped).
    #[inline]
    pub fn fetch(&self, x: f32, y: f32) -> (f32, f32) {
        let last = (Self::N - 1) as f32;
        let tx = x.clamp(0.0, 1.0) * last;
        let ty = y.clamp(0.0, 1.0) * last;
        let i = (tx as usize).min(Self::N - 2);
        let j = (ty as usize).min(Self::N - 2);
        let (fx, fy) = (tx - i as f32, ty - j as f32);
        let at = |i: usize, j: usize| self.data[j * Self::N + i];
        let (p00, p10, p01, p11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
        let lerp2 = |c: usize| {
            let lo = p00[c] as f32 + fx * (p10[c] as f32 - p00[c] as f32);
            let hi = p01[c] as f32 + fx * (p11[c] as f32 - p01[c] as f32);
            (lo + fy * (hi - lo)) * (1.0 / 65535.0)
        };
        (lerp2(0), lerp2(1))
    }
}

/// A value of an example's `--name value` option ([`example_options!`]).
pub trait OptionValue: Sized {
    /// The value written `s`; None when `s` does not parse.
    fn parse_option(s: &str) -> Option<Self>;
}

macro_rules! option_value_from_str {
    ($($t:ty),*) => {$(
        impl OptionValue for $t {
            fn parse_option(s: &str) -> Option<Self> {
                s.parse().ok()
            }
        }
    )*};
}
option_value_from_str!(usize, u64, u32, f64);

/// A path or name: the text itself.
impl OptionValue for Option<String> {
    fn parse_option(s: &str) -> Option<Self> {
        Some(Some(s.to_string()))
    }
}

/// A switch written as a number: 0 is off, any other integer on.
impl OptionValue for bool {
    fn parse_option(s: &str) -> Option<Self> {
        s.parse::<u32>().ok().map(|v| v != 0)
    }
}

/// An examples' options struct: `example_options! { struct Args { field: Type = default,
/// "--flag"; … } }` declares the struct and `Args::from_args()`, which reads the command
/// line as `--flag value` pairs over the defaults and panics on an unknown flag or a value
/// that does not parse ([`OptionValue`]).
#[macro_export]
macro_rules! example_options {
    (struct $name:ident { $($field:ident: $ty:ty = $default:expr, $flag:literal;)* }) => {
        struct $name {
            $($field: $ty,)*
        }

        impl $name {
            fn from_args() -> Self {
                let mut a = Self { $($field: $default,)* };
                let v: Vec<String> = std::env::args().skip(1).collect();
                for p in v.chunks(2) {
                    let x = p.get(1).map_or("", String::as_str);
                    match p[0].as_str() {
                        $($flag => {
                            a.$field = $crate::OptionValue::parse_option(x).expect($flag)
                        })*
                        o => panic!("unknown option {o}"),
                    }
                }
                a
            }
        }
    };
}

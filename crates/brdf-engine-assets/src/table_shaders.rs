//! What a shader needs to read an exported table: the per-axis inverse mapping (physical value
//! → texture coordinate) as sidecar JSON, the roughness convention of the table's model, and a
//! GLSL and a WGSL function that sample an exported 2-D table (warp, placement, `texture()`,
//! channel decode).
//!
//! Warps (docs/lut-format.md): t = (x − lo)/(hi − lo) (linear), ln(x/lo)/ln(hi/lo) (log),
//! √((x − lo)/(hi − lo)) (sqrt), (cos lo − cos x)/(cos lo − cos hi) (cos),
//! (√cos lo − √cos x)/(√cos lo − √cos hi) (sqrt-cos), x clamped to [lo, hi] first and t to
//! [0, 1]. Placement: endpoint nodes sit at t = i/(N − 1), i.e. at texel centres
//! u = (i + ½)/N, so u = (t·(N − 1) + ½)/N; texel-centre nodes sit at t = (i + ½)/N, so u = t.

use brdf_lut::{Axis, Header, Interpolation, Model, Placement, Warp};
use serde_json::{json, Value};

/// The warp name used in the sidecar.
pub fn warp_name(w: Warp) -> &'static str {
    match w {
        Warp::Linear => "linear",
        Warp::Log => "log",
        Warp::Sqrt => "sqrt",
        Warp::Cos => "cos",
        Warp::SqrtCos => "sqrt-cos",
    }
}

fn warp_t_formula(w: Warp) -> &'static str {
    match w {
        Warp::Linear => "t = (x - lo) / (hi - lo)",
        Warp::Log => "t = ln(x / lo) / ln(hi / lo)",
        Warp::Sqrt => "t = sqrt((x - lo) / (hi - lo))",
        Warp::Cos => "t = (cos(lo) - cos(x)) / (cos(lo) - cos(hi))   (x in radians)",
        Warp::SqrtCos => {
            "t = (sqrt(cos(lo)) - sqrt(max(cos(x), 0))) / (sqrt(cos(lo)) - sqrt(max(cos(hi), 0)))   (x in radians)"
        }
    }
}

fn u_formula(p: Placement) -> &'static str {
    match p {
        Placement::Endpoint => "u = (t * (N - 1) + 0.5) / N",
        Placement::TexelCentre => "u = t",
    }
}

/// The warp origin and 1/span in f32, exactly as `brdf_lut::AxisMap` computes them.
fn warp_consts(a: &Axis<'_>) -> (f32, f32) {
    let (lo, hi) = (a.lo as f32, a.hi as f32);
    let (base, span) = match a.warp {
        Warp::Linear | Warp::Sqrt => (lo, hi - lo),
        Warp::Log => (lo.ln(), hi.ln() - lo.ln()),
        Warp::Cos => (lo.cos(), lo.cos() - hi.cos()),
        Warp::SqrtCos => {
            let (p, q) = (lo.cos().sqrt(), hi.cos().max(0.0).sqrt());
            (p, p - q)
        }
    };
    (base, 1.0 / span)
}

/// The sidecar's `inverse_mapping` entry of one axis.
pub fn axis_mapping(k: usize, a: &Axis<'_>) -> Value {
    let (base, inv) = warp_consts(a);
    json!({
        "axis": k,
        "name": a.name,
        "texture_coordinate": if k == 0 { "u (x, columns)" } else if k == 1 { "v (y, rows; row 0 = first row of the data, v = 0)" } else { "w / layer" },
        "warp": warp_name(a.warp),
        "lo": a.lo,
        "hi": a.hi,
        "clamp": [a.lo, a.hi],
        "count": a.count,
        "placement": match a.placement { Placement::Endpoint => "endpoint", Placement::TexelCentre => "texel-centre" },
        "step_1_clamp": "x = clamp(x, lo, hi)",
        "step_2_warp": warp_t_formula(a.warp),
        "step_3_clamp": "t = clamp(t, 0, 1)",
        "step_4_placement": u_formula(a.placement),
        "warp_base_f32": base,
        "warp_inv_span_f32": inv,
        "warp_compact": match a.warp {
            Warp::Linear => "t = (x - base) * inv",
            Warp::Log => "t = (ln(x) - base) * inv",
            Warp::Sqrt => "t = sqrt(max((x - base) * inv, 0))",
            Warp::Cos => "t = (base - cos(x)) * inv",
            Warp::SqrtCos => "t = (base - sqrt(max(cos(x), 0))) * inv",
        },
    })
}

/// The roughness convention of a model's roughness axis.
pub fn roughness_convention(m: Model) -> &'static str {
    match m {
        Model::GgxSmithCorrelated | Model::GgxSmithSeparable | Model::RoughDielectricGgx => {
            "perceptual roughness r in [0, 1]; GGX alpha = r^2"
        }
        Model::BeckmannSmithCorrelated
        | Model::BeckmannSmithSeparable
        | Model::RoughDielectricBeckmann => {
            "perceptual roughness r in [0, 1]; Beckmann m = alpha = r^2"
        }
        Model::ModifiedG => {
            "sigma = RMS surface slope of the Gaussian surface (the 2015 Acta Physica Sinica paper, eqs 6-13); not a perceptual roughness"
        }
        Model::TorranceSparrowModifiedG
        | Model::TorranceSparrowSmith
        | Model::TorranceSparrowSmithSeparable
        | Model::TorranceSparrowVCavity => {
            "sigma = RMS slope of the Gaussian slope distribution; Beckmann m = sqrt(2) * sigma; not a perceptual roughness"
        }
        Model::SheenEstevezKulla | Model::SheenAshikhmin => {
            "perceptual sheen roughness r in [0, 1]; Charlie alpha = r^2, clamped at 1e-4"
        }
    }
}

/// A float literal both GLSL ES 3.0 and WGSL read as f32 (always with a decimal point or an
/// exponent; Rust's shortest round-trip form). Only finite values reach it (validated header).
fn lit(x: f32) -> String {
    let s = format!("{x:?}");
    let s = if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    };
    // Parenthesised when negative, so `a - -b` never reads as a decrement token.
    if s.starts_with('-') {
        format!("({s})")
    } else {
        s
    }
}

/// The shader expression of t for axis `a` on variable `x` (`wgsl` picks `max`/`log` forms
/// valid in both languages — they are the same here).
fn t_expr(a: &Axis<'_>, x: &str) -> String {
    let (base, inv) = warp_consts(a);
    let (b, i) = (lit(base), lit(inv));
    match a.warp {
        Warp::Linear => format!("({x} - {b}) * {i}"),
        Warp::Log => format!("(log({x}) - {b}) * {i}"),
        Warp::Sqrt => format!("sqrt(max(({x} - {b}) * {i}, 0.0))"),
        Warp::Cos => format!("({b} - cos({x})) * {i}"),
        Warp::SqrtCos => format!("({b} - sqrt(max(cos({x}), 0.0))) * {i}"),
    }
}

fn u_expr(a: &Axis<'_>, t: &str) -> String {
    match a.placement {
        Placement::Endpoint => {
            let n = a.count as f32;
            format!("({t} * {} + 0.5) / {}", lit(n - 1.0), lit(n))
        }
        Placement::TexelCentre => t.to_string(),
    }
}

/// A name from the file made safe for a shader comment.
fn ident(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
        .take(32)
        .collect()
}

/// Channel decode value = offset + scale × texel, per channel (identity for float textures).
pub type Decode = Vec<(f32, f32)>;

/// The sampling-function templates: a shared comment head, then one function per language
/// (rendered one after the other: the workspace builds minijinja without `include`).
const HEAD: &str = include_str!("../templates/shaders/head.txt");
const GLSL: &str = include_str!("../templates/shaders/sampler.glsl");
const WGSL: &str = include_str!("../templates/shaders/sampler.wgsl");

/// What a sampling function needs of one axis: its clamp range, t (warp) and u (placement)
/// expressions, as shader source.
fn axis_ctx(a: &Axis<'_>, x: &str) -> minijinja::Value {
    minijinja::context! {
        name => ident(a.name),
        lo => lit(a.lo as f32),
        hi => lit(a.hi as f32),
        t => t_expr(a, x),
        u => u_expr(a, &x.replace('x', "t")),
    }
}

/// The GLSL ES 3.0 and WGSL sampling functions for a 2-D table named `name`; `None` for other
/// dimensions or more than 2 channels (or, which cannot happen with the fixed templates, a
/// template error).
pub fn shaders(h: &Header<'_>, name: &str, decode: &Decode) -> Option<(String, String)> {
    if h.axes.len() != 2 || !(1..=2).contains(&decode.len()) {
        return None;
    }
    let (off, scale): (Vec<String>, Vec<String>) =
        decode.iter().map(|&(o, s)| (lit(o), lit(s))).unzip();
    let ctx = minijinja::context! {
        name => name,
        nc => decode.len(),
        a0 => axis_ctx(&h.axes[0], "x0"),
        a1 => axis_ctx(&h.axes[1], "x1"),
        catmull_rom => h.interpolation == Interpolation::CatmullRom,
        off => off,
        scale => scale,
    };
    let mut env = minijinja::Environment::new();
    env.set_auto_escape_callback(|_| minijinja::AutoEscape::None);
    env.set_undefined_behavior(minijinja::UndefinedBehavior::Strict);
    env.set_trim_blocks(true);
    env.set_keep_trailing_newline(true);
    for (n, t) in [("head.txt", HEAD), ("glsl", GLSL), ("wgsl", WGSL)] {
        env.add_template(n, t).ok()?;
    }
    let render = |n: &str| env.get_template(n).ok()?.render(&ctx).ok();
    let head = render("head.txt")?;
    Some((head.clone() + &render("glsl")?, head + &render("wgsl")?))
}

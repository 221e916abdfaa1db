//! `cargo xtask eval brdf` end to end: the binary is run on CSV input and its output is
//! checked against closed forms written out here, and its errors against bad input.

use std::process::Output;

mod common;
use common::{fails_with, stderr};

/// `cargo xtask eval brdf args` with `stdin` as input.
fn run(args: &[&str], stdin: &str) -> Output {
    common::xtask_stdin(&[&["eval", "brdf"], args].concat(), stdin)
}

fn rows(o: &Output) -> Vec<Vec<f64>> {
    let s = String::from_utf8(o.stdout.clone()).unwrap();
    let mut lines = s.lines();
    assert_eq!(lines.next(), Some("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,r,g,b"));
    lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect()
}

#[test]
fn list_names_every_model_and_parameter() {
    let o = run(&["--list"], "");
    assert!(o.status.success());
    let s = String::from_utf8(o.stdout).unwrap();
    for m in [
        "lambert",
        "standard",
        "phong",
        "blinn-phong",
        "cook-torrance",
        "lambert-mirror",
        "shirley-damped",
        "coupled-smooth",
        "torrance-sparrow",
        "ggx-anisotropic",
        "ashikhmin-shirley",
        "bank",
        "rough-dielectric",
        "ward",
        "ggx",
    ] {
        assert!(s.lines().any(|l| l == m), "model {m} missing from --list");
    }
    for p in [
        "alpha",
        "nu",
        "nv",
        "r0",
        "gloss",
        "tangent_azimuth",
        "default",
        "range",
        "unit",
    ] {
        assert!(s.contains(p), "{p} missing from --list");
    }
}

#[test]
fn lambert_and_coupled_match_closed_forms() {
    let o = run(
        &["--model", "lambert", "--param", "albedo=0.5,0.25,1"],
        "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0,0,1,0,0,1\n0.6,0,0.8,0,0.6,0.8\n0,0,-1,0,0,1\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&o);
    assert_eq!(r.len(), 3);
    let pi = std::f64::consts::PI;
    assert_eq!(&r[0][..6], &[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    for row in &r[..2] {
        assert!((row[6] - 0.5 / pi).abs() < 1e-15 && (row[7] - 0.25 / pi).abs() < 1e-15);
        assert!((row[8] - 1.0 / pi).abs() < 1e-15);
    }
    assert_eq!(&r[2][6..], &[0.0, 0.0, 0.0], "below the horizon");

    // Coupled, default (conserving) k at normal incidence: k = 21(1 − R0)/(20π), f = 1.
    let o = run(
        &["--model", "coupled", "--param", "r0=0.05"],
        "0,0,1,0,0,1\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let want = 21.0 * 0.95 / (20.0 * pi);
    assert!((rows(&o)[0][6] - want).abs() < 1e-15);
    let o = run(
        &[
            "--model",
            "coupled",
            "--param",
            "r0=0.05",
            "--param",
            "k=printed",
        ],
        "0,0,1,0,0,1\n",
    );
    let want = 21.0 / (20.0 * pi * 0.95);
    assert!((rows(&o)[0][6] - want).abs() < 1e-14);
}

#[test]
fn ggx_matches_its_formula() {
    // wi at 30° in x–z, wo at 45° in y–z; h, D, V, F written out independently.
    let (a, f0) = (0.3f64, 0.04f64);
    let wi = [0.5f64, 0.0, 3f64.sqrt() / 2.0];
    let wo = [0.0, 1.0 / 2f64.sqrt(), 1.0 / 2f64.sqrt()];
    let s = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
    let l = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    let h = [s[0] / l, s[1] / l, s[2] / l];
    let a2 = a * a;
    let d = a2 / (std::f64::consts::PI * (h[2] * h[2] * (a2 - 1.0) + 1.0).powi(2));
    let lam = |c: f64| ((1.0 + a2 * (1.0 - c * c) / (c * c)).sqrt() - 1.0) / 2.0;
    let g = 1.0 / (1.0 + lam(wi[2]) + lam(wo[2]));
    let ih = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
    let f = f0 + (1.0 - f0) * (1.0 - ih).powi(5);
    let want = d * g * f / (4.0 * wi[2] * wo[2]);
    let input = format!(
        "{},{},{},{},{},{}\n",
        wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]
    );
    let o = run(
        &[
            "--model",
            "ggx",
            "--param",
            "alpha=0.3",
            "--param",
            "f0=0.04",
        ],
        &input,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let got = rows(&o)[0][6];
    assert!((got - want).abs() < 1e-12 * want, "{got} vs {want}");
}

/// `rough-dielectric` accepts wo below the surface and returns the transmitted part there.
/// At normal incidence everything is closed form: h = n, D(n) = 1/(π α²), G1 = 1,
/// F = ((η − 1)/(η + 1))², reflection F D/4 (Walter eq 20) and transmission
/// η_o² (1 − F) D/(η_i − η_o)² (eq 21 with i·h = 1, o·h = −1), in both directions of travel.
#[test]
fn rough_dielectric_transmits_below_the_surface() {
    let (a, eta) = (0.3f64, 1.5f64);
    let d = 1.0 / (std::f64::consts::PI * a * a);
    let f = ((eta - 1.0) / (eta + 1.0)).powi(2);
    let refl = f * d / 4.0;
    let into = eta * eta * (1.0 - f) * d / (1.0 - eta).powi(2);
    let out = (1.0 - f) * d / (eta - 1.0).powi(2);
    let input = "0,0,1,0,0,1\n0,0,1,0,0,-1\n0,0,-1,0,0,1\n0,0,-1,0,0,-1\n";
    let args = [
        "--model",
        "rough-dielectric",
        "--param",
        "alpha=0.3",
        "--param",
        "eta=1.5",
    ];
    let o = run(&args, input);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&o);
    for (row, want) in r.iter().zip([refl, into, out, refl]) {
        assert!((row[6] - want).abs() < 1e-12 * want, "{row:?} vs {want}");
    }
    // η = 1: an invisible interface, its straight-through Dirac not in r,g,b.
    let o = run(&["--model", "rough-glass", "--param", "eta=1"], input);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(rows(&o).iter().all(|row| row[6] == 0.0));
}

#[test]
fn bad_input_is_a_clear_error() {
    let o = run(&["--model", "nosuch"], "0,0,1,0,0,1\n");
    fails_with(&o, "unknown model `nosuch`");

    let o = run(&["--model", "ggx", "--param", "beta=1"], "0,0,1,0,0,1\n");
    fails_with(&o, "no parameter `beta`");

    let o = run(&["--model", "ggx", "--param", "alpha=0"], "0,0,1,0,0,1\n");
    fails_with(&o, "alpha");

    let o = run(&["--model", "ggx", "--param", "alpha"], "");
    assert!(!o.status.success());

    let o = run(
        &["--model", "ggx"],
        "0,0,1,0,0,1\n0,0,1,0,0,1\n0,0,1,0,zero,1\n",
    );
    fails_with(&o, "line 3");

    let o = run(&["--model", "ggx"], "0,0,1,0,0\n");
    fails_with(&o, "line 1");
    fails_with(&o, "6 fields");

    let o = run(&["--model", "ggx"], "0,0,0,0,0,1\n");
    fails_with(&o, "line 1: wi is a zero vector");

    let o = run(&[], "");
    assert!(!o.status.success());
}

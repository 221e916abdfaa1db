//! The shared `eval` input reader end to end (line cap, BOM) and the range warnings of
//! `eval dfg` and `eval g --lut`.

use std::process::Output;

mod common;
use common::{stderr, stdout, xtask_stdin as run, xtask_with as run_with};

/// The (A, B) columns of `eval dfg` output rows.
fn ab(o: &Output) -> Vec<(f64, f64)> {
    stdout(o)
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (f[2], f[3])
        })
        .collect()
}

#[test]
fn nul_stream_is_refused_after_the_line_cap() {
    // 1 GiB of NUL bytes offered in 64 KiB chunks; the tool must stop with a clear error
    // long before (it reads at most one capped line).
    for cmd in [
        &["eval", "dfg", "--direct"][..],
        &["eval", "g"][..],
        &["eval", "brdf", "--model", "lambert"][..],
    ] {
        let chunks = (0..(1 << 14)).map(|_| vec![0u8; 64 << 10]);
        let o = run_with(cmd, chunks);
        assert!(!o.status.success(), "{cmd:?}");
        let e = stderr(&o);
        assert!(e.contains("line 1: longer than 4096 bytes"), "{cmd:?}: {e}");
    }
}

#[test]
fn bom_is_stripped() {
    let plain = run(&["eval", "dfg", "--direct"], "mu,roughness\n0.5,0.5\n");
    let bom = run(
        &["eval", "dfg", "--direct"],
        "\u{feff}mu,roughness\n0.5,0.5\n",
    );
    let bom_data = run(&["eval", "dfg", "--direct"], "\u{feff}0.5,0.5\n");
    for o in [&plain, &bom, &bom_data] {
        assert!(o.status.success(), "{}", stderr(o));
    }
    assert_eq!(stdout(&plain), stdout(&bom));
    assert_eq!(stdout(&plain), stdout(&bom_data));
    let g = run(
        &["eval", "g"],
        "\u{feff}theta_i_deg,theta_r_deg,sigma\n30,60,0.3\n",
    );
    assert!(g.status.success(), "{}", stderr(&g));
    assert_eq!(stdout(&g).lines().count(), 2);
}

#[test]
fn dfg_warns_where_the_table_clamps_grazing_mu() {
    // cos 89°: the default table's smallest μ.
    let mu_min = 89f64.to_radians().cos();
    let input = format!("0.001,0.5\n{mu_min},0.5\n0.5,0.5\n");
    let t = run(&["eval", "dfg"], &input);
    assert!(t.status.success(), "{}", stderr(&t));
    let e = stderr(&t);
    assert!(e.contains("warning: 1 row(s) (the first on line 1)"), "{e}");
    assert!(e.contains("clamped"), "{e}");
    let v = ab(&t);
    // Clamped: μ = 0.001 answers the table's value at its edge (up to the f32 rounding of
    // the warp at the edge node, far below 1e-6).
    assert!(
        (v[0].0 - v[1].0).abs() < 1e-6 && (v[0].1 - v[1].1).abs() < 1e-6,
        "{v:?}"
    );
    // The direct integrals at μ = 0.001 and at cos 89° differ by more than 1e-3 (far more
    // than their quadrature error): that difference is what the warning is about.
    let d = run(&["eval", "dfg", "--direct"], &input);
    assert!(d.status.success());
    assert!(stderr(&d).is_empty(), "{}", stderr(&d));
    let w = ab(&d);
    assert!((w[0].0 - w[1].0).abs() > 1e-3, "{w:?}");
    // Inside the range: no warning.
    let ok = run(&["eval", "dfg"], "0.5,0.5\n");
    assert!(stderr(&ok).is_empty(), "{}", stderr(&ok));
}

#[test]
fn g_lut_refuses_sigma_outside_the_table() {
    let o = run(&["eval", "g", "--lut"], "30,60,5\n");
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains("line 1: sigma 5 is outside the table's range [0.05, 1]"),
        "{e}"
    );
    // Inside: the table's G agrees with the direct G (same row, no --lut) to well within
    // 1e-3 (the committed table's recorded max |error| is ~1e-5).
    let row = "30,60,0.3\n";
    let (t, d) = (run(&["eval", "g", "--lut"], row), run(&["eval", "g"], row));
    assert!(t.status.success() && d.status.success(), "{}", stderr(&t));
    let g = |o: &Output| -> f64 {
        let l = stdout(o).lines().nth(1).unwrap().to_string();
        l.split(',').nth(5).unwrap().parse().unwrap()
    };
    assert!((g(&t) - g(&d)).abs() < 1e-3, "{} vs {}", g(&t), g(&d));
}

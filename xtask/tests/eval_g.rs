//! `cargo xtask eval g` end to end: values against the independent reference, the error path.

use brdf_tests::reference::RefDensity;

mod common;

/// `cargo xtask eval g args` with `input` on stdin: (success, stdout, stderr).
fn run(args: &[&str], input: &str) -> (bool, String, String) {
    let out = common::xtask_stdin(&[&["eval", "g"], args].concat(), input);
    let text = |b: Vec<u8>| String::from_utf8(b).expect("UTF-8 output");
    (out.status.success(), text(out.stdout), text(out.stderr))
}

#[test]
fn values_match_reference_in_both_conventions() {
    let input = "theta_i_deg,theta_r_deg,sigma\n30,60,0.3\n30,-60,0.3\n75,10,0.8\n10,85,0.05\n";
    for (conv, printed) in [("reciprocal", false), ("printed", true)] {
        let (ok, out, err) = run(&["--convention", conv, "--nodes", "16"], input);
        assert!(ok, "{err}");
        let mut lines = out.lines();
        assert_eq!(
            lines.next().unwrap(),
            "theta_i_deg,theta_r_deg,sigma,GM,GS,G,G_blinn,G_smith_separable,G_smith_correlated"
        );
        for line in lines {
            let f: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(f.len(), 9);
            let d = RefDensity::new(f[2]);
            let (ti, tr) = (f[0].to_radians(), f[1].to_radians());
            let (gm, gs, g) = if printed {
                d.g_printed(ti, tr)
            } else {
                d.g_reciprocal(ti, tr)
            };
            for (got, want) in [(f[3], gm), (f[4], gs), (f[5], g)] {
                assert!((got - want).abs() < 1e-8, "{line}: {got} vs {want}");
            }
            // 17 significant digits: each value round-trips.
            for x in line.split(',').skip(3) {
                assert!(x.contains('e') && x.len() >= 20, "{x}");
            }
        }
    }
}

#[test]
fn malformed_rows_name_their_line() {
    for (input, needle) in [
        (
            "theta_i_deg,theta_r_deg,sigma\n10,20,0.3\n10,abc,0.3\n",
            "line 3",
        ),
        ("10,20\n", "line 1"),
        ("10,20,0.3\n10,20,-1\n", "line 2"),
        ("95,20,0.3\n", "line 1"),
        ("10,20,NaN\n", "line 1"),
    ] {
        let (ok, _, err) = run(&[], input);
        assert!(!ok, "accepted {input:?}");
        assert!(err.contains(needle), "{input:?}: {err}");
    }
    let (ok, _, err) = run(&["--nodes", "7"], "10,20,0.3\n");
    assert!(!ok && err.contains("not compiled in"));
    let (ok, _, err) = run(&["--convention", "weird"], "10,20,0.3\n");
    assert!(!ok && err.contains("convention"));
}

//! The 3-D simulator against known answers (fast, reduced sizes), and the reduced 3-D run.

use brdf_validate::study2d::{Settings2d, Surface2d};
use brdf_validate::surface2d::{Conditioned, Field, Ray};

/// The two triangles of a cell meet the cell's four nodes and each other on the diagonal:
/// the representation is continuous.
#[test]
fn triangle_surface_is_continuous() {
    let f = Field::generate(6, 1);
    let c = Conditioned::plain(&f);
    for (i, j) in [(0i64, 0i64), (5, 7), (63, 63)] {
        for (x, y, z) in [
            (0.0, 0.0, f.h(i, j)),
            (1.0, 0.0, f.h(i + 1, j)),
            (0.0, 1.0, f.h(i, j + 1)),
            (1.0, 1.0, f.h(i + 1, j + 1)),
        ] {
            let got = c.height_in_cell(i, j, i as f64 + x, j as f64 + y);
            assert!(
                (got - z).abs() < 1e-12,
                "node ({x}, {y}) of cell ({i}, {j})"
            );
        }
        // A point on the cell edge x = 1 agrees with the neighbour cell's x = 0 edge.
        let a = c.height_in_cell(i, j, i as f64 + 1.0, j as f64 + 0.3);
        let b = c.height_in_cell(i + 1, j, i as f64 + 1.0, j as f64 + 0.3);
        assert!((a - b).abs() < 1e-12);
    }
}

/// Conditioning makes the chosen triangle's slope exactly the required one and leaves the
/// field unchanged far away (the covariance vanishes beyond 6ℓ).
#[test]
fn conditioning_sets_the_slope_exactly() {
    let f = Field::generate(8, 2);
    for t in 0..2 {
        let s = [1.7, -0.4];
        let c = Conditioned::new(&f, 10, 200, t, s);
        let d = c.slope(10, 200, t);
        assert!(
            (d[0] - s[0]).abs() < 1e-9 && (d[1] - s[1]).abs() < 1e-9,
            "{d:?}"
        );
        let far = c.height_in_cell(100, 100, 100.2, 100.1);
        let plain = Conditioned::plain(&f).height_in_cell(100, 100, 100.2, 100.1);
        assert_eq!(far, plain);
    }
}

/// Against a brute-force reference: a ray is blocked iff some point sampled densely along
/// its path is below the surface (the dense scan can only miss blockers thinner than its
/// step). On the plain field and on fields conditioned on steep slopes (which exercises the
/// conditioning window's bounds and the block skips).
#[test]
fn tracer_agrees_with_dense_scan() {
    let f = Field::generate(8, 3);
    let (mut disagree, mut blocked, mut total) = (0, 0, 0);
    for k in 0..600u64 {
        let (i, j) = ((k * 37 % 256) as i64, (k * 91 % 256) as i64);
        let (x, y) = (i as f64 + 0.7, j as f64 + 0.2); // lower triangle
        let steep = [0.0, 3.0, -6.0][(k % 3) as usize];
        let c = if steep == 0.0 {
            Conditioned::plain(&f)
        } else {
            Conditioned::new(&f, i, j, 0, [steep, 0.5 * steep])
        };
        let s = c.slope(i, j, 0);
        let th = (20.0 + (k % 7) as f64 * 10.0f64).to_radians();
        let psi = k as f64 * 0.37;
        let sigma = 0.5;
        let d = [
            sigma * th.sin() * psi.cos(),
            sigma * th.sin() * psi.sin(),
            th.cos(),
        ];
        if d[2] - s[0] * d[0] - s[1] * d[1] <= 0.0 {
            continue;
        }
        let o = [x, y, c.height_in_cell(i, j, x, y)];
        let vis = c.visible(&Ray { o, d }, (i, j), s);
        let mut scan_blocked = false;
        let mut t = 1e-4;
        while t < 6000.0 && o[2] + t * d[2] < 200.0 {
            let (px, py) = (o[0] + t * d[0], o[1] + t * d[1]);
            let (ci, cj) = (px.floor() as i64, py.floor() as i64);
            if o[2] + t * d[2] < c.height_in_cell(ci, cj, px, py) - 1e-9 {
                scan_blocked = true;
                break;
            }
            t += 0.01;
        }
        total += 1;
        blocked += scan_blocked as u32;
        if vis == scan_blocked {
            disagree += 1;
        }
    }
    assert!(
        blocked > 20 && total - blocked > 20,
        "both outcomes ({blocked} of {total})"
    );
    assert_eq!(disagree, 0);
}

/// Projected-area identity and area-weighted G1 = Smith on a small isotropic surface: the
/// estimates must agree within 4 SE (plus 0.002 for the finite field's realised slope RMS).
#[test]
fn projected_area_identity_and_smith_g1() {
    let fields: Vec<Field> = (0..2).map(|i| Field::generate(8, 10 + i)).collect();
    let surf = Surface2d {
        fields: &fields,
        sigma: (0.5, 0.5),
        random_azimuth: true,
    };
    for th in [40.0f64, 75.0] {
        let (g1, id) = surf.g1_area(th.to_radians(), 0.0, 4000, 4, 5);
        assert!(
            (id.mean - 1.0).abs() < 4.0 * id.se() + 0.002,
            "identity {id:?}"
        );
        let smith = brdf_validate::smith1d::g1(th.to_radians(), 0.5);
        assert!(
            (g1.mean - smith).abs() < 4.0 * g1.se() + 0.002,
            "G1 {g1:?} vs {smith}"
        );
    }
}

/// The reduced 3-D run writes the JSON, the maps and the spliced section; vertical rays are
/// never blocked; the section lands between its markers and the 1-D text stays.
#[test]
fn quick_run_writes_json_figures_and_section() {
    let dir = std::env::temp_dir().join(format!("brdf-validate-2d-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("docs")).unwrap();
    std::fs::write(dir.join("docs/validation.md"), "# 1-D part\n\ntext\n").unwrap();
    let s = Settings2d::quick();
    let out = brdf_validate::report2d::run(&dir, &s).expect("3-D run");
    let md = std::fs::read_to_string(dir.join("docs/validation.md")).unwrap();
    assert!(md.starts_with("# 1-D part\n\ntext\n"));
    assert!(md.contains(&out.section.trim_end().to_string()));
    assert!(!md.contains("NaN"));
    let j: serde_json::Value = serde_json::from_str(&out.json).unwrap();
    let normal = &j["checks"]["normal_incidence"][0];
    assert_eq!(normal["g"], serde_json::json!(1.0));
    assert_eq!(
        j["sweeps"][0]["cells"].as_array().unwrap().len(),
        s.grid().len()
    );
    let svg = std::fs::read_to_string(dir.join("docs/figures/g3_error_theta_i60.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    // Running again replaces the section rather than appending a second one.
    let again = brdf_validate::report2d::run(&dir, &s).unwrap();
    let md2 = std::fs::read_to_string(dir.join("docs/validation.md")).unwrap();
    assert_eq!(md2, md, "deterministic and spliced in place");
    assert_eq!(again.json, out.json);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The full 3-D run into this repository's docs/ — the same library call as
/// `cargo xtask plot --3d`, for machines where building the release xtask is the slow part:
/// `cargo test -p brdf-validate --test surface2d full_run -- --ignored --nocapture`.
#[test]
#[ignore = "full run (minutes); writes docs/"]
fn full_run() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = brdf_validate::report2d::run(&root, &Settings2d::default_run()).expect("full run");
    println!("3-D study: {:.1} s wall time", out.seconds);
}

/// Cost probe: the full grid at σ = 0.1 and 1 with few samples (prints the time).
#[test]
#[ignore = "timing probe"]
fn timing_probe() {
    let mut s = Settings2d::default_run();
    s.run.sigmas = vec![0.1, 1.0];
    s.run.per_batch = 20;
    let fields = brdf_validate::study2d::make_fields(&s);
    let t0 = std::time::Instant::now();
    let pb = indicatif::ProgressBar::hidden();
    for &sg in &s.run.sigmas {
        let t1 = std::time::Instant::now();
        let _ = brdf_validate::study2d::sweep2d(&s, &fields, sg, &pb);
        println!("σ = {sg}: {:.2} s", t1.elapsed().as_secs_f64());
    }
    println!("sweeps {:.2} s", t0.elapsed().as_secs_f64());
}

/// Re-renders §7 from the committed docs/validation-2d.json (template changes only).
#[test]
#[ignore = "writes docs/"]
fn rerender_section() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    brdf_validate::report2d::rerender(&root).expect("re-render");
}

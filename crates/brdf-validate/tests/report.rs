//! The quick report run writes every figure (SVG and PNG) and a markdown file whose tables
//! are filled.

#[test]
fn quick_report_writes_figures_and_tables() {
    let dir = std::env::temp_dir().join(format!("brdf-validate-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut s = brdf_validate::study::Settings::quick();
    s.run.sigmas = vec![0.3];
    s.run.per_batch = 100;
    let out = brdf_validate::report::run(&dir, &s).expect("report runs");
    for name in [
        "fig6_g_theta_i30_sigma0.3",
        "fig7_brdf_theta_i10_sigma0.3",
        "heatmap_g_error",
        "albedo_models",
    ] {
        let svg =
            std::fs::read_to_string(dir.join("docs/figures").join(format!("{name}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("</svg>"),
            "{name}.svg"
        );
        let png = std::fs::read(dir.join("docs/figures").join(format!("{name}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{name}.png");
    }
    let md = std::fs::read_to_string(dir.join("docs/validation.md")).unwrap();
    assert_eq!(md, out.markdown);
    assert!(
        md.contains("| 0.3 |") && !md.contains("NaN"),
        "tables filled"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

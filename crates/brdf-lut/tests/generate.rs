//! `brdf_lut::generate`: tables built to order, checked against independent values (the
//! committed assets; closed forms; the brdf-core kernels, called directly; an inequality
//! between the two Smith forms) and the option errors.

use brdf_lut::generate::{
    default_set, generate, Distribution, GenError, Generated, Kind, Masking, Roughness, Spec,
};
use brdf_lut::Lut;
use brdf_lut::{Encoding, Interpolation, LutView, Placement, Warp};

fn asset(name: &str) -> Lut {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name);
    Lut::from_path(&p).unwrap()
}

fn nodes(bytes: &[u8]) -> Vec<f32> {
    let v = LutView::parse(bytes).unwrap();
    let n: usize = v.header().axes.iter().map(|a| a.count as usize).product();
    (0..n)
        .flat_map(|k| (0..v.channels()).map(move |c| (k, c)))
        .map(|(k, c)| v.node_value(k, c))
        .collect()
}

/// A spec of `kind`, distribution `d`, masking `m` on a small `counts` grid (μ, r).
fn small(kind: Kind, d: Distribution, m: Masking, counts: [u32; 2], samples: u32) -> Spec {
    let mut s = Spec::new(kind, d, m);
    s.axes[0].count = counts[0];
    s.axes[1].count = counts[1];
    s.samples = samples;
    s
}

/// The table `s` describes, without progress reports.
fn build(s: &Spec) -> Generated {
    generate(s, &|_| {}).unwrap()
}

/// `s` on the axes (count, range, warp, placement) of the committed table `lut`.
fn on_grid_of(s: &mut Spec, lut: &Lut) {
    for (a, b) in s.axes.iter_mut().zip(lut.header().axes.iter()) {
        (a.count, a.lo, a.hi, a.warp, a.placement) = (b.count, b.lo, b.hi, b.warp, b.placement);
    }
}

fn invalid(s: &Spec) -> String {
    match generate(s, &|_| {}) {
        Err(GenError::Invalid(m)) => m,
        other => panic!("expected an option error, got {other:?}"),
    }
}

/// The committed GGX split-sum asset's grid, rebuilt through the library: the same node
/// values (u16 codes decode to the same f32) as the xtask generator's, which calls the
/// dedicated `dfg_ggx` kernel rather than the generic split sum used here.
#[test]
fn ggx_split_sum_matches_the_committed_asset() {
    let lut = asset("dfg_ggx.blut");
    let mut s = Spec::new(Kind::SplitSum, Distribution::Ggx, Masking::SmithCorrelated);
    s.samples = 200;
    on_grid_of(&mut s, &lut);
    let t = build(&s);
    let (mine, theirs) = (nodes(&t.bytes), nodes(lut.bytes()));
    assert_eq!(mine.len(), theirs.len());
    for (k, (a, b)) in mine.iter().zip(&theirs).enumerate() {
        // Same u16 code: identical after decoding; allow one code (1/65535 of the range) for
        // last-bit differences between the two quadrature call paths.
        assert!((a - b).abs() <= 1.6e-5, "node {k}: {a} vs {b}");
    }
    // A 64 x 64 cubic table is accurate to well below 1e-3 (the asset records ~1e-4).
    assert!(t.error.max_abs < 1e-3, "{:?}", t.error);
}

/// The default set's cheaper tables (E_avg of both models, the linear per-σ G table), rebuilt
/// from `default_set()`, are byte-identical to the committed files: node values, quadrature
/// record, tool name and the measured error in the header all reproduce. (`cargo xtask lut
/// --check` compares the whole set.)
#[test]
fn default_set_reproduces_committed_bytes() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    let picked: Vec<_> = default_set()
        .into_iter()
        .filter(|a| a.file.starts_with("kc_eavg_") || a.file == "g_modified_sigma0.3_linear.blut")
        .collect();
    assert_eq!(picked.len(), 3);
    for a in picked {
        let fresh = generate(&a.spec, &|_| {}).unwrap().bytes;
        let committed = std::fs::read(dir.join(&a.file)).unwrap();
        assert!(
            fresh == committed,
            "{} differs from the committed file",
            a.file
        );
    }
}

/// Texel-centre nodes through the generator (the converged polar rule at 2e-6) agree with
/// brdf-core's independent adaptive integrator (`converged`, visible-normal cap, at 1e-9)
/// within the tolerance plus the reference's own estimate, at every texel of a 64² grid
/// (its first column, μ = 1/128, is the grazing one where the former fixed rule was off by
/// up to 1.1e-4); and the recorded integration bound is never below what it claims.
#[test]
fn texel_centre_split_sum_agrees_with_the_converged_reference() {
    use brdf_core::split_sum::converged::DfgGgxRow;
    let n = 64u32;
    let mut s = Spec::new(Kind::SplitSum, Distribution::Ggx, Masking::SmithCorrelated);
    for a in s.axes.iter_mut() {
        (a.count, a.lo, a.hi, a.warp) = (n, 0.0, 1.0, Warp::Linear);
        a.placement = Placement::TexelCentre;
    }
    let ev = brdf_lut::generate::evaluate_with_error(&s, &|_| {}).unwrap();
    assert!(ev.integration <= 2e-6, "bound {}", ev.integration);
    let c = |i: u32| (i as f64 + 0.5) / n as f64;
    // Every column at 8 rows (the reference is slow), all rows in the grazing column.
    let picked = (0..n).step_by(9).flat_map(|j| (0..n).map(move |i| (i, j)));
    for (i, j) in picked.chain((0..n).map(|j| (0, j))) {
        let r = DfgGgxRow::new(c(j)).texel(c(i), 1e-9);
        let k = (j * n + i) as usize;
        for ch in 0..2 {
            let d = (ev.values[2 * k + ch] - r.value[ch]).abs();
            assert!(
                d <= 2e-6 + r.error[ch],
                "texel ({i}, {j}) channel {ch}: {d:e}"
            );
        }
    }
}

/// The per-σ G table for σ = 0.3 on the committed asset's grid: same node values.
#[test]
fn g_per_sigma_matches_the_committed_asset() {
    let lut = asset("g_modified_sigma0.3.blut");
    let mut s = Spec::new(
        Kind::GPerSigma { sigma: 0.3 },
        Distribution::TorranceSparrow,
        Masking::Modified,
    );
    s.samples = 500;
    assert_eq!(s.roughness, Roughness::Sigma);
    on_grid_of(&mut s, &lut);
    let t = build(&s);
    for (a, b) in nodes(&t.bytes).iter().zip(&nodes(lut.bytes())) {
        assert!((a - b).abs() <= 1.6e-5, "{a} vs {b}");
    }
}

/// r = 0 is the mirror: A = 1 − (1 − μ)⁵, B = (1 − μ)⁵ (Schlick with F90 = 1), a closed form;
/// f32 storage: 1e-6.
#[test]
fn mirror_column_is_the_closed_form() {
    let mut s = small(
        Kind::SplitSum,
        Distribution::Beckmann,
        Masking::SmithSeparable,
        [5, 3],
        10,
    );
    s.encoding = Encoding::F32;
    let t = build(&s);
    let v = LutView::parse(&t.bytes).unwrap();
    let mu_axis = v.header().axes[0];
    for i in 0..5u32 {
        let mu = mu_axis.node(i);
        let fc = (1.0 - mu).powi(5);
        let k = i as usize; // roughness node 0
        assert!((v.node_value(k, 0) as f64 - (1.0 - fc)).abs() < 1e-6);
        assert!((v.node_value(k, 1) as f64 - fc).abs() < 1e-6);
    }
}

/// Separable Smith masks at least as much as height-correlated Smith
/// (G1(i)G1(o) = 1/((1+Λi)(1+Λo)) ≤ 1/(1+Λi+Λo)), so its albedo is never larger.
#[test]
fn separable_albedo_never_exceeds_correlated() {
    for d in [Distribution::Ggx, Distribution::Beckmann] {
        let mk = |m| {
            let mut s = small(Kind::Albedo, d, m, [6, 6], 10);
            s.encoding = Encoding::F32;
            nodes(&build(&s).bytes)
        };
        let (sep, cor) = (mk(Masking::SmithSeparable), mk(Masking::SmithCorrelated));
        for (a, b) in sep.iter().zip(&cor) {
            assert!(*a <= *b + 1e-6, "{d:?}: {a} > {b}");
            assert!(*b <= 1.0 + 1e-6, "{d:?}: albedo {b} > 1");
        }
    }
}

/// E_avg of GGX against brdf-core's own fixed-rule E_avg kernel at the nodes (an
/// independent rule: 24 μ nodes of the 32 × 16 split sum, good to about 1e-6 away from
/// grazing; f32 storage adds 1e-7).
#[test]
fn e_avg_nodes_match_the_core_kernel() {
    use brdf_core::split_sum::{e_avg_ggx, InnerRule, OuterRule};
    let mut s = Spec::new(
        Kind::AverageAlbedo,
        Distribution::Ggx,
        Masking::SmithCorrelated,
    );
    s.axes[0].count = 5;
    s.axes[0].placement = Placement::TexelCentre;
    s.encoding = Encoding::F32;
    s.samples = 20;
    let t = build(&s);
    let v = LutView::parse(&t.bytes).unwrap();
    let a = v.header().axes[0];
    for i in 0..5 {
        let want = e_avg_ggx::<f64, OuterRule, InnerRule>(a.node(i));
        assert!((v.node_value(i as usize, 0) as f64 - want).abs() < 1e-6);
    }
}

/// A 2 x 2 split-sum table cannot represent the function: the measured error says so
/// (the reader interpolates linearly between four corner values of a curved surface).
#[test]
fn coarse_table_reports_a_large_error() {
    let mut s = small(
        Kind::SplitSum,
        Distribution::Ggx,
        Masking::SmithCorrelated,
        [2, 2],
        500,
    );
    s.interpolation = Interpolation::Linear;
    let t = build(&s);
    assert!(t.error.max_abs > 0.1, "{:?}", t.error);
}

#[test]
fn deterministic_and_progress_counts_every_node() {
    let s = small(
        Kind::SplitSum,
        Distribution::TorranceSparrow,
        Masking::Blinn,
        [4, 3],
        20,
    );
    let n = std::sync::atomic::AtomicU64::new(0);
    let a = generate(&s, &|k| {
        n.fetch_add(k, std::sync::atomic::Ordering::Relaxed);
    })
    .unwrap();
    assert_eq!(n.into_inner(), 12);
    let b = build(&s);
    assert_eq!(a.bytes, b.bytes);
}

#[test]
fn option_errors_name_the_real_problem() {
    let base = Spec::new(Kind::SplitSum, Distribution::Ggx, Masking::SmithCorrelated);
    let mut s = base.clone();
    s.axes[0].count = 1;
    s.axes[1].count = 1;
    assert_eq!(
        invalid(&s),
        "axis mu: 1 node(s); an axis needs at least 2 nodes"
    );
    let mut s = base.clone();
    s.roughness = Roughness::Sigma;
    assert!(invalid(&s).contains("GGX has no RMS slope"));
    let mut s = base.clone();
    s.masking = Masking::Blinn;
    assert!(invalid(&s).contains("Torrance–Sparrow"));
    let mut s = base.clone();
    s.axes[0].lo = 0.0;
    assert!(invalid(&s).contains("a log warp needs lo > 0"));
    let mut s = base.clone();
    s.axes[1].hi = 2.0;
    assert!(invalid(&s).contains("leaves the domain perceptual r"));
    let mut s = base.clone();
    s.axes[0].warp = Warp::Linear;
    s.axes[0].lo = 0.5;
    s.axes[0].hi = 0.5;
    assert!(invalid(&s).contains("is empty"));
    let mut s = base.clone();
    s.axes[0].count = 65_536;
    s.axes[1].count = 65_536;
    assert!(invalid(&s).contains("more than this generator builds"));
    let mut s = Spec::new(
        Kind::GOverSigma,
        Distribution::TorranceSparrow,
        Masking::Modified,
    );
    s.masking = Masking::SmithCorrelated;
    assert!(invalid(&s).contains("choose the modified G"));
    let s = Spec::new(
        Kind::GPerSigma { sigma: 0.0 },
        Distribution::TorranceSparrow,
        Masking::Modified,
    );
    assert!(invalid(&s).contains("must be > 0"));
}

/// Every committed asset's header describes a spec whose direct kernel reproduces the
/// stored node values (at 60 nodes per table, spread over the grid) to within the storage
/// quantisation: half a u16 code of the channel's range (scale/65535/2), plus 1e-6 for
/// last-bit differences between the xtask generator's dedicated kernels and the generic
/// split sum used here. This ties the library's models to the default set's.
#[test]
fn committed_assets_are_reproduced_from_their_headers() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    let mut seen = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_none_or(|x| x != "blut") {
            continue;
        }
        let lut = Lut::from_path(&p).unwrap();
        let v = lut.view().unwrap();
        let h = v.header();
        let spec = Spec::from_header(h).unwrap_or_else(|| panic!("{p:?}: no spec"));
        assert_eq!(spec.axis_names().len(), h.axes.len());
        let n: usize = h.axes.iter().map(|a| a.count as usize).product();
        for j in 0..60usize {
            let k = (j * 7919 + 13) % n;
            let mut r = k;
            let x: Vec<f64> = h
                .axes
                .iter()
                .map(|a| {
                    let i = (r % a.count as usize) as u32;
                    r /= a.count as usize;
                    a.node(i)
                })
                .collect();
            let want = spec.value(&x);
            for (c, w) in want.iter().enumerate() {
                let tol = match h.encoding {
                    Encoding::Unorm16 => h.channels[c].scale as f64 / 65535.0 * 0.5,
                    _ => 0.0,
                } + 1e-6;
                let got = v.node_value(k, c) as f64;
                assert!(
                    (got - w).abs() <= tol,
                    "{p:?} node {k} ch {c}: {got} vs {w}"
                );
            }
        }
        seen += 1;
    }
    assert!(seen >= 10, "only {seen} assets");
}

/// A loader error prints its cause once, also through an error chain (`{:#}` in anyhow walks
/// `source()`).
#[test]
fn loader_error_states_its_cause_once() {
    let e = Lut::from_path("/nonexistent/dir/x.blut").unwrap_err();
    let mut text = e.to_string();
    let mut src = std::error::Error::source(&e);
    while let Some(s) = src {
        text += &format!(": {s}");
        src = s.source();
    }
    assert_eq!(
        text.matches("No such file or directory").count(),
        1,
        "{text}"
    );
}

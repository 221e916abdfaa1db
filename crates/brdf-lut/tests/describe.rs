//! A table described by names and values (`generate::Description`, the reading the TOML
//! file, the command line and the Python package share): errors are typed and name the
//! field, the flags' spelling is `--field`, and a described table holds the direct
//! integral at its nodes (an independent integrator) and is measured with its own model.

use brdf_lut::generate::{check_limits, measure_table, DescribeError, Description, Value};
use brdf_lut::{Encoding, Lut, Model, Placement, Warp};

fn text(s: &str) -> Value {
    Value::Text(s.into())
}

/// A description from (field, value) pairs, set one by one as a front end does.
fn describe(fields: &[(&str, Value)]) -> Result<Description, DescribeError> {
    let mut d = Description::default();
    for (k, v) in fields {
        d.set(k, v.clone())?;
    }
    Ok(d)
}

fn split_sum() -> Vec<(&'static str, Value)> {
    vec![("kind", text("split-sum")), ("model", text("ggx"))]
}

#[test]
fn errors_are_typed_and_name_the_field() {
    let with = |extra: (&'static str, Value)| {
        let mut f = split_sum();
        f.push(extra);
        describe(&f).and_then(|d| d.spec()).unwrap_err()
    };
    let e = with(("res", text("1x8")));
    assert!(matches!(e, DescribeError::Limit { .. }), "{e:?}");
    assert!(
        e.to_string()
            .contains("`res` `1x8`: `1`: nodes per axis is 1; the limit is 2..=65536"),
        "{e}"
    );
    assert!(
        e.with_flags().starts_with("--res `1x8`"),
        "{}",
        e.with_flags()
    );
    let e = with(("res", text("64")));
    assert!(
        matches!(&e, DescribeError::ResCount { given: 1, axes, .. } if axes == &["mu", "roughness"]),
        "{e:?}"
    );
    let e = with(("res", text("64xq")));
    assert!(e.to_string().contains("`q` is not a whole number"), "{e}");
    let e = with(("encoding", text("u8")));
    assert!(e.to_string().contains("unknown encoding `u8`"), "{e}");
    let e = with(("warp", text("cubic")));
    assert!(e.to_string().contains("unknown warp `cubic`"), "{e}");
    let e = with(("max-error", Value::Float(0.0)));
    assert!(
        e.with_flags().contains("--max-error must be a positive"),
        "{e}"
    );
    let e = with(("masking", text("v-cavity")));
    assert!(matches!(e, DescribeError::Invalid(_)) && e.to_string().contains("Torrance"));
    // Field names and types.
    let e = describe(&[("colour", Value::Int(1))]).unwrap_err();
    assert!(e.to_string().contains("unknown field `colour`"), "{e}");
    let e = describe(&[("samples", text("many"))]).unwrap_err();
    assert!(matches!(e, DescribeError::WrongType { .. }), "{e:?}");
    // `max_error` is `max-error`.
    assert_eq!(
        describe(&[("max_error", Value::Float(1e-3))])
            .unwrap()
            .max_error,
        Some(1e-3)
    );
    // Missing and misplaced fields.
    let e = describe(&[]).unwrap().spec().unwrap_err();
    assert!(e.with_flags().starts_with("--kind is missing"), "{e}");
    let e = describe(&[("kind", text("split-sum"))])
        .unwrap()
        .spec()
        .unwrap_err();
    assert!(e.to_string().starts_with("`model` is missing"), "{e}");
    let e = describe(&[("kind", text("g-per-sigma"))])
        .unwrap()
        .spec()
        .unwrap_err();
    assert_eq!(e, DescribeError::SigmaMissing);
    assert!(e.with_flags().contains("needs --sigma"));
    let mut d = describe(&split_sum()).unwrap();
    d.set_axis("sigma", "count", Value::Int(8)).unwrap();
    let e = d.spec().unwrap_err();
    assert!(e.to_string().starts_with("no axis `sigma`"), "{e}");
    // An unknown axis named without fields (`[axes.theta]`, Python's `{"theta": {}}`).
    let mut d = describe(&split_sum()).unwrap();
    d.name_axis("theta");
    let e = d.spec().unwrap_err();
    assert!(e.to_string().starts_with("no axis `theta`"), "{e}");
}

/// A split-sum table described with texel-centre nodes on a linear μ axis: its nodes sit at
/// (i + ½)/8 of the range and hold the integral of brdf-core's independent adaptive
/// integrator (1e-9) within the generator's converged rule's 2e-6 per channel plus f32
/// storage (6e-8 relative) and the reference's own estimate.
#[test]
fn texel_centre_split_sum_matches_the_direct_integral_at_its_nodes() {
    let mut f = split_sum();
    f.extend([
        ("res", text("8x8")),
        ("warp", text("linear")),
        ("placement", text("texel-centre")),
        ("encoding", text("f32")),
        ("samples", Value::Int(50)),
    ]);
    let mut d = describe(&f).unwrap();
    d.set_axis("mu", "lo", Value::Float(0.01)).unwrap();
    d.set_axis("mu", "hi", Value::Int(1)).unwrap();
    let spec = d.spec().unwrap();
    check_limits(&spec).unwrap();
    let t = brdf_lut::generate::generate(&spec, &|_| {}).unwrap();
    let lut = Lut::from_bytes(t.bytes).unwrap();
    let v = lut.view().unwrap();
    let h = v.header();
    assert_eq!(h.encoding, Encoding::F32);
    assert_eq!(
        (h.axes[0].warp, h.axes[0].placement),
        (Warp::Linear, Placement::TexelCentre)
    );
    for i in 0..8u32 {
        let mu = 0.01 + (i as f64 + 0.5) / 8.0 * 0.99;
        let r = (i as f64 + 0.5) / 8.0;
        assert!((h.axes[0].node(i) - mu).abs() < 1e-12);
        let k = (i + 8 * i) as usize;
        let c = brdf_core::split_sum::converged::dfg_ggx_converged(mu, r, 1e-9);
        for ch in 0..2 {
            let d = (v.node_value(k, ch) as f64 - c.value[ch]).abs();
            assert!(d < 2.2e-6 + c.error[ch], "channel {ch} at node {i}: {d:e}");
        }
    }
}

/// A table measured from its header alone (`measure_table`) uses its own model: a Beckmann
/// albedo table with separable Smith on an `m` axis measures at the accuracy its grid gives
/// (≈1e-3 here), where reading it as the default GGX/perceptual-r model would be off by
/// ≫ 1e-2.
#[test]
fn measure_table_uses_the_model_of_a_table_built_to_order() {
    let mut d = describe(&[
        ("kind", text("e")),
        ("model", text("beckmann")),
        ("masking", text("smith-separable")),
        ("roughness", text("alpha")),
        ("res", text("24x16")),
        ("samples", Value::Int(200)),
    ])
    .unwrap();
    d.set_axis("m", "lo", Value::Float(0.1)).unwrap();
    d.set_axis("m", "hi", Value::Float(1.0)).unwrap();
    let t = brdf_lut::generate::generate(&d.spec().unwrap(), &|_| {}).unwrap();
    let lut = Lut::from_bytes(t.bytes).unwrap();
    assert_eq!(lut.header().generator.model, Model::BeckmannSmithSeparable);
    let st = measure_table(&lut.view().unwrap(), 300, 0x5EED_0002).stats;
    assert!(st.max_abs < 5e-3, "{st:?}");
}

//! `brdf_engine_assets::export`: the sidecar's inverse mapping and the emitted shaders read
//! the exported texture at the table's own values (library calls on the committed assets;
//! `cargo xtask lut export` writes these bytes, `xtask/tests/lut_writes.rs` checks that).

use brdf_engine_assets::export::{export, Export, Format};
use std::path::PathBuf;

/// The committed asset `name`.
fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name)
}

/// Exports the committed `name` in `fmt`, its output called `out`.
fn export_asset(name: &str, fmt: Format, out: &str) -> Export {
    let lut = brdf_lut::Lut::from_path(asset(name)).unwrap();
    export(&lut.view().unwrap(), fmt, out, name).unwrap()
}

/// The export's sidecar as JSON.
fn sidecar(e: &Export) -> serde_json::Value {
    serde_json::from_slice(&e.sidecar).unwrap()
}

/// u (or v) of physical x from a sidecar `inverse_mapping` entry, in f64, from its stated
/// formulas (warp name, lo, hi, count, placement) — not from the exporter's f32 constants.
fn coord(m: &serde_json::Value, x: f64) -> f64 {
    let lo = m["lo"].as_f64().unwrap();
    let hi = m["hi"].as_f64().unwrap();
    let n = m["count"].as_f64().unwrap();
    let x = x.clamp(lo, hi);
    let t = match m["warp"].as_str().unwrap() {
        "linear" => (x - lo) / (hi - lo),
        "log" => (x / lo).ln() / (hi / lo).ln(),
        "sqrt" => ((x - lo) / (hi - lo)).sqrt(),
        "cos" => (lo.cos() - x.cos()) / (lo.cos() - hi.cos()),
        "sqrt-cos" => {
            (lo.cos().sqrt() - x.cos().max(0.0).sqrt())
                / (lo.cos().sqrt() - hi.cos().max(0.0).sqrt())
        }
        w => panic!("unknown warp {w}"),
    }
    .clamp(0.0, 1.0);
    match m["placement"].as_str().unwrap() {
        "endpoint" => (t * (n - 1.0) + 0.5) / n,
        "texel-centre" => t,
        p => panic!("unknown placement {p}"),
    }
}

/// GL bilinear filtering with clamp-to-edge of a w × h single-channel texture at (u, v),
/// row 0 at v = 0 (texel centres at (i + ½)/w).
fn bilinear(tex: &[f32], w: usize, h: usize, u: f64, v: f64) -> f64 {
    let ax = |c: f64, n: usize| {
        let p = (c * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let i = (p.floor() as usize).min(n.saturating_sub(2));
        (i, p - i as f64)
    };
    let (i, fx) = ax(u, w);
    let (j, fy) = ax(v, h);
    let at = |a: usize, b: usize| tex[b * w + a] as f64;
    let r0 = at(i, j) * (1.0 - fx) + at(i + 1, j) * fx;
    let r1 = at(i, j + 1) * (1.0 - fx) + at(i + 1, j + 1) * fx;
    r0 * (1.0 - fy) + r1 * fy
}

/// Sampling the exported f32 texture bilinearly at the sidecar's uv reproduces brdf-lut's
/// own linear interpolation of the table at random points.
#[test]
fn sidecar_mapping_reproduces_the_tables_lookup() {
    let name = "g_modified_sigma0.3_linear.blut";
    let lut = brdf_lut::Lut::from_path(asset(name)).unwrap();
    let view = lut.view().unwrap();
    assert_eq!(view.dims(), 2);
    assert_eq!(view.header().interpolation, brdf_lut::Interpolation::Linear);
    let e = export_asset(name, Format::RawF32, "g.f32.bin");
    let side = sidecar(&e);
    let m = side["inverse_mapping"].as_array().unwrap();
    let (w, h) = (
        m[0]["count"].as_u64().unwrap() as usize,
        m[1]["count"].as_u64().unwrap() as usize,
    );
    let tex: Vec<f32> = e
        .texture
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    assert_eq!(tex.len(), w * h);
    let (lo0, hi0) = (m[0]["lo"].as_f64().unwrap(), m[0]["hi"].as_f64().unwrap());
    let (lo1, hi1) = (m[1]["lo"].as_f64().unwrap(), m[1]["hi"].as_f64().unwrap());
    // Deterministic LCG points, a margin beyond both ends to exercise the clamps.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut worst = 0.0f64;
    for _ in 0..20_000 {
        let x = lo0 - 0.02 + rnd() * (hi0 - lo0 + 0.04);
        let y = lo1 - 0.02 + rnd() * (hi1 - lo1 + 0.04);
        let got = bilinear(&tex, w, h, coord(&m[0], x), coord(&m[1], y));
        let want = view.sample2(x as f32, y as f32)[0] as f64;
        worst = worst.max((got - want).abs());
    }
    // Same node values (f32 export of the decoded nodes), same linear weights: the only
    // difference is brdf-lut's f32 coordinate arithmetic vs this f64 one, a few f32 ulps
    // (~1e-7 relative) in t, times at most N = 56 texels of node steps < 1 each of F: ~1e-5
    // (measured 2.6e-7). A half-texel placement error shifts values by about half a node step
    // (> 1e-2 on this table), far above this bound.
    assert!(worst < 1e-5, "max |bilinear(uv) - lookup| = {worst:e}");
}

/// The emitted WGSL validates with naga and the GLSL has the documented signature; a 3-D
/// table gets no shader and says so.
#[test]
fn shaders_validate_and_non_2d_says_so() {
    for (asset, fmt, out, ret) in [
        ("dfg_ts_smith.blut", Format::Png16, "dfg.png", "vec2"),
        (
            "g_modified_sigma0.3_linear.blut",
            Format::RawF16,
            "g.f16.bin",
            "float",
        ),
        ("dfg_ggx.blut", Format::RawF32, "ggx.f32.bin", "vec2"),
    ] {
        let e = export_asset(asset, fmt, out);
        let side = sidecar(&e);
        let (glsl, wgsl) = e.shaders.expect("a 2-D table gets shaders");
        let name = side["shaders"]["function"].as_str().unwrap().to_string();
        let module = naga::front::wgsl::parse_str(&wgsl)
            .unwrap_or_else(|e| panic!("{asset}: {}", e.emit_to_string(&wgsl)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{asset}: {e:?}"));
        assert!(module
            .functions
            .iter()
            .any(|(_, f)| f.name.as_deref() == Some(name.as_str())));
        assert!(glsl.contains(&format!("{ret} {name}(sampler2D lut, float p0, float p1)")));
        assert!(side["values"].as_str().unwrap().starts_with("linear"));
    }
    let ggx = sidecar(&export_asset("dfg_ggx.blut", Format::RawF32, "x.bin"));
    assert!(ggx["roughness"].as_str().unwrap().contains("alpha = r^2"));
    let e = export_asset("g_modified.blut", Format::RawF32, "g3.bin");
    let side = sidecar(&e);
    assert!(side["shaders"]["function"].is_null());
    assert!(side["shaders"]["note"].as_str().unwrap().contains("2-D"));
    assert!(e.shaders.is_none());
    assert!(side["roughness"].as_str().unwrap().starts_with("sigma"));
}

/// A 16-bit PNG export of a 2-channel table also writes one 16-bit greyscale PNG per channel, whose
/// decoded values are the table's node values within the 16-bit quantisation.
#[test]
fn png16_writes_single_channel_pngs() {
    let name = "dfg_ts_smith.blut";
    let lut = brdf_lut::Lut::from_path(asset(name)).unwrap();
    let view = lut.view().unwrap();
    let e = export_asset(name, Format::Png16, "dfg.png");
    let side = sidecar(&e);
    let dec = side["channel_decode"].as_array().unwrap();
    for (c, ch) in ["A", "B"].iter().enumerate() {
        let file = format!("dfg_{ch}.png");
        let (_, bytes) = e
            .single_channel_pngs
            .iter()
            .find(|(n, _)| *n == file)
            .unwrap();
        let mut r = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let mut buf = vec![0; r.output_buffer_size()];
        let info = r.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Grayscale);
        assert_eq!(info.bit_depth, png::BitDepth::Sixteen);
        let (off, sc) = (
            dec[c]["offset"].as_f64().unwrap(),
            dec[c]["scale"].as_f64().unwrap(),
        );
        for (k, b) in buf[..info.buffer_size()].chunks_exact(2).enumerate() {
            let q = u16::from_be_bytes([b[0], b[1]]) as f64 / 65535.0;
            let want = view.node_value(k, c) as f64;
            // Re-quantising to 16 bits: half a step of the channel's range.
            assert!((off + sc * q - want).abs() <= 0.5 / 65535.0 * sc + 1e-7);
        }
        assert!(side["single_channel_pngs"]
            .as_array()
            .unwrap()
            .iter()
            .any(|n| n.as_str() == Some(&format!("dfg_{ch}.png"))));
    }
}

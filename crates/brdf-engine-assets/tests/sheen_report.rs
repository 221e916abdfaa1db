//! `report::sheen::compare_sheen` on synthetic "shipped" files whose values are known: made
//! from the independent reference integral (`sheen_e_reference`, half-vector coordinates,
//! another rule than the generator the comparison uses), quantised as the viewer's files are,
//! one of them sRGB-encoded by the forward transform written here. The comparison must find
//! only the quantisation, the planted offset at its (μ, r), and the sRGB encoding's size.

use brdf_engine_assets::report::sheen::{compare_sheen, MU_MIN};
use brdf_lut::generate::sheen_e_reference;

const N: usize = 32;
const STEP: usize = 4;

fn centre(i: usize) -> f64 {
    (i as f64 + 0.5) / N as f64
}

/// The sRGB encode (IEC 61966-2-1): 12.92 c below 0.0031308, else 1.055 c^(1/2.4) − 0.055.
fn srgb_encode(c: f64) -> f64 {
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

fn png(bits16: bool, rgb: &[f64]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, N as u32, N as u32);
    e.set_color(png::ColorType::Rgb);
    let data: Vec<u8> = if bits16 {
        e.set_depth(png::BitDepth::Sixteen);
        rgb.iter()
            .flat_map(|&v| ((v.clamp(0.0, 1.0) * 65535.0).round() as u16).to_be_bytes())
            .collect()
    } else {
        e.set_depth(png::BitDepth::Eight);
        rgb.iter()
            .map(|&v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
            .collect()
    };
    let mut w = e.write_header().unwrap();
    w.write_image_data(&data).unwrap();
    drop(w);
    out
}

#[test]
fn finds_quantisation_the_planted_offset_and_the_srgb_encoding() {
    // [EK, Ashikhmin] at the sampled texels, to 1e-8.
    let mut refs = vec![[0.0; 2]; N * N];
    for j in (0..N).step_by(STEP) {
        for i in (0..N).step_by(STEP) {
            refs[j * N + i] = sheen_e_reference(centre(i), centre(j), 1e-8).0;
        }
    }
    let (pi, pj) = (5 * STEP, 2 * STEP);
    let charlie: Vec<f64> = (0..N * N)
        .flat_map(|k| {
            let planted = if k == pj * N + pi { 0.25 } else { 0.0 };
            [0.9, 0.1, refs[k][1] + planted]
        })
        .collect();
    let sheen: Vec<f64> = (0..N * N)
        .flat_map(|k| [srgb_encode(refs[k][0]); 3])
        .collect();
    let c = compare_sheen(&png(false, &charlie), &png(true, &sheen), STEP).unwrap();
    assert_eq!((c.n, c.step, c.sampled), (N, STEP, 64));
    let counted = (0..N)
        .step_by(STEP)
        .flat_map(|j| (0..N).step_by(STEP).map(move |i| (i, j)))
        .filter(|&(i, j)| centre(i) >= MU_MIN && refs[j * N + i][1] <= 1.0)
        .count();
    assert_eq!(c.diffs[0].texels.len(), counted);
    // B: the planted +0.25 (within half an 8-bit step and the tolerances) at its texel.
    let q8 = 0.5 / 255.0 + 2e-5;
    assert!((c.diffs[0].max - 0.25).abs() <= q8, "{}", c.diffs[0].max);
    assert_eq!(c.diffs[0].at, (centre(pi), centre(pj)));
    for &(mu, r, d) in &c.diffs[0].texels {
        if (mu, r) != (centre(pi), centre(pj)) {
            assert!(d.abs() <= q8, "B at ({mu}, {r}): {d}");
        }
    }
    // R after the decode: the 16-bit step through the decode's slope (≤ 2.4/1.055 on [0, 1]).
    let q16 = 0.5 / 65535.0 * 2.4 / 1.055 + 2e-5;
    assert!(c.diffs[2].max <= q16, "decoded R: {}", c.diffs[2].max);
    // R as stored: the encoding itself, srgb(E) − E, at every counted texel.
    for &(mu, r, d) in &c.diffs[1].texels {
        let i = (mu * N as f64 - 0.5).round() as usize;
        let j = (r * N as f64 - 0.5).round() as usize;
        let e = refs[j * N + i][0];
        assert!(
            (d - (srgb_encode(e) - e)).abs() <= 0.5 / 65535.0 + 2e-5,
            "({mu}, {r})"
        );
    }
    assert!(
        c.diffs[1].median > 0.05,
        "the encoding is large: {}",
        c.diffs[1].median
    );
}

#[test]
fn refuses_files_of_two_edges_and_non_png() {
    let a = png(false, &vec![0.5; N * N * 3]);
    assert!(compare_sheen(&a, b"not a png", 4).is_err());
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, 2, 2);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    e.write_header()
        .unwrap()
        .write_image_data(&[0; 12])
        .unwrap();
    assert!(compare_sheen(&a, &out, 4).is_err());
}

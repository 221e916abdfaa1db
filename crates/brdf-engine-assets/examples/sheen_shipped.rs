//! The glTF Sample Viewer's shipped sheen textures against the converged sheen albedo
//! (`brdf_lut::generate::sheen_e`): `lut_charlie.png` channel B (the viewer's sheen "DG":
//! ∫ D V μl dωl with Charlie D, α = r², and Ashikhmin's V) and `lut_sheen_E.png` channel R
//! (the viewer's albedo scaling: the same integral with the Estevez–Kulla V), on the
//! Khronos axes (column μ = (i + ½)/N, PNG row j from the top: r = (j + ½)/N), at every
//! `stride`-th texel of each axis. Prints max and median |shipped − converged| over the
//! texels with μ ≥ cos 89° whose converged value a unit texture can hold (≤ 1), where the
//! max is, for the file as stored and, for lut_sheen_E, after the sRGB → linear decode
//! its values look encoded with. A measurement for docs/engines.md, not a test (the
//! anchors are not in the repository).
//!
//! ```text
//! cargo run --release -p brdf-engine-assets --example sheen_shipped -- DIR [stride]
//! ```

use brdf_lut::generate::sheen_e;

/// (edge, channel values in [0, 1], row-major from the top) of an 8/16-bit RGB(A) PNG.
fn read(path: &str, channel: usize) -> (usize, Vec<f64>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    dec.set_transformations(png::Transformations::IDENTITY);
    let mut rd = dec.read_info().expect("png");
    let info = rd.info();
    let (w, chan) = (info.width as usize, info.color_type.samples());
    let sixteen = info.bit_depth == png::BitDepth::Sixteen;
    let mut buf = vec![0; rd.output_buffer_size()];
    rd.next_frame(&mut buf).expect("png frame");
    let v = (0..w * w)
        .map(|i| {
            let o = i * chan + channel;
            if sixteen {
                u16::from_be_bytes([buf[2 * o], buf[2 * o + 1]]) as f64 / 65535.0
            } else {
                buf[o] as f64 / 255.0
            }
        })
        .collect();
    (w, v)
}

/// The sRGB decode (IEC 61966-2-1).
fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn stats(name: &str, n: usize, stride: usize, v: &[f64], want: &[Vec<f64>]) {
    let mut d: Vec<(f64, usize, usize)> = vec![];
    for (jj, j) in (0..n).step_by(stride).enumerate() {
        for (ii, i) in (0..n).step_by(stride).enumerate() {
            // Only where the file can hold the value (converged ≤ 1) and μ ≥ cos 89°.
            if want[jj][ii] <= 1.0 && (i as f64 + 0.5) / n as f64 >= 0.017_452_4 {
                d.push(((v[j * n + i] - want[jj][ii]).abs(), i, j));
            }
        }
    }
    d.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (m, i, j) = d[d.len() - 1];
    println!(
        "{name}: {} texels, max |shipped − converged| {m:.4} at mu {:.4}, r {:.4}; median {:.5}",
        d.len(),
        (i as f64 + 0.5) / n as f64,
        (j as f64 + 0.5) / n as f64,
        d[d.len() / 2].0
    );
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let dir = a.get(1).cloned().unwrap_or_else(|| ".".into());
    let stride: usize = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(32);
    let (n, charlie) = read(&format!("{dir}/lut_charlie.png"), 2);
    let (n2, sheen) = read(&format!("{dir}/lut_sheen_E.png"), 0);
    assert_eq!(n, n2);
    // Converged [EK, Ashikhmin] at each sampled texel, to 1e-5 (far below both encodings'
    // steps compared here).
    let conv: Vec<Vec<[f64; 2]>> = (0..n)
        .step_by(stride)
        .map(|j| {
            (0..n)
                .step_by(stride)
                .map(|i| {
                    sheen_e(
                        (i as f64 + 0.5) / n as f64,
                        (j as f64 + 0.5) / n as f64,
                        1e-5,
                    )
                    .value
                })
                .collect()
        })
        .collect();
    let pick = |c: usize| -> Vec<Vec<f64>> {
        conv.iter()
            .map(|row| row.iter().map(|v| v[c]).collect())
            .collect()
    };
    stats(
        "lut_charlie.png B vs Ashikhmin E",
        n,
        stride,
        &charlie,
        &pick(1),
    );
    let above: usize = conv.iter().flatten().filter(|v| v[1] > 1.0).count();
    let above_ek: usize = conv.iter().flatten().filter(|v| v[0] > 1.0).count();
    println!(
        "sampled texels with converged E > 1 (not representable): Ashikhmin {above}, EK {above_ek} of {}",
        conv.iter().flatten().count()
    );
    stats(
        "lut_sheen_E.png R (as stored) vs Estevez-Kulla E",
        n,
        stride,
        &sheen,
        &pick(0),
    );
    let lin: Vec<f64> = sheen.iter().map(|&c| srgb_to_linear(c)).collect();
    stats(
        "lut_sheen_E.png R (sRGB-decoded) vs Estevez-Kulla E",
        n,
        stride,
        &lin,
        &pick(0),
    );
}

//! The rough-glass engine files (`brdf_engine_assets::glass`): the 3-D KTX2 read back by an
//! independent reader (the `ktx2` crate, zstd) holds, at each texel centre, the direct f64
//! integral rounded to binary16 (so within half a unit in the last place of it), the BLUT
//! file holds the same bits, and the sidecar names what they are.

mod common;

use brdf_lut::generate::glass::glass_e;
use brdf_lut::generate::INTEGRATION_TOL;

/// The file named `name` among `files`.
fn file<'a>(files: &'a [brdf_engine_assets::File], name: &str) -> &'a brdf_engine_assets::File {
    files
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("{name} missing"))
}

#[test]
fn glass_ktx2_decodes_to_the_integrals_within_half_rounding() {
    let n = [3usize, 3, 2];
    for inside in [false, true] {
        let files = brdf_engine_assets::glass(&n, inside, &|_| {}).unwrap();
        let stem = if inside { "glass_e_inv" } else { "glass_e" };
        let get = |ext: &str| file(&files, &format!("{stem}.{ext}"));
        let rd = ktx2::Reader::new(&get("ktx2").bytes[..]).unwrap();
        let h = rd.header();
        assert_eq!(h.format, Some(ktx2::Format::R16G16_SFLOAT));
        assert_eq!(
            [h.pixel_width, h.pixel_height, h.pixel_depth],
            [3, 3, 2],
            "3-D dimensions"
        );
        assert_eq!(
            h.supercompression_scheme,
            Some(ktx2::SupercompressionScheme::Zstandard)
        );
        let level = rd.levels().next().unwrap();
        let raw = zstd::bulk::decompress(level.data, 3 * 3 * 2 * 4).unwrap();
        assert_eq!(raw.len(), 72);
        let (elo, ehi) = if inside { (1.0 / 3.0, 1.0) } else { (1.0, 3.0) };
        let centre =
            |i: usize, k: usize, lo: f64, hi: f64| lo + (i as f64 + 0.5) / k as f64 * (hi - lo);
        for z in 0..2 {
            for y in 0..3 {
                for x in 0..3 {
                    let (mu, r) = (centre(x, 3, 0.0, 1.0), centre(y, 3, 0.0, 1.0));
                    let eta = centre(z, 2, elo, ehi);
                    let (v, _) = glass_e(mu, r * r, eta, INTEGRATION_TOL);
                    let o = 4 * (x + 3 * (y + 3 * z));
                    for c in 0..2 {
                        let bits = u16::from_le_bytes([raw[o + 2 * c], raw[o + 2 * c + 1]]);
                        let got = half::f16::from_bits(bits).to_f64();
                        // Half a binary16 ulp of v (v in (0, 1]: exponent ≤ 0, 10-bit mantissa).
                        let e = v[c].abs().max(6.1e-5).log2().floor();
                        let half_ulp = 2f64.powf(e - 10.0) * 0.5;
                        assert!(
                            (got - v[c]).abs() <= half_ulp,
                            "({mu}, {r}, {eta}) channel {c}: texel {got} vs integral {}",
                            v[c]
                        );
                    }
                }
            }
        }
        let blut = brdf_lut::LutView::parse(&get("blut").bytes[..]).unwrap();
        assert_eq!(
            blut.payload(),
            &raw[..],
            "the BLUT payload is the KTX2 level data"
        );
        let side: serde_json::Value = serde_json::from_slice(&get("json").bytes).unwrap();
        for key in common::SIDECAR_KEYS {
            assert!(side.get(key).is_some(), "sidecar key {key}");
        }
    }
}

/// A size outside 2..=256 on any axis is a typed error, not a panic.
#[test]
fn glass_sizes_are_checked() {
    assert!(brdf_engine_assets::glass(&[1, 4, 4], false, &|_| {}).is_err());
    assert!(brdf_engine_assets::glass(&[4, 4, 1000], true, &|_| {}).is_err());
}

/// The 2-D average files (`glass(&[N0, N1], …)`): the KTX2 read back by the `ktx2` crate
/// holds, at each texel centre (r, η), `lut verify`'s reference for E_avg (the radial rule's
/// E in the μ rule, `glass_e_avg_radial`, a different integrator from the generator's) within
/// half a binary16 ulp plus the two rules' tolerances (2e-6 + 2e-7); the BLUT holds the
/// same bits; the sidecar has the shared keys.
#[test]
fn glass_average_ktx2_holds_the_reference_averages() {
    use brdf_lut::generate::glass::{glass_e_avg_radial, AVERAGE_REFERENCE_TOL};
    for inside in [false, true] {
        let files = brdf_engine_assets::glass(&[2, 2], inside, &|_| {}).unwrap();
        let stem = if inside {
            "glass_e_avg_inv"
        } else {
            "glass_e_avg"
        };
        let get = |ext: &str| file(&files, &format!("{stem}.{ext}"));
        let rd = ktx2::Reader::new(&get("ktx2").bytes[..]).unwrap();
        let h = rd.header();
        assert_eq!(h.format, Some(ktx2::Format::R16G16_SFLOAT));
        assert_eq!([h.pixel_width, h.pixel_height, h.pixel_depth], [2, 2, 0]);
        let raw = zstd::bulk::decompress(rd.levels().next().unwrap().data, 16).unwrap();
        let (elo, ehi) = if inside { (1.0 / 3.0, 1.0) } else { (1.0, 3.0) };
        for y in 0..2 {
            for x in 0..2 {
                let r = (x as f64 + 0.5) / 2.0;
                let eta = elo + (y as f64 + 0.5) / 2.0 * (ehi - elo);
                let (v, _) = glass_e_avg_radial(r * r, eta, AVERAGE_REFERENCE_TOL);
                let o = 4 * (x + 2 * y);
                for c in 0..2 {
                    let bits = u16::from_le_bytes([raw[o + 2 * c], raw[o + 2 * c + 1]]);
                    let got = half::f16::from_bits(bits).to_f64();
                    let e = v[c].abs().max(6.1e-5).log2().floor();
                    let allowed =
                        2f64.powf(e - 10.0) * 0.5 + INTEGRATION_TOL + AVERAGE_REFERENCE_TOL;
                    assert!(
                        (got - v[c]).abs() <= allowed,
                        "(r {r}, η {eta}) channel {c}: texel {got} vs reference {}",
                        v[c]
                    );
                }
            }
        }
        let blut = brdf_lut::LutView::parse(&get("blut").bytes[..]).unwrap();
        assert_eq!(blut.payload(), &raw[..]);
        let side: serde_json::Value = serde_json::from_slice(&get("json").bytes).unwrap();
        for key in common::SIDECAR_KEYS {
            assert!(side.get(key).is_some(), "sidecar key {key}");
        }
    }
    assert!(brdf_engine_assets::glass(&[4], false, &|_| {}).is_err());
    assert!(brdf_engine_assets::glass(&[4, 4, 4, 4], false, &|_| {}).is_err());
}

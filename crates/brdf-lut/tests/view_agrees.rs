//! The typed tables and the zero-copy view read a table through the same lookup, so their
//! values agree bit for bit (issue 26 row 6: `AlbedoTable::e` and `LutView::sample2`
//! differed by 1 ulp at 583 of 40,401 grid points of `kc_e_ggx.blut` while the albedo
//! tables read their log μ axis with an inline logarithm of their own).
//!
//! Every point of a dense grid over each axis' range (and a margin outside it, where the
//! coordinates are clamped) of every shipped asset of the kind: the view's value is the
//! reference, the typed lookup must give the same bits (G tables: each one-sided factor
//! clamped to [0, 1], G their minimum, paper eq 13). One documented exception: `GTable3`
//! on a linear u16 table (the speed tier, `g_modified_linear.blut`) reads its log-warped σ
//! axis with an inline logarithm on hosted targets (its instruction budget), within
//! 1.5e-7 + 2.5e-7·|ln σ| of ln σ; with a = 27/ln 20 ≈ 9 cells per unit of ln σ that moves
//! σ's node fraction by < 1e-4 (the lookup module's own test), and since G and its factors
//! lie in [0, 1] the values by at most 1e-4 (plus f32 rounding). There the bound is checked
//! and the number of differing points printed.

use brdf_lut::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, LutView};

fn asset(name: &str) -> Vec<u8> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name);
    std::fs::read(p).unwrap()
}

/// `n + 1` points over the range of axis `k` of `v`, widened by 5 % of the span on both
/// sides.
fn grid(v: &LutView<'_>, k: usize, n: usize) -> Vec<f32> {
    let a = &v.header().axes[k];
    let (lo, hi) = (a.lo, a.hi);
    let m = 0.05 * (hi - lo);
    (0..=n)
        .map(|i| (lo - m + (hi - lo + 2.0 * m) * i as f64 / n as f64) as f32)
        .collect()
}

/// Runs `check(name, bytes, view)` on each named committed table.
fn each_table(names: &[&str], mut check: impl FnMut(&str, &[u8], &LutView<'_>)) {
    for &name in names {
        let b = asset(name);
        let v = LutView::parse(&b).unwrap();
        check(name, &b, &v);
    }
}

fn bits(x: f32) -> u32 {
    x.to_bits()
}

fn unit01(x: f32) -> f32 {
    x.clamp(0.0, 1.0)
}

#[test]
fn albedo_e_equals_the_view_bit_for_bit() {
    each_table(&["kc_e_ggx.blut", "kc_e_beckmann.blut"], |name, b, v| {
        let t = AlbedoTable::parse(b).unwrap();
        let (mus, rs) = (grid(v, 0, 400), grid(v, 1, 400));
        let mut pts: Vec<(f32, f32)> = Vec::new();
        for &r in &rs {
            for &mu in &mus {
                pts.push((mu, r));
            }
        }
        // The reported point (roughness below the range: clamped).
        pts.push((0.729_902_4, -0.300_918_28));
        let mut differ = 0;
        for &(mu, r) in &pts {
            if bits(t.e(mu, r)) != bits(v.sample2(mu, r)[0]) {
                differ += 1;
            }
        }
        assert_eq!(differ, 0, "{name}: {differ} of {} points differ", pts.len());
        // The batch entry point too (bit-identical to `e`, so to the view).
        let (mu, r): (Vec<f32>, Vec<f32>) = pts.iter().copied().unzip();
        let mut out = vec![0.0; pts.len()];
        t.e_batch(&mu, &r, &mut out);
        for (k, &(mu, r)) in pts.iter().enumerate() {
            assert_eq!(
                bits(out[k]),
                bits(v.sample2(mu, r)[0]),
                "{name} ({mu}, {r})"
            );
        }
    });
}

#[test]
fn average_albedo_and_dfg_equal_the_view_bit_for_bit() {
    each_table(
        &["kc_eavg_ggx.blut", "kc_eavg_beckmann.blut"],
        |name, b, v| {
            let t = AverageAlbedoTable::parse(b).unwrap();
            for r in grid(v, 0, 20_000) {
                assert_eq!(bits(t.e_avg(r)), bits(v.sample1(r)[0]), "{name} {r}");
            }
        },
    );
    each_table(
        &[
            "dfg_ggx.blut",
            "dfg_ggx_linear.blut",
            "dfg_ts_modified.blut",
            "dfg_ts_smith.blut",
        ],
        |name, b, v| {
            let t = DfgTable::parse(b).unwrap();
            let (mus, rs) = (grid(v, 0, 300), grid(v, 1, 300));
            for &r in &rs {
                for &mu in &mus {
                    let (a, bb) = t.ab(mu, r);
                    let s = v.sample2(mu, r);
                    assert_eq!(
                        (bits(a), bits(bb)),
                        (bits(s[0]), bits(s[1])),
                        "{name} ({mu}, {r})"
                    );
                }
            }
        },
    );
}

/// (GM, GS, G) from the view: the passing-factor table F(θ, φ) read at
/// GM = F(|θr|, sgn θr · θi) and GS = F(θi, θr) (docs/conventions.md §4), each clamped to
/// [0, 1].
fn g_from_view(v: &LutView<'_>, ti: f32, tr: f32, sigma: Option<f32>) -> (f32, f32, f32) {
    let s = if tr < 0.0 { -ti } else { ti };
    let at = |x: f32, y: f32| match sigma {
        Some(z) => v.sample3(x, y, z)[0],
        None => v.sample2(x, y)[0],
    };
    let (gm, gs) = (unit01(at(tr.abs(), s)), unit01(at(ti, tr)));
    (gm, gs, if gs < gm { gs } else { gm })
}

fn angles(n: usize) -> (Vec<f32>, Vec<f32>) {
    let h = std::f64::consts::FRAC_PI_2;
    let ti = (0..=n).map(|i| (h * i as f64 / n as f64) as f32).collect();
    let tr = (0..=2 * n)
        .map(|i| (-h + h * i as f64 / n as f64) as f32)
        .collect();
    (ti, tr)
}

#[test]
fn g_tables_equal_the_view_bit_for_bit() {
    let (tis, trs) = angles(120);
    each_table(
        &[
            "g_modified_sigma0.1.blut",
            "g_modified_sigma0.3.blut",
            "g_modified_sigma0.3_linear.blut",
            "g_modified_sigma0.5.blut",
        ],
        |name, b, v| {
            let t = GTable::parse(b).unwrap();
            for &ti in &tis {
                for &tr in &trs {
                    let (gm, gs, g) = t.terms(ti, tr);
                    let w = g_from_view(v, ti, tr, None);
                    assert_eq!(
                        (bits(gm), bits(gs), bits(g)),
                        (bits(w.0), bits(w.1), bits(w.2)),
                        "{name} ({ti}, {tr})"
                    );
                }
            }
        },
    );
    let (tis, trs) = angles(40);
    each_table(
        &["g_modified.blut", "g_modified_linear.blut"],
        |name, b, v| {
            let exact = name == "g_modified.blut";
            let t = GTable3::parse(b).unwrap();
            let (mut differ, mut worst, mut total) = (0usize, 0f32, 0usize);
            for sigma in grid(v, 2, 60) {
                for &ti in &tis {
                    for &tr in &trs {
                        let (gm, gs, g) = t.terms(ti, tr, sigma);
                        let w = g_from_view(v, ti, tr, Some(sigma));
                        total += 1;
                        if exact {
                            assert_eq!(
                                (bits(gm), bits(gs), bits(g)),
                                (bits(w.0), bits(w.1), bits(w.2)),
                                "{name} ({ti}, {tr}, {sigma})"
                            );
                        } else if (bits(gm), bits(gs), bits(g)) != (bits(w.0), bits(w.1), bits(w.2))
                        {
                            differ += 1;
                            for (a, b) in [(gm, w.0), (gs, w.1), (g, w.2)] {
                                worst = worst.max((a - b).abs());
                            }
                        }
                    }
                }
            }
            println!("{name}: {differ} of {total} points differ, by at most {worst:e}");
            assert!(worst <= 1e-4, "{name}: {worst}");
        },
    );
}

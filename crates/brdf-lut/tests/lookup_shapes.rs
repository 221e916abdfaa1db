//! Every shape the lookup engine accepts (axes × channels 1×1, 2×1, 2×2, 3×1, 3×2: the
//! kinds' shapes), linear and Catmull–Rom (a 3-node axis too: the per-tap path), u16 / f16
//! / f32 payloads, every warp and both placements, on small tables built here whose node
//! values are polynomials in the node indices, different per channel and not symmetric in
//! the axes (so a swapped axis, stride or channel shows):
//! (a) each typed batch entry point equals its scalar lookup bit for bit, over queries with
//!     tails shorter than a chunk, NaN, ±∞, out-of-range values, range ends and nodes;
//! (b) the scalar lookup at a node gives the value written there, and a linear table at a
//!     cell's centre gives the mean of the cell's 2^D corners (the multilinear closed form).

use brdf_lut::write::{self, Spec};
use brdf_lut::*;
use brdf_lut::{AverageAlbedoTable as Avg, DfgTable as Dfg};
use brdf_lut::{GlassAlbedoTable as Glass, GlassAverageTable as GAvg};

/// Channel c at node (i, j, k): quadratic, with cross terms, differing per channel.
fn poly(c: usize, [i, j, k]: [f64; 3]) -> f64 {
    match c {
        0 => 1.0 + i + 0.5 * i * i + 3.0 * j - 0.25 * i * j + 7.0 * k + 0.5 * j * k,
        _ => 20.0 - 2.0 * i + 0.75 * j * j + 1.5 * k - 0.3 * i * k + 0.1 * i * j * k,
    }
}

fn ax(count: u32, lo: f64, hi: f64, warp: Warp, placement: Placement) -> Axis<'static> {
    let mut a = Axis::default();
    (a.name, a.count, a.lo, a.hi, a.warp, a.placement) = ("x", count, lo, hi, warp, placement);
    a
}

/// The physical coordinate at fractional node index t (f64; the warps and placements of
/// docs/lut-format.md §6, inverted by hand).
fn phys(a: &Axis<'_>, t: f64) -> f64 {
    let n = a.count as f64;
    let s = match a.placement {
        Placement::Endpoint => t / (n - 1.0),
        Placement::TexelCentre => (t + 0.5) / n,
    };
    let (lo, hi) = (a.lo, a.hi);
    match a.warp {
        Warp::Linear => lo + s * (hi - lo),
        Warp::Sqrt => lo + s * s * (hi - lo),
        Warp::Log => lo * (hi / lo).powf(s),
        Warp::Cos => (lo.cos() - s * (lo.cos() - hi.cos())).acos(),
        Warp::SqrtCos => {
            let (a0, a1) = (lo.cos().sqrt(), hi.cos().max(0.0).sqrt());
            (a0 - s * (a0 - a1)).powi(2).acos()
        }
    }
}

struct Table {
    bytes: Vec<u8>,
    kind: TableKind,
    axes: Vec<Axis<'static>>,
    c: usize,
    linear: bool,
    /// Per channel: the allowed error of (b).
    tol: [f64; 2],
}

/// Node (i, j, k) of flat index `flat` (axis 0 fastest; absent axes 0).
fn node(axes: &[Axis<'_>], mut flat: usize) -> [f64; 3] {
    let mut idx = [0.0; 3];
    for (d, a) in axes.iter().enumerate() {
        idx[d] = (flat % a.count as usize) as f64;
        flat /= a.count as usize;
    }
    idx
}

/// The table, and the tolerance of (b) per channel: the encoding's rounding of a node value
/// (u16: ½ LSB of the channel's span; f16: 2⁻¹¹ of |v|; f32: 2⁻²⁴ of |v|); the f32 node
/// index's error (a few ulp of the warped coordinate and of a·w + b: < 1e-5 of a cell with
/// ≤ 6 nodes) times the interpolant's slope (≤ 4 spans per cell for Catmull–Rom with the
/// folded ends); the f32 blend (≲ 10 roundings, 1e-6 of |v|).
fn build(kind: TableKind, axes: &[Axis<'static>], e: Encoding, i: Interpolation) -> Table {
    use TableKind::{GlassAlbedo, GlassAverageAlbedo, SplitSum};
    let c = 1 + usize::from(matches!(kind, SplitSum | GlassAlbedo | GlassAverageAlbedo));
    let generator = Generator::default();
    let channels = &["A", "B"][..c];
    let spec = Spec {
        kind,
        axes,
        channels,
        encoding: e,
        interpolation: i,
        generator,
    };
    let values: Vec<f64> = (0..spec.nodes())
        .flat_map(|f| (0..c).map(move |ch| poly(ch, node(axes, f))))
        .collect();
    let mut tol = [0.0; 2];
    for (ch, t) in tol.iter_mut().enumerate().take(c) {
        let v = values.iter().skip(ch).step_by(c);
        let (lo, hi) = v.fold((f64::MAX, f64::MIN), |(l, h), &x| (l.min(x), h.max(x)));
        let big = lo.abs().max(hi.abs());
        let q = match e {
            Encoding::Unorm16 => 0.5 * (hi - lo) / 65535.0,
            Encoding::F16 => big / 2048.0,
            Encoding::F32 => big / 16_777_216.0,
        };
        *t = q + 1e-5 * 4.0 * (hi - lo) + 1e-6 * big;
    }
    let bytes = write::build(&spec, &values, |_| ErrorStats::default()).unwrap();
    let linear = i == Interpolation::Linear;
    Table {
        bytes,
        kind,
        axes: axes.to_vec(),
        c,
        linear,
        tol,
    }
}

/// The scalar lookup of the table's typed reader (the 3-D G table's factor: the view's).
fn scalar(t: &Table, x: [f32; 3]) -> [f32; 2] {
    let b = &t.bytes[..];
    match t.kind {
        TableKind::AverageAlbedo => [Avg::parse(b).unwrap().e_avg(x[0]), 0.0],
        TableKind::DirectionalAlbedo => [AlbedoTable::parse(b).unwrap().e(x[0], x[1]), 0.0],
        TableKind::SplitSum => Dfg::parse(b).unwrap().ab(x[0], x[1]).into(),
        TableKind::GlassAverageAlbedo => GAvg::parse(b).unwrap().rt_avg(x[0], x[1]).into(),
        TableKind::GlassAlbedo => Glass::parse(b).unwrap().rt(x[0], x[1], x[2]).into(),
        _ => [LutView::parse(b).unwrap().sample3(x[0], x[1], x[2])[0], 0.0],
    }
}

/// At a node (`step` 0) its value; at a cell centre (`step` 1) the mean of the 2^D corners.
fn mean(c: usize, ijk: [f64; 3], d: usize, step: f64) -> f64 {
    let corner = |m: usize| core::array::from_fn(|a| ijk[a] + step * ((m >> a) & 1) as f64);
    (0..1usize << d).map(|m| poly(c, corner(m))).sum::<f64>() / (1 << d) as f64
}

/// (b): node values, and for linear tables the cell centres' corner means.
fn check_values(t: &Table) {
    let d = t.axes.len();
    let nodes: usize = t.axes.iter().map(|a| a.count as usize).product();
    for f in 0..nodes {
        let ijk = node(&t.axes, f);
        let at = |a: usize, off: f64| t.axes.get(a).map_or(0.0, |ax| phys(ax, ijk[a] + off));
        let x = |off: f64| core::array::from_fn(|a| at(a, off) as f32);
        let inner = (0..d).all(|a| ijk[a] + 1.0 < t.axes[a].count as f64);
        let centre = t.linear && inner;
        for off in [0.0, 0.5].into_iter().filter(|&o| o == 0.0 || centre) {
            let v = scalar(t, x(off));
            for (c, (&vc, tol)) in v.iter().zip(t.tol).enumerate().take(t.c) {
                let want = mean(c, ijk, d, 2.0 * off);
                let msg = format!("{:?} {ijk:?}+{off} ch {c}: {vc} vs {want}", t.kind);
                assert!((vc as f64 - want).abs() <= tol, "{msg}");
            }
        }
    }
}

/// `n` queries on axis `a`: uniform over the range widened by 20 % each side, with NaN,
/// ±∞, ±1e30, the range ends and nodes mixed in.
fn queries(a: &Axis<'_>, n: usize, mut s: u64) -> Vec<f32> {
    let special = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1e30, 1e30];
    (0..n)
        .map(|k| {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let u = (s >> 40) as f64 / (1u64 << 24) as f64;
            let w = 0.2 * (a.hi - a.lo);
            match k % 11 {
                3 => special[(k / 11) % special.len()],
                5 => a.lo as f32,
                7 => a.hi as f32,
                9 => phys(a, ((s >> 20) % a.count as u64) as f64) as f32,
                _ => (a.lo - w + u * (a.hi - a.lo + 2.0 * w)) as f32,
            }
        })
        .collect()
}

/// (a): the table's batch entry point against its scalar lookup, bit for bit, and nothing
/// written past the queries.
fn check_batch(t: &Table) {
    let b = &t.bytes[..];
    for n in [0, 1, 3, 7, 8, 9, 13, 17, 31, 33, 64, 203] {
        let x: Vec<Vec<f32>> = (0..3)
            .map(|d| {
                t.axes
                    .get(d)
                    .map_or(vec![0.0; n], |a| queries(a, n, (31 * d + n) as u64))
            })
            .collect();
        let (mut o0, mut o1) = (vec![-1.0f32; n + 2], vec![-1.0f32; n + 2]);
        let (x0, x1, x2) = (&x[0][..], &x[1][..], &x[2][..]);
        let (o, p) = (&mut o0, &mut o1);
        let m = match t.kind {
            TableKind::AverageAlbedo => Avg::parse(b).unwrap().e_avg_batch(x0, o),
            TableKind::DirectionalAlbedo => AlbedoTable::parse(b).unwrap().e_batch(x0, x1, o),
            TableKind::SplitSum => Dfg::parse(b).unwrap().ab_batch(x0, x1, o, p),
            TableKind::GlassAverageAlbedo => GAvg::parse(b).unwrap().rt_avg_batch((x0, x1), o, p),
            TableKind::GlassAlbedo => Glass::parse(b).unwrap().rt_batch((x0, x1, x2), o, p),
            _ => {
                // G's own batch (its chunk paths, one σ per call) against its scalar G.
                let g = GTable3::parse(b).unwrap();
                for sigma in [0.3, 0.05, 2.0, f32::NAN] {
                    assert_eq!(g.g_batch(x0, x1, sigma, o), n);
                    for k in 0..n {
                        let v = g.g(x0[k], x1[k], sigma);
                        assert_eq!(o[k].to_bits(), v.to_bits(), "G n {n} query {k}");
                    }
                }
                continue;
            }
        };
        assert_eq!(m, n);
        for k in 0..n {
            let v = scalar(t, [x0[k], x1[k], x2[k]]);
            for (c, o) in [&o0, &o1].into_iter().enumerate().take(t.c) {
                let msg = format!("{:?} n {n} query {k} ch {c}: {} vs {}", t.kind, o[k], v[c]);
                assert_eq!(o[k].to_bits(), v[c].to_bits(), "{msg}");
            }
        }
        assert!(
            o0[n..].iter().chain(&o1[n..]).all(|&v| v == -1.0),
            "wrote past n"
        );
    }
}

#[test]
fn every_shape_encoding_and_warp() {
    use Placement::{Endpoint as E, TexelCentre as T};
    use TableKind as K;
    use Warp::*;
    let h = core::f64::consts::FRAC_PI_2;
    let g = [
        ax(5, 0.0, h, SqrtCos, E),
        ax(4, -h, h, Linear, E),
        ax(4, 0.05, 1.0, Log, E),
    ];
    let glass = [
        ax(5, 0.0, 1.0, Linear, E),
        ax(4, 0.0, 1.0, Sqrt, T),
        ax(6, 1.0, 3.0, Log, E),
    ];
    // (The channel counts follow from the kinds: 2 for split-sum and glass, else 1.)
    let shapes = [
        (K::AverageAlbedo, vec![ax(6, 0.0, 1.0, Sqrt, E)]),
        (
            K::DirectionalAlbedo,
            vec![ax(5, 0.1, 2.0, Log, E), ax(4, -1.0, 2.0, Linear, T)],
        ),
        (
            K::SplitSum,
            vec![ax(6, 0.0, 1.0, Sqrt, E), ax(5, 0.0, 1.0, Linear, E)],
        ),
        (
            K::GlassAverageAlbedo,
            vec![ax(4, 0.2, 1.3, Cos, E), ax(5, 1.0, 3.0, Log, T)],
        ),
        (K::PassingFactor, g.to_vec()),
        (K::GlassAlbedo, glass.to_vec()),
    ];
    let mut tables = 0;
    for (kind, axes) in &shapes {
        for e in [Encoding::Unorm16, Encoding::F16, Encoding::F32] {
            for i in [Interpolation::Linear, Interpolation::CatmullRom] {
                // Catmull–Rom also with a 3-node axis 0: the per-tap general path.
                let short = (i == Interpolation::CatmullRom).then(|| {
                    let mut s = axes.clone();
                    s[0].count = 3;
                    s
                });
                for axes in core::iter::once(axes.clone()).chain(short) {
                    let t = build(*kind, &axes, e, i);
                    check_values(&t);
                    check_batch(&t);
                    tables += 1;
                }
            }
        }
    }
    assert_eq!(tables, 6 * 3 * 3);
}

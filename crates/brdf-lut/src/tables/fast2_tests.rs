//! The two-lane lookup of 2-D one- and two-channel linear u16 tables (`lookup::simd::Fast2`) and
//! its eight-lane AVX2 batch against the general scalar reader, bit for bit, on the
//! committed assets and on made-up tables written by the crate's writer. (Here, above the
//! lookup module, because the tables are built with `write` and prepared from a view.)

use super::Prepared;
use crate::header::{Axis, Encoding, Interpolation, Placement, TableKind, Warp};
use crate::lookup::simd::{Fast2, Kind, One, Two};
use crate::lookup::{Lane, Reader};
use crate::testing::{asset, asset_path, axis};
use crate::write;
use crate::LutView;
use std::vec::Vec;

/// `v` equals `want` bit for bit, except that two different NaNs (signs) meeting in one
/// operation give either one: x86 returns the first operand's, and the compiler may swap
/// the operands of a multiplication. Only then (x and y NaNs of different bits) are the
/// NaNs' bits left free.
fn agrees(x: f32, y: f32, v: (f32, f32), want: [f32; 2]) -> bool {
    let same = v.0.to_bits() == want[0].to_bits() && v.1.to_bits() == want[1].to_bits();
    let free = x.is_nan() && y.is_nan() && x.to_bits() != y.to_bits();
    same || free && v.0.is_nan() && v.1.is_nan() && want[0].is_nan()
}

/// The table of `spec` holding `values`, written by the crate's writer.
/// The spec of a made-up u16 table of one channel (directional albedo, `A`) or two
/// (split-sum, `A` and `B`).
fn u16_spec<'a>(
    axes: &'a [Axis<'a>],
    channels: usize,
    interpolation: Interpolation,
) -> write::Spec<'a> {
    const NAMES: [&str; 2] = ["A", "B"];
    write::Spec {
        kind: [TableKind::DirectionalAlbedo, TableKind::SplitSum][channels - 1],
        axes,
        channels: &NAMES[..channels],
        encoding: Encoding::Unorm16,
        interpolation,
        generator: Default::default(),
    }
}

fn encode(spec: &write::Spec, values: &[f64]) -> Vec<u8> {
    let (chans, payload) = write::quantise(spec, values).unwrap();
    let h = write::header(spec, chans, Default::default()).unwrap();
    write::encode(&h, &payload).unwrap()
}

/// Coordinates for one axis of `lane`: special values, the range ends and their f32
/// neighbours, every node exactly (x = lo + (hi − lo)·s² or lo + (hi − lo)·s at node
/// s = k/(n − 1) and its neighbours), cell midpoints and an additive recurrence.
fn coords(l: &Lane) -> Vec<f32> {
    let (lo, hi) = (l.lo, l.hi);
    let up = |x: f32| {
        f32::from_bits(if x >= 0.0 {
            x.to_bits() + 1
        } else {
            x.to_bits() - 1
        })
    };
    let down = |x: f32| {
        f32::from_bits(if x > 0.0 {
            x.to_bits() - 1
        } else {
            x.to_bits() + 1
        })
    };
    let mut v = std::vec![
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        f32::MAX,
        -f32::MAX,
        f32::MIN_POSITIVE,
        1e-30,
        -1e-30,
        lo,
        hi,
        up(lo),
        down(lo),
        up(hi),
        down(hi),
        lo - 1.0,
        hi + 1.0,
        0.5 * (lo + hi),
    ];
    let n = l.n;
    for k in 0..n {
        for m in [0.0, 0.5] {
            let s = ((k as f64 + m) / (n - 1) as f64).min(1.0);
            let s = if l.warp == Warp::Sqrt { s * s } else { s };
            let x = (lo as f64 + (hi as f64 - lo as f64) * s) as f32;
            v.extend([x, up(x), down(x)]);
        }
    }
    for k in 0..2000 {
        let u = (0.618_033_988_749_895 * k as f64).fract() as f32;
        v.push(lo + (hi - lo) * u);
    }
    v
}

/// `Fast2::lookup::<Two>` (from the payload and from the whole file) against the general scalar
/// reader, bit for bit, over the product of both axes' coordinates; returns the kind.
fn check(bytes: &[u8]) -> Kind {
    let view = LutView::parse(bytes).unwrap();
    let p = Prepared::new(&view);
    let f = Fast2::new(&p.reader, p.grid.dims, p.grid.channels);
    if f.kind == Kind::None {
        return Kind::None;
    }
    if p.grid.channels == 1 {
        return check_one(bytes, &p, &f);
    }
    let payload = view.payload();
    let hl = p.header_len;
    assert_eq!(&bytes[hl..], payload);
    let (xs, ys) = (coords(&p.reader.lanes[0]), coords(&p.reader.lanes[1]));
    let mut nan = 0;
    for &x in &xs {
        for &y in &ys {
            let want = p.reader.sample::<2, 2>(&p.grid, payload, [x, y]);
            let (a, b) = (
                f.lookup::<Two>(&p.reader, payload, 0, x, y),
                f.lookup::<Two>(&p.reader, bytes, hl, x, y),
            );
            let ok = |v: Option<(f32, f32)>| v.is_some_and(|v| agrees(x, y, v, want));
            assert!(ok(a) && ok(b), "({x:e}, {y:e}): {a:?} {b:?} vs {want:?}");
            // NaN in either coordinate (only then) gives NaN in both channels.
            assert_eq!(
                x.is_nan() || y.is_nan(),
                want[0].is_nan() && want[1].is_nan()
            );
            nan += usize::from(want[0].is_nan());
        }
    }
    assert!(nan > 0);
    // A payload one byte short of the last block reads NaN (no panic, no read past it).
    let short = &payload[..payload.len() - 1];
    let (l0, l1) = (&p.reader.lanes[0], &p.reader.lanes[1]);
    let v = f.lookup::<Two>(&p.reader, short, 0, l0.hi, l1.hi).unwrap();
    assert!(v.0.is_nan() && v.1.is_nan());
    assert!(!f
        .lookup::<Two>(&p.reader, short, 0, l0.lo, l1.lo)
        .unwrap()
        .0
        .is_nan());
    if f.kind == Kind::Sqrt {
        batch_equals_scalar(&f, &p.reader, bytes, hl, &xs, &ys);
    }
    f.kind
}

/// [`check`] of a one-channel table: `Fast2::lookup::<One>` (from the payload and from the whole file)
/// against the general scalar reader, bit for bit, NaN exactly where a coordinate is NaN,
/// and NaN from a payload one byte short of the last block.
fn check_one(bytes: &[u8], p: &Prepared, f: &Fast2) -> Kind {
    let hl = p.header_len;
    let payload = &bytes[hl..];
    let (xs, ys) = (coords(&p.reader.lanes[0]), coords(&p.reader.lanes[1]));
    for &x in &xs {
        for &y in &ys {
            let [want] = p.reader.sample::<2, 1>(&p.grid, payload, [x, y]);
            let got = [
                f.lookup::<One>(&p.reader, payload, 0, x, y),
                f.lookup::<One>(&p.reader, bytes, hl, x, y),
            ];
            // As in `check`: only two NaNs of different signs leave the NaN's bits free.
            let free = x.is_nan() && y.is_nan() && x.to_bits() != y.to_bits();
            for v in got {
                let ok = v.is_some_and(|v| {
                    v.to_bits() == want.to_bits() || free && v.is_nan() && want.is_nan()
                });
                assert!(ok, "({x:e}, {y:e}): {v:?} vs {want:?}");
            }
            assert_eq!(x.is_nan() || y.is_nan(), want.is_nan());
        }
    }
    let short = &payload[..payload.len() - 1];
    let (l0, l1) = (&p.reader.lanes[0], &p.reader.lanes[1]);
    assert!(f
        .lookup::<One>(&p.reader, short, 0, l0.hi, l1.hi)
        .unwrap()
        .is_nan());
    assert!(!f
        .lookup::<One>(&p.reader, short, 0, l0.lo, l1.lo)
        .unwrap()
        .is_nan());
    // The two-channel entry points do not take a one-channel table.
    assert!(f
        .lookup::<Two>(&p.reader, payload, 0, l0.lo, l1.lo)
        .is_none());
    f.kind
}

/// The eight-lane batch (where the processor has AVX2) against `Fast2::lookup::<Two>`, bit for
/// bit: every (x, y) of the coordinate product in query order, a tail of 1–7, and a
/// payload one byte short, whose chunks that touch the last block fall back to the
/// scalar lookup (NaN there).
fn batch_equals_scalar(f: &Fast2, r: &Reader, bytes: &[u8], hl: usize, xs: &[f32], ys: &[f32]) {
    if !std::is_x86_feature_detected!("avx2") {
        return;
    }
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for &a in xs {
        for &b in ys {
            x.push(a);
            y.push(b);
        }
    }
    let (l0, l1) = (&r.lanes[0], &r.lanes[1]);
    let short = &bytes[..bytes.len() - 1];
    for (data, n) in [(bytes, x.len()), (bytes, 13), (short, 40)] {
        let (x, mut y) = (&x[x.len() - n..], y[y.len() - n..].to_vec());
        if data.len() < bytes.len() {
            // Every third query at the far corner (its block is the short one).
            let mut x = x.to_vec();
            for k in (0..n).step_by(3) {
                (x[k], y[k]) = (l0.hi, l1.hi);
            }
            return run(f, r, data, hl, &x, &y);
        }
        run(f, r, data, hl, x, &y);
    }
    fn run(f: &Fast2, r: &Reader, data: &[u8], hl: usize, x: &[f32], y: &[f32]) {
        let n = x.len();
        let (mut a, mut b) = (std::vec![-1.0; n], std::vec![-1.0; n]);
        let limit = f.limit(data, hl).unwrap();
        // SAFETY: the processor has AVX2 (checked above).
        assert!(unsafe { f.batch_avx2(r, data, hl, limit, x, y, [&mut a, &mut b]) });
        for k in 0..n {
            let want = f.lookup::<Two>(r, data, hl, x[k], y[k]).unwrap();
            let ok = agrees(x[k], y[k], (a[k], b[k]), [want.0, want.1]);
            assert!(
                ok,
                "{k} ({:e}, {:e}): {:?} vs {want:?}",
                x[k],
                y[k],
                (a[k], b[k])
            );
        }
    }
}

/// Every committed asset: the one- and two-channel linear 2-D ones take the two-lane path (the
/// split-sum speed tier its inlined form) and equal the general reader bit for bit.
#[test]
fn assets_equal_the_general_reader() {
    let dir = asset_path("");
    let mut taken = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        if !name.ends_with(".blut") {
            continue;
        }
        let bytes = asset(&name);
        let h = *LutView::parse(&bytes).unwrap().header();
        let fits = h.axes.len() == 2
            && (1..=2).contains(&h.channels.len())
            && h.axes
                .iter()
                .all(|a| matches!(a.warp, Warp::Linear | Warp::Sqrt))
            && h.encoding == Encoding::Unorm16
            && h.interpolation == Interpolation::Linear;
        let kind = check(&bytes);
        assert_eq!(kind != Kind::None, fits, "{name}");
        if fits {
            taken.push((name, kind));
        }
    }
    assert!(
        taken.contains(&("dfg_ggx_linear.blut".into(), Kind::Sqrt)),
        "{taken:?}"
    );
}

/// A √ endpoint axis whose t at hi rounds above n − 1 (found by search) keeps the t
/// clamp: the table takes the out-of-line form, with the same values.
#[test]
fn rounding_past_the_last_node_keeps_the_clamp() {
    let ax = |hi: f64| axis(256, 0.0, hi, Warp::Sqrt, Placement::Endpoint);
    let over = (1..1000)
        .map(|k| 0.3 + 0.0007 * k as f64)
        .find(|&hi| {
            let l = Lane::new(&ax(hi), 2).unwrap();
            l.a * libm::sqrtf(l.hi - l.lo) + l.b > l.last
        })
        .expect("some range rounds past the last node");
    let axes = [ax(over), ax(1.0)];
    let spec = u16_spec(&axes, 2, Interpolation::Linear);
    let values: Vec<f64> = (0..spec.nodes() * 2)
        .map(|k| (0.37 * k as f64).sin())
        .collect();
    assert_eq!(check(&encode(&spec, &values)), Kind::Mixed);
    // The same table with the other range takes the inlined form.
    let axes = [ax(1.0), ax(1.0)];
    let spec = write::Spec {
        axes: &axes,
        ..spec
    };
    assert_eq!(check(&encode(&spec, &values)), Kind::Sqrt);
}

/// Made-up tables of every axis form the path takes (linear, √, endpoint and texel-centre
/// nodes, 2 to 300 nodes, ranges that do and do not start at 0, negative ends), and
/// some it does not (log warp, Catmull–Rom); two channels and one.
#[test]
fn made_up_tables_equal_the_general_reader() {
    let ax = axis;
    use Placement::{Endpoint as E, TexelCentre as T};
    use Warp::{Linear as L, Log, Sqrt as S};
    // (axes, channels, interpolation); two channels and linear unless said.
    let lin = |a, b| ([a, b], 2, Interpolation::Linear);
    let cases = [
        lin(ax(256, 0.0, 1.0, S, E), ax(256, 0.0, 1.0, S, E)),
        lin(ax(2, 0.0, 1.0, S, E), ax(3, 0.0, 1.0, S, E)),
        lin(ax(64, 0.05, 0.93, S, E), ax(19, 0.1, 1.0, S, E)),
        lin(ax(37, 0.05, 0.93, S, E), ax(19, 0.1, 1.0, S, E)),
        lin(ax(16, 0.0, 1.0, S, T), ax(9, 0.0, 1.0, S, T)),
        lin(ax(33, -1.5, 2.25, L, E), ax(17, 0.0, 1.0, S, E)),
        lin(ax(8, 0.0, 1.0, S, E), ax(300, -3.0, -1.0, L, T)),
        lin(ax(64, 0.0, 1.0, L, E), ax(64, 0.0, 1.0, L, E)),
        lin(ax(16, 0.1, 1.0, Log, E), ax(16, 0.0, 1.0, S, E)),
        (
            [ax(16, 0.0, 1.0, S, E), ax(16, 0.0, 1.0, S, E)],
            2,
            Interpolation::CatmullRom,
        ),
        (
            [ax(16, 0.0, 1.0, S, E), ax(16, 0.0, 1.0, S, E)],
            1,
            Interpolation::Linear,
        ),
        // One channel: the sheen albedo's default axes (μ √ from cos 89°, r linear from
        // 0), and other forms.
        (
            [ax(64, 0.017_452_4, 1.0, S, E), ax(64, 0.0, 1.0, L, E)],
            1,
            Interpolation::Linear,
        ),
        (
            [ax(32, 0.0, 1.0, S, E), ax(3, 0.0, 1.0, S, E)],
            1,
            Interpolation::Linear,
        ),
        (
            [ax(37, -1.5, 2.25, L, T), ax(2, 0.1, 1.0, S, E)],
            1,
            Interpolation::Linear,
        ),
        (
            [ax(16, 0.0, 1.0, S, E), ax(16, 0.0, 1.0, S, E)],
            1,
            Interpolation::CatmullRom,
        ),
    ];
    let mut kinds = Vec::new();
    for (axes, nc, interpolation) in cases {
        let spec = u16_spec(&axes, nc, interpolation);
        let nodes = spec.nodes();
        // Smooth plus a fixed pseudo-random part, so neighbouring nodes differ.
        let values: Vec<f64> = (0..nodes * nc)
            .map(|k| {
                let u = (0.754_877_666_246_692_7 * k as f64).fract();
                (0.37 * k as f64).sin() + 0.2 * u
            })
            .collect();
        kinds.push(check(&encode(&spec, &values)));
    }
    use Kind::{Mixed as M, MixedOne as M1, None as N, Sqrt as Q, SqrtOne as Q1};
    // Which form each table takes: √ with endpoint nodes and 2^k nodes on axis 0 the
    // inlined one (t at the range ends rounds into [0, n − 1] for these ranges), the
    // rest (37 nodes on axis 0, texel centres, linear axes) out of line.
    let want = [Q, Q, Q, M, M, M, M, M, N, N, Q1, M1, Q1, M1, N];
    assert_eq!(kinds, want);
}

//! Table layouts: the prepared lookup constants of a typed table without its bytes, so that
//! an owner who cannot keep a borrow of the bytes across calls (a WebAssembly module whose
//! host may rewrite the buffer between calls) keeps the layout instead and rebuilds the
//! typed table per call without decoding the header again.

use super::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, Prepared};
use crate::LutError;
use core::fmt;
use core::marker::PhantomData;

/// What a typed table `T` prepared from its header (every lookup constant), the total length
/// of its bytes and its CRC-32 field, without the bytes: a small `Copy` value taken from a
/// parsed table by `layout()` (e.g. [`GTable3::layout`]) and turned back into the table by
/// `with_layout` (e.g. [`GTable3::with_layout`]) in O(1), with no header decode.
///
/// `T` names the table type the layout belongs to (`TableLayout<GTable3>` for a
/// [`GTable3`] over any byte container), so a layout cannot rebuild a table of another kind
/// or shape. The contents are opaque.
pub struct TableLayout<T> {
    p: Prepared,
    /// Length of the table's bytes, header and payload.
    len: usize,
    /// Where the CRC-32 field (the last 4 bytes of the header) starts, and its bytes;
    /// `None` if the table's bytes no longer decoded when the layout was taken.
    crc: Option<(usize, [u8; 4])>,
    table: PhantomData<fn() -> T>,
}

impl<T> Clone for TableLayout<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for TableLayout<T> {}

impl<T> fmt::Debug for TableLayout<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TableLayout")
            .field("len", &self.len)
            .field("crc", &self.crc.map(|(_, c)| u32::from_le_bytes(c)))
            .finish_non_exhaustive()
    }
}

impl<T> TableLayout<T> {
    /// `header_len`: where the payload of `bytes` starts (`None` if they no longer decode).
    fn new(p: Prepared, bytes: &[u8], header_len: Option<usize>) -> Self {
        let crc = header_len.and_then(|end| {
            let at = end.checked_sub(4)?;
            let field: [u8; 4] = bytes.get(at..end)?.try_into().ok()?;
            Some((at, field))
        });
        TableLayout {
            p,
            len: bytes.len(),
            crc,
            table: PhantomData,
        }
    }

    /// Length in bytes (header and payload) of the table the layout was taken from: the
    /// only length `with_layout` accepts.
    pub fn byte_len(&self) -> usize {
        self.len
    }

    /// The table's CRC-32 as its header stores it (checked when the table was parsed);
    /// `None` only for a layout taken from bytes that had changed since they were parsed.
    pub fn crc32(&self) -> Option<u32> {
        self.crc.map(|(_, c)| u32::from_le_bytes(c))
    }

    /// The O(1) checks of `with_layout`: the length, then the CRC-32 field.
    fn check(&self, bytes: &[u8]) -> Result<(), LutError> {
        let Some((at, crc)) = self.crc else {
            return Err(LutError::Truncated);
        };
        if bytes.len() != self.len {
            let header = at + 4;
            return Err(LutError::PayloadLength {
                expected: self.len.saturating_sub(header) as u64,
                found: bytes.len().saturating_sub(header) as u64,
            });
        }
        // In range: `at + 4` ≤ the recorded length, which `bytes` has.
        let Some(field) = bytes
            .get(at..at + 4)
            .and_then(|f| <[u8; 4]>::try_from(f).ok())
        else {
            return Err(LutError::Truncated);
        };
        if field != crc {
            return Err(LutError::Checksum {
                stored: u32::from_le_bytes(field),
                computed: u32::from_le_bytes(crc),
            });
        }
        Ok(())
    }
}

macro_rules! layout_of {
    ($($name:ident),+) => {$(
        impl<B: AsRef<[u8]>> $name<B> {
            /// The table's [`TableLayout`]: its prepared lookup constants, byte length and
            /// CRC-32 field, to rebuild it later with `with_layout` without a header decode.
            ///
            /// Decodes the header once more (no CRC) to locate the CRC-32 field.
            pub fn layout(&self) -> TableLayout<$name> {
                // The view's decoder rather than `header_len`: the same code as `parse`,
                // so small builds (WebAssembly) link no second header decoder.
                let header_len = self.view().ok().map(|v| v.header_len());
                TableLayout::new(self.p, self.bytes.as_ref(), header_len)
            }

            /// Rebuilds the table from `bytes` and the layout taken from the table parsed
            /// from these bytes, in O(1): the header is not decoded and the CRC-32 is not
            /// recomputed. Checks only that `bytes` has the recorded length
            /// ([`LutError::PayloadLength`] otherwise, in payload bytes) and that its
            /// CRC-32 field still holds the recorded value ([`LutError::Checksum`]
            /// otherwise, `stored` from `bytes`, `computed` the recorded one), which catches
            /// another table of the same length put in their place.
            ///
            /// If the payload changed since the layout was taken, lookups give wrong values
            /// or NaN, but never panic and never read out of bounds: the layout's constants
            /// are not taken from `bytes`, so every node index stays within the recorded
            /// length, and every payload read is a bounds-checked slice. To trust changed
            /// bytes again, parse them (`parse` checks everything, CRC included).
            pub fn with_layout(bytes: B, layout: TableLayout<$name>) -> Result<Self, LutError> {
                layout.check(bytes.as_ref())?;
                Ok(Self { bytes, p: layout.p })
            }
        }
    )+};
}

layout_of!(GTable, GTable3, DfgTable, AlbedoTable, AverageAlbedoTable);

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use std::vec::Vec;

    use crate::testing::asset;

    /// A grid over [lo, hi] with `n` points, ends included, plus points outside (clamped)
    /// and NaN.
    fn coords(lo: f32, hi: f32, n: usize) -> Vec<f32> {
        let mut v: Vec<f32> = (0..n)
            .map(|k| lo + (hi - lo) * k as f32 / (n - 1) as f32)
            .collect();
        v.extend([lo - 1.0, hi + 1.0, f32::NAN]);
        v
    }

    /// Equal bit for bit (NaN equal to NaN only if both are NaN).
    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    const FRAC_PI_2: f32 = core::f32::consts::FRAC_PI_2;

    // The reference is the table parsed with every check (header decode and CRC): the
    // rebuilt table must give exactly its values, so no tolerance.
    #[test]
    fn rebuilt_tables_look_up_the_parsed_values_bit_for_bit() {
        let bytes = asset("g_modified.blut");
        let t = GTable3::parse(&bytes[..]).unwrap();
        let r = GTable3::with_layout(&bytes[..], t.layout()).unwrap();
        let (slo, shi) = t.sigma_range();
        assert_eq!(r.sigma_range(), (slo, shi));
        for &s in &coords(slo, shi, 5) {
            for &ti in &coords(0.0, FRAC_PI_2, 9) {
                for &tr in &coords(-FRAC_PI_2, FRAC_PI_2, 9) {
                    let (a, b) = (t.terms(ti, tr, s), r.terms(ti, tr, s));
                    assert!(same(a.0, b.0) && same(a.1, b.1) && same(a.2, b.2));
                    assert!(same(t.g_dots(ti, tr, s, s), r.g_dots(ti, tr, s, s)));
                }
            }
        }

        let bytes = asset("g_modified_sigma0.3_linear.blut");
        let t = GTable::parse(bytes.clone()).unwrap();
        let r = GTable::with_layout(bytes, t.layout()).unwrap();
        assert!(same(t.sigma(), r.sigma()));
        for &ti in &coords(0.0, FRAC_PI_2, 17) {
            for &tr in &coords(-FRAC_PI_2, FRAC_PI_2, 17) {
                assert!(same(t.g(ti, tr), r.g(ti, tr)));
            }
        }

        let bytes = asset("dfg_ggx.blut");
        let t = DfgTable::parse(&bytes[..]).unwrap();
        let r = DfgTable::with_layout(&bytes[..], t.layout()).unwrap();
        for &mu in &coords(0.0, 1.0, 17) {
            for &rough in &coords(0.0, 1.0, 17) {
                let (a, b) = (t.ab(mu, rough), r.ab(mu, rough));
                assert!(same(a.0, b.0) && same(a.1, b.1));
            }
        }

        let bytes = asset("kc_e_ggx.blut");
        let t = AlbedoTable::parse(&bytes[..]).unwrap();
        let r = AlbedoTable::with_layout(&bytes[..], t.layout()).unwrap();
        let bytes = asset("kc_eavg_ggx.blut");
        let t1 = AverageAlbedoTable::parse(&bytes[..]).unwrap();
        let r1 = AverageAlbedoTable::with_layout(&bytes[..], t1.layout()).unwrap();
        for &mu in &coords(0.0, 1.0, 17) {
            assert!(same(t1.e_avg(mu), r1.e_avg(mu)));
            for &rough in &coords(0.0, 1.0, 17) {
                assert!(same(t.e(mu, rough), r.e(mu, rough)));
            }
        }
    }

    #[test]
    fn the_layout_records_the_length_and_the_checksum_of_the_file() {
        let bytes = asset("dfg_ggx.blut");
        let layout = DfgTable::parse(&bytes[..]).unwrap().layout();
        assert_eq!(layout.byte_len(), bytes.len());
        // The CRC-32 of the signed header part and the payload (docs/lut-format.md), from
        // the crate's checksum over the file's own bytes.
        let end = crate::header_len(&bytes).unwrap();
        let crc = crate::Crc32::new()
            .update(&bytes[..end - 4])
            .update(&bytes[end..])
            .finish();
        assert_eq!(layout.crc32(), Some(crc));
    }

    #[test]
    fn the_header_is_not_read_again() {
        // A clobbered magic and header (CRC field and length kept) still rebuild and give
        // the parsed values: the header is not decoded, which is the point of the layout.
        let bytes = asset("dfg_ggx.blut");
        let t = DfgTable::parse(&bytes[..]).unwrap();
        let end = crate::header_len(&bytes).unwrap();
        let mut junk = bytes.clone();
        junk[..end - 4].fill(0xA5);
        assert!(DfgTable::parse(&junk[..]).is_err());
        let r = DfgTable::with_layout(&junk[..], t.layout()).unwrap();
        for &mu in &coords(0.0, 1.0, 9) {
            let (a, b) = (t.ab(mu, 0.4), r.ab(mu, 0.4));
            assert!(same(a.0, b.0) && same(a.1, b.1));
        }
    }

    #[test]
    fn other_lengths_and_other_tables_are_rejected() {
        let bytes = asset("g_modified_sigma0.3.blut");
        let layout = GTable::parse(&bytes[..]).unwrap().layout();
        let end = crate::header_len(&bytes).unwrap();
        let payload = (bytes.len() - end) as u64;
        let cut = GTable::with_layout(&bytes[..bytes.len() - 1], layout).unwrap_err();
        assert_eq!(
            cut,
            LutError::PayloadLength {
                expected: payload,
                found: payload - 1
            }
        );
        assert!(GTable::with_layout(&bytes[..10], layout).is_err());
        assert!(GTable::with_layout(&[][..], layout).is_err());
        let mut long = bytes.clone();
        long.push(0);
        assert!(matches!(
            GTable::with_layout(&long[..], layout),
            Err(LutError::PayloadLength { .. })
        ));
        // Another valid table of exactly the same length (another σ): its CRC field differs.
        let other = asset("g_modified_sigma0.5.blut");
        assert_eq!(other.len(), bytes.len());
        assert!(matches!(
            GTable::with_layout(&other[..], layout),
            Err(LutError::Checksum { .. })
        ));
    }

    #[test]
    fn changed_payloads_give_wrong_values_or_nan_but_never_panic() {
        // An all-zero payload (CRC field kept, so the rebuild succeeds): every stored u16
        // is 0, so each channel is its offset exactly, whatever the weights (0 · w = 0).
        let bytes = asset("dfg_ggx.blut");
        let t = DfgTable::parse(&bytes[..]).unwrap();
        let view = t.view().unwrap();
        assert_eq!(view.header().encoding, crate::Encoding::Unorm16);
        let off: Vec<f32> = view.header().channels.iter().map(|c| c.offset).collect();
        let end = view.header_len();
        let mut zero = bytes.clone();
        zero[end..].fill(0);
        let r = DfgTable::with_layout(&zero[..], t.layout()).unwrap();
        for &mu in &coords(0.0, 1.0, 17) {
            for &rough in &coords(0.0, 1.0, 17) {
                let (a, b) = r.ab(mu, rough);
                if mu.is_nan() || rough.is_nan() {
                    assert!(a.is_nan() && b.is_nan());
                } else {
                    assert_eq!((a, b), (off[0], off[1]), "at ({mu}, {rough})");
                }
            }
        }

        // Arbitrary payload bytes in the G table over σ (Catmull–Rom, 3-D): any value, no
        // panic; G stays clamped to [0, 1] or NaN.
        let bytes = asset("g_modified.blut");
        let t = GTable3::parse(&bytes[..]).unwrap();
        let end = crate::header_len(&bytes).unwrap();
        let mut noise = bytes.clone();
        let mut x = 0x2545_f491u32;
        for b in &mut noise[end..] {
            // xorshift32
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            *b = x as u8;
        }
        let r = GTable3::with_layout(&noise[..], t.layout()).unwrap();
        let (slo, shi) = t.sigma_range();
        let mut changed = 0;
        for &s in &coords(slo, shi, 5) {
            for &ti in &coords(0.0, FRAC_PI_2, 9) {
                for &tr in &coords(-FRAC_PI_2, FRAC_PI_2, 9) {
                    let g = r.g(ti, tr, s);
                    assert!(g.is_nan() || (0.0..=1.0).contains(&g), "{g}");
                    changed += usize::from(!same(g, t.g(ti, tr, s)));
                }
            }
        }
        assert!(changed > 0, "the noise payload was not read");
    }

    #[test]
    fn a_short_payload_reads_as_nan() {
        // Past `with_layout`'s length check (built here from the fields): the reader's own
        // bounds checks give NaN for taps beyond the bytes and the true values before them.
        let bytes = asset("kc_eavg_ggx.blut");
        let t = AverageAlbedoTable::parse(&bytes[..]).unwrap();
        let layout = t.layout();
        let empty = AverageAlbedoTable {
            bytes: &bytes[..layout.crc.unwrap().0 + 4],
            p: layout.p,
        };
        let end = crate::header_len(&bytes).unwrap();
        let cut = AverageAlbedoTable {
            bytes: &bytes[..end + (bytes.len() - end) / 2],
            p: layout.p,
        };
        for &r in &coords(0.0, 1.0, 33) {
            assert!(empty.e_avg(r).is_nan());
        }
        // E_avg(0) = 1 (a mirror reflects everything) lies at the start; the last node is
        // gone.
        assert!(same(cut.e_avg(0.0), t.e_avg(0.0)));
        assert!((cut.e_avg(0.0) - 1.0).abs() < 1e-4);
        assert!(cut.e_avg(1.0).is_nan());

        let bytes = asset("g_modified.blut");
        let t = GTable3::parse(&bytes[..]).unwrap();
        let layout = t.layout();
        for n in [0, 7, 100, bytes.len() / 3, bytes.len() - 1] {
            let short = GTable3 {
                bytes: &bytes[..n],
                p: layout.p,
            };
            for &ti in &coords(0.0, FRAC_PI_2, 5) {
                for &tr in &coords(-FRAC_PI_2, FRAC_PI_2, 5) {
                    let g = short.g(ti, tr, 0.3);
                    assert!(g.is_nan() || (0.0..=1.0).contains(&g), "{g}");
                }
            }
        }
    }
}

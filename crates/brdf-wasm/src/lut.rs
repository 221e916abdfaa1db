//! Look-up tables whose bytes the host copies into linear memory, read through the no_std,
//! zero-copy readers of `brdf-lut` (format in docs/lut-format.md).
//!
//! Three slots, each a fixed static buffer for one table kind:
//!
//! | slot | table | capacity | default asset |
//! | --- | --- | --- | --- |
//! | 0 | modified G over σ ([`GTable3`]) | 256 KiB | `assets/g_modified.blut` |
//! | 1 | modified G for one σ ([`GTable`]) | 64 KiB | `assets/g_modified_sigma0.3.blut` |
//! | 2 | split-sum (A, B) ([`DfgTable`]) | 64 KiB | `assets/dfg_ggx.blut` |
//!
//! Protocol: copy the file's bytes to `brdf_lut_ptr(slot)`, then call
//! `brdf_lut_load(slot, len)`, which validates everything (magic, version, header, sizes,
//! CRC-32, table kind) and returns 0, or a negative status with the reason in
//! `brdf_lut_error()`. Queries on a slot without a valid table return NaN ([`NO_LUT`] for
//! the status-returning ones). The load keeps the table's [`TableLayout`] (its prepared
//! lookup constants, length and CRC-32 field), not the table: a table borrowing the slot
//! across calls would be unsound, as the host may rewrite the slot between calls. Each query
//! rebuilds the table from the slot's bytes and the layout in O(1), with no header decode
//! (`with_layout` checks the length and the CRC-32 field only). A host that rewrites a slot
//! must load it again: until then the payload it wrote is read as it is (wrong values or NaN,
//! never a panic or an out-of-bounds read), and a table of another length or checksum gives
//! NaN ([`NO_LUT`]).

use crate::memory::{batch, map2, usable, StaticBuf};
use crate::status::{BAD_BUFFER, BAD_LUT, NO_LUT, OK};
use brdf_lut::{DfgTable, GTable, GTable3, LutError, LutView, TableLayout};
use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicU32, Ordering};

static SLOT0: StaticBuf<{ 256 * 1024 }> = StaticBuf::new();
static SLOT1: StaticBuf<{ 64 * 1024 }> = StaticBuf::new();
static SLOT2: StaticBuf<{ 64 * 1024 }> = StaticBuf::new();

/// The layout of a slot's validated table; `None` = no table.
static LAYOUT0: LayoutCell<GTable3> = LayoutCell::new();
static LAYOUT1: LayoutCell<GTable> = LayoutCell::new();
static LAYOUT2: LayoutCell<DfgTable> = LayoutCell::new();
/// Reason of the last failed load (see [`brdf_lut_error`]).
static LAST_ERROR: AtomicU32 = AtomicU32::new(0);

/// A slot's table layout, read and written by value only (no reference to the contents
/// ever leaves a method).
struct LayoutCell<T>(UnsafeCell<Option<TableLayout<T>>>);

// SAFETY: the module is single-threaded; on the host, callers (tests) serialise access
// themselves, as for the slots' buffers; the contents are only copied in and out.
unsafe impl<T> Sync for LayoutCell<T> {}

impl<T> LayoutCell<T> {
    const fn new() -> Self {
        Self(UnsafeCell::new(None))
    }
    fn get(&self) -> Option<TableLayout<T>> {
        // SAFETY: a copy out; no other access is in progress (single-threaded).
        unsafe { *self.0.get() }
    }
    fn set(&self, layout: Option<TableLayout<T>>) {
        // SAFETY: as above.
        unsafe { *self.0.get() = layout }
    }
}

fn slot(slot: u32) -> Option<(*mut u8, usize)> {
    match slot {
        0 => Some((SLOT0.ptr(), SLOT0.len())),
        1 => Some((SLOT1.ptr(), SLOT1.len())),
        2 => Some((SLOT2.ptr(), SLOT2.len())),
        _ => None,
    }
}

/// The first `len` bytes of a slot (at most its capacity).
///
/// # Safety
/// The host must not write the slot while the returned slice is in use (the module is
/// single-threaded, so this holds within one export call).
unsafe fn bytes<'a, const N: usize>(buf: &StaticBuf<N>, len: usize) -> &'a [u8] {
    // SAFETY: the slot holds N initialised bytes (zeroed statics) at a stable address, and
    // nothing writes them while the slice lives (the contract).
    unsafe { core::slice::from_raw_parts(buf.ptr(), len.min(N)) }
}

fn error_code(e: LutError) -> u32 {
    match e {
        LutError::Truncated => 1,
        LutError::BadMagic => 2,
        LutError::UnsupportedVersion { .. } => 3,
        LutError::MalformedHeader => 4,
        LutError::Inconsistent(_) => 5,
        LutError::PayloadLength { .. } => 6,
        LutError::Checksum { .. } => 7,
        LutError::WrongKind { .. } => 8,
        _ => 9,
    }
}

/// Address of slot `slot`'s buffer (null for an unknown slot).
#[no_mangle]
pub extern "C" fn brdf_lut_ptr(slot_id: u32) -> *mut u8 {
    slot(slot_id).map_or(core::ptr::null_mut(), |(p, _)| p)
}

/// Capacity of slot `slot` in bytes (0 for an unknown slot).
#[no_mangle]
pub extern "C" fn brdf_lut_capacity(slot_id: u32) -> u32 {
    slot(slot_id).map_or(0, |(_, n)| n as u32)
}

/// Validates the first `len` bytes of a slot's buffer (every check of [`LutView::parse`],
/// CRC included), checks the table kind with `typed` and keeps the table's layout in `cell`
/// (none on failure).
fn load<T, const N: usize>(
    buf: &StaticBuf<N>,
    cell: &LayoutCell<T>,
    len: u32,
    typed: impl FnOnce(LutView<'_>) -> Result<TableLayout<T>, LutError>,
) -> i32 {
    cell.set(None);
    if len as usize > N {
        return BAD_BUFFER;
    }
    // SAFETY: used within this call only.
    match LutView::parse(unsafe { bytes(buf, len as usize) }).and_then(typed) {
        Ok(layout) => {
            cell.set(Some(layout));
            LAST_ERROR.store(0, Ordering::Relaxed);
            OK
        }
        Err(e) => {
            LAST_ERROR.store(error_code(e), Ordering::Relaxed);
            BAD_LUT
        }
    }
}

/// Validates the first `len` bytes of slot `slot` as that slot's table kind and makes it the
/// slot's table. Returns 0; [`BAD_BUFFER`] for an unknown slot or `len` beyond the capacity;
/// [`BAD_LUT`] when the view rejects the bytes (reason in [`brdf_lut_error`]). On failure the
/// slot has no table.
#[no_mangle]
pub extern "C" fn brdf_lut_load(slot_id: u32, len: u32) -> i32 {
    match slot_id {
        0 => load(&SLOT0, &LAYOUT0, len, |v| {
            GTable3::from_view(v).map(|t| t.layout())
        }),
        1 => load(&SLOT1, &LAYOUT1, len, |v| {
            GTable::from_view(v).map(|t| t.layout())
        }),
        2 => load(&SLOT2, &LAYOUT2, len, |v| {
            DfgTable::from_view(v).map(|t| t.layout())
        }),
        _ => BAD_BUFFER,
    }
}

/// Why the last `brdf_lut_load` failed: 0 none, 1 truncated, 2 bad magic, 3 unsupported
/// version, 4 malformed header, 5 inconsistent header, 6 wrong payload length, 7 checksum
/// mismatch, 8 wrong table kind for the slot, 9 other.
#[no_mangle]
pub extern "C" fn brdf_lut_error() -> u32 {
    LAST_ERROR.load(Ordering::Relaxed)
}

fn with_g3<R>(f: impl FnOnce(&GTable3<&[u8]>) -> R) -> Option<R> {
    let layout = LAYOUT0.get()?;
    // SAFETY: used within this call only.
    let bytes = unsafe { bytes(&SLOT0, layout.byte_len()) };
    Some(f(&GTable3::with_layout(bytes, layout).ok()?))
}

fn with_g2<R>(f: impl FnOnce(&GTable<&[u8]>) -> R) -> Option<R> {
    let layout = LAYOUT1.get()?;
    // SAFETY: as above.
    let bytes = unsafe { bytes(&SLOT1, layout.byte_len()) };
    Some(f(&GTable::with_layout(bytes, layout).ok()?))
}

fn with_dfg<R>(f: impl FnOnce(&DfgTable<&[u8]>) -> R) -> Option<R> {
    let layout = LAYOUT2.get()?;
    // SAFETY: as above.
    let bytes = unsafe { bytes(&SLOT2, layout.byte_len()) };
    Some(f(&DfgTable::with_layout(bytes, layout).ok()?))
}

/// The modified G from the table over σ (slot 0) at in-plane angles θi, θr (radians) and
/// RMS slope σ (clamped to the table's ranges). NaN without a table or for NaN input.
#[no_mangle]
pub extern "C" fn brdf_g_lut(sigma: f32, theta_i: f32, theta_r: f32) -> f32 {
    with_g3(|t| t.g(theta_i, theta_r, sigma)).unwrap_or(f32::NAN)
}

/// The σ range of the table in slot 0 (`hi = 0` for lo, 1 for hi); NaN without a table.
#[no_mangle]
pub extern "C" fn brdf_g_lut_sigma_range(hi: u32) -> f32 {
    with_g3(|t| {
        let (lo, h) = t.sigma_range();
        if hi == 0 {
            lo
        } else {
            h
        }
    })
    .unwrap_or(f32::NAN)
}

/// Batch [`brdf_g_lut`] for one σ. Returns n, [`NO_LUT`] or [`BAD_BUFFER`].
///
/// # Safety
/// Each pointer that passes the null and alignment checks must be valid for n f32 (reads
/// for `theta_i`, `theta_r`, writes for `out`).
#[no_mangle]
pub unsafe extern "C" fn brdf_g_lut_batch(
    sigma: f32,
    theta_i: *const f32,
    theta_r: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    batch(n, &[theta_i, theta_r, out.cast_const()], || {
        // SAFETY: the pointers passed `batch`'s check and are valid for n f32 (the contract).
        with_g3(|t| unsafe { map2(theta_i, theta_r, out, n, |a, b| t.g(a, b, sigma)) })
            .unwrap_or(NO_LUT)
    })
}

/// The modified G from the one-σ table (slot 1) at in-plane angles (radians). NaN without a
/// table or for NaN input.
#[no_mangle]
pub extern "C" fn brdf_g_lut_fixed(theta_i: f32, theta_r: f32) -> f32 {
    with_g2(|t| t.g(theta_i, theta_r)).unwrap_or(f32::NAN)
}

/// The σ of the one-σ table in slot 1 (NaN without a table).
#[no_mangle]
pub extern "C" fn brdf_g_lut_fixed_sigma() -> f32 {
    with_g2(|t| t.sigma()).unwrap_or(f32::NAN)
}

/// Split-sum (A, B) from slot 2 at μ = n·v and roughness (clamped to the table's ranges),
/// written to `out[0..2]`. Returns 0, [`NO_LUT`] or [`BAD_BUFFER`].
///
/// # Safety
/// `out`, when it passes the null and alignment checks, must be valid for writes of 2 f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_dfg(mu: f32, roughness: f32, out: *mut f32) -> i32 {
    if !usable(out.cast_const()) {
        return BAD_BUFFER;
    }
    with_dfg(|t| {
        let (a, b) = t.ab(mu, roughness);
        // SAFETY: `out` is non-null and aligned (checked) and valid for 2 f32 (the contract).
        unsafe {
            *out = a;
            *out.add(1) = b;
        }
        OK
    })
    .unwrap_or(NO_LUT)
}

/// Batch [`brdf_dfg`]: `out` gets n pairs (A, B). Returns n, [`NO_LUT`] or [`BAD_BUFFER`].
///
/// # Safety
/// When they pass the null and alignment checks, `mu` and `roughness` must be valid for
/// reads of n f32 and `out` for writes of 2n f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_dfg_batch(
    mu: *const f32,
    roughness: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    batch(n, &[mu, roughness, out.cast_const()], || {
        with_dfg(|t| {
            // SAFETY: the pointers are non-null and aligned (checked) and valid for n, n and
            // 2n f32 (the contract); the inputs of row k are read before its outputs are
            // written.
            unsafe {
                for k in 0..n as usize {
                    let (a, b) = t.ab(*mu.add(k), *roughness.add(k));
                    *out.add(2 * k) = a;
                    *out.add(2 * k + 1) = b;
                }
            }
            n as i32
        })
        .unwrap_or(NO_LUT)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn put(s: u32, bytes: &[u8]) -> i32 {
        let cap = brdf_lut_capacity(s) as usize;
        let n = bytes.len().min(cap);
        // SAFETY: `n` is at most the slot's capacity and the source's length; no other
        // reference to the slot is live during the copy.
        unsafe { core::ptr::copy_nonoverlapping(bytes.as_ptr(), brdf_lut_ptr(s), n) };
        brdf_lut_load(s, bytes.len() as u32)
    }

    // One test touches the static slots, so parallel tests never share them.
    #[test]
    fn load_query_and_reject() {
        let g3: &[u8] = include_bytes!("../../../assets/g_modified.blut");
        let dfg: &[u8] = include_bytes!("../../../assets/dfg_ggx.blut");
        assert!(brdf_g_lut(0.3, 0.5, 0.5).is_nan(), "no table yet");
        let mut ab = [0.0f32; 2];
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        assert_eq!(unsafe { brdf_dfg(0.5, 0.5, ab.as_mut_ptr()) }, NO_LUT);

        assert_eq!(put(0, g3), OK);
        // Against brdf-core's own view over the same bytes, and within the asset's stated
        // accuracy (1e-3) of the direct kernel.
        let t = GTable3::parse(g3).unwrap();
        let direct = brdf_core::masking::ModifiedG::<f64>::new(0.3).unwrap();
        for (ti, tr) in [(0.5f32, 0.5f32), (0.2, -1.2), (1.4, 1.5)] {
            let v = brdf_g_lut(0.3, ti, tr);
            assert_eq!(v, t.g(ti, tr, 0.3));
            let d = direct.g(ti as f64, tr as f64);
            assert!((v as f64 - d).abs() < 1e-3, "{v} vs direct {d}");
        }
        assert!(brdf_g_lut(f32::NAN, 0.5, 0.5).is_nan());

        // Corruptions: a flipped payload byte (checksum), truncation, wrong kind, too long.
        let mut bad = g3.to_vec();
        let k = bad.len() - 100;
        bad[k] ^= 0x10;
        assert_eq!(put(0, &bad), BAD_LUT);
        assert_eq!(brdf_lut_error(), 7);
        assert!(
            brdf_g_lut(0.3, 0.5, 0.5).is_nan(),
            "a failed load leaves no table"
        );
        assert_eq!(put(0, &g3[..g3.len() / 2]), BAD_LUT);
        assert_eq!(put(0, dfg), BAD_LUT);
        assert_eq!(brdf_lut_error(), 8);
        assert_eq!(brdf_lut_load(0, 300 * 1024), BAD_BUFFER);
        assert_eq!(brdf_lut_load(3, 10), BAD_BUFFER);
        assert_eq!(put(0, b"BLUT"), BAD_LUT);

        assert_eq!(put(2, dfg), OK);
        // SAFETY: the pointers are to live local arrays of the lengths the call states.
        assert_eq!(unsafe { brdf_dfg(0.5, 0.5, ab.as_mut_ptr()) }, OK);
        let (a, b) = DfgTable::parse(dfg).unwrap().ab(0.5, 0.5);
        assert_eq!(ab, [a, b]);
        // Directional albedo with F = 1 is A + B ∈ (0, 1] (docs/conventions.md §8).
        assert!(a + b > 0.5 && a + b <= 1.0, "{a} + {b}");

        // The host rewrites slot 1 without loading: the queries do not trust the bytes.
        let s3: &[u8] = include_bytes!("../../../assets/g_modified_sigma0.3.blut");
        let s5: &[u8] = include_bytes!("../../../assets/g_modified_sigma0.5.blut");
        assert_eq!(s3.len(), s5.len(), "two tables of one length");
        let (t3, t5) = (GTable::parse(s3).unwrap(), GTable::parse(s5).unwrap());
        assert_eq!(put(1, s3), OK);
        assert_eq!(brdf_g_lut_fixed(0.4, -1.1), t3.g(0.4, -1.1));
        // SAFETY: slot 1's buffer is larger than these tables (their `put` above succeeded),
        // and no other reference to it is live during the copy.
        let write = |bytes: &[u8]| unsafe {
            core::ptr::copy_nonoverlapping(bytes.as_ptr(), brdf_lut_ptr(1), bytes.len())
        };
        // Another table of the same length: its CRC-32 field differs, so no table.
        write(s5);
        assert!(brdf_g_lut_fixed(0.4, -1.1).is_nan());
        assert!(brdf_g_lut_fixed_sigma().is_nan());
        // A changed payload under the loaded header is read as it is (no panic): in a
        // payload of zeros every node is the channel's offset, so G = min(GM, GS) is that
        // offset clamped into [0, 1] (whatever the interpolation weights: w · 0 = 0).
        let view = t3.view().unwrap();
        let offset = view.header().channels[0].offset.clamp(0.0, 1.0);
        let mut zero = s3.to_vec();
        zero[view.header_len()..].fill(0);
        write(&zero);
        assert_eq!(brdf_g_lut_fixed(0.4, -1.1), offset);
        // Loading makes the new table the slot's.
        assert_eq!(put(1, s5), OK);
        assert_eq!(brdf_g_lut_fixed_sigma(), 0.5);
        assert_eq!(brdf_g_lut_fixed(0.4, -1.1), t5.g(0.4, -1.1));
        assert_ne!(t3.g(0.4, -1.1), t5.g(0.4, -1.1));
    }
}

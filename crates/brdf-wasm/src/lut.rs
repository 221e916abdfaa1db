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
//! the status-returning ones). Later queries re-read the header without the CRC (the bytes
//! were checked at load), so nothing borrowed outlives a call.

use crate::g::MAX_BATCH;
use crate::memory::{usable, StaticBuf};
use crate::status::{BAD_BUFFER, BAD_LUT, NO_LUT, OK};
use brdf_lut::{DfgTable, GTable, GTable3, LutError, LutView};
use core::sync::atomic::{AtomicU32, Ordering};

static SLOT0: StaticBuf<{ 256 * 1024 }> = StaticBuf::new();
static SLOT1: StaticBuf<{ 64 * 1024 }> = StaticBuf::new();
static SLOT2: StaticBuf<{ 64 * 1024 }> = StaticBuf::new();

/// Validated length per slot; 0 = no table.
static LOADED: [AtomicU32; 3] = [AtomicU32::new(0), AtomicU32::new(0), AtomicU32::new(0)];
/// Reason of the last failed load (see [`brdf_lut_error`]).
static LAST_ERROR: AtomicU32 = AtomicU32::new(0);

fn slot(slot: u32) -> Option<(*mut u8, usize)> {
    match slot {
        0 => Some((SLOT0.ptr(), SLOT0.len())),
        1 => Some((SLOT1.ptr(), SLOT1.len())),
        2 => Some((SLOT2.ptr(), SLOT2.len())),
        _ => None,
    }
}

/// The loaded bytes of a slot, if any.
///
/// # Safety
/// The host must not write the slot while the returned slice is in use (the module is
/// single-threaded, so this holds within one export call).
unsafe fn loaded<'a>(s: u32) -> Option<&'a [u8]> {
    let (p, _) = slot(s)?;
    let n = LOADED.get(s as usize)?.load(Ordering::Relaxed) as usize;
    if n == 0 {
        return None;
    }
    Some(core::slice::from_raw_parts(p, n))
}

/// Checks `bytes` as the table kind of slot `s`.
fn validate(s: u32, bytes: &[u8], crc: bool) -> Result<(), LutError> {
    let view = if crc {
        LutView::parse(bytes)?
    } else {
        LutView::parse_skip_checksum(bytes)?
    };
    match s {
        0 => GTable3::from_view(view).map(|_| ()),
        1 => GTable::from_view(view).map(|_| ()),
        _ => DfgTable::from_view(view).map(|_| ()),
    }
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

/// Validates the first `len` bytes of slot `slot` as that slot's table kind and makes it the
/// slot's table. Returns 0; [`BAD_BUFFER`] for an unknown slot or `len` beyond the capacity;
/// [`BAD_LUT`] when the view rejects the bytes (reason in [`brdf_lut_error`]). On failure the
/// slot has no table.
#[no_mangle]
pub extern "C" fn brdf_lut_load(slot_id: u32, len: u32) -> i32 {
    let Some((p, cap)) = slot(slot_id) else {
        return BAD_BUFFER;
    };
    LOADED[slot_id as usize].store(0, Ordering::Relaxed);
    if len as usize > cap {
        return BAD_BUFFER;
    }
    // SAFETY: `len` ≤ capacity of a static buffer; single-threaded module.
    let bytes = unsafe { core::slice::from_raw_parts(p, len as usize) };
    match validate(slot_id, bytes, true) {
        Ok(()) => {
            LOADED[slot_id as usize].store(len, Ordering::Relaxed);
            LAST_ERROR.store(0, Ordering::Relaxed);
            OK
        }
        Err(e) => {
            LAST_ERROR.store(error_code(e), Ordering::Relaxed);
            BAD_LUT
        }
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
    // SAFETY: used within this call only.
    let bytes = unsafe { loaded(0)? };
    let t = GTable3::from_view(LutView::parse_skip_checksum(bytes).ok()?).ok()?;
    Some(f(&t))
}

fn with_g2<R>(f: impl FnOnce(&GTable<&[u8]>) -> R) -> Option<R> {
    // SAFETY: as above.
    let bytes = unsafe { loaded(1)? };
    let t = GTable::from_view(LutView::parse_skip_checksum(bytes).ok()?).ok()?;
    Some(f(&t))
}

fn with_dfg<R>(f: impl FnOnce(&DfgTable<&[u8]>) -> R) -> Option<R> {
    // SAFETY: as above.
    let bytes = unsafe { loaded(2)? };
    let t = DfgTable::from_view(LutView::parse_skip_checksum(bytes).ok()?).ok()?;
    Some(f(&t))
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
/// Each pointer valid for n f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_g_lut_batch(
    sigma: f32,
    theta_i: *const f32,
    theta_r: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    if n > MAX_BATCH || !usable(theta_i) || !usable(theta_r) || !usable(out.cast_const()) {
        return BAD_BUFFER;
    }
    with_g3(|t| {
        for k in 0..n as usize {
            let v = t.g(*theta_i.add(k), *theta_r.add(k), sigma);
            *out.add(k) = v;
        }
        n as i32
    })
    .unwrap_or(NO_LUT)
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
/// `out` valid for 2 f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_dfg(mu: f32, roughness: f32, out: *mut f32) -> i32 {
    if !usable(out.cast_const()) {
        return BAD_BUFFER;
    }
    with_dfg(|t| {
        let (a, b) = t.ab(mu, roughness);
        *out = a;
        *out.add(1) = b;
        OK
    })
    .unwrap_or(NO_LUT)
}

/// Batch [`brdf_dfg`]: `out` gets n pairs (A, B). Returns n, [`NO_LUT`] or [`BAD_BUFFER`].
///
/// # Safety
/// `mu`, `roughness` valid for n f32, `out` for 2n f32.
#[no_mangle]
pub unsafe extern "C" fn brdf_dfg_batch(
    mu: *const f32,
    roughness: *const f32,
    out: *mut f32,
    n: u32,
) -> i32 {
    if n > MAX_BATCH || !usable(mu) || !usable(roughness) || !usable(out.cast_const()) {
        return BAD_BUFFER;
    }
    with_dfg(|t| {
        for k in 0..n as usize {
            let (a, b) = t.ab(*mu.add(k), *roughness.add(k));
            *out.add(2 * k) = a;
            *out.add(2 * k + 1) = b;
        }
        n as i32
    })
    .unwrap_or(NO_LUT)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn asset(name: &str) -> Vec<u8> {
        let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets")
            .join(name);
        std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
    }

    fn put(s: u32, bytes: &[u8]) -> i32 {
        let cap = brdf_lut_capacity(s) as usize;
        let n = bytes.len().min(cap);
        unsafe { core::ptr::copy_nonoverlapping(bytes.as_ptr(), brdf_lut_ptr(s), n) };
        brdf_lut_load(s, bytes.len() as u32)
    }

    // One test touches the static slots, so parallel tests never share them.
    #[test]
    fn load_query_and_reject() {
        let g3 = asset("g_modified.blut");
        let dfg = asset("dfg_ggx.blut");
        assert!(brdf_g_lut(0.3, 0.5, 0.5).is_nan(), "no table yet");
        let mut ab = [0.0f32; 2];
        assert_eq!(unsafe { brdf_dfg(0.5, 0.5, ab.as_mut_ptr()) }, NO_LUT);

        assert_eq!(put(0, &g3), OK);
        // Against brdf-core's own view over the same bytes, and within the asset's stated
        // accuracy (1e-3) of the direct kernel.
        let t = GTable3::parse(&g3).unwrap();
        let direct = brdf_core::masking::ModifiedG::<f64>::new(0.3).unwrap();
        for (ti, tr) in [(0.5f32, 0.5f32), (0.2, -1.2), (1.4, 1.5)] {
            let v = brdf_g_lut(0.3, ti, tr);
            assert_eq!(v, t.g(ti, tr, 0.3));
            let d = direct.g(ti as f64, tr as f64);
            assert!((v as f64 - d).abs() < 1e-3, "{v} vs direct {d}");
        }
        assert!(brdf_g_lut(f32::NAN, 0.5, 0.5).is_nan());

        // Corruptions: a flipped payload byte (checksum), truncation, wrong kind, too long.
        let mut bad = g3.clone();
        let k = bad.len() - 100;
        bad[k] ^= 0x10;
        assert_eq!(put(0, &bad), BAD_LUT);
        assert_eq!(brdf_lut_error(), 7);
        assert!(
            brdf_g_lut(0.3, 0.5, 0.5).is_nan(),
            "a failed load leaves no table"
        );
        assert_eq!(put(0, &g3[..g3.len() / 2]), BAD_LUT);
        assert_eq!(put(0, &dfg), BAD_LUT);
        assert_eq!(brdf_lut_error(), 8);
        assert_eq!(brdf_lut_load(0, 300 * 1024), BAD_BUFFER);
        assert_eq!(brdf_lut_load(3, 10), BAD_BUFFER);
        assert_eq!(put(0, b"BLUT"), BAD_LUT);

        assert_eq!(put(2, &dfg), OK);
        assert_eq!(unsafe { brdf_dfg(0.5, 0.5, ab.as_mut_ptr()) }, OK);
        let (a, b) = DfgTable::parse(&dfg).unwrap().ab(0.5, 0.5);
        assert_eq!(ab, [a, b]);
        // Directional albedo with F = 1 is A + B ∈ (0, 1] (docs/conventions.md §8).
        assert!(a + b > 0.5 && a + b <= 1.0, "{a} + {b}");
    }
}

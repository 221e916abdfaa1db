//! Fixed static buffers in linear memory (there is no allocator).
//!
//! The host writes inputs into the scratch buffer, passes pointers into it to the array
//! exports and reads the outputs back. The JavaScript wrapper hands out consecutive,
//! 16-byte-aligned regions of it per call.

use crate::status::BAD_BUFFER;
use core::cell::UnsafeCell;

/// Size of the scratch buffer in bytes: a 512 × 512 RGBA image plus 64 KiB for parameters.
pub const SCRATCH_LEN: usize = (1 << 20) + (1 << 16);

/// A byte buffer with a stable address, written only through raw pointers.
#[repr(C, align(16))]
pub struct StaticBuf<const N: usize>(UnsafeCell<[u8; N]>);

// SAFETY: the module is single-threaded; on the host, callers (tests) serialise access
// themselves, and the contents are only reached through raw pointers.
unsafe impl<const N: usize> Sync for StaticBuf<N> {}

impl<const N: usize> core::fmt::Debug for StaticBuf<N> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "StaticBuf<{N}>")
    }
}

impl<const N: usize> StaticBuf<N> {
    /// A zeroed buffer.
    pub const fn new() -> Self {
        Self(UnsafeCell::new([0; N]))
    }
    /// The first byte.
    pub fn ptr(&self) -> *mut u8 {
        self.0.get().cast()
    }
    /// Length in bytes.
    pub const fn len(&self) -> usize {
        N
    }
    /// Always false (N > 0 for every buffer here).
    pub const fn is_empty(&self) -> bool {
        N == 0
    }
}

impl<const N: usize> Default for StaticBuf<N> {
    fn default() -> Self {
        Self::new()
    }
}

static SCRATCH: StaticBuf<SCRATCH_LEN> = StaticBuf::new();

/// Address of the scratch buffer (16-byte aligned).
#[no_mangle]
pub extern "C" fn brdf_scratch_ptr() -> *mut u8 {
    SCRATCH.ptr()
}

/// Length of the scratch buffer in bytes.
#[no_mangle]
pub extern "C" fn brdf_scratch_len() -> u32 {
    SCRATCH_LEN as u32
}

/// `true` when `p` is non-null and aligned for `T` (the arrays the exports take).
pub(crate) fn usable<T>(p: *const T) -> bool {
    !p.is_null() && (p as usize).is_multiple_of(core::mem::align_of::<T>())
}

/// Largest array length the batch exports accept.
pub const MAX_BATCH: u32 = 1 << 24;

/// The buffer check of every batch export: `n` at most [`MAX_BATCH`] and every array
/// [`usable`] (one function, not a copy in each export).
fn batch_ok(n: u32, arrays: &[*const f32]) -> bool {
    n <= MAX_BATCH && arrays.iter().all(|&p| usable(p))
}

/// The frame of every batch export: [`BAD_BUFFER`] unless [`batch_ok`] (checked before
/// anything else, nothing written), else `body`'s status (n, or the export's own negative
/// status).
pub(crate) fn batch(n: u32, arrays: &[*const f32], body: impl FnOnce() -> i32) -> i32 {
    if !batch_ok(n, arrays) {
        return BAD_BUFFER;
    }
    body()
}

/// `out[k] = f(a[k], b[k])` for k < n, each element read before it is written (so `out`
/// may coincide with an input); returns n.
///
/// # Safety
/// `a` and `b` valid for reads and `out` for writes of n f32 ([`batch`] checked the
/// pointers' null and alignment).
pub(crate) unsafe fn map2(
    a: *const f32,
    b: *const f32,
    out: *mut f32,
    n: u32,
    f: impl Fn(f32, f32) -> f32,
) -> i32 {
    for k in 0..n as usize {
        // SAFETY: element k < n is in bounds of each array (the contract).
        unsafe { *out.add(k) = f(*a.add(k), *b.add(k)) };
    }
    n as i32
}

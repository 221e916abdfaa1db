//! # brdf-ffi
//!
//! A stable C ABI over the brdf-core kernels and LUT readers, for firmware and host programs
//! written in C. The header `include/brdf.h` is generated from this crate by cbindgen
//! (`cargo xtask cffi --write-header`; CI regenerates it and fails on any difference).
//!
//! Rules every export follows:
//!
//! * **No panics across the boundary, no allocation.** Bad input gives a [`BrdfStatus`]
//!   code (functions that fill handles or arrays) or NaN (functions that return a value), as
//!   each function documents. On `thumbv7em-none-eabihf` the crate is `no_std` (panic =
//!   abort) with a panic handler that traps; see the handler for what is checked.
//! * **Caller-allocated handles.** A prepared surface or a parsed table lives in a plain
//!   struct of a size the header states ([`BrdfGTable`], …): the caller allocates it (static,
//!   stack, anywhere), an `*_init`/`*_parse` function fills it, queries read it. A handle
//!   carries a tag that only a successful init writes, so a handle that was never filled, or
//!   whose init failed, or that belongs to another type, is refused (NaN or
//!   [`BRDF_STATUS_NOT_INITIALISED`]). Handles may be copied with `memcpy`.
//! * **Borrowed tables.** A table handle points into the caller's byte buffer, which must
//!   stay alive and unchanged while the handle is used (e.g. a `const` array in flash).
//! * **Enums as integers.** Every choice (convention, Fresnel, …) is a `uint32_t` with named
//!   constants, checked on entry: an unknown value is an error, never undefined behaviour.
//! * **Arrays.** Batch functions take caller-owned arrays of `n` elements; a null array with
//!   `n > 0` is [`BRDF_STATUS_NULL_POINTER`]. Outputs may alias inputs (each element is read
//!   before it is written).
//!
//! The Rust functions are also callable from Rust (the xtask recomputes the C program's
//! values through them).
#![cfg_attr(target_os = "none", no_std)]
#![deny(missing_docs)]
#![deny(unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]
#![deny(clippy::missing_safety_doc)]
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// The header expansion (`--cfg brdf_header`) drops the `# Safety` docs, the only users of
// `safety!`.
#![cfg_attr(brdf_header, allow(unused_macros, unused_imports))]

/// The `# Safety` section of an export's documentation, by what the export's pointers must
/// be. It is attached as `#[cfg_attr(not(brdf_header), doc = safety!(..))]`: Rust readers
/// see it, while the C header (generated with `--cfg brdf_header`, see `cargo xtask cffi`)
/// keeps its C-facing text, whose handle and buffer rules (the header's preamble) say the
/// same. Every check the exports make (null pointers, tags, lengths) is in addition to this
/// contract, not a replacement for it.
macro_rules! safety {
    (@handle) => {
        "A handle pointer is null or points to a readable, 8-byte-aligned handle of its type \
         whose bytes are initialised: filled by its init or parse function, or any other \
         bytes (a handle that was never filled is refused by its tag, not read further)."
    };
    (@arrays) => {
        "Each array pointer is null or valid for `n` reads (inputs) or writes (outputs) of \
         its element type; outputs may alias inputs."
    };
    (init) => {
        "\n# Safety\n\n`out` is null or valid for writes of one handle of its type, 8-byte \
         aligned (its previous content does not matter)."
    };
    (query) => {
        concat!("\n# Safety\n\n", $crate::safety!(@handle))
    };
    (batch) => {
        concat!(
            "\n# Safety\n\n",
            $crate::safety!(@handle),
            "\n\n",
            $crate::safety!(@arrays)
        )
    };
    (sample) => {
        concat!(
            $crate::safety!(query),
            " `out` is null or valid for writes of one result struct of its type."
        )
    };
    (parse) => {
        concat!(
            $crate::safety!(init),
            " `bytes` is null or valid for `len` reads, and those bytes stay alive and \
             unchanged for as long as the handle is used."
        )
    };
    (range) => {
        concat!(
            $crate::safety!(query),
            " `lo` and `hi` are each null or valid for writing one `float`."
        )
    };
}
pub(crate) use safety;

pub mod kernels;
pub mod lut;

pub use kernels::*;
pub use lut::*;

/// A status code: `BRDF_STATUS_OK` (0) or one of the `BRDF_STATUS_*` errors.
pub type BrdfStatus = i32;

/// Success.
pub const BRDF_STATUS_OK: BrdfStatus = 0;
/// A required pointer was null (or an array pointer was null with `n > 0`).
pub const BRDF_STATUS_NULL_POINTER: BrdfStatus = 1;
/// A parameter is NaN, infinite, outside its documented range, or an unknown enum value.
pub const BRDF_STATUS_INVALID_ARGUMENT: BrdfStatus = 2;
/// The handle was never initialised, its init failed, or it is a handle of another type.
pub const BRDF_STATUS_NOT_INITIALISED: BrdfStatus = 3;
/// A length does not fit (e.g. larger than the address space allows).
pub const BRDF_STATUS_BAD_LENGTH: BrdfStatus = 4;
/// A sampler found no direction for these inputs (e.g. a viewer at the horizon); the output
/// is not written.
pub const BRDF_STATUS_NO_SAMPLE: BrdfStatus = 5;
/// Table: the buffer ends before the header or payload does.
pub const BRDF_STATUS_TABLE_TRUNCATED: BrdfStatus = 10;
/// Table: not a LUT (the magic bytes are wrong).
pub const BRDF_STATUS_TABLE_BAD_MAGIC: BrdfStatus = 11;
/// Table: a format version this library does not read.
pub const BRDF_STATUS_TABLE_UNSUPPORTED_VERSION: BrdfStatus = 12;
/// Table: the header does not decode.
pub const BRDF_STATUS_TABLE_MALFORMED_HEADER: BrdfStatus = 13;
/// Table: the header decodes but contradicts itself (axes, channels, limits).
pub const BRDF_STATUS_TABLE_INCONSISTENT: BrdfStatus = 14;
/// Table: the payload length differs from what the header implies.
pub const BRDF_STATUS_TABLE_PAYLOAD_LENGTH: BrdfStatus = 15;
/// Table: the CRC-32 does not match (the bytes were corrupted).
pub const BRDF_STATUS_TABLE_CHECKSUM: BrdfStatus = 16;
/// Table: a valid table of another kind than the handle reads.
pub const BRDF_STATUS_TABLE_WRONG_KIND: BrdfStatus = 17;
/// Table: a stored value is not finite or out of the format's range.
pub const BRDF_STATUS_TABLE_BAD_VALUE: BrdfStatus = 18;

/// Version of this ABI; bumped whenever a signature, a handle size or a constant changes.
pub const BRDF_ABI_VERSION: u32 = 1;

/// The ABI version the library was built with (`BRDF_ABI_VERSION`); compare with the
/// header's macro to catch a stale library.
#[no_mangle]
pub extern "C" fn brdf_abi_version() -> u32 {
    BRDF_ABI_VERSION
}

/// A static, NUL-terminated English name of a status code (e.g. `"checksum mismatch"`);
/// `"unknown status"` for any other value. Never null.
#[no_mangle]
pub extern "C" fn brdf_status_str(status: BrdfStatus) -> *const core::ffi::c_char {
    let s: &'static core::ffi::CStr = match status {
        BRDF_STATUS_OK => c"ok",
        BRDF_STATUS_NULL_POINTER => c"null pointer",
        BRDF_STATUS_INVALID_ARGUMENT => c"invalid argument",
        BRDF_STATUS_NOT_INITIALISED => c"handle not initialised",
        BRDF_STATUS_BAD_LENGTH => c"bad length",
        BRDF_STATUS_NO_SAMPLE => c"no sample",
        BRDF_STATUS_TABLE_TRUNCATED => c"table truncated",
        BRDF_STATUS_TABLE_BAD_MAGIC => c"not a table (bad magic)",
        BRDF_STATUS_TABLE_UNSUPPORTED_VERSION => c"unsupported table version",
        BRDF_STATUS_TABLE_MALFORMED_HEADER => c"malformed table header",
        BRDF_STATUS_TABLE_INCONSISTENT => c"inconsistent table header",
        BRDF_STATUS_TABLE_PAYLOAD_LENGTH => c"table payload length mismatch",
        BRDF_STATUS_TABLE_CHECKSUM => c"table checksum mismatch",
        BRDF_STATUS_TABLE_WRONG_KIND => c"table of another kind",
        BRDF_STATUS_TABLE_BAD_VALUE => c"table value not finite or out of range",
        _ => c"unknown status",
    };
    s.as_ptr()
}

/// Compile-time proof that a `T` fits a handle's `W` storage words in size and alignment
/// (evaluated where [`store`] and [`load`] are instantiated).
struct Fits<T, const W: usize>(core::marker::PhantomData<T>);

impl<T, const W: usize> Fits<T, W> {
    const OK: () = {
        assert!(
            core::mem::size_of::<T>() <= 8 * W,
            "handle storage too small"
        );
        assert!(
            core::mem::align_of::<T>() <= 8,
            "handle storage under-aligned"
        );
    };
}

/// Stores `value` in a handle's storage words and then writes `tag`. The tag is cleared
/// first, so a handle is valid only after a complete store.
///
/// # Safety
/// `tag` and `storage` must be valid for writes (they are fields of one handle, 8-byte
/// aligned).
#[inline]
pub(crate) unsafe fn store<T, const W: usize>(
    tag: *mut u64,
    storage: *mut [u64; W],
    value: T,
    t: u64,
) {
    let () = Fits::<T, W>::OK;
    // SAFETY: both pointers are valid for writes (the contract); `T` fits the storage words
    // in size and alignment (`Fits`, checked at compile time).
    unsafe {
        tag.write(0);
        storage.cast::<T>().write(value);
        tag.write(t);
    }
}

/// Reads a handle: `None` for a null pointer or a tag other than `t`.
///
/// # Safety
/// A non-null `tag`/`storage` must point into a live handle that, when its tag equals `t`,
/// was filled by [`store`] with a `T`.
#[inline]
pub(crate) unsafe fn load<'a, T, const W: usize>(
    tag: *const u64,
    storage: *const [u64; W],
    t: u64,
) -> Option<&'a T> {
    let () = Fits::<T, W>::OK;
    // SAFETY: `tag` is non-null (checked first) and points into a live handle (the contract).
    if tag.is_null() || storage.is_null() || unsafe { tag.read() } != t {
        return None;
    }
    // SAFETY: the tag says `store` wrote a `T` there (the contract); `T` fits the storage in
    // size and alignment (`Fits`, checked at compile time).
    Some(unsafe { &*storage.cast::<T>() })
}

/// Defines a handle struct `$h` (its docs, `#[repr(C)]`, a tag word and `$words` storage
/// words) holding a `$inner` under tag `$tag`, with `put`/`get`/`clear`.
macro_rules! handle {
    ($(#[$doc:meta])* $h:ident[$words:ident] = $inner:ty, $tag:expr) => {
        $(#[$doc])*
        #[repr(C)]
        pub struct $h {
            tag: u64,
            storage: [u64; $words],
        }

        impl $h {
            /// The handle's tag and storage fields as raw pointers (nothing is read).
            ///
            /// # Safety
            /// `h` non-null and pointing to a live handle.
            #[inline]
            unsafe fn fields(h: *mut Self) -> (*mut u64, *mut [u64; $words]) {
                // SAFETY: `h` points to a live handle (the contract); no reference is formed.
                unsafe {
                    (
                        core::ptr::addr_of_mut!((*h).tag),
                        core::ptr::addr_of_mut!((*h).storage),
                    )
                }
            }
            /// Stores `v` and then the tag.
            ///
            /// # Safety
            /// `h` non-null and valid for writes.
            #[inline]
            pub(crate) unsafe fn put(h: *mut Self, v: $inner) {
                // SAFETY: `h` is valid for writes (the contract), so are its two fields.
                unsafe {
                    let (tag, storage) = Self::fields(h);
                    $crate::store(tag, storage, v, $tag)
                }
            }
            /// The stored value, `None` for a null handle or a tag other than this type's.
            ///
            /// # Safety
            /// `h` null or pointing to a live, initialised handle.
            #[inline]
            pub(crate) unsafe fn get<'a>(h: *const Self) -> Option<&'a $inner> {
                if h.is_null() {
                    return None;
                }
                // SAFETY: `h` is non-null and points to a live handle (the contract; the
                // fields are only read); only `put` writes this type's tag, after a
                // complete store of `$inner`.
                unsafe {
                    let (tag, storage) = Self::fields(h.cast_mut());
                    $crate::load(tag, storage, $tag)
                }
            }
            /// Clears the tag: the handle is refused until the next `put`.
            ///
            /// # Safety
            /// `h` null or valid for writes.
            #[inline]
            pub(crate) unsafe fn clear(h: *mut Self) {
                if !h.is_null() {
                    // SAFETY: `h` is non-null and valid for writes (the contract).
                    unsafe { Self::fields(h).0.write(0) };
                }
            }
        }
    };
}
pub(crate) use handle;

/// Reads element `i` of a caller array (no reference is formed, so outputs may alias).
///
/// # Safety
/// `p` valid for `i + 1` reads.
#[inline]
pub(crate) unsafe fn rd<T: Copy>(p: *const T, i: usize) -> T {
    // SAFETY: element `i` is in bounds of the caller's array (the contract).
    unsafe { p.add(i).read_unaligned() }
}

/// Writes element `i` of a caller array.
///
/// # Safety
/// `p` valid for `i + 1` writes.
#[inline]
pub(crate) unsafe fn wr<T>(p: *mut T, i: usize, v: T) {
    // SAFETY: element `i` is in bounds of the caller's array (the contract).
    unsafe { p.add(i).write_unaligned(v) }
}

/// Checks the arrays of a batch call: each pointer non-null unless `n == 0`, and `n`
/// elements of `elem` bytes addressable.
#[inline]
pub(crate) fn check_arrays(ptrs: &[bool], n: usize, elem: usize) -> BrdfStatus {
    if n == 0 {
        return BRDF_STATUS_OK;
    }
    if ptrs.iter().any(|&null| null) {
        return BRDF_STATUS_NULL_POINTER;
    }
    if !matches!(n.checked_mul(elem), Some(b) if b <= isize::MAX as usize) {
        return BRDF_STATUS_BAD_LENGTH;
    }
    BRDF_STATUS_OK
}

/// Device builds (`target_os = "none"`): the exports never panic by design (every pointer,
/// length and index is checked, every error is a value), and `cargo xtask cffi` checks that
/// no code of brdf-core or brdf-ffi in the linked C firmware calls into the panic machinery
/// (it lists the bounds checks the optimiser kept elsewhere). Should a panic ever be reached
/// anyway, the core executes a permanently undefined instruction: a HardFault the
/// firmware's fault handler sees, never a silent hang or an unwind into C.
#[cfg(all(target_os = "none", not(test)))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    #[cfg(target_arch = "arm")]
    // SAFETY: UDF only raises the undefined-instruction fault; it touches no state.
    unsafe {
        core::arch::asm!("udf #0", options(noreturn, nomem, nostack))
    }
    #[cfg(not(target_arch = "arm"))]
    loop {
        core::hint::spin_loop();
    }
}

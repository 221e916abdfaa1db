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

/// The tag of a handle type: the eight ASCII bytes `BRDF` and `name` read as a big-endian
/// integer (`tag(*b"MG32")` is 0x4252_4446_4d47_3332), so distinct names give distinct tags.
pub(crate) const fn tag(name: [u8; 4]) -> u64 {
    let [a, b, c, d] = name;
    u64::from_be_bytes([b'B', b'R', b'D', b'F', a, b, c, d])
}

/// The tag of a handle holding `T` values (`f32` or `f64`): `kind` followed by the width of
/// `T` in bits, `32` or `64` (`scalar_tag::<f64>(*b"TS")` is `tag(*b"TS64")`).
pub(crate) const fn scalar_tag<T>(kind: [u8; 2]) -> u64 {
    let [a, b] = kind;
    match core::mem::size_of::<T>() {
        4 => tag([a, b, b'3', b'2']),
        8 => tag([a, b, b'6', b'4']),
        _ => panic!("a handle's scalar is f32 or f64"),
    }
}

/// Defines a handle struct `$h` (its docs, `#[repr(C)]`, a tag word and `$words` storage
/// words) holding a `$inner` under tag `$tag` (a constant: [`tag`] or [`scalar_tag`]), with
/// `put`/`get`/`clear`.
macro_rules! handle {
    ($(#[$doc:meta])* $h:ident[$words:ident] = $inner:ty, $tag:expr) => {
        $(#[$doc])*
        #[repr(C)]
        pub struct $h {
            tag: u64,
            storage: [u64; $words],
        }

        impl $h {
            /// The tag `put` writes last and `get` requires.
            pub(crate) const TAG: u64 = $tag;

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
                    $crate::store(tag, storage, v, Self::TAG)
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
                    $crate::load(tag, storage, Self::TAG)
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

/// The body of every `*_init` and `*_parse` export: refuses a null `out`, clears its tag,
/// builds the value and stores it (the tag is written last, so a failed init leaves the
/// handle refused).
///
/// # Safety
/// `out` is null or valid for writes of one `H`, 8-byte aligned; `clear` and `put` are the
/// handle's own functions, which need exactly that.
#[inline]
pub(crate) unsafe fn init<H, V>(
    out: *mut H,
    clear: unsafe fn(*mut H),
    put: unsafe fn(*mut H, V),
    new: impl FnOnce() -> Result<V, BrdfStatus>,
) -> BrdfStatus {
    if out.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    // SAFETY: `out` is non-null and valid for writes (this function's contract).
    unsafe { clear(out) };
    match new() {
        Ok(v) => {
            // SAFETY: as above.
            unsafe { put(out, v) };
            BRDF_STATUS_OK
        }
        Err(s) => s,
    }
}

/// The caller's arrays of a batch export: `I` inputs and `O` outputs of `n` elements of `T`.
pub(crate) struct Arrays<T, const I: usize, const O: usize> {
    ins: [*const T; I],
    outs: [*mut T; O],
    n: usize,
}

impl<T: Copy, const I: usize, const O: usize> Arrays<T, I, O> {
    /// The arrays of one call (nothing is checked or read here).
    ///
    /// # Safety
    /// Each pointer is null or valid for `n` reads (`ins`) or writes (`outs`) of `T` until
    /// [`Arrays::map`] returns.
    pub(crate) unsafe fn new(ins: [*const T; I], outs: [*mut T; O], n: usize) -> Self {
        Self { ins, outs, n }
    }

    /// The body of every batch export: `BRDF_STATUS_NOT_INITIALISED` for a missing handle,
    /// `BRDF_STATUS_NULL_POINTER` for a null array when `n > 0`, `BRDF_STATUS_BAD_LENGTH`
    /// when `n` elements of `T` are not addressable (writing nothing in each case);
    /// otherwise, for each k < n, element k of the outputs is `f(h, [element k of each
    /// input])`, whose inputs are all read before any output is written (outputs may alias
    /// inputs).
    #[inline]
    pub(crate) fn map<H>(self, h: Option<&H>, f: impl Fn(&H, [T; I]) -> [T; O]) -> BrdfStatus {
        let Some(h) = h else {
            return BRDF_STATUS_NOT_INITIALISED;
        };
        let n = self.n;
        if n == 0 {
            return BRDF_STATUS_OK;
        }
        if self.ins.iter().any(|p| p.is_null()) || self.outs.iter().any(|p| p.is_null()) {
            return BRDF_STATUS_NULL_POINTER;
        }
        if !matches!(n.checked_mul(core::mem::size_of::<T>()), Some(b) if b <= isize::MAX as usize)
        {
            return BRDF_STATUS_BAD_LENGTH;
        }
        for k in 0..n {
            // SAFETY: the arrays are non-null (checked) and hold `n` elements (`new`'s
            // contract).
            let x = self.ins.map(|p| unsafe { rd(p, k) });
            for (&p, y) in self.outs.iter().zip(f(h, x)) {
                // SAFETY: as above.
                unsafe { wr(p, k, y) };
            }
        }
        BRDF_STATUS_OK
    }
}

/// Emits an `*_init` or `*_parse` export (`$safety`: `init` or `parse`, the `# Safety`
/// section [`safety!`] gives it): `$name(out: *mut $h, $arg: $ty, …)` fills `*out` with
/// `$new`, a `Result<_, BrdfStatus>` built from the arguments, through [`init`].
macro_rules! init_export {
    (
        $(#[$doc:meta])*
        $safety:ident $name:ident($h:ty; $($arg:ident: $ty:ty),+ $(,)?) = $new:expr
    ) => {
        $(#[$doc])*
        #[cfg_attr(not(brdf_header), doc = $crate::safety!($safety))]
        #[no_mangle]
        pub unsafe extern "C" fn $name(out: *mut $h, $($arg: $ty),+) -> BrdfStatus {
            // Outside the `unsafe` block below: `$new` is checked as safe code.
            let new = || $new;
            // SAFETY: the caller's contract for `out` is the one `init` needs.
            unsafe { $crate::init(out, <$h>::clear, <$h>::put, new) }
        }
    };
}
pub(crate) use init_export;

/// Emits query exports: each `$name($hv: *const $h, $arg: $ty, …) -> $ret` evaluates `$body`
/// with `$hv` rebound to the handle's value, an `Option<&_>` ([`handle!`]'s `get`: `None` for a
/// null, uninitialised or foreign handle).
macro_rules! query_export {
    ($(
        $(#[$doc:meta])*
        $name:ident($hv:ident: $h:ty $(, $arg:ident: $ty:ty)*) -> $ret:ty = $body:expr;
    )+) => {$(
        $(#[$doc])*
        #[cfg_attr(not(brdf_header), doc = $crate::safety!(query))]
        #[no_mangle]
        pub unsafe extern "C" fn $name($hv: *const $h $(, $arg: $ty)*) -> $ret {
            // SAFETY: the handle is null or readable (the caller's contract).
            let $hv = unsafe { <$h>::get($hv) };
            $body
        }
    )+};
}
pub(crate) use query_export;

/// Emits a batch export `$name($handle: *const $h, $in: *const $t, …, $out: *mut $t, …,
/// n: usize)` whose body is [`Arrays::map`] with `$f`, a closure `|&model, [inputs]| [outputs]`.
macro_rules! batch_export {
    (
        $(#[$doc:meta])*
        $name:ident($handle:ident: $h:ty; $($in:ident),+ => $($out:ident),+: $t:ty) = $f:expr
    ) => {
        $(#[$doc])*
        #[cfg_attr(not(brdf_header), doc = $crate::safety!(batch))]
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            $handle: *const $h,
            $($in: *const $t,)+
            $($out: *mut $t,)+
            n: usize,
        ) -> BrdfStatus {
            // SAFETY: the handle is null or readable (the caller's contract).
            let h = unsafe { <$h>::get($handle) };
            // SAFETY: each array is null or valid for `n` elements (the caller's contract).
            let arrays = unsafe { $crate::Arrays::new([$($in),+], [$($out),+], n) };
            arrays.map(h, $f)
        }
    };
}
pub(crate) use batch_export;

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn handle_tags_spell_brdf_and_their_name_and_all_differ() {
        // ASCII: B 0x42, R 0x52, D 0x44, F 0x46, M 0x4d, G 0x47, 3 0x33, 2 0x32, 6 0x36,
        // 4 0x34, L 0x4c, E 0x45, A 0x41, V 0x56.
        assert_eq!(BrdfModifiedGF32::TAG, 0x4252_4446_4d47_3332);
        assert_eq!(BrdfRoughDielectricF64::TAG, 0x4252_4446_5244_3634);
        assert_eq!(BrdfAverageAlbedoTable::TAG, 0x4252_4446_4c45_4156);
        let tags = [
            BrdfModifiedGF32::TAG,
            BrdfModifiedGF64::TAG,
            BrdfTorranceSparrowF32::TAG,
            BrdfTorranceSparrowF64::TAG,
            BrdfGgxF32::TAG,
            BrdfGgxF64::TAG,
            BrdfSheenF32::TAG,
            BrdfSheenF64::TAG,
            BrdfRoughDielectricF32::TAG,
            BrdfRoughDielectricF64::TAG,
            BrdfGTable::TAG,
            BrdfGTable3::TAG,
            BrdfDfgTable::TAG,
            BrdfAlbedoTable::TAG,
            BrdfAverageAlbedoTable::TAG,
        ];
        for (k, a) in tags.iter().enumerate() {
            assert!(tags[k + 1..].iter().all(|b| b != a), "tag {a:#x} repeats");
            // A zeroed handle must not pass for an initialised one.
            assert_ne!(*a, 0);
        }
    }
}

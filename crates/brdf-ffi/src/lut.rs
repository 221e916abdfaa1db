//! LUT readers: parse a table (format: docs/lut-format.md) from a byte buffer the caller
//! owns into a caller-allocated handle, then query it: the modified G (per σ or over σ), the
//! split-sum (A, B), the directional albedo E(μ, r) and the average albedo E_avg(r), one
//! value at a time or over caller-owned arrays. All in `f32`, like the tables.
//!
//! Parsing validates everything (magic, version, header, sizes, CRC-32) and never reads
//! past `len`; a query never reads outside the payload. Coordinates outside a table's axes
//! (including ±∞) are clamped to the axes' ranges; a NaN coordinate gives NaN.

use crate::kernels::BrdfGTermsF32;
use crate::{
    batch_export, handle, init_export, query_export, tag, BrdfStatus, BRDF_STATUS_BAD_LENGTH,
    BRDF_STATUS_INVALID_ARGUMENT, BRDF_STATUS_NOT_INITIALISED, BRDF_STATUS_NULL_POINTER,
    BRDF_STATUS_OK, BRDF_STATUS_TABLE_BAD_MAGIC, BRDF_STATUS_TABLE_BAD_VALUE,
    BRDF_STATUS_TABLE_CHECKSUM, BRDF_STATUS_TABLE_INCONSISTENT, BRDF_STATUS_TABLE_MALFORMED_HEADER,
    BRDF_STATUS_TABLE_PAYLOAD_LENGTH, BRDF_STATUS_TABLE_TRUNCATED,
    BRDF_STATUS_TABLE_UNSUPPORTED_VERSION, BRDF_STATUS_TABLE_WRONG_KIND,
};
use brdf_lut::{AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, LutError};

/// Storage words (8 bytes each) of every table handle.
pub const BRDF_TABLE_WORDS: usize = 56;

handle! {
    /// A parsed per-σ modified-G table (2-D passing-factor table, reciprocal convention). Fill
    /// it with `brdf_g_table_parse`; the fields are private to the library.
    BrdfGTable[BRDF_TABLE_WORDS] = GTable<&'static [u8]>, tag(*b"LG02")
}

handle! {
    /// A parsed modified-G table over σ (3-D passing-factor table). Fill it with
    /// `brdf_g_table3_parse`; the fields are private to the library.
    BrdfGTable3[BRDF_TABLE_WORDS] = GTable3<&'static [u8]>, tag(*b"LG03")
}

handle! {
    /// A parsed split-sum table (A, B) over (μ, roughness). Fill it with `brdf_dfg_table_parse`;
    /// the fields are private to the library.
    BrdfDfgTable[BRDF_TABLE_WORDS] = DfgTable<&'static [u8]>, tag(*b"LDFG")
}

handle! {
    /// A parsed directional-albedo table E(μ, roughness). Fill it with
    /// `brdf_albedo_table_parse`; the fields are private to the library.
    BrdfAlbedoTable[BRDF_TABLE_WORDS] = AlbedoTable<&'static [u8]>, tag(*b"LE02")
}

handle! {
    /// A parsed average-albedo table E_avg(roughness). Fill it with
    /// `brdf_average_albedo_table_parse`; the fields are private to the library.
    BrdfAverageAlbedoTable[BRDF_TABLE_WORDS] = AverageAlbedoTable<&'static [u8]>, tag(*b"LEAV")
}

/// The split-sum pair: specular E = F0·A + F90·B.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfDfgF32 {
    /// The F0 coefficient A.
    pub a: f32,
    /// The F90 coefficient B.
    pub b: f32,
}

fn status(e: LutError) -> BrdfStatus {
    match e {
        LutError::Truncated => BRDF_STATUS_TABLE_TRUNCATED,
        LutError::BadMagic => BRDF_STATUS_TABLE_BAD_MAGIC,
        LutError::UnsupportedVersion { .. } => BRDF_STATUS_TABLE_UNSUPPORTED_VERSION,
        LutError::MalformedHeader => BRDF_STATUS_TABLE_MALFORMED_HEADER,
        LutError::Inconsistent(_) => BRDF_STATUS_TABLE_INCONSISTENT,
        LutError::PayloadLength { .. } => BRDF_STATUS_TABLE_PAYLOAD_LENGTH,
        LutError::Checksum { .. } => BRDF_STATUS_TABLE_CHECKSUM,
        LutError::WrongKind { .. } => BRDF_STATUS_TABLE_WRONG_KIND,
        LutError::NonCanonical => BRDF_STATUS_TABLE_MALFORMED_HEADER,
        LutError::DegenerateAxis { .. } => BRDF_STATUS_TABLE_INCONSISTENT,
        LutError::BadValue { .. } => BRDF_STATUS_TABLE_BAD_VALUE,
        LutError::BadInput(_) => BRDF_STATUS_INVALID_ARGUMENT,
        // Only the encoder reports this; a reader cannot.
        LutError::BufferTooSmall => BRDF_STATUS_TABLE_MALFORMED_HEADER,
        // `LutError` is non-exhaustive: a reason added by a later brdf-lut is still a table
        // this library cannot read, reported with the generic status of a corrupt header.
        _ => BRDF_STATUS_TABLE_MALFORMED_HEADER,
    }
}

/// `parse` (a brdf-lut reader's constructor) over the caller's buffer of `len` bytes at `p`,
/// with the C status codes: `BRDF_STATUS_NULL_POINTER` (`p` null), `BRDF_STATUS_BAD_LENGTH`
/// (`len` over `isize::MAX`), [`status`] of the reader's error.
///
/// # Safety
/// `p` null or valid for `len` reads for as long as the handle is used.
unsafe fn parse_table<V>(
    p: *const u8,
    len: usize,
    parse: fn(&'static [u8]) -> Result<V, LutError>,
) -> Result<V, BrdfStatus> {
    if p.is_null() {
        return Err(BRDF_STATUS_NULL_POINTER);
    }
    if len > isize::MAX as usize {
        return Err(BRDF_STATUS_BAD_LENGTH);
    }
    // SAFETY: `p` is non-null, `len` fits `isize` (both checked) and `p` is valid for `len`
    // reads for as long as the handle is used (the contract).
    parse(unsafe { core::slice::from_raw_parts(p, len) }).map_err(status)
}

/// GM, GS and G of a table's `terms`; all NaN for `None` (a bad handle).
fn terms(t: Option<(f32, f32, f32)>) -> BrdfGTermsF32 {
    let (gm, gs, g) = t.unwrap_or((f32::NAN, f32::NAN, f32::NAN));
    BrdfGTermsF32 { gm, gs, g }
}

/// Emits a `*_parse` export: `$name(out, bytes, len)` parses a `$table` into the handle `$h`.
macro_rules! parse_export {
    ($(#[$doc:meta])* $name:ident($h:ident) = $table:ident) => {
        init_export! {
            $(#[$doc])*
            parse $name($h; bytes: *const u8, len: usize) =
                // SAFETY: the buffer's contract is the export's.
                unsafe { parse_table(bytes, len, $table::parse) }
        }
    };
}

parse_export! {
    /// Parses a per-σ modified-G table from `len` bytes at `bytes` into `*out`. The bytes are
    /// borrowed, not copied: keep them alive and unchanged while `*out` is used. Returns
    /// `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` (`out` or `bytes` null),
    /// `BRDF_STATUS_BAD_LENGTH`, a `BRDF_STATUS_TABLE_*` code for a corrupt table, or
    /// `BRDF_STATUS_TABLE_WRONG_KIND` for a valid table of another kind; on error `*out` is left
    /// not initialised.
    brdf_g_table_parse(BrdfGTable) = GTable
}

query_export! {
    /// The table's σ; NaN when the header does not record it or the handle is bad.
    brdf_g_table_sigma(t: BrdfGTable) -> f32 =
        t.map_or(f32::NAN, |t| t.sigma());

    /// GM, GS and G = min(GM, GS) ∈ [0, 1] at in-plane angles in radians (θi ∈ [0, π/2],
    /// θr ∈ [−π/2, π/2] signed; clamped), interpolated in the table. All NaN for a NaN angle or a
    /// null or uninitialised handle.
    brdf_g_table_terms(t: BrdfGTable, theta_i: f32, theta_r: f32) -> BrdfGTermsF32 =
        terms(t.map(|t| t.terms(theta_i, theta_r)));

    /// G ∈ [0, 1] from the table; see `brdf_g_table_terms`.
    brdf_g_table_g(t: BrdfGTable, theta_i: f32, theta_r: f32) -> f32 =
        t.map_or(f32::NAN, |t| t.g(theta_i, theta_r));

    /// G ∈ [0, 1] from the dot products n·wi, n·wo, wi·wo of unit vectors (the reciprocal 3-D
    /// extension of the modified G, as `brdf_modified_g_dots_f32`), interpolated in the table.
    /// A direction at or below the horizon gives 0; NaN for a non-finite dot product or a bad
    /// handle.
    brdf_g_table_g_dots(t: BrdfGTable, n_i: f32, n_o: f32, i_o: f32) -> f32 =
        match t {
            Some(t) if n_i.is_finite() && n_o.is_finite() && i_o.is_finite() => t.g_dots(n_i, n_o, i_o),
            _ => f32::NAN,
        };
}

batch_export! {
    /// `out[k] = brdf_g_table_g(t, theta_i[k], theta_r[k])` for k < n. Returns
    /// `BRDF_STATUS_NOT_INITIALISED` (bad handle), `BRDF_STATUS_NULL_POINTER` (an array null with
    /// n > 0), `BRDF_STATUS_BAD_LENGTH` (n too large) — writing nothing — or `BRDF_STATUS_OK`.
    /// `out` may alias an input.
    brdf_g_table_g_batch(t: BrdfGTable; theta_i, theta_r => out: f32) = |t, [ti, tr]| [t.g(ti, tr)]
}

parse_export! {
    /// Parses a modified-G table over σ (3-D); contract as for `brdf_g_table_parse`.
    brdf_g_table3_parse(BrdfGTable3) = GTable3
}

/// Writes the table's σ range to `*lo` and `*hi` (queries outside it are clamped). Returns
/// `BRDF_STATUS_OK`, `BRDF_STATUS_NULL_POINTER` (`lo` or `hi` null) or
/// `BRDF_STATUS_NOT_INITIALISED`.
#[cfg_attr(not(brdf_header), doc = crate::safety!(range))]
#[no_mangle]
pub unsafe extern "C" fn brdf_g_table3_sigma_range(
    t: *const BrdfGTable3,
    lo: *mut f32,
    hi: *mut f32,
) -> BrdfStatus {
    // SAFETY: `t` is null or a readable handle (the caller's contract).
    let Some(t) = (unsafe { BrdfGTable3::get(t) }) else {
        return BRDF_STATUS_NOT_INITIALISED;
    };
    if lo.is_null() || hi.is_null() {
        return BRDF_STATUS_NULL_POINTER;
    }
    let (a, b) = t.sigma_range();
    // SAFETY: both are non-null (checked) and valid for one write (the contract).
    unsafe {
        lo.write_unaligned(a);
        hi.write_unaligned(b);
    }
    BRDF_STATUS_OK
}

query_export! {
    /// GM, GS and G ∈ [0, 1] at in-plane angles (radians, clamped) and RMS slope σ (clamped to
    /// the table's range). All NaN for NaN input or a bad handle.
    brdf_g_table3_terms(t: BrdfGTable3, theta_i: f32, theta_r: f32, sigma: f32) -> BrdfGTermsF32 =
        terms(t.map(|t| t.terms(theta_i, theta_r, sigma)));

    /// G ∈ [0, 1] from the 3-D table; see `brdf_g_table3_terms`.
    brdf_g_table3_g(t: BrdfGTable3, theta_i: f32, theta_r: f32, sigma: f32) -> f32 =
        t.map_or(f32::NAN, |t| t.g(theta_i, theta_r, sigma));

    /// G ∈ [0, 1] from dot products (see `brdf_g_table_g_dots`) at RMS slope σ (clamped to the
    /// table's range); NaN for non-finite input or a bad handle.
    brdf_g_table3_g_dots(t: BrdfGTable3, n_i: f32, n_o: f32, i_o: f32, sigma: f32) -> f32 =
        match t {
            Some(t) if n_i.is_finite() && n_o.is_finite() && i_o.is_finite() && !sigma.is_nan() => {
                t.g_dots(n_i, n_o, i_o, sigma)
            }
            _ => f32::NAN,
        };
}

batch_export! {
    /// `out[k] = brdf_g_table3_g(t, theta_i[k], theta_r[k], sigma[k])` for k < n; status codes
    /// as for `brdf_g_table_g_batch`.
    brdf_g_table3_g_batch(t: BrdfGTable3; theta_i, theta_r, sigma => out: f32) = |t, [ti, tr, s]| [t.g(ti, tr, s)]
}

parse_export! {
    /// Parses a split-sum table; contract as for `brdf_g_table_parse`.
    brdf_dfg_table_parse(BrdfDfgTable) = DfgTable
}

query_export! {
    /// (A, B) at μ = n·v ∈ [0, 1] and roughness (perceptual r for GGX tables, σ for
    /// Torrance–Sparrow tables; the table's header says which), both clamped to the table's
    /// axes. Both NaN for NaN input or a bad handle.
    brdf_dfg_table_ab(t: BrdfDfgTable, mu: f32, roughness: f32) -> BrdfDfgF32 =
        {
            let (a, b) = t.map_or((f32::NAN, f32::NAN), |t| t.ab(mu, roughness));
            BrdfDfgF32 { a, b }
        };
}

batch_export! {
    /// `a_out[k], b_out[k] = brdf_dfg_table_ab(t, mu[k], roughness[k])` for k < n; status codes
    /// as for `brdf_g_table_g_batch`. Outputs may alias inputs (not each other).
    brdf_dfg_table_ab_batch(t: BrdfDfgTable; mu, roughness => a_out, b_out: f32) = |t, [mu, r]| {
        let (a, b) = t.ab(mu, r);
        [a, b]
    }
}

parse_export! {
    /// Parses a directional-albedo table E(μ, r); contract as for `brdf_g_table_parse`.
    brdf_albedo_table_parse(BrdfAlbedoTable) = AlbedoTable
}

query_export! {
    /// E(μ, r) ∈ [0, 1] (F = 1) at μ = n·v and roughness, clamped to the table's axes; NaN for
    /// NaN input or a bad handle.
    brdf_albedo_table_e(t: BrdfAlbedoTable, mu: f32, roughness: f32) -> f32 =
        t.map_or(f32::NAN, |t| t.e(mu, roughness));
}

batch_export! {
    /// `out[k] = brdf_albedo_table_e(t, mu[k], roughness[k])` for k < n; status codes as for
    /// `brdf_g_table_g_batch`.
    brdf_albedo_table_e_batch(t: BrdfAlbedoTable; mu, roughness => out: f32) = |t, [mu, r]| [t.e(mu, r)]
}

parse_export! {
    /// Parses an average-albedo table E_avg(r); contract as for `brdf_g_table_parse`.
    brdf_average_albedo_table_parse(BrdfAverageAlbedoTable) = AverageAlbedoTable
}

query_export! {
    /// E_avg(r) = 2∫₀¹ E(μ, r) μ dμ at roughness r, clamped to the table's axis; NaN for NaN
    /// input or a bad handle.
    brdf_average_albedo_table_e_avg(t: BrdfAverageAlbedoTable, roughness: f32) -> f32 =
        t.map_or(f32::NAN, |t| t.e_avg(roughness));
}

batch_export! {
    /// `out[k] = brdf_average_albedo_table_e_avg(t, roughness[k])` for k < n; status codes as
    /// for `brdf_g_table_g_batch`.
    brdf_average_albedo_table_e_avg_batch(t: BrdfAverageAlbedoTable; roughness => out: f32) = |t, [r]| [t.e_avg(r)]
}

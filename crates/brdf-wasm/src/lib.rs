//! # brdf-wasm
//!
//! The brdf-core kernels as a WebAssembly module with plain C-ABI exports: no wasm-bindgen,
//! no allocator, no imports. Every export takes and returns `f32`/`i32`/`u32` or pointers
//! into the module's linear memory; arrays live in fixed static buffers whose addresses the
//! host asks for ([`memory`]). Built for `wasm32-unknown-unknown` by `cargo xtask wasm`;
//! the JavaScript wrapper is `js/brdf.mjs`.
//!
//! Exports (all names start with `brdf_`):
//!
//! | group | exports |
//! | --- | --- |
//! | memory | `brdf_scratch_ptr`, `brdf_scratch_len` |
//! | G, direct | `brdf_g`, `brdf_g_dots`, `brdf_g_batch`, `brdf_g_dots_batch` ([`g`]) |
//! | models | `brdf_model_count`, `brdf_model_info_ptr/len`, `brdf_eval`, `brdf_eval_batch`, `brdf_torrance_sparrow`, `brdf_torrance_sparrow_nh` ([`models`]) |
//! | G and DFG from LUTs | `brdf_lut_ptr`, `brdf_lut_capacity`, `brdf_lut_load`, `brdf_lut_error`, `brdf_g_lut`, `brdf_g_lut_batch`, `brdf_g_lut_sigma_range`, `brdf_g_lut_fixed`, `brdf_g_lut_fixed_sigma`, `brdf_dfg`, `brdf_dfg_batch` ([`lut`]) |
//! | rendering | `brdf_render_sphere` ([`render`]) |
//!
//! Conventions: angles in radians; in-plane angles as in the paper (θi ∈ [0, π/2],
//! θr ∈ [−π/2, π/2] signed); directions in the local shading frame (z = normal,
//! x = tangent), pointing away from the surface. Invalid parameters (σ ≤ 0, NaN, an unknown
//! model or G kind) give NaN from scalar exports and a negative [`status`] from batch exports;
//! nothing panics.
//!
//! The module is single-threaded: the static buffers are shared by every call.
#![cfg_attr(target_arch = "wasm32", no_std)]
#![deny(missing_debug_implementations)]
#![deny(unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]

pub mod g;
pub mod lut;
pub mod memory;
pub mod models;
pub mod render;
pub mod status;

/// On wasm32 there is no std: a panic (which the exports are written never to reach) traps.
#[cfg(target_arch = "wasm32")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    core::arch::wasm32::unreachable()
}

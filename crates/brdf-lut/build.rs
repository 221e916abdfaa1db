//! Sets the one `cfg` alias of the crate: `hosted` for targets with an operating system
//! other than WebAssembly (not `target_os = "none"`, not `target_family = "wasm"`). The
//! speed paths (forced inlining, the SSE/AVX2 lookups, the batch chunks) are compiled there;
//! bare-metal and WebAssembly builds keep the smaller forms their size budgets were
//! measured with.

fn main() {
    println!("cargo:rustc-check-cfg=cfg(hosted)");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let family = std::env::var("CARGO_CFG_TARGET_FAMILY").unwrap_or_default();
    let wasm = family.split(',').any(|f| f == "wasm");
    if os != "none" && !wasm {
        println!("cargo:rustc-cfg=hosted");
    }
    println!("cargo:rerun-if-changed=build.rs");
}

//! `cargo xtask firmware|wasm|web` (owned by the platforms issue).

#[path = "firmware.rs"]
pub(crate) mod firmware_impl;
pub use firmware_impl::FirmwareArgs;
#[path = "wasm.rs"]
mod wasm_impl;
pub use wasm_impl::WasmArgs;
#[path = "web.rs"]
mod web_impl;
pub use web_impl::WebArgs;

pub fn firmware(a: FirmwareArgs) -> anyhow::Result<()> {
    firmware_impl::run(a)
}
pub fn wasm(a: WasmArgs) -> anyhow::Result<()> {
    wasm_impl::run_cmd(a)
}
pub fn web(a: WebArgs) -> anyhow::Result<()> {
    web_impl::run_cmd(a)
}

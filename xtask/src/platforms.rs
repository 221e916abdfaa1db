//! `cargo xtask firmware|wasm|web` (owned by the platforms issue).

#[derive(clap::Args)]
pub struct FirmwareArgs {}
#[derive(clap::Args)]
pub struct WasmArgs {}
#[derive(clap::Args)]
pub struct WebArgs {}

pub fn firmware(_a: FirmwareArgs) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask firmware` is not implemented yet")
}
pub fn wasm(_a: WasmArgs) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask wasm` is not implemented yet")
}
pub fn web(_a: WebArgs) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask web` is not implemented yet")
}

//! `cargo xtask lut`: LUT generation, verification, inspection, export (owned by the LUT issue).

#[derive(clap::Args)]
pub struct Args {}

pub fn run(_a: Args) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask lut` is not implemented yet")
}

//! `cargo xtask eval brdf` (owned by the models issue).

#[derive(clap::Args)]
pub struct Args {}

pub fn run(_a: Args) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask eval brdf` is not implemented yet")
}

//! `cargo xtask eval dfg` (owned by the LUT issue).

#[derive(clap::Args)]
pub struct Args {}

pub fn run(_a: Args) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask eval dfg` is not implemented yet")
}

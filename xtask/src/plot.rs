//! `cargo xtask plot`: validation figures and report (owned by the validation issue).

#[derive(clap::Args)]
pub struct Args {}

pub fn run(_a: Args) -> anyhow::Result<()> {
    anyhow::bail!("`cargo xtask plot` is not implemented yet")
}

//! `cargo xtask eval <kernel>`: CSV in on stdin, CSV out on stdout.

use clap::Subcommand;

mod g;

#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    what: What,
}

#[derive(Subcommand)]
enum What {
    /// The modified G (GM, GS, G) with Blinn's and Smith's G, from `theta_i_deg,theta_r_deg,sigma` rows.
    G(g::Args),
}

pub fn run(a: Args) -> anyhow::Result<()> {
    match a.what {
        What::G(a) => g::run(a),
    }
}

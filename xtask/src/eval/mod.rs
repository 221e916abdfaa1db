//! `cargo xtask eval <kernel>`: CSV in on stdin, CSV out on stdout.

use clap::Subcommand;

mod brdf;
mod dfg;
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
    /// A BRDF model from `wi_x,wi_y,wi_z,wo_x,wo_y,wo_z` rows (local frame, z = normal).
    Brdf(brdf::Args),
    /// Split-sum (A, B) from `mu,roughness` rows.
    Dfg(dfg::Args),
}

pub fn run(a: Args) -> anyhow::Result<()> {
    match a.what {
        What::G(a) => g::run(a),
        What::Brdf(a) => brdf::run(a),
        What::Dfg(a) => dfg::run(a),
    }
}

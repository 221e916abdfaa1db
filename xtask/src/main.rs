//! `cargo xtask …`: the project's command line (table generation, evaluation for scripting,
//! benchmarks, firmware, plots, CI). Each subcommand lives in its own module.

use clap::{Parser, Subcommand};

mod ci;
mod eval;

#[derive(Parser)]
#[command(name = "cargo xtask", about = "brdf-kernels tasks", version)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Evaluate kernels on CSV rows read from stdin (for scripting).
    Eval(eval::Args),
    /// Everything CI runs: format, clippy, tests, no_std builds (the README's test command).
    Ci(ci::Args),
}

fn main() {
    let cli = Cli::parse();
    let res = match cli.cmd {
        Cmd::Eval(a) => eval::run(a),
        Cmd::Ci(a) => ci::run(a),
    };
    if let Err(e) = res {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

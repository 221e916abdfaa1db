//! `cargo xtask …`: the project's command line (table generation, evaluation for scripting,
//! benchmarks, firmware, plots, CI). The table and evaluation commands live in this crate's
//! modules; the repository's own jobs in their crates, called from here: the target runners
//! in `tools/runners` (brdf-runners), CI, MSRV, packaging and the published LUTs in
//! `tools/maint` (brdf-maint), the benchmark run in `crates/brdf-bench` (`brdf_bench::run`).

use brdf_maint::{anchors, ci, msrv, package};
use brdf_runners::{cffi, firmware, wasm, web};
use clap::{Parser, Subcommand};

mod args;
mod engine;
mod eval;
mod fsio;
mod lut;
mod plot;

#[derive(Parser)]
#[command(name = "cargo xtask", about = "brdf-kernels tasks", version)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Evaluate kernels on CSV rows read from stdin (for scripting).
    #[command(subcommand)]
    Eval(eval::What),
    /// Generate, verify, inspect and export the LUT assets (default: generate the default set).
    Lut(lut::Args),
    /// Run the benchmark suite with short settings and write docs/benchmarks.md.
    Bench(brdf_bench::run::Args),
    /// Build the Cortex-M firmware, run it under QEMU and compare with the host.
    Firmware(firmware::FirmwareArgs),
    /// Check the C header, build the C example for the Cortex-M4F and the host, run both and
    /// compare bit for bit with the host's Rust values.
    Cffi(cffi::Args),
    /// Build the WebAssembly module, optimise it and run the Node tests.
    Wasm(wasm::WasmArgs),
    /// Build the web example and run the headless-browser test.
    Web(web::WebArgs),
    /// Run the validation simulations and write the figures and docs/validation.md.
    Plot(plot::Args),
    /// Fetch the engines' published LUTs into .cache/anchors (pinned SHA-256).
    Anchors(anchors::Args),
    /// Build and test the publishable crates with the toolchain their rust-version declares.
    Msrv(msrv::Args),
    /// Check what publishing needs: warning-free docs and `cargo package` of the publishable
    /// crates (both archives built and compiled on their own).
    Package(package::Args),
    /// Everything CI runs: format, clippy, tests, no_std builds (the README's test command).
    Ci(ci::Args),
}

fn main() {
    let cli = Cli::parse();
    let res = match cli.cmd {
        Cmd::Eval(a) => eval::run(a),
        Cmd::Anchors(a) => anchors::run(a),
        Cmd::Msrv(a) => msrv::run(a),
        Cmd::Package(a) => package::run(a),
        Cmd::Ci(a) => ci::run(a),
        Cmd::Lut(a) => lut::run(a),
        Cmd::Bench(a) => brdf_bench::run::run(a),
        Cmd::Firmware(a) => firmware::run(a),
        Cmd::Wasm(a) => wasm::run(a),
        Cmd::Web(a) => web::run(a),
        Cmd::Cffi(a) => cffi::run(a),
        Cmd::Plot(a) => plot::run(a),
    };
    if let Err(e) = res {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

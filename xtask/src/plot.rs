//! `cargo xtask plot`: runs the validation simulations (crates/brdf-validate) and writes
//! docs/figures/*.svg|png and docs/validation.md.

use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// CI-sized run (fewer samples, σ values and grid points; about 10 s).
    #[arg(long)]
    quick: bool,
    /// Repository root to write docs/ into (default: the workspace root).
    #[arg(long)]
    root: Option<PathBuf>,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    let root = a.root.unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("."))
    });
    let settings = if a.quick {
        brdf_validate::study::Settings::quick()
    } else {
        brdf_validate::study::Settings::default_run()
    };
    let out = brdf_validate::report::run(&root, &settings)?;
    println!(
        "wrote {} and docs/figures/ ({} settings) in {:.1} s",
        root.join("docs/validation.md").display(),
        settings.name,
        out.seconds
    );
    Ok(())
}

//! `cargo xtask plot`: runs the validation simulations (crates/brdf-validate) and writes
//! docs/figures/*.svg|png and docs/validation.md.

use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// CI-sized run (fewer samples, σ values and grid points; about 10 s).
    #[arg(long)]
    quick: bool,
    /// Run the 3-D study instead (2-D random surfaces, issue 25): writes
    /// docs/validation-2d.json, docs/figures/g3_error_*.svg|png and §7 of docs/validation.md.
    /// With --quick: the test-sized run (seconds).
    #[arg(long = "3d")]
    three_d: bool,
    /// Repository root to write docs/ into (default: the workspace root).
    #[arg(long)]
    root: Option<PathBuf>,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    let root = a.root.unwrap_or_else(crate::fsio::workspace_root);
    if a.three_d {
        return run_3d(&root, a.quick);
    }
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

fn run_3d(root: &std::path::Path, quick: bool) -> anyhow::Result<()> {
    let settings = if quick {
        brdf_validate::study2d::Settings2d::quick()
    } else {
        brdf_validate::study2d::Settings2d::default_run()
    };
    let out = brdf_validate::report2d::run(root, &settings)?;
    println!(
        "wrote docs/validation-2d.json, §7 of {} and docs/figures/g3_error_* ({} settings) in {:.1} s wall time",
        root.join("docs/validation.md").display(),
        settings.name,
        out.seconds
    );
    Ok(())
}

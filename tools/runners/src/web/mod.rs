//! `cargo xtask web`: builds the module as `cargo xtask wasm` does (without its Node tests
//! unless asked), installs the page's npm packages when missing (`npm ci` in examples/web:
//! playwright-core only; the browser is Debian's /usr/bin/chromium) and runs the
//! headless-browser test `node --test examples/web/test/`, which writes
//! `examples/web/screenshot.png`. Before it, the khronos engine LUT (64²), its GLSL function
//! and the test points are written to target/lut-engine-web/ for
//! `examples/web/test/lut_engine.test.mjs` (a WebGL2 fragment shader samples the table), and
//! `lut export --raw-f16` of assets/dfg_ggx.blut with its GLSL function and test points to
//! target/lut-engine-web/native/ for the same file's native-export test; the Khronos sheen
//! textures (64²) and the rough-glass 3-D textures (12³, light from outside and from inside)
//! with their test points ([`prepare`]) to
//! target/lut-engine-web/{sheen,glass}/ for `examples/web/test/lut_sheen_glass.test.mjs`.

mod prepare;

use crate::wasm::WasmArgs;
use anyhow::{bail, Result};
use std::process::Command;
use std::time::Instant;

#[derive(clap::Args)]
pub struct WebArgs {
    /// Also run the Node tests of the module first.
    #[arg(long)]
    pub with_node_tests: bool,
}

pub fn run(a: WebArgs) -> Result<()> {
    let root = crate::workspace_root();
    crate::wasm::run(WasmArgs {
        no_test: !a.with_node_tests,
    })?;
    let web = root.join("examples/web");
    if !web.join("node_modules/playwright-core").is_dir() {
        crate::run_in(
            &web,
            Command::new("npm").args(["ci", "--no-audit", "--no-fund"]),
        )?;
    }
    if !std::path::Path::new("/usr/bin/chromium").exists() {
        bail!("/usr/bin/chromium missing: install Debian's chromium (bash .ci/install-web.sh)");
    }
    prepare::prepare(&root.join("target/lut-engine-web"))?;
    prepare::prepare_native(&root.join("target/lut-engine-web/native"))?;
    let t = Instant::now();
    prepare::prepare_sheen(&root.join("target/lut-engine-web/sheen"))?;
    let ts = t.elapsed().as_secs_f64();
    prepare::prepare_glass(&root.join("target/lut-engine-web/glass"))?;
    println!(
        "web: sheen textures and points {ts:.1} s, glass textures and points {:.1} s",
        t.elapsed().as_secs_f64() - ts
    );
    let t = Instant::now();
    crate::run_in(
        &root,
        Command::new("node").args(["--test", "examples/web/test/"]),
    )?;
    println!(
        "web: browser test {:.1} s; screenshot examples/web/screenshot.png",
        t.elapsed().as_secs_f64()
    );
    Ok(())
}

//! Where xtask finds the repository, and its write policy. The safe writes themselves
//! (temporary file + rename, `--force`, no partial files, inputs never overwritten) are the
//! library's: [`brdf_engine_assets::fsio`], re-exported here for the commands.

use std::path::{Path, PathBuf};

use brdf_engine_assets::fsio as lib;

/// [`lib::write_together`]: all files replaced or none.
pub fn write_together(files: &[(PathBuf, Vec<u8>)], policy: &lib::Policy) -> anyhow::Result<()> {
    Ok(lib::write_together(files, policy)?)
}

/// [`lib::check`]: the outputs against the policy, nothing written.
pub fn check(outputs: &[&Path], policy: &lib::Policy) -> anyhow::Result<()> {
    Ok(lib::check(outputs, policy)?)
}

/// [`lib::read_limited`]: a regular file of at most `limit` bytes.
pub fn read_limited(path: &Path, limit: u64) -> anyhow::Result<Vec<u8>> {
    Ok(lib::read_limited(path, limit)?)
}

/// [`lib::load_lut`]: a LUT file, size-capped, the path named once in errors.
pub fn load_lut(path: &Path) -> anyhow::Result<brdf_lut::Lut> {
    Ok(lib::load_lut(path)?)
}

/// The workspace root (the folder that holds `xtask/`): the one place xtask locates the
/// repository from.
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace root")
        .to_path_buf()
}

/// The committed default assets, `assets/` under the workspace root.
pub fn assets_dir() -> PathBuf {
    workspace_root().join("assets")
}

/// The repository's write policy: `Policy::new(force, inputs)` is the library's
/// [`brdf_engine_assets::fsio::Policy`] with the inputs never overwritten, existing outputs
/// replaced only with `force` and `assets/` protected (only the unmodified default set,
/// which builds its own policy, writes there).
pub struct Policy;

impl Policy {
    /// The library policy for a command's outputs (type docs).
    #[allow(clippy::new_ret_no_self)] // a constructor of the library type with xtask's folder
    pub fn new(force: bool, inputs: &[&Path]) -> lib::Policy {
        lib::Policy {
            force,
            inputs: inputs.iter().map(|p| p.to_path_buf()).collect(),
            protected: Some(assets_dir()),
        }
    }
}

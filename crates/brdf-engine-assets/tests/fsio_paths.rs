//! One rule for output paths, as a property of `brdf_engine_assets::fsio`: for generated
//! spellings of an output path (`.`, `..`, symbolic links to folders, folders that do not
//! exist, hard links, absolute paths into a protected folder), [`write_together`] never
//! changes one of the inputs of its [`Policy`] and never writes into the protected folder;
//! every spelling that leads elsewhere is written exactly where the operating system's path
//! resolution leads (a data file and its sidecar, or a single file), and nothing else is
//! created. (`cargo xtask lut export` and `lut generate` pass their `-o`/`--out` and inputs
//! to these calls; `xtask/tests/lut_writes.rs` checks that end to end.)
//!
//! The expected target is computed from the fixture's known layout (which names are
//! folders, which are links to where), not by the library's own resolver.

#![cfg(unix)]

use brdf_engine_assets::fsio::{write_together, Policy};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

const CFG: &str = "kind = \"e-avg\"\nmodel = \"ggx\"\nres = \"4\"\n";
const TABLE: &[u8] = b"an input table";

/// The fixture: `work/` with the inputs `in.blut`, its hard link `hard.blut` and
/// `cfg.toml`; the folder `sub/`; `link` → `sub`; `up` → `work` itself; `alink` → the
/// protected folder `assets/` (beside `work/`, holding `kc_eavg_ggx.blut`).
struct Fixture {
    _root: tempfile::TempDir,
    work: PathBuf,
    assets: PathBuf,
}

fn fixture() -> Fixture {
    let root = tempfile::tempdir().unwrap();
    let work = root.path().canonicalize().unwrap().join("work");
    std::fs::create_dir_all(work.join("sub")).unwrap();
    let assets = work.parent().unwrap().join("assets");
    std::fs::create_dir(&assets).unwrap();
    std::fs::write(assets.join("kc_eavg_ggx.blut"), TABLE).unwrap();
    std::fs::write(work.join("in.blut"), TABLE).unwrap();
    std::fs::hard_link(work.join("in.blut"), work.join("hard.blut")).unwrap();
    std::fs::write(work.join("cfg.toml"), CFG).unwrap();
    std::os::unix::fs::symlink(work.join("sub"), work.join("link")).unwrap();
    std::os::unix::fs::symlink(&work, work.join("up")).unwrap();
    std::os::unix::fs::symlink(&assets, work.join("alink")).unwrap();
    Fixture {
        _root: root,
        work,
        assets,
    }
}

/// Where `spelling` leads in the fixture, by its known layout: links replaced by their
/// targets, `..` applied to the folder reached so far (a folder that does not exist yet is
/// created by the writer, so `missing/..` is where it started).
fn expected(f: &Fixture, spelling: &[String]) -> PathBuf {
    let mut p = f.work.clone();
    let n = spelling.len();
    for (k, c) in spelling.iter().enumerate() {
        match c.as_str() {
            "." => {}
            ".." => {
                p.pop();
            }
            "ASSETS" => p = f.assets.clone(),
            "link" if k + 1 < n && p == f.work => p = f.work.join("sub"),
            "up" if k + 1 < n && p == f.work => p = f.work.clone(),
            "alink" if k + 1 < n && p == f.work => p = f.assets.clone(),
            name => p.push(name),
        }
    }
    p
}

/// Every file under `dir` (not following links) with its bytes' length and modification
/// time.
fn snapshot(dir: &Path) -> Vec<(PathBuf, u64, std::time::SystemTime)> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let m = e.metadata().unwrap();
        if m.is_dir() {
            v.extend(snapshot(&e.path()));
        } else {
            v.push((e.path(), m.len(), m.modified().unwrap()));
        }
    }
    v.sort();
    v
}

/// One of `names`, as a `String`.
fn one_of(names: &'static [&'static str]) -> impl Strategy<Value = String> {
    prop::sample::select(names).prop_map(str::to_string)
}

/// A folder component of a spelling: the fixture's names, `.`, `..` and missing folders.
fn component() -> impl Strategy<Value = String> {
    one_of(&[".", "..", "sub", "link", "up", "alink", "missing", "deeper"])
}

/// The last component: an input, a new name or a file of the protected folder.
fn file_name() -> impl Strategy<Value = String> {
    one_of(&[
        "in.blut",
        "hard.blut",
        "cfg.toml",
        "new.bin",
        "kc_eavg_ggx.blut",
    ])
}

/// A spelling: folders then a file name, sometimes starting at the protected folder.
fn spelling() -> impl Strategy<Value = Vec<String>> {
    (
        prop::bool::weighted(0.1),
        prop::collection::vec(component(), 0..4),
        file_name(),
    )
        .prop_map(|(abs_assets, mut dirs, name)| {
            if abs_assets {
                dirs.insert(0, "ASSETS".into());
            }
            dirs.push(name);
            dirs
        })
}

/// One case: `spelling` (relative to `work/`) written with `force` by the policy of an
/// export (inputs `in.blut`, `hard.blut`; a data file and its `.json` sidecar) or of a table
/// built from `cfg.toml` (input `cfg.toml`; one file), `assets/` protected.
fn run_case(export: bool, spelling: &[String]) -> Result<(), TestCaseError> {
    let f = fixture();
    let target = expected(&f, spelling);
    // Only spellings that stay in the fixture (a `..` out of it would write into /tmp,
    // shared with other tests).
    let root = f.work.parent().unwrap().to_path_buf();
    prop_assume!(target.starts_with(&root));
    let assets_before = snapshot(&f.assets);
    let arg: PathBuf = std::iter::once(f.work.clone())
        .chain(spelling.iter().map(|c| match c.as_str() {
            "ASSETS" => f.assets.clone(),
            c => PathBuf::from(c),
        }))
        .collect();
    let inputs = if export {
        vec![f.work.join("in.blut"), f.work.join("hard.blut")]
    } else {
        vec![f.work.join("cfg.toml")]
    };
    let policy = Policy {
        force: true,
        inputs,
        protected: Some(f.assets.clone()),
    };
    let mut files = vec![(arg.clone(), b"new data".to_vec())];
    if export {
        files.push((
            PathBuf::from(format!("{}.json", arg.display())),
            b"{}".to_vec(),
        ));
    }
    let res = write_together(&files, &policy);
    let msg = res
        .as_ref()
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    // The inputs, whatever happened.
    if export {
        prop_assert_eq!(std::fs::read(f.work.join("in.blut")).unwrap(), TABLE);
        prop_assert_eq!(std::fs::read(f.work.join("hard.blut")).unwrap(), TABLE);
    } else {
        prop_assert_eq!(
            std::fs::read_to_string(f.work.join("cfg.toml")).unwrap(),
            CFG
        );
    }
    // assets/ untouched, whatever happened.
    prop_assert_eq!(snapshot(&f.assets), assets_before, "{}", msg);
    let is_input = policy.inputs.contains(&target);
    let folder_is_file = target.ancestors().skip(1).any(|a| a.is_file());
    if is_input || target.starts_with(&f.assets) || target.is_dir() || folder_is_file {
        prop_assert!(res.is_err(), "{:?} was written", target);
    } else {
        prop_assert!(res.is_ok(), "{:?} -> {:?}: {}", spelling, target, msg);
        prop_assert_eq!(std::fs::read(&target).unwrap(), b"new data");
        if export {
            let side = PathBuf::from(format!("{}.json", target.display()));
            prop_assert_eq!(std::fs::read(&side).unwrap(), b"{}");
        }
    }
    // No folder created that the target does not lie in.
    for name in ["missing", "deeper"] {
        for base in [f.work.clone(), f.work.join("sub")] {
            let made = base.join(name);
            if made.exists() {
                prop_assert!(
                    target.starts_with(&made),
                    "{:?} created for {:?}",
                    made,
                    target
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]
    #[test]
    fn outputs_never_overwrite_inputs_or_protected(export in any::<bool>(), s in spelling()) {
        run_case(export, &s)?;
    }
}

/// The spellings of the issue and the edge cases, always run.
#[test]
fn named_spellings() {
    for (export, s) in [
        (false, "missing/../cfg.toml"),
        (true, "missing/../in.blut"),
        (true, "link/../hard.blut"),
        (true, "up/up/./in.blut"),
        (true, "alink/new.bin"),
        (true, "missing/../alink/new.bin"),
        (true, "link/missing/../../in.blut"),
        (true, "missing/deeper/../../new.bin"),
        (false, "sub/../link/../cfg.toml"),
        (true, "in.blut/new.bin"),
    ] {
        let parts: Vec<String> = s.split('/').map(String::from).collect();
        run_case(export, &parts).unwrap();
    }
}

/// A written file gets the mode `File::create` gives a new file (not a temporary file's
/// 0o600), and a replaced file keeps its own mode.
#[test]
fn written_files_have_the_mode_of_new_files() {
    use std::os::unix::fs::PermissionsExt;
    let d = tempfile::tempdir().unwrap();
    let plain = d.path().join("plain");
    std::fs::File::create(&plain).unwrap();
    let want = std::fs::metadata(&plain).unwrap().permissions().mode() & 0o777;
    let new = d.path().join("new.bin");
    write_together(&[(new.clone(), b"x".to_vec())], &Policy::default()).unwrap();
    let got = std::fs::metadata(&new).unwrap().permissions().mode() & 0o777;
    assert_eq!(got, want, "{got:o} vs {want:o}");
    std::fs::set_permissions(&new, std::fs::Permissions::from_mode(0o640)).unwrap();
    let policy = Policy {
        force: true,
        ..Policy::default()
    };
    write_together(&[(new.clone(), b"y".to_vec())], &policy).unwrap();
    let kept = std::fs::metadata(&new).unwrap().permissions().mode() & 0o777;
    assert_eq!(kept, 0o640, "{kept:o}");
    assert_eq!(std::fs::read(&new).unwrap(), b"y");
}

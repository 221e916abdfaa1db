//! One rule for output paths, as a property: for generated spellings of `--out`/`-o`
//! (relative, `.`, `..`, symbolic links to folders, folders that do not exist, hard links,
//! absolute paths into the committed `assets/`), `lut export` and `lut generate --config`
//! never change one of their inputs and never write into `assets/`; every spelling that
//! leads elsewhere is written exactly where the operating system's path resolution leads,
//! and nothing else is created.
//!
//! The expected target is computed from the fixture's known layout (which names are
//! folders, which are links to where), not by the tool's own resolver.

#![cfg(unix)]

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const CFG: &str = "kind = \"e-avg\"\nmodel = \"ggx\"\nres = \"4\"\n";

/// The fixture: `work/` (the current folder) with the inputs `in.blut`, its hard link
/// `hard.blut` and `cfg.toml`; the folder `sub/`; `link` → `sub`; `up` → `work` itself;
/// `alink` → the committed assets folder.
struct Fixture {
    _root: tempfile::TempDir,
    work: PathBuf,
    assets: PathBuf,
    table: Vec<u8>,
}

fn assets_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .canonicalize()
        .unwrap()
}

fn fixture() -> Fixture {
    let root = tempfile::tempdir().unwrap();
    let work = root.path().canonicalize().unwrap().join("work");
    std::fs::create_dir_all(work.join("sub")).unwrap();
    let assets = assets_dir();
    let table = std::fs::read(assets.join("kc_eavg_ggx.blut")).unwrap();
    std::fs::write(work.join("in.blut"), &table).unwrap();
    std::fs::hard_link(work.join("in.blut"), work.join("hard.blut")).unwrap();
    std::fs::write(work.join("cfg.toml"), CFG).unwrap();
    std::os::unix::fs::symlink(work.join("sub"), work.join("link")).unwrap();
    std::os::unix::fs::symlink(&work, work.join("up")).unwrap();
    std::os::unix::fs::symlink(&assets, work.join("alink")).unwrap();
    Fixture {
        _root: root,
        work,
        assets,
        table,
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

fn component() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(".".to_string()),
        Just("..".to_string()),
        Just("sub".to_string()),
        Just("link".to_string()),
        Just("up".to_string()),
        Just("alink".to_string()),
        Just("missing".to_string()),
        Just("deeper".to_string()),
    ]
}

fn file_name() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("in.blut".to_string()),
        Just("hard.blut".to_string()),
        Just("cfg.toml".to_string()),
        Just("new.bin".to_string()),
        Just("kc_eavg_ggx.blut".to_string()),
    ]
}

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

fn run_case(export: bool, spelling: &[String]) -> Result<(), TestCaseError> {
    let f = fixture();
    let target = expected(&f, spelling);
    // Only spellings that stay in the fixture or lead into assets/ (a `..` out of them
    // would write into the workspace or /tmp, shared with other tests).
    let root = f.work.parent().unwrap().to_path_buf();
    prop_assume!(target.starts_with(&root) || target.starts_with(&f.assets));
    let assets_before = snapshot(&f.assets);
    let arg: PathBuf = spelling
        .iter()
        .map(|c| match c.as_str() {
            "ASSETS" => f.assets.clone(),
            c => PathBuf::from(c),
        })
        .collect();
    let args: Vec<&std::ffi::OsStr> = if export {
        ["lut", "export", "in.blut", "--raw-f32", "--force", "-o"]
            .iter()
            .map(|s| s.as_ref())
            .chain([arg.as_os_str()])
            .collect()
    } else {
        [
            "lut",
            "generate",
            "--config",
            "cfg.toml",
            "--samples",
            "4",
            "--force",
            "--out",
        ]
        .iter()
        .map(|s| s.as_ref())
        .chain([arg.as_os_str()])
        .collect()
    };
    let o = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(&args)
        .current_dir(&f.work)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr).into_owned();
    // The inputs of the command, whatever happened.
    if export {
        prop_assert_eq!(
            std::fs::read(f.work.join("in.blut")).unwrap(),
            f.table.clone()
        );
        prop_assert_eq!(
            std::fs::read(f.work.join("hard.blut")).unwrap(),
            f.table.clone()
        );
    } else {
        prop_assert_eq!(
            std::fs::read_to_string(f.work.join("cfg.toml")).unwrap(),
            CFG
        );
    }
    // assets/ untouched, whatever happened.
    prop_assert_eq!(snapshot(&f.assets), assets_before, "{}", msg);
    let is_input = if export {
        target == f.work.join("in.blut") || target == f.work.join("hard.blut")
    } else {
        target == f.work.join("cfg.toml")
    };
    let folder_is_file = target.ancestors().skip(1).any(|a| a.is_file());
    if is_input || target.starts_with(&f.assets) || target.is_dir() || folder_is_file {
        prop_assert!(!o.status.success(), "{:?} was written", target);
    } else {
        prop_assert!(
            o.status.success(),
            "{:?} -> {:?}: {}",
            spelling,
            target,
            msg
        );
        let bytes = std::fs::read(&target).unwrap();
        if export {
            let side = PathBuf::from(format!("{}.json", target.display()));
            prop_assert!(side.is_file(), "no sidecar {:?}", side);
        } else {
            prop_assert!(brdf_lut::LutView::parse(&bytes).is_ok());
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
    fn outputs_never_overwrite_inputs_or_assets(export in any::<bool>(), s in spelling()) {
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

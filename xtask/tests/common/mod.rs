//! What the end-to-end tests of the `xtask` binary share: running it (with no input, or with
//! input on stdin written from a thread), reading its output, and the committed assets.
//! Each test file uses part of it.
#![allow(dead_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// Runs `xtask args` in `cwd` with stdin closed.
pub fn xtask(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .output()
        .expect("xtask runs")
}

/// Runs `xtask args` with `input` on stdin, written from a thread. The tool may exit before
/// reading everything (a bad argument, or the line cap under test), so write errors (a
/// closed pipe) are ignored: only the exit status and the output are checked.
pub fn xtask_with(args: &[&str], input: impl Iterator<Item = Vec<u8>> + Send + 'static) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("xtask runs");
    let mut stdin = child.stdin.take().expect("piped stdin");
    let writer = std::thread::spawn(move || {
        for chunk in input {
            if stdin.write_all(&chunk).is_err() {
                break;
            }
        }
    });
    let out = child.wait_with_output().expect("xtask output");
    writer.join().expect("stdin writer");
    out
}

/// Runs `xtask args` with the text `input` on stdin.
pub fn xtask_stdin(args: &[&str], input: &str) -> Output {
    xtask_with(args, std::iter::once(input.as_bytes().to_vec()))
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Asserts that the command failed and that its message contains `text`.
pub fn fails_with(o: &Output, text: &str) {
    assert!(!o.status.success(), "expected failure: {}", stderr(o));
    assert!(
        stderr(o).contains(text),
        "wanted `{text}` in: {}",
        stderr(o)
    );
}

/// The committed default assets.
pub fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets")
}

/// The sorted file names in `dir`.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("readable folder")
        .map(|e| {
            e.expect("folder entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    v.sort();
    v
}

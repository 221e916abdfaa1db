//! What the end-to-end tests of the `xtask` binary share: running it (with no input, or with
//! input on stdin written from a thread), reading its output, and the committed assets.
//! Each test file uses part of it.
#![allow(dead_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

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
    let mut child = spawn(
        Command::new(env!("CARGO_BIN_EXE_xtask")).args(args),
        Stdio::piped(),
    );
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

/// Starts `cmd` with the given stdin and its stdout and stderr captured.
pub fn spawn(cmd: &mut Command, stdin: Stdio) -> Child {
    cmd.stdin(stdin)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("xtask starts")
}

/// Runs `cmd` (stdin closed, output captured), killing it once it has run for `limit`;
/// returns its output and how long it ran.
pub fn run_within(cmd: &mut Command, limit: Duration) -> (Output, Duration) {
    let t = Instant::now();
    let mut child = spawn(cmd, Stdio::null());
    while child.try_wait().expect("wait").is_none() {
        if t.elapsed() > limit {
            let _ = child.kill();
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    (child.wait_with_output().expect("output"), t.elapsed())
}

/// Runs `xtask lut export <input> <flags…>` in `cwd`.
pub fn export(input: &str, flags: &[&str], cwd: &Path) -> Output {
    xtask(&[&["lut", "export", input], flags].concat(), cwd)
}

/// Asserts that the command succeeded, showing its message otherwise.
pub fn succeeds(o: &Output) {
    assert!(o.status.success(), "{}", stderr(o));
}

/// The `lut generate` options naming the GGX split-sum table.
pub const GGX_SPLIT_SUM: [&str; 4] = ["--kind", "split-sum", "--model", "ggx"];

/// `lut generate` of a GGX E_avg table with `res` nodes from `samples` points into `out`.
pub fn ggx_e_avg<'a>(res: &'a str, samples: &'a str, out: &'a str) -> [&'a str; 12] {
    [
        "lut",
        "generate",
        "--kind",
        "e-avg",
        "--model",
        "ggx",
        "--res",
        res,
        "--samples",
        samples,
        "--out",
        out,
    ]
}

/// `xtask lut` building the default set's table `only` alone at `res` nodes into `out`.
pub fn default_table<'a>(only: &'a str, res: &'a str, out: &'a str) -> [&'a str; 7] {
    ["lut", "--only", only, "--res", res, "--out", out]
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

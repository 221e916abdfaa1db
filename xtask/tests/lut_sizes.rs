//! One rule for work sizes, as a property (issue 26, item 3): for generated spellings of
//! every number that sizes memory or time on the command line (`--res` of a table built to
//! order and of the default set, `--samples` of `lut generate` and `lut verify`, `--size`
//! of `lut engine`, and a TOML file's node count), the CLI
//!
//! * never panics and never aborts (an exit code other than 101, the panic code, and 134,
//!   an abort; no signal; no "panicked" or "memory allocation" in its output);
//! * exits non-zero with a message naming the limit for every number outside the tool's
//!   limits (`brdf_lut::limits`: nodes per axis 2..=65536, points 1..=200000, engine table
//!   edge 2..=4096), spelled in any integer width, up to numbers wider than u64;
//! * exits non-zero with a message for spellings that are not numbers (empty, negative,
//!   non-ASCII digits, letters);
//! * succeeds on small in-range numbers;
//! * never allocates by the number given: every run is under an address-space limit of
//!   2 GB (`ulimit -v`), far below what the largest spellings would ask for (an
//!   `18446744073709551615 x 4` grid is 2⁶⁶ values), and within 60 s.
//!
//! The expected class of each spelling (in range, over, under, not a number) is decided
//! here from the limits as documented in `cargo xtask lut --help` and docs/lut-format.md,
//! not by the tool's parser.

#![cfg(unix)]

use proptest::prelude::*;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

mod common;

/// The class of a spelled number against a limit lo..=hi.
#[derive(Clone, Debug, PartialEq)]
enum Class {
    /// A small number within the limits.
    Fits,
    /// A whole number (ASCII digits) outside the limits.
    Outside,
    /// Not a whole number.
    NotANumber,
}

/// A spelling and its class.
type Spelt = (String, Class);

/// Spellings of a number limited to lo..=hi: small ones in range (`small`), numbers above
/// hi in every width (just above, u32::MAX, u64::MAX, wider than u64), numbers below lo,
/// and non-numbers (empty, negative, non-ASCII digits, other text without ASCII digits).
fn number(lo: u64, hi: u64, small: std::ops::RangeInclusive<u64>) -> BoxedStrategy<Spelt> {
    let fits = small.prop_map(|n| (n.to_string(), Class::Fits));
    let over = prop_oneof![
        Just(hi + 1),
        (hi + 1..=u32::MAX as u64),
        Just(u32::MAX as u64),
        Just(u32::MAX as u64 + 1),
        (u32::MAX as u64..=u64::MAX),
        Just(u64::MAX),
    ]
    .prop_map(|n| (n.to_string(), Class::Outside));
    let wide = "[1-9][0-9]{20,40}".prop_map(|s| (s, Class::Outside));
    let under = (0..lo).prop_map(|n| (n.to_string(), Class::Outside));
    let zeros = "0{2,5}".prop_map(|s| (s, Class::Outside));
    let not_a_number = prop_oneof![
        Just(String::new()),
        "-[0-9]{1,25}",
        "[٠-٩]{1,4}",
        "[０-９]{1,4}",
        "[a-wyzé ,.]{1,6}",
        Just("1e3".to_string()),
        Just("0x10".to_string()),
        Just("8.5".to_string()),
        Just("-0".to_string()),
    ]
    .prop_map(|s| (s, Class::NotANumber));
    let mut parts = vec![
        fits.boxed(),
        over.boxed(),
        wide.boxed(),
        not_a_number.boxed(),
    ];
    if lo > 0 {
        parts.push(under.boxed());
        parts.push(zeros.boxed());
    }
    proptest::strategy::Union::new(parts).boxed()
}

/// Nodes per axis: 2..=65536 (small: 2..=6).
fn nodes() -> BoxedStrategy<Spelt> {
    number(2, 65536, 2..=6)
}

/// Error-measurement points: 1..=200000 (small: 1..=12).
fn points() -> BoxedStrategy<Spelt> {
    number(1, 200_000, 1..=12)
}

/// Engine table edge: 2..=4096 (small: 2..=6), spellings wider than u64 included.
fn edge() -> BoxedStrategy<Spelt> {
    number(2, 4096, 2..=6)
}

/// The class of a grid spelled `a x b x …`: not a number if any part is not, else outside
/// if any part is, else within the limits.
fn grid(parts: &[Spelt]) -> Spelt {
    let s = parts
        .iter()
        .map(|p| p.0.as_str())
        .collect::<Vec<_>>()
        .join("x");
    let class = if parts.iter().any(|p| p.1 == Class::NotANumber) {
        Class::NotANumber
    } else if parts.iter().any(|p| p.1 == Class::Outside) {
        Class::Outside
    } else {
        Class::Fits
    };
    (s, class)
}

/// `xtask args` in `dir` under a 2 GB address-space limit, killed after 60 s.
fn xtask(args: &[String], dir: &Path) -> (Output, Duration) {
    common::run_within(
        Command::new("sh")
            .arg("-c")
            .arg("ulimit -v 2000000 && exec \"$@\"")
            .arg("sh")
            .arg(env!("CARGO_BIN_EXE_xtask"))
            .args(args)
            .current_dir(dir),
        Duration::from_secs(60),
    )
}

/// The outcome of one spelling: no panic, abort, signal or hang; the class's exit status;
/// for a number outside the limits, one of `limit_texts` in the message.
fn check(
    args: &[String],
    dir: &Path,
    class: &Class,
    limit_texts: &[&str],
) -> Result<(), TestCaseError> {
    let (o, took) = xtask(args, dir);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    let case = format!("{args:?}: {:?} after {took:?}\n{err}", o.status);
    prop_assert!(took < Duration::from_secs(60), "hang: {}", case);
    prop_assert!(o.status.signal().is_none(), "signal: {}", case);
    let code = o.status.code().unwrap_or(-1);
    prop_assert!(code != 101 && code != 134, "panic or abort: {}", case);
    prop_assert!(
        !err.contains("panicked") && !err.contains("memory allocation"),
        "{}",
        case
    );
    match class {
        Class::Fits => prop_assert_eq!(code, 0, "{}", case),
        Class::Outside => {
            prop_assert!(code != 0, "accepted: {}", case);
            prop_assert!(
                limit_texts.iter().any(|t| err.contains(t)),
                "no limit ({:?}) named: {}",
                limit_texts,
                case
            );
        }
        Class::NotANumber => {
            prop_assert!(code != 0, "accepted: {}", case);
            prop_assert!(err.trim().len() > 10, "no message: {}", case);
        }
    }
    Ok(())
}

fn s(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}

/// A scratch folder with a small E_avg table (4 nodes, built here) for `lut verify`.
fn scratch() -> (tempfile::TempDir, PathBuf) {
    let d = tempfile::tempdir().unwrap();
    let args = s(&common::ggx_e_avg("4", "4", "small.blut"));
    let (o, _) = xtask(&args, d.path());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let p = d.path().join("small.blut");
    (d, p)
}

/// A node count outside the limit: the range 2..=65536, or the lower end in words.
const NODES: &[&str] = &["65536", "at least 2 nodes"];
const POINTS: &[&str] = &["200000", "at least 1"];

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, failure_persistence: None, ..ProptestConfig::default() })]

    /// `lut generate --kind split-sum --res AxB` (and a 1-D E_avg table's `--res A`).
    #[test]
    fn res_of_a_table_built_to_order(a in nodes(), b in nodes(), one_d in any::<bool>()) {
        let d = tempfile::tempdir().unwrap();
        let (res, class) = if one_d { grid(&[a]) } else { grid(&[a, b]) };
        let kind = if one_d { "e-avg" } else { "split-sum" };
        let args = s(&["lut", "generate", "--kind", kind, "--model", "ggx", "--samples", "2",
            "--out", "x.blut", "--force"]);
        let args = [args, vec![format!("--res={res}")]].concat();
        check(&args, d.path(), &class, NODES)?;
    }

    /// `lut --only dfg_ggx --res AxB` (the default set's override).
    #[test]
    fn res_of_the_default_set(a in nodes(), b in nodes()) {
        let d = tempfile::tempdir().unwrap();
        let (res, class) = grid(&[a, b]);
        // Only numbers the set refuses: an accepted grid would rebuild the asset with
        // its own (large) error sample.
        prop_assume!(class != Class::Fits);
        let args = [s(&["lut", "--only", "dfg_ggx", "--out", "o"]), vec![format!("--res={res}")]]
            .concat();
        check(&args, d.path(), &class, NODES)?;
    }

    /// `lut generate --samples N` and `lut verify --samples N`.
    #[test]
    fn samples_of_generate_and_verify(n in points()) {
        let (d, table) = scratch();
        let args = [
            s(&["lut", "generate", "--kind", "e-avg", "--model", "ggx", "--res", "3",
                "--out", "y.blut", "--force"]),
            vec![format!("--samples={}", n.0)],
        ]
        .concat();
        check(&args, d.path(), &n.1, POINTS)?;
        let args = [
            // A generous tolerance: the table's recorded error comes from 4 points, the
            // verification's from N others; only the size rule is under test here.
            s(&["lut", "verify", "--tolerance", "1000"]),
            vec![format!("--samples={}", n.0), table.display().to_string()],
        ]
        .concat();
        check(&args, d.path(), &n.1, POINTS)?;
    }

    /// `lut engine khronos --size N`.
    #[test]
    fn size_of_an_engine_table(n in edge()) {
        let d = tempfile::tempdir().unwrap();
        let args = [
            s(&["lut", "engine", "khronos", "--out", "eng", "--force"]),
            vec![format!("--size={}", n.0)],
        ]
        .concat();
        check(&args, d.path(), &n.1, &["4096"])?;
    }

    /// A TOML file's node count (`[axes.roughness] count = N`), for numbers TOML can spell.
    #[test]
    fn node_count_in_a_config_file(n in nodes()) {
        prop_assume!(n.1 != Class::NotANumber && n.0.parse::<i64>().is_ok());
        let d = tempfile::tempdir().unwrap();
        let cfg = format!(
            "kind = \"e-avg\"\nmodel = \"ggx\"\nsamples = 2\n[axes.roughness]\ncount = {}\n",
            n.0.trim_start_matches('0').parse::<u64>().unwrap_or(0)
        );
        std::fs::write(d.path().join("c.toml"), cfg).unwrap();
        let args = s(&["lut", "generate", "--config", "c.toml", "--out", "z.blut"]);
        // Counts beyond u32 are refused by the TOML reader's type (u32) with its own
        // message; within u32 by the limit.
        let texts: &[&str] = if n.0.parse::<u32>().is_ok() { NODES } else { &["u32", "65536"] };
        check(&args, d.path(), &n.1, texts)?;
    }
}

/// The spelling of the issue: `--res 18446744073709551615x4` names the 65536 limit.
#[test]
fn the_issues_spelling_names_the_limit() {
    let d = tempfile::tempdir().unwrap();
    for args in [
        s(&[
            "lut",
            "generate",
            "--kind",
            "split-sum",
            "--model",
            "ggx",
            "--res",
            "18446744073709551615x4",
            "--out",
            "x.blut",
        ]),
        s(&[
            "lut",
            "--only",
            "dfg_ggx",
            "--res",
            "18446744073709551616x4",
            "--out",
            "o",
        ]),
    ] {
        let (o, _) = xtask(&args, d.path());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("2..=65536"), "{args:?}: {err}");
    }
}

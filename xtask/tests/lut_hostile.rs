//! The hostile-user cases of `cargo xtask lut …` (one test per case; each would fail on the
//! code before the fix): sizes beyond the tool's limits, output paths through folders that
//! do not exist, a header that records an unbounded amount of verification work, error
//! statistics that are not numbers, a FIFO as input, and header strings that would reorder
//! the terminal's text. The crafted inputs are built here.

use brdf_lut::{Crc32, Header, LutView};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

mod common;
use common::{
    default_table, export, fails_with, ggx_e_avg, listing, run_within, stderr as err, succeeds,
    xtask, GGX_SPLIT_SUM,
};
use std::process::Command;

fn asset(name: &str) -> PathBuf {
    common::assets().join(name)
}

/// `bytes` (a valid table) with its header replaced by `edit(header)`, re-encoded by the
/// library's encoder (which fills in the CRC and checks the header).
fn reencode<'a>(bytes: &'a [u8], edit: impl FnOnce(&mut Header<'a>)) -> Vec<u8> {
    let v = LutView::parse(bytes).unwrap();
    let mut h = *v.header();
    edit(&mut h);
    let mut out = vec![0u8; bytes.len() + 4096];
    let n = brdf_lut::encode_into(&h, v.payload(), &mut out).unwrap();
    out.truncate(n);
    out
}

/// `bytes` with the first occurrence of `from` replaced by `to` and the CRC recomputed:
/// what a crafted file looks like that the encoder would refuse to write.
fn patch_and_resign(bytes: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    let hl = brdf_lut::header_len(bytes).unwrap();
    let at = bytes[..hl - 4]
        .windows(from.len())
        .position(|w| w == from)
        .expect("pattern in the header");
    let mut d = bytes.to_vec();
    d[at..at + to.len()].copy_from_slice(to);
    let crc = Crc32::new().update(&d[..hl - 4]).update(&d[hl..]).finish();
    d[hl - 4..hl].copy_from_slice(&crc.to_le_bytes());
    d
}

/// Row 1: a sample count or grid beyond the tool's limits is refused with the limit before
/// anything is allocated (it used to abort: "memory allocation of 24000000000 bytes failed").
#[test]
fn sizes_beyond_the_limits_are_refused_before_any_work() {
    let d = tempfile::tempdir().unwrap();
    let base = [
        &["lut", "generate"][..],
        &GGX_SPLIT_SUM,
        &["--out", "x.blut"],
    ]
    .concat();
    for (extra, text) in [
        (
            &["--res", "8x8", "--samples", "1000000000"][..],
            "1..=200000",
        ),
        (&["--res", "8x8", "--samples", "4294967295"], "1..=200000"),
        (&["--res", "8x8", "--samples", "0"], "1..=200000"),
        // 2 channels x 8192 x 4096 = 2^26 values: over the 2^25 limit.
        (&["--res", "8192x4096"], "values"),
        // Within the value limit, far beyond the time budget (2^23 split-sum nodes).
        (
            &["--res", "4096x2048", "--encoding", "f32"],
            "estimated work",
        ),
    ] {
        let t = Instant::now();
        let o = xtask(&[&base[..], extra].concat(), d.path());
        fails_with(&o, text);
        assert!(
            t.elapsed() < Duration::from_secs(30),
            "{extra:?} took {:?}",
            t.elapsed()
        );
    }
    // The same rule for a table read from a TOML file.
    std::fs::write(
        d.path().join("big.toml"),
        "kind = \"e-avg\"\nmodel = \"ggx\"\nres = \"8\"\nsamples = 4294967295\n",
    )
    .unwrap();
    let o = xtask(
        &["lut", "generate", "--config", "big.toml", "--out", "y.blut"],
        d.path(),
    );
    fails_with(&o, "1..=200000");
    // And for the default set's override: --res beyond the format's axis limit.
    let o = xtask(&default_table("dfg_ggx", "70000x8", "o"), d.path());
    fails_with(&o, "nodes per axis");
    assert_eq!(listing(d.path()), ["big.toml"]);
}

/// Row 2: an output that resolves to an input through a folder that does not exist is
/// refused, `--force` or not, and the folder is not created (it used to overwrite cfg.toml).
#[test]
fn output_through_a_missing_folder_never_overwrites_the_config() {
    let d = tempfile::tempdir().unwrap();
    let cfg = "kind = \"e-avg\"\nmodel = \"ggx\"\nres = \"8\"\n";
    std::fs::write(d.path().join("cfg.toml"), cfg).unwrap();
    for out in [
        "nosuch/../cfg.toml",
        "./nosuch/a/../../cfg.toml",
        "cfg.toml",
    ] {
        let o = xtask(
            &[
                "lut",
                "generate",
                "--config",
                "cfg.toml",
                "--out",
                out,
                "--force",
                "--samples",
                "10",
            ],
            d.path(),
        );
        fails_with(&o, "it is the input");
        assert_eq!(
            std::fs::read_to_string(d.path().join("cfg.toml")).unwrap(),
            cfg
        );
        assert_eq!(listing(d.path()), ["cfg.toml"], "{out}");
    }
}

/// Row 3: outputs through a folder that does not exist are written where the path leads
/// (they used to be reported as "named twice among the outputs").
#[test]
fn export_through_a_missing_folder_writes_where_the_path_leads() {
    let d = tempfile::tempdir().unwrap();
    std::fs::copy(asset("kc_eavg_ggx.blut"), d.path().join("in.blut")).unwrap();
    let o = export(
        "in.blut",
        &["--raw-f32", "-o", "nosuch/../out.bin"],
        d.path(),
    );
    succeeds(&o);
    assert_eq!(listing(d.path()), ["in.blut", "out.bin", "out.bin.json"]);
    // The values: the table's nodes as f32 (independently: the parsed view's node values).
    let bytes = std::fs::read(d.path().join("in.blut")).unwrap();
    let v = LutView::parse(&bytes).unwrap();
    let raw = std::fs::read(d.path().join("out.bin")).unwrap();
    let n = v.header().axes[0].count as usize;
    assert_eq!(raw.len(), 4 * n);
    for k in 0..n {
        let x = f32::from_le_bytes(raw[4 * k..4 * k + 4].try_into().unwrap());
        assert_eq!(x.to_bits(), v.node_value(k, 0).to_bits());
    }
}

/// An E_avg table built here (8 nodes), its header then claiming `samples` points.
fn e_avg_table(dir: &Path, samples: u32) -> PathBuf {
    succeeds(&xtask(&ggx_e_avg("8", "16", "e.blut"), dir));
    let bytes = std::fs::read(dir.join("e.blut")).unwrap();
    let p = dir.join(format!("e_{samples}.blut"));
    std::fs::write(&p, reencode(&bytes, |h| h.error.samples = samples)).unwrap();
    p
}

/// Row 4: a header recording 20,000,000 points no longer sets the verification's work: it
/// is capped by the kind's time budget with a note (it used to run for 20–30 minutes).
#[test]
fn verify_work_is_bounded_by_time_not_by_the_header() {
    use brdf_lut::limits;
    let d = tempfile::tempdir().unwrap();
    e_avg_table(d.path(), 20_000_000);
    let t = Instant::now();
    let o = xtask(&["lut", "verify", "e_20000000.blut"], d.path());
    let secs = t.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", err(&o));
    let cap = limits::max_verify_points(
        brdf_lut::TableKind::AverageAlbedo,
        brdf_lut::Model::GgxSmithCorrelated,
    );
    assert!(
        err(&o).contains(&format!("verifying {cap} of the 20000000 recorded points")),
        "{}",
        err(&o)
    );
    // The budget is 20 s of one core; allow for a loaded machine.
    assert!(secs < 120.0, "verify took {secs:.1} s");
    // Asking for more than the budget allows is an error that names the budget.
    let o = xtask(
        &["lut", "verify", "e_20000000.blut", "--samples", "200000"],
        d.path(),
    );
    fails_with(&o, "budget");
}

/// Row 5: error statistics that are not finite and ≥ 0 are refused at parse with a typed
/// error, so `lut verify` fails on them (a NaN maximum used to pass every comparison).
#[test]
fn verify_fails_on_error_statistics_that_are_not_numbers() {
    let d = tempfile::tempdir().unwrap();
    let p = e_avg_table(d.path(), 16);
    // A sentinel maximum to find the field by, then the crafted values in its place.
    let marked = reencode(&std::fs::read(&p).unwrap(), |h| {
        h.error.max_abs = 0.123_456_79;
        h.error.rms = 0.012_345_679;
    });
    let max = 0.123_456_79f32.to_le_bytes();
    let rms = 0.012_345_679f32.to_le_bytes();
    assert!(LutView::parse(&marked).is_ok());
    let cases: [(&[u8; 4], f32); 5] = [
        (&max, f32::NAN),
        (&max, f32::INFINITY),
        (&max, -1e-3),
        (&rms, f32::NAN),
        (&rms, 0.5), // RMS above the maximum
    ];
    for (k, (field, bad)) in cases.iter().enumerate() {
        let bytes = patch_and_resign(&marked, *field, &bad.to_le_bytes());
        assert!(
            matches!(
                LutView::parse(&bytes),
                Err(brdf_lut::LutError::BadErrorStats { .. })
            ),
            "case {k}: {:?}",
            LutView::parse(&bytes).err()
        );
        let name = format!("bad{k}.blut");
        std::fs::write(d.path().join(&name), &bytes).unwrap();
        let o = xtask(&["lut", "verify", &name, "--samples", "10"], d.path());
        fails_with(&o, "error statistics");
        let o = xtask(&["lut", "inspect", &name], d.path());
        fails_with(&o, "error statistics");
    }
}

/// Row 8: a FIFO (or any input that is not a regular file) is refused before it is opened;
/// `open` on a FIFO without a writer used to block forever.
#[test]
#[cfg(unix)]
fn non_regular_inputs_are_refused_without_blocking() {
    let d = tempfile::tempdir().unwrap();
    let ok = Command::new("mkfifo")
        .arg(d.path().join("f"))
        .status()
        .is_ok_and(|s| s.success());
    assert!(ok, "mkfifo failed");
    std::fs::create_dir(d.path().join("dir")).unwrap();
    std::os::unix::fs::symlink(d.path().join("f"), d.path().join("link")).unwrap();
    let cases: [&[&str]; 7] = [
        &["lut", "inspect", "f"],
        &["lut", "inspect", "link"],
        &["lut", "inspect", "/dev/zero"],
        &["lut", "inspect", "dir"],
        &["lut", "verify", "f"],
        &["lut", "export", "f", "--raw-f32", "-o", "x.bin"],
        &["lut", "generate", "--config", "f", "--out", "x.blut"],
    ];
    for args in cases {
        let limit = Duration::from_secs(20);
        let (o, took) = run_within(
            Command::new(env!("CARGO_BIN_EXE_xtask"))
                .args(args)
                .current_dir(d.path()),
            limit,
        );
        assert!(took <= limit, "{args:?} blocked");
        let want = if args.contains(&"dir") {
            "a folder"
        } else {
            "not a regular file"
        };
        fails_with(&o, want);
    }
    assert_eq!(listing(d.path()), ["dir", "f", "link"]);
}

/// Row 9: header strings with bidirectional and other format characters are printed
/// escaped, as control characters are (a right-to-left override used to reach the terminal).
#[test]
fn inspect_escapes_bidi_and_format_characters() {
    let d = tempfile::tempdir().unwrap();
    let p = e_avg_table(d.path(), 16);
    let bytes = std::fs::read(&p).unwrap();
    let tricks = [
        '\u{202E}',
        '\u{202A}',
        '\u{2066}',
        '\u{2069}',
        '\u{200E}',
        '\u{200F}',
        '\u{061C}',
        '\u{200B}',
        '\u{FEFF}',
        '\u{2028}',
        '\u{E0041}',
        '\u{1b}',
    ];
    let name: String = tricks.iter().flat_map(|&c| [c, 'é']).collect();
    let crafted = reencode(&bytes, |h| {
        let mut ch = h.channels[0];
        ch.name = &name;
        h.channels = brdf_lut::List::from_slice(&[ch]).unwrap();
        h.generator.tool = &name;
    });
    std::fs::write(d.path().join("bidi.blut"), &crafted).unwrap();
    let o = xtask(&["lut", "inspect", "bidi.blut"], d.path());
    assert!(o.status.success(), "{}", err(&o));
    let out = String::from_utf8(o.stdout).unwrap();
    for c in tricks {
        assert!(!out.contains(c), "{:?} printed raw in:\n{out}", c);
        let esc = format!("\\u{{{:x}}}", c as u32);
        assert_eq!(
            out.matches(&esc).count(),
            2,
            "{esc} not escaped twice in:\n{out}"
        );
    }
    // Printable non-ASCII stays as it is.
    assert_eq!(out.matches('é').count(), 2 * tricks.len(), "{out}");
}

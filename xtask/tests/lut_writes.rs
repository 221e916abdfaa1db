//! `cargo xtask lut …` never loses a file: the write cases of the command line, end to end.
//! (The temp-file/rename/rollback logic itself is unit-tested with injected faults in
//! `brdf_engine_assets::fsio`, and its path rule is a property test there.)

use std::path::{Path, PathBuf};

mod common;
use common::{assets, default_table, export, fails_with, listing, stderr as err, succeeds, xtask};
use std::process::{Command, Stdio};

/// A small committed table copied into `dir` under `name`.
fn input(dir: &Path, name: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::copy(assets().join("kc_eavg_ggx.blut"), &p).unwrap();
    p
}

#[test]
fn export_never_overwrites_its_input() {
    let d = tempfile::tempdir().unwrap();
    let inp = input(d.path(), "mine.blut");
    let before = std::fs::read(&inp).unwrap();
    for force in [false, true] {
        let mut args = vec!["lut", "export", "mine.blut", "--raw-f16", "-o", "mine.blut"];
        if force {
            args.push("--force");
        }
        let o = xtask(&args, d.path());
        fails_with(&o, "it is the input");
        assert_eq!(std::fs::read(&inp).unwrap(), before);
    }
    // A table named table.png exported with --png16: the default output is the input.
    let png = input(d.path(), "table.png");
    let o = export("table.png", &["--png16"], d.path());
    fails_with(&o, "it is the input");
    assert_eq!(std::fs::read(&png).unwrap(), before);
    assert_eq!(listing(d.path()), ["mine.blut", "table.png"]);
}

#[test]
fn export_defaults_to_the_current_folder_and_needs_force_to_replace() {
    let d = tempfile::tempdir().unwrap();
    let src = assets().join("kc_eavg_ggx.blut");
    let assets_before = listing(&assets());
    let o = export(src.to_str().unwrap(), &["--png16"], d.path());
    succeeds(&o);
    assert_eq!(
        listing(&assets()),
        assets_before,
        "export wrote into assets/"
    );
    assert_eq!(
        listing(d.path()),
        ["kc_eavg_ggx.png", "kc_eavg_ggx.png.json"]
    );
    // The PNG is complete: an independent decoder reads every row (IEND present).
    let dec = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(d.path().join("kc_eavg_ggx.png")).unwrap(),
    ));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size()];
    r.next_frame(&mut buf).unwrap();
    r.finish().unwrap();
    // Existing output: refused without --force, nothing touched.
    std::fs::write(d.path().join("kc_eavg_ggx.png.json"), b"mine").unwrap();
    let o = export(src.to_str().unwrap(), &["--png16"], d.path());
    fails_with(&o, "--force");
    assert_eq!(
        std::fs::read(d.path().join("kc_eavg_ggx.png.json")).unwrap(),
        b"mine"
    );
    let o = export(src.to_str().unwrap(), &["--png16", "--force"], d.path());
    succeeds(&o);
    let side = std::fs::read_to_string(d.path().join("kc_eavg_ggx.png.json")).unwrap();
    assert!(side.contains("\"format\": \"png16\""), "{side}");
    assert_eq!(
        listing(d.path()),
        ["kc_eavg_ggx.png", "kc_eavg_ggx.png.json"]
    );
}

#[test]
fn export_refuses_assets_folder() {
    let d = tempfile::tempdir().unwrap();
    let inp = input(d.path(), "t.blut");
    let target = assets().join("t.f32.bin");
    let o = export(
        inp.to_str().unwrap(),
        &["--raw-f32", "-o", target.to_str().unwrap(), "--force"],
        d.path(),
    );
    fails_with(&o, "committed default tables");
    assert!(!target.exists());
}

#[test]
fn missing_input_named_once() {
    let d = tempfile::tempdir().unwrap();
    let o = export("gone.blut", &["--raw-f32"], d.path());
    assert!(!o.status.success());
    let e = err(&o);
    assert_eq!(e.matches("gone.blut").count(), 1, "{e}");
    assert_eq!(e.matches("os error 2").count(), 1, "{e}");
}

#[test]
fn modified_default_table_never_replaces_the_committed_asset() {
    let d = tempfile::tempdir().unwrap();
    let committed = std::fs::read(assets().join("dfg_ggx.blut")).unwrap();
    let o = xtask(&["lut", "--only", "dfg_ggx", "--res", "32x32"], d.path());
    fails_with(&o, "--out");
    // Naming assets/ explicitly is refused too, --force or not.
    let a = assets();
    let o = xtask(
        &[
            &default_table("kc_eavg_ggx", "4", a.to_str().unwrap())[..],
            &["--force"],
        ]
        .concat(),
        d.path(),
    );
    fails_with(&o, "committed default tables");
    assert_eq!(
        std::fs::read(assets().join("dfg_ggx.blut")).unwrap(),
        committed
    );
    // Elsewhere: written, then refused without --force, replaced with it.
    let out = d.path().join("out");
    let args = default_table("kc_eavg_ggx", "4", out.to_str().unwrap());
    let o = xtask(&args, d.path());
    succeeds(&o);
    assert_eq!(listing(&out), ["kc_eavg_ggx.blut"]);
    let o = xtask(&args, d.path());
    fails_with(&o, "--force");
    let mut forced = args.to_vec();
    forced.push("--force");
    let o = xtask(&forced, d.path());
    succeeds(&o);
    assert_eq!(listing(&out), ["kc_eavg_ggx.blut"]);
}

/// A real full disk (16 KiB tmpfs; needs root, skipped otherwise): the 32 KiB export fails
/// naming its path, and neither a partial data file nor a sidecar is left.
#[test]
#[cfg(target_os = "linux")]
fn export_onto_full_disk_leaves_nothing() {
    let d = tempfile::tempdir().unwrap();
    let mnt = d.path().join("small");
    std::fs::create_dir(&mnt).unwrap();
    let ok = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=16k", "tmpfs"])
        .arg(&mnt)
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        eprintln!("skipped: cannot mount a tmpfs here (needs root)");
        return;
    }
    let src = assets().join("dfg_ggx.blut");
    let o = export(src.to_str().unwrap(), &["--raw-f32", "-o", "t.bin"], &mnt);
    let left = listing(&mnt);
    let _ = Command::new("umount").arg(&mnt).status();
    assert!(!o.status.success());
    let e = err(&o);
    assert!(e.contains("t.bin") && e.contains("No space left"), "{e}");
    assert!(left.is_empty(), "{left:?}");
}

/// `--max-error` on the default set: a 2 x 2 split-sum table (max error ~0.3) fails with a
/// non-zero exit and writes nothing; the same table without the limit is written.
#[test]
fn max_error_fails_an_overridden_default_table() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    let args = default_table("dfg_ggx", "2x2", out.to_str().unwrap());
    let mut strict = args.to_vec();
    strict.extend_from_slice(&["--max-error", "0.01"]);
    let o = xtask(&strict, d.path());
    fails_with(&o, "dfg_ggx.blut");
    assert!(err(&o).contains("exceeds --max-error"), "{}", err(&o));
    assert!(!out.exists() || listing(&out).is_empty());
    let o = xtask(&args, d.path());
    succeeds(&o);
    let lut = brdf_lut::Lut::from_path(out.join("dfg_ggx.blut")).unwrap();
    assert!(lut.header().error.max_abs > 0.01);
}

/// `lut export -o` of a 2-D, 2-channel table writes what the library's export gives, under
/// the documented names: texture, sidecar, GLSL, WGSL and one PNG per channel.
#[test]
fn export_writes_the_librarys_files_under_their_names() {
    use brdf_engine_assets::export::{export as library_export, Format};
    let d = tempfile::tempdir().unwrap();
    let src = assets().join("dfg_ts_smith.blut");
    let o = export(
        src.to_str().unwrap(),
        &["--png16", "-o", "dfg.png"],
        d.path(),
    );
    succeeds(&o);
    let names = [
        "dfg.png",
        "dfg.png.glsl",
        "dfg.png.json",
        "dfg.png.wgsl",
        "dfg_A.png",
        "dfg_B.png",
    ];
    assert_eq!(listing(d.path()), names);
    let lut = brdf_lut::Lut::from_path(&src).unwrap();
    let e = library_export(
        &lut.view().unwrap(),
        Format::Png16,
        "dfg.png",
        "dfg_ts_smith.blut",
    )
    .unwrap();
    let (glsl, wgsl) = e.shaders.unwrap();
    let read = |n: &str| std::fs::read(d.path().join(n)).unwrap();
    assert_eq!(read("dfg.png"), e.texture);
    assert_eq!(read("dfg.png.json"), e.sidecar);
    assert_eq!(read("dfg.png.glsl"), glsl.into_bytes());
    assert_eq!(read("dfg.png.wgsl"), wgsl.into_bytes());
    for (n, b) in &e.single_channel_pngs {
        assert_eq!(&read(n), b, "{n}");
    }
}

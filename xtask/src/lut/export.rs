//! `cargo xtask lut export`: node values as a 16-bit PNG or raw little-endian f16/f32, with
//! a JSON sidecar and sampling shaders, made by `brdf_engine_assets::export`; this file parses
//! the arguments and writes the files.

use anyhow::{anyhow, bail, Result};
use brdf_engine_assets::export::{export, Format};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct ExportArgs {
    /// The LUT file.
    file: PathBuf,
    /// 16-bit PNG (1 channel: grey; 2: R, G with B = 0; 1- or 2-D tables only).
    #[arg(long, group = "fmt")]
    png16: bool,
    /// Raw little-endian IEEE binary16, channels interleaved, axis 0 fastest.
    #[arg(long, group = "fmt")]
    raw_f16: bool,
    /// Raw little-endian IEEE binary32, channels interleaved, axis 0 fastest.
    #[arg(long, group = "fmt")]
    raw_f32: bool,
    /// Output path (default: the input's file name with the format's extension, in the
    /// current folder, never in assets/); the sidecar is `<output>.json`. The input is never
    /// overwritten.
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Replace an existing output and sidecar.
    #[arg(long)]
    force: bool,
}

/// The default output: the input's file name with `ext`, in the current folder.
fn default_out(input: &Path, ext: &str) -> PathBuf {
    let name = input
        .file_name()
        .map(Path::new)
        .unwrap_or(Path::new("table"));
    PathBuf::from(name.with_extension(ext).file_name().unwrap_or_default())
}

/// `p` with `suffix` appended to its last component (`t.bin` → `t.bin.json`), byte for
/// byte (no lossy conversion of a non-UTF-8 name).
fn with_suffix(p: &Path, suffix: &str) -> PathBuf {
    let mut s = p.as_os_str().to_os_string();
    s.push(suffix);
    PathBuf::from(s)
}

/// The format the flags name.
fn format(a: &ExportArgs) -> Result<Format> {
    Ok(if a.png16 {
        Format::Png16
    } else if a.raw_f16 {
        Format::RawF16
    } else if a.raw_f32 {
        Format::RawF32
    } else {
        bail!("choose one of --png16, --raw-f16, --raw-f32");
    })
}

/// The file name of `p`, lossily as text ("" for none).
fn name_of(p: &Path) -> String {
    p.file_name()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned())
}

/// Exports the table (the library's [`brdf_engine_assets::export`]) and writes the texture,
/// its sidecar, shaders and single-channel PNGs together, never over the input.
pub fn run(a: ExportArgs) -> Result<()> {
    let lut = crate::fsio::load_lut(&a.file)?;
    let v = lut.view()?;
    let fmt = format(&a)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| default_out(&a.file, fmt.extension()));
    let (side_path, glsl_path, wgsl_path) = (
        with_suffix(&out, ".json"),
        with_suffix(&out, ".glsl"),
        with_suffix(&out, ".wgsl"),
    );
    let policy = crate::fsio::Policy::new(a.force, &[&a.file]);
    crate::fsio::check(&[&out, &side_path, &glsl_path, &wgsl_path], &policy)?;
    let e = export(&v, fmt, &name_of(&out), &name_of(&a.file)).map_err(|e| anyhow!("{e}"))?;
    let singles: Vec<(PathBuf, Vec<u8>)> = e
        .single_channel_pngs
        .into_iter()
        .map(|(n, b)| (out.with_file_name(n), b))
        .collect();
    let single_paths: Vec<&Path> = singles.iter().map(|(p, _)| p.as_path()).collect();
    crate::fsio::check(&single_paths, &policy)?;
    let mut files = vec![(out.clone(), e.texture), (side_path, e.sidecar)];
    files.extend(singles);
    if let Some((g, w)) = e.shaders {
        files.push((glsl_path, g.into_bytes()));
        files.push((wgsl_path, w.into_bytes()));
    }
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    crate::fsio::write_together(&files, &policy)?;
    println!("wrote {}", names.join(", "));
    Ok(())
}

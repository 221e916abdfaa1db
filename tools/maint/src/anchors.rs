//! `cargo xtask anchors [--check]`: fetches the engines' published split-sum tables, which
//! the comparison tests (`tests/tests/lut_anchors.rs`) read, from the public packages that
//! ship them, into `.cache/anchors/`, and checks each file against a pinned SHA-256.
//!
//! - Khronos glTF Sample Viewer LUTs: npm package `@khronosgroup/gltf-viewer` (`npm pack`).
//! - three.js DFG table: npm package `three`; the 16×16 RG16F table is a `Uint16Array`
//!   literal in `src/nodes/functions/BSDF/DFGLUT.js`, stored here as raw little-endian f16.
//! - Bevy's `dfg.ktx2`: the `bevy_pbr` crate, downloaded from crates.io.
//!
//! Filament's multiscatter table and the legacy glTF-WebGL-PBR `brdfLUT.png` are not in any
//! package registry (they are vendored in the OGRE repository); they stay optional: the
//! tests use them when they are present in `.cache/anchors/` or `../shared/anchors/`, with
//! the pinned hashes below, and say they skip them otherwise.
//!
//! Files already in the cache with the pinned hash are not fetched again. Every file is
//! written through a temporary file and renamed into place.

use anyhow::{bail, Context, Result};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::process::Command;

#[derive(clap::Args)]
pub struct Args {
    /// Only check the files already in `.cache/anchors/`; fetch nothing.
    #[arg(long)]
    check: bool,
}

/// Where a package comes from.
enum Package {
    /// `npm pack <spec>` (an exact version).
    Npm(&'static str),
    /// A crate version downloaded from crates.io.
    Crate {
        name: &'static str,
        version: &'static str,
    },
}

/// How an anchor file is obtained from the unpacked package.
enum Extract {
    /// The file, byte for byte.
    Copy,
    /// The first `Uint16Array([...])` literal of a JavaScript file, as little-endian u16s.
    JsUint16Array { count: usize },
}

struct Anchor {
    /// Path below the anchors directory (the same layout as the tests use).
    rel: &'static str,
    /// Path inside the unpacked package.
    inner: &'static str,
    extract: Extract,
    sha256: &'static str,
}

struct Source {
    package: Package,
    anchors: &'static [Anchor],
}

/// The fetchable anchors and their pinned hashes.
const SOURCES: &[Source] = &[
    Source {
        package: Package::Npm("@khronosgroup/gltf-viewer@1.0.10"),
        anchors: &[
            Anchor {
                rel: "khronos/lut_ggx.png",
                inner: "package/dist/assets/lut_ggx.png",
                extract: Extract::Copy,
                sha256: "94b7fcafe6313206e57c3904501605524581062b370161b5dad05e5d8408efe8",
            },
            Anchor {
                rel: "khronos/lut_charlie.png",
                inner: "package/dist/assets/lut_charlie.png",
                extract: Extract::Copy,
                sha256: "b346fbd8e60ea0eb96006c07dcd0014066df6870c2b0499d10dfc1fb2d6093e8",
            },
            Anchor {
                rel: "khronos/lut_sheen_E.png",
                inner: "package/dist/assets/lut_sheen_E.png",
                extract: Extract::Copy,
                sha256: "7f21d7754dd3a2a972d9d1298ee3e67e20c5b2f21969095d322a1bc20f8b2f04",
            },
        ],
    },
    Source {
        package: Package::Npm("three@0.187.0"),
        anchors: &[Anchor {
            rel: "threejs/three_dfg_lut_16x16_rg16f.bin",
            inner: "package/src/nodes/functions/BSDF/DFGLUT.js",
            extract: Extract::JsUint16Array { count: 16 * 16 * 2 },
            sha256: "b41ba8e2bd29fa007dfbf034d4d58b853f378062183847846b1f6d228f2c7e79",
        }],
    },
    Source {
        package: Package::Crate {
            name: "bevy_pbr",
            version: "0.20.1",
        },
        anchors: &[Anchor {
            rel: "bevy/dfg.ktx2",
            inner: "bevy_pbr-0.20.1/src/environment_map/dfg.ktx2",
            extract: Extract::Copy,
            sha256: "3090e8136a63be266b635f4f3700c5b3daf93a1a9d288699577c1e0c7d194415",
        }],
    },
];

/// Optional anchors (no package ships them): path and pinned hash.
const OPTIONAL: &[(&str, &str)] = &[
    (
        "filament/filament_dfg_multiscatter_64_rgba16f.dds",
        "cdebaafd9cac1e11cd5b84448c63a9056b58b671b352b7b843873cc068c47275",
    ),
    (
        "karis_legacy/brdfLUT_256_rgb8.png",
        "0e34e9d9b573ac90bc40ac0492d76b97eed0c5c591923c4fd75fc92a2628c5ac",
    ),
];

/// Largest package archive accepted (the three.js tarball is ~5 MB).
const MAX_ARCHIVE: u64 = 64 << 20;

fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// True when `path` exists and hashes to `want`.
fn cached_ok(path: &Path, want: &str) -> bool {
    std::fs::read(path).is_ok_and(|b| sha256_hex(&b) == want)
}

pub fn run(a: Args) -> Result<()> {
    let root = crate::workspace_root();
    let cache = root.join(".cache/anchors");
    let mut problems = Vec::new();
    for src in SOURCES {
        let missing: Vec<&Anchor> = src
            .anchors
            .iter()
            .filter(|an| !cached_ok(&cache.join(an.rel), an.sha256))
            .collect();
        if missing.is_empty() {
            for an in src.anchors {
                println!("ok       {} (cached, SHA-256 pinned)", an.rel);
            }
            continue;
        }
        if a.check {
            for an in missing {
                problems.push(format!(
                    "{} is missing or does not match its pinned SHA-256",
                    cache.join(an.rel).display()
                ));
            }
            continue;
        }
        let work = tempdir(&root)?;
        let res = fetch(&src.package, &work).and_then(|dir| {
            for an in &missing {
                let bytes = extract(&dir.join(an.inner), &an.extract)
                    .with_context(|| format!("extracting {} from {}", an.rel, describe(src)))?;
                let got = sha256_hex(&bytes);
                if got != an.sha256 {
                    bail!(
                        "{} from {} has SHA-256 {got}, pinned {}",
                        an.rel,
                        describe(src),
                        an.sha256
                    );
                }
                write_atomic(&cache.join(an.rel), &bytes)?;
                println!("fetched  {} from {}", an.rel, describe(src));
            }
            Ok(())
        });
        let _ = std::fs::remove_dir_all(&work);
        if let Err(e) = res {
            problems.push(format!("{e:#}"));
        }
    }
    for (rel, sha) in OPTIONAL {
        let found = [cache.join(rel), root.join("../shared/anchors").join(rel)]
            .into_iter()
            .find(|p| p.is_file());
        match found {
            Some(p) if cached_ok(&p, sha) => println!("ok       {rel} (optional, {})", p.display()),
            Some(p) => problems.push(format!(
                "{} does not match its pinned SHA-256 {sha}",
                p.display()
            )),
            None => println!(
                "optional {rel}: not in any package registry; the test using it is skipped \
                 unless it is placed in .cache/anchors/ (SHA-256 {sha})"
            ),
        }
    }
    if !problems.is_empty() {
        bail!("anchors:\n  {}", problems.join("\n  "));
    }
    Ok(())
}

fn describe(src: &Source) -> String {
    match src.package {
        Package::Npm(spec) => format!("npm {spec}"),
        Package::Crate { name, version } => format!("crate {name} {version}"),
    }
}

fn tempdir(root: &Path) -> Result<PathBuf> {
    let d = root
        .join(".cache/tmp")
        .join(format!("anchors-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).with_context(|| format!("creating {}", d.display()))?;
    Ok(d)
}

fn run_cmd(cmd: &mut Command, what: &str) -> Result<()> {
    let out = cmd.output().with_context(|| format!("running {what}"))?;
    if !out.status.success() {
        bail!(
            "{what} failed ({}): {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(())
}

/// Downloads and unpacks the package into `work`; returns the unpack directory.
fn fetch(p: &Package, work: &Path) -> Result<PathBuf> {
    let archive = match p {
        Package::Npm(spec) => {
            let out = Command::new("npm")
                .args(["pack", "--silent", spec, "--pack-destination"])
                .arg(work)
                .output()
                .context("running npm pack (is Node.js/npm installed?)")?;
            if !out.status.success() {
                bail!(
                    "npm pack {spec} failed: {}",
                    String::from_utf8_lossy(&out.stderr).trim()
                );
            }
            let name = String::from_utf8_lossy(&out.stdout)
                .lines()
                .last()
                .map(str::trim)
                .filter(|l| !l.is_empty() && !l.contains('/'))
                .with_context(|| format!("npm pack {spec} printed no file name"))?
                .to_string();
            work.join(name)
        }
        Package::Crate { name, version } => {
            let url = format!("https://static.crates.io/crates/{name}/{name}-{version}.crate");
            let dest = work.join(format!("{name}-{version}.crate"));
            run_cmd(
                Command::new("curl")
                    .args(["--fail", "--silent", "--show-error", "--location"])
                    .args(["--max-filesize", &MAX_ARCHIVE.to_string()])
                    .arg("--output")
                    .arg(&dest)
                    .arg(&url),
                &format!("curl {url}"),
            )?;
            dest
        }
    };
    let len = std::fs::metadata(&archive)
        .with_context(|| format!("{} was not written", archive.display()))?
        .len();
    if len > MAX_ARCHIVE {
        bail!(
            "{} is {len} bytes, over the {MAX_ARCHIVE}-byte limit",
            archive.display()
        );
    }
    let dir = work.join("unpacked");
    std::fs::create_dir_all(&dir)?;
    run_cmd(
        Command::new("tar")
            .arg("-xzf")
            .arg(&archive)
            .arg("-C")
            .arg(&dir),
        &format!("tar -xzf {}", archive.display()),
    )?;
    Ok(dir)
}

fn extract(path: &Path, how: &Extract) -> Result<Vec<u8>> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    match how {
        Extract::Copy => Ok(bytes),
        Extract::JsUint16Array { count } => {
            let text = String::from_utf8(bytes).context("the JavaScript file is not UTF-8")?;
            js_uint16_array(&text, *count)
        }
    }
}

/// The values of the first `new Uint16Array( [ … ] )` literal, little-endian; exactly
/// `count` hexadecimal or decimal entries.
fn js_uint16_array(text: &str, count: usize) -> Result<Vec<u8>> {
    let start = text
        .find("Uint16Array(")
        .context("no Uint16Array literal")?;
    let rest = &text[start..];
    let open = rest.find('[').context("Uint16Array without '['")?;
    let close = rest[open..].find(']').context("Uint16Array without ']'")? + open;
    let mut out = Vec::with_capacity(2 * count);
    for tok in rest[open + 1..close]
        .split(',')
        .map(str::trim)
        .filter(|t| !t.is_empty())
    {
        let v = match tok.strip_prefix("0x").or_else(|| tok.strip_prefix("0X")) {
            Some(h) => u16::from_str_radix(h, 16),
            None => tok.parse(),
        }
        .with_context(|| format!("{tok:?} is not a u16"))?;
        if out.len() == 2 * count {
            bail!("Uint16Array has more than {count} entries");
        }
        out.extend_from_slice(&v.to_le_bytes());
    }
    if out.len() != 2 * count {
        bail!(
            "Uint16Array has {} entries, expected {count}",
            out.len() / 2
        );
    }
    Ok(out)
}

fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().context("anchor path without a directory")?;
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let tmp = path.with_extension(format!("tmp-{}", std::process::id()));
    std::fs::write(&tmp, bytes).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("renaming to {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_a_known_string() {
        // FIPS 180-2 appendix B.1 test vector.
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[test]
    fn uint16_array_literal_is_read_little_endian_and_counted() {
        let js = "const DATA = new Uint16Array( [\n\t0x3c00, 0x0001,\n\t258, ] );";
        assert_eq!(
            js_uint16_array(js, 3).unwrap(),
            vec![0x00, 0x3c, 0x01, 0x00, 0x02, 0x01]
        );
        assert!(js_uint16_array(js, 4).is_err());
        assert!(js_uint16_array(js, 2).is_err());
        assert!(js_uint16_array("new Uint16Array([0x10000])", 1).is_err());
        assert!(js_uint16_array("no array here", 1).is_err());
    }
}

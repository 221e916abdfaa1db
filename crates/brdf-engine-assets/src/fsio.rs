//! Writes that never lose a file, and reads that never block or exhaust memory.
//!
//! Every file the command line writes goes through [`write_together`]:
//!
//! - each output is first written to a temporary file in its own folder, flushed and synced,
//!   and only then renamed over the target, so a crash or a full disk leaves the previous file
//!   intact and no partial file behind;
//! - every output path is resolved by one function, [`resolve`] (folders that do not exist
//!   yet, `..`, `.`, symbolic links), and the file is written where it resolves to;
//! - an output that is one of the command's inputs (same path, another spelling of it, a hard
//!   or symbolic link to it: compared by resolved path and by device and inode) is refused,
//!   `force` or not;
//! - an existing output is replaced only with [`Policy::force`];
//! - a protected folder ([`Policy::protected`], e.g. committed assets) is never written;
//! - outputs written together (a data file and its JSON sidecar) succeed or fail together:
//!   all temporaries are written before the first rename, and a failed rename puts every
//!   file already renamed back as it was;
//! - every error is an [`io::Error`] whose message names its path once (refusals have kind
//!   `InvalidInput`, `AlreadyExists` or `PermissionDenied`).
//!
//! ```
//! use brdf_engine_assets::fsio::{write_together, Policy};
//! let dir = tempfile::tempdir().unwrap();
//! let (t, s) = (dir.path().join("t.bin"), dir.path().join("t.bin.json"));
//! write_together(&[(t.clone(), vec![1, 2]), (s, b"{}".to_vec())], &Policy::default()).unwrap();
//! // Replacing needs `force`.
//! let again = write_together(&[(t.clone(), vec![3])], &Policy::default()).unwrap_err();
//! assert_eq!(again.kind(), std::io::ErrorKind::AlreadyExists);
//! assert_eq!(std::fs::read(&t).unwrap(), [1, 2]);
//! ```

use std::io::{self, ErrorKind, Write};
use std::path::{Path, PathBuf};
use tempfile::{NamedTempFile, TempPath};

/// An [`io::Error`] of `kind` with the message `msg`.
fn fail(kind: ErrorKind, msg: String) -> io::Error {
    io::Error::new(kind, msg)
}

/// `e` with `what` (a path, "reading PATH", …) in front, keeping its kind.
fn named(what: impl std::fmt::Display, e: &io::Error) -> io::Error {
    fail(e.kind(), format!("{what}: {e}"))
}

/// What a command may do to existing files and folders.
#[derive(Clone, Debug, Default)]
pub struct Policy {
    /// Replace existing outputs (`--force`).
    pub force: bool,
    /// The command's inputs: never written, whatever `force` says.
    pub inputs: Vec<PathBuf>,
    /// A folder that must not be written (the committed assets), if any.
    pub protected: Option<PathBuf>,
}

/// Fault injection for the tests: the temporary file's writer fails with "no space left on
/// device" after `fail_after_bytes` bytes, or the `fail_rename`-th rename into place (0-based)
/// fails.
#[derive(Clone, Copy, Debug, Default)]
pub struct Faults {
    /// Bytes each temporary file accepts before its writer fails (ENOSPC).
    pub fail_after_bytes: Option<u64>,
    /// The 0-based rename that fails.
    pub fail_rename: Option<usize>,
}

/// A writer that accepts `left` bytes, then fails as a full disk does.
struct FailAfter<W> {
    inner: W,
    left: Option<u64>,
}

impl<W: Write> Write for FailAfter<W> {
    /// Writes up to the remaining allowance, then fails with ENOSPC.
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self.left {
            None => self.inner.write(buf),
            Some(0) => Err(io::Error::from_raw_os_error(28)), // ENOSPC
            Some(n) => {
                let k = buf.len().min(n as usize);
                let w = self.inner.write(&buf[..k])?;
                self.left = Some(n - w as u64);
                Ok(w)
            }
        }
    }
    /// Flushes the inner writer.
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// The folder a path lives in (`.` for a bare file name).
fn folder(p: &Path) -> PathBuf {
    match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The one place an output path is resolved (every write goes through [`check`] and
/// [`write_together`], which call it): the absolute path the file will have, with every
/// symbolic link of its folders resolved, whether or not the file or its folders exist yet.
///
/// The components are walked from the left: the deepest existing prefix is canonicalised;
/// each following component is appended and, while it exists, canonicalised again (so a
/// symbolic link met after a `..` is followed too); `.` is dropped and `..` removes the last
/// component of the path resolved so far, which is a real folder at that point (or one to be
/// created), so this is what the operating system will do once the folders exist. The last
/// component is kept as written (a symbolic link there is replaced, not followed; [`check`]
/// compares with the inputs by device and inode as well). Errors: a path that names no file
/// (ending in `..`, `/` or empty), a dangling symbolic link among the folders, a component
/// that exists but is not a folder, an unreadable folder.
pub fn resolve(p: &Path) -> io::Result<PathBuf> {
    use std::path::Component;
    let name = match p.components().next_back() {
        Some(Component::Normal(n)) => n.to_os_string(),
        _ => {
            return Err(fail(
                ErrorKind::InvalidInput,
                format!("{}: not a file name", p.display()),
            ))
        }
    };
    let folder_of = p.parent().filter(|d| !d.as_os_str().is_empty());
    let start = match folder_of {
        Some(d) if d.is_absolute() => PathBuf::new(),
        _ => std::env::current_dir().map_err(|e| named(p.display(), &e))?,
    };
    let mut out = start.canonicalize().unwrap_or_else(|_| start.to_path_buf());
    for c in folder_of.into_iter().flat_map(Path::components) {
        match c {
            Component::Prefix(_) | Component::RootDir => out = PathBuf::from(c.as_os_str()),
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            Component::Normal(n) => {
                out.push(n);
                out = resolve_existing(p, out)?;
            }
        }
    }
    out.push(name);
    Ok(out)
}

/// One step of [`resolve`]: `out` canonicalised if it exists (and then a folder), as it is
/// if it does not exist yet.
fn resolve_existing(p: &Path, out: PathBuf) -> io::Result<PathBuf> {
    match std::fs::symlink_metadata(&out) {
        Ok(_) => {
            let real = out.canonicalize().map_err(|e| {
                named(
                    format!("{}: {} cannot be resolved", p.display(), out.display()),
                    &e,
                )
            })?;
            if !real.is_dir() {
                let msg = format!("{}: {} is not a folder", p.display(), real.display());
                return Err(fail(ErrorKind::InvalidInput, msg));
            }
            Ok(real)
        }
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(out),
        Err(e) => Err(named(format!("{}: {}", p.display(), out.display()), &e)),
    }
}

/// Opens an input for reading only if it is a regular file (or a link to one): a FIFO, a
/// device or a folder is refused before `open` (which would block on a FIFO without a
/// writer), and the opened file's type is checked again (the path may change in between).
pub fn open_regular(path: &Path) -> io::Result<std::fs::File> {
    let not_regular = |m: &std::fs::Metadata| {
        let what = if m.file_type().is_dir() {
            "a folder"
        } else {
            "not a regular file (a FIFO, socket or device)"
        };
        fail(
            ErrorKind::InvalidInput,
            format!("{} is {what}; give a file", path.display()),
        )
    };
    let reading = |e: io::Error| named(format!("reading {}", path.display()), &e);
    let m = std::fs::metadata(path).map_err(reading)?;
    if !m.is_file() {
        return Err(not_regular(&m));
    }
    let f = std::fs::File::open(path).map_err(reading)?;
    let m = f.metadata().map_err(reading)?;
    if !m.is_file() {
        return Err(not_regular(&m));
    }
    Ok(f)
}

/// Reads an input file whole, refusing files over `limit` bytes before reading them and
/// anything that is not a regular file ([`open_regular`]). The error names the path once.
pub fn read_limited(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    use std::io::Read;
    let f = open_regular(path)?;
    let mut v = Vec::new();
    f.take(limit + 1)
        .read_to_end(&mut v)
        .map_err(|e| named(format!("reading {}", path.display()), &e))?;
    if v.len() as u64 > limit {
        let msg = format!("{} is larger than {limit} bytes", path.display());
        return Err(fail(ErrorKind::InvalidData, msg));
    }
    Ok(v)
}

/// Loads a LUT ([`read_limited`] to [`brdf_lut::MAX_FILE_BYTES`], then
/// [`brdf_lut::Lut::from_bytes`]); the error names the path once and the cause once (a
/// format error has kind `InvalidData`).
pub fn load_lut(path: &Path) -> io::Result<brdf_lut::Lut> {
    let bytes = read_limited(path, brdf_lut::MAX_FILE_BYTES)?;
    brdf_lut::Lut::from_bytes(bytes)
        .map_err(|e| fail(ErrorKind::InvalidData, format!("{}: {e}", path.display())))
}

/// Checks every output against the policy without writing anything (commands call it before
/// long computations, and [`write_together`] calls it again just before writing).
pub fn check(outputs: &[&Path], policy: &Policy) -> io::Result<()> {
    resolve_all(outputs, policy).map(|_| ())
}

/// [`check`], giving the resolved outputs ([`resolve`]) in the same order.
fn resolve_all(outputs: &[&Path], policy: &Policy) -> io::Result<Vec<PathBuf>> {
    // The inputs as the outputs are resolved (an input that cannot be resolved is still
    // compared by device and inode).
    let inputs: Vec<(&PathBuf, Option<PathBuf>)> =
        policy.inputs.iter().map(|i| (i, resolve(i).ok())).collect();
    let prot = policy
        .protected
        .as_ref()
        .and_then(|p| p.canonicalize().ok());
    let mut done: Vec<PathBuf> = Vec::with_capacity(outputs.len());
    for out in outputs {
        let abs = resolve(out)?;
        if done.contains(&abs) {
            let msg = format!("{} is named twice among the outputs", out.display());
            return Err(fail(ErrorKind::InvalidInput, msg));
        }
        check_one(out, &abs, &inputs, prot.as_deref(), policy.force)?;
        done.push(abs);
    }
    Ok(done)
}

/// One output `out` (resolved: `abs`) against the inputs, the protected folder and what
/// exists there.
fn check_one(
    out: &Path,
    abs: &Path,
    inputs: &[(&PathBuf, Option<PathBuf>)],
    prot: Option<&Path>,
    force: bool,
) -> io::Result<()> {
    for (inp, inp_abs) in inputs {
        // Same path, or the same file by (device, inode): hard and symbolic links.
        let same =
            inp_abs.as_deref() == Some(abs) || same_file::is_same_file(abs, inp).unwrap_or(false);
        if same {
            let msg = format!(
                "refusing to write {}: it is the input {} (choose another output path)",
                out.display(),
                inp.display()
            );
            return Err(fail(ErrorKind::InvalidInput, msg));
        }
    }
    if let Some(prot) = prot.filter(|p| abs.starts_with(p)) {
        let msg = format!(
            "refusing to write {}: {} holds the committed default tables, which only \
             `cargo xtask lut` (the default set, unmodified) regenerates; choose another \
             output folder",
            out.display(),
            prot.display()
        );
        return Err(fail(ErrorKind::PermissionDenied, msg));
    }
    let shown = out.display();
    match std::fs::symlink_metadata(abs) {
        // A folder, or a link to one (a link is replaced, never followed, by the rename).
        Ok(m) if m.is_dir() || abs.is_dir() => Err(fail(
            ErrorKind::InvalidInput,
            format!("{shown} is a folder"),
        )),
        Ok(_) if !force => Err(fail(
            ErrorKind::AlreadyExists,
            format!("{shown} exists; pass --force to replace it"),
        )),
        Ok(_) => Ok(()),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(()),
        Err(e) => Err(named(shown, &e)),
    }
}

/// Writes `files` (path, bytes) so that all of them are replaced or none is (module docs).
pub fn write_together(files: &[(PathBuf, Vec<u8>)], policy: &Policy) -> io::Result<()> {
    write_with_faults(files, policy, Faults::default())
}

/// Replaces a generated file (a report, a build product) atomically: temp file, sync, rename.
pub fn replace(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let policy = Policy {
        force: true,
        ..Policy::default()
    };
    write_together(&[(path.to_path_buf(), bytes.to_vec())], &policy)
}

/// Writes `bytes` to a synced temporary file in the folder of `target` (created if
/// missing); errors name `shown`, the path as given.
fn write_temp(
    shown: &Path,
    target: &Path,
    bytes: &[u8],
    faults: Faults,
) -> io::Result<NamedTempFile> {
    let dir = folder(target);
    std::fs::create_dir_all(&dir).map_err(|e| named(format!("creating {}", dir.display()), &e))?;
    let writing = |e: io::Error| named(format!("writing {}", shown.display()), &e);
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    let prefix = format!(".{name}.");
    let mut b = tempfile::Builder::new();
    b.prefix(&prefix).suffix(".tmp");
    // The mode `File::create` gives (0o666 less the umask), not the temporary file's
    // default 0o600: a written asset is as readable as any other new file.
    #[cfg(unix)]
    b.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let tmp = b.tempfile_in(&dir).map_err(writing)?;
    let mut w = FailAfter {
        inner: io::BufWriter::new(tmp.as_file()),
        left: faults.fail_after_bytes,
    };
    w.write_all(bytes)
        .and_then(|_| w.flush())
        .and_then(|_| tmp.as_file().sync_all())
        .map_err(writing)?;
    drop(w);
    Ok(tmp)
}

/// [`write_together`] with injected faults (tests).
pub fn write_with_faults(
    files: &[(PathBuf, Vec<u8>)],
    policy: &Policy,
    faults: Faults,
) -> io::Result<()> {
    let paths: Vec<&Path> = files.iter().map(|(p, _)| p.as_path()).collect();
    // Written where they resolve to (no folder that a `..` leaves is created); messages
    // name the paths as given.
    let targets = resolve_all(&paths, policy)?;
    // 1. Every temporary written and synced before anything is renamed.
    let temps = files
        .iter()
        .zip(&targets)
        .map(|((path, bytes), target)| write_temp(path, target, bytes, faults))
        .collect::<io::Result<Vec<_>>>()?;
    // 2. Renames, each target's previous file kept aside until all have succeeded.
    let mut done: Vec<(PathBuf, Option<TempPath>)> = Vec::new();
    for (k, (((shown, _), target), tmp)) in files.iter().zip(&targets).zip(temps).enumerate() {
        let inject = faults.fail_rename == Some(k);
        match commit_one(shown, target, tmp, policy.force, inject) {
            Ok(backup) => done.push((target.clone(), backup)),
            Err(e) => {
                roll_back(done);
                return Err(e);
            }
        }
    }
    for d in targets.iter().map(|p| folder(p)) {
        sync_dir(&d);
    }
    // The backups are deleted when `done` drops.
    Ok(())
}

/// Undoes the renames already made, last first: each previous file back in place, each new
/// file removed.
fn roll_back(done: Vec<(PathBuf, Option<TempPath>)>) {
    for (path, backup) in done.into_iter().rev() {
        match backup {
            Some(b) => {
                let _ = std::fs::rename(&b, &path);
                let _ = b.keep();
            }
            None => {
                let _ = std::fs::remove_file(&path);
            }
        }
    }
}

/// Renames `tmp` onto `path` (the resolved target; errors name `shown`, the path as given);
/// returns the previous file's new (temporary) name, if any.
fn commit_one(
    shown: &Path,
    path: &Path,
    tmp: NamedTempFile,
    force: bool,
    inject: bool,
) -> io::Result<Option<TempPath>> {
    let err = |e: &io::Error| named(format!("writing {}", shown.display()), e);
    if let Ok(m) = std::fs::metadata(path) {
        // A replaced file keeps its mode.
        let _ = tmp.as_file().set_permissions(m.permissions());
    }
    let backup = if force && path.exists() {
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let b = tempfile::Builder::new()
            .prefix(&format!(".{name}."))
            .suffix(".old")
            .tempfile_in(folder(path))
            .map_err(|e| err(&e))?
            .into_temp_path();
        std::fs::rename(path, &b).map_err(|e| err(&e))?;
        Some(b)
    } else {
        None
    };
    let restore = |b: Option<TempPath>| {
        if let Some(b) = b {
            let _ = std::fs::rename(&b, path);
            let _ = b.keep();
        }
    };
    if inject {
        restore(backup);
        return Err(err(&io::Error::other("injected rename failure")));
    }
    let res = if force {
        tmp.persist(path).map(|_| ())
    } else {
        // Fails if the target appeared since the check: never replaced without --force.
        tmp.persist_noclobber(path).map(|_| ())
    };
    match res {
        Ok(()) => Ok(backup),
        Err(e) => {
            restore(backup);
            Err(err(&e.error))
        }
    }
}

/// Makes the renames durable (best effort: not every platform can sync a folder).
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(f) = std::fs::File::open(dir) {
        let _ = f.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pol(force: bool) -> Policy {
        Policy {
            force,
            inputs: vec![],
            protected: None,
        }
    }

    /// Files in `dir` other than the named ones (temporaries or backups left behind).
    fn strays(dir: &Path, keep: &[&str]) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| !keep.contains(&n.as_str()))
            .collect()
    }

    #[test]
    fn new_file_is_written_and_nothing_else_is_left() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("a.bin");
        write_together(&[(p.clone(), vec![1, 2, 3])], &pol(false)).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), [1, 2, 3]);
        assert!(strays(d.path(), &["a.bin"]).is_empty());
    }

    #[test]
    fn missing_folder_is_created() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("x/y/a.bin");
        write_together(&[(p.clone(), vec![7])], &pol(false)).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), [7]);
    }

    #[test]
    fn existing_file_needs_force() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("a.bin");
        std::fs::write(&p, b"old").unwrap();
        let e = write_together(&[(p.clone(), b"new".to_vec())], &pol(false)).unwrap_err();
        assert!(e.to_string().contains("--force"), "{e}");
        assert_eq!(std::fs::read(&p).unwrap(), b"old");
        write_together(&[(p.clone(), b"new".to_vec())], &pol(true)).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new");
        assert!(strays(d.path(), &["a.bin"]).is_empty());
    }

    #[test]
    fn input_is_never_written_under_any_spelling() {
        let d = tempfile::tempdir().unwrap();
        let inp = d.path().join("in.blut");
        std::fs::write(&inp, b"input").unwrap();
        let link = d.path().join("hard.blut");
        std::fs::hard_link(&inp, &link).unwrap();
        let other = d.path().join("sub");
        std::fs::create_dir(&other).unwrap();
        let spellings = [
            inp.clone(),
            d.path().join(".").join("in.blut"),
            other.join("..").join("in.blut"),
            link,
        ];
        #[cfg(unix)]
        let spellings = {
            let mut s = spellings.to_vec();
            let sym = d.path().join("sym.blut");
            std::os::unix::fs::symlink(&inp, &sym).unwrap();
            s.push(sym);
            s
        };
        for out in spellings.iter() {
            let p = Policy {
                force: true,
                inputs: vec![inp.clone()],
                protected: None,
            };
            let e = write_together(&[(out.clone(), b"x".to_vec())], &p).unwrap_err();
            assert!(e.to_string().contains("it is the input"), "{out:?}: {e}");
            assert_eq!(std::fs::read(&inp).unwrap(), b"input");
        }
    }

    #[test]
    fn protected_folder_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let p = Policy {
            force: true,
            inputs: vec![],
            protected: Some(d.path().to_path_buf()),
        };
        let e = write_together(&[(d.path().join("t.blut"), vec![1])], &p).unwrap_err();
        assert!(e.to_string().contains("committed default tables"), "{e}");
        // Also in a subfolder that does not exist yet (it must not be created).
        let deep = d.path().join("new/sub/t.blut");
        let e = write_together(&[(deep, vec![1])], &p).unwrap_err();
        assert!(e.to_string().contains("committed default tables"), "{e}");
        assert!(strays(d.path(), &[]).is_empty());
    }

    #[test]
    fn full_disk_leaves_previous_file_and_no_partial() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("a.bin");
        std::fs::write(&p, b"previous").unwrap();
        let big = vec![0xAB; 507_904];
        let f = Faults {
            fail_after_bytes: Some(65_536),
            fail_rename: None,
        };
        let e = write_with_faults(&[(p.clone(), big)], &pol(true), f).unwrap_err();
        let msg = format!("{e:#}");
        assert_eq!(msg.matches("a.bin").count(), 1, "{msg}");
        assert_eq!(msg.matches("No space left").count(), 1, "{msg}");
        assert_eq!(std::fs::read(&p).unwrap(), b"previous");
        assert!(strays(d.path(), &["a.bin"]).is_empty());
        // A new file on a full disk: nothing at all is left.
        let q = d.path().join("new.bin");
        write_with_faults(&[(q.clone(), vec![1; 100])], &pol(false), f).unwrap();
        let f0 = Faults {
            fail_after_bytes: Some(0),
            fail_rename: None,
        };
        let r = d.path().join("never.bin");
        assert!(write_with_faults(&[(r.clone(), vec![1; 100])], &pol(false), f0).is_err());
        assert!(!r.exists());
        assert!(strays(d.path(), &["a.bin", "new.bin"]).is_empty());
    }

    #[test]
    fn pair_fails_together_on_second_write() {
        let d = tempfile::tempdir().unwrap();
        let (a, b) = (d.path().join("t.png"), d.path().join("t.png.json"));
        // The first file fits, the sidecar does not: the limit applies per file, so give the
        // data file fewer bytes than the limit and the sidecar more.
        let f = Faults {
            fail_after_bytes: Some(10),
            fail_rename: None,
        };
        let files = [(a.clone(), vec![1; 5]), (b.clone(), vec![2; 50])];
        assert!(write_with_faults(&files, &pol(false), f).is_err());
        assert!(!a.exists() && !b.exists());
        assert!(strays(d.path(), &[]).is_empty());
    }

    #[test]
    fn pair_rolls_back_when_second_rename_fails() {
        let d = tempfile::tempdir().unwrap();
        let (a, b) = (d.path().join("t.bin"), d.path().join("t.bin.json"));
        std::fs::write(&a, b"old data").unwrap();
        std::fs::write(&b, b"old side").unwrap();
        let f = Faults {
            fail_after_bytes: None,
            fail_rename: Some(1),
        };
        let files = [
            (a.clone(), b"new data".to_vec()),
            (b.clone(), b"new side".to_vec()),
        ];
        let e = write_with_faults(&files, &pol(true), f).unwrap_err();
        assert!(e.to_string().contains("t.bin.json"), "{e}");
        assert_eq!(std::fs::read(&a).unwrap(), b"old data");
        assert_eq!(std::fs::read(&b).unwrap(), b"old side");
        assert!(strays(d.path(), &["t.bin", "t.bin.json"]).is_empty());
        // New pair, second rename fails: neither file exists afterwards.
        let (c, s) = (d.path().join("n.bin"), d.path().join("n.bin.json"));
        let files = [(c.clone(), vec![1]), (s.clone(), vec![2])];
        assert!(write_with_faults(&files, &pol(false), f).is_err());
        assert!(!c.exists() && !s.exists());
        assert!(strays(d.path(), &["t.bin", "t.bin.json"]).is_empty());
    }

    #[test]
    fn missing_input_error_names_path_and_cause_once() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("nope.blut");
        let msg = format!("{:#}", load_lut(&p).unwrap_err());
        assert_eq!(msg.matches("nope.blut").count(), 1, "{msg}");
        assert_eq!(msg.matches("No such file or directory").count(), 1, "{msg}");
        let bad = d.path().join("bad.blut");
        std::fs::write(&bad, b"not a table").unwrap();
        let msg = format!("{:#}", load_lut(&bad).unwrap_err());
        assert_eq!(msg.matches("bad.blut").count(), 1, "{msg}");
    }

    /// A real full disk: a 64 KiB tmpfs. Needs the right to mount (root on Linux); skipped
    /// with a message otherwise, the injected-writer tests above cover the logic.
    #[test]
    #[cfg(target_os = "linux")]
    fn real_full_tmpfs_keeps_previous_file() {
        let d = tempfile::tempdir().unwrap();
        let mnt = d.path().join("small");
        std::fs::create_dir(&mnt).unwrap();
        let ok = std::process::Command::new("mount")
            .args(["-t", "tmpfs", "-o", "size=64k", "tmpfs"])
            .arg(&mnt)
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if !ok {
            eprintln!("skipped: cannot mount a tmpfs here (needs root)");
            return;
        }
        let p = mnt.join("dfg.f32.bin");
        let r = (|| {
            write_together(&[(p.clone(), vec![5; 20_000])], &pol(false))?;
            let e = write_together(&[(p.clone(), vec![6; 507_904])], &pol(true)).unwrap_err();
            let msg = format!("{e:#}");
            let prev = std::fs::read(&p)?;
            let left = strays(&mnt, &["dfg.f32.bin"]);
            Ok::<_, std::io::Error>((msg, prev, left))
        })();
        let _ = std::process::Command::new("umount").arg(&mnt).status();
        let (msg, prev, left) = r.unwrap();
        assert!(
            msg.contains("dfg.f32.bin") && msg.contains("No space left"),
            "{msg}"
        );
        assert_eq!(prev, vec![5; 20_000]);
        assert!(left.is_empty(), "{left:?}");
    }
}

//! The `std` loader: a LUT file owned in memory, validated and prepared once.

use crate::tables::Prepared;
use crate::{Header, LutError, LutView, TableKind};
use std::fmt;
use std::io::Read;
use std::path::Path;
use std::string::String;
use std::vec::Vec;

/// Largest file the loader accepts (64 MiB); a longer file is refused before it is read.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Why a LUT could not be loaded or queried.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// Reading failed.
    Io(std::io::Error),
    /// The file is longer than [`MAX_FILE_BYTES`].
    TooLarge {
        /// Its size (or a lower bound for readers).
        size: u64,
    },
    /// The bytes are not a valid LUT.
    Format(LutError),
    /// The query does not fit the table (e.g. `dfg` on a G table).
    WrongKind {
        /// What the query needs.
        expected: &'static str,
        /// What the file holds.
        found: TableKind,
    },
    /// A per-σ G table was asked for another σ.
    SigmaMismatch {
        /// The table's σ.
        table: f32,
        /// The σ asked for.
        asked: f32,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io(e) => write!(f, "cannot read LUT: {e}"),
            Error::TooLarge { size } => write!(
                f,
                "LUT file of {size} bytes exceeds the limit of {MAX_FILE_BYTES} bytes"
            ),
            Error::Format(e) => write!(f, "{e}"),
            Error::WrongKind { expected, found } => {
                write!(f, "this query needs {expected}, the file holds {found:?}")
            }
            Error::SigmaMismatch { table, asked } => write!(
                f,
                "the table is for sigma = {table}, asked for sigma = {asked}"
            ),
        }
    }
}

impl std::error::Error for Error {
    // The message of the wrapped error is already part of this one's `Display`; returning
    // it as the source too would print it twice in a chain ("…: No such file or directory
    // (os error 2): No such file or directory (os error 2)").
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        None
    }
}

impl From<LutError> for Error {
    fn from(e: LutError) -> Self {
        Error::Format(e)
    }
}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Self {
        Error::Io(e)
    }
}

/// Reads a file of at most [`MAX_FILE_BYTES`]: the size is checked before reading when the
/// file system knows it, and the read itself stops after the cap, so an endless file
/// (`/dev/zero`, a pipe) gives [`Error::TooLarge`] instead of exhausting memory. The buffer
/// grows with the bytes actually read, never from a size the file declares. Use it to feed
/// the typed tables: `DfgTable::parse(read_capped(path)?)`.
pub fn read_capped(path: impl AsRef<Path>) -> Result<Vec<u8>, Error> {
    let f = std::fs::File::open(path)?;
    let size = f.metadata()?.len();
    if size > MAX_FILE_BYTES {
        return Err(Error::TooLarge { size });
    }
    let mut bytes = Vec::with_capacity(size as usize);
    f.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(Error::TooLarge {
            size: bytes.len() as u64,
        });
    }
    bytes.shrink_to_fit();
    Ok(bytes)
}

/// A loaded, validated LUT of any kind, owning its bytes, its lookup constants prepared at
/// load. Its queries run the same code as the typed tables (`DfgTable`, `GTable`, …) and
/// give the same values; each checks the kind first (one compare) and returns
/// [`Error::WrongKind`] on a mismatch. For a table of known kind, the typed tables over
/// `Vec<u8>` avoid even that: `DfgTable::parse(std::fs::read(path)?)`.
#[derive(Clone, Debug)]
pub struct Lut {
    bytes: Vec<u8>,
    p: Prepared,
    g: GShape,
}

/// What a G query can do with a table, decided at load so that a query makes one test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum GShape {
    /// Not a passing-factor table.
    NotG,
    /// A passing-factor table in the printed convention (not served).
    Printed,
    /// A per-σ 2-D table (reciprocal).
    PerSigma,
    /// A 3-D table over σ (reciprocal).
    OverSigma,
}

impl Lut {
    /// Validates `bytes` (magic, version, header, sizes, CRC-32) and keeps them.
    pub fn from_bytes(bytes: Vec<u8>) -> Result<Self, Error> {
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(Error::TooLarge {
                size: bytes.len() as u64,
            });
        }
        let p = Prepared::new(&LutView::parse(&bytes)?);
        let g = match (p.kind, p.reciprocal, p.grid.dims) {
            (TableKind::PassingFactor, false, _) => GShape::Printed,
            (TableKind::PassingFactor, true, 3) => GShape::OverSigma,
            (TableKind::PassingFactor, true, _) => GShape::PerSigma,
            _ => GShape::NotG,
        };
        Ok(Self { bytes, p, g })
    }

    /// Reads ([`read_capped`]) and validates a file.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Self, Error> {
        Self::from_bytes(read_capped(path)?)
    }

    /// Reads at most [`MAX_FILE_BYTES`] + 1 bytes from `r` and validates them. The buffer
    /// grows with the bytes actually read (never from a size the file declares) and is
    /// shrunk to the data before validation.
    pub fn from_reader(r: impl Read) -> Result<Self, Error> {
        let mut bytes = Vec::new();
        r.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes)?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(Error::TooLarge {
                size: bytes.len() as u64,
            });
        }
        bytes.shrink_to_fit();
        Self::from_bytes(bytes)
    }

    /// The file's bytes.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// The no_std view of the bytes (re-decodes the header; the CRC is not recomputed).
    /// The bytes passed the full check at load and cannot change, so this does not fail in
    /// practice; it returns a `Result` only to stay total without a panic path.
    pub fn view(&self) -> Result<LutView<'_>, LutError> {
        LutView::parse_skip_checksum(&self.bytes)
    }

    /// The decoded header (see [`Lut::view`]; the default header if that ever failed).
    pub fn header(&self) -> Header<'_> {
        self.view().map(|v| *v.header()).unwrap_or_default()
    }

    /// What the table holds.
    pub fn kind(&self) -> TableKind {
        self.p.kind
    }

    #[inline(always)]
    fn payload(&self) -> &[u8] {
        self.bytes.get(self.p.header_len..).unwrap_or(&[])
    }

    #[inline(always)]
    fn expect(&self, kind: TableKind, dims: usize, what: &'static str) -> Result<(), Error> {
        if self.p.kind != kind || self.p.grid.dims != dims {
            return Err(Error::WrongKind {
                expected: what,
                found: self.p.kind,
            });
        }
        Ok(())
    }

    /// (GM, GS, G) of the modified G at in-plane angles (radians) and σ: from a 3-D table at
    /// any σ in its range (clamped), or from a per-σ table whose σ equals `sigma` within 1e-6.
    #[inline]
    pub fn g_terms(
        &self,
        theta_i: f32,
        theta_r: f32,
        sigma: f32,
    ) -> Result<(f32, f32, f32), Error> {
        match self.g {
            GShape::OverSigma => Ok(self.p.g3(self.payload(), theta_i, theta_r, sigma)),
            // Within 1e-6 of the table's σ (NaN fails the comparison).
            GShape::PerSigma if (self.p.sigma - sigma).abs() <= 1e-6 => {
                Ok(self.p.g2(self.payload(), theta_i, theta_r))
            }
            GShape::PerSigma => Err(Error::SigmaMismatch {
                table: self.p.sigma,
                asked: sigma,
            }),
            GShape::Printed => Err(Error::Format(LutError::Inconsistent(
                "G tables must use the reciprocal convention",
            ))),
            GShape::NotG => Err(Error::WrongKind {
                expected: "a modified-G passing-factor table",
                found: self.p.kind,
            }),
        }
    }

    /// G = min(GM, GS); see [`Lut::g_terms`].
    #[inline]
    pub fn g(&self, theta_i: f32, theta_r: f32, sigma: f32) -> Result<f32, Error> {
        Ok(self.g_terms(theta_i, theta_r, sigma)?.2)
    }

    /// Split-sum (A, B) at μ and roughness (see the table's header for which roughness).
    #[inline]
    pub fn dfg(&self, mu: f32, roughness: f32) -> Result<(f32, f32), Error> {
        self.expect(TableKind::SplitSum, 2, "a split-sum table")?;
        Ok(self.p.two_at(&self.bytes, mu, roughness))
    }

    /// Directional albedo E(μ, r).
    #[inline]
    pub fn e(&self, mu: f32, roughness: f32) -> Result<f32, Error> {
        self.expect(
            TableKind::DirectionalAlbedo,
            2,
            "a directional-albedo table",
        )?;
        Ok(self.p.two1(self.payload(), mu, roughness))
    }

    /// Average albedo E_avg(r).
    #[inline]
    pub fn e_avg(&self, roughness: f32) -> Result<f32, Error> {
        self.expect(TableKind::AverageAlbedo, 1, "an average-albedo table")?;
        Ok(self.p.one(self.payload(), roughness))
    }

    /// The header in words (what `cargo xtask lut inspect` prints).
    pub fn summary(&self) -> String {
        match self.view() {
            Ok(v) => summary(&v, self.bytes.len()),
            Err(e) => std::format!("{e}\n"),
        }
    }
}

/// A header string for a terminal: printable characters as they are, everything else as
/// Rust escapes (`\u{1b}`), so a crafted name cannot clear the screen or fake output:
/// control characters (category Cc, such as ESC), format characters (category Cf: the
/// bidirectional overrides and isolates U+202A–202E and U+2066–2069, the marks U+200E/200F
/// and U+061C, zero-width characters, the BOM, …) and the line and paragraph separators
/// U+2028/2029.
pub struct Escaped<'a>(pub &'a str);

/// Unicode general category Cf (Unicode 15.1), and Zl/Zp (U+2028, U+2029): characters that
/// change how the text around them is shown without showing themselves.
const INVISIBLE: [(u32, u32); 21] = [
    (0xAD, 0xAD),
    (0x600, 0x605),
    (0x61C, 0x61C),
    (0x6DD, 0x6DD),
    (0x70F, 0x70F),
    (0x890, 0x891),
    (0x8E2, 0x8E2),
    (0x180E, 0x180E),
    (0x200B, 0x200F),
    (0x2028, 0x202E),
    (0x2060, 0x2064),
    (0x2066, 0x206F),
    (0xFEFF, 0xFEFF),
    (0xFFF9, 0xFFFB),
    (0x110BD, 0x110BD),
    (0x110CD, 0x110CD),
    (0x13430, 0x1343F),
    (0x1BCA0, 0x1BCA3),
    (0x1D173, 0x1D17A),
    (0xE0001, 0xE0001),
    (0xE0020, 0xE007F),
];

/// Whether [`Escaped`] escapes `c`.
fn escaped(c: char) -> bool {
    let u = c as u32;
    c.is_control() || INVISIBLE.iter().any(|&(lo, hi)| (lo..=hi).contains(&u))
}

impl fmt::Display for Escaped<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buf = String::new();
        for c in self.0.chars() {
            if escaped(c) {
                buf.extend(c.escape_default());
            } else {
                buf.push(c);
            }
        }
        // `pad` keeps width and alignment flags working.
        f.pad(&buf)
    }
}

/// The header of a view in words, header strings escaped ([`Escaped`]).
pub fn summary(v: &LutView<'_>, file_len: usize) -> String {
    use std::fmt::Write;
    let h = v.header();
    let mut s = String::new();
    let _ = writeln!(s, "format      BLUT version {}", crate::FORMAT_VERSION);
    let _ = writeln!(s, "kind        {:?}", h.kind);
    let _ = writeln!(
        s,
        "size        {file_len} bytes (header {} + payload {})",
        v.header_len(),
        v.payload().len()
    );
    for (k, a) in h.axes.iter().enumerate() {
        let _ = writeln!(
            s,
            "axis {k}      {:<10} {:>5} nodes  [{}, {}]  warp {:?}  placement {:?}",
            Escaped(a.name),
            a.count,
            a.lo,
            a.hi,
            a.warp,
            a.placement
        );
    }
    for c in h.channels.iter() {
        let _ = writeln!(
            s,
            "channel     {:<4} value = {} + {} * stored",
            Escaped(c.name),
            c.offset,
            c.scale
        );
    }
    let _ = writeln!(s, "encoding    {:?} little-endian", h.encoding);
    let _ = writeln!(s, "interp      {:?}", h.interpolation);
    let g = &h.generator;
    let _ = writeln!(
        s,
        "generator   model {:?}, convention {:?}, sigma {:?}, nodes {:?}, tool `{}`",
        g.model,
        g.convention,
        g.sigma,
        g.nodes.as_slice(),
        Escaped(g.tool)
    );
    let _ = writeln!(
        s,
        "error       max |err| {:.3e}, RMS {:.3e} over {} random points (seed {})",
        h.error.max_abs, h.error.rms, h.error.samples, h.error.seed
    );
    let _ = match h.integration {
        Some(e) => writeln!(
            s,
            "integration max estimated |node value - integral| {e:.3e} (over all nodes and channels)"
        ),
        None => writeln!(s, "integration not recorded (a version 1 file)"),
    };
    let _ = writeln!(s, "checksum    CRC-32 {:#010x}", h.checksum);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::testing::asset_path as asset;

    #[test]
    fn path_reader_and_bytes_load_the_same_table() {
        let p = asset("kc_eavg_ggx.blut");
        let a = Lut::from_path(&p).unwrap();
        let b = Lut::from_reader(std::fs::File::open(&p).unwrap()).unwrap();
        let c = Lut::from_bytes(std::fs::read(&p).unwrap()).unwrap();
        assert_eq!(a.bytes(), b.bytes());
        assert_eq!(a.bytes(), c.bytes());
        assert_eq!(a.kind(), TableKind::AverageAlbedo);
        // E_avg of a perfect mirror (r = 0) is 1: every direction reflects everything.
        assert!((a.e_avg(0.0).unwrap() - 1.0).abs() < 1e-4);
        assert!(matches!(a.dfg(0.5, 0.5), Err(Error::WrongKind { .. })));
        let s = a.summary();
        assert!(s.contains("AverageAlbedo") && s.contains("roughness"));
    }

    #[test]
    fn g_queries_route_by_table_shape() {
        // A per-σ table answers only at its σ (within 1e-6; NaN σ is a mismatch), a 3-D
        // table at any σ; both equal their typed tables bit for bit.
        let b = std::fs::read(asset("g_modified_sigma0.3.blut")).unwrap();
        let lut = Lut::from_bytes(b.clone()).unwrap();
        let t = crate::GTable::parse(&b[..]).unwrap();
        let g = lut.g(0.4, -0.7, 0.3).unwrap();
        assert_eq!(g.to_bits(), t.g(0.4, -0.7).to_bits());
        for s in [0.31, 0.3 + 2e-6, f32::NAN] {
            assert!(matches!(
                lut.g(0.4, -0.7, s),
                Err(Error::SigmaMismatch { .. })
            ));
        }
        let b3 = std::fs::read(asset("g_modified.blut")).unwrap();
        let lut3 = Lut::from_bytes(b3.clone()).unwrap();
        let t3 = crate::GTable3::parse(&b3[..]).unwrap();
        for s in [0.05, 0.31, 0.9] {
            let g = lut3.g(0.4, -0.7, s).unwrap();
            assert_eq!(g.to_bits(), t3.g(0.4, -0.7, s).to_bits());
        }
    }

    #[test]
    fn bad_files_are_typed_errors() {
        let good = std::fs::read(asset("dfg_ggx.blut")).unwrap();
        let cut = Lut::from_reader(&good[..good.len() / 2]).unwrap_err();
        assert!(matches!(cut, Error::Format(LutError::PayloadLength { .. })));
        let missing = Lut::from_path(asset("no-such-file.blut")).unwrap_err();
        assert!(matches!(missing, Error::Io(_)));
        let big = std::io::repeat(b'B').take(MAX_FILE_BYTES + 5);
        assert!(matches!(Lut::from_reader(big), Err(Error::TooLarge { .. })));
    }
}

#[cfg(test)]
mod codec_tests {
    use super::*;
    use std::vec;

    /// Every committed asset decodes and re-encodes to the same bytes: the writer's header
    /// encoding is the one the files were written with.
    #[test]
    fn assets_round_trip_byte_for_byte() {
        let dir = crate::testing::asset_path("");
        let mut n = 0;
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.extension() != Some(std::ffi::OsStr::new("blut")) {
                continue;
            }
            let bytes = std::fs::read(&p).unwrap();
            let v = LutView::parse(&bytes).unwrap();
            let mut out = vec![0u8; bytes.len() + 64];
            let k = crate::encode_into(v.header(), v.payload(), &mut out).unwrap();
            assert_eq!(&out[..k], &bytes[..], "{}", p.display());
            n += 1;
        }
        assert!(n >= 10, "only {n} assets found");
    }
}

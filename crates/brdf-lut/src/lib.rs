//! # brdf-lut
//!
//! The thin `std` loader of the LUT files described in `docs/lut-format.md`. It reads a file
//! (from a path, a byte vector or a reader), validates it with the `no_std` view
//! [`brdf_core::lut::LutView`] and answers the typed queries through the same code, so its
//! lookups are the very same `f32` values as the view's.
//!
//! ```no_run
//! let lut = brdf_lut::Lut::from_path("assets/dfg_ggx.blut").unwrap();
//! let (a, b) = lut.dfg(0.5, 0.3).unwrap();
//! # let _ = (a, b);
//! ```

pub mod generate;

pub use brdf_core::lut::{self as format, Header};
use brdf_core::lut::{
    AlbedoTable, AverageAlbedoTable, DfgTable, GTable, GTable3, LutError, LutView, TableKind,
};
use std::fmt;
use std::io::Read;
use std::path::Path;

/// Largest file the loader accepts (64 MiB); a longer file is refused before it is read.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Why a LUT could not be loaded or queried.
#[derive(Debug)]
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
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io(e) => Some(e),
            Error::Format(e) => Some(e),
            _ => None,
        }
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

/// A loaded, validated LUT owning its bytes.
#[derive(Clone, Debug)]
pub struct Lut {
    bytes: Vec<u8>,
}

impl Lut {
    /// Validates `bytes` (magic, version, header, sizes, CRC-32) and keeps them.
    pub fn from_bytes(bytes: Vec<u8>) -> Result<Self, Error> {
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(Error::TooLarge {
                size: bytes.len() as u64,
            });
        }
        LutView::parse(&bytes)?;
        Ok(Self { bytes })
    }

    /// Reads and validates a file. The size is checked before reading, and the buffer is
    /// allocated once with the file's size (nothing the file declares is trusted for sizes).
    pub fn from_path(path: impl AsRef<Path>) -> Result<Self, Error> {
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
        Self::from_bytes(bytes)
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

    /// The no_std view of the bytes (validated at load; the CRC is not recomputed).
    pub fn view(&self) -> LutView<'_> {
        // Cannot fail: the same bytes passed the full check in `from_bytes`.
        match LutView::parse_skip_checksum(&self.bytes) {
            Ok(v) => v,
            Err(e) => unreachable!("validated LUT failed to re-parse: {e}"),
        }
    }

    /// The decoded header.
    pub fn header(&self) -> Header<'_> {
        self.view().header().clone()
    }

    /// What the table holds.
    pub fn kind(&self) -> TableKind {
        self.view().kind()
    }

    /// (GM, GS, G) of the modified G at in-plane angles (radians) and σ: from a 3-D table at
    /// any σ in its range (clamped), or from a per-σ table whose σ equals `sigma` within 1e-6.
    pub fn g_terms(
        &self,
        theta_i: f32,
        theta_r: f32,
        sigma: f32,
    ) -> Result<(f32, f32, f32), Error> {
        let v = self.view();
        let wrong = |found| Error::WrongKind {
            expected: "a modified-G passing-factor table",
            found,
        };
        if v.kind() != TableKind::PassingFactor {
            return Err(wrong(v.kind()));
        }
        if v.dims() == 3 {
            Ok(GTable3::from_view(v)?.terms(theta_i, theta_r, sigma))
        } else {
            let t = GTable::from_view(v)?;
            if (t.sigma() - sigma).abs().is_nan() || (t.sigma() - sigma).abs() > 1e-6 {
                return Err(Error::SigmaMismatch {
                    table: t.sigma(),
                    asked: sigma,
                });
            }
            Ok(t.terms(theta_i, theta_r))
        }
    }

    /// G = min(GM, GS); see [`Lut::g_terms`].
    pub fn g(&self, theta_i: f32, theta_r: f32, sigma: f32) -> Result<f32, Error> {
        Ok(self.g_terms(theta_i, theta_r, sigma)?.2)
    }

    /// Split-sum (A, B) at μ and roughness (see the table's header for which roughness).
    pub fn dfg(&self, mu: f32, roughness: f32) -> Result<(f32, f32), Error> {
        let v = self.view();
        let k = v.kind();
        DfgTable::from_view(v)
            .map(|t| t.ab(mu, roughness))
            .map_err(|_| Error::WrongKind {
                expected: "a split-sum table",
                found: k,
            })
    }

    /// Directional albedo E(μ, r).
    pub fn e(&self, mu: f32, roughness: f32) -> Result<f32, Error> {
        let v = self.view();
        let k = v.kind();
        AlbedoTable::from_view(v)
            .map(|t| t.e(mu, roughness))
            .map_err(|_| Error::WrongKind {
                expected: "a directional-albedo table",
                found: k,
            })
    }

    /// Average albedo E_avg(r).
    pub fn e_avg(&self, roughness: f32) -> Result<f32, Error> {
        let v = self.view();
        let k = v.kind();
        AverageAlbedoTable::from_view(v)
            .map(|t| t.e_avg(roughness))
            .map_err(|_| Error::WrongKind {
                expected: "an average-albedo table",
                found: k,
            })
    }

    /// The header in words (what `cargo xtask lut inspect` prints).
    pub fn summary(&self) -> String {
        summary(&self.view(), self.bytes.len())
    }
}

/// The header of a view in words.
pub fn summary(v: &LutView<'_>, file_len: usize) -> String {
    use std::fmt::Write;
    let h = v.header();
    let mut s = String::new();
    let _ = writeln!(s, "format      BLUT version {}", h.version);
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
            a.name, a.count, a.lo, a.hi, a.warp, a.placement
        );
    }
    for c in &h.channels {
        let _ = writeln!(
            s,
            "channel     {:<4} value = {} + {} * stored",
            c.name, c.offset, c.scale
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
        g.tool
    );
    let _ = writeln!(
        s,
        "error       max |err| {:.3e}, RMS {:.3e} over {} random points (seed {})",
        h.error.max_abs, h.error.rms, h.error.samples, h.error.seed
    );
    let _ = writeln!(
        s,
        "checksum    CRC-32 {:#010x}",
        u32::from_le_bytes(h.checksum)
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn asset(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets")
            .join(name)
    }

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

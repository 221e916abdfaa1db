//! The header's byte encoding (docs/lut-format.md §3): the fields in declaration order;
//! unsigned integers and enum tags as LEB128 varints in their shortest form, `f32`/`f64` as
//! little-endian IEEE bytes, strings as a varint byte length and UTF-8, lists as a varint
//! length and the items, an `Option` as one byte 0 or 1 and the value, fixed byte arrays raw.
//! (This is the layout the `postcard` crate gives the same struct, so the files written by
//! earlier versions read unchanged; unlike that crate's decoder, a varint that is not in its
//! shortest form is rejected, so every header has exactly one encoding.)

use crate::header::*;
use crate::LutError;

/// A cursor over the encoded header.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// The format version being decoded (fields added by a version are read from it on).
    pub(crate) version: u16,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Self {
            bytes,
            pos: 0,
            version: FORMAT_VERSION,
        }
    }
    /// Bytes consumed so far.
    pub(crate) fn pos(&self) -> usize {
        self.pos
    }
    fn take(&mut self, n: usize) -> Result<&'a [u8], LutError> {
        let end = self.pos.checked_add(n).ok_or(LutError::Truncated)?;
        let s = self.bytes.get(self.pos..end).ok_or(LutError::Truncated)?;
        self.pos = end;
        Ok(s)
    }
    fn byte(&mut self) -> Result<u8, LutError> {
        Ok(self.take(1)?[0])
    }
    /// A shortest-form LEB128 varint of at most `max` bits.
    pub(crate) fn varint(&mut self, max: u32) -> Result<u64, LutError> {
        let mut v: u64 = 0;
        let mut shift = 0u32;
        loop {
            let b = self.byte()?;
            let bits = (b & 0x7F) as u64;
            if shift >= max || (shift > 0 && max - shift < 7 && bits >> (max - shift) != 0) {
                return Err(LutError::MalformedHeader);
            }
            v |= bits << shift;
            if b & 0x80 == 0 {
                // Shortest form: a final group of zero bits is only allowed alone.
                if b == 0 && shift > 0 {
                    return Err(LutError::NonCanonical);
                }
                return Ok(v);
            }
            shift += 7;
        }
    }
    fn u16(&mut self) -> Result<u16, LutError> {
        Ok(self.varint(16)? as u16)
    }
    fn u32(&mut self) -> Result<u32, LutError> {
        Ok(self.varint(32)? as u32)
    }
    fn u64(&mut self) -> Result<u64, LutError> {
        self.varint(64)
    }
    fn tag(&mut self, variants: u32) -> Result<u32, LutError> {
        let t = self.u32()?;
        if t < variants {
            Ok(t)
        } else {
            Err(LutError::MalformedHeader)
        }
    }
    fn f32(&mut self) -> Result<f32, LutError> {
        let b = self.take(4)?;
        Ok(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    fn f64(&mut self) -> Result<f64, LutError> {
        let b = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(f64::from_le_bytes(a))
    }
    fn str(&mut self) -> Result<&'a str, LutError> {
        let n = self.u32()? as usize;
        core::str::from_utf8(self.take(n)?).map_err(|_| LutError::MalformedHeader)
    }
    fn list_len(&mut self, cap: usize) -> Result<usize, LutError> {
        let n = self.u32()? as usize;
        if n > cap {
            Err(LutError::MalformedHeader)
        } else {
            Ok(n)
        }
    }

    fn axis(&mut self) -> Result<Axis<'a>, LutError> {
        Ok(Axis {
            name: self.str()?,
            count: self.u32()?,
            lo: self.f64()?,
            hi: self.f64()?,
            warp: match self.tag(5)? {
                0 => Warp::Linear,
                1 => Warp::Log,
                2 => Warp::Sqrt,
                3 => Warp::Cos,
                _ => Warp::SqrtCos,
            },
            placement: match self.tag(2)? {
                0 => Placement::Endpoint,
                _ => Placement::TexelCentre,
            },
        })
    }

    /// The header after the magic; the version must already have been read.
    pub(crate) fn header(&mut self) -> Result<Header<'a>, LutError> {
        let kind = TableKind::from_code(self.u32()?).ok_or(LutError::MalformedHeader)?;
        let mut axes = List::new();
        for _ in 0..self.list_len(MAX_AXES)? {
            let _ = axes.push(self.axis()?);
        }
        let mut channels = List::new();
        for _ in 0..self.list_len(MAX_CHANNELS)? {
            let _ = channels.push(Channel {
                name: self.str()?,
                scale: self.f32()?,
                offset: self.f32()?,
            });
        }
        let encoding = match self.tag(3)? {
            0 => Encoding::Unorm16,
            1 => Encoding::F16,
            _ => Encoding::F32,
        };
        let interpolation = match self.tag(2)? {
            0 => Interpolation::Linear,
            _ => Interpolation::CatmullRom,
        };
        let model = Model::from_code(self.tag(Model::ALL.len() as u32)?).unwrap_or_default();
        let convention = match self.tag(2)? {
            0 => Convention::Reciprocal,
            _ => Convention::Printed,
        };
        let sigma = match self.byte()? {
            0 => None,
            1 => Some(self.f64()?),
            _ => return Err(LutError::MalformedHeader),
        };
        let mut nodes = List::new();
        for _ in 0..self.list_len(MAX_GENERATOR_NODES)? {
            let _ = nodes.push(self.u16()?);
        }
        let tool = self.str()?;
        let error = ErrorStats {
            max_abs: self.f32()?,
            rms: self.f32()?,
            samples: self.u32()?,
            seed: self.u64()?,
        };
        // Version 2 added the integration error bound.
        // Version 2 added the integration bound: an option tag 0 or 1 (one byte, read as a
        // two-variant tag, which refuses anything else) and the f32.
        let integration = if self.version >= 2 && self.tag(2)? == 1 {
            Some(self.f32()?)
        } else {
            None
        };
        let c = self.take(4)?;
        Ok(Header {
            kind,
            axes,
            channels,
            encoding,
            interpolation,
            generator: Generator {
                model,
                convention,
                sigma,
                nodes,
                tool,
            },
            error,
            integration,
            checksum: u32::from_le_bytes([c[0], c[1], c[2], c[3]]),
        })
    }
}

/// A cursor writing into a caller's buffer.
pub(crate) struct Writer<'b> {
    out: &'b mut [u8],
    pos: usize,
}

impl<'b> Writer<'b> {
    pub(crate) fn new(out: &'b mut [u8]) -> Self {
        Self { out, pos: 0 }
    }
    pub(crate) fn pos(&self) -> usize {
        self.pos
    }
    pub(crate) fn bytes(&mut self, b: &[u8]) -> Result<(), LutError> {
        let end = self.pos + b.len();
        self.out
            .get_mut(self.pos..end)
            .ok_or(LutError::BufferTooSmall)?
            .copy_from_slice(b);
        self.pos = end;
        Ok(())
    }
    fn varint(&mut self, mut v: u64) -> Result<(), LutError> {
        loop {
            let b = (v & 0x7F) as u8;
            v >>= 7;
            if v == 0 {
                return self.bytes(&[b]);
            }
            self.bytes(&[b | 0x80])?;
        }
    }
    fn str(&mut self, s: &str) -> Result<(), LutError> {
        self.varint(s.len() as u64)?;
        self.bytes(s.as_bytes())
    }

    /// Magic, version and the header with the checksum field zero.
    pub(crate) fn header(&mut self, h: &Header<'_>) -> Result<(), LutError> {
        self.bytes(&MAGIC)?;
        self.varint(FORMAT_VERSION as u64)?;
        self.varint(h.kind.code() as u64)?;
        self.varint(h.axes.len() as u64)?;
        for a in h.axes.iter() {
            self.str(a.name)?;
            self.varint(a.count as u64)?;
            self.bytes(&a.lo.to_le_bytes())?;
            self.bytes(&a.hi.to_le_bytes())?;
            self.varint(a.warp as u64)?;
            self.varint(a.placement as u64)?;
        }
        self.varint(h.channels.len() as u64)?;
        for c in h.channels.iter() {
            self.str(c.name)?;
            self.bytes(&c.scale.to_le_bytes())?;
            self.bytes(&c.offset.to_le_bytes())?;
        }
        self.varint(h.encoding as u64)?;
        self.varint(h.interpolation as u64)?;
        let g = &h.generator;
        self.varint(g.model.code() as u64)?;
        self.varint(g.convention as u64)?;
        match g.sigma {
            None => self.bytes(&[0])?,
            Some(s) => {
                self.bytes(&[1])?;
                self.bytes(&s.to_le_bytes())?;
            }
        }
        self.varint(g.nodes.len() as u64)?;
        for &n in g.nodes.iter() {
            self.varint(n as u64)?;
        }
        self.str(g.tool)?;
        self.bytes(&h.error.max_abs.to_le_bytes())?;
        self.bytes(&h.error.rms.to_le_bytes())?;
        self.varint(h.error.samples as u64)?;
        self.varint(h.error.seed)?;
        match h.integration {
            None => self.bytes(&[0])?,
            Some(e) => {
                self.bytes(&[1])?;
                self.bytes(&e.to_le_bytes())?;
            }
        }
        self.bytes(&[0; 4])
    }
}

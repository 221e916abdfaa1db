//! CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, initial value and final XOR
//! 0xFFFFFFFF): the checksum of a LUT file (docs/lut-format.md §5). Check value:
//! `crc32(b"123456789") == 0xCBF43926`.

/// The reflected CRC-32 (IEEE 802.3) polynomial.
const POLY: u32 = 0xEDB8_8320;

/// The CRC register after shifting in the low `BITS` bits of every index (`N` = 2^BITS).
#[cfg_attr(feature = "compact", allow(dead_code))]
const fn make_table<const N: usize, const BITS: u32>() -> [u32; N] {
    let mut t = [0u32; N];
    let mut i = 0;
    while i < N {
        let mut c = i as u32;
        let mut k = 0;
        while k < BITS {
            c = if c & 1 != 0 { POLY ^ (c >> 1) } else { c >> 1 };
            k += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
}

/// Byte-at-a-time table (1 KiB).
#[cfg(not(feature = "compact"))]
static TABLE: [u32; 256] = make_table::<256, 8>();

/// A running CRC-32: `Crc32::new().update(a).update(b).finish()` is the CRC of `a ++ b`.
#[derive(Clone, Copy, Debug)]
pub struct Crc32(u32);

impl Default for Crc32 {
    fn default() -> Self {
        Self::new()
    }
}

impl Crc32 {
    /// The empty message's running state.
    pub const fn new() -> Self {
        Self(0xFFFF_FFFF)
    }
    /// Feeds bytes.
    pub fn update(mut self, bytes: &[u8]) -> Self {
        for &b in bytes {
            #[cfg(not(feature = "compact"))]
            {
                self.0 = TABLE[((self.0 ^ b as u32) & 0xFF) as usize] ^ (self.0 >> 8);
            }
            #[cfg(feature = "compact")]
            {
                // Bit by bit, no table: the polynomial is XORed in where the low bit is 1.
                let mut c = self.0 ^ b as u32;
                for _ in 0..8 {
                    c = (c >> 1) ^ (POLY & (c & 1).wrapping_neg());
                }
                self.0 = c;
            }
        }
        self
    }
    /// The checksum.
    pub fn finish(self) -> u32 {
        self.0 ^ 0xFFFF_FFFF
    }
}

/// CRC-32 of one byte string. The standard check value of CRC-32/ISO-HDLC, whole and in
/// two pieces through [`Crc32`]:
///
/// ```
/// use brdf_lut::{crc32, Crc32};
/// assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
/// assert_eq!(crc32(b""), 0);
/// let pieces = Crc32::new().update(b"1234").update(b"56789").finish();
/// assert_eq!(pieces, 0xCBF4_3926);
/// ```
pub fn crc32(bytes: &[u8]) -> u32 {
    Crc32::new().update(bytes).finish()
}

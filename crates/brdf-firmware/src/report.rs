//! The line protocol printed over semihosting, parsed by `cargo xtask firmware`:
//!
//! ```text
//! BRDF-FW 1 math=<libm|micromath>
//! TABLE <file> <bytes> <crc32>          an embedded table (file name under assets/, its
//!                                       length and the CRC-32 its header stores, hex)
//! R <kernel> <arg>... = <result>        one evaluated kernel; every number is the f32's bit
//!                                       pattern in 8 hex digits followed by `/` and its
//!                                       shortest round-trip decimal, e.g. 3e99999a/0.3
//! CHECK <name> <ok|FAIL> <detail>       an on-device self-check
//! STACK <bytes>                         peak stack use, measured by stack painting
//! END <results> <failed checks>
//! ```
//!
//! The host recomputes each `R` line from the printed argument bits, so the inputs live
//! only here in the firmware.

use core::fmt;
use cortex_m_semihosting::hprintln;

/// An `f32` shown as `bits/decimal`.
#[derive(Clone, Copy)]
pub struct Num(pub f32);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:08x}/{}", self.0.to_bits(), self.0)
    }
}

/// Args shown space-separated.
struct Args<'a>(&'a [f32]);

impl fmt::Display for Args<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for &a in self.0 {
            write!(f, " {}", Num(a))?;
        }
        Ok(())
    }
}

/// Prints the banner line.
#[inline(never)]
pub fn banner(math: &str) {
    hprintln!("BRDF-FW 1 math={}", math);
}

/// Prints one `TABLE` line.
#[inline(never)]
pub fn table(file: &str, len: usize, crc: u32) {
    hprintln!("TABLE {} {} {:08x}", file, len, crc);
}

/// Prints one `R` line.
#[inline(never)]
pub fn result(kernel: &str, args: &[f32], value: f32) {
    hprintln!("R {}{} = {}", kernel, Args(args), Num(value));
}

/// Prints one `CHECK` line and returns whether it passed.
#[inline(never)]
pub fn check(name: &str, ok: bool, detail: fmt::Arguments<'_>) -> bool {
    hprintln!(
        "CHECK {} {} {}",
        name,
        if ok { "ok" } else { "FAIL" },
        detail
    );
    ok
}

/// Prints the `STACK` and `END` lines.
#[inline(never)]
pub fn end(stack_bytes: usize, results: u32, failed: u32) {
    hprintln!("STACK {}", stack_bytes);
    hprintln!("END {} {}", results, failed);
}

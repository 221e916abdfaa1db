//! Peak stack measurement by painting: fill the unused stack with a pattern before the work,
//! then find the deepest word that was overwritten. cortex-m-rt's linker script provides
//! `_stack_start` (top, initial SP) and `_stack_end` (lowest address the stack may use).

use core::ptr::{addr_of, addr_of_mut};

const PAINT: u32 = 0xDEAD_BEEF;
/// Bytes below the current SP left unpainted (the painter's own frame).
const MARGIN: usize = 256;

extern "C" {
    static mut _stack_end: u32;
    static _stack_start: u32;
}

fn bottom() -> *mut u32 {
    addr_of_mut!(_stack_end)
}

/// Paints from the bottom of the stack region up to just below the current frame.
#[inline(never)]
pub fn paint() {
    let marker = 0u32;
    let sp = core::hint::black_box(addr_of!(marker)) as usize;
    let mut p = bottom();
    while (p as usize) + MARGIN < sp {
        // SAFETY: [_stack_end, sp − MARGIN) is unused stack memory inside RAM.
        unsafe { p.write_volatile(PAINT) };
        p = p.wrapping_add(1);
    }
}

/// Bytes of stack used since [`paint`]: from the deepest overwritten word to the top.
#[inline(never)]
pub fn peak_bytes() -> usize {
    let top = addr_of!(_stack_start) as usize;
    let mut p = bottom();
    // SAFETY: reads within the painted region and the live stack below `top`.
    while (p as usize) < top && unsafe { p.read_volatile() } == PAINT {
        p = p.wrapping_add(1);
    }
    top - p as usize
}

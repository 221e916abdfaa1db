//! The flash/RAM report from `llvm-size -A` and `llvm-nm`: every sized symbol attributed to
//! a group (kernels, LUT view, math, formatting, runtime, …) to separate the kernels' code
//! from the formatting code.

use crate::device::elf::{elf_sections, elf_symbols, with_commas};
use anyhow::Result;
use std::collections::BTreeMap;
use std::path::Path;

/// Flash budget for the kernels (G, Torrance–Sparrow, the LUT view, with libm), bytes.
pub const KERNEL_FLASH_BUDGET: u64 = 16 * 1024;

/// Where a symbol's bytes are counted. The first three make up "the kernels" of the budget.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
pub(crate) enum Group {
    /// Direct G and Torrance–Sparrow: brdf-core outside `lut`, the firmware's wrappers.
    KernelG,
    /// The LUT view: `brdf_lut` (header decoding, validation, CRC, interpolation) and
    /// the serde/postcard/heapless code it instantiates.
    KernelLut,
    /// Math shared by the kernels: libm or micromath, soft-float f64 helpers (libm's f32
    /// functions compute internally in f64).
    KernelMath,
    /// The anisotropic model (Ashikhmin–Shirley) and `powf`, which only it uses here; outside
    /// the kernel budget.
    Aniso,
    /// Embedded table bytes.
    TableData,
    /// core::fmt, float printing, the firmware's report module, semihosting, panics.
    Formatting,
    /// cortex-m-rt start-up, main, stack painting, memcpy and friends.
    Runtime,
    /// Unnamed constants (`.Lanon.*`: string pieces, numeric tables) of any origin.
    Anonymous,
}

impl Group {
    pub(crate) fn is_kernel(self) -> bool {
        matches!(self, Group::KernelG | Group::KernelLut | Group::KernelMath)
    }
}

pub(crate) fn classify(name: &str) -> Group {
    let has = |s: &str| name.contains(s);
    if has("brdf_firmware::TABLE_") {
        Group::TableData
    } else if name.starts_with(".L") {
        Group::Anonymous
    } else if has("ashikhmin") || has("AshikhminShirley") || has("::powf") {
        Group::Aniso
    } else if has("brdf_lut::")
        || has("kernels::g_table")
        || has("kernels::g_lut")
        || has("serde")
        || has("postcard::")
        || has("heapless::")
    {
        Group::KernelLut
    } else if has("brdf_core::") || has("brdf_firmware_kernels::") {
        Group::KernelG
    } else if has("libm::")
        || has("micromath::")
        || has("compiler_builtins::float::")
        || name.starts_with("__aeabi_d")
        || name.starts_with("__aeabi_f")
        || name.starts_with("__aeabi_i2d")
        || name.starts_with("__aeabi_ui2d")
        || name.starts_with("__aeabi_l2d")
        || name.starts_with("__aeabi_ul2d")
        || [
            "__adddf3",
            "__subdf3",
            "__muldf3",
            "__divdf3",
            "__extendsfdf2",
            "__truncdfsf2",
            "__fixdfsi",
            "__fixunsdfsi",
            "__floatsidf",
            "__floatunsidf",
            "__eqdf2",
            "__nedf2",
            "__ltdf2",
            "__ledf2",
            "__gtdf2",
            "__gedf2",
            "__unorddf2",
            "__cmpdf2",
        ]
        .contains(&name)
    {
        Group::KernelMath
    } else if has("core::fmt")
        || has("core::num::flt2dec")
        || has("core::num::fmt")
        || has("core::num::")
        || has("as core::fmt::")
        || has("brdf_firmware::report::")
        || has("cortex_m_semihosting::")
        || has("core::panicking")
        || has("core::panic")
        || has("core::str::")
        || has("core::slice::index")
        || has("core::result::unwrap_failed")
        || has("core::option::")
        || has("brdf_firmware::panic")
    {
        Group::Formatting
    } else {
        Group::Runtime
    }
}

pub(crate) struct Sizes {
    /// Section name → size from `llvm-size -A`.
    pub(crate) sections: BTreeMap<String, u64>,
    /// Group → (text bytes, rodata bytes) attributed through symbols.
    pub(crate) groups: BTreeMap<Group, (u64, u64)>,
    /// Flash bytes in .text + .rodata not attributed to any sized symbol.
    pub(crate) unattributed: u64,
    /// The largest kernel symbols (name, bytes).
    pub(crate) top_kernels: Vec<(String, u64)>,
    pub(crate) has_allocator: bool,
}

impl Sizes {
    pub(crate) fn sec(&self, s: &str) -> u64 {
        self.sections.get(s).copied().unwrap_or(0)
    }
    pub(crate) fn flash(&self) -> u64 {
        self.sec(".vector_table") + self.sec(".text") + self.sec(".rodata") + self.sec(".data")
    }
    pub(crate) fn static_ram(&self) -> u64 {
        self.sec(".data") + self.sec(".bss") + self.sec(".uninit")
    }
    pub(crate) fn group(&self, g: Group) -> u64 {
        self.groups.get(&g).map_or(0, |(t, r)| t + r)
    }
    pub(crate) fn kernels_flash(&self) -> u64 {
        self.group(Group::KernelG) + self.group(Group::KernelLut) + self.group(Group::KernelMath)
    }
}

pub(crate) fn sizes(elf: &Path) -> Result<Sizes> {
    let with_addr = elf_sections(elf)?;
    // (name, start, end) of the allocated flash sections, to attribute symbols by address.
    let ranges: Vec<(&str, u64, u64)> = [".text", ".rodata"]
        .into_iter()
        .filter_map(|n| with_addr.get(n).map(|&(len, a)| (n, a, a + len)))
        .collect();
    let mut groups: BTreeMap<Group, (u64, u64)> = BTreeMap::new();
    let mut kernels: Vec<(String, u64)> = Vec::new();
    let mut has_allocator = false;
    let mut attributed = 0u64;
    for sym in elf_symbols(elf)? {
        if sym.name.contains("__rust_alloc") || sym.name.contains("__rg_alloc") {
            has_allocator = true;
        }
        let addr = sym.addr & !1; // Thumb bit
        let Some((sec, _, _)) = ranges.iter().find(|(_, lo, hi)| (*lo..*hi).contains(&addr)) else {
            continue; // vector table, RAM, debug info
        };
        let g = classify(&sym.name);
        let e = groups.entry(g).or_default();
        if *sec == ".text" {
            e.0 += sym.size;
        } else {
            e.1 += sym.size;
        }
        attributed += sym.size;
        if g.is_kernel() || g == Group::Aniso {
            kernels.push((sym.name, sym.size));
        }
    }
    kernels.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    kernels.truncate(12);
    let sections: BTreeMap<String, u64> = with_addr.into_iter().map(|(k, v)| (k, v.0)).collect();
    let text_ro =
        sections.get(".text").copied().unwrap_or(0) + sections.get(".rodata").copied().unwrap_or(0);
    Ok(Sizes {
        sections,
        groups,
        unattributed: text_ro.saturating_sub(attributed),
        top_kernels: kernels,
        has_allocator,
    })
}

pub(crate) fn print_sizes(s: &Sizes, stack: Option<u64>, math: &str) {
    println!();
    println!("firmware[{math}] sizes (llvm-size -A; bytes):");
    for (k, v) in &s.sections {
        if !k.starts_with(".debug") && *v > 0 && k != ".comment" && k != ".ARM.attributes" {
            println!("  {k:<16} {v:>8}");
        }
    }
    println!(
        "  flash total {} B, static RAM (.data+.bss+.uninit) {} B, peak stack {} B, heap none",
        s.flash(),
        s.static_ram(),
        stack.map_or("?".into(), |v| v.to_string())
    );
    println!("| part ({math}) | code B | rodata B | flash B |");
    println!("|---|---:|---:|---:|");
    for (g, label) in [
        (Group::KernelG, "kernels: direct G, Torrance–Sparrow"),
        (
            Group::KernelLut,
            "kernels: LUT view (parse, CRC, lookup; serde/postcard)",
        ),
        (
            Group::KernelMath,
            "kernels: libm/micromath + soft-f64 helpers",
        ),
        (Group::Aniso, "anisotropic model (Ashikhmin–Shirley + powf)"),
        (Group::TableData, "embedded table bytes"),
        (
            Group::Formatting,
            "formatting (core::fmt, float printing, semihosting, panics)",
        ),
        (Group::Runtime, "runtime (cortex-m-rt, main, memcpy, …)"),
        (
            Group::Anonymous,
            "unnamed constants (.Lanon.*: strings, tables)",
        ),
    ] {
        let (t, r) = s.groups.get(&g).copied().unwrap_or((0, 0));
        println!("| {label} | {t} | {r} | {} |", t + r);
    }
    println!(
        "| unattributed (.text+.rodata without a sized symbol) | | | {} |",
        s.unattributed
    );
    println!(
        "| vector table | | | {} |",
        s.sections.get(".vector_table").copied().unwrap_or(0)
    );
    let k = s.kernels_flash();
    let verdict = if math != "libm" {
        "the budget applies to the libm build".to_string()
    } else if k <= KERNEL_FLASH_BUDGET {
        format!("within the {} KiB budget", KERNEL_FLASH_BUDGET / 1024)
    } else {
        format!(
            "OVER the {} KiB budget by {} B",
            KERNEL_FLASH_BUDGET / 1024,
            k - KERNEL_FLASH_BUDGET
        )
    };
    println!(
        "kernels (G, Torrance–Sparrow, LUT view): {k} B of flash ({:.1} KiB): {verdict}",
        k as f64 / 1024.0
    );
    println!("largest kernel symbols:");
    for (n, b) in &s.top_kernels {
        println!("  {b:>6}  {n}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::elf::tidy;

    #[test]
    fn classify_separates_kernels_from_formatting() {
        assert_eq!(
            classify("brdf_core::masking::modified::ModifiedG<T,R>::passing_cs"),
            Group::KernelG
        );
        assert_eq!(classify("brdf_lut::LutView::sample"), Group::KernelLut);
        assert_eq!(classify("libm::math::expf::expf"), Group::KernelMath);
        assert_eq!(classify("__aeabi_dmul"), Group::KernelMath);
        assert_eq!(classify("libm::math::powf::powf"), Group::Aniso);
        assert_eq!(
            classify("brdf_firmware_kernels::ashikhmin_shirley"),
            Group::Aniso
        );
        assert_eq!(classify("brdf_firmware_kernels::g_dots"), Group::KernelG);
        assert_eq!(classify("brdf_firmware_kernels::g_lut"), Group::KernelLut);
        assert_eq!(
            classify("core::fmt::float::float_to_decimal_common_shortest"),
            Group::Formatting
        );
        assert_eq!(classify("Reset"), Group::Runtime);
        assert_eq!(
            tidy("_$LT$brdf_firmware..report..Num$u20$as$u20$core..fmt..Display$GT$::fmt::h89d7b88652567c93"),
            "<brdf_firmware::report::Num as core::fmt::Display>::fmt"
        );
        assert_eq!(
            classify(&tidy(
                "_$LT$$RF$T$u20$as$u20$core..fmt..Display$GT$::fmt::hf5eaf33a05909de8"
            )),
            Group::Formatting
        );
    }
}

/// The README's size sentence: "… take 15,254 B of flash with libm … 8 B of static RAM".
const README_FLASH: &str = " B of flash with libm";
const README_RAM: &str = " B of static RAM";

/// The number written just before `marker` in `text` (digits and thousands commas), with
/// its byte range.
fn number_before(text: &str, marker: &str) -> Option<(u64, std::ops::Range<usize>)> {
    let end = text.find(marker)?;
    let start = text[..end]
        .rfind(|c: char| !(c.is_ascii_digit() || c == ','))
        .map_or(0, |i| i + 1);
    let v = text[start..end].replace(',', "").parse().ok()?;
    Some((v, start..end))
}

/// The README's (kernel flash, static RAM) figures, if the sentence is there.
pub(crate) fn readme_sizes(readme: &str) -> Option<(u64, u64)> {
    Some((
        number_before(readme, README_FLASH)?.0,
        number_before(readme, README_RAM)?.0,
    ))
}

/// The README with its figures replaced by `flash` and `ram`.
pub(crate) fn readme_with_sizes(readme: &str, flash: u64, ram: u64) -> Option<String> {
    let mut s = readme.to_string();
    // Replace the later figure first so the earlier range stays valid.
    let mut edits = [
        (number_before(&s, README_FLASH)?.1, with_commas(flash)),
        (number_before(&s, README_RAM)?.1, with_commas(ram)),
    ];
    edits.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    for (r, v) in edits {
        s.replace_range(r, &v);
    }
    Some(s)
}

#[cfg(test)]
mod readme_tests {
    use super::*;

    #[test]
    fn readme_figures_are_read_and_rewritten() {
        let t = "kernels take 15,254 B of flash with libm (budget\n  16 KiB), no heap, 8 B of static RAM.";
        assert_eq!(readme_sizes(t), Some((15254, 8)));
        let u = readme_with_sizes(t, 1_015_300, 16).unwrap();
        assert_eq!(
            u,
            "kernels take 1,015,300 B of flash with libm (budget\n  16 KiB), no heap, 16 B of static RAM."
        );
        assert_eq!(readme_sizes("no figures"), None);
    }
}

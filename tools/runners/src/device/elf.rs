//! Reading an ELF for the size reports of both runners: sections from `llvm-size -A`,
//! sized symbols from `llvm-nm` (names demangled and tidied), and the README's way of
//! writing a byte count.

use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

pub(crate) fn llvm_tool(name: &str) -> Result<PathBuf> {
    let mut cands: Vec<PathBuf> = vec![PathBuf::from(format!("/usr/bin/{name}"))];
    for v in (14..=21).rev() {
        cands.push(PathBuf::from(format!("/usr/lib/llvm-{v}/bin/{name}")));
    }
    if let Some(p) = std::env::var_os("PATH") {
        for d in std::env::split_paths(&p) {
            cands.push(d.join(name));
        }
    }
    cands
        .into_iter()
        .find(|p| p.is_file())
        .with_context(|| format!("{name} not found (apt-get install llvm)"))
}

/// Stdout of a tool that reads an ELF (`what` names it in the messages).
pub(crate) fn stdout_of(cmd: &mut Command, what: &str) -> Result<String> {
    let out = cmd.output().with_context(|| format!("running {what}"))?;
    if !out.status.success() {
        bail!("{what} failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Stdout of an LLVM binary tool run on `elf`.
fn tool_output(tool: &str, args: &[&str], elf: &Path) -> Result<String> {
    stdout_of(Command::new(llvm_tool(tool)?).args(args).arg(elf), tool)
}

/// The ELF's sections from `llvm-size -A`: name → (size, address), in bytes.
pub(crate) fn elf_sections(elf: &Path) -> Result<BTreeMap<String, (u64, u64)>> {
    let mut sections = BTreeMap::new();
    for l in tool_output("llvm-size", &["-A"], elf)?.lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.len() == 3 && f[0].starts_with('.') {
            if let (Ok(n), Ok(addr)) = (f[1].parse::<u64>(), f[2].parse::<u64>()) {
                sections.insert(f[0].to_string(), (n, addr));
            }
        }
    }
    Ok(sections)
}

/// A defined, sized symbol from `llvm-nm` (name demangled and tidied).
pub(crate) struct Symbol {
    pub(crate) addr: u64,
    pub(crate) size: u64,
    /// nm's type letter (`t`/`T` code, `r`/`R` read-only data, `d`/`D` data, …).
    pub(crate) ty: String,
    pub(crate) name: String,
}

/// The ELF's defined symbols that have a size.
pub(crate) fn elf_symbols(elf: &Path) -> Result<Vec<Symbol>> {
    let text = tool_output(
        "llvm-nm",
        &["--print-size", "--demangle", "--defined-only"],
        elf,
    )?;
    let mut syms = Vec::new();
    for l in text.lines() {
        // "<addr> <size> <type> <name…>"
        let mut it = l.splitn(4, ' ');
        let (Some(addr), Some(size), Some(ty), Some(raw)) =
            (it.next(), it.next(), it.next(), it.next())
        else {
            continue;
        };
        let (Ok(addr), Ok(size)) = (u64::from_str_radix(addr, 16), u64::from_str_radix(size, 16))
        else {
            continue;
        };
        let (ty, name) = (ty.to_string(), tidy(raw));
        syms.push(Symbol {
            addr,
            size,
            ty,
            name,
        });
    }
    Ok(syms)
}

/// Finishes what llvm-nm's demangler leaves of Rust's legacy mangling (`$LT$`, `..`, …)
/// and drops the trailing `::h<hash>`.
pub(crate) fn tidy(name: &str) -> String {
    let mut n = name
        .strip_prefix('_')
        .filter(|r| r.starts_with('$'))
        .unwrap_or(name)
        .to_string();
    for (from, to) in [
        ("$LT$", "<"),
        ("$GT$", ">"),
        ("$u20$", " "),
        ("$C$", ","),
        ("$RF$", "&"),
        ("$BP$", "*"),
        ("$SP$", "@"),
        ("$u27$", "'"),
        ("$u5b$", "["),
        ("$u5d$", "]"),
        ("$u7b$", "{"),
        ("$u7d$", "}"),
        ("$u3b$", ";"),
        ("$u21$", "!"),
        ("$u2b$", "+"),
        ("..", "::"),
    ] {
        n = n.replace(from, to);
    }
    if let Some(i) = n.rfind("::h") {
        let h = &n[i + 3..];
        if h.len() == 16 && h.bytes().all(|b| b.is_ascii_hexdigit()) {
            n.truncate(i);
        }
    }
    n
}

/// `1234567` → `1,234,567` (the README's style).
pub(crate) fn with_commas(v: u64) -> String {
    let d = v.to_string();
    let mut out = String::new();
    for (i, c) in d.chars().enumerate() {
        if i > 0 && (d.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_commas_groups_digits_in_threes() {
        assert_eq!(with_commas(0), "0");
        assert_eq!(with_commas(999), "999");
        assert_eq!(with_commas(1000), "1,000");
        assert_eq!(with_commas(132_510), "132,510");
        assert_eq!(with_commas(1_234_567), "1,234,567");
    }
}

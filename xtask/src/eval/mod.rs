//! `cargo xtask eval <kernel>`: CSV in on stdin, CSV out on stdout.
//!
//! All three commands read their input with [`for_each_row`]: one reader with one set of
//! rules (line cap, BOM, header, blank lines, field count, error wording).

use anyhow::{anyhow, bail, Result};
use clap::Subcommand;
use std::io::{BufRead, Read};

mod brdf;
mod dfg;
mod g;

/// The `eval` subcommands (nested under `cargo xtask eval`).
#[derive(Subcommand)]
pub enum What {
    /// The modified G (GM, GS, G) with Blinn's and Smith's G, from `theta_i_deg,theta_r_deg,sigma` rows.
    G(g::Args),
    /// A BRDF model from `wi_x,wi_y,wi_z,wo_x,wo_y,wo_z` rows (local frame, z = normal).
    Brdf(brdf::Args),
    /// Split-sum (A, B) from `mu,roughness` rows.
    Dfg(dfg::Args),
}

pub fn run(what: What) -> anyhow::Result<()> {
    match what {
        What::G(a) => g::run(a),
        What::Brdf(a) => brdf::run(a),
        What::Dfg(a) => dfg::run(a),
    }
}

/// The longest input line accepted, in bytes without its line ending. Rows of a few numbers
/// are far shorter; the cap keeps a stream without line breaks (a binary file, a stream of
/// NUL bytes) from being buffered whole.
pub const MAX_LINE: usize = 4096;

/// Reads comma-separated rows of `columns.len()` fields from `input` and calls
/// `row(lineno, fields)` for each, with 1-based line numbers and trimmed fields.
///
/// Rules: a UTF-8 byte-order mark at the start is skipped; blank lines are skipped; a first
/// line whose first field is `columns[0]` is the header and skipped; `\r\n` endings are
/// accepted; a line longer than [`MAX_LINE`] bytes, a line that is not UTF-8 or a row with
/// another number of fields is an error naming the line.
pub fn for_each_row(
    mut input: impl BufRead,
    columns: &[&str],
    mut row: impl FnMut(usize, &[&str]) -> Result<()>,
) -> Result<()> {
    let mut buf = Vec::with_capacity(256);
    let mut lineno = 0usize;
    loop {
        buf.clear();
        lineno += 1;
        let n = (&mut input)
            .take(MAX_LINE as u64 + 2)
            .read_until(b'\n', &mut buf)
            .map_err(|e| anyhow!("line {lineno}: reading the input: {e}"))?;
        if n == 0 {
            return Ok(());
        }
        let mut line: &[u8] = &buf;
        if let Some(l) = line.strip_suffix(b"\n") {
            line = l.strip_suffix(b"\r").unwrap_or(l);
        } else if line.len() > MAX_LINE {
            bail!(
                "line {lineno}: longer than {MAX_LINE} bytes; the input must be CSV rows of \
                 {} numbers ({})",
                columns.len(),
                columns.join(",")
            );
        }
        if line.len() > MAX_LINE {
            bail!("line {lineno}: longer than {MAX_LINE} bytes");
        }
        if lineno == 1 {
            line = line.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(line);
        }
        let text = std::str::from_utf8(line)
            .map_err(|_| anyhow!("line {lineno}: not UTF-8 text"))?
            .trim();
        if text.is_empty() {
            continue;
        }
        let fields: Vec<&str> = text.split(',').map(str::trim).collect();
        if lineno == 1 && fields[0] == columns[0] {
            continue;
        }
        if fields.len() != columns.len() {
            bail!(
                "line {lineno}: expected {} fields {}, found {}",
                columns.len(),
                columns.join(","),
                fields.len()
            );
        }
        row(lineno, &fields)?;
    }
}

/// Parses field `i` of a row as a finite number; the error names the line and the column.
pub fn number(fields: &[&str], i: usize, name: &str, lineno: usize) -> Result<f64> {
    let v: f64 = fields[i]
        .parse()
        .map_err(|_| anyhow!("line {lineno}: {name} `{}` is not a number", fields[i]))?;
    if !v.is_finite() {
        bail!("line {lineno}: {name} is not finite");
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(input: &[u8]) -> Result<Vec<(usize, Vec<String>)>> {
        let mut v = Vec::new();
        for_each_row(input, &["mu", "roughness"], |n, f| {
            v.push((n, f.iter().map(|s| s.to_string()).collect()));
            Ok(())
        })?;
        Ok(v)
    }

    #[test]
    fn bom_header_crlf_and_blank_lines() {
        let r = rows(b"\xEF\xBB\xBFmu,roughness\r\n0.5, 0.25\r\n\r\n1,0\n").unwrap();
        assert_eq!(
            r,
            vec![
                (2, vec!["0.5".into(), "0.25".into()]),
                (4, vec!["1".into(), "0".into()])
            ]
        );
        // A BOM before data (no header) is not part of the first number.
        let r = rows(b"\xEF\xBB\xBF0.5,0.25").unwrap();
        assert_eq!(r, vec![(1, vec!["0.5".into(), "0.25".into()])]);
    }

    #[test]
    fn field_count_and_utf8_errors_name_the_line() {
        let e = rows(b"0.5,0.25\n0.5\n").unwrap_err().to_string();
        assert!(
            e.starts_with("line 2: expected 2 fields mu,roughness, found 1"),
            "{e}"
        );
        let e = rows(b"0.5,0.25\n\xff,1\n").unwrap_err().to_string();
        assert!(e.starts_with("line 2: not UTF-8"), "{e}");
    }

    #[test]
    fn endless_line_is_refused_with_bounded_reading() {
        // 1 GiB of NUL bytes, produced lazily: the reader must stop after the cap, having
        // consumed only a few KiB of it.
        struct Zeros(u64);
        impl Read for Zeros {
            fn read(&mut self, b: &mut [u8]) -> std::io::Result<usize> {
                let n = (b.len() as u64).min(self.0) as usize;
                b[..n].fill(0);
                self.0 -= n as u64;
                Ok(n)
            }
        }
        let mut src = std::io::BufReader::new(Zeros(1 << 30));
        let e = for_each_row(&mut src, &["mu", "roughness"], |_, _| Ok(()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("longer than 4096 bytes"), "{e}");
        let left = src.get_ref().0;
        assert!(
            (1u64 << 30) - left < 64 * 1024,
            "read {} bytes",
            (1u64 << 30) - left
        );
        // A line of exactly the cap is accepted (and then fails as a row, not as a length).
        let mut l = vec![b'1'; MAX_LINE];
        l.push(b'\n');
        let e = rows(&l).unwrap_err().to_string();
        assert!(e.contains("expected 2 fields"), "{e}");
    }
}

//! Turns PLY problems into `file:line:col` errors.
//!
//! `ply-rs-bw` reports a line number and, inside its message, the parser's column; those become
//! the error's location. Problems found after parsing (a non-finite coordinate, a face index out
//! of range) are located in ASCII files by counting records after `end_header`; binary files
//! have no lines, so they name the file and the record.
use crate::error::{InputError, Loc};
use ply_rs_bw::parser::ParseError;
use ply_rs_bw::ply::{Encoding, Header};
use std::path::Path;
use std::sync::Arc;

/// A parser error, located at its line (and column when the parser gave one). Lines past the
/// header of a binary file mean nothing to a reader, so those errors name the file only.
pub(crate) fn parse_error(path: &Path, bytes: &[u8], e: &ParseError) -> InputError {
    let text = e.to_string();
    // Messages look like "Line 11: What went wrong.\n\tString: 'the line'\n\tError: ...".
    let body = text.split_once(": ").map_or(text.as_str(), |(_, b)| b);
    let what = body.split('\n').next().unwrap_or(body).trim();
    let what = what.strip_suffix('.').unwrap_or(what);
    let line_str = body
        .split_once("String: '")
        .and_then(|(_, rest)| rest.split_once('\''))
        .map(|(s, _)| s.trim_end());
    let msg = match line_str {
        Some(s) => format!("bad PLY file: {what}: {s:?}"),
        None => format!("bad PLY file: {what}"),
    };
    match e.line().filter(|&l| !in_binary_payload(bytes, l)) {
        Some(line) => {
            let col = parser_column(body).unwrap_or(1);
            InputError::at(
                &Loc::new(Arc::new(path.to_path_buf()), line as u32, col),
                msg,
            )
        }
        None => InputError::file(path, msg),
    }
}

/// Whether 1-based `line` lies after `end_header` in a file whose header says it is binary.
fn in_binary_payload(bytes: &[u8], line: usize) -> bool {
    let head = &bytes[..bytes.len().min(1 << 16)];
    let head = String::from_utf8_lossy(head);
    let mut lines = head.split('\n').map(str::trim_end);
    let Some(end) = lines.clone().position(|l| l == "end_header") else {
        return false;
    };
    let binary = lines.any(|l| l.starts_with("format binary"));
    binary && line > end + 1
}

/// The column inside the offending line, from the parser's "error at 1:COL" or
/// "column: COL" text.
fn parser_column(body: &str) -> Option<u32> {
    let digits = |s: &str| -> Option<u32> {
        let end = s.find(|c: char| !c.is_ascii_digit()).unwrap_or(s.len());
        s[..end].parse().ok()
    };
    if let Some((_, rest)) = body.split_once("error at ") {
        return rest.split_once(':').and_then(|(_, c)| digits(c));
    }
    body.split_once("column: ").and_then(|(_, c)| digits(c))
}

/// An error about record `index` of element `element`; `token` picks the whitespace-separated
/// value on that record's line to point at (ASCII files), or the line's start when `None`.
pub(crate) fn record_error(
    path: &Path,
    bytes: &[u8],
    header: &Header,
    element: &str,
    index: usize,
    token: Option<usize>,
    msg: String,
) -> InputError {
    let located = (header.encoding == Encoding::Ascii)
        .then(|| record_line(bytes, header, element, index))
        .flatten();
    let Some((line_no, line)) = located else {
        return InputError::file(path, format!("{element} {index}: {msg}"));
    };
    let col = token.and_then(|k| token_column(line, k)).unwrap_or(1);
    InputError::at(&Loc::new(Arc::new(path.to_path_buf()), line_no, col), msg)
}

/// The 1-based line number and text of record `index` of `element` in an ASCII PLY file:
/// records follow `end_header` one per line, elements in header order.
fn record_line<'a>(
    bytes: &'a [u8],
    header: &Header,
    element: &str,
    index: usize,
) -> Option<(u32, &'a str)> {
    let mut skip = index;
    for (name, def) in &header.elements {
        if name == element {
            break;
        }
        skip = skip.checked_add(def.count)?;
    }
    let text = std::str::from_utf8(bytes).ok()?;
    let mut lines = text.split('\n').enumerate();
    lines.by_ref().find(|(_, l)| l.trim_end() == "end_header")?;
    let (i, line) = lines.nth(skip)?;
    Some((u32::try_from(i + 1).ok()?, line.trim_end_matches('\r')))
}

/// The 1-based column where the `k`-th whitespace-separated token of `line` starts.
fn token_column(line: &str, k: usize) -> Option<u32> {
    let mut count = 0;
    let mut in_token = false;
    for (i, c) in line.char_indices() {
        let ws = c.is_whitespace();
        if !ws && !in_token {
            if count == k {
                return u32::try_from(line[..i].chars().count() + 1).ok();
            }
            count += 1;
        }
        in_token = !ws;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn token_columns() {
        assert_eq!(token_column("1 0 abc", 2), Some(5));
        assert_eq!(token_column("  3  0 1 2", 0), Some(3));
        assert_eq!(token_column("  3  0 1 2", 1), Some(6));
        assert_eq!(token_column("1 2", 2), None);
    }

    #[test]
    fn parser_columns() {
        assert_eq!(parser_column("x\tError: error at 1:5: expected"), Some(5));
        assert_eq!(
            parser_column("Error: ParseError { location: LineCol { line: 1, column: 15, o"),
            Some(15)
        );
        assert_eq!(parser_column("no column here"), None);
    }

    #[test]
    fn binary_payload_lines() {
        let bin = b"ply\nformat binary_little_endian 1.0\nend_header\n\x01\n\x02";
        assert!(!in_binary_payload(bin, 3));
        assert!(in_binary_payload(bin, 4));
        let ascii = b"ply\nformat ascii 1.0\nend_header\n0\n";
        assert!(!in_binary_payload(ascii, 4));
    }
}

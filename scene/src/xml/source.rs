//! One XML source file in memory: reading it (with a size limit), parsing it with roxmltree,
//! and turning byte offsets into `file:line:col` locations quickly.
//!
//! roxmltree's own `text_pos_at` rescans the text from the start on every call, which is
//! quadratic over a whole file, so this module keeps a line table and a character-count table.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::error::{InputError, Loc};

/// The largest scene file accepted (64 MiB).
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;

/// Bytes between two entries of the character-count table.
const CHUNK: usize = 4096;

/// Reads a whole text file, refusing files over [`MAX_FILE_BYTES`]: checked before reading and
/// while reading, so a stream of unknown size (a pipe, `/dev/zero`) stops at the limit too.
///
/// Errors are `Err(message)` without location; the caller decides where to attach them.
pub(crate) fn read_text(path: &Path) -> Result<String, String> {
    use std::io::Read;
    let f = std::fs::File::open(path).map_err(|e| format!("cannot read file: {e}"))?;
    let meta = f.metadata().map_err(|e| format!("cannot read file: {e}"))?;
    if meta.is_dir() {
        return Err("cannot read file: it is a directory".to_string());
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    f.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read file: {e}"))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(format!(
            "file is too large (over {MAX_FILE_BYTES} bytes; the limit is 64 MiB)"
        ));
    }
    String::from_utf8(bytes).map_err(|_| "cannot read file: it is not UTF-8 text".to_string())
}

/// Refuses a text over [`MAX_FILE_BYTES`].
pub(crate) fn check_size(text: &str) -> Result<(), String> {
    if text.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(text.len() as u64));
    }
    Ok(())
}

fn too_large(len: u64) -> String {
    format!("file is too large ({len} bytes; the limit is 64 MiB)")
}

/// Parses XML text, converting roxmltree's errors into located [`InputError`]s.
pub(crate) fn parse_document<'t>(
    text: &'t str,
    file: &Arc<PathBuf>,
) -> Result<roxmltree::Document<'t>, InputError> {
    let opts = roxmltree::ParsingOptions {
        allow_dtd: false,
        ..Default::default()
    };
    roxmltree::Document::parse_with_options(text, opts).map_err(|e| convert_error(&e, file, text))
}

/// Converts a roxmltree error: `file:line:col: message` when it has a position.
fn convert_error(e: &roxmltree::Error, file: &Arc<PathBuf>, text: &str) -> InputError {
    use roxmltree::Error as E;
    let full = match e {
        E::DtdDetected => {
            // roxmltree gives no position: point at the `<!DOCTYPE` when it can be found.
            let msg = "XML DTDs (<!DOCTYPE ...>) are not supported";
            return match text.find("<!DOCTYPE") {
                Some(at) => {
                    let before = &text[..at];
                    let line = before.matches('\n').count() as u32 + 1;
                    let start = before.rfind('\n').map_or(0, |i| i + 1);
                    let col = text[start..at].chars().count() as u32 + 1;
                    InputError::at(&Loc::new(file.clone(), line, col), msg)
                }
                None => InputError::file(file, msg),
            };
        }
        E::NoRootNode => return InputError::file(file, "the file contains no XML element"),
        E::UnclosedRootNode => {
            // roxmltree gives no position: the problem shows at the end of the text.
            let line = text.lines().count().max(1) as u32;
            let col = text.lines().last().map_or(0, |l| l.chars().count()) as u32 + 1;
            return InputError::at(
                &Loc::new(file.clone(), line, col),
                "XML error: the file ends before the root element is closed",
            );
        }
        other => other.to_string(),
    };
    let pos = e.pos();
    let suffix = format!(" at {pos}");
    match full.find(&suffix) {
        Some(i) => {
            let msg = format!("XML error: {}{}", &full[..i], &full[i + suffix.len()..]);
            InputError::at(&Loc::new(file.clone(), pos.row, pos.col), msg)
        }
        None => InputError::file(file, format!("XML error: {full}")),
    }
}

/// A parsed file's name and a fast offset-to-position table.
pub(crate) struct Source<'t> {
    /// The file's path as given (used in every location).
    pub file: Arc<PathBuf>,
    /// The directory relative paths (includes) are resolved against.
    pub dir: PathBuf,
    /// Byte offset of the start of each line.
    line_starts: Vec<usize>,
    /// `chars_before[k]` = number of characters in `text[..k * CHUNK]`.
    chars_before: Vec<u32>,
    /// The whole text.
    text: &'t str,
}

impl<'t> Source<'t> {
    /// Indexes `text`, which was read from `file`.
    pub fn new(file: Arc<PathBuf>, text: &'t str) -> Self {
        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
        let bytes = text.as_bytes();
        let mut line_starts = vec![0];
        line_starts.extend(newline_offsets(bytes));
        let mut chars_before = Vec::with_capacity(bytes.len() / CHUNK + 2);
        let mut count = 0u32;
        for chunk in bytes.chunks(CHUNK) {
            chars_before.push(count);
            count += count_chars(chunk);
        }
        chars_before.push(count);
        Source {
            file,
            dir,
            line_starts,
            chars_before,
            text,
        }
    }

    /// The location of byte offset `pos`.
    pub fn loc(&self, pos: usize) -> Loc {
        let pos = pos.min(self.text.len());
        let line = self.line_starts.partition_point(|&s| s <= pos); // >= 1
        let start = self.line_starts[line - 1];
        let col = self.chars_upto(pos) - self.chars_upto(start) + 1;
        Loc::new(self.file.clone(), line as u32, col)
    }

    /// Number of characters in `text[..pos]`.
    fn chars_upto(&self, pos: usize) -> u32 {
        let k = pos / CHUNK;
        self.chars_before[k] + count_chars(&self.text.as_bytes()[k * CHUNK..pos])
    }

    /// The whole text.
    pub fn text(&self) -> &'t str {
        self.text
    }
}

/// Offsets just after each `\n`.
fn newline_offsets(bytes: &[u8]) -> impl Iterator<Item = usize> + '_ {
    bytes
        .iter()
        .enumerate()
        .filter(|(_, &b)| b == b'\n')
        .map(|(i, _)| i + 1)
}

/// Number of UTF-8 characters that start in `bytes` (non-continuation bytes).
fn count_chars(bytes: &[u8]) -> u32 {
    bytes.iter().filter(|&&b| (b & 0xC0) != 0x80).count() as u32
}

/// The canonical form of a path when it exists, else the path itself (how the parser knows a
/// file it is already reading, to refuse include cycles).
pub(super) fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loc_matches_roxmltree() {
        let mut text = String::from("<a>\n  <b x='é'/>\r\n<c/>\n");
        for i in 0..3000 {
            text.push_str(&format!("<d{i} v='ü€{i}'/>"));
        }
        text.push_str("\n</a>");
        let file = Arc::new(PathBuf::from("t.xml"));
        let doc = parse_document(&text, &file).unwrap();
        let src = Source::new(file, &text);
        for pos in (0..text.len())
            .filter(|&p| text.is_char_boundary(p))
            .step_by(7)
        {
            let want = doc.text_pos_at(pos);
            let got = src.loc(pos);
            assert_eq!((got.line, got.col), (want.row, want.col), "at byte {pos}");
        }
    }

    #[test]
    fn xml_error_is_located() {
        let file = Arc::new(PathBuf::from("bad.xml"));
        let err = parse_document("<scene>\n  <float name='a' value='1'>\n</scene>", &file)
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("bad.xml:3:"), "{err}");
        assert!(!err.contains(" at 3:"), "{err}");
        let err = parse_document("", &file).unwrap_err().to_string();
        assert!(err.starts_with("bad.xml: "), "{err}");
    }
}

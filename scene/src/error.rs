//! Errors about bad input (scene files, command-line values): located, one line each.
//!
//! An [`InputError`] is what the user gets to see when a scene cannot be loaded. It prints as a
//! single line, `file:line:col: message`, so editors and terminals can jump to the spot. The
//! program exits with [`InputError::EXIT_CODE`] when it reports one.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A position in a source file (1-based line and column).
#[derive(Clone, Debug, PartialEq)]
pub struct Loc {
    /// The file the position is in.
    pub file: Arc<PathBuf>,
    /// 1-based line number.
    pub line: u32,
    /// 1-based column number (in characters).
    pub col: u32,
}

impl Loc {
    /// A position in `file`.
    pub fn new(file: Arc<PathBuf>, line: u32, col: u32) -> Self {
        Loc { file, line, col }
    }
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.col)
    }
}

/// Bad input (exit code 2).
///
/// Displays as exactly one line: `file:line:col: message` when the location is known,
/// `file: message` when only the file is known, or just `message`.
#[derive(Clone, Debug)]
pub struct InputError {
    /// Where in a file the problem is, if known.
    pub loc: Option<Loc>,
    /// Which file the problem is in, when there is no precise location.
    pub file: Option<PathBuf>,
    /// What is wrong (never contains a newline).
    pub msg: String,
}

/// Replaces line breaks with spaces, so a message stays on one line.
fn one_line(s: &str) -> String {
    if s.contains(['\n', '\r']) {
        s.replace("\r\n", " ").replace(['\n', '\r'], " ")
    } else {
        s.to_string()
    }
}

impl InputError {
    /// The process exit code for bad input.
    pub const EXIT_CODE: i32 = 2;

    /// An error at a position in a file.
    pub fn at(loc: &Loc, msg: impl Into<String>) -> Self {
        InputError {
            loc: Some(loc.clone()),
            file: None,
            msg: one_line(&msg.into()),
        }
    }

    /// An error about a whole file.
    pub fn file(path: &Path, msg: impl Into<String>) -> Self {
        InputError {
            loc: None,
            file: Some(path.to_path_buf()),
            msg: one_line(&msg.into()),
        }
    }

    /// An error with no file attached (for example a bad command-line value).
    pub fn plain(msg: impl Into<String>) -> Self {
        InputError {
            loc: None,
            file: None,
            msg: one_line(&msg.into()),
        }
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match (&self.loc, &self.file) {
            (Some(loc), _) => format!("{loc}: {}", self.msg),
            (None, Some(file)) => format!("{}: {}", file.display(), self.msg),
            (None, None) => self.msg.clone(),
        };
        // The fields are public, so enforce the one-line rule here too.
        f.write_str(&one_line(&text))
    }
}

impl std::error::Error for InputError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_forms() {
        let loc = Loc::new(Arc::new(PathBuf::from("a/scene.xml")), 12, 5);
        assert_eq!(loc.to_string(), "a/scene.xml:12:5");
        assert_eq!(
            InputError::at(&loc, "bad").to_string(),
            "a/scene.xml:12:5: bad"
        );
        assert_eq!(
            InputError::file(Path::new("x.xml"), "cannot read file").to_string(),
            "x.xml: cannot read file"
        );
        assert_eq!(InputError::plain("oops").to_string(), "oops");
    }

    #[test]
    fn never_multiline() {
        let e = InputError::plain("a\nb\r\nc\rd");
        assert_eq!(e.msg, "a b c d");
        let mut e = InputError::plain("x");
        e.msg = "p\nq".into();
        assert_eq!(e.to_string(), "p q");
    }
}

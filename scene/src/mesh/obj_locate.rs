//! Finds the line and column of what made an OBJ file unreadable, for the error message.
//!
//! `tobj` reports what went wrong but not where; when it fails (or yields a non-finite number),
//! this pass re-reads the text and names the first offending token.
use crate::error::{InputError, Loc};
use std::path::Path;
use std::sync::Arc;

/// The first malformed number, non-finite coordinate or out-of-range face index, if any.
pub(crate) fn locate_obj_error(path: &Path, text: &str) -> Option<InputError> {
    let file = Arc::new(path.to_path_buf());
    let counts = |kw: &str| {
        text.lines()
            .filter(|l| l.split_whitespace().next() == Some(kw))
            .count() as i64
    };
    let (nv, nvt, nvn) = (counts("v"), counts("vt"), counts("vn"));
    for (ln, line) in text.lines().enumerate() {
        let mut col = 0usize;
        let tokens: Vec<(usize, &str)> = line
            .split(|c: char| c.is_whitespace())
            .map(|t| {
                let c = col;
                col += t.len() + 1;
                (c, t)
            })
            .filter(|(_, t)| !t.is_empty())
            .collect();
        let Some(&(_, kw)) = tokens.first() else {
            continue;
        };
        let at = |c: usize, msg: String| {
            Some(InputError::at(
                &Loc::new(file.clone(), ln as u32 + 1, c as u32 + 1),
                msg,
            ))
        };
        match kw {
            "v" | "vn" | "vt" => {
                for &(c, t) in &tokens[1..] {
                    match t.parse::<f32>() {
                        Ok(v) if v.is_finite() => {}
                        Ok(_) => return at(c, format!("non-finite number {t:?} in vertex data")),
                        Err(_) => return at(c, format!("cannot read {t:?} as a number")),
                    }
                }
            }
            "f" => {
                if tokens.len() < 4 {
                    return at(tokens[0].0, "a face needs at least three vertices".into());
                }
                for &(c, t) in &tokens[1..] {
                    for (k, part) in t.split('/').enumerate() {
                        if part.is_empty() && k > 0 {
                            continue;
                        }
                        let n = [nv, nvt, nvn].get(k).copied().unwrap_or(0);
                        let what = ["vertex", "texture coordinate", "normal"]
                            .get(k)
                            .copied()
                            .unwrap_or("index");
                        match part.parse::<i64>() {
                            Ok(i) if (i > 0 && i <= n) || (i < 0 && -i <= n) => {}
                            Ok(i) => {
                                return at(
                                    c,
                                    format!("face refers to {what} {i}, but the file has {n}"),
                                )
                            }
                            Err(_) => {
                                return at(c, format!("cannot read {part:?} as a face index"))
                            }
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}

//! Mitsuba 3's curve files, as its `linearcurve` and `bsplinecurve` read them: one control
//! point per line, `x y z radius`, blank lines (or lines of whitespace) separating curves.
//! Every malformed line is an error at its line and column: a count of numbers other than four,
//! a token that is not a number, a value that is not finite, a negative radius; so is a curve
//! with fewer points than its kind needs (at its first line) and a file without points.
use crate::error::{InputError, Loc};
use std::path::Path;
use std::sync::Arc;

/// The control points of a curve file, grouped into curves.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveData {
    /// Every control point: position and radius, in file order.
    pub points: Vec<[f32; 4]>,
    /// Per curve: its first point's index and its number of points.
    pub curves: Vec<(usize, usize)>,
}

/// Reads a curve file whose curves need at least `min_points` points each (`kind` names them
/// in errors, "linear curve" or "B-spline curve").
pub fn load_curves(path: &Path, min_points: usize, kind: &str) -> Result<CurveData, InputError> {
    let text = crate::xml::source::read_text(path).map_err(|msg| InputError::file(path, msg))?;
    parse_curves(&text, path, min_points, kind)
}

/// Parses the text of a curve file (`path` locates errors).
pub fn parse_curves(
    text: &str,
    path: &Path,
    min_points: usize,
    kind: &str,
) -> Result<CurveData, InputError> {
    let file = Arc::new(path.to_path_buf());
    let at = |line: usize, col: usize, msg: String| {
        InputError::at(
            &Loc::new(file.clone(), line as u32 + 1, col as u32 + 1),
            msg,
        )
    };
    let mut points = Vec::new();
    let mut curves: Vec<(usize, usize)> = Vec::new();
    let mut first_line = Vec::new();
    let mut open = false;
    for (ln, line) in text.split('\n').enumerate() {
        let line = line.strip_suffix('\r').unwrap_or(line);
        let mut values = [0f32; 4];
        let mut count = 0;
        for (col, tok) in tokens(line) {
            if count == 4 {
                return Err(at(
                    ln,
                    col,
                    format!(
                        "a {kind} control point has four numbers (x y z radius), this line has \
                         more: \"{tok}\""
                    ),
                ));
            }
            let v: f32 = tok.parse().map_err(|_| {
                at(
                    ln,
                    col,
                    format!("\"{tok}\" is not a number (a {kind} control point is x y z radius)"),
                )
            })?;
            if !v.is_finite() {
                return Err(at(ln, col, format!("\"{tok}\" is not a finite number")));
            }
            if count == 3 && v < 0.0 {
                return Err(at(ln, col, format!("the radius {tok} is negative")));
            }
            values[count] = v;
            count += 1;
        }
        if count == 0 {
            open = false;
            continue;
        }
        if count < 4 {
            return Err(at(
                ln,
                line.len(),
                format!(
                    "a {kind} control point has four numbers (x y z radius), this line has \
                     {count}"
                ),
            ));
        }
        if !open {
            curves.push((points.len(), 0));
            first_line.push(ln);
            open = true;
        }
        points.push(values);
        curves.last_mut().expect("a curve is open").1 += 1;
    }
    if points.is_empty() {
        return Err(InputError::file(
            path,
            format!("the {kind} file has no control points"),
        ));
    }
    for (i, &(_, n)) in curves.iter().enumerate() {
        if n < min_points {
            return Err(at(
                first_line[i],
                0,
                format!(
                    "this {kind} has {n} control point{}, it needs at least {min_points}",
                    if n == 1 { "" } else { "s" }
                ),
            ));
        }
    }
    Ok(CurveData { points, curves })
}

/// The whitespace-separated tokens of a line with their byte columns.
fn tokens(line: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut rest = line;
    let mut offset = 0;
    std::iter::from_fn(move || {
        let start = rest.find(|c: char| !c.is_whitespace())?;
        let tail = &rest[start..];
        let len = tail.find(char::is_whitespace).unwrap_or(tail.len());
        let tok = &tail[..len];
        let col = offset + start;
        offset += start + len;
        rest = &tail[len..];
        Some((col, tok))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str, min: usize) -> Result<CurveData, String> {
        parse_curves(text, Path::new("c.txt"), min, "linear curve").map_err(|e| e.to_string())
    }

    #[test]
    fn curves_are_split_by_blank_lines() {
        let d = parse(
            "0 0 0 1\n1 0 0 1\n\n \t\n2 0 0 0.5\r\n3 0 0 0.5\n4 0 0 0.5\n",
            2,
        )
        .unwrap();
        assert_eq!(d.curves, vec![(0, 2), (2, 3)]);
        assert_eq!(d.points[4], [4.0, 0.0, 0.0, 0.5]);
    }

    #[test]
    fn malformed_lines_are_located() {
        let cases = [
            ("0 0 0 1\n1 0 0\n", 2, "c.txt:2:6", "this line has 3"),
            ("0 0 0 1\n1 0 0 1 7\n", 2, "c.txt:2:9", "has more: \"7\""),
            (
                "0 0 0 1\n1 x 0 1\n",
                2,
                "c.txt:2:3",
                "\"x\" is not a number",
            ),
            (
                "0 0 0 1\n1 0 0 -0.5\n",
                2,
                "c.txt:2:7",
                "radius -0.5 is negative",
            ),
            (
                "0 0 0 1\n1 0 nan 1\n",
                2,
                "c.txt:2:5",
                "not a finite number",
            ),
            (
                "0 0 0 1\n1 0 0 1\n\n5 5 5 1\n",
                2,
                "c.txt:4:1",
                "has 1 control point,",
            ),
            (
                "0 0 0 1\n1 0 0 1\n2 0 0 1\n",
                4,
                "c.txt:1:1",
                "has 3 control points, it needs at least 4",
            ),
        ];
        for (text, min, loc, msg) in cases {
            let e = parse(text, min).unwrap_err();
            assert!(e.contains(loc) && e.contains(msg), "{text:?}: {e}");
        }
        let e = parse("\n  \n", 2).unwrap_err();
        assert!(e.contains("no control points"), "{e}");
    }
}

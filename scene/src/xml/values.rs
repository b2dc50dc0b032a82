//! Parsing attribute text into numbers, booleans and number lists.
//!
//! Lists may separate their items with commas, whitespace, or both ("1, 2 3,4").
//! Numbers must be finite. Errors are plain messages; callers attach the location.

/// Splits a list on commas and whitespace, skipping empty items.
pub(crate) fn split_list(s: &str) -> impl Iterator<Item = &str> {
    s.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
}

/// Parses a finite floating-point number (surrounding whitespace allowed).
pub(crate) fn parse_float(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("\"{s}\" is not a finite number")),
        Err(_) => Err(format!("\"{s}\" is not a number")),
    }
}

/// Parses a 64-bit signed integer (surrounding whitespace allowed).
pub(crate) fn parse_int(s: &str) -> Result<i64, String> {
    s.trim()
        .parse::<i64>()
        .map_err(|_| format!("\"{s}\" is not an integer"))
}

/// Parses `true` or `false` (any letter case, as Mitsuba does).
pub(crate) fn parse_bool(s: &str) -> Result<bool, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("true") {
        Ok(true)
    } else if t.eq_ignore_ascii_case("false") {
        Ok(false)
    } else {
        Err(format!("\"{s}\" is not a boolean (expected true or false)"))
    }
}

/// Parses a list of finite numbers.
pub(crate) fn parse_floats(s: &str) -> Result<Vec<f64>, String> {
    split_list(s).map(parse_float).collect()
}

/// Parses exactly three numbers, or one number repeated three times when `allow_one`.
pub(crate) fn parse_vec3(s: &str, allow_one: bool) -> Result<[f64; 3], String> {
    let v = parse_floats(s)?;
    match v.len() {
        3 => Ok([v[0], v[1], v[2]]),
        1 if allow_one => Ok([v[0]; 3]),
        n => Err(format!(
            "\"{s}\" has {n} number{}, expected {}3",
            if n == 1 { "" } else { "s" },
            if allow_one { "1 or " } else { "" }
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(parse_float(" 1e-3 ").unwrap(), 1e-3);
        assert_eq!(parse_float("-2").unwrap(), -2.0);
        assert!(parse_float("inf").is_err());
        assert!(parse_float("NaN").is_err());
        assert!(parse_float("1,5").is_err());
        assert_eq!(parse_int("+42").unwrap(), 42);
        assert!(parse_int("4.0").is_err());
        assert!(parse_bool("True").unwrap());
        assert!(!parse_bool("false").unwrap());
        assert!(parse_bool("1").is_err());
    }

    #[test]
    fn lists() {
        assert_eq!(
            parse_floats("1, 2 3,4 ,\t5").unwrap(),
            vec![1.0, 2.0, 3.0, 4.0, 5.0]
        );
        assert_eq!(parse_vec3("0.1 0.2 0.3", false).unwrap(), [0.1, 0.2, 0.3]);
        assert_eq!(parse_vec3("0.5", true).unwrap(), [0.5; 3]);
        assert!(parse_vec3("0.5", false).is_err());
        assert!(parse_vec3("1 2", true)
            .unwrap_err()
            .contains("has 2 numbers"));
        assert!(parse_vec3("1 x 2", true).unwrap_err().contains("\"x\""));
    }
}

//! `$name` parameter substitution inside attribute values.
//!
//! Parameters come from `-D name=value` on the command line and from `<default name= value=/>`
//! elements (a default never overrides a value that is already set). Every `$name` token in an
//! attribute value, where `name` is the longest run of `[A-Za-z0-9_]` after the `$`, is
//! replaced by the parameter's value; an unknown name is an error. Replacement text is not
//! scanned again.

use std::borrow::Cow;
use std::collections::HashMap;

/// True for the characters a parameter name is made of.
pub(crate) fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// True when `name` is a valid parameter name (non-empty, `[A-Za-z0-9_]` only).
pub(crate) fn is_valid_name(name: &str) -> bool {
    !name.is_empty() && name.chars().all(is_name_char)
}

/// Replaces every `$name` in `value`; `Err(message)` names the first unknown parameter.
pub(crate) fn substitute<'v>(
    value: &'v str,
    params: &HashMap<String, String>,
) -> Result<Cow<'v, str>, String> {
    if !value.contains('$') {
        return Ok(Cow::Borrowed(value));
    }
    let mut out = String::with_capacity(value.len());
    let mut rest = value;
    while let Some(i) = rest.find('$') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let len = after
            .find(|c: char| !is_name_char(c))
            .unwrap_or(after.len());
        let name = &after[..len];
        if name.is_empty() {
            return Err(format!(
                "\"$\" must be followed by a parameter name in \"{value}\""
            ));
        }
        match params.get(name) {
            Some(v) => out.push_str(v),
            None => {
                return Err(format!(
                    "unknown parameter \"${name}\" (declare it with <default name=\"{name}\" \
                     value=\"...\"/> before its use, or pass -D {name}=...)"
                ))
            }
        }
        rest = &after[len..];
    }
    out.push_str(rest);
    Ok(Cow::Owned(out))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> HashMap<String, String> {
        [("spp", "64"), ("sp", "X"), ("w", "1.5")]
            .iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    }

    #[test]
    fn whole_tokens() {
        let p = params();
        assert_eq!(substitute("$spp", &p).unwrap(), "64");
        assert_eq!(substitute("$sp", &p).unwrap(), "X");
        assert_eq!(substitute("a $w, $w/$spp.", &p).unwrap(), "a 1.5, 1.5/64.");
        assert_eq!(substitute("plain", &p).unwrap(), "plain");
        assert!(substitute("$sppx", &p).unwrap_err().contains("\"$sppx\""));
        assert!(substitute("cost $", &p).is_err());
    }

    #[test]
    fn no_rescan() {
        let mut p = params();
        p.insert("a".into(), "$a".into());
        assert_eq!(substitute("$a", &p).unwrap(), "$a");
    }
}

//! `-D name=value`: overrides of a scene file's `<default>`s on the command line.

/// Parses `name=value` for `-D`.
pub(crate) fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((k, v)) if !k.is_empty() => Ok((k.to_string(), v.to_string())),
        _ => Err(format!("expected name=value, found \"{s}\"")),
    }
}

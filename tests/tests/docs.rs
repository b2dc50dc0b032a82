//! Keeps the user documentation honest: the README stays short enough to read (at most 25 KB),
//! every relative link in README.md and docs/**/*.md points at a file that exists, and the text
//! speaks of the project as it is, not of when it was built (no "session N" or "issue N"; history
//! lives in git). Each check is also run on a made-up input it must flag, so a checker that
//! cannot fail is caught.
use std::fs;
use std::path::{Path, PathBuf};

/// The README's size limit in bytes.
const README_LIMIT: u64 = 25 * 1024;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// README.md and every Markdown file under docs/, sorted.
fn doc_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    let mut files = vec![root().join("README.md")];
    walk(&root().join("docs"), &mut files);
    files
}

/// The targets of the Markdown links `[text](target)` and images `![alt](target)` of `text`,
/// outside code blocks and code spans, with the line each is on.
fn link_targets(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Drop code spans: a link inside backticks is text, not a link.
        let mut plain = String::new();
        let mut in_code = false;
        for c in line.chars() {
            if c == '`' {
                in_code = !in_code;
            } else if !in_code {
                plain.push(c);
            }
        }
        let mut rest = plain.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            match after.find(')') {
                Some(j) => {
                    out.push((n + 1, after[..j].trim().to_string()));
                    rest = &after[j..];
                }
                None => break,
            }
        }
    }
    out
}

/// The relative links of `text` (a file in `dir`) whose file does not exist, as
/// `line: target`. Web addresses and links within the same page are not checked.
fn broken_links(text: &str, dir: &Path) -> Vec<String> {
    link_targets(text)
        .into_iter()
        .filter(|(_, t)| !t.is_empty() && !t.starts_with('#') && !t.contains("://"))
        .filter(|(_, t)| !t.starts_with("mailto:"))
        .filter_map(|(line, t)| {
            let file = t.split('#').next().unwrap_or("");
            let file = file.split_whitespace().next().unwrap_or(""); // [a](b "title")
            (!dir.join(file).exists()).then(|| format!("{line}: {t}"))
        })
        .collect()
}

/// Occurrences of "session N" or "issue N" (any case, N a number, any spacing between), as
/// `line: phrase`.
fn dated_phrases(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let lower = line.to_ascii_lowercase();
        for word in ["session", "issue"] {
            let mut from = 0;
            while let Some(i) = lower[from..].find(word) {
                let start = from + i;
                let after = &lower[start + word.len()..];
                let spaced = after.trim_start_matches([' ', '\t', '#']);
                let gap = after.len() - spaced.len();
                if gap > 0 && spaced.starts_with(|c: char| c.is_ascii_digit()) {
                    out.push(format!("{}: {}", n + 1, &line[start..start + word.len() + gap + 1]));
                }
                from = start + word.len();
            }
        }
    }
    out
}

/// Why a README of `size` bytes is too long, if it is.
fn size_problem(size: u64) -> Option<String> {
    (size > README_LIMIT).then(|| format!("README.md is {size} bytes, more than {README_LIMIT}"))
}

#[test]
fn readme_is_at_most_25_kb() {
    let size = fs::metadata(root().join("README.md")).unwrap().len();
    assert!(size > 1000, "README.md is only {size} bytes");
    if let Some(p) = size_problem(size) {
        panic!("{p}");
    }
}

#[test]
fn size_check_control_flags_a_long_readme() {
    assert!(size_problem(README_LIMIT).is_none());
    assert!(size_problem(README_LIMIT + 1).is_some());
    assert!(size_problem(122_584).is_some());
}

#[test]
fn every_relative_link_points_at_a_file() {
    let files = doc_files();
    assert!(files.len() > 10, "found only {} Markdown files", files.len());
    let mut broken = Vec::new();
    for f in &files {
        let text = fs::read_to_string(f).unwrap();
        for b in broken_links(&text, f.parent().unwrap()) {
            broken.push(format!("{}:{b}", f.strip_prefix(root()).unwrap_or(f).display()));
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn link_checker_control_flags_a_missing_file() {
    let dir = root().join("docs");
    let text = "See [the guide](guide/rendering.md), [web](https://example.org/x), [here](#top),\n\
                `[code](not/a/link.md)` and [gone](guide/no-such-page.md#part).\n\
                ![picture](../scenes/no-such-image.png)\n";
    assert_eq!(
        broken_links(text, &dir),
        vec![
            "2: guide/no-such-page.md#part".to_string(),
            "3: ../scenes/no-such-image.png".to_string()
        ]
    );
}

#[test]
fn no_session_or_issue_numbers() {
    let mut found = Vec::new();
    for f in doc_files() {
        let text = fs::read_to_string(&f).unwrap();
        for p in dated_phrases(&text) {
            found.push(format!("{}:{p}", f.strip_prefix(root()).unwrap_or(&f).display()));
        }
    }
    assert!(found.is_empty(), "dated narrative:\n{}", found.join("\n"));
}

#[test]
fn dated_phrase_control_flags_sessions_and_issues() {
    let text = "Measured in Session 34.\nissue 5's targets\nsessions of work, an issue with X\n";
    assert_eq!(
        dated_phrases(text),
        vec!["1: Session 3".to_string(), "2: issue 5".to_string()]
    );
}

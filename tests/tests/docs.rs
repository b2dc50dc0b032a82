//! Keeps the user documentation honest: the README stays short enough to read (at most 25,000
//! bytes), every relative link in README.md and docs/**/*.md points at a file that exists and,
//! where it names a section (`page.md#section`, `#section`), at a heading of that page, and no
//! file of the repository speaks of when or how it was built ("session N", "issue N", or
//! "issue" and a hash sign: history lives in git). Each check is also run on a made-up input it must flag, so
//! a checker that cannot fail is caught.
use std::fs;
use std::path::{Path, PathBuf};

/// The README's size limit in bytes.
const README_LIMIT: u64 = 25_000;

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

/// GitHub's anchor for a heading: lower case, characters other than letters, digits, spaces,
/// `-` and `_` dropped, spaces turned into `-`.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of the headings of Markdown `text` (outside code blocks); a repeated heading's
/// later anchors get `-1`, `-2`, ... as on GitHub.
fn anchors(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut bases = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let hashes = line.len() - line.trim_start_matches('#').len();
        if fenced || hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = slug(&line[hashes..]);
        let repeats = bases.iter().filter(|b| **b == base).count();
        let anchor = match repeats {
            0 => base.clone(),
            k => format!("{base}-{k}"),
        };
        bases.push(base);
        out.push(anchor);
    }
    out
}

/// The relative links of `text` (a file in `dir`) whose file does not exist, or whose
/// `#section` is not a heading of the Markdown page it names, as `line: target`. Web addresses
/// are not checked.
fn broken_links(text: &str, dir: &Path) -> Vec<String> {
    link_targets(text)
        .into_iter()
        .filter(|(_, t)| !t.is_empty() && !t.contains("://"))
        .filter(|(_, t)| !t.starts_with("mailto:"))
        .filter_map(|(line, t)| {
            let t = t.split_whitespace().next().unwrap_or("").to_string(); // [a](b "title")
            let (file, anchor) = match t.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (t.as_str(), None),
            };
            let broken = if file.is_empty() {
                anchor.is_some_and(|a| !anchors(text).iter().any(|h| h == a))
            } else {
                let path = dir.join(file);
                !path.exists()
                    || anchor.is_some_and(|a| {
                        file.ends_with(".md")
                            && !anchors(&fs::read_to_string(&path).unwrap_or_default())
                                .iter()
                                .any(|h| h == a)
                    })
            };
            broken.then(|| format!("{line}: {t}"))
        })
        .collect()
}

/// Occurrences of "session N", "issue N" or "issue" followed by a hash sign (any case, N a
/// number, any spacing between), as `line: phrase`.
fn dated_phrases(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let lower = line.to_ascii_lowercase();
        for word in ["session", "issue"] {
            let mut from = 0;
            while let Some(i) = lower[from..].find(word) {
                let start = from + i;
                let after = &lower[start + word.len()..];
                let spaced = after.trim_start_matches([' ', '\t']);
                let gap = after.len() - spaced.len();
                let numbered = spaced
                    .trim_start_matches('#')
                    .starts_with(|c: char| c.is_ascii_digit());
                let hashed = word == "issue" && spaced.starts_with('#');
                if gap > 0 && (numbered || hashed) {
                    let end = (start + word.len() + gap + 1).min(line.len());
                    out.push(format!("{}: {}", n + 1, &line[start..end]));
                }
                from = start + word.len();
            }
        }
    }
    out
}

/// Every file git tracks in the repository that is text (others are skipped).
fn tracked_text_files() -> Vec<PathBuf> {
    let out = std::process::Command::new("git")
        .arg("-C")
        .arg(root())
        .args(["ls-files", "-z"])
        .output()
        .expect("git runs");
    assert!(out.status.success(), "git ls-files failed");
    String::from_utf8(out.stdout)
        .unwrap()
        .split('\0')
        .filter(|f| !f.is_empty())
        .map(|f| root().join(f))
        .filter(|p| fs::read_to_string(p).is_ok())
        .collect()
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

/// What `find` reports in the text of each of `files` (given the text and the file's path),
/// each finding prefixed with the file's path from the repository root.
fn findings_in(files: &[PathBuf], find: impl Fn(&str, &Path) -> Vec<String>) -> Vec<String> {
    let mut found = Vec::new();
    for f in files {
        let text = fs::read_to_string(f).unwrap();
        for p in find(&text, f) {
            found.push(format!(
                "{}:{p}",
                f.strip_prefix(root()).unwrap_or(f).display()
            ));
        }
    }
    found
}

#[test]
fn every_relative_link_points_at_a_file() {
    let files = doc_files();
    assert!(
        files.len() > 10,
        "found only {} Markdown files",
        files.len()
    );
    let broken = findings_in(&files, |text, f| broken_links(text, f.parent().unwrap()));
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
            "1: #top".to_string(), // no heading "top" in the text
            "2: guide/no-such-page.md#part".to_string(),
            "3: ../scenes/no-such-image.png".to_string()
        ]
    );
}

#[test]
fn no_session_or_issue_numbers() {
    let files = tracked_text_files();
    assert!(
        files.len() > 300,
        "found only {} tracked text files",
        files.len()
    );
    let found = findings_in(&files, |text, _| dated_phrases(text));
    assert!(found.is_empty(), "dated narrative:\n{}", found.join("\n"));
}

#[test]
fn dated_phrase_control_flags_sessions_and_issues() {
    // Built at run time, so that this file does not hold the phrases it looks for.
    let (s, i) = ("Session", "issue");
    let text = format!(
        "Measured in {s} 34.\n{i} 5's targets\nsee {i} #12\nsessions of work, an {i} with X\n"
    );
    assert_eq!(
        dated_phrases(&text),
        vec![
            format!("1: {s} 3"),
            format!("2: {i} 5"),
            format!("3: {i} #")
        ]
    );
}

#[test]
fn anchor_control_flags_a_missing_section() {
    let dir = root().join("docs");
    let text = "# Top page\n## Two words (`x`)\n## Two words (`x`)\n\
                [a](#top-page) [b](#two-words-x) [c](#two-words-x-1) [d](#nowhere)\n\
                [e](reference/plugins.md#integrators-integrator) [f](reference/plugins.md#no-such-family)\n";
    assert_eq!(
        broken_links(text, &dir),
        vec![
            "4: #nowhere".to_string(),
            "5: reference/plugins.md#no-such-family".to_string()
        ]
    );
}

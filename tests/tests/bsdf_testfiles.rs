//! `tessera test` on the Nori-style BSDF test files of `tests/bsdf_tests/` (t-tests of the
//! directional albedo against references computed with Mitsuba 3 by
//! `scripts/make_bsdf_ttests.py`, and chi-square tests of sampling against the pdf), run
//! through the command's own entry point (`cli::test::run_to`, the code behind the binary),
//! so exit codes and printed lines are the user's.
//!
//! Controls: a wrong reference fails (exit 1, `FAIL` on its line); bad input (missing or
//! malformed lists, count mismatches, unknown parameters, out-of-range settings, a chi2test
//! with too few samples) exits 2 with one `file:line:col: message` line.
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use tessera_cli::test::{run_to, TestArgs};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_tests")
}

/// The `.xml` files directly in `folder`, sorted.
fn xml_files(folder: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "xml"))
        .collect();
    v.sort();
    v
}

/// Runs `tessera test FILE --seed SEED`: (exit code, stdout, stderr).
fn tessera_test(file: &Path, seed: u64) -> (i32, String, String) {
    let args = TestArgs {
        file: file.to_path_buf(),
        seed,
    };
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = run_to(&args, &mut out, &mut err);
    (
        code,
        String::from_utf8(out).unwrap(),
        String::from_utf8(err).unwrap(),
    )
}

/// Writes `text` to a fresh temporary file and returns its path.
fn temp_file(name: &str, text: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let p = std::env::temp_dir().join(format!(
        "tessera-bsdf-testfiles-{}-{}-{name}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn every_bsdf_test_file_passes() {
    let files = xml_files(&dir());
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    for want in [
        "chi2_diffuse.xml",
        "ttest_diffuse.xml",
        "ttest_twosided.xml",
        "chi2_conductor.xml",
        "ttest_conductor.xml",
        "chi2_roughconductor.xml",
        "ttest_roughconductor.xml",
        "chi2_dielectric.xml",
        "ttest_dielectric.xml",
        "chi2_roughdielectric.xml",
        "ttest_roughdielectric.xml",
        "chi2_plastic.xml",
        "ttest_plastic.xml",
        "chi2_roughplastic.xml",
        "ttest_roughplastic.xml",
        "chi2_blendbsdf.xml",
        "ttest_blendbsdf.xml",
    ] {
        assert!(names.iter().any(|n| n == want), "{want} missing: {names:?}");
    }
    for file in &files {
        let (code, out, err) = tessera_test(file, 0);
        assert!(
            code == 0 && err.is_empty(),
            "{}: exit {code}\n{out}{err}",
            file.display()
        );
        let lines: Vec<&str> = out.lines().collect();
        let cases = &lines[..lines.len() - 1];
        assert!(!cases.is_empty() && cases.iter().all(|l| l.ends_with(" PASS")));
        assert_eq!(
            lines.last().unwrap(),
            &format!("{} passed, 0 failed", cases.len())
        );
    }
}

#[test]
fn a_wrong_reference_fails_with_exit_code_1() {
    let path = dir().join("ttest_diffuse.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let key = "name=\"references\" value=\"";
    let start = text.find(key).unwrap() + key.len();
    let end = start + text[start..].find(',').unwrap();
    let right: f64 = text[start..end].parse().unwrap();
    // One part in 1e4: the diffuse weight is deterministic, so even this is far off.
    let altered = format!("{}{}{}", &text[..start], right * 1.0001, &text[end..]);
    let file = temp_file("wrong-reference.xml", &altered);
    let (code, out, err) = tessera_test(&file, 0);
    std::fs::remove_file(&file).ok();
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.is_empty(), "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].ends_with(" FAIL"), "{out}");
    assert!(lines[1..lines.len() - 1]
        .iter()
        .all(|l| l.ends_with(" PASS")));
    let n = lines.len() - 2;
    assert_eq!(lines.last().unwrap(), &format!("{n} passed, 1 failed"));
}

/// 1-based (line, column) of the first occurrence of `needle` in `text`.
fn position(text: &str, needle: &str) -> (usize, usize) {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle} not in text"));
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let col = before.chars().rev().take_while(|&c| c != '\n').count() + 1;
    (line, col)
}

/// Runs the file `text` and requires exit 2 with exactly one line on stderr:
/// `error: FILE:LINE:COL: ...` at `at` (a substring of `text`) containing `message`.
fn bad_input(text: &str, at: &str, message: &str) {
    let file = temp_file("bad.xml", text);
    let (code, out, err) = tessera_test(&file, 0);
    std::fs::remove_file(&file).ok();
    let (line, col) = position(text, at);
    let prefix = format!("error: {}:{line}:{col}: ", file.display());
    assert_eq!(code, 2, "{out}{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with(&prefix) && err.contains(message),
        "expected {prefix}...{message}..., got {err}"
    );
}

const DIFFUSE: &str = r#"<bsdf type="diffuse"/>"#;

fn ttest(params: &str) -> String {
    format!("<test type=\"ttest\">\n  {params}\n  {DIFFUSE}\n  {DIFFUSE}\n</test>\n")
}

#[test]
fn bad_bsdf_ttest_input_is_a_located_error() {
    let angles = r#"<string name="angles" value="0, 45"/>"#;
    bad_input(&ttest(angles), "<test", "missing parameter \"references\"");
    let refs3 = r#"<string name="references" value="0.5, 0.5, 0.5"/>"#;
    bad_input(
        &ttest(&format!("{angles}{refs3}")),
        "<string name=\"references\"",
        "3 references for 2 bsdf(s) x 2 angle(s)",
    );
    let refs4 = r#"<string name="references" value="0.5, 0.5, 0.5, 0.5"/>"#;
    bad_input(&ttest(refs4), "<test", "missing parameter \"angles\"");
    let text = ttest(&format!(
        "{angles}{refs4}<integer name=\"sampelCount\" value=\"9\"/>"
    ));
    bad_input(&text, "<integer", "unused parameter \"sampel_count\"");
    let text = ttest(&format!(
        "{}{refs4}",
        r#"<string name="angles" value="0, 190"/>"#
    ));
    bad_input(
        &text,
        "<string name=\"angles\"",
        "incident angles are degrees",
    );
    let text = ttest(&format!(
        "{angles}{}",
        r#"<string name="references" value="0.5, x, 0.5, 0.5"/>"#
    ));
    bad_input(&text, "<string name=\"references\"", "holds \"x\"");
    let text = ttest(&format!(
        "{angles}{refs4}<integer name=\"sampleCount\" value=\"10\"/>"
    ));
    bad_input(&text, "<integer", "\"sampleCount\" must be at least 100");
    let text = ttest(&format!(
        "{angles}{refs4}<float name=\"significanceLevel\" value=\"1e-9\"/>"
    ));
    bad_input(&text, "<float", "\"significanceLevel\" must be at least");
    // A BSDF parameter error is reported where it is.
    let text = format!(
        "<test type=\"ttest\">\n  {angles}\n  {}\n  <bsdf type=\"diffuse\">\
         <float name=\"roughness\" value=\"1\"/></bsdf>\n</test>\n",
        r#"<string name="references" value="0.5, 0.5"/>"#
    );
    bad_input(&text, "<float", "unused parameter \"roughness\"");
    // Scenes and BSDFs do not mix.
    let text =
        format!("<test type=\"ttest\">\n  {angles}\n  {refs4}\n  {DIFFUSE}\n  <scene/>\n</test>\n");
    bad_input(&text, "<scene", "holds <bsdf> elements only");
}

#[test]
fn bad_chi2test_input_is_a_located_error() {
    let chi2 =
        |params: &str| format!("<test type=\"chi2test\">\n  {params}\n  {DIFFUSE}\n</test>\n");
    // (parameter, where the error points, what it says)
    #[rustfmt::skip]
    let cases = [
        // Too few samples to have power: 10 x 20 cells need 50 each on average.
        (r#"<integer name="sampleCount" value="5000"/>"#, "<integer", "too few samples"),
        (r#"<integer name="resolution" value="1"/>"#, "<integer", "\"resolution\" must be at least 2"),
        (r#"<integer name="minExpFrequency" value="3"/>"#, "<integer", "\"minExpFrequency\" = 3 is not supported"),
        (r#"<float name="significanceLevel" value="0"/>"#, "<float", "\"significanceLevel\" must be at least"),
        (r#"<string name="references" value="1"/>"#, "<string", "unused parameter \"references\""),
    ];
    for (param, at, says) in cases {
        bad_input(&chi2(param), at, says);
    }
    bad_input(
        "<test type=\"chi2test\">\n  <integer name=\"testCount\" value=\"2\"/>\n</test>\n",
        "<test",
        "holds no <bsdf>",
    );
    bad_input(
        &format!("<test type=\"chi3test\">\n  {DIFFUSE}\n</test>\n"),
        "<test",
        "unknown test type \"chi3test\"",
    );
}

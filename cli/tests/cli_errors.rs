//! The `tessera` binary on bad input: exit code 2, exactly one line on stderr naming
//! `file:line:column` (or at least the file / the bad value), never a panic, and never an output
//! image (nor a temporary file) left behind. Also: a failing write exits with 1 and leaves
//! nothing, and a good render writes valid images.
//!
//! Scenes are written from the test into a fresh temporary directory (`in/`), so the line and
//! column each error must name are computed from the text right here; the mesh fixtures under
//! `tests/fixtures/` are copied beside them. Outputs go to a separate, initially empty `out/`.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::support;
use support::temp_dir::TempDir;
use support::{run_os, stderr as stderr_of};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

fn cbox() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml")
}

/// A fresh temporary directory with `in/` (scene files) and `out/` (outputs); removed on drop.
struct Tmp {
    _root: TempDir,
    input: PathBuf,
    out: PathBuf,
}

impl Tmp {
    fn new(name: &str) -> Tmp {
        let root = TempDir::new("tessera-cli-errors", name);
        let (input, out) = (root.0.join("in"), root.0.join("out"));
        std::fs::create_dir_all(&input).unwrap();
        std::fs::create_dir_all(&out).unwrap();
        Tmp {
            _root: root,
            input,
            out,
        }
    }

    /// Writes `text` to `in/name` and returns its path.
    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.input.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    /// Copies `tests/fixtures/name` to `in/name`; returns its path and text.
    fn fixture(&self, name: &str) -> (PathBuf, String) {
        let text = std::fs::read_to_string(fixtures().join(name)).unwrap();
        (self.write(name, &text), text)
    }

    /// The names of everything in `out/`.
    fn out_entries(&self) -> Vec<String> {
        support::temp_dir::entries(&self.out)
    }
}

/// `tessera render <scene> -o <out> -q <extra...>`.
fn render(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "render".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "-q".as_ref(),
    ];
    args.extend(extra.iter().map(|s| std::ffi::OsStr::new(*s)));
    run_os(&args)
}

/// `path:LINE:COL` of the first (and only) occurrence of `needle` in `text` (1-based; the
/// column counts characters).
fn loc(path: &Path, text: &str, needle: &str) -> String {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("fixture lacks {needle:?}"));
    assert!(
        text[at + 1..].find(needle).is_none(),
        "{needle:?} occurs more than once in the fixture"
    );
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = text[line_start..at].chars().count() + 1;
    format!("{}:{line}:{col}", path.display())
}

/// What breaks the bad-input contract, if anything: the contract is exit code 2, one non-empty
/// line on stderr containing `expected`, no panic, no output file, nothing at all in `out/`.
fn bad_input_problem(
    case: &str,
    o: &Output,
    expected: &str,
    output: &Path,
    tmp: &Tmp,
) -> Option<String> {
    let err = stderr_of(o);
    let ctx = format!("case {case}: exit {:?}, stderr {err:?}", o.status.code());
    let line = err
        .strip_suffix("\r\n")
        .or_else(|| err.strip_suffix('\n'))
        .unwrap_or(&err);
    let entries = tmp.out_entries();
    let problem = if err.contains("panicked") {
        "the binary panicked".to_string()
    } else if o.status.code() != Some(2) {
        "want exit code 2".to_string()
    } else if line.trim().is_empty() {
        "stderr is empty".to_string()
    } else if line.contains('\n') || line.contains('\r') {
        "stderr has more than one line".to_string()
    } else if !line.contains(expected) {
        format!("stderr does not name {expected:?}")
    } else if output.exists() {
        format!("the output {} was written", output.display())
    } else if !entries.is_empty() {
        format!("files were left in the output directory: {entries:?}")
    } else {
        return None;
    };
    Some(format!("{ctx}: {problem}"))
}

/// Asserts the bad-input contract (see [`bad_input_problem`]).
fn assert_bad_input(case: &str, o: &Output, expected: &str, output: &Path, tmp: &Tmp) {
    if let Some(p) = bad_input_problem(case, o, expected, output, tmp) {
        panic!("{p}");
    }
}

/// Fails with every problem found, one per line, when there are any.
fn assert_no_problems(problems: Vec<String>) {
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

/// A valid scene's first nine lines: the body of every case starts on line 10.
const HEADER: &str = r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <film type="hdrfilm">
            <integer name="width" value="4"/>
            <integer name="height" value="4"/>
        </film>
    </sensor>
    <emitter type="constant"/>
"#;

/// A small valid scene with `body` (lines starting at 10) added at the top level.
fn scene(body: &str) -> String {
    format!("{HEADER}{body}</scene>\n")
}

/// Writes `text` as a scene, renders it with `extra` arguments, and checks the bad-input
/// contract with the location of `needle` (in `text`) as the expected `file:line:col`.
fn located_problem(name: &str, text: &str, needle: &str, extra: &[&str]) -> Option<String> {
    let tmp = Tmp::new(name);
    let path = tmp.write("scene.xml", text);
    let output = tmp.out.join("image.png");
    let o = render(&path, &output, extra);
    bad_input_problem(name, &o, &loc(&path, text, needle), &output, &tmp)
}

/// [`located_problem`], asserted.
fn check_located(name: &str, text: &str, needle: &str, extra: &[&str]) {
    if let Some(p) = located_problem(name, text, needle, extra) {
        panic!("{p}");
    }
}

#[test]
fn the_fixture_scene_itself_renders() {
    // Every error case below is this scene plus one mistake: make sure the rest is fine.
    let tmp = Tmp::new("fixture-ok");
    let path = tmp.write("scene.xml", &scene(""));
    let output = tmp.out.join("image.png");
    let o = render(&path, &output, &[]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr_of(&o));
    assert!(output.exists());
    let sphere = scene(
        "    <shape type=\"sphere\">\n        <float name=\"radius\" value=\"1\"/>\n    </shape>\n",
    );
    let path = tmp.write("sphere.xml", &sphere);
    let o = render(&path, &output, &[]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr_of(&o));
}

#[test]
fn missing_scene_file() {
    let tmp = Tmp::new("missing");
    let path = tmp.input.join("no_such_scene.xml");
    let output = tmp.out.join("image.png");
    let o = render(&path, &output, &[]);
    assert_bad_input(
        "missing scene file",
        &o,
        &path.display().to_string(),
        &output,
        &tmp,
    );
}

#[test]
fn malformed_xml_mismatched_tag() {
    let text = scene("    <shape type=\"sphere\">\n    </bsdf>\n");
    // roxmltree reports the closing tag that does not match.
    check_located("mismatched-tag", &text, "</bsdf>", &[]);
}

#[test]
fn malformed_xml_unclosed_tag() {
    // <shape> is never closed; the parser notices at the </scene> that closes the root.
    let text = scene("    <shape type=\"sphere\">\n");
    check_located("unclosed-tag", &text, "</scene>", &[]);
}

#[test]
fn malformed_xml_unterminated_start_tag() {
    // `<shape type="sphere"` lacks its `>`: the next token, on the next line, is the error.
    let text = scene("    <shape type=\"sphere\"\n");
    check_located("unterminated-start-tag", &text, "</scene>", &[]);
}

#[test]
fn malformed_xml_truncated_file() {
    // The file ends inside <shape>: the message must still be located (somewhere in the file:
    // at the unclosed element or at the end of the text).
    let tmp = Tmp::new("truncated");
    let text = format!("{HEADER}    <shape type=\"sphere\">\n");
    let path = tmp.write("scene.xml", &text);
    let output = tmp.out.join("image.png");
    let o = render(&path, &output, &[]);
    let prefix = format!("{}:", path.display());
    assert_bad_input("truncated file", &o, &prefix, &output, &tmp);
    let err = stderr_of(&o);
    let rest = &err[err.find(&prefix).unwrap() + prefix.len()..];
    let mut parts = rest.splitn(3, ':');
    let line: Option<usize> = parts.next().and_then(|s| s.parse().ok());
    let col: Option<usize> = parts.next().and_then(|s| s.parse().ok());
    let lines = text.lines().count();
    assert!(
        matches!((line, col), (Some(l), Some(c)) if (1..=lines + 1).contains(&l) && c >= 1),
        "case truncated file: stderr {err:?} does not name {prefix}LINE:COL"
    );
}

#[test]
fn unknown_plugin_types() {
    let cases = [
        (
            "unknown-shape",
            "    <shape type=\"teapot\"/>\n",
            "<shape type=\"teapot\"",
        ),
        (
            "unknown-bsdf",
            "    <bsdf type=\"glitter\"/>\n",
            "<bsdf type=\"glitter\"",
        ),
        (
            "unknown-integrator",
            "    <integrator type=\"magic\"/>\n",
            "<integrator type=\"magic\"",
        ),
    ];
    let problems = cases
        .iter()
        .filter_map(|(name, body, needle)| located_problem(name, &scene(body), needle, &[]))
        .collect();
    assert_no_problems(problems);
}

#[test]
fn wrong_parameter_types() {
    // A string where the sphere wants a float: at the property element.
    let text = scene(
        "    <shape type=\"sphere\">\n        <string name=\"radius\" value=\"x\"/>\n    </shape>\n",
    );
    check_located(
        "string-radius",
        &text,
        "<string name=\"radius\" value=\"x\"/>",
        &[],
    );
    // A float that is not a number: at its `value` attribute.
    let text = scene(concat!(
        "    <shape type=\"sphere\">\n",
        "        <bsdf type=\"diffuse\">\n",
        "            <float name=\"reflectance\" value=\"abc\"/>\n",
        "        </bsdf>\n",
        "    </shape>\n",
    ));
    check_located("float-abc", &text, "value=\"abc\"", &[]);
}

#[test]
fn unknown_parameter() {
    let text = scene(
        "    <shape type=\"sphere\">\n        <float name=\"radiuss\" value=\"1\"/>\n    </shape>\n",
    );
    check_located(
        "unused-radiuss",
        &text,
        "<float name=\"radiuss\" value=\"1\"/>",
        &[],
    );
}

fn mesh_scene(kind: &str, file: &str) -> String {
    scene(&format!(
        "    <shape type=\"{kind}\">\n        <string name=\"filename\" value=\"{file}\"/>\n    </shape>\n"
    ))
}

#[test]
fn mesh_fixture_errors_are_located() {
    // (fixture, the text the error must point at): `f 1 2 9` and `3 0 1 7` with three vertices
    // at the bad index, a `nan` coordinate at itself.
    let cases = [
        ("bad_index.obj", "9\n"),
        ("nan_vertex.obj", "nan"),
        ("bad_index.ply", "7\n"),
    ];
    let mut problems = Vec::new();
    for (fixture, needle) in cases {
        let tmp = Tmp::new(fixture);
        let (mesh, text) = tmp.fixture(fixture);
        let kind = fixture.rsplit('.').next().unwrap();
        let path = tmp.write("scene.xml", &mesh_scene(kind, fixture));
        let output = tmp.out.join("image.png");
        let o = render(&path, &output, &[]);
        let want = loc(&mesh, &text, needle);
        problems.extend(bad_input_problem(fixture, &o, &want, &output, &tmp));
    }
    assert_no_problems(problems);
}

/// An ASCII PLY triangle whose second vertex line is `second`, with a comment line in the header.
fn ascii_ply(second: &str) -> String {
    format!(
        "ply\nformat ascii 1.0\ncomment test\nelement vertex 3\nproperty float x\n\
         property float y\nproperty float z\nelement face 1\n\
         property list uchar int vertex_indices\nend_header\n0 0 0\n{second}\n0 1 0\n3 0 1 2\n"
    )
}

#[test]
fn ply_errors_are_located() {
    // A token the parser cannot read, a number that overflows f32, and a misspelt header
    // keyword: each at its line and column in the PLY file.
    let cases = [
        ("unreadable", ascii_ply("1 0 abc"), "abc"),
        ("overflow", ascii_ply("1  0 1e39"), "1e39"),
        (
            "header",
            ascii_ply("1 0 0").replace("property float y", "property floaty y"),
            "y y\n",
        ),
    ];
    let mut problems = Vec::new();
    for (name, text, needle) in cases {
        let tmp = Tmp::new(&format!("ply-{name}"));
        let ply = tmp.write("m.ply", &text);
        let path = tmp.write("scene.xml", &mesh_scene("ply", "m.ply"));
        let output = tmp.out.join("image.png");
        let o = render(&path, &output, &[]);
        problems.extend(bad_input_problem(
            name,
            &o,
            &loc(&ply, &text, needle),
            &output,
            &tmp,
        ));
    }
    assert_no_problems(problems);
}

#[test]
fn binary_ply_errors_name_the_record() {
    // Binary files have no lines: the error names the file and the record.
    let tmp = Tmp::new("ply-binary");
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
end_header\n"
        .to_vec();
    for v in [
        [0.0f32, 0.0, 0.0],
        [1.0, f32::INFINITY, 0.0],
        [0.0, 1.0, 0.0],
    ] {
        v.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
    }
    bytes.push(3);
    [0i32, 1, 2]
        .iter()
        .for_each(|i| bytes.extend(i.to_le_bytes()));
    let ply = tmp.input.join("m.ply");
    std::fs::write(&ply, &bytes).unwrap();
    let path = tmp.write("scene.xml", &mesh_scene("ply", "m.ply"));
    let output = tmp.out.join("image.png");
    let o = render(&path, &output, &[]);
    let want = format!("{}: vertex 1: non-finite vertex y", ply.display());
    assert_bad_input("binary ply", &o, &want, &output, &tmp);
}

#[test]
fn undefined_parameter_reference() {
    // The scene uses `$r`, which neither a <default> nor the -D on the command line defines:
    // at the attribute that uses it.
    let text = scene(
        "    <shape type=\"sphere\">\n        <float name=\"radius\" value=\"$r\"/>\n    </shape>\n",
    );
    check_located("undefined-$r", &text, "value=\"$r\"", &["-D", "radius=2"]);
}

#[test]
fn define_of_a_name_the_scene_does_not_declare() {
    // `-D ress=8` (a typo of `res`) names no `<default>` and no `$ress` in the scene: bad input,
    // not a silent full-size render.
    let tmp = Tmp::new("define-typo");
    let output = tmp.out.join("image.png");
    let o = render(
        &cbox(),
        &output,
        &["-D", "ress=8", "-D", "res=8", "-D", "spp=1"],
    );
    assert_bad_input("-D ress=8 on cbox", &o, "ress", &output, &tmp);
}

#[test]
fn negative_radius() {
    let text = scene(
        "    <shape type=\"sphere\">\n        <float name=\"radius\" value=\"-1\"/>\n    </shape>\n",
    );
    check_located(
        "negative-radius",
        &text,
        "<float name=\"radius\" value=\"-1\"/>",
        &[],
    );
}

#[test]
fn zero_film_width() {
    let text = scene("").replace(
        "<integer name=\"width\" value=\"4\"/>",
        "<integer name=\"width\" value=\"0\"/>",
    );
    check_located(
        "zero-width",
        &text,
        "<integer name=\"width\" value=\"0\"/>",
        &[],
    );
}

#[test]
fn bad_command_line_values() {
    let cases: [(&str, &[&str], &str, &str); 5] = [
        ("spp-0", &["--spp", "0"], "image.png", "--spp"),
        (
            "integrator-foo",
            &["--integrator", "foo"],
            "image.png",
            "foo",
        ),
        ("bmp", &[], "out.bmp", "out.bmp"),
        (
            "tile-size-0",
            &["--tile-size", "0"],
            "image.png",
            "--tile-size",
        ),
        ("threads-0", &["--threads", "0"], "image.png", "--threads"),
    ];
    let mut problems = Vec::new();
    for (name, extra, out_name, expected) in cases {
        let tmp = Tmp::new(name);
        let path = tmp.write("scene.xml", &scene(""));
        let output = tmp.out.join(out_name);
        let o = render(&path, &output, extra);
        problems.extend(bad_input_problem(name, &o, expected, &output, &tmp));
    }
    assert_no_problems(problems);
}

#[test]
fn unparsable_command_line_values() {
    // Values clap itself rejects are bad input too: exit 2 and one line.
    let cases: [(&str, &[&str], &str); 3] = [
        ("spp-abc", &["--spp", "abc"], "abc"),
        ("define-no-equals", &["-D", "res"], "res"),
        ("tile-size-negative", &["--tile-size", "-3"], "-3"),
    ];
    let mut problems = Vec::new();
    for (name, extra, expected) in cases {
        let tmp = Tmp::new(name);
        let path = tmp.write("scene.xml", &scene(""));
        let output = tmp.out.join("image.png");
        let o = render(&path, &output, extra);
        problems.extend(bad_input_problem(name, &o, expected, &output, &tmp));
    }
    assert_no_problems(problems);
}

#[test]
fn failed_write_exits_1_and_leaves_nothing() {
    // The parent directory of the output does not exist: the render runs, the write fails.
    let tmp = Tmp::new("no-parent");
    let missing_dir = tmp.out.join("no_such_dir");
    let output = missing_dir.join("image.png");
    let o = render(&cbox(), &output, &["-D", "res=8", "--spp", "1"]);
    let err = stderr_of(&o);
    assert!(!err.contains("panicked"), "stderr {err:?}");
    assert_eq!(o.status.code(), Some(1), "stderr {err:?}");
    assert!(
        err.contains(&output.display().to_string()),
        "stderr {err:?}"
    );
    assert!(!missing_dir.exists(), "the missing directory was created");
    assert_eq!(tmp.out_entries(), Vec::<String>::new());

    // The target is an existing directory: the temporary file is written but cannot be renamed
    // over it; it must be removed and the directory left as it was.
    let tmp = Tmp::new("onto-dir");
    let output = tmp.out.join("image.png");
    std::fs::create_dir(&output).unwrap();
    std::fs::write(output.join("keep"), "x").unwrap();
    let o = render(&cbox(), &output, &["-D", "res=8", "--spp", "1"]);
    let err = stderr_of(&o);
    assert!(!err.contains("panicked"), "stderr {err:?}");
    assert_eq!(o.status.code(), Some(1), "stderr {err:?}");
    assert!(output.is_dir());
    assert_eq!(std::fs::read_to_string(output.join("keep")).unwrap(), "x");
    assert_eq!(tmp.out_entries(), vec!["image.png".to_string()]);

    // One good output and one failing one: exit 1, the good one written, no temporary files.
    let tmp = Tmp::new("one-fails");
    let good = tmp.out.join("good.pfm");
    let bad = tmp.out.join("no_such_dir").join("bad.pfm");
    let o = run_os(&[
        "render".as_ref(),
        cbox().as_os_str(),
        "-o".as_ref(),
        good.as_os_str(),
        "-o".as_ref(),
        bad.as_os_str(),
        "-q".as_ref(),
        "-D".as_ref(),
        "res=8".as_ref(),
        "--spp".as_ref(),
        "1".as_ref(),
    ]);
    let err = stderr_of(&o);
    assert!(!err.contains("panicked"), "stderr {err:?}");
    assert_eq!(o.status.code(), Some(1), "stderr {err:?}");
    assert_eq!(tmp.out_entries(), vec!["good.pfm".to_string()]);
}

#[test]
fn good_render_writes_valid_images() {
    let tmp = Tmp::new("success");
    let outs = ["image.png", "image.exr", "image.pfm"].map(|n| tmp.out.join(n));
    let o = run_os(&[
        "render".as_ref(),
        cbox().as_os_str(),
        "-o".as_ref(),
        outs[0].as_os_str(),
        "-o".as_ref(),
        outs[1].as_os_str(),
        "-o".as_ref(),
        outs[2].as_os_str(),
        "-q".as_ref(),
        "-D".as_ref(),
        "res=8".as_ref(),
        "--spp".as_ref(),
        "1".as_ref(),
    ]);
    let err = stderr_of(&o);
    assert_eq!(o.status.code(), Some(0), "stderr {err:?}");
    assert!(!err.contains("panicked"), "stderr {err:?}");
    let magic: [&[u8]; 3] = [b"\x89PNG\r\n\x1a\n", &[0x76, 0x2f, 0x31, 0x01], b"PF\n"];
    for (p, m) in outs.iter().zip(magic) {
        let bytes = std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        assert!(
            bytes.starts_with(m),
            "{} has the wrong magic bytes",
            p.display()
        );
        let img = tessera::image_io::read_image(p).unwrap();
        assert_eq!((img.width, img.height), (8, 8), "{}", p.display());
        assert!(
            img.data
                .iter()
                .flatten()
                .all(|v| v.is_finite() && *v >= 0.0),
            "{}",
            p.display()
        );
        assert!(
            img.data.iter().flatten().any(|v| *v > 0.0),
            "{} is black",
            p.display()
        );
    }
    // Exactly the three images: no temporary files.
    assert_eq!(
        tmp.out_entries(),
        vec!["image.exr", "image.pfm", "image.png"]
    );
}

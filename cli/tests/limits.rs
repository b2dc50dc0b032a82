//! Resource limits, end to end through the `tessera` binary: input that asks for absurd
//! amounts of memory or recursion (giant films, sample counts that overflow, include cycles,
//! deep nesting, mesh headers claiming billions of vertices, `/dev/zero` or a directory given as
//! a file) is refused with exit code 2 and one line naming `file:line:col`, quickly and without
//! allocating what it asks for; an output whose write fails midway leaves the previous file of
//! that name untouched (exit 1).
//!
//! The memory claims are checked by running the binary under `ulimit -v` (2 GB of address
//! space): an allocation sized by a count in the file would abort instead of exiting with 2.
//! The controls show the limits bite: the same commands with sane values succeed.
#![cfg(unix)]

use std::path::Path;
use std::process::{Command, Output};

use crate::support;
use support::stderr as stderr_of;
use support::temp_dir::TempDir;

const BIN: &str = env!("CARGO_BIN_EXE_tessera");

/// Address-space limit for the binary, in KiB (`ulimit -v`).
const MEM_KIB: u64 = 2_000_000;

/// A fresh temporary directory (`tessera-limits-...`), removed on drop.
fn temp_dir(name: &str) -> TempDir {
    TempDir::new("tessera-limits", name)
}

/// Runs `tessera args...` through `sh` with `ulimits` (e.g. `ulimit -v 2000000`) applied first
/// and SIGXFSZ ignored (so a file-size limit makes writes fail instead of killing the process).
fn run_limited(ulimits: &str, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("trap '' XFSZ; {ulimits}; exec \"$0\" \"$@\""))
        .arg(BIN)
        .args(args)
        .output()
        .expect("cannot run the tessera binary")
}

/// `tessera render scene -o out -q --threads 1 extra...` with [`MEM_KIB`] of address space.
fn render(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
        "--threads",
        "1",
    ];
    args.extend(extra);
    run_limited(&format!("ulimit -v {MEM_KIB}"), &args)
}

/// `path:LINE:COL` of the only occurrence of `needle` in `text`.
fn loc(path: &Path, text: &str, needle: &str) -> String {
    let at = text.find(needle).expect("needle in text");
    assert!(text[at + 1..].find(needle).is_none(), "{needle:?} twice");
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = text[start..at].chars().count() + 1;
    format!("{}:{line}:{col}", path.display())
}

/// Asserts exit code 2, one line on stderr containing `expected` and then `message`, no panic,
/// no output written.
fn assert_refused(case: &str, o: &Output, expected: &str, message: &str, out: &Path) {
    let err = stderr_of(o);
    let ctx = format!("case {case}: exit {:?}, stderr {err:?}", o.status.code());
    assert!(!err.contains("panicked"), "{ctx}: panic");
    assert_eq!(o.status.code(), Some(2), "{ctx}: want exit code 2");
    assert_eq!(err.trim_end().lines().count(), 1, "{ctx}: want one line");
    let at = err
        .find(&format!("{expected}: "))
        .unwrap_or_else(|| panic!("{ctx}: does not name {expected:?}"));
    assert!(err[at..].contains(message), "{ctx}: lacks {message:?}");
    assert!(!out.exists(), "{ctx}: the output was written");
}

/// A scene with a 4x4 film (`W`, `H` and `SPP` replaced by the caller) and `body`.
fn scene(w: &str, h: &str, spp: &str, body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <film type="hdrfilm">
            <integer name="width" value="{w}"/>
            <integer name="height" value="{h}"/>
        </film>
        <sampler type="independent">
            <integer name="sample_count" value="{spp}"/>
        </sampler>
    </sensor>
    <emitter type="constant"/>
{body}</scene>
"#
    )
}

#[test]
fn control_small_scene_renders_under_the_memory_limit() {
    let tmp = temp_dir("control");
    let path = tmp.write("scene.xml", scene("4", "4", "2", ""));
    let out = tmp.0.join("image.pfm");
    let o = render(&path, &out, &[]);
    assert_eq!(o.status.code(), Some(0), "stderr {:?}", stderr_of(&o));
    assert!(out.is_file());
}

#[test]
fn absurd_film_sizes_and_sample_counts() {
    // (case, width, height, sample_count, needle the error must point at, message)
    let cases = [
        (
            "1e6 x 1e6",
            "1000000",
            "1000000",
            "1",
            "<integer name=\"width\"",
            "between 1 and 65536",
        ),
        (
            "negative width",
            "-5",
            "4",
            "1",
            "<integer name=\"width\"",
            "between 1 and 65536",
        ),
        (
            "zero height",
            "4",
            "0",
            "1",
            "<integer name=\"height\"",
            "between 1 and 65536",
        ),
        (
            "u32 overflow",
            "4294967297",
            "4",
            "1",
            "<integer name=\"width\"",
            "between 1 and 65536",
        ),
        (
            "i64 overflow",
            "99999999999999999999",
            "4",
            "1",
            "value=\"99999999999999999999\"",
            "not an integer",
        ),
        (
            "float width",
            "1e6",
            "4",
            "1",
            "value=\"1e6\"",
            "not an integer",
        ),
        // Each edge is allowed, the product is 3.6e9 pixels (230 GB of accumulators).
        (
            "60000 x 60000",
            "60000",
            "60000",
            "1",
            "<sensor",
            "over the limit of 67108864 pixels",
        ),
        (
            "spp 1e30",
            "4",
            "4",
            "1e30",
            "value=\"1e30\"",
            "not an integer",
        ),
        (
            "spp u64 overflow",
            "4",
            "4",
            "18446744073709551616",
            "value=\"18446744073709551616\"",
            "not an integer",
        ),
        (
            "spp 2^40+1",
            "4",
            "4",
            "1099511627777",
            "<integer name=\"sample_count\"",
            "between 1 and 2^40",
        ),
        (
            "spp negative",
            "4",
            "4",
            "-1",
            "<integer name=\"sample_count\"",
            "between 1 and 2^40",
        ),
        (
            "spp zero",
            "4",
            "4",
            "0",
            "<integer name=\"sample_count\"",
            "between 1 and 2^40",
        ),
    ];
    for (case, w, h, spp, needle, message) in cases {
        let tmp = temp_dir("film");
        let text = scene(w, h, spp, "");
        let path = tmp.write("scene.xml", &text);
        let out = tmp.0.join("image.png");
        let o = render(&path, &out, &[]);
        assert_refused(case, &o, &loc(&path, &text, needle), message, &out);
    }
}

#[test]
fn command_line_sample_count_that_overflows_u64() {
    let tmp = temp_dir("cli-spp");
    let path = tmp.write("scene.xml", scene("4", "4", "1", ""));
    let out = tmp.0.join("image.png");
    let o = render(&path, &out, &["--spp", "18446744073709551616"]);
    assert_refused("--spp 2^64", &o, "error", "18446744073709551616", &out);
}

#[test]
fn include_cycles_and_depth() {
    let inc =
        |f: &str| format!("<scene version=\"3.0.0\">\n    <include filename=\"{f}\"/>\n</scene>\n");
    // A file that includes itself.
    let tmp = temp_dir("self");
    let text = inc("self.xml");
    let path = tmp.write("self.xml", &text);
    let out = tmp.0.join("image.png");
    let o = render(&path, &out, &[]);
    assert_refused(
        "self include",
        &o,
        &loc(&path, &text, "<include"),
        "include cycle",
        &out,
    );

    // a.xml -> b.xml -> a.xml: the error is at b.xml's include.
    let tmp = temp_dir("cycle");
    let a = tmp.write("a.xml", inc("b.xml"));
    let b_text = inc("a.xml");
    let b = tmp.write("b.xml", &b_text);
    let out = tmp.0.join("image.png");
    let o = render(&a, &out, &[]);
    assert_refused(
        "a-b-a",
        &o,
        &loc(&b, &b_text, "<include"),
        "include cycle",
        &out,
    );

    // A chain of 40 files: refused at the 32nd file's include.
    let tmp = temp_dir("chain");
    for i in 0..40 {
        tmp.write(&format!("c{i}.xml"), inc(&format!("c{}.xml", i + 1)));
    }
    tmp.write("c40.xml", scene("4", "4", "1", ""));
    let out = tmp.0.join("image.png");
    let o = render(&tmp.0.join("c0.xml"), &out, &[]);
    let c31 = tmp.0.join("c31.xml");
    let want = loc(&c31, &inc("c32.xml"), "<include");
    assert_refused("chain of 40", &o, &want, "nested deeper than 32", &out);

    // Control: a chain of 20 loads and renders.
    let tmp = temp_dir("chain-ok");
    for i in 0..20 {
        tmp.write(&format!("c{i}.xml"), inc(&format!("c{}.xml", i + 1)));
    }
    tmp.write("c20.xml", scene("4", "4", "1", ""));
    let out = tmp.0.join("image.png");
    let o = render(&tmp.0.join("c0.xml"), &out, &[]);
    assert_eq!(o.status.code(), Some(0), "stderr {:?}", stderr_of(&o));
}

#[test]
fn deep_element_nesting_and_entity_expansion() {
    // 100 000 nested BSDFs: refused at the 65th level, no stack overflow.
    let n = 100_000;
    let body = format!(
        "<shape type=\"sphere\">\n{}{}\n</shape>\n",
        "<bsdf type=\"twosided\">".repeat(n),
        "</bsdf>".repeat(n)
    );
    let tmp = temp_dir("deep");
    let text = scene("4", "4", "1", &body);
    let path = tmp.write("scene.xml", &text);
    let out = tmp.0.join("image.png");
    let o = render(&path, &out, &[]);
    // Level 1 is <scene>, 2 <shape>, so the 63rd <bsdf> is level 65.
    let line = text.lines().position(|l| l.starts_with("<bsdf")).unwrap() + 1;
    let col = "<bsdf type=\"twosided\">".len() * 62 + 1;
    let want = format!("{}:{line}:{col}", path.display());
    assert_refused("deep nesting", &o, &want, "nested deeper than 64", &out);

    // A million nested elements of an unknown kind: the first is refused.
    let tmp = temp_dir("deep-unknown");
    let n = 1_000_000;
    let text = format!(
        "<scene>\n{}{}\n</scene>\n",
        "<a>".repeat(n),
        "</a>".repeat(n)
    );
    let path = tmp.write("scene.xml", &text);
    let out = tmp.0.join("image.png");
    let o = render(&path, &out, &[]);
    let want = format!("{}:2:1", path.display());
    assert_refused("deep unknown", &o, &want, "unknown element <a>", &out);

    // Billion laughs: DTDs are refused before any entity is expanded.
    let tmp = temp_dir("laughs");
    let mut dtd = String::from("<!DOCTYPE scene [<!ENTITY l0 \"lol\">");
    for i in 1..10 {
        let prev = format!("&l{};", i - 1).repeat(10);
        dtd.push_str(&format!("<!ENTITY l{i} \"{prev}\">"));
    }
    let text = format!("<?xml version=\"1.0\"?>\n{dtd}]>\n<scene>&l9;</scene>\n");
    let path = tmp.write("scene.xml", &text);
    let out = tmp.0.join("image.png");
    let o = render(&path, &out, &[]);
    assert_refused(
        "billion laughs",
        &o,
        &loc(&path, &text, "<!DOCTYPE"),
        "DTDs",
        &out,
    );
}

/// A scene whose one shape reads `file` as a `kind` mesh.
fn mesh_scene(kind: &str, file: &str) -> String {
    scene(
        "4",
        "4",
        "1",
        &format!("    <shape type=\"{kind}\">\n        <string name=\"filename\" value=\"{file}\"/>\n    </shape>\n"),
    )
}

const PLY_HEADER: &str = "ply\nformat FORMAT 1.0\nelement vertex NV\nproperty float x\nproperty float y\nproperty float z\nelement face NF\nproperty list uchar int vertex_indices\nend_header\n";

fn ply(format: &str, nv: &str, nf: &str, payload: &[u8]) -> Vec<u8> {
    let mut v = PLY_HEADER
        .replace("FORMAT", format)
        .replace("NV", nv)
        .replace("NF", nf)
        .into_bytes();
    v.extend_from_slice(payload);
    v
}

/// Three vertices and one triangle, as little-endian binary PLY data.
fn binary_triangle() -> Vec<u8> {
    let mut v = Vec::new();
    for x in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
        v.extend_from_slice(&x.to_le_bytes());
    }
    v.push(3);
    for i in [0i32, 1, 2] {
        v.extend_from_slice(&i.to_le_bytes());
    }
    v
}

#[test]
fn huge_meshes_referenced_by_mistake() {
    let ascii = b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    // (case, file name, contents, message)
    let cases: Vec<(&str, &str, Vec<u8>, &str)> = vec![
        (
            "ascii 4e9 vertices",
            "a.ply",
            ply("ascii", "4000000000", "1", ascii),
            "expected 4000000000",
        ),
        (
            "ascii 4e9 faces",
            "b.ply",
            ply("ascii", "3", "4000000000", ascii),
            "expected 4000000000",
        ),
        (
            "binary 4e9 vertices",
            "c.ply",
            ply(
                "binary_little_endian",
                "4000000000",
                "1",
                &binary_triangle(),
            ),
            "expected 4000000000",
        ),
        (
            "count beyond u64",
            "d.ply",
            ply("ascii", "99999999999999999999999", "1", ascii),
            "bad PLY file",
        ),
        (
            "obj index 4e9",
            "e.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n".to_vec(),
            "face refers to vertex 4000000000",
        ),
    ];
    for (case, name, bytes, message) in cases {
        let tmp = temp_dir("huge-mesh");
        let mesh = tmp.write(name, &bytes);
        let kind = &name[2..];
        let text = mesh_scene(kind, name);
        let path = tmp.write("scene.xml", &text);
        let out = tmp.0.join("image.png");
        let o = render(&path, &out, &[]);
        // Located in the mesh file when the mesh has lines (OBJ, ASCII PLY: the line where the
        // data ran out or the count is), else at the filename property.
        let want = match case {
            "obj index 4e9" => loc(&mesh, &String::from_utf8_lossy(&bytes), "4000000000"),
            "ascii 4e9 vertices" | "ascii 4e9 faces" => format!("{}:14:1", mesh.display()),
            "count beyond u64" => format!("{}:3:1", mesh.display()),
            _ => loc(&path, &text, "<string name=\"filename\""),
        };
        assert_refused(case, &o, &want, message, &out);
    }
    // Control: the same files with honest counts load.
    for (name, bytes) in [
        ("a.ply", ply("ascii", "3", "1", ascii)),
        (
            "c.ply",
            ply("binary_little_endian", "3", "1", &binary_triangle()),
        ),
    ] {
        let tmp = temp_dir("mesh-ok");
        tmp.write(name, &bytes);
        let path = tmp.write("scene.xml", mesh_scene("ply", name));
        let out = tmp.0.join("image.png");
        let o = render(&path, &out, &[]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{name}: stderr {:?}",
            stderr_of(&o)
        );
    }
}

#[test]
fn special_files_as_mesh_or_scene() {
    let tmp = temp_dir("special");
    std::fs::create_dir(tmp.0.join("dir.obj")).unwrap();
    for (kind, file, message) in [
        ("obj", "/dev/zero", "not a regular file"),
        ("ply", "/dev/zero", "not a regular file"),
        ("obj", "dir.obj", "not a regular file"),
        ("ply", "missing.ply", "cannot read mesh"),
    ] {
        let text = mesh_scene(kind, file);
        let path = tmp.write("scene.xml", &text);
        let out = tmp.0.join("image.png");
        let o = render(&path, &out, &[]);
        let want = loc(&path, &text, "<string name=\"filename\"");
        assert_refused(file, &o, &want, message, &out);
    }
    // A material library that is /dev/zero: ignored (plain OBJ: materials are not used) or
    // refused at its `mtllib` statement (use_mtl), after reading at most 64 MiB either way.
    let obj = tmp.write(
        "m.obj",
        "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let text = mesh_scene("obj", "m.obj");
    let path = tmp.write("scene.xml", &text);
    let out = tmp.0.join("image.exr");
    let o = render(&path, &out, &["--spp", "1"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "mtllib /dev/zero, plain: {}",
        stderr_of(&o)
    );
    std::fs::remove_file(&out).unwrap();
    let text = text.replace(
        "</shape>",
        "<boolean name=\"use_mtl\" value=\"true\"/></shape>",
    );
    let path = tmp.write("scene.xml", &text);
    let o = render(&path, &out, &[]);
    let want = loc(&obj, "mtllib /dev/zero\n", "mtllib");
    assert_refused("mtllib /dev/zero", &o, &want, "too large", &out);
    // The scene itself: /dev/zero stops at the 64 MiB limit; a directory is refused.
    let out = tmp.0.join("image.png");
    let o = render(Path::new("/dev/zero"), &out, &[]);
    assert_refused("scene /dev/zero", &o, "/dev/zero", "too large", &out);
    let o = render(&tmp.0, &out, &[]);
    assert_refused(
        "scene dir",
        &o,
        &tmp.0.display().to_string(),
        "directory",
        &out,
    );
}

#[test]
fn failed_write_keeps_the_previous_output() {
    // A 64x64 PFM is 49 KB; `ulimit -f 8` (8 KiB) makes the write fail in the middle.
    let tmp = temp_dir("fsize");
    let path = tmp.write("scene.xml", scene("64", "64", "1", ""));
    let out = tmp.write("image.pfm", "the previous good output");
    let args = [
        "render",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
    ];
    let o = run_limited("ulimit -f 8", &args);
    let err = stderr_of(&o);
    assert!(!err.contains("panicked"), "stderr {err:?}");
    assert_eq!(o.status.code(), Some(1), "stderr {err:?}");
    assert!(
        err.contains(&format!("{}: cannot write image", out.display())),
        "stderr {err:?}"
    );
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "the previous good output"
    );
    assert_eq!(
        tmp.entries(),
        ["image.pfm", "scene.xml"],
        "a temporary file was left"
    );

    // Control: without the limit the same command replaces the file.
    let o = run_limited("true", &args);
    assert_eq!(o.status.code(), Some(0), "stderr {:?}", stderr_of(&o));
    assert_eq!(std::fs::read(&out).unwrap().len(), 3 * 4 * 64 * 64 + 14);
    assert_eq!(tmp.entries(), ["image.pfm", "scene.xml"]);
}

#[test]
fn output_onto_a_directory_or_a_read_only_directory() {
    let tmp = temp_dir("outdir");
    let path = tmp.write("scene.xml", scene("4", "4", "1", ""));
    // An existing directory with the output's name: exit 1, the directory is left as it was.
    let out = tmp.0.join("image.png");
    std::fs::create_dir(&out).unwrap();
    let o = render(&path, &out, &[]);
    assert_eq!(o.status.code(), Some(1), "stderr {:?}", stderr_of(&o));
    assert!(out.is_dir() && std::fs::read_dir(&out).unwrap().next().is_none());
    assert_eq!(tmp.entries(), ["image.png", "scene.xml"]);

    // A read-only directory holding a good output (only meaningful when permissions apply:
    // root can write there anyway, which the probe detects).
    use std::os::unix::fs::PermissionsExt;
    let ro = tmp.0.join("ro");
    std::fs::create_dir(&ro).unwrap();
    let good = ro.join("image.pfm");
    std::fs::write(&good, "good").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let writable = std::fs::write(ro.join("probe"), "").is_ok();
    if !writable {
        let o = render(&path, &good, &[]);
        assert_eq!(o.status.code(), Some(1), "stderr {:?}", stderr_of(&o));
        assert_eq!(std::fs::read_to_string(&good).unwrap(), "good");
    } else {
        eprintln!("running as a user that can write read-only directories: part skipped");
    }
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
}

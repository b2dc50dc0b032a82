//! Mitsuba `.serialized` meshes (`<shape type="serialized">`).
//!
//! - Files written by Mitsuba (`tests/real/mitsuba-data/`, see its NOTICE) load to the same
//!   world-space positions, normals, uvs and triangles as Mitsuba 3.9.1 gives them: each
//!   `tests/serialized_cases/NAME.xml` holds one shape, `NAME.txt` is Mitsuba's view of it,
//!   written by `scripts/mitsuba_mesh_dump.py` (to_world with non-uniform scale, computed
//!   vertex normals, face normals; and the built-in `cube`, whose vertex order, normals and
//!   texture coordinates are Mitsuba's). Controls: another case's table, and a shifted
//!   to_world.
//! - The same rectangles as OBJ files (from the same source) load to the same mesh through the
//!   OBJ reader. Control: a different rectangle.
//! - Several shapes in one file are found through the end-of-file dictionary, in both its
//!   version 4 (`u64` offsets) and version 3 (`u32`) forms, and double precision and vertex
//!   colours are read; files written here from the documented layout, since the
//!   Mitsuba-written ones hold one single-precision shape each.
//! - Corrupt files (bad magic or version, truncated, a bad shape_index) are one-line errors
//!   naming the file at the shape's `filename`; every truncation and random byte changes never
//!   panic, and a truncated file never yields a different mesh.

use std::path::{Path, PathBuf};
use tessera_core::geometry::{Mesh, ShapeKind};
use tessera_scene::mesh::{load_obj, parse_serialized, MeshData};
use tessera_scene::{load_scene, load_scene_str};

fn tests_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn real(name: &str) -> PathBuf {
    tests_dir().join("real/mitsuba-data").join(name)
}

/// The only mesh of a loaded scene file.
fn only_mesh(path: &Path) -> Mesh {
    let l = load_scene(path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let meshes: Vec<Mesh> = l
        .scene
        .shapes
        .iter()
        .filter_map(|s| match &s.kind {
            ShapeKind::Mesh(m) => Some(m.clone()),
            _ => None,
        })
        .collect();
    assert_eq!(meshes.len(), 1, "{}", path.display());
    meshes.into_iter().next().unwrap()
}

/// Mitsuba's table: positions, normals, uvs (rows of floats) and faces.
struct Table {
    positions: Vec<Vec<f32>>,
    normals: Vec<Vec<f32>>,
    uvs: Vec<Vec<f32>>,
    faces: Vec<[u32; 3]>,
}

fn read_table(path: &Path) -> Table {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e} (run scripts/mitsuba_mesh_dump.py)", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let mut section = |name: &str| -> Vec<Vec<f32>> {
        let head = lines.next().expect("a section header");
        let n: usize = head
            .strip_prefix(name)
            .and_then(|r| r.trim().parse().ok())
            .unwrap_or_else(|| panic!("{}: expected \"{name} N\", found {head}", path.display()));
        (0..n)
            .map(|_| {
                let row = lines.next().expect("a row");
                row.split(' ').map(|x| x.parse().unwrap()).collect()
            })
            .collect()
    };
    let positions = section("positions");
    let normals = section("normals");
    let uvs = section("uvs");
    let faces = section("faces")
        .into_iter()
        .map(|r| [r[0] as u32, r[1] as u32, r[2] as u32])
        .collect();
    Table {
        positions,
        normals,
        uvs,
        faces,
    }
}

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs()).max(1.0)
}

/// Mismatches between Tessera's mesh and Mitsuba's table.
fn mismatches(mesh: &Mesh, t: &Table) -> Vec<String> {
    let mut bad = Vec::new();
    let mut rows = |what: &str, ours: Vec<Vec<f32>>, theirs: &[Vec<f32>]| {
        if ours.len() != theirs.len() {
            bad.push(format!(
                "{what}: {} rows, Mitsuba {}",
                ours.len(),
                theirs.len()
            ));
            return;
        }
        for (i, (a, b)) in ours.iter().zip(theirs).enumerate() {
            if a.len() != b.len() || !a.iter().zip(b).all(|(x, y)| close(*x, *y)) {
                bad.push(format!("{what} {i}: {a:?}, Mitsuba {b:?}"));
            }
        }
    };
    rows(
        "position",
        mesh.positions
            .iter()
            .map(|p| p.to_array().to_vec())
            .collect(),
        &t.positions,
    );
    rows(
        "normal",
        mesh.normals.iter().map(|p| p.to_array().to_vec()).collect(),
        &t.normals,
    );
    rows(
        "uv",
        mesh.uvs.iter().map(|p| p.to_array().to_vec()).collect(),
        &t.uvs,
    );
    if mesh.indices != t.faces {
        bad.push(format!("faces {:?}, Mitsuba {:?}", mesh.indices, t.faces));
    }
    bad
}

fn cases() -> Vec<PathBuf> {
    let mut c: Vec<PathBuf> = std::fs::read_dir(tests_dir().join("serialized_cases"))
        .expect("tests/serialized_cases exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    c.sort();
    c
}

#[test]
fn mitsuba_written_meshes_load_as_mitsuba_loads_them() {
    let cases = cases();
    assert!(cases.len() >= 3, "{} cases", cases.len());
    let mut failures = Vec::new();
    for c in &cases {
        let bad = mismatches(&only_mesh(c), &read_table(&c.with_extension("txt")));
        println!("{}: {} mismatches", c.display(), bad.len());
        failures.extend(bad.into_iter().map(|b| format!("{}: {b}", c.display())));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_wrong_mesh_is_caught() {
    let dir = tests_dir().join("serialized_cases");
    // Another case's table.
    let mesh = only_mesh(&dir.join("normals_uv_to_world.xml"));
    let other = read_table(&dir.join("uv_computed_normals.txt"));
    assert!(
        !mismatches(&mesh, &other).is_empty(),
        "another case's table matched"
    );
    // The same shape moved by 1e-3 along x.
    let text = std::fs::read_to_string(dir.join("normals_uv_to_world.xml")).unwrap();
    let moved = text.replace(r#"<translate x="1""#, r#"<translate x="1.001""#);
    assert_ne!(moved, text);
    let l = load_scene_str(&moved, &dir.join("moved.xml"), &[]).unwrap();
    let ShapeKind::Mesh(m) = &l.scene.shapes[0].kind else {
        panic!("not a mesh")
    };
    let own = read_table(&dir.join("normals_uv_to_world.txt"));
    let bad = mismatches(m, &own);
    assert_eq!(bad.len(), 4, "moved mesh: {bad:?}");
}

fn same_data(a: &MeshData, b: &MeshData) -> bool {
    let near = |x: &[f32], y: &[f32]| x.iter().zip(y).all(|(p, q)| (p - q).abs() <= 1e-6);
    a.positions.len() == b.positions.len()
        && a.positions
            .iter()
            .zip(&b.positions)
            .all(|(p, q)| near(p, q))
        && a.normals.len() == b.normals.len()
        && a.normals.iter().zip(&b.normals).all(|(p, q)| near(p, q))
        && a.uvs.len() == b.uvs.len()
        && a.uvs.iter().zip(&b.uvs).all(|(p, q)| near(p, q))
        && a.indices == b.indices
}

fn serialized(name: &str, index: u64) -> MeshData {
    let bytes = std::fs::read(real(&format!("{name}.serialized"))).unwrap();
    parse_serialized(&bytes, index).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn same_mesh_as_the_obj_file() {
    for name in ["rectangle_normals", "rectangle_uv", "rectangle_normals_uv"] {
        let obj = load_obj(&real(&format!("{name}.obj"))).unwrap();
        let ser = serialized(name, 0);
        assert!(
            same_data(&ser, &obj),
            "{name}: serialized {ser:?}\nobj {obj:?}"
        );
    }
    // Control: a rectangle without uvs is not the one with them.
    let obj = load_obj(&real("rectangle_normals_uv.obj")).unwrap();
    assert!(!same_data(&serialized("rectangle_normals", 0), &obj));
}

/// A `.serialized` file of `shapes` in format `version` (3 or 4), as the documented layout
/// says: per shape the header and a zlib stream, then the dictionary of offsets and the count.
fn write_serialized(shapes: &[MeshData], version: u16) -> Vec<u8> {
    write_serialized_as(shapes, version, false, false)
}

/// [`write_serialized`] with numbers in double precision (`double`) and with vertex colours
/// (`colours`, which a reader must skip).
fn write_serialized_as(shapes: &[MeshData], version: u16, double: bool, colours: bool) -> Vec<u8> {
    let mut file = Vec::new();
    let mut offsets = Vec::new();
    for (k, s) in shapes.iter().enumerate() {
        offsets.push(file.len() as u64);
        file.extend_from_slice(&0x041Cu16.to_le_bytes());
        file.extend_from_slice(&version.to_le_bytes());
        let mut raw = Vec::new();
        let flags = u32::from(!s.normals.is_empty())
            | (u32::from(!s.uvs.is_empty()) << 1)
            | (u32::from(colours) << 3)
            | if double { 0x2000 } else { 0x1000 };
        raw.extend_from_slice(&flags.to_le_bytes());
        if version == 4 {
            raw.extend_from_slice(format!("shape{k}\0").as_bytes());
        }
        raw.extend_from_slice(&(s.positions.len() as u64).to_le_bytes());
        raw.extend_from_slice(&(s.indices.len() as u64).to_le_bytes());
        let colour_values: Vec<f32> = if colours {
            (0..s.positions.len() * 3)
                .map(|i| i as f32 * 0.125)
                .collect()
        } else {
            Vec::new()
        };
        let floats = s
            .positions
            .iter()
            .flatten()
            .chain(s.normals.iter().flatten())
            .chain(s.uvs.iter().flatten())
            .chain(colour_values.iter());
        for v in floats {
            if double {
                raw.extend_from_slice(&f64::from(*v).to_le_bytes());
            } else {
                raw.extend_from_slice(&v.to_le_bytes());
            }
        }
        for i in s.indices.iter().flatten() {
            raw.extend_from_slice(&i.to_le_bytes());
        }
        file.extend(miniz_oxide::deflate::compress_to_vec_zlib(&raw, 6));
    }
    for o in &offsets {
        if version == 4 {
            file.extend_from_slice(&o.to_le_bytes());
        } else {
            file.extend_from_slice(&(*o as u32).to_le_bytes());
        }
    }
    file.extend_from_slice(&(shapes.len() as u32).to_le_bytes());
    file
}

/// Three different shapes: the Mitsuba-written rectangles.
fn three_shapes() -> Vec<MeshData> {
    ["rectangle_normals", "rectangle_uv", "rectangle_normals_uv"]
        .iter()
        .map(|n| serialized(n, 0))
        .collect()
}

#[test]
fn shape_index_reads_the_dictionary() {
    let shapes = three_shapes();
    for version in [3, 4] {
        let file = write_serialized(&shapes, version);
        for (k, s) in shapes.iter().enumerate() {
            let got = parse_serialized(&file, k as u64).unwrap();
            assert!(same_data(&got, s), "version {version}, shape {k}");
            // Control: the other shapes differ from this one.
            for (j, other) in shapes.iter().enumerate().filter(|(j, _)| *j != k) {
                assert!(
                    !same_data(&got, other),
                    "version {version}: shapes {k} and {j}"
                );
            }
        }
        let e = parse_serialized(&file, 3).unwrap_err();
        assert!(e.contains("shape_index 3 is out of range"), "{e}");
        assert!(e.contains("3 shapes"), "{e}");
    }
}

#[test]
fn double_precision_and_vertex_colours() {
    let shapes = three_shapes();
    for double in [false, true] {
        for colours in [false, true] {
            let file = write_serialized_as(&shapes, 4, double, colours);
            for (k, s) in shapes.iter().enumerate() {
                let got = parse_serialized(&file, k as u64)
                    .unwrap_or_else(|e| panic!("double {double}, colours {colours}: {e}"));
                assert!(
                    same_data(&got, s),
                    "double {double}, colours {colours}, shape {k}"
                );
            }
        }
    }
    // Control: double-precision data read as single precision is not the mesh.
    let mut file = write_serialized_as(&shapes[2..], 4, true, false);
    let data = miniz_oxide::inflate::decompress_to_vec_zlib(&file[4..]).unwrap();
    let mut single = data.clone();
    single[..4].copy_from_slice(
        &(u32::from_le_bytes(data[..4].try_into().unwrap()) & !0x2000).to_le_bytes(),
    );
    let dictionary = file.split_off(file.len() - 12);
    file.truncate(4);
    file.extend(miniz_oxide::deflate::compress_to_vec_zlib(&single, 6));
    file.extend(dictionary);
    if let Ok(m) = parse_serialized(&file, 0) {
        assert!(
            !same_data(&m, &shapes[2]),
            "double precision read as single gave the mesh"
        );
    }
}

/// The one-line load error of a scene whose only shape reads `file` (written to a temporary
/// folder) with the given extra XML; the shape element starts at line 2, column 1.
fn load_error(bytes: &[u8], extra: &str) -> String {
    let dir = std::env::temp_dir().join(format!("tessera-serialized-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.serialized"), bytes).unwrap();
    let xml = format!(
        "<scene version=\"3.0.0\">\n<shape type=\"serialized\"><string name=\"filename\" \
         value=\"m.serialized\"/>{extra}</shape>\n<sensor type=\"perspective\"/></scene>"
    );
    let e = match load_scene_str(&xml, &dir.join("scene.xml"), &[]) {
        Ok(_) => panic!("loaded: {extra}"),
        Err(e) => e.to_string(),
    };
    assert!(!e.contains('\n'), "not one line: {e}");
    e
}

#[test]
fn corrupt_files_are_located_errors() {
    let good = std::fs::read(real("rectangle_normals_uv.serialized")).unwrap();
    // Where the `filename` property is: line 2, column 26.
    let at = "scene.xml:2:26";
    let mut bad_magic = good.clone();
    bad_magic[0] = 0x1D;
    let mut bad_version = good.clone();
    bad_version[2] = 9;
    let cases: Vec<(Vec<u8>, &str, &str)> = vec![
        (bad_magic, "", "not a serialized mesh"),
        (bad_version, "", "format version 9"),
        (good[..3].to_vec(), "", "inside a shape header"),
        (good[..40].to_vec(), "", "shape 0"),
        (
            good.clone(),
            r#"<integer name="shape_index" value="1"/>"#,
            "shape_index 1 is out of range: the file holds 1 shape",
        ),
        (
            good.clone(),
            r#"<integer name="shape_index" value="5"/>"#,
            "shape_index 5 is out of range",
        ),
    ];
    for (bytes, extra, words) in cases {
        let e = load_error(&bytes, extra);
        println!("{e}");
        assert!(e.contains(at), "{e}: not at {at}");
        assert!(e.contains("m.serialized"), "{e}: does not name the file");
        assert!(e.contains(words), "{e}: does not say {words:?}");
    }
    // A negative shape_index is refused at its own element.
    let e = load_error(&good, r#"<integer name="shape_index" value="-1"/>"#);
    assert!(
        e.contains("scene.xml:2:") && e.contains("shape_index"),
        "{e}"
    );
    // Control: the good file loads.
    let dir = std::env::temp_dir().join(format!("tessera-serialized-{}", std::process::id()));
    std::fs::write(dir.join("m.serialized"), &good).unwrap();
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"serialized\"><string name=\"filename\" \
               value=\"m.serialized\"/></shape>\n<sensor type=\"perspective\"/></scene>";
    load_scene_str(xml, &dir.join("scene.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
}

/// A small deterministic generator (SplitMix64) for the random corruptions.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[test]
fn random_truncations_and_flips_never_panic() {
    let single = std::fs::read(real("rectangle_normals_uv.serialized")).unwrap();
    let multi = write_serialized(&three_shapes(), 4);
    let mut state = 7u64;
    let mut errors = 0;
    for file in [&single, &multi] {
        // Every truncation: an error, or (when the cut spares the shape read, as a cut in the
        // dictionary does for shape 0, which is found without it) exactly the untruncated mesh.
        for index in 0..3 {
            let whole = parse_serialized(file, index).ok();
            for n in 0..file.len() {
                match parse_serialized(&file[..n], index) {
                    Err(_) => errors += 1,
                    Ok(m) => {
                        let same = whole.as_ref().is_some_and(|w| same_data(w, &m));
                        assert!(
                            same,
                            "a file truncated to {n} bytes gave another shape {index}"
                        );
                    }
                }
            }
        }
        // Random byte changes: any outcome but a panic, and a loaded mesh is valid.
        for _ in 0..3000 {
            let mut f = file.clone();
            for _ in 0..1 + splitmix(&mut state) % 4 {
                let i = (splitmix(&mut state) % f.len() as u64) as usize;
                f[i] = splitmix(&mut state) as u8;
            }
            let index = splitmix(&mut state) % 4;
            if let Ok(m) = parse_serialized(&f, index) {
                let n = m.positions.len();
                assert!(m.normals.is_empty() || m.normals.len() == n);
                assert!(m.uvs.is_empty() || m.uvs.len() == n);
            }
        }
    }
    assert!(errors > 0);
}

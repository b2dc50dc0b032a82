//! Wavefront OBJ meshes, read with `tobj` (polygons fan-triangulated, one index per vertex),
//! optionally with their MTL materials.
//!
//! Scene parameters (`<shape type="obj">`): `filename` (string, required), `to_world` (transform),
//! `face_normals` (boolean, default false: use the file's vertex normals, or smooth ones computed
//! from the faces when the file has none), `flip_normals` (boolean, default false), `use_mtl`
//! (boolean, default false; a Tessera extension, see `scene/src/shapes/mesh_file.rs`). Without `use_mtl` all
//! objects and groups of the file form one mesh and `mtllib` / `usemtl` are ignored, as in
//! Mitsuba 3; with it, the faces are split by material.
use super::data::{read_mesh_bytes, MeshData};
use super::mtl::{load_mtl, MtlMaterial};
use super::obj_locate::locate_obj_error;
use crate::error::{InputError, Loc};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// An OBJ file's triangles grouped by material.
#[derive(Clone, Debug, Default)]
pub struct ObjParts {
    /// The faces before any `usemtl`, if there are some.
    pub plain: Option<MeshData>,
    /// Each material used (an index into `materials`) with its faces, in file order of first
    /// use.
    pub by_material: Vec<(usize, MeshData)>,
    /// Every material of the file's `mtllib`s, in library order.
    pub materials: Vec<MtlMaterial>,
}

// tobj's optional features add fields to `LoadOptions`; the update keeps this building with them.
#[allow(clippy::needless_update)]
fn options() -> tobj::LoadOptions {
    tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    }
}

fn bad_obj(path: &Path, text: &str, e: tobj::LoadError) -> InputError {
    locate_obj_error(path, text)
        .unwrap_or_else(|| InputError::file(path, format!("bad OBJ file: {e}")))
}

/// Loads an OBJ file as one mesh (materials ignored).
pub fn load_obj(path: &Path) -> Result<MeshData, InputError> {
    let bytes = read_mesh_bytes(path)?;
    let text = String::from_utf8_lossy(&bytes);
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    // As `tobj::load_obj` does: the libraries are read (a `usemtl` splits the faces into models
    // before they are merged again) and a library that cannot be read is ignored.
    // Read through the capped reader: `mtllib /dev/zero` must not exhaust memory even though
    // the materials are then ignored.
    let (models, _) = tobj::load_obj_buf(&mut bytes.as_slice(), &options(), |lib| {
        let text = crate::xml::source::read_text(&dir.join(lib))
            .map_err(|_| tobj::LoadError::OpenFileFailed)?;
        tobj::load_mtl_buf(&mut text.as_bytes())
    })
    .map_err(|e| bad_obj(path, &text, e))?;
    merge(path, &text, &models.iter().collect::<Vec<_>>())
}

/// The `mtllib` and `usemtl` statements of an OBJ text: (keyword, argument, position).
fn statements(text: &str, path: &Path) -> Vec<(&'static str, String, Loc)> {
    let file = Arc::new(path.to_path_buf());
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let start = line.len() - line.trim_start().len();
        let t = &line[start..];
        for kw in ["mtllib", "usemtl"] {
            if let Some(rest) = t.strip_prefix(kw) {
                if rest.starts_with(char::is_whitespace) {
                    let loc = Loc::new(file.clone(), ln as u32 + 1, start as u32 + 1);
                    out.push((kw, rest.trim().to_string(), loc));
                }
            }
        }
    }
    out
}

/// Loads an OBJ file with its MTL libraries, split into one mesh per material. A `usemtl` that
/// names no material of the libraries, or a library that cannot be read, is an error at its
/// statement.
pub fn load_obj_with_materials(path: &Path) -> Result<ObjParts, InputError> {
    let bytes = read_mesh_bytes(path)?;
    let text = String::from_utf8_lossy(&bytes);
    let stmts = statements(&text, path);
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let materials = RefCell::new(Vec::<MtlMaterial>::new());
    let failure = RefCell::new(None::<InputError>);
    let loader = |lib: &Path| -> tobj::MTLLoadResult {
        let loaded = load_mtl(&dir.join(lib)).map_err(|e| {
            // Point at the mtllib statement when the library itself cannot be read.
            match (
                &e.loc,
                stmts
                    .iter()
                    .find(|s| s.0 == "mtllib" && Path::new(&s.1) == lib),
            ) {
                (None, Some(s)) => InputError::at(&s.2, format!("mtllib \"{}\": {}", s.1, e.msg)),
                _ => e,
            }
        });
        match loaded {
            Ok(list) => {
                let map: HashMap<String, usize> = list
                    .iter()
                    .enumerate()
                    .map(|(i, m)| (m.name.clone(), i))
                    .collect();
                let names = list
                    .iter()
                    .map(|m| tobj::Material {
                        name: m.name.clone(),
                        ..Default::default()
                    })
                    .collect();
                materials.borrow_mut().extend(list);
                Ok((names, map))
            }
            Err(e) => {
                failure.borrow_mut().get_or_insert(e);
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    // tobj reads the argument of `mtllib` / `usemtl` after the line's first space: give it
    // lines without indentation and with one space after those keywords.
    let normalized: String = text
        .lines()
        .map(|l| {
            let t = l.trim_start();
            match ["mtllib", "usemtl"].iter().find_map(|kw| {
                t.strip_prefix(kw)
                    .filter(|r| r.starts_with(char::is_whitespace))
                    .map(|r| (kw, r.trim()))
            }) {
                Some((kw, arg)) => format!("{kw} {arg}\n"),
                None => format!("{t}\n"),
            }
        })
        .collect();
    let mut reader = std::io::Cursor::new(normalized.as_bytes());
    let result = tobj::load_obj_buf(&mut reader, &options(), loader);
    if let Some(e) = failure.into_inner() {
        return Err(e);
    }
    let (models, _) = result.map_err(|e| bad_obj(path, &text, e))?;
    let materials = materials.into_inner();
    if let Some(s) = stmts
        .iter()
        .find(|s| s.0 == "usemtl" && !materials.iter().any(|m| m.name == s.1))
    {
        return Err(InputError::at(
            &s.2,
            format!("usemtl \"{}\": no such material in the file's mtllib", s.1),
        ));
    }
    let mut groups: Vec<(Option<usize>, Vec<&tobj::Model>)> = Vec::new();
    for m in &models {
        let id = m.mesh.material_id;
        match groups.iter_mut().find(|g| g.0 == id) {
            Some(g) => g.1.push(m),
            None => groups.push((id, vec![m])),
        }
    }
    let mut parts = ObjParts {
        materials,
        ..Default::default()
    };
    for (id, list) in groups {
        let data = merge(path, &text, &list)?;
        if data.indices.is_empty() {
            continue;
        }
        match id {
            Some(i) => parts.by_material.push((i, data)),
            None => parts.plain = Some(data),
        }
    }
    Ok(parts)
}

/// One mesh from several `tobj` models.
fn merge(path: &Path, text: &str, models: &[&tobj::Model]) -> Result<MeshData, InputError> {
    let mut data = MeshData::default();
    let with_normals = models.iter().all(|m| !m.mesh.normals.is_empty()) && !models.is_empty();
    let with_uvs = models.iter().all(|m| !m.mesh.texcoords.is_empty()) && !models.is_empty();
    for m in models {
        let base = data.positions.len() as u64;
        let mesh = &m.mesh;
        data.positions
            .extend(mesh.positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        if with_normals {
            data.normals
                .extend(mesh.normals.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        }
        if with_uvs {
            // OBJ's v axis points up the image; Mitsuba 3 flips it (measured), and so do we.
            data.uvs
                .extend(mesh.texcoords.chunks_exact(2).map(|c| [c[0], 1.0 - c[1]]));
        }
        for t in mesh.indices.chunks_exact(3) {
            let idx = [base + t[0] as u64, base + t[1] as u64, base + t[2] as u64];
            if idx.iter().any(|&i| i > u32::MAX as u64) {
                return Err(InputError::file(path, "mesh has more than 2^32 vertices"));
            }
            data.indices.push(idx.map(|i| i as u32));
        }
    }
    let finite = data
        .positions
        .iter()
        .flatten()
        .chain(data.normals.iter().flatten())
        .chain(data.uvs.iter().flatten())
        .all(|v| v.is_finite());
    if !finite {
        return Err(locate_obj_error(path, text)
            .unwrap_or_else(|| InputError::file(path, "mesh has a non-finite number")));
    }
    data.validate(path)?;
    Ok(data)
}

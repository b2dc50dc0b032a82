//! Stanford PLY meshes (ASCII and binary), read with `ply-rs-bw`.
//!
//! Scene parameters (`<shape type="ply">`): `filename` (string, required), `to_world`,
//! `face_normals` (boolean, default false), `flip_normals` (boolean, default false). Reads the
//! `vertex` element's `x y z`, optional `nx ny nz` and `u v` (or `s t`), and the `face` element's
//! `vertex_indices` (or `vertex_index`) lists, fan-triangulated, and the other properties of
//! both as Mitsuba 3's mesh attributes (`ply_attributes.rs`; a face's values are repeated for
//! each triangle of its fan).
use super::data::MeshData;
use super::ply_locate::{parse_error, record_error};
use crate::error::InputError;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Header, Property, PropertyType};
use std::path::Path;
use tessera_core::geometry::MeshAttribute;

fn scalar(e: &DefaultElement, key: &str) -> Option<f32> {
    e.get(key).and_then(|p| p.to_f32_lossy())
}

/// A mesh attribute's component `name` of record `e`, as a float (integers as they are, as
/// Mitsuba 3 reads them).
fn attribute_value(e: &DefaultElement, name: &str) -> Result<f32, String> {
    match scalar(e, name) {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(format!("non-finite mesh attribute value {name}")),
        None => Err(format!("mesh attribute property {name} is not a number")),
    }
}

fn list(p: &Property) -> Option<Vec<i64>> {
    Some(match p {
        Property::ListChar(v) => v.iter().map(|&x| x as i64).collect(),
        Property::ListUChar(v) => v.iter().map(|&x| x as i64).collect(),
        Property::ListShort(v) => v.iter().map(|&x| x as i64).collect(),
        Property::ListUShort(v) => v.iter().map(|&x| x as i64).collect(),
        Property::ListInt(v) => v.iter().map(|&x| x as i64).collect(),
        Property::ListUInt(v) => v.iter().map(|&x| x as i64).collect(),
        _ => return None,
    })
}

/// Which whitespace-separated value of an ASCII record holds scalar property `prop` (`None`
/// when a list comes before it, so its position varies from record to record).
fn scalar_token(header: &Header, element: &str, prop: &str) -> Option<usize> {
    let def = header.elements.get(element)?;
    for (k, (name, p)) in def.properties.iter().enumerate() {
        if name == prop {
            return Some(k);
        }
        if matches!(p.data_type, PropertyType::List(..)) {
            return None;
        }
    }
    None
}

/// Where list property `prop` of the face element starts (only when it is the first property).
fn list_token(header: &Header, prop: &str) -> Option<usize> {
    let def = header.elements.get("face")?;
    (def.properties.get_index(0)?.0 == prop).then_some(0)
}

/// Loads a PLY file.
pub fn load_ply(path: &Path) -> Result<MeshData, InputError> {
    let err = |m: String| InputError::file(path, m);
    let bytes = super::data::read_mesh_bytes(path)?;
    let mut r = bytes.as_slice();
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut r)
        .map_err(|e| parse_error(path, &bytes, &e))?;
    let at = |element: &str, index: usize, token: Option<usize>, msg: String| {
        record_error(path, &bytes, &ply.header, element, index, token, msg)
    };
    let verts = ply
        .payload
        .get("vertex")
        .ok_or_else(|| err("PLY file has no vertex element".into()))?;
    let faces = ply
        .payload
        .get("face")
        .ok_or_else(|| err("PLY file has no face element".into()))?;
    let mut data = MeshData::default();
    // Each attribute's name and the names of its component properties, per element.
    let mut vertex_attrs = Vec::new();
    let mut face_attrs = Vec::new();
    for kind in ["vertex", "face"] {
        if let Some(def) = ply.header.elements.get(kind) {
            let mut fields = Vec::new();
            for (name, p) in &def.properties {
                match p.data_type {
                    // Mitsuba's reader writes a list as its count and three entries.
                    PropertyType::List(..) => {
                        fields.push(format!("{name}.count"));
                        fields.extend(["i0", "i1", "i2"].map(String::from));
                    }
                    _ => fields.push(name.clone()),
                }
            }
            for (name, parts) in super::ply_attributes::mitsuba_attributes(kind, &fields) {
                let parts: Vec<String> = parts.iter().map(|&k| fields[k].clone()).collect();
                if kind == "vertex" {
                    vertex_attrs.push((name, parts));
                } else {
                    face_attrs.push((name, parts));
                }
            }
        }
    }
    let mut vertex_values: Vec<Vec<f32>> = vec![Vec::new(); vertex_attrs.len()];
    let mut face_values: Vec<Vec<f32>> = vec![Vec::new(); face_attrs.len()];
    let has_n = verts.first().is_some_and(|v| v.get("nx").is_some());
    let uv_keys = verts.first().and_then(|v| {
        if v.get("u").is_some() {
            Some(("u", "v"))
        } else if v.get("s").is_some() {
            Some(("s", "t"))
        } else {
            None
        }
    });
    for (i, v) in verts.iter().enumerate() {
        let p = [scalar(v, "x"), scalar(v, "y"), scalar(v, "z")];
        let [Some(x), Some(y), Some(z)] = p else {
            return Err(at("vertex", i, None, "vertex lacks x, y or z".into()));
        };
        if let Some(k) = [x, y, z].iter().position(|c| !c.is_finite()) {
            let name = ["x", "y", "z"][k];
            let token = scalar_token(&ply.header, "vertex", name);
            return Err(at("vertex", i, token, format!("non-finite vertex {name}")));
        }
        data.positions.push([x, y, z]);
        if has_n {
            let n = [
                scalar(v, "nx").unwrap_or(0.0),
                scalar(v, "ny").unwrap_or(0.0),
                scalar(v, "nz").unwrap_or(0.0),
            ];
            if let Some(k) = n.iter().position(|c| !c.is_finite()) {
                let name = ["nx", "ny", "nz"][k];
                let token = scalar_token(&ply.header, "vertex", name);
                return Err(at("vertex", i, token, format!("non-finite normal {name}")));
            }
            data.normals.push(n);
        }
        if let Some((ku, kv)) = uv_keys {
            data.uvs
                .push([scalar(v, ku).unwrap_or(0.0), scalar(v, kv).unwrap_or(0.0)]);
        }
        for ((_, parts), values) in vertex_attrs.iter().zip(&mut vertex_values) {
            for name in parts {
                values.push(
                    attribute_value(v, name).map_err(|m| {
                        at("vertex", i, scalar_token(&ply.header, "vertex", name), m)
                    })?,
                );
            }
        }
    }
    let n = data.positions.len() as i64;
    for (fi, f) in faces.iter().enumerate() {
        let key = if f.get("vertex_indices").is_some() {
            "vertex_indices"
        } else {
            "vertex_index"
        };
        let idx = f.get(key).and_then(list);
        let idx =
            idx.ok_or_else(|| at("face", fi, None, "face has no vertex_indices list".into()))?;
        if let Some(j) = idx.iter().position(|&i| i < 0 || i >= n) {
            // The list's values follow its length, so value j is token 1 + j when the list
            // comes first.
            let token = list_token(&ply.header, key).map(|k| k + 1 + j);
            let bad = idx[j];
            return Err(at(
                "face",
                fi,
                token,
                format!("face refers to vertex {bad}, but the file has {n}"),
            ));
        }
        let mut row = Vec::new();
        for ((_, parts), values) in face_attrs.iter().zip(&mut face_values) {
            row.clear();
            for name in parts {
                row.push(
                    attribute_value(f, name)
                        .map_err(|m| at("face", fi, scalar_token(&ply.header, "face", name), m))?,
                );
            }
            // One row per triangle of the face's fan.
            for _ in 1..idx.len().saturating_sub(1) {
                values.extend_from_slice(&row);
            }
        }
        for k in 1..idx.len().saturating_sub(1) {
            data.indices
                .push([idx[0] as u32, idx[k] as u32, idx[k + 1] as u32]);
        }
    }
    let attributes = vertex_attrs
        .into_iter()
        .zip(vertex_values)
        .map(|(a, v)| (a, v, false))
        .chain(
            face_attrs
                .into_iter()
                .zip(face_values)
                .map(|(a, v)| (a, v, true)),
        );
    for ((name, parts), values, per_face) in attributes {
        data.attributes.push(MeshAttribute {
            name,
            dim: parts.len(),
            per_face,
            values,
        });
    }
    data.validate(path)?;
    Ok(data)
}

//! Stanford PLY meshes (ASCII and binary), read with `ply-rs-bw`.
//!
//! Scene parameters (`<shape type="ply">`): `filename` (string, required), `to_world`,
//! `face_normals` (boolean, default false), `flip_normals` (boolean, default false). Reads the
//! `vertex` element's `x y z`, optional `nx ny nz` and `u v` (or `s t`), and the `face` element's
//! `vertex_indices` (or `vertex_index`) lists, fan-triangulated.
use super::MeshData;
use crate::error::InputError;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};
use std::path::Path;

fn scalar(e: &DefaultElement, key: &str) -> Option<f32> {
    e.get(key).and_then(|p| p.to_f32_lossy())
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

/// Loads a PLY file.
pub fn load_ply(path: &Path) -> Result<MeshData, InputError> {
    let err = |m: String| InputError::file(path, m);
    let bytes = super::read_mesh_bytes(path)?;
    let mut r = bytes.as_slice();
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut r)
        .map_err(|e| err(format!("bad PLY file: {e}")))?;
    let verts = ply
        .payload
        .get("vertex")
        .ok_or_else(|| err("PLY file has no vertex element".into()))?;
    let faces = ply
        .payload
        .get("face")
        .ok_or_else(|| err("PLY file has no face element".into()))?;
    let mut data = MeshData::default();
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
            return Err(err(format!("vertex {i} lacks x, y or z")));
        };
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return Err(err(format!("vertex {i} has a non-finite coordinate")));
        }
        data.positions.push([x, y, z]);
        if has_n {
            let n = [
                scalar(v, "nx").unwrap_or(0.0),
                scalar(v, "ny").unwrap_or(0.0),
                scalar(v, "nz").unwrap_or(0.0),
            ];
            if !n.iter().all(|c| c.is_finite()) {
                return Err(err(format!("vertex {i} has a non-finite normal")));
            }
            data.normals.push(n);
        }
        if let Some((ku, kv)) = uv_keys {
            data.uvs
                .push([scalar(v, ku).unwrap_or(0.0), scalar(v, kv).unwrap_or(0.0)]);
        }
    }
    let n = data.positions.len() as i64;
    for (fi, f) in faces.iter().enumerate() {
        let idx = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .and_then(list);
        let idx = idx.ok_or_else(|| err(format!("face {fi} has no vertex_indices list")))?;
        if let Some(bad) = idx.iter().find(|&&i| i < 0 || i >= n) {
            return Err(err(format!(
                "face {fi} refers to vertex {bad}, but the file has {n}"
            )));
        }
        for k in 1..idx.len().saturating_sub(1) {
            data.indices
                .push([idx[0] as u32, idx[k] as u32, idx[k + 1] as u32]);
        }
    }
    data.validate(path)?;
    Ok(data)
}

//! Mitsuba's `.serialized` meshes, as Mitsuba 3.9.1 reads them (`src/shapes/serialized.cpp`),
//! the format versions 3 and 4 that Mitsuba 0.x writes.
//!
//! Layout, little-endian: per shape, an uncompressed header (`u16` magic `0x041C`, `u16`
//! version) followed by a zlib stream holding a `u32` flag word (`0x1` vertex normals, `0x2`
//! texture coordinates, `0x8` vertex colours, `0x2000` double precision; others unused here),
//! in version 4 the shape's NUL-terminated name, `u64` vertex and `u64` triangle counts, then
//! positions, normals, uvs and colours (3, 3, 2, 3 floats per vertex, each array present by its
//! flag) and `3 u32` indices per triangle. The file ends with a dictionary: each shape's byte
//! offset (`u64`, or `u32` in version 3), then the `u32` shape count. Colours are read past, as
//! Mitsuba 3 does; so is the file's face-normal flag, which Mitsuba 3.9.1 does not apply
//! either (the scene's `face_normals` decides).
//!
//! Nothing here trusts the file: every count is checked against the bytes there are before
//! anything is allocated for it, and the decompressed size is bounded by what deflate can
//! expand the compressed bytes to.
use super::data::{read_mesh_bytes, MeshData};
use crate::error::InputError;
use std::path::Path;

/// The first `u16` of the file and of every shape.
const MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_UVS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const DOUBLE_PRECISION: u32 = 0x2000;

/// Deflate expands at most about 1032 to 1: a bound on a shape's decompressed size.
const MAX_EXPANSION: usize = 1100;

/// Reads shape `index` of the `.serialized` file at `path` (object space).
pub(crate) fn load_serialized(path: &Path, index: u64) -> Result<MeshData, InputError> {
    let bytes = read_mesh_bytes(path)?;
    parse_serialized(&bytes, index)
        .map_err(|m| InputError::file(path, format!("serialized mesh: {m}")))
        .and_then(|data| data.validate(path).map(|_| data))
}

/// Shape `index` of a `.serialized` file's bytes; the error says what is wrong.
pub fn parse_serialized(bytes: &[u8], index: u64) -> Result<MeshData, String> {
    let (magic, version) = header(bytes, 0)?;
    if magic != MAGIC {
        return Err(format!(
            "not a serialized mesh (starts with 0x{magic:04X}, not 0x{MAGIC:04X})"
        ));
    }
    if version != 3 && version != 4 {
        return Err(format!("format version {version} (3 and 4 are read)"));
    }
    let start = if index == 0 {
        0
    } else {
        shape_offset(bytes, version, index)?
    };
    if header(bytes, start)? != (MAGIC, version) {
        return Err(format!(
            "shape {index} at byte {start} does not start with the file's header"
        ));
    }
    let compressed = &bytes[start + 4..];
    let limit = compressed.len().saturating_mul(MAX_EXPANSION);
    let data = miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(compressed, limit)
        .map_err(|e| format!("shape {index}: corrupt compressed data ({:?})", e.status))?;
    parse_shape(&data, version).map_err(|m| format!("shape {index}: {m}"))
}

/// The magic and version at `at`.
fn header(bytes: &[u8], at: usize) -> Result<(u16, u16), String> {
    let h = bytes
        .get(at..at + 4)
        .ok_or_else(|| format!("file ends at byte {} inside a shape header", bytes.len()))?;
    Ok((
        u16::from_le_bytes([h[0], h[1]]),
        u16::from_le_bytes([h[2], h[3]]),
    ))
}

/// The byte offset of shape `index` from the dictionary at the end of the file.
fn shape_offset(bytes: &[u8], version: u16, index: u64) -> Result<usize, String> {
    let n = bytes.len();
    let short = || "file too short for its dictionary of shapes".to_string();
    let count = u64::from(u32::from_le_bytes(
        bytes
            .get(n.checked_sub(4).ok_or_else(short)?..)
            .and_then(|b| b.try_into().ok())
            .ok_or_else(short)?,
    ));
    if index >= count {
        return Err(format!(
            "shape_index {index} is out of range: the file holds {count} shape{}",
            if count == 1 { "" } else { "s" }
        ));
    }
    let width: u64 = if version >= 4 { 8 } else { 4 };
    let back = (count - index)
        .checked_mul(width)
        .and_then(|b| b.checked_add(4))
        .filter(|&b| b <= n as u64)
        .ok_or_else(short)?;
    let at = n - back as usize;
    let raw = &bytes[at..at + width as usize];
    let offset = if width == 8 {
        u64::from_le_bytes(raw.try_into().map_err(|_| short())?)
    } else {
        u64::from(u32::from_le_bytes(raw.try_into().map_err(|_| short())?))
    };
    usize::try_from(offset)
        .ok()
        .filter(|&o| o < at)
        .ok_or_else(|| format!("shape {index}'s offset {offset} is outside the file"))
}

/// A little-endian reader of a decompressed shape that never reads past its end.
struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let end = self.pos.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| {
            format!(
                "data ends at byte {} of the shape, inside its {what}",
                self.bytes.len()
            )
        })?;
        let s = &self.bytes[self.pos..end];
        self.pos = end;
        Ok(s)
    }

    fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self, what: &str) -> Result<u64, String> {
        let b = self.take(8, what)?;
        Ok(u64::from_le_bytes(b.try_into().unwrap_or_default()))
    }

    /// `n` vectors of `D` floats (`f64` narrowed to `f32` when `double`).
    fn floats<const D: usize>(
        &mut self,
        n: usize,
        double: bool,
        what: &str,
    ) -> Result<Vec<[f32; D]>, String> {
        let size = if double { 8 } else { 4 };
        let b = self.take(n * D * size, what)?;
        Ok(b.chunks_exact(D * size)
            .map(|v| {
                std::array::from_fn(|k| {
                    let c = &v[k * size..(k + 1) * size];
                    if double {
                        f64::from_le_bytes(c.try_into().unwrap_or_default()) as f32
                    } else {
                        f32::from_le_bytes(c.try_into().unwrap_or_default())
                    }
                })
            })
            .collect())
    }
}

/// One decompressed shape.
fn parse_shape(data: &[u8], version: u16) -> Result<MeshData, String> {
    let mut r = Reader {
        bytes: data,
        pos: 0,
    };
    let flags = r.u32("flags")?;
    if version == 4 {
        let name_len = data[r.pos..]
            .iter()
            .position(|&b| b == 0)
            .ok_or("the shape's name is not terminated")?;
        r.take(name_len + 1, "name")?;
    }
    let vertices = r.u64("vertex count")?;
    let faces = r.u64("triangle count")?;
    let double = flags & DOUBLE_PRECISION != 0;
    let size: u64 = if double { 8 } else { 4 };
    let per_vertex = 3
        + 3 * u64::from(flags & HAS_NORMALS != 0)
        + 2 * u64::from(flags & HAS_UVS != 0)
        + 3 * u64::from(flags & HAS_COLORS != 0);
    let need = vertices
        .checked_mul(per_vertex * size)
        .and_then(|v| faces.checked_mul(12).and_then(|f| v.checked_add(f)));
    let left = (data.len() - r.pos) as u64;
    if need.is_none_or(|n| n > left) || vertices > u64::from(u32::MAX) {
        return Err(format!(
            "{vertices} vertices and {faces} triangles do not fit in the {left} bytes of data"
        ));
    }
    let (nv, nf) = (vertices as usize, faces as usize);
    let positions = r.floats::<3>(nv, double, "positions")?;
    let normals = if flags & HAS_NORMALS != 0 {
        r.floats::<3>(nv, double, "normals")?
    } else {
        Vec::new()
    };
    let uvs = if flags & HAS_UVS != 0 {
        r.floats::<2>(nv, double, "texture coordinates")?
    } else {
        Vec::new()
    };
    if flags & HAS_COLORS != 0 {
        r.floats::<3>(nv, double, "vertex colours")?;
    }
    let indices = r
        .take(nf * 12, "triangles")?
        .chunks_exact(12)
        .map(|t| {
            std::array::from_fn(|k| {
                u32::from_le_bytes([t[4 * k], t[4 * k + 1], t[4 * k + 2], t[4 * k + 3]])
            })
        })
        .collect();
    Ok(MeshData {
        positions,
        normals,
        uvs,
        indices,
        attributes: Vec::new(),
    })
}

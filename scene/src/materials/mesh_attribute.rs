//! The `mesh_attribute` texture plugin: a mesh's per-vertex or per-face values (a PLY file's
//! extra properties, named as `ply_attributes.rs` says) read where the surface is hit, as
//! Mitsuba 3.9.1 reads them (`tessera_core::texture::MeshAttributeTexture`).
//!
//! The values are not known until the texture meets a mesh, so they are not range-checked
//! here: a reflectance above 1 from a file's attribute is the file's. A shape whose BSDF reads
//! an attribute its mesh lacks is refused where the shape is built.
use super::texture_plugin::TexturePlugin;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use tessera_core::texture::{MeshAttributeTexture, Texture};

const NAME: Param = Param::new(
    "name",
    ParamType::String,
    Default::Required,
    Range::Note("starts with \"vertex_\" or \"face_\""),
    "the attribute: `vertex_*` values are blended by the hit's barycentric coordinates, \
     `face_*` values are constant over each face",
);
const SCALE: Param = Param::float("scale", 1.0, Range::Any, "factor on the value");

/// `mesh_attribute`.
pub(crate) const MESH_ATTRIBUTE: TexturePlugin = Plugin {
    name: "mesh_attribute",
    aliases: &[],
    doc: "A mesh attribute (per-vertex or per-face values of a PLY file) as a texture. A \
          one-component attribute is grey as a colour; a three-component one is an RGB colour \
          and reads as 0 where a scalar is wanted, as in Mitsuba 3.",
    params: &[NAME, SCALE],
    nested: "",
    build: |obj, _unit| {
        let name = NAME.read_string(obj)?;
        if !(name.starts_with("vertex_") || name.starts_with("face_")) {
            return Err(super::super::util::at_prop(
                obj,
                NAME.name,
                format!("mesh attribute name \"{name}\" must start with \"vertex_\" or \"face_\""),
            ));
        }
        let scale = SCALE.read_f32(obj)?;
        Ok(Texture::MeshAttribute(MeshAttributeTexture { name, scale }))
    },
};

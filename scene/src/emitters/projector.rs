//! `projector`: a point light projecting a texture through a pinhole frustum, Mitsuba 3's
//! reciprocal of its `perspective` sensor (the same field-of-view parameters). The frustum's
//! aspect ratio is the texture's resolution (1:1 for a constant or a checkerboard); the
//! conventions are in `tessera_core::emitter::Projector`.
use super::delta::TO_WORLD;
use super::EmitterPlugin;
use crate::materials::texture::read_texture;
use crate::plugin::{Param, Plugin, Range};
use crate::sensor::{read_fov, FOCAL_LENGTH, FOV, FOV_AXIS};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::camera::Perspective;
use tessera_core::emitter::{Emitter, Projector};

const IRRADIANCE: Param = Param::texture(
    "irradiance",
    [1.0; 3],
    Range::NonNegative,
    "the projected image: a white surface facing the projector at depth 1 receives pi scale \
     times this irradiance (W/m^2), and so looks this bright",
);
const SCALE: Param = Param::float("scale", 1.0, Range::NonNegative, "factor on the irradiance");

/// `projector`.
pub const PROJECTOR: EmitterPlugin = Plugin {
    name: "projector",
    aliases: &[],
    doc: "A point light projecting an image through a pinhole frustum that looks down its local \
          +z axis (the perspective sensor's, the image's first column toward local +x and first \
          row toward +y); the frustum's aspect ratio is the texture's resolution.",
    params: &[IRRADIANCE, SCALE, FOV, FOV_AXIS, FOCAL_LENGTH, TO_WORLD],
    nested: "the irradiance texture, nested with that name",
    build: build_projector,
};

fn build_projector(obj: &Object, _: Option<u32>) -> Result<Emitter> {
    let irradiance = read_texture(obj, &IRRADIANCE)?;
    let scale = SCALE.read_f32(obj)?;
    let (fov, axis) = read_fov(obj)?;
    let to_world = TO_WORLD.read_transform(obj)?;
    let (w, h) = irradiance.bitmap().map_or((1, 1), |b| b.size());
    let frustum = Perspective::new(w as u32, h as u32, fov, axis, 1e-4, 1e4);
    Ok(Emitter::Projector(Projector::new(
        irradiance,
        scale,
        frustum.half_extent(),
        &to_world,
    )))
}

//! The delta lights: `point`, `spot` and `directional` (a point or a direction, no area). The
//! `projector`, also a point light, has its own file.
use super::EmitterPlugin;
use crate::materials::texture::texture;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::{at_prop, vec3, Result};
use crate::xml::Object;
use glam::DVec3;
use tessera_core::emitter::{DirectionalLight, Emitter, PointLight, SpotLight};
use tessera_core::math::Norm;
use tessera_core::texture::Texture;

const INTENSITY: Param = Param::rgb(
    "intensity",
    Default::Rgb([1.0; 3]),
    Range::NonNegative,
    "radiant intensity (W/sr)",
);
const POWER: Param = Param::rgb(
    "power",
    Default::Absent,
    Range::NonNegative,
    "total power (W), the Nori and Wakame way to give a point light's strength: the \
     intensity is power / (4 pi); not together with intensity",
);
const POSITION: Param = Param::new(
    "position",
    ParamType::Point,
    Default::Note("to_world's translation"),
    Range::Any,
    "where the light is",
);
/// Where the light is and which way it looks (shared with `projector`).
pub(super) const TO_WORLD: Param = Param::transform("to_world", "placement of the light");

/// `point`.
pub const POINT: EmitterPlugin = Plugin {
    name: "point",
    aliases: &[],
    doc: "An isotropic point light.",
    params: &[INTENSITY, POWER, POSITION, TO_WORLD],
    nested: "",
    build: |obj, _| {
        let intensity = match obj.has(POWER.name) {
            true if obj.has(INTENSITY.name) => {
                return Err(obj.error("a point light takes \"intensity\" or \"power\", not both"))
            }
            true => POWER.read_color_opt(obj)?.unwrap_or_default() / (4.0 * std::f32::consts::PI),
            false => INTENSITY.read_color(obj)?,
        };
        let position = match obj.point_opt(POSITION.name)? {
            Some(p) => vec3(p),
            None => TO_WORLD.read_transform(obj)?.point(glam::Vec3::ZERO),
        };
        Ok(Emitter::Point(PointLight {
            position,
            intensity,
        }))
    },
};

const CUTOFF_ANGLE: Param = Param::float(
    "cutoff_angle",
    20.0,
    Range::open_closed(0.0, 180.0),
    "angle from the axis where the light ends",
)
.with_unit("degrees");
const BEAM_WIDTH: Param = Param::new(
    "beam_width",
    ParamType::Float,
    Default::Note("3/4 of cutoff_angle"),
    Range::Note("in [0, cutoff_angle]"),
    "angle from the axis where the falloff starts",
)
.with_unit("degrees");

const TEXTURE: Param = Param::new(
    "texture",
    ParamType::Texture,
    Default::Absent,
    Range::Note("a bitmap or checkerboard (not a constant); finite and non-negative"),
    "image projected into the cone, multiplying the intensity: the cone is inscribed in its \
     unit square, local +x toward u = 1 and +y toward v = 1",
);

/// `spot`.
pub(crate) const SPOT: EmitterPlugin = Plugin {
    name: "spot",
    aliases: &[],
    doc: "A point light shining down its local +z axis, with a smooth falloff between beam_width \
          and cutoff_angle.",
    params: &[INTENSITY, CUTOFF_ANGLE, BEAM_WIDTH, TEXTURE, TO_WORLD],
    nested: "",
    build: build_spot,
};

fn build_spot(obj: &Object, _: Option<u32>) -> Result<Emitter> {
    let intensity = INTENSITY.read_color(obj)?;
    let cutoff = CUTOFF_ANGLE.read_f32(obj)?;
    let beam = BEAM_WIDTH.read_f32_where(obj, f64::from(cutoff) * 0.75, |v| {
        (0.0..=f64::from(cutoff)).contains(&v)
    })?;
    let to_world = TO_WORLD.read_transform(obj)?;
    let spot = SpotLight::new(intensity, cutoff, beam, &to_world);
    if !obj.has(TEXTURE.name) {
        return Ok(Emitter::Spot(spot));
    }
    let t = texture(obj, TEXTURE.name, [1.0; 3], false)?;
    if let Texture::Constant(_) = t {
        return Err(at_prop(
            obj,
            TEXTURE.name,
            format!(
                "\"texture\" of {} must vary over the cone (a bitmap or checkerboard texture); \
                 a constant belongs in \"intensity\"",
                obj.describe()
            ),
        ));
    }
    Ok(Emitter::Spot(spot.with_texture(t)))
}

const IRRADIANCE: Param = Param::rgb(
    "irradiance",
    Default::Rgb([1.0; 3]),
    Range::NonNegative,
    "irradiance on a surface facing the light (W/m^2)",
);
const DIRECTION: Param = Param::new(
    "direction",
    ParamType::Vector,
    Default::Note("to_world applied to +z"),
    Range::Note("non-zero; not with to_world"),
    "the direction the light travels",
);

/// `directional`.
pub(crate) const DIRECTIONAL: EmitterPlugin = Plugin {
    name: "directional",
    aliases: &[],
    doc: "Parallel light from one direction at infinity.",
    params: &[IRRADIANCE, DIRECTION, TO_WORLD],
    nested: "",
    build: build_directional,
};

fn build_directional(obj: &Object, _: Option<u32>) -> Result<Emitter> {
    let irradiance = IRRADIANCE.read_color(obj)?;
    if obj.has(DIRECTION.name) && obj.has(TO_WORLD.name) {
        return Err(at_prop(
            obj,
            DIRECTION.name,
            format!(
                "{} takes \"direction\" or \"to_world\", not both",
                obj.describe()
            ),
        ));
    }
    let (d, name) = match obj.vector_opt(DIRECTION.name)? {
        Some(v) => (DVec3::from(v), DIRECTION.name),
        None => {
            let m = obj.transform(TO_WORLD.name, glam::DMat4::IDENTITY)?;
            (m.transform_vector3(DVec3::Z), TO_WORLD.name)
        }
    };
    let len = d.norm();
    let direction = (d / len).as_vec3();
    if !(len > 0.0) || !len.is_finite() || !direction.is_finite() {
        return Err(at_prop(
            obj,
            name,
            format!(
                "\"{name}\" of {} must give a non-zero finite direction",
                obj.describe()
            ),
        ));
    }
    Ok(Emitter::Directional(DirectionalLight {
        direction,
        irradiance,
    }))
}

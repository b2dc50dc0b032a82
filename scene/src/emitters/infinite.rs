//! The lights at infinity: `constant`, `envmap` and Nori / Wakame's `distantdisk`. Their
//! `to_world` may only rotate (directions have no position).
use super::EmitterPlugin;
use crate::error::InputError;
use crate::image::read_image;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::{at_prop, Result};
use crate::xml::Object;
use glam::{DMat3, Mat3};
use tessera_core::emitter::{ConstantEnv, DistantDisk, Emitter, EnvMap};

const TO_WORLD: Param = Param::transform(
    "to_world",
    "orientation (a rotation; a uniform scale and a translation are ignored)",
);
const CONSTANT_RADIANCE: Param = Param::rgb(
    "radiance",
    Default::Rgb([1.0; 3]),
    Range::NonNegative,
    "radiance from every direction",
);

/// `constant`.
pub(crate) const CONSTANT: EmitterPlugin = Plugin {
    name: "constant",
    aliases: &[],
    doc: "Uniform radiance from every direction at infinity.",
    params: &[CONSTANT_RADIANCE],
    nested: "",
    build: |obj, _| {
        Ok(Emitter::Constant(ConstantEnv {
            radiance: CONSTANT_RADIANCE.read_color(obj)?,
        }))
    },
};

const DISK_RADIANCE: Param = Param::rgb(
    "radiance",
    Default::Required,
    Range::NonNegative,
    "radiance inside the disk",
);
const THETA_A: Param = Param::new(
    "theta_a",
    ParamType::Float,
    Default::Required,
    Range::open_closed(0.0, 180.0),
    "half angle of the disk (Nori's thetaA)",
)
.with_unit("degrees");

/// `distantdisk`.
pub(crate) const DISTANTDISK: EmitterPlugin = Plugin {
    name: "distantdisk",
    aliases: &[],
    doc: "The Wakame assignment's disk of uniform radiance at infinity (a sun), centred on the \
          local +z axis.",
    params: &[DISK_RADIANCE, THETA_A, TO_WORLD],
    nested: "",
    build: build_distant_disk,
};

fn build_distant_disk(obj: &Object, _: Option<u32>) -> Result<Emitter> {
    let radiance = DISK_RADIANCE.read_color(obj)?;
    // Nori's `thetaA` reaches here as `theta_a` (the dialect layer's camelCase to snake_case).
    if !obj.has(THETA_A.name) {
        return Err(obj.error(format!(
            "{} needs the parameter \"thetaA\" (half angle in degrees)",
            obj.describe()
        )));
    }
    let theta = THETA_A.read_f32(obj)?;
    let to_world = rotation(obj, TO_WORLD.name)?;
    Ok(Emitter::DistantDisk(DistantDisk::new(
        radiance, theta, to_world,
    )))
}

const FILENAME: Param = Param::file(
    "an EXR, PFM or RGBE .hdr image, relative to the scene file, at least 2x3 pixels",
    "the latitude-longitude image of linear radiance",
);
const SCALE: Param = Param::float("scale", 1.0, Range::NonNegative, "factor on the radiance");
const MIS_COMPENSATION: Param = Param::boolean(
    "mis_compensation",
    true,
    "sample by the luminance less the map's mean (MIS compensation) where the integrator \
     weighs every emitter sample by MIS (path, with or without reuse; volpath without media; \
     direct with both strategies); false keeps the plain tables. Other integrators always \
     sample by the plain tables (Mitsuba 3's default: false)",
);

/// `envmap`.
pub(crate) const ENVMAP: EmitterPlugin = Plugin {
    name: "envmap",
    aliases: &[],
    doc: "Radiance at infinity from a latitude-longitude image, sampled by its luminance.",
    params: &[FILENAME, SCALE, TO_WORLD, MIS_COMPENSATION],
    nested: "",
    build: build_envmap,
};

fn build_envmap(obj: &Object, _: Option<u32>) -> Result<Emitter> {
    let name = obj.string_opt(FILENAME.name)?.ok_or_else(|| {
        obj.error(format!(
            "{} needs the parameter \"filename\"",
            obj.describe()
        ))
    })?;
    let path = obj.resolve_file(&name);
    let file_error = |msg: String| -> InputError { at_prop(obj, "filename", msg) };
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    if !matches!(ext.as_str(), "exr" | "pfm" | "hdr") {
        return Err(file_error(format!(
            "\"{name}\": an environment map must be an EXR, PFM or RGBE .hdr image (linear \
             radiance)"
        )));
    }
    let img = read_image(&path).map_err(file_error)?;
    if img.width < 2 || img.height < 3 {
        return Err(file_error(format!(
            "\"{name}\": an environment map must be at least 2x3 pixels, found {}x{}",
            img.width, img.height
        )));
    }
    if let Some(i) = img
        .data
        .iter()
        .position(|p| p.iter().any(|c| !c.is_finite() || *c < 0.0))
    {
        let (x, y) = (i % img.width as usize, i / img.width as usize);
        return Err(file_error(format!(
            "\"{name}\": pixel ({x}, {y}) is {:?}; radiance must be finite and non-negative",
            img.data[i]
        )));
    }
    let scale = SCALE.read_f32(obj)?;
    let to_world = rotation(obj, TO_WORLD.name)?;
    let compensation = MIS_COMPENSATION.read_bool(obj)?;
    let (w, h) = (img.width as usize, img.height as usize);
    let mut env = EnvMap::new(img.data, w, h, scale, to_world)
        .ok_or_else(|| file_error(format!("\"{name}\": unusable image size {w}x{h}")))?;
    env.allow_compensation(compensation);
    Ok(Emitter::EnvMap(env))
}

/// A transform parameter's rotation (identity when absent) for lights at infinity: the linear
/// part divided by its scale, which must be uniform; translation is ignored (directions only).
fn rotation(obj: &Object, name: &str) -> Result<Mat3> {
    let Some(m) = obj.transform_opt(name)? else {
        return Ok(Mat3::IDENTITY);
    };
    let l = DMat3::from_mat4(m);
    let scale = (l.determinant().abs()).cbrt();
    let r = l * (1.0 / scale);
    let err = (r.transpose() * r - DMat3::IDENTITY)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |a, v| a.max(v.abs()));
    if !(scale > 0.0) || !scale.is_finite() || !(err < 1e-4) {
        return Err(at_prop(
            obj,
            name,
            format!(
                "\"{name}\" of {} must be a rotation (with at most a uniform scale and a \
                 translation, which are ignored)",
                obj.describe()
            ),
        ));
    }
    Ok(r.as_mat3())
}

//! `<emitter>` objects: `area` (nested in a shape); `constant`, `envmap`, `distantdisk` (at
//! infinity), `point`, `spot`, `directional` (delta lights) in the scene.
//!
//! `area`: `radiance` (rgb, required). `constant`: `radiance` (rgb, default 1). `point`:
//! `intensity` (rgb, default 1), `position` (point) or `to_world` (its translation). `spot`:
//! `intensity` (rgb, default 1), `cutoff_angle` (float degrees in (0, 180], default 20),
//! `beam_width` (float degrees in [0, cutoff_angle], default cutoff_angle * 3/4), `to_world`.
//! `directional`: `irradiance` (rgb, default 1), `direction` (vector) or `to_world` (+z), not
//! both. `distantdisk` (Nori / Wakame): `radiance` (rgb, required), `thetaA` = `theta_a` (float
//! degrees in (0, 180], required), `toWorld` = `to_world` (a rotation). `envmap`: `filename`
//! (string, required: EXR, PFM or RGBE `.hdr`, relative to the scene file, at least 2x3 pixels),
//! `scale` (float >= 0, default 1), `to_world` (a rotation), `mis_compensation` (boolean,
//! ignored). The plugin files in `tessera_core::emitter` give each light's conventions.
use super::util::{at_prop, color, color_required, float_checked, transform, vec3, Result};
use crate::error::InputError;
use crate::image::read_image;
use crate::xml::Object;
use glam::{DMat3, DVec3, Mat3};
use tessera_core::emitter::{
    AreaLight, ConstantEnv, DirectionalLight, DistantDisk, Emitter, EnvMap, PointLight, SpotLight,
};
use tessera_core::math::Norm;

/// An area light on shape `shape`.
pub fn build_area(obj: &Object, shape: u32) -> Result<Emitter> {
    if obj.plugin != "area" {
        return Err(obj.error(format!(
            "a shape can only carry an \"area\" emitter, found \"{}\"",
            obj.plugin
        )));
    }
    let radiance = color_required(obj, "radiance")?;
    obj.check_unused()?;
    Ok(Emitter::Area(AreaLight::new(shape, radiance)))
}

/// An emitter declared at scene level.
pub fn build_scene_emitter(obj: &Object) -> Result<Emitter> {
    let e = match obj.plugin.as_str() {
        "constant" => Emitter::Constant(ConstantEnv {
            radiance: color(obj, "radiance", [1.0; 3])?,
        }),
        "point" => {
            let intensity = color(obj, "intensity", [1.0; 3])?;
            let position = match obj.point_opt("position")? {
                Some(p) => vec3(p),
                None => transform(obj, "to_world")?.point(glam::Vec3::ZERO),
            };
            Emitter::Point(PointLight {
                position,
                intensity,
            })
        }
        "spot" => build_spot(obj)?,
        "directional" => build_directional(obj)?,
        "distantdisk" => build_distant_disk(obj)?,
        "envmap" => build_envmap(obj)?,
        "area" => return Err(obj.error("an area emitter must be nested in a shape")),
        other => {
            return Err(obj.error(format!(
                "unknown emitter \"{other}\" (known: area, constant, directional, distantdisk, \
                 envmap, point, spot)"
            )))
        }
    };
    obj.check_unused()?;
    Ok(e)
}

fn build_spot(obj: &Object) -> Result<Emitter> {
    let intensity = color(obj, "intensity", [1.0; 3])?;
    let cutoff = float_checked(
        obj,
        "cutoff_angle",
        20.0,
        |v| v > 0.0 && v <= 180.0,
        "in (0, 180] degrees",
    )?;
    let beam = float_checked(
        obj,
        "beam_width",
        f64::from(cutoff) * 0.75,
        |v| (0.0..=f64::from(cutoff)).contains(&v),
        &format!("in [0, cutoff_angle = {cutoff}] degrees"),
    )?;
    let to_world = transform(obj, "to_world")?;
    Ok(Emitter::Spot(SpotLight::new(
        intensity, cutoff, beam, &to_world,
    )))
}

fn build_directional(obj: &Object) -> Result<Emitter> {
    let irradiance = color(obj, "irradiance", [1.0; 3])?;
    if obj.has("direction") && obj.has("to_world") {
        return Err(at_prop(
            obj,
            "direction",
            format!(
                "{} takes \"direction\" or \"to_world\", not both",
                obj.describe()
            ),
        ));
    }
    let (d, name) = match obj.vector_opt("direction")? {
        Some(v) => (DVec3::from(v), "direction"),
        None => {
            let m = obj.transform("to_world", glam::DMat4::IDENTITY)?;
            (m.transform_vector3(DVec3::Z), "to_world")
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

fn build_distant_disk(obj: &Object) -> Result<Emitter> {
    let radiance = color_required(obj, "radiance")?;
    // Nori's `thetaA` reaches here as `theta_a` (the dialect layer's camelCase to snake_case).
    if !obj.has("theta_a") {
        return Err(obj.error(format!(
            "{} needs the parameter \"thetaA\" (half angle in degrees)",
            obj.describe()
        )));
    }
    let theta = float_checked(
        obj,
        "theta_a",
        0.0,
        |v| v > 0.0 && v <= 180.0,
        "in (0, 180] degrees",
    )?;
    let to_world = rotation(obj, "to_world")?;
    Ok(Emitter::DistantDisk(DistantDisk::new(
        radiance, theta, to_world,
    )))
}

fn build_envmap(obj: &Object) -> Result<Emitter> {
    let name = obj.string_opt("filename")?.ok_or_else(|| {
        obj.error(format!(
            "{} needs the parameter \"filename\"",
            obj.describe()
        ))
    })?;
    let base = obj
        .loc
        .file
        .parent()
        .map(|p| p.to_path_buf())
        .unwrap_or_default();
    let path = base.join(&name);
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
    let scale = float_checked(obj, "scale", 1.0, |v| v >= 0.0, "finite and non-negative")?;
    let to_world = rotation(obj, "to_world")?;
    // Mitsuba 3's sampling option: Tessera samples its own way, so it has no effect here.
    obj.boolean("mis_compensation", false)?;
    let (w, h) = (img.width as usize, img.height as usize);
    let env = EnvMap::new(img.data, w, h, scale, to_world)
        .ok_or_else(|| file_error(format!("\"{name}\": unusable image size {w}x{h}")))?;
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// A scene with one camera and `emitter` (the emitter's first line is line 3).
    fn scene(emitter: &str) -> String {
        format!("<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n{emitter}\n</scene>\n")
    }

    /// Loads `emitter` and returns the error line (panics if it loads).
    fn error_of(emitter: &str) -> String {
        let text = scene(emitter);
        match crate::load_scene_str(&text, Path::new("/nowhere/test.xml"), &[]) {
            Ok(_) => panic!("loaded: {emitter}"),
            Err(e) => e.to_string(),
        }
    }

    /// The error is located at `file:line:col` of the first occurrence of `needle` and says
    /// `what`.
    fn check(emitter: &str, needle: &str, what: &str) {
        let text = scene(emitter);
        let at = text.find(needle).expect("needle in the scene");
        let line = text[..at].matches('\n').count() + 1;
        let col = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
        let e = error_of(emitter);
        assert!(
            e.starts_with(&format!("/nowhere/test.xml:{line}:{col}: ")),
            "{emitter}: expected an error at {line}:{col}, got: {e}"
        );
        assert!(e.contains(what), "{emitter}: expected \"{what}\" in: {e}");
    }

    #[test]
    fn spot_values_are_checked() {
        check(
            "<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"0\"/></emitter>",
            "<float",
            "in (0, 180] degrees",
        );
        check(
            "<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"181\"/></emitter>",
            "<float",
            "in (0, 180] degrees",
        );
        check(
            "<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"20\"/>\n\
             <float name=\"beam_width\" value=\"25\"/></emitter>",
            "<float name=\"beam",
            "beam_width",
        );
        check(
            "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"1, -1, 1\"/></emitter>",
            "<rgb",
            "non-negative",
        );
    }

    #[test]
    fn directional_values_are_checked() {
        check(
            "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, 0\"/>\
             </emitter>",
            "<vector",
            "non-zero",
        );
        check(
            "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, 1\"/>\
             <transform name=\"to_world\"><rotate x=\"1\" angle=\"5\"/></transform></emitter>",
            "<vector",
            "not both",
        );
    }

    #[test]
    fn distant_disk_values_are_checked() {
        check(
            "<emitter type=\"distantdisk\"><rgb name=\"radiance\" value=\"1\"/>\
             <float name=\"thetaA\" value=\"0\"/></emitter>",
            "<float",
            "in (0, 180] degrees",
        );
        check(
            "<emitter type=\"distantdisk\"><rgb name=\"radiance\" value=\"1\"/>\
             <float name=\"theta_a\" value=\"180.5\"/></emitter>",
            "<float",
            "in (0, 180] degrees",
        );
        check(
            "<emitter type=\"distantdisk\"><rgb name=\"radiance\" value=\"1\"/></emitter>",
            "<emitter",
            "thetaA",
        );
        check(
            "<emitter type=\"distantdisk\"><float name=\"thetaA\" value=\"5\"/></emitter>",
            "<emitter",
            "radiance",
        );
        check(
            "<emitter type=\"distantdisk\"><rgb name=\"radiance\" value=\"1\"/>\
             <float name=\"thetaA\" value=\"5\"/>\
             <transform name=\"toWorld\"><scale x=\"1\" y=\"2\" z=\"1\"/></transform></emitter>",
            "<transform",
            "must be a rotation",
        );
    }

    #[test]
    fn envmap_files_are_checked() {
        check("<emitter type=\"envmap\"/>", "<emitter", "filename");
        check(
            "<emitter type=\"envmap\"><string name=\"filename\" value=\"missing.exr\"/></emitter>",
            "<string",
            "cannot read image",
        );
        check(
            "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.png\"/></emitter>",
            "<string",
            "EXR, PFM or RGBE",
        );
    }

    #[test]
    fn envmap_pixels_and_size_are_checked() {
        let dir = std::env::temp_dir().join(format!("tessera-envmap-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let write = |name: &str, w: u32, h: u32, v: f32| {
            let path = dir.join(name);
            let flat: Vec<f32> = (0..w * h).flat_map(|_| [v, 0.5, 0.5]).collect();
            image::Rgb32FImage::from_raw(w, h, flat)
                .expect("size")
                .save(&path)
                .expect("write");
            path.display().to_string()
        };
        let small = write("small.exr", 2, 2, 1.0);
        check(
            &format!(
                "<emitter type=\"envmap\"><string name=\"filename\" value=\"{small}\"/></emitter>"
            ),
            "<string",
            "at least 2x3 pixels",
        );
        let negative = write("negative.exr", 4, 3, -1.0);
        check(
            &format!(
                "<emitter type=\"envmap\"><string name=\"filename\" value=\"{negative}\"/></emitter>"
            ),
            "<string",
            "finite and non-negative",
        );
        let fine = write("fine.exr", 4, 3, 1.0);
        let text = scene(&format!(
            "<emitter type=\"envmap\"><string name=\"filename\" value=\"{fine}\"/>\
             <float name=\"scale\" value=\"2\"/><boolean name=\"mis_compensation\" value=\"true\"/>\
             </emitter>"
        ));
        crate::load_scene_str(&text, Path::new("/nowhere/test.xml"), &[]).expect("loads");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

//! The emitter plugins: one [`Plugin`] per `<emitter type=...>` (`EMITTERS`): `area` (nested
//! in a shape) in `area.rs`; the delta lights `point`, `spot`, `directional` in `delta.rs` and
//! `projector` in `projector.rs`; the lights at infinity `constant`, `envmap`, `distantdisk` in
//! `infinite.rs`. The plugin files in `tessera_core::emitter` give each light's conventions.
pub(crate) mod area;
mod delta;
mod infinite;
mod projector;
mod table;

pub(crate) use area::AREA;
pub(crate) use table::build_emitter;
pub use table::EMITTERS;

use crate::plugin::Plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::emitter::Emitter;

/// An emitter plugin, built with the index of the shape that carries it (area lights only).
pub(crate) type EmitterPlugin = Plugin<fn(&Object, Option<u32>) -> Result<Emitter>>;

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
    fn declarations_match_what_the_builders_read() {
        let sky = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/textures/sky.exr");
        crate::plugin::check::check_family(
            super::EMITTERS,
            crate::xml::Kind::Emitter,
            |obj| super::build_emitter(obj, (obj.plugin == "area").then_some(0)),
            |name| match name {
                "area" => "<rgb name=\"radiance\" value=\"1\"/>".to_string(),
                "distantdisk" => {
                    "<rgb name=\"radiance\" value=\"1\"/><float name=\"theta_a\" value=\"5\"/>"
                        .to_string()
                }
                "envmap" => format!("<string name=\"filename\" value=\"{sky}\"/>"),
                // fov_axis is read with fov, focal_length only without it.
                "projector" => "<float name=\"fov\" value=\"45\"/>".to_string(),
                _ => String::new(),
            },
            &[("projector", "focal_length")],
        );
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
    fn a_spot_texture_must_vary() {
        check(
            "<emitter type=\"spot\"><rgb name=\"texture\" value=\"0.5\"/></emitter>",
            "<rgb",
            "must vary over the cone",
        );
        check(
            "<emitter type=\"spot\"><texture type=\"checkerboard\" name=\"texture\">\
             <rgb name=\"color0\" value=\"-1\"/></texture></emitter>",
            "<rgb",
            "non-negative",
        );
        // Control: a checkerboard loads.
        let text = scene(
            "<emitter type=\"spot\"><texture type=\"checkerboard\" name=\"texture\"/></emitter>",
        );
        crate::load_scene_str(&text, Path::new("/nowhere/test.xml"), &[]).expect("loads");
    }

    #[test]
    fn projector_values_are_checked() {
        check(
            "<emitter type=\"projector\"><float name=\"fov\" value=\"180\"/></emitter>",
            "<float",
            "fov",
        );
        check(
            "<emitter type=\"projector\"><float name=\"scale\" value=\"-2\"/></emitter>",
            "<float",
            "scale",
        );
        check(
            "<emitter type=\"projector\"><string name=\"focal_length\" value=\"wide\"/></emitter>",
            "<string",
            "focal_length",
        );
        check(
            "<emitter type=\"projector\"><texture type=\"bitmap\" name=\"irradiance\">\
             <string name=\"filename\" value=\"missing.png\"/></texture></emitter>",
            "<string",
            "cannot read image",
        );
        check(
            "<emitter type=\"projector\"><float name=\"fov\" value=\"30\"/>\
             <float name=\"near_clip\" value=\"1\"/></emitter>",
            "<float name=\"near",
            "near_clip",
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

    #[test]
    fn an_area_emitter_can_be_declared_apart_and_referenced() {
        // Referenced before its declaration (as Mitsuba's cbox fragments do), by two shapes:
        // each shape emits.
        let text = scene(
            "<shape type=\"sphere\"><ref id=\"light\"/></shape>\n\
             <shape type=\"sphere\"><point name=\"center\" value=\"3 0 0\"/><ref id=\"light\"/></shape>\n\
             <emitter type=\"area\" id=\"light\"><rgb name=\"radiance\" value=\"2\"/></emitter>",
        );
        let l = crate::load_scene_str(&text, Path::new("/nowhere/test.xml"), &[])
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(l.scene.emitters.len(), 2);
        assert!(l.scene.shapes.iter().all(|s| s.emitter.is_some()));
        // Control: declared apart but referenced by no shape, it is refused where it is.
        check(
            "<shape type=\"sphere\"/>\n<emitter type=\"area\" id=\"light\"><rgb name=\"radiance\" value=\"2\"/></emitter>",
            "<emitter",
            "must be nested in a shape or referenced from one",
        );
    }

    /// Nori's and Wakame's point light gives its power; the intensity is power / (4 pi).
    #[test]
    fn a_point_light_power_is_four_pi_times_its_intensity() {
        let emitter = |params: &str| {
            let text = scene(&format!(
                "<emitter type=\"point\"><point name=\"position\" value=\"0, 1, 0\"/>{params}</emitter>"
            ));
            let l = crate::load_scene_str(&text, Path::new("/nowhere/test.xml"), &[]).unwrap();
            format!("{:?}", l.scene.emitters[0])
        };
        let power = 4.0 * std::f64::consts::PI;
        let given = emitter(&format!(
            "<rgb name=\"power\" value=\"{power}, {}, 0\"/>",
            2.0 * power
        ));
        assert_eq!(
            given,
            emitter("<rgb name=\"intensity\" value=\"1, 2, 0\"/>")
        );
        // Control: power read as if it were the intensity.
        assert_ne!(
            given,
            emitter(&format!(
                "<rgb name=\"intensity\" value=\"{power}, {}, 0\"/>",
                2.0 * power
            ))
        );
        check(
            "<emitter type=\"point\"><rgb name=\"power\" value=\"1\"/><rgb name=\"intensity\" value=\"1\"/></emitter>",
            "<emitter",
            "not both",
        );
    }
}

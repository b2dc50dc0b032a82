//! The `<sensor>` plugins (`SENSORS`, in `table.rs`; Nori's `<camera>`): Mitsuba 3's `perspective`,
//! `thinlens` and `orthographic`, with the `<film>` ([`FILMS`]), `<rfilter>` and `<sampler>`
//! that may hang off them. The parameters every sensor shares are declared here.
mod film;
mod fov;
mod orthographic;
mod perspective;
mod table;

use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::camera::{Camera, Crop, Filter};
use tessera_core::sampling::SamplerKind;

pub use film::{FILMS, MAX_EDGE, MAX_PIXELS};
pub(crate) use fov::{read_fov, FOCAL_LENGTH, FOV, FOV_AXIS};
pub use orthographic::ORTHOGRAPHIC;
pub use perspective::{PERSPECTIVE, THINLENS};
pub(crate) use table::build_sensor;
pub use table::SENSORS;

/// The sensor and what hangs off it.
#[derive(Debug)]
pub(crate) struct SensorParts {
    pub camera: Camera,
    pub filter: Filter,
    pub spp: Option<u64>,
    pub seed: Option<u64>,
    pub sampler: Option<SamplerKind>,
}

/// A sensor plugin; the builder may add warnings (from its sampler).
pub(crate) type SensorPlugin = Plugin<fn(&Object, &mut Vec<String>) -> Result<SensorParts>>;

const TO_WORLD: Param = Param::transform(
    "to_world",
    "camera to world; the camera looks down its local +z, with +y up",
);
const NEAR_CLIP: Param = Param::new(
    "near_clip",
    ParamType::Float,
    Default::Note("0.01; 1e-4 on a Nori camera (one that carries width/height)"),
    Range::NonNegative,
    "distance before which nothing is seen",
);
const FAR_CLIP: Param = Param::new(
    "far_clip",
    ParamType::Float,
    Default::Float(10000.0),
    Range::Note("greater than near_clip"),
    "distance beyond which nothing is seen",
);
const SHUTTER_OPEN: Param = Param::float(
    "shutter_open",
    0.0,
    Range::Any,
    "has no effect: nothing moves, so there is no motion blur",
)
.ignored();
const SHUTTER_CLOSE: Param = Param::float(
    "shutter_close",
    0.0,
    Range::Any,
    "has no effect: nothing moves, so there is no motion blur",
)
.ignored();

/// The near and far clip distances (`near_default` when `near_clip` is absent).
fn read_clips(obj: &Object, near_default: f64) -> Result<(f32, f32)> {
    let near = NEAR_CLIP.read_f32_or(obj, near_default)?;
    let far = FAR_CLIP.read_f32_where(obj, 10000.0, |v| v > near as f64)?;
    Ok((near, far))
}

/// Reads the shutter times, which have no effect.
fn read_shutter(obj: &Object) -> Result<()> {
    SHUTTER_OPEN.read_f32(obj)?;
    SHUTTER_CLOSE.read_f32(obj)?;
    Ok(())
}

/// The parts of a sensor whose camera `camera` makes from the film's size.
fn parts(film: film::Film, camera: impl FnOnce(u32, u32) -> Camera) -> SensorParts {
    let mut camera = camera(film.width, film.height);
    if let Some([x, y, width, height]) = film.crop {
        camera.crop = Some(Crop {
            x,
            y,
            film_width: film.width,
            film_height: film.height,
        });
        (camera.width, camera.height) = (width, height);
    }
    SensorParts {
        camera,
        filter: film.filter,
        spp: film.spp,
        seed: film.seed,
        sampler: film.sampler,
    }
}

#[cfg(test)]
mod tests {
    use crate::plugin::check::check_family;
    use crate::xml::Kind;

    #[test]
    fn declarations_match_what_the_builders_read() {
        check_family(
            super::SENSORS,
            Kind::Sensor,
            |obj| super::build_sensor(obj, &mut Vec::new()),
            // fov_axis is read with fov; focal_length only without it. A thin lens needs its
            // aperture.
            |name| match name {
                "perspective" => "<float name=\"fov\" value=\"45\"/>".to_string(),
                "thinlens" => "<float name=\"fov\" value=\"45\"/>\
                               <float name=\"aperture_radius\" value=\"0.1\"/>"
                    .to_string(),
                _ => String::new(),
            },
            // A camera that carries width/height is Nori's: its near_clip default differs.
            &[
                ("perspective", "width"),
                ("perspective", "height"),
                ("perspective", "focal_length"),
                ("thinlens", "focal_length"),
            ],
        );
        check_family(
            super::FILMS,
            Kind::Film,
            |obj| (super::FILMS[0].build)(obj),
            |_| String::new(),
            &[],
        );
    }
}

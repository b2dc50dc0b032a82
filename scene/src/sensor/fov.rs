//! The field of view of a pinhole frustum as Mitsuba 3 gives it: `fov` along `fov_axis`, or
//! else `focal_length` on a 36x24 mm frame's diagonal. Shared by the `perspective` and
//! `thinlens` sensors and the `projector` emitter, which take the same three parameters.
use crate::plugin::{Default, Param, ParamType, Range};
use crate::util::{at_prop, Result};
use crate::xml::Object;
use tessera_core::camera::FovAxis;

/// `fov`: the field of view in degrees.
pub(crate) const FOV: Param = Param::new(
    "fov",
    ParamType::Float,
    Default::Absent,
    Range::open(0.0, 180.0),
    "field of view along fov_axis (else focal_length sets it)",
)
.with_unit("degrees");
/// `fov_axis`: the image extent `fov` spans.
pub(crate) const FOV_AXIS: Param = Param::choice(
    "fov_axis",
    "x",
    &["x", "y", "diagonal", "smaller", "larger"],
    "the image axis fov spans",
);
/// `focal_length`: the field of view as a 35 mm lens's focal length, without `fov`.
pub(crate) const FOCAL_LENGTH: Param = Param::new(
    "focal_length",
    ParamType::String,
    Default::Str("50mm"),
    Range::Note("a positive length like \"50mm\""),
    "focal length on a 36x24 mm frame (a diagonal field of view), when fov is absent",
);
/// The field of view in degrees and the axis it spans: `fov` and `fov_axis`, else
/// `focal_length` on a 36x24 mm frame's diagonal.
pub(crate) fn read_fov(obj: &Object) -> Result<(f32, FovAxis)> {
    if let Some(fov) = FOV.read_f32_opt(obj)? {
        let axis = match FOV_AXIS.read_choice(obj)? {
            "y" => FovAxis::Y,
            "diagonal" => FovAxis::Diagonal,
            "smaller" => FovAxis::Smaller,
            "larger" => FovAxis::Larger,
            _ => FovAxis::X,
        };
        return Ok((fov, axis));
    }
    let s = FOCAL_LENGTH.read_string(obj)?;
    let f: f64 = s
        .trim_end_matches("mm")
        .trim()
        .parse()
        .ok()
        .filter(|f: &f64| *f > 0.0 && f.is_finite())
        .ok_or_else(|| {
            at_prop(
                obj,
                "focal_length",
                format!("\"focal_length\" must be a positive length like \"50mm\", found \"{s}\""),
            )
        })?;
    let diag = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
    Ok((
        (2.0 * (diag / (2.0 * f)).atan()).to_degrees() as f32,
        FovAxis::Diagonal,
    ))
}

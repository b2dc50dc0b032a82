//! The `<volume>` plugins ([`VOLUMES`]): `gridvolume` (a voxel grid from a `.vol` file) and
//! `constvolume`, and reading a volume-valued parameter of a medium: a `<float>` or `<rgb>`
//! (a constant, as Mitsuba 3 makes it a `constvolume`) or a nested or referenced `<volume>`.
//! The lookup's conventions are in `tessera_core::medium::voxel_grid`.
use super::vol_file::read_vol;
use crate::error::InputError;
use crate::plugin::{self, Default, Param, ParamType, Plugin, Range};
use crate::util::{at_prop, check_color, Result};
use crate::xml::{Kind, Object};
use glam::{Mat4, Vec3};
use tessera_core::math::Transform;
use tessera_core::medium::{GridFilter, GridVolume, GridWrap, Volume, VolumeData};

/// A volume plugin.
pub(crate) type VolumePlugin = Plugin<fn(&Object) -> Result<Volume>>;

/// Every `<volume type=...>` Tessera knows.
pub static VOLUMES: &[VolumePlugin] = &[GRIDVOLUME, CONSTVOLUME];

/// Builds a `<volume>` and reports its unused parameters.
pub(crate) fn build_volume(obj: &Object) -> Result<Volume> {
    let plugin = plugin::find(VOLUMES, "volume", obj)?;
    let v = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
    Ok(v)
}

/// A volume-valued parameter with a constant default.
pub(crate) const fn volume_param(name: &'static str, default: f64, doc: &'static str) -> Param {
    Param::new(
        name,
        ParamType::Volume,
        Default::Rgb([default; 3]),
        Range::NonNegative,
        doc,
    )
}

/// The volume parameter `p` of `obj`: a nested or referenced `<volume>`, or a constant (the
/// declared default when absent), every value finite and non-negative.
pub(crate) fn read_volume(obj: &Object, p: &Param) -> Result<Volume> {
    let name = p.name;
    if obj.has(name) && obj.prop(name).is_none() {
        let child = obj.child(name).expect("a named child exists");
        if child.obj.kind != Kind::Volume {
            return Err(InputError::at(
                &child.loc,
                format!(
                    "parameter \"{name}\" of {} must be a volume or a value, found {}",
                    obj.describe(),
                    child.obj.describe()
                ),
            ));
        }
        let v = build_volume(&child.obj)?;
        if let VolumeData::Grid(g) = &v.data {
            if g.grid.channels() == 6 {
                return Err(InputError::at(
                    &child.loc,
                    format!(
                        "parameter \"{name}\" of {} takes a volume of 1 or 3 channels, found 6 \
                         (a grid of SGGX matrices, for an sggx phase function's S)",
                        obj.describe()
                    ),
                ));
            }
        }
        return Ok(v);
    }
    let Default::Rgb(d) = p.default else {
        unreachable!("\"{name}\" has a colour default")
    };
    Ok(Volume::constant(check_color(obj, name, obj.rgb(name, d)?)?))
}

const FILENAME: Param = Param::file(
    ".vol (Mitsuba's binary grid, version 3, float32, 1, 3 or 6 channels)",
    "the grid's file",
);
const TO_WORLD: Param = Param::transform(
    "to_world",
    "places the volume: its local unit cube [0, 1]^3 (or the file's box with use_grid_bbox) in \
     the world",
);
const USE_GRID_BBOX: Param = Param::boolean(
    "use_grid_bbox",
    false,
    "the grid spans the bounding box its file states (then to_world) instead of the unit cube",
);
const FILTER_TYPE: Param = Param::choice(
    "filter_type",
    "trilinear",
    &["trilinear", "nearest"],
    "trilinear: blend of the 8 voxel centres around the point; nearest: the voxel it is in",
);
const WRAP_MODE: Param = Param::choice(
    "wrap_mode",
    "clamp",
    &["clamp", "repeat", "mirror"],
    "lookups beyond the grid: the edge voxel, the grid tiled, or the grid mirrored",
);
const RAW: Param = Param::boolean(
    "raw",
    false,
    "has no effect: Mitsuba 3 skips spectral upsampling of 3-channel data with it, and RGB \
     rendering has none to skip",
)
.ignored();
const MAX_VALUE: Param = Param::new(
    "max_value",
    ParamType::Float,
    Default::Note("the grid's maximum"),
    Range::NonNegative,
    "has no effect: Mitsuba 3's override of the grid's maximum (its majorant); Tessera bounds \
     the extinction from the voxels themselves",
)
.ignored();
const ACCEL: Param = Param::boolean(
    "accel",
    true,
    "has no effect: Mitsuba 3's hardware texture lookups on the GPU",
)
.ignored();

/// The map from the unit cube to the box `[lo, hi]`; `None` when the box is empty or not
/// finite.
fn box_transform(lo: [f32; 3], hi: [f32; 3]) -> Option<Mat4> {
    let (lo, hi) = (Vec3::from(lo), Vec3::from(hi));
    let ext = hi - lo;
    (lo.is_finite() && hi.is_finite() && ext.min_element() > 0.0)
        .then(|| Mat4::from_translation(lo) * Mat4::from_scale(ext))
}

/// `gridvolume`.
pub(crate) const GRIDVOLUME: VolumePlugin = Plugin {
    name: "gridvolume",
    aliases: &[],
    doc: "A voxel grid read from a `.vol` file, looked up as Mitsuba 3 does: voxel centres at \
          (i + 0.5) / n of the local unit cube, trilinear or nearest, indices beyond the ends \
          mapped by wrap_mode. Used as a medium's sigma_t or albedo (1 or 3 channels) \
          or an sggx phase function's S (6 channels); the \
          medium's extinction is zero outside its sigma_t grid's box.",
    params: &[
        FILENAME,
        TO_WORLD,
        USE_GRID_BBOX,
        FILTER_TYPE,
        WRAP_MODE,
        RAW,
        MAX_VALUE,
        ACCEL,
    ],
    nested: "",
    build: |obj| {
        for p in [RAW, ACCEL] {
            p.read_bool(obj)?;
        }
        MAX_VALUE.read_f32_or(obj, 0.0)?;
        let filter = match FILTER_TYPE.read_choice(obj)? {
            "nearest" => GridFilter::Nearest,
            _ => GridFilter::Trilinear,
        };
        let wrap = match WRAP_MODE.read_choice(obj)? {
            "repeat" => GridWrap::Repeat,
            "mirror" => GridWrap::Mirror,
            _ => GridWrap::Clamp,
        };
        let name = obj
            .string_opt(FILENAME.name)?
            .ok_or_else(|| obj.error(format!("{} needs \"filename\"", obj.describe())))?;
        let path = obj.resolve_file(&name);
        let file = read_vol(&path)
            .map_err(|e| at_prop(obj, FILENAME.name, format!("{}: {e}", path.display())))?;
        let mut to_world = TO_WORLD.read_transform(obj)?.m;
        if USE_GRID_BBOX.read_bool(obj)? {
            let b = box_transform(file.bbox[0], file.bbox[1]).ok_or_else(|| {
                at_prop(
                    obj,
                    USE_GRID_BBOX.name,
                    format!(
                        "{}: the .vol file's bounding box {:?} to {:?} is empty or not finite",
                        path.display(),
                        file.bbox[0],
                        file.bbox[1]
                    ),
                )
            })?;
            to_world *= b;
        }
        let to_world = Transform::new(to_world).ok_or_else(|| {
            at_prop(
                obj,
                TO_WORLD.name,
                format!("\"to_world\" of {} is not invertible", obj.describe()),
            )
        })?;
        Ok(Volume {
            data: VolumeData::Grid(GridVolume {
                grid: file.grid,
                filter,
                wrap,
            }),
            to_world,
        })
    },
};

const CONST_TO_WORLD: Param = Param::transform(
    "to_world",
    "places the volume: its local unit cube [0, 1]^3 in the world",
);
const VALUE: Param = Param::rgb(
    "value",
    Default::Rgb([1.0; 3]),
    Range::NonNegative,
    "the value everywhere (a float or rgb)",
);

/// `constvolume`.
pub(crate) const CONSTVOLUME: VolumePlugin = Plugin {
    name: "constvolume",
    aliases: &[],
    doc: "The same value everywhere. As a heterogeneous medium's sigma_t it still bounds the \
          medium, as in Mitsuba 3: to its unit cube placed by to_world (a float or rgb given \
          directly for sigma_t is this with to_world the identity).",
    params: &[VALUE, CONST_TO_WORLD],
    nested: "",
    build: |obj| {
        Ok(Volume {
            data: VolumeData::Constant(VALUE.read_color(obj)?),
            to_world: CONST_TO_WORLD.read_transform(obj)?,
        })
    },
};

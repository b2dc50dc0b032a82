//! `<sensor>` / Nori's `<camera>` with its `<film>`, `<rfilter>` and `<sampler>`.
//!
//! Sensor `perspective`: `fov` (float, degrees) with `fov_axis` (x|y|diagonal|smaller|larger,
//! default x), or else `focal_length` (string like "50mm", default 50mm, a diagonal field of view
//! on a 36x24 mm frame, as in Mitsuba 3); `to_world`; `near_clip` (0.01; 1e-4 for a Nori camera, which carries width/height), `far_clip`
//! (10000).
//! Film `hdrfilm`: `width` (768), `height` (576); `pixel_format`, `component_format` and
//! `file_format` are accepted and have no effect (the output file's extension decides). Nori
//! puts `width`/`height` (defaults 1280x720) on the camera. Filter: `box`, `gaussian` (`stddev`
//! 0.5); default gaussian. Sampler (`sample_count` 4, `seed` 0): `independent` (default), or
//! Tessera's `zsobol` (Owen-scrambled Sobol in Morton order, see
//! `tessera_core::sampling::ZSobolSampler`). Mitsuba's stratified low-discrepancy samplers
//! (`ldsampler`, `stratified`, `multijitter`, `orthogonal`) render with `zsobol`, the closest
//! Tessera has (not Mitsuba's exact points; a warning says so); `correlated` renders with the
//! independent sampler (a warning says so).
use super::util::{at_prop, float_checked, transform, Result};
use crate::xml::{Kind, Object};
use tessera_core::camera::{Filter, FovAxis, GaussianFilter, Perspective};
use tessera_core::sampling::SamplerKind;

/// Largest image edge accepted.
pub const MAX_EDGE: i64 = 1 << 16;
/// Largest pixel count accepted (the accumulation buffer takes 64 bytes a pixel).
pub const MAX_PIXELS: i64 = 1 << 26;

/// The sensor and what hangs off it.
pub struct SensorParts {
    pub camera: Perspective,
    pub filter: Filter,
    pub spp: Option<u64>,
    pub seed: Option<u64>,
    pub sampler: Option<SamplerKind>,
}

/// Builds the pixel filter.
pub fn build_filter(obj: &Object) -> Result<Filter> {
    let f = match obj.plugin.as_str() {
        "box" => Filter::Box,
        "gaussian" => Filter::Gaussian(GaussianFilter::new(float_checked(
            obj,
            "stddev",
            0.5,
            |v| v > 0.0 && v <= 64.0,
            "in (0, 64]",
        )?)),
        other => {
            return Err(obj.error(format!(
                "unknown rfilter \"{other}\" (known: box, gaussian)"
            )))
        }
    };
    obj.check_unused()?;
    Ok(f)
}

/// Reads a sampler: `(sample_count, seed, which sampler)`.
pub fn build_sampler(obj: &Object, warnings: &mut Vec<String>) -> Result<(u64, u64, SamplerKind)> {
    let name = match obj.plugin.as_str() {
        n @ ("independent" | "zsobol") => n,
        n @ ("stratified" | "multijitter" | "orthogonal" | "ldsampler" | "correlated") => {
            let sub = if n == "correlated" {
                "independent"
            } else {
                "zsobol"
            };
            warnings.push(format!(
                "{}: sampler \"{n}\" renders with Tessera's {sub} sampler",
                obj.loc
            ));
            obj.boolean_opt("jitter")?;
            sub
        }
        other => {
            return Err(obj.error(format!(
                "unknown sampler \"{other}\" (known: independent, zsobol; Mitsuba's \
                 ldsampler, stratified, multijitter, orthogonal map to zsobol)"
            )))
        }
    };
    let spp = obj.integer("sample_count", 4)?;
    if !(1..=1 << 40).contains(&spp) {
        return Err(at_prop(
            obj,
            "sample_count",
            format!("\"sample_count\" must be between 1 and 2^40, found {spp}"),
        ));
    }
    let seed = obj.integer("seed", 0)?;
    obj.check_unused()?;
    // `name` is one of the two known names by the match above.
    let kind = SamplerKind::from_name(name, spp as u64).unwrap_or_default();
    Ok((spp as u64, seed as u64, kind))
}

fn size(obj: &Object, name: &str, default: i64) -> Result<u32> {
    let v = obj.integer(name, default)?;
    if !(1..=MAX_EDGE).contains(&v) {
        return Err(at_prop(
            obj,
            name,
            format!("\"{name}\" must be between 1 and {MAX_EDGE}, found {v}"),
        ));
    }
    Ok(v as u32)
}

/// Builds the sensor.
pub fn build_sensor(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    if obj.plugin != "perspective" {
        return Err(obj.error(format!(
            "unknown sensor \"{}\" (known: perspective)",
            obj.plugin
        )));
    }
    let to_world = transform(obj, "to_world")?;
    // Nori's camera carries width/height and clips at 1e-4; Mitsuba's sensor clips at 0.01.
    let nori = obj.has("width") || obj.has("height");
    let near = float_checked(
        obj,
        "near_clip",
        if nori { 1e-4 } else { 0.01 },
        |v| v >= 0.0,
        "non-negative",
    )?;
    let far = float_checked(
        obj,
        "far_clip",
        10000.0,
        |v| v > near as f64,
        "greater than near_clip",
    )?;
    let (fov, axis) = match obj.float_opt("fov")? {
        Some(_) => {
            let fov = float_checked(
                obj,
                "fov",
                0.0,
                |v| v > 0.0 && v < 180.0,
                "in (0, 180) degrees",
            )?;
            let axis = match obj.string("fov_axis", "x")?.as_str() {
                "x" => FovAxis::X,
                "y" => FovAxis::Y,
                "diagonal" => FovAxis::Diagonal,
                "smaller" => FovAxis::Smaller,
                "larger" => FovAxis::Larger,
                other => {
                    return Err(at_prop(
                        obj,
                        "fov_axis",
                        format!("unknown fov_axis \"{other}\" (x, y, diagonal, smaller, larger)"),
                    ))
                }
            };
            (fov, axis)
        }
        None => {
            let s = obj.string("focal_length", "50mm")?;
            let f: f64 = s.trim_end_matches("mm").trim().parse().ok().filter(|f: &f64| *f > 0.0 && f.is_finite()).ok_or_else(|| {
                at_prop(obj, "focal_length", format!("\"focal_length\" must be a positive length like \"50mm\", found \"{s}\""))
            })?;
            let diag = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            (
                (2.0 * (diag / (2.0 * f)).atan()).to_degrees() as f32,
                FovAxis::Diagonal,
            )
        }
    };
    let mut filter = Filter::Gaussian(GaussianFilter::new(0.5));
    let (mut width, mut height) = (768, 576);
    // Nori: width/height (and the filter) on the camera itself.
    if obj.has("width") || obj.has("height") {
        width = size(obj, "width", 1280)?;
        height = size(obj, "height", 720)?;
    }
    let (mut spp, mut seed, mut sampler) = (None, None, None);
    for c in &obj.children {
        match c.obj.kind {
            Kind::Film => {
                c.mark_used();
                let film = &c.obj;
                if film.plugin != "hdrfilm" {
                    return Err(
                        film.error(format!("unknown film \"{}\" (known: hdrfilm)", film.plugin))
                    );
                }
                width = size(film, "width", 768)?;
                height = size(film, "height", 576)?;
                for p in ["pixel_format", "component_format", "file_format"] {
                    film.string_opt(p)?;
                }
                for f in &film.children {
                    if f.obj.kind == Kind::RFilter {
                        f.mark_used();
                        filter = build_filter(&f.obj)?;
                    }
                }
                film.check_unused()?;
            }
            Kind::RFilter => {
                c.mark_used();
                filter = build_filter(&c.obj)?;
            }
            Kind::Sampler => {
                c.mark_used();
                let (n, s, k) = build_sampler(&c.obj, warnings)?;
                spp = Some(n);
                seed = Some(s);
                sampler = Some(k);
            }
            _ => {}
        }
    }
    if width as i64 * height as i64 > MAX_PIXELS {
        return Err(obj.error(format!(
            "image of {width}x{height} pixels is over the limit of {MAX_PIXELS} pixels"
        )));
    }
    obj.check_unused()?;
    let camera = Perspective::new(to_world, width, height, fov, axis, near, far);
    Ok(SensorParts {
        camera,
        filter,
        spp,
        seed,
        sampler,
    })
}

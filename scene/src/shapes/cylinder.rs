//! The `cylinder` shape, as Mitsuba 3 reads it: the open cylinder of radius `radius` around the
//! segment from `p0` to `p1`, placed by `to_world`. The frame around the axis is the one Mitsuba
//! 3 builds (its `Frame3f` of the axis direction), so uv agree. Computed in f64 before anything
//! is stored.
use super::{Geometry, ShapePlugin, RADIUS, TO_WORLD};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use glam::{DMat4, DVec3};
use tessera_core::geometry::{Cylinder, ShapeKind};
use tessera_core::math::Norm;

const P0: Param = Param::new(
    "p0",
    ParamType::Point,
    Default::Note("(0, 0, 0)"),
    Range::Any,
    "start of the axis, before to_world",
);
const P1: Param = Param::new(
    "p1",
    ParamType::Point,
    Default::Note("(0, 0, 1)"),
    Range::Any,
    "end of the axis, before to_world",
);

/// `cylinder`.
pub(crate) const CYLINDER: ShapePlugin = Plugin {
    name: "cylinder",
    aliases: &[],
    doc: "An analytic open cylinder (no end caps) of the given radius around the segment from \
          p0 to p1, normals pointing away from the axis, placed by to_world, which must keep \
          the cross-section a circle (rotation, translation, a scale uniform across the axis; \
          it may stretch along the axis).",
    params: &[P0, P1, RADIUS, TO_WORLD, super::FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: build_cylinder,
};

/// The frame Mitsuba 3 puts around a unit direction (Duff et al.'s), in f64: `(s, t)`.
fn frame_of(n: DVec3) -> (DVec3, DVec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

fn build_cylinder(obj: &Object) -> Result<Geometry> {
    let p0 = DVec3::from(obj.point(P0.name, [0.0, 0.0, 0.0])?);
    let p1 = DVec3::from(obj.point(P1.name, [0.0, 0.0, 1.0])?);
    let radius = f64::from(RADIUS.read_f32(obj)?);
    let tf = obj.transform(TO_WORLD.name, DMat4::IDENTITY)?;
    let d = p1 - p0;
    let length = d.norm();
    if !(length > 0.0 && length.is_finite()) {
        return Err(obj.error("the cylinder's p0 and p1 must differ"));
    }
    let n = d / length;
    let (s, t) = frame_of(n);
    // Columns of to_world * translate(p0) * frame * scale(radius, radius, length).
    let cx = tf.transform_vector3(s * radius);
    let cy = tf.transform_vector3(t * radius);
    let cz = tf.transform_vector3(n * length);
    let origin = tf.transform_point3(p0);
    let (r, ry, len) = (cx.norm(), cy.norm(), cz.norm());
    let tol = 1e-5;
    if !(r > 0.0 && len > 0.0 && r.is_finite() && len.is_finite() && origin.is_finite())
        || (r - ry).abs() > tol * r
        || cx.dot(cy).abs() > tol * r * ry
        || cx.dot(cz).abs() > tol * r * len
        || cy.dot(cz).abs() > tol * ry * len
    {
        return Err(obj.error(
            "the to_world of a cylinder must keep its cross-section a circle (no shear, the \
             same scale across the axis)",
        ));
    }
    let axes = [cx / r, cy / ry, cz / len];
    if axes[0].cross(axes[1]).dot(axes[2]) < 0.0 {
        return Err(obj.error("the to_world of a cylinder must not mirror it"));
    }
    Geometry::of(ShapeKind::Cylinder(Cylinder {
        origin,
        axes,
        radius: r,
        length: len,
    }))
}

//! An instance of a shape group (Mitsuba 3's `instance` of a `shapegroup`): the group's shapes,
//! stored once in object space under their own hierarchy, placed by a transform. Rays go to
//! object space by the inverse; hits come back by the transform, normals by its inverse
//! transpose.
use super::Interaction;
use crate::math::{gamma, Aabb, Frame, Norm, Ray, Transform};
use glam::Vec3;

/// One placed copy of a shape group.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    /// The group (index into the scene's groups).
    pub group: u32,
    /// Object (group) to world, with its inverse.
    pub to_world: Transform,
}

impl Instance {
    /// The ray in the group's space; the ray parameter `t` means the same point in both.
    #[inline]
    pub fn to_object(&self, ray: &Ray) -> Ray {
        Ray {
            o: self.to_world.inv.transform_point3(ray.o),
            d: self.to_world.inv.transform_vector3(ray.d),
            t_max: ray.t_max,
        }
    }

    /// World bounds of the group's object-space box `b` (empty stays empty).
    pub fn bounds(&self, b: Aabb) -> Aabb {
        if b.is_empty() {
            return b;
        }
        let mut out = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            out = out.grow(self.to_world.point(c));
        }
        out
    }

    /// The object-space interaction `it` (found with [`Instance::to_object`] of `ray`) in world
    /// space.
    #[inline]
    pub(crate) fn interaction_to_world(&self, it: &Interaction, ray: &Ray) -> Interaction {
        let tf = &self.to_world;
        let m = tf.m;
        let p = tf.point(it.p);
        // The object point's own bound carried through the matrix, plus the rounding of the
        // transform itself.
        let abs = |v: glam::Vec4| v.truncate().abs();
        let (cx, cy, cz, cw) = (abs(m.x_axis), abs(m.y_axis), abs(m.z_axis), abs(m.w_axis));
        let lin = cx * it.p.x.abs() + cy * it.p.y.abs() + cz * it.p.z.abs();
        let carried = cx * it.p_err.x + cy * it.p_err.y + cz * it.p_err.z;
        let p_err = carried * (1.0 + gamma(3)) + (lin + cw) * gamma(3);
        let ng = tf.normal(it.ng).unit_or(Vec3::Z);
        let n = tf.normal(it.frame.n).unit_or(ng);
        let frame = Frame::from_normal_tangent(n, tf.vector(it.frame.s));
        Interaction {
            p,
            p_err,
            t: it.t,
            ng,
            frame,
            uv: it.uv,
            shape: it.shape,
            wi: (-ray.d).unit(),
        }
    }
}

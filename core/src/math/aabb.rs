//! Axis-aligned bounding boxes and the robust slab test.
use super::{gamma, Ray};
use glam::Vec3;

/// An axis-aligned box; the empty box has `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (identity of `union`).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The box around one point.
    pub fn point(p: Vec3) -> Self {
        Aabb { min: p, max: p }
    }
    /// Smallest box holding both.
    #[inline]
    pub fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }
    /// Smallest box holding the box and the point.
    #[inline]
    pub fn grow(self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }
    /// Centre point.
    #[inline]
    pub fn centroid(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }
    /// Edge lengths (zero or negative when empty).
    #[inline]
    pub fn extent(&self) -> Vec3 {
        self.max - self.min
    }
    /// Whether no point is inside.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }
    /// Surface area (0 for empty boxes).
    pub fn area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }
    /// Slab test against `[0, t_max)` with the conservative far-bound widening of pbrt-v4, so a
    /// ray grazing a box face is never missed through rounding. `inv_d` is `1 / ray.d`.
    #[inline]
    pub fn hit(&self, ray: &Ray, inv_d: Vec3, t_max: f32) -> Option<f32> {
        let t0 = (self.min - ray.o) * inv_d;
        let t1 = (self.max - ray.o) * inv_d;
        let near = t0.min(t1);
        let far = t0.max(t1) * (1.0 + 2.0 * gamma(3));
        let t_near = near.max_element().max(0.0);
        let t_far = far.min_element().min(t_max);
        // NaN from 0 * inf (origin on a slab plane, direction parallel) fails the comparison
        // in `max_element`/`min_element` consistently; treat it as a hit to stay conservative.
        if t_near <= t_far {
            Some(t_near)
        } else {
            None
        }
    }
}

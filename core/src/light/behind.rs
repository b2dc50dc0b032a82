//! The half-space behind a flat one-sided area light, where none of its light arrives.
//!
//! An area light emits from the front side of its surface only (`emitter::AreaLight`).
//! When the surface is a flat mesh with face normals, a point behind its plane cannot receive
//! any of it: every sample light sampling draws for such a point fails the one-sided test, after
//! paying for a triangle choice, a point, a distance and a density. [`Behind::contains`] answers
//! first, for the price of a dot product. In the Cornell box this is every point of the ceiling,
//! which sits 5 mm above the light.
//!
//! The answer must never differ from what the samples would have found, or images would change.
//! So it says "behind" only when the point is behind the plane by more than a margin that covers
//! everything the per-sample test can see differently:
//! - the vertices' distances from the fitted plane (`dev`, exact in `f64`);
//! - each triangle's own stored normal against the plane's (`tilt`, times the distance from the
//!   point to the farthest vertex);
//! - rounding, in the sampled point's interpolation, in `p - r`, its normalisation and the
//!   dot product, and in this test's own dot product: a few `f32` epsilons each, bounded by
//!   `ROUNDING` (`1e-5`, about 80 epsilons) relative to the coordinates and lengths involved.
//!
//! Meshes with vertex normals are left out (the one-sided test uses the interpolated shading
//! normal, which may lean anywhere), as are curved meshes (the margin would swallow the test).
//! Spheres and disks are not covered.
use crate::geometry::{Shape, ShapeKind};
use crate::math::Norm;
use glam::{DVec3, Vec3};

/// Relative bound on the rounding errors of the test and of light sampling (see the header).
const ROUNDING: f32 = 1e-5;

/// Largest `tilt` for which the test is kept: a mesh leaning more is not treated as flat.
const MAX_TILT: f64 = 1e-3;

/// The half-space behind a flat one-sided area light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Behind {
    /// Unit normal of the lit side.
    normal: Vec3,
    /// `normal . x` for the points `x` of the plane.
    offset: f32,
    /// A point of the light (its vertices' centroid).
    center: Vec3,
    /// Largest distance from `center` to a vertex.
    radius: f32,
    /// Largest distance of a vertex from the plane, plus rounding of the vertices' coordinates.
    dev: f32,
    /// Largest distance between a triangle's stored unit normal and `normal`.
    tilt: f32,
}

impl Behind {
    /// The half-space of `shape` as an area light, if it is a flat mesh with face normals.
    pub fn of(shape: &Shape) -> Option<Behind> {
        let ShapeKind::Mesh(m) = &shape.kind else {
            return None;
        };
        if !m.normals.is_empty() || m.indices.is_empty() {
            return None;
        }
        let flip = if shape.flip_normals { -1.0 } else { 1.0 };
        // Area-weighted normal and the vertices' centroid, in f64.
        let mut sum = DVec3::ZERO;
        for i in 0..m.indices.len() {
            let [p0, p1, p2] = m.vertices(i).map(|p| p.as_dvec3());
            sum += (p1 - p0).cross(p2 - p0);
        }
        let normal = (sum * flip).try_unit()?;
        let used: alloc::vec::Vec<DVec3> = m
            .indices
            .iter()
            .flat_map(|idx| idx.iter().map(|&i| m.positions[i as usize].as_dvec3()))
            .collect();
        let center = used.iter().copied().sum::<DVec3>() / used.len() as f64;
        let offset = normal.dot(center);
        let mut dev = 0.0f64;
        let mut radius = 0.0f64;
        let mut extent = 0.0f64;
        for &p in &used {
            dev = dev.max((normal.dot(p) - offset).abs());
            radius = radius.max((p - center).norm());
            extent = extent.max(p.abs().max_element());
        }
        let mut tilt = 0.0f64;
        for i in 0..m.indices.len() {
            let n = m.face_normal(i).as_dvec3() * flip;
            tilt = tilt.max((n - normal).norm());
        }
        if !(tilt <= MAX_TILT) {
            return None;
        }
        let b = Behind {
            normal: normal.as_vec3(),
            offset: offset as f32,
            center: center.as_vec3(),
            // Rounded up by the relative bound so that f32 storage cannot shrink them.
            radius: (radius * (1.0 + ROUNDING as f64)) as f32,
            dev: (dev + ROUNDING as f64 * extent) as f32,
            tilt: (tilt + ROUNDING as f64) as f32,
        };
        let finite = b.normal.is_finite()
            && b.offset.is_finite()
            && b.center.is_finite()
            && b.radius.is_finite()
            && b.dev.is_finite();
        finite.then_some(b)
    }

    /// Whether no light of the light reaches `r`: `r` lies behind its plane by more than the
    /// margin. False for non-finite points.
    #[inline]
    pub fn contains(&self, r: Vec3) -> bool {
        let s = self.normal.dot(r) - self.offset;
        // In front or on the plane: the common case, decided by the dot product alone.
        if !(s < 0.0) {
            return false;
        }
        let reach = (r - self.center).norm() + self.radius;
        let margin = self.dev + self.tilt * reach + ROUNDING * (reach + r.abs().max_element());
        s < -margin
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emitter::{AreaLight, EmitterCtx};
    use crate::geometry::{Interaction, Mesh};
    use crate::math::Frame;
    use crate::sampling::owen::mix64;
    use crate::Color;
    use glam::Vec2;

    fn unit(h: u64) -> f32 {
        (h >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A flat quad (two triangles) of random size, orientation and position, far from the origin
    /// or near it.
    fn random_quad(r: u64) -> Shape {
        let h = |k: u64| unit(mix64(r ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15)));
        let scale = 10f32.powf(h(1) * 4.0 - 2.0);
        let center = Vec3::new(h(2) - 0.5, h(3) - 0.5, h(4) - 0.5) * 10f32.powf(h(5) * 3.0);
        let n = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(h(6), h(7)));
        let f = Frame::from_normal(n);
        let (a, b) = (scale * (0.2 + h(8)), scale * (0.2 + h(9)));
        let corners = [(-a, -b), (a, -b), (a, b), (-a, b)].map(|(x, y)| center + f.s * x + f.t * y);
        let mesh = Mesh::new(
            corners.to_vec(),
            alloc::vec::Vec::new(),
            alloc::vec::Vec::new(),
            alloc::vec![[0, 1, 2], [0, 2, 3]],
        );
        Shape {
            kind: ShapeKind::Mesh(mesh),
            bsdf: 0,
            emitter: Some(0),
            flip_normals: h(10) < 0.5,
        }
    }

    /// Wherever `contains` says "behind", light sampling finds nothing either, for points at
    /// every distance from the plane down to a few ulps and any light size and position. And it
    /// says so for most points clearly behind, so the test above is not vacuous.
    #[test]
    fn behind_means_no_sample_arrives() {
        let (mut behind, mut clearly) = (0, 0);
        for t in 0..300u64 {
            let shape = random_quad(mix64(t + 1));
            let b = Behind::of(&shape).expect("a flat quad has a half-space");
            // Without its half-space, so that every sample is tested the long way.
            let light = AreaLight::new(0, Color::ONE);
            let shapes = [shape];
            let ctx = EmitterCtx {
                shapes: &shapes,
                disks: &[],
                scene_center: Vec3::ZERO,
                scene_radius: 1.0,
            };
            for k in 0..200u64 {
                let h = mix64(t << 20 | k);
                // Signed distance from the plane: +-10^(-7..2) times the light's size.
                let side = if h & 1 == 0 { -1.0 } else { 1.0 };
                let dist = side * b.radius * 10f32.powf(unit(mix64(h)) * 9.0 - 7.0);
                let along = Frame::from_normal(b.normal);
                let (x, y) = (unit(mix64(h ^ 1)) - 0.5, unit(mix64(h ^ 2)) - 0.5);
                let r = b.center + b.normal * dist + (along.s * x + along.t * y) * (4.0 * b.radius);
                let it = Interaction {
                    p: r,
                    p_err: Vec3::ZERO,
                    t: 1.0,
                    ng: Vec3::Z,
                    frame: Frame::from_normal(Vec3::Z),
                    uv: Vec2::ZERO,
                    shape: 1,
                    wi: Vec3::Z,
                };
                if b.contains(r) {
                    behind += 1;
                    for j in 0..64u64 {
                        let hu = mix64(h ^ (j + 7) << 32);
                        let u = Vec2::new(unit(hu), unit(mix64(hu)));
                        assert!(
                            light.sample(&ctx, &it, u).is_none(),
                            "quad {t} point {k}: a sample arrives behind"
                        );
                    }
                }
                // The margin grows with the coordinates' size (rounding) and the point's reach.
                let clear = 1e-3 * (6.0 * b.radius + b.center.abs().max_element());
                if dist < -clear {
                    clearly += 1;
                    assert!(
                        b.contains(r),
                        "quad {t} point {k} at {dist}: not found behind"
                    );
                }
            }
        }

        assert!(behind > 12_000 && clearly > 8_000, "{behind} {clearly}");
    }

    /// Curved meshes and meshes with vertex normals get no half-space.
    #[test]
    fn only_flat_meshes_with_face_normals() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.0, 0.0, 1.0)];
        let bent = Mesh::new(
            p.to_vec(),
            alloc::vec::Vec::new(),
            alloc::vec::Vec::new(),
            alloc::vec![[0, 1, 2], [0, 3, 1]],
        );
        let shape = |kind| Shape {
            kind,
            bsdf: 0,
            emitter: Some(0),
            flip_normals: false,
        };
        assert_eq!(Behind::of(&shape(ShapeKind::Mesh(bent))), None);
        let normals = alloc::vec![Vec3::Z; 3];
        let smooth = Mesh::new(
            p[..3].to_vec(),
            normals,
            alloc::vec::Vec::new(),
            alloc::vec![[0, 1, 2]],
        );
        assert_eq!(Behind::of(&shape(ShapeKind::Mesh(smooth))), None);
        let flat = Mesh::new(
            p[..3].to_vec(),
            alloc::vec::Vec::new(),
            alloc::vec::Vec::new(),
            alloc::vec![[0, 1, 2]],
        );
        let b = Behind::of(&shape(ShapeKind::Mesh(flat))).unwrap();
        assert!(b.contains(Vec3::new(0.2, 0.2, -0.1)));
        assert!(!b.contains(Vec3::new(0.2, 0.2, 0.1)));
        assert!(!b.contains(Vec3::new(0.2, 0.2, 0.0)));
        assert!(!b.contains(Vec3::NAN));
    }
}

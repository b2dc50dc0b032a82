//! The parts of a camera ray's hit that only the `aov` integrator's `dp_du`, `dp_dv`,
//! `prim_index` and `shape_index` outputs read: the position's partial derivatives along the
//! surface's (u, v) and which primitive and shape were hit, numbered as Mitsuba 3.9.1 numbers
//! them (`ShapeNumbering`).
//!
//! They are computed by a cast of their own rather than kept in every `Interaction`
//! (`crate::geometry::Interaction`): no other integrator needs them, and the ordinary hit stays
//! as small and as fast as it was.
//!
//! The derivatives follow Mitsuba 3.9.1's shapes: a mesh solves them from its texture
//! coordinates (zero where those are degenerate; `p1 - p0` and `p2 - p0` without texture
//! coordinates); a sphere's are `2 pi r` along increasing longitude and `pi r` along the polar
//! angle (world axes: Tessera's sphere keeps no rotation); a disk's are the unit radial
//! direction and `2 pi r` along the angle, carried by its transform; a cylinder's are `2 pi r`
//! around the axis and the axis times the length; an instance carries its shape's by its
//! transform.
use super::{Scene, SurfaceDetail};
use crate::geometry::{Hit, Mesh, Prim, ShapeKind};
use crate::math::{sqrt, Norm, Ray, PI};
use core::cell::Cell;
use glam::Vec3;

impl Scene {
    /// [`SurfaceDetail`] of the closest hit along `ray` (the hit `Scene::intersect` finds).
    pub fn surface_detail(&self, ray: &Ray) -> Option<SurfaceDetail> {
        let inner = Cell::default();
        let hit = self.closest(ray, &inner)?;
        let numbering = &self.shape_numbering;
        match self.prims[hit.prim as usize] {
            Prim::Instance { instance } => {
                let inst = &self.instances[instance as usize];
                let g = &self.groups[inst.group as usize];
                let ih = inner.get();
                let prim = &g.prims[ih.prim as usize];
                let ohit = Hit {
                    t: hit.t,
                    prim: ih.prim,
                    uv: ih.uv,
                };
                let (dp_du, dp_dv, prim_index) =
                    self.local_detail(prim, &ohit, &inst.to_object(ray));
                let shape_index = match numbering.instances.get(instance as usize) {
                    Some(&n) => n,
                    None => self.shapes.len() as u32 + instance + 1,
                };
                Some(SurfaceDetail {
                    dp_du: inst.to_world.vector(dp_du),
                    dp_dv: inst.to_world.vector(dp_dv),
                    prim_index,
                    shape_index,
                })
            }
            prim => {
                let (dp_du, dp_dv, prim_index) = self.local_detail(&prim, &hit, ray);
                let shape_index = match numbering.shapes.get(prim.shape() as usize) {
                    Some(n) => n.index,
                    None => prim.shape() + 1,
                };
                Some(SurfaceDetail {
                    dp_du,
                    dp_dv,
                    prim_index,
                    shape_index,
                })
            }
        }
    }

    /// Derivatives and Mitsuba's primitive index of a hit on a shape's primitive, in the space
    /// `ray` is in.
    fn local_detail(&self, prim: &Prim, hit: &Hit, ray: &Ray) -> (Vec3, Vec3, u32) {
        let shape = prim.shape();
        let number = self.shape_numbering.shapes.get(shape as usize).copied();
        match (&self.shapes[shape as usize].kind, prim) {
            (ShapeKind::Mesh(m), Prim::Triangle { face, .. }) => {
                let (dp_du, dp_dv) = mesh_partials(m, *face as usize);
                let prim_index = match number {
                    Some(n) if n.rectangle => {
                        let uv = m.uv_at(*face as usize, hit.uv.x, hit.uv.y);
                        n.prim_offset + u32::from(uv.x + uv.y > 1.0)
                    }
                    Some(n) => n.prim_offset + face,
                    None => *face,
                };
                (dp_du, dp_dv, prim_index)
            }
            (ShapeKind::Sphere(s), _) => {
                let n = ((ray.at(hit.t) - s.center) / s.radius).unit_or(Vec3::Z);
                let dp_du = Vec3::new(-n.y, n.x, 0.0) * (2.0 * PI * s.radius);
                let rd = sqrt(n.x * n.x + n.y * n.y);
                let dp_dv = if rd == 0.0 {
                    Vec3::X
                } else {
                    Vec3::new(n.z * n.x / rd, n.z * n.y / rd, -rd)
                };
                (dp_du, dp_dv * (PI * s.radius), 0)
            }
            (ShapeKind::Disk(d), _) => {
                let disk = &self.disks[*d as usize];
                let r = hit.uv.norm();
                let inv_r = if r > 0.0 { 1.0 / r } else { 0.0 };
                let (c, s) = (hit.uv.x * inv_r, hit.uv.y * inv_r);
                let dp_du = disk.to_world.vector(Vec3::new(c, s, 0.0));
                let dp_dv = disk.to_world.vector(Vec3::new(-s, c, 0.0)) * (2.0 * PI * r);
                (dp_du, dp_dv, 0)
            }
            (ShapeKind::Cylinder(c), _) => {
                let (_, _, l) = c.project(ray.at(hit.t));
                let (_, dp_du) = c.uv_dpdu(l);
                (dp_du, (c.axes[2] * c.length).as_vec3(), 0)
            }
            // The builder pairs each primitive with its shape's kind.
            _ => (Vec3::ZERO, Vec3::ZERO, 0),
        }
    }
}

/// Mitsuba 3's position partials of triangle `i`: solved from the texture coordinates (zero
/// where their map is degenerate), or the edges `p1 - p0`, `p2 - p0` without them.
fn mesh_partials(m: &Mesh, i: usize) -> (Vec3, Vec3) {
    let [a, b, c] = m.indices[i].map(|k| k as usize);
    let (e1, e2) = (
        m.positions[b] - m.positions[a],
        m.positions[c] - m.positions[a],
    );
    if m.uvs.is_empty() {
        return (e1, e2);
    }
    let (d0, d1) = (m.uvs[b] - m.uvs[a], m.uvs[c] - m.uvs[a]);
    let det = d0.x * d1.y - d0.y * d1.x;
    let inv = if det != 0.0 { 1.0 / det } else { 0.0 };
    ((e1 * d1.y - e2 * d0.y) * inv, (e2 * d0.x - e1 * d1.x) * inv)
}

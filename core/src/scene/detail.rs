//! The parts of a ray's hit that only the `aov` integrator's `dp_du`, `dp_dv`, `prim_index`
//! and `shape_index` outputs and bump-mapped vertices (`shading_point.rs`) read: the position's partial derivatives along the
//! surface's (u, v) and which primitive and shape were hit, numbered as Mitsuba 3.9.1 numbers
//! them (`ShapeNumbering`).
//!
//! They are computed by a cast of their own rather than kept in every `Interaction`
//! (`crate::geometry::Interaction`): ordinary vertices do not need them, and the ordinary hit
//! stays as small and as fast as it was.
//!
//! The derivatives are Mitsuba 3.9.1's (`Shape::partials`); an instance carries its shape's
//! by its transform.
use super::{Scene, SurfaceDetail};
use crate::geometry::{Hit, MeshSite, Prim, ShapeKind};
use crate::math::Ray;
use core::cell::Cell;
use glam::Vec3;

impl Scene {
    /// [`SurfaceDetail`] of the closest hit along `ray` (the hit `Scene::intersect` finds).
    pub fn surface_detail(&self, ray: &Ray) -> Option<SurfaceDetail> {
        self.surface_detail_and_site(ray).map(|(d, _)| d)
    }

    /// [`SurfaceDetail`] of the closest hit along `ray` and, on a mesh, the triangle hit and
    /// its barycentric coordinates (what `mesh_attribute` textures read).
    pub fn surface_detail_and_site(
        &self,
        ray: &Ray,
    ) -> Option<(SurfaceDetail, Option<MeshSite<'_>>)> {
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
                let (dp_du, dp_dv, prim_index, site) =
                    self.local_detail(prim, &ohit, &inst.to_object(ray));
                let shape_index = match numbering.instances.get(instance as usize) {
                    Some(&n) => n,
                    None => self.shapes.len() as u32 + instance + 1,
                };
                let detail = SurfaceDetail {
                    dp_du: inst.to_world.vector(dp_du),
                    dp_dv: inst.to_world.vector(dp_dv),
                    prim_index,
                    shape_index,
                };
                Some((detail, site))
            }
            prim => {
                let (dp_du, dp_dv, prim_index, site) = self.local_detail(&prim, &hit, ray);
                let shape_index = match numbering.shapes.get(prim.shape() as usize) {
                    Some(n) => n.index,
                    None => prim.shape() + 1,
                };
                let detail = SurfaceDetail {
                    dp_du,
                    dp_dv,
                    prim_index,
                    shape_index,
                };
                Some((detail, site))
            }
        }
    }

    /// Derivatives and Mitsuba's primitive index of a hit on a shape's primitive, in the space
    /// `ray` is in (the derivatives are the interaction's: see `Shape::interaction`), and the
    /// triangle hit on a mesh.
    fn local_detail(
        &self,
        prim: &Prim,
        hit: &Hit,
        ray: &Ray,
    ) -> (Vec3, Vec3, u32, Option<MeshSite<'_>>) {
        let shape_index = prim.shape();
        let shape = &self.shapes[shape_index as usize];
        let it = shape.interaction(hit, prim, ray, &self.disks, true);
        let (dp_du, dp_dv) = shape.partials(hit, prim, it.p, &self.disks);
        let number = self
            .shape_numbering
            .shapes
            .get(shape_index as usize)
            .copied();
        let prim_index = match (&shape.kind, prim) {
            (ShapeKind::Mesh(m), Prim::Triangle { face, .. }) => match number {
                Some(n) if n.rectangle => {
                    let uv = m.uv_at(*face as usize, hit.uv.x, hit.uv.y);
                    n.prim_offset + u32::from(uv.x + uv.y > 1.0)
                }
                Some(n) => n.prim_offset + face,
                None => *face,
            },
            _ => 0,
        };
        let site = match (&shape.kind, prim) {
            (ShapeKind::Mesh(m), Prim::Triangle { face, .. }) => Some(MeshSite {
                mesh: m,
                face: *face,
                b: hit.uv,
            }),
            _ => None,
        };
        (dp_du, dp_dv, prim_index, site)
    }
}

//! Shapes: geometry plus the material and emitter attached to it.
//!
//! Common scene parameters of every `<shape>`: `flip_normals` (boolean, default false), a nested
//! or referenced `<bsdf>` (default: `diffuse` with reflectance 0.5, as in Mitsuba 3), an optional
//! nested `<emitter type="area">`.
use super::{Curve, Cylinder, Disk, Hit, Interaction, Mesh, Prim, Sphere};
use crate::math::{acos, atan2_turns, sqrt, Frame, Norm, Ray};
use glam::{Vec2, Vec3};

/// The geometry of a shape.
#[derive(Clone, Debug)]
pub enum ShapeKind {
    /// A triangle mesh (also rectangles and cubes).
    Mesh(Mesh),
    /// An analytic sphere.
    Sphere(Sphere),
    /// An analytic disk; the index is into the scene's disk array.
    Disk(u32),
    /// An analytic open cylinder.
    Cylinder(Cylinder),
    /// Linear or B-spline curves (never an emitter: Mitsuba 3 cannot sample them).
    Curve(Curve),
}

/// A shape in the scene.
#[derive(Clone, Debug)]
pub struct Shape {
    /// Geometry.
    pub kind: ShapeKind,
    /// Index of its BSDF.
    pub bsdf: u32,
    /// Index of its area emitter, if any.
    pub emitter: Option<u32>,
    /// Whether normals are flipped (inside-out).
    pub flip_normals: bool,
}

/// A point on a shape's surface.
#[derive(Clone, Copy, Debug)]
pub struct PositionSample {
    /// The point.
    pub p: Vec3,
    /// Its error bound.
    pub p_err: Vec3,
    /// Unit geometric normal there (after `flip_normals`): the area-to-solid-angle Jacobian.
    pub ng: Vec3,
    /// Unit shading normal there (after `flip_normals`): the side an area emitter lights.
    pub ns: Vec3,
    /// Texture coordinates there, as a ray hitting the point would find them (zero where the
    /// sampler was not asked for them).
    pub uv: Vec2,
}

/// A point sampled on a shape for a reference point `r` ([`Shape::sample_toward`]).
#[derive(Clone, Copy, Debug)]
pub struct SampleToward {
    /// The point.
    pub ps: PositionSample,
    /// Its solid-angle density at `r`.
    pub pdf: f32,
    /// `ps.p - r`.
    pub d: Vec3,
    /// `|d|`.
    pub dist: f32,
}

impl Shape {
    /// Surface area.
    pub fn area(&self, disks: &[Disk]) -> f32 {
        match &self.kind {
            ShapeKind::Mesh(m) => m.area(),
            ShapeKind::Sphere(s) => s.area(),
            ShapeKind::Disk(d) => disks[*d as usize].area,
            ShapeKind::Cylinder(c) => c.area(),
            // Not computed: only emitters need it, and the loader refuses emitting curves.
            ShapeKind::Curve(_) => 0.0,
        }
    }

    #[inline]
    fn orient(&self, n: Vec3) -> Vec3 {
        if self.flip_normals {
            -n
        } else {
            n
        }
    }

    /// The full interaction for a hit on primitive `prim` of this shape; on a sphere, its
    /// texture coordinates only with `uv` (zero without: the two angles are a sizeable part of
    /// a sphere hit's cost, and most spheres' materials read none).
    #[inline]
    pub fn interaction(
        &self,
        hit: &Hit,
        prim: &Prim,
        ray: &Ray,
        disks: &[Disk],
        uv: bool,
    ) -> Interaction {
        let (p, p_err, ng, ns, uv, dpdu, tangent) = match (&self.kind, prim) {
            (ShapeKind::Mesh(m), Prim::Triangle { face, .. }) => {
                let h = m.hit(*face as usize, hit.uv.x, hit.uv.y);
                (h.p, h.p_err, h.ng, h.ns, h.uv, h.dpdu, h.tangent)
            }
            (ShapeKind::Sphere(s), _) => {
                let (p, err) = s.project(ray.at(hit.t));
                let n = (p - s.center) / s.radius;
                let n = n.unit_or(Vec3::Z);
                let uv = uv_if(uv, || sphere_uv(n));
                // Along increasing longitude, as Mitsuba 3's sphere.
                (p, err, n, n, uv, Vec3::new(-n.y, n.x, 0.0), None)
            }
            (ShapeKind::Disk(d), _) => {
                let disk = &disks[*d as usize];
                let (p, err) = disk.point(hit.uv);
                let uv = disk_uv(hit.uv);
                // Radial, as Mitsuba 3's disk (u is the radius).
                (
                    p,
                    err,
                    disk.normal,
                    disk.normal,
                    uv,
                    p - disk.to_world.point(Vec3::ZERO),
                    None,
                )
            }
            (ShapeKind::Cylinder(c), _) => {
                let (p, err, l) = c.project(ray.at(hit.t));
                let n = c.normal(l.x, l.y);
                let (uv, dpdu) = c.uv_dpdu(l);
                (p, err, n, n, uv, dpdu, None)
            }
            (ShapeKind::Curve(c), Prim::Curve { segment, .. }) => {
                let (p, err, s) = c.surface(*segment as usize, hit.uv.x, ray.at(hit.t));
                (p, err, s.n, s.n, s.uv, s.dp_du, None)
            }
            _ => unreachable_shape(),
        };
        let ng = self.orient(ng);
        let ns = self.orient(ns);
        // A stored tangent is the one from_normal_tangent finds for the unflipped normal.
        let frame = match tangent {
            Some(s) if !self.flip_normals => Frame {
                s,
                t: ns.cross(s),
                n: ns,
            },
            _ => Frame::from_normal_tangent(ns, dpdu),
        };
        Interaction {
            p,
            p_err,
            t: hit.t,
            ng,
            frame,
            uv,
            shape: hit_shape(prim),
            wi: (-ray.d).unit(),
        }
    }

    /// Mitsuba 3.9.1's position partials `(dp/du, dp/dv)` at a hit on primitive `prim` of this
    /// shape whose point is `p` (in the shape's space): a mesh solves them from its texture
    /// coordinates ([`Mesh::partials`]); a sphere's are `2 pi r` along increasing longitude
    /// and `pi r` along the polar angle; a disk's are the unit radial direction and `2 pi r`
    /// along the angle, carried by its transform; a cylinder's are `2 pi r` around the axis and
    /// the axis times the length. Only what reads them asks (`bumpmap`, the `aov` outputs),
    /// so [`Shape::interaction`] does not compute them.
    pub fn partials(&self, hit: &Hit, prim: &Prim, p: Vec3, disks: &[Disk]) -> (Vec3, Vec3) {
        match (&self.kind, prim) {
            (ShapeKind::Mesh(m), Prim::Triangle { face, .. }) => m.partials(*face as usize),
            (ShapeKind::Sphere(s), _) => {
                let n = ((p - s.center) / s.radius).unit_or(Vec3::Z);
                let r = s.radius;
                let dp_du = Vec3::new(-n.y, n.x, 0.0) * (2.0 * core::f32::consts::PI * r);
                let rd = sqrt(n.x * n.x + n.y * n.y);
                let dp_dv = if rd == 0.0 {
                    Vec3::X
                } else {
                    Vec3::new(n.z * n.x / rd, n.z * n.y / rd, -rd)
                };
                (dp_du, dp_dv * (core::f32::consts::PI * r))
            }
            (ShapeKind::Disk(d), _) => {
                let disk = &disks[*d as usize];
                let r = hit.uv.norm();
                let inv_r = if r > 0.0 { 1.0 / r } else { 0.0 };
                let (c, s) = (hit.uv.x * inv_r, hit.uv.y * inv_r);
                let dp_du = disk.to_world.vector(Vec3::new(c, s, 0.0));
                let dp_dv =
                    disk.to_world.vector(Vec3::new(-s, c, 0.0)) * (2.0 * core::f32::consts::PI * r);
                (dp_du, dp_dv)
            }
            (ShapeKind::Cylinder(c), _) => {
                let (_, _, l) = c.project(p);
                let (_, dp_du) = c.uv_dpdu(l);
                (dp_du, (c.axes[2] * c.length).as_vec3())
            }
            (ShapeKind::Curve(c), Prim::Curve { segment, .. }) => {
                let s = c.surface(*segment as usize, hit.uv.x, p).2;
                (s.dp_du, s.dp_dv)
            }
            _ => (Vec3::ZERO, Vec3::ZERO),
        }
    }

    /// A point uniformly distributed by area (density `1 / area`); its texture coordinates only
    /// with `uv` (zero without).
    #[inline]
    pub(crate) fn sample_position(
        &self,
        u: Vec2,
        disks: &[Disk],
        uv: bool,
    ) -> Option<PositionSample> {
        let (p, p_err, ng, ns, uv) = match &self.kind {
            ShapeKind::Mesh(m) => {
                if let Some(pg) = m.parallelogram() {
                    let q = pg.point(u);
                    (
                        q.p,
                        q.p_err,
                        q.ng,
                        q.ns,
                        uv_if(uv, || m.uv_at(q.triangle, q.b1, q.b2)),
                    )
                } else {
                    let (i, b1, b2) = m.sample(u)?;
                    let (p, err, ng, ns) = m.point(i, b1, b2);
                    (p, err, ng, ns, uv_if(uv, || m.uv_at(i, b1, b2)))
                }
            }
            ShapeKind::Sphere(s) => {
                let d = crate::sampling::warp::square_to_uniform_sphere(u);
                let (p, err) = s.project(s.center + d * s.radius);
                (p, err, d, d, uv_if(uv, || sphere_uv(d)))
            }
            ShapeKind::Disk(d) => {
                let disk = &disks[*d as usize];
                let local = crate::sampling::warp::square_to_uniform_disk_concentric(u);
                let (p, err) = disk.point(local);
                (
                    p,
                    err,
                    disk.normal,
                    disk.normal,
                    uv_if(uv, || disk_uv(local)),
                )
            }
            ShapeKind::Cylinder(c) => {
                let (p, err, n) = c.sample(u);
                (p, err, n, n, uv_if(uv, || c.sample_uv(u)))
            }
            ShapeKind::Curve(_) => return None,
        };
        Some(PositionSample {
            p,
            p_err,
            uv,
            ng: self.orient(ng),
            ns: self.orient(ns),
        })
    }

    /// A point on the shape sampled for the reference point `r`, with its solid-angle density
    /// at `r`: cone sampling for spheres seen from outside, area sampling otherwise.
    pub fn sample_from(&self, r: Vec3, u: Vec2, disks: &[Disk]) -> Option<(PositionSample, f32)> {
        self.sample_toward(r, u, disks, true).map(|s| (s.ps, s.pdf))
    }

    /// [`Shape::sample_from`] with the offset from `r` to the point and its length, which the
    /// density needs anyway and light sampling needs next; the point's texture coordinates
    /// only with `uv` (zero without: on a sphere they are an `atan2` and an `acos`, half the
    /// cost of a light's sample where the light is not textured).
    #[inline]
    pub fn sample_toward(
        &self,
        r: Vec3,
        u: Vec2,
        disks: &[Disk],
        uv: bool,
    ) -> Option<SampleToward> {
        if let ShapeKind::Sphere(s) = &self.kind {
            if let Some(cs) = s.sample_cone(r, u) {
                // `cs.p` is already projected onto the sphere, with its error bound.
                let (p, p_err) = (cs.p, cs.p_err);
                let n = self.orient(cs.n);
                let d = p - r;
                return Some(SampleToward {
                    ps: PositionSample {
                        p,
                        p_err,
                        ng: n,
                        ns: n,
                        uv: uv_if(uv, || sphere_uv(cs.n)),
                    },
                    pdf: cs.pdf,
                    d,
                    dist: d.norm(),
                });
            }
        }
        let ps = self.sample_position(u, disks, uv)?;
        // area_to_solid_angle, keeping the distance.
        let d = ps.p - r;
        let dist2 = d.length_squared();
        let dist = sqrt(dist2);
        let cos = ps.ng.dot(d).abs() / dist;
        let pdf = if cos > 0.0 && dist2 > 0.0 {
            self.inv_area(disks) * dist2 / cos
        } else {
            0.0
        };
        (pdf > 0.0 && pdf.is_finite()).then_some(SampleToward { ps, pdf, d, dist })
    }

    /// `1 / area` (stored for meshes).
    #[inline]
    fn inv_area(&self, disks: &[Disk]) -> f32 {
        match &self.kind {
            ShapeKind::Mesh(m) => m.inv_area(),
            _ => 1.0 / self.area(disks),
        }
    }

    /// The solid-angle density with which [`Shape::sample_from`] picks point `p` (geometric
    /// normal `ng`) when sampling from `r`.
    pub fn pdf_from(&self, r: Vec3, p: Vec3, ng: Vec3, disks: &[Disk]) -> f32 {
        if let ShapeKind::Sphere(s) = &self.kind {
            if let Some(pdf) = s.cone_pdf(r) {
                return pdf;
            }
        }
        area_to_solid_angle(r, p, ng, self.inv_area(disks))
    }
}

/// Converts an area density at `p` (normal `n`) to a solid-angle density seen from `r`.
#[inline]
pub(crate) fn area_to_solid_angle(r: Vec3, p: Vec3, n: Vec3, pdf_area: f32) -> f32 {
    let d = p - r;
    let dist2 = d.length_squared();
    let cos = n.dot(d).abs() / sqrt(dist2);
    if cos > 0.0 && dist2 > 0.0 {
        pdf_area * dist2 / cos
    } else {
        0.0
    }
}

/// The texture coordinates `f` finds when they are `asked` for, else zero (what callers that
/// read none get, without the cost).
#[inline(always)]
fn uv_if(asked: bool, f: impl FnOnce() -> Vec2) -> Vec2 {
    if asked {
        f()
    } else {
        Vec2::ZERO
    }
}

/// Texture coordinates of a sphere at unit outward normal `n` (before `flip_normals`):
/// longitude over `2 pi` in `[0, 1)`, polar angle over `pi`, as Mitsuba 3's sphere.
#[inline]
fn sphere_uv(n: Vec3) -> Vec2 {
    Vec2::new(
        atan2_turns(n.y, n.x),
        acos(n.z.clamp(-1.0, 1.0)) * crate::math::INV_PI,
    )
}

/// Texture coordinates of a disk at local point `local` of the unit disk: the radius, then the
/// angle over `2 pi` in `[0, 1)`, as Mitsuba 3's disk.
#[inline]
fn disk_uv(local: Vec2) -> Vec2 {
    Vec2::new(local.norm(), atan2_turns(local.y, local.x))
}

#[inline]
fn hit_shape(prim: &Prim) -> u32 {
    prim.shape()
}

#[cold]
fn unreachable_shape() -> ! {
    // The scene builder pairs primitives with their shapes; a mismatch is a construction bug.
    panic!("primitive does not belong to its shape kind")
}

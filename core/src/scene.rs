//! The flat, read-only scene: shapes, primitives under a BVH, BSDFs, emitters, camera.
use crate::accel::Bvh;
use crate::bsdf::Bsdf;
use crate::camera::{Filter, Perspective};
use crate::emitter::{Emitter, EmitterCtx};
use crate::geometry::{Disk, Hit, Interaction, Prim, Shape, ShapeKind};
use crate::math::{Aabb, Ray};
use alloc::vec::Vec;

/// What a scene contains, computed once; integrators consult it to skip work a scene does not
/// need (no shadow rays without emitters, no environment lookups without an environment...).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneFeatures {
    /// Any emitter at all.
    pub has_emitters: bool,
    /// An environment emitter exists.
    pub has_environment: bool,
    /// Any emitter that rays can hit (area or environment).
    pub has_hittable_emitters: bool,
    /// Any delta (point) emitter.
    pub has_delta_emitters: bool,
    /// Any triangle primitives.
    pub has_triangles: bool,
    /// Any sphere primitives.
    pub has_spheres: bool,
    /// Any disk primitives.
    pub has_disks: bool,
}

/// Everything needed to build a [`Scene`].
#[derive(Clone, Debug)]
pub struct SceneParts {
    /// Shapes (their `bsdf` / `emitter` indices refer to the arrays below).
    pub shapes: Vec<Shape>,
    /// Disk geometry referred to by `ShapeKind::Disk`.
    pub disks: Vec<Disk>,
    /// Materials.
    pub bsdfs: Vec<Bsdf>,
    /// Lights.
    pub emitters: Vec<Emitter>,
    /// The camera.
    pub camera: Perspective,
    /// The pixel filter.
    pub filter: Filter,
}

/// A scene ready to render: built once, then only read (it is `Sync`).
#[derive(Clone, Debug)]
pub struct Scene {
    /// Shapes.
    pub shapes: Vec<Shape>,
    /// Disks.
    pub disks: Vec<Disk>,
    /// Primitives in BVH order.
    pub prims: Vec<Prim>,
    /// The hierarchy over `prims`.
    pub bvh: Bvh,
    /// Materials.
    pub bsdfs: Vec<Bsdf>,
    /// Lights.
    pub emitters: Vec<Emitter>,
    /// Index of the environment emitter, if any (at most one).
    pub environment: Option<u32>,
    /// The camera.
    pub camera: Perspective,
    /// The pixel filter.
    pub filter: Filter,
    /// What the scene contains.
    pub features: SceneFeatures,
}

/// Why a scene could not be built (the driver checks inputs first; this guards embedders).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuildError {
    /// A shape refers to a BSDF, emitter or disk that does not exist, or an area emitter to a
    /// shape that does not carry it.
    BadIndex,
    /// A mesh index is out of range.
    BadMeshIndex,
    /// More than one environment emitter.
    TwoEnvironments,
    /// Too many primitives for 32-bit ids.
    TooLarge,
}

impl Scene {
    /// Validates the parts, builds primitives and the BVH, and computes the features.
    pub fn new(p: SceneParts) -> Result<Scene, BuildError> {
        let mut prims = Vec::new();
        for (si, s) in p.shapes.iter().enumerate() {
            if s.bsdf as usize >= p.bsdfs.len()
                || s.emitter.is_some_and(|e| e as usize >= p.emitters.len())
            {
                return Err(BuildError::BadIndex);
            }
            let shape = u32::try_from(si).map_err(|_| BuildError::TooLarge)?;
            match &s.kind {
                ShapeKind::Mesh(m) => {
                    let n = m.positions.len();
                    for (f, idx) in m.indices.iter().enumerate() {
                        if idx.iter().any(|&i| i as usize >= n) {
                            return Err(BuildError::BadMeshIndex);
                        }
                        let face = u32::try_from(f).map_err(|_| BuildError::TooLarge)?;
                        prims.push(Prim::Triangle {
                            v: m.vertices(f),
                            shape,
                            face,
                        });
                    }
                }
                ShapeKind::Sphere(sp) => prims.push(Prim::Sphere { sphere: *sp, shape }),
                ShapeKind::Disk(d) => {
                    if *d as usize >= p.disks.len() {
                        return Err(BuildError::BadIndex);
                    }
                    prims.push(Prim::Disk { disk: *d, shape })
                }
            }
        }
        if prims.len() >= u32::MAX as usize {
            return Err(BuildError::TooLarge);
        }
        let mut environment = None;
        for (i, e) in p.emitters.iter().enumerate() {
            match e {
                Emitter::Area(a) => {
                    if p.shapes.get(a.shape as usize).and_then(|s| s.emitter) != Some(i as u32) {
                        return Err(BuildError::BadIndex);
                    }
                }
                e if e.is_environment() => {
                    if environment.replace(i as u32).is_some() {
                        return Err(BuildError::TwoEnvironments);
                    }
                }
                _ => {}
            }
        }
        let bounds: Vec<Aabb> = prims.iter().map(|pr| pr.bounds(&p.disks)).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let prims: Vec<Prim> = order.iter().map(|&i| prims[i as usize]).collect();
        let features = SceneFeatures {
            has_emitters: !p.emitters.is_empty(),
            has_environment: environment.is_some(),
            has_hittable_emitters: p.emitters.iter().any(|e| !e.is_delta()),
            has_delta_emitters: p.emitters.iter().any(|e| e.is_delta()),
            has_triangles: prims.iter().any(|pr| matches!(pr, Prim::Triangle { .. })),
            has_spheres: prims.iter().any(|pr| matches!(pr, Prim::Sphere { .. })),
            has_disks: prims.iter().any(|pr| matches!(pr, Prim::Disk { .. })),
        };
        Ok(Scene {
            shapes: p.shapes,
            disks: p.disks,
            prims,
            bvh,
            bsdfs: p.bsdfs,
            emitters: p.emitters,
            environment,
            camera: p.camera,
            filter: p.filter,
            features,
        })
    }

    /// Bounds of all geometry.
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// The context emitters sample in.
    #[inline]
    pub fn emitter_ctx(&self) -> EmitterCtx<'_> {
        EmitterCtx {
            shapes: &self.shapes,
            disks: &self.disks,
        }
    }

    /// The closest hit along the ray, if any.
    pub fn intersect_hit(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        self.bvh.traverse(ray, |first, count, mut t_max| {
            for i in first..first + count {
                if let Some((t, uv)) = self.prims[i].intersect(ray, t_max, &self.disks) {
                    t_max = t;
                    best = Some(Hit {
                        t,
                        prim: i as u32,
                        uv,
                    });
                }
            }
            Some(t_max)
        });
        best
    }

    /// The closest surface interaction along the ray, if any.
    pub fn intersect(&self, ray: &Ray) -> Option<Interaction> {
        let hit = self.intersect_hit(ray)?;
        let prim = &self.prims[hit.prim as usize];
        let shape = &self.shapes[prim.shape() as usize];
        Some(shape.interaction(&hit, prim, ray, &self.disks))
    }

    /// Whether anything blocks the ray within its extent (any hit, early exit).
    pub fn occluded(&self, ray: &Ray) -> bool {
        let mut hit = false;
        self.bvh.traverse(ray, |first, count, t_max| {
            for i in first..first + count {
                if self.prims[i].intersect(ray, t_max, &self.disks).is_some() {
                    hit = true;
                    return None;
                }
            }
            Some(t_max)
        });
        hit
    }
}

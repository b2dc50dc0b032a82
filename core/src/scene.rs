//! The flat, read-only scene: shapes, primitives under a BVH, BSDFs, emitters, camera.
use crate::accel::level::{Level, LevelError, LevelPrims, NOT_A_TRIANGLE};
use crate::accel::{BuildParams, Bvh8, Fork, InTurn, TriBlocks};
use crate::bsdf::{Bsdf, BsdfTraits};
use crate::camera::{Camera, Filter};
use crate::emitter::{Emitter, EmitterCtx};
use crate::geometry::{Disk, Instance, Prim, Shape, ShapeKind};
use crate::light::{Behind, LightBound, LightSampler, LightSelection};
use crate::math::{Aabb, Norm};
use crate::medium::SceneMedia;
use crate::splat::Footprint;
use alloc::vec::Vec;
use glam::Vec3;

mod casts;
mod detail;
mod environment_sampling;
mod numbering;
mod queries;
mod shading_point;
mod surface_detail;
pub use numbering::{ShapeNumber, ShapeNumbering};
pub use surface_detail::SurfaceDetail;

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
    /// Any `null` BSDF (a surface `volpath` steps through without a bounce).
    pub has_null_bsdfs: bool,
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
    pub camera: Camera,
    /// The pixel filter.
    pub filter: Filter,
    /// How emitter sampling picks a light.
    pub light_selection: LightSelection,
    /// Shape groups: each the indices of its shapes (in object space, without emitters; they
    /// are drawn only through instances).
    pub groups: Vec<Vec<u32>>,
    /// Placed copies of the groups.
    pub instances: Vec<Instance>,
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
    /// Triangle corners in blocks of four, each leaf's primitives in consecutive blocks (the
    /// leaf loop's data; NaN corners for a primitive that is not a triangle, which sends the
    /// loop to `prims`).
    pub blocks: TriBlocks,
    /// The 8-wide hierarchy over `prims`; its leaves refer to their first block in `blocks`.
    pub bvh: Bvh8,
    /// Each shape group's own hierarchy (the bottom level), built once however many instances
    /// it has.
    pub groups: Vec<Level>,
    /// Instances of the groups (the top level's `Prim::Instance` refer to them).
    pub instances: Vec<Instance>,
    /// Materials.
    pub bsdfs: Vec<Bsdf>,
    /// What each BSDF's sampling reads and whether it has smooth components, by BSDF index
    /// (computed when the scene is built, as `features` is).
    bsdf_traits: Vec<BsdfTraits>,
    /// By shape: whether its hits compute texture coordinates (false only for a sphere whose
    /// BSDF and emitter read none, where the angles cost a tenth of the hit).
    uv_read: Vec<bool>,
    /// Lights.
    pub emitters: Vec<Emitter>,
    /// Indices of the emitters at infinity (seen by rays that escape the scene).
    pub environments: Vec<u32>,
    /// How emitter sampling picks a light (built from `emitters`).
    lights: LightSampler,
    /// The camera.
    pub camera: Camera,
    /// The pixel filter.
    pub filter: Filter,
    /// How samples reach pixels: splatted over this footprint (the default for every filter
    /// but `box`, see `splat.rs`), or, when `None`, each counting in its own pixel only (`box`,
    /// and filter importance sampling, which the driver selects by setting it to `None`).
    pub splat: Option<Footprint>,
    /// The sampler pixels are rendered with (default independent; the driver sets it).
    pub sampler: crate::sampling::SamplerKind,
    /// What the scene contains.
    pub features: SceneFeatures,
    /// Mitsuba 3's numbering of the shapes (the `aov` integrator's indices; the loader sets it).
    pub shape_numbering: ShapeNumbering,
    /// Centre of the scene's bounding sphere.
    pub scene_center: glam::Vec3,
    /// Radius of the scene's bounding sphere (lights at infinity aim at it).
    pub scene_radius: f32,
    /// Participating media and the surfaces that bound them (empty unless set with
    /// [`Scene::set_media`]; only `volpath` reads them).
    pub media: SceneMedia,
}

/// Why a scene could not be built (the driver checks inputs first; this guards embedders).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuildError {
    /// A shape refers to a BSDF, emitter or disk that does not exist, or an area emitter to a
    /// shape that does not carry it.
    BadIndex,
    /// A mesh index is out of range.
    BadMeshIndex,
    /// Too many primitives for 32-bit ids.
    TooLarge,
}

impl Scene {
    /// Validates the parts, builds primitives and the BVH, and computes the features.
    pub fn new(p: SceneParts) -> Result<Scene, BuildError> {
        Scene::with_build_params(p, Bvh8::PARAMS)
    }

    /// [`Scene::new`] with a chosen BVH leaf-size trade-off (for measuring it).
    pub fn with_build_params(p: SceneParts, params: BuildParams) -> Result<Scene, BuildError> {
        Scene::build(p, params, &InTurn)
    }

    /// [`Scene::new`], the BVH builds' large halves run through `fork` (a `std` caller's
    /// threads): the same scene whatever the fork does.
    pub fn new_forked(p: SceneParts, fork: &dyn Fork) -> Result<Scene, BuildError> {
        Scene::build(p, Bvh8::PARAMS, fork)
    }

    /// [`Scene::new`] with both choices.
    fn build(mut p: SceneParts, params: BuildParams, fork: &dyn Fork) -> Result<Scene, BuildError> {
        let mut grouped = alloc::vec![false; p.shapes.len()];
        for g in &p.groups {
            for &si in g {
                let s = p.shapes.get(si as usize).ok_or(BuildError::BadIndex)?;
                // Instanced geometry carries no light (Mitsuba 3 refuses it as well).
                if s.emitter.is_some() || grouped[si as usize] {
                    return Err(BuildError::BadIndex);
                }
                grouped[si as usize] = true;
            }
        }
        for s in &p.shapes {
            if s.bsdf as usize >= p.bsdfs.len()
                || s.emitter.is_some_and(|e| e as usize >= p.emitters.len())
            {
                return Err(BuildError::BadIndex);
            }
        }
        let top = (0..p.shapes.len()).filter(|&si| !grouped[si]);
        let mut top = LevelPrims::of_shapes(&p.shapes, top, &p.disks)?;
        let mut groups = Vec::with_capacity(p.groups.len());
        for g in &p.groups {
            let which = g.iter().map(|&si| si as usize);
            let lp = LevelPrims::of_shapes(&p.shapes, which, &p.disks)?;
            let bounds: Vec<Aabb> = lp
                .prims
                .iter()
                .zip(&lp.tris)
                .map(|(pr, v)| pr.bounds(v, &p.disks, &p.shapes))
                .collect();
            groups.push(Level::build(lp, &bounds, params, fork));
        }
        let mut instance_bounds = Vec::new();
        top.prims.reserve_exact(p.instances.len());
        top.tris.reserve_exact(p.instances.len());
        for (ii, inst) in p.instances.iter().enumerate() {
            let g = groups
                .get(inst.group as usize)
                .ok_or(BuildError::BadIndex)?;
            let b = inst.bounds(g.bvh.bounds());
            if g.prims.is_empty() || b.is_empty() {
                // An empty group: nothing to hit.
                continue;
            }
            let instance = u32::try_from(ii).map_err(|_| BuildError::TooLarge)?;
            top.prims.push(Prim::Instance { instance });
            top.tris.push(NOT_A_TRIANGLE);
            instance_bounds.push(b);
        }
        let (prims, tris) = (&top.prims, &top.tris);
        if prims.len() >= u32::MAX as usize {
            return Err(BuildError::TooLarge);
        }
        let mut environments = Vec::new();
        for (i, e) in p.emitters.iter_mut().enumerate() {
            if let Emitter::Area(a) = e {
                let shape = p.shapes.get(a.shape as usize);
                if shape.and_then(|s| s.emitter) != Some(i as u32) {
                    return Err(BuildError::BadIndex);
                }
                a.behind = shape.and_then(Behind::of);
            }
            if e.is_environment() {
                environments.push(i as u32);
            }
        }
        let mut instance_bounds = instance_bounds.into_iter();
        let bounds: Vec<Aabb> = prims
            .iter()
            .zip(tris)
            .map(|(pr, v)| match pr {
                Prim::Instance { .. } => instance_bounds.next().unwrap_or(Aabb::EMPTY),
                _ => pr.bounds(v, &p.disks, &p.shapes),
            })
            .collect();
        let Level { prims, blocks, bvh } = Level::build(top, &bounds, params, fork);
        let world = bvh.bounds();
        let (center, radius) = if world.is_empty() {
            (glam::Vec3::ZERO, 1.0)
        } else {
            (
                world.centroid(),
                (world.extent().norm() * 0.5).max(f32::MIN_POSITIVE),
            )
        };
        let ctx = EmitterCtx {
            shapes: &p.shapes,
            disks: &p.disks,
            scene_center: center,
            scene_radius: radius,
        };
        let lights = LightSampler::new(p.light_selection, &p.emitters, &ctx);
        let features = SceneFeatures {
            has_emitters: !p.emitters.is_empty(),
            has_environment: !environments.is_empty(),
            has_hittable_emitters: p.emitters.iter().any(|e| !e.is_delta()),
            has_delta_emitters: p.emitters.iter().any(|e| e.is_delta()),
            has_triangles: prims.iter().any(|pr| matches!(pr, Prim::Triangle { .. })),
            has_spheres: prims.iter().any(|pr| matches!(pr, Prim::Sphere { .. })),
            has_disks: prims.iter().any(|pr| matches!(pr, Prim::Disk { .. })),
            has_null_bsdfs: p.bsdfs.iter().any(|b| matches!(b, Bsdf::Null(_))),
        };
        let bsdf_traits: Vec<BsdfTraits> = p.bsdfs.iter().map(BsdfTraits::of).collect();
        let uv_read = p
            .shapes
            .iter()
            .map(|s| shape_reads_uv(s, &bsdf_traits, &p.emitters))
            .collect();
        Ok(Scene {
            shapes: p.shapes,
            disks: p.disks,
            prims,
            blocks,
            bvh,
            groups,
            instances: p.instances,
            bsdfs: p.bsdfs,
            bsdf_traits,
            uv_read,
            emitters: p.emitters,
            environments,
            lights,
            scene_center: center,
            scene_radius: radius,
            camera: p.camera,
            splat: Footprint::of(&p.filter),
            filter: p.filter,
            sampler: crate::sampling::SamplerKind::Independent,
            features,
            shape_numbering: ShapeNumbering::default(),
            media: SceneMedia::default(),
        })
    }

    /// Gives the scene its media; `BadIndex` when a shape or the camera names a medium that
    /// does not exist, or there are interfaces for more shapes than the scene has.
    pub fn set_media(&mut self, media: SceneMedia) -> Result<(), BuildError> {
        let n = media.media.len() as u32;
        let ok = |m: Option<u32>| m.is_none_or(|i| i < n);
        if media.interfaces.len() > self.shapes.len()
            || !ok(media.camera)
            || !media
                .interfaces
                .iter()
                .all(|i| ok(i.interior) && ok(i.exterior))
        {
            return Err(BuildError::BadIndex);
        }
        self.media = media;
        Ok(())
    }

    /// Bounds of all geometry.
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// The context emitters sample in.
    #[inline]
    pub(crate) fn emitter_ctx(&self) -> EmitterCtx<'_> {
        EmitterCtx {
            shapes: &self.shapes,
            disks: &self.disks,
            scene_center: self.scene_center,
            scene_radius: self.scene_radius,
        }
    }

    /// Changes how emitter sampling picks a light.
    pub fn set_light_selection(&mut self, how: LightSelection) {
        self.lights = LightSampler::new(how, &self.emitters, &self.emitter_ctx());
    }

    /// How emitter sampling picks a light.
    #[inline]
    pub fn lights(&self) -> &LightSampler {
        &self.lights
    }

    /// [`BsdfTraits::of`] BSDF `i`, as computed when the scene was built.
    #[inline]
    pub fn bsdf_traits(&self, i: u32) -> BsdfTraits {
        self.bsdf_traits[i as usize]
    }

    /// Each light as vertex selection sees it; empty where the scene-wide choice applies.
    #[inline]
    pub fn light_bounds(&self) -> &[LightBound] {
        self.lights.bounds()
    }

    /// Corners of primitive `i` if it is a triangle.
    pub fn triangle(&self, i: usize) -> Option<[Vec3; 3]> {
        match self.prims[i] {
            Prim::Triangle { shape, face } => match &self.shapes[shape as usize].kind {
                ShapeKind::Mesh(m) => Some(m.vertices(face as usize)),
                _ => None,
            },
            _ => None,
        }
    }

    /// Bytes of the ray-casting data (not counting spare vector capacity).
    pub fn accel_memory(&self) -> AccelMemory {
        AccelMemory {
            nodes: self.bvh.memory_bytes(),
            triangles: self.blocks.memory_bytes(),
            prims: core::mem::size_of_val(self.prims.as_slice()),
            instances: core::mem::size_of_val(self.instances.as_slice()),
            groups: self.groups.iter().map(Level::memory_bytes).sum(),
        }
    }
}

/// What [`Scene::accel_memory`] counts, in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccelMemory {
    /// The 8-wide BVH's nodes.
    pub nodes: usize,
    /// The triangle test's data: blocks of four primitives' corners (37 bytes per primitive in
    /// full blocks, more where a leaf's last block is partly empty).
    pub triangles: usize,
    /// Per primitive, which shape and face it is (for shading, and for spheres and disks).
    pub prims: usize,
    /// The instances' records (group and transform pair).
    pub instances: usize,
    /// The shape groups' own hierarchies (nodes, blocks, primitive records).
    pub groups: usize,
}

impl From<LevelError> for BuildError {
    fn from(e: LevelError) -> BuildError {
        match e {
            LevelError::BadIndex => BuildError::BadIndex,
            LevelError::BadMeshIndex => BuildError::BadMeshIndex,
            LevelError::TooLarge => BuildError::TooLarge,
        }
    }
}

/// Whether hits on `shape` should compute texture coordinates (see [`Scene::reads_uv`]), from
/// the traits of the scene's BSDFs and its emitters.
fn shape_reads_uv(shape: &Shape, bsdf_traits: &[BsdfTraits], emitters: &[Emitter]) -> bool {
    let textured_light = shape.emitter.is_some_and(
        |e| matches!(emitters.get(e as usize), Some(Emitter::Area(a)) if a.texture.is_some()),
    );
    !matches!(shape.kind, ShapeKind::Sphere(_))
        || bsdf_traits
            .get(shape.bsdf as usize)
            .is_none_or(|t| t.reads_uv)
        || textured_light
}

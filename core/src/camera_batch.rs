//! A batch of one pixel's camera rays finished together: the rays cast, the paths of those that
//! met a surface taken first vertex first ([`PathIntegrator::li_from_camera_hits`]), and those
//! that escaped to an environment map looked up together ([`Escapes`]).
//!
//! The batch's samples share their pixel, so their first vertices are alike (one shape, one
//! BSDF, the same lights): done one after another, the same code and data serve all of them.
//! Each sample keeps its own sampler and its own sum, so every value is the one the
//! sample-by-sample loop gives, bit for bit, whatever the batch holds.
//!
//! It applies to the `path` integrator without path reuse (whose samples depend on their
//! group), with a probe that observes nothing but the rays cast; the lookups of escaped rays
//! where [`Escapes`] applies, else escaped rays are followed as paths (what the environment
//! gives them, if any). The zsobol sampler's loop, whose samplers borrow the pixel's cache one
//! at a time, takes its samples one by one ([`Escapes::push`]).
use crate::camera_draw::{CameraDraw, CameraSample, CAMERA_BATCH};
use crate::escapes::{escaped_value, Escapes};
use crate::geometry::Interaction;
use crate::integrator::{Integrator, PathIntegrator, Probe, RayKind};
use crate::math::{Norm, Ray};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::{Vec2, Vec3};

/// What finishing a batch of camera rays needs: the path integrator, and the lookups of
/// escaped rays where they apply.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CameraBatch<'a> {
    path: &'a PathIntegrator,
    escapes: Option<Escapes<'a>>,
}

impl<'a> CameraBatch<'a> {
    /// The batch finisher for rendering `scene` with `integrator` and probe type `P`, when it
    /// applies (see the module's header).
    #[inline]
    pub(crate) fn of<P: Probe>(scene: &'a Scene, integrator: &'a Integrator) -> Option<Self> {
        let Integrator::Path(path) = integrator else {
            return None;
        };
        if P::OBSERVES || path.reuses() {
            return None;
        }
        Some(CameraBatch {
            path,
            escapes: Escapes::of::<P>(scene, integrator),
        })
    }

    /// The samples whose camera parts are `draws` (the first [`CAMERA_BATCH`] of them): each
    /// value, offset and camera sample passed to `add` in index order.
    #[inline(always)]
    pub(crate) fn finish<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        draws: impl Iterator<Item = CameraDraw<S>>,
        probe: &mut P,
        add: &mut impl FnMut(Color, Vec2, &CameraSample),
    ) {
        // Per sample: its sampler (kept only by those whose paths are followed), where it
        // lies, its ray and what the ray met; the escaped directions for the lookups.
        let mut samplers: [Option<S>; CAMERA_BATCH] = core::array::from_fn(|_| None);
        let unused = Ray::new(Vec3::ZERO, Vec3::Y);
        let mut rays = [unused; CAMERA_BATCH];
        let mut cams = [(
            Vec2::ZERO,
            CameraSample {
                ray: unused,
                weight: None,
            },
        ); CAMERA_BATCH];
        let mut hits: [Option<Interaction>; CAMERA_BATCH] = [None; CAMERA_BATCH];
        let mut dirs = [Vec3::Y; CAMERA_BATCH];
        let mut looked_up = [false; CAMERA_BATCH];
        let mut n = 0;
        for draw in draws.take(CAMERA_BATCH) {
            let CameraDraw {
                sampler,
                offset,
                cam,
                ..
            } = draw;
            rays[n] = cam.ray;
            hits[n] = scene.intersect(&cam.ray);
            if hits[n].is_none() && self.escapes.is_some() {
                // The path loop reports its camera ray; this one it never sees.
                probe.ray(RayKind::Camera);
                dirs[n] = cam.ray.d.unit();
                looked_up[n] = true;
            } else {
                samplers[n] = Some(sampler);
            }
            cams[n] = (offset, cam);
            n += 1;
        }
        let mut values = [Color::ZERO; CAMERA_BATCH];
        self.path.li_from_camera_hits(
            scene,
            &rays[..n],
            &hits[..n],
            &mut samplers[..n],
            &mut values[..n],
            probe,
        );
        if let Some(esc) = self.escapes.as_ref().filter(|_| looked_up.contains(&true)) {
            let sky = esc.look_up(&dirs);
            for k in (0..n).filter(|&k| looked_up[k]) {
                values[k] = escaped_value(sky[k]);
            }
        }
        for (value, (offset, cam)) in values.iter().zip(&cams[..n]) {
            add(cam.weigh(*value), *offset, cam);
        }
    }
}

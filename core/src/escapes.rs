//! Camera rays that escape to an environment map, finished eight at a time.
//!
//! A sample whose camera ray meets nothing is worth the map's radiance along the ray, and a
//! lookup's coordinates (a rotation, a normalisation, polynomial `atan2` and `acos`) are one
//! long chain of dependent operations: in a mostly-sky image that chain was a sixth of the
//! render. Here the directions of a batch's escaped camera rays are looked up together
//! ([`EnvMap::eval8`], in AVX2 registers where the CPU has them): for the independent sampler's
//! batches through `camera_batch.rs`, for zsobol's samples (which take their samplers
//! one at a time from the pixel's cache) through [`Escapes::push`], which follows a path from
//! the hit already found ([`PathIntegrator::li_from_camera_hit`]) or keeps the direction, and
//! [`Escapes::flush`]. Every value is the one the sample-by-sample loop gives, bit for bit: the
//! lookups compute the scalar code's bits, and each path keeps its own sampler, so the order
//! the work is done in moves nothing.
//!
//! It applies where the shortcut is exactly what the path integrator does with an escaping
//! camera ray: the `path` integrator (any strategy) showing emitters to the camera, at least
//! one segment long, one environment which is a map, and a probe that observes nothing but the
//! rays cast.
use crate::accel::slab_simd::Avx2;
use crate::camera_draw::{CameraDraw, CameraSample, CAMERA_BATCH};
use crate::emitter::{Emitter, EnvMap};
use crate::integrator::{Integrator, PathIntegrator, Probe, RayKind};
use crate::math::Norm;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::{Vec2, Vec3};

/// What finishing a batch of camera rays needs: the path integrator, the scene's one map and
/// the SIMD choice of the scene's traversal.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Escapes<'a> {
    path: &'a PathIntegrator,
    env: &'a EnvMap,
    avx2: Option<Avx2>,
}

impl<'a> Escapes<'a> {
    /// The batch finisher for rendering `scene` with `integrator` and probe type `P`, when it
    /// applies (see the module's
    /// header).
    #[inline]
    pub(crate) fn of<P: Probe>(scene: &'a Scene, integrator: &'a Integrator) -> Option<Self> {
        let Integrator::Path(path) = integrator else {
            return None;
        };
        if P::OBSERVES || path.hide_emitters || path.max_depth == Some(0) {
            return None;
        }
        let [env] = scene.environments[..] else {
            return None;
        };
        let Emitter::EnvMap(env) = &scene.emitters[env as usize] else {
            return None;
        };
        Some(Escapes {
            path,
            env,
            avx2: scene.bvh.avx2(),
        })
    }
}

/// Samples of a run of up to [`CAMERA_BATCH`] consecutive indices on their way through
/// [`Escapes`]: the values of those that met a surface, the directions of those that escaped.
#[derive(Debug)]
pub(crate) struct Pending {
    /// Per sample taken: its value (zero until looked up, for an escaped one), whether it
    /// escaped, its offset and its camera sample.
    taken: [Option<(Color, bool, Vec2, CameraSample)>; CAMERA_BATCH],
    /// The escaped rays' directions as the path loop normalises them; the other lanes hold a
    /// direction whose value is not used.
    dirs: [Vec3; CAMERA_BATCH],
    n: usize,
    escaped: bool,
}

impl Default for Pending {
    fn default() -> Self {
        Pending {
            taken: [None; CAMERA_BATCH],
            dirs: [Vec3::Y; CAMERA_BATCH],
            n: 0,
            escaped: false,
        }
    }
}

impl Pending {
    /// Whether the run holds [`CAMERA_BATCH`] samples (time to [`Escapes::flush`]).
    #[inline]
    pub(crate) fn is_full(&self) -> bool {
        self.n == CAMERA_BATCH
    }
}

impl Escapes<'_> {
    /// Takes the sample whose camera part is `draw` (the next index of the run in `pending`,
    /// which must not be full): casts its ray, and follows its path from the hit, or keeps the
    /// direction it escaped along for [`Escapes::flush`].
    #[inline(always)]
    pub(crate) fn push<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        pending: &mut Pending,
        draw: CameraDraw<S>,
        probe: &mut P,
    ) {
        let CameraDraw {
            mut sampler,
            offset,
            cam,
            ..
        } = draw;
        let k = pending.n;
        pending.n += 1;
        pending.taken[k] = Some(match scene.intersect(&cam.ray) {
            Some(si) => {
                let l = self
                    .path
                    .li_from_camera_hit(scene, cam.ray, Some(si), &mut sampler, probe);
                (cam.weigh(l), false, offset, cam)
            }
            None => {
                // The path loop reports its camera ray; this one it never sees.
                probe.ray(RayKind::Camera);
                pending.dirs[k] = cam.ray.d.unit();
                pending.escaped = true;
                (Color::ZERO, true, offset, cam)
            }
        });
    }

    /// Looks up the escaped samples of `pending` together and passes every sample's value,
    /// offset and camera sample to `add` in index order, as the sample-by-sample loop gives them
    /// (the same bits); `pending` is then empty.
    #[inline(always)]
    pub(crate) fn flush(
        &self,
        pending: &mut Pending,
        add: &mut impl FnMut(Color, Vec2, &CameraSample),
    ) {
        let sky = if pending.escaped {
            self.look_up(&pending.dirs)
        } else {
            [Color::ZERO; CAMERA_BATCH]
        };
        for (taken, le) in pending.taken[..pending.n].iter_mut().zip(sky) {
            let Some((value, escaped, offset, cam)) = taken.take() else {
                continue;
            };
            let value = if escaped {
                cam.weigh(escaped_value(le))
            } else {
                value
            };
            add(value, offset, &cam);
        }
        pending.n = 0;
        pending.escaped = false;
    }

    /// The map's radiance along each of `dirs` (normalised as the path loop normalises a camera
    /// ray's direction), eight lookups together.
    #[inline(always)]
    pub(crate) fn look_up(&self, dirs: &[Vec3; CAMERA_BATCH]) -> [Color; CAMERA_BATCH] {
        self.env.eval8(self.avx2, dirs)
    }
}

/// The path loop's sum for a camera ray that escaped to radiance `le`: nothing, plus the
/// throughput (one) times the radiance times the weight (one) where the radiance is not zero.
#[inline(always)]
pub(crate) fn escaped_value(le: Color) -> Color {
    let mut l = Color::ZERO;
    if le != Color::ZERO {
        l += Color::ONE * le * 1.0;
    }
    l
}

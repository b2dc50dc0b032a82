//! Emitters: a closed enum, one variant per file: what each kind of light emits and how it is
//! sampled from a point. Choosing among the lights is the `light` module's.
mod area;
mod constant;
mod directional;
mod distant_disk;
mod envmap;
mod envmap_coords;
mod envmap_tables;
mod point;
mod projector;
mod sample;
mod spot;

pub use area::AreaLight;
pub use constant::ConstantEnv;
pub use directional::DirectionalLight;
pub use distant_disk::DistantDisk;
pub use envmap::EnvMap;
pub use point::PointLight;
pub use projector::Projector;
pub use sample::{luminance, EmitterCtx, EmitterSample};
pub use spot::SpotLight;

use crate::geometry::Interaction;
use crate::Color;
use glam::{Vec2, Vec3};

/// Light sources.
#[derive(Clone, Debug)]
pub enum Emitter {
    /// Emission from a shape's surface.
    Area(AreaLight),
    /// Uniform radiance from every direction at infinity.
    Constant(ConstantEnv),
    /// An isotropic point light.
    Point(PointLight),
    /// A point light with an angular falloff around its axis.
    Spot(SpotLight),
    /// A point light projecting an image through a frustum.
    Projector(Projector),
    /// Parallel light from one direction at infinity.
    Directional(DirectionalLight),
    /// A disk of uniform radiance at infinity (a sun).
    DistantDisk(DistantDisk),
    /// Radiance at infinity from a latitude-longitude image.
    EnvMap(EnvMap),
}

impl Emitter {
    /// Samples light arriving at `it` (direct illumination).
    #[inline]
    pub fn sample(&self, ctx: &EmitterCtx, it: &Interaction, u: Vec2) -> Option<EmitterSample> {
        match self {
            Emitter::Area(e) => e.sample(ctx, it, u),
            Emitter::Constant(e) => e.sample(it, u),
            Emitter::Point(e) => e.sample(it),
            Emitter::Spot(e) => e.sample(it),
            Emitter::Projector(e) => e.sample(it),
            Emitter::Directional(e) => e.sample(it),
            Emitter::DistantDisk(e) => e.sample(it, u),
            Emitter::EnvMap(e) => e.sample(it, u),
        }
    }
    /// Emitted power (luminance, watts up to a constant), for choosing lights by power.
    pub fn power(&self, ctx: &EmitterCtx) -> f32 {
        use crate::math::PI;
        let p = match self {
            Emitter::Area(e) => {
                PI * ctx.shapes[e.shape as usize].area(ctx.disks) * luminance(e.radiance)
            }
            Emitter::Constant(e) => {
                4.0 * PI * PI * ctx.scene_radius * ctx.scene_radius * luminance(e.radiance)
            }
            Emitter::Point(e) => 4.0 * PI * luminance(e.intensity),
            Emitter::Spot(e) => e.solid_angle() * e.luminance(),
            Emitter::Projector(e) => e.power(),
            Emitter::Directional(e) => {
                PI * ctx.scene_radius * ctx.scene_radius * luminance(e.irradiance)
            }
            Emitter::DistantDisk(e) => {
                PI * ctx.scene_radius * ctx.scene_radius * e.solid_angle() * luminance(e.radiance)
            }
            // What its tables sample: with MIS-compensated tables, BSDF sampling finds the rest.
            Emitter::EnvMap(e) => {
                PI * ctx.scene_radius * ctx.scene_radius * e.sampled_luminance_integral()
            }
        };
        if p.is_finite() && p > 0.0 {
            p
        } else {
            0.0
        }
    }
    /// Whether the emitter is at infinity (seen by rays that escape the scene).
    pub(crate) fn is_environment(&self) -> bool {
        matches!(
            self,
            Emitter::Constant(_) | Emitter::DistantDisk(_) | Emitter::EnvMap(_)
        )
    }
    /// Whether it is a delta light (in position or direction), which no ray can hit.
    pub(crate) fn is_delta(&self) -> bool {
        matches!(
            self,
            Emitter::Point(_) | Emitter::Spot(_) | Emitter::Projector(_) | Emitter::Directional(_)
        )
    }
    /// Radiance of an environment emitter along an escaping ray direction `d`.
    pub fn eval_environment(&self, d: Vec3) -> Color {
        match self {
            Emitter::Constant(e) => e.radiance,
            Emitter::DistantDisk(e) => e.eval(d),
            Emitter::EnvMap(e) => e.eval(d),
            _ => Color::ZERO,
        }
    }
    /// [`Emitter::eval_environment`] and [`Emitter::pdf_environment`] together (an
    /// environment map finds the direction's pixels once for both).
    #[inline]
    pub fn eval_pdf_environment(&self, r: Vec3, d: Vec3) -> (Color, f32) {
        match self {
            Emitter::EnvMap(e) => e.eval_pdf(d),
            _ => (self.eval_environment(d), self.pdf_environment(r, d)),
        }
    }
    /// Density with which `sample` from `r` picks the direction `d` toward an environment.
    pub fn pdf_environment(&self, _r: Vec3, d: Vec3) -> f32 {
        match self {
            Emitter::Constant(e) => e.pdf(),
            Emitter::DistantDisk(e) => e.pdf(d),
            Emitter::EnvMap(e) => e.pdf(d),
            _ => 0.0,
        }
    }
}

//! BSDFs: a closed enum, one variant per file, evaluated in the local shading frame.
//!
//! Conventions: `wi` points from the surface toward the previous path vertex (the viewer), `wo`
//! toward the next one (the light); both are unit vectors in the shading frame (normal = +z).
//! `eval` includes the cosine factor `|cos theta_o|`.
mod diffuse;
mod twosided;

pub use diffuse::Diffuse;
pub use twosided::TwoSided;

use crate::Color;
use glam::{Vec2, Vec3};

/// A sampled direction with its Monte Carlo weight.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Sampled direction (local).
    pub wo: Vec3,
    /// `eval(wi, wo) / pdf`: the throughput factor.
    pub weight: Color,
    /// Solid-angle density (for a delta component: its discrete probability).
    pub pdf: f32,
    /// Whether a delta (specular) component was sampled.
    pub delta: bool,
}

/// Surface scattering models.
#[derive(Clone, Debug)]
pub enum Bsdf {
    /// Lambertian reflection.
    Diffuse(Diffuse),
    /// A front and back model on one surface.
    TwoSided(TwoSided),
}

impl Bsdf {
    /// `f(wi, wo) |cos theta_o|`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, uv: Vec2) -> Color {
        match self {
            Bsdf::Diffuse(b) => b.eval(wi, wo, uv),
            Bsdf::TwoSided(b) => b.eval(wi, wo, uv),
        }
    }
    /// Solid-angle density with which `sample` produces `wo` (smooth components only).
    pub fn pdf(&self, wi: Vec3, wo: Vec3, uv: Vec2) -> f32 {
        match self {
            Bsdf::Diffuse(b) => b.pdf(wi, wo, uv),
            Bsdf::TwoSided(b) => b.pdf(wi, wo, uv),
        }
    }
    /// Samples `wo` for `wi` from two uniform numbers (one for choosing a component).
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, uv: Vec2) -> Option<BsdfSample> {
        match self {
            Bsdf::Diffuse(b) => b.sample(wi, u1, u2, uv),
            Bsdf::TwoSided(b) => b.sample(wi, u1, u2, uv),
        }
    }
    /// Whether any component is smooth (non-delta): emitter sampling is useful.
    pub fn has_smooth(&self) -> bool {
        match self {
            Bsdf::Diffuse(_) => true,
            Bsdf::TwoSided(b) => b.front.has_smooth() || b.back.has_smooth(),
        }
    }
}

//! What a BSDF that wraps other BSDFs (`twosided`, `blendbsdf`, `mask`, `normalmap`, the
//! Chalmers coating) asks of the models it wraps, as a trait: each wrapper is written over any
//! model type, so its file need not know the `Bsdf` enum that holds it (the enum implements the
//! trait by dispatching on its variants, and the wrappers are instantiated with it).
use super::diffuse::Diffuse;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::Color;
use glam::{Vec2, Vec3};

/// A scattering model in the local shading frame (the conventions of the `bsdf` module).
pub trait Model {
    /// `f(wi, wo) |cos theta_o|` of the smooth components.
    fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color;
    /// Solid-angle density with which `sample` produces `wo` (smooth components only).
    fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32;
    /// Samples `wo` for `wi` from three uniform numbers.
    fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample>;
    /// Whether any component is smooth.
    fn has_smooth(&self) -> bool;
    /// Whether any component is a delta distribution.
    fn has_delta(&self) -> bool;
    /// The model as a Lambertian reflector, when it is one (a wrapper calls it directly, so
    /// the common case inlines).
    fn as_diffuse(&self) -> Option<&Diffuse>;
}
